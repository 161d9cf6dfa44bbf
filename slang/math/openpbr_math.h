// Small numeric helpers shared by every lobe. Pure functions, no state.
#ifndef OPENPBR_MATH_H
#define OPENPBR_MATH_H

#include "../../interop/openpbr_interop.h"
#include "../openpbr_working_space.h"

#define OPENPBR_PI 3.14159265358979323846f
#define OPENPBR_TWO_PI 6.28318530717958647692f
#define OPENPBR_INV_PI 0.31830988618379067154f
// Smallest positive normal float: results below it are flushed by lavapipe and many GPUs,
// so no decision may depend on a denormal.
#define OPENPBR_FLOAT_MIN_NORMAL 1.17549435e-38f
// Just below the largest float (3.40282347e+38): Slang reads literals in double precision and
// turned 3.40282347e+38f (above FLT_MAX as a double) into infinity, which broke every range
// check against it on the Slang paths (stability corpus, rotation (1, inf) -> NaN).
#define OPENPBR_FLOAT_MAX 3.4e+38f

// Fast-math hooks, each off (0) by default; e.g. -DOPENPBR_FAST_RCP_SQRT=1. They trade a
// bounded relative error for speed in the hot helpers every lobe calls (openpbr_rsqrt,
// openpbr_sqrt, openpbr_normalize, openpbr_safe_normalize, openpbr_safe_sqrt):
//   OPENPBR_FAST_RCP_SQRT  1/sqrt(x): in C++ the bit-level initial guess of Lomont 2003 ("Fast
//                          Inverse Square Root") with one Newton step, relative error <= 1.8e-3;
//                          on GPUs inversesqrt is already the native approximate instruction,
//                          so the hook changes nothing there.
//   OPENPBR_FAST_SQRT      sqrt(x) as x * openpbr_rsqrt(x) (0 stays 0).
//   OPENPBR_FAST_NORMALIZE normalize(v) as v * openpbr_rsqrt(dot(v, v)).
// docs/accuracy-vs-time.md has the measured error and time of each.
#ifndef OPENPBR_FAST_RCP_SQRT
#define OPENPBR_FAST_RCP_SQRT 0
#endif
#ifndef OPENPBR_FAST_SQRT
#define OPENPBR_FAST_SQRT 0
#endif
#ifndef OPENPBR_FAST_NORMALIZE
#define OPENPBR_FAST_NORMALIZE 0
#endif

OPENPBR_NAMESPACE_BEGIN

// 1 / sqrt(x) for x > 0 (OPENPBR_FAST_RCP_SQRT).
OPENPBR_FUNC float openpbr_rsqrt(float x)
{
#if OPENPBR_FAST_RCP_SQRT && defined(OPENPBR_LANGUAGE_TARGET_CPP)
    const float guess = uintBitsToFloat(0x5f375a86u - (floatBitsToUint(x) >> 1u));
    return guess * (1.5f - 0.5f * x * guess * guess);
#else
    return inversesqrt(x);
#endif
}

// sqrt(x) for x >= 0 (OPENPBR_FAST_SQRT).
OPENPBR_FUNC float openpbr_sqrt(float x)
{
#if OPENPBR_FAST_SQRT
    // Infinity passes through (x * rsqrt(x) would be inf * 0); NaN and negatives give 0.
    return x > 0.0f ? (x <= OPENPBR_FLOAT_MAX ? x * openpbr_rsqrt(x) : x) : 0.0f;
#else
    return sqrt(x);
#endif
}

// v / |v| for a non-zero v (OPENPBR_FAST_NORMALIZE).
OPENPBR_FUNC vec3 openpbr_normalize(vec3 v)
{
#if OPENPBR_FAST_NORMALIZE
    return v * openpbr_rsqrt(dot(v, v));
#else
    return normalize(v);
#endif
}

