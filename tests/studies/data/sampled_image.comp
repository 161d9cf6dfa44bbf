// Reads a 2D image through the runner's sampled-image binding (host/gpu/vulkan_runner.h,
// BufferBinding::image_width): results[i] = the bilinearly filtered texel value at
// coordinates[i] (normalized texture coordinates), as the hardware-filtered table mode
// (OPENPBR_LUT_FILTERED_2D) reads table 0.
#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) uniform sampler2D table_texture;
layout(std430, set = 0, binding = 1) readonly buffer Coordinates { vec2 coordinates[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Results { float results[]; };

void main()
{
    const uint index = gl_GlobalInvocationID.x;
    results[index] = textureLod(table_texture, coordinates[index], 0.0).r;
}
