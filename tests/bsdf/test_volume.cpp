// Tests for slang/openpbr_volume.h: the specification's medium formulas (docs/spec-notes.md
// section 5), the van de Hulst inversion, the Henyey-Greenstein phase function, the spectral-MIS
// distance sampler, and robustness against extreme inputs. All random tests use fixed seeds.
#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/openpbr_volume.h"
#include "slang/openpbr_input_contract.h"  // the caller-side clamping, for the non-finite test

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

using glm::vec2;
using glm::vec3;
using openpbr::OpenPBR_HomogeneousVolume;
using openpbr::OpenPBR_ResolvedInputs;
using openpbr::OpenPBR_VolumeDistanceSample;

constexpr double kPi = 3.14159265358979323846;
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr float kDenormal = 1e-40f;

float channel(const vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

OpenPBR_ResolvedInputs translucent_inputs(const vec3& color, float depth, const vec3& scatter, float anisotropy)
{
    OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    inputs.transmission_weight = 1.0f;
    inputs.transmission_color = color;
    inputs.transmission_depth = depth;
    inputs.transmission_scatter = scatter;
    inputs.transmission_scatter_anisotropy = anisotropy;
    return inputs;
}

OpenPBR_ResolvedInputs subsurface_inputs(const vec3& color, float radius, const vec3& scale, float anisotropy)
{
    OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    inputs.subsurface_weight = 1.0f;
    inputs.subsurface_color = color;
    inputs.subsurface_radius = radius;
    inputs.subsurface_radius_scale = scale;
    inputs.subsurface_scatter_anisotropy = anisotropy;
    return inputs;
}

OpenPBR_HomogeneousVolume make_test_volume(const vec3& extinction, const vec3& albedo, float anisotropy)
{
    OpenPBR_HomogeneousVolume volume;
    volume.extinction = extinction;
    volume.albedo = albedo;
    volume.anisotropy = anisotropy;
    volume.is_present = true;
    return volume;
}

bool finite(float x) { return std::isfinite(x); }
bool finite(const vec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }

// ---------------------------------------------------------------------------------------------
// Spec formulas

TEST(VolumeSpec, BeerLawTransmittanceAtDepthEqualsTransmissionColor)
{
    const vec3 color(0.2f, 0.5f, 0.9f);
    for (const float depth : {1e-3f, 0.37f, 2.5f, 1e4f})
    {
        const OpenPBR_HomogeneousVolume volume =
            openpbr::openpbr_make_volume(translucent_inputs(color, depth, vec3(0.0f), 0.0f));
        ASSERT_TRUE(volume.is_present);
        const vec3 transmittance = openpbr::openpbr_volume_transmittance(volume, depth);
        for (int c = 0; c < 3; ++c)
        {
            EXPECT_NEAR(channel(transmittance, c), channel(color, c), 2e-6f * channel(color, c) + 1e-7f)
                << "depth " << depth << " channel " << c;
            // No scattering: mu_t = -ln(T) / depth exactly, pure absorber.
            EXPECT_NEAR(channel(volume.extinction, c), -std::log(channel(color, c)) / depth,
                        1e-5f * channel(volume.extinction, c));
            EXPECT_EQ(channel(volume.albedo, c), 0.0f);
        }
        // Half the depth: sqrt(T).
        const vec3 half = openpbr::openpbr_volume_transmittance(volume, 0.5f * depth);
        EXPECT_NEAR(half.y, std::sqrt(color.y), 1e-6f);
    }
}

TEST(VolumeSpec, TranslucentScatteringWithoutGrayShift)
{
    // -ln(0.1) = 2.30 > S in every channel: mu_a >= 0, no shift; mu_s = S / depth.
    const vec3 color(0.1f);
    const vec3 scatter(0.5f, 1.0f, 0.2f);
    const float depth = 2.0f;
    const OpenPBR_HomogeneousVolume volume = openpbr::openpbr_make_volume(translucent_inputs(color, depth, scatter, 0.4f));
    ASSERT_TRUE(volume.is_present);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(channel(volume.extinction, c), -std::log(0.1f) / depth, 1e-5f);
        EXPECT_NEAR(channel(volume.extinction * volume.albedo, c), channel(scatter, c) / depth, 1e-5f);
    }
    EXPECT_NEAR(openpbr::openpbr_volume_transmittance(volume, depth).x, 0.1f, 1e-6f);
    EXPECT_FLOAT_EQ(volume.anisotropy, 0.4f);
}

TEST(VolumeSpec, TranslucentGrayShift)
{
    // T = 1: mu_t = 0, mu_a = -S / depth, shifted by max(S) / depth = 0.5 / depth.
    const float depth = 4.0f;
    const OpenPBR_HomogeneousVolume volume =
        openpbr::openpbr_make_volume(translucent_inputs(vec3(1.0f), depth, vec3(0.5f, 0.2f, 0.0f), 0.0f));
    ASSERT_TRUE(volume.is_present);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(channel(volume.extinction, c), 0.5f / depth, 1e-7f);
    }
    EXPECT_NEAR(volume.albedo.x, 1.0f, 1e-6f);
    EXPECT_NEAR(volume.albedo.y, 0.4f, 1e-6f);
    EXPECT_NEAR(volume.albedo.z, 0.0f, 1e-6f);

    // White furnace configuration of the spec: white scatter with white color is non-absorbing.
    const OpenPBR_HomogeneousVolume white =
        openpbr::openpbr_make_volume(translucent_inputs(vec3(1.0f), 0.3f, vec3(1.0f), 0.7f));
    EXPECT_EQ(white.albedo, vec3(1.0f));
}

