#include "host/cli/furnace_command.h"

#include <fstream>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "host/checks/furnace.h"
#include "host/cli/output_files.h"

namespace openpbr::host {

struct FurnaceCommandOptions
{
    FurnaceOptions furnace;
    std::string json_path;  // e.g. furnace.json; empty = table only
};

FurnaceCommand add_furnace_subcommand(CLI::App& app)
{
    FurnaceCommand command;
    command.options = std::make_shared<FurnaceCommandOptions>();
    command.subcommand = app.add_subcommand("furnace", "white furnace: directional albedo of white configurations");
    command.subcommand->add_option("--json", command.options->json_path, "write {\"configs\": [...]} to this file");
    command.subcommand->add_option("--samples", command.options->furnace.samples, "samples per configuration and view")
        ->capture_default_str()->check(CLI::Range(std::uint64_t(1024), std::uint64_t(1) << 32));
    command.subcommand->add_option("--filter", command.options->furnace.name_filter,
                                   "only configurations whose name contains this, e.g. glass");
    return command;
}

int run_furnace_command(const FurnaceCommand& command)
{
    try
    {
        const std::vector<FurnaceRow> rows = run_white_furnace(command.options->furnace);
        if (rows.empty())
        {
            throw std::runtime_error("no configuration matches --filter '" + command.options->furnace.name_filter + "'");
        }
        std::cout << furnace_to_text(rows);
        if (!command.options->json_path.empty())
        {
            write_json_file(command.options->json_path, furnace_to_json(rows));
            std::cout << "wrote " << command.options->json_path << "\n";
        }
        std::size_t failures = 0;
        for (const FurnaceRow& row : rows)
        {
            failures += row.within_tolerance ? 0 : 1;
        }
        std::cout << rows.size() - failures << " of " << rows.size() << " within tolerance (|1 - albedo| <= "
                  << furnace_tolerance << " for cos >= " << furnace_tolerance_min_cos << ", albedo <= " << furnace_max_albedo
                  << " everywhere)\n";
        return failures == 0 ? 0 : 2;
    }
    catch (const std::exception& error)
    {
        std::cerr << "openpbr furnace: error: " << error.what() << "\n";
        return 1;
    }
}

}  // namespace openpbr::host
