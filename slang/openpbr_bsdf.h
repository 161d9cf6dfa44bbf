// The OpenPBR 1.1 surface BSDF: prepare, eval, sample, pdf.
//
// Layering follows the specification's reduction to a mixture of lobes (spec "Reduction to a
// mixture of lobes", docs/spec-notes.md 2.3) with albedo scaling:
//   f_PBR        = lerp(f_pass_through, f_surface, geometry_opacity)
//   f_surface    = F f_fuzz + (1 - F E_fuzz) f_coated
//   f_coated     = C f_coat + lerp(1, T_coat (1 - E_coat), C) darkening f_base
//   f_base       = lerp(f_dielectric, f_metal, M)
//   f_dielectric = f^R_specular + (1 - E[f^R_specular]) lerp(lerp(f_diffuse, f_sss, S), f^T, T)
// Inside a non-thin-walled object only the interface is seen (reflection + refraction with
// the inverted IOR); thin-walled surfaces are mirrored so the view is always on top.
// Every view-dependent factor (albedos, compensation, lobe weights and selection
// probabilities) is computed once in openpbr_prepare; eval, sample and pdf then only do
// per-light-direction work.
//
// Conventions: world-space unit directions pointing away from the surface; eval returns
// BSDF x |cos(light, normal)|; sample returns weight = BSDF x |cos| / pdf; pdf == 0 means no
// sample. Delta lobes (roughness below OPENPBR_DELTA_ALPHA_THRESHOLD, opacity pass-through)
// are not seen by eval and pdf; a delta sample returns its lobe's selection probability as
// pdf and OPENPBR_LOBE_TYPE_SPECULAR in its lobe type.
#ifndef OPENPBR_BSDF_H
#define OPENPBR_BSDF_H

#include "openpbr_input_contract.h"
#include "openpbr_features.h"
#include "openpbr_lut.h"
#include "openpbr_volume.h"
#include "lobes/openpbr_dielectric_lobe.h"
#include "lobes/openpbr_diffuse_lobe.h"
#include "lobes/openpbr_fuzz_lobe.h"
#include "lobes/openpbr_microfacet_reflection_lobe.h"

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_DiffuseSpecular
{
    vec3 diffuse;   // diffuse lobes (EON reflection and thin-walled diffuse transmission)
    vec3 specular;  // everything else (microfacet lobes, fuzz)
};

struct OpenPBR_BsdfSample
{
    vec3 direction;                   // world space
    OpenPBR_DiffuseSpecular weight;   // BSDF x |cos| / pdf, split like eval
    float pdf;                        // solid-angle pdf, or the discrete probability of a delta lobe
    OpenPBR_BsdfLobeType lobe_type;   // OPENPBR_LOBE_TYPE_NONE when pdf == 0
};

// Wavelengths (nm) the three channels stand for when the caller passes none: the dominant
// wavelengths of the Rec.709 primaries, e.g. for dispersion in an RGB renderer.
#define OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM vec3(612.0f, 549.0f, 465.0f)

// The same as a function, for callers that see the library through a module (Slang `import
// openpbr;` exports declarations, not macros), e.g. to pass an exterior IOR to openpbr_prepare.
OPENPBR_FUNC vec3 openpbr_default_rgb_wavelengths_nm()
{
    return OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM;
}

struct OpenPBR_PreparedBsdf
{
    OpenPBR_Basis basis;       // base shading frame, view side up (flipped for back faces)
    OpenPBR_Basis coat_basis;  // coat frame, same side as the base frame
    OpenPBR_Basis fuzz_basis;  // fuzz frame: base and coat normals blended by coat_weight
    vec3 view;                 // view in the base frame (z >= 0)
    vec3 coat_view;
    vec3 fuzz_view;
    vec3 view_world;
    bool inside;               // view from inside a non-thin-walled object: interface only

    OpenPBR_FuzzLobe fuzz;
    OpenPBR_MicrofacetReflectionLobe coat;
    OpenPBR_MicrofacetReflectionLobe specular;
    OpenPBR_MicrofacetReflectionLobe metal;
    OpenPBR_DiffuseLobe diffuse;
    OpenPBR_DiffuseLobe diffuse_transmission;          // thin-walled subsurface, mirrored below
    OpenPBR_DielectricLobe transmission;               // entering refraction, or the interface from inside
    OpenPBR_MicrofacetReflectionLobe thin_transmission; // thin-walled un-deflected transmission
    vec3 pass_through_weight;                          // (1 - geometry_opacity), delta straight through

    // Factor on every lobe under the coat for a light above: constant + absorbing * T(light),
    // T(light) = coat_color^(1 / (2 mu_t(light))) (spec "Coat", view-dependent absorption).
    vec3 under_coat_constant;
    vec3 under_coat_absorbing;
    vec3 coat_half_log_color;  // 0.5 ln(coat_color); 0 when the coat does not absorb
    bool coat_absorbs;         // false: T(light) = 1, so eval and sample skip its exp
    float coat_inverse_eta_squared;
    vec3 under_coat_transmitted;  // the factor for lights below (the coat is crossed once)

    // Selection probabilities (sum 1, or all 0 when nothing scatters). A lobe with
    // probability 0 is never evaluated: a zero-weight lobe costs nothing in eval/pdf/sample.
    float probability_fuzz;
    float probability_coat;
    float probability_specular;
    float probability_metal;
    float probability_diffuse;
    float probability_diffuse_transmission;
    float probability_transmission;
    float probability_thin_transmission;
    float probability_pass_through;

