#!/usr/bin/env bash
# Builds the CPU unit tests with Clang in the Release configuration (-O3 -DNDEBUG; warnings as
# errors when OPENPBR_WARNINGS_AS_ERRORS is set, as CI sets it) in their own build directory and
# runs them. ctest runs GCC's RelWithDebInfo build and the sanitizers run Clang with their
# instrumentation, so without this step no CI build is a plain optimized Clang one: that is where
# Clang folds constant expressions with fused multiply-adds (-ffp-contract=on) that run as
# separate ones, and a test comparing a folded value with a run-time one bit for bit failed
# there only (ParameterTable.LoaderStoresEveryInputInItsField, 2026-11-27). Only the subset's
# programs are built: the BSDF, its math and lobes, the thin film and its estimate, the volume,
# the input contract, the parameter table, the MaterialX loader, the established API, and the
# stability corpus on the CPU. Left out, as in scripts/ci_sanitizers.sh: what creates a Vulkan
# context (lavapipe compiles the kernels, not Clang) and the statistical suite (minutes).
# Environment: OPENPBR_CLANG_RELEASE_BUILD_DIR (default build-clang-release),
# OPENPBR_CLANG_RELEASE_JOBS (build jobs and test programs run at once, default nproc),
# OPENPBR_STABILITY_CPU_SAMPLES (samples per corpus case, default here 20000 as under the
# sanitizers, e.g. 200000 for the full count).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${OPENPBR_CLANG_RELEASE_BUILD_DIR:-$repo_root/build-clang-release}
jobs=${OPENPBR_CLANG_RELEASE_JOBS:-$(nproc)}
export OPENPBR_STABILITY_CPU_SAMPLES=${OPENPBR_STABILITY_CPU_SAMPLES:-20000}

# Test executables and the gtest filter each runs with (Vulkan paths left out).
tests=(
  "test_bsdf_basics:*"
  "test_math:*"
  "test_thin_film:*"
  "test_film_estimate:*"
  "test_film_table:*"
  "test_volume:*"
  "test_fuzz_lobe:*"
  "test_coat_frame:*"
  "test_input_contract:*"
  "test_parameter_table:*"
  "test_material_library:*"
  "test_established_api:*"
  "test_stability_cpu:*"
)

# shellcheck source=scripts/ci_test_subset.sh
source "$repo_root/scripts/ci_test_subset.sh"
ci_configure_clang "$build_dir" Release -DOPENPBR_BUILD_FUZZ=OFF
ci_build_and_run_tests ci_clang_release "$build_dir" "$jobs" "${tests[@]}"
