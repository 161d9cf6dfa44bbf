// GGX microfacet reflection (Walter et al. 2007) with visible-normal sampling; one struct for
// the base specular reflection, the metal and the coat, which differ only in their Fresnel
// factor (OpenPBR_Fresnel) and weight. Below OPENPBR_DELTA_ALPHA_THRESHOLD it is a mirror.
// Mirrored below the surface (hemisphere_sign -1) it is the thin-walled specular
// transmission: an un-deflected transmission lobe with the reflection's shape (spec
// "Thin-walled case": the sheet does not refract; the roughened lobe follows Kulla 2017).
//   f cos = weight * F(wo.h) D(h) G2(wo, wi) / (4 wo.z)
//   pdf   = G1(wo) D(h) / (4 wo.z)          (VNDF density times the reflection Jacobian)
//   sample weight of the lobe alone = weight * F G2 / G1(wo)
// Multiple-scattering compensation (Turquin 2019) is folded into `weight` by prepare, as it
// depends only on the view, so eval stays a single-scattering evaluation.
// Four uses, each with its prepare: the coat (openpbr_coat_lobe_prepare), the dielectric
// base's specular reflection (openpbr_specular_reflection_lobe_prepare), the metal
// (openpbr_metal_lobe_prepare) and the thin-walled transmission
// (openpbr_thin_transmission_lobe_prepare).
#ifndef OPENPBR_MICROFACET_REFLECTION_LOBE_H
#define OPENPBR_MICROFACET_REFLECTION_LOBE_H

#include "openpbr_lobe_common.h"
#include "../math/openpbr_fresnel.h"
#include "../math/openpbr_vndf.h"
#include "../openpbr_lut.h"
#include "../openpbr_resolved_inputs.h"

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_MicrofacetReflectionLobe
{
    vec3 weight;               // layering weight times energy compensation
    vec2 alpha;                // (alpha_t, alpha_b)
    bool is_delta;             // mirror: eval and pdf are 0, sample is deterministic
    float lambda_view;         // Smith Lambda of the view, shared by every eval
    float g1_view;             // 1 / (1 + lambda_view)
    float inverse_4_cos_view;  // 1 / (4 wo.z)
    OpenPBR_Fresnel fresnel;
    uint lobe_id;           // OPENPBR_LOBE_ID_SPECULAR_REFLECTION, _METAL, _COAT or _SPECULAR_TRANSMISSION
    float hemisphere_sign;  // +1 reflection, -1 mirrored into the lower hemisphere
};

OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_microfacet_reflection_lobe_init(vec3 weight, vec2 alpha,
                                                                                      OPENPBR_IN(OpenPBR_Fresnel) fresnel,
                                                                                      uint lobe_id, float hemisphere_sign,
                                                                                      vec3 view)
{
    OpenPBR_MicrofacetReflectionLobe lobe;
    lobe.weight = weight;
    lobe.alpha = alpha;
    lobe.is_delta = openpbr_ggx_is_delta(alpha);
    lobe.lambda_view = openpbr_ggx_lambda(view, alpha);
    lobe.g1_view = 1.0f / (1.0f + lobe.lambda_view);
    lobe.inverse_4_cos_view = 0.25f / max(view.z, OPENPBR_FLOAT_MIN_NORMAL);
    lobe.fresnel = fresnel;
    lobe.lobe_id = lobe_id;
    lobe.hemisphere_sign = hemisphere_sign;
    return lobe;
}

// A lobe of weight 0 that prepare leaves in place of an absent one (never evaluated: its
// selection probability is 0); constants only, so setting it up costs nothing.
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_microfacet_reflection_lobe_empty(uint lobe_id)
{
    OpenPBR_MicrofacetReflectionLobe lobe;
    lobe.weight = vec3(0.0f);
    lobe.alpha = vec2(1.0f);
    lobe.is_delta = false;
    lobe.lambda_view = 0.0f;
    lobe.g1_view = 1.0f;
    lobe.inverse_4_cos_view = 0.25f;
    lobe.fresnel = openpbr_make_constant_fresnel(vec3(0.0f));
    lobe.lobe_id = lobe_id;
    lobe.hemisphere_sign = 1.0f;
    return lobe;
}

