// The hard-case corpus (tests/data/stability_corpus.json) on the CPU build and on every GPU path:
// no non-finite or negative output, and no energy gain (mean sample weight <= 1.005 per case and
// channel) anywhere. Each path is its own test so that ctest, which runs every test in its own
// process, computes each path once: the CPU with 200000 samples per case, GPU paths (lavapipe
// on machines without a GPU) with 10000, a prefix of the CPU's query stream (lavapipe runs at
// about 1M queries/s on two cores). The energy bound allows three standard
// errors of the mean on top of 1.005 (for deterministic delta cases the standard error is 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/checks/stability.h"
#include "host/scene/material_library.h"

namespace {

using openpbr::host::StabilityCase;
using openpbr::host::StabilityCaseResult;
using openpbr::host::StabilityOptions;
using openpbr::host::StabilityPathResult;
using openpbr::host::StabilityReport;

constexpr double max_mean_weight = 1.005;
constexpr std::size_t default_cpu_samples_per_case = 200000;
constexpr std::size_t gpu_samples_per_case = 10000;
// The WebGPU paths (SwiftShader in CI) take fewer: 2000 per case keeps the corpus (187 cases,
// about 0.37M queries) inside one batch of the stability runner (1.3M queries), so one Node
// process and one pipeline build (SwiftShader: 40-65 s on the loaded 2-core machine, where
// the dispatch itself ran at 20-50 us per query). The energy check's three standard errors
// scale with the sample count, so the check stays as strict in what it can assert.
constexpr std::size_t webgpu_samples_per_case = 2000;

const std::vector<StabilityCase>& corpus()
{
    static const std::vector<StabilityCase> cases = openpbr::host::load_stability_corpus(OPENPBR_STABILITY_CORPUS);
    return cases;
}

// OPENPBR_STABILITY_CPU_SAMPLES overrides the CPU sample count, e.g. for sanitizer builds.
std::size_t cpu_samples_per_case()
{
    const char* text = std::getenv("OPENPBR_STABILITY_CPU_SAMPLES");
    return text && *text ? std::size_t(std::strtoull(text, nullptr, 10)) : default_cpu_samples_per_case;
}

std::string describe_case(const std::string& name)
{
    for (const StabilityCase& stability_case : corpus())
    {
        if (stability_case.name == name)
        {
            std::ostringstream text;
            text << name << " (" << stability_case.description << "; view " << stability_case.view.x << ", "
                 << stability_case.view.y << ", " << stability_case.view.z << "; inputs:";
            for (const std::string& input : stability_case.inputs_set)
            {
                text << " " << input;
            }
            text << ")";
            return text.str();
        }
    }
    return name;
}

std::string describe_violations(const StabilityCaseResult& result)
{
    std::ostringstream text;
    for (const auto& record : result.violations)
    {
        text << "\n  " << record.what << " at query " << record.query << ": view (" << record.view[0] << ", "
             << record.view[1] << ", " << record.view[2] << ") light (" << record.light[0] << ", " << record.light[1] << ", "
             << record.light[2] << ") u (" << record.u[0] << ", " << record.u[1] << ", " << record.u[2] << ") outputs:";
        for (const float value : record.outputs)
        {
            text << " " << value;
        }
    }
    return text.str();
}

StabilityReport run_one_path(const std::string& path, std::size_t samples)
{
    StabilityOptions options;
    options.samples_per_case = samples;
    options.kernel_directory = OPENPBR_KERNEL_DIR;
    options.paths = {path};
    options.validation = path != "cpu";
    return openpbr::host::run_stability(corpus(), options);
}

TEST(StabilityCorpus, LoadsAndCoversEveryInputName)
{
    ASSERT_GE(corpus().size(), 60u);
    const std::vector<std::string> names = openpbr::host::stability_input_names();
    for (const std::string& input : openpbr::host::supported_input_names())
    {
        EXPECT_NE(std::find(names.begin(), names.end(), input), names.end()) << input;
    }
    // Every input name appears in at least one case.
    std::set<std::string> used;
    for (const StabilityCase& stability_case : corpus())
    {
        used.insert(stability_case.inputs_set.begin(), stability_case.inputs_set.end());
        EXPECT_FALSE(stability_case.lights.empty()) << stability_case.name;
    }
    for (const std::string& input : names)
    {
        EXPECT_TRUE(used.count(input)) << "no corpus case sets " << input;
    }
}

TEST(StabilityCorpus, ParsesSpecialValuesAndNormalizesLights)
{
    const auto document = nlohmann::json::parse(R"({"cases": [{"name": "special",
        "material": {"base_weight": "nan", "specular_ior": "inf", "coat_ior": "-inf", "fuzz_weight": "denorm",
                     "coat_weight": "-denorm", "base_color": [1, "nan", 0.5], "geometry_thin_walled": true,
                     "specular_anisotropy_rotation": [0, 1], "geometry_normal": [0, 0, 2]},
        "view": [3, 0, 4], "lights": [[0, 0, 5], [0, 0, 0], ["nan", 0, 1]]}]})");
    const std::vector<StabilityCase> cases = openpbr::host::parse_stability_corpus(document, "inline");
    ASSERT_EQ(cases.size(), 1u);
    const auto& inputs = cases[0].inputs;
    EXPECT_TRUE(std::isnan(inputs.base_weight));
    EXPECT_EQ(inputs.specular_ior, std::numeric_limits<float>::infinity());
    EXPECT_EQ(inputs.coat_ior, -std::numeric_limits<float>::infinity());
    EXPECT_EQ(inputs.fuzz_weight, 1e-40f);
    EXPECT_EQ(inputs.coat_weight, -1e-40f);
    EXPECT_TRUE(std::isnan(inputs.base_color.y));
    EXPECT_TRUE(inputs.geometry_thin_walled);
    EXPECT_EQ(inputs.specular_anisotropy_rotation, glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(inputs.geometry_basis.normal, glm::vec3(0.0f, 0.0f, 2.0f));  // raw: the contract normalizes
    EXPECT_EQ(cases[0].view, glm::vec3(3.0f, 0.0f, 4.0f));                 // raw: prepare normalizes
    EXPECT_EQ(cases[0].lights[0], glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(cases[0].lights[1], glm::vec3(0.0f));
    EXPECT_TRUE(std::isnan(cases[0].lights[2].x));
}

// Bad corpora fail with a message naming the source, the case and the field.
TEST(StabilityCorpus, ErrorsNameFileCaseAndField)
{
    struct BadCorpus
    {
        const char* json;
        std::vector<std::string> expected;
    };
    const BadCorpus bad[] = {
        {R"({"cases": [{"name": "a", "material": {"base_colour": [1, 1, 1]}, "view": [0, 0, 1], "lights": [[0, 0, 1]]}]})",
         {"corpus.json", "case 'a'", "material.base_colour", "unknown OpenPBR input name"}},
        {R"({"cases": [{"name": "b", "material": {"base_color": 0.5}, "view": [0, 0, 1], "lights": [[0, 0, 1]]}]})",
         {"case 'b'", "material.base_color", "color3"}},
        {R"({"cases": [{"name": "c", "material": {"base_weight": "big"}, "view": [0, 0, 1], "lights": [[0, 0, 1]]}]})",
         {"case 'c'", "material.base_weight", "\"big\""}},
        {R"({"cases": [{"name": "d", "material": {"geometry_thin_walled": 1}, "view": [0, 0, 1], "lights": [[0, 0, 1]]}]})",
         {"case 'd'", "geometry_thin_walled", "boolean"}},
        {R"({"cases": [{"name": "e", "material": {}, "view": [0, 1], "lights": [[0, 0, 1]]}]})", {"case 'e'", "'view'"}},
        {R"({"cases": [{"name": "f", "material": {}, "view": [0, 0, 1], "lights": [[0, 0, 1], [1, 2]]}]})",
         {"case 'f'", "lights[1]"}},
        {R"({"cases": [{"name": "g", "view": [0, 0, 1], "lights": [[0, 0, 1]], "colour": 1}]})", {"case 'g'", "'colour'"}},
        {R"({"cases": [{"name": "h", "material": {"specular_anisotropy_rotation": [1, 0, 0]}, "view": [0, 0, 1],
             "lights": [[0, 0, 1]]}]})",
         {"case 'h'", "specular_anisotropy_rotation", "vector2"}},
        {R"({"cases": [{"view": [0, 0, 1], "lights": [[0, 0, 1]]}]})", {"case '#0'", "'name'"}},
        {R"({"cases": [{"name": "i", "view": [0, 0, 1], "lights": [[0, 0, 1]]},
                       {"name": "i", "view": [0, 0, 1], "lights": [[0, 0, 1]]}]})",
         {"duplicate case name 'i'"}},
    };
    for (const BadCorpus& corpus_text : bad)
    {
        try
        {
            openpbr::host::parse_stability_corpus(nlohmann::json::parse(corpus_text.json), "corpus.json");
            ADD_FAILURE() << "accepted: " << corpus_text.json;
        }
        catch (const openpbr::host::StabilityCorpusError& error)
        {
            const std::string message = error.what();
            EXPECT_NE(message.find("corpus.json"), std::string::npos) << message;
            for (const std::string& part : corpus_text.expected)
            {
                EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' missing from: " << message;
            }
        }
    }
    EXPECT_THROW(openpbr::host::load_stability_corpus("/nonexistent/stability_corpus.json"),
                 openpbr::host::StabilityCorpusError);
}

