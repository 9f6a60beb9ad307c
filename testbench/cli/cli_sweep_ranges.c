/* cli_sweep_ranges.c - the sweep's --ranges observed|derived and --range
 * NAME=LO:HI: the options, and the observed and derived interval of every
 * signal of each group's chosen design (measured by testbench/study/tb_sweep_check.c;
 * docs/sweeps.md, "Derived ranges"). */
#include "testbench/cli/cli_sweep.h"
#include "testbench/study/tb_sweep_check.h"
#include "base/base_json.h"
#include <stdlib.h>
#include <math.h>
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
    if (!t->dres || !t->dobs) base_out_of_memory();
    char err[600];
    int st = tb_sweep_derived_all(s, t->res, &a->ranges, t->dres, t->dobs, err, sizeof err);
    return cli_from_tb(st, "sweep: %s", err);
}

void sweep_ranges_print(FILE *f, const target_info *t, size_t g)
{
    if (!t->dres || !t->dres[g].sigs) return;
    const tb_derived *d = &t->dres[g];
    fprintf(f, "  ranges of the chosen formats: derived for inputs in their declared ranges (%d items, %llu clocks "
               "to settle), observed on the sweep's stimuli:\n", d->items, (unsigned long long)d->clocks);
    tb_derived_print(f, d, &t->dobs[g], 1);
    const tb_result *r = &t->dobs[g];
    /* Measured, not proven: the bound holds for any input, but the input
     * rounding and the method's error are the largest on the stimuli. */
    for (int o = 0; o < r->n_out; o++)
        fprintf(f, "  error of %s: <= %.4g on the box stimuli (a test on %zu stimuli, not a guarantee for every input "
                   "of the box): its bound %.4g (any input) + input rounding %.4g + method %.4g (the largest on the "
                   "stimuli)\n", r->out[o].name,
                r->out[o].bound + r->out[o].max_input_err + r->out[o].max_method_err, t->box_items, r->out[o].bound,
                r->out[o].max_input_err, r->out[o].max_method_err);
    if (t->box[0]) fprintf(f, "  box of the stimuli: %s\n", t->box);
}

void sweep_ranges_json(FILE *f, const target_info *t, size_t g)
{
    if (!t->dres || !t->dres[g].sigs) return;
    fputs(",\n     \"ranges\": ", f);
    tb_derived_json(f, &t->dres[g], &t->dobs[g]);
    fputs(",\n     \"error_box\": ", f);
    base_json_num(f, tb_derived_err(&t->dobs[g]), 17);
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
 * workload's. First the corners of the input box, each input at four
 * levels: its ends and just inside them (by 2^-40 of the range: below any
 * LSB, so that truncating or rounding the input errs by almost a whole
 * LSB, as at an end it errs by none); all 4^n of them up to 1024, else
 * the two ends (2^n up to 1024), else corners at random. Then inputs
 * drawn uniformly. Expected outputs from the float reference. An input
 * without --range spans what it spans in the sweep's own vectors (its
 * format's whole range would take the unit where its error bound does not
 * apply: horner's t in [1, 2)); the derivation still takes the format's
 * whole range for it. */
#define RANGE_STIMULI 4000
#define RANGE_CORNERS 1024

static double level(double lo, double hi, unsigned k)
{
    double in = (hi - lo) * 0x1p-40;
    return k == 0 ? lo : k == 1 ? hi : k == 2 ? lo + in : hi - in;
}

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
        if (p == 0) {
            /* the box as the report names it: --range, else the vectors' span */
            char *b = a->t.box;
            size_t len = sizeof a->t.box, at = 0;
            b[0] = 0;
            for (int i = 0, j = 0; i < u->nsigs && j < nin; i++) {
                if (u->sigs[i].role != UNIT_SIG_IN) continue;
                int w = snprintf(b + at, at < len ? len - at : 0, "%s%s [%.6g, %.6g]%s", j ? ", " : "", u->sigs[i].name,
                                 lo[j], hi[j], a->ranges.set[i] ? "" : " (its vectors' span)");
                if (w > 0) at += (size_t)w;
                j++;
            }
            if (at >= len) b[len - 1] = 0;
            if (s->npsets > 1 && at + 40 < len) snprintf(b + at, len - at, "; of the first parameter set");
        }
        /* The unit's precondition lo < hi (div's n < d): a stimulus that
         * breaks it is outside the unit's domain and left out; one that
         * keeps it keeps at least the least gap the sweep's own vectors
         * keep (div's 2^-8), so that it still holds once the inputs are
         * quantized. */
        int jlo = -1, jhi = -1;
        for (int i = 0, j = 0; i < u->nsigs && j < nin && u->below.lo; i++) {
            if (u->sigs[i].role != UNIT_SIG_IN) continue;
            if (!strcmp(u->sigs[i].name, u->below.lo)) jlo = j;
            if (!strcmp(u->sigs[i].name, u->below.hi)) jhi = j;
            j++;
        }
        double gap = INFINITY;
        if (jlo < 0 || jhi < 0) jlo = jhi = -1;
        for (size_t r = 0; jlo >= 0 && r < vs->n_rows; r++) gap = fmin(gap, vec_row(vs, r)[jhi] - vec_row(vs, r)[jlo]);
        if (!(gap > 0)) gap = 0;
        size_t pushed = 0;
        vec_rng rng = { a->seed ^ 0x5eedULL };
        /* levels per input: 4 (ends and just inside), 2 (ends), or 0 (random corners) */
        int lv = 2 * nin <= 10 ? 4 : nin <= 10 ? 2 : 0;
        size_t corners = lv == 4 ? (size_t)1 << (2 * nin) : lv == 2 ? (size_t)1 << nin : RANGE_CORNERS;
        for (size_t k = 0; k < corners + RANGE_STIMULI; k++) {
            uint64_t bits = lv ? k : vec_rng_next(&rng);
            for (int j = 0; j < nin; j++) {
                unsigned l = lv == 4 ? (unsigned)(bits >> (2 * j)) & 3 : (unsigned)(bits >> j) & 1;
                v[j] = k < corners ? level(lo[j], hi[j], l) : vec_rng_range(&rng, lo[j], hi[j]);
            }
            if (jlo >= 0 && !(v[jhi] - v[jlo] >= gap && v[jhi] > v[jlo])) continue;
            u->ref->eval(&cfg.model, v, v + vs->n_in);
            if (vec_set_push(vs, v)) base_out_of_memory();
            pushed++;
        }
        a->t.box_items = pushed;
    }
    return 0;
}
