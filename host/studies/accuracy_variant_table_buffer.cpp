// Accuracy-study variant: float32 tables in buffer mode (OPENPBR_LUT_MODE_BUFFER), the storage
// of the Vulkan paths, read through the pointer the application sets (host/studies/accuracy_variants.h).
// The macro gives this translation unit's buffer pointer its own name: the shipped variant's
// ::openpbr::openpbr_lut_data is the compiled-in array, and one name cannot be both.
#define openpbr_lut_data accuracy_buffer_lut_data
#define OPENPBR_CPP_VARIANT_NAMESPACE table_buffer
#define OPENPBR_LUT_MODE_BUFFER 1
// The fuzz table stays compiled in (only the compensation tables change).
#define OPENPBR_FUZZ_LTC_MODE_ARRAY 1
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_table_buffer
#include "host/studies/accuracy_variant_body.h"

namespace openpbr::host {
void accuracy_set_buffer_table(const float* values) { ::openpbr::openpbr_lut_data = values; }
}  // namespace openpbr::host
