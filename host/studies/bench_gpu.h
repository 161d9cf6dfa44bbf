// bench_gpu.h - `openpbr bench gpu`: BSDF throughput measured on the device itself.
//   - Vulkan: the conformance kernel of one path (default slang-spirv) in three modes, each
//     prepare plus one operation (eval, sample, pdf: OPENPBR_CONFORMANCE_MODE_* of
//     targets/kernels/openpbr_conformance_kernel.h), with its buffers in device-local memory
//     uploaded once (DispatchRequest::device_local) and the time between two
//     vkCmdWriteTimestamp around the dispatch (ticks x timestampPeriod), median over repeats
//     after the first, median over `rounds` passes over every entry; per material class
//     (the materials grouped by the toggle set they need, host/scene/features.h), on the full
//     pipeline and on the pipeline specialized to the class.
//   - CUDA: the CUDA conformance program's kernels timed with CUDA events (median of 5 after a
//     warm-up), per class, for the "cuda" and "slang-cuda" paths.
// With `features` (`--features`), one entry per feature variant of
// host/studies/feature_variants.h (Default, EveryLobe, Only/<feature>, Without/<feature>: the
// rows of benchmark_bsdf's per-feature table) instead of the material classes, each a single
// material on the full pipeline (run-time branching, as the CPU build) and on the pipeline
// specialized to the toggles it needs; the report adds per feature "alone" (Only/<feature> -
// Default) and "saved" (EveryLobe - Without/<feature>). Every mode runs prepare, so prepare
// alone is not timed: the pdf mode, whose operation is the cheapest, is the closest to it.
// Every rate names its device as the driver reports it. Timings only: nothing passes or fails.
// JSON: {"set": "material classes"|"features", "vulkan_device", "cuda_device",
//   "queries_per_class", "repeats", "rounds", "classes": [{"variant" (features only), "toggles",
//   "materials", "vulkan": {"full"|"specialized": {"eval"|"sample"|"pdf": {"ns_per_query",
//   "queries_per_second", "ns_per_round": [...]}}}, "cuda": {"cuda"|"slang-cuda": {...}}}],
//   "feature_costs" (features only): {<feature>: {"full"|"specialized": {"eval"|"sample"|"pdf":
//   {"alone_ns", "saved_ns"}}}}}.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace openpbr::host {

struct GpuBenchOptions
{
    std::string materials_directory;   // e.g. "materials"
    std::string kernel_directory;      // e.g. "build/kernels"
    std::string path = "slang-spirv";  // Vulkan path, e.g. "glsl-spirv"
    std::size_t queries = 1u << 20;    // queries per class and kernel, e.g. 4096 on lavapipe
    int repeats = 10;                  // dispatches per kernel, median of 2..n, e.g. 10
    // Vulkan: passes over every entry, each rate the median of the passes' medians, e.g. 6 on a
    // shared machine (a slow spell then falls on every entry, not on those measured during it).
    int rounds = 1;
    bool vulkan = true;     // false: skip Vulkan
    bool cuda = true;       // false: skip the CUDA program
    bool features = false;  // true: the feature variants instead of the material classes
};

nlohmann::json run_gpu_bench(const GpuBenchOptions& options);
std::string gpu_bench_text(const nlohmann::json& report);

}  // namespace openpbr::host
