// Accuracy-study variant: the shipped defaults (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE shipped
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_shipped
#include "host/studies/accuracy_variant_body.h"
