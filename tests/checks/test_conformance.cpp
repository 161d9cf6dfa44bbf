// Conformance between the CPU build and every executed GPU path, at the tolerances of the
// foundation issue (max relative error 1e-3, 99.9th percentile 1e-5, lobe agreement 99.9 %).
#include <gtest/gtest.h>

#include "host/checks/conformance.h"
#include "host/scene/material_library.h"

namespace {

using openpbr::host::ConformanceOptions;
using openpbr::host::ConformanceReport;

// ctest runs every test in its own process, so each test computes only what it checks: the
// CPU batch alone, or the CPU batch and one path.
ConformanceReport run_paths(const std::vector<std::string>& paths)
{
    ConformanceOptions options;
    options.query_count = 20000;
    options.kernel_directory = OPENPBR_KERNEL_DIR;
    options.validation = true;
    options.paths = paths;
    const auto materials =
        openpbr::host::conformance_materials(openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR));
    return openpbr::host::run_conformance(materials, options);
}

TEST(Conformance, CpuOutputsAreFinite)
{
    // "cpu-only" names no path, so no GPU path runs.
    EXPECT_EQ(run_paths({"cpu-only"}).cpu_nonfinite, 0u);
}

class ConformancePath : public ::testing::TestWithParam<std::string>
{
};

TEST_P(ConformancePath, MatchesCpuBuild)
{
    const ConformanceReport result = run_paths({GetParam()});
    const auto found = std::find_if(result.paths.begin(), result.paths.end(),
                                    [](const auto& path) { return path.name == GetParam(); });
    ASSERT_NE(found, result.paths.end()) << "path missing from the report: " << GetParam();
    if (!found->executed)
    {
        GTEST_SKIP() << GetParam() << " not executed: " << found->note;
    }
    EXPECT_EQ(found->nonfinite, 0u);
    EXPECT_LE(found->max_relative_error, 1e-3) << found->worst_output;
    EXPECT_LE(found->p999_relative_error, 1e-5);
    EXPECT_LE(found->lobe_mismatch_fraction, 1e-3);
    EXPECT_EQ(found->validation_messages, 0u) << found->note;
}

INSTANTIATE_TEST_SUITE_P(AllPaths, ConformancePath,
                         ::testing::ValuesIn(openpbr::host::known_conformance_paths()),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
