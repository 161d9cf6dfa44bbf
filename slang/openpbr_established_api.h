// The established OpenPBR-BSDF API: the names and signatures renderers already call (the public
// interface of the OpenPBR BSDF library renderers adopted first), each implemented through this
// project's own functions, so code written against that interface compiles here by changing
// the include path. Nothing here adds physics: every function forwards to, or rearranges the
// results of, the project-form API of openpbr_bsdf.h and openpbr_volume.h (README "Two API
// forms").
//
//   OpenPBR_PreparedBsdf prepared = openpbr_prepare(inputs, path_throughput, OpenPBR_BaseRgbWavelengths_nm,
//                                                   OpenPBR_VacuumIor, view_direction);
//   OpenPBR_DiffuseSpecular value = openpbr_eval(prepared, light_direction);  // BSDF x |cos|
//   float pdf = openpbr_pdf(prepared, light_direction);
//   openpbr_sample(prepared, rand, light_direction, weight, pdf, sampled_type); // pdf <= 0: no sample
//   vec3 color = openpbr_get_sum_of_diffuse_specular(value);
//
// Conventions are the project's (openpbr_bsdf.h): world-space unit directions pointing away
// from the surface; weight = BSDF x |cos| / pdf; delta lobes report their selection
// probability as pdf.
#ifndef OPENPBR_ESTABLISHED_API_H
#define OPENPBR_ESTABLISHED_API_H

#include "openpbr_bsdf.h"

OPENPBR_NAMESPACE_BEGIN

// ---------------------------------------------------------------------------------------------
// Constants.

// The wavelengths (nm) the R, G, B channels stand for in an RGB renderer: the dominant
// wavelengths of the working space's primaries (OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM), e.g. the
// rgb_wavelengths_nm of openpbr_prepare when the renderer does not trace spectra.
OPENPBR_GLOBAL_CONSTANT vec3 OpenPBR_BaseRgbWavelengths_nm = OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM;
// IOR of vacuum (and, to 3e-4, air): the exterior_ior of a surface in the open.
OPENPBR_GLOBAL_CONSTANT float OpenPBR_VacuumIor = 1.0f;

// ---------------------------------------------------------------------------------------------
// Preparation, evaluation, sampling.

// path_throughput: the path's throughput so far; it only steers lobe selection (probabilities
// proportional to luminance(throughput x lobe albedo), openpbr_selection_channel_weights);
// eval, pdf and sample stay unbiased for any value (vec3(1.0f): the unweighted selection of
// the project-form openpbr_prepare). exterior_ior: the IOR of the medium the surface is
// embedded in, e.g. OpenPBR_VacuumIor (1.33 under water): every interface sees the relative
// IOR (openpbr_prepare_lobes_of; NaN counts as 1, clamped to [1/3, 3]).
OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 path_throughput,
                                                  vec3 rgb_wavelengths_nm, float exterior_ior, vec3 view_direction)
{
    return openpbr_prepare_for_path(inputs, view_direction, rgb_wavelengths_nm, exterior_ior, path_throughput);
}

// Out-parameter form of the project's openpbr_sample(prepared, u): pdf <= 0 means no sample
// (then light_direction and weight are 0 and sampled_type is OPENPBR_LOBE_TYPE_NONE).
OPENPBR_FUNC void openpbr_sample(OPENPBR_IN(OpenPBR_PreparedBsdf) prepared, vec3 rand, OPENPBR_OUT(vec3) light_direction,
                                 OPENPBR_OUT(OpenPBR_DiffuseSpecular) weight, OPENPBR_OUT(float) pdf,
                                 OPENPBR_OUT(OpenPBR_BsdfLobeType) sampled_type)
{
    const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(prepared, rand);
    light_direction = bsdf_sample.direction;
    weight = bsdf_sample.weight;
    pdf = bsdf_sample.pdf;
    sampled_type = bsdf_sample.lobe_type;
}

