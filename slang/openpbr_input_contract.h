// The input contract (README "Input contract"): every field of OpenPBR_ResolvedInputs has a
// valid range, and openpbr_prepare clamps to it. NaN maps to the field's default, +-inf to the
// nearer bound, so no out-of-range or non-finite input can produce NaN, negative values or
// energy gain downstream. The C++ build can report each clamp through OPENPBR_CLAMP_HOOK.
#ifndef OPENPBR_INPUT_CONTRACT_H
#define OPENPBR_INPUT_CONTRACT_H

#include "openpbr_resolved_inputs.h"

// IORs are clamped to the range the energy-compensation tables cover, e.g. 1.5 stays 1.5,
// 0.2 becomes 1/3, 5 becomes 3.
#define OPENPBR_IOR_MIN 0.33333334f
#define OPENPBR_IOR_MAX 3.0f
// Lengths are clamped far above any scene scale, so products with them stay finite.
#define OPENPBR_LENGTH_MAX 1e18f
// Emission up to 1e18 nits; beyond that a float sum of a few samples could overflow.
#define OPENPBR_LUMINANCE_MAX 1e18f
// specular_weight may exceed 1 (spec range [0, inf)); 1e6 is far past where the modulated IOR
// saturates (xi_s is further clamped to 1/F_s in prepare).
#define OPENPBR_SPECULAR_WEIGHT_MAX 1e6f
// Abbe number: a value near 0 means unbounded dispersion; 1 still bends blue far from red.
#define OPENPBR_ABBE_MIN 1.0f
#define OPENPBR_ABBE_MAX 1e6f

