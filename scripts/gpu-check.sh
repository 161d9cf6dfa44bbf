#!/usr/bin/env bash
# gpu-check.sh - every GPU measurement of the project in one command, on a machine with a GPU
# where the binaries exist (built here or built elsewhere and copied; docs/gpu.md):
#
#   scripts/gpu-check.sh RESULTS_DIR [BUILD_DIR]
#
#   RESULTS_DIR  where the results go (created), e.g. $OUT
#   BUILD_DIR    the build folder holding `openpbr`, `kernels/` and `openpbr_cuda_conformance`;
#                default: build under the repository root
#
# Steps (each runs even when an earlier one failed; a summary ends the run):
#   1. environment: nvidia-smi, the Vulkan devices, the binaries' libraries
#   2. conformance: every path (CPU paths that round like a GPU, five Vulkan paths, CUDA),
#      OPENPBR_GPU_CHECK_QUERIES queries (default 10^6), per-kind metric and device times
#   3. stability: the hard-case corpus on every GPU path (10^5 samples per case)
#   4. bench gpu: device-timed prepare+eval / sample / pdf per material class
#   5. bench specialization: full versus specialized pipelines, same timing
#   6. gallery: the Vulkan path tracer at 1024 samples per pixel
# The steps' time limits add up to 560 s (a whole run on an H100 is expected to take 3-4 min).
#
# Every path the binaries read is passed explicitly, relative to the repository root and the
# build folder, so a build made on another machine (other absolute paths) runs as it is.
#
# Environment (each optional):
#   OPENPBR_GPU_CHECK_QUERIES  conformance queries, e.g. 1000000 (default)
#   OPENPBR_GPU_CHECK_SMOKE    1: tiny sizes everywhere (checks the script itself on a machine
#                              without a GPU, e.g. on lavapipe in a minute or two)
#   OPENPBR_GPU_CHECK_DEBS     a folder of .deb files (scripts/gpu-bundle.sh) for machines without
#                              our packages: the Vulkan loader and glvnd libraries are extracted
#                              into / (as root, when no libvulkan.so.1 is installed) and
#                              ldconfig run; the others (TBB, pugixml) into a scratch folder put
#                              on LD_LIBRARY_PATH
#   VK_DRIVER_FILES            the Vulkan driver manifest; default: NVIDIA's where it exists
#
# RESULTS_DIR gets at most 8 files: summary.txt, results.tar.gz (every step's output and JSON,
# the environment, the log), the gallery PNG and the JSON of conformance, stability, bench gpu
# and bench specialization.
set -uo pipefail

