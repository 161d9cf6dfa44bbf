// Accuracy-study variant: no multiple-scattering compensation (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE compensation_none
#define OPENPBR_COMPENSATION_MODE OPENPBR_COMPENSATION_NONE
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_compensation_none
#include "host/studies/accuracy_variant_body.h"
