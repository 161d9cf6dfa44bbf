// colour_spaces.h - colour management of the host: MaterialX colour spaces into the library's
// working space (slang/openpbr_working_space.h, OPENPBR_WORKING_SPACE), and the working space
// out to the display's primaries (docs/colour.md).
//
// The numbers are generated (tools/make_colour_tables.py -> host/scene/colour_space_table.h,
// the same table as the viewer's viewer/src/colour_spaces.mjs): per MaterialX name, a transfer
// function (linear, the sRGB curve of IEC 61966-2-1, or a pure power) and a 3 x 3 matrix from
// its linear RGB into each working space, with Bradford adaptation between white points.
// Conversions run in double precision and round to float once, so the C++ and JavaScript
// loaders give the same floats (tests/scene/test_colour_spaces.cpp and colour_spaces_test.mjs
// reproduce tests/data/colour_conversions.json).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

namespace openpbr::host {

// The MaterialX name of the working space this build uses, e.g. "acescg".
std::string_view working_space_name();

// What a MaterialX document that names no colour space is in (the OpenPBR specification,
// "Metadata": ACEScg).
std::string_view default_document_colour_space();

// Every colour space name the loader accepts, comma-separated, for messages: the MaterialX
// names (acescg, lin_rec709, srgb_texture, ...) and their other spellings (lin_ap1, the ASWF
// Color Interop Forum identifiers such as lin_rec709_scene, the legacy gamma18 and gamma22).
std::string colour_space_names();

// A color3 value as written in colour space `space` -> linear working-space RGB, e.g.
// ("srgb_texture", (1, 0.5, 0)) -> the working space's linear values. Negative encoded values
// decode to the negative of their magnitude's decoding (the curves extended oddly); nothing is
// clamped here (openpbr_prepare's input contract clamps). std::nullopt for an unknown name.
std::optional<glm::vec3> colour_to_working_space(std::string_view space, glm::vec3 encoded);

// The same into a named working space ("lin_rec709" or "acescg") rather than this build's,
// e.g. for tests; std::nullopt when either name is unknown.
std::optional<glm::vec3> colour_to_working_space(std::string_view space, glm::vec3 encoded, std::string_view working_space);

// Linear Rec.709 -> the working space, e.g. for the preview scene's light and sky, which are
// given in Rec.709.
glm::vec3 rec709_to_working_space(glm::vec3 linear);

// The working space -> linear Rec.709, the display's primaries (the first step of the view
// transform, before the tone curve). Colours outside Rec.709 come out with negative components.
glm::vec3 working_space_to_display(glm::vec3 working);

}  // namespace openpbr::host
