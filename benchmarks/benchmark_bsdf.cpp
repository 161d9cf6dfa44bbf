// CPU cost of the BSDF API per feature variant (host/studies/feature_variants.h: Default,
// EveryLobe, Only/<feature>, Without/<feature>) and per bundled material: ns per prepare, eval,
// sample and pdf (Google Benchmark; numbers go to docs/performance.md). Queries cycle through a
// fixed set of directions so the branch pattern is that of a real batch, not one repeated input.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "host/scene/material_library.h"
#include "host/studies/feature_variants.h"
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
    // The rows of the per-feature cost table (host/studies/feature_variants.h).
    for (const openpbr::host::FeatureVariant& variant : openpbr::host::feature_variants())
    {
        register_material(variant.name, variant.inputs);
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
