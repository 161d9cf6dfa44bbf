// Execution paths: see execution_path.h.
#include "host/checks/execution_path.h"

#include <algorithm>
#include <filesystem>
#include <regex>

#include "host/checks/conformance.h"
#include "host/checks/conformance_cpu_variants.h"
#include "host/gpu/build_tools.h"
#include "host/gpu/cuda_conformance.h"
#include "host/gpu/vulkan_runner.h"
#include "host/scene/features.h"
#include "host/support/stopwatch.h"

namespace openpbr::host {

namespace {

namespace fs = std::filesystem;

const std::vector<VulkanPathKernel>& vulkan_kernels()
{
    static const std::vector<VulkanPathKernel> kernels = {
        {"slang-spirv", "conformance.slang.spv", "main"},
        {"glsl-spirv", "conformance.glsl.spv", "main"},
        {"slang-hlsl", "conformance.slang-hlsl.spv", "main"},
        {"slang-glsl", "conformance.slang-glsl.spv", "main"},
        {"hlsl", "conformance.hlsl.spv", "main"},
        {"glsl-spirv-texture", "conformance_texture.glsl.spv", "main", true},
        {"slang-spirv-texture", "conformance_texture.slang.spv", "main", true},
        {"hlsl-texture", "conformance_texture.hlsl.spv", "main", true},
    };
    return kernels;
}

const char* const cuda_path_names[] = {"cuda", "slang-cuda"};

// The WebGPU paths: a WGSL kernel under the kernel directory (built by CMakeLists.txt, "Slang
// kernels") and its entry point, dispatched by targets/wgsl/dispatch_conformance.mjs.
struct WgslPathKernel
{
    const char* name;
    const char* kernel_file;
    const char* entry_point;
    const char* description;
};
const WgslPathKernel wgsl_kernels[] = {
    {"slang-wgsl", "conformance.slang.wgsl", "conformance_main",
     "Slang module -> WGSL (Slang wasm), Dawn for Node (WebGPU)"},
    {"wgsl-library", "conformance.library.wgsl", "main",
     "generated openpbr.wgsl + a WGSL kernel over it, Dawn for Node (WebGPU)"},
};

std::size_t query_count_of(const PathBatch& batch) { return batch.queries.size() / conformance_query_floats; }

// The paths with one kernel and every toggle on (the CPU builds, the CUDA program) cannot run a
// batch on another toggle set: they say so rather than run the full kernel under its name.
void require_full_toggle_set(const PathBatch& batch, const std::string& name, const char* why)
{
    if (batch.feature_mask && *batch.feature_mask != full_feature_mask())
    {
        throw PathUnavailable(name + " runs no kernel specialized to " + feature_set_label(*batch.feature_mask) + " (" +
                              why + ")");
    }
}

// A batch on one toggle set refuses a material that needs a toggle the set lacks (it would run
// without the effect), as every specialized pipeline does (host/scene/features.h).
void check_batch_toggle_set(const PathBatch& batch)
{
    if (batch.feature_mask && batch.material_list)
    {
        check_pipeline_supports(*batch.material_list, *batch.feature_mask);
    }
}

}  // namespace

// The devices the paths of one ExecutionPaths share.
struct ExecutionPaths::Shared
{
    ExecutionPathSettings settings;

    // One Vulkan context, created at the first Vulkan path's use.
    bool vulkan_tried = false;
    std::optional<VulkanContext> vulkan;
    std::string vulkan_error;

    VulkanContext* vulkan_context()
    {
        if (!vulkan_tried)
        {
            VulkanOptions options;
            options.enable_validation = settings.validation;
            vulkan = VulkanContext::create(options, &vulkan_error);
            vulkan_tried = true;
        }
        return vulkan ? &*vulkan : nullptr;
    }

    // The CUDA program runs both CUDA paths at once: the last batch's results are kept, so
    // the second path of the same batch does not run the program again.
    std::vector<float> cuda_queries;
    std::vector<float> cuda_materials;
    std::vector<ExternalPathResult> cuda_results;

