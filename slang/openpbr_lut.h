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

// Table ids and offsets into the flat array.
// 0: GGX reflection albedo with F = 1, E(mu, r): 2D.
// 1: dielectric reflection albedo with exact Fresnel, E_R(mu, r, x): 3D.
// 2: dielectric transmission albedo without the Fresnel factor, E_T0(mu, r, x): 3D
//    (OpenPBR "the transmission Fresnel factor may be omitted", spec section 2.3 of the digest).
// 3: dielectric reflection + transmission albedo with Fresnel, E_RT(mu, r, x): 3D.
#define OPENPBR_LUT_2D_COUNT (OPENPBR_LUT_2D_SIZE * OPENPBR_LUT_2D_SIZE)
#define OPENPBR_LUT_3D_COUNT (OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_SIZE)
#define OPENPBR_LUT_GGX_ALBEDO_OFFSET 0
#define OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET (OPENPBR_LUT_GGX_ALBEDO_OFFSET + OPENPBR_LUT_2D_COUNT)
#define OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET (OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET (OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_TOTAL_COUNT (OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET + OPENPBR_LUT_3D_COUNT)

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

OPENPBR_NAMESPACE_END

#endif
