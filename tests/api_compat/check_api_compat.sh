#!/usr/bin/env bash
# The api_compat program in every language, and the compile-time hooks (ctest -L api_compat):
#   bash tests/api_compat/check_api_compat.sh glsl|slang|hlsl|cuda|hooks
#   glsl   glslang on api_compat.comp (the router's GLSL fallback), spirv-val
#   slang  slangc.mjs on api_compat.slang (`import openpbr;`) to SPIR-V, GLSL, HLSL, CUDA and
#          Metal; spirv-val, glslang on the GLSL and the HLSL, check_targets.mjs on the Metal
#   hlsl   generate_hlsl.mjs: openpbr.hlsl and the program spelled in HLSL; glslang -D
#   cuda   nvcc api_compat_device.cu with the project's nvcc flags (host and device code from
#          one source), run where a CUDA device answers
#   hooks  backend selection and overrides (hooks/hook_language_target.cpp, one compile per
#          case), the #error without GLM, the #error of texture tables without their macros,
#          OPENPBR_USE_CUSTOM_SATURATE in GLSL (compiles with the hook, fails without it)
# Environment (set by CMake): OPENPBR_SOURCE_DIR, GLSLANG_VALIDATOR, SPIRV_VAL, NODE,
# OPENPBR_NVCC, CXX_COMPILER. Exit status 77 = skipped (tool missing).
set -u

SRC="${OPENPBR_SOURCE_DIR:?}"
GLSLANG="${GLSLANG_VALIDATOR:-glslangValidator}"
NODE="${NODE:-node}"
CXX="${CXX_COMPILER:-c++}"
HERE="$SRC/tests/api_compat"
source "$SRC/targets/check_lib.sh"

run_fails() { # run_fails DESCRIPTION PATTERN COMMAND...: ok if the command fails printing PATTERN
  local what="$1" pattern="$2"
  shift 2
  if "$@" > "$WORK/log" 2>&1; then
    echo "FAIL: $what (compiled, must not)"
    FAILURES=$((FAILURES + 1))
  elif grep -q -- "$pattern" "$WORK/log"; then
    echo "ok:   $what"
    PASSES=$((PASSES + 1))
  else
    echo "FAIL: $what (failed without '$pattern')"
    sed 's/^/      /' "$WORK/log" | head -20
    FAILURES=$((FAILURES + 1))
  fi
}

spirv_val() { # spirv_val FILE ENV: spirv-val when installed
  if [ -n "${SPIRV_VAL:-}" ] && [ -x "${SPIRV_VAL}" ]; then
    run "spirv-val $(basename "$1")" "$SPIRV_VAL" --target-env "$2" "$1"
  fi
}

