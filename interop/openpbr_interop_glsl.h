// GLSL backend: the dialect is GLSL 4.50, so only the few non-GLSL names are defined here.
// Include after `#version 450` (and after any `#extension` lines of the including shader).
#ifndef OPENPBR_INTEROP_GLSL_H
#define OPENPBR_INTEROP_GLSL_H

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
// (OPENPBR_SPECIALIZATION_ID_<name>), on unless the pipeline's VkSpecializationInfo says false.
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name) \
    layout(constant_id = OPENPBR_SPECIALIZATION_ID_##name) const bool name = true;
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) name

// Program-scope constants, e.g. OpenPBR_VacuumIor.
#define OPENPBR_GLOBAL_CONSTANT const

// Loops kept rolled (openpbr_interop.h), where the compiler has the extension (glslang does).
#ifdef GL_EXT_control_flow_attributes
#extension GL_EXT_control_flow_attributes : enable
#define OPENPBR_DONT_UNROLL [[dont_unroll]]
#endif

float atan2(float y, float x) { return atan(y, x); }

// HLSL's saturate, which the dialect uses; a shader that defines its own sets
// OPENPBR_USE_CUSTOM_SATURATE=1 (GLSL rejects a second definition of the same overload).
#if !(defined(OPENPBR_USE_CUSTOM_SATURATE) && OPENPBR_USE_CUSTOM_SATURATE)
float saturate(float x) { return clamp(x, 0.0f, 1.0f); }
vec2 saturate(vec2 x) { return clamp(x, vec2(0.0f), vec2(1.0f)); }
vec3 saturate(vec3 x) { return clamp(x, vec3(0.0f), vec3(1.0f)); }
vec4 saturate(vec4 x) { return clamp(x, vec4(0.0f), vec4(1.0f)); }
#endif

#endif