    vec3 emission;                       // attenuated emission towards the view, nits
    OpenPBR_HomogeneousVolume volume;    // interior medium (is_present false when none)
};

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
    if (openpbr_ggx_is_delta(alpha))
    {
        return openpbr_fresnel_evaluate(filmed, view.z) - vec3(openpbr_fresnel_dielectric(view.z, eta));
    }
    const float lambda_view = openpbr_ggx_lambda(view, alpha);
    vec3 change = vec3(0.0f);
    float weight_sum = 0.0f;
    for (int node = 0; node < 4; ++node)
    {
        const vec2 u = vec2(fract(0.5f + 0.618034f * float(node)), (float(node) + 0.5f) * 0.25f);
        const vec3 microfacet = openpbr_sample_vndf_spherical_cap(view, alpha, u);
        const float cos_microfacet = dot(view, microfacet);
        const vec3 light = 2.0f * cos_microfacet * microfacet - view;
        if (light.z > 0.0f)
        {
            const float weight = (1.0f + lambda_view) / (1.0f + lambda_view + openpbr_ggx_lambda(light, alpha));
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

// OpenPBR 1.1 "Base Substrate", modulated IOR: specular_weight xi scales F0 through the IOR,
// eps = sgn(eta - 1) sqrt(xi F0(eta)), eta' = (1 + eps) / (1 - eps), xi clamped below 1/F0.
OPENPBR_FUNC float openpbr_modulated_ior(float eta, float specular_weight)
{
    const float f0 = openpbr_dielectric_f0(eta);
    const float xi = min(specular_weight, 0.9999f / max(f0, 1e-8f));
    const float epsilon = (eta >= 1.0f ? 1.0f : -1.0f) * sqrt(xi * f0);
    // xi > 1 pushes eta' past the input contract's [1/3, 3] (e.g. xi = 5 at eta = 3 gives
    // eta' ~ 4e4), outside the compensation tables: clamp after modulation as well.
    return clamp((1.0f + epsilon) / (1.0f - epsilon), OPENPBR_IOR_MIN, OPENPBR_IOR_MAX);
}

// Spec "Coat" darkening: hemispherical average of the dielectric Fresnel factor, the spec's
// fit for eta in [1, 3] and the reciprocity relation E_F(eta) = 1 - eta^2 (1 - E_F(1/eta)).
OPENPBR_FUNC float openpbr_average_fresnel(float eta)
{
    const float e = max(eta, 1.0f / max(eta, 1e-3f));
    const float average = log((10893.0f * e - 1438.2f) / (-774.4f * e * e + 10212.0f * e + 1.0f));
    const float clamped = clamp(average, 0.0f, 1.0f);
    return eta >= 1.0f ? clamped : 1.0f - eta * eta * (1.0f - clamped);
}

// Dispersion (spec "Translucent base"): Cauchy n(lambda) = A + B / lambda^2 through n_d at the
// Fraunhofer d line with Abbe number V_d = abbe / scale (F 486.1 nm, d 587.6 nm, C 656.3 nm).
OPENPBR_FUNC vec3 openpbr_dispersive_ior(float ior_d, float abbe_number, float dispersion_scale, vec3 wavelengths_nm)
{
    if (!(dispersion_scale > 0.0f))
    {
        return vec3(ior_d);
    }
    const float abbe = max(abbe_number / dispersion_scale, OPENPBR_ABBE_MIN);
    const float inverse_f2 = 1.0f / (486.1f * 486.1f);
    const float inverse_c2 = 1.0f / (656.3f * 656.3f);
    const float b = (ior_d - 1.0f) / (abbe * (inverse_f2 - inverse_c2));
    const float a = ior_d - b / (587.6f * 587.6f);
    // NaN or infinite wavelengths (caller input) map into the range too: NaN to 300 nm, so the
    // IOR and every table coordinate derived from it stay finite.
    const vec3 lambda = openpbr_clamp_finite(wavelengths_nm, 300.0f, 1000.0f);
    return clamp(vec3(a) + b / (lambda * lambda), vec3(OPENPBR_IOR_MIN), vec3(OPENPBR_IOR_MAX));
}

// The inputs every prepare step reads: the input contract (README "Input contract"), then the
// feature toggles (slang/openpbr_features.h); run once per prepare.
OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_prepare_inputs(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs)
{
    return openpbr_apply_feature_toggles(openpbr_apply_input_contract(raw_inputs));
}

// Whether results depend on the wavelengths passed to prepare (dispersive transmission).
OPENPBR_FUNC bool openpbr_needs_rgb_wavelengths(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs)
{
    const OpenPBR_ResolvedInputs inputs = openpbr_prepare_inputs(raw_inputs);
    return inputs.transmission_dispersion_scale > 0.0f && inputs.transmission_weight > 0.0f &&
           inputs.base_metalness < 1.0f && inputs.geometry_opacity > 0.0f && !inputs.geometry_thin_walled;
}

// Transmittance of one pass through the coat at cosine mu (outside), T = coat_color^(1/(2 mu_t)).
OPENPBR_FUNC vec3 openpbr_coat_transmittance(vec3 half_log_color, float inverse_eta_squared, float mu)
{
    const float mu_t = openpbr_safe_sqrt(1.0f - (1.0f - mu * mu) * inverse_eta_squared);
    return exp(half_log_color / max(mu_t, 1e-4f));
}

// A local view as the lobes see it. Above the surface but closer to grazing than the tables hold
// (OPENPBR_LUT_MIN_VIEW_COSINE), it is seen at that cosine, so the albedo estimates stay valid:
// below it a lobe whose smooth anisotropic direction (alpha_b down to 1e-7) faces the view turns
// rough in projection (alpha_b tan(theta) > 1) and reflected up to twice the tabulated albedo
// (white anisotropic metal at cos 1e-8: mean sample weight 1.90). The length changes by at most
// 5e-9. At or below the horizon the cosine is 0: nothing scatters.
OPENPBR_FUNC vec3 openpbr_floor_view_cosine(vec3 view)
{
    return vec3(view.x, view.y, view.z > 0.0f ? max(view.z, OPENPBR_LUT_MIN_VIEW_COSINE) : 0.0f);
}

OPENPBR_FUNC OpenPBR_Basis openpbr_flip_basis(OPENPBR_IN(OpenPBR_Basis) basis)
{
    OpenPBR_Basis flipped;
    flipped.tangent = basis.tangent;
    flipped.bitangent = -basis.bitangent;
    flipped.normal = -basis.normal;
    return flipped;
}

// Selection probability below which a lobe is dropped, relative to the sum over all lobes, e.g.
// 1e-9 (below float resolution of that sum, 6e-8). Such lobes come from weights or colors near
// the underflow limit (e.g. opacity 1e-7 times a coat color 1e-7), where the albedo estimate and
// the value eval returns are products of different factors and can disagree by orders of
// magnitude: a sample of any lobe then met a pdf far below the dropped lobe's value (fuzzing found
// sample weights of 1e4 to 1e22, docs/stability.md). Dropping loses at most 1e-9 of the energy.
#define OPENPBR_MIN_LOBE_PROBABILITY 1e-9f

OPENPBR_FUNC float openpbr_kept_probability(float probability, float cut)
{
    return probability >= cut ? probability : 0.0f;
}

// Channel weights that steer lobe selection towards what a lobe adds to the current path: the
// path throughput divided by its largest channel, each channel floored at
// OPENPBR_SELECTION_CHANNEL_FLOOR. Selection probabilities are then proportional to
// luminance(throughput x lobe albedo) (the luminance of the lobe's contribution to this path),
// which lowers variance where the path carries mostly one color (e.g. after a red glass).
// Any positive choice keeps every estimator unbiased (sample weights divide by the probability
// actually used, and pdf reports the same mixture); the floor keeps every lobe the unweighted
// selection would sample selectable, so a lobe whose albedo estimate misses a channel of its
// value still covers it. NaN or negative channels count as 0, +inf as the largest float; an
// all-zero throughput (or the project-form prepare, which passes white) weighs nothing:
// exactly vec3(1).
// Floor of a channel weight, e.g. 1e-3: a lobe seen only through a channel with 1/1000 of the
// largest throughput keeps 1/1000 of its unweighted share.
#define OPENPBR_SELECTION_CHANNEL_FLOOR 1e-3f

OPENPBR_FUNC vec3 openpbr_selection_channel_weights(vec3 path_throughput)
{
    const vec3 nonnegative = openpbr_clamp_finite(path_throughput, 0.0f, OPENPBR_FLOAT_MAX);
    const float largest = openpbr_max3(nonnegative);
    // Grey (white included) is exactly vec3(1) without a division: GPU division is not
    // correctly rounded (2.5 ulp in Vulkan), and 1 / 1 != 1 there would move every selection
    // probability by an ulp and the GPU's lobe choices away from the CPU's.
    const bool grey = nonnegative.x == nonnegative.y && nonnegative.y == nonnegative.z;
    if (!(largest > OPENPBR_FLOAT_MIN_NORMAL) || grey)
    {
        return vec3(1.0f);
    }
    return max(nonnegative / largest, vec3(OPENPBR_SELECTION_CHANNEL_FLOOR));
}

// The luminance of a white lobe's weight under the channel weights: exactly 1 for white weights
// (so the project-form prepare keeps its probabilities bit for bit), the luminance otherwise.
OPENPBR_FUNC float openpbr_selection_white_scale(vec3 channel_weights)
{
    const bool white = channel_weights.x == channel_weights.y && channel_weights.y == channel_weights.z;
    return white ? channel_weights.x : openpbr_luminance(channel_weights);
}

// Every lobe below is set up only where its weight is above zero (issue "a lobe whose weight is
// zero costs nothing"): the others keep the empty lobe and selection probability 0, which eval,
// pdf and sample never look at. With a feature toggled off its weight is the constant 0, so the
// compiler removes the set-up altogether. `inputs` have passed openpbr_prepare_inputs.
// exterior_ior: the absolute IOR of the medium the view is in (README "Exterior medium"),
// already passed through openpbr_contract_exterior_ior. `path_throughput` only steers lobe
// selection (openpbr_selection_channel_weights); white gives the unweighted probabilities.
OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare_lobes_of(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world,
                                                           vec3 rgb_wavelengths_nm, float exterior_ior,
                                                           vec3 path_throughput)
{
    OpenPBR_PreparedBsdf bsdf;
    bsdf.view_world = openpbr_safe_normalize(view_world, inputs.geometry_basis.normal);
    const float opacity = inputs.geometry_opacity;
    const float metalness = inputs.base_metalness;
    const float coat_weight = inputs.coat_weight;
    const float fuzz_weight = inputs.fuzz_weight;
    const bool thin_walled = inputs.geometry_thin_walled;
    // Light enters the interior through the dielectric base (translucent or subsurface).
    const float entering_weight = (1.0f - metalness) *
                                  (inputs.transmission_weight + (1.0f - inputs.transmission_weight) * inputs.subsurface_weight);
    const bool back_face = dot(bsdf.view_world, inputs.geometry_basis.normal) < 0.0f;
    bsdf.inside = back_face && !thin_walled && entering_weight > 0.0f && opacity > 0.0f;
    bsdf.basis = back_face ? openpbr_flip_basis(inputs.geometry_basis) : inputs.geometry_basis;
    bsdf.coat_basis = back_face ? openpbr_flip_basis(inputs.geometry_coat_basis) : inputs.geometry_coat_basis;
    bsdf.view = openpbr_to_local(bsdf.basis, bsdf.view_world);
    bsdf.view = openpbr_floor_view_cosine(bsdf.view);
    // Coat and fuzz frames only where those layers exist; otherwise the base frame stands in
    // (eval then transforms the light once).
    bsdf.coat_view = bsdf.view;
    if (coat_weight > 0.0f)
    {
        bsdf.coat_view = openpbr_to_local(bsdf.coat_basis, bsdf.view_world);
        bsdf.coat_view = openpbr_floor_view_cosine(bsdf.coat_view);
    }
    bsdf.fuzz_basis = bsdf.basis;
    bsdf.fuzz_view = bsdf.view;
    if (fuzz_weight > 0.0f)
    {
        bsdf.fuzz_basis = openpbr_make_basis(mix(bsdf.basis.normal, bsdf.coat_basis.normal, coat_weight));
        bsdf.fuzz_view = openpbr_to_local(bsdf.fuzz_basis, bsdf.view_world);
        bsdf.fuzz_view = openpbr_floor_view_cosine(bsdf.fuzz_view);
    }
    const vec3 view = bsdf.view;
    const float mu = view.z;
    // The interior medium exists only where light can enter (the volume helper returns an empty
    // one otherwise too; the branch skips its set-up for opaque and thin-walled materials).
    bsdf.volume = (entering_weight > 0.0f && !thin_walled) ? openpbr_make_volume(inputs) : openpbr_make_empty_volume();
    bsdf.emission = vec3(0.0f);
    bsdf.pass_through_weight = vec3(1.0f - opacity);

    // ---- IORs (spec "Base Substrate", "Coat" total internal reflection fix) ----
    // Every interface sees a relative IOR: the coat against the exterior medium, the base
    // against the exterior (uncoated) or the coat (spec "Coat": the base's relative IOR under
    // the coat, inverted where the coat is the denser medium), blended by coat_weight.
    const float coat_eta = openpbr_relative_ior(inputs.coat_ior, exterior_ior);
    const float base_eta = openpbr_relative_ior(inputs.specular_ior, exterior_ior);
    const float base_over_coat = inputs.coat_ior > inputs.specular_ior ? inputs.coat_ior / inputs.specular_ior
                                                                       : inputs.specular_ior / inputs.coat_ior;
    const float eta_base = openpbr_modulated_ior(coat_weight > 0.0f ? mix(base_eta, base_over_coat, coat_weight) : base_eta,
                                                 inputs.specular_weight);
    const vec3 eta_channels = openpbr_dispersive_ior(eta_base, inputs.transmission_dispersion_abbe_number,
                                                     thin_walled ? 0.0f : inputs.transmission_dispersion_scale,
                                                     rgb_wavelengths_nm);

    // ---- Roughness: the coat roughens the base (spec "Coat", roughening) ----
    const float coat_roughness = inputs.coat_roughness;
    const float base_roughness =
        coat_weight > 0.0f
            ? mix(inputs.specular_roughness,
                  pow(min(1.0f, pow(inputs.specular_roughness, 4.0f) + 2.0f * pow(coat_roughness, 4.0f)), 0.25f), coat_weight)
            : inputs.specular_roughness;
    const vec2 alpha = openpbr_ggx_alpha(base_roughness, inputs.specular_roughness_anisotropy);
    const OpenPBR_GgxLobeAlbedo base_lobe_albedo =
        openpbr_ggx_lobe_albedo(base_roughness, inputs.specular_roughness_anisotropy, alpha, view);
    const float table_alpha = base_lobe_albedo.table_alpha;

    bsdf.probability_fuzz = 0.0f;
    bsdf.probability_coat = 0.0f;
    bsdf.probability_specular = 0.0f;
    bsdf.probability_metal = 0.0f;
    bsdf.probability_diffuse = 0.0f;
    bsdf.probability_diffuse_transmission = 0.0f;
    bsdf.probability_transmission = 0.0f;
    bsdf.probability_thin_transmission = 0.0f;
    bsdf.probability_pass_through = 0.0f;
    bsdf.under_coat_constant = vec3(1.0f);
    bsdf.under_coat_absorbing = vec3(0.0f);
    bsdf.coat_half_log_color = vec3(0.0f);
    bsdf.coat_absorbs = false;
    bsdf.coat_inverse_eta_squared = 1.0f / (coat_eta * coat_eta);
    bsdf.under_coat_transmitted = vec3(1.0f);
    const vec3 zero = vec3(0.0f);
    const OpenPBR_Fresnel no_fresnel = openpbr_make_constant_fresnel(vec3(1.0f));
    // Empty lobes: every argument is a constant, so these fold to stores of constants.
    const vec3 normal_view = vec3(0.0f, 0.0f, 1.0f);
    bsdf.fuzz = openpbr_fuzz_lobe_empty();
    bsdf.coat = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_COAT);
    bsdf.specular = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_SPECULAR_REFLECTION);
    bsdf.metal = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_METAL);
    bsdf.thin_transmission = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION);
    bsdf.diffuse = openpbr_diffuse_lobe_empty(1.0f);
    bsdf.diffuse_transmission = openpbr_diffuse_lobe_empty(-1.0f);
    bsdf.transmission = openpbr_dielectric_lobe_init(zero, zero, vec2(1.0f), vec3(1.0f), false,
                                                     OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, normal_view);

    if (bsdf.inside)
    {
        // Inside: the dielectric interface seen from the denser side (eta inverted), with
        // Fresnel, total internal reflection and energy compensation 1 / E_RT. Light leaving
        // crosses the coat once and the fuzz (approximated as view-independent factors).
        const vec3 eta_inside = vec3(1.0f) / eta_channels;
        const float compensation =
            openpbr_ggx_is_delta(alpha) ? 1.0f
                                        : 1.0f / max(openpbr_dielectric_interface_albedo(mu, table_alpha, eta_inside.y), 0.05f);
        const vec3 exit_factor =
            (coat_weight > 0.0f ? mix(vec3(1.0f), sqrt(inputs.coat_color), coat_weight) : vec3(1.0f)) *
            (fuzz_weight > 0.0f ? 1.0f - fuzz_weight * openpbr_fuzz_albedo_white(1.0f, inputs.fuzz_roughness) : 1.0f);
        const float weight = opacity * compensation;
        bsdf.transmission = openpbr_dielectric_lobe_init(vec3(weight), exit_factor * weight, alpha, eta_inside, true,
                                                         OPENPBR_LOBE_ID_INTERFACE_FROM_INSIDE, view);
        const float total = opacity + (1.0f - opacity);
        bsdf.probability_transmission = opacity / total;
        bsdf.probability_pass_through = (1.0f - opacity) / total;
        return bsdf;
    }

    // ---- Fuzz (spec "Fuzz"): F f_fuzz + (1 - F E_fuzz) f_coated ----
    float under_fuzz = opacity;
    if (fuzz_weight > 0.0f)
    {
        const float fuzz_albedo_white = openpbr_fuzz_albedo_white(bsdf.fuzz_view.z, inputs.fuzz_roughness);
        bsdf.fuzz = openpbr_fuzz_lobe_init(vec3(opacity * fuzz_weight), inputs.fuzz_color, inputs.fuzz_roughness, bsdf.fuzz_view);
        under_fuzz = opacity * (1.0f - fuzz_weight * fuzz_albedo_white);
    }

    // ---- Coat (spec "Coat"): C f_coat + lerp(1, T_coat (1 - E_coat), C) darkening f_base ----
    const float coat_mu = bsdf.coat_view.z;
    float coat_albedo = 0.0f;
    vec3 coat_view_transmittance = vec3(1.0f);
    if (coat_weight > 0.0f)
    {
        const vec2 coat_alpha = openpbr_ggx_alpha(coat_roughness, inputs.coat_roughness_anisotropy);
        const OpenPBR_GgxLobeAlbedo coat_lobe_albedo =
            openpbr_ggx_lobe_albedo(coat_roughness, inputs.coat_roughness_anisotropy, coat_alpha, bsdf.coat_view);
        const OpenPBR_Fresnel coat_fresnel = openpbr_make_dielectric_fresnel(coat_eta, vec3(1.0f));
        const vec3 coat_compensation =
            openpbr_multiple_scattering_compensation(vec3(openpbr_dielectric_f0(coat_eta)), coat_lobe_albedo.albedo);
        bsdf.coat = openpbr_microfacet_reflection_lobe_init(coat_compensation * (under_fuzz * coat_weight), coat_alpha,
                                                            coat_fresnel, OPENPBR_LOBE_ID_COAT, 1.0f, bsdf.coat_view);
        const float coat_single_albedo =
            bsdf.coat.is_delta ? openpbr_fresnel_dielectric(coat_mu, coat_eta)
                               : openpbr_dielectric_reflection_albedo(coat_mu, coat_lobe_albedo.reflection_alpha, coat_eta) *
                                     coat_lobe_albedo.reflection_scale;
        coat_albedo = min(coat_single_albedo * coat_compensation.x, 1.0f);
        bsdf.coat_absorbs = !(inputs.coat_color.x == 1.0f && inputs.coat_color.y == 1.0f && inputs.coat_color.z == 1.0f);
        if (bsdf.coat_absorbs)
        {
            bsdf.coat_half_log_color = 0.5f * log(max(inputs.coat_color, vec3(1e-6f)));
            coat_view_transmittance =
                openpbr_coat_transmittance(bsdf.coat_half_log_color, bsdf.coat_inverse_eta_squared, coat_mu);
        }
    }

    // ---- Base substrate, with unit layering factor first (albedos feed darkening) ----
    // Dielectric specular reflection, tinted by specular_color (reflection from above only).
    // Thin film on the base (spec "Thin-film iridescence"): over the metal and the dielectric,
    // under the coat; the medium above it is the coat where there is one (IOR blended by
    // coat_weight, the spec's "depending on coat coverage"), otherwise the exterior medium.
    // Absolute IORs: the film's Fresnel model reads n_outside, n_film and n_base themselves.
    const float film_weight = inputs.thin_film_weight;
    const float film_outside_ior = coat_weight > 0.0f ? mix(exterior_ior, inputs.coat_ior, coat_weight) : exterior_ior;
    const float dielectric_weight = 1.0f - metalness;
    vec3 specular_albedo = vec3(0.0f);
    if (dielectric_weight > 0.0f)
    {
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
            openpbr_ggx_is_delta(alpha)
                ? openpbr_fresnel_dielectric(mu, eta_channels.y)
                : openpbr_dielectric_reflection_albedo(mu, base_lobe_albedo.reflection_alpha, eta_channels.y) *
                      base_lobe_albedo.reflection_scale;
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
        specular_albedo = openpbr_saturate(inputs.specular_color * specular_compensation * reflection_albedo);
        bsdf.specular = openpbr_microfacet_reflection_lobe_init(specular_compensation * dielectric_weight, alpha,
                                                                dielectric_fresnel, OPENPBR_LOBE_ID_SPECULAR_REFLECTION,
                                                                1.0f, view);
    }
    const vec3 under_specular = vec3(1.0f) - specular_albedo;

    // What passes the specular interface splits into translucent, subsurface and diffuse.
    const float translucent = inputs.transmission_weight;
    const float subsurface = (1.0f - translucent) * inputs.subsurface_weight;
    const float diffuse_fraction = (1.0f - translucent) * (1.0f - inputs.subsurface_weight);
    vec3 diffuse_weight = under_specular * (dielectric_weight * diffuse_fraction * inputs.base_weight);
    vec3 diffuse_color = inputs.base_color;
    vec3 transmission_weight = vec3(0.0f);
    vec3 thin_transmission_weight = vec3(0.0f);
    // The albedo the coat's darkening sees of the slabs light enters (spec "Coat", darkening:
    // E_b is "the albedos of the base slabs blended by their weights"): the subsurface slab
    // returns subsurface_color (spec "Subsurface": its multiple-scattering albedo), the
    // translucent slab its tint. The lobe itself refracts untinted; the medium applies the color.
    vec3 entering_slab_albedo = vec3(0.0f);
    const float entering = dielectric_weight * (translucent + subsurface);
    if (thin_walled && entering > 0.0f)
    {
        // Thin-walled (spec "Thin-walled case"): subsurface becomes a thin scattering sheet,
        // reflection 1/2 S (1 - g), transmission 1/2 S (1 + g), both diffuse lobes; the
        // translucent base becomes an un-deflected transmission tinted by transmission_color.
        if (subsurface > 0.0f)
        {
            const float g = inputs.subsurface_scatter_anisotropy;
            const vec3 sheet = under_specular * (dielectric_weight * subsurface);
            diffuse_color = (diffuse_weight * inputs.base_color + sheet * (0.5f * (1.0f - g)) * inputs.subsurface_color) /
                            max(diffuse_weight + sheet * (0.5f * (1.0f - g)), vec3(1e-12f));
            diffuse_weight = diffuse_weight + sheet * (0.5f * (1.0f - g));
            bsdf.diffuse_transmission = openpbr_diffuse_lobe_init(sheet * (0.5f * (1.0f + g)), inputs.subsurface_color,
                                                                  inputs.base_diffuse_roughness, -1.0f, view);
        }
        if (translucent > 0.0f)
        {
            thin_transmission_weight = under_specular * (dielectric_weight * translucent) * inputs.transmission_color;
            const float thin_compensation = 1.0f / max(base_lobe_albedo.albedo, 0.05f);
            bsdf.thin_transmission =
                openpbr_microfacet_reflection_lobe_init(thin_transmission_weight * thin_compensation, alpha, no_fresnel,
                                                        OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, -1.0f, view);
        }
    }
    else if (entering > 0.0f)
    {
        // Refraction into the interior: translucent (tinted by transmission_color when there
        // is no medium, spec "Translucent base") and subsurface (the medium does the rest).
        const vec3 translucent_tint = inputs.transmission_depth > 0.0f ? vec3(1.0f) : inputs.transmission_color;
        transmission_weight = under_specular * dielectric_weight * (translucent * translucent_tint + vec3(subsurface));
        entering_slab_albedo =
            under_specular * dielectric_weight * (translucent * translucent_tint + subsurface * inputs.subsurface_color);
        // A delta lobe refracts exactly 1 - F: no compensation (the table near alpha = 0 smears
        // the step at the critical angle when eta < 1 and gained up to 115 % there).
        const float transmission_compensation =
            openpbr_ggx_is_delta(alpha) ? 1.0f
                                        : 1.0f / max(openpbr_dielectric_transmission_albedo(mu, table_alpha, eta_channels.y), OPENPBR_MIN_TRANSMISSION_ALBEDO);
        bsdf.transmission = openpbr_dielectric_lobe_init(zero, transmission_weight * transmission_compensation, alpha,
                                                         eta_channels, false, OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, view);
    }
    if (max(diffuse_weight.x, max(diffuse_weight.y, diffuse_weight.z)) > 0.0f)
    {
        bsdf.diffuse = openpbr_diffuse_lobe_init(diffuse_weight, diffuse_color, inputs.base_diffuse_roughness, 1.0f, view);
    }

    // Metal: F82-tint Fresnel, F0 = base_weight base_color, scaled by specular_weight.
    vec3 metal_albedo = vec3(0.0f);
    if (metalness > 0.0f)
    {
        const vec3 metal_f0 = inputs.base_weight * inputs.base_color;
        OpenPBR_Fresnel metal_fresnel =
            openpbr_make_f82_fresnel(metal_f0, inputs.specular_color, vec3(min(inputs.specular_weight, 1.0f)));
        if (film_weight > 0.0f)
        {
            metal_fresnel = openpbr_add_thin_film(metal_fresnel, film_weight, inputs.thin_film_thickness,
                                                  inputs.thin_film_ior, film_outside_ior);
        }
        const vec3 metal_compensation = openpbr_multiple_scattering_compensation(metal_f0, base_lobe_albedo.albedo);
        bsdf.metal = openpbr_microfacet_reflection_lobe_init(metal_compensation * metalness, alpha, metal_fresnel,
                                                             OPENPBR_LOBE_ID_METAL, 1.0f, view);
        metal_albedo = openpbr_saturate(metal_compensation * openpbr_fresnel_evaluate(metal_fresnel, mu) *
                                        (bsdf.metal.is_delta ? 1.0f : base_lobe_albedo.albedo)) *
                       metalness;
    }

    // Albedo estimates of the base lobes (unit layering factor).
    const vec3 specular_estimate = specular_albedo * dielectric_weight;
    const vec3 diffuse_estimate = bsdf.diffuse.albedo;
    const vec3 diffuse_transmission_estimate = bsdf.diffuse_transmission.albedo;
    const vec3 transmission_estimate = transmission_weight;
    const vec3 thin_transmission_estimate = thin_transmission_weight;

    // Darkening (spec "Coat", darkening): lerp(1, Delta, C delta), Delta = (1 - K)/(1 - E_b K),
    // K = lerp(K_s, K_r, r_b); E_b the albedo of the whole base, its slabs blended by their mix
    // weights (spec: translucent and subsurface slabs included, so a white glass base under a
    // white coat is not darkened and passes the white furnace), taken at the view rather than
    // only at normal incidence (a documented approximation). No coat: no darkening.
    vec3 darkening = vec3(1.0f);
    if (coat_weight > 0.0f)
    {
        const vec3 base_albedo =
            openpbr_saturate(specular_estimate + diffuse_estimate + metal_albedo + diffuse_transmission_estimate +
                             entering_slab_albedo + thin_transmission_estimate);
        const float k_specular = openpbr_fresnel_dielectric(coat_mu, coat_eta);
        const float k_rough = 1.0f - (1.0f - openpbr_average_fresnel(coat_eta)) * bsdf.coat_inverse_eta_squared;
        const float specular_f0 = openpbr_dielectric_f0(eta_base);
        const float base_surface_roughness =
            mix(mix(1.0f, inputs.specular_roughness, min(specular_f0 * inputs.specular_weight, 1.0f)), inputs.specular_roughness,
                metalness);
        const float k = mix(k_specular, k_rough, base_surface_roughness);
        const vec3 delta = vec3(1.0f - k) / max(vec3(1.0f) - base_albedo * k, vec3(1e-6f));
        darkening = mix(vec3(1.0f), delta, coat_weight * inputs.coat_darkening);
    }

    // Layering factors on every base lobe: fuzz and opacity, coat absorption and darkening.
    bsdf.under_coat_constant = darkening * (under_fuzz * (1.0f - coat_weight));
    bsdf.under_coat_absorbing = darkening * (under_fuzz * coat_weight * (1.0f - coat_albedo)) * coat_view_transmittance;
    bsdf.under_coat_transmitted = bsdf.under_coat_constant + bsdf.under_coat_absorbing;
    // Estimate for selection: the light-side transmittance taken equal to the view side's.
    const vec3 under_reflected = bsdf.under_coat_constant + bsdf.under_coat_absorbing * coat_view_transmittance;

    // Selection probability proportional to each lobe's estimated albedo (luminance), weighted
    // by the path's channel weights; the probabilities only steer sampling, so estimates need
    // not be exact.
    const vec3 channel = openpbr_selection_channel_weights(path_throughput);
    const float white = openpbr_selection_white_scale(channel);
    const float fuzz_p =
        fuzz_weight > 0.0f ? openpbr_luminance(openpbr_fuzz_lobe_albedo(bsdf.fuzz, bsdf.fuzz_view) * channel) : 0.0f;
    const float coat_p = coat_weight > 0.0f ? under_fuzz * coat_weight * coat_albedo * white : 0.0f;
    const float specular_p = dielectric_weight > 0.0f ? openpbr_luminance(specular_estimate * under_reflected * channel) : 0.0f;
    const float metal_p = metalness > 0.0f ? openpbr_luminance(metal_albedo * under_reflected * channel) : 0.0f;
    const float diffuse_p = openpbr_luminance(diffuse_estimate * under_reflected * channel);
    const float diffuse_transmission_p =
        openpbr_luminance(diffuse_transmission_estimate * bsdf.under_coat_transmitted * channel);
    const float transmission_p = openpbr_luminance(transmission_estimate * bsdf.under_coat_transmitted * channel);
    const float thin_transmission_p = openpbr_luminance(thin_transmission_estimate * bsdf.under_coat_transmitted * channel);
    const float pass_through_p = (1.0f - opacity) * white;
    const float raw_total = fuzz_p + coat_p + specular_p + metal_p + diffuse_p + diffuse_transmission_p + transmission_p +
                            thin_transmission_p + pass_through_p;
    // Negligible lobes are dropped: probability 0, so eval, pdf and sample skip them alike.
    const float cut = OPENPBR_MIN_LOBE_PROBABILITY * raw_total;
    const float fuzz_kept = openpbr_kept_probability(fuzz_p, cut);
    const float coat_kept = openpbr_kept_probability(coat_p, cut);
    const float specular_kept = openpbr_kept_probability(specular_p, cut);
    const float metal_kept = openpbr_kept_probability(metal_p, cut);
    const float diffuse_kept = openpbr_kept_probability(diffuse_p, cut);
    const float diffuse_transmission_kept = openpbr_kept_probability(diffuse_transmission_p, cut);
    const float transmission_kept = openpbr_kept_probability(transmission_p, cut);
    const float thin_transmission_kept = openpbr_kept_probability(thin_transmission_p, cut);
    const float pass_through_kept = openpbr_kept_probability(pass_through_p, cut);
    const float total = fuzz_kept + coat_kept + specular_kept + metal_kept + diffuse_kept + diffuse_transmission_kept +
                        transmission_kept + thin_transmission_kept + pass_through_kept;
    // A denormal total (e.g. a metal of color 1e-40) would overflow 1 / total to infinity; below
    // the smallest normal float nothing is sampled (GPUs flush such values to 0 anyway).
    const float inverse_total = total >= OPENPBR_FLOAT_MIN_NORMAL ? 1.0f / total : 0.0f;
    bsdf.probability_fuzz = fuzz_kept * inverse_total;
    bsdf.probability_coat = coat_kept * inverse_total;
    bsdf.probability_specular = specular_kept * inverse_total;
    bsdf.probability_metal = metal_kept * inverse_total;
    bsdf.probability_diffuse = diffuse_kept * inverse_total;
    bsdf.probability_diffuse_transmission = diffuse_transmission_kept * inverse_total;
    bsdf.probability_transmission = transmission_kept * inverse_total;
    bsdf.probability_thin_transmission = thin_transmission_kept * inverse_total;
    bsdf.probability_pass_through = pass_through_kept * inverse_total;
    return bsdf;
}

