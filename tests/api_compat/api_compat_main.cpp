// The api_compat program (api_compat_program.h, established-API signatures only) as C++: built
// with -Wall -Wextra -Werror and run. For every case it checks that the established form gives
// bit for bit what the project form gives (both are the same functions underneath:
// slang/openpbr_established_api.h forwards to openpbr_bsdf.h), and exits non-zero otherwise.
// Usage: api_compat_cpp (no arguments); prints the number of cases and compared floats.
#include <glm/glm.hpp>

#include "slang/openpbr.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {
std::array<float, 4096> results{};
}
#define API_COMPAT_WRITE(index, value) (results[(index)] = (value))
#include "tests/api_compat/api_compat_program.h"

namespace {

using namespace openpbr;

// A small deterministic generator (PCG32, O'Neill 2014), so every run checks the same cases.
struct Random
{
    std::uint64_t state = 0x853c49e6748fea9bULL;
    float next()
    {
        const std::uint64_t old = state;
        state = old * 6364136223846793005ULL + 1442695040888963407ULL;
        const std::uint32_t shifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const std::uint32_t rotation = static_cast<std::uint32_t>(old >> 59u);
        const std::uint32_t value = (shifted >> rotation) | (shifted << ((32u - rotation) & 31u));
        return static_cast<float>(value >> 8) * (1.0f / 16777216.0f);
    }
    // A range end (0 or 1) one time in five each, else uniform: the ends are where formulas
    // degenerate.
    float unit_with_ends()
    {
        const float pick = next();
        return pick < 0.2f ? 0.0f : (pick < 0.4f ? 1.0f : next());
    }
    glm::vec3 color() { return glm::vec3(next(), next(), next()); }
    glm::vec3 direction()
    {
        const float z = 1.0f - 2.0f * next();
        const float radius = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 6.28318530718f * next();
        return glm::vec3(radius * std::cos(phi), radius * std::sin(phi), z);
    }
};

OpenPBR_ResolvedInputs random_material(Random& random)
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.base_color = random.color();
    inputs.base_metalness = random.unit_with_ends();
    inputs.base_diffuse_roughness = random.unit_with_ends();
    inputs.specular_roughness = random.unit_with_ends();
    inputs.specular_roughness_anisotropy = random.next() < 0.7f ? 0.0f : random.unit_with_ends();
    inputs.specular_ior = 1.0f + 1.5f * random.next();
    inputs.transmission_weight = random.unit_with_ends();
    inputs.transmission_color = random.color();
    inputs.transmission_depth = random.next() < 0.5f ? 0.0f : random.next();
    inputs.transmission_scatter = random.color();
    inputs.subsurface_weight = random.unit_with_ends();
    inputs.coat_weight = random.unit_with_ends();
    inputs.coat_color = random.color();
    inputs.coat_roughness = random.unit_with_ends();
    inputs.fuzz_weight = random.unit_with_ends();
    inputs.thin_film_weight = random.next() < 0.8f ? 0.0f : random.next();
    inputs.emission_luminance = random.next() < 0.7f ? 0.0f : 10.0f * random.next();
    inputs.geometry_opacity = random.unit_with_ends();
    inputs.geometry_thin_walled = random.next() < 0.2f;
    inputs.transmission_dispersion_scale = random.next() < 0.8f ? 0.0f : random.next();
    return inputs;
}

std::uint32_t bits(float value)
{
    std::uint32_t word = 0;
    std::memcpy(&word, &value, sizeof(word));
    return word;
}

}  // namespace

