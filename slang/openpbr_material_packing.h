// Flat float packing of OpenPBR_ResolvedInputs, for material buffers on GPUs and for the
// conformance kernels. The layout is the parameter table's order (OPENPBR_PARAMETERS in
// openpbr_parameters.h): a float takes one slot, a color three, a vector2 two, a bool one
// (0 or 1), a basis nine (tangent, bitangent, normal). The unpacking below (every language)
// and the C++ packing (host/scene/material_packing.h) expand that one table, so they can never
// disagree.
#ifndef OPENPBR_MATERIAL_PACKING_H
#define OPENPBR_MATERIAL_PACKING_H

#include "openpbr_parameters.h"

// Floats per packed material, e.g. 80: 77 used, padded to a multiple of 16 bytes.
#define OPENPBR_PACKED_MATERIAL_FLOATS 80

#endif

// Unpacking needs OPENPBR_MATERIAL_READ(index) -> float, defined by the includer (a buffer
// read on GPUs, an array read in C++) before an include of this header; an include without it
// gives the layout only, and a later one with it still defines the reader
// openpbr_unpack_material(material_index).
//
// A reader under another name, for a second material buffer in the same program (e.g. the
// preview renderer's kernel, targets/kernels/openpbr_render_kernel.h, whose C++ build shares a
// program with the conformance kernel's: one name with two bodies would break C++'s one
// definition rule): define OPENPBR_MATERIAL_UNPACK_NAME (the function's name, e.g.
// openpbr_render_unpack_material) and OPENPBR_MATERIAL_UNPACK_READ(index) -> float, then include
// this header at namespace scope. It defines that function once and undefines both macros.
#if defined(OPENPBR_MATERIAL_UNPACK_NAME) && defined(OPENPBR_MATERIAL_UNPACK_READ)
#define OPENPBR_UNPACK_NAMED 1
#define OPENPBR_UNPACK_LOAD(index) OPENPBR_MATERIAL_UNPACK_READ(index)
#elif defined(OPENPBR_MATERIAL_READ) && !defined(OPENPBR_MATERIAL_UNPACK_DEFINED)
#define OPENPBR_MATERIAL_UNPACK_DEFINED
#define OPENPBR_UNPACK_NAMED 0
#define OPENPBR_UNPACK_LOAD(index) OPENPBR_MATERIAL_READ(index)
#endif

#if defined(OPENPBR_UNPACK_NAMED)

OPENPBR_NAMESPACE_BEGIN

#define OPENPBR_UNPACK_VEC3(name)                                                                                       \
    material.name = vec3(OPENPBR_UNPACK_LOAD(index), OPENPBR_UNPACK_LOAD(index + 1u), OPENPBR_UNPACK_LOAD(index + 2u)); \
    index += 3u;
#define OPENPBR_UNPACK_FLOAT(name, default_value, low, high) \
    material.name = OPENPBR_UNPACK_LOAD(index);              \
    index += 1u;
#define OPENPBR_UNPACK_COLOR(name, default_r, default_g, default_b, low, high) OPENPBR_UNPACK_VEC3(name)
#define OPENPBR_UNPACK_VECTOR2(name, default_x, default_y)                             \
    material.name = vec2(OPENPBR_UNPACK_LOAD(index), OPENPBR_UNPACK_LOAD(index + 1u)); \
    index += 2u;
#define OPENPBR_UNPACK_BOOL(name, default_value)        \
    material.name = OPENPBR_UNPACK_LOAD(index) != 0.0f; \
    index += 1u;
#define OPENPBR_UNPACK_BASIS(name, normal_input, tangent_input) \
    OPENPBR_UNPACK_VEC3(name.tangent) OPENPBR_UNPACK_VEC3(name.bitangent) OPENPBR_UNPACK_VEC3(name.normal)

#if OPENPBR_UNPACK_NAMED
OPENPBR_FUNC OpenPBR_ResolvedInputs OPENPBR_MATERIAL_UNPACK_NAME(uint material_index)
#else
OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_unpack_material(uint material_index)
#endif
{
    OpenPBR_ResolvedInputs material = openpbr_make_default_resolved_inputs();
    uint index = material_index * uint(OPENPBR_PACKED_MATERIAL_FLOATS);
    OPENPBR_PARAMETERS(OPENPBR_UNPACK_FLOAT, OPENPBR_UNPACK_COLOR, OPENPBR_UNPACK_VECTOR2, OPENPBR_UNPACK_BOOL,
                       OPENPBR_UNPACK_BASIS)
    return material;
}

#undef OPENPBR_UNPACK_VEC3
#undef OPENPBR_UNPACK_FLOAT
#undef OPENPBR_UNPACK_COLOR
#undef OPENPBR_UNPACK_VECTOR2
#undef OPENPBR_UNPACK_BOOL
#undef OPENPBR_UNPACK_BASIS

OPENPBR_NAMESPACE_END

#undef OPENPBR_UNPACK_NAMED
#undef OPENPBR_UNPACK_LOAD
#undef OPENPBR_MATERIAL_UNPACK_NAME
#undef OPENPBR_MATERIAL_UNPACK_READ

#endif
