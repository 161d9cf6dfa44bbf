// OpenPBR 1.1 surface BSDF, single source. Include this one header from C++, GLSL, CUDA or
// Metal; Slang users `import openpbr;` (slang/openpbr.slang). See README.md.
#ifndef OPENPBR_H
#define OPENPBR_H

#include "../interop/openpbr_interop.h"
#include "openpbr_bsdf.h"

#endif
