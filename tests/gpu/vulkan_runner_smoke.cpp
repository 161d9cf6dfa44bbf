// vulkan_runner_smoke.cpp - standalone smoke test of host/vulkan_runner.
//
// Usage: vulkan_runner_smoke [path/to/vulkan_runner_smoke.comp]
//   Without an argument the shader is looked up at VULKAN_RUNNER_SMOKE_SHADER (a compile
//   definition the build may set) or next to this source file (tests/data/).
// Exit status: 0 passed, 1 failed, 77 skipped because no Vulkan device exists (the
// "skipped" code of automake and of ctest's SKIP_RETURN_CODE).
// Environment: OPENPBR_VULKAN_DEVICE_FILTER selects a device by name (e.g. "llvmpipe");
// MESA_SHADER_CACHE_DIR is set to a temporary directory unless the caller set it.
// Needs glslangValidator on PATH and the Khronos validation layer.

#include "host/gpu/vulkan_runner.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace openpbr::host;

int failure_count = 0;

void expect(const bool condition, const std::string& what)
{
    if (!condition)
    {
        ++failure_count;
        std::cout << "FAIL: " << what << "\n";
    }
}

template <class Function>
void expect_throws(Function&& function, const std::string& expected_fragment, const std::string& what)
{
    try
    {
        function();
    }
    catch (const std::runtime_error& error)
    {
        const std::string message = error.what();
        expect(message.find(expected_fragment) != std::string::npos,
               what + ": message '" + message + "' lacks '" + expected_fragment + "'");
        return;
    }
    expect(false, what + ": no exception thrown");
}

fs::path default_shader_path()
{
#ifdef VULKAN_RUNNER_SMOKE_SHADER
    return fs::path(VULKAN_RUNNER_SMOKE_SHADER);
#else
    return fs::path(__FILE__).parent_path() / "data" / "vulkan_runner_smoke.comp";
#endif
}

