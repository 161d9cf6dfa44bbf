// accuracy.cpp - see accuracy.h.
#include "host/studies/accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/packing.hpp>
#include <tbb/parallel_for.h>

#include "host/studies/accuracy_variants.h"
#include "host/checks/conformance.h"
#include "host/tables/lut_generator.h"
#include "host/scene/material_library.h"
#include "host/tables/microsurface.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "host/support/directional_albedo.h"
#include "host/support/progress.h"
#include "host/support/stopwatch.h"
#include "slang/baselines/openpbr_baseline_ggx.h"
#include "slang/openpbr.h"

namespace openpbr::host {

AccuracyOptions AccuracyOptions::effective() const
{
    AccuracyOptions result = *this;
    if (quick)
    {
        result.walk_paths = std::min<std::uint64_t>(walk_paths, 1u << 12);
        result.albedo_samples = std::min<std::uint32_t>(albedo_samples, 256);
        result.timing_queries = std::min<std::uint32_t>(timing_queries, 512);
        result.table_samples = std::min<std::uint32_t>(table_samples, 256);
        result.compile = false;
    }
    return result;
}

namespace {

// ---- Grids and workloads ------------------------------------------------------------------

struct Grid
{
    std::vector<float> roughness;
    std::vector<float> mu;
    std::vector<float> f0;  // Schlick conductors; F0 stands in for the IOR axis
};

Grid make_grid(bool quick)
{
    if (quick)
    {
        return {{0.3f, 0.7f}, {0.2f, 0.6f, 1.0f}, {1.0f, 0.5f}};
    }
    return {{0.1f, 0.3f, 0.5f, 0.7f, 0.9f}, {0.1f, 0.25f, 0.5f, 0.75f, 1.0f}, {1.0f, 0.9f, 0.5f}};
}

AccuracyMaterial metal(float f0, float roughness)
{
    AccuracyMaterial material;
    material.base_color[0] = material.base_color[1] = material.base_color[2] = f0;
    material.base_metalness = 1.0f;
    material.specular_roughness = roughness;
    return material;
}

AccuracyMaterial glass(float roughness)
{
    AccuracyMaterial material;
    material.transmission_weight = 1.0f;
    material.specular_roughness = roughness;
    return material;
}

// The timing and per-query workload: a mix of the materials a renderer meets.
std::vector<AccuracyMaterial> workload_materials(bool thin_film)
{
    std::vector<AccuracyMaterial> materials;
    for (const float roughness : {0.1f, 0.4f, 0.8f})
    {
        AccuracyMaterial plastic;
        plastic.specular_roughness = roughness;
        AccuracyMaterial coated = metal(0.9f, roughness);
        coated.coat_weight = 1.0f;
        coated.coat_roughness = 0.1f;
        AccuracyMaterial brushed = metal(0.8f, roughness);
        brushed.specular_roughness_anisotropy = 0.6f;
        for (AccuracyMaterial material : {plastic, metal(0.95f, roughness), glass(roughness), coated, brushed})
        {
            if (thin_film)
            {
                material.thin_film_weight = 1.0f;
                material.thin_film_thickness = 0.3f + 0.2f * roughness;
            }
            materials.push_back(material);
        }
    }
    return materials;
}

std::vector<AccuracyQuery> workload_queries(std::size_t material_count, std::uint32_t count)
{
    std::mt19937_64 generator(20231122);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::vector<AccuracyQuery> queries(count);
    for (std::uint32_t i = 0; i < count; ++i)
    {
        AccuracyQuery& query = queries[i];
        query.material = i % std::uint32_t(material_count);
        const float view_cos = 0.05f + 0.95f * uniform(generator);
        const float view_phi = 6.2831853f * uniform(generator);
        const float view_sin = std::sqrt(1.0f - view_cos * view_cos);
        query.view[0] = view_sin * std::cos(view_phi);
        query.view[1] = view_sin * std::sin(view_phi);
        query.view[2] = view_cos;
        // Light: uniform on the sphere, so transmission is evaluated too.
        const float light_z = 1.0f - 2.0f * uniform(generator);
        const float light_phi = 6.2831853f * uniform(generator);
        const float light_r = std::sqrt(std::max(0.0f, 1.0f - light_z * light_z));
        query.light[0] = light_r * std::cos(light_phi);
        query.light[1] = light_r * std::sin(light_phi);
        query.light[2] = light_z;
        for (float& u : query.u)
        {
            u = std::min(uniform(generator), 0.99999994f);
        }
    }
    return queries;
}

// Best of three runs of `run`, in ns per query (the minimum is the least disturbed by the other
// processes of a shared machine).
template <typename Function> double time_ns_per_query(std::size_t queries, Function run)
{
    double best = std::numeric_limits<double>::infinity();
    for (int repeat = 0; repeat < 3; ++repeat)
    {
        const Stopwatch stopwatch;
        run();
        best = std::min(best, stopwatch.seconds() * 1e9 / double(queries));
    }
    return best;
}

// Largest relative difference of `values` from `reference` over entries whose reference
// exceeds 1e-3 (smaller values are dominated by float rounding of cancelling terms).
double max_relative_error(const std::vector<float>& values, const std::vector<float>& reference)
{
    double worst = 0.0;
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        if (std::abs(reference[i]) > 1e-3f)
        {
            worst = std::max(worst, std::abs(double(values[i]) - reference[i]) / std::abs(double(reference[i])));
        }
    }
    return worst;
}

// A percentile (e.g. 0.5, 0.99) of the same relative differences (the maximum is set by a few
// values near cancellation, e.g. 1 - F of transmission near total internal reflection).
double percentile_relative_error(const std::vector<float>& values, const std::vector<float>& reference,
                                 double percentile = 0.99)
{
    std::vector<double> errors;
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        if (std::abs(reference[i]) > 1e-3f)
        {
            errors.push_back(std::abs(double(values[i]) - reference[i]) / std::abs(double(reference[i])));
        }
    }
    if (errors.empty())
    {
        return 0.0;
    }
    const std::size_t index = std::min(errors.size() - 1, std::size_t(percentile * double(errors.size())));
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(index), errors.end());
    return errors[index];
}

