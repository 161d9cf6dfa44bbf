// The OpenPBR 1.1.1 surface BSDF: prepare, eval, sample, pdf.
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
// per-light-direction work. Each lobe's set-up is its prepare in its file under slang/lobes/
// (the lobe shape: slang/lobes/openpbr_lobe_common.h); this file composes them.
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

struct OpenPBR_DiffuseSpecular OPENPBR_DIFFERENTIABLE
{
    vec3 diffuse;   // diffuse lobes (EON reflection and thin-walled diffuse transmission)
    vec3 specular;  // everything else (microfacet lobes, fuzz)
};

struct OpenPBR_BsdfSample OPENPBR_DIFFERENTIABLE
{
    vec3 direction;                  // world space
    OpenPBR_DiffuseSpecular weight;  // BSDF x |cos| / pdf, split like eval
    float pdf;                       // solid-angle pdf, or the discrete probability of a delta lobe
    OpenPBR_BsdfLobeType lobe_type;  // OPENPBR_LOBE_TYPE_NONE when pdf == 0
};

// Wavelengths (nm) the three channels stand for when the caller passes none: the dominant
// wavelengths of the working space's primaries (slang/openpbr_working_space.h; e.g.
// (611.4, 549.1, 464.2) for linear Rec.709, (628.8, 532.9, 467.2) for ACEScg), e.g. for
// dispersion in an RGB renderer.
#define OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM OPENPBR_WORKING_SPACE_DOMINANT_WAVELENGTHS_NM

// The same as a function, for callers that see the library through a module (Slang `import
// openpbr;` exports declarations, not macros), e.g. to pass an exterior IOR to openpbr_prepare.
OPENPBR_FUNC vec3 openpbr_default_rgb_wavelengths_nm() { return OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM; }

struct OpenPBR_PreparedBsdf OPENPBR_DIFFERENTIABLE
{
    OpenPBR_Basis basis;       // base shading frame, view side up (flipped for back faces)
    OpenPBR_Basis coat_basis;  // coat frame, same side as the base frame
    OpenPBR_Basis fuzz_basis;  // fuzz frame: base and coat normals blended by coat_weight
    vec3 view;                 // view in the base frame (z >= 0)
    vec3 coat_view;
    vec3 fuzz_view;
    vec3 view_world;
    bool inside;  // view from inside a non-thin-walled object: interface only

    OpenPBR_FuzzLobe fuzz;
    OpenPBR_MicrofacetReflectionLobe coat;
    OpenPBR_MicrofacetReflectionLobe specular;
    OpenPBR_MicrofacetReflectionLobe metal;
    OpenPBR_DiffuseLobe diffuse;
    OpenPBR_DiffuseLobe diffuse_transmission;            // thin-walled subsurface, mirrored below
    OpenPBR_DielectricLobe transmission;                 // entering refraction, or the interface from inside
    OpenPBR_MicrofacetReflectionLobe thin_transmission;  // thin-walled un-deflected transmission
    vec3 pass_through_weight;                            // (1 - geometry_opacity), delta straight through

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

    vec3 emission;                     // attenuated emission towards the view, nits
    OpenPBR_HomogeneousVolume volume;  // interior medium (is_present false when none)
};

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
// At eta = 1 (a coat of the exterior's IOR) the two arguments of the max meet: the derivative
// is eta's, the side the branch below takes there (max's at a tie would be half of each, and
// 1/eta's slope cancels eta's: 0).
OPENPBR_FUNC float openpbr_average_fresnel(float eta)
{
    const float e = openpbr_max_first_at_tie(eta, 1.0f / max(eta, 1e-3f));
    const float average = log((10893.0f * e - 1438.2f) / (-774.4f * e * e + 10212.0f * e + 1.0f));
    const float clamped = clamp(average, 0.0f, 1.0f);
    return eta >= 1.0f ? clamped : 1.0f - eta * eta * (1.0f - clamped);
}

// 1 where a dispersive IOR channel sits at an end of the IOR range and its offset from n_d
// (b (1/lambda^2 - 1/lambda_d^2), of the sign of (n_d - 1) (1/lambda^2 - 1/lambda_d^2)) points out
// of the range, e.g. the blue channel of n_d = 3 as the dispersion grows from 0; else 0.
OPENPBR_FUNC float openpbr_dispersion_leaves_range(float channel, float pushes)
{
    return ((channel >= OPENPBR_IOR_MAX && pushes > 0.0f) || (channel <= OPENPBR_IOR_MIN && pushes < 0.0f)) ? 1.0f : 0.0f;
}

// What a channel at an end of the IOR range whose offset from n_d points out of it loses: that
// offset's derivative (the offset minus itself detached: 0 in value).
OPENPBR_FUNC vec3 openpbr_dispersion_leaving(vec3 channels, float b, float ior_d, vec3 lambda)
{
    const vec3 direction = vec3(1.0f) / (lambda * lambda) - vec3(1.0f / (587.6f * 587.6f));
    const vec3 pushes = (ior_d - 1.0f) * direction;
    const vec3 leaves =
        vec3(openpbr_dispersion_leaves_range(channels.x, pushes.x), openpbr_dispersion_leaves_range(channels.y, pushes.y),
             openpbr_dispersion_leaves_range(channels.z, pushes.z));
    const vec3 offset = b * direction;
    return leaves * (offset - OPENPBR_DETACH(offset));
}

// The dispersive channels before the clamp to the IOR range; the differentiable build takes the
// same values, but a channel at an end of the range whose offset from n_d points out of it has
// that offset's derivative cut. The clamp holds such a channel at the end as the scale grows, so
// its one-sided derivative is that of n_d alone, where the clamp at its end would pass the
// offset's derivative too.
OPENPBR_FUNC vec3 openpbr_dispersion_inside_range(vec3 channels, float b, float ior_d, vec3 lambda)
{
    return channels - openpbr_dispersion_leaving(channels, b, ior_d, lambda);
}

