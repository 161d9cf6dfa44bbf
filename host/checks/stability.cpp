// Stability runner: see stability.h.
#include "host/checks/stability.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <variant>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "fuzz/fuzz_input_layout.h"
#include "host/checks/conformance.h"
#include "host/scene/material_library.h"
#include "host/support/directional_albedo.h"
#include "host/scene/parameter_table.h"
#include "host/support/random.h"
#include "host/support/files.h"
#include "host/support/stopwatch.h"
#include "slang/openpbr.h"

namespace openpbr::host {

StabilityCorpusError::~StabilityCorpusError() = default;

namespace {

using Inputs = openpbr::OpenPBR_ResolvedInputs;

// ---- Corpus: input table ------------------------------------------------------------------
//
// Every OpenPBR 1.1 input (specification order) and the two rotation extensions: the parameter
// table (slang/openpbr_parameters.h, as C++ data in host/scene/parameter_table.h).

// ---- Corpus: values -------------------------------------------------------------------------

constexpr float denormal_value = 1e-40f;

// Record sizes of targets/kernels/openpbr_conformance_kernel.h (OPENPBR_QUERY_FLOATS and
// OPENPBR_RESULT_FLOATS; that header's body is the CPU kernel of conformance_cpu.cpp and is not
// included twice). run_path checks the result size against them.
constexpr std::size_t query_floats = 11;
constexpr std::size_t result_floats = 24;

struct Where
{
    const std::string& source;
    std::string case_name;
    std::string field;

    std::string operator()(const std::string& message) const
    {
        std::string text = source;
        if (!case_name.empty())
        {
            text += ": case '" + case_name + "'";
        }
        if (!field.empty())
        {
            text += ": field '" + field + "'";
        }
        return text + ": " + message;
    }
};

float parse_float(const nlohmann::json& value, const Where& where)
{
    if (value.is_number())
    {
        const double number = value.get<double>();
        // Out-of-range doubles round to the infinities explicitly (a plain cast is undefined).
        if (number > double(std::numeric_limits<float>::max()))
        {
            return std::numeric_limits<float>::infinity();
        }
        if (number < -double(std::numeric_limits<float>::max()))
        {
            return -std::numeric_limits<float>::infinity();
        }
        return float(number);
    }
    if (value.is_string())
    {
        const std::string text = value.get<std::string>();
        if (text == "nan")
        {
            return std::numeric_limits<float>::quiet_NaN();
        }
        if (text == "inf" || text == "+inf")
        {
            return std::numeric_limits<float>::infinity();
        }
        if (text == "-inf")
        {
            return -std::numeric_limits<float>::infinity();
        }
        if (text == "denorm")
        {
            return denormal_value;
        }
        if (text == "-denorm")
        {
            return -denormal_value;
        }
        throw StabilityCorpusError(where("unknown special value \"" + text +
                                         "\" (expected a number, \"nan\", \"inf\", \"-inf\", \"denorm\" or \"-denorm\")"));
    }
    throw StabilityCorpusError(where(std::string("expected a number or a special-value string, got ") + value.type_name()));
}

template <int N> std::array<float, N> parse_floats(const nlohmann::json& value, const Where& where, const char* kind)
{
    if (!value.is_array() || value.size() != std::size_t(N))
    {
        throw StabilityCorpusError(
            where(std::string("expected ") + kind + " (an array of " + std::to_string(N) + " numbers), got " +
                  (value.is_array() ? "an array of " + std::to_string(value.size()) : std::string(value.type_name()))));
    }
    std::array<float, N> result{};
    for (int i = 0; i < N; ++i)
    {
        result[std::size_t(i)] = parse_float(value[std::size_t(i)], where);
    }
    return result;
}

glm::vec3 parse_vec3(const nlohmann::json& value, const Where& where, const char* kind)
{
    const std::array<float, 3> v = parse_floats<3>(value, where, kind);
    return glm::vec3(v[0], v[1], v[2]);
}

// Normalized in double precision where the vector has a finite, non-zero length.
glm::vec3 normalize_light(const glm::vec3& light)
{
    const double x = light.x, y = light.y, z = light.z;
    const double length = std::sqrt(x * x + y * y + z * z);
    if (!(length > 0.0) || !std::isfinite(length))
    {
        return light;
    }
    return glm::vec3(float(x / length), float(y / length), float(z / length));
}

// Raw basis as packed for the kernel: the contract in openpbr_prepare re-orthonormalizes it.
openpbr::OpenPBR_Basis raw_basis(const std::optional<glm::vec3>& normal, const std::optional<glm::vec3>& tangent)
{
    openpbr::OpenPBR_Basis basis;
    basis.normal = normal.value_or(glm::vec3(0.0f, 0.0f, 1.0f));
    basis.tangent = tangent.value_or(glm::vec3(1.0f, 0.0f, 0.0f));
    basis.bitangent = glm::cross(basis.normal, basis.tangent);
    return basis;
}

bool valid_case_name(const std::string& name)
{
    return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
               c == '.';
    });
}

