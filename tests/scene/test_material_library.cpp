// Tests for host/material_library: the specification's defaults, the bundled example materials
// and the loader's errors. Needs OPENPBR_MATERIALS_DIR (a string literal: the materials folder).
#include "host/scene/material_library.h"
#include "host/scene/colour_spaces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

#ifndef OPENPBR_MATERIALS_DIR
#error "define OPENPBR_MATERIALS_DIR as the path of the materials folder, e.g. -DOPENPBR_MATERIALS_DIR=\"/repo/materials\""
#endif

namespace {

using openpbr::OpenPBR_ResolvedInputs;
using openpbr::host::Material;
using openpbr::host::MaterialError;

std::vector<float> as_list(const float value) { return {value}; }
std::vector<float> as_list(const glm::vec3& value) { return {value.x, value.y, value.z}; }

// An independent second table of every OpenPBR 1.1.1 input, written out by hand here rather
// than taken from the library, so a wrong entry in the library's table shows up as a mismatch.
struct InputCase
{
    std::string name;
    std::string type;
    std::string non_default_value;            // written to a file by the round-trip test
    std::vector<float> expected_non_default;  // what the loader must produce from it
    std::function<std::vector<float>(const OpenPBR_ResolvedInputs&)> read;
};

const std::vector<InputCase>& input_cases()
{
    using Inputs = OpenPBR_ResolvedInputs;
    static const std::vector<InputCase> cases = {
        {"base_weight", "float", "0.25", {0.25f}, [](const Inputs& i) { return as_list(i.base_weight); }},
        {"base_color", "color3", "0.1, 0.2, 0.3", {0.1f, 0.2f, 0.3f}, [](const Inputs& i) { return as_list(i.base_color); }},
        {"base_diffuse_roughness",
         "float",
         "0.7",
         {0.7f},
         [](const Inputs& i) { return as_list(i.base_diffuse_roughness); }},
        {"base_metalness", "float", "0.9", {0.9f}, [](const Inputs& i) { return as_list(i.base_metalness); }},
        {"specular_weight", "float", "0.6", {0.6f}, [](const Inputs& i) { return as_list(i.specular_weight); }},
        {"specular_color",
         "color3",
         "0.4,0.5,0.6",
         {0.4f, 0.5f, 0.6f},
         [](const Inputs& i) { return as_list(i.specular_color); }},
        {"specular_roughness", "float", "0.05", {0.05f}, [](const Inputs& i) { return as_list(i.specular_roughness); }},
        {"specular_roughness_anisotropy",
         "float",
         "0.8",
         {0.8f},
         [](const Inputs& i) { return as_list(i.specular_roughness_anisotropy); }},
        {"specular_ior", "float", "1.33", {1.33f}, [](const Inputs& i) { return as_list(i.specular_ior); }},
        {"transmission_weight", "float", "0.5", {0.5f}, [](const Inputs& i) { return as_list(i.transmission_weight); }},
        {"transmission_color",
         "color3",
         "0.9, 0.8, 0.7",
         {0.9f, 0.8f, 0.7f},
         [](const Inputs& i) { return as_list(i.transmission_color); }},
        {"transmission_depth", "float", "2.5", {2.5f}, [](const Inputs& i) { return as_list(i.transmission_depth); }},
        {"transmission_scatter",
         "color3",
         "0.1, 0.1, 0.2",
         {0.1f, 0.1f, 0.2f},
         [](const Inputs& i) { return as_list(i.transmission_scatter); }},
        {"transmission_scatter_anisotropy",
         "float",
         "-0.3",
         {-0.3f},
         [](const Inputs& i) { return as_list(i.transmission_scatter_anisotropy); }},
        {"transmission_dispersion_scale",
         "float",
         "0.75",
         {0.75f},
         [](const Inputs& i) { return as_list(i.transmission_dispersion_scale); }},
        {"transmission_dispersion_abbe_number",
         "float",
         "58",
         {58.0f},
         [](const Inputs& i) { return as_list(i.transmission_dispersion_abbe_number); }},
        {"subsurface_weight", "float", "0.4", {0.4f}, [](const Inputs& i) { return as_list(i.subsurface_weight); }},
        {"subsurface_color",
         "color3",
         "0.7, 0.3, 0.2",
         {0.7f, 0.3f, 0.2f},
         [](const Inputs& i) { return as_list(i.subsurface_color); }},
        {"subsurface_radius", "float", "3", {3.0f}, [](const Inputs& i) { return as_list(i.subsurface_radius); }},
        {"subsurface_radius_scale",
         "color3",
         "0.2, 0.3, 0.4",
         {0.2f, 0.3f, 0.4f},
         [](const Inputs& i) { return as_list(i.subsurface_radius_scale); }},
        {"subsurface_scatter_anisotropy",
         "float",
         "0.6",
         {0.6f},
         [](const Inputs& i) { return as_list(i.subsurface_scatter_anisotropy); }},
        {"fuzz_weight", "float", "1", {1.0f}, [](const Inputs& i) { return as_list(i.fuzz_weight); }},
        {"fuzz_color", "color3", "0.3, 0.2, 0.1", {0.3f, 0.2f, 0.1f}, [](const Inputs& i) { return as_list(i.fuzz_color); }},
        {"fuzz_roughness", "float", "0.9", {0.9f}, [](const Inputs& i) { return as_list(i.fuzz_roughness); }},
        {"coat_weight", "float", "1.0", {1.0f}, [](const Inputs& i) { return as_list(i.coat_weight); }},
        {"coat_color",
         "color3",
         "0.95, 0.9, 0.85",
         {0.95f, 0.9f, 0.85f},
         [](const Inputs& i) { return as_list(i.coat_color); }},
        {"coat_roughness", "float", "0.15", {0.15f}, [](const Inputs& i) { return as_list(i.coat_roughness); }},
        {"coat_roughness_anisotropy",
         "float",
         "0.35",
         {0.35f},
         [](const Inputs& i) { return as_list(i.coat_roughness_anisotropy); }},
        {"coat_ior", "float", "1.45", {1.45f}, [](const Inputs& i) { return as_list(i.coat_ior); }},
        {"coat_darkening", "float", "0.5", {0.5f}, [](const Inputs& i) { return as_list(i.coat_darkening); }},
        {"thin_film_weight", "float", "0.65", {0.65f}, [](const Inputs& i) { return as_list(i.thin_film_weight); }},
        {"thin_film_thickness", "float", "0.32", {0.32f}, [](const Inputs& i) { return as_list(i.thin_film_thickness); }},
        {"thin_film_ior", "float", "1.9", {1.9f}, [](const Inputs& i) { return as_list(i.thin_film_ior); }},
        {"emission_luminance", "float", "1000", {1000.0f}, [](const Inputs& i) { return as_list(i.emission_luminance); }},
        {"emission_color",
         "color3",
         "1, 0.5, 0.2",
         {1.0f, 0.5f, 0.2f},
         [](const Inputs& i) { return as_list(i.emission_color); }},
        {"geometry_opacity", "float", "0.2", {0.2f}, [](const Inputs& i) { return as_list(i.geometry_opacity); }},
        {"geometry_thin_walled",
         "boolean",
         "true",
         {1.0f},
         [](const Inputs& i) { return as_list(i.geometry_thin_walled ? 1.0f : 0.0f); }},
        // The frame vectors come back through the bases; the values are chosen orthonormal so
        // the loader's Gram-Schmidt leaves them unchanged.
        {"geometry_normal",
         "vector3",
         "0, 1, 0",
         {0.0f, 1.0f, 0.0f},
         [](const Inputs& i) { return as_list(i.geometry_basis.normal); }},
        {"geometry_tangent",
         "vector3",
         "0, 0, 1",
         {0.0f, 0.0f, 1.0f},
         [](const Inputs& i) { return as_list(i.geometry_basis.tangent); }},
        {"geometry_coat_normal",
         "vector3",
         "1, 0, 0",
         {1.0f, 0.0f, 0.0f},
         [](const Inputs& i) { return as_list(i.geometry_coat_basis.normal); }},
        {"geometry_coat_tangent",
         "vector3",
         "0, 1, 0",
         {0.0f, 1.0f, 0.0f},
         [](const Inputs& i) { return as_list(i.geometry_coat_basis.tangent); }},
    };
    return cases;
}

// Every input the file did not set must keep the specification's default, bit for bit.
void expect_unset_inputs_are_defaults(const Material& material)
{
    const OpenPBR_ResolvedInputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    for (const InputCase& input : input_cases())
    {
        const bool is_set =
            std::find(material.inputs_set.begin(), material.inputs_set.end(), input.name) != material.inputs_set.end();
        if (!is_set)
        {
            EXPECT_EQ(input.read(material.inputs), input.read(defaults)) << material.name << ": " << input.name;
        }
    }
}

const Material& find_material(const std::vector<Material>& materials, const std::string& name)
{
    const auto found =
        std::find_if(materials.begin(), materials.end(), [&](const Material& material) { return material.name == name; });
    if (found == materials.end())
    {
        throw std::logic_error("no material named " + name);
    }
    return *found;
}

std::size_t count_mtlx_files(const std::filesystem::path& directory)
{
    std::size_t count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(directory))
    {
        count += entry.path().extension() == ".mtlx" ? 1 : 0;
    }
    return count;
}

