// Implementation of the statistical test machinery; see bsdf_statistics.h.
#include "tests/bsdf/bsdf_statistics.h"
#include "host/support/random.h"
#include "host/support/directional_albedo.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

namespace openpbr::testing {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

// SplitMix64 (host/support/random.h): turns consecutive seeds into unrelated 64-bit values.
std::uint64_t mix_seed(const std::uint64_t x) { return openpbr::host::splitmix64(x); }

// Point `index` of a shifted R3 sequence as the vec3 the samplers take.
glm::vec3 point_of(const openpbr::host::ShiftedR3Sequence& sequence, const std::uint64_t index)
{
    const std::array<float, 3> u = sequence.point(index);
    return glm::vec3(u[0], u[1], u[2]);
}

bool is_finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool is_non_negative(const glm::vec3& v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }
double max_component(const glm::vec3& v) { return std::max({double(v.x), double(v.y), double(v.z)}); }

// Splits [0, count) into chunks whose results do not depend on the number of threads.
struct ChunkPlan
{
    std::uint64_t count;
    std::uint64_t chunks;
    std::uint64_t begin(std::uint64_t chunk) const { return count * chunk / chunks; }
    std::uint64_t end(std::uint64_t chunk) const { return count * (chunk + 1) / chunks; }
};

ChunkPlan plan_chunks(std::uint64_t count)
{
    const std::uint64_t chunk_size = 8192;
    return ChunkPlan{count, std::max<std::uint64_t>(1, std::min<std::uint64_t>(256, (count + chunk_size - 1) / chunk_size))};
}

template <class Function> void parallel_for_index(std::uint64_t count, const Function& function)
{
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, count, 1), [&](const tbb::blocked_range<std::uint64_t>& range) {
        for (std::uint64_t i = range.begin(); i != range.end(); ++i)
        {
            function(i);
        }
    });
}

// Calls visit(index, u) for the indices of one chunk with independent uniform triples; chunk
// c of seed s always yields the same numbers.
template <class Visit>
void draw_independent_samples(RandomStream& rng, std::uint64_t begin, std::uint64_t end, const Visit& visit)
{
    for (std::uint64_t i = begin; i < end; ++i)
    {
        const float u0 = rng.next_float();
        const float u1 = rng.next_float();
        const float u2 = rng.next_float();
        visit(i, glm::vec3(u0, u1, u2));
    }
}

template <class Visit>
void for_each_independent_sample(std::uint64_t seed, std::uint64_t chunk, std::uint64_t begin, std::uint64_t end,
                                 const Visit& visit)
{
    RandomStream rng(mix_seed(seed), chunk);
    draw_independent_samples(rng, begin, end, visit);
}