// Dispersion (spec "Translucent base"): Cauchy n(lambda) = A + B / lambda^2 through n_d at the
// Fraunhofer d line with Abbe number V_d = abbe / scale (F 486.1 nm, d 587.6 nm, C 656.3 nm).
OPENPBR_FUNC vec3 openpbr_dispersive_ior(float ior_d, float abbe_number, float dispersion_scale, vec3 wavelengths_nm)
{
    if (!OPENPBR_WEIGHT_ACTIVE(dispersion_scale))
    {
        return vec3(ior_d);
    }
    const float inverse_f2 = 1.0f / (486.1f * 486.1f);
    const float inverse_c2 = 1.0f / (656.3f * 656.3f);
    // The differentiable build forms 1 / V_d = scale / abbe (the same value), whose derivative is
    // finite at scale 0 where abbe / scale's is not; at scale 1 and abbe OPENPBR_ABBE_MIN it meets
    // its cap, where the derivative is the one from inside the ranges (min's would be half).
    const float b =
        OPENPBR_AUTODIFF != 0
            ? (ior_d - 1.0f) * openpbr_min_first_at_tie(dispersion_scale / abbe_number, 1.0f / OPENPBR_ABBE_MIN) /
                  (inverse_f2 - inverse_c2)
            : (ior_d - 1.0f) / (max(abbe_number / dispersion_scale, OPENPBR_ABBE_MIN) * (inverse_f2 - inverse_c2));
    const float a = ior_d - b / (587.6f * 587.6f);
    // NaN or infinite wavelengths (caller input) map into the range too: NaN to 300 nm, so the
    // IOR and every table coordinate derived from it stay finite.
    const vec3 lambda = openpbr_clamp_finite(wavelengths_nm, 300.0f, 1000.0f);
    const vec3 channels = vec3(a) + b / (lambda * lambda);
    // The plain build calls nothing here (Slang's SPIR-V would keep the call).
    return clamp(OPENPBR_AUTODIFF != 0 ? openpbr_dispersion_inside_range(channels, b, ior_d, lambda) : channels,
                 vec3(OPENPBR_IOR_MIN), vec3(OPENPBR_IOR_MAX));
}

// The inputs every prepare step reads: the input contract (docs/api.md "Input contract"), then the
// feature toggles (slang/openpbr_features.h); run once per prepare.
OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_prepare_inputs(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs)
{
    return openpbr_apply_feature_toggles(openpbr_apply_input_contract(raw_inputs));
}

