// Packing of a material library: see material_packing.h.
#include "host/scene/material_packing.h"

namespace openpbr::host {

std::vector<float> pack_materials(const std::vector<Material>& materials)
{
    std::vector<float> packed(materials.size() * OPENPBR_PACKED_MATERIAL_FLOATS, 0.0f);
    for (std::size_t m = 0; m < materials.size(); ++m)
    {
        pack_material(materials[m].inputs, packed.data() + m * OPENPBR_PACKED_MATERIAL_FLOATS);
    }
    return packed;
}

}  // namespace openpbr::host
