// Energy-compensation tables: layout, storage modes and interpolated look-ups.
//
// All tables live in one flat float array so every storage mode indexes them identically:
//   OPENPBR_LUT_MODE_ARRAY   constants compiled into the code (default for C++, CUDA, Metal);
//                            slang/generated/openpbr_lut_values.inc, written by `openpbr lutgen`.
//   OPENPBR_LUT_MODE_BUFFER  a bound storage buffer named openpbr_lut_data (default for the
//                            Vulkan paths: llvmpipe cannot compile large constant arrays);
//                            the host uploads the same floats (openpbr_lut.bin, which the
//                            build derives from the .inc). In C++ the
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
// The 3D tables of the dielectric interface (tables 1-3) replace c_mu by a view axis that
// follows the relative IOR and split eta into two halves (openpbr_lut_3d_coordinates):
//   c_eta: eta < 1 and eta > 1 are two separate halves of OPENPBR_LUT_3D_ETA_SIZE / 2 nodes,
//          each evenly spaced in w = asinh(s / s_0) + 4 s from s = s_0 (the node at eta = 1) to
//          s = 1 (eta = 1/3 or 3), s = sqrt(2 |y|), y = (eta - 1) / (eta + 1), s_0 =
//          OPENPBR_LUT_ETA_KNEE: s is proportional to the critical cosine below near eta = 1,
//          and logarithmic steps in it there keep the ratio of the view cosines that
//          neighbouring eta slices put on one node near 1.6 (24 nodes), so the albedos of rough
//          lobes, which change on the scale of mu itself, stay smooth along eta; the linear
//          term keeps steps of s below 0.1 towards the range ends (asinh alone left eta nodes at
//          1.29, 1.65 and 3: white furnace of glass of IOR 2 at normal view 0.987);
//   u_mu:  sqrt(mu) warped piecewise linearly so that the critical cosine
//          mu_c = sqrt(1 - min(eta, 1/eta)^2) always lies at a node u_mu = S:
//          u_mu = S sqrt(mu / mu_c) below it, S + (1 - S) (sqrt(mu) - sqrt(mu_c)) / (1 - sqrt(mu_c))
//          above it; S = 1/2 below eta = 1, OPENPBR_LUT_VIEW_SPLIT_ABOVE = 3/4 at and above it.
//          Why mu_c: below eta = 1 total internal reflection sets in at the view cosine mu_c
//          (Snell's law, sin(theta) = eta), a kink in every albedo that moves across the whole mu
//          axis as eta goes from 1/3 to 1; above eta = 1 the Fresnel factor at grazing views is a
//          function of mu / sqrt(eta^2 - 1) (Fresnel's equations with cos_t^2 = 1 - (1 - mu^2) /
//          eta^2), whose scale is the same mu_c to first order in eta - 1. On a fixed mu axis both
//          fall inside a cell of one eta node and outside that of the next, and interpolating
//          along eta mixed the two (errors up to 0.97 in E_R at eta 0.999); on this axis the
//          nodes of neighbouring eta slices sit at the same fraction of mu_c.
//          Why S = 3/4 above eta = 1: seen from outside nothing steps at mu_c there, while a
//          near-mirror lobe's shadowing bends at grazing views (mu about 2 alpha). With S = 1/2
//          the tables read E_R of smooth glass (roughness 0.05) 0.006 low at cos 0.02 and the
//          white furnace gained 0.6 % there at relative IOR 1.5-3; with 3/4 (spacing in sqrt(mu)
//          below mu_c 2/3 of before) 1.0029-1.0039. The sweep's rows at cos 0.001 lose at most
//          1.1 % (was 5.3 %: relative IOR 1.05, roughness 1, 0.947 -> 1.000) and gain at most
//          0.43 % (was 0.37 %); the largest cost above mu_c is rough glass near index matching
//          from inside at cos 0.5 (relative IOR 1.01, roughness 1: 0.9991 -> 0.9970).
//          Below eta = 1 each half is warped further towards mu_c on the scale of the step
//          itself (openpbr_lut_step_warp): a microfacet tilted by delta (about alpha for GGX)
//          meets the view at the critical angle when the view is delta away from it, so the
//          albedos go from total internal reflection to the Fresnel factor's square-root edge
//          (F ~ 1 - C sqrt(mu - mu_c)) over a width w = alpha sin(theta_c) in mu, i.e.
//          alpha eta / (2 sqrt(mu_c)) in sqrt(mu) (sin(theta_c) = eta). With d the distance
//          from sqrt(mu_c) as a fraction of the half and k = K w / (half's length), the half's
//          coordinate is (asinh(d / k) + L d) / (asinh(1 / k) + L): even steps of about k next
//          to mu_c, logarithmic ones beyond, and linear (the axis above) once k >> 1 (the
//          roughest lobes: openpbr_lut_step_width uses alpha / (1 - alpha)). Because w is
//          proportional to alpha = r^2 for smooth lobes, a node past the step keeps its sqrt(d)
//          (the Fresnel edge) linear in r, the roughness axis. On the plain axis 16 cells per
//          side put the step of smooth lobes inside one cell: E_T0 read 0.49 wrong and E_R 0.46
//          next to mu_c (1D study at exact eta nodes, 2^15 samples per value, roughness
//          0.02-0.5, views within 0.15 of mu_c); with the warp 0.044 and 0.13, and at most 0.025
//          and 0.042 where mu_c >= 0.007 (the 0.13 at mu_c = 0.002, eta 1 - 2e-6, at mu = 8e-4);
//          mean error over the study 0.041 -> 0.0024 (with L = 2 on both halves; docs/stability.md
//          "Critical angle below relative IOR 1"). K = OPENPBR_LUT_STEP_WIDTH_SCALE;
//          L = OPENPBR_LUT_STEP_LINEAR_WEIGHT_ABOVE past mu_c and
//          OPENPBR_LUT_STEP_LINEAR_WEIGHT_BELOW before it (longer cells at grazing views).
// The two nodes at eta = 1 hold the one-sided limits (s = s_0, eta = 1 -/+ 2^-20): at grazing
// views the Fresnel factor tends to a function of mu / mu_c that differs between the sides (1
// under total internal reflection below eta = 1), and is 0 at eta = 1 itself. Closer to
// eta = 1 the look-up reads the limit node.
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

// Table sizes (the generator reads the same defines; every other file takes them from here),
// e.g. 128 x 128 for the 2D table and 33 x 33 x 48 (u_mu, r, c_eta) for the 3D tables. The eta
// size is even: two halves, eta < 1 and eta > 1, each ending in its own node at eta = 1 (the
// albedos are not smooth across eta = 1, and interpolation never mixes the two sides).
#ifndef OPENPBR_LUT_2D_SIZE
#define OPENPBR_LUT_2D_SIZE 128
#endif
#ifndef OPENPBR_LUT_3D_SIZE
#define OPENPBR_LUT_3D_SIZE 33
#endif
#ifndef OPENPBR_LUT_3D_ETA_SIZE
#define OPENPBR_LUT_3D_ETA_SIZE 48
#endif
// Weight of the linear term of the eta axis (see c_eta above), e.g. 4.
#define OPENPBR_LUT_ETA_LINEAR_WEIGHT 4.0f
// The eta axis' knee s_0 = 2^-10, e.g. 9.765625e-4: the eta = 1 nodes lie at s = s_0, i.e.
// |eta - 1| = 2^-20 (to first order): close enough to be the one-sided limits, far enough that
// their critical cosine (1.4e-3) lies above the smallest view cosine OPENPBR_LUT_MIN_VIEW_COSINE.
#define OPENPBR_LUT_ETA_KNEE 9.765625e-4f
// Distance from eta = 1 below which the critical cosine is that of the eta = 1 nodes, 2^-20.
#define OPENPBR_LUT_UNIT_ETA_STEP 9.5367431640625e-7f
// The view axis' warp towards the critical cosine below eta = 1 (u_mu above): the scale K of
// the step's width, e.g. 0.5; the weight L of the warp's linear term past mu_c, e.g. 2, and
// before it, e.g. 16; and the smallest alpha the width takes, e.g. 1e-4 (the generator's
// smallest alpha). 1D study (K 0.25-2, L 1-16): every choice within a factor 2 of the others
// next to mu_c, K 0.5 and L 2 the smallest mean error. Before mu_c the half ends at grazing
// views, where rough lobes' albedos change fastest: with L = 2 its last cells were up to 2.2
// times as long as the plain axis' and rough glass below eta = 1 lost up to 14 % more at
// cos 0.001 (white furnace, eta 0.9, roughness 0.5: 0.845 -> 0.706); L = 16 keeps them within
// 1.2 times (roughness >= 0.2).
#define OPENPBR_LUT_STEP_WIDTH_SCALE 0.5f
#define OPENPBR_LUT_STEP_LINEAR_WEIGHT_ABOVE 2.0f
#define OPENPBR_LUT_STEP_LINEAR_WEIGHT_BELOW 16.0f
#define OPENPBR_LUT_STEP_MIN_ALPHA 1e-4f
// Fraction of the view axis below the critical cosine's scale mu_c = sqrt(1 - 1/eta^2) at and
// above eta = 1, e.g. 0.75 (24 of the 32 cells; a multiple of 1 / (OPENPBR_LUT_3D_SIZE - 1), so
// mu_c is a node). Below eta = 1 the halves are equal (mu_c is the step there).
#ifndef OPENPBR_LUT_VIEW_SPLIT_ABOVE
#define OPENPBR_LUT_VIEW_SPLIT_ABOVE 0.75f
#endif

