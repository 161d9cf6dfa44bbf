// The verdict line of `openpbr conformance` and `openpbr stability` (host/checks/path_verdict.h):
// one case per shape of a run (all pass, some fail, other failures, nothing executed, paths not
// executed grouped by reason), each checked as the line a reader sees and as the JSON counts.
#include "host/checks/path_verdict.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using openpbr::host::PathNotExecuted;
using openpbr::host::PathVerdict;

struct VerdictCase
{
    const char* name;
    PathVerdict verdict;
    std::string line;  // the exact verdict line
    bool passes;
    int executed;
    int failed;
    int not_executed;
};

std::vector<VerdictCase> verdict_cases()
{
    const PathNotExecuted cuda{"cuda", "not built: build/openpbr_cuda_conformance does not exist"};
    const PathNotExecuted slang_cuda{"slang-cuda", "not built: the CUDA toolkit was not found"};
    const PathNotExecuted wgsl{"slang-wgsl", "no adapter: Dawn found no WebGPU adapter"};
    return {
        {"AllPass", {{}, {}, {"glsl", "hlsl"}, {}}, "verdict: 2 of 2 executed paths pass", true, 2, 0, 0},
        {"OnePasses", {{}, {}, {"glsl"}, {}}, "verdict: 1 of 1 executed path passes", true, 1, 0, 0},
        {"OneFails",
         {{}, {"hlsl"}, {"glsl", "slang-spirv"}, {}},
         "verdict: 1 of 3 executed paths fails: hlsl; 2 pass",
         false,
         3,
         1,
         0},
        {"TwoFail",
         {{}, {"hlsl", "metal"}, {"glsl"}, {}},
         "verdict: 2 of 3 executed paths fail: hlsl, metal; 1 passes",
         false,
         3,
         2,
         0},
        {"OtherFailureFirst",
         {{"volume check: 2 cases fail"}, {}, {"glsl"}, {}},
         "verdict: volume check: 2 cases fail; 1 of 1 executed path passes",
         false,
         1,
         0,
         0},
        {"NothingExecuted",
         {{}, {}, {}, {cuda}},
         "verdict: no path executed; not executed: cuda (not built)",
         true,
         0,
         0,
         1},
        {"NotExecutedGrouped",
         {{}, {}, {"glsl"}, {cuda, wgsl, slang_cuda}},
         "verdict: 1 of 1 executed path passes; not executed: cuda, slang-cuda (not built); slang-wgsl (no adapter)",
         true,
         1,
         0,
         3},
        {"ReasonWithoutClause",
         {{}, {}, {"glsl"}, {{"metal", ""}}},
         "verdict: 1 of 1 executed path passes; not executed: metal (no reason given)",
         true,
         1,
         0,
         1},
    };
}

class PathVerdictLine : public ::testing::TestWithParam<VerdictCase>
{
};

TEST_P(PathVerdictLine, LineAndCounts)
{
    const VerdictCase& expected = GetParam();
    EXPECT_EQ(openpbr::host::verdict_line(expected.verdict), expected.line);
    const nlohmann::json json = openpbr::host::to_json(expected.verdict);
    EXPECT_EQ(json.at("text").get<std::string>(), expected.line);
    EXPECT_EQ(json.at("passes").get<bool>(), expected.passes);
    EXPECT_EQ(expected.verdict.passes(), expected.passes);
    EXPECT_EQ(json.at("executed").get<int>(), expected.executed);
    EXPECT_EQ(json.at("failed").get<int>(), expected.failed);
    EXPECT_EQ(json.at("passed").get<int>(), expected.executed - expected.failed);
    EXPECT_EQ(json.at("not_executed").get<int>(), expected.not_executed);
    EXPECT_EQ(json.at("failed_paths").size(), static_cast<std::size_t>(expected.failed));
    EXPECT_EQ(json.at("not_executed_paths").size(), static_cast<std::size_t>(expected.not_executed));
}

INSTANTIATE_TEST_SUITE_P(Runs, PathVerdictLine, ::testing::ValuesIn(verdict_cases()),
                         [](const ::testing::TestParamInfo<VerdictCase>& info) { return std::string(info.param.name); });

}  // namespace
