// Feature toggles: what a material needs, and that a pipeline specialized to that set renders
// it exactly like the full pipeline (CPU: bit-identical; lavapipe: max relative error <= 1e-6),
// while a set that lacks a needed feature is refused.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "host/studies/bench_specialization.h"
#include "host/checks/conformance.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"
#include "host/gpu/vulkan_runner.h"
#include "slang/openpbr.h"

namespace {

using openpbr::host::Material;

const std::vector<Material>& library()
{
    static const std::vector<Material> materials = openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR);
    return materials;
}

// ---- Toggle set per material ----------------------------------------------------------------

struct DerivationCase
{
    const char* name;
    void (*modify)(openpbr::OpenPBR_ResolvedInputs&);
    std::uint32_t expected;
};

class FeatureDerivation : public ::testing::TestWithParam<DerivationCase>
{
};

TEST_P(FeatureDerivation, NeedsExactlyTheEffectsInUse)
{
    openpbr::OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    GetParam().modify(inputs);
    EXPECT_EQ(openpbr::host::required_feature_mask(inputs), GetParam().expected)
        << openpbr::host::feature_set_label(openpbr::host::required_feature_mask(inputs));
}

std::string derivation_name(const ::testing::TestParamInfo<DerivationCase>& info)
{
    std::string name;
    for (const char* c = info.param.name; *c != 0; ++c)
    {
        name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
    }
    return name;
}

INSTANTIATE_TEST_SUITE_P(
    Table, FeatureDerivation,
    ::testing::Values(
        DerivationCase{"defaults", [](openpbr::OpenPBR_ResolvedInputs&) {}, 0u},
        DerivationCase{"coat", [](openpbr::OpenPBR_ResolvedInputs& i) { i.coat_weight = 0.5f; }, OPENPBR_FEATURE_BIT_COAT},
        DerivationCase{"fuzz", [](openpbr::OpenPBR_ResolvedInputs& i) { i.fuzz_weight = 1.0f; }, OPENPBR_FEATURE_BIT_FUZZ},
        DerivationCase{"metal", [](openpbr::OpenPBR_ResolvedInputs& i) { i.base_metalness = 1.0f; },
                       OPENPBR_FEATURE_BIT_METAL},
        DerivationCase{"transmission", [](openpbr::OpenPBR_ResolvedInputs& i) { i.transmission_weight = 1.0f; },
                       OPENPBR_FEATURE_BIT_TRANSMISSION},
        DerivationCase{"dispersion",
                       [](openpbr::OpenPBR_ResolvedInputs& i) {
                           i.transmission_weight = 1.0f;
                           i.transmission_dispersion_scale = 0.5f;
                       },
                       OPENPBR_FEATURE_BIT_TRANSMISSION | OPENPBR_FEATURE_BIT_DISPERSION},
        DerivationCase{"thin film", [](openpbr::OpenPBR_ResolvedInputs& i) { i.thin_film_weight = 1.0f; },
                       OPENPBR_FEATURE_BIT_THIN_FILM},
        DerivationCase{"thin-walled", [](openpbr::OpenPBR_ResolvedInputs& i) { i.geometry_thin_walled = true; },
                       OPENPBR_FEATURE_BIT_THIN_WALLED},
        DerivationCase{"subsurface", [](openpbr::OpenPBR_ResolvedInputs& i) { i.subsurface_weight = 0.3f; },
                       OPENPBR_FEATURE_BIT_SUBSURFACE},
        DerivationCase{"emission", [](openpbr::OpenPBR_ResolvedInputs& i) { i.emission_luminance = 100.0f; },
                       OPENPBR_FEATURE_BIT_EMISSION},
        DerivationCase{"specular anisotropy",
                       [](openpbr::OpenPBR_ResolvedInputs& i) { i.specular_roughness_anisotropy = 0.5f; },
                       OPENPBR_FEATURE_BIT_ANISOTROPY},
        DerivationCase{"coat anisotropy",
                       [](openpbr::OpenPBR_ResolvedInputs& i) {
                           i.coat_weight = 1.0f;
                           i.coat_roughness_anisotropy = 0.5f;
                       },
                       OPENPBR_FEATURE_BIT_COAT | OPENPBR_FEATURE_BIT_ANISOTROPY},
        // The input contract runs first: NaN is the default (0), a negative weight clamps to 0.
        DerivationCase{"NaN coat", [](openpbr::OpenPBR_ResolvedInputs& i) { i.coat_weight = std::nanf(""); }, 0u},
        DerivationCase{"negative fuzz", [](openpbr::OpenPBR_ResolvedInputs& i) { i.fuzz_weight = -1.0f; }, 0u}),
    derivation_name);