// with_film false where the caller knows the lobe's Fresnel factor carries no thin film (the
// coat and the thin-walled transmission: spec "Thin-film iridescence" puts the film on the base
// only): the film code is then not compiled into that call site (GPU compilers inline every
// call, and the film is the largest function of the BSDF).
OPENPBR_FUNC vec3 openpbr_microfacet_reflection_lobe_eval_with(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe, vec3 view,
                                                               vec3 light_direction, bool with_film)
{
    const vec3 light = vec3(light_direction.x, light_direction.y, light_direction.z * lobe.hemisphere_sign);
    if (lobe.is_delta || light.z <= 0.0f || view.z <= 0.0f)
    {
        return vec3(0.0f);
    }
    const vec3 h = openpbr_safe_normalize(view + light, vec3(0.0f, 0.0f, 1.0f));
    const float d = openpbr_ggx_d(h, lobe.alpha);
    const float g2 = openpbr_ggx_g2(lobe.lambda_view, openpbr_ggx_lambda(light, lobe.alpha));
    const vec3 f = with_film ? openpbr_fresnel_evaluate(lobe.fresnel, dot(view, h))
                             : openpbr_fresnel_evaluate_without_film(lobe.fresnel, dot(view, h));
    return lobe.weight * f * (d * g2 * lobe.inverse_4_cos_view);
}

OPENPBR_FUNC vec3 openpbr_microfacet_reflection_lobe_eval(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe, vec3 view,
                                                          vec3 light_direction)
{
    return openpbr_microfacet_reflection_lobe_eval_with(lobe, view, light_direction, true);
}

// The base's dielectric and metal reflection lobes together (spec "Base Substrate": both follow
// specular_roughness and specular_roughness_anisotropy, so they share alpha, the view terms and
// the half vector): the sum of both lobes' eval, with D, G2 and the film's harmonics computed
// once. An inactive lobe adds nothing; the geometry is taken from an active one. Both are
// reflection lobes (hemisphere_sign +1).
OPENPBR_FUNC vec3 openpbr_microfacet_reflection_lobe_pair_eval(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) dielectric,
                                                               bool dielectric_active,
                                                               OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) metal,
                                                               bool metal_active, vec3 view, vec3 light)
{
    const bool is_delta = dielectric_active ? dielectric.is_delta : metal.is_delta;
    if (!(dielectric_active || metal_active) || is_delta || light.z <= 0.0f || view.z <= 0.0f)
    {
        return vec3(0.0f);
    }
    const vec2 alpha = dielectric_active ? dielectric.alpha : metal.alpha;
    const float lambda_view = dielectric_active ? dielectric.lambda_view : metal.lambda_view;
    const float inverse_4_cos_view = dielectric_active ? dielectric.inverse_4_cos_view : metal.inverse_4_cos_view;
    const vec3 h = openpbr_safe_normalize(view + light, vec3(0.0f, 0.0f, 1.0f));
    const float d = openpbr_ggx_d(h, alpha);
    const float g2 = openpbr_ggx_g2(lambda_view, openpbr_ggx_lambda(light, alpha));
    const OpenPBR_FresnelPair f =
        openpbr_fresnel_evaluate_base_pair(dielectric.fresnel, dielectric_active, metal.fresnel, metal_active, dot(view, h));
    vec3 value = vec3(0.0f);
    if (dielectric_active)
    {
        value = dielectric.weight * f.first;
    }
    if (metal_active)
    {
        value += metal.weight * f.second;
    }
    return value * (d * g2 * inverse_4_cos_view);
}

OPENPBR_FUNC float openpbr_microfacet_reflection_lobe_pdf(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe, vec3 view,
                                                          vec3 light_direction)
{
    const vec3 light = vec3(light_direction.x, light_direction.y, light_direction.z * lobe.hemisphere_sign);
    if (lobe.is_delta || light.z <= 0.0f || view.z <= 0.0f)
    {
        return 0.0f;
    }
    const vec3 h = openpbr_safe_normalize(view + light, vec3(0.0f, 0.0f, 1.0f));
    // The sampler's density (OPENPBR_VNDF_METHOD, slang/math/openpbr_vndf.h).
    return openpbr_vndf_reflection_pdf(view, h, lobe.alpha, lobe.g1_view, lobe.inverse_4_cos_view);
}

