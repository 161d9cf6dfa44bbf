// The byte layout of one input of fuzz/fuzz_bsdf.cpp, shared with the seed-corpus writer
// (host/checks/stability.cpp, `openpbr stability --write-fuzz-corpus DIR`): little-endian floats,
//   [0, 80)   the packed material (slang/openpbr_material_packing.h, OPENPBR_PACKED_MATERIAL_FLOATS)
//   [80, 83)  view direction, world space, as given to openpbr_prepare
//   [83, 86)  light direction (the harness normalizes it; eval and pdf take unit directions)
//   [86, 89)  random numbers u for openpbr_sample (the harness maps them into [0, 1))
//   [89, 92)  wavelengths in nm for openpbr_prepare (dispersion)
// Shorter inputs are completed from the default input (default material, view and light along
// +z, u = 0.5, the default RGB wavelengths); bytes past the end are ignored.
#ifndef OPENPBR_FUZZ_INPUT_LAYOUT_H
#define OPENPBR_FUZZ_INPUT_LAYOUT_H

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/openpbr_material_packing.h"

#define OPENPBR_FUZZ_MATERIAL_OFFSET 0
#define OPENPBR_FUZZ_VIEW_OFFSET OPENPBR_PACKED_MATERIAL_FLOATS
#define OPENPBR_FUZZ_LIGHT_OFFSET (OPENPBR_FUZZ_VIEW_OFFSET + 3)
#define OPENPBR_FUZZ_U_OFFSET (OPENPBR_FUZZ_LIGHT_OFFSET + 3)
#define OPENPBR_FUZZ_WAVELENGTH_OFFSET (OPENPBR_FUZZ_U_OFFSET + 3)
#define OPENPBR_FUZZ_INPUT_FLOATS (OPENPBR_FUZZ_WAVELENGTH_OFFSET + 3)

#endif
