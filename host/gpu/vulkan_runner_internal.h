// vulkan_runner_internal.h - what the parts of the Vulkan compute runner share (not installed;
// included only by host/gpu/vulkan_*.cpp). The runner is split by job: vulkan_context.cpp
// (instance and device), vulkan_memory.cpp (buffers, images and their memory),
// vulkan_pipeline.cpp (shader modules and compute pipelines), vulkan_dispatch.cpp (descriptor
// sets, command recording, submission, timing and read-back). The public interface is
// vulkan_runner.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/gpu/vulkan_runner.h"

namespace openpbr::host {

namespace vulkan_internal {

// SPIR-V words start with this magic number; seen byte-swapped, the file has the other
// endianness, which Vulkan does not accept.
constexpr uint32_t spirv_magic = 0x07230203u;
constexpr uint32_t spirv_magic_swapped = 0x03022307u;
constexpr uint32_t spirv_header_words = 5;

// Vulkan forbids zero-sized buffers, and 16 bytes keeps every buffer a whole number of
// vec4s, the strictest alignment a std140/std430 block can ask for.
constexpr VkDeviceSize minimum_buffer_size = 16;
constexpr VkDeviceSize buffer_size_granule = 16;

// A runaway validation layer (one message per dispatch, say) must not grow memory without
// bound; beyond this many, messages are only counted.
constexpr std::size_t maximum_kept_validation_messages = 1000;

constexpr uint32_t required_api_version = VK_API_VERSION_1_2;

const char* const validation_layer_name = "VK_LAYER_KHRONOS_validation";

inline void check(const VkResult result, const char* const call_name)
{
    if (result != VK_SUCCESS)
    {
        throw std::runtime_error(std::string(call_name) + " failed: " + vk_result_name(result));
    }
}

inline double median(std::vector<double> samples)
{
    if (samples.empty()) return 0.0;
    std::sort(samples.begin(), samples.end());
    const std::size_t middle = samples.size() / 2;
    return samples.size() % 2 == 1 ? samples[middle] : 0.5 * (samples[middle - 1] + samples[middle]);
}

inline VkDescriptorType descriptor_type_of(const BindingLayout& layout)
{
    return layout.sampled_image ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
           : layout.uniform     ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

inline VkDeviceSize round_up(const VkDeviceSize value, const VkDeviceSize granule)
{
    return (value + granule - 1) / granule * granule;
}

struct ValidationLog
{
    mutable std::mutex mutex;
    std::vector<std::string> messages;
    std::size_t dropped_count = 0;
};

}  // namespace vulkan_internal

// ----------------------------------------------------------------------------------------
// Context (vulkan_context.cpp)

struct ContextState
{
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger = nullptr;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory_properties{};
    uint32_t queue_family_index = 0;
    uint32_t timestamp_valid_bits = 0;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool command_pool = VK_NULL_HANDLE;
    // Kept for the context's lifetime so that pipelines built from the same SPIR-V (or the
    // same code with other specialization constants) can reuse the driver's work.
    VkPipelineCache pipeline_cache = VK_NULL_HANDLE;
    bool validation_active = false;
    // VK_KHR_pipeline_executable_properties enabled (pipelines then capture statistics).
    bool executable_statistics = false;
    PFN_vkGetPipelineExecutablePropertiesKHR get_executable_properties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR get_executable_statistics = nullptr;
    // Its address is handed to the messenger, so it lives here, in a heap object that never
    // moves, rather than in the movable VulkanContext.
    vulkan_internal::ValidationLog validation_log;

    ContextState() = default;
    ContextState(const ContextState&) = delete;
    ContextState& operator=(const ContextState&) = delete;

    ~ContextState()
    {
        if (device != VK_NULL_HANDLE)
        {
            // Nothing may still be executing when its objects go away; errors cannot be
            // reported from a destructor and the device is being torn down anyway.
            static_cast<void>(vkDeviceWaitIdle(device));
            if (pipeline_cache != VK_NULL_HANDLE) vkDestroyPipelineCache(device, pipeline_cache, nullptr);
            if (command_pool != VK_NULL_HANDLE) vkDestroyCommandPool(device, command_pool, nullptr);
            vkDestroyDevice(device, nullptr);
        }
        if (messenger != VK_NULL_HANDLE && destroy_messenger != nullptr)
        {
            destroy_messenger(instance, messenger, nullptr);
        }
        if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
    }
};

// ----------------------------------------------------------------------------------------
// Pipeline (vulkan_pipeline.cpp)

struct PipelineState
{
    std::shared_ptr<ContextState> context;
    VkShaderModule shader_module = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::vector<BindingLayout> bindings;  // sorted by binding index
    uint32_t push_constant_size = 0;
    double create_ms = 0.0;

    PipelineState() = default;
    PipelineState(const PipelineState&) = delete;
    PipelineState& operator=(const PipelineState&) = delete;

    ~PipelineState()
    {
        if (!context) return;
        const VkDevice device = context->device;
        if (pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device, pipeline, nullptr);
        if (pipeline_layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, pipeline_layout, nullptr);
        if (set_layout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
        if (shader_module != VK_NULL_HANDLE) vkDestroyShaderModule(device, shader_module, nullptr);
    }
};

namespace vulkan_internal {

// ----------------------------------------------------------------------------------------
// Memory (vulkan_memory.cpp)

struct MappedBuffer
{
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    VkDeviceSize size = 0;
    // A sampled-image binding (BufferBinding::image_width > 0) has these instead of a buffer.
    // The image lives in device-local memory with optimal tiling; `buffer` / `memory` are then
    // its host-visible staging copy, moved into the image once before the first dispatch.
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory image_memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
};

// Everything one run() creates, released in its destructor so that an exception anywhere
// in run() leaks nothing.
struct RunResources
{
    const ContextState& context;
    std::vector<MappedBuffer> buffers;
    // DispatchRequest::device_local: the device-local buffer behind each staging buffer of
    // `buffers` (VK_NULL_HANDLE for images), and the copy back after the last dispatch.
    std::vector<MappedBuffer> device_buffers;
    VkCommandBuffer readback_command_buffer = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    VkCommandBuffer command_buffer = VK_NULL_HANDLE;
    VkCommandBuffer setup_command_buffer = VK_NULL_HANDLE;  // image layout transitions
    VkFence fence = VK_NULL_HANDLE;
    VkQueryPool query_pool = VK_NULL_HANDLE;
    bool submitted = false;

    explicit RunResources(const ContextState& owner) : context(owner) {}
    RunResources(const RunResources&) = delete;
    RunResources& operator=(const RunResources&) = delete;
    ~RunResources();
};

// The buffers of one run (DispatchRequest::device_local: also their device-local copies),
// created, allocated, mapped and filled from the bindings' data; images through
// create_sampled_image. Throws std::runtime_error naming the binding on failures.
void upload_buffers(RunResources& resources, const std::vector<BufferBinding>& buffers, const DispatchRequest& request);

// Device-local memory for one buffer or image, from its requirements; the caller binds it.
VkDeviceMemory allocate_device_memory(const ContextState& context, const VkMemoryRequirements& requirements);

}  // namespace vulkan_internal

}  // namespace openpbr::host
