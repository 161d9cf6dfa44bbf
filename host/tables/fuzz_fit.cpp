// fuzz_fit.cpp - see fuzz_fit.h for the model, the conventions and the table layout.
#include "host/tables/fuzz_fit.h"
#include "host/support/files.h"
#include "host/support/progress.h"
#include "host/support/random.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace openpbr::host {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr int fuzz_max_scattering = 100000;  // a walk this long is counted as absorbed

// Uniform double in [0, 1) from the top 53 bits of a 64-bit Mersenne Twister output
// (std::mt19937_64 is specified exactly by the standard, so streams are portable).
class UniformSource
{
  public:
    explicit UniformSource(std::uint64_t seed) : engine_(seed) {}
    double next() { return double(engine_() >> 11) * 0x1.0p-53; }

  private:
    std::mt19937_64 engine_;
};

// Orthonormal basis around a unit vector n (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited", JCGT 6(1)).
void orthonormal_basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b)
{
    const double sign = std::copysign(1.0, n.z);
    const double p = -1.0 / (sign + n.z);
    const double q = n.x * n.y * p;
    t = glm::dvec3(1.0 + sign * n.x * n.x * p, sign * q, -sign * n.x);
    b = glm::dvec3(q, sign + n.y * n.y * p, -n.y);
}

glm::dvec3 normalized(const glm::dvec3& v) { return v / std::sqrt(glm::dot(v, v)); }

}  // namespace

double fuzz_mu_from_coordinate(double c) { return std::clamp(c, 0.0, 1.0); }
double fuzz_alpha_from_coordinate(double c) { return std::clamp(c, 0.0, 1.0); }
double fuzz_cross_section_from_roughness(double alpha)
{
    const double clamped = std::clamp(alpha, 0.0, 1.0);
    return std::max(clamped * clamped, fuzz_min_cross_section);
}
// Per-cell seeds: SplitMix64 over the seed and the cell index.
std::uint64_t fuzz_cell_seed(std::uint64_t seed, std::size_t cell)
{
    return splitmix64(splitmix64(seed) ^ std::uint64_t(cell));
}

// SGGX (Heitz et al. 2015) with S = diag(1, 1, c^2), c = cross_section: sigma(w) = sqrt(w^T S w),
// D(m) = 1 / (pi sqrt(det S) (m^T S^-1 m)^2).
double fuzz_sggx_projected_area(const glm::dvec3& w, double cross_section)
{
    return std::sqrt(w.x * w.x + w.y * w.y + cross_section * cross_section * w.z * w.z);
}

double fuzz_sggx_normal_density(const glm::dvec3& m, double cross_section)
{
    const double q = m.x * m.x + m.y * m.y + m.z * m.z / (cross_section * cross_section);
    return 1.0 / (pi * cross_section * q * q);
}

// The SGGX distribution is the normal distribution of the ellipsoid with semi-axes S^-1/2 =
// diag(1, 1, 1/c) (Heitz et al. 2015, section 3). Visible normals: the linear map
// A^-1 = diag(1, 1, c) takes the ellipsoid to the unit sphere and rays along w to rays
// along A^-1 w, preserving uniform density over the projected area; the sphere's visible
// normals are cosine-distributed about the (mapped) direction, and a sphere normal n' maps
// back to the ellipsoid normal A^-T n' = A^-1 n'. This is the same distribution as the
// paper's Appendix algorithm, written through the ellipsoid.
glm::dvec3 fuzz_sggx_sample_visible_normal(const glm::dvec3& w, double cross_section, double u1, double u2)
{
    const glm::dvec3 w_sphere = normalized(glm::dvec3(w.x, w.y, cross_section * w.z));
    glm::dvec3 t;
    glm::dvec3 b;
    orthonormal_basis(w_sphere, t, b);
    const double radius = std::sqrt(u1);
    const double phi = 2.0 * pi * u2;
    const double z = std::sqrt(std::max(1.0 - u1, 0.0));
    const glm::dvec3 n_sphere = t * (radius * std::cos(phi)) + b * (radius * std::sin(phi)) + w_sphere * z;
    return normalized(glm::dvec3(n_sphere.x, n_sphere.y, cross_section * n_sphere.z));
}

