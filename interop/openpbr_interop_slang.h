// Slang backend: GLSL names map onto Slang's HLSL-flavoured core module.
// Macros do not cross Slang module boundaries, so these spellings stay inside the
// openpbr module; importers see ordinary float3/float2 signatures.
#ifndef OPENPBR_INTEROP_SLANG_H
#define OPENPBR_INTEROP_SLANG_H

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

// Feature toggles (slang/openpbr_features.h): SPIR-V specialization constants with stable ids
// (OPENPBR_SPECIALIZATION_ID_<name>). For HLSL and CUDA output Slang would turn them into
// uniforms, which the downstream compiler cannot fold; those builds pass
// -DOPENPBR_SPECIALIZATION_CONSTANTS=0 and choose toggles as compile-time permutations, e.g.
// -DOPENPBR_FEATURE_COAT=0 (default 1: specialization constants).
#ifndef OPENPBR_SPECIALIZATION_CONSTANTS
#define OPENPBR_SPECIALIZATION_CONSTANTS 1
#endif
#if OPENPBR_SPECIALIZATION_CONSTANTS
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name) \
    [vk::constant_id(OPENPBR_SPECIALIZATION_ID_##name)] const bool name = true;
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) name
#else
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name)
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) true
#endif

#endif
