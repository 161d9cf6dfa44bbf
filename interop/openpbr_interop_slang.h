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
// The differentiable build (OPENPBR_AUTODIFF=1, interop/openpbr_interop.h): every function
// [Differentiable] (a differentiable function may call only differentiable ones, so the whole
// module is marked), every struct IDifferentiable, data-dependent loops bounded.
#if defined(OPENPBR_AUTODIFF) && OPENPBR_AUTODIFF
#define OPENPBR_FUNC [Differentiable]
#define OPENPBR_DIFFERENTIABLE : IDifferentiable
#define OPENPBR_MAX_ITERS(count) [MaxIters(count)]
#define OPENPBR_DETACH(value) detach(value)
#if defined(OPENPBR_USE_TEXTURE_LUTS) && OPENPBR_USE_TEXTURE_LUTS
#error "OPENPBR_AUTODIFF=1 needs buffer or array tables: texture reads (SampleLevel) have no derivative"
#endif
#else
#define OPENPBR_FUNC
// A part of prepare, inlined where it is called (interop/openpbr_interop.h); the differentiable
// build keeps the parts functions, each with its derivative.
#define OPENPBR_INLINE_FUNC [ForceInline]
#endif
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
