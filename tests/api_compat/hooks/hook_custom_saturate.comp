#version 450
// OPENPBR_USE_CUSTOM_SATURATE (GLSL): this shader defines saturate() itself. Compiled once with
// -DOPENPBR_USE_CUSTOM_SATURATE=1 (must compile) and once without (must fail: GLSL rejects the
// backend's second definition), which shows that the hook decides.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;

float saturate(float x) { return clamp(x, 0.0f, 1.0f); }
vec2 saturate(vec2 x) { return clamp(x, vec2(0.0f), vec2(1.0f)); }
vec3 saturate(vec3 x) { return clamp(x, vec3(0.0f), vec3(1.0f)); }
vec4 saturate(vec4 x) { return clamp(x, vec4(0.0f), vec4(1.0f)); }

#include "../../../slang/openpbr.h"

layout(std430, set = 0, binding = 2) writeonly buffer Results { float results[]; };

void main()
{
    const OpenPBR_PreparedBsdf prepared = openpbr_prepare(openpbr_make_default_resolved_inputs(), vec3(0.0f, 0.0f, 1.0f));
    results[0] = prepared.probability_specular;
}