    const ExternalPathResult& cuda_result(const std::string& name, const PathBatch& batch)
    {
        if (cuda_results.empty() || cuda_queries != batch.queries || cuda_materials != batch.materials)
        {
            cuda_results = run_cuda_conformance_program(default_cuda_conformance_program(), batch.queries, batch.materials);
            cuda_queries = batch.queries;
            cuda_materials = batch.materials;
        }
        for (const ExternalPathResult& result : cuda_results)
        {
            if (result.name == name)
            {
                return result;
            }
        }
        throw PathUnavailable("the CUDA conformance program did not report " + name);
    }
};

namespace {

// cpu-fma, cpu-fast: the kernel body compiled to round like a GPU.
class CpuVariantPath final : public ExecutionPath
{
  public:
    explicit CpuVariantPath(std::string name) : name_(std::move(name)) {}
    std::string name() const override { return name_; }
    std::string description() const override
    {
        return name_ == "cpu-fma" ? "CPU, -mfma -ffp-contract=fast"
                                  : "CPU, -mfma -ffp-contract=fast -freciprocal-math, fast sqrt/normalize";
    }
    std::string unavailable_reason() override { return conformance_cpu_fma_unavailable_reason(); }
    PathRun run(const PathBatch& batch) override
    {
        require_full_toggle_set(batch, name_, "a CPU build with every toggle on");
        PathRun run;
        run.device = description();
        const Stopwatch stopwatch;
        run.results = name_ == "cpu-fma" ? run_conformance_cpu_fma(batch.queries, batch.materials)
                                         : run_conformance_cpu_fast(batch.queries, batch.materials);
        run.wall_seconds = stopwatch.seconds();
        return run;
    }

  private:
    std::string name_;
};

// cpu-ulp: the CPU build with every random number moved by one ulp (the chaos of the sampled
// outputs, as a reference).
class CpuUlpPath final : public ExecutionPath
{
  public:
    std::string name() const override { return "cpu-ulp"; }
    std::string description() const override { return "CPU build, u moved by one ulp"; }
    std::string unavailable_reason() override { return ""; }
    PathRun run(const PathBatch& batch) override
    {
        require_full_toggle_set(batch, name(), "the CPU build with every toggle on");
        PathRun run;
        run.device = description();
        const Stopwatch stopwatch;
        run.results = run_conformance_cpu(nudge_random_numbers(batch.queries), batch.materials);
        run.wall_seconds = stopwatch.seconds();
        return run;
    }
};

class VulkanPath final : public ExecutionPath
{
  public:
    VulkanPath(const VulkanPathKernel& kernel, ExecutionPaths::Shared& shared) : kernel_(kernel), shared_(shared) {}
    std::string name() const override { return kernel_.name; }
    std::string description() const override { return "Vulkan compute, kernel " + kernel_.kernel_file; }
    std::string unavailable_reason() override { return shared_.vulkan_context() ? "" : shared_.vulkan_error; }
    PathRun run(const PathBatch& batch) override
    {
        VulkanContext* context = shared_.vulkan_context();
        if (!context)
        {
            throw PathUnavailable(shared_.vulkan_error);
        }
        context->clear_validation_messages();
        check_batch_toggle_set(batch);
        const Stopwatch stopwatch;
        PathRun run;
        DispatchTiming timing;
        ConformanceDispatchSettings dispatch_settings;
        dispatch_settings.mode = batch.mode;
        dispatch_settings.device_local = batch.device_local;
        dispatch_settings.texture_tables = kernel_.texture_tables;
        if (batch.feature_mask)
        {
            // One pipeline of the given toggle set, built once and kept for the path's next
            // batches (bench gpu: every operation and round on the same pipelines).
            if (!pipelines_)
            {
                pipelines_.emplace(*context,
                                   conformance_pipeline_description(kernel_.name, shared_.settings.kernel_directory));
            }
            const std::size_t builds_before = pipelines_->build_count();
            ComputePipeline& pipeline = pipelines_->pipeline(*batch.feature_mask);
            ConformanceDispatch dispatch =
                dispatch_conformance_pipeline(pipeline, batch.queries, batch.materials, batch.repeats, dispatch_settings);
            run.results = std::move(dispatch.results);
            timing = dispatch.timing;
            run.pipeline_count = pipelines_->build_count() - builds_before;
            for (const PipelineStatistic& statistic : pipeline.statistics())
            {
                run.pipeline_statistics[statistic.name] = statistic.value;
            }
        }
        else if (shared_.settings.specialize)
        {
            if (!batch.material_list)
            {
                throw std::invalid_argument("a specialized run of " + kernel_.name + " needs the material list");
            }
            // One pipeline per toggle set the materials need; the first-dispatch time is that of
            // every set together, the steady-state time the sum over the sets.
            const SpecializedConformanceRun specialized = run_conformance_gpu_specialized(
                kernel_.name, *context, batch.queries, *batch.material_list, shared_.settings.kernel_directory, std::nullopt,
                batch.repeats, dispatch_settings);
            run.results = specialized.results;
            timing.dispatch_ms = specialized.dispatch_ms;
            timing.device_dispatch_ms = specialized.device_dispatch_ms;
            for (const SpecializedPipelineTiming& pipeline : specialized.pipelines)
            {
                timing.first_dispatch_ms += pipeline.first_dispatch_ms;
            }
            run.pipeline_count = specialized.pipeline_builds;
        }
        else
        {
            // One pipeline for every batch of the path: llvmpipe compiles the kernel at a
            // pipeline's first dispatch and keeps it, so a run of many batches (the stability
            // corpus, the furnace's rows: 1.3M queries a batch) compiles it once, not per batch.
            if (!pipeline_)
            {
                pipeline_.emplace(*context,
                                  conformance_pipeline_description(kernel_.name, shared_.settings.kernel_directory));
                run.pipeline_count = 1;
            }
            ConformanceDispatch dispatch =
                dispatch_conformance_pipeline(*pipeline_, batch.queries, batch.materials, batch.repeats, dispatch_settings);
            run.results = std::move(dispatch.results);
            timing = dispatch.timing;
        }
        run.wall_seconds = stopwatch.seconds();
        run.device = context->device_name();
        run.first_dispatch_ms = timing.first_dispatch_ms;
        run.dispatch_ms = timing.dispatch_ms;
        const std::size_t query_count = query_count_of(batch);
        if (timing.device_dispatch_ms && query_count > 0)
        {
            run.device_ns_per_query = *timing.device_dispatch_ms * 1e6 / double(query_count);
        }
        run.validation_messages = context->validation_messages();
        return run;
    }

