#!/usr/bin/env bash
# The full module's size, a guard for its llvmpipe build time without timing anything: the
# conformance kernel (every feature on) after `spirv-opt -O` (inlined and folded, close to what
# Mesa's NIR compiles, since NIR inlines every call) must stay within a budget of instructions.
# Why a budget (docs/performance.md, "llvmpipe build time"): one commit that wrote a per-channel
# table look-up out three times grew this count from 23,101 to 25,024 and the full module's
# pipeline creation + first dispatch from about 2.6 to 3.9 s; after the mend it is 20,633
# (2.6-2.7 s). The budget was 22,000, that count plus 6.6 %: a growth like that commit's fails.
# A change that needs more must measure the build time and raise the budget with the figure.
# 2026-11-29 (docs/thin-film-estimate.md, "Rolled film-table reads"): the film table's reads in
# loops kept rolled (OPENPBR_DONT_UNROLL) grew the count from 21,906 to 22,386 while the build
# itself fell from 19.61 G to 16.67 G instructions (benchmarks/llvmpipe_build_instructions.sh,
# valgrind: the direct measure; this count only guards against copies of code). The budget is
# 23,860, that count plus the same 6.6 %.
#
# Usage: targets/check_module_size.sh KERNEL.spv [BUDGET]
#   e.g. targets/check_module_size.sh build/kernels/conformance.slang.spv 23860
set -euo pipefail
kernel="${1:?usage: check_module_size.sh KERNEL.spv [BUDGET]}"
budget="${2:-23860}"  # instructions after spirv-opt -O, e.g. 23860 (see above)
for tool in spirv-opt spirv-dis; do
    if ! command -v "$tool" > /dev/null; then
        echo "check_module_size.sh: $tool not found (Debian: apt-get install spirv-tools)" >&2
        exit 2
    fi
done
if [[ ! -f "$kernel" ]]; then
    echo "check_module_size.sh: $kernel not found (build the openpbr_kernels target)" >&2
    exit 2
fi
optimized="$(mktemp)"
trap 'rm -f "$optimized"' EXIT
spirv-opt -O "$kernel" -o "$optimized"
count=$(spirv-dis --no-header "$optimized" | grep -c "Op")
echo "$kernel: $count instructions after spirv-opt -O (budget $budget)"
if ((count > budget)); then
    echo "FAIL: the module grew past its budget; see docs/performance.md, \"llvmpipe build time\"" >&2
    exit 1
fi
