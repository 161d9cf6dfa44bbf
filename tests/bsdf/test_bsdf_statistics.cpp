// Statistical tests of the OpenPBR BSDF: sampling against pdf (chi-square over the full
// sphere), pdf normalization, weight == eval / pdf, white furnace and per-lobe reciprocity.
//
// Data-driven: a new material configuration is one entry of material_configs() (or of
// host::white_furnace_configs() in host/checks/furnace.cpp, shared with `openpbr furnace`); a new
// lobe is one entry of reciprocity_cases(). Every configuration is tested at each view cosine
// of kViewCosines, on the sides it lists (outside: view above the geometric normal; inside:
// below it) and for each IOR variant (e.g. eta and 1/eta for transmission).
#include "tests/bsdf/bsdf_statistics.h"
#include "host/checks/furnace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace openpbr;
using namespace openpbr::testing;

// ------------------------------------------------------------------------------------------
// Configuration table

enum class Side
{
    outside,  // view on the side the geometric normal points to
    inside    // view below the geometric normal (a ray leaving the object / back face)
};

struct MaterialConfig
{
    std::string name;
    std::function<OpenPBR_ResolvedInputs()> make_inputs;
    std::vector<Side> sides = {Side::outside};
    // specular_ior values to test; empty: the value make_inputs sets. For transmission, e.g.
    // {1.5f, 1.0f / 1.5f} to test entering and leaving a denser medium.
    std::vector<float> ior_variants = {};
    // IOR of the medium around the surface (openpbr_prepare's exterior_ior), e.g. 1.33 in water.
    float exterior_ior = 1.0f;
};

// A tilted, non-axis-aligned geometry frame: exercises the world <-> local transforms.
OpenPBR_Basis tilted_basis()
{
    OpenPBR_Basis basis;
    basis.normal = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));
    basis.tangent = glm::vec3(1.0f, 0.5f, 0.0f);  // not orthogonal: prepare orthonormalizes it
    basis.bitangent = glm::cross(basis.normal, basis.tangent);
    return basis;
}

OpenPBR_ResolvedInputs defaults() { return openpbr_make_default_resolved_inputs(); }

// The rough dielectric at relative IORs 0.67, 0.99, 1 (index-matched, a delta pass-through),
// 1.01 and 1.5, entering and leaving, in a medium of IOR `exterior` (specular_ior = relative
// IOR x exterior).
MaterialConfig rough_dielectric_through_one(const std::string& name, const float roughness, const float exterior)
{
    MaterialConfig config{name, [roughness] {
                              OpenPBR_ResolvedInputs i = defaults();
                              i.transmission_weight = 1.0f;
                              i.specular_roughness = roughness;
                              return i;
                          }};
    config.sides = {Side::outside, Side::inside};
    for (const float relative : {0.67f, 0.99f, 1.0f, 1.01f, 1.5f})
    {
        config.ior_variants.push_back(relative * exterior);
    }
    config.exterior_ior = exterior;
    return config;
}

// The base alone: diffuse, specular, metal, opacity.
std::vector<MaterialConfig> base_configs()
{
    return {
        {"lambert",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.specular_weight = 0.0f;
             return i;
         }},
        {"eon_rough_diffuse",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.specular_weight = 0.0f;
             i.base_diffuse_roughness = 1.0f;
             return i;
         }},
        {"default_material", [] { return defaults(); }, {Side::outside, Side::inside}},
        {"rough_dielectric_specular",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.base_weight = 0.0f;
             return i;
         }},
        {"metal_rough",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.base_metalness = 1.0f;
             i.base_color = glm::vec3(0.9f, 0.6f, 0.3f);
             i.specular_roughness = 0.5f;
             return i;
         }},
        {"metal_anisotropic",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.base_metalness = 1.0f;
             i.base_color = glm::vec3(0.95f, 0.8f, 0.5f);
             i.specular_roughness = 0.5f;
             i.specular_roughness_anisotropy = 0.8f;
             i.geometry_basis = tilted_basis();
             i.specular_anisotropy_rotation = glm::vec2(std::cos(0.5f), std::sin(0.5f));
             return i;
         },
         {Side::outside, Side::inside}},
        {"metal_smooth",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.base_metalness = 1.0f;
             i.specular_roughness = 0.0f;
             return i;
         }},
        {"partial_opacity",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.geometry_opacity = 0.5f;
             return i;
         }},
    };
}

// The layers above the base: coat and fuzz.
std::vector<MaterialConfig> layer_configs()
{
    return {
        {"coat_glossy",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.coat_weight = 1.0f;
             i.coat_roughness = 0.2f;
             i.coat_color = glm::vec3(0.9f, 0.8f, 0.6f);
             return i;
         }},
        {"coat_smooth_tilted_coat_normal",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.coat_weight = 0.7f;
             i.coat_roughness = 0.0f;
             i.geometry_coat_basis.normal = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f));
             return i;
         }},
        {"fuzz",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.fuzz_weight = 1.0f;
             i.fuzz_roughness = 0.5f;
             return i;
         }},
    };
}

