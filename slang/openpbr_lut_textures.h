// Texture tables (OPENPBR_USE_TEXTURE_LUTS=1): every table read through the host's filtered
// texture fetches instead of a constant array or a storage buffer, e.g. for HLSL engines in
// which long constant arrays render black, or to use the texture units' filtering.
//
// The host defines, before including openpbr.h (or importing the Slang module):
//   OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv)   float: the filtered value of 2D table lut_id at uv
//   OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw)  float: the same for a 3D table
// with lut_id one of the ids below (a compile-time constant: an index into an array of
// textures, or a switch), e.g. in GLSL
//   layout(set = 0, binding = 6) uniform sampler2D openpbr_tables_2d[4];
//   layout(set = 0, binding = 7) uniform sampler3D openpbr_tables_3d[4];
//   #define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) textureLod(openpbr_tables_2d[OPENPBR_LUT_TEXTURE_SLOT(lut_id)], uv,
//   0.0f).x #define OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw) textureLod(openpbr_tables_3d[OPENPBR_LUT_TEXTURE_SLOT(lut_id)],
//   uvw, 0.0f).x
//
// How to fill each texture. All tables: one channel, 32-bit float (VK_FORMAT_R32_SFLOAT,
// DXGI_FORMAT_R32_FLOAT, MTLPixelFormatR32Float; 16-bit float works at the 16-bit buffer
// mode's accuracy), linear min/mag filtering, no mipmaps (level 0 only, sampled at LOD 0),
// clamp-to-edge addressing on every axis, normalized coordinates. Texel (x, y, z) holds the
// value at offset + (z * height + y) * width + x of the flat table (slang/generated/
// openpbr_lut.bin for ids 0-4, openpbr_fuzz_ltc.bin for ids 5-7): the textures are the flat
// array's tables with x running fastest, so each is one upload of a contiguous range.
// Sizes: OPENPBR_LUT_2D_SIZE, OPENPBR_LUT_3D_SIZE (x and y of the 3D tables),
// OPENPBR_LUT_3D_ETA_SIZE (their z), OPENPBR_LUT_4D_SIZE, OPENPBR_LUT_4D_ANISOTROPY_SIZE of
// slang/openpbr_lut.h (the shipped values in the table below).
// Coordinate mapping: the grids are node-centred (openpbr_lut.h), so node i of an axis with N
// nodes sits at texel centre (i + 0.5) / N; the library converts its node coordinate f in
// [0, N - 1] to (f + 0.5) / N itself. Hardware filtering between two nodes is then the
// linear interpolation of the array mode (to the filter's weight precision, 8 fractional bits
// on many GPUs; docs/accuracy-vs-time.md "Texture tables").
//
//   id                                         dim  size (x, y, z)    axes (x, y, z)            flat offset
//   OPENPBR_LUT_TEXTURE_GGX_ALBEDO          0   2D  128 x 128         c_mu, c_r OPENPBR_LUT_GGX_ALBEDO_OFFSET
//   OPENPBR_LUT_TEXTURE_DIELECTRIC_REFLECTION 1 3D  33 x 33 x 48      u_mu, c_r, c_eta
//   OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET OPENPBR_LUT_TEXTURE_DIELECTRIC_TRANSMISSION 2 3D 33 x 33 x 48     u_mu, c_r,
//   c_eta          OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET OPENPBR_LUT_TEXTURE_DIELECTRIC_INTERFACE 3  3D  33 x 33 x 48
//   u_mu, c_r, c_eta          OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET OPENPBR_LUT_TEXTURE_GGX_ANISOTROPY_RATIO 4  3D  16 x
//   16 x 100     c_mu, c_r, 10 c_phi + c_a OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET OPENPBR_LUT_TEXTURE_FUZZ_LTC_A          5
//   2D  32 x 32           mu, fuzz roughness        OPENPBR_FUZZ_LTC_A_OFFSET (fuzz table) OPENPBR_LUT_TEXTURE_FUZZ_LTC_B 6
//   2D  32 x 32           mu, fuzz roughness        OPENPBR_FUZZ_LTC_B_OFFSET (fuzz table) OPENPBR_LUT_TEXTURE_FUZZ_LTC_R 7
//   2D  32 x 32           mu, fuzz roughness        OPENPBR_FUZZ_LTC_R_OFFSET (fuzz table)
//   OPENPBR_LUT_TEXTURE_FILM_LOBE 8  3D  41 x 32 x 64  p, c_mu, channel x 32 + c_r  OPENPBR_LUT_FILM_OFFSET
// The film table's two channels (the quantile and the first partial moment) are stacked along
// z; it is read at texel centres only (the library interpolates its nodes itself), so its
// filtering mode does not matter.
// The anisotropy table is 4D (mu, r, a, phi): its 10 azimuth slabs of 16 x 16 x 10 are stacked
// along z (z = phi node x 10 + anisotropy node); the library filters within a slab (trilinear
// over mu, r, a) and blends the two azimuth slabs itself, so filtering never mixes slabs.
//
// Along eta the array mode interpolates quadratically through three nodes and never mixes the
// two sides of eta = 1 (openpbr_lut_3d_along_eta); a trilinear fetch would interpolate
// linearly. By default the library therefore samples each 3D table at exact eta-node centres
// (each fetch is a bilinear filter within one eta slice) and keeps its own interpolation along
// eta: 3 fetches per look-up, 6 where the view is in the first mu cell.
// OPENPBR_LUT_TEXTURE_TRILINEAR_ETA=1 uses one trilinear fetch instead: cheaper, at the accuracy cost measured in
// docs/accuracy-vs-time.md.
#ifndef OPENPBR_LUT_TEXTURES_H
#define OPENPBR_LUT_TEXTURES_H

