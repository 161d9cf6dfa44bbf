// The parameter table (slang/openpbr_parameters.h) and the places derived from it agree: the
// struct defaults are the table's, the packing round-trips every field through
// openpbr_unpack_material into its own slots, the input contract clamps to the table's range,
// the MaterialX loader reads every MaterialX name of the table into its field, and the
// stability corpus reader knows every name including the extensions.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "host/checks/stability.h"
#include "host/scene/material_library.h"
#include "host/scene/material_packing.h"
#include "host/scene/parameter_table.h"
#include "slang/openpbr.h"

namespace {
const float* unpack_source = nullptr;
}  // namespace

#define OPENPBR_MATERIAL_READ(index) unpack_source[index]
#include "slang/openpbr_material_packing.h"

namespace {

using Inputs = openpbr::OpenPBR_ResolvedInputs;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Bitwise equality: -0 and +0 are told apart, and the packing must keep the sign of zero.
bool same_bits(const float a, const float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A vector the compiler cannot fold. The loader builds its frames at run time from parsed text;
// Clang (-ffp-contract=on) folds a frame built from constants with fused multiply-adds, and the
// tangent of the normal (0.6, 0, 0.8) then comes out 1 ulp apart: 0.8 folded against
// 0.79999995 at run time (Clang 14 -O3, the Release build; GCC folds as it runs).
glm::vec3 unfolded(const float x, const float y, const float z)
{
    volatile float components[3] = {x, y, z};
    return glm::vec3(components[0], components[1], components[2]);
}

// Every float of a material through the visitor, in table order (a basis as tangent,
// bitangent, normal), as (name, reference) pairs.
template <typename Visit> void for_each_float(Inputs& inputs, Visit visit)
{
#define VISIT_FLOAT(name, default_value, low, high) visit(#name, inputs.name);
#define VISIT_COLOR(name, default_r, default_g, default_b, low, high) \
    visit(#name, inputs.name.x);                                      \
    visit(#name, inputs.name.y);                                      \
    visit(#name, inputs.name.z);
#define VISIT_VECTOR2(name, default_x, default_y) \
    visit(#name, inputs.name.x);                  \
    visit(#name, inputs.name.y);
#define VISIT_BOOL(name, default_value)
#define VISIT_BASIS(name, normal_input, tangent_input)                                             \
    for (glm::vec3 * vector : {&inputs.name.tangent, &inputs.name.bitangent, &inputs.name.normal}) \
    {                                                                                              \
        visit(#name, vector->x);                                                                   \
        visit(#name, vector->y);                                                                   \
        visit(#name, vector->z);                                                                   \
    }
    OPENPBR_PARAMETERS(VISIT_FLOAT, VISIT_COLOR, VISIT_VECTOR2, VISIT_BOOL, VISIT_BASIS)
#undef VISIT_FLOAT
#undef VISIT_COLOR
#undef VISIT_VECTOR2
#undef VISIT_BOOL
#undef VISIT_BASIS
}

TEST(ParameterTable, DefaultsAreTheTables)
{
    const Inputs defaults = openpbr::openpbr_make_default_resolved_inputs();
#define CHECK_FLOAT(name, default_value, low, high) EXPECT_EQ(defaults.name, default_value) << #name;
#define CHECK_COLOR(name, default_r, default_g, default_b, low, high) \
    EXPECT_EQ(defaults.name, glm::vec3(default_r, default_g, default_b)) << #name;
#define CHECK_VECTOR2(name, default_x, default_y) EXPECT_EQ(defaults.name, glm::vec2(default_x, default_y)) << #name;
#define CHECK_BOOL(name, default_value) EXPECT_EQ(defaults.name, default_value) << #name;
// geometry_basis defaults to the +z frame; geometry_coat_basis to all zero, "follow the base
// frame" (resolved by the input contract, slang/openpbr_resolved_inputs.h).
#define CHECK_BASIS(name, normal_input, tangent_input)                                                     \
    EXPECT_EQ(defaults.name.normal,                                                                        \
              std::string(#name) == "geometry_coat_basis" ? glm::vec3(0.0f) : glm::vec3(0.0f, 0.0f, 1.0f)) \
        << #name;                                                                                          \
    EXPECT_EQ(defaults.name.tangent,                                                                       \
              std::string(#name) == "geometry_coat_basis" ? glm::vec3(0.0f) : glm::vec3(1.0f, 0.0f, 0.0f)) \
        << #name;
    OPENPBR_PARAMETERS(CHECK_FLOAT, CHECK_COLOR, CHECK_VECTOR2, CHECK_BOOL, CHECK_BASIS)
#undef CHECK_FLOAT
#undef CHECK_COLOR
#undef CHECK_VECTOR2
#undef CHECK_BOOL
#undef CHECK_BASIS
}

// Distinct values in every float (and the bool flipped from its default), packed and unpacked:
// every field comes back bit for bit, every used slot holds its own value, the padding is 0.
TEST(ParameterTable, PackingRoundTripsEveryField)
{
    for (const bool thin_walled : {false, true})
    {
        Inputs inputs = openpbr::openpbr_make_default_resolved_inputs();
        float next = 0.125f;
        for_each_float(inputs, [&](const char*, float& value) {
            value = next;
            next += 1.0f;
        });
        inputs.geometry_thin_walled = thin_walled;

        std::vector<float> packed(2 * OPENPBR_PACKED_MATERIAL_FLOATS, kNaN);
        openpbr::host::pack_material(inputs, packed.data() + OPENPBR_PACKED_MATERIAL_FLOATS);
        unpack_source = packed.data();
        Inputs unpacked = openpbr::openpbr_unpack_material(1u);

        std::vector<float> expected;
        std::vector<float> actual;
        for_each_float(inputs, [&](const char*, float& value) { expected.push_back(value); });
        for_each_float(unpacked, [&](const char*, float& value) { actual.push_back(value); });
        ASSERT_EQ(expected.size(), actual.size());
        for (std::size_t k = 0; k < expected.size(); ++k)
        {
            EXPECT_TRUE(same_bits(expected[k], actual[k])) << "float " << k;
        }
        EXPECT_EQ(unpacked.geometry_thin_walled, thin_walled);

        // Every float value appears exactly once among the used slots, plus the bool's 0 or 1.
        const std::size_t used = openpbr::host::packed_material_used_floats();
        EXPECT_EQ(used, expected.size() + 1);
        std::multiset<float> slots(packed.begin() + OPENPBR_PACKED_MATERIAL_FLOATS,
                                   packed.begin() + OPENPBR_PACKED_MATERIAL_FLOATS + std::ptrdiff_t(used));
        for (const float value : expected)
        {
            EXPECT_EQ(slots.count(value), 1u) << value;
        }
        EXPECT_EQ(slots.count(thin_walled ? 1.0f : 0.0f), 1u);
        for (std::size_t k = used; k < OPENPBR_PACKED_MATERIAL_FLOATS; ++k)
        {
            EXPECT_EQ(packed[OPENPBR_PACKED_MATERIAL_FLOATS + k], 0.0f) << "padding slot " << k;
        }
    }
}

// The contract maps -inf to the table's low end, +inf to its high end, NaN to the default and
// leaves a value inside the range alone, per float and per color channel.
TEST(ParameterTable, ContractClampsToTheTablesRange)
{
    struct Probe
    {
        float input;
        bool to_low;
        bool to_high;
    };
    const Inputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    auto check = [&](const char* name, float Inputs::*scalar, glm::vec3 Inputs::*color, const float low, const float high) {
        const float inside = 0.5f * low + 0.5f * high;
        for (int channel = 0; channel < (color ? 3 : 1); ++channel)
        {
            for (const float input : {-kInf, kInf, kNaN, inside})
            {
                Inputs raw = defaults;
                float& field = scalar ? raw.*scalar : (raw.*color)[channel];
                field = input;
                const Inputs clamped = openpbr::openpbr_apply_input_contract(raw);
                const float result = scalar ? clamped.*scalar : (clamped.*color)[channel];
                const float fallback = scalar ? defaults.*scalar : (defaults.*color)[channel];
                const float expected = std::isnan(input) ? fallback : input < low ? low : input > high ? high : input;
                EXPECT_EQ(result, expected) << name << " channel " << channel << " input " << input;
            }
        }
    };
#define CLAMP_FLOAT(name, default_value, low, high) check(#name, &Inputs::name, nullptr, low, high);
#define CLAMP_COLOR(name, default_r, default_g, default_b, low, high) check(#name, nullptr, &Inputs::name, low, high);
#define CLAMP_VECTOR2(name, default_x, default_y)
#define CLAMP_BOOL(name, default_value)
#define CLAMP_BASIS(name, normal_input, tangent_input)
    OPENPBR_PARAMETERS(CLAMP_FLOAT, CLAMP_COLOR, CLAMP_VECTOR2, CLAMP_BOOL, CLAMP_BASIS)
#undef CLAMP_FLOAT
#undef CLAMP_COLOR
#undef CLAMP_VECTOR2
#undef CLAMP_BOOL
#undef CLAMP_BASIS
}

// The MaterialX names of the table, in table order (a basis gives its normal and tangent).
std::vector<std::string> table_materialx_names()
{
    std::vector<std::string> names;
#define NAME_FLOAT(name, default_value, low, high) names.emplace_back(#name);
#define NAME_COLOR(name, default_r, default_g, default_b, low, high) names.emplace_back(#name);
#define NAME_VECTOR2(name, default_x, default_y)
#define NAME_BOOL(name, default_value) names.emplace_back(#name);
#define NAME_BASIS(name, normal_input, tangent_input) \
    names.emplace_back(#normal_input);                \
    names.emplace_back(#tangent_input);
    OPENPBR_PARAMETERS(NAME_FLOAT, NAME_COLOR, NAME_VECTOR2, NAME_BOOL, NAME_BASIS)
#undef NAME_FLOAT
#undef NAME_COLOR
#undef NAME_VECTOR2
#undef NAME_BOOL
#undef NAME_BASIS
    return names;
}

TEST(ParameterTable, LoaderKnowsEveryMaterialXName)
{
    // 41 inputs in OpenPBR 1.1 (spec "Parameter reference").
    EXPECT_EQ(table_materialx_names().size(), 41u);
    EXPECT_EQ(openpbr::host::supported_input_names(), table_materialx_names());
}

// One file per MaterialX input, setting it to a value unlike its default: the loader must read
// it into its own field and leave every other field at the default.
TEST(ParameterTable, LoaderStoresEveryInputInItsField)
{
    const Inputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "openpbr_parameter_table_test.mtlx";
    for (const openpbr::host::ParameterDescriptor& descriptor : openpbr::host::parameter_descriptors())
    {
        if (!descriptor.materialx)
        {
            continue;
        }
        std::string type = "float";
        std::string value = "0.375";
        Inputs expected = defaults;
        if (const auto* scalar = std::get_if<float Inputs::*>(&descriptor.target))
        {
            expected.*(*scalar) = 0.375f;
        }
        else if (const auto* color = std::get_if<glm::vec3 Inputs::*>(&descriptor.target))
        {
            type = "color3";
            value = "0.25, 0.5, 0.75";
            expected.*(*color) = glm::vec3(0.25f, 0.5f, 0.75f);
        }
        else if (const auto* flag = std::get_if<bool Inputs::*>(&descriptor.target))
        {
            type = "boolean";
            value = "true";
            expected.*(*flag) = true;
        }
        else if (const auto* vector = std::get_if<openpbr::host::GeometryVector>(&descriptor.target))
        {
            // A tilted normal, or a tangent along +y: both change the basis they belong to.
            type = "vector3";
            value = vector->tangent ? "0, 1, 0" : "0.6, 0, 0.8";
            // A file that sets any frame vector gets every basis from the file: the ones it
            // leaves unset become the unperturbed frame (the coat's default "follow the base"
            // applies only to files that set no frame at all).
            for (const auto& other : openpbr::host::parameter_bases())
            {
                expected.*(other.field) = openpbr::openpbr_make_basis(glm::vec3(0.0f, 0.0f, 1.0f));
            }
            openpbr::OpenPBR_Basis& basis = expected.*(openpbr::host::parameter_bases()[vector->basis].field);
            basis = vector->tangent
                        ? openpbr::openpbr_make_basis(unfolded(0.0f, 0.0f, 1.0f), unfolded(0.0f, 1.0f, 0.0f), 1.0f)
                        : openpbr::openpbr_make_basis(unfolded(0.6f, 0.0f, 0.8f));
        }
        {
            std::ofstream file(path);
            file << "<?xml version=\"1.0\"?>\n<materialx version=\"1.39\">\n"
                 << "  <open_pbr_surface name=\"probe\" type=\"surfaceshader\">\n"
                 << "    <input name=\"" << descriptor.name << "\" type=\"" << type << "\" value=\"" << value
                 << "\" />\n  </open_pbr_surface>\n</materialx>\n";
        }
        const std::vector<openpbr::host::Material> materials = openpbr::host::load_materialx_file(path.string());
        ASSERT_EQ(materials.size(), 1u) << descriptor.name;
        Inputs loaded = materials[0].inputs;
        std::vector<float> loaded_floats;
        std::vector<float> expected_floats;
        for_each_float(loaded, [&](const char*, float& v) { loaded_floats.push_back(v); });
        for_each_float(expected, [&](const char*, float& v) { expected_floats.push_back(v); });
        EXPECT_EQ(loaded_floats, expected_floats) << descriptor.name;
        EXPECT_EQ(loaded.geometry_thin_walled, expected.geometry_thin_walled) << descriptor.name;
    }
    std::filesystem::remove(path);
}

// The corpus reader knows the MaterialX names and the extensions, and stores each extension.
TEST(ParameterTable, CorpusReaderKnowsEveryName)
{
    std::vector<std::string> names = table_materialx_names();
    std::vector<std::string> extensions;
#define EXTENSION_FLOAT(name, default_value, low, high)
#define EXTENSION_COLOR(name, default_r, default_g, default_b, low, high)
#define EXTENSION_VECTOR2(name, default_x, default_y) extensions.emplace_back(#name);
#define EXTENSION_BOOL(name, default_value)
#define EXTENSION_BASIS(name, normal_input, tangent_input)
    OPENPBR_PARAMETERS(EXTENSION_FLOAT, EXTENSION_COLOR, EXTENSION_VECTOR2, EXTENSION_BOOL, EXTENSION_BASIS)
#undef EXTENSION_FLOAT
#undef EXTENSION_COLOR
#undef EXTENSION_VECTOR2
#undef EXTENSION_BOOL
#undef EXTENSION_BASIS
    ASSERT_EQ(extensions.size(), 2u);
    names.insert(names.end(), extensions.begin(), extensions.end());
    EXPECT_EQ(openpbr::host::stability_input_names(), names);

    for (const std::string& extension : extensions)
    {
        const nlohmann::json corpus = nlohmann::json::parse(
            R"({"cases": [{"name": "probe", "view": [0, 0, 1], "lights": [[0, 0, 1]], "material": {")" + extension +
            R"(": [0, 1]}}]})");
        const auto cases = openpbr::host::parse_stability_corpus(corpus, "probe.json");
        ASSERT_EQ(cases.size(), 1u);
        Inputs inputs = cases[0].inputs;
        const openpbr::host::ParameterDescriptor* descriptor = openpbr::host::find_parameter(extension);
        ASSERT_NE(descriptor, nullptr);
        EXPECT_FALSE(descriptor->materialx) << extension;
        EXPECT_EQ(inputs.*std::get<glm::vec2 Inputs::*>(descriptor->target), glm::vec2(0.0f, 1.0f)) << extension;
    }
}

}  // namespace
