// lut_generator.cpp - Monte Carlo generation of the energy-compensation tables (see
// lut_generator.h for the tables, the estimator and the file formats).
//
// This file is compiled in table buffer mode whatever the build defines: it reads only the
// layout macros of slang/openpbr_lut.h and the pure GGX / VNDF / Fresnel functions, never the
// table data, so it compiles before (and without) slang/generated/openpbr_lut_values.inc. It
// calls no look-up function and never reads openpbr_lut_data, so no buffer-mode definition is
// emitted into this object file and other files may include openpbr_lut.h in array mode.
#undef OPENPBR_LUT_MODE_ARRAY
#undef OPENPBR_LUT_MODE_TEXTURE
#ifndef OPENPBR_LUT_MODE_BUFFER
#define OPENPBR_LUT_MODE_BUFFER 1
#endif

#include "host/tables/lut_generator.h"
#include "host/support/files.h"
#include "host/support/progress.h"
#include "host/support/random.h"

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_fresnel.h"
#include "slang/math/openpbr_ggx.h"
#include "slang/math/openpbr_vndf.h"
#include "slang/openpbr_lut.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace openpbr::host {
namespace {

// Parameter floors: mu = 0 and alpha = 0 would divide by zero in Lambda and the VNDF sampler.
// alpha = 1e-4 is far below OPENPBR_DELTA_ALPHA_THRESHOLD, so the r = 0 nodes hold the delta
// (smooth interface) limit to within float precision except at grazing mu.
constexpr double minimum_mu = 1e-4;
constexpr double minimum_alpha = 1e-4;

constexpr int maximum_size_2d = 1024;
constexpr int maximum_size_3d = 256;
constexpr int maximum_size_4d = 64;

void check_table(const int table)
{
    if (table < 0 || table >= lut_table_count)
    {
        throw std::invalid_argument("lut_generator: table id " + std::to_string(table) + " is not in [0, " +
                                    std::to_string(lut_table_count - 1) + "]");
    }
}

// ---- Sample sequence -------------------------------------------------------------------------

std::uint32_t reverse_bits(std::uint32_t v)
{
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

// Second Sobol dimension: its generator matrix is Pascal's triangle mod 2, whose columns are
// v_1 = 2^31 and v_{k+1} = v_k xor (v_k >> 1). With the van der Corput sequence (the first
// dimension, reverse_bits) it forms a (0, 2)-sequence: every 2^m consecutive points aligned
// at a multiple of 2^m put one point in each of the 2^m elementary dyadic boxes.
std::uint32_t sobol_second_dimension(std::uint32_t index)
{
    std::uint32_t result = 0;
    for (std::uint32_t column = 0x80000000u; index != 0; index >>= 1, column ^= column >> 1)
    {
        if (index & 1u)
        {
            result ^= column;
        }
    }
    return result;
}

// 32 random bits -> float in [0, 1): the top 24 bits, so the result is exact and below 1.
float bits_to_unit_float(const std::uint32_t bits) { return float(bits >> 8) * (1.0f / 16777216.0f); }

// ---- Per-sample weights -----------------------------------------------------------------------

struct CellSetup
{
    int table;
    vec3 view;
    vec2 alpha;
    float eta;
    float lambda_view;
    float inverse_g1_view;  // 1 + Lambda(wo)
};

// G2(wo, w) / G1(wo) for a light direction w.
float masking_ratio(const CellSetup& cell, const vec3 light)
{
    return cell.inverse_g1_view * openpbr_ggx_g2(cell.lambda_view, openpbr_ggx_lambda(light, cell.alpha));
}

float reflection_weight(const CellSetup& cell, const vec3 h)
{
    const vec3 light = reflect(-cell.view, h);
    return light.z > 0.0f ? masking_ratio(cell, light) : 0.0f;
}

// Refraction of the view through the microfacet h into the lower side (eta = n_t / n_i); GLSL
// refract returns the zero vector under total internal reflection, which the z test rejects.
float transmission_weight(const CellSetup& cell, const vec3 h)
{
    const vec3 light = refract(-cell.view, h, 1.0f / cell.eta);
    return light.z < 0.0f ? masking_ratio(cell, light) : 0.0f;
}

float sample_weight(const CellSetup& cell, const vec3 h)
{
    switch (cell.table)
    {
    case lut_table_ggx_albedo:
    case lut_table_ggx_anisotropy_ratio: return reflection_weight(cell, h);
    case lut_table_dielectric_reflection:
        return openpbr_fresnel_dielectric(dot(cell.view, h), cell.eta) * reflection_weight(cell, h);
    case lut_table_dielectric_transmission: return transmission_weight(cell, h);
    default:
    {
        // Both events of the same microfacet, weighted by F and 1 - F: no random choice between
        // them, so the only variance left is that of h.
        const float fresnel = openpbr_fresnel_dielectric(dot(cell.view, h), cell.eta);
        const float reflected = fresnel > 0.0f ? fresnel * reflection_weight(cell, h) : 0.0f;
        const float transmitted = fresnel < 1.0f ? (1.0f - fresnel) * transmission_weight(cell, h) : 0.0f;
        return reflected + transmitted;
    }
    }
}

// ---- Files ---------------------------------------------------------------------------------

void check_finite(const std::vector<float>& data, const std::filesystem::path& path)
{
    for (std::size_t i = 0; i < data.size(); ++i)
    {
        if (!std::isfinite(data[i]))
        {
            throw std::runtime_error("lut_generator: value " + std::to_string(i) + " to be written to " + path.string() +
                                     " is not finite");
        }
    }
}

}  // namespace

// ---- Layout --------------------------------------------------------------------------------

const char* lut_table_name(const int table)
{
    check_table(table);
    static const char* const names[lut_table_count] = {"ggx_albedo", "dielectric_reflection", "dielectric_transmission",
                                                       "dielectric_interface", "ggx_anisotropy_ratio"};
    return names[table];
}

int LutLayout::dimensions(const int table) const
{
    check_table(table);
    return table == lut_table_ggx_albedo ? 2 : table == lut_table_ggx_anisotropy_ratio ? 4 : 3;
}

int LutLayout::size(const int table) const
{
    const int d = dimensions(table);
    return d == 2 ? size_2d : d == 3 ? size_3d : size_4d;
}

int LutLayout::axis_size(const int table, const int axis) const
{
    if (axis < 0 || axis >= dimensions(table))
    {
        throw std::invalid_argument("lut_generator: table " + std::to_string(table) + " has no axis " +
                                    std::to_string(axis));
    }
    if (axis == 2 && dimensions(table) == 3)
    {
        return size_3d_eta;
    }
    return axis >= 2 && dimensions(table) == 4 ? size_4d_anisotropy : size(table);
}

std::size_t LutLayout::count(const int table) const
{
    std::size_t result = 1;
    for (int axis = 0; axis < dimensions(table); ++axis)
    {
        result *= std::size_t(std::max(axis_size(table, axis), 0));
    }
    return result;
}

std::size_t LutLayout::offset(const int table) const
{
    check_table(table);
    std::size_t result = 0;
    for (int t = 0; t < table; ++t)
    {
        result += count(t);
    }
    return result;
}

std::size_t LutLayout::total_count() const { return offset(lut_table_count - 1) + count(lut_table_count - 1); }

// LutLayout computes the offsets itself (for any sizes); these pin it to the header's macros.
static_assert(OPENPBR_LUT_GGX_ALBEDO_OFFSET == 0, "table 0 must come first");
static_assert(OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET == OPENPBR_LUT_2D_SIZE * OPENPBR_LUT_2D_SIZE,
              "table 1 must follow the 2D table");
static_assert(OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET ==
                  OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET +
                      OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_SIZE * OPENPBR_LUT_3D_ETA_SIZE,
              "table 2 must follow table 1");
static_assert(OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET == OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET + OPENPBR_LUT_3D_COUNT,
              "table 3 must follow table 2");
static_assert(OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET == OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET + OPENPBR_LUT_3D_COUNT,
              "table 4 must follow table 3");
static_assert(OPENPBR_LUT_3D_ETA_SIZE % 2 == 0 && OPENPBR_LUT_3D_ETA_SIZE >= 6,
              "the eta axis has two halves of at least 3 nodes (the quadratic stencil)");
static_assert(OPENPBR_LUT_4D_COUNT == OPENPBR_LUT_4D_SIZE * OPENPBR_LUT_4D_SIZE * OPENPBR_LUT_4D_ANISOTROPY_SIZE *
                                          OPENPBR_LUT_4D_ANISOTROPY_SIZE,
              "table 4 has N x N x M x M nodes");
static_assert(OPENPBR_LUT_COMPENSATION_COUNT == OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET + OPENPBR_LUT_4D_COUNT,
              "table 4 must be the last compensation table (table 5, the film's, is generated by film_table_generator.cpp)");

LutLayout compiled_lut_layout()
{
    return LutLayout{OPENPBR_LUT_2D_SIZE, OPENPBR_LUT_3D_SIZE, OPENPBR_LUT_4D_SIZE, OPENPBR_LUT_4D_ANISOTROPY_SIZE,
                     OPENPBR_LUT_3D_ETA_SIZE};
}

// ---- Estimator -----------------------------------------------------------------------------

// Inverses of the axis coordinates of slang/openpbr_lut.h.
double lut_eta_from_coordinate(const double x)
{
    const double c = std::clamp(x, 0.0, 1.0) - 0.5;
    const double y = (c < 0.0 ? -2.0 : 2.0) * c * c;
    return (1.0 + y) / (1.0 - y);
}

double lut_eta_from_node(const int index, const int eta_size)
{
    const int half_size = eta_size / 2;
    const bool below_one = index < half_size;
    const double w =
        below_one ? 1.0 - double(index) / double(half_size - 1) : double(index - half_size) / double(half_size - 1);
    // w = (v(s) - v(s_0)) / (v(1) - v(s_0)), v(s) = asinh(s / s_0) + k s, inverted by bisection
    // (v increases).
    const double knee = double(OPENPBR_LUT_ETA_KNEE);
    const double linear = double(OPENPBR_LUT_ETA_LINEAR_WEIGHT);
    const auto v = [&](const double s) { return std::asinh(s / knee) + linear * s; };
    const double target = v(knee) + w * (v(1.0) - v(knee));
    double low = knee;
    double high = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration)
    {
        const double middle = 0.5 * (low + high);
        (v(middle) < target ? low : high) = middle;
    }
    const double s = w <= 0.0 ? knee : (w >= 1.0 ? 1.0 : 0.5 * (low + high));
    const double y = (below_one ? -0.5 : 0.5) * s * s;
    return (1.0 + y) / (1.0 - y);
}