std::optional<fs::path> find_on_path(const std::string& program)
{
    const char* const path_variable = std::getenv("PATH");
    if (path_variable == nullptr) return std::nullopt;
    std::stringstream directories(path_variable);
    std::string directory;
    while (std::getline(directories, directory, ':'))
    {
        if (directory.empty()) continue;
        const fs::path candidate = fs::path(directory) / program;
        if (access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return std::nullopt;
}

// Single-quotes a path for /bin/sh, because std::system goes through the shell.
std::string shell_quote(const std::string& text)
{
    std::string quoted = "'";
    for (const char c : text) quoted += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

void write_file(const fs::path& path, const std::vector<unsigned char>& bytes)
{
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void check_spirv_loading(const fs::path& scratch)
{
    const fs::path missing = scratch / "missing.spv";
    expect_throws([&] { load_spirv_file(missing.string()); }, missing.string(),
                  "load_spirv_file of a missing file names the path");
    const fs::path odd_size = scratch / "odd_size.spv";
    write_file(odd_size, {0x03, 0x02, 0x23, 0x07, 0x00, 0x00});
    expect_throws([&] { load_spirv_file(odd_size.string()); }, "multiple of 4",
                  "load_spirv_file rejects a size that is not a multiple of 4");
    const fs::path bad_magic = scratch / "bad_magic.spv";
    write_file(bad_magic, std::vector<unsigned char>(20, 0xab));
    expect_throws([&] { load_spirv_file(bad_magic.string()); }, "magic", "load_spirv_file rejects a bad magic number");
}

std::vector<std::byte> uint_bytes(const uint32_t value)
{
    // A std140 block holding one uint is 16 bytes; the tail stays zero.
    std::vector<uint32_t> words = {value, 0, 0, 0};
    return to_bytes(words);
}

void print_timing(const std::string& label, const DispatchTiming& timing)
{
    std::printf("%-28s create %.3f ms, first dispatch %.3f ms, dispatch (median of %d) %.3f ms", label.c_str(),
                timing.pipeline_create_ms, timing.first_dispatch_ms,
                timing.dispatch_count > 1 ? timing.dispatch_count - 1 : 1, timing.dispatch_ms);
    if (timing.device_dispatch_ms) std::printf(", device %.3f ms", *timing.device_dispatch_ms);
    std::printf(", upload %.3f ms, readback %.3f ms\n", timing.upload_ms, timing.readback_ms);
}

// Runs the kernel over `element_count` values and compares every result bit for bit.
// The inputs are multiples of 0.5 and the multipliers exact binary fractions, so every
// product and sum is exact in float: fused multiply-add or not, there is one right answer.
void check_kernel(const VulkanContext& context, const std::vector<uint32_t>& spirv, const std::string& label,
                  const uint32_t element_count, const float multiplier, const bool add_index, const uint32_t workgroup_size,
                  const float bias, const int repeats)
{
    std::vector<float> source(element_count);
    for (uint32_t index = 0; index < element_count; ++index)
    {
        source[index] = static_cast<float>(index % 97) * 0.5f - 7.0f;
    }
    std::vector<std::byte> source_bytes = to_bytes(source);
    const std::vector<std::byte> original_source_bytes = source_bytes;
    // Filled with a pattern so that an element the shader failed to write shows up.
    std::vector<std::byte> result_bytes = to_bytes(std::vector<float>(element_count, -12345.0f));
    std::vector<std::byte> parameter_bytes = uint_bytes(element_count);

    const std::vector<BufferBinding> buffers = {
        {0, &source_bytes, /*read_back=*/true, /*uniform=*/false},
        {1, &result_bytes, /*read_back=*/true, /*uniform=*/false},
        {2, &parameter_bytes, /*read_back=*/false, /*uniform=*/true},
    };
    ComputePipelineDescription description;
    description.spirv_words = spirv;
    description.specialization_constants = {SpecializationConstant::of_float(0, multiplier),
                                            SpecializationConstant::of_uint(1, workgroup_size),
                                            SpecializationConstant::of_bool(2, add_index)};
    description.bindings = binding_layouts_of(buffers);
    description.push_constant_size = sizeof(float);
    ComputePipeline pipeline(context, description);

    DispatchRequest request;
    request.groups_x = std::max<uint32_t>(1, (element_count + workgroup_size - 1) / workgroup_size);
    request.repeats = repeats;
    request.push_constants = to_bytes(std::vector<float>{bias});
    const DispatchTiming timing = run(pipeline, buffers, request);
    print_timing(label, timing);

    const std::vector<float> results = from_bytes<float>(result_bytes);
    expect(results.size() == element_count, label + ": result size changed");
    int mismatches = 0;
    for (uint32_t index = 0; index < element_count && index < results.size(); ++index)
    {
        float expected = source[index] * multiplier + bias;
        if (add_index) expected += static_cast<float>(index);
        if (std::memcmp(&expected, &results[index], sizeof(float)) != 0 && ++mismatches <= 5)
        {
            expect(false, label + ": result[" + std::to_string(index) + "] = " + std::to_string(results[index]) +
                              ", expected " + std::to_string(expected));
        }
    }
    expect(mismatches == 0, label + ": " + std::to_string(mismatches) + " mismatching results");
    // Read back although the shader only reads it: proves the copy-back leaves it intact.
    expect(source_bytes == original_source_bytes, label + ": read-only source buffer changed");
    expect(timing.dispatch_count == repeats, label + ": dispatch count");
}

void check_error_handling(const VulkanContext& context, const std::vector<uint32_t>& spirv)
{
    std::vector<std::byte> empty;
    std::vector<std::byte> parameters = uint_bytes(0);
    std::vector<BufferBinding> buffers = {
        {0, &empty, false, false}, {1, &empty, true, false}, {2, &parameters, false, true}};
    ComputePipelineDescription description;
    description.spirv_words = spirv;
    description.bindings = binding_layouts_of(buffers);
    description.push_constant_size = sizeof(float);
    ComputePipeline pipeline(context, description);

    DispatchRequest request;
    request.push_constants = to_bytes(std::vector<float>{0.0f});
    const std::vector<BufferBinding> missing_binding(buffers.begin(), buffers.begin() + 2);
    expect_throws([&] { run(pipeline, missing_binding, request); }, "do not match", "run rejects a missing binding");
    std::vector<BufferBinding> wrong_kind = buffers;
    wrong_kind[2].uniform = false;
    expect_throws([&] { run(pipeline, wrong_kind, request); }, "do not match",
                  "run rejects a storage buffer where the layout has a uniform buffer");
    std::vector<BufferBinding> doubled = buffers;
    doubled.push_back(buffers[1]);
    expect_throws([&] { run(pipeline, doubled, request); }, "do not match", "run rejects two buffers at one binding");
    expect_throws([&] { run(pipeline, buffers, 1); }, "push constant", "run rejects missing push constants");
    DispatchRequest no_groups = request;
    no_groups.groups_x = 0;
    expect_throws([&] { run(pipeline, buffers, no_groups); }, "group count", "run rejects zero groups");
    DispatchRequest no_repeats = request;
    no_repeats.repeats = 0;
    expect_throws([&] { run(pipeline, buffers, no_repeats); }, "repeats", "run rejects zero repeats");
    // After all those refusals the pipeline still works.
    expect(run(pipeline, buffers, request).dispatch_count == 1, "pipeline usable after errors");

    ComputePipelineDescription duplicate = description;
    duplicate.bindings.push_back({1, false});
    expect_throws([&] { ComputePipeline rejected(context, duplicate); }, "listed twice",
                  "pipeline rejects a binding listed twice");
    ComputePipelineDescription not_spirv = description;
    not_spirv.spirv_words = {1, 2, 3, 4, 5};
    expect_throws([&] { ComputePipeline rejected(context, not_spirv); }, "magic",
                  "pipeline rejects words that are not SPIR-V");
}

// Provokes one deliberate validation error, so that "no messages" later means "no
// problems" and not "the messenger is deaf".
void check_messenger_hears(VulkanContext& context)
{
    VkBufferCreateInfo invalid{};
    invalid.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    invalid.size = 16;
    invalid.usage = 0;  // VUID-VkBufferCreateInfo-usage-requiredbitmask
    invalid.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(context.device_handle(), &invalid, nullptr, &buffer) == VK_SUCCESS)
    {
        vkDestroyBuffer(context.device_handle(), buffer, nullptr);
    }
    const std::vector<std::string> messages = context.validation_messages();
    expect(!messages.empty() && messages.front().rfind("error: ", 0) == 0,
           "validation messenger reports a deliberate error");
    context.clear_validation_messages();
    expect(context.validation_messages().empty(), "clear_validation_messages empties the log");
}

}  // namespace

int main(int argc, char** argv)
{
    const fs::path shader_source = argc > 1 ? fs::path(argv[1]) : default_shader_path();
    const fs::path scratch = fs::temp_directory_path() / ("vulkan_runner_smoke_" + std::to_string(getpid()));
    std::error_code ignored;
    fs::create_directories(scratch, ignored);

    // Mesa reads this when the device is created. A directory that does not exist disables
    // the cache silently, so it is created here; a caller's own choice is left alone.
    if (std::getenv("MESA_SHADER_CACHE_DIR") == nullptr)
    {
        const fs::path cache = fs::temp_directory_path() / "openpbr-mesa-shader-cache";
        fs::create_directories(cache, ignored);
        setenv("MESA_SHADER_CACHE_DIR", cache.c_str(), 0);
    }
    std::cout << "MESA_SHADER_CACHE_DIR=" << std::getenv("MESA_SHADER_CACHE_DIR") << "\n";

    int status = 0;
    try
    {
        check_spirv_loading(scratch);

        const std::optional<fs::path> compiler = find_on_path("glslangValidator");
        if (!compiler) throw std::runtime_error("glslangValidator not found on PATH (install glslang-tools)");
        const fs::path spirv_path = scratch / "vulkan_runner_smoke.spv";
        const std::string command = shell_quote(compiler->string()) + " -V --quiet " + shell_quote(shader_source.string()) +
                                    " -o " + shell_quote(spirv_path.string());
        if (std::system(command.c_str()) != 0) throw std::runtime_error("shader compilation failed: " + command);
        const std::vector<uint32_t> spirv = load_spirv_file(spirv_path.string());

        VulkanOptions options;
        options.enable_validation = true;
        if (const char* const filter = std::getenv("OPENPBR_VULKAN_DEVICE_FILTER"))
        {
            options.device_name_filter = filter;
        }
        std::string error_message;
        std::optional<VulkanContext> context = VulkanContext::create(options, &error_message);
        if (!context)
        {
            std::cout << "SKIPPED: no Vulkan device: " << error_message << "\n";
            fs::remove_all(scratch, ignored);
            return 77;
        }
        std::cout << "device: " << context->device_name() << "\n";
        if (!context->validation_enabled())
        {
            throw std::runtime_error("validation layer unavailable (install vulkan-validationlayers)");
        }
        check_messenger_hears(*context);

        check_kernel(*context, spirv, "1000 x (in*2.5 + i):", 1000, 2.5f, true, 64, 0.0f, 10);
        check_kernel(*context, spirv, "999 x (in*-3 + 0.5):", 999, -3.0f, false, 32, 0.5f, 3);
        check_kernel(*context, spirv, "1 x single repeat:", 1, 2.5f, true, 64, 0.0f, 1);
        check_kernel(*context, spirv, "empty buffers:", 0, 2.5f, true, 64, 0.0f, 1);
        check_kernel(*context, spirv, "1M x (in*0.25 + i):", 1 << 20, 0.25f, true, 256, 0.0f, 5);
        check_error_handling(*context, spirv);

        const std::vector<std::string> messages = context->validation_messages();
        for (const std::string& message : messages) std::cout << "validation " << message << "\n";
        expect(messages.empty(), std::to_string(messages.size()) + " validation messages");
    }
    catch (const std::exception& error)
    {
        std::cout << "FAIL: " << error.what() << "\n";
        ++failure_count;
    }
    fs::remove_all(scratch, ignored);

    status = failure_count == 0 ? 0 : 1;
    std::cout << (status == 0 ? "PASSED" : "FAILED (" + std::to_string(failure_count) + " failures)") << "\n";
    return status;
}
