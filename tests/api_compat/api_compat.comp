#version 450
// The api_compat program as GLSL: the single-source headers through the interop's GLSL
// backend, reached by the router's fallback (no OPENPBR_LANGUAGE_TARGET_* is defined here).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;

#include "../../slang/openpbr.h"
#if !defined(OPENPBR_LANGUAGE_TARGET_GLSL)
#error "the interop router did not fall back to GLSL"
#endif

layout(std430, set = 0, binding = 2) writeonly buffer ApiCompatResults { float api_compat_results[]; };
#define API_COMPAT_WRITE(index, value) api_compat_results[index] = (value)
#include "api_compat_program.h"

void main()
{
    api_compat_shade(openpbr_make_default_resolved_inputs(), vec3(0.0f, 0.0f, 1.0f), normalize(vec3(0.3f, 0.2f, 0.9f)),
                     vec3(1.0f, 0.5f, 0.25f), OpenPBR_VacuumIor, vec3(0.3f, 0.6f, 0.9f), vec2(0.4f, 0.7f), 0u);
}
