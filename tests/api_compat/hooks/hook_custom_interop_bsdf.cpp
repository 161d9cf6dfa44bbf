// The BSDF built through the host's interop layer (custom_interop_host.h): a translation unit of
// its own, since its functions live in namespace renderer_bsdf.
#include "tests/api_compat/hooks/custom_interop_host.h"

#include "slang/openpbr.h"

#if defined(OPENPBR_INTEROP_CPP_H)
#error "OPENPBR_USE_CUSTOM_INTEROP=1 but the C++ backend was included"
#endif

#include "tests/api_compat/hooks/custom_interop_host_switches.h"
#include "tests/api_compat/hooks/hook_custom_interop.h"

// Only reachable if OPENPBR_NAMESPACE_BEGIN came from the host: renderer_bsdf::openpbr_prepare.
float custom_interop_shade(const float* material_values, const float* view_values, const float* u_values, float* out)
{
    renderer_bsdf::OpenPBR_ResolvedInputs inputs = renderer_bsdf::openpbr_make_default_resolved_inputs();
    inputs.base_color = glm::vec3(material_values[0], material_values[1], material_values[2]);
    inputs.coat_weight = material_values[3];
    inputs.fuzz_weight = material_values[4];
    inputs.specular_roughness = material_values[5];
    const glm::vec3 view(view_values[0], view_values[1], view_values[2]);
    const renderer_bsdf::OpenPBR_PreparedBsdf prepared = renderer_bsdf::openpbr_prepare(
        inputs, glm::vec3(1.0f), renderer_bsdf::OpenPBR_BaseRgbWavelengths_nm, renderer_bsdf::OpenPBR_VacuumIor, view);
    const renderer_bsdf::OpenPBR_BsdfSample bsdf_sample =
        renderer_bsdf::openpbr_sample(prepared, glm::vec3(u_values[0], u_values[1], u_values[2]));
    out[0] = bsdf_sample.pdf;
    out[1] = bsdf_sample.weight.specular.x + bsdf_sample.weight.diffuse.x;
    out[2] = prepared.probability_coat;
    return prepared.probability_fuzz;
}

void custom_interop_set_enabled_features(unsigned mask) { renderer::enabled_features = mask; }
