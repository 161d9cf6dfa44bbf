#!/usr/bin/env bash
# The whole test suite: set up what is missing, build, run every test through ctest.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo_root/scripts/setup.sh"
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
ctest --test-dir "$build_dir" --output-on-failure --parallel "$(nproc)" "$@"
