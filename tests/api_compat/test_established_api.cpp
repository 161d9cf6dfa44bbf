// The established API form (slang/openpbr_established_api.h): what it adds over forwarding.
//   - path_throughput-weighted lobe selection: probabilities follow throughput x lobe albedo,
//     the estimator's mean does not move;
//   - the staged preparation equals the one-call prepare bit for bit;
//   - the interior-volume helpers are unbiased and agree with the project's sampler;
//   - the straight-through shadow shortcut against a path-traced slab, its bias measured.
#include <glm/glm.hpp>

#include "slang/openpbr.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {

using namespace openpbr;

struct Random
{
    std::uint64_t state;
    explicit Random(std::uint64_t seed) : state(seed * 0x9E3779B97F4A7C15ULL + 0x853c49e6748fea9bULL) {}
    float next()
    {
        const std::uint64_t old = state;
        state = old * 6364136223846793005ULL + 1442695040888963407ULL;
        const std::uint32_t shifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const std::uint32_t rotation = static_cast<std::uint32_t>(old >> 59u);
        const std::uint32_t value = (shifted >> rotation) | (shifted << ((32u - rotation) & 31u));
        return static_cast<float>(value >> 8) * (1.0f / 16777216.0f);
    }
    glm::vec3 next3() { return glm::vec3(next(), next(), next()); }
};

std::uint32_t bits(float value)
{
    std::uint32_t word = 0;
    std::memcpy(&word, &value, sizeof(word));
    return word;
}

// Mean and standard error of a per-channel estimator.
struct Mean3
{
    glm::dvec3 sum{0.0};
    glm::dvec3 sum_squares{0.0};
    int count = 0;
    void add(const glm::vec3& value)
    {
        sum += glm::dvec3(value);
        sum_squares += glm::dvec3(value) * glm::dvec3(value);
        ++count;
    }
    glm::dvec3 mean() const { return sum / double(count); }
    glm::dvec3 standard_error() const
    {
        const glm::dvec3 m = mean();
        return glm::sqrt(glm::max(sum_squares / double(count) - m * m, glm::dvec3(0.0)) / double(count));
    }
};

OpenPBR_ResolvedInputs red_plastic()
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.base_color = glm::vec3(0.9f, 0.05f, 0.05f);
    inputs.specular_roughness = 0.3f;
    inputs.coat_weight = 0.5f;
    inputs.coat_roughness = 0.1f;
    return inputs;
}

// ---- path_throughput-weighted lobe selection -------------------------------------------------

