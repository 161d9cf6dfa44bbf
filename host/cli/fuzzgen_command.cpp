// `openpbr fuzzgen`: re-simulates the fuzz layer and refits its LTC table (host/tables/fuzz_fit.h)
// into openpbr_fuzz_ltc_values.inc, the tracked form; the build derives openpbr_fuzz_ltc.bin
// from it (tools/table_inc_to_bin.py). Exit status 0, or 1 on errors.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "host/cli/command.h"
#include "host/tables/fuzz_fit.h"

#ifndef OPENPBR_DEFAULT_GENERATED_DIR
#define OPENPBR_DEFAULT_GENERATED_DIR "slang/generated"
#endif

namespace openpbr::host {

namespace {

struct FuzzgenSettings
{
    FuzzFitOptions options;
    std::string output_directory = OPENPBR_DEFAULT_GENERATED_DIR;
};

}  // namespace

CLI::App* add_fuzzgen_subcommand(CLI::App& parent, const CommandContext&)
{
    auto settings = std::make_shared<FuzzgenSettings>();
    CLI::App* command = parent.add_subcommand("fuzzgen", "simulate the fuzz layer and fit its LTC table");
    command->add_option("--photons", settings->options.photons, "photons per table cell")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1024), std::uint64_t(1) << 34));
    command->add_option("--seed", settings->options.seed, "base seed of the per-cell streams")->capture_default_str();
    command
        ->add_option("-o,--output-dir", settings->output_directory,
                     "where openpbr_fuzz_ltc_values.inc goes (the build derives openpbr_fuzz_ltc.bin from it)")
        ->capture_default_str();
    command->add_flag("--progress", settings->options.progress,
                      "print progress on stderr (a line per 10 %, a bar on a terminal)");
    command->callback([settings]() {
        run_command([&]() {
            const std::vector<float> table = generate_fuzz_table(settings->options);
            const std::string values_path = settings->output_directory + "/openpbr_fuzz_ltc_values.inc";
            write_fuzz_values_inc(values_path, table);
            std::cout << "wrote " << values_path << " (" << table.size() << " values)\n";
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
