// The hard-case corpus (tests/data/stability_corpus.json) on every GPU path: what
// stability_expectations.h asks of every path (no non-finite or negative output, no energy
// gain). Each path is its own test so that ctest, which runs every test in its own process,
// computes each path once: GPU paths (lavapipe on machines without a GPU) with 10000 samples per
// case, a prefix of the CPU build's query stream (lavapipe runs at about 1M queries/s on two
// cores). The CPU build and the corpus reader are test_stability_cpu.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/checks/stability.h"
#include "tests/checks/stability_expectations.h"

namespace {

using openpbr::host::StabilityOptions;
using openpbr::host::StabilityPathResult;
using openpbr::host::StabilityReport;
using openpbr::host::stability_tests::corpus;

constexpr std::size_t gpu_samples_per_case = 10000;
// The WebGPU paths (SwiftShader in CI) take fewer: 2000 per case keeps the corpus (187 cases,
// about 0.37M queries) inside one batch of the stability runner (1.3M queries), so one Node
// process and one pipeline build (SwiftShader: 40-65 s on the loaded 2-core machine, where
// the dispatch itself ran at 20-50 us per query). The energy check's three standard errors
// scale with the sample count, so the check stays as strict in what it can assert.
constexpr std::size_t webgpu_samples_per_case = 2000;

// run_stability composes the CPU build (run_stability_cpu) with the GPU paths: asked for the
// CPU alone, it gives run_stability_cpu's report (the same query stream, bit for bit).
TEST(Stability, CpuPathThroughEveryPathRunnerIsTheCpuRunners)
{
    StabilityOptions options;
    options.samples_per_case = 100;
    options.paths = {"cpu"};
    const StabilityReport through_paths = openpbr::host::run_stability(corpus(), options);
    const StabilityReport cpu_only = openpbr::host::run_stability_cpu(corpus(), options);
    ASSERT_EQ(through_paths.paths.size(), 1u);
    ASSERT_EQ(cpu_only.paths.size(), 1u);
    ASSERT_EQ(through_paths.paths[0].cases.size(), cpu_only.paths[0].cases.size());
    for (std::size_t c = 0; c < cpu_only.paths[0].cases.size(); ++c)
    {
        for (int channel = 0; channel < 3; ++channel)
        {
            EXPECT_EQ(through_paths.paths[0].cases[c].mean_weight[channel], cpu_only.paths[0].cases[c].mean_weight[channel])
                << cpu_only.paths[0].cases[c].name;
        }
    }
    EXPECT_EQ(through_paths.volumes.size(), cpu_only.volumes.size());
    options.paths = {"no-such-path"};
    EXPECT_THROW(openpbr::host::run_stability(corpus(), options), std::invalid_argument);
}

class StabilityPath : public ::testing::TestWithParam<std::string>
{
};

TEST_P(StabilityPath, FiniteNonNegativeAndNoEnergyGain)
{
    StabilityOptions options;
    options.samples_per_case =
        openpbr::host::execution_path_has_wgsl_math(GetParam()) ? webgpu_samples_per_case : gpu_samples_per_case;
    options.kernel_directory = OPENPBR_KERNEL_DIR;
    options.paths = {GetParam()};
    options.validation = true;
    const StabilityReport report = openpbr::host::run_stability(corpus(), options);
    ASSERT_EQ(report.paths.size(), 1u);
    const StabilityPathResult& path = report.paths[0];
    if (!path.executed)
    {
        // As in test_conformance: where SwiftShader is installed a WebGPU path must run.
        ASSERT_FALSE(openpbr::host::execution_path_has_wgsl_math(GetParam()) &&
                     std::filesystem::exists(openpbr::host::swiftshader_vulkan_driver()))
            << GetParam() << " not executed although SwiftShader is installed: " << path.note;
        GTEST_SKIP() << GetParam() << " not executed: " << path.note;
    }
    openpbr::host::stability_tests::expect_stable(path);
}

INSTANTIATE_TEST_SUITE_P(AllPaths, StabilityPath, ::testing::ValuesIn(openpbr::host::known_conformance_paths()),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