// with_film as for openpbr_microfacet_reflection_lobe_eval_with (the mirror's weight).
OPENPBR_FUNC OpenPBR_LobeSample openpbr_microfacet_reflection_lobe_sample_with(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe)
                                                                                   lobe,
                                                                               vec3 view, vec2 u, bool with_film)
{
    if (view.z <= 0.0f)
    {
        return openpbr_make_no_lobe_sample();
    }
    const uint side = lobe.hemisphere_sign > 0.0f ? OPENPBR_LOBE_TYPE_REFLECTION : OPENPBR_LOBE_TYPE_TRANSMISSION;
    if (lobe.is_delta)
    {
        OpenPBR_LobeSample mirror =
            openpbr_make_lobe_sample(vec3(-view.x, -view.y, view.z * lobe.hemisphere_sign),
                                     openpbr_lobe_type(lobe.lobe_id, side | OPENPBR_LOBE_TYPE_SPECULAR));
        mirror.delta_weight = lobe.weight * (with_film ? openpbr_fresnel_evaluate(lobe.fresnel, view.z)
                                                       : openpbr_fresnel_evaluate_without_film(lobe.fresnel, view.z));
        return mirror;
    }
    const vec3 h = openpbr_sample_vndf_reflection(view, lobe.alpha, u);
    const vec3 light = reflect(-view, h);
    if (light.z <= 0.0f)
    {
        return openpbr_make_no_lobe_sample();
    }
    return openpbr_make_lobe_sample(vec3(light.x, light.y, light.z * lobe.hemisphere_sign),
                                    openpbr_lobe_type(lobe.lobe_id, side | OPENPBR_LOBE_TYPE_GLOSSY));
}

OPENPBR_FUNC OpenPBR_LobeSample openpbr_microfacet_reflection_lobe_sample(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe,
                                                                          vec3 view, vec2 u)
{
    return openpbr_microfacet_reflection_lobe_sample_with(lobe, view, u, true);
}

// The single-scattering albedos of one GGX lobe that compensation and layering read, for its
// view (computed once in prepare).
struct OpenPBR_GgxLobeAlbedo
{
    // Alpha of the isotropic look-ups of E_T0 and E_RT: the root mean square of
    // (alpha_t, alpha_b), which OpenPBR's anisotropy mapping keeps equal to r^2 (spec
    // "Microfacet model").
    float table_alpha;
    // E, the F = 1 reflection albedo of the lobe itself at this view (Turquin compensation).
    float albedo;
    // E_R of an anisotropic lobe is approximated from the isotropic 3D table as
    //   E_R(mu, alpha_view, eta) E / E(mu, alpha_view),
    //   alpha_view^2 = mu^2 r^4 + (1 - mu^2) (alpha_t^2 cos^2 phi + alpha_b^2 sin^2 phi):
    // the Fresnel factor sees mostly the slopes along the view azimuth (their projected
    // roughness also gives the view's masking exactly, Heitz 2014), blended towards the
    // azimuth-free r^2 at normal incidence; the ratio then carries the remaining difference of
    // the shadowing loss. Scaling E_R(mu, r^2) by E / E(mu, r^2) instead misses the Fresnel
    // shift (towards grazing along the smooth direction the visible normals cluster round the
    // macro normal and E_R nearly doubles) and measured worse than no correction. E_T0 and E_RT
    // keep r^2 unscaled: no such stand-in measured better. Isotropic lobes: table_alpha and 1.
    float reflection_alpha;
    float reflection_scale;
};

// Anisotropic lobes (anisotropy > 0) read the 4D table of E(mu, r, a, phi) / E(mu, r);
// isotropic ones only the cheaper 2D table. roughness and anisotropy are those given to
// openpbr_ggx_alpha for alpha; view is local (tangent along x).
OPENPBR_FUNC OpenPBR_GgxLobeAlbedo openpbr_ggx_lobe_albedo(float roughness, float anisotropy, vec2 alpha, vec3 view)
{
    OpenPBR_GgxLobeAlbedo result;
    result.table_alpha = sqrt(0.5f * (alpha.x * alpha.x + alpha.y * alpha.y));
    // A delta lobe scatters once: albedo 1 exactly, so no compensation is applied to it (the
    // tables near alpha = 0 are close to 1 but not exactly at grazing angles).
    const bool is_delta = openpbr_ggx_is_delta(alpha);
    result.albedo = is_delta ? 1.0f : openpbr_ggx_albedo(view.z, result.table_alpha);
    result.reflection_alpha = result.table_alpha;
    result.reflection_scale = 1.0f;
    if (anisotropy > 0.0f && !is_delta)
    {
        const float cos_phi_squared = openpbr_cos_azimuth_squared(view);
        result.albedo *= openpbr_ggx_anisotropy_ratio(view.z, roughness, anisotropy, cos_phi_squared);
        const float mu_squared = view.z * view.z;
        const float projected_alpha_squared =
            alpha.x * alpha.x * cos_phi_squared + alpha.y * alpha.y * (1.0f - cos_phi_squared);
        result.reflection_alpha =
            sqrt(mu_squared * result.table_alpha * result.table_alpha + (1.0f - mu_squared) * projected_alpha_squared);
        result.reflection_scale = result.albedo / max(openpbr_ggx_albedo(view.z, result.reflection_alpha), 1e-3f);
    }
    return result;
}