double fuzz_phase_density(const glm::dvec3& wi, const glm::dvec3& wo, const double cross_section)
{
    const glm::dvec3 h_sum = wi + wo;
    const double length_squared = glm::dot(h_sum, h_sum);
    if (length_squared <= 0.0)
    {
        return 0.0;
    }
    const glm::dvec3 h = h_sum / std::sqrt(length_squared);
    return fuzz_sggx_normal_density(h, cross_section) / (4.0 * fuzz_sggx_projected_area(wi, cross_section));
}

glm::dvec3 fuzz_phase_sample(const glm::dvec3& wi, double cross_section, double u1, double u2)
{
    const glm::dvec3 m = fuzz_sggx_sample_visible_normal(wi, cross_section, u1, u2);
    return normalized(2.0 * glm::dot(wi, m) * m - wi);
}

double fuzz_ltc_density(double a, double b, const glm::dvec3& w)
{
    if (w.z <= 0.0)
    {
        return 0.0;
    }
    // v = M^-1 w = (a wx + b wz, a wy, wz); D = cos(v) / pi * |det M^-1| / |v|^3 = a^2 wz / (pi |v|^4).
    const double x = a * w.x + b * w.z;
    const double q = x * x + a * a * w.y * w.y + w.z * w.z;
    return w.z * a * a / (pi * q * q);
}

double FuzzSimulation::bin_solid_angle() const { return 2.0 * pi / (double(mu_bins) * double(phi_bins)); }

FuzzSimulation simulate_fuzz_layer(double mu_o, double cross_section, std::uint64_t photons, int mu_bins, int phi_bins,
                                   std::uint64_t seed)
{
    if (mu_bins < 1 || phi_bins < 1 || !(cross_section > 0.0 && cross_section <= 1.0) || !(mu_o >= 0.0 && mu_o <= 1.0))
    {
        throw std::invalid_argument("simulate_fuzz_layer: bins must be >= 1, cross_section in (0, 1], mu_o in [0, 1]");
    }
    FuzzSimulation result;
    result.mu_o = mu_o;
    result.cross_section = cross_section;
    result.photons = photons;
    result.mu_bins = mu_bins;
    result.phi_bins = phi_bins;
    result.histogram.assign(std::size_t(mu_bins) * std::size_t(phi_bins), 0);
    UniformSource random(seed);
    const glm::dvec3 start_direction(-std::sqrt(std::max(1.0 - mu_o * mu_o, 0.0)), 0.0, -mu_o);
    for (std::uint64_t photon = 0; photon < photons; ++photon)
    {
        // The slab is z in [-1, 0]; light enters at the top (z = 0) travelling along -wo.
        glm::dvec3 direction = start_direction;
        double z = 0.0;
        for (int event = 0;; ++event)
        {
            const double sigma = fuzz_sggx_projected_area(direction, cross_section);
            const double distance = -std::log(1.0 - random.next()) / sigma;
            const double z_next = z + distance * direction.z;
            if (z_next > 0.0)
            {
                // Left through the top: record the exit direction (= wi of the BSDF).
                const double phi = std::atan2(std::abs(direction.y), direction.x);
                const int mu_bin = std::min(int(direction.z * mu_bins), mu_bins - 1);
                const int phi_bin = std::min(int(phi / pi * phi_bins), phi_bins - 1);
                ++result.histogram[std::size_t(mu_bin) * std::size_t(phi_bins) + std::size_t(phi_bin)];
                ++result.reflected;
                break;
            }
            if (z_next < -1.0)
            {
                break;  // reached the black base
            }
            if (event >= fuzz_max_scattering)
            {
                ++result.capped;
                break;
            }
            z = z_next;
            const double u1 = random.next();
            const double u2 = random.next();
            direction = fuzz_phase_sample(-direction, cross_section, u1, u2);
        }
    }
    return result;
}

