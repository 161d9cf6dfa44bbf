// The homogeneous interior medium of a non-thin-walled OpenPBR 1.1 surface (spec "Translucent
// base" and "Subsurface"; docs/spec-notes.md section 5): its coefficients, distance sampling
// with spectral MIS over the three color channels, transmittance and the Henyey-Greenstein
// phase function.
//
// Units: extinction and scattering coefficients are per scene length unit, like
// transmission_depth and subsurface_radius. Directions of the phase function are propagation
// directions (the way the path travels): cos_theta = dot(incoming_direction, outgoing_direction),
// so g > 0 scatters forward.
#ifndef OPENPBR_VOLUME_H
#define OPENPBR_VOLUME_H

#include "openpbr_resolved_inputs.h"
#include "math/openpbr_warps.h"

// Extinction cap, 1/scene unit: a mean free path of 1e-12 scene units is far below any
// geometric feature, so the cap never shows, and products with distances stay far from the
// float range for every distance a scene can have. It regularizes subsurface_radius -> 0 and
// transmission_color -> 0 (spec: "regularize as r -> 0"; the limit is an opaque look).
#define OPENPBR_VOLUME_EXTINCTION_MAX 1e12f
// Smallest transmission_color used in -ln(T): e^-69 is numerically black, so T = 0 becomes a
// finite optical depth of about 69 over transmission_depth instead of infinity.
#define OPENPBR_VOLUME_TRANSMITTANCE_MIN 1e-30f
// Henyey-Greenstein |g| limit (the spec allows clamping g away from +-1): at |g| = 1 the
// phase function is a delta, and its value and sampling degenerate.
#define OPENPBR_HG_ANISOTROPY_MAX 0.999f
#define OPENPBR_INV_FOUR_PI 0.07957747154594766788f

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_HomogeneousVolume OPENPBR_DIFFERENTIABLE
{
    vec3 extinction;   // sigma_t per channel, 1/scene unit, in [0, OPENPBR_VOLUME_EXTINCTION_MAX]
    vec3 albedo;       // single-scattering albedo sigma_s / sigma_t, in [0, 1]
    float anisotropy;  // Henyey-Greenstein g, in [-OPENPBR_HG_ANISOTROPY_MAX, OPENPBR_HG_ANISOTROPY_MAX]
    bool is_present;   // false: no interior medium (openpbr_make_volume then zeroes the other fields)
};

struct OpenPBR_VolumeDistanceSample OPENPBR_DIFFERENTIABLE
{
    float distance;  // to the scattering event, or t_max when the path passes through
    bool scattered;  // true: a real scattering event at `distance` < t_max
    // Scatter: transmittance * sigma_s / pdf. Pass-through: transmittance / P(no scatter).
    // Multiply the path throughput by it (per channel).
    vec3 weight;
    float pdf;  // scatter: density of `distance` (1/scene unit); pass-through: its probability
};

// ---------------------------------------------------------------------------------------------
// Henyey-Greenstein phase function (Henyey & Greenstein 1941, "Diffuse radiation in the
// galaxy", ApJ 93).

OPENPBR_FUNC float openpbr_henyey_greenstein_clamp_anisotropy(float g)
{
    // NaN means "no preference", i.e. isotropic; openpbr_clamp_finite alone would map it to -0.999.
    return clamp(openpbr_finite_or(g, 0.0f), -OPENPBR_HG_ANISOTROPY_MAX, OPENPBR_HG_ANISOTROPY_MAX);
}

// p(cos_theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos_theta)^(3/2)), per steradian; it is also
// the solid-angle pdf of openpbr_henyey_greenstein_sample.
OPENPBR_FUNC float openpbr_henyey_greenstein_eval(float g, float cos_theta)
{
    const float anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(g);
    const float cosine = openpbr_clamp_finite(cos_theta, -1.0f, 1.0f);
    // 1 + g^2 - 2 g cos written as a sum of two non-negative terms, so rounding cannot make it
    // smaller than (1 - |g|)^2 >= 1e-6 near the peak (the plain form cancels there).
    const float denominator = anisotropy >= 0.0f ? openpbr_square(1.0f - anisotropy) + 2.0f * anisotropy * (1.0f - cosine)
                                                 : openpbr_square(1.0f + anisotropy) - 2.0f * anisotropy * (1.0f + cosine);
    return OPENPBR_INV_FOUR_PI * (1.0f - anisotropy * anisotropy) / (denominator * sqrt(denominator));
}

