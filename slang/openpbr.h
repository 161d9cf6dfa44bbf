// OpenPBR 1.1.1 surface BSDF, single source. Include this one header from C++, GLSL, CUDA or
// Metal; Slang users `import openpbr;` (slang/openpbr.slang). See README.md.
#ifndef OPENPBR_H
#define OPENPBR_H

// C++ and CUDA: this entry header includes <glm/glm.hpp> itself, so project code may include it
// first; the lower headers (interop/, openpbr_bsdf.h, openpbr_established_api.h) require GLM to
// be included before them and say so with an #error otherwise. A host with its own vector
// library defines OPENPBR_USE_CUSTOM_VEC_TYPES=1 (or OPENPBR_USE_CUSTOM_INTEROP=1) instead.
#if defined(__cplusplus) && !defined(__METAL_VERSION__) && !defined(OPENPBR_LANGUAGE_TARGET_SLANG) && \
    !defined(OPENPBR_LANGUAGE_TARGET_GLSL) && !defined(OPENPBR_LANGUAGE_TARGET_HLSL) &&               \
    !defined(OPENPBR_LANGUAGE_TARGET_METAL) && !defined(OPENPBR_LANGUAGE_TARGET_MSL) &&               \
    !(defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES) &&                       \
    !(defined(OPENPBR_USE_CUSTOM_INTEROP) && OPENPBR_USE_CUSTOM_INTEROP)
#include <glm/glm.hpp>
#endif
#include "../interop/openpbr_interop.h"
#include "openpbr_bsdf.h"
// The established API form (README "Two API forms"), implemented through openpbr_bsdf.h.
#include "openpbr_established_api.h"

#endif
