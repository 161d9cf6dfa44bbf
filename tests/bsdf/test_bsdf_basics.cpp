// Basic invariants of the OpenPBR BSDF over random materials and directions, shading-frame
// construction, and opacity. Every parameter of OpenPBR_ResolvedInputs is randomized, so lobes
// added later (coat, fuzz, transmission, thin film, volumes) are covered without changes here.
#include "tests/bsdf/bsdf_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace openpbr;
using namespace openpbr::testing;

constexpr float kPiF = 3.14159265358979f;

// ------------------------------------------------------------------------------------------
// Random materials and directions

class RandomMaterials
{
  public:
    explicit RandomMaterials(std::uint64_t seed) : rng_(seed, 17) {}

    float uniform(float low, float high) { return low + (high - low) * rng_.next_float(); }
    glm::vec3 color() { return glm::vec3(rng_.next_float(), rng_.next_float(), rng_.next_float()); }
    // One of the range ends or a uniform value, so the extremes are hit often.
    float unit_with_ends()
    {
        const float pick = rng_.next_float();
        return pick < 0.2f ? 0.0f : (pick < 0.4f ? 1.0f : rng_.next_float());
    }

    glm::vec3 sphere_direction()
    {
        const float z = 1.0f - 2.0f * rng_.next_float();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 2.0f * kPiF * rng_.next_float();
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    }

    // A view over the full sphere around `normal`; sometimes exactly grazing or normal.
    glm::vec3 view_around(const glm::vec3& normal)
    {
        const float pick = rng_.next_float();
        if (pick < 0.05f)
        {
            const OpenPBR_Basis b = openpbr_make_basis(normal);
            return glm::normalize(b.tangent * std::cos(3.0f * pick * 100.0f) + b.bitangent * std::sin(3.0f * pick * 100.0f));
        }
        if (pick < 0.08f)
        {
            return glm::normalize(normal);
        }
        return sphere_direction();
    }

    float roughness()
    {
        const float pick = rng_.next_float();
        if (pick < 0.15f)
        {
            return 0.0f;
        }
        if (pick < 0.3f)
        {
            return uniform(0.02f, 0.06f);  // around the delta threshold (alpha 1e-3)
        }
        return rng_.next_float();
    }

    OpenPBR_ResolvedInputs material()
    {
        OpenPBR_ResolvedInputs i = openpbr_make_default_resolved_inputs();
        i.base_weight = unit_with_ends();
        i.base_color = color();
        i.base_diffuse_roughness = unit_with_ends();
        i.base_metalness = unit_with_ends();
        i.specular_weight = rng_.next_float() < 0.8f ? unit_with_ends() : uniform(1.0f, 5.0f);
        i.specular_color = color();
        i.specular_roughness = roughness();
        i.specular_roughness_anisotropy = rng_.next_float() < 0.5f ? 0.0f : unit_with_ends();
        i.specular_ior = rng_.next_float() < 0.7f ? uniform(1.0f, 3.0f) : uniform(1.0f / 3.0f, 1.0f);
        i.transmission_weight = unit_with_ends();
        i.transmission_color = color();
        i.transmission_depth = rng_.next_float() < 0.5f ? 0.0f : uniform(0.0f, 10.0f);
        i.transmission_scatter = color();
        i.transmission_scatter_anisotropy = uniform(-1.0f, 1.0f);
        i.transmission_dispersion_scale = rng_.next_float();
        i.transmission_dispersion_abbe_number = uniform(1.0f, 100.0f);
        i.subsurface_weight = unit_with_ends();
        i.subsurface_color = color();
        i.subsurface_radius = uniform(0.0f, 5.0f);
        i.subsurface_radius_scale = color();
        i.subsurface_scatter_anisotropy = uniform(-1.0f, 1.0f);
        i.fuzz_weight = unit_with_ends();
        i.fuzz_color = color();
        i.fuzz_roughness = unit_with_ends();
        i.coat_weight = unit_with_ends();
        i.coat_color = color();
        i.coat_roughness = roughness();
        i.coat_roughness_anisotropy = rng_.next_float() < 0.5f ? 0.0f : unit_with_ends();
        i.coat_ior = uniform(1.0f, 3.0f);
        i.coat_darkening = rng_.next_float();
        i.thin_film_weight = unit_with_ends();
        i.thin_film_thickness = uniform(0.0f, 2.0f);
        i.thin_film_ior = uniform(1.0f, 3.0f);
        i.emission_luminance = rng_.next_float() < 0.5f ? 0.0f : uniform(0.0f, 1000.0f);
        i.emission_color = color();
        i.geometry_opacity = unit_with_ends();
        i.geometry_thin_walled = rng_.next_float() < 0.3f;
        i.geometry_basis = random_basis();
        i.geometry_coat_basis = rng_.next_float() < 0.5f ? i.geometry_basis : random_basis();
        const float angle = uniform(0.0f, 2.0f * kPiF);
        i.specular_anisotropy_rotation = glm::vec2(std::cos(angle), std::sin(angle));
        const float coat_angle = uniform(0.0f, 2.0f * kPiF);
        i.coat_anisotropy_rotation = glm::vec2(std::cos(coat_angle), std::sin(coat_angle));
        return i;
    }

