// Accuracy-study variant: every fast-math hook (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE fast_all
#define OPENPBR_FAST_RCP_SQRT 1
#define OPENPBR_FAST_SQRT 1
#define OPENPBR_FAST_NORMALIZE 1
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_fast_all
#include "host/studies/accuracy_variant_body.h"