double lut_critical_cosine(const double eta)
{
    const double distance = std::max(std::fabs(eta - 1.0), double(OPENPBR_LUT_UNIT_ETA_STEP));
    const double larger = std::max(eta, 1.0);
    return std::sqrt(std::min(distance * (eta + 1.0) / (larger * larger), 1.0));
}

double lut_step_width(const double alpha, const double eta)
{
    const double scale = std::max(alpha, double(OPENPBR_LUT_STEP_MIN_ALPHA)) / std::max(1.0 - alpha, 1e-3);
    return eta < 1.0 ? double(OPENPBR_LUT_STEP_WIDTH_SCALE) * scale * eta / (2.0 * std::sqrt(lut_critical_cosine(eta)))
                     : 0.0;
}

double lut_view_split(const double eta) { return eta < 1.0 ? 0.5 : double(OPENPBR_LUT_VIEW_SPLIT_ABOVE); }

double lut_view_coordinate(const double mu, const double eta, const double alpha)
{
    const double m = std::sqrt(std::clamp(mu, 0.0, 1.0));
    const double c = std::sqrt(lut_critical_cosine(eta));
    const double width = lut_step_width(alpha, eta);
    if (width <= 0.0)
    {
        const double split = lut_view_split(eta);
        return m < c ? split * m / c : split + (1.0 - split) * (m - c) / (1.0 - c);
    }
    const auto warp = [](const double distance, const double scale, const double slope) {
        return (std::asinh(distance / scale) + slope * distance) / (std::asinh(1.0 / scale) + slope);
    };
    return m < c ? 0.5 - 0.5 * warp((c - m) / c, width / c, double(OPENPBR_LUT_STEP_LINEAR_WEIGHT_BELOW))
                 : 0.5 + 0.5 * warp(std::min((m - c) / (1.0 - c), 1.0), width / (1.0 - c),
                                    double(OPENPBR_LUT_STEP_LINEAR_WEIGHT_ABOVE));
}

