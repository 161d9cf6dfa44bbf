// OpenPBR Surface 1.1 parameters after texture/graph evaluation ("resolved"), one field per
// parameter of the specification (docs/spec-notes.md section 1, spec "Parameter reference"),
// plus geometry bases and two anisotropy-rotation extensions. Units: lengths in scene units,
// thin_film_thickness in micrometers, emission_luminance in nits (cd/m^2).
// openpbr_prepare clamps every field to the range documented in README "Input contract".
#ifndef OPENPBR_RESOLVED_INPUTS_H
#define OPENPBR_RESOLVED_INPUTS_H

#include "math/openpbr_basis.h"

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_ResolvedInputs
{
    // Base (spec "Base Substrate")
    float base_weight;             // [0,1], default 1
    vec3 base_color;               // [0,1]^3, default (0.8, 0.8, 0.8)
    float base_diffuse_roughness;  // [0,1], default 0 (EON sigma; 0 = Lambert)
    float base_metalness;          // [0,1], default 0

    // Specular (dielectric and metal reflection)
    float specular_weight;                // [0,inf), default 1
    vec3 specular_color;                  // [0,1]^3, default (1, 1, 1)
    float specular_roughness;             // [0,1], default 0.3
    float specular_roughness_anisotropy;  // [0,1], default 0
    float specular_ior;                   // (0,inf), default 1.5

    // Transmission (translucent base)
    float transmission_weight;                  // [0,1], default 0
    vec3 transmission_color;                    // [0,1]^3, default (1, 1, 1)
    float transmission_depth;                   // [0,inf) scene units, default 0 (no medium)
    vec3 transmission_scatter;                  // [0,1]^3, default (0, 0, 0)
    float transmission_scatter_anisotropy;      // [-1,1], default 0
    float transmission_dispersion_scale;        // [0,1], default 0
    float transmission_dispersion_abbe_number;  // (0,inf), default 20

    // Subsurface
    float subsurface_weight;              // [0,1], default 0
    vec3 subsurface_color;                // [0,1]^3, default (0.8, 0.8, 0.8)
    float subsurface_radius;              // [0,inf) scene units, default 1
    vec3 subsurface_radius_scale;         // [0,1]^3, default (1, 0.5, 0.25)
    float subsurface_scatter_anisotropy;  // [-1,1], default 0

    // Fuzz
    float fuzz_weight;     // [0,1], default 0
    vec3 fuzz_color;       // [0,1]^3, default (1, 1, 1)
    float fuzz_roughness;  // [0,1], default 0.5

    // Coat
    float coat_weight;                // [0,1], default 0
    vec3 coat_color;                  // [0,1]^3, default (1, 1, 1)
    float coat_roughness;             // [0,1], default 0
    float coat_roughness_anisotropy;  // [0,1], default 0
    float coat_ior;                   // (0,inf), default 1.6
    float coat_darkening;             // [0,1], default 1

    // Thin film
    float thin_film_weight;     // [0,1], default 0
    float thin_film_thickness;  // [0,inf) micrometers, default 0.5
    float thin_film_ior;        // (0,inf), default 1.4

    // Emission
    float emission_luminance;  // [0,inf) nits, default 0
    vec3 emission_color;       // [0,1]^3, default (1, 1, 1)

    // Geometry
    float geometry_opacity;     // [0,1], default 1
    bool geometry_thin_walled;  // default false
    OpenPBR_Basis geometry_basis;       // geometry_normal / geometry_tangent, default +z frame
    // geometry_coat_normal / geometry_coat_tangent. Default: all zero, meaning "the coat follows
    // geometry_basis" (resolved in the input contract), so setting only geometry_basis tilts the
    // coat with the base; set it, e.g. openpbr_make_basis(coat_normal, coat_tangent, 1.0f), for a
    // coat frame of its own (spec "Coat": the coat normal defaults to the geometry normal).
    OpenPBR_Basis geometry_coat_basis;

    // Extensions: rotation of the anisotropy direction about the normal as (cos, sin), e.g.
    // (0, 1) for 90 degrees; default (1, 0). Normalized in prepare; (0, 0) means no rotation.
    vec2 specular_anisotropy_rotation;
    vec2 coat_anisotropy_rotation;
};

OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_make_default_resolved_inputs()
{
    OpenPBR_ResolvedInputs inputs;
    inputs.base_weight = 1.0f;
    inputs.base_color = vec3(0.8f, 0.8f, 0.8f);
    inputs.base_diffuse_roughness = 0.0f;
    inputs.base_metalness = 0.0f;
    inputs.specular_weight = 1.0f;
    inputs.specular_color = vec3(1.0f, 1.0f, 1.0f);
    inputs.specular_roughness = 0.3f;
    inputs.specular_roughness_anisotropy = 0.0f;
    inputs.specular_ior = 1.5f;
    inputs.transmission_weight = 0.0f;
    inputs.transmission_color = vec3(1.0f, 1.0f, 1.0f);
    inputs.transmission_depth = 0.0f;
    inputs.transmission_scatter = vec3(0.0f, 0.0f, 0.0f);
    inputs.transmission_scatter_anisotropy = 0.0f;
    inputs.transmission_dispersion_scale = 0.0f;
    inputs.transmission_dispersion_abbe_number = 20.0f;
    inputs.subsurface_weight = 0.0f;
    inputs.subsurface_color = vec3(0.8f, 0.8f, 0.8f);
    inputs.subsurface_radius = 1.0f;
    inputs.subsurface_radius_scale = vec3(1.0f, 0.5f, 0.25f);
    inputs.subsurface_scatter_anisotropy = 0.0f;
    inputs.fuzz_weight = 0.0f;
    inputs.fuzz_color = vec3(1.0f, 1.0f, 1.0f);
    inputs.fuzz_roughness = 0.5f;
    inputs.coat_weight = 0.0f;
    inputs.coat_color = vec3(1.0f, 1.0f, 1.0f);
    inputs.coat_roughness = 0.0f;
    inputs.coat_roughness_anisotropy = 0.0f;
    inputs.coat_ior = 1.6f;
    inputs.coat_darkening = 1.0f;
    inputs.thin_film_weight = 0.0f;
    inputs.thin_film_thickness = 0.5f;
    inputs.thin_film_ior = 1.4f;
    inputs.emission_luminance = 0.0f;
    inputs.emission_color = vec3(1.0f, 1.0f, 1.0f);
    inputs.geometry_opacity = 1.0f;
    inputs.geometry_thin_walled = false;
    // openpbr_make_basis(+z) written out as the constants it returns (zero signs included): the
    // input contract builds these defaults in every prepare, and the call was not folded.
    inputs.geometry_basis.tangent = vec3(1.0f, -0.0f, -0.0f);
    inputs.geometry_basis.bitangent = vec3(-0.0f, 1.0f, -0.0f);
    inputs.geometry_basis.normal = vec3(0.0f, 0.0f, 1.0f);
    inputs.geometry_coat_basis.tangent = vec3(0.0f);
    inputs.geometry_coat_basis.bitangent = vec3(0.0f);
    inputs.geometry_coat_basis.normal = vec3(0.0f);
    inputs.specular_anisotropy_rotation = vec2(1.0f, 0.0f);
    inputs.coat_anisotropy_rotation = vec2(1.0f, 0.0f);
    return inputs;
}

OPENPBR_NAMESPACE_END

#endif
