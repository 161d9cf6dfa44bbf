// HLSL backend (DXC, FXC-era HLSL, glslang's HLSL front end): the GLSL dialect's names map
// onto HLSL intrinsics, as in the Slang backend, and the tables are StructuredBuffers at
// registers t<OPENPBR_LUT_BINDING> and t<OPENPBR_FUZZ_LTC_BINDING> (t0 and t1 by default) in
// space OPENPBR_HLSL_REGISTER_SPACE (0 by default); no [[vk::binding]]: DXC's -spirv maps
// t<N>/space<S> to binding N of set S by itself.
//
// One construct of the dialect has no HLSL spelling: a vector built from one scalar, e.g.
// vec3(1.0f), which DXC and FXC reject ("too few elements in vector initialization") while
// glslang and Slang accept it. HLSL users take the generated, self-contained openpbr.hlsl
// (targets/hlsl/generate_hlsl.mjs): it spells every such call openpbr_splat3(x) and every
// dialect name in HLSL, so it defines no vec3/mix/fract macros in the includer's scope.
// Including slang/openpbr.h from HLSL directly works only with compilers that accept splats.
#ifndef OPENPBR_INTEROP_HLSL_H
#define OPENPBR_INTEROP_HLSL_H

// OPENPBR_USE_CUSTOM_VEC_TYPES=1: the host spells vec2/vec3/vec4 itself (e.g. typedefs).
#if !(defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES)
#define vec2 float2
#define vec3 float3
#define vec4 float4
#endif
#define mix lerp
#define fract frac
#define inversesqrt rsqrt

// Token pasting through one level of expansion, e.g. OPENPBR_CONCATENATE(t, 0) -> t0 for an
// HLSL register named after a binding macro.
#define OPENPBR_CONCATENATE_TOKENS(a, b) a##b
#define OPENPBR_CONCATENATE(a, b) OPENPBR_CONCATENATE_TOKENS(a, b)

// Register space of the table buffers, e.g. 0 (space0).
#ifndef OPENPBR_HLSL_REGISTER_SPACE
#define OPENPBR_HLSL_REGISTER_SPACE 0
#endif

// Program-scope constants, e.g. OpenPBR_VacuumIor (saturate is built in).
#define OPENPBR_GLOBAL_CONSTANT static const
#define OPENPBR_DONT_UNROLL [loop]

#define OPENPBR_NAMESPACE_BEGIN
#define OPENPBR_NAMESPACE_END
#define OPENPBR_FUNC
#define OPENPBR_IN(type) in type
#define OPENPBR_INOUT(type) inout type
// Marks a parameter a lobe ignores (the shared lobe signature has it), e.g. the view of a
// Lambertian pdf; C-family compilers would otherwise warn.
#define OPENPBR_UNUSED(name)
#define OPENPBR_OUT(type) out type

// Feature toggles (slang/openpbr_features.h): compile-time permutations, e.g. dxc
// -DOPENPBR_FEATURE_COAT=0; DXIL has no specialization constants (a uniform would fold nothing).
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name)
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) true

// Vector from one value, the HLSL spelling of the dialect's vec2(x), vec3(x), vec4(x): a
// scalar is replicated, a vector of the same size passes through.
float2 openpbr_splat2(float x) { return float2(x, x); }
float2 openpbr_splat2(int x) { return float2(float(x), float(x)); }
float2 openpbr_splat2(uint x) { return float2(float(x), float(x)); }
float2 openpbr_splat2(float2 v) { return v; }
float3 openpbr_splat3(float x) { return float3(x, x, x); }
float3 openpbr_splat3(int x) { return float3(float(x), float(x), float(x)); }
float3 openpbr_splat3(uint x) { return float3(float(x), float(x), float(x)); }
float3 openpbr_splat3(float3 v) { return v; }
float4 openpbr_splat4(float x) { return float4(x, x, x, x); }
float4 openpbr_splat4(int x) { return float4(float(x), float(x), float(x), float(x)); }
float4 openpbr_splat4(uint x) { return float4(float(x), float(x), float(x), float(x)); }
float4 openpbr_splat4(float4 v) { return v; }

#endif
