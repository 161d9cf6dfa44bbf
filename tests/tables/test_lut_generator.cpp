// Tests for host/lut_generator: the shipped energy-compensation tables against a fresh
// low-sample regeneration, physical bounds and closed-form limits, an independent quadrature of
// the albedo integrals, determinism, half rounding and the file formats.
// Needs OPENPBR_LUT_BIN_PATH and OPENPBR_LUT_INC_PATH (string literals: the openpbr_lut.bin the
// build derives from the tracked slang/generated/openpbr_lut_values.inc, and that .inc).
#include "host/tables/lut_generator.h"

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_fresnel.h"
#include "slang/math/openpbr_ggx.h"

#include <vector>

// The look-up functions of slang/openpbr_lut.h read the shipped binary through texture mode,
// so this test checks the shading-language index order and axis maps against the generator's.
// (Array or buffer mode would define openpbr_lut_data here, beside other definitions of it in
// the host library.)
namespace {
const std::vector<float>& shipped();
float fetch_shipped(const int index) { return shipped()[std::size_t(index)]; }
}  // namespace
#define OPENPBR_LUT_MODE_TEXTURE 1
#define OPENPBR_LUT_FETCH(index) fetch_shipped(index)
#include "slang/openpbr_lut.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#ifndef OPENPBR_LUT_BIN_PATH
#error "define OPENPBR_LUT_BIN_PATH as the path of slang/generated/openpbr_lut.bin"
#endif
#ifndef OPENPBR_LUT_INC_PATH
#error "define OPENPBR_LUT_INC_PATH as the path of slang/generated/openpbr_lut_values.inc"
#endif

namespace {

using namespace openpbr::host;

const LutLayout layout = compiled_lut_layout();
const int n2 = layout.size_2d;
const int n3 = layout.size_3d;
const int e3 = layout.size_3d_eta;
const int n4 = layout.size_4d;
const int m4 = layout.size_4d_anisotropy;

const std::vector<float>& shipped()
{
    // The whole buffer: the compensation tables, then the film table (slang/openpbr_lut.h).
    static const std::vector<float> data = read_lut_binary(OPENPBR_LUT_BIN_PATH, 0);
    return data;
}

float at_2d(const std::vector<float>& data, const int mu_index, const int r_index)
{
    return data[layout.offset(lut_table_ggx_albedo) + std::size_t(r_index) * n2 + mu_index];
}

float at_3d(const std::vector<float>& data, const int table, const int mu_index, const int r_index, const int x_index)
{
    return data[layout.offset(table) + (std::size_t(x_index) * n3 + r_index) * n3 + mu_index];
}

float at_4d(const std::vector<float>& data, const int mu_index, const int r_index, const int a_index, const int phi_index)
{
    return data[layout.offset(lut_table_ggx_anisotropy_ratio) +
                ((std::size_t(phi_index) * m4 + a_index) * n4 + r_index) * n4 + mu_index];
}

double node(const int i, const int n) { return double(i) / double(n - 1); }

// The relative IOR and view cosine of a node of tables 1-3 (x the eta node, r the roughness
// node, mu the view node; below eta = 1 the view axis depends on alpha).
double eta_of_node(const int x) { return lut_eta_from_node(x, e3); }
double mu_of_node(const int mu, const int r, const int x)
{
    return lut_mu_from_view_coordinate(node(mu, n3), eta_of_node(x), lut_alpha_from_coordinate(node(r, n3)));
}
// E_ggx from the shipped table 0 at view cosine mu and roughness coordinate r, as the shading
// language reads it.
double shipped_ggx_albedo(const double mu, const double r)
{
    return openpbr::openpbr_lut_2d(OPENPBR_LUT_GGX_ALBEDO_OFFSET, openpbr::openpbr_lut_mu_coordinate(float(mu)), float(r));
}

// The physical parameters of a node of table 4.
struct AnisotropicNode
{
    double mu, r, anisotropy, cos_phi_squared;
};

AnisotropicNode anisotropic_node(const int mu_index, const int r_index, const int a_index, const int phi_index)
{
    AnisotropicNode p;
    p.mu = lut_mu_from_coordinate(node(mu_index, n4));
    p.r = node(r_index, n4);
    p.anisotropy = lut_anisotropy_from_coordinate(node(a_index, m4));
    p.cos_phi_squared = lut_cos_phi_squared_from_coordinate(node(phi_index, m4), p.mu, p.r, p.anisotropy);
    return p;
}

// F = 1 reflection albedo of GGX with alpha = (alpha_x, alpha_y) for the view wo, by the
// midpoint rule over the whole hemisphere of light directions (the view's azimuth breaks the
// phi -> -phi symmetry): E = integral of D(h) G2 / (4 wo.z), h = normalize(wo + wi).
double quadrature_ggx_albedo(const openpbr::vec3 wo, const openpbr::vec2 alpha)
{
    using openpbr::vec3;
    const float lambda_o = openpbr::openpbr_ggx_lambda(wo, alpha);
    const int n_theta = 1024;
    const int n_phi = 2048;
    const double d_theta = 0.5 * M_PI / n_theta;
    const double d_phi = 2.0 * M_PI / n_phi;
    double sum = 0.0;
    for (int i = 0; i < n_theta; ++i)
    {
        const double theta = (i + 0.5) * d_theta;
        const double sin_theta = std::sin(theta);
        for (int j = 0; j < n_phi; ++j)
        {
            const double phi = (j + 0.5) * d_phi;
            const vec3 wi(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(std::cos(theta)));
            const vec3 h = openpbr::normalize(wo + wi);
            const float g2 = openpbr::openpbr_ggx_g2(lambda_o, openpbr::openpbr_ggx_lambda(wi, alpha));
            sum += double(openpbr::openpbr_ggx_d(h, alpha) * g2 / (4.0f * wo.z)) * sin_theta;
        }
    }
    return sum * d_theta * d_phi;
}

// ---- Independent reference: the albedo integral by quadrature over light directions ----------
//
// E = integral over wi of f |wi.z|, with the BSDFs written out (Walter et al. 2007):
//   reflection    f |cos_i| = F(wo.h) D(h) G2 / (4 wo.z),                h = normalize(wo + wi)
//   transmission  f |cos_i| = eta^2 |wi.h| |wo.h| D(h) G2 / (wo.z (wo.h + eta wi.h)^2),
//                 h = -normalize(wo + eta wi), valid where wo.h > 0 and wi.h < 0
// (times 1 - F for E_RT). The generator never evaluates these: it samples visible normals and
// uses G2 / G1, so agreement checks its directions, weights and sampling density.
// mu_value is the view cosine, r the roughness coordinate, eta_value the relative IOR.
double quadrature_albedo(const int table, const double mu_value, const double r, const double eta_value)
{
    using openpbr::vec2;
    using openpbr::vec3;
    const float mu_o = float(mu_value);
    const vec3 wo(std::sqrt(1.0f - mu_o * mu_o), 0.0f, mu_o);
    const vec2 alpha(float(lut_alpha_from_coordinate(r)));
    const float eta = float(eta_value);
    const float lambda_o = openpbr::openpbr_ggx_lambda(wo, alpha);
    const bool reflection = table != lut_table_dielectric_transmission;
    const bool transmission = table == lut_table_dielectric_transmission || table == lut_table_dielectric_interface;

    // Midpoint rule in (theta, phi); the integrand is symmetric in phi -> -phi.
    const int n_theta = 1024;
    const int n_phi = 1024;
    const double d_theta = 0.5 * M_PI / n_theta;
    const double d_phi = M_PI / n_phi;
    double sum = 0.0;
    for (int side = 0; side < 2; ++side)
    {
        if ((side == 0 && !reflection) || (side == 1 && !transmission))
        {
            continue;
        }
        for (int i = 0; i < n_theta; ++i)
        {
            const double theta = (i + 0.5) * d_theta;
            const double sin_theta = std::sin(theta);
            const double cos_theta = std::cos(theta);
            for (int j = 0; j < n_phi; ++j)
            {
                const double phi = (j + 0.5) * d_phi;
                const vec3 wi(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)),
                              float(side == 0 ? cos_theta : -cos_theta));
                const float g2 = openpbr::openpbr_ggx_g2(lambda_o, openpbr::openpbr_ggx_lambda(wi, alpha));
                double value = 0.0;
                if (side == 0)
                {
                    const vec3 h = openpbr::normalize(wo + wi);
                    const float f =
                        table == lut_table_ggx_albedo ? 1.0f : openpbr::openpbr_fresnel_dielectric(openpbr::dot(wo, h), eta);
                    value = f * openpbr::openpbr_ggx_d(h, alpha) * g2 / (4.0f * wo.z);
                }
                else
                {
                    vec3 h = -openpbr::normalize(wo + eta * wi);
                    if (h.z < 0.0f)
                    {
                        h = -h;
                    }
                    const float wo_h = openpbr::dot(wo, h);
                    const float wi_h = openpbr::dot(wi, h);
                    if (wo_h <= 0.0f || wi_h >= 0.0f)
                    {
                        continue;
                    }
                    const float f = table == lut_table_dielectric_interface
                                        ? 1.0f - openpbr::openpbr_fresnel_dielectric(wo_h, eta)
                                        : 1.0f;
                    const float denominator = wo_h + eta * wi_h;
                    value = f * eta * eta * std::fabs(wi_h) * wo_h * openpbr::openpbr_ggx_d(h, alpha) * g2 /
                            (wo.z * denominator * denominator);
                }
                sum += value * sin_theta;
            }
        }
    }
    return 2.0 * sum * d_theta * d_phi;
}

