// Rough dielectric interface lobe (Walter et al. 2007, "Microfacet Models for Refraction
// through Rough Surfaces") with visible-normal sampling, in two forms:
//  - transmission only, without the Fresnel factor (OpenPBR 1.1 "Reduction to a mixture of
//    lobes": under albedo scaling the transmission Fresnel factor may be omitted, the
//    (1 - E[f^R]) weight already removes the reflected energy). Used for light entering the
//    translucent base and the subsurface medium.
//  - reflection + transmission with the Fresnel factor, chosen per microfacet with
//    probability F (the classical rough dielectric). Used from inside the object.
// eta = n_below / n_above in the lobe's frame, where the view is above (view.z > 0); it may be
// per channel (dispersion): each channel is then evaluated with its own IOR and sampling is a
// one-sample MIS over the three channel IORs, so an RGB renderer stays unbiased.
// The BTDF is written for throughput (no 1/eta^2 radiance factor): the factor cancels on
// entering and leaving a closed object, and a renderer with cameras or lights inside a medium
// applies it itself. With it, a white dielectric conserves energy (spec "White furnace").
//   f_T |cos_i| = eta^2 |i.h| |o.h| (1 - F) D G2 / (|o.n| (eta i.h + o.h)^2)
//   pdf_T       = P_T G1(o) |o.h| D / |o.n| * eta^2 |i.h| / (eta i.h + o.h)^2
//
// Near eta = 1 the refracted lobe collapses. To first order in d = eta - 1, the direction
// refracted through a microfacet h is t = -o + d (o - h / (o.h)) (Snell's law expanded), a
// deviation of |d| tan(theta_oh) from the straight-through -o; as the visible normals spread by
// alpha around a mean at cosine about sqrt(mu^2 + alpha^2) from the view, the transmitted lobe
// is about
//   w_T = |1 - 1/eta| alpha / (mu^2 + alpha^2)
// wide (radians), and at eta = 1 every microfacet sends the light straight on (t = -o): the BTDF
// is a delta, the Walter half vector o + eta t vanishes, and eval cannot resolve the lobe from
// the light direction alone. Below w_T = OPENPBR_DELTA_ALPHA_THRESHOLD, the width at which a
// GGX reflection lobe is already treated as a mirror, transmission is therefore a delta event:
// the sample is drawn exactly as for the rough lobe (visible normal, then Snell's law through
// it), but its weight is the microfacet estimator itself, (1 - F) G2 / G1 / P_T = G2 / G1,
// instead of eval / pdf. The estimator's mean is the rough lobe's transmission albedo on both
// sides of the switch, so the energy does not jump there, and at eta = 1 it is the delta
// pass-through t = -o with weight G2(o, -o) / G1(o) = (1 + Lambda) / (1 + 2 Lambda), which the
// compensation 1 / E_T0 (E_T0 of eta = 1 is that same value) turns into 1. Reflection keeps its
// rough lobe: at grazing views the Fresnel factor of a nearly index-matched interface is large.
// Two uses, each with its prepare: light entering the interior (openpbr_transmission_lobe_prepare)
// and the interface seen from inside (openpbr_interface_lobe_prepare).
#ifndef OPENPBR_DIELECTRIC_LOBE_H
#define OPENPBR_DIELECTRIC_LOBE_H

#include "openpbr_lobe_common.h"
#include "../math/openpbr_fresnel.h"
#include "../math/openpbr_vndf.h"
#include "../openpbr_lut.h"
#include "../openpbr_resolved_inputs.h"

// Smallest view cosine the rough lobe scatters at, e.g. 1e-18: GGX Lambda squares the cosine,
// which must stay a normal float (1e-18^2 = 1e-36 > 1.2e-38).
#define OPENPBR_MIN_VIEW_COSINE 1e-18f

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_DielectricLobe OPENPBR_DIFFERENTIABLE
{
    vec3 reflection_weight;    // multiplies F D G2 / (4 o.n); 0 for the transmission-only form
    vec3 transmission_weight;  // multiplies the BTDF (including compensation and tint)
    vec2 alpha;
    bool is_delta;
    bool transmission_is_delta;  // is_delta, or the refracted lobe narrower than the delta threshold
    bool with_fresnel;           // false: transmission-only form, the (1 - F) factor is 1
    bool dispersive;             // eta differs per channel
    vec3 eta;                    // n_below / n_above, per channel
    float lambda_view;
    float g1_view;
    uint lobe_id;
};

