// Sampling of the GGX distribution of visible normals D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z.
// Two equivalent samplers (same density, different cost):
//  - openpbr_sample_vndf_spherical_cap: Dupuy & Benyoub 2023, "Sampling Visible GGX Normals
//    with Spherical Caps" (the default: no branch, no orthonormal basis);
//  - openpbr_sample_vndf_hemisphere: Heitz 2018, "Sampling the GGX Distribution of Visible
//    Normals" (JCGT 7(4)), kept for the accuracy/performance study.
// Both take the view direction in the upper hemisphere (wo.z > 0).
// A third sampler, for reflection only, draws from a different density:
//  - openpbr_sample_vndf_bounded: Eto & Tokuyoshi 2023, "Bounded VNDF Sampling for Smith-GGX
//    Reflections" (SIGGRAPH Asia 2023 Technical Communications): the spherical cap is shrunk
//    so that fewer microfacet normals reflect the view below the horizon; its reflection
//    density is openpbr_vndf_bounded_reflection_pdf, not the VNDF's.
// OPENPBR_VNDF_METHOD chooses the sampler of the microfacet reflection lobes (metal, specular
// reflection, coat), e.g. -DOPENPBR_VNDF_METHOD=OPENPBR_VNDF_METHOD_BOUNDED; refraction always
// needs the full VNDF, so the dielectric lobe uses spherical caps under BOUNDED.
// openpbr_sample_vndf_reflection / openpbr_vndf_reflection_pdf are the chosen pair.
#ifndef OPENPBR_VNDF_H
#define OPENPBR_VNDF_H

#include "openpbr_ggx.h"

#define OPENPBR_VNDF_METHOD_SPHERICAL_CAP 0
#define OPENPBR_VNDF_METHOD_HEMISPHERE 1
#define OPENPBR_VNDF_METHOD_BOUNDED 2
// Default: spherical caps (no branch, no basis; the same density as Heitz 2018).
#ifndef OPENPBR_VNDF_METHOD
#define OPENPBR_VNDF_METHOD OPENPBR_VNDF_METHOD_SPHERICAL_CAP
#endif

OPENPBR_NAMESPACE_BEGIN

OPENPBR_FUNC vec3 openpbr_sample_vndf_spherical_cap(vec3 view, vec2 alpha, vec2 u)
{
    // Stretch to the hemisphere configuration (alpha = 1).
    const vec3 view_std = openpbr_normalize(vec3(view.x * alpha.x, view.y * alpha.y, view.z));
    // Uniform sample on the spherical cap bounded by the plane z = -view_std.z.
    const float phi = OPENPBR_TWO_PI * u.x;
    const float z = (1.0f - u.y) * (1.0f + view_std.z) - view_std.z;
    const float sin_theta = openpbr_safe_sqrt(1.0f - z * z);
    const vec3 cap = vec3(sin_theta * cos(phi), sin_theta * sin(phi), z);
    const vec3 h_std = cap + view_std;
    // Unstretch; h_std = 0 only on a measure-zero set, mapped to the normal.
    return openpbr_safe_normalize(vec3(h_std.x * alpha.x, h_std.y * alpha.y, max(h_std.z, 0.0f)), vec3(0.0f, 0.0f, 1.0f));
}

OPENPBR_FUNC vec3 openpbr_sample_vndf_hemisphere(vec3 view, vec2 alpha, vec2 u)
{
    const vec3 view_h = openpbr_normalize(vec3(view.x * alpha.x, view.y * alpha.y, view.z));
    const float length_squared = view_h.x * view_h.x + view_h.y * view_h.y;
    const vec3 t1 =
        length_squared > 0.0f ? vec3(-view_h.y, view_h.x, 0.0f) * inversesqrt(length_squared) : vec3(1.0f, 0.0f, 0.0f);
    const vec3 t2 = cross(view_h, t1);
    const float r = sqrt(u.x);
    const float phi = OPENPBR_TWO_PI * u.y;
    const float p1 = r * cos(phi);
    const float s = 0.5f * (1.0f + view_h.z);
    const float p2 = (1.0f - s) * openpbr_safe_sqrt(1.0f - p1 * p1) + s * r * sin(phi);
    const vec3 n_h = t1 * p1 + t2 * p2 + view_h * openpbr_safe_sqrt(1.0f - p1 * p1 - p2 * p2);
    return openpbr_safe_normalize(vec3(alpha.x * n_h.x, alpha.y * n_h.y, max(n_h.z, 0.0f)), vec3(0.0f, 0.0f, 1.0f));
}

// Density of visible normals: G1(wo) max(0, wo.h) D(h) / wo.z.
OPENPBR_FUNC float openpbr_vndf_pdf(vec3 view, vec3 h, vec2 alpha)
{
    return openpbr_ggx_g1(view, alpha) * max(dot(view, h), 0.0f) * openpbr_ggx_d(h, alpha) / view.z;
}

