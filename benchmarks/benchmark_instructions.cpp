// benchmark_instructions: a fixed number of calls of one BSDF operation on one material of the
// per-feature cost tables (host/studies/feature_variants.h), for instruction counts under
// callgrind. On a shared machine the Google Benchmark timings of benchmark_bsdf move by 10-20 %
// with the load; instruction counts do not, so they say whether a change made a call cheaper.
// benchmarks/count_instructions.sh runs this twice per row under valgrind and reports
// (I(3n calls) - I(n calls)) / 2n, which removes the start-up and the prepared set.
//
// Usage: benchmark_instructions <prepare|eval|sample|pdf> <variant> <calls>
//        benchmark_instructions --list      (the variant names, one per line)
// The variants: the per-feature materials, then Soap_Bubble (materials/open_pbr_soapbubble.mtlx:
// a thin-walled film over a dielectric of IOR 1, the film's dielectric-only path).
// The directions are those of benchmark_bsdf: 256 views, lights and random triples from
// std::mt19937(7).
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "host/studies/feature_variants.h"
#include "slang/openpbr.h"

namespace {

using namespace openpbr;

constexpr int direction_count = 256;

int usage(const char* program)
{
    std::fprintf(stderr,
                 "usage: %s <prepare|eval|sample|pdf> <variant> <calls>\n"
                 "       %s --list\n",
                 program, program);
    return 2;
}

// The inputs of materials/open_pbr_soapbubble.mtlx (this program reads no files).
host::FeatureVariant soap_bubble()
{
    host::FeatureVariant variant{"Soap_Bubble", openpbr_make_default_resolved_inputs()};
    variant.inputs.specular_roughness = 0.0f;
    variant.inputs.specular_ior = 1.0f;
    variant.inputs.transmission_weight = 1.0f;
    variant.inputs.thin_film_weight = 1.0f;
    variant.inputs.thin_film_thickness = 0.5f;
    variant.inputs.thin_film_ior = 1.4f;
    variant.inputs.geometry_thin_walled = true;
    return variant;
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<host::FeatureVariant> variants = host::feature_variants();
    variants.push_back(soap_bubble());
    if (argc == 2 && std::string(argv[1]) == "--list")
    {
        for (const host::FeatureVariant& variant : variants)
        {
            std::printf("%s\n", variant.name.c_str());
        }
        return 0;
    }
    if (argc != 4)
    {
        return usage(argv[0]);
    }
    const std::string operation = argv[1];
    if (operation != "prepare" && operation != "eval" && operation != "sample" && operation != "pdf")
    {
        std::fprintf(stderr, "unknown operation '%s'\n", argv[1]);
        return usage(argv[0]);
    }
    const host::FeatureVariant* chosen = nullptr;
    for (const host::FeatureVariant& variant : variants)
    {
        if (variant.name == argv[2])
        {
            chosen = &variant;
        }
    }
    if (chosen == nullptr)
    {
        std::fprintf(stderr, "unknown variant '%s' (--list prints the names)\n", argv[2]);
        return usage(argv[0]);
    }
    char* end = nullptr;
    const long calls = std::strtol(argv[3], &end, 10);
    if (end == argv[3] || *end != '\0' || calls < 0)
    {
        std::fprintf(stderr, "calls must be a non-negative integer, got '%s'\n", argv[3]);
        return usage(argv[0]);
    }

    std::mt19937 generator(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::vector<vec3> views;
    std::vector<vec3> lights;
    std::vector<vec3> randoms;
    for (int i = 0; i < direction_count; ++i)
    {
        const vec3 u(uniform(generator), uniform(generator), uniform(generator));
        views.push_back(openpbr_sample_cosine_hemisphere(vec2(u.x, u.y)));
        lights.push_back(openpbr_sample_cosine_hemisphere(vec2(uniform(generator), uniform(generator))));
        randoms.push_back(vec3(uniform(generator), uniform(generator), std::min(u.z, 0.999f)));
    }
    std::vector<OpenPBR_PreparedBsdf> prepared;
    for (const vec3& view : views)
    {
        prepared.push_back(openpbr_prepare(chosen->inputs, view));
    }
    // The operation chosen once, outside the loop, so the loop adds only its own few
    // instructions; the results feed a volatile sum so the calls cannot be optimized away.
    const int chosen_operation = operation == "prepare" ? 0 : operation == "eval" ? 1 : operation == "sample" ? 2 : 3;
    volatile float sink = 0.0f;
    for (long call = 0; call < calls; ++call)
    {
        const int i = int(call & (direction_count - 1));
        switch (chosen_operation)
        {
        case 0: sink = sink + openpbr_prepare(chosen->inputs, views[i]).view.x; break;
        case 1:
        {
            const OpenPBR_DiffuseSpecular value = openpbr_eval(prepared[i], lights[i]);
            sink = sink + value.diffuse.x + value.specular.x;
            break;
        }
        case 2: sink = sink + openpbr_sample(prepared[i], randoms[i]).pdf; break;
        default: sink = sink + openpbr_pdf(prepared[i], lights[i]); break;
        }
    }
    return 0;
}
