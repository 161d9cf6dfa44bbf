// The api_compat program as CUDA (nvcc, compile only): the headers' CUDA backend, chosen by the
// router from __CUDACC__.
#include <glm/glm.hpp>

#include "slang/openpbr.h"
#if !defined(OPENPBR_LANGUAGE_TARGET_CUDA)
#error "the interop router did not pick the CUDA backend under nvcc"
#endif

__device__ float* api_compat_results_device;
// Device stores only: the program's functions are __host__ __device__ (OPENPBR_FUNC).
__host__ __device__ inline void api_compat_store(unsigned index, float value)
{
#ifdef __CUDA_ARCH__
    api_compat_results_device[index] = value;
#else
    (void)index;
    (void)value;
#endif
}
#define API_COMPAT_WRITE(index, value) api_compat_store((index), (value))
#include "tests/api_compat/api_compat_program.h"

__global__ void api_compat_kernel(float* results)
{
    using namespace openpbr;
    api_compat_results_device = results;
    api_compat_shade(openpbr_make_default_resolved_inputs(), vec3(0.0f, 0.0f, 1.0f), normalize(vec3(0.3f, 0.2f, 0.9f)),
                     vec3(1.0f, 0.5f, 0.25f), OpenPBR_VacuumIor, vec3(0.3f, 0.6f, 0.9f), vec2(0.4f, 0.7f),
                     static_cast<unsigned>(threadIdx.x) * API_COMPAT_RESULT_COUNT);
}
