#!/usr/bin/env bash
# Sourced, not run (needs repo_root): the part shared by the CI steps that build a subset of the CPU test programs
# in a build directory of their own and run them (scripts/ci_sanitizers.sh: Clang under ASan +
# UBSan; scripts/ci_clang_release.sh: Clang's Release build). The caller configures the build
# directory with Clang,
#   ci_configure_clang BUILD_DIR BUILD_TYPE [CMAKE_ARGUMENT ...]
# (warnings as errors when OPENPBR_WARNINGS_AS_ERRORS is set, as CI sets it), then calls
#   ci_build_and_run_tests STEP BUILD_DIR JOBS "program:gtest_filter" ...
# e.g. ci_build_and_run_tests ci_sanitizers build-sanitize 2 "test_volume:*": it builds only the
# named programs (and what they depend on), runs each with its filter (JOBS at a time) and prints
# its output and time, and returns 1 when any program was not built or failed. Both record their parts' times
# (scripts/common.sh), e.g. "ci_sanitizers: build".
# The kernels are not compiled again: they are the same Slang and glslang outputs in every
# build directory, so the test programs here take them from the main build's kernel directory
# (OPENPBR_PREBUILT_KERNEL_DIR in CMakeLists.txt), built by scripts/setup.sh before these steps.
# Environment: OPENPBR_BUILD_DIR (default build), whose kernels/ is used when it holds them.
# shellcheck source=scripts/common.sh
source "$repo_root/scripts/common.sh"
step_times_init

ci_configure_clang() {
  local build_dir=$1 build_type=$2
  shift 2
  local common_flags kernel_flags=() main_kernels="${OPENPBR_BUILD_DIR:-$repo_root/build}/kernels"
  mapfile -t common_flags < <(openpbr_cmake_flags)
  [[ -f "$main_kernels/conformance.slang.spv" ]] && kernel_flags=(-DOPENPBR_PREBUILT_KERNEL_DIR="$main_kernels")
  step_run "$(basename "$0" .sh): configure" step cmake -S "$repo_root" -B "$build_dir" "${common_flags[@]}" \
    -DCMAKE_BUILD_TYPE="$build_type" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DOPENPBR_WARNINGS_AS_ERRORS="${OPENPBR_WARNINGS_AS_ERRORS:-OFF}" "${kernel_flags[@]}" "$@" >/dev/null
}

ci_build_and_run_tests() {
  local step=$1 build_dir=$2 jobs=$3
  shift 3
  local entries=("$@") targets=() failed=() entry name filter executable
  for entry in "${entries[@]}"; do
    targets+=("${entry%%:*}")
  done
  step_run "$step: build" step cmake --build "$build_dir" --parallel "$jobs" --target "${targets[@]}" || return 1
  local tests_start=$EPOCHREALTIME tests_cpu_start
  step_times_children_cpu
  tests_cpu_start=$step_times_cpu
  # The programs run JOBS at a time: each is one process on one core, so one after another they
  # left the other core idle (scripts/ci_clang_release.sh: 97 s of tests, 64 s of them
  # test_bsdf_basics, docs/stability.md). Each writes its own log, printed whole in list order.
  local log_dir index=0 running=0 status seconds
  log_dir=$(mktemp -d)
  for entry in "${entries[@]}"; do
    name=${entry%%:*}
    filter=${entry#*:}
    executable=$(find "$build_dir/tests" -type f -name "$name" -perm -u+x | head -n 1)
    if [[ -z "$executable" ]]; then
      echo "$step: $name was not built" >"$log_dir/$index.log"
      echo "127 0" >"$log_dir/$index.status"
    else
      if ((running >= jobs)); then
        wait -n || true
        running=$((running - 1))
      fi
      (
        start=$EPOCHREALTIME
        status=0
        "$executable" --gtest_filter="$filter" --gtest_brief=1 >"$log_dir/$index.log" 2>&1 || status=$?
        echo "$status $(awk -v start="$start" -v end="$EPOCHREALTIME" 'BEGIN { printf "%.0f", end - start }')" \
          >"$log_dir/$index.status"
      ) &
      running=$((running + 1))
    fi
    index=$((index + 1))
  done
  wait
  index=0
  for entry in "${entries[@]}"; do
    name=${entry%%:*}
    echo "$step: $name --gtest_filter=${entry#*:}"
    cat "$log_dir/$index.log"
    read -r status seconds <"$log_dir/$index.status"
    ((status == 0)) || failed+=("$name")
    echo "$step: $name took $seconds s$( ((status == 0)) || echo ", exit status $status")"
    index=$((index + 1))
  done
  rm -rf "$log_dir"
  step_times_children_cpu
  awk -v step="$step" -v start="$tests_start" -v end="$EPOCHREALTIME" -v failed=$((${#failed[@]} > 0)) \
    -v cpu=$((step_times_cpu - tests_cpu_start)) -v ticks="$step_times_clock_ticks" \
    'BEGIN { printf "%s: tests\tstep\t%.1f\t%.1f\t%d\n", step, end - start, cpu / ticks, failed }' >>"$OPENPBR_STEP_TIMES_FILE"
  if ((${#failed[@]})); then
    echo "$step: failed: ${failed[*]}" >&2
    return 1
  fi
  echo "$step: all passed"
}