std::string lobe_type_string(std::uint32_t lobe_type)
{
    std::ostringstream out;
    out << "id " << (lobe_type >> OPENPBR_LOBE_ID_SHIFT) << " [";
    const char* names[] = {"R", "T", "diffuse", "glossy", "delta"};
    bool first = true;
    for (int bit = 0; bit < 5; ++bit)
    {
        if ((lobe_type & (1u << bit)) != 0u)
        {
            out << (first ? "" : "|") << names[bit];
            first = false;
        }
    }
    out << "]";
    return out.str();
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Random numbers

RandomStream::RandomStream(const std::uint64_t seed, const std::uint64_t stream)
{
    generator_.state = openpbr::host::splitmix64(seed) ^ openpbr::host::splitmix64(~stream);
}

std::uint32_t RandomStream::next_uint() { return static_cast<std::uint32_t>(generator_.next_bits() >> 32); }

float RandomStream::next_float() { return openpbr::host::unit_float_from_bits(generator_.next_bits()); }

double RandomStream::next_double() { return generator_.next_double(); }

float to_unit_float(double x)
{
    const float largest_below_one = 0x1.fffffep-1f;
    const float f = static_cast<float>(x);
    return f < 0.0f ? 0.0f : (f > largest_below_one ? largest_below_one : f);
}

std::uint64_t seed_from_name(const std::string& name)
{
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (const char c : name)
    {
        hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
    }
    return hash;
}

// ------------------------------------------------------------------------------------------
// Targets

namespace {

// Share of delta samples of the prepared BSDF's dielectric lobe: below 1 only where its rough
// microfacets refract as a delta event (see dielectric_delta_share); a smooth lobe's samples
// are all delta.
double transmission_delta_share(const OpenPBR_PreparedBsdf& bsdf)
{
    const OpenPBR_DielectricLobe& lobe = bsdf.transmission;
    return bsdf.probability_transmission > 0.0f && lobe.transmission_is_delta && !lobe.is_delta
               ? dielectric_delta_share(lobe, bsdf.view)
               : 1.0;
}

double delta_probability_with(const OpenPBR_PreparedBsdf& bsdf, double transmission_share)
{
    // Keep in sync with the delta lobes of openpbr_sample: every lobe that can return an
    // OPENPBR_LOBE_TYPE_SPECULAR sample contributes its selection probability.
    // Lobes that are never delta (diffuse, diffuse transmission, fuzz) do not appear.
    double probability = bsdf.probability_pass_through;
    probability += bsdf.coat.is_delta ? bsdf.probability_coat : 0.0f;
    probability += bsdf.specular.is_delta ? bsdf.probability_specular : 0.0f;
    probability += bsdf.metal.is_delta ? bsdf.probability_metal : 0.0f;
    // The dielectric lobe's transmission is a delta also where its refracted lobe collapses
    // (eta near 1); its rough reflections (Fresnel) and its totally reflecting microfacets
    // then take the share of its samples that are not delta.
    if (transmission_share == 1.0)
    {
        probability += bsdf.transmission.transmission_is_delta ? bsdf.probability_transmission : 0.0f;
    }
    else
    {
        probability += bsdf.probability_transmission * transmission_share;
    }
    probability += bsdf.thin_transmission.is_delta ? bsdf.probability_thin_transmission : 0.0f;
    return probability;
}

// Pilot of the refracted lobe for the warped grid: mean direction and median angle from it of
// up to 4096 non-delta refracted samples (at most 65536 draws); false with fewer than 256.
bool refracted_lobe_axis(const SamplingTarget& target, std::uint32_t lobe_id, std::uint64_t seed, glm::dvec3& axis,
                         double& median_angle)
{
    RandomStream rng(mix_seed(seed), 0x9170u);
    std::vector<glm::dvec3> directions;
    glm::dvec3 sum(0.0);
    for (int draw = 0; draw < 65536 && directions.size() < 4096; ++draw)
    {
        const float u0 = rng.next_float();
        const float u1 = rng.next_float();
        const float u2 = rng.next_float();
        const DirectionSample s = target.sample(glm::vec3(u0, u1, u2));
        const std::uint32_t wanted = OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_GLOSSY;
        if ((s.lobe_type >> OPENPBR_LOBE_ID_SHIFT) == lobe_id && (s.lobe_type & wanted) == wanted && is_finite(s.direction))
        {
            directions.push_back(glm::normalize(glm::dvec3(s.direction)));
            sum += directions.back();
        }
    }
    if (directions.size() < 256 || !(glm::length(sum) > 0.0))
    {
        return false;
    }
    axis = glm::normalize(sum);
    std::vector<double> angles;
    angles.reserve(directions.size());
    for (const glm::dvec3& d : directions)
    {
        angles.push_back(std::atan2(glm::length(glm::cross(d, axis)), glm::dot(d, axis)));
    }
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    median_angle = angles[angles.size() / 2];
    return median_angle > 0.0;
}

}  // namespace

double delta_selection_probability(const OpenPBR_PreparedBsdf& bsdf)
{
    return delta_probability_with(bsdf, transmission_delta_share(bsdf));
}

double dielectric_delta_share(const OpenPBR_DielectricLobe& lobe, const glm::vec3& view)
{
    if (lobe.is_delta || !lobe.transmission_is_delta || !(view.z > 0.0f))
    {
        return 1.0;
    }
    // The deficit 1 - share is integrated (it is small: 3e-5 at relative IOR 0.99, roughness
    // 0.2, view cos 1), so the quadrature's relative error applies to it rather than to 1.
    const int channels = lobe.dispersive ? 3 : 1;
    double share = 0.0;
    for (int channel = 0; channel < channels; ++channel)
    {
        const float eta = lobe.eta[channel];
        if (eta == 1.0f)
        {
            share += 1.0;
            continue;
        }
        SamplingTarget deficit;
        deficit.name = "visible normals not refracting as a delta";
        deficit.frame = openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
        deficit.polar_scale = std::max(lobe.alpha.x, lobe.alpha.y);
        const glm::dvec3 o(view);
        deficit.pdf = [lobe, o, eta](const glm::vec3& h_float) {
            const glm::dvec3 h(h_float);
            const double o_dot_h = glm::dot(o, h);
            if (!(h.z > 0.0) || !(o_dot_h > 0.0))
            {
                return 0.0;
            }
            const double visible = double(lobe.g1_view) * o_dot_h * double(openpbr_ggx_d(h_float, lobe.alpha)) / o.z;
            const double f = lobe.with_fresnel ? double(openpbr_fresnel_dielectric(float(o_dot_h), eta)) : 0.0;
            // Snell's law through h: t = -o / eta + (o.h / eta - cos theta_t) h, none past the
            // critical angle; a refraction that leaves above the surface is no sample either.
            const double sin2_t = (1.0 - o_dot_h * o_dot_h) / (double(eta) * eta);
            bool refracts = sin2_t < 1.0;
            if (refracts)
            {
                const glm::dvec3 t = -o / double(eta) + (o_dot_h / eta - std::sqrt(1.0 - sin2_t)) * h;
                refracts = t.z < 0.0;
            }
            return visible * (refracts ? f : 1.0);
        };
        double missing = 0.0;
        for (const double cell : integrate_pdf_over_grid(deficit, SphereGridOptions()))
        {
            missing += cell;
        }
        share += 1.0 - missing;
    }
    return share / channels;
}

SamplingTarget make_bsdf_target(const OpenPBR_PreparedBsdf& bsdf, const std::string& name)
{
    SamplingTarget target;
    target.name = name;
    target.frame = bsdf.basis;
    const double transmission_share = transmission_delta_share(bsdf);
    target.delta_probability = delta_probability_with(bsdf, transmission_share);
    if (transmission_share != 1.0)
    {
        target.delta_share[bsdf.transmission.lobe_id] = transmission_share;
    }
    target.sample = [bsdf](const glm::vec3& u) {
        const OpenPBR_BsdfSample s = openpbr_sample(bsdf, u);
        DirectionSample result;
        result.direction = s.direction;
        result.weight = s.weight;
        result.pdf = s.pdf;
        result.lobe_type = s.lobe_type;
        return result;
    };
    target.pdf = [bsdf](const glm::vec3& direction) { return static_cast<double>(openpbr_pdf(bsdf, direction)); };
    target.eval = [bsdf](const glm::vec3& direction) { return openpbr_eval(bsdf, direction); };
    const OpenPBR_DielectricLobe& lobe = bsdf.transmission;
    glm::dvec3 axis;
    double median_angle = 0.0;
    if (bsdf.probability_transmission > 0.0f && !lobe.transmission_is_delta &&
        openpbr_dielectric_transmission_width(lobe.alpha, lobe.eta, bsdf.view.z) < kNarrowRefractionWidth &&
        refracted_lobe_axis(target, lobe.lobe_id, seed_from_name(name) ^ 0x70696c6f74ull, axis, median_angle))
    {
        target.frame = openpbr_make_basis(glm::vec3(axis));
        target.polar_scale = median_angle;
    }
    return target;
}

// ------------------------------------------------------------------------------------------
// Numerics

namespace {

// P(a, x) by its power series; converges quickly for x < a + 1.
double gamma_p_series(double a, double x)
{
    double term = 1.0 / a;
    double sum = term;
    double denominator = a;
    for (int n = 0; n < 100000; ++n)
    {
        denominator += 1.0;
        term *= x / denominator;
        sum += term;
        if (std::fabs(term) < std::fabs(sum) * 1e-16)
        {
            break;
        }
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by its continued fraction (modified Lentz); converges quickly for x >= a + 1.
double gamma_q_continued_fraction(double a, double x)
{
    const double tiny = 1e-300;
    double b = x + 1.0 - a;
    double c = 1.0 / tiny;
    double d = 1.0 / b;
    double h = d;
    for (int i = 1; i < 100000; ++i)
    {
        const double an = -static_cast<double>(i) * (static_cast<double>(i) - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny)
        {
            d = tiny;
        }
        c = b + an / c;
        if (std::fabs(c) < tiny)
        {
            c = tiny;
        }
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16)
        {
            break;
        }
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double regularized_gamma_p(double a, double x)
{
    if (!(a > 0.0) || std::isnan(x))
    {
        return std::numeric_limits<double>::quiet_NaN();
    }
    if (x <= 0.0)
    {
        return 0.0;
    }
    if (std::isinf(x))
    {
        return 1.0;
    }
    return x < a + 1.0 ? gamma_p_series(a, x) : 1.0 - gamma_q_continued_fraction(a, x);
}

double regularized_gamma_q(double a, double x)
{
    if (!(a > 0.0) || std::isnan(x))
    {
        return std::numeric_limits<double>::quiet_NaN();
    }
    if (x <= 0.0)
    {
        return 1.0;
    }
    if (std::isinf(x))
    {
        return 0.0;
    }
    return x < a + 1.0 ? 1.0 - gamma_p_series(a, x) : gamma_q_continued_fraction(a, x);
}

double chi_square_p_value(double statistic, int degrees_of_freedom)
{
    if (degrees_of_freedom <= 0)
    {
        return 1.0;
    }
    return regularized_gamma_q(0.5 * degrees_of_freedom, 0.5 * statistic);
}

double binomial_two_sided_p_value(std::uint64_t successes, std::uint64_t trials, double p)
{
    if (successes > trials || std::isnan(p))
    {
        return 0.0;
    }
    if (p <= 0.0)
    {
        return successes == 0 ? 1.0 : 0.0;
    }
    if (p >= 1.0)
    {
        return successes == trials ? 1.0 : 0.0;
    }
    const double n = static_cast<double>(trials);
    const double k = static_cast<double>(successes);
    const double mean = n * p;
    const double variance = n * p * (1.0 - p);
    if (variance >= 400.0)
    {
        // Normal approximation with continuity correction; skewness is below 0.05 here.
        const double z = std::max(std::fabs(k - mean) - 0.5, 0.0) / std::sqrt(variance);
        return std::erfc(z / std::sqrt(2.0));
    }
    // Exact: sum the pmf of every outcome no more likely than the observed one, over a window
    // of +-(40 sd + 20) around the mean and the observation (the rest is below 1e-300).
    const double log_p = std::log(p);
    const double log_q = std::log1p(-p);
    const double log_n_factorial = std::lgamma(n + 1.0);
    const auto log_pmf = [&](double j) {
        return log_n_factorial - std::lgamma(j + 1.0) - std::lgamma(n - j + 1.0) + j * log_p + (n - j) * log_q;
    };
    const double observed = log_pmf(k);
    const double half_width = 40.0 * std::sqrt(variance) + 20.0;
    const double low = std::max(0.0, std::floor(std::min(k, mean) - half_width));
    const double high = std::min(n, std::ceil(std::max(k, mean) + half_width));
    double sum = 0.0;
    for (double j = low; j <= high; j += 1.0)
    {
        const double value = log_pmf(j);
        if (value <= observed + 1e-7)
        {
            sum += std::exp(value);
        }
    }
    return std::min(sum, 1.0);
}

double sidak_significance(double family_significance, int test_count)
{
    return -std::expm1(std::log1p(-family_significance) / std::max(test_count, 1));
}

void gauss_legendre(int order, std::vector<double>& nodes, std::vector<double>& weights)
{
    nodes.assign(static_cast<std::size_t>(order), 0.0);
    weights.assign(static_cast<std::size_t>(order), 0.0);
    for (int i = 0; i < order; ++i)
    {
        double x = std::cos(kPi * (i + 0.75) / (order + 0.5));  // close to the i-th root
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration)
        {
            // P_order(x) and P_(order-1)(x) by the three-term recurrence.
            double p_previous = 1.0;
            double p = x;
            for (int j = 2; j <= order; ++j)
            {
                const double p_next = ((2.0 * j - 1.0) * x * p - (j - 1.0) * p_previous) / j;
                p_previous = p;
                p = p_next;
            }
            if (order == 1)
            {
                p_previous = 1.0;
                p = x;
            }
            derivative = order * (x * p - p_previous) / (x * x - 1.0);
            const double step = p / derivative;
            x -= step;
            if (std::fabs(step) < 1e-15)
            {
                break;
            }
        }
        nodes[static_cast<std::size_t>(i)] = x;
        weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
}

// ------------------------------------------------------------------------------------------
// Grid integration

glm::vec3 direction_in_basis(const OpenPBR_Basis& basis, double cos_theta, double phi)
{
    const double z = std::clamp(cos_theta, -1.0, 1.0);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double x = r * std::cos(phi);
    const double y = r * std::sin(phi);
    const glm::dvec3 t(basis.tangent);
    const glm::dvec3 b(basis.bitangent);
    const glm::dvec3 n(basis.normal);
    return glm::vec3(t * x + b * y + n * z);
}

namespace {

// The warped polar coordinate of SamplingTarget::polar_scale: theta = scale (exp(s L) - 1),
// L = log(1 + pi / scale), so s in [0, 1] covers theta in [0, pi];
// d omega = sin theta dtheta dphi = sin theta L (theta + scale) ds dphi.
struct PolarWarp
{
    double scale;
    double log_range;
    explicit PolarWarp(double polar_scale) : scale(polar_scale), log_range(std::log1p(kPi / polar_scale)) {}
    double theta(double s) const { return std::min(scale * std::expm1(s * log_range), kPi); }
    double coordinate(double angle) const { return std::log1p(angle / scale) / log_range; }
    double jacobian(double s) const
    {
        const double angle = theta(s);
        return std::sin(angle) * log_range * (angle + scale);
    }
};

glm::vec3 direction_at_polar_angle(const OpenPBR_Basis& basis, double theta, double phi)
{
    const double r = std::sin(theta);
    const glm::dvec3 d = glm::dvec3(basis.tangent) * (r * std::cos(phi)) +
                         glm::dvec3(basis.bitangent) * (r * std::sin(phi)) + glm::dvec3(basis.normal) * std::cos(theta);
    return glm::vec3(d);
}

}  // namespace

int grid_cell_of(const SamplingTarget& target, const SphereGridOptions& grid, const glm::vec3& direction)
{
    const glm::dvec3 d(direction);
    const double x = glm::dot(d, glm::dvec3(target.frame.tangent));
    const double y = glm::dot(d, glm::dvec3(target.frame.bitangent));
    const double z = glm::dot(d, glm::dvec3(target.frame.normal));
    double phi = std::atan2(y, x);
    if (phi < 0.0)
    {
        phi += kTwoPi;
    }
    const int i_phi = std::clamp(static_cast<int>(phi / kTwoPi * grid.phi_bins), 0, grid.phi_bins - 1);
    if (target.polar_scale > 0.0)
    {
        // atan2 keeps the angle accurate near the axis, where 1 - cos theta underflows.
        const double s = PolarWarp(target.polar_scale).coordinate(std::atan2(std::sqrt(x * x + y * y), z));
        const int i_theta = std::clamp(static_cast<int>(s * grid.cos_theta_bins), 0, grid.cos_theta_bins - 1);
        return i_theta * grid.phi_bins + i_phi;
    }
    const double length = std::sqrt(x * x + y * y + z * z);
    const double cos_theta = std::clamp(z / length, -1.0, 1.0);
    const int i_theta =
        std::clamp(static_cast<int>((cos_theta + 1.0) * 0.5 * grid.cos_theta_bins), 0, grid.cos_theta_bins - 1);
    return i_theta * grid.phi_bins + i_phi;
}

namespace {

struct CellIntegrator
{
    const SamplingTarget& target;
    const SphereGridOptions& grid;
    std::vector<double> nodes;
    std::vector<double> weights;

    // Fixed-order Gauss-Legendre over [z0, z1] x [p0, p1]: z is cos theta (d omega = dz dphi)
    // or the warped polar coordinate (d omega = PolarWarp::jacobian dz dphi).
    double gauss(double z0, double z1, double p0, double p1) const
    {
        const double z_mid = 0.5 * (z0 + z1);
        const double z_half = 0.5 * (z1 - z0);
        const double p_mid = 0.5 * (p0 + p1);
        const double p_half = 0.5 * (p1 - p0);
        const bool warped = target.polar_scale > 0.0;
        const PolarWarp warp(warped ? target.polar_scale : 1.0);
        double sum = 0.0;
        for (std::size_t i = 0; i < nodes.size(); ++i)
        {
            const double z = z_mid + z_half * nodes[i];
            double row = 0.0;
            if (warped)
            {
                const double theta = warp.theta(z);
                for (std::size_t j = 0; j < nodes.size(); ++j)
                {
                    const double phi = p_mid + p_half * nodes[j];
                    row += weights[j] * target.pdf(direction_at_polar_angle(target.frame, theta, phi));
                }
                row *= warp.jacobian(z);
            }
            else
            {
                for (std::size_t j = 0; j < nodes.size(); ++j)
                {
                    const double phi = p_mid + p_half * nodes[j];
                    row += weights[j] * target.pdf(direction_in_basis(target.frame, z, phi));
                }
            }
            sum += weights[i] * row;
        }
        return sum * z_half * p_half;
    }

    double adaptive(double z0, double z1, double p0, double p1, double coarse, int depth) const
    {
        const double zm = 0.5 * (z0 + z1);
        const double pm = 0.5 * (p0 + p1);
        const double parts[4] = {gauss(z0, zm, p0, pm), gauss(z0, zm, pm, p1), gauss(zm, z1, p0, pm), gauss(zm, z1, pm, p1)};
        const double fine = parts[0] + parts[1] + parts[2] + parts[3];
        if (depth >= grid.max_depth ||
            std::fabs(fine - coarse) <= std::max(grid.relative_tolerance * std::fabs(fine), grid.absolute_tolerance) ||
            !std::isfinite(fine))
        {
            return fine;
        }
        return adaptive(z0, zm, p0, pm, parts[0], depth + 1) + adaptive(z0, zm, pm, p1, parts[1], depth + 1) +
               adaptive(zm, z1, p0, pm, parts[2], depth + 1) + adaptive(zm, z1, pm, p1, parts[3], depth + 1);
    }
};

}  // namespace

std::vector<double> integrate_pdf_over_grid(const SamplingTarget& target, const SphereGridOptions& grid)
{
    CellIntegrator integrator{target, grid, {}, {}};
    gauss_legendre(grid.quadrature_order, integrator.nodes, integrator.weights);
    std::vector<double> cells(static_cast<std::size_t>(grid.cos_theta_bins * grid.phi_bins), 0.0);
    // z: cos theta over [-1, 1], or the warped polar coordinate over [0, 1].
    const bool warped = target.polar_scale > 0.0;
    const double z_begin = warped ? 0.0 : -1.0;
    const double dz = (warped ? 1.0 : 2.0) / grid.cos_theta_bins;
    const double dphi = kTwoPi / grid.phi_bins;
    parallel_for_index(cells.size(), [&](std::uint64_t index) {
        const int i_theta = static_cast<int>(index) / grid.phi_bins;
        const int i_phi = static_cast<int>(index) % grid.phi_bins;
        const double z0 = z_begin + i_theta * dz;
        const double z1 = i_theta + 1 == grid.cos_theta_bins ? 1.0 : z0 + dz;
        const double p0 = i_phi * dphi;
        const double p1 = (i_phi + 1) * dphi;
        const double coarse = integrator.gauss(z0, z1, p0, p1);
        cells[index] = integrator.adaptive(z0, z1, p0, p1, coarse, 1);
    });
    return cells;
}

// ------------------------------------------------------------------------------------------
// Chi-square

namespace {

struct SampleTally
{
    std::vector<std::uint64_t> cells;
    std::map<std::uint32_t, DeltaAtom> atoms;
    std::uint64_t continuous = 0;
    std::uint64_t invalid = 0;
    std::uint64_t nonfinite = 0;
};

bool is_unit_direction(const glm::vec3& d)
{
    return is_finite(d) && std::fabs(glm::dot(glm::dvec3(d), glm::dvec3(d)) - 1.0) < 1e-3;
}

SampleTally tally_samples(const SamplingTarget& target, const SphereGridOptions& grid, std::uint64_t sample_count,
                          std::uint64_t seed)
{
    const ChunkPlan plan = plan_chunks(sample_count);
    std::vector<SampleTally> tallies(plan.chunks);
    parallel_for_index(plan.chunks, [&](std::uint64_t chunk) {
        SampleTally& tally = tallies[chunk];
        tally.cells.assign(static_cast<std::size_t>(grid.cos_theta_bins * grid.phi_bins), 0);
        for_each_independent_sample(seed, chunk, plan.begin(chunk), plan.end(chunk), [&](std::uint64_t, const glm::vec3& u) {
            const DirectionSample s = target.sample(u);
            if (!s.is_valid())
            {
                ++tally.invalid;
                return;
            }
            if (s.is_delta())
            {
                // One atom per delta lobe (its id): a lobe with several branches (reflection
                // and refraction of a smooth dielectric) reports its selection probability as
                // the pdf of each branch, so only the lobe as a whole can be checked.
                DeltaAtom& atom = tally.atoms[s.lobe_type >> OPENPBR_LOBE_ID_SHIFT];
                if (atom.count == 0)
                {
                    atom.lobe_type = s.lobe_type;
                    atom.reported_pdf_min = s.pdf;
                    atom.reported_pdf_max = s.pdf;
                }
                ++atom.count;
                atom.reported_pdf_min = std::min(atom.reported_pdf_min, s.pdf);
                atom.reported_pdf_max = std::max(atom.reported_pdf_max, s.pdf);
                atom.reported_pdf_mean += s.pdf;  // a sum until merged
                return;
            }
            if (!is_unit_direction(s.direction))
            {
                ++tally.nonfinite;
                return;
            }
            ++tally.continuous;
            ++tally.cells[static_cast<std::size_t>(grid_cell_of(target, grid, s.direction))];
        });
    });
    SampleTally total;
    total.cells.assign(static_cast<std::size_t>(grid.cos_theta_bins * grid.phi_bins), 0);
    for (const SampleTally& tally : tallies)
    {
        for (std::size_t i = 0; i < total.cells.size(); ++i)
        {
            total.cells[i] += tally.cells[i];
        }
        for (const auto& [type, atom] : tally.atoms)
        {
            DeltaAtom& merged = total.atoms[type];
            if (merged.count == 0)
            {
                merged = atom;
            }
            else
            {
                merged.count += atom.count;
                merged.reported_pdf_min = std::min(merged.reported_pdf_min, atom.reported_pdf_min);
                merged.reported_pdf_max = std::max(merged.reported_pdf_max, atom.reported_pdf_max);
                merged.reported_pdf_mean += atom.reported_pdf_mean;
            }
        }
        total.continuous += tally.continuous;
        total.invalid += tally.invalid;
        total.nonfinite += tally.nonfinite;
    }
    for (auto& [type, atom] : total.atoms)
    {
        atom.reported_pdf_mean /= static_cast<double>(atom.count);
    }
    return total;
}

struct Cell
{
    double observed;
    double expected;
    std::string label;
};

// Expected fraction of an atom: its reported pdf (the lobe's selection probability) times the
// lobe's share of delta samples.
double expected_atom_fraction(const SamplingTarget& target, const DeltaAtom& atom)
{
    const auto share = target.delta_share.find(atom.lobe_type >> OPENPBR_LOBE_ID_SHIFT);
    return atom.reported_pdf_mean * (share == target.delta_share.end() ? 1.0 : share->second);
}

// The delta atoms into the result, with whether every atom reports one pdf and their sum
// matches the target's delta probability.
void record_delta_atoms(ChiSquareResult& result, const SamplingTarget& target, const SampleTally& tally,
                        const ChiSquareOptions& options)
{
    for (const auto& [type, atom] : tally.atoms)
    {
        result.atoms.push_back(atom);
        result.delta_count += atom.count;
        result.delta_reported_sum += expected_atom_fraction(target, atom);
        const double spread = atom.reported_pdf_max - atom.reported_pdf_min;
        if (!(spread <= options.delta_pdf_relative_tolerance * atom.reported_pdf_max) || !(atom.reported_pdf_min > 0.0))
        {
            result.delta_pdfs_consistent = false;
        }
    }
    // Atoms never sampled cannot report; the binomial test catches a missing delta lobe.
    if (!result.atoms.empty() && !(std::fabs(result.delta_reported_sum - result.delta_probability) <=
                                   options.delta_pdf_relative_tolerance * std::max(result.delta_probability, 1e-3)))
    {
        result.delta_pdfs_consistent = false;
    }
}

// Cells: the grid (labelled by their bounds; observed and expected also go to the result), one
// atom per delta lobe type, and "no sample".
std::vector<Cell> chi_square_cells(ChiSquareResult& result, const SamplingTarget& target, const SphereGridOptions& grid,
                                   const std::vector<double>& probabilities, const SampleTally& tally)
{
    const double n = static_cast<double>(result.sample_count);
    const bool warped = target.polar_scale > 0.0;
    const PolarWarp warp(warped ? target.polar_scale : 1.0);
    const double dz = (warped ? 1.0 : 2.0) / grid.cos_theta_bins;
    const double dphi = 360.0 / grid.phi_bins;
    std::vector<Cell> cells;
    cells.reserve(probabilities.size() + result.atoms.size() + 1);
    result.observed.resize(probabilities.size());
    result.expected.resize(probabilities.size());
    for (std::size_t i = 0; i < probabilities.size(); ++i)
    {
        const int i_theta = static_cast<int>(i) / grid.phi_bins;
        const int i_phi = static_cast<int>(i) % grid.phi_bins;
        std::ostringstream label;
        if (warped)
        {
            label << std::setprecision(4) << "angle from the lobe axis in [" << warp.theta(i_theta * dz) << ", "
                  << warp.theta((i_theta + 1) * dz) << ") rad";
        }
        else
        {
            label << std::setprecision(4) << "cos in [" << -1.0 + i_theta * dz << ", " << -1.0 + (i_theta + 1) * dz << ")";
        }
        label << ", phi in [" << i_phi * dphi << ", " << (i_phi + 1) * dphi << ") deg";
        result.observed[i] = static_cast<double>(tally.cells[i]);
        result.expected[i] = n * probabilities[i];
        cells.push_back({result.observed[i], result.expected[i], label.str()});
    }
    for (const DeltaAtom& atom : result.atoms)
    {
        cells.push_back({static_cast<double>(atom.count), n * expected_atom_fraction(target, atom),
                         "delta " + lobe_type_string(atom.lobe_type)});
    }
    const double no_sample_probability = std::max(0.0, 1.0 - result.pdf_integral - result.delta_reported_sum);
    cells.push_back({static_cast<double>(tally.invalid + tally.nonfinite), n * no_sample_probability, "no sample"});
    return cells;
}

// The statistic over the cells after pooling, with each term and its cell for the report.
struct ChiSquareTerms
{
    Cell pool{0.0, 0.0, "pool of small cells"};
    int pooled_cell_count = 0;
    double statistic = 0.0;
    int terms = 0;
    std::vector<std::pair<double, std::size_t>> contributions;  // (term, cell index), pool = npos

    const Cell& cell(const std::vector<Cell>& cells, std::size_t index) const
    {
        return index == static_cast<std::size_t>(-1) ? pool : cells[index];
    }
};

// PBRT-style pooling: every cell expecting fewer than min_expected_count goes into one pool, and
// the pool takes the next-smallest cells until it expects enough itself.
ChiSquareTerms pooled_chi_square(const std::vector<Cell>& cells, double min_expected_count)
{
    ChiSquareTerms terms;
    std::vector<std::size_t> order(cells.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
        order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return cells[a].expected < cells[b].expected; });
    std::size_t first_unpooled = 0;
    while (first_unpooled < order.size() && (cells[order[first_unpooled]].expected < min_expected_count ||
                                             (terms.pool.expected > 0.0 && terms.pool.expected < min_expected_count)))
    {
        terms.pool.observed += cells[order[first_unpooled]].observed;
        terms.pool.expected += cells[order[first_unpooled]].expected;
        ++first_unpooled;
        ++terms.pooled_cell_count;
    }
    const auto add_term = [&](const Cell& cell, std::size_t index) {
        if (cell.expected <= 0.0)
        {
            if (cell.observed > 0.0)
            {
                terms.statistic = std::numeric_limits<double>::infinity();
                terms.contributions.push_back({terms.statistic, index});
            }
            return;
        }
        const double difference = cell.observed - cell.expected;
        const double term = difference * difference / cell.expected;
        terms.statistic += term;
        ++terms.terms;
        terms.contributions.push_back({term, index});
    };
    if (terms.pooled_cell_count > 0)
    {
        add_term(terms.pool, static_cast<std::size_t>(-1));
    }
    for (std::size_t i = first_unpooled; i < order.size(); ++i)
    {
        add_term(cells[order[i]], order[i]);
    }
    return terms;
}

// The human-readable summary: counts, the binomial tests, the atoms, the statistic and the six
// largest terms.
std::string chi_square_report(const SamplingTarget& target, const ChiSquareResult& result, const std::vector<Cell>& cells,
                              ChiSquareTerms terms)
{
    const double n = static_cast<double>(result.sample_count);
    std::ostringstream report;
    report << std::setprecision(6) << "target '" << target.name << "': " << result.sample_count << " samples, "
           << result.continuous_count << " continuous, " << result.delta_count << " delta, " << result.invalid_count
           << " no sample, " << result.nonfinite_count << " with a bad direction\n"
           << "  pdf integral " << result.pdf_integral << " vs continuous fraction " << result.continuous_count / n
           << " (p = " << result.continuous_p_value << ")\n"
           << "  delta probability " << result.delta_probability << " vs fraction " << result.delta_count / n
           << " (p = " << result.delta_p_value << "), reported sum " << result.delta_reported_sum
           << (result.delta_pdfs_consistent ? "" : " [INCONSISTENT delta pdfs]") << "\n";
    for (const DeltaAtom& atom : result.atoms)
    {
        report << "  atom " << lobe_type_string(atom.lobe_type) << ": " << atom.count << " samples, reported pdf in ["
               << atom.reported_pdf_min << ", " << atom.reported_pdf_max << "]\n";
    }
    report << "  chi2 = " << result.statistic << ", dof = " << result.degrees_of_freedom << ", p = " << result.p_value
           << " (" << result.pooled_cell_count << " cells pooled)\n";
    std::sort(terms.contributions.begin(), terms.contributions.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t i = 0; i < std::min<std::size_t>(6, terms.contributions.size()); ++i)
    {
        const Cell& cell = terms.cell(cells, terms.contributions[i].second);
        report << "    worst: " << cell.label << ": observed " << cell.observed << ", expected " << cell.expected
               << ", term " << terms.contributions[i].first << "\n";
    }
    return report.str();
}

}  // namespace

ChiSquareResult run_chi_square_test(const SamplingTarget& target, const ChiSquareOptions& options)
{
    ChiSquareResult result;
    result.sample_count = options.sample_count;
    const std::vector<double> probabilities = integrate_pdf_over_grid(target, options.grid);
    const SampleTally tally = tally_samples(target, options.grid, options.sample_count, options.seed);
    result.continuous_count = tally.continuous;
    result.invalid_count = tally.invalid;
    result.nonfinite_count = tally.nonfinite;
    result.delta_probability = target.delta_probability;
    record_delta_atoms(result, target, tally, options);
    for (double p : probabilities)
    {
        result.pdf_integral += p;
    }

    const std::vector<Cell> cells = chi_square_cells(result, target, options.grid, probabilities, tally);
    ChiSquareTerms terms = pooled_chi_square(cells, options.min_expected_count);
    result.pooled_cell_count = terms.pooled_cell_count;
    result.statistic = terms.statistic;
    result.degrees_of_freedom = terms.terms - 1;
    result.p_value = std::isinf(terms.statistic) ? 0.0 : chi_square_p_value(terms.statistic, result.degrees_of_freedom);
    if (std::isnan(terms.statistic))
    {
        result.p_value = std::numeric_limits<double>::quiet_NaN();
    }

    result.delta_p_value = binomial_two_sided_p_value(result.delta_count, options.sample_count, result.delta_probability);
    result.continuous_p_value =
        binomial_two_sided_p_value(result.continuous_count, options.sample_count, std::clamp(result.pdf_integral, 0.0, 1.0));
    result.report = chi_square_report(target, result, cells, std::move(terms));
    return result;
}

// ------------------------------------------------------------------------------------------
// Pdf integral

PdfIntegralResult check_pdf_integral(const SamplingTarget& target, std::uint64_t sample_count, std::uint64_t seed,
                                     const SphereGridOptions& grid)
{
    PdfIntegralResult result;
    result.sample_count = sample_count;
    for (double p : integrate_pdf_over_grid(target, grid))
    {
        result.pdf_integral += p;
    }
    const ChunkPlan plan = plan_chunks(sample_count);
    std::vector<std::uint64_t> counts(plan.chunks, 0);
    parallel_for_index(plan.chunks, [&](std::uint64_t chunk) {
        for_each_independent_sample(seed, chunk, plan.begin(chunk), plan.end(chunk), [&](std::uint64_t, const glm::vec3& u) {
            const DirectionSample s = target.sample(u);
            if (s.is_valid() && !s.is_delta() && s.pdf > 0.0)
            {
                ++counts[chunk];
            }
        });
    });
    std::uint64_t valid = 0;
    for (std::uint64_t c : counts)
    {
        valid += c;
    }
    const double n = static_cast<double>(sample_count);
    result.valid_fraction = valid / n;
    result.standard_error = std::sqrt(std::max(result.valid_fraction * (1.0 - result.valid_fraction), 1.0 / n) / n);
    result.p_value = binomial_two_sided_p_value(valid, sample_count, std::clamp(result.pdf_integral, 0.0, 1.0));
    if (result.pdf_integral > 1.0 + 1e-6)
    {
        result.p_value = 0.0;  // a pdf cannot integrate above 1
    }
    return result;
}

// ------------------------------------------------------------------------------------------
// Per-sample consistency

ConsistencyResult check_sample_consistency(const SamplingTarget& target, const ConsistencyOptions& options)
{
    const ChunkPlan plan = plan_chunks(options.sample_count);
    std::vector<ConsistencyResult> partial(plan.chunks);
    const openpbr::host::ShiftedR3Sequence sequence(options.seed);
    parallel_for_index(plan.chunks, [&](std::uint64_t chunk) {
        ConsistencyResult& r = partial[chunk];
        const auto fail = [&](std::uint64_t& counter, const std::string& what, const glm::vec3& u, const DirectionSample& s,
                              double pdf, const OpenPBR_DiffuseSpecular* eval) {
            ++counter;
            if (r.first_failure.empty())
            {
                std::ostringstream out;
                out << std::setprecision(9) << what << ": u = " << to_string(u) << ", lobe " << lobe_type_string(s.lobe_type)
                    << ", direction " << to_string(s.direction) << ", returned pdf " << s.pdf << ", pdf() " << pdf
                    << ", weight diffuse " << to_string(s.weight.diffuse) << " specular " << to_string(s.weight.specular);
                if (eval != nullptr)
                {
                    out << ", eval diffuse " << to_string(eval->diffuse) << " specular " << to_string(eval->specular);
                }
                r.first_failure = out.str();
            }
        };
        const auto visit = [&](std::uint64_t, const glm::vec3& u) {
            ++r.sample_count;
            const DirectionSample s = target.sample(u);
            if (!s.is_valid())
            {
                if (s.pdf != 0.0 || s.weight.diffuse != glm::vec3(0.0f) || s.weight.specular != glm::vec3(0.0f))
                {
                    fail(r.invalid_value_count, "no sample (lobe type NONE) but pdf or weight != 0", u, s, 0.0, nullptr);
                }
                return;
            }
            if (!(s.pdf > 0.0) || !std::isfinite(s.pdf) || !is_finite(s.weight.diffuse) || !is_finite(s.weight.specular) ||
                !is_non_negative(s.weight.diffuse) || !is_non_negative(s.weight.specular) || !is_unit_direction(s.direction))
            {
                fail(r.invalid_value_count, "invalid sample (pdf <= 0, non-finite/negative weight or bad direction)", u, s,
                     0.0, nullptr);
                return;
            }
            if (s.is_delta())
            {
                return;
            }
            const double pdf = target.pdf(s.direction);
            const OpenPBR_DiffuseSpecular value =
                target.eval ? target.eval(s.direction) : OpenPBR_DiffuseSpecular{glm::vec3(0.0f), glm::vec3(0.0f)};
            if (!std::isfinite(pdf) || pdf < 0.0 || !is_finite(value.diffuse) || !is_finite(value.specular) ||
                !is_non_negative(value.diffuse) || !is_non_negative(value.specular))
            {
                fail(r.invalid_value_count, "pdf()/eval() non-finite or negative at a sampled direction", u, s, pdf, &value);
                return;
            }
            if (std::max(s.pdf, pdf) < options.min_pdf)
            {
                return;
            }
            ++r.checked_count;
            const double pdf_error = std::fabs(pdf - s.pdf) / std::max(pdf, s.pdf);
            r.max_pdf_relative_error = std::max(r.max_pdf_relative_error, pdf_error);
            if (!(pdf_error <= options.relative_tolerance))
            {
                fail(r.pdf_mismatch_count, "returned pdf != pdf()", u, s, pdf, &value);
            }
            if (!target.eval || !(pdf > 0.0))
            {
                return;
            }
            const glm::vec3 got[2] = {s.weight.diffuse, s.weight.specular};
            const glm::vec3 values[2] = {value.diffuse, value.specular};
            double scale = 0.0;
            for (int part = 0; part < 2; ++part)
            {
                scale = std::max({scale, max_component(got[part]), max_component(values[part]) / pdf});
            }
            if (std::max(max_component(value.diffuse), max_component(value.specular)) < options.min_value)
            {
                return;
            }
            double weight_error = 0.0;
            for (int part = 0; part < 2; ++part)
            {
                for (int c = 0; c < 3; ++c)
                {
                    weight_error =
                        std::max(weight_error, std::fabs(double(got[part][c]) - double(values[part][c]) / pdf) / scale);
                }
            }
            r.max_weight_relative_error = std::max(r.max_weight_relative_error, weight_error);
            if (!(weight_error <= options.relative_tolerance))
            {
                fail(r.weight_mismatch_count, "weight != eval / pdf", u, s, pdf, &value);
            }
        };
        if (options.sampler == SamplerKind::independent)
        {
            for_each_independent_sample(options.seed, chunk, plan.begin(chunk), plan.end(chunk), visit);
        }
        else
        {
            for (std::uint64_t i = plan.begin(chunk); i < plan.end(chunk); ++i)
            {
                visit(i, point_of(sequence, i));
            }
        }
    });
    ConsistencyResult total;
    for (const ConsistencyResult& r : partial)
    {
        total.sample_count += r.sample_count;
        total.checked_count += r.checked_count;
        total.weight_mismatch_count += r.weight_mismatch_count;
        total.pdf_mismatch_count += r.pdf_mismatch_count;
        total.invalid_value_count += r.invalid_value_count;
        total.max_weight_relative_error = std::max(total.max_weight_relative_error, r.max_weight_relative_error);
        total.max_pdf_relative_error = std::max(total.max_pdf_relative_error, r.max_pdf_relative_error);
        if (total.first_failure.empty())
        {
            total.first_failure = r.first_failure;
        }
    }
    return total;
}

// ------------------------------------------------------------------------------------------
// Albedo

namespace {

AlbedoEstimate to_albedo_estimate(const openpbr::host::DirectionalAlbedo& albedo)
{
    AlbedoEstimate estimate;
    estimate.sample_count = albedo.samples;
    estimate.mean = glm::dvec3(albedo.mean[0], albedo.mean[1], albedo.mean[2]);
    estimate.standard_error = glm::dvec3(albedo.standard_error[0], albedo.standard_error[1], albedo.standard_error[2]);
    estimate.max_weight = glm::dvec3(albedo.max_weight[0], albedo.max_weight[1], albedo.max_weight[2]);
    return estimate;
}

}  // namespace

IndependentAlbedoSampler::IndependentAlbedoSampler(const SamplingTarget& target, std::uint64_t seed)
    : target_(target), seed_(seed)
{
}

AlbedoEstimate IndependentAlbedoSampler::estimate(std::uint64_t sample_count)
{
    const ChunkPlan plan = plan_chunks(sample_count);
    // Each chunk of this count draws the numbers its first per_chunk_ samples drew before, so
    // those are kept (see the class comment).
    const bool continues = per_chunk_ > 0 && streams_.size() == plan.chunks && sample_count % plan.chunks == 0 &&
                           sample_count / plan.chunks >= per_chunk_;
    if (!continues)
    {
        streams_.clear();
        for (std::uint64_t chunk = 0; chunk < plan.chunks; ++chunk)
        {
            streams_.emplace_back(mix_seed(seed_), chunk);
        }
        sums_.assign(plan.chunks, host::SampleWeightSums());
        per_chunk_ = 0;
    }
    const std::uint64_t drawn = per_chunk_;
    parallel_for_index(plan.chunks, [&](std::uint64_t chunk) {
        // The chunk's stream continued where it stopped (for_each_independent_sample's numbers).
        draw_independent_samples(streams_[chunk], plan.begin(chunk) + drawn, plan.end(chunk),
                                 [&](std::uint64_t, const glm::vec3& u) {
                                     const DirectionSample s = target_.sample(u);
                                     const glm::dvec3 w = s.is_valid() ? glm::dvec3(s.total_weight()) : glm::dvec3(0.0);
                                     sums_[chunk].add(w.x, w.y, w.z);
                                 });
    });
    // Only a count of equal chunks can be continued.
    per_chunk_ = sample_count % plan.chunks == 0 ? sample_count / plan.chunks : 0;
    host::SampleWeightSums total;
    for (const host::SampleWeightSums& chunk_sums : sums_)
    {
        total.merge(chunk_sums);
    }
    return to_albedo_estimate(host::directional_albedo_from_sums(total));
}

AlbedoEstimate estimate_albedo(const SamplingTarget& target, std::uint64_t sample_count, std::uint64_t seed,
                               SamplerKind sampler, int replicas)
{
    // The host's one directional-albedo estimator (host/support/directional_albedo.h); this
    // function only draws the samples.
    if (sampler == SamplerKind::independent)
    {
        return IndependentAlbedoSampler(target, seed).estimate(sample_count);
    }
    const auto weight_of = [&](const glm::vec3& u) {
        const DirectionSample s = target.sample(u);
        return s.is_valid() ? glm::dvec3(s.total_weight()) : glm::dvec3(0.0);
    };
    // Randomized QMC: independent replicas, each a shifted R3 sequence.
    const int r = std::max(replicas, 2);
    const std::uint64_t per_replica = std::max<std::uint64_t>(1, sample_count / static_cast<std::uint64_t>(r));
    std::vector<openpbr::host::SampleWeightSums> partial(static_cast<std::size_t>(r));
    parallel_for_index(static_cast<std::uint64_t>(r), [&](std::uint64_t replica) {
        const openpbr::host::ShiftedR3Sequence sequence(mix_seed(seed) ^ (replica * 0x9e3779b97f4a7c15ull));
        openpbr::host::accumulate_sample_weights(partial[replica], 0, per_replica,
                                                 [&](std::uint64_t i) { return weight_of(point_of(sequence, i)); });
    });
    return to_albedo_estimate(openpbr::host::directional_albedo_from_replicas(partial));
}

// ------------------------------------------------------------------------------------------
// Reciprocity

ReciprocityResult check_reciprocity(const LobeFunction& f, std::uint64_t pair_count, std::uint64_t seed,
                                    const ReciprocityOptions& options)
{
    ReciprocityResult result;
    result.pair_count = pair_count;
    RandomStream rng(mix_seed(seed), 11);
    const auto random_direction = [&](bool full_sphere) {
        const double z = full_sphere ? 2.0 * rng.next_double() - 1.0 : rng.next_double();
        const double phi = kTwoPi * rng.next_double();
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        return glm::dvec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    // f(view, light) / |cos light| for both orders.
    const auto both_orders = [&](const glm::vec3& wo, const glm::vec3& wi, glm::dvec3& forward, glm::dvec3& backward) {
        forward = glm::dvec3(f(wo, wi)) / std::fabs(double(wi.z));
        backward = glm::dvec3(f(wi, wo)) / std::fabs(double(wo.z));
    };
    for (std::uint64_t i = 0; i < pair_count; ++i)
    {
        const glm::dvec3 wo_d = random_direction(false);
        const glm::dvec3 wi_d = random_direction(options.both_sides);
        const glm::vec3 wo(wo_d);
        const glm::vec3 wi(wi_d);
        if (std::fabs(wo.z) < 1e-4f || std::fabs(wi.z) < 1e-4f)
        {
            continue;
        }
        glm::dvec3 forward, backward;
        both_orders(wo, wi, forward, backward);
        // Sensitivity: the largest change of either order when both directions move by
        // about options.direction_precision in random directions.
        glm::dvec3 sensitivity(0.0);
        for (int k = 0; k < 8; ++k)
        {
            const glm::vec3 wo_p(glm::normalize(wo_d + options.direction_precision * random_direction(true)));
            const glm::vec3 wi_p(glm::normalize(wi_d + options.direction_precision * random_direction(true)));
            if (wo_p.z * wo.z <= 0.0f || wi_p.z * wi.z <= 0.0f)
            {
                continue;
            }
            glm::dvec3 forward_p, backward_p;
            both_orders(wo_p, wi_p, forward_p, backward_p);
            sensitivity = glm::max(sensitivity, glm::max(glm::abs(forward_p - forward), glm::abs(backward_p - backward)));
        }
        for (int c = 0; c < 3; ++c)
        {
            const double larger = std::max(std::fabs(forward[c]), std::fabs(backward[c]));
            if (!(larger >= options.min_value) && std::isfinite(larger))
            {
                continue;
            }
            ++result.checked_count;
            const double difference = std::fabs(forward[c] - backward[c]);
            const double allowed = options.relative_tolerance * larger + sensitivity[c];
            const double relative_error = difference / larger;
            result.max_relative_error =
                std::max(result.max_relative_error,
                         std::isnan(relative_error) ? std::numeric_limits<double>::infinity() : relative_error);
            const double excess = difference / allowed;
            if (!(difference <= allowed))
            {
                ++result.failure_count;
            }
            if (!(excess <= result.max_excess))
            {
                result.max_excess = std::isnan(excess) ? std::numeric_limits<double>::infinity() : excess;
                std::ostringstream out;
                out << std::setprecision(9) << "wo = " << to_string(wo) << ", wi = " << to_string(wi) << ", channel " << c
                    << ": f(wo, wi) / |cos wi| = " << forward[c] << ", f(wi, wo) / |cos wo| = " << backward[c]
                    << ", allowed difference " << allowed;
                result.worst = out.str();
            }
        }
    }
    return result;
}

// ------------------------------------------------------------------------------------------
// Helpers

std::string to_string(const glm::vec3& v)
{
    std::ostringstream out;
    out << std::setprecision(7) << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return out.str();
}

std::string describe_inputs(const OpenPBR_ResolvedInputs& i)
{
    std::ostringstream out;
    out << std::setprecision(7) << "base_weight " << i.base_weight << ", base_color " << to_string(i.base_color)
        << ", base_diffuse_roughness " << i.base_diffuse_roughness << ", base_metalness " << i.base_metalness
        << ", specular_weight " << i.specular_weight << ", specular_color " << to_string(i.specular_color)
        << ", specular_roughness " << i.specular_roughness << ", specular_roughness_anisotropy "
        << i.specular_roughness_anisotropy << ", specular_ior " << i.specular_ior << ", transmission_weight "
        << i.transmission_weight << ", subsurface_weight " << i.subsurface_weight << ", fuzz_weight " << i.fuzz_weight
        << ", coat_weight " << i.coat_weight << ", thin_film_weight " << i.thin_film_weight << ", geometry_opacity "
        << i.geometry_opacity << ", thin_walled " << i.geometry_thin_walled << ", normal "
        << to_string(i.geometry_basis.normal) << ", tangent " << to_string(i.geometry_basis.tangent) << ", bitangent "
        << to_string(i.geometry_basis.bitangent) << ", anisotropy rotation (" << i.specular_anisotropy_rotation.x << ", "
        << i.specular_anisotropy_rotation.y << ")";
    return out.str();
}

}  // namespace openpbr::testing
