// vulkan_runner.cpp - implementation of the Vulkan compute runner (see vulkan_runner.h).

#include "vulkan_runner.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>
#include <iostream>
#include <mutex>
#include <set>
#include <sstream>
#include <utility>

#include "host/support/stopwatch.h"

namespace openpbr::host {

namespace {

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

void check(const VkResult result, const char* const call_name)
{
    if (result != VK_SUCCESS)
    {
        throw std::runtime_error(std::string(call_name) + " failed: " + vk_result_name(result));
    }
}

std::string lower_case(std::string text)
{
    std::transform(text.begin(), text.end(), text.begin(),
                   [](const unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string version_text(const uint32_t version)
{
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
           std::to_string(VK_API_VERSION_PATCH(version));
}

double median(std::vector<double> samples)
{
    if (samples.empty()) return 0.0;
    std::sort(samples.begin(), samples.end());
    const std::size_t middle = samples.size() / 2;
    return samples.size() % 2 == 1 ? samples[middle] : 0.5 * (samples[middle - 1] + samples[middle]);
}

VkDescriptorType descriptor_type_of(const BindingLayout& layout)
{
    return layout.sampled_image ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
           : layout.uniform     ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

VkDeviceSize round_up(const VkDeviceSize value, const VkDeviceSize granule)
{
    return (value + granule - 1) / granule * granule;
}

struct ValidationLog
{
    mutable std::mutex mutex;
    std::vector<std::string> messages;
    std::size_t dropped_count = 0;
};

VKAPI_ATTR VkBool32 VKAPI_CALL collect_validation_message(const VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                          const VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                          const VkDebugUtilsMessengerCallbackDataEXT* const callback_data,
                                                          void* const user_data)
{
    auto* const log = static_cast<ValidationLog*>(user_data);
    std::string text = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "error: " : "warning: ";
    text += (callback_data != nullptr && callback_data->pMessage != nullptr) ? callback_data->pMessage : "(no message text)";
    const std::lock_guard<std::mutex> lock(log->mutex);
    if (log->messages.size() < maximum_kept_validation_messages)
    {
        log->messages.push_back(std::move(text));
    }
    else
    {
        ++log->dropped_count;
    }
    // The specification requires VK_FALSE: the call that triggered the message proceeds.
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_create_info(ValidationLog* const log)
{
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    // Info and verbose messages are chatter (loader scans, object creation); tests care
    // about what the layer considers suspicious or wrong.
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = collect_validation_message;
    info.pUserData = log;
    return info;
}

bool layer_available(const char* const layer_name)
{
    uint32_t count = 0;
    check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> layers(count);
    check(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, layer_name) == 0; });
}

// Looks in the loader's own extensions and in those of the given layer (debug utils is
// usually provided by both, but a minimal loader may lack it).
bool instance_extension_available(const char* const extension_name, const char* const layer_name)
{
    for (const char* const source : {static_cast<const char*>(nullptr), layer_name})
    {
        uint32_t count = 0;
        check(vkEnumerateInstanceExtensionProperties(source, &count, nullptr), "vkEnumerateInstanceExtensionProperties");
        std::vector<VkExtensionProperties> extensions(count);
        check(vkEnumerateInstanceExtensionProperties(source, &count, extensions.data()),
              "vkEnumerateInstanceExtensionProperties");
        for (const VkExtensionProperties& extension : extensions)
        {
            if (std::strcmp(extension.extensionName, extension_name) == 0) return true;
        }
    }
    return false;
}

void warn_once_missing_validation(const std::string& what)
{
    static std::atomic<bool> warned{false};
    if (!warned.exchange(true))
    {
        std::cerr << "openpbr::host::VulkanContext: validation requested but " << what
                  << "; continuing without validation (install vulkan-validationlayers)\n";
    }
}

const char* device_type_name(const VkPhysicalDeviceType type)
{
    switch (type)
    {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

// Higher is preferred: a real GPU before a software rasterizer when no filter is given.
int device_type_rank(const VkPhysicalDeviceType type)
{
    switch (type)
    {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

std::optional<uint32_t> find_compute_queue_family(const VkPhysicalDevice physical_device,
                                                  uint32_t* const timestamp_valid_bits)
{
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &count, families.data());
    for (uint32_t index = 0; index < count; ++index)
    {
        if ((families[index].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0 && families[index].queueCount > 0)
        {
            *timestamp_valid_bits = families[index].timestampValidBits;
            return index;
        }
    }
    return std::nullopt;
}

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

// ----------------------------------------------------------------------------------------
// Context

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
    ValidationLog validation_log;

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

namespace {

const std::string no_device_message = "no Vulkan device found: install mesa-vulkan-drivers (lavapipe) or a GPU driver";

void create_instance(ContextState& state, const VulkanOptions& options)
{
    uint32_t loader_version = VK_API_VERSION_1_0;
    check(vkEnumerateInstanceVersion(&loader_version), "vkEnumerateInstanceVersion");
    if (loader_version < required_api_version)
    {
        throw std::runtime_error("Vulkan loader " + version_text(loader_version) + " is older than the required 1.2");
    }

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (options.enable_validation)
    {
        if (!layer_available(validation_layer_name))
        {
            warn_once_missing_validation(std::string(validation_layer_name) + " is not installed");
        }
        else if (!instance_extension_available(VK_EXT_DEBUG_UTILS_EXTENSION_NAME, validation_layer_name))
        {
            warn_once_missing_validation(std::string(VK_EXT_DEBUG_UTILS_EXTENSION_NAME) + " is not available");
        }
        else
        {
            layers.push_back(validation_layer_name);
            extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
            state.validation_active = true;
        }
    }

    VkApplicationInfo application{};
    application.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    application.pApplicationName = "openpbr-vulkan-runner";
    application.applicationVersion = 1;
    application.pEngineName = "openpbr";
    application.engineVersion = 1;
    // 1.2 at least: lavapipe's validation flags SPIR-V 1.5 (what Slang emits) under 1.0/1.1.
    application.apiVersion = required_api_version;

    // Chained into the instance create info, the messenger also sees what goes wrong inside
    // vkCreateInstance and vkDestroyInstance, which the persistent messenger cannot.
    const VkDebugUtilsMessengerCreateInfoEXT instance_messenger_info = messenger_create_info(&state.validation_log);

    VkInstanceCreateInfo create_info{};
    create_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    create_info.pNext = state.validation_active ? &instance_messenger_info : nullptr;
    create_info.pApplicationInfo = &application;
    create_info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    create_info.ppEnabledLayerNames = layers.data();
    create_info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    create_info.ppEnabledExtensionNames = extensions.data();
    const VkResult result = vkCreateInstance(&create_info, nullptr, &state.instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    {
        // The loader found no driver at all: the same situation as zero devices.
        throw std::runtime_error(no_device_message + " (vkCreateInstance: " + vk_result_name(result) + ")");
    }
    check(result, "vkCreateInstance");

    if (state.validation_active)
    {
        const auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(state.instance, "vkCreateDebugUtilsMessengerEXT"));
        state.destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(state.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (create_messenger == nullptr || state.destroy_messenger == nullptr)
        {
            throw std::runtime_error("vkGetInstanceProcAddr found no debug utils messenger functions");
        }
        check(create_messenger(state.instance, &instance_messenger_info, nullptr, &state.messenger),
              "vkCreateDebugUtilsMessengerEXT");
    }
}

void choose_physical_device(ContextState& state, const VulkanOptions& options)
{
    uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(state.instance, &count, nullptr), "vkEnumeratePhysicalDevices");
    if (count == 0) throw std::runtime_error(no_device_message);
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(state.instance, &count, devices.data()), "vkEnumeratePhysicalDevices");

    const std::string filter = lower_case(options.device_name_filter);
    std::vector<std::string> rejected;  // for a message that says what was there instead
    int best_rank = -1;
    for (const VkPhysicalDevice device : devices)
    {
        VkPhysicalDeviceProperties properties{};
        vkGetPhysicalDeviceProperties(device, &properties);
        const std::string name = properties.deviceName;
        if (!filter.empty() && lower_case(name).find(filter) == std::string::npos)
        {
            rejected.push_back(name + " (name does not match)");
            continue;
        }
        if (properties.apiVersion < required_api_version)
        {
            rejected.push_back(name + " (Vulkan " + version_text(properties.apiVersion) + " < 1.2)");
            continue;
        }
        uint32_t timestamp_valid_bits = 0;
        const std::optional<uint32_t> family = find_compute_queue_family(device, &timestamp_valid_bits);
        if (!family)
        {
            rejected.push_back(name + " (no compute queue)");
            continue;
        }
        const int rank = device_type_rank(properties.deviceType);
        if (rank > best_rank)
        {  // strict: among equals, the first enumerated wins
            best_rank = rank;
            state.physical_device = device;
            state.properties = properties;
            state.queue_family_index = *family;
            state.timestamp_valid_bits = timestamp_valid_bits;
        }
    }
    if (state.physical_device == VK_NULL_HANDLE)
    {
        std::string message = filter.empty() ? "no Vulkan 1.2 compute-capable device found"
                                             : "no Vulkan device matches filter '" + options.device_name_filter + "'";
        message += "; devices seen:";
        for (const std::string& reason : rejected) message += " " + reason + ";";
        throw std::runtime_error(message);
    }
    vkGetPhysicalDeviceMemoryProperties(state.physical_device, &state.memory_properties);
}

void create_device(ContextState& state)
{
    const float queue_priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{};
    queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue_info.queueFamilyIndex = state.queue_family_index;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &queue_priority;

    VkDeviceCreateInfo device_info{};
    device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;

    // Register counts, spills and the like per pipeline where the driver reports them
    // (VK_KHR_pipeline_executable_properties; pipeline_statistics()).
    uint32_t extension_count = 0;
    vkEnumerateDeviceExtensionProperties(state.physical_device, nullptr, &extension_count, nullptr);
    std::vector<VkExtensionProperties> extensions(extension_count);
    vkEnumerateDeviceExtensionProperties(state.physical_device, nullptr, &extension_count, extensions.data());
    const char* const executable_extension = VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable_features{};
    executable_features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR;
    const bool has_extension = std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, executable_extension) == 0;
    });
    if (has_extension && state.properties.apiVersion >= VK_API_VERSION_1_1)
    {
        VkPhysicalDeviceFeatures2 features{};
        features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
        features.pNext = &executable_features;
        vkGetPhysicalDeviceFeatures2(state.physical_device, &features);
    }
    if (executable_features.pipelineExecutableInfo == VK_TRUE)
    {
        device_info.pNext = &executable_features;
        device_info.enabledExtensionCount = 1;
        device_info.ppEnabledExtensionNames = &executable_extension;
    }
    check(vkCreateDevice(state.physical_device, &device_info, nullptr, &state.device), "vkCreateDevice");
    if (executable_features.pipelineExecutableInfo == VK_TRUE)
    {
        state.get_executable_properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
            vkGetDeviceProcAddr(state.device, "vkGetPipelineExecutablePropertiesKHR"));
        state.get_executable_statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
            vkGetDeviceProcAddr(state.device, "vkGetPipelineExecutableStatisticsKHR"));
        state.executable_statistics =
            state.get_executable_properties != nullptr && state.get_executable_statistics != nullptr;
    }
    vkGetDeviceQueue(state.device, state.queue_family_index, 0, &state.queue);

    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.queueFamilyIndex = state.queue_family_index;
    check(vkCreateCommandPool(state.device, &pool_info, nullptr, &state.command_pool), "vkCreateCommandPool");

    VkPipelineCacheCreateInfo cache_info{};
    cache_info.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
    check(vkCreatePipelineCache(state.device, &cache_info, nullptr, &state.pipeline_cache), "vkCreatePipelineCache");
}

}  // namespace

std::optional<VulkanContext> VulkanContext::create(const VulkanOptions& options, std::string* const error_message)
{
    try
    {
        auto state = std::make_shared<ContextState>();
        create_instance(*state, options);
        choose_physical_device(*state, options);
        create_device(*state);
        return VulkanContext(std::move(state));
    }
    catch (const std::exception& error)
    {
        // Callers (tests above all) decide whether a missing device is a failure or a skip,
        // so this reports instead of throwing.
        if (error_message != nullptr) *error_message = error.what();
        return std::nullopt;
    }
}

VulkanContext::VulkanContext(std::shared_ptr<ContextState> state) : state_(std::move(state)) {}
VulkanContext::VulkanContext(VulkanContext&&) noexcept = default;
VulkanContext& VulkanContext::operator=(VulkanContext&&) noexcept = default;
VulkanContext::~VulkanContext() = default;

std::string VulkanContext::device_name() const
{
    return std::string(state_->properties.deviceName) + " (" + device_type_name(state_->properties.deviceType) +
           ", Vulkan " + version_text(state_->properties.apiVersion) + ")";
}

bool VulkanContext::validation_enabled() const { return state_->validation_active; }

std::vector<std::string> VulkanContext::validation_messages() const
{
    const ValidationLog& log = state_->validation_log;
    const std::lock_guard<std::mutex> lock(log.mutex);
    std::vector<std::string> messages = log.messages;
    if (log.dropped_count > 0)
    {
        messages.push_back("warning: " + std::to_string(log.dropped_count) + " more validation messages were dropped");
    }
    return messages;
}

void VulkanContext::clear_validation_messages()
{
    ValidationLog& log = state_->validation_log;
    const std::lock_guard<std::mutex> lock(log.mutex);
    log.messages.clear();
    log.dropped_count = 0;
}

VkInstance VulkanContext::instance_handle() const { return state_->instance; }
VkPhysicalDevice VulkanContext::physical_device_handle() const { return state_->physical_device; }
VkDevice VulkanContext::device_handle() const { return state_->device; }
VkQueue VulkanContext::queue_handle() const { return state_->queue; }

// ----------------------------------------------------------------------------------------
// Pipeline

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

// ----------------------------------------------------------------------------------------
// Dispatch

namespace {

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

    ~RunResources()
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
};

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
    const ContextState& context = *pipeline_state.context;
    const VkDevice device = context.device;
    const VkPhysicalDeviceLimits& limits = context.properties.limits;

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

    DispatchTiming timing;
    timing.pipeline_create_ms = pipeline_state.create_ms;
    RunResources resources(context);

    // Upload: one buffer and one allocation per binding. Tests bind a handful of buffers,
    // so sub-allocation would be complexity without benefit.
    const Stopwatch upload_stopwatch;
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
    timing.upload_ms = upload_stopwatch.milliseconds();

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

    VkCommandBufferAllocateInfo command_info{};
    command_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    command_info.commandPool = context.command_pool;
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(device, &command_info, &resources.command_buffer), "vkAllocateCommandBuffers");

