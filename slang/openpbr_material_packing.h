// Flat float packing of OpenPBR_ResolvedInputs, for material buffers on GPUs and for the
// conformance kernels. The field list is written once (OPENPBR_MATERIAL_FIELDS) and expanded
// by the unpacking code below (every language) and by host-side packing (C++), so the two
// can never disagree about the order.
#ifndef OPENPBR_MATERIAL_PACKING_H
#define OPENPBR_MATERIAL_PACKING_H

// Floats per packed material, e.g. 80: 77 used, padded to a multiple of 16 bytes.
#define OPENPBR_PACKED_MATERIAL_FLOATS 80

// X-macro: FLOAT(name), COLOR(name), VECTOR2(name), BOOL(name), BASIS(name), in packing order.
#define OPENPBR_MATERIAL_FIELDS(FLOAT, COLOR, VECTOR2, BOOL, BASIS)                                         \
    FLOAT(base_weight) COLOR(base_color) FLOAT(base_diffuse_roughness) FLOAT(base_metalness)                \
    FLOAT(specular_weight) COLOR(specular_color) FLOAT(specular_roughness)                                  \
    FLOAT(specular_roughness_anisotropy) FLOAT(specular_ior)                                                \
    FLOAT(transmission_weight) COLOR(transmission_color) FLOAT(transmission_depth)                          \
    COLOR(transmission_scatter) FLOAT(transmission_scatter_anisotropy) FLOAT(transmission_dispersion_scale) \
    FLOAT(transmission_dispersion_abbe_number)                                                              \
    FLOAT(subsurface_weight) COLOR(subsurface_color) FLOAT(subsurface_radius) COLOR(subsurface_radius_scale) \
    FLOAT(subsurface_scatter_anisotropy)                                                                    \
    FLOAT(fuzz_weight) COLOR(fuzz_color) FLOAT(fuzz_roughness)                                              \
    FLOAT(coat_weight) COLOR(coat_color) FLOAT(coat_roughness) FLOAT(coat_roughness_anisotropy)             \
    FLOAT(coat_ior) FLOAT(coat_darkening)                                                                   \
    FLOAT(thin_film_weight) FLOAT(thin_film_thickness) FLOAT(thin_film_ior)                                 \
    FLOAT(emission_luminance) COLOR(emission_color)                                                         \
    FLOAT(geometry_opacity) BOOL(geometry_thin_walled) BASIS(geometry_basis) BASIS(geometry_coat_basis)     \
    VECTOR2(specular_anisotropy_rotation) VECTOR2(coat_anisotropy_rotation)

// Unpacking needs OPENPBR_MATERIAL_READ(index) -> float, defined by the includer (a buffer
// read on GPUs, an array read in C++).
#ifdef OPENPBR_MATERIAL_READ

OPENPBR_NAMESPACE_BEGIN

#define OPENPBR_UNPACK_FLOAT(name) material.name = OPENPBR_MATERIAL_READ(index); index += 1u;
#define OPENPBR_UNPACK_COLOR(name)                                                                       \
    material.name = vec3(OPENPBR_MATERIAL_READ(index), OPENPBR_MATERIAL_READ(index + 1u),                \
                         OPENPBR_MATERIAL_READ(index + 2u));                                             \
    index += 3u;
#define OPENPBR_UNPACK_VECTOR2(name) \
    material.name = vec2(OPENPBR_MATERIAL_READ(index), OPENPBR_MATERIAL_READ(index + 1u)); index += 2u;
#define OPENPBR_UNPACK_BOOL(name) material.name = OPENPBR_MATERIAL_READ(index) != 0.0f; index += 1u;
#define OPENPBR_UNPACK_BASIS(name) \
    OPENPBR_UNPACK_COLOR(name.tangent) OPENPBR_UNPACK_COLOR(name.bitangent) OPENPBR_UNPACK_COLOR(name.normal)

OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_unpack_material(uint material_index)
{
    OpenPBR_ResolvedInputs material = openpbr_make_default_resolved_inputs();
    uint index = material_index * uint(OPENPBR_PACKED_MATERIAL_FLOATS);
    OPENPBR_MATERIAL_FIELDS(OPENPBR_UNPACK_FLOAT, OPENPBR_UNPACK_COLOR, OPENPBR_UNPACK_VECTOR2, OPENPBR_UNPACK_BOOL,
                            OPENPBR_UNPACK_BASIS)
    return material;
}

#undef OPENPBR_UNPACK_FLOAT
#undef OPENPBR_UNPACK_COLOR
#undef OPENPBR_UNPACK_VECTOR2
#undef OPENPBR_UNPACK_BOOL
#undef OPENPBR_UNPACK_BASIS

OPENPBR_NAMESPACE_END

#endif

#endif
