# Shared by the shell checks (targets/check_targets.sh, tests/api_compat/check_api_compat.sh):
# a scratch folder WORK removed on exit, pass/fail counters, and
#   run DESCRIPTION COMMAND...  prints ok/FAIL, and the command's output (40 lines) on failure.
# Sourced, not run.
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
FAILURES=0
PASSES=0

run() {
  local what="$1"
  shift
  if "$@" > "$WORK/log" 2>&1; then
    echo "ok:   $what"
    PASSES=$((PASSES + 1))
  else
    echo "FAIL: $what"
    echo "      command: $*"
    sed 's/^/      /' "$WORK/log" | head -40
    FAILURES=$((FAILURES + 1))
  fi
}
