// Tests of the fuzz lobe (slang/lobes/openpbr_fuzz_lobe.h) and of its reference simulation and
// LTC fit (host/tables/fuzz_fit.h). Include directory: the repository root. Optional
// OPENPBR_GENERATED_DIR and OPENPBR_TABLE_DIR (string literals, e.g. "/repo/slang/generated"
// and "/repo/build/generated"): also checks that the tracked .inc and the .bin the build derives
// from it hold the table compiled into this build.
// Statistical tests use fixed seeds; the chi-square tests share a family-wise significance of
// 0.01 (Sidak correction over the configurations).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <random>
#include <vector>

#include "host/tables/fuzz_fit.h"
#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/lobes/openpbr_fuzz_lobe.h"

namespace {

using openpbr::openpbr_fuzz_ltc_data;  // OPENPBR_FUZZ_LTC_FETCH names it unqualified
using openpbr::OpenPBR_FuzzLobe;
using openpbr::OpenPBR_LobeSample;
using openpbr::vec2;
using openpbr::vec3;

constexpr double pi = 3.14159265358979323846;

struct Configuration
{
    float mu_o;
    float phi_o;  // azimuth of the view
    float roughness;
};

// Extremes, the grazing table row and column, interior points off the nodes, a rotated view.
const Configuration configurations[] = {
    {0.0f, 0.0f, 0.0f},  {0.0f, 1.0f, 0.5f}, {0.02f, 0.0f, 0.03f}, {0.15f, 2.2f, 0.1f}, {0.4f, -0.7f, 0.33f},
    {0.7f, 4.0f, 0.61f}, {1.0f, 0.0f, 1.0f}, {0.93f, 0.3f, 0.2f},  {0.5f, 0.0f, 0.0f},  {0.25f, 3.0f, 0.9f},
};
constexpr int configuration_count = int(std::size(configurations));

vec3 view_of(const Configuration& c)
{
    const float s = std::sqrt(std::max(1.0f - c.mu_o * c.mu_o, 0.0f));
    return vec3(s * std::cos(c.phi_o), s * std::sin(c.phi_o), c.mu_o);
}

OpenPBR_FuzzLobe lobe_of(const Configuration& c, vec3 weight = vec3(1.0f), vec3 color = vec3(1.0f))
{
    return openpbr::openpbr_fuzz_lobe_init(weight, color, c.roughness, view_of(c));
}

class UniformFloats
{
  public:
    explicit UniformFloats(std::uint64_t seed) : engine_(seed) {}
    float next() { return float(engine_() >> 40) * 0x1.0p-24f; }  // [0, 1), 24 bits
    vec2 next2()
    {
        const float x = next();
        return vec2(x, next());
    }

