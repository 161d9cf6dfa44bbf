// A renderer's shading step written against the established OpenPBR-BSDF API only: every call
// below uses the names and signatures of that API (docs/api.md "The established API form"), nothing of the
// project form. The same source is compiled as C++ (api_compat_main.cpp, -Wall -Wextra
// -Werror, run), GLSL (api_compat.comp), Slang (api_compat.slang, `import openpbr;`), HLSL
// (api_compat.hlsl over the generated openpbr.hlsl), CUDA (api_compat_device.cu, nvcc) and Metal
// (Slang's Metal output of api_compat.slang); tests/api_compat/CMakeLists.txt runs them.
//
// The includer defines API_COMPAT_WRITE(index, value), a float store into its result buffer,
// and includes this after the OpenPBR headers (Slang: after `import openpbr;` and the Slang
// backend's macros).
#ifndef API_COMPAT_PROGRAM_H
#define API_COMPAT_PROGRAM_H

// Floats written per call of api_compat_shade, e.g. 72.
#define API_COMPAT_RESULT_COUNT 72

OPENPBR_NAMESPACE_BEGIN

OPENPBR_FUNC void api_compat_write_vec3(uint index, vec3 value)
{
    API_COMPAT_WRITE(index, value.x);
    API_COMPAT_WRITE(index + 1u, value.y);
    API_COMPAT_WRITE(index + 2u, value.z);
}

// One shading step of a path tracer: prepare at a hit, evaluate a light, sample the BSDF, the
// staged preparation, the interior medium and the shadow shortcut. base: first result index.
OPENPBR_FUNC void api_compat_shade(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs, vec3 view_direction, vec3 light_to_evaluate,
                                   vec3 path_throughput, float exterior_ior, vec3 rand, vec2 medium_rand, uint base)
{
    const OpenPBR_PreparedBsdf prepared =
        openpbr_prepare(inputs, path_throughput, OpenPBR_BaseRgbWavelengths_nm, exterior_ior, view_direction);

    const OpenPBR_DiffuseSpecular value = openpbr_eval(prepared, light_to_evaluate);
    const float light_pdf = openpbr_pdf(prepared, light_to_evaluate);
    api_compat_write_vec3(base + 0u, value.diffuse);
    api_compat_write_vec3(base + 3u, value.specular);
    api_compat_write_vec3(base + 6u, openpbr_get_sum_of_diffuse_specular(value));
    API_COMPAT_WRITE(base + 9u, light_pdf);

    vec3 light_direction;
    OpenPBR_DiffuseSpecular weight;
    float pdf;
    OpenPBR_BsdfLobeType sampled_type;
    openpbr_sample(prepared, rand, light_direction, weight, pdf, sampled_type);
    api_compat_write_vec3(base + 10u, light_direction);
    api_compat_write_vec3(base + 13u, weight.diffuse);
    api_compat_write_vec3(base + 16u, weight.specular);
    API_COMPAT_WRITE(base + 19u, pdf);
    API_COMPAT_WRITE(base + 20u, float(sampled_type));
    api_compat_write_vec3(base + 21u, prepared.emission);

    // Staged preparation, in its order; the result must match the one-call prepare.
    OpenPBR_PreparedBsdf staged = prepared;
    openpbr_prepare_volume(staged, inputs);
    openpbr_prepare_lobes(staged, inputs, path_throughput, OpenPBR_BaseRgbWavelengths_nm, exterior_ior, view_direction);
    openpbr_prepare_emission(staged, inputs, exterior_ior, view_direction);
    api_compat_write_vec3(base + 24u, openpbr_get_sum_of_diffuse_specular(openpbr_eval(staged, light_to_evaluate)));
    API_COMPAT_WRITE(base + 27u, openpbr_pdf(staged, light_to_evaluate));
    api_compat_write_vec3(base + 28u, staged.emission);
    api_compat_write_vec3(base + 31u, staged.volume.extinction);

    // The interior medium: a flight to the next event, and the weights of both outcomes.
    const OpenPBR_HomogeneousVolume medium = prepared.volume;
    const float event_distance = openpbr_sample_event_distance(medium, path_throughput, medium_rand);
    api_compat_write_vec3(
        base + 34u, openpbr_calculate_weight_for_event_at_distance(medium, path_throughput, min(event_distance, 1.0f)));
    api_compat_write_vec3(base + 37u, openpbr_calculate_weight_for_surface_at_distance(medium, path_throughput, 0.5f));
    api_compat_write_vec3(base + 40u, openpbr_calculate_transmittance_at_distance(medium, 0.5f));
    api_compat_write_vec3(base + 43u, openpbr_calculate_transmittance_at_infinity(medium));
    API_COMPAT_WRITE(base + 46u, min(event_distance, 1.0e6f));

    const vec3 isotropic_direction = openpbr_sample_isotropic_phase_function(medium_rand);
    const vec3 anisotropic_direction = openpbr_sample_anisotropic_phase_function(medium, -view_direction, medium_rand);
    api_compat_write_vec3(base + 47u, isotropic_direction);
    api_compat_write_vec3(base + 50u, anisotropic_direction);
    API_COMPAT_WRITE(base + 53u, openpbr_calculate_isotropic_phase_function_value());
    API_COMPAT_WRITE(base + 54u, openpbr_calculate_isotropic_phase_function_pdf());
    API_COMPAT_WRITE(base + 55u,
                     openpbr_calculate_anisotropic_phase_function_value(medium, -view_direction, anisotropic_direction));
    API_COMPAT_WRITE(base + 56u,
                     openpbr_calculate_anisotropic_phase_function_pdf(medium, -view_direction, anisotropic_direction));

    // Media built by the renderer itself.
    const OpenPBR_HomogeneousVolume fog =
        openpbr_make_homogeneous_volume_from_extinction_and_albedo(vec3(0.5f, 1.0f, 2.0f), vec3(0.9f, 0.8f, 0.7f), 0.3f);
    const OpenPBR_HomogeneousVolume smoke = openpbr_make_homogeneous_volume_from_absorption_and_scattering(
        vec3(0.1f, 0.2f, 0.3f), vec3(1.0f, 1.0f, 1.0f), -0.2f);
    const OpenPBR_HomogeneousVolume ink = openpbr_make_homogeneous_volume_from_extinction(vec3(4.0f, 2.0f, 1.0f));
    api_compat_write_vec3(base + 57u, openpbr_calculate_transmittance_at_distance(fog, 1.0f));
    api_compat_write_vec3(base + 60u, smoke.albedo);
    api_compat_write_vec3(base + 63u, openpbr_calculate_transmittance_at_distance(ink, 0.25f));

    // Shadow rays through glass-like surfaces.
    vec3 shadow_weight;
    float shadow_probability;
    openpbr_translucent_shadow_weight_and_prob(prepared, shadow_weight, shadow_probability);
    api_compat_write_vec3(base + 66u, shadow_weight);
    API_COMPAT_WRITE(base + 69u, shadow_probability);
    API_COMPAT_WRITE(base + 70u, OpenPBR_VacuumIor);
    API_COMPAT_WRITE(base + 71u, OpenPBR_BaseRgbWavelengths_nm.x);
}

OPENPBR_NAMESPACE_END

#endif
