// accuracy_gpu.cpp - device times of the accuracy study's settings (host/studies/accuracy_internal.h):
// the Slang conformance kernel (targets/kernels/conformance.slang) compiled once per setting with
// the setting's defines, to SPIR-V for lavapipe (Vulkan timestamps around each dispatch) and to
// WGSL for SwiftShader through Dawn (targets/wgsl/dispatch_conformance.mjs, WebGPU timestamps),
// each on its family's workload and operation, with the table the setting reads.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "host/scene/features.h"
#include "host/studies/accuracy_internal.h"
#include "host/support/files.h"
#include "host/support/stopwatch.h"

namespace openpbr::host::accuracy {
namespace {

// One setting's kernel in both forms.
struct GpuKernel
{
    const BsdfVariant* variant = nullptr;
    std::filesystem::path spirv;
    std::filesystem::path wgsl;
    bool compiled = false;
    std::optional<ComputePipeline> pipeline;  // built at its first lavapipe job
};

// One timing: a kernel on a workload in one mode, and the setting it belongs to.
struct GpuJob
{
    std::size_t kernel = 0;
    const Workload* workload = nullptr;
    Operation operation = Operation::eval;
    std::size_t family = 0;
    std::size_t setting = 0;
    std::vector<std::vector<double>> lavapipe_ms;  // per round, per chunk
    std::optional<double> webgpu_ns;
};

std::uint32_t conformance_mode(const Operation operation) { return operation == Operation::eval ? 1u : 2u; }

// The workload in the conformance kernel's query layout (OPENPBR_QUERY_FLOATS per query).
std::vector<float> conformance_queries(const Workload& workload)
{
    std::vector<float> records(workload.queries.size() * conformance_query_floats, 0.0f);
    for (std::size_t i = 0; i < workload.queries.size(); ++i)
    {
        const AccuracyQuery& query = workload.queries[i];
        float* record = records.data() + i * conformance_query_floats;
        record[0] = float(query.material);
        std::copy(query.view, query.view + 3, record + 1);
        std::copy(query.light, query.light + 3, record + 4);
        std::copy(query.u, query.u + 3, record + 7);
        record[10] = 1.0f;  // exterior IOR: the study's materials sit in air
    }
    return records;
}

// What a kernel was compiled from: its defines and the newest modification time of the sources
// it reads (slang/, targets/kernels/, the driver), so an unchanged kernel is not compiled again
// (a compile took about a minute on 2 cores at load 20, 4 s idle).
std::string kernel_stamp(const BsdfVariant& variant, const std::filesystem::path& root)
{
    // From the clock's minimum: libstdc++'s file clock counts from 2174, so today's times are
    // negative and a zero start hid every change.
    std::filesystem::file_time_type newest = std::filesystem::file_time_type::min();
    for (const char* folder : {"slang", "targets/kernels"})
    {
        for (const auto& entry : std::filesystem::recursive_directory_iterator(root / folder))
        {
            newest = std::max(newest, entry.last_write_time());
        }
    }
    newest = std::max(newest, std::filesystem::last_write_time(root / "targets/slangc.mjs"));
    std::string stamp = std::to_string(newest.time_since_epoch().count()) + " spirv,wgsl";
    for (const std::string& define : variant.slang_defines)
    {
        stamp += " " + define;
    }
    return stamp + "\n";
}

// node targets/slangc.mjs once for both targets, SPIR-V and WGSL (the wasm compiler starts once
// per process, so the second costs little), unless the kernel's files and stamp say it is up to
// date.
bool compile_kernel(GpuKernel& kernel, const std::filesystem::path& root, const std::filesystem::path& directory)
{
    const std::string name = "accuracy_" + kernel.variant->name;
    kernel.spirv = directory / (name + ".spv");
    kernel.wgsl = directory / (name + ".wgsl");
    const std::filesystem::path stamp_file = directory / (name + ".stamp");
    const std::string stamp = kernel_stamp(*kernel.variant, root);
    if (std::filesystem::exists(stamp_file) && read_whole_file(stamp_file) == stamp &&
        std::filesystem::exists(kernel.spirv) && std::filesystem::exists(kernel.wgsl))
    {
        kernel.compiled = true;
        return true;
    }
    std::filesystem::remove(kernel.spirv);
    std::filesystem::remove(kernel.wgsl);
    std::string command = "node \"" + (root / "targets/slangc.mjs").string() +
                          "\" -q -target spirv,wgsl -entry conformance_main -stage compute -I \"" +
                          (root / "slang").string() + "\"";
    for (const std::string& define : kernel.variant->slang_defines)
    {
        command += " -D" + define;
    }
    command += " -o \"" + directory.string() + "\" -name " + name;
    command += " \"" + (root / "targets/kernels/conformance.slang").string() + "\" > /dev/null 2>&1";
    const int status = std::system(command.c_str());
    kernel.compiled = status == 0 && std::filesystem::exists(kernel.spirv) && std::filesystem::exists(kernel.wgsl);
    if (kernel.compiled)
    {
        write_file_atomically(stamp_file, stamp);
    }
    return kernel.compiled;
}

// Queries per lavapipe dispatch of a workload: a dispatch of a few milliseconds on one
// lavapipe thread fits in a time slice of a loaded machine, where one of the whole workload
// (330 ms of filmed queries) was always preempted and read 7 times the CPU's time.
std::size_t lavapipe_chunk(const Workload& workload)
{
    return workload.name == "films" || workload.name == "film stacks" ? 64 : 512;
}

// The lavapipe buffers of one chunk of a job (bindings of targets/kernels/conformance.slang).
struct LavapipeBuffers
{
    std::vector<std::byte> table, fuzz, queries, materials, parameters, results;
    std::vector<BufferBinding> bindings()
    {
        return {{0, &table, false},     {1, &fuzz, false},       {2, &queries, false},
                {3, &materials, false}, {4, &parameters, false}, {5, &results, true}};
    }
};

LavapipeBuffers lavapipe_buffers(const GpuKernel& kernel, const GpuJob& job, const StudyTables& tables,
                                 const std::vector<float>& records, const std::size_t begin, const std::size_t count)
{
    LavapipeBuffers buffers;
    buffers.table = table_bytes(tables, kernel.variant->table);
    buffers.fuzz = to_bytes(shipped_fuzz_ltc());
    buffers.queries =
        to_bytes(std::vector<float>(records.begin() + std::ptrdiff_t(begin * conformance_query_floats),
                                    records.begin() + std::ptrdiff_t((begin + count) * conformance_query_floats)));
    buffers.materials = to_bytes(job.workload->packed);
    buffers.parameters = to_bytes(std::vector<std::uint32_t>{std::uint32_t(count), conformance_mode(job.operation), 0, 0});
    buffers.results.assign(count * conformance_result_floats * sizeof(float), std::byte{0});
    return buffers;
}

// One round of a job on lavapipe: each chunk dispatched twice, the second (warm) dispatch's
// device time (Vulkan timestamps, else the wall clock) kept in `chunk_ms`; in eval mode with
// `check`, the per-query relative error of the kernel's eval against the same setting on the CPU.
void run_lavapipe_job(VulkanContext& context, GpuKernel& kernel, const GpuJob& job, const StudyTables& tables,
                      std::vector<double>& chunk_ms, std::optional<RelativeErrors>* check)
{
    const std::vector<float> records = conformance_queries(*job.workload);
    const std::size_t count = job.workload->queries.size();
    const std::size_t chunk = lavapipe_chunk(*job.workload);
    std::vector<float> gpu(3 * count);
    for (std::size_t begin = 0; begin < count; begin += chunk)
    {
        const std::size_t size = std::min(chunk, count - begin);
        LavapipeBuffers buffers = lavapipe_buffers(kernel, job, tables, records, begin, size);
        std::vector<BufferBinding> bindings = buffers.bindings();
        if (!kernel.pipeline)
        {
            ComputePipelineDescription description;
            description.spirv_words = load_spirv_file(kernel.spirv.string());
            description.entry_point = "main";
            description.bindings = binding_layouts_of(bindings);
            kernel.pipeline.emplace(context, description);
        }
        const DispatchTiming timing = run(*kernel.pipeline, bindings, std::uint32_t((size + 63) / 64), 1, 1, 2);
        chunk_ms.push_back(timing.device_dispatch_ms ? *timing.device_dispatch_ms : timing.dispatch_ms);
        const std::vector<float> results = from_bytes<float>(buffers.results);
        for (std::size_t i = 0; i < size; ++i)
        {
            for (std::size_t c = 0; c < 3; ++c)
            {
                // Result record: eval.diffuse (3), eval.specular (3), ...
                gpu[3 * (begin + i) + c] =
                    results[i * conformance_result_floats + c] + results[i * conformance_result_floats + 3 + c];
            }
        }
    }
    if (check && job.operation == Operation::eval)
    {
        std::vector<float> cpu(3 * count);
        kernel.variant->eval(job.workload->packed.data(), job.workload->queries, cpu.data());
        *check = relative_errors(gpu, cpu);
    }
}

// One SwiftShader run of a job through targets/wgsl/dispatch_conformance.mjs: its
// "dispatch = T ns/query" (median of the dispatches after the first).
std::optional<double> run_webgpu_job(const GpuKernel& kernel, const GpuJob& job, const StudyTables& tables,
                                     const std::filesystem::path& root, const std::filesystem::path& directory)
{
    std::filesystem::create_directories(directory);
    write_float32_file(directory / "queries.f32", conformance_queries(*job.workload));
    write_float32_file(directory / "materials.f32", job.workload->packed);
    const std::vector<std::byte> table = table_bytes(tables, kernel.variant->table);
    write_file_atomically(directory / "lut.f32", std::string(reinterpret_cast<const char*>(table.data()), table.size()));
    write_float32_file(directory / "fuzz_ltc.f32", shipped_fuzz_ltc());
    const std::filesystem::path output = directory / "dispatch.txt";
    std::string command =
        "node \"" + (root / "targets/wgsl/dispatch_conformance.mjs").string() + "\" -path accuracy -kernel \"" +
        kernel.wgsl.string() + "\" -entry conformance_main -swiftshader \"" + swiftshader_vulkan_driver() + "\" -mode " +
        std::to_string(conformance_mode(job.operation)) + " -repeats 5 -dir \"" + directory.string() + "\"";
    // The pipeline specialized to the toggles the workload needs (the others' `override`
    // constants false): SwiftShader built the full conformance pipeline in about two minutes on
    // 2 cores at load 20.
    std::uint32_t mask = 0;
    for (const Material& material : job.workload->materials)
    {
        mask |= required_feature_mask(material);
    }
    for (const FeatureToggle& toggle : feature_toggles())
    {
        if ((mask & toggle.bit) == 0)
        {
            command += " -constant " + std::to_string(toggle.constant_id) + "=false";
        }
    }
    command += " > \"" + output.string() + "\" 2>&1";
    if (std::system(command.c_str()) != 0 || !std::filesystem::exists(output))
    {
        return std::nullopt;
    }
    static const std::regex rate("dispatch = ([0-9.eE+-]+) ns/query");
    const std::string text = read_whole_file(output);
    std::smatch match;
    return std::regex_search(text, match, rate) ? std::optional<double>(std::stod(match[1].str())) : std::nullopt;
}

const Workload& workload_named(const StudyContext& context, const std::string& name)
{
    for (const Workload* workload : {&context.general, &context.metals, &context.films, &context.film_stacks})
    {
        if (workload->name == name)
        {
            return *workload;
        }
    }
    throw std::runtime_error("accuracy study: no workload named '" + name + "'");
}

// Per query: the best is the sum over chunks of each chunk's fastest round, the median the
// median over the rounds of their sums.
AccuracyTime lavapipe_time(const std::vector<std::vector<double>>& rounds, const std::size_t queries)
{
    std::vector<double> best(rounds.front().size(), std::numeric_limits<double>::infinity());
    std::vector<double> totals;
    for (const std::vector<double>& round : rounds)
    {
        double total = 0.0;
        for (std::size_t c = 0; c < round.size() && c < best.size(); ++c)
        {
            best[c] = std::min(best[c], round[c]);
            total += round[c];
        }
        totals.push_back(total);
    }
    std::sort(totals.begin(), totals.end());
    double sum = 0.0;
    for (const double value : best)
    {
        sum += value;
    }
    const double scale = 1e6 / double(queries);  // ms per workload -> ns per query
    return AccuracyTime{sum * scale, totals[totals.size() / 2] * scale};
}

}  // namespace

std::size_t gpu_kernel_count(const std::vector<BsdfVariant>& variants)
{
    return std::size_t(std::count_if(variants.begin(), variants.end(), [](const BsdfVariant& v) { return v.on_gpu; }));
}

void measure_gpu_times(const StudyContext& context, const StudyTables& tables, std::vector<FamilyMeasurement>& families,
                       ProgressReporter& progress)
{
    const AccuracyOptions& options = context.options;
    const std::filesystem::path directory =
        (options.cache_directory.empty() ? std::filesystem::temp_directory_path() : options.cache_directory) / "gpu";
    std::filesystem::create_directories(directory);
    std::vector<GpuKernel> kernels;
    std::map<std::string, std::size_t> kernel_of;
    std::vector<GpuJob> jobs;
    for (std::size_t f = 0; f < families.size(); ++f)
    {
        for (std::size_t s = 0; s < families[f].family.settings.size(); ++s)
        {
            const BsdfVariant& variant = variant_named(context.variants, families[f].family.settings[s].variant);
            if (!variant.on_gpu)
            {
                continue;
            }
            if (kernel_of.find(variant.name) == kernel_of.end())
            {
                kernel_of[variant.name] = kernels.size();
                kernels.emplace_back();
                kernels.back().variant = &variant;
            }
            GpuJob job;
            job.kernel = kernel_of[variant.name];
            job.workload = &workload_named(context, families[f].workload);
            job.operation = families[f].operation;
            job.family = f;
            job.setting = s;
            jobs.push_back(job);
        }
    }
    for (GpuKernel& kernel : kernels)
    {
        if (!compile_kernel(kernel, options.repository_root, directory))
        {
            std::cerr << "\nopenpbr bench accuracy: the Slang compile of '" << kernel.variant->name
                      << "' failed (node and targets/slangc.mjs needed); its GPU rows left out\n";
        }
        progress.begin_step("Slang compile: " + kernel.variant->name);
    }
    // lavapipe on one thread, unless the caller chose otherwise: its device time is then one
    // core's, comparable with the CPU rows, and a dispatch is not held up by the slower of two
    // threads on a shared machine.
    setenv("LP_NUM_THREADS", "1", 0);
    std::string vulkan_error;
    std::optional<VulkanContext> vulkan = VulkanContext::create(VulkanOptions{}, &vulkan_error);
    if (!vulkan)
    {
        std::cerr << "\nopenpbr bench accuracy: no Vulkan device (" << vulkan_error << "); lavapipe rows left out\n";
    }
    // Rounds over every job, as the CPU timer does: a slow spell falls on every setting.
    const int rounds = 3;
    for (int round = 0; round < rounds && vulkan; ++round)
    {
        for (GpuJob& job : jobs)
        {
            GpuKernel& kernel = kernels[job.kernel];
            if (!kernel.compiled)
            {
                continue;
            }
            std::optional<RelativeErrors> check;
            job.lavapipe_ms.emplace_back();
            run_lavapipe_job(*vulkan, kernel, job, tables, job.lavapipe_ms.back(), round == 0 ? &check : nullptr);
            if (check)
            {
                families[job.family].family.settings[job.setting].other_errors["lavapipe eval vs CPU, same setting "
                                                                               "(99th percentile relative)"] = check->p99;
            }
        }
        progress.begin_step("lavapipe, round " + std::to_string(round + 1) + " of " + std::to_string(rounds));
    }
    for (std::size_t j = 0; j < jobs.size() && options.webgpu; ++j)
    {
        GpuJob& job = jobs[j];
        const GpuKernel& kernel = kernels[job.kernel];
        if (kernel.compiled && std::filesystem::exists(kernel.wgsl))
        {
            job.webgpu_ns =
                run_webgpu_job(kernel, job, tables, options.repository_root, directory / ("webgpu_" + std::to_string(j)));
            if (!job.webgpu_ns)
            {
                std::cerr << "\nopenpbr bench accuracy: SwiftShader did not run '" << kernel.variant->name << "' (see "
                          << (directory / ("webgpu_" + std::to_string(j)) / "dispatch.txt").string() << ")\n";
            }
        }
        progress.begin_step("SwiftShader: " + kernel.variant->name);
    }
    for (const GpuJob& job : jobs)
    {
        AccuracySetting& setting = families[job.family].family.settings[job.setting];
        if (!job.lavapipe_ms.empty())
        {
            setting.lavapipe_ns = lavapipe_time(job.lavapipe_ms, job.workload->queries.size());
        }
        if (job.webgpu_ns)
        {
            setting.webgpu_ns = AccuracyTime{*job.webgpu_ns, *job.webgpu_ns};
        }
    }
}

}  // namespace openpbr::host::accuracy