// Transmission: rough, index-matched, smooth and dispersive glass, and the thin-walled lobes.
std::vector<MaterialConfig> transmission_configs()
{
    return {
        {"rough_glass",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.transmission_weight = 1.0f;
             return i;
         },
         {Side::outside, Side::inside},
         {1.5f, 1.0f / 1.5f}},
        // The rough dielectric at relative IORs through 1 (1: index-matched, a delta pass-through),
        // in air and in water. Near 1 the refracted lobe is |1 - 1/eta| alpha / (mu^2 + alpha^2)
        // rad wide (openpbr_dielectric_transmission_width): at 0.99 and 1.01 and roughness 0.5,
        // 2.4e-3 at view cos 1 to 0.04 at 0.02, below the 0.098 rad cells of the surface grid, so
        // make_bsdf_target bins it on the warped polar grid around the lobe (polar_scale).
        // Roughness 0.2 has both regimes of the collapse: at view cos 1 the lobe (4e-4 rad) is
        // narrower than OPENPBR_DELTA_ALPHA_THRESHOLD and refracts as a delta event (its share of
        // delta samples from dielectric_delta_share: 1 - 3.2e-5 entering at 0.99, 1 - 6.2e-5
        // seen from inside at 1.01, where rough Fresnel reflections add to the totally reflecting
        // microfacets), at view cos 0.5 it is rough and 1.6e-3 rad wide, the narrowest rough
        // refraction tested.
        rough_dielectric_through_one("rough_dielectric_relative_ior", 0.5f, 1.0f),
        rough_dielectric_through_one("rough_dielectric_relative_ior_roughness_0p2", 0.2f, 1.0f),
        // ... and in water: specular_ior = relative IOR x 1.33.
        rough_dielectric_through_one("rough_dielectric_relative_ior_in_water", 0.5f, 1.33f),
        rough_dielectric_through_one("rough_dielectric_relative_ior_roughness_0p2_in_water", 0.2f, 1.33f),
        {"smooth_glass",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.transmission_weight = 1.0f;
             i.specular_roughness = 0.0f;
             return i;
         },
         {Side::outside, Side::inside},
         {1.5f, 1.0f / 1.5f}},
        {"dispersive_rough_glass",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.transmission_weight = 1.0f;
             i.transmission_dispersion_scale = 1.0f;
             i.specular_roughness = 0.4f;
             return i;
         }},
        {"thin_walled_translucent",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.geometry_thin_walled = true;
             i.transmission_weight = 1.0f;
             return i;
         },
         {Side::outside, Side::inside}},
        {"thin_walled_subsurface",
         [] {
             OpenPBR_ResolvedInputs i = defaults();
             i.geometry_thin_walled = true;
             i.subsurface_weight = 1.0f;
             i.subsurface_scatter_anisotropy = 0.3f;
             return i;
         }},
    };
}

// The whole BSDF with every lobe on at partial weight (thin film, anisotropy, a tilted coat
// normal, dispersion and partial opacity included), entering and leaving.
MaterialConfig every_lobe_partial_config()
{
    return {"every_lobe_partial",
            [] {
                OpenPBR_ResolvedInputs i = defaults();
                i.base_metalness = 0.3f;
                i.base_diffuse_roughness = 0.5f;
                i.specular_roughness = 0.35f;
                i.specular_roughness_anisotropy = 0.5f;
                i.geometry_basis = tilted_basis();
                i.specular_anisotropy_rotation = glm::vec2(std::cos(0.5f), std::sin(0.5f));
                i.geometry_coat_basis.normal = glm::normalize(glm::vec3(-0.1f, 0.2f, 1.0f));
                i.geometry_coat_basis.tangent = glm::vec3(1.0f, 0.0f, 0.0f);
                i.geometry_coat_basis.bitangent = glm::cross(i.geometry_coat_basis.normal, i.geometry_coat_basis.tangent);
                i.transmission_weight = 0.3f;
                i.transmission_dispersion_scale = 0.5f;
                i.subsurface_weight = 0.3f;
                i.coat_weight = 0.5f;
                i.coat_roughness = 0.2f;
                i.coat_color = glm::vec3(0.9f, 0.8f, 0.7f);
                i.fuzz_weight = 0.4f;
                i.thin_film_weight = 0.5f;
                i.geometry_opacity = 0.9f;
                return i;
            },
            {Side::outside, Side::inside},
            {1.5f, 1.0f / 1.5f}};
}

const std::vector<MaterialConfig>& material_configs()
{
    static const std::vector<MaterialConfig> configs = [] {
        std::vector<MaterialConfig> all;
        for (const std::vector<MaterialConfig>& group : {base_configs(), layer_configs(), transmission_configs()})
        {
            all.insert(all.end(), group.begin(), group.end());
        }
        all.push_back(every_lobe_partial_config());
        return all;
    }();
    return configs;
}

const std::vector<float> kViewCosines = {1.0f, 0.5f, 0.1f, 0.02f};

struct StatisticsCase
{
    const MaterialConfig* config;
    float view_cos;
    Side side;
    float ior;  // NaN: as the configuration sets it

    OpenPBR_ResolvedInputs inputs() const
    {
        OpenPBR_ResolvedInputs i = config->make_inputs();
        if (!std::isnan(ior))
        {
            i.specular_ior = ior;
        }
        return i;
    }

    // View at cos theta = +-view_cos from the geometric normal, azimuth 0.6 rad from the
    // (orthonormalized, unrotated) geometry tangent.
    glm::vec3 view_world() const
    {
        const OpenPBR_ResolvedInputs i = inputs();
        const OpenPBR_Basis frame =
            openpbr_make_basis(i.geometry_basis.normal, i.geometry_basis.tangent, i.geometry_basis.bitangent);
        return direction_in_basis(frame, side == Side::outside ? view_cos : -view_cos, 0.6);
    }

    std::string name() const
    {
        std::ostringstream out;
        out << config->name << "_cos" << view_cos << (side == Side::outside ? "_outside" : "_inside");
        if (!std::isnan(ior))
        {
            out << "_ior" << ior;
        }
        std::string s = out.str();
        for (char& c : s)
        {
            c = (c == '.') ? 'p' : c;
        }
        return s;
    }
};

std::vector<StatisticsCase> statistics_cases()
{
    std::vector<StatisticsCase> cases;
    for (const MaterialConfig& config : material_configs())
    {
        std::vector<float> iors = config.ior_variants;
        if (iors.empty())
        {
            iors.push_back(std::nanf(""));
        }
        for (float view_cos : kViewCosines)
        {
            for (Side side : config.sides)
            {
                for (float ior : iors)
                {
                    cases.push_back({&config, view_cos, side, ior});
                }
            }
        }
    }
    return cases;
}