// E_R of a rough dielectric reflection lobe of relative IOR eta (single scattering), with the
// anisotropy correction of lobe_albedo: F_avg at the projected alpha times E_ggx (slang/
// openpbr_lut.h, openpbr_dielectric_reflection_albedo). Under table compensation
// lobe_albedo.albedo is that E_ggx already (E_ggx(reflection_alpha) x reflection_scale), so
// the 2D look-up is not repeated; the other modes read the table's E_ggx themselves.
OPENPBR_FUNC float openpbr_ggx_lobe_dielectric_reflection_albedo(float mu, float eta,
                                                                 OPENPBR_IN(OpenPBR_GgxLobeAlbedo) lobe_albedo)
{
#if OPENPBR_COMPENSATION_MODE == OPENPBR_COMPENSATION_TABLE
    return openpbr_dielectric_fresnel_average(mu, lobe_albedo.reflection_alpha, eta) * lobe_albedo.albedo;
#else
    return openpbr_dielectric_reflection_albedo(mu, lobe_albedo.reflection_alpha, eta) * lobe_albedo.reflection_scale;
#endif
}

// Mean change F_film - F_plain of the Fresnel factor over the light a GGX reflection lobe
// reflects at this view: a fixed 4-point quadrature over the visible normals (a rank-1 lattice
// through the spherical-cap sampler, each point weighted by the reflected fraction
// G2 / G1, Heitz 2014), exact for a mirror. The film's phase makes F_film oscillate with the
// microfacet angle, so no single angle stands for the lobe: evaluated at the view cosine the
// estimate was off by up to 14 % at roughness 0.9 (white furnace of a filmed white dielectric),
// 1.4 % with these 4 points. Only the change is estimated this way; the plain part keeps the
// tabulated E_R (the ratio F_film / F_plain would magnify the tables' error).
OPENPBR_FUNC vec3 openpbr_film_fresnel_change(OPENPBR_IN(OpenPBR_Fresnel) filmed, float eta, vec3 view, vec2 alpha)
{
    // A mirror is one node at the view; the film is evaluated at one call site either way (GPU
    // compilers inline every call, and the film is the largest function of the BSDF).
    const bool is_delta = openpbr_ggx_is_delta(alpha);
    const int node_count = is_delta ? 1 : 4;
    const float lambda_view = is_delta ? 0.0f : openpbr_ggx_lambda(view, alpha);
    vec3 change = vec3(0.0f);
    float weight_sum = 0.0f;
    for (int node = 0; node < node_count; ++node)
    {
        float cos_microfacet = view.z;
        float weight = 1.0f;
        if (!is_delta)
        {
            const vec2 u = vec2(fract(0.5f + 0.618034f * float(node)), (float(node) + 0.5f) * 0.25f);
            const vec3 microfacet = openpbr_sample_vndf_spherical_cap(view, alpha, u);
            cos_microfacet = dot(view, microfacet);
            const vec3 light = 2.0f * cos_microfacet * microfacet - view;
            weight = light.z > 0.0f ? (1.0f + lambda_view) / (1.0f + lambda_view + openpbr_ggx_lambda(light, alpha)) : 0.0f;
        }
        if (weight > 0.0f)
        {
            change += weight * (openpbr_fresnel_evaluate(filmed, cos_microfacet) -
                                vec3(openpbr_fresnel_dielectric(cos_microfacet, eta)));
            weight_sum += weight;
        }
    }
    return weight_sum > 0.0f ? change / weight_sum : vec3(0.0f);
}

