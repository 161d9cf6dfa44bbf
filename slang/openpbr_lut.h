// Energy-compensation tables: layout, storage modes and interpolated look-ups.
//
// All tables live in one flat float array so every storage mode indexes them identically:
//   OPENPBR_LUT_MODE_ARRAY   constants compiled into the code (default for C++, CUDA, Metal);
//                            slang/generated/openpbr_lut_data.h, written by `openpbr lutgen`.
//   OPENPBR_LUT_MODE_BUFFER  a bound storage buffer named openpbr_lut_data (default for the
//                            Vulkan paths: llvmpipe cannot compile large constant arrays);
//                            the host uploads slang/generated/openpbr_lut.bin. In C++ the
//                            buffer is a pointer the application sets (openpbr_lut_data).
//   OPENPBR_LUT_MODE_TEXTURE the including code defines OPENPBR_LUT_FETCH itself (e.g. from a
//                            texel fetch of a 1D texture) before including this header.
// Array and buffer mode read the same floats with the same arithmetic: bit-identical results.
//
// Grids are node-centred: coordinate c in [0, 1] maps to c * (N - 1), so the table corners
// hold the exact end values (mu = 0 and 1, roughness 0 and 1).
// Axes, each chosen so the tabulated albedos are close to linear along it (linear
// interpolation error was the largest error of the first, uniform layout):
//   c_mu  = sqrt(mu), mu = cos(theta) of the view: nodes crowd towards grazing, where
//           Fresnel and shadowing change fastest;
//   c_r   = r = sqrt(alpha) (perceptually even roughness steps);
//   c_eta = 0.5 + sgn(y) sqrt(|y| / 2), y = (eta - 1) / (eta + 1): maps eta in [1/3, 3]
//           monotonically onto [0, 1], reciprocal IORs mirrored, with nodes crowding towards
//           eta = 1: near grazing the Fresnel factor depends on (eta^2 - 1) / mu^2, so it
//           changes fastest there (bases under a coat of similar IOR live there).
// The 4D table of anisotropic GGX adds two axes (see openpbr_lut_anisotropy_coordinate and
// openpbr_lut_azimuth_coordinate below):
//   c_a   = 1 - sqrt(1 - a), a the OpenPBR anisotropy: nodes crowd towards a = 1, where
//           alpha_b = (1 - a) alpha_t vanishes and the albedo bends fastest;
//   c_phi = the fraction of the change of the view's masking G1 between phi = pi/2 and
//           phi = 0 reached at the view azimuth phi (from the tangent): about cos^2 phi away
//           from grazing, it tracks the sharp rise of the albedo with phi near grazing views.
#ifndef OPENPBR_LUT_H
#define OPENPBR_LUT_H

#include "math/openpbr_math.h"

// Table sizes (the generator reads the same defines), e.g. 32 x 32 for the 2D table. The 3D
// size is odd so a node lies exactly at eta = 1 (c_eta = 0.5): the albedos are not smooth
// across eta = 1 (total internal reflection starts below it), and interpolation must not mix
// the two sides.
#ifndef OPENPBR_LUT_2D_SIZE
#define OPENPBR_LUT_2D_SIZE 32
#endif
#ifndef OPENPBR_LUT_3D_SIZE
#define OPENPBR_LUT_3D_SIZE 25
#endif
// The 4D table: OPENPBR_LUT_4D_SIZE nodes on its mu and roughness axes and
// OPENPBR_LUT_4D_ANISOTROPY_SIZE on its anisotropy and azimuth axes, e.g. 16 x 16 x 10 x 10.
// Error of the anisotropic albedo looked up with these sizes (relative, against Monte Carlo at
// 3000 random points with view cosine >= 0.1, roughness >= 0.05): median 0.04 %, 99th
// percentile 0.33 %, max 0.95 %, the largest errors where a rough lobe (r > 0.6, a > 0.8) is
// seen along its smooth bitangent (phi > 80 degrees) at mu = 0.1 - 0.3. 16 x 16 x 8 x 8 with
// cos^2 phi as the azimuth axis gave a max of 14 %; 24 x 24 x 16 x 16 still 0.75 %.
#ifndef OPENPBR_LUT_4D_SIZE
#define OPENPBR_LUT_4D_SIZE 16
#endif
#ifndef OPENPBR_LUT_4D_ANISOTROPY_SIZE
#define OPENPBR_LUT_4D_ANISOTROPY_SIZE 10
#endif

