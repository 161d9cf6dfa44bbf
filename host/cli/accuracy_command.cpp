// `openpbr bench accuracy`: error and time of every accuracy knob (host/studies/accuracy.h,
// docs/accuracy-vs-time.md) as a table and, on request, JSON, CSV and an SVG plot. Exit status
// 0, or 1 on errors.
#include "host/cli/command.h"

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
    std::string plot_path;
    std::string cache_directory;
    bool no_compile = false;
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
    command->add_option("--json", settings->json_path, "write {\"rows\": [...]} to this file, e.g. accuracy.json");
    command->add_option("--csv", settings->csv_path, "write the rows as CSV, e.g. accuracy.csv");
    command->add_option("--plot", settings->plot_path, "write the error-vs-time plot (SVG), e.g. accuracy.svg");
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
    command->add_flag("--no-compile", settings->no_compile, "skip the Slang compile-time rows");
    command->add_flag("--no-progress", settings->no_progress, "no progress bar on stderr");
    command->callback([settings]() {
        run_command([&]() {
            AccuracyOptions options = settings->options;
            options.cache_directory = settings->cache_directory;
            options.compile = options.compile && !settings->no_compile;
            options.progress = !settings->no_progress;
            const std::vector<AccuracyRow> rows = run_accuracy_study(options);
            std::cout << accuracy_to_text(rows);
            if (!settings->json_path.empty())
            {
                write_json_file(settings->json_path, accuracy_to_json(rows));
                std::cout << "wrote " << settings->json_path << "\n";
            }
            if (!settings->csv_path.empty())
            {
                write_text_file(settings->csv_path, accuracy_to_csv(rows));
                std::cout << "wrote " << settings->csv_path << "\n";
            }
            if (!settings->plot_path.empty())
            {
                write_text_file(settings->plot_path, accuracy_to_svg(rows));
                std::cout << "wrote " << settings->plot_path << "\n";
            }
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