TEST(VolumeSpec, DepthZeroIsNoMedium)
{
    EXPECT_FALSE(openpbr::openpbr_make_volume(translucent_inputs(vec3(0.3f), 0.0f, vec3(0.5f), 0.0f)).is_present);
    // A denormal depth is 0 on GPUs that flush denormals; the CPU build must agree.
    EXPECT_FALSE(openpbr::openpbr_make_volume(translucent_inputs(vec3(0.3f), kDenormal, vec3(0.5f), 0.0f)).is_present);
    // Depth > 0 with white color and no scatter: vacuum, no medium either.
    EXPECT_FALSE(openpbr::openpbr_make_volume(translucent_inputs(vec3(1.0f), 1.0f, vec3(0.0f), 0.0f)).is_present);
    // Defaults (no transmission, no subsurface) have no medium.
    EXPECT_FALSE(openpbr::openpbr_make_volume(openpbr::openpbr_make_default_resolved_inputs()).is_present);
}

TEST(VolumeSpec, SubsurfaceMeanFreePathAndAlbedo)
{
    const vec3 scale(1.0f, 0.5f, 0.25f);
    const vec3 color(0.8f, 0.4f, 0.1f);
    const float radius = 0.2f;
    const float g = 0.3f;
    const OpenPBR_HomogeneousVolume volume = openpbr::openpbr_make_volume(subsurface_inputs(color, radius, scale, g));
    ASSERT_TRUE(volume.is_present);
    for (int c = 0; c < 3; ++c)
    {
        const float mean_free_path = radius * channel(scale, c);
        EXPECT_NEAR(1.0f / channel(volume.extinction, c), mean_free_path, 1e-6f * mean_free_path);
        // Transmittance over one mean free path is 1/e.
        EXPECT_NEAR(channel(openpbr::openpbr_volume_transmittance(volume, mean_free_path), c), std::exp(-1.0f), 1e-6f);
        EXPECT_FLOAT_EQ(channel(volume.albedo, c), openpbr::openpbr_van_de_hulst_albedo(channel(color, c), g));
    }
    EXPECT_FLOAT_EQ(volume.anisotropy, g);
}

TEST(VolumeSpec, SubsurfaceColorEndpointsAndZeroRadius)
{
    const OpenPBR_HomogeneousVolume black =
        openpbr::openpbr_make_volume(subsurface_inputs(vec3(0.0f), 1.0f, vec3(1.0f), 0.0f));
    const OpenPBR_HomogeneousVolume white =
        openpbr::openpbr_make_volume(subsurface_inputs(vec3(1.0f), 1.0f, vec3(1.0f), -0.5f));
    // The spec's fit gives s = 0.999997 at C = 0, i.e. alpha = 5.7e-6: black within the fit.
    EXPECT_LT(openpbr::openpbr_max3(black.albedo), 1e-5f);
    EXPECT_EQ(white.albedo, vec3(1.0f));  // the spec's white furnace: subsurface white must not absorb

    const OpenPBR_HomogeneousVolume dense =
        openpbr::openpbr_make_volume(subsurface_inputs(vec3(0.5f), 0.0f, vec3(1.0f), 0.0f));
    ASSERT_TRUE(dense.is_present);
    EXPECT_EQ(dense.extinction, vec3(OPENPBR_VOLUME_EXTINCTION_MAX));
    const OpenPBR_HomogeneousVolume zero_scale =
        openpbr::openpbr_make_volume(subsurface_inputs(vec3(0.5f), 1.0f, vec3(1.0f, 0.0f, kDenormal), 0.0f));
    EXPECT_FLOAT_EQ(zero_scale.extinction.x, 1.0f);
    EXPECT_EQ(zero_scale.extinction.y, OPENPBR_VOLUME_EXTINCTION_MAX);
    EXPECT_EQ(zero_scale.extinction.z, OPENPBR_VOLUME_EXTINCTION_MAX);
}

TEST(VolumeSpec, WeightsThinWalledAndMetal)
{
    OpenPBR_ResolvedInputs inputs = subsurface_inputs(vec3(0.5f), 1.0f, vec3(1.0f), 0.0f);
    inputs.geometry_thin_walled = true;
    EXPECT_FALSE(openpbr::openpbr_make_volume(inputs).is_present);
    inputs.geometry_thin_walled = false;
    inputs.base_metalness = 1.0f;
    EXPECT_FALSE(openpbr::openpbr_make_volume(inputs).is_present);
    inputs.base_metalness = 0.0f;
    inputs.subsurface_weight = 0.0f;
    EXPECT_FALSE(openpbr::openpbr_make_volume(inputs).is_present);
    inputs.subsurface_weight = kDenormal;
    EXPECT_FALSE(openpbr::openpbr_make_volume(inputs).is_present);
    // Metalness < 1 does not change the medium (only the ratio of the two weights does).
    inputs.subsurface_weight = 1.0f;
    const OpenPBR_HomogeneousVolume plain = openpbr::openpbr_make_volume(inputs);
    inputs.base_metalness = 0.9f;
    const OpenPBR_HomogeneousVolume metallic = openpbr::openpbr_make_volume(inputs);
    EXPECT_EQ(plain.extinction, metallic.extinction);
    EXPECT_EQ(plain.albedo, metallic.albedo);
}