// Hypothesis tests in this binary: per case the chi-square, the delta-fraction binomial and
// the continuous-fraction binomial of the chi-square run, plus the pdf-integral binomial.
constexpr int kHypothesesPerCase = 4;

double significance_level()
{
    static const double level = sidak_significance(0.01, static_cast<int>(statistics_cases().size()) * kHypothesesPerCase);
    return level;
}

constexpr std::uint64_t kChiSquareSamples = 1000000;
constexpr std::uint64_t kConsistencySamples = 200000;
constexpr std::uint64_t kPdfIntegralSamples = 400000;

class BsdfStatistics : public ::testing::TestWithParam<StatisticsCase>
{
  protected:
    OpenPBR_PreparedBsdf prepare() const
    {
        return openpbr_prepare(GetParam().inputs(), GetParam().view_world(), OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM,
                               GetParam().config->exterior_ior);
    }
    std::string context() const
    {
        return GetParam().name() + "\n  inputs: " + describe_inputs(GetParam().inputs()) +
               "\n  view: " + to_string(GetParam().view_world());
    }
    std::uint64_t seed() const { return seed_from_name(GetParam().name()); }
};

TEST_P(BsdfStatistics, ChiSquareSampleMatchesPdf)
{
    const OpenPBR_PreparedBsdf bsdf = prepare();
    ChiSquareOptions options;
    options.sample_count = kChiSquareSamples;
    options.seed = seed();
    const ChiSquareResult result = run_chi_square_test(make_bsdf_target(bsdf, GetParam().name()), options);
    const double alpha = significance_level();
    SCOPED_TRACE(context() + "\n" + result.report);
    EXPECT_EQ(result.nonfinite_count, 0u);
    EXPECT_TRUE(result.delta_pdfs_consistent) << "delta samples must report their selection probability as pdf";
    EXPECT_GT(result.p_value, alpha) << "sample() does not follow pdf() (chi-square)";
    EXPECT_GT(result.delta_p_value, alpha) << "fraction of delta samples != sum of delta selection probabilities";
    EXPECT_GT(result.continuous_p_value, alpha) << "fraction of continuous samples != integral of pdf";
}

TEST_P(BsdfStatistics, PdfIntegralMatchesValidFraction)
{
    const OpenPBR_PreparedBsdf bsdf = prepare();
    const PdfIntegralResult result =
        check_pdf_integral(make_bsdf_target(bsdf, GetParam().name()), kPdfIntegralSamples, seed() + 1);
    SCOPED_TRACE(context());
    EXPECT_LE(result.pdf_integral, 1.0 + 1e-4);
    EXPECT_GT(result.p_value, significance_level())
        << "integral of pdf " << result.pdf_integral << " vs fraction of valid non-delta samples " << result.valid_fraction
        << " +- " << result.standard_error;
}

TEST_P(BsdfStatistics, SampleWeightIsEvalOverPdf)
{
    const OpenPBR_PreparedBsdf bsdf = prepare();
    ConsistencyOptions options;
    options.sample_count = kConsistencySamples;
    options.seed = seed() + 2;
    const ConsistencyResult result = check_sample_consistency(make_bsdf_target(bsdf, GetParam().name()), options);
    SCOPED_TRACE(context());
    EXPECT_TRUE(result.ok()) << result.weight_mismatch_count << " weight and " << result.pdf_mismatch_count
                             << " pdf mismatches, " << result.invalid_value_count << " invalid values of "
                             << result.sample_count << " samples (max relative errors: weight "
                             << result.max_weight_relative_error << ", pdf " << result.max_pdf_relative_error
                             << "); first: " << result.first_failure;
}

INSTANTIATE_TEST_SUITE_P(Configurations, BsdfStatistics, ::testing::ValuesIn(statistics_cases()),
                         [](const ::testing::TestParamInfo<StatisticsCase>& info) { return info.param.name(); });

// ------------------------------------------------------------------------------------------
// White furnace

// The configurations and tolerances are host/checks/furnace.h's, shared with `openpbr furnace`.
constexpr double kFurnaceTargetError = 5e-4;

struct FurnaceCase
{
    const host::FurnaceConfig* config;
    float view_cos;
    host::FurnaceSide side;
    std::string name() const
    {
        std::ostringstream out;
        out << config->name << "_cos" << view_cos << (side == host::FurnaceSide::inside ? "_inside" : "");
        std::string s = out.str();
        for (char& c : s)
        {
            c = (c == '.') ? 'p' : (c == '-' ? 'm' : c);
        }
        return s;
    }
};

std::vector<FurnaceCase> furnace_cases()
{
    std::vector<FurnaceCase> cases;
    for (const host::FurnaceConfig& config : host::white_furnace_configs())
    {
        // Every row of the relative-IOR sweep included: a row outside the sweep's band is held
        // to its measured band of host::furnace_known_limits() (docs/known-limits.md).
        for (float view_cos : host::furnace_view_cosines(config))
        {
            for (host::FurnaceSide side : config.sides)
            {
                cases.push_back({&config, view_cos, side});
            }
        }
    }
    return cases;
}

class WhiteFurnace : public ::testing::TestWithParam<FurnaceCase>
{
};