StabilityCase parse_case(const nlohmann::json& item, std::size_t index, const std::string& source)
{
    Where where{source, "#" + std::to_string(index), ""};
    if (!item.is_object())
    {
        throw StabilityCorpusError(where(std::string("a case must be an object, got ") + item.type_name()));
    }
    StabilityCase result;
    result.inputs = openpbr::openpbr_make_default_resolved_inputs();
    if (!item.contains("name") || !item["name"].is_string())
    {
        throw StabilityCorpusError(where("missing string field 'name'"));
    }
    result.name = item["name"].get<std::string>();
    if (!valid_case_name(result.name))
    {
        throw StabilityCorpusError(where("case name '" + result.name + "' must be non-empty and use only [A-Za-z0-9_.-]"));
    }
    where.case_name = result.name;
    for (const auto& [key, value] : item.items())
    {
        if (key != "name" && key != "description" && key != "material" && key != "view" && key != "lights" &&
            key != "exterior_ior")
        {
            throw StabilityCorpusError(
                where("unknown key '" + key + "' (expected name, description, material, view, lights, exterior_ior)"));
        }
    }
    if (item.contains("description"))
    {
        if (!item["description"].is_string())
        {
            Where field_where = where;
            field_where.field = "description";
            throw StabilityCorpusError(field_where("expected a string"));
        }
        result.description = item["description"].get<std::string>();
    }

    GeometryVectors geometry_vectors;
    if (item.contains("material"))
    {
        const nlohmann::json& material = item["material"];
        if (!material.is_object())
        {
            Where field_where = where;
            field_where.field = "material";
            throw StabilityCorpusError(field_where(std::string("expected an object, got ") + material.type_name()));
        }
        for (auto entry = material.begin(); entry != material.end(); ++entry)
        {
            // Plain references, not structured bindings: lambdas below capture them (C++17).
            const std::string& key = entry.key();
            const nlohmann::json& value = entry.value();
            Where field_where = where;
            field_where.field = "material." + key;
            const ParameterDescriptor* descriptor = find_parameter(key);
            if (!descriptor)
            {
                throw StabilityCorpusError(field_where("unknown OpenPBR input name"));
            }
            std::visit(
                [&](const auto target) {
                    using Target = std::decay_t<decltype(target)>;
                    if constexpr (std::is_same_v<Target, float Inputs::*>)
                    {
                        result.inputs.*target = parse_float(value, field_where);
                    }
                    else if constexpr (std::is_same_v<Target, glm::vec3 Inputs::*>)
                    {
                        result.inputs.*target = parse_vec3(value, field_where, "a color3");
                    }
                    else if constexpr (std::is_same_v<Target, bool Inputs::*>)
                    {
                        if (!value.is_boolean())
                        {
                            throw StabilityCorpusError(
                                field_where(std::string("expected a boolean, got ") + value.type_name()));
                        }
                        result.inputs.*target = value.get<bool>();
                    }
                    else if constexpr (std::is_same_v<Target, glm::vec2 Inputs::*>)
                    {
                        const std::array<float, 2> v = parse_floats<2>(value, field_where, "a vector2 (cos, sin)");
                        result.inputs.*target = glm::vec2(v[0], v[1]);
                    }
                    else
                    {
                        geometry_vectors[target] = parse_vec3(value, field_where, "a vector3");
                    }
                },
                descriptor->target);
            result.inputs_set.push_back(key);
        }
    }
    for (std::size_t basis = 0; basis < parameter_bases().size(); ++basis)
    {
        result.inputs.*(parameter_bases()[basis].field) =
            raw_basis(geometry_vectors.normals[basis], geometry_vectors.tangents[basis]);
    }

    {
        Where field_where = where;
        field_where.field = "view";
        if (!item.contains("view"))
        {
            throw StabilityCorpusError(field_where("missing (a direction [x, y, z])"));
        }
        result.view = parse_vec3(item["view"], field_where, "a direction");
    }
    if (item.contains("exterior_ior"))
    {
        Where field_where = where;
        field_where.field = "exterior_ior";
        result.exterior_ior = parse_float(item["exterior_ior"], field_where);
    }
    {
        Where field_where = where;
        field_where.field = "lights";
        if (!item.contains("lights") || !item["lights"].is_array() || item["lights"].empty())
        {
            throw StabilityCorpusError(field_where("expected a non-empty array of directions"));
        }
        std::size_t light_index = 0;
        for (const nlohmann::json& light : item["lights"])
        {
            Where light_where = where;
            light_where.field = "lights[" + std::to_string(light_index++) + "]";
            result.lights.push_back(normalize_light(parse_vec3(light, light_where, "a direction")));
        }
    }
    return result;
}

