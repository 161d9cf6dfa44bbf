// The hard-case corpus (tests/data/stability_corpus.json): the reader, and the CPU build with
// 200000 samples per case (stability_expectations.h has what every path must meet). A program
// of its own, linking no GPU path (openpbr_host_core), so that the sanitizer and Clang Release
// builds run it without compiling them; test_stability.cpp runs the GPU paths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/checks/stability.h"
#include "host/scene/material_library.h"
#include "tests/checks/stability_expectations.h"

namespace {

using openpbr::host::StabilityCase;
using openpbr::host::StabilityOptions;
using openpbr::host::StabilityReport;
using openpbr::host::stability_tests::corpus;
using openpbr::host::stability_tests::describe_case;

constexpr std::size_t default_cpu_samples_per_case = 200000;

// OPENPBR_STABILITY_CPU_SAMPLES overrides the CPU sample count, e.g. for sanitizer builds.
std::size_t cpu_samples_per_case()
{
    const char* text = std::getenv("OPENPBR_STABILITY_CPU_SAMPLES");
    return text && *text ? std::size_t(std::strtoull(text, nullptr, 10)) : default_cpu_samples_per_case;
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
    StabilityOptions options;
    options.samples_per_case = 0;  // the volume check reads no samples
    const StabilityReport report = openpbr::host::run_stability_cpu(corpus(), options);
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
    const StabilityReport report = openpbr::host::run_stability_cpu(corpus(), options);
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
    const StabilityReport again = openpbr::host::run_stability_cpu(corpus(), options);
    for (std::size_t c = 0; c < report.paths[0].cases.size(); ++c)
    {
        EXPECT_EQ(report.paths[0].cases[c].mean_weight[1], again.paths[0].cases[c].mean_weight[1]);
    }
}

std::string last_line(const std::string& text)
{
    const std::size_t end = text.size() - (text.empty() || text.back() != '\n' ? 0 : 1);
    const std::size_t start = text.rfind('\n', end - 1);
    return text.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1));
}

// The verdict line ends the report (`openpbr stability`) and its counts are in the JSON. The
// failing path is a real run of the CPU build whose executor turns every query's eval.diffuse.r
// into NaN; the paths reported as they finish are the ones in the report.
TEST(StabilityVerdict, FailuresFirstThenPassesThenNotExecuted)
{
    const std::vector<StabilityCase> cases(corpus().begin(), corpus().begin() + 3);
    StabilityOptions options;
    options.samples_per_case = 100;
    std::vector<std::string> finished;
    options.on_path_finished = [&finished](const openpbr::host::StabilityPathResult& path) {
        finished.push_back(path.name);
    };
    StabilityReport report = openpbr::host::run_stability_cpu(cases, options);
    EXPECT_EQ(finished, std::vector<std::string>{"cpu"});
    EXPECT_EQ(last_line(openpbr::host::to_text(report)), "verdict: 1 of 1 executed path passes");

    const openpbr::host::StabilityExecutor nan_eval = [](const std::vector<float>& queries,
                                                         const std::vector<float>& materials) {
        std::vector<float> results = openpbr::host::run_conformance_cpu(queries, materials);
        for (std::size_t record = 0; record < results.size(); record += openpbr::host::conformance_result_floats)
        {
            results[record] = std::numeric_limits<float>::quiet_NaN();
        }
        return results;
    };
    openpbr::host::StabilityPathResult broken =
        openpbr::host::run_stability_path("nan-eval", nan_eval, cases, options.samples_per_case, options.seed);
    ASSERT_TRUE(broken.executed);
    EXPECT_GT(broken.nonfinite, 0u);
    report.paths.push_back(broken);
    openpbr::host::StabilityPathResult missing;
    missing.name = "cuda";
    missing.note = "not built: build/openpbr_cuda_conformance does not exist";
    report.paths.push_back(missing);
    EXPECT_TRUE(openpbr::host::has_violations(report));
    EXPECT_EQ(last_line(openpbr::host::to_text(report)),
              "verdict: 1 of 2 executed paths fails: nan-eval; 1 passes; not executed: cuda (not built)");
    const nlohmann::json verdict = openpbr::host::to_json(report)["verdict"];
    EXPECT_EQ(verdict["executed"], 2);
    EXPECT_EQ(verdict["passed"], 1);
    EXPECT_EQ(verdict["failed"], 1);
    EXPECT_EQ(verdict["not_executed"], 1);
    EXPECT_EQ(verdict["passes"], false);
    EXPECT_EQ(verdict["failed_paths"], nlohmann::json::array({"nan-eval"}));
    EXPECT_EQ(verdict["text"], last_line(openpbr::host::to_text(report)));

    // A volume check that fails comes before the paths.
    report.volume_violations = 2;
    EXPECT_EQ(last_line(openpbr::host::to_text(report)),
              "verdict: volume check fails in 2 cases; 1 of 2 executed paths fails: nan-eval; 1 passes; not executed: "
              "cuda (not built)");
    EXPECT_EQ(openpbr::host::to_json(report)["verdict"]["other_failures"].size(), 1u);
}

TEST(StabilityCpu, FiniteNonNegativeAndNoEnergyGain)
{
    StabilityOptions options;
    options.samples_per_case = cpu_samples_per_case();
    const StabilityReport report = openpbr::host::run_stability_cpu(corpus(), options);
    ASSERT_EQ(report.paths.size(), 1u);
    ASSERT_TRUE(report.paths[0].executed);
    openpbr::host::stability_tests::expect_stable(report.paths[0]);
}

}  // namespace
