// Accuracy-study variant: the whole BSDF in double precision (host/studies/accuracy_variants.h), the
// reference of the "per-query relative error vs the double build" metric. Compiled against the
// double-precision copy of the headers that tools/make_double_headers.py derives from the
// single source into the build directory (CMake target openpbr_accuracy_double, whose include
// path puts that copy before the repository's). Not generated from
// host/studies/accuracy_variants.cmake like the float variants: those compile against the
// repository's headers.
// The compiled-in tables get this translation unit's own names: the float variants'
// ::openpbr::openpbr_lut_data is a float array, and one name cannot have two types.
#define openpbr_lut_data accuracy_double_lut_data
#define openpbr_fuzz_ltc_data accuracy_double_fuzz_ltc_data
#define OPENPBR_CPP_VARIANT_NAMESPACE double_precision
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_double
#include "host/studies/accuracy_variant_body.h"

static_assert(sizeof(openpbr::double_precision::OpenPBR_DiffuseSpecular{}.diffuse.x) == sizeof(double),
              "the double-precision headers must come first on this translation unit's include path");
