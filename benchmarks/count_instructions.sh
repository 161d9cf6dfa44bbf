#!/usr/bin/env bash
# Instructions per call of prepare / eval / sample / pdf for the per-feature cost table's
# materials (host/studies/feature_variants.h), counted by callgrind: a number that does not move
# with the machine's load, unlike benchmark_bsdf's timings. Per row it runs
# benchmark_instructions with n and 3n calls and prints (I(3n) - I(n)) / 2n.
#
# Usage: benchmarks/count_instructions.sh [BUILD_DIR] [VARIANT_REGEX]
#   e.g. benchmarks/count_instructions.sh build '^(Default|EveryLobe)$'
# Needs valgrind (apt-get install valgrind). Output: variant, then one count per operation.
set -euo pipefail
build_dir="${1:-build}"
pattern="${2:-.}"
program="$build_dir/benchmark_instructions"
calls=512  # n; about a second per run under callgrind, e.g. 512
if [[ ! -x "$program" ]]; then
    echo "count_instructions.sh: $program not found (build the benchmark_instructions target)" >&2
    exit 2
fi
if ! command -v valgrind > /dev/null; then
    echo "count_instructions.sh: valgrind not found (apt-get install valgrind)" >&2
    exit 2
fi
count() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$program" "$1" "$2" "$3" 2>&1 |
        awk '/Collected :/ { print $4 }'
}
printf '%-28s %10s %10s %10s %10s\n' variant prepare eval sample pdf
"$program" --list | grep -E -- "$pattern" | while read -r variant; do
    row=$(printf '%-28s' "$variant")
    for operation in prepare eval sample pdf; do
        low=$(count "$operation" "$variant" "$calls")
        high=$(count "$operation" "$variant" $((3 * calls)))
        if [[ -z "$low" || -z "$high" ]]; then
            echo "count_instructions.sh: callgrind gave no count for $operation $variant" >&2
            exit 1
        fi
        row+=$(printf ' %10d' $(((high - low) / (2 * calls))))
    done
    echo "$row"
done