// ---- Query stream -------------------------------------------------------------------------------

// Counter-based numbers: query k of case c is the same whatever the batching and path.
struct QueryRandom
{
    std::uint64_t state;
    QueryRandom(std::uint64_t seed, std::size_t case_index, std::size_t query)
        : state(splitmix64(splitmix64(seed ^ 0x5851f42d4c957f2dull) ^ (std::uint64_t(case_index) << 40) ^
                           std::uint64_t(query)))
    {
    }
    float next()
    {
        state = splitmix64(state);
        return float(state >> 40) * (1.0f / 16777216.0f);  // [0, 1)
    }
};

void fill_query(float* out, const StabilityCase& stability_case, std::size_t case_index, std::size_t query,
                std::uint64_t seed)
{
    QueryRandom random(seed, case_index, query);
    out[0] = float(case_index);
    out[1] = stability_case.view.x, out[2] = stability_case.view.y, out[3] = stability_case.view.z;
    for (int k = 7; k < 10; ++k)
    {
        out[k] = random.next();
    }
    glm::vec3 light;
    if (query < stability_case.lights.size())
    {
        light = stability_case.lights[query];
    }
    else
    {
        const float z = 1.0f - 2.0f * random.next();
        const float radius = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 6.2831853f * random.next();
        light = glm::vec3(radius * std::cos(phi), radius * std::sin(phi), z);
    }
    out[4] = light.x, out[5] = light.y, out[6] = light.z;
    out[10] = stability_case.exterior_ior;
}

// ---- Per-query checks -------------------------------------------------------------------------

constexpr int checked_slots = 21;
constexpr std::size_t max_violation_records = 5;

bool must_be_non_negative(int slot) { return slot <= 6 || (slot >= 10 && slot <= 16) || (slot >= 18 && slot <= 20); }

struct CaseAccumulator
{
    std::size_t queries = 0;
    std::size_t samples = 0;
    std::size_t nonfinite = 0;
    std::size_t negative = 0;
    std::size_t invalid = 0;
    std::size_t delta = 0;
    std::size_t bad_directions = 0;
    // Sample weights (diffuse + specular) of the sampling queries, a sample without a direction
    // weighing 0 (host/support/directional_albedo.h, the estimator the furnace uses).
    SampleWeightSums weights;
    std::vector<StabilityQueryRecord> violations;
};