struct AlbedoErrors
{
    double max_error = 0.0;
    double mean_error = 0.0;
};

AlbedoErrors albedo_errors(const std::vector<double>& model, const std::vector<double>& truth)
{
    AlbedoErrors errors;
    for (std::size_t i = 0; i < model.size(); ++i)
    {
        const double error = std::abs(model[i] - truth[i]);
        errors.max_error = std::max(errors.max_error, error);
        errors.mean_error += error / double(model.size());
    }
    return errors;
}

// ---- Tables of other sizes and precisions ---------------------------------------------------

// The shipped flat table with table 0 replaced by one of `size` x `size` nodes (the layout of
// slang/openpbr_lut.h with OPENPBR_LUT_2D_SIZE = size; the film table 5 follows the
// compensation tables as in the shipped array), cached in the cache directory.
std::vector<float> table_with_2d_size(int size, std::uint32_t samples, const std::filesystem::path& cache_directory)
{
    const LutLayout shipped = compiled_lut_layout();
    const std::vector<float> shipped_values(openpbr_lut_data, openpbr_lut_data + OPENPBR_LUT_TOTAL_COUNT);
    LutLayout layout = shipped;
    layout.size_2d = size;
    const std::filesystem::path cache_file =
        cache_directory.empty()
            ? std::filesystem::path()
            : cache_directory / ("lut_2d_" + std::to_string(size) + "_" + std::to_string(samples) + ".bin");
    if (!cache_file.empty() && std::filesystem::exists(cache_file))
    {
        try
        {
            return read_lut_binary(cache_file, layout.total_count() + OPENPBR_LUT_FILM_COUNT);
        }
        catch (const std::exception&)
        {
            // A damaged cache entry is regenerated below.
        }
    }
    std::vector<float> values(layout.total_count() + OPENPBR_LUT_FILM_COUNT);
    const std::size_t cells = std::size_t(size) * std::size_t(size);
    tbb::parallel_for(std::size_t(0), cells, [&](std::size_t cell) {
        const double mu = double(cell % std::size_t(size)) / double(size - 1);
        const double r = double(cell / std::size_t(size)) / double(size - 1);
        values[cell] = float(estimate_lut_entry(lut_table_ggx_albedo, mu, r, 0.0, samples, lut_cell_seed(0, cell)));
    });
    std::copy(shipped_values.begin() + std::ptrdiff_t(shipped.count(0)), shipped_values.end(),
              values.begin() + std::ptrdiff_t(cells));
    if (!cache_file.empty())
    {
        std::filesystem::create_directories(cache_directory);
        write_lut_binary(cache_file, values);
    }
    return values;
}

// ---- Baselines --------------------------------------------------------------------------------

