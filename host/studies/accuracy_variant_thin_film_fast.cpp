// Accuracy-study variant: the fast thin-film approximation (host/studies/accuracy_variants.h).
#define OPENPBR_CPP_VARIANT_NAMESPACE thin_film_fast
#define OPENPBR_THIN_FILM_MODEL OPENPBR_THIN_FILM_MODEL_FAST
#define OPENPBR_ACCURACY_VARIANT_FACTORY make_variant_thin_film_fast
#include "host/studies/accuracy_variant_body.h"
