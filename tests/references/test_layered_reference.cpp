// The layered ground truth (host/references/layered_reference.h): with one layer it is the
// single-interface references (the microsurface walk, the fuzz fit's simulation), white lossless
// stacks keep all energy, it is reciprocal, and layers of weight 0 (or invisible ones: an
// index-matched clear coat) change nothing. Tolerances are multiples of the standard errors the
// estimates report, measured in the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "host/references/layered_reference.h"
#include "host/tables/fuzz_fit.h"
#include "slang/openpbr.h"

namespace {

using openpbr::host::estimate_layered;
using openpbr::host::layered_bin_transfer;
using openpbr::host::layered_material_from_inputs;
using openpbr::host::LayeredEstimate;
using openpbr::host::LayeredGrid;
using openpbr::host::MicrosurfaceKind;
using openpbr::host::MicrosurfaceMaterial;

constexpr std::uint64_t quick_paths = 1u << 13;  // per estimate: 8192 paths, 10-100 ms each

openpbr::OpenPBR_ResolvedInputs defaults() { return openpbr::openpbr_make_default_resolved_inputs(); }

LayeredEstimate estimate(const openpbr::OpenPBR_ResolvedInputs& inputs, double mu, std::uint64_t paths = quick_paths,
                         std::uint64_t seed = 1)
{
    return estimate_layered(layered_material_from_inputs(inputs), mu, LayeredGrid{}, paths, seed);
}

// A rough F82 metal with the edge tint 1 is a Schlick conductor: per channel, the microsurface
// walk of that F0 (host/tables/microsurface.h). Measured: |difference| 0.2-2.1 combined standard
// errors (0.0006-0.0015) at cos 1 and 0.3; asserted within 4.
TEST(LayeredReference, MetalLayerIsTheMicrosurfaceWalk)
{
    auto inputs = defaults();
    inputs.base_metalness = 1.0f;
    inputs.base_color = glm::vec3(0.9f, 0.6f, 0.3f);
    inputs.specular_roughness = 0.6f;
    for (const double mu : {1.0, 0.3})
    {
        const LayeredEstimate layered = estimate(inputs, mu);
        for (int c = 0; c < 3; ++c)
        {
            MicrosurfaceMaterial material;
            material.kind = MicrosurfaceKind::conductor_schlick;
            material.alpha = 0.36;
            material.f0 = double(inputs.base_color[c]);
            const auto walk = openpbr::host::microsurface_albedo(material, mu, 0, quick_paths, 3);
            const double error = std::hypot(layered.albedo_error[std::size_t(c)], walk.reflected_error);
            EXPECT_NEAR(layered.albedo[std::size_t(c)], walk.reflected, 4.0 * error) << "mu " << mu << " channel " << c;
            EXPECT_EQ(layered.transmitted[std::size_t(c)], 0.0);
        }
    }
}

// A translucent base (no coat, no fuzz) is one rough dielectric interface: the walk's reflected
// and transmitted shares. Measured within 0.6 combined standard errors (0.003-0.005); asserted
// within 4.
TEST(LayeredReference, DielectricLayerIsTheMicrosurfaceWalk)
{
    auto inputs = defaults();
    inputs.transmission_weight = 1.0f;
    inputs.specular_roughness = 0.5f;
    for (const double mu : {1.0, 0.3})
    {
        const LayeredEstimate layered = estimate(inputs, mu);
        MicrosurfaceMaterial material;
        material.kind = MicrosurfaceKind::dielectric;
        material.alpha = 0.25;
        material.eta = 1.5;
        const auto walk = openpbr::host::microsurface_albedo(material, mu, 0, quick_paths, 3);
        EXPECT_NEAR(layered.reflected[1], walk.reflected,
                    4.0 * std::hypot(layered.reflected_error[1], walk.reflected_error));
        EXPECT_NEAR(layered.transmitted[1], walk.transmitted,
                    4.0 * std::hypot(layered.transmitted_error[1], walk.transmitted_error));
    }
}

// Fuzz over a black base (a metal of specular_weight 0) is the fuzz fit's own simulation
// (host/tables/fuzz_fit.h): its reflected fraction. Measured within 1.0 combined standard errors
// (0.002-0.007); asserted within 4.
TEST(LayeredReference, FuzzLayerIsTheFuzzFitSimulation)
{
    auto inputs = defaults();
    inputs.base_metalness = 1.0f;
    inputs.specular_weight = 0.0f;
    inputs.fuzz_weight = 1.0f;
    inputs.fuzz_roughness = 0.5f;
    for (const double mu : {1.0, 0.3})
    {
        const LayeredEstimate layered = estimate(inputs, mu);
        const auto simulation = openpbr::host::simulate_fuzz_layer(mu, openpbr::host::fuzz_cross_section_from_roughness(0.5),
                                                                   quick_paths, 4, 4, 7);
        const double p = simulation.reflected_fraction();
        const double simulation_error = std::sqrt(p * (1.0 - p) / double(quick_paths));
        EXPECT_NEAR(layered.reflected[1], p, 4.0 * std::hypot(layered.reflected_error[1], simulation_error));
    }
}

// White, non-absorbing stacks (spec "White furnace testing") lose nothing: every path leaves
// with weight 1 (no roulette: weights never fall) unless a weight varies by channel or by
// direction (the film's RGB Fresnel, the rough EON), so the albedo is 1 to rounding. Measured:
// 1 - albedo = 0 exactly (standard error 0) for the stacks without film or rough diffuse; within
// 0.6 standard errors (0.007) for the rough diffuse and within 2.1 (0.001) with a film; asserted
// within 1e-9 + 4 standard errors.
struct WhiteStack
{
    std::string name;
    void (*configure)(openpbr::OpenPBR_ResolvedInputs&);
};

class WhiteStacks : public testing::TestWithParam<WhiteStack>
{
};

TEST_P(WhiteStacks, ConserveEnergy)
{
    auto inputs = defaults();
    inputs.base_color = glm::vec3(1.0f);
    GetParam().configure(inputs);
    for (const double mu : {1.0, 0.4, 0.1})
    {
        const LayeredEstimate layered = estimate(inputs, mu);
        EXPECT_EQ(layered.capped, 0u);
        for (int c = 0; c < 3; ++c)
        {
            EXPECT_NEAR(layered.albedo[std::size_t(c)], 1.0, 1e-9 + 4.0 * layered.albedo_error[std::size_t(c)])
                << "mu " << mu << " channel " << c;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Furnace, WhiteStacks,
                         testing::Values(WhiteStack{"coat_over_metal",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.base_metalness = 1.0f;
                                                        in.specular_roughness = 0.8f;
                                                        in.coat_weight = 1.0f;
                                                        in.coat_roughness = 0.5f;
                                                    }},
                                         WhiteStack{"fuzz_coat_film_over_glossy_diffuse",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.specular_roughness = 0.4f;
                                                        in.coat_weight = 1.0f;
                                                        in.coat_roughness = 0.2f;
                                                        in.fuzz_weight = 1.0f;
                                                        in.thin_film_weight = 1.0f;
                                                    }},
                                         WhiteStack{"rough_diffuse_half_coat",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.base_diffuse_roughness = 1.0f;
                                                        in.coat_weight = 0.5f;
                                                    }},
                                         WhiteStack{"coated_rough_glass",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.transmission_weight = 1.0f;
                                                        in.specular_roughness = 0.6f;
                                                        in.coat_weight = 1.0f;
                                                        in.coat_ior = 1.3f;
                                                    }},
                                         WhiteStack{"thin_walled_glass_with_film",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.transmission_weight = 1.0f;
                                                        in.specular_roughness = 0.3f;
                                                        in.thin_film_weight = 1.0f;
                                                        in.geometry_thin_walled = true;
                                                    }},
                                         WhiteStack{"thin_walled_subsurface_under_fuzz",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.subsurface_weight = 1.0f;
                                                        in.subsurface_color = glm::vec3(1.0f);
                                                        in.fuzz_weight = 1.0f;
                                                        in.geometry_thin_walled = true;
                                                    }},
                                         WhiteStack{"half_opaque_metal",
                                                    [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                        in.base_metalness = 1.0f;
                                                        in.geometry_opacity = 0.5f;
                                                    }}),
                         [](const testing::TestParamInfo<WhiteStack>& info) { return info.param.name; });

