// accuracy.cpp - see accuracy.h: the run of the accuracy study and its outputs. The measurements
// live in accuracy_families.cpp, accuracy_floors.cpp, accuracy_gpu.cpp and accuracy_pictures.cpp
// (host/studies/accuracy_internal.h).
#include "host/studies/accuracy.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <limits>
#include <sstream>
#include <thread>

#include "host/studies/accuracy_internal.h"
#include "host/support/stopwatch.h"

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
        result.timing_rounds = std::min(timing_rounds, 2);
        result.gpu = false;
    }
    result.webgpu = result.webgpu && result.gpu;
    return result;
}

void mark_pareto_front(AccuracyFamily& family)
{
    // A setting is on the front when no other setting is at least as fast and as accurate and
    // strictly better in one of the two.
    for (AccuracySetting& candidate : family.settings)
    {
        candidate.pareto = std::none_of(family.settings.begin(), family.settings.end(), [&](const AccuracySetting& other) {
            const bool no_worse = other.cpu_ns.best <= candidate.cpu_ns.best && other.error <= candidate.error;
            const bool better = other.cpu_ns.best < candidate.cpu_ns.best || other.error < candidate.error;
            return &other != &candidate && no_worse && better;
        });
    }
}

namespace {

using accuracy::FamilyMeasurement;

// The variance family's figure of merit once its times are known: 1 / (variance x ns per
// sample), relative to the shipped setting's.
void add_sampling_efficiency(AccuracyFamily& family)
{
    const auto shipped = std::find_if(family.settings.begin(), family.settings.end(),
                                      [](const AccuracySetting& setting) { return setting.shipped; });
    if (family.kind != "variance" || shipped == family.settings.end())
    {
        return;
    }
    const double shipped_cost = shipped->error * shipped->cpu_ns.best;
    for (AccuracySetting& setting : family.settings)
    {
        setting.other_errors["variance x ns per sample"] = setting.error * setting.cpu_ns.best;
        setting.other_errors["efficiency relative to the shipped setting"] =
            shipped_cost / std::max(setting.error * setting.cpu_ns.best, 1e-30);
    }
}

nlohmann::json run_description(const AccuracyOptions& options, const double seconds)
{
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    return {{"date", date},
            {"seconds", seconds},
            {"hardware_threads", std::thread::hardware_concurrency()},
            {"quick", options.quick},
            {"albedo_samples", options.albedo_samples},
            {"walk_paths", options.walk_paths},
            {"timing_queries", options.timing_queries},
            {"timing_rounds", options.timing_rounds},
            {"gpu", options.gpu},
            {"webgpu", options.webgpu}};
}

}  // namespace

