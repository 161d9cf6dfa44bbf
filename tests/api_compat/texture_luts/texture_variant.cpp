// The BSDF with texture tables (OPENPBR_USE_TEXTURE_LUTS=1) over the texture units' stand-in,
// built once per variant into its own namespace (OPENPBR_CPP_VARIANT_NAMESPACE =
// TEXTURE_VARIANT, set by CMake with the variant's defines, e.g. OPENPBR_LUT_TEXTURE_TRILINEAR_ETA=1).
#include <glm/glm.hpp>

#include "tests/api_compat/texture_luts/texture_sampler.h"

#define OPENPBR_USE_TEXTURE_LUTS 1
#include "slang/openpbr.h"

#include "tests/api_compat/texture_luts/texture_variant.h"

#include <cmath>

namespace texture_variants {

TableLookups TEXTURE_VARIANT::lookups(float mu, float alpha, float eta, float anisotropy, float cos_phi_squared,
                                      float fuzz_roughness)
{
    using namespace openpbr::TEXTURE_VARIANT;
    TableLookups result;
    result.ggx_albedo = openpbr_ggx_albedo(mu, alpha);
    result.reflection = openpbr_dielectric_reflection_albedo(mu, alpha, eta);
    result.transmission = openpbr_dielectric_transmission_albedo(mu, alpha, eta);
    result.interface_albedo = openpbr_dielectric_interface_albedo(mu, alpha, eta);
    result.anisotropy_ratio = openpbr_ggx_anisotropy_ratio(mu, std::sqrt(alpha), anisotropy, cos_phi_squared);
    const glm::vec3 fuzz = openpbr_fuzz_ltc_coefficients(mu, fuzz_roughness);
    result.fuzz_a = fuzz.x;
    result.fuzz_b = fuzz.y;
    result.fuzz_r = fuzz.z;
    return result;
}

glm::vec3 TEXTURE_VARIANT::eval(const MaterialParameters& material, glm::vec3 view, glm::vec3 light)
{
    using namespace openpbr::TEXTURE_VARIANT;
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    apply_parameters(inputs, material);
    const OpenPBR_DiffuseSpecular value = openpbr_eval(openpbr_prepare(inputs, view), light);
    return value.diffuse + value.specular;
}

}  // namespace texture_variants
