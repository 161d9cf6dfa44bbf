// Energy-preserving Oren-Nayar diffuse (EON): Portsmouth, Kutz, Hill 2025, "EON: A Practical
// Energy-Preserving Rough Diffuse BRDF" (JCGT 14(1)); OpenPBR 1.1 "Glossy-diffuse".
//   f = (rho/pi) (A + B s/t) + (rho_ms/pi) (1 - E(mu_i)) (1 - E(mu_o)) / (1 - E_avg)
//   A = 1 / (1 + c1 sigma), B = sigma A, c1 = 1/2 - 2/(3 pi),
//   s = wi.wo - mu_i mu_o, t = max(mu_i, mu_o) if s > 0 else 1 (the Fujii "FON" form),
//   rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)), E_avg = A (1 + c2 sigma), c2 = 2/3 - 28/(15 pi)
// (the spec prints rho_ms with an extra 1/pi; the paper's form above passes the furnace test,
// see docs/spec-notes.md 4.1). Sigma = 0 reduces exactly to Lambert. Reciprocal.
// Sampling: cosine-weighted (unbiased; the weight pi f / rho is bounded by about 1.3).
// The same lobe mirrored below the surface is the thin-walled diffuse transmission.
// Two uses, each with its prepare: the base's diffuse reflection (openpbr_diffuse_lobe_prepare)
// and the thin-walled subsurface sheet (openpbr_diffuse_transmission_lobe_prepare).
#ifndef OPENPBR_DIFFUSE_LOBE_H
#define OPENPBR_DIFFUSE_LOBE_H

#include "openpbr_lobe_common.h"
#include "../math/openpbr_warps.h"
#include "../openpbr_resolved_inputs.h"

#define OPENPBR_EON_C1 0.28779763f  // 1/2 - 2/(3 pi)
#define OPENPBR_EON_C2 0.07252938f  // 2/3 - 28/(15 pi)

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_DiffuseLobe OPENPBR_DIFFERENTIABLE
{
    vec3 single_scatter_a;  // weight * rho * A / pi
    vec3 single_scatter_b;  // weight * rho * B / pi
    vec3 multiple_scatter;  // weight * rho_ms (1 - E(mu_o)) / (pi (1 - E_avg)); 0 for sigma = 0
    vec3 albedo;            // weight * directional albedo at the view (for lobe selection)
    float sigma;
    float hemisphere_sign;  // +1: reflection lobe; -1: mirrored below (thin-walled transmission)
};

// Directional albedo of the unit-rho FON term, the paper's polynomial fit of G (about 2.5e-4
// absolute error): E(mu) = (1 + sigma G(mu)) / (1 + c1 sigma).
OPENPBR_FUNC float openpbr_eon_fon_albedo(float mu, float sigma)
{
    const float m = 1.0f - clamp(mu, 0.0f, 1.0f);
    const float g_over_pi = m * (0.0571085289f + m * (0.491881867f + m * (-0.332181442f + m * 0.0714429953f)));
    return (1.0f + sigma * g_over_pi) / (1.0f + OPENPBR_EON_C1 * sigma);
}

OPENPBR_FUNC OpenPBR_DiffuseLobe openpbr_diffuse_lobe_init(vec3 weight, vec3 rho, float sigma, float hemisphere_sign,
                                                           vec3 view)
{
    OpenPBR_DiffuseLobe lobe;
    const float a = 1.0f / (1.0f + OPENPBR_EON_C1 * sigma);
    const vec3 weighted_rho = weight * rho * OPENPBR_INV_PI;
    lobe.single_scatter_a = weighted_rho * a;
    lobe.single_scatter_b = weighted_rho * (sigma * a);
    lobe.sigma = sigma;
    lobe.hemisphere_sign = hemisphere_sign;
    const float e_avg = a * (1.0f + OPENPBR_EON_C2 * sigma);
    const float e_view = openpbr_eon_fon_albedo(abs(view.z), sigma);
    // 1 - E_avg is 0 at sigma = 0, where the multiple-scattering term vanishes anyway.
    const float one_minus_e_avg = 1.0f - e_avg;
    const vec3 rho_ms = rho * rho * e_avg / (vec3(1.0f) - rho * one_minus_e_avg);
    lobe.multiple_scatter =
        one_minus_e_avg > 1e-6f
            ? weight * rho_ms * (openpbr_max_first_at_tie(1.0f - e_view, 0.0f) * OPENPBR_INV_PI / one_minus_e_avg)
            : vec3(0.0f);
    // Albedo = rho E(mu_o) + rho_ms (1 - E(mu_o)): the multiple-scattering term integrates
    // (1 - E(mu_i)) cos over the hemisphere to pi (1 - E_avg), cancelling its denominator.
    lobe.albedo = weight * (rho * e_view + rho_ms * openpbr_max_first_at_tie(1.0f - e_view, 0.0f));
    return lobe;
}