// Smallest view cosine the tables hold, e.g. 1e-4: the generator's floor (minimum_mu in
// host/tables/lut_generator.cpp); openpbr_prepare raises closer-to-grazing views to it.
#define OPENPBR_LUT_MIN_VIEW_COSINE 1e-4f
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
// Table 5, the microfacet cosines a GGX reflection lobe reflects at (host/tables/
// film_table_generator.h; read by openpbr_film_lobe_cumulative for the thin film's lobe
// averages): OPENPBR_LUT_FILM_QUANTILE_SIZE nodes on its probability axis, OPENPBR_LUT_FILM_SIZE
// on its view (c_mu) and roughness (c_r) axes, two channels (the quantile and the first partial
// moment), e.g. 41 x 32 x 32 x 2. The probability nodes (openpbr_film_lobe_probability) are
// OPENPBR_LUT_FILM_CORE_SIZE even ones, p = j / (OPENPBR_LUT_FILM_CORE_SIZE - 1) (e.g. 33: the
// estimate's equal shares and quartiles are among them), and OPENPBR_LUT_FILM_TAIL_NODES more
// in each tail between the first even node and the end, halving towards it (e.g. 4: 1/64,
// 1/128, 1/256 and 1/512 from each end). Measured against the dense lobe average
// (tests/bsdf/test_film_estimate.cpp, docs/thin-film-estimate.md): 17 even nodes doubled the
// largest error of the film's change under a coat of IOR 1.6 (0.20 against 0.10 with 33; 65 gave
// 0.10). The tail nodes: a GGX lobe's first and last 1/32 of light spans cosines far from the
// rest (view cos 0.5, alpha 0.0167: the first 1/32 spans 0.25-0.47), where a film's critical
// cosine can lie and its thresholds do (film 1.4 under a medium of IOR 1.565, critical cosine
// 0.447): one cell there put 0.0099 of the light below 0.447 where the lobe has 0.0145, and the
// change of a 1.5 um film 0.013 low; with the tail nodes 0.003 (docs/thin-film-estimate.md).
#define OPENPBR_LUT_FILM_CORE_SIZE 33
#define OPENPBR_LUT_FILM_TAIL_NODES 4
#define OPENPBR_LUT_FILM_QUANTILE_SIZE (OPENPBR_LUT_FILM_CORE_SIZE + 2 * OPENPBR_LUT_FILM_TAIL_NODES)
// The bisection's steps over table 5's nodes (openpbr_film_lobe_cumulative): ceil(log2(nodes - 1)).
#define OPENPBR_LUT_FILM_BISECTION_STEPS 6
#if OPENPBR_LUT_FILM_QUANTILE_SIZE - 1 > (1 << OPENPBR_LUT_FILM_BISECTION_STEPS) || \
    OPENPBR_LUT_FILM_QUANTILE_SIZE - 1 <= (1 << (OPENPBR_LUT_FILM_BISECTION_STEPS - 1))
#error "OPENPBR_LUT_FILM_BISECTION_STEPS must be ceil(log2(OPENPBR_LUT_FILM_QUANTILE_SIZE - 1))"
#endif
#define OPENPBR_LUT_FILM_SIZE 32
#define OPENPBR_LUT_FILM_CHANNEL_COUNT 2

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
// 5: the microfacet cosines of the light a GGX reflection lobe reflects (quantiles and partial
//    moments over the probability p, the view and the roughness), for the thin film: its own
//    tracked file, slang/generated/openpbr_film_lut_values.inc, whose values follow those of
//    openpbr_lut_values.inc (tables 0-4, OPENPBR_LUT_COMPENSATION_COUNT values) in the flat
//    array and in openpbr_lut.bin.
#define OPENPBR_LUT_2D_COUNT (OPENPBR_LUT_2D_SIZE * OPENPBR_LUT_2D_SIZE)
#define OPENPBR_LUT_3D_COUNT (OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_ETA_SIZE)
#define OPENPBR_LUT_4D_COUNT \
    (OPENPBR_LUT_4D_SIZE * OPENPBR_LUT_4D_SIZE * OPENPBR_LUT_4D_ANISOTROPY_SIZE * OPENPBR_LUT_4D_ANISOTROPY_SIZE)
#define OPENPBR_LUT_GGX_ALBEDO_OFFSET 0
#define OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET (OPENPBR_LUT_GGX_ALBEDO_OFFSET + OPENPBR_LUT_2D_COUNT)
#define OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET (OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET (OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET (OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET + OPENPBR_LUT_3D_COUNT)
#define OPENPBR_LUT_FILM_COUNT \
    (OPENPBR_LUT_FILM_QUANTILE_SIZE * OPENPBR_LUT_FILM_SIZE * OPENPBR_LUT_FILM_SIZE * OPENPBR_LUT_FILM_CHANNEL_COUNT)
#define OPENPBR_LUT_FILM_OFFSET (OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET + OPENPBR_LUT_4D_COUNT)
#define OPENPBR_LUT_COMPENSATION_COUNT OPENPBR_LUT_FILM_OFFSET
#define OPENPBR_LUT_TOTAL_COUNT (OPENPBR_LUT_FILM_OFFSET + OPENPBR_LUT_FILM_COUNT)

// Compensation mode, the knob of docs/accuracy-vs-time.md, e.g.
// -DOPENPBR_COMPENSATION_MODE=OPENPBR_COMPENSATION_ANALYTIC. Default TABLE.
//   TABLE     the tables below (Turquin 2019 compensation and the dielectric 1 / E terms);
//   ANALYTIC  the GGX albedo E(mu, r) of table 0 from a 15-term polynomial fit (in the spirit of
//             the fits of real-time and "enterprise" PBR models) and no anisotropy correction;
//             the dielectric tables stay (their 3D shape has no cheap fit);
//   NONE      no multiple-scattering compensation: the albedos that only compensation reads
//             (E_ggx, E_T0, E_RT, the anisotropy ratio) are 1. E_R stays a table: it is the
//             layering weight 1 - E_R of the spec's albedo scaling, not a compensation.
#define OPENPBR_COMPENSATION_NONE 0
#define OPENPBR_COMPENSATION_ANALYTIC 1
#define OPENPBR_COMPENSATION_TABLE 2
#ifndef OPENPBR_COMPENSATION_MODE
#define OPENPBR_COMPENSATION_MODE OPENPBR_COMPENSATION_TABLE
#endif

// 16-bit table values, buffer mode only, e.g. -DOPENPBR_LUT_16BIT=1. Default 0 (float32).
#ifndef OPENPBR_LUT_16BIT
#define OPENPBR_LUT_16BIT 0
#endif

// Texture tables (OPENPBR_USE_TEXTURE_LUTS=1): ids, fill instructions and the host's macros.
#include "openpbr_lut_textures.h"

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
    ,