double lut_mu_from_view_coordinate(const double u, const double eta, const double alpha)
{
    const double c = std::sqrt(lut_critical_cosine(eta));
    const double v = std::clamp(u, 0.0, 1.0);
    const double split = lut_view_split(eta);
    double m = v < split ? v / split * c : c + (v - split) / (1.0 - split) * (1.0 - c);
    if (lut_step_width(alpha, eta) > 0.0 && v != split)
    {
        // The warped axis is increasing in m on each half: bisection on the half of v.
        double low = v < split ? 0.0 : c;
        double high = v < split ? c : 1.0;
        for (int iteration = 0; iteration < 100; ++iteration)
        {
            const double middle = 0.5 * (low + high);
            (lut_view_coordinate(middle * middle, eta, alpha) < v ? low : high) = middle;
        }
        m = v <= 0.0 ? 0.0 : (v >= 1.0 ? 1.0 : 0.5 * (low + high));
    }
    return std::max(m * m, minimum_mu);
}

double lut_alpha_from_coordinate(const double r)
{
    const double c = std::clamp(r, 0.0, 1.0);
    return std::max(c * c, minimum_alpha);
}

double lut_mu_from_coordinate(const double mu)
{
    const double c = std::clamp(mu, 0.0, 1.0);
    return std::max(c * c, minimum_mu);
}

