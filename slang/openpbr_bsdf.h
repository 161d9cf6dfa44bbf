// The OpenPBR 1.1 surface BSDF: prepare, eval, sample, pdf.
//
// Layering follows the specification's reduction to a mixture of lobes (spec "Reduction to a
// mixture of lobes", docs/spec-notes.md 2.3) with albedo scaling:
//   f_base   = lerp(f_dielectric, f_metal, M)
//   f_dielectric = f^R_specular + (1 - E[f^R_specular](wo)) f_diffuse
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
#include "openpbr_lut.h"
#include "lobes/openpbr_diffuse_lobe.h"
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

// Per-lobe selection probabilities, in a fixed order (the order of sampling).
#define OPENPBR_LOBE_SLOT_DIFFUSE 0
#define OPENPBR_LOBE_SLOT_SPECULAR 1
#define OPENPBR_LOBE_SLOT_METAL 2
#define OPENPBR_LOBE_SLOT_PASS_THROUGH 3
#define OPENPBR_LOBE_SLOT_COUNT 4

struct OpenPBR_PreparedBsdf
{
    OpenPBR_Basis basis;  // base shading frame, flipped to the view's side for two-sided surfaces
    vec3 view;            // view direction in the base frame
    vec3 view_world;
    float opacity;
    OpenPBR_DiffuseLobe diffuse;
    OpenPBR_MicrofacetReflectionLobe specular;
    OpenPBR_MicrofacetReflectionLobe metal;
    vec3 pass_through_weight;  // (1 - geometry_opacity): a delta transmission straight through
    // Selection probabilities (sum 1, or all 0 when nothing scatters); 0 for inactive lobes,
    // so eval skips them without evaluating anything.
    float probability_diffuse;
    float probability_specular;
    float probability_metal;
    float probability_pass_through;
    vec3 emission;  // attenuated emission luminance leaving towards the view, nits
};

// Albedo-table roughness of an anisotropic lobe seen from `view`: the projected roughness
// that Smith's Lambda uses, sqrt((ax^2 vx^2 + ay^2 vy^2) / (vx^2 + vy^2)).
OPENPBR_FUNC float openpbr_projected_alpha(vec2 alpha, vec3 view)
{
    const float sin2 = view.x * view.x + view.y * view.y;
    return sin2 > 1e-12f ? sqrt((openpbr_square(alpha.x * view.x) + openpbr_square(alpha.y * view.y)) / sin2)
                         : sqrt(alpha.x * alpha.y);
}

// Turquin 2019, "Practical multiple scattering compensation for microfacet models": scale the
// single-scattering lobe by 1 + F0 (1 - E) / E, E the F = 1 albedo of the same roughness.
OPENPBR_FUNC vec3 openpbr_multiple_scattering_compensation(vec3 f0, float mu, float alpha)
{
    const float albedo = max(openpbr_ggx_albedo(mu, alpha), 1e-3f);
    return vec3(1.0f) + f0 * ((1.0f - albedo) / albedo);
}

