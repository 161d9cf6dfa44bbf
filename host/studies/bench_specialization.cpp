// `openpbr bench specialization`: see bench_specialization.h.
#include "host/studies/bench_specialization.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <optional>
#include <random>
#include <sstream>

#include "host/checks/conformance.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"
#include "host/gpu/vulkan_runner.h"
#include "slang/openpbr.h"

namespace openpbr::host {

namespace {

constexpr std::size_t direction_count = 256;

// The floor: a bare GGX + Lambert BRDF times cos, the cheapest reasonable real-time BRDF.
// Walter et al. 2007 GGX D; Heitz 2014 height-correlated Smith G2 = 1 / (1 + L(o) + L(i));
// Schlick 1994 Fresnel; Lambert diffuse not weighted by (1 - F); no energy compensation. The
// view's Lambda and the frame are prepared once per view, as the BSDF's prepare does.
struct FloorBrdf
{
    glm::vec3 tangent, bitangent, normal;
    glm::vec3 view;  // local
    float alpha_squared;
    float lambda_view;
    glm::vec3 diffuse;  // rho / pi
    glm::vec3 f0;
};

float floor_lambda(float cos_theta, float alpha_squared)
{
    const float cos2 = cos_theta * cos_theta;
    const float tan2 = std::max(1.0f - cos2, 0.0f) / std::max(cos2, 1e-12f);
    return 0.5f * (std::sqrt(1.0f + alpha_squared * tan2) - 1.0f);
}

FloorBrdf prepare_floor(const glm::vec3& view_world, float roughness, const glm::vec3& base_color)
{
    FloorBrdf brdf;
    brdf.tangent = glm::vec3(1.0f, 0.0f, 0.0f);
    brdf.bitangent = glm::vec3(0.0f, 1.0f, 0.0f);
    brdf.normal = glm::vec3(0.0f, 0.0f, 1.0f);
    brdf.view = glm::vec3(glm::dot(view_world, brdf.tangent), glm::dot(view_world, brdf.bitangent),
                          glm::dot(view_world, brdf.normal));
    const float alpha = roughness * roughness;
    brdf.alpha_squared = alpha * alpha;
    brdf.lambda_view = floor_lambda(brdf.view.z, brdf.alpha_squared);
    brdf.diffuse = base_color * 0.31830988f;
    brdf.f0 = glm::vec3(0.04f);
    return brdf;
}

glm::vec3 eval_floor(const FloorBrdf& brdf, const glm::vec3& light_world)
{
    const glm::vec3 light(glm::dot(light_world, brdf.tangent), glm::dot(light_world, brdf.bitangent),
                          glm::dot(light_world, brdf.normal));
    if (light.z <= 0.0f || brdf.view.z <= 0.0f)
    {
        return glm::vec3(0.0f);
    }
    const glm::vec3 h = glm::normalize(brdf.view + light);
    const float cos_h2 = h.z * h.z;
    const float d_denominator = cos_h2 * (brdf.alpha_squared - 1.0f) + 1.0f;
    const float d = brdf.alpha_squared / (3.14159265f * d_denominator * d_denominator);
    const float g2 = 1.0f / (1.0f + brdf.lambda_view + floor_lambda(light.z, brdf.alpha_squared));
    const float one_minus = 1.0f - std::max(glm::dot(brdf.view, h), 0.0f);
    const float one_minus2 = one_minus * one_minus;
    const glm::vec3 fresnel = brdf.f0 + (glm::vec3(1.0f) - brdf.f0) * (one_minus2 * one_minus2 * one_minus);
    return (brdf.diffuse + fresnel * (d * g2 / (4.0f * brdf.view.z * light.z))) * light.z;
}

double floor_eval_ns(const BenchDirections& directions)
{
    std::vector<FloorBrdf> prepared;
    for (const glm::vec3& view : directions.views)
    {
        prepared.push_back(prepare_floor(view, 0.3f, glm::vec3(0.8f)));
    }
    return measure_ns_per_call(prepared.size(), [&](std::size_t i, std::size_t j) {
        const glm::vec3 value = eval_floor(prepared[i], directions.lights[j]);
        return value.x + value.y;
    });
}

// ns per openpbr_eval over the scene's materials, prepared under the current run-time toggles.
double bsdf_eval_ns(const std::vector<Material>& materials, const BenchDirections& directions)
{
    std::vector<openpbr::OpenPBR_PreparedBsdf> prepared;
    for (std::size_t i = 0; i < directions.views.size(); ++i)
    {
        prepared.push_back(openpbr::openpbr_prepare(materials[i % materials.size()].inputs, directions.views[i]));
    }
    return measure_ns_per_call(prepared.size(), [&](std::size_t i, std::size_t j) {
        const openpbr::OpenPBR_DiffuseSpecular value = openpbr::openpbr_eval(prepared[i], directions.lights[j]);
        return value.diffuse.x + value.specular.y;
    });
}

struct Scene
{
    std::string name;
    std::vector<Material> materials;
};

// The benchmark scenes (docs/performance.md), from the bundled materials by what they need.
std::vector<Scene> make_scenes(const std::vector<Material>& library)
{
    const auto select = [&](const std::function<bool(std::uint32_t)>& wanted) {
        std::vector<Material> chosen;
        for (const Material& material : library)
        {
            if (wanted(required_feature_mask(material)))
            {
                chosen.push_back(material);
            }
        }
        return chosen;
    };
    std::vector<Scene> scenes;
    std::vector<Material> dielectric = select([](std::uint32_t mask) { return mask == 0; });
    if (dielectric.empty())
    {
        dielectric.push_back(default_material());
    }
    scenes.push_back({"plain dielectric", dielectric});
    scenes.push_back({"metal", select([](std::uint32_t mask) { return mask == OPENPBR_FEATURE_BIT_METAL; })});
    scenes.push_back({"coated", select([](std::uint32_t mask) { return (mask & OPENPBR_FEATURE_BIT_COAT) != 0; })});
    scenes.push_back({"glass", select([](std::uint32_t mask) {
                          return (mask & OPENPBR_FEATURE_BIT_TRANSMISSION) != 0 &&
                                 (mask & (OPENPBR_FEATURE_BIT_SUBSURFACE | OPENPBR_FEATURE_BIT_THIN_WALLED)) == 0;
                      })});
    scenes.push_back({"full bundled set", library});
    std::vector<Scene> non_empty;
    for (Scene& scene : scenes)
    {
        if (!scene.materials.empty())
        {
            non_empty.push_back(std::move(scene));
        }
    }
    return non_empty;
}

}  // namespace

BenchDirections make_bench_directions(std::size_t count, unsigned seed)
{
    BenchDirections directions;
    std::mt19937 generator(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (std::size_t i = 0; i < count; ++i)
    {
        directions.views.push_back(
            openpbr::openpbr_sample_cosine_hemisphere(glm::vec2(uniform(generator), uniform(generator))));
        directions.lights.push_back(
            openpbr::openpbr_sample_cosine_hemisphere(glm::vec2(uniform(generator), uniform(generator))));
    }
    return directions;
}

nlohmann::json run_specialization_bench(const SpecializationBenchOptions& options)
{
    const std::vector<Material> library = load_material_directory(options.materials_directory);
    const std::vector<Scene> scenes = make_scenes(library);
    const BenchDirections directions = make_bench_directions(direction_count, 7);

    nlohmann::json report;
    report["cpu_floor_ns"] = floor_eval_ns(directions);
    report["scenes"] = nlohmann::json::array();
    report["pipelines"] = nlohmann::json::array();

    std::optional<VulkanContext> context;
    std::string context_error = "GPU part not requested";
    if (options.gpu)
    {
        // Pipeline creation and first dispatch are reported as llvmpipe compiles them: no warm
        // Mesa cache unless the caller chose one.
        setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
        context = VulkanContext::create(VulkanOptions{}, &context_error);
    }
    report["device"] = context ? context->device_name() : "none: " + context_error;
    report["gpu_path"] = options.path;

    for (const Scene& scene : scenes)
    {
        const std::uint32_t mask = scene_feature_mask(scene.materials);
        nlohmann::json entry;
        entry["name"] = scene.name;
        entry["materials"] = scene.materials.size();
        entry["toggles"] = feature_names(mask);
        {
            const ScopedFeatureMask full(full_feature_mask());
            entry["cpu_full_ns"] = bsdf_eval_ns(scene.materials, directions);
        }
        {
            const ScopedFeatureMask specialized(mask);
            entry["cpu_specialized_ns"] = bsdf_eval_ns(scene.materials, directions);
        }
        if (mask == 0)
        {
            entry["cpu_compile_time_specialized_ns"] =
                base_only_eval_ns(pack_materials(scene.materials), scene.materials.size(), directions);
        }
        if (context)
        {
            const std::vector<float> queries = make_queries(options.gpu_queries, scene.materials.size(), 1);
            const auto measure = [&](std::uint32_t pipeline_mask, const char* key) {
                // The timing of `openpbr bench gpu`: device-local buffers uploaded once, GPU
                // timestamps around the dispatch (host time only where the queue has none).
                ConformanceDispatchSettings settings;
                settings.device_local = true;
                const SpecializedConformanceRun run =
                    run_conformance_gpu_specialized(options.path, *context, queries, scene.materials,
                                                    options.kernel_directory, pipeline_mask, options.gpu_repeats, settings);
                const double ms = run.device_dispatch_ms.value_or(run.dispatch_ms);
                entry[key] = ms > 0.0 ? double(options.gpu_queries) / (ms * 1e-3) : 0.0;
                entry["gpu_timing"] = run.device_dispatch_ms ? "device timestamps" : "host (no timestamps)";
                for (const SpecializedPipelineTiming& pipeline : run.pipelines)
                {
                    // Register count, spills and the like where the driver reports them
                    // (VK_KHR_pipeline_executable_properties): why a pipeline is or is not faster.
                    nlohmann::json statistics = nlohmann::json::object();
                    for (const PipelineStatistic& statistic : pipeline.statistics)
                    {
                        statistics[statistic.name] = statistic.value;
                    }
                    report["pipelines"].push_back(
                        {{"scene", scene.name},
                         {"statistics", statistics},
                         {"toggles", feature_names(pipeline.mask)},
                         {"create_ms", pipeline.create_ms},
                         {"first_dispatch_ms", pipeline.first_dispatch_ms},
                         {"create_plus_first_dispatch_s", (pipeline.create_ms + pipeline.first_dispatch_ms) * 1e-3}});
                }
            };
            measure(full_feature_mask(), "gpu_full_qps");
            measure(mask, "gpu_specialized_qps");
        }
        report["scenes"].push_back(entry);
    }
    return report;
}

std::string specialization_bench_text(const nlohmann::json& report)
{
    std::ostringstream text;
    text << "device: " << report["device"].get<std::string>() << " (path " << report["gpu_path"].get<std::string>()
         << ")\nCPU floor (GGX + Lambert, Schlick, height-correlated Smith): " << report["cpu_floor_ns"].get<double>()
         << " ns per eval\n";
    for (const nlohmann::json& scene : report["scenes"])
    {
        std::string toggles;
        for (const nlohmann::json& name : scene["toggles"])
        {
            toggles += (toggles.empty() ? "" : "+") + name.get<std::string>();
        }
        text << scene["name"].get<std::string>() << " (" << scene["materials"].get<std::size_t>() << " materials, {"
             << (toggles.empty() ? "base" : toggles) << "}): CPU eval " << scene["cpu_full_ns"].get<double>() << " ns full, "
             << scene["cpu_specialized_ns"].get<double>() << " ns specialized (run-time)";
        if (scene.contains("cpu_compile_time_specialized_ns"))
        {
            text << ", " << scene["cpu_compile_time_specialized_ns"].get<double>() << " ns (compile-time)";
        }
        if (scene.contains("gpu_full_qps"))
        {
            const double full = scene["gpu_full_qps"].get<double>();
            const double specialized = scene["gpu_specialized_qps"].get<double>();
            text << "; GPU (" << scene["gpu_timing"].get<std::string>() << ") " << std::lround(full) << " q/s full, "
                 << std::lround(specialized) << " q/s specialized (x" << (full > 0.0 ? specialized / full : 0.0) << ")";
        }
        text << "\n";
    }
    for (const nlohmann::json& pipeline : report["pipelines"])
    {
        std::string toggles;
        for (const nlohmann::json& name : pipeline["toggles"])
        {
            toggles += (toggles.empty() ? "" : "+") + name.get<std::string>();
        }
        text << "  pipeline {" << (toggles.empty() ? "base" : toggles) << "} for " << pipeline["scene"].get<std::string>()
             << ": create " << pipeline["create_ms"].get<double>() << " ms + first dispatch "
             << pipeline["first_dispatch_ms"].get<double>() << " ms\n";
        for (const auto& [name, value] : pipeline["statistics"].items())
        {
            text << "    " << name << ": " << value.get<double>() << "\n";
        }
    }
    return text.str();
}

}  // namespace openpbr::host