double lut_anisotropy_from_coordinate(const double a)
{
    const double c = 1.0 - std::clamp(a, 0.0, 1.0);
    return 1.0 - c * c;
}

// The same expression as openpbr_lut_azimuth_coordinate (see there), in double.
double lut_azimuth_coordinate(const double mu, const double r, const double a, const double cos_phi_squared)
{
    const double b = 1.0 - std::clamp(a, 0.0, 1.0);
    const double cos_theta = std::clamp(mu, minimum_mu, 1.0);
    const double alpha = lut_alpha_from_coordinate(r);
    const double alpha_t_squared = alpha * alpha * (2.0 / (1.0 + b * b));
    const double x = alpha_t_squared * (1.0 - cos_theta * cos_theta) / (cos_theta * cos_theta);
    const double cos_squared = std::clamp(cos_phi_squared, 0.0, 1.0);
    const double q_squared = cos_squared + b * b * (1.0 - cos_squared);
    const double s_1 = std::sqrt(1.0 + x);
    const double s_b = std::sqrt(1.0 + x * b * b);
    const double s_q = std::sqrt(1.0 + x * q_squared);
    return std::clamp(cos_squared * (s_1 + s_b) * (s_1 + 1.0) / ((s_q + s_b) * (s_q + 1.0)), 0.0, 1.0);
}

double lut_cos_phi_squared_from_coordinate(const double phi, const double mu, const double r, const double a)
{
    const double target = std::clamp(phi, 0.0, 1.0);
    if (target <= 0.0 || target >= 1.0)
    {
        return target;  // the map fixes both ends
    }
    double low = 0.0;
    double high = 1.0;
    for (int iteration = 0; iteration < 64 && high - low > 1e-16; ++iteration)
    {
        const double middle = 0.5 * (low + high);
        (lut_azimuth_coordinate(mu, r, a, middle) < target ? low : high) = middle;
    }
    return 0.5 * (low + high);
}

std::uint64_t lut_cell_seed(const int table, const std::size_t cell, const std::uint64_t generator_seed)
{
    const std::uint64_t stream = mix64_finalize(generator_seed + splitmix64_increment * std::uint64_t(table + 1));
    return mix64_finalize(stream ^ std::uint64_t(cell));
}

double estimate_lut_entry(const int table, const double mu, const double r, const double x, const std::uint32_t samples,
                          const std::uint64_t seed)
{
    return estimate_lut_entry(table, mu, r, x, 0.0, samples, seed);
}