void accumulate(CaseAccumulator& accumulator, const float* query, const float* result, std::size_t query_in_case,
                std::size_t light_count)
{
    ++accumulator.queries;
    // The query and its outputs, kept for the report while fewer than max_violation_records are.
    const auto record_violation = [&](const std::string& what) {
        if (accumulator.violations.size() >= max_violation_records)
        {
            return;
        }
        StabilityQueryRecord record;
        record.query = query_in_case;
        std::copy(query + 1, query + 4, record.view);
        std::copy(query + 4, query + 7, record.light);
        std::copy(query + 7, query + 10, record.u);
        std::copy(result, result + checked_slots, record.outputs);
        record.what = what;
        accumulator.violations.push_back(record);
    };
    std::string first_problem;
    for (int slot = 0; slot < checked_slots; ++slot)
    {
        const float value = result[slot];
        if (!std::isfinite(value))
        {
            ++accumulator.nonfinite;
            if (first_problem.empty())
            {
                first_problem = std::string("non-finite ") + conformance_slot_name(slot);
            }
        }
        else if (must_be_non_negative(slot) && value < 0.0f)
        {
            ++accumulator.negative;
            if (first_problem.empty())
            {
                first_problem = std::string("negative ") + conformance_slot_name(slot);
            }
        }
    }
    if (!first_problem.empty())
    {
        record_violation(first_problem);
    }
    if (query_in_case < light_count)
    {
        return;  // sampling statistics come from the extra samples only
    }
    ++accumulator.samples;
    const float sample_pdf = result[16];
    const auto lobe_type = static_cast<std::uint32_t>(result[17]);
    if (!(sample_pdf > 0.0f) || lobe_type == OPENPBR_LOBE_TYPE_NONE)
    {
        ++accumulator.invalid;
        accumulator.weights.add(0.0, 0.0, 0.0);
        return;
    }
    if ((lobe_type & OPENPBR_LOBE_TYPE_SPECULAR) != 0u)
    {
        ++accumulator.delta;
    }
    const double length =
        std::sqrt(double(result[7]) * result[7] + double(result[8]) * result[8] + double(result[9]) * result[9]);
    if (!(std::fabs(length - 1.0) <= 1e-3))
    {
        ++accumulator.bad_directions;
        record_violation("sample direction of length " + std::to_string(length));
    }
    // A non-finite channel is counted above and weighs 0 here, so it cannot hide the others.
    double weight[3];
    for (int c = 0; c < 3; ++c)
    {
        const double value = double(result[10 + c]) + double(result[13 + c]);
        weight[c] = std::isfinite(value) ? value : 0.0;
    }
    accumulator.weights.add(weight[0], weight[1], weight[2]);
}

StabilityCaseResult finish_case(const std::string& name, const CaseAccumulator& accumulator)
{
    StabilityCaseResult result;
    result.name = name;
    result.queries = accumulator.queries;
    result.samples = accumulator.samples;
    result.nonfinite = accumulator.nonfinite;
    result.negative = accumulator.negative;
    result.invalid_samples = accumulator.invalid;
    result.delta_samples = accumulator.delta;
    result.bad_directions = accumulator.bad_directions;
    result.violations = accumulator.violations;
    const double n = double(std::max<std::size_t>(accumulator.samples, 1));
    result.invalid_sample_fraction = double(accumulator.invalid) / n;
    const DirectionalAlbedo estimate = directional_albedo_from_sums(accumulator.weights);
    result.max_weight = estimate.max_weight_any_channel();
    int worst = 0;
    for (int c = 0; c < 3; ++c)
    {
        result.mean_weight[c] = estimate.mean[c];
        if (result.mean_weight[c] > result.mean_weight[worst])
        {
            worst = c;
        }
    }
    result.max_mean_weight = result.mean_weight[worst];
    result.mean_weight_standard_error = estimate.standard_error[worst];
    return result;
}

// Runs one path over every case in batches of at most `batch_queries` queries.
using Executor = StabilityExecutor;

// 1.3M queries: 124.8 MB of results, under lavapipe's 128 MiB storage-buffer range.
constexpr std::size_t batch_queries = 1300000;

