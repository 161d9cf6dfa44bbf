// OpenPBR Surface 1.1.1 parameters after texture/graph evaluation ("resolved"), one field per
// parameter of the specification (docs/spec-notes.md section 1, spec "Parameter reference"),
// plus geometry bases and two anisotropy-rotation extensions, declared from the parameter
// table (openpbr_parameters.h), which gives each field's type, default, range and units.
// openpbr_prepare clamps every field to the range documented in README "Input contract".
#ifndef OPENPBR_RESOLVED_INPUTS_H
#define OPENPBR_RESOLVED_INPUTS_H

#include "math/openpbr_basis.h"
#include "openpbr_parameters.h"

OPENPBR_NAMESPACE_BEGIN

// One field per entry of OPENPBR_PARAMETERS (openpbr_parameters.h: type, default, range and
// MaterialX name of each), in table order.
#define OPENPBR_DECLARE_FLOAT(name, default_value, low, high) float name;
#define OPENPBR_DECLARE_COLOR(name, default_r, default_g, default_b, low, high) vec3 name;
#define OPENPBR_DECLARE_VECTOR2(name, default_x, default_y) vec2 name;
#define OPENPBR_DECLARE_BOOL(name, default_value) bool name;
#define OPENPBR_DECLARE_BASIS(name, normal_input, tangent_input) OpenPBR_Basis name;

struct OpenPBR_ResolvedInputs
{
    OPENPBR_PARAMETERS(OPENPBR_DECLARE_FLOAT, OPENPBR_DECLARE_COLOR, OPENPBR_DECLARE_VECTOR2, OPENPBR_DECLARE_BOOL,
                       OPENPBR_DECLARE_BASIS)
};

#undef OPENPBR_DECLARE_FLOAT
#undef OPENPBR_DECLARE_COLOR
#undef OPENPBR_DECLARE_VECTOR2
#undef OPENPBR_DECLARE_BOOL
#undef OPENPBR_DECLARE_BASIS

#define OPENPBR_DEFAULT_FLOAT(name, default_value, low, high) inputs.name = default_value;
#define OPENPBR_DEFAULT_COLOR(name, default_r, default_g, default_b, low, high) \
    inputs.name = vec3(default_r, default_g, default_b);
#define OPENPBR_DEFAULT_VECTOR2(name, default_x, default_y) inputs.name = vec2(default_x, default_y);
#define OPENPBR_DEFAULT_BOOL(name, default_value) inputs.name = default_value;
#define OPENPBR_DEFAULT_BASIS(name, normal_input, tangent_input)

OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_make_default_resolved_inputs()
{
    OpenPBR_ResolvedInputs inputs;
    OPENPBR_PARAMETERS(OPENPBR_DEFAULT_FLOAT, OPENPBR_DEFAULT_COLOR, OPENPBR_DEFAULT_VECTOR2, OPENPBR_DEFAULT_BOOL,
                       OPENPBR_DEFAULT_BASIS)
    // geometry_basis (geometry_normal / geometry_tangent) defaults to the +z frame.
    // openpbr_make_basis(+z) is written out as the constants it returns (zero signs included):
    // the input contract builds these defaults in every prepare, and the call was not folded.
    inputs.geometry_basis.tangent = vec3(1.0f, -0.0f, -0.0f);
    inputs.geometry_basis.bitangent = vec3(-0.0f, 1.0f, -0.0f);
    inputs.geometry_basis.normal = vec3(0.0f, 0.0f, 1.0f);
    // geometry_coat_basis (geometry_coat_normal / geometry_coat_tangent) defaults to all zero,
    // meaning "the coat follows geometry_basis" (resolved in the input contract), so setting
    // only geometry_basis tilts the coat with the base; set it, e.g.
    // openpbr_make_basis(coat_normal, coat_tangent, 1.0f), for a coat frame of its own (spec
    // "Coat": the coat normal defaults to the geometry normal).
    inputs.geometry_coat_basis.tangent = vec3(0.0f);
    inputs.geometry_coat_basis.bitangent = vec3(0.0f);
    inputs.geometry_coat_basis.normal = vec3(0.0f);
    return inputs;
}

#undef OPENPBR_DEFAULT_FLOAT
#undef OPENPBR_DEFAULT_COLOR
#undef OPENPBR_DEFAULT_VECTOR2
#undef OPENPBR_DEFAULT_BOOL
#undef OPENPBR_DEFAULT_BASIS

OPENPBR_NAMESPACE_END

#endif