// The total of a diffuse/specular split, e.g. the color an eval or a sample weight stands for.
OPENPBR_FUNC vec3 openpbr_get_sum_of_diffuse_specular(OPENPBR_IN(OpenPBR_DiffuseSpecular) value)
{
    return value.diffuse + value.specular;
}

// ---------------------------------------------------------------------------------------------
// Staged preparation: openpbr_prepare_volume, openpbr_prepare_lobes, openpbr_prepare_emission,
// in that order, fill the same OpenPBR_PreparedBsdf as one openpbr_prepare (bit for bit), e.g.
// to skip the emission of a path vertex that does not need it. Each fills only its fields:
// the volume stage `volume`; the lobe stage everything else, keeping `volume` and clearing
// `emission`; the emission stage `emission`.

OPENPBR_FUNC void openpbr_prepare_volume(OPENPBR_INOUT(OpenPBR_PreparedBsdf) prepared,
                                         OPENPBR_IN(OpenPBR_ResolvedInputs) inputs)
{
    prepared.volume = openpbr_prepare_volume(inputs);
}

OPENPBR_FUNC void openpbr_prepare_lobes(OPENPBR_INOUT(OpenPBR_PreparedBsdf) prepared,
                                        OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 path_throughput,
                                        vec3 rgb_wavelengths_nm, float exterior_ior, vec3 view_direction)
{
    const OpenPBR_HomogeneousVolume volume = prepared.volume;
    prepared = openpbr_prepare_lobes_of(openpbr_prepare_inputs(inputs), view_direction, rgb_wavelengths_nm,
                                        openpbr_contract_exterior_ior(exterior_ior), path_throughput);
    prepared.volume = volume;
}

OPENPBR_FUNC void openpbr_prepare_emission(OPENPBR_INOUT(OpenPBR_PreparedBsdf) prepared,
                                           OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, float exterior_ior,
                                           vec3 view_direction)
{
    prepared.emission = openpbr_prepare_emission(inputs, view_direction, exterior_ior);
}

// ---------------------------------------------------------------------------------------------
// Interior volume (openpbr_volume.h under the established names). A path inside the object
// samples the distance to its next event; an event before the next surface hit scatters
// (multiply the throughput by openpbr_calculate_weight_for_event_at_distance and sample the
// phase function), otherwise the path reaches the surface (multiply by
// openpbr_calculate_weight_for_surface_at_distance at the hit distance). path_throughput picks
// the channel each flight is drawn from (spectral MIS, Wilkie et al. 2014); pass the same value
// to the sampler and the weight.

// Homogeneous medium from per-channel extinction sigma_t (1/scene unit) and single-scattering
// albedo sigma_s / sigma_t, with Henyey-Greenstein anisotropy g. Clamped like the media prepare
// builds: extinction to [0, OPENPBR_VOLUME_EXTINCTION_MAX], albedo to [0, 1], |g| to
// OPENPBR_HG_ANISOTROPY_MAX; no extinction in any channel: no medium (is_present false).
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_homogeneous_volume_from_extinction_and_albedo(vec3 extinction,
                                                                                                  vec3 albedo,
                                                                                                  float anisotropy)
{
    OpenPBR_HomogeneousVolume volume;
    volume.extinction = openpbr_clamp_finite(extinction, 0.0f, OPENPBR_VOLUME_EXTINCTION_MAX);
    volume.albedo = openpbr_clamp_finite(albedo, 0.0f, 1.0f);
    volume.anisotropy = openpbr_henyey_greenstein_clamp_anisotropy(anisotropy);
    volume.is_present = openpbr_max3(volume.extinction) > OPENPBR_FLOAT_MIN_NORMAL;
    return volume.is_present ? volume : openpbr_make_empty_volume();
}