// Whether results depend on the wavelengths passed to prepare (dispersive transmission).
OPENPBR_FUNC bool openpbr_needs_rgb_wavelengths(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs)
{
    const OpenPBR_ResolvedInputs inputs = openpbr_prepare_inputs(raw_inputs);
    return OPENPBR_WEIGHT_ACTIVE(inputs.transmission_dispersion_scale) &&
           OPENPBR_WEIGHT_ACTIVE(inputs.transmission_weight) && inputs.base_metalness < 1.0f &&
           inputs.geometry_opacity > 0.0f && !inputs.geometry_thin_walled;
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

// Defensive floor of the metal's selection estimate (Hesterberg 1995, "Weighted average
// importance sampling and defensive mixture distributions"), relative to the largest albedo its
// lobe can reach (its weight times its Fresnel tint: F82-tint, filmed or not, stays within
// [0, 1]), e.g. 1e-3. The estimate follows the Fresnel factor at the view (or the film's lobe
// average); a rough metal of F0 near 0 seen head-on reads F0 there while its tilted
// microfacets reflect the Schlick rise, so without a floor it was selected with probability
// 1.2e-8 and a sample on its highlight weighed 1.2e4 (fuzzer finding,
// fuzz/corpus/finding_black_metal_beside_pass_through.bin). With it a metal sample weighs at
// most 1/floor times the sum of the estimates; the floor moves no probability of a metal whose
// estimate exceeds 1/1000 of that bound (every base_color above 1e-3 seen head-on).
#define OPENPBR_METAL_SELECTION_FLOOR 1e-3f

// The differentiable build keeps every lobe (no cut): dropping one is a jump in pdf where its
// probability crosses the cut, and a weight-0 lobe's one-sided derivative needs it kept.
OPENPBR_FUNC float openpbr_kept_probability(float probability, float cut)
{
    return (OPENPBR_AUTODIFF != 0 || probability >= cut) ? probability : 0.0f;
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

// The frames and views of the three layers, the side the view is on and what does not depend on
// the lobes: the interior medium, the pass-through weight, an emission of 0 (openpbr_prepare
// sets it). Coat and fuzz frames only where those layers exist; otherwise the base frame stands
// in (eval then transforms the light once). `inputs` have passed openpbr_prepare_inputs.
OPENPBR_INLINE_FUNC OpenPBR_PreparedBsdf openpbr_prepare_frames(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world)
{
    OpenPBR_PreparedBsdf bsdf;
    bsdf.view_world = openpbr_safe_normalize(view_world, inputs.geometry_basis.normal);
    const float opacity = inputs.geometry_opacity;
    const float metalness = inputs.base_metalness;
    const float coat_weight = inputs.coat_weight;
    const float fuzz_weight = inputs.fuzz_weight;
    const bool thin_walled = inputs.geometry_thin_walled;
    // Light enters the interior through the dielectric base (translucent or subsurface).
    const float entering_weight =
        (1.0f - metalness) * (inputs.transmission_weight + (1.0f - inputs.transmission_weight) * inputs.subsurface_weight);
    const bool back_face = dot(bsdf.view_world, inputs.geometry_basis.normal) < 0.0f;
    bsdf.inside = back_face && !thin_walled && entering_weight > 0.0f && opacity > 0.0f;
    bsdf.basis = back_face ? openpbr_flip_basis(inputs.geometry_basis) : inputs.geometry_basis;
    bsdf.coat_basis = back_face ? openpbr_flip_basis(inputs.geometry_coat_basis) : inputs.geometry_coat_basis;
    bsdf.view = openpbr_to_local(bsdf.basis, bsdf.view_world);
    bsdf.view = openpbr_floor_view_cosine(bsdf.view);
    bsdf.coat_view = bsdf.view;
    if (OPENPBR_WEIGHT_ACTIVE(coat_weight))
    {
        bsdf.coat_view = openpbr_to_local(bsdf.coat_basis, bsdf.view_world);
        bsdf.coat_view = openpbr_floor_view_cosine(bsdf.coat_view);
        // A coat whose own frame faces away from the view (its cosine floored to 0, e.g. a coat
        // on the unperturbed frame over a base seen from below) sees the view at no cosine: its
        // value stays put as the view moves, and the derivatives of its horizon terms there are
        // 0 / 0, so the differentiable build cuts them (the plain build has no reverse pass).
        if (OPENPBR_AUTODIFF != 0 && bsdf.coat_view.z <= 0.0f)
        {
            bsdf.coat_view = OPENPBR_DETACH(bsdf.coat_view);
        }
    }
    bsdf.fuzz_basis = bsdf.basis;
    bsdf.fuzz_view = bsdf.view;
    if (OPENPBR_WEIGHT_ACTIVE(fuzz_weight))
    {
        bsdf.fuzz_basis = openpbr_make_basis(mix(bsdf.basis.normal, bsdf.coat_basis.normal, coat_weight));
        bsdf.fuzz_view = openpbr_to_local(bsdf.fuzz_basis, bsdf.view_world);
        bsdf.fuzz_view = openpbr_floor_view_cosine(bsdf.fuzz_view);
    }
    // The interior medium exists only where light can enter (the volume helper returns an empty
    // one otherwise too; the branch skips its set-up for opaque and thin-walled materials).
    // Detached in the differentiable build: the medium's set-up has infinite derivatives where a
    // slab's weight is 0, which a reverse pass multiplied by the medium's zero cotangent into NaN.
    bsdf.volume =
        (entering_weight > 0.0f && !thin_walled) ? openpbr_make_volume(OPENPBR_DETACH(inputs)) : openpbr_make_empty_volume();
    bsdf.emission = vec3(0.0f);
    bsdf.pass_through_weight = vec3(1.0f - opacity);
    return bsdf;
}

// Every lobe empty and every selection probability 0, the layering factors those of no coat:
// what prepare leaves where a layer or lobe has weight 0. Every argument is a constant, so the
// empty lobes fold to stores of constants.
OPENPBR_INLINE_FUNC void openpbr_clear_lobes(OPENPBR_INOUT(OpenPBR_PreparedBsdf) bsdf)
{
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
    bsdf.under_coat_transmitted = vec3(1.0f);
    bsdf.fuzz = openpbr_fuzz_lobe_empty();
    bsdf.coat = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_COAT);
    bsdf.specular = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_SPECULAR_REFLECTION);
    bsdf.metal = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_METAL);
    bsdf.thin_transmission = openpbr_microfacet_reflection_lobe_empty(OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION);
    bsdf.diffuse = openpbr_diffuse_lobe_empty(1.0f);
    bsdf.diffuse_transmission = openpbr_diffuse_lobe_empty(-1.0f);
    bsdf.transmission = openpbr_dielectric_lobe_empty(OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION);
}

// The base layer's microsurface and IOR, which the base lobes, the interface seen from inside
// and the coat's darkening share (spec "Base Substrate", "Coat").
struct OpenPBR_BaseMicrosurface OPENPBR_DIFFERENTIABLE
{
    float coat_eta;                     // the coat's IOR relative to the exterior medium
    float eta;                          // the base's relative IOR under the coat, modulated by specular_weight
    vec3 eta_channels;                  // eta per channel (dispersion)
    vec2 alpha;                         // the base's GGX alpha, roughened by the coat
    OpenPBR_GgxLobeAlbedo lobe_albedo;  // its albedos at the view
};

// Every interface sees a relative IOR: the coat against the exterior medium, the base against
// the exterior (uncoated) or the coat (spec "Coat": the base's relative IOR under the coat,
// inverted where the coat is the denser medium), blended by coat_weight. The coat roughens the
// base (spec "Coat", roughening).
OPENPBR_INLINE_FUNC OpenPBR_BaseMicrosurface openpbr_prepare_base_microsurface(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                                               vec3 rgb_wavelengths_nm, float exterior_ior,
                                                                               vec3 view)
{
    const float coat_weight = inputs.coat_weight;
    OpenPBR_BaseMicrosurface base;
    base.coat_eta = openpbr_relative_ior(inputs.coat_ior, exterior_ior);
    const float base_eta = openpbr_relative_ior(inputs.specular_ior, exterior_ior);
    const float base_over_coat = inputs.coat_ior > inputs.specular_ior ? inputs.coat_ior / inputs.specular_ior
                                                                       : inputs.specular_ior / inputs.coat_ior;
    base.eta = openpbr_modulated_ior(
        OPENPBR_WEIGHT_ACTIVE(coat_weight) ? mix(base_eta, base_over_coat, coat_weight) : base_eta, inputs.specular_weight);
    base.eta_channels = openpbr_dispersive_ior(base.eta, inputs.transmission_dispersion_abbe_number,
                                               inputs.geometry_thin_walled ? 0.0f : inputs.transmission_dispersion_scale,
                                               rgb_wavelengths_nm);
    const float coat_roughness = inputs.coat_roughness;
    const float base_roughness =
        OPENPBR_WEIGHT_ACTIVE(coat_weight)
            ? mix(inputs.specular_roughness,
                  pow(min(1.0f, pow(inputs.specular_roughness, 4.0f) + 2.0f * pow(coat_roughness, 4.0f)), 0.25f),
                  coat_weight)
            : inputs.specular_roughness;
    base.alpha = openpbr_ggx_alpha(base_roughness, inputs.specular_roughness_anisotropy);
    base.lobe_albedo = openpbr_ggx_lobe_albedo(base_roughness, inputs.specular_roughness_anisotropy, base.alpha, view);
    return base;
}