// Emission (spec "Emission"): emission_luminance x emission_color in nits, under the coat:
// lerp(1, T_coat, C) with T_coat one pass through the coat towards the view; zero when seen
// from inside a non-thin-walled object (the emitting surface faces outwards).
// `inputs` have passed openpbr_prepare_inputs.
OPENPBR_FUNC vec3 openpbr_prepare_emission_of(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world,
                                              float exterior_ior)
{
    if (!(inputs.emission_luminance > 0.0f))
    {
        return vec3(0.0f);
    }
    const vec3 view = openpbr_safe_normalize(view_world, inputs.geometry_basis.normal);
    const float cos_base = dot(view, inputs.geometry_basis.normal);
    if (cos_base < 0.0f && !inputs.geometry_thin_walled)
    {
        return vec3(0.0f);
    }
    vec3 attenuation = vec3(1.0f);
    if (inputs.coat_weight > 0.0f)
    {
        const float coat_mu = min(abs(dot(view, inputs.geometry_coat_basis.normal)), 1.0f);
        const vec3 half_log_color = 0.5f * log(max(inputs.coat_color, vec3(1e-6f)));
        const float coat_eta = openpbr_relative_ior(inputs.coat_ior, exterior_ior);
        const vec3 coat_transmittance = openpbr_coat_transmittance(half_log_color, 1.0f / (coat_eta * coat_eta), coat_mu);
        attenuation = mix(vec3(1.0f), coat_transmittance, inputs.coat_weight);
    }
    return inputs.emission_color * inputs.emission_luminance * attenuation * inputs.geometry_opacity;
}