// A scratch folder per test, removed afterwards; the random suffix keeps concurrent runs of
// the same test binary (e.g. ctest -j with repeats) from sharing files.
class MaterialFileTest : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        const std::string test_name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        directory_ = std::filesystem::temp_directory_path() /
                     ("openpbr_material_library_" + test_name + "_" + std::to_string(std::random_device{}()));
        std::filesystem::create_directories(directory_);
    }

    void TearDown() override
    {
        std::error_code ignored;
        std::filesystem::remove_all(directory_, ignored);
    }

    std::string write_file(const std::string& file_name, const std::string& contents) const
    {
        const std::filesystem::path path = directory_ / file_name;
        std::ofstream stream(path, std::ios::binary);
        stream << contents;
        return path.string();
    }

    // A document shaped like the bundled materials: one surfacematerial named "Test" that
    // references one open_pbr_surface holding `inputs`. Its colour space is acescg, the
    // working space: its colours load unchanged.
    std::string write_surface(const std::string& file_name, const std::string& inputs,
                              const std::string& materialx_attributes = " colorspace=\"acescg\"",
                              const std::string& surface_attributes = "") const
    {
        return write_file(file_name,
                          "<?xml version=\"1.0\"?>\n"
                          "<materialx version=\"1.39\"" +
                              materialx_attributes +
                              ">\n"
                              "  <surfacematerial name=\"Test\" type=\"material\">\n"
                              "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"test_surface\" />\n"
                              "  </surfacematerial>\n"
                              "  <open_pbr_surface name=\"test_surface\" type=\"surfaceshader\"" +
                              surface_attributes + ">\n" + inputs +
                              "  </open_pbr_surface>\n"
                              "</materialx>\n");
    }

    std::filesystem::path directory_;
};

