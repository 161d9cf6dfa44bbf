// accuracy_workloads.cpp - the accuracy study's workloads, tables, error statistics and CPU timer
// (host/studies/accuracy_internal.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>

#include <glm/gtc/packing.hpp>
#include <tbb/parallel_for.h>

#include "host/scene/material_packing.h"
#include "host/studies/accuracy_internal.h"
#include "host/support/stopwatch.h"
#include "host/tables/lut_generator.h"

namespace openpbr::host {

const float* accuracy_lut_values_16 = nullptr;
const float* accuracy_lut_values_64 = nullptr;
const float* accuracy_lut_values_reference = nullptr;

namespace accuracy {

// ---- Workloads ---------------------------------------------------------------------------------

Workload make_workload(const std::string& name, std::vector<Material> materials, const std::uint32_t count)
{
    Workload workload;
    workload.name = name;
    workload.materials = std::move(materials);
    workload.packed = pack_materials(workload.materials);
    std::mt19937_64 generator(20231122);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    workload.queries.resize(count);
    for (std::uint32_t i = 0; i < count; ++i)
    {
        AccuracyQuery& query = workload.queries[i];
        query.material = i % std::uint32_t(workload.materials.size());
        const float view_cos = 0.05f + 0.95f * uniform(generator);
        const float view_phi = 6.2831853f * uniform(generator);
        const float view_sin = std::sqrt(1.0f - view_cos * view_cos);
        query.view[0] = view_sin * std::cos(view_phi);
        query.view[1] = view_sin * std::sin(view_phi);
        query.view[2] = view_cos;
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
    return workload;
}

Material metal_material(const float f0, const float roughness)
{
    Material material = default_material();
    material.name = "metal";
    material.inputs.base_color = glm::vec3(f0);
    material.inputs.base_metalness = 1.0f;
    material.inputs.specular_roughness = roughness;
    return material;
}

Material glass_material(const float roughness)
{
    Material material = default_material();
    material.name = "glass";
    material.inputs.transmission_weight = 1.0f;
    material.inputs.specular_roughness = roughness;
    return material;
}

std::vector<Material> general_materials(const bool thin_film)
{
    std::vector<Material> materials;
    for (const float roughness : {0.1f, 0.4f, 0.8f})
    {
        Material plastic = default_material();
        plastic.inputs.specular_roughness = roughness;
        Material coated = metal_material(0.9f, roughness);
        coated.inputs.coat_weight = 1.0f;
        coated.inputs.coat_roughness = 0.1f;
        Material brushed = metal_material(0.8f, roughness);
        brushed.inputs.specular_roughness_anisotropy = 0.6f;
        for (Material material : {plastic, metal_material(0.95f, roughness), glass_material(roughness), coated, brushed})
        {
            if (thin_film)
            {
                material.inputs.thin_film_weight = 1.0f;
                material.inputs.thin_film_thickness = 0.3f + 0.2f * roughness;
            }
            materials.push_back(material);
        }
    }
    return materials;
}

std::vector<Material> film_stack_materials()
{
    std::vector<Material> materials;
    for (const float thickness : {0.3f, 0.6f, 0.9f, 1.5f})
    {
        for (const float roughness : {0.1f, 0.4f, 0.8f})
        {
            Material film = default_material();
            film.name = "film stack";
            film.inputs.base_color = glm::vec3(1.0f);
            film.inputs.specular_roughness = roughness;
            film.inputs.coat_weight = 1.0f;
            film.inputs.coat_ior = 1.6f;
            film.inputs.coat_roughness = roughness;
            film.inputs.thin_film_weight = 1.0f;
            film.inputs.thin_film_ior = 1.4f;
            film.inputs.thin_film_thickness = thickness;
            materials.push_back(film);
        }
    }
    return materials;
}

std::vector<AlbedoPoint> compensation_grid(const bool quick)
{
    const std::vector<float> roughness =
        quick ? std::vector<float>{0.3f, 0.9f} : std::vector<float>{0.05f, 0.1f, 0.2f, 0.3f, 0.45f, 0.6f, 0.8f, 1.0f};
    const std::vector<float> mu =
        quick ? std::vector<float>{0.2f, 1.0f} : std::vector<float>{0.05f, 0.1f, 0.2f, 0.35f, 0.5f, 0.7f, 0.85f, 1.0f};
    std::vector<AlbedoPoint> grid;
    for (const float r : roughness)
    {
        for (const float m : mu)
        {
            grid.push_back({r, m});
        }
    }
    return grid;
}

// ---- Tables ------------------------------------------------------------------------------------

namespace {

// Smith Lambda of isotropic GGX for a direction of cosine z.
double smith_lambda(const double z, const double alpha)
{
    if (z >= 1.0)
    {
        return 0.0;
    }
    const double tan_squared = (1.0 - z * z) / (z * z);
    return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * tan_squared));
}

// The shipped flat table with table 0 replaced by one of `size` x `size` nodes (the layout of
// slang/openpbr_lut.h with OPENPBR_LUT_2D_SIZE = size; the other tables follow as shipped), each
// node from `node_value(mu coordinate, r coordinate)`, cached in the cache directory under
// `cache_name`.
template <typename NodeValue>
std::vector<float> table_with_2d_size(const int size, const std::filesystem::path& cache_directory,
                                      const std::string& cache_name, NodeValue node_value)
{
    const LutLayout shipped = compiled_lut_layout();
    LutLayout layout = shipped;
    layout.size_2d = size;
    const std::size_t total = layout.total_count() + OPENPBR_LUT_FILM_COUNT;
    const std::filesystem::path cache_file =
        cache_directory.empty() ? std::filesystem::path() : cache_directory / (cache_name + ".bin");
    if (!cache_file.empty() && std::filesystem::exists(cache_file))
    {
        try
        {
            return read_lut_binary(cache_file, total);
        }
        catch (const std::exception&)
        {
            // A damaged cache entry is regenerated below.
        }
    }
    std::vector<float> values(total);
    const std::size_t cells = std::size_t(size) * std::size_t(size);
    tbb::parallel_for(std::size_t(0), cells, [&](const std::size_t cell) {
        values[cell] = float(node_value(double(cell % std::size_t(size)) / double(size - 1),
                                        double(cell / std::size_t(size)) / double(size - 1), cell));
    });
    std::copy(openpbr_lut_data + shipped.count(0), openpbr_lut_data + OPENPBR_LUT_TOTAL_COUNT,
              values.begin() + std::ptrdiff_t(cells));
    if (!cache_file.empty())
    {
        std::filesystem::create_directories(cache_directory);
        write_lut_binary(cache_file, values);
    }
    return values;
}

std::vector<std::byte> float_bytes(const std::vector<float>& values)
{
    std::vector<std::byte> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

}  // namespace

double ggx_albedo_quadrature(const double mu_value, const double alpha_value, const int n)
{
    // E = integral over the visible microfacets of G2 / G1(view), written over the distribution
    // of normals D(h) (h.n) with u1 -> tan^2(theta_h) = alpha^2 u1 / (1 - u1) and phi_h in
    // [0, pi] (the integrand is even in phi): weight (v.h) / (mu (h.n)) G2. Midpoint nodes in s
    // with u1 = 1 - s^4 crowd towards grazing microfacets, where (v.h) / (h.n) diverges like
    // (1 - u1)^-1/2 and light leaves past the horizon (an unresolved tail of the lobe put the
    // plain midpoint rule 7e-3 off at roughness 0.3, mu = 1, with 64 nodes).
    const double mu = std::clamp(mu_value, 1e-4, 1.0);
    const double alpha = std::max(alpha_value, 1e-4);
    const double view_x = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const double lambda_view = smith_lambda(mu, alpha);
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
    {
        const double s = (i + 0.5) / n;
        const double s2 = s * s;
        const double u1 = 1.0 - s2 * s2;
        const double jacobian = 4.0 * s2 * s;
        const double tan_squared = alpha * alpha * u1 / (1.0 - u1);
        const double cos_h = 1.0 / std::sqrt(1.0 + tan_squared);
        const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
        double row = 0.0;
        for (int j = 0; j < n; ++j)
        {
            const double phi = 3.14159265358979323846 * (j + 0.5) / n;
            const double view_dot_h = view_x * sin_h * std::cos(phi) + mu * cos_h;
            const double light_z = 2.0 * view_dot_h * cos_h - mu;
            if (view_dot_h > 0.0 && light_z > 0.0)
            {
                row += view_dot_h / (mu * cos_h) / (1.0 + lambda_view + smith_lambda(light_z, alpha));
            }
        }
        sum += row * jacobian;
    }
    return sum / (double(n) * double(n));
}

StudyTables make_study_tables(const AccuracyOptions& options)
{
    StudyTables tables;
    const auto monte_carlo = [&](const double mu, const double r, const std::size_t cell) {
        return estimate_lut_entry(lut_table_ggx_albedo, mu, r, 0.0, options.table_samples, lut_cell_seed(0, cell));
    };
    const std::string samples = "_" + std::to_string(options.table_samples);
    tables.size_16 = table_with_2d_size(16, options.cache_directory, "lut_2d_16" + samples, monte_carlo);
    tables.size_64 = table_with_2d_size(64, options.cache_directory, "lut_2d_64" + samples, monte_carlo);
    // The reference: the quadrature at the generator's node parameters (lut_mu_from_coordinate,
    // lut_alpha_from_coordinate), 256 x 256 nodes (16 in quick mode).
    const int nodes = options.quick ? 16 : 256;
    tables.reference =
        table_with_2d_size(reference_table_size, options.cache_directory, "lut_2d_reference_" + std::to_string(nodes),
                           [&](const double mu, const double r, std::size_t) {
                               return ggx_albedo_quadrature(lut_mu_from_coordinate(mu), lut_alpha_from_coordinate(r), nodes);
                           });
    accuracy_lut_values_16 = tables.size_16.data();
    accuracy_lut_values_64 = tables.size_64.data();
    accuracy_lut_values_reference = tables.reference.data();
    tables.halves.resize(OPENPBR_LUT_TOTAL_COUNT);
    for (std::size_t i = 0; i < tables.halves.size(); ++i)
    {
        tables.halves[i] = glm::packHalf1x16(openpbr_lut_data[i]);
    }
    accuracy_set_half_table(tables.halves.data());
    accuracy_set_buffer_table(openpbr_lut_data);
    return tables;
}

std::vector<std::byte> table_bytes(const StudyTables& tables, const AccuracyTable table)
{
    switch (table)
    {
    case AccuracyTable::size_16: return float_bytes(tables.size_16);
    case AccuracyTable::size_64: return float_bytes(tables.size_64);
    case AccuracyTable::reference: return float_bytes(tables.reference);
    case AccuracyTable::half:
    {
        // Two halves per 32-bit word, the first in the low bits (OPENPBR_LUT_16BIT).
        std::vector<std::uint32_t> words((tables.halves.size() + 1) / 2, 0u);
        for (std::size_t i = 0; i < tables.halves.size(); ++i)
        {
            words[i / 2] |= std::uint32_t(tables.halves[i]) << (16 * (i % 2));
        }
        std::vector<std::byte> bytes(words.size() * sizeof(std::uint32_t));
        std::memcpy(bytes.data(), words.data(), bytes.size());
        return bytes;
    }
    case AccuracyTable::shipped: break;
    }
    return float_bytes(std::vector<float>(openpbr_lut_data, openpbr_lut_data + OPENPBR_LUT_TOTAL_COUNT));
}

// ---- Errors ------------------------------------------------------------------------------------

RelativeErrors relative_errors(const std::vector<float>& values, const std::vector<float>& reference)
{
    std::vector<double> errors;
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        if (std::abs(reference[i]) > 1e-3f)
        {
            errors.push_back(std::abs(double(values[i]) - reference[i]) / std::abs(double(reference[i])));
        }
    }
    RelativeErrors result;
    if (errors.empty())
    {
        return result;
    }
    std::sort(errors.begin(), errors.end());
    const auto at = [&](const double fraction) {
        return errors[std::min(errors.size() - 1, std::size_t(fraction * double(errors.size())))];
    };
    result.median = at(0.5);
    result.p99 = at(0.99);
    result.max = errors.back();
    return result;
}

// ---- CPU timing --------------------------------------------------------------------------------

std::size_t CpuTimer::add(const BsdfVariant& variant, const Workload& workload, const Operation operation)
{
    for (std::size_t i = 0; i < jobs_.size(); ++i)
    {
        if (jobs_[i].variant == &variant && jobs_[i].workload == &workload && jobs_[i].operation == operation)
        {
            return i;
        }
    }
    if (chunks_.find(&workload) == chunks_.end())
    {
        std::vector<std::vector<AccuracyQuery>>& chunks = chunks_[&workload];
        for (std::size_t begin = 0; begin < workload.queries.size(); begin += timing_chunk)
        {
            const std::size_t end = std::min(workload.queries.size(), begin + timing_chunk);
            chunks.emplace_back(workload.queries.begin() + std::ptrdiff_t(begin),
                                workload.queries.begin() + std::ptrdiff_t(end));
        }
    }
    jobs_.push_back(Job{&variant, &workload, operation, {}});
    return jobs_.size() - 1;
}

void CpuTimer::run(const int rounds, ProgressReporter& progress)
{
    std::vector<float> scratch(3 * timing_chunk);
    for (int round = 0; round < rounds; ++round)
    {
        for (Job& job : jobs_)
        {
            const auto call = job.operation == Operation::eval ? job.variant->eval : job.variant->sample;
            double seconds = 0.0;
            for (const std::vector<AccuracyQuery>& chunk : chunks_.at(job.workload))
            {
                double best = std::numeric_limits<double>::infinity();
                for (int attempt = 0; attempt < 3; ++attempt)
                {
                    const Stopwatch stopwatch;
                    call(job.workload->packed.data(), chunk, scratch.data());
                    best = std::min(best, stopwatch.seconds());
                }
                seconds += best;
            }
            job.ns.push_back(seconds * 1e9 / double(job.workload->queries.size()));
        }
        progress.begin_step("CPU timings, round " + std::to_string(round + 1) + " of " + std::to_string(rounds));
    }
}

AccuracyTime CpuTimer::time(const std::size_t job) const
{
    std::vector<double> ns = jobs_.at(job).ns;
    AccuracyTime time;
    if (ns.empty())
    {
        return time;
    }
    std::sort(ns.begin(), ns.end());
    time.best = ns.front();
    time.median = ns[ns.size() / 2];
    return time;
}

}  // namespace accuracy
}  // namespace openpbr::host
