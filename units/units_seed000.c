/* units_seed000.c - the units of seed 000, in the order `shadesim list`
 * shows them. */
#include "units/unit.h"

extern const unit_desc unit_horner3, unit_horner2, unit_div3, unit_coef3_n1, unit_coef3_n2,
                       unit_coef2, unit_interp3, unit_interp2;

const unit_desc *const units_seed000[] = {
    &unit_horner3, &unit_horner2,
    &unit_div3, &unit_coef3_n1, &unit_coef3_n2, &unit_coef2, &unit_interp3, &unit_interp2,
    NULL
};
