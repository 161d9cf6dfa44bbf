// accuracy_variants.h - the BSDF compiled once per knob setting of the accuracy study
// (docs/accuracy-vs-time.md), each in its own translation unit and namespace
// (OPENPBR_CPP_VARIANT_NAMESPACE of interop/openpbr_interop_cpp.h), behind one interface of
// plain functions, so one process measures every setting with the same workload.
// host/accuracy_variant_body.h is the single body every variant file includes.
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
};

// Table data of the variants that read tables through a pointer (sizes other than the shipped
// ones, 16-bit values); set before running them. Layout: slang/openpbr_lut.h for that size.
extern const float* accuracy_lut_values_16;  // 2D table at 16 x 16, other tables shipped
extern const float* accuracy_lut_values_64;  // 2D table at 64 x 64

// The 16-bit variant (OPENPBR_LUT_16BIT in buffer mode) reads openpbr_lut_data_half of its own
// translation unit; this sets it, e.g. to glm::packHalf1x16 of every shipped value.
void accuracy_set_half_table(const std::uint16_t* halves);

// Every variant: the shipped default first, then one per knob setting.
std::vector<BsdfVariant> bsdf_variants();

}  // namespace openpbr::host