#include "generated/openpbr_film_lut_values.inc"
);
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#elif defined(OPENPBR_LANGUAGE_TARGET_SLANG) || defined(OPENPBR_LANGUAGE_TARGET_HLSL)
static const float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
    ,
#include "generated/openpbr_film_lut_values.inc"
};
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#elif defined(OPENPBR_LANGUAGE_TARGET_CUDA)
namespace openpbr {
// Global memory, not __constant__: the tables (about 0.2 MiB) exceed the 64 KiB constant bank.
__device__ const float openpbr_lut_data_device[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
    ,
#include "generated/openpbr_film_lut_values.inc"
};
static const float openpbr_lut_data_host[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
    ,
#include "generated/openpbr_film_lut_values.inc"
};
}  // namespace openpbr
   // __host__ __device__ functions see the array of the side they are compiled for.
#ifdef __CUDA_ARCH__
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data_device[index]
#else
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data_host[index]
#endif
#elif defined(OPENPBR_LANGUAGE_TARGET_METAL)
constant float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
    ,
#include "generated/openpbr_film_lut_values.inc"
};
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#else
namespace openpbr {
inline constexpr float openpbr_lut_data[OPENPBR_LUT_TOTAL_COUNT] = {
#include "generated/openpbr_lut_values.inc"
    ,
#include "generated/openpbr_film_lut_values.inc"
};
}  // namespace openpbr
   // Qualified: a host interop layer (OPENPBR_USE_CUSTOM_INTEROP) may put the BSDF in another
   // namespace; the shared table stays in openpbr.
#define OPENPBR_LUT_FETCH(index) ::openpbr::openpbr_lut_data[index]
#endif
#elif defined(OPENPBR_LUT_MODE_BUFFER) && OPENPBR_LUT_16BIT
// 16-bit table values (OPENPBR_LUT_16BIT): IEEE halves, two per 32-bit word, the value at
// index i in the low (i even) or high (i odd) half of word i / 2; half the memory and
// bandwidth of float32, at a rounding error of at most 2^-11 relative (the accuracy study
// measures what that does to the albedos).
#if defined(OPENPBR_LANGUAGE_TARGET_SLANG)
[[vk::binding(OPENPBR_LUT_BINDING, 0)]] StructuredBuffer<uint> openpbr_lut_data
    : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_BINDING));
#define OPENPBR_LUT_FETCH(index) f16tof32(openpbr_lut_data[(index) >> 1] >> (((index)&1) * 16))
#elif defined(OPENPBR_LANGUAGE_TARGET_HLSL)
StructuredBuffer<uint> openpbr_lut_data
    : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_BINDING), OPENPBR_CONCATENATE(space, OPENPBR_HLSL_REGISTER_SPACE));
#define OPENPBR_LUT_FETCH(index) f16tof32(openpbr_lut_data[(index) >> 1] >> (((index)&1) * 16))
#elif defined(OPENPBR_LANGUAGE_TARGET_GLSL)
layout(std430, set = 0, binding = OPENPBR_LUT_BINDING) readonly buffer OpenPBR_LutBuffer { uint openpbr_lut_data[]; };
#define OPENPBR_LUT_FETCH(index) (unpackHalf2x16(openpbr_lut_data[(index) >> 1])[(index)&1])
#elif defined(OPENPBR_LANGUAGE_TARGET_CPP)
#include <glm/gtc/packing.hpp>
namespace openpbr {
// Set by the application before any prepare/eval: the halves, one per entry.
inline const std::uint16_t* openpbr_lut_data_half = nullptr;
}  // namespace openpbr
#define OPENPBR_LUT_FETCH(index) glm::unpackHalf1x16(::openpbr::openpbr_lut_data_half[index])
#else
#error "OPENPBR_LUT_16BIT is not available for this language"
#endif
#elif defined(OPENPBR_LUT_MODE_BUFFER)
#if defined(OPENPBR_LANGUAGE_TARGET_SLANG)
// The explicit register keeps Slang's HLSL output in step with the Vulkan binding
// (HLSL front ends then map t<N> to binding N).
[[vk::binding(OPENPBR_LUT_BINDING, 0)]] StructuredBuffer<float> openpbr_lut_data
    : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_BINDING));
#elif defined(OPENPBR_LANGUAGE_TARGET_HLSL)
StructuredBuffer<float> openpbr_lut_data
    : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_BINDING), OPENPBR_CONCATENATE(space, OPENPBR_HLSL_REGISTER_SPACE));
#elif defined(OPENPBR_LANGUAGE_TARGET_GLSL)
layout(std430, set = 0, binding = OPENPBR_LUT_BINDING) readonly buffer OpenPBR_LutBuffer { float openpbr_lut_data[]; };
#elif defined(OPENPBR_LANGUAGE_TARGET_CPP)
namespace openpbr {
// Set by the application before any prepare/eval, e.g. to the contents of openpbr_lut.bin.
inline const float* openpbr_lut_data = nullptr;
}  // namespace openpbr
#else
#error "OPENPBR_LUT_MODE_BUFFER is not available for this language; use OPENPBR_LUT_MODE_ARRAY"
#endif
#define OPENPBR_LUT_FETCH(index) openpbr_lut_data[index]
#elif !defined(OPENPBR_LUT_FETCH) && !OPENPBR_USE_TEXTURE_LUTS
#error "OPENPBR_LUT_MODE_TEXTURE needs OPENPBR_LUT_FETCH(index) defined before including openpbr_lut.h"
#endif

// Hardware-filtered 2D table, e.g. -DOPENPBR_LUT_FILTERED_2D=1 (Slang on Vulkan; default 0):
// table 0 (E_ggx, read by every microfacet lobe's compensation) as an N x N single-channel
// float texture at OPENPBR_LUT_TEXTURE_BINDING (default 6) of set 0, a combined image sampler
// with bilinear filtering and clamp-to-edge addressing (host/gpu/vulkan_runner.h image bindings);
// the other tables stay where the storage mode puts them. Texel i holds node i, so node
// coordinate f in [0, N - 1] lies at texture coordinate (f + 0.5) / N, where bilinear
// filtering blends nodes floor(f) and floor(f) + 1 by fract(f): openpbr_lut_2d's arithmetic in
// the texture unit, with the blend weight rounded to the sampler's sub-texel precision
// (Vulkan's subTexelPrecisionBits, 8 on lavapipe). The accuracy study measures what that costs.
#ifndef OPENPBR_LUT_FILTERED_2D
#define OPENPBR_LUT_FILTERED_2D 0
#endif
#ifndef OPENPBR_LUT_TEXTURE_BINDING
#define OPENPBR_LUT_TEXTURE_BINDING 6
#endif
#if OPENPBR_LUT_FILTERED_2D
#if defined(OPENPBR_LANGUAGE_TARGET_SLANG)
[[vk::binding(OPENPBR_LUT_TEXTURE_BINDING, 0)]] Sampler2D<float> openpbr_lut_texture_2d;
#define OPENPBR_LUT_SAMPLE_2D(fx, fy)   \
    openpbr_lut_texture_2d.SampleLevel( \
        float2(((fx) + 0.5f) / float(OPENPBR_LUT_2D_SIZE), ((fy) + 0.5f) / float(OPENPBR_LUT_2D_SIZE)), 0.0f)
#else
#error "OPENPBR_LUT_FILTERED_2D is available for Slang (Vulkan) only"
#endif
#endif

OPENPBR_NAMESPACE_BEGIN