// ---- The shipped files -------------------------------------------------------------------------

TEST(LutGenerator, ShippedBinaryHasTheCompiledLayout)
{
    EXPECT_EQ(layout.total_count(), std::size_t(OPENPBR_LUT_COMPENSATION_COUNT));
    EXPECT_EQ(shipped().size(), layout.total_count() + OPENPBR_LUT_FILM_COUNT);
    EXPECT_EQ(std::filesystem::file_size(OPENPBR_LUT_BIN_PATH), std::size_t(OPENPBR_LUT_TOTAL_COUNT) * sizeof(float));
}

// openpbr_lut.bin is the compensation tables' .inc followed by the film table's .inc.
TEST(LutGenerator, ShippedIncsAndBinaryHoldTheSameFloats)
{
    std::vector<float> from_incs = read_lut_values_inc(OPENPBR_LUT_INC_PATH);
    const std::vector<float> film = read_lut_values_inc(OPENPBR_FILM_LUT_INC_PATH);
    EXPECT_EQ(from_incs.size(), std::size_t(OPENPBR_LUT_COMPENSATION_COUNT));
    EXPECT_EQ(film.size(), std::size_t(OPENPBR_LUT_FILM_COUNT));
    from_incs.insert(from_incs.end(), film.begin(), film.end());
    ASSERT_EQ(from_incs.size(), shipped().size());
    for (std::size_t i = 0; i < from_incs.size(); ++i)
    {
        ASSERT_EQ(std::memcmp(&from_incs[i], &shipped()[i], sizeof(float)), 0)
            << "entry " << i << ": .inc " << from_incs[i] << ", .bin " << shipped()[i];
    }
}

class ShippedInc : public ::testing::TestWithParam<std::pair<const char*, std::size_t>>
{
};

TEST_P(ShippedInc, LiteralsAreValidInEveryShadingLanguage)
{
    // GLSL needs a decimal point or an exponent before the "f" suffix ("1f" is an error there).
    std::ifstream file(GetParam().first);
    std::string line;
    std::size_t literals = 0;
    while (std::getline(file, line))
    {
        if (line.rfind("//", 0) == 0)
        {
            continue;
        }
        if (!line.empty() && line.back() == ',')
        {
            line.pop_back();
        }
        ASSERT_FALSE(line.empty());
        EXPECT_EQ(line.back(), 'f') << line;
        EXPECT_NE(line.find_first_of(".eE"), std::string::npos) << line;
        ++literals;
    }
    EXPECT_EQ(literals, GetParam().second);
}

INSTANTIATE_TEST_SUITE_P(CompensationAndFilm, ShippedInc,
                         ::testing::Values(std::make_pair(OPENPBR_LUT_INC_PATH, std::size_t(OPENPBR_LUT_COMPENSATION_COUNT)),
                                           std::make_pair(OPENPBR_FILM_LUT_INC_PATH, std::size_t(OPENPBR_LUT_FILM_COUNT))),
                         [](const ::testing::TestParamInfo<std::pair<const char*, std::size_t>>& info) {
                             return std::string(info.index == 0 ? "compensation" : "film");
                         });