// Table ids and offsets into the flat array.
// 0: GGX reflection albedo with F = 1, E(mu, r): 2D.
// 1: dielectric reflection albedo with exact Fresnel, E_R(mu, r, x): 3D.
// 2: dielectric transmission albedo without the Fresnel factor, E_T0(mu, r, x): 3D
//    (OpenPBR "the transmission Fresnel factor may be omitted", spec section 2.3 of the digest).
// 3: dielectric reflection + transmission albedo with Fresnel, E_RT(mu, r, x): 3D.
// 4: anisotropic over isotropic GGX reflection albedo with F = 1, E(mu, r, a, phi) / E(mu, r):
//    4D, 1 at a = 0. The view azimuth phi is folded onto [0, pi/2] by the lobe's symmetries
//    phi -> -phi and phi -> pi - phi. A ratio rather than E itself because the isotropic shape
//    (e.g. the dip of E near mu = 0.1 at low roughness, which 16 mu nodes interpolate 0.5 % too
//    high) then comes from table 0's finer grid, and the 4D grid holds only what anisotropy
//    changes.
#define OPENPBR_LUT_2D_COUNT (OPENPBR_LUT_2D_SIZE * OPENPBR_LUT_2D_SIZE)
#define OPENPBR_LUT_3D_COUNT (OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_SIZE)
#define OPENPBR_LUT_4D_COUNT \
    (OPENPBR_LUT_4D_SIZE * OPENPBR_LUT_4D_SIZE * OPENPBR_LUT_4D_ANISOTROPY_SIZE * OPENPBR_LUT_4D_ANISOTROPY_SIZE)
#define OPENPBR_LUT_GGX_ALBEDO_OFFSET 0
#define OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET (OPENPBR_LUT_GGX_ALBEDO_OFFSET + OPENPBR_LUT_2D_COUNT)
#define OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET (OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET (OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET (OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_TOTAL_COUNT (OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET + OPENPBR_LUT_4D_COUNT)

#if !defined(OPENPBR_LUT_MODE_ARRAY) && !defined(OPENPBR_LUT_MODE_BUFFER) && !defined(OPENPBR_LUT_MODE_TEXTURE)
#if defined(OPENPBR_LANGUAGE_TARGET_SLANG) || defined(OPENPBR_LANGUAGE_TARGET_GLSL) || defined(OPENPBR_LANGUAGE_TARGET_HLSL)
#define OPENPBR_LUT_MODE_BUFFER 1
#else
#define OPENPBR_LUT_MODE_ARRAY 1
#endif
#endif

// Descriptor binding of the table buffer on the Vulkan paths, e.g. 0 in set 0 by default.
#ifndef OPENPBR_LUT_BINDING
#define OPENPBR_LUT_BINDING 0
#endif

#if defined(OPENPBR_LUT_MODE_ARRAY)
// The values come from one generated list (comma-separated float literals) wrapped in each
// language's array syntax, so the data is written once for every language.
#if defined(OPENPBR_LANGUAGE_TARGET_GLSL)
const float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = float[](
#include "generated/openpbr_lut_values.inc"
);
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#elif defined(OPENPBR_LANGUAGE_TARGET_SLANG) || defined(OPENPBR_LANGUAGE_TARGET_HLSL)
static const float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
};
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#elif defined(OPENPBR_LANGUAGE_TARGET_CUDA)
namespace openpbr {
// Global memory, not __constant__: the tables (187 KiB) exceed the 64 KiB constant bank.
__device__ const float openpbr_lut_data_device[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
};
static const float openpbr_lut_data_host[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
};
}
// __host__ __device__ functions see the array of the side they are compiled for.
#ifdef __CUDA_ARCH__
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data_device[index]
#else
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data_host[index]
#endif
#elif defined(OPENPBR_LANGUAGE_TARGET_METAL)
constant float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
};
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#else
namespace openpbr {
inline constexpr float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
};
}
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#endif
#elif defined(OPENPBR_LUT_MODE_BUFFER)
#if defined(OPENPBR_LANGUAGE_TARGET_SLANG)
// The explicit register keeps Slang's HLSL output in step with the Vulkan binding
// (HLSL front ends then map t<N> to binding N).
[[vk::binding(OPENPBR_LUT_BINDING, 0)]] StructuredBuffer<float> openpbr_lut_data : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_BINDING));
#elif defined(OPENPBR_LANGUAGE_TARGET_HLSL)
StructuredBuffer<float> openpbr_lut_data : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_BINDING), OPENPBR_CONCATENATE(space, OPENPBR_HLSL_REGISTER_SPACE));
#elif defined(OPENPBR_LANGUAGE_TARGET_GLSL)
layout(std430, set = 0, binding = OPENPBR_LUT_BINDING) readonly buffer OpenPBR_LutBuffer { float openpbr_lut_data[]; };
#elif defined(OPENPBR_LANGUAGE_TARGET_CPP)
namespace openpbr {
// Set by the application before any prepare/eval, e.g. to the contents of openpbr_lut.bin.
inline const float* openpbr_lut_data = nullptr;
}
#else
#error "OPENPBR_LUT_MODE_BUFFER is not available for this language; use OPENPBR_LUT_MODE_ARRAY"
#endif
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#elif !defined(OPENPBR_LUT_FETCH)
#error "OPENPBR_LUT_MODE_TEXTURE needs OPENPBR_LUT_FETCH(index) defined before including openpbr_lut.h"
#endif