  private:
    VulkanPathKernel kernel_;
    ExecutionPaths::Shared& shared_;
    std::optional<ComputePipeline> pipeline_;            // built at the first batch
    std::optional<SpecializedPipelineCache> pipelines_;  // the batches with a feature_mask
};

// A path whose kernel runs in another program that exchanges float32 files with this one
// (host/gpu/cuda_conformance.h): the program's line is the device, its "= T ns/query" the
// device time.
PathRun external_run(const ExternalPathResult& external, double wall_seconds)
{
    if (!external.executed)
    {
        // The reason without the program's own "skipped: ", which callers add where they say it.
        const std::string skipped = "skipped: ";
        throw PathUnavailable(external.note.rfind(skipped, 0) == 0 ? external.note.substr(skipped.size()) : external.note);
    }
    PathRun run;
    run.results = external.results;
    run.device = external.note;
    run.wall_seconds = wall_seconds;
    run.device_ns_per_operation = external.device_ns_per_query;
    const auto all = external.device_ns_per_query.find("all");
    if (all != external.device_ns_per_query.end() && all->second > 0.0)
    {
        run.device_ns_per_query = all->second;
    }
    run.pipeline_count = 1;
    return run;
}

class CudaPath final : public ExecutionPath
{
  public:
    CudaPath(std::string name, ExecutionPaths::Shared& shared) : name_(std::move(name)), shared_(shared) {}
    std::string name() const override { return name_; }
    std::string description() const override
    {
        return name_ == "cuda" ? "the headers through their CUDA backend (openpbr_cuda_conformance)"
                               : "Slang's CUDA output (openpbr_cuda_conformance)";
    }
    // Whether a device exists is known only once the program has run.
    std::string unavailable_reason() override
    {
        const std::string program = default_cuda_conformance_program();
        if (program.empty())
        {
            return "not built: nvcc was not found when the build was configured";
        }
        return fs::exists(program) ? "" : "not built: " + program + " does not exist (build target openpbr_cuda_programs)";
    }
    PathRun run(const PathBatch& batch) override
    {
        require_full_toggle_set(batch, name_, "the CUDA program's one kernel has every toggle on");
        const Stopwatch stopwatch;
        const ExternalPathResult& external = shared_.cuda_result(name_, batch);
        return external_run(external, stopwatch.seconds());
    }

  private:
    std::string name_;
    ExecutionPaths::Shared& shared_;
};

class WebGpuPath final : public ExecutionPath
{
  public:
    WebGpuPath(const WgslPathKernel& kernel, ExecutionPaths::Shared& shared) : kernel_(kernel), shared_(shared) {}
    std::string name() const override { return kernel_.name; }
    std::string description() const override { return kernel_.description; }
    std::string unavailable_reason() override
    {
        const fs::path kernel = kernel_path();
        if (!fs::exists(kernel))
        {
            return "not built: " + kernel.string() + " does not exist (build target openpbr_kernels)";
        }
        return fs::exists(dispatcher()) ? "" : "no dispatcher: " + dispatcher().string() + " does not exist";
    }
    PathRun run(const PathBatch& batch) override
    {
        const std::string reason = unavailable_reason();
        if (!reason.empty())
        {
            throw PathUnavailable(reason);
        }
        check_batch_toggle_set(batch);
        std::vector<std::string> command = {OPENPBR_COMPILE_NODE,
                                            dispatcher().string(),
                                            "-path",
                                            kernel_.name,
                                            "-kernel",
                                            kernel_path().string(),
                                            "-entry",
                                            kernel_.entry_point,
                                            "-swiftshader",
                                            swiftshader_vulkan_driver(),
                                            "-mode",
                                            std::to_string(batch.mode),
                                            "-repeats",
                                            std::to_string(batch.repeats)};
        if (batch.feature_mask)
        {
            // The toggles as the kernel's `override` constants, set at pipeline creation: each
            // one outside the set false, by its @id (the legacy aliases stay on, as in
            // specialization_constants).
            for (const FeatureToggle& toggle : feature_toggles())
            {
                if ((*batch.feature_mask & toggle.bit) == 0)
                {
                    command.insert(command.end(), {"-constant", std::to_string(toggle.constant_id) + "=false"});
                }
            }
        }
        command.push_back("-dir");
        const Stopwatch stopwatch;
        const std::vector<ExternalPathResult> results =
            run_conformance_program(command, {kernel_.name}, batch.queries, batch.materials);
        PathRun run = external_run(results.front(), stopwatch.seconds());
        // "... first dispatch 57 ms, ...": the dispatch that includes SwiftShader's compilation.
        static const std::regex first_dispatch("first dispatch ([0-9.]+) ms");
        std::smatch match;
        if (std::regex_search(run.device, match, first_dispatch))
        {
            run.first_dispatch_ms = std::stod(match[1].str());
        }
        return run;
    }

