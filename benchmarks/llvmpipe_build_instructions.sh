#!/usr/bin/env bash
# Instructions lavapipe spends building the full conformance module (Slang's SPIR-V) and
# running its first small dispatch, counted by callgrind: a number that does not move with the
# machine's load, unlike the build's wall time (one kernel's pipelines spread over 1.5-2 s
# within one run on the 2-core CI machine, docs/thin-film-estimate.md). llvmpipe compiles at the
# first dispatch, so the count of the threads lavapipe starts is the build plus 64 queries.
# Compare kernels with it, e.g. a commit's kernel against today's: the wall time of the build
# scales with it (513ea8a's kernel: 15.34 G here, 2.57-2.70 s on the 2026-11-27 machine).
#
# Usage: benchmarks/llvmpipe_build_instructions.sh [BUILD_DIR] [KERNEL_DIR ...]
#   e.g. benchmarks/llvmpipe_build_instructions.sh build build/kernels /tmp/old_kernels
# A kernel directory holds conformance.slang.spv (build one from any checkout with
# `node targets/slangc.mjs -target spirv -entry conformance_main -stage compute -I slang
#  -o DIR/conformance.slang.spv targets/kernels/conformance.slang`). About 3 minutes per kernel.
# Needs valgrind (apt-get install valgrind). Output: kernel directory, lavapipe's threads'
# instructions, the whole process's.
set -euo pipefail
build_dir="${1:-build}"
shift || true
kernel_dirs=("$@")
if [[ ${#kernel_dirs[@]} -eq 0 ]]; then
    kernel_dirs=("$build_dir/kernels")
fi
program="$build_dir/openpbr"
material="$(dirname "$0")/../materials/open_pbr_aluminum_brushed.mtlx"  # one material, e.g. any bundled one
if [[ ! -x "$program" ]]; then
    echo "llvmpipe_build_instructions.sh: $program not found (build the openpbr target)" >&2
    exit 2
fi
for tool in valgrind callgrind_annotate; do
    if ! command -v "$tool" > /dev/null; then
        echo "llvmpipe_build_instructions.sh: $tool not found (apt-get install valgrind)" >&2
        exit 2
    fi
done
profile=$(mktemp)
trap 'rm -f "$profile"' EXIT
printf '%-40s %16s %16s\n' kernel_dir lavapipe_threads process
for kernel_dir in "${kernel_dirs[@]}"; do
    if [[ ! -f "$kernel_dir/conformance.slang.spv" ]]; then
        echo "llvmpipe_build_instructions.sh: $kernel_dir/conformance.slang.spv not found" >&2
        exit 2
    fi
    # A fresh shader cache directory, so no build is skipped.
    cache=$(mktemp -d)
    if ! MESA_SHADER_CACHE_DIR="$cache" MESA_SHADER_CACHE_DISABLE=true valgrind --tool=callgrind \
        --callgrind-out-file="$profile" "$program" --kernel-dir "$kernel_dir" conformance --paths slang-spirv \
        --queries 64 --materials "$material" > /dev/null 2>&1; then
        rm -rf "$cache"
        echo "llvmpipe_build_instructions.sh: the conformance run of $kernel_dir failed" >&2
        exit 1
    fi
    rm -rf "$cache"
    # (awk reads to the end: an early exit would stop callgrind_annotate with SIGPIPE.)
    threads=$(callgrind_annotate --inclusive=yes "$profile" |
        awk '/start_thread/ && !found { gsub(",", "", $1); print $1; found = 1 }')
    total=$(callgrind_annotate "$profile" | awk '/PROGRAM TOTALS/ && !found { gsub(",", "", $1); print $1; found = 1 }')
    if [[ -z "$threads" || -z "$total" ]]; then
        echo "llvmpipe_build_instructions.sh: callgrind gave no count for $kernel_dir" >&2
        exit 1
    fi
    printf '%-40s %16d %16d\n' "$kernel_dir" "$threads" "$total"
done
