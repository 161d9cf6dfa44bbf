#!/usr/bin/env bash
# Sourced, not run (needs repo_root): the part shared by the CI steps that build a subset of the CPU test programs
# in a build directory of their own and run them (scripts/ci_sanitizers.sh: Clang under ASan +
# UBSan; scripts/ci_clang_release.sh: Clang's Release build). The caller configures the build
# directory with Clang,
#   ci_configure_clang BUILD_DIR BUILD_TYPE [CMAKE_ARGUMENT ...]
# (warnings as errors when OPENPBR_WARNINGS_AS_ERRORS is set, as CI sets it), then calls
#   ci_build_and_run_tests STEP BUILD_DIR JOBS "program:gtest_filter" ...
# e.g. ci_build_and_run_tests ci_sanitizers build-sanitize 2 "test_volume:*": it builds only the
# named programs (and what they depend on), runs each with its filter and prints its time, and
# returns 1 when any program was not built or failed.
ci_configure_clang() {
  local build_dir=$1 build_type=$2
  shift 2
  local generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  cmake -S "$repo_root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE="$build_type" \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DOPENPBR_WARNINGS_AS_ERRORS="${OPENPBR_WARNINGS_AS_ERRORS:-OFF}" "$@" >/dev/null
}

ci_build_and_run_tests() {
  local step=$1 build_dir=$2 jobs=$3
  shift 3
  local entries=("$@") targets=() failed=() entry name filter executable start
  for entry in "${entries[@]}"; do
    targets+=("${entry%%:*}")
  done
  cmake --build "$build_dir" --parallel "$jobs" --target "${targets[@]}"
  for entry in "${entries[@]}"; do
    name=${entry%%:*}
    filter=${entry#*:}
    executable=$(find "$build_dir/tests" -type f -name "$name" -perm -u+x | head -n 1)
    if [[ -z "$executable" ]]; then
      echo "$step: $name was not built" >&2
      failed+=("$name")
      continue
    fi
    echo "$step: $name --gtest_filter=$filter"
    start=$(date +%s)
    if ! "$executable" --gtest_filter="$filter" --gtest_brief=1; then
      failed+=("$name")
    fi
    echo "$step: $name took $(($(date +%s) - start)) s"
  done
  if ((${#failed[@]})); then
    echo "$step: failed: ${failed[*]}" >&2
    return 1
  fi
  echo "$step: all passed"
}