    // Unnormalized normal and tangent, random handedness through the bitangent.
    OpenPBR_Basis random_basis()
    {
        OpenPBR_Basis b;
        b.normal = sphere_direction() * uniform(0.5f, 2.0f);
        b.tangent = sphere_direction() * uniform(0.5f, 2.0f);
        b.bitangent = glm::cross(b.normal, b.tangent) * (rng_.next_float() < 0.5f ? -1.0f : 1.0f);
        return b;
    }

    RandomStream& rng() { return rng_; }

  private:
    RandomStream rng_;
};

bool finite_non_negative(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

// Checks one prepared BSDF: eval/pdf at random lights over the full sphere, and samples
// (pdf == 0 exactly for no sample, pdf > 0 otherwise, weight == eval / pdf, returned pdf ==
// openpbr_pdf). Returns an empty string or a description of the first problem.
std::string check_prepared(const OpenPBR_PreparedBsdf& bsdf, RandomMaterials& random, int light_count, int sample_count,
                           std::uint64_t seed, std::uint64_t* checked_count = nullptr)
{
    std::ostringstream problem;
    problem << std::setprecision(9);
    if (!finite_non_negative(bsdf.emission))
    {
        problem << "emission " << to_string(bsdf.emission);
        return problem.str();
    }
    for (int k = 0; k < light_count; ++k)
    {
        const glm::vec3 light = random.sphere_direction();
        const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, light);
        const float pdf = openpbr_pdf(bsdf, light);
        if (!finite_non_negative(value.diffuse) || !finite_non_negative(value.specular) || !std::isfinite(pdf) || pdf < 0.0f)
        {
            problem << "light " << to_string(light) << ": eval diffuse " << to_string(value.diffuse) << " specular "
                    << to_string(value.specular) << ", pdf " << pdf;
            return problem.str();
        }
    }
    ConsistencyOptions options;
    options.sample_count = static_cast<std::uint64_t>(sample_count);
    options.seed = seed;
    const ConsistencyResult result = check_sample_consistency(make_bsdf_target(bsdf), options);
    if (checked_count != nullptr)
    {
        *checked_count += result.checked_count;
    }
    if (!result.ok())
    {
        problem << result.weight_mismatch_count << " weight mismatches, " << result.pdf_mismatch_count << " pdf mismatches, "
                << result.invalid_value_count << " invalid samples (max relative errors: weight "
                << result.max_weight_relative_error << ", pdf " << result.max_pdf_relative_error
                << "); first: " << result.first_failure;
    }
    return problem.str();
}

TEST(BsdfBasics, RandomMaterialsGiveFiniteNonNegativeConsistentOutputs)
{
    RandomMaterials random(2024);
    int failures = 0;
    std::uint64_t checked = 0;  // samples whose weight and pdf were compared
    const int material_count = 20000;
    const int samples_per_material = 128;
    for (int m = 0; m < material_count && failures < 5; ++m)
    {
        const OpenPBR_ResolvedInputs inputs = random.material();
        const glm::vec3 view = random.view_around(inputs.geometry_basis.normal);
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
        const std::string problem =
            check_prepared(bsdf, random, 32, samples_per_material, static_cast<std::uint64_t>(m), &checked);
        if (!problem.empty())
        {
            ++failures;
            ADD_FAILURE() << "material " << m << ": " << describe_inputs(inputs) << "\n  view " << to_string(view) << "\n  "
                          << problem;
        }
    }
    // Most samples are continuous and above the comparison floors.
    EXPECT_GT(checked, std::uint64_t(material_count) * samples_per_material / 4);
}

