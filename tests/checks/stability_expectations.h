// Shared by the stability tests (test_stability_cpu.cpp: the corpus and the CPU build;
// test_stability.cpp: the GPU paths): the corpus, the energy bound and the expectations every
// path's result must meet. No non-finite or negative output and no energy gain (mean sample
// weight <= 1.005 per case and channel) anywhere; the energy bound allows three standard errors
// of the mean on top of 1.005 (for deterministic delta cases the standard error is 0).
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "host/checks/stability.h"

namespace openpbr::host::stability_tests {

constexpr double max_mean_weight = 1.005;

inline const std::vector<StabilityCase>& corpus()
{
    static const std::vector<StabilityCase> cases = load_stability_corpus(OPENPBR_STABILITY_CORPUS);
    return cases;
}

inline std::string describe_case(const std::string& name)
{
    for (const StabilityCase& stability_case : corpus())
    {
        if (stability_case.name == name)
        {
            std::ostringstream text;
            text << name << " (" << stability_case.description << "; view " << stability_case.view.x << ", "
                 << stability_case.view.y << ", " << stability_case.view.z << "; inputs:";
            for (const std::string& input : stability_case.inputs_set)
            {
                text << " " << input;
            }
            text << ")";
            return text.str();
        }
    }
    return name;
}

inline std::string describe_violations(const StabilityCaseResult& result)
{
    std::ostringstream text;
    for (const auto& record : result.violations)
    {
        text << "\n  " << record.what << " at query " << record.query << ": view (" << record.view[0] << ", "
             << record.view[1] << ", " << record.view[2] << ") light (" << record.light[0] << ", " << record.light[1] << ", "
             << record.light[2] << ") u (" << record.u[0] << ", " << record.u[1] << ", " << record.u[2] << ") outputs:";
        for (const float value : record.outputs)
        {
            text << " " << value;
        }
    }
    return text.str();
}

// The expectations on one executed path's result over the whole corpus.
inline void expect_stable(const StabilityPathResult& path)
{
    ASSERT_EQ(path.cases.size(), corpus().size());
    EXPECT_EQ(path.nonfinite, 0u);
    EXPECT_EQ(path.negative, 0u);
    EXPECT_EQ(path.bad_directions, 0u);
    EXPECT_EQ(path.validation_messages, 0u);
    for (const StabilityCaseResult& result : path.cases)
    {
        EXPECT_EQ(result.nonfinite + result.negative + result.bad_directions, 0u)
            << describe_case(result.name) << ": " << result.nonfinite << " non-finite, " << result.negative << " negative, "
            << result.bad_directions << " non-unit sample directions" << describe_violations(result);
        // Noisy cases (e.g. dispersion: one channel carries weight 3) may exceed the bound by
        // sampling noise alone; three standard errors keep the check from depending on the seed.
        EXPECT_LE(result.max_mean_weight - 3.0 * result.mean_weight_standard_error, max_mean_weight)
            << describe_case(result.name) << ": mean sample weight (" << result.mean_weight[0] << ", "
            << result.mean_weight[1] << ", " << result.mean_weight[2] << ") +- " << result.mean_weight_standard_error
            << " over " << result.samples << " samples";
    }
}

}  // namespace openpbr::host::stability_tests