// Critical cosine of the interface of relative IOR eta, mu_c = sqrt(1 - min(eta, 1/eta)^2),
// written as |eta - 1| (eta + 1) / max(eta, 1)^2 so that it keeps its precision near eta = 1,
// where |eta - 1| is floored at OPENPBR_LUT_UNIT_ETA_STEP (the eta = 1 nodes' distance).
OPENPBR_FUNC float openpbr_lut_critical_cosine(float eta)
{
    const float distance = max(abs(eta - 1.0f), OPENPBR_LUT_UNIT_ETA_STEP);
    const float larger = max(eta, 1.0f);
    return sqrt(min(distance * (eta + 1.0f) / (larger * larger), 1.0f));
}
OPENPBR_FUNC float openpbr_lut_asinh(float x) { return log(x + sqrt(x * x + 1.0f)); }
// Width w of the albedos' step at the critical cosine, in sqrt(mu), scaled by K (see u_mu at
// the top of this file): K a eta / (2 sqrt(mu_c)) below eta = 1 with a = max(alpha, 1e-4) /
// max(1 - alpha, 1e-3), 0 (no step: the plain axis) at and above it. a is alpha for smooth
// lobes; 1 / (1 - alpha) returns the roughest lobes to the plain axis (w -> 1000 times the
// half), whose albedos change on the scale of mu itself: with a = alpha, glass of relative IOR
// 0.5 and roughness 1 gained 0.8 % at cos 0.5 (1.0079 +- 0.0007, against 1.004 on the plain
// axis).
OPENPBR_FUNC float openpbr_lut_step_width(float alpha, float eta, float critical_cosine)
{
    const float scale = max(alpha, OPENPBR_LUT_STEP_MIN_ALPHA) / max(1.0f - alpha, 1e-3f);
    return eta < 1.0f ? OPENPBR_LUT_STEP_WIDTH_SCALE * scale * eta / (2.0f * sqrt(critical_cosine)) : 0.0f;
}
// Position in [0, 1] along one half of the view axis of the point at fraction `distance` of
// the half from the critical cosine, for a step of width `scale` (as a fraction of the half)
// and the linear weight `slope`: (asinh(d / k) + L d) / (asinh(1 / k) + L), 0 at d = 0 and 1
// at d = 1.
OPENPBR_FUNC float openpbr_lut_step_warp(float distance, float scale, float slope)
{
    return (openpbr_lut_asinh(distance / scale) + slope * distance) / (openpbr_lut_asinh(1.0f / scale) + slope);
}
// The 3D tables' view axis u_mu in [0, 1]: sqrt(mu) with the critical cosine at 1/2, warped
// towards it by a step of width step_width (openpbr_lut_step_width; 0: not warped) (see the top
// of this file). mu_c <= sqrt(8/9) on [1/3, 3], so 1 - sqrt(mu_c) >= 0.029.
// The plain axis (no warp), also the form at and above eta = 1.
OPENPBR_FUNC float openpbr_lut_plain_view_coordinate(float mu, float critical_cosine, float split)
{
    const float m = sqrt(clamp(mu, 0.0f, 1.0f));
    const float c = sqrt(critical_cosine);
    return m < c ? split * m / c : split + (1.0f - split) * (m - c) / (1.0f - c);
}
OPENPBR_FUNC float openpbr_lut_view_coordinate(float mu, float critical_cosine, float step_width)
{
    if (step_width <= 0.0f)
    {
        return openpbr_lut_plain_view_coordinate(mu, critical_cosine, 0.5f);
    }
    const float m = sqrt(clamp(mu, 0.0f, 1.0f));
    const float c = sqrt(critical_cosine);
    return m < c ? 0.5f - 0.5f * openpbr_lut_step_warp((c - m) / c, step_width / c, OPENPBR_LUT_STEP_LINEAR_WEIGHT_BELOW)
                 : 0.5f + 0.5f * openpbr_lut_step_warp(min((m - c) / (1.0f - c), 1.0f), step_width / (1.0f - c),
                                                       OPENPBR_LUT_STEP_LINEAR_WEIGHT_ABOVE);
}
// The view coordinates (x) of mu and (y) of the generator's floor OPENPBR_LUT_MIN_VIEW_COSINE
// for GGX alpha and relative IOR eta. A branch, not a select: the warp's two logarithms and the
// step's width are computed only below eta = 1, and the plain axis is its own small (inlined)
// function, so look-ups at or above eta = 1 cost what they did before the warp (callgrind, per
// prepare of the default material: +69 instructions with the width computed unconditionally,
// +48 with the plain axis as a branch of the warped one, which the compiler stopped inlining).
OPENPBR_FUNC vec2 openpbr_lut_view_coordinates(float mu, float alpha, float eta, float critical_cosine)
{
    if (eta < 1.0f)
    {
        const float step_width = openpbr_lut_step_width(alpha, eta, critical_cosine);
        return vec2(openpbr_lut_view_coordinate(mu, critical_cosine, step_width),
                    openpbr_lut_view_coordinate(OPENPBR_LUT_MIN_VIEW_COSINE, critical_cosine, step_width));
    }
    return vec2(
        openpbr_lut_plain_view_coordinate(mu, critical_cosine, OPENPBR_LUT_VIEW_SPLIT_ABOVE),
        openpbr_lut_plain_view_coordinate(OPENPBR_LUT_MIN_VIEW_COSINE, critical_cosine, OPENPBR_LUT_VIEW_SPLIT_ABOVE));
}
// Node coordinate along eta of the 3D tables, in [0, OPENPBR_LUT_3D_ETA_SIZE - 1]: [0, H - 1]
// for eta < 1 (node H - 1 the limit eta -> 1 from below), [H, 2 H - 1] for eta >= 1 (node H the
// limit from above), H = OPENPBR_LUT_3D_ETA_SIZE / 2.
OPENPBR_FUNC float openpbr_lut_eta_node(float eta)
{
    const float y = (eta - 1.0f) / (eta + 1.0f);
    // At the range ends (eta = 3 and 1/3) s meets its cap: the derivative there is the one from
    // inside the range (min's at a tie would be half of it).
    const float s = openpbr_min_first_at_tie(sqrt(2.0f * abs(y)), 1.0f);
    const float knee = OPENPBR_LUT_ETA_KNEE;
    // (not "linear": an HLSL keyword)
    const float slope = OPENPBR_LUT_ETA_LINEAR_WEIGHT;
    const float first = openpbr_lut_asinh(1.0f) + slope * knee;
    const float w = clamp(
        (openpbr_lut_asinh(s / knee) + slope * s - first) / (openpbr_lut_asinh(1.0f / knee) + slope - first), 0.0f, 1.0f);
    const int half_size = OPENPBR_LUT_3D_ETA_SIZE / 2;
    const float span = float(half_size - 1);
    return eta < 1.0f ? (1.0f - w) * span : float(half_size) + w * span;
}
OPENPBR_FUNC float openpbr_lut_roughness_coordinate(float alpha) { return clamp(sqrt(alpha), 0.0f, 1.0f); }
OPENPBR_FUNC float openpbr_lut_mu_coordinate(float mu) { return sqrt(clamp(mu, 0.0f, 1.0f)); }
OPENPBR_FUNC float openpbr_lut_anisotropy_coordinate(float anisotropy)
{
    return 1.0f - sqrt(1.0f - clamp(anisotropy, 0.0f, 1.0f));
}

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
// The floors of mu and alpha are the generator's (host/tables/lut_generator.cpp).
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
#if OPENPBR_LUT_FILTERED_2D
    // Table 0 is the only 2D table, so the offset is implied by the texture.
    OPENPBR_UNUSED(offset);
    return OPENPBR_LUT_SAMPLE_2D(fx, fy);
#elif OPENPBR_USE_TEXTURE_LUTS
    // The GGX albedo is the only 2D table of this file (the fuzz lobe reads its own).
    OPENPBR_UNUSED(offset);
    return OPENPBR_SAMPLE_2D_TEXTURE(OPENPBR_LUT_TEXTURE_GGX_ALBEDO,
                                     (vec2(fx, fy) + vec2(0.5f)) / float(OPENPBR_LUT_2D_SIZE));
#else
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
#endif
}

// Bilinear look-up in the eta slice z of a 3D table: index = offset + (z * N + r_index) * N +
// mu_index.
#if OPENPBR_USE_TEXTURE_LUTS
// Texture id of a 3D table from its offset in the flat layout (constants: folded).
OPENPBR_FUNC int openpbr_lut_texture_id_3d(int offset)
{
    return offset == OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET
               ? OPENPBR_LUT_TEXTURE_DIELECTRIC_REFLECTION
               : (offset == OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET ? OPENPBR_LUT_TEXTURE_DIELECTRIC_TRANSMISSION
                                                                       : OPENPBR_LUT_TEXTURE_DIELECTRIC_INTERFACE);
}