// A regeneration with 4096 samples per cell (instead of the shipped 65536) must reproduce the
// shipped tables. Every sample weight lies in [0, 1], so plain Monte Carlo with 4096 samples
// would have a standard deviation of at most 0.5 / 64 = 0.008 per cell; the (0, 2)-sequence
// converges about as N^-0.85 here (max error over the 13312 cells: 1.0e-2 at 1024 samples,
// 3.4e-3 at 4096, 1.4e-3 at 8192, the worst cells being those whose visible normals straddle a
// total-internal-reflection boundary). The tolerance, 0.01, is three times the observed error
// and well below what a wrong index order, axis map or weight produces (> 0.03).
TEST(LutGenerator, LowSampleRegenerationMatchesTheShippedTables)
{
    LutGeneratorOptions options;
    options.samples = 4096;
    options.progress = false;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> regenerated = generate_lut(options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The compensation tables: the shipped buffer without the film table that follows them.
    const std::vector<float> compensation(shipped().begin(), shipped().begin() + std::ptrdiff_t(layout.total_count()));
    ASSERT_EQ(regenerated.size(), compensation.size());
    for (int table = 0; table < lut_table_count; ++table)
    {
        const double difference = max_abs_difference(regenerated, compensation, table);
        std::printf("  %-24s max |4096 samples - shipped| = %.2e\n", lut_table_name(table), difference);
        EXPECT_LE(difference, 0.01) << lut_table_name(table);
    }
    std::printf("  regeneration with 4096 samples/cell: %.2f s\n", seconds);
}

// ---- Physical bounds and closed-form limits of the shipped tables -------------------------

// ---- The anisotropic table ---------------------------------------------------------------------

TEST(LutGenerator, AnisotropyRatioIsOneAtZeroAnisotropy)
{
    // a = 0: alpha_t = alpha_b = max(r^2, 1e-4), the same lobe as the denominator's, estimated
    // from the same points.
    for (int phi = 0; phi < m4; ++phi)
    {
        for (int r = 0; r < n4; ++r)
        {
            for (int mu = 0; mu < n4; ++mu)
            {
                ASSERT_EQ(at_4d(shipped(), mu, r, 0, phi), 1.0f) << "mu node " << mu << ", r node " << r;
            }
        }
    }
}

TEST(LutGenerator, AnisotropicAlbedosAreAlbedos)
{
    // ratio x E_ggx(mu, r) must lie in [0, 1]; table 0's nodes differ from table 4's, so the
    // isotropic albedo comes from a fresh estimate (16384 samples, noise below 1e-4).
    double largest = 0.0;
    for (int r = 0; r < n4; r += 3)
    {
        for (int mu = 0; mu < n4; mu += 3)
        {
            const double isotropic = estimate_lut_entry(lut_table_ggx_albedo, node(mu, n4), node(r, n4), 0.5, 16384,
                                                        lut_cell_seed(0, 7919u * r + mu, 1));
            for (int a = 0; a < m4; ++a)
            {
                for (int phi = 0; phi < m4; ++phi)
                {
                    const double albedo = at_4d(shipped(), mu, r, a, phi) * isotropic;
                    largest = std::max(largest, albedo);
                    EXPECT_GT(albedo, 0.2)
                        << "mu node " << mu << ", r node " << r << ", a node " << a << ", phi node " << phi;
                    EXPECT_LE(albedo, 1.0 + 1e-3)
                        << "mu node " << mu << ", r node " << r << ", a node " << a << ", phi node " << phi;
                }
            }
        }
    }
    std::printf("  largest anisotropic albedo at the nodes: %.5f\n", largest);
}

TEST(LutGenerator, AnisotropicTableIsSymmetricWhereTheAzimuthIsUndefined)
{
    // At normal incidence every azimuth is the same view: only the per-cell noise differs.
    for (int a = 0; a < m4; ++a)
    {
        for (int r = 0; r < n4; ++r)
        {
            for (int phi = 1; phi < m4; ++phi)
            {
                EXPECT_NEAR(at_4d(shipped(), n4 - 1, r, a, phi), at_4d(shipped(), n4 - 1, r, a, 0), 1e-3)
                    << "r node " << r << ", a node " << a << ", phi node " << phi;
            }
        }
    }
}

TEST(LutGenerator, AnisotropicTableMatchesAnIndependentQuadrature)
{
    struct Point
    {
        int mu, r, a, phi;  // node indices
    };
    // Anisotropy nodes below a ~ 0.95 only: the midpoint rule cannot resolve the needle-like
    // lobes of alpha_b -> 0.
    const int last = n4 - 1;
    const int top_a = m4 - 3;
    const Point points[] = {
        {last, last, top_a, 0},         {last / 2, (2 * last) / 3, top_a / 2, (m4 - 1) / 3},
        {last / 4, last, top_a, 0},     {last / 4, last, top_a, m4 - 1},
        {last / 3, last / 2, top_a, 1}, {2, last, top_a - 1, (m4 - 1) / 2},
    };
    double worst = 0.0;
    for (const Point& p : points)
    {
        const AnisotropicNode n = anisotropic_node(p.mu, p.r, p.a, p.phi);
        const double b = 1.0 - n.anisotropy;
        const double alpha_t = lut_alpha_from_coordinate(n.r) * std::sqrt(2.0 / (1.0 + b * b));
        const double sin_theta = std::sqrt(1.0 - n.mu * n.mu);
        const openpbr::vec3 wo(float(sin_theta * std::sqrt(n.cos_phi_squared)),
                               float(sin_theta * std::sqrt(1.0 - n.cos_phi_squared)), float(n.mu));
        const double reference =
            quadrature_ggx_albedo(wo, openpbr::vec2(float(alpha_t), float(std::max(b * alpha_t, 1e-7)))) /
            quadrature_ggx_albedo(wo, openpbr::vec2(float(lut_alpha_from_coordinate(n.r))));
        const double value = at_4d(shipped(), p.mu, p.r, p.a, p.phi);
        worst = std::max(worst, std::fabs(value - reference));
        // Observed: 7e-5 at most.
        EXPECT_NEAR(value, reference, 1e-3) << "node mu " << p.mu << ", r " << p.r << ", a " << p.a << ", phi " << p.phi;
    }
    std::printf("  max |table - quadrature| = %.2e\n", worst);
}

TEST(LutGenerator, AzimuthCoordinateMatchesTheShadingLanguage)
{
    for (const double mu : {1e-4, 0.01, 0.1, 0.5, 0.99, 1.0})
    {
        for (const double r : {0.0, 0.2, 0.7, 1.0})
        {
            for (const double a : {0.0, 0.3, 0.9, 1.0})
            {
                double previous = -1.0;
                for (int i = 0; i <= 20; ++i)
                {
                    const double cos_phi_squared = double(i) / 20.0;
                    const double coordinate = lut_azimuth_coordinate(mu, r, a, cos_phi_squared);
                    EXPECT_NEAR(
                        openpbr::openpbr_lut_azimuth_coordinate(float(mu), float(r), float(a), float(cos_phi_squared)),
                        coordinate, 1e-5);
                    EXPECT_GE(coordinate, previous);
                    previous = coordinate;
                    // The inverse is ill-conditioned only where the map is flat (grazing, a -> 1).
                    if (mu >= 0.01)
                    {
                        EXPECT_NEAR(lut_cos_phi_squared_from_coordinate(coordinate, mu, r, a), cos_phi_squared, 1e-9)
                            << "mu " << mu << ", r " << r << ", a " << a;
                    }
                }
                EXPECT_EQ(lut_azimuth_coordinate(mu, r, a, 0.0), 0.0);
                EXPECT_NEAR(lut_azimuth_coordinate(mu, r, a, 1.0), 1.0, 1e-12);
            }
        }
    }
}

TEST(LutGenerator, ViewCoordinateMatchesTheShadingLanguage)
{
    // The 3D tables' view axis in float (slang/openpbr_lut.h) and in double (the generator), at
    // the relative IORs users set, the eta = 1 limits and the range ends, at the roughness ends
    // and the smooth lobes whose critical step the warp resolves, and at views next to mu_c.
    const double unit_below = lut_eta_from_node(e3 / 2 - 1, e3);
    for (const double eta : {1.0 / 3.0, 0.5, 0.75, 0.9, 0.99, 0.999, unit_below, 1.0, 1.001, 1.5, 3.0})
    {
        const double critical = lut_critical_cosine(eta);
        for (const double alpha : {0.0, 1e-4, 0.0016, 0.0025, 0.04, 0.25, 1.0})
        {
            const float step_width =
                openpbr::openpbr_lut_step_width(float(alpha), float(eta), openpbr::openpbr_lut_critical_cosine(float(eta)));
            EXPECT_EQ(step_width > 0.0f, eta < 1.0);
            EXPECT_NEAR(lut_view_coordinate(critical, eta, alpha), lut_view_split(eta), 1e-12);
            // mu_c is a node of the axis (the split a whole number of cells).
            const double split_cells = lut_view_split(eta) * (OPENPBR_LUT_3D_SIZE - 1);
            EXPECT_EQ(split_cells, std::round(split_cells)) << "eta " << eta;
            double previous = -1.0;
            for (const double offset : {-1.0, -0.3, -0.01, -0.001, -1e-4, 0.0, 1e-4, 0.001, 0.003, 0.01, 0.05, 0.3, 1.0})
            {
                const double mu = std::clamp(critical + offset, 1e-4, 1.0);
                const double coordinate = lut_view_coordinate(mu, eta, alpha);
                // Float against double at the same (float) inputs, compared as the view cosine the
                // float coordinate stands for: next to mu_c of a smooth lobe the axis stretches a
                // float ulp of mu or of mu_c over up to 3e-4 of the coordinate, so the
                // coordinates differ there as much as the albedos do between mu and its float
                // neighbours; and near grazing the lower half's 1/2 - g/2 cancels (coordinate
                // 0.001, error 1e-8). Bound 1e-4 of mu; largest measured 4.0e-5 (at mu 1e-4), 1.9e-6
                // at mu 0.34.
                const float mu_float = float(mu);
                const float eta_float = float(eta);
                const float shading = openpbr::openpbr_lut_view_coordinates(mu_float, float(alpha), eta_float,
                                                                            openpbr::openpbr_lut_critical_cosine(eta_float))
                                          .x;
                EXPECT_NEAR(lut_mu_from_view_coordinate(shading, eta_float, alpha), double(mu_float), 1e-4 * mu)
                    << "eta " << eta << ", alpha " << alpha << ", mu " << mu << ": coordinate " << shading << " against "
                    << coordinate;
                EXPECT_GE(coordinate, previous);
                previous = coordinate;
                // The generator's inverse puts each node at the view the look-up maps to it.
                EXPECT_NEAR(lut_mu_from_view_coordinate(coordinate, eta, alpha), mu, 1e-9 + 1e-9 * mu)
                    << "eta " << eta << ", alpha " << alpha << ", mu " << mu;
            }
            EXPECT_EQ(lut_view_coordinate(0.0, eta, alpha), 0.0);
            EXPECT_NEAR(lut_view_coordinate(1.0, eta, alpha), 1.0, 1e-12);
        }
    }
}

TEST(LutGenerator, LookUpResolvesTheCriticalStepBelowUnitEta)
{
    // Seen from the less dense side the interface's albedos step at the critical cosine mu_c =
    // sqrt(1 - eta^2) over a width of about alpha (docs/stability.md "Critical angle below
    // relative IOR 1"). The look-up (view axis warped towards mu_c on the scale of alpha,
    // interpolated in r and along eta) against Monte Carlo at the furnace's critical rows'
    // relative IORs and roughnesses, at views from 0.01 before to 0.04 past mu_c, which fall
    // between the table's nodes on every axis. Measured largest |look-up - Monte Carlo| (2^16
    // samples per value, standard error below 1e-3): E_R 0.0173, past mu_c at roughness 0.05
    // (between the r nodes 1/32 and 1/16, where the warp's scale changes fourfold; 0.004 at r
    // 0.1), read too high there: the refraction gets less light, a loss; E_T0 0.032, before mu_c
    // (mu_c - 0.003 and - 0.01), where the warp's linear weight 16 keeps longer cells for the
    // grazing views (0.011 with weight 6, which loses twice as much at cos 0.001); with the plain
    // axis (16 cells per side of mu_c) up to 0.46 and 0.49 (1D study).
    double largest_reflection = 0.0;
    double largest_transmission = 0.0;
    for (const double eta : {0.5, 0.75, 0.9, 0.95, 0.99})
    {
        const double critical = std::sqrt(1.0 - eta * eta);
        for (const double roughness : {0.05, 0.1, 0.2})
        {
            const double alpha = roughness * roughness;
            for (const double offset : {-0.01, -0.003, 0.0, 0.002, 0.005, 0.01, 0.02, 0.04})
            {
                const double mu = critical + offset;
                const double reflection =
                    openpbr::openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET, float(mu), float(alpha), float(eta));
                const double transmission =
                    openpbr::openpbr_lut_3d(OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET, float(mu), float(alpha), float(eta));
                const double reflection_error =
                    reflection - estimate_dielectric_entry(lut_table_dielectric_reflection, mu, alpha, eta, 1u << 16, 7);
                const double transmission_error =
                    transmission - estimate_dielectric_entry(lut_table_dielectric_transmission, mu, alpha, eta, 1u << 16, 7);
                EXPECT_LE(std::fabs(reflection_error), 0.022)
                    << "E_R at eta " << eta << ", roughness " << roughness << ", mu_c + " << offset;
                EXPECT_LE(std::fabs(transmission_error), 0.04)
                    << "E_T0 at eta " << eta << ", roughness " << roughness << ", mu_c + " << offset;
                largest_reflection = std::max(largest_reflection, std::fabs(reflection_error));
                largest_transmission = std::max(largest_transmission, std::fabs(transmission_error));
            }
        }
    }
    std::printf("largest |look-up - Monte Carlo| next to mu_c: E_R %.4f, E_T0 %.4f\n", largest_reflection,
                largest_transmission);
}

