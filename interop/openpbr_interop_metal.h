// Metal backend (MSL 2.x): Metal's stdlib already has mix, fract, atan2 and vector types.
#ifndef OPENPBR_INTEROP_METAL_H
#define OPENPBR_INTEROP_METAL_H

#include <metal_stdlib>

// OPENPBR_USE_CUSTOM_VEC_TYPES=1: the host provides vec2/vec3/vec4 (saturate is built in).
#if defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES
#define OPENPBR_METAL_VECTOR_NAMES
#else
#define OPENPBR_METAL_VECTOR_NAMES \
    typedef float2 vec2;           \
    typedef float3 vec3;           \
    typedef float4 vec4;
#endif
#define OPENPBR_NAMESPACE_BEGIN \
    namespace openpbr {         \
    using namespace metal;      \
    OPENPBR_METAL_VECTOR_NAMES
#define OPENPBR_NAMESPACE_END }
// Program-scope constants (e.g. OpenPBR_VacuumIor) in the constant address space.
#define OPENPBR_GLOBAL_CONSTANT constant
#define inversesqrt rsqrt

#define OPENPBR_FUNC inline
#define OPENPBR_IN(type) thread const type&
#define OPENPBR_INOUT(type) thread type&
// Marks a parameter a lobe ignores (the shared lobe signature has it), e.g. the view of a
// Lambertian pdf; C-family compilers would otherwise warn.
#define OPENPBR_UNUSED(name) (void)(name)
#define OPENPBR_OUT(type) thread type&

// Feature toggles (slang/openpbr_features.h): Metal function constants at the stable ids
// (MTLFunctionConstantValues setConstantValue:type:atIndex:); a constant the application does
// not set is on.
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name) \
    constant bool name [[function_constant(OPENPBR_SPECIALIZATION_ID_##name)]];
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) (is_function_constant_defined(name) ? name : true)

#endif
