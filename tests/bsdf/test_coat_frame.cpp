// The coat frame follows the base frame unless the caller sets it (spec "Coat":
// geometry_coat_normal defaults to the geometry normal; slang/openpbr_input_contract.h).
// With random shading frames, a coated material that sets only geometry_basis must shade
// exactly like one that sets geometry_coat_basis to the same frame: both resolve the coat frame
// with the same arithmetic, so eval, pdf and samples are compared bit for bit. A coat that
// stayed at +z instead differed by up to ~1800x relative on these frames, which the last test
// checks is still detected.
#include "tests/bsdf/bsdf_statistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using namespace openpbr;
using openpbr::testing::RandomStream;

constexpr float kPiF = 3.14159265358979f;

glm::vec3 random_direction(RandomStream& rng)
{
    const float z = 1.0f - 2.0f * rng.next_float();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPiF * rng.next_float();
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// A coated material on a random shading frame; the coat's own parameters random too, with the
// range ends of weight and roughness among them.
OpenPBR_ResolvedInputs random_coated_material(RandomStream& rng, const OpenPBR_Basis& frame)
{
    OpenPBR_ResolvedInputs material = openpbr_make_default_resolved_inputs();
    material.base_color = glm::vec3(rng.next_float(), rng.next_float(), rng.next_float());
    material.base_metalness = rng.next_float() < 0.5f ? 0.0f : rng.next_float();
    material.specular_roughness = rng.next_float();
    const float weight_pick = rng.next_float();
    material.coat_weight = weight_pick < 0.2f ? 1.0f : 0.05f + 0.95f * rng.next_float();
    const float roughness_pick = rng.next_float();
    material.coat_roughness = roughness_pick < 0.2f ? 0.0f : rng.next_float();
    material.coat_roughness_anisotropy = rng.next_float() < 0.5f ? 0.0f : rng.next_float();
    material.coat_ior = 1.0f + rng.next_float();
    material.coat_color = glm::vec3(rng.next_float(), rng.next_float(), rng.next_float());
    material.geometry_basis = frame;
    return material;
}

struct Shading
{
    OpenPBR_DiffuseSpecular eval;
    float pdf;
    OpenPBR_BsdfSample bsdf_sample;
};

Shading shade(const OpenPBR_ResolvedInputs& material, const glm::vec3& view, const glm::vec3& light, const glm::vec3& u)
{
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(material, view);
    return {openpbr_eval(bsdf, light), openpbr_pdf(bsdf, light), openpbr_sample(bsdf, u)};
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) { return a == b; }

constexpr int kMaterialCount = 400;
constexpr int kQueriesPerMaterial = 16;

TEST(CoatFrame, FollowsBaseFrameWhenUnset)
{
    RandomStream rng(20261125, 3);
    int compared = 0;
    for (int material_index = 0; material_index < kMaterialCount; ++material_index)
    {
        const OpenPBR_Basis frame =
            openpbr_make_basis(random_direction(rng), random_direction(rng), rng.next_float() < 0.5f ? -1.0f : 1.0f);
        const OpenPBR_ResolvedInputs base_only = random_coated_material(rng, frame);
        OpenPBR_ResolvedInputs both = base_only;
        both.geometry_coat_basis = frame;
        for (int query = 0; query < kQueriesPerMaterial; ++query)
        {
            const glm::vec3 view = random_direction(rng);
            const glm::vec3 light = random_direction(rng);
            const glm::vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
            const Shading a = shade(base_only, view, light, u);
            const Shading b = shade(both, view, light, u);
            const std::string where = "material " + std::to_string(material_index) + " query " + std::to_string(query);
            EXPECT_TRUE(same_bits(a.eval.diffuse, b.eval.diffuse)) << where;
            EXPECT_TRUE(same_bits(a.eval.specular, b.eval.specular)) << where;
            EXPECT_EQ(a.pdf, b.pdf) << where;
            EXPECT_TRUE(same_bits(a.bsdf_sample.direction, b.bsdf_sample.direction)) << where;
            EXPECT_EQ(a.bsdf_sample.pdf, b.bsdf_sample.pdf) << where;
            EXPECT_EQ(a.bsdf_sample.lobe_type, b.bsdf_sample.lobe_type) << where;
            ++compared;
        }
    }
    EXPECT_EQ(compared, kMaterialCount * kQueriesPerMaterial);
}

// The comparison above can fail: a coat frame pinned at +z (the behaviour of a default that
// ignores geometry_basis) shades these materials differently.
TEST(CoatFrame, PinnedCoatFrameIsDetected)
{
    RandomStream rng(20261125, 5);
    int differing = 0;
    int compared = 0;
    for (int material_index = 0; material_index < 50; ++material_index)
    {
        const OpenPBR_Basis frame = openpbr_make_basis(random_direction(rng), random_direction(rng), 1.0f);
        OpenPBR_ResolvedInputs base_only = random_coated_material(rng, frame);
        base_only.coat_weight = 1.0f;
        base_only.coat_roughness = 0.3f;
        OpenPBR_ResolvedInputs pinned = base_only;
        pinned.geometry_coat_basis = openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
        for (int query = 0; query < 4; ++query)
        {
            const glm::vec3 view = random_direction(rng);
            const glm::vec3 light = random_direction(rng);
            const glm::vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
            const Shading a = shade(base_only, view, light, u);
            const Shading b = shade(pinned, view, light, u);
            differing += (a.eval.specular != b.eval.specular || a.pdf != b.pdf) ? 1 : 0;
            ++compared;
        }
    }
    // Most random frames are far from +z; a handful of queries see neither lobe (both zero).
    EXPECT_GT(differing, compared / 2);
}

}  // namespace
