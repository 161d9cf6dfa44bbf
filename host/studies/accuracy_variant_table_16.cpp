// Accuracy-study variant: 2D table at 16 x 16, read through a pointer (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE table_16
#define OPENPBR_LUT_2D_SIZE 16
#define OPENPBR_LUT_MODE_TEXTURE 1
#define OPENPBR_LUT_FETCH(index) ::openpbr::host::accuracy_lut_values_16[index]
// The fuzz table stays compiled in (only the compensation tables change).
#define OPENPBR_FUZZ_LTC_MODE_ARRAY 1
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_table_16
#include "host/studies/accuracy_variant_body.h"
