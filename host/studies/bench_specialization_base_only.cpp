// The C++ build of the BSDF specialized at compile time to the base layer: every feature toggle
// of slang/openpbr_features.h is 0, so coat, fuzz, metal, transmission, dispersion, thin film,
// thin-walled, subsurface, emission and anisotropy code is compiled out. Its own namespace
// (openpbr::base_only, interop/openpbr_interop_cpp.h) keeps it apart from the default build.
#define OPENPBR_CPP_VARIANT_NAMESPACE base_only
#define OPENPBR_FEATURE_COAT 0
#define OPENPBR_FEATURE_FUZZ 0
#define OPENPBR_FEATURE_METAL 0
#define OPENPBR_FEATURE_TRANSMISSION 0
#define OPENPBR_FEATURE_DISPERSION 0
#define OPENPBR_FEATURE_THIN_FILM 0
#define OPENPBR_FEATURE_THIN_WALLED 0
#define OPENPBR_FEATURE_SUBSURFACE 0
#define OPENPBR_FEATURE_EMISSION 0
#define OPENPBR_FEATURE_ANISOTROPY 0

#include "host/studies/bench_specialization.h"

#include <tbb/parallel_for.h>

#include "slang/openpbr.h"

namespace openpbr::host::base_only_kernel {
const float* queries = nullptr;
const float* materials = nullptr;
float* results = nullptr;
}  // namespace openpbr::host::base_only_kernel
#define OPENPBR_QUERY_READ(index) ::openpbr::host::base_only_kernel::queries[index]
#define OPENPBR_MATERIAL_READ(index) ::openpbr::host::base_only_kernel::materials[index]
#define OPENPBR_RESULT_WRITE(index, value) ::openpbr::host::base_only_kernel::results[index] = (value)
#include "targets/kernels/openpbr_conformance_kernel.h"

namespace openpbr::host {

std::vector<float> run_conformance_cpu_base_only(const std::vector<float>& queries, const std::vector<float>& materials)
{
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    std::vector<float> results(query_count * OPENPBR_RESULT_FLOATS, 0.0f);
    base_only_kernel::queries = queries.data();
    base_only_kernel::materials = materials.data();
    base_only_kernel::results = results.data();
    tbb::parallel_for(std::size_t(0), query_count, [](std::size_t query) {
        base_only::openpbr_conformance_run_query(unsigned(query), OPENPBR_CONFORMANCE_MODE_ALL);
    });
    return results;
}

double base_only_eval_ns(const std::vector<float>& packed_materials, std::size_t material_count,
                         const BenchDirections& directions)
{
    base_only_kernel::materials = packed_materials.data();
    std::vector<base_only::OpenPBR_PreparedBsdf> prepared;
    for (std::size_t i = 0; i < directions.views.size(); ++i)
    {
        const base_only::OpenPBR_ResolvedInputs inputs = base_only::openpbr_unpack_material(unsigned(i % material_count));
        prepared.push_back(base_only::openpbr_prepare(inputs, directions.views[i]));
    }
    return measure_ns_per_call(prepared.size(), [&](std::size_t i, std::size_t j) {
        const base_only::OpenPBR_DiffuseSpecular value = base_only::openpbr_eval(prepared[i], directions.lights[j]);
        return value.diffuse.x + value.specular.y;
    });
}

}  // namespace openpbr::host