// Turquin 2019, "Practical multiple scattering compensation for microfacet models": scale the
// single-scattering lobe by 1 + F0 (1 - E) / E, E the F = 1 albedo of the same lobe.
OPENPBR_FUNC vec3 openpbr_multiple_scattering_compensation(vec3 f0, float ggx_albedo)
{
    const float albedo = max(ggx_albedo, 1e-3f);
    return vec3(1.0f) + f0 * ((1.0f - albedo) / albedo);
}
// OpenPBR 1.1 "Coat": a dielectric GGX reflection at coat_eta, the coat's IOR relative to the
// exterior medium, with Turquin compensation; layer_weight is what the layers above leave it
// (opacity and fuzz), e.g. 1 for a bare coat. `albedo` receives the compensated directional
// albedo E_coat at the view, per unit coat weight (all channels equal: the coat reflects
// untinted); layering reads it as E_coat in lerp(1, T_coat (1 - E_coat), C).
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_coat_lobe_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                                        float coat_eta, float layer_weight, vec3 view,
                                                                        OPENPBR_OUT(vec3) albedo)
{
    const float coat_roughness = inputs.coat_roughness;
    const float coat_mu = view.z;
    const vec2 coat_alpha = openpbr_ggx_alpha(coat_roughness, inputs.coat_roughness_anisotropy);
    const OpenPBR_GgxLobeAlbedo coat_lobe_albedo =
        openpbr_ggx_lobe_albedo(coat_roughness, inputs.coat_roughness_anisotropy, coat_alpha, view);
    const OpenPBR_Fresnel coat_fresnel = openpbr_make_dielectric_fresnel(coat_eta, vec3(1.0f));
    const vec3 coat_compensation =
        openpbr_multiple_scattering_compensation(vec3(openpbr_dielectric_f0(coat_eta)), coat_lobe_albedo.albedo);
    const OpenPBR_MicrofacetReflectionLobe coat = openpbr_microfacet_reflection_lobe_init(
        coat_compensation * (layer_weight * inputs.coat_weight), coat_alpha, coat_fresnel, OPENPBR_LOBE_ID_COAT, 1.0f, view);
    const float coat_single_albedo =
        coat.is_delta ? openpbr_fresnel_dielectric(coat_mu, coat_eta)
                      : openpbr_ggx_lobe_dielectric_reflection_albedo(coat_mu, coat_eta, coat_lobe_albedo);
    albedo = vec3(min(coat_single_albedo * coat_compensation.x, 1.0f));
    return coat;
}

// OpenPBR 1.1 "Base Substrate", f^R_specular: the dielectric base's GGX reflection at the
// (modulated, per-channel) relative IOR eta_channels, tinted by specular_color, with Turquin
// compensation and, where thin_film_weight > 0, the thin film on top (spec "Thin-film
// iridescence"; film_outside_ior the absolute IOR above the film). alpha and base_lobe_albedo
// are the base's microsurface (shared with the metal and the thin-walled transmission).
// Weight (1 - base_metalness). `albedo` receives E[f^R_specular] at the view per unit
// dielectric weight, the estimate the layers under it see removed: (1 - albedo) reaches them.
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_specular_reflection_lobe_prepare(
    OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 eta_channels, vec2 alpha,
    OPENPBR_IN(OpenPBR_GgxLobeAlbedo) base_lobe_albedo, float film_outside_ior, vec3 view, OPENPBR_OUT(vec3) albedo)
{
    const float mu = view.z;
    const float film_weight = inputs.thin_film_weight;
    const float dielectric_weight = 1.0f - inputs.base_metalness;
    // The film only where there is one: each copy of the Fresnel struct costs (prepare).
    OpenPBR_Fresnel dielectric_fresnel = openpbr_make_dielectric_fresnel(eta_channels.y, inputs.specular_color);
    if (film_weight > 0.0f)
    {
        dielectric_fresnel = openpbr_add_thin_film(dielectric_fresnel, film_weight, inputs.thin_film_thickness,
                                                   inputs.thin_film_ior, film_outside_ior);
    }
    const vec3 specular_compensation =
        openpbr_multiple_scattering_compensation(vec3(openpbr_dielectric_f0(eta_channels.y)), base_lobe_albedo.albedo);
    const float plain_reflection_albedo =
        openpbr_ggx_is_delta(alpha) ? openpbr_fresnel_dielectric(mu, eta_channels.y)
                                    : openpbr_ggx_lobe_dielectric_reflection_albedo(mu, eta_channels.y, base_lobe_albedo);
    // With a film, E[f^R] moves by the film's change of the Fresnel factor averaged over the
    // lobe, times the lobe's F = 1 albedo (the tables hold no film): exact for a mirror.
    vec3 reflection_albedo = vec3(plain_reflection_albedo);
    if (film_weight > 0.0f)
    {
        OpenPBR_Fresnel untinted = dielectric_fresnel;
        untinted.tint = vec3(1.0f);
        reflection_albedo = max(reflection_albedo + openpbr_film_fresnel_change(untinted, eta_channels.y, view, alpha) *
                                                        base_lobe_albedo.albedo,
                                vec3(0.0f));
    }
    albedo = openpbr_saturate(inputs.specular_color * specular_compensation * reflection_albedo);
    return openpbr_microfacet_reflection_lobe_init(specular_compensation * dielectric_weight, alpha, dielectric_fresnel,
                                                   OPENPBR_LOBE_ID_SPECULAR_REFLECTION, 1.0f, view);
}