TEST(LutGenerator, AnisotropicLookUpReturnsTheNodeValues)
{
    // openpbr_ggx_albedo_anisotropic at the physical parameters of a node reads that node: the
    // shading-language layout, axis maps and index order agree with the generator's.
    for (int phi = 0; phi < m4; phi += 3)
    {
        for (int a = 0; a < m4; a += 2)
        {
            for (int r = 0; r < n4; r += 3)
            {
                for (int mu = 1; mu < n4; mu += 2)
                {
                    const AnisotropicNode n = anisotropic_node(mu, r, a, phi);
                    const float value = openpbr::openpbr_ggx_anisotropy_ratio(float(n.mu), float(n.r), float(n.anisotropy),
                                                                              float(n.cos_phi_squared));
                    EXPECT_NEAR(value, at_4d(shipped(), mu, r, a, phi), 2e-4)
                        << "node mu " << mu << ", r " << r << ", a " << a << ", phi " << phi;
                }
            }
        }
    }
    // The 2D accessor likewise, and the anisotropic albedo is the isotropic one at anisotropy 0.
    const double mu_coordinate = node(n2 / 4, n2);
    const double r_coordinate = node(n2 / 2, n2);
    EXPECT_NEAR(openpbr::openpbr_ggx_albedo(float(mu_coordinate * mu_coordinate), float(r_coordinate * r_coordinate)),
                at_2d(shipped(), n2 / 4, n2 / 2), 1e-5);
    for (const float mu : {0.05f, 0.3f, 0.8f})
    {
        for (const float r : {0.2f, 0.55f, 0.9f})
        {
            EXPECT_NEAR(openpbr::openpbr_ggx_albedo_anisotropic(mu, r, 0.0f, 0.4f), openpbr::openpbr_ggx_albedo(mu, r * r),
                        1e-6)
                << "mu " << mu << ", r " << r;
        }
    }
}

