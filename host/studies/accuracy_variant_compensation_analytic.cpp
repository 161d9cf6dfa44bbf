// Accuracy-study variant: polynomial fit of the GGX albedo (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE compensation_analytic
#define OPENPBR_COMPENSATION_MODE OPENPBR_COMPENSATION_ANALYTIC
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_compensation_analytic
#include "host/studies/accuracy_variant_body.h"
