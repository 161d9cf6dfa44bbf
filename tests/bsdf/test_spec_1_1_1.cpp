// What OpenPBR 1.1.1 states that an implementation must do (docs/spec-notes.md, "OpenPBR
// 1.1.1"), tested on the CPU build: emission_color is an HDR multiplier, the metal's
// specular_weight multiplies its whole lobe once (the edge tint is specular_color alone),
// thin-walled subsurface ignores subsurface_radius and subsurface_radius_scale; and the working
// space's luminance weights against the published ones. The GPU paths see the same materials in
// conformance (host/checks/conformance.cpp, conformance_materials). Built once per working space
// (test_spec_1_1_1: ACEScg, the default; test_bsdf_lin_rec709: linear Rec.709).
#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/openpbr.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

using namespace openpbr;

// Relative luminance weights as published: the Y row of RGB -> XYZ. ACEScg: the ACES AP1 ->
// XYZ matrix (S-2014-004, ten digits); the generated weights carry seven significant digits,
// measured 3.7e-8 off. Rec.709: ITU-R BT.709 / IEC 61966-2-1, four decimals (5e-5 each),
// measured 3.9e-5 off.
#if OPENPBR_WORKING_SPACE == OPENPBR_WORKING_SPACE_ACESCG
const glm::dvec3 published_luminance(0.2722287168, 0.6740817658, 0.0536895174);
constexpr double published_luminance_tolerance = 1e-7;
#else
const glm::dvec3 published_luminance(0.2126, 0.7152, 0.0722);
constexpr double published_luminance_tolerance = 5e-5;
#endif

TEST(Spec111, LuminanceWeightsAreTheWorkingSpacesY)
{
    const glm::vec3 weights = OPENPBR_WORKING_SPACE_LUMINANCE_WEIGHTS;
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(weights[c], published_luminance[c], published_luminance_tolerance) << "channel " << c;
    }
    // White has luminance 1 (to float rounding of the three weights: measured exactly 1 in both spaces).
    EXPECT_NEAR(openpbr_luminance(glm::vec3(1.0f)), 1.0f, 2e-7f);
}

// Spec "Emission" (1.1.1): emission_color in [0, inf)^3, "may exceed 1, in order to be able to
// plug in an HDR texture"; the emission is emission_color x emission_luminance.
TEST(Spec111, HdrEmissionColourIsKept)
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.emission_color = glm::vec3(4.0f, 2.0f, 1.0f);
    inputs.emission_luminance = 100.0f;
    const glm::vec3 view(0.0f, 0.0f, 1.0f);
    EXPECT_EQ(openpbr_prepare_emission(inputs, view), glm::vec3(400.0f, 200.0f, 100.0f));
    EXPECT_EQ(openpbr_prepare(inputs, view).emission, glm::vec3(400.0f, 200.0f, 100.0f));
    // The luminance of the emission is emission_luminance times the colour's luminance: 100 nits
    // for white (the spec's definition of emission_luminance), Y(4, 2, 1) x 100 for the HDR colour.
    const double hdr_luminance =
        100.0 * (4.0 * published_luminance.x + 2.0 * published_luminance.y + 1.0 * published_luminance.z);
    // Relative 1e-4: against the Rec.709 weights' four published decimals, measured 3.7e-5; ACEScg 3.8e-8.
    EXPECT_NEAR(openpbr_luminance(openpbr_prepare_emission(inputs, view)), hdr_luminance, 1e-4 * hdr_luminance);
    inputs.emission_color = glm::vec3(1.0f);
    EXPECT_NEAR(openpbr_luminance(openpbr_prepare_emission(inputs, view)), 100.0f, 100.0f * 2e-7f);  // measured exact
    // Only negative values are clamped (to 0), and NaN falls back to the default white.
    inputs.emission_color = glm::vec3(-1.0f, 1e6f, std::nanf(""));
    EXPECT_EQ(openpbr_prepare_emission(inputs, view), glm::vec3(0.0f, 1e8f, 100.0f));
}

OpenPBR_ResolvedInputs tinted_metal(float specular_weight)
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.base_metalness = 1.0f;
    inputs.base_color = glm::vec3(0.95f, 0.64f, 0.54f);
    inputs.specular_color = glm::vec3(0.4f, 0.7f, 1.0f);  // F82 edge tint
    inputs.specular_roughness = 0.35f;
    inputs.specular_weight = specular_weight;
    return inputs;
}