TEST(LutGenerator, ShippedValuesAreAlbedos)
{
    // Tables 0-2 are albedos or (table 1) an average Fresnel factor; table 3 is E_RT / E_ggx,
    // which exceeds 1 where refraction adds to a shadowed reflection (SmoothInterfaceConservesEnergy
    // bounds E_RT itself); table 4 holds ratios (AnisotropicAlbedosAreAlbedos checks it).
    for (std::size_t i = 0; i < layout.offset(lut_table_ggx_anisotropy_ratio); ++i)
    {
        ASSERT_GE(shipped()[i], 0.0f) << "entry " << i;
        if (i < layout.offset(lut_table_dielectric_interface))
        {
            ASSERT_LE(shipped()[i], 1.0f + 1e-6f) << "entry " << i;
        }
    }
}

TEST(LutGenerator, SmoothMirrorReflectsEverything)
{
    // r = 0 is the delta limit: E_ggx = 1 wherever the alpha floor (1e-4) is negligible next to
    // mu, i.e. from mu = 0.01 on (on the sqrt(mu) axis nodes 1 and 2 of 32 lie at mu = 0.001 and
    // 0.004, where E is 0.9946 and 0.9997).
    for (int mu = 1; mu < n2; ++mu)
    {
        if (lut_mu_from_coordinate(node(mu, n2)) >= 0.01)
        {
            EXPECT_NEAR(at_2d(shipped(), mu, 0), 1.0f, 1e-4f) << "mu node " << mu;
        }
    }
    // Rough GGX loses energy to multiple scattering, the more the rougher. Toward grazing view
    // the single-scattering albedo rises again (Lambda(wo) -> infinity, so G2 / G1 -> 1, and
    // every mirrored visible normal sends the light upward): at r = 1 E falls from about 1 at
    // mu -> 0 to about 0.31 at mu = 1.
    EXPECT_LT(at_2d(shipped(), n2 - 1, n2 - 1), 0.35f);
    EXPECT_GT(at_2d(shipped(), 0, n2 - 1), 0.99f);
    for (int r = 1; r < n2; ++r)
    {
        EXPECT_LE(at_2d(shipped(), n2 - 1, r), at_2d(shipped(), n2 - 1, r - 1) + 1e-6f) << "r node " << r;
    }
    for (int mu = 1; mu < n2; ++mu)
    {
        EXPECT_LE(at_2d(shipped(), mu, n2 - 1), at_2d(shipped(), mu - 1, n2 - 1) + 1e-6f) << "mu node " << mu;
    }
}

