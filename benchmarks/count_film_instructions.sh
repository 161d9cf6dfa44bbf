#!/usr/bin/env bash
# Instructions per thin-film evaluation (benchmarks/film_instructions.cpp), counted by callgrind
# like benchmarks/count_instructions.sh: per row (I(3n) - I(n)) / 2n calls of
# openpbr_thin_film_model_bases, both bases, the dielectric alone and the metal alone, under an
# outside medium of IOR 1.3 (a coat) and 1 (air).
#
# Usage: benchmarks/count_film_instructions.sh [BUILD_DIR]
#   e.g. benchmarks/count_film_instructions.sh build
# Needs valgrind. Output: outside IOR, then one count per base choice.
set -euo pipefail
build_dir="${1:-build}"
program="$build_dir/film_instructions"
calls=1024  # n, e.g. 1024
if [[ ! -x "$program" ]]; then
    echo "count_film_instructions.sh: $program not found (build the film_instructions target)" >&2
    exit 2
fi
if ! command -v valgrind > /dev/null; then
    echo "count_film_instructions.sh: valgrind not found (apt-get install valgrind)" >&2
    exit 2
fi
count() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$program" "$1" "$2" "$3" 2>&1 |
        awk '/Collected :/ { print $4 }'
}
printf '%-12s %10s %10s %10s\n' outside_ior both dielectric metal
for outside_ior in 1.3 1.0; do
    row=$(printf '%-12s' "$outside_ior")
    for bases in both dielectric metal; do
        low=$(count "$outside_ior" "$bases" "$calls")
        high=$(count "$outside_ior" "$bases" $((3 * calls)))
        if [[ -z "$low" || -z "$high" ]]; then
            echo "count_film_instructions.sh: callgrind gave no count for $outside_ior $bases" >&2
            exit 1
        fi
        row+=$(printf ' %10d' $(((high - low) / (2 * calls))))
    done
    echo "$row"
done