// Staged and full forms. exterior_ior (default 1, air) is the absolute IOR of the medium the
// view is in, e.g. 1.33 for an object under water; the shorter forms pass 1.
OPENPBR_FUNC vec3 openpbr_prepare_emission(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs, vec3 view_world, float exterior_ior)
{
    return openpbr_prepare_emission_of(openpbr_prepare_inputs(raw_inputs), view_world,
                                       openpbr_contract_exterior_ior(exterior_ior));
}

OPENPBR_FUNC vec3 openpbr_prepare_emission(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs, vec3 view_world)
{
    return openpbr_prepare_emission(raw_inputs, view_world, 1.0f);
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare_lobes(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs, vec3 view_world,
                                                        vec3 rgb_wavelengths_nm, float exterior_ior)
{
    return openpbr_prepare_lobes_of(openpbr_prepare_inputs(raw_inputs), view_world, rgb_wavelengths_nm,
                                    openpbr_contract_exterior_ior(exterior_ior), vec3(1.0f));
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare_lobes(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs, vec3 view_world,
                                                        vec3 rgb_wavelengths_nm)
{
    return openpbr_prepare_lobes(raw_inputs, view_world, rgb_wavelengths_nm, 1.0f);
}

OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_prepare_volume(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs)
{
    return openpbr_make_volume(openpbr_prepare_inputs(raw_inputs));
}

// The whole preparation with lobe selection steered by the path's throughput (see
// openpbr_selection_channel_weights; results stay unbiased): what the established-API
// openpbr_prepare(inputs, path_throughput, ...) runs. vec3(1.0f) is openpbr_prepare.
OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare_for_path(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world,
                                                           vec3 rgb_wavelengths_nm, float exterior_ior,
                                                           vec3 path_throughput)
{
    // The input contract and the toggles run once, for the lobes and the emission.
    const OpenPBR_ResolvedInputs prepared_inputs = openpbr_prepare_inputs(inputs);
    const float exterior = openpbr_contract_exterior_ior(exterior_ior);
    OpenPBR_PreparedBsdf bsdf =
        openpbr_prepare_lobes_of(prepared_inputs, view_world, rgb_wavelengths_nm, exterior, path_throughput);
    bsdf.emission = openpbr_prepare_emission_of(prepared_inputs, view_world, exterior);
    return bsdf;
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world,
                                                  vec3 rgb_wavelengths_nm, float exterior_ior)
{
    return openpbr_prepare_for_path(inputs, view_world, rgb_wavelengths_nm, exterior_ior, vec3(1.0f));
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world,
                                                  vec3 rgb_wavelengths_nm)
{
    return openpbr_prepare(inputs, view_world, rgb_wavelengths_nm, 1.0f);
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world)
{
    return openpbr_prepare(inputs, view_world, OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM, 1.0f);
}

// Sum of the continuous lobes at one world-space light direction, split diffuse / specular.
OPENPBR_FUNC OpenPBR_DiffuseSpecular openpbr_eval(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 light_world)
{
    OpenPBR_DiffuseSpecular value;
    value.diffuse = vec3(0.0f);
    value.specular = vec3(0.0f);
    const vec3 light = openpbr_to_local(bsdf.basis, light_world);
    // Each lobe test starts with its feature toggle: a constant in a specialized build, where
    // the lobe's code then disappears from eval (the probabilities are only known at run time).
    if ((OPENPBR_FEATURE_TRANSMISSION || OPENPBR_FEATURE_SUBSURFACE) && bsdf.inside)
    {
        if (bsdf.probability_transmission > 0.0f)
        {
            value.specular = openpbr_dielectric_lobe_eval(bsdf.transmission, bsdf.view, light);
        }
        return value;
    }
    if (OPENPBR_FEATURE_FUZZ && bsdf.probability_fuzz > 0.0f)
    {
        value.specular = openpbr_fuzz_lobe_eval(bsdf.fuzz, bsdf.fuzz_view, openpbr_to_local(bsdf.fuzz_basis, light_world));
    }
    if (OPENPBR_FEATURE_COAT && bsdf.probability_coat > 0.0f)
    {
        value.specular = value.specular + openpbr_microfacet_reflection_lobe_eval(bsdf.coat, bsdf.coat_view,
                                                                                  openpbr_to_local(bsdf.coat_basis, light_world));
    }
    vec3 diffuse = vec3(0.0f);
    vec3 specular = vec3(0.0f);
    if (light.z >= 0.0f)
    {
        if (bsdf.probability_specular > 0.0f)
        {
            specular = specular + openpbr_microfacet_reflection_lobe_eval(bsdf.specular, bsdf.view, light);
        }
        if (OPENPBR_FEATURE_METAL && bsdf.probability_metal > 0.0f)
        {
            specular = specular + openpbr_microfacet_reflection_lobe_eval(bsdf.metal, bsdf.view, light);
        }
        if (bsdf.probability_diffuse > 0.0f)
        {
            diffuse = openpbr_diffuse_lobe_eval(bsdf.diffuse, bsdf.view, light);
        }
        // The coat's absorption towards the light: its exp only where the coat absorbs.
        vec3 factor = bsdf.under_coat_transmitted;
        if (OPENPBR_FEATURE_COAT && bsdf.coat_absorbs)
        {
            const float coat_mu = max(dot(light_world, bsdf.coat_basis.normal), 0.0f);
            factor = bsdf.under_coat_constant +
                     bsdf.under_coat_absorbing *
                         openpbr_coat_transmittance(bsdf.coat_half_log_color, bsdf.coat_inverse_eta_squared, coat_mu);
        }
        value.diffuse = diffuse * factor;
        value.specular = value.specular + specular * factor;
        return value;
    }
    if ((OPENPBR_FEATURE_TRANSMISSION || OPENPBR_FEATURE_SUBSURFACE) && bsdf.probability_transmission > 0.0f)
    {
        specular = openpbr_dielectric_lobe_eval(bsdf.transmission, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_TRANSMISSION && bsdf.probability_thin_transmission > 0.0f)
    {
        specular = specular + openpbr_microfacet_reflection_lobe_eval(bsdf.thin_transmission, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_SUBSURFACE && bsdf.probability_diffuse_transmission > 0.0f)
    {
        diffuse = openpbr_diffuse_lobe_eval(bsdf.diffuse_transmission, bsdf.view, light);
    }
    value.diffuse = diffuse * bsdf.under_coat_transmitted;
    value.specular = value.specular + specular * bsdf.under_coat_transmitted;
    return value;
}

OPENPBR_FUNC float openpbr_pdf(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 light_world)
{
    const vec3 light = openpbr_to_local(bsdf.basis, light_world);
    float pdf = 0.0f;
    if ((OPENPBR_FEATURE_TRANSMISSION || OPENPBR_FEATURE_SUBSURFACE) && bsdf.probability_transmission > 0.0f)
    {
        pdf += bsdf.probability_transmission * openpbr_dielectric_lobe_pdf(bsdf.transmission, bsdf.view, light);
    }
    if (bsdf.inside)
    {
        return pdf;
    }
    if (OPENPBR_FEATURE_FUZZ && bsdf.probability_fuzz > 0.0f)
    {
        pdf += bsdf.probability_fuzz *
               openpbr_fuzz_lobe_pdf(bsdf.fuzz, bsdf.fuzz_view, openpbr_to_local(bsdf.fuzz_basis, light_world));
    }
    if (OPENPBR_FEATURE_COAT && bsdf.probability_coat > 0.0f)
    {
        pdf += bsdf.probability_coat * openpbr_microfacet_reflection_lobe_pdf(bsdf.coat, bsdf.coat_view,
                                                                              openpbr_to_local(bsdf.coat_basis, light_world));
    }
    if (bsdf.probability_specular > 0.0f)
    {
        pdf += bsdf.probability_specular * openpbr_microfacet_reflection_lobe_pdf(bsdf.specular, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_METAL && bsdf.probability_metal > 0.0f)
    {
        pdf += bsdf.probability_metal * openpbr_microfacet_reflection_lobe_pdf(bsdf.metal, bsdf.view, light);
    }
    if (bsdf.probability_diffuse > 0.0f)
    {
        pdf += bsdf.probability_diffuse * openpbr_diffuse_lobe_pdf(bsdf.diffuse, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_SUBSURFACE && bsdf.probability_diffuse_transmission > 0.0f)
    {
        pdf += bsdf.probability_diffuse_transmission * openpbr_diffuse_lobe_pdf(bsdf.diffuse_transmission, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_TRANSMISSION && bsdf.probability_thin_transmission > 0.0f)
    {
        pdf += bsdf.probability_thin_transmission *
               openpbr_microfacet_reflection_lobe_pdf(bsdf.thin_transmission, bsdf.view, light);
    }
    return pdf;
}

OPENPBR_FUNC OpenPBR_BsdfSample openpbr_make_no_sample()
{
    OpenPBR_BsdfSample bsdf_sample;
    bsdf_sample.direction = vec3(0.0f);
    bsdf_sample.weight.diffuse = vec3(0.0f);
    bsdf_sample.weight.specular = vec3(0.0f);
    bsdf_sample.pdf = 0.0f;
    bsdf_sample.lobe_type = OPENPBR_LOBE_TYPE_NONE;
    return bsdf_sample;
}

// u: three uniform numbers in [0, 1); u.z selects the lobe (its remainder drives choices
// inside the lobe), (u.x, u.y) drive the lobe's warp.
OPENPBR_FUNC OpenPBR_BsdfSample openpbr_sample(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 u)
{
    const vec2 u_direction = vec2(u.x, u.y);
    float selector = u.z;
    float probability = 0.0f;
    OpenPBR_LobeSample lobe_sample = openpbr_make_no_lobe_sample();
    OpenPBR_Basis frame = bsdf.basis;
    vec3 delta_factor = bsdf.under_coat_transmitted;  // layering factor of a delta base lobe
    if (selector < bsdf.probability_transmission)
    {
        lobe_sample = openpbr_dielectric_lobe_sample(bsdf.transmission, bsdf.view, u_direction,
                                                     selector / bsdf.probability_transmission);
        probability = bsdf.probability_transmission;
        delta_factor = bsdf.inside ? vec3(1.0f) : bsdf.under_coat_transmitted;
    }
    else if ((selector -= bsdf.probability_transmission) < bsdf.probability_fuzz)
    {
        lobe_sample = openpbr_fuzz_lobe_sample(bsdf.fuzz, bsdf.fuzz_view, u_direction);
        probability = bsdf.probability_fuzz;
        frame = bsdf.fuzz_basis;
    }
    else if ((selector -= bsdf.probability_fuzz) < bsdf.probability_coat)
    {
        lobe_sample = openpbr_microfacet_reflection_lobe_sample(bsdf.coat, bsdf.coat_view, u_direction);
        probability = bsdf.probability_coat;
        frame = bsdf.coat_basis;
        delta_factor = vec3(1.0f);
    }
    else if ((selector -= bsdf.probability_coat) < bsdf.probability_specular)
    {
        lobe_sample = openpbr_microfacet_reflection_lobe_sample(bsdf.specular, bsdf.view, u_direction);
        probability = bsdf.probability_specular;
    }
    else if ((selector -= bsdf.probability_specular) < bsdf.probability_metal)
    {
        lobe_sample = openpbr_microfacet_reflection_lobe_sample(bsdf.metal, bsdf.view, u_direction);
        probability = bsdf.probability_metal;
    }
    else if ((selector -= bsdf.probability_metal) < bsdf.probability_diffuse)
    {
        lobe_sample = openpbr_diffuse_lobe_sample(bsdf.diffuse, bsdf.view, u_direction);
        probability = bsdf.probability_diffuse;
    }
    else if ((selector -= bsdf.probability_diffuse) < bsdf.probability_diffuse_transmission)
    {
        lobe_sample = openpbr_diffuse_lobe_sample(bsdf.diffuse_transmission, bsdf.view, u_direction);
        probability = bsdf.probability_diffuse_transmission;
    }
    else if ((selector -= bsdf.probability_diffuse_transmission) < bsdf.probability_thin_transmission)
    {
        lobe_sample = openpbr_microfacet_reflection_lobe_sample(bsdf.thin_transmission, bsdf.view, u_direction);
        probability = bsdf.probability_thin_transmission;
    }
    else if (bsdf.probability_pass_through > 0.0f)
    {
        // Straight on from the unfloored view (bsdf.view may be raised to the tables' floor).
        lobe_sample = openpbr_make_lobe_sample(-openpbr_to_local(bsdf.basis, bsdf.view_world),
                                               openpbr_lobe_type(OPENPBR_LOBE_ID_PASS_THROUGH,
                                                                 OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_SPECULAR));
        lobe_sample.delta_weight = bsdf.pass_through_weight;
        probability = bsdf.probability_pass_through;
        delta_factor = vec3(1.0f);
    }
    // A selection probability below the smallest normal float (e.g. 1e-40 with u.z = 0) would
    // overflow the estimator 1 / probability: no sample, as for probability 0.
    if (lobe_sample.lobe_type == OPENPBR_LOBE_TYPE_NONE || !(probability >= OPENPBR_FLOAT_MIN_NORMAL))
    {
        return openpbr_make_no_sample();
    }
    OpenPBR_BsdfSample bsdf_sample;
    bsdf_sample.direction = openpbr_to_world(frame, lobe_sample.direction);
    bsdf_sample.lobe_type = lobe_sample.lobe_type;
    if ((lobe_sample.lobe_type & OPENPBR_LOBE_TYPE_SPECULAR) != 0u)
    {
        // Delta lobe: the estimator is value / P(selecting the lobe). A reflecting delta under
        // the coat sees the coat's absorption along the mirrored direction.
        vec3 factor = delta_factor;
        if (OPENPBR_FEATURE_COAT && bsdf.coat_absorbs && !bsdf.inside &&
            (lobe_sample.lobe_type & OPENPBR_LOBE_TYPE_REFLECTION) != 0u &&
            (lobe_sample.lobe_type >> OPENPBR_LOBE_ID_SHIFT) != OPENPBR_LOBE_ID_COAT)
        {
            const float coat_mu = max(dot(bsdf_sample.direction, bsdf.coat_basis.normal), 0.0f);
            factor = bsdf.under_coat_constant +
                     bsdf.under_coat_absorbing *
                         openpbr_coat_transmittance(bsdf.coat_half_log_color, bsdf.coat_inverse_eta_squared, coat_mu);
        }
        bsdf_sample.pdf = probability;
        bsdf_sample.weight.diffuse = vec3(0.0f);
        bsdf_sample.weight.specular = lobe_sample.delta_weight * factor / probability;
        return bsdf_sample;
    }
    // One-sample MIS over the continuous lobes: weight = f(wi) / sum_j P_j pdf_j(wi), so the
    // weight equals eval / pdf at the returned direction by construction.
    const float pdf = openpbr_pdf(bsdf, bsdf_sample.direction);
    if (!(pdf >= OPENPBR_FLOAT_MIN_NORMAL) || !(pdf <= OPENPBR_FLOAT_MAX))
    {
        return openpbr_make_no_sample();
    }
    const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, bsdf_sample.direction);
    const float inverse_pdf = 1.0f / pdf;
    bsdf_sample.pdf = pdf;
    bsdf_sample.weight.diffuse = value.diffuse * inverse_pdf;
    bsdf_sample.weight.specular = value.specular * inverse_pdf;
    return bsdf_sample;
}

OPENPBR_NAMESPACE_END

#endif
