// vulkan_runner.h - a small Vulkan compute runner: create a context, build a compute pipeline
// from SPIR-V, run it over host buffers and read results back, with timings.
//
// Link dependencies:
//   - Vulkan::Vulkan   (CMake: find_package(Vulkan REQUIRED); Debian package libvulkan-dev)
//   - otherwise only the C++17 standard library
// Runtime dependencies (not needed to build):
//   - a Vulkan driver; on machines without a GPU, Mesa's lavapipe (mesa-vulkan-drivers)
//   - optional: VK_LAYER_KHRONOS_validation (vulkan-validationlayers) when validation is on
//
// Environment variables callers may set (the library never sets them itself, because the
// right cache location is a decision of the program or test, not of a library):
//   - MESA_SHADER_CACHE_DIR: where Mesa (lavapipe included) keeps its on-disk shader cache.
//     lavapipe compiles shaders at the first dispatch, so a warm cache makes that dispatch
//     much faster. Mesa silently disables the cache if the directory does not exist, so
//     create it before creating a VulkanContext.
//   - VK_ICD_FILENAMES / VK_DRIVER_FILES: restrict which Vulkan drivers the loader sees.
//
// Memory model: by default every buffer lives in HOST_VISIBLE | HOST_COHERENT memory and is
// written and read through a persistent mapping (DispatchRequest::device_local moves buffers
// to DEVICE_LOCAL memory behind staging copies). That is the natural (and only) kind on lavapipe, which
// runs on the CPU, and keeps this runner free of staging copies and explicit flushes. On a
// discrete GPU it is correct but slower (the shader reads over the bus); this runner is meant
// for tests and measurements of small kernels, not for throughput.
//
// Threading: a VulkanContext and the pipelines made from it must be used from one thread at
// a time. The validation message log is the exception: it is guarded by a mutex because the
// validation layer may report from any thread.

#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <vulkan/vulkan.h>

namespace openpbr::host {

struct VulkanOptions
{
    // Enables VK_LAYER_KHRONOS_validation and a debug messenger that collects warnings and
    // errors (see VulkanContext::validation_messages). If the layer is not installed, a
    // warning is printed once per process to stderr and the context is created without it.
    bool enable_validation = false;
    // Case-insensitive substring of the device name (e.g. "llvmpipe"). Empty: the best
    // compute-capable device, preferring discrete, then integrated, virtual, then CPU devices.
    std::string device_name_filter;
};

// One buffer bound to the pipeline's descriptor set 0.
struct BufferBinding
{
    uint32_t binding = 0;
    // Bytes uploaded before the dispatch. May be null or empty: the buffer is then still
    // created (at least 16 bytes, zero-filled) because Vulkan forbids zero-sized buffers.
    std::vector<std::byte>* data = nullptr;
    // Copy the buffer back into *data after the last dispatch (same size as uploaded).
    bool read_back = false;
    // Uniform buffer instead of storage buffer (must match the pipeline's layout).
    bool uniform = false;
    // Non-zero: not a buffer but a 2D single-channel float image (VK_FORMAT_R32_SFLOAT) of
    // image_width x image_height texels, row by row in *data, bound as a combined image sampler
    // with bilinear filtering and clamp-to-edge addressing (e.g. a table read with hardware
    // filtering, OPENPBR_LUT_FILTERED_2D). Never read back.
    uint32_t image_width = 0;
    uint32_t image_height = 0;
    // Above 1: a 3D image of image_depth slices of image_width x image_height, slice by slice
    // in *data, with trilinear filtering (e.g. the 3D tables of OPENPBR_USE_TEXTURE_LUTS).
    uint32_t image_depth = 1;
};

// The descriptor layout of one binding, as the pipeline is created with it.
struct BindingLayout
{
    uint32_t binding = 0;
    bool uniform = false;
    bool sampled_image = false;  // a combined image sampler (BufferBinding::image_width > 0)
};

// A specialization constant as its 32-bit pattern. Every scalar kind that GLSL/Slang allow
// for constant_id (bool as VkBool32, int, uint, float) is 4 bytes, so one word suffices.
struct SpecializationConstant
{
    uint32_t id = 0;
    uint32_t value_bits = 0;