StabilityPathResult run_path(const std::string& name, const Executor& execute, const std::vector<StabilityCase>& cases,
                             const std::vector<float>& materials, std::size_t samples_per_case, std::uint64_t seed)
{
    StabilityPathResult path;
    path.name = name;
    const Stopwatch stopwatch;
    std::vector<CaseAccumulator> accumulators(cases.size());
    std::vector<float> queries;
    std::vector<std::pair<std::size_t, std::size_t>> owners;  // (case, query in case) per query
    owners.reserve(batch_queries);
    auto flush = [&]() {
        if (owners.empty())
        {
            return;
        }
        // Queries are a pure function of (seed, case, query in case): filled in parallel.
        queries.resize(owners.size() * query_floats);
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, owners.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
                for (std::size_t q = range.begin(); q != range.end(); ++q)
                {
                    const auto [case_index, query_in_case] = owners[q];
                    fill_query(queries.data() + q * query_floats, cases[case_index], case_index, query_in_case, seed);
                }
            });
        const std::vector<float> results = execute(queries, materials);
        if (results.size() != owners.size() * result_floats)
        {
            throw std::logic_error("stability: unexpected result size from path '" + name + "'");
        }
        // Runs of one case are accumulated by one task each (accumulators are per case).
        std::vector<std::size_t> run_starts;
        for (std::size_t q = 0; q < owners.size(); ++q)
        {
            if (q == 0 || owners[q].first != owners[q - 1].first)
            {
                run_starts.push_back(q);
            }
        }
        run_starts.push_back(owners.size());
        tbb::parallel_for(std::size_t(0), run_starts.size() - 1, [&](std::size_t run) {
            for (std::size_t q = run_starts[run]; q < run_starts[run + 1]; ++q)
            {
                const auto [case_index, query_in_case] = owners[q];
                accumulate(accumulators[case_index], queries.data() + q * query_floats, results.data() + q * result_floats,
                           query_in_case, cases[case_index].lights.size());
            }
        });
        owners.clear();
    };
    for (std::size_t c = 0; c < cases.size(); ++c)
    {
        const std::size_t total = cases[c].lights.size() + samples_per_case;
        for (std::size_t k = 0; k < total; ++k)
        {
            owners.emplace_back(c, k);
            if (owners.size() == batch_queries)
            {
                flush();
            }
        }
    }
    flush();
    path.executed = true;
    for (std::size_t c = 0; c < cases.size(); ++c)
    {
        StabilityCaseResult result = finish_case(cases[c].name, accumulators[c]);
        path.nonfinite += result.nonfinite;
        path.negative += result.negative;
        path.bad_directions += result.bad_directions;
        if (path.cases.empty() || result.max_mean_weight > path.max_mean_weight)
        {
            path.max_mean_weight = result.max_mean_weight;
            path.max_mean_weight_case = result.name;
        }
        if (path.cases.empty() || result.max_weight > path.max_weight)
        {
            path.max_weight = result.max_weight;
            path.max_weight_case = result.name;
        }
        path.cases.push_back(std::move(result));
    }
    path.seconds = stopwatch.seconds();
    return path;
}

StabilityVolumeResult check_volume(const StabilityCase& stability_case)
{
    StabilityVolumeResult result;
    result.name = stability_case.name;
    const openpbr::OpenPBR_HomogeneousVolume volume = openpbr::openpbr_prepare_volume(stability_case.inputs);
    result.present = volume.is_present;
    result.anisotropy = volume.anisotropy;
    result.ok = std::isfinite(volume.anisotropy) && volume.anisotropy >= -1.0f && volume.anisotropy <= 1.0f;
    for (int c = 0; c < 3; ++c)
    {
        result.extinction[c] = volume.extinction[c];
        result.albedo[c] = volume.albedo[c];
        result.ok = result.ok && std::isfinite(volume.extinction[c]) && volume.extinction[c] >= 0.0f &&
                    std::isfinite(volume.albedo[c]) && volume.albedo[c] >= 0.0f && volume.albedo[c] <= 1.0f;
    }
    return result;
}

std::vector<float> pack_cases(const std::vector<StabilityCase>& cases)
{
    std::vector<Material> materials;
    materials.reserve(cases.size());
    for (const StabilityCase& stability_case : cases)
    {
        Material material;
        material.name = stability_case.name;
        material.inputs = stability_case.inputs;
        materials.push_back(material);
    }
    return pack_materials(materials);
}

nlohmann::json float_or_string(double value)
{
    if (std::isnan(value))
    {
        return "nan";
    }
    if (std::isinf(value))
    {
        return value > 0 ? "inf" : "-inf";
    }
    return value;
}

