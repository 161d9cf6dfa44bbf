// accuracy_floors.cpp - the model floors of the accuracy study (host/studies/accuracy_internal.h):
// the compensation model and real-time baselines against the microsurface random walk, and the
// layering model against the layered ground truth read from `openpbr accuracy layering`'s JSON.
#include <algorithm>
#include <cmath>
#include <limits>

#include "host/scene/material_packing.h"
#include "host/studies/accuracy_internal.h"
#include "host/support/directional_albedo.h"
#include "host/support/files.h"
#include "host/support/stopwatch.h"
#include "host/tables/microsurface.h"
#include "slang/baselines/openpbr_baseline_ggx.h"
#include "slang/openpbr.h"

namespace openpbr::host {

std::vector<float> generate_dfg_table(const int size, const std::uint32_t samples, const int visibility)
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

namespace accuracy {
namespace {

// A point of the floor's grid: a Schlick conductor (base_color = F0, specular_color 1, so
// OpenPBR's F82 curve is Schlick's; F0 stands in for the IOR axis, the compensation being the
// same for every Fresnel) at a roughness and view cosine.
struct FloorPoint
{
    float f0;
    float roughness;
    float mu;
};

std::vector<FloorPoint> floor_grid(const bool quick)
{
    const std::vector<float> f0 = quick ? std::vector<float>{1.0f, 0.5f} : std::vector<float>{1.0f, 0.9f, 0.5f};
    const std::vector<float> roughness =
        quick ? std::vector<float>{0.3f, 0.7f} : std::vector<float>{0.1f, 0.3f, 0.5f, 0.7f, 0.9f};
    const std::vector<float> mu =
        quick ? std::vector<float>{0.2f, 0.6f, 1.0f} : std::vector<float>{0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
    std::vector<FloorPoint> grid;
    for (const float f : f0)
    {
        for (const float r : roughness)
        {
            for (const float m : mu)
            {
                grid.push_back({f, r, m});
            }
        }
    }
    return grid;
}

// The random walk of every grid point (all orders), cached; its standard errors beside.
std::vector<MicrosurfaceAlbedo> walk_albedos(const std::vector<FloorPoint>& grid, const AccuracyOptions& options)
{
    MicrosurfaceCache cache(options.cache_directory.empty() ? std::filesystem::path()
                                                            : options.cache_directory / "microsurface_walks.json");
    std::vector<MicrosurfaceQuery> queries;
    for (const FloorPoint& point : grid)
    {
        MicrosurfaceQuery query;
        query.material.kind = point.f0 >= 1.0f ? MicrosurfaceKind::conductor_white : MicrosurfaceKind::conductor_schlick;
        query.material.alpha = double(point.roughness) * double(point.roughness);
        query.material.f0 = point.f0;
        query.mu = point.mu;
        query.max_order = 0;
        query.paths = options.walk_paths;
        query.seed = queries.size() + 1;
        queries.push_back(query);
    }
    const std::vector<MicrosurfaceAlbedo> albedos = cache.albedos(queries);
    cache.save();
    return albedos;
}

// The baseline GGX's albedo by the study's estimator (ShiftedR3Sequence, as the variants').
double baseline_albedo(const FloorPoint& point, const int visibility, const std::uint32_t samples, const std::uint64_t seed)
{
    const glm::vec3 view(std::sqrt(std::max(0.0f, 1.0f - point.mu * point.mu)), 0.0f, point.mu);
    const OpenPBR_BaselineGgx bsdf =
        openpbr_baseline_ggx_prepare(glm::vec3(point.f0), 1.0f, point.roughness, visibility, view);
    const ShiftedR3Sequence sequence(seed);
    const DirectionalAlbedo estimate = estimate_directional_albedo(samples, [&](const std::uint64_t s) {
        const std::array<float, 3> u = sequence.point(s);
        const glm::vec4 drawn = openpbr_baseline_ggx_sample(bsdf, glm::vec3(u[0], u[1], u[2]));
        const float weight = drawn.w > 0.0f ? openpbr_baseline_ggx_eval(bsdf, glm::vec3(drawn)).x / drawn.w : 0.0f;
        return std::array<float, 3>{weight, weight, weight};
    });
    return estimate.mean[0];
}

// Bilinear look-up of the DFG table at (n.v, roughness).
glm::vec2 dfg_lookup(const std::vector<float>& table, const int size, const float n_dot_v, const float roughness)
{
    const float fx = glm::clamp(n_dot_v, 0.0f, 1.0f) * float(size - 1);
    const float fy = glm::clamp(roughness, 0.0f, 1.0f) * float(size - 1);
    const int x0 = std::min(int(fx), size - 2);
    const int y0 = std::min(int(fy), size - 2);
    const float tx = fx - float(x0);
    const float ty = fy - float(y0);
    const auto at = [&](const int x, const int y) {
        const std::size_t index = 2 * (std::size_t(y) * std::size_t(size) + std::size_t(x));
        return glm::vec2(table[index], table[index + 1]);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
}

// Best of three runs of `run` over `count` queries, in ns per query.
template <typename Function> double time_ns_per_query(const std::size_t count, Function run)
{
    double best = std::numeric_limits<double>::infinity();
    for (int repeat = 0; repeat < 3; ++repeat)
    {
        const Stopwatch stopwatch;
        run();
        best = std::min(best, stopwatch.seconds() * 1e9 / double(count));
    }
    return best;
}

// The floor row of a model's albedos: the largest |A - A_walk| and the walk's standard error there.
AccuracyFloorRow floor_row(const std::string& setting, const std::vector<double>& model,
                           const std::vector<MicrosurfaceAlbedo>& walk, const double time_ns, const std::string& time_metric)
{
    AccuracyFloorRow row{setting, 0.0, 0.0, time_ns, time_metric};
    for (std::size_t i = 0; i < model.size(); ++i)
    {
        const double error = std::abs(model[i] - walk[i].reflected);
        if (error > row.error)
        {
            row.error = error;
            row.error_uncertainty = walk[i].reflected_error;
        }
    }
    return row;
}

// The real-time baselines' rows: bare GGX with either visibility term, split-sum DFG tables.
void add_baseline_rows(AccuracyFloor& floor, const std::vector<FloorPoint>& grid,
                       const std::vector<MicrosurfaceAlbedo>& walk, const StudyContext& context)
{
    const std::vector<AccuracyQuery>& queries = context.general.queries;
    for (const int visibility : {OPENPBR_BASELINE_VISIBILITY_SCHLICK_SMITH, OPENPBR_BASELINE_VISIBILITY_HEIGHT_CORRELATED})
    {
        std::vector<double> model;
        for (std::size_t i = 0; i < grid.size(); ++i)
        {
            model.push_back(baseline_albedo(grid[i], visibility, context.options.albedo_samples, 1000 + i));
        }
        float sink = 0.0f;
        const double ns = time_ns_per_query(queries.size(), [&] {
            for (const AccuracyQuery& query : queries)
            {
                const OpenPBR_BaselineGgx bsdf =
                    openpbr_baseline_ggx_prepare(glm::vec3(0.9f), 1.0f, 0.1f + 0.8f * query.u[0], visibility,
                                                 glm::vec3(query.view[0], query.view[1], query.view[2]));
                sink += openpbr_baseline_ggx_eval(bsdf, glm::vec3(query.light[0], query.light[1], query.light[2])).x;
            }
        });
        const std::string name = visibility == OPENPBR_BASELINE_VISIBILITY_SCHLICK_SMITH
                                     ? "bare GGX, Schlick-Smith"
                                     : "bare GGX, height-correlated Smith";
        // `sink` enters the time times 0, so the compiler cannot drop the timed loop.
        floor.rows.push_back(floor_row(name, model, walk, ns + 0.0 * double(sink), "CPU ns per prepare+eval"));
    }
    const int dfg_size = 32;
    for (const std::uint32_t samples : {4u, 256u})
    {
        const std::vector<float> dfg = generate_dfg_table(dfg_size, samples, OPENPBR_BASELINE_VISIBILITY_HEIGHT_CORRELATED);
        std::vector<double> model;
        for (const FloorPoint& point : grid)
        {
            const glm::vec2 scale_bias = dfg_lookup(dfg, dfg_size, point.mu, point.roughness);
            model.push_back(point.f0 * scale_bias.x + scale_bias.y);
        }
        float sink = 0.0f;
        const double ns = time_ns_per_query(queries.size(), [&] {
            for (const AccuracyQuery& query : queries)
            {
                const glm::vec2 scale_bias = dfg_lookup(dfg, dfg_size, query.view[2], query.u[0]);
                sink += 0.9f * scale_bias.x + scale_bias.y;
            }
        });
        floor.rows.push_back(floor_row("split-sum IBL, DFG 32x32 at " + std::to_string(samples) + " samples", model, walk,
                                       ns + 0.0 * double(sink), "CPU ns per DFG look-up"));
    }
}

}  // namespace

AccuracyFloor measure_compensation_floor(const StudyContext& context, const std::vector<AccuracyFamily>& families)
{
    AccuracyFloor floor;
    floor.name = "compensation";
    floor.error_metric = "metal directional albedo error vs the microsurface random walk (max over F0 x roughness x "
                         "view cosine)";
    floor.reference = "microsurface random walk, all orders (Heitz et al. 2016; host/tables/microsurface.h)";
    const std::vector<FloorPoint> grid = floor_grid(context.options.quick);
    const std::vector<MicrosurfaceAlbedo> walk = walk_albedos(grid, context.options);
    const AccuracyFamily* compensation = nullptr;
    for (const AccuracyFamily& family : families)
    {
        compensation = family.name == "compensation" ? &family : compensation;
    }
    for (const AccuracySetting& setting : compensation ? compensation->settings : std::vector<AccuracySetting>{})
    {
        if (setting.variant == "table_16" || setting.variant == "table_64")
        {
            continue;  // the resolution is the knob's own error, not the model's
        }
        const BsdfVariant& variant = variant_named(context.variants, setting.variant);
        std::vector<double> model;
        for (std::size_t i = 0; i < grid.size(); ++i)
        {
            const std::vector<float> packed = pack_materials({metal_material(grid[i].f0, grid[i].roughness)});
            model.push_back(variant.albedo(packed.data(), grid[i].mu, context.options.albedo_samples, 1000 + i).mean[0]);
        }
        floor.rows.push_back(
            floor_row("OpenPBR, " + setting.setting, model, walk, setting.cpu_ns.best, compensation->time_metric));
    }
    add_baseline_rows(floor, grid, walk, context);
    return floor;
}

AccuracyFloor read_layering_floor(const std::filesystem::path& path)
{
    AccuracyFloor floor;
    floor.name = "layering";
    floor.error_metric = "directional albedo error vs the layered ground truth (max over channels and view cosines)";
    floor.reference = "position-free Monte Carlo through OpenPBR's layer stack (`openpbr accuracy layering`)";
    if (path.empty() || !std::filesystem::exists(path))
    {
        floor.note = "left out: " + (path.empty() ? std::string("no file given") : path.string() + " does not exist") +
                     "; run `openpbr accuracy layering --json " + (path.empty() ? "FILE" : path.string()) +
                     "`, then this study again";
        return floor;
    }
    try
    {
        const nlohmann::json document = nlohmann::json::parse(read_whole_file(path));
        std::map<std::string, AccuracyFloorRow> by_material;
        for (const nlohmann::json& row : document.at("rows"))
        {
            const std::string material = row.at("material").get<std::string>();
            AccuracyFloorRow& floor_row = by_material[material];
            floor_row.setting = material;
            floor_row.time_metric = "CPU ns per prepare+eval (model)";
            for (int c = 0; c < 3; ++c)
            {
                const double error =
                    std::abs(row.at("model_albedo").at(c).get<double>() - row.at("reference_albedo").at(c).get<double>());
                if (error >= floor_row.error)
                {
                    floor_row.error = error;
                    floor_row.error_uncertainty = row.at("reference_standard_error").at(c).get<double>();
                }
            }
            floor_row.time_ns = row.value("model_ns", 0.0);
        }
        for (const auto& [material, row] : by_material)
        {
            floor.rows.push_back(row);
        }
        floor.details = document.value("summary", nlohmann::json::object());
    }
    catch (const std::exception& error)
    {
        floor.rows.clear();
        floor.note = "left out: " + path.string() + " could not be read (" + error.what() + ")";
    }
    return floor;
}

}  // namespace accuracy
}  // namespace openpbr::host