// Whether dispersion gives the channels different IORs (each channel then refracts, and is
// compensated, with its own).
// The differentiable build treats every IOR as dispersive, so the derivative with respect to the
// dispersion at scale 0 is kept.
OPENPBR_FUNC bool openpbr_channels_differ(vec3 eta) { return OPENPBR_AUTODIFF != 0 || !(eta.x == eta.y && eta.y == eta.z); }

// Width w_T (radians) of the refracted lobe at view cosine mu (see the header): |1 - 1/eta|
// alpha / (mu^2 + alpha^2), the widest channel for a dispersive eta.
OPENPBR_FUNC float openpbr_dielectric_transmission_width(vec2 alpha, vec3 eta, float mu)
{
    const float alpha_max = max(alpha.x, alpha.y);
    const vec3 deviation = abs(vec3(1.0f) - vec3(1.0f) / eta);
    return max(deviation.x, max(deviation.y, deviation.z)) * alpha_max / (mu * mu + alpha_max * alpha_max);
}

OPENPBR_FUNC OpenPBR_DielectricLobe openpbr_dielectric_lobe_init(vec3 reflection_weight, vec3 transmission_weight,
                                                                 vec2 alpha, vec3 eta, bool with_fresnel, uint lobe_id,
                                                                 vec3 view)
{
    OpenPBR_DielectricLobe lobe;
    lobe.reflection_weight = with_fresnel ? reflection_weight : vec3(0.0f);
    lobe.transmission_weight = transmission_weight;
    lobe.alpha = alpha;
    lobe.is_delta = openpbr_ggx_is_delta(alpha);
    lobe.transmission_is_delta =
        lobe.is_delta || openpbr_dielectric_transmission_width(alpha, eta, view.z) < OPENPBR_DELTA_ALPHA_THRESHOLD;
    lobe.with_fresnel = with_fresnel;
    lobe.dispersive = openpbr_channels_differ(eta);
    lobe.eta = eta;
    lobe.lambda_view = openpbr_ggx_lambda(view, alpha);
    lobe.g1_view = 1.0f / (1.0f + lobe.lambda_view);
    lobe.lobe_id = lobe_id;
    return lobe;
}

// A lobe of weight 0 that prepare leaves in place of an absent one (never evaluated: its
// selection probability is 0); every argument is a constant, so it folds to stores of constants.
OPENPBR_FUNC OpenPBR_DielectricLobe openpbr_dielectric_lobe_empty(uint lobe_id)
{
    return openpbr_dielectric_lobe_init(vec3(0.0f), vec3(0.0f), vec2(1.0f), vec3(1.0f), false, lobe_id,
                                        vec3(0.0f, 0.0f, 1.0f));
}

// Probability of choosing transmission at a microfacet with Fresnel reflectance f.
OPENPBR_FUNC float openpbr_dielectric_transmission_probability(OPENPBR_IN(OpenPBR_DielectricLobe) lobe, float f)
{
    return lobe.with_fresnel ? 1.0f - f : 1.0f;
}

