// GGX / Trowbridge-Reitz microfacet distribution with Smith masking-shadowing
// (Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces";
// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs").
// All directions are in the local frame (z = macro normal); alpha = (alpha_x, alpha_y).
#ifndef OPENPBR_GGX_H
#define OPENPBR_GGX_H

#include "openpbr_math.h"

// Below this alpha a lobe is treated as a perfect mirror / refractor (a delta lobe): the
// peak of D would exceed 1/(pi 1e-6) and float directions could no longer resolve it. The
// same threshold as PBRT-v4's "effectively smooth" test. Example: roughness 0.02 gives
// alpha 4e-4, a delta lobe; roughness 0.05 gives alpha 2.5e-3, a glossy lobe.
#define OPENPBR_DELTA_ALPHA_THRESHOLD 1e-3f

OPENPBR_NAMESPACE_BEGIN

// OpenPBR 1.1 "Microfacet model": alpha = r^2, anisotropy a stretches along the tangent,
// alpha_t = r^2 sqrt(2 / (1 + (1 - a)^2)), alpha_b = (1 - a) alpha_t.
// The result is floored at a tiny positive value so no division by zero is possible;
// openpbr_ggx_is_delta decides whether the lobe is handled as a delta.
OPENPBR_FUNC vec2 openpbr_ggx_alpha(float roughness, float anisotropy)
{
    const float r = clamp(roughness, 0.0f, 1.0f);
    const float a = clamp(anisotropy, 0.0f, 1.0f);
    const float alpha_t = r * r * sqrt(2.0f / (1.0f + openpbr_square(1.0f - a)));
    const float alpha_b = (1.0f - a) * alpha_t;
    return vec2(max(alpha_t, 1e-7f), max(alpha_b, 1e-7f));
}

OPENPBR_FUNC bool openpbr_ggx_is_delta(vec2 alpha) { return max(alpha.x, alpha.y) < OPENPBR_DELTA_ALPHA_THRESHOLD; }

// D(h) = 1 / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2), for h in the upper hemisphere.
OPENPBR_FUNC float openpbr_ggx_d(vec3 h, vec2 alpha)
{
    const float x = h.x / alpha.x;
    const float y = h.y / alpha.y;
    const float denominator = x * x + y * y + h.z * h.z;
    return h.z > 0.0f ? 1.0f / (OPENPBR_PI * alpha.x * alpha.y * denominator * denominator) : 0.0f;
}

// Smith Lambda for GGX: (-1 + sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2)) / 2.
// Written as 2 / (1 + sqrt(1 + t)) form of G1 below to stay accurate at grazing angles.
OPENPBR_FUNC float openpbr_ggx_lambda(vec3 w, vec2 alpha)
{
    const float z2 = w.z * w.z;
    const float a2 = openpbr_square(alpha.x * w.x) + openpbr_square(alpha.y * w.y);
    // a2 / z2 overflows to inf for z -> 0; sqrt(inf) = inf and Lambda = inf, G1 = 0, as it should.
    return 0.5f * (openpbr_sqrt(1.0f + a2 / max(z2, OPENPBR_FLOAT_MIN_NORMAL)) - 1.0f);
}

OPENPBR_FUNC float openpbr_ggx_g1(vec3 w, vec2 alpha) { return 1.0f / (1.0f + openpbr_ggx_lambda(w, alpha)); }

// Height-correlated masking-shadowing G2 (Heitz 2014, eq. 99) from the two Lambdas.
OPENPBR_FUNC float openpbr_ggx_g2(float lambda_view, float lambda_light)
{
    return 1.0f / (1.0f + lambda_view + lambda_light);
}

OPENPBR_NAMESPACE_END

#endif
