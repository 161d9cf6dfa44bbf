#!/usr/bin/env bash
# Function length check: no function over 150 lines in host/, targets/, viewer/ and tests/, none
# over 200 in slang/ (the BSDF, whose composition keeps a layer's steps together). Prints each
# function over its folder's limit ("LINES FILE:LINE NAME") and exits 1 when there is one.
# How a length is measured: from the line that names the function to the line of its closing
# brace, both included (comments and blank lines inside count).
#   - C, C++, CUDA and the kernels' dialects (*.h, *.hpp, *.cpp, *.cu, *.cuh, *.comp, *.slang,
#     *.hlsl): universal-ctags's C++ parser, function definitions (kind f, a gtest TEST body
#     included) with their end lines (--fields=+ne);
#   - JavaScript (*.mjs, *.js): scripts/function_lengths.mjs, a tokenizer (ctags 5.9's JavaScript
#     parser gives no end line).
# Only tracked files. Needs universal-ctags (Debian: apt-get install universal-ctags; scripts/setup.sh)
# and node. Usage: scripts/check-function-length.sh (no arguments).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"
# Each folder and its limit in lines, e.g. "slang 200".
limits=("host 150" "targets 150" "viewer 150" "tests 150" "slang 200")
if ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "check-function-length: universal-ctags not found (Debian: apt-get install universal-ctags)" >&2
  exit 1
fi
folders=()
for entry in "${limits[@]}"; do
  folders+=("${entry%% *}")
done
mapfile -t c_files < <(git ls-files -- "${folders[@]}" | grep -E '\.(h|hpp|cpp|cu|cuh|comp|slang|hlsl)$')
mapfile -t js_files < <(git ls-files -- "${folders[@]}" | grep -E '\.(mjs|js)$')
lengths=$(
  {
    printf '%s\n' "${c_files[@]}" |
      ctags --fields=+ne --kinds-C++=f --language-force=C++ -L - -f - 2>/dev/null |
      awk -F'\t' '{
        line = 0; end = 0
        for (i = 4; i <= NF; i++) {
          if ($i ~ /^line:/) line = substr($i, 6)
          if ($i ~ /^end:/) end = substr($i, 5)
        }
        if (end > 0) printf "%d\t%s:%d\t%s\n", end - line + 1, $2, line, $1
      }'
    if ((${#js_files[@]})); then
      node scripts/function_lengths.mjs "${js_files[@]}"
    fi
  }
)
limit_table=$(printf '%s\n' "${limits[@]}")
over=$(awk -F'\t' -v table="$limit_table" '
  BEGIN { n = split(table, rows, "\n"); for (i = 1; i <= n; i++) { split(rows[i], f, " "); limit[f[1]] = f[2] } }
  { split($2, where, "/"); if ($1 > limit[where[1]]) print $1 " " $2 " " $3 }' <<<"$lengths" | sort -u | sort -rn)
if [[ -n "$over" ]]; then
  echo "check-function-length: functions over their folder's limit (lines, where, name; limits: ${limits[*]}):" >&2
  echo "$over" >&2
  exit 1
fi
count=$(wc -l <<<"$lengths")
echo "check-function-length: $count functions, none over the limits (${limits[*]})"
