// The entry point of hook_custom_interop_bsdf.cpp, callable without either build's types.
#ifndef HOOK_CUSTOM_INTEROP_H
#define HOOK_CUSTOM_INTEROP_H
// material_values: base_color rgb, coat_weight, fuzz_weight, specular_roughness; view: xyz;
// u: xyz. out: sample pdf, sample weight (red), probability_coat. Returns probability_fuzz.
float custom_interop_shade(const float* material_values, const float* view_values, const float* u_values, float* out);
#endif
