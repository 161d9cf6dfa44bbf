// `openpbr bench gpu`: see bench_gpu.h.
#include "host/studies/bench_gpu.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/gpu/vulkan_runner.h"
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

std::vector<BenchClass> bench_classes(const GpuBenchOptions& options)
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

// ns per query of one variant, pipeline and operation; NaN where the queue had no timestamps.
double variant_ns(const nlohmann::json& classes, const std::string& variant, const char* pipeline, const char* operation)
{
    for (const nlohmann::json& entry : classes)
    {
        if (entry.value("variant", "") == variant)
        {
            const nlohmann::json& rate = entry["vulkan"][pipeline][operation];
            return rate.contains("ns_per_query") ? rate["ns_per_query"].get<double>() : std::nan("");
        }
    }
    return std::nan("");
}

// Per feature, pipeline and operation: "alone" = Only/<feature> minus Default (what the feature
// adds to the default material), "saved" = EveryLobe minus Without/<feature> (what leaving it
// out of the every-lobe material saves), in ns per query, as the CPU table of docs/performance.md
// reads benchmark_bsdf's rows.
nlohmann::json feature_costs(const nlohmann::json& classes)
{
    nlohmann::json costs = nlohmann::json::object();
    for (const CostFeature& feature : cost_features())
    {
        for (const char* pipeline : {"full", "specialized"})
        {
            for (const Operation& operation : operations)
            {
                const double alone = variant_ns(classes, std::string("Only/") + feature.name, pipeline, operation.name) -
                                     variant_ns(classes, "Default", pipeline, operation.name);
                const double saved = variant_ns(classes, "EveryLobe", pipeline, operation.name) -
                                     variant_ns(classes, std::string("Without/") + feature.name, pipeline, operation.name);
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

// One round of the Vulkan timings of one entry, full and specialized pipeline, every mode: the
// median over the repeats after the first is appended to the cell's "ns_per_round".
void measure_vulkan(SpecializedPipelineCache& cache, const BenchClass& bench_class, const GpuBenchOptions& options,
                    bool first_round, nlohmann::json& entry)
{
    const std::vector<float> queries = make_queries(options.queries, bench_class.members.size(), 1);
    const std::vector<float> packed = pack_materials(bench_class.members);
    for (const auto& [pipeline_name, pipeline_mask] :
         {std::pair<const char*, std::uint32_t>{"full", full_feature_mask()}, {"specialized", bench_class.mask}})
    {
        ComputePipeline& pipeline = cache.pipeline(pipeline_mask);
        bool statistics_reported = !first_round;
        for (const Operation& operation : operations)
        {
            ConformanceDispatchSettings settings;
            settings.mode = operation.mode;
            settings.device_local = true;
            const DispatchTiming timing =
                dispatch_conformance_pipeline(pipeline, queries, packed, options.repeats, settings).timing;
            nlohmann::json& cell = entry["vulkan"][pipeline_name][operation.name];
            if (timing.device_dispatch_ms)
            {
                cell["ns_per_round"].push_back(*timing.device_dispatch_ms * 1e6 / double(options.queries));
            }
            else
            {
                cell["note"] = "the queue has no timestamps";
                cell["host_ns_per_round"].push_back(timing.dispatch_ms * 1e6 / double(options.queries));
            }
            if (!statistics_reported)
            {
                // After the first dispatch: lavapipe compiles there. Register count, spills and
                // the like where the driver reports them.
                nlohmann::json statistics = nlohmann::json::object();
                for (const PipelineStatistic& statistic : pipeline.statistics())
                {
                    statistics[statistic.name] = statistic.value;
                }
                entry["vulkan"][std::string(pipeline_name) + "_statistics"] = statistics;
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
    report["vulkan_path"] = options.path;
    report["timing"] = "device: Vulkan timestamps around the dispatch (buffers device-local, uploaded once), median "
                       "after the first, median of the rounds; CUDA events around the launch, median after a warm-up";
    std::optional<VulkanContext> context;
    std::string context_error = "not requested";
    if (options.vulkan)
    {
        context = VulkanContext::create(VulkanOptions{}, &context_error);
    }
    report["vulkan_device"] = context ? context->device_name() : "none: " + context_error;
    // Pipelines built once (full, and one per class's toggle set) and shared by the three modes,
    // which are a parameter of the kernel.
    std::optional<SpecializedPipelineCache> cache;
    if (context)
    {
        cache.emplace(*context, conformance_pipeline_description(options.path, options.kernel_directory));
    }
    report["cuda_device"] = options.cuda ? "none" : "not requested";
    ExecutionPaths paths(ExecutionPathSettings{options.kernel_directory, false, false});
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
        if (options.cuda)
        {
            // The CUDA paths through the execution-path mechanism (one program run per class for
            // both): their kernel times per operation, or why they did not run.
            const std::vector<float> queries = make_queries(options.queries, members.size(), 1);
            const std::vector<float> packed = pack_materials(members);
            for (const char* name : {"cuda", "slang-cuda"})
            {
                ExecutionPath& path = paths.path(name);
                try
                {
                    const std::string reason = path.unavailable_reason();
                    if (!reason.empty())
                    {
                        throw PathUnavailable(reason);
                    }
                    const PathRun run = path.run(PathBatch{queries, packed});
                    const std::string& note = run.device;
                    const std::size_t on = note.find("executed on ");
                    const std::size_t colon = note.find(": ", on);
                    if (on != std::string::npos && colon != std::string::npos)
                    {
                        report["cuda_device"] = note.substr(on + 12, colon - on - 12);
                    }
                    for (const auto& [operation, ns] : run.device_ns_per_operation)
                    {
                        entry["cuda"][name][operation] = rate(ns);
                    }
                }
                catch (const PathUnavailable& unavailable)
                {
                    report["cuda_device"] = std::string("none: ") + unavailable.what();
                }
            }
        }
        report["classes"].push_back(entry);
    }
    if (context)
    {
        // Rounds over every entry, so a slow spell of a shared machine falls on all entries rather
        // than on the ones measured during it; the median of the rounds drops the spells (the
        // fastest round was tried: on the 2-core machine at load 9-11 one lucky round put a
        // variant at a third of an identical one's time).
        for (int round = 0; round < options.rounds; ++round)
        {
            for (std::size_t index = 0; index < classes.size(); ++index)
            {
                measure_vulkan(*cache, classes[index], options, round == 0, report["classes"][index]);
            }
        }
        for (nlohmann::json& entry : report["classes"])
        {
            for (const char* pipeline_name : {"full", "specialized"})
            {
                for (const Operation& operation : operations)
                {
                    nlohmann::json& cell = entry["vulkan"][pipeline_name][operation.name];
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
    if (options.features && context)
    {
        report["feature_costs"] = feature_costs(report["classes"]);
    }
    return report;
}

std::string gpu_bench_text(const nlohmann::json& report)
{
    std::ostringstream text;
    text << "bench gpu: " << report["queries_per_class"].get<std::size_t>() << " queries per class and kernel; "
         << report["timing"].get<std::string>() << "\n";
    text << "  Vulkan device: " << report["vulkan_device"].get<std::string>() << " (path "
         << report["vulkan_path"].get<std::string>() << ")\n";
    text << "  CUDA device: " << report["cuda_device"].get<std::string>() << "\n";
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
        if (entry.contains("vulkan"))
        {
            text << " vulkan full " << triple(entry["vulkan"]["full"]) << ", specialized "
                 << triple(entry["vulkan"]["specialized"]);
        }
        if (entry.contains("cuda"))
        {
            for (const auto& [name, kernels] : entry["cuda"].items())
            {
                text << "; " << name << " " << triple(kernels);
            }
        }
        text << "\n";
    }
    if (report.contains("feature_costs"))
    {
        text << "  per feature, ns per query (eval / sample / pdf): alone = Only/<feature> - Default, saved = "
                "EveryLobe - Without/<feature>\n";
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
        // Table order (the JSON object sorts its keys).
        for (const CostFeature& feature : cost_features())
        {
            const nlohmann::json& pipelines = report["feature_costs"][feature.name];
            text << "  " << feature.name << ": full alone " << differences(pipelines["full"], "alone_ns") << ", saved "
                 << differences(pipelines["full"], "saved_ns") << "; specialized alone "
                 << differences(pipelines["specialized"], "alone_ns") << ", saved "
                 << differences(pipelines["specialized"], "saved_ns") << "\n";
        }
    }
    return text.str();
}

}  // namespace openpbr::host