nlohmann::json array_json(const float* values, int count)
{
    nlohmann::json array = nlohmann::json::array();
    for (int i = 0; i < count; ++i)
    {
        array.push_back(float_or_string(values[i]));
    }
    return array;
}

}  // namespace

// ---- Public API ------------------------------------------------------------------------------

std::vector<std::string> stability_input_names()
{
    std::vector<std::string> names;
    for (const ParameterDescriptor& descriptor : parameter_descriptors())
    {
        names.emplace_back(descriptor.name);
    }
    return names;
}

std::vector<StabilityCase> parse_stability_corpus(const nlohmann::json& document, const std::string& source)
{
    const Where where{source, "", ""};
    if (!document.is_object() || !document.contains("cases") || !document["cases"].is_array())
    {
        throw StabilityCorpusError(where("expected an object with an array 'cases'"));
    }
    std::vector<StabilityCase> cases;
    std::size_t index = 0;
    for (const nlohmann::json& item : document["cases"])
    {
        StabilityCase parsed = parse_case(item, index++, source);
        for (const StabilityCase& earlier : cases)
        {
            if (earlier.name == parsed.name)
            {
                throw StabilityCorpusError(where("duplicate case name '" + parsed.name + "'"));
            }
        }
        cases.push_back(std::move(parsed));
    }
    if (cases.empty())
    {
        throw StabilityCorpusError(where("the corpus has no cases"));
    }
    return cases;
}

std::vector<StabilityCase> load_stability_corpus(const std::string& path)
{
    std::ifstream file(path);
    if (!file)
    {
        throw StabilityCorpusError(path + ": cannot open the stability corpus");
    }
    nlohmann::json document;
    try
    {
        file >> document;
    }
    catch (const nlohmann::json::parse_error& error)
    {
        throw StabilityCorpusError(path + ": malformed JSON: " + error.what());
    }
    return parse_stability_corpus(document, path);
}

bool stability_path_passes(const StabilityPathResult& path)
{
    return path.executed && path.nonfinite == 0 && path.negative == 0 && path.bad_directions == 0;
}

bool has_violations(const StabilityReport& report)
{
    if (report.volume_violations > 0)
    {
        return true;
    }
    return std::any_of(report.paths.begin(), report.paths.end(),
                       [](const StabilityPathResult& path) { return path.executed && !stability_path_passes(path); });
}

PathVerdict stability_verdict(const StabilityReport& report)
{
    PathVerdict verdict;
    if (report.volume_violations > 0)
    {
        verdict.other_failures.push_back("volume check fails in " + std::to_string(report.volume_violations) +
                                         (report.volume_violations == 1 ? " case" : " cases"));
    }
    for (const StabilityPathResult& path : report.paths)
    {
        if (!path.executed)
        {
            verdict.not_executed.push_back({path.name, path.note});
            continue;
        }
        (stability_path_passes(path) ? verdict.passed : verdict.failed).push_back(path.name);
    }
    return verdict;
}

StabilityPathResult run_stability_path(const std::string& name, const StabilityExecutor& execute,
                                       const std::vector<StabilityCase>& cases, std::size_t samples_per_case,
                                       std::uint64_t seed)
{
    return run_path(name, execute, cases, pack_cases(cases), samples_per_case, seed);
}

StabilityReport run_stability_cpu(const std::vector<StabilityCase>& cases, const StabilityOptions& options,
                                  bool include_cpu_path)
{
    StabilityReport report;
    report.case_count = cases.size();
    report.samples_per_case = options.samples_per_case;
    report.gpu_samples_per_case = options.gpu_samples_per_case ? options.gpu_samples_per_case : options.samples_per_case;
    report.seed = options.seed;
    if (include_cpu_path)
    {
        StabilityPathResult cpu =
            run_path("cpu", run_conformance_cpu, cases, pack_cases(cases), options.samples_per_case, options.seed);
        cpu.note = "CPU build (C++ single source)";
        report.paths.push_back(std::move(cpu));
        if (options.on_path_finished)
        {
            options.on_path_finished(report.paths.back());
        }
    }
    for (const StabilityCase& stability_case : cases)
    {
        report.volumes.push_back(check_volume(stability_case));
        report.volume_violations += report.volumes.back().ok ? 0 : 1;
    }
    return report;
}

