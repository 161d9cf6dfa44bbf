// CPU cost of the BSDF API per bundled material: ns per prepare, eval, sample and pdf
// (Google Benchmark; numbers go to docs/performance.md). Queries cycle through a fixed set of
// directions so the branch pattern is that of a real batch, not one repeated input.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "host/scene/material_library.h"
#include "slang/openpbr.h"

namespace {

using namespace openpbr;

constexpr int direction_count = 256;

struct Directions
{
    std::vector<vec3> views;
    std::vector<vec3> lights;
    std::vector<vec3> randoms;
};

const Directions& directions()
{
    static const Directions cached = [] {
        Directions d;
        std::mt19937 generator(7);
        std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
        for (int i = 0; i < direction_count; ++i)
        {
            const vec3 u(uniform(generator), uniform(generator), uniform(generator));
            d.views.push_back(openpbr_sample_cosine_hemisphere(vec2(u.x, u.y)));
            d.lights.push_back(openpbr_sample_cosine_hemisphere(vec2(uniform(generator), uniform(generator))));
            d.randoms.push_back(vec3(uniform(generator), uniform(generator), std::min(u.z, 0.999f)));
        }
        return d;
    }();
    return cached;
}

void benchmark_prepare(benchmark::State& state, const OpenPBR_ResolvedInputs& inputs)
{
    const Directions& d = directions();
    int i = 0;
    for (auto _ : state)
    {
        OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, d.views[i]);
        benchmark::DoNotOptimize(bsdf);
        i = (i + 1) & (direction_count - 1);
    }
}

std::vector<OpenPBR_PreparedBsdf> prepared_set(const OpenPBR_ResolvedInputs& inputs)
{
    std::vector<OpenPBR_PreparedBsdf> prepared;
    for (const vec3& view : directions().views)
    {
        prepared.push_back(openpbr_prepare(inputs, view));
    }
    return prepared;
}

// One prepared BSDF per view; `call(bsdf, index)` is the measured work for direction `index`.
template <typename Call> void benchmark_prepared(benchmark::State& state, const OpenPBR_ResolvedInputs& inputs, Call call)
{
    const std::vector<OpenPBR_PreparedBsdf> prepared = prepared_set(inputs);
    int i = 0;
    for (auto _ : state)
    {
        auto result = call(prepared[i], i);
        benchmark::DoNotOptimize(result);
        i = (i + 1) & (direction_count - 1);
    }
}

void benchmark_eval(benchmark::State& state, const OpenPBR_ResolvedInputs& inputs)
{
    benchmark_prepared(state, inputs,
                       [](const OpenPBR_PreparedBsdf& bsdf, int i) { return openpbr_eval(bsdf, directions().lights[i]); });
}

void benchmark_sample(benchmark::State& state, const OpenPBR_ResolvedInputs& inputs)
{
    benchmark_prepared(state, inputs, [](const OpenPBR_PreparedBsdf& bsdf, int i) {
        return openpbr_sample(bsdf, directions().randoms[i]);
    });
}

void benchmark_pdf(benchmark::State& state, const OpenPBR_ResolvedInputs& inputs)
{
    benchmark_prepared(state, inputs,
                       [](const OpenPBR_PreparedBsdf& bsdf, int i) { return openpbr_pdf(bsdf, directions().lights[i]); });
}

// One feature of the every-lobe material: its name and how it is switched on and off. The
// per-feature cost table in docs/performance.md reads two rows per feature: "Only/<feature>"
// (the default material plus that feature, as the every-lobe material sets it) against
// "Default", and "Without/<feature>" (every lobe but that one) against "EveryLobe".
struct Feature
{
    const char* name;
    void (*switch_on)(OpenPBR_ResolvedInputs&);
    void (*switch_off)(OpenPBR_ResolvedInputs&);
};

const Feature features[] = {
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
         m.coat_color = vec3(0.9f, 0.8f, 0.7f);
     },
     [](OpenPBR_ResolvedInputs& m) { m.coat_weight = 0.0f; }},
    {"thin_film", [](OpenPBR_ResolvedInputs& m) { m.thin_film_weight = 0.5f; },
     [](OpenPBR_ResolvedInputs& m) { m.thin_film_weight = 0.0f; }},
    {"emission", [](OpenPBR_ResolvedInputs& m) { m.emission_luminance = 1.0f; },
     [](OpenPBR_ResolvedInputs& m) { m.emission_luminance = 0.0f; }},
};

// A material with every lobe at partial weight: the most expensive configuration.
OpenPBR_ResolvedInputs every_lobe_material()
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    for (const Feature& feature : features)
    {
        feature.switch_on(inputs);
    }
    return inputs;
}

void register_material(const std::string& name, const OpenPBR_ResolvedInputs& inputs)
{
    benchmark::RegisterBenchmark(("prepare/" + name).c_str(), benchmark_prepare, inputs);
    benchmark::RegisterBenchmark(("eval/" + name).c_str(), benchmark_eval, inputs);
    benchmark::RegisterBenchmark(("sample/" + name).c_str(), benchmark_sample, inputs);
    benchmark::RegisterBenchmark(("pdf/" + name).c_str(), benchmark_pdf, inputs);
}

}  // namespace

int main(int argc, char** argv)
{
    register_material("Default", openpbr_make_default_resolved_inputs());
    register_material("EveryLobe", every_lobe_material());
    for (const Feature& feature : features)
    {
        OpenPBR_ResolvedInputs only = openpbr_make_default_resolved_inputs();
        feature.switch_on(only);
        register_material(std::string("Only/") + feature.name, only);
        OpenPBR_ResolvedInputs without = every_lobe_material();
        feature.switch_off(without);
        register_material(std::string("Without/") + feature.name, without);
    }
    for (const openpbr::host::Material& material : openpbr::host::load_material_directory(OPENPBR_MATERIALS_DIR))
    {
        register_material(material.name, material.inputs);
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