  private:
    std::mt19937_64 engine_;
};

// Upper-tail probability of the chi-square distribution with k degrees of freedom by the
// Wilson-Hilferty cube-root normal approximation (accurate for the k > 30 used here).
double chi_square_p_value(double statistic, double k)
{
    const double z = (std::cbrt(statistic / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

bool finite_non_negative(vec3 v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

// Sampling draws the density the pdf reports: chi-square over (cos theta, phi) bins with
// expected counts from the pdf integrated per bin (32 x 32 midpoint points per bin).
TEST(FuzzLobe, SamplingMatchesPdfChiSquare)
{
    constexpr int mu_bins = 16;
    constexpr int phi_bins = 32;
    constexpr int sub = 32;
    constexpr std::uint64_t samples = 1u << 20;
    const double per_test_alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / configuration_count);
    for (int index = 0; index < configuration_count; ++index)
    {
        const Configuration& c = configurations[index];
        const OpenPBR_FuzzLobe lobe = lobe_of(c);
        const vec3 view = view_of(c);
        std::vector<double> expected(mu_bins * phi_bins, 0.0);
        for (int i = 0; i < mu_bins; ++i)
        {
            for (int j = 0; j < phi_bins; ++j)
            {
                double sum = 0.0;
                for (int si = 0; si < sub; ++si)
                {
                    for (int sj = 0; sj < sub; ++sj)
                    {
                        const double mu = (i + (si + 0.5) / sub) / mu_bins;
                        const double phi = (j + (sj + 0.5) / sub) / phi_bins * 2.0 * pi;
                        const double s = std::sqrt(1.0 - mu * mu);
                        sum += openpbr::openpbr_fuzz_lobe_pdf(
                            lobe, view, vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu)));
                    }
                }
                expected[i * phi_bins + j] = sum / (sub * sub) * (2.0 * pi / (mu_bins * phi_bins)) * double(samples);
            }
        }
        std::vector<double> observed(mu_bins * phi_bins, 0.0);
        UniformFloats random(1000 + std::uint64_t(index));
        std::uint64_t failures = 0;
        for (std::uint64_t k = 0; k < samples; ++k)
        {
            const OpenPBR_LobeSample sample = openpbr::openpbr_fuzz_lobe_sample(lobe, view, random.next2());
            const vec3 d = sample.direction;
            if (sample.lobe_type == OPENPBR_LOBE_TYPE_NONE || !(d.z > 0.0f))
            {
                ++failures;
                continue;
            }
            double phi = std::atan2(double(d.y), double(d.x));
            phi = phi < 0.0 ? phi + 2.0 * pi : phi;
            const int i = std::min(int(double(d.z) * mu_bins), mu_bins - 1);
            const int j = std::min(int(phi / (2.0 * pi) * phi_bins), phi_bins - 1);
            observed[i * phi_bins + j] += 1.0;
        }
        // Pool bins with expected counts below 5 into one.
        double statistic = 0.0;
        double pooled_expected = 0.0;
        double pooled_observed = 0.0;
        int cells = 0;
        for (std::size_t b = 0; b < expected.size(); ++b)
        {
            if (expected[b] < 5.0)
            {
                pooled_expected += expected[b];
                pooled_observed += observed[b];
                continue;
            }
            statistic += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
            ++cells;
        }
        if (pooled_expected >= 5.0)
        {
            statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
            ++cells;
        }
        const double p = chi_square_p_value(statistic, cells - 1);
        EXPECT_GT(p, per_test_alpha) << "mu_o " << c.mu_o << " roughness " << c.roughness << " chi2 " << statistic
                                     << " cells " << cells;
        EXPECT_LE(failures, samples / 100000) << "samples lost at mu_o " << c.mu_o << " roughness " << c.roughness;
    }
}

// The pdf integrates to 1 over the hemisphere (midpoint rule, 4096 x 512 in (cos theta, phi)).
TEST(FuzzLobe, PdfIntegratesToOne)
{
    constexpr int mu_steps = 4096;
    constexpr int phi_steps = 512;
    for (const Configuration& c : configurations)
    {
        const OpenPBR_FuzzLobe lobe = lobe_of(c);
        const vec3 view = view_of(c);
        double sum = 0.0;
        for (int i = 0; i < mu_steps; ++i)
        {
            const double mu = (i + 0.5) / mu_steps;
            const double s = std::sqrt(1.0 - mu * mu);
            for (int j = 0; j < phi_steps; ++j)
            {
                const double phi = (j + 0.5) / phi_steps * 2.0 * pi;
                sum += openpbr::openpbr_fuzz_lobe_pdf(lobe, view,
                                                      vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu)));
            }
        }
        const double integral = sum * 2.0 * pi / (double(mu_steps) * phi_steps);
        EXPECT_NEAR(integral, 1.0, 2e-3) << "mu_o " << c.mu_o << " roughness " << c.roughness;
    }
}