// Value and density of one channel's IOR at a light direction; returns (value, pdf) with the
// value excluding the weight, so channels can share the code.
OPENPBR_FUNC vec2 openpbr_dielectric_lobe_channel(OPENPBR_IN(OpenPBR_DielectricLobe) lobe, vec3 view, vec3 light, float eta)
{
    // Below OPENPBR_MIN_VIEW_COSINE the visible microfacet area G1(o) o.n is under float
    // resolution (and Lambda's z^2 would be denormal): nothing scatters.
    if (lobe.is_delta || !(view.z >= OPENPBR_MIN_VIEW_COSINE) || light.z == 0.0f)
    {
        return vec2(0.0f);
    }
    const float lambda_light = openpbr_ggx_lambda(light, lobe.alpha);
    // G2 / G1(o) and G1(o) / o.n are formed separately: both stay bounded at grazing view
    // (G1(o) / o.n -> 2 / alpha), while D / o.n alone overflows for o.n near 1e-38.
    const float g2_over_g1 = (1.0f + lobe.lambda_view) / (1.0f + lobe.lambda_view + lambda_light);
    const float g1_over_cos_view = lobe.g1_view / view.z;
    if (light.z > 0.0f)
    {
        if (!lobe.with_fresnel)
        {
            return vec2(0.0f);
        }
        const vec3 h = openpbr_safe_normalize(view + light, vec3(0.0f, 0.0f, 1.0f));
        const float d = openpbr_ggx_d(h, lobe.alpha);
        const float f = openpbr_fresnel_dielectric(dot(view, h), eta);
        const float pdf = f * d * (0.25f * g1_over_cos_view);
        return vec2(pdf * g2_over_g1, pdf);
    }
    // A transmission narrower than the delta threshold is a delta event (header): not seen here.
    if (lobe.transmission_is_delta)
    {
        return vec2(0.0f);
    }
    // Transmission: generalized half vector, oriented to the upper hemisphere.
    vec3 h = view + light * eta;
    h = openpbr_safe_normalize(h.z < 0.0f ? -h : h, vec3(0.0f, 0.0f, 1.0f));
    const float o_dot_h = dot(view, h);
    const float i_dot_h = dot(light, h);
    // Refraction geometry: the view above and the light below the microfacet.
    if (o_dot_h <= 0.0f || i_dot_h >= 0.0f)
    {
        return vec2(0.0f);
    }
    const float d = openpbr_ggx_d(h, lobe.alpha);
    const float f = lobe.with_fresnel ? openpbr_fresnel_dielectric(o_dot_h, eta) : 0.0f;
    const float denominator = openpbr_square(eta * i_dot_h + o_dot_h);
    // The denominator vanishes only at the straight-through direction of eta -> 1, where the
    // BTDF tends to a delta; below 1e-20 the Jacobian (<= 9e20) would overflow the products.
    if (!(denominator >= 1e-20f))
    {
        return vec2(0.0f);
    }
    const float jacobian = eta * eta * abs(i_dot_h) / denominator;
    const float visible = (o_dot_h * d) * g1_over_cos_view * jacobian;
    const float value = (1.0f - f) * g2_over_g1 * visible;
    const float pdf = openpbr_dielectric_transmission_probability(lobe, f) * visible;
    return vec2(value, pdf);
}

// A dispersive lobe is evaluated once per channel IOR, the others once (at eta.x = eta.y =
// eta.z). One loop whose trip count (1 or 3) is known only at run time, so the channel code is
// compiled once per call site: Mesa's NIR inlines every call and unrolls loops of known trip
// count, and the four copies written out (one plain, three dispersive) in each of eval and pdf
// made up a tenth of the full module (docs/performance.md, "llvmpipe build time").
OPENPBR_FUNC int openpbr_dielectric_lobe_channel_count(OPENPBR_IN(OpenPBR_DielectricLobe) lobe)
{
    return lobe.dispersive ? 3 : 1;
}

OPENPBR_FUNC vec3 openpbr_dielectric_lobe_eval(OPENPBR_IN(OpenPBR_DielectricLobe) lobe, vec3 view, vec3 light)
{
    const vec3 weight = light.z > 0.0f ? lobe.reflection_weight : lobe.transmission_weight;
    vec3 value = vec3(0.0f);
    const int channel_count = openpbr_dielectric_lobe_channel_count(lobe);
    OPENPBR_MAX_ITERS(3)  // one channel, or three where dispersive
    for (int channel = 0; channel < channel_count; ++channel)
    {
        value = openpbr_with_channel(
            value, channel, openpbr_dielectric_lobe_channel(lobe, view, light, openpbr_channel_of(lobe.eta, channel)).x);
    }
    return weight * (lobe.dispersive ? value : vec3(value.x));
}

OPENPBR_FUNC float openpbr_dielectric_lobe_pdf(OPENPBR_IN(OpenPBR_DielectricLobe) lobe, vec3 view, vec3 light)
{
    // Dispersive: one-sample MIS over the channel IORs, each chosen with probability 1/3.
    float pdf_sum = 0.0f;
    const int channel_count = openpbr_dielectric_lobe_channel_count(lobe);
    OPENPBR_MAX_ITERS(3)  // one channel, or three where dispersive
    for (int channel = 0; channel < channel_count; ++channel)
    {
        pdf_sum += openpbr_dielectric_lobe_channel(lobe, view, light, openpbr_channel_of(lobe.eta, channel)).y;
    }
    return lobe.dispersive ? pdf_sum * (1.0f / 3.0f) : pdf_sum;
}