AccuracyAlbedo baseline_albedo(float f0, float roughness, float mu, int visibility, std::uint32_t samples,
                               std::uint64_t seed)
{
    const glm::vec3 view(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    const OpenPBR_BaselineGgx bsdf = openpbr_baseline_ggx_prepare(glm::vec3(f0), 1.0f, roughness, visibility, view);
    // The point set and estimator of the BSDF variants' albedo (host/studies/accuracy_variant_body.h).
    const ShiftedR3Sequence sequence(seed);
    const DirectionalAlbedo estimate = estimate_directional_albedo(samples, [&](const std::uint64_t s) {
        const std::array<float, 3> point = sequence.point(s);
        const glm::vec4 drawn = openpbr_baseline_ggx_sample(bsdf, glm::vec3(point[0], point[1], point[2]));
        const float weight = drawn.w > 0.0f ? openpbr_baseline_ggx_eval(bsdf, glm::vec3(drawn)).x / drawn.w : 0.0f;
        return std::array<float, 3>{weight, weight, weight};
    });
    AccuracyAlbedo result;
    result.mean[0] = result.mean[1] = result.mean[2] = estimate.mean[0];
    return result;
}

// Bilinear look-up of the DFG table at (n.v, roughness).
glm::vec2 dfg_lookup(const std::vector<float>& table, int size, float n_dot_v, float roughness)
{
    const float fx = glm::clamp(n_dot_v, 0.0f, 1.0f) * float(size - 1);
    const float fy = glm::clamp(roughness, 0.0f, 1.0f) * float(size - 1);
    const int x0 = std::min(int(fx), size - 2);
    const int y0 = std::min(int(fy), size - 2);
    const float tx = fx - float(x0);
    const float ty = fy - float(y0);
    auto at = [&](int x, int y) {
        const std::size_t index = 2 * (std::size_t(y) * std::size_t(size) + std::size_t(x));
        return glm::vec2(table[index], table[index + 1]);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
}

// ---- Slang compile time -----------------------------------------------------------------------

struct CompileResult
{
    bool ok = false;
    double milliseconds = 0.0;
    double bytes = 0.0;
};

CompileResult slang_compile(const std::filesystem::path& root, const std::vector<std::string>& defines,
                            const std::filesystem::path& output)
{
    std::string command = "node \"" + (root / "targets/slangc.mjs").string() +
                          "\" -target spirv -entry conformance_main -stage compute -I \"" + (root / "slang").string() + "\"";
    for (const std::string& define : defines)
    {
        command += " -D" + define;
    }
    command +=
        " -o \"" + output.string() + "\" \"" + (root / "targets/kernels/conformance.slang").string() + "\" > /dev/null 2>&1";
    CompileResult result;
    const Stopwatch stopwatch;
    const int status = std::system(command.c_str());
    result.milliseconds = stopwatch.milliseconds();
    result.ok = status == 0 && std::filesystem::exists(output);
    result.bytes = result.ok ? double(std::filesystem::file_size(output)) : 0.0;
    return result;
}

// ---- lavapipe ---------------------------------------------------------------------------------

// The study's workload in the conformance kernel's layout (targets/kernels/conformance.slang,
// openpbr_conformance_kernel.h): per query the material index, view, light and the sampler's
// three numbers; the materials packed by the single-source field list.
struct LavapipeWorkload
{
    std::vector<float> queries;
    std::vector<float> materials;
    std::size_t query_count = 0;
    std::size_t result_floats = 0;  // floats per result record
};

LavapipeWorkload lavapipe_workload(const std::vector<AccuracyMaterial>& materials, const std::vector<AccuracyQuery>& queries)
{
    std::vector<Material> library;
    for (const AccuracyMaterial& material : materials)
    {
        Material entry = default_material();
        accuracy_apply_material(material, entry.inputs);
        library.push_back(entry);
    }
    LavapipeWorkload workload;
    workload.materials = pack_materials(library);
    workload.query_count = queries.size();
    // The record sizes come from the conformance module itself (a one-query batch), so this
    // layout cannot drift from the kernel's.
    const std::vector<float> probe = make_queries(1, 1, 1);
    const std::size_t query_floats = probe.size();
    workload.result_floats = run_conformance_cpu(probe, pack_materials({default_material()})).size();
    if (query_floats < 11)
    {
        throw std::runtime_error("accuracy: unexpected conformance query record of " + std::to_string(query_floats) +
                                 " floats");
    }
    workload.queries.assign(queries.size() * query_floats, 0.0f);
    for (std::size_t i = 0; i < queries.size(); ++i)
    {
        float* record = workload.queries.data() + i * query_floats;
        record[0] = float(queries[i].material);
        std::copy(queries[i].view, queries[i].view + 3, record + 1);
        std::copy(queries[i].light, queries[i].light + 3, record + 4);
        std::copy(queries[i].u, queries[i].u + 3, record + 7);
        record[10] = 1.0f;  // exterior IOR: the study's materials sit in air
    }
    return workload;
}

struct LavapipeRun
{
    double queries_per_second = 0.0;
    std::vector<float> values;  // eval diffuse + specular, 3 per query
};

// One conformance kernel on the workload: bindings 0 tables (`table`), 1 fuzz LTC table,
// 2 queries, 3 materials, 4 parameters, 5 results (host/checks/conformance.cpp's layout), and with
// `filtered_size` > 0 binding 6, table 0 (the first filtered_size^2 floats of `table`) as a
// bilinearly filtered image (OPENPBR_LUT_FILTERED_2D). Nine dispatches; the first includes
// llvmpipe's compile, the rate is from the median of the other eight (the machine is shared).
LavapipeRun run_on_lavapipe(VulkanContext& context, const std::filesystem::path& spirv, std::vector<std::byte> table,
                            const LavapipeWorkload& workload, std::uint32_t filtered_size = 0)
{
    std::vector<std::byte> fuzz_bytes = to_bytes(shipped_fuzz_ltc());
    std::vector<std::byte> query_bytes = to_bytes(workload.queries);
    std::vector<std::byte> material_bytes = to_bytes(workload.materials);
    std::vector<std::byte> result_bytes(workload.query_count * workload.result_floats * sizeof(float));
    std::vector<std::byte> parameter_bytes =
        to_bytes(std::vector<std::uint32_t>{std::uint32_t(workload.query_count), 0, 0, 0});
    std::vector<std::byte> image_bytes(table.begin(),
                                       table.begin() + std::ptrdiff_t(filtered_size * filtered_size * sizeof(float)));
    std::vector<BufferBinding> buffers = {{0, &table, false},           {1, &fuzz_bytes, false},
                                          {2, &query_bytes, false},     {3, &material_bytes, false},
                                          {4, &parameter_bytes, false}, {5, &result_bytes, true}};
    if (filtered_size > 0)
    {
        BufferBinding image;
        image.binding = 6;
        image.data = &image_bytes;
        image.image_width = filtered_size;
        image.image_height = filtered_size;
        buffers.push_back(image);
    }
    ComputePipelineDescription description;
    description.spirv_words = load_spirv_file(spirv.string());
    description.entry_point = "main";
    description.bindings = binding_layouts_of(buffers);
    ComputePipeline pipeline(context, description);
    const DispatchTiming timing = run(pipeline, buffers, std::uint32_t((workload.query_count + 63) / 64), 1, 1, 9);
    LavapipeRun result;
    result.queries_per_second = double(workload.query_count) / (std::max(timing.dispatch_ms, 1e-6) * 1e-3);
    const std::vector<float> results = from_bytes<float>(result_bytes);
    result.values.resize(3 * workload.query_count);
    for (std::size_t i = 0; i < workload.query_count; ++i)
    {
        for (int c = 0; c < 3; ++c)
        {
            // Result record: eval.diffuse (3), eval.specular (3), ...
            result.values[3 * i + c] = results[i * workload.result_floats + c] + results[i * workload.result_floats + 3 + c];
        }
    }
    return result;
}

}  // namespace

std::vector<float> generate_dfg_table(int size, std::uint32_t samples, int visibility)
{
    if (size < 2 || samples == 0)
    {
        throw std::invalid_argument("generate_dfg_table: size >= 2 and samples >= 1");
    }
    std::vector<float> table(2 * std::size_t(size) * std::size_t(size));
    for (int y = 0; y < size; ++y)
    {
        const float roughness = float(y) / float(size - 1);
        const float alpha = std::max(roughness * roughness, 4e-4f);
        for (int x = 0; x < size; ++x)
        {
            const float n_dot_v = std::max(float(x) / float(size - 1), 1e-3f);
            glm::dvec2 sum(0.0);
            for (std::uint32_t s = 0; s < samples; ++s)
            {
                // Hammersley point set: (i + 1/2) / n and the base-2 radical inverse.
                std::uint32_t bits = s;
                bits = (bits << 16u) | (bits >> 16u);
                bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
                bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
                bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
                bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
                const glm::vec2 u((float(s) + 0.5f) / float(samples), std::min(float(bits) * 2.3283064e-10f, 0.99999994f));
                sum += glm::dvec2(openpbr_baseline_dfg_sample(n_dot_v, alpha, visibility, u));
            }
            const std::size_t index = 2 * (std::size_t(y) * std::size_t(size) + std::size_t(x));
            table[index] = float(sum.x / samples);
            table[index + 1] = float(sum.y / samples);
        }
    }
    return table;
}

const float* accuracy_lut_values_16 = nullptr;
const float* accuracy_lut_values_64 = nullptr;

std::vector<AccuracyRow> run_accuracy_study(const AccuracyOptions& requested)
{
    const AccuracyOptions options = requested.effective();
    const Grid grid = make_grid(options.quick);
    std::vector<BsdfVariant> variants = bsdf_variants();
    const int baseline_count = 2 + 4;
    int vulkan_settings = 0;
    for (const BsdfVariant& variant : variants)
    {
        vulkan_settings += variant.on_vulkan ? 1 : 0;
    }
    ProgressReporter progress(
        std::uint64_t(4 + int(variants.size()) + baseline_count + (options.compile ? vulkan_settings + 1 : 0)),
        options.progress, "accuracy");
    std::vector<AccuracyRow> rows;
    auto add = [&rows](const std::string& knob, const std::string& setting, const std::string& error_metric, double error,
                       const std::string& time_metric, double time, bool plotted = false) {
        rows.push_back(AccuracyRow{knob, setting, error_metric, error, time_metric, time, plotted});
    };

    // Ground truth: the random walk of every grid point (all orders), cached.
    MicrosurfaceCache cache(options.cache_directory.empty() ? std::filesystem::path()
                                                            : options.cache_directory / "microsurface_walks.json");
    std::vector<MicrosurfaceQuery> truth_queries;
    std::vector<AccuracyMaterial> grid_materials;
    std::vector<float> grid_mu;
    for (const float f0 : grid.f0)
    {
        for (const float roughness : grid.roughness)
        {
            for (const float mu : grid.mu)
            {
                MicrosurfaceQuery query;
                query.material.kind = f0 >= 1.0f ? MicrosurfaceKind::conductor_white : MicrosurfaceKind::conductor_schlick;
                query.material.alpha = double(roughness) * double(roughness);
                query.material.f0 = f0;
                query.mu = mu;
                query.max_order = 0;
                query.paths = options.walk_paths;
                query.seed = truth_queries.size() + 1;
                truth_queries.push_back(query);
                grid_materials.push_back(metal(f0, roughness));
                grid_mu.push_back(mu);
            }
        }
    }
    // The single-scattering walk (order 1) of the same points: what the baselines without
    // compensation converge to.
    std::vector<MicrosurfaceQuery> single_queries = truth_queries;
    for (MicrosurfaceQuery& query : single_queries)
    {
        query.max_order = 1;
    }
    const std::vector<MicrosurfaceAlbedo> single_albedos = cache.albedos(single_queries);
    std::vector<double> single_truth(single_albedos.size());
    for (std::size_t i = 0; i < single_truth.size(); ++i)
    {
        single_truth[i] = single_albedos[i].reflected;
    }
    const std::vector<MicrosurfaceAlbedo> truth_albedos = cache.albedos(truth_queries);
    cache.save();
    std::vector<double> truth(truth_albedos.size());
    for (std::size_t i = 0; i < truth.size(); ++i)
    {
        truth[i] = truth_albedos[i].reflected;
    }
    progress.begin_step("ground truth (random walk)");

    // Tables at 16 and 64 nodes per axis; 16-bit halves of the shipped table.
    const std::vector<float> table_16 = table_with_2d_size(16, options.table_samples, options.cache_directory);
    const std::vector<float> table_64 = table_with_2d_size(64, options.table_samples, options.cache_directory);
    accuracy_lut_values_16 = table_16.data();
    accuracy_lut_values_64 = table_64.data();
    const std::size_t shipped_count = compiled_lut_layout().total_count();
    std::vector<std::uint16_t> halves(shipped_count);
    for (std::size_t i = 0; i < shipped_count; ++i)
    {
        halves[i] = glm::packHalf1x16(openpbr_lut_data[i]);
    }
    accuracy_set_half_table(halves.data());
    accuracy_set_buffer_table(openpbr_lut_data);
    progress.begin_step("tables at 16 and 64 nodes, 16-bit values");

    const std::vector<AccuracyMaterial> materials = workload_materials(false);
    const std::vector<AccuracyMaterial> film_materials = workload_materials(true);
    const std::vector<AccuracyQuery> queries = workload_queries(materials.size(), options.timing_queries);
    std::vector<float> reference(3 * queries.size());
    std::vector<float> film_reference(3 * queries.size());
    variants.front().eval(materials, queries, reference.data());
    variants.front().eval(film_materials, queries, film_reference.data());
    std::vector<float> reference_samples(3 * queries.size());
    variants.front().sample(materials, queries, reference_samples.data());
    // The double-precision build's values (the precision knob's reference).
    std::vector<float> double_reference;
    for (const BsdfVariant& variant : variants)
    {
        if (variant.double_reference)
        {
            double_reference.resize(3 * queries.size());
            variant.eval(materials, queries, double_reference.data());
        }
    }
    progress.begin_step("reference evaluations");

    const std::vector<AccuracyMaterial> white_materials = {metal(1.0f, 0.2f), metal(1.0f, 0.5f), metal(1.0f, 0.9f),
                                                           glass(0.2f),       glass(0.5f),       glass(0.9f)};
    // The film-estimate knob's furnace: a white diffuse base under a white film (IOR 1.4) under a
    // white coat of weight 1 (IOR 1.6), the stack whose film turns evanescent inside the lobe
    // (past its critical cosine 0.484; the base's IOR relative to the coat is inverted to 1.067 by
    // the spec's rule, so it does not reflect totally), films of 0.3-1.5 um, coat and specular
    // roughness 0.1-0.8.
    std::vector<AccuracyMaterial> white_film_materials;
    for (const float thickness : {0.3f, 0.6f, 0.9f, 1.5f})
    {
        for (const float roughness : {0.1f, 0.4f, 0.8f})
        {
            AccuracyMaterial film;
            film.base_color[0] = film.base_color[1] = film.base_color[2] = 1.0f;
            film.specular_roughness = roughness;
            film.coat_weight = 1.0f;
            film.coat_roughness = roughness;
            film.thin_film_weight = 1.0f;
            film.thin_film_thickness = thickness;
            white_film_materials.push_back(film);
        }
    }
    // CPU times of every variant in rounds (each round times every variant once, the minimum
    // over the rounds is kept): a burst of load from other processes then slows one round of
    // every variant instead of every round of one, so the settings stay comparable.
    std::vector<double> eval_times(variants.size(), std::numeric_limits<double>::infinity());
    std::vector<double> sample_times(variants.size(), std::numeric_limits<double>::infinity());
    {
        std::vector<float> scratch(3 * queries.size());
        const int rounds = options.quick ? 2 : 15;
        for (int round = 0; round < rounds; ++round)
        {
            for (std::size_t v = 0; v < variants.size(); ++v)
            {
                eval_times[v] = std::min(eval_times[v], time_ns_per_query(queries.size(), [&] {
                                             variants[v].eval(materials, queries, scratch.data());
                                         }));
                sample_times[v] = std::min(sample_times[v], time_ns_per_query(queries.size(), [&] {
                                               variants[v].sample(materials, queries, scratch.data());
                                           }));
            }
        }
    }
    progress.begin_step("CPU timings");
    for (std::size_t v = 0; v < variants.size(); ++v)
    {
        const BsdfVariant& variant = variants[v];
        std::vector<float> values(3 * queries.size());
        const double eval_ns = eval_times[v];
        const double sample_ns = sample_times[v];
        variant.eval(materials, queries, values.data());
        const double query_error = max_relative_error(values, reference);

        std::vector<double> model(grid_materials.size());
        double variance = 0.0;
        for (std::size_t i = 0; i < grid_materials.size(); ++i)
        {
            const AccuracyAlbedo albedo = variant.albedo(grid_materials[i], grid_mu[i], options.albedo_samples, 1000 + i);
            model[i] = albedo.mean[0];
            variance += albedo.variance / double(grid_materials.size());
        }
        const AlbedoErrors errors = albedo_errors(model, truth);
        double furnace = 0.0;
        for (const AccuracyMaterial& white : white_materials)
        {
            for (const float mu : grid.mu)
            {
                const AccuracyAlbedo albedo = variant.albedo(white, mu, options.albedo_samples, 77);
                furnace = std::max(furnace, std::abs(1.0 - (albedo.mean[0] + albedo.mean[1] + albedo.mean[2]) / 3.0));
            }
        }
        const std::string& knob = variant.knob;
        const std::string& setting = variant.setting;
        add(knob, setting, "albedo error vs random walk (max)", errors.max_error, "CPU ns per prepare+eval", eval_ns, true);
        add(knob, setting, "albedo error vs random walk (mean)", errors.mean_error, "CPU ns per prepare+eval", eval_ns);
        add(knob, setting, "white furnace deviation (max)", furnace, "CPU ns per prepare+sample", sample_ns);
        add(knob, setting, "per-query relative error vs shipped (max)", query_error, "CPU ns per prepare+eval", eval_ns);
        add(knob, setting, "per-query relative error vs shipped (99th percentile)",
            percentile_relative_error(values, reference), "CPU ns per prepare+eval", eval_ns);
        add(knob, setting, "per-query relative error vs shipped (median)", percentile_relative_error(values, reference, 0.5),
            "CPU ns per prepare+eval", eval_ns);
        add(knob, setting, "albedo estimator variance (mean)", variance, "CPU ns per prepare+sample", sample_ns);
        add(knob, setting, "variance x ns per sample", variance * sample_ns, "CPU ns per prepare+sample", sample_ns);
        if (!double_reference.empty())
        {
            add(knob, setting, "per-query relative error vs C++ double (median)",
                percentile_relative_error(values, double_reference, 0.5), "CPU ns per prepare+eval", eval_ns);
            add(knob, setting, "per-query relative error vs C++ double (99th percentile)",
                percentile_relative_error(values, double_reference), "CPU ns per prepare+eval", eval_ns);
        }
        if (variant.bit_identical_to_shipped)
        {
            // Array and buffer mode read the same floats with the same arithmetic
            // (slang/openpbr_lut.h): count every output whose bits differ (the test asserts 0).
            std::vector<float> samples(3 * queries.size());
            variant.sample(materials, queries, samples.data());
            std::size_t differing = 0;
            for (std::size_t i = 0; i < values.size(); ++i)
            {
                differing += std::memcmp(&values[i], &reference[i], sizeof(float)) != 0 ? 1 : 0;
                differing += std::memcmp(&samples[i], &reference_samples[i], sizeof(float)) != 0 ? 1 : 0;
            }
            add(knob, setting, "eval + sample outputs differing in bits from the array build (count)", double(differing),
                "CPU ns per prepare+eval", eval_ns);
        }
        if (variant.knob == "film estimate" || variant.knob == "shipped")
        {
            // The largest deviation from 1 of any channel's albedo over the filmed white materials
            // at view cos 1, 0.5 and 0.1, and the time of prepare + eval on the thin-film workload.
            double film_furnace = 0.0;
            for (const AccuracyMaterial& white : white_film_materials)
            {
                for (const float mu : {1.0f, 0.5f, 0.1f})
                {
                    const AccuracyAlbedo albedo = variant.albedo(white, mu, options.albedo_samples, 91);
                    for (int channel = 0; channel < 3; ++channel)
                    {
                        film_furnace = std::max(film_furnace, std::abs(1.0 - albedo.mean[channel]));
                    }
                }
            }
            std::vector<float> film_values(3 * queries.size());
            const double film_ns =
                time_ns_per_query(queries.size(), [&] { variant.eval(film_materials, queries, film_values.data()); });
            add(knob, setting, "thin-film white furnace deviation under a coat (max)", film_furnace,
                "CPU ns per prepare+eval (thin-film materials)", film_ns);
        }
        if (variant.setting.find("thin film") != std::string::npos || variant.knob == "shipped")
        {
            std::vector<float> film_values(3 * queries.size());
            const double film_ns =
                time_ns_per_query(queries.size(), [&] { variant.eval(film_materials, queries, film_values.data()); });
            add(knob, setting, "per-query relative error vs full thin film (max)",
                max_relative_error(film_values, film_reference), "CPU ns per prepare+eval (thin-film materials)", film_ns);
            add(knob, setting, "per-query relative error vs full thin film (99th percentile)",
                percentile_relative_error(film_values, film_reference), "CPU ns per prepare+eval (thin-film materials)",
                film_ns);
        }
        progress.begin_step(knob + ": " + setting);
    }

    // A baseline's three albedo-error rows: max (plotted) and mean against the random walk, max
    // against the single-scattering walk. `sink` (what the timed loop summed) enters the first
    // row's time times 0, so the compiler cannot drop the loop.
    const auto add_baseline_albedo_rows = [&](const std::string& setting, const std::vector<double>& model,
                                              const std::string& time_metric, const double time, const float sink) {
        const AlbedoErrors errors = albedo_errors(model, truth);
        add("baseline", setting, "albedo error vs random walk (max)", errors.max_error, time_metric,
            time + 0.0 * double(sink), true);
        add("baseline", setting, "albedo error vs random walk (mean)", errors.mean_error, time_metric, time);
        add("baseline", setting, "albedo error vs single-scattering walk (max)",
            albedo_errors(model, single_truth).max_error, time_metric, time);
    };

    // Baselines: bare real-time GGX (no compensation), two visibility terms.
    for (const int visibility : {OPENPBR_BASELINE_VISIBILITY_SCHLICK_SMITH, OPENPBR_BASELINE_VISIBILITY_HEIGHT_CORRELATED})
    {
        const std::string setting = visibility == OPENPBR_BASELINE_VISIBILITY_SCHLICK_SMITH
                                        ? "bare GGX, Schlick-Smith visibility"
                                        : "bare GGX, height-correlated Smith";
        std::vector<double> model(grid_materials.size());
        for (std::size_t i = 0; i < grid_materials.size(); ++i)
        {
            model[i] = baseline_albedo(grid_materials[i].base_color[0], grid_materials[i].specular_roughness, grid_mu[i],
                                       visibility, options.albedo_samples, 1000 + i)
                           .mean[0];
        }
        float sink = 0.0f;
        const double eval_ns = time_ns_per_query(queries.size(), [&] {
            for (const AccuracyQuery& query : queries)
            {
                const AccuracyMaterial& material = materials[query.material];
                const OpenPBR_BaselineGgx bsdf = openpbr_baseline_ggx_prepare(
                    glm::vec3(material.base_color[0], material.base_color[1], material.base_color[2]),
                    material.base_metalness, material.specular_roughness, visibility,
                    glm::vec3(query.view[0], query.view[1], query.view[2]));
                sink += openpbr_baseline_ggx_eval(bsdf, glm::vec3(query.light[0], query.light[1], query.light[2])).x;
            }
        });
        add_baseline_albedo_rows(setting, model, "CPU ns per prepare+eval", eval_ns, sink);
        progress.begin_step("baseline: " + setting);
    }

    // Split-sum image-based lighting: DFG tables at 4, 16, 64 and 256 samples per texel.
    const int dfg_size = 32;
    for (const std::uint32_t samples : {4u, 16u, 64u, 256u})
    {
        const std::vector<float> dfg = generate_dfg_table(dfg_size, samples, OPENPBR_BASELINE_VISIBILITY_HEIGHT_CORRELATED);
        std::vector<double> model(grid_materials.size());
        for (std::size_t i = 0; i < grid_materials.size(); ++i)
        {
            const glm::vec2 scale_bias = dfg_lookup(dfg, dfg_size, grid_mu[i], grid_materials[i].specular_roughness);
            model[i] = grid_materials[i].base_color[0] * scale_bias.x + scale_bias.y;
        }
        float sink = 0.0f;
        const double lookup_ns = time_ns_per_query(queries.size(), [&] {
            for (const AccuracyQuery& query : queries)
            {
                const AccuracyMaterial& material = materials[query.material];
                const glm::vec2 scale_bias = dfg_lookup(dfg, dfg_size, query.view[2], material.specular_roughness);
                sink += material.base_color[0] * scale_bias.x + scale_bias.y;
            }
        });
        const std::string setting = "split-sum IBL, DFG " + std::to_string(dfg_size) + "x" + std::to_string(dfg_size) +
                                    " at " + std::to_string(samples) + " samples";
        add_baseline_albedo_rows(setting, model, "CPU ns per DFG look-up", lookup_ns, sink);
        progress.begin_step("baseline: " + setting);
    }

    // Per setting that compiles to SPIR-V: the Slang compile time and SPIR-V size of the
    // conformance kernel with the setting's defines, then that kernel on lavapipe over the
    // timing workload (queries/s and its per-query error against the CPU shipped build).
    if (options.compile)
    {
        const std::filesystem::path directory =
            options.cache_directory.empty() ? std::filesystem::temp_directory_path() : options.cache_directory;
        std::filesystem::create_directories(directory);
        std::string vulkan_error;
        std::optional<VulkanContext> context = VulkanContext::create(VulkanOptions{}, &vulkan_error);
        if (!context)
        {
            std::cerr << "\nopenpbr bench accuracy: no Vulkan device (" << vulkan_error << "); lavapipe rows left out\n";
        }
        const std::uint32_t lavapipe_queries = std::max<std::uint32_t>(options.timing_queries, 1u << 16);
        const std::vector<AccuracyQuery> gpu_queries = workload_queries(materials.size(), lavapipe_queries);
        const LavapipeWorkload workload = lavapipe_workload(materials, gpu_queries);
        const LavapipeWorkload film_workload = lavapipe_workload(film_materials, gpu_queries);
        std::vector<float> gpu_reference(3 * gpu_queries.size());
        variants.front().eval(materials, gpu_queries, gpu_reference.data());
        std::vector<float> gpu_film_reference(3 * gpu_queries.size());
        variants.front().eval(film_materials, gpu_queries, gpu_film_reference.data());
        LavapipeRun buffer_run;  // the shipped kernel (float32 buffer tables) on lavapipe
        std::vector<std::uint32_t> half_words((shipped_count + 1) / 2, 0u);
        for (std::size_t i = 0; i < shipped_count; ++i)
        {
            half_words[i / 2] |= std::uint32_t(halves[i]) << (16 * (i % 2));
        }
        for (const BsdfVariant& variant : variants)
        {
            if (!variant.on_vulkan)
            {
                continue;
            }
            const std::filesystem::path spirv = directory / "accuracy_kernel.spv";
            std::filesystem::remove(spirv);
            const CompileResult result = slang_compile(options.repository_root, variant.slang_defines, spirv);
            if (!result.ok)
            {
                std::cerr << "\nopenpbr bench accuracy: the Slang compile of '" << variant.setting << "' failed (node and "
                          << (options.repository_root / "targets/slangc.mjs").string() << " needed); row left out\n";
                progress.begin_step("slang + lavapipe: " + variant.setting);
                continue;
            }
            add(variant.knob, variant.setting, "SPIR-V bytes", result.bytes, "Slang compile ms (wasm, spirv)",
                result.milliseconds);
            if (context)
            {
                const std::vector<std::byte> table = variant.table == AccuracyTable::half      ? to_bytes(half_words)
                                                     : variant.table == AccuracyTable::size_16 ? to_bytes(table_16)
                                                     : variant.table == AccuracyTable::size_64 ? to_bytes(table_64)
                                                                                               : to_bytes(shipped_lut());
                const LavapipeRun run = run_on_lavapipe(*context, spirv, table, workload);
                if (&variant == &variants.front())
                {
                    buffer_run = run;
                }
                add(variant.knob, variant.setting, "lavapipe per-query relative error vs CPU shipped (median)",
                    percentile_relative_error(run.values, gpu_reference, 0.5), "lavapipe queries/s", run.queries_per_second);
                add(variant.knob, variant.setting, "lavapipe per-query relative error vs CPU shipped (99th percentile)",
                    percentile_relative_error(run.values, gpu_reference), "lavapipe queries/s", run.queries_per_second);
                if (variant.setting.find("thin film") != std::string::npos || variant.knob == "shipped")
                {
                    // Thin film only shows on materials with a film (the CPU rows' film workload).
                    const LavapipeRun film_run = run_on_lavapipe(*context, spirv, table, film_workload);
                    add(variant.knob, variant.setting,
                        "lavapipe per-query relative error vs CPU full thin film (99th percentile)",
                        percentile_relative_error(film_run.values, gpu_film_reference),
                        "lavapipe queries/s (thin-film materials)", film_run.queries_per_second);
                }
            }
            progress.begin_step("slang + lavapipe: " + variant.setting);
        }
        // Texture storage with hardware filtering: Vulkan only (a C++ build has no texture
        // unit), compared with the shipped kernel (float32 buffer) on the same device.
        const std::filesystem::path spirv = directory / "accuracy_kernel.spv";
        const std::string texture_setting = "texture, 2D table hardware-filtered (lavapipe)";
        if (!buffer_run.values.empty())
        {
            std::filesystem::remove(spirv);
            const CompileResult texture_compile =
                slang_compile(options.repository_root, {"OPENPBR_LUT_FILTERED_2D=1"}, spirv);
            if (texture_compile.ok)
            {
                const LavapipeRun texture_run = run_on_lavapipe(*context, spirv, to_bytes(shipped_lut()), workload,
                                                                std::uint32_t(compiled_lut_layout().size_2d));
                add("table storage", texture_setting, "SPIR-V bytes", texture_compile.bytes,
                    "Slang compile ms (wasm, spirv)", texture_compile.milliseconds);
                add("table storage", texture_setting, "lavapipe per-query relative error vs lavapipe buffer (median)",
                    percentile_relative_error(texture_run.values, buffer_run.values, 0.5), "lavapipe queries/s",
                    texture_run.queries_per_second);
                add("table storage", texture_setting,
                    "lavapipe per-query relative error vs lavapipe buffer (99th percentile)",
                    percentile_relative_error(texture_run.values, buffer_run.values), "lavapipe queries/s",
                    texture_run.queries_per_second);
                add("table storage", texture_setting, "lavapipe per-query relative error vs lavapipe buffer (max)",
                    max_relative_error(texture_run.values, buffer_run.values), "lavapipe queries/s",
                    texture_run.queries_per_second);
                add("table storage", texture_setting, "lavapipe per-query relative error vs CPU shipped (99th percentile)",
                    percentile_relative_error(texture_run.values, gpu_reference), "lavapipe queries/s",
                    texture_run.queries_per_second);
                add("table storage", "float32 buffer (lavapipe)",
                    "lavapipe per-query relative error vs CPU shipped (99th percentile)",
                    percentile_relative_error(buffer_run.values, gpu_reference), "lavapipe queries/s",
                    buffer_run.queries_per_second);
            }
        }
        else
        {
            std::cerr << "\nopenpbr bench accuracy: texture storage rows left out (no Vulkan device or no Slang)\n";
        }
        progress.begin_step("slang + lavapipe: " + texture_setting);
    }
    progress.finish();
    return rows;
}

nlohmann::json accuracy_to_json(const std::vector<AccuracyRow>& rows)
{
    nlohmann::json list = nlohmann::json::array();
    for (const AccuracyRow& row : rows)
    {
        list.push_back({{"knob", row.knob},
                        {"setting", row.setting},
                        {"error_metric", row.error_metric},
                        {"error", row.error},
                        {"time_metric", row.time_metric},
                        {"time", row.time},
                        {"plotted", row.plotted}});
    }
    return nlohmann::json{{"rows", list}};
}

namespace {

std::string csv_field(const std::string& text)
{
    if (text.find_first_of(",\"\n") == std::string::npos)
    {
        return text;
    }
    std::string quoted = "\"";
    for (const char c : text)
    {
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    }
    return quoted + "\"";
}

std::string number(double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.6g", value);
    return buffer;
}

std::string xml_escape(const std::string& text)
{
    std::string escaped;
    for (const char c : text)
    {
        switch (c)
        {
        case '&': escaped += "&amp;"; break;
        case '<': escaped += "&lt;"; break;
        case '>': escaped += "&gt;"; break;
        case '"': escaped += "&quot;"; break;
        default: escaped += c;
        }
    }
    return escaped;
}

}  // namespace

std::string accuracy_to_csv(const std::vector<AccuracyRow>& rows)
{
    std::string csv = "knob,setting,error_metric,error,time_metric,time\n";
    for (const AccuracyRow& row : rows)
    {
        csv += csv_field(row.knob) + "," + csv_field(row.setting) + "," + csv_field(row.error_metric) + "," +
               number(row.error) + "," + csv_field(row.time_metric) + "," + number(row.time) + "\n";
    }
    return csv;
}

std::string accuracy_to_text(const std::vector<AccuracyRow>& rows)
{
    std::ostringstream text;
    char line[512];
    std::snprintf(line, sizeof(line), "%-16s %-44s %-46s %11s  %s\n", "knob", "setting", "error metric", "error", "time");
    text << line;
    for (const AccuracyRow& row : rows)
    {
        std::snprintf(line, sizeof(line), "%-16.16s %-44.44s %-46.46s %11.4g  %.4g %s\n", row.knob.c_str(),
                      row.setting.c_str(), row.error_metric.c_str(), row.error, row.time, row.time_metric.c_str());
        text << line;
    }
    return text.str();
}

std::vector<std::size_t> accuracy_pareto_front(const std::vector<AccuracyRow>& rows)
{
    std::vector<std::size_t> plotted;
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        if (rows[i].plotted)
        {
            plotted.push_back(i);
        }
    }
    std::sort(plotted.begin(), plotted.end(), [&](std::size_t a, std::size_t b) {
        return rows[a].time != rows[b].time ? rows[a].time < rows[b].time : rows[a].error < rows[b].error;
    });
    // Walking by increasing time, a row is on the front when it is more accurate than every
    // faster row.
    std::vector<std::size_t> front;
    double best_error = std::numeric_limits<double>::infinity();
    for (const std::size_t index : plotted)
    {
        if (rows[index].error < best_error)
        {
            front.push_back(index);
            best_error = rows[index].error;
        }
    }
    return front;
}