namespace {

// Sub-sample points of the histogram bins (midpoint rule, sub x sub per bin) as arrays.
struct BinPoints
{
    int bins = 0;
    int per_bin = 0;
    std::vector<double> x, y, z;
};

BinPoints make_bin_points(int mu_bins, int phi_bins, int sub)
{
    BinPoints points;
    points.bins = mu_bins * phi_bins;
    points.per_bin = sub * sub;
    const std::size_t total = std::size_t(points.bins) * std::size_t(points.per_bin);
    points.x.reserve(total);
    points.y.reserve(total);
    points.z.reserve(total);
    for (int i = 0; i < mu_bins; ++i)
    {
        for (int j = 0; j < phi_bins; ++j)
        {
            for (int si = 0; si < sub; ++si)
            {
                for (int sj = 0; sj < sub; ++sj)
                {
                    const double mu = (double(i) + (double(si) + 0.5) / sub) / mu_bins;
                    const double phi = (double(j) + (double(sj) + 0.5) / sub) / phi_bins * pi;
                    const double s = std::sqrt(std::max(1.0 - mu * mu, 0.0));
                    points.x.push_back(s * std::cos(phi));
                    points.y.push_back(s * std::sin(phi));
                    points.z.push_back(mu);
                }
            }
        }
    }
    return points;
}

// Bin averages of the LTC density, written into `out` (points.bins values).
void ltc_bin_averages(const BinPoints& points, double a, double b, std::vector<double>& out)
{
    out.assign(std::size_t(points.bins), 0.0);
    const double a2 = a * a;
    const double scale = a2 / (pi * points.per_bin);
    std::size_t k = 0;
    for (int bin = 0; bin < points.bins; ++bin)
    {
        double sum = 0.0;
        for (int s = 0; s < points.per_bin; ++s, ++k)
        {
            const double x = a * points.x[k] + b * points.z[k];
            const double q = x * x + a2 * points.y[k] * points.y[k] + points.z[k] * points.z[k];
            sum += points.z[k] / (q * q);
        }
        out[std::size_t(bin)] = sum * scale;
    }
}

constexpr double log_a_min = -6.907755278982137;  // log(1e-3)
constexpr double log_a_max = 2.302585092994046;   // log(10)
constexpr double b_limit = 10.0;

// Nelder & Mead 1965 downhill simplex in n <= 2 dimensions with the usual coefficients
// (reflection 1, expansion 2, contraction 1/2, shrink 1/2).
template <typename Function>
std::array<double, 2> nelder_mead(const Function& f, std::array<double, 2> start, std::array<double, 2> step, int n,
                                  int max_evaluations)
{
    std::array<std::array<double, 2>, 3> vertex;
    std::array<double, 3> value;
    for (int i = 0; i <= n; ++i)
    {
        vertex[std::size_t(i)] = start;
        if (i > 0)
        {
            vertex[std::size_t(i)][std::size_t(i - 1)] += step[std::size_t(i - 1)];
        }
        value[std::size_t(i)] = f(vertex[std::size_t(i)]);
    }
    int evaluations = n + 1;
    while (evaluations < max_evaluations)
    {
        // Order: best first.
        std::array<int, 3> order = {0, 1, 2};
        std::sort(order.begin(), order.begin() + n + 1,
                  [&](int l, int r) { return value[std::size_t(l)] < value[std::size_t(r)]; });
        std::array<std::array<double, 2>, 3> sorted_vertex;
        std::array<double, 3> sorted_value;
        for (int i = 0; i <= n; ++i)
        {
            sorted_vertex[std::size_t(i)] = vertex[std::size_t(order[std::size_t(i)])];
            sorted_value[std::size_t(i)] = value[std::size_t(order[std::size_t(i)])];
        }
        vertex = sorted_vertex;
        value = sorted_value;
        double size = 0.0;
        for (int i = 1; i <= n; ++i)
        {
            for (int d = 0; d < n; ++d)
            {
                size = std::max(size, std::abs(vertex[std::size_t(i)][std::size_t(d)] - vertex[0][std::size_t(d)]));
            }
        }
        if (size < 1e-6 || value[std::size_t(n)] - value[0] <= 1e-12 * std::abs(value[0]))
        {
            break;
        }
        std::array<double, 2> centroid = {0.0, 0.0};
        for (int i = 0; i < n; ++i)
        {
            for (int d = 0; d < n; ++d)
            {
                centroid[std::size_t(d)] += vertex[std::size_t(i)][std::size_t(d)] / n;
            }
        }
        const auto along = [&](double t) {
            std::array<double, 2> p = centroid;
            for (int d = 0; d < n; ++d)
            {
                p[std::size_t(d)] += t * (vertex[std::size_t(n)][std::size_t(d)] - centroid[std::size_t(d)]);
            }
            return p;
        };
        const std::array<double, 2> reflected = along(-1.0);
        const double reflected_value = f(reflected);
        ++evaluations;
        if (reflected_value < value[0])
        {
            const std::array<double, 2> expanded = along(-2.0);
            const double expanded_value = f(expanded);
            ++evaluations;
            if (expanded_value < reflected_value)
            {
                vertex[std::size_t(n)] = expanded;
                value[std::size_t(n)] = expanded_value;
            }
            else
            {
                vertex[std::size_t(n)] = reflected;
                value[std::size_t(n)] = reflected_value;
            }
            continue;
        }
        if (reflected_value < value[std::size_t(n - 1)])
        {
            vertex[std::size_t(n)] = reflected;
            value[std::size_t(n)] = reflected_value;
            continue;
        }
        const bool outside = reflected_value < value[std::size_t(n)];
        const std::array<double, 2> contracted = along(outside ? -0.5 : 0.5);
        const double contracted_value = f(contracted);
        ++evaluations;
        if (contracted_value < std::min(reflected_value, value[std::size_t(n)]))
        {
            vertex[std::size_t(n)] = contracted;
            value[std::size_t(n)] = contracted_value;
            continue;
        }
        for (int i = 1; i <= n; ++i)
        {
            for (int d = 0; d < n; ++d)
            {
                vertex[std::size_t(i)][std::size_t(d)] =
                    0.5 * (vertex[0][std::size_t(d)] + vertex[std::size_t(i)][std::size_t(d)]);
            }
            value[std::size_t(i)] = f(vertex[std::size_t(i)]);
            ++evaluations;
        }
    }
    int best = 0;
    for (int i = 1; i <= n; ++i)
    {
        if (value[std::size_t(i)] < value[std::size_t(best)])
        {
            best = i;
        }
    }
    return vertex[std::size_t(best)];
}

// Histogram densities p_b = count_b / (reflected * bin solid angle).
std::vector<double> histogram_densities(const FuzzSimulation& simulation)
{
    std::vector<double> density(simulation.histogram.size(), 0.0);
    if (simulation.reflected == 0)
    {
        return density;
    }
    const double scale = 1.0 / (double(simulation.reflected) * simulation.bin_solid_angle());
    for (std::size_t i = 0; i < density.size(); ++i)
    {
        density[i] = double(simulation.histogram[i]) * scale;
    }
    return density;
}

void fill_errors(const FuzzSimulation& simulation, const std::vector<double>& target, const std::vector<double>& ltc,
                 FuzzLtcFit& fit)
{
    double squared_error = 0.0;
    double squared_target = 0.0;
    double absolute = 0.0;
    const double omega = simulation.bin_solid_angle();
    for (std::size_t i = 0; i < target.size(); ++i)
    {
        squared_error += (ltc[i] - target[i]) * (ltc[i] - target[i]);
        squared_target += target[i] * target[i];
        absolute += std::abs(ltc[i] - target[i]) * omega;
    }
    fit.relative_l2_error = squared_target > 0.0 ? std::sqrt(squared_error / squared_target) : 0.0;
    fit.total_variation = 0.5 * absolute;
    double noise = 0.0;
    for (const std::uint64_t count : simulation.histogram)
    {
        noise += std::sqrt(2.0 * double(count) / pi);
    }
    fit.noise_total_variation = simulation.reflected ? 0.5 * noise / double(simulation.reflected) : 0.0;
}

constexpr int fit_subsamples = 3;  // midpoint rule with 3 x 3 points per bin

}  // namespace

