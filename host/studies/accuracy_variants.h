// accuracy_variants.h - the BSDF compiled once per knob setting of the accuracy study
// (docs/accuracy-vs-time.md), each in its own translation unit and namespace
// (OPENPBR_CPP_VARIANT_NAMESPACE of interop/openpbr_interop_cpp.h), behind one interface of
// plain functions, so one process measures every setting with the same workload.
// host/studies/accuracy_variant_body.h is the single body every variant file includes; the
// variant files and bsdf_variants() are generated from host/studies/accuracy_variants.cmake.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace openpbr::host {

// A material of the study: the handful of OpenPBR inputs the knobs touch; the rest keep the
// spec defaults (openpbr_make_default_resolved_inputs).
struct AccuracyMaterial
{
    float base_color[3] = {0.8f, 0.8f, 0.8f};
    float base_metalness = 0.0f;
    float specular_roughness = 0.3f;
    float specular_roughness_anisotropy = 0.0f;
    float specular_ior = 1.5f;
    float transmission_weight = 0.0f;
    float coat_weight = 0.0f;
    float coat_roughness = 0.0f;
    float thin_film_weight = 0.0f;
    float thin_film_thickness = 0.5f;
};

// The fields of AccuracyMaterial, for code that copies them into OpenPBR_ResolvedInputs (the
// variants, the Vulkan workload): SCALAR(name) per float field, COLOR(name) per RGB field.
#define OPENPBR_ACCURACY_MATERIAL_FIELDS(SCALAR, COLOR) \
    COLOR(base_color)                                   \
    SCALAR(base_metalness)                              \
    SCALAR(specular_roughness)                          \
    SCALAR(specular_roughness_anisotropy)               \
    SCALAR(specular_ior)                                \
    SCALAR(transmission_weight)                         \
    SCALAR(coat_weight)                                 \
    SCALAR(coat_roughness)                              \
    SCALAR(thin_film_weight)                            \
    SCALAR(thin_film_thickness)

// Copies the study's fields of `material` into `inputs` (an OpenPBR_ResolvedInputs of any
// variant namespace); the other fields keep their values.
template <typename Inputs> void accuracy_apply_material(const AccuracyMaterial& material, Inputs& inputs)
{
#define OPENPBR_ACCURACY_COPY_SCALAR(name) inputs.name = material.name;
#define OPENPBR_ACCURACY_COPY_COLOR(name) inputs.name = {material.name[0], material.name[1], material.name[2]};
    OPENPBR_ACCURACY_MATERIAL_FIELDS(OPENPBR_ACCURACY_COPY_SCALAR, OPENPBR_ACCURACY_COPY_COLOR)
#undef OPENPBR_ACCURACY_COPY_SCALAR
#undef OPENPBR_ACCURACY_COPY_COLOR
}

// One query: a material (index), a view and a light direction (local = world frame, normal
// +z) and the sampler's random numbers.
struct AccuracyQuery
{
    std::uint32_t material = 0;
    float view[3] = {0.0f, 0.0f, 1.0f};
    float light[3] = {0.0f, 0.0f, 1.0f};
    float u[3] = {0.5f, 0.5f, 0.5f};
};

// Results of an albedo estimate: mean of the sample weights (RGB) and the variance of one
// weight's luminance.
struct AccuracyAlbedo
{
    double mean[3] = {0.0, 0.0, 0.0};
    double variance = 0.0;
};

// The compensation table a setting reads (host uploads it to binding 0 on Vulkan).
enum class AccuracyTable
{
    shipped,  // slang/generated, float32
    size_16,  // 2D table at 16 x 16 (accuracy_lut_values_16)
    size_64,  // 2D table at 64 x 64 (accuracy_lut_values_64)
    half,     // shipped values as IEEE halves, two per 32-bit word (OPENPBR_LUT_16BIT)
};

struct BsdfVariant
{
    std::string knob;     // e.g. "vndf sampling"
    std::string setting;  // e.g. "bounded (Eto & Tokuyoshi 2023)"
    // openpbr_prepare + openpbr_eval per query: out[3 i + c] = (diffuse + specular)[c].
    void (*eval)(const std::vector<AccuracyMaterial>&, const std::vector<AccuracyQuery>&, float* out) = nullptr;
    // openpbr_prepare + openpbr_sample per query: out[3 i + c] = weight (0 for no sample).
    void (*sample)(const std::vector<AccuracyMaterial>&, const std::vector<AccuracyQuery>&, float* out) = nullptr;
    // Directional albedo at view cosine mu: the mean of `samples` sample weights at a
    // low-discrepancy point set shifted by `seed`, and the sample variance of the weights.
    AccuracyAlbedo (*albedo)(const AccuracyMaterial&, float mu, std::uint32_t samples, std::uint64_t seed) = nullptr;
    // The same setting for the Slang conformance kernel (compile time, SPIR-V size, lavapipe
    // queries/s): its -D defines, e.g. {"OPENPBR_VNDF_METHOD=2"}, and the table it binds.
    std::vector<std::string> slang_defines;
    AccuracyTable table = AccuracyTable::shipped;
    // False where the Vulkan kernel of this setting is another row's (e.g. float32 buffer
    // tables: the shipped Vulkan kernel already reads a buffer).
    bool on_vulkan = true;
    // The setting only stores the same values differently (float32 buffer against the
    // compiled-in array): its eval and sample outputs must equal the shipped build's bit for bit.
    bool bit_identical_to_shipped = false;
    // The double-precision build (host/studies/accuracy_double_variant.cpp): every setting's per-query
    // error is also measured against it.
    bool double_reference = false;
};

// Table data of the variants that read tables through a pointer (sizes other than the shipped
// ones, 16-bit values); set before running them. Layout: slang/openpbr_lut.h for that size.
extern const float* accuracy_lut_values_16;  // 2D table at 16 x 16, other tables shipped
extern const float* accuracy_lut_values_64;  // 2D table at 64 x 64

// The 16-bit variant (OPENPBR_LUT_16BIT in buffer mode) reads openpbr_lut_data_half of its own
// translation unit; this sets it, e.g. to glm::packHalf1x16 of every shipped value.
void accuracy_set_half_table(const std::uint16_t* halves);

// The float32 buffer-mode variant (OPENPBR_LUT_MODE_BUFFER) reads the table through this
// pointer, e.g. the shipped values, so it must match the compiled-in array bit for bit.
void accuracy_set_buffer_table(const float* values);

// Every variant: the shipped default first, then one per knob setting.
std::vector<BsdfVariant> bsdf_variants();

}  // namespace openpbr::host