if [[ $# -lt 1 || $# -gt 2 || "$1" == "-h" || "$1" == "--help" ]]; then
  sed -n '2,/^set /p' "$0" | grep '^#' | sed 's/^# \{0,1\}//'
  exit 2
fi
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
final=$(mkdir -p "$1" && cd "$1" && pwd)
# Every step writes into a scratch folder; RESULTS_DIR gets the few files listed above.
scratch=$(mktemp -d "${TMPDIR:-/tmp}/openpbr-gpu-check.XXXXXX")
results=$scratch/results
mkdir -p "$results"
build=$(cd "${2:-$repo_root/build}" 2>/dev/null && pwd) || { echo "gpu-check: no build folder ${2:-$repo_root/build}" >&2; exit 2; }
queries=${OPENPBR_GPU_CHECK_QUERIES:-1000000}
gpu_samples=100000
bench_queries=1048576
specialization_queries=1000000
spp=1024
render_size=()
if [[ "${OPENPBR_GPU_CHECK_SMOKE:-0}" == 1 ]]; then
  queries=${OPENPBR_GPU_CHECK_QUERIES:-2000}
  gpu_samples=64
  bench_queries=256
  specialization_queries=1000
  spp=1
  render_size=(--size 256x128)
fi

openpbr=$build/openpbr
kernels=$build/kernels
materials=$repo_root/materials
corpus=$repo_root/tests/data/stability_corpus.json
cuda_program=$build/openpbr_cuda_conformance
log=$results/gpu-check.log
: >"$log"

say() { echo "$*" | tee -a "$log"; }

# ---- Environment -------------------------------------------------------------------------------
if [[ -n "${OPENPBR_GPU_CHECK_DEBS:-}" ]]; then
  debs=$(cd "$OPENPBR_GPU_CHECK_DEBS" && pwd)
  sysroot=$scratch/sysroot
  mkdir -p "$sysroot"
  loader_missing=0
  ldconfig -p 2>/dev/null | grep -q 'libvulkan.so.1 ' || loader_missing=1
  for deb in "$debs"/*.deb; do
    [[ -e "$deb" ]] || continue
    case $(basename "$deb") in
      libvulkan1_*|libegl1_*|libglvnd0_*|libopengl0_*|libgl1_*|libglx0_*|libgles2_*)
        # The loader and glvnd where the driver's libraries look for them (as the device notes
        # did it); anything else stays out of /.
        if [[ $loader_missing -eq 1 && $(id -u) -eq 0 ]]; then dpkg -x "$deb" /; else dpkg -x "$deb" "$sysroot"; fi ;;
      *) dpkg -x "$deb" "$sysroot" ;;
    esac
  done
  [[ $loader_missing -eq 1 && $(id -u) -eq 0 ]] && ldconfig
  export LD_LIBRARY_PATH="${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$sysroot/usr/lib/x86_64-linux-gnu"
fi
if [[ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" && -f /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json ]]; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fi
if [[ -z "${VK_DRIVER_FILES:-}" && -z "${VK_ICD_FILENAMES:-}" ]]; then
  for manifest in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
                  /etc/vulkan/icd.d/nvidia_icd.json; do
    if [[ -f "$manifest" ]]; then
      export VK_DRIVER_FILES=$manifest
      break
    fi
  done
fi
# The CUDA program at this build's path, whatever path was baked in at configure time.
export OPENPBR_CUDA_CONFORMANCE_PROGRAM=$cuda_program
# A Mesa shader cache of our own (used only if the driver is Mesa's).
export MESA_SHADER_CACHE_DIR=$scratch/mesa-shader-cache
mkdir -p "$MESA_SHADER_CACHE_DIR"

{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host: $(uname -a)"
  echo "repository: $repo_root"
  echo "build: $build"
  echo "VK_DRIVER_FILES=${VK_DRIVER_FILES:-}"
  echo "LD_LIBRARY_PATH=${LD_LIBRARY_PATH:-}"
  echo "OPENPBR_CUDA_CONFORMANCE_PROGRAM=$OPENPBR_CUDA_CONFORMANCE_PROGRAM"
  echo "--- nvidia-smi"
  nvidia-smi --query-gpu=name,driver_version,compute_cap,memory.total --format=csv 2>/dev/null || echo "(no nvidia-smi)"
  echo "--- vulkaninfo --summary"
  (command -v vulkaninfo >/dev/null && vulkaninfo --summary 2>&1 | head -60) || echo "(no vulkaninfo)"
  echo "--- ldd openpbr"
  ldd "$openpbr" 2>&1
  echo "--- ldd openpbr_cuda_conformance"
  ldd "$cuda_program" 2>&1
} >"$results/environment.txt" 2>&1

# ---- Steps -------------------------------------------------------------------------------------
declare -a step_names=() step_status=() step_seconds=()

# run_step NAME TIMEOUT_SECONDS COMMAND...: output to RESULTS_DIR/NAME.txt, status recorded.
run_step() {
  local name=$1 limit=$2
  shift 2
  say "== $name: $*"
  local start=$SECONDS
  timeout --kill-after=10 "$limit" "$@" >"$results/$name.txt" 2>&1
  local status=$?
  local seconds=$((SECONDS - start))
  step_names+=("$name")
  step_status+=("$status")
  step_seconds+=("$seconds")
  tail -n 40 "$results/$name.txt" | tee -a "$log" >/dev/null
  say "== $name: exit $status after ${seconds} s$([[ $status -eq 124 || $status -eq 137 ]] && echo ' (time limit)')"
}

for required in "$openpbr" "$kernels/conformance.slang.spv"; do
  [[ -e "$required" ]] || say "missing: $required (steps that need it will fail)"
done
[[ -x "$cuda_program" ]] || say "missing: $cuda_program (the CUDA paths will report 'not built')"

common=(--kernel-dir "$kernels" --materials-dir "$materials")

run_step conformance 180 "$openpbr" "${common[@]}" conformance --queries "$queries" \
  --json "$results/conformance.json"
run_step stability 110 "$openpbr" "${common[@]}" stability --corpus "$corpus" \
  --paths slang-spirv glsl-spirv slang-hlsl slang-glsl hlsl cuda slang-cuda \
  --gpu-samples "$gpu_samples" --json "$results/stability.json"
run_step bench-gpu 130 "$openpbr" "${common[@]}" bench gpu --queries "$bench_queries" --repeats 10 \
  --json "$results/bench-gpu.json"
run_step bench-specialization 100 "$openpbr" "${common[@]}" bench specialization --queries "$specialization_queries" \
  --repeats 10 --json "$results/bench-specialization.json"
run_step gallery 40 "$openpbr" "${common[@]}" render --gallery --backend vulkan --spp "$spp" "${render_size[@]}" \
  --quiet -o "$results/gallery-${spp}spp.png" --json "$results/gallery.json"

# ---- Summary -----------------------------------------------------------------------------------
failed=0
for status in "${step_status[@]}"; do
  [[ $status -ne 0 ]] && failed=$((failed + 1))
done
{
  echo "gpu-check summary ($(date -u +%Y-%m-%dT%H:%M:%SZ)), results in $final"
  grep -m1 -A2 "^--- nvidia-smi" "$results/environment.txt" | tail -n 2
  for index in "${!step_names[@]}"; do
    status=${step_status[$index]}
    verdict=ok
    [[ $status -ne 0 ]] && verdict=FAILED
    printf '  %-22s %-7s exit %3d  %4d s\n' "${step_names[$index]}" "$verdict" "$status" "${step_seconds[$index]}"
  done
  echo "conformance per path (per-kind metric verdict, device ns/query):"
  grep -E "^  [a-z-]+: (passes|FAILS|not executed)|device time|^      [a-z.]+ (p99.9|max) of error|^verdict: " "$results/conformance.txt" 2>/dev/null | sed 's/^/  /'
  echo "bench gpu:"
  grep -E "device:|^  [a-z_+]+ \(" "$results/bench-gpu.txt" 2>/dev/null | sed 's/^/  /'
  echo "gallery:"
  tail -n 3 "$results/gallery.txt" 2>/dev/null | sed 's/^/  /'
  echo "$failed step(s) failed"
} | tee "$results/summary.txt" | tee -a "$log" >/dev/null
cat "$results/summary.txt"
cp "$results/summary.txt" "$final/summary.txt"
for file in conformance.json stability.json bench-gpu.json bench-specialization.json "gallery-${spp}spp.png"; do
  [[ -f "$results/$file" ]] && cp "$results/$file" "$final/$file"
done
tar -C "$scratch" -czf "$final/results.tar.gz" results
echo "wrote $final: $(cd "$final" && ls | tr '\n' ' ')"
# Exit 1 when a step failed (every step ran regardless).
[[ $failed -eq 0 ]]
