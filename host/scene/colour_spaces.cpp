// colour_spaces.cpp - the conversions of colour_spaces.h over the generated table.
#include "host/scene/colour_spaces.h"
#include "host/scene/colour_space_table.h"
#include "slang/openpbr_working_space.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace openpbr::host {
namespace {

static_assert(OPENPBR_WORKING_SPACE >= 0 &&
                  OPENPBR_WORKING_SPACE < static_cast<int>(colour_table::working_space_names.size()),
              "OPENPBR_WORKING_SPACE has no column in host/scene/colour_space_table.h");
constexpr std::size_t working_space = OPENPBR_WORKING_SPACE;

const colour_table::FileSpace* find_space(const std::string_view name)
{
    for (const colour_table::FileSpace& space : colour_table::file_spaces)
    {
        if (space.name == name)
        {
            return &space;
        }
    }
    return nullptr;
}

// Encoded -> linear for one channel; the same operations, in the same order, as
// viewer/src/colour_spaces.mjs's decode.
double decode(const colour_table::FileSpace& space, const double value)
{
    const double magnitude = std::fabs(value);
    double linear = magnitude;
    if (space.transfer == colour_table::Transfer::srgb)
    {
        linear = magnitude <= 0.04045 ? magnitude / 12.92 : std::pow((magnitude + 0.055) / 1.055, 2.4);
    }
    else if (space.transfer == colour_table::Transfer::gamma)
    {
        linear = std::pow(magnitude, space.exponent);
    }
    return value < 0.0 ? -linear : linear;
}

glm::vec3 multiply(const std::array<double, 9>& matrix, const std::array<double, 3>& value)
{
    glm::vec3 result;
    for (int row = 0; row < 3; ++row)
    {
        const std::size_t at = std::size_t(3 * row);
        result[row] = float(matrix[at] * value[0] + matrix[at + 1] * value[1] + matrix[at + 2] * value[2]);
    }
    return result;
}

std::array<double, 3> as_doubles(const glm::vec3 value) { return {double(value.x), double(value.y), double(value.z)}; }

}  // namespace

std::string_view working_space_name() { return colour_table::working_space_names[working_space]; }

std::string_view default_document_colour_space() { return colour_table::default_document_space; }

std::string colour_space_names()
{
    std::string names;
    for (const colour_table::FileSpace& space : colour_table::file_spaces)
    {
        names += (names.empty() ? "" : ", ") + std::string(space.name);
    }
    return names;
}

std::optional<glm::vec3> colour_to_working_space(const std::string_view space_name, const glm::vec3 encoded,
                                                 const std::string_view working_space_name)
{
    const colour_table::FileSpace* const space = find_space(space_name);
    const auto& names = colour_table::working_space_names;
    const auto working = std::find(names.begin(), names.end(), working_space_name);
    if (space == nullptr || working == names.end())
    {
        return std::nullopt;
    }
    const std::array<double, 3> linear = {decode(*space, encoded.x), decode(*space, encoded.y), decode(*space, encoded.z)};
    return multiply(space->to_working[std::size_t(working - names.begin())], linear);
}

std::optional<glm::vec3> colour_to_working_space(const std::string_view space_name, const glm::vec3 encoded)
{
    return colour_to_working_space(space_name, encoded, working_space_name());
}

glm::vec3 rec709_to_working_space(const glm::vec3 linear)
{
    return multiply(find_space("lin_rec709")->to_working[working_space], as_doubles(linear));
}

glm::vec3 working_space_to_display(const glm::vec3 working)
{
    return multiply(colour_table::working_to_display[working_space], as_doubles(working));
}

}  // namespace openpbr::host