OPENPBR_NAMESPACE_BEGIN

OPENPBR_FUNC float openpbr_lut_eta_coordinate(float eta)
{
    const float y = (eta - 1.0f) / (eta + 1.0f);
    return clamp(0.5f + (y < 0.0f ? -1.0f : 1.0f) * sqrt(0.5f * abs(y)), 0.0f, 1.0f);
}
OPENPBR_FUNC float openpbr_lut_roughness_coordinate(float alpha) { return clamp(sqrt(alpha), 0.0f, 1.0f); }
OPENPBR_FUNC float openpbr_lut_mu_coordinate(float mu) { return sqrt(clamp(mu, 0.0f, 1.0f)); }
OPENPBR_FUNC float openpbr_lut_anisotropy_coordinate(float anisotropy) { return 1.0f - sqrt(1.0f - clamp(anisotropy, 0.0f, 1.0f)); }

// Azimuth coordinate of a view at cosine mu with squared azimuth cosine cos_phi_squared (phi
// from the tangent) over the lobe of roughness r and anisotropy a (openpbr_ggx_alpha):
//   c_phi = (G1(pi/2) - G1(phi)) / (G1(pi/2) - G1(0)),
// G1 the view's Smith masking (Heitz 2014), which sees only the roughness projected onto the
// view azimuth, alpha_t q with q^2 = cos^2 phi + b^2 sin^2 phi, b = 1 - a. Why: towards grazing
// the albedo jumps where alpha_t q tan(theta) crosses 1, i.e. in a band of phi near pi/2 whose
// width shrinks with mu and b; this coordinate stretches that band over the axis (at
// 16 x 16 x 8 x 12 nodes the max interpolation error was 2.2 % with |cos phi| as the axis,
// 1.7 % with this one).
// With G1 = 2 / (1 + S(q)), S(q) = sqrt(1 + X q^2), X = (alpha_t tan(theta))^2, the quotient
// simplifies without cancellation to
//   c_phi = cos^2 phi (S(1) + S(b)) (S(1) + 1) / ((S(q) + S(b)) (S(q) + 1)),
// which tends to cos^2 phi where the masking no longer depends on phi (mu -> 1 or a -> 0).
// The floors of mu and alpha are the generator's (host/lut_generator.cpp).
OPENPBR_FUNC float openpbr_lut_azimuth_coordinate(float mu, float roughness, float anisotropy, float cos_phi_squared)
{
    const float b = 1.0f - clamp(anisotropy, 0.0f, 1.0f);
    const float r = clamp(roughness, 0.0f, 1.0f);
    const float cos_theta = clamp(mu, 1e-4f, 1.0f);
    const float alpha_t_squared = max(r * r * r * r, 1e-8f) * (2.0f / (1.0f + b * b));
    const float x = alpha_t_squared * (1.0f - cos_theta * cos_theta) / (cos_theta * cos_theta);
    const float cos_squared = clamp(cos_phi_squared, 0.0f, 1.0f);
    const float q_squared = cos_squared + b * b * (1.0f - cos_squared);
    const float s_1 = sqrt(1.0f + x);
    const float s_b = sqrt(1.0f + x * b * b);
    const float s_q = sqrt(1.0f + x * q_squared);
    return clamp(cos_squared * (s_1 + s_b) * (s_1 + 1.0f) / ((s_q + s_b) * (s_q + 1.0f)), 0.0f, 1.0f);
}

// cos^2 of the azimuth of a local direction from the tangent (x axis); 1 along the normal,
// where the azimuth is undefined and the anisotropic albedo does not depend on it.
OPENPBR_FUNC float openpbr_cos_azimuth_squared(vec3 direction)
{
    const float sin_theta_squared = direction.x * direction.x + direction.y * direction.y;
    return sin_theta_squared > 0.0f ? direction.x * direction.x / sin_theta_squared : 1.0f;
}