// The filtered value of 3D table `offset` at node coordinates (fx, fy, fz).
OPENPBR_FUNC float openpbr_lut_texture_3d(int offset, float fx, float fy, float fz)
{
    const vec3 uvw = (vec3(fx, fy, fz) + vec3(0.5f)) /
                     vec3(float(OPENPBR_LUT_3D_SIZE), float(OPENPBR_LUT_3D_SIZE), float(OPENPBR_LUT_3D_ETA_SIZE));
    const int lut_id = openpbr_lut_texture_id_3d(offset);
    if (lut_id == OPENPBR_LUT_TEXTURE_DIELECTRIC_REFLECTION)
    {
        return OPENPBR_SAMPLE_3D_TEXTURE(OPENPBR_LUT_TEXTURE_DIELECTRIC_REFLECTION, uvw);
    }
    if (lut_id == OPENPBR_LUT_TEXTURE_DIELECTRIC_TRANSMISSION)
    {
        return OPENPBR_SAMPLE_3D_TEXTURE(OPENPBR_LUT_TEXTURE_DIELECTRIC_TRANSMISSION, uvw);
    }
    return OPENPBR_SAMPLE_3D_TEXTURE(OPENPBR_LUT_TEXTURE_DIELECTRIC_INTERFACE, uvw);
}

// A fetch at the centre of eta slice z: the filter interpolates within the slice only.
OPENPBR_FUNC float openpbr_lut_3d_slice(int offset, int x0, int y0, int z, float tx, float ty)
{
    return openpbr_lut_texture_3d(offset, float(x0) + tx, float(y0) + ty, float(z));
}
#else
OPENPBR_FUNC float openpbr_lut_3d_slice(int offset, int x0, int y0, int z, float tx, float ty)
{
    const int n = OPENPBR_LUT_3D_SIZE;
    const int base = offset + (z * n + y0) * n + x0;
    return mix(mix(OPENPBR_LUT_FETCH(base), OPENPBR_LUT_FETCH(base + 1), tx),
               mix(OPENPBR_LUT_FETCH(base + n), OPENPBR_LUT_FETCH(base + n + 1), tx), ty);
}
#endif

// Along eta in the 3D table at mu weight tx and roughness weight ty of the cell (x0, y0):
// quadratic through a 3-node Lagrange stencil around the nearest node, kept within the half of
// the eta axis that fz lies in (eta < 1 or eta >= 1, see openpbr_lut_eta_node). Why quadratic:
// the albedos bend strongly along eta for rough interfaces seen from inside; linear
// interpolation left 1 % errors in E_RT (white furnace of rough glass from inside 0.990 at
// normal incidence), the quadratic stencil cut the largest E_RT error at view cos >= 0.1 from
// 0.0145 to 0.0039 (1500 random points against Monte Carlo).
OPENPBR_FUNC float openpbr_lut_3d_along_eta(int offset, int x0, int y0, float tx, float ty, float fz)
{
    const int half_size = OPENPBR_LUT_3D_ETA_SIZE / 2;
    const int low = fz < float(half_size) ? 0 : half_size;
    const int centre = clamp(int(fz + 0.5f), low + 1, low + half_size - 2);
    const float t = fz - float(centre);
    const float v_minus = openpbr_lut_3d_slice(offset, x0, y0, centre - 1, tx, ty);
    const float v_zero = openpbr_lut_3d_slice(offset, x0, y0, centre, tx, ty);
    const float v_plus = openpbr_lut_3d_slice(offset, x0, y0, centre + 1, tx, ty);
    return v_zero + 0.5f * t * (v_plus - v_minus) + 0.5f * t * t * (v_plus - 2.0f * v_zero + v_minus);
}

// 3D look-up of table `offset` at view cosine mu, GGX alpha and relative IOR eta: bilinear in
// (u_mu, r), quadratic along eta (openpbr_lut_3d_along_eta, 12 fetches). In the first mu cell
// (between the generator's floor mu = 1e-4 and the first node), where E_R of smooth lobes is
// concave in the view axis (coat of roughness 0.1 and IOR 1.6 at cos 1e-3: true 0.820,
// interpolated 0.814), it returns the larger of the two mu nodes' values (24 fetches): every
// caller reads these albedos as a divisor of a compensation (E_T0, E_RT) or as the part of the
// light a layer takes before the layers below (E_R), so an albedo read too high can only lose
// energy, and one read too low gains it.
OPENPBR_FUNC float openpbr_lut_3d(int offset, float mu, float alpha, float eta)
{
    const float scale = float(OPENPBR_LUT_3D_SIZE - 1);
    const float critical_cosine = openpbr_lut_critical_cosine(eta);
    const vec2 views = openpbr_lut_view_coordinates(mu, alpha, eta, critical_cosine);
    const float view = views.x;
    // NaN-safe clamps: a NaN coordinate (e.g. from a NaN wavelength) would make int() undefined.
    const float fx = openpbr_clamp_finite(view, 0.0f, 1.0f) * scale;
    const float fy = openpbr_clamp_finite(openpbr_lut_roughness_coordinate(alpha), 0.0f, 1.0f) * scale;
    const float fz = openpbr_clamp_finite(openpbr_lut_eta_node(eta), 0.0f, float(OPENPBR_LUT_3D_ETA_SIZE - 1));
#if OPENPBR_USE_TEXTURE_LUTS && OPENPBR_LUT_TEXTURE_TRILINEAR_ETA
    // One trilinear fetch: linear along eta (slang/openpbr_lut_textures.h). fz never lies
    // between the two eta = 1 nodes, so the filter never mixes the halves.
    return openpbr_lut_texture_3d(offset, fx, fy, fz);
#endif
    const int x0 = min(int(fx), OPENPBR_LUT_3D_SIZE - 2);
    const int y0 = min(int(fy), OPENPBR_LUT_3D_SIZE - 2);
    const float tx = fx - float(x0);
    const float ty = fy - float(y0);
    // Nodes below the view coordinate of the generator's floor mu = 1e-4 hold the floor's values
    // (near eta = 1 the warped axis puts the first nodes there), so a cell starting at one is a
    // first cell too (IOR 1.0001, roughness 0.3, cos 1e-4: E_T0 interpolated 0.825, true 0.850).
    const bool first_cell = float(x0) < scale * views.y;
    if (!first_cell || tx == 0.0f)
    {
        return openpbr_lut_3d_along_eta(offset, x0, y0, tx, ty, fz);
    }
    return max(openpbr_lut_3d_along_eta(offset, x0, y0, 0.0f, ty, fz),
               openpbr_lut_3d_along_eta(offset, x0, y0, 1.0f, ty, fz));
}

#if !OPENPBR_USE_TEXTURE_LUTS
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
#endif

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
#if OPENPBR_USE_TEXTURE_LUTS
    // The azimuth slabs are stacked along z (slang/openpbr_lut_textures.h): one trilinear fetch
    // per slab, within it, and the blend of the two slabs here.
    OPENPBR_UNUSED(offset);
    OPENPBR_UNUSED(x0);
    OPENPBR_UNUSED(y0);
    OPENPBR_UNUSED(z0);
    const vec2 uv = (vec2(fx, fy) + vec2(0.5f)) / float(n);
    const float depth = float(m * m);
    const float near_phi =
        OPENPBR_SAMPLE_3D_TEXTURE(OPENPBR_LUT_TEXTURE_GGX_ANISOTROPY_RATIO, vec3(uv, (float(w0 * m) + fz + 0.5f) / depth));
    const float far_phi = OPENPBR_SAMPLE_3D_TEXTURE(OPENPBR_LUT_TEXTURE_GGX_ANISOTROPY_RATIO,
                                                    vec3(uv, (float((w0 + 1) * m) + fz + 0.5f) / depth));
#else
    const int stride_a = n * n;
    const int stride_phi = n * n * m;
    const int base = offset + w0 * stride_phi + z0 * stride_a + y0 * n + x0;
    const float near_phi = openpbr_lut_trilinear(base, n, stride_a, fx - float(x0), fy - float(y0), fz - float(z0));
    const float far_phi =
        openpbr_lut_trilinear(base + stride_phi, n, stride_a, fx - float(x0), fy - float(y0), fz - float(z0));
#endif
    return mix(near_phi, far_phi, fw - float(w0));
}

