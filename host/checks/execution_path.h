// Execution paths: every way this project runs the conformance kernel
// (targets/kernels/openpbr_conformance_kernel.h) on a batch of queries, behind one interface.
// A path says what it is, whether it can run here (and why not), and runs a batch of queries
// to results with its timings. Conformance, the stability corpus, the furnace's GPU rows and
// `openpbr bench gpu` find their paths here; none of them knows how a path dispatches.
//
// The paths, in report order:
//   cpu-fma, cpu-fast, cpu-ulp  the CPU build rounded like a GPU, and moved by one ulp
//                               (host/checks/conformance_cpu_variants.h)
//   slang-spirv ... hlsl-texture  Vulkan compute (host/gpu/vulkan_runner.h), one SPIR-V kernel each
//   cuda, slang-cuda            the CUDA program (host/gpu/cuda_conformance.h)
//   slang-wgsl, wgsl-library    WebGPU through Dawn for Node (targets/wgsl/dispatch_conformance.mjs)
// The CPU build itself ("cpu") is the reference every path is compared with, not a path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/scene/material_library.h"

namespace openpbr::host {

// Thrown by ExecutionPath::run when the path turns out not to run here (e.g. the CUDA program
// found no device): callers report the path as not executed, with the message as the reason.
struct PathUnavailable : std::runtime_error
{
    using std::runtime_error::runtime_error;
};

// Where a path's device lives and how it is used; shared by every path of one ExecutionPaths.
struct ExecutionPathSettings
{
    std::string kernel_directory;  // compiled kernels (.spv, .wgsl), e.g. build/kernels
    bool validation = false;       // Vulkan validation layers (on in tests)
    // Vulkan paths: one pipeline per toggle set the batch's materials need (host/scene/features.h)
    // instead of the full pipeline; needs PathBatch::material_list.
    bool specialize = false;
};

// One batch: queries (OPENPBR_QUERY_FLOATS each) over packed materials. The defaults are what
// conformance runs; `openpbr bench gpu` times one operation at a time on a given toggle set.
struct PathBatch
{
    // A constructor rather than aggregate initialization: callers name the batch and set the
    // rest by name (-Wmissing-field-initializers).
    PathBatch(const std::vector<float>& batch_queries, const std::vector<float>& batch_materials,
              const std::vector<Material>* batch_material_list = nullptr)
        : queries(batch_queries), materials(batch_materials), material_list(batch_material_list)
    {
    }

