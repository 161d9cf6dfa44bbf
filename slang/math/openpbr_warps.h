// Warps from the unit square to directions and discs, with their densities.
#ifndef OPENPBR_WARPS_H
#define OPENPBR_WARPS_H

#include "openpbr_math.h"

OPENPBR_NAMESPACE_BEGIN

// Cosine-weighted hemisphere about +z (Malley's method with a polar disc map).
// pdf = cos(theta) / pi. Polar rather than concentric: one sin/cos pair and no branches.
OPENPBR_FUNC vec3 openpbr_sample_cosine_hemisphere(vec2 u)
{
    const float radius = sqrt(u.x);
    const float phi = OPENPBR_TWO_PI * u.y;
    return vec3(radius * cos(phi), radius * sin(phi), openpbr_safe_sqrt(1.0f - u.x));
}

OPENPBR_FUNC float openpbr_cosine_hemisphere_pdf(float cos_theta) { return max(cos_theta, 0.0f) * OPENPBR_INV_PI; }

// Uniform sphere, pdf = 1 / (4 pi); used by isotropic phase functions and tests.
OPENPBR_FUNC vec3 openpbr_sample_uniform_sphere(vec2 u)
{
    const float z = 1.0f - 2.0f * u.x;
    const float radius = openpbr_safe_sqrt(1.0f - z * z);
    const float phi = OPENPBR_TWO_PI * u.y;
    return vec3(radius * cos(phi), radius * sin(phi), z);
}

OPENPBR_NAMESPACE_END

#endif