// openpbr_prepare_volume on every case: extinction finite and >= 0, albedo in [0, 1].
TEST(Stability, VolumesAreFiniteAndBounded)
{
    const StabilityReport report = run_one_path("cpu", 0);
    EXPECT_EQ(report.volume_violations, 0u);
    for (const auto& volume : report.volumes)
    {
        EXPECT_TRUE(volume.ok) << describe_case(volume.name) << ": extinction " << volume.extinction[0] << " "
                               << volume.extinction[1] << " " << volume.extinction[2] << ", albedo " << volume.albedo[0]
                               << " " << volume.albedo[1] << " " << volume.albedo[2];
    }
}

TEST(Stability, ReportJsonHasTheDocumentedShape)
{
    StabilityOptions options;
    options.samples_per_case = 100;
    options.paths = {"cpu"};
    const StabilityReport report = openpbr::host::run_stability(corpus(), options);
    const nlohmann::json json = openpbr::host::to_json(report);
    EXPECT_EQ(json["cases"], corpus().size());
    ASSERT_EQ(json["paths"].size(), 1u);
    const nlohmann::json& path = json["paths"][0];
    EXPECT_EQ(path["name"], "cpu");
    for (const char* key : {"nonfinite", "negative", "max_mean_weight", "max_weight", "cases"})
    {
        EXPECT_TRUE(path.contains(key)) << key;
    }
    EXPECT_EQ(path["cases"].size(), corpus().size());
    EXPECT_FALSE(openpbr::host::to_text(report).empty());
    // The query stream is a pure function of the seed.
    const StabilityReport again = openpbr::host::run_stability(corpus(), options);
    for (std::size_t c = 0; c < report.paths[0].cases.size(); ++c)
    {
        EXPECT_EQ(report.paths[0].cases[c].mean_weight[1], again.paths[0].cases[c].mean_weight[1]);
    }
}

