// Shared by the three out-of-tree consumers (examples/cpp_consumer, slang_consumer,
// hlsl_consumer): the same materials and queries, the CPU shading of a query through the C++
// build of the installed headers, and the comparison of a GPU kernel's results with it.
//
// A query is 16 floats: view (xyz, w unused), light (xyz, w unused), u (xyz, w unused),
// material index (x, as a float), 3 unused. A result is 16 floats, written the same way by the
// C++ code here and by both GPU kernels:
//   0-2 eval diffuse (BSDF x |cos| toward the light), 3 pdf toward the light,
//   4-6 eval specular, 7 unused,
//   8-10 sampled direction, 11 its pdf (0: no sample),
//   12-14 sample weight (diffuse + specular), 15 the sample's lobe type (as a float).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "slang/openpbr.h"
#include "slang/openpbr_material_packing.h"

namespace openpbr_consumer {

using namespace openpbr;

constexpr std::size_t query_floats = 16;
constexpr std::size_t result_floats = 16;

// A frame that is neither +z nor orthogonal: the coated material sets only geometry_basis, so
// its coat must follow this frame (docs/api.md "Frames").
inline OpenPBR_Basis tilted_frame()
{
    return openpbr_make_basis(normalize(vec3(0.4f, -0.3f, 1.0f)), vec3(1.0f, 0.2f, 0.0f), 1.0f);
}

// A few materials that cover the lobes: a plastic, a rough gold, a coated red on a tilted
// frame, a fuzzy cloth, a rough glass, and a metal at roughness 0 (delta lobe).
inline std::vector<OpenPBR_ResolvedInputs> make_materials()
{
    std::vector<OpenPBR_ResolvedInputs> materials;
    OpenPBR_ResolvedInputs plastic = openpbr_make_default_resolved_inputs();
    plastic.base_color = vec3(0.2f, 0.5f, 0.8f);
    plastic.specular_roughness = 0.3f;
    materials.push_back(plastic);

    OpenPBR_ResolvedInputs gold = openpbr_make_default_resolved_inputs();
    gold.base_metalness = 1.0f;
    gold.base_color = vec3(0.94f, 0.78f, 0.37f);
    gold.specular_roughness = 0.4f;
    gold.specular_roughness_anisotropy = 0.5f;
    materials.push_back(gold);

    OpenPBR_ResolvedInputs coated = openpbr_make_default_resolved_inputs();
    coated.base_color = vec3(0.8f, 0.1f, 0.1f);
    coated.coat_weight = 1.0f;
    coated.coat_roughness = 0.1f;
    coated.geometry_basis = tilted_frame();
    materials.push_back(coated);

    OpenPBR_ResolvedInputs cloth = openpbr_make_default_resolved_inputs();
    cloth.base_color = vec3(0.3f, 0.3f, 0.6f);
    cloth.fuzz_weight = 1.0f;
    cloth.fuzz_roughness = 0.6f;
    materials.push_back(cloth);

    OpenPBR_ResolvedInputs glass = openpbr_make_default_resolved_inputs();
    glass.transmission_weight = 1.0f;
    glass.specular_roughness = 0.2f;
    glass.specular_ior = 1.5f;
    materials.push_back(glass);

    OpenPBR_ResolvedInputs mirror = openpbr_make_default_resolved_inputs();
    mirror.base_metalness = 1.0f;
    mirror.base_color = vec3(0.9f);
    mirror.specular_roughness = 0.0f;
    materials.push_back(mirror);
    return materials;
}

// Packs materials with the parameter table of slang/openpbr_parameters.h, in the order the
// kernels' openpbr_unpack_material reads them.
inline std::vector<float> pack_materials(const std::vector<OpenPBR_ResolvedInputs>& materials)
{
    std::vector<float> packed(materials.size() * OPENPBR_PACKED_MATERIAL_FLOATS, 0.0f);
    for (std::size_t m = 0; m < materials.size(); ++m)
    {
        const OpenPBR_ResolvedInputs& material = materials[m];
        std::size_t index = m * OPENPBR_PACKED_MATERIAL_FLOATS;
        auto put = [&](float value) { packed[index++] = value; };
        auto put3 = [&](const vec3& value) {
            put(value.x);
            put(value.y);
            put(value.z);
        };
#define CONSUMER_PACK_FLOAT(name, default_value, low, high) put(material.name);
#define CONSUMER_PACK_COLOR(name, default_r, default_g, default_b, low, high) put3(material.name);
#define CONSUMER_PACK_VECTOR2(name, default_x, default_y) \
    put(material.name.x);                                 \
    put(material.name.y);
#define CONSUMER_PACK_BOOL(name, default_value) put(material.name ? 1.0f : 0.0f);
#define CONSUMER_PACK_BASIS(name, normal_input, tangent_input) \
    put3(material.name.tangent);                               \
    put3(material.name.bitangent);                             \
    put3(material.name.normal);
        OPENPBR_PARAMETERS(CONSUMER_PACK_FLOAT, CONSUMER_PACK_COLOR, CONSUMER_PACK_VECTOR2, CONSUMER_PACK_BOOL,
                           CONSUMER_PACK_BASIS)
#undef CONSUMER_PACK_FLOAT
#undef CONSUMER_PACK_COLOR
#undef CONSUMER_PACK_VECTOR2
#undef CONSUMER_PACK_BOOL
#undef CONSUMER_PACK_BASIS
    }
    return packed;
}

// query_count random queries (fixed seed) over the materials: views and lights over the whole
// sphere, so back faces and transmission are included.
inline std::vector<float> make_queries(std::size_t query_count, std::size_t material_count)
{
    std::mt19937 generator(20261125u);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    auto direction = [&]() {
        const float z = 1.0f - 2.0f * uniform(generator);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 6.2831853f * uniform(generator);
        return vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    std::vector<float> queries(query_count * query_floats, 0.0f);
    for (std::size_t q = 0; q < query_count; ++q)
    {
        float* query = queries.data() + q * query_floats;
        const vec3 view = direction();
        const vec3 light = direction();
        for (int axis = 0; axis < 3; ++axis)
        {
            query[axis] = view[axis];
            query[4 + axis] = light[axis];
            query[8 + axis] = uniform(generator);
        }
        query[12] = float(q % material_count);
    }
    return queries;
}

// The C++ build's result for one query, in the result layout above.
inline void shade_on_cpu(const std::vector<OpenPBR_ResolvedInputs>& materials, const float* query, float* result)
{
    const OpenPBR_ResolvedInputs& material = materials[std::size_t(query[12])];
    const vec3 view(query[0], query[1], query[2]);
    const vec3 light(query[4], query[5], query[6]);
    const vec3 u(query[8], query[9], query[10]);
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(material, view);
    const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, light);
    const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(bsdf, u);
    const vec3 weight = bsdf_sample.weight.diffuse + bsdf_sample.weight.specular;
    const float values[result_floats] = {value.diffuse.x,
                                         value.diffuse.y,
                                         value.diffuse.z,
                                         openpbr_pdf(bsdf, light),
                                         value.specular.x,
                                         value.specular.y,
                                         value.specular.z,
                                         0.0f,
                                         bsdf_sample.direction.x,
                                         bsdf_sample.direction.y,
                                         bsdf_sample.direction.z,
                                         bsdf_sample.pdf,
                                         weight.x,
                                         weight.y,
                                         weight.z,
                                         float(bsdf_sample.lobe_type)};
    std::copy(values, values + result_floats, result);
}

inline std::vector<float> shade_all_on_cpu(const std::vector<OpenPBR_ResolvedInputs>& materials,
                                           const std::vector<float>& queries)
{
    const std::size_t query_count = queries.size() / query_floats;
    std::vector<float> results(query_count * result_floats, 0.0f);
    for (std::size_t q = 0; q < query_count; ++q)
    {
        shade_on_cpu(materials, queries.data() + q * query_floats, results.data() + q * result_floats);
    }
    return results;
}

// A table file of the installed package (raw little-endian float32, e.g. openpbr_lut.bin),
// checked against the element count the headers expect.
inline std::vector<float> read_table(const std::string& path, std::size_t expected_count)
{
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file)
    {
        throw std::runtime_error("cannot open table " + path);
    }
    const std::streamsize bytes = file.tellg();
    if (bytes != std::streamsize(expected_count * sizeof(float)))
    {
        throw std::runtime_error(path + ": " + std::to_string(bytes) + " bytes, expected " +
                                 std::to_string(expected_count * sizeof(float)));
    }
    std::vector<float> values(expected_count);
    file.seekg(0);
    file.read(reinterpret_cast<char*>(values.data()), bytes);
    return values;
}