    // Recorded once and submitted `repeats` times: the steady-state measurement then
    // contains no recording cost, only submission, execution and the fence wait.
    const VkCommandBuffer commands = resources.command_buffer;
    VkCommandBufferBeginInfo begin_info{};
    begin_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
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

    const Stopwatch readback_stopwatch;
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

// ----------------------------------------------------------------------------------------
// Utilities

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

const char* vk_result_name(const VkResult result)
{
    switch (result)
    {
#define OPENPBR_VK_RESULT_CASE(name) \
    case name: return #name;
        OPENPBR_VK_RESULT_CASE(VK_SUCCESS)
        OPENPBR_VK_RESULT_CASE(VK_NOT_READY)
        OPENPBR_VK_RESULT_CASE(VK_TIMEOUT)
        OPENPBR_VK_RESULT_CASE(VK_EVENT_SET)
        OPENPBR_VK_RESULT_CASE(VK_EVENT_RESET)
        OPENPBR_VK_RESULT_CASE(VK_INCOMPLETE)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_DEVICE_LOST)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_UNKNOWN)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_FRAGMENTATION)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        OPENPBR_VK_RESULT_CASE(VK_PIPELINE_COMPILE_REQUIRED)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_SURFACE_LOST_KHR)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        OPENPBR_VK_RESULT_CASE(VK_SUBOPTIMAL_KHR)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
        OPENPBR_VK_RESULT_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef OPENPBR_VK_RESULT_CASE
    default: return "VK_RESULT_UNKNOWN_VALUE";
    }
}

}  // namespace openpbr::host
