// Conformance between the CPU build and every executed GPU path, at the tolerances of the
// foundation issue (max relative error 1e-3, 99.9th percentile 1e-5, lobe agreement 99.9 %).
#include <gtest/gtest.h>

#include "host/conformance.h"
#include "host/material_library.h"

namespace {

using openpbr::host::ConformanceOptions;
using openpbr::host::ConformanceReport;

const ConformanceReport& report()
{
    static const ConformanceReport cached = [] {
        ConformanceOptions options;
        options.query_count = 20000;
        options.kernel_directory = OPENPBR_KERNEL_DIR;
        options.validation = true;
        const auto materials = openpbr::host::conformance_materials(
            openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR));
        return openpbr::host::run_conformance(materials, options);
    }();
    return cached;
}

TEST(Conformance, CpuOutputsAreFinite) { EXPECT_EQ(report().cpu_nonfinite, 0u); }

class ConformancePath : public ::testing::TestWithParam<std::string>
{
};

TEST_P(ConformancePath, MatchesCpuBuild)
{
    const ConformanceReport& result = report();
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
