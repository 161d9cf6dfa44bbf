// vulkan_memory.cpp - the Vulkan compute runner's buffers, images and their memory (see
// vulkan_runner.h): host-visible coherent buffers by default, device-local ones behind staging
// copies on request, sampled images with their staging buffers.
#include <cstring>

#include "host/gpu/vulkan_runner.h"
#include "host/gpu/vulkan_runner_internal.h"

namespace openpbr::host::vulkan_internal {

RunResources::~RunResources()
{
    const VkDevice device = context.device;
    // After a failed wait the GPU may still use these objects; waiting for the queue
    // is the only safe way to destroy them.
    if (submitted) static_cast<void>(vkQueueWaitIdle(context.queue));
    if (query_pool != VK_NULL_HANDLE) vkDestroyQueryPool(device, query_pool, nullptr);
    if (fence != VK_NULL_HANDLE) vkDestroyFence(device, fence, nullptr);
    if (command_buffer != VK_NULL_HANDLE)
    {
        vkFreeCommandBuffers(device, context.command_pool, 1, &command_buffer);
    }
    if (setup_command_buffer != VK_NULL_HANDLE)
    {
        vkFreeCommandBuffers(device, context.command_pool, 1, &setup_command_buffer);
    }
    if (readback_command_buffer != VK_NULL_HANDLE)
    {
        vkFreeCommandBuffers(device, context.command_pool, 1, &readback_command_buffer);
    }
    for (const MappedBuffer& buffer : device_buffers)
    {
        if (buffer.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, buffer.buffer, nullptr);
        if (buffer.memory != VK_NULL_HANDLE) vkFreeMemory(device, buffer.memory, nullptr);
    }
    if (descriptor_pool != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, descriptor_pool, nullptr);
    for (const MappedBuffer& buffer : buffers)
    {
        if (buffer.sampler != VK_NULL_HANDLE) vkDestroySampler(device, buffer.sampler, nullptr);
        if (buffer.view != VK_NULL_HANDLE) vkDestroyImageView(device, buffer.view, nullptr);
        if (buffer.image != VK_NULL_HANDLE) vkDestroyImage(device, buffer.image, nullptr);
        if (buffer.image_memory != VK_NULL_HANDLE) vkFreeMemory(device, buffer.image_memory, nullptr);
        if (buffer.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, buffer.buffer, nullptr);
        // Freeing mapped memory unmaps it implicitly.
        if (buffer.memory != VK_NULL_HANDLE) vkFreeMemory(device, buffer.memory, nullptr);
    }
}

namespace {

uint32_t find_host_memory_type(const ContextState& context, const uint32_t allowed_type_bits)
{
    // Coherent so that neither flushes before the dispatch nor invalidations after it are
    // needed; the device lists memory types best first, so the first match is taken.
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (uint32_t index = 0; index < context.memory_properties.memoryTypeCount; ++index)
    {
        if ((allowed_type_bits & (1u << index)) != 0 &&
            (context.memory_properties.memoryTypes[index].propertyFlags & wanted) == wanted)
        {
            return index;
        }
    }
    throw std::runtime_error("no HOST_VISIBLE | HOST_COHERENT memory type for a buffer");
}

// DEVICE_LOCAL memory for a buffer (any other properties allowed: on lavapipe and integrated
// GPUs it is also host-visible).
uint32_t find_device_memory_type(const ContextState& context, const uint32_t allowed_type_bits)
{
    for (uint32_t index = 0; index < context.memory_properties.memoryTypeCount; ++index)
    {
        if ((allowed_type_bits & (1u << index)) != 0 &&
            (context.memory_properties.memoryTypes[index].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) != 0)
        {
            return index;
        }
    }
    throw std::runtime_error("no DEVICE_LOCAL memory type for a buffer");
}

// Host-visible, coherent memory for one buffer or image (the same path for both); the caller
// binds it (vkBindBufferMemory / vkBindImageMemory) and maps it.
void allocate_mapped_memory(const ContextState& context, const VkMemoryRequirements& requirements, MappedBuffer& target)
{
    VkMemoryAllocateInfo allocate_info{};
    allocate_info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate_info.allocationSize = requirements.size;
    allocate_info.memoryTypeIndex = find_host_memory_type(context, requirements.memoryTypeBits);
    check(vkAllocateMemory(context.device, &allocate_info, nullptr, &target.memory), "vkAllocateMemory");
}

// A sampled-image binding: an optimal-tiled R32_SFLOAT image in device-local memory, its
// host-visible staging buffer holding the floats tightly packed (x fastest, then y, then z),
// its view and a bilinear clamp-to-edge sampler. Optimal tiling because GPUs need it: NVIDIA's
// driver samples no linear-tiled 3D image (seen on an H100, driver 580), and linear 2D images
// are only guaranteed, not fast. run() copies the staging buffer into the image and moves it to
// SHADER_READ_ONLY_OPTIMAL once, before the first dispatch.
void create_sampled_image(const ContextState& context, const BufferBinding& binding, MappedBuffer& target)
{
    const VkDevice device = context.device;
    const VkFormat format = VK_FORMAT_R32_SFLOAT;
    const std::size_t row_bytes = std::size_t(binding.image_width) * sizeof(float);
    const std::string where = "run: image at binding " + std::to_string(binding.binding);
    const uint32_t depth = std::max(binding.image_depth, 1u);
    const bool volume = depth > 1;
    if (binding.image_height == 0 || binding.data == nullptr ||
        binding.data->size() != row_bytes * binding.image_height * depth)
    {
        throw std::runtime_error(where + " needs " + std::to_string(binding.image_width) + " x " +
                                 std::to_string(binding.image_height) + " x " + std::to_string(depth) + " floats of data");
    }
    VkFormatProperties format_properties{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device, format, &format_properties);
    const VkFormatFeatureFlags needed =
        VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if ((format_properties.optimalTilingFeatures & needed) != needed)
    {
        throw std::runtime_error(where + ": the device cannot sample R32_SFLOAT images with bilinear filtering");
    }
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImageFormatProperties image_properties{};
    if (vkGetPhysicalDeviceImageFormatProperties(context.physical_device, format,
                                                 volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                                 usage, 0, &image_properties) != VK_SUCCESS ||
        image_properties.maxExtent.width < binding.image_width || image_properties.maxExtent.height < binding.image_height ||
        image_properties.maxExtent.depth < depth)
    {
        throw std::runtime_error(where + ": the device cannot sample R32_SFLOAT images of " +
                                 std::to_string(binding.image_width) + " x " + std::to_string(binding.image_height) + " x " +
                                 std::to_string(depth));
    }
    VkImageCreateInfo image_info{};
    image_info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    image_info.imageType = volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    image_info.format = format;
    image_info.extent = {binding.image_width, binding.image_height, depth};
    image_info.mipLevels = 1;
    image_info.arrayLayers = 1;
    image_info.samples = VK_SAMPLE_COUNT_1_BIT;
    image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
    image_info.usage = usage;
    image_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    image_info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(device, &image_info, nullptr, &target.image), "vkCreateImage");
    VkMemoryRequirements image_requirements{};
    vkGetImageMemoryRequirements(device, target.image, &image_requirements);
    target.image_memory = allocate_device_memory(context, image_requirements);
    check(vkBindImageMemory(device, target.image, target.image_memory, 0), "vkBindImageMemory");