// A lobe of weight 0 that prepare leaves in place of an absent one (never evaluated: its
// selection probability is 0): what openpbr_diffuse_lobe_init returns for weight 0, stored as
// constants (the init call with constant arguments was not folded by GCC, 5 % of a prepare).
OPENPBR_FUNC OpenPBR_DiffuseLobe openpbr_diffuse_lobe_empty(float hemisphere_sign)
{
    OpenPBR_DiffuseLobe lobe;
    lobe.single_scatter_a = vec3(0.0f);
    lobe.single_scatter_b = vec3(0.0f);
    lobe.multiple_scatter = vec3(0.0f);
    lobe.albedo = vec3(0.0f);
    lobe.sigma = 0.0f;
    lobe.hemisphere_sign = hemisphere_sign;
    return lobe;
}

OPENPBR_FUNC vec3 openpbr_diffuse_lobe_eval(OPENPBR_IN(OpenPBR_DiffuseLobe) lobe, vec3 view, vec3 light)
{
    // Mirror the light into the lobe's hemisphere so one formula serves both sides.
    const vec3 l = vec3(light.x, light.y, light.z * lobe.hemisphere_sign);
    // Written so that a NaN light (no direction) also returns 0.
    if (!(l.z > 0.0f))
    {
        return vec3(0.0f);
    }
    const float mu_o = abs(view.z);
    const float mu_i = l.z;
    vec3 value = lobe.single_scatter_a * mu_i;
    if (OPENPBR_WEIGHT_ACTIVE(lobe.sigma))
    {
        // (s / t) mu_i is formed as s (mu_i / t): s / t alone overflows when view and light
        // are both grazing (mu 1e-40, s ~ 1), while mu_i / max(mu_i, mu_o) stays in [0, 1].
        const float s = dot(l, vec3(view.x, view.y, mu_o)) - mu_i * mu_o;
        const float s_over_t_cos = s > 0.0f ? s * (mu_i / max(mu_i, mu_o)) : s * mu_i;
        value =
            value + lobe.single_scatter_b * s_over_t_cos +
            lobe.multiple_scatter * (openpbr_max_first_at_tie(1.0f - openpbr_eon_fon_albedo(mu_i, lobe.sigma), 0.0f) * mu_i);
    }
    return openpbr_max_first_at_tie(value, vec3(0.0f));
}

OPENPBR_FUNC float openpbr_diffuse_lobe_pdf(OPENPBR_IN(OpenPBR_DiffuseLobe) lobe, vec3 view, vec3 light)
{
    OPENPBR_UNUSED(view);
    // 0 for a NaN light as in eval (max(NaN, 0) is NaN on some targets).
    const float cos_theta = light.z * lobe.hemisphere_sign;
    return cos_theta > 0.0f ? openpbr_cosine_hemisphere_pdf(cos_theta) : 0.0f;
}

OPENPBR_FUNC OpenPBR_LobeSample openpbr_diffuse_lobe_sample(OPENPBR_IN(OpenPBR_DiffuseLobe) lobe, vec3 view, vec2 u)
{
    OPENPBR_UNUSED(view);
    const vec3 d = openpbr_sample_cosine_hemisphere(u);
    const bool transmits = lobe.hemisphere_sign < 0.0f;
    return openpbr_make_lobe_sample(
        vec3(d.x, d.y, d.z * lobe.hemisphere_sign),
        transmits ? openpbr_lobe_type(OPENPBR_LOBE_ID_DIFFUSE_TRANSMISSION,
                                      OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_DIFFUSE)
                  : openpbr_lobe_type(OPENPBR_LOBE_ID_DIFFUSE, OPENPBR_LOBE_TYPE_REFLECTION | OPENPBR_LOBE_TYPE_DIFFUSE));
}

