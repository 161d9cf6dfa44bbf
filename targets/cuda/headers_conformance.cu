// Conformance path "cuda": the single-source headers compiled by nvcc through the interop's
// CUDA backend (GLM for host and device; tables in array mode, compiled into the module),
// running the shared kernel body of targets/kernels/openpbr_conformance_kernel.h.
#include <cuda_runtime.h>

#include "slang/openpbr.h"
#include "targets/cuda/openpbr_cuda_conformance.h"

namespace {

struct KernelBuffers
{
    const float* queries;
    const float* materials;
    float* results;
};

__constant__ KernelBuffers kernel_buffers;

#ifndef __CUDA_ARCH__
// The body's functions are __host__ __device__; their host side is compiled, never called.
inline KernelBuffers& host_buffers()
{
    static KernelBuffers buffers = {nullptr, nullptr, nullptr};
    return buffers;
}
#endif

}  // namespace

#ifdef __CUDA_ARCH__
#define OPENPBR_CUDA_BUFFERS kernel_buffers
#else
#define OPENPBR_CUDA_BUFFERS host_buffers()
#endif
#define OPENPBR_QUERY_READ(index) OPENPBR_CUDA_BUFFERS.queries[index]
#define OPENPBR_MATERIAL_READ(index) OPENPBR_CUDA_BUFFERS.materials[index]
#define OPENPBR_RESULT_WRITE(index, value) OPENPBR_CUDA_BUFFERS.results[index] = (value)
#include "targets/kernels/openpbr_conformance_kernel.h"

static_assert(OPENPBR_QUERY_FLOATS == openpbr::cuda_conformance::query_floats, "query record size");
static_assert(OPENPBR_RESULT_FLOATS == openpbr::cuda_conformance::result_floats, "result record size");

__global__ void openpbr_headers_conformance_kernel(unsigned query_count, unsigned mode)
{
    const unsigned query = blockIdx.x * blockDim.x + threadIdx.x;
    if (query < query_count)
    {
        openpbr::openpbr_conformance_run_query(query, mode);
    }
}

namespace openpbr::cuda_conformance {

int run_headers_conformance(const DeviceBatch& batch)
{
    const KernelBuffers buffers = {batch.queries, batch.materials, batch.results};
    cudaError_t status = cudaMemcpyToSymbol(kernel_buffers, &buffers, sizeof(buffers));
    if (status != cudaSuccess)
    {
        return int(status);
    }
    const unsigned blocks = (batch.query_count + 63u) / 64u;
    if (batch.kernel_start)
    {
        cudaEventRecord(batch.kernel_start);
    }
    openpbr_headers_conformance_kernel<<<blocks, 64>>>(batch.query_count, batch.mode);
    status = cudaGetLastError();
    if (batch.kernel_stop)
    {
        cudaEventRecord(batch.kernel_stop);
    }
    if (status != cudaSuccess)
    {
        return int(status);
    }
    return int(cudaDeviceSynchronize());
}

}  // namespace openpbr::cuda_conformance
