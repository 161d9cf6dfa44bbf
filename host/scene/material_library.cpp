// material_library.cpp - MaterialX reader for constant-valued <open_pbr_surface> nodes.
// Design: the parameter table (slang/openpbr_parameters.h, as C++ data in parameter_table.h)
// maps every OpenPBR 1.1.1 input name to its MaterialX type and to where its value goes; parsing,
// validation, describe() and supported_input_names() are all driven by it, so adding an input
// is one line there.
#include "host/scene/material_library.h"
#include "host/scene/colour_spaces.h"
#include "host/scene/parameter_table.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <variant>

#include <pugixml.hpp>

namespace openpbr::host {
namespace {

using Inputs = openpbr::OpenPBR_ResolvedInputs;

enum class ValueType
{
    float_value,
    color3_value,
    vector3_value,
    boolean_value,
};

// The MaterialX spelling of each type, used both to check the file and in messages.
const char* type_name(const ValueType type)
{
    switch (type)
    {
    case ValueType::float_value: return "float";
    case ValueType::color3_value: return "color3";
    case ValueType::vector3_value: return "vector3";
    case ValueType::boolean_value: return "boolean";
    }
    return "unknown";
}

// The MaterialX type of each parameter target: a bool is "boolean", a vec3 field "color3",
// a basis's normal or tangent "vector3", a float "float".
ValueType value_type(const ParameterDescriptor& descriptor)
{
    if (std::holds_alternative<glm::vec3 Inputs::*>(descriptor.target))
    {
        return ValueType::color3_value;
    }
    if (std::holds_alternative<GeometryVector>(descriptor.target))
    {
        return ValueType::vector3_value;
    }
    if (std::holds_alternative<bool Inputs::*>(descriptor.target))
    {
        return ValueType::boolean_value;
    }
    return ValueType::float_value;
}

// Every OpenPBR 1.1.1 input in specification order ("Parameter reference"): the MaterialX inputs
// of the parameter table (slang/openpbr_parameters.h), without the extensions.
const std::vector<const ParameterDescriptor*>& input_table()
{
    static const std::vector<const ParameterDescriptor*> table = [] {
        std::vector<const ParameterDescriptor*> inputs;
        for (const ParameterDescriptor& descriptor : parameter_descriptors())
        {
            if (descriptor.materialx)
            {
                inputs.push_back(&descriptor);
            }
        }
        return inputs;
    }();
    return table;
}

const ParameterDescriptor* find_input(const std::string_view name)
{
    const ParameterDescriptor* descriptor = find_parameter(name);
    return descriptor && descriptor->materialx ? descriptor : nullptr;
}

// An input's value before it is stored: floats for every numeric type, or a boolean.
struct ParsedValue
{
    glm::vec3 vector{0.0f};
    float scalar = 0.0f;
    bool boolean = false;
};

// What one <open_pbr_surface> node amounts to while its inputs are being read.
struct SurfaceValues
{
    Inputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    GeometryVectors geometry_vectors;
    std::vector<std::string> inputs_set;
};

// Unset normals and tangents mean the unperturbed shading frame (+z normal, +x tangent), for
// the coat as well: the spec lets the coat keep the smooth geometric normal when the base has
// a normal map, so in a file the coat basis does not follow geometry_normal.
OpenPBR_Basis make_basis_from(const std::optional<glm::vec3>& normal, const std::optional<glm::vec3>& tangent)
{
    const glm::vec3 resolved_normal = normal.value_or(glm::vec3(0.0f, 0.0f, 1.0f));
    if (!tangent)
    {
        return openpbr::openpbr_make_basis(resolved_normal);
    }
    return openpbr::openpbr_make_basis(resolved_normal, *tangent, 1.0f);
}

void store_value(SurfaceValues& values, const ParameterDescriptor& descriptor, const ParsedValue& value)
{
    std::visit(
        [&](const auto target) {
            using Target = std::decay_t<decltype(target)>;
            if constexpr (std::is_same_v<Target, float Inputs::*>)
            {
                values.inputs.*target = value.scalar;
            }
            else if constexpr (std::is_same_v<Target, glm::vec3 Inputs::*>)
            {
                values.inputs.*target = value.vector;
            }
            else if constexpr (std::is_same_v<Target, bool Inputs::*>)
            {
                values.inputs.*target = value.boolean;
            }
            else if constexpr (std::is_same_v<Target, GeometryVector>)
            {
                values.geometry_vectors[target] = value.vector;
            }
        },
        descriptor.target);
}

std::string format_float(const float value)
{
    std::ostringstream stream;
    stream << value;
    return stream.str();
}

std::string format_vector(const glm::vec3& value)
{
    return "(" + format_float(value.x) + ", " + format_float(value.y) + ", " + format_float(value.z) + ")";
}

// The value an input currently has in `inputs`, as text, for describe(). Geometry vectors are
// read back from the bases, so a tangent shows after Gram-Schmidt against its normal.
std::string format_input(const Inputs& inputs, const ParameterDescriptor& descriptor)
{
    return std::visit(
        [&](const auto target) -> std::string {
            using Target = std::decay_t<decltype(target)>;
            if constexpr (std::is_same_v<Target, float Inputs::*>)
            {
                return format_float(inputs.*target);
            }
            else if constexpr (std::is_same_v<Target, glm::vec3 Inputs::*>)
            {
                return format_vector(inputs.*target);
            }
            else if constexpr (std::is_same_v<Target, bool Inputs::*>)
            {
                return inputs.*target ? "true" : "false";
            }
            else if constexpr (std::is_same_v<Target, GeometryVector>)
            {
                const OpenPBR_Basis& basis = inputs.*(parameter_bases()[target.basis].field);
                return format_vector(target.tangent ? basis.tangent : basis.normal);
            }
            else
            {
                // Extensions (vec2) are not MaterialX inputs and never reach here.
                return "";
            }
        },
        descriptor.target);
}

// The file's text and path, kept so every message can say "path:line:column".
class SourceFile
{
  public:
    SourceFile(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

    const std::string& path() const { return path_; }
    const std::string& text() const { return text_; }

    // "path:line:column" for a byte offset into the text, or "path" when it is unknown.
    std::string location(const std::ptrdiff_t offset) const
    {
        if (offset < 0 || static_cast<std::size_t>(offset) > text_.size())
        {
            return path_;
        }
        const auto end = text_.begin() + offset;
        const auto line = 1 + std::count(text_.begin(), end, '\n');
        const auto line_start = std::find(std::make_reverse_iterator(end), text_.rend(), '\n').base();
        const auto column = 1 + (end - line_start);
        return path_ + ":" + std::to_string(line) + ":" + std::to_string(column);
    }

    // pugixml reports an element at its name; editors and compilers point at the '<'.
    std::string location(const pugi::xml_node& node) const
    {
        const std::ptrdiff_t offset = node.offset_debug();
        const bool after_bracket = offset > 0 && static_cast<std::size_t>(offset) <= text_.size() &&
                                   text_[static_cast<std::size_t>(offset) - 1] == '<';
        return location(after_bracket ? offset - 1 : offset);
    }

    [[noreturn]] void fail(const pugi::xml_node& node, const std::string& problem) const
    {
        throw MaterialError(location(node) + ": " + problem);
    }

  private:
    std::string path_;
    std::string text_;
};

SourceFile read_source_file(const std::string& path)
{
    std::ifstream stream(path, std::ios::binary);
    if (!stream)
    {
        // errno is set by the open that failed on every platform we build for; it tells a
        // missing file apart from a permission problem.
        throw MaterialError(path + ": cannot open MaterialX file: " + std::strerror(errno));
    }
    std::ostringstream contents;
    contents << stream.rdbuf();
    if (stream.bad())
    {
        throw MaterialError(path + ": cannot read MaterialX file");
    }
    return SourceFile(path, contents.str());
}

std::string_view trim(std::string_view text)
{
    constexpr std::string_view whitespace = " \t\r\n";
    const auto first = text.find_first_not_of(whitespace);
    if (first == std::string_view::npos)
    {
        return {};
    }
    const auto last = text.find_last_not_of(whitespace);
    return text.substr(first, last - first + 1);
}

// Parses MaterialX's comma-separated float lists ("0.8, 0.8, 0.8"). std::from_chars, not
// strtof or streams, so a host that set a locale with a decimal comma still reads "0.5".
// Returns an error description, or an empty string on success.
std::string parse_float_list(const std::string_view text, std::vector<float>& components)
{
    components.clear();
    std::size_t start = 0;
    while (true)
    {
        const std::size_t comma = text.find(',', start);
        const std::string_view piece =
            trim(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        // from_chars rejects a leading '+', which is still a well-formed number in a file.
        const std::string_view number = (!piece.empty() && piece.front() == '+') ? piece.substr(1) : piece;
        float component = 0.0f;
        const auto result = std::from_chars(number.data(), number.data() + number.size(), component);
        if (number.empty() || result.ec == std::errc::invalid_argument || result.ptr != number.data() + number.size())
        {
            return "cannot parse '" + std::string(piece) + "' as a number";
        }
        if (result.ec == std::errc::result_out_of_range)
        {
            return "'" + std::string(piece) + "' is outside the range of a 32-bit float";
        }
        if (!std::isfinite(component))
        {
            return "non-finite value '" + std::string(piece) + "'";
        }
        components.push_back(component);
        if (comma == std::string_view::npos)
        {
            return {};
        }
        start = comma + 1;
    }
}

// "unknown colorspace 'name' (known: acescg, ...)", the same words as viewer/src/materialx.mjs.
std::string unknown_colorspace_message(const std::string& name)
{
    return "unknown colorspace '" + name + "' (known: " + colour_space_names() + ")";
}

// The versions of the specification whose documents this loader reads: an <open_pbr_surface>
// may name its node definition's version (MaterialX "version" attribute), e.g. "1.1.1".
constexpr std::array<std::string_view, 2> supported_versions = {"1.1", "1.1.1"};

// Attributes by which MaterialX connects an input to another node instead of a constant.
constexpr std::array<const char*, 4> connection_attributes = {"nodename", "nodegraph", "output", "interfacename"};

void read_input(const SourceFile& source, const std::string& document_colorspace, const pugi::xml_node& surface_node,
                const pugi::xml_node& input_node, SurfaceValues& values)
{
    const std::string name = input_node.attribute("name").as_string();
    const std::string context =
        "open_pbr_surface '" + std::string(surface_node.attribute("name").as_string()) + "', input '" + name + "'";
    if (name.empty())
    {
        source.fail(input_node, "open_pbr_surface '" + std::string(surface_node.attribute("name").as_string()) +
                                    "' has an <input> without a name");
    }
    const ParameterDescriptor* const descriptor = find_input(name);
    if (descriptor == nullptr)
    {
        source.fail(input_node, context + ": unknown input name (not an OpenPBR 1.1.1 input)");
    }
    const ValueType type = value_type(*descriptor);
    if (std::find(values.inputs_set.begin(), values.inputs_set.end(), name) != values.inputs_set.end())
    {
        source.fail(input_node, context + ": input given more than once");
    }
    for (const char* const attribute_name : connection_attributes)
    {
        const pugi::xml_attribute connection = input_node.attribute(attribute_name);
        if (connection)
        {
            source.fail(input_node, context + ": connected input (" + attribute_name + "=\"" + connection.value() +
                                        "\"); textures and node graphs are not supported, only constant values");
        }
    }
    const pugi::xml_attribute type_attribute = input_node.attribute("type");
    if (!type_attribute)
    {
        source.fail(input_node, context + ": missing type attribute (expected '" + type_name(type) + "')");
    }
    if (std::string_view(type_attribute.value()) != type_name(type))
    {
        source.fail(input_node,
                    context + ": wrong type '" + type_attribute.value() + "', expected '" + type_name(type) + "'");
    }
    // An input's own colorspace overrides the document's (MaterialX "Color Spaces"); a name
    // outside the table is an error on any input, though only color3 values are converted.
    const pugi::xml_attribute input_colorspace = input_node.attribute("colorspace");
    const std::string colorspace = input_colorspace ? input_colorspace.value() : document_colorspace;
    if (input_colorspace && !colour_to_working_space(colorspace, glm::vec3(0.0f)))
    {
        source.fail(input_node, context + ": " + unknown_colorspace_message(colorspace));
    }
    const pugi::xml_attribute value_attribute = input_node.attribute("value");
    if (!value_attribute)
    {
        source.fail(input_node, context + ": no value attribute");
    }
    const std::string_view text = value_attribute.value();

    ParsedValue value;
    if (type == ValueType::boolean_value)
    {
        const std::string_view word = trim(text);
        if (word != "true" && word != "false")
        {
            source.fail(input_node, context + ": boolean value must be 'true' or 'false', got '" + std::string(text) + "'");
        }
        value.boolean = word == "true";
    }
    else
    {
        std::vector<float> components;
        const std::string problem = parse_float_list(text, components);
        if (!problem.empty())
        {
            source.fail(input_node, context + ": " + problem + " in value '" + std::string(text) + "'");
        }
        const std::size_t expected_count = type == ValueType::float_value ? 1 : 3;
        if (components.size() != expected_count)
        {
            source.fail(input_node, context + ": value '" + std::string(text) + "' has " +
                                        std::to_string(components.size()) + " component(s), type '" + type_name(type) +
                                        "' needs " + std::to_string(expected_count));
        }
        value.scalar = components[0];
        if (expected_count == 3)
        {
            value.vector = glm::vec3(components[0], components[1], components[2]);
        }
        // Colors into the working space (docs/colour.md); vector3 inputs are directions.
        if (type == ValueType::color3_value)
        {
            value.vector = *colour_to_working_space(colorspace, value.vector);
        }
    }
    store_value(values, *descriptor, value);
    values.inputs_set.push_back(name);
}

Material read_surface(const SourceFile& source, const std::string& document_colorspace, const pugi::xml_node& surface_node,
                      const std::string& material_name)
{
    const pugi::xml_attribute version = surface_node.attribute("version");
    if (version && std::find(supported_versions.begin(), supported_versions.end(), std::string_view(version.value())) ==
                       supported_versions.end())
    {
        source.fail(surface_node, "open_pbr_surface '" + std::string(surface_node.attribute("name").as_string()) +
                                      "': version '" + version.value() +
                                      "' is not supported (this loader reads OpenPBR 1.1 and 1.1.1)");
    }
    SurfaceValues values;
    for (const pugi::xml_node& input_node : surface_node.children("input"))
    {
        read_input(source, document_colorspace, surface_node, input_node, values);
    }
    // A file that sets no frame at all keeps the API's default bases (+z, and a coat basis that
    // follows the base frame); one that perturbs only the base keeps the coat on the unperturbed
    // frame, the spec's default geometry_coat_normal.
    bool any_frame_set = false;
    for (std::size_t basis = 0; basis < parameter_bases().size(); ++basis)
    {
        any_frame_set = any_frame_set || values.geometry_vectors.normals[basis].has_value() ||
                        values.geometry_vectors.tangents[basis].has_value();
    }
    for (std::size_t basis = 0; any_frame_set && basis < parameter_bases().size(); ++basis)
    {
        values.inputs.*(parameter_bases()[basis].field) =
            make_basis_from(values.geometry_vectors.normals[basis], values.geometry_vectors.tangents[basis]);
    }

    Material material;
    material.name = material_name;
    material.file = source.path();
    material.colorspace = document_colorspace;
    material.inputs = values.inputs;
    material.inputs_set = std::move(values.inputs_set);
    return material;
}

bool is_open_pbr_surface(const pugi::xml_node& node) { return std::string_view(node.name()) == "open_pbr_surface"; }

}  // namespace

MaterialError::~MaterialError() = default;

std::vector<Material> load_materialx_file(const std::string& path)
{
    const SourceFile source = read_source_file(path);
    pugi::xml_document document;
    const pugi::xml_parse_result parse_result = document.load_buffer(source.text().data(), source.text().size());
    if (!parse_result)
    {
        throw MaterialError(source.location(parse_result.offset) + ": malformed XML: " + parse_result.description());
    }
    const pugi::xml_node root = document.document_element();
    if (std::string_view(root.name()) != "materialx")
    {
        throw MaterialError(source.location(root) + ": not a MaterialX document (root element is <" +
                            std::string(root.name()) + ">, expected <materialx>)");
    }
    // No colorspace on the document: the specification's default, ACEScg ("Metadata").
    const pugi::xml_attribute colorspace_attribute = root.attribute("colorspace");
    const std::string document_colorspace =
        colorspace_attribute ? colorspace_attribute.value() : std::string(default_document_colour_space());
    if (!colour_to_working_space(document_colorspace, glm::vec3(0.0f)))
    {
        source.fail(root, "<materialx>: " + unknown_colorspace_message(document_colorspace));
    }

    // MaterialX element names are unique within their parent; nodename refers to top-level ones.
    std::map<std::string, pugi::xml_node> top_level_elements;
    for (const pugi::xml_node& element : root.children())
    {
        if (element.type() != pugi::node_element)
        {
            continue;
        }
        const std::string element_name = element.attribute("name").as_string();
        if (!element_name.empty() && !top_level_elements.emplace(element_name, element).second)
        {
            source.fail(element, "duplicate element name '" + element_name + "'");
        }
    }

    std::vector<Material> materials;
    std::vector<pugi::xml_node> referenced_surfaces;
    for (const pugi::xml_node& material_node : root.children("surfacematerial"))
    {
        const std::string material_name = material_node.attribute("name").as_string();
        const std::string context = "surfacematerial '" + material_name + "'";
        const pugi::xml_node shader_input = material_node.find_child_by_attribute("input", "name", "surfaceshader");
        if (!shader_input)
        {
            source.fail(material_node, context + ": no surfaceshader input");
        }
        if (shader_input.attribute("nodegraph"))
        {
            source.fail(shader_input, context + ": surfaceshader connected to nodegraph '" +
                                          shader_input.attribute("nodegraph").value() + "'; node graphs are not supported");
        }
        const std::string node_name = shader_input.attribute("nodename").as_string();
        if (node_name.empty())
        {
            source.fail(shader_input, context + ": surfaceshader input has no nodename");
        }
        const auto found = top_level_elements.find(node_name);
        if (found == top_level_elements.end())
        {
            source.fail(shader_input,
                        context + ": surfaceshader nodename '" + node_name + "' references a node that does not exist");
        }
        // A material of another shading model (standard_surface, ...) is not ours to load.
        if (!is_open_pbr_surface(found->second))
        {
            continue;
        }
        referenced_surfaces.push_back(found->second);
        materials.push_back(read_surface(source, document_colorspace, found->second, material_name));
    }
    for (const pugi::xml_node& surface_node : root.children("open_pbr_surface"))
    {
        if (std::find(referenced_surfaces.begin(), referenced_surfaces.end(), surface_node) == referenced_surfaces.end())
        {
            materials.push_back(
                read_surface(source, document_colorspace, surface_node, surface_node.attribute("name").as_string()));
        }
    }
    if (materials.empty())
    {
        throw MaterialError(path + ": no <open_pbr_surface> node found");
    }
    return materials;
}

std::vector<Material> load_material_directory(const std::string& directory)
{
    std::error_code error;
    std::vector<std::filesystem::path> files;
    for (std::filesystem::directory_iterator entry(directory, error), end; !error && entry != end; entry.increment(error))
    {
        if (entry->path().extension() == ".mtlx" && entry->is_regular_file(error))
        {
            files.push_back(entry->path());
        }
    }
    if (error)
    {
        throw MaterialError(directory + ": cannot list material directory: " + error.message());
    }
    std::sort(files.begin(), files.end(), [](const std::filesystem::path& left, const std::filesystem::path& right) {
        return left.filename().string() < right.filename().string();
    });

    std::vector<Material> materials;
    for (const std::filesystem::path& file : files)
    {
        std::vector<Material> file_materials = load_materialx_file(file.string());
        std::move(file_materials.begin(), file_materials.end(), std::back_inserter(materials));
    }
    return materials;
}

Material default_material()
{
    Material material;
    material.name = "Default";
    material.inputs = openpbr::openpbr_make_default_resolved_inputs();
    return material;
}

std::string describe(const Material& material)
{
    const Inputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    std::string text = material.name;
    if (!material.file.empty())
    {
        text += " (" + material.file + ")";
    }
    text += ":";
    bool any_differs = false;
    // Compared as printed (6 significant digits): a difference too small to show would only
    // print as "x = <the default>", which tells the reader nothing.
    for (const ParameterDescriptor* descriptor : input_table())
    {
        const std::string value = format_input(material.inputs, *descriptor);
        if (value != format_input(defaults, *descriptor))
        {
            text += std::string(any_differs ? ", " : " ") + descriptor->name + " = " + value;
            any_differs = true;
        }
    }
    if (!any_differs)
    {
        text += " all inputs at their defaults";
    }
    return text;
}

std::vector<std::string> supported_input_names()
{
    std::vector<std::string> names;
    names.reserve(input_table().size());
    for (const ParameterDescriptor* descriptor : input_table())
    {
        names.emplace_back(descriptor->name);
    }
    return names;
}

}  // namespace openpbr::host
