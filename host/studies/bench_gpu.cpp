// `openpbr bench gpu`: see bench_gpu.h.
#include "host/studies/bench_gpu.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/gpu/cuda_conformance.h"
#include "host/gpu/vulkan_runner.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"

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

}  // namespace

nlohmann::json run_gpu_bench(const GpuBenchOptions& options)
{
    const std::vector<Material> materials = conformance_materials(load_material_directory(options.materials_directory));
    // Material classes: the materials grouped by the toggle set they need.
    std::map<std::uint32_t, std::vector<Material>> classes;
    for (const Material& material : materials)
    {
        classes[required_feature_mask(material)].push_back(material);
    }

    nlohmann::json report;
    report["queries_per_class"] = options.queries;
    report["repeats"] = options.repeats;
    report["vulkan_path"] = options.path;
    report["timing"] = "device: Vulkan timestamps around the dispatch (buffers device-local, uploaded once), CUDA "
                       "events around the launch; median after the first";
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
    report["classes"] = nlohmann::json::array();
    for (const auto& [mask, members] : classes)
    {
        nlohmann::json entry;
        entry["toggles"] = feature_set_label(mask);
        std::vector<std::string> names;
        for (const Material& material : members)
        {
            names.push_back(material.name);
        }
        entry["materials"] = names;
        const std::vector<float> queries = make_queries(options.queries, members.size(), 1);
        if (context)
        {
            const std::vector<float> packed = pack_materials(members);
            for (const auto& [pipeline_name, pipeline_mask] :
                 {std::pair<const char*, std::uint32_t>{"full", full_feature_mask()}, {"specialized", mask}})
            {
                ComputePipeline& pipeline = cache->pipeline(pipeline_mask);
                bool statistics_reported = false;
                for (const Operation& operation : operations)
                {
                    ConformanceDispatchSettings settings;
                    settings.mode = operation.mode;
                    settings.device_local = true;
                    const DispatchTiming timing =
                        dispatch_conformance_pipeline(pipeline, queries, packed, options.repeats, settings).timing;
                    if (timing.device_dispatch_ms)
                    {
                        entry["vulkan"][pipeline_name][operation.name] =
                            rate(*timing.device_dispatch_ms * 1e6 / double(options.queries));
                    }
                    else
                    {
                        entry["vulkan"][pipeline_name][operation.name] = {
                            {"note", "the queue has no timestamps"},
                            {"host_ns_per_query", timing.dispatch_ms * 1e6 / double(options.queries)}};
                    }
                    if (!statistics_reported)
                    {
                        // After the first dispatch: lavapipe compiles there. Register count,
                        // spills and the like where the driver reports them.
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
        if (options.cuda)
        {
            for (const ExternalPathResult& external :
                 run_cuda_conformance_program(default_cuda_conformance_program(), queries, pack_materials(members)))
            {
                if (!external.executed)
                {
                    report["cuda_device"] = "none: " + external.note;
                    continue;
                }
                const std::string& note = external.note;
                const std::size_t on = note.find("executed on ");
                const std::size_t colon = note.find(": ", on);
                if (on != std::string::npos && colon != std::string::npos)
                {
                    report["cuda_device"] = note.substr(on + 12, colon - on - 12);
                }
                for (const auto& [operation, ns] : external.device_ns_per_query)
                {
                    entry["cuda"][external.name][operation] = rate(ns);
                }
            }
        }
        report["classes"].push_back(entry);
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
        text << "  " << entry["toggles"].get<std::string>() << " (" << entry["materials"].size() << " materials):";
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
    return text.str();
}

}  // namespace openpbr::host
