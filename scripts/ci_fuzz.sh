#!/usr/bin/env bash
# Builds the BSDF fuzzer (fuzz/fuzz_bsdf.cpp: libFuzzer + ASan + UBSan, clang) in its own build
# directory and runs it for a bounded time from the seed corpus in fuzz/corpus/. Exits non-zero
# on a finding (crash, sanitizer report, or a check in the harness); the input that triggered
# it is left in $build_dir/artifacts/ and printed as floats.
# Environment: OPENPBR_FUZZ_BUILD_DIR (default build-fuzz), OPENPBR_FUZZ_SECONDS (default 60),
# OPENPBR_FUZZ_RUNS (optional: stop after this many inputs, e.g. for a timing run).
# Runs are not repeatable (libFuzzer seeds from the clock, and even a fixed -seed diverges: two
# 300,000-input runs with -seed=1 -use_cmp=0 kept different corpora), so a finding is known only
# by its input: on a finding the harness's message and the input as floats are also written to
# $build_dir/finding.txt, which scripts/test.sh prints again at its end (CI logs keep the tail).
# Needs clang and libFuzzer (Debian: clang, libclang-rt-14-dev).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${OPENPBR_FUZZ_BUILD_DIR:-$repo_root/build-fuzz}
seconds=${OPENPBR_FUZZ_SECONDS:-60}

# shellcheck source=scripts/common.sh
source "$repo_root/scripts/common.sh"
mapfile -t common_flags < <(openpbr_cmake_flags)
cmake -S "$repo_root" -B "$build_dir" "${common_flags[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DOPENPBR_BUILD_HOST=OFF \
  -DOPENPBR_WARNINGS_AS_ERRORS="${OPENPBR_WARNINGS_AS_ERRORS:-OFF}" >/dev/null
cmake --build "$build_dir" --target fuzz_bsdf
fuzzer="$build_dir/fuzz/fuzz_bsdf"
[[ -x "$fuzzer" ]] || { echo "ci_fuzz: $fuzzer was not built (clang with -fsanitize=fuzzer needed)" >&2; exit 1; }

# New inputs go to a work corpus in the build directory; the seeds in the repository stay as they are.
work_corpus="$build_dir/corpus"
mkdir -p "$work_corpus" "$build_dir/artifacts"
runs=()
[[ -n "${OPENPBR_FUZZ_RUNS:-}" ]] && runs=(-runs="$OPENPBR_FUZZ_RUNS")
rm -f "$build_dir/finding.txt"
echo "ci_fuzz: fuzzing for at most ${seconds} s"
log="$build_dir/fuzz.log"
status=0
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=abort_on_error=1 \
  "$fuzzer" -max_total_time="$seconds" "${runs[@]}" -print_final_stats=1 -timeout=10 \
  -artifact_prefix="$build_dir/artifacts/" "$work_corpus" "$repo_root/fuzz/corpus" 2>&1 | tee "$log" || status=$?
if ((status != 0)); then
  # The harness's message (fuzz_bsdf: ... and the input floats), a sanitizer's report line, and
  # where libFuzzer left the input.
  {
    echo "ci_fuzz: finding (full log ${log})"
    grep -A 13 -E '^fuzz_bsdf: ' "$log" || true
    grep -E 'runtime error|ERROR: AddressSanitizer|SUMMARY: |Test unit written to' "$log" || true
  } >"$build_dir/finding.txt"
  cat "$build_dir/finding.txt"
  exit "$status"
fi
echo "ci_fuzz: no finding"