// u.x, u.y: the microfacet; selector in [0, 1): channel (when dispersive) and then R or T.
OPENPBR_FUNC OpenPBR_LobeSample openpbr_dielectric_lobe_sample(OPENPBR_IN(OpenPBR_DielectricLobe) lobe, vec3 view, vec2 u,
                                                               float selector)
{
    if (!(view.z >= OPENPBR_MIN_VIEW_COSINE))
    {
        return openpbr_make_no_lobe_sample();
    }
    float choice = clamp(selector, 0.0f, 0.99999994f);
    int channel = 0;
    if (lobe.dispersive)
    {
        channel = min(int(choice * 3.0f), 2);
        choice = choice * 3.0f - float(channel);
    }
    const float eta = channel == 0 ? lobe.eta.x : (channel == 1 ? lobe.eta.y : lobe.eta.z);
    const vec3 h = lobe.is_delta ? vec3(0.0f, 0.0f, 1.0f) : openpbr_sample_vndf_full(view, lobe.alpha, u);
    const float o_dot_h = dot(view, h);
    const float f = lobe.with_fresnel ? openpbr_fresnel_dielectric(o_dot_h, eta) : 0.0f;
    const bool reflects = choice >= openpbr_dielectric_transmission_probability(lobe, f);
    const bool delta_event = reflects ? lobe.is_delta : lobe.transmission_is_delta;
    const uint kind = delta_event ? OPENPBR_LOBE_TYPE_SPECULAR : OPENPBR_LOBE_TYPE_GLOSSY;
    vec3 light;
    if (reflects)
    {
        light = reflect(-view, h);
        if (light.z <= 0.0f)
        {
            return openpbr_make_no_lobe_sample();
        }
    }
    else
    {
        light = refract(-view, h, 1.0f / eta);
        if (light.z >= 0.0f || dot(light, light) < 0.5f)
        {
            return openpbr_make_no_lobe_sample();
        }
        light = normalize(light);
    }
    OpenPBR_LobeSample lobe_sample = openpbr_make_lobe_sample(
        light,
        openpbr_lobe_type(lobe.lobe_id, kind | (reflects ? OPENPBR_LOBE_TYPE_REFLECTION : OPENPBR_LOBE_TYPE_TRANSMISSION)));
    if (delta_event)
    {
        // Delta: the chosen branch carries F or (1 - F) over its probability, i.e. exactly 1
        // per branch, times the shadowing G2 / G1 of the transmitted direction where the
        // microfacets are rough (a collapsed refraction lobe, see the header); a dispersive
        // delta only lights the sampled channel (times 3 for its 1/3).
        const vec3 weight = reflects ? lobe.reflection_weight : lobe.transmission_weight;
        const vec3 channel_mask =
            lobe.dispersive ? vec3(channel == 0 ? 3.0f : 0.0f, channel == 1 ? 3.0f : 0.0f, channel == 2 ? 3.0f : 0.0f)
                            : vec3(1.0f);
        const float shadowing =
            lobe.is_delta ? 1.0f
                          : (1.0f + lobe.lambda_view) / (1.0f + lobe.lambda_view + openpbr_ggx_lambda(light, lobe.alpha));
        lobe_sample.delta_weight = weight * (channel_mask * shadowing);
    }
    return lobe_sample;
}

// The albedo that compensates a rough dielectric interface: E_T0 for the refraction entering
// from outside (floored at OPENPBR_MIN_TRANSMISSION_ALBEDO), E_RT for the interface seen from
// inside (floored at 0.05). At relative IOR exactly 1 either is the delta pass-through of weight
// G2 / G1 = (1 + Lambda) / (1 + 2 Lambda) (lambda_view: Smith Lambda of the view; Fresnel is 0),
// which is then the albedo exactly: the tables' one-sided nodes at 1 -/+ 2^-20 interpolate to
// within 5e-5 of it but not exactly (a mean weight of 1.0052 at roughness 0.05, view cos 0.02).
OPENPBR_FUNC float openpbr_dielectric_compensation_albedo(float mu, float table_alpha, float eta, float lambda_view,
                                                          bool from_inside)
{
    if (eta == 1.0f)
    {
        return (1.0f + lambda_view) / (1.0f + 2.0f * lambda_view);
    }
    return from_inside ? max(openpbr_dielectric_interface_albedo(mu, table_alpha, eta), 0.05f)
                       : max(openpbr_dielectric_transmission_albedo(mu, table_alpha, eta), OPENPBR_MIN_TRANSMISSION_ALBEDO);
}

