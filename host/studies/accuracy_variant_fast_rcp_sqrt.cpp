// Accuracy-study variant: OPENPBR_FAST_RCP_SQRT (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE fast_rcp_sqrt
#define OPENPBR_FAST_RCP_SQRT 1
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_fast_rcp_sqrt
#include "host/studies/accuracy_variant_body.h"