// OPENPBR_CLAMP_HOOK(field_name, value_before, value_after) is called for every clamp that
// changes a value, in the C++ build only, when the application defines it (e.g. to assert).
#if defined(OPENPBR_CLAMP_HOOK) && (defined(OPENPBR_LANGUAGE_TARGET_CPP))
#define OPENPBR_REPORT_CLAMP(field, before, after) \
    if (!((before) == (after))) { OPENPBR_CLAMP_HOOK(#field, before, after); }
#else
#define OPENPBR_REPORT_CLAMP(field, before, after)
#endif

OPENPBR_NAMESPACE_BEGIN

// NaN -> fallback, otherwise clamp to [low, high].
OPENPBR_FUNC float openpbr_contract_float(float value, float low, float high, float fallback)
{
    return (value == value) ? clamp(value, low, high) : fallback;
}

OPENPBR_FUNC vec3 openpbr_contract_color(vec3 value, float low, float high, vec3 fallback)
{
    return vec3(openpbr_contract_float(value.x, low, high, fallback.x),
                openpbr_contract_float(value.y, low, high, fallback.y),
                openpbr_contract_float(value.z, low, high, fallback.z));
}

#define OPENPBR_CONTRACT_FLOAT(field, low, high)                                                  \
    {                                                                                             \
        const float before = inputs.field;                                                        \
        result.field = openpbr_contract_float(before, low, high, defaults.field);                 \
        OPENPBR_REPORT_CLAMP(field, before, result.field)                                        \
    }
#define OPENPBR_CONTRACT_COLOR(field, low, high)                                                  \
    {                                                                                             \
        result.field = openpbr_contract_color(inputs.field, low, high, defaults.field);           \
        OPENPBR_REPORT_CLAMP(field, inputs.field.x, result.field.x)                              \
        OPENPBR_REPORT_CLAMP(field, inputs.field.y, result.field.y)                              \
        OPENPBR_REPORT_CLAMP(field, inputs.field.z, result.field.z)                              \
    }

OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_apply_input_contract(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs)
{
    const OpenPBR_ResolvedInputs defaults = openpbr_make_default_resolved_inputs();
    OpenPBR_ResolvedInputs result = inputs;
    OPENPBR_CONTRACT_FLOAT(base_weight, 0.0f, 1.0f)
    OPENPBR_CONTRACT_COLOR(base_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(base_diffuse_roughness, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(base_metalness, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(specular_weight, 0.0f, OPENPBR_SPECULAR_WEIGHT_MAX)
    OPENPBR_CONTRACT_COLOR(specular_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(specular_roughness, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(specular_roughness_anisotropy, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(specular_ior, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX)
    OPENPBR_CONTRACT_FLOAT(transmission_weight, 0.0f, 1.0f)
    OPENPBR_CONTRACT_COLOR(transmission_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(transmission_depth, 0.0f, OPENPBR_LENGTH_MAX)
    OPENPBR_CONTRACT_COLOR(transmission_scatter, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(transmission_scatter_anisotropy, -1.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(transmission_dispersion_scale, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(transmission_dispersion_abbe_number, OPENPBR_ABBE_MIN, OPENPBR_ABBE_MAX)
    OPENPBR_CONTRACT_FLOAT(subsurface_weight, 0.0f, 1.0f)
    OPENPBR_CONTRACT_COLOR(subsurface_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(subsurface_radius, 0.0f, OPENPBR_LENGTH_MAX)
    OPENPBR_CONTRACT_COLOR(subsurface_radius_scale, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(subsurface_scatter_anisotropy, -1.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(fuzz_weight, 0.0f, 1.0f)
    OPENPBR_CONTRACT_COLOR(fuzz_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(fuzz_roughness, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(coat_weight, 0.0f, 1.0f)
    OPENPBR_CONTRACT_COLOR(coat_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(coat_roughness, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(coat_roughness_anisotropy, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(coat_ior, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX)
    OPENPBR_CONTRACT_FLOAT(coat_darkening, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(thin_film_weight, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(thin_film_thickness, 0.0f, OPENPBR_LENGTH_MAX)
    OPENPBR_CONTRACT_FLOAT(thin_film_ior, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX)
    OPENPBR_CONTRACT_FLOAT(emission_luminance, 0.0f, OPENPBR_LUMINANCE_MAX)
    OPENPBR_CONTRACT_COLOR(emission_color, 0.0f, 1.0f)
    OPENPBR_CONTRACT_FLOAT(geometry_opacity, 0.0f, 1.0f)
    // Bases: re-orthonormalized (a degenerate tangent falls back to a frame from the normal).
    result.geometry_basis = openpbr_rotate_basis(
        openpbr_make_basis(inputs.geometry_basis.normal, inputs.geometry_basis.tangent, inputs.geometry_basis.bitangent),
        inputs.specular_anisotropy_rotation);
    // A coat of weight 0 is never looked at (prepare, eval and sample read its frame only where
    // coat_weight > 0; the fuzz frame blends it in by coat_weight), so it takes the base frame
    // instead of a second re-orthonormalization (a fifth of the default material's prepare).
    result.geometry_coat_basis =
        result.coat_weight > 0.0f
            ? openpbr_rotate_basis(openpbr_make_basis(inputs.geometry_coat_basis.normal, inputs.geometry_coat_basis.tangent,
                                                      inputs.geometry_coat_basis.bitangent),
                                   inputs.coat_anisotropy_rotation)
            : result.geometry_basis;
    result.specular_anisotropy_rotation = vec2(1.0f, 0.0f);
    result.coat_anisotropy_rotation = vec2(1.0f, 0.0f);
    return result;
}

#undef OPENPBR_CONTRACT_FLOAT
#undef OPENPBR_CONTRACT_COLOR

// The absolute IOR of the medium the surface sits in (openpbr_prepare's exterior_ior), e.g. 1
// for air, 1.33 for water: NaN becomes 1, the rest is clamped to the IOR range. Every interface
// then works with a relative IOR (material IOR / exterior IOR), itself clamped to
// [OPENPBR_IOR_MIN, OPENPBR_IOR_MAX] (openpbr_relative_ior).
OPENPBR_FUNC float openpbr_contract_exterior_ior(float exterior_ior)
{
    return openpbr_contract_float(exterior_ior, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX, 1.0f);
}

// n_inside / n_outside, clamped to the range the compensation tables cover: e.g. 1.5 / 1.33 =
// 1.128, 1.33 / 1.5 = 0.887, 3 / (1/3) = 9 becomes 3.
OPENPBR_FUNC float openpbr_relative_ior(float inside_ior, float outside_ior)
{
    return clamp(inside_ior / outside_ior, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX);
}

OPENPBR_NAMESPACE_END

#endif