// The share of the refraction that the compensation's floor keeps from one channel (see
// openpbr_transmission_lobe_prepare): 0 unless the floor holds, a second look-up only then.
OPENPBR_FUNC float openpbr_transmission_floor_share(float mu, float table_alpha, float eta, float compensation_albedo)
{
    return eta != 1.0f && compensation_albedo <= OPENPBR_MIN_TRANSMISSION_ALBEDO
               ? 1.0f - max(openpbr_dielectric_transmission_albedo(mu, table_alpha, eta), 0.0f) /
                            OPENPBR_MIN_TRANSMISSION_ALBEDO
               : 0.0f;
}

// A rough dielectric's compensation per channel: the albedo (openpbr_dielectric_compensation_albedo)
// and, entering from outside, the floor's share (openpbr_transmission_floor_share; 0 from inside).
struct OpenPBR_DielectricCompensation OPENPBR_DIFFERENTIABLE
{
    vec3 albedo;
    vec3 floor_share;
};

// A dispersive lobe refracts each channel with its own IOR, so each channel is compensated by
// its own albedo. One channel's albedo for all three let a channel that transmits much more than
// the green one gain energy: relative IOR 1/3 (green, mostly total internal reflection, E_T0 at
// the floor) against 0.996 (a 1000 nm channel at Abbe number 1) carried the red channel's
// 1 - E_R / 1e-3 instead of 1 - E_R, a sample weight of 1.4e4
// (fuzz/corpus/finding_dispersive_channel_compensation.bin). Without dispersion the green
// channel's values serve all three.
// One loop over the channels, whose trip count (1 or 3) is known only at run time: Mesa's NIR
// inlines every call and unrolls loops of known trip count, and the three channels written out
// (six table look-ups at each of the two call sites, three floor shares) made the full module's
// llvmpipe pipeline 1.3 s slower to build (docs/performance.md, "llvmpipe build time").
OPENPBR_FUNC OpenPBR_DielectricCompensation openpbr_dielectric_compensation(float mu, float table_alpha, vec3 eta,
                                                                            float lambda_view, bool from_inside)
{
    const bool dispersive = openpbr_channels_differ(eta);
    const int first_channel = dispersive ? 0 : 1;
    const int end_channel = dispersive ? 3 : 2;
    OpenPBR_DielectricCompensation compensation;
    compensation.albedo = vec3(0.0f);
    compensation.floor_share = vec3(0.0f);
    // Counted from 0: Slang's reverse mode fails on a loop whose counter starts at a run-time value.
    OPENPBR_MAX_ITERS(3)  // one channel, or three where dispersive
    for (int step = 0; step < end_channel - first_channel; ++step)
    {
        const int channel = first_channel + step;
        const float channel_eta = openpbr_channel_of(eta, channel);
        const float albedo = openpbr_dielectric_compensation_albedo(mu, table_alpha, channel_eta, lambda_view, from_inside);
        const float floor_share =
            from_inside ? 0.0f : openpbr_transmission_floor_share(mu, table_alpha, channel_eta, albedo);
        compensation.albedo = openpbr_with_channel(compensation.albedo, channel, albedo);
        compensation.floor_share = openpbr_with_channel(compensation.floor_share, channel, floor_share);
    }
    if (!dispersive)
    {
        compensation.albedo = vec3(compensation.albedo.y);
        compensation.floor_share = vec3(compensation.floor_share.y);
    }
    return compensation;
}