FuzzLtcFit evaluate_fuzz_ltc(const FuzzSimulation& simulation, double a, double b)
{
    FuzzLtcFit fit;
    fit.a = a;
    fit.b = b;
    fit.fitted = simulation.reflected >= fuzz_min_fit_count;
    const BinPoints points = make_bin_points(simulation.mu_bins, simulation.phi_bins, fit_subsamples);
    std::vector<double> ltc;
    ltc_bin_averages(points, a, b, ltc);
    fill_errors(simulation, histogram_densities(simulation), ltc, fit);
    return fit;
}

FuzzLtcFit fit_fuzz_ltc(const FuzzSimulation& simulation, bool symmetric)
{
    FuzzLtcFit fit;
    if (simulation.reflected < fuzz_min_fit_count)
    {
        return fit;  // (1, 0), fitted = false
    }
    const std::vector<double> target = histogram_densities(simulation);
    const auto objective_with = [&](const BinPoints& points, std::vector<double>& scratch, double log_a, double b) {
        const double clamped_log_a = std::clamp(log_a, log_a_min, log_a_max);
        const double clamped_b = symmetric ? 0.0 : std::clamp(b, -b_limit, b_limit);
        ltc_bin_averages(points, std::exp(clamped_log_a), clamped_b, scratch);
        double sum = 0.0;
        for (std::size_t i = 0; i < target.size(); ++i)
        {
            sum += (scratch[i] - target[i]) * (scratch[i] - target[i]);
        }
        // Leaving the box costs a penalty that grows with the distance.
        const double outside = std::abs(log_a - clamped_log_a) + (symmetric ? 0.0 : std::abs(b - clamped_b));
        return sum * (1.0 + outside);
    };
    // Coarse grid search with one point per bin.
    const BinPoints centres = make_bin_points(simulation.mu_bins, simulation.phi_bins, 1);
    std::vector<double> scratch;
    double best_log_a = 0.0;
    double best_b = 0.0;
    double best_value = std::numeric_limits<double>::infinity();
    const int b_steps = symmetric ? 0 : 20;
    for (int i = 0; i <= 40; ++i)
    {
        const double log_a = -5.0 + 6.0 * double(i) / 40.0;  // a in [0.0067, 2.7]
        for (int j = -b_steps; j <= b_steps; ++j)
        {
            const double b = 0.075 * double(j);  // b in [-1.5, 1.5]
            const double value = objective_with(centres, scratch, log_a, b);
            if (value < best_value)
            {
                best_value = value;
                best_log_a = log_a;
                best_b = b;
            }
        }
    }
    // Refinement with 3 x 3 points per bin.
    const BinPoints points = make_bin_points(simulation.mu_bins, simulation.phi_bins, fit_subsamples);
    const auto objective = [&](const std::array<double, 2>& p) { return objective_with(points, scratch, p[0], p[1]); };
    const std::array<double, 2> best = nelder_mead(objective, {best_log_a, best_b}, {0.1, 0.1}, symmetric ? 1 : 2, 400);
    fit.a = std::exp(std::clamp(best[0], log_a_min, log_a_max));
    fit.b = symmetric ? 0.0 : std::clamp(best[1], -b_limit, b_limit);
    fit.fitted = true;
    std::vector<double> ltc;
    ltc_bin_averages(points, fit.a, fit.b, ltc);
    fill_errors(simulation, target, ltc, fit);
    return fit;
}

