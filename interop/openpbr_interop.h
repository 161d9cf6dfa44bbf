// OpenPBR interop router: picks exactly one language backend for the single-source BSDF.
//
// The BSDF headers in slang/ are written in a GLSL-style C dialect: GLSL 4.50 built-in
// functions and types (vec2/vec3/vec4, uint, bool, mix, fract, inversesqrt, ...), plus
// atan2(y, x), and a handful of OPENPBR_ macros for what the languages spell differently
// (function qualifiers, parameter passing, specialization constants, table access).
// Each backend maps that dialect onto its language.
//
// Selection (at most one OPENPBR_LANGUAGE_TARGET_* may be set by the user):
//   OPENPBR_LANGUAGE_TARGET_SLANG=1  chosen explicitly (e.g. by slang/openpbr.slang)
//   OPENPBR_LANGUAGE_TARGET_HLSL     chosen explicitly or auto-detected from __HLSL_VERSION
//                                    (DXC); HLSL users take the generated openpbr.hlsl
//   OPENPBR_LANGUAGE_TARGET_CUDA     auto-detected from __CUDACC__
//   OPENPBR_LANGUAGE_TARGET_METAL    auto-detected from __METAL_VERSION__
//   OPENPBR_LANGUAGE_TARGET_CPP      auto-detected from __cplusplus
//   OPENPBR_LANGUAGE_TARGET_GLSL     the fallback (GLSL has no language macro to test)
#ifndef OPENPBR_INTEROP_H
#define OPENPBR_INTEROP_H

#if defined(OPENPBR_LANGUAGE_TARGET_SLANG) && !OPENPBR_LANGUAGE_TARGET_SLANG
#undef OPENPBR_LANGUAGE_TARGET_SLANG
#endif

#if (defined(OPENPBR_LANGUAGE_TARGET_SLANG) + defined(OPENPBR_LANGUAGE_TARGET_CUDA) + \
     defined(OPENPBR_LANGUAGE_TARGET_METAL) + defined(OPENPBR_LANGUAGE_TARGET_CPP) +   \
     defined(OPENPBR_LANGUAGE_TARGET_GLSL) + defined(OPENPBR_LANGUAGE_TARGET_HLSL)) > 1
#error "openpbr_interop.h: more than one OPENPBR_LANGUAGE_TARGET_* is defined; set at most one"
#endif

#if !defined(OPENPBR_LANGUAGE_TARGET_SLANG) && !defined(OPENPBR_LANGUAGE_TARGET_CUDA) && \
    !defined(OPENPBR_LANGUAGE_TARGET_METAL) && !defined(OPENPBR_LANGUAGE_TARGET_CPP) &&   \
    !defined(OPENPBR_LANGUAGE_TARGET_GLSL) && !defined(OPENPBR_LANGUAGE_TARGET_HLSL)
#if defined(__HLSL_VERSION)
#define OPENPBR_LANGUAGE_TARGET_HLSL 1
#elif defined(__CUDACC__)
#define OPENPBR_LANGUAGE_TARGET_CUDA 1
#elif defined(__METAL_VERSION__)
#define OPENPBR_LANGUAGE_TARGET_METAL 1
#elif defined(__cplusplus)
#define OPENPBR_LANGUAGE_TARGET_CPP 1
#else
#define OPENPBR_LANGUAGE_TARGET_GLSL 1
#endif
#endif

#if defined(OPENPBR_LANGUAGE_TARGET_SLANG)
#include "openpbr_interop_slang.h"
#elif defined(OPENPBR_LANGUAGE_TARGET_CUDA)
#include "openpbr_interop_cuda.h"
#elif defined(OPENPBR_LANGUAGE_TARGET_METAL)
#include "openpbr_interop_metal.h"
#elif defined(OPENPBR_LANGUAGE_TARGET_HLSL)
#include "openpbr_interop_hlsl.h"
#elif defined(OPENPBR_LANGUAGE_TARGET_CPP)
#include "openpbr_interop_cpp.h"
#else
#include "openpbr_interop_glsl.h"
#endif

// Every backend must provide these; checked here so a new backend fails loudly.
#if !defined(OPENPBR_FUNC) || !defined(OPENPBR_IN) || !defined(OPENPBR_INOUT) || \
    !defined(OPENPBR_OUT) || !defined(OPENPBR_UNUSED) || !defined(OPENPBR_NAMESPACE_BEGIN) || !defined(OPENPBR_NAMESPACE_END) || \
    !defined(OPENPBR_DECLARE_SPECIALIZATION_CONSTANT) || !defined(OPENPBR_GET_SPECIALIZATION_CONSTANT)
#error "openpbr_interop.h: the selected backend does not define the full macro set"
#endif

#endif
