// `openpbr features` (the smallest feature-toggle set that renders the materials exactly; exit 3
// when a material needs more than --pipeline), `openpbr bench specialization` and
// `openpbr bench gpu` (timings, no pass/fail).
#include "host/cli/command.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "host/checks/execution_path.h"
#include "host/studies/bench_gpu.h"
#include "host/studies/bench_specialization.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"
#include "host/cli/output_files.h"

namespace openpbr::host {

namespace {

void write_json(const std::string& path, const nlohmann::json& json)
{
    write_json_file(path, json);
    std::cout << "wrote " << path << "\n";
}

// Runs `body` as a subcommand (run_command); a FeatureError (a material needs a feature the
// chosen pipeline lacks) exits with `refusal_code`.
template <typename Body> void run_reporting_errors(Body body, int refusal_code)
{
    run_command([&]() {
        try
        {
            body();
        }
        catch (const FeatureError& error)
        {
            std::cerr << "openpbr: refused: " << error.what() << "\n";
            return refusal_code;
        }
        return 0;
    });
}

}  // namespace

CLI::App* add_features_subcommand(CLI::App& parent, const CommandContext& context)
{
    struct FeaturesSettings
    {
        std::vector<std::string> files;
        std::string json;
        std::vector<std::string> pipeline;
    };
    auto features = std::make_shared<FeaturesSettings>();
    CLI::App* command = parent.add_subcommand(
        "features", "smallest feature-toggle set that renders the materials exactly, and its specialization info");
    command->add_option("files", features->files, "MaterialX files (default: every file of --materials-dir)");
    command->add_option("--json", features->json, "write the report as JSON");
    command
        ->add_option("--pipeline", features->pipeline,
                     "check a pipeline's toggle set, e.g. coat,metal (exit 3 when a material needs more)")
        ->delimiter(',');
    command->callback([features, context]() {
        run_reporting_errors(
            [&]() {
                std::vector<Material> materials;
                if (features->files.empty())
                {
                    materials = load_material_directory(context.materials_directory);
                }
                for (const std::string& file : features->files)
                {
                    const std::vector<Material> loaded = load_materialx_file(file);
                    materials.insert(materials.end(), loaded.begin(), loaded.end());
                }
                std::cout << features_report_text(materials);
                if (!features->json.empty())
                {
                    write_json(features->json, features_report_json(materials));
                }
                if (!features->pipeline.empty())
                {
                    const std::uint32_t mask = parse_feature_names(features->pipeline);
                    check_pipeline_supports(materials, mask);
                    std::cout << "pipeline {" << feature_set_label(mask) << "} renders every material exactly\n";
                }
            },
            3);
    });

    struct BenchSettings
    {
        SpecializationBenchOptions options;
        std::string json;
        bool cpu_only = false;
    };
    auto bench = std::make_shared<BenchSettings>();
    CLI::App* bench_command = parent.add_subcommand("bench", "measurements (timings, no pass/fail)");
    bench_command->require_subcommand(1);
    CLI::App* specialization =
        bench_command->add_subcommand("specialization", "full versus specialized pipelines: lavapipe and CPU");
    specialization->add_option("--json", bench->json, "write the report as JSON");
    specialization->add_option("--queries", bench->options.gpu_queries, "lavapipe queries per scene and pipeline")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(64), std::size_t(10000000)));
    specialization->add_option("--repeats", bench->options.gpu_repeats, "dispatches per pipeline (median of 2..n)")
        ->capture_default_str()
        ->check(CLI::Range(2, 100));
    specialization->add_option("--path", bench->options.path, "GPU path, e.g. slang-spirv or glsl-spirv")
        ->capture_default_str();
    specialization->add_flag("--cpu-only", bench->cpu_only, "skip lavapipe");
    specialization->callback([bench, context]() {
        run_reporting_errors(
            [&]() {
                bench->options.materials_directory = context.materials_directory;
                bench->options.kernel_directory = context.kernel_directory;
                bench->options.gpu = !bench->cpu_only;
                const nlohmann::json report = run_specialization_bench(bench->options);
                std::cout << specialization_bench_text(report);
                if (!bench->json.empty())
                {
                    write_json(bench->json, report);
                }
            },
            1);
    });

    struct GpuBenchSettings
    {
        GpuBenchOptions options;
        std::string json;
        bool no_vulkan = false;
        bool no_cuda = false;
    };
    auto gpu = std::make_shared<GpuBenchSettings>();
    CLI::App* gpu_command = bench_command->add_subcommand(
        "gpu", "device-timed throughput of prepare+eval, sample, pdf per material class and execution path (Vulkan "
               "timestamps, CUDA events, WebGPU timestamp queries)");
    gpu_command->add_option("--json", gpu->json, "write the report as JSON");
    gpu_command->add_option("--queries", gpu->options.queries, "queries per class and kernel (e.g. 4096 on lavapipe)")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(64), std::size_t(100000000)));
    gpu_command->add_option("--repeats", gpu->options.repeats, "dispatches per kernel (median of 2..n)")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000));
    gpu_command
        ->add_option("--rounds", gpu->options.rounds,
                     "passes over every entry, median of the passes (e.g. 6 on a shared machine)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    gpu_command
        ->add_option("--paths", gpu->options.paths,
                     "execution paths in report order: Vulkan (slang-spirv, glsl-spirv, ...), CUDA (cuda, slang-cuda), "
                     "WebGPU (slang-wgsl, wgsl-library: one pipeline build per batch, seconds each on SwiftShader)")
        ->capture_default_str();
    gpu_command->add_option("--entries", gpu->options.entries,
                            "only these entries: material classes by toggle set (base, coat+metal, ...) or, with "
                            "--features, variants (Default, Only/coat, ...)");
    gpu_command->add_flag("--no-vulkan", gpu->no_vulkan, "leave the Vulkan paths out of --paths");
    gpu_command->add_flag("--no-cuda", gpu->no_cuda, "leave the CUDA paths out of --paths");
    gpu_command->add_flag("--features", gpu->options.features,
                          "per feature variant (Default, EveryLobe, Only/<feature>, Without/<feature>) instead of "
                          "per material class: the per-feature cost table of docs/performance.md");
    gpu_command->callback([gpu, context]() {
        run_reporting_errors(
            [&]() {
                gpu->options.materials_directory = context.materials_directory;
                gpu->options.kernel_directory = context.kernel_directory;
                const std::vector<std::string> vulkan = vulkan_path_names();
                const std::vector<std::string>::iterator kept =
                    std::remove_if(gpu->options.paths.begin(), gpu->options.paths.end(), [&](const std::string& name) {
                        const bool is_vulkan = std::find(vulkan.begin(), vulkan.end(), name) != vulkan.end();
                        const bool is_cuda = name == "cuda" || name == "slang-cuda";
                        return (gpu->no_vulkan && is_vulkan) || (gpu->no_cuda && is_cuda);
                    });
                gpu->options.paths.erase(kept, gpu->options.paths.end());
                const nlohmann::json report = run_gpu_bench(gpu->options);
                std::cout << gpu_bench_text(report);
                if (!gpu->json.empty())
                {
                    write_json(gpu->json, report);
                }
            },
            1);
    });
    return command;
}

}  // namespace openpbr::host