nlohmann::json to_json(const StabilityReport& report)
{
    nlohmann::json json;
    json["cases"] = report.case_count;
    json["samples_per_case"] = report.samples_per_case;
    json["gpu_samples_per_case"] = report.gpu_samples_per_case;
    json["seed"] = report.seed;
    json["paths"] = nlohmann::json::array();
    for (const StabilityPathResult& path : report.paths)
    {
        nlohmann::json path_json = {{"name", path.name},
                                    {"executed", path.executed},
                                    {"note", path.note},
                                    {"nonfinite", path.nonfinite},
                                    {"negative", path.negative},
                                    {"bad_directions", path.bad_directions},
                                    {"max_mean_weight", path.max_mean_weight},
                                    {"max_mean_weight_case", path.max_mean_weight_case},
                                    {"max_weight", path.max_weight},
                                    {"max_weight_case", path.max_weight_case},
                                    {"seconds", path.seconds},
                                    {"validation_messages", path.validation_messages}};
        path_json["cases"] = nlohmann::json::array();
        for (const StabilityCaseResult& result : path.cases)
        {
            nlohmann::json case_json = {
                {"name", result.name},
                {"queries", result.queries},
                {"samples", result.samples},
                {"nonfinite", result.nonfinite},
                {"negative", result.negative},
                {"bad_directions", result.bad_directions},
                {"invalid_sample_fraction", result.invalid_sample_fraction},
                {"delta_samples", result.delta_samples},
                {"max_weight", result.max_weight},
                {"mean_weight", {result.mean_weight[0], result.mean_weight[1], result.mean_weight[2]}},
                {"max_mean_weight", result.max_mean_weight},
                {"mean_weight_standard_error", result.mean_weight_standard_error}};
            if (!result.violations.empty())
            {
                case_json["violations"] = nlohmann::json::array();
                for (const StabilityQueryRecord& record : result.violations)
                {
                    case_json["violations"].push_back({{"query", record.query},
                                                       {"what", record.what},
                                                       {"view", array_json(record.view, 3)},
                                                       {"light", array_json(record.light, 3)},
                                                       {"u", array_json(record.u, 3)},
                                                       {"outputs", array_json(record.outputs, checked_slots)}});
                }
            }
            path_json["cases"].push_back(case_json);
        }
        json["paths"].push_back(path_json);
    }
    nlohmann::json volume = {{"violations", report.volume_violations}, {"cases", nlohmann::json::array()}};
    for (const StabilityVolumeResult& result : report.volumes)
    {
        volume["cases"].push_back({{"name", result.name},
                                   {"present", result.present},
                                   {"ok", result.ok},
                                   {"extinction", array_json(result.extinction, 3)},
                                   {"albedo", array_json(result.albedo, 3)},
                                   {"anisotropy", float_or_string(result.anisotropy)}});
    }
    json["volume"] = volume;
    json["verdict"] = to_json(stability_verdict(report));
    return json;
}

std::string stability_header_text(const StabilityReport& report)
{
    std::ostringstream text;
    text << "stability: " << report.case_count << " cases, " << report.samples_per_case << " samples per case (GPU "
         << report.gpu_samples_per_case << "), seed " << report.seed << "\n";
    return text.str();
}

