// Conformance runner: see conformance.h.
#include "host/checks/conformance.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "host/checks/conformance_cpu_variants.h"
#include "host/checks/execution_path.h"
#include "host/scene/features.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "host/support/files.h"
#include "host/support/stopwatch.h"
#include "slang/openpbr.h"

namespace openpbr::host {

#if !OPENPBR_CONFORMANCE_CPU_FMA_BUILT
std::vector<float> run_conformance_cpu_fma(const std::vector<float>&, const std::vector<float>&)
{
    throw std::logic_error("cpu-fma was not built (conformance_cpu_fma_unavailable_reason)");
}
std::vector<float> run_conformance_cpu_fast(const std::vector<float>&, const std::vector<float>&)
{
    throw std::logic_error("cpu-fast was not built (conformance_cpu_fma_unavailable_reason)");
}
#endif

std::string conformance_cpu_fma_unavailable_reason()
{
#if OPENPBR_CONFORMANCE_CPU_FMA_BUILT
    __builtin_cpu_init();
    return __builtin_cpu_supports("fma") ? "" : "this CPU has no FMA instructions";
#else
    return "not built: the compiler does not accept -mfma or the target is not x86-64";
#endif
}

namespace {

// Output slots compared for every query (eval and pdf) and for agreeing samples only.
constexpr int eval_slot_begin = 0;
constexpr int eval_slot_end = 7;
constexpr int sample_slot_begin = 7;
constexpr int sample_slot_end = 17;
constexpr int lobe_type_slot = 17;
constexpr int emission_slot_begin = 18;
constexpr int emission_slot_end = 21;

// Sign patterns of nudge_directions: the CPU's condition is the largest change over them.
constexpr int conformance_nudge_patterns = 4;

double relative_error(float gpu, float cpu)
{
    return std::fabs(double(gpu) - double(cpu)) / std::max(std::fabs(double(cpu)), 1e-3);
}

struct GpuBatchResult
{
    std::vector<float> results;
    DispatchTiming timing;
};

// Bindings shared by every conformance kernel: 0 tables, 1 fuzz table, 2 queries,
// 3 materials, 4 parameters, 5 results.
ComputePipelineDescription conformance_pipeline_description(const VulkanPathKernel& path,
                                                            const std::string& kernel_directory)
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

// The nine table textures, filled as slang/openpbr_lut_textures.h says (contiguous ranges of
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
    const std::uint32_t e3 = OPENPBR_LUT_3D_ETA_SIZE;
    const std::uint32_t n4 = OPENPBR_LUT_4D_SIZE;
    const std::uint32_t m4 = OPENPBR_LUT_4D_ANISOTROPY_SIZE;
    const std::uint32_t nf = OPENPBR_FUZZ_LTC_SIZE;
    return {{n2, n2, 1, false, OPENPBR_LUT_GGX_ALBEDO_OFFSET},
            {n3, n3, e3, false, OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET},
            {n3, n3, e3, false, OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET},
            {n3, n3, e3, false, OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET},
            {n4, n4, m4 * m4, false, OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET},
            {nf, nf, 1, true, OPENPBR_FUZZ_LTC_A_OFFSET},
            {nf, nf, 1, true, OPENPBR_FUZZ_LTC_B_OFFSET},
            {nf, nf, 1, true, OPENPBR_FUZZ_LTC_R_OFFSET},
            {OPENPBR_LUT_FILM_QUANTILE_SIZE, OPENPBR_LUT_FILM_SIZE, OPENPBR_LUT_FILM_CHANNEL_COUNT * OPENPBR_LUT_FILM_SIZE,
             false, OPENPBR_LUT_FILM_OFFSET}};
}

GpuBatchResult dispatch_conformance(ComputePipeline& pipeline, const std::vector<float>& queries,
                                    const std::vector<float>& materials, int repeats,
                                    const ConformanceDispatchSettings& settings = {})
{
    const std::size_t query_count = queries.size() / conformance_query_floats;

    std::vector<std::byte> lut_bytes = to_bytes(shipped_lut());
    std::vector<std::byte> fuzz_bytes = to_bytes(shipped_fuzz_ltc());
    std::vector<std::byte> query_bytes = to_bytes(queries);
    std::vector<std::byte> material_bytes = to_bytes(materials);
    std::vector<std::byte> result_bytes(query_count * conformance_result_floats * sizeof(float));
    std::vector<std::byte> parameter_bytes =
        to_bytes(std::vector<std::uint32_t>{std::uint32_t(query_count), settings.mode, 0, 0});
    std::vector<BufferBinding> buffers = {
        {2, &query_bytes, false}, {3, &material_bytes, false}, {4, &parameter_bytes, false}, {5, &result_bytes, true}};
    std::vector<std::vector<std::byte>> texture_bytes;
    if (settings.texture_tables)
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
    DispatchRequest request;
    request.groups_x = groups;
    request.repeats = repeats;
    request.device_local = settings.device_local;
    batch.timing = run(pipeline, buffers, request);
    batch.results = from_bytes<float>(result_bytes);
    return batch;
}

}  // namespace

