// material_packing.h - OpenPBR_ResolvedInputs as the flat float records GPU kernels read
// (slang/openpbr_material_packing.h: OPENPBR_PACKED_MATERIAL_FLOATS floats per material, in the
// order of the parameter table OPENPBR_PARAMETERS). The inverse of openpbr_unpack_material.
// Header-only packing of one material (pack_material), so the fuzz harness uses it without
// linking the host library; pack_materials (material_packing.cpp) packs a library.
#pragma once

#include <vector>

#include "host/scene/material_library.h"
#include "slang/openpbr.h"
#include "slang/openpbr_material_packing.h"

namespace openpbr::host {

// Writes OPENPBR_PACKED_MATERIAL_FLOATS floats to `out`: the table's fields (a bool as 0 or 1,
// a basis as tangent, bitangent, normal), then zeros up to the padded size.
inline void pack_material(const OpenPBR_ResolvedInputs& material, float* out)
{
    std::size_t index = 0;
    auto put = [&](const float value) { out[index++] = value; };
    auto put3 = [&](const glm::vec3& value) {
        put(value.x);
        put(value.y);
        put(value.z);
    };
#define OPENPBR_PACK_FLOAT(name, default_value, low, high) put(material.name);
#define OPENPBR_PACK_COLOR(name, default_r, default_g, default_b, low, high) put3(material.name);
#define OPENPBR_PACK_VECTOR2(name, default_x, default_y) \
    put(material.name.x);                                \
    put(material.name.y);
#define OPENPBR_PACK_BOOL(name, default_value) put(material.name ? 1.0f : 0.0f);
#define OPENPBR_PACK_BASIS(name, normal_input, tangent_input) \
    put3(material.name.tangent);                              \
    put3(material.name.bitangent);                            \
    put3(material.name.normal);
    OPENPBR_PARAMETERS(OPENPBR_PACK_FLOAT, OPENPBR_PACK_COLOR, OPENPBR_PACK_VECTOR2, OPENPBR_PACK_BOOL, OPENPBR_PACK_BASIS)
#undef OPENPBR_PACK_FLOAT
#undef OPENPBR_PACK_COLOR
#undef OPENPBR_PACK_VECTOR2
#undef OPENPBR_PACK_BOOL
#undef OPENPBR_PACK_BASIS
    while (index < OPENPBR_PACKED_MATERIAL_FLOATS)
    {
        put(0.0f);
    }
}

// Floats the table fills, e.g. 77 of the 80 of a record; the rest is padding.
constexpr std::size_t packed_material_used_floats()
{
#define OPENPBR_COUNT_FLOAT(name, default_value, low, high) +1
#define OPENPBR_COUNT_COLOR(name, default_r, default_g, default_b, low, high) +3
#define OPENPBR_COUNT_VECTOR2(name, default_x, default_y) +2
#define OPENPBR_COUNT_BOOL(name, default_value) +1
#define OPENPBR_COUNT_BASIS(name, normal_input, tangent_input) +9
    return 0 OPENPBR_PARAMETERS(OPENPBR_COUNT_FLOAT, OPENPBR_COUNT_COLOR, OPENPBR_COUNT_VECTOR2, OPENPBR_COUNT_BOOL,
                                OPENPBR_COUNT_BASIS);
#undef OPENPBR_COUNT_FLOAT
#undef OPENPBR_COUNT_COLOR
#undef OPENPBR_COUNT_VECTOR2
#undef OPENPBR_COUNT_BOOL
#undef OPENPBR_COUNT_BASIS
}
static_assert(packed_material_used_floats() <= OPENPBR_PACKED_MATERIAL_FLOATS,
              "OPENPBR_PACKED_MATERIAL_FLOATS is smaller than the parameter table");

// Every material's record, one after the other (materials.size() * OPENPBR_PACKED_MATERIAL_FLOATS).
std::vector<float> pack_materials(const std::vector<Material>& materials);

}  // namespace openpbr::host
