// A stand-in for a GPU's texture units, for the C++ build of the texture tables
// (OPENPBR_USE_TEXTURE_LUTS=1): the eight tables of slang/openpbr_lut_textures.h as textures
// filled exactly as that header says (one float channel, x fastest), sampled the way Vulkan
// specifies linear filtering with clamp-to-edge addressing and normalized coordinates
// (Vulkan spec, "Texel Filtering": i0 = floor(u W - 0.5), alpha = frac(u W - 0.5)), with the
// filter weights either exact (float) or rounded to `subtexel_bits` fractional bits as a GPU's
// filter hardware does (VkPhysicalDeviceLimits::subTexelPrecisionBits, 8 on most GPUs and on
// lavapipe; the Vulkan minimum is 4).
#ifndef OPENPBR_TEXTURE_SAMPLER_H
#define OPENPBR_TEXTURE_SAMPLER_H

#include <glm/glm.hpp>

namespace texture_luts_host {

// Fractional bits of the filter weights, e.g. 8; 0: exact float weights.
extern int subtexel_bits;
// Number of texture fetches so far (for the cost comparison).
extern long long fetch_count;

float sample_2d(int lut_id, glm::vec2 uv);
float sample_3d(int lut_id, glm::vec3 uvw);

}  // namespace texture_luts_host

#define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) ::texture_luts_host::sample_2d((lut_id), (uv))
#define OPENPBR_SAMPLE_3D_TEXTURE(lut_id, uvw) ::texture_luts_host::sample_3d((lut_id), (uvw))

#endif