// eval / pdf is the constant weight * color * R at sampled directions, and eval is BSDF x cos:
// its integral is the albedo.
TEST(FuzzLobe, SampleWeightIsConstant)
{
    const vec3 weight(0.8f, 0.6f, 1.0f);
    const vec3 color(0.9f, 0.3f, 0.5f);
    for (const Configuration& c : configurations)
    {
        const OpenPBR_FuzzLobe lobe = lobe_of(c, weight, color);
        const vec3 view = view_of(c);
        const float r = openpbr::openpbr_fuzz_albedo_white(c.mu_o, c.roughness);
        const vec3 expected = weight * color * r;
        const vec3 albedo = openpbr::openpbr_fuzz_lobe_albedo(lobe, view);
        EXPECT_NEAR(albedo.x, expected.x, 1e-6f);
        EXPECT_NEAR(albedo.y, expected.y, 1e-6f);
        EXPECT_NEAR(albedo.z, expected.z, 1e-6f);
        UniformFloats random(77);
        for (int k = 0; k < 2000; ++k)
        {
            const OpenPBR_LobeSample sample = openpbr::openpbr_fuzz_lobe_sample(lobe, view, random.next2());
            if (sample.lobe_type == OPENPBR_LOBE_TYPE_NONE)
            {
                continue;
            }
            EXPECT_EQ(sample.lobe_type, openpbr::openpbr_lobe_type(OPENPBR_LOBE_ID_FUZZ,
                                                                   OPENPBR_LOBE_TYPE_REFLECTION | OPENPBR_LOBE_TYPE_GLOSSY));
            const float pdf = openpbr::openpbr_fuzz_lobe_pdf(lobe, view, sample.direction);
            const vec3 value = openpbr::openpbr_fuzz_lobe_eval(lobe, view, sample.direction);
            if (!(pdf > 0.0f))
            {
                continue;  // a direction within rounding of the horizon
            }
            const vec3 ratio = value / pdf;
            EXPECT_NEAR(ratio.x, expected.x, 1e-5f * (1.0f + expected.x));
            EXPECT_NEAR(ratio.y, expected.y, 1e-5f * (1.0f + expected.y));
            EXPECT_NEAR(ratio.z, expected.z, 1e-5f * (1.0f + expected.z));
        }
    }
}

// R and the lobe's albedo stay in [0, 1] for weights and colors in [0, 1], and R varies
// the way the physics says: larger at grazing views, 0 through the black base at alpha = 0
// and normal incidence.
TEST(FuzzLobe, AlbedoInUnitInterval)
{
    for (int i = 0; i <= 100; ++i)
    {
        for (int j = 0; j <= 100; ++j)
        {
            const float mu = float(i) / 100.0f;
            const float roughness = float(j) / 100.0f;
            const float r = openpbr::openpbr_fuzz_albedo_white(mu, roughness);
            ASSERT_GE(r, 0.0f);
            ASSERT_LE(r, 1.0f);
            const float s = std::sqrt(1.0f - mu * mu);
            const OpenPBR_FuzzLobe lobe =
                openpbr::openpbr_fuzz_lobe_init(vec3(1.0f), vec3(1.0f, 0.5f, 0.0f), roughness, vec3(s, 0.0f, mu));
            const vec3 albedo = openpbr::openpbr_fuzz_lobe_albedo(lobe, vec3(s, 0.0f, mu));
            ASSERT_TRUE(finite_non_negative(albedo));
            ASSERT_LE(albedo.x, 1.0f);
        }
    }
    EXPECT_GT(openpbr::openpbr_fuzz_albedo_white(0.0f, 0.0f), 0.5f);
    EXPECT_LT(openpbr::openpbr_fuzz_albedo_white(1.0f, 0.0f), 1e-3f);
    for (int j = 0; j <= 10; ++j)
    {
        const float roughness = float(j) / 10.0f;
        EXPECT_GT(openpbr::openpbr_fuzz_albedo_white(0.1f, roughness), openpbr::openpbr_fuzz_albedo_white(0.9f, roughness));
    }
}

