// Smoke-test kernel for host/vulkan_runner: result[i] = source[i] * multiplier + bias (+ i).
// It touches every feature the runner passes to a shader: two storage buffers, a uniform
// buffer, a push constant, float and bool specialization constants and a specialized
// workgroup size.
#version 450

// The workgroup size is a specialization constant so that the test can check that
// constant ids reach the pipeline; 64 is only the default.
layout(local_size_x = 64, local_size_x_id = 1) in;

layout(constant_id = 0) const float multiplier = 1.0;
layout(constant_id = 2) const bool add_index = true;

layout(std430, set = 0, binding = 0) readonly buffer SourceValues { float values[]; } source_values;
layout(std430, set = 0, binding = 1) writeonly buffer ResultValues { float values[]; } result_values;
layout(std140, set = 0, binding = 2) uniform Parameters { uint element_count; } parameters;
layout(push_constant) uniform PushConstants { float bias; } push_constants;

void main() {
    const uint index = gl_GlobalInvocationID.x;
    // The last group usually overhangs the data; the count comes from the uniform buffer
    // rather than the buffer length so that the uniform path is exercised.
    if (index >= parameters.element_count) return;
    float value = source_values.values[index] * multiplier + push_constants.bias;
    if (add_index) value += float(index);
    result_values.values[index] = value;
}