FuzzCellReport generate_fuzz_cell(const FuzzFitOptions& options, int mu_index, int alpha_index)
{
    const int n = options.size;
    if (n < 2 || mu_index < 0 || mu_index >= n || alpha_index < 0 || alpha_index >= n)
    {
        throw std::invalid_argument("generate_fuzz_cell: size must be >= 2 and the indices inside the grid");
    }
    FuzzCellReport cell;
    cell.mu_o = fuzz_mu_from_coordinate(double(mu_index) / double(n - 1));
    cell.alpha = fuzz_alpha_from_coordinate(double(alpha_index) / double(n - 1));
    cell.cross_section = fuzz_cross_section_from_roughness(cell.alpha);
    const std::size_t cell_index = std::size_t(alpha_index) * std::size_t(n) + std::size_t(mu_index);
    const FuzzSimulation simulation =
        simulate_fuzz_layer(cell.mu_o, cell.cross_section, options.photons, options.histogram_mu_bins,
                            options.histogram_phi_bins, fuzz_cell_seed(options.seed, cell_index));
    cell.reflected_fraction = simulation.reflected_fraction();
    cell.fit = fit_fuzz_ltc(simulation, mu_index == n - 1);
    return cell;
}

std::vector<float> generate_fuzz_table(const FuzzFitOptions& options, std::vector<FuzzCellReport>* report)
{
    const int n = options.size;
    if (n < 2 || n > 512 || options.photons == 0 || options.threads < 0 || options.histogram_mu_bins < 1 ||
        options.histogram_phi_bins < 1)
    {
        throw std::invalid_argument("generate_fuzz_table: size in [2, 512], photons > 0, threads >= 0, bins >= 1");
    }
    std::unique_ptr<tbb::global_control> limit;
    if (options.threads > 0)
    {
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      std::size_t(options.threads));
    }
    const std::size_t cells = std::size_t(n) * std::size_t(n);
    std::vector<FuzzCellReport> results(cells);
    // Forced on (--progress): a line per 10 % in a log, the bar on a terminal.
    ProgressReporter progress(cells, options.progress, "fuzz fit");
    // Largest alpha first: those walks are the longest, so the load balances better.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k != range.end(); ++k)
        {
            const std::size_t cell = cells - 1 - k;
            results[cell] = generate_fuzz_cell(options, int(cell % std::size_t(n)), int(cell / std::size_t(n)));
            progress.advance();
        }
    });
    progress.finish();
    const std::size_t channel = cells;
    std::vector<float> table(std::size_t(fuzz_ltc_channel_count) * channel, 0.0f);
    for (int mu_index = 0; mu_index < n; ++mu_index)
    {
        // Unfitted cells take the shape of the nearest fitted cell of higher alpha.
        double fill_a = 1.0;
        double fill_b = 0.0;
        for (int alpha_index = n - 1; alpha_index >= 0; --alpha_index)
        {
            const std::size_t cell = std::size_t(alpha_index) * std::size_t(n) + std::size_t(mu_index);
            const FuzzCellReport& result = results[cell];
            if (result.fit.fitted)
            {
                fill_a = result.fit.a;
                fill_b = result.fit.b;
            }
            table[cell] = float(result.fit.fitted ? result.fit.a : fill_a);
            table[channel + cell] = float(result.fit.fitted ? result.fit.b : fill_b);
            table[2 * channel + cell] = float(result.reflected_fraction);
        }
    }
    if (report)
    {
        *report = std::move(results);
    }
    return table;
}