    const std::vector<float>& queries;
    const std::vector<float>& materials;  // pack_materials(...)
    // The materials unpacked, for specialized runs; may be null otherwise.
    const std::vector<Material>* material_list = nullptr;
    // The kernel's mode (OPENPBR_CONFORMANCE_MODE_* of targets/kernels/openpbr_conformance_kernel.h):
    // 0 every operation, 1 prepare + eval, 2 prepare + sample, 3 prepare + pdf; only that
    // operation's result slots are written. The CPU and CUDA paths run every operation whatever
    // the mode (the CUDA program times each on its own: PathRun::device_ns_per_operation).
    std::uint32_t mode = 0;
    // One pipeline for the whole batch with this toggle set (OPENPBR_FEATURE_BIT_*,
    // host/scene/features.h), kept by the path for the next batch with the same set: Vulkan as
    // specialization constants, WebGPU as the kernel's `override` constants set at pipeline
    // creation. Unset: ExecutionPathSettings::specialize decides. A path that has no such form
    // (CPU, CUDA: one kernel, every toggle on) throws PathUnavailable for any set but the full one.
    std::optional<std::uint32_t> feature_mask;
    // Vulkan and WebGPU paths: how many times the batch is dispatched. Every dispatch computes the
    // same results (the last is read back); those after the first give the steady-state time
    // (the median from the second on) that conformance and `openpbr bench gpu` report. 1 where
    // only the results matter: the stability corpus and the furnace's GPU rows, whose batches
    // lavapipe ran three times (docs/ci-time.md).
    int repeats = 3;
    bool device_local = false;  // Vulkan: buffers in device-local memory, uploaded once (timings)
};

// What a path returns for a batch.
struct PathRun
{
    std::vector<float> results;  // OPENPBR_RESULT_FLOATS per query, laid out as run_conformance_cpu's
    std::string device;          // what ran it, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    double wall_seconds = 0.0;   // the whole run, as the caller waited for it
    // Dispatch timings where the path has them (0 / empty otherwise): the first dispatch, the
    // steady-state one (wall clock), and the kernel time measured on the device.
    double first_dispatch_ms = 0.0;
    double dispatch_ms = 0.0;
    std::optional<double> device_ns_per_query;
    // Kernel time per operation where the path measures each on its own (the CUDA program:
    // "all", "eval", "sample", "pdf"), ns per query.
    std::map<std::string, double> device_ns_per_operation;
    std::size_t pipeline_count = 0;  // pipelines built for the batch (0 on the CPU)
    // The driver's statistics of the pipeline that ran the batch (Vulkan, where the driver has
    // VK_KHR_pipeline_executable_properties), by name, after its dispatch.
    std::map<std::string, double> pipeline_statistics;
    std::vector<std::string> validation_messages;
};

class ExecutionPath
{
  public:
    virtual ~ExecutionPath() = default;
    virtual std::string name() const = 0;
    // One line: what runs, e.g. "Slang module -> WGSL, Dawn for Node (WebGPU)".
    virtual std::string description() const = 0;
    // Empty when the path can run here as far as can be known without running it; otherwise
    // why not (e.g. "not built: nvcc was not found ..."). run() may still throw PathUnavailable.
    virtual std::string unavailable_reason() = 0;
    // Throws PathUnavailable when it cannot run here, std::exception subclasses on errors.
    virtual PathRun run(const PathBatch& batch) = 0;
};

// Every path this build knows, in report order; `cpu_variants` false leaves out the CPU ones.
std::vector<std::string> execution_path_names(bool cpu_variants = true);

// True for the paths whose kernels run WGSL's math builtins (slang-wgsl, wgsl-library), which
// the WGSL specification allows far less precision than a correctly rounded float
// (conformance_tolerances(path_name), host/checks/conformance.h).
bool execution_path_has_wgsl_math(const std::string& name);

// SwiftShader's Vulkan driver as Debian's `chromium` package installs it: the WebGPU paths'
// adapter where Dawn finds no other (it refuses lavapipe).
std::string swiftshader_vulkan_driver();

// The kernel a Vulkan path dispatches: its SPIR-V file under the kernel directory, and whether
// it reads the tables as sampled images (OPENPBR_USE_TEXTURE_LUTS, bindings 6-14) instead of
// the buffers at bindings 0 and 1. Throws std::invalid_argument for a name that is not a Vulkan path.
struct VulkanPathKernel
{
    std::string name;
    std::string kernel_file;
    std::string entry_point;
    bool texture_tables = false;
};
const VulkanPathKernel& vulkan_path_kernel(const std::string& name);
std::vector<std::string> vulkan_path_names();

// The paths of one run, made on demand and sharing their devices (one Vulkan context, created
// at the first Vulkan path's use and kept for the others). Use from one thread.
class ExecutionPaths
{
  public:
    explicit ExecutionPaths(ExecutionPathSettings settings);
    ~ExecutionPaths();
    ExecutionPaths(const ExecutionPaths&) = delete;
    ExecutionPaths& operator=(const ExecutionPaths&) = delete;

    // The path of that name; throws std::invalid_argument naming the known ones otherwise.
    ExecutionPath& path(const std::string& name);

    struct Shared;  // the devices the paths share (execution_path.cpp)

  private:
    ExecutionPathSettings settings_;
    std::unique_ptr<Shared> shared_;
    std::vector<std::unique_ptr<ExecutionPath>> paths_;
};

}  // namespace openpbr::host