// Cosine of the scattering angle for a uniform u. The standard inversion of the HG CDF (Pharr,
// Jakob, Humphreys, "Physically Based Rendering", 3rd/4th ed., "Sampling the Henyey-Greenstein
// phase function") is cos = (1 + g^2 - ((1 - g^2) / (1 + g a))^2) / (2 g) with a = 2u - 1,
// which divides by g and cancels catastrophically as g -> 0. Multiplying out gives the
// algebraically identical
//   cos = (a + g) / (1 + g a) + g (1 - g^2) (1 - a^2) / (2 (1 + g a)^2),
// which has no 1/g, reduces to the uniform a at g = 0 and gives exactly +-1 at a = +-1.
OPENPBR_FUNC float openpbr_henyey_greenstein_sample_cos_theta(float g, float u)
{
    const float anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(g);
    const float signed_u = 2.0f * openpbr_clamp_finite(u, 0.0f, 1.0f) - 1.0f;
    const float denominator = 1.0f + anisotropy * signed_u;  // >= 1 - |anisotropy| > 0
    // Dividing (rather than multiplying by a reciprocal) makes a = +-1 give exactly +-1.
    const float cos_theta = (signed_u + anisotropy) / denominator + 0.5f * anisotropy * (1.0f - anisotropy * anisotropy) *
                                                                        (1.0f - signed_u * signed_u) /
                                                                        (denominator * denominator);
    return clamp(cos_theta, -1.0f, 1.0f);
}

// Direction about `incoming_direction` (the propagation direction of the arriving path, unit
// length) with solid-angle pdf openpbr_henyey_greenstein_eval(g, dot(incoming, result)).
// u.x picks the polar angle, u.y the azimuth.
OPENPBR_FUNC vec3 openpbr_henyey_greenstein_sample(float g, vec3 incoming_direction, vec2 u)
{
    const float cos_theta = openpbr_henyey_greenstein_sample_cos_theta(g, u.x);
    const float sin_theta = openpbr_safe_sqrt(1.0f - cos_theta * cos_theta);
    const float phi = OPENPBR_TWO_PI * u.y;
    const OpenPBR_Basis frame = openpbr_make_basis(incoming_direction);
    return openpbr_to_world(frame, vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta));
}

OPENPBR_FUNC float openpbr_isotropic_phase_eval() { return OPENPBR_INV_FOUR_PI; }

OPENPBR_FUNC vec3 openpbr_isotropic_phase_sample(vec2 u) { return openpbr_sample_uniform_sphere(u); }

// ---------------------------------------------------------------------------------------------
// Subsurface albedo inversion (spec "Subsurface", eq. after subsurface_albedo_constraint):
// van de Hulst's semi-infinite, index-matched multiple-scattering albedo with similarity
// theory for anisotropy,
//   C = (1 - s)(1 - 0.139 s) / (1 + 1.17 s),  s = sqrt((1 - alpha) / (1 - alpha g)),
// and the spec's closed-form inverse
//   s = 4.09712 + 4.20863 C - sqrt(9.59217 + 41.6808 C + 17.7126 C^2),
//   alpha = (1 - s^2) / (1 - g s^2).

