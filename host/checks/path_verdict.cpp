// The verdict line of a run over execution paths: see path_verdict.h.
#include "host/checks/path_verdict.h"

#include <algorithm>
#include <utility>

namespace openpbr::host {

namespace {

std::string joined(const std::vector<std::string>& items, const std::string& separator)
{
    std::string text;
    for (const std::string& item : items)
    {
        text += (text.empty() ? "" : separator) + item;
    }
    return text;
}

std::string first_clause(const std::string& reason)
{
    const std::string clause = reason.substr(0, reason.find(':'));
    return clause.empty() ? "no reason given" : clause;
}

// "cuda, slang-cuda (not built); slang-wgsl (no adapter)": one group per first clause, in the
// order the groups first appear.
std::string not_executed_text(const std::vector<PathNotExecuted>& paths)
{
    std::vector<std::pair<std::string, std::vector<std::string>>> groups;
    for (const PathNotExecuted& path : paths)
    {
        const std::string clause = first_clause(path.reason);
        const auto group =
            std::find_if(groups.begin(), groups.end(), [&](const auto& candidate) { return candidate.first == clause; });
        if (group == groups.end())
        {
            groups.push_back({clause, {path.name}});
        }
        else
        {
            group->second.push_back(path.name);
        }
    }
    std::vector<std::string> parts;
    for (const auto& [clause, names] : groups)
    {
        parts.push_back(joined(names, ", ") + " (" + clause + ")");
    }
    return joined(parts, "; ");
}

}  // namespace

std::string verdict_line(const PathVerdict& verdict)
{
    std::vector<std::string> clauses = verdict.other_failures;
    const std::size_t executed = verdict.failed.size() + verdict.passed.size();
    const std::string of_executed =
        " of " + std::to_string(executed) + (executed == 1 ? " executed path " : " executed paths ");
    if (executed == 0)
    {
        clauses.push_back("no path executed");
    }
    else if (!verdict.failed.empty())
    {
        clauses.push_back(std::to_string(verdict.failed.size()) + of_executed +
                          (verdict.failed.size() == 1 ? "fails: " : "fail: ") + joined(verdict.failed, ", "));
        clauses.push_back(std::to_string(verdict.passed.size()) + (verdict.passed.size() == 1 ? " passes" : " pass"));
    }
    else
    {
        clauses.push_back(std::to_string(executed) + of_executed + (executed == 1 ? "passes" : "pass"));
    }
    if (!verdict.not_executed.empty())
    {
        clauses.push_back("not executed: " + not_executed_text(verdict.not_executed));
    }
    return "verdict: " + joined(clauses, "; ");
}

nlohmann::json to_json(const PathVerdict& verdict)
{
    nlohmann::json not_executed = nlohmann::json::array();
    for (const PathNotExecuted& path : verdict.not_executed)
    {
        not_executed.push_back({{"name", path.name}, {"reason", path.reason}});
    }
    return {{"text", verdict_line(verdict)},
            {"passes", verdict.passes()},
            {"executed", verdict.failed.size() + verdict.passed.size()},
            {"passed", verdict.passed.size()},
            {"failed", verdict.failed.size()},
            {"not_executed", verdict.not_executed.size()},
            {"failed_paths", verdict.failed},
            {"not_executed_paths", not_executed},
            {"other_failures", verdict.other_failures}};
}

}  // namespace openpbr::host
