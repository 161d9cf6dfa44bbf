// openpbr_cuda_conformance: runs the CUDA conformance paths on one query batch.
//
//   openpbr_cuda_conformance INPUT_DIR [OUTPUT_DIR]
//
// INPUT_DIR holds raw little-endian float32 files, as `openpbr conformance --dump DIR` writes
// them (host/gpu/cuda_conformance.h): queries.f32 (OPENPBR_QUERY_FLOATS per query), materials.f32
// (packed materials), lut.f32 and fuzz_ltc.f32 (the shipped tables). For each path it writes
// OUTPUT_DIR/<path>.results.f32 (OPENPBR_RESULT_FLOATS per query; OUTPUT_DIR defaults to
// INPUT_DIR) and prints one line:
//   cuda: executed on <device>: <queries> queries, first launch <ms> ms, kernel <ms> ms =
//         <ns> ns/query (CUDA events, median of 5 after the first launch); eval <ns> ns/query,
//         sample <ns> ns/query, pdf <ns> ns/query
//   cuda: skipped: no CUDA device
// The first launch includes loading the module (and JIT compilation when the program carries
// no SASS for the device: targets/CMakeLists.txt, OPENPBR_CUDA_ARCHITECTURES). The per-operation
// times run prepare plus that one operation (OPENPBR_CONFORMANCE_MODE_*).
// Exit status: 0 = every path executed; 77 = skipped (no CUDA device or driver); 1 = error.
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "targets/cuda/openpbr_cuda_conformance.h"

namespace {

using openpbr::cuda_conformance::DeviceBatch;

bool read_floats(const std::string& path, std::vector<float>& values)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
    {
        std::fprintf(stderr, "openpbr_cuda_conformance: cannot read %s\n", path.c_str());
        return false;
    }
    const std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (bytes.size() % sizeof(float) != 0)
    {
        std::fprintf(stderr, "openpbr_cuda_conformance: %s is not a float32 array\n", path.c_str());
        return false;
    }
    values.resize(bytes.size() / sizeof(float));
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(values.data()));
    return true;
}

bool write_floats(const std::string& path, const std::vector<float>& values)
{
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
    return bool(file);
}

// A device copy of a host array; freed by the owner.
float* upload(const std::vector<float>& values)
{
    float* device = nullptr;
    if (cudaMalloc(&device, values.size() * sizeof(float)) != cudaSuccess)
    {
        return nullptr;
    }
    if (cudaMemcpy(device, values.data(), values.size() * sizeof(float), cudaMemcpyHostToDevice) != cudaSuccess)
    {
        cudaFree(device);
        return nullptr;
    }
    return device;
}

struct Path
{
    const char* name;
    int (*run)(const DeviceBatch&);
};

