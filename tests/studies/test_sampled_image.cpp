// The Vulkan runner's sampled-image binding (host/gpu/vulkan_runner.h), which the accuracy study's
// texture storage mode uses (OPENPBR_LUT_FILTERED_2D, docs/accuracy-vs-time.md): texel centres
// return the texel, points between texels the bilinear blend, points outside the image the edge
// texel (clamp to edge), with no validation message.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "host/gpu/vulkan_runner.h"

namespace {

using openpbr::host::BufferBinding;

constexpr std::uint32_t image_width = 3;
constexpr std::uint32_t image_height = 2;
// Row by row: texel (x, y) at y * width + x.
const std::vector<float> texels = {1.0f, 2.0f, 4.0f, 8.0f, 16.0f, 32.0f};

float texel(int x, int y) { return texels[std::size_t(y) * image_width + std::size_t(x)]; }

// Normalized coordinate of the point at `fraction` of the way from texel i to texel i + 1 along
// an axis of n texels (texel centres at (i + 0.5) / n).
float coordinate(float texel_index, float fraction, std::uint32_t n) { return (texel_index + 0.5f + fraction) / float(n); }

struct Probe
{
    float u = 0.0f;
    float v = 0.0f;
    float expected = 0.0f;
    float tolerance = 0.0f;
    std::string what;
};

TEST(SampledImage, BilinearClampToEdge)
{
    openpbr::host::VulkanOptions options;
    options.enable_validation = true;
    std::string error;
    std::optional<openpbr::host::VulkanContext> context = openpbr::host::VulkanContext::create(options, &error);
    ASSERT_TRUE(context.has_value()) << "no Vulkan device (lavapipe is a dependency): " << error;

    // Blend weights of 0.5 and 0.25 are exact at any sub-texel precision of >= 2 bits; 0.3 is
    // rounded to the device's subTexelPrecisionBits (>= 4 by the Vulkan spec), so it gets
    // 2^-4 of the texel difference.
    const float difference = texel(1, 0) - texel(0, 0);
    const std::vector<Probe> probes = {
        {coordinate(0, 0, image_width), coordinate(0, 0, image_height), texel(0, 0), 1e-6f, "texel (0, 0)"},
        {coordinate(2, 0, image_width), coordinate(1, 0, image_height), texel(2, 1), 1e-6f, "texel (2, 1)"},
        {coordinate(0, 0.5f, image_width), coordinate(0, 0, image_height), 0.5f * (texel(0, 0) + texel(1, 0)), 1e-5f,
         "half way along x"},
        {coordinate(1, 0.25f, image_width), coordinate(0, 0.5f, image_height),
         0.5f * (0.75f * texel(1, 0) + 0.25f * texel(2, 0)) + 0.5f * (0.75f * texel(1, 1) + 0.25f * texel(2, 1)), 1e-4f,
         "bilinear (0.25, 0.5)"},
        {coordinate(0, 0.3f, image_width), coordinate(0, 0, image_height), texel(0, 0) + 0.3f * difference,
         difference / 16.0f, "weight 0.3"},
        {-0.5f, coordinate(1, 0, image_height), texel(0, 1), 1e-6f, "clamped left of the image"},
        {1.5f, 2.0f, texel(2, 1), 1e-6f, "clamped beyond the corner"},
    };

    std::vector<float> coordinates;
    for (const Probe& probe : probes)
    {
        coordinates.push_back(probe.u);
        coordinates.push_back(probe.v);
    }
    std::vector<std::byte> image_bytes = openpbr::host::to_bytes(texels);
    std::vector<std::byte> coordinate_bytes = openpbr::host::to_bytes(coordinates);
    std::vector<std::byte> result_bytes(probes.size() * sizeof(float));
    BufferBinding image;
    image.binding = 0;
    image.data = &image_bytes;
    image.image_width = image_width;
    image.image_height = image_height;
    const std::vector<BufferBinding> buffers = {image, {1, &coordinate_bytes, false}, {2, &result_bytes, true}};

    openpbr::host::ComputePipelineDescription description;
    description.spirv_words = openpbr::host::load_spirv_file(OPENPBR_SAMPLED_IMAGE_SPIRV);
    description.bindings = openpbr::host::binding_layouts_of(buffers);
    openpbr::host::ComputePipeline pipeline(*context, description);
    // Two dispatches: the image's layout transition must happen once, not per dispatch.
    openpbr::host::run(pipeline, buffers, std::uint32_t(probes.size()), 1, 1, 2);

    const std::vector<float> results = openpbr::host::from_bytes<float>(result_bytes);
    for (std::size_t i = 0; i < probes.size(); ++i)
    {
        EXPECT_NEAR(results[i], probes[i].expected, probes[i].tolerance) << probes[i].what;
    }
    EXPECT_TRUE(context->validation_messages().empty())
        << (context->validation_messages().empty() ? std::string() : context->validation_messages().front());
}

}  // namespace