ComputePipelineDescription conformance_pipeline_description(const std::string& path_name,
                                                            const std::string& kernel_directory)
{
    return conformance_pipeline_description(vulkan_path_kernel(path_name), kernel_directory);
}

ConformanceDispatch dispatch_conformance_pipeline(ComputePipeline& pipeline, const std::vector<float>& queries,
                                                  const std::vector<float>& materials, int repeats,
                                                  const ConformanceDispatchSettings& settings)
{
    GpuBatchResult batch = dispatch_conformance(pipeline, queries, materials, repeats, settings);
    return {std::move(batch.results), batch.timing};
}

namespace {

// The rate of a path's steady-state dispatch where it times one (Vulkan), else of its device
// time (CUDA, WebGPU), else of its whole run (the CPU paths).
double queries_per_second(const PathRun& run, std::size_t query_count)
{
    if (run.dispatch_ms > 0.0)
    {
        return double(query_count) / (run.dispatch_ms * 1e-3);
    }
    if (run.device_ns_per_query)
    {
        return 1e9 / *run.device_ns_per_query;
    }
    return run.pipeline_count == 0 && run.wall_seconds > 0.0 ? double(query_count) / run.wall_seconds : 0.0;
}

// The pooled metric: every compared slot's relative error (floor 1e-3) in one population.
void compare_pooled(ConformancePathResult& result, const std::vector<float>& queries, const std::vector<float>& gpu_results,
                    const std::vector<float>& cpu_results)
{
    const std::size_t query_count = queries.size() / conformance_query_floats;
    std::vector<double> errors;
    errors.reserve(query_count * (eval_slot_end + sample_slot_end - sample_slot_begin + 3));
    double worst = -1.0;
    for (std::size_t query = 0; query < query_count; ++query)
    {
        const float* gpu = gpu_results.data() + query * conformance_result_floats;
        const float* cpu = cpu_results.data() + query * conformance_result_floats;
        const bool lobes_agree = gpu[lobe_type_slot] == cpu[lobe_type_slot];
        auto compare = [&](int begin, int end) {
            for (int slot = begin; slot < end; ++slot)
            {
                const double error = relative_error(gpu[slot], cpu[slot]);
                errors.push_back(std::isfinite(error) ? error : 1e30);
                if (error > worst)
                {
                    worst = error;
                    std::ostringstream where;
                    where << conformance_slot_name(slot) << " of query " << query << " (material "
                          << queries[query * conformance_query_floats] << "): gpu " << gpu[slot] << ", cpu " << cpu[slot];
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
}

// One channel of the per-kind metric while it is being filled.
struct ChannelAccumulator
{
    ConformanceChannel channel;
    std::vector<double> errors;
    std::vector<double> p999_ratios;  // error / its p99.9 allowance (docs/conformance.md)
    double max_ratio = 0.0;           // largest error / its max allowance

    // A non-finite error (NaN on one side) is the worst possible value.
    static double finite_or_worst(double value)
    {
        return std::isnan(value) ? std::numeric_limits<double>::infinity() : value;
    }

    void add(double error, double p999_ratio, double max_ratio_of_value, std::size_t query, float gpu, double cpu)
    {
        const double value = finite_or_worst(error);
        errors.push_back(value);
        p999_ratios.push_back(finite_or_worst(p999_ratio));
        const double ratio = finite_or_worst(max_ratio_of_value);
        if (errors.size() == 1 || ratio > max_ratio)
        {
            max_ratio = ratio;
            std::ostringstream where;
            where << "query " << query << ": gpu " << gpu << ", cpu " << cpu << ", relative error " << value;
            channel.worst = where.str();
        }
    }

    ConformanceChannel finish()
    {
        // Selection, not a sort: 22 channels of 10^6 values per path.
        auto p999 = [](std::vector<double>& values) {
            if (values.empty())
            {
                return 0.0;
            }
            const auto rank = values.begin() + std::ptrdiff_t(0.999 * double(values.size() - 1));
            std::nth_element(values.begin(), rank, values.end());
            return *rank;
        };
        channel.count = errors.size();
        channel.max = errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end());
        channel.p999 = p999(errors);
        channel.p999_bound_ratio = p999(p999_ratios);
        channel.max_bound_ratio = max_ratio;
        return channel;
    }
};

// Angle between two directions, radians: 2 asin(|a/|a| - b/|b|| / 2) stays accurate for tiny
// angles, where acos of the dot product loses everything below about 3e-4 rad in float and
// 2e-8 in double.
double angle_between(const float* a, const float* b)
{
    const double length_a = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
    const double length_b = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
    if (!(length_a > 0.0) || !(length_b > 0.0))
    {
        return std::numeric_limits<double>::infinity();
    }
    double chord = 0.0;
    for (int axis = 0; axis < 3; ++axis)
    {
        const double difference = double(a[axis]) / length_a - double(b[axis]) / length_b;
        chord += difference * difference;
    }
    return 2.0 * std::asin(std::min(1.0, 0.5 * std::sqrt(chord)));
}

bool is_delta_lobe(float lobe_type) { return (std::uint32_t(lobe_type) & OPENPBR_LOBE_TYPE_SPECULAR) != 0u; }

// Compares one path's results with the CPU build's: the per-kind metric (docs/conformance.md)
// and the pooled one. Sampled outputs are chaotic in the last bit of the random numbers, so a
// continuous sample is checked for consistency: its weight and pdf against the CPU's eval and
// pdf at the path's own direction (the CPU kernel run again, same materials and views, with the
// light set to that direction). Delta samples (weight and pdf independent of a warp) and the
// direction (as an angle) are compared with the CPU's sample where the lobes agree.
void compare_with_cpu(ConformancePathResult& result, const std::vector<float>& queries, const std::vector<float>& materials,
                      const std::vector<float>& gpu_results, const std::vector<float>& cpu_results)
{
    const std::size_t query_count = queries.size() / conformance_query_floats;
    compare_pooled(result, queries, gpu_results, cpu_results);

    // The CPU at each continuous GPU sample's direction (slots 0-6: eval and pdf there).
    std::vector<float> at_gpu_direction_queries = queries;
    for (std::size_t query = 0; query < query_count; ++query)
    {
        const float* gpu = gpu_results.data() + query * conformance_result_floats;
        float* light = at_gpu_direction_queries.data() + query * conformance_query_floats + 4;
        if (gpu[lobe_type_slot] != 0.0f && !is_delta_lobe(gpu[lobe_type_slot]))
        {
            std::copy(gpu + sample_slot_begin, gpu + sample_slot_begin + 3, light);
        }
    }
    const std::vector<float> at_gpu_direction = run_conformance_cpu(at_gpu_direction_queries, materials);
    // The CPU's own sensitivity: the same queries with view and light moved by one ulp.
    std::vector<std::vector<float>> cpu_nudged;
    std::vector<std::vector<float>> at_gpu_direction_nudged;
    for (int pattern = 0; pattern < conformance_nudge_patterns; ++pattern)
    {
        cpu_nudged.push_back(run_conformance_cpu(nudge_directions(queries, pattern), materials));
        at_gpu_direction_nudged.push_back(
            run_conformance_cpu(nudge_directions(at_gpu_direction_queries, pattern), materials));
    }
    const ConformanceTolerances& tolerances = conformance_tolerances(result.name);

    // Channels in report order: eval.diffuse rgb (0-2), eval.specular rgb (3-5), pdf (6),
    // emission rgb (7-9), sample.consistency.pdf (10), its weight.diffuse rgb (11-13) and
    // weight.specular rgb (14-16), sample.delta.pdf (17), its weight.specular rgb (18-20),
    // sample.direction.angle (21).
    static const char* const channel_names[] = {"eval.diffuse.r",
                                                "eval.diffuse.g",
                                                "eval.diffuse.b",
                                                "eval.specular.r",
                                                "eval.specular.g",
                                                "eval.specular.b",
                                                "pdf",
                                                "emission.r",
                                                "emission.g",
                                                "emission.b",
                                                "sample.consistency.pdf",
                                                "sample.consistency.weight.diffuse.r",
                                                "sample.consistency.weight.diffuse.g",
                                                "sample.consistency.weight.diffuse.b",
                                                "sample.consistency.weight.specular.r",
                                                "sample.consistency.weight.specular.g",
                                                "sample.consistency.weight.specular.b",
                                                "sample.delta.pdf",
                                                "sample.delta.weight.specular.r",
                                                "sample.delta.weight.specular.g",
                                                "sample.delta.weight.specular.b",
                                                "sample.direction.angle"};
    constexpr int eval_diffuse = 0, eval_specular = 3, pdf_channel = 6, emission = 7, consistency_pdf = 10,
                  consistency_diffuse = 11, consistency_specular = 14, delta_pdf = 17, delta_specular = 18,
                  direction_angle = 21, channel_count = 22;
    std::vector<ChannelAccumulator> channels(channel_count);
    for (int index = 0; index < channel_count; ++index)
    {
        channels[std::size_t(index)].channel.name = channel_names[index];
        channels[std::size_t(index)].channel.angle = index == direction_angle;
        channels[std::size_t(index)].errors.reserve(query_count);
    }

    std::size_t mismatches = 0;
    for (std::size_t query = 0; query < query_count; ++query)
    {
        const float* gpu = gpu_results.data() + query * conformance_result_floats;
        const float* cpu = cpu_results.data() + query * conformance_result_floats;
        const float* cpu_there = at_gpu_direction.data() + query * conformance_result_floats;
        const std::size_t record = query * conformance_result_floats;
        // The largest change of a value over the nudged runs; `value(run)` reads it from one.
        auto largest_change = [&](double cpu_value, const auto& value) {
            double change = 0.0;
            for (int pattern = 0; pattern < conformance_nudge_patterns; ++pattern)
            {
                change = std::max(change, std::fabs(value(pattern) - cpu_value));
            }
            return change;
        };
        for (int slot = 0; slot < emission_slot_end; ++slot)
        {
            if (!std::isfinite(gpu[slot]))
            {
                ++result.nonfinite;
            }
        }
        // A value's allowance: the relative bound (of max(|cpu|, floor)), or the CPU's own change
        // under a one-ulp move of its input directions times condition_factor, the larger.
        auto relative = [&](int index, float gpu_value, double cpu_value, double change) {
            const double difference = std::fabs(double(gpu_value) - cpu_value);
            const double scale = std::max(std::fabs(cpu_value), tolerances.relative_floor);
            const double sensitivity = tolerances.condition_factor * change;
            channels[std::size_t(index)].add(
                difference / scale, difference / std::max(tolerances.relative_p999 * scale, sensitivity),
                difference / std::max(tolerances.relative_max * scale, sensitivity), query, gpu_value, cpu_value);
        };
        for (int c = 0; c < 3; ++c)
        {
            for (const int slot : {c, 3 + c, emission_slot_begin + c})
            {
                const int index = slot < 3 ? eval_diffuse + c : slot < 6 ? eval_specular + c : emission + c;
                relative(index, gpu[slot], cpu[slot], largest_change(cpu[slot], [&](int pattern) {
                             return double(cpu_nudged[std::size_t(pattern)][record + std::size_t(slot)]);
                         }));
            }
        }
        relative(pdf_channel, gpu[6], cpu[6],
                 largest_change(cpu[6], [&](int pattern) { return double(cpu_nudged[std::size_t(pattern)][record + 6]); }));

        const float gpu_lobe = gpu[lobe_type_slot];
        const bool lobes_agree = gpu_lobe == cpu[lobe_type_slot];
        mismatches += lobes_agree ? 0 : 1;
        if (gpu_lobe != 0.0f && !is_delta_lobe(gpu_lobe))
        {
            // weight = eval / pdf at the sample's direction (slang/openpbr_bsdf.h, openpbr_sample).
            const double pdf_there = cpu_there[6];
            auto ratio = [](double value, double pdf) { return pdf > 0.0 ? value / pdf : 0.0; };
            auto there = [&](int pattern, int slot) {
                return double(at_gpu_direction_nudged[std::size_t(pattern)][record + std::size_t(slot)]);
            };
            relative(consistency_pdf, gpu[16], pdf_there,
                     largest_change(pdf_there, [&](int pattern) { return there(pattern, 6); }));
            for (int c = 0; c < 3; ++c)
            {
                for (const int slot : {c, 3 + c})
                {
                    const double expected = ratio(cpu_there[slot], pdf_there);
                    relative((slot < 3 ? consistency_diffuse : consistency_specular) + c, gpu[10 + slot], expected,
                             largest_change(expected,
                                            [&](int pattern) { return ratio(there(pattern, slot), there(pattern, 6)); }));
                }
            }
        }
        if (lobes_agree && gpu_lobe != 0.0f)
        {
            const double angle = angle_between(gpu + sample_slot_begin, cpu + sample_slot_begin);
            channels[direction_angle].add(angle, angle / tolerances.angle_p999, angle / tolerances.angle_max, query,
                                          gpu[sample_slot_begin], cpu[sample_slot_begin]);
            if (is_delta_lobe(gpu_lobe))
            {
                // A nudged run whose lobe differs says nothing about this one's condition.
                auto same_lobe = [&](int slot) {
                    return [&, slot](int pattern) {
                        const float* nudged = cpu_nudged[std::size_t(pattern)].data() + record;
                        return nudged[lobe_type_slot] == gpu_lobe ? double(nudged[slot]) : double(cpu[slot]);
                    };
                };
                relative(delta_pdf, gpu[16], cpu[16], largest_change(cpu[16], same_lobe(16)));
                for (int c = 0; c < 3; ++c)
                {
                    relative(delta_specular + c, gpu[13 + c], cpu[13 + c], largest_change(cpu[13 + c], same_lobe(13 + c)));
                }
            }
        }
    }
    result.channels.clear();
    for (ChannelAccumulator& accumulator : channels)
    {
        result.channels.push_back(accumulator.finish());
    }
    result.lobe_mismatch_fraction = query_count ? double(mismatches) / double(query_count) : 0.0;
}

}  // namespace

SpecializedConformanceRun run_conformance_gpu_specialized(const std::string& path_name, VulkanContext& context,
                                                          const std::vector<float>& queries,
                                                          const std::vector<Material>& materials,
                                                          const std::string& kernel_directory,
                                                          std::optional<std::uint32_t> pipeline_mask, int repeats,
                                                          const ConformanceDispatchSettings& settings)
{
    if (pipeline_mask)
    {
        check_pipeline_supports(materials, *pipeline_mask);
    }
    const VulkanPathKernel& path = vulkan_path_kernel(path_name);
    SpecializedPipelineCache cache(context, conformance_pipeline_description(path, kernel_directory));
    const std::vector<float> packed = pack_materials(materials);
    const std::size_t query_count = queries.size() / conformance_query_floats;
    // Queries grouped by the toggle set of the pipeline that runs them.
    std::map<std::uint32_t, std::vector<std::size_t>> groups;
    for (std::size_t query = 0; query < query_count; ++query)
    {
        const std::size_t material = std::size_t(queries[query * conformance_query_floats]);
        if (material >= materials.size())
        {
            throw std::invalid_argument("query " + std::to_string(query) + " names material " + std::to_string(material) +
                                        " of " + std::to_string(materials.size()));
        }
        groups[pipeline_mask ? *pipeline_mask : required_feature_mask(materials[material])].push_back(query);
    }
    SpecializedConformanceRun run;
    run.results.assign(query_count * conformance_result_floats, 0.0f);
    for (const auto& [mask, members] : groups)
    {
        std::vector<float> group_queries(members.size() * conformance_query_floats);
        for (std::size_t i = 0; i < members.size(); ++i)
        {
            std::memcpy(&group_queries[i * conformance_query_floats], &queries[members[i] * conformance_query_floats],
                        conformance_query_floats * sizeof(float));
        }
        const std::size_t builds_before = cache.build_count();
        ComputePipeline& pipeline = cache.pipeline(mask);
        ConformanceDispatchSettings path_settings = settings;
        path_settings.texture_tables = path.texture_tables;
        const GpuBatchResult batch = dispatch_conformance(pipeline, group_queries, packed, repeats, path_settings);
        for (std::size_t i = 0; i < members.size(); ++i)
        {
            std::memcpy(&run.results[members[i] * conformance_result_floats], &batch.results[i * conformance_result_floats],
                        conformance_result_floats * sizeof(float));
        }
        SpecializedPipelineTiming timing;
        timing.mask = mask;
        timing.query_count = members.size();
        timing.built = cache.build_count() > builds_before;
        timing.create_ms = pipeline.create_ms();
        timing.first_dispatch_ms = batch.timing.first_dispatch_ms;
        timing.dispatch_ms = batch.timing.dispatch_ms;
        timing.device_dispatch_ms = batch.timing.device_dispatch_ms;
        timing.statistics = pipeline.statistics();
        run.dispatch_ms += batch.timing.dispatch_ms;
        if (batch.timing.device_dispatch_ms)
        {
            run.device_dispatch_ms = run.device_dispatch_ms.value_or(0.0) + *batch.timing.device_dispatch_ms;
        }
        run.pipelines.push_back(timing);
    }
    run.pipeline_builds = cache.build_count();
    return run;
}

std::vector<std::string> cpu_conformance_paths() { return {"cpu-fma", "cpu-fast", "cpu-ulp"}; }

std::vector<float> nudge_random_numbers(const std::vector<float>& queries)
{
    std::vector<float> nudged = queries;
    for (std::size_t record = 0; record + conformance_query_floats <= nudged.size(); record += conformance_query_floats)
    {
        for (int k = 7; k < 10; ++k)
        {
            // Up by one ulp, or down at the largest float below 1 (u stays in [0, 1)).
            float& u = nudged[record + std::size_t(k)];
            u = u < 0.99999994f ? std::nextafter(u, 1.0f) : std::nextafter(u, 0.0f);
        }
    }
    return nudged;
}

std::vector<float> nudge_directions(const std::vector<float>& queries, int pattern)
{
    // Signs per view and light component: rotations by about one ulp of angle about two
    // different axes, which normalization does not undo (moving every component away from zero
    // would mostly scale the vectors).
    static const float signs[conformance_nudge_patterns][6] = {
        {1, -1, 1, -1, 1, -1}, {1, 1, -1, -1, -1, 1}, {-1, 1, 1, 1, -1, -1}, {1, 1, 1, -1, 1, 1}};
    const float* sign = signs[std::size_t(pattern) % conformance_nudge_patterns];
    std::vector<float> nudged = queries;
    for (std::size_t record = 0; record + conformance_query_floats <= nudged.size(); record += conformance_query_floats)
    {
        for (int k = 1; k < 7; ++k)
        {
            float& component = nudged[record + std::size_t(k)];
            component = std::nextafter(component, 2.0f * sign[k - 1]);
        }
    }
    return nudged;
}

std::vector<std::string> all_conformance_paths() { return execution_path_names(true); }

std::vector<std::string> known_conformance_paths() { return execution_path_names(false); }

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
    // What OpenPBR 1.1.1 states, on every path (tests/bsdf/test_spec_1_1_1.cpp tests the same on
    // the CPU): an HDR emission colour under a coat, a tinted metal at part weight, thin-walled
    // subsurface with a radius that must have no effect.
    Material hdr_emission = default_material();
    hdr_emission.name = "HdrEmission";
    hdr_emission.inputs.emission_color = glm::vec3(4.0f, 2.0f, 1.0f);
    hdr_emission.inputs.emission_luminance = 50.0f;
    hdr_emission.inputs.coat_weight = 0.5f;
    materials.push_back(hdr_emission);
    Material weighted_metal = default_material();
    weighted_metal.name = "TintedMetalPartWeight";
    weighted_metal.inputs.base_metalness = 1.0f;
    weighted_metal.inputs.base_color = glm::vec3(0.95f, 0.64f, 0.54f);
    weighted_metal.inputs.specular_color = glm::vec3(0.4f, 0.7f, 1.0f);
    weighted_metal.inputs.specular_weight = 0.5f;
    weighted_metal.inputs.specular_roughness = 0.35f;
    materials.push_back(weighted_metal);
    Material thin_subsurface = default_material();
    thin_subsurface.name = "ThinWalledSubsurfaceRadius";
    thin_subsurface.inputs.geometry_thin_walled = true;
    thin_subsurface.inputs.subsurface_weight = 0.7f;
    thin_subsurface.inputs.subsurface_color = glm::vec3(0.8f, 0.5f, 0.3f);
    thin_subsurface.inputs.subsurface_radius = 5.0f;
    thin_subsurface.inputs.subsurface_radius_scale = glm::vec3(0.1f, 0.9f, 0.3f);
    materials.push_back(thin_subsurface);
    return materials;
}

ConformanceReport run_conformance(const std::vector<Material>& materials, const ConformanceOptions& options)
{
    ConformanceReport report;
    report.query_count = options.query_count;
    report.material_count = materials.size();
    const std::vector<float> packed = pack_materials(materials);
    const std::vector<float> queries = make_queries(options.query_count, materials.size(), options.seed);

    const Stopwatch cpu_stopwatch;
    const std::vector<float> cpu_results = run_conformance_cpu(queries, packed);
    const double cpu_seconds = cpu_stopwatch.seconds();
    report.cpu_queries_per_second = cpu_seconds > 0.0 ? double(options.query_count) / cpu_seconds : 0.0;
    for (const float value : cpu_results)
    {
        report.cpu_nonfinite += std::isfinite(value) ? 0 : 1;
    }
    if (!options.cpu_dump_path.empty())
    {
        write_float32_file(options.cpu_dump_path, cpu_results);
    }
    // Each executed path's raw results under options.dump_directory (nothing when it is empty).
    const auto dump = [&options](const std::string& name, const std::vector<float>& results) {
        if (!options.dump_directory.empty())
        {
            std::filesystem::create_directories(options.dump_directory);
            write_float32_file(std::filesystem::path(options.dump_directory) / (name + ".f32"), results);
        }
    };
    dump("cpu", cpu_results);

    const std::vector<std::string> known = all_conformance_paths();
    const std::vector<std::string> wanted = options.paths.empty() ? known : options.paths;
    // "cpu" names the reference itself, which always runs: {"cpu"} runs no other path.
    for (const std::string& name : wanted)
    {
        if (name != "cpu" && std::find(known.begin(), known.end(), name) == known.end())
        {
            std::string list;
            for (const std::string& candidate : known)
            {
                list += (list.empty() ? "" : ", ") + candidate;
            }
            throw std::invalid_argument("unknown conformance path '" + name + "' (known: cpu, " + list + ")");
        }
    }
    ExecutionPathSettings settings;
    settings.kernel_directory = options.kernel_directory;
    settings.validation = options.validation;
    settings.specialize = options.specialize;
    ExecutionPaths paths(settings);
    const PathBatch batch{queries, packed, &materials};
    // In report order; a path that cannot run here (no device, not built, a texture format the
    // device lacks) is reported as not executed with the reason, and the others still run.
    for (const std::string& name : known)
    {
        if (std::find(wanted.begin(), wanted.end(), name) == wanted.end())
        {
            continue;
        }
        ConformancePathResult result;
        result.name = name;
        try
        {
            ExecutionPath& path = paths.path(name);
            result.note = path.unavailable_reason();
            if (!result.note.empty())
            {
                report.paths.push_back(result);
                continue;
            }
            const PathRun run = path.run(batch);
            result.executed = true;
            result.note = run.device;
            result.pipeline_count = run.pipeline_count;
            result.first_dispatch_ms = run.first_dispatch_ms;
            result.device_ns_per_query = run.device_ns_per_query;
            result.queries_per_second = queries_per_second(run, options.query_count);
            result.validation_messages = run.validation_messages.size();
            if (!run.validation_messages.empty())
            {
                result.note += "; validation: " + run.validation_messages.front();
            }
            dump(name, run.results);
            compare_with_cpu(result, queries, packed, run.results, cpu_results);
        }
        catch (const std::exception& error)
        {
            result.executed = false;
            result.note = error.what();
        }
        report.paths.push_back(result);
    }
    return report;
}

const ConformanceTolerances& conformance_tolerances()
{
    static const ConformanceTolerances tolerances;
    return tolerances;
}

const ConformanceTolerances& conformance_tolerances(const std::string& path_name)
{
    // The measurements behind each bound are in conformance.h (conformance_tolerances(path)).
    static const ConformanceTolerances wgsl_math = [] {
        ConformanceTolerances tolerances;
        tolerances.relative_p999 = 5e-5;  // measured 1.5e-5: 3.4x
        tolerances.relative_max = 1e-3;   // measured 2.8e-4: 3.6x
        tolerances.angle_p999 = 1e-3;     // measured 3.2e-4 rad: 3.1x
        tolerances.angle_max = 2e-2;      // measured 5.9e-3 rad: 3.4x
        return tolerances;
    }();
    return execution_path_has_wgsl_math(path_name) ? wgsl_math : conformance_tolerances();
}

std::vector<std::string> conformance_violations(const ConformancePathResult& result)
{
    const ConformanceTolerances& tolerances = conformance_tolerances(result.name);
    std::vector<std::string> violations;
    auto check = [&](const std::string& what, double value, double bound) {
        if (!(value <= bound))
        {
            std::ostringstream line;
            line << what << " " << value << " > " << bound;
            violations.push_back(line.str());
        }
    };
    if (result.nonfinite != 0)
    {
        violations.push_back(std::to_string(result.nonfinite) + " non-finite outputs");
    }
    check("lobe mismatch fraction", result.lobe_mismatch_fraction, tolerances.lobe_mismatch_fraction);
    for (const ConformanceChannel& channel : result.channels)
    {
        // Ratios of each value's error to its allowance (ConformanceTolerances): at most 1.
        check(channel.name + " p99.9 of error / allowance", channel.p999_bound_ratio, 1.0);
        check(channel.name + " max of error / allowance (" + channel.worst + ")", channel.max_bound_ratio, 1.0);
    }
    return violations;
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
        nlohmann::json& entry = json["paths"].back();
        if (path.device_ns_per_query)
        {
            entry["device_ns_per_query"] = *path.device_ns_per_query;
        }
        entry["pooled"] = {{"max_rel_err", path.max_relative_error}, {"p999_rel_err", path.p999_relative_error}};
        nlohmann::json channels = nlohmann::json::object();
        for (const ConformanceChannel& channel : path.channels)
        {
            channels[channel.name] = {{"unit", channel.angle ? "radians" : "relative"},
                                      {"count", channel.count},
                                      {"max", channel.max},
                                      {"p999", channel.p999},
                                      {"p999_bound_ratio", channel.p999_bound_ratio},
                                      {"max_bound_ratio", channel.max_bound_ratio},
                                      {"worst", channel.worst}};
        }
        entry["channels"] = channels;
        const ConformanceTolerances& bounds = conformance_tolerances(path.name);
        entry["bounds"] = {{"relative_p999", bounds.relative_p999},
                           {"relative_max", bounds.relative_max},
                           {"angle_p999_radians", bounds.angle_p999},
                           {"angle_max_radians", bounds.angle_max}};
        const std::vector<std::string> violations = conformance_violations(path);
        entry["passes"] = path.executed && violations.empty();
        entry["violations"] = violations;
    }
    const ConformanceTolerances& tolerances = conformance_tolerances();
    json["tolerances"] = {{"relative_p999", tolerances.relative_p999},
                          {"relative_max", tolerances.relative_max},
                          {"relative_floor", tolerances.relative_floor},
                          {"angle_p999_radians", tolerances.angle_p999},
                          {"angle_max_radians", tolerances.angle_max},
                          {"condition_factor", tolerances.condition_factor},
                          {"lobe_mismatch_fraction", tolerances.lobe_mismatch_fraction}};
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
        // The verdict and the per-kind figures it is made from lead each path; the pooled figure
        // (one population of every slot's relative error, the metric before docs/conformance.md
        // "The per-kind metric") comes last and is labelled as the old metric, because its
        // maximum grows with the batch and read as a failure against the 1e-3 bound.
        double relative_max = 0.0, relative_p999 = 0.0, angle_max = 0.0, angle_p999 = 0.0;
        for (const ConformanceChannel& channel : path.channels)
        {
            (channel.angle ? angle_max : relative_max) = std::max(channel.angle ? angle_max : relative_max, channel.max);
            (channel.angle ? angle_p999 : relative_p999) =
                std::max(channel.angle ? angle_p999 : relative_p999, channel.p999);
        }
        const std::vector<std::string> violations = conformance_violations(path);
        text << "  " << path.name << ": " << (violations.empty() ? "passes" : "FAILS")
             << "; per kind: eval/pdf/consistency worst channel max " << relative_max << ", p99.9 " << relative_p999
             << "; direction angle max " << angle_max << " rad, p99.9 " << angle_p999 << " rad\n";
        for (const std::string& violation : violations)
        {
            text << "      " << violation << "\n";
        }
        text << "    " << path.note << ": non-finite " << path.nonfinite << ", lobe mismatch "
             << 100.0 * path.lobe_mismatch_fraction << " %, " << std::lround(path.queries_per_second)
             << " queries/s, first dispatch " << path.first_dispatch_ms << " ms, " << path.pipeline_count
             << (path.pipeline_count == 1 ? " pipeline\n" : " pipelines\n");
        if (path.device_ns_per_query)
        {
            text << "    device time " << *path.device_ns_per_query << " ns/query\n";
        }
        text << "    old metric (pooled, not the verdict): max rel err " << path.max_relative_error << ", p99.9 "
             << path.p999_relative_error << ", worst: " << path.worst_output << "\n";
    }
    return text.str();
}

}  // namespace openpbr::host
