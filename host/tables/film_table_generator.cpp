// Table 5 of slang/openpbr_lut.h (film_table_generator.h). Compiled in table buffer mode like
// lut_generator.cpp: it reads only the layout macros and the GGX and visible-normal functions,
// never the tables, so it does not depend on its own output.
#define OPENPBR_LUT_MODE_BUFFER 1

#include "host/tables/film_table_generator.h"

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_ggx.h"
#include "slang/math/openpbr_vndf.h"
#include "slang/openpbr_lut.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace openpbr::host {

static_assert(OPENPBR_LUT_FILM_OFFSET == OPENPBR_LUT_COMPENSATION_COUNT, "table 5 follows the compensation tables");

std::vector<double> film_lobe_probabilities()
{
    std::vector<double> probabilities(OPENPBR_LUT_FILM_QUANTILE_SIZE);
    for (int k = 0; k < OPENPBR_LUT_FILM_QUANTILE_SIZE; ++k)
    {
        probabilities[std::size_t(k)] = double(openpbr_film_lobe_probability(k));
    }
    return probabilities;
}

std::vector<FilmLobePoint> film_lobe_points(const double mu, const double alpha, const int lattice_size)
{
    const glm::vec3 view(float(std::sqrt(std::max(1.0 - mu * mu, 0.0))), 0.0f, float(mu));
    const glm::vec2 alphas = glm::vec2(float(alpha));
    const float lambda_view = openpbr_ggx_lambda(view, alphas);
    std::vector<FilmLobePoint> points;
    points.reserve(std::size_t(lattice_size) * std::size_t(lattice_size));
    for (int i = 0; i < lattice_size; ++i)
    {
        for (int j = 0; j < lattice_size; ++j)
        {
            const glm::vec2 u((float(i) + 0.5f) / float(lattice_size), (float(j) + 0.5f) / float(lattice_size));
            const glm::vec3 microfacet = openpbr_sample_vndf_spherical_cap(view, alphas, u);
            const float cosine = glm::dot(view, microfacet);
            const glm::vec3 light = 2.0f * cosine * microfacet - view;
            const double weight =
                light.z > 0.0f ? double((1.0f + lambda_view) / (1.0f + lambda_view + openpbr_ggx_lambda(light, alphas)))
                               : 0.0;
            points.push_back({std::clamp(double(cosine), 0.0, 1.0), weight});
        }
    }
    return points;
}

std::vector<double> film_lobe_quantiles(std::vector<FilmLobePoint> points, const std::vector<double>& probabilities)
{
    const int quantile_size = int(probabilities.size());
    std::vector<double> result(std::size_t(OPENPBR_LUT_FILM_CHANNEL_COUNT * quantile_size), 0.0);
    double total = 0.0;
    for (const FilmLobePoint& point : points)
    {
        total += point.weight;
    }
    std::sort(points.begin(), points.end(),
              [](const FilmLobePoint& a, const FilmLobePoint& b) { return a.cosine < b.cosine; });
    if (points.empty() || total <= 0.0)
    {
        // No light reflects (a view on the horizon): every cosine at the mean of the points, so
        // the look-up returns one segment there.
        double mean = 0.0;
        for (const FilmLobePoint& point : points)
        {
            mean += point.cosine / double(points.size());
        }
        for (int k = 0; k < quantile_size; ++k)
        {
            const double p = probabilities[std::size_t(k)];
            result[std::size_t(k)] = mean;
            result[std::size_t(quantile_size + k)] = p * mean;
        }
        return result;
    }
    // Walk the sorted points: point i carries probability weight_i / total; the quantile at p_k
    // is the cosine of the point in which the cumulative probability reaches p_k, and that point
    // contributes only its part below p_k to the moments.
    std::size_t next = 0;
    double accumulated = 0.0;
    double first_moment = 0.0;
    auto first_weighted = [&]() {
        for (const FilmLobePoint& point : points)
        {
            if (point.weight > 0.0)
            {
                return point.cosine;
            }
        }
        return points.front().cosine;
    };
    result[0] = first_weighted();
    for (int k = 1; k < quantile_size; ++k)
    {
        const double target = probabilities[std::size_t(k)];
        while (next < points.size() && accumulated + points[next].weight / total <= target)
        {
            const double probability = points[next].weight / total;
            accumulated += probability;
            first_moment += probability * points[next].cosine;
            ++next;
        }
        // The point that crosses p_k, or the last weighted point at p = 1.
        std::size_t crossing = next;
        while (crossing < points.size() && points[crossing].weight <= 0.0)
        {
            ++crossing;
        }
        double cosine = 0.0;
        double part = 0.0;
        if (crossing < points.size())
        {
            cosine = points[crossing].cosine;
            part = std::max(target - accumulated, 0.0);
        }
        else
        {
            for (std::size_t i = points.size(); i-- > 0;)
            {
                if (points[i].weight > 0.0)
                {
                    cosine = points[i].cosine;
                    break;
                }
            }
        }
        result[std::size_t(k)] = cosine;
        result[std::size_t(quantile_size + k)] = first_moment + part * cosine;
    }
    // p = 1 holds the whole distribution: its moments are the full sums.
    return result;
}