namespace {

// One entry at physical parameters: mu_value the view cosine, alpha_value the isotropic GGX
// alpha, eta the relative IOR; r, x and phi are table 4's coordinates.
double estimate_entry(const int table, const double mu_value, const double alpha_value, const double eta, const double r,
                      const double x, const double phi, const std::uint32_t samples, const std::uint64_t seed)
{
    check_table(table);
    if (samples == 0)
    {
        throw std::invalid_argument("lut_generator: samples must be at least 1");
    }
    const double sin_theta = std::sqrt(1.0 - mu_value * mu_value);
    CellSetup cell;
    cell.table = table;
    cell.view = vec3(float(sin_theta), 0.0f, float(mu_value));
    cell.alpha = vec2(float(alpha_value));
    cell.eta = float(eta);
    if (table == lut_table_ggx_anisotropy_ratio)
    {
        // OpenPBR's anisotropy mapping (openpbr_ggx_alpha) on the floored isotropic alpha, so at
        // a = 0 both lobes are table 0's; the view azimuth follows from the phi coordinate.
        const double r_value = std::clamp(r, 0.0, 1.0);
        const double anisotropy = lut_anisotropy_from_coordinate(x);
        const double b = 1.0 - anisotropy;
        const double alpha_t = lut_alpha_from_coordinate(r_value) * std::sqrt(2.0 / (1.0 + b * b));
        const double cos_phi_squared = lut_cos_phi_squared_from_coordinate(phi, mu_value, r_value, anisotropy);
        cell.view = vec3(float(sin_theta * std::sqrt(cos_phi_squared)), float(sin_theta * std::sqrt(1.0 - cos_phi_squared)),
                         float(mu_value));
        cell.alpha = vec2(float(alpha_t), float(std::max(b * alpha_t, 1e-7)));
        cell.eta = 1.0f;
    }
    cell.lambda_view = openpbr_ggx_lambda(cell.view, cell.alpha);
    cell.inverse_g1_view = 1.0f + cell.lambda_view;
    // Table 4's denominator: the isotropic lobe of table 0 at the same (rotated) view.
    CellSetup isotropic_cell = cell;
    isotropic_cell.alpha = vec2(float(alpha_value));
    isotropic_cell.lambda_view = openpbr_ggx_lambda(isotropic_cell.view, isotropic_cell.alpha);
    isotropic_cell.inverse_g1_view = 1.0f + isotropic_cell.lambda_view;

    // Random digital shift (xor of the same random bits into every point): keeps the net
    // structure of the sequence and makes each cell's estimate unbiased and independent.
    const std::uint32_t shift_x = std::uint32_t(seed);
    const std::uint32_t shift_y = std::uint32_t(seed >> 32);
    double sum = 0.0;
    double isotropic_sum = 0.0;
    for (std::uint32_t i = 0; i < samples; ++i)
    {
        const vec2 u(bits_to_unit_float(reverse_bits(i) ^ shift_x), bits_to_unit_float(sobol_second_dimension(i) ^ shift_y));
        const vec3 h = openpbr_sample_vndf_spherical_cap(cell.view, cell.alpha, u);
        sum += double(sample_weight(cell, h));
        if (table == lut_table_dielectric_reflection || table == lut_table_dielectric_interface)
        {
            // Tables 1 and 3 divide by the F = 1 reflection albedo of the same lobe, from the
            // same points (errors correlated, so they largely cancel in the quotient).
            isotropic_sum += double(reflection_weight(cell, h));
        }
        if (table == lut_table_ggx_anisotropy_ratio)
        {
            // The same points for both lobes: their errors are correlated and largely cancel in
            // the ratio, and at a = 0 (equal lobes) the ratio is exactly 1.
            const vec3 isotropic_h = openpbr_sample_vndf_spherical_cap(isotropic_cell.view, isotropic_cell.alpha, u);
            isotropic_sum += double(sample_weight(isotropic_cell, isotropic_h));
        }
    }
    if (table == lut_table_ggx_anisotropy_ratio)
    {
        return isotropic_sum > 0.0 ? sum / isotropic_sum : 1.0;
    }
    if (table == lut_table_dielectric_reflection || table == lut_table_dielectric_interface)
    {
        // No reflected light at all (not reached for views the tables hold): the Fresnel
        // factor of the view itself, or 1.
        const double fallback =
            table == lut_table_dielectric_reflection ? double(openpbr_fresnel_dielectric(cell.view.z, cell.eta)) : 1.0;
        return isotropic_sum > 0.0 ? sum / isotropic_sum : fallback;
    }
    return sum / double(samples);
}

bool is_dielectric_table(const int table)
{
    return table == lut_table_dielectric_reflection || table == lut_table_dielectric_transmission ||
           table == lut_table_dielectric_interface;
}

}  // namespace