// OpenPBR 1.1 "Glossy-diffuse": the base's diffuse reflection of roughness
// base_diffuse_roughness, weight `weight` (what passes the specular reflection times the
// diffuse share and base_weight) and color `color` (base_color, blended with the sheet's
// reflection by openpbr_diffuse_transmission_lobe_prepare on a thin-walled base). `albedo`
// receives its directional albedo at the view, weight included.
OPENPBR_FUNC OpenPBR_DiffuseLobe openpbr_diffuse_lobe_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 weight,
                                                              vec3 color, vec3 view, OPENPBR_OUT(vec3) albedo)
{
    const OpenPBR_DiffuseLobe lobe = openpbr_diffuse_lobe_init(weight, color, inputs.base_diffuse_roughness, 1.0f, view);
    albedo = lobe.albedo;
    return lobe;
}

// The differentiable build's blend of the base's diffuse colour `color` (weight `weight`) and the
// sheet's reflection (`sheet_color`, weight `sheet_weight`), to be used with the weight
// weight + sheet_weight + 1e-12. The plain blend (w c + s S) / max(w + s, 1e-12) is 0 / 1e-12
// where both weights are 0 (transmission_weight 1, or subsurface_weight 1 with anisotropy 1),
// and its reverse pass gives 0 there (weight 0 times the blend's derivative of 1e12) where the
// one-sided derivative is the lobe at the colour that grows. Here `color` enters once more with
// weight 1e-12 (a value change of ~1e-13, lost in rounding wherever a weight is above ~1e-5): the
// lobe's weight times its colour is then w c + s S + 1e-12 c, whose derivative is exact for the
// single-scattering terms (every lobe at base_diffuse_roughness 0) and for the multiple
// scattering as the base's weight grows; as the sheet's grows from 0 the multiple scattering's
// rho_ms(S) is taken to first order about rho_ms(c).
OPENPBR_FUNC vec3 openpbr_blend_kept_at_zero(vec3 weight, vec3 color, vec3 sheet_weight, vec3 sheet_color)
{
    return (weight * color + sheet_weight * sheet_color + 1e-12f * color) / (weight + sheet_weight + 1e-12f);
}

// OpenPBR 1.1 "Thin-walled case", subsurface: a thin scattering sheet of weight `sheet`, which
// reflects 1/2 S (1 - g) and transmits 1/2 S (1 + g), S = subsurface_color and
// g = subsurface_scatter_anisotropy, both diffuse lobes. Returns the transmission (the lobe
// mirrored below); the reflected half joins the base's diffuse reflection, whose
// reflection_weight and reflection_color (weight and base_color before the call) it updates
// to the weighted blend. `albedo` receives the transmission's directional albedo at the view.
OPENPBR_FUNC OpenPBR_DiffuseLobe openpbr_diffuse_transmission_lobe_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                                           vec3 sheet, vec3 view,
                                                                           OPENPBR_INOUT(vec3) reflection_weight,
                                                                           OPENPBR_INOUT(vec3) reflection_color,
                                                                           OPENPBR_OUT(vec3) albedo)
{
    const float g = inputs.subsurface_scatter_anisotropy;
    // The differentiable build's blend (openpbr_blend_kept_at_zero) keeps the derivative where
    // both weights are 0; its weight grows by the same 1e-12.
    reflection_color = OPENPBR_AUTODIFF != 0
                           ? openpbr_blend_kept_at_zero(reflection_weight, reflection_color, sheet * (0.5f * (1.0f - g)),
                                                        inputs.subsurface_color)
                           : (reflection_weight * reflection_color + sheet * (0.5f * (1.0f - g)) * inputs.subsurface_color) /
                                 max(reflection_weight + sheet * (0.5f * (1.0f - g)), vec3(1e-12f));
    reflection_weight = OPENPBR_AUTODIFF != 0 ? reflection_weight + sheet * (0.5f * (1.0f - g)) + 1e-12f
                                              : reflection_weight + sheet * (0.5f * (1.0f - g));
    const OpenPBR_DiffuseLobe lobe = openpbr_diffuse_lobe_init(sheet * (0.5f * (1.0f + g)), inputs.subsurface_color,
                                                               inputs.base_diffuse_roughness, -1.0f, view);
    albedo = lobe.albedo;
    return lobe;
}

OPENPBR_NAMESPACE_END

#endif