// Reciprocity: Q(a -> b) = Q(b -> a) for the integral of f cos cos over view bin a and light bin
// b (a 2 x 2 grid: quarter hemispheres, one per quadrant of azimuth), for absorbing, coloured
// stacks. Measured |difference| at most 2.1 combined standard errors (which are 1-11 % of Q);
// asserted within 4.
struct ReciprocityCase
{
    std::string name;
    void (*configure)(openpbr::OpenPBR_ResolvedInputs&);
};

class Reciprocity : public testing::TestWithParam<ReciprocityCase>
{
};

TEST_P(Reciprocity, SwappedBinsAgree)
{
    auto inputs = defaults();
    GetParam().configure(inputs);
    const auto material = layered_material_from_inputs(inputs);
    LayeredGrid grid;
    grid.resolution = 2;
    for (const auto& [a, b] : {std::pair{0, 3}, std::pair{1, 2}, std::pair{0, 1}})
    {
        const auto forward = layered_bin_transfer(material, grid, a, b, quick_paths, 5);
        const auto backward = layered_bin_transfer(material, grid, b, a, quick_paths, 6);
        for (std::size_t c = 0; c < 3; ++c)
        {
            EXPECT_GT(forward[0][c], 0.0);
            EXPECT_NEAR(forward[0][c], backward[0][c], 4.0 * std::hypot(forward[1][c], backward[1][c]))
                << "bins " << a << " <-> " << b << " channel " << c;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Stacks, Reciprocity,
                         testing::Values(ReciprocityCase{"tinted_coat_over_diffuse",
                                                         [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                             in.base_color = glm::vec3(0.9f, 0.5f, 0.2f);
                                                             in.specular_roughness = 0.5f;
                                                             in.coat_weight = 1.0f;
                                                             in.coat_roughness = 0.3f;
                                                             in.coat_color = glm::vec3(0.7f, 0.9f, 0.5f);
                                                         }},
                                         ReciprocityCase{"fuzz_over_coated_metal",
                                                         [](openpbr::OpenPBR_ResolvedInputs& in) {
                                                             in.base_metalness = 1.0f;
                                                             in.base_color = glm::vec3(0.9f, 0.6f, 0.3f);
                                                             in.specular_roughness = 0.4f;
                                                             in.coat_weight = 1.0f;
                                                             in.coat_roughness = 0.6f;
                                                             in.fuzz_weight = 1.0f;
                                                             in.fuzz_roughness = 0.7f;
                                                         }}),
                         [](const testing::TestParamInfo<ReciprocityCase>& info) { return info.param.name; });

// The grid's bins: every direction of a bin maps back to it, and uniform directions fill the
// bins equally (equal solid angle). Measured: the largest deviation of a bin's count from the
// mean 2.7 standard deviations over 162 bins (2^18 directions); asserted within 4.5.
TEST(LayeredGrid, BinsRoundTripAndHaveEqualSolidAngle)
{
    const LayeredGrid grid;
    openpbr::host::SplitMix64 random{42};
    for (int bin = 0; bin < grid.bin_count(); ++bin)
    {
        for (int k = 0; k < 8; ++k)
        {
            const glm::dvec3 d = grid.bin_direction(bin, random.next_double(), random.next_double());
            EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
            EXPECT_EQ(grid.bin_of(d), bin);
        }
    }
    EXPECT_EQ(grid.bin_of(glm::dvec3(0.0, 0.0, 1.0)), 4 * 9 + 4);  // the normal: the middle cell
    std::vector<double> counts(std::size_t(grid.bin_count()), 0.0);
    const int samples = 1 << 18;
    for (int s = 0; s < samples; ++s)
    {
        const double z = 2.0 * random.next_double() - 1.0;
        const double phi = 2.0 * 3.14159265358979323846 * random.next_double();
        const double r = std::sqrt(1.0 - z * z);
        counts[std::size_t(grid.bin_of(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z)))] += 1.0;
    }
    const double expected = double(samples) / grid.bin_count();
    for (const double count : counts)
    {
        EXPECT_NEAR(count, expected, 4.5 * std::sqrt(expected));
    }
}

// A coat or fuzz of weight 0 is no layer at all: the estimate is the one of the material
// without it, whatever its other parameters, bit for bit (same stacks, same seeds).
TEST(LayeredReference, WeightZeroLayersChangeNothing)
{
    auto plain = defaults();
    plain.specular_roughness = 0.4f;
    auto with_unused = plain;
    with_unused.coat_ior = 2.5f;
    with_unused.coat_color = glm::vec3(0.2f, 0.3f, 0.4f);
    with_unused.coat_roughness = 0.8f;
    with_unused.fuzz_color = glm::vec3(0.1f);
    with_unused.fuzz_roughness = 0.2f;
    const LayeredEstimate a = estimate(plain, 0.6);
    const LayeredEstimate b = estimate(with_unused, 0.6);
    for (std::size_t c = 0; c < 3; ++c)
    {
        EXPECT_EQ(a.albedo[c], b.albedo[c]);
    }
    for (std::size_t bin = 0; bin < a.bins.size(); ++bin)
    {
        EXPECT_EQ(a.bins[bin], b.bins[bin]);
    }
}

// A clear coat of IOR 1 (index-matched, non-absorbing) is physically invisible, at any weight
// and roughness: same albedo and bins as no coat within noise. Measured: albedo within 0.2
// combined standard errors (0.004), the largest bin difference 3.5 of its standard error over
// 162 bins; asserted within 4 (albedo) and 5 (each bin, 162 of them).
TEST(LayeredReference, IndexMatchedClearCoatIsInvisible)
{
    auto plain = defaults();
    plain.base_color = glm::vec3(0.7f, 0.5f, 0.3f);
    plain.specular_roughness = 0.4f;
    auto coated = plain;
    coated.coat_weight = 1.0f;
    coated.coat_ior = 1.0f;
    coated.coat_roughness = 0.7f;
    const LayeredEstimate a = estimate(plain, 0.5, quick_paths, 1);
    const LayeredEstimate b = estimate(coated, 0.5, quick_paths, 2);
    for (std::size_t c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(a.albedo[c], b.albedo[c], 4.0 * std::hypot(a.albedo_error[c], b.albedo_error[c]));
    }
    for (std::size_t bin = 0; bin < a.bins.size(); ++bin)
    {
        EXPECT_NEAR(a.bins[bin][1], b.bins[bin][1], 5.0 * std::hypot(a.bin_errors[bin][1], b.bin_errors[bin][1]) + 1e-12)
            << "bin " << bin;
    }
}

// An absorbing smooth coat (IOR 1.6, coat_color c) over a Lambertian of albedo rho under an
// interface of the same IOR (index-matched: specular_ior 1.6, so rho = base_color) has a closed
// form at normal incidence, the geometric series of the diffuse light's round trips:
//   R = F0 + (1 - F0) t(1) rho A / (1 - rho B),  t(mu) = c^(1 / (2 mu)) one pass at cosine mu,
//   A = <t (1 - F_in)>, B = <t^2 F_in> over cosine-weighted directions inside, F_in the Fresnel
//   factor from inside (total internal reflection beyond 38.7 degrees).
// Measured: 1.8 standard errors (0.0015, 2^15 paths) at c = 0.6, rho = 0.8 (R = 0.2436; the
// shipped model gives 0.374 there); within 0.5 at c = 1 and c = 0.4, rho = 0.5; asserted within 4.
TEST(LayeredReference, AbsorbingCoatOverLambertianMatchesTheGeometricSeries)
{
    for (const auto& [coat_color, base_rho] : {std::pair{0.6, 0.8}, std::pair{0.4, 0.5}})
    {
        const double color = coat_color;  // a copy the lambda below may capture (C++17)
        const double rho = base_rho;
        auto inputs = defaults();
        inputs.base_color = glm::vec3(float(rho));
        inputs.specular_ior = 1.6f;
        inputs.coat_weight = 1.0f;
        inputs.coat_ior = 1.6f;
        inputs.coat_roughness = 0.0f;
        inputs.coat_color = glm::vec3(float(color));
        const LayeredEstimate layered = estimate(inputs, 1.0);
        const double n = 1.6;
        const auto pass = [&](double mu) { return std::pow(color, 1.0 / (2.0 * mu)); };
        double a = 0.0;
        double b = 0.0;
        const int steps = 20000;
        for (int i = 0; i < steps; ++i)
        {
            const double mu = std::sqrt((i + 0.5) / steps);  // cosine-weighted: mu^2 uniform
            const double f_inside = openpbr::host::microsurface_fresnel_dielectric(mu, 1.0 / n);
            a += pass(mu) * (1.0 - f_inside) / steps;
            b += pass(mu) * pass(mu) * f_inside / steps;
        }
        const double f0 = openpbr::host::microsurface_fresnel_dielectric(1.0, n);
        const double expected = f0 + (1.0 - f0) * pass(1.0) * rho * a / (1.0 - rho * b);
        EXPECT_NEAR(layered.albedo[1], expected, 4.0 * layered.albedo_error[1]) << "coat colour " << color;
    }
}

// The glossy-diffuse calibration meets the spec's definition of base_color (eq.
// glossy_diffuse_albedo_constraint): at normal incidence and diffuse roughness 0 the albedo is
// E_spec + (1 - E_spec) C, with E_spec the interface's reflectance walked on its own.
// Measured within 1.1 combined standard errors (0.0012-0.0016); asserted within 4.
TEST(LayeredReference, GlossyDiffuseMeetsTheBaseColorDefinition)
{
    auto inputs = defaults();
    inputs.base_color = glm::vec3(0.8f, 0.4f, 0.1f);
    inputs.specular_roughness = 0.5f;
    const LayeredEstimate layered = estimate(inputs, 1.0, quick_paths * 4);
    MicrosurfaceMaterial interface;
    interface.kind = MicrosurfaceKind::dielectric;
    interface.alpha = 0.25;
    interface.eta = 1.5;
    const auto walk = openpbr::host::microsurface_albedo(interface, 1.0, 0, quick_paths * 4, 9);
    for (int c = 0; c < 3; ++c)
    {
        const double expected = walk.reflected + (1.0 - walk.reflected) * double(inputs.base_color[c]);
        EXPECT_NEAR(layered.albedo[std::size_t(c)], expected,
                    4.0 * std::hypot(layered.albedo_error[std::size_t(c)], walk.reflected_error))
            << "channel " << c;
    }
}

}  // namespace
