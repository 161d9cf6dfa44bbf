#!/usr/bin/env bash
# Sourced, not run: what scripts/setup.sh, run.sh, test.sh and the CI steps share.
#
# Build settings of every build directory the scripts configure (build/, build-sanitize/,
# build-clang-release/, build-fuzz/, the consumers):
#   openpbr_cmake_flags     prints one CMake argument per line: Ninja when it is installed, and
#                           ccache as the C++ compiler launcher (the project and its consumers
#                           compile only C++) when it is installed and OPENPBR_CCACHE is not 0
#                           (default 1; e.g. OPENPBR_CCACHE=0 to time a build without it).
#                           ccache keeps compiled objects across reruns (CCACHE_DIR, default
#                           ~/.cache/ccache). CCACHE_BASEDIR defaults to the repository root
#                           (paths in the command lines relative to it); a clone at another path
#                           hits the same entries only with CCACHE_NOHASHDIR=1 as well (e.g. for
#                           throw-away clones; their debug information then names the first
#                           clone's directory), since -g builds hash the working directory.
#
# Step times (wall and CPU seconds), recorded by the outermost script and printed as one table
# at its end, with the children's records (scripts/setup.sh run by scripts/test.sh) included:
#   step_times_init                 once, at the start of each script: the outermost one creates
#                                   the record file (OPENPBR_STEP_TIMES_FILE) and prints the table
#                                   on exit;
#   step_times_elapsed              prints the time since step_times_init, with and without the
#                                   package installs recorded so far;
#   step_run NAME KIND COMMAND...   runs COMMAND, records its wall time, the CPU time (user + sys)
#                                   of everything it ran, and its exit status, and returns that
#                                   status. KIND is "install" for package installs (apt-get,
#                                   npm ci), which the CI time budget leaves out, "step"
#                                   otherwise.
# e.g. step_run ctest step ctest --test-dir build --parallel 2

openpbr_cmake_flags() {
  command -v ninja >/dev/null && echo "-GNinja"
  if [[ "${OPENPBR_CCACHE:-1}" != 0 ]] && command -v ccache >/dev/null; then
    echo "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
  fi
  return 0
}
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}

# Sets step_times_cpu to the CPU time (user + sys, clock ticks) of this shell's children that
# have ended, read from /proc/$BASHPID/stat (this shell, also when it is a background subshell
# of the script; no command substitution, whose own children would be none of ours). Fields 16
# and 17 of the stat line.
step_times_children_cpu() {
  local stat fields
  read -r stat </proc/"$BASHPID"/stat
  # The command name (field 2) is in parentheses and may hold spaces: split after it.
  read -r -a fields <<<"${stat##*) }"
  # fields[0] is field 3 (state), so cutime (16) and cstime (17) are fields[13] and fields[14].
  step_times_cpu=$((fields[13] + fields[14]))
}

step_times_init() {
  step_times_clock_ticks=$(getconf CLK_TCK)
  step_times_started=$EPOCHREALTIME
  if [[ -z "${OPENPBR_STEP_TIMES_FILE:-}" ]]; then
    OPENPBR_STEP_TIMES_FILE=$(mktemp)
    export OPENPBR_STEP_TIMES_FILE
    trap 'step_times_print' EXIT
  fi
}

# "N s since the start (M s without package installs)": where a script stands, e.g. when it
# writes its first file.
step_times_elapsed() {
  awk -F '\t' -v start="$step_times_started" -v now="$EPOCHREALTIME" '
    $2 == "install" { install += $3 }
    END { printf "%.0f s since the start (%.0f s without package installs)\n", now - start, now - start - install }
  ' "$OPENPBR_STEP_TIMES_FILE"
}

step_run() {
  local name=$1 kind=$2
  shift 2
  local wall_start=$EPOCHREALTIME cpu_start status=0
  step_times_children_cpu
  cpu_start=$step_times_cpu
  "$@" || status=$?
  step_times_children_cpu
  awk -v name="$name" -v kind="$kind" -v start="$wall_start" -v end="$EPOCHREALTIME" -v status="$status" \
    -v cpu=$((step_times_cpu - cpu_start)) -v ticks="$step_times_clock_ticks" \
    'BEGIN { printf "%s\t%s\t%.1f\t%.1f\t%d\n", name, kind, end - start, cpu / ticks, status }' >>"$OPENPBR_STEP_TIMES_FILE"
  return "$status"
}

step_times_print() {
  local exit_status=$?
  [[ -s "$OPENPBR_STEP_TIMES_FILE" ]] || { rm -f "$OPENPBR_STEP_TIMES_FILE"; return "$exit_status"; }
  echo
  echo "step times ($(nproc) cores; load average at the end: $(cut -d ' ' -f 1-3 /proc/loadavg)):"
  awk -F '\t' -v total="$(awk -v start="$step_times_started" -v end="$EPOCHREALTIME" 'BEGIN { print end - start }')" '
    BEGIN { printf "  %-40s %9s %9s  %s\n", "step", "wall s", "CPU s", "status" }
    {
      printf "  %-40s %9.1f %9.1f  %s\n", $1 ($2 == "install" ? " (install)" : ""), $3, $4, ($5 == 0 ? "ok" : "exit " $5)
      if ($2 == "install") { install += $3 }
    }
    END {
      printf "  %-40s %9.1f\n", "total", total
      printf "  %-40s %9.1f\n", "total without package installs", total - install
    }' "$OPENPBR_STEP_TIMES_FILE"
  rm -f "$OPENPBR_STEP_TIMES_FILE"
  return "$exit_status"
}