// OpenPBR 1.1 "Base Substrate", modulated IOR: specular_weight xi scales F0 through the IOR,
// eps = sgn(eta - 1) sqrt(xi F0(eta)), eta' = (1 + eps) / (1 - eps), xi clamped below 1/F0.
OPENPBR_FUNC float openpbr_modulated_ior(float eta, float specular_weight)
{
    const float f0 = openpbr_dielectric_f0(eta);
    const float xi = min(specular_weight, 0.9999f / max(f0, 1e-8f));
    const float epsilon = (eta >= 1.0f ? 1.0f : -1.0f) * sqrt(xi * f0);
    return (1.0f + epsilon) / (1.0f - epsilon);
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare_lobes(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs,
                                                        vec3 view_world)
{
    const OpenPBR_ResolvedInputs inputs = openpbr_apply_input_contract(raw_inputs);
    OpenPBR_PreparedBsdf bsdf;
    bsdf.view_world = openpbr_safe_normalize(view_world, inputs.geometry_basis.normal);
    bsdf.basis = inputs.geometry_basis;
    // Opaque surfaces are two-sided: a view from below sees the same surface mirrored.
    if (dot(bsdf.view_world, bsdf.basis.normal) < 0.0f)
    {
        bsdf.basis.normal = -bsdf.basis.normal;
        bsdf.basis.bitangent = -bsdf.basis.bitangent;
    }
    bsdf.view = openpbr_to_local(bsdf.basis, bsdf.view_world);
    bsdf.view.z = max(bsdf.view.z, 0.0f);
    const vec3 view = bsdf.view;
    const float mu = view.z;
    bsdf.opacity = inputs.geometry_opacity;

    const float metalness = inputs.base_metalness;
    const vec2 alpha = openpbr_ggx_alpha(inputs.specular_roughness, inputs.specular_roughness_anisotropy);
    const float table_alpha = openpbr_projected_alpha(alpha, view);
    const float opacity = inputs.geometry_opacity;

    // Dielectric specular reflection, tinted by specular_color (reflection from above only).
    const float eta = openpbr_modulated_ior(inputs.specular_ior, inputs.specular_weight);
    const OpenPBR_Fresnel dielectric_fresnel = openpbr_make_dielectric_fresnel(eta, inputs.specular_color);
    const vec3 specular_compensation =
        openpbr_multiple_scattering_compensation(vec3(openpbr_dielectric_f0(eta)), mu, table_alpha);
    const float dielectric_weight = opacity * (1.0f - metalness);
    bsdf.specular = openpbr_microfacet_reflection_lobe_init(specular_compensation * dielectric_weight, alpha,
                                                            dielectric_fresnel, OPENPBR_LOBE_ID_SPECULAR_REFLECTION, view);
    // E[f^R](wo): tinted albedo including the compensation; a mirror has albedo F(mu).
    const float reflection_albedo = bsdf.specular.is_delta ? openpbr_fresnel_dielectric(mu, eta)
                                                           : openpbr_dielectric_reflection_albedo(mu, table_alpha, eta);
    const vec3 specular_albedo = openpbr_saturate(inputs.specular_color * specular_compensation * reflection_albedo);

    // Diffuse under the specular layer: albedo scaling by (1 - E[f^R]).
    const vec3 diffuse_weight = (vec3(1.0f) - specular_albedo) * (dielectric_weight * inputs.base_weight);
    bsdf.diffuse = openpbr_diffuse_lobe_init(diffuse_weight, inputs.base_color, inputs.base_diffuse_roughness, 1.0f, view);

    // Metal: F82-tint Fresnel, F0 = base_weight base_color, scaled by specular_weight.
    const vec3 metal_f0 = inputs.base_weight * inputs.base_color;
    const OpenPBR_Fresnel metal_fresnel =
        openpbr_make_f82_fresnel(metal_f0, inputs.specular_color, vec3(min(inputs.specular_weight, 1.0f)));
    const vec3 metal_compensation = openpbr_multiple_scattering_compensation(metal_f0, mu, table_alpha);
    bsdf.metal = openpbr_microfacet_reflection_lobe_init(metal_compensation * (opacity * metalness), alpha,
                                                         metal_fresnel, OPENPBR_LOBE_ID_METAL, view);
    const vec3 metal_albedo = bsdf.metal.weight * openpbr_fresnel_evaluate(metal_fresnel, mu) *
                              (bsdf.metal.is_delta ? 1.0f : openpbr_ggx_albedo(mu, table_alpha));

    bsdf.pass_through_weight = vec3(1.0f - opacity);

    // Lobe selection proportional to each lobe's estimated albedo (luminance).
    const float diffuse_estimate = (inputs.base_weight > 0.0f) ? openpbr_luminance(bsdf.diffuse.albedo) : 0.0f;
    const float specular_estimate = dielectric_weight > 0.0f ? openpbr_luminance(specular_albedo) * dielectric_weight : 0.0f;
    const float metal_estimate = metalness > 0.0f ? openpbr_luminance(metal_albedo) : 0.0f;
    const float pass_through_estimate = 1.0f - opacity;
    const float total = diffuse_estimate + specular_estimate + metal_estimate + pass_through_estimate;
    const float inverse_total = total > 0.0f ? 1.0f / total : 0.0f;
    bsdf.probability_diffuse = diffuse_estimate * inverse_total;
    bsdf.probability_specular = specular_estimate * inverse_total;
    bsdf.probability_metal = metal_estimate * inverse_total;
    bsdf.probability_pass_through = pass_through_estimate * inverse_total;
    bsdf.emission = vec3(0.0f);
    return bsdf;
}

// Emission (spec "Emission"): emission_luminance x emission_color, in nits.
OPENPBR_FUNC vec3 openpbr_prepare_emission(OPENPBR_IN(OpenPBR_ResolvedInputs) raw_inputs, vec3 view_world)
{
    OPENPBR_UNUSED(view_world);
    const OpenPBR_ResolvedInputs inputs = openpbr_apply_input_contract(raw_inputs);
    return inputs.emission_color * inputs.emission_luminance * inputs.geometry_opacity;
}

OPENPBR_FUNC OpenPBR_PreparedBsdf openpbr_prepare(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_world)
{
    OpenPBR_PreparedBsdf bsdf = openpbr_prepare_lobes(inputs, view_world);
    bsdf.emission = openpbr_prepare_emission(inputs, view_world);
    return bsdf;
}

// Sum of the continuous lobes at one light direction, split into diffuse and specular.
OPENPBR_FUNC OpenPBR_DiffuseSpecular openpbr_eval_local(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 light)
{
    OpenPBR_DiffuseSpecular value;
    value.diffuse = vec3(0.0f);
    value.specular = vec3(0.0f);
    if (bsdf.probability_diffuse > 0.0f)
    {
        value.diffuse = openpbr_diffuse_lobe_eval(bsdf.diffuse, bsdf.view, light);
    }
    if (bsdf.probability_specular > 0.0f)
    {
        value.specular = value.specular + openpbr_microfacet_reflection_lobe_eval(bsdf.specular, bsdf.view, light);
    }
    if (bsdf.probability_metal > 0.0f)
    {
        value.specular = value.specular + openpbr_microfacet_reflection_lobe_eval(bsdf.metal, bsdf.view, light);
    }
    return value;
}

OPENPBR_FUNC float openpbr_pdf_local(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 light)
{
    float pdf = 0.0f;
    if (bsdf.probability_diffuse > 0.0f)
    {
        pdf += bsdf.probability_diffuse * openpbr_diffuse_lobe_pdf(bsdf.diffuse, bsdf.view, light);
    }
    if (bsdf.probability_specular > 0.0f)
    {
        pdf += bsdf.probability_specular * openpbr_microfacet_reflection_lobe_pdf(bsdf.specular, bsdf.view, light);
    }
    if (bsdf.probability_metal > 0.0f)
    {
        pdf += bsdf.probability_metal * openpbr_microfacet_reflection_lobe_pdf(bsdf.metal, bsdf.view, light);
    }
    return pdf;
}

OPENPBR_FUNC OpenPBR_DiffuseSpecular openpbr_eval(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 light_world)
{
    return openpbr_eval_local(bsdf, openpbr_to_local(bsdf.basis, light_world));
}

OPENPBR_FUNC float openpbr_pdf(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 light_world)
{
    return openpbr_pdf_local(bsdf, openpbr_to_local(bsdf.basis, light_world));
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

// u: three uniform numbers in [0, 1); u.z selects the lobe, (u.x, u.y) drive the lobe's warp.
OPENPBR_FUNC OpenPBR_BsdfSample openpbr_sample(OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 u)
{
    const vec2 u_direction = vec2(u.x, u.y);
    float selector = u.z;
    float probability = 0.0f;
    OpenPBR_LobeSample lobe_sample = openpbr_make_no_lobe_sample();
    bool is_diffuse_delta = false;
    if (selector < bsdf.probability_diffuse)
    {
        lobe_sample = openpbr_diffuse_lobe_sample(bsdf.diffuse, bsdf.view, u_direction);
        probability = bsdf.probability_diffuse;
    }
    else if ((selector -= bsdf.probability_diffuse) < bsdf.probability_specular)
    {
        lobe_sample = openpbr_microfacet_reflection_lobe_sample(bsdf.specular, bsdf.view, u_direction);
        probability = bsdf.probability_specular;
    }
    else if ((selector -= bsdf.probability_specular) < bsdf.probability_metal)
    {
        lobe_sample = openpbr_microfacet_reflection_lobe_sample(bsdf.metal, bsdf.view, u_direction);
        probability = bsdf.probability_metal;
    }
    else if (bsdf.probability_pass_through > 0.0f)
    {
        lobe_sample = openpbr_make_lobe_sample(-bsdf.view, openpbr_lobe_type(OPENPBR_LOBE_ID_PASS_THROUGH,
                                                                             OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_SPECULAR));
        lobe_sample.delta_weight = bsdf.pass_through_weight;
        probability = bsdf.probability_pass_through;
    }
    if (lobe_sample.lobe_type == OPENPBR_LOBE_TYPE_NONE || probability <= 0.0f)
    {
        return openpbr_make_no_sample();
    }
    OpenPBR_BsdfSample bsdf_sample;
    bsdf_sample.direction = openpbr_to_world(bsdf.basis, lobe_sample.direction);
    bsdf_sample.lobe_type = lobe_sample.lobe_type;
    if ((lobe_sample.lobe_type & OPENPBR_LOBE_TYPE_SPECULAR) != 0u)
    {
        // Delta lobe: the estimator is value / P(selecting the lobe).
        bsdf_sample.pdf = probability;
        bsdf_sample.weight.diffuse = is_diffuse_delta ? lobe_sample.delta_weight / probability : vec3(0.0f);
        bsdf_sample.weight.specular = is_diffuse_delta ? vec3(0.0f) : lobe_sample.delta_weight / probability;
        return bsdf_sample;
    }
    // One-sample MIS over the continuous lobes: weight = f(wi) / sum_j P_j pdf_j(wi), so the
    // weight equals eval / pdf at the returned direction by construction.
    const float pdf = openpbr_pdf_local(bsdf, lobe_sample.direction);
    if (!(pdf > 0.0f) || !(pdf <= OPENPBR_FLOAT_MAX))
    {
        return openpbr_make_no_sample();
    }
    const OpenPBR_DiffuseSpecular value = openpbr_eval_local(bsdf, lobe_sample.direction);
    const float inverse_pdf = 1.0f / pdf;
    bsdf_sample.pdf = pdf;
    bsdf_sample.weight.diffuse = value.diffuse * inverse_pdf;
    bsdf_sample.weight.specular = value.specular * inverse_pdf;
    return bsdf_sample;
}

OPENPBR_NAMESPACE_END

#endif
