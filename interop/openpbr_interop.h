// OpenPBR interop router: picks exactly one language backend for the single-source BSDF.
//
// The BSDF headers in slang/ are written in a GLSL-style C dialect: GLSL 4.50 built-in
// functions and types (vec2/vec3/vec4, uint, bool, mix, fract, inversesqrt, ...), plus
// atan2(y, x), and a handful of OPENPBR_ macros for what the languages spell differently
// (function qualifiers, parameter passing, specialization constants, table access).
// Each backend maps that dialect onto its language.
//
// Selection (at most one OPENPBR_LANGUAGE_TARGET_* may be set by the user; an explicit one
// overrides the auto-detection, e.g. -DOPENPBR_LANGUAGE_TARGET_GLSL=1 for a C-preprocessed
// GLSL build, or OPENPBR_LANGUAGE_TARGET_CPP=1 for host code in a .cu file):
//   OPENPBR_LANGUAGE_TARGET_SLANG=1  chosen explicitly (e.g. by slang/openpbr.slang)
//   OPENPBR_LANGUAGE_TARGET_HLSL     chosen explicitly or auto-detected from __HLSL_VERSION
//                                    (DXC); HLSL users take the generated openpbr.hlsl
//   OPENPBR_LANGUAGE_TARGET_CUDA     auto-detected from __CUDACC__
//   OPENPBR_LANGUAGE_TARGET_MSL      auto-detected from __METAL_VERSION__; the older name
//                                    OPENPBR_LANGUAGE_TARGET_METAL means the same
//   OPENPBR_LANGUAGE_TARGET_CPP      auto-detected from __cplusplus
//   OPENPBR_LANGUAGE_TARGET_GLSL     the fallback (GLSL has no language macro to test)
//
// Integration hooks, each defined (to 1) before the first include, default 0:
//   OPENPBR_USE_CUSTOM_INTEROP=1    the host supplies the whole interop layer: no backend is
//                                   included, and the host must have defined the macro set
//                                   checked at the end of this file (and the dialect's names).
//   OPENPBR_USE_CUSTOM_VEC_TYPES=1  the host provides vec2/vec3/vec4 (C++ and CUDA: also the
//                                   GLSL math functions the dialect calls, visible from
//                                   namespace openpbr, e.g. a renderer's own vector library);
//                                   the C++/CUDA backends then neither include GLM nor use it,
//                                   Slang/HLSL/Metal define no vector names. GLSL: no effect.
//   OPENPBR_USE_CUSTOM_SATURATE=1   the host already defines saturate(x) for float and the
//                                   vector types (C++, CUDA, GLSL, where the backend would
//                                   otherwise define it); Slang, HLSL and Metal have it built in.
#ifndef OPENPBR_INTEROP_H
#define OPENPBR_INTEROP_H

#ifndef OPENPBR_USE_CUSTOM_INTEROP
#define OPENPBR_USE_CUSTOM_INTEROP 0
#endif
#ifndef OPENPBR_USE_CUSTOM_VEC_TYPES
#define OPENPBR_USE_CUSTOM_VEC_TYPES 0
#endif
#ifndef OPENPBR_USE_CUSTOM_SATURATE
#define OPENPBR_USE_CUSTOM_SATURATE 0
#endif

#if defined(OPENPBR_LANGUAGE_TARGET_SLANG) && !OPENPBR_LANGUAGE_TARGET_SLANG
#undef OPENPBR_LANGUAGE_TARGET_SLANG
#endif

#if (defined(OPENPBR_LANGUAGE_TARGET_SLANG) + defined(OPENPBR_LANGUAGE_TARGET_CUDA) +   \
     (defined(OPENPBR_LANGUAGE_TARGET_METAL) || defined(OPENPBR_LANGUAGE_TARGET_MSL)) + \
     defined(OPENPBR_LANGUAGE_TARGET_CPP) + defined(OPENPBR_LANGUAGE_TARGET_GLSL) +     \
     defined(OPENPBR_LANGUAGE_TARGET_HLSL)) > 1
#error "openpbr_interop.h: more than one OPENPBR_LANGUAGE_TARGET_* is defined; set at most one"
#endif

// The Metal target has two names; the backends and the BSDF test OPENPBR_LANGUAGE_TARGET_METAL.
#if defined(OPENPBR_LANGUAGE_TARGET_MSL) && !defined(OPENPBR_LANGUAGE_TARGET_METAL)
#define OPENPBR_LANGUAGE_TARGET_METAL 1
#endif
#if defined(OPENPBR_LANGUAGE_TARGET_METAL) && !defined(OPENPBR_LANGUAGE_TARGET_MSL)
#define OPENPBR_LANGUAGE_TARGET_MSL 1
#endif

