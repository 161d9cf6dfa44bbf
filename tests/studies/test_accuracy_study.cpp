// `openpbr bench accuracy --quick` (host/studies/accuracy.h): every knob family with its own
// metric against its own reference, the shipped setting and a Pareto front in each, the model
// floors (the layering floor read from a file of `openpbr accuracy layering`'s form, or a note
// without one), the picture strips, and the settings' stated tolerances.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "host/studies/accuracy.h"
#include "host/studies/accuracy_internal.h"
#include "host/support/files.h"

namespace {

using openpbr::host::AccuracyFamily;
using openpbr::host::AccuracyReport;
using openpbr::host::AccuracySetting;

const std::filesystem::path& test_directory()
{
    static const std::filesystem::path directory = std::filesystem::temp_directory_path() / "openpbr_accuracy_test";
    return directory;
}

const AccuracyReport& quick_report()
{
    static const AccuracyReport report = [] {
        openpbr::host::AccuracyOptions options;
        options.quick = true;
        options.progress = false;
        options.cache_directory = test_directory() / "cache";
        options.repository_root = OPENPBR_SOURCE_DIR;
        options.layering_json = test_directory() / "no-such-layering.json";
        options.pictures_directory = test_directory() / "pictures";
        return openpbr::host::run_accuracy_study(options);
    }();
    return report;
}

const AccuracyFamily& family(const std::string& name)
{
    for (const AccuracyFamily& candidate : quick_report().families)
    {
        if (candidate.name == name)
        {
            return candidate;
        }
    }
    throw std::runtime_error("no family " + name);
}

const AccuracySetting& setting(const std::string& family_name, const std::string& variant)
{
    for (const AccuracySetting& candidate : family(family_name).settings)
    {
        if (candidate.variant == variant)
        {
            return candidate;
        }
    }
    throw std::runtime_error("no setting " + variant + " in " + family_name);
}

TEST(AccuracyStudy, EveryFamilyHasTheShippedSettingAFiniteErrorAndATime)
{
    std::set<std::string> names;
    for (const AccuracyFamily& candidate : quick_report().families)
    {
        names.insert(candidate.name);
        EXPECT_FALSE(candidate.error_metric.empty());
        EXPECT_FALSE(candidate.reference.empty());
        int shipped = 0, on_front = 0;
        for (const AccuracySetting& entry : candidate.settings)
        {
            shipped += entry.shipped ? 1 : 0;
            on_front += entry.pareto ? 1 : 0;
            EXPECT_TRUE(std::isfinite(entry.error) && entry.error >= 0.0) << candidate.name << ": " << entry.setting;
            EXPECT_GT(entry.cpu_ns.best, 0.0) << candidate.name << ": " << entry.setting;
            EXPECT_GE(entry.cpu_ns.median, entry.cpu_ns.best) << candidate.name << ": " << entry.setting;
        }
        EXPECT_EQ(shipped, 1) << candidate.name;
        EXPECT_GE(on_front, 1) << candidate.name;
    }
    const std::set<std::string> expected = {"compensation", "table storage", "fast math",    "precision",
                                            "thin film",    "film estimate", "vndf sampling"};
    EXPECT_EQ(names, expected);
}

// A reference is measured against itself: error 0 exactly, the isolation the study rests on.
TEST(AccuracyStudy, ReferencesHaveNoErrorAgainstThemselves)
{
    EXPECT_EQ(setting("compensation", "compensation_exact").error, 0.0);
    EXPECT_EQ(setting("precision", "double_precision").error, 0.0);
    EXPECT_EQ(setting("thin film", "shipped").error, 0.0);
    EXPECT_EQ(setting("table storage", "shipped").error, 0.0);
}

// No setting on a family's Pareto front is beaten in both error and CPU time by another.
TEST(AccuracyStudy, ParetoFrontHasNoDominatedSetting)
{
    for (const AccuracyFamily& candidate : quick_report().families)
    {
        for (const AccuracySetting& front : candidate.settings)
        {
            for (const AccuracySetting& other : candidate.settings)
            {
                if (front.pareto && &front != &other)
                {
                    EXPECT_FALSE(other.error < front.error && other.cpu_ns.best < front.cpu_ns.best)
                        << candidate.name << ": " << other.setting << " beats " << front.setting;
                }
            }
        }
    }
}

// Stated tolerance of the fast-math hooks on the whole BSDF (docs/accuracy-vs-time.md): the
// median query within 2 % relative of the shipped build. Why 2 %: every normalized vector is
// off by up to 1.75e-3 (test_fast_math_hooks), and an eval multiplies several of them, D alone
// scaling as |h|^-4; measured 0.45-0.53 %.
TEST(AccuracyStudy, FastMathStaysWithinItsTolerance)
{
    for (const AccuracySetting& entry : family("fast math").settings)
    {
        EXPECT_LT(entry.other_errors.at("per-query relative error (median)"), 0.02) << entry.setting;
    }
}

// Array and buffer mode read the same floats with the same arithmetic (slang/openpbr_lut.h), so
// the float32 buffer variant's eval and sample outputs equal the shipped (array) build's bit for
// bit.
TEST(AccuracyStudy, BufferTablesAreBitIdenticalToTheArray)
{
    const AccuracySetting& buffer = setting("table storage", "table_buffer");
    EXPECT_EQ(buffer.other_errors.at("eval + sample outputs differing in bits from the array build (count)"), 0.0);
    EXPECT_EQ(buffer.error, 0.0);
}

// The float build agrees with the double-precision build (tools/make_double_headers.py) to float
// rounding on typical queries: median relative difference below 1e-5 (float epsilon 6e-8 times
// the few hundred operations of a prepare + eval; measured 1.2e-7), and the double build differs
// from the float one at all (it is not the float build by mistake).
TEST(AccuracyStudy, FloatAgreesWithDouble)
{
    const double median = setting("precision", "shipped").other_errors.at("per-query relative error (median)");
    EXPECT_LT(median, 1e-5);
    EXPECT_GT(median, 0.0);
}

// Every coarser compensation is further from the exact E_ggx than the shipped table, and none
// at all furthest. Measured in quick mode (whose reference table has 16 x 16 quadrature nodes):
// shipped 0.0082, table 16 0.0115, analytic fit 0.032, none 0.57; in the full study 2.4e-4,
// 0.011, 0.064 and 0.69.
TEST(AccuracyStudy, CompensationErrorsOrderAsTheirApproximations)
{
    const double shipped = setting("compensation", "shipped").error;
    EXPECT_LT(shipped, setting("compensation", "compensation_analytic").error);
    EXPECT_LT(setting("compensation", "compensation_analytic").error, setting("compensation", "compensation_none").error);
    EXPECT_LT(shipped, setting("compensation", "table_16").error);
}

// The film-estimate knob against the dense lobe average: the shipped estimate is closer than the
// film at the view only (the estimate most implementations use).
TEST(AccuracyStudy, FilmEstimateBeatsTheFilmAtTheView)
{
    EXPECT_LT(setting("film estimate", "shipped").error, setting("film estimate", "film_estimate_at_view").error);
}

// The fast film differs from the full film at all (it is not the full model by mistake).
TEST(AccuracyStudy, FastFilmDiffersFromTheFullFilm) { EXPECT_GT(setting("thin film", "thin_film_fast").error, 0.0); }

// The sampling family carries the efficiency, 1 for the shipped setting.
TEST(AccuracyStudy, SamplingEfficiencyIsRelativeToTheShippedSetting)
{
    EXPECT_DOUBLE_EQ(setting("vndf sampling", "shipped").other_errors.at("efficiency relative to the shipped setting"), 1.0);
    EXPECT_GT(setting("vndf sampling", "vndf_bounded").error, 0.0);
}

// The compensation floor has the model's rows and the baselines; without a layering file the
// layering floor says why it is absent.
TEST(AccuracyStudy, ModelFloorsAreRowsOfTheirOwn)
{
    const nlohmann::json document = openpbr::host::accuracy_to_json(quick_report());
    ASSERT_TRUE(document.contains("model_floors"));
    const nlohmann::json& floors = document["model_floors"];
    ASSERT_TRUE(floors.contains("compensation"));
    EXPECT_GE(floors["compensation"]["rows"].size(), 6u);
    ASSERT_TRUE(floors.contains("layering"));
    EXPECT_TRUE(floors["layering"]["rows"].empty());
    EXPECT_NE(floors["layering"]["note"].get<std::string>().find("does not exist"), std::string::npos);
    EXPECT_GE(document["rows"].size(), 40u);
}

// A file of `openpbr accuracy layering`'s form: one floor row per material, its largest albedo
// error over channels and view cosines, with the reference's standard error there.
TEST(AccuracyStudy, LayeringFloorReadsTheLayeringFile)
{
    const std::filesystem::path path = test_directory() / "layering.json";
    std::filesystem::create_directories(test_directory());
    const nlohmann::json document = {{"rows",
                                      {{{"material", "Car Paint"},
                                        {"view_cosine", 1.0},
                                        {"model_albedo", {0.5, 0.5, 0.5}},
                                        {"reference_albedo", {0.5, 0.45, 0.5}},
                                        {"reference_standard_error", {0.001, 0.002, 0.001}},
                                        {"shape_error", 0.1},
                                        {"model_ns", 400.0},
                                        {"reference_ns", 1e6}},
                                       {{"material", "Car Paint"},
                                        {"view_cosine", 0.5},
                                        {"model_albedo", {0.5, 0.5, 0.5}},
                                        {"reference_albedo", {0.52, 0.5, 0.5}},
                                        {"reference_standard_error", {0.003, 0.002, 0.001}},
                                        {"shape_error", 0.1},
                                        {"model_ns", 400.0},
                                        {"reference_ns", 1e6}}}},
                                     {"summary", {{"materials", 1}}}};
    openpbr::host::write_file_atomically(path, document.dump());
    const openpbr::host::AccuracyFloor floor = openpbr::host::accuracy::read_layering_floor(path);
    ASSERT_EQ(floor.rows.size(), 1u);
    EXPECT_NEAR(floor.rows[0].error, 0.05, 1e-12);
    EXPECT_NEAR(floor.rows[0].error_uncertainty, 0.002, 1e-12);
    EXPECT_EQ(floor.rows[0].time_ns, 400.0);
    EXPECT_TRUE(floor.note.empty());
}

// The picture strips: one per family but layering, every tile a whole image; the float32 buffer
// tables' tile equals the shipped one bit for bit.
TEST(AccuracyStudy, PictureStripsAreWritten)
{
    quick_report();
    const std::filesystem::path directory = test_directory() / "pictures";
    const nlohmann::json manifest = nlohmann::json::parse(openpbr::host::read_whole_file(directory / "manifest.json"));
    ASSERT_EQ(manifest["strips"].size(), 7u);
    for (const nlohmann::json& strip : manifest["strips"])
    {
        const std::size_t floats = strip["width"].get<std::size_t>() * strip["height"].get<std::size_t>() * 3;
        for (const nlohmann::json& tile : strip["tiles"])
        {
            EXPECT_EQ(openpbr::host::read_float32_file(directory / tile["file"].get<std::string>()).size(), floats)
                << tile["file"];
        }
    }
    EXPECT_EQ(openpbr::host::read_float32_file(directory / "table_storage_table_buffer.f32"),
              openpbr::host::read_float32_file(directory / "table_storage_shipped.f32"));
}

}  // namespace