// Every output is finite and non-negative, whatever the inputs.
TEST(FuzzLobe, FiniteAtExtremes)
{
    const float nan = std::nanf("");
    const float inf = INFINITY;
    const float roughness_values[] = {0.0f, 1e-8f, 0.5f, 1.0f, -1.0f, 2.0f, nan, inf, -inf};
    const vec3 directions[] = {
        vec3(0.0f, 0.0f, 1.0f),      vec3(1.0f, 0.0f, 0.0f),    vec3(0.0f, -1.0f, 0.0f),
        vec3(0.6f, 0.8f, 1e-7f),     vec3(-1.0f, 0.0f, 1e-30f), vec3(0.0f, 0.0f, -1.0f),
        vec3(0.6f, 0.0f, -0.8f),     vec3(1e-20f, 0.0f, 1.0f),  vec3(0.70710677f, 0.0f, 0.70710677f),
        vec3(-0.9998f, 0.0f, 0.02f), vec3(0.0f, 0.0f, 0.0f),
    };
    const vec2 uniforms[] = {vec2(0.0f, 0.0f), vec2(0.99999994f, 0.99999994f), vec2(0.5f, 0.25f), vec2(1e-7f, 0.5f),
                             vec2(0.99999994f, 0.0f)};
    for (const float roughness : roughness_values)
    {
        for (const vec3 view : directions)
        {
            const OpenPBR_FuzzLobe lobe = openpbr::openpbr_fuzz_lobe_init(vec3(1.0f), vec3(1.0f), roughness, view);
            ASSERT_TRUE(finite_non_negative(openpbr::openpbr_fuzz_lobe_albedo(lobe, view)));
            ASSERT_TRUE(std::isfinite(lobe.ltc_a) && lobe.ltc_a >= OPENPBR_FUZZ_LTC_MIN_A);
            ASSERT_TRUE(std::isfinite(lobe.ltc_b));
            for (const vec3 light : directions)
            {
                const float pdf = openpbr::openpbr_fuzz_lobe_pdf(lobe, view, light);
                ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f) << roughness << " " << view.z << " " << light.z;
                ASSERT_TRUE(finite_non_negative(openpbr::openpbr_fuzz_lobe_eval(lobe, view, light)));
            }
            for (const vec2 u : uniforms)
            {
                const OpenPBR_LobeSample sample = openpbr::openpbr_fuzz_lobe_sample(lobe, view, u);
                const vec3 d = sample.direction;
                ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z));
                if (sample.lobe_type != OPENPBR_LOBE_TYPE_NONE)
                {
                    EXPECT_GT(d.z, 0.0f);
                    EXPECT_NEAR(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 1.0f, 1e-5f);
                    const float pdf = openpbr::openpbr_fuzz_lobe_pdf(lobe, view, d);
                    ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f);
                }
            }
        }
    }
    float non_finite[] = {nan, inf, -inf};
    for (const float x : non_finite)
    {
        const float r = openpbr::openpbr_fuzz_albedo_white(x, x);
        EXPECT_TRUE(r >= 0.0f && r <= 1.0f);
    }
}

// The table's transform never degenerates (det M^-1 = a^2) and b = 0 at normal incidence.
TEST(FuzzLobe, TableIsWellFormed)
{
    constexpr int n = OPENPBR_FUZZ_LTC_SIZE;
    for (int k = 0; k < n * n; ++k)
    {
        const float a = OPENPBR_FUZZ_LTC_FETCH(OPENPBR_FUZZ_LTC_A_OFFSET + k);
        const float b = OPENPBR_FUZZ_LTC_FETCH(OPENPBR_FUZZ_LTC_B_OFFSET + k);
        const float r = OPENPBR_FUZZ_LTC_FETCH(OPENPBR_FUZZ_LTC_R_OFFSET + k);
        EXPECT_GT(a, 0.01f) << k;
        EXPECT_LT(a, 2.0f) << k;
        EXPECT_LT(std::abs(b), 1.0f) << k;
        EXPECT_GE(r, 0.0f) << k;
        EXPECT_LE(r, 1.0f) << k;
        if (k % n == n - 1)
        {
            EXPECT_EQ(b, 0.0f) << "mu_o = 1 must be rotationally symmetric";
        }
    }
}

#if defined(OPENPBR_GENERATED_DIR) && defined(OPENPBR_TABLE_DIR)
TEST(FuzzFit, ShippedFilesMatchCompiledTable)
{
    const std::vector<float> compiled(std::begin(openpbr::openpbr_fuzz_ltc_data), std::end(openpbr::openpbr_fuzz_ltc_data));
    const std::vector<float> from_inc =
        openpbr::host::read_fuzz_values_inc(std::string(OPENPBR_GENERATED_DIR) + "/openpbr_fuzz_ltc_values.inc");
    const std::vector<float> from_bin = openpbr::host::read_fuzz_binary(
        std::string(OPENPBR_TABLE_DIR) + "/openpbr_fuzz_ltc.bin", std::size_t(OPENPBR_FUZZ_LTC_TOTAL_COUNT));
    EXPECT_EQ(from_inc, compiled);
    EXPECT_EQ(from_bin, compiled);
}
#endif

// --- The reference simulation -------------------------------------------------------------