// OpenPBR 1.1 "Translucent base" and "Subsurface": refraction into the interior, the
// transmission-only form. layer_weight is what passes the specular reflection per unit of
// base, e.g. (1 - E[f^R_specular]) (1 - base_metalness); translucent and subsurface are the
// shares of the two slabs light enters (their sum at most 1). The translucent share is tinted
// by transmission_color when there is no medium (transmission_depth 0); otherwise, and for
// subsurface, the interior medium applies the color. Compensated by 1 / E_T0 of the rough
// lobe, per channel where dispersion gives each channel its own IOR. `albedo` receives the weight the lobe refracts (its
// selection estimate); `slab_albedo` the albedo the coat's darkening sees of the entering slabs: the subsurface slab returns
// subsurface_color (spec "Subsurface": its multiple-scattering albedo), the translucent slab its tint. `reflected` receives
// the share of layer_weight x (translucent + subsurface) that the compensation's floor keeps from the refraction: where E_T0
// lies below OPENPBR_MIN_TRANSMISSION_ALBEDO (below relative IOR 1 seen from outside at grazing views, where nearly every
// microfacet reflects totally) the lobe carries E_T0 / floor of 1 - E_R, and the caller hands the rest to the specular
// reflection (openpbr_prepare_lobes_of): light that meets a totally reflecting microsurface several times leaves it by
// reflection. Without it the white furnace of relative IOR 0.67, roughness 0.2 at view cos 0.02 lost 0.039 (E_T0 6e-4) and
// 0.5 at cos 0.1 lost 0.017. `slab_albedo` excludes that share; `albedo`, the lobe's selection estimate, keeps it, so a
// refracted sample weighs at most about (1 - E_R) / OPENPBR_MIN_TRANSMISSION_ALBEDO (selecting by the carried share E_T0 /
// floor made weights grow like 1 / E_T0: 1.7e4 found by the fuzzer).
OPENPBR_FUNC OpenPBR_DielectricLobe openpbr_transmission_lobe_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                                      vec3 layer_weight, float translucent, float subsurface,
                                                                      vec2 alpha, float table_alpha, vec3 eta_channels,
                                                                      vec3 view, OPENPBR_OUT(vec3) albedo,
                                                                      OPENPBR_OUT(vec3) slab_albedo,
                                                                      OPENPBR_OUT(vec3) reflected)
{
    const float mu = view.z;
    const vec3 translucent_tint = inputs.transmission_depth > 0.0f ? vec3(1.0f) : inputs.transmission_color;
    const vec3 transmission_weight = layer_weight * (translucent * translucent_tint + vec3(subsurface));
    // A delta lobe refracts exactly 1 - F: no compensation (the table near alpha = 0 smears
    // the step at the critical angle when eta < 1 and gained up to 115 % there).
    const bool is_delta = openpbr_ggx_is_delta(alpha);
    vec3 compensation_albedo = vec3(1.0f);
    vec3 kept = vec3(0.0f);
    if (!is_delta)
    {
        const OpenPBR_DielectricCompensation compensation =
            openpbr_dielectric_compensation(mu, table_alpha, eta_channels, openpbr_ggx_lambda(view, alpha), false);
        compensation_albedo = compensation.albedo;
        kept = compensation.floor_share;
    }
    albedo = transmission_weight;
    slab_albedo =
        layer_weight * (translucent * translucent_tint + subsurface * inputs.subsurface_color) * (vec3(1.0f) - kept);
    reflected = layer_weight * ((translucent + subsurface) * kept);
    return openpbr_dielectric_lobe_init(vec3(0.0f), transmission_weight / compensation_albedo, alpha, eta_channels, false,
                                        OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, view);
}

// The dielectric interface seen from the denser side, inside a non-thin-walled object (eta
// inverted): reflection and refraction with Fresnel and total internal reflection, compensated
// by 1 / E_RT (per channel where dispersion gives each channel its own IOR). layer_weight is the geometry opacity;
// exit_factor what light leaving crosses above the interface (the coat once, the fuzz), applied to the refracted part only.
OPENPBR_FUNC OpenPBR_DielectricLobe openpbr_interface_lobe_prepare(float layer_weight, vec3 exit_factor, vec2 alpha,
                                                                   float table_alpha, vec3 eta_channels, vec3 view)
{
    const float mu = view.z;
    const vec3 eta_inside = vec3(1.0f) / eta_channels;
    const vec3 compensation_albedo =
        openpbr_ggx_is_delta(alpha)
            ? vec3(1.0f)
            : openpbr_dielectric_compensation(mu, table_alpha, eta_inside, openpbr_ggx_lambda(view, alpha), true).albedo;
    const vec3 weight = layer_weight / compensation_albedo;
    return openpbr_dielectric_lobe_init(weight, exit_factor * weight, alpha, eta_inside, true,
                                        OPENPBR_LOBE_ID_INTERFACE_FROM_INSIDE, view);
}

OPENPBR_NAMESPACE_END

#endif
