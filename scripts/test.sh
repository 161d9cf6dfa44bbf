#!/usr/bin/env bash
# The whole test suite: set up what is missing, build, run every test through ctest, then the
# installed package as outside projects use it (scripts/ci_consumers.sh: install to a temporary
# prefix, build and run the three consumers of examples/), then the stability checks of
# docs/stability.md: the BSDF fuzzer for a bounded time (scripts/ci_fuzz.sh, 60 s) and the CPU
# unit tests under ASan + UBSan (scripts/ci_sanitizers.sh) and in Clang's Release build
# (scripts/ci_clang_release.sh), and the format check of the C, C++ and CUDA sources against
# .clang-format (scripts/format-check.sh) with the word check of tracked text
# (scripts/check-words.sh: no names of work rounds, no tracker numbers), the link check of the
# Markdown (scripts/check-links.py) and the function length check (scripts/check-function-length.sh:
# none over 150 lines, 200 in slang/). Every step runs even when an earlier one fails; the
# script fails if any did. OPENPBR_SKIP_CONSUMERS=1, OPENPBR_SKIP_SANITIZERS=1,
# OPENPBR_SKIP_CLANG_RELEASE=1, OPENPBR_SKIP_FUZZ=1 and OPENPBR_SKIP_FORMAT=1 leave those steps
# out, e.g. for a quick local run. Prints a table of each step's wall and CPU time at the end
# (scripts/common.sh; docs/ci-time.md has the measured ones).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=scripts/common.sh
source "$repo_root/scripts/common.sh"
step_times_init
"$repo_root/scripts/setup.sh"
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
failed=()
ctest_status=0
step_run "ctest" step ctest --test-dir "$build_dir" --output-on-failure --parallel "$(nproc)" "$@" || ctest_status=$?
((ctest_status == 0)) || failed+=(ctest)
if [[ "${OPENPBR_SKIP_CONSUMERS:-0}" != 1 ]]; then
  step_run "ci_consumers" step "$repo_root/scripts/ci_consumers.sh" || failed+=(ci_consumers)
fi
# The fuzzer, the sanitizer and the Clang Release steps run at the same time, each into its own
# log, printed whole in this order. The fuzzer is one process on one core for 60 s, one after
# another it left the other core idle for that minute; each Clang step ends with its test
# programs, whose longest (test_bsdf_basics) ran alone for half a minute likewise. The Clang
# steps run at a lower priority (nice 10) than the fuzzer, so that the fuzzer keeps a core of
# its own: the number of inputs it tries in its 60 s is its power (docs/ci-time.md has the
# inputs per second alone and beside them). The same builds, tests and fuzzing; in the step
# table their wall times overlap.
side_steps=()
[[ "${OPENPBR_SKIP_FUZZ:-0}" == 1 ]] || side_steps+=(ci_fuzz)
[[ "${OPENPBR_SKIP_SANITIZERS:-0}" == 1 ]] || side_steps+=(ci_sanitizers)
[[ "${OPENPBR_SKIP_CLANG_RELEASE:-0}" == 1 ]] || side_steps+=(ci_clang_release)
side_step_pids=()
side_step_logs=$(mktemp -d)
for step in "${side_steps[@]}"; do
  priority=()
  [[ "$step" == ci_fuzz ]] || priority=(nice -n 10)
  step_run "$step" step "${priority[@]}" "$repo_root/scripts/$step.sh" >"$side_step_logs/$step.log" 2>&1 &
  side_step_pids+=($!)
done
for index in "${!side_steps[@]}"; do
  step_status=0
  wait "${side_step_pids[$index]}" || step_status=$?
  cat "$side_step_logs/${side_steps[$index]}.log"
  ((step_status == 0)) || failed+=("${side_steps[$index]}")
done
rm -rf "$side_step_logs"
if [[ "${OPENPBR_SKIP_FORMAT:-0}" != 1 ]]; then
  step_run "format-check" step "$repo_root/scripts/format-check.sh" || failed+=(format-check)
  step_run "check-words" step "$repo_root/scripts/check-words.sh" || failed+=(check-words)
  step_run "check-links" step "$repo_root/scripts/check-links.py" || failed+=(check-links)
  step_run "check-function-length" step "$repo_root/scripts/check-function-length.sh" || failed+=(check-function-length)
fi
if ((${#failed[@]})); then
  # A fuzz finding again at the end, where a truncated CI log still shows it.
  fuzz_finding="${OPENPBR_FUZZ_BUILD_DIR:-$repo_root/build-fuzz}/finding.txt"
  [[ " ${failed[*]} " == *" ci_fuzz "* && -f "$fuzz_finding" ]] && cat "$fuzz_finding" >&2
  echo "test: failed: ${failed[*]}" >&2
  # ctest's own status when it failed (e.g. 8 for failed tests), 1 otherwise.
  exit $((ctest_status != 0 ? ctest_status : 1))
fi
