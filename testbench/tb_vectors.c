/* tb_vectors.c - a unit's golden vectors made from its float reference
 * (tb.h: tb_make_vectors), for run, sweep, the Verilog export and the
 * tests when no vector file is given. */
#include "testbench/tb.h"
#include <stdio.h>

int tb_make_vectors(const unit_desc *u, const unit_cfg *cfg, size_t n, uint64_t seed,
                    vec_set *vs, char *err, size_t errlen)
{
    const vec_model *m = u->ref;
    if (!m) { snprintf(err, errlen, "unit %s has no float reference model", u->name); return -1; }
    vec_set_init(vs);
    vec_set_header(vs, m, &cfg->model);
    if (m->gen(&cfg->model, n, seed, vs)) { snprintf(err, errlen, "cannot generate vectors for %s", u->name); return -1; }
    return 0;
}