// The input contract: NaN, infinities and out-of-range values must not produce NaN, negative
// values or infinities downstream.
TEST(BsdfBasics, InvalidInputsGiveFiniteNonNegativeOutputs)
{
    RandomMaterials random(77);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float bad_values[] = {nan, inf, -inf, -1.0f, 2.0f, 1e30f, -1e-30f};
    int failures = 0;
    for (int m = 0; m < 1500 && failures < 5; ++m)
    {
        OpenPBR_ResolvedInputs inputs = random.material();
        float* fields[] = {&inputs.base_weight,
                           &inputs.base_color.x,
                           &inputs.base_diffuse_roughness,
                           &inputs.base_metalness,
                           &inputs.specular_weight,
                           &inputs.specular_color.y,
                           &inputs.specular_roughness,
                           &inputs.specular_roughness_anisotropy,
                           &inputs.specular_ior,
                           &inputs.transmission_weight,
                           &inputs.transmission_depth,
                           &inputs.subsurface_weight,
                           &inputs.subsurface_radius,
                           &inputs.fuzz_weight,
                           &inputs.fuzz_roughness,
                           &inputs.coat_weight,
                           &inputs.coat_roughness,
                           &inputs.coat_ior,
                           &inputs.thin_film_weight,
                           &inputs.thin_film_thickness,
                           &inputs.emission_luminance,
                           &inputs.geometry_opacity,
                           &inputs.geometry_basis.tangent.x,
                           &inputs.specular_anisotropy_rotation.x};
        const int field_count = static_cast<int>(sizeof(fields) / sizeof(fields[0]));
        for (int k = 0; k < 3; ++k)
        {
            *fields[random.rng().next_uint() % static_cast<std::uint32_t>(field_count)] =
                bad_values[random.rng().next_uint() % 7u];
        }
        const glm::vec3 view = random.view_around(inputs.geometry_basis.normal);
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
        const std::string problem = check_prepared(bsdf, random, 16, 32, static_cast<std::uint64_t>(m));
        if (!problem.empty())
        {
            ++failures;
            ADD_FAILURE() << "material " << m << ": " << describe_inputs(inputs) << "\n  view " << to_string(view) << "\n  "
                          << problem;
        }
    }
}

// ------------------------------------------------------------------------------------------
// Opacity

TEST(BsdfBasics, ZeroOpacityIsOnlyThePassThroughDelta)
{
    RandomMaterials random(5);
    for (int m = 0; m < 200; ++m)
    {
        OpenPBR_ResolvedInputs inputs = random.material();
        inputs.geometry_opacity = 0.0f;
        const glm::vec3 view = random.view_around(inputs.geometry_basis.normal);
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
        SCOPED_TRACE("material " + std::to_string(m) + ": " + describe_inputs(inputs) + "\n  view " + to_string(view));
        EXPECT_EQ(bsdf.emission, glm::vec3(0.0f)) << "a fully transparent surface does not emit";
        for (int k = 0; k < 16; ++k)
        {
            const glm::vec3 light = random.sphere_direction();
            const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, light);
            EXPECT_EQ(value.diffuse, glm::vec3(0.0f));
            EXPECT_EQ(value.specular, glm::vec3(0.0f));
            EXPECT_EQ(openpbr_pdf(bsdf, light), 0.0f);

            const glm::vec3 u(random.rng().next_float(), random.rng().next_float(), random.rng().next_float());
            const OpenPBR_BsdfSample s = openpbr_sample(bsdf, u);
            EXPECT_EQ(s.lobe_type, openpbr_lobe_type(OPENPBR_LOBE_ID_PASS_THROUGH,
                                                     OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_SPECULAR));
            EXPECT_EQ(s.pdf, 1.0f);
            EXPECT_EQ(s.weight.diffuse, glm::vec3(0.0f));
            EXPECT_NEAR(s.weight.specular.x, 1.0f, 1e-6f);
            EXPECT_NEAR(s.weight.specular.y, 1.0f, 1e-6f);
            EXPECT_NEAR(s.weight.specular.z, 1.0f, 1e-6f);
            EXPECT_LT(glm::length(s.direction + glm::normalize(view)), 1e-5f)
                << "pass-through must continue straight: " << to_string(s.direction);
        }
    }
}

// ------------------------------------------------------------------------------------------
// Shading frames