#if !defined(OPENPBR_LANGUAGE_TARGET_SLANG) && !defined(OPENPBR_LANGUAGE_TARGET_CUDA) && \
    !defined(OPENPBR_LANGUAGE_TARGET_METAL) && !defined(OPENPBR_LANGUAGE_TARGET_CPP) &&  \
    !defined(OPENPBR_LANGUAGE_TARGET_GLSL) && !defined(OPENPBR_LANGUAGE_TARGET_HLSL)
#if defined(__HLSL_VERSION)
#define OPENPBR_LANGUAGE_TARGET_HLSL 1
#elif defined(__CUDACC__)
#define OPENPBR_LANGUAGE_TARGET_CUDA 1
#elif defined(__METAL_VERSION__)
#define OPENPBR_LANGUAGE_TARGET_METAL 1
#define OPENPBR_LANGUAGE_TARGET_MSL 1
#elif defined(__cplusplus)
#define OPENPBR_LANGUAGE_TARGET_CPP 1
#else
#define OPENPBR_LANGUAGE_TARGET_GLSL 1
#endif
#endif

#if OPENPBR_USE_CUSTOM_INTEROP
// The host's interop layer is already in place (see the macro check below).
#elif defined(OPENPBR_LANGUAGE_TARGET_SLANG)
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

// Declaration prefix of a program-scope constant, e.g. OPENPBR_GLOBAL_CONSTANT float x = 1.0f;
// (a custom interop layer may leave it out: plain const then).
#ifndef OPENPBR_GLOBAL_CONSTANT
#define OPENPBR_GLOBAL_CONSTANT const
#endif

// Prefix of a loop the driver should keep rolled, e.g. OPENPBR_DONT_UNROLL for (...) { ... }:
// SPIR-V's DontUnroll loop control from Slang and HLSL ([loop]) and GLSL ([[dont_unroll]]),
// nvcc's `#pragma unroll 1`; nothing in C++ and Metal, where the compiler decides. Mesa's NIR
// honours it: a loop of table reads kept rolled is one read site where an unrolled one is one
// per iteration, and each site adds to llvmpipe's build time (docs/performance.md).
#ifndef OPENPBR_DONT_UNROLL
#define OPENPBR_DONT_UNROLL
#endif

// OPENPBR_AUTODIFF=1: the differentiable build (docs/gradients.md), e.g. slangc -DOPENPBR_AUTODIFF=1.
// Under Slang every function is [Differentiable] and every struct IDifferentiable; in every
// language lobes of weight 0 are prepared and evaluated (their one-sided derivative) and the
// input contract's clamps pass the derivative at their ends. Default 0: the plain module.
#ifndef OPENPBR_AUTODIFF
#define OPENPBR_AUTODIFF 0
#endif

// Suffix of a struct's name in its definition, e.g. struct OpenPBR_Basis OPENPBR_DIFFERENTIABLE:
// `: IDifferentiable` in Slang's differentiable build (its float fields get a differential, its
// bool and int fields drop out); empty elsewhere.
#ifndef OPENPBR_DIFFERENTIABLE
#define OPENPBR_DIFFERENTIABLE
#endif

// Prefix of a loop whose trip count depends on the data, with the bound the code guarantees, e.g.
// OPENPBR_MAX_ITERS(3) for (int channel = 0; channel < channel_count; ++channel): Slang's
// [MaxIters(n)] in the differentiable build (reverse mode needs it to size the loop's tape);
// empty elsewhere.
#ifndef OPENPBR_MAX_ITERS
#define OPENPBR_MAX_ITERS(count)
#endif

// A value whose derivative is cut, e.g. bsdf.volume = OPENPBR_DETACH(openpbr_make_volume(inputs)):
// Slang's detach() in the differentiable build (no reverse pass runs through its set-up); the
// value itself elsewhere.
#ifndef OPENPBR_DETACH
#define OPENPBR_DETACH(value) (value)
#endif

// Whether a lobe or layer of this weight is set up and evaluated, e.g.
// if (OPENPBR_WEIGHT_ACTIVE(coat_weight)). The plain module skips weight 0 (such a lobe adds
// nothing and costs nothing); the differentiable one keeps it, so d/d(weight) at 0 is the lobe's
// one-sided derivative instead of 0 (weights are >= 0 after the input contract).
#if OPENPBR_AUTODIFF
#define OPENPBR_WEIGHT_ACTIVE(weight) ((weight) >= 0.0f)
#else
#define OPENPBR_WEIGHT_ACTIVE(weight) ((weight) > 0.0f)
#endif

