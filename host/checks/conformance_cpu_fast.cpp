// Conformance path "cpu-fast" (host/checks/conformance_cpu_variants.h); compiled with
// -mfma -ffp-contract=fast by CMakeLists.txt, plus the fast-math hooks with a GPU counterpart.
#define OPENPBR_CPP_VARIANT_NAMESPACE conformance_cpu_fast
#define OPENPBR_CONFORMANCE_CPU_VARIANT_FUNCTION run_conformance_cpu_fast
#define OPENPBR_FAST_SQRT 1
#define OPENPBR_FAST_NORMALIZE 1
#include "host/checks/conformance_cpu_variant_body.h"