// OPENPBR_COMPENSATION_ANALYTIC: least-squares fit of table 0 by a polynomial of total degree
// 4 in (m, r) = (sqrt(mu), sqrt(alpha)), the table's own axes, sum of c_ij m^i r^j. Fitted to
// the 32 x 32 table shipped until 2026-11-25 (max error 0.094, mean 0.012 over its nodes; the largest errors at
// grazing views, mu < 0.01).
OPENPBR_FUNC float openpbr_ggx_albedo_fit(float mu, float alpha)
{
    const float m = openpbr_lut_mu_coordinate(mu);
    const float r = openpbr_lut_roughness_coordinate(alpha);
    const float m0 =
        9.8593036e-01f + r * (-3.2435618e-01f + r * (1.4709299e+00f + r * (-1.7097017e+00f + r * 5.6800775e-01f)));
    const float m1 = -3.2264028e-02f + r * (-5.9167797e-01f + r * (-9.1125256e-01f + r * 1.1548465e+00f));
    const float m2 = 1.7432353e-01f + r * (3.4434184e-01f + r * -1.9105729e+00f);
    const float m3 = 2.3961913e-01f + r * 1.2671594e+00f;
    const float m4 = -4.3714556e-01f;
    return clamp(m0 + m * (m1 + m * (m2 + m * (m3 + m * m4))), 0.0f, 1.0f);
}

// Table 0 itself, E_ggx(mu, alpha), whatever the compensation mode: the factor of E_R and E_RT
// (openpbr_dielectric_reflection_albedo) as well as the table mode's openpbr_ggx_albedo.
OPENPBR_FUNC float openpbr_tabulated_ggx_albedo(float mu, float alpha)
{
    return openpbr_lut_2d(OPENPBR_LUT_GGX_ALBEDO_OFFSET, openpbr_lut_mu_coordinate(mu),
                          openpbr_lut_roughness_coordinate(alpha));
}

// Directional albedo of GGX reflection with F = 1 (single scattering); 1 under
// OPENPBR_COMPENSATION_NONE, the fit under OPENPBR_COMPENSATION_ANALYTIC.
OPENPBR_FUNC float openpbr_ggx_albedo(float mu, float alpha)
{
#if OPENPBR_COMPENSATION_MODE == OPENPBR_COMPENSATION_NONE
    OPENPBR_UNUSED(mu);
    OPENPBR_UNUSED(alpha);
    return 1.0f;
#elif OPENPBR_COMPENSATION_MODE == OPENPBR_COMPENSATION_ANALYTIC
    return openpbr_ggx_albedo_fit(mu, alpha);
#else
    return openpbr_tabulated_ggx_albedo(mu, alpha);
#endif
}

// Directional albedo of GGX reflection off a dielectric of relative IOR eta (single scattering):
// E_R = F_avg E_ggx, table 1's Fresnel factor averaged over the reflected light times table 0's
// F = 1 albedo (in every compensation mode: E_R is the layering weight 1 - E_R of the spec's
// albedo scaling, not a compensation). Why a product: at grazing views a near-mirror lobe's
// shadowing changes on the scale mu ~ alpha, which a 33 x 33 (view, roughness) grid does not
// resolve (E_R of eta 1.5, roughness 0.05 at view cos 0.02 interpolated 0.8632 against 0.8772;
// now 0.8713); the shadowing largely cancels in F_avg, and table 0's finer grid carries it.
// F_avg = E_R / E_ggx alone: callers that hold E_ggx already (openpbr_ggx_lobe_albedo) multiply.
OPENPBR_FUNC float openpbr_dielectric_fresnel_average(float mu, float alpha, float eta)
{
    return openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET, mu, alpha, eta);
}
OPENPBR_FUNC float openpbr_dielectric_reflection_albedo(float mu, float alpha, float eta)
{
    return openpbr_dielectric_fresnel_average(mu, alpha, eta) * openpbr_tabulated_ggx_albedo(mu, alpha);
}

// Smallest E_T0 the transmission compensation 1 / E_T0 divides by, e.g. 1e-3. Below eta = 1
// seen from outside (a bubble) E_T0 is small where most microfacets reflect totally (0.012 at
// eta 0.5, roughness 0.5, view cos 0.1), and the compensation hands the transmitted lobe all of
// 1 - E_R (0.15 there): a floor of 0.05 lost 0.11 of the white furnace there. The weight of a
// transmitted sample stays below (1 - E_R) / OPENPBR_MIN_TRANSMISSION_ALBEDO.
#ifndef OPENPBR_MIN_TRANSMISSION_ALBEDO
#define OPENPBR_MIN_TRANSMISSION_ALBEDO 1e-3f
#endif

// Directional albedo of the GGX BTDF without its Fresnel factor (single scattering).
OPENPBR_FUNC float openpbr_dielectric_transmission_albedo(float mu, float alpha, float eta)
{
#if OPENPBR_COMPENSATION_MODE == OPENPBR_COMPENSATION_NONE
    OPENPBR_UNUSED(mu);
    OPENPBR_UNUSED(alpha);
    OPENPBR_UNUSED(eta);
    return 1.0f;
#else
    return openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET, mu, alpha, eta);
#endif
}

// Directional albedo of reflection plus transmission of a rough dielectric interface.
OPENPBR_FUNC float openpbr_dielectric_interface_albedo(float mu, float alpha, float eta)
{
#if OPENPBR_COMPENSATION_MODE == OPENPBR_COMPENSATION_NONE
    OPENPBR_UNUSED(mu);
    OPENPBR_UNUSED(alpha);
    OPENPBR_UNUSED(eta);
    return 1.0f;
#else
    // E_RT = (E_RT / E_ggx) E_ggx, like E_R (openpbr_dielectric_reflection_albedo).
    return openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET, mu, alpha, eta) * openpbr_tabulated_ggx_albedo(mu, alpha);
#endif
}

// E(mu, r, a, phi) / E(mu, r) of GGX reflection with F = 1 (single scattering): the anisotropic
// lobe of OpenPBR's roughness and anisotropy (openpbr_ggx_alpha) over the isotropic lobe of
// alpha = roughness^2, the view at cosine mu and at squared azimuth cosine cos_phi_squared from
// the tangent (openpbr_cos_azimuth_squared of the local view). 1 at anisotropy 0.
OPENPBR_FUNC float openpbr_ggx_anisotropy_ratio(float mu, float roughness, float anisotropy, float cos_phi_squared)
{
#if OPENPBR_COMPENSATION_MODE != OPENPBR_COMPENSATION_TABLE
    OPENPBR_UNUSED(mu);
    OPENPBR_UNUSED(roughness);
    OPENPBR_UNUSED(anisotropy);
    OPENPBR_UNUSED(cos_phi_squared);
    return 1.0f;
#else
    return openpbr_lut_4d(OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET, openpbr_lut_mu_coordinate(mu),
                          clamp(roughness, 0.0f, 1.0f), openpbr_lut_anisotropy_coordinate(anisotropy),
                          openpbr_lut_azimuth_coordinate(mu, roughness, anisotropy, cos_phi_squared));
#endif
}

// Directional albedo of anisotropic GGX reflection with F = 1 (single scattering), arguments as
// openpbr_ggx_anisotropy_ratio. Equals openpbr_ggx_albedo(mu, roughness^2) at anisotropy 0,
// where that alone is the cheaper look-up.
OPENPBR_FUNC float openpbr_ggx_albedo_anisotropic(float mu, float roughness, float anisotropy, float cos_phi_squared)
{
    const float r = clamp(roughness, 0.0f, 1.0f);
    return openpbr_ggx_albedo(mu, r * r) * openpbr_ggx_anisotropy_ratio(mu, r, anisotropy, cos_phi_squared);
}

// ---- Table 5: the microfacet cosines of a lobe's reflected light (thin film) ----------------

