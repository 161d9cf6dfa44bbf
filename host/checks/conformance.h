// Cross-target conformance: one batch of BSDF queries (material, view, light, three random
// numbers) evaluated by the CPU build of the single source and by each GPU path, compared
// output by output. See README "Conformance".
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/scene/material_library.h"
#include "host/scene/material_packing.h"
#include "host/gpu/vulkan_runner.h"

namespace openpbr::host {

// Record sizes of targets/kernels/openpbr_conformance_kernel.h (OPENPBR_QUERY_FLOATS and
// OPENPBR_RESULT_FLOATS), for code that does not include the kernel body (conformance.cpp
// checks that they agree).
constexpr std::size_t conformance_query_floats = 11;
constexpr std::size_t conformance_result_floats = 24;

struct ConformanceOptions
{
    std::size_t query_count = 100000;  // e.g. 100000 queries spread evenly over the materials
    std::uint64_t seed = 1;            // queries are a pure function of the seed
    std::string kernel_directory;      // compiled kernels (.spv), e.g. build/kernels
    // Paths to run, e.g. {"slang-spirv", "cpu-fma"}; empty = all_conformance_paths(); {"cpu"} = the
    // CPU build only. An unknown name is an error (std::invalid_argument) naming the known ones.
    std::vector<std::string> paths;
    bool validation = false;  // Vulkan validation layers (on in tests)
    // One pipeline per toggle set the materials need (host/scene/features.h) instead of the full
    // pipeline, e.g. true for `openpbr conformance --specialize`.
    bool specialize = false;
    // Raw CPU results (float32, OPENPBR_RESULT_FLOATS per query), e.g. "cpu.f32" to compare two
    // builds bit for bit; empty writes nothing.
    std::string cpu_dump_path;
    // Raw results of every path that executes (DIR/<path>.f32, float32, OPENPBR_RESULT_FLOATS per
    // query; the CPU build as DIR/cpu.f32), e.g. to check that a refactoring changed no output
    // bit (cmp); empty writes nothing.
    std::string dump_directory;
};

// One output channel of the per-kind metric (docs/conformance.md): a relative error with a
// floor for near-zero values, or an angle in radians.
struct ConformanceChannel
{
    std::string name;       // e.g. "eval.diffuse.r", "sample.consistency.pdf", "sample.direction.angle"
    bool angle = false;     // true: radians between directions; false: relative error
    std::size_t count = 0;  // values compared
    double max = 0.0;       // of the error (relative, or radians)
    double p999 = 0.0;
    // The error of each value over its allowance (ConformanceTolerances): the p99.9 with the
    // p99.9 bound, the largest with the max bound; the channel passes when both are <= 1.
    double p999_bound_ratio = 0.0;
    double max_bound_ratio = 0.0;
    std::string worst;  // the value with the largest max_bound_ratio, for diagnosis
};

// The bounds of the per-kind metric; docs/conformance.md gives the measurements behind each.
// A relative-error value (eval, pdf, emission; a continuous sample's weight and pdf against the
// CPU's eval and pdf at the sample's own direction; a delta sample's weight and pdf) is
// allowed the larger of
//   - relative_p999 (for the 99.9th percentile) or relative_max (for the largest) times
//     max(|cpu|, relative_floor), and
//   - condition_factor times the CPU's own largest change when its view and light move by one
//     ulp (nudge_directions, four patterns): the value's condition, large where float
//     evaluation is ill-conditioned (a sharp anisotropic GGX peak: D's relative error is about
//     ulp(1) / alpha_y).
// Measured over 10^6 queries (cpu-fma, cpu-fast): plain relative error p99.9 <= 2.8e-5 and max
// <= 8.9e-4 (sample.consistency.pdf at pdf 4.4e3); as ratios to the allowance p99.9 <= 0.10 and
// max <= 0.43, so the bounds hold with a margin of 2.3x or more.
struct ConformanceTolerances
{
    double relative_p999 = 1e-5;
    double relative_max = 1e-4;
    // Values below this magnitude are compared in absolute terms (e.g. an eval of 1e-9 at a
    // grazing light, a cancellation of O(1) terms); the pooled metric used the same floor.
    double relative_floor = 1e-3;
    // FMA moves intermediate results by a few ulps where a one-ulp nudge of the inputs moves
    // them by about one: measured largest error / condition 16 x 0.43 = 6.9.
    double condition_factor = 16.0;
    // Angle between the path's and the CPU's sampled directions (agreeing lobes), radians. The
    // CPU's own sampled direction moves by up to 8.6e-5 rad (p99.9 1.2e-6) when each random
    // number moves by one ulp (cpu-ulp, 10^6 queries); FMA moved it by up to 1.2e-5 (p99.9
    // 3.8e-7). 1e-3 rad is 0.06 degrees.
    double angle_p999 = 1e-5;
    double angle_max = 1e-3;
    double lobe_mismatch_fraction = 1e-3;  // u.z on a lobe-selection boundary
};
const ConformanceTolerances& conformance_tolerances();

// The bounds a path is held to: conformance_tolerances(), except on the WebGPU paths
// (execution_path_has_wgsl_math, host/checks/execution_path.h). WGSL specifies its math
// builtins far below correct rounding (sin and cos to an absolute error of 2^-11 on [-pi, pi];
// exp, exp2 to 3 + 2|x| ulp; pow through exp2 and log2), and SwiftShader uses that room: its
// sin and cos are off by up to 1.9e-4 (measured over 65536 arguments in [-pi, pi]) where the
// Vulkan paths here are within 1e-7. Measured on slang-wgsl over 2x10^5 queries (SwiftShader
// 5.0.0): worst channel relative error p99.9 1.5e-5 and max 2.8e-4 (eval.diffuse at an eval of
// 0.01), direction angle p99.9 3.2e-4 rad and max 5.9e-3 rad; the WebGPU bounds hold those with
// a margin of 3.1x or more. At the tests' 2x10^4 queries: relative max 4.3e-5, angle p99.9
// 2.6e-4 and max 1.1e-3 rad.
const ConformanceTolerances& conformance_tolerances(const std::string& path_name);

// Per GPU path, the comparison against the CPU build.
struct ConformancePathResult
{
    std::string name;  // e.g. "slang-spirv"
    bool executed = false;
    std::string note;  // why it did not execute, or the device name
    // The per-kind metric, one entry per channel (see ConformanceTolerances).
    std::vector<ConformanceChannel> channels;
    // The pooled metric (every compared output slot, sampled direction components included,
    // relative error with a 1e-3 floor), kept for comparison: FMA alone breaks its max bound.
    double max_relative_error = 0.0;
    double p999_relative_error = 0.0;
    std::size_t nonfinite = 0;  // non-finite outputs on the GPU side
    double lobe_mismatch_fraction = 0.0;
    double first_dispatch_ms = 0.0;
    double queries_per_second = 0.0;
    std::size_t validation_messages = 0;
    std::string worst_output;        // where the maximum error occurred, for diagnosis
    std::size_t pipeline_count = 0;  // pipelines built (one per toggle set when specialized)
    // Kernel time per query measured on the device (Vulkan timestamps, CUDA events), when the
    // path has one.
    std::optional<double> device_ns_per_query;
};

struct ConformanceReport
{
    std::size_t query_count = 0;
    std::size_t material_count = 0;
    std::size_t cpu_nonfinite = 0;
    double cpu_queries_per_second = 0.0;
    std::vector<ConformancePathResult> paths;
};

// Name of output slot `slot` of a conformance result (e.g. 3 -> "eval.specular.r"); "unused"
// past the last slot.
const char* conformance_slot_name(int slot);

// The GPU paths this build knows (Vulkan, CUDA, then WebGPU), in report order
// (host/checks/execution_path.h).
std::vector<std::string> known_conformance_paths();

// Every conformance path: cpu_conformance_paths(), then known_conformance_paths().
std::vector<std::string> all_conformance_paths();

// The CPU paths compared like GPU paths: "cpu-fma" and "cpu-fast" (host/checks/
// conformance_cpu_variants.h: the kernel rounded like a GPU) and "cpu-ulp" (the CPU build with
// every random number moved by one ulp: the chaos of the sampled outputs, as a reference).
std::vector<std::string> cpu_conformance_paths();

// The queries with each random number u moved by one ulp (up; down at the largest float below 1).
std::vector<float> nudge_random_numbers(const std::vector<float>& queries);

// The queries with every view and light component moved by one ulp, signs by pattern (0-3):
// small rotations about four different axes.
std::vector<float> nudge_directions(const std::vector<float>& queries, int pattern);

// Materials used by conformance: the given library plus synthetic materials that switch on
// every lobe at partial weight, and three that exercise what OpenPBR 1.1.1 states (an HDR
// emission colour, a tinted metal at part weight, thin-walled subsurface with a radius).
std::vector<Material> conformance_materials(const std::vector<Material>& library);

// Deterministic query batch.
std::vector<float> make_queries(std::size_t query_count, std::size_t material_count, std::uint64_t seed);

// The CPU build of the conformance kernel; results as laid out in openpbr_conformance_kernel.h.
std::vector<float> run_conformance_cpu(const std::vector<float>& queries, const std::vector<float>& materials);

// How a conformance kernel is dispatched: the kernel's mode (OPENPBR_CONFORMANCE_MODE_* of
// targets/kernels/openpbr_conformance_kernel.h, e.g. 1 = prepare + eval only; 0 = everything,
// as conformance runs) and where its buffers live (DispatchRequest::device_local, e.g. true for
// throughput measurements on a discrete GPU).
struct ConformanceDispatchSettings
{
    std::uint32_t mode = 0;
    bool device_local = false;
    // Tables as sampled images (OPENPBR_USE_TEXTURE_LUTS kernels, slang/openpbr_lut_textures.h)
    // instead of storage buffers at bindings 0 and 1, e.g. true for the *-texture paths.
    bool texture_tables = false;
};

// The pipeline description of a Vulkan path's conformance kernel (bindings 0 tables, 1 fuzz
// table, 2 queries, 3 materials, 4 parameters, 5 results), without specialization constants.
ComputePipelineDescription conformance_pipeline_description(const std::string& path_name,
                                                            const std::string& kernel_directory);

// One batch on a built conformance pipeline: results (laid out like run_conformance_cpu's; in
// a mode other than 0 only that operation's slots are written) and the dispatch timing.
struct ConformanceDispatch
{
    std::vector<float> results;
    DispatchTiming timing;
};

// A Vulkan path runs a batch this way (host/checks/execution_path.cpp), on a pipeline of
// conformance_pipeline_description: `repeats` dispatches, the steady-state time from the second on.
ConformanceDispatch dispatch_conformance_pipeline(ComputePipeline& pipeline, const std::vector<float>& queries,
                                                  const std::vector<float>& materials, int repeats,
                                                  const ConformanceDispatchSettings& settings);

// One dispatch group of a specialized run: the toggle set, its pipeline's creation and first
// dispatch (where llvmpipe compiles), and the steady-state dispatch time (median of repeats).
struct SpecializedPipelineTiming
{
    std::uint32_t mask = 0;  // OPENPBR_FEATURE_BIT_*
    std::size_t query_count = 0;
    bool built = false;  // false: the pipeline came from the cache
    double create_ms = 0.0;
    double first_dispatch_ms = 0.0;
    double dispatch_ms = 0.0;
    std::optional<double> device_dispatch_ms;  // GPU timestamps, same rule as dispatch_ms
    // The driver's statistics of the pipeline (ComputePipeline::statistics), after its dispatch.
    std::vector<PipelineStatistic> statistics;
};

struct SpecializedConformanceRun
{
    std::vector<float> results;  // laid out like run_conformance_cpu's
    std::vector<SpecializedPipelineTiming> pipelines;
    std::size_t pipeline_builds = 0;
    double dispatch_ms = 0.0;                  // sum of the groups' steady-state dispatch times
    std::optional<double> device_dispatch_ms;  // the same from GPU timestamps, when the queue has them
};

// One GPU path with one pipeline per toggle set (host/scene/features.h): with `pipeline_mask`
// unset, each query runs on the pipeline specialized to its material's needs (pipelines built
// once per set and cached); with it set, every query runs on that one pipeline, after
// check_pipeline_supports refused (FeatureError) any material that needs more. `repeats` >= 1
// dispatches per group (steady-state timing from the second on).
SpecializedConformanceRun run_conformance_gpu_specialized(const std::string& path_name, VulkanContext& context,
                                                          const std::vector<float>& queries,
                                                          const std::vector<Material>& materials,
                                                          const std::string& kernel_directory,
                                                          std::optional<std::uint32_t> pipeline_mask, int repeats,
                                                          const ConformanceDispatchSettings& settings = {});

ConformanceReport run_conformance(const std::vector<Material>& materials, const ConformanceOptions& options);

// The bounds of conformance_tolerances() a path breaks, one line each (empty: it passes).
std::vector<std::string> conformance_violations(const ConformancePathResult& result);

nlohmann::json to_json(const ConformanceReport& report);
std::string to_text(const ConformanceReport& report);

}  // namespace openpbr::host