OPENPBR_FUNC float openpbr_van_de_hulst_albedo(float color, float g)
{
    const float clamped_color = openpbr_clamp_finite(color, 0.0f, 1.0f);
    // The fit gives s = -5e-6 at C = 1; the clamp to [0, 1] makes white exactly non-absorbing
    // (alpha = 1, the spec's white furnace). At C = 0 the fit gives s = 0.999997, alpha = 5.7e-6,
    // within the fit's own accuracy of black.
    const float root = sqrt(9.59217f + clamped_color * (41.6808f + clamped_color * 17.7126f));
    const float s = clamp(4.09712f + 4.20863f * clamped_color - root, 0.0f, 1.0f);
    const float s2 = s * s;
    // |g| <= 0.999 keeps the denominator >= 0.001, and alpha <= 1 because g <= 1.
    const float anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(g);
    return clamp((1.0f - s2) / (1.0f - anisotropy * s2), 0.0f, 1.0f);
}

OPENPBR_FUNC vec3 openpbr_van_de_hulst_albedo(vec3 color, float g)
{
    return vec3(openpbr_van_de_hulst_albedo(color.x, g), openpbr_van_de_hulst_albedo(color.y, g),
                openpbr_van_de_hulst_albedo(color.z, g));
}

// The forward map (albedo -> observed color), for tests and for renderers that start from a
// medium.
OPENPBR_FUNC float openpbr_van_de_hulst_color(float albedo, float g)
{
    const float clamped_albedo = openpbr_clamp_finite(albedo, 0.0f, 1.0f);
    const float anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(g);
    const float s = openpbr_safe_sqrt((1.0f - clamped_albedo) / (1.0f - clamped_albedo * anisotropy));
    return clamp((1.0f - s) * (1.0f - 0.139f * s) / (1.0f + 1.17f * s), 0.0f, 1.0f);
}

OPENPBR_FUNC vec3 openpbr_van_de_hulst_color(vec3 albedo, float g)
{
    return vec3(openpbr_van_de_hulst_color(albedo.x, g), openpbr_van_de_hulst_color(albedo.y, g),
                openpbr_van_de_hulst_color(albedo.z, g));
}

// ---------------------------------------------------------------------------------------------
// Construction from the resolved inputs.

OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_empty_volume()
{
    OpenPBR_HomogeneousVolume volume;
    volume.extinction = vec3(0.0f);
    volume.albedo = vec3(0.0f);
    volume.anisotropy = 0.0f;
    volume.is_present = false;
    return volume;
}

// Translucent medium (spec "Translucent base"): mu_t = -ln(T) / depth, mu_s = S / depth,
// mu_a = mu_t - mu_s, shifted up by -min(mu_a) when negative (the spec's gray shift), and the
// final extinction is mu_a + mu_s. Depth 0 (or below the smallest normal float, which GPUs
// flush to 0) is the spec's "no medium": all coefficients 0.
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_translucent_volume(vec3 transmission_color, float depth, vec3 scatter,
                                                                       float anisotropy)
{
    OpenPBR_HomogeneousVolume volume = openpbr_make_empty_volume();
    volume.anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(anisotropy);
    if (!(depth > OPENPBR_FLOAT_MIN_NORMAL))
    {
        return volume;
    }
    // Work in optical depths over `depth` (tau = mu * depth): the gray shift and the albedo do
    // not depend on depth, and tau stays small (<= about 70), so nothing overflows before the
    // single division below.
    const vec3 transmittance = openpbr_clamp_finite(transmission_color, OPENPBR_VOLUME_TRANSMITTANCE_MIN, 1.0f);
    const vec3 tau_extinction = max(-log(transmittance), vec3(0.0f));
    const vec3 tau_scattering = openpbr_clamp_finite(scatter, 0.0f, 1.0f);
    const vec3 tau_absorption_unshifted = tau_extinction - tau_scattering;
    const float lowest = min(tau_absorption_unshifted.x, min(tau_absorption_unshifted.y, tau_absorption_unshifted.z));
    const vec3 tau_absorption = max(tau_absorption_unshifted - vec3(min(lowest, 0.0f)), vec3(0.0f));
    const vec3 tau = tau_absorption + tau_scattering;
    // A channel with no extinction has no scattering either; its albedo is irrelevant, 0.
    volume.albedo = vec3(tau.x > OPENPBR_FLOAT_MIN_NORMAL ? tau_scattering.x / tau.x : 0.0f,
                         tau.y > OPENPBR_FLOAT_MIN_NORMAL ? tau_scattering.y / tau.y : 0.0f,
                         tau.z > OPENPBR_FLOAT_MIN_NORMAL ? tau_scattering.z / tau.z : 0.0f);
    volume.albedo = openpbr_clamp_finite(volume.albedo, 0.0f, 1.0f);
    // min(tau / depth, cap) without overflow for tiny depths: cap first, then divide.
    const float tau_max = OPENPBR_VOLUME_EXTINCTION_MAX * depth;
    volume.extinction = min(tau, vec3(tau_max)) / depth;
    volume.extinction = openpbr_clamp_finite(volume.extinction, 0.0f, OPENPBR_VOLUME_EXTINCTION_MAX);
    // Denormal coefficients are flushed to 0 on GPUs: decide on normal floats only.
    volume.is_present = openpbr_max3(volume.extinction) > OPENPBR_FLOAT_MIN_NORMAL;
    return volume;
}