// From absorption sigma_a and scattering sigma_s (each >= 0, 1/scene unit): sigma_t = sigma_a +
// sigma_s, albedo sigma_s / sigma_t (0 where sigma_t is 0).
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_homogeneous_volume_from_absorption_and_scattering(vec3 absorption,
                                                                                                      vec3 scattering,
                                                                                                      float anisotropy)
{
    const vec3 absorbing = openpbr_clamp_finite(absorption, 0.0f, OPENPBR_VOLUME_EXTINCTION_MAX);
    const vec3 scattering_clamped = openpbr_clamp_finite(scattering, 0.0f, OPENPBR_VOLUME_EXTINCTION_MAX);
    const vec3 extinction = absorbing + scattering_clamped;
    const vec3 albedo = vec3(extinction.x > OPENPBR_FLOAT_MIN_NORMAL ? scattering_clamped.x / extinction.x : 0.0f,
                             extinction.y > OPENPBR_FLOAT_MIN_NORMAL ? scattering_clamped.y / extinction.y : 0.0f,
                             extinction.z > OPENPBR_FLOAT_MIN_NORMAL ? scattering_clamped.z / extinction.z : 0.0f);
    return openpbr_make_homogeneous_volume_from_extinction_and_albedo(extinction, albedo, anisotropy);
}

// A purely absorbing medium (albedo 0), e.g. tinted glass: transmittance only.
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_make_homogeneous_volume_from_extinction(vec3 extinction)
{
    return openpbr_make_homogeneous_volume_from_extinction_and_albedo(extinction, vec3(0.0f), 0.0f);
}

// Distance to the next event of a flight through the medium (scene units): rand.x picks the
// channel in proportion to path_throughput, rand.y the free flight. A channel without
// extinction never has an event: OPENPBR_FLOAT_MAX (beyond any surface hit). No medium: the
// same.
OPENPBR_FUNC float openpbr_sample_event_distance(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume, vec3 path_throughput,
                                                 vec2 rand)
{
    return openpbr_volume_sample_distance(volume, path_throughput, OPENPBR_FLOAT_MAX, rand.x, rand.y).distance;
}

// The channel whose term dominates the MIS denominator at `distance_value` (P_k sigma_k T_k for
// an event, P_k T_k for a pass), found on logarithms; its extinction is the reference that
// keeps openpbr_volume_flight_weight finite. -1 extinction: no channel can have the event.
OPENPBR_FUNC float openpbr_volume_reference_extinction(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume, vec3 probabilities,
                                                       float distance_value, bool scattered)
{
    float best_score = -OPENPBR_FLOAT_MAX;
    float best_extinction = -1.0f;
    for (int channel = 0; channel < 3; ++channel)
    {
        const float probability = channel == 0 ? probabilities.x : (channel == 1 ? probabilities.y : probabilities.z);
        const float extinction =
            channel == 0 ? volume.extinction.x : (channel == 1 ? volume.extinction.y : volume.extinction.z);
        const bool usable = probability > 0.0f && (!scattered || extinction > OPENPBR_FLOAT_MIN_NORMAL);
        const float score = log(max(probability, OPENPBR_FLOAT_MIN_NORMAL)) +
                            (scattered ? log(max(extinction, OPENPBR_FLOAT_MIN_NORMAL)) : 0.0f) -
                            extinction * distance_value;
        if (usable && score > best_score)
        {
            best_score = score;
            best_extinction = extinction;
        }
    }
    return best_extinction;
}

// Throughput factor of an event at distance_value drawn by openpbr_sample_event_distance with
// the same path_throughput: transmittance x sigma_s / pdf(distance), per channel (the phase
// function is sampled next, with weight 1).
OPENPBR_FUNC vec3 openpbr_calculate_weight_for_event_at_distance(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                                 vec3 path_throughput, float distance_value)
{
    if (!volume.is_present)
    {
        return vec3(0.0f);
    }
    const float distance_clamped = openpbr_volume_clamp_distance(distance_value);
    const vec3 probabilities = openpbr_volume_channel_probabilities(path_throughput);
    const float reference = openpbr_volume_reference_extinction(volume, probabilities, distance_clamped, true);
    return reference < 0.0f ? vec3(0.0f)
                            : openpbr_volume_flight_weight(volume, probabilities, reference, distance_clamped, true);
}

