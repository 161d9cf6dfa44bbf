// bench_specialization.h - `openpbr bench specialization`: what the feature toggles
// (slang/openpbr_features.h) buy, full pipeline versus the pipeline specialized to a scene's
// toggle set, in one run:
//   - the Vulkan device (lavapipe here): BSDF queries per second of the conformance kernel
//     (prepare, eval, pdf and sample per query) timed as `openpbr bench gpu` times it
//     (device-local buffers, GPU timestamps), plus pipeline creation and first dispatch (where
//     llvmpipe compiles) per toggle set;
//   - CPU: ns per openpbr_eval, the full build against the run-time toggles
//     (openpbr_runtime_feature_mask) and, for a base-only scene, the build specialized at
//     compile time (host/studies/bench_specialization_base_only.cpp);
//   - the floor: a bare GGX + Lambert BRDF (Schlick Fresnel, height-correlated Smith, no
//     compensation) measured in the same run.
// JSON: {"scenes": [{"name", "toggles", "gpu_full_qps", "gpu_specialized_qps", "gpu_timing",
//        "cpu_full_ns", "cpu_specialized_ns", ...}], "cpu_floor_ns", "pipelines": [...]}.
// Timings only: nothing here passes or fails.
#pragma once

#include <algorithm>
#include <ctime>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace openpbr::host {

// World-space views and lights (upper hemisphere of +z), a pure function of the seed.
struct BenchDirections
{
    std::vector<glm::vec3> views;
    std::vector<glm::vec3> lights;
};
BenchDirections make_bench_directions(std::size_t count, unsigned seed);

// Median over 7 runs of the ns per call of `call(i, j)` (prepared object i, light j, both below
// `count`), each run 2^18 calls; `call` returns a float that is summed so nothing is elided.
// Thread CPU time, as Google Benchmark's CPU column: wall time counted the time other jobs held
// the core (on the shared 2-core machine the floor read 18 ns idle and 42-49 ns under load).
inline double thread_cpu_seconds()
{
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

template <typename Call> double measure_ns_per_call(std::size_t count, Call call)
{
    constexpr std::size_t calls = std::size_t(1) << 18;
    std::vector<double> runs;
    volatile float sink = 0.0f;
    for (int run = 0; run < 7; ++run)
    {
        float sum = 0.0f;
        const double start = thread_cpu_seconds();
        for (std::size_t k = 0; k < calls; ++k)
        {
            sum += call(k % count, (k * 7 + k / count) % count);
        }
        const double seconds = thread_cpu_seconds() - start;
        sink = sink + sum;
        runs.push_back(seconds * 1e9 / double(calls));
    }
    std::sort(runs.begin(), runs.end());
    return runs[runs.size() / 2];
}

// The compile-time base-only build (all ten toggles 0): ns per eval over packed materials
// (slang/openpbr_material_packing.h layout), and the conformance kernel body on the CPU.
double base_only_eval_ns(const std::vector<float>& packed_materials, std::size_t material_count,
                         const BenchDirections& directions);
std::vector<float> run_conformance_cpu_base_only(const std::vector<float>& queries, const std::vector<float>& materials);

struct SpecializationBenchOptions
{
    std::string materials_directory;   // e.g. "materials"
    std::string kernel_directory;      // e.g. "build/kernels"
    std::string path = "slang-spirv";  // GPU path, e.g. "glsl-spirv"
    std::size_t gpu_queries = 100000;  // queries per scene and pipeline, e.g. 100000
    int gpu_repeats = 5;               // dispatches per pipeline (median of 2..n), e.g. 5
    bool gpu = true;                   // false: CPU numbers only
};

nlohmann::json run_specialization_bench(const SpecializationBenchOptions& options);
std::string specialization_bench_text(const nlohmann::json& report);

}  // namespace openpbr::host
