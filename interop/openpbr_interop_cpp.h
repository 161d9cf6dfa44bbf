// C++ backend (host and CPU reference build): the dialect maps onto GLM.
// Everything lives in namespace openpbr so vec3 & co. do not leak into user code.
#ifndef OPENPBR_INTEROP_CPP_H
#define OPENPBR_INTEROP_CPP_H

#include <cmath>
#include <cstdint>
#include <type_traits>

// GLM is the C++ vector library unless the host brings its own (OPENPBR_USE_CUSTOM_VEC_TYPES).
// The host includes <glm/glm.hpp> first (as for any GLM-based header library; slang/openpbr.h,
// the project's entry header, does it for its includers); every GLM header defines
// GLM_VERSION, which is what can be tested here.
#if !(defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES)
#if !defined(GLM_VERSION)
#error \
    "OpenPBR (C++): include <glm/glm.hpp> before the OpenPBR headers, or include slang/openpbr.h (which includes it), or define OPENPBR_USE_CUSTOM_VEC_TYPES=1 and provide vec2/vec3/vec4 and their math functions"
#endif
#include <glm/glm.hpp>
// vec4 as GLM's aligned vector where GLM's SIMD is on (GLM_FORCE_INTRINSICS before GLM, as this
// project's build defines it): its arithmetic, min, max, abs, floor and sqrt are then one or a few
// SSE instructions for the four lanes (the thin film's four stacks and four spectral lobes).
// Elsewhere, or with OPENPBR_CPP_ALIGNED_VEC4=0 (e.g. for a host whose own code must see
// glm::vec4 there), vec4 is glm::vec4; both compute the same values lane by lane. (The test
// sizeof(float) == 4 keeps the double-precision copy of the headers, tools/make_double_headers.py,
// where float reads double, on GLM's plain dvec4.)
#ifndef OPENPBR_CPP_ALIGNED_VEC4
#define OPENPBR_CPP_ALIGNED_VEC4 1
#endif
#if OPENPBR_CPP_ALIGNED_VEC4 && GLM_CONFIG_SIMD == GLM_ENABLE && GLM_CONFIG_ALIGNED_GENTYPES == GLM_ENABLE
#define OPENPBR_CPP_USE_VECTOR_LIBRARY \
    using namespace glm;               \
    typedef std::conditional<sizeof(float) == 4, glm::vec<4, float, glm::aligned_highp>, glm::vec<4, float>>::type vec4;
// With SSE lanes the thin film's four-lane form is the faster one (openpbr_interop.h,
// OPENPBR_FILM_FOUR_LANES).
#ifndef OPENPBR_FILM_FOUR_LANES
#define OPENPBR_FILM_FOUR_LANES 1
#endif
#else
#define OPENPBR_CPP_USE_VECTOR_LIBRARY using namespace glm;
#endif
#else
#define OPENPBR_CPP_USE_VECTOR_LIBRARY
#endif

// A build of the BSDF with other compile-time feature toggles (e.g. -DOPENPBR_FEATURE_COAT=0)
// in a program that also has the default build needs its own namespace, or the two sets of
// inline functions would break the one-definition rule: OPENPBR_CPP_VARIANT_NAMESPACE, e.g.
// base_only, puts that translation unit's BSDF in openpbr::base_only (the shared tables stay
// in openpbr). Unset (the default): namespace openpbr.
#if defined(OPENPBR_CPP_VARIANT_NAMESPACE)
#define OPENPBR_NAMESPACE_BEGIN               \
    namespace openpbr {                       \
    namespace OPENPBR_CPP_VARIANT_NAMESPACE { \
    OPENPBR_CPP_USE_VECTOR_LIBRARY            \
    typedef unsigned int uint;
#define OPENPBR_NAMESPACE_END \
    }                         \
    }
#else
#define OPENPBR_NAMESPACE_BEGIN    \
    namespace openpbr {            \
    OPENPBR_CPP_USE_VECTOR_LIBRARY \
    typedef unsigned int uint;
#define OPENPBR_NAMESPACE_END }
#endif

// Feature toggles (slang/openpbr_features.h), run-time form: bit k of the mask is the toggle
// with constant id k, all on by default; e.g. openpbr::openpbr_runtime_feature_mask =
// OPENPBR_FEATURE_BIT_COAT | OPENPBR_FEATURE_BIT_METAL renders with only coat and metal
// (host::ScopedFeatureMask sets and restores it). Process-wide, like a pipeline's
// specialization: set it before shading, not while other threads shade. The compile-time form
// (-DOPENPBR_FEATURE_<NAME>=0) overrides it.
namespace openpbr {
inline std::uint32_t openpbr_runtime_feature_mask = 0xffffffffu;
}
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name)
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) \
    (((::openpbr::openpbr_runtime_feature_mask >> OPENPBR_SPECIALIZATION_ID_##name) & 1u) != 0u)

// Header-only: every function is inline; structs go by const reference to avoid copies.
#define OPENPBR_FUNC inline
// A part of a larger function, split out for reading and called once (e.g. a layer of prepare):
// GCC and Clang keep such an `inline` function out of line (its linkage is external), and each
// call spills the registers live across it (every-lobe prepare +60 instructions per call split
// into parts, callgrind). Forced inline, the compiled code is the unsplit function's.
#if defined(_MSC_VER)
#define OPENPBR_INLINE_FUNC __forceinline
#else
#define OPENPBR_INLINE_FUNC inline __attribute__((always_inline))
#endif
#define OPENPBR_IN(type) const type&
#define OPENPBR_INOUT(type) type&
// Marks a parameter a lobe ignores (the shared lobe signature has it), e.g. the view of a
// Lambertian pdf; C-family compilers would otherwise warn.
#define OPENPBR_UNUSED(name) (void)(name)
#define OPENPBR_OUT(type) type&

// Short loops unrolled by the compiler (openpbr_interop.h, OPENPBR_ROLLED_ON_GPU).
#if defined(__GNUC__)
#define OPENPBR_ROLLED_ON_GPU _Pragma("GCC unroll 8")
#else
#define OPENPBR_ROLLED_ON_GPU
#endif

// Program-scope constants (e.g. OpenPBR_VacuumIor): one definition across translation units.
#define OPENPBR_GLOBAL_CONSTANT inline const

OPENPBR_NAMESPACE_BEGIN
// GLSL has atan(y, x); the dialect spells it atan2 so Slang/HLSL/Metal need no wrapper.
inline float atan2(float y, float x) { return std::atan2(y, x); }
#if !(defined(OPENPBR_USE_CUSTOM_SATURATE) && OPENPBR_USE_CUSTOM_SATURATE) && \
    !(defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES)
// HLSL's saturate, which the dialect uses; a host that has its own (visible from namespace
// openpbr) sets OPENPBR_USE_CUSTOM_SATURATE=1. With custom vector types the host's library
// provides it alongside the other math functions.
inline float saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
template <glm::length_t L, glm::qualifier Q> inline glm::vec<L, float, Q> saturate(const glm::vec<L, float, Q>& v)
{
    return glm::clamp(v, glm::vec<L, float, Q>(0.0f), glm::vec<L, float, Q>(1.0f));
}
#endif
OPENPBR_NAMESPACE_END

#endif