TEST(LutGenerator, NormalIncidenceReflectionIsF0)
{
    for (int x = 0; x < e3; ++x)
    {
        const double eta = eta_of_node(x);
        const double f0 = std::pow((eta - 1.0) / (eta + 1.0), 2.0);
        EXPECT_NEAR(at_3d(shipped(), lut_table_dielectric_reflection, n3 - 1, 0, x), f0, 1e-3) << "eta " << eta;
    }
    // eta = 1 exactly (x = 0.5; the nodes are 2^-20 away): no interface, no reflection.
    EXPECT_NEAR(estimate_lut_entry(lut_table_dielectric_reflection, 0.7, 0.5, 0.5, 4096, 1), 0.0, 1e-7);
    EXPECT_NEAR(estimate_lut_entry(lut_table_dielectric_reflection, 1.0, 0.0, 0.5, 4096, 1), 0.0, 1e-7);
}

TEST(LutGenerator, SmoothInterfaceConservesEnergy)
{
    for (int x = 0; x < e3; ++x)
    {
        for (int r = 0; r < n3; ++r)
        {
            for (int mu = 0; mu < n3; ++mu)
            {
                // E_RT = table 3 x E_ggx (openpbr_dielectric_interface_albedo): the F = 1
                // albedo at the node from table 0, whose interpolation adds up to 1.7e-3
                // (largest of 400 random grazing points against Monte Carlo).
                const double e_ggx = shipped_ggx_albedo(mu_of_node(mu, r, x), node(r, n3));
                EXPECT_LE(at_3d(shipped(), lut_table_dielectric_interface, mu, r, x) * e_ggx, 1.0 + 2e-3)
                    << "mu node " << mu << ", r node " << r << ", x node " << x;
            }
        }
        // r = 0: reflection + refraction of a smooth interface sum to 1 (views below mu = 0.0017,
        // where the alpha floor 1e-4 is not negligible, are excluded).
        // Near the critical cosine of a nearly index-matched interface (below 0.1) the floor
        // is not negligible either: the total internal reflection of a lobe 0.01 rad wide
        // sets in within 0.1 of grazing there (0.947 measured at the critical node of
        // eta 0.9997, 0.996-0.998 three to five nodes below it on the plain view axis; on the
        // warped axis 0.988 at 1.03 mu_c and 0.997 at 0.81 mu_c of eta 1 - 3e-6), so the views
        // from 0.45 mu_c to 1.1 mu_c are left out there (five nodes below to one above the
        // critical node on the plain axis reached from 0.47 mu_c to 4.8 mu_c).
        for (int mu = 1; mu < n3; ++mu)
        {
            const double critical = lut_critical_cosine(eta_of_node(x));
            const double mu_value = mu_of_node(mu, 0, x);
            if (mu_value < 0.0017 || (critical < 0.1 && mu_value >= 0.45 * critical && mu_value <= 1.1 * critical))
            {
                continue;
            }
            EXPECT_NEAR(at_3d(shipped(), lut_table_dielectric_interface, mu, 0, x), 1.0f, 2e-3f)
                << "mu node " << mu << ", x node " << x;
        }
    }
    // eta = 1 with small roughness: the light passes straight through.
    EXPECT_NEAR(estimate_dielectric_entry(lut_table_dielectric_transmission, 0.36, 0.0, 1.0, 4096, 1), 1.0, 1e-4);
    EXPECT_NEAR(estimate_dielectric_entry(lut_table_dielectric_transmission, 0.36, 0.01, 1.0, 4096, 1), 1.0, 1e-3);
    EXPECT_NEAR(estimate_dielectric_entry(lut_table_dielectric_interface, 0.36, 0.01, 1.0, 4096, 1), 1.0, 1e-3);
}

TEST(LutGenerator, TotalInternalReflection)
{
    // Inside the denser medium (eta < 1) at grazing view beyond the critical angle a smooth
    // interface transmits nothing and reflects everything: eta = 1/3 at x = 0 (critical cosine
    // 0.943), the last view node below mu = 0.3 (0.26 on the warped axis) gives sin_t = 0.97 * 3
    // > 1.
    int mu = 1;
    while (mu_of_node(mu + 1, 0, 0) < 0.3)
    {
        ++mu;
    }
    ASSERT_GT(mu_of_node(mu, 0, 0), 0.1);
    EXPECT_NEAR(at_3d(shipped(), lut_table_dielectric_transmission, mu, 0, 0), 0.0f, 1e-4f);
    EXPECT_NEAR(at_3d(shipped(), lut_table_dielectric_reflection, mu, 0, 0), 1.0f, 2e-3f);
}

TEST(LutGenerator, ShippedTablesMatchAnIndependentQuadrature)
{
    struct Point
    {
        int table;
        int mu, r, x;  // node indices
    };
    const int last = n3 - 1;
    // Eta nodes 1.37 (e3 - 6), 2.0 (e3 - 3), 0.66 (4), 0.79 (6) and 0.89 (8): away from
    // eta = 1, where the refracted lobe narrows below what this 1024 x 1024 midpoint rule
    // resolves (eta 1.015, alpha 0.25, mu 0.17: quadrature 0.8382, the table and 2^20-sample
    // Monte Carlo 0.8339).
    const Point points[] = {
        {lut_table_ggx_albedo, n2 - 1, n2 - 1, 0},
        {lut_table_ggx_albedo, n2 / 4, (2 * n2) / 3, 0},
        {lut_table_ggx_albedo, 1, n2 - 1, 0},
        {lut_table_dielectric_reflection, last / 2, last / 2, e3 - 6},
        {lut_table_dielectric_reflection, last / 5, last, 4},
        {lut_table_dielectric_reflection, last / 3, last / 4, 8},
        {lut_table_dielectric_transmission, last / 2, last / 2, e3 - 6},
        {lut_table_dielectric_transmission, (3 * last) / 4, last, 4},
        {lut_table_dielectric_transmission, (2 * last) / 5, last / 4, e3 - 3},
        {lut_table_dielectric_interface, last / 3, (2 * last) / 3, e3 - 6},
        {lut_table_dielectric_interface, last, last, 6},
    };
    for (const Point& p : points)
    {
        const bool dielectric = p.table != lut_table_ggx_albedo;
        const int n = dielectric ? n3 : n2;
        const double mu_value = dielectric ? mu_of_node(p.mu, p.r, p.x) : lut_mu_from_coordinate(node(p.mu, n));
        double reference = quadrature_albedo(p.table, mu_value, node(p.r, n), dielectric ? eta_of_node(p.x) : 1.0);
        // Tables 1 and 3 hold E_R and E_RT over the F = 1 albedo of the same lobe.
        if (p.table == lut_table_dielectric_reflection || p.table == lut_table_dielectric_interface)
        {
            reference /= quadrature_albedo(lut_table_ggx_albedo, mu_value, node(p.r, n), 1.0);
        }
        const float value =
            p.table == lut_table_ggx_albedo ? at_2d(shipped(), p.mu, p.r) : at_3d(shipped(), p.table, p.mu, p.r, p.x);
        // Observed: |table - quadrature| from 6e-7 to 5.6e-4 (the latter in a cell with a total
        // internal reflection boundary, where the midpoint rule is least accurate and the 16384
        // sample estimate noisiest).
        EXPECT_NEAR(value, reference, 1e-3)
            << lut_table_name(p.table) << " at node mu " << p.mu << ", r " << p.r << ", x " << p.x;
    }
}