// Subsurface medium (spec "Subsurface"): mean free path r = radius * radius_scale per channel,
// mu_t = 1 / r (capped, which regularizes r -> 0), albedo from the van de Hulst inversion.
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_subsurface_volume(vec3 color, float radius, vec3 radius_scale,
                                                                      float anisotropy)
{
    OpenPBR_HomogeneousVolume volume;
    volume.anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(anisotropy);
    const vec3 mean_free_path =
        openpbr_clamp_finite(radius, 0.0f, OPENPBR_FLOAT_MAX) * openpbr_clamp_finite(radius_scale, 0.0f, 1.0f);
    // max() with 1/cap both caps the extinction and keeps 1/r finite for r = 0 or denormal.
    volume.extinction = vec3(1.0f) / max(mean_free_path, vec3(1.0f / OPENPBR_VOLUME_EXTINCTION_MAX));
    volume.extinction = openpbr_clamp_finite(volume.extinction, 0.0f, OPENPBR_VOLUME_EXTINCTION_MAX);
    volume.albedo = openpbr_van_de_hulst_albedo(color, volume.anisotropy);
    volume.is_present = true;
    return volume;
}

// The interior medium of the surface. Leaf weights (spec "Reduction to a mixture of lobes"):
// translucent (1-M) T, subsurface (1-M)(1-T) S. Only their ratio matters for the interior
// (the (1-M) cancels); M = 1, or T = S = 0, leaves no medium.
//
// Blending two media into one homogeneous medium is physically ambiguous (the spec expects T to
// be 0 or 1). Our choice: the normalized weights blend the extinction and scattering
// coefficients linearly (a mixture of two particle populations in one volume), and g is the
// scattering-weighted mean of the two g's (the mean cosine of a scattering event in that
// mixture). A translucent base with depth 0 counts as vacuum (the spec's mu_t = 0), so the
// blend stays continuous as T -> 1. Thin-walled surfaces have no interior (spec "Thin-walled
// case"): no medium.
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_volume(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs)
{
    OpenPBR_HomogeneousVolume volume = openpbr_make_empty_volume();
    const float metalness = openpbr_clamp_finite(inputs.base_metalness, 0.0f, 1.0f);
    const float transmission = openpbr_clamp_finite(inputs.transmission_weight, 0.0f, 1.0f);
    const float subsurface = openpbr_clamp_finite(inputs.subsurface_weight, 0.0f, 1.0f);
    const float subsurface_share = (1.0f - transmission) * subsurface;
    const float total = transmission + subsurface_share;
    if (inputs.geometry_thin_walled || !(metalness < 1.0f) || !(total > OPENPBR_FLOAT_MIN_NORMAL))
    {
        return volume;
    }
    const float translucent_fraction = transmission / total;
    const float subsurface_fraction = subsurface_share / total;

    const OpenPBR_HomogeneousVolume translucent =
        openpbr_make_translucent_volume(inputs.transmission_color, inputs.transmission_depth, inputs.transmission_scatter,
                                        inputs.transmission_scatter_anisotropy);
    const OpenPBR_HomogeneousVolume subsurface_medium =
        openpbr_make_subsurface_volume(inputs.subsurface_color, inputs.subsurface_radius, inputs.subsurface_radius_scale,
                                       inputs.subsurface_scatter_anisotropy);

    // Each term is at most the cap, so the convex combinations stay below it.
    const vec3 translucent_scattering = translucent.extinction * translucent.albedo * translucent_fraction;
    const vec3 subsurface_scattering = subsurface_medium.extinction * subsurface_medium.albedo * subsurface_fraction;
    const vec3 extinction =
        translucent.extinction * translucent_fraction + subsurface_medium.extinction * subsurface_fraction;
    const vec3 scattering = translucent_scattering + subsurface_scattering;

    volume.extinction = openpbr_clamp_finite(extinction, 0.0f, OPENPBR_VOLUME_EXTINCTION_MAX);
    volume.albedo = vec3(extinction.x > OPENPBR_FLOAT_MIN_NORMAL ? scattering.x / extinction.x : 0.0f,
                         extinction.y > OPENPBR_FLOAT_MIN_NORMAL ? scattering.y / extinction.y : 0.0f,
                         extinction.z > OPENPBR_FLOAT_MIN_NORMAL ? scattering.z / extinction.z : 0.0f);
    volume.albedo = openpbr_clamp_finite(volume.albedo, 0.0f, 1.0f);

    // Scattering-weighted g over all channels; with no scattering g is irrelevant and the
    // plain weighted mean is used.
    const float translucent_scattering_sum = dot(translucent_scattering, vec3(1.0f));
    const float subsurface_scattering_sum = dot(subsurface_scattering, vec3(1.0f));
    const float scattering_sum = translucent_scattering_sum + subsurface_scattering_sum;
    const float scattered_anisotropy =
        (translucent_scattering_sum * translucent.anisotropy + subsurface_scattering_sum * subsurface_medium.anisotropy) /
        max(scattering_sum, OPENPBR_FLOAT_MIN_NORMAL);
    const float weighted_anisotropy =
        translucent_fraction * translucent.anisotropy + subsurface_fraction * subsurface_medium.anisotropy;
    const float blended_anisotropy = scattering_sum > OPENPBR_FLOAT_MIN_NORMAL ? scattered_anisotropy : weighted_anisotropy;
    volume.anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(blended_anisotropy);
    volume.is_present = openpbr_max3(volume.extinction) > OPENPBR_FLOAT_MIN_NORMAL;
    if (!volume.is_present)
    {
        return openpbr_make_empty_volume();
    }
    return volume;
}