double estimate_lut_entry(const int table, const double mu, const double r, const double x, const double phi,
                          const std::uint32_t samples, const std::uint64_t seed)
{
    check_table(table);
    const double eta = is_dielectric_table(table) ? lut_eta_from_coordinate(x) : 1.0;
    const double mu_value = is_dielectric_table(table) ? lut_mu_from_view_coordinate(mu, eta, lut_alpha_from_coordinate(r))
                                                       : lut_mu_from_coordinate(mu);
    return estimate_entry(table, mu_value, lut_alpha_from_coordinate(r), eta, r, x, phi, samples, seed);
}

double estimate_dielectric_entry(const int table, const double mu, const double alpha, const double eta,
                                 const std::uint32_t samples, const std::uint64_t seed)
{
    if (!is_dielectric_table(table))
    {
        throw std::invalid_argument("lut_generator: estimate_dielectric_entry takes tables 1-3, got " +
                                    std::to_string(table));
    }
    return estimate_entry(table, std::clamp(mu, minimum_mu, 1.0), std::max(alpha, minimum_alpha), eta, 0.0, 0.0, 0.0,
                          samples, seed);
}

float round_to_half(const float value)
{
    if (!std::isfinite(value))
    {
        return value;
    }
    const float magnitude = std::fabs(value);
    constexpr float smallest_normal_half = 6.103515625e-05f;  // 2^-14
    if (magnitude < smallest_normal_half)
    {
        // Half subnormals are multiples of 2^-24; v * 2^24 < 2^10 is exact, rint ties to even.
        return std::nearbyint(value * 16777216.0f) * (1.0f / 16777216.0f);
    }
    // Keep 10 of the 23 mantissa bits, rounding to nearest, ties to even; a carry out of the
    // mantissa correctly increments the exponent.
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    bits += 0x00000FFFu + ((bits >> 13) & 1u);
    bits &= ~0x00001FFFu;
    float rounded = 0.0f;
    std::memcpy(&rounded, &bits, sizeof(rounded));
    constexpr float largest_half = 65504.0f;
    if (std::fabs(rounded) > largest_half)
    {
        return std::copysign(std::numeric_limits<float>::infinity(), value);
    }
    return rounded;
}

std::string describe(const LutGeneratorOptions& options)
{
    const LutLayout layout = options.layout();
    std::ostringstream text;
    const bool valid = layout.size_2d >= 2 && layout.size_3d >= 2 && layout.size_4d >= 2 && layout.size_4d_anisotropy >= 2 &&
                       layout.size_3d_eta >= 2;
    text << "openpbr lutgen: 2D " << options.size_2d << ", 3D " << options.size_3d << "x" << options.size_3d << "x"
         << options.size_3d_eta << ", 4D " << options.size_4d << "x" << options.size_4d << "x" << options.size_4d_anisotropy
         << "x" << options.size_4d_anisotropy << ", " << options.samples << " samples/cell, "
         << (options.bits == 16 ? "half-rounded" : "float32") << ", " << (valid ? layout.total_count() : 0) << " values";
    if (options.seed != 0)
    {
        text << ", seed " << options.seed;
    }
    if (layout != compiled_lut_layout())
    {
        text << " (not the compiled layout " << OPENPBR_LUT_2D_SIZE << " / " << OPENPBR_LUT_3D_SIZE << "x"
             << OPENPBR_LUT_3D_ETA_SIZE << " / " << OPENPBR_LUT_4D_SIZE << " / " << OPENPBR_LUT_4D_ANISOTROPY_SIZE << ")";
    }
    return text.str();
}