std::string accuracy_to_svg(const std::vector<AccuracyRow>& rows)
{
    const double width = 960.0, height = 640.0, left = 80.0, right = 330.0, top = 40.0, bottom = 60.0;
    double min_time = std::numeric_limits<double>::infinity(), max_time = 0.0;
    double min_error = std::numeric_limits<double>::infinity(), max_error = 0.0;
    for (const AccuracyRow& row : rows)
    {
        if (row.plotted)
        {
            min_time = std::min(min_time, std::max(row.time, 1e-3));
            max_time = std::max(max_time, std::max(row.time, 1e-3));
            min_error = std::min(min_error, std::max(row.error, 1e-6));
            max_error = std::max(max_error, std::max(row.error, 1e-6));
        }
    }
    if (!(max_time > 0.0))
    {
        min_time = 1.0, max_time = 10.0, min_error = 1e-3, max_error = 1.0;
    }
    // Whole decades on both axes.
    const double time_low = std::floor(std::log10(min_time)), time_high = std::ceil(std::log10(max_time) + 1e-9);
    const double error_low = std::floor(std::log10(min_error)), error_high = std::ceil(std::log10(max_error) + 1e-9);
    const double plot_width = width - left - right, plot_height = height - top - bottom;
    auto x_of = [&](double time) {
        return left + (std::log10(std::max(time, 1e-3)) - time_low) / std::max(time_high - time_low, 1.0) * plot_width;
    };
    auto y_of = [&](double error) {
        return top + (error_high - std::log10(std::max(error, 1e-6))) / std::max(error_high - error_low, 1.0) * plot_height;
    };
    const std::vector<std::string> palette = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                              "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};
    std::map<std::string, std::string> colours;
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"" << left
        << "\" y=\"22\" font-size=\"15\">OpenPBR accuracy vs time: directional albedo error "
           "(max, vs random walk) against CPU time per query</text>\n";
    for (double decade = time_low; decade <= time_high + 1e-9; decade += 1.0)
    {
        const double x = x_of(std::pow(10.0, decade));
        svg << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << top + plot_height
            << "\" stroke=\"#ddd\"/>\n<text x=\"" << x << "\" y=\"" << top + plot_height + 16
            << "\" text-anchor=\"middle\">1e" << int(decade) << " ns</text>\n";
    }
    for (double decade = error_low; decade <= error_high + 1e-9; decade += 1.0)
    {
        const double y = y_of(std::pow(10.0, decade));
        svg << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + plot_width << "\" y2=\"" << y
            << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">1e"
            << int(decade) << "</text>\n";
    }
    svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plot_width << "\" height=\"" << plot_height
        << "\" fill=\"none\" stroke=\"black\"/>\n";
    svg << "<text x=\"" << left + plot_width / 2 << "\" y=\"" << height - 18
        << "\" text-anchor=\"middle\">time per query (ns, log)</text>\n";
    svg << "<text transform=\"translate(20," << top + plot_height / 2
        << ") rotate(-90)\" text-anchor=\"middle\">max albedo error (log)</text>\n";
    // Pareto front.
    const std::vector<std::size_t> front = accuracy_pareto_front(rows);
    if (!front.empty())
    {
        svg << "<polyline fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\" points=\"";
        for (const std::size_t index : front)
        {
            svg << x_of(rows[index].time) << "," << y_of(rows[index].error) << " ";
        }
        svg << "\"/>\n";
    }
    int label = 0;
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        const AccuracyRow& row = rows[i];
        if (!row.plotted)
        {
            continue;
        }
        if (colours.find(row.knob) == colours.end())
        {
            const std::size_t next = colours.size();
            colours[row.knob] = palette[next % palette.size()];
        }
        const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
        const double x = x_of(row.time), y = y_of(row.error);
        ++label;
        svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"" << (on_front ? 6 : 4) << "\" fill=\""
            << colours[row.knob] << "\"" << (on_front ? " stroke=\"black\" stroke-width=\"1.5\"" : "") << "/>\n";
        svg << "<text x=\"" << x + 7 << "\" y=\"" << y - 5 << "\" font-size=\"9\">" << label << "</text>\n";
        svg << "<text x=\"" << width - right + 12 << "\" y=\"" << top + 12.0 * label << "\" font-size=\"9\" fill=\""
            << colours[row.knob] << "\">" << label << ". " << xml_escape(row.knob + ": " + row.setting)
            << (on_front ? " *" : "") << "</text>\n";
    }
    svg << "<text x=\"" << width - right + 12 << "\" y=\"" << top + 12.0 * (label + 2)
        << "\" font-size=\"9\">* on the Pareto front (dashed)</text>\n</svg>\n";
    return svg.str();
}

}  // namespace openpbr::host