    VkBufferCreateInfo staging_info{};
    staging_info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    staging_info.size = binding.data->size();
    staging_info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    staging_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(device, &staging_info, nullptr, &target.buffer), "vkCreateBuffer");
    VkMemoryRequirements staging_requirements{};
    vkGetBufferMemoryRequirements(device, target.buffer, &staging_requirements);
    allocate_mapped_memory(context, staging_requirements, target);
    check(vkBindBufferMemory(device, target.buffer, target.memory, 0), "vkBindBufferMemory");
    check(vkMapMemory(device, target.memory, 0, VK_WHOLE_SIZE, 0, &target.mapped), "vkMapMemory");
    target.size = binding.data->size();
    std::memcpy(target.mapped, binding.data->data(), binding.data->size());

    VkImageViewCreateInfo view_info{};
    view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view_info.image = target.image;
    view_info.viewType = volume ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    check(vkCreateImageView(device, &view_info, nullptr, &target.view), "vkCreateImageView");

    VkSamplerCreateInfo sampler_info{};
    sampler_info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    sampler_info.magFilter = VK_FILTER_LINEAR;
    sampler_info.minFilter = VK_FILTER_LINEAR;
    sampler_info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler_info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    check(vkCreateSampler(device, &sampler_info, nullptr, &target.sampler), "vkCreateSampler");
}

}  // namespace

