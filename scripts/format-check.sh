#!/usr/bin/env bash
# Format check: every tracked C, C++ and CUDA source (*.h, *.hpp, *.cpp, *.cu, *.cuh: host/,
# slang/, interop/, targets/, tests/, benchmarks/, examples/, fuzz/) against the root
# .clang-format, with clang-format --dry-run --Werror; exit status 1 and the offending lines when
# a file differs. Left out: the generated tables (slang/generated/*.inc, data), and sources in
# other dialects clang-format does not parse (*.slang, *.hlsl, *.comp, *.metal, *.in, *.mjs).
# `scripts/format-check.sh --fix` rewrites the files in place instead (clang-format -i).
# Environment: CLANG_FORMAT (default clang-format; version 14, Debian 12's, wrote .clang-format's
# choices: another version may format some constructs differently).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
clang_format=${CLANG_FORMAT:-clang-format}
mode=(--dry-run --Werror)
if [[ "${1:-}" == --fix ]]; then
  mode=(-i)
elif [[ $# -gt 0 ]]; then
  echo "usage: scripts/format-check.sh [--fix]" >&2
  exit 2
fi
if ! command -v "$clang_format" >/dev/null; then
  echo "format-check: $clang_format not found (Debian: apt-get install clang-format)" >&2
  exit 1
fi
cd "$repo_root"
mapfile -t files < <(git ls-files -- '*.h' '*.hpp' '*.cpp' '*.cu' '*.cuh' ':!:slang/generated/*')
if ((${#files[@]} == 0)); then
  echo "format-check: no files (not a git checkout?)" >&2
  exit 1
fi
# Files that no longer exist in the working tree (deleted, not yet committed) are skipped.
existing=()
for file in "${files[@]}"; do
  [[ -f "$file" ]] && existing+=("$file")
done
if printf '%s\0' "${existing[@]}" | xargs -0 -n 32 -P "$(nproc)" "$clang_format" --style=file "${mode[@]}"; then
  [[ "${mode[0]}" == -i ]] || echo "format-check: ${#existing[@]} files formatted as .clang-format says"
else
  echo "format-check: files differ from .clang-format (scripts/format-check.sh --fix rewrites them)" >&2
  exit 1
fi
