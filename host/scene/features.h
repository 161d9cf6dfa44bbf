// features.h - scene analysis for the feature toggles of slang/openpbr_features.h: which
// toggles a material needs, the smallest set for a scene, the specialization info a host passes
// to vkCreateComputePipelines, a refusal when a pipeline lacks a feature a material needs, and
// a cache of compute pipelines keyed by toggle set.
//
// A toggle set is a mask of OPENPBR_FEATURE_BIT_* (bit k = the toggle with constant id k).
//
// Link dependencies: the host library (vulkan_runner, material_library), nlohmann-json.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/scene/material_library.h"
#include "host/gpu/vulkan_runner.h"

namespace openpbr::host {

// One toggle: its name on the command line and in JSON (e.g. "thin_film"), its mask bit and
// its specialization constant (name and stable id, e.g. "EnableThinFilm", 5).
struct FeatureToggle
{
    const char* name;
    std::uint32_t bit;
    const char* constant_name;
    std::uint32_t constant_id;
};

// The ten toggles in constant-id order.
const std::vector<FeatureToggle>& feature_toggles();

// Every toggle on: the full pipeline.
std::uint32_t full_feature_mask();

// Toggles a material needs to render exactly (the input contract applied first).
std::uint32_t required_feature_mask(const openpbr::OpenPBR_ResolvedInputs& inputs);
std::uint32_t required_feature_mask(const Material& material);

// The smallest toggle set that renders every material exactly: the union of their needs.
std::uint32_t scene_feature_mask(const std::vector<Material>& materials);

// {"coat", "metal"}; an empty mask gives an empty list (base layer only).
std::vector<std::string> feature_names(std::uint32_t mask);
// "coat+metal", or "base" for the empty mask.
std::string feature_set_label(std::uint32_t mask);
// Inverse of feature_names; throws std::invalid_argument naming an unknown toggle. "all" is
// every toggle, "none" or "base" none.
std::uint32_t parse_feature_names(const std::vector<std::string>& names);

// A material needs a feature the pipeline switched off.
class FeatureError : public std::runtime_error
{
  public:
    explicit FeatureError(const std::string& message) : std::runtime_error(message) {}
    ~FeatureError() override;
};

// Throws FeatureError naming the first material (and its file) and every feature it needs that
// `pipeline_mask` lacks: such a material would otherwise render silently without it.
void check_pipeline_supports(const std::vector<Material>& materials, std::uint32_t pipeline_mask);

// The specialization constants for a toggle set: one bool per constant id (the legacy aliases
// stay on: they only switch features off), e.g. for ComputePipelineDescription.
std::vector<SpecializationConstant> specialization_constants(std::uint32_t mask);

// The compile-time form of a toggle set (slang/openpbr_features.h): the preprocessor defines
// that fold it when a target is generated, for Slang (`-D`) or the library generators:
// OPENPBR_SPECIALIZATION_CONSTANTS=0, then OPENPBR_FEATURE_<NAME>=0 for each toggle outside the
// mask, e.g. {"OPENPBR_SPECIALIZATION_CONSTANTS=0", "OPENPBR_FEATURE_FUZZ=0", ...} for coat+metal.
// The viewer builds the same list in the page (viewer/features.mjs, specializationDefines).
std::vector<std::string> specialization_defines(std::uint32_t mask);

// The VkSpecializationInfo the host passes to vkCreateComputePipelines, as JSON:
// {"mapEntries": [{"constantID": i, "offset": o, "size": 4}], "data": [VkBool32...]}.
nlohmann::json specialization_info_json(std::uint32_t mask);

// `openpbr features` as JSON: per material its needs, the scene's smallest set and its
// specialization info.
nlohmann::json features_report_json(const std::vector<Material>& materials);
std::string features_report_text(const std::vector<Material>& materials);

// Sets the C++ build's run-time toggles (openpbr::openpbr_runtime_feature_mask) for a scope and
// restores the previous mask; not for use while other threads shade.
class ScopedFeatureMask
{
  public:
    explicit ScopedFeatureMask(std::uint32_t mask);
    ~ScopedFeatureMask();
    ScopedFeatureMask(const ScopedFeatureMask&) = delete;
    ScopedFeatureMask& operator=(const ScopedFeatureMask&) = delete;

  private:
    std::uint32_t previous_;
};

// Compute pipelines of one kernel, one per toggle set, built on first use and kept: a second
// request for the same set returns the same pipeline without rebuilding.
class SpecializedPipelineCache
{
  public:
    // `base` without specialization constants; the cache adds them per toggle set.
    SpecializedPipelineCache(const VulkanContext& context, ComputePipelineDescription base);

    ComputePipeline& pipeline(std::uint32_t mask);
    // How many pipelines were built so far (cache misses).
    std::size_t build_count() const { return build_count_; }

  private:
    const VulkanContext* context_;
    ComputePipelineDescription base_;
    std::map<std::uint32_t, std::unique_ptr<ComputePipeline>> pipelines_;
    std::size_t build_count_ = 0;
};

}  // namespace openpbr::host