// The specular SGGX phase function is sampled with the density fuzz_phase_density reports
// (chi-square over the sphere, 16 x 32 bins in (z, phi), 64 x 64 midpoint points per bin), for
// fiber-like, moderately rough and spherical flakes.
TEST(FuzzFit, PhaseSamplingMatchesDensity)
{
    struct Case
    {
        glm::dvec3 wi;
        double cross_section;
    };
    const Case cases[] = {{glm::normalize(glm::dvec3(0.8, 0.1, 0.5)), 0.15},
                          {glm::normalize(glm::dvec3(-0.2, 0.3, -0.9)), 0.6},
                          {glm::dvec3(1.0, 0.0, 0.0), 0.05},
                          {glm::dvec3(0.0, 0.0, 1.0), 1.0}};
    constexpr int z_bins = 16;
    constexpr int phi_bins = 32;
    constexpr int sub = 64;  // the c = 0.05 lobe is about 0.05 wide: fine quadrature needed
    constexpr int samples = 1 << 20;
    const double per_test_alpha = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(std::size(cases)));
    std::mt19937_64 engine(5);
    const auto uniform = [&]() { return double(engine() >> 11) * 0x1.0p-53; };
    for (const Case& c : cases)
    {
        std::vector<double> expected(z_bins * phi_bins, 0.0);
        for (int i = 0; i < z_bins; ++i)
        {
            for (int j = 0; j < phi_bins; ++j)
            {
                double sum = 0.0;
                for (int si = 0; si < sub; ++si)
                {
                    for (int sj = 0; sj < sub; ++sj)
                    {
                        const double z = -1.0 + 2.0 * (i + (si + 0.5) / sub) / z_bins;
                        const double phi = (j + (sj + 0.5) / sub) / phi_bins * 2.0 * pi;
                        const double s = std::sqrt(1.0 - z * z);
                        sum += openpbr::host::fuzz_phase_density(c.wi, glm::dvec3(s * std::cos(phi), s * std::sin(phi), z),
                                                                 c.cross_section);
                    }
                }
                expected[i * phi_bins + j] = sum / (sub * sub) * (4.0 * pi / (z_bins * phi_bins)) * samples;
            }
        }
        std::vector<double> observed(z_bins * phi_bins, 0.0);
        for (int k = 0; k < samples; ++k)
        {
            const double u1 = uniform();
            const double u2 = uniform();
            const glm::dvec3 wo = openpbr::host::fuzz_phase_sample(c.wi, c.cross_section, u1, u2);
            double phi = std::atan2(wo.y, wo.x);
            phi = phi < 0.0 ? phi + 2.0 * pi : phi;
            const int i = std::clamp(int((wo.z + 1.0) * 0.5 * z_bins), 0, z_bins - 1);
            const int j = std::min(int(phi / (2.0 * pi) * phi_bins), phi_bins - 1);
            observed[i * phi_bins + j] += 1.0;
        }
        double statistic = 0.0;
        int cells = 0;
        double total_expected = 0.0;
        for (std::size_t b = 0; b < expected.size(); ++b)
        {
            total_expected += expected[b];
            if (expected[b] >= 5.0)
            {
                statistic += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
                ++cells;
            }
        }
        EXPECT_NEAR(total_expected / samples, 1.0, 5e-3) << "the phase function integrates to 1";
        EXPECT_GT(chi_square_p_value(statistic, cells - 1), per_test_alpha)
            << "cross section " << c.cross_section << " chi2 " << statistic;
    }
}

// At alpha = c = 1 the flakes are spheres, whose specular reflection scatters isotropically: the
// simulated R must equal that of an isotropically scattering slab (independent random walk).
TEST(FuzzFit, SphericalFlakesMatchIsotropicSlab)
{
    constexpr std::uint64_t photons = 400000;
    for (const double mu_o : {1.0, 0.5, 0.1})
    {
        const openpbr::host::FuzzSimulation simulation = openpbr::host::simulate_fuzz_layer(mu_o, 1.0, photons, 8, 8, 11);
        std::mt19937_64 engine(12);
        const auto uniform = [&]() { return double(engine() >> 11) * 0x1.0p-53; };
        std::uint64_t reflected = 0;
        for (std::uint64_t k = 0; k < photons; ++k)
        {
            double z = 0.0;
            double dz = -mu_o;
            for (;;)
            {
                z += -std::log(1.0 - uniform()) * dz;  // unit extinction coefficient
                if (z > 0.0)
                {
                    ++reflected;
                    break;
                }
                if (z < -1.0)
                {
                    break;
                }
                dz = 1.0 - 2.0 * uniform();  // isotropic: cos theta uniform in [-1, 1]
            }
        }
        const double r_isotropic = double(reflected) / photons;
        const double sigma = std::sqrt(2.0 * r_isotropic * (1.0 - r_isotropic) / photons);
        EXPECT_NEAR(simulation.reflected_fraction(), r_isotropic, 5.0 * sigma) << "mu_o " << mu_o;
    }
}

