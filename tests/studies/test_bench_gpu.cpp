// `openpbr bench gpu` (host/studies/bench_gpu.h) on the Vulkan device of this machine (lavapipe)
// with small sizes, over the material classes and over the feature variants (`--features`):
// every entry, pipeline and operation reports a positive, finite device time, the device is
// named as the driver names it, and the feature variants are those of benchmark_bsdf's table.
// The paths come from the execution-path interface: a texture-table path runs as well, a path
// that cannot run here is reported with its reason, an unknown name is refused.
// No timing thresholds: timings are measured, never asserted.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/gpu/vulkan_runner.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"
#include "host/studies/bench_gpu.h"
#include "host/studies/feature_variants.h"

namespace {

// Every entry of a report (material classes or feature variants), on both pipelines and in
// every mode, has a positive, finite device time on `path`: the median of its rounds.
void expect_positive_finite_rates(const nlohmann::json& report, const std::string& path)
{
    ASSERT_FALSE(report["classes"].empty());
    for (const nlohmann::json& entry : report["classes"])
    {
        const std::string label = entry.value("variant", entry["toggles"].get<std::string>());
        ASSERT_TRUE(entry["paths"].contains(path)) << label << ": " << entry.dump();
        for (const char* pipeline : {"full", "specialized"})
        {
            for (const char* operation : {"eval", "sample", "pdf"})
            {
                const nlohmann::json& rate = entry["paths"][path][pipeline][operation];
                ASSERT_TRUE(rate.contains("ns_per_query"))
                    << label << " " << pipeline << " " << operation << ": " << rate.dump();
                const double ns = rate["ns_per_query"].get<double>();
                EXPECT_TRUE(std::isfinite(ns) && ns > 0.0) << label << " " << pipeline << " " << operation;
                EXPECT_GT(rate["queries_per_second"].get<double>(), 0.0);
                // One median per round; the rate is the median of the rounds (of 3: the middle one).
                std::vector<double> rounds = rate["ns_per_round"].get<std::vector<double>>();
                ASSERT_EQ(rounds.size(), report["rounds"].get<std::size_t>()) << label << " " << pipeline;
                std::sort(rounds.begin(), rounds.end());
                EXPECT_EQ(ns, rounds[rounds.size() / 2]) << label << " " << pipeline;
            }
        }
    }
}

// A small bench over the bundled materials and built kernels: queries per entry, 2 repeats.
openpbr::host::GpuBenchOptions small_bench_options(std::size_t queries)
{
    openpbr::host::GpuBenchOptions options;
    options.materials_directory = OPENPBR_MATERIALS_DIR;
    options.kernel_directory = OPENPBR_KERNEL_DIR;
    options.queries = queries;
    options.repeats = 2;
    return options;
}

// The material classes (default) and the feature variants (`--features`).
class BenchGpuSet : public ::testing::TestWithParam<bool>
{
};

TEST_P(BenchGpuSet, ReportsPositiveFiniteDeviceTimes)
{
    std::string error;
    const auto context = openpbr::host::VulkanContext::create({}, &error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    openpbr::host::GpuBenchOptions options = small_bench_options(256);
    options.paths = {"slang-spirv"};  // the CUDA program has its own check (targets_cuda_nvcc)
    options.features = GetParam();
    options.rounds = options.features ? 3 : 1;  // both the single pass and the median of several
    const nlohmann::json report = openpbr::host::run_gpu_bench(options);
    ASSERT_EQ(report["paths"].size(), 1u);
    EXPECT_EQ(report["paths"][0]["name"].get<std::string>(), "slang-spirv");
    EXPECT_EQ(report["paths"][0]["device"].get<std::string>(), context->device_name());
    EXPECT_EQ(report["set"].get<std::string>(), options.features ? "features" : "material classes");
    expect_positive_finite_rates(report, "slang-spirv");
    EXPECT_FALSE(openpbr::host::gpu_bench_text(report).empty());
    if (!options.features)
    {
        return;
    }
    // One entry per variant of host/studies/feature_variants.h, in its order, each a single
    // material specialized to the toggles it needs.
    const std::vector<openpbr::host::FeatureVariant> variants = openpbr::host::feature_variants();
    ASSERT_EQ(report["classes"].size(), variants.size());
    for (std::size_t v = 0; v < variants.size(); ++v)
    {
        const nlohmann::json& entry = report["classes"][v];
        EXPECT_EQ(entry["variant"].get<std::string>(), variants[v].name);
        EXPECT_EQ(entry["materials"], nlohmann::json::array({variants[v].name}));
        EXPECT_EQ(entry["toggles"].get<std::string>(),
                  openpbr::host::feature_set_label(openpbr::host::required_feature_mask(variants[v].inputs)));
    }
    // Per feature: alone = Only/<feature> - Default, saved = EveryLobe - Without/<feature>.
    auto ns = [&](const std::string& variant, const char* pipeline, const char* operation) {
        for (const nlohmann::json& entry : report["classes"])
        {
            if (entry["variant"] == variant)
            {
                return entry["paths"]["slang-spirv"][pipeline][operation]["ns_per_query"].get<double>();
            }
        }
        ADD_FAILURE() << "no variant " << variant;
        return 0.0;
    };
    for (const openpbr::host::CostFeature& feature : openpbr::host::cost_features())
    {
        for (const char* pipeline : {"full", "specialized"})
        {
            for (const char* operation : {"eval", "sample", "pdf"})
            {
                const nlohmann::json& cell = report["feature_costs"]["slang-spirv"][feature.name][pipeline][operation];
                ASSERT_TRUE(cell.contains("alone_ns") && cell.contains("saved_ns"))
                    << feature.name << " " << pipeline << " " << operation << ": " << cell.dump();
                EXPECT_DOUBLE_EQ(cell["alone_ns"].get<double>(),
                                 ns(std::string("Only/") + feature.name, pipeline, operation) -
                                     ns("Default", pipeline, operation));
                EXPECT_DOUBLE_EQ(cell["saved_ns"].get<double>(),
                                 ns("EveryLobe", pipeline, operation) -
                                     ns(std::string("Without/") + feature.name, pipeline, operation));
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(BenchGpu, BenchGpuSet, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                             return info.param ? std::string("Features") : std::string("MaterialClasses");
                         });

// Through the execution-path interface, a path whose tables are sampled images times as a
// buffer path does (before, the bench bound no tables for it), and each path of a report is
// either timed on its device or reported with the reason it cannot run here: the CUDA paths,
// built or not, have no specialized kernel, which the report says instead of timing the full
// one under that name. --entries keeps the entries named, in report order. An unknown path or
// entry and a CPU path (no device time) are refused.
TEST(BenchGpu, EveryPathIsTimedOrReportedWithItsReason)
{
    std::string error;
    const auto context = openpbr::host::VulkanContext::create({}, &error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    openpbr::host::GpuBenchOptions options = small_bench_options(128);
    options.paths = {"slang-spirv-texture", "cuda"};
    options.entries = {"metal", "base"};  // report order: base first
    const nlohmann::json report = openpbr::host::run_gpu_bench(options);
    ASSERT_EQ(report["classes"].size(), 2u);
    EXPECT_EQ(report["classes"][0]["toggles"].get<std::string>(), "base");
    EXPECT_EQ(report["classes"][1]["toggles"].get<std::string>(), "metal");
    ASSERT_EQ(report["paths"].size(), 2u);
    EXPECT_EQ(report["paths"][0]["device"].get<std::string>(), context->device_name());
    expect_positive_finite_rates(report, "slang-spirv-texture");
    const nlohmann::json& cuda = report["paths"][1];
    EXPECT_EQ(cuda["name"].get<std::string>(), "cuda");
    if (cuda.contains("skipped"))
    {
        EXPECT_FALSE(cuda["skipped"].get<std::string>().empty());
        for (const nlohmann::json& entry : report["classes"])
        {
            EXPECT_FALSE(entry["paths"].contains("cuda")) << entry.dump();
        }
    }
    else
    {
        EXPECT_NE(cuda["specialized_skipped"].get<std::string>().find("every toggle on"), std::string::npos);
    }
    EXPECT_NE(openpbr::host::gpu_bench_text(report).find("cuda device: "), std::string::npos);
    options.entries = {"no-such-entry"};
    EXPECT_THROW(openpbr::host::run_gpu_bench(options), std::invalid_argument);
    options.entries.clear();
    options.paths = {"no-such-path"};
    EXPECT_THROW(openpbr::host::run_gpu_bench(options), std::invalid_argument);
    options.paths = {"cpu-fma"};  // no device time to report
    EXPECT_THROW(openpbr::host::run_gpu_bench(options), std::invalid_argument);
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