AccuracyReport run_accuracy_study(const AccuracyOptions& requested)
{
    const Stopwatch stopwatch;
    const AccuracyOptions options = requested.effective();
    const std::vector<BsdfVariant> variants = bsdf_variants();
    const std::size_t gpu_steps = options.gpu ? accuracy::gpu_kernel_count(variants) * (options.webgpu ? 3 : 1) + 3 : 0;
    ProgressReporter progress(std::uint64_t(11 + options.timing_rounds + (options.pictures_directory.empty() ? 0 : 1)) +
                                  gpu_steps,
                              options.progress, "accuracy");
    const accuracy::StudyTables tables = accuracy::make_study_tables(options);
    progress.begin_step("tables at 16, 64 and 256 (quadrature) nodes, 16-bit values");
    const accuracy::Workload general =
        accuracy::make_workload("general", accuracy::general_materials(false), options.timing_queries);
    std::vector<Material> metals;
    for (const float f0 : {1.0f, 0.5f})
    {
        for (const float roughness : {0.1f, 0.3f, 0.6f, 0.9f})
        {
            metals.push_back(accuracy::metal_material(f0, roughness));
        }
    }
    const accuracy::Workload metal_workload = accuracy::make_workload("metals", metals, options.timing_queries);
    const accuracy::Workload films =
        accuracy::make_workload("films", accuracy::general_materials(true), options.timing_queries);
    const accuracy::Workload film_stacks =
        accuracy::make_workload("film stacks", accuracy::film_stack_materials(), options.timing_queries);
    accuracy::CpuTimer timer;
    const accuracy::StudyContext context{options, variants, general, metal_workload, films, film_stacks, tables, timer};
    std::vector<FamilyMeasurement> measured;
    for (const auto measure : {accuracy::measure_compensation, accuracy::measure_table_storage, accuracy::measure_fast_math,
                               accuracy::measure_precision, accuracy::measure_thin_film, accuracy::measure_film_estimate,
                               accuracy::measure_sampling})
    {
        measured.push_back(measure(context));
        progress.begin_step(measured.back().family.name);
    }
    timer.run(options.timing_rounds, progress);
    if (options.gpu)
    {
        accuracy::measure_gpu_times(context, tables, measured, progress);
    }
    AccuracyReport report;
    for (FamilyMeasurement& measurement : measured)
    {
        for (std::size_t s = 0; s < measurement.family.settings.size(); ++s)
        {
            measurement.family.settings[s].cpu_ns = timer.time(measurement.timing_jobs[s]);
        }
        add_sampling_efficiency(measurement.family);
        mark_pareto_front(measurement.family);
        report.families.push_back(std::move(measurement.family));
    }
    report.floors.push_back(accuracy::measure_compensation_floor(context, report.families));
    progress.begin_step("model floor: compensation vs random walk, baselines");
    report.floors.push_back(accuracy::read_layering_floor(options.layering_json));
    if (!options.pictures_directory.empty())
    {
        accuracy::write_picture_strips(context);
        progress.begin_step("pictures");
    }
    progress.finish();
    report.run = run_description(options, stopwatch.seconds());
    return report;
}

// ---- Outputs -----------------------------------------------------------------------------------

namespace {

nlohmann::json time_json(const AccuracyTime& time) { return {{"best", time.best}, {"median", time.median}}; }

nlohmann::json setting_json(const AccuracySetting& setting)
{
    nlohmann::json json = {{"variant", setting.variant},
                           {"setting", setting.setting},
                           {"shipped", setting.shipped},
                           {"reference", setting.reference},
                           {"error", setting.error},
                           {"error_uncertainty", setting.error_uncertainty},
                           {"other_errors", setting.other_errors},
                           {"cpu_ns", time_json(setting.cpu_ns)},
                           {"pareto", setting.pareto}};
    if (setting.lavapipe_ns)
    {
        json["lavapipe_ns"] = time_json(*setting.lavapipe_ns);
    }
    if (setting.webgpu_ns)
    {
        json["webgpu_ns"] = time_json(*setting.webgpu_ns);
    }
    return json;
}

// One flat row per setting and metric (the CSV and the rows of the JSON).
struct FlatRow
{
    std::string family, setting, metric;
    double value;
    std::string time_metric;
    double time;
};

std::vector<FlatRow> flat_rows(const AccuracyReport& report)
{
    std::vector<FlatRow> rows;
    for (const AccuracyFamily& family : report.families)
    {
        for (const AccuracySetting& setting : family.settings)
        {
            rows.push_back(
                {family.name, setting.setting, family.error_metric, setting.error, family.time_metric, setting.cpu_ns.best});
            for (const auto& [metric, value] : setting.other_errors)
            {
                rows.push_back({family.name, setting.setting, metric, value, family.time_metric, setting.cpu_ns.best});
            }
            const std::string gpu_metric = family.time_metric.substr(family.time_metric.find("per "));
            if (setting.lavapipe_ns)
            {
                rows.push_back({family.name, setting.setting, family.error_metric, setting.error,
                                "lavapipe device ns " + gpu_metric, setting.lavapipe_ns->best});
            }
            if (setting.webgpu_ns)
            {
                rows.push_back({family.name, setting.setting, family.error_metric, setting.error,
                                "SwiftShader (WebGPU) device ns " + gpu_metric, setting.webgpu_ns->best});
            }
        }
    }
    for (const AccuracyFloor& floor : report.floors)
    {
        for (const AccuracyFloorRow& row : floor.rows)
        {
            rows.push_back(
                {"model floor: " + floor.name, row.setting, floor.error_metric, row.error, row.time_metric, row.time_ns});
        }
    }
    return rows;
}

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

std::string number(const double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.6g", value);
    return buffer;
}

}  // namespace

