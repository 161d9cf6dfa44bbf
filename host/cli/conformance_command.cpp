// `openpbr conformance`: every GPU path against the CPU build (host/checks/conformance.h); prints
// the report, ending with the verdict line (host/checks/path_verdict.h), and writes --json, --dump-cpu and
// --dump-dir. Exit status 0 once the report is written (the verdict says which paths pass), 1 on errors.
#include <iostream>
#include <string>
#include <vector>

#include "host/checks/conformance.h"
#include "host/cli/command.h"
#include "host/cli/output_files.h"
#include "host/scene/material_library.h"

namespace openpbr::host {

namespace {

struct ConformanceSettings
{
    ConformanceOptions options;
    std::string json_path;
    std::vector<std::string> material_files;  // empty: every material of the materials directory
    bool validation = false;
};

std::vector<Material> load_materials(const std::vector<std::string>& files, const std::string& directory)
{
    if (files.empty())
    {
        return load_material_directory(directory);
    }
    std::vector<Material> materials;
    for (const std::string& file : files)
    {
        const std::vector<Material> loaded = load_materialx_file(file);
        materials.insert(materials.end(), loaded.begin(), loaded.end());
    }
    return materials;
}

}  // namespace

CLI::App* add_conformance_subcommand(CLI::App& parent, const CommandContext& context)
{
    auto settings = std::make_shared<ConformanceSettings>();
    CLI::App* command = parent.add_subcommand("conformance", "compare every GPU path with the CPU build");
    command->add_option("--queries", settings->options.query_count, "number of queries")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(1), std::size_t(100000000)));
    command->add_option("--seed", settings->options.seed, "random seed")->capture_default_str();
    command->add_option("--json", settings->json_path, "write the report as JSON");
    command->add_option("--paths", settings->options.paths, "paths to run (default: all; cpu = the CPU build only)");
    command->add_option("--materials", settings->material_files, "material files (default: the materials directory)");
    command->add_option("--dump-cpu", settings->options.cpu_dump_path,
                        "write the CPU results as raw float32, e.g. cpu.f32 (bit-for-bit comparisons)");
    command->add_option("--dump-dir", settings->options.dump_directory,
                        "write each executed path's raw results as DIR/<path>.f32 (and DIR/cpu.f32)");
    command->add_flag("--validation", settings->validation, "enable Vulkan validation layers");
    command->add_flag("--specialize", settings->options.specialize,
                      "one pipeline per feature-toggle set the materials need (default: the full pipeline)");
    command->callback([settings, context]() {
        run_command([&]() {
            ConformanceOptions options = settings->options;
            options.kernel_directory = context.kernel_directory;
            options.validation = settings->validation;
            const auto materials =
                conformance_materials(load_materials(settings->material_files, context.materials_directory));
            const ConformanceReport report = run_conformance(materials, options);
            // The JSON first, so that the report's last line is the verdict.
            if (!settings->json_path.empty())
            {
                write_json_file(settings->json_path, to_json(report));
                std::cout << "wrote " << settings->json_path << "\n";
            }
            std::cout << to_text(report);
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