TEST(EstablishedApi, SelectionFollowsThroughputAndTheEstimatorKeepsItsMean)
{
    const OpenPBR_ResolvedInputs inputs = red_plastic();
    const glm::vec3 view = glm::normalize(glm::vec3(0.3f, 0.1f, 0.8f));
    const glm::vec3 white(1.0f);
    const glm::vec3 red_path(1.0f, 0.02f, 0.02f);
    const glm::vec3 cyan_path(0.02f, 1.0f, 1.0f);
    const OpenPBR_PreparedBsdf for_white =
        openpbr_prepare(inputs, white, OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, view);
    const OpenPBR_PreparedBsdf for_red =
        openpbr_prepare(inputs, red_path, OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, view);
    const OpenPBR_PreparedBsdf for_cyan =
        openpbr_prepare(inputs, cyan_path, OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, view);
    // The red diffuse lobe adds most to a red path and least to a cyan one; the white coat and
    // specular lobes take the rest.
    EXPECT_GT(for_red.probability_diffuse, for_white.probability_diffuse);
    EXPECT_LT(for_cyan.probability_diffuse, for_white.probability_diffuse);
    EXPECT_GT(for_cyan.probability_specular, for_white.probability_specular);
    std::printf("P(diffuse): white path %.4f, red path %.4f, cyan path %.4f\n", double(for_white.probability_diffuse),
                double(for_red.probability_diffuse), double(for_cyan.probability_diffuse));

    // eval does not depend on the throughput at all (bit for bit); pdf is the mixture actually
    // sampled, so it does.
    Random random(7);
    for (int index = 0; index < 200; ++index)
    {
        const glm::vec3 light = glm::normalize(random.next3() * 2.0f - 1.0f + glm::vec3(0.0f, 0.0f, 0.5f));
        const OpenPBR_DiffuseSpecular a = openpbr_eval(for_white, light);
        const OpenPBR_DiffuseSpecular b = openpbr_eval(for_red, light);
        for (int channel = 0; channel < 3; ++channel)
        {
            ASSERT_EQ(bits(a.diffuse[channel]), bits(b.diffuse[channel]));
            ASSERT_EQ(bits(a.specular[channel]), bits(b.specular[channel]));
        }
    }

    // The estimator E[weight] (the directional albedo) is the same for every throughput, and
    // the diffuse lobe is selected as often as its probability says.
    const int sample_count = 400000;
    const glm::vec3 paths[3] = {white, red_path, cyan_path};
    const OpenPBR_PreparedBsdf* prepared[3] = {&for_white, &for_red, &for_cyan};
    Mean3 means[3];
    for (int path = 0; path < 3; ++path)
    {
        Random sampler(11 + path);
        int diffuse_picks = 0;
        for (int index = 0; index < sample_count; ++index)
        {
            vec3 light_direction;
            OpenPBR_DiffuseSpecular weight;
            float pdf = 0.0f;
            OpenPBR_BsdfLobeType sampled_type = 0u;
            openpbr_sample(*prepared[path], sampler.next3(), light_direction, weight, pdf, sampled_type);
            means[path].add(pdf > 0.0f ? openpbr_get_sum_of_diffuse_specular(weight) : glm::vec3(0.0f));
            diffuse_picks += (sampled_type >> OPENPBR_LOBE_ID_SHIFT) == OPENPBR_LOBE_ID_DIFFUSE ? 1 : 0;
        }
        const double frequency = double(diffuse_picks) / sample_count;
        const double expected = prepared[path]->probability_diffuse;
        const double frequency_error = std::sqrt(expected * (1.0 - expected) / sample_count);
        EXPECT_NEAR(frequency, expected, 5.0 * frequency_error) << "path " << path;
        (void)paths;
    }
    for (int path = 1; path < 3; ++path)
    {
        const glm::dvec3 difference = means[path].mean() - means[0].mean();
        const glm::dvec3 error = glm::sqrt(means[path].standard_error() * means[path].standard_error() +
                                           means[0].standard_error() * means[0].standard_error());
        for (int channel = 0; channel < 3; ++channel)
        {
            // 5 standard errors: a false alarm about once in 1.7 million runs.
            EXPECT_LT(std::abs(difference[channel]), 5.0 * error[channel])
                << "path " << path << " channel " << channel << ": mean " << means[path].mean()[channel] << " vs "
                << means[0].mean()[channel];
        }
        std::printf("albedo estimate, path %d: (%.4f %.4f %.4f) vs white (%.4f %.4f %.4f), std. error %.1e\n", path,
                    means[path].mean().x, means[path].mean().y, means[path].mean().z, means[0].mean().x, means[0].mean().y,
                    means[0].mean().z, error.x);
    }
}

TEST(EstablishedApi, DegenerateThroughputsSelectLikeWhite)
{
    const OpenPBR_ResolvedInputs inputs = red_plastic();
    const glm::vec3 view(0.0f, 0.0f, 1.0f);
    const OpenPBR_PreparedBsdf white = openpbr_prepare(inputs, view);
    const float nan = std::nanf("");
    const float infinity = INFINITY;
    // All zero, negative, NaN: no preference; a grey of any scale is white after normalization.
    for (const glm::vec3 throughput :
         {glm::vec3(0.0f), glm::vec3(-1.0f), glm::vec3(nan), glm::vec3(0.25f), glm::vec3(3.0e38f)})
    {
        const OpenPBR_PreparedBsdf prepared =
            openpbr_prepare(inputs, throughput, OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, view);
        EXPECT_EQ(bits(prepared.probability_diffuse), bits(white.probability_diffuse)) << throughput.x;
        EXPECT_EQ(bits(prepared.probability_coat), bits(white.probability_coat)) << throughput.x;
    }
    // An infinite channel counts as the largest float (the documented clamp): an infinitely
    // red path, on which the red diffuse lobe is picked more often than on a white one.
    const OpenPBR_PreparedBsdf partly_infinite =
        openpbr_prepare(inputs, glm::vec3(infinity, 1.0f, 1.0f), OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, view);
    EXPECT_TRUE(std::isfinite(partly_infinite.probability_diffuse));
    EXPECT_GT(partly_infinite.probability_diffuse, white.probability_diffuse);
}

