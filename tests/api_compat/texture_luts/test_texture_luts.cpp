// Texture tables (OPENPBR_USE_TEXTURE_LUTS=1) on the CPU, through a stand-in for the texture
// units (texture_sampler.h: Vulkan's linear filter and clamp-to-edge, exact or 8-bit weights):
// every table look-up and whole-BSDF evaluations against the array mode, for both ways of
// reading the 3D tables (the library's interpolation along eta from slice fetches, and one
// trilinear fetch). The errors are printed; docs/accuracy-vs-time.md "Texture tables" has them.
#include <glm/glm.hpp>

#include "slang/openpbr.h"
#include "tests/api_compat/texture_luts/texture_sampler.h"
#include "tests/api_compat/texture_luts/texture_variant.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

using texture_variants::TableLookups;

struct Random
{
    std::uint64_t state = 0x2545F4914F6CDD1DULL;
    float next()
    {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        return float(state >> 40) * (1.0f / 16777216.0f);
    }
    // A range end one time in ten each, else uniform.
    float unit_with_ends()
    {
        const float pick = next();
        return pick < 0.1f ? 0.0f : (pick < 0.2f ? 1.0f : next());
    }
};

TableLookups array_lookups(float mu, float alpha, float eta, float anisotropy, float cos_phi_squared, float fuzz_roughness)
{
    using namespace openpbr;
    TableLookups result;
    result.ggx_albedo = openpbr_ggx_albedo(mu, alpha);
    result.reflection = openpbr_dielectric_reflection_albedo(mu, alpha, eta);
    result.transmission = openpbr_dielectric_transmission_albedo(mu, alpha, eta);
    result.interface_albedo = openpbr_dielectric_interface_albedo(mu, alpha, eta);
    result.anisotropy_ratio = openpbr_ggx_anisotropy_ratio(mu, std::sqrt(alpha), anisotropy, cos_phi_squared);
    const glm::vec3 fuzz = openpbr_fuzz_ltc_coefficients(mu, fuzz_roughness);
    result.fuzz_a = fuzz.x;
    result.fuzz_b = fuzz.y;
    result.fuzz_r = fuzz.z;
    return result;
}

constexpr int kTableCount = 8;
const char* const kTableNames[kTableCount] = {"ggx_albedo (2D)", "reflection (3D)", "transmission (3D)", "interface (3D)",
                                              "anisotropy (4D)", "fuzz_ltc_a (2D)", "fuzz_ltc_b (2D)",   "fuzz_ltc_r (2D)"};

float field(const TableLookups& lookups, int table)
{
    const float values[kTableCount] = {
        lookups.ggx_albedo,       lookups.reflection, lookups.transmission, lookups.interface_albedo,
        lookups.anisotropy_ratio, lookups.fuzz_a,     lookups.fuzz_b,       lookups.fuzz_r};
    return values[table];
}

// Largest and 99th-percentile absolute difference per table between a texture build and the
// array mode over `count` random points (ends of every axis included).
struct TableErrors
{
    float largest[kTableCount] = {};
    float percentile_99[kTableCount] = {};
    double fetches_per_point = 0.0;
};

// mu_min: the smallest view cosine drawn, e.g. 0.01 to leave out the first mu cell of the 3D
// tables (mu < 1/576), where the array mode brackets between the cell's two columns.
template <class Lookup> TableErrors measure(Lookup lookup, int subtexel_bits, int count, float mu_min = 1e-4f)
{
    texture_luts_host::subtexel_bits = subtexel_bits;
    texture_luts_host::fetch_count = 0;
    std::vector<float> differences[kTableCount];
    Random random;
    for (int index = 0; index < count; ++index)
    {
        const float mu = std::max(random.unit_with_ends(), mu_min);
        const float alpha = random.unit_with_ends();
        // eta over the tables' [1/3, 3], with eta = 1 (the node between the two sides) often.
        const float pick = random.next();
        const float eta =
            pick < 0.1f ? 1.0f : (pick < 0.55f ? 1.0f + 2.0f * random.next() : 1.0f / (1.0f + 2.0f * random.next()));
        const float anisotropy = random.unit_with_ends();
        const float cos_phi_squared = random.unit_with_ends();
        const float fuzz_roughness = random.unit_with_ends();
        const TableLookups expected = array_lookups(mu, alpha, eta, anisotropy, cos_phi_squared, fuzz_roughness);
        const TableLookups actual = lookup(mu, alpha, eta, anisotropy, cos_phi_squared, fuzz_roughness);
        for (int table = 0; table < kTableCount; ++table)
        {
            differences[table].push_back(std::abs(field(actual, table) - field(expected, table)));
        }
    }
    TableErrors errors;
    for (int table = 0; table < kTableCount; ++table)
    {
        std::sort(differences[table].begin(), differences[table].end());
        errors.largest[table] = differences[table].back();
        errors.percentile_99[table] = differences[table][size_t(0.99 * double(differences[table].size()))];
    }
    errors.fetches_per_point = double(texture_luts_host::fetch_count) / count;
    return errors;
}

