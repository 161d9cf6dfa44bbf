// accuracy_families.cpp - each knob family of the accuracy study measured with its own metric
// against the reference that isolates it (host/studies/accuracy_internal.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "host/scene/material_packing.h"
#include "host/studies/accuracy_internal.h"
#include "host/studies/film_dense_reference.h"
#include "slang/openpbr.h"

namespace openpbr::host::accuracy {

const BsdfVariant& variant_named(const std::vector<BsdfVariant>& variants, const std::string& name)
{
    for (const BsdfVariant& variant : variants)
    {
        if (variant.name == name)
        {
            return variant;
        }
    }
    throw std::runtime_error("accuracy study: no variant named '" + name + "' in host/studies/accuracy_variants.cmake");
}

namespace {

// The settings of a family: the shipped build under the family's name for it, then the named
// variants with their own labels.
struct FamilySettings
{
    std::vector<const BsdfVariant*> variants;
    std::vector<AccuracySetting> settings;
};

FamilySettings family_settings(const StudyContext& context, const std::string& shipped_label,
                               const std::vector<std::string>& names)
{
    FamilySettings result;
    const auto add = [&](const BsdfVariant& variant, const std::string& label) {
        AccuracySetting setting;
        setting.variant = variant.name;
        setting.setting = label;
        setting.shipped = variant.name == "shipped";
        setting.reference = variant.reference;
        result.variants.push_back(&variant);
        result.settings.push_back(setting);
    };
    add(variant_named(context.variants, "shipped"), shipped_label);
    for (const std::string& name : names)
    {
        const BsdfVariant& variant = variant_named(context.variants, name);
        add(variant, variant.setting);
    }
    return result;
}

std::vector<float> evaluate(const BsdfVariant& variant, const Workload& workload, const Operation operation)
{
    std::vector<float> values(3 * workload.queries.size());
    (operation == Operation::eval ? variant.eval : variant.sample)(workload.packed.data(), workload.queries, values.data());
    return values;
}

// The family with each setting's CPU job on `workload`.
FamilyMeasurement finish_family(const StudyContext& context, AccuracyFamily family, const FamilySettings& settings,
                                const Workload& workload, const Operation operation)
{
    FamilyMeasurement measurement;
    family.settings = settings.settings;
    for (const BsdfVariant* variant : settings.variants)
    {
        measurement.timing_jobs.push_back(context.timer.add(*variant, workload, operation));
    }
    measurement.family = std::move(family);
    measurement.workload = workload.name;
    measurement.operation = operation;
    return measurement;
}

// Per-query relative errors of every setting's eval on `workload` against the setting
// `reference_index`: the family's error is the 99th percentile.
void per_query_errors(const FamilySettings& settings, std::vector<AccuracySetting>& out, const Workload& workload,
                      const std::size_t reference_index)
{
    const std::vector<float> reference = evaluate(*settings.variants[reference_index], workload, Operation::eval);
    for (std::size_t i = 0; i < out.size(); ++i)
    {
        const RelativeErrors errors = relative_errors(evaluate(*settings.variants[i], workload, Operation::eval), reference);
        out[i].error = errors.p99;
        out[i].other_errors["per-query relative error (median)"] = errors.median;
        out[i].other_errors["per-query relative error (max)"] = errors.max;
    }
}

// Largest |1 - albedo| (mean of RGB) of white metal and white glass at roughness 0.2, 0.5, 0.9
// and view cosines 0.1-1.
double white_furnace_deviation(const BsdfVariant& variant, const AccuracyOptions& options)
{
    double deviation = 0.0;
    for (const float roughness : {0.2f, 0.5f, 0.9f})
    {
        for (const Material& material : {metal_material(1.0f, roughness), glass_material(roughness)})
        {
            const std::vector<float> packed = pack_materials({material});
            for (const float mu : {0.1f, 0.25f, 0.5f, 0.75f, 1.0f})
            {
                const AccuracyAlbedo albedo = variant.albedo(packed.data(), mu, options.albedo_samples, 77);
                deviation = std::max(deviation, std::abs(1.0 - (albedo.mean[0] + albedo.mean[1] + albedo.mean[2]) / 3.0));
            }
        }
    }
    return deviation;
}

}  // namespace

FamilyMeasurement measure_compensation(const StudyContext& context)
{
    const FamilySettings settings =
        family_settings(context, "table 128x128 (shipped)",
                        {"table_64", "table_16", "compensation_analytic", "compensation_none", "compensation_exact"});
    AccuracyFamily family;
    family.name = "compensation";
    family.kind = "bias";
    family.error_metric = "white-metal directional albedo error vs exact E_ggx (max over roughness x view cosine)";
    family.reference = "the same model reading E_ggx from a 256x256 table integrated by quadrature in double";
    family.time_metric = "CPU ns per prepare+eval (general workload)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.general, Operation::eval);
    std::vector<AccuracySetting>& out = measurement.family.settings;
    // Paired estimates: a lone metal lobe samples the same directions whatever its compensation
    // (a factor of the view alone), so the differences carry no sampling noise of their own.
    const std::vector<AlbedoPoint> grid = compensation_grid(context.options.quick);
    std::vector<std::vector<double>> albedos(out.size(), std::vector<double>(grid.size()));
    for (std::size_t p = 0; p < grid.size(); ++p)
    {
        const std::vector<float> packed = pack_materials({metal_material(1.0f, grid[p].roughness)});
        for (std::size_t s = 0; s < out.size(); ++s)
        {
            albedos[s][p] =
                settings.variants[s]->albedo(packed.data(), grid[p].mu, context.options.albedo_samples, 1000 + p).mean[0];
        }
    }
    const std::size_t reference = out.size() - 1;
    const std::vector<float> reference_values = evaluate(*settings.variants[reference], context.metals, Operation::eval);
    for (std::size_t s = 0; s < out.size(); ++s)
    {
        double max_error = 0.0, mean_error = 0.0;
        for (std::size_t p = 0; p < grid.size(); ++p)
        {
            const double error = std::abs(albedos[s][p] - albedos[reference][p]);
            max_error = std::max(max_error, error);
            mean_error += error / double(grid.size());
        }
        out[s].error = max_error;
        out[s].other_errors["white-metal albedo error vs exact E_ggx (mean)"] = mean_error;
        const RelativeErrors metal =
            relative_errors(evaluate(*settings.variants[s], context.metals, Operation::eval), reference_values);
        out[s].other_errors["metal per-query relative error vs exact E_ggx (99th percentile)"] = metal.p99;
    }
    // The reference's own error: its table read bilinearly at the grid against the quadrature
    // with 512 x 512 nodes there.
    if (!context.options.quick)
    {
        double reference_error = 0.0;
        const std::vector<float>& table = context.tables.reference;
        const int size = reference_table_size;
        for (const AlbedoPoint& point : grid)
        {
            const double fx = std::sqrt(double(point.mu)) * (size - 1), fy = double(point.roughness) * (size - 1);
            const int x0 = std::min(int(fx), size - 2), y0 = std::min(int(fy), size - 2);
            const double tx = fx - x0, ty = fy - y0;
            const auto at = [&](const int x, const int y) { return double(table[std::size_t(y) * size + x]); };
            const double lookup = (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
                                  ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
            const double exact = ggx_albedo_quadrature(point.mu, double(point.roughness) * point.roughness, 512);
            reference_error = std::max(reference_error, std::abs(lookup - exact));
        }
        out[reference].other_errors["reference table vs quadrature at 512x512 nodes (max |E| difference)"] = reference_error;
    }
    return measurement;
}

FamilyMeasurement measure_table_storage(const StudyContext& context)
{
    const FamilySettings settings = family_settings(context, "float32 array (shipped)", {"table_buffer", "table_half"});
    AccuracyFamily family;
    family.name = "table storage";
    family.kind = "bias";
    family.error_metric = "per-query relative eval error vs float32 tables (99th percentile)";
    family.reference = "the shipped float32 values";
    family.time_metric = "CPU ns per prepare+eval (general workload)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.general, Operation::eval);
    std::vector<AccuracySetting>& out = measurement.family.settings;
    per_query_errors(settings, out, context.general, 0);
    // Array and buffer mode read the same floats with the same arithmetic (slang/openpbr_lut.h):
    // count every output whose bits differ (the test asserts 0).
    const std::vector<float> eval_reference = evaluate(*settings.variants[0], context.general, Operation::eval);
    const std::vector<float> sample_reference = evaluate(*settings.variants[0], context.general, Operation::sample);
    for (std::size_t s = 0; s < out.size(); ++s)
    {
        if (!settings.variants[s]->bit_identical_to_shipped)
        {
            continue;
        }
        const std::vector<float> values = evaluate(*settings.variants[s], context.general, Operation::eval);
        const std::vector<float> samples = evaluate(*settings.variants[s], context.general, Operation::sample);
        std::size_t differing = 0;
        for (std::size_t i = 0; i < values.size(); ++i)
        {
            differing += std::memcmp(&values[i], &eval_reference[i], sizeof(float)) != 0 ? 1 : 0;
            differing += std::memcmp(&samples[i], &sample_reference[i], sizeof(float)) != 0 ? 1 : 0;
        }
        out[s].other_errors["eval + sample outputs differing in bits from the array build (count)"] = double(differing);
    }
    return measurement;
}

FamilyMeasurement measure_fast_math(const StudyContext& context)
{
    const FamilySettings settings =
        family_settings(context, "precise math (shipped)", {"fast_rcp_sqrt", "fast_sqrt", "fast_normalize", "fast_all"});
    AccuracyFamily family;
    family.name = "fast math";
    family.kind = "bias";
    family.error_metric = "per-query relative eval error vs precise math (99th percentile)";
    family.reference = "the shipped build (precise sqrt, inversesqrt, normalize)";
    family.time_metric = "CPU ns per prepare+eval (general workload)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.general, Operation::eval);
    per_query_errors(settings, measurement.family.settings, context.general, 0);
    for (std::size_t s = 0; s < settings.variants.size(); ++s)
    {
        measurement.family.settings[s].other_errors["white furnace deviation (max)"] =
            white_furnace_deviation(*settings.variants[s], context.options);
    }
    return measurement;
}

FamilyMeasurement measure_precision(const StudyContext& context)
{
    const FamilySettings settings = family_settings(context, "C++ float (shipped)", {"double_precision"});
    AccuracyFamily family;
    family.name = "precision";
    family.kind = "bias";
    family.error_metric = "per-query relative eval error vs the double build (99th percentile)";
    family.reference = "the same source compiled in double (tools/make_double_headers.py)";
    family.time_metric = "CPU ns per prepare+eval (general workload)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.general, Operation::eval);
    per_query_errors(settings, measurement.family.settings, context.general, 1);
    return measurement;
}

FamilyMeasurement measure_thin_film(const StudyContext& context)
{
    const FamilySettings settings = family_settings(context, "full spectral film (shipped)", {"thin_film_fast"});
    AccuracyFamily family;
    family.name = "thin film";
    family.kind = "bias";
    family.error_metric = "film reflectance error vs the full film (max absolute, RGB)";
    family.reference = "the full spectral film (shipped)";
    family.time_metric = "CPU ns per prepare+eval (filmed workload)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.films, Operation::eval);
    std::vector<AccuracySetting>& out = measurement.family.settings;
    // The film's reflectance on a dielectric base over films of IOR 1.2, 1.4 and 2 and 0.1-1.5
    // um, in air and under a medium of IOR 1.5, on bases of IOR 1 (a soap bubble) and 1.5, at
    // cosines 0.02-1.
    std::vector<std::array<float, 3>> full, model;
    for (const float outside : {1.0f, 1.5f})
    {
        for (const float film_ior : {1.2f, 1.4f, 2.0f})
        {
            for (const float thickness : {0.1f, 0.25f, 0.4f, 0.55f, 0.7f, 0.9f, 1.2f, 1.5f})
            {
                for (const float base : {1.0f, 1.5f})
                {
                    for (int c = 0; c < 16; ++c)
                    {
                        const AccuracyFilm film{outside, film_ior, thickness, base, 0.0f, 1.0f};
                        const float cosine = 0.02f + 0.98f * float(c) / 15.0f;
                        std::array<float, 3> a{}, b{};
                        settings.variants[0]->film_reflectance(film, cosine, a.data());
                        settings.variants[1]->film_reflectance(film, cosine, b.data());
                        full.push_back(a);
                        model.push_back(b);
                    }
                }
            }
        }
    }
    double max_error = 0.0, mean_error = 0.0;
    for (std::size_t i = 0; i < full.size(); ++i)
    {
        for (int c = 0; c < 3; ++c)
        {
            const double error = std::abs(double(model[i][std::size_t(c)]) - full[i][std::size_t(c)]);
            max_error = std::max(max_error, error);
            mean_error += error / (3.0 * double(full.size()));
        }
    }
    out[1].error = max_error;
    out[1].other_errors["film reflectance error vs the full film (mean absolute)"] = mean_error;
    const std::vector<float> reference = evaluate(*settings.variants[0], context.films, Operation::eval);
    for (std::size_t s = 0; s < out.size(); ++s)
    {
        const RelativeErrors errors =
            relative_errors(evaluate(*settings.variants[s], context.films, Operation::eval), reference);
        out[s].other_errors["filmed per-query relative eval error (99th percentile)"] = errors.p99;
        out[s].other_errors["filmed per-query relative eval error (median)"] = errors.median;
    }
    return measurement;
}

namespace {

// The film-estimate cases: the regimes of tests/bsdf/test_film_estimate.cpp (in air, under a
// medium of IOR 1.3, under 1.6 where the film turns evanescent and the base totally reflecting
// inside the lobe, under 3 where everything past cos 0.94 reflects totally), films of 0.25 and
// 1 um, roughness 0.1-0.9, view cosines 1-0.02.
std::vector<AccuracyFilm> film_estimate_cases(const bool quick)
{
    struct Regime
    {
        float outside_ior;
        std::vector<float> film_iors;
    };
    const std::vector<Regime> regimes = {{1.0f, {1.33f, 1.8f}}, {1.3f, {1.4f, 2.2f}}, {1.6f, {1.4f}}, {3.0f, {1.5f}}};
    const std::vector<float> roughness = quick ? std::vector<float>{0.3f} : std::vector<float>{0.1f, 0.3f, 0.6f, 0.9f};
    const std::vector<float> cosines = quick ? std::vector<float>{0.5f} : std::vector<float>{1.0f, 0.5f, 0.2f, 0.02f};
    std::vector<AccuracyFilm> cases;
    for (const Regime& regime : regimes)
    {
        for (const float film_ior : regime.film_iors)
        {
            for (const float thickness : {0.25f, 1.0f})
            {
                for (const float r : roughness)
                {
                    for (const float cosine : cosines)
                    {
                        cases.push_back({regime.outside_ior, film_ior, thickness, 1.5f, r, cosine});
                    }
                }
            }
        }
    }
    return cases;
}

// What the estimate approximates (host/studies/film_dense_reference.h): the dense reference of
// docs/thin-film-estimate.md for this film.
std::array<double, 6> dense_film_average(const AccuracyFilm& film, const int n)
{
    return host::dense_film_average(host::filmed_bases(film.outside_ior, film.film_ior, film.thickness_um, film.base_ior),
                                    film.roughness, film.view_cosine, n);
}

// Largest deviation from 1 of any channel's albedo over the film stacks at view cos 1, 0.5, 0.1.
double film_stack_furnace_deviation(const BsdfVariant& variant, const AccuracyOptions& options)
{
    double deviation = 0.0;
    for (const Material& stack : film_stack_materials())
    {
        const std::vector<float> packed = pack_materials({stack});
        for (const float mu : {1.0f, 0.5f, 0.1f})
        {
            const AccuracyAlbedo albedo = variant.albedo(packed.data(), mu, options.albedo_samples, 91);
            for (const double channel : albedo.mean)
            {
                deviation = std::max(deviation, std::abs(1.0 - channel));
            }
        }
    }
    return deviation;
}

}  // namespace

FamilyMeasurement measure_film_estimate(const StudyContext& context)
{
    const FamilySettings settings =
        family_settings(context, "segments and cuts (shipped)", {"film_estimate_quartile_cuts", "film_estimate_at_view"});
    AccuracyFamily family;
    family.name = "film estimate";
    family.kind = "bias";
    family.error_metric = "lobe-averaged film reflectance error vs the dense average (max absolute)";
    family.reference = "a dense 128x128 average over the lobe's visible normals (docs/thin-film-estimate.md)";
    family.time_metric = "CPU ns per prepare+eval (film-under-coat stacks)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.film_stacks, Operation::eval);
    std::vector<AccuracySetting>& out = measurement.family.settings;
    const std::vector<AccuracyFilm> cases = film_estimate_cases(context.options.quick);
    std::vector<std::array<double, 6>> dense;
    for (const AccuracyFilm& film : cases)
    {
        dense.push_back(dense_film_average(film, context.options.quick ? 32 : 128));
    }
    for (std::size_t s = 0; s < out.size(); ++s)
    {
        double change_error = 0.0, metal_error = 0.0;
        for (std::size_t k = 0; k < cases.size(); ++k)
        {
            std::array<float, 6> estimate{};
            settings.variants[s]->film_estimate(cases[k], estimate.data());
            for (std::size_t c = 0; c < 3; ++c)
            {
                change_error = std::max(change_error, std::abs(estimate[c] - dense[k][c]));
                metal_error = std::max(metal_error, std::abs(estimate[c + 3] - dense[k][c + 3]));
            }
        }
        out[s].error = std::max(change_error, metal_error);
        out[s].other_errors["dielectric's film change vs the dense average (max absolute)"] = change_error;
        out[s].other_errors["metal's filmed factor vs the dense average (max absolute)"] = metal_error;
        out[s].other_errors["film-under-coat white furnace deviation (max)"] =
            film_stack_furnace_deviation(*settings.variants[s], context.options);
    }
    return measurement;
}

FamilyMeasurement measure_sampling(const StudyContext& context)
{
    const FamilySettings settings =
        family_settings(context, "spherical caps (shipped)", {"vndf_hemisphere", "vndf_bounded"});
    AccuracyFamily family;
    family.name = "vndf sampling";
    family.kind = "variance";
    family.error_metric = "per-sample variance of the metal albedo estimator (mean over the metal workload's "
                          "materials x view cosines)";
    family.reference = "efficiency 1 / (variance x ns per sample) relative to the shipped setting";
    family.time_metric = "CPU ns per prepare+sample (metal workload)";
    FamilyMeasurement measurement = finish_family(context, family, settings, context.metals, Operation::sample);
    std::vector<AccuracySetting>& out = measurement.family.settings;
    // Four independent point sets: the variance's mean and its standard error over them.
    const int seeds = 4;
    const std::vector<float> cosines =
        context.options.quick ? std::vector<float>{0.3f, 1.0f} : std::vector<float>{0.1f, 0.3f, 0.6f, 1.0f};
    for (std::size_t s = 0; s < out.size(); ++s)
    {
        std::vector<double> per_seed(seeds, 0.0);
        for (const Material& material : context.metals.materials)
        {
            const std::vector<float> packed = pack_materials({material});
            for (const float mu : cosines)
            {
                for (int seed = 0; seed < seeds; ++seed)
                {
                    const AccuracyAlbedo albedo =
                        settings.variants[s]->albedo(packed.data(), mu, context.options.albedo_samples, 5000 + 7919 * seed);
                    per_seed[std::size_t(seed)] +=
                        albedo.variance / double(context.metals.materials.size() * cosines.size());
                }
            }
        }
        double mean = 0.0, spread = 0.0;
        for (const double value : per_seed)
        {
            mean += value / seeds;
        }
        for (const double value : per_seed)
        {
            spread += (value - mean) * (value - mean) / (seeds - 1);
        }
        out[s].error = mean;
        out[s].error_uncertainty = std::sqrt(spread / seeds);
    }
    return measurement;
}

}  // namespace openpbr::host::accuracy
