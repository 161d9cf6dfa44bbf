#!/usr/bin/env bash
# The main job on the bundled default materials: set up what is missing, build, render the
# labelled gallery of every bundled material (CPU path tracer), run the cross-target
# conformance and print its summary, and name the files written.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo_root/scripts/setup.sh"
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
out_dir=${OPENPBR_OUT_DIR:-$repo_root/out}
mkdir -p "$out_dir"
export MESA_SHADER_CACHE_DIR=${MESA_SHADER_CACHE_DIR:-$build_dir/mesa-shader-cache}
"$build_dir/openpbr" render --gallery --backend cpu -o "$out_dir/gallery.png"
"$build_dir/openpbr" conformance --queries 100000 --json "$out_dir/conformance.json"
echo "wrote: $out_dir/gallery.png $out_dir/conformance.json"