std::string to_text(const StabilityPathResult& path)
{
    std::ostringstream text;
    if (!path.executed)
    {
        text << "  " << path.name << ": not executed: " << path.note << "\n";
        return text.str();
    }
    text << "  " << path.name << " (" << path.note << "): non-finite " << path.nonfinite << ", negative " << path.negative
         << ", max mean weight " << std::fixed << std::setprecision(5) << path.max_mean_weight << " ("
         << path.max_mean_weight_case << "), max weight " << std::setprecision(3) << path.max_weight << " ("
         << path.max_weight_case << "), " << std::setprecision(1) << path.seconds << " s\n";
    text.unsetf(std::ios::floatfield);
    text << std::setprecision(6);
    text << "    " << std::left << std::setw(48) << "case" << std::right << std::setw(7) << "nonfin" << std::setw(7) << "neg"
         << std::setw(9) << "invalid" << std::setw(9) << "delta" << std::setw(12) << "max_w" << std::setw(10) << "mean_w"
         << std::setw(9) << "+-"
         << "\n";
    for (const StabilityCaseResult& result : path.cases)
    {
        const double n = double(std::max<std::size_t>(result.samples, 1));
        text << "    " << std::left << std::setw(48) << result.name << std::right << std::setw(7) << result.nonfinite
             << std::setw(7) << result.negative << std::fixed << std::setprecision(4) << std::setw(9)
             << result.invalid_sample_fraction << std::setw(9) << double(result.delta_samples) / n << std::setprecision(3)
             << std::setw(12) << result.max_weight << std::setprecision(5) << std::setw(10) << result.max_mean_weight
             << std::setw(9) << result.mean_weight_standard_error << "\n";
        text.unsetf(std::ios::floatfield);
        for (const StabilityQueryRecord& record : result.violations)
        {
            text << "      " << record.what << " at query " << record.query << ": view (" << record.view[0] << ", "
                 << record.view[1] << ", " << record.view[2] << "), light (" << record.light[0] << ", " << record.light[1]
                 << ", " << record.light[2] << "), u (" << record.u[0] << ", " << record.u[1] << ", " << record.u[2]
                 << ")\n";
        }
    }
    return text.str();
}

std::string stability_volume_text(const StabilityReport& report)
{
    std::ostringstream text;
    text << "  volume (CPU openpbr_prepare_volume): " << report.volume_violations << " violations\n";
    for (const StabilityVolumeResult& result : report.volumes)
    {
        if (!result.ok)
        {
            text << "    " << result.name << ": extinction (" << result.extinction[0] << ", " << result.extinction[1] << ", "
                 << result.extinction[2] << "), albedo (" << result.albedo[0] << ", " << result.albedo[1] << ", "
                 << result.albedo[2] << "), anisotropy " << result.anisotropy << "\n";
        }
    }
    return text.str();
}

std::string to_text(const StabilityReport& report)
{
    std::string text = stability_header_text(report);
    for (const StabilityPathResult& path : report.paths)
    {
        text += to_text(path);
    }
    return text + stability_volume_text(report) + verdict_line(stability_verdict(report)) + "\n";
}

std::size_t write_fuzz_seed_corpus(const std::vector<StabilityCase>& cases, const std::string& directory)
{
    // The first three lights of each case (the fuzzer mutates directions itself).
    constexpr std::size_t fuzz_seed_lights_per_case = 3;
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error)
    {
        throw std::runtime_error("cannot create '" + directory + "': " + error.message());
    }
    const std::vector<float> materials = pack_cases(cases);
    std::size_t count = 0;
    for (std::size_t c = 0; c < cases.size(); ++c)
    {
        for (std::size_t l = 0; l < std::min<std::size_t>(cases[c].lights.size(), fuzz_seed_lights_per_case); ++l)
        {
            float input[OPENPBR_FUZZ_INPUT_FLOATS] = {};
            std::copy(materials.begin() + std::ptrdiff_t(c * OPENPBR_PACKED_MATERIAL_FLOATS),
                      materials.begin() + std::ptrdiff_t((c + 1) * OPENPBR_PACKED_MATERIAL_FLOATS),
                      input + OPENPBR_FUZZ_MATERIAL_OFFSET);
            float query[query_floats];
            fill_query(query, cases[c], c, l, 1);
            std::copy(query + 1, query + 4, input + OPENPBR_FUZZ_VIEW_OFFSET);
            std::copy(query + 4, query + 7, input + OPENPBR_FUZZ_LIGHT_OFFSET);
            std::copy(query + 7, query + 10, input + OPENPBR_FUZZ_U_OFFSET);
            input[OPENPBR_FUZZ_WAVELENGTH_OFFSET + 0] = 612.0f;
            input[OPENPBR_FUZZ_WAVELENGTH_OFFSET + 1] = 549.0f;
            input[OPENPBR_FUZZ_WAVELENGTH_OFFSET + 2] = 465.0f;
            const std::string path = directory + "/" + cases[c].name + "_" + std::to_string(l) + ".bin";
            write_float32_file(path, std::vector<float>(std::begin(input), std::end(input)));
            ++count;
        }
    }
    return count;
}

}  // namespace openpbr::host