void print(const char* what, const TableErrors& errors)
{
    std::printf("%s: %.2f fetches per point (all 8 tables)\n", what, errors.fetches_per_point);
    for (int table = 0; table < kTableCount; ++table)
    {
        std::printf("  %-18s max |error| %.2e, 99th percentile %.2e\n", kTableNames[table], double(errors.largest[table]),
                    double(errors.percentile_99[table]));
    }
}

constexpr int kPointCount = 200000;

// Exact filter weights: the texture build is the array mode's arithmetic in another order,
// so the look-ups agree to float rounding. Measured: max 1.1e-6 (the 4D table; 3D 9.5e-7, 2D
// 1.2e-7) over 2e5 points; bound 4e-6 (a few ulps of values up to about 1, times the quadratic
// eta step's factor 3, and room for other compilers' contractions).
TEST(TextureLuts, ExactWeightsMatchTheArrayMode)
{
    const TableErrors errors = measure(texture_variants::texture_exact::lookups, 0, kPointCount);
    print("texture tables, eta from slice fetches, exact weights", errors);
    for (int table = 0; table < kTableCount; ++table)
    {
        // The LTC a coefficient reaches 1e3 (OPENPBR_FUZZ_LTC_MAX_A): relative there.
        const float scale = table == 5 ? 1000.0f : 1.0f;
        EXPECT_LT(errors.largest[table], 4e-6f * scale) << kTableNames[table];
    }
}

// GPU filter weights (8 fractional bits): the weights move by up to 1/512, so a look-up moves
// by up to 1/512 of the difference between neighbouring nodes. Measured max 2.2e-3
// (transmission), 1.8e-3 (reflection), 1.0e-3 (4D), 0.2-0.9e-3 (2D); 99th percentiles
// 0.1-0.4e-3. Bound 5e-3 absolute on the albedos, the LTC a coefficient relative to its range.
TEST(TextureLuts, EightBitWeightsStayWithinTheFilterPrecision)
{
    const TableErrors errors = measure(texture_variants::texture_exact::lookups, 8, kPointCount);
    print("texture tables, eta from slice fetches, 8-bit weights", errors);
    for (int table = 0; table < kTableCount; ++table)
    {
        const float scale = table == 5 ? 1000.0f : 1.0f;
        EXPECT_LT(errors.largest[table], 5e-3f * scale) << kTableNames[table];
    }
}