// Bilinear look-up at axis coordinates in [0, 1]; mu is the fastest-varying axis:
// index = offset + r_index * N + mu_index.
OPENPBR_FUNC float openpbr_lut_2d(int offset, float mu, float r)
{
    const float scale = float(OPENPBR_LUT_2D_SIZE - 1);
    const float fx = clamp(mu, 0.0f, 1.0f) * scale;
    const float fy = clamp(r, 0.0f, 1.0f) * scale;
    const int x0 = min(int(fx), OPENPBR_LUT_2D_SIZE - 2);
    const int y0 = min(int(fy), OPENPBR_LUT_2D_SIZE - 2);
    const float tx = fx - float(x0);
    const float ty = fy - float(y0);
    const int base = offset + y0 * OPENPBR_LUT_2D_SIZE + x0;
    const float v00 = OPENPBR_LUT_FETCH(base);
    const float v10 = OPENPBR_LUT_FETCH(base + 1);
    const float v01 = OPENPBR_LUT_FETCH(base + OPENPBR_LUT_2D_SIZE);
    const float v11 = OPENPBR_LUT_FETCH(base + OPENPBR_LUT_2D_SIZE + 1);
    return mix(mix(v00, v10, tx), mix(v01, v11, tx), ty);
}

// Trilinear look-up: index = offset + (x_index * N + r_index) * N + mu_index.
OPENPBR_FUNC float openpbr_lut_3d(int offset, float mu, float r, float x)
{
    const float scale = float(OPENPBR_LUT_3D_SIZE - 1);
    const float fx = clamp(mu, 0.0f, 1.0f) * scale;
    const float fy = clamp(r, 0.0f, 1.0f) * scale;
    const float fz = clamp(x, 0.0f, 1.0f) * scale;
    const int x0 = min(int(fx), OPENPBR_LUT_3D_SIZE - 2);
    const int y0 = min(int(fy), OPENPBR_LUT_3D_SIZE - 2);
    const int z0 = min(int(fz), OPENPBR_LUT_3D_SIZE - 2);
    const float tx = fx - float(x0);
    const float ty = fy - float(y0);
    const float tz = fz - float(z0);
    const int n = OPENPBR_LUT_3D_SIZE;
    const int base = offset + (z0 * n + y0) * n + x0;
    const float v000 = OPENPBR_LUT_FETCH(base);
    const float v100 = OPENPBR_LUT_FETCH(base + 1);
    const float v010 = OPENPBR_LUT_FETCH(base + n);
    const float v110 = OPENPBR_LUT_FETCH(base + n + 1);
    const float v001 = OPENPBR_LUT_FETCH(base + n * n);
    const float v101 = OPENPBR_LUT_FETCH(base + n * n + 1);
    const float v011 = OPENPBR_LUT_FETCH(base + n * n + n);
    const float v111 = OPENPBR_LUT_FETCH(base + n * n + n + 1);
    const float front = mix(mix(v000, v100, tx), mix(v010, v110, tx), ty);
    const float back = mix(mix(v001, v101, tx), mix(v011, v111, tx), ty);
    return mix(front, back, tz);
}

// Trilinear blend of the 2 x 2 x 2 nodes from base with strides 1, stride_y and stride_z.
OPENPBR_FUNC float openpbr_lut_trilinear(int base, int stride_y, int stride_z, float tx, float ty, float tz)
{
    const float v000 = OPENPBR_LUT_FETCH(base);
    const float v100 = OPENPBR_LUT_FETCH(base + 1);
    const float v010 = OPENPBR_LUT_FETCH(base + stride_y);
    const float v110 = OPENPBR_LUT_FETCH(base + stride_y + 1);
    const float v001 = OPENPBR_LUT_FETCH(base + stride_z);
    const float v101 = OPENPBR_LUT_FETCH(base + stride_z + 1);
    const float v011 = OPENPBR_LUT_FETCH(base + stride_z + stride_y);
    const float v111 = OPENPBR_LUT_FETCH(base + stride_z + stride_y + 1);
    const float front = mix(mix(v000, v100, tx), mix(v010, v110, tx), ty);
    const float back = mix(mix(v001, v101, tx), mix(v011, v111, tx), ty);
    return mix(front, back, tz);
}

