// Sampling of the GGX distribution of visible normals D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z.
// Two equivalent samplers (same density, different cost):
//  - openpbr_sample_vndf_spherical_cap: Dupuy & Benyoub 2023, "Sampling Visible GGX Normals
//    with Spherical Caps" (the default: no branch, no orthonormal basis);
//  - openpbr_sample_vndf_hemisphere: Heitz 2018, "Sampling the GGX Distribution of Visible
//    Normals" (JCGT 7(4)), kept for the accuracy/performance study.
// Both take the view direction in the upper hemisphere (wo.z > 0).
#ifndef OPENPBR_VNDF_H
#define OPENPBR_VNDF_H

#include "openpbr_ggx.h"

OPENPBR_NAMESPACE_BEGIN

OPENPBR_FUNC vec3 openpbr_sample_vndf_spherical_cap(vec3 view, vec2 alpha, vec2 u)
{
    // Stretch to the hemisphere configuration (alpha = 1).
    const vec3 view_std = normalize(vec3(view.x * alpha.x, view.y * alpha.y, view.z));
    // Uniform sample on the spherical cap bounded by the plane z = -view_std.z.
    const float phi = OPENPBR_TWO_PI * u.x;
    const float z = (1.0f - u.y) * (1.0f + view_std.z) - view_std.z;
    const float sin_theta = openpbr_safe_sqrt(1.0f - z * z);
    const vec3 cap = vec3(sin_theta * cos(phi), sin_theta * sin(phi), z);
    const vec3 h_std = cap + view_std;
    // Unstretch; h_std = 0 only on a measure-zero set, mapped to the normal.
    return openpbr_safe_normalize(vec3(h_std.x * alpha.x, h_std.y * alpha.y, max(h_std.z, 0.0f)),
                                  vec3(0.0f, 0.0f, 1.0f));
}

OPENPBR_FUNC vec3 openpbr_sample_vndf_hemisphere(vec3 view, vec2 alpha, vec2 u)
{
    const vec3 view_h = normalize(vec3(view.x * alpha.x, view.y * alpha.y, view.z));
    const float length_squared = view_h.x * view_h.x + view_h.y * view_h.y;
    const vec3 t1 = length_squared > 0.0f ? vec3(-view_h.y, view_h.x, 0.0f) * inversesqrt(length_squared)
                                          : vec3(1.0f, 0.0f, 0.0f);
    const vec3 t2 = cross(view_h, t1);
    const float r = sqrt(u.x);
    const float phi = OPENPBR_TWO_PI * u.y;
    const float p1 = r * cos(phi);
    const float s = 0.5f * (1.0f + view_h.z);
    const float p2 = (1.0f - s) * openpbr_safe_sqrt(1.0f - p1 * p1) + s * r * sin(phi);
    const vec3 n_h = t1 * p1 + t2 * p2 + view_h * openpbr_safe_sqrt(1.0f - p1 * p1 - p2 * p2);
    return openpbr_safe_normalize(vec3(alpha.x * n_h.x, alpha.y * n_h.y, max(n_h.z, 0.0f)),
                                  vec3(0.0f, 0.0f, 1.0f));
}

// Density of visible normals: G1(wo) max(0, wo.h) D(h) / wo.z.
OPENPBR_FUNC float openpbr_vndf_pdf(vec3 view, vec3 h, vec2 alpha)
{
    return openpbr_ggx_g1(view, alpha) * max(dot(view, h), 0.0f) * openpbr_ggx_d(h, alpha) / view.z;
}

OPENPBR_NAMESPACE_END

#endif
