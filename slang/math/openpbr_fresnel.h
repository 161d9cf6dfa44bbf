// Fresnel factors. Every function takes cosines on the incident side, in [0, 1].
#ifndef OPENPBR_FRESNEL_H
#define OPENPBR_FRESNEL_H

#include "openpbr_math.h"
#include "openpbr_thin_film.h"
#include "../openpbr_features.h"

OPENPBR_NAMESPACE_BEGIN

// Unpolarized Fresnel reflectance of a smooth dielectric interface (Born & Wolf, ch. 1.5).
// eta = n_transmitted / n_incident; eta < 1 allows total internal reflection (returns 1).
OPENPBR_FUNC float openpbr_fresnel_dielectric(float cos_incident, float eta)
{
    const float cos_i = clamp(cos_incident, 0.0f, 1.0f);
    // cos_t^2 = 1 - (1 - cos_i^2) / eta^2 written as cos_i^2 + (1 - cos_i^2)(1 - 1/eta^2): no
    // cancellation near grazing for eta near 1 (no spurious total internal reflection), and
    // exactly cos_i^2 (F = 0) for eta = 1.
    const float cos2_i = cos_i * cos_i;
    const float cos2_t = cos2_i + (1.0f - cos2_i) * (1.0f - 1.0f / (eta * eta));
    if (cos2_t <= 0.0f)
    {
        return 1.0f;
    }
    const float cos_t = sqrt(cos2_t);
    const float r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const float r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5f * (r_s * r_s + r_p * r_p);
}

// Normal-incidence reflectance of a dielectric interface: ((eta - 1) / (eta + 1))^2.
OPENPBR_FUNC float openpbr_dielectric_f0(float eta) { return openpbr_square((eta - 1.0f) / (eta + 1.0f)); }

