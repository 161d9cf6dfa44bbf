// layering_accuracy.cpp - see layering_accuracy.h.
#include "host/studies/layering_accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "host/scene/material_library.h"
#include "host/support/directional_albedo.h"
#include "host/support/progress.h"
#include "host/support/random.h"
#include "host/support/stopwatch.h"
#include "slang/openpbr.h"

namespace openpbr::host {
namespace {

constexpr double pi = 3.14159265358979323846;

double luminance(const LayeredColor& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// The model's estimates at one view: albedo (R + T), reflection, and bin sums of the weights.
struct ModelEstimate
{
    LayeredColor albedo{}, albedo_error{}, reflection{};
    std::vector<LayeredColor> bins, bin_errors;  // bin averages of f |cos| and their standard errors
};

ModelEstimate estimate_model(const OpenPBR_ResolvedInputs& inputs, double mu, const LayeredGrid& grid, std::uint64_t samples,
                             std::uint64_t seed)
{
    const glm::vec3 view(float(std::sqrt(std::max(0.0, 1.0 - mu * mu))), 0.0f, float(mu));
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
    const std::size_t bin_count = std::size_t(grid.bin_count());
    std::vector<LayeredColor> sums(bin_count, LayeredColor{}), squares(bin_count, LayeredColor{});
    LayeredColor reflection{};
    SplitMix64 random{splitmix64(seed)};
    const DirectionalAlbedo albedo = estimate_directional_albedo(samples, [&](std::uint64_t) {
        const glm::vec3 u(unit_float_from_bits(random.next_bits()), unit_float_from_bits(random.next_bits()),
                          unit_float_from_bits(random.next_bits()));
        const OpenPBR_BsdfSample drawn = openpbr_sample(bsdf, u);
        const glm::vec3 weight = drawn.pdf > 0.0f ? drawn.weight.diffuse + drawn.weight.specular : glm::vec3(0.0f);
        if (drawn.pdf > 0.0f)
        {
            const int bin = grid.bin_of(glm::dvec3(drawn.direction));
            for (std::size_t c = 0; c < 3; ++c)
            {
                const double w = double(weight[int(c)]);
                if (bin >= 0)
                {
                    sums[std::size_t(bin)][c] += w;
                    squares[std::size_t(bin)][c] += w * w;
                }
                reflection[c] += drawn.direction.z > 0.0f ? w : 0.0;
            }
        }
        return weight;
    });
    ModelEstimate estimate;
    const double n = double(samples);
    const double inverse_solid_angle = 1.0 / grid.bin_solid_angle();
    estimate.bins.assign(bin_count, LayeredColor{});
    estimate.bin_errors.assign(bin_count, LayeredColor{});
    for (std::size_t c = 0; c < 3; ++c)
    {
        estimate.albedo[c] = albedo.mean[c];
        estimate.albedo_error[c] = albedo.standard_error[c];
        estimate.reflection[c] = reflection[c] / n;
        for (std::size_t b = 0; b < bin_count; ++b)
        {
            const double mean = sums[b][c] / n;
            const double variance = std::max(squares[b][c] / n - mean * mean, 0.0) / std::max(n - 1.0, 1.0);
            estimate.bins[b][c] = mean * inverse_solid_angle;
            estimate.bin_errors[b][c] = std::sqrt(variance) * inverse_solid_angle;
        }
    }
    return estimate;
}

// ns per query of prepare + eval and of prepare + sample at view cosine mu: the thread's CPU time,
// the best of five batches of `queries` (light directions uniform on the sphere).
std::array<double, 2> time_model(const OpenPBR_ResolvedInputs& inputs, double mu, std::uint32_t queries, std::uint64_t seed)
{
    const glm::vec3 view(float(std::sqrt(std::max(0.0, 1.0 - mu * mu))), 0.0f, float(mu));
    SplitMix64 random{splitmix64(seed ^ 0x7157ull)};
    std::vector<glm::vec3> lights(queries), us(queries);
    for (std::uint32_t i = 0; i < queries; ++i)
    {
        const double z = 2.0 * random.next_double() - 1.0;
        const double phi = 2.0 * pi * random.next_double();
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        lights[i] = glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
        us[i] = glm::vec3(unit_float_from_bits(random.next_bits()), unit_float_from_bits(random.next_bits()),
                          unit_float_from_bits(random.next_bits()));
    }
    std::array<double, 2> best{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    volatile float sink = 0.0f;
    for (int round = 0; round < 5; ++round)
    {
        const ThreadCpuStopwatch eval_watch;
        float eval_sum = 0.0f;
        for (std::uint32_t i = 0; i < queries; ++i)
        {
            const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
            const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, lights[i]);
            eval_sum += value.diffuse.y + value.specular.y;
        }
        best[0] = std::min(best[0], eval_watch.seconds() * 1e9 / queries);
        const ThreadCpuStopwatch sample_watch;
        float sample_sum = 0.0f;
        for (std::uint32_t i = 0; i < queries; ++i)
        {
            const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
            const OpenPBR_BsdfSample drawn = openpbr_sample(bsdf, us[i]);
            sample_sum += drawn.weight.diffuse.y + drawn.weight.specular.y;
        }
        best[1] = std::min(best[1], sample_watch.seconds() * 1e9 / queries);
        sink = sink + eval_sum + sample_sum;
    }
    return best;
}

// Total-variation distance of the two binned energy distributions and its noise floor.
std::array<double, 2> shape_distance(const ModelEstimate& model, const LayeredEstimate& reference)
{
    double model_total = 0.0;
    double reference_total = 0.0;
    for (std::size_t b = 0; b < model.bins.size(); ++b)
    {
        model_total += std::max(luminance(model.bins[b]), 0.0);
        reference_total += std::max(luminance(reference.bins[b]), 0.0);
    }
    if (!(model_total > 0.0) || !(reference_total > 0.0))
    {
        return {model_total > 0.0 || reference_total > 0.0 ? 1.0 : 0.0, 0.0};
    }
    double distance = 0.0;
    double noise = 0.0;
    for (std::size_t b = 0; b < model.bins.size(); ++b)
    {
        const double p_model = std::max(luminance(model.bins[b]), 0.0) / model_total;
        const double p_reference = std::max(luminance(reference.bins[b]), 0.0) / reference_total;
        distance += std::abs(p_model - p_reference);
        const double sigma_model = luminance(model.bin_errors[b]) / model_total;
        const double sigma_reference = luminance(reference.bin_errors[b]) / reference_total;
        noise += std::sqrt(2.0 / pi) * std::hypot(sigma_model, sigma_reference);
    }
    return {0.5 * distance, 0.5 * noise};
}

LayeringRow study_one(const LayeringMaterial& material, const LayeredMaterial& layered, double mu,
                      const LayeringOptions& options, std::uint64_t seed)
{
    LayeringRow row;
    row.material = material.name;
    row.group = material.group;
    row.stack = layered.description;
    row.view_cosine = mu;
    OpenPBR_ResolvedInputs model_inputs = material.inputs;
    if (model_inputs.coat_weight > 0.0f && model_inputs.coat_darkening != 1.0f)
    {
        char note[96];
        std::snprintf(note, sizeof(note), "coat_darkening %.3g -> 1 (the physical setting)",
                      double(model_inputs.coat_darkening));
        row.note = note;
        model_inputs.coat_darkening = 1.0f;
    }
    const ModelEstimate model = estimate_model(model_inputs, mu, options.grid, options.model_samples, seed);
    const LayeredEstimate reference = estimate_layered(layered, mu, options.grid, options.reference_paths, seed ^ 0x5eedull);
    const std::array<double, 2> times = time_model(model_inputs, mu, options.timing_queries, seed);
    row.model_albedo = model.albedo;
    row.model_standard_error = model.albedo_error;
    row.model_reflection = model.reflection;
    row.reference_albedo = reference.albedo;
    row.reference_standard_error = reference.albedo_error;
    row.reference_reflection = reference.reflected;
    row.reference_reflection_error = reference.reflected_error;
    for (std::size_t c = 0; c < 3; ++c)
    {
        const double error = std::abs(model.albedo[c] - reference.albedo[c]);
        if (error >= row.albedo_error)
        {
            const double combined = std::hypot(reference.albedo_error[c], model.albedo_error[c]);
            row.albedo_error = error;
            // Standard errors floored at 1e-6: an exact estimate (every weight the same, e.g. a
            // smooth dielectric) still carries the float rounding of the model's weights.
            row.albedo_error_sigmas = error / std::max(combined, 1e-6);
        }
        row.reflection_error = std::max(row.reflection_error, std::abs(model.reflection[c] - reference.reflected[c]));
    }
    const std::array<double, 2> shape = shape_distance(model, reference);
    row.shape_error = shape[0];
    row.shape_noise = shape[1];
    row.model_ns = times[0];
    row.model_sample_ns = times[1];
    row.reference_paths = reference.paths;
    row.capped_paths = reference.capped;
    row.reference_ns = reference.cpu_seconds * 1e9 / double(std::max<std::uint64_t>(reference.paths, 1));
    const double ratio = reference.luminance_error / options.target_standard_error;
    row.reference_estimate_ms = row.reference_ns * double(reference.paths) * ratio * ratio * 1e-6;
    return row;
}

LayeringMaterial grid_material(const std::string& base, const std::string& variation)
{
    LayeringMaterial material;
    material.group = "grid";
    material.name = base + (variation.empty() ? "" : ", " + variation);
    OpenPBR_ResolvedInputs& in = material.inputs;
    in = openpbr_make_default_resolved_inputs();
    if (base == "metal")
    {
        in.base_metalness = 1.0f;
        in.base_color = glm::vec3(0.95f, 0.64f, 0.54f);
    }
    else if (base == "glossy-diffuse")
    {
        in.base_color = glm::vec3(0.8f, 0.35f, 0.1f);
    }
    else
    {
        in.transmission_weight = 1.0f;
        in.specular_roughness = 0.2f;
    }
    return material;
}

}  // namespace

std::vector<LayeringMaterial> layering_materials_from_files(const std::vector<std::string>& files)
{
    std::vector<LayeringMaterial> materials;
    for (const std::string& file : files)
    {
        for (const Material& loaded : load_materialx_file(file))
        {
            materials.push_back({loaded.name, "bundled", loaded.inputs});
        }
    }
    return materials;
}

std::vector<LayeringMaterial> layering_materials_from_directory(const std::string& directory)
{
    std::vector<LayeringMaterial> materials;
    for (const Material& loaded : load_material_directory(directory))
    {
        materials.push_back({loaded.name, "bundled", loaded.inputs});
    }
    return materials;
}

std::vector<LayeringMaterial> layering_grid_materials()
{
    std::vector<LayeringMaterial> materials;
    for (const std::string base : {"metal", "glossy-diffuse", "glass"})
    {
        // The centre coat and its variations, one axis at a time.
        const auto coated = [&](const std::string& variation, auto&& change) {
            LayeringMaterial material = grid_material(base, variation.empty() ? "coat" : "coat " + variation);
            material.inputs.coat_weight = 1.0f;
            material.inputs.coat_ior = 1.6f;
            material.inputs.coat_roughness = 0.1f;
            change(material.inputs);
            materials.push_back(material);
        };
        coated("", [](OpenPBR_ResolvedInputs&) {});
        coated("weight 0", [](OpenPBR_ResolvedInputs& in) { in.coat_weight = 0.0f; });
        coated("weight 0.5", [](OpenPBR_ResolvedInputs& in) { in.coat_weight = 0.5f; });
        coated("IOR 1.3", [](OpenPBR_ResolvedInputs& in) { in.coat_ior = 1.3f; });
        coated("IOR 2", [](OpenPBR_ResolvedInputs& in) { in.coat_ior = 2.0f; });
        coated("roughness 0", [](OpenPBR_ResolvedInputs& in) { in.coat_roughness = 0.0f; });
        coated("roughness 0.4", [](OpenPBR_ResolvedInputs& in) { in.coat_roughness = 0.4f; });
        coated("roughness 0.8", [](OpenPBR_ResolvedInputs& in) { in.coat_roughness = 0.8f; });
        coated("colour 0.9 0.6 0.3", [](OpenPBR_ResolvedInputs& in) { in.coat_color = glm::vec3(0.9f, 0.6f, 0.3f); });
        coated("+ fuzz", [](OpenPBR_ResolvedInputs& in) { in.fuzz_weight = 1.0f; });
        coated("+ film", [](OpenPBR_ResolvedInputs& in) {
            in.thin_film_weight = 1.0f;
            in.thin_film_thickness = 0.4f;
        });
        LayeringMaterial fuzz = grid_material(base, "fuzz");
        fuzz.inputs.fuzz_weight = 1.0f;
        materials.push_back(fuzz);
        LayeringMaterial film = grid_material(base, "film");
        film.inputs.thin_film_weight = 1.0f;
        film.inputs.thin_film_thickness = 0.4f;
        materials.push_back(film);
    }
    return materials;
}

std::vector<LayeringRow> run_layering_study(const std::vector<LayeringMaterial>& materials, const LayeringOptions& options)
{
    if (options.view_cosines.empty())
    {
        throw std::invalid_argument("accuracy layering: no view cosines");
    }
    for (const double mu : options.view_cosines)
    {
        if (!(mu > 0.0 && mu <= 1.0))
        {
            throw std::invalid_argument("accuracy layering: view cosines must be in (0, 1], got " + std::to_string(mu));
        }
    }
    std::unique_ptr<tbb::global_control> limit;
    if (options.threads > 0)
    {
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      std::size_t(options.threads));
    }
    const std::size_t views = options.view_cosines.size();
    ProgressReporter progress(materials.size() * (views + 1), options.progress, "layering");
    // The stacks first (each glossy-diffuse one walks its calibration), then every view.
    std::vector<LayeredMaterial> layered(materials.size());
    tbb::parallel_for(std::size_t(0), materials.size(), [&](std::size_t i) {
        LayeredBuildOptions build;
        build.seed = splitmix64(options.seed ^ (0xb11dull + i));
        layered[i] = layered_material_from_inputs(materials[i].inputs, build);
        progress.advance();
    });
    std::vector<LayeringRow> rows(materials.size() * views);
    tbb::parallel_for(std::size_t(0), rows.size(), [&](std::size_t task) {
        const std::size_t m = task / views;
        const std::size_t v = task % views;
        rows[task] = study_one(materials[m], layered[m], options.view_cosines[v], options,
                               splitmix64(options.seed * 0x2545f4914f6cdd1dull + task));
        progress.advance();
    });
    progress.finish();
    return rows;
}

namespace {

// Six significant digits: beyond every standard error here, and a third of the file's size.
double rounded(double value)
{
    if (!std::isfinite(value) || value == 0.0)
    {
        return value;
    }
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", value);
    return std::strtod(text, nullptr);
}

nlohmann::json color_json(const LayeredColor& c)
{
    return nlohmann::json::array({rounded(c[0]), rounded(c[1]), rounded(c[2])});
}

double median(std::vector<double> values)
{
    if (values.empty())
    {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// Per material: the worst view for the albedo and for the shape, and the mean times.
struct MaterialSummary
{
    std::string material;
    std::string group;
    std::string stack;
    double albedo_error = -1.0;
    double albedo_view = 0.0;
    double albedo_sigmas = 0.0;
    double shape_error = -1.0;
    double shape_view = 0.0;
    double shape_noise = 0.0;
    double model_ns = 0.0;
    double reference_ns = 0.0;
    double reference_estimate_ms = 0.0;
    int views = 0;
};

std::vector<MaterialSummary> summarize(const std::vector<LayeringRow>& rows)
{
    std::vector<MaterialSummary> summaries;
    std::map<std::string, std::size_t> index;
    for (const LayeringRow& row : rows)
    {
        const std::string key = row.group + "/" + row.material;
        if (!index.count(key))
        {
            index[key] = summaries.size();
            summaries.push_back({row.material, row.group, row.stack});
        }
        MaterialSummary& summary = summaries[index[key]];
        if (row.albedo_error > summary.albedo_error)
        {
            summary.albedo_error = row.albedo_error;
            summary.albedo_view = row.view_cosine;
            summary.albedo_sigmas = row.albedo_error_sigmas;
        }
        if (row.shape_error > summary.shape_error)
        {
            summary.shape_error = row.shape_error;
            summary.shape_view = row.view_cosine;
            summary.shape_noise = row.shape_noise;
        }
        summary.model_ns += row.model_ns;
        summary.reference_ns += row.reference_ns;
        summary.reference_estimate_ms += row.reference_estimate_ms;
        ++summary.views;
    }
    for (MaterialSummary& summary : summaries)
    {
        summary.model_ns /= summary.views;
        summary.reference_ns /= summary.views;
        summary.reference_estimate_ms /= summary.views;
    }
    std::stable_sort(summaries.begin(), summaries.end(), [](const MaterialSummary& a, const MaterialSummary& b) {
        return a.group != b.group ? a.group < b.group : a.albedo_error > b.albedo_error;
    });
    return summaries;
}

}  // namespace

nlohmann::json layering_to_json(const std::vector<LayeringRow>& rows, const LayeringOptions& options, double seconds)
{
    nlohmann::json document;
    nlohmann::json& list = document["rows"];
    list = nlohmann::json::array();
    std::vector<double> model_ns, reference_ns, estimate_ms;
    for (const LayeringRow& row : rows)
    {
        list.push_back({{"material", row.material},
                        {"group", row.group},
                        {"stack", row.stack},
                        {"note", row.note},
                        {"view_cosine", row.view_cosine},
                        {"model_albedo", color_json(row.model_albedo)},
                        {"model_standard_error", color_json(row.model_standard_error)},
                        {"reference_albedo", color_json(row.reference_albedo)},
                        {"reference_standard_error", color_json(row.reference_standard_error)},
                        {"model_reflection", color_json(row.model_reflection)},
                        {"reference_reflection", color_json(row.reference_reflection)},
                        {"reference_reflection_standard_error", color_json(row.reference_reflection_error)},
                        {"albedo_error", rounded(row.albedo_error)},
                        {"albedo_error_sigmas", rounded(row.albedo_error_sigmas)},
                        {"reflection_error", rounded(row.reflection_error)},
                        {"shape_error", rounded(row.shape_error)},
                        {"shape_noise", rounded(row.shape_noise)},
                        {"model_ns", rounded(row.model_ns)},
                        {"model_sample_ns", rounded(row.model_sample_ns)},
                        {"reference_ns", rounded(row.reference_ns)},
                        {"reference_estimate_ms", rounded(row.reference_estimate_ms)},
                        {"reference_paths", row.reference_paths},
                        {"capped_paths", row.capped_paths}});
        model_ns.push_back(row.model_ns);
        reference_ns.push_back(row.reference_ns);
        estimate_ms.push_back(row.reference_estimate_ms);
    }
    nlohmann::json& summary = document["summary"];
    summary["what"] = "the shipped BSDF's layering against the layered ground truth, per material and view cosine "
                      "(docs/layering-accuracy.md, host/studies/layering_accuracy.h)";
    summary["albedo_error"] =
        "max over channels of |model - reference| of the directional albedo (reflection + transmission)";
    summary["shape_error"] = "total-variation distance of the luminance of f |cos| over the grid's bins, each "
                             "distribution normalised (0: same shape, 1: disjoint)";
    summary["settings"] = {{"view_cosines", options.view_cosines},
                           {"reference_paths", options.reference_paths},
                           {"model_samples", options.model_samples},
                           {"grid_resolution", options.grid.resolution},
                           {"target_standard_error", options.target_standard_error},
                           {"seed", options.seed}};
    summary["seconds"] = rounded(seconds);
    summary["rows"] = rows.size();
    summary["median_model_ns"] = rounded(median(model_ns));
    summary["median_reference_ns_per_path"] = rounded(median(reference_ns));
    summary["median_reference_estimate_ms"] = rounded(median(estimate_ms));
    nlohmann::json& materials = summary["materials"];
    materials = nlohmann::json::array();
    for (const MaterialSummary& entry : summarize(rows))
    {
        materials.push_back({{"material", entry.material},
                             {"group", entry.group},
                             {"stack", entry.stack},
                             {"max_albedo_error", rounded(entry.albedo_error)},
                             {"max_albedo_error_view_cosine", entry.albedo_view},
                             {"max_albedo_error_sigmas", rounded(entry.albedo_sigmas)},
                             {"max_shape_error", rounded(entry.shape_error)},
                             {"max_shape_error_view_cosine", entry.shape_view},
                             {"max_shape_error_noise", rounded(entry.shape_noise)},
                             {"model_ns", rounded(entry.model_ns)},
                             {"reference_ns_per_path", rounded(entry.reference_ns)},
                             {"reference_estimate_ms", rounded(entry.reference_estimate_ms)}});
    }
    return document;
}

std::string layering_json_text(const nlohmann::json& document)
{
    std::string text = "{\n  \"rows\": [\n";
    const nlohmann::json& rows = document.at("rows");
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        text += "    " + rows[i].dump() + (i + 1 < rows.size() ? ",\n" : "\n");
    }
    text += "  ],\n  \"summary\": " + document.at("summary").dump(2) + "\n}\n";
    return text;
}

std::string layering_to_text(const std::vector<LayeringRow>& rows)
{
    std::ostringstream text;
    char line[512];
    std::snprintf(line, sizeof(line), "%-34s %-6s %9s %5s %6s %9s %5s %8s %9s %10s\n", "material", "group", "albedo_err",
                  "at_mu", "sigmas", "shape_err", "at_mu", "model_ns", "ref_ns/path", "ref_ms/est");
    text << line;
    for (const MaterialSummary& entry : summarize(rows))
    {
        std::snprintf(line, sizeof(line), "%-34.34s %-6s %9.4f %5.2f %6.1f %9.4f %5.2f %8.0f %9.0f %10.1f\n",
                      entry.material.c_str(), entry.group.c_str(), entry.albedo_error, entry.albedo_view,
                      entry.albedo_sigmas, entry.shape_error, entry.shape_view, entry.model_ns, entry.reference_ns,
                      entry.reference_estimate_ms);
        text << line;
    }
    return text.str();
}

}  // namespace openpbr::host
