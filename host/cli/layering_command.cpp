// `openpbr accuracy layering`: the shipped model's layering against the layered ground truth,
// per material and view cosine (host/studies/layering_accuracy.h, docs/layering-accuracy.md):
// a table on stdout, the rows as JSON on request, and the picture strip. Exit status 0, or 1
// on errors (unreadable materials, bad options, unwritable outputs).
#include "host/cli/command.h"

#include <iostream>
#include <memory>

#include "host/cli/output_files.h"
#include "host/studies/layering_accuracy.h"
#include "host/support/stopwatch.h"

namespace openpbr::host {
namespace {

struct LayeringCommandSettings
{
    LayeringOptions options;
    std::vector<std::string> material_files;
    bool grid = false;
    bool quick = false;
    bool no_progress = false;
    std::string json_path;
    std::string pictures_path;
    LayeringPictureOptions pictures;
};

// The strip's materials: the grid's coated metal and the bundled car paint.
std::vector<LayeringMaterial> picture_materials(const std::string& materials_directory)
{
    std::vector<LayeringMaterial> chosen;
    for (const LayeringMaterial& material : layering_grid_materials())
    {
        if (material.name == "metal, coat")
        {
            chosen.push_back(material);
        }
    }
    for (const LayeringMaterial& material : layering_materials_from_files({materials_directory + "/open_pbr_carpaint.mtlx"}))
    {
        chosen.push_back(material);
    }
    return chosen;
}

int run_layering(const LayeringCommandSettings& settings, const CommandContext& context)
{
    LayeringOptions options = settings.options;
    options.progress = !settings.no_progress;
    if (settings.quick)
    {
        options.reference_paths = 1u << 12;
        options.model_samples = 1u << 15;
        options.timing_queries = 512;
        options.view_cosines = {1.0, 0.4};
    }
    const Stopwatch watch;
    std::vector<LayeringMaterial> materials = settings.material_files.empty()
                                                  ? layering_materials_from_directory(context.materials_directory)
                                                  : layering_materials_from_files(settings.material_files);
    if (settings.grid)
    {
        const std::vector<LayeringMaterial> grid = layering_grid_materials();
        materials.insert(materials.end(), grid.begin(), grid.end());
    }
    const std::vector<LayeringRow> rows = run_layering_study(materials, options);
    const double seconds = watch.seconds();
    std::cout << layering_to_text(rows);
    std::cout << rows.size() << " rows in " << seconds << " s\n";
    if (!settings.json_path.empty())
    {
        write_text_file(settings.json_path, layering_json_text(layering_to_json(rows, options, seconds)));
        std::cout << "wrote " << settings.json_path << "\n";
    }
    if (!settings.pictures_path.empty())
    {
        LayeringPictureOptions pictures = settings.pictures;
        pictures.threads = options.threads;
        if (settings.quick)
        {
            pictures.size = 32;
            pictures.samples = 16;
        }
        for (const LayeringPictureStats& entry :
             write_layering_pictures(settings.pictures_path, picture_materials(context.materials_directory), pictures))
        {
            std::cout << "picture " << entry.material << ": rms difference " << entry.rms_difference << ", rms noise "
                      << entry.rms_noise << ", " << entry.seconds << " s\n";
        }
        std::cout << "wrote " << settings.pictures_path << "\n";
    }
    return 0;
}

}  // namespace

CLI::App* add_accuracy_layering_subcommand(CLI::App& parent, const CommandContext& context)
{
    CLI::App* accuracy = nullptr;
    try
    {
        accuracy = parent.get_subcommand("accuracy");
    }
    catch (const CLI::OptionNotFound&)
    {
        accuracy = parent.add_subcommand("accuracy", "the model's own errors against ground truths");
        accuracy->require_subcommand(1);
    }
    CLI::App* command = accuracy->add_subcommand(
        "layering", "the layering model against the layered ground truth, per material (docs/layering-accuracy.md)");
    auto settings = std::make_shared<LayeringCommandSettings>();
    command->add_option("--materials", settings->material_files,
                        "MaterialX files to study (default: every .mtlx in --materials-dir), e.g. my.mtlx");
    command->add_flag("--grid", settings->grid, "also the parameter grid over coat, fuzz, film and base type");
    command->add_option("--json", settings->json_path, "write {\"rows\": [...], \"summary\": {...}}, e.g. layering.json");
    command->add_option("--samples", settings->options.reference_paths, "reference paths per material and view")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(16), std::uint64_t(1) << 32));
    command->add_option("--model-samples", settings->options.model_samples, "model samples per material and view")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(16), std::uint64_t(1) << 32));
    command->add_option("--view-cosines", settings->options.view_cosines, "view cosines in (0, 1], e.g. 1 0.5 0.2")
        ->capture_default_str();
    command->add_option("--threads", settings->options.threads, "worker threads (0: every core)")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));
    command->add_option(
        "--pictures", settings->pictures_path,
        "write the picture strip (coated metal and car paint: reference | model | difference), e.g. strip.png");
    command->add_option("--picture-samples", settings->pictures.samples, "paths and samples per pixel of the strip")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 20));
    command->add_option("--picture-size", settings->pictures.size, "pixels per sphere of the strip")
        ->capture_default_str()
        ->check(CLI::Range(8, 1024));
    command->add_flag("--quick", settings->quick, "small sample counts and two views (seconds; for tests)");
    command->add_flag("--no-progress", settings->no_progress, "no progress on stderr");
    command->callback([settings, context]() { run_command([&]() { return run_layering(*settings, context); }); });
    return command;
}

}  // namespace openpbr::host