OPENPBR_FUNC float openpbr_square(float x) { return x * x; }
OPENPBR_FUNC vec3 openpbr_square(vec3 x) { return x * x; }
// Through saturate(): built in for Slang, HLSL and Metal, defined by the C++, CUDA and GLSL
// backends, or the host's own (OPENPBR_USE_CUSTOM_SATURATE=1, interop/openpbr_interop.h).
OPENPBR_FUNC float openpbr_saturate(float x) { return saturate(x); }
OPENPBR_FUNC vec3 openpbr_saturate(vec3 x) { return saturate(x); }
OPENPBR_FUNC float openpbr_max3(vec3 v) { return max(v.x, max(v.y, v.z)); }
// max(a, b) whose derivative at a tie is a's, e.g. a term floored at 0 that is 0 exactly where a
// weight is 0 and grows from there: the differentiable build compares (Slang's max gives half the
// derivative to each argument at a tie); the plain build keeps max.
OPENPBR_FUNC float openpbr_max_first_at_tie(float a, float b)
{
    return OPENPBR_AUTODIFF != 0 ? (a >= b ? a : b) : max(a, b);
}
// min(a, b) whose derivative at a tie is a's (as openpbr_max_first_at_tie), e.g. a weight capped
// at 1 whose derivative at 1 is the one from below.
OPENPBR_FUNC float openpbr_min_first_at_tie(float a, float b)
{
    return OPENPBR_AUTODIFF != 0 ? (a <= b ? a : b) : min(a, b);
}
OPENPBR_FUNC vec3 openpbr_max_first_at_tie(vec3 a, vec3 b)
{
    return OPENPBR_AUTODIFF != 0 ? vec3(openpbr_max_first_at_tie(a.x, b.x), openpbr_max_first_at_tie(a.y, b.y),
                                        openpbr_max_first_at_tie(a.z, b.z))
                                 : max(a, b);
}

// sqrt that never sees a negative argument produced by rounding.
OPENPBR_FUNC float openpbr_safe_sqrt(float x) { return openpbr_sqrt(max(x, 0.0f)); }

// Replaces NaN and infinities by `fallback`, keeps finite values. Used by the input
// contract: isnan/isinf may be folded away under fast-math, so the test is written as a
// range check that also fails for NaN (every comparison with NaN is false).
OPENPBR_FUNC float openpbr_finite_or(float x, float fallback)
{
    return (x >= -OPENPBR_FLOAT_MAX && x <= OPENPBR_FLOAT_MAX) ? x : fallback;
}

// Clamp that maps NaN to the lower bound (plain clamp propagates NaN on some targets).
OPENPBR_FUNC float openpbr_clamp_finite(float x, float low, float high)
{
    return (x >= low) ? ((x <= high) ? x : high) : low;
}

OPENPBR_FUNC vec3 openpbr_clamp_finite(vec3 v, float low, float high)
{
    return vec3(openpbr_clamp_finite(v.x, low, high), openpbr_clamp_finite(v.y, low, high),
                openpbr_clamp_finite(v.z, low, high));
}

// Normalize that survives a zero vector (returns `fallback` instead of NaN).
OPENPBR_FUNC vec3 openpbr_safe_normalize(vec3 v, vec3 fallback)
{
    const float length_squared = dot(v, v);
    return (length_squared > 1e-30f && length_squared <= OPENPBR_FLOAT_MAX) ? v * openpbr_rsqrt(length_squared) : fallback;
}

// The two polynomials in u2 = u^2, written once for every argument type (float or vector):
// cos(pi u), and sin(pi u) / u.
#define OPENPBR_COS_PI_POLYNOMIAL(u2) \
    (1.0f +                           \
     (u2) * (-4.934802201f +          \
             (u2) * (4.058712126f +   \
                     (u2) * (-1.335262769f + (u2) * (0.2353306304f + (u2) * (-0.02580689139f + (u2)*0.001929574309f))))))