// The shipped R and (a, b) are reproduced by a fresh low-count fit of a few cells, and the fit
// error (the LTC against the simulated distribution) is reported and bounded.
TEST(FuzzFit, RegeneratedCellsMatchTable)
{
    openpbr::host::FuzzFitOptions options;
    options.photons = 1u << 17;
    constexpr int n = OPENPBR_FUZZ_LTC_SIZE;
    ASSERT_EQ(options.size, n);
    const int cells[][2] = {{31, 31}, {0, 31}, {10, 10}, {20, 16}, {3, 5}, {0, 0}, {16, 3}, {5, 25}};
    for (const auto& cell : cells)
    {
        const int mu_index = cell[0];
        const int alpha_index = cell[1];
        const openpbr::host::FuzzCellReport report = openpbr::host::generate_fuzz_cell(options, mu_index, alpha_index);
        const int k = alpha_index * n + mu_index;
        const double table_a = OPENPBR_FUZZ_LTC_FETCH(OPENPBR_FUZZ_LTC_A_OFFSET + k);
        const double table_b = OPENPBR_FUZZ_LTC_FETCH(OPENPBR_FUZZ_LTC_B_OFFSET + k);
        const double table_r = OPENPBR_FUZZ_LTC_FETCH(OPENPBR_FUZZ_LTC_R_OFFSET + k);
        const double r = report.reflected_fraction;
        // R: binomial standard error of the fresh estimate (the table's is half of it), 5 sigma.
        const double sigma = std::sqrt(std::max(r * (1.0 - r), 1e-4) / double(options.photons));
        EXPECT_NEAR(r, table_r, 5.0 * 1.2 * sigma + 1e-6) << "mu_o " << report.mu_o << " alpha " << report.alpha;
        std::printf("[ fuzz fit ] mu_o %.3f alpha %.3f: R %.4f (table %.4f), a %.4f (table %.4f), b %.4f (table %.4f), "
                    "total variation %.3f (histogram noise %.3f), relative L2 %.3f\n",
                    report.mu_o, report.alpha, r, table_r, report.fit.a, table_a, report.fit.b, table_b,
                    report.fit.total_variation, report.fit.noise_total_variation, report.fit.relative_l2_error);
        if (report.fit.fitted && r > 0.1)
        {
            EXPECT_NEAR(report.fit.a, table_a, 0.05 * table_a + 0.01);
            EXPECT_NEAR(report.fit.b, table_b, 0.05);
            // Beyond the histogram's own noise; near-grazing views fit worst (the exit density does
            // not vanish at the horizon there, an LTC's does).
            EXPECT_LT(report.fit.total_variation - report.fit.noise_total_variation, report.mu_o < 0.15 ? 0.15 : 0.08);
        }
    }
}

// The lobe's reflected distribution against a fresh simulation: the table interpolated at a
// point between nodes (through the lobe itself) reproduces the simulated histogram.
TEST(FuzzFit, LobeMatchesSimulationBetweenNodes)
{
    const double mu_o = 0.37;
    const double alpha = 0.44;
    const openpbr::host::FuzzSimulation simulation = openpbr::host::simulate_fuzz_layer(
        mu_o, openpbr::host::fuzz_cross_section_from_roughness(alpha), 1u << 18, 32, 32, 99);
    const vec3 view(float(std::sqrt(1.0 - mu_o * mu_o)), 0.0f, float(mu_o));
    const OpenPBR_FuzzLobe lobe = openpbr::openpbr_fuzz_lobe_init(vec3(1.0f), vec3(1.0f), float(alpha), view);
    EXPECT_NEAR(openpbr::openpbr_fuzz_lobe_albedo(lobe, view).x, simulation.reflected_fraction(), 0.01);
    const openpbr::host::FuzzLtcFit error = openpbr::host::evaluate_fuzz_ltc(simulation, lobe.ltc_a, lobe.ltc_b);
    std::printf("[ fuzz fit ] interpolated lobe at mu_o %.2f alpha %.2f: total variation %.3f (histogram noise %.3f), "
                "relative L2 %.3f\n",
                mu_o, alpha, error.total_variation, error.noise_total_variation, error.relative_l2_error);
    EXPECT_LT(error.total_variation - error.noise_total_variation, 0.06);
}

}  // namespace
