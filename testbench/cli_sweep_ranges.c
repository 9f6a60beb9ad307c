/* cli_sweep_ranges.c - the sweep's --ranges observed|derived and --range
 * NAME=LO:HI: the options, and the observed and derived interval of every
 * signal of each group's chosen design (docs/sweeps.md, "Derived ranges"). */
#include "testbench/cli_sweep.h"
#include <stdlib.h>
#include <string.h>

int sweep_o_ranges(void *base, const char *opt, const char *val)
{
    sweep_args *a = base;
    (void)opt;
    if (!strcmp(val, "derived")) a->derived = 1;
    else if (!strcmp(val, "observed")) a->derived = 0;
    else {
        char e[200];
        return cli_usage_error("--ranges %s: expected observed or derived", cli_esc(val, e, sizeof e));
    }
    return 0;
}

int sweep_o_range(void *base, const char *opt, const char *val)
{
    sweep_args *a = base;
    char err[400];
    (void)opt;
    if (tb_ranges_parse(a->o.u, val, &a->ranges, err, sizeof err)) return cli_usage_error("%s", err);
    a->nrange++;
    return 0;
}

int sweep_ranges_check(sweep_args *a)
{
    if (a->nrange && !a->derived) return cli_usage_error("sweep: --range goes with --ranges derived");
    if (a->derived && !a->t.on)
        return cli_usage_error("sweep: --ranges derived goes with --target-error or --target-nmse");
    a->sp.ranges = a->derived ? &a->ranges : NULL;
    return 0;
}

int sweep_ranges_collect(sweep_args *a, tb_sweep *s)
{
    if (!a->derived) return 0;
    target_info *t = &a->t;
    t->dres = calloc(s->ngroups, sizeof *t->dres);
    t->dobs = calloc(s->ngroups, sizeof *t->dobs);
    if (!t->dres || !t->dobs) return cli_usage_error("sweep: out of memory");
    for (size_t g = 0; g < s->ngroups; g++) {
        const tb_target_res *x = &t->res[g];
        if (!x->met) continue;
        const tb_sweep_cfg *c = &s->cfg[x->uniform];
        char err[600];
        if (tb_derive(s->spec.u, &c->cfg, &x->fmts, &a->ranges, &t->dres[g], err, sizeof err))
            return cli_usage_error("sweep: %s", err);
        int st = tb_run(s->spec.u, &c->cfg, &x->fmts, s->vs[c->pset], NULL, &t->dobs[g], err, sizeof err);
        if (st != TB_OK) return cli_usage_error("sweep: %s", err);
    }
    return 0;
}

void sweep_ranges_print(FILE *f, const target_info *t, size_t g)
{
    if (!t->dres || !t->dres[g].sigs) return;
    const tb_derived *d = &t->dres[g];
    fprintf(f, "  ranges of the chosen formats: derived for inputs in their declared ranges (%d items, %llu clocks "
               "to settle), observed on the sweep's stimuli:\n", d->items, (unsigned long long)d->clocks);
    tb_derived_print(f, d, &t->dobs[g], 1);
}

void sweep_ranges_json(FILE *f, const target_info *t, size_t g)
{
    if (!t->dres || !t->dres[g].sigs) return;
    fputs(",\n     \"ranges\": ", f);
    tb_derived_json(f, &t->dres[g], &t->dobs[g]);
}

void sweep_ranges_free(target_info *t, size_t ngroups)
{
    for (size_t g = 0; t->dres && g < ngroups; g++) tb_derived_free(&t->dres[g]);
    for (size_t g = 0; t->dobs && g < ngroups; g++) tb_result_free(&t->dobs[g]);
    free(t->dres);
    free(t->dobs);
    t->dres = NULL;
    t->dobs = NULL;
}

/* Stimuli over the declared ranges, appended to each parameter set's
 * vectors under --ranges derived, so that the search chooses fraction bits
 * on inputs anywhere in the ranges the formats are made for, not only the
 * workload's: every corner of the input box (up to 256 of them, then
 * corners at random), then inputs drawn uniformly; expected outputs from
 * the float reference. An input without --range spans what it spans in
 * the sweep's own vectors (its format's whole range would take the unit
 * where its error bound does not apply: horner's t in [1, 2)); the
 * derivation still takes the format's whole range for it. */
#define RANGE_STIMULI 4000

int sweep_ranges_stimuli(sweep_args *a, tb_sweep *s, vec_set *sets)
{
    if (!a->derived) return 0;
    const unit_desc *u = a->o.u;
    if (!u->ref) return cli_usage_error("sweep: --ranges derived needs %s's float reference", u->name);
    for (size_t p = 0; p < s->npsets; p++) {
        unit_cfg cfg = *tb_sweep_pset_cfg(s, p);
        vec_set *vs = &sets[p];
        double lo[VEC_MAX_PORTS], hi[VEC_MAX_PORTS], v[2 * VEC_MAX_PORTS];
        int nin = 0;
        for (int i = 0; i < u->nsigs && nin < VEC_MAX_PORTS; i++) {
            if (u->sigs[i].role != UNIT_SIG_IN) continue;
            lo[nin] = hi[nin] = vs->n_rows ? vec_row(vs, 0)[nin] : 0;
            for (size_t r = 1; r < vs->n_rows; r++) {
                double x = vec_row(vs, r)[nin];
                if (x < lo[nin]) lo[nin] = x;
                if (x > hi[nin]) hi[nin] = x;
            }
            if (a->ranges.set[i]) { lo[nin] = a->ranges.lo[i]; hi[nin] = a->ranges.hi[i]; }
            nin++;
        }
        vec_rng rng = { a->seed ^ 0x5eedULL };
        size_t corners = nin <= 8 ? (size_t)1 << nin : 256;
        for (size_t k = 0; k < corners + RANGE_STIMULI; k++) {
            uint64_t bits = nin <= 8 ? k : vec_rng_next(&rng);
            for (int j = 0; j < nin; j++)
                v[j] = k < corners ? ((bits >> j) & 1 ? hi[j] : lo[j]) : vec_rng_range(&rng, lo[j], hi[j]);
            u->ref->eval(&cfg.model, v, v + vs->n_in);
            if (vec_set_push(vs, v)) return cli_usage_error("sweep: out of memory");
        }
    }
    return 0;
}
