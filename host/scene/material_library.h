// material_library.h - loads OpenPBR materials from MaterialX (.mtlx) documents into
// openpbr::OpenPBR_ResolvedInputs, so hosts and tests can render the bundled example materials
// in materials/ (and user files of the same shape) without linking MaterialX.
//
// Supported subset: top-level <open_pbr_surface> nodes whose inputs are constant values, each
// found through a <surfacematerial> whose "surfaceshader" input names the node (or, for a node
// that no surfacematerial references, on its own, named by the node's name). Textures, node
// graphs and any other connected input are rejected with an error rather than silently
// replaced by a default, because a silently wrong material is harder to notice than an error.
//
// Values are kept as written, including values outside the ranges the specification
// documents: openpbr_prepare clamps them (README "Input contract"), and a loader that clamped
// too would hide what the file really says. The one change: every color3 value is converted
// from its colour space (its input's colorspace attribute, else the document's, else ACEScg,
// the specification's default) into the library's working space (host/scene/colour_spaces.h,
// docs/colour.md); an unknown colour space is an error naming it. An <open_pbr_surface> may
// name its version: 1.1 and 1.1.1 are read, any other is an error.
//
// Link dependencies: pugixml (CMake: find_package(pugixml), target pugixml::pugixml), GLM
// (header-only, via slang/openpbr_resolved_inputs.h); include directory: the repository root.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/openpbr_resolved_inputs.h"

namespace openpbr::host {

// Every loader failure: unreadable file, malformed XML, unsupported or invalid input. The
// message names the file, the line and column where known, and the input concerned.
class MaterialError : public std::runtime_error
{
  public:
    explicit MaterialError(const std::string& message) : std::runtime_error(message) {}
    ~MaterialError() override;  // defined in the .cpp so the vtable lives in one object file
};

struct Material
{
    std::string name;                        // the surfacematerial's name, e.g. "Glass"; the node's name for a bare node
    std::string file;                        // the path the material was loaded from, as given; empty for built-ins
    std::string colorspace;                  // the document's colour space, e.g. "acescg" (also when it names none)
    openpbr::OpenPBR_ResolvedInputs inputs;  // spec defaults, overridden by the file's values
    std::vector<std::string> inputs_set;     // OpenPBR input names given in the file, file order
};

// One Material per <surfacematerial> that references an <open_pbr_surface>, then one per
// <open_pbr_surface> that no surfacematerial references, in document order. Throws
// MaterialError when the file yields no material or anything in it is invalid or unsupported.
std::vector<Material> load_materialx_file(const std::string& path);

// Every "*.mtlx" file directly in `directory`, sorted by file name, materials of each file in
// document order. Throws MaterialError when the directory cannot be listed or a file fails.
std::vector<Material> load_material_directory(const std::string& directory);

// The specification's defaults, named "Default".
Material default_material();

// "Glass (materials/open_pbr_glass.mtlx): specular_roughness = 0, specular_ior = 1.52, ..."
// listing only inputs whose value differs from the specification's default.
std::string describe(const Material& material);

// The names of every OpenPBR 1.1.1 input the loader understands, in specification order.
std::vector<std::string> supported_input_names();

}  // namespace openpbr::host
