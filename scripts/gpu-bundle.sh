#!/usr/bin/env bash
# gpu-bundle.sh - the build outputs scripts/gpu-check.sh needs, in one small folder that can
# travel to a GPU machine without this machine's packages (docs/gpu.md):
#
#   scripts/gpu-bundle.sh BUILD_DIR BUNDLE_DIR
#
# BUNDLE_DIR gets: openpbr (stripped), kernels/, openpbr_cuda_conformance (when built), and
# debs/ with the .deb files of the runtime libraries (the Vulkan loader and the glvnd libraries
# the NVIDIA driver needs; TBB and pugixml), from `apt-get download`. About 15 MB. Then, on the
# GPU machine, from the repository root:
#
#   OPENPBR_GPU_CHECK_DEBS=BUNDLE_DIR/debs scripts/gpu-check.sh RESULTS_DIR BUNDLE_DIR
set -euo pipefail
if [[ $# -ne 2 ]]; then
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
build=$1
bundle=$2
mkdir -p "$bundle/debs"
strip -o "$bundle/openpbr" "$build/openpbr"
rm -rf "$bundle/kernels"
cp -r "$build/kernels" "$bundle/kernels"
if [[ -x "$build/openpbr_cuda_conformance" ]]; then
  # Host symbols only: the device code (fatbin) lives in a data section that strip keeps.
  strip -o "$bundle/openpbr_cuda_conformance" "$build/openpbr_cuda_conformance"
else
  echo "gpu-bundle: no $build/openpbr_cuda_conformance (build target openpbr_cuda_programs); the CUDA paths will say 'not built'" >&2
fi
(cd "$bundle/debs" && apt-get download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 \
  libtbb12 libtbbmalloc2 libpugixml1v5)
du -sh "$bundle"
