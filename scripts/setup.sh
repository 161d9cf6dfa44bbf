#!/usr/bin/env bash
# Shared set-up for scripts/run.sh and scripts/test.sh on Debian 12: installs only what is
# missing (apt-get), installs the Slang compiler (npm ci), configures and builds.
# Environment: OPENPBR_BUILD_DIR (default build), OPENPBR_BUILD_TYPE (default RelWithDebInfo),
# OPENPBR_WARNINGS_AS_ERRORS (unset: the cache's value, OFF in a new build; e.g. 1 in CI, which
# .ci/run sets, for -Werror).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${OPENPBR_BUILD_DIR:-$repo_root/build}
build_type=${OPENPBR_BUILD_TYPE:-RelWithDebInfo}

# Debian packages the build and the tests use, e.g. libglm-dev for the C++ backend, chromium
# (headless, with its SwiftShader WebGPU adapter) for the browser viewer's test.
packages=(
  g++ clang cmake ninja-build git nodejs npm
  libglm-dev libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools libpugixml-dev libcli11-dev nlohmann-json3-dev libstb-dev
  libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev python3 python3-matplotlib
  libclang-rt-14-dev clang-format
  chromium
)
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
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The Slang 2025.15 WebAssembly compiler, pinned in package-lock.json.
stamp="$repo_root/node_modules/.openpbr-lock-stamp"
if [[ ! -f "$stamp" ]] || ! cmp -s "$repo_root/package-lock.json" "$stamp"; then
  echo "setup: npm ci (Slang compiler)"
  (cd "$repo_root" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$repo_root/package-lock.json" "$stamp"
fi

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
configure_flags=()
[[ -z "${OPENPBR_WARNINGS_AS_ERRORS:-}" ]] || configure_flags+=(-DOPENPBR_WARNINGS_AS_ERRORS="$OPENPBR_WARNINGS_AS_ERRORS")
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S "$repo_root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE="$build_type" "${configure_flags[@]}"
elif ((${#configure_flags[@]})); then
  cmake -S "$repo_root" -B "$build_dir" "${configure_flags[@]}" >/dev/null
fi
cmake --build "$build_dir" --parallel "$(nproc)"