// The message of the MaterialError that loading `path` throws; fails the test if none.
std::string load_error_message(const std::string& path)
{
    try
    {
        openpbr::host::load_materialx_file(path);
    }
    catch (const MaterialError& error)
    {
        return error.what();
    }
    ADD_FAILURE() << "no MaterialError for " << path;
    return {};
}

std::string file_name_of(const std::string& path) { return std::filesystem::path(path).filename().string(); }

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

TEST(MaterialLibraryDefaults, DefaultInputsEqualTheSpecificationsDefaults)
{
    const OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    const glm::vec3 one(1.0f);
    EXPECT_EQ(inputs.base_weight, 1.0f);
    EXPECT_EQ(inputs.base_color, glm::vec3(0.8f));
    EXPECT_EQ(inputs.base_diffuse_roughness, 0.0f);
    EXPECT_EQ(inputs.base_metalness, 0.0f);
    EXPECT_EQ(inputs.specular_weight, 1.0f);
    EXPECT_EQ(inputs.specular_color, one);
    EXPECT_EQ(inputs.specular_roughness, 0.3f);
    EXPECT_EQ(inputs.specular_roughness_anisotropy, 0.0f);
    EXPECT_EQ(inputs.specular_ior, 1.5f);
    EXPECT_EQ(inputs.transmission_weight, 0.0f);
    EXPECT_EQ(inputs.transmission_color, one);
    EXPECT_EQ(inputs.transmission_depth, 0.0f);
    EXPECT_EQ(inputs.transmission_scatter, glm::vec3(0.0f));
    EXPECT_EQ(inputs.transmission_scatter_anisotropy, 0.0f);
    EXPECT_EQ(inputs.transmission_dispersion_scale, 0.0f);
    EXPECT_EQ(inputs.transmission_dispersion_abbe_number, 20.0f);
    EXPECT_EQ(inputs.subsurface_weight, 0.0f);
    EXPECT_EQ(inputs.subsurface_color, glm::vec3(0.8f));
    EXPECT_EQ(inputs.subsurface_radius, 1.0f);
    EXPECT_EQ(inputs.subsurface_radius_scale, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(inputs.subsurface_scatter_anisotropy, 0.0f);
    EXPECT_EQ(inputs.fuzz_weight, 0.0f);
    EXPECT_EQ(inputs.fuzz_color, one);
    EXPECT_EQ(inputs.fuzz_roughness, 0.5f);
    EXPECT_EQ(inputs.coat_weight, 0.0f);
    EXPECT_EQ(inputs.coat_color, one);
    EXPECT_EQ(inputs.coat_roughness, 0.0f);
    EXPECT_EQ(inputs.coat_roughness_anisotropy, 0.0f);
    EXPECT_EQ(inputs.coat_ior, 1.6f);
    EXPECT_EQ(inputs.coat_darkening, 1.0f);
    EXPECT_EQ(inputs.thin_film_weight, 0.0f);
    EXPECT_EQ(inputs.thin_film_thickness, 0.5f);
    EXPECT_EQ(inputs.thin_film_ior, 1.4f);
    EXPECT_EQ(inputs.emission_luminance, 0.0f);
    EXPECT_EQ(inputs.emission_color, one);
    EXPECT_EQ(inputs.geometry_opacity, 1.0f);
    EXPECT_FALSE(inputs.geometry_thin_walled);
    // The unperturbed frame: +z normal, +x tangent, right-handed; the coat shares it through its
    // all-zero default, which means "follow geometry_basis" (tests/bsdf/test_coat_frame.cpp).
    EXPECT_EQ(inputs.geometry_basis.normal, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(inputs.geometry_basis.tangent, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(inputs.geometry_basis.bitangent, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(inputs.geometry_coat_basis.normal, glm::vec3(0.0f));
    EXPECT_EQ(inputs.geometry_coat_basis.tangent, glm::vec3(0.0f));
    EXPECT_EQ(inputs.specular_anisotropy_rotation, glm::vec2(1.0f, 0.0f));
    EXPECT_EQ(inputs.coat_anisotropy_rotation, glm::vec2(1.0f, 0.0f));
}

TEST(MaterialLibraryDefaults, DefaultMaterialHasSpecificationDefaults)
{
    const Material material = openpbr::host::default_material();
    EXPECT_EQ(material.name, "Default");
    EXPECT_TRUE(material.inputs_set.empty());
    expect_unset_inputs_are_defaults(material);
    EXPECT_CONTAINS(openpbr::host::describe(material), "all inputs at their defaults");
}

TEST(MaterialLibraryDefaults, SupportedInputsAreExactlyTheOpenPbr11Inputs)
{
    const std::vector<std::string> names = openpbr::host::supported_input_names();
    std::vector<std::string> expected;
    for (const InputCase& input : input_cases())
    {
        expected.push_back(input.name);
    }
    EXPECT_EQ(names.size(), 41u);
    EXPECT_EQ(names, expected);
}

TEST(MaterialLibraryBundled, LoadsEveryBundledMaterial)
{
    const std::vector<Material> materials = openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR);
    ASSERT_EQ(materials.size(), count_mtlx_files(OPENPBR_MATERIALS_DIR));
    std::set<std::string> names;
    for (std::size_t index = 0; index < materials.size(); ++index)
    {
        const Material& material = materials[index];
        EXPECT_FALSE(material.name.empty()) << material.file;
        EXPECT_FALSE(material.inputs_set.empty()) << material.file;
        EXPECT_EQ(material.colorspace, "acescg") << material.file;
        names.insert(material.name);
        expect_unset_inputs_are_defaults(material);
        if (index > 0)
        {
            EXPECT_LT(file_name_of(materials[index - 1].file), file_name_of(material.file)) << "not sorted by file name";
        }
    }
    EXPECT_EQ(names.size(), materials.size()) << "material names are not unique";
}

TEST(MaterialLibraryBundled, GlassHasItsValues)
{
    const std::vector<Material> materials =
        openpbr::host::load_materialx_file(std::string(OPENPBR_MATERIALS_DIR) + "/open_pbr_glass.mtlx");
    ASSERT_EQ(materials.size(), 1u);
    const Material& glass = materials[0];
    EXPECT_EQ(glass.name, "Glass");
    EXPECT_EQ(glass.inputs.transmission_weight, 1.0f);
    EXPECT_EQ(glass.inputs.specular_ior, 1.52f);
    EXPECT_EQ(glass.inputs.specular_roughness, 0.0f);
    EXPECT_EQ(glass.inputs.transmission_dispersion_scale, 1.0f);
    EXPECT_EQ(glass.inputs.transmission_dispersion_abbe_number, 64.0f);
    EXPECT_EQ(glass.inputs_set,
              (std::vector<std::string>{"specular_roughness", "specular_ior", "transmission_weight",
                                        "transmission_dispersion_scale", "transmission_dispersion_abbe_number"}));
    expect_unset_inputs_are_defaults(glass);

    const std::string description = openpbr::host::describe(glass);
    EXPECT_CONTAINS(description, "specular_ior = 1.52");
    EXPECT_CONTAINS(description, "transmission_weight = 1");
    EXPECT_EQ(description.find("base_color"), std::string::npos) << description;
}

TEST(MaterialLibraryBundled, SpotChecksOtherMaterials)
{
    const std::vector<Material> materials = openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR);
    const Material& soap_bubble = find_material(materials, "Soap_Bubble");
    EXPECT_TRUE(soap_bubble.inputs.geometry_thin_walled);
    EXPECT_EQ(soap_bubble.inputs.thin_film_weight, 1.0f);
    EXPECT_EQ(soap_bubble.inputs.specular_ior, 1.0f);
    const Material& car_paint = find_material(materials, "Car_Paint");
    EXPECT_EQ(car_paint.inputs.base_color, glm::vec3(0.1f, 0.6f, 0.9f));
    EXPECT_EQ(car_paint.inputs.coat_roughness, 0.02f);
}

TEST(MaterialLibraryBundled, DefaultFileEqualsSpecificationDefaults)
{
    // open_pbr_default.mtlx writes out every input at its default, so it must load to exactly
    // openpbr_make_default_resolved_inputs(): a cross-check of the header against the spec.
    const std::vector<Material> materials =
        openpbr::host::load_materialx_file(std::string(OPENPBR_MATERIALS_DIR) + "/open_pbr_default.mtlx");
    ASSERT_EQ(materials.size(), 1u);
    const OpenPBR_ResolvedInputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    EXPECT_GE(materials[0].inputs_set.size(), 37u);
    for (const InputCase& input : input_cases())
    {
        EXPECT_EQ(input.read(materials[0].inputs), input.read(defaults)) << input.name;
    }
}

TEST_F(MaterialFileTest, EveryInputRoundTrips)
{
    std::string inputs;
    for (const InputCase& input : input_cases())
    {
        inputs += "    <input name=\"" + input.name + "\" type=\"" + input.type + "\" value=\"" + input.non_default_value +
                  "\" />\n";
    }
    const std::vector<Material> materials = openpbr::host::load_materialx_file(write_surface("all.mtlx", inputs));
    ASSERT_EQ(materials.size(), 1u);
    const OpenPBR_ResolvedInputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    EXPECT_EQ(materials[0].inputs_set.size(), input_cases().size());
    for (const InputCase& input : input_cases())
    {
        EXPECT_EQ(input.read(materials[0].inputs), input.expected_non_default) << input.name;
        EXPECT_NE(input.read(defaults), input.expected_non_default) << input.name << ": test value is the default";
    }
}

TEST_F(MaterialFileTest, ValuesOutsideTheSpecRangeAreKept)
{
    const std::vector<Material> materials = openpbr::host::load_materialx_file(
        write_surface("range.mtlx", "    <input name=\"base_color\" type=\"color3\" value=\" 2, -1 ,+0.5 \" />\n"
                                    "    <input name=\"specular_ior\" type=\"float\" value=\"-3e0\" />\n"));
    EXPECT_EQ(materials[0].inputs.base_color, glm::vec3(2.0f, -1.0f, 0.5f));
    EXPECT_EQ(materials[0].inputs.specular_ior, -3.0f);
}

TEST_F(MaterialFileTest, TangentAloneUsesTheDefaultNormalAndCoatIgnoresGeometryNormal)
{
    const std::vector<Material> materials = openpbr::host::load_materialx_file(
        write_surface("frames.mtlx", "    <input name=\"geometry_tangent\" type=\"vector3\" value=\"0, 3, 0.5\" />\n"));
    const openpbr::OpenPBR_Basis& basis = materials[0].inputs.geometry_basis;
    EXPECT_EQ(basis.normal, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(basis.tangent.y, 1.0f, 1e-6f);
    EXPECT_NEAR(basis.bitangent.x, -1.0f, 1e-6f);  // cross(+z, +y): right-handed

    const std::vector<Material> tilted = openpbr::host::load_materialx_file(
        write_surface("tilted.mtlx", "    <input name=\"geometry_normal\" type=\"vector3\" value=\"0, 0, -2\" />\n"));
    EXPECT_EQ(tilted[0].inputs.geometry_basis.normal, glm::vec3(0.0f, 0.0f, -1.0f));
    // The coat keeps the unperturbed normal so a smooth coat can sit on a bumpy base.
    EXPECT_EQ(tilted[0].inputs.geometry_coat_basis.normal, glm::vec3(0.0f, 0.0f, 1.0f));
}

TEST_F(MaterialFileTest, BareSurfaceIsNamedByItsNode)
{
    const std::string path = write_file("bare.mtlx", "<?xml version=\"1.0\"?>\n"
                                                     "<materialx version=\"1.39\">\n"
                                                     "  <open_pbr_surface name=\"lonely\" type=\"surfaceshader\">\n"
                                                     "    <input name=\"base_metalness\" type=\"float\" value=\"1\" />\n"
                                                     "  </open_pbr_surface>\n"
                                                     "</materialx>\n");
    const std::vector<Material> materials = openpbr::host::load_materialx_file(path);
    ASSERT_EQ(materials.size(), 1u);
    EXPECT_EQ(materials[0].name, "lonely");
    EXPECT_EQ(materials[0].file, path);
    EXPECT_EQ(materials[0].inputs.base_metalness, 1.0f);
}

TEST_F(MaterialFileTest, OtherShadingModelsAreSkipped)
{
    const std::string path =
        write_file("mixed.mtlx", "<?xml version=\"1.0\"?>\n"
                                 "<materialx version=\"1.39\">\n"
                                 "  <surfacematerial name=\"Standard\" type=\"material\">\n"
                                 "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"ss\" />\n"
                                 "  </surfacematerial>\n"
                                 "  <standard_surface name=\"ss\" type=\"surfaceshader\" />\n"
                                 "  <surfacematerial name=\"Open\" type=\"material\">\n"
                                 "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"os\" />\n"
                                 "  </surfacematerial>\n"
                                 "  <open_pbr_surface name=\"os\" type=\"surfaceshader\" />\n"
                                 "</materialx>\n");
    const std::vector<Material> materials = openpbr::host::load_materialx_file(path);
    ASSERT_EQ(materials.size(), 1u);
    EXPECT_EQ(materials[0].name, "Open");
    EXPECT_TRUE(materials[0].inputs_set.empty());
}

TEST_F(MaterialFileTest, DirectoryIsSortedAndIgnoresOtherFiles)
{
    write_surface("b.mtlx", "");
    write_surface("a.mtlx", "    <input name=\"coat_weight\" type=\"float\" value=\"1\" />\n");
    write_file("notes.txt", "not a material");
    const std::vector<Material> materials = openpbr::host::load_material_directory(directory_.string());
    ASSERT_EQ(materials.size(), 2u);
    EXPECT_EQ(file_name_of(materials[0].file), "a.mtlx");
    EXPECT_EQ(materials[0].inputs.coat_weight, 1.0f);
    EXPECT_EQ(file_name_of(materials[1].file), "b.mtlx");
}

TEST_F(MaterialFileTest, MissingDirectoryThrows)
{
    EXPECT_THROW(openpbr::host::load_material_directory((directory_ / "absent").string()), MaterialError);
}

TEST_F(MaterialFileTest, UnreadableFile)
{
    const std::string message = load_error_message((directory_ / "absent.mtlx").string());
    EXPECT_CONTAINS(message, "absent.mtlx");
    EXPECT_CONTAINS(message, "cannot open");
}

TEST_F(MaterialFileTest, MalformedXml)
{
    const std::string message =
        load_error_message(write_surface("broken.mtlx", "    <input name=\"base_weight\" type=\"float\" value=\"1\">\n"));
    EXPECT_CONTAINS(message, "broken.mtlx:");
    EXPECT_CONTAINS(message, "malformed XML");
}

TEST_F(MaterialFileTest, NotMaterialX)
{
    const std::string message = load_error_message(write_file("other.mtlx", "<html><body/></html>"));
    EXPECT_CONTAINS(message, "other.mtlx");
    EXPECT_CONTAINS(message, "not a MaterialX document");
}

TEST_F(MaterialFileTest, UnknownInputNamesFileLineAndInput)
{
    const std::string message = load_error_message(
        write_surface("unknown.mtlx", "    <input name=\"base_colour\" type=\"color3\" value=\"1, 1, 1\" />\n"));
    // The input is on line 7 of the written document, column 5 after the indentation.
    EXPECT_CONTAINS(message, "unknown.mtlx:7:5:");
    EXPECT_CONTAINS(message, "'base_colour'");
    EXPECT_CONTAINS(message, "unknown input");
}

TEST_F(MaterialFileTest, WrongType)
{
    const std::string float_color =
        load_error_message(write_surface("type.mtlx", "    <input name=\"base_color\" type=\"float\" value=\"0.5\" />\n"));
    EXPECT_CONTAINS(float_color, "type.mtlx");
    EXPECT_CONTAINS(float_color, "'base_color'");
    EXPECT_CONTAINS(float_color, "expected 'color3'");

    const std::string integer_float = load_error_message(
        write_surface("integer.mtlx", "    <input name=\"coat_weight\" type=\"integer\" value=\"1\" />\n"));
    EXPECT_CONTAINS(integer_float, "integer.mtlx");
    EXPECT_CONTAINS(integer_float, "'coat_weight'");

    const std::string float_boolean = load_error_message(
        write_surface("boolean.mtlx", "    <input name=\"geometry_thin_walled\" type=\"float\" value=\"1\" />\n"));
    EXPECT_CONTAINS(float_boolean, "'geometry_thin_walled'");
    EXPECT_CONTAINS(float_boolean, "expected 'boolean'");

    const std::string color_vector = load_error_message(
        write_surface("vector.mtlx", "    <input name=\"geometry_normal\" type=\"color3\" value=\"0, 0, 1\" />\n"));
    EXPECT_CONTAINS(color_vector, "'geometry_normal'");
    EXPECT_CONTAINS(color_vector, "expected 'vector3'");
}

TEST_F(MaterialFileTest, BadValues)
{
    const std::string unparsable = load_error_message(
        write_surface("value.mtlx", "    <input name=\"base_color\" type=\"color3\" value=\"0.5, x\" />\n"));
    EXPECT_CONTAINS(unparsable, "value.mtlx");
    EXPECT_CONTAINS(unparsable, "'base_color'");
    EXPECT_CONTAINS(unparsable, "'0.5, x'");

    const std::string count = load_error_message(
        write_surface("count.mtlx", "    <input name=\"specular_color\" type=\"color3\" value=\"0.5, 0.5\" />\n"));
    EXPECT_CONTAINS(count, "count.mtlx");
    EXPECT_CONTAINS(count, "'specular_color'");
    EXPECT_CONTAINS(count, "2 component(s)");

    const std::string extra = load_error_message(
        write_surface("extra.mtlx", "    <input name=\"coat_ior\" type=\"float\" value=\"1.5, 1.6\" />\n"));
    EXPECT_CONTAINS(extra, "'coat_ior'");

    for (const char* const bad : {"inf", "nan", "-INF", "1e39"})
    {
        const std::string finite = load_error_message(write_surface(
            "finite.mtlx", "    <input name=\"specular_ior\" type=\"float\" value=\"" + std::string(bad) + "\" />\n"));
        EXPECT_CONTAINS(finite, "finite.mtlx");
        EXPECT_CONTAINS(finite, "'specular_ior'");
    }

    for (const char* const bad : {"", " ", "1.5x", "0x1p0", "1,,2"})
    {
        const std::string garbage = load_error_message(write_surface(
            "garbage.mtlx", "    <input name=\"specular_ior\" type=\"float\" value=\"" + std::string(bad) + "\" />\n"));
        EXPECT_CONTAINS(garbage, "'specular_ior'");
    }

    const std::string boolean = load_error_message(
        write_surface("yes.mtlx", "    <input name=\"geometry_thin_walled\" type=\"boolean\" value=\"yes\" />\n"));
    EXPECT_CONTAINS(boolean, "'geometry_thin_walled'");
    EXPECT_CONTAINS(boolean, "'true' or 'false'");
}

TEST_F(MaterialFileTest, DuplicateInput)
{
    const std::string message =
        load_error_message(write_surface("twice.mtlx", "    <input name=\"coat_ior\" type=\"float\" value=\"1.5\" />\n"
                                                       "    <input name=\"coat_ior\" type=\"float\" value=\"1.6\" />\n"));
    EXPECT_CONTAINS(message, "twice.mtlx:8:");
    EXPECT_CONTAINS(message, "'coat_ior'");
}

TEST_F(MaterialFileTest, ConnectedInputIsNotSupported)
{
    const std::string message = load_error_message(
        write_surface("texture.mtlx", "    <input name=\"base_color\" type=\"color3\" nodename=\"image1\" />\n"));
    EXPECT_CONTAINS(message, "texture.mtlx");
    EXPECT_CONTAINS(message, "'base_color'");
    EXPECT_CONTAINS(message, "textures and node graphs are not supported");

    const std::string graph = load_error_message(write_surface(
        "graph.mtlx", "    <input name=\"specular_roughness\" type=\"float\" nodegraph=\"ng\" output=\"out\" />\n"));
    EXPECT_CONTAINS(graph, "'specular_roughness'");
    EXPECT_CONTAINS(graph, "not supported");
}

// An input's colorspace overrides the document's; color3 values are converted into the
// working space (host/scene/colour_spaces.h), floats and vectors are not.
TEST_F(MaterialFileTest, ColoursAreConvertedFromTheirSpace)
{
    const std::vector<Material> materials = openpbr::host::load_materialx_file(write_surface(
        "spaces.mtlx",
        "    <input name=\"base_color\" type=\"color3\" value=\"1, 0.5, 0\" colorspace=\"srgb_texture\" />\n"
        "    <input name=\"coat_color\" type=\"color3\" value=\"0.9, 0.5, 0.25\" />\n"
        "    <input name=\"specular_color\" type=\"color3\" value=\"0.9, 0.5, 0.25\" colorspace=\"acescg\" />\n"
        "    <input name=\"geometry_normal\" type=\"vector3\" value=\"0, 0.6, 0.8\" />\n"
        "    <input name=\"coat_roughness\" type=\"float\" value=\"0.5\" colorspace=\"srgb_texture\" />\n",
        " colorspace=\"lin_rec709\""));
    const openpbr::OpenPBR_ResolvedInputs& inputs = materials[0].inputs;
    EXPECT_EQ(materials[0].colorspace, "lin_rec709");
    EXPECT_EQ(inputs.base_color, *openpbr::host::colour_to_working_space("srgb_texture", glm::vec3(1.0f, 0.5f, 0.0f)));
    EXPECT_EQ(inputs.coat_color, openpbr::host::rec709_to_working_space(glm::vec3(0.9f, 0.5f, 0.25f)));
    EXPECT_NE(inputs.coat_color, glm::vec3(0.9f, 0.5f, 0.25f));  // Rec.709 differs from the working space
    EXPECT_EQ(inputs.specular_color, glm::vec3(0.9f, 0.5f, 0.25f));
    EXPECT_EQ(inputs.geometry_basis.normal, glm::vec3(0.0f, 0.6f, 0.8f));
    EXPECT_EQ(inputs.coat_roughness, 0.5f);
}

// The specification's default when a document names no colour space: ACEScg ("Metadata").
TEST_F(MaterialFileTest, DocumentWithoutColorspaceIsAcescg)
{
    const std::vector<Material> materials = openpbr::host::load_materialx_file(
        write_surface("plain.mtlx", "    <input name=\"base_color\" type=\"color3\" value=\"0.9, 0.5, 0.25\" />\n", ""));
    EXPECT_EQ(materials[0].colorspace, "acescg");
    EXPECT_EQ(materials[0].inputs.base_color,
              *openpbr::host::colour_to_working_space("acescg", glm::vec3(0.9f, 0.5f, 0.25f)));
}

TEST_F(MaterialFileTest, UnknownColorspaceIsAnErrorNamingIt)
{
    const std::string document = load_error_message(write_surface(
        "document.mtlx", "    <input name=\"base_color\" type=\"color3\" value=\"1, 0, 0\" />\n", " colorspace=\"sRGB\""));
    EXPECT_CONTAINS(document, "document.mtlx:2:");
    EXPECT_CONTAINS(document, "unknown colorspace 'sRGB'");
    EXPECT_CONTAINS(document, "srgb_texture");  // the known names are listed
    const std::string input = load_error_message(write_surface(
        "input.mtlx", "    <input name=\"base_color\" type=\"color3\" value=\"1, 0, 0\" colorspace=\"lin_ap0\" />\n"));
    EXPECT_CONTAINS(input, "input.mtlx:7:");
    EXPECT_CONTAINS(input, "'base_color'");
    EXPECT_CONTAINS(input, "unknown colorspace 'lin_ap0'");
}

// A 1.1.1 document (the node definition's version named, geometry_thin_walled uniform) loads;
// so does one naming 1.1; any other version is refused.
TEST_F(MaterialFileTest, ReadsOpenPbr11And111Documents)
{
    for (const std::string version : {"1.1", "1.1.1"})
    {
        const std::vector<Material> materials = openpbr::host::load_materialx_file(write_surface(
            "v" + version + ".mtlx",
            "    <input name=\"geometry_thin_walled\" type=\"boolean\" value=\"true\" uniform=\"true\" />\n"
            "    <input name=\"emission_color\" type=\"color3\" value=\"4, 2, 1\" />\n",
            " colorspace=\"acescg\"", " version=\"" + version + "\" nodedef=\"ND_open_pbr_surface_surfaceshader\""));
        EXPECT_TRUE(materials[0].inputs.geometry_thin_walled) << version;
        // emission_color is HDR in 1.1.1 ([0, inf)^3): kept as written.
        EXPECT_EQ(materials[0].inputs.emission_color, glm::vec3(4.0f, 2.0f, 1.0f)) << version;
    }
    for (const std::string version : {"1.0", "1.2", "2"})
    {
        const std::string message =
            load_error_message(write_surface("other.mtlx", "", " colorspace=\"acescg\"", " version=\"" + version + "\""));
        EXPECT_CONTAINS(message, "other.mtlx:6:");
        EXPECT_CONTAINS(message, "version '" + version + "' is not supported");
    }
}

TEST_F(MaterialFileTest, MissingNode)
{
    const std::string path =
        write_file("missing.mtlx", "<?xml version=\"1.0\"?>\n"
                                   "<materialx version=\"1.39\">\n"
                                   "  <surfacematerial name=\"Lost\" type=\"material\">\n"
                                   "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"nowhere\" />\n"
                                   "  </surfacematerial>\n"
                                   "</materialx>\n");
    const std::string message = load_error_message(path);
    EXPECT_CONTAINS(message, "missing.mtlx:4:");
    EXPECT_CONTAINS(message, "'nowhere'");
    EXPECT_CONTAINS(message, "'Lost'");
}

TEST_F(MaterialFileTest, NoOpenPbrSurface)
{
    const std::string message =
        load_error_message(write_file("empty.mtlx", "<?xml version=\"1.0\"?>\n<materialx version=\"1.39\" />\n"));
    EXPECT_CONTAINS(message, "empty.mtlx");
    EXPECT_CONTAINS(message, "no <open_pbr_surface>");
}

TEST_F(MaterialFileTest, SurfaceshaderFromNodeGraphIsNotSupported)
{
    const std::string path =
        write_file("graph_material.mtlx",
                   "<?xml version=\"1.0\"?>\n"
                   "<materialx version=\"1.39\">\n"
                   "  <surfacematerial name=\"Graph\" type=\"material\">\n"
                   "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodegraph=\"ng\" output=\"out\" />\n"
                   "  </surfacematerial>\n"
                   "</materialx>\n");
    const std::string message = load_error_message(path);
    EXPECT_CONTAINS(message, "graph_material.mtlx");
    EXPECT_CONTAINS(message, "node graphs are not supported");
}

}  // namespace
