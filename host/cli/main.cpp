// The `openpbr` command line: conformance and the other jobs of the host library. Every
// subcommand has the one shape of host/cli/command.h (add_<name>_subcommand in
// host/cli/<name>_command.cpp); main() only adds them and parses.
#include <string>

#include <CLI/CLI.hpp>

#include "host/cli/command.h"

#ifndef OPENPBR_DEFAULT_MATERIALS_DIR
#define OPENPBR_DEFAULT_MATERIALS_DIR "materials"
#endif
#ifndef OPENPBR_DEFAULT_KERNEL_DIR
#define OPENPBR_DEFAULT_KERNEL_DIR "kernels"
#endif

int main(int argc, char** argv)
{
    CLI::App app{"openpbr: OpenPBR 1.1.1 BSDF tools (conformance, table generation, ...)"};
    app.require_subcommand(1);

    std::string materials_directory = OPENPBR_DEFAULT_MATERIALS_DIR;
    std::string kernel_directory = OPENPBR_DEFAULT_KERNEL_DIR;
    app.add_option("--materials-dir", materials_directory, "directory of .mtlx materials")->capture_default_str();
    app.add_option("--kernel-dir", kernel_directory, "directory of compiled kernels")->capture_default_str();

    const openpbr::host::CommandContext context{materials_directory, kernel_directory};
    openpbr::host::add_conformance_subcommand(app, context);
    openpbr::host::add_lutgen_subcommand(app, context);
    openpbr::host::add_fuzzgen_subcommand(app, context);
    openpbr::host::add_compile_subcommand(app, context);
    openpbr::host::add_render_subcommand(app, context);
    openpbr::host::add_furnace_subcommand(app, context);
    openpbr::host::add_features_subcommand(app, context);
    openpbr::host::add_stability_subcommand(app, context);
    openpbr::host::add_bench_accuracy_subcommand(app, context);  // after "bench" exists (features)
    openpbr::host::add_accuracy_layering_subcommand(app, context);

    CLI11_PARSE(app, argc, argv);
    return 0;
}
