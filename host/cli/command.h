// command.h - the one shape of every `openpbr` subcommand (CLI11). Each lives in
// host/cli/<name>_command.cpp as
//   CLI::App* add_<name>_subcommand(CLI::App& parent, const CommandContext& context);
// which registers the subcommand's options on `parent` and, as its CLI11 callback, runs it
// through run_command, so that main() only adds the subcommands and parses:
//   const openpbr::host::CommandContext context{materials_directory, kernel_directory};
//   openpbr::host::add_furnace_subcommand(app, context);
//   CLI11_PARSE(app, argc, argv);
// Exit status: what the action returns (0 success; 2 for a check that found a failure, as each
// subcommand documents), 1 with "openpbr: error: ..." on stderr when it throws.
#pragma once

#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

namespace openpbr::host {

// The application's shared options, bound to --materials-dir and --kernel-dir: references, read
// when a subcommand runs (after parsing), never when it is added.
struct CommandContext
{
    const std::string& materials_directory;
    const std::string& kernel_directory;
};

// The subcommands, in the order main() adds them ("bench accuracy" after "features", which
// creates "bench"). Exit statuses beyond 0 and 1 are documented in each file.
CLI::App* add_conformance_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_lutgen_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_fuzzgen_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_compile_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_render_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_furnace_subcommand(CLI::App& parent, const CommandContext& context);
// `features` and `bench` with `bench specialization` and `bench gpu`; returns `features`.
CLI::App* add_features_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_stability_subcommand(CLI::App& parent, const CommandContext& context);
CLI::App* add_bench_accuracy_subcommand(CLI::App& parent, const CommandContext& context);
// `accuracy layering` (and `accuracy` when no other subcommand created it).
CLI::App* add_accuracy_layering_subcommand(CLI::App& parent, const CommandContext& context);

// Runs `action` (returning the exit status) as a subcommand's callback: a non-zero status and
// any std::exception become CLI::RuntimeError(status), which CLI11_PARSE returns from main().
template <typename Action> void run_command(Action&& action)
{
    int status = 0;
    try
    {
        status = action();
    }
    catch (const CLI::Error&)
    {
        throw;
    }
    catch (const std::exception& error)
    {
        std::cerr << "openpbr: error: " << error.what() << "\n";
        status = 1;
    }
    if (status != 0)
    {
        throw CLI::RuntimeError(status);
    }
}

}  // namespace openpbr::host
