// vulkan_dispatch.cpp - one run of the Vulkan compute runner (see vulkan_runner.h): the
// request checked against the pipeline, the buffers uploaded (vulkan_memory.cpp), descriptor set
// 0 written, the dispatch recorded once and submitted `repeats` times with timings, and the
// results read back. Each step is a function of its own over the run's RunResources, which
// release everything whatever step throws.
#include <cstring>

#include "host/gpu/vulkan_runner.h"
#include "host/gpu/vulkan_runner_internal.h"
#include "host/support/stopwatch.h"

namespace openpbr::host {

using namespace vulkan_internal;

namespace {

void check_buffers_match_pipeline(const PipelineState& pipeline, const std::vector<BufferBinding>& buffers)
{
    std::vector<BindingLayout> given = binding_layouts_of(buffers);
    std::sort(given.begin(), given.end(),
              [](const BindingLayout& a, const BindingLayout& b) { return a.binding < b.binding; });
    const auto describe = [](const std::vector<BindingLayout>& layouts) {
        std::string text;
        for (const BindingLayout& layout : layouts)
        {
            text += (text.empty() ? "" : ", ") + std::to_string(layout.binding) +
                    (layout.sampled_image ? " sampled image"
                     : layout.uniform     ? " uniform"
                                          : " storage");
        }
        return "[" + text + "]";
    };
    const bool same =
        given.size() == pipeline.bindings.size() && std::equal(given.begin(), given.end(), pipeline.bindings.begin(),
                                                               [](const BindingLayout& a, const BindingLayout& b) {
                                                                   return a.binding == b.binding && a.uniform == b.uniform &&
                                                                          a.sampled_image == b.sampled_image;
                                                               });
    if (!same)
    {
        throw std::runtime_error("run: buffers " + describe(given) + " do not match the pipeline's bindings " +
                                 describe(pipeline.bindings));
    }
}

// The request's repeats, group counts and push constants against the device and the pipeline,
// and the buffers against the pipeline's bindings.
void check_request(const PipelineState& pipeline_state, const std::vector<BufferBinding>& buffers,
                   const DispatchRequest& request)
{
    const VkPhysicalDeviceLimits& limits = pipeline_state.context->properties.limits;
    if (request.repeats < 1)
    {
        throw std::runtime_error("run: repeats must be at least 1, got " + std::to_string(request.repeats));
    }
    const uint32_t groups[3] = {request.groups_x, request.groups_y, request.groups_z};
    for (int axis = 0; axis < 3; ++axis)
    {
        if (groups[axis] == 0 || groups[axis] > limits.maxComputeWorkGroupCount[axis])
        {
            throw std::runtime_error("run: group count " + std::to_string(groups[axis]) + " on axis " +
                                     std::to_string(axis) + " is zero or above the device limit " +
                                     std::to_string(limits.maxComputeWorkGroupCount[axis]));
        }
    }
    if (request.push_constants.size() != pipeline_state.push_constant_size)
    {
        throw std::runtime_error("run: " + std::to_string(request.push_constants.size()) +
                                 " push constant bytes given, pipeline expects " +
                                 std::to_string(pipeline_state.push_constant_size));
    }
    check_buffers_match_pipeline(pipeline_state, buffers);
}

// Descriptor set 0 over the uploaded buffers and images; VK_NULL_HANDLE without bindings.
VkDescriptorSet write_descriptor_set(RunResources& resources, const PipelineState& pipeline_state,
                                     const std::vector<BufferBinding>& buffers, const DispatchRequest& request)
{
    const VkDevice device = resources.context.device;
    // Descriptor set 0. A pipeline without bindings gets no set at all, because a pool with
    // no pool sizes is not allowed.
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
    if (!buffers.empty())
    {
        uint32_t storage_count = 0;
        uint32_t uniform_count = 0;
        uint32_t image_count = 0;
        for (const BufferBinding& binding : buffers)
        {
            ++(binding.image_width > 0 ? image_count : binding.uniform ? uniform_count : storage_count);
        }
        std::vector<VkDescriptorPoolSize> pool_sizes;
        if (image_count > 0) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, image_count});
        if (storage_count > 0) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage_count});
        if (uniform_count > 0) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniform_count});
        VkDescriptorPoolCreateInfo pool_info{};
        pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = static_cast<uint32_t>(pool_sizes.size());
        pool_info.pPoolSizes = pool_sizes.data();
        check(vkCreateDescriptorPool(device, &pool_info, nullptr, &resources.descriptor_pool), "vkCreateDescriptorPool");

        VkDescriptorSetAllocateInfo set_info{};
        set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
        set_info.descriptorPool = resources.descriptor_pool;
        set_info.descriptorSetCount = 1;
        set_info.pSetLayouts = &pipeline_state.set_layout;
        check(vkAllocateDescriptorSets(device, &set_info, &descriptor_set), "vkAllocateDescriptorSets");

        std::vector<VkDescriptorBufferInfo> buffer_infos(buffers.size());
        std::vector<VkDescriptorImageInfo> image_infos(buffers.size());
        std::vector<VkWriteDescriptorSet> writes(buffers.size());
        const std::vector<BindingLayout> layouts = binding_layouts_of(buffers);
        for (std::size_t index = 0; index < buffers.size(); ++index)
        {
            const MappedBuffer& resource = resources.buffers[index];
            VkWriteDescriptorSet& write = writes[index];
            write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            write.dstSet = descriptor_set;
            write.dstBinding = buffers[index].binding;
            write.descriptorCount = 1;
            write.descriptorType = descriptor_type_of(layouts[index]);
            if (layouts[index].sampled_image)
            {
                image_infos[index] = {resource.sampler, resource.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
                write.pImageInfo = &image_infos[index];
            }
            else
            {
                const VkBuffer shader_buffer =
                    request.device_local ? resources.device_buffers[index].buffer : resource.buffer;
                buffer_infos[index] = {shader_buffer, 0, resource.size};
                write.pBufferInfo = &buffer_infos[index];
            }
        }
        vkUpdateDescriptorSets(device, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
    }
    return descriptor_set;
}

