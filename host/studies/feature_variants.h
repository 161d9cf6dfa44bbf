// feature_variants.h - the materials of the per-feature cost tables in docs/performance.md
// ("Cost per feature (CPU)" from benchmarks/benchmark_bsdf.cpp, "Cost per feature (lavapipe)"
// from `openpbr bench gpu --features`), one list for both so the two tables measure the same
// materials.
//
// The every-lobe material has each feature of the OpenPBR 1.1 surface (spec sections "Base",
// "Specular", "Transmission", "Subsurface", "Fuzz", "Coat", "Thin film", "Emission") at a
// partial weight. Per feature two variants are read against a baseline:
//   "Only/<feature>":    the default material plus that feature as the every-lobe material sets
//                        it, read against "Default" (what the feature adds alone);
//   "Without/<feature>": the every-lobe material without that feature, read against
//                        "EveryLobe" (what leaving it out saves when everything else is on).
//
// Header-only; link dependencies: none beyond GLM and slang/ (include directory: the
// repository root).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/openpbr_resolved_inputs.h"

namespace openpbr::host {

// One feature of the every-lobe material: its name (e.g. "thin_film") and how it is switched on
// (to the every-lobe value) and off (to the value that disables it, the spec default).
struct CostFeature
{
    const char* name;
    void (*switch_on)(openpbr::OpenPBR_ResolvedInputs&);
    void (*switch_off)(openpbr::OpenPBR_ResolvedInputs&);
};

// The features in table order.
inline const std::vector<CostFeature>& cost_features()
{
    using openpbr::OpenPBR_ResolvedInputs;
    static const std::vector<CostFeature> features = {
        {"metal", [](OpenPBR_ResolvedInputs& m) { m.base_metalness = 0.3f; },
         [](OpenPBR_ResolvedInputs& m) { m.base_metalness = 0.0f; }},
        {"diffuse_roughness", [](OpenPBR_ResolvedInputs& m) { m.base_diffuse_roughness = 0.5f; },
         [](OpenPBR_ResolvedInputs& m) { m.base_diffuse_roughness = 0.0f; }},
        {"anisotropy", [](OpenPBR_ResolvedInputs& m) { m.specular_roughness_anisotropy = 0.5f; },
         [](OpenPBR_ResolvedInputs& m) { m.specular_roughness_anisotropy = 0.0f; }},
        {"transmission", [](OpenPBR_ResolvedInputs& m) { m.transmission_weight = 0.3f; },
         [](OpenPBR_ResolvedInputs& m) { m.transmission_weight = 0.0f; }},
        {"subsurface", [](OpenPBR_ResolvedInputs& m) { m.subsurface_weight = 0.3f; },
         [](OpenPBR_ResolvedInputs& m) { m.subsurface_weight = 0.0f; }},
        {"fuzz", [](OpenPBR_ResolvedInputs& m) { m.fuzz_weight = 0.3f; },
         [](OpenPBR_ResolvedInputs& m) { m.fuzz_weight = 0.0f; }},
        {"coat",
         [](OpenPBR_ResolvedInputs& m) {
             m.coat_weight = 0.5f;
             m.coat_roughness = 0.2f;
             m.coat_color = glm::vec3(0.9f, 0.8f, 0.7f);
         },
         [](OpenPBR_ResolvedInputs& m) { m.coat_weight = 0.0f; }},
        {"thin_film", [](OpenPBR_ResolvedInputs& m) { m.thin_film_weight = 0.5f; },
         [](OpenPBR_ResolvedInputs& m) { m.thin_film_weight = 0.0f; }},
        {"emission", [](OpenPBR_ResolvedInputs& m) { m.emission_luminance = 1.0f; },
         [](OpenPBR_ResolvedInputs& m) { m.emission_luminance = 0.0f; }},
    };
    return features;
}

// Every feature switched on: the most expensive configuration of the list.
inline openpbr::OpenPBR_ResolvedInputs every_lobe_material()
{
    openpbr::OpenPBR_ResolvedInputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    for (const CostFeature& feature : cost_features())
    {
        feature.switch_on(inputs);
    }
    return inputs;
}

// One row of a cost table: its name ("Default", "EveryLobe", "Only/coat", "Without/coat") and
// its inputs.
struct FeatureVariant
{
    std::string name;
    openpbr::OpenPBR_ResolvedInputs inputs;
};

// "Default", "EveryLobe", then per feature in cost_features() order "Only/<feature>" and
// "Without/<feature>".
inline std::vector<FeatureVariant> feature_variants()
{
    std::vector<FeatureVariant> variants;
    variants.push_back({"Default", openpbr::openpbr_make_default_resolved_inputs()});
    variants.push_back({"EveryLobe", every_lobe_material()});
    for (const CostFeature& feature : cost_features())
    {
        FeatureVariant only{std::string("Only/") + feature.name, openpbr::openpbr_make_default_resolved_inputs()};
        feature.switch_on(only.inputs);
        variants.push_back(only);
        FeatureVariant without{std::string("Without/") + feature.name, every_lobe_material()};
        feature.switch_off(without.inputs);
        variants.push_back(without);
    }
    return variants;
}

}  // namespace openpbr::host
