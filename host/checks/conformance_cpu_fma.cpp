// Conformance path "cpu-fma" (host/checks/conformance_cpu_variants.h); compiled with
// -mfma -ffp-contract=fast by CMakeLists.txt.
#define OPENPBR_CPP_VARIANT_NAMESPACE conformance_cpu_fma
#define OPENPBR_CONFORMANCE_CPU_VARIANT_FUNCTION run_conformance_cpu_fma
#include "host/checks/conformance_cpu_variant_body.h"