OPENPBR_FUNC float openpbr_schlick_weight(float cos_theta)
{
    const float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

// F82-tint metal Fresnel (OpenPBR 1.1 "Metal"; Hoffman 2019, "Fresnel Equations Considered
// Harmful"; Kutz et al. 2021): Schlick minus a term a * mu * (1 - mu)^6 whose coefficient
// makes the reflectance at mu_bar = 1/7 (about 82 degrees) equal tint * Schlick(mu_bar).
// The prepared coefficient depends only on the material, so it is computed once.
OPENPBR_FUNC vec3 openpbr_f82_coefficient(vec3 f0, vec3 tint)
{
    // mu_bar = 1/7: Schlick(mu_bar) = f0 + (1 - f0) (6/7)^5; mu_bar (1 - mu_bar)^6 = 6^6 / 7^7.
    const float one_minus_mu_bar_5 = 0.46266436f;            // (6/7)^5
    const float inverse_mu_bar_term = 823543.0f / 46656.0f;  // 7^7 / 6^6
    const vec3 schlick_at_mu_bar = f0 + (vec3(1.0f) - f0) * one_minus_mu_bar_5;
    return schlick_at_mu_bar * (vec3(1.0f) - tint) * inverse_mu_bar_term;
}

OPENPBR_FUNC vec3 openpbr_fresnel_f82(vec3 f0, vec3 f82_coefficient, float cos_theta)
{
    const float mu = clamp(cos_theta, 0.0f, 1.0f);
    const float m = 1.0f - mu;
    const float m5 = openpbr_schlick_weight(mu);
    const vec3 schlick = f0 + (vec3(1.0f) - f0) * m5;
    // Clamped to [0, 1]: a tint above 1 must not produce energy gain or a negative value.
    return openpbr_saturate(schlick - f82_coefficient * (mu * m5 * m));
}

// The Fresnel factor of one microfacet lobe, chosen at prepare time: a dielectric interface
// (base specular, coat) or the F82-tint metal. Evaluating through one struct lets a single
// microfacet lobe implementation serve the specular, metal and coat lobes.
#define OPENPBR_FRESNEL_DIELECTRIC 0u
#define OPENPBR_FRESNEL_F82 1u
#define OPENPBR_FRESNEL_NONE 2u  // F = 1 (times tint): thin-walled transmission, table generation

struct OpenPBR_Fresnel OPENPBR_DIFFERENTIABLE
{
    uint kind;             // OPENPBR_FRESNEL_DIELECTRIC, _F82 or _NONE
    float eta;             // dielectric: n_transmitted / n_incident, e.g. 1.5
    vec3 f0;               // F82: reflectance at normal incidence (base_weight * base_color)
    vec3 f82_coefficient;  // F82: from openpbr_f82_coefficient
    vec3 tint;             // multiplies the result, e.g. specular_color * specular_weight for metals
    // Thin-film iridescence (spec "Thin-film iridescence"): a linear blend of the Fresnel factor
    // with and without the film, by film_weight; 0 = no film (nothing else is read then).
    float film_weight;        // e.g. 0.5
    float film_thickness_um;  // e.g. 0.5 (500 nm)
    float film_ior;           // e.g. 1.4
    float outside_ior;        // absolute IOR above the film, e.g. 1 (air) or the coat's
    float base_ior;           // dielectric: absolute IOR below the film
    vec3 base_n;              // conductor: complex IOR below the film (Gulbrandsen 2014)
    vec3 base_k;
};

OPENPBR_FUNC OpenPBR_Fresnel openpbr_make_dielectric_fresnel(float eta, vec3 tint)
{
    OpenPBR_Fresnel fresnel;
    fresnel.kind = OPENPBR_FRESNEL_DIELECTRIC;
    fresnel.eta = eta;
    fresnel.f0 = vec3(openpbr_dielectric_f0(eta));
    fresnel.f82_coefficient = vec3(0.0f);
    fresnel.tint = tint;
    fresnel.film_weight = 0.0f;
    fresnel.film_thickness_um = 0.0f;
    fresnel.film_ior = 1.0f;
    fresnel.outside_ior = 1.0f;
    fresnel.base_ior = eta;
    fresnel.base_n = vec3(1.0f);
    fresnel.base_k = vec3(0.0f);
    return fresnel;
}

OPENPBR_FUNC OpenPBR_Fresnel openpbr_make_f82_fresnel(vec3 f0, vec3 edge_tint, vec3 tint)
{
    OpenPBR_Fresnel fresnel = openpbr_make_dielectric_fresnel(1.0f, tint);
    fresnel.kind = OPENPBR_FRESNEL_F82;
    fresnel.f0 = f0;
    fresnel.f82_coefficient = openpbr_f82_coefficient(f0, edge_tint);
    // The conductor's complex IOR for the film from (F0, edge tint), Gulbrandsen 2014; F82-tint
    // itself defines none, and the spec asks for "some reasonable approximation".
    const vec3 r = clamp(f0, vec3(0.0f), vec3(0.9999f));
    fresnel.base_n = openpbr_gulbrandsen_n(r, clamp(edge_tint, vec3(0.0f), vec3(1.0f)));
    fresnel.base_k = openpbr_gulbrandsen_k(r, fresnel.base_n);
    return fresnel;
}

OPENPBR_FUNC OpenPBR_Fresnel openpbr_make_constant_fresnel(vec3 tint)
{
    OpenPBR_Fresnel fresnel = openpbr_make_dielectric_fresnel(1.0f, tint);
    fresnel.kind = OPENPBR_FRESNEL_NONE;
    return fresnel;
}

// Puts a film of the given weight, thickness (micrometers) and IOR on a Fresnel factor, with
// the medium above the film of absolute IOR outside_ior (the base IOR follows from eta).
OPENPBR_FUNC OpenPBR_Fresnel openpbr_add_thin_film(OPENPBR_IN(OpenPBR_Fresnel) fresnel, float weight, float thickness_um,
                                                   float film_ior, float outside_ior)
{
    OpenPBR_Fresnel filmed = fresnel;
    filmed.film_weight = fresnel.kind == OPENPBR_FRESNEL_NONE ? 0.0f : weight;
    filmed.film_thickness_um = thickness_um;
    filmed.film_ior = film_ior;
    filmed.outside_ior = outside_ior;
    filmed.base_ior = fresnel.eta * outside_ior;
    return filmed;
}

// The Fresnel factor without its film and tint (1 for OPENPBR_FRESNEL_NONE).
OPENPBR_FUNC vec3 openpbr_fresnel_plain(OPENPBR_IN(OpenPBR_Fresnel) fresnel, float cos_theta)
{
    if (fresnel.kind == OPENPBR_FRESNEL_NONE)
    {
        return vec3(1.0f);
    }
    return fresnel.kind == OPENPBR_FRESNEL_F82 ? openpbr_fresnel_f82(fresnel.f0, fresnel.f82_coefficient, cos_theta)
                                               : vec3(openpbr_fresnel_dielectric(cos_theta, fresnel.eta));
}

// The factor of a Fresnel struct known to carry no film (film_weight 0), without the film code.
OPENPBR_FUNC vec3 openpbr_fresnel_evaluate_without_film(OPENPBR_IN(OpenPBR_Fresnel) fresnel, float cos_theta)
{
    return fresnel.kind == OPENPBR_FRESNEL_NONE ? fresnel.tint : fresnel.tint * openpbr_fresnel_plain(fresnel, cos_theta);
}

OPENPBR_FUNC vec3 openpbr_fresnel_evaluate(OPENPBR_IN(OpenPBR_Fresnel) fresnel, float cos_theta)
{
    if (fresnel.kind == OPENPBR_FRESNEL_NONE)
    {
        return fresnel.tint;
    }
    const vec3 plain = openpbr_fresnel_plain(fresnel, cos_theta);
    // OPENPBR_FEATURE_THIN_FILM (slang/openpbr_features.h): with the toggle a constant 0 the
    // film code below is compiled out of every lobe that reads a Fresnel factor.
    if (!(OPENPBR_FEATURE_THIN_FILM && OPENPBR_WEIGHT_ACTIVE(fresnel.film_weight)))
    {
        return fresnel.tint * plain;
    }
    // One call for both bases: the film code is compiled once per call site, not twice.
    const vec3 film = openpbr_thin_film_fresnel_model(cos_theta, fresnel.outside_ior, fresnel.film_ior,
                                                      fresnel.kind == OPENPBR_FRESNEL_F82, fresnel.base_ior, fresnel.base_n,
                                                      fresnel.base_k, fresnel.film_thickness_um);
    return fresnel.tint * mix(plain, film, fresnel.film_weight);
}

// The base layer's dielectric and metal Fresnel factors at one microfacet angle (both built by
// prepare, the first of kind OPENPBR_FRESNEL_DIELECTRIC or _NONE, the second _F82 or _NONE,
// under the same film): equal to two openpbr_fresnel_evaluate calls, with the film's spectral
// harmonics computed once for both (openpbr_thin_film_model_bases). An inactive factor
// is 0.
struct OpenPBR_FresnelPair OPENPBR_DIFFERENTIABLE
{
    vec3 first;
    vec3 second;
};

// optical_path_spread_um: the film's path spread over the microfacets averaged at once
// (OpenPBR_ThinFilmInputs), 0 for one microfacet (openpbr_fresnel_evaluate_base_pair).
OPENPBR_FUNC OpenPBR_FresnelPair openpbr_fresnel_evaluate_base_pair_spread(OPENPBR_IN(OpenPBR_Fresnel) dielectric,
                                                                           bool dielectric_active,
                                                                           OPENPBR_IN(OpenPBR_Fresnel) metal,
                                                                           bool metal_active, float cos_theta,
                                                                           float optical_path_spread_um)
{
    OpenPBR_FresnelPair pair;
    pair.first = vec3(0.0f);
    pair.second = vec3(0.0f);
    if (dielectric_active)
    {
        pair.first = openpbr_fresnel_plain(dielectric, cos_theta);
    }
    if (metal_active)
    {
        pair.second = openpbr_fresnel_plain(metal, cos_theta);
    }
    const bool dielectric_filmed = dielectric_active && OPENPBR_WEIGHT_ACTIVE(dielectric.film_weight);
    const bool metal_filmed = metal_active && OPENPBR_WEIGHT_ACTIVE(metal.film_weight);
    // OPENPBR_FEATURE_THIN_FILM: compiled out with the toggle a constant 0, as in
    // openpbr_fresnel_evaluate. Both factors carry the same film (openpbr_add_thin_film).
    if (OPENPBR_FEATURE_THIN_FILM && (dielectric_filmed || metal_filmed))
    {
        OpenPBR_ThinFilmInputs film_inputs =
            openpbr_thin_film_inputs(cos_theta, dielectric_filmed ? dielectric.outside_ior : metal.outside_ior,
                                     dielectric_filmed ? dielectric.film_ior : metal.film_ior,
                                     dielectric_filmed ? dielectric.film_thickness_um : metal.film_thickness_um);
        film_inputs.optical_path_spread_um = optical_path_spread_um;
        const OpenPBR_ThinFilmBasePair film = openpbr_thin_film_model_bases(
            film_inputs, dielectric_filmed, dielectric.base_ior, metal_filmed, metal.base_n, metal.base_k);
        if (dielectric_filmed)
        {
            pair.first = mix(pair.first, film.dielectric, dielectric.film_weight);
        }
        if (metal_filmed)
        {
            pair.second = mix(pair.second, film.conductor, metal.film_weight);
        }
    }
    if (dielectric_active)
    {
        pair.first = pair.first * dielectric.tint;
    }
    if (metal_active)
    {
        pair.second = pair.second * metal.tint;
    }
    return pair;
}

OPENPBR_FUNC OpenPBR_FresnelPair openpbr_fresnel_evaluate_base_pair(OPENPBR_IN(OpenPBR_Fresnel) dielectric,
                                                                    bool dielectric_active,
                                                                    OPENPBR_IN(OpenPBR_Fresnel) metal, bool metal_active,
                                                                    float cos_theta)
{
    return openpbr_fresnel_evaluate_base_pair_spread(dielectric, dielectric_active, metal, metal_active, cos_theta, 0.0f);
}

OPENPBR_NAMESPACE_END

#endif