// Quadrilinear look-up of the 4D table (16 fetches):
// index = offset + ((phi_index * M + a_index) * N + r_index) * N + mu_index,
// N = OPENPBR_LUT_4D_SIZE, M = OPENPBR_LUT_4D_ANISOTROPY_SIZE.
OPENPBR_FUNC float openpbr_lut_4d(int offset, float mu, float r, float a, float phi)
{
    const int n = OPENPBR_LUT_4D_SIZE;
    const int m = OPENPBR_LUT_4D_ANISOTROPY_SIZE;
    const float scale = float(n - 1);
    const float anisotropy_scale = float(m - 1);
    const float fx = clamp(mu, 0.0f, 1.0f) * scale;
    const float fy = clamp(r, 0.0f, 1.0f) * scale;
    const float fz = clamp(a, 0.0f, 1.0f) * anisotropy_scale;
    const float fw = clamp(phi, 0.0f, 1.0f) * anisotropy_scale;
    const int x0 = min(int(fx), n - 2);
    const int y0 = min(int(fy), n - 2);
    const int z0 = min(int(fz), m - 2);
    const int w0 = min(int(fw), m - 2);
    const int stride_a = n * n;
    const int stride_phi = n * n * m;
    const int base = offset + w0 * stride_phi + z0 * stride_a + y0 * n + x0;
    const float near_phi = openpbr_lut_trilinear(base, n, stride_a, fx - float(x0), fy - float(y0), fz - float(z0));
    const float far_phi =
        openpbr_lut_trilinear(base + stride_phi, n, stride_a, fx - float(x0), fy - float(y0), fz - float(z0));
    return mix(near_phi, far_phi, fw - float(w0));
}

// Directional albedo of GGX reflection with F = 1 (single scattering).
OPENPBR_FUNC float openpbr_ggx_albedo(float mu, float alpha)
{
    return openpbr_lut_2d(OPENPBR_LUT_GGX_ALBEDO_OFFSET, openpbr_lut_mu_coordinate(mu),
                          openpbr_lut_roughness_coordinate(alpha));
}

// Directional albedo of GGX reflection off a dielectric of relative IOR eta (single scattering).
OPENPBR_FUNC float openpbr_dielectric_reflection_albedo(float mu, float alpha, float eta)
{
    return openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET, openpbr_lut_mu_coordinate(mu), openpbr_lut_roughness_coordinate(alpha),
                          openpbr_lut_eta_coordinate(eta));
}

// Directional albedo of the GGX BTDF without its Fresnel factor (single scattering).
OPENPBR_FUNC float openpbr_dielectric_transmission_albedo(float mu, float alpha, float eta)
{
    return openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET, openpbr_lut_mu_coordinate(mu), openpbr_lut_roughness_coordinate(alpha),
                          openpbr_lut_eta_coordinate(eta));
}

// Directional albedo of reflection plus transmission of a rough dielectric interface.
OPENPBR_FUNC float openpbr_dielectric_interface_albedo(float mu, float alpha, float eta)
{
    return openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET, openpbr_lut_mu_coordinate(mu), openpbr_lut_roughness_coordinate(alpha),
                          openpbr_lut_eta_coordinate(eta));
}

// E(mu, r, a, phi) / E(mu, r) of GGX reflection with F = 1 (single scattering): the anisotropic
// lobe of OpenPBR's roughness and anisotropy (openpbr_ggx_alpha) over the isotropic lobe of
// alpha = roughness^2, the view at cosine mu and at squared azimuth cosine cos_phi_squared from
// the tangent (openpbr_cos_azimuth_squared of the local view). 1 at anisotropy 0.
OPENPBR_FUNC float openpbr_ggx_anisotropy_ratio(float mu, float roughness, float anisotropy, float cos_phi_squared)
{
    return openpbr_lut_4d(OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET, openpbr_lut_mu_coordinate(mu),
                          clamp(roughness, 0.0f, 1.0f), openpbr_lut_anisotropy_coordinate(anisotropy),
                          openpbr_lut_azimuth_coordinate(mu, roughness, anisotropy, cos_phi_squared));
}

// Directional albedo of anisotropic GGX reflection with F = 1 (single scattering), arguments as
// openpbr_ggx_anisotropy_ratio. Equals openpbr_ggx_albedo(mu, roughness^2) at anisotropy 0,
// where that alone is the cheaper look-up.
OPENPBR_FUNC float openpbr_ggx_albedo_anisotropic(float mu, float roughness, float anisotropy, float cos_phi_squared)
{
    const float r = clamp(roughness, 0.0f, 1.0f);
    return openpbr_ggx_albedo(mu, r * r) * openpbr_ggx_anisotropy_ratio(mu, r, anisotropy, cos_phi_squared);
}

OPENPBR_NAMESPACE_END

#endif
