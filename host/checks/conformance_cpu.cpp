// The conformance kernel's CPU build (see conformance.h): the shared kernel body
// (targets/kernels/openpbr_conformance_kernel.h) compiled as C++, the query generator and the
// result slots' names. Apart from the GPU comparison in conformance.cpp, so that a program that
// needs only the CPU build (the stability corpus on the CPU, the sanitizer build's subset) links
// no GPU path (CMakeLists.txt, openpbr_host_core).
#include <algorithm>
#include <cmath>
#include <random>

#include <tbb/parallel_for.h>

#include "host/checks/conformance.h"
#include "slang/openpbr.h"

// The CPU build of the shared kernel body: the macros read and write these arrays, which the
// runner points at the batch before the parallel loop (read-only, and each query writes only
// its own result slots).
namespace openpbr::host::cpu_kernel {
const float* queries = nullptr;
const float* materials = nullptr;
float* results = nullptr;
}  // namespace openpbr::host::cpu_kernel
#define OPENPBR_QUERY_READ(index) ::openpbr::host::cpu_kernel::queries[index]
#define OPENPBR_MATERIAL_READ(index) ::openpbr::host::cpu_kernel::materials[index]
#define OPENPBR_RESULT_WRITE(index, value) ::openpbr::host::cpu_kernel::results[index] = (value)
#include "targets/kernels/openpbr_conformance_kernel.h"

namespace openpbr::host {

static_assert(conformance_query_floats == OPENPBR_QUERY_FLOATS && conformance_result_floats == OPENPBR_RESULT_FLOATS,
              "conformance.h's record sizes are the kernel's");

std::vector<float> make_queries(std::size_t query_count, std::size_t material_count, std::uint64_t seed)
{
    std::mt19937_64 generator(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    auto unit_sphere = [&]() {
        const float z = 1.0f - 2.0f * uniform(generator);
        const float radius = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 6.2831853f * uniform(generator);
        return glm::vec3(radius * std::cos(phi), radius * std::sin(phi), z);
    };
    std::vector<float> queries(query_count * OPENPBR_QUERY_FLOATS);
    for (std::size_t query = 0; query < query_count; ++query)
    {
        float* out = queries.data() + query * OPENPBR_QUERY_FLOATS;
        out[0] = float(query % std::max<std::size_t>(material_count, 1));
        // Views mostly above the surface (where most shading happens), some from below.
        glm::vec3 view = unit_sphere();
        if (uniform(generator) < 0.8f)
        {
            view.z = std::fabs(view.z);
        }
        const glm::vec3 light = unit_sphere();
        out[1] = view.x, out[2] = view.y, out[3] = view.z;
        out[4] = light.x, out[5] = light.y, out[6] = light.z;
        // u in [0, 1): the float distribution can round up to 1.
        for (int k = 7; k < 10; ++k)
        {
            out[k] = std::min(uniform(generator), 0.99999994f);
        }
        // Exterior IOR: mostly air; one query in eight under water (1.33), one in eight inside
        // glass (1.5), so the relative IOR of every interface also falls below 1.
        const float exterior_choice = uniform(generator);
        out[10] = exterior_choice < 0.75f ? 1.0f : (exterior_choice < 0.875f ? 1.33f : 1.5f);
    }
    return queries;
}

std::vector<float> run_conformance_cpu(const std::vector<float>& queries, const std::vector<float>& materials)
{
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    std::vector<float> results(query_count * OPENPBR_RESULT_FLOATS, 0.0f);
    cpu_kernel::queries = queries.data();
    cpu_kernel::materials = materials.data();
    cpu_kernel::results = results.data();
    tbb::parallel_for(std::size_t(0), query_count, [](std::size_t query) {
        openpbr::openpbr_conformance_run_query(unsigned(query), OPENPBR_CONFORMANCE_MODE_ALL);
    });
    return results;
}

const char* conformance_slot_name(int slot)
{
    static const char* names[] = {"eval.diffuse.r",
                                  "eval.diffuse.g",
                                  "eval.diffuse.b",
                                  "eval.specular.r",
                                  "eval.specular.g",
                                  "eval.specular.b",
                                  "pdf",
                                  "sample.direction.x",
                                  "sample.direction.y",
                                  "sample.direction.z",
                                  "sample.weight.diffuse.r",
                                  "sample.weight.diffuse.g",
                                  "sample.weight.diffuse.b",
                                  "sample.weight.specular.r",
                                  "sample.weight.specular.g",
                                  "sample.weight.specular.b",
                                  "sample.pdf",
                                  "sample.lobe_type",
                                  "emission.r",
                                  "emission.g",
                                  "emission.b"};
    return slot >= 0 && slot < 21 ? names[slot] : "unused";
}

}  // namespace openpbr::host
