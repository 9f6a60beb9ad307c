/* tb_sweep_check.c - the target search's checks (tb_sweep_check.h). */
#include "testbench/study/tb_sweep_check.h"
#include "base/base_out.h"
#include <stdio.h>
#include <stdlib.h>

int tb_sweep_heldout_all(const tb_sweep *s, tb_target_res *res, tb_target_kind k, double target, uint64_t seed,
                         int *failed, char *err, size_t errlen)
{
    vec_set *ho = calloc(s->npsets, sizeof *ho);
    unsigned char *made = calloc(s->npsets, 1);
    int rc = 0;
    if (!ho || !made) base_out_of_memory();
    for (size_t g = 0; g < s->ngroups && !rc; g++) {
        tb_target_res *x = &res[g];
        size_t p = s->cfg[g].pset;
        if (!x->met) continue;
        if (!made[p]) {
            char e[600];
            if (tb_make_vectors(s->spec.u, tb_sweep_pset_cfg(s, p), s->vs[p]->n_rows, seed, &ho[p], e, sizeof e)) {
                snprintf(err, errlen, "held-out stimuli: %s", e);
                rc = -1;
                break;
            }
            made[p] = 1;
        }
        if (tb_sweep_target_heldout(s, &ho[p], k, target, x, err, errlen)) rc = -1;
        else if (!x->heldout_ok) *failed = 1;
    }
    for (size_t p = 0; p < s->npsets; p++) if (made[p]) vec_set_free(&ho[p]);
    free(ho);
    free(made);
    return rc;
}

int tb_sweep_derived_all(const tb_sweep *s, const tb_target_res *res, const tb_ranges *rg, tb_derived *dres,
                         tb_result *dobs, char *err, size_t errlen)
{
    for (size_t g = 0; g < s->ngroups; g++) {
        const tb_target_res *x = &res[g];
        if (!x->met) continue;
        const tb_sweep_cfg *c = &s->cfg[x->uniform];
        if (tb_derive(s->spec.u, &c->cfg, &x->fmts, rg, &dres[g], err, errlen)) return TB_BADINPUT;
        int st = tb_run(s->spec.u, &c->cfg, &x->fmts, s->vs[c->pset], NULL, &dobs[g], err, errlen);
        if (st != TB_OK) return st;
    }
    return TB_OK;
}