// ---- staged preparation ----------------------------------------------------------------------

TEST(EstablishedApi, StagedPreparationEqualsOneCall)
{
    Random random(3);
    for (int index = 0; index < 300; ++index)
    {
        OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
        inputs.base_color = random.next3();
        inputs.transmission_weight = random.next() < 0.5f ? 1.0f : random.next();
        inputs.transmission_depth = random.next();
        inputs.subsurface_weight = random.next();
        inputs.coat_weight = random.next();
        inputs.emission_luminance = 5.0f * random.next();
        inputs.specular_roughness = random.next();
        const glm::vec3 view = glm::normalize(random.next3() * 2.0f - 1.0f);
        const glm::vec3 throughput = random.next3();
        // In air and under water (the coat's and the base's relative IORs change).
        const float exterior_ior = index % 2 == 0 ? OpenPBR_VacuumIor : 1.33f;
        const OpenPBR_PreparedBsdf one_call =
            openpbr_prepare(inputs, throughput, OpenPBR_BaseRgbWavelengths_nm, exterior_ior, view);
        // Start from another material's preparation: every field the stages own must be
        // overwritten.
        OpenPBR_ResolvedInputs other = openpbr_make_default_resolved_inputs();
        other.emission_luminance = 100.0f;
        other.subsurface_weight = 1.0f;
        OpenPBR_PreparedBsdf staged = openpbr_prepare(other, glm::vec3(0.0f, 1.0f, 0.0f));
        openpbr_prepare_volume(staged, inputs);
        openpbr_prepare_lobes(staged, inputs, throughput, OpenPBR_BaseRgbWavelengths_nm, exterior_ior, view);
        openpbr_prepare_emission(staged, inputs, exterior_ior, view);
        for (int channel = 0; channel < 3; ++channel)
        {
            ASSERT_EQ(bits(staged.emission[channel]), bits(one_call.emission[channel]));
            ASSERT_EQ(bits(staged.volume.extinction[channel]), bits(one_call.volume.extinction[channel]));
            ASSERT_EQ(bits(staged.volume.albedo[channel]), bits(one_call.volume.albedo[channel]));
        }
        ASSERT_EQ(staged.volume.is_present, one_call.volume.is_present);
        ASSERT_EQ(bits(staged.volume.anisotropy), bits(one_call.volume.anisotropy));
        for (int query = 0; query < 8; ++query)
        {
            const glm::vec3 light = glm::normalize(random.next3() * 2.0f - 1.0f);
            const glm::vec3 u = random.next3();
            const glm::vec3 a = openpbr_get_sum_of_diffuse_specular(openpbr_eval(staged, light));
            const glm::vec3 b = openpbr_get_sum_of_diffuse_specular(openpbr_eval(one_call, light));
            const OpenPBR_BsdfSample sa = openpbr_sample(staged, u);
            const OpenPBR_BsdfSample sb = openpbr_sample(one_call, u);
            for (int channel = 0; channel < 3; ++channel)
            {
                ASSERT_EQ(bits(a[channel]), bits(b[channel]));
                ASSERT_EQ(bits(sa.direction[channel]), bits(sb.direction[channel]));
                ASSERT_EQ(bits(sa.weight.specular[channel]), bits(sb.weight.specular[channel]));
            }
            ASSERT_EQ(bits(openpbr_pdf(staged, light)), bits(openpbr_pdf(one_call, light)));
        }
    }
}

// ---- interior volume ---------------------------------------------------------------------------