// Orthonormal, and det(t, b, n) = expected_handedness.
void expect_orthonormal(const OpenPBR_Basis& b, float expected_handedness, const std::string& what)
{
    SCOPED_TRACE(what + ": t " + to_string(b.tangent) + ", b " + to_string(b.bitangent) + ", n " + to_string(b.normal));
    const glm::vec3 axes[3] = {b.tangent, b.bitangent, b.normal};
    for (int i = 0; i < 3; ++i)
    {
        ASSERT_TRUE(std::isfinite(axes[i].x) && std::isfinite(axes[i].y) && std::isfinite(axes[i].z)) << "axis " << i;
        EXPECT_NEAR(glm::length(axes[i]), 1.0f, 1e-5f) << "axis " << i;
        for (int j = i + 1; j < 3; ++j)
        {
            EXPECT_LT(std::fabs(glm::dot(axes[i], axes[j])), 1e-5f) << "axes " << i << ", " << j;
        }
    }
    EXPECT_NEAR(glm::dot(glm::cross(b.tangent, b.bitangent), b.normal), expected_handedness, 1e-5f);
}

void expect_same_basis(const OpenPBR_Basis& a, const OpenPBR_Basis& b, const std::string& what)
{
    SCOPED_TRACE(what);
    EXPECT_LT(glm::length(a.tangent - b.tangent), 1e-6f);
    EXPECT_LT(glm::length(a.bitangent - b.bitangent), 1e-6f);
    EXPECT_LT(glm::length(a.normal - b.normal), 1e-6f);
}

std::vector<glm::vec3> test_normals()
{
    std::vector<glm::vec3> normals = {
        {0.0f, 0.0f, 1.0f},   {0.0f, 0.0f, -1.0f},    {1.0f, 0.0f, 0.0f},     {0.0f, -1.0f, 0.0f},  {1e-4f, 2e-4f, -1.0f},
        {0.0f, 1e-7f, -1.0f}, {-1e-8f, 1e-8f, -1.0f}, {3e-4f, 0.0f, -1.0f},   {0.6f, 0.8f, -1e-8f}, {0.6f, 0.8f, 1e-8f},
        {0.6f, 0.8f, -0.0f},  {1e3f, -2e3f, 5e2f},    {1e-3f, 2e-3f, -3e-3f}, {0.3f, -0.2f, -0.93f}};
    RandomMaterials random(3);
    for (int i = 0; i < 2000; ++i)
    {
        normals.push_back(random.sphere_direction() * random.uniform(0.01f, 100.0f));
    }
    return normals;
}

TEST(BsdfBasis, FromNormalIsOrthonormalAndRightHanded)
{
    for (const glm::vec3& n : test_normals())
    {
        const OpenPBR_Basis b = openpbr_make_basis(n);
        expect_orthonormal(b, 1.0f, "normal " + to_string(n));
        EXPECT_GT(glm::dot(glm::dvec3(b.normal), glm::normalize(glm::dvec3(n))), 1.0 - 1e-6)
            << "the normal must be kept: " << to_string(n);
    }
    // Zero and non-finite normals fall back to +z.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const glm::vec3& n :
         {glm::vec3(0.0f), glm::vec3(nan, 0.0f, 1.0f), glm::vec3(std::numeric_limits<float>::infinity(), 0.0f, 0.0f)})
    {
        const OpenPBR_Basis b = openpbr_make_basis(n);
        expect_orthonormal(b, 1.0f, "degenerate normal " + to_string(n));
        EXPECT_EQ(b.normal, glm::vec3(0.0f, 0.0f, 1.0f));
    }
}

TEST(BsdfBasis, FromNormalAndTangentKeepsTheTangentAndHandedness)
{
    RandomMaterials random(4);
    for (const glm::vec3& n : test_normals())
    {
        const glm::vec3 t = random.sphere_direction() * random.uniform(0.01f, 100.0f);
        const glm::dvec3 nd = glm::normalize(glm::dvec3(n));
        const glm::dvec3 t_projected = glm::dvec3(t) - nd * glm::dot(nd, glm::dvec3(t));
        if (glm::length(t_projected) < 1e-2 * glm::length(glm::dvec3(t)))
        {
            continue;  // nearly parallel: covered below
        }
        for (float handedness : {1.0f, -1.0f})
        {
            const OpenPBR_Basis b = openpbr_make_basis(n, t, handedness);
            const std::string what =
                "n " + to_string(n) + ", t " + to_string(t) + ", handedness " + std::to_string(handedness);
            expect_orthonormal(b, handedness, what);
            EXPECT_GT(glm::dot(glm::dvec3(b.tangent), glm::normalize(t_projected)), 1.0 - 1e-5) << what;
            // The (n, t, b) overload takes only the side of the bitangent.
            const glm::vec3 bitangent = glm::cross(n, t) * handedness * random.uniform(0.1f, 10.0f);
            expect_same_basis(openpbr_make_basis(n, t, bitangent), b, what + " via bitangent");
        }
        // Handedness 0 is treated as +1.
        expect_same_basis(openpbr_make_basis(n, t, 0.0f), openpbr_make_basis(n, t, 1.0f), "handedness 0");
    }
}