// Relative error with a floor of 1e-3 on the reference, the metric of the project's own
// conformance check (host/checks/conformance.cpp).
inline double relative_error(float gpu, float cpu)
{
    return std::fabs(double(gpu) - double(cpu)) / std::max(std::fabs(double(cpu)), 1e-3);
}

// Compares a GPU kernel's results with the CPU build's; prints a summary and returns true when
// they agree. Tolerances: the project's conformance check measures a max relative error below
// 1e-3 and sample-lobe mismatches (a sample drawn at a lobe-selection boundary, where float
// differences pick the neighbour) below 1e-3 of the queries on every Vulkan path; the same
// bounds apply here. Sample outputs are compared only where the lobes agree.
inline bool compare_with_cpu(const char* name, const std::vector<float>& gpu, const std::vector<float>& cpu)
{
    constexpr double max_relative_error = 1e-3;
    constexpr double max_lobe_mismatch_fraction = 1e-3;
    const std::size_t query_count = cpu.size() / result_floats;
    double worst = 0.0;
    std::size_t worst_query = 0;
    std::size_t nonfinite = 0;
    std::size_t lobe_mismatches = 0;
    for (std::size_t q = 0; q < query_count; ++q)
    {
        const float* g = gpu.data() + q * result_floats;
        const float* c = cpu.data() + q * result_floats;
        const bool lobes_agree = g[15] == c[15];
        lobe_mismatches += lobes_agree ? 0 : 1;
        for (std::size_t slot = 0; slot < result_floats; ++slot)
        {
            if (!std::isfinite(g[slot]))
            {
                ++nonfinite;
                continue;
            }
            if (slot >= 8 && !lobes_agree)
            {
                continue;
            }
            const double error = relative_error(g[slot], c[slot]);
            if (error > worst)
            {
                worst = error;
                worst_query = q;
            }
        }
    }
    const double mismatch_fraction = query_count ? double(lobe_mismatches) / double(query_count) : 1.0;
    const bool pass =
        query_count > 0 && nonfinite == 0 && worst <= max_relative_error && mismatch_fraction <= max_lobe_mismatch_fraction;
    std::printf("%s: %zu queries, max relative error %.3g (query %zu), lobe mismatches %zu, non-finite %zu: %s\n", name,
                query_count, worst, worst_query, lobe_mismatches, nonfinite, pass ? "agrees with the C++ build" : "FAILED");
    return pass;
}

}  // namespace openpbr_consumer
