// layered_formulas.h - the closed-form pieces of the layered reference
// (host/references/layered_reference.h) in double precision: the shipped BSDF's own formulas,
// compiled from the double-precision copy of slang/ (tools/make_double_headers.py) in
// layered_formulas_double.cpp, so the reference uses exactly the model's Fresnel factors,
// IOR modulation and diffuse BRDF, one mechanism, without a float rounding on the way:
//   - F82-tint (spec "Metal"): openpbr_fresnel_f82 with F0 = base_weight base_color and the
//     edge tint specular_color;
//   - the thin film's Airy reflectance (spec "Thin-film iridescence"; slang/math/openpbr_thin_film.h,
//     the full model) over a dielectric base, or over a conductor whose complex IOR comes from
//     (F0, edge tint) by Gulbrandsen 2014 as in the model;
//   - specular_weight's IOR modulation (spec "Base Substrate", eq. modulated_ior) and the
//     Cauchy dispersion of the IOR (spec "Translucent base");
//   - the energy-preserving Oren-Nayar BRDF (EON, spec "Glossy-diffuse"; Portsmouth, Kutz &
//     Hill 2025) and the GGX roughness mapping (spec "Microfacet model").
// Every colour is linear RGB per channel; cosines are on the incident side, in [0, 1].
#pragma once

#include <array>

#include <glm/vec3.hpp>

namespace openpbr::host {

using LayeredColor = std::array<double, 3>;

// specular_weight * F82-tint(cos) is the spec's metal Fresnel; this is F82-tint alone (the
// reference applies specular_weight once per hit of the metal, see layered_reference.h).
LayeredColor layered_f82_fresnel(const LayeredColor& f0, const LayeredColor& edge_tint, double cos_theta);

// Reflectance of a film (absolute IORs, thickness in micrometres) over a dielectric of absolute
// IOR n_base, seen from the medium of IOR n_outside at cos_theta on the outside.
LayeredColor layered_film_over_dielectric(double cos_theta, double n_outside, double n_film, double n_base,
                                          double thickness_um);

// The same over the conductor of F82 parameters (f0, edge_tint), through Gulbrandsen's n and k.
LayeredColor layered_film_over_conductor(double cos_theta, double n_outside, double n_film, const LayeredColor& f0,
                                         const LayeredColor& edge_tint, double thickness_um);

// eta' of the spec's eq. modulated_ior for a relative IOR eta and specular_weight xi.
double layered_modulated_ior(double eta, double specular_weight);

// Per-channel relative IOR with Cauchy dispersion (scale 0: none) at the model's default
// wavelengths (OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM).
LayeredColor layered_dispersive_ior(double eta, double abbe_number, double dispersion_scale);

// The GGX alphas (along the tangent, along the bitangent) of a roughness and an anisotropy.
std::array<double, 2> layered_ggx_alpha(double roughness, double anisotropy);

// EON f * cos(light) for albedo rho and roughness sigma; view and light unit vectors on the
// same side (z > 0); 0 otherwise.
LayeredColor layered_eon_value(const LayeredColor& rho, double sigma, const glm::dvec3& view, const glm::dvec3& light);

}  // namespace openpbr::host
