// vulkan_pipeline.cpp - the Vulkan compute runner's shader modules and compute pipelines
// (see vulkan_runner.h).
#include <fstream>
#include <set>
#include <sstream>

#include "host/gpu/vulkan_runner.h"
#include "host/gpu/vulkan_runner_internal.h"
#include "host/support/stopwatch.h"

namespace openpbr::host {

using namespace vulkan_internal;

namespace {

void check_spirv_header(const std::vector<uint32_t>& words, const std::string& what)
{
    if (words.size() < spirv_header_words)
    {
        throw std::runtime_error(what + ": " + std::to_string(words.size() * 4) +
                                 " bytes is shorter than a SPIR-V header (20 bytes)");
    }
    if (words[0] == spirv_magic_swapped)
    {
        throw std::runtime_error(what + ": SPIR-V of the other byte order is not supported");
    }
    if (words[0] != spirv_magic)
    {
        std::ostringstream message;
        message << what << ": bad SPIR-V magic 0x" << std::hex << words[0] << " (expected 0x" << spirv_magic << ")";
        throw std::runtime_error(message.str());
    }
}

}  // namespace

ComputePipeline::ComputePipeline(const VulkanContext& context, const ComputePipelineDescription& description)
    : state_(std::make_unique<PipelineState>())
{
    const Stopwatch create_stopwatch;
    PipelineState& state = *state_;
    state.context = context.state();
    const ContextState& context_state = *state.context;
    const VkDevice device = context_state.device;

    check_spirv_header(description.spirv_words, "ComputePipeline");
    if (description.entry_point.empty())
    {
        throw std::runtime_error("ComputePipeline: empty entry point name");
    }
    if (description.push_constant_size % 4 != 0 ||
        description.push_constant_size > context_state.properties.limits.maxPushConstantsSize)
    {
        throw std::runtime_error("ComputePipeline: push constant size " + std::to_string(description.push_constant_size) +
                                 " is not a multiple of 4 or exceeds the device limit " +
                                 std::to_string(context_state.properties.limits.maxPushConstantsSize));
    }
    state.push_constant_size = description.push_constant_size;

    state.bindings = description.bindings;
    std::sort(state.bindings.begin(), state.bindings.end(),
              [](const BindingLayout& a, const BindingLayout& b) { return a.binding < b.binding; });
    for (std::size_t index = 1; index < state.bindings.size(); ++index)
    {
        // Two descriptors at one binding are not rejected by every driver or layer; on
        // lavapipe they silently give wrong results, so refuse them here.
        if (state.bindings[index].binding == state.bindings[index - 1].binding)
        {
            throw std::runtime_error("ComputePipeline: binding " + std::to_string(state.bindings[index].binding) +
                                     " is listed twice");
        }
    }

    std::set<uint32_t> specialization_ids;
    for (const SpecializationConstant& constant : description.specialization_constants)
    {
        if (!specialization_ids.insert(constant.id).second)
        {
            throw std::runtime_error("ComputePipeline: specialization constant id " + std::to_string(constant.id) +
                                     " is listed twice");
        }
    }

    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = description.spirv_words.size() * sizeof(uint32_t);
    module_info.pCode = description.spirv_words.data();
    check(vkCreateShaderModule(device, &module_info, nullptr, &state.shader_module), "vkCreateShaderModule");

    std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
    for (const BindingLayout& binding : state.bindings)
    {
        VkDescriptorSetLayoutBinding layout_binding{};
        layout_binding.binding = binding.binding;
        layout_binding.descriptorType = descriptor_type_of(binding);
        layout_binding.descriptorCount = 1;
        layout_binding.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        layout_bindings.push_back(layout_binding);
    }
    VkDescriptorSetLayoutCreateInfo set_layout_info{};
    set_layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_layout_info.bindingCount = static_cast<uint32_t>(layout_bindings.size());
    set_layout_info.pBindings = layout_bindings.data();
    check(vkCreateDescriptorSetLayout(device, &set_layout_info, nullptr, &state.set_layout), "vkCreateDescriptorSetLayout");

    VkPushConstantRange push_range{};
    push_range.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    push_range.offset = 0;
    push_range.size = state.push_constant_size;
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &state.set_layout;
    layout_info.pushConstantRangeCount = state.push_constant_size > 0 ? 1 : 0;
    layout_info.pPushConstantRanges = &push_range;
    check(vkCreatePipelineLayout(device, &layout_info, nullptr, &state.pipeline_layout), "vkCreatePipelineLayout");

    // Every constant is one 32-bit word, laid out back to back.
    std::vector<VkSpecializationMapEntry> map_entries;
    std::vector<uint32_t> specialization_data;
    for (const SpecializationConstant& constant : description.specialization_constants)
    {
        VkSpecializationMapEntry entry{};
        entry.constantID = constant.id;
        entry.offset = static_cast<uint32_t>(specialization_data.size() * sizeof(uint32_t));
        entry.size = sizeof(uint32_t);
        map_entries.push_back(entry);
        specialization_data.push_back(constant.value_bits);
    }
    VkSpecializationInfo specialization{};
    specialization.mapEntryCount = static_cast<uint32_t>(map_entries.size());
    specialization.pMapEntries = map_entries.data();
    specialization.dataSize = specialization_data.size() * sizeof(uint32_t);
    specialization.pData = specialization_data.data();

    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = state.shader_module;
    pipeline_info.stage.pName = description.entry_point.c_str();
    pipeline_info.stage.pSpecializationInfo = map_entries.empty() ? nullptr : &specialization;
    pipeline_info.layout = state.pipeline_layout;
    if (context_state.executable_statistics) pipeline_info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    check(vkCreateComputePipelines(device, context_state.pipeline_cache, 1, &pipeline_info, nullptr, &state.pipeline),
          "vkCreateComputePipelines");

    // The pipeline holds what it needs; the module is dead weight from here on.
    vkDestroyShaderModule(device, state.shader_module, nullptr);
    state.shader_module = VK_NULL_HANDLE;
    state.create_ms = create_stopwatch.milliseconds();
}

ComputePipeline::ComputePipeline(ComputePipeline&&) noexcept = default;
ComputePipeline& ComputePipeline::operator=(ComputePipeline&&) noexcept = default;
ComputePipeline::~ComputePipeline() = default;

double ComputePipeline::create_ms() const { return state_->create_ms; }

std::vector<PipelineStatistic> ComputePipeline::statistics() const
{
    const ContextState& context = *state_->context;
    std::vector<PipelineStatistic> result;
    if (!context.executable_statistics) return result;
    VkPipelineInfoKHR pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR;
    pipeline_info.pipeline = state_->pipeline;
    uint32_t executable_count = 0;
    if (context.get_executable_properties(context.device, &pipeline_info, &executable_count, nullptr) != VK_SUCCESS)
    {
        return result;
    }
    std::vector<VkPipelineExecutablePropertiesKHR> executables(executable_count);
    for (VkPipelineExecutablePropertiesKHR& executable : executables)
    {
        executable.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR;
    }
    if (context.get_executable_properties(context.device, &pipeline_info, &executable_count, executables.data()) !=
        VK_SUCCESS)
    {
        return result;
    }
    for (uint32_t index = 0; index < executable_count; ++index)
    {
        VkPipelineExecutableInfoKHR executable_info{};
        executable_info.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR;
        executable_info.pipeline = state_->pipeline;
        executable_info.executableIndex = index;
        uint32_t statistic_count = 0;
        if (context.get_executable_statistics(context.device, &executable_info, &statistic_count, nullptr) != VK_SUCCESS)
        {
            continue;
        }
        std::vector<VkPipelineExecutableStatisticKHR> statistics(statistic_count);
        for (VkPipelineExecutableStatisticKHR& statistic : statistics)
        {
            statistic.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
        }
        if (context.get_executable_statistics(context.device, &executable_info, &statistic_count, statistics.data()) !=
            VK_SUCCESS)
        {
            continue;
        }
        for (const VkPipelineExecutableStatisticKHR& statistic : statistics)
        {
            double value = 0.0;
            switch (statistic.format)
            {
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: value = statistic.value.b32 ? 1.0 : 0.0; break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: value = double(statistic.value.i64); break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: value = double(statistic.value.u64); break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: value = statistic.value.f64; break;
            default: continue;
            }
            result.push_back({std::string(executables[index].name) + ": " + statistic.name, value});
        }
    }
    return result;
}
const std::vector<BindingLayout>& ComputePipeline::bindings() const { return state_->bindings; }
uint32_t ComputePipeline::push_constant_size() const { return state_->push_constant_size; }

std::vector<uint32_t> load_spirv_file(const std::string& path)
{
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) throw std::runtime_error("load_spirv_file: cannot open '" + path + "'");
    const std::streamoff size = file.tellg();
    if (size <= 0) throw std::runtime_error("load_spirv_file: '" + path + "' is empty or unreadable");
    if (size % 4 != 0)
    {
        throw std::runtime_error("load_spirv_file: '" + path + "' has " + std::to_string(size) +
                                 " bytes, not a multiple of 4");
    }
    std::vector<uint32_t> words(static_cast<std::size_t>(size / 4));
    file.seekg(0);
    if (!file.read(reinterpret_cast<char*>(words.data()), size))
    {
        throw std::runtime_error("load_spirv_file: reading '" + path + "' failed");
    }
    check_spirv_header(words, "load_spirv_file: '" + path + "'");
    return words;
}

}  // namespace openpbr::host
