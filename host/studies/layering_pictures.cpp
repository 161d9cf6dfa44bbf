// layering_pictures.cpp - the layering picture strip of layering_accuracy.h: a sphere per material
// under a smooth environment, rendered from the layered reference's paths and from the shipped
// BSDF's samples, the same number per pixel, with the scaled difference beside them.
//
// Each pixel is the radiance towards an orthographic camera looking down -z, L = integral of
// f |cos| L_env: the reference traces paths of the mixture (layered_trace_material) from the
// pixel's view and weighs each exit direction by the environment; the model draws
// openpbr_sample from the same view. No next-event estimation, no bounce off the sphere: one
// scattering of the environment, so both sides are unbiased estimates of the same integral and
// the difference image shows the model's error plus noise, whose RMS is reported beside it.
// The environment: a sky brightening upwards, a darker ground and a soft sun (a lobe of about 15
// degrees towards the upper right, in front), smooth enough for low noise at a few hundred
// samples while it still shows highlights and the coat's reflection of the sun.
#include "host/studies/layering_accuracy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "host/preview/render.h"
#include "host/support/random.h"
#include "host/support/stopwatch.h"
#include "slang/openpbr.h"

namespace openpbr::host {
namespace {

// Environment radiance towards world direction d (render units).
LayeredColor environment(const glm::dvec3& d)
{
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.55, 0.65, 0.5));
    const double sun_lobe = 8.0 * std::exp((glm::dot(d, sun) - 1.0) / 0.035);
    const double up = std::clamp(d.y, -1.0, 1.0);
    const LayeredColor sky =
        up >= 0.0 ? LayeredColor{0.25 + 0.3 * up, 0.3 + 0.35 * up, 0.4 + 0.45 * up} : LayeredColor{0.12, 0.1, 0.08};
    return {sky[0] + sun_lobe, sky[1] + sun_lobe * 0.95, sky[2] + sun_lobe * 0.85};
}

// The shading frame of the sphere at normal n (world), tangent along the world x axis projected.
struct Frame
{
    glm::dvec3 tangent, bitangent, normal;
    glm::dvec3 to_local(const glm::dvec3& v) const
    {
        return {glm::dot(v, tangent), glm::dot(v, bitangent), glm::dot(v, normal)};
    }
    glm::dvec3 to_world(const glm::dvec3& v) const { return tangent * v.x + bitangent * v.y + normal * v.z; }
};

Frame frame_at(const glm::dvec3& normal)
{
    const glm::dvec3 axis = std::abs(normal.y) < 0.999 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 tangent = glm::normalize(glm::cross(axis, normal));
    return {tangent, glm::cross(normal, tangent), normal};
}

struct PixelEstimate
{
    LayeredColor mean{};
    LayeredColor variance_of_mean{};
};

template <class Draw> PixelEstimate estimate_pixel(std::uint64_t samples, Draw&& draw)
{
    LayeredColor sum{}, squares{};
    for (std::uint64_t s = 0; s < samples; ++s)
    {
        const LayeredColor value = draw();
        for (std::size_t c = 0; c < 3; ++c)
        {
            sum[c] += value[c];
            squares[c] += value[c] * value[c];
        }
    }
    PixelEstimate estimate;
    const double n = double(samples);
    for (std::size_t c = 0; c < 3; ++c)
    {
        estimate.mean[c] = sum[c] / n;
        estimate.variance_of_mean[c] =
            std::max(squares[c] / n - estimate.mean[c] * estimate.mean[c], 0.0) / std::max(n - 1.0, 1.0);
    }
    return estimate;
}

}  // namespace

