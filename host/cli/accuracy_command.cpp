// `openpbr bench accuracy`: error and time of every accuracy knob (host/studies/accuracy.h,
// docs/accuracy-vs-time.md) as a table and, on request, JSON, CSV and the picture strips' images
// (tools/accuracy_figures.py draws the figures from them). Exit status 0, or 1 on errors.
#include "host/cli/command.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "host/studies/accuracy.h"
#include "host/cli/output_files.h"

namespace openpbr::host {
namespace {

struct AccuracyCommandSettings
{
    AccuracyOptions options;
    std::string json_path;
    std::string csv_path;
    std::string cache_directory;
    std::string layering_json;
    std::string pictures_directory;
    bool no_compile = false;
    bool webgpu = false;
    bool no_progress = false;
};

}  // namespace

#ifndef OPENPBR_DEFAULT_ACCURACY_CACHE
#define OPENPBR_DEFAULT_ACCURACY_CACHE "accuracy-cache"
#endif
#ifndef OPENPBR_DEFAULT_SOURCE_ROOT
#define OPENPBR_DEFAULT_SOURCE_ROOT "."
#endif

CLI::App* add_bench_accuracy_subcommand(CLI::App& parent, const CommandContext&)
{
    const std::string default_cache_directory = OPENPBR_DEFAULT_ACCURACY_CACHE;
    const std::string repository_root = OPENPBR_DEFAULT_SOURCE_ROOT;
    CLI::App* bench = nullptr;
    try
    {
        bench = parent.get_subcommand("bench");
    }
    catch (const CLI::OptionNotFound&)
    {
        bench = parent.add_subcommand("bench", "measurements of the BSDF's cost");
        bench->require_subcommand(1);
    }
    CLI::App* command =
        bench->add_subcommand("accuracy", "error and time of every accuracy knob (docs/accuracy-vs-time.md)");
    auto settings = std::make_shared<AccuracyCommandSettings>();
    settings->cache_directory = default_cache_directory;
    settings->options.repository_root = repository_root;
    settings->layering_json = (std::filesystem::path(repository_root) / "docs" / "layering-accuracy.json").string();
    command->add_option("--json", settings->json_path,
                        "write {\"run\", \"families\", \"model_floors\", \"rows\"} to this file, e.g. accuracy.json");
    command->add_option("--csv", settings->csv_path, "write the flat rows as CSV, e.g. accuracy.csv");
    command->add_option("--pictures", settings->pictures_directory,
                        "write the picture strips' float32 images and manifest.json here, e.g. build/accuracy-pictures");
    command->add_option("--layering", settings->layering_json,
                        "`openpbr accuracy layering`'s JSON for the layering floor (default: docs/layering-accuracy.json)");
    command->add_flag("--quick", settings->options.quick, "small grids and sample counts (seconds; for tests)");
    command->add_option("--cache-dir", settings->cache_directory,
                        "ground-truth and table cache (default: the build directory's accuracy-cache)");
    command->add_option("--walk-paths", settings->options.walk_paths, "random-walk paths per ground-truth point")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 30));
    command->add_option("--albedo-samples", settings->options.albedo_samples, "BSDF samples per albedo estimate")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 24));
    command->add_option("--timing-queries", settings->options.timing_queries, "queries per timing batch")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 24));
    command->add_option("--table-samples", settings->options.table_samples, "samples per node of the 16/64 tables")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 24));
    command->add_option("--rounds", settings->options.timing_rounds, "CPU timing rounds (best and median kept)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    command->add_flag("--no-compile", settings->no_compile, "no GPU rows (no Slang compile, lavapipe or SwiftShader)");
    command->add_flag("--webgpu", settings->webgpu,
                      "also time each setting on SwiftShader through Dawn (WebGPU; about 20 s to 2 min per setting)");
    command->add_flag("--no-progress", settings->no_progress, "no progress bar on stderr");
    command->callback([settings]() {
        run_command([&]() {
            AccuracyOptions options = settings->options;
            options.cache_directory = settings->cache_directory;
            options.gpu = options.gpu && !settings->no_compile;
            options.webgpu = settings->webgpu;
            options.layering_json = settings->layering_json;
            options.pictures_directory = settings->pictures_directory;
            options.progress = !settings->no_progress;
            const AccuracyReport report = run_accuracy_study(options);
            std::cout << accuracy_to_text(report);
            if (!settings->json_path.empty())
            {
                write_json_file(settings->json_path, accuracy_to_json(report));
                std::cout << "wrote " << settings->json_path << "\n";
            }
            if (!settings->csv_path.empty())
            {
                write_text_file(settings->csv_path, accuracy_to_csv(report));
                std::cout << "wrote " << settings->csv_path << "\n";
            }
            if (!settings->pictures_directory.empty())
            {
                std::cout << "wrote " << settings->pictures_directory << "/manifest.json\n";
            }
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
