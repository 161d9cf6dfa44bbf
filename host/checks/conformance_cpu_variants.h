// CPU conformance paths that round like a GPU (docs/conformance.md, docs/conformance.md):
//   cpu-fma   the conformance kernel compiled with -mfma -ffp-contract=fast: every a * b + c
//             the compiler can fuse becomes one fused multiply-add, as GPU compilers do
//             (NVIDIA's fuse by default, SPIR-V drivers may);
//   cpu-fast  the same plus the fast-math hooks that have a GPU counterpart
//             (OPENPBR_FAST_SQRT and OPENPBR_FAST_NORMALIZE: sqrt and normalize through the
//             reciprocal square root, as GPU compilers lower them). OPENPBR_FAST_RCP_SQRT
//             stays off: in C++ it is a 1.8e-3 bit-trick approximation, not the GPU's
//             hardware rsqrt (a few ulp), so it would test a different BSDF.
// Built on x86-64 compilers that accept -mfma (CMakeLists.txt defines
// OPENPBR_CONFORMANCE_CPU_FMA_BUILT); they run only on CPUs with FMA (checked at run time).
#pragma once

#include <string>
#include <vector>

namespace openpbr::host {

// Why the FMA paths cannot run here (not built, or the CPU lacks FMA); empty when they can.
std::string conformance_cpu_fma_unavailable_reason();

// The kernel of each path on a batch; results laid out as run_conformance_cpu's. Call only
// when conformance_cpu_fma_unavailable_reason() is empty.
std::vector<float> run_conformance_cpu_fma(const std::vector<float>& queries, const std::vector<float>& materials);
std::vector<float> run_conformance_cpu_fast(const std::vector<float>& queries, const std::vector<float>& materials);

}  // namespace openpbr::host
