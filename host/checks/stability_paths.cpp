// Stability runner on every path (see stability.h): the CPU build through run_stability_cpu, the
// GPU paths through the one execution-path mechanism (host/checks/execution_path.h). Apart from
// stability.cpp so that the corpus and the CPU build link without the GPU paths
// (CMakeLists.txt, openpbr_host_core).
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/checks/stability.h"

namespace openpbr::host {

std::vector<std::string> stability_paths(const StabilityOptions& options)
{
    std::vector<std::string> wanted = options.paths;
    if (wanted.empty())
    {
        wanted.push_back("cpu");
        for (const std::string& name : known_conformance_paths())
        {
            wanted.push_back(name);
        }
    }
    const std::vector<std::string> known_gpu = known_conformance_paths();
    for (const std::string& name : wanted)
    {
        if (name != "cpu" && std::find(known_gpu.begin(), known_gpu.end(), name) == known_gpu.end())
        {
            throw std::invalid_argument("unknown path '" + name + "' (known: cpu and the conformance GPU paths)");
        }
    }
    // Report order: the CPU build, then the GPU paths in the order they are known.
    const auto asked = [&wanted](const std::string& name) {
        return std::find(wanted.begin(), wanted.end(), name) != wanted.end();
    };
    std::vector<std::string> ordered;
    if (asked("cpu"))
    {
        ordered.push_back("cpu");
    }
    for (const std::string& name : known_gpu)
    {
        if (asked(name))
        {
            ordered.push_back(name);
        }
    }
    return ordered;
}

StabilityReport run_stability(const std::vector<StabilityCase>& cases, const StabilityOptions& options)
{
    const std::vector<std::string> wanted = stability_paths(options);
    const std::vector<std::string> known_gpu = known_conformance_paths();
    StabilityReport report =
        run_stability_cpu(cases, options, std::find(wanted.begin(), wanted.end(), "cpu") != wanted.end());

    // Every GPU path through the one mechanism (host/checks/execution_path.h); one that cannot
    // run here (no device, not built) is reported as not executed, with the reason.
    ExecutionPathSettings settings;
    settings.kernel_directory = options.kernel_directory;
    settings.validation = options.validation;
    ExecutionPaths paths(settings);
    for (const std::string& name : known_gpu)
    {
        if (std::find(wanted.begin(), wanted.end(), name) == wanted.end())
        {
            continue;
        }
        ExecutionPath& path = paths.path(name);
        std::string device;
        std::size_t validation_messages = 0;
        const StabilityExecutor execute = [&path, &device, &validation_messages](const std::vector<float>& queries,
                                                                                 const std::vector<float>& packed) {
            PathBatch batch{queries, packed};
            // The report needs each batch's results, not its steady-state dispatch time.
            batch.repeats = 1;
            PathRun run = path.run(batch);
            device = run.device;
            validation_messages += run.validation_messages.size();
            return std::move(run.results);
        };
        try
        {
            const std::string reason = path.unavailable_reason();
            if (!reason.empty())
            {
                throw PathUnavailable(reason);
            }
            StabilityPathResult result = run_stability_path(name, execute, cases, report.gpu_samples_per_case, options.seed);
            result.note = device;
            result.validation_messages = validation_messages;
            report.paths.push_back(std::move(result));
        }
        catch (const PathUnavailable& unavailable)
        {
            StabilityPathResult skipped;
            skipped.name = name;
            skipped.note = unavailable.what();
            report.paths.push_back(std::move(skipped));
        }
        if (options.on_path_finished)
        {
            options.on_path_finished(report.paths.back());
        }
    }
    return report;
}

}  // namespace openpbr::host