// ---- Generator behaviour -----------------------------------------------------------------------

TEST(LutGenerator, DeterministicAndIndependentOfThreadCount)
{
    LutGeneratorOptions options;
    options.size_2d = 5;
    options.size_3d = 4;
    options.size_3d_eta = 6;
    options.size_4d = 3;
    options.size_4d_anisotropy = 4;
    options.samples = 256;
    options.progress = false;
    options.threads = 1;
    const std::vector<float> one_thread = generate_lut(options);
    options.threads = 0;
    const std::vector<float> all_threads = generate_lut(options);
    ASSERT_EQ(one_thread.size(), std::size_t(5 * 5 + 3 * 4 * 4 * 6 + 3 * 3 * 4 * 4));
    EXPECT_EQ(std::memcmp(one_thread.data(), all_threads.data(), one_thread.size() * sizeof(float)), 0);
    // Each entry is the estimate at its node's parameters with its cell seed: eta node 2 of 6
    // (below 1), r node 1 of 4, view node 3 of 4 (mu = 1).
    const LutLayout small = options.layout();
    const double eta = lut_eta_from_node(2, 6);
    EXPECT_EQ(one_thread[small.offset(lut_table_dielectric_transmission) + (2 * 4 + 1) * 4 + 3],
              float(estimate_dielectric_entry(lut_table_dielectric_transmission,
                                              lut_mu_from_view_coordinate(1.0, eta, lut_alpha_from_coordinate(1.0 / 3.0)),
                                              lut_alpha_from_coordinate(1.0 / 3.0), eta, 256,
                                              lut_cell_seed(lut_table_dielectric_transmission, (2 * 4 + 1) * 4 + 3))));
    // Table 4: mu node 1 of 3, r node 2 of 3, a node 3 of 4, phi node 1 of 4.
    const std::size_t cell = ((1 * 4 + 3) * 3 + 2) * 3 + 1;
    EXPECT_EQ(one_thread[small.offset(lut_table_ggx_anisotropy_ratio) + cell],
              float(estimate_lut_entry(lut_table_ggx_anisotropy_ratio, 0.5, 1.0, 1.0, 1.0 / 3.0, 256,
                                       lut_cell_seed(lut_table_ggx_anisotropy_ratio, cell))));
}

TEST(LutGenerator, OtherSizesKeepTheNodeValues)
{
    // A 17 x 17 x 6 grid: eta node 3 is the limit eta -> 1 from above (1 + 2^-20), where E_R = 0
    // and E_T0 = E_RT away from grazing views (mu >= 0.1; closer to grazing the Fresnel factor
    // of the limit is a function of mu / 0.0014).
    LutGeneratorOptions options;
    options.size_2d = 2;
    options.size_3d = 17;
    options.size_3d_eta = 6;
    options.size_4d = 2;
    options.size_4d_anisotropy = 2;
    options.samples = 4096;
    options.progress = false;
    const std::vector<float> data = generate_lut(options);
    const LutLayout other = options.layout();
    ASSERT_EQ(data.size(), other.total_count());
    EXPECT_EQ(max_abs_difference(data, data, lut_table_dielectric_interface, other), 0.0);
    for (int r = 0; r < 17; ++r)
    {
        for (int mu = 1; mu < 17; ++mu)
        {
            const double mu_value =
                lut_mu_from_view_coordinate(node(mu, 17), lut_eta_from_node(3, 6), lut_alpha_from_coordinate(node(r, 17)));
            if (mu_value < 0.1)
            {
                continue;
            }
            const std::size_t cell = (std::size_t(3) * 17 + r) * 17 + mu;
            EXPECT_NEAR(data[other.offset(lut_table_dielectric_reflection) + cell], 0.0f, 1e-7f);
            // E_RT = E_T0 there. Table 3 holds E_RT / E_ggx of its own samples, so E_ggx comes
            // from an independent 2^16-sample estimate; measured |difference| up to 5.8e-4 with
            // 4096 samples per cell (8.3e-3 with 256).
            const double e_ggx =
                estimate_lut_entry(lut_table_ggx_albedo, std::sqrt(mu_value), node(r, 17), 0.0, 1u << 16, 5);
            const double difference = std::fabs(data[other.offset(lut_table_dielectric_interface) + cell] * e_ggx -
                                                data[other.offset(lut_table_dielectric_transmission) + cell]);
            EXPECT_LE(difference, 2e-3);
        }
    }
    // 2D corners: mu = 1 and r = 0 -> 1.
    EXPECT_NEAR(data[1], 1.0f, 1e-6f);
}

