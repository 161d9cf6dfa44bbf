#!/usr/bin/env bash
# The package as an outside project sees it (README "Integrating"): installs the build to a
# temporary prefix, then configures, builds and runs the four consumers of examples/ against
# that prefix only: cpp_consumer (find_package + BSDF checks), slang_consumer (`import openpbr;`
# from the installed module, run on Vulkan) and hlsl_consumer (the installed openpbr.hlsl
# through glslang's HLSL front end, run on Vulkan); the GPU two compare with the C++ build; and
# wgsl_consumer (the installed openpbr.wgsl under a WGSL kernel, run on WebGPU through Dawn for
# Node, SwiftShader where there is no GPU: sample weights against eval / pdf, a white furnace).
# Fails on any error. Environment: OPENPBR_BUILD_DIR (default build, already built),
# OPENPBR_CONSUMER_DIR (default: a temporary directory, removed afterwards).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
work_dir=${OPENPBR_CONSUMER_DIR:-}
if [[ -z "$work_dir" ]]; then
  work_dir=$(mktemp -d)
  trap 'rm -rf "$work_dir"' EXIT
fi
prefix="$work_dir/prefix"
# shellcheck source=scripts/common.sh
source "$repo_root/scripts/common.sh"
mapfile -t common_flags < <(openpbr_cmake_flags)
export MESA_SHADER_CACHE_DIR="$build_dir/mesa-shader-cache"
mkdir -p "$MESA_SHADER_CACHE_DIR"

start=$(date +%s)
cmake --install "$build_dir" --prefix "$prefix" >/dev/null
echo "ci_consumers: installed to $prefix"

# consumer <name> [extra cmake arguments...]: configure against the prefix, build, run.
consumer() {
  local name=$1
  shift
  local consumer_start
  consumer_start=$(date +%s)
  # Configure and build quietly; on failure the whole log is printed (compiler errors included).
  local log="$work_dir/$name.log"
  if ! { cmake -S "$repo_root/examples/$name" -B "$work_dir/$name" "${common_flags[@]}" -DCMAKE_BUILD_TYPE=Release \
           -DCMAKE_PREFIX_PATH="$prefix" "$@" && cmake --build "$work_dir/$name"; } >"$log" 2>&1; then
    cat "$log" >&2
    echo "ci_consumers: $name failed to configure or build" >&2
    return 1
  fi
  case "$name" in
    cpp_consumer) "$work_dir/$name/cpp_consumer" ;;
    *) cmake --build "$work_dir/$name" --target "run_$name" ;;
  esac
  echo "ci_consumers: $name took $(($(date +%s) - consumer_start)) s"
}

# The consumers run at the same time: each is mostly one process at a time (configure, a
# small build, one run), so one after another they left a core idle (81 s in all in the
# clean-clone run of 5fafbe5, docs/ci-time.md). Each one's output is printed whole, in order.
names=(cpp_consumer slang_consumer hlsl_consumer wgsl_consumer)
pids=()
consumer cpp_consumer >"$work_dir/cpp_consumer.out" 2>&1 &
pids+=($!)
# The Slang compiler is the source tree's driver (node_modules from scripts/setup.sh), or a
# native slangc through OPENPBR_SLANGC.
consumer slang_consumer -DOPENPBR_SLANGC="${OPENPBR_SLANGC:-}" -DOPENPBR_SLANGC_DRIVER="$repo_root/targets/slangc.mjs" \
  >"$work_dir/slang_consumer.out" 2>&1 &
pids+=($!)
consumer hlsl_consumer >"$work_dir/hlsl_consumer.out" 2>&1 &
pids+=($!)
# Dawn for Node comes from the source tree's node_modules (scripts/setup.sh's npm ci).
consumer wgsl_consumer -DOPENPBR_NODE_MODULES="$repo_root/node_modules" >"$work_dir/wgsl_consumer.out" 2>&1 &
pids+=($!)
failed=()
for index in "${!names[@]}"; do
  status=0
  wait "${pids[$index]}" || status=$?
  cat "$work_dir/${names[$index]}.out"
  ((status == 0)) || failed+=("${names[$index]}")
done
if ((${#failed[@]})); then
  echo "ci_consumers: failed: ${failed[*]}" >&2
  exit 1
fi
echo "ci_consumers: all consumers passed in $(($(date +%s) - start)) s"
