// accuracy_command.h - `openpbr bench accuracy [--json FILE] [--csv FILE] [--plot FILE.svg]
// [--quick] [--cache-dir DIR] [--no-compile]` (host/studies/accuracy.h). Adds "accuracy" under the
// "bench" subcommand, creating "bench" when no other part of the program has.
// Exit status: 0 on success, 1 on errors (e.g. an unwritable output path).
#pragma once

#include <CLI/CLI.hpp>

namespace openpbr::host {

// The ground truth and generated tables are cached in OPENPBR_DEFAULT_ACCURACY_CACHE (the build
// directory's accuracy-cache; --cache-dir overrides it); the Slang compile rows read the
// repository at OPENPBR_DEFAULT_SOURCE_ROOT. Call after every other subcommand is registered,
// so an existing "bench" is found.
CLI::App* add_bench_accuracy_subcommand(CLI::App& app);

}  // namespace openpbr::host