// ---------------------------------------------------------------------------------------------
// Transmittance and distance sampling.

// Clamps a distance to [0, FLOAT_MAX]; NaN becomes 0, +inf FLOAT_MAX.
OPENPBR_FUNC float openpbr_volume_clamp_distance(float distance_value)
{
    return openpbr_clamp_finite(distance_value, 0.0f, OPENPBR_FLOAT_MAX);
}

// Beer-Lambert law: exp(-sigma_t d) per channel. An absent medium is fully transparent.
OPENPBR_FUNC vec3 openpbr_volume_transmittance(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume, float distance_value)
{
    if (!volume.is_present)
    {
        return vec3(1.0f);
    }
    // sigma_t <= 1e12 and d <= FLOAT_MAX: the product may overflow to +inf, never NaN (0 * d
    // is 0 for finite d), and exp(-inf) = 0; the min keeps exp's argument finite anyway.
    const vec3 optical_depth = volume.extinction * openpbr_volume_clamp_distance(distance_value);
    return exp(-min(optical_depth, vec3(1e4f)));
}

// Channel selection probabilities proportional to the path throughput (non-finite or negative
// components count as 0; all-zero throughput selects uniformly). Any choice that is positive
// where the throughput is keeps the estimator unbiased, so a caller may instead pass e.g.
// throughput * albedo to favour the channels that scatter.
OPENPBR_FUNC vec3 openpbr_volume_channel_probabilities(vec3 throughput)
{
    const vec3 nonnegative_throughput = openpbr_clamp_finite(throughput, 0.0f, OPENPBR_FLOAT_MAX);
    const float largest = openpbr_max3(nonnegative_throughput);
    if (!(largest > OPENPBR_FLOAT_MIN_NORMAL))
    {
        return vec3(1.0f / 3.0f);
    }
    // Divide by the largest first so the sum cannot overflow; denormal shares are flushed to 0
    // (as GPUs do), so a drawn channel always has a normal probability.
    const vec3 scaled = nonnegative_throughput / largest;
    const vec3 flushed =
        vec3(scaled.x > OPENPBR_FLOAT_MIN_NORMAL ? scaled.x : 0.0f, scaled.y > OPENPBR_FLOAT_MIN_NORMAL ? scaled.y : 0.0f,
             scaled.z > OPENPBR_FLOAT_MIN_NORMAL ? scaled.z : 0.0f);
    return flushed / (flushed.x + flushed.y + flushed.z);
}

