// Metal backend (MSL 2.x): Metal's stdlib already has mix, fract, atan2 and vector types.
#ifndef OPENPBR_INTEROP_METAL_H
#define OPENPBR_INTEROP_METAL_H

#include <metal_stdlib>

#define OPENPBR_NAMESPACE_BEGIN \
    namespace openpbr {         \
    using namespace metal;      \
    typedef float2 vec2;        \
    typedef float3 vec3;        \
    typedef float4 vec4;
#define OPENPBR_NAMESPACE_END }
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
