// `openpbr bench gpu`: see bench_gpu.h.
#include "host/studies/bench_gpu.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"
#include "host/studies/feature_variants.h"

namespace openpbr::host {

namespace {

struct Operation
{
    const char* name;
    std::uint32_t mode;  // OPENPBR_CONFORMANCE_MODE_*
};

const Operation operations[] = {{"eval", 1u}, {"sample", 2u}, {"pdf", 3u}};

nlohmann::json rate(double ns_per_query)
{
    return {{"ns_per_query", ns_per_query}, {"queries_per_second", ns_per_query > 0.0 ? 1e9 / ns_per_query : 0.0}};
}

// What one entry of the report measures: a material class (the materials that need one toggle
// set) or one feature variant (a single material, named).
struct BenchClass
{
    std::string variant;  // empty for a material class, e.g. "Only/coat"
    std::uint32_t mask;   // the toggle set the specialized pipeline gets
    std::vector<Material> members;
};

std::vector<BenchClass> every_bench_class(const GpuBenchOptions& options)
{
    std::vector<BenchClass> bench;
    if (options.features)
    {
        for (const FeatureVariant& variant : feature_variants())
        {
            Material material = default_material();
            material.name = variant.name;
            material.inputs = variant.inputs;
            bench.push_back({variant.name, required_feature_mask(material), {material}});
        }
        return bench;
    }
    // Material classes: the materials grouped by the toggle set they need.
    std::map<std::uint32_t, std::vector<Material>> classes;
    for (const Material& material : conformance_materials(load_material_directory(options.materials_directory)))
    {
        classes[required_feature_mask(material)].push_back(material);
    }
    for (const auto& [mask, members] : classes)
    {
        bench.push_back({std::string(), mask, members});
    }
    return bench;
}

// An entry's name: a feature variant's ("Default"), a material class's toggle set ("coat+metal").
std::string entry_label(const BenchClass& bench_class)
{
    return bench_class.variant.empty() ? feature_set_label(bench_class.mask) : bench_class.variant;
}

// The entries of the report: every one, or those options.entries names (in report order); an
// unknown name is an error naming the known ones.
std::vector<BenchClass> bench_classes(const GpuBenchOptions& options)
{
    const std::vector<BenchClass> every = every_bench_class(options);
    if (options.entries.empty())
    {
        return every;
    }
    std::vector<BenchClass> chosen;
    for (const BenchClass& bench_class : every)
    {
        if (std::find(options.entries.begin(), options.entries.end(), entry_label(bench_class)) != options.entries.end())
        {
            chosen.push_back(bench_class);
        }
    }
    for (const std::string& name : options.entries)
    {
        if (std::none_of(every.begin(), every.end(),
                         [&](const BenchClass& bench_class) { return entry_label(bench_class) == name; }))
        {
            std::string known;
            for (const BenchClass& bench_class : every)
            {
                known += (known.empty() ? "" : ", ") + entry_label(bench_class);
            }
            throw std::invalid_argument("no entry '" + name + "' (known: " + known + ")");
        }
    }
    return chosen;
}

// ns per query of one variant, path, pipeline and operation; NaN where it has no device time.
double variant_ns(const nlohmann::json& classes, const std::string& variant, const std::string& path, const char* pipeline,
                  const char* operation)
{
    for (const nlohmann::json& entry : classes)
    {
        if (entry.value("variant", "") == variant)
        {
            const nlohmann::json rate = entry["paths"]
                                            .value(path, nlohmann::json::object())
                                            .value(pipeline, nlohmann::json::object())
                                            .value(operation, nlohmann::json::object());
            return rate.contains("ns_per_query") ? rate["ns_per_query"].get<double>() : std::nan("");
        }
    }
    return std::nan("");
}

// Per feature, pipeline and operation: "alone" = Only/<feature> minus Default (what the feature
// adds to the default material), "saved" = EveryLobe minus Without/<feature> (what leaving it
// out of the every-lobe material saves), in ns per query, as the CPU table of docs/performance.md
// reads benchmark_bsdf's rows.
nlohmann::json feature_costs(const nlohmann::json& classes, const std::string& path)
{
    nlohmann::json costs = nlohmann::json::object();
    for (const CostFeature& feature : cost_features())
    {
        for (const char* pipeline : {"full", "specialized"})
        {
            for (const Operation& operation : operations)
            {
                const double alone =
                    variant_ns(classes, std::string("Only/") + feature.name, path, pipeline, operation.name) -
                    variant_ns(classes, "Default", path, pipeline, operation.name);
                const double saved =
                    variant_ns(classes, "EveryLobe", path, pipeline, operation.name) -
                    variant_ns(classes, std::string("Without/") + feature.name, path, pipeline, operation.name);
                nlohmann::json& cell = costs[feature.name][pipeline][operation.name];
                // JSON has no NaN: a missing timing stays a missing key.
                if (std::isfinite(alone))
                {
                    cell["alone_ns"] = alone;
                }
                if (std::isfinite(saved))
                {
                    cell["saved_ns"] = saved;
                }
            }
        }
    }
    return costs;
}

// The middle value (the mean of the two middle ones for an even count) of a non-empty list.
double median(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// What one path has done so far: why it stopped, or why its specialized column did.
struct PathState
{
    ExecutionPath* path = nullptr;
    std::string skipped;              // non-empty: not run (any more), and why
    std::string specialized_skipped;  // non-empty: no specialized form, and why
    std::string device;
};

// "X" of a line "NAME: executed on X: ..." (the CUDA and WebGPU programs' lines), else the line.
std::string device_of(const std::string& note)
{
    const std::string executed_on = "executed on ";
    const std::size_t on = note.find(executed_on);
    const std::size_t colon = on == std::string::npos ? on : note.find(": ", on);
    return colon == std::string::npos ? note : note.substr(on + executed_on.size(), colon - on - executed_on.size());
}

// One round of one path on one entry, full and specialized pipeline, every mode: the device
// time per query of each batch is appended to its cell's "ns_per_round" (the host's dispatch
// time to "host_ns_per_round" where the path has no device time).
void measure_path(PathState& state, const BenchClass& bench_class, const std::vector<float>& queries,
                  const std::vector<float>& packed, const GpuBenchOptions& options, bool first_round, nlohmann::json& entry)
{
    const std::string name = state.path->name();
    for (const auto& [pipeline_name, pipeline_mask] :
         {std::pair<const char*, std::uint32_t>{"full", full_feature_mask()}, {"specialized", bench_class.mask}})
    {
        const bool specialized = std::string(pipeline_name) == "specialized";
        bool statistics_reported = !first_round;
        for (const Operation& operation : operations)
        {
            if (!state.skipped.empty() || (specialized && !state.specialized_skipped.empty()))
            {
                return;
            }
            PathBatch batch{queries, packed};
            batch.material_list = &bench_class.members;
            batch.mode = operation.mode;
            batch.feature_mask = pipeline_mask;
            batch.repeats = options.repeats;
            batch.device_local = true;
            PathRun run;
            try
            {
                run = state.path->run(batch);
            }
            catch (const PathUnavailable& unavailable)
            {
                // The full pipeline is every path's: a path that cannot run it cannot run here.
                (specialized ? state.specialized_skipped : state.skipped) = unavailable.what();
                continue;
            }
            if (state.device.empty())
            {
                state.device = device_of(run.device);
            }
            nlohmann::json& cell = entry["paths"][name][pipeline_name][operation.name];
            // The CUDA program times each operation in one run; the others time the batch's mode.
            const auto own = run.device_ns_per_operation.find(operation.name);
            if (own != run.device_ns_per_operation.end())
            {
                cell["ns_per_round"].push_back(own->second);
            }
            else if (run.device_ns_per_query)
            {
                cell["ns_per_round"].push_back(*run.device_ns_per_query);
            }
            else
            {
                cell["note"] = "the queue has no timestamps";
                cell["host_ns_per_round"].push_back(run.dispatch_ms * 1e6 / double(options.queries));
            }
            if (!statistics_reported)
            {
                // After the first dispatch: lavapipe compiles there. Register count, spills and
                // the like where the driver reports them.
                if (!run.pipeline_statistics.empty())
                {
                    entry["paths"][name][std::string(pipeline_name) + "_statistics"] = run.pipeline_statistics;
                }
                statistics_reported = true;
            }
        }
    }
}

}  // namespace

nlohmann::json run_gpu_bench(const GpuBenchOptions& options)
{
    const std::vector<BenchClass> classes = bench_classes(options);

    nlohmann::json report;
    report["set"] = options.features ? "features" : "material classes";
    report["queries_per_class"] = options.queries;
    report["repeats"] = options.repeats;
    report["rounds"] = options.rounds;
    report["timing"] = "device: Vulkan timestamps around the dispatch (buffers device-local, uploaded once), median "
                       "after the first, median of the rounds; CUDA events around the launch, median after a warm-up; "
                       "WebGPU timestamp queries around the pass, median after the first";
    ExecutionPaths paths(ExecutionPathSettings{options.kernel_directory, false, false});
    std::vector<PathState> states;
    const std::vector<std::string> device_paths = execution_path_names(false);
    const std::vector<std::string> every_path = execution_path_names(true);
    for (const std::string& name : options.paths)
    {
        if (std::find(device_paths.begin(), device_paths.end(), name) == device_paths.end() &&
            std::find(every_path.begin(), every_path.end(), name) != every_path.end())
        {
            // The CPU paths have no device time; benchmark_bsdf times the CPU build.
            throw std::invalid_argument("bench gpu times device kernels; '" + name +
                                        "' is a CPU path (benchmarks/benchmark_bsdf times the CPU build)");
        }
        PathState state;
        state.path = &paths.path(name);
        state.skipped = state.path->unavailable_reason();
        states.push_back(state);
    }
    report["classes"] = nlohmann::json::array();
    for (const auto& [variant, mask, members] : classes)
    {
        nlohmann::json entry;
        if (!variant.empty())
        {
            entry["variant"] = variant;
        }
        entry["toggles"] = feature_set_label(mask);
        std::vector<std::string> names;
        for (const Material& material : members)
        {
            names.push_back(material.name);
        }
        entry["materials"] = names;
        entry["paths"] = nlohmann::json::object();
        report["classes"].push_back(entry);
    }
    // Each entry's batch, the same in every round.
    std::vector<std::vector<float>> class_queries;
    std::vector<std::vector<float>> class_materials;
    for (const BenchClass& bench_class : classes)
    {
        class_queries.push_back(make_queries(options.queries, bench_class.members.size(), 1));
        class_materials.push_back(pack_materials(bench_class.members));
    }
    // Rounds over every entry, so a slow spell of a shared machine falls on all entries rather
    // than on the ones measured during it; the median of the rounds drops the spells (the
    // fastest round was tried: on the 2-core machine at load 9-11 one lucky round put a variant
    // at a third of an identical one's time).
    for (int round = 0; round < options.rounds; ++round)
    {
        for (std::size_t index = 0; index < classes.size(); ++index)
        {
            for (PathState& state : states)
            {
                measure_path(state, classes[index], class_queries[index], class_materials[index], options, round == 0,
                             report["classes"][index]);
            }
        }
    }
    for (nlohmann::json& entry : report["classes"])
    {
        for (auto& [name, path_cells] : entry["paths"].items())
        {
            for (const char* pipeline_name : {"full", "specialized"})
            {
                if (!path_cells.contains(pipeline_name))
                {
                    continue;
                }
                for (auto& [operation, cell] : path_cells[pipeline_name].items())
                {
                    if (cell.contains("ns_per_round"))
                    {
                        cell.update(rate(median(cell["ns_per_round"].get<std::vector<double>>())));
                    }
                    if (cell.contains("host_ns_per_round"))
                    {
                        cell["host_ns_per_query"] = median(cell["host_ns_per_round"].get<std::vector<double>>());
                    }
                }
            }
        }
    }
    report["paths"] = nlohmann::json::array();
    for (const PathState& state : states)
    {
        nlohmann::json path_report = {{"name", state.path->name()}, {"description", state.path->description()}};
        if (!state.skipped.empty())
        {
            path_report["skipped"] = state.skipped;
        }
        else
        {
            path_report["device"] = state.device;
            if (!state.specialized_skipped.empty())
            {
                path_report["specialized_skipped"] = state.specialized_skipped;
            }
            if (options.features)
            {
                report["feature_costs"][state.path->name()] = feature_costs(report["classes"], state.path->name());
            }
        }
        report["paths"].push_back(path_report);
    }
    return report;
}

std::string gpu_bench_text(const nlohmann::json& report)
{
    std::ostringstream text;
    text << "bench gpu: " << report["queries_per_class"].get<std::size_t>() << " queries per class and kernel; "
         << report["timing"].get<std::string>() << "\n";
    for (const nlohmann::json& path : report["paths"])
    {
        const std::string name = path["name"].get<std::string>();
        if (path.contains("skipped"))
        {
            text << "  " << name << " device: none: " << path["skipped"].get<std::string>() << "\n";
            continue;
        }
        text << "  " << name << " device: " << path["device"].get<std::string>() << "\n";
        if (path.contains("specialized_skipped"))
        {
            text << "    specialized not run: " << path["specialized_skipped"].get<std::string>() << "\n";
        }
    }
    text << "  ns per query (eval / sample / pdf, each with prepare):\n";
    auto triple = [](const nlohmann::json& kernels) {
        std::ostringstream line;
        bool first = true;
        for (const char* name : {"eval", "sample", "pdf"})
        {
            line << (first ? "" : " / ");
            first = false;
            if (kernels.contains(name) && kernels[name].contains("ns_per_query"))
            {
                line << kernels[name]["ns_per_query"].get<double>();
            }
            else
            {
                line << "-";
            }
        }
        return line.str();
    };
    for (const nlohmann::json& entry : report["classes"])
    {
        if (entry.contains("variant"))
        {
            text << "  " << entry["variant"].get<std::string>() << " (" << entry["toggles"].get<std::string>() << "):";
        }
        else
        {
            text << "  " << entry["toggles"].get<std::string>() << " (" << entry["materials"].size() << " materials):";
        }
        // In the order asked for (the JSON object sorts its keys).
        const char* separator = " ";
        for (const nlohmann::json& path : report["paths"])
        {
            const std::string name = path["name"].get<std::string>();
            if (!entry["paths"].contains(name))
            {
                continue;
            }
            const nlohmann::json& cells = entry["paths"][name];
            text << separator << name << " full " << triple(cells.value("full", nlohmann::json::object()))
                 << ", specialized " << triple(cells.value("specialized", nlohmann::json::object()));
            separator = "; ";
        }
        text << "\n";
    }
    if (report.contains("feature_costs"))
    {
        auto differences = [](const nlohmann::json& operations_json, const char* key) {
            std::ostringstream line;
            bool first = true;
            for (const char* name : {"eval", "sample", "pdf"})
            {
                line << (first ? "" : " / ");
                first = false;
                if (operations_json[name].contains(key))
                {
                    line << std::showpos << operations_json[name][key].get<double>() << std::noshowpos;
                }
                else
                {
                    line << "-";
                }
            }
            return line.str();
        };
        for (const auto& [path, costs] : report["feature_costs"].items())
        {
            text << "  " << path
                 << " per feature, ns per query (eval / sample / pdf): alone = Only/<feature> - Default, saved = "
                    "EveryLobe - Without/<feature>\n";
            // Table order (the JSON object sorts its keys).
            for (const CostFeature& feature : cost_features())
            {
                const nlohmann::json& pipelines = costs[feature.name];
                text << "  " << feature.name << ": full alone " << differences(pipelines["full"], "alone_ns") << ", saved "
                     << differences(pipelines["full"], "saved_ns") << "; specialized alone "
                     << differences(pipelines["specialized"], "alone_ns") << ", saved "
                     << differences(pipelines["specialized"], "saved_ns") << "\n";
            }
        }
    }
    return text.str();
}

}  // namespace openpbr::host