// Fuzz (spec "Fuzz"): F f_fuzz + (1 - F E_fuzz) f_coated. Sets bsdf.fuzz where fuzz_weight > 0
// (bsdf.fuzz_view prepared); returns what reaches the layers below, `layer_weight` (the
// opacity) times 1 - F E_fuzz; `albedo` receives the fuzz's directional albedo at the view.
OPENPBR_INLINE_FUNC float openpbr_prepare_fuzz_layer(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, float layer_weight,
                                                     OPENPBR_INOUT(OpenPBR_PreparedBsdf) bsdf, OPENPBR_OUT(vec3) albedo)
{
    float under_fuzz = layer_weight;
    albedo = vec3(0.0f);
    if (OPENPBR_WEIGHT_ACTIVE(inputs.fuzz_weight))
    {
        const float fuzz_albedo_white = openpbr_fuzz_albedo_white(bsdf.fuzz_view.z, inputs.fuzz_roughness);
        bsdf.fuzz = openpbr_fuzz_lobe_prepare(inputs, layer_weight, bsdf.fuzz_view, albedo);
        under_fuzz = layer_weight * (1.0f - inputs.fuzz_weight * fuzz_albedo_white);
    }
    return under_fuzz;
}

// Coat (spec "Coat"): C f_coat + lerp(1, T_coat (1 - E_coat), C) darkening f_base. Sets
// bsdf.coat and the coat's absorption where coat_weight > 0 (bsdf.coat_view and
// bsdf.coat_inverse_eta_squared prepared); `layer_weight` is what the fuzz leaves. `albedo`
// receives E_coat at the view, `view_transmittance` T_coat towards the view (1 without
// absorption).
OPENPBR_INLINE_FUNC void openpbr_prepare_coat_layer(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, float coat_eta,
                                                    float layer_weight, OPENPBR_INOUT(OpenPBR_PreparedBsdf) bsdf,
                                                    OPENPBR_OUT(vec3) albedo, OPENPBR_OUT(vec3) view_transmittance)
{
    albedo = vec3(0.0f);
    view_transmittance = vec3(1.0f);
    if (OPENPBR_WEIGHT_ACTIVE(inputs.coat_weight))
    {
        bsdf.coat = openpbr_coat_lobe_prepare(inputs, coat_eta, layer_weight, bsdf.coat_view, albedo);
        bsdf.coat_absorbs = OPENPBR_AUTODIFF != 0 ||
                            !(inputs.coat_color.x == 1.0f && inputs.coat_color.y == 1.0f && inputs.coat_color.z == 1.0f);
        if (bsdf.coat_absorbs)
        {
            bsdf.coat_half_log_color = 0.5f * log(max(inputs.coat_color, vec3(1e-6f)));
            view_transmittance =
                openpbr_coat_transmittance(bsdf.coat_half_log_color, bsdf.coat_inverse_eta_squared, bsdf.coat_view.z);
        }
    }
}

// The albedo estimates of the base lobes at the view, with a unit layering factor: what the
// coat's darkening and lobe selection read.
struct OpenPBR_BaseAlbedos OPENPBR_DIFFERENTIABLE
{
    vec3 specular;              // the dielectric reflection, (1 - base_metalness) included
    vec3 diffuse;               // the diffuse reflection
    vec3 metal;                 // the metal, base_metalness included
    vec3 diffuse_transmission;  // the thin-walled subsurface sheet's transmission
    vec3 transmission;          // the refraction into the interior (its selection estimate)
    vec3 thin_transmission;     // the thin-walled un-deflected transmission
    // What the coat's darkening sees of the slabs light enters (spec "Coat", darkening: E_b is
    // "the albedos of the base slabs blended by their weights").
    vec3 entering_slab;
};