int main()
{
    Random random;
    int cases = 0;
    int compared = 0;
    int mismatches = 0;
    const auto expect_same = [&](const char* what, int index, float project_value) {
        ++compared;
        if (bits(results[index]) != bits(project_value))
        {
            if (++mismatches <= 10)
            {
                std::printf("case %d: %s (result %d): established %.9g, project %.9g\n", cases, what, index,
                            static_cast<double>(results[index]), static_cast<double>(project_value));
            }
        }
    };
    const auto expect_same3 = [&](const char* what, int index, const glm::vec3& project_value) {
        expect_same(what, index, project_value.x);
        expect_same(what, index + 1, project_value.y);
        expect_same(what, index + 2, project_value.z);
    };
    for (int material_index = 0; material_index < 400; ++material_index)
    {
        const OpenPBR_ResolvedInputs inputs = random_material(random);
        for (int query = 0; query < 8; ++query, ++cases)
        {
            const glm::vec3 view = random.direction();
            const glm::vec3 light = random.direction();
            // White one time in four (the project form's unweighted selection), else a color.
            const glm::vec3 throughput = query % 4 == 0 ? glm::vec3(1.0f) : random.color();
            const glm::vec3 u(random.next(), random.next(), random.next());
            const glm::vec2 medium_u(random.next(), random.next());
            // In air (the seed's OpenPBR_VacuumIor) and in water or glass around the object.
            const float exterior_ior = query % 3 == 0 ? 1.0f : (query % 3 == 1 ? 1.33f : 1.5f);
            api_compat_shade(inputs, view, light, throughput, exterior_ior, u, medium_u, 0u);

            // The same step through the project form.
            const OpenPBR_PreparedBsdf prepared =
                openpbr_prepare_for_path(inputs, view, OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM, exterior_ior, throughput);
            if (throughput == glm::vec3(1.0f))
            {
                // White throughput: the plain project-form prepare gives the same lobes.
                const OpenPBR_PreparedBsdf plain =
                    openpbr_prepare(inputs, view, OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM, exterior_ior);
                expect_same("plain prepare pdf", 9, openpbr_pdf(plain, light));
            }
            const OpenPBR_DiffuseSpecular value = openpbr_eval(prepared, light);
            expect_same3("eval diffuse", 0, value.diffuse);
            expect_same3("eval specular", 3, value.specular);
            expect_same3("eval sum", 6, value.diffuse + value.specular);
            expect_same("pdf", 9, openpbr_pdf(prepared, light));
            const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(prepared, u);
            expect_same3("sample direction", 10, bsdf_sample.direction);
            expect_same3("sample weight diffuse", 13, bsdf_sample.weight.diffuse);
            expect_same3("sample weight specular", 16, bsdf_sample.weight.specular);
            expect_same("sample pdf", 19, bsdf_sample.pdf);
            expect_same("sample lobe type", 20, static_cast<float>(bsdf_sample.lobe_type));
            expect_same3("emission", 21, prepared.emission);
            expect_same3("staged eval", 24, value.diffuse + value.specular);
            expect_same("staged pdf", 27, openpbr_pdf(prepared, light));
            expect_same3("staged emission", 28, prepared.emission);
            expect_same3("staged volume", 31, openpbr_prepare_volume(inputs).extinction);
            expect_same3("transmittance", 40, openpbr_volume_transmittance(prepared.volume, 0.5f));
            const OpenPBR_VolumeDistanceSample flight =
                openpbr_volume_sample_distance(prepared.volume, throughput, OPENPBR_FLOAT_MAX, medium_u.x, medium_u.y);
            expect_same("event distance", 46, std::min(flight.distance, 1.0e6f));
            expect_same3("isotropic phase sample", 47, openpbr_isotropic_phase_sample(medium_u));
            expect_same3("anisotropic phase sample", 50,
                         openpbr_henyey_greenstein_sample(prepared.volume.anisotropy, -view, medium_u));
            expect_same("isotropic phase value", 53, openpbr_isotropic_phase_eval());
            expect_same("OpenPBR_VacuumIor", 70, 1.0f);
            expect_same("OpenPBR_BaseRgbWavelengths_nm", 71, OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM.x);
            for (int index = 0; index < API_COMPAT_RESULT_COUNT; ++index)
            {
                if (!std::isfinite(results[index]))
                {
                    ++mismatches;
                    std::printf("case %d: result %d is not finite\n", cases, index);
                }
            }
        }
    }
    std::printf("api_compat (C++): %d cases, %d floats compared bit for bit, %d mismatches\n", cases, compared, mismatches);
    return mismatches == 0 && compared > 0 ? 0 : 1;
}
