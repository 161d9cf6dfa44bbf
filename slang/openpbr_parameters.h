// The OpenPBR Surface 1.1.1 parameter table (spec "Parameter reference"; docs/spec-notes.md
// section 1): every field of OpenPBR_ResolvedInputs, written once, with its type, default,
// valid range, MaterialX input name and packing slot. Everything that lists the parameters is
// an expansion of this table: the struct and its defaults (openpbr_resolved_inputs.h), the
// input contract clamps (openpbr_input_contract.h), the flat GPU packing
// (openpbr_material_packing.h), the MaterialX loader and the stability corpus reader (C++,
// host/scene/parameter_table.h). Adding a parameter is one line here plus the lobe code that
// reads it; tests/bsdf/test_parameter_table.cpp proves the expansions agree.
//
// Plain preprocessor only (no variadic macros, no stringizing), so the one table expands in
// every language the single source compiles to: C++, GLSL (glslang), Slang, HLSL, CUDA, Metal.
#ifndef OPENPBR_PARAMETERS_H
#define OPENPBR_PARAMETERS_H

// ---- Range bounds that are not 0 or 1 ----

// IORs are clamped to the range the energy-compensation tables cover, e.g. 1.5 stays 1.5,
// 0.2 becomes 1/3, 5 becomes 3.
#define OPENPBR_IOR_MIN 0.33333334f
#define OPENPBR_IOR_MAX 3.0f
// Lengths are clamped far above any scene scale, so products with them stay finite.
#define OPENPBR_LENGTH_MAX 1e18f
// Emission up to 1e18 nits; beyond that a float sum of a few samples could overflow.
#define OPENPBR_LUMINANCE_MAX 1e18f
// emission_color is an HDR multiplier (spec 1.1.1: [0, inf)^3, e.g. (4, 2, 1) from an HDR
// texture); up to 1e18 per channel, so emission_color x emission_luminance stays below 1e36 and
// a hundred such sums below the largest float (3.4e38).
#define OPENPBR_EMISSION_COLOR_MAX 1e18f
// specular_weight may exceed 1 (spec range [0, inf)); 1e6 is far past where the modulated IOR
// saturates (xi_s is further clamped to 1/F_s in prepare).
#define OPENPBR_SPECULAR_WEIGHT_MAX 1e6f
// Abbe number: a value near 0 means unbounded dispersion; 1 still bends blue far from red.
#define OPENPBR_ABBE_MIN 1.0f
#define OPENPBR_ABBE_MAX 1e6f