TEST(LutGenerator, HalfPrecisionRounding)
{
    EXPECT_EQ(round_to_half(1.0f), 1.0f);
    EXPECT_EQ(round_to_half(0.0f), 0.0f);
    EXPECT_EQ(round_to_half(1.0f + std::ldexp(1.0f, -11)), 1.0f);                                // tie -> even
    EXPECT_EQ(round_to_half(1.0f + 3.0f * std::ldexp(1.0f, -11)), 1.0f + std::ldexp(1.0f, -9));  // tie -> even
    EXPECT_EQ(round_to_half(1.0f + std::ldexp(1.0f, -11) + std::ldexp(1.0f, -20)), 1.0f + std::ldexp(1.0f, -10));
    EXPECT_EQ(round_to_half(2.0f - std::ldexp(1.0f, -12)), 2.0f);  // carry into the exponent
    EXPECT_EQ(round_to_half(0.1f), 0.0999755859375f);
    EXPECT_EQ(round_to_half(65504.0f), 65504.0f);
    EXPECT_TRUE(std::isinf(round_to_half(65520.0f)));
    EXPECT_EQ(round_to_half(std::ldexp(1.0f, -24)), std::ldexp(1.0f, -24));  // smallest subnormal
    EXPECT_EQ(round_to_half(std::ldexp(1.0f, -26)), 0.0f);

    LutGeneratorOptions options;
    options.size_2d = 4;
    options.size_3d = 3;
    options.size_4d = 3;
    options.size_4d_anisotropy = 2;
    options.samples = 64;
    options.progress = false;
    const std::vector<float> full = generate_lut(options);
    options.bits = 16;
    const std::vector<float> half = generate_lut(options);
    ASSERT_EQ(full.size(), half.size());
    for (std::size_t i = 0; i < full.size(); ++i)
    {
        EXPECT_EQ(half[i], round_to_half(full[i]));
        // Half a unit in the last place: 2^-11 relative, or 2^-25 among the half subnormals.
        EXPECT_LE(std::fabs(half[i] - full[i]), std::max(std::ldexp(std::fabs(full[i]), -11), std::ldexp(1.0f, -25)));
    }
}

TEST(LutGenerator, RejectsInvalidOptions)
{
    LutGeneratorOptions options;
    options.progress = false;
    options.samples = 0;
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.samples = 16;
    options.bits = 8;
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.bits = 32;
    options.size_3d = 1;
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.size_3d = 16;
    options.size_4d_anisotropy = 1;
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.size_4d_anisotropy = 2;
    options.size_4d = 65;
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.size_4d = 16;
    options.size_3d_eta = 7;  // odd: no two halves
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.size_3d_eta = 4;  // halves of 2 nodes: no quadratic stencil
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    options.size_3d_eta = 48;
    options.threads = -1;
    EXPECT_THROW(generate_lut(options), std::invalid_argument);
    EXPECT_THROW(lut_table_name(5), std::invalid_argument);
    EXPECT_THROW(layout.axis_size(lut_table_ggx_albedo, 2), std::invalid_argument);
    EXPECT_EQ(layout.axis_size(lut_table_ggx_anisotropy_ratio, 1), n4);
    EXPECT_EQ(layout.axis_size(lut_table_ggx_anisotropy_ratio, 3), m4);
    EXPECT_THROW(max_abs_difference(std::vector<float>(3), std::vector<float>(3), 0), std::invalid_argument);
}

// ---- Files -----------------------------------------------------------------------------------

class LutFiles : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        const ::testing::UnitTest& unit_test = *::testing::UnitTest::GetInstance();
        directory_ = std::filesystem::temp_directory_path() /
                     ("openpbr_lut_generator_test_" + std::to_string(unit_test.random_seed()) + "_" +
                      unit_test.current_test_info()->name());
        std::filesystem::create_directories(directory_);
    }
    void TearDown() override { std::filesystem::remove_all(directory_); }
    std::filesystem::path directory_;
};

TEST_F(LutFiles, RoundTripIsExact)
{
    const std::vector<float> values = {0.0f, 1.0f, 0.1f, 1.0f / 3.0f, 0.99999994f, 1e-7f, 5.9604645e-08f, 0.5f};
    const auto inc = directory_ / "values.inc";
    const auto bin = directory_ / "values.bin";
    write_lut_values_inc(inc, values, "first line\nsecond line");
    write_lut_binary(bin, values);
    const std::vector<float> from_inc = read_lut_values_inc(inc);
    const std::vector<float> from_bin = read_lut_binary(bin, values.size());
    ASSERT_EQ(from_inc.size(), values.size());
    ASSERT_EQ(from_bin.size(), values.size());
    EXPECT_EQ(std::memcmp(from_inc.data(), values.data(), values.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(from_bin.data(), values.data(), values.size() * sizeof(float)), 0);
    EXPECT_EQ(std::filesystem::file_size(bin), values.size() * sizeof(float));
    EXPECT_EQ(read_lut_binary(bin, 0).size(), values.size());

    std::ifstream file(inc);
    std::string line;
    std::getline(file, line);
    EXPECT_EQ(line, "// first line");
    std::getline(file, line);
    std::getline(file, line);
    EXPECT_EQ(line, "0.00000000e+00f,");
    std::getline(file, line);
    EXPECT_EQ(line, "1.00000000e+00f,");
    EXPECT_FALSE(std::filesystem::exists(directory_ / "values.inc.tmp"));
}

TEST_F(LutFiles, ErrorsNameThePath)
{
    const auto missing = directory_ / "missing.bin";
    try
    {
        read_lut_binary(missing);
        FAIL() << "no exception";
    }
    catch (const std::runtime_error& error)
    {
        EXPECT_NE(std::string(error.what()).find(missing.string()), std::string::npos) << error.what();
    }

    const auto short_file = directory_ / "short.bin";
    write_lut_binary(short_file, std::vector<float>(10, 0.5f));
    try
    {
        read_lut_binary(short_file, 11);
        FAIL() << "no exception";
    }
    catch (const std::runtime_error& error)
    {
        EXPECT_NE(std::string(error.what()).find(short_file.string()), std::string::npos) << error.what();
    }
    {
        std::ofstream odd(directory_ / "odd.bin", std::ios::binary);
        odd << "12345";
    }
    EXPECT_THROW(read_lut_binary(directory_ / "odd.bin", 0), std::runtime_error);

    const auto bad_inc = directory_ / "bad.inc";
    {
        std::ofstream bad(bad_inc);
        bad << "1.0f,\n2.0x,\n";
    }
    EXPECT_THROW(read_lut_values_inc(bad_inc), std::runtime_error);
    {
        std::ofstream bad(bad_inc);
        bad << "1.0f\n2.0f\n";  // missing comma
    }
    EXPECT_THROW(read_lut_values_inc(bad_inc), std::runtime_error);
    EXPECT_THROW(write_lut_binary(directory_ / "no" / "such" / "dir.bin", {1.0f}), std::runtime_error);
    EXPECT_THROW(write_lut_binary(directory_ / "nan.bin", {std::nanf("")}), std::runtime_error);
}

}  // namespace
