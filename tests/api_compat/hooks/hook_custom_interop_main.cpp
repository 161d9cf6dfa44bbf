// OPENPBR_USE_CUSTOM_INTEROP and OPENPBR_GET_SPECIALIZATION_CONSTANT with the coarse toggle
// names: the BSDF compiled through a host's interop layer (namespace renderer_bsdf, the host's
// feature switches) gives bit for bit what the standard build gives, and switching the coarse
// EnableSheenAndCoat off through the host's macro removes coat and fuzz, as switching off the
// fine EnableCoat and EnableFuzz does in the standard build.
#include <glm/glm.hpp>

#include "slang/openpbr.h"
#include "tests/api_compat/hooks/custom_interop_host_switches.h"
#include "tests/api_compat/hooks/hook_custom_interop.h"

#include <cstdio>
#include <cstring>

namespace {
unsigned bits(float value)
{
    unsigned word = 0;
    std::memcpy(&word, &value, sizeof(word));
    return word;
}
}  // namespace

int main()
{
    using namespace openpbr;
    int failures = 0;
    const float material[6] = {0.7f, 0.3f, 0.2f, 0.6f, 0.4f, 0.35f};
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.base_color = glm::vec3(material[0], material[1], material[2]);
    inputs.coat_weight = material[3];
    inputs.fuzz_weight = material[4];
    inputs.specular_roughness = material[5];
    for (int coarse_off = 0; coarse_off < 2; ++coarse_off)
    {
        // Host build: its own switch word, the coarse toggle. Standard build: the fine toggles.
        custom_interop_set_enabled_features(coarse_off ? ~(1u << OPENPBR_SPECIALIZATION_ID_EnableSheenAndCoat)
                                                       : 0xffffffffu);
        openpbr_runtime_feature_mask = coarse_off ? ~(OPENPBR_FEATURE_BIT_COAT | OPENPBR_FEATURE_BIT_FUZZ) : 0xffffffffu;
        for (int query = 0; query < 64; ++query)
        {
            const float view[3] = {0.1f * float(query % 7) - 0.3f, 0.05f * float(query % 5), 1.0f};
            const float u[3] = {float(query) / 64.0f, float((query * 37) % 64) / 64.0f,
                                float((query * 11) % 64) / 64.0f + 0.005f};
            float custom[3] = {0.0f, 0.0f, 0.0f};
            const float custom_fuzz = custom_interop_shade(material, view, u, custom);
            const OpenPBR_PreparedBsdf prepared = openpbr_prepare(inputs, glm::vec3(view[0], view[1], view[2]));
            const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(prepared, glm::vec3(u[0], u[1], u[2]));
            const float standard[3] = {bsdf_sample.pdf, bsdf_sample.weight.specular.x + bsdf_sample.weight.diffuse.x,
                                       prepared.probability_coat};
            for (int index = 0; index < 3; ++index)
            {
                if (bits(custom[index]) != bits(standard[index]))
                {
                    ++failures;
                    std::printf("coarse_off %d query %d value %d: host interop %.9g, standard %.9g\n", coarse_off, query,
                                index, double(custom[index]), double(standard[index]));
                }
            }
            if (bits(custom_fuzz) != bits(prepared.probability_fuzz))
            {
                ++failures;
            }
            // The coarse toggle took effect: no coat, no fuzz.
            if (coarse_off && (custom[2] != 0.0f || custom_fuzz != 0.0f))
            {
                ++failures;
                std::printf("EnableSheenAndCoat off through the host macro, but coat %g fuzz %g remain\n", double(custom[2]),
                            double(custom_fuzz));
            }
            if (!coarse_off && !(custom[2] > 0.0f && custom_fuzz > 0.0f))
            {
                ++failures;
                std::printf("coat and fuzz missing with every feature on\n");
            }
        }
    }
    std::printf("custom interop: %s (%d failures)\n", failures == 0 ? "ok" : "FAIL", failures);
    return failures == 0 ? 0 : 1;
}
