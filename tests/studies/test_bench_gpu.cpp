// `openpbr bench gpu` (host/studies/bench_gpu.h) on the Vulkan device of this machine (lavapipe)
// with small sizes: every class, pipeline and operation reports a positive, finite device time
// and the device is named as the driver names it. No timing thresholds: timings are measured,
// never asserted.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "host/checks/conformance.h"
#include "host/gpu/vulkan_runner.h"
#include "host/scene/material_library.h"
#include "host/studies/bench_gpu.h"

namespace {

TEST(BenchGpu, ReportsPositiveFiniteDeviceTimes)
{
    std::string error;
    const auto context = openpbr::host::VulkanContext::create({}, &error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    openpbr::host::GpuBenchOptions options;
    options.materials_directory = OPENPBR_MATERIALS_DIR;
    options.kernel_directory = OPENPBR_KERNEL_DIR;
    options.queries = 256;
    options.repeats = 2;
    options.cuda = false;  // the CUDA program has its own check (targets_cuda_nvcc)
    const nlohmann::json report = openpbr::host::run_gpu_bench(options);
    EXPECT_EQ(report["vulkan_device"].get<std::string>(), context->device_name());
    ASSERT_FALSE(report["classes"].empty());
    for (const nlohmann::json& entry : report["classes"])
    {
        for (const char* pipeline : {"full", "specialized"})
        {
            for (const char* operation : {"eval", "sample", "pdf"})
            {
                const nlohmann::json& rate = entry["vulkan"][pipeline][operation];
                ASSERT_TRUE(rate.contains("ns_per_query"))
                    << entry["toggles"] << " " << pipeline << " " << operation << ": " << rate.dump();
                const double ns = rate["ns_per_query"].get<double>();
                EXPECT_TRUE(std::isfinite(ns) && ns > 0.0) << entry["toggles"] << " " << pipeline << " " << operation;
                EXPECT_GT(rate["queries_per_second"].get<double>(), 0.0);
            }
        }
    }
    EXPECT_FALSE(openpbr::host::gpu_bench_text(report).empty());
}

// The device-local buffers (staging copies in and out) give the same results as host-visible
// ones, and each mode writes exactly its own operation's slots of the full run.
TEST(BenchGpu, DeviceLocalBuffersAndModesMatchTheFullKernel)
{
    std::string error;
    auto context = openpbr::host::VulkanContext::create({}, &error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    const auto materials =
        openpbr::host::conformance_materials(openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR));
    const std::vector<float> packed = openpbr::host::pack_materials(materials);
    const std::vector<float> queries = openpbr::host::make_queries(512, materials.size(), 3);
    openpbr::host::ComputePipeline pipeline(
        *context, openpbr::host::conformance_pipeline_description("slang-spirv", OPENPBR_KERNEL_DIR));
    const std::vector<float> host_visible =
        openpbr::host::dispatch_conformance_pipeline(pipeline, queries, packed, 1, {}).results;
    const std::vector<float> device_local =
        openpbr::host::dispatch_conformance_pipeline(pipeline, queries, packed, 1, {0u, true}).results;
    // OPENPBR_RESULT_FLOATS of targets/kernels/openpbr_conformance_kernel.h.
    constexpr std::size_t result_floats = 24;
    ASSERT_EQ(host_visible.size(), 512 * result_floats);
    EXPECT_EQ(host_visible, device_local);
    // Slots written per mode (targets/kernels/openpbr_conformance_kernel.h).
    const std::vector<std::pair<std::uint32_t, std::vector<int>>> modes = {
        {1u, {0, 1, 2, 3, 4, 5, 18, 19, 20}}, {2u, {7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17}}, {3u, {6}}};
    for (const auto& [mode, slots] : modes)
    {
        const std::vector<float> results =
            openpbr::host::dispatch_conformance_pipeline(pipeline, queries, packed, 1, {mode, true}).results;
        for (std::size_t query = 0; query < 512; ++query)
        {
            for (int slot = 0; slot < int(result_floats); ++slot)
            {
                const bool written = std::find(slots.begin(), slots.end(), slot) != slots.end();
                const float expected = written ? host_visible[query * result_floats + std::size_t(slot)] : 0.0f;
                ASSERT_EQ(results[query * result_floats + std::size_t(slot)], expected)
                    << "mode " << mode << ", query " << query << ", slot " << slot;
            }
        }
    }
}

}  // namespace
