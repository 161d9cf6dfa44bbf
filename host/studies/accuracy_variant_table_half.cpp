// Accuracy-study variant: 16-bit table values (buffer mode) (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE table_half
#define OPENPBR_LUT_MODE_BUFFER 1
#define OPENPBR_LUT_16BIT 1
// The fuzz table stays compiled in (only the compensation tables change).
#define OPENPBR_FUZZ_LTC_MODE_ARRAY 1
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_table_half
#include "host/studies/accuracy_variant_body.h"

namespace openpbr::host {
void accuracy_set_half_table(const std::uint16_t* halves) { ::openpbr::openpbr_lut_data_half = halves; }
}  // namespace openpbr::host
