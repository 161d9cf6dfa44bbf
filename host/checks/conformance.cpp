// Conformance runner: see conformance.h.
#include "host/checks/conformance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "host/gpu/cuda_conformance.h"
#include "host/scene/features.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "slang/openpbr.h"

// The CPU build of the shared kernel body: the macros read and write these arrays, which the
// runner points at the batch before the parallel loop (read-only, and each query writes only
// its own result slots).
namespace openpbr::host::cpu_kernel {
const float* queries = nullptr;
const float* materials = nullptr;
float* results = nullptr;
}  // namespace openpbr::host::cpu_kernel
#define OPENPBR_QUERY_READ(index) ::openpbr::host::cpu_kernel::queries[index]
#define OPENPBR_MATERIAL_READ(index) ::openpbr::host::cpu_kernel::materials[index]
#define OPENPBR_RESULT_WRITE(index, value) ::openpbr::host::cpu_kernel::results[index] = (value)
#include "targets/kernels/openpbr_conformance_kernel.h"

namespace openpbr::host {

namespace {

// Output slots compared for every query (eval and pdf) and for agreeing samples only.
constexpr int eval_slot_begin = 0;
constexpr int eval_slot_end = 7;
constexpr int sample_slot_begin = 7;
constexpr int sample_slot_end = 17;
constexpr int lobe_type_slot = 17;
constexpr int emission_slot_begin = 18;
constexpr int emission_slot_end = 21;

const char* slot_name(int slot)
{
    static const char* names[] = {"eval.diffuse.r",  "eval.diffuse.g",  "eval.diffuse.b",  "eval.specular.r",
                                  "eval.specular.g", "eval.specular.b", "pdf",             "sample.direction.x",
                                  "sample.direction.y", "sample.direction.z", "sample.weight.diffuse.r",
                                  "sample.weight.diffuse.g", "sample.weight.diffuse.b", "sample.weight.specular.r",
                                  "sample.weight.specular.g", "sample.weight.specular.b", "sample.pdf",
                                  "sample.lobe_type", "emission.r", "emission.g", "emission.b"};
    return slot < 21 ? names[slot] : "unused";
}

double relative_error(float gpu, float cpu)
{
    return std::fabs(double(gpu) - double(cpu)) / std::max(std::fabs(double(cpu)), 1e-3);
}

struct GpuBatchResult
{
    std::vector<float> results;
    DispatchTiming timing;
};

struct GpuPath
{
    std::string name;
    std::string kernel_file;  // under the kernel directory
    std::string entry_point;
    // Texture tables (OPENPBR_USE_TEXTURE_LUTS): the tables are sampled images at bindings
    // 6-13 (slang/openpbr_lut_textures.h), not the buffers at 0 and 1.
    bool texture_tables = false;
};

const std::vector<GpuPath>& gpu_paths()
{
    static const std::vector<GpuPath> paths = {
        {"slang-spirv", "conformance.slang.spv", "main"},
        {"glsl-spirv", "conformance.glsl.spv", "main"},
        {"slang-hlsl", "conformance.slang-hlsl.spv", "main"},
        {"slang-glsl", "conformance.slang-glsl.spv", "main"},
        {"hlsl", "conformance.hlsl.spv", "main"},
        {"glsl-spirv-texture", "conformance_texture.glsl.spv", "main", true},
        {"slang-spirv-texture", "conformance_texture.slang.spv", "main", true},
        {"hlsl-texture", "conformance_texture.hlsl.spv", "main", true},
    };
    return paths;
}

const GpuPath& find_gpu_path(const std::string& path_name)
{
    for (const GpuPath& path : gpu_paths())
    {
        if (path.name == path_name)
        {
            return path;
        }
    }
    throw std::invalid_argument("unknown GPU path '" + path_name + "'");
}

// Bindings shared by every conformance kernel: 0 tables, 1 fuzz table, 2 queries,
// 3 materials, 4 parameters, 5 results.
ComputePipelineDescription conformance_pipeline_description(const GpuPath& path, const std::string& kernel_directory)
{
    ComputePipelineDescription description;
    description.spirv_words = load_spirv_file(kernel_directory + "/" + path.kernel_file);
    description.entry_point = path.entry_point;
    if (path.texture_tables)
    {
        description.bindings = {{2, false}, {3, false}, {4, false}, {5, false}};
        for (std::uint32_t table = 0; table < OPENPBR_LUT_TEXTURE_COUNT; ++table)
        {
            description.bindings.push_back({OPENPBR_LUT_TEXTURES_FIRST_BINDING + table, false, true});
        }
    }
    else
    {
        description.bindings = {{0, false}, {1, false}, {2, false}, {3, false}, {4, false}, {5, false}};
    }
    return description;
}

// The eight table textures, filled as slang/openpbr_lut_textures.h says (contiguous ranges of
// the shipped flat tables, x fastest).
struct TableTexture
{
    std::uint32_t width;
    std::uint32_t height;
    std::uint32_t depth;
    bool fuzz_table;  // from the fuzz LTC table rather than the energy-compensation tables
    std::size_t offset;
};

std::vector<TableTexture> table_textures()
{
    const std::uint32_t n2 = OPENPBR_LUT_2D_SIZE;
    const std::uint32_t n3 = OPENPBR_LUT_3D_SIZE;
    const std::uint32_t n4 = OPENPBR_LUT_4D_SIZE;
    const std::uint32_t m4 = OPENPBR_LUT_4D_ANISOTROPY_SIZE;
    const std::uint32_t nf = OPENPBR_FUZZ_LTC_SIZE;
    return {{n2, n2, 1, false, OPENPBR_LUT_GGX_ALBEDO_OFFSET},
            {n3, n3, n3, false, OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET},
            {n3, n3, n3, false, OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET},
            {n3, n3, n3, false, OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET},
            {n4, n4, m4 * m4, false, OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET},
            {nf, nf, 1, true, OPENPBR_FUZZ_LTC_A_OFFSET},
            {nf, nf, 1, true, OPENPBR_FUZZ_LTC_B_OFFSET},
            {nf, nf, 1, true, OPENPBR_FUZZ_LTC_R_OFFSET}};
}

GpuBatchResult dispatch_conformance(ComputePipeline& pipeline, const std::vector<float>& queries,
                                    const std::vector<float>& materials, int repeats, bool texture_tables = false)
{
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;

    std::vector<std::byte> lut_bytes = to_bytes(shipped_lut());
    std::vector<std::byte> fuzz_bytes = to_bytes(shipped_fuzz_ltc());
    std::vector<std::byte> query_bytes = to_bytes(queries);
    std::vector<std::byte> material_bytes = to_bytes(materials);
    std::vector<std::byte> result_bytes(query_count * OPENPBR_RESULT_FLOATS * sizeof(float));
    std::vector<std::byte> parameter_bytes = to_bytes(std::vector<std::uint32_t>{std::uint32_t(query_count), 0, 0, 0});
    std::vector<BufferBinding> buffers = {{2, &query_bytes, false}, {3, &material_bytes, false},
                                          {4, &parameter_bytes, false}, {5, &result_bytes, true}};
    std::vector<std::vector<std::byte>> texture_bytes;
    if (texture_tables)
    {
        const std::vector<TableTexture> textures = table_textures();
        texture_bytes.reserve(textures.size());
        for (std::size_t table = 0; table < textures.size(); ++table)
        {
            const TableTexture& texture = textures[table];
            const std::vector<std::byte>& source = texture.fuzz_table ? fuzz_bytes : lut_bytes;
            const std::size_t bytes = std::size_t(texture.width) * texture.height * texture.depth * sizeof(float);
            const auto first = source.begin() + std::ptrdiff_t(texture.offset * sizeof(float));
            texture_bytes.emplace_back(first, first + std::ptrdiff_t(bytes));
            BufferBinding image;
            image.binding = OPENPBR_LUT_TEXTURES_FIRST_BINDING + std::uint32_t(table);
            image.data = &texture_bytes.back();
            image.image_width = texture.width;
            image.image_height = texture.height;
            image.image_depth = texture.depth;
            buffers.push_back(image);
        }
    }
    else
    {
        buffers.insert(buffers.begin(), {{0, &lut_bytes, false}, {1, &fuzz_bytes, false}});
    }
    const std::uint32_t groups = std::uint32_t((query_count + 63) / 64);
    GpuBatchResult batch;
    batch.timing = run(pipeline, buffers, groups, 1, 1, repeats);
    batch.results = from_bytes<float>(result_bytes);
    return batch;
}

GpuBatchResult execute_gpu_path(const GpuPath& path, VulkanContext& context, const std::vector<float>& queries,
                                const std::vector<float>& materials, const std::string& kernel_directory)
{
    ComputePipeline pipeline(context, conformance_pipeline_description(path, kernel_directory));
    return dispatch_conformance(pipeline, queries, materials, 3, path.texture_tables);
}

// Compares one path's results with the CPU build's (see the foundation issue's metrics).
void compare_with_cpu(ConformancePathResult& result, const std::vector<float>& queries,
                      const std::vector<float>& gpu_results, const std::vector<float>& cpu_results)
{
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    std::vector<double> errors;
    errors.reserve(query_count * (eval_slot_end + sample_slot_end - sample_slot_begin + 3));
    std::size_t mismatches = 0;
    double worst = -1.0;
    for (std::size_t query = 0; query < query_count; ++query)
    {
        const float* gpu = gpu_results.data() + query * OPENPBR_RESULT_FLOATS;
        const float* cpu = cpu_results.data() + query * OPENPBR_RESULT_FLOATS;
        for (int slot = 0; slot < emission_slot_end; ++slot)
        {
            if (!std::isfinite(gpu[slot]))
            {
                ++result.nonfinite;
            }
        }
        const bool lobes_agree = gpu[lobe_type_slot] == cpu[lobe_type_slot];
        mismatches += lobes_agree ? 0 : 1;
        auto compare = [&](int begin, int end) {
            for (int slot = begin; slot < end; ++slot)
            {
                const double error = relative_error(gpu[slot], cpu[slot]);
                errors.push_back(std::isfinite(error) ? error : 1e30);
                if (error > worst)
                {
                    worst = error;
                    std::ostringstream where;
                    where << slot_name(slot) << " of query " << query << " (material "
                          << queries[query * OPENPBR_QUERY_FLOATS] << "): gpu " << gpu[slot] << ", cpu " << cpu[slot];
                    result.worst_output = where.str();
                }
            }
        };
        compare(eval_slot_begin, eval_slot_end);
        compare(emission_slot_begin, emission_slot_end);
        if (lobes_agree)
        {
            compare(sample_slot_begin, sample_slot_end);
        }
    }
    std::sort(errors.begin(), errors.end());
    result.max_relative_error = errors.empty() ? 0.0 : errors.back();
    result.p999_relative_error = errors.empty() ? 0.0 : errors[std::size_t(0.999 * double(errors.size() - 1))];
    result.lobe_mismatch_fraction = query_count ? double(mismatches) / double(query_count) : 0.0;
}

ConformancePathResult run_gpu_path(const GpuPath& path, VulkanContext& context, const std::vector<float>& queries,
                                   const std::vector<Material>& material_list, const std::vector<float>& materials,
                                   const std::vector<float>& cpu_results, const ConformanceOptions& options)
{
    ConformancePathResult result;
    result.name = path.name;
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    context.clear_validation_messages();
    GpuBatchResult batch;
    if (options.specialize)
    {
        // One pipeline per toggle set the materials need (host/scene/features.h); the first-dispatch
        // time is that of every set together, the steady-state time the sum over the sets.
        const SpecializedConformanceRun run = run_conformance_gpu_specialized(
            path.name, context, queries, material_list, options.kernel_directory, std::nullopt, 3);
        batch.results = run.results;
        batch.timing.dispatch_ms = run.dispatch_ms;
        for (const SpecializedPipelineTiming& pipeline : run.pipelines)
        {
            batch.timing.first_dispatch_ms += pipeline.first_dispatch_ms;
        }
        result.pipeline_count = run.pipeline_builds;
    }
    else
    {
        batch = execute_gpu_path(path, context, queries, materials, options.kernel_directory);
        result.pipeline_count = 1;
    }
    const DispatchTiming& timing = batch.timing;
    result.executed = true;
    result.note = context.device_name();
    result.first_dispatch_ms = timing.first_dispatch_ms;
    result.queries_per_second = timing.dispatch_ms > 0.0 ? double(query_count) / (timing.dispatch_ms * 1e-3) : 0.0;
    const std::vector<std::string> messages = context.validation_messages();
    result.validation_messages = messages.size();
    if (!messages.empty())
    {
        result.note += "; validation: " + messages.front();
    }
    compare_with_cpu(result, queries, batch.results, cpu_results);
    return result;
}

}  // namespace

std::vector<float> run_conformance_gpu(const std::string& path_name, VulkanContext& context,
                                       const std::vector<float>& queries, const std::vector<float>& materials,
                                       const std::string& kernel_directory)
{
    return execute_gpu_path(find_gpu_path(path_name), context, queries, materials, kernel_directory).results;
}

SpecializedConformanceRun run_conformance_gpu_specialized(const std::string& path_name, VulkanContext& context,
                                                          const std::vector<float>& queries,
                                                          const std::vector<Material>& materials,
                                                          const std::string& kernel_directory,
                                                          std::optional<std::uint32_t> pipeline_mask, int repeats)
{
    if (pipeline_mask)
    {
        check_pipeline_supports(materials, *pipeline_mask);
    }
    const GpuPath& path = find_gpu_path(path_name);
    SpecializedPipelineCache cache(context, conformance_pipeline_description(path, kernel_directory));
    const std::vector<float> packed = pack_materials(materials);
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    // Queries grouped by the toggle set of the pipeline that runs them.
    std::map<std::uint32_t, std::vector<std::size_t>> groups;
    for (std::size_t query = 0; query < query_count; ++query)
    {
        const std::size_t material = std::size_t(queries[query * OPENPBR_QUERY_FLOATS]);
        if (material >= materials.size())
        {
            throw std::invalid_argument("query " + std::to_string(query) + " names material " + std::to_string(material) +
                                        " of " + std::to_string(materials.size()));
        }
        groups[pipeline_mask ? *pipeline_mask : required_feature_mask(materials[material])].push_back(query);
    }
    SpecializedConformanceRun run;
    run.results.assign(query_count * OPENPBR_RESULT_FLOATS, 0.0f);
    for (const auto& [mask, members] : groups)
    {
        std::vector<float> group_queries(members.size() * OPENPBR_QUERY_FLOATS);
        for (std::size_t i = 0; i < members.size(); ++i)
        {
            std::memcpy(&group_queries[i * OPENPBR_QUERY_FLOATS], &queries[members[i] * OPENPBR_QUERY_FLOATS],
                        OPENPBR_QUERY_FLOATS * sizeof(float));
        }
        const std::size_t builds_before = cache.build_count();
        ComputePipeline& pipeline = cache.pipeline(mask);
        const GpuBatchResult batch = dispatch_conformance(pipeline, group_queries, packed, repeats, path.texture_tables);
        for (std::size_t i = 0; i < members.size(); ++i)
        {
            std::memcpy(&run.results[members[i] * OPENPBR_RESULT_FLOATS], &batch.results[i * OPENPBR_RESULT_FLOATS],
                        OPENPBR_RESULT_FLOATS * sizeof(float));
        }
        SpecializedPipelineTiming timing;
        timing.mask = mask;
        timing.query_count = members.size();
        timing.built = cache.build_count() > builds_before;
        timing.create_ms = pipeline.create_ms();
        timing.first_dispatch_ms = batch.timing.first_dispatch_ms;
        timing.dispatch_ms = batch.timing.dispatch_ms;
        run.dispatch_ms += batch.timing.dispatch_ms;
        run.pipelines.push_back(timing);
    }
    run.pipeline_builds = cache.build_count();
    return run;
}

std::vector<std::string> known_conformance_paths()
{
    std::vector<std::string> names;
    for (const GpuPath& path : gpu_paths())
    {
        names.push_back(path.name);
    }
    names.push_back("cuda");
    names.push_back("slang-cuda");
    return names;
}

std::vector<Material> conformance_materials(const std::vector<Material>& library)
{
    std::vector<Material> materials = library;
    materials.push_back(default_material());
    // Every lobe at partial weight, on a rough and a smooth variant, so mixtures of lobes and
    // delta lobes next to glossy ones are exercised everywhere.
    for (const float roughness : {0.45f, 0.0f})
    {
        Material everything = default_material();
        everything.name = roughness > 0.0f ? "EveryLobeRough" : "EveryLobeSmooth";
        OpenPBR_ResolvedInputs& inputs = everything.inputs;
        inputs.base_metalness = 0.3f;
        inputs.base_diffuse_roughness = 0.6f;
        inputs.specular_roughness = roughness;
        inputs.specular_roughness_anisotropy = 0.5f;
        inputs.specular_anisotropy_rotation = glm::vec2(0.6f, 0.8f);
        inputs.transmission_weight = 0.4f;
        inputs.transmission_depth = 0.5f;
        inputs.transmission_color = glm::vec3(0.9f, 0.7f, 0.5f);
        inputs.subsurface_weight = 0.3f;
        inputs.fuzz_weight = 0.35f;
        inputs.fuzz_roughness = 0.4f;
        inputs.coat_weight = 0.6f;
        inputs.coat_roughness = roughness * 0.5f;
        inputs.coat_color = glm::vec3(0.9f, 0.85f, 0.8f);
        inputs.thin_film_weight = 0.5f;
        inputs.thin_film_thickness = 0.4f;
        inputs.emission_luminance = 2.0f;
        inputs.geometry_opacity = 0.8f;
        materials.push_back(everything);
    }
    return materials;
}

std::vector<float> pack_materials(const std::vector<Material>& materials)
{
    std::vector<float> packed(materials.size() * OPENPBR_PACKED_MATERIAL_FLOATS, 0.0f);
    for (std::size_t m = 0; m < materials.size(); ++m)
    {
        const OpenPBR_ResolvedInputs& material = materials[m].inputs;
        float* out = packed.data() + m * OPENPBR_PACKED_MATERIAL_FLOATS;
        std::size_t index = 0;
        auto put = [&](float value) { out[index++] = value; };
        auto put3 = [&](const glm::vec3& value) { put(value.x); put(value.y); put(value.z); };
#define OPENPBR_PACK_FLOAT(name) put(material.name);
#define OPENPBR_PACK_COLOR(name) put3(material.name);
#define OPENPBR_PACK_VECTOR2(name) put(material.name.x); put(material.name.y);
#define OPENPBR_PACK_BOOL(name) put(material.name ? 1.0f : 0.0f);
#define OPENPBR_PACK_BASIS(name) put3(material.name.tangent); put3(material.name.bitangent); put3(material.name.normal);
        OPENPBR_MATERIAL_FIELDS(OPENPBR_PACK_FLOAT, OPENPBR_PACK_COLOR, OPENPBR_PACK_VECTOR2, OPENPBR_PACK_BOOL,
                                OPENPBR_PACK_BASIS)
#undef OPENPBR_PACK_FLOAT
#undef OPENPBR_PACK_COLOR
#undef OPENPBR_PACK_VECTOR2
#undef OPENPBR_PACK_BOOL
#undef OPENPBR_PACK_BASIS
        if (index > OPENPBR_PACKED_MATERIAL_FLOATS)
        {
            throw std::logic_error("OPENPBR_PACKED_MATERIAL_FLOATS is smaller than the material field list");
        }
    }
    return packed;
}

std::vector<float> make_queries(std::size_t query_count, std::size_t material_count, std::uint64_t seed)
{
    std::mt19937_64 generator(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    auto unit_sphere = [&]() {
        const float z = 1.0f - 2.0f * uniform(generator);
        const float radius = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 6.2831853f * uniform(generator);
        return glm::vec3(radius * std::cos(phi), radius * std::sin(phi), z);
    };
    std::vector<float> queries(query_count * OPENPBR_QUERY_FLOATS);
    for (std::size_t query = 0; query < query_count; ++query)
    {
        float* out = queries.data() + query * OPENPBR_QUERY_FLOATS;
        out[0] = float(query % std::max<std::size_t>(material_count, 1));
        // Views mostly above the surface (where most shading happens), some from below.
        glm::vec3 view = unit_sphere();
        if (uniform(generator) < 0.8f)
        {
            view.z = std::fabs(view.z);
        }
        const glm::vec3 light = unit_sphere();
        out[1] = view.x, out[2] = view.y, out[3] = view.z;
        out[4] = light.x, out[5] = light.y, out[6] = light.z;
        // u in [0, 1): the float distribution can round up to 1.
        for (int k = 7; k < 10; ++k)
        {
            out[k] = std::min(uniform(generator), 0.99999994f);
        }
        // Exterior IOR: mostly air; one query in eight under water (1.33), one in eight inside
        // glass (1.5), so the relative IOR of every interface also falls below 1.
        const float exterior_choice = uniform(generator);
        out[10] = exterior_choice < 0.75f ? 1.0f : (exterior_choice < 0.875f ? 1.33f : 1.5f);
    }
    return queries;
}

std::vector<float> run_conformance_cpu(const std::vector<float>& queries, const std::vector<float>& materials)
{
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    std::vector<float> results(query_count * OPENPBR_RESULT_FLOATS, 0.0f);
    cpu_kernel::queries = queries.data();
    cpu_kernel::materials = materials.data();
    cpu_kernel::results = results.data();
    tbb::parallel_for(std::size_t(0), query_count,
                      [](std::size_t query) { openpbr::openpbr_conformance_run_query(unsigned(query)); });
    return results;
}

ConformanceReport run_conformance(const std::vector<Material>& materials, const ConformanceOptions& options)
{
    ConformanceReport report;
    report.query_count = options.query_count;
    report.material_count = materials.size();
    const std::vector<float> packed = pack_materials(materials);
    const std::vector<float> queries = make_queries(options.query_count, materials.size(), options.seed);

    const auto cpu_start = std::chrono::steady_clock::now();
    const std::vector<float> cpu_results = run_conformance_cpu(queries, packed);
    const double cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - cpu_start).count();
    report.cpu_queries_per_second = cpu_seconds > 0.0 ? double(options.query_count) / cpu_seconds : 0.0;
    for (const float value : cpu_results)
    {
        report.cpu_nonfinite += std::isfinite(value) ? 0 : 1;
    }
    if (!options.cpu_dump_path.empty())
    {
        std::ofstream dump(options.cpu_dump_path, std::ios::binary);
        dump.write(reinterpret_cast<const char*>(cpu_results.data()), std::streamsize(cpu_results.size() * sizeof(float)));
        if (!dump)
        {
            throw std::runtime_error("cannot write " + options.cpu_dump_path);
        }
    }

    std::vector<std::string> wanted = options.paths.empty() ? known_conformance_paths() : options.paths;
    std::string context_error;
    VulkanOptions vulkan_options;
    vulkan_options.enable_validation = options.validation;
    std::optional<VulkanContext> context = VulkanContext::create(vulkan_options, &context_error);
    for (const GpuPath& path : gpu_paths())
    {
        if (std::find(wanted.begin(), wanted.end(), path.name) == wanted.end())
        {
            continue;
        }
        if (!context)
        {
            ConformancePathResult skipped;
            skipped.name = path.name;
            skipped.note = context_error;
            report.paths.push_back(skipped);
            continue;
        }
        report.paths.push_back(run_gpu_path(path, *context, queries, materials, packed, cpu_results, options));
    }
    // CUDA runs in its own program (built with nvcc); it says plainly when no device exists.
    const bool wants_cuda = std::find(wanted.begin(), wanted.end(), "cuda") != wanted.end() ||
                            std::find(wanted.begin(), wanted.end(), "slang-cuda") != wanted.end();
    if (wants_cuda)
    {
        for (const ExternalPathResult& external :
             run_cuda_conformance_program(default_cuda_conformance_program(), queries, packed))
        {
            if (std::find(wanted.begin(), wanted.end(), external.name) == wanted.end())
            {
                continue;
            }
            ConformancePathResult result;
            result.name = external.name;
            result.executed = external.executed;
            result.note = external.note;
            if (external.executed)
            {
                compare_with_cpu(result, queries, external.results, cpu_results);
            }
            report.paths.push_back(result);
        }
    }
    return report;
}

nlohmann::json to_json(const ConformanceReport& report)
{
    nlohmann::json json;
    json["queries"] = report.query_count;
    json["materials"] = report.material_count;
    json["cpu_nonfinite"] = report.cpu_nonfinite;
    json["cpu_queries_per_second"] = report.cpu_queries_per_second;
    json["paths"] = nlohmann::json::array();
    for (const ConformancePathResult& path : report.paths)
    {
        json["paths"].push_back({{"name", path.name},
                                 {"executed", path.executed},
                                 {"note", path.note},
                                 {"max_rel_err", path.max_relative_error},
                                 {"p999_rel_err", path.p999_relative_error},
                                 {"nonfinite", path.nonfinite},
                                 {"lobe_mismatch_frac", path.lobe_mismatch_fraction},
                                 {"first_dispatch_ms", path.first_dispatch_ms},
                                 {"queries_per_second", path.queries_per_second},
                                 {"validation_messages", path.validation_messages},
                                 {"pipelines", path.pipeline_count},
                                 {"worst_output", path.worst_output}});
    }
    return json;
}

std::string to_text(const ConformanceReport& report)
{
    std::ostringstream text;
    text << "conformance: " << report.query_count << " queries over " << report.material_count
         << " materials; CPU: " << report.cpu_nonfinite << " non-finite, " << std::lround(report.cpu_queries_per_second)
         << " queries/s\n";
    for (const ConformancePathResult& path : report.paths)
    {
        if (!path.executed)
        {
            text << "  " << path.name << ": not executed: " << path.note << "\n";
            continue;
        }
        text << "  " << path.name << " (" << path.note << "): max rel err " << path.max_relative_error
             << ", p99.9 " << path.p999_relative_error << ", non-finite " << path.nonfinite << ", lobe mismatch "
             << 100.0 * path.lobe_mismatch_fraction << " %, " << std::lround(path.queries_per_second)
             << " queries/s, first dispatch " << path.first_dispatch_ms << " ms, " << path.pipeline_count
             << (path.pipeline_count == 1 ? " pipeline\n" : " pipelines\n");
        text << "    worst: " << path.worst_output << "\n";
    }
    return text.str();
}

}  // namespace openpbr::host
