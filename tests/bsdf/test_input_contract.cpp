// The input contract (README "Input contract", slang/openpbr_input_contract.h): every field of
// OpenPBR_ResolvedInputs is clamped to its documented range (NaN to the field's default,
// infinities to the nearer bound), OPENPBR_CLAMP_HOOK reports exactly the clamps that change a
// value, and preparing raw inputs gives the same BSDF as preparing the already-clamped inputs.
//
// This file defines the hook before including the BSDF, so it is built as its own executable
// (tests/stability/CMakeLists.txt): no other object in it may include slang/openpbr.h.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

struct ClampRecord
{
    std::string field;
    float before;
    float after;
};

std::vector<ClampRecord>& clamp_log()
{
    static std::vector<ClampRecord> log;
    return log;
}

#define OPENPBR_CLAMP_HOOK(name, before, after) clamp_log().push_back(ClampRecord{name, before, after})
#include "slang/openpbr.h"

#include <gtest/gtest.h>

namespace {

using openpbr::OpenPBR_ResolvedInputs;
using Inputs = OpenPBR_ResolvedInputs;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// The documented ranges (README "Input contract"), written out independently of the header.
struct FieldRange
{
    const char* name;
    float Inputs::*scalar;
    glm::vec3 Inputs::*color;
    float low;
    float high;
};

constexpr float ior_low = 1.0f / 3.0f;
constexpr float length_max = 1e18f;

const std::vector<FieldRange>& fields()
{
    static const std::vector<FieldRange> table = {
        {"base_weight", &Inputs::base_weight, nullptr, 0.0f, 1.0f},
        {"base_color", nullptr, &Inputs::base_color, 0.0f, 1.0f},
        {"base_diffuse_roughness", &Inputs::base_diffuse_roughness, nullptr, 0.0f, 1.0f},
        {"base_metalness", &Inputs::base_metalness, nullptr, 0.0f, 1.0f},
        {"specular_weight", &Inputs::specular_weight, nullptr, 0.0f, 1e6f},
        {"specular_color", nullptr, &Inputs::specular_color, 0.0f, 1.0f},
        {"specular_roughness", &Inputs::specular_roughness, nullptr, 0.0f, 1.0f},
        {"specular_roughness_anisotropy", &Inputs::specular_roughness_anisotropy, nullptr, 0.0f, 1.0f},
        {"specular_ior", &Inputs::specular_ior, nullptr, ior_low, 3.0f},
        {"transmission_weight", &Inputs::transmission_weight, nullptr, 0.0f, 1.0f},
        {"transmission_color", nullptr, &Inputs::transmission_color, 0.0f, 1.0f},
        {"transmission_depth", &Inputs::transmission_depth, nullptr, 0.0f, length_max},
        {"transmission_scatter", nullptr, &Inputs::transmission_scatter, 0.0f, 1.0f},
        {"transmission_scatter_anisotropy", &Inputs::transmission_scatter_anisotropy, nullptr, -1.0f, 1.0f},
        {"transmission_dispersion_scale", &Inputs::transmission_dispersion_scale, nullptr, 0.0f, 1.0f},
        {"transmission_dispersion_abbe_number", &Inputs::transmission_dispersion_abbe_number, nullptr, 1.0f, 1e6f},
        {"subsurface_weight", &Inputs::subsurface_weight, nullptr, 0.0f, 1.0f},
        {"subsurface_color", nullptr, &Inputs::subsurface_color, 0.0f, 1.0f},
        {"subsurface_radius", &Inputs::subsurface_radius, nullptr, 0.0f, length_max},
        {"subsurface_radius_scale", nullptr, &Inputs::subsurface_radius_scale, 0.0f, 1.0f},
        {"subsurface_scatter_anisotropy", &Inputs::subsurface_scatter_anisotropy, nullptr, -1.0f, 1.0f},
        {"fuzz_weight", &Inputs::fuzz_weight, nullptr, 0.0f, 1.0f},
        {"fuzz_color", nullptr, &Inputs::fuzz_color, 0.0f, 1.0f},
        {"fuzz_roughness", &Inputs::fuzz_roughness, nullptr, 0.0f, 1.0f},
        {"coat_weight", &Inputs::coat_weight, nullptr, 0.0f, 1.0f},
        {"coat_color", nullptr, &Inputs::coat_color, 0.0f, 1.0f},
        {"coat_roughness", &Inputs::coat_roughness, nullptr, 0.0f, 1.0f},
        {"coat_roughness_anisotropy", &Inputs::coat_roughness_anisotropy, nullptr, 0.0f, 1.0f},
        {"coat_ior", &Inputs::coat_ior, nullptr, ior_low, 3.0f},
        {"coat_darkening", &Inputs::coat_darkening, nullptr, 0.0f, 1.0f},
        {"thin_film_weight", &Inputs::thin_film_weight, nullptr, 0.0f, 1.0f},
        {"thin_film_thickness", &Inputs::thin_film_thickness, nullptr, 0.0f, length_max},
        {"thin_film_ior", &Inputs::thin_film_ior, nullptr, ior_low, 3.0f},
        {"emission_luminance", &Inputs::emission_luminance, nullptr, 0.0f, 1e18f},
        {"emission_color", nullptr, &Inputs::emission_color, 0.0f, 1e18f},  // spec 1.1.1: [0, inf)^3 (HDR)
        {"geometry_opacity", &Inputs::geometry_opacity, nullptr, 0.0f, 1.0f},
    };
    return table;
}

// NaN, both infinities, huge, negative, denormal and an in-range value for every field.
const float test_values[] = {kNaN, kInf, -kInf, 1e30f, -1e30f, -1.0f, -1e-40f, 1e-40f, 2.0f, 0.5f};

float get(const Inputs& inputs, const FieldRange& field, int channel)
{
    return field.scalar ? inputs.*field.scalar : (inputs.*field.color)[channel];
}

void set(Inputs& inputs, const FieldRange& field, float value)
{
    if (field.scalar)
    {
        inputs.*field.scalar = value;
    }
    else
    {
        inputs.*field.color = glm::vec3(value);
    }
}

float expected_clamp(float value, float low, float high, float fallback)
{
    if (std::isnan(value))
    {
        return fallback;
    }
    return std::min(std::max(value, low), high);
}

// A material with every lobe on, so that every field matters to prepare.
Inputs every_lobe()
{
    Inputs inputs = openpbr::openpbr_make_default_resolved_inputs();
    inputs.base_metalness = 0.3f;
    inputs.base_diffuse_roughness = 0.6f;
    inputs.specular_roughness_anisotropy = 0.5f;
    inputs.transmission_weight = 0.4f;
    inputs.transmission_depth = 0.5f;
    inputs.transmission_scatter = glm::vec3(0.3f);
    inputs.transmission_dispersion_scale = 0.5f;
    inputs.subsurface_weight = 0.3f;
    inputs.fuzz_weight = 0.35f;
    inputs.coat_weight = 0.6f;
    inputs.coat_color = glm::vec3(0.9f, 0.8f, 0.7f);
    inputs.thin_film_weight = 0.5f;
    inputs.emission_luminance = 2.0f;
    inputs.geometry_opacity = 0.8f;
    return inputs;
}

TEST(InputContract, TableCoversEveryFloatField)
{
    // 36 float or color fields; the rest are the bool, the two bases and the two rotations.
    EXPECT_EQ(fields().size(), 36u);
}

TEST(InputContract, ClampsEveryFieldAndReportsEachClamp)
{
    const Inputs defaults = openpbr::openpbr_make_default_resolved_inputs();
    for (const FieldRange& field : fields())
    {
        for (const float value : test_values)
        {
            Inputs raw = every_lobe();
            set(raw, field, value);
            clamp_log().clear();
            const Inputs clamped = openpbr::openpbr_apply_input_contract(raw);
            const int channels = field.scalar ? 1 : 3;
            std::vector<float> expected_after;  // the values the hook must report, channel order
            for (int c = 0; c < channels; ++c)
            {
                const float expected = expected_clamp(value, field.low, field.high, get(defaults, field, c));
                const float result = get(clamped, field, c);
                EXPECT_EQ(result, expected) << field.name << " = " << value << " (channel " << c << ")";
                EXPECT_TRUE(std::isfinite(result)) << field.name << " = " << value;
                EXPECT_TRUE(result >= field.low && result <= field.high) << field.name << " = " << value;
                if (!(expected == value))
                {
                    expected_after.push_back(expected);
                }
            }
            ASSERT_EQ(clamp_log().size(), expected_after.size()) << field.name << " = " << value;
            for (std::size_t r = 0; r < clamp_log().size(); ++r)
            {
                const ClampRecord& record = clamp_log()[r];
                EXPECT_EQ(record.field, field.name);
                EXPECT_TRUE(std::isnan(value) ? std::isnan(record.before) : record.before == value) << field.name;
                EXPECT_EQ(record.after, expected_after[r]) << field.name;
            }
        }
    }
}

TEST(InputContract, InRangeInputsAreNotReported)
{
    clamp_log().clear();
    openpbr::openpbr_apply_input_contract(every_lobe());
    openpbr::openpbr_apply_input_contract(openpbr::openpbr_make_default_resolved_inputs());
    EXPECT_TRUE(clamp_log().empty()) << clamp_log().front().field;
}

TEST(InputContract, BasesAreOrthonormalized)
{
    const glm::vec3 bad_vectors[] = {glm::vec3(0.0f),
                                     glm::vec3(kNaN),
                                     glm::vec3(kInf, 0.0f, 1.0f),
                                     glm::vec3(0.0f, 0.0f, 1e30f),
                                     glm::vec3(0.0f, 0.0f, 1e-30f),
                                     glm::vec3(1e-40f, 0.0f, 1e-40f)};
    for (const glm::vec3& normal : bad_vectors)
    {
        for (const glm::vec3& tangent : bad_vectors)
        {
            Inputs raw = every_lobe();
            raw.geometry_basis.normal = normal;
            raw.geometry_basis.tangent = tangent;
            raw.geometry_basis.bitangent = glm::cross(normal, tangent);
            raw.geometry_coat_basis = raw.geometry_basis;
            raw.specular_anisotropy_rotation = glm::vec2(kNaN, kInf);
            raw.coat_anisotropy_rotation = glm::vec2(0.0f);
            const Inputs clamped = openpbr::openpbr_apply_input_contract(raw);
            for (const openpbr::OpenPBR_Basis& basis : {clamped.geometry_basis, clamped.geometry_coat_basis})
            {
                const glm::vec3 axes[] = {basis.tangent, basis.bitangent, basis.normal};
                for (int i = 0; i < 3; ++i)
                {
                    EXPECT_NEAR(glm::dot(axes[i], axes[i]), 1.0f, 1e-5f);
                    for (int j = i + 1; j < 3; ++j)
                    {
                        EXPECT_NEAR(glm::dot(axes[i], axes[j]), 0.0f, 1e-5f);
                    }
                }
            }
        }
    }
}

// Bit-identical results: prepare(raw) against prepare(contract(raw)), for eval, pdf, sample,
// emission and the volume, and the second contract reports no clamp.
struct Outputs
{
    std::vector<float> values;
};

Outputs evaluate(const Inputs& inputs, const glm::vec3& view)
{
    Outputs outputs;
    const openpbr::OpenPBR_PreparedBsdf bsdf = openpbr::openpbr_prepare(inputs, view);
    auto push3 = [&](const glm::vec3& v) { outputs.values.insert(outputs.values.end(), {v.x, v.y, v.z}); };
    push3(bsdf.emission);
    const glm::vec3 lights[] = {glm::normalize(glm::vec3(-0.6f, 0.0f, 0.8f)), glm::vec3(0.0f, 0.0f, 1.0f),
                                glm::normalize(glm::vec3(0.3f, -0.4f, -0.8f)), glm::normalize(glm::vec3(1.0f, 0.0f, 1e-6f))};
    for (const glm::vec3& light : lights)
    {
        const openpbr::OpenPBR_DiffuseSpecular value = openpbr::openpbr_eval(bsdf, light);
        push3(value.diffuse);
        push3(value.specular);
        outputs.values.push_back(openpbr::openpbr_pdf(bsdf, light));
    }
    for (int i = 0; i < 16; ++i)
    {
        const glm::vec3 u((float(i) + 0.5f) / 16.0f, float((i * 7) % 16) / 16.0f, float((i * 11 + 3) % 16) / 16.0f);
        const openpbr::OpenPBR_BsdfSample sample = openpbr::openpbr_sample(bsdf, u);
        push3(sample.direction);
        push3(sample.weight.diffuse);
        push3(sample.weight.specular);
        outputs.values.push_back(sample.pdf);
        outputs.values.push_back(float(sample.lobe_type));
    }
    const openpbr::OpenPBR_HomogeneousVolume volume = openpbr::openpbr_prepare_volume(inputs);
    push3(volume.extinction);
    push3(volume.albedo);
    outputs.values.push_back(volume.anisotropy);
    return outputs;
}

TEST(InputContract, PrepareOnRawEqualsPrepareOnClamped)
{
    const glm::vec3 views[] = {glm::vec3(0.6f, 0.0f, 0.8f), glm::vec3(1.0f, 0.0f, 1e-6f), glm::vec3(0.3f, 0.0f, -0.95f)};
    for (const FieldRange& field : fields())
    {
        for (const float value : test_values)
        {
            Inputs raw = every_lobe();
            set(raw, field, value);
            const Inputs clamped = openpbr::openpbr_apply_input_contract(raw);
            for (const glm::vec3& view : views)
            {
                const Outputs from_raw = evaluate(raw, view);
                clamp_log().clear();
                const Outputs from_clamped = evaluate(clamped, view);
                EXPECT_TRUE(clamp_log().empty()) << field.name << " = " << value << ": the contract is not idempotent";
                ASSERT_EQ(from_raw.values.size(), from_clamped.values.size());
                for (std::size_t i = 0; i < from_raw.values.size(); ++i)
                {
                    EXPECT_EQ(std::memcmp(&from_raw.values[i], &from_clamped.values[i], sizeof(float)), 0)
                        << field.name << " = " << value << ", output " << i << ": " << from_raw.values[i] << " vs "
                        << from_clamped.values[i];
                    EXPECT_TRUE(std::isfinite(from_raw.values[i])) << field.name << " = " << value << ", output " << i;
                }
            }
        }
    }
}

}  // namespace
