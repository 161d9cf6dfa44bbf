#!/usr/bin/env bash
# The ctest checks of every target (targets/CMakeLists.txt): bash targets/check_targets.sh CHECK
#   spirv         spirv-val (Vulkan 1.2) on Slang's SPIR-V of the conformance kernel and example
#   glsl          glslang on Slang's GLSL of both
#   hlsl          glslang's HLSL front end (-D) on Slang's HLSL of both
#   hlsl_library  the generated openpbr.hlsl: check_targets.mjs hlsl-library, then glslang -D on
#                 its conformance kernel (default registers, and overridden ones), spirv-val
#   metal         check_targets.mjs metal on Slang's Metal of both (no Metal compiler on Linux)
#   cuda_nvcc     nvcc: the four CUDA translation units and the conformance program
#   cpp COMPILER  the headers under COMPILER -Wall -Wextra -Werror, array and buffer mode
# Environment (set by CMake): OPENPBR_TARGETS_DIR (the `openpbr compile --target all` output),
# OPENPBR_SOURCE_DIR, GLSLANG_VALIDATOR, SPIRV_VAL, NODE, OPENPBR_NVCC, CMAKE_COMMAND,
# OPENPBR_BUILD_DIR. Exit status 77 = skipped (tool missing), said plainly.
set -u

OUT="${OPENPBR_TARGETS_DIR:?}"
SRC="${OPENPBR_SOURCE_DIR:?}"
GLSLANG="${GLSLANG_VALIDATOR:-glslangValidator}"
NODE="${NODE:-node}"
source "$SRC/targets/check_lib.sh"

skip() { echo "skipped: $*"; exit 77; }

finish() {
  echo "$PASSES passed, $FAILURES failed"
  [ "$FAILURES" -eq 0 ]
  exit $?
}

case "${1:-}" in
  spirv)
    [ -n "${SPIRV_VAL:-}" ] && [ -x "${SPIRV_VAL}" ] || skip "spirv-val not found"
    for f in "$OUT/spirv/conformance.slang.spv" "$OUT/spirv/shade_batch.spv"; do
      run "spirv-val --target-env vulkan1.2 $(basename "$f")" "$SPIRV_VAL" --target-env vulkan1.2 "$f"
    done
    ;;
  glsl)
    for f in "$OUT/glsl/conformance.slang.glsl" "$OUT/glsl/shade_batch.glsl"; do
      run "glslang -V $(basename "$f")" "$GLSLANG" -V --target-env vulkan1.2 -S comp -o "$WORK/out.spv" "$f"
    done
    ;;
  hlsl)
    # Slang writes explicit registers (t, u; b0 for the spec-constant/uniform cbuffer): shift
    # the cbuffers away from the t/u bindings, as a Vulkan host would. -Od everywhere: glslang
    # 11.12's optimizer takes 10-15 s on these kernels and is not what is being checked.
    run "glslang -D conformance.slang.hlsl" "$GLSLANG" -D -V -Od -S comp -e main --source-entrypoint conformance_main \
      --hlsl-iomap --shift-cbuffer-binding 8 -o "$WORK/c.spv" "$OUT/hlsl/conformance.slang.hlsl"
    run "glslang -D shade_batch.hlsl" "$GLSLANG" -D -V -Od -S comp -e main --source-entrypoint shade_batch \
      --hlsl-iomap --shift-cbuffer-binding 8 -o "$WORK/s.spv" "$OUT/hlsl/shade_batch.hlsl"
    ;;
  hlsl_library)
    run "check_targets.mjs hlsl-library openpbr.hlsl" "$NODE" "$SRC/targets/check_targets.mjs" hlsl-library "$OUT/hlsl/openpbr.hlsl"
    run "glslang -D conformance.hlsl (includes openpbr.hlsl)" "$GLSLANG" -D -V -Od -S comp -e main --hlsl-iomap \
      -o "$WORK/lib.spv" "$OUT/hlsl/conformance.hlsl"
    if [ -n "${SPIRV_VAL:-}" ] && [ -x "${SPIRV_VAL}" ]; then
      # glslang's HLSL output is SPIR-V 1.0 with BufferBlock: valid for Vulkan 1.0 rules.
      run "spirv-val conformance.hlsl.spv" "$SPIRV_VAL" --target-env vulkan1.0 "$WORK/lib.spv"
    fi
    # Registers overridden by the includer: t7/t8 in space2.
    run "glslang -D with OPENPBR_LUT_BINDING=7 OPENPBR_FUZZ_LTC_BINDING=8 OPENPBR_HLSL_REGISTER_SPACE=2" \
      "$GLSLANG" -D -V -Od -S comp -e main --hlsl-iomap -DOPENPBR_LUT_BINDING=7 -DOPENPBR_FUZZ_LTC_BINDING=8 \
      -DOPENPBR_HLSL_REGISTER_SPACE=2 -o "$WORK/moved.spv" "$OUT/hlsl/conformance.hlsl"
    if command -v spirv-dis > /dev/null; then
      spirv-dis "$WORK/moved.spv" > "$WORK/moved.txt" 2>&1
      check_binding() { # NAME BINDING SET
        grep -q "OpDecorate %$1 Binding $2\$" "$WORK/moved.txt" && grep -q "OpDecorate %$1 DescriptorSet $3\$" "$WORK/moved.txt"
      }
      run "overridden registers reach the SPIR-V (lut 7, fuzz 8, set 2)" \
        bash -c "$(declare -f check_binding); WORK='$WORK'; check_binding 'openpbr_lut_data[_0-9]*' 7 2 && check_binding 'openpbr_fuzz_ltc_data[_0-9]*' 8 2"
    fi
    ;;
  metal)
    run "metal conformance.slang.metal" "$NODE" "$SRC/targets/check_targets.mjs" metal "$OUT/metal/conformance.slang.metal" \
      conformance_main "$SRC/targets/kernels/conformance.slang" "$SRC/slang/openpbr_features.h"
    run "metal shade_batch.metal" "$NODE" "$SRC/targets/check_targets.mjs" metal "$OUT/metal/shade_batch.metal" \
      shade_batch "$SRC/examples/shade_batch.slang" "$SRC/slang/openpbr_features.h"
    ;;
  cuda_nvcc)
    [ -x "${OPENPBR_NVCC:-}" ] || skip "nvcc not found (${OPENPBR_NVCC:-unset})"
    run "nvcc: Slang's CUDA (conformance, example) and the headers' CUDA backend, linked" \
      "${CMAKE_COMMAND:?}" --build "${OPENPBR_BUILD_DIR:?}" --target openpbr_cuda_programs
    ;;
  cpp)
    compiler="${2:-}"
    [ -n "$compiler" ] && [ -x "$compiler" ] || skip "C++ compiler '${compiler}' not found"
    for mode in "" "-DOPENPBR_LUT_MODE_BUFFER"; do
      run "$(basename "$compiler") -Wall -Wextra -Werror ${mode:-(array mode)}" "$compiler" -std=c++17 -Wall -Wextra -Werror -O2 \
        $mode -I "$SRC" -c -o "$WORK/tu.o" "$SRC/targets/cpp/headers_warning_check.cpp"
    done
    ;;
  *)
    echo "usage: check_targets.sh spirv|glsl|hlsl|hlsl_library|metal|cuda_nvcc|cpp COMPILER" >&2
    exit 2
    ;;
esac
finish