// The base substrate (spec "Base Substrate"): the dielectric's specular reflection over its
// translucent, subsurface and diffuse slabs (thin-walled: the sheet and the un-deflected
// transmission), beside the metal, each where its weight is above zero. Sets those lobes in
// bsdf (frames prepared) and returns their albedo estimates.
OPENPBR_INLINE_FUNC OpenPBR_BaseAlbedos openpbr_prepare_base_layer(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                                   OPENPBR_IN(OpenPBR_BaseMicrosurface) base,
                                                                   float exterior_ior,
                                                                   OPENPBR_INOUT(OpenPBR_PreparedBsdf) bsdf)
{
    const float metalness = inputs.base_metalness;
    const float coat_weight = inputs.coat_weight;
    const bool thin_walled = inputs.geometry_thin_walled;
    const vec3 view = bsdf.view;
    const vec2 alpha = base.alpha;
    // Dielectric specular reflection, tinted by specular_color (reflection from above only).
    // Thin film on the base (spec "Thin-film iridescence"): over the metal and the dielectric,
    // under the coat; the medium above it is the coat where there is one (IOR blended by
    // coat_weight, the spec's "depending on coat coverage"), otherwise the exterior medium.
    // Absolute IORs: the film's Fresnel model reads n_outside, n_film and n_base themselves.
    const float film_outside_ior =
        OPENPBR_WEIGHT_ACTIVE(coat_weight) ? mix(exterior_ior, inputs.coat_ior, coat_weight) : exterior_ior;
    const float dielectric_weight = 1.0f - metalness;
    // The film's lobe averages for both base factors at once (they share its evaluations).
    // The lobes build their Fresnel structs again: a film-free material then pays for no copy.
    OpenPBR_FresnelPair film_averages;
    film_averages.first = vec3(0.0f);
    film_averages.second = vec3(0.0f);
    if (OPENPBR_WEIGHT_ACTIVE(inputs.thin_film_weight))
    {
        OpenPBR_Fresnel metal_fresnel = openpbr_make_constant_fresnel(vec3(0.0f));
        if (OPENPBR_WEIGHT_ACTIVE(metalness))
        {
            metal_fresnel = openpbr_metal_fresnel(inputs, film_outside_ior);
        }
        film_averages = openpbr_base_film_estimate(
            openpbr_specular_reflection_fresnel(inputs, base.eta_channels.y, film_outside_ior),
            OPENPBR_WEIGHT_ACTIVE(dielectric_weight), metal_fresnel, OPENPBR_WEIGHT_ACTIVE(metalness), view, alpha);
    }
    vec3 specular_albedo = vec3(0.0f);
    if (OPENPBR_WEIGHT_ACTIVE(dielectric_weight))
    {
        bsdf.specular = openpbr_specular_reflection_lobe_prepare(inputs, base.eta_channels, alpha, base.lobe_albedo,
                                                                 film_outside_ior, film_averages, view, specular_albedo);
    }
    const vec3 under_specular = vec3(1.0f) - specular_albedo;

    // What passes the specular interface splits into translucent, subsurface and diffuse
    // (spec "Base Substrate").
    const float translucent = inputs.transmission_weight;
    const float subsurface = (1.0f - translucent) * inputs.subsurface_weight;
    const float diffuse_fraction = (1.0f - translucent) * (1.0f - inputs.subsurface_weight);
    vec3 diffuse_weight = under_specular * (dielectric_weight * diffuse_fraction * inputs.base_weight);
    vec3 diffuse_color = inputs.base_color;
    // Plain variables as out arguments (see openpbr_prepare_lobes_of), gathered at the end.
    vec3 diffuse_albedo = vec3(0.0f);
    vec3 diffuse_transmission_albedo = vec3(0.0f);
    vec3 transmission_albedo = vec3(0.0f);
    vec3 thin_transmission_albedo = vec3(0.0f);
    vec3 entering_slab_albedo = vec3(0.0f);
    vec3 metal_albedo = vec3(0.0f);
    const float entering = dielectric_weight * (translucent + subsurface);
    if (thin_walled && OPENPBR_WEIGHT_ACTIVE(entering))
    {
        // Thin-walled (spec "Thin-walled case"): subsurface becomes a thin scattering sheet
        // whose reflection joins the diffuse lobe; the translucent base becomes an un-deflected
        // transmission.
        if (OPENPBR_WEIGHT_ACTIVE(subsurface))
        {
            bsdf.diffuse_transmission =
                openpbr_diffuse_transmission_lobe_prepare(inputs, under_specular * (dielectric_weight * subsurface), view,
                                                          diffuse_weight, diffuse_color, diffuse_transmission_albedo);
        }
        if (OPENPBR_WEIGHT_ACTIVE(translucent))
        {
            bsdf.thin_transmission =
                openpbr_thin_transmission_lobe_prepare(inputs, under_specular * (dielectric_weight * translucent), alpha,
                                                       base.lobe_albedo, view, thin_transmission_albedo);
        }
    }
    else if (OPENPBR_WEIGHT_ACTIVE(entering))
    {
        // Refraction into the interior: translucent and subsurface (the medium does the rest).
        vec3 reflected = vec3(0.0f);
        bsdf.transmission = openpbr_transmission_lobe_prepare(
            inputs, under_specular * dielectric_weight, translucent, subsurface, alpha, base.lobe_albedo.table_alpha,
            base.eta_channels, view, transmission_albedo, entering_slab_albedo, reflected);
        // What the compensation's floor keeps from the refraction reflects instead (see
        // openpbr_transmission_lobe_prepare): the specular lobe's weight grows by that share of
        // its albedo, per channel where it reflects at all (specular_color 0 reflects nothing).
        if (max(reflected.x, max(reflected.y, reflected.z)) > 0.0f)
        {
            const vec3 reflecting = specular_albedo * dielectric_weight;
            const vec3 takes = vec3(reflecting.x > 1e-4f ? 1.0f : 0.0f, reflecting.y > 1e-4f ? 1.0f : 0.0f,
                                    reflecting.z > 1e-4f ? 1.0f : 0.0f);
            bsdf.specular.weight *= vec3(1.0f) + takes * reflected / max(reflecting, vec3(1e-4f));
            specular_albedo += takes * reflected / dielectric_weight;
        }
    }
    if (OPENPBR_WEIGHT_ACTIVE(max(diffuse_weight.x, max(diffuse_weight.y, diffuse_weight.z))))
    {
        bsdf.diffuse = openpbr_diffuse_lobe_prepare(inputs, diffuse_weight, diffuse_color, view, diffuse_albedo);
    }

    // Metal (spec "Base Substrate"): F82-tint Fresnel.
    if (OPENPBR_WEIGHT_ACTIVE(metalness))
    {
        bsdf.metal =
            openpbr_metal_lobe_prepare(inputs, alpha, base.lobe_albedo, film_outside_ior, film_averages, view, metal_albedo);
    }
    OpenPBR_BaseAlbedos albedos;
    albedos.specular = specular_albedo * dielectric_weight;
    albedos.diffuse = diffuse_albedo;
    albedos.metal = metal_albedo;
    albedos.diffuse_transmission = diffuse_transmission_albedo;
    albedos.transmission = transmission_albedo;
    albedos.thin_transmission = thin_transmission_albedo;
    albedos.entering_slab = entering_slab_albedo;
    return albedos;
}