std::vector<LayeringPictureStats> write_layering_pictures(const std::string& path,
                                                          const std::vector<LayeringMaterial>& materials,
                                                          const LayeringPictureOptions& options)
{
    if (materials.empty() || options.size < 8 || options.samples == 0)
    {
        throw std::invalid_argument("layering pictures: need materials, a size of at least 8 and samples > 0");
    }
    std::unique_ptr<tbb::global_control> limit;
    if (options.threads > 0)
    {
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      std::size_t(options.threads));
    }
    const int size = options.size;
    RenderImage image;
    image.cell_size = size;
    image.columns = 3;
    image.rows = int(materials.size());
    image.width = 3 * size;
    image.height = image.rows * size;
    image.mean.assign(std::size_t(image.width) * std::size_t(image.height) * 3, 0.0f);
    std::vector<LayeringPictureStats> stats;
    char label[96];
    for (std::size_t m = 0; m < materials.size(); ++m)
    {
        const Stopwatch watch;
        const LayeredMaterial layered = layered_material_from_inputs(materials[m].inputs);
        OpenPBR_ResolvedInputs model_inputs = materials[m].inputs;
        model_inputs.coat_darkening = 1.0f;  // the physical setting, as in the study
        std::vector<double> squared_difference(std::size_t(size) * std::size_t(size), -1.0);
        std::vector<double> noise_variance(squared_difference.size(), 0.0);
        tbb::parallel_for(0, size * size, [&](int pixel) {
            const int px = pixel % size;
            const int py = pixel / size;
            const double x = (px + 0.5) / size * 2.0 - 1.0;
            const double y = 1.0 - (py + 0.5) / size * 2.0;
            const double r2 = x * x + y * y;
            if (r2 >= 0.97)
            {
                return;  // background and the very rim (views beyond 80 degrees)
            }
            const glm::dvec3 normal(x, y, std::sqrt(1.0 - r2));
            const Frame frame = frame_at(normal);
            const glm::dvec3 view = frame.to_local(glm::dvec3(0.0, 0.0, 1.0));
            SplitMix64 random{splitmix64(options.seed ^ (std::uint64_t(m) << 40) ^ std::uint64_t(pixel))};
            const PixelEstimate reference = estimate_pixel(options.samples, [&]() -> LayeredColor {
                const LayeredExit exit = layered_trace_material(layered, view, random);
                if (!exit.left)
                {
                    return {0.0, 0.0, 0.0};
                }
                const LayeredColor light = environment(frame.to_world(exit.direction));
                return {exit.weight[0] * light[0], exit.weight[1] * light[1], exit.weight[2] * light[2]};
            });
            const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(model_inputs, glm::vec3(view));
            const PixelEstimate model = estimate_pixel(options.samples, [&]() -> LayeredColor {
                const glm::vec3 u(unit_float_from_bits(random.next_bits()), unit_float_from_bits(random.next_bits()),
                                  unit_float_from_bits(random.next_bits()));
                const OpenPBR_BsdfSample drawn = openpbr_sample(bsdf, u);
                if (!(drawn.pdf > 0.0f))
                {
                    return {0.0, 0.0, 0.0};
                }
                const glm::vec3 weight = drawn.weight.diffuse + drawn.weight.specular;
                const LayeredColor light = environment(frame.to_world(glm::dvec3(drawn.direction)));
                return {weight.x * light[0], weight.y * light[1], weight.z * light[2]};
            });
            double squared = 0.0;
            double variance = 0.0;
            for (std::size_t c = 0; c < 3; ++c)
            {
                const std::size_t row = std::size_t(m) * std::size_t(size) + std::size_t(py);
                const std::size_t base = (row * std::size_t(image.width) + std::size_t(px)) * 3 + c;
                const double difference = reference.mean[c] - model.mean[c];
                image.mean[base] = float(reference.mean[c]);
                image.mean[base + std::size_t(size) * 3] = float(model.mean[c]);
                image.mean[base + std::size_t(size) * 6] = float(std::abs(difference) * options.difference_scale);
                squared += difference * difference;
                variance += reference.variance_of_mean[c] + model.variance_of_mean[c];
            }
            squared_difference[std::size_t(pixel)] = squared / 3.0;
            noise_variance[std::size_t(pixel)] = variance / 3.0;
        });
        LayeringPictureStats entry;
        entry.material = materials[m].name;
        double squared_sum = 0.0;
        double variance_sum = 0.0;
        std::size_t pixels = 0;
        for (std::size_t p = 0; p < squared_difference.size(); ++p)
        {
            if (squared_difference[p] >= 0.0)
            {
                squared_sum += squared_difference[p];
                variance_sum += noise_variance[p];
                ++pixels;
            }
        }
        entry.rms_difference = std::sqrt(squared_sum / double(std::max<std::size_t>(pixels, 1)));
        entry.rms_noise = std::sqrt(variance_sum / double(std::max<std::size_t>(pixels, 1)));
        entry.seconds = watch.seconds();
        stats.push_back(entry);
        image.labels.push_back(materials[m].name + ": reference");
        image.labels.push_back("shipped model");
        std::snprintf(label, sizeof(label), "difference x%.3g (rms %.3f, noise %.3f)", options.difference_scale,
                      entry.rms_difference, entry.rms_noise);
        image.labels.push_back(label);
    }
    write_render_png(path, image, 1.0f, true);
    return stats;
}

}  // namespace openpbr::host