TEST_P(WhiteFurnace, Albedo)
{
    const FurnaceCase& c = GetParam();
    const OpenPBR_ResolvedInputs& inputs = c.config->inputs;
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, host::furnace_view(inputs, c.view_cos, c.side),
                                                      c.config->wavelengths_nm, c.config->exterior_ior);
    const bool sweep = c.config->expectation == host::FurnaceExpectation::relative_ior_sweep;
    // Deterministic sample-count escalation: 2^18 samples, 4x more while the standard error
    // exceeds kFurnaceTargetError (lobe selection makes some configurations noisy). The
    // relative-IOR sweep (about 600 cases) starts at 2^14: its interface lobes weigh close to 1
    // per sample (standard error 1e-4 to 6e-4 at 2^14 where the interface keeps its energy), and
    // its band is 0.015 wide, so a target of 1e-3 (3 se inside a fifth of the band) suffices.
    // The sweep draws independent samples, up to 2^24: below relative IOR 1 seen from outside
    // the few microfacets that transmit carry weights up to 1000 (about 1e-4 of the samples),
    // which the shifted R3 replicas under-sample while their spread stays small (relative IOR
    // 0.67, roughness 0.2, view cos 0.1: 0.9265 +- 0.0005 from 2^22 R3 points against 0.9989
    // +- 0.0016 from 2^24 independent ones and 0.9974 +- 0.0063 from the furnace command's 2^20).
    const double target_error = sweep ? 1e-3 : kFurnaceTargetError;
    const SamplingTarget target = make_bsdf_target(bsdf, c.name());
    // The sweep's escalation keeps the samples it drew (IndependentAlbedoSampler: the same
    // estimate at each count, bit for bit, without drawing the first quarter again from 2^22
    // to 2^24).
    IndependentAlbedoSampler independent(target, seed_from_name(c.name()));
    AlbedoEstimate albedo;
    for (std::uint64_t samples = sweep ? (1u << 14) : (1u << 18); samples <= (sweep ? (1u << 24) : (1u << 22)); samples *= 4)
    {
        albedo = sweep ? independent.estimate(samples)
                       : estimate_albedo(target, samples, seed_from_name(c.name()), SamplerKind::low_discrepancy);
        const glm::dvec3 se = albedo.standard_error;
        if (std::max({se.x, se.y, se.z}) <= target_error)
        {
            break;
        }
    }
    SCOPED_TRACE(c.name() + "\n  inputs: " + describe_inputs(inputs));
    for (int channel = 0; channel < 3; ++channel)
    {
        const double a = albedo.mean[channel];
        const double se = albedo.standard_error[channel];
        // The estimate must be precise enough for the 0.005 tolerance to mean something. At
        // grazing views (only the 1.005 bound applies) cosine-sampled EON has heavy-tailed
        // weights (pi f / rho grows like sigma / max(mu_i, mu_o)), so there 4M samples only
        // reach a few 1e-3.
        // A relative IOR below 1 seen from outside hands the light that the mostly totally
        // reflecting interface does not reflect, 1 - E_R, to the few microfacets that transmit,
        // weight (1 - E_R) / E_T0 (up to 1000, OPENPBR_MIN_TRANSMISSION_ALBEDO): measured
        // standard errors up to 0.009 at 65536 samples (relative IOR 0.67, roughness 0.5, view
        // cos 0.1) and 0.0018 at 2^24 (0.5, roughness 0.2, cos 0.1), so those sweep rows get 3e-3.
        const double max_standard_error = c.view_cos >= host::furnace_tolerance_min_cos ? (sweep ? 3e-3 : 1e-3) : 5e-3;
        EXPECT_LT(se, max_standard_error) << "channel " << channel << ": albedo " << a << " from " << albedo.sample_count
                                          << " samples";
        const host::FurnaceBand band = host::furnace_band(*c.config, c.side, c.view_cos);
        EXPECT_LE(a - 3.0 * se, band.max_albedo) << "energy gain, channel " << channel << ": albedo " << a << " +- " << se
                                                 << (band.known_limit ? " (known limit)" : "");
        EXPECT_GE(a + 3.0 * se, band.min_albedo) << "white furnace, channel " << channel << ": albedo " << a << " +- " << se
                                                 << (band.known_limit ? " (known limit)" : "");
        // A known limit is held to its measured band above instead (docs/known-limits.md).
        if (c.config->expectation == host::FurnaceExpectation::energy_conserving &&
            c.view_cos >= host::furnace_tolerance_min_cos && !band.known_limit)
        {
            EXPECT_LE(std::fabs(1.0 - a), host::furnace_tolerance)
                << "white furnace, channel " << channel << ": albedo " << a << " +- " << se;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Configurations, WhiteFurnace, ::testing::ValuesIn(furnace_cases()),
                         [](const ::testing::TestParamInfo<FurnaceCase>& info) { return info.param.name(); });

// ------------------------------------------------------------------------------------------
// Reciprocity of individual lobes, compensation disabled (weight 1). The full BSDF is not
// reciprocal by design: see the comment on LobeFunction in bsdf_statistics.h.

struct ReciprocityCase
{
    std::string name;
    LobeFunction f;
    bool both_sides = false;  // light over the full sphere (transmission lobes)
    double min_value = 1e-6;  // values below are not compared (see reciprocity_cases())
};

// hemisphere_sign -1: the thin-walled transmission form of a lobe (the reflection lobe
// mirrored below the surface). A view from below is mirrored with the light, so swapping the
// two directions of a transmitted pair stays a valid query.
LobeFunction eon_lobe(glm::vec3 rho, float sigma, float hemisphere_sign = 1.0f)
{
    return [rho, sigma, hemisphere_sign](const glm::vec3& view, const glm::vec3& light) {
        const glm::vec3 mirror(1.0f, 1.0f, view.z < 0.0f ? -1.0f : 1.0f);
        const OpenPBR_DiffuseLobe lobe =
            openpbr_diffuse_lobe_init(glm::vec3(1.0f), rho, sigma, hemisphere_sign, view * mirror);
        return openpbr_diffuse_lobe_eval(lobe, view * mirror, light * mirror);
    };
}

LobeFunction microfacet_lobe(glm::vec2 alpha, OpenPBR_Fresnel fresnel, float hemisphere_sign = 1.0f)
{
    return [alpha, fresnel, hemisphere_sign](const glm::vec3& view, const glm::vec3& light) {
        const glm::vec3 mirror(1.0f, 1.0f, view.z < 0.0f ? -1.0f : 1.0f);
        const OpenPBR_MicrofacetReflectionLobe lobe = openpbr_microfacet_reflection_lobe_init(
            glm::vec3(1.0f), alpha, fresnel, OPENPBR_LOBE_ID_SPECULAR_REFLECTION, hemisphere_sign, view * mirror);
        return openpbr_microfacet_reflection_lobe_eval(lobe, view * mirror, light * mirror);
    };
}

// Rough dielectric interface (reflection and refraction with Fresnel) between n = 1 above and
// n = `ior` below. The lobe is written for throughput, so f(o, i) / n_i^2 = f(i, o) / n_o^2
// (n_i, n_o: the indices on the light's and the view's side); dividing by n_light^2 makes it
// plainly reciprocal. A view from below is evaluated in the mirrored frame with eta = 1/ior.
LobeFunction dielectric_interface_lobe(glm::vec2 alpha, float ior)
{
    return [alpha, ior](const glm::vec3& view, const glm::vec3& light) {
        const bool below = view.z < 0.0f;
        const glm::vec3 v = below ? glm::vec3(view.x, view.y, -view.z) : view;
        const glm::vec3 l = below ? glm::vec3(light.x, light.y, -light.z) : light;
        const float eta = below ? 1.0f / ior : ior;
        const OpenPBR_DielectricLobe lobe = openpbr_dielectric_lobe_init(
            glm::vec3(1.0f), glm::vec3(1.0f), alpha, glm::vec3(eta), true, OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, v);
        const float n_light = light.z > 0.0f ? 1.0f : ior;
        return openpbr_dielectric_lobe_eval(lobe, v, l) / (n_light * n_light);
    };
}

const std::vector<ReciprocityCase>& reciprocity_cases()
{
    static const std::vector<ReciprocityCase> cases = {
        {"lambert", eon_lobe(glm::vec3(0.8f), 0.0f)},
        {"eon_sigma0p5", eon_lobe(glm::vec3(0.9f, 0.5f, 0.1f), 0.5f)},
        {"eon_sigma1", eon_lobe(glm::vec3(1.0f), 1.0f)},
        {"ggx_dielectric_r0p5",
         microfacet_lobe(openpbr_ggx_alpha(0.5f, 0.0f), openpbr_make_dielectric_fresnel(1.5f, glm::vec3(1.0f)))},
        {"ggx_dielectric_inverse_eta",
         microfacet_lobe(openpbr_ggx_alpha(0.3f, 0.0f), openpbr_make_dielectric_fresnel(1.0f / 1.5f, glm::vec3(1.0f)))},
        {"ggx_dielectric_r1",
         microfacet_lobe(openpbr_ggx_alpha(1.0f, 0.0f), openpbr_make_dielectric_fresnel(1.5f, glm::vec3(1.0f)))},
        {"ggx_f82_metal", microfacet_lobe(openpbr_ggx_alpha(0.4f, 0.0f),
                                          openpbr_make_f82_fresnel(glm::vec3(0.9f, 0.6f, 0.3f), glm::vec3(0.8f, 0.9f, 1.0f),
                                                                   glm::vec3(1.0f)))},
        {"ggx_anisotropic",
         microfacet_lobe(openpbr_ggx_alpha(0.6f, 0.8f), openpbr_make_dielectric_fresnel(1.5f, glm::vec3(1.0f)))},
        // The view-from-below evaluation computes the Fresnel factor from the inside cosine,
        // which is ill-conditioned near the critical angle: rounding of 1e-7 in
        // 1 - sin^2(theta_t) = cos^2(theta_outside) is a relative error of 1e-7 / (o.h)^2. Such
        // pairs (grazing outside, o.h -> 0) only have values well below 1e-2, so smaller values
        // are not compared (on typical values of 0.1 to 10).
        {"dielectric_interface_r0p3", dielectric_interface_lobe(openpbr_ggx_alpha(0.3f, 0.0f), 1.5f), true, 1e-2},
        {"dielectric_interface_r0p8_aniso", dielectric_interface_lobe(openpbr_ggx_alpha(0.8f, 0.5f), 1.33f), true, 1e-2},
        // Thin-walled transmission: the diffuse sheet and the un-deflected rough transmission.
        {"eon_thin_walled_transmission", eon_lobe(glm::vec3(0.7f), 0.6f, -1.0f), true},
        {"ggx_thin_walled_transmission",
         microfacet_lobe(openpbr_ggx_alpha(0.4f, 0.0f), openpbr_make_constant_fresnel(glm::vec3(1.0f)), -1.0f), true},
        // Not listed: the fuzz LTC lobe, which is not reciprocal (docs/model.md).
    };
    return cases;
}

class LobeReciprocity : public ::testing::TestWithParam<ReciprocityCase>
{
};

TEST_P(LobeReciprocity, SwappingViewAndLightKeepsTheBsdf)
{
    ReciprocityOptions options;
    options.both_sides = GetParam().both_sides;
    options.min_value = GetParam().min_value;
    const ReciprocityResult result = check_reciprocity(GetParam().f, 100000, 99, options);
    EXPECT_GT(result.checked_count, 30000u);
    EXPECT_EQ(result.failure_count, 0u) << GetParam().name << ": " << result.failure_count << " of " << result.checked_count
                                        << " values differ by more than 1e-4 (relative) plus "
                                        << "rounding; largest raw relative error " << result.max_relative_error
                                        << "; worst pair " << result.worst;
}

INSTANTIATE_TEST_SUITE_P(Lobes, LobeReciprocity, ::testing::ValuesIn(reciprocity_cases()),
                         [](const ::testing::TestParamInfo<ReciprocityCase>& info) { return info.param.name; });

// ------------------------------------------------------------------------------------------
// The machinery itself: known values and a sampler with a deliberately wrong pdf.

TEST(StatisticsMachinery, IncompleteGammaKnownValues)
{
    // Q(1, x) = exp(-x); Q(1/2, x) = erfc(sqrt(x)); chi-square(1 dof) at 3.841459 is 0.05.
    for (double x : {0.01, 0.5, 1.0, 2.0, 10.0, 50.0})
    {
        EXPECT_NEAR(regularized_gamma_q(1.0, x), std::exp(-x), 1e-12 * std::max(1.0, std::exp(-x)));
        EXPECT_NEAR(regularized_gamma_q(0.5, x), std::erfc(std::sqrt(x)), 1e-12);
        EXPECT_NEAR(regularized_gamma_p(3.0, x) + regularized_gamma_q(3.0, x), 1.0, 1e-12);
    }
    EXPECT_NEAR(chi_square_p_value(3.841459, 1), 0.05, 1e-6);
    EXPECT_NEAR(chi_square_p_value(18.307038, 10), 0.05, 1e-6);
    // Even dof 2m: Q(m, x) = exp(-x) sum_{k < m} x^k / k!, summed here in log space.
    const auto poisson_tail = [](int m, double x) {
        double sum = 0.0;
        for (int k = 0; k < m; ++k)
        {
            sum += std::exp(-x + k * std::log(x) - std::lgamma(k + 1.0));
        }
        return sum;
    };
    EXPECT_NEAR(chi_square_p_value(1000.0, 1000), poisson_tail(500, 500.0), 1e-10);
    EXPECT_NEAR(chi_square_p_value(1100.0, 1000), poisson_tail(500, 550.0), 1e-10);
    EXPECT_NEAR(chi_square_p_value(30.0, 60), poisson_tail(30, 15.0), 1e-10);
    // Sidak: 100 tests at family level 0.01.
    EXPECT_NEAR(sidak_significance(0.01, 100), 1.0 - std::pow(0.99, 0.01), 1e-15);
}

TEST(StatisticsMachinery, BinomialPValue)
{
    EXPECT_NEAR(binomial_two_sided_p_value(5, 10, 0.5), 1.0, 1e-12);
    // P(X <= 1 or X >= 9) for Binomial(10, 1/2) = 22 / 1024.
    EXPECT_NEAR(binomial_two_sided_p_value(1, 10, 0.5), 22.0 / 1024.0, 1e-12);
    EXPECT_EQ(binomial_two_sided_p_value(1, 10, 0.0), 0.0);
    EXPECT_EQ(binomial_two_sided_p_value(10, 10, 1.0), 1.0);
    EXPECT_LT(binomial_two_sided_p_value(510000, 1000000, 0.5), 1e-9);
    EXPECT_GT(binomial_two_sided_p_value(500300, 1000000, 0.5), 0.5);
}

TEST(StatisticsMachinery, GaussLegendreIntegratesPolynomialsExactly)
{
    std::vector<double> nodes, weights;
    gauss_legendre(8, nodes, weights);
    for (int degree = 0; degree <= 15; ++degree)
    {
        double sum = 0.0;
        for (std::size_t i = 0; i < nodes.size(); ++i)
        {
            sum += weights[i] * std::pow(nodes[i], degree);
        }
        EXPECT_NEAR(sum, degree % 2 == 0 ? 2.0 / (degree + 1) : 0.0, 1e-13) << "degree " << degree;
    }
}

SamplingTarget cosine_target(bool wrong_pdf)
{
    SamplingTarget target;
    target.name = wrong_pdf ? "cosine sampler, uniform pdf" : "cosine sampler";
    target.frame = openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
    target.sample = [](const glm::vec3& u) {
        DirectionSample s;
        s.direction = openpbr_sample_cosine_hemisphere(glm::vec2(u.x, u.y));
        s.pdf = openpbr_cosine_hemisphere_pdf(s.direction.z);
        s.lobe_type = s.pdf > 0.0 ? OPENPBR_LOBE_TYPE_REFLECTION | OPENPBR_LOBE_TYPE_DIFFUSE : OPENPBR_LOBE_TYPE_NONE;
        return s;
    };
    target.pdf = [wrong_pdf](const glm::vec3& d) {
        return d.z > 0.0f ? (wrong_pdf ? 1.0 / (2.0 * 3.14159265358979) : d.z / 3.14159265358979) : 0.0;
    };
    return target;
}

// The furnace's escalation (IndependentAlbedoSampler) continues each chunk where the smaller
// count stopped: every estimate must be estimate_albedo's at that count, bit for bit, through
// a change of chunk count (2^20: 128 chunks, 2^21 and up: 256) and a continuation (2^21 ->
// 2^23). Weights vary per sample (the cosine sampler weighted by its own random numbers), so a
// sample drawn twice or skipped changes the sums.
TEST(StatisticsMachinery, EscalatingSamplerKeepsEstimateAlbedosSamples)
{
    SamplingTarget target = cosine_target(false);
    target.sample = [](const glm::vec3& u) {
        DirectionSample s;
        s.direction = openpbr_sample_cosine_hemisphere(glm::vec2(u.x, u.y));
        s.pdf = openpbr_cosine_hemisphere_pdf(s.direction.z);
        s.lobe_type = OPENPBR_LOBE_TYPE_REFLECTION | OPENPBR_LOBE_TYPE_DIFFUSE;
        s.weight.diffuse = glm::vec3(u.z, 1.0f - u.z, u.x * u.y);
        return s;
    };
    IndependentAlbedoSampler escalating(target, 7);
    for (const std::uint64_t samples : {std::uint64_t(1) << 20, std::uint64_t(1) << 21, std::uint64_t(1) << 23})
    {
        const AlbedoEstimate kept = escalating.estimate(samples);
        const AlbedoEstimate fresh = estimate_albedo(target, samples, 7, SamplerKind::independent);
        EXPECT_EQ(kept.sample_count, samples);
        for (int channel = 0; channel < 3; ++channel)
        {
            EXPECT_EQ(kept.mean[channel], fresh.mean[channel]) << samples << " samples, channel " << channel;
            EXPECT_EQ(kept.standard_error[channel], fresh.standard_error[channel]) << samples << " samples";
            EXPECT_EQ(kept.max_weight[channel], fresh.max_weight[channel]) << samples << " samples";
        }
    }
}

TEST(StatisticsMachinery, ChiSquareAcceptsCorrectAndRejectsWrongPdf)
{
    ChiSquareOptions options;
    options.sample_count = 200000;
    const ChiSquareResult good = run_chi_square_test(cosine_target(false), options);
    EXPECT_GT(good.p_value, 1e-3) << good.report;
    EXPECT_NEAR(good.pdf_integral, 1.0, 1e-6);
    const ChiSquareResult bad = run_chi_square_test(cosine_target(true), options);
    EXPECT_LT(bad.p_value, 1e-12) << bad.report;
}

// Sampling a GGX lobe of alpha 0.25 against the pdf of alpha 0.27: a subtle shape error.
TEST(StatisticsMachinery, ChiSquareDetectsASlightlyWrongRoughness)
{
    const glm::vec3 view = glm::normalize(glm::vec3(0.5f, 0.1f, 0.7f));
    const OpenPBR_Fresnel fresnel = openpbr_make_dielectric_fresnel(1.5f, glm::vec3(1.0f));
    const OpenPBR_MicrofacetReflectionLobe sampled = openpbr_microfacet_reflection_lobe_init(
        glm::vec3(1.0f), glm::vec2(0.25f), fresnel, OPENPBR_LOBE_ID_SPECULAR_REFLECTION, 1.0f, view);
    const OpenPBR_MicrofacetReflectionLobe reported = openpbr_microfacet_reflection_lobe_init(
        glm::vec3(1.0f), glm::vec2(0.27f), fresnel, OPENPBR_LOBE_ID_SPECULAR_REFLECTION, 1.0f, view);
    SamplingTarget target;
    target.name = "ggx 0.25 sampled, 0.27 pdf";
    target.frame = openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
    target.sample = [sampled, reported, view](const glm::vec3& u) {
        const OpenPBR_LobeSample ls = openpbr_microfacet_reflection_lobe_sample(sampled, view, glm::vec2(u.x, u.y));
        DirectionSample s;
        s.direction = ls.direction;
        s.lobe_type = ls.lobe_type;
        s.pdf = ls.lobe_type != OPENPBR_LOBE_TYPE_NONE ? openpbr_microfacet_reflection_lobe_pdf(reported, view, ls.direction)
                                                       : 0.0;
        return s;
    };
    target.pdf = [reported, view](const glm::vec3& d) {
        return double(openpbr_microfacet_reflection_lobe_pdf(reported, view, d));
    };
    ChiSquareOptions options;
    options.sample_count = 200000;
    const ChiSquareResult result = run_chi_square_test(target, options);
    EXPECT_LT(result.p_value, 1e-6) << result.report;
}

TEST(StatisticsMachinery, ChiSquareRejectsMissingDeltaProbability)
{
    // Half of the samples are a delta atom whose probability the target does not declare.
    SamplingTarget target = cosine_target(false);
    const auto continuous = target.sample;
    target.sample = [continuous](const glm::vec3& u) {
        if (u.z < 0.5f)
        {
            DirectionSample s;
            s.direction = glm::vec3(0.0f, 0.0f, -1.0f);
            s.pdf = 0.5;
            s.lobe_type = OPENPBR_LOBE_TYPE_TRANSMISSION | OPENPBR_LOBE_TYPE_SPECULAR;
            return s;
        }
        return continuous(u);
    };
    ChiSquareOptions options;
    options.sample_count = 100000;
    const ChiSquareResult result = run_chi_square_test(target, options);
    EXPECT_LT(result.p_value, 1e-12) << result.report;  // the continuous half is over-expected
    EXPECT_LT(result.delta_p_value, 1e-12) << result.report;
    EXPECT_FALSE(result.delta_pdfs_consistent);
}

// The warped polar grid integrates the pdf of a GGX reflection lobe of alpha 2e-3 (twice the
// delta threshold, view along the normal) to 1 - alpha^2 / (1 + alpha^2), the visible normals
// tilted by less than 45 degrees (the others reflect below the horizon), measured to within
// 2.0e-7 (the pdf's jump at the horizon, which crosses coarse outer cells), held to 5e-7: a
// quarter of the binomial standard error of the continuous fraction at 1e6 samples (2e-6). The
// surface grid, whose pole cells are 0.35 rad wide, integrates 0.4255 of it.
TEST(StatisticsMachinery, WarpedGridIntegratesANarrowLobe)
{
    const glm::vec3 view(0.0f, 0.0f, 1.0f);
    const OpenPBR_MicrofacetReflectionLobe lobe = openpbr_microfacet_reflection_lobe_init(
        glm::vec3(1.0f), glm::vec2(2e-3f), openpbr_make_dielectric_fresnel(1.5f, glm::vec3(1.0f)),
        OPENPBR_LOBE_ID_SPECULAR_REFLECTION, 1.0f, view);
    SamplingTarget target;
    target.name = "ggx alpha 2e-3";
    target.frame = openpbr_make_basis(view);
    target.pdf = [lobe, view](const glm::vec3& d) { return double(openpbr_microfacet_reflection_lobe_pdf(lobe, view, d)); };
    const auto integral = [](const SamplingTarget& t) {
        double sum = 0.0;
        for (const double cell : integrate_pdf_over_grid(t, SphereGridOptions()))
        {
            sum += cell;
        }
        return sum;
    };
    const double surface_grid = integral(target);
    target.polar_scale = 2e-3;
    const double warped_grid = integral(target);
    const double a2 = 2e-3 * 2e-3;
    EXPECT_NEAR(warped_grid, 1.0 - a2 / (1.0 + a2), 5e-7);
    EXPECT_LT(surface_grid, 0.9) << "the surface grid resolves the lobe: the test lost its point";
}

// The share of delta samples of a collapsed refraction (transmission-only form, relative IOR
// 0.99, alpha 0.04, view along the normal) is the visible-normal mass inside the critical angle:
// at normal incidence the visible normals are distributed as D(h) cos theta_h, whose GGX mass
// beyond theta_c is alpha^2 / (alpha^2 + tan^2 theta_c), 3.2486e-5 with sin theta_c = 0.99.
// The quadrature is 4.3e-7 under it (measured: the integrand jumps at the critical angle), held
// to 1e-6: a sixth of the binomial standard error of that deficit at 1e6 samples (5.7e-6).
TEST(StatisticsMachinery, DeltaShareOfACollapsedRefraction)
{
    const glm::vec3 view(0.0f, 0.0f, 1.0f);
    const float alpha = 0.04f;
    const float eta = 0.99f;
    const OpenPBR_DielectricLobe lobe =
        openpbr_dielectric_lobe_init(glm::vec3(1.0f), glm::vec3(1.0f), glm::vec2(alpha), glm::vec3(eta), false,
                                     OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, view);
    ASSERT_TRUE(lobe.transmission_is_delta && !lobe.is_delta);
    const double tan2_critical = double(eta) * eta / (1.0 - double(eta) * eta);
    const double a2 = double(alpha) * alpha;
    EXPECT_NEAR(1.0 - dielectric_delta_share(lobe, view), a2 / (a2 + tan2_critical), 1e-6);
    const OpenPBR_DielectricLobe matched =
        openpbr_dielectric_lobe_init(glm::vec3(1.0f), glm::vec3(1.0f), glm::vec2(alpha), glm::vec3(1.0f), true,
                                     OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION, view);
    EXPECT_EQ(dielectric_delta_share(matched, view), 1.0);
}

// At relative IOR 0.99, roughness 0.5, view cos 1 (a refracted lobe 2.4e-3 rad wide), sampling
// the BSDF against the pdf of a refracted lobe 10% wider (alpha x 1.1: roughness x sqrt(1.1))
// is rejected on the warped grid: measured chi2 = 12573 for 1025 degrees of freedom (p = 0).
TEST(StatisticsMachinery, ChiSquareDetectsATenPercentWiderRefractionNearIndexMatching)
{
    OpenPBR_ResolvedInputs inputs = defaults();
    inputs.transmission_weight = 1.0f;
    inputs.specular_roughness = 0.5f;
    inputs.specular_ior = 0.99f;
    const glm::vec3 view(0.0f, 0.0f, 1.0f);
    const OpenPBR_PreparedBsdf sampled = openpbr_prepare(inputs, view);
    inputs.specular_roughness = 0.5f * std::sqrt(1.1f);
    const OpenPBR_PreparedBsdf reported = openpbr_prepare(inputs, view);
    SamplingTarget target = make_bsdf_target(sampled, "ior 0.99, pdf of a 10% wider refraction");
    ASSERT_GT(target.polar_scale, 0.0);
    target.pdf = [reported](const glm::vec3& d) { return double(openpbr_pdf(reported, d)); };
    ChiSquareOptions options;
    options.sample_count = 1000000;
    const ChiSquareResult result = run_chi_square_test(target, options);
    EXPECT_LT(result.p_value, 1e-6) << result.report;
}

TEST(StatisticsMachinery, ConsistencyDetectsSmallWeightAndPdfErrors)
{
    const OpenPBR_PreparedBsdf bsdf =
        openpbr_prepare(openpbr_make_default_resolved_inputs(), glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)));
    ConsistencyOptions options;
    options.sample_count = 20000;
    const SamplingTarget exact = make_bsdf_target(bsdf);
    EXPECT_TRUE(check_sample_consistency(exact, options).ok());
    SamplingTarget wrong_weight = exact;
    wrong_weight.sample = [exact](const glm::vec3& u) {
        DirectionSample s = exact.sample(u);
        s.weight.diffuse *= 1.0003f;
        return s;
    };
    EXPECT_GT(check_sample_consistency(wrong_weight, options).weight_mismatch_count, 1000u);
    SamplingTarget wrong_pdf = exact;
    wrong_pdf.pdf = [exact](const glm::vec3& d) { return exact.pdf(d) * 1.0003; };
    EXPECT_GT(check_sample_consistency(wrong_pdf, options).pdf_mismatch_count, 1000u);
    SamplingTarget negative = exact;
    negative.sample = [exact](const glm::vec3& u) {
        DirectionSample s = exact.sample(u);
        s.weight.specular.y = -1e-9f;
        return s;
    };
    EXPECT_GT(check_sample_consistency(negative, options).invalid_value_count, 1000u);
}

