// Orthonormal shading frames. Directions enter the API in world space; every lobe works in
// the local frame of its basis (z = normal), so lobes never see an unnormalized basis.
#ifndef OPENPBR_BASIS_H
#define OPENPBR_BASIS_H

#include "openpbr_math.h"

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_Basis OPENPBR_DIFFERENTIABLE
{
    vec3 tangent;    // x axis, e.g. the direction of anisotropic stretching
    vec3 bitangent;  // y axis
    vec3 normal;     // z axis, e.g. the shading normal
};

// Frame from a normal alone: Duff et al. 2017, "Building an Orthonormal Basis, Revisited"
// (JCGT 6(1)). Branch-free apart from the sign, continuous except across z = 0.
OPENPBR_FUNC OpenPBR_Basis openpbr_make_basis(vec3 normal)
{
    const vec3 n = openpbr_safe_normalize(normal, vec3(0.0f, 0.0f, 1.0f));
    const float sign_z = n.z >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (sign_z + n.z);
    const float b = n.x * n.y * a;
    OpenPBR_Basis basis;
    basis.tangent = vec3(1.0f + sign_z * n.x * n.x * a, sign_z * b, -sign_z * n.x);
    basis.bitangent = vec3(b, sign_z + n.y * n.y * a, -n.y);
    basis.normal = n;
    return basis;
}

// Frame from a normal and a tangent: Gram-Schmidt. A tangent parallel to the normal, zero or
// non-finite falls back to the normal-only frame. `handedness` (+1 or -1, e.g. the sign stored
// in a mesh's tangent.w) chooses the bitangent side; 0 is treated as +1.
OPENPBR_FUNC OpenPBR_Basis openpbr_make_basis(vec3 normal, vec3 tangent, float handedness)
{
    // The normal as the fallback frame normalizes it; the rest of that frame is built only where
    // it is used (every prepare builds this frame, and a valid tangent is the common case).
    const vec3 n = openpbr_safe_normalize(normal, vec3(0.0f, 0.0f, 1.0f));
    const vec3 t_orthogonal = tangent - n * dot(n, tangent);
    const float length_squared = dot(t_orthogonal, t_orthogonal);
    // 1e-12 relative to a unit tangent: below this the direction is rounding noise.
    if (!(length_squared > 1e-12f * max(dot(tangent, tangent), 1e-30f)) || !(length_squared <= OPENPBR_FLOAT_MAX))
    {
        return openpbr_make_basis(normal);
    }
    // Gram-Schmidt twice ("twice is enough", Giraud et al. 2005, Numer. Math. 101): for a tangent
    // nearly parallel to the normal the first projection keeps a rounding error of ~1e-7 |tangent|
    // along n, which its normalization magnifies (a tangent 1.5e-5 rad off the normal gave a
    // frame whose to_world output had length 0.99); the second pass removes it.
    const vec3 t_first = t_orthogonal * inversesqrt(length_squared);
    const vec3 t_second = t_first - n * dot(n, t_first);
    OpenPBR_Basis basis;
    basis.normal = n;
    const float second_length_squared = dot(t_second, t_second);
    // openpbr_safe_normalize(t_second, fallback tangent), with the fallback built only when taken.
    basis.tangent = (second_length_squared > 1e-30f && second_length_squared <= OPENPBR_FLOAT_MAX)
                        ? t_second * openpbr_rsqrt(second_length_squared)
                        : openpbr_make_basis(normal).tangent;
    basis.bitangent = cross(n, basis.tangent) * (handedness < 0.0f ? -1.0f : 1.0f);
    return basis;
}

// Frame from normal, tangent and bitangent: the bitangent only contributes its handedness
// (which side of the normal-tangent plane it is on), as tangent frames from meshes do.
// A frame that is already orthonormal to within a few float roundings (unit normal and tangent
// within 1e-6 in squared length, orthogonal within 1e-6, as a mesh's normalized frame is) is
// kept as given, with the bitangent on its side: re-orthonormalizing would move it by rounding
// only, and its three square roots and divisions were a sixth of the default material's prepare.
OPENPBR_FUNC OpenPBR_Basis openpbr_make_basis(vec3 normal, vec3 tangent, vec3 bitangent)
{
    const vec3 normal_cross_tangent = cross(normal, tangent);
    const float handedness = dot(normal_cross_tangent, bitangent) < 0.0f ? -1.0f : 1.0f;
    // Written so that NaN fails every test and takes the general path.
    if (abs(dot(normal, normal) - 1.0f) <= 1e-6f && abs(dot(tangent, tangent) - 1.0f) <= 1e-6f &&
        abs(dot(normal, tangent)) <= 1e-6f)
    {
        OpenPBR_Basis basis;
        basis.normal = normal;
        basis.tangent = tangent;
        basis.bitangent = normal_cross_tangent * handedness;
        return basis;
    }
    return openpbr_make_basis(normal, tangent, handedness);
}

// Rotates the tangent about the normal by an angle given as (cos, sin), e.g. (0.7071, 0.7071)
// for 45 degrees. The pair is normalized first; (0, 0) or non-finite values mean no rotation.
OPENPBR_FUNC OpenPBR_Basis openpbr_rotate_basis(OPENPBR_IN(OpenPBR_Basis) basis, vec2 cos_sin)
{
    const float c0 = openpbr_finite_or(cos_sin.x, 1.0f);
    const float s0 = openpbr_finite_or(cos_sin.y, 0.0f);
    const float length_squared = c0 * c0 + s0 * s0;
    const bool valid = length_squared > 1e-30f && length_squared <= OPENPBR_FLOAT_MAX;
    const float scale = valid ? inversesqrt(length_squared) : 0.0f;
    const float c = valid ? c0 * scale : 1.0f;
    const float s = valid ? s0 * scale : 0.0f;
    OpenPBR_Basis rotated;
    rotated.normal = basis.normal;
    rotated.tangent = basis.tangent * c + basis.bitangent * s;
    rotated.bitangent = basis.bitangent * c - basis.tangent * s;
    return rotated;
}

OPENPBR_FUNC vec3 openpbr_to_local(OPENPBR_IN(OpenPBR_Basis) basis, vec3 v)
{
    return vec3(dot(v, basis.tangent), dot(v, basis.bitangent), dot(v, basis.normal));
}

OPENPBR_FUNC vec3 openpbr_to_world(OPENPBR_IN(OpenPBR_Basis) basis, vec3 v)
{
    return basis.tangent * v.x + basis.bitangent * v.y + basis.normal * v.z;
}

OPENPBR_NAMESPACE_END

#endif