TEST(VolumeSpec, BlendOfTranslucentAndSubsurface)
{
    OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    inputs.base_metalness = 0.3f;
    inputs.transmission_weight = 0.25f;
    inputs.transmission_color = vec3(0.5f, 0.6f, 0.7f);
    inputs.transmission_depth = 2.0f;
    inputs.transmission_scatter = vec3(0.3f, 0.2f, 0.1f);
    inputs.transmission_scatter_anisotropy = 0.8f;
    inputs.subsurface_weight = 0.5f;
    inputs.subsurface_color = vec3(0.9f, 0.5f, 0.2f);
    inputs.subsurface_radius = 0.5f;
    inputs.subsurface_radius_scale = vec3(1.0f, 0.5f, 0.25f);
    inputs.subsurface_scatter_anisotropy = -0.2f;

    // Spec weights: translucent (1-M) T, subsurface (1-M)(1-T) S; normalized: 0.4 and 0.6.
    const float w_translucent = 0.7f * 0.25f;
    const float w_subsurface = 0.7f * 0.75f * 0.5f;
    const float a = w_translucent / (w_translucent + w_subsurface);
    const float b = 1.0f - a;

    OpenPBR_ResolvedInputs only_translucent = inputs;
    only_translucent.subsurface_weight = 0.0f;
    OpenPBR_ResolvedInputs only_subsurface = inputs;
    only_subsurface.transmission_weight = 0.0f;
    const OpenPBR_HomogeneousVolume t = openpbr::openpbr_make_volume(only_translucent);
    const OpenPBR_HomogeneousVolume s = openpbr::openpbr_make_volume(only_subsurface);
    const OpenPBR_HomogeneousVolume mixed = openpbr::openpbr_make_volume(inputs);
    ASSERT_TRUE(t.is_present && s.is_present && mixed.is_present);

    const vec3 sigma_s_t = t.extinction * t.albedo;
    const vec3 sigma_s_s = s.extinction * s.albedo;
    for (int c = 0; c < 3; ++c)
    {
        const float extinction = a * channel(t.extinction, c) + b * channel(s.extinction, c);
        const float scattering = a * channel(sigma_s_t, c) + b * channel(sigma_s_s, c);
        EXPECT_NEAR(channel(mixed.extinction, c), extinction, 1e-5f * extinction);
        EXPECT_NEAR(channel(mixed.albedo, c), scattering / extinction, 1e-5f);
    }
    const float sum_t = a * (sigma_s_t.x + sigma_s_t.y + sigma_s_t.z);
    const float sum_s = b * (sigma_s_s.x + sigma_s_s.y + sigma_s_s.z);
    EXPECT_NEAR(mixed.anisotropy, (sum_t * 0.8f + sum_s * -0.2f) / (sum_t + sum_s), 1e-5f);

    // Depth 0 makes the translucent part vacuum: the subsurface coefficients are diluted by b.
    inputs.transmission_depth = 0.0f;
    const OpenPBR_HomogeneousVolume diluted = openpbr::openpbr_make_volume(inputs);
    EXPECT_NEAR(diluted.extinction.y, b * s.extinction.y, 1e-5f * s.extinction.y);
    EXPECT_NEAR(diluted.albedo.y, s.albedo.y, 1e-6f);
    EXPECT_FLOAT_EQ(diluted.anisotropy, -0.2f);
}

// ---------------------------------------------------------------------------------------------
// van de Hulst inversion

// The spec's forward formula in double, the reference for the round trips.
double van_de_hulst_color_reference(double albedo, double g)
{
    const double s = std::sqrt((1.0 - albedo) / (1.0 - albedo * g));
    return (1.0 - s) * (1.0 - 0.139 * s) / (1.0 + 1.17 * s);
}

TEST(VanDeHulst, ColorToAlbedoToColorRoundTrip)
{
    for (const float g : {-0.9f, -0.3f, 0.0f, 0.5f, 0.95f})
    {
        for (int i = 0; i <= 1000; ++i)
        {
            const float color = float(i) / 1000.0f;
            const float albedo = openpbr::openpbr_van_de_hulst_albedo(color, g);
            ASSERT_GE(albedo, 0.0f);
            ASSERT_LE(albedo, 1.0f);
            // The fit inverts the formula to 1.2e-5 (checked in double). Near alpha = 1 the color
            // also moves by dC/dalpha * (float spacing of alpha), which grows like 1/sqrt(1 - alpha):
            // that is the resolution of a float albedo, not an error of the inversion.
            const double spacing = std::ldexp(1.0, -24);
            const double sensitivity = std::fabs(van_de_hulst_color_reference(std::min(double(albedo) + spacing, 1.0), g) -
                                                 van_de_hulst_color_reference(std::max(double(albedo) - spacing, 0.0), g));
            const double tolerance = 1.5e-5 + 2.0 * sensitivity;
            EXPECT_NEAR(van_de_hulst_color_reference(albedo, g), color, tolerance) << "g " << g << " C " << color;
            // The float forward function agrees with the double reference to the same resolution.
            EXPECT_NEAR(openpbr::openpbr_van_de_hulst_color(albedo, g), van_de_hulst_color_reference(albedo, g),
                        2e-6 + 2.0 * sensitivity);
        }
    }
}

