#!/usr/bin/env bash
# Self-test of targets/slangc.mjs: compiles a small compute shader that imports a module with
# #include'd headers and a specialization constant to every target, then checks error cases.
# Needs `npm ci` in the repository root. Uses spirv-dis/spirv-val when installed.
set -u

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SLANGC=(node "$ROOT/targets/slangc.mjs")
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
FAILURES=0

fail() { echo "FAIL: $*"; FAILURES=$((FAILURES + 1)); }
pass() { echo "ok:   $*"; }

mkdir -p "$WORK/slang/inc"
cat > "$WORK/slang/inc/consts.h" <<'EOF'
#pragma once
/* A directive inside a comment is not followed:
#include "does_not_exist.h"
*/
static const float kScale = SCALE;
EOF
cat > "$WORK/slang/inc/helpers.h" <<'EOF'
#pragma once
#include "consts.h"
float scaled(float x) { return x * kScale; }
EOF
cat > "$WORK/slang/mylib.slang" <<'EOF'
// No `module` line: every declaration is visible to importers.
#include "inc/helpers.h"
#include "inc/consts.h"
[vk::constant_id(0)] const bool USE_SCALE = true;
float apply(float x) { return USE_SCALE ? scaled(x) : x; }
EOF
cat > "$WORK/main.slang" <<'EOF'
import mylib;
RWStructuredBuffer<float> data;
[shader("compute")]
[numthreads(64, 1, 1)]
void computeMain(uint3 id : SV_DispatchThreadID)
{
    data[id.x] = apply(data[id.x]) + BIAS;
}
EOF
cd "$WORK" || exit 1
FLAGS=(-entry computeMain -stage compute -DSCALE=2.0 -D BIAS -I slang)

# Every target, one process each.
for target in spirv hlsl glsl metal cuda wgsl; do
  if "${SLANGC[@]}" -target "$target" "${FLAGS[@]}" -o "out/main.$target" main.slang 2> err.txt \
      && [ -s "out/main.$target" ]; then
    pass "$target"
  else
    fail "$target: $(cat err.txt)"
  fi
done

# The specialization constant survives on the targets that have them.
grep -q 'constant_id = 0' out/main.glsl || fail 'GLSL lost layout(constant_id = 0)'
grep -q 'function_constant(0)' out/main.metal || fail 'Metal lost [[function_constant(0)]]'
if [ "$(od -An -tx4 -N4 out/main.spirv | tr -d ' ')" != 07230203 ]; then
  fail 'SPIR-V output lacks the magic number'
fi
if command -v spirv-dis > /dev/null; then
  dis="$(spirv-dis out/main.spirv)"
  grep -q 'OpSpecConstantTrue' <<< "$dis" || fail 'SPIR-V lost OpSpecConstantTrue'
  grep -q 'SpecId 0' <<< "$dis" || fail 'SPIR-V lost SpecId 0'
  grep -q 'OpSource Unknown' <<< "$dis" || fail 'SPIR-V OpSource language not rewritten'
  pass 'SPIR-V specialization constant and OpSource'
fi
if command -v spirv-val > /dev/null; then
  spirv-val --target-env vulkan1.2 out/main.spirv && pass 'spirv-val' || fail 'spirv-val'
fi

# Several targets in one process, with a depfile.
if "${SLANGC[@]}" -target all "${FLAGS[@]}" -o out/all -depfile out/all.d main.slang \
    && [ -s out/all/main.spv ] && [ -s out/all/main.hlsl ] && [ -s out/all/main.metal ] \
    && [ -s out/all/main.cu ] && [ -s out/all/main.glsl ] \
    && grep -q 'slang/inc/consts.h' out/all.d && grep -q 'slang/mylib.slang' out/all.d; then
  pass '-target all with -depfile'
else
  fail '-target all with -depfile'
fi

# A module without entry points gives its export functions on text targets.
printf 'export float twice(float x) { return 2.0 * x; }\n' > lib.slang
if "${SLANGC[@]}" -target hlsl lib.slang | grep -q 'twice'; then
  pass 'module-level export code'
else
  fail 'module-level export code'
fi

# A header first included under an inactive #if is still there for a later active include.
printf '#pragma once\nfloat common_fn(float x) { return x + 1.0; }\n' > common.h
printf '#pragma once\n#include "common.h"\nfloat cuda_fn(float x) { return common_fn(x); }\n' > cuda_side.h
cat > router.slang <<'EOF'
#ifdef USE_CUDA
#include "cuda_side.h"
#endif
#include "common.h"
#include "router.slang"
export float routed(float x) { return common_fn(x); }
EOF
if "${SLANGC[@]}" -target glsl router.slang 2> err.txt | grep -q 'common_fn'; then
  pass 'include after an inactive #if branch'
else
  fail "include after an inactive #if branch: $(cat err.txt)"
fi
{ cat router.slang; echo 'float broken() { return undefined_name; }'; } > router_bad.slang
"${SLANGC[@]}" -target glsl router_bad.slang > /dev/null 2> err.txt
if grep -q 'router_bad.slang(7): error' err.txt; then
  pass 'line numbers after an inactive include'
else
  fail "line numbers after an inactive include: $(cat err.txt)"
fi

# A compile error exits non-zero and points at the real file and line.
sed 's/x \* kScale/x * kScalez/' slang/inc/helpers.h > helpers_bad.h
mkdir -p bad/inc && cp slang/inc/consts.h bad/inc/ && cp helpers_bad.h bad/inc/helpers.h
cp slang/mylib.slang bad/
if "${SLANGC[@]}" -target hlsl -DSCALE=2.0 -D BIAS -I bad -o out/bad.hlsl main.slang 2> err.txt; then
  fail 'error case exited 0'
elif grep -q 'bad/inc/helpers.h(3): error' err.txt; then
  pass 'error case reports bad/inc/helpers.h(3)'
else
  fail "error case message: $(cat err.txt)"
fi

# A missing entry point is an error too.
if "${SLANGC[@]}" -target glsl -entry nope -DSCALE=1 -DBIAS=0 -I slang main.slang > /dev/null 2>&1; then
  fail 'missing entry point exited 0'
else
  pass 'missing entry point fails'
fi

if [ "$FAILURES" -ne 0 ]; then
  echo "$FAILURES check(s) failed"
  exit 1
fi
echo 'all slangc checks passed'