nlohmann::json accuracy_to_json(const AccuracyReport& report)
{
    nlohmann::json families = nlohmann::json::array();
    for (const AccuracyFamily& family : report.families)
    {
        nlohmann::json settings = nlohmann::json::array();
        for (const AccuracySetting& setting : family.settings)
        {
            settings.push_back(setting_json(setting));
        }
        families.push_back({{"family", family.name},
                            {"kind", family.kind},
                            {"error_metric", family.error_metric},
                            {"reference", family.reference},
                            {"time_metric", family.time_metric},
                            {"settings", settings}});
    }
    nlohmann::json floors = nlohmann::json::object();
    for (const AccuracyFloor& floor : report.floors)
    {
        nlohmann::json rows = nlohmann::json::array();
        for (const AccuracyFloorRow& row : floor.rows)
        {
            rows.push_back({{"setting", row.setting},
                            {"error", row.error},
                            {"error_uncertainty", row.error_uncertainty},
                            {"time_ns", row.time_ns},
                            {"time_metric", row.time_metric}});
        }
        floors[floor.name] = {{"error_metric", floor.error_metric}, {"reference", floor.reference}, {"rows", rows}};
        if (!floor.note.empty())
        {
            floors[floor.name]["note"] = floor.note;
        }
        if (!floor.details.is_null() && !floor.details.empty())
        {
            floors[floor.name]["summary"] = floor.details;
        }
    }
    nlohmann::json rows = nlohmann::json::array();
    for (const FlatRow& row : flat_rows(report))
    {
        rows.push_back({{"knob", row.family},
                        {"setting", row.setting},
                        {"error_metric", row.metric},
                        {"error", row.value},
                        {"time_metric", row.time_metric},
                        {"time", row.time}});
    }
    return {{"run", report.run}, {"families", families}, {"model_floors", floors}, {"rows", rows}};
}

std::string accuracy_to_csv(const AccuracyReport& report)
{
    std::string csv = "knob,setting,error_metric,error,time_metric,time\n";
    for (const FlatRow& row : flat_rows(report))
    {
        csv += csv_field(row.family) + "," + csv_field(row.setting) + "," + csv_field(row.metric) + "," + number(row.value) +
               "," + csv_field(row.time_metric) + "," + number(row.time) + "\n";
    }
    return csv;
}

std::string accuracy_to_text(const AccuracyReport& report)
{
    std::ostringstream text;
    char line[512];
    for (const AccuracyFamily& family : report.families)
    {
        text << family.name << ": " << family.error_metric << "\n  against " << family.reference << "\n";
        std::snprintf(line, sizeof(line), "  %-50s %11s  %9s %9s %9s\n", "setting", "error", "CPU ns", "lavapipe", "WebGPU");
        text << line;
        for (const AccuracySetting& setting : family.settings)
        {
            const auto ns = [](const std::optional<AccuracyTime>& time) {
                return time ? number(time->best) : std::string("-");
            };
            std::snprintf(line, sizeof(line), "  %-50.50s %11.4g  %9.4g %9s %9s%s\n",
                          (setting.setting + (setting.pareto ? " *" : "")).c_str(), setting.error, setting.cpu_ns.best,
                          ns(setting.lavapipe_ns).c_str(), ns(setting.webgpu_ns).c_str(),
                          setting.reference ? "  (reference)" : "");
            text << line;
        }
    }
    for (const AccuracyFloor& floor : report.floors)
    {
        text << "model floor, " << floor.name << ": " << floor.error_metric << "\n";
        if (!floor.note.empty())
        {
            text << "  " << floor.note << "\n";
        }
        for (const AccuracyFloorRow& row : floor.rows)
        {
            std::snprintf(line, sizeof(line), "  %-50.50s %11.4g +- %-9.2g %9.4g\n", row.setting.c_str(), row.error,
                          row.error_uncertainty, row.time_ns);
            text << line;
        }
    }
    text << "(* on the family's Pareto front of error against CPU time)\n";
    return text.str();
}

}  // namespace openpbr::host