void write_fuzz_values_inc(const std::filesystem::path& path, const std::vector<float>& data, const std::string& comment)
{
    std::string text;
    std::istringstream comment_lines(comment);
    for (std::string line; std::getline(comment_lines, line);)
    {
        text += "// " + line + "\n";
    }
    char buffer[64];
    for (std::size_t i = 0; i < data.size(); ++i)
    {
        if (!std::isfinite(data[i]))
        {
            throw std::runtime_error("write_fuzz_values_inc: non-finite value at index " + std::to_string(i));
        }
        std::snprintf(buffer, sizeof(buffer), "%.8ef%s\n", double(data[i]), i + 1 < data.size() ? "," : "");
        text += buffer;
    }
    write_file_atomically(path, text);
}

std::vector<float> read_fuzz_values_inc(const std::filesystem::path& path)
{
    std::istringstream lines(read_whole_file(path));
    std::vector<float> values;
    int line_number = 0;
    for (std::string line; std::getline(lines, line);)
    {
        ++line_number;
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line.compare(first, 2, "//") == 0)
        {
            continue;
        }
        const char* begin = line.c_str() + first;
        char* end = nullptr;
        const float value = std::strtof(begin, &end);
        if (end == begin)
        {
            throw std::runtime_error("'" + path.string() + "' line " + std::to_string(line_number) + ": not a float");
        }
        std::string rest(end);
        rest.erase(std::remove_if(rest.begin(), rest.end(), [](char c) { return c == ' ' || c == '\t' || c == '\r'; }),
                   rest.end());
        if (rest != "f," && rest != "f" && rest != "," && !rest.empty())
        {
            throw std::runtime_error("'" + path.string() + "' line " + std::to_string(line_number) + ": malformed value");
        }
        values.push_back(value);
    }
    return values;
}

std::vector<float> read_fuzz_binary(const std::filesystem::path& path, std::size_t expected_count)
{
    const std::string bytes = read_whole_file(path);
    if (bytes.size() % 4 != 0 || (expected_count != 0 && bytes.size() != expected_count * 4))
    {
        throw std::runtime_error("'" + path.string() + "': unexpected size " + std::to_string(bytes.size()));
    }
    return floats_from_float32_little_endian(bytes, path);
}

}  // namespace openpbr::host
