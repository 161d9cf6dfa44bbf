// bench_gpu.h - `openpbr bench gpu`: BSDF throughput measured on the device itself, for each
// execution path asked for (host/checks/execution_path.h; default slang-spirv, cuda, slang-cuda),
// through the paths' one interface: per entry, toggle set and operation one batch, its kernel
// time per query as the path measures it on its device (PathRun):
//   - Vulkan paths: the conformance kernel in three modes, each prepare plus one operation
//     (eval, sample, pdf: OPENPBR_CONFORMANCE_MODE_* of targets/kernels/openpbr_conformance_kernel.h),
//     with its buffers in device-local memory uploaded once (PathBatch::device_local) and the
//     time between two vkCmdWriteTimestamp around the dispatch (ticks x timestampPeriod),
//     median over repeats after the first; pipelines built once per toggle set and kept.
//   - CUDA paths: the CUDA conformance program's kernels timed with CUDA events (median of 5
//     after a warm-up), one program run per entry for every operation; its one kernel has every
//     toggle on, so the specialized column is not run.
//   - WebGPU paths (slang-wgsl, wgsl-library; opt-in, SwiftShader builds each pipeline for
//     seconds): timestamp queries around the compute pass, median after the first of the
//     repeats; the toggle set as the kernel's `override` constants at pipeline creation, one
//     Dawn process (and pipeline build) per batch.
// Each rate is the median over `rounds` passes over every entry. Per material class (the
// materials grouped by the toggle set they need, host/scene/features.h), on the full pipeline
// and on the pipeline specialized to the class. A path that cannot run here is reported with
// its reason and skipped.
// With `features` (`--features`), one entry per feature variant of
// host/studies/feature_variants.h (Default, EveryLobe, Only/<feature>, Without/<feature>: the
// rows of benchmark_bsdf's per-feature table) instead of the material classes, each a single
// material on the full pipeline (run-time branching, as the CPU build) and on the pipeline
// specialized to the toggles it needs; the report adds per path and feature "alone"
// (Only/<feature> - Default) and "saved" (EveryLobe - Without/<feature>). Every mode runs
// prepare, so prepare alone is not timed: the pdf mode, whose operation is the cheapest, is the
// closest to it. Every rate names its device as the path reports it. Timings only: nothing
// passes or fails.
// JSON: {"set": "material classes"|"features", "queries_per_class", "repeats", "rounds",
//   "timing", "paths": [{"name", "description", "device" | "skipped", "specialized_skipped"
//   (where the path ran but has no specialized form)}], "classes": [{"variant" (features only),
//   "toggles", "materials", "paths": {<path>: {"full"|"specialized": {"eval"|"sample"|"pdf":
//   {"ns_per_query", "queries_per_second", "ns_per_round": [...]}}, "full_statistics",
//   "specialized_statistics" (where the driver reports them)}}}], "feature_costs" (features
//   only): {<path>: {<feature>: {"full"|"specialized": {"eval"|"sample"|"pdf": {"alone_ns",
//   "saved_ns"}}}}}}.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace openpbr::host {

struct GpuBenchOptions
{
    std::string materials_directory;  // e.g. "materials"
    std::string kernel_directory;     // e.g. "build/kernels"
    // Execution paths in report order, e.g. {"glsl-spirv", "slang-wgsl"}; an unknown name is an
    // error naming the known ones.
    std::vector<std::string> paths = {"slang-spirv", "cuda", "slang-cuda"};
    std::size_t queries = 1u << 20;  // queries per class and kernel, e.g. 4096 on lavapipe
    int repeats = 10;                // dispatches per kernel, median of 2..n, e.g. 10
    // Passes over every entry, each rate the median of the passes' medians, e.g. 6 on a shared
    // machine (a slow spell then falls on every entry, not on those measured during it).
    int rounds = 1;
    bool features = false;  // true: the feature variants instead of the material classes
    // Only these entries, by name: a material class's toggle set ("base", "coat+metal") or a
    // feature variant ("Default", "Only/coat"); empty: every entry. E.g. for the WebGPU paths,
    // whose every batch builds a pipeline.
    std::vector<std::string> entries;
};

nlohmann::json run_gpu_bench(const GpuBenchOptions& options);
std::string gpu_bench_text(const nlohmann::json& report);

}  // namespace openpbr::host
