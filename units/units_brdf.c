/* units_brdf.c - the BRDF approximation units of seeds 000/001/004. */
#include "units/unit.h"

const unit_desc *const units_brdf[] = {
    NULL
};
