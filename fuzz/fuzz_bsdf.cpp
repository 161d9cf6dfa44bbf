// libFuzzer harness over the raw bytes of a BSDF query (fuzz/fuzz_input_layout.h): the packed
// material floats, the view and light directions, the random numbers and the wavelengths. Every
// input runs openpbr_prepare, openpbr_eval, openpbr_pdf, openpbr_sample (and eval and pdf at the
// sampled direction) and openpbr_prepare_volume, and aborts on
//   - any non-finite output,
//   - a negative eval, pdf, sample weight, sample pdf, emission, extinction or albedo,
//   - a volume albedo above 1 or anisotropy outside [-1, 1],
//   - a sample without a lobe type but with a pdf or weight, or a sample direction not of unit length,
//   - a non-delta sample weight above 1e4 with view and light both more than 1e-4 off the
//     surface (a weight that large means a pdf far below the value: energy gain),
// printing the input as floats first. Build: fuzz/CMakeLists.txt (clang, -fsanitize=fuzzer);
// run: scripts/ci_fuzz.sh. The seed corpus in fuzz/corpus/ comes from the stability corpus
// (`openpbr stability --write-fuzz-corpus fuzz/corpus`).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "slang/openpbr.h"

namespace {
// The current input as floats (92 = OPENPBR_FUZZ_INPUT_FLOATS, checked below).
float g_input[92];
}  // namespace

// The layout header includes the packing header: with the read macro defined first, it defines
// openpbr_unpack_material over g_input.
#define OPENPBR_MATERIAL_READ(index) g_input[(index)]
#include "fuzz/fuzz_input_layout.h"
#include "host/scene/material_packing.h"  // header-only packing, the inverse of the read above

static_assert(sizeof(g_input) / sizeof(float) == OPENPBR_FUZZ_INPUT_FLOATS, "input layout changed");
static_assert(OPENPBR_FUZZ_MATERIAL_OFFSET == 0, "the material is read from the start of the input");