// Texture tables on (1) or off (0, default: the array or buffer mode of openpbr_lut.h).
#ifndef OPENPBR_USE_TEXTURE_LUTS
#define OPENPBR_USE_TEXTURE_LUTS 0
#endif
// One trilinear fetch per 3D look-up (1) or the array mode's interpolation along eta from
// slice fetches (0, default).
#ifndef OPENPBR_LUT_TEXTURE_TRILINEAR_ETA
#define OPENPBR_LUT_TEXTURE_TRILINEAR_ETA 0
#endif

#define OPENPBR_LUT_TEXTURE_GGX_ALBEDO 0
#define OPENPBR_LUT_TEXTURE_DIELECTRIC_REFLECTION 1
#define OPENPBR_LUT_TEXTURE_DIELECTRIC_TRANSMISSION 2
#define OPENPBR_LUT_TEXTURE_DIELECTRIC_INTERFACE 3
#define OPENPBR_LUT_TEXTURE_GGX_ANISOTROPY_RATIO 4
#define OPENPBR_LUT_TEXTURE_FUZZ_LTC_A 5
#define OPENPBR_LUT_TEXTURE_FUZZ_LTC_B 6
#define OPENPBR_LUT_TEXTURE_FUZZ_LTC_R 7
#define OPENPBR_LUT_TEXTURE_FILM_LOBE 8
#define OPENPBR_LUT_TEXTURE_COUNT 9
// Index of a table among the host's textures of its dimension, e.g. for two arrays
// sampler2D[4] (ids 0, 5, 6, 7) and sampler3D[5] (ids 1-4, 8): 0, 0, 1, 2, 3, 1, 2, 3, 4.
#define OPENPBR_LUT_TEXTURE_SLOT(lut_id) \
    ((lut_id) == 0 ? 0 : ((lut_id) <= 4 ? (lut_id)-1 : ((lut_id) == 8 ? 4 : (lut_id)-4)))

// Declarations the library can make itself (OPENPBR_LUT_TEXTURES_DECLARE=1, Slang, GLSL and
// HLSL; default 0: the host declares its textures and defines the two macros): table id k at
// binding (HLSL register t) OPENPBR_LUT_TEXTURES_FIRST_BINDING + k of set 0, a combined image
// sampler (HLSL: a Texture2D/3D<float> and one SamplerState, for glslang's
// --auto-sampled-textures or DXC's [[vk::combinedImageSampler]]), e.g. for the Slang module,
// whose macros an importer cannot define: slangc -DOPENPBR_USE_TEXTURE_LUTS=1
// -DOPENPBR_LUT_TEXTURES_DECLARE=1.
#ifndef OPENPBR_LUT_TEXTURES_DECLARE
#define OPENPBR_LUT_TEXTURES_DECLARE 0
#endif
// First binding of the declared textures, e.g. 6 (after the conformance kernels' buffers 0-5).
#ifndef OPENPBR_LUT_TEXTURES_FIRST_BINDING
#define OPENPBR_LUT_TEXTURES_FIRST_BINDING 6
#endif
// Name of the declared texture of a table id (expanded first, then pasted).
#define OPENPBR_LUT_TEXTURE_NAME_OF(number) openpbr_lut_texture_##number
#define OPENPBR_LUT_TEXTURE_NAME(lut_id) OPENPBR_LUT_TEXTURE_NAME_OF(lut_id)

#if OPENPBR_USE_TEXTURE_LUTS && OPENPBR_LUT_TEXTURES_DECLARE
#if defined(OPENPBR_LANGUAGE_TARGET_GLSL)
#define OPENPBR_LUT_TEXTURE_DECLARE(number, kind) \
    layout(set = 0, binding = OPENPBR_LUT_TEXTURES_FIRST_BINDING + number) uniform kind openpbr_lut_texture_##number;
