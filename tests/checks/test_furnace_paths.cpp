// The white furnace on every GPU path (issue: the furnace targets hold on the CPU and every
// executed GPU path): `openpbr furnace --paths` runs the configurations through the conformance
// kernel (host/checks/furnace.h). Rows: the sweep's rough glass of relative IOR 1, 1.001, 1.01,
// 1.05, 1.2 and 1.5 (the configurations named sweep_glass_eta1*: the index-matched limit and the
// grazing rows the tables' view axis resolves), roughness 0.05-1, both sides (from inside the
// relative IOR is below 1), view cos 1-0.001, 2^15 samples each: 240 rows per path, one pipeline. Each GPU row must be
// within its configuration's band (3 standard errors, as on the CPU) and agree with the CPU row within 5 combined standard
// errors plus 1e-4 (the two use different random streams; the conformance batch has the same queries agree to 7.3e-6
// relative on lavapipe). A path without a device is skipped with the reason. The same for 51 rows
// of the filmed grid (film_subset below), and those rows on the CPU at 2^16 samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/checks/furnace.h"

namespace {

using openpbr::host::FurnaceOptions;
using openpbr::host::FurnaceRow;

class FurnacePath : public ::testing::TestWithParam<std::string>
{
};

// The filmed grid's subset (host/checks/furnace.h, film_furnace_configs): every axis' ends
// (films of IOR 1.2 and 2, 0.1 and 1.5 um; no coat and a coat of weight 1 and IOR 1.8; air and
// water; the diffuse, metal and glass bases; roughness 0.1 and 0.8 and view cos 1 and 0.1 in each),
// the rows where the estimate before it failed worst (a coat of IOR 1.8 over a film of 0.9 um lost
// 13.6 %, a film of 0.6 um under a coat of IOR 1.6 gained 9.6 % with a quadrature in c; a film
// of 1.2 um under a half coat of IOR 1.3 lost 4 % with two halves at cos 0.1), the grid's worst
// row without table 5's tail nodes (film 1.4 of 1.5 um under a half coat of IOR 1.8 in water at
// cos 0.5: 1.0125), and the last rows outside the band without the upper tail on its own
// (film 2 of 0.6 um under a coat of IOR 1.6 in water, roughness 0.8: 1.0060 at cos 0.1; film 1.2
// of 0.9 um under a half coat of IOR 1.3 in air over glass, roughness 0.1: 1.0054 at cos 0.1): 57
// rows.
const std::vector<std::string>& film_subset()
{
    static const std::vector<std::string> filters = {"film_diffuse_nocoat_air_n1p2_d0p1",
                                                     "film_metal_coat1_ior1p8_water_n2_d1p5",
                                                     "film_glass_coat0p5_ior1p3_air_n1p4_d0p6",
                                                     "film_diffuse_coat1_ior1p8_air_n1p4_d0p9",
                                                     "film_diffuse_coat1_ior1p6_air_n1p4_d0p6",
                                                     "film_diffuse_coat0p5_ior1p3_air_n1p2_d1p2_r0p4",
                                                     "film_diffuse_coat0p5_ior1p8_water_n1p4_d1p5_r0p1",
                                                     "film_diffuse_coat1_ior1p6_water_n2_d0p6_r0p8",
                                                     "film_glass_coat0p5_ior1p3_air_n1p2_d0p9_r0p1"};
    return filters;
}

// On the CPU build at 2^16 samples (docs/thin-film-estimate.md's first grid runs): every
// row within its band (3 standard errors).
TEST(FilmFurnace, SubsetWithinItsBandsOnTheCpu)
{
    FurnaceOptions options;
    options.samples = 1u << 16;
    options.film_grid = true;
    options.name_filters = film_subset();
    std::vector<std::string> skipped;
    const std::vector<FurnaceRow> rows = openpbr::host::run_white_furnace(options, &skipped);
    EXPECT_EQ(rows.size(), 5u * 9u + 4u * 3u);  // five filters hold 3 roughnesses x 3 views, four one roughness
    for (const FurnaceRow& row : rows)
    {
        EXPECT_TRUE(row.within_tolerance) << row.name << " at cos " << row.cos_theta << ": " << row.estimate.albedo[0]
                                          << " / " << row.estimate.albedo[1] << " / " << row.estimate.albedo[2] << " +- "
                                          << row.estimate.standard_error[0];
    }
}

TEST_P(FurnacePath, RowsWithinTheirBandsAndAgreeWithTheCpu)
{
    std::size_t compared = 0;
    for (const bool film_grid : {false, true})
    {
        FurnaceOptions options;
        options.samples = 1u << 15;
        options.film_grid = film_grid;
        if (film_grid)
        {
            options.name_filters = film_subset();
        }
        else
        {
            options.name_filter = "sweep_glass_eta1";
        }
        const std::string filter = film_grid ? "the filmed subset" : options.name_filter;
        options.paths = {"cpu", GetParam()};
        options.kernel_directory = OPENPBR_KERNEL_DIR;
        std::vector<std::string> skipped;
        const std::vector<FurnaceRow> rows = openpbr::host::run_white_furnace(options, &skipped);
        if (!skipped.empty())
        {
            GTEST_SKIP() << skipped.front();
        }
        std::map<std::pair<std::string, float>, const FurnaceRow*> cpu_rows;
        for (const FurnaceRow& row : rows)
        {
            if (row.path == "cpu")
            {
                cpu_rows[{row.name, row.cos_theta}] = &row;
            }
        }
        ASSERT_FALSE(cpu_rows.empty()) << filter;
        std::size_t gpu_row_count = 0;
        for (const FurnaceRow& row : rows)
        {
            if (row.path == "cpu")
            {
                continue;
            }
            ++gpu_row_count;
            EXPECT_TRUE(row.within_tolerance) << row.path << ": " << row.name << " at cos " << row.cos_theta << ": "
                                              << row.estimate.albedo[0] << " +- " << row.estimate.standard_error[0];
            const FurnaceRow& cpu = *cpu_rows.at({row.name, row.cos_theta});
            for (int channel = 0; channel < 3; ++channel)
            {
                const double combined =
                    std::hypot(row.estimate.standard_error[channel], cpu.estimate.standard_error[channel]);
                EXPECT_NEAR(row.estimate.albedo[channel], cpu.estimate.albedo[channel], 5.0 * combined + 1e-4)
                    << row.path << ": " << row.name << " at cos " << row.cos_theta << ", channel " << channel;
            }
            ++compared;
        }
        EXPECT_EQ(gpu_row_count, cpu_rows.size()) << filter;
    }
    EXPECT_GT(compared, 0u);
}

// Every GPU path but the WebGPU ones: 240 rows of 2^15 samples are 7.9M queries, minutes on
// SwiftShader (20-50 us per query on the loaded 2-core CI machine) where lavapipe takes seconds;
// `openpbr furnace --paths slang-wgsl` runs them through the same mechanism, and the WebGPU
// paths' CI checks are conformance and the stability corpus.
std::vector<std::string> gpu_paths()
{
    std::vector<std::string> paths;
    for (const std::string& name : openpbr::host::known_conformance_paths())
    {
        if (!openpbr::host::execution_path_has_wgsl_math(name))
        {
            paths.push_back(name);
        }
    }
    return paths;
}

INSTANTIATE_TEST_SUITE_P(AllGpuPaths, FurnacePath, ::testing::ValuesIn(gpu_paths()), [](const auto& info) {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
});

}  // namespace
