// The single-source headers as C++ (GLM backend), compiled by the targets_cpp_* tests with
// g++ and clang++ under -Wall -Wextra -Werror, in array mode (default) and, with
// -DOPENPBR_LUT_MODE_BUFFER, in buffer mode. Every entry point is used, so the inline code is
// compiled, not only parsed.
#include "slang/openpbr.h"

namespace {
const float* material_floats = nullptr;
}  // namespace

#define OPENPBR_MATERIAL_READ(index) material_floats[index]
#include "slang/openpbr_material_packing.h"

float openpbr_headers_warning_check(const float* packed, unsigned material, float x)
{
    material_floats = packed;
    const openpbr::OpenPBR_ResolvedInputs inputs = openpbr::openpbr_unpack_material(material);
    const glm::vec3 view = glm::normalize(glm::vec3(x, 0.2f, 1.0f));
    const glm::vec3 light = glm::normalize(glm::vec3(-x, 0.1f, 1.0f));
    const openpbr::OpenPBR_PreparedBsdf bsdf = openpbr::openpbr_prepare(inputs, view);
    const openpbr::OpenPBR_DiffuseSpecular value = openpbr::openpbr_eval(bsdf, light);
    const openpbr::OpenPBR_BsdfSample sample = openpbr::openpbr_sample(bsdf, glm::vec3(0.25f, 0.5f, 0.75f));
    return value.diffuse.x + value.specular.y + openpbr::openpbr_pdf(bsdf, light) + sample.pdf + bsdf.emission.z;
}