#define OPENPBR_SIN_PI_OVER_U_POLYNOMIAL(u2) \
    (3.141592654f +                          \
     (u2) * (-5.167712780f +                 \
             (u2) * (2.550164040f + (u2) * (-0.5992645293f + (u2) * (0.08214588661f + (u2) * -0.007370430946f)))))

// (sin(pi t), cos(pi t)) for t in [0, 1], e.g. t = 0.25 gives (0.7071, 0.7071). Taylor series
// in u = t - 1/2 (|pi u| <= pi/2): sin(pi t) = cos(pi u) to u^12 and cos(pi t) = -sin(pi u) to
// u^11, so the truncation error is at most 6e-9 and 6e-8 (the first terms left out,
// (pi/2)^14 / 14! and (pi/2)^13 / 13!); with float rounding the largest error measured is 1.7e-7
// (tests/bsdf/test_math.cpp). Why not sin and cos: the thin film needs six phases per film
// evaluation, its argument is already reduced to half a turn, and glibc's sincosf costs about 55
// instructions per call (callgrind) against 19 here; on GPUs the polynomial replaces the precise
// sin / cos sequences with a few FMAs.
OPENPBR_FUNC vec2 openpbr_sin_cos_pi(float t)
{
    const float u = t - 0.5f;
    const float u2 = u * u;
    return vec2(OPENPBR_COS_PI_POLYNOMIAL(u2), -(u * OPENPBR_SIN_PI_OVER_U_POLYNOMIAL(u2)));
}

// openpbr_sin_cos_pi in four lanes: sin(pi t) and cos(pi t) for each t in [0, 1].
OPENPBR_FUNC vec4 openpbr_sin_pi(vec4 t)
{
    const vec4 u = t - vec4(0.5f);
    const vec4 u2 = u * u;
    return OPENPBR_COS_PI_POLYNOMIAL(u2);
}

OPENPBR_FUNC vec4 openpbr_cos_pi(vec4 t)
{
    const vec4 u = t - vec4(0.5f);
    const vec4 u2 = u * u;
    return -(u * OPENPBR_SIN_PI_OVER_U_POLYNOMIAL(u2));
}

// Component `channel` (0, 1, 2) of v, for loops over the RGB channels (a select chain, which
// every target language compiles alike).
OPENPBR_FUNC float openpbr_channel_of(vec3 v, int channel) { return channel == 0 ? v.x : (channel == 1 ? v.y : v.z); }

// The unit vector along channel `channel` (0, 1, 2), to put one channel's value into a vec3.
OPENPBR_FUNC vec3 openpbr_channel_mask(int channel)
{
    return vec3(channel == 0 ? 1.0f : 0.0f, channel == 1 ? 1.0f : 0.0f, channel == 2 ? 1.0f : 0.0f);
}

// v with component `channel` (0, 1, 2) replaced by value (a select, so an infinite value does not
// turn the other components into NaN as a mask product would).
OPENPBR_FUNC vec3 openpbr_with_channel(vec3 v, int channel, float value)
{
    return vec3(channel == 0 ? value : v.x, channel == 1 ? value : v.y, channel == 2 ? value : v.z);
}

// The same for a vec4 (components 0 .. 3): what a loop of table reads kept rolled gathers its
// reads into (openpbr_film_lobe_node).
OPENPBR_FUNC vec4 openpbr_with_channel(vec4 v, int channel, float value)
{
    return vec4(channel == 0 ? value : v.x, channel == 1 ? value : v.y, channel == 2 ? value : v.z,
                channel == 3 ? value : v.w);
}

// Relative luminance Y of a working-space colour (slang/openpbr_working_space.h: the Y row of
// its RGB -> XYZ matrix, white (1, 1, 1) -> 1); used only for sampling decisions, never for
// values, so the weights do not affect the result's expectation.
OPENPBR_FUNC float openpbr_luminance(vec3 c) { return dot(c, OPENPBR_WORKING_SPACE_LUMINANCE_WEIGHTS); }

OPENPBR_NAMESPACE_END

#endif
