// accuracy_variants.h - the BSDF compiled once per knob setting of the accuracy study
// (docs/accuracy-vs-time.md), each in its own translation unit and namespace
// (OPENPBR_CPP_VARIANT_NAMESPACE of interop/openpbr_interop_cpp.h), behind one interface of
// plain functions, so one process measures every setting with the same workload.
// host/studies/accuracy_variant_body.h is the single body every variant file includes; the
// variant files and bsdf_variants() are generated from host/studies/accuracy_variants.cmake.
//
// Materials reach a variant packed (host::pack_materials, OPENPBR_PACKED_MATERIAL_FLOATS floats
// per material in the parameter table's order) and are unpacked by the variant's own copy of
// slang/openpbr_material_packing.h: the GPU kernels' one mechanism, so a variant sees every
// OpenPBR input, whatever its namespace or float type.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace openpbr::host {

// One query: a material (index into the packed materials), a view and a light direction
// (local = world frame, normal +z) and the sampler's random numbers.
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

// A thin film on a base, for the film's own functions (the film-estimate and film-model knobs):
// a dielectric base of IOR base_ior and a gold-coloured F82 metal, both under a film of
// film_ior and thickness_um, seen from a medium of outside_ior through a GGX lobe of
// `roughness` at view cosine view_cosine (e.g. a coat of IOR 1.6 over a film of 1.4).
struct AccuracyFilm
{
    float outside_ior = 1.0f;
    float film_ior = 1.4f;
    float thickness_um = 0.5f;
    float base_ior = 1.5f;
    float roughness = 0.3f;
    float view_cosine = 1.0f;
};

// The compensation table a setting reads (host uploads it to binding 0 on Vulkan).
enum class AccuracyTable
{
    shipped,    // slang/generated, float32
    size_16,    // 2D table at 16 x 16 (accuracy_lut_values_16)
    size_64,    // 2D table at 64 x 64 (accuracy_lut_values_64)
    reference,  // 2D table at 256 x 256 by quadrature in double (accuracy_lut_values_reference)
    half,       // shipped values as IEEE halves, two per 32-bit word (OPENPBR_LUT_16BIT)
};

struct BsdfVariant
{
    std::string name;     // the list's name, e.g. "vndf_bounded"
    std::string knob;     // e.g. "vndf sampling"
    std::string setting;  // e.g. "bounded (Eto & Tokuyoshi 2023)"
    // openpbr_prepare + openpbr_eval per query over packed materials: out[3 i + c] = (diffuse +
    // specular)[c].
    void (*eval)(const float* packed_materials, const std::vector<AccuracyQuery>&, float* out) = nullptr;
    // openpbr_prepare + openpbr_sample per query: out[3 i + c] = weight (0 for no sample).
    void (*sample)(const float* packed_materials, const std::vector<AccuracyQuery>&, float* out) = nullptr;
    // Directional albedo of the packed material at view cosine mu: the mean of `samples` sample
    // weights at a low-discrepancy point set shifted by `seed`, and the sample variance.
    AccuracyAlbedo (*albedo)(const float* packed_material, float mu, std::uint32_t samples, std::uint64_t seed) = nullptr;
    // openpbr_base_film_estimate of the film on both bases: out[0..2] the dielectric's change
    // F_film - F_plain, out[3..5] the metal's filmed factor.
    void (*film_estimate)(const AccuracyFilm&, float* out) = nullptr;
    // The film's reflectance on the dielectric base at cosine `cosine` (the model the knob
    // OPENPBR_THIN_FILM_MODEL picks), RGB into out[0..2].
    void (*film_reflectance)(const AccuracyFilm&, float cosine, float* out) = nullptr;
    // The same setting for the Slang conformance kernel (device times on lavapipe and
    // SwiftShader): its -D defines, e.g. {"OPENPBR_VNDF_METHOD=2"}, and the table it binds.
    std::vector<std::string> slang_defines;
    AccuracyTable table = AccuracyTable::shipped;
    // False where the setting has no kernel of its own (a C++-only storage mode, the double
    // build, the reference table).
    bool on_gpu = true;
    // The setting only stores the same values differently (float32 buffer against the
    // compiled-in array): its eval and sample outputs must equal the shipped build's bit for bit.
    bool bit_identical_to_shipped = false;
    // The reference its knob's errors are measured against (the same model with the knob's part
    // exact: the double build for precision, the 256 x 256 quadrature table for compensation).
    bool reference = false;
};

// Table data of the variants that read tables through a pointer (sizes other than the shipped
// ones); set before running them. Layout: slang/openpbr_lut.h for that size.
extern const float* accuracy_lut_values_16;         // 2D table at 16 x 16, other tables shipped
extern const float* accuracy_lut_values_64;         // 2D table at 64 x 64
extern const float* accuracy_lut_values_reference;  // 2D table at 256 x 256 (quadrature)

// The 16-bit variant (OPENPBR_LUT_16BIT in buffer mode) reads openpbr_lut_data_half of its own
// translation unit; this sets it, e.g. to glm::packHalf1x16 of every shipped value.
void accuracy_set_half_table(const std::uint16_t* halves);

// The float32 buffer-mode variant (OPENPBR_LUT_MODE_BUFFER) reads the table through this
// pointer, e.g. the shipped values, so it must match the compiled-in array bit for bit.
void accuracy_set_buffer_table(const float* values);

// Every variant: the shipped default first, then one per knob setting.
std::vector<BsdfVariant> bsdf_variants();

}  // namespace openpbr::host