    static SpecializationConstant of_bool(uint32_t id, bool value) { return {id, value ? VK_TRUE : VK_FALSE}; }
    static SpecializationConstant of_uint(uint32_t id, uint32_t value) { return {id, value}; }
    static SpecializationConstant of_int(uint32_t id, int32_t value)
    {
        uint32_t bits = 0;
        std::memcpy(&bits, &value, sizeof bits);
        return {id, bits};
    }
    static SpecializationConstant of_float(uint32_t id, float value)
    {
        static_assert(sizeof(float) == sizeof(uint32_t), "float must be 32-bit");
        uint32_t bits = 0;
        std::memcpy(&bits, &value, sizeof bits);
        return {id, bits};
    }
};

struct DispatchTiming
{
    double pipeline_create_ms = 0.0;  // vkCreateComputePipelines (lavapipe defers codegen)
    double first_dispatch_ms = 0.0;   // submit to fence signalled; includes llvmpipe's JIT
    // Median over dispatches 2..repeats. With repeats == 1 there is no steady-state sample
    // and this equals first_dispatch_ms.
    double dispatch_ms = 0.0;
    // Same rule as dispatch_ms, from GPU timestamp queries; empty when the queue has no
    // timestamp support.
    std::optional<double> device_dispatch_ms;
    double upload_ms = 0.0;    // create, allocate and map buffers, copy host data in
    double readback_ms = 0.0;  // copy read_back buffers out of mapped memory
    int dispatch_count = 0;
};

// One statistic a driver reports for a pipeline (VK_KHR_pipeline_executable_properties), e.g.
// {"<executable>: Register count", 96}.
struct PipelineStatistic
{
    std::string name;
    double value = 0.0;
};

struct ContextState;   // defined in vulkan_runner_internal.h (not installed)
struct PipelineState;  // defined in vulkan_runner_internal.h (not installed)

class VulkanContext
{
  public:
    // Returns nullopt (and a one-line reason in *error_message, if given) when no usable
    // device exists or any step of instance/device creation fails. Never throws for that.
    static std::optional<VulkanContext> create(const VulkanOptions& options, std::string* error_message);

    VulkanContext(VulkanContext&&) noexcept;
    VulkanContext& operator=(VulkanContext&&) noexcept;
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;
    ~VulkanContext();

    std::string device_name() const;
    // True when the validation layer and messenger are active (requested and available).
    bool validation_enabled() const;
    // Validation-layer warnings and errors collected so far, each prefixed "error: " or
    // "warning: ". Tests assert this is empty after their work.
    std::vector<std::string> validation_messages() const;
    void clear_validation_messages();

    // Raw handles, for callers that need to do something this runner does not.
    VkInstance instance_handle() const;
    VkPhysicalDevice physical_device_handle() const;
    VkDevice device_handle() const;
    VkQueue queue_handle() const;

    // Implementation detail, public only for ComputePipeline: pipelines share the state so
    // that the device outlives every pipeline made from it.
    const std::shared_ptr<ContextState>& state() const { return state_; }

  private:
    explicit VulkanContext(std::shared_ptr<ContextState> state);
    std::shared_ptr<ContextState> state_;
};

struct ComputePipelineDescription
{
    std::vector<uint32_t> spirv_words;
    std::string entry_point = "main";
    std::vector<SpecializationConstant> specialization_constants;
    // Descriptor set 0 layout; each binding index at most once.
    std::vector<BindingLayout> bindings;
    uint32_t push_constant_size = 0;  // bytes, multiple of 4; 0 = no push constants
};

class ComputePipeline
{
  public:
    // Throws std::runtime_error on invalid descriptions or failing Vulkan calls. The
    // pipeline keeps the context's device alive, so it may outlive the VulkanContext object.
    ComputePipeline(const VulkanContext& context, const ComputePipelineDescription& description);