TEST(BsdfBasis, DegenerateTangentsFallBackToTheNormalOnlyFrame)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (const glm::vec3& n : test_normals())
    {
        const glm::vec3 unit_n = glm::vec3(glm::normalize(glm::dvec3(n)));
        const glm::vec3 degenerate[] = {
            glm::vec3(0.0f),           unit_n, -3.0f * unit_n, 1e-20f * unit_n, glm::vec3(nan, 0.0f, 0.0f), glm::vec3(nan),
            glm::vec3(inf, 1.0f, 0.0f)};
        const OpenPBR_Basis fallback = openpbr_make_basis(n);
        for (const glm::vec3& t : degenerate)
        {
            for (float handedness : {1.0f, -1.0f})
            {
                const std::string what =
                    "n " + to_string(n) + ", degenerate t " + to_string(t) + ", handedness " + std::to_string(handedness);
                const OpenPBR_Basis b = openpbr_make_basis(n, t, handedness);
                // Documented behaviour: the normal-only frame (right-handed) is returned,
                // whatever the requested handedness.
                expect_orthonormal(b, 1.0f, what);
                expect_same_basis(b, fallback, what);
            }
        }
    }
}

TEST(BsdfBasis, PreparedBasisIsOrthonormalForDegenerateGeometry)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Geometry
    {
        glm::vec3 normal, tangent, bitangent;
    };
    const Geometry cases[] = {
        {{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
        {{0.0f, 0.0f, -1.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}},
        {{0.0f, 0.0f, 2.0f}, {0.0f, 0.0f, 5.0f}, {1.0f, 0.0f, 0.0f}},
        {{1e-4f, 0.0f, -1.0f}, {nan, nan, nan}, {0.0f, 1.0f, 0.0f}},
        {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}},
        {{3.0f, 4.0f, 0.0f}, {-4.0f, 3.0f, 1.0f}, {0.0f, 0.0f, -1.0f}},
    };
    RandomMaterials random(6);
    for (const Geometry& g : cases)
    {
        OpenPBR_ResolvedInputs inputs = random.material();
        inputs.geometry_basis.normal = g.normal;
        inputs.geometry_basis.tangent = g.tangent;
        inputs.geometry_basis.bitangent = g.bitangent;
        for (int k = 0; k < 20; ++k)
        {
            const glm::vec3 view = random.sphere_direction();
            const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
            const std::string what =
                "geometry n " + to_string(g.normal) + ", t " + to_string(g.tangent) + ", view " + to_string(view);
            const float det = glm::dot(glm::cross(bsdf.basis.tangent, bsdf.basis.bitangent), bsdf.basis.normal);
            expect_orthonormal(bsdf.basis, det < 0.0f ? -1.0f : 1.0f, what);
            EXPECT_GE(glm::dot(bsdf.basis.normal, view), -1e-6f) << what << ": the prepared frame faces the view";
            EXPECT_TRUE(std::isfinite(bsdf.view.x) && std::isfinite(bsdf.view.y) && std::isfinite(bsdf.view.z)) << what;
            EXPECT_GE(bsdf.view.z, 0.0f) << what;
        }
    }
}

}  // namespace

