// Accuracy-study variant: bounded VNDF sampling (Eto & Tokuyoshi 2023) (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE vndf_bounded
#define OPENPBR_VNDF_METHOD OPENPBR_VNDF_METHOD_BOUNDED
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_vndf_bounded
#include "host/studies/accuracy_variant_body.h"