case "${1:-}" in
  glsl)
    run "glslang -V api_compat.comp" "$GLSLANG" -V --target-env vulkan1.2 -S comp -o "$WORK/glsl.spv" "$HERE/api_compat.comp"
    spirv_val "$WORK/glsl.spv" vulkan1.2
    ;;
  slang)
    run "slangc.mjs api_compat.slang -> spirv, glsl, hlsl, cuda, metal" "$NODE" "$SRC/targets/slangc.mjs" -q \
      -target spirv,glsl,hlsl,metal,cuda -entry api_compat_main -stage compute -I "$SRC/slang" -o "$WORK/slang" \
      "$HERE/api_compat.slang"
    spirv_val "$WORK/slang/api_compat.spv" vulkan1.2
    run "glslang -V Slang's GLSL" "$GLSLANG" -V --target-env vulkan1.2 -S comp -o "$WORK/slang_glsl.spv" "$WORK/slang/api_compat.glsl"
    run "glslang -D Slang's HLSL" "$GLSLANG" -D -V -Od -S comp -e main --source-entrypoint api_compat_main --hlsl-iomap \
      --shift-cbuffer-binding 8 -o "$WORK/slang_hlsl.spv" "$WORK/slang/api_compat.hlsl"
    run "check_targets.mjs metal (Slang's Metal)" "$NODE" "$SRC/targets/check_targets.mjs" metal "$WORK/slang/api_compat.metal" \
      api_compat_main "$HERE/api_compat.slang" "$SRC/slang/openpbr_features.h"
    run "Slang's CUDA defines the kernel" grep -q "api_compat_main" "$WORK/slang/api_compat.cu"
    ;;
  hlsl)
    mkdir -p "$WORK/hlsl"
    run "generate_hlsl.mjs openpbr.hlsl" "$NODE" "$SRC/targets/hlsl/generate_hlsl.mjs" -preset hlsl -I "$SRC/slang" \
      -o "$WORK/hlsl/openpbr.hlsl" "$SRC/targets/hlsl/openpbr.hlsl.in"
    run "generate_hlsl.mjs api_compat_program.hlsl" "$NODE" "$SRC/targets/hlsl/generate_hlsl.mjs" -preset hlsl -I "$SRC/slang" \
      -provided "$SRC/targets/hlsl/openpbr.hlsl.in" -o "$WORK/hlsl/api_compat_program.hlsl" "$HERE/api_compat_program.h"
    cp "$HERE/api_compat.hlsl" "$WORK/hlsl/"
    run "check_targets.mjs hlsl-library openpbr.hlsl" "$NODE" "$SRC/targets/check_targets.mjs" hlsl-library "$WORK/hlsl/openpbr.hlsl"
    run "glslang -D api_compat.hlsl" "$GLSLANG" -D -V -Od -S comp -e main --hlsl-iomap -o "$WORK/hlsl.spv" "$WORK/hlsl/api_compat.hlsl"
    spirv_val "$WORK/hlsl.spv" vulkan1.0
    ;;
  cuda)
    [ -x "${OPENPBR_NVCC:-}" ] || { echo "skipped: nvcc not found (${OPENPBR_NVCC:-unset})"; exit 77; }
    # One compile for both checks (the router's CUDA backend under the project's nvcc flags:
    # -rdc, every warning an error, host -Wall -Wextra -Werror; and host and device code from
    # one source). Two compiles, the first of a compile-only copy, took 17 s and 26 s of CPU;
    # this one 17 s (-rdc=true also keeps ptxas from optimizing the whole program at once).
    run "nvcc api_compat_device.cu (host and device, -rdc, -Werror all-warnings, host -Wall -Wextra -Werror)" \
      "$OPENPBR_NVCC" -std=c++17 -O2 -rdc=true -D__NV_NO_VECTOR_DEPRECATION_DIAG -diag-suppress 550,20012 \
      -Werror all-warnings -Xcompiler=-Wall,-Wextra,-Werror -I "$SRC" -o "$WORK/api_compat_device" "$HERE/api_compat_device.cu"
    # Run where a device answers (none on the lavapipe machines).
    if command -v nvidia-smi > /dev/null && nvidia-smi -L > /dev/null 2>&1; then
      run "api_compat_device on $(nvidia-smi -L | head -1)" "$WORK/api_compat_device"
    else
      echo "note: no CUDA device, api_compat_device compiled only"
    fi
    ;;
  hooks)
    target_case() { # target_case EXPECTED DEFINES...: the router picks EXPECTED
      local expected="$1"
      shift
      run "router: ${*:-(no defines)} -> $expected" "$CXX" -std=c++17 -Wall -Wextra -Werror -fsyntax-only -I "$SRC" \
        "-DEXPECT_$expected" "$@" "$HERE/hooks/hook_language_target.cpp"
    }
    target_case CPP
    target_case CUDA -D__CUDACC__
    target_case METAL -D__METAL_VERSION__=230
    target_case METAL -DOPENPBR_LANGUAGE_TARGET_MSL=1
    target_case METAL -DOPENPBR_LANGUAGE_TARGET_METAL=1
    target_case GLSL -DOPENPBR_LANGUAGE_TARGET_GLSL=1
    target_case SLANG -DOPENPBR_LANGUAGE_TARGET_SLANG=1
    target_case CPP -D__CUDACC__ -DOPENPBR_LANGUAGE_TARGET_CPP=1
    target_case GLSL -D__METAL_VERSION__=230 -DOPENPBR_LANGUAGE_TARGET_GLSL=1
    # A wrong expectation must fail, or the cases above prove nothing.
    run_fails "router: the checker itself rejects a wrong expectation" "expected the GLSL backend" \
      "$CXX" -std=c++17 -fsyntax-only -I "$SRC" -DEXPECT_GLSL "$HERE/hooks/hook_language_target.cpp"
    run_fails "router: two explicit targets are an error" "more than one OPENPBR_LANGUAGE_TARGET" \
      "$CXX" -std=c++17 -fsyntax-only -I "$SRC" -DEXPECT_CPP -DOPENPBR_LANGUAGE_TARGET_CPP=1 -DOPENPBR_LANGUAGE_TARGET_MSL=1 \
      "$HERE/hooks/hook_language_target.cpp"
    run_fails "C++ without <glm/glm.hpp> first: the interop's #error" "include <glm/glm.hpp> before the OpenPBR headers" \
      "$CXX" -std=c++17 -fsyntax-only -I "$SRC" "$HERE/hooks/hook_missing_glm.cpp"
    run_fails "OPENPBR_USE_TEXTURE_LUTS=1 without the texture macros: the #error" \
      "define OPENPBR_SAMPLE_2D_TEXTURE(lut_id, uv) and OPENPBR_SAMPLE_3D_TEXTURE" \
      "$CXX" -std=c++17 -fsyntax-only -I "$SRC" -DOPENPBR_USE_TEXTURE_LUTS=1 "$HERE/hooks/hook_texture_luts_missing.cpp"
    run_fails "GLSL: OPENPBR_USE_TEXTURE_LUTS=1 without the texture macros: the #error" "OPENPBR_SAMPLE_2D_TEXTURE" \
      "$GLSLANG" -V --target-env vulkan1.2 -S comp -DOPENPBR_USE_TEXTURE_LUTS=1 -o "$WORK/t.spv" "$HERE/api_compat.comp"
    run "GLSL: texture tables through the library's declarations compile" "$GLSLANG" -V --target-env vulkan1.2 -S comp \
      -DOPENPBR_USE_TEXTURE_LUTS=1 -DOPENPBR_LUT_TEXTURES_DECLARE=1 -o "$WORK/t.spv" "$HERE/api_compat.comp"
    run "GLSL host saturate() with OPENPBR_USE_CUSTOM_SATURATE=1 compiles" "$GLSLANG" -V --target-env vulkan1.2 -S comp \
      -DOPENPBR_USE_CUSTOM_SATURATE=1 -o "$WORK/saturate.spv" "$HERE/hooks/hook_custom_saturate.comp"
    run_fails "GLSL host saturate() without the hook collides with the backend's" "function already has a body" \
      "$GLSLANG" -V --target-env vulkan1.2 -S comp -o "$WORK/saturate.spv" "$HERE/hooks/hook_custom_saturate.comp"
    ;;
  *)
    echo "usage: check_api_compat.sh glsl|slang|hlsl|cuda|hooks" >&2
    exit 2
    ;;
esac
echo "$PASSES passed, $FAILURES failed"
[ "$FAILURES" -eq 0 ]
