// Launch wrapper of the example kernel examples/shade_batch.slang for CUDA: Slang's output
// (build/targets/cuda/shade_batch.cu, from `openpbr compile --target cuda`) plus the host
// function a CUDA renderer calls. Compile with -rdc=true: this file defines the parameter block
// SLANG_globalParams that the generated code declares extern (see slang_conformance.cu).
// On CUDA the two specialization constants of the example are fields of that block.
#include <cuda_runtime.h>

#include "shade_batch.cu"

__constant__ GlobalParams_0 SLANG_globalParams;

// Shades `count` queries (ShadeQuery records, 64 bytes) into `results` (ShadeResult records,
// 96 bytes); every pointer is a device pointer. Returns the first CUDA error as an int.
extern "C" int openpbr_shade_batch(const float* materials, size_t material_floats, const void* queries, void* results,
                                   unsigned count, const float* lut, size_t lut_count, const float* fuzz_ltc,
                                   size_t fuzz_ltc_count, bool evaluate, bool sample)
{
    static_assert(sizeof(ShadeQuery_0) == 64, "ShadeQuery layout");
    static_assert(sizeof(ShadeResult_0) == 96, "ShadeResult layout");
    GlobalParams_0 block = {};
    block.SHADE_BATCH_EVALUATE_0 = evaluate;
    block.SHADE_BATCH_SAMPLE_0 = sample;
    block.shade_materials_0.data = const_cast<float*>(materials);
    block.shade_materials_0.count = material_floats;
    block.shade_queries_0.data = static_cast<ShadeQuery_0*>(const_cast<void*>(queries));
    block.shade_queries_0.count = count;
    block.shade_results_0.data = static_cast<ShadeResult_0*>(results);
    block.shade_results_0.count = count;
    block.openpbr_lut_data_0.data = const_cast<float*>(lut);
    block.openpbr_lut_data_0.count = lut_count;
    block.openpbr_fuzz_ltc_data_0.data = const_cast<float*>(fuzz_ltc);
    block.openpbr_fuzz_ltc_data_0.count = fuzz_ltc_count;
    cudaError_t status = cudaMemcpyToSymbol(SLANG_globalParams, &block, sizeof(block));
    if (status != cudaSuccess)
    {
        return int(status);
    }
    // [numthreads(64, 1, 1)] is not enforced by CUDA: launch with that size.
    shade_batch<<<(count + 63u) / 64u, 64>>>(count);
    status = cudaGetLastError();
    return int(status == cudaSuccess ? cudaDeviceSynchronize() : status);
}