// Throughput factor of a flight that reaches a surface at distance_value without an event:
// transmittance / P(no event before distance_value), per channel.
OPENPBR_FUNC vec3 openpbr_calculate_weight_for_surface_at_distance(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                                   vec3 path_throughput, float distance_value)
{
    if (!volume.is_present)
    {
        return vec3(1.0f);
    }
    const float distance_clamped = openpbr_volume_clamp_distance(distance_value);
    const vec3 probabilities = openpbr_volume_channel_probabilities(path_throughput);
    const float reference = openpbr_volume_reference_extinction(volume, probabilities, distance_clamped, false);
    return openpbr_volume_flight_weight(volume, probabilities, reference, distance_clamped, false);
}

// Beer-Lambert transmittance exp(-sigma_t d) per channel (1 without a medium).
OPENPBR_FUNC vec3 openpbr_calculate_transmittance_at_distance(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                              float distance_value)
{
    return openpbr_volume_transmittance(volume, distance_value);
}

// Transmittance of an unbounded flight: 0 in every channel with extinction, 1 elsewhere.
OPENPBR_FUNC vec3 openpbr_calculate_transmittance_at_infinity(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume)
{
    return openpbr_volume_transmittance(volume, OPENPBR_FLOAT_MAX);
}

// Isotropic phase function: a uniform direction on the sphere, value = pdf = 1 / (4 pi).
OPENPBR_FUNC vec3 openpbr_sample_isotropic_phase_function(vec2 rand) { return openpbr_isotropic_phase_sample(rand); }
OPENPBR_FUNC float openpbr_calculate_isotropic_phase_function_value() { return openpbr_isotropic_phase_eval(); }
OPENPBR_FUNC float openpbr_calculate_isotropic_phase_function_pdf() { return openpbr_isotropic_phase_eval(); }

// Henyey-Greenstein phase function of the medium (g = volume.anisotropy). Directions are
// propagation directions (openpbr_volume.h): incoming_direction is the way the path arrived,
// outgoing_direction the way it leaves; g > 0 scatters forward. Sampling is exact: value = pdf.
OPENPBR_FUNC vec3 openpbr_sample_anisotropic_phase_function(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                            vec3 incoming_direction, vec2 rand)
{
    return openpbr_henyey_greenstein_sample(volume.anisotropy, incoming_direction, rand);
}
OPENPBR_FUNC float openpbr_calculate_anisotropic_phase_function_value(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                                      vec3 incoming_direction, vec3 outgoing_direction)
{
    return openpbr_henyey_greenstein_eval(volume.anisotropy, dot(incoming_direction, outgoing_direction));
}
OPENPBR_FUNC float openpbr_calculate_anisotropic_phase_function_pdf(OPENPBR_IN(OpenPBR_HomogeneousVolume) volume,
                                                                    vec3 incoming_direction, vec3 outgoing_direction)
{
    return openpbr_calculate_anisotropic_phase_function_value(volume, incoming_direction, outgoing_direction);
}

