// The api_compat program run on a CUDA device and on the host from the same translation unit
// (the headers' CUDA backend, __host__ __device__ functions): every result finite on both, and
// the device's results within float tolerance of the host's. Compiled everywhere nvcc is
// (tests/api_compat/check_api_compat.sh cuda: -rdc, every warning an error), run on machines
// with a GPU: nvcc -std=c++17 -rdc=true -arch=sm_90 -I . -o api_compat_device
// tests/api_compat/api_compat_device.cu && ./api_compat_device
#include <glm/glm.hpp>

#include "slang/openpbr.h"
#if !defined(OPENPBR_LANGUAGE_TARGET_CUDA)
#error "the interop router did not pick the CUDA backend under nvcc"
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

__device__ float* api_compat_results_device;
float* api_compat_results_host = nullptr;
__host__ __device__ inline void api_compat_store(unsigned index, float value)
{
#ifdef __CUDA_ARCH__
    api_compat_results_device[index] = value;
#else
    api_compat_results_host[index] = value;
#endif
}
#define API_COMPAT_WRITE(index, value) api_compat_store((index), (value))
#include "tests/api_compat/api_compat_program.h"

// Case k: a material and query derived from k alone (the same on host and device).
__host__ __device__ inline void api_compat_case(unsigned k, openpbr::OpenPBR_ResolvedInputs& inputs, glm::vec3& view,
                                                glm::vec3& light, glm::vec3& throughput, float& exterior_ior, glm::vec3& u,
                                                glm::vec2& medium_u)
{
    using namespace openpbr;
    const auto hash = [k](unsigned salt) {
        unsigned x = k * 747796405u + salt * 2891336453u;
        x = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
        return float((x >> 22u) ^ x & 0xffffffu) * (1.0f / 16777216.0f);
    };
    inputs = openpbr_make_default_resolved_inputs();
    inputs.base_color = glm::vec3(hash(1), hash(2), hash(3));
    inputs.base_metalness = hash(4) < 0.3f ? 0.0f : hash(5);
    inputs.specular_roughness = hash(6) < 0.2f ? 0.0f : hash(7);
    inputs.transmission_weight = hash(8) < 0.5f ? 0.0f : hash(9);
    inputs.transmission_depth = hash(10) < 0.5f ? 0.0f : hash(11);
    inputs.subsurface_weight = hash(12) < 0.5f ? 0.0f : hash(13);
    inputs.coat_weight = hash(14) < 0.5f ? 0.0f : hash(15);
    inputs.fuzz_weight = hash(16) < 0.5f ? 0.0f : hash(17);
    inputs.geometry_opacity = hash(18) < 0.7f ? 1.0f : hash(19);
    inputs.emission_luminance = hash(20) < 0.7f ? 0.0f : 3.0f;
    const float z = 1.0f - 2.0f * hash(21);
    const float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    view = glm::vec3(r * cosf(6.2831853f * hash(22)), r * sinf(6.2831853f * hash(22)), z);
    light = glm::normalize(glm::vec3(hash(23) - 0.5f, hash(24) - 0.5f, hash(25)));
    throughput = k % 4u == 0u ? glm::vec3(1.0f) : glm::vec3(hash(26), hash(27), hash(28));
    exterior_ior = k % 3u == 0u ? 1.0f : 1.33f;
    u = glm::vec3(hash(29), hash(30), hash(31));
    medium_u = glm::vec2(hash(32), hash(33));
}

__global__ void api_compat_kernel(float* results, unsigned count)
{
    const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= count)
    {
        return;
    }
    api_compat_results_device = results;
    openpbr::OpenPBR_ResolvedInputs inputs;
    glm::vec3 view, light, throughput, u;
    glm::vec2 medium_u;
    float exterior_ior = 1.0f;
    api_compat_case(k, inputs, view, light, throughput, exterior_ior, u, medium_u);
    openpbr::api_compat_shade(inputs, view, light, throughput, exterior_ior, u, medium_u, k * API_COMPAT_RESULT_COUNT);
}

int main()
{
    const unsigned count = 4096;
    const size_t floats = size_t(count) * API_COMPAT_RESULT_COUNT;
    std::vector<float> host(floats), device(floats);
    api_compat_results_host = host.data();
    for (unsigned k = 0; k < count; ++k)
    {
        openpbr::OpenPBR_ResolvedInputs inputs;
        glm::vec3 view, light, throughput, u;
        glm::vec2 medium_u;
        float exterior_ior = 1.0f;
        api_compat_case(k, inputs, view, light, throughput, exterior_ior, u, medium_u);
        openpbr::api_compat_shade(inputs, view, light, throughput, exterior_ior, u, medium_u, k * API_COMPAT_RESULT_COUNT);
    }
    float* results = nullptr;
    if (cudaMalloc(&results, floats * sizeof(float)) != cudaSuccess)
    {
        std::printf("no CUDA device\n");
        return 77;
    }
    api_compat_kernel<<<(count + 63) / 64, 64>>>(results, count);
    if (cudaMemcpy(device.data(), results, floats * sizeof(float), cudaMemcpyDeviceToHost) != cudaSuccess)
    {
        std::printf("kernel failed: %s\n", cudaGetErrorString(cudaGetLastError()));
        return 1;
    }
    int nonfinite = 0;
    size_t exact = 0;
    std::vector<float> relative;
    for (size_t i = 0; i < floats; ++i)
    {
        nonfinite += std::isfinite(host[i]) && std::isfinite(device[i]) ? 0 : 1;
        exact += host[i] == device[i] ? 1u : 0u;
        const float scale = std::fmax(std::fabs(host[i]), 1e-3f);
        relative.push_back(std::fabs(host[i] - device[i]) / scale);
    }
    std::vector<float> sorted = relative;
    std::sort(sorted.begin(), sorted.end());
    std::printf("api_compat on the device: %u cases, %zu floats, %zu bit-equal to the host, non-finite %d, "
                "relative difference median %.2e, p99.9 %.2e, max %.2e\n",
                count, floats, exact, nonfinite, double(sorted[floats / 2]), double(sorted[size_t(0.999 * floats)]),
                double(sorted.back()));
    return nonfinite == 0 ? 0 : 1;
}