VkCommandBufferAllocateInfo command_buffer_info(const ContextState& context)
{
    VkCommandBufferAllocateInfo command_info{};
    command_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    command_info.commandPool = context.command_pool;
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    return command_info;
}

VkCommandBufferBeginInfo command_buffer_begin_info()
{
    VkCommandBufferBeginInfo begin_info{};
    begin_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    return begin_info;
}

// The dispatch's command buffer (with its timestamps where the queue has them) and the fence
// its submissions signal.
void record_dispatch(RunResources& resources, const PipelineState& pipeline_state, const VkDescriptorSet descriptor_set,
                     const DispatchRequest& request)
{
    const ContextState& context = resources.context;
    const VkDevice device = context.device;
    // Timestamps only where the queue supports them; they are a bonus, never a requirement.
    const bool use_timestamps = context.timestamp_valid_bits > 0;
    if (use_timestamps)
    {
        VkQueryPoolCreateInfo query_info{};
        query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        query_info.queryCount = 2;
        check(vkCreateQueryPool(device, &query_info, nullptr, &resources.query_pool), "vkCreateQueryPool");
    }

    const VkCommandBufferAllocateInfo command_info = command_buffer_info(context);
    check(vkAllocateCommandBuffers(device, &command_info, &resources.command_buffer), "vkAllocateCommandBuffers");

    // Recorded once and submitted `repeats` times: the steady-state measurement then
    // contains no recording cost, only submission, execution and the fence wait.
    const VkCommandBuffer commands = resources.command_buffer;
    const VkCommandBufferBeginInfo begin_info = command_buffer_begin_info();
    check(vkBeginCommandBuffer(commands, &begin_info), "vkBeginCommandBuffer");
    if (use_timestamps) vkCmdResetQueryPool(commands, resources.query_pool, 0, 2);
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_state.pipeline);
    if (descriptor_set != VK_NULL_HANDLE)
    {
        vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_state.pipeline_layout, 0, 1,
                                &descriptor_set, 0, nullptr);
    }
    if (!request.push_constants.empty())
    {
        vkCmdPushConstants(commands, pipeline_state.pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                           static_cast<uint32_t>(request.push_constants.size()), request.push_constants.data());
    }
    if (use_timestamps)
    {
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, resources.query_pool, 0);
    }
    vkCmdDispatch(commands, request.groups_x, request.groups_y, request.groups_z);
    if (use_timestamps)
    {
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, resources.query_pool, 1);
    }
    // Shader writes must be visible to host reads after the fence (or to the copy back, for
    // device-local buffers); host writes before the submit need no barrier because
    // vkQueueSubmit makes them visible.
    VkMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = request.device_local ? VK_ACCESS_TRANSFER_READ_BIT : VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         request.device_local ? VK_PIPELINE_STAGE_TRANSFER_BIT : VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host,
                         0, nullptr, 0, nullptr);
    check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    check(vkCreateFence(device, &fence_info, nullptr, &resources.fence), "vkCreateFence");
}

