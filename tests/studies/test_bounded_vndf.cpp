// Bounded VNDF sampling (Eto & Tokuyoshi 2023, slang/math/openpbr_vndf.h): the reflected
// directions it draws follow openpbr_vndf_bounded_reflection_pdf (histogram against the
// integrated density), and the BSDF built with it (OPENPBR_VNDF_METHOD_BOUNDED, the accuracy
// study's variant) estimates the same albedo as the shipped sampler.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "host/scene/material_packing.h"
#include "host/studies/accuracy_variants.h"
#include "slang/openpbr.h"

namespace {

struct VndfCase
{
    float alpha;
    float mu;
};

class BoundedVndf : public testing::TestWithParam<VndfCase>
{
};

TEST_P(BoundedVndf, HistogramMatchesPdf)
{
    const VndfCase c = GetParam();
    const glm::vec3 view(std::sqrt(1.0f - c.mu * c.mu), 0.0f, c.mu);
    const glm::vec2 alpha(c.alpha);
    constexpr int z_bins = 10;
    constexpr int phi_bins = 16;
    constexpr int samples = 400000;
    std::vector<double> observed(z_bins * phi_bins, 0.0);
    std::mt19937 generator(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    int above = 0;
    for (int s = 0; s < samples; ++s)
    {
        const glm::vec3 h =
            openpbr::openpbr_sample_vndf_bounded(view, alpha, glm::vec2(uniform(generator), uniform(generator)));
        const glm::vec3 light = glm::reflect(-view, h);
        if (light.z <= 0.0f)
        {
            continue;
        }
        ++above;
        const float phi = std::atan2(light.y, light.x) + 3.14159265f;
        const int zi = std::min(int(light.z * z_bins), z_bins - 1);
        const int pi = std::min(int(phi / 6.2831853f * phi_bins), phi_bins - 1);
        observed[zi * phi_bins + pi] += 1.0;
    }
    // Expected counts: the density integrated over each bin (dz dphi is the solid angle).
    double total_probability = 0.0;
    constexpr int sub = 8;
    for (int zi = 0; zi < z_bins; ++zi)
    {
        for (int pi = 0; pi < phi_bins; ++pi)
        {
            double probability = 0.0;
            for (int a = 0; a < sub; ++a)
            {
                for (int b = 0; b < sub; ++b)
                {
                    const double z = (zi + (a + 0.5) / sub) / z_bins;
                    const double phi = (pi + (b + 0.5) / sub) / phi_bins * 6.283185307179586 - 3.141592653589793;
                    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                    const glm::vec3 light(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                    const glm::vec3 h = glm::normalize(view + light);
                    probability += openpbr::openpbr_vndf_bounded_reflection_pdf(view, h, alpha);
                }
            }
            probability *= (1.0 / z_bins) * (6.283185307179586 / phi_bins) / (sub * sub);
            total_probability += probability;
            const double expected = probability * samples;
            if (expected >= 50.0)
            {
                EXPECT_NEAR(observed[zi * phi_bins + pi], expected, 5.0 * std::sqrt(expected) + 0.03 * expected)
                    << "bin z " << zi << " phi " << pi;
            }
        }
    }
    // The density integrates to the fraction of samples reflected above the horizon.
    EXPECT_NEAR(total_probability, double(above) / samples, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Views, BoundedVndf,
                         testing::Values(VndfCase{0.3f, 0.9f}, VndfCase{0.3f, 0.2f}, VndfCase{0.7f, 0.5f},
                                         VndfCase{1.0f, 0.3f}),
                         [](const testing::TestParamInfo<VndfCase>& info) {
                             return "alpha" + std::to_string(int(info.param.alpha * 100)) + "_mu" +
                                    std::to_string(int(info.param.mu * 100));
                         });

// At alpha 1 the bound k is 0 and at alpha -> 0 it tends to 1 (Eto & Tokuyoshi 2023, eq. 5).
TEST(BoundedVndf, BoundLimits)
{
    const glm::vec3 view = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));
    EXPECT_NEAR(openpbr::openpbr_vndf_bounded_k(view, glm::vec2(1.0f)), 0.0f, 1e-6f);
    EXPECT_NEAR(openpbr::openpbr_vndf_bounded_k(view, glm::vec2(1e-4f)), 1.0f, 1e-6f);
}

// The BSDF sampled with bounded VNDF estimates the same albedo as with spherical caps: its
// lobes' pdf matches the sampler (a mismatch would bias every sample weight).
class BoundedBsdf : public testing::TestWithParam<VndfCase>
{
};

TEST_P(BoundedBsdf, AlbedoMatchesShippedSampler)
{
    const VndfCase c = GetParam();
    const std::vector<openpbr::host::BsdfVariant> variants = openpbr::host::bsdf_variants();
    const openpbr::host::BsdfVariant* bounded = nullptr;
    for (const auto& variant : variants)
    {
        if (variant.setting.find("bounded") != std::string::npos)
        {
            bounded = &variant;
        }
    }
    ASSERT_NE(bounded, nullptr);
    openpbr::host::Material material = openpbr::host::default_material();
    material.inputs.base_metalness = 1.0f;
    material.inputs.base_color = glm::vec3(0.9f);
    material.inputs.specular_roughness = std::sqrt(c.alpha);
    const std::vector<float> packed = openpbr::host::pack_materials({material});
    const std::uint32_t samples = 1u << 17;
    const auto reference = variants.front().albedo(packed.data(), c.mu, samples, 3);
    const auto tested = bounded->albedo(packed.data(), c.mu, samples, 4);
    const double error = std::sqrt((reference.variance + tested.variance) / samples);
    EXPECT_NEAR(tested.mean[0], reference.mean[0], 5.0 * error + 1e-4);
    // Bounded sampling wastes fewer samples below the horizon, so its variance is not larger.
    EXPECT_LE(tested.variance, reference.variance * 1.05 + 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Metal, BoundedBsdf,
                         testing::Values(VndfCase{0.2f, 0.3f}, VndfCase{0.5f, 0.2f}, VndfCase{0.8f, 0.6f}),
                         [](const testing::TestParamInfo<VndfCase>& info) {
                             return "alpha" + std::to_string(int(info.param.alpha * 100)) + "_mu" +
                                    std::to_string(int(info.param.mu * 100));
                         });

}  // namespace