// Spectral MIS over the channels (the one-sample "balance heuristic over wavelengths" of
// Wilkie et al. 2014, "Hero wavelength spectral sampling", and Miller, Georgiev, Jarosz 2019,
// "A null-scattering path integral formulation of light transport", on chromatic media):
// a distance sampled from channel c's exponential has, seen by all channels, the mixture
// density pdf(t) = sum_k P(k) sigma_t,k exp(-sigma_t,k t), and the probability of passing a
// segment of length t_max is sum_k P(k) exp(-sigma_t,k t_max).
// `scattered` selects the density (true) or the pass-through probability (false).
OPENPBR_FUNC float openpbr_volume_distance_pdf(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume, vec3 throughput,
                                               float distance_value, bool scattered)
{
    if (!volume.is_present)
    {
        return scattered ? 0.0f : 1.0f;
    }
    const vec3 probabilities = openpbr_volume_channel_probabilities(throughput);
    const vec3 transmittance = openpbr_volume_transmittance(volume, distance_value);
    return scattered ? dot(probabilities, volume.extinction * transmittance) : dot(probabilities, transmittance);
}

// Ratio of channel k's free-flight density (scattered) or transmittance (passed) at distance d
// to that of the drawn channel c: (sigma_k / sigma_c) exp(-(sigma_k - sigma_c) d), resp. without
// the sigma factor. Evaluated as one exponential of a log so that neither factor over- or
// underflows on its own (sigma_c d <= about 69 bounds the exponent from above; the clamp only
// keeps a -inf away from exp). Channel c itself gives exactly 1.
OPENPBR_FUNC float openpbr_volume_channel_ratio(float extinction_k, float extinction_c, float distance_value, bool scattered)
{
    if (scattered && !(extinction_k > OPENPBR_FLOAT_MIN_NORMAL))
    {
        return 0.0f;
    }
    const float log_ratio = scattered ? log(extinction_k) - log(extinction_c) : 0.0f;
    return exp(clamp(log_ratio - (extinction_k - extinction_c) * distance_value, -1e4f, 80.0f));
}