// The bound k of Eto & Tokuyoshi 2023 (eq. 5, isotropic bound with a = min(alpha_x, alpha_y),
// valid for a <= 1): the lower end of the cap is at z = -k view_std.z instead of -view_std.z.
// k in (0, 1]; 1 for alpha = 1 (nothing to bound) and towards grazing views.
OPENPBR_FUNC float openpbr_vndf_bounded_k(vec3 view, vec2 alpha)
{
    const float a = clamp(min(alpha.x, alpha.y), 0.0f, 1.0f);
    const float s = 1.0f + sqrt(view.x * view.x + view.y * view.y);
    const float a2 = a * a;
    const float s2 = s * s;
    return (1.0f - a2) * s2 / (s2 + a2 * view.z * view.z);
}

// Eto & Tokuyoshi 2023, Listing 1: the spherical-cap sampler with the cap's lower end raised
// to z = -k view_std.z; every removed normal would have reflected the view below the horizon.
OPENPBR_FUNC vec3 openpbr_sample_vndf_bounded(vec3 view, vec2 alpha, vec2 u)
{
    const vec3 view_std = openpbr_normalize(vec3(view.x * alpha.x, view.y * alpha.y, view.z));
    const float b = openpbr_vndf_bounded_k(view, alpha) * view_std.z;
    const float phi = OPENPBR_TWO_PI * u.x;
    const float z = (1.0f - u.y) * (1.0f + b) - b;
    const float sin_theta = openpbr_safe_sqrt(1.0f - z * z);
    const vec3 h_std = vec3(sin_theta * cos(phi), sin_theta * sin(phi), z) + view_std;
    return openpbr_safe_normalize(vec3(h_std.x * alpha.x, h_std.y * alpha.y, max(h_std.z, 0.0f)), vec3(0.0f, 0.0f, 1.0f));
}

// Solid-angle density of the reflected direction when h comes from openpbr_sample_vndf_bounded
// (Eto & Tokuyoshi 2023, eq. 7): D(h) / (2 (k wo.z + |(ax wo.x, ay wo.y, wo.z)|)). With k = 1
// it is the VNDF's G1(wo) D(h) / (4 wo.z).
OPENPBR_FUNC float openpbr_vndf_bounded_reflection_pdf(vec3 view, vec3 h, vec2 alpha)
{
    const float t = length(vec3(view.x * alpha.x, view.y * alpha.y, view.z));
    return openpbr_ggx_d(h, alpha) / (2.0f * (openpbr_vndf_bounded_k(view, alpha) * view.z + t));
}

// The microfacet reflection lobes' sampler (OPENPBR_VNDF_METHOD) ...
OPENPBR_FUNC vec3 openpbr_sample_vndf_reflection(vec3 view, vec2 alpha, vec2 u)
{
#if OPENPBR_VNDF_METHOD == OPENPBR_VNDF_METHOD_BOUNDED
    return openpbr_sample_vndf_bounded(view, alpha, u);
#elif OPENPBR_VNDF_METHOD == OPENPBR_VNDF_METHOD_HEMISPHERE
    return openpbr_sample_vndf_hemisphere(view, alpha, u);
#else
    return openpbr_sample_vndf_spherical_cap(view, alpha, u);
#endif
}

// ... and the density of the reflected direction it produces, for the half vector h.
// g1_view: G1(wo), which the lobes have already computed; inverse_4_cos_view = 1 / (4 wo.z).
OPENPBR_FUNC float openpbr_vndf_reflection_pdf(vec3 view, vec3 h, vec2 alpha, float g1_view, float inverse_4_cos_view)
{
#if OPENPBR_VNDF_METHOD == OPENPBR_VNDF_METHOD_BOUNDED
    OPENPBR_UNUSED(g1_view);
    OPENPBR_UNUSED(inverse_4_cos_view);
    return openpbr_vndf_bounded_reflection_pdf(view, h, alpha);
#else
    OPENPBR_UNUSED(view);
    return g1_view * openpbr_ggx_d(h, alpha) * inverse_4_cos_view;
#endif
}

// Full VNDF sampler for refraction (every method but BOUNDED, which falls back to caps).
OPENPBR_FUNC vec3 openpbr_sample_vndf_full(vec3 view, vec2 alpha, vec2 u)
{
#if OPENPBR_VNDF_METHOD == OPENPBR_VNDF_METHOD_HEMISPHERE
    return openpbr_sample_vndf_hemisphere(view, alpha, u);
#else
    return openpbr_sample_vndf_spherical_cap(view, alpha, u);
#endif
}

OPENPBR_NAMESPACE_END

#endif