TEST(VanDeHulst, AlbedoToColorToAlbedoRoundTrip)
{
    for (const float g : {-0.9f, 0.0f, 0.5f, 0.95f})
    {
        for (int i = 0; i <= 1000; ++i)
        {
            const float albedo = float(i) / 1000.0f;
            const float color = openpbr::openpbr_van_de_hulst_color(albedo, g);
            const float back = openpbr::openpbr_van_de_hulst_albedo(color, g);
            // Compare s = sqrt((1 - alpha) / (1 - g alpha)), the variable the fit is accurate in;
            // alpha itself is ill-conditioned near 1 (d alpha / dC -> 0 there, dC/d alpha -> inf).
            const float s = std::sqrt((1.0f - albedo) / (1.0f - g * albedo));
            const float s_back = std::sqrt(std::max(1.0f - back, 0.0f) / (1.0f - g * back));
            EXPECT_NEAR(s_back, s, 5e-5f) << "g " << g << " albedo " << albedo;
            EXPECT_NEAR(back, albedo, 2e-4f) << "g " << g << " albedo " << albedo;
        }
    }
}

TEST(VanDeHulst, ForwardFormulaAndMonotonicity)
{
    // C(alpha) from the spec's formula at a point computed by hand: alpha = 0.9, g = 0:
    // s = sqrt(0.1) = 0.316228, C = 0.683772 * 0.956044 / 1.369987 = 0.477171.
    EXPECT_NEAR(openpbr::openpbr_van_de_hulst_color(0.9f, 0.0f), 0.477171f, 2e-6f);
    float previous = -1.0f;
    for (int i = 0; i <= 200; ++i)
    {
        const float albedo = openpbr::openpbr_van_de_hulst_albedo(float(i) / 200.0f, 0.2f);
        EXPECT_GE(albedo, previous);
        previous = albedo;
    }
}

// ---------------------------------------------------------------------------------------------
// Henyey-Greenstein

// Integral of p over [c0, c1] in cos(theta), times 2 pi (the azimuth), in double. The substitution
// v = ln(1 + delta - c) (mirrored for g < 0) spreads the forward peak of width ~(1 - |g|)^2.
double hg_integral(float g, double c0, double c1, int steps)
{
    const double sign = g >= 0.0f ? 1.0 : -1.0;
    const double delta = std::max((1.0 - std::fabs(double(g))) * (1.0 - std::fabs(double(g))), 1e-12);
    // In the mirrored variable x = sign * c the peak is at x = 1.
    const double x0 = sign > 0.0 ? c0 : -c1;
    const double x1 = sign > 0.0 ? c1 : -c0;
    const double v0 = std::log(1.0 + delta - x1);
    const double v1 = std::log(1.0 + delta - x0);
    // Composite Simpson over v; dx = -e^v dv.
    double sum = 0.0;
    const double h = (v1 - v0) / steps;
    for (int i = 0; i <= steps; ++i)
    {
        const double v = v0 + h * i;
        const double x = 1.0 + delta - std::exp(v);
        const double weight = (i == 0 || i == steps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        sum += weight * double(openpbr::openpbr_henyey_greenstein_eval(g, float(sign * x))) * std::exp(v);
    }
    return 2.0 * kPi * sum * h / 3.0;
}

TEST(HenyeyGreenstein, NormalizedByQuadrature)
{
    for (const float g : {-0.99f, -0.9f, -0.5f, 0.0f, 1e-4f, 0.3f, 0.8f, 0.95f, 0.99f})
    {
        EXPECT_NEAR(hg_integral(g, -1.0, 1.0, 20000), 1.0, 2e-5) << "g " << g;
    }
    // At |g| = 0.999 the peak is 5e-7 wide in cos(theta), about 8 float steps below 1: the float
    // argument itself resolves the peak only to ~1e-3 of its mass. Out-of-range g is clamped to
    // +-0.999.
    for (const float g : {-1.0f, -0.999f, 0.999f, 1.0f})
    {
        EXPECT_NEAR(hg_integral(g, -1.0, 1.0, 20000), 1.0, 2e-3) << "g " << g;
    }
}

TEST(HenyeyGreenstein, KnownValuesAndIsotropic)
{
    // Peak and tail values: (1 -+ g)... p(1) = (1 + g) / (4 pi (1 - g)^2), p(-1) = (1 - g) / (4 pi (1 + g)^2).
    const float g = 0.6f;
    EXPECT_NEAR(openpbr::openpbr_henyey_greenstein_eval(g, 1.0f), 1.6 / (4.0 * kPi * 0.16), 1e-5);
    EXPECT_NEAR(openpbr::openpbr_henyey_greenstein_eval(g, -1.0f), 0.4 / (4.0 * kPi * 2.56), 1e-7);
    EXPECT_NEAR(openpbr::openpbr_henyey_greenstein_eval(0.0f, 0.3f), 1.0 / (4.0 * kPi), 1e-8);
    EXPECT_NEAR(openpbr::openpbr_isotropic_phase_eval(), 1.0 / (4.0 * kPi), 1e-8);
    // Mean cosine equals g (the spec: g is formally the mean cosine): integral of c p(c) dc.
    double mean = 0.0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i)
    {
        const double c = -1.0 + 2.0 * (i + 0.5) / steps;
        mean += c * openpbr::openpbr_henyey_greenstein_eval(0.5f, float(c)) * 2.0 * kPi * 2.0 / steps;
    }
    EXPECT_NEAR(mean, 0.5, 1e-5);
}