  private:
    fs::path kernel_path() const { return fs::path(shared_.settings.kernel_directory) / kernel_.kernel_file; }
    static fs::path dispatcher()
    {
        return fs::path(OPENPBR_COMPILE_SOURCE_DIR) / "targets" / "wgsl" / "dispatch_conformance.mjs";
    }

    WgslPathKernel kernel_;
    ExecutionPaths::Shared& shared_;
};

}  // namespace

std::string swiftshader_vulkan_driver() { return "/usr/lib/chromium/vk_swiftshader_icd.json"; }

bool execution_path_has_wgsl_math(const std::string& name)
{
    return std::any_of(std::begin(wgsl_kernels), std::end(wgsl_kernels),
                       [&name](const WgslPathKernel& kernel) { return name == kernel.name; });
}

std::vector<std::string> vulkan_path_names()
{
    std::vector<std::string> names;
    for (const VulkanPathKernel& kernel : vulkan_kernels())
    {
        names.push_back(kernel.name);
    }
    return names;
}

const VulkanPathKernel& vulkan_path_kernel(const std::string& name)
{
    for (const VulkanPathKernel& kernel : vulkan_kernels())
    {
        if (kernel.name == name)
        {
            return kernel;
        }
    }
    throw std::invalid_argument("unknown GPU path '" + name + "'");
}

std::vector<std::string> execution_path_names(bool cpu_variants)
{
    std::vector<std::string> names;
    if (cpu_variants)
    {
        names = {"cpu-fma", "cpu-fast", "cpu-ulp"};
    }
    for (const std::string& name : vulkan_path_names())
    {
        names.push_back(name);
    }
    for (const char* name : cuda_path_names)
    {
        names.push_back(name);
    }
    for (const WgslPathKernel& kernel : wgsl_kernels)
    {
        names.push_back(kernel.name);
    }
    return names;
}

ExecutionPaths::ExecutionPaths(ExecutionPathSettings settings)
    : settings_(std::move(settings)), shared_(std::make_unique<Shared>())
{
    shared_->settings = settings_;
}

ExecutionPaths::~ExecutionPaths() = default;

ExecutionPath& ExecutionPaths::path(const std::string& name)
{
    for (const std::unique_ptr<ExecutionPath>& path : paths_)
    {
        if (path->name() == name)
        {
            return *path;
        }
    }
    std::unique_ptr<ExecutionPath> made;
    if (name == "cpu-fma" || name == "cpu-fast")
    {
        made = std::make_unique<CpuVariantPath>(name);
    }
    else if (name == "cpu-ulp")
    {
        made = std::make_unique<CpuUlpPath>();
    }
    else if (std::find(std::begin(cuda_path_names), std::end(cuda_path_names), name) != std::end(cuda_path_names))
    {
        made = std::make_unique<CudaPath>(name, *shared_);
    }
    for (const WgslPathKernel& kernel : wgsl_kernels)
    {
        if (name == kernel.name)
        {
            made = std::make_unique<WebGpuPath>(kernel, *shared_);
        }
    }
    if (!made)
    {
        const std::vector<std::string> vulkan = vulkan_path_names();
        if (std::find(vulkan.begin(), vulkan.end(), name) == vulkan.end())
        {
            std::string known;
            for (const std::string& candidate : execution_path_names())
            {
                known += (known.empty() ? "" : ", ") + candidate;
            }
            throw std::invalid_argument("unknown path '" + name + "' (known: " + known + ")");
        }
        made = std::make_unique<VulkanPath>(vulkan_path_kernel(name), *shared_);
    }
    paths_.push_back(std::move(made));
    return *paths_.back();
}

}  // namespace openpbr::host