TEST(EstablishedApi, VolumeConstructorsClampAndAgree)
{
    const OpenPBR_HomogeneousVolume a = openpbr_make_homogeneous_volume_from_absorption_and_scattering(
        glm::vec3(0.5f, 0.0f, 2.0f), glm::vec3(1.5f, 0.0f, 2.0f), 0.4f);
    EXPECT_TRUE(a.is_present);
    EXPECT_FLOAT_EQ(a.extinction.x, 2.0f);
    EXPECT_FLOAT_EQ(a.albedo.x, 0.75f);
    EXPECT_EQ(a.albedo.y, 0.0f);  // no extinction: albedo 0
    EXPECT_FLOAT_EQ(a.albedo.z, 0.5f);
    const OpenPBR_HomogeneousVolume b = openpbr_make_homogeneous_volume_from_extinction_and_albedo(
        glm::vec3(2.0f, 0.0f, 4.0f), glm::vec3(0.75f, 0.0f, 0.5f), 0.4f);
    EXPECT_FLOAT_EQ(b.extinction.z, a.extinction.z);
    const float nan = std::nanf("");
    const OpenPBR_HomogeneousVolume clamped = openpbr_make_homogeneous_volume_from_extinction_and_albedo(
        glm::vec3(-1.0f, nan, 1e30f), glm::vec3(2.0f, -1.0f, nan), 5.0f);
    EXPECT_EQ(clamped.extinction.x, 0.0f);
    EXPECT_EQ(clamped.extinction.y, 0.0f);
    EXPECT_EQ(clamped.extinction.z, OPENPBR_VOLUME_EXTINCTION_MAX);
    EXPECT_EQ(clamped.albedo.x, 1.0f);
    EXPECT_EQ(clamped.albedo.y, 0.0f);
    EXPECT_EQ(clamped.anisotropy, OPENPBR_HG_ANISOTROPY_MAX);
    EXPECT_FALSE(openpbr_make_homogeneous_volume_from_extinction(glm::vec3(0.0f)).is_present);
    const OpenPBR_HomogeneousVolume ink = openpbr_make_homogeneous_volume_from_extinction(glm::vec3(1.0f, 0.0f, 2.0f));
    EXPECT_EQ(ink.albedo, glm::vec3(0.0f));
    EXPECT_EQ(openpbr_calculate_transmittance_at_infinity(ink), glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(openpbr_calculate_transmittance_at_distance(ink, 0.5f).z, std::exp(-1.0f));
}

// Unbiasedness of the flight pair: over a segment of length t, E[pass] = T(t) per channel and
// E[event] = albedo (1 - T(t)) (the single-scattering share of a homogeneous segment), for a
// coloured throughput that draws mostly from one channel.
TEST(EstablishedApi, EventAndSurfaceWeightsAreUnbiased)
{
    const OpenPBR_HomogeneousVolume medium = openpbr_make_homogeneous_volume_from_extinction_and_albedo(
        glm::vec3(0.5f, 2.0f, 8.0f), glm::vec3(0.9f, 0.5f, 0.2f), 0.0f);
    const float segment = 0.7f;
    const glm::vec3 throughput(1.0f, 0.3f, 0.05f);
    Mean3 passed;
    Mean3 scattered;
    Random random(5);
    float largest_relative_difference = 0.0f;
    for (int index = 0; index < 300000; ++index)
    {
        const glm::vec2 u(random.next(), random.next());
        const float distance_value = openpbr_sample_event_distance(medium, throughput, u);
        if (distance_value < segment)
        {
            const glm::vec3 weight = openpbr_calculate_weight_for_event_at_distance(medium, throughput, distance_value);
            scattered.add(weight);
            passed.add(glm::vec3(0.0f));
            // The project's sampler computes the same weight with the drawn channel as reference.
            const OpenPBR_VolumeDistanceSample flight =
                openpbr_volume_sample_distance(medium, throughput, segment, u.x, u.y);
            for (int channel = 0; channel < 3; ++channel)
            {
                largest_relative_difference =
                    std::max(largest_relative_difference, std::abs(flight.weight[channel] - weight[channel]) /
                                                              std::max(std::abs(flight.weight[channel]), 1e-30f));
            }
        }
        else
        {
            passed.add(openpbr_calculate_weight_for_surface_at_distance(medium, throughput, segment));
            scattered.add(glm::vec3(0.0f));
        }
    }
    // Measured 3.6e-7 (float rounding of the two reference channels); 1e-5 leaves room for
    // other compilers' contraction choices.
    EXPECT_LT(largest_relative_difference, 1e-5f);
    for (int channel = 0; channel < 3; ++channel)
    {
        const double transmittance = std::exp(-double(medium.extinction[channel]) * segment);
        EXPECT_NEAR(passed.mean()[channel], transmittance, 5.0 * passed.standard_error()[channel] + 1e-6) << channel;
        EXPECT_NEAR(scattered.mean()[channel], medium.albedo[channel] * (1.0 - transmittance),
                    5.0 * scattered.standard_error()[channel] + 1e-6)
            << channel;
    }
}

TEST(EstablishedApi, PhaseFunctionsAreNormalizedAndSampledExactly)
{
    const OpenPBR_HomogeneousVolume medium =
        openpbr_make_homogeneous_volume_from_extinction_and_albedo(glm::vec3(1.0f), glm::vec3(1.0f), 0.6f);
    const glm::vec3 incoming = glm::normalize(glm::vec3(0.2f, -0.3f, 0.9f));
    Random random(9);
    double integral = 0.0;
    const int count = 200000;
    for (int index = 0; index < count; ++index)
    {
        const glm::vec2 u(random.next(), random.next());
        const glm::vec3 uniform = openpbr_sample_isotropic_phase_function(u);
        integral += openpbr_calculate_anisotropic_phase_function_value(medium, incoming, uniform) /
                    openpbr_calculate_isotropic_phase_function_pdf();
        const glm::vec3 sampled = openpbr_sample_anisotropic_phase_function(medium, incoming, u);
        ASSERT_EQ(openpbr_calculate_anisotropic_phase_function_value(medium, incoming, sampled),
                  openpbr_calculate_anisotropic_phase_function_pdf(medium, incoming, sampled));
    }
    // HG at g = 0.6 over uniform directions: relative standard error about 0.4 % at 2e5
    // samples (measured spread); 2 % is five of them.
    EXPECT_NEAR(integral / count, 1.0, 0.02);
    EXPECT_FLOAT_EQ(openpbr_calculate_isotropic_phase_function_value() * 4.0f * 3.14159265f, 1.0f);
}

// ---- straight-through shadow rays --------------------------------------------------------------

// A slab between z = 0 (top face, normal +z) and z = -thickness (bottom face, normal -z), of
// `inputs`. The reference traces paths with the BSDF's own sampling through both faces (every
// internal reflection, refraction and the medium's absorption along the refracted segments) and
// counts the throughput leaving through the bottom: the slab's total transmittance for light
// arriving along `direction`.
glm::dvec3 path_traced_slab_transmittance(const OpenPBR_ResolvedInputs& inputs, glm::vec3 direction, float thickness,
                                          int path_count)
{
    OpenPBR_ResolvedInputs top = inputs;
    top.geometry_basis = openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
    top.geometry_coat_basis = top.geometry_basis;
    OpenPBR_ResolvedInputs bottom = inputs;
    bottom.geometry_basis = openpbr_make_basis(glm::vec3(0.0f, 0.0f, -1.0f));
    bottom.geometry_coat_basis = bottom.geometry_basis;
    const OpenPBR_HomogeneousVolume medium = openpbr_prepare_volume(inputs);
    Random random(21);
    glm::dvec3 total(0.0);
    for (int path = 0; path < path_count; ++path)
    {
        glm::vec3 travel = direction;
        bool at_top = true;
        glm::vec3 throughput(1.0f);
        for (int bounce = 0; bounce < 64; ++bounce)
        {
            const OpenPBR_PreparedBsdf prepared = openpbr_prepare(at_top ? top : bottom, -travel);
            const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(prepared, random.next3());
            if (!(bsdf_sample.pdf > 0.0f))
            {
                break;
            }
            throughput *= bsdf_sample.weight.diffuse + bsdf_sample.weight.specular;
            travel = bsdf_sample.direction;
            if (at_top && travel.z > 0.0f)
            {
                break;  // reflected back up, or left through the top
            }
            if (!at_top && travel.z < 0.0f)
            {
                total += glm::dvec3(throughput);  // left through the bottom
                break;
            }
            throughput *= openpbr_volume_transmittance(medium, thickness / std::abs(travel.z));
            at_top = !at_top;
        }
    }
    return total / double(path_count);
}

glm::vec3 shortcut_slab_transmittance(const OpenPBR_ResolvedInputs& inputs, glm::vec3 direction, float thickness)
{
    OpenPBR_ResolvedInputs top = inputs;
    top.geometry_basis = openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
    top.geometry_coat_basis = top.geometry_basis;
    OpenPBR_ResolvedInputs bottom = inputs;
    bottom.geometry_basis = openpbr_make_basis(glm::vec3(0.0f, 0.0f, -1.0f));
    bottom.geometry_coat_basis = bottom.geometry_basis;
    const OpenPBR_PreparedBsdf entering =
        openpbr_prepare(top, glm::vec3(1.0f), OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, -direction);
    const OpenPBR_PreparedBsdf leaving =
        openpbr_prepare(bottom, glm::vec3(1.0f), OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, -direction);
    vec3 entering_weight;
    float entering_probability = 0.0f;
    vec3 leaving_weight;
    float leaving_probability = 0.0f;
    openpbr_translucent_shadow_weight_and_prob(entering, entering_weight, entering_probability);
    openpbr_translucent_shadow_weight_and_prob(leaving, leaving_weight, leaving_probability);
    EXPECT_FALSE(entering.inside);
    EXPECT_TRUE(leaving.inside);
    const glm::vec3 interior =
        openpbr_calculate_transmittance_at_distance(entering.volume, thickness / std::abs(direction.z));
    return entering_weight * entering_probability * interior * leaving_weight * leaving_probability;
}

struct SlabCase
{
    const char* name;
    float roughness;
    float depth;      // transmission_depth; 0: no medium (the tint is applied on entry)
    float angle_deg;  // of the shadow ray from the normal
    float tolerance;  // on shortcut / (reference x predicted bias), see the table below
};

class TranslucentShadow : public ::testing::TestWithParam<SlabCase>
{
};

// Smooth slabs: the shortcut's bias is known in closed form. With F the Fresnel reflectance at
// the exterior angle, T_i = exp(-sigma L / cos(theta_i)) and T_t = exp(-sigma L / cos(theta_t))
// the straight and the refracted interior transmittances,
//   shortcut  = (1 - F)^2 T_i,   exact = (1 - F)^2 T_t / (1 - F^2 T_t^2),
// so shortcut / exact = (T_i / T_t) (1 - F^2 T_t^2): the test checks the measured ratio against
// that prediction (the path tracer carries only Monte Carlo noise, under 0.2 % at 2e5 paths).
// Rough slabs have no closed form: their ratio is printed and bounded by the measured figure.
TEST_P(TranslucentShadow, MatchesPathTracedSlab)
{
    const SlabCase slab = GetParam();
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.transmission_weight = 1.0f;
    inputs.transmission_color = glm::vec3(0.9f, 0.6f, 0.3f);
    inputs.transmission_depth = slab.depth;
    inputs.specular_roughness = slab.roughness;
    inputs.specular_ior = 1.5f;
    const float thickness = 0.5f;
    const float angle = slab.angle_deg * 3.14159265f / 180.0f;
    const glm::vec3 direction(std::sin(angle), 0.0f, -std::cos(angle));
    const glm::dvec3 reference = path_traced_slab_transmittance(inputs, direction, thickness, 200000);
    const glm::vec3 shortcut = shortcut_slab_transmittance(inputs, direction, thickness);
    const OpenPBR_HomogeneousVolume medium = openpbr_prepare_volume(inputs);
    const float cos_i = std::cos(angle);
    const float sin_t = std::sin(angle) / 1.5f;
    const float cos_t = std::sqrt(1.0f - sin_t * sin_t);
    const float fresnel = openpbr_fresnel_dielectric(cos_i, 1.5f);
    for (int channel = 0; channel < 3; ++channel)
    {
        const double ratio = shortcut[channel] / reference[channel];
        const double sigma = medium.is_present ? medium.extinction[channel] : 0.0;
        const double t_i = std::exp(-sigma * thickness / cos_i);
        const double t_t = std::exp(-sigma * thickness / cos_t);
        const double predicted = slab.roughness == 0.0f ? (t_i / t_t) * (1.0 - fresnel * fresnel * t_t * t_t) : 1.0;
        std::printf("%s channel %d: shortcut %.5f, path-traced %.5f, ratio %.4f (smooth-slab prediction %.4f)\n", slab.name,
                    channel, double(shortcut[channel]), reference[channel], ratio, predicted);
        EXPECT_NEAR(ratio / predicted, 1.0, slab.tolerance) << slab.name << " channel " << channel;
    }
}

// Tolerances on ratio / prediction: smooth cases 0.01 (measured within 0.4 % of the closed
// form, the reference's Monte Carlo noise at 2e5 paths included); rough cases 0.05 around 1
// (measured shortcut / path-traced: 1.0003-1.0035 at normal incidence, 1.020 at 45 degrees,
// where the rough exit sends part of the light back that the shortcut lets through).
INSTANTIATE_TEST_SUITE_P(Slabs, TranslucentShadow,
                         ::testing::Values(SlabCase{"smooth_clear_normal", 0.0f, 0.0f, 0.0f, 0.01f},
                                           SlabCase{"smooth_absorbing_normal", 0.0f, 1.0f, 0.0f, 0.01f},
                                           SlabCase{"smooth_absorbing_45", 0.0f, 1.0f, 45.0f, 0.01f},
                                           SlabCase{"smooth_absorbing_70", 0.0f, 1.0f, 70.0f, 0.01f},
                                           SlabCase{"rough_absorbing_normal", 0.3f, 1.0f, 0.0f, 0.05f},
                                           SlabCase{"rough_clear_45", 0.3f, 0.0f, 45.0f, 0.05f}),
                         [](const ::testing::TestParamInfo<SlabCase>& info) { return std::string(info.param.name); });

TEST(EstablishedApi, ShadowShortcutOfOpaqueAndThinMaterials)
{
    const glm::vec3 view(0.0f, 0.0f, 1.0f);
    vec3 weight;
    float probability = 1.0f;
    // Opaque plastic: blocked.
    openpbr_translucent_shadow_weight_and_prob(openpbr_prepare(red_plastic(), view), weight, probability);
    EXPECT_EQ(probability, 0.0f);
    EXPECT_EQ(weight, glm::vec3(0.0f));
    // Half-transparent plastic: the pass-through, (1 - opacity) straight on.
    OpenPBR_ResolvedInputs cutout = red_plastic();
    cutout.geometry_opacity = 0.25f;
    const OpenPBR_PreparedBsdf cutout_prepared = openpbr_prepare(cutout, view);
    openpbr_translucent_shadow_weight_and_prob(cutout_prepared, weight, probability);
    EXPECT_FLOAT_EQ(probability, cutout_prepared.probability_pass_through);
    EXPECT_NEAR(weight.x * probability, 0.75f, 1e-6f);
    // A smooth thin-walled sheet of glass: one interface's (1 - F) and the tint, exactly.
    OpenPBR_ResolvedInputs sheet = openpbr_make_default_resolved_inputs();
    sheet.geometry_thin_walled = true;
    sheet.transmission_weight = 1.0f;
    sheet.transmission_color = glm::vec3(0.5f, 0.7f, 0.9f);
    sheet.specular_roughness = 0.0f;
    openpbr_translucent_shadow_weight_and_prob(openpbr_prepare(sheet, view), weight, probability);
    const float fresnel = openpbr_fresnel_dielectric(1.0f, 1.5f);
    EXPECT_NEAR(weight.y * probability, (1.0f - fresnel) * 0.7f, 1e-5f);
}

}  // namespace
