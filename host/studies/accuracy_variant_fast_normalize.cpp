// Accuracy-study variant: OPENPBR_FAST_NORMALIZE (with the fast reciprocal square root) (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE fast_normalize
#define OPENPBR_FAST_RCP_SQRT 1
#define OPENPBR_FAST_NORMALIZE 1
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_fast_normalize
#include "host/studies/accuracy_variant_body.h"
