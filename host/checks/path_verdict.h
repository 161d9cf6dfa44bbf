// The one-line verdict of a run over execution paths (`openpbr conformance`, `openpbr
// stability`): how many of the executed paths pass, failures first, and the paths that did not
// execute with their reason, e.g.
//   verdict: 13 of 13 executed paths pass; not executed: cuda, slang-cuda (not built)
//   verdict: 1 of 13 executed paths fails: hlsl; 12 pass; not executed: cuda, slang-cuda (not built)
// and the same counts as JSON.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace openpbr::host {

struct PathNotExecuted
{
    std::string name;  // e.g. "cuda"
    // Why, as the path's report line gives it, e.g. "not built: build/openpbr_cuda_conformance
    // does not exist (build target openpbr_cuda_programs)"; the verdict line shows its first
    // clause (up to the first ':'), e.g. "not built".
    std::string reason;
};

struct PathVerdict
{
    // Failures of the run besides the paths', listed first, e.g. "volume check: 2 cases fail".
    std::vector<std::string> other_failures;
    std::vector<std::string> failed;  // executed paths that fail, in report order
    std::vector<std::string> passed;  // executed paths that pass, in report order
    std::vector<PathNotExecuted> not_executed;

    bool passes() const { return other_failures.empty() && failed.empty(); }
};

// One line, starting "verdict: " and without the newline. The not-executed paths are grouped by
// the first clause of their reason, in report order.
std::string verdict_line(const PathVerdict& verdict);

// {"text": verdict_line, "passes": bool, "executed": n, "passed": n, "failed": n,
//  "not_executed": n, "failed_paths": [name, ...], "not_executed_paths": [{"name", "reason"}],
//  "other_failures": [text, ...]}.
nlohmann::json to_json(const PathVerdict& verdict);

}  // namespace openpbr::host