// Device-local memory for one buffer or image, from its requirements; the caller binds it.
VkDeviceMemory allocate_device_memory(const ContextState& context, const VkMemoryRequirements& requirements)
{
    VkMemoryAllocateInfo allocate_info{};
    allocate_info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate_info.allocationSize = requirements.size;
    allocate_info.memoryTypeIndex = find_device_memory_type(context, requirements.memoryTypeBits);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(context.device, &allocate_info, nullptr, &memory), "vkAllocateMemory");
    return memory;
}

void upload_buffers(RunResources& resources, const std::vector<BufferBinding>& buffers, const DispatchRequest& request)
{
    const ContextState& context = resources.context;
    const VkDevice device = context.device;
    const VkPhysicalDeviceLimits& limits = context.properties.limits;
    // Upload: one buffer and one allocation per binding. Tests bind a handful of buffers,
    // so sub-allocation would be complexity without benefit.
    resources.buffers.resize(buffers.size());
    if (request.device_local) resources.device_buffers.resize(buffers.size());
    for (std::size_t index = 0; index < buffers.size(); ++index)
    {
        const BufferBinding& binding = buffers[index];
        MappedBuffer& target = resources.buffers[index];
        if (binding.image_width > 0)
        {
            create_sampled_image(context, binding, target);
            continue;
        }
        const VkDeviceSize data_size = binding.data != nullptr ? binding.data->size() : 0;
        target.size = std::max(minimum_buffer_size, round_up(data_size, buffer_size_granule));
        const VkDeviceSize range_limit = binding.uniform ? limits.maxUniformBufferRange : limits.maxStorageBufferRange;
        if (target.size > range_limit)
        {
            throw std::runtime_error("run: buffer at binding " + std::to_string(binding.binding) + " has " +
                                     std::to_string(target.size) + " bytes, above the device's range limit " +
                                     std::to_string(range_limit));
        }

        VkBufferCreateInfo buffer_info{};
        buffer_info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
        buffer_info.size = target.size;
        const VkBufferUsageFlags shader_usage =
            binding.uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        buffer_info.usage =
            request.device_local ? VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT : shader_usage;
        buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        check(vkCreateBuffer(device, &buffer_info, nullptr, &target.buffer), "vkCreateBuffer");
        if (request.device_local)
        {
            MappedBuffer& device_target = resources.device_buffers[index];
            VkBufferCreateInfo device_info = buffer_info;
            device_info.usage = shader_usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
            check(vkCreateBuffer(device, &device_info, nullptr, &device_target.buffer), "vkCreateBuffer");
            VkMemoryRequirements device_requirements{};
            vkGetBufferMemoryRequirements(device, device_target.buffer, &device_requirements);
            device_target.memory = allocate_device_memory(context, device_requirements);
            check(vkBindBufferMemory(device, device_target.buffer, device_target.memory, 0), "vkBindBufferMemory");
            device_target.size = target.size;
        }

        VkMemoryRequirements requirements{};
        vkGetBufferMemoryRequirements(device, target.buffer, &requirements);
        allocate_mapped_memory(context, requirements, target);
        check(vkBindBufferMemory(device, target.buffer, target.memory, 0), "vkBindBufferMemory");
        check(vkMapMemory(device, target.memory, 0, VK_WHOLE_SIZE, 0, &target.mapped), "vkMapMemory");

        // The padding is zeroed so that a shader reading past the host data sees zeros,
        // not another run's leftovers.
        std::memset(target.mapped, 0, static_cast<std::size_t>(target.size));
        if (data_size > 0) std::memcpy(target.mapped, binding.data->data(), binding.data->size());
    }
}

}  // namespace openpbr::host::vulkan_internal