class StabilityPath : public ::testing::TestWithParam<std::string>
{
};

TEST_P(StabilityPath, FiniteNonNegativeAndNoEnergyGain)
{
    const bool cpu = GetParam() == "cpu";
    const std::size_t samples = cpu                                                       ? cpu_samples_per_case()
                                : openpbr::host::execution_path_has_wgsl_math(GetParam()) ? webgpu_samples_per_case
                                                                                          : gpu_samples_per_case;
    const StabilityReport report = run_one_path(GetParam(), samples);
    ASSERT_EQ(report.paths.size(), 1u);
    const StabilityPathResult& path = report.paths[0];
    if (!path.executed)
    {
        // As in test_conformance: where SwiftShader is installed a WebGPU path must run.
        ASSERT_FALSE(openpbr::host::execution_path_has_wgsl_math(GetParam()) &&
                     std::filesystem::exists(openpbr::host::swiftshader_vulkan_driver()))
            << GetParam() << " not executed although SwiftShader is installed: " << path.note;
        GTEST_SKIP() << GetParam() << " not executed: " << path.note;
    }
    ASSERT_EQ(path.cases.size(), corpus().size());
    EXPECT_EQ(path.nonfinite, 0u);
    EXPECT_EQ(path.negative, 0u);
    EXPECT_EQ(path.bad_directions, 0u);
    EXPECT_EQ(path.validation_messages, 0u);
    for (const StabilityCaseResult& result : path.cases)
    {
        EXPECT_EQ(result.nonfinite + result.negative + result.bad_directions, 0u)
            << describe_case(result.name) << ": " << result.nonfinite << " non-finite, " << result.negative << " negative, "
            << result.bad_directions << " non-unit sample directions" << describe_violations(result);
        // Noisy cases (e.g. dispersion: one channel carries weight 3) may exceed the bound by
        // sampling noise alone; three standard errors keep the check from depending on the seed.
        EXPECT_LE(result.max_mean_weight - 3.0 * result.mean_weight_standard_error, max_mean_weight)
            << describe_case(result.name) << ": mean sample weight (" << result.mean_weight[0] << ", "
            << result.mean_weight[1] << ", " << result.mean_weight[2] << ") +- " << result.mean_weight_standard_error
            << " over " << result.samples << " samples";
    }
}

std::vector<std::string> all_paths()
{
    std::vector<std::string> paths = {"cpu"};
    for (const std::string& name : openpbr::host::known_conformance_paths())
    {
        paths.push_back(name);
    }
    return paths;
}

INSTANTIATE_TEST_SUITE_P(AllPaths, StabilityPath, ::testing::ValuesIn(all_paths()), [](const auto& info) {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
});

}  // namespace
