// parameter_table.h - the parameter table of slang/openpbr_parameters.h as C++ data, for code
// that reads parameters by name: the MaterialX loader (material_library.cpp) and the stability
// corpus reader (host/checks/stability.cpp). One descriptor per named input, in table order;
// a basis contributes two (its normal and its tangent input), e.g. geometry_coat_basis gives
// geometry_coat_normal and geometry_coat_tangent.
#pragma once

#include <optional>
#include <string_view>
#include <variant>
#include <vector>

#include "slang/openpbr.h"

namespace openpbr::host {

using ParameterInputs = openpbr::OpenPBR_ResolvedInputs;

// One of the two vector3 inputs that make a basis: the bases are built only after every input
// is read, because a tangent frame needs its normal and tangent together.
struct GeometryVector
{
    std::size_t basis = 0;  // index into parameter_bases()
    bool tangent = false;   // false: the basis's normal input
};

using ParameterTarget = std::variant<float ParameterInputs::*, glm::vec3 ParameterInputs::*, bool ParameterInputs::*,
                                     glm::vec2 ParameterInputs::*, GeometryVector>;

struct ParameterDescriptor
{
    const char* name;  // the input name, e.g. "base_color", "geometry_normal"
    ParameterTarget target;
    // True for OpenPBR 1.1.1 inputs (a MaterialX <open_pbr_surface> input of the same name);
    // false for the extensions (the anisotropy rotations), which only the corpus reads.
    bool materialx = true;
};

struct ParameterBasis
{
    OpenPBR_Basis ParameterInputs::*field;  // e.g. &OpenPBR_ResolvedInputs::geometry_basis
    const char* normal_name;                // e.g. "geometry_normal"
    const char* tangent_name;               // e.g. "geometry_tangent"
};

// Every named input, in table order (the specification's order, extensions last).
const std::vector<ParameterDescriptor>& parameter_descriptors();

// The bases of the table, in table order.
const std::vector<ParameterBasis>& parameter_bases();

// The descriptor of an input name, or nullptr.
const ParameterDescriptor* find_parameter(std::string_view name);

// The normal and tangent inputs read so far, per basis of parameter_bases(); unset means the
// reader's default for that vector.
struct GeometryVectors
{
    std::vector<std::optional<glm::vec3>> normals = std::vector<std::optional<glm::vec3>>(parameter_bases().size());
    std::vector<std::optional<glm::vec3>> tangents = std::vector<std::optional<glm::vec3>>(parameter_bases().size());

    std::optional<glm::vec3>& operator[](const GeometryVector& vector)
    {
        return vector.tangent ? tangents[vector.basis] : normals[vector.basis];
    }
};

}  // namespace openpbr::host