std::vector<float> generate_lut(const LutGeneratorOptions& options)
{
    if (options.size_2d < 2 || options.size_2d > maximum_size_2d || options.size_3d < 2 ||
        options.size_3d > maximum_size_3d || options.size_4d < 2 || options.size_4d > maximum_size_4d ||
        options.size_4d_anisotropy < 2 || options.size_4d_anisotropy > maximum_size_4d || options.size_3d_eta < 6 ||
        options.size_3d_eta > maximum_size_3d || options.size_3d_eta % 2 != 0)
    {
        throw std::invalid_argument("lut_generator: table sizes must be in [2, " + std::to_string(maximum_size_2d) +
                                    "] (2D), [2, " + std::to_string(maximum_size_3d) + "] (3D), [2, " +
                                    std::to_string(maximum_size_4d) + "] (4D) and an even eta size in [6, " +
                                    std::to_string(maximum_size_3d) + "], got " + std::to_string(options.size_2d) + ", " +
                                    std::to_string(options.size_3d) + ", " + std::to_string(options.size_4d) + ", " +
                                    std::to_string(options.size_4d_anisotropy) + " and eta " +
                                    std::to_string(options.size_3d_eta));
    }
    if (options.samples == 0)
    {
        throw std::invalid_argument("lut_generator: samples must be at least 1");
    }
    if (options.bits != 16 && options.bits != 32)
    {
        throw std::invalid_argument("lut_generator: bits must be 16 or 32, got " + std::to_string(options.bits));
    }
    if (options.threads < 0)
    {
        throw std::invalid_argument("lut_generator: threads must be >= 0 (0: all cores), got " +
                                    std::to_string(options.threads));
    }

    const LutLayout layout = options.layout();
    const std::size_t total = layout.total_count();
    std::vector<float> data(total, 0.0f);
    ProgressReporter progress(total, options.progress_always || (options.progress && stderr_is_terminal()), "lutgen");

    std::size_t offsets[lut_table_count];
    for (int t = 0; t < lut_table_count; ++t)
    {
        offsets[t] = layout.offset(t);
    }
    auto compute_cell = [&](const std::size_t index) {
        int table = lut_table_count - 1;
        while (index < offsets[table])
        {
            --table;
        }
        const std::size_t local = index - offsets[table];
        // Node coordinates, mu fastest; the x axis is eta (3D) or the anisotropy (4D).
        double coordinates[4] = {0.0, 0.0, 0.5, 0.0};
        std::size_t rest = local;
        for (int axis = 0; axis < layout.dimensions(table); ++axis)
        {
            const std::size_t n = std::size_t(layout.axis_size(table, axis));
            coordinates[axis] = double(rest % n) / double(n - 1);
            rest /= n;
        }
        double value = 0.0;
        if (is_dielectric_table(table))
        {
            // The eta node's relative IOR and the view cosine of the warped view axis there.
            const int eta_index = int(local / (std::size_t(layout.size_3d) * std::size_t(layout.size_3d)));
            const double eta = lut_eta_from_node(eta_index, layout.size_3d_eta);
            value = estimate_entry(
                table, lut_mu_from_view_coordinate(coordinates[0], eta, lut_alpha_from_coordinate(coordinates[1])),
                lut_alpha_from_coordinate(coordinates[1]), eta, coordinates[1], 0.0, 0.0, options.samples,
                lut_cell_seed(table, local, options.seed));
        }
        else
        {
            value = estimate_lut_entry(table, coordinates[0], coordinates[1], coordinates[2], coordinates[3],
                                       options.samples, lut_cell_seed(table, local, options.seed));
        }
        data[index] = options.bits == 16 ? round_to_half(float(value)) : float(value);
        progress.advance();
    };

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 4), [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t index = range.begin(); index != range.end(); ++index)
            {
                compute_cell(index);
            }
        });
    });
    progress.finish();
    return data;
}

// ---- Files ---------------------------------------------------------------------------------

void write_lut_values_inc(const std::filesystem::path& path, const std::vector<float>& data, const std::string& comment)
{
    check_finite(data, path);
    std::string text;
    text.reserve(data.size() * 18 + comment.size() + 64);
    if (!comment.empty())
    {
        std::istringstream lines(comment);
        std::string line;
        while (std::getline(lines, line))
        {
            text += "// " + line + "\n";
        }
    }
    char literal[48];
    for (std::size_t i = 0; i < data.size(); ++i)
    {
        // "%.8e": 9 significant digits, enough for any float to round-trip; the exponent makes
        // the literal a floating constant in GLSL, so the "f" suffix is valid there too.
        std::snprintf(literal, sizeof(literal), "%.8ef%s\n", double(data[i]), i + 1 < data.size() ? "," : "");
        text += literal;
    }
    write_file_atomically(path, text);
}

