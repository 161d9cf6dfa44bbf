// GGX microfacet reflection (Walter et al. 2007) with visible-normal sampling; one struct for
// the base specular reflection, the metal and the coat, which differ only in their Fresnel
// factor (OpenPBR_Fresnel) and weight. Below OPENPBR_DELTA_ALPHA_THRESHOLD it is a mirror.
// Mirrored below the surface (hemisphere_sign -1) it is the thin-walled specular
// transmission: an un-deflected transmission lobe with the reflection's shape (spec
// "Thin-walled case": the sheet does not refract; the roughened lobe follows Kulla 2017).
//   f cos = weight * F(wo.h) D(h) G2(wo, wi) / (4 wo.z)
//   pdf   = G1(wo) D(h) / (4 wo.z)          (VNDF density times the reflection Jacobian)
//   sample weight of the lobe alone = weight * F G2 / G1(wo)
// Multiple-scattering compensation (Turquin 2019) is folded into `weight` by the caller,
// which depends only on the view, so eval stays a single-scattering evaluation.
#ifndef OPENPBR_MICROFACET_REFLECTION_LOBE_H
#define OPENPBR_MICROFACET_REFLECTION_LOBE_H

#include "openpbr_lobe_common.h"
#include "../math/openpbr_fresnel.h"
#include "../math/openpbr_vndf.h"

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_MicrofacetReflectionLobe
{
    vec3 weight;           // layering weight times energy compensation
    vec2 alpha;            // (alpha_t, alpha_b)
    bool is_delta;         // mirror: eval and pdf are 0, sample is deterministic
    float lambda_view;     // Smith Lambda of the view, shared by every eval
    float g1_view;         // 1 / (1 + lambda_view)
    float inverse_4_cos_view;  // 1 / (4 wo.z)
    OpenPBR_Fresnel fresnel;
    uint lobe_id;          // OPENPBR_LOBE_ID_SPECULAR_REFLECTION, _METAL, _COAT or _SPECULAR_TRANSMISSION
    float hemisphere_sign; // +1 reflection, -1 mirrored into the lower hemisphere
};

OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_microfacet_reflection_lobe_init(
    vec3 weight, vec2 alpha, OPENPBR_IN(OpenPBR_Fresnel) fresnel, uint lobe_id, float hemisphere_sign, vec3 view)
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
OPENPBR_FUNC vec3 openpbr_microfacet_reflection_lobe_eval_with(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe,
                                                               vec3 view, vec3 light_direction, bool with_film)
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

OPENPBR_FUNC vec3 openpbr_microfacet_reflection_lobe_eval(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe,
                                                          vec3 view, vec3 light_direction)
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

OPENPBR_FUNC float openpbr_microfacet_reflection_lobe_pdf(OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe,
                                                          vec3 view, vec3 light_direction)
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
OPENPBR_FUNC OpenPBR_LobeSample openpbr_microfacet_reflection_lobe_sample_with(
    OPENPBR_IN(OpenPBR_MicrofacetReflectionLobe) lobe, vec3 view, vec2 u, bool with_film)
{
    if (view.z <= 0.0f)
    {
        return openpbr_make_no_lobe_sample();
    }
    const uint side = lobe.hemisphere_sign > 0.0f ? OPENPBR_LOBE_TYPE_REFLECTION : OPENPBR_LOBE_TYPE_TRANSMISSION;
    if (lobe.is_delta)
    {
        OpenPBR_LobeSample mirror = openpbr_make_lobe_sample(
            vec3(-view.x, -view.y, view.z * lobe.hemisphere_sign),
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

OPENPBR_NAMESPACE_END

#endif
