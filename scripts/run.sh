#!/usr/bin/env bash
# The main job on the bundled default materials: set up what is missing, build only what the
# job runs (the openpbr program and the kernels it loads; not the test programs, which
# scripts/test.sh builds), render the labelled gallery of every bundled material (CPU path
# tracer), run the cross-target conformance and print its summary, and name the files written.
# Prints the time of each step at the end, package installs apart (scripts/common.sh).
# Environment: OPENPBR_BUILD_DIR (default build), OPENPBR_OUT_DIR (default out), and
# scripts/setup.sh's settings (e.g. OPENPBR_CCACHE=0).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=scripts/common.sh
source "$repo_root/scripts/common.sh"
step_times_init
# The program (target openpbr_cli, file openpbr), the Slang/GLSL kernels (openpbr_kernels) and
# the HLSL library's kernels (openpbr_hlsl_kernel) that `openpbr conformance` loads.
echo "run: [1/3] set-up and build of openpbr and its kernels"
"$repo_root/scripts/setup.sh" openpbr_cli openpbr_kernels openpbr_hlsl_kernel
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
out_dir=${OPENPBR_OUT_DIR:-$repo_root/out}
mkdir -p "$out_dir"
export MESA_SHADER_CACHE_DIR=${MESA_SHADER_CACHE_DIR:-$build_dir/mesa-shader-cache}
echo "run: [2/3] gallery of the bundled materials (CPU path tracer)"
step_run "run: gallery" step "$build_dir/openpbr" render --gallery --backend cpu -o "$out_dir/gallery.png"
echo "run: first file, $out_dir/gallery.png, written $(step_times_elapsed)"
echo "run: [3/3] cross-target conformance (100000 queries)"
step_run "run: conformance" step "$build_dir/openpbr" conformance --queries 100000 --json "$out_dir/conformance.json"
echo "wrote: $out_dir/gallery.png $out_dir/conformance.json"
