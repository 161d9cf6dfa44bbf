// `openpbr features` and `openpbr bench specialization` (CLI11 subcommands).
//
//   openpbr features materials/open_pbr_glass.mtlx materials/open_pbr_gold.mtlx [--json FILE]
//       [--pipeline coat,metal]
// prints each material's toggle set, the smallest set for the whole scene and the
// specialization info (VkSpecializationInfo map entries and data) for vkCreateComputePipelines;
// with --pipeline it checks a given toggle set and exits 3 naming the material and feature a
// pipeline with that set would drop.
//
//   openpbr bench specialization [--json FILE] [--queries N] [--path slang-spirv] [--cpu-only]
// measures full versus specialized (host/studies/bench_specialization.h).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace openpbr::host {

// Adds "features" and "bench" to `app`; the directories are read when a subcommand runs, so
// they may be the variables bound to the app's --materials-dir and --kernel-dir options.
void add_features_subcommands(CLI::App& app, const std::string& materials_directory, const std::string& kernel_directory);

}  // namespace openpbr::host