TEST(HenyeyGreenstein, StableInversionMatchesPbrtForm)
{
    for (const float g : {-0.95f, -0.5f, -0.1f, 0.1f, 0.5f, 0.95f})
    {
        for (int i = 0; i <= 100; ++i)
        {
            const double u = i / 100.0;
            const double gd = g;
            const double term = (1.0 - gd * gd) / (1.0 - gd + 2.0 * gd * u);
            const double expected = (1.0 + gd * gd - term * term) / (2.0 * gd);
            EXPECT_NEAR(openpbr::openpbr_henyey_greenstein_sample_cos_theta(g, float(u)), expected, 2e-5);
        }
    }
    // g = 0: uniform in cos(theta), exactly.
    EXPECT_FLOAT_EQ(openpbr::openpbr_henyey_greenstein_sample_cos_theta(0.0f, 0.25f), -0.5f);
    EXPECT_EQ(openpbr::openpbr_henyey_greenstein_sample_cos_theta(0.7f, 1.0f), 1.0f);
    EXPECT_EQ(openpbr::openpbr_henyey_greenstein_sample_cos_theta(0.7f, 0.0f), -1.0f);
}

// Upper quantile of chi-square with k degrees of freedom (Wilson-Hilferty), z standard deviations.
double chi_square_quantile(int k, double z)
{
    const double a = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

TEST(HenyeyGreenstein, SamplingMatchesPdfChiSquare)
{
    const vec3 incoming = glm::normalize(vec3(0.3f, -0.5f, 0.8f));
    std::mt19937 rng(12345u);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const int bins = 40;
    const int samples = 400000;
    // |g| up to 0.99: at 0.999 the peak is narrower than the float spacing of cos(theta) near 1.
    for (const float g : {-0.95f, -0.7f, 0.0f, 0.3f, 0.9f, 0.99f})
    {
        // Bins equally spaced in v = ln(1 + delta - x) (x = c mirrored so the peak is at +1):
        // the narrow forward peak gets bins of comparable probability.
        const double sign = g >= 0.0f ? 1.0 : -1.0;
        const double delta = std::max((1.0 - std::fabs(double(g))) * (1.0 - std::fabs(double(g))), 1e-12);
        const double v_low = std::log(delta);         // x = 1
        const double v_high = std::log(2.0 + delta);  // x = -1
        std::vector<double> observed(bins, 0.0);
        double mean_perpendicular_x = 0.0;
        for (int i = 0; i < samples; ++i)
        {
            const vec3 direction = openpbr::openpbr_henyey_greenstein_sample(g, incoming, vec2(uniform(rng), uniform(rng)));
            ASSERT_NEAR(glm::length(direction), 1.0f, 1e-5f);
            const double x = sign * std::max(-1.0, std::min(1.0, double(glm::dot(direction, incoming))));
            const double v = std::log(1.0 + delta - x);
            const int bin = std::min(bins - 1, std::max(0, int((v - v_low) / (v_high - v_low) * bins)));
            observed[bin] += 1.0;
            mean_perpendicular_x += direction.x - glm::dot(direction, incoming) * incoming.x;
        }
        double chi_square = 0.0;
        double total_probability = 0.0;
        for (int b = 0; b < bins; ++b)
        {
            const double x_high = 1.0 + delta - std::exp(v_low + (v_high - v_low) * b / bins);
            const double x_low = 1.0 + delta - std::exp(v_low + (v_high - v_low) * (b + 1) / bins);
            const double c0 = sign > 0.0 ? x_low : -x_high;
            const double c1 = sign > 0.0 ? x_high : -x_low;
            const double probability = hg_integral(g, c0, c1, 2000);
            total_probability += probability;
            const double expected = probability * samples;
            ASSERT_GT(expected, 5.0) << "bin " << b << " too small for chi-square";
            chi_square += (observed[b] - expected) * (observed[b] - expected) / expected;
        }
        EXPECT_NEAR(total_probability, 1.0, 1e-4);
        EXPECT_LT(chi_square, chi_square_quantile(bins - 1, 4.75)) << "g " << g;  // p ~ 1e-6
        // Azimuth is uniform: the component perpendicular to the incoming direction averages 0.
        EXPECT_NEAR(mean_perpendicular_x / samples, 0.0, 5e-3) << "g " << g;
    }
}

TEST(HenyeyGreenstein, ForwardScatteringFollowsIncomingDirection)
{
    const vec3 incoming = glm::normalize(vec3(-1.0f, 2.0f, -0.5f));
    const vec3 forward = openpbr::openpbr_henyey_greenstein_sample(0.999f, incoming, vec2(0.999f, 0.3f));
    EXPECT_GT(glm::dot(forward, incoming), 0.999f);
    const vec3 backward = openpbr::openpbr_henyey_greenstein_sample(-0.999f, incoming, vec2(0.001f, 0.3f));
    EXPECT_LT(glm::dot(backward, incoming), -0.999f);
    const vec3 isotropic = openpbr::openpbr_isotropic_phase_sample(vec2(0.5f, 0.25f));
    EXPECT_NEAR(glm::length(isotropic), 1.0f, 1e-6f);
}

// ---------------------------------------------------------------------------------------------
// Distance sampling

struct Accumulator
{
    double sum = 0.0;
    double sum_squares = 0.0;
    void add(double x)
    {
        sum += x;
        sum_squares += x * x;
    }
    double mean(int n) const { return sum / n; }
    double standard_error(int n) const
    {
        const double m = mean(n);
        return std::sqrt(std::max(sum_squares / n - m * m, 0.0) / n);
    }
};

// Runs the sampler n times and checks, per channel with positive throughput, that the
// estimators of (a) transmittance over t_max, (b) the probability of scattering before t_max
// weighted by albedo, integral_0^L T(t) sigma_s dt = alpha (1 - e^{-sigma L}), and (c) the
// first moment integral_0^L t T(t) sigma_s dt match the analytic values within 5 standard errors.
void check_distance_sampler_unbiased(const OpenPBR_HomogeneousVolume& volume, const vec3& throughput, float t_max,
                                     uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const int n = 1000000;
    Accumulator pass[3], scatter[3], moment[3];
    for (int i = 0; i < n; ++i)
    {
        const OpenPBR_VolumeDistanceSample sampled =
            openpbr::openpbr_volume_sample_distance(volume, throughput, t_max, uniform(rng), uniform(rng));
        ASSERT_TRUE(finite(sampled.weight));
        ASSERT_GE(sampled.distance, 0.0f);
        ASSERT_LE(sampled.distance, std::min(t_max, std::numeric_limits<float>::max()));
        // The returned pdf is the one openpbr_volume_distance_pdf reports.
        ASSERT_NEAR(sampled.pdf,
                    openpbr::openpbr_volume_distance_pdf(volume, throughput, sampled.distance, sampled.scattered),
                    1e-6f * sampled.pdf);
        for (int c = 0; c < 3; ++c)
        {
            const double w = channel(sampled.weight, c);
            pass[c].add(sampled.scattered ? 0.0 : w);
            scatter[c].add(sampled.scattered ? w : 0.0);
            moment[c].add(sampled.scattered ? w * sampled.distance : 0.0);
        }
    }
    for (int c = 0; c < 3; ++c)
    {
        if (!(channel(throughput, c) > 0.0f))
        {
            continue;
        }
        const double sigma = channel(volume.extinction, c);
        const double sigma_s = sigma * channel(volume.albedo, c);
        const double length = std::isinf(t_max) ? 1e30 : double(t_max);
        const double transmittance = std::exp(-sigma * length);
        const double expected_scatter = sigma > 0.0 ? sigma_s / sigma * (1.0 - transmittance) : 0.0;
        const double expected_moment =
            sigma > 0.0 ? sigma_s / (sigma * sigma) * (1.0 - transmittance * (1.0 + sigma * length)) : 0.0;
        EXPECT_NEAR(pass[c].mean(n), transmittance, 5.0 * pass[c].standard_error(n) + 1e-6) << "channel " << c;
        EXPECT_NEAR(scatter[c].mean(n), expected_scatter, 5.0 * scatter[c].standard_error(n) + 1e-6) << "channel " << c;
        EXPECT_NEAR(moment[c].mean(n), expected_moment, 5.0 * moment[c].standard_error(n) + 1e-6) << "channel " << c;
        // The test must have power: errors well below the quantities measured.
        EXPECT_LT(scatter[c].standard_error(n), 0.01);
    }
}

TEST(VolumeDistanceSampling, UnbiasedChromaticFiniteSegment)
{
    const OpenPBR_HomogeneousVolume volume = make_test_volume(vec3(0.5f, 2.0f, 8.0f), vec3(0.9f, 0.5f, 0.99f), 0.0f);
    check_distance_sampler_unbiased(volume, vec3(0.2f, 1.0f, 0.5f), 0.7f, 1u);
    check_distance_sampler_unbiased(volume, vec3(1.0f), 0.05f, 2u);
    check_distance_sampler_unbiased(volume, vec3(1.0f), 3.0f, 3u);
}

TEST(VolumeDistanceSampling, UnbiasedInfiniteSegmentAndZeroThroughputChannel)
{
    const OpenPBR_HomogeneousVolume volume = make_test_volume(vec3(1.0f, 3.0f, 0.2f), vec3(0.3f, 0.8f, 1.0f), 0.0f);
    check_distance_sampler_unbiased(volume, vec3(1.0f, 0.7f, 0.4f), kInfinity, 4u);
    // Channel y gets no samples of its own; x and z still cover every distance, so all three
    // channels stay unbiased (checked for x and z, whose throughput is positive).
    check_distance_sampler_unbiased(volume, vec3(1.0f, 0.0f, 0.5f), 1.5f, 5u);
}

TEST(VolumeDistanceSampling, UnbiasedWithVacuumChannel)
{
    // A translucent medium with a white channel and no scatter in it: sigma_t.x = 0.
    const OpenPBR_HomogeneousVolume volume =
        openpbr::openpbr_make_volume(translucent_inputs(vec3(1.0f, 0.3f, 0.05f), 1.0f, vec3(0.0f, 0.2f, 0.5f), 0.0f));
    ASSERT_TRUE(volume.is_present);
    ASSERT_EQ(volume.extinction.x, 0.0f);
    check_distance_sampler_unbiased(volume, vec3(1.0f), 2.0f, 6u);
}

TEST(VolumeDistanceSampling, AbsentMediumPassesThrough)
{
    const OpenPBR_HomogeneousVolume none = openpbr::openpbr_make_empty_volume();
    const OpenPBR_VolumeDistanceSample sampled = openpbr::openpbr_volume_sample_distance(none, vec3(1.0f), 5.0f, 0.3f, 0.9f);
    EXPECT_FALSE(sampled.scattered);
    EXPECT_EQ(sampled.distance, 5.0f);
    EXPECT_EQ(sampled.weight, vec3(1.0f));
    EXPECT_EQ(openpbr::openpbr_volume_transmittance(none, 1e30f), vec3(1.0f));
}

TEST(VolumeDistanceSampling, GrayMediumWeightIsAlbedo)
{
    // Equal extinction in all channels: the MIS pdf is the plain exponential, so the scatter
    // weight is exactly the albedo and the pass-through weight exactly 1.
    const OpenPBR_HomogeneousVolume volume = make_test_volume(vec3(2.0f), vec3(0.9f, 0.5f, 0.1f), 0.0f);
    const OpenPBR_VolumeDistanceSample scattered =
        openpbr::openpbr_volume_sample_distance(volume, vec3(1.0f), 10.0f, 0.4f, 0.5f);
    ASSERT_TRUE(scattered.scattered);
    EXPECT_NEAR(scattered.distance, std::log(2.0f) / 2.0f, 1e-6f);
    EXPECT_NEAR(scattered.weight.x, 0.9f, 1e-5f);
    EXPECT_NEAR(scattered.weight.z, 0.1f, 1e-5f);
    const OpenPBR_VolumeDistanceSample passed =
        openpbr::openpbr_volume_sample_distance(volume, vec3(1.0f), 0.1f, 0.4f, 0.5f);
    ASSERT_FALSE(passed.scattered);
    EXPECT_NEAR(passed.weight.y, 1.0f, 1e-5f);
    EXPECT_NEAR(passed.pdf, std::exp(-0.2f), 1e-6f);

    // A flight of optical depth ~69 in a very thin medium: the absolute pdf (1e-18 * 1e-30)
    // underflows, the weight must not.
    const OpenPBR_HomogeneousVolume thin = make_test_volume(vec3(1e-18f), vec3(0.5f), 0.0f);
    const OpenPBR_VolumeDistanceSample far = openpbr::openpbr_volume_sample_distance(thin, vec3(1.0f), 1e30f, 0.5f, 1.0f);
    ASSERT_TRUE(far.scattered);
    EXPECT_NEAR(far.distance, 69.0776f / 1e-18f, 1e-5f * far.distance);
    EXPECT_NEAR(far.weight.x, 0.5f, 1e-5f);
}

// ---------------------------------------------------------------------------------------------
// Robustness

void check_volume_sane(const OpenPBR_HomogeneousVolume& volume)
{
    for (int c = 0; c < 3; ++c)
    {
        ASSERT_TRUE(finite(channel(volume.extinction, c)));
        ASSERT_GE(channel(volume.extinction, c), 0.0f);
        ASSERT_LE(channel(volume.extinction, c), OPENPBR_VOLUME_EXTINCTION_MAX);
        ASSERT_GE(channel(volume.albedo, c), 0.0f);
        ASSERT_LE(channel(volume.albedo, c), 1.0f);
    }
    ASSERT_GE(volume.anisotropy, -OPENPBR_HG_ANISOTROPY_MAX);
    ASSERT_LE(volume.anisotropy, OPENPBR_HG_ANISOTROPY_MAX);
    if (!volume.is_present)
    {
        ASSERT_EQ(volume.extinction, vec3(0.0f));
        ASSERT_EQ(volume.albedo, vec3(0.0f));
    }
    const float t_values[] = {0.0f,      kDenormal,
                              1e-30f,    1e-3f,
                              1.0f,      1e6f,
                              1e30f,     std::numeric_limits<float>::max(),
                              kInfinity, std::numeric_limits<float>::quiet_NaN()};
    const vec3 throughputs[] = {vec3(1.0f),
                                vec3(0.0f),
                                vec3(1.0f, 0.0f, 0.0f),
                                vec3(0.0f, 0.0f, 1e-3f),
                                vec3(kDenormal, 1.0f, kDenormal),
                                vec3(3e38f),
                                vec3(-1.0f, 0.5f, 0.0f)};
    const float u_values[] = {0.0f, 1e-7f, 0.5f, 0.99999994f, 1.0f};
    for (const float t_max : t_values)
    {
        const vec3 transmittance = openpbr::openpbr_volume_transmittance(volume, t_max);
        ASSERT_TRUE(finite(transmittance));
        ASSERT_GE(glm::min(transmittance.x, glm::min(transmittance.y, transmittance.z)), 0.0f);
        ASSERT_LE(glm::max(transmittance.x, glm::max(transmittance.y, transmittance.z)), 1.0f);
        for (const vec3& throughput : throughputs)
        {
            for (const float u_channel : u_values)
            {
                for (const float u_distance : u_values)
                {
                    const OpenPBR_VolumeDistanceSample sampled =
                        openpbr::openpbr_volume_sample_distance(volume, throughput, t_max, u_channel, u_distance);
                    ASSERT_TRUE(finite(sampled.weight)) << "t_max " << t_max;
                    ASSERT_GE(glm::min(sampled.weight.x, glm::min(sampled.weight.y, sampled.weight.z)), 0.0f);
                    ASSERT_TRUE(finite(sampled.distance));
                    ASSERT_GE(sampled.distance, 0.0f);
                    ASSERT_TRUE(finite(sampled.pdf));
                    ASSERT_GE(sampled.pdf, 0.0f);
                    ASSERT_LE(sampled.distance, openpbr::openpbr_volume_clamp_distance(t_max));
                    // A scattering event needs a channel with positive throughput share.
                    ASSERT_TRUE(!sampled.scattered || openpbr::openpbr_max3(sampled.weight) > 0.0f ||
                                openpbr::openpbr_max3(volume.albedo) == 0.0f)
                        << "t_max " << t_max << " throughput " << throughput.x << " " << throughput.y << " " << throughput.z
                        << " u " << u_channel << " " << u_distance;
                }
            }
        }
    }
}

TEST(VolumeRobustness, ExtremeInputsNeverProduceNanOrOutOfRange)
{
    const float depths[] = {0.0f, kDenormal, 1.17549435e-38f, 1e-30f, 1e-6f, 1.0f, 1e6f, OPENPBR_LENGTH_MAX};
    const vec3 colors[] = {vec3(0.0f), vec3(1.0f), vec3(kDenormal), vec3(0.0f, 0.5f, 1.0f),
                           vec3(1.0f, kDenormal, 0.999999f)};
    const float radii[] = {0.0f, kDenormal, 1e-20f, 1.0f, OPENPBR_LENGTH_MAX};
    const vec3 scales[] = {vec3(0.0f), vec3(1.0f), vec3(1.0f, 0.5f, 0.25f), vec3(kDenormal, 1e-30f, 1.0f)};
    const float anisotropies[] = {-1.0f, -0.999f, 0.0f, 0.5f, 1.0f};
    const float weights[] = {0.0f, kDenormal, 0.5f, 1.0f};
    int present = 0;
    for (const float depth : depths)
        for (const vec3& color : colors)
            for (const float radius : radii)
                for (const vec3& scale : scales)
                    for (const float g : anisotropies)
                        for (const float weight : weights)
                        {
                            OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
                            inputs.transmission_weight = weight;
                            inputs.transmission_color = color;
                            inputs.transmission_depth = depth;
                            inputs.transmission_scatter = vec3(1.0f) - color;
                            inputs.transmission_scatter_anisotropy = g;
                            inputs.subsurface_weight = 1.0f - weight;
                            inputs.subsurface_color = color;
                            inputs.subsurface_radius = radius;
                            inputs.subsurface_radius_scale = scale;
                            inputs.subsurface_scatter_anisotropy = -g;
                            const OpenPBR_HomogeneousVolume volume = openpbr::openpbr_make_volume(inputs);
                            present += volume.is_present ? 1 : 0;
                            // The sampler sweep is expensive: run it on a subset.
                            if (radius == 0.0f || radius == OPENPBR_LENGTH_MAX || depth == kDenormal)
                            {
                                check_volume_sane(volume);
                            }
                            else
                            {
                                ASSERT_TRUE(finite(volume.extinction) && finite(volume.albedo));
                                ASSERT_GE(glm::min(volume.albedo.x, glm::min(volume.albedo.y, volume.albedo.z)), 0.0f);
                                ASSERT_LE(glm::max(volume.albedo.x, glm::max(volume.albedo.y, volume.albedo.z)), 1.0f);
                            }
                            ASSERT_FALSE(HasFatalFailure());
                        }
    EXPECT_GT(present, 0);
}

TEST(VolumeRobustness, NonFiniteInputsThroughTheContract)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    inputs.transmission_weight = 0.5f;
    inputs.transmission_depth = kInfinity;
    inputs.transmission_color = vec3(nan, 0.0f, kInfinity);
    inputs.subsurface_weight = 1.0f;
    inputs.subsurface_radius = nan;
    inputs.subsurface_scatter_anisotropy = nan;
    const OpenPBR_HomogeneousVolume volume = openpbr::openpbr_make_volume(openpbr::openpbr_apply_input_contract(inputs));
    check_volume_sane(volume);
    // Even without the contract the medium stays finite.
    check_volume_sane(openpbr::openpbr_make_volume(inputs));
}

TEST(VolumeRobustness, PhaseFunctionExtremes)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const float g : {-1.0f, -0.999f, 0.0f, 0.999f, 1.0f, nan, -kInfinity})
    {
        for (const float c : {-1.0f, -0.5f, 0.0f, 1.0f, 1.5f, nan})
        {
            const float value = openpbr::openpbr_henyey_greenstein_eval(g, c);
            ASSERT_TRUE(finite(value));
            ASSERT_GT(value, 0.0f);
        }
        for (const float u : {0.0f, 1e-7f, 0.5f, 0.99999994f, 1.0f})
        {
            const vec3 direction = openpbr::openpbr_henyey_greenstein_sample(g, vec3(0.0f, 0.0f, -1.0f), vec2(u, u));
            ASSERT_TRUE(finite(direction));
            ASSERT_NEAR(glm::length(direction), 1.0f, 1e-5f);
        }
    }
}

}  // namespace