// Darkening (spec "Coat", darkening): lerp(1, Delta, C delta), Delta = (1 - K)/(1 - E_b K),
// K = lerp(K_s, K_r, r_b); E_b the albedo of the whole base, its slabs blended by their mix
// weights (spec: translucent and subsurface slabs included, so a white glass base under a
// white coat is not darkened and passes the white furnace), taken at the view rather than
// only at normal incidence (a documented approximation). No coat: no darkening.
OPENPBR_INLINE_FUNC vec3 openpbr_coat_darkening(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                                OPENPBR_IN(OpenPBR_BaseMicrosurface) base,
                                                OPENPBR_IN(OpenPBR_BaseAlbedos) albedos, float coat_mu,
                                                float coat_inverse_eta_squared)
{
    const float coat_weight = inputs.coat_weight;
    vec3 darkening = vec3(1.0f);
    if (OPENPBR_WEIGHT_ACTIVE(coat_weight))
    {
        const vec3 base_albedo =
            openpbr_saturate(albedos.specular + albedos.diffuse + albedos.metal + albedos.diffuse_transmission +
                             albedos.entering_slab + albedos.thin_transmission);
        const float k_specular = openpbr_fresnel_dielectric(coat_mu, base.coat_eta);
        const float k_rough = 1.0f - (1.0f - openpbr_average_fresnel(base.coat_eta)) * coat_inverse_eta_squared;
        const float specular_f0 = openpbr_dielectric_f0(base.eta);
        const float base_surface_roughness =
            mix(mix(1.0f, inputs.specular_roughness, min(specular_f0 * inputs.specular_weight, 1.0f)),
                inputs.specular_roughness, inputs.base_metalness);
        const float k = mix(k_specular, k_rough, base_surface_roughness);
        const vec3 delta = vec3(1.0f - k) / max(vec3(1.0f) - base_albedo * k, vec3(1e-6f));
        darkening = mix(vec3(1.0f), delta, coat_weight * inputs.coat_darkening);
    }
    return darkening;
}

// The estimates of the layers above the base that lobe selection reads besides the base's.
struct OpenPBR_LayerAlbedos OPENPBR_DIFFERENTIABLE
{
    vec3 fuzz;             // the fuzz's directional albedo, weights included
    vec3 coat;             // E_coat per unit coat weight
    float under_fuzz;      // what the fuzz leaves the coat (opacity included)
    vec3 under_reflected;  // the base's layering factor for light reflected back to the view side
};

// Selection probability proportional to each lobe's estimated albedo (luminance), weighted by
// the path's channel weights; the probabilities only steer sampling, so estimates need not be
// exact. Negligible lobes are dropped: probability 0, so eval, pdf and sample skip them alike.
OPENPBR_INLINE_FUNC void openpbr_select_lobes(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs,
                                              OPENPBR_IN(OpenPBR_LayerAlbedos) layers,
                                              OPENPBR_IN(OpenPBR_BaseAlbedos) albedos, vec3 path_throughput,
                                              OPENPBR_INOUT(OpenPBR_PreparedBsdf) bsdf)
{
    const float metalness = inputs.base_metalness;
    const float coat_weight = inputs.coat_weight;
    const float dielectric_weight = 1.0f - metalness;
    const vec3 under_reflected = layers.under_reflected;
    const vec3 channel = openpbr_selection_channel_weights(path_throughput);
    const float white = openpbr_selection_white_scale(channel);
    const float fuzz_p = OPENPBR_WEIGHT_ACTIVE(inputs.fuzz_weight) ? openpbr_luminance(layers.fuzz * channel) : 0.0f;
    const float coat_p = OPENPBR_WEIGHT_ACTIVE(coat_weight) ? layers.under_fuzz * coat_weight * layers.coat.x * white : 0.0f;
    const float specular_p =
        OPENPBR_WEIGHT_ACTIVE(dielectric_weight) ? openpbr_luminance(albedos.specular * under_reflected * channel) : 0.0f;
    float metal_p = 0.0f;
    if (OPENPBR_WEIGHT_ACTIVE(metalness))
    {
        const vec3 metal_selection_albedo = openpbr_max_first_at_tie(
            albedos.metal, OPENPBR_METAL_SELECTION_FLOOR * bsdf.metal.weight * bsdf.metal.fresnel.tint);
        metal_p = openpbr_luminance(metal_selection_albedo * under_reflected * channel);
    }
    const float diffuse_p = openpbr_luminance(albedos.diffuse * under_reflected * channel);
    const float diffuse_transmission_p =
        openpbr_luminance(albedos.diffuse_transmission * bsdf.under_coat_transmitted * channel);
    const float transmission_p = openpbr_luminance(albedos.transmission * bsdf.under_coat_transmitted * channel);
    const float thin_transmission_p = openpbr_luminance(albedos.thin_transmission * bsdf.under_coat_transmitted * channel);
    const float pass_through_p = (1.0f - inputs.geometry_opacity) * white;
    const float raw_total = fuzz_p + coat_p + specular_p + metal_p + diffuse_p + diffuse_transmission_p + transmission_p +
                            thin_transmission_p + pass_through_p;
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
}