TEST(StatisticsMachinery, RandomNumbersAreDeterministicAndUniform)
{
    RandomStream a(42, 3), b(42, 3), c(42, 4);
    bool differs = false;
    double sum = 0.0;
    for (int i = 0; i < 100000; ++i)
    {
        const float x = a.next_float();
        EXPECT_EQ(x, b.next_float());
        differs = differs || (x != c.next_float());
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
        sum += x;
    }
    EXPECT_TRUE(differs);
    EXPECT_NEAR(sum / 100000.0, 0.5, 0.005);
    const openpbr::host::ShiftedR3Sequence sequence(5);
    glm::dvec3 mean(0.0);
    for (int i = 0; i < 4096; ++i)
    {
        const std::array<float, 3> point = sequence.point(static_cast<std::uint64_t>(i));
        const glm::vec3 u(point[0], point[1], point[2]);
        ASSERT_TRUE(u.x >= 0.0f && u.x < 1.0f && u.y >= 0.0f && u.y < 1.0f && u.z >= 0.0f && u.z < 1.0f);
        mean += glm::dvec3(u);
    }
    mean /= 4096.0;
    EXPECT_NEAR(mean.x, 0.5, 1e-3);  // low discrepancy: far closer than 1/sqrt(N)
    EXPECT_NEAR(mean.y, 0.5, 1e-3);
    EXPECT_NEAR(mean.z, 0.5, 1e-3);
}

}  // namespace