TEST(FeatureScene, BundledGlassAndGoldNeedTransmissionAndMetal)
{
    std::uint32_t glass = 0;
    std::uint32_t gold = 0;
    for (const Material& material : library())
    {
        glass |= material.name == "Glass" ? openpbr::host::required_feature_mask(material) : 0u;
        gold |= material.name == "Gold" ? openpbr::host::required_feature_mask(material) : 0u;
    }
    EXPECT_NE(glass & OPENPBR_FEATURE_BIT_TRANSMISSION, 0u);
    EXPECT_NE(gold & OPENPBR_FEATURE_BIT_METAL, 0u);
    const std::uint32_t scene = openpbr::host::scene_feature_mask(library());
    EXPECT_EQ(scene & (glass | gold), glass | gold);
}

TEST(FeatureScene, SpecializationInfoHasOneBoolPerStableId)
{
    const std::uint32_t mask = OPENPBR_FEATURE_BIT_COAT | OPENPBR_FEATURE_BIT_THIN_FILM;
    const std::vector<openpbr::host::SpecializationConstant> constants = openpbr::host::specialization_constants(mask);
    ASSERT_EQ(constants.size(), openpbr::host::feature_toggles().size());
    for (std::size_t k = 0; k < constants.size(); ++k)
    {
        EXPECT_EQ(constants[k].id, k);
        EXPECT_EQ(constants[k].value_bits, ((mask >> k) & 1u) ? 1u : 0u) << "constant " << k;
    }
    const nlohmann::json info = openpbr::host::specialization_info_json(mask);
    EXPECT_EQ(info["mapEntries"][5]["offset"], 20);
    EXPECT_EQ(info["data"][5], 1);
    EXPECT_EQ(info["data"][1], 0);
    EXPECT_EQ(openpbr::host::parse_feature_names(openpbr::host::feature_names(mask)), mask);
    EXPECT_THROW(openpbr::host::parse_feature_names({"sheen"}), std::invalid_argument);
}

// ---- Refusal ------------------------------------------------------------------------------------

TEST(FeatureRefusal, WrongToggleSetNamesMaterialAndFeature)
{
    std::vector<Material> glass;
    for (const Material& material : library())
    {
        if (material.name == "Glass")
        {
            glass.push_back(material);
        }
    }
    ASSERT_EQ(glass.size(), 1u);
    const std::uint32_t needs = openpbr::host::required_feature_mask(glass[0]);
    EXPECT_NO_THROW(openpbr::host::check_pipeline_supports(glass, needs));
    try
    {
        openpbr::host::check_pipeline_supports(glass, needs & ~OPENPBR_FEATURE_BIT_TRANSMISSION);
        FAIL() << "a pipeline without transmission was accepted for Glass";
    }
    catch (const openpbr::host::FeatureError& error)
    {
        const std::string message = error.what();
        EXPECT_NE(message.find("Glass"), std::string::npos) << message;
        EXPECT_NE(message.find("transmission"), std::string::npos) << message;
    }
}

// ---- CPU: specialized equals full, bit for bit ---------------------------------------------------

std::vector<float> queries_for_one_material(std::size_t count, std::uint64_t seed)
{
    return openpbr::host::make_queries(count, 1, seed);
}

