// The CUDA conformance paths, as host functions over device buffers; each lives in its own
// translation unit (the two kernels bring their own tables and preludes):
//   cuda        the single-source headers through their CUDA backend (headers_conformance.cu)
//   slang-cuda  Slang's CUDA output of targets/kernels/conformance.slang (slang_conformance.cu)
// Both read the query/material records of targets/kernels/openpbr_conformance_kernel.h and
// write OPENPBR_RESULT_FLOATS floats per query.
#pragma once

#include <cstddef>

#include <cuda_runtime.h>

namespace openpbr::cuda_conformance {

// Record sizes of targets/kernels/openpbr_conformance_kernel.h (checked there by
// headers_conformance.cu), e.g. 11 floats per query.
constexpr unsigned query_floats = 11;
constexpr unsigned result_floats = 24;

// Device pointers (cudaMalloc'ed by the caller) and the query count.
struct DeviceBatch
{
    const float* queries = nullptr;
    const float* materials = nullptr;
    std::size_t material_floats = 0;
    const float* lut = nullptr;  // the floats of openpbr_lut.bin (slang-cuda only)
    std::size_t lut_count = 0;
    const float* fuzz_ltc = nullptr;  // the floats of openpbr_fuzz_ltc.bin (slang-cuda only)
    std::size_t fuzz_ltc_count = 0;
    float* results = nullptr;
    unsigned query_count = 0;
    // OPENPBR_CONFORMANCE_MODE_* of targets/kernels/openpbr_conformance_kernel.h: 0 runs
    // everything (conformance); 1 eval, 2 sample, 3 pdf (each after prepare) for timings.
    unsigned mode = 0;
    // When set, recorded right before and right after the kernel launch (device timing).
    cudaEvent_t kernel_start = nullptr;
    cudaEvent_t kernel_stop = nullptr;
};

// Both launch one thread per query in blocks of 64 and wait for the kernel; they return
// cudaSuccess or the first CUDA error as an int (cudaError_t).
int run_headers_conformance(const DeviceBatch& batch);
int run_slang_conformance(const DeviceBatch& batch);

}  // namespace openpbr::cuda_conformance