    ComputePipeline(ComputePipeline&&) noexcept;
    ComputePipeline& operator=(ComputePipeline&&) noexcept;
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;
    ~ComputePipeline();

    // Time to create the shader module, layouts and pipeline. On lavapipe this is small:
    // llvmpipe compiles the shader at the first dispatch instead.
    double create_ms() const;
    // The driver's statistics of this pipeline (register count, spills, ... as the driver names
    // them) where it supports VK_KHR_pipeline_executable_properties; empty elsewhere.
    std::vector<PipelineStatistic> statistics() const;
    const std::vector<BindingLayout>& bindings() const;
    uint32_t push_constant_size() const;
    // Implementation detail, public only for run().
    PipelineState& state() const { return *state_; }

  private:
    std::unique_ptr<PipelineState> state_;
};

struct DispatchRequest
{
    uint32_t groups_x = 1;
    uint32_t groups_y = 1;
    uint32_t groups_z = 1;
    int repeats = 1;  // total dispatches (>= 1); each is submitted and waited for on its own
    // Exactly the pipeline's push_constant_size bytes (or empty when it has none).
    std::vector<std::byte> push_constants;
    // Buffers in DEVICE_LOCAL memory, filled once from host-visible staging buffers by a copy
    // before the first dispatch and read back by a copy after the last: on a discrete GPU the
    // kernel then reads video memory instead of host memory over the bus (throughput
    // measurements, `openpbr bench gpu`). Images keep their host-visible linear memory.
    bool device_local = false;
};

// Uploads every buffer, dispatches `repeats` times and copies read_back buffers back into
// their vectors. `buffers` must cover exactly the pipeline's bindings, with matching kinds.
// Throws std::runtime_error on mismatches and failing Vulkan calls.
DispatchTiming run(ComputePipeline& pipeline, const std::vector<BufferBinding>& buffers, const DispatchRequest& request);
DispatchTiming run(ComputePipeline& pipeline, const std::vector<BufferBinding>& buffers, uint32_t groups_x,
                   uint32_t groups_y = 1, uint32_t groups_z = 1, int repeats = 1);

// The layout a pipeline needs for these buffers (binding index and kind of each).
std::vector<BindingLayout> binding_layouts_of(const std::vector<BufferBinding>& buffers);

// Reads a SPIR-V binary. Throws std::runtime_error naming the path when the file is missing,
// unreadable, empty, not a multiple of 4 bytes, or does not start with the SPIR-V magic.
std::vector<uint32_t> load_spirv_file(const std::string& path);

// The name of a VkResult ("VK_ERROR_DEVICE_LOST"), for messages.
const char* vk_result_name(VkResult result);

// Byte views of trivially copyable element vectors, for BufferBinding::data.
template <class Element> std::vector<std::byte> to_bytes(const std::vector<Element>& elements)
{
    static_assert(std::is_trivially_copyable_v<Element>, "elements are copied as bytes");
    std::vector<std::byte> bytes(elements.size() * sizeof(Element));
    if (!bytes.empty()) std::memcpy(bytes.data(), elements.data(), bytes.size());
    return bytes;
}

template <class Element> std::vector<Element> from_bytes(const std::vector<std::byte>& bytes)
{
    static_assert(std::is_trivially_copyable_v<Element>, "elements are copied as bytes");
    if (bytes.size() % sizeof(Element) != 0)
    {
        throw std::runtime_error("from_bytes: " + std::to_string(bytes.size()) +
                                 " bytes is not a whole number of elements of size " + std::to_string(sizeof(Element)));
    }
    std::vector<Element> elements(bytes.size() / sizeof(Element));
    if (!bytes.empty()) std::memcpy(elements.data(), bytes.data(), bytes.size());
    return elements;
}

}  // namespace openpbr::host
