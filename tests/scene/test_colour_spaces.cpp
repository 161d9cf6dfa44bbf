// Tests for host/scene/colour_spaces.h and its generated table (tools/make_colour_tables.py):
// the matrices against published ones, the conversions of tests/data/colour_conversions.json
// (which viewer/src/colour_spaces.mjs reproduces too, tests/scene/colour_spaces_test.mjs), and
// the per-space documents of tests/data/colour_spaces/ loading to the same working values.
// Needs OPENPBR_SOURCE_DIR (a string literal: the repository root).
#include "host/scene/colour_space_table.h"
#include "host/scene/colour_spaces.h"
#include "host/scene/material_library.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

Matrix multiply(const Matrix& a, const Matrix& b)
{
    Matrix product{};
    for (int i = 0; i < 3; ++i)
    {
        for (int j = 0; j < 3; ++j)
        {
            for (int k = 0; k < 3; ++k)
            {
                product[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    return product;
}

// GLM's inverse (column-major: element [row][column] of a Matrix is [column][row] of a dmat3).
Matrix inverse(const Matrix& m)
{
    glm::dmat3 columns(1.0);
    for (int row = 0; row < 3; ++row)
    {
        for (int column = 0; column < 3; ++column)
        {
            columns[column][row] = m[row][column];
        }
    }
    const glm::dmat3 inverted = glm::inverse(columns);
    Matrix result{};
    for (int row = 0; row < 3; ++row)
    {
        for (int column = 0; column < 3; ++column)
        {
            result[row][column] = inverted[column][row];
        }
    }
    return result;
}

Matrix from_row_major(const std::array<double, 9>& values)
{
    Matrix m{};
    for (int i = 0; i < 9; ++i)
    {
        m[std::size_t(i / 3)][std::size_t(i % 3)] = values[std::size_t(i)];
    }
    return m;
}

// ---- Published matrices ----------------------------------------------------------------------

// ACES AP1 -> XYZ and back (ACEScg specification S-2014-004, ACES documentation TB-2014-004).
const Matrix aces_ap1_to_xyz = {{{0.6624541811, 0.1340042065, 0.1561876870},
                                 {0.2722287168, 0.6740817658, 0.0536895174},
                                 {-0.0055746495, 0.0040607335, 1.0103391003}}};
const Matrix aces_xyz_to_ap1 = {{{1.6410233797, -0.3248032942, -0.2364246952},
                                 {-0.6636628587, 1.6153315917, 0.0167563477},
                                 {0.0117218943, -0.0082844420, 0.9883948585}}};
// sRGB (Rec.709 primaries, D65) -> XYZ, IEC 61966-2-1 (four decimals).
const Matrix iec_srgb_to_xyz = {{{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}}};
// Bradford cone response (Lam 1985), and the XYZ of the two white points (Y = 1).
const Matrix bradford = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
const std::array<double, 3> d65_xyz = {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290};
const std::array<double, 3> aces_white_xyz = {0.32168 / 0.33767, 1.0, (1.0 - 0.32168 - 0.33767) / 0.33767};
// ACEScg -> linear Rec.709 as the ACES and OpenColorIO transforms publish it (five decimals).
const Matrix published_ap1_to_rec709 = {
    {{1.70505, -0.62179, -0.08326}, {-0.13026, 1.14080, -0.01055}, {-0.02400, -0.12897, 1.15297}}};

Matrix bradford_adaptation(const std::array<double, 3>& source_white, const std::array<double, 3>& target_white)
{
    Matrix scale{};
    for (int i = 0; i < 3; ++i)
    {
        double source = 0.0;
        double target = 0.0;
        for (int k = 0; k < 3; ++k)
        {
            source += bradford[std::size_t(i)][std::size_t(k)] * source_white[std::size_t(k)];
            target += bradford[std::size_t(i)][std::size_t(k)] * target_white[std::size_t(k)];
        }
        scale[std::size_t(i)][std::size_t(i)] = target / source;
    }
    return multiply(inverse(bradford), multiply(scale, bradford));
}

const openpbr::host::colour_table::FileSpace& table_row(const std::string_view name)
{
    for (const auto& space : openpbr::host::colour_table::file_spaces)
    {
        if (space.name == name)
        {
            return space;
        }
    }
    throw std::runtime_error("no table row " + std::string(name));
}

constexpr std::size_t rec709_column = 0;  // working_space_names order
constexpr std::size_t acescg_column = 1;

void expect_matrix_near(const Matrix& actual, const Matrix& expected, double tolerance, const std::string& what)
{
    for (int i = 0; i < 3; ++i)
    {
        for (int j = 0; j < 3; ++j)
        {
            EXPECT_NEAR(actual[std::size_t(i)][std::size_t(j)], expected[std::size_t(i)][std::size_t(j)], tolerance)
                << what << " [" << i << "][" << j << "]";
        }
    }
}

TEST(ColourTable, WorkingSpaceColumnsAreNamedAsTheSetting)
{
    EXPECT_EQ(openpbr::host::colour_table::working_space_names[rec709_column], "lin_rec709");
    EXPECT_EQ(openpbr::host::colour_table::working_space_names[acescg_column], "acescg");
}

// ACEScg <-> Rec.709 from the ACES documentation's AP1 matrices, the Bradford adaptation and the
// IEC sRGB matrix, against the generated table (derived from chromaticities instead).
TEST(ColourTable, MatchesPublishedMatrices)
{
    // The published pair is inverse to its ten digits: 6.8e-11 measured.
    expect_matrix_near(multiply(aces_ap1_to_xyz, aces_xyz_to_ap1), {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, 1e-9,
                       "AP1 round trip");
    const Matrix table_rec709_to_ap1 = from_row_major(table_row("lin_rec709").to_working[acescg_column]);
    const Matrix published_rec709_to_ap1 =
        multiply(aces_xyz_to_ap1, multiply(bradford_adaptation(d65_xyz, aces_white_xyz), iec_srgb_to_xyz));
    // 1e-4: the IEC matrix's four decimals (5e-5 each); measured 6.9e-5.
    expect_matrix_near(table_rec709_to_ap1, published_rec709_to_ap1, 1e-4, "lin_rec709 -> acescg");
    const Matrix table_ap1_to_rec709 = from_row_major(openpbr::host::colour_table::working_to_display[acescg_column]);
    // 5e-6: the published five decimals; measured 4.7e-6.
    expect_matrix_near(table_ap1_to_rec709, published_ap1_to_rec709, 5e-6, "acescg -> lin_rec709");
    // The two directions are inverse to rounding (measured 8.9e-16).
    expect_matrix_near(multiply(table_ap1_to_rec709, table_rec709_to_ap1), {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, 1e-14,
                       "round trip");
    // A space in its own column is exactly the identity, so working-space files pass unchanged.
    expect_matrix_near(from_row_major(table_row("acescg").to_working[acescg_column]), {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                       0.0, "acescg -> acescg");
    expect_matrix_near(from_row_major(table_row("lin_rec709").to_working[rec709_column]),
                       {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, 0.0, "lin_rec709 -> lin_rec709");
}

TEST(ColourSpaces, WhiteStaysWhite)
{
    for (const auto& space : openpbr::host::colour_table::file_spaces)
    {
        for (const std::string_view working : openpbr::host::colour_table::working_space_names)
        {
            // Every space's (1, 1, 1) is its white; Bradford maps white to white: exactly 1 in
            // float (the row sums differ from 1 by at most 6.7e-16, measured).
            const std::optional<glm::vec3> white =
                openpbr::host::colour_to_working_space(space.name, glm::vec3(1.0f), working);
            ASSERT_TRUE(white.has_value());
            EXPECT_EQ(*white, glm::vec3(1.0f)) << space.name << " -> " << working;
        }
    }
    EXPECT_EQ(openpbr::host::working_space_to_display(glm::vec3(0.5f)), glm::vec3(0.5f));
}

// tests/data/colour_conversions.json: the generator's double-precision conversions rounded to
// float; the C++ conversion (double inside, one rounding) gives the same float bits.
TEST(ColourSpaces, ReproducesTheGeneratedConversions)
{
    std::ifstream stream(std::string(OPENPBR_SOURCE_DIR) + "/tests/data/colour_conversions.json");
    ASSERT_TRUE(stream) << "cannot open tests/data/colour_conversions.json";
    const nlohmann::json document = nlohmann::json::parse(stream);
    std::size_t count = 0;
    for (const nlohmann::json& item : document.at("cases"))
    {
        const std::string space = item.at("space");
        const std::string working = item.at("working_space");
        const glm::vec3 value(item.at("value")[0].get<float>(), item.at("value")[1].get<float>(),
                              item.at("value")[2].get<float>());
        const std::optional<glm::vec3> converted = openpbr::host::colour_to_working_space(space, value, working);
        ASSERT_TRUE(converted.has_value()) << space;
        for (int c = 0; c < 3; ++c)
        {
            EXPECT_EQ((*converted)[c], item.at("expected")[std::size_t(c)].get<float>())
                << space << " -> " << working << " channel " << c;
        }
        ++count;
    }
    // Every name of the table, both working spaces, eight values each.
    EXPECT_EQ(count, openpbr::host::colour_table::file_spaces.size() * 2 * 8);
}

TEST(ColourSpaces, UnknownNamesAreRefused)
{
    EXPECT_FALSE(openpbr::host::colour_to_working_space("srgb", glm::vec3(1.0f)).has_value());
    EXPECT_FALSE(openpbr::host::colour_to_working_space("ACEScg", glm::vec3(1.0f)).has_value());
    EXPECT_FALSE(openpbr::host::colour_to_working_space("acescg", glm::vec3(1.0f), "lin_ap0").has_value());
    EXPECT_NE(openpbr::host::colour_space_names().find("srgb_texture"), std::string::npos);
}

// The same two colours (linear Rec.709 (0.6, 0.3, 0.1) and the HDR (4, 2, 1)) written in each
// MaterialX colour space load to the same working values.
TEST(ColourSpaces, EveryDocumentSpaceLoadsToTheSameWorkingValues)
{
    const glm::vec3 base = openpbr::host::rec709_to_working_space(glm::vec3(0.6f, 0.3f, 0.1f));
    const glm::vec3 emission = openpbr::host::rec709_to_working_space(glm::vec3(4.0f, 2.0f, 1.0f));
    std::size_t files = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(OPENPBR_SOURCE_DIR) + "/tests/data/colour_spaces"))
    {
        const std::vector<openpbr::host::Material> materials = openpbr::host::load_materialx_file(entry.path().string());
        ASSERT_EQ(materials.size(), 1u) << entry.path();
        const openpbr::OpenPBR_ResolvedInputs& inputs = materials[0].inputs;
        for (int c = 0; c < 3; ++c)
        {
            // The files carry nine significant digits, read as floats: the working values differ by
            // float rounding, measured at most 1.9e-7 relative on the base and 1.1e-7 on the
            // emission (one to two ulps).
            EXPECT_NEAR(inputs.base_color[c], base[c], 4e-7f * base[c]) << entry.path() << " channel " << c;
            EXPECT_NEAR(inputs.emission_color[c], emission[c], 4e-7f * emission[c]) << entry.path() << " channel " << c;
        }
        EXPECT_EQ(materials[0].colorspace, entry.path().stem().string());
        ++files;
    }
    EXPECT_EQ(files, 11u);  // acescg, g22_ap1, g18_ap1, lin_rec709, g22_rec709, g18_rec709, srgb_texture,
                            // lin_displayp3, srgb_displayp3, lin_adobergb, adobergb
}

}  // namespace