bool bit_identical(const std::vector<float>& a, const std::vector<float>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::vector<std::string> library_names()
{
    std::vector<std::string> names;
    for (const Material& material : library())
    {
        names.push_back(material.name);
    }
    return names;
}

const Material& material_named(const std::string& name)
{
    for (const Material& material : library())
    {
        if (material.name == name)
        {
            return material;
        }
    }
    throw std::invalid_argument("no bundled material " + name);
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info)
{
    std::string name;
    for (const char c : info.param)
    {
        name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    }
    return name;
}

class CpuSpecialization : public ::testing::TestWithParam<std::string>
{
};

TEST_P(CpuSpecialization, RunTimeTogglesMatchFullBitForBit)
{
    const Material& material = material_named(GetParam());
    const std::vector<float> packed = openpbr::host::pack_materials({material});
    const std::vector<float> queries = queries_for_one_material(4096, 11);
    const std::uint32_t needs = openpbr::host::required_feature_mask(material);
    std::vector<float> full;
    {
        const openpbr::host::ScopedFeatureMask scope(openpbr::host::full_feature_mask());
        full = openpbr::host::run_conformance_cpu(queries, packed);
    }
    std::vector<float> specialized;
    {
        const openpbr::host::ScopedFeatureMask scope(needs);
        specialized = openpbr::host::run_conformance_cpu(queries, packed);
    }
    EXPECT_TRUE(bit_identical(full, specialized)) << openpbr::host::feature_set_label(needs);
    // The set is the smallest: switching off any one needed feature changes the output.
    for (const std::string& name : openpbr::host::feature_names(needs))
    {
        const openpbr::host::ScopedFeatureMask scope(needs & ~openpbr::host::parse_feature_names({name}));
        EXPECT_FALSE(bit_identical(full, openpbr::host::run_conformance_cpu(queries, packed)))
            << "switching off " << name << " changed nothing";
    }
}

INSTANTIATE_TEST_SUITE_P(Bundled, CpuSpecialization, ::testing::ValuesIn(library_names()), test_name);

// The bundled materials that need only the base layer.
std::vector<std::string> base_only_names()
{
    std::vector<std::string> names;
    for (const Material& material : library())
    {
        if (openpbr::host::required_feature_mask(material) == 0)
        {
            names.push_back(material.name);
        }
    }
    return names;
}

class CpuCompileTimeBaseOnly : public ::testing::TestWithParam<std::string>
{
};

TEST_P(CpuCompileTimeBaseOnly, MatchesFullBitForBit)
{
    const Material& material = material_named(GetParam());
    ASSERT_EQ(openpbr::host::required_feature_mask(material), 0u);
    const std::vector<float> packed = openpbr::host::pack_materials({material});
    const std::vector<float> queries = queries_for_one_material(4096, 12);
    EXPECT_TRUE(bit_identical(openpbr::host::run_conformance_cpu(queries, packed),
                              openpbr::host::run_conformance_cpu_base_only(queries, packed)));
}

INSTANTIATE_TEST_SUITE_P(Bundled, CpuCompileTimeBaseOnly, ::testing::ValuesIn(base_only_names()), test_name);

TEST(CpuSpecializationBaseOnly, DefaultMaterialMatchesFullBitForBit)
{
    const std::vector<float> packed = openpbr::host::pack_materials({openpbr::host::default_material()});
    const std::vector<float> queries = queries_for_one_material(4096, 13);
    EXPECT_TRUE(bit_identical(openpbr::host::run_conformance_cpu(queries, packed),
                              openpbr::host::run_conformance_cpu_base_only(queries, packed)));
}

// ---- lavapipe: specialized pipelines against the full one ---------------------------------------

double relative_error(float a, float b) { return std::fabs(double(a) - double(b)) / std::max(std::fabs(double(b)), 1e-3); }

class GpuSpecialization : public ::testing::TestWithParam<std::string>
{
  protected:
    static std::optional<openpbr::host::VulkanContext> make_context(std::string& error)
    {
        return openpbr::host::VulkanContext::create(openpbr::host::VulkanOptions{}, &error);
    }
};

TEST_P(GpuSpecialization, PerMaterialPipelinesMatchFullPipeline)
{
    std::string error;
    std::optional<openpbr::host::VulkanContext> context = make_context(error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    const std::vector<Material>& materials = library();
    const std::vector<float> queries = openpbr::host::make_queries(materials.size() * 256, materials.size(), 5);
    const openpbr::host::SpecializedConformanceRun full = openpbr::host::run_conformance_gpu_specialized(
        GetParam(), *context, queries, materials, OPENPBR_KERNEL_DIR, openpbr::host::full_feature_mask(), 1);
    const openpbr::host::SpecializedConformanceRun specialized = openpbr::host::run_conformance_gpu_specialized(
        GetParam(), *context, queries, materials, OPENPBR_KERNEL_DIR, std::nullopt, 1);
    EXPECT_EQ(full.pipeline_builds, 1u);
    EXPECT_GT(specialized.pipeline_builds, 1u);
    ASSERT_EQ(full.results.size(), specialized.results.size());
    double worst = 0.0;
    std::size_t worst_index = 0;
    for (std::size_t i = 0; i < full.results.size(); ++i)
    {
        const double e = relative_error(specialized.results[i], full.results[i]);
        const double error_value = std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
        if (error_value > worst)
        {
            worst = error_value;
            worst_index = i;
        }
    }
    constexpr std::size_t result_floats = 24;  // OPENPBR_RESULT_FLOATS of the conformance kernel
    EXPECT_LE(worst, 1e-6) << "output " << worst_index % result_floats << " of query " << worst_index / result_floats
                           << ": specialized " << specialized.results[worst_index] << ", full " << full.results[worst_index];
}

TEST_P(GpuSpecialization, PipelineCacheBuildsEachSetOnceAndRefusesWrongSet)
{
    std::string error;
    std::optional<openpbr::host::VulkanContext> context = make_context(error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    std::vector<Material> gold;
    for (const Material& material : library())
    {
        if (material.name == "Gold")
        {
            gold.push_back(material);
        }
    }
    ASSERT_EQ(gold.size(), 1u);
    const std::vector<float> queries = openpbr::host::make_queries(64, 1, 3);
    EXPECT_THROW(openpbr::host::run_conformance_gpu_specialized(GetParam(), *context, queries, gold, OPENPBR_KERNEL_DIR,
                                                                std::uint32_t(0), 1),
                 openpbr::host::FeatureError);
    openpbr::host::ComputePipelineDescription description;
    description.spirv_words = openpbr::host::load_spirv_file(
        std::string(OPENPBR_KERNEL_DIR) + (GetParam() == "glsl-spirv" ? "/conformance.glsl.spv" : "/conformance.slang.spv"));
    description.bindings = {{0, false}, {1, false}, {2, false}, {3, false}, {4, false}, {5, false}};
    openpbr::host::SpecializedPipelineCache cache(*context, description);
    openpbr::host::ComputePipeline& first = cache.pipeline(OPENPBR_FEATURE_BIT_METAL);
    openpbr::host::ComputePipeline& again = cache.pipeline(OPENPBR_FEATURE_BIT_METAL);
    EXPECT_EQ(&first, &again);
    EXPECT_EQ(cache.build_count(), 1u);
    cache.pipeline(0);
    EXPECT_EQ(cache.build_count(), 2u);
}

INSTANTIATE_TEST_SUITE_P(Paths, GpuSpecialization, ::testing::Values("slang-spirv", "glsl-spirv"), test_name);

// Both SPIR-V kernels declare every toggle (and the legacy aliases) at its stable constant id.
class KernelSpecIds : public ::testing::TestWithParam<std::string>
{
};

TEST_P(KernelSpecIds, EveryToggleHasItsStableId)
{
    const std::vector<std::uint32_t> words =
        openpbr::host::load_spirv_file(std::string(OPENPBR_KERNEL_DIR) + "/" + GetParam());
    std::vector<bool> seen(OPENPBR_SPECIALIZATION_CONSTANT_COUNT, false);
    constexpr std::uint32_t op_decorate = 71;
    constexpr std::uint32_t decoration_spec_id = 1;
    for (std::size_t at = 5; at < words.size();)
    {
        const std::uint32_t count = words[at] >> 16;
        if (count == 0)
        {
            break;
        }
        if ((words[at] & 0xffffu) == op_decorate && count == 4 && words[at + 2] == decoration_spec_id &&
            words[at + 3] < seen.size())
        {
            seen[words[at + 3]] = true;
        }
        at += count;
    }
    for (std::size_t id = 0; id < seen.size(); ++id)
    {
        EXPECT_TRUE(seen[id]) << "no SpecId " << id;
    }
}

INSTANTIATE_TEST_SUITE_P(Kernels, KernelSpecIds, ::testing::Values("conformance.slang.spv", "conformance.glsl.spv"),
                         test_name);

}  // namespace
