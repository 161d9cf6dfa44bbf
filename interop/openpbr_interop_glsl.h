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

float atan2(float y, float x) { return atan(y, x); }

#endif
