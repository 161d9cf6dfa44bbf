// The Slang module's exported constants and lobe-type helpers, seen from an importer
// (tests/targets/module_exports.slang, compiled by the Slang driver and run on Vulkan), equal
// the C++ build's macros and helpers bit for bit.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "host/gpu/vulkan_runner.h"
#include "slang/openpbr.h"
#include "slang/openpbr_module_constants.h"

namespace {

using namespace openpbr;
namespace host = openpbr::host;

std::uint32_t bits_of(std::uint32_t value) { return value; }
std::uint32_t bits_of(int value) { return std::uint32_t(value); }
std::uint32_t bits_of(float value)
{
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

constexpr std::uint32_t probe_lobe_types[] = {0u, 16u, 521u, 770u | 16u, 1290u, 0xffffffffu};

struct Expected
{
    std::vector<std::uint32_t> values;
    std::vector<std::string> names;
};

Expected expected_values()
{
    Expected expected;
#define OPENPBR_EXPECT_EXPORTED(type, name)   \
    expected.values.push_back(bits_of(name)); \
    expected.names.push_back(#name);
    OPENPBR_MODULE_CONSTANTS(OPENPBR_EXPECT_EXPORTED)
#undef OPENPBR_EXPECT_EXPORTED
    for (const std::uint32_t lobe_type : probe_lobe_types)
    {
        expected.values.push_back(
            (openpbr_lobe_type_is_reflection(lobe_type) ? 1u : 0u) |
            (openpbr_lobe_type_is_transmission(lobe_type) ? 2u : 0u) | (openpbr_lobe_type_is_diffuse(lobe_type) ? 4u : 0u) |
            (openpbr_lobe_type_is_glossy(lobe_type) ? 8u : 0u) | (openpbr_lobe_type_is_specular(lobe_type) ? 16u : 0u));
        expected.names.push_back("flags of lobe type " + std::to_string(lobe_type));
        expected.values.push_back(openpbr_lobe_type_id(lobe_type));
        expected.names.push_back("id of lobe type " + std::to_string(lobe_type));
    }
    return expected;
}

TEST(ModuleExports, HelpersReadFlagsBelowTheLobeId)
{
    // 521 = OPENPBR_LOBE_ID_SPECULAR_REFLECTION << 8 | GLOSSY | REFLECTION.
    EXPECT_TRUE(openpbr_lobe_type_is_glossy(521u));
    EXPECT_TRUE(openpbr_lobe_type_is_reflection(521u));
    EXPECT_FALSE(openpbr_lobe_type_is_specular(521u));
    EXPECT_FALSE(openpbr_lobe_type_is_transmission(521u));
    EXPECT_EQ(openpbr_lobe_type_id(521u), OPENPBR_LOBE_ID_SPECULAR_REFLECTION);
    EXPECT_FALSE(openpbr_lobe_type_is_reflection(OPENPBR_LOBE_TYPE_NONE));
    EXPECT_EQ(openpbr_lobe_type_id(OPENPBR_LOBE_TYPE_NONE), 0u);
}

TEST(ModuleExports, ImporterSeesEveryConstant)
{
    std::string error;
    std::optional<host::VulkanContext> context = host::VulkanContext::create(host::VulkanOptions{}, &error);
    ASSERT_TRUE(context.has_value()) << "no Vulkan device: " << error;
    const Expected expected = expected_values();
    std::vector<std::byte> out(expected.values.size() * sizeof(std::uint32_t));
    const std::vector<host::BufferBinding> buffers = {{0, &out, true}};
    host::ComputePipelineDescription description;
    description.spirv_words = host::load_spirv_file(std::string(OPENPBR_KERNEL_DIR) + "/module_exports.slang.spv");
    description.bindings = host::binding_layouts_of(buffers);
    host::ComputePipeline pipeline(*context, description);
    host::run(pipeline, buffers, 1);
    const std::vector<std::uint32_t> seen = host::from_bytes<std::uint32_t>(out);
    ASSERT_EQ(seen.size(), expected.values.size());
    for (std::size_t i = 0; i < seen.size(); ++i)
    {
        EXPECT_EQ(seen[i], expected.values[i]) << expected.names[i];
    }
}

}  // namespace
