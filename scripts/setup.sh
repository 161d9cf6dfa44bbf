#!/usr/bin/env bash
# Shared set-up for scripts/run.sh and scripts/test.sh on Debian 12: installs only what is
# missing (apt-get), installs the Slang compiler (npm ci), configures and builds.
#   scripts/setup.sh              builds every target (what scripts/test.sh needs);
#   scripts/setup.sh TARGET ...   builds only the named targets and what they depend on, e.g.
#                                 `scripts/setup.sh openpbr_cli openpbr_kernels` (scripts/run.sh).
# Prints how long each part took (package installs, configure, build; scripts/common.sh).
# Environment: OPENPBR_BUILD_DIR (default build), OPENPBR_BUILD_TYPE (default RelWithDebInfo),
# OPENPBR_WARNINGS_AS_ERRORS (unset: the cache's value, OFF in a new build; e.g. 1 in CI, which
# .ci/run sets, for -Werror), OPENPBR_CCACHE (default 1: compile through ccache when it is
# installed; e.g. 0 for a build without it), OPENPBR_DEBUG_INFO (unset: the build type's own;
# "lines" for line tables only, -g1, in a RelWithDebInfo build: what .ci/run sets. GCC generates
# the same code at -g and -g1 (the disassembly of host/checks/stability.cpp's object compared
# equal), backtraces keep their functions, files and lines, and the compiles take about 30 % less
# CPU: host/checks/stability.cpp 11.7 s at -g, 8.6 s at -g1, docs/ci-time.md).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
build_type=${OPENPBR_BUILD_TYPE:-RelWithDebInfo}
# shellcheck source=scripts/common.sh
source "$repo_root/scripts/common.sh"
step_times_init
build_targets=("$@")

# Debian packages the build and the tests use, e.g. libglm-dev for the C++ backend, chromium
# (headless, with its SwiftShader WebGPU adapter) for the browser viewer's test, universal-ctags
# for the function length check (scripts/check-function-length.sh).
packages=(
  g++ clang cmake ninja-build git nodejs npm
  libglm-dev libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools libpugixml-dev libcli11-dev nlohmann-json3-dev libstb-dev
  libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev python3 python3-matplotlib
  libclang-rt-14-dev clang-format ccache universal-ctags
  chromium
)
# chromium: its SwiftShader Vulkan driver (/usr/lib/chromium/vk_swiftshader_icd.json) is the
# WebGPU adapter of the conformance paths slang-wgsl and wgsl-library where there is no GPU
# (Dawn refuses lavapipe); the browser itself runs the viewer's test.
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
# node may come from elsewhere (e.g. NodeSource); Debian's nodejs/npm are only needed without one.
if command -v node >/dev/null && command -v npm >/dev/null; then
  filtered=()
  for package in "${missing[@]}"; do
    [[ "$package" == nodejs || "$package" == npm ]] || filtered+=("$package")
  done
  missing=("${filtered[@]+"${filtered[@]}"}")
fi
if ((${#missing[@]})); then
  echo "setup: installing missing Debian packages: ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  # One command line (&&): step_run runs it where set -e does not stop at a failed update.
  install_packages() {
    "${sudo_cmd[@]}" apt-get update -qq &&
      DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
  }
  step_run "setup: apt-get install" install install_packages
fi

# The Slang 2025.15 WebAssembly compiler, pinned in package-lock.json.
stamp="$repo_root/node_modules/.openpbr-lock-stamp"
if [[ ! -f "$stamp" ]] || ! cmp -s "$repo_root/package-lock.json" "$stamp"; then
  echo "setup: npm ci (Slang compiler)"
  install_slang() { (cd "$repo_root" && npm ci --no-audit --no-fund --loglevel=error); }
  step_run "setup: npm ci" install install_slang
  cp "$repo_root/package-lock.json" "$stamp"
fi

configure_flags=()
[[ -z "${OPENPBR_WARNINGS_AS_ERRORS:-}" ]] || configure_flags+=(-DOPENPBR_WARNINGS_AS_ERRORS="$OPENPBR_WARNINGS_AS_ERRORS")
case "${OPENPBR_DEBUG_INFO:-}" in
  "") ;;
  lines) configure_flags+=("-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG") ;;
  *) echo "setup: OPENPBR_DEBUG_INFO must be empty or \"lines\", got \"$OPENPBR_DEBUG_INFO\"" >&2; exit 1 ;;
esac
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  mapfile -t common_flags < <(openpbr_cmake_flags)
  step_run "setup: configure" step cmake -S "$repo_root" -B "$build_dir" "${common_flags[@]}" \
    -DCMAKE_BUILD_TYPE="$build_type" "${configure_flags[@]}"
elif ((${#configure_flags[@]})); then
  step_run "setup: configure" step cmake -S "$repo_root" -B "$build_dir" "${configure_flags[@]}" >/dev/null
fi
target_flags=()
build_label=all
if ((${#build_targets[@]})); then
  target_flags=(--target "${build_targets[@]}")
  build_label="${#build_targets[@]} targets"
fi
echo "setup: building ${build_targets[*]:-every target} in $build_dir"
step_run "setup: build ($build_label)" step cmake --build "$build_dir" --parallel "$(nproc)" "${target_flags[@]}"
