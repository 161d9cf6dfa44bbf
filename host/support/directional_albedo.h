// directional_albedo.h - the host's one directional-albedo estimator, shared by the white furnace
// (host/checks/furnace.cpp), the accuracy study (host/studies/accuracy_variant_body.h) and the
// statistical tests (tests/bsdf/bsdf_statistics.cpp).
//
// The directional albedo of a BSDF f seen from direction o is
//     E(o) = integral over the sphere of f(o, i) |cos theta_i| di,
// and for a sampler that returns the weight w = f |cos| / pdf (0 where it draws no direction),
// E(o) = mean of w (spec "White furnace testing": a white, energy-conserving material has
// E = 1). The estimate is the mean of n weights per channel; its standard error is
// sqrt(s^2 / (n - 1)) with s^2 the (biased) sample variance, for independent samples. For
// randomized quasi-Monte Carlo (independently shifted low-discrepancy sequences, Owen 2013,
// "Monte Carlo theory, methods and examples", ch. 17) the standard error comes from the spread of
// the replicas' means instead. The Rec. 709 luminance of the weights (ITU-R BT.709:
// 0.2126 R + 0.7152 G + 0.0722 B) is tracked too, for the study's per-sample variance.
//
// Header-only and free of the BSDF: a caller supplies "draw sample i, return its weight" (any
// type indexable [0..2], e.g. glm::vec3 or glm::dvec3), so every BSDF build (the accuracy
// study's per-variant namespaces, the double-precision one) uses the same code.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace openpbr::host {

// Roberts' R3 sequence (the generalized golden ratio phi_3 = 1.2207..., steps 1 / phi_3^k;
// M. Roberts 2018, "The unreasonable effectiveness of quasirandom sequences") shifted by a random
// vector from the seed (a Cranley-Patterson rotation): the accuracy study's low-discrepancy
// point set, whose mean converges far faster than independent numbers while the sample variance
// of the weights is still the per-sample variance of the estimator.
class ShiftedR3Sequence
{
  public:
    explicit ShiftedR3Sequence(const std::uint64_t seed)
    {
        std::mt19937_64 generator(seed);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        for (double& value : shift_)
        {
            value = uniform(generator);
        }
    }

    // Point `index` in [0, 1)^3, each coordinate at most 0.99999994 (the largest float below 1:
    // the float rounding of a value just below 1 would give 1).
    std::array<float, 3> point(const std::uint64_t index) const
    {
        std::array<float, 3> u{};
        for (int k = 0; k < 3; ++k)
        {
            const double value = shift_[k] + step_[k] * double(index);
            u[k] = std::min(float(value - std::floor(value)), 0.99999994f);
        }
        return u;
    }

  private:
    double shift_[3] = {0.0, 0.0, 0.0};
    static constexpr double step_[3] = {0.8191725133961645, 0.6710436067037893, 0.5497004779019703};
};

// Running sums of sample weights: add() one weight at a time, merge() partial sums of disjoint
// sample sets (e.g. one per thread).
struct SampleWeightSums
{
    double sum[3] = {0.0, 0.0, 0.0};
    double sum_squares[3] = {0.0, 0.0, 0.0};
    double max_weight[3] = {0.0, 0.0, 0.0};  // per channel, from 0 (a sample with no direction weighs 0)
    double luminance_sum = 0.0;
    double luminance_sum_squares = 0.0;
    std::uint64_t count = 0;  // samples, those with no direction included

    void add(const double red, const double green, const double blue)
    {
        const double weight[3] = {red, green, blue};
        for (int channel = 0; channel < 3; ++channel)
        {
            sum[channel] += weight[channel];
            sum_squares[channel] += weight[channel] * weight[channel];
            max_weight[channel] = std::max(max_weight[channel], weight[channel]);
        }
        const double luminance = 0.2126 * red + 0.7152 * green + 0.0722 * blue;
        luminance_sum += luminance;
        luminance_sum_squares += luminance * luminance;
        ++count;
    }