// Composes the lobes in the specification's layer order (fuzz over coat over base), each set up
// by its prepare in slang/lobes/ only where its weight is above zero (a lobe whose weight is
// zero costs nothing): the others keep the empty lobe and selection probability 0, which eval,
// pdf and sample never look at. With a feature toggled off its weight is the constant 0, so the
// compiler removes the set-up altogether. The emission is prepared apart
// (openpbr_prepare_emission_of).
// `inputs` have passed openpbr_prepare_inputs. exterior_ior: the absolute IOR of the medium the view is in (docs/api.md
// "Exterior medium"), already passed through openpbr_contract_exterior_ior. `path_throughput` only steers lobe selection
// (openpbr_selection_channel_weights); white gives the unweighted probabilities.
OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare_lobes_of(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world,
                                                           vec3 rgb_wavelengths_nm, float exterior_ior, vec3 path_throughput)
{
    OpenPBR_PreparedBsdf bsdf = openpbr_prepare_frames(inputs, view_world);
    const float opacity = inputs.geometry_opacity;
    const float coat_weight = inputs.coat_weight;
    const OpenPBR_BaseMicrosurface base =
        openpbr_prepare_base_microsurface(inputs, rgb_wavelengths_nm, exterior_ior, bsdf.view);
    openpbr_clear_lobes(bsdf);
    bsdf.coat_inverse_eta_squared = 1.0f / (base.coat_eta * base.coat_eta);

    if (bsdf.inside)
    {
        // Inside: the dielectric interface seen from the denser side. Light leaving crosses the
        // coat once and the fuzz (approximated as view-independent factors).
        const float fuzz_weight = inputs.fuzz_weight;
        const vec3 exit_factor =
            (OPENPBR_WEIGHT_ACTIVE(coat_weight) ? mix(vec3(1.0f), sqrt(inputs.coat_color), coat_weight) : vec3(1.0f)) *
            (OPENPBR_WEIGHT_ACTIVE(fuzz_weight) ? 1.0f - fuzz_weight * openpbr_fuzz_albedo_white(1.0f, inputs.fuzz_roughness)
                                                : 1.0f);
        bsdf.transmission = openpbr_interface_lobe_prepare(opacity, exit_factor, base.alpha, base.lobe_albedo.table_alpha,
                                                           base.eta_channels, bsdf.view);
        const float total = opacity + (1.0f - opacity);
        bsdf.probability_transmission = opacity / total;
        bsdf.probability_pass_through = (1.0f - opacity) / total;
        return bsdf;
    }

    // Out arguments are plain variables, not fields of a struct: for a field passed as an out
    // argument Slang's SPIR-V emits another copy of the callee's whole call tree (with fields:
    // 66 functions up to four times, the conformance kernel 263,836 bytes; with variables
    // 225,868, 2026-12-02).
    OpenPBR_LayerAlbedos layers;
    vec3 fuzz_albedo = vec3(0.0f);
    layers.under_fuzz = openpbr_prepare_fuzz_layer(inputs, opacity, bsdf, fuzz_albedo);
    layers.fuzz = fuzz_albedo;
    vec3 coat_albedo = vec3(0.0f);
    vec3 coat_view_transmittance = vec3(1.0f);
    openpbr_prepare_coat_layer(inputs, base.coat_eta, layers.under_fuzz, bsdf, coat_albedo, coat_view_transmittance);
    layers.coat = coat_albedo;
    const OpenPBR_BaseAlbedos albedos = openpbr_prepare_base_layer(inputs, base, exterior_ior, bsdf);
    const vec3 darkening = openpbr_coat_darkening(inputs, base, albedos, bsdf.coat_view.z, bsdf.coat_inverse_eta_squared);

    // Layering factors on every base lobe: fuzz and opacity, coat absorption and darkening.
    bsdf.under_coat_constant = darkening * (layers.under_fuzz * (1.0f - coat_weight));
    bsdf.under_coat_absorbing =
        darkening * (layers.under_fuzz * coat_weight * (1.0f - layers.coat.x)) * coat_view_transmittance;
    bsdf.under_coat_transmitted = bsdf.under_coat_constant + bsdf.under_coat_absorbing;
    // Estimate for selection: the light-side transmittance taken equal to the view side's.
    layers.under_reflected = bsdf.under_coat_constant + bsdf.under_coat_absorbing * coat_view_transmittance;
    openpbr_select_lobes(inputs, layers, albedos, path_throughput, bsdf);
    return bsdf;
}

