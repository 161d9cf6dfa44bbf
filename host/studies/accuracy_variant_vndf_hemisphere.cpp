// Accuracy-study variant: Heitz 2018 visible-normal sampling (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE vndf_hemisphere
#define OPENPBR_VNDF_METHOD OPENPBR_VNDF_METHOD_HEMISPHERE
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_vndf_hemisphere
#include "host/studies/accuracy_variant_body.h"