std::vector<float> read_lut_values_inc(const std::filesystem::path& path)
{
    const std::string text = read_whole_file(path);
    std::vector<float> values;
    std::istringstream lines(text);
    std::string line;
    int line_number = 0;
    bool expect_more = false;  // the previous value ended with a comma
    while (std::getline(lines, line))
    {
        ++line_number;
        const std::size_t comment = line.find("//");
        if (comment != std::string::npos)
        {
            line.erase(comment);
        }
        std::size_t position = 0;
        while (position < line.size())
        {
            const std::size_t comma = line.find(',', position);
            const std::size_t length = comma == std::string::npos ? std::string::npos : comma - position;
            const std::string token = line.substr(position, length);
            position = comma == std::string::npos ? line.size() : comma + 1;
            const std::size_t first = token.find_first_not_of(" \t\r");
            if (first == std::string::npos)
            {
                if (comma != std::string::npos)
                {
                    throw std::runtime_error("lut_generator: " + path.string() + ":" + std::to_string(line_number) +
                                             ": empty value between commas");
                }
                continue;
            }
            const std::size_t last = token.find_last_not_of(" \t\r");
            std::string literal = token.substr(first, last - first + 1);
            if (!literal.empty() && (literal.back() == 'f' || literal.back() == 'F'))
            {
                literal.pop_back();
            }
            char* end = nullptr;
            errno = 0;
            const float value = std::strtof(literal.c_str(), &end);
            if (literal.empty() || end != literal.c_str() + literal.size() || errno == ERANGE)
            {
                throw std::runtime_error("lut_generator: " + path.string() + ":" + std::to_string(line_number) +
                                         ": malformed value '" + token.substr(first, last - first + 1) + "'");
            }
            if (!values.empty() && !expect_more)
            {
                throw std::runtime_error("lut_generator: " + path.string() + ":" + std::to_string(line_number) +
                                         ": missing comma before '" + literal + "'");
            }
            values.push_back(value);
            expect_more = comma != std::string::npos;
        }
    }
    return values;
}

void write_lut_binary(const std::filesystem::path& path, const std::vector<float>& data)
{
    check_finite(data, path);
    write_float32_file(path, data);
}

std::vector<float> read_lut_binary(const std::filesystem::path& path, const std::size_t expected_count)
{
    const std::string bytes = read_whole_file(path);
    if (bytes.size() % sizeof(float) != 0)
    {
        throw std::runtime_error("lut_generator: " + path.string() + " has " + std::to_string(bytes.size()) +
                                 " bytes, not a whole number of float32 values");
    }
    const std::size_t count = bytes.size() / sizeof(float);
    if (expected_count != 0 && count != expected_count)
    {
        throw std::runtime_error("lut_generator: " + path.string() + " holds " + std::to_string(count) +
                                 " values, expected " + std::to_string(expected_count) + " (" +
                                 std::to_string(expected_count * sizeof(float)) + " bytes)");
    }
    return floats_from_float32_little_endian(bytes, path);
}

double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b, const int table, const LutLayout& layout)
{
    check_table(table);
    const std::size_t total = layout.total_count();
    if (a.size() != total || b.size() != total)
    {
        throw std::invalid_argument("lut_generator: max_abs_difference needs two arrays of " + std::to_string(total) +
                                    " values (layout " + std::to_string(layout.size_2d) + " / " +
                                    std::to_string(layout.size_3d) + " / " + std::to_string(layout.size_4d) + " / " +
                                    std::to_string(layout.size_4d_anisotropy) + "), got " + std::to_string(a.size()) +
                                    " and " + std::to_string(b.size()));
    }
    const std::size_t begin = layout.offset(table);
    const std::size_t end = begin + layout.count(table);
    double result = 0.0;
    for (std::size_t i = begin; i < end; ++i)
    {
        result = std::max(result, std::fabs(double(a[i]) - double(b[i])));
    }
    return result;
}

}  // namespace openpbr::host