// Images filled from their staging buffers and device-local buffers from theirs, once, in a
// submission of their own before the dispatches.
void submit_setup(RunResources& resources, const std::vector<BufferBinding>& buffers, const DispatchRequest& request)
{
    const ContextState& context = resources.context;
    const VkDevice device = context.device;
    const VkCommandBufferAllocateInfo command_info = command_buffer_info(context);
    const VkCommandBufferBeginInfo begin_info = command_buffer_begin_info();
    // Images are filled from their staging buffers and moved to SHADER_READ_ONLY_OPTIMAL once,
    // in a submission of their own: the dispatch command buffer is submitted `repeats` times
    // and must not repeat a transition out of a layout the image has already left.
    std::vector<VkImageMemoryBarrier> image_barriers;       // UNDEFINED -> TRANSFER_DST_OPTIMAL
    std::vector<VkImageMemoryBarrier> image_read_barriers;  // TRANSFER_DST -> SHADER_READ_ONLY
    for (const MappedBuffer& resource : resources.buffers)
    {
        if (resource.image == VK_NULL_HANDLE) continue;
        VkImageMemoryBarrier barrier{};
        barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
        barrier.srcAccessMask = 0;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.image = resource.image;
        barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        image_barriers.push_back(barrier);
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        image_read_barriers.push_back(barrier);
    }
    if (!image_barriers.empty() || request.device_local)
    {
        check(vkAllocateCommandBuffers(device, &command_info, &resources.setup_command_buffer), "vkAllocateCommandBuffers");
        check(vkBeginCommandBuffer(resources.setup_command_buffer, &begin_info), "vkBeginCommandBuffer");
        if (request.device_local)
        {
            // Staging to device-local, once; the dispatches then read and write video memory.
            for (std::size_t index = 0; index < buffers.size(); ++index)
            {
                if (resources.device_buffers[index].buffer == VK_NULL_HANDLE) continue;
                const VkBufferCopy region{0, 0, resources.buffers[index].size};
                vkCmdCopyBuffer(resources.setup_command_buffer, resources.buffers[index].buffer,
                                resources.device_buffers[index].buffer, 1, &region);
            }
            VkMemoryBarrier to_shader{};
            to_shader.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
            to_shader.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            to_shader.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT;
            vkCmdPipelineBarrier(resources.setup_command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &to_shader, 0, nullptr, 0, nullptr);
        }
        if (!image_barriers.empty())
        {
            vkCmdPipelineBarrier(resources.setup_command_buffer, VK_PIPELINE_STAGE_HOST_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 0, 0, nullptr, 0, nullptr, static_cast<uint32_t>(image_barriers.size()),
                                 image_barriers.data());
            for (std::size_t index = 0; index < buffers.size(); ++index)
            {
                const MappedBuffer& resource = resources.buffers[index];
                if (resource.image == VK_NULL_HANDLE) continue;
                VkBufferImageCopy region{};
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageExtent = {buffers[index].image_width, buffers[index].image_height,
                                      std::max(buffers[index].image_depth, 1u)};
                vkCmdCopyBufferToImage(resources.setup_command_buffer, resource.buffer, resource.image,
                                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            }
            vkCmdPipelineBarrier(resources.setup_command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr,
                                 static_cast<uint32_t>(image_read_barriers.size()), image_read_barriers.data());
        }
        check(vkEndCommandBuffer(resources.setup_command_buffer), "vkEndCommandBuffer");
        VkSubmitInfo setup_submit{};
        setup_submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
        setup_submit.commandBufferCount = 1;
        setup_submit.pCommandBuffers = &resources.setup_command_buffer;
        check(vkQueueSubmit(context.queue, 1, &setup_submit, resources.fence), "vkQueueSubmit");
        resources.submitted = true;
        check(vkWaitForFences(device, 1, &resources.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        check(vkResetFences(device, 1, &resources.fence), "vkResetFences");
    }
}

// The dispatch submitted request.repeats times, each waited for: the host and (where the queue
// has timestamps) device times into `timing`.
void submit_dispatches(RunResources& resources, const DispatchRequest& request, DispatchTiming& timing)
{
    const ContextState& context = resources.context;
    const VkDevice device = context.device;
    const VkPhysicalDeviceLimits& limits = context.properties.limits;
    const VkCommandBuffer commands = resources.command_buffer;
    const bool use_timestamps = resources.query_pool != VK_NULL_HANDLE;
    VkSubmitInfo submit_info{};
    submit_info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit_info.commandBufferCount = 1;
    submit_info.pCommandBuffers = &commands;

    const uint64_t timestamp_mask =
        context.timestamp_valid_bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << context.timestamp_valid_bits) - 1;
    std::vector<double> host_samples;
    std::vector<double> device_samples;
    for (int repeat = 0; repeat < request.repeats; ++repeat)
    {
        if (repeat > 0) check(vkResetFences(device, 1, &resources.fence), "vkResetFences");
        const Stopwatch dispatch_stopwatch;
        check(vkQueueSubmit(context.queue, 1, &submit_info, resources.fence), "vkQueueSubmit");
        resources.submitted = true;
        check(vkWaitForFences(device, 1, &resources.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        host_samples.push_back(dispatch_stopwatch.milliseconds());

        if (use_timestamps)
        {
            uint64_t stamps[2] = {0, 0};
            check(vkGetQueryPoolResults(device, resources.query_pool, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                                        VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                  "vkGetQueryPoolResults");
            // Masked subtraction survives a counter that wraps between the two stamps.
            const uint64_t ticks = (stamps[1] - stamps[0]) & timestamp_mask;
            device_samples.push_back(static_cast<double>(ticks) * static_cast<double>(limits.timestampPeriod) * 1e-6);
        }
    }
    timing.dispatch_count = request.repeats;
    timing.first_dispatch_ms = host_samples.front();
    // The first dispatch pays for lavapipe's shader compilation, so the steady state is
    // measured over the rest whenever there is a rest.
    const auto steady = [](const std::vector<double>& samples) {
        return samples.size() > 1 ? median(std::vector<double>(samples.begin() + 1, samples.end())) : samples.front();
    };
    timing.dispatch_ms = steady(host_samples);
    if (use_timestamps) timing.device_dispatch_ms = steady(device_samples);
}

// The read_back buffers into their vectors (device-local ones through their staging copies).
void read_back(RunResources& resources, const std::vector<BufferBinding>& buffers, const DispatchRequest& request)
{
    const ContextState& context = resources.context;
    const VkDevice device = context.device;
    const VkCommandBufferAllocateInfo command_info = command_buffer_info(context);
    const VkCommandBufferBeginInfo begin_info = command_buffer_begin_info();
    if (request.device_local)
    {
        // Device-local results back into their staging buffers, then read as usual.
        check(vkAllocateCommandBuffers(device, &command_info, &resources.readback_command_buffer),
              "vkAllocateCommandBuffers");
        const VkCommandBuffer readback = resources.readback_command_buffer;
        check(vkBeginCommandBuffer(readback, &begin_info), "vkBeginCommandBuffer");
        for (std::size_t index = 0; index < buffers.size(); ++index)
        {
            if (!buffers[index].read_back || resources.device_buffers[index].buffer == VK_NULL_HANDLE) continue;
            const VkBufferCopy region{0, 0, resources.buffers[index].size};
            vkCmdCopyBuffer(readback, resources.device_buffers[index].buffer, resources.buffers[index].buffer, 1, &region);
        }
        VkMemoryBarrier copy_to_host{};
        copy_to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        copy_to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        copy_to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(readback, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &copy_to_host, 0,
                             nullptr, 0, nullptr);
        check(vkEndCommandBuffer(readback), "vkEndCommandBuffer");
        check(vkResetFences(device, 1, &resources.fence), "vkResetFences");
        VkSubmitInfo readback_submit{};
        readback_submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
        readback_submit.commandBufferCount = 1;
        readback_submit.pCommandBuffers = &readback;
        check(vkQueueSubmit(context.queue, 1, &readback_submit, resources.fence), "vkQueueSubmit");
        check(vkWaitForFences(device, 1, &resources.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    }
    for (std::size_t index = 0; index < buffers.size(); ++index)
    {
        const BufferBinding& binding = buffers[index];
        if (binding.read_back && binding.image_width == 0 && binding.data != nullptr && !binding.data->empty())
        {
            std::memcpy(binding.data->data(), resources.buffers[index].mapped, binding.data->size());
        }
    }
}

}  // namespace

std::vector<BindingLayout> binding_layouts_of(const std::vector<BufferBinding>& buffers)
{
    std::vector<BindingLayout> layouts;
    layouts.reserve(buffers.size());
    for (const BufferBinding& buffer : buffers)
    {
        layouts.push_back({buffer.binding, buffer.uniform, buffer.image_width > 0});
    }
    return layouts;
}

DispatchTiming run(ComputePipeline& pipeline, const std::vector<BufferBinding>& buffers, const DispatchRequest& request)
{
    const PipelineState& pipeline_state = pipeline.state();
    check_request(pipeline_state, buffers, request);

    DispatchTiming timing;
    timing.pipeline_create_ms = pipeline_state.create_ms;
    RunResources resources(*pipeline_state.context);
    const Stopwatch upload_stopwatch;
    upload_buffers(resources, buffers, request);
    timing.upload_ms = upload_stopwatch.milliseconds();

    const VkDescriptorSet descriptor_set = write_descriptor_set(resources, pipeline_state, buffers, request);
    record_dispatch(resources, pipeline_state, descriptor_set, request);
    submit_setup(resources, buffers, request);
    submit_dispatches(resources, request, timing);

    const Stopwatch readback_stopwatch;
    read_back(resources, buffers, request);
    timing.readback_ms = readback_stopwatch.milliseconds();
    return timing;
}

DispatchTiming run(ComputePipeline& pipeline, const std::vector<BufferBinding>& buffers, const uint32_t groups_x,
                   const uint32_t groups_y, const uint32_t groups_z, const int repeats)
{
    DispatchRequest request;
    request.groups_x = groups_x;
    request.groups_y = groups_y;
    request.groups_z = groups_z;
    request.repeats = repeats;
    return run(pipeline, buffers, request);
}

}  // namespace openpbr::host
