// The interface of each texture-table build (texture_variant.cpp), in plain types: every build
// has its own OpenPBR_* types (its own namespace), so materials cross as parameter lists.
#ifndef OPENPBR_TEXTURE_VARIANT_H
#define OPENPBR_TEXTURE_VARIANT_H

#include <glm/glm.hpp>

namespace texture_variants {

// Every table look-up at one point.
struct TableLookups
{
    float ggx_albedo;
    float reflection;
    float transmission;
    float interface_albedo;
    float anisotropy_ratio;
    float fuzz_a;
    float fuzz_b;
    float fuzz_r;
};

// A material as the tests vary it.
struct MaterialParameters
{
    glm::vec3 base_color;
    float metalness;
    float roughness;
    float anisotropy;
    float ior;
    float transmission;
    float coat;
    float coat_roughness;
    float fuzz;
    float fuzz_roughness;
};

// Sets the fields MaterialParameters covers on any build's OpenPBR_ResolvedInputs.
template <class Inputs> void apply_parameters(Inputs& inputs, const MaterialParameters& parameters)
{
    inputs.base_color = parameters.base_color;
    inputs.base_metalness = parameters.metalness;
    inputs.specular_roughness = parameters.roughness;
    inputs.specular_roughness_anisotropy = parameters.anisotropy;
    inputs.specular_ior = parameters.ior;
    inputs.transmission_weight = parameters.transmission;
    inputs.coat_weight = parameters.coat;
    inputs.coat_roughness = parameters.coat_roughness;
    inputs.fuzz_weight = parameters.fuzz;
    inputs.fuzz_roughness = parameters.fuzz_roughness;
}

// One namespace per build: texture_exact (eta interpolated by the library from slice fetches)
// and texture_trilinear (OPENPBR_LUT_TEXTURE_TRILINEAR_ETA=1).
#define OPENPBR_TEXTURE_VARIANT_INTERFACE(variant)                                                                         \
    namespace variant {                                                                                                    \
    TableLookups lookups(float mu, float alpha, float eta, float anisotropy, float cos_phi_squared, float fuzz_roughness); \
    glm::vec3 eval(const MaterialParameters& material, glm::vec3 view, glm::vec3 light);                                   \
    }
OPENPBR_TEXTURE_VARIANT_INTERFACE(texture_exact)
OPENPBR_TEXTURE_VARIANT_INTERFACE(texture_trilinear)

}  // namespace texture_variants

#endif