// OpenPBR 1.1 "Base Substrate", f_metal: F82-tint Fresnel (F0 = base_weight base_color, tinted
// by specular_color, scaled by specular_weight), on the base's microsurface (alpha,
// base_lobe_albedo), with Turquin compensation and the thin film where thin_film_weight > 0.
// Weight base_metalness. `albedo` receives the metal's directional albedo at the view,
// base_metalness included.
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_metal_lobe_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                                         vec2 alpha,
                                                                         OPENPBR_IN(OpenPBR_GgxLobeAlbedo) base_lobe_albedo,
                                                                         float film_outside_ior, vec3 view,
                                                                         OPENPBR_OUT(vec3) albedo)
{
    const float mu = view.z;
    const float metalness = inputs.base_metalness;
    const float film_weight = inputs.thin_film_weight;
    const vec3 metal_f0 = inputs.base_weight * inputs.base_color;
    OpenPBR_Fresnel metal_fresnel =
        openpbr_make_f82_fresnel(metal_f0, inputs.specular_color, vec3(min(inputs.specular_weight, 1.0f)));
    if (film_weight > 0.0f)
    {
        metal_fresnel = openpbr_add_thin_film(metal_fresnel, film_weight, inputs.thin_film_thickness, inputs.thin_film_ior,
                                              film_outside_ior);
    }
    const vec3 metal_compensation = openpbr_multiple_scattering_compensation(metal_f0, base_lobe_albedo.albedo);
    const OpenPBR_MicrofacetReflectionLobe metal = openpbr_microfacet_reflection_lobe_init(
        metal_compensation * metalness, alpha, metal_fresnel, OPENPBR_LOBE_ID_METAL, 1.0f, view);
    albedo = openpbr_saturate(metal_compensation * openpbr_fresnel_evaluate(metal_fresnel, mu) *
                              (metal.is_delta ? 1.0f : base_lobe_albedo.albedo)) *
             metalness;
    return metal;
}

// OpenPBR 1.1 "Thin-walled case", translucent base: an un-deflected transmission tinted by
// transmission_color, the reflection lobe's shape mirrored below, compensated by 1 / E of the
// base's microsurface. layer_weight is the translucent share of what passes the specular
// reflection, e.g. (1 - E[f^R_specular]) for a fully translucent dielectric. `albedo` receives
// the estimate layer_weight * transmission_color.
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_thin_transmission_lobe_prepare(
    OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 layer_weight, vec2 alpha,
    OPENPBR_IN(OpenPBR_GgxLobeAlbedo) base_lobe_albedo, vec3 view, OPENPBR_OUT(vec3) albedo)
{
    const vec3 thin_transmission_weight = layer_weight * inputs.transmission_color;
    const float thin_compensation = 1.0f / max(base_lobe_albedo.albedo, 0.05f);
    const OpenPBR_Fresnel no_fresnel = openpbr_make_constant_fresnel(vec3(1.0f));
    albedo = thin_transmission_weight;
    return openpbr_microfacet_reflection_lobe_init(thin_transmission_weight * thin_compensation, alpha, no_fresnel,
                                                   OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, -1.0f, view);
}

OPENPBR_NAMESPACE_END

#endif
