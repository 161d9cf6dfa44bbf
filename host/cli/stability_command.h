// `openpbr stability`: the hard-case corpus on the CPU build and every GPU path (host/checks/stability.h).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace openpbr::host {

// Adds the subcommand to `app`. `kernel_directory` is read when the subcommand runs (after
// parsing), so it may be the variable bound to the app's own --kernel-dir option. The
// subcommand prints the text report, writes --json, and exits with status 2 when any path
// produced a non-finite or negative output (status 1 on errors, e.g. a bad corpus).
CLI::App* add_stability_subcommand(CLI::App& app, const std::string& default_corpus, const std::string& kernel_directory);

}  // namespace openpbr::host
