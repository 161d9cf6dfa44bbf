// Table 5 of slang/openpbr_lut.h, the microfacet cosines of a GGX lobe's reflected light
// (host/tables/film_table_generator.h), and its look-up (openpbr_film_lobe_cumulative):
//  * the shipped table is what the generator writes (cells regenerated bit for bit);
//  * the generator against an independent reference: the lobe's reflected light integrated
//    over light directions on a fine grid (the BRDF D G2 / (4 mu_o mu_i) times mu_i, no
//    visible-normal sampler), its mean cosine and its share below the tabulated quantiles;
//  * the table's invariants (quantiles and the partial first moment grow with p, cosines in
//    [0, 1]);
//  * the look-up at the nodes returns the nodes, and grows with the threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "host/tables/film_table_generator.h"
#include "host/tables/lut_generator.h"
#include "slang/openpbr.h"

namespace {

using namespace openpbr;
using namespace openpbr::host;

constexpr int quantile_size = OPENPBR_LUT_FILM_QUANTILE_SIZE;
constexpr int size = OPENPBR_LUT_FILM_SIZE;

float shipped_node(int p, int mu_index, int r_index, int channel)
{
    return openpbr_film_table_node(p, mu_index, r_index, channel);
}

double mu_of(int index)
{
    const double c = double(index) / double(size - 1);
    return std::max(c * c, 1e-4);
}

double alpha_of(int index)
{
    const double c = double(index) / double(size - 1);
    return std::max(c * c, 1e-4);
}

// Cells across the view and roughness axes, their ends included.
std::vector<std::pair<int, int>> sample_cells()
{
    return {{0, 0}, {size - 1, 0}, {0, size - 1}, {size - 1, size - 1}, {5, 3}, {16, 9}, {24, 20}, {9, 28}, {31, 14}};
}

TEST(FilmTable, ShippedCellsAreTheGeneratorsOutput)
{
    const FilmTableOptions options;
    for (const auto& [mu_index, r_index] : sample_cells())
    {
        const std::vector<double> generated = film_lobe_quantiles(
            film_lobe_points(mu_of(mu_index), alpha_of(r_index), options.lattice_size), film_lobe_probabilities());
        for (int channel = 0; channel < OPENPBR_LUT_FILM_CHANNEL_COUNT; ++channel)
        {
            for (int p = 0; p < quantile_size; ++p)
            {
                ASSERT_EQ(float(generated[std::size_t(channel * quantile_size + p)]),
                          shipped_node(p, mu_index, r_index, channel))
                    << "mu node " << mu_index << " r node " << r_index << " channel " << channel << " p node " << p;
            }
        }
    }
}

TEST(FilmTable, QuantilesAndPartialMomentsGrowWithTheProbability)
{
    for (int r_index = 0; r_index < size; ++r_index)
    {
        for (int mu_index = 0; mu_index < size; ++mu_index)
        {
            for (int p = 0; p < quantile_size; ++p)
            {
                const float q = shipped_node(p, mu_index, r_index, 0);
                const float m1 = shipped_node(p, mu_index, r_index, 1);
                ASSERT_GE(q, 0.0f);
                ASSERT_LE(q, 1.0f);
                // E[c; c <= Q(p)] <= p Q(p) for cosines in [0, 1]; 1e-6 for float rounding of
                // values of order 1.
                const float share = openpbr_film_lobe_probability(p);
                ASSERT_LE(m1, share * q + 1e-6f);
                if (p > 0)
                {
                    ASSERT_GE(q, shipped_node(p - 1, mu_index, r_index, 0));
                    ASSERT_GE(m1, shipped_node(p - 1, mu_index, r_index, 1));
                }
            }
        }
    }
}

// The reflected light of the lobe integrated over light directions: a midpoint grid over
// (theta_i, phi_i), each direction weighted by D(h) G2(wo, wi) / (4 mu_o) sin(theta_i), with
// h = normalize(wo + wi) and c = wo.h.
struct DirectIntegral
{
    double total = 0.0;
    double first_moment = 0.0;
    std::vector<std::pair<double, double>> cosine_weights;
};

DirectIntegral integrate_over_lights(double mu, double alpha)
{
    const glm::vec3 view(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
    const glm::vec2 alphas = glm::vec2(float(alpha));
    const float lambda_view = openpbr_ggx_lambda(view, alphas);
    const int theta_steps = 1024;
    const int phi_steps = 1024;
    DirectIntegral integral;
    for (int i = 0; i < theta_steps; ++i)
    {
        const double theta = (i + 0.5) / theta_steps * (M_PI / 2.0);
        for (int j = 0; j < phi_steps; ++j)
        {
            const double phi = (j + 0.5) / phi_steps * (2.0 * M_PI);
            const glm::vec3 light(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                                  float(std::cos(theta)));
            const glm::vec3 h = glm::normalize(view + light);
            const double g2 = 1.0 / (1.0 + lambda_view + openpbr_ggx_lambda(light, alphas));
            const double weight = double(openpbr_ggx_d(h, alphas)) * g2 / (4.0 * mu) * std::sin(theta);
            const double cosine = double(glm::dot(view, h));
            integral.total += weight;
            integral.first_moment += weight * cosine;
            integral.cosine_weights.push_back({cosine, weight});
        }
    }
    return integral;
}

// Measured (this grid, 1024^2 directions, against the 256^2-point table, 2026-11-27): largest
// difference of the mean cosine 2.6e-5, of the share below a tabulated quantile 6.0e-3 (the
// share's step on the grid of directions near a mirror-like view). Bounds: 2e-4 and 0.01, far
// below what a wrong weight (G1 instead of G2 / G1) or a wrong quantile walk produces (shares
// off by a whole probability step, 1/32 = 0.031).
TEST(FilmTable, MatchesTheLobeIntegratedOverLightDirections)
{
    double largest_mean_difference = 0.0;
    double largest_share_difference = 0.0;
    for (const auto& [mu_index, r_index] : std::vector<std::pair<int, int>>{{31, 31}, {16, 24}, {8, 20}, {24, 12}})
    {
        const double mu = mu_of(mu_index);
        const double alpha = alpha_of(r_index);
        const DirectIntegral integral = integrate_over_lights(mu, alpha);
        const double mean = integral.first_moment / integral.total;
        largest_mean_difference =
            std::max(largest_mean_difference, std::abs(shipped_node(quantile_size - 1, mu_index, r_index, 1) - mean));
        EXPECT_NEAR(shipped_node(quantile_size - 1, mu_index, r_index, 1), mean, 2e-4) << "mu " << mu << " alpha " << alpha;
        for (int p = 4; p < quantile_size - 1; p += 4)
        {
            const double quantile = shipped_node(p, mu_index, r_index, 0);
            double below = 0.0;
            for (const auto& [cosine, weight] : integral.cosine_weights)
            {
                below += cosine <= quantile ? weight : 0.0;
            }
            const double share = double(openpbr_film_lobe_probability(p));
            largest_share_difference = std::max(largest_share_difference, std::abs(below / integral.total - share));
            EXPECT_NEAR(below / integral.total, share, 0.01) << "mu " << mu << " alpha " << alpha << " p node " << p;
        }
    }
    std::printf("  largest difference: mean cosine %.2e, share below a quantile %.2e\n", largest_mean_difference,
                largest_share_difference);
}

// At a node of the view and roughness axes, the look-up at a tabulated quantile returns that
// node's probability and partial moments (up to float rounding of the cell arithmetic).
TEST(FilmTableLookUp, ReturnsTheNodesAtTheirQuantiles)
{
    for (const auto& [mu_index, r_index] : sample_cells())
    {
        if (mu_index == size - 1 || r_index == size - 1)
        {
            continue;  // the last node is reached as the upper corner of the cell below it
        }
        // The cell's lower corner itself (weights 0): openpbr_film_lobe_table's coordinates land
        // there only up to float rounding.
        const OpenPBR_FilmLobeTable table = {mu_index, r_index, 0.0f, 0.0f};
        for (int p = 1; p < quantile_size - 1; ++p)
        {
            const float q = shipped_node(p, mu_index, r_index, 0);
            if (q <= shipped_node(p - 1, mu_index, r_index, 0) || q >= shipped_node(p + 1, mu_index, r_index, 0))
            {
                continue;  // equal neighbours (a near-mirror lobe): the bisection may pick either
            }
            const vec2 at = openpbr_film_lobe_cumulative(table, q);
            EXPECT_NEAR(at.x, openpbr_film_lobe_probability(p), 1e-5f);
            EXPECT_NEAR(at.y, shipped_node(p, mu_index, r_index, 1), 1e-5f);
        }
    }
}

// The probability axis: from 0 to 1, increasing, the even nodes at j / 32 (the estimate's equal
// shares and quartiles), the tail nodes halving towards each end, symmetric.
TEST(FilmTable, ProbabilityNodesAreTheEvenNodesAndTheTails)
{
    const int last = quantile_size - 1;
    EXPECT_EQ(openpbr_film_lobe_probability(0), 0.0f);
    EXPECT_EQ(openpbr_film_lobe_probability(last), 1.0f);
    for (int k = 1; k <= last; ++k)
    {
        EXPECT_GT(openpbr_film_lobe_probability(k), openpbr_film_lobe_probability(k - 1)) << "node " << k;
        EXPECT_EQ(openpbr_film_lobe_probability(last - k), 1.0f - openpbr_film_lobe_probability(k)) << "node " << k;
    }
    for (int j = 1; j < OPENPBR_LUT_FILM_CORE_SIZE - 1; ++j)
    {
        EXPECT_EQ(openpbr_film_lobe_probability(openpbr_film_lobe_even_node(j)),
                  float(j) / float(OPENPBR_LUT_FILM_CORE_SIZE - 1))
            << "even node " << j;
    }
    for (int k = 1; k <= OPENPBR_LUT_FILM_TAIL_NODES; ++k)
    {
        EXPECT_EQ(openpbr_film_lobe_probability(k), 0.5f * openpbr_film_lobe_probability(k + 1)) << "tail node " << k;
    }
}

// The quantile look-up returns the tabulated quantile at every node's probability (up to float
// rounding of the cell arithmetic), the tail nodes included, and never decreases between them.
TEST(FilmTableLookUp, QuantileReturnsTheNodesAndGrows)
{
    for (const auto& [mu_index, r_index] : sample_cells())
    {
        if (mu_index == size - 1 || r_index == size - 1)
        {
            continue;  // the last node is reached as the upper corner of the cell below it
        }
        const OpenPBR_FilmLobeTable table = {mu_index, r_index, 0.0f, 0.0f};
        float previous = 0.0f;
        for (int k = 0; k < quantile_size; ++k)
        {
            const float p = openpbr_film_lobe_probability(k);
            EXPECT_NEAR(openpbr_film_lobe_quantile(table, p), shipped_node(k, mu_index, r_index, 0), 1e-5f)
                << "mu node " << mu_index << " r node " << r_index << " p node " << k;
            for (int step = 0; step < 8 && k + 1 < quantile_size; ++step)
            {
                const float between =
                    openpbr_film_lobe_quantile(table, p + (openpbr_film_lobe_probability(k + 1) - p) * float(step) / 8.0f);
                EXPECT_GE(between, previous - 1e-6f) << "mu node " << mu_index << " r node " << r_index << " p node " << k;
                previous = between;
            }
        }
    }
}

TEST(FilmTableLookUp, GrowsWithTheThresholdFromNothingToTheWholeLobe)
{
    for (const float mu : {1e-4f, 0.05f, 0.3f, 0.77f, 1.0f})
    {
        for (const float alpha : {1e-4f, 0.01f, 0.2f, 0.55f, 1.0f})
        {
            const OpenPBR_FilmLobeTable table = openpbr_film_lobe_table(mu, alpha);
            vec2 previous = openpbr_film_lobe_cumulative(table, 0.0f);
            EXPECT_EQ(previous.x, 0.0f);
            for (int step = 1; step <= 400; ++step)
            {
                const vec2 at = openpbr_film_lobe_cumulative(table, float(step) / 400.0f * 1.001f);
                EXPECT_GE(at.x, previous.x - 1e-6f) << "mu " << mu << " alpha " << alpha;
                EXPECT_GE(at.y, previous.y - 1e-6f) << "mu " << mu << " alpha " << alpha;
                EXPECT_LE(at.x, 1.0f);
                previous = at;
            }
            const vec2 whole = openpbr_film_lobe_even_moment(table, OPENPBR_LUT_FILM_CORE_SIZE - 1);
            EXPECT_EQ(previous.x, whole.x);
            EXPECT_EQ(previous.y, whole.y);
            EXPECT_GT(whole.y, 0.0f);
            EXPECT_LE(whole.y, 1.0f);
        }
    }
}

}  // namespace
