// layered_formulas_double.cpp - see layered_formulas.h. Compiled against the double-precision
// copy of the BSDF headers (CMake target openpbr_layered_formulas_double puts that copy first on
// the include path), in a namespace of its own; the compiled-in tables get this translation
// unit's own names (one name cannot have a float and a double type).
#define openpbr_lut_data layered_double_lut_data
#define openpbr_fuzz_ltc_data layered_double_fuzz_ltc_data
#define OPENPBR_CPP_VARIANT_NAMESPACE layered_double

#include "host/references/layered_formulas.h"

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/openpbr.h"

static_assert(sizeof(openpbr::layered_double::OpenPBR_DiffuseSpecular{}.diffuse.x) == sizeof(double),
              "the double-precision headers must come first on this translation unit's include path");

namespace openpbr::host {
namespace {

namespace model = ::openpbr::layered_double;

glm::dvec3 to_vector(const LayeredColor& color) { return glm::dvec3(color[0], color[1], color[2]); }
LayeredColor to_color(const glm::dvec3& vector) { return {vector.x, vector.y, vector.z}; }

}  // namespace

LayeredColor layered_f82_fresnel(const LayeredColor& f0, const LayeredColor& edge_tint, double cos_theta)
{
    const glm::dvec3 coefficient = model::openpbr_f82_coefficient(to_vector(f0), to_vector(edge_tint));
    return to_color(model::openpbr_fresnel_f82(to_vector(f0), coefficient, cos_theta));
}

LayeredColor layered_film_over_dielectric(double cos_theta, double n_outside, double n_film, double n_base,
                                          double thickness_um)
{
    return to_color(model::openpbr_thin_film_fresnel_dielectric(cos_theta, n_outside, n_film, n_base, thickness_um));
}

LayeredColor layered_film_over_conductor(double cos_theta, double n_outside, double n_film, const LayeredColor& f0,
                                         const LayeredColor& edge_tint, double thickness_um)
{
    // The conductor the model's film sees (openpbr_make_f82_fresnel).
    const model::OpenPBR_Fresnel fresnel =
        model::openpbr_make_f82_fresnel(to_vector(f0), to_vector(edge_tint), glm::dvec3(1.0));
    return to_color(model::openpbr_thin_film_fresnel_conductor(cos_theta, n_outside, n_film, fresnel.base_n, fresnel.base_k,
                                                               thickness_um));
}

double layered_modulated_ior(double eta, double specular_weight)
{
    return model::openpbr_modulated_ior(eta, specular_weight);
}

LayeredColor layered_dispersive_ior(double eta, double abbe_number, double dispersion_scale)
{
    return to_color(
        model::openpbr_dispersive_ior(eta, abbe_number, dispersion_scale, model::openpbr_default_rgb_wavelengths_nm()));
}

std::array<double, 2> layered_ggx_alpha(double roughness, double anisotropy)
{
    const glm::dvec2 alpha = model::openpbr_ggx_alpha(roughness, anisotropy);
    return {alpha.x, alpha.y};
}

LayeredColor layered_eon_value(const LayeredColor& rho, double sigma, const glm::dvec3& view, const glm::dvec3& light)
{
    const model::OpenPBR_DiffuseLobe lobe =
        model::openpbr_diffuse_lobe_init(glm::dvec3(1.0), to_vector(rho), sigma, 1.0, view);
    return to_color(model::openpbr_diffuse_lobe_eval(lobe, view, light));
}

}  // namespace openpbr::host