namespace {

using glm::vec3;

// The default input: default material, view and light along +z, u = 0.5, RGB wavelengths.
void make_default_input(float* input)
{
    const openpbr::OpenPBR_ResolvedInputs material = openpbr::openpbr_make_default_resolved_inputs();
    openpbr::host::pack_material(material, input + OPENPBR_FUZZ_MATERIAL_OFFSET);
    const float rest[] = {0, 0, 1, 0, 0, 1, 0.5f, 0.5f, 0.5f, 612.0f, 549.0f, 465.0f};
    std::memcpy(input + OPENPBR_FUZZ_VIEW_OFFSET, rest, sizeof rest);
}

[[noreturn]] void fail(const char* what, float value)
{
    std::fprintf(stderr, "fuzz_bsdf: %s (value %g)\ninput floats:", what, double(value));
    for (int i = 0; i < OPENPBR_FUZZ_INPUT_FLOATS; ++i)
    {
        std::fprintf(stderr, "%s%.9g", i % 8 == 0 ? "\n  " : " ", double(g_input[i]));
    }
    std::fprintf(stderr, "\n");
    std::abort();
}

void check_finite(float value, const char* what)
{
    if (!std::isfinite(value))
    {
        fail(what, value);
    }
}

void check_non_negative(float value, const char* what)
{
    check_finite(value, what);
    if (value < 0.0f)
    {
        fail(what, value);
    }
}

void check_non_negative(const vec3& value, const char* what)
{
    check_non_negative(value.x, what);
    check_non_negative(value.y, what);
    check_non_negative(value.z, what);
}

// u in [0, 1): values outside map into it (fractional part of |u|), non-finite values to 0.5.
float unit_interval(float u)
{
    if (!std::isfinite(u))
    {
        return 0.5f;
    }
    if (u >= 0.0f && u < 1.0f)
    {
        return u;
    }
    const float fraction = std::fabs(u) - std::floor(std::fabs(u));
    return fraction < 1.0f ? fraction : 0.0f;
}

// eval and pdf take unit directions: normalize in double; a vector without a direction
// (zero or non-finite) becomes +z.
vec3 unit_direction(const vec3& v)
{
    const double length = std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
    if (!(length > 0.0) || !std::isfinite(length))
    {
        return vec3(0.0f, 0.0f, 1.0f);
    }
    return vec3(float(v.x / length), float(v.y / length), float(v.z / length));
}

void check_eval_pdf(const openpbr::OpenPBR_PreparedBsdf& bsdf, const vec3& light, bool at_sample)
{
    const openpbr::OpenPBR_DiffuseSpecular value = openpbr::openpbr_eval(bsdf, light);
    check_non_negative(value.diffuse, at_sample ? "eval.diffuse at the sampled direction" : "eval.diffuse at the light");
    check_non_negative(value.specular, at_sample ? "eval.specular at the sampled direction" : "eval.specular at the light");
    check_non_negative(openpbr::openpbr_pdf(bsdf, light), at_sample ? "pdf at the sampled direction" : "pdf at the light");
}

void run_input()
{
    const openpbr::OpenPBR_ResolvedInputs inputs = openpbr::openpbr_unpack_material(0u);
    const vec3 view(g_input[OPENPBR_FUZZ_VIEW_OFFSET], g_input[OPENPBR_FUZZ_VIEW_OFFSET + 1],
                    g_input[OPENPBR_FUZZ_VIEW_OFFSET + 2]);
    const vec3 light = unit_direction(vec3(g_input[OPENPBR_FUZZ_LIGHT_OFFSET], g_input[OPENPBR_FUZZ_LIGHT_OFFSET + 1],
                                           g_input[OPENPBR_FUZZ_LIGHT_OFFSET + 2]));
    const vec3 u(unit_interval(g_input[OPENPBR_FUZZ_U_OFFSET]), unit_interval(g_input[OPENPBR_FUZZ_U_OFFSET + 1]),
                 unit_interval(g_input[OPENPBR_FUZZ_U_OFFSET + 2]));
    const vec3 wavelengths(g_input[OPENPBR_FUZZ_WAVELENGTH_OFFSET], g_input[OPENPBR_FUZZ_WAVELENGTH_OFFSET + 1],
                           g_input[OPENPBR_FUZZ_WAVELENGTH_OFFSET + 2]);

    const openpbr::OpenPBR_PreparedBsdf bsdf = openpbr::openpbr_prepare(inputs, view, wavelengths);
    check_non_negative(bsdf.emission, "emission");
    check_eval_pdf(bsdf, light, false);

    const openpbr::OpenPBR_BsdfSample sample = openpbr::openpbr_sample(bsdf, u);
    check_non_negative(sample.pdf, "sample pdf");
    check_non_negative(sample.weight.diffuse, "sample weight (diffuse)");
    check_non_negative(sample.weight.specular, "sample weight (specular)");
    check_finite(sample.direction.x, "sample direction");
    check_finite(sample.direction.y, "sample direction");
    check_finite(sample.direction.z, "sample direction");
    if (sample.lobe_type == OPENPBR_LOBE_TYPE_NONE)
    {
        if (sample.pdf != 0.0f || openpbr::openpbr_max3(sample.weight.diffuse + sample.weight.specular) != 0.0f)
        {
            fail("sample without a lobe type has a pdf or weight", sample.pdf);
        }
    }
    else
    {
        const float length = glm::length(sample.direction);
        if (!(std::fabs(length - 1.0f) < 1e-3f))
        {
            fail("sample direction is not of unit length", length);
        }
        check_eval_pdf(bsdf, sample.direction, true);
        const bool delta = (sample.lobe_type & OPENPBR_LOBE_TYPE_SPECULAR) != 0u;
        // Cosines in the prepared (clamped, view-side-up) shading frame.
        const float view_cos = bsdf.view.z;
        const float light_cos = std::fabs(glm::dot(sample.direction, bsdf.basis.normal));
        const float weight = openpbr::openpbr_max3(sample.weight.diffuse + sample.weight.specular);
        if (!delta && view_cos > 1e-4f && light_cos > 1e-4f && weight > 1e4f)
        {
            fail("non-delta sample weight above 1e4", weight);
        }
    }

    const openpbr::OpenPBR_HomogeneousVolume volume = openpbr::openpbr_prepare_volume(inputs);
    check_non_negative(volume.extinction, "volume extinction");
    check_non_negative(volume.albedo, "volume albedo");
    check_finite(volume.anisotropy, "volume anisotropy");
    if (openpbr::openpbr_max3(volume.albedo) > 1.0f)
    {
        fail("volume albedo above 1", openpbr::openpbr_max3(volume.albedo));
    }
    if (std::fabs(volume.anisotropy) > 1.0f)
    {
        fail("volume anisotropy outside [-1, 1]", volume.anisotropy);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    make_default_input(g_input);
    std::memcpy(g_input, data, size < sizeof g_input ? size : sizeof g_input);
    run_input();
    return 0;
}
