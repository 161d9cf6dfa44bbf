// The material fits of examples/fit/ (host/gradients/material_fit.h) in a quick mode: fewer
// measurements than the cases' own (`openpbr fit examples/fit/*.json` runs them in full), the
// cases' starts, iterations and tolerances. Each fitted component must end within its case's
// tolerance of the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "host/gradients/material_fit.h"

namespace openpbr::test {
namespace {

// Quick mode: 8 views of 32 lights (256 measurements) instead of 32 of 64.
constexpr std::size_t quick_views = 8;
constexpr std::size_t quick_lights_per_view = 32;

class MaterialFit : public ::testing::TestWithParam<const char*>
{
};

TEST_P(MaterialFit, RecoversTheParametersWithinTheirTolerances)
{
    host::FitCase fit_case = host::load_fit_case(std::string(OPENPBR_SOURCE_DIR) + "/examples/fit/" + GetParam() + ".json");
    fit_case.views = quick_views;
    fit_case.lights_per_view = quick_lights_per_view;
    const std::vector<host::Measurement> measurements = host::make_measurements(fit_case);
    const host::FitResult result = host::fit_material(fit_case, measurements);
    const std::vector<std::string> names = host::fit_component_names(fit_case);
    std::printf("%s: loss %.4g -> %.4g in %zu iterations\n", fit_case.name.c_str(), result.history.front().loss,
                result.history.back().loss, fit_case.iterations);
    std::size_t index = 0;
    for (const host::FitParameter& parameter : fit_case.parameters)
    {
        for (std::size_t component = 0; component < parameter.count; ++component, ++index)
        {
            const float error = std::fabs(result.fitted[index] - parameter.truth[component]);
            std::printf("  %-28s start %.4f fitted %.4f truth %.4f (error %.4f, tolerance %.3g)\n", names[index].c_str(),
                        double(parameter.start[component]), double(result.fitted[index]), double(parameter.truth[component]),
                        double(error), double(parameter.tolerance));
            EXPECT_LE(error, parameter.tolerance) << names[index];
        }
    }
    EXPECT_LT(result.history.back().loss, result.history.front().loss);
}

INSTANTIATE_TEST_SUITE_P(Examples, MaterialFit,
                         ::testing::Values("plain_dielectric", "rough_metal", "coated_metal", "fuzz", "transmission"));

}  // namespace
}  // namespace openpbr::test
