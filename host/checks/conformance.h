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

struct ConformanceOptions
{
    std::size_t query_count = 100000;  // e.g. 100000 queries spread evenly over the materials
    std::uint64_t seed = 1;            // queries are a pure function of the seed
    std::string kernel_directory;      // compiled kernels (.spv), e.g. build/kernels
    std::vector<std::string> paths;    // GPU paths to run, e.g. {"slang-spirv"}; empty = all known
    bool validation = false;           // Vulkan validation layers (on in tests)
    // One pipeline per toggle set the materials need (host/scene/features.h) instead of the full
    // pipeline, e.g. true for `openpbr conformance --specialize`.
    bool specialize = false;
    // Raw CPU results (float32, OPENPBR_RESULT_FLOATS per query), e.g. "cpu.f32" to compare two
    // builds bit for bit; empty writes nothing.
    std::string cpu_dump_path;
};

// Per GPU path, the comparison against the CPU build.
struct ConformancePathResult
{
    std::string name;            // e.g. "slang-spirv"
    bool executed = false;
    std::string note;            // why it did not execute, or the device name
    double max_relative_error = 0.0;
    double p999_relative_error = 0.0;
    std::size_t nonfinite = 0;   // non-finite outputs on the GPU side
    double lobe_mismatch_fraction = 0.0;
    double first_dispatch_ms = 0.0;
    double queries_per_second = 0.0;
    std::size_t validation_messages = 0;
    std::string worst_output;    // where the maximum error occurred, for diagnosis
    std::size_t pipeline_count = 0;  // pipelines built (one per toggle set when specialized)
};

struct ConformanceReport
{
    std::size_t query_count = 0;
    std::size_t material_count = 0;
    std::size_t cpu_nonfinite = 0;
    double cpu_queries_per_second = 0.0;
    std::vector<ConformancePathResult> paths;
};

// The GPU paths this build knows, in report order.
std::vector<std::string> known_conformance_paths();

// Materials used by conformance: the given library plus synthetic materials that switch on
// every lobe at partial weight.
std::vector<Material> conformance_materials(const std::vector<Material>& library);

// Deterministic query batch.
std::vector<float> make_queries(std::size_t query_count, std::size_t material_count, std::uint64_t seed);

// The CPU build of the conformance kernel; results as laid out in openpbr_conformance_kernel.h.
std::vector<float> run_conformance_cpu(const std::vector<float>& queries, const std::vector<float>& materials);

// One GPU path on a query batch (results as the CPU runner lays them out). Throws when the
// path is unknown or its kernel cannot be loaded.
std::vector<float> run_conformance_gpu(const std::string& path_name, VulkanContext& context,
                                       const std::vector<float>& queries, const std::vector<float>& materials,
                                       const std::string& kernel_directory);

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
};

struct SpecializedConformanceRun
{
    std::vector<float> results;  // laid out like run_conformance_cpu's
    std::vector<SpecializedPipelineTiming> pipelines;
    std::size_t pipeline_builds = 0;
    double dispatch_ms = 0.0;  // sum of the groups' steady-state dispatch times
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
                                                          std::optional<std::uint32_t> pipeline_mask, int repeats);

ConformanceReport run_conformance(const std::vector<Material>& materials, const ConformanceOptions& options);

nlohmann::json to_json(const ConformanceReport& report);
std::string to_text(const ConformanceReport& report);

}  // namespace openpbr::host