// Spec "Metal" (1.1.1): F(mu_bar) = specular_color x F_Schlick(mu_bar) at mu_bar = 1/7 is the
// edge tint, and F_metal = specular_weight x F82: the weight multiplies the whole lobe once and
// does not enter the edge tint (the 1.1 reference graph applied it to the edge colour too).
TEST(Spec111, MetalWeightMultipliesTheWholeLobeOnce)
{
    const OpenPBR_ResolvedInputs full = tinted_metal(1.0f);
    const glm::vec3 f0 = full.base_color;
    const float mu_bar = 1.0f / 7.0f;
    const glm::vec3 schlick_at_mu_bar = f0 + (glm::vec3(1.0f) - f0) * std::pow(1.0f - mu_bar, 5.0f);
    for (const float weight : {1.0f, 0.7f, 0.25f})
    {
        const OpenPBR_Fresnel fresnel = openpbr_metal_fresnel(tinted_metal(weight), 1.0f);
        const glm::vec3 at_edge = openpbr_fresnel_evaluate(fresnel, mu_bar);
        const glm::vec3 at_normal = openpbr_fresnel_evaluate(fresnel, 1.0f);
        for (int c = 0; c < 3; ++c)
        {
            // Float rounding of the F82 polynomial: measured 4.4e-7 relative at the edge, exact at
            // normal incidence.
            const float edge = weight * full.specular_color[c] * schlick_at_mu_bar[c];
            EXPECT_NEAR(at_edge[c], edge, 1e-6f * edge) << weight;
            EXPECT_NEAR(at_normal[c], weight * f0[c], 1e-6f * weight * f0[c]) << weight;
        }
    }
    // The lobe's shape at weight w is the shape at weight 1, scaled by w: eval / w is the same
    // for every pair of directions (the edge tint does not move with the weight).
    const std::vector<glm::vec3> views = {{0.0f, 0.0f, 1.0f}, {0.6f, 0.0f, 0.8f}, {0.0f, 0.98f, 0.2f}, {0.995f, 0.0f, 0.1f}};
    for (const glm::vec3& view : views)
    {
        const OpenPBR_PreparedBsdf reference = openpbr_prepare(full, glm::normalize(view));
        for (const float weight : {0.7f, 0.25f})
        {
            const OpenPBR_PreparedBsdf weighted = openpbr_prepare(tinted_metal(weight), glm::normalize(view));
            for (int i = 0; i < 64; ++i)
            {
                const float phi = 0.1f + 6.283185f * float(i % 8) / 8.0f;
                const float cos_theta = 0.05f + 0.9f * float(i / 8) / 7.0f;
                const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
                const glm::vec3 light(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
                const glm::vec3 expected = openpbr_eval(reference, light).specular * weight;
                const glm::vec3 value = openpbr_eval(weighted, light).specular;
                for (int c = 0; c < 3; ++c)
                {
                    // Float rounding only: measured 1.9e-7 relative.
                    EXPECT_NEAR(value[c], expected[c], 1e-6f * expected[c] + 1e-12f)
                        << "weight " << weight << " view " << view.x << "," << view.z << " light " << i;
                }
            }
        }
    }
}

OpenPBR_ResolvedInputs thin_walled_subsurface(float radius, glm::vec3 radius_scale, bool thin_walled)
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.geometry_thin_walled = thin_walled;
    inputs.subsurface_weight = 0.7f;
    inputs.subsurface_color = glm::vec3(0.8f, 0.5f, 0.3f);
    inputs.subsurface_scatter_anisotropy = 0.3f;
    inputs.base_diffuse_roughness = 0.4f;
    inputs.subsurface_radius = radius;
    inputs.subsurface_radius_scale = radius_scale;
    return inputs;
}

// Everything a renderer reads of a prepared BSDF at a few views, lights and random numbers.
std::vector<float> outputs(const OpenPBR_ResolvedInputs& inputs)
{
    std::vector<float> values;
    const std::vector<glm::vec3> directions = {
        {0.0f, 0.0f, 1.0f}, {0.6f, 0.0f, 0.8f}, {0.0f, -0.9f, 0.436f}, {0.3f, 0.4f, -0.866f}, {-0.8f, 0.0f, -0.6f}};
    for (const glm::vec3& view : directions)
    {
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
        const OpenPBR_HomogeneousVolume volume = openpbr_prepare_volume(inputs);
        values.insert(values.end(), {volume.extinction.x, volume.extinction.y, volume.extinction.z, volume.albedo.x,
                                     volume.albedo.y, volume.albedo.z, volume.is_present ? 1.0f : 0.0f});
        for (const glm::vec3& light : directions)
        {
            const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, light);
            values.insert(values.end(), {value.diffuse.x, value.diffuse.y, value.diffuse.z, value.specular.x,
                                         value.specular.y, value.specular.z, openpbr_pdf(bsdf, light)});
        }
        for (const glm::vec3& u : {glm::vec3(0.1f, 0.3f, 0.7f), glm::vec3(0.5f, 0.9f, 0.2f), glm::vec3(0.95f, 0.05f, 0.5f)})
        {
            const OpenPBR_BsdfSample sample = openpbr_sample(bsdf, u);
            values.insert(values.end(), {sample.direction.x, sample.direction.y, sample.direction.z, sample.weight.diffuse.x,
                                         sample.weight.specular.y, sample.pdf, float(sample.lobe_type)});
        }
    }
    return values;
}

// Spec "Thin-walled mode" (1.1.1): "subsurface_radius and subsurface_radius_scale are ignored
// and have no effect, since the scattering MFP is infinitesimal".
TEST(Spec111, ThinWalledSubsurfaceIgnoresRadiusAndScale)
{
    const glm::vec3 default_scale(1.0f, 0.5f, 0.25f);
    const std::vector<float> reference = outputs(thin_walled_subsurface(1.0f, default_scale, true));
    const std::vector<glm::vec3> scales = {default_scale, glm::vec3(1.0f), glm::vec3(0.1f, 0.9f, 0.3f), glm::vec3(0.0f)};
    for (const float radius : {0.0f, 1e-3f, 1.0f, 5.0f, 1e18f})
    {
        for (const glm::vec3& scale : scales)
        {
            // Bit for bit: nothing of the thin-walled path reads either input.
            EXPECT_EQ(outputs(thin_walled_subsurface(radius, scale, true)), reference)
                << "radius " << radius << " scale " << scale.x << "," << scale.y << "," << scale.z;
        }
    }
    // The same material with an interior does depend on them (its subsurface medium).
    EXPECT_NE(outputs(thin_walled_subsurface(5.0f, glm::vec3(0.1f, 0.9f, 0.3f), false)),
              outputs(thin_walled_subsurface(1.0f, default_scale, false)));
}

}  // namespace
