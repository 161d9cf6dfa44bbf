// The input contract (docs/api.md "Input contract"): every field of OpenPBR_ResolvedInputs has a
// valid range, and openpbr_prepare clamps to it. NaN maps to the field's default, +-inf to the
// nearer bound, so no out-of-range or non-finite input can produce NaN, negative values or
// energy gain downstream. The C++ build can report each clamp through OPENPBR_CLAMP_HOOK.
#ifndef OPENPBR_INPUT_CONTRACT_H
#define OPENPBR_INPUT_CONTRACT_H

#include "openpbr_resolved_inputs.h"

// The ranges are the parameter table's (openpbr_parameters.h), e.g. specular_ior to
// [OPENPBR_IOR_MIN, OPENPBR_IOR_MAX] = [1/3, 3].

// OPENPBR_CLAMP_HOOK(field_name, value_before, value_after) is called for every clamp that
// changes a value, in the C++ build only, when the application defines it (e.g. to assert).
#if defined(OPENPBR_CLAMP_HOOK) && (defined(OPENPBR_LANGUAGE_TARGET_CPP))
#define OPENPBR_REPORT_CLAMP(field, before, after) \
    if (!((before) == (after)))                    \
    {                                              \
        OPENPBR_CLAMP_HOOK(#field, before, after); \
    }
#else
#define OPENPBR_REPORT_CLAMP(field, before, after)
#endif

OPENPBR_NAMESPACE_BEGIN

// NaN -> fallback, otherwise clamp to [low, high].
OPENPBR_FUNC float openpbr_contract_float(float value, float low, float high, float fallback)
{
    return (value == value) ? OPENPBR_CONTRACT_CLAMP(value, low, high) : fallback;
}

OPENPBR_FUNC vec3 openpbr_contract_color(vec3 value, float low, float high, vec3 fallback)
{
    return vec3(openpbr_contract_float(value.x, low, high, fallback.x),
                openpbr_contract_float(value.y, low, high, fallback.y),
                openpbr_contract_float(value.z, low, high, fallback.z));
}

#define OPENPBR_CONTRACT_FLOAT(field, default_value, low, high)                   \
    {                                                                             \
        const float before = inputs.field;                                        \
        result.field = openpbr_contract_float(before, low, high, defaults.field); \
        OPENPBR_REPORT_CLAMP(field, before, result.field)                         \
    }
#define OPENPBR_CONTRACT_COLOR(field, default_r, default_g, default_b, low, high)       \
    {                                                                                   \
        result.field = openpbr_contract_color(inputs.field, low, high, defaults.field); \
        OPENPBR_REPORT_CLAMP(field, inputs.field.x, result.field.x)                     \
        OPENPBR_REPORT_CLAMP(field, inputs.field.y, result.field.y)                     \
        OPENPBR_REPORT_CLAMP(field, inputs.field.z, result.field.z)                     \
    }
// Booleans have no invalid value; the bases and rotations are handled after the table.
#define OPENPBR_CONTRACT_VECTOR2(field, default_x, default_y)
#define OPENPBR_CONTRACT_BOOL(field, default_value)
#define OPENPBR_CONTRACT_BASIS(field, normal_input, tangent_input)

OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_apply_input_contract(OPENPBR_IN(OpenPBR_ResolvedInputs) inputs)
{
    const OpenPBR_ResolvedInputs defaults = openpbr_make_default_resolved_inputs();
    OpenPBR_ResolvedInputs result = inputs;
    OPENPBR_PARAMETERS(OPENPBR_CONTRACT_FLOAT, OPENPBR_CONTRACT_COLOR, OPENPBR_CONTRACT_VECTOR2, OPENPBR_CONTRACT_BOOL,
                       OPENPBR_CONTRACT_BASIS)
    // Bases: re-orthonormalized (a degenerate tangent falls back to a frame from the normal).
    result.geometry_basis = openpbr_rotate_basis(
        openpbr_make_basis(inputs.geometry_basis.normal, inputs.geometry_basis.tangent, inputs.geometry_basis.bitangent),
        inputs.specular_anisotropy_rotation);
    // A coat of weight 0 is never looked at (prepare, eval and sample read its frame only where
    // coat_weight > 0; the fuzz frame blends it in by coat_weight), so it takes the base frame
    // instead of a second re-orthonormalization (a fifth of the default material's prepare).
    // The differentiable build keeps the coat's own frame at weight 0, so that the derivative
    // with respect to coat_weight there is that of the coat as it appears (docs/gradients.md,
    // "Zero weights"; with the base frame instead it was 2-10 times off where the two differ).
    // A coat basis left at its default (zero normal, openpbr_make_default_resolved_inputs)
    // follows geometry_basis (spec "Coat": geometry_coat_normal defaults to the geometry
    // normal), so a caller that sets only geometry_basis gets the same coat frame as one that
    // sets both to it; the coat's own anisotropy rotation still applies.
    const bool coat_basis_set = dot(inputs.geometry_coat_basis.normal, inputs.geometry_coat_basis.normal) > 0.0f;
    const OpenPBR_Basis coat_source_basis = coat_basis_set ? inputs.geometry_coat_basis : inputs.geometry_basis;
    result.geometry_coat_basis =
        (OPENPBR_AUTODIFF != 0 || result.coat_weight > 0.0f)
            ? openpbr_rotate_basis(
                  openpbr_make_basis(coat_source_basis.normal, coat_source_basis.tangent, coat_source_basis.bitangent),
                  inputs.coat_anisotropy_rotation)
            : result.geometry_basis;
    result.specular_anisotropy_rotation = vec2(1.0f, 0.0f);
    result.coat_anisotropy_rotation = vec2(1.0f, 0.0f);
    return result;
}

#undef OPENPBR_CONTRACT_FLOAT
#undef OPENPBR_CONTRACT_COLOR
#undef OPENPBR_CONTRACT_VECTOR2
#undef OPENPBR_CONTRACT_BOOL
#undef OPENPBR_CONTRACT_BASIS

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
