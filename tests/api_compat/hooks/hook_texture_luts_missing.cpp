// Must NOT compile (with -DOPENPBR_USE_TEXTURE_LUTS=1): texture tables without the host's
// OPENPBR_SAMPLE_2D_TEXTURE / OPENPBR_SAMPLE_3D_TEXTURE stop at slang/openpbr_lut_textures.h's
// #error (tests/api_compat/check_api_compat.sh hooks).
#include <glm/glm.hpp>

#include "slang/openpbr.h"

int main() { return 0; }
