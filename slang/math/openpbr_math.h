// Small numeric helpers shared by every lobe. Pure functions, no state.
#ifndef OPENPBR_MATH_H
#define OPENPBR_MATH_H

#include "../../interop/openpbr_interop.h"

#define OPENPBR_PI 3.14159265358979323846f
#define OPENPBR_TWO_PI 6.28318530717958647692f
#define OPENPBR_INV_PI 0.31830988618379067154f
// Smallest positive normal float: results below it are flushed by lavapipe and many GPUs,
// so no decision may depend on a denormal.
#define OPENPBR_FLOAT_MIN_NORMAL 1.17549435e-38f
#define OPENPBR_FLOAT_MAX 3.40282347e+38f

OPENPBR_NAMESPACE_BEGIN

OPENPBR_FUNC float openpbr_square(float x) { return x * x; }
OPENPBR_FUNC vec3 openpbr_square(vec3 x) { return x * x; }
OPENPBR_FUNC float openpbr_saturate(float x) { return clamp(x, 0.0f, 1.0f); }
OPENPBR_FUNC vec3 openpbr_saturate(vec3 x) { return clamp(x, vec3(0.0f), vec3(1.0f)); }
OPENPBR_FUNC float openpbr_max3(vec3 v) { return max(v.x, max(v.y, v.z)); }
OPENPBR_FUNC float openpbr_average(vec3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

// sqrt that never sees a negative argument produced by rounding.
OPENPBR_FUNC float openpbr_safe_sqrt(float x) { return sqrt(max(x, 0.0f)); }

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
    return (length_squared > 1e-30f && length_squared <= OPENPBR_FLOAT_MAX) ? v * inversesqrt(length_squared)
                                                                              : fallback;
}

// Luminance with Rec.709 / linear sRGB primaries; used only for sampling decisions, never
// for values, so the exact primaries do not affect the result's expectation.
OPENPBR_FUNC float openpbr_luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

OPENPBR_NAMESPACE_END

#endif
