// vulkan_context.cpp - the Vulkan compute runner's instance and device (see vulkan_runner.h).
#include <algorithm>
#include <atomic>
#include <cctype>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "host/gpu/vulkan_runner.h"
#include "host/gpu/vulkan_runner_internal.h"

namespace openpbr::host {

using namespace vulkan_internal;

namespace {

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