// One trilinear fetch per 3D look-up: linear along eta instead of the quadratic through three
// nodes, mixing the two sides of eta = 1 within the cells next to it, no rounding up between
// eta nodes where the albedo jumps (the onset of total internal reflection moves with eta, so
// below eta = 1 E_R steps from about 0.1 to 1 between two nodes) and no bracketing in the first
// mu cell. The 2D and 4D tables are read as in the exact build (same errors); the 3D tables'
// error is what trilinear filtering costs. Measured (2e5 points): max 0.89 / 1.00 / 0.45
// (reflection / transmission / interface), 99th percentile 0.11 / 0.13 / 0.08; with views
// mu >= 0.01 only, max 0.89 / 1.00 / 0.29 and 99th percentile 0.11 / 0.12 / 0.05: the large
// errors are the jumps along eta, not grazing views. Bound: 99th percentile below 0.2; the
// test also fails if the option stops taking effect (errors no larger than the exact build's).
TEST(TextureLuts, TrilinearEtaCostsAccuracyOnTheThreeDimensionalTables)
{
    const TableErrors exact = measure(texture_variants::texture_exact::lookups, 0, kPointCount);
    const TableErrors trilinear = measure(texture_variants::texture_trilinear::lookups, 0, kPointCount);
    const TableErrors trilinear_away = measure(texture_variants::texture_trilinear::lookups, 0, kPointCount, 0.01f);
    print("texture tables, one trilinear fetch per 3D look-up, exact weights", trilinear);
    print("the same for view cosines >= 0.01", trilinear_away);
    for (int table = 1; table <= 3; ++table)
    {
        EXPECT_GT(trilinear.largest[table], 10.0f * exact.largest[table]) << kTableNames[table];
        EXPECT_LT(trilinear.percentile_99[table], 0.2f) << kTableNames[table];
        EXPECT_LT(trilinear_away.percentile_99[table], 0.2f) << kTableNames[table];
    }
    EXPECT_LT(trilinear.fetches_per_point, exact.fetches_per_point);
}

// The whole BSDF: eval of random materials and directions, texture (exact eta, exact and 8-bit
// weights) against the array mode. Relative error of the summed eval; measured in the printout.
TEST(TextureLuts, WholeBsdfAgreesWithTheArrayMode)
{
    Random random;
    std::vector<float> relative[2];
    for (int index = 0; index < 20000; ++index)
    {
        texture_variants::MaterialParameters material;
        material.base_color = glm::vec3(random.next(), random.next(), random.next());
        material.metalness = random.unit_with_ends();
        material.roughness = random.unit_with_ends();
        material.anisotropy = random.next() < 0.5f ? 0.0f : random.unit_with_ends();
        material.ior = 1.0f + 1.5f * random.next();
        material.transmission = random.unit_with_ends();
        material.coat = random.unit_with_ends();
        material.coat_roughness = random.unit_with_ends();
        material.fuzz = random.unit_with_ends();
        material.fuzz_roughness = random.unit_with_ends();
        const auto direction = [&random]() {
            const float z = 1.0f - 2.0f * random.next();
            const float radius = std::sqrt(std::max(0.0f, 1.0f - z * z));
            const float phi = 6.2831853f * random.next();
            return glm::vec3(radius * std::cos(phi), radius * std::sin(phi), z);
        };
        const glm::vec3 view = direction();
        const glm::vec3 light = direction();
        openpbr::OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
        texture_variants::apply_parameters(inputs, material);
        const openpbr::OpenPBR_DiffuseSpecular value = openpbr::openpbr_eval(openpbr::openpbr_prepare(inputs, view), light);
        const glm::vec3 expected = value.diffuse + value.specular;
        for (int bits_case = 0; bits_case < 2; ++bits_case)
        {
            texture_luts_host::subtexel_bits = bits_case == 0 ? 0 : 8;
            const glm::vec3 actual = texture_variants::texture_exact::eval(material, view, light);
            for (int channel = 0; channel < 3; ++channel)
            {
                const float reference = std::abs(expected[channel]);
                if (reference > 1e-3f)
                {
                    relative[bits_case].push_back(std::abs(actual[channel] - expected[channel]) / reference);
                }
            }
        }
    }
    for (int bits_case = 0; bits_case < 2; ++bits_case)
    {
        std::sort(relative[bits_case].begin(), relative[bits_case].end());
        const float largest = relative[bits_case].back();
        const float median = relative[bits_case][relative[bits_case].size() / 2];
        std::printf("whole BSDF eval, %s weights: median relative error %.2e, max %.2e (%zu values)\n",
                    bits_case == 0 ? "exact" : "8-bit", double(median), double(largest), relative[bits_case].size());
        // Exact weights: float rounding through prepare (measured max 6.2e-7, median 0);
        // 8-bit weights: the table error carried into the compensation factors (measured
        // median 2.6e-5, max 3.8e-3). Bounds 1e-4 and 2e-2.
        EXPECT_LT(largest, bits_case == 0 ? 1e-4f : 2e-2f);
    }
}

}  // namespace
