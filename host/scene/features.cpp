#include "host/scene/features.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <utility>

#include "slang/openpbr.h"

namespace openpbr::host {

FeatureError::~FeatureError() = default;

const std::vector<FeatureToggle>& feature_toggles()
{
    static const std::vector<FeatureToggle> toggles = {
        {"coat", OPENPBR_FEATURE_BIT_COAT, "EnableCoat", OPENPBR_SPECIALIZATION_ID_EnableCoat},
        {"fuzz", OPENPBR_FEATURE_BIT_FUZZ, "EnableFuzz", OPENPBR_SPECIALIZATION_ID_EnableFuzz},
        {"metal", OPENPBR_FEATURE_BIT_METAL, "EnableMetal", OPENPBR_SPECIALIZATION_ID_EnableMetal},
        {"transmission", OPENPBR_FEATURE_BIT_TRANSMISSION, "EnableTransmission",
         OPENPBR_SPECIALIZATION_ID_EnableTransmission},
        {"dispersion", OPENPBR_FEATURE_BIT_DISPERSION, "EnableDispersion", OPENPBR_SPECIALIZATION_ID_EnableDispersion},
        {"thin_film", OPENPBR_FEATURE_BIT_THIN_FILM, "EnableThinFilm", OPENPBR_SPECIALIZATION_ID_EnableThinFilm},
        {"thin_walled", OPENPBR_FEATURE_BIT_THIN_WALLED, "EnableThinWalled", OPENPBR_SPECIALIZATION_ID_EnableThinWalled},
        {"subsurface", OPENPBR_FEATURE_BIT_SUBSURFACE, "EnableSubsurface", OPENPBR_SPECIALIZATION_ID_EnableSubsurface},
        {"emission", OPENPBR_FEATURE_BIT_EMISSION, "EnableEmission", OPENPBR_SPECIALIZATION_ID_EnableEmission},
        {"anisotropy", OPENPBR_FEATURE_BIT_ANISOTROPY, "EnableAnisotropy", OPENPBR_SPECIALIZATION_ID_EnableAnisotropy},
    };
    return toggles;
}

std::uint32_t full_feature_mask() { return OPENPBR_FEATURE_MASK_ALL; }

std::uint32_t required_feature_mask(const openpbr::OpenPBR_ResolvedInputs& inputs)
{
    return openpbr::openpbr_required_feature_mask(openpbr::openpbr_apply_input_contract(inputs));
}

std::uint32_t required_feature_mask(const Material& material) { return required_feature_mask(material.inputs); }

std::uint32_t scene_feature_mask(const std::vector<Material>& materials)
{
    std::uint32_t mask = 0;
    for (const Material& material : materials)
    {
        mask |= required_feature_mask(material);
    }
    return mask;
}

std::vector<std::string> feature_names(std::uint32_t mask)
{
    std::vector<std::string> names;
    for (const FeatureToggle& toggle : feature_toggles())
    {
        if ((mask & toggle.bit) != 0)
        {
            names.push_back(toggle.name);
        }
    }
    return names;
}

std::string feature_set_label(std::uint32_t mask)
{
    const std::vector<std::string> names = feature_names(mask);
    if (names.empty())
    {
        return "base";
    }
    std::string label;
    for (const std::string& name : names)
    {
        label += (label.empty() ? "" : "+") + name;
    }
    return label;
}

std::uint32_t parse_feature_names(const std::vector<std::string>& names)
{
    std::uint32_t mask = 0;
    for (const std::string& name : names)
    {
        if (name == "all")
        {
            mask |= full_feature_mask();
            continue;
        }
        if (name == "none" || name == "base")
        {
            continue;
        }
        bool known = false;
        for (const FeatureToggle& toggle : feature_toggles())
        {
            if (name == toggle.name)
            {
                mask |= toggle.bit;
                known = true;
            }
        }
        if (!known)
        {
            std::string list;
            for (const FeatureToggle& toggle : feature_toggles())
            {
                list += std::string(list.empty() ? "" : ", ") + toggle.name;
            }
            throw std::invalid_argument("unknown feature '" + name + "'; known: " + list + ", all, none");
        }
    }
    return mask;
}

void check_pipeline_supports(const std::vector<Material>& materials, std::uint32_t pipeline_mask)
{
    for (const Material& material : materials)
    {
        const std::uint32_t missing = required_feature_mask(material) & ~pipeline_mask;
        if (missing != 0)
        {
            std::string features;
            for (const std::string& name : feature_names(missing))
            {
                features += (features.empty() ? "" : ", ") + name;
            }
            throw FeatureError("material '" + material.name + "'" +
                               (material.file.empty() ? std::string() : " (" + material.file + ")") + " needs " + features +
                               ", which the pipeline specialized to {" + feature_set_label(pipeline_mask) +
                               "} switched off; refusing to render it without (use a pipeline with those features)");
        }
    }
}

std::vector<SpecializationConstant> specialization_constants(std::uint32_t mask)
{
    std::vector<SpecializationConstant> constants;
    for (const FeatureToggle& toggle : feature_toggles())
    {
        constants.push_back(SpecializationConstant::of_bool(toggle.constant_id, (mask & toggle.bit) != 0));
    }
    // The legacy aliases (EnableSheenAndCoat, EnableTranslucency, EnableMetallic) keep their
    // default (true): the new toggles above already say everything.
    return constants;
}

std::vector<std::string> specialization_defines(std::uint32_t mask)
{
    // Without specialization constants every OPENPBR_GET_SPECIALIZATION_CONSTANT is on, so only
    // the toggles switched off need a define.
    std::vector<std::string> defines = {"OPENPBR_SPECIALIZATION_CONSTANTS=0"};
    for (const FeatureToggle& toggle : feature_toggles())
    {
        if ((mask & toggle.bit) == 0)
        {
            std::string name = toggle.name;
            std::transform(name.begin(), name.end(), name.begin(),
                           [](unsigned char character) { return char(std::toupper(character)); });
            defines.push_back("OPENPBR_FEATURE_" + name + "=0");
        }
    }
    return defines;
}

nlohmann::json specialization_info_json(std::uint32_t mask)
{
    nlohmann::json entries = nlohmann::json::array();
    nlohmann::json data = nlohmann::json::array();
    std::uint32_t offset = 0;
    for (const SpecializationConstant& constant : specialization_constants(mask))
    {
        entries.push_back({{"constantID", constant.id}, {"offset", offset}, {"size", 4}});
        data.push_back(constant.value_bits);
        offset += 4;
    }
    return {{"mapEntryCount", entries.size()}, {"mapEntries", entries}, {"dataSize", offset}, {"data", data}};
}

nlohmann::json features_report_json(const std::vector<Material>& materials)
{
    nlohmann::json list = nlohmann::json::array();
    for (const Material& material : materials)
    {
        list.push_back(
            {{"name", material.name}, {"file", material.file}, {"toggles", feature_names(required_feature_mask(material))}});
    }
    const std::uint32_t scene = scene_feature_mask(materials);
    nlohmann::json constants = nlohmann::json::array();
    for (const FeatureToggle& toggle : feature_toggles())
    {
        constants.push_back(
            {{"name", toggle.constant_name}, {"id", toggle.constant_id}, {"value", (scene & toggle.bit) != 0}});
    }
    return {{"materials", list},
            {"toggles", feature_names(scene)},
            {"mask", scene},
            {"specialization_constants", constants},
            {"specialization_info", specialization_info_json(scene)}};
}

std::string features_report_text(const std::vector<Material>& materials)
{
    std::ostringstream text;
    for (const Material& material : materials)
    {
        text << material.name << ": " << feature_set_label(required_feature_mask(material)) << "\n";
    }
    const std::uint32_t scene = scene_feature_mask(materials);
    text << "scene toggle set (" << materials.size() << " materials): " << feature_set_label(scene) << "\n";
    text << "specialization constants (VkSpecializationInfo, 4-byte VkBool32 each):\n";
    std::uint32_t offset = 0;
    for (const FeatureToggle& toggle : feature_toggles())
    {
        text << "  constantID " << toggle.constant_id << " offset " << offset << " " << toggle.constant_name << " = "
             << ((scene & toggle.bit) != 0 ? "VK_TRUE" : "VK_FALSE") << "\n";
        offset += 4;
    }
    return text.str();
}

ScopedFeatureMask::ScopedFeatureMask(std::uint32_t mask) : previous_(openpbr::openpbr_runtime_feature_mask)
{
    // Only the ten feature bits change; the legacy alias bits stay on.
    openpbr::openpbr_runtime_feature_mask = (previous_ & ~full_feature_mask()) | (mask & full_feature_mask());
}

ScopedFeatureMask::~ScopedFeatureMask() { openpbr::openpbr_runtime_feature_mask = previous_; }

SpecializedPipelineCache::SpecializedPipelineCache(const VulkanContext& context, ComputePipelineDescription base)
    : context_(&context), base_(std::move(base))
{
}

ComputePipeline& SpecializedPipelineCache::pipeline(std::uint32_t mask)
{
    const std::uint32_t key = mask & full_feature_mask();
    auto found = pipelines_.find(key);
    if (found != pipelines_.end())
    {
        return *found->second;
    }
    ComputePipelineDescription description = base_;
    description.specialization_constants = specialization_constants(key);
    auto built = std::make_unique<ComputePipeline>(*context_, description);
    ++build_count_;
    return *pipelines_.emplace(key, std::move(built)).first->second;
}

}  // namespace openpbr::host