// How table 5 is read, e.g. 1 (the default): in loops kept rolled on GPUs and unrolled in C++
// (OPENPBR_ROLLED_ON_GPU), each one read site on the GPU: a node's four bilinear corners, a
// cell's four nodes, the lobe's quartiles and a node segment's quartiles and median. llvmpipe's
// build of the full conformance module then takes 16.7 G instructions instead of 19.1 G
// (callgrind, -13 %; the corners alone 2.15 G, docs/thin-film-estimate.md "Rolled film-table
// reads"), while GCC at -O2 unrolls them as it does at -O3 (kept rolled, the corner loop's
// selects cost 13 % of the estimate's instructions at -O2, docs/thin-film-estimate.md "Cost").
// Or 0: the loops left to each compiler, which unrolls them (the loads of a node in flight at
// once, a shorter prepare of filmed materials on GPUs whose table reads wait on memory; the
// longer build). Outputs are the same either way.
#ifndef OPENPBR_ROLLED_FILM_TABLE_READS
#define OPENPBR_ROLLED_FILM_TABLE_READS 1
#endif
#if OPENPBR_ROLLED_FILM_TABLE_READS
#define OPENPBR_FILM_TABLE_READ_LOOP OPENPBR_ROLLED_ON_GPU
#else
#define OPENPBR_FILM_TABLE_READ_LOOP
#endif

// The four (view, roughness) nodes around a lobe and their bilinear weights; mu the view cosine,
// alpha the lobe's (isotropic or root-mean-square) GGX alpha.
struct OpenPBR_FilmLobeTable OPENPBR_DIFFERENTIABLE
{
    int mu_index;
    int r_index;
    float mu_weight;  // of node mu_index + 1
    float r_weight;   // of node r_index + 1
};

OPENPBR_FUNC OpenPBR_FilmLobeTable openpbr_film_lobe_table(float mu, float alpha)
{
    const float scale = float(OPENPBR_LUT_FILM_SIZE - 1);
    const float fx = openpbr_lut_mu_coordinate(mu) * scale;
    const float fy = openpbr_lut_roughness_coordinate(alpha) * scale;
    OpenPBR_FilmLobeTable table;
    table.mu_index = min(int(fx), OPENPBR_LUT_FILM_SIZE - 2);
    table.r_index = min(int(fy), OPENPBR_LUT_FILM_SIZE - 2);
    table.mu_weight = fx - float(table.mu_index);
    table.r_weight = fy - float(table.r_index);
    return table;
}

// One node of table 5: channel 0 the quantile Q, 1 the partial first moment M1
// (host/tables/film_table_generator.h), at probability node p, view node m, roughness node r.
// Texture mode: texel (p, m, channel * N + r) of a 3D texture, read at its centre (no filtering
// between nodes; the library interpolates).
OPENPBR_FUNC float openpbr_film_table_node(int p, int m, int r, int channel)
{
#if OPENPBR_USE_TEXTURE_LUTS
    const vec3 uvw = vec3(
        (float(p) + 0.5f) / float(OPENPBR_LUT_FILM_QUANTILE_SIZE), (float(m) + 0.5f) / float(OPENPBR_LUT_FILM_SIZE),
        (float(channel * OPENPBR_LUT_FILM_SIZE + r) + 0.5f) / float(OPENPBR_LUT_FILM_CHANNEL_COUNT * OPENPBR_LUT_FILM_SIZE));
    return OPENPBR_SAMPLE_3D_TEXTURE(OPENPBR_LUT_TEXTURE_FILM_LOBE, uvw);
#else
    return OPENPBR_LUT_FETCH(
        OPENPBR_LUT_FILM_OFFSET +
        ((channel * OPENPBR_LUT_FILM_SIZE + r) * OPENPBR_LUT_FILM_SIZE + m) * OPENPBR_LUT_FILM_QUANTILE_SIZE + p);
#endif
}

// A channel at probability node p, interpolated bilinearly between the lobe's four nodes
// (quantiles of neighbouring lobes blend as the lobes' cosines shift: the quantile function of
// the blend of two distributions' displacement).
// The four corners are read in one loop, at one read site: the film estimate reads nodes at
// about twenty places, each inlined, and every table read site lengthens llvmpipe's build of
// the module (see OPENPBR_ROLLED_FILM_TABLE_READS).
OPENPBR_FUNC float openpbr_film_lobe_node(OPENPBR_IN(OpenPBR_FilmLobeTable) table, int p, int channel)
{
    // (m, r), (m + 1, r), (m, r + 1), (m + 1, r + 1) in x .. w.
    vec4 corners = vec4(0.0f);
    OPENPBR_FILM_TABLE_READ_LOOP
    for (int corner = 0; corner < 4; ++corner)
    {
        const float value =
            openpbr_film_table_node(p, table.mu_index + (corner & 1), table.r_index + (corner >> 1), channel);
        corners = openpbr_with_channel(corners, corner, value);
    }
    return mix(mix(corners.x, corners.y, table.mu_weight), mix(corners.z, corners.w, table.mu_weight), table.r_weight);
}

// The probability p of table 5's node (OPENPBR_LUT_FILM_QUANTILE_SIZE nodes, see the sizes
// above): the even nodes j / (OPENPBR_LUT_FILM_CORE_SIZE - 1) between the tails, and in each
// tail OPENPBR_LUT_FILM_TAIL_NODES nodes halving towards its end (1/64 down to 1/512 from each
// end with 33 even nodes and 4 tail nodes). Exact in float (powers of two).
OPENPBR_FUNC float openpbr_film_lobe_probability(int node)
{
    const int last = OPENPBR_LUT_FILM_QUANTILE_SIZE - 1;
    const int from_end = min(max(min(node, last - node), 0), last / 2);
    const float step = 1.0f / float(OPENPBR_LUT_FILM_CORE_SIZE - 1);
    const float from_end_probability =
        from_end > OPENPBR_LUT_FILM_TAIL_NODES
            ? float(from_end - OPENPBR_LUT_FILM_TAIL_NODES) * step
            : (from_end > 0 ? step / float(1 << (OPENPBR_LUT_FILM_TAIL_NODES + 1 - from_end)) : 0.0f);
    return node <= last - node ? from_end_probability : 1.0f - from_end_probability;
}

// Table 5's node at the even probability j / (OPENPBR_LUT_FILM_CORE_SIZE - 1), 0 < j <
// OPENPBR_LUT_FILM_CORE_SIZE - 1 (e.g. the quartiles: j = 8, 16, 24 of 32).
OPENPBR_FUNC int openpbr_film_lobe_even_node(int j) { return j + OPENPBR_LUT_FILM_TAIL_NODES; }

// The lobe's quantile at the even probability j / (OPENPBR_LUT_FILM_CORE_SIZE - 1), a node read
// (e.g. its quartiles, j = 8, 16, 24 of 32).
OPENPBR_FUNC float openpbr_film_lobe_even_quantile(OPENPBR_IN(OpenPBR_FilmLobeTable) table, int j)
{
    return openpbr_film_lobe_node(table, openpbr_film_lobe_even_node(j), 0);
}

// (P, M1) at the even probability j / (OPENPBR_LUT_FILM_CORE_SIZE - 1), 0 <= j <=
// OPENPBR_LUT_FILM_CORE_SIZE - 1: the light of the lobe below its quantile there, a node read
// (e.g. j = 16: (1/2, E[c; c <= Q(1/2)]); j = 32: the whole lobe, (1, E[c])).
OPENPBR_FUNC vec2 openpbr_film_lobe_even_moment(OPENPBR_IN(OpenPBR_FilmLobeTable) table, int j)
{
    const int last = OPENPBR_LUT_FILM_CORE_SIZE - 1;
    const int node = j <= 0 ? 0 : (j >= last ? OPENPBR_LUT_FILM_QUANTILE_SIZE - 1 : openpbr_film_lobe_even_node(j));
    return vec2(float(j) / float(last), openpbr_film_lobe_node(table, node, 1));
}

