// furnace_command.h - the `openpbr furnace` subcommand (CLI11): the white furnace of
// host/checks/furnace.h as a table and, with --json FILE, as
// {"configs": [{"name": s, "cos_theta": c, "albedo": [r, g, b], ...}]}.
//
//   openpbr::host::FurnaceCommand furnace = openpbr::host::add_furnace_subcommand(app);
//   ... CLI11_PARSE(app, argc, argv); ...
//   if (furnace.subcommand->parsed()) return openpbr::host::run_furnace_command(furnace);
#pragma once

#include <memory>

namespace CLI {
class App;
}

namespace openpbr::host {

struct FurnaceCommandOptions;  // the parsed options; defined in furnace_command.cpp

struct FurnaceCommand {
    CLI::App* subcommand = nullptr;
    std::shared_ptr<FurnaceCommandOptions> options;  // CLI11 writes into it while parsing
};

// Registers "furnace" on the application.
FurnaceCommand add_furnace_subcommand(CLI::App& app);

// Runs a parsed furnace command; returns the process exit code: 0 when every configuration is
// within its tolerance, 2 when one is not, 1 on errors (e.g. an unwritable JSON path).
int run_furnace_command(const FurnaceCommand& command);

}  // namespace openpbr::host
