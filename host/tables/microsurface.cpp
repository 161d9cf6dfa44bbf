// microsurface.cpp - see microsurface.h. Double precision throughout; no shader code.
#include "host/tables/microsurface.h"
#include "host/support/files.h"
#include "host/support/random.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

namespace openpbr::host {
namespace {

struct Vector
{
    double x = 0.0, y = 0.0, z = 0.0;
};
Vector operator+(const Vector& a, const Vector& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vector operator-(const Vector& a, const Vector& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vector operator*(const Vector& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Vector operator-(const Vector& a) { return {-a.x, -a.y, -a.z}; }
double dot(const Vector& a, const Vector& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vector normalized(const Vector& a) { return a * (1.0 / std::sqrt(dot(a, a))); }

constexpr double pi = 3.14159265358979323846;

// Smith Lambda of GGX for a direction of either hemisphere (depends on |tan theta| and, when
// anisotropic, on the azimuth through the stretched slope).
double smith_lambda(const Vector& w, double alpha_x, double alpha_y)
{
    const double z2 = w.z * w.z;
    if (z2 <= 0.0)
    {
        return std::numeric_limits<double>::infinity();
    }
    const double stretched = alpha_x == alpha_y ? alpha_x * alpha_x * (w.x * w.x + w.y * w.y)
                                                : alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y;
    return 0.5 * (std::sqrt(1.0 + stretched / z2) - 1.0);
}

double smith_lambda(const Vector& w, double alpha) { return smith_lambda(w, alpha, alpha); }

// A normal visible from direction `from` (any hemisphere; Dupuy & Benyoub 2023 cap, see header).
Vector sample_visible_normal(const Vector& from, double alpha_x, double alpha_y, double u1, double u2)
{
    const Vector from_std = normalized({from.x * alpha_x, from.y * alpha_y, from.z});
    const double phi = 2.0 * pi * u1;
    const double z = (1.0 - u2) * (1.0 + from_std.z) - from_std.z;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vector h_std = Vector{sin_theta * std::cos(phi), sin_theta * std::sin(phi), z} + from_std;
    const Vector h = {h_std.x * alpha_x, h_std.y * alpha_y, std::max(h_std.z, 0.0)};
    const double length_squared = dot(h, h);
    return length_squared > 0.0 ? h * (1.0 / std::sqrt(length_squared)) : Vector{0.0, 0.0, 1.0};
}

Vector sample_visible_normal(const Vector& from, double alpha, double u1, double u2)
{
    return sample_visible_normal(from, alpha, alpha, u1, u2);
}

double fresnel_schlick(double f0, double cosine)
{
    const double m = 1.0 - std::clamp(cosine, 0.0, 1.0);
    return f0 + (1.0 - f0) * m * m * m * m * m;
}

Vector reflect_about(const Vector& from, const Vector& m) { return m * (2.0 * dot(from, m)) - from; }

// Refraction of the direction `from` (pointing away from the surface) through normal m into the
// medium of relative IOR eta; valid when not totally reflected.
Vector refract_about(const Vector& from, const Vector& m, double eta)
{
    const double cos_i = dot(from, m);
    const double sin_t_squared = (1.0 - cos_i * cos_i) / (eta * eta);
    const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin_t_squared));
    return normalized(from * (-1.0 / eta) + m * (cos_i / eta - cos_t));
}

void check_mu(double mu)
{
    if (!(mu > 0.0 && mu <= 1.0))
    {
        throw std::invalid_argument("microsurface: view cosine must be in (0, 1], got " + std::to_string(mu));
    }
}

// The Fresnel factors of the accuracy study's kinds.
class SchlickFresnel final : public MicrosurfaceFresnel
{
  public:
    explicit SchlickFresnel(double f0_value) : f0(f0_value) {}
    MicrosurfaceColor reflectance(double cos_incident, bool) const override
    {
        const double f = fresnel_schlick(f0, cos_incident);
        return {f, f, f};
    }

  private:
    double f0;
};

class DielectricFresnel final : public MicrosurfaceFresnel
{
  public:
    explicit DielectricFresnel(double eta_value) : eta(eta_value) {}
    MicrosurfaceColor reflectance(double cos_incident, bool from_above) const override
    {
        const double f = microsurface_fresnel_dielectric(cos_incident, from_above ? eta : 1.0 / eta);
        return {f, f, f};
    }

  private:
    double eta;
};

// The probability of reflecting at an event: F itself when grey (so a grey walk is exactly the
// single-channel one), the channels' mean otherwise.
double reflection_probability(const MicrosurfaceColor& f)
{
    return f[0] == f[1] && f[1] == f[2] ? f[0] : (f[0] + f[1] + f[2]) / 3.0;
}

}  // namespace

double microsurface_fresnel_dielectric(double cosine, double eta)
{
    const double c = std::clamp(cosine, 0.0, 1.0);
    const double sin_t_squared = (1.0 - c * c) / (eta * eta);
    if (sin_t_squared >= 1.0)
    {
        return 1.0;
    }
    const double cos_t = std::sqrt(1.0 - sin_t_squared);
    const double rs = (c - eta * cos_t) / (c + eta * cos_t);
    const double rp = (eta * c - cos_t) / (eta * c + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

MicrosurfaceScattering microsurface_scatter(const MicrosurfaceInterface& interface, const glm::dvec3& travel, int max_order,
                                            SplitMix64& random)
{
    const double alpha_x = std::max(interface.alpha_x, 1e-4);
    const double alpha_y = std::max(interface.alpha_y, 1e-4);
    const bool from_above = travel.z < 0.0;
    // The walk's frame has the light's side up: from below it is the interface turned over.
    const double flip = from_above ? 1.0 : -1.0;
    Vector ray = {travel.x * flip, travel.y * flip, travel.z * flip};
    double c1 = 1.0;  // C1 of the current height: start above the microsurface
    MicrosurfaceColor energy = {1.0, 1.0, 1.0};
    double eta = from_above ? interface.eta : 1.0 / interface.eta;
    bool upper = from_above;  // whether the walk is on the interface's upper side
    const int order_limit = max_order > 0 ? max_order : 1000;
    MicrosurfaceScattering result;
    for (int order = 0;; ++order)
    {
        // Next height along the ray.
        const double u = random.next_double();
        if (ray.z > 0.0)
        {
            const double lambda = smith_lambda(ray, alpha_x, alpha_y);
            // Escape with probability G1 = C1^Lambda, i.e. when 1 - u <= C1^Lambda.
            if (!(lambda > 0.0) || std::pow(c1, lambda) >= 1.0 - u)
            {
                const double side = upper ? 1.0 : -1.0;
                result.direction = glm::dvec3(ray.x * side, ray.y * side, ray.z * side);
                result.transmitted = upper != from_above;
                result.absorbed = false;
                result.weight = energy;
                return result;
            }
            c1 = c1 / std::pow(1.0 - u, 1.0 / lambda);
        }
        else if (ray.z < 0.0)
        {
            // Downwards Lambda(ray) = -1 - Lambda(-ray): the ray always hits.
            c1 = c1 * std::pow(1.0 - u, 1.0 / (1.0 + smith_lambda(ray, alpha_x, alpha_y)));
        }
        c1 = std::clamp(c1, 1e-300, 1.0);
        if (order >= order_limit)
        {
            return result;  // a further bounce: outside the kept orders
        }
        // Next direction.
        const Vector from = -ray;
        const double u1 = random.next_double();
        const double u2 = random.next_double();
        const Vector m = sample_visible_normal(from, alpha_x, alpha_y, u1, u2);
        const double cos_i = dot(from, m);
        if (!(cos_i > 0.0))
        {
            return result;  // measure-zero degenerate normal
        }
        if (interface.response == MicrosurfaceResponse::reflect)
        {
            if (interface.fresnel != nullptr)
            {
                const MicrosurfaceColor f = interface.fresnel->reflectance(cos_i, upper);
                for (int c = 0; c < 3; ++c)
                {
                    energy[c] *= f[c];
                }
            }
            ray = reflect_about(from, m);
            continue;
        }
        const MicrosurfaceColor f =
            interface.fresnel != nullptr
                ? interface.fresnel->reflectance(cos_i, upper)
                : MicrosurfaceColor{microsurface_fresnel_dielectric(cos_i, eta), microsurface_fresnel_dielectric(cos_i, eta),
                                    microsurface_fresnel_dielectric(cos_i, eta)};
        const double p = reflection_probability(f);
        const bool reflects =
            interface.response == MicrosurfaceResponse::reflect_or_refract ? random.next_double() < p : p >= 1.0;
        if (reflects)
        {
            if (interface.response == MicrosurfaceResponse::refract)
            {
                return result;  // total internal reflection: E_T0 counts no reflected energy
            }
            for (int c = 0; c < 3; ++c)
            {
                energy[c] = f[c] == p ? energy[c] : energy[c] * f[c] / p;
            }
            ray = reflect_about(from, m);
        }
        else
        {
            if (interface.response == MicrosurfaceResponse::reflect_or_refract)
            {
                for (int c = 0; c < 3; ++c)
                {
                    energy[c] = f[c] == p ? energy[c] : energy[c] * (1.0 - f[c]) / (1.0 - p);
                }
            }
            // Continue on the other side: negate heights and directions, invert eta.
            ray = -refract_about(from, m, eta);
            c1 = 1.0 - c1;  // C1(-h) = 1 - C1(h) for uniform heights
            eta = 1.0 / eta;
            upper = !upper;
        }
    }
}

namespace {

struct PathResult
{
    double reflected = 0.0;
    double transmitted = 0.0;
};

// One random walk of the accuracy study's kinds, through microsurface_scatter.
PathResult walk(const MicrosurfaceMaterial& material, const Vector& view, int max_order, SplitMix64& random)
{
    MicrosurfaceInterface interface;
    interface.alpha_x = material.alpha;
    interface.alpha_y = material.alpha;
    interface.eta = material.eta;
    const SchlickFresnel schlick(material.f0);
    const DielectricFresnel dielectric(material.eta);
    switch (material.kind)
    {
    case MicrosurfaceKind::conductor_white: interface.response = MicrosurfaceResponse::reflect; break;
    case MicrosurfaceKind::conductor_schlick:
        interface.response = MicrosurfaceResponse::reflect;
        interface.fresnel = &schlick;
        break;
    case MicrosurfaceKind::dielectric_reflect:
        interface.response = MicrosurfaceResponse::reflect;
        interface.fresnel = &dielectric;
        break;
    case MicrosurfaceKind::dielectric: interface.response = MicrosurfaceResponse::reflect_or_refract; break;
    case MicrosurfaceKind::dielectric_refract: interface.response = MicrosurfaceResponse::refract; break;
    }
    const MicrosurfaceScattering scattering =
        microsurface_scatter(interface, glm::dvec3(-view.x, -view.y, -view.z), max_order, random);
    PathResult result;
    if (!scattering.absorbed)
    {
        (scattering.transmitted ? result.transmitted : result.reflected) = scattering.weight[0];
    }
    return result;
}

}  // namespace

MicrosurfaceAlbedo microsurface_albedo(const MicrosurfaceMaterial& material, double mu, int max_order, std::uint64_t paths,
                                       std::uint64_t seed)
{
    check_mu(mu);
    if (paths == 0 || max_order < 0)
    {
        throw std::invalid_argument("microsurface_albedo: paths must be > 0 and max_order >= 0");
    }
    const Vector view{std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
    SplitMix64 random{seed * 0x632be59bd9b4e019ull + 0x8cb92ba72f3d8dd7ull};
    double sum_r = 0.0, sum_r2 = 0.0, sum_t = 0.0, sum_t2 = 0.0;
    for (std::uint64_t path = 0; path < paths; ++path)
    {
        const PathResult result = walk(material, view, max_order, random);
        sum_r += result.reflected;
        sum_r2 += result.reflected * result.reflected;
        sum_t += result.transmitted;
        sum_t2 += result.transmitted * result.transmitted;
    }
    const double n = double(paths);
    MicrosurfaceAlbedo albedo;
    albedo.reflected = sum_r / n;
    albedo.transmitted = sum_t / n;
    albedo.reflected_error = std::sqrt(std::max(0.0, sum_r2 / n - albedo.reflected * albedo.reflected) / n);
    albedo.transmitted_error = std::sqrt(std::max(0.0, sum_t2 / n - albedo.transmitted * albedo.transmitted) / n);
    return albedo;
}

double microsurface_single_scattering_albedo(const MicrosurfaceMaterial& material, double mu, int n)
{
    check_mu(mu);
    if (n < 1 || material.kind == MicrosurfaceKind::dielectric || material.kind == MicrosurfaceKind::dielectric_refract)
    {
        throw std::invalid_argument("microsurface_single_scattering_albedo: reflection kinds and n >= 1 only");
    }
    const double alpha = std::max(material.alpha, 1e-4);
    const Vector view{std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
    const double lambda_view = smith_lambda(view, alpha);
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; j < n; ++j)
        {
            const Vector m = sample_visible_normal(view, alpha, (i + 0.5) / n, (j + 0.5) / n);
            const double cos_i = dot(view, m);
            const Vector light = reflect_about(view, m);
            if (!(light.z > 0.0) || !(cos_i > 0.0))
            {
                continue;
            }
            const double f = material.kind == MicrosurfaceKind::conductor_white ? 1.0
                             : material.kind == MicrosurfaceKind::conductor_schlick
                                 ? fresnel_schlick(material.f0, cos_i)
                                 : microsurface_fresnel_dielectric(cos_i, material.eta);
            // Weight of a visible normal: F G2 / G1(view), G2 = 1 / (1 + Lambda_v + Lambda_l).
            sum += f * (1.0 + lambda_view) / (1.0 + lambda_view + smith_lambda(light, alpha));
        }
    }
    return sum / (double(n) * double(n));
}

namespace {

std::string cache_key(const MicrosurfaceQuery& query)
{
    char buffer[256];
    std::snprintf(buffer, sizeof(buffer), "k%d a%.9g f%.9g e%.9g mu%.9g o%d p%llu s%llu", int(query.material.kind),
                  query.material.alpha, query.material.f0, query.material.eta, query.mu, query.max_order,
                  static_cast<unsigned long long>(query.paths), static_cast<unsigned long long>(query.seed));
    return buffer;
}

}  // namespace

MicrosurfaceCache::MicrosurfaceCache(std::filesystem::path path) : file(std::move(path))
{
    if (file.empty() || !std::filesystem::exists(file))
    {
        return;
    }
    try
    {
        const nlohmann::json document = nlohmann::json::parse(read_whole_file(file));
        if (document.value("version", 0) != 1)
        {
            return;
        }
        for (const auto& [key, value] : document.at("entries").items())
        {
            entries[key] = MicrosurfaceAlbedo{value.at(0).get<double>(), value.at(1).get<double>(),
                                              value.at(2).get<double>(), value.at(3).get<double>()};
        }
    }
    catch (const std::exception&)
    {
        entries.clear();  // a damaged cache is recomputed, never trusted
    }
}

std::vector<MicrosurfaceAlbedo> MicrosurfaceCache::albedos(const std::vector<MicrosurfaceQuery>& queries)
{
    std::vector<MicrosurfaceAlbedo> results(queries.size());
    std::vector<std::size_t> missing;
    for (std::size_t i = 0; i < queries.size(); ++i)
    {
        const auto found = entries.find(cache_key(queries[i]));
        if (found != entries.end())
        {
            results[i] = found->second;
            ++hit_count;
        }
        else
        {
            missing.push_back(i);
        }
    }
    tbb::parallel_for(std::size_t(0), missing.size(), [&](std::size_t k) {
        const MicrosurfaceQuery& query = queries[missing[k]];
        results[missing[k]] = microsurface_albedo(query.material, query.mu, query.max_order, query.paths, query.seed);
    });
    for (const std::size_t i : missing)
    {
        entries[cache_key(queries[i])] = results[i];
    }
    miss_count += missing.size();
    dirty = dirty || !missing.empty();
    return results;
}

void MicrosurfaceCache::save() const
{
    if (file.empty() || !dirty)
    {
        return;
    }
    nlohmann::json document;
    document["version"] = 1;
    nlohmann::json& list = document["entries"];
    list = nlohmann::json::object();
    for (const auto& [key, value] : entries)
    {
        list[key] = {value.reflected, value.transmitted, value.reflected_error, value.transmitted_error};
    }
    if (file.has_parent_path())
    {
        std::filesystem::create_directories(file.parent_path());
    }
    write_file_atomically(file, document.dump() + "\n");
}

}  // namespace openpbr::host