// Coat darkening over a subsurface base (spec "Coat", darkening: E_b is the albedos of the base
// slabs blended by their weights; the subsurface slab's albedo is subsurface_color): a colored
// subsurface base is darkened more than a white one, its darker channels more, and not at all
// with coat_darkening 0.
// A metal's samples stay bounded however far its albedo estimate (F82 at the view) falls below
// what its lobe reflects: metals of F0 0 to 1e-3 (where the estimate is F0 but tilted
// microfacets reflect the Schlick rise), from a mirror (roughness 0) to roughness 1, anisotropic
// up to 1, alone, beside a pass-through and under a coat, at views from head-on to the horizon
// (cos 0): 576 metals. Every sample drawn from the metal's selection
// window (a 48 x 48 grid of directions) weighs at most 1 / OPENPBR_METAL_SELECTION_FLOOR = 1000,
// the floor's guarantee (the sum of the selection estimates is at most 1 here). Measured largest
// weight: 1.87 (F0 0, roughness 0.3, opacity 0.6, view cos 0.5); without the floor 2.9e4 (F0
// 1.4e-8, roughness 1, anisotropy 0.8, opacity 0.6, head-on: metal probability 7.7e-9).
TEST(BsdfBasics, MetalSamplesStayBoundedWhereItsEstimateMissesTheGrazingRise)
{
    float largest = 0.0f;
    std::string largest_case;
    for (const float f0 : {0.0f, 1.4e-8f, 1e-5f, 1e-3f})
    {
        for (const float roughness : {0.0f, 0.3f, 0.8f, 1.0f})
        {
            for (const float anisotropy : {0.0f, 0.8f, 1.0f})
            {
                for (const int layering : {0, 1, 2})  // alone, opacity 0.6, under a coat
                {
                    for (const float view_cosine : {1.0f, 0.5f, 0.1f, 0.0f})
                    {
                        OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
                        inputs.base_weight = 1.0f;
                        inputs.base_color = glm::vec3(f0);
                        inputs.base_metalness = 1.0f;
                        inputs.specular_roughness = roughness;
                        inputs.specular_roughness_anisotropy = anisotropy;
                        inputs.geometry_opacity = layering == 1 ? 0.6f : 1.0f;
                        inputs.coat_weight = layering == 2 ? 1.0f : 0.0f;
                        const glm::vec3 view(std::sqrt(1.0f - view_cosine * view_cosine), 0.0f, view_cosine);
                        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view);
                        if (bsdf.probability_metal <= 0.0f)
                        {
                            continue;
                        }
                        const float window_start = bsdf.probability_transmission + bsdf.probability_fuzz +
                                                   bsdf.probability_coat + bsdf.probability_specular;
                        const int n = 48;
                        for (int i = 0; i < n; ++i)
                        {
                            for (int j = 0; j < n; ++j)
                            {
                                const glm::vec3 u((i + 0.5f) / n, (j + 0.5f) / n,
                                                  window_start + 0.5f * bsdf.probability_metal);
                                const OpenPBR_BsdfSample sample = openpbr_sample(bsdf, u);
                                const float weight =
                                    std::max({sample.weight.specular.x, sample.weight.specular.y, sample.weight.specular.z});
                                if (weight > largest)
                                {
                                    largest = weight;
                                    std::ostringstream name;
                                    name << "F0 " << f0 << ", roughness " << roughness << ", anisotropy " << anisotropy
                                         << ", layering " << layering << ", view cos " << view_cosine
                                         << ", metal probability " << bsdf.probability_metal;
                                    largest_case = name.str();
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    const float bound = 1000.0f;  // 1 / OPENPBR_METAL_SELECTION_FLOOR (1e-3)
    EXPECT_LE(largest, bound) << largest_case;
    std::cout << "largest metal sample weight " << largest << " (" << largest_case << ")\n";
}

TEST(BsdfBasics, CoatDarkeningSeesTheSubsurfaceColor)
{
    auto pearl = [](glm::vec3 subsurface_color, float coat_darkening) {
        OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
        inputs.subsurface_weight = 1.0f;
        inputs.subsurface_color = subsurface_color;
        inputs.coat_weight = 1.0f;
        inputs.coat_ior = 1.68f;
        inputs.coat_darkening = coat_darkening;
        inputs.thin_film_weight = 1.0f;
        return openpbr_prepare(inputs, glm::normalize(glm::vec3(0.3f, 0.1f, 0.9f))).under_coat_transmitted;
    };
    const glm::vec3 colored = pearl(glm::vec3(0.78f, 0.75f, 0.71f), 1.0f);
    const glm::vec3 white = pearl(glm::vec3(1.0f), 1.0f);
    EXPECT_LT(colored.x, white.x * 0.99f);
    EXPECT_LT(colored.z, colored.x);
    const glm::vec3 colored_undarkened = pearl(glm::vec3(0.78f, 0.75f, 0.71f), 0.0f);
    const glm::vec3 white_undarkened = pearl(glm::vec3(1.0f), 0.0f);
    EXPECT_EQ(colored_undarkened.x, white_undarkened.x);
    EXPECT_EQ(colored_undarkened.z, white_undarkened.z);
}