// ---- The table ----
//
// OPENPBR_PARAMETERS(FLOAT, COLOR, VECTOR2, BOOL, BASIS) calls one of its five arguments per
// parameter, in table order. Table order is the struct's field order, the specification's
// order and the packing order: a parameter's packing slot is the sum of the float counts of
// the entries above it (OPENPBR_PACKED_MATERIAL_FLOATS in openpbr_material_packing.h).
//
//   FLOAT(name, default, low, high)
//       one float; the contract clamps it to [low, high], NaN becomes the default.
//   COLOR(name, default_r, default_g, default_b, low, high)
//       a vec3 (three packed floats); each component clamped like a FLOAT.
//   BOOL(name, default)
//       a bool, packed as one float (0 or 1).
//   BASIS(name, normal_input, tangent_input)
//       an OpenPBR_Basis (nine packed floats: tangent, bitangent, normal), set from the two
//       MaterialX vector3 inputs normal_input and tangent_input; re-orthonormalized by the
//       contract. Defaults: the +z frame (openpbr_make_default_resolved_inputs).
//   VECTOR2(name, default_x, default_y)
//       a vec2 extension with no MaterialX input (two packed floats): an anisotropy rotation
//       about the normal as (cos, sin), e.g. (0, 1) for 90 degrees; applied to the matching
//       basis by the contract, (0, 0) means no rotation.
//
// The MaterialX input name of a FLOAT, COLOR or BOOL is its field name. Units: lengths in
// scene units, thin_film_thickness in micrometers, emission_luminance in nits (cd/m^2).
// Comments inside the macro are block comments: a line comment would swallow the next line.
#define OPENPBR_PARAMETERS(FLOAT, COLOR, VECTOR2, BOOL, BASIS)                               \
    /* Base (spec "Base Substrate"); base_diffuse_roughness is the EON sigma, 0 = Lambert */ \
    FLOAT(base_weight, 1.0f, 0.0f, 1.0f)                                                     \
    COLOR(base_color, 0.8f, 0.8f, 0.8f, 0.0f, 1.0f)                                          \
    FLOAT(base_diffuse_roughness, 0.0f, 0.0f, 1.0f)                                          \
    FLOAT(base_metalness, 0.0f, 0.0f, 1.0f)                                                  \
    /* Specular (dielectric and metal reflection) */                                         \
    FLOAT(specular_weight, 1.0f, 0.0f, OPENPBR_SPECULAR_WEIGHT_MAX)                          \
    COLOR(specular_color, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f)                                      \
    FLOAT(specular_roughness, 0.3f, 0.0f, 1.0f)                                              \
    FLOAT(specular_roughness_anisotropy, 0.0f, 0.0f, 1.0f)                                   \
    FLOAT(specular_ior, 1.5f, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX)                              \
    /* Transmission (translucent base); depth 0 means no medium */                           \
    FLOAT(transmission_weight, 0.0f, 0.0f, 1.0f)                                             \
    COLOR(transmission_color, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f)                                  \
    FLOAT(transmission_depth, 0.0f, 0.0f, OPENPBR_LENGTH_MAX)                                \
    COLOR(transmission_scatter, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f)                                \
    FLOAT(transmission_scatter_anisotropy, 0.0f, -1.0f, 1.0f)                                \
    FLOAT(transmission_dispersion_scale, 0.0f, 0.0f, 1.0f)                                   \
    FLOAT(transmission_dispersion_abbe_number, 20.0f, OPENPBR_ABBE_MIN, OPENPBR_ABBE_MAX)    \
    /* Subsurface; radius and radius_scale have no effect when thin-walled (spec 1.1.1) */   \
    FLOAT(subsurface_weight, 0.0f, 0.0f, 1.0f)                                               \
    COLOR(subsurface_color, 0.8f, 0.8f, 0.8f, 0.0f, 1.0f)                                    \
    FLOAT(subsurface_radius, 1.0f, 0.0f, OPENPBR_LENGTH_MAX)                                 \
    COLOR(subsurface_radius_scale, 1.0f, 0.5f, 0.25f, 0.0f, 1.0f)                            \
    FLOAT(subsurface_scatter_anisotropy, 0.0f, -1.0f, 1.0f)                                  \
    /* Fuzz */                                                                               \
    FLOAT(fuzz_weight, 0.0f, 0.0f, 1.0f)                                                     \
    COLOR(fuzz_color, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f)                                          \
    FLOAT(fuzz_roughness, 0.5f, 0.0f, 1.0f)                                                  \
    /* Coat */                                                                               \
    FLOAT(coat_weight, 0.0f, 0.0f, 1.0f)                                                     \
    COLOR(coat_color, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f)                                          \
    FLOAT(coat_roughness, 0.0f, 0.0f, 1.0f)                                                  \
    FLOAT(coat_roughness_anisotropy, 0.0f, 0.0f, 1.0f)                                       \
    FLOAT(coat_ior, 1.6f, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX)                                  \
    FLOAT(coat_darkening, 1.0f, 0.0f, 1.0f)                                                  \
    /* Thin film; thickness in micrometers */                                                \
    FLOAT(thin_film_weight, 0.0f, 0.0f, 1.0f)                                                \
    FLOAT(thin_film_thickness, 0.5f, 0.0f, OPENPBR_LENGTH_MAX)                               \
    FLOAT(thin_film_ior, 1.4f, OPENPBR_IOR_MIN, OPENPBR_IOR_MAX)                             \
    /* Emission; luminance in nits */                                                        \
    FLOAT(emission_luminance, 0.0f, 0.0f, OPENPBR_LUMINANCE_MAX)                             \
    COLOR(emission_color, 1.0f, 1.0f, 1.0f, 0.0f, OPENPBR_EMISSION_COLOR_MAX)                \
    /* Geometry */                                                                           \
    FLOAT(geometry_opacity, 1.0f, 0.0f, 1.0f)                                                \
    BOOL(geometry_thin_walled, false)                                                        \
    BASIS(geometry_basis, geometry_normal, geometry_tangent)                                 \
    BASIS(geometry_coat_basis, geometry_coat_normal, geometry_coat_tangent)                  \
    /* Extensions: rotation of the anisotropy direction about the normal */                  \
    VECTOR2(specular_anisotropy_rotation, 1.0f, 0.0f)                                        \
    VECTOR2(coat_anisotropy_rotation, 1.0f, 0.0f)

#endif
