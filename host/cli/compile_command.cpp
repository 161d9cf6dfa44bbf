// `openpbr compile`: emits the shaders of every target (host/gpu/compile_targets.h) and prints
// what it wrote and how long each took. Exit status 0, or 1 on errors (e.g. a failed compiler).
#include <iostream>
#include <memory>

#include "host/cli/command.h"
#include "host/gpu/compile_targets.h"

namespace openpbr::host {

CLI::App* add_compile_subcommand(CLI::App& parent, const CommandContext&)
{
    auto options = std::make_shared<CompileTargetsOptions>(default_compile_targets_options());
    CLI::App* command =
        parent.add_subcommand("compile", "emit the shaders of every target (SPIR-V, HLSL, Metal, CUDA, GLSL, WGSL)");
    command->add_option("--target", options->targets, "spirv, hlsl, metal, cuda, glsl, wgsl or all")
        ->delimiter(',')
        ->check(CLI::IsMember({"spirv", "hlsl", "metal", "cuda", "glsl", "wgsl", "all"}));
    command->add_option("-o,--output-dir", options->output_directory, "output directory")->required();
    command->callback([options]() {
        run_command([&]() {
            std::cout << to_text(compile_targets(*options));
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