std::vector<float> generate_film_table(const FilmTableOptions& options)
{
    const std::vector<double> probabilities = film_lobe_probabilities();
    const int quantile_size = int(probabilities.size());
    const int size = options.size > 0 ? options.size : OPENPBR_LUT_FILM_SIZE;
    if (size < 2 || options.lattice_size < 2 || options.threads < 0)
    {
        throw std::invalid_argument("film table: sizes must be at least 2 and threads at least 0");
    }
    const int channels = OPENPBR_LUT_FILM_CHANNEL_COUNT;
    std::vector<float> table(std::size_t(channels) * std::size_t(size) * std::size_t(size) * std::size_t(quantile_size));
    auto fill = [&]() {
        tbb::parallel_for(tbb::blocked_range<int>(0, size * size), [&](const tbb::blocked_range<int>& range) {
            for (int cell = range.begin(); cell != range.end(); ++cell)
            {
                const int mu_index = cell % size;
                const int r_index = cell / size;
                const double c_mu = double(mu_index) / double(size - 1);
                const double c_r = double(r_index) / double(size - 1);
                const double mu = std::max(c_mu * c_mu, 1e-4);
                const double alpha = std::max(c_r * c_r, 1e-4);
                const std::vector<double> quantiles =
                    film_lobe_quantiles(film_lobe_points(mu, alpha, options.lattice_size), probabilities);
                for (int channel = 0; channel < channels; ++channel)
                {
                    for (int k = 0; k < quantile_size; ++k)
                    {
                        const std::size_t index =
                            ((std::size_t(channel) * size + std::size_t(r_index)) * size + std::size_t(mu_index)) *
                                std::size_t(quantile_size) +
                            std::size_t(k);
                        table[index] = float(quantiles[std::size_t(channel * quantile_size + k)]);
                    }
                }
            }
        });
    };
    if (options.threads > 0)
    {
        tbb::task_arena arena(options.threads);
        arena.execute(fill);
    }
    else
    {
        fill();
    }
    return table;
}

std::string describe(const FilmTableOptions& options)
{
    std::ostringstream text;
    text << "openpbr lutgen --only film: film lobe cosines " << OPENPBR_LUT_FILM_QUANTILE_SIZE << " x "
         << (options.size > 0 ? options.size : OPENPBR_LUT_FILM_SIZE) << " x "
         << (options.size > 0 ? options.size : OPENPBR_LUT_FILM_SIZE) << " x " << OPENPBR_LUT_FILM_CHANNEL_COUNT
         << " (Q, M1), lattice " << options.lattice_size << "^2 per cell";
    return text.str();
}

}  // namespace openpbr::host
