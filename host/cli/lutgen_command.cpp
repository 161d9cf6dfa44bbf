// `openpbr lutgen`: regenerates the energy-compensation tables (host/tables/lut_generator.h) into
// openpbr_lut_values.inc and the thin film's lobe table (host/tables/film_table_generator.h) into
// openpbr_film_lut_values.inc, the tracked forms; the build derives openpbr_lut.bin from the two
// (tools/table_inc_to_bin.py). `--only compensation` or `--only film` writes one of them.
// Exit status 0, or 1 on errors.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "host/cli/command.h"
#include "host/tables/film_table_generator.h"
#include "host/tables/lut_generator.h"

#ifndef OPENPBR_DEFAULT_GENERATED_DIR
#define OPENPBR_DEFAULT_GENERATED_DIR "slang/generated"
#endif

namespace openpbr::host {

namespace {

struct LutgenSettings
{
    LutGeneratorOptions options;
    FilmTableOptions film_options;
    std::string only;  // "" both, "compensation" or "film", e.g. film
    std::string output_directory = OPENPBR_DEFAULT_GENERATED_DIR;
};

}  // namespace

CLI::App* add_lutgen_subcommand(CLI::App& parent, const CommandContext&)
{
    auto settings = std::make_shared<LutgenSettings>();
    CLI::App* command = parent.add_subcommand("lutgen", "generate the energy-compensation tables (Monte Carlo)");
    LutGeneratorOptions& options = settings->options;
    command->add_option("--size-2d", options.size_2d, "nodes per axis of the 2D table")
        ->capture_default_str()
        ->check(CLI::Range(2, 256));
    command->add_option("--size-3d", options.size_3d, "nodes on the view and roughness axes of the 3D tables")
        ->capture_default_str()
        ->check(CLI::Range(2, 128));
    command->add_option("--size-3d-eta", options.size_3d_eta, "nodes on the eta axis of the 3D tables (even)")
        ->capture_default_str()
        ->check(CLI::Range(6, 128));
    command->add_option("--samples", options.samples, "Monte Carlo samples per table cell")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 30));
    command->add_option("--bits", options.bits, "32 (float) or 16 (values rounded to half precision)")
        ->capture_default_str()
        ->check(CLI::IsMember({16, 32}));
    command->add_option("--seed", options.seed, "0 = the shipped tables; others give independent replicas")
        ->capture_default_str();
    command
        ->add_option("-o,--output-dir", settings->output_directory,
                     "where openpbr_lut_values.inc goes (the build derives openpbr_lut.bin from it)")
        ->capture_default_str();
    command->add_flag("--progress", options.progress_always, "print progress even when stderr is not a terminal");
    command->add_option("--only", settings->only, "write one file only: compensation (tables 0-4) or film (table 5)")
        ->check(CLI::IsMember({"compensation", "film"}));
    command
        ->add_option("--film-lattice", settings->film_options.lattice_size,
                     "reference points per axis of each film-table cell (e.g. 256: 65536 per cell)")
        ->capture_default_str()
        ->check(CLI::Range(2, 4096));
    command->callback([settings]() {
        run_command([&]() {
            if (settings->only != "film")
            {
                const std::vector<float> table = generate_lut(settings->options);
                const std::string values_path = settings->output_directory + "/openpbr_lut_values.inc";
                write_lut_values_inc(values_path, table, describe(settings->options));
                std::cout << "wrote " << values_path << " (" << table.size() << " values, " << describe(settings->options)
                          << ")\n";
            }
            if (settings->only != "compensation")
            {
                const std::vector<float> film_table = generate_film_table(settings->film_options);
                const std::string film_path = settings->output_directory + "/openpbr_film_lut_values.inc";
                write_lut_values_inc(film_path, film_table, describe(settings->film_options));
                std::cout << "wrote " << film_path << " (" << film_table.size() << " values, "
                          << describe(settings->film_options) << ")\n";
            }
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