OPENPBR_LUT_TEXTURE_DECLARE(0, sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(1, sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(2, sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(3, sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(4, sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(5, sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(6, sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(7, sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(8, sampler3D)
#define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) textureLod(OPENPBR_LUT_TEXTURE_NAME(lut_id), uv, 0.0f).x
#define OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw) textureLod(OPENPBR_LUT_TEXTURE_NAME(lut_id), uvw, 0.0f).x
#elif defined(OPENPBR_LANGUAGE_TARGET_SLANG)
#define OPENPBR_LUT_TEXTURE_DECLARE(number, kind) \
    [[vk::binding(OPENPBR_LUT_TEXTURES_FIRST_BINDING + number, 0)]] kind<float> openpbr_lut_texture_##number;
OPENPBR_LUT_TEXTURE_DECLARE(0, Sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(1, Sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(2, Sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(3, Sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(4, Sampler3D)
OPENPBR_LUT_TEXTURE_DECLARE(5, Sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(6, Sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(7, Sampler2D)
OPENPBR_LUT_TEXTURE_DECLARE(8, Sampler3D)
#define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) OPENPBR_LUT_TEXTURE_NAME(lut_id).SampleLevel(uv, 0.0f)
#define OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw) OPENPBR_LUT_TEXTURE_NAME(lut_id).SampleLevel(uvw, 0.0f)
#elif defined(OPENPBR_LANGUAGE_TARGET_HLSL)
#define OPENPBR_LUT_TEXTURE_DECLARE(number, kind)                                                                       \
    kind<float> openpbr_lut_texture_##number : register(OPENPBR_CONCATENATE(t, OPENPBR_LUT_TEXTURES_REGISTER_##number), \
                                                        OPENPBR_CONCATENATE(space, OPENPBR_HLSL_REGISTER_SPACE));
// Registers t6 ... t14 for the default first binding 6 (HLSL registers are literal tokens).
#define OPENPBR_LUT_TEXTURES_REGISTER_0 6
#define OPENPBR_LUT_TEXTURES_REGISTER_1 7
#define OPENPBR_LUT_TEXTURES_REGISTER_2 8
#define OPENPBR_LUT_TEXTURES_REGISTER_3 9
#define OPENPBR_LUT_TEXTURES_REGISTER_4 10
#define OPENPBR_LUT_TEXTURES_REGISTER_5 11
#define OPENPBR_LUT_TEXTURES_REGISTER_6 12
#define OPENPBR_LUT_TEXTURES_REGISTER_7 13
#define OPENPBR_LUT_TEXTURES_REGISTER_8 14
OPENPBR_LUT_TEXTURE_DECLARE(0, Texture2D)
OPENPBR_LUT_TEXTURE_DECLARE(1, Texture3D)
OPENPBR_LUT_TEXTURE_DECLARE(2, Texture3D)
OPENPBR_LUT_TEXTURE_DECLARE(3, Texture3D)
OPENPBR_LUT_TEXTURE_DECLARE(4, Texture3D)
OPENPBR_LUT_TEXTURE_DECLARE(5, Texture2D)
OPENPBR_LUT_TEXTURE_DECLARE(6, Texture2D)
OPENPBR_LUT_TEXTURE_DECLARE(7, Texture2D)
OPENPBR_LUT_TEXTURE_DECLARE(8, Texture3D)
SamplerState openpbr_lut_sampler : register(s0, OPENPBR_CONCATENATE(space, OPENPBR_HLSL_REGISTER_SPACE));
#define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) OPENPBR_LUT_TEXTURE_NAME(lut_id).SampleLevel(openpbr_lut_sampler, uv, 0.0f)
#define OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw) OPENPBR_LUT_TEXTURE_NAME(lut_id).SampleLevel(openpbr_lut_sampler, uvw, 0.0f)
#else
#error "OPENPBR_LUT_TEXTURES_DECLARE=1 is available for Slang, GLSL and HLSL; define the texture macros yourself"
#endif
#endif

#if OPENPBR_USE_TEXTURE_LUTS
#if !defined(OPENPBR_SAMPLE_2D_TEXTURE) || !defined(OPENPBR_SAMPLE_3D_TEXTURE)
#error \
    "OPENPBR_USE_TEXTURE_LUTS=1: define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) and OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw) before including openpbr.h (slang/openpbr_lut_textures.h says how to fill the textures)"
#endif
#if defined(OPENPBR_LUT_MODE_ARRAY) || defined(OPENPBR_LUT_MODE_BUFFER)
#error "OPENPBR_USE_TEXTURE_LUTS=1 replaces the array and buffer modes: define no OPENPBR_LUT_MODE_*"
#endif
// No table storage is declared: every look-up goes through the host's texture macros.
#define OPENPBR_LUT_MODE_TEXTURE 1
#define OPENPBR_FUZZ_LTC_MODE_TEXTURE 1
#endif

#endif
