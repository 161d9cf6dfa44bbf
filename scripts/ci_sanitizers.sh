#!/usr/bin/env bash
# Runs the CPU unit tests under AddressSanitizer and UndefinedBehaviorSanitizer (clang,
# -fsanitize=address,undefined -fno-sanitize-recover=all: the first report fails the test) in
# their own build directory. Only the subset's targets are built (the host library, six test
# programs; the kernels they depend on are copied from build/, scripts/ci_test_subset.sh), not
# the whole project: the BSDF basics and lobe tests, thin film, volume, fuzz lobe, the input
# contract and the stability corpus on the CPU (docs/stability.md lists the timings). Left out:
# everything that creates a Vulkan context (the Vulkan loader and driver leak JIT allocations
# LeakSanitizer cannot attribute, and lavapipe's shaders run uninstrumented anyway) and the
# statistical suite (minutes under ASan).
# Environment: OPENPBR_SANITIZE_BUILD_DIR (default build-sanitize), OPENPBR_STABILITY_CPU_SAMPLES
# (samples per corpus case, default here 20000, against 200000 in the plain build: ASan and
# UBSan slow the BSDF down about 10x), OPENPBR_SANITIZE_JOBS (build jobs and test programs run
# at once, default nproc).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${OPENPBR_SANITIZE_BUILD_DIR:-$repo_root/build-sanitize}
jobs=${OPENPBR_SANITIZE_JOBS:-$(nproc)}
export OPENPBR_STABILITY_CPU_SAMPLES=${OPENPBR_STABILITY_CPU_SAMPLES:-20000}

# Test executables and the gtest filter each runs with (Vulkan paths left out).
tests=(
  "test_bsdf_basics:*"
  "test_thin_film:*"
  "test_volume:*"
  "test_fuzz_lobe:*"
  "test_input_contract:*"
  "test_stability_cpu:*"
)

sanitizers="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# shellcheck source=scripts/ci_test_subset.sh
source "$repo_root/scripts/ci_test_subset.sh"
# Debug information: line tables only (-gline-tables-only), which is what the sanitizers'
# reports print (function, file and line of every frame, inlined ones included); full -g made
# each translation unit about 9 % slower to compile (stability.cpp 10.4 s against 9.5 s of CPU,
# 2026-11-27) for variable and type information no report uses.
ci_configure_clang "$build_dir" RelWithDebInfo -DCMAKE_CXX_FLAGS="$sanitizers" -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
ci_build_and_run_tests ci_sanitizers "$build_dir" "$jobs" "${tests[@]}"