// ---------------------------------------------------------------------------------------------
// Straight-through shadow rays (a practical, biased shortcut).
//
// A shadow ray that hits a transmissive or subsurface surface is blocked in an unbiased path
// tracer (the light reaches the point behind only along refracted paths, found by BSDF
// sampling). This shortcut lets it pass straight on instead: at each crossing, continue with
// probability `probability`, multiplying the shadow ray's throughput by `weight` (else the
// ray is blocked); between the crossings of a closed object multiply by
// openpbr_calculate_transmittance_at_distance(prepared.volume, segment length). The expected
// factor of one crossing, probability x weight, is the surface's straight transmission: the
// pass-through of opacity < 1, plus the energy its transmission lobes send across the
// interface ((1 - E_R) x tint x coat, fuzz and opacity factors when entering; the Fresnel
// transmittance 1 - F at the exterior angle when leaving). `probability` is the selection
// probability of those lobes, so a mostly opaque material stops most shadow rays early.
// Prepare with view_direction = -(shadow ray direction), as for a path arriving along it.
//
// Its bias (tests/api_compat/test_established_api.cpp measures it against a path-traced slab):
//   - no refraction: the ray is not bent, so the light is found along the wrong line of sight
//     (fine for thin parallel slabs, e.g. windows, where it exits parallel; wrong for lenses,
//     whose caustics it misses), and the interior segment is the straight one (L / cos of the
//     exterior angle instead of the refracted angle: more absorption at oblique incidence);
//   - no internal reflections: the light bounced between the two faces is lost, a factor
//     1 - R^2 T^2 on a smooth slab (0.2 % for clear glass of IOR 1.5 at normal incidence);
//   - rough interfaces send their whole transmission straight on (the blur is lost; the energy
//     is kept to the albedo tables' accuracy);
//   - subsurface and scattering media: the segment's transmittance counts scattering as loss,
//     so the in-scattered light is missing (darker shadows than the path-traced ones).
// Thin-walled surfaces have no interior: the un-deflected transmission is exact for a smooth
// sheet; the diffuse transmission of a thin subsurface sheet is not straight and is left out.
OPENPBR_FUNC void openpbr_translucent_shadow_weight_and_prob(OPENPBR_IN(OpenPBR_PreparedBsdf) prepared,
                                                             OPENPBR_OUT(vec3) weight, OPENPBR_OUT(float) probability)
{
    const float mu = prepared.view.z;
    vec3 straight = prepared.pass_through_weight;
    float straight_probability = prepared.probability_pass_through;
    if (prepared.probability_transmission > 0.0f)
    {
        const OpenPBR_DielectricLobe lobe = prepared.transmission;
        const float table_alpha = sqrt(0.5f * (lobe.alpha.x * lobe.alpha.x + lobe.alpha.y * lobe.alpha.y));
        if (prepared.inside)
        {
            // Leaving: the lobe's weight carries the exit factors and 1 / E_RT; the straight
            // crossing transmits 1 - F at the exterior angle (the same as 1 - F at the refracted
            // interior angle, Fresnel's reciprocity), so it never meets total internal reflection.
            const float compensation_undone =
                lobe.is_delta ? 1.0f
                              : openpbr_dielectric_compensation_albedo(mu, table_alpha, lobe.eta.y, lobe.lambda_view, true);
            straight += lobe.transmission_weight *
                        (compensation_undone * (1.0f - openpbr_fresnel_dielectric(mu, 1.0f / lobe.eta.y)));
        }
        else
        {
            // Entering: the lobe's weight is (1 - E_R) x tint x 1 / E_T0 (openpbr_prepare_lobes_of).
            const float compensation_undone =
                lobe.is_delta ? 1.0f
                              : openpbr_dielectric_compensation_albedo(mu, table_alpha, lobe.eta.y, lobe.lambda_view, false);
            straight += lobe.transmission_weight * compensation_undone * prepared.under_coat_transmitted;
        }
        straight_probability += prepared.probability_transmission;
    }
    if (prepared.probability_thin_transmission > 0.0f)
    {
        const OpenPBR_MicrofacetReflectionLobe lobe = prepared.thin_transmission;
        const float table_alpha = sqrt(0.5f * (lobe.alpha.x * lobe.alpha.x + lobe.alpha.y * lobe.alpha.y));
        const float compensation_undone = lobe.is_delta ? 1.0f : max(openpbr_ggx_albedo(mu, table_alpha), 0.05f);
        straight += lobe.weight * compensation_undone * prepared.under_coat_transmitted;
        straight_probability += prepared.probability_thin_transmission;
    }
    probability = min(straight_probability, 1.0f);
    weight = probability > 0.0f ? straight / probability : vec3(0.0f);
}

OPENPBR_NAMESPACE_END

#endif