// The one-sample spectral-MIS weight of a flight that ends at `distance_value` (scattered:
// transmittance * sigma_s / pdf(t); passed: transmittance / P(pass)), divided through by the
// density (or transmittance) of a reference channel with extinction `extinction_reference`
// so that neither part under- or overflows on its own. Any reference channel gives the same
// weight up to rounding; the sampler passes the drawn one, whose own term makes the
// denominator at least P(c) > 0.
OPENPBR_FUNC vec3 openpbr_volume_flight_weight(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume, vec3 probabilities,
                                               float extinction_reference, float distance_value, bool scattered)
{
    const vec3 ratio =
        vec3(openpbr_volume_channel_ratio(volume.extinction.x, extinction_reference, distance_value, scattered),
             openpbr_volume_channel_ratio(volume.extinction.y, extinction_reference, distance_value, scattered),
             openpbr_volume_channel_ratio(volume.extinction.z, extinction_reference, distance_value, scattered));
    const vec3 numerator = scattered ? ratio * volume.albedo : ratio;
    const float denominator = dot(probabilities, ratio);
    // A channel with P = 0 can get a large weight, but its throughput is 0; the clamp keeps the
    // weight finite for it.
    return denominator > OPENPBR_FLOAT_MIN_NORMAL ? openpbr_clamp_finite(numerator / denominator, 0.0f, OPENPBR_FLOAT_MAX)
                                                  : vec3(0.0f);
}

// Samples where the path, travelling a segment of length t_max (e.g. to the next surface hit;
// +inf is allowed) through the medium, scatters next. u_channel picks the channel in
// proportion to `throughput`, u_distance the exponential free flight of that channel
// (t = -ln(1 - u) / sigma_t,c). The weight is the one-sample MIS estimator
// transmittance * sigma_s / pdf(t) for a scattering event, and transmittance / P(pass) when
// the flight reaches t_max; it has the expectation of the exact per-channel transport. The
// phase function is not included (sample it next; HG sampling has weight 1).
OPENPBR_FUNC OpenPBR_VolumeDistanceSample openpbr_volume_sample_distance(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                                         vec3 throughput, float t_max, float u_channel,
                                                                         float u_distance)
{
    OpenPBR_VolumeDistanceSample result;
    const float segment = openpbr_volume_clamp_distance(t_max);
    result.distance = segment;
    result.scattered = false;
    result.weight = vec3(1.0f);
    result.pdf = 1.0f;
    if (!volume.is_present)
    {
        return result;
    }
    const vec3 probabilities = openpbr_volume_channel_probabilities(throughput);
    // Channel by inverting the discrete CDF. Rounding can put u past p.x + p.y when p.z = 0;
    // such a u falls back to the last channel with a positive probability.
    const float u = openpbr_clamp_finite(u_channel, 0.0f, 1.0f);
    const bool pick_x = u < probabilities.x || (probabilities.y <= 0.0f && probabilities.z <= 0.0f);
    const bool pick_y = !pick_x && (u < probabilities.x + probabilities.y || probabilities.z <= 0.0f);
    const float extinction_picked = pick_x ? volume.extinction.x : (pick_y ? volume.extinction.y : volume.extinction.z);
    // A denormal extinction is 0 on GPUs that flush denormals: treat it as 0 everywhere.
    const float extinction_channel = extinction_picked > OPENPBR_FLOAT_MIN_NORMAL ? extinction_picked : 0.0f;

    // Optical depth of the free flight, -ln(1 - u); the max keeps it finite (<= about 69) for u = 1.
    const float flight_optical_depth =
        -log(max(1.0f - openpbr_clamp_finite(u_distance, 0.0f, 1.0f), OPENPBR_VOLUME_TRANSMITTANCE_MIN));
    // Compare optical depths rather than distances, so sigma_t,c = 0 needs no division: it
    // never scatters.
    result.scattered = flight_optical_depth < extinction_channel * segment;
    if (result.scattered)
    {
        result.distance = flight_optical_depth / extinction_channel;
    }
    // The weight divided through by the drawn channel's own density (or transmittance): the
    // denominator is then >= P(c) > 0, so the weight stays finite where the absolute pdf
    // underflows (e.g. a flight of optical depth 69 in a medium with sigma_t = 1e-18).
    result.weight =
        openpbr_volume_flight_weight(volume, probabilities, extinction_channel, result.distance, result.scattered);
    // The absolute pdf, for MIS with other distance samplers; it may underflow to 0 for
    // extremely long flights, where the weight above is still exact.
    result.pdf = openpbr_volume_distance_pdf(volume, throughput, result.distance, result.scattered);
    return result;
}

OPENPBR_NAMESPACE_END

#endif
