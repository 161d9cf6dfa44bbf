// Conformance path "slang-cuda": Slang's CUDA output of targets/kernels/conformance.slang
// (build/targets/cuda/conformance.slang.cu, from `openpbr compile --target cuda`) and its
// launcher. Compile with -rdc=true: the generated code declares its parameter block
// `extern "C" __constant__ ... SLANG_globalParams;`, which this file defines (without -rdc,
// nvcc treats that extern declaration as a static definition: warning 20044).
// The block (type GlobalParams_0) holds one StructuredBuffer {data, count} per global of the
// kernel; the type and field names are Slang's (name + "_0"), stable for a given kernel source
// and Slang version (decltype(SLANG_globalParams) does not survive nvcc's host-side pass).
#include <cuda_runtime.h>

#include "conformance.slang.cu"

#include "targets/cuda/openpbr_cuda_conformance.h"

__constant__ GlobalParams_0 SLANG_globalParams;

namespace openpbr::cuda_conformance {

namespace {

template <typename T, typename Pointer> void bind(StructuredBuffer<T>& buffer, Pointer data, std::size_t count)
{
    buffer.data = const_cast<T*>(data);
    buffer.count = count;
}

}  // namespace

int run_slang_conformance(const DeviceBatch& batch)
{
    // The query count and the mode are the first entries of the parameter buffer, as in the Vulkan paths.
    unsigned* parameters = nullptr;
    cudaError_t status = cudaMalloc(&parameters, 4 * sizeof(unsigned));
    if (status != cudaSuccess)
    {
        return int(status);
    }
    const unsigned parameter_values[4] = {batch.query_count, batch.mode, 0u, 0u};
    status = cudaMemcpy(parameters, parameter_values, sizeof(parameter_values), cudaMemcpyHostToDevice);

    GlobalParams_0 block = {};
    bind(block.conformance_queries_0, batch.queries, std::size_t(batch.query_count) * query_floats);
    bind(block.conformance_materials_0, batch.materials, batch.material_floats);
    bind(block.conformance_parameters_0, parameters, 4);
    bind(block.conformance_results_0, batch.results, std::size_t(batch.query_count) * result_floats);
    bind(block.openpbr_lut_data_0, batch.lut, batch.lut_count);
    bind(block.openpbr_fuzz_ltc_data_0, batch.fuzz_ltc, batch.fuzz_ltc_count);
    if (status == cudaSuccess)
    {
        status = cudaMemcpyToSymbol(SLANG_globalParams, &block, sizeof(block));
    }
    if (status == cudaSuccess)
    {
        // The kernel's [numthreads(64, 1, 1)] is not enforced by CUDA: launch with that size.
        const unsigned blocks = (batch.query_count + 63u) / 64u;
        if (batch.kernel_start)
        {
            cudaEventRecord(batch.kernel_start);
        }
        conformance_main<<<blocks, 64>>>();
        status = cudaGetLastError();
        if (batch.kernel_stop)
        {
            cudaEventRecord(batch.kernel_stop);
        }
    }
    if (status == cudaSuccess)
    {
        status = cudaDeviceSynchronize();
    }
    cudaFree(parameters);
    return int(status);
}

}  // namespace openpbr::cuda_conformance