// Inside a probability cell [p_i, p_i+1] of table 5, c is modelled as a power of the cell's
// fractional probability t, skewed towards the end the cell's mean lies nearer to:
//   c(t) = q0 + (q1 - q0) t^k            where the mean is in the cell's lower half,
//   c(t) = q1 - (q1 - q0) (1 - t)^k      where it is in the upper half,
// with k = 1 / g - 1, g the mean's distance (as a fraction of q1 - q0) from the near end, so the
// model's mean is the tabulated one ((M1_i+1 - M1_i) / (p_i+1 - p_i)) and its integral ends at
// the tabulated M1 (linear at g = 0.5). GGX lobes have long tails: the first and last cells of a
// narrow lobe span cosines far from most of their light (alpha 0.01 at view cosine 0.5: the last
// cell spans 0.52-0.72 with its mean at 0.53), and a linear model put 2.4 % of the light above
// 0.566 where the lobe has 0.4 % (an error of 0.024 in the filmed estimate of a film just past its
// critical cosine); the power model puts the cell's light where its mean says. g is kept in
// [1/64, 1/2] (k at most 63).
struct OpenPBR_FilmLobeCell OPENPBR_DIFFERENTIABLE
{
    float low;           // q0, the cosine at the cell's start
    float width;         // q1 - q0
    float exponent;      // k
    float mean;          // the model's mean cosine in the cell (the tabulated one, within the clamp of g)
    bool upper;          // skewed towards q1 (the mirrored form)
    float moment;        // M1 at the cell's start
    float moment_width;  // M1 at its end minus M1 at its start (the cell's light times its mean)
};

// The cell between nodes index and index + 1, cell_probability = p_index+1 - p_index.
OPENPBR_FUNC OpenPBR_FilmLobeCell openpbr_film_lobe_cell(OPENPBR_IN(OpenPBR_FilmLobeTable) table, int index,
                                                         float cell_probability)
{
    // Q and M1 at the cell's two nodes, read at one site (OPENPBR_ROLLED_FILM_TABLE_READS).
    vec4 nodes = vec4(0.0f);
    OPENPBR_FILM_TABLE_READ_LOOP
    for (int read = 0; read < 4; ++read)
    {
        nodes = openpbr_with_channel(nodes, read, openpbr_film_lobe_node(table, index + (read & 1), read >> 1));
    }
    OpenPBR_FilmLobeCell cell;
    cell.low = nodes.x;
    cell.width = max(nodes.y - cell.low, 0.0f);
    cell.moment = nodes.z;
    cell.moment_width = nodes.w - cell.moment;
    const float mean = cell.moment_width / cell_probability;
    const float position = cell.width > 1e-7f ? clamp((mean - cell.low) / cell.width, 0.0f, 1.0f) : 0.5f;
    cell.upper = position > 0.5f;
    const float near = clamp(cell.upper ? 1.0f - position : position, 1.0f / 64.0f, 0.5f);
    cell.exponent = 1.0f / near - 1.0f;
    cell.mean = cell.low + cell.width * (cell.upper ? 1.0f - near : near);
    return cell;
}

// (t, the cell's part of c's integral over [0, t] as a fraction of its whole) for the cosine x
// in the cell.
OPENPBR_FUNC vec2 openpbr_film_lobe_cell_below(OPENPBR_IN(OpenPBR_FilmLobeCell) cell, float x)
{
    const float s = cell.width > 0.0f ? clamp((x - cell.low) / cell.width, 0.0f, 1.0f) : 1.0f;
    const float k = cell.exponent;
    // Lower form: c = q0 + w t^k, so t = s^(1/k). Upper form: c = q1 - w (1 - t)^k, so
    // t = 1 - (1 - s)^(1/k), and (1 - t)^(k + 1) = (1 - t)(1 - s). One pow for both forms
    // (each pow site is a polynomial in llvmpipe's build of the module).
    const float root = pow(cell.upper ? 1.0f - s : s, 1.0f / k);
    const float t = cell.upper ? 1.0f - root : root;
    const float integral = cell.upper ? (cell.low + cell.width) * t - cell.width * (1.0f - root * (1.0f - s)) / (k + 1.0f)
                                      : cell.low * t + cell.width * t * s / (k + 1.0f);
    return vec2(t, cell.mean > 0.0f ? clamp(integral / cell.mean, 0.0f, 1.0f) : t);
}

// The cosine at fraction t of the cell's light.
OPENPBR_FUNC float openpbr_film_lobe_cell_cosine(OPENPBR_IN(OpenPBR_FilmLobeCell) cell, float t)
{
    const float power = pow(max(cell.upper ? 1.0f - t : t, 0.0f), cell.exponent);
    return cell.low + cell.width * (cell.upper ? 1.0f - power : power);
}

// The light of the lobe whose microfacet cosine is at most x: (P, M1) = (its fraction,
// E[c; c <= x]). Q is inverted by bisection over the probability nodes; inside a cell, the power
// model above (exact at the nodes, never decreasing in x).
OPENPBR_FUNC vec2 openpbr_film_lobe_cumulative(OPENPBR_IN(OpenPBR_FilmLobeTable) table, float x)
{
    const int last = OPENPBR_LUT_FILM_QUANTILE_SIZE - 1;
    if (x <= openpbr_film_lobe_node(table, 0, 0))
    {
        return vec2(0.0f);
    }
    if (x >= openpbr_film_lobe_node(table, last, 0))
    {
        return vec2(1.0f, openpbr_film_lobe_node(table, last, 1));
    }
    // Bisection over all the nodes, Q(p_low) <= x < Q(p_high): the last node at or below x, the
    // same cell as any search finds, since Q never decreases. The loop ends on the data, not on
    // a count: a counted loop is unrolled by drivers into one table read per step (llvmpipe's
    // build of the module: the bisection over the even nodes with the tails tested first took
    // 0.48 G more instructions to compile, docs/thin-film-estimate.md).
    // Each step halves high - low (rounding up): ceil(log2(last)) steps, 6 for the 41 nodes.
    int low = 0;
    int high = last;
    OPENPBR_MAX_ITERS(OPENPBR_LUT_FILM_BISECTION_STEPS)
    while (high - low > 1)
    {
        const int middle = (low + high) / 2;
        if (openpbr_film_lobe_node(table, middle, 0) <= x)
        {
            low = middle;
        }
        else
        {
            high = middle;
        }
    }
    const float p0 = openpbr_film_lobe_probability(low);
    const float cell_probability = openpbr_film_lobe_probability(low + 1) - p0;
    const OpenPBR_FilmLobeCell cell = openpbr_film_lobe_cell(table, low, cell_probability);
    const vec2 below = openpbr_film_lobe_cell_below(cell, x);
    return vec2(p0 + cell_probability * below.x, cell.moment + cell.moment_width * below.y);
}

// The cosine below which a fraction p of the lobe's light lies, Q(p), with the cell model above
// (the same model as openpbr_film_lobe_cumulative: a segment's quartiles read with a linear model
// inside a tail cell landed outside the segment and put an optical-path spread of 0.52 um on a
// segment whose own is about 0.1).
OPENPBR_FUNC float openpbr_film_lobe_quantile(OPENPBR_IN(OpenPBR_FilmLobeTable) table, float p)
{
    // The cell holding p: between the tails from the even nodes' step directly, in a tail its
    // nodes one by one (no table reads either way).
    const float target = clamp(p, 0.0f, 1.0f);
    const float step = 1.0f / float(OPENPBR_LUT_FILM_CORE_SIZE - 1);
    const float f = target * float(OPENPBR_LUT_FILM_CORE_SIZE - 1);
    const int even = min(int(f), OPENPBR_LUT_FILM_CORE_SIZE - 2);
    int low = even + OPENPBR_LUT_FILM_TAIL_NODES;
    float p0 = float(even) * step;
    float cell_probability = step;
    if (f < 1.0f || f >= float(OPENPBR_LUT_FILM_CORE_SIZE - 2))
    {
        const int first = f < 1.0f ? 0 : OPENPBR_LUT_FILM_QUANTILE_SIZE - 2 - OPENPBR_LUT_FILM_TAIL_NODES;
        low = first;
        for (int node = 1; node <= OPENPBR_LUT_FILM_TAIL_NODES; ++node)
        {
            low = openpbr_film_lobe_probability(first + node) <= target ? first + node : low;
        }
        p0 = openpbr_film_lobe_probability(low);
        cell_probability = openpbr_film_lobe_probability(low + 1) - p0;
    }
    const float t = clamp((target - p0) / cell_probability, 0.0f, 1.0f);
    return openpbr_film_lobe_cell_cosine(openpbr_film_lobe_cell(table, low, cell_probability), t);
}

OPENPBR_NAMESPACE_END

#endif