// Kernel time of one mode in ns per query: the median of `repeats` launches timed with CUDA
// events around the launch alone (the kernel's parameter upload is outside), after the launches
// that came before (the module is loaded). Negative on a CUDA error.
double timed_ns_per_query(const Path& path, DeviceBatch batch, unsigned mode, int repeats)
{
    batch.mode = mode;
    cudaEventCreate(&batch.kernel_start);
    cudaEventCreate(&batch.kernel_stop);
    std::vector<float> samples;
    for (int repeat = 0; repeat < repeats; ++repeat)
    {
        if (path.run(batch) != cudaSuccess)
        {
            break;
        }
        float ms = 0.0f;
        if (cudaEventElapsedTime(&ms, batch.kernel_start, batch.kernel_stop) == cudaSuccess)
        {
            samples.push_back(ms);
        }
    }
    cudaEventDestroy(batch.kernel_start);
    cudaEventDestroy(batch.kernel_stop);
    if (samples.size() != std::size_t(repeats) || batch.query_count == 0)
    {
        return -1.0;
    }
    std::sort(samples.begin(), samples.end());
    return double(samples[samples.size() / 2]) * 1e6 / double(batch.query_count);
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2 || argc > 3)
    {
        std::fprintf(stderr, "usage: openpbr_cuda_conformance INPUT_DIR [OUTPUT_DIR]\n");
        return 1;
    }
    const std::string input = argv[1];
    const std::string output = argc > 2 ? argv[2] : input;
    const Path paths[] = {{"cuda", openpbr::cuda_conformance::run_headers_conformance},
                          {"slang-cuda", openpbr::cuda_conformance::run_slang_conformance}};

    int device_count = 0;
    const cudaError_t count_status = cudaGetDeviceCount(&device_count);
    if (count_status != cudaSuccess || device_count == 0)
    {
        for (const Path& path : paths)
        {
            std::printf("%s: skipped: no CUDA device (%s)\n", path.name,
                        count_status != cudaSuccess ? cudaGetErrorString(count_status) : "device count 0");
        }
        return 77;
    }
    cudaDeviceProp properties{};
    cudaGetDeviceProperties(&properties, 0);

    std::vector<float> queries, materials, lut, fuzz_ltc;
    if (!read_floats(input + "/queries.f32", queries) || !read_floats(input + "/materials.f32", materials) ||
        !read_floats(input + "/lut.f32", lut) || !read_floats(input + "/fuzz_ltc.f32", fuzz_ltc))
    {
        return 1;
    }
    const unsigned query_count = unsigned(queries.size() / openpbr::cuda_conformance::query_floats);
    const std::size_t result_floats = std::size_t(query_count) * openpbr::cuda_conformance::result_floats;

    DeviceBatch batch;
    batch.query_count = query_count;
    batch.queries = upload(queries);
    batch.materials = upload(materials);
    batch.material_floats = materials.size();
    batch.lut = upload(lut);
    batch.lut_count = lut.size();
    batch.fuzz_ltc = upload(fuzz_ltc);
    batch.fuzz_ltc_count = fuzz_ltc.size();
    if (cudaMalloc(&batch.results, result_floats * sizeof(float)) != cudaSuccess || !batch.queries || !batch.materials ||
        !batch.lut || !batch.fuzz_ltc)
    {
        std::fprintf(stderr, "openpbr_cuda_conformance: device allocation failed\n");
        return 1;
    }

    int status = 0;
    for (const Path& path : paths)
    {
        cudaMemset(batch.results, 0, result_floats * sizeof(float));
        const auto start = std::chrono::steady_clock::now();
        const int error = path.run(batch);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::vector<float> results(result_floats);
        if (error == cudaSuccess)
        {
            const cudaError_t copy =
                cudaMemcpy(results.data(), batch.results, result_floats * sizeof(float), cudaMemcpyDeviceToHost);
            if (copy != cudaSuccess)
            {
                std::printf("%s: error: %s\n", path.name, cudaGetErrorString(copy));
                status = 1;
                continue;
            }
        }
        else
        {
            std::printf("%s: error: %s\n", path.name, cudaGetErrorString(cudaError_t(error)));
            status = 1;
            continue;
        }
        if (!write_floats(output + "/" + path.name + ".results.f32", results))
        {
            std::fprintf(stderr, "openpbr_cuda_conformance: cannot write %s/%s.results.f32\n", output.c_str(), path.name);
            status = 1;
            continue;
        }
        // A warm-up launch per mode, then five timed ones (modes: all, eval, sample, pdf).
        double ns_per_query[4] = {0.0, 0.0, 0.0, 0.0};
        for (unsigned mode = 0; mode < 4; ++mode)
        {
            DeviceBatch warm_up = batch;
            warm_up.mode = mode;
            path.run(warm_up);
            ns_per_query[mode] = timed_ns_per_query(path, batch, mode, 5);
        }
        std::printf("%s: executed on %s (sm_%d%d): %u queries, first launch %.3f ms (includes module load), kernel "
                    "%.6f ms = %.4f ns/query (CUDA events, median of 5 after a warm-up); eval %.4f ns/query, "
                    "sample %.4f ns/query, pdf %.4f ns/query\n",
                    path.name, properties.name, properties.major, properties.minor, query_count, ms,
                    ns_per_query[0] * 1e-6 * double(query_count), ns_per_query[0], ns_per_query[1], ns_per_query[2],
                    ns_per_query[3]);
    }
    cudaFree(const_cast<float*>(batch.queries));
    cudaFree(const_cast<float*>(batch.materials));
    cudaFree(const_cast<float*>(batch.lut));
    cudaFree(const_cast<float*>(batch.fuzz_ltc));
    cudaFree(batch.results);
    return status;
}