    void merge(const SampleWeightSums& other)
    {
        for (int channel = 0; channel < 3; ++channel)
        {
            sum[channel] += other.sum[channel];
            sum_squares[channel] += other.sum_squares[channel];
            max_weight[channel] = std::max(max_weight[channel], other.max_weight[channel]);
        }
        luminance_sum += other.luminance_sum;
        luminance_sum_squares += other.luminance_sum_squares;
        count += other.count;
    }
};

struct DirectionalAlbedo
{
    double mean[3] = {0.0, 0.0, 0.0};  // the albedo per channel
    double standard_error[3] = {0.0, 0.0, 0.0};
    double max_weight[3] = {0.0, 0.0, 0.0};
    double luminance_variance = 0.0;  // per-sample variance of the weights' luminance (biased)
    std::uint64_t samples = 0;

    double max_weight_any_channel() const { return std::max(max_weight[0], std::max(max_weight[1], max_weight[2])); }
};

// Adds the weights of samples [begin, end) to `sums`, in index order (so a `draw` that keeps
// state, e.g. a generator advanced per call, sees the indices one after the other).
template <class Draw>
void accumulate_sample_weights(SampleWeightSums& sums, const std::uint64_t begin, const std::uint64_t end, Draw&& draw)
{
    for (std::uint64_t index = begin; index != end; ++index)
    {
        const auto weight = draw(index);
        sums.add(double(weight[0]), double(weight[1]), double(weight[2]));
    }
}

// The estimate from independent samples: mean, standard error, max weight, luminance variance.
inline DirectionalAlbedo directional_albedo_from_sums(const SampleWeightSums& sums)
{
    DirectionalAlbedo result;
    result.samples = sums.count;
    const double n = double(std::max<std::uint64_t>(sums.count, 1));
    for (int channel = 0; channel < 3; ++channel)
    {
        const double mean = sums.sum[channel] / n;
        const double variance = std::max(sums.sum_squares[channel] / n - mean * mean, 0.0);
        result.mean[channel] = mean;
        result.standard_error[channel] = std::sqrt(variance / std::max(n - 1.0, 1.0));
        result.max_weight[channel] = sums.max_weight[channel];
    }
    const double mean_luminance = sums.luminance_sum / n;
    result.luminance_variance = std::max(0.0, sums.luminance_sum_squares / n - mean_luminance * mean_luminance);
    return result;
}

// The estimate from `sample_count` samples drawn one after the other: draw(i) returns the weight
// of sample i.
template <class Draw> DirectionalAlbedo estimate_directional_albedo(const std::uint64_t sample_count, Draw&& draw)
{
    SampleWeightSums sums;
    accumulate_sample_weights(sums, 0, sample_count, draw);
    return directional_albedo_from_sums(sums);
}

// The estimate from randomized quasi-Monte Carlo replicas (one SampleWeightSums each, at least
// two): the mean of the replicas' means, its standard error from their spread (unbiased
// variance of the replica means over the replica count); the max weight over all samples.
inline DirectionalAlbedo directional_albedo_from_replicas(const std::vector<SampleWeightSums>& replicas)
{
    DirectionalAlbedo result;
    const double r = double(replicas.size());
    double sum_of_means[3] = {0.0, 0.0, 0.0};
    double sum_of_squared_means[3] = {0.0, 0.0, 0.0};
    for (const SampleWeightSums& replica : replicas)
    {
        for (int channel = 0; channel < 3; ++channel)
        {
            const double mean = replica.sum[channel] / double(replica.count);
            sum_of_means[channel] += mean;
            sum_of_squared_means[channel] += mean * mean;
            result.max_weight[channel] = std::max(result.max_weight[channel], replica.max_weight[channel]);
        }
        result.samples += replica.count;
    }
    for (int channel = 0; channel < 3; ++channel)
    {
        result.mean[channel] = sum_of_means[channel] / r;
        const double variance =
            std::max(sum_of_squared_means[channel] / r - result.mean[channel] * result.mean[channel], 0.0) * (r / (r - 1.0));
        result.standard_error[channel] = std::sqrt(variance / r);
    }
    return result;
}

}  // namespace openpbr::host
