// conformance_cpu_variant_body.h - the conformance kernel body (targets/kernels/
// openpbr_conformance_kernel.h) compiled as a CPU path that rounds like a GPU: the including
// file (host/checks/conformance_cpu_<name>.cpp) is built with FMA contraction
// (-mfma -ffp-contract=fast, set by CMakeLists.txt), defines OPENPBR_CPP_VARIANT_NAMESPACE
// (its own namespace, so its inline functions never merge with the default build's), any
// OPENPBR_FAST_* hooks, and OPENPBR_CONFORMANCE_CPU_VARIANT_FUNCTION (the entry point of
// host/checks/conformance_cpu_variants.h), then includes this file. No include guard: one
// inclusion per translation unit by design.
#include <tbb/parallel_for.h>

#include "host/checks/conformance_cpu_variants.h"
#include "slang/openpbr.h"

namespace openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::cpu_kernel {
const float* queries = nullptr;
const float* materials = nullptr;
float* results = nullptr;
}  // namespace openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::cpu_kernel
#define OPENPBR_QUERY_READ(index) ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::cpu_kernel::queries[index]
#define OPENPBR_MATERIAL_READ(index) ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::cpu_kernel::materials[index]
#define OPENPBR_RESULT_WRITE(index, value) ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::cpu_kernel::results[index] = (value)
#include "targets/kernels/openpbr_conformance_kernel.h"

namespace openpbr::host {

std::vector<float> OPENPBR_CONFORMANCE_CPU_VARIANT_FUNCTION(const std::vector<float>& queries,
                                                            const std::vector<float>& materials)
{
    namespace variant = ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE;
    const std::size_t query_count = queries.size() / OPENPBR_QUERY_FLOATS;
    std::vector<float> results(query_count * OPENPBR_RESULT_FLOATS, 0.0f);
    variant::cpu_kernel::queries = queries.data();
    variant::cpu_kernel::materials = materials.data();
    variant::cpu_kernel::results = results.data();
    tbb::parallel_for(std::size_t(0), query_count, [](std::size_t query) {
        variant::openpbr_conformance_run_query(unsigned(query), OPENPBR_CONFORMANCE_MODE_ALL);
    });
    return results;
}

}  // namespace openpbr::host
