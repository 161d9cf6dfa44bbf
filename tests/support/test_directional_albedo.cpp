// The host's one directional-albedo estimator (host/support/directional_albedo.h) on weights
// whose statistics are known in closed form: a constant weight (mean exact, no error), two
// alternating values (mean, biased variance and standard error by hand), per-channel maxima,
// the luminance variance, partial sums merged, and replicas (the spread of their means).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "host/support/directional_albedo.h"

namespace {

using namespace openpbr::host;
using Weight = std::array<double, 3>;

TEST(DirectionalAlbedo, ConstantWeightIsExact)
{
    const DirectionalAlbedo albedo = estimate_directional_albedo(1000, [](std::uint64_t) { return Weight{0.5, 1.0, 0.25}; });
    EXPECT_EQ(albedo.samples, 1000u);
    EXPECT_EQ(albedo.mean[0], 0.5);
    EXPECT_EQ(albedo.mean[1], 1.0);
    EXPECT_EQ(albedo.mean[2], 0.25);
    for (int channel = 0; channel < 3; ++channel)
    {
        EXPECT_EQ(albedo.standard_error[channel], 0.0);
    }
    EXPECT_EQ(albedo.max_weight_any_channel(), 1.0);
    EXPECT_EQ(albedo.luminance_variance, 0.0);
}

TEST(DirectionalAlbedo, AlternatingWeightsGiveTheTextbookStatistics)
{
    // Weights 0 (a sample with no direction) and 2, alternating: mean 1, biased variance 1,
    // standard error sqrt(1 / (n - 1)); luminance 0 or 2 (the BT.709 weights sum to 1).
    const std::uint64_t n = 1024;
    const DirectionalAlbedo albedo = estimate_directional_albedo(n, [](std::uint64_t i) {
        const double w = (i % 2 == 0) ? 0.0 : 2.0;
        return Weight{w, w, w};
    });
    for (int channel = 0; channel < 3; ++channel)
    {
        EXPECT_EQ(albedo.mean[channel], 1.0);
        EXPECT_DOUBLE_EQ(albedo.standard_error[channel], std::sqrt(1.0 / double(n - 1)));
        EXPECT_EQ(albedo.max_weight[channel], 2.0);
    }
    EXPECT_NEAR(albedo.luminance_variance, 1.0, 1e-12);  // 1e-12: rounding of 0.2126 + 0.7152 + 0.0722
}

TEST(DirectionalAlbedo, MergedPartialSumsEqualOneRun)
{
    const auto draw = [](std::uint64_t i) { return Weight{double(i % 7), double(i % 3) * 0.5, double(i % 5 == 0)}; };
    SampleWeightSums first;
    SampleWeightSums second;
    accumulate_sample_weights(first, 0, 300, draw);
    accumulate_sample_weights(second, 300, 1000, draw);
    first.merge(second);
    const DirectionalAlbedo merged = directional_albedo_from_sums(first);
    const DirectionalAlbedo whole = estimate_directional_albedo(1000, draw);
    EXPECT_EQ(merged.samples, whole.samples);
    for (int channel = 0; channel < 3; ++channel)
    {
        // Integer-valued weights: every partial sum is exact, so the two orders agree exactly.
        EXPECT_EQ(merged.mean[channel], whole.mean[channel]);
        EXPECT_EQ(merged.standard_error[channel], whole.standard_error[channel]);
        EXPECT_EQ(merged.max_weight[channel], whole.max_weight[channel]);
    }
    EXPECT_EQ(merged.max_weight[0], 6.0);
}

TEST(DirectionalAlbedo, NoSamplesGiveZeroNotNaN)
{
    const DirectionalAlbedo albedo = estimate_directional_albedo(0, [](std::uint64_t) { return Weight{1.0, 1.0, 1.0}; });
    EXPECT_EQ(albedo.samples, 0u);
    EXPECT_EQ(albedo.mean[0], 0.0);
    EXPECT_EQ(albedo.standard_error[0], 0.0);
}

TEST(DirectionalAlbedo, ReplicasTakeTheErrorFromTheSpreadOfTheirMeans)
{
    // Four replicas with means 0.9, 1.0, 1.0, 1.1 (each a constant weight): mean 1, unbiased
    // variance of the means (0.01 + 0 + 0 + 0.01) / 3, standard error sqrt(that / 4).
    const double replica_means[4] = {0.9, 1.0, 1.0, 1.1};
    std::vector<SampleWeightSums> replicas(4);
    for (int r = 0; r < 4; ++r)
    {
        accumulate_sample_weights(replicas[std::size_t(r)], 0, 64, [&](std::uint64_t) {
            return Weight{replica_means[r], replica_means[r], replica_means[r]};
        });
    }
    const DirectionalAlbedo albedo = directional_albedo_from_replicas(replicas);
    EXPECT_EQ(albedo.samples, 256u);
    EXPECT_NEAR(albedo.mean[0], 1.0, 1e-15);  // 1e-15: four double additions
    EXPECT_NEAR(albedo.standard_error[0], std::sqrt(0.02 / 3.0 / 4.0), 1e-12);
    EXPECT_EQ(albedo.max_weight[0], 1.1);
}

}  // namespace
