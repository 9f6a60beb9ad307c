/* tb_sweep_ranges.c - the target search under derived ranges (--ranges
 * derived): integer bits from the intervals the unit's network gives for
 * any input in the declared ranges (tb_derive.h), fraction bits searched
 * as for observed ranges (tb_sweep.c). */
#include "testbench/study/tb_sweep.h"
#include <string.h>

int tb_sweep_derive(const tb_sweep *s, const tb_sweep_cfg *c, const unsigned char *keep, unit_fmts *f,
                    char *err, size_t errlen)
{
    unit_fmts in = *f;
    return tb_derive_fmts(s->spec.u, &c->cfg, &in, s->spec.ranges, keep, f, err, errlen);
}

int tb_sweep_derived_start(const tb_sweep *s, size_t group, tb_target_kind k, double target,
                           const unsigned char *keep, tb_target_res *out, char *err, size_t errlen)
{
    out->met = 0;
    for (size_t i = group; i < s->n; i += s->ngroups) {
        /* every width: its uniform design may overflow where the
         * derived one does not */
        const tb_sweep_cfg *c = &s->cfg[i];
        unit_fmts f = c->fmts;
        char e[400];
        /* A width whose formats cannot be derived (an interval beyond 64
         * bits) is skipped, as one that misses the target. */
        if (tb_sweep_derive(s, c, keep, &f, e, sizeof e)) continue;
        tb_result r;
        int st = tb_run(s->spec.u, &c->cfg, &f, s->vs[c->pset], NULL, &r, e, sizeof e);
        tb_result_free(&r);
        if (st == TB_BADINPUT) { snprintf(err, errlen, "derived ranges: %s", e); return -1; }
        out->runs++;
        if (!tb_target_holds_derived(&r, st, k, target)) continue;
        out->met = 1;
        out->uniform = i;
        out->fmts = f;
        out->r = r;
        return 0;
    }
    return 0;
}
