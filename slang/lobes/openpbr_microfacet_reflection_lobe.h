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

struct OpenPBR_MicrofacetReflectionLobe OPENPBR_DIFFERENTIABLE
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
struct OpenPBR_GgxLobeAlbedo OPENPBR_DIFFERENTIABLE
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

// alpha_view of OpenPBR_GgxLobeAlbedo as the differentiable build computes it: the same value,
// written with T^2 = (alpha_t^2 + alpha_b^2) / 2 as
//   alpha_view^2 = T^2 + (1 - mu^2) (cos^2 phi - 1/2) (alpha_t^2 - alpha_b^2),
// whose second term, 0 at anisotropy 0 exactly, grows with the anisotropy where cos^2 phi > 1/2.
// The tables' roughness coordinate clamps at alpha 1, which alpha_view meets exactly at
// roughness 1 and anisotropy 0; there the one-sided derivatives from inside the range differ by
// input: a lower roughness moves alpha_view below 1 (the tables' slope), a higher anisotropy
// moves it above (the clamp: 0). So at or above 1 the anisotropic term's derivative is dropped
// where it grows and T's is kept (the clamp's own derivative passes at 1 and is 0 above).
OPENPBR_FUNC float openpbr_ggx_view_alpha_differentiable(float table_alpha, vec2 alpha, float mu_squared,
                                                         float cos_phi_squared)
{
    const float isotropic = table_alpha * table_alpha;
    const float anisotropic = (1.0f - mu_squared) * (cos_phi_squared - 0.5f) * (alpha.x * alpha.x - alpha.y * alpha.y);
    const bool capped = isotropic + anisotropic >= 1.0f && cos_phi_squared > 0.5f;
    return sqrt(isotropic + (capped ? OPENPBR_DETACH(anisotropic) : anisotropic));
}

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
    if (OPENPBR_WEIGHT_ACTIVE(anisotropy) && !is_delta)
    {
        const float cos_phi_squared = openpbr_cos_azimuth_squared(view);
        result.albedo *= openpbr_ggx_anisotropy_ratio(view.z, roughness, anisotropy, cos_phi_squared);
        const float mu_squared = view.z * view.z;
        const float projected_alpha_squared =
            alpha.x * alpha.x * cos_phi_squared + alpha.y * alpha.y * (1.0f - cos_phi_squared);
        result.reflection_alpha =
            OPENPBR_AUTODIFF != 0
                ? openpbr_ggx_view_alpha_differentiable(result.table_alpha, alpha, mu_squared, cos_phi_squared)
                : sqrt(mu_squared * result.table_alpha * result.table_alpha + (1.0f - mu_squared) * projected_alpha_squared);
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

// Lobe averages of the base layer's filmed Fresnel factors (spec "Thin-film iridescence": the
// film lies over the dielectric and the metal), for the albedo estimates prepare needs: the
// mean over the light a GGX reflection lobe reflects at this view (visible normals weighted by
// the reflected fraction G2 / G1, Heitz 2014) of
//   first:  the dielectric's change F_film - F_plain, untinted (the plain part keeps the
//           tabulated E_R: a ratio F_film / F_plain would magnify the tables' error);
//   second: the metal's factor, tinted as openpbr_fresnel_evaluate gives it.
// A factor that is not filmed (or not active) returns 0. Exact for a mirror (one evaluation at
// the view).
//
// Method. The filmed reflectance is a smooth function of the microfacet cosine c except at
// the stack's critical cosines, where it bends sharply: the film's, past which the film is
// evanescent (n_o sin theta >= n_f: frustrated total reflection, e.g. under a coat denser than
// the film), and the dielectric base's, past which the base reflects totally with or without
// the film (n_o sin theta >= n_b). A quadrature over c that ignores them weighs the wrong
// microfacets: four visible normals evaluated one by one lost up to 13.6 % and gained up to
// 5.8 % in a white furnace under a coat. So the lobe's light is cut into segments at those
// critical cosines and at further cosines, with each segment's exact share and mean from table 5
// (the quantiles Q(p) and partial first moments of c for this view and roughness,
// host/tables/film_table_generator.h; openpbr_film_lobe_cumulative inverts Q):
//  * below the base's critical cosine the dielectric's change is 0 (it reflects totally, filmed
//    or not); only a filmed metal is evaluated there, once;
//  * the evanescent film between the two critical cosines (or below the film's):
//    OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS segments cut at Chebyshev points of the interval,
//    crowded towards both ends, where the stack's quantities change like square roots (the base's
//    Fresnel factor rises from total reflection like sqrt(c^2 - c_b^2), the film's tunnelling like
//    sqrt(c_f^2 - c^2)): the largest error of the dielectric's change over the furnace's stacks
//    (docs/thin-film-estimate.md) fell from 0.034 with two halves to 0.020 with four of these;
//    eight (the default) left 65 -> 12 of 1,800 stacks past a critical cosine (the first of the
//    three grids) overestimating it by more than 0.01;
//  * the propagating film past the higher critical cosine c*: cut where w = sqrt(c^2 - c*^2)
//    crosses OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS - 1 thresholds spaced geometrically from
//    OPENPBR_FILM_ESTIMATE_FIRST_CUT to OPENPBR_FILM_ESTIMATE_LAST_CUT, and at the bounds of
//    the lobe's OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS equal shares (its sixteenths).
//    Past c* the stack's quantities are smooth functions of w (n_o w is the film's or the base's
//    n cos in it), not of c, and the reflectance falls from total reflection on the scale of w
//    itself (coat 1.33 over film 1.2: the change falls from 0.87 at c* to 0.21 at c* + 0.04):
//    cells even in c or in the lobe's share put that fall inside one cell (the largest error of
//    the dielectric's change was 0.04 with two halves, 0.003 with these cuts at exact moments).
//    Each segment is evaluated at one point while the change decays convexly past c*, so a wide
//    segment underestimates it (Jensen) and the layers below gain: over the furnace's stacks
//    (2,250 dense-reference cases, docs/thin-film-estimate.md) 85 cases underestimated the
//    change by more than 0.01 with 8 segments, 54 with 12, 42 with 16 (the default).
//    The share bounds keep segments in a near-mirror lobe that lies between two thresholds
//    (film 1.4 under a coat of 1.6, roughness 0.1, view cos 0.5, just past c* = 0.484: the
//    error of the change 0.021 with the median alone, 0.010 with the quartiles), and they split
//    the lobe's light beyond the last threshold, where a thick film's fringes pass through it
//    (film 1.4 of 1.5 um under a coat of 1.6, roughness 0.13, view cos 0.5: -0.0099 with
//    quarters and 12 thresholds, -0.0047 with sixteenths and 16). Over the three dense-reference grids (10,980 stacks)
//    the cases past a critical cosine underestimating the change by more than 0.005 went 299 ->
//    70 with sixteenths, 16 thresholds, 8 evanescent segments and the slivers below merged, and
//    the filmed furnace's worst cos 0.5 row under a coat of IOR 1.6 went from 1.008 into the band. A sliver of
//    light under OPENPBR_FILM_ESTIMATE_MIN_SHARE between two cuts joins the next segment (a
//    GGX lobe's long tails made every cut a film evaluation);
//  * without any critical cosine (in air, under a coat less dense than film and base): equal
//    shares of the lobe's light cut at table 5's even nodes, two halves
//    (OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS = 2), and the upper tail on its own at views below
//    OPENPBR_FILM_ESTIMATE_TAIL_VIEW. A film nearly index-matched to the medium above it (film
//    1.2 under a half coat of IOR 1.3 in air: n_o 1.15) has the sqrt-like bend of a critical
//    cosine just below 0 (n_f cos_f = sqrt(n_f^2 - n_o^2 + n_o^2 c^2)): two halves erred by
//    0.042 there at view cosine 0.1 (the furnace's worst losses, 0.960), four segments by 0.011.
//    So a wide lobe, whose interquartile range of c is at least OPENPBR_FILM_ESTIMATE_WIDE_WIDTH
//    times its median (rough lobes and grazing views, whose light reaches the grazing
//    microfacets where the film's amplitudes bend), is OPENPBR_FILM_ESTIMATE_WIDE_SEGMENTS
//    quarters, and one whose interquartile range is at least
//    OPENPBR_FILM_ESTIMATE_VERY_WIDE_RANGE in c itself (alpha 0.1 below view cos 0.04, 0.2
//    below about 0.35, 0.4 below about 0.7) OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS eighths.
//    The upper tail (docs/thin-film-estimate.md "The upper tail on its own"): a GGX lobe's long upper tail (at view cos 0.1
//    and alpha 0.013 the middle three quarters of its light lie between c = 0.089 and 0.110, the last eighth above 0.120,
//    reaching far up) pulled the upper half's mean to where the film's change bends, the largest remaining errors of the
//    dense reference without a critical cosine (0.034 high, 0.020 low); the last eighth as a segment of its own, evaluated
//    at its median, cut them to 0.0087 / 0.0085. Every cut and every segment's quartiles are even nodes, so the shares,
//    means and spreads are node reads (the cut at the lobe's mean before took a search and the cell model: the tail's
//    evaluation is paid by what that saved). A narrow lobe there, whose interquartile range of c is below
//    OPENPBR_FILM_ESTIMATE_NARROW_WIDTH times its median, is one segment evaluated at its median (one film evaluation
//    instead of two, as the mirror limit's one at the view): the film's amplitudes and the plain Fresnel factor change on
//    the scale of c itself (their derivatives grow like 1 / c towards grazing), so a lobe narrow against its median cosine
//    sees them nearly linear, and its fringes are averaged by the lobe's path spread as any segment's are (Belcour & Barla
//    2017's Gaussian phase average).
// Segments at or below c* are evaluated at their median cosine (the film's quantities change
// like sqrt there, and quantiles, unlike means, follow any monotonic change of variable), the
// others at their mean. The film's phase varies across a segment; averaging e^{i m delta} over it
// damps harmonic m like the spread of a spectral lobe does, so each segment passes the spread of
// its optical path 2 n_f d cos_f to the film (OpenPBR_ThinFilmInputs.optical_path_spread_um), from
// its quartiles (openpbr_film_segment_point). Up to OPENPBR_FILM_ESTIMATE_MAX_SEGMENTS film
// evaluations past a critical cosine (fewer where the cuts hold slivers of light: they join the
// next segment), both bases in each (they share the film's harmonics); one, two, four or eight
// (and the tail) in air or under a coat less dense than film and base. The segments depend on the view's cosine and the
// lobe's roughness only, so the estimate of an isotropic lobe does not depend on the view's azimuth; an anisotropic lobe
// reads the table at its root-mean-square alpha. Measured against a 96 x 96-node lobe average
// (tests/bsdf/test_film_estimate.cpp) and a 128 x 128-node one (docs/thin-film-estimate.md). The estimate's method, e.g.
// -DOPENPBR_FILM_ESTIMATE_METHOD=OPENPBR_FILM_ESTIMATE_AT_VIEW: SEGMENTS (default) the lobe's segments below; AT_VIEW the
// film at the view's cosine only, as for a mirror (what most implementations do; the accuracy study's comparison row).
#define OPENPBR_FILM_ESTIMATE_SEGMENTS 0
#define OPENPBR_FILM_ESTIMATE_AT_VIEW 1
#ifndef OPENPBR_FILM_ESTIMATE_METHOD
#define OPENPBR_FILM_ESTIMATE_METHOD OPENPBR_FILM_ESTIMATE_SEGMENTS
#endif
// Segments of the propagating film past a critical cosine, e.g. 16 (the default) or 2 for a
// cheaper estimate; and the first and last cut in w = sqrt(c^2 - c*^2) (0.015 and 0.53: from
// where total reflection ends at a film's edge to where the lobe is smooth again).
#ifndef OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS
#define OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS 16
#endif
#if OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS < 2
#error "OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS must be at least 2"
#endif
#define OPENPBR_FILM_ESTIMATE_FIRST_CUT 0.015f
#define OPENPBR_FILM_ESTIMATE_LAST_CUT 0.53f
// Segments of the evanescent film between the critical cosines, e.g. 8 (the default) or 2.
#ifndef OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS
#define OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS 8
#endif
// Equal shares of a lobe without a critical cosine (in air or under a coat less dense than the
// film and the base) that is neither narrow nor wide, cut at table 5's even nodes, e.g. 2 (the
// default: two film evaluations, three with the tail), 1 (one film evaluation fewer: every-lobe
// prepare 13,494 -> 11,588 instructions; against the dense reference without a critical cosine
// (benchmarks/film_estimate_dense.cpp, 4,758 stacks) the dielectric's change low by more than
// 0.01 / 0.005 and high by more than 0.01 in 0 / 5 / 0 -> 20 / 110 / 24 stacks, extremes
// -0.0058 / +0.0084 -> -0.0176 / +0.0263, the metal off by more than 0.01 in 0 -> 36) or 4
// (every-lobe prepare about 5,000 instructions more). 1, 2, 4 or 8: each share's quartiles must
// be even nodes.
#ifndef OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS
#define OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS 2
#endif
// Relative width below which a lobe without a critical cosine is one segment at its median
// (see the method above): (Q(3/4) - Q(1/4)) < width Q(1/2), e.g. 0.05 (the default: roughness
// 0.1 down to view cosines of about 0.3, roughness 0.2 down to about 0.7, roughness 0.3 from
// about 0.9; over the dense reference's 10,980 stacks of roughness 0.1-0.8
// (docs/thin-film-estimate.md) no case moved past 0.005 on the gain side, and no largest
// error moved) or 0 (always the two halves). On benchmarks/film_estimate_dense.cpp's 4,758 stacks
// without a critical cosine, 0.1 took every-lobe prepare 13,494 -> 12,683 instructions and left
// the change's counts as they were but put the metal off by more than 0.01 in 10 stacks (largest
// 0.0121, against 0.0081); 0.2 took it to 11,702 with the change low by more than 0.01 / 0.005
// and high by more than 0.01 in 7 / 52 / 3 stacks (extremes -0.0159 / +0.0113), the metal 23.
#ifndef OPENPBR_FILM_ESTIMATE_NARROW_WIDTH
#define OPENPBR_FILM_ESTIMATE_NARROW_WIDTH 0.05f
#endif
// The least share of the lobe's light evaluated on its own between two cuts past a critical
// cosine, e.g. 0.01 (the default: under a coat of IOR 1.6 over a film of 1.4, roughness 0.4,
// view cos 0.5, prepare 166,000 -> 110,000 instructions; dense-reference cases past a critical
// cosine low by more than 0.005: 58 -> 70 of 10,980) or 0 (every non-empty segment). Segments
// of share s in [m, 2 m) keep 2 (s - m) of it and those below m none (the rest joins the next
// segment), so the estimate has no jump where s crosses m.
#ifndef OPENPBR_FILM_ESTIMATE_MIN_SHARE
#define OPENPBR_FILM_ESTIMATE_MIN_SHARE 0.01f
#endif
// Equal shares of the lobe's light past the higher critical cosine: their bounds are further
// cuts there beside the thresholds in w, at table 5's nodes, e.g. 16 (the default), 8 (about
// 20 % fewer film evaluations; dense-reference cases low by more than 0.005: 70 -> 115 of
// 10,980) or 4 (the quartiles: 299 with 12 thresholds and 4 evanescent segments).
#ifndef OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS
#define OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS 16
#endif
// A wide lobe without a critical cosine, whose interquartile range of c is at least
// OPENPBR_FILM_ESTIMATE_WIDE_WIDTH times its median, is cut into OPENPBR_FILM_ESTIMATE_WIDE_SEGMENTS
// equal shares at table 5's nodes instead of two halves, e.g. 4 and 0.4 (the defaults: every-lobe
// prepare 18,961 -> 20,295 instructions (20,350 with the partial sliver merge); dense-reference
// cases without a critical cosine low by more than 0.005: 343 -> 249 of 5,490), 0.3 (20,929 instructions, 185 cases), 0.1
// (every lobe not narrow; 126 cases) or a width above 2 (never).
// A very wide lobe without a critical cosine, whose interquartile range of c is at least
// OPENPBR_FILM_ESTIMATE_VERY_WIDE_RANGE, is cut into OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS equal
// shares, e.g. 0.2 and 8 (the defaults: alpha 0.1 below view cos 0.04, 0.2 below about 0.35,
// 0.4 below about 0.7; with the tail below, dense-reference cases without a critical cosine low
// by more than 0.005: 36 -> 17 of 3,120 on grids A and B) or a range above 1 (never).
#ifndef OPENPBR_FILM_ESTIMATE_VERY_WIDE_RANGE
#define OPENPBR_FILM_ESTIMATE_VERY_WIDE_RANGE 0.2f
#endif
#ifndef OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS
#define OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS 8
#endif
// The upper tail of a lobe without a critical cosine as a segment of its own: the light above
// table 5's even node OPENPBR_FILM_ESTIMATE_TAIL_NODE of 32, e.g. 28 (the default: the last
// eighth; the last sixteenth left 31 cases low by more than 0.005 where the eighth left 38, the
// last 1/32 54), at views whose cosine is below OPENPBR_FILM_ESTIMATE_TAIL_VIEW, e.g. 0.55 (the
// default; 0.6 cost 20,509 instructions of every-lobe prepare against 20,295 with the one-lane
// film and the tail at its mean), 0 (never: every-lobe prepare 13,494 -> 12,821 instructions; the
// dense reference's stacks without a critical cosine low by more than 0.01 / 0.005 and high by
// more than 0.01: 0 / 5 / 0 -> 24 / 169 / 25) or 2 (always: about 24,500 with the one-lane film). A multiple of 4 (the
// tail's quartiles are even nodes).
#ifndef OPENPBR_FILM_ESTIMATE_TAIL_NODE
#define OPENPBR_FILM_ESTIMATE_TAIL_NODE 28
#endif
#if OPENPBR_FILM_ESTIMATE_TAIL_NODE % 4 != 0 || OPENPBR_FILM_ESTIMATE_TAIL_NODE <= 0 || \
    OPENPBR_FILM_ESTIMATE_TAIL_NODE >= OPENPBR_LUT_FILM_CORE_SIZE - 1
#error "OPENPBR_FILM_ESTIMATE_TAIL_NODE must be a multiple of 4 between 0 and 32 (e.g. 28)"
#endif
#ifndef OPENPBR_FILM_ESTIMATE_TAIL_VIEW
#define OPENPBR_FILM_ESTIMATE_TAIL_VIEW 0.55f
#endif
#ifndef OPENPBR_FILM_ESTIMATE_WIDE_SEGMENTS
#define OPENPBR_FILM_ESTIMATE_WIDE_SEGMENTS 4
#endif
#ifndef OPENPBR_FILM_ESTIMATE_WIDE_WIDTH
#define OPENPBR_FILM_ESTIMATE_WIDE_WIDTH 0.4f
#endif
#if (OPENPBR_LUT_FILM_CORE_SIZE - 1) % (4 * OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS) != 0 || \
    (OPENPBR_LUT_FILM_CORE_SIZE - 1) % (4 * OPENPBR_FILM_ESTIMATE_WIDE_SEGMENTS) != 0 ||  \
    (OPENPBR_LUT_FILM_CORE_SIZE - 1) % (4 * OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS) != 0
#error "the equal shares without a critical cosine must be 1, 2, 4 or 8 (each share's quartiles even nodes of 32)"
#endif
#if (OPENPBR_LUT_FILM_CORE_SIZE - 1) % OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS != 0
#error "OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS must divide table 5's probability intervals (32: 2, 4, 8, 16 or 32)"
#endif
#if (OPENPBR_LUT_FILM_CORE_SIZE - 1) % 4 != 0
#error "table 5's even probability nodes must include the quartiles (OPENPBR_LUT_FILM_CORE_SIZE = 4 k + 1)"
#endif
#if OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS < 1 || OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS < 1
#error "OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS and OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS must be at least 1"
#endif
// Metal below the base's critical cosine (1), the evanescent film, the propagating film (its
// segments and the share bounds), or the plain lobe's segments.
#define OPENPBR_FILM_ESTIMATE_CRITICAL_CUTS                                                \
    (OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS + OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS + \
     OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS)
#define OPENPBR_FILM_ESTIMATE_MAX_SEGMENTS                                              \
    (OPENPBR_FILM_ESTIMATE_CRITICAL_CUTS > OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS + 1 \
         ? OPENPBR_FILM_ESTIMATE_CRITICAL_CUTS                                          \
         : OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS + 1)
// The steps of the merge of thresholds and share bounds in openpbr_base_film_estimate: each but
// the last advances next_share (at most SHARE_SEGMENTS times) or next_threshold (at most
// CRITICAL_SEGMENTS - 1 times).
#define OPENPBR_FILM_ESTIMATE_MERGE_STEPS (OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS + OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS)
// The step of table 5's even nodes between equal shares (8 of 32 for quarters).
#define OPENPBR_FILM_ESTIMATE_SHARE_STEP ((OPENPBR_LUT_FILM_CORE_SIZE - 1) / OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS)

OPENPBR_FUNC float openpbr_critical_cosine(float n, float n_o)
{
    return n >= n_o ? 0.0f : openpbr_safe_sqrt(1.0f - openpbr_square(n / n_o));
}

// The cosine past c* = lowest where w = sqrt(c^2 - c*^2) crosses the index-th of the
// OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS - 1 thresholds, geometric from
// OPENPBR_FILM_ESTIMATE_FIRST_CUT to OPENPBR_FILM_ESTIMATE_LAST_CUT.
OPENPBR_FUNC float openpbr_film_estimate_threshold(float lowest, int index)
{
    const float step = OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS > 2
                           ? float(index) / float(OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS - 2)
                           : 0.5f;
    const float w =
        OPENPBR_FILM_ESTIMATE_FIRST_CUT * pow(OPENPBR_FILM_ESTIMATE_LAST_CUT / OPENPBR_FILM_ESTIMATE_FIRST_CUT, step);
    return sqrt(lowest * lowest + w * w);
}

// Optical path 2 d n_f cos_f of a film at outside cosine c; film_offset = (n_f - n_o)(n_f + n_o),
// 0 where the film is evanescent.
OPENPBR_FUNC float openpbr_film_optical_path(float thickness_um, float film_offset, float n_o, float cosine)
{
    return 2.0f * thickness_um * openpbr_safe_sqrt(film_offset + openpbr_square(n_o * cosine));
}

// The spread of the optical path over a segment whose quartile cosines are lower and upper:
// (path(Q(p_75)) - path(Q(p_25))) / 1.349, a Gaussian's interquartile range.
OPENPBR_FUNC float openpbr_film_path_spread(float thickness_um, float film_offset, float n_o, float lower, float upper)
{
    return abs(openpbr_film_optical_path(thickness_um, film_offset, n_o, upper) -
               openpbr_film_optical_path(thickness_um, film_offset, n_o, lower)) *
           (1.0f / 1.349f);
}

// The segment of the lobe's light between the cumulative bounds start and end (share,
// E[c; c <= x]): where the film is evaluated, at the segment's median cosine Q(p_mid)
// (at_median) or at its mean cosine, and the spread of its optical path from its quartiles,
// (path(Q(p_75)) - path(Q(p_25))) / 1.349 (a Gaussian's interquartile range). (A variance from
// tabulated second moments was tried and dropped: between the table's view and roughness nodes
// second moments blend as a mixture of the neighbouring lobes, whose spread of means, e.g. 0.012
// in cosine between the nodes around a view cosine of 0.5, dwarfs the width of a near-mirror
// lobe and damped its fringes away: an error of 0.105 in the dielectric's change under a coat of
// IOR 1.6, 0.022 with the quartiles. Quantiles and first moments blend as the lobes shift.)
// One quantile look-up in a loop (the quartiles, then the median only where the segment is
// evaluated there), so the look-up is compiled once.
OPENPBR_FUNC vec2 openpbr_film_segment_point(OPENPBR_IN(OpenPBR_FilmLobeTable) table, vec2 start, vec2 end, bool at_median,
                                             float thickness_um, float film_offset, float n_o)
{
    const float share = max(end.x - start.x, 0.0f);
    vec2 quartile_paths = vec2(0.0f);
    float median = 0.0f;
    const int look_ups = at_median ? 3 : 2;
    OPENPBR_MAX_ITERS(3)  // the quartiles and the median
    for (int look_up = 0; look_up < look_ups; ++look_up)
    {
        // p = 0.25, 0.75, 0.5 of the segment's share.
        const float fraction = look_up == 2 ? 0.5f : 0.25f + 0.5f * float(look_up);
        const float cosine = openpbr_film_lobe_quantile(table, start.x + fraction * share);
        const float path = openpbr_film_optical_path(thickness_um, film_offset, n_o, cosine);
        quartile_paths = look_up == 0   ? vec2(path, quartile_paths.y)
                         : look_up == 1 ? vec2(quartile_paths.x, path)
                                        : quartile_paths;
        median = cosine;
    }
    const float mean = share > 0.0f ? (end.y - start.y) / share : median;
    return vec2(clamp(at_median ? median : mean, 0.0f, 1.0f), abs(quartile_paths.y - quartile_paths.x) * (1.0f / 1.349f));
}

// The same for a segment between table 5's even nodes start_node and end_node (of 32, their
// distance a multiple of 4), start and end their (P, M1): at its mean cosine (the tail at its
// median), with the spread of the paths of its quartiles, which are even nodes too (node reads).
OPENPBR_FUNC vec2 openpbr_film_node_segment_point(OPENPBR_IN(OpenPBR_FilmLobeTable) table, int start_node, int end_node,
                                                  vec2 start, vec2 end, float thickness_um, float film_offset, float n_o)
{
    const int quarter = (end_node - start_node) / 4;
    // The lower and upper quartiles and the median, read at one site.
    vec4 quantiles = vec4(0.0f);
    OPENPBR_FILM_TABLE_READ_LOOP
    for (int read = 0; read < 3; ++read)
    {
        const int node = read == 0 ? start_node + quarter : (read == 1 ? end_node - quarter : (start_node + end_node) / 2);
        quantiles = openpbr_with_channel(quantiles, read, openpbr_film_lobe_even_quantile(table, node));
    }
    const float lower = quantiles.x;
    const float upper = quantiles.y;
    const float mean = clamp((end.y - start.y) / max(end.x - start.x, 1e-6f), 0.0f, 1.0f);
    // The tail (the segment ending at p = 1 that starts at OPENPBR_FILM_ESTIMATE_TAIL_NODE) at its
    // median: its light is skewed far up in c, where the film's change bends, and its mean
    // stood for it badly (film 1.2 under n_o 1.15, alpha 0.0134, view cos 0.1: the tail's change
    // in green -0.150, -0.188 at its mean cosine 0.158, -0.150 at its median).
    const bool tail = end_node == OPENPBR_LUT_FILM_CORE_SIZE - 1 && start_node == OPENPBR_FILM_ESTIMATE_TAIL_NODE;
    const float where = tail ? quantiles.z : mean;
    return vec2(where, openpbr_film_path_spread(thickness_um, film_offset, n_o, lower, upper));
}

OPENPBR_FUNC OpenPBR_FresnelPair openpbr_base_film_estimate(OPENPBR_IN(OpenPBR_Fresnel) dielectric, bool dielectric_active,
                                                            OPENPBR_IN(OpenPBR_Fresnel) metal, bool metal_active, vec3 view,
                                                            vec2 alpha)
{
    const bool dielectric_filmed = dielectric_active && OPENPBR_WEIGHT_ACTIVE(dielectric.film_weight);
    const bool metal_filmed = metal_active && OPENPBR_WEIGHT_ACTIVE(metal.film_weight);
    OpenPBR_Fresnel untinted = dielectric;
    untinted.tint = vec3(1.0f);
    // Both factors carry the same film (openpbr_add_thin_film).
    const float n_o = dielectric_filmed ? dielectric.outside_ior : metal.outside_ior;
    const float n_f = dielectric_filmed ? dielectric.film_ior : metal.film_ior;
    const float thickness_um = dielectric_filmed ? dielectric.film_thickness_um : metal.film_thickness_um;
    // (n_f cos_f)^2 = (n_f - n_o)(n_f + n_o) + (n_o cos)^2 (openpbr_thin_film_normal_term).
    const float film_offset = (n_f - n_o) * (n_f + n_o);
    const float film_critical = openpbr_critical_cosine(n_f, n_o);
    const float base_critical = dielectric_filmed ? openpbr_critical_cosine(dielectric.base_ior, n_o) : 0.0f;
    const float lowest = max(film_critical, base_critical);

    vec3 dielectric_sum = vec3(0.0f);
    vec3 metal_sum = vec3(0.0f);
    const bool at_view = openpbr_ggx_is_delta(alpha) || OPENPBR_FILM_ESTIMATE_METHOD == OPENPBR_FILM_ESTIMATE_AT_VIEW;
    const OpenPBR_FilmLobeTable table =
        openpbr_film_lobe_table(view.z, sqrt(0.5f * (alpha.x * alpha.x + alpha.y * alpha.y)));
    // The lobe's quartiles: the cuts past c*, and the width and the median of a narrow lobe
    // without a critical cosine. Table 5's even probability nodes include them (p = 1/4 at even
    // node 8 of 32), so they are node reads, without the cell model of openpbr_film_lobe_quantile.
    float quartiles[3];
    OPENPBR_FILM_TABLE_READ_LOOP
    for (int quartile = 0; quartile < 3; ++quartile)
    {
        quartiles[quartile] =
            at_view ? view.z
                    : openpbr_film_lobe_even_quantile(table, (quartile + 1) * ((OPENPBR_LUT_FILM_CORE_SIZE - 1) / 4));
    }
    const bool narrow =
        !at_view && lowest <= 0.0f && quartiles[2] - quartiles[0] < OPENPBR_FILM_ESTIMATE_NARROW_WIDTH * quartiles[1];
    const bool wide =
        !at_view && lowest <= 0.0f && quartiles[2] - quartiles[0] >= OPENPBR_FILM_ESTIMATE_WIDE_WIDTH * quartiles[1];
    // The cosines where the segments end, in increasing order (the last one, 2, above every
    // cosine: the whole lobe), see the method above.
    // Without a critical cosine (by_nodes) they are table 5's even nodes j of 32 instead, held as
    // floats (j >= 4 > 0 = c*, so the tests on c* below read them as cuts above it): one local
    // array where a second one for the nodes cost 20 SPIR-V instructions of the full module.
    float cuts[OPENPBR_FILM_ESTIMATE_MAX_SEGMENTS];
    const bool by_nodes = !at_view && !narrow && lowest <= 0.0f;
    int cut_count = 0;
    if (at_view || narrow)
    {
        cuts[0] = 2.0f;
        cut_count = 1;
    }
    else if (lowest <= 0.0f)
    {
        // No critical cosine: equal shares of the lobe's light cut at table 5's even nodes (two
        // halves, a wide lobe's quarters), and at grazing views the upper tail on its own; the
        // segments' shares, means and quartiles are node reads (no search, no cell model).
        const bool very_wide = quartiles[2] - quartiles[0] >= OPENPBR_FILM_ESTIMATE_VERY_WIDE_RANGE;
        const int segments = very_wide ? OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS
                             : wide    ? OPENPBR_FILM_ESTIMATE_WIDE_SEGMENTS
                                       : OPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS;
        const int step = (OPENPBR_LUT_FILM_CORE_SIZE - 1) / segments;
        OPENPBR_MAX_ITERS(OPENPBR_FILM_ESTIMATE_VERY_WIDE_SEGMENTS)  // segments - 1 cuts, at most the very wide lobe's
        for (int segment = 1; segment < segments; ++segment)
        {
            cuts[cut_count] = float(segment * step);
            ++cut_count;
        }
        if (view.z < OPENPBR_FILM_ESTIMATE_TAIL_VIEW &&
            (OPENPBR_LUT_FILM_CORE_SIZE - 1) - OPENPBR_FILM_ESTIMATE_TAIL_NODE < step)
        {
            cuts[cut_count] = float(OPENPBR_FILM_ESTIMATE_TAIL_NODE);
            ++cut_count;
        }
        cuts[cut_count] = float(OPENPBR_LUT_FILM_CORE_SIZE - 1);
        ++cut_count;
    }
    else
    {
        if (base_critical > 0.0f)
        {
            cuts[cut_count] = base_critical;
            ++cut_count;
        }
        if (film_critical > base_critical)
        {
            // The evanescent film between the two critical cosines (or between 0 and the film's),
            // cut at Chebyshev points: (1 - cos(pi k / E)) / 2 of the way.
            for (int segment = 1; segment < OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS; ++segment)
            {
                const float angle = OPENPBR_PI * float(segment) / float(OPENPBR_FILM_ESTIMATE_EVANESCENT_SEGMENTS);
                cuts[cut_count] = mix(base_critical, film_critical, 0.5f - 0.5f * cos(angle));
                ++cut_count;
            }
            cuts[cut_count] = film_critical;
            ++cut_count;
        }
        // Past c*: the thresholds in w and the bounds of the lobe's equal shares that lie past c*,
        // merged in increasing order in one loop (one step per cut: a nested loop would be
        // unrolled by drivers into thresholds x bounds copies of its body).
        int next_threshold = 0;
        float threshold = openpbr_film_estimate_threshold(lowest, 0);
        // The first step reads the first bound (below every cut, -1 is no cut): one read site.
        int next_share = 0;
        float share_bound = -1.0f;
        OPENPBR_MAX_ITERS(OPENPBR_FILM_ESTIMATE_MERGE_STEPS)
        for (;;)
        {
            // Bounds at or above 1 (past every threshold) are not cuts.
            if (next_share < OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS && share_bound < threshold)
            {
                if (share_bound > lowest)
                {
                    cuts[cut_count] = share_bound;
                    ++cut_count;
                }
                ++next_share;
                share_bound = next_share < OPENPBR_FILM_ESTIMATE_SHARE_SEGMENTS
                                  ? openpbr_film_lobe_even_quantile(table, next_share * OPENPBR_FILM_ESTIMATE_SHARE_STEP)
                                  : 2.0f;
            }
            else if (next_threshold < OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS - 1)
            {
                cuts[cut_count] = threshold;
                ++cut_count;
                ++next_threshold;
                threshold = next_threshold < OPENPBR_FILM_ESTIMATE_CRITICAL_SEGMENTS - 1
                                ? openpbr_film_estimate_threshold(lowest, next_threshold)
                                : 1.0f;
            }
            else
            {
                break;
            }
        }
        cuts[cut_count] = 2.0f;
        ++cut_count;
    }

    // One cumulative look-up, one segment point and one film evaluation per segment, each at one
    // call site, both bases in each evaluation.
    vec2 start = vec2(0.0f);
    int start_node = 0;
    OPENPBR_MAX_ITERS(OPENPBR_FILM_ESTIMATE_MAX_SEGMENTS)  // cut_count fills cuts[], that many at most
    for (int index = 0; index < cut_count; ++index)
    {
        const float cut = cuts[index];
        const int end_node = by_nodes ? int(cut) : 0;
        vec2 end = at_view || narrow ? vec2(1.0f, view.z)
                   : by_nodes        ? openpbr_film_lobe_even_moment(table, end_node)
                                     : openpbr_film_lobe_cumulative(table, cut);
        end = end.x > start.x ? end : start;
        // A sliver of the lobe's light joins the next segment, except at a critical cosine: a
        // segment of share s below 2 m (m = OPENPBR_FILM_ESTIMATE_MIN_SHARE) keeps the share
        // 2 (s - m) of it, nothing below m, so the estimate stays continuous in the view and the
        // stack (dropping a cut outright made it jump by 1e-4 relative where a share crossed m:
        // CPU against GPU-like rounding, query 1813542 of tests/checks/test_conformance.cpp).
        const float natural_share = end.x - start.x;
        const bool mergeable = cut != base_critical && cut != film_critical && index + 1 < cut_count;
        const float kept =
            mergeable && natural_share < 2.0f * OPENPBR_FILM_ESTIMATE_MIN_SHARE
                ? clamp(2.0f - 2.0f * OPENPBR_FILM_ESTIMATE_MIN_SHARE / max(natural_share, 1e-12f), 0.0f, 1.0f)
                : 1.0f;
        end = start + kept * (end - start);
        const float share = end.x - start.x;
        // Below the base's critical cosine the dielectric's change is 0 (total reflection, filmed
        // or not): only the metal there.
        const bool with_dielectric = dielectric_filmed && (at_view ? view.z >= base_critical : cut > base_critical);
        if (share > 1e-6f && (with_dielectric || metal_filmed))
        {
            // Segments at or below c* at their median (the evanescent film and the metal's part
            // below the base's critical cosine), the others at their mean.
            // (not "point": an HLSL keyword)
            // A narrow lobe at its median with the spread of its quartiles' paths, as
            // openpbr_film_segment_point gives it for the whole lobe, from the quartiles above.
            const vec2 where = at_view    ? vec2(view.z, 0.0f)
                               : narrow   ? vec2(quartiles[1], openpbr_film_path_spread(thickness_um, film_offset, n_o,
                                                                                        quartiles[0], quartiles[2]))
                               : by_nodes ? openpbr_film_node_segment_point(table, start_node, end_node, start, end,
                                                                            thickness_um, film_offset, n_o)
                                          : openpbr_film_segment_point(table, start, end, lowest > 0.0f && cut <= lowest,
                                                                       thickness_um, film_offset, n_o);
            const OpenPBR_FresnelPair pair =
                openpbr_fresnel_evaluate_base_pair_spread(untinted, with_dielectric, metal, metal_filmed, where.x, where.y);
            if (with_dielectric)
            {
                dielectric_sum += share * (pair.first - vec3(openpbr_fresnel_dielectric(where.x, dielectric.eta)));
            }
            if (metal_filmed)
            {
                metal_sum += share * pair.second;
            }
        }
        start = end;
        start_node = end_node;
    }
    OpenPBR_FresnelPair result;
    result.first = dielectric_sum;
    result.second = metal_sum;
    return result;
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

// The base layer's two Fresnel factors (spec "Base Substrate"), with the thin film on top where
// thin_film_weight > 0 (spec "Thin-film iridescence"; film_outside_ior the absolute IOR above
// the film). The dielectric's: GGX reflection at the (modulated) relative IOR eta, tinted by
// specular_color. The metal's: F82-tint (F0 = base_weight base_color, tinted by
// specular_color, scaled by specular_weight). The film only where there is one: each copy of
// the Fresnel struct costs (prepare).
OPENPBR_FUNC OpenPBR_Fresnel openpbr_specular_reflection_fresnel(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, float eta,
                                                                 float film_outside_ior)
{
    OpenPBR_Fresnel fresnel = openpbr_make_dielectric_fresnel(eta, inputs.specular_color);
    if (OPENPBR_WEIGHT_ACTIVE(inputs.thin_film_weight))
    {
        fresnel = openpbr_add_thin_film(fresnel, inputs.thin_film_weight, inputs.thin_film_thickness, inputs.thin_film_ior,
                                        film_outside_ior);
    }
    return fresnel;
}

OPENPBR_FUNC OpenPBR_Fresnel openpbr_metal_fresnel(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, float film_outside_ior)
{
    OpenPBR_Fresnel fresnel = openpbr_make_f82_fresnel(inputs.base_weight * inputs.base_color, inputs.specular_color,
                                                       vec3(openpbr_min_first_at_tie(inputs.specular_weight, 1.0f)));
    if (OPENPBR_WEIGHT_ACTIVE(inputs.thin_film_weight))
    {
        fresnel = openpbr_add_thin_film(fresnel, inputs.thin_film_weight, inputs.thin_film_thickness, inputs.thin_film_ior,
                                        film_outside_ior);
    }
    return fresnel;
}

// OpenPBR 1.1 "Base Substrate", f^R_specular: the dielectric base's GGX reflection with the
// Fresnel factor of openpbr_specular_reflection_fresnel at the (modulated, per-channel)
// relative IOR eta_channels, with Turquin compensation. alpha and base_lobe_albedo are the
// base's microsurface (shared with the metal and the thin-walled transmission); film_averages
// is openpbr_base_film_estimate's result where thin_film_weight > 0 (not read otherwise).
// Weight (1 - base_metalness). `albedo` receives E[f^R_specular] at the view per unit
// dielectric weight, the estimate the layers under it see removed: (1 - albedo) reaches them.
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe
openpbr_specular_reflection_lobe_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 eta_channels, vec2 alpha,
                                         OPENPBR_IN(OpenPBR_GgxLobeAlbedo) base_lobe_albedo, float film_outside_ior,
                                         OPENPBR_IN(OpenPBR_FresnelPair) film_averages, vec3 view, OPENPBR_OUT(vec3) albedo)
{
    const float mu = view.z;
    const OpenPBR_Fresnel fresnel = openpbr_specular_reflection_fresnel(inputs, eta_channels.y, film_outside_ior);
    const float dielectric_weight = 1.0f - inputs.base_metalness;
    const vec3 specular_compensation =
        openpbr_multiple_scattering_compensation(vec3(openpbr_dielectric_f0(eta_channels.y)), base_lobe_albedo.albedo);
    const float plain_reflection_albedo =
        openpbr_ggx_is_delta(alpha) ? openpbr_fresnel_dielectric(mu, eta_channels.y)
                                    : openpbr_ggx_lobe_dielectric_reflection_albedo(mu, eta_channels.y, base_lobe_albedo);
    // With a film, E[f^R] moves by the film's change of the Fresnel factor averaged over the
    // lobe, times the lobe's F = 1 albedo (the tables hold no film): exact for a mirror.
    vec3 reflection_albedo = vec3(plain_reflection_albedo);
    if (OPENPBR_WEIGHT_ACTIVE(fresnel.film_weight))
    {
        reflection_albedo = max(reflection_albedo + film_averages.first * base_lobe_albedo.albedo, vec3(0.0f));
    }
    albedo = openpbr_saturate(inputs.specular_color * specular_compensation * reflection_albedo);
    return openpbr_microfacet_reflection_lobe_init(specular_compensation * dielectric_weight, alpha, fresnel,
                                                   OPENPBR_LOBE_ID_SPECULAR_REFLECTION, 1.0f, view);
}

// OpenPBR 1.1 "Base Substrate", f_metal: the Fresnel factor of openpbr_metal_fresnel on the
// base's microsurface (alpha, base_lobe_albedo), with Turquin compensation; film_averages as for
// openpbr_specular_reflection_lobe_prepare. Weight base_metalness. `albedo` receives the metal's
// directional albedo at the view, base_metalness included.
OPENPBR_FUNC OpenPBR_MicrofacetReflectionLobe openpbr_metal_lobe_prepare(
    OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec2 alpha, OPENPBR_IN(OpenPBR_GgxLobeAlbedo) base_lobe_albedo,
    float film_outside_ior, OPENPBR_IN(OpenPBR_FresnelPair) film_averages, vec3 view, OPENPBR_OUT(vec3) albedo)
{
    const float mu = view.z;
    const OpenPBR_Fresnel fresnel = openpbr_metal_fresnel(inputs, film_outside_ior);
    const float metalness = inputs.base_metalness;
    const vec3 metal_compensation = openpbr_multiple_scattering_compensation(fresnel.f0, base_lobe_albedo.albedo);
    const OpenPBR_MicrofacetReflectionLobe metal = openpbr_microfacet_reflection_lobe_init(
        metal_compensation * metalness, alpha, fresnel, OPENPBR_LOBE_ID_METAL, 1.0f, view);
    // The filmed factor averaged over the lobe; without a film, the factor at the view.
    const vec3 mean_fresnel = OPENPBR_WEIGHT_ACTIVE(fresnel.film_weight)
                                  ? film_averages.second
                                  : openpbr_fresnel_evaluate_without_film(fresnel, mu);
    albedo =
        openpbr_saturate(metal_compensation * mean_fresnel * (metal.is_delta ? 1.0f : base_lobe_albedo.albedo)) * metalness;
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
