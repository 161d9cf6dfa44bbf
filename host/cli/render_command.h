// render_command.h - the `openpbr render` subcommand (CLI11): gallery, furnace and
// CPU-versus-Vulkan comparison renders of the preview path tracer (host/preview/render.h).
//
//   openpbr::host::RenderCommand render = openpbr::host::add_render_subcommand(app);
//   ... CLI11_PARSE(app, argc, argv); ...
//   if (render.subcommand->parsed()) return openpbr::host::run_render_command(render, materials_dir, kernel_dir);
#pragma once

#include <memory>
#include <string>

namespace CLI {
class App;
}

namespace openpbr::host {

struct RenderCommandOptions;  // the parsed options; defined in render_command.cpp

struct RenderCommand {
    CLI::App* subcommand = nullptr;
    std::shared_ptr<RenderCommandOptions> options;  // CLI11 writes into it while parsing
};

// Registers "render" on the application.
RenderCommand add_render_subcommand(CLI::App& app);

// Runs a parsed render command; returns the process exit code (0 on success; 1 on errors,
// a failed furnace check or a failed comparison). Prints the output file names.
int run_render_command(const RenderCommand& command, const std::string& materials_directory,
                       const std::string& kernel_directory);

}  // namespace openpbr::host