// Emission (spec "Emission"): emission_luminance x emission_color in nits, under the coat:
// lerp(1, T_coat, C) with T_coat one pass through the coat towards the view; zero when seen
// from inside a non-thin-walled object (the emitting surface faces outwards).
// `inputs` have passed openpbr_prepare_inputs.
OPENPBR_FUNC vec3 openpbr_prepare_emission_of(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world, float exterior_ior)
{
    if (!OPENPBR_WEIGHT_ACTIVE(inputs.emission_luminance))
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
    if (OPENPBR_WEIGHT_ACTIVE(inputs.coat_weight))
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
OPENPBR_FUNC vec3 openpbr_prepare_emission(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs, vec3 view_world,
                                           float exterior_ior)
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
                                                           vec3 rgb_wavelengths_nm, float exterior_ior, vec3 path_throughput)
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
        if (OPENPBR_WEIGHT_ACTIVE(bsdf.probability_transmission))
        {
            value.specular = openpbr_dielectric_lobe_eval(bsdf.transmission, bsdf.view, light);
        }
        return value;
    }
    if (OPENPBR_FEATURE_FUZZ && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_fuzz))
    {
        value.specular = openpbr_fuzz_lobe_eval(bsdf.fuzz, bsdf.fuzz_view, openpbr_to_local(bsdf.fuzz_basis, light_world));
    }
    if (OPENPBR_FEATURE_COAT && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_coat))
    {
        // The coat carries no film (the film lies on the base): no film code here.
        value.specular = value.specular +
                         openpbr_microfacet_reflection_lobe_eval_with(bsdf.coat, bsdf.coat_view,
                                                                      openpbr_to_local(bsdf.coat_basis, light_world), false);
    }
    vec3 diffuse = vec3(0.0f);
    vec3 specular = vec3(0.0f);
    if (light.z >= 0.0f)
    {
        // The dielectric and metal lobes in one evaluation: one D, G2 and film for both. A lone
        // dielectric without a film takes the film-free lobe evaluation (no pair bookkeeping).
        const bool specular_active = OPENPBR_WEIGHT_ACTIVE(bsdf.probability_specular);
        const bool metal_active = OPENPBR_FEATURE_METAL && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_metal);
        if (!metal_active && !(OPENPBR_FEATURE_THIN_FILM && OPENPBR_WEIGHT_ACTIVE(bsdf.specular.fresnel.film_weight)))
        {
            if (specular_active)
            {
                specular = openpbr_microfacet_reflection_lobe_eval_with(bsdf.specular, bsdf.view, light, false);
            }
        }
        else
        {
            specular = openpbr_microfacet_reflection_lobe_pair_eval(bsdf.specular, specular_active, bsdf.metal, metal_active,
                                                                    bsdf.view, light);
        }
        if (OPENPBR_WEIGHT_ACTIVE(bsdf.probability_diffuse))
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
    if ((OPENPBR_FEATURE_TRANSMISSION || OPENPBR_FEATURE_SUBSURFACE) && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_transmission))
    {
        specular = openpbr_dielectric_lobe_eval(bsdf.transmission, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_TRANSMISSION &&
        OPENPBR_WEIGHT_ACTIVE(bsdf.probability_thin_transmission))
    {
        specular = specular + openpbr_microfacet_reflection_lobe_eval_with(bsdf.thin_transmission, bsdf.view, light, false);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_SUBSURFACE &&
        OPENPBR_WEIGHT_ACTIVE(bsdf.probability_diffuse_transmission))
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
    if ((OPENPBR_FEATURE_TRANSMISSION || OPENPBR_FEATURE_SUBSURFACE) && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_transmission))
    {
        pdf += bsdf.probability_transmission * openpbr_dielectric_lobe_pdf(bsdf.transmission, bsdf.view, light);
    }
    if (bsdf.inside)
    {
        return pdf;
    }
    if (OPENPBR_FEATURE_FUZZ && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_fuzz))
    {
        pdf += bsdf.probability_fuzz *
               openpbr_fuzz_lobe_pdf(bsdf.fuzz, bsdf.fuzz_view, openpbr_to_local(bsdf.fuzz_basis, light_world));
    }
    if (OPENPBR_FEATURE_COAT && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_coat))
    {
        pdf += bsdf.probability_coat * openpbr_microfacet_reflection_lobe_pdf(
                                           bsdf.coat, bsdf.coat_view, openpbr_to_local(bsdf.coat_basis, light_world));
    }
    if (OPENPBR_WEIGHT_ACTIVE(bsdf.probability_specular))
    {
        pdf += bsdf.probability_specular * openpbr_microfacet_reflection_lobe_pdf(bsdf.specular, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_METAL && OPENPBR_WEIGHT_ACTIVE(bsdf.probability_metal))
    {
        pdf += bsdf.probability_metal * openpbr_microfacet_reflection_lobe_pdf(bsdf.metal, bsdf.view, light);
    }
    if (OPENPBR_WEIGHT_ACTIVE(bsdf.probability_diffuse))
    {
        pdf += bsdf.probability_diffuse * openpbr_diffuse_lobe_pdf(bsdf.diffuse, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_SUBSURFACE &&
        OPENPBR_WEIGHT_ACTIVE(bsdf.probability_diffuse_transmission))
    {
        pdf += bsdf.probability_diffuse_transmission * openpbr_diffuse_lobe_pdf(bsdf.diffuse_transmission, bsdf.view, light);
    }
    if (OPENPBR_FEATURE_THIN_WALLED && OPENPBR_FEATURE_TRANSMISSION &&
        OPENPBR_WEIGHT_ACTIVE(bsdf.probability_thin_transmission))
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
        lobe_sample = openpbr_microfacet_reflection_lobe_sample_with(bsdf.coat, bsdf.coat_view, u_direction, false);
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
        lobe_sample = openpbr_microfacet_reflection_lobe_sample_with(bsdf.thin_transmission, bsdf.view, u_direction, false);
        probability = bsdf.probability_thin_transmission;
    }
    else if (bsdf.probability_pass_through > 0.0f)
    {
        // Straight on from the unfloored view (bsdf.view may be raised to the tables' floor).
        lobe_sample = openpbr_make_lobe_sample(
            -openpbr_to_local(bsdf.basis, bsdf.view_world),
            openpbr_lobe_type(OPENPBR_LOBE_ID_PASS_THROUGH, OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_SPECULAR));
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
    if (openpbr_lobe_type_is_specular(lobe_sample.lobe_type))
    {
        // Delta lobe: the estimator is value / P(selecting the lobe). A reflecting delta under
        // the coat sees the coat's absorption along the mirrored direction.
        vec3 factor = delta_factor;
        if (OPENPBR_FEATURE_COAT && bsdf.coat_absorbs && !bsdf.inside &&
            openpbr_lobe_type_is_reflection(lobe_sample.lobe_type) &&
            openpbr_lobe_type_id(lobe_sample.lobe_type) != OPENPBR_LOBE_ID_COAT)
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