// The input contract's clamp to [low, high]. The differentiable build spells it with comparisons
// that keep the value at either end (same result), so the derivative there is the one-sided one
// from inside the range (1) instead of the built-in clamp's 0.
#if OPENPBR_AUTODIFF
#define OPENPBR_CONTRACT_CLAMP(value, low, high) ((value) < (low) ? (low) : ((value) > (high) ? (high) : (value)))
#else
#define OPENPBR_CONTRACT_CLAMP(value, low, high) clamp(value, low, high)
#endif

// Declaration prefix of a part of a larger function, split out for reading and called once, e.g.
// OPENPBR_INLINE_FUNC void openpbr_clear_lobes(...): forced inline where a compiler would keep it
// out of line (the C++ and CUDA backends) and in Slang's plain build (whose SPIR-V would keep each
// part a function of its own: the conformance kernel 231,912 bytes against 225,868, 2026-12-02);
// elsewhere OPENPBR_FUNC (GPU compilers inline every call).
#ifndef OPENPBR_INLINE_FUNC
#define OPENPBR_INLINE_FUNC OPENPBR_FUNC
#endif

// Prefix of a loop of at most 8 steps that GPU drivers keep rolled and C++ compilers unroll,
// e.g. OPENPBR_ROLLED_ON_GPU for (int lobe = 0; lobe < 6; ++lobe) { ... }: OPENPBR_DONT_UNROLL on
// the GPU backends (each step's code compiled once, a shorter build), `#pragma GCC unroll 8`
// from the C++ backend (GCC and Clang at -O2 keep such a loop rolled, GCC unrolls it at -O3;
// unrolled, the step's index is a constant and the selects it drives fold away). The loop
// computes the same values either way.
#ifndef OPENPBR_ROLLED_ON_GPU
#define OPENPBR_ROLLED_ON_GPU OPENPBR_DONT_UNROLL
#endif

// The form of the thin film's full model (slang/math/openpbr_thin_film.h), e.g. 0 (the default):
// one lane, the stacks that differ in their base (the dielectric, the conductor's three
// channels) one after another. Or 1: the four stacks side by side in the lanes of vec4s, the
// six lobes' phases computed once for all of them. The C++ backend sets 1 where vec4 is GLM's
// SSE vector (GLM_FORCE_INTRINSICS, this project's build): one film evaluation then takes 2,024
// instructions instead of 5,292 (docs/thin-film-estimate.md "Cost"). Elsewhere 0: on the GPU
// paths the four-lane form grew llvmpipe's build of the full module by half and the SPIR-V by
// 2 %, and C++ without SIMD ran it slower than one lane. Both forms give the same reflectance
// within 1e-5 (tests/bsdf/test_thin_film_regression.cpp); e.g. -DOPENPBR_FILM_FOUR_LANES=0 keeps
// a SIMD C++ build on the one-lane form.
#ifndef OPENPBR_FILM_FOUR_LANES
#define OPENPBR_FILM_FOUR_LANES 0
#endif

// Every backend must provide these; checked here so a new backend fails loudly.
#if !defined(OPENPBR_FUNC) || !defined(OPENPBR_IN) || !defined(OPENPBR_INOUT) || !defined(OPENPBR_OUT) || \
    !defined(OPENPBR_UNUSED) || !defined(OPENPBR_NAMESPACE_BEGIN) || !defined(OPENPBR_NAMESPACE_END) ||   \
    !defined(OPENPBR_DECLARE_SPECIALIZATION_CONSTANT) || !defined(OPENPBR_GET_SPECIALIZATION_CONSTANT)
#if OPENPBR_USE_CUSTOM_INTEROP
#error \
    "openpbr_interop.h: OPENPBR_USE_CUSTOM_INTEROP=1 but the host's interop layer lacks one of OPENPBR_FUNC, OPENPBR_IN, OPENPBR_INOUT, OPENPBR_OUT, OPENPBR_UNUSED, OPENPBR_NAMESPACE_BEGIN/END, OPENPBR_DECLARE/GET_SPECIALIZATION_CONSTANT"
#else
#error "openpbr_interop.h: the selected backend does not define the full macro set"
#endif
#endif

#endif
