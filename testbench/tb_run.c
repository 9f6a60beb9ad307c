/* tb_run.c - the generic testbench: a driver and a monitor process around
 * any unit, then error metrics against the golden vectors. */
#include "testbench/tb.h"
#include "testbench/tb_stream.h"
#include "testbench/tb_range.h"
#include "testbench/tb_wave.h"
#include "testbench/tb_energy.h"
#include "testbench/tb_lanes.h"
#include "testbench/tb_drive.h"
#include "base/base_par.h"
#include "base/base_out.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct tb_state {
    tb_drive drv;                /* the driver (tb_drive.h), on the quantized inputs */
    const unit_io *io;
    int n_out, beats;
    size_t n_items;
    size_t got;                  /* beats collected */
    const sim_ctx *ctx;
    uint64_t *beat_cycle;
    int64_t  *raw;
    tb_range rg;                /* range logging (tb_range.h) */
} tb_state;

/* Monitor, at each rising edge: the values before the edge are those of the
 * cycle that just ended (range logging, then the output beat when there is
 * one, in collect). */
static __attribute__((noinline)) void collect(tb_state *s, sim_proc *p)
{
    size_t total = s->n_items * (size_t)s->beats;
    if (s->got >= total) return;
    s->beat_cycle[s->got] = sim_get_stats(s->ctx)->clocks - 1;
    for (int o = 0; o < s->n_out; o++) s->raw[s->got * (size_t)s->n_out + o] = s->io->out[o]->cur;
    if (++s->got == total) sim_stop(p->ctx);
}

static void monitor(sim_proc *p)
{
    tb_state *s = p->data;
    tb_range_sample(&s->rg);
    if (s->io->out_valid->cur) collect(s, p);
}

void tb_expected_header(const unit_desc *u, const unit_cfg *cfg, vec_set *h)
{
    int beats = u->beats(cfg);
    snprintf(h->unit, sizeof h->unit, "%s", u->name);
    h->n_in = h->n_out = 0;
    for (int i = 0; i < u->nsigs; i++) {
        if (u->sigs[i].role == UNIT_SIG_IN) snprintf(h->in_names[h->n_in++], 16, "%s", u->sigs[i].name);
    }
    for (int b = 0; b < beats; b++)
        for (int i = 0; i < u->nsigs; i++) {
            if (u->sigs[i].role != UNIT_SIG_OUT || h->n_out >= VEC_MAX_PORTS) continue;
            if (beats == 1) snprintf(h->out_names[h->n_out++], 16, "%s", u->sigs[i].name);
            else snprintf(h->out_names[h->n_out++], 16, "%.10s%d", u->sigs[i].name, b & 1023);
        }
}

static int header_matches(const vec_set *a, const vec_set *b, char *err, size_t errlen)
{
    if (strcmp(a->unit, b->unit)) { snprintf(err, errlen, "vectors are for unit '%s', not '%s'", a->unit, b->unit); return 0; }
    if (a->n_in != b->n_in || a->n_out != b->n_out) {
        snprintf(err, errlen, "vectors have %d inputs and %d outputs; unit %s needs %d and %d",
                 a->n_in, a->n_out, b->unit, b->n_in, b->n_out);
        return 0;
    }
    for (int i = 0; i < a->n_in; i++)
        if (strcmp(a->in_names[i], b->in_names[i])) { snprintf(err, errlen, "input %d is '%s', unit %s expects '%s'", i + 1, a->in_names[i], b->unit, b->in_names[i]); return 0; }
    for (int i = 0; i < a->n_out; i++)
        if (strcmp(a->out_names[i], b->out_names[i])) { snprintf(err, errlen, "output %d is '%s', unit %s expects '%s'", i + 1, a->out_names[i], b->unit, b->out_names[i]); return 0; }
    return 1;
}

/* Per-row figures the golden check needs, beat-major like ideal. */
typedef struct tb_golden {
    const double *ideal_r;   /* ideal of the inputs rounded (not wrapped) to their formats */
    const double *ideal_u;   /* ideal of the vector file's inputs */
    const double *ref_u;     /* the float reference model of the file's inputs */
} tb_golden;

/* The metrics over every item, in item order (tb_stream.c accumulates
 * them; tb_run_stream does the same as its items complete). */
static void metrics(tb_result *r, const vec_set *vs, const double *ideal, const sim_dy *exact,
                    const sim_dy *exact_den, const sim_dy *exact_hi, const unsigned char *exact_ok,
                    const tb_golden *g)
{
    tb_acc a;
    size_t nv = (size_t)r->beats * (size_t)r->n_out;
    tb_acc_begin(&a, r);
    for (size_t it = 0; it < r->vectors; it++) {
        size_t at = it * nv;
        tb_item ti = { NULL, (double *)ideal + at, (double *)g->ideal_r + at, (double *)g->ideal_u + at,
                       (double *)g->ref_u + at, exact ? (sim_dy *)exact + at : NULL,
                       exact_den ? (sim_dy *)exact_den + at : NULL, exact_hi ? (sim_dy *)exact_hi + at : NULL,
                       (unsigned char *)exact_ok + it, NULL };
        tb_acc_item(&a, r, it, r->raw + at, vec_row(vs, it) + r->n_in, &ti);
    }
    tb_acc_end(&a, r);
}

/* tb_run in steps: the working memory (run_mem_alloc), the inputs as the
 * hardware holds them and what it should give (run_prepare), the
 * simulation built (run_build) and run (run_simulate), the figures
 * (run_collect). */

/* What tb_run keeps per item and output value, beat-major. */
typedef struct run_mem {
    size_t n, nbeats, nvals;            /* items, output beats, output values */
    int64_t *in_raw;                    /* [item][input] quantized inputs */
    double *ideal;                      /* 4 * nvals: the ideal, then gold's three */
    sim_dy *exact, *exact_den, *exact_hi;   /* the exact ideal, where the unit has one */
    unsigned char *exact_ok;            /* [item] */
    tb_golden gold;
    uint64_t in_ovf[UNIT_MAX_IO];       /* input overflows, per input */
} run_mem;

static void run_mem_free(run_mem *m)
{
    free(m->in_raw);
    free(m->ideal);
    free(m->exact);
    free(m->exact_den);
    free(m->exact_hi);
    free(m->exact_ok);
}

static int run_mem_alloc(run_mem *m, const unit_desc *u, tb_result *r, size_t n, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    m->n = n;
    m->nbeats = n * (size_t)r->beats;
    m->nvals = m->nbeats * (size_t)r->n_out;
    m->in_raw = malloc(n * (size_t)r->n_in * sizeof *m->in_raw);
    m->ideal = malloc(4 * m->nvals * sizeof *m->ideal);
    int has_exact = u->ideal_exact || u->ideal_ratio || u->ideal_interval;
    m->exact = has_exact ? malloc(m->nvals * sizeof *m->exact) : NULL;
    m->exact_den = u->ideal_ratio ? malloc(m->nvals * sizeof *m->exact_den) : NULL;
    m->exact_hi = u->ideal_interval ? malloc(m->nvals * sizeof *m->exact_hi) : NULL;
    m->exact_ok = calloc(n, 1);
    r->raw = calloc(m->nvals, sizeof *r->raw);
    r->beat_cycle = calloc(m->nbeats, sizeof *r->beat_cycle);
    if (!m->in_raw || !m->ideal || (has_exact && !m->exact) || (u->ideal_ratio && !m->exact_den) ||
        (u->ideal_interval && !m->exact_hi) || !m->exact_ok || !r->raw || !r->beat_cycle) {
        (void)err, (void)errlen;
        base_out_of_memory();   /* the contract: one line, exit status 3 */
    }
    m->gold = (tb_golden){ m->ideal + m->nvals, m->ideal + 2 * m->nvals, m->ideal + 3 * m->nvals };
    return TB_OK;
}

/* Quantize inputs as the hardware will hold them, and compute what the
 * unit should give for exactly those inputs and the golden check's
 * figures (tb_prep); name each output with its format and bound. */
static void run_prepare(run_mem *m, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
                        const vec_set *vs, tb_result *r, int64_t *in_scratch)
{
    tb_prep_ctx pc;
    tb_prep_init(&pc, u, cfg, fmts);
    for (size_t it = 0; it < m->n; it++) {
        size_t at = it * (size_t)r->beats * (size_t)r->n_out;
        tb_item ti = { in_scratch ? in_scratch : m->in_raw + it * (size_t)r->n_in, m->ideal + at, (double *)m->gold.ideal_r + at,
                       (double *)m->gold.ideal_u + at, (double *)m->gold.ref_u + at, m->exact ? m->exact + at : NULL,
                       m->exact_den ? m->exact_den + at : NULL, m->exact_hi ? m->exact_hi + at : NULL, m->exact_ok + it, NULL };
        tb_prep(&pc, vec_row(vs, it), &ti, m->in_ovf);
    }

    tb_stream_outputs(r, u, cfg, fmts);
}

/* The simulation: the unit under a clock, the driver and monitor around
 * it, and the dump when asked for. */
typedef struct run_sim {
    sim_ctx *c;
    sim_signal *clk;
    sim_scope *sc;
    unit_io io;
    tb_state st;
    sim_vcd *vcd;
    tb_wave wave;
    sim_toggle *tog;             /* switching activity (tb_energy.h) */
} run_sim;

static int run_build(run_sim *s, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts, const vec_set *vs,
                     const tb_opts *o, run_mem *m, tb_result *r, char *err, size_t errlen)
{
    tb_built b;
    int bad = tb_build(u, cfg, fmts, &b, err, errlen);
    s->c = b.c; s->clk = b.clk; s->sc = b.sc; s->io = b.io;
    if (bad) return TB_BADINPUT;
    if (o && o->reference) { sim_set_reference(s->c, 1); r->reference = 1; }
    /* 100 MHz in a 1 ns timescale: rising edges at 5, 15, 25, ... */
    sim_clock(s->c, s->clk, 5, 5);
    tb_state *st = &s->st;
    tb_drive_raws(&st->drv, r->n_in, m->in_raw, m->n);
    st->drv.io = &s->io; st->drv.ctx = s->c;
    st->io = &s->io; st->n_out = r->n_out; st->beats = r->beats; st->n_items = m->n;
    st->ctx = s->c; st->beat_cycle = r->beat_cycle; st->raw = r->raw;
    if (tb_range_init(&st->rg, s->c, s->sc, s->clk)) base_out_of_memory();
    sim_proc *drv = sim_proc_new(s->c, "tb.driver", tb_drive_proc, &st->drv);
    sim_sensitive(drv, s->clk, SIM_EDGE_POS);
    sim_proc *mon = sim_proc_new(s->c, "tb.monitor", monitor, st);
    sim_sensitive(mon, s->clk, SIM_EDGE_POS);
    mon->no_init = 1;
    /* every signal exists now: toggles counted from initialization on */
    if (!(s->tog = sim_toggle_new(s->c))) base_out_of_memory();
    if (o && o->vcd_path) {
        s->vcd = tb_wave_open(&s->wave, s->c, o, &s->io, s->clk, u, cfg, vs, err, errlen);
        if (!s->vcd) return TB_BADINPUT;
    }
    return TB_OK;
}

/* Run to the last output beat; a unit that never answers is a failure.
 * The dump is closed here, whatever the outcome. */
static int run_simulate(run_sim *s, const unit_desc *u, const run_mem *m, tb_result *r, char *err, size_t errlen)
{
    int rc = TB_OK;
    /* No unit needs more than a few thousand clocks per beat (pow_n at
     * n = 1024 takes about 20). */
    uint64_t max_clocks = 1000 + m->nbeats * 4096;
    sim_status ss = sim_run(s->c, max_clocks * 10);
    r->stats = *sim_get_stats(s->c);
    if (ss != SIM_OK) {         /* a loop, or a design that is not well formed */
        snprintf(err, errlen, "%s", sim_error(s->c));
        rc = TB_FAIL;
    } else if (s->st.got < m->nbeats) {
        snprintf(err, errlen, "unit %s gave %zu of %zu outputs in %llu clocks", u->name, s->st.got, m->nbeats,
                 (unsigned long long)r->stats.clocks);
        rc = TB_FAIL;
    }
    if (s->vcd) {
        rc = tb_wave_close(&s->wave, s->c, s->vcd, u, rc, err, errlen);
        s->vcd = NULL;
    }
    return rc;
}

/* What both engines derive alike from the beats' cycles and the built
 * design: clocks, area, the critical path and the overflow counts (the
 * unit's, and the inputs' quantization). */
static void run_figures(const run_mem *m, sim_ctx *c, const sim_scope *sc, tb_result *r)
{
    size_t nb = (size_t)r->beats;
    tb_stream_figures(r, m->n, r->beat_cycle[0], r->beat_cycle[(m->n - 1) * nb], r->beat_cycle[m->nbeats - 1], c, sc,
                      m->in_ovf);
}

/* Timing, area, overflows, ranges, error metrics and the verdict. */
static void run_collect(run_sim *s, run_mem *m, const vec_set *vs, tb_result *r)
{
    run_figures(m, s->c, s->sc, r);
    tb_range_finish(&s->st.rg, s->sc, &s->io, m->in_ovf, r);
    tb_energy_fill(r, &s->st.rg, s->tog, s->c, r->stats.clocks);
    metrics(r, vs, m->ideal, m->exact, m->exact_den, m->exact_hi, m->exact_ok, &m->gold);
    tb_verdict(r, NULL);
}

/* The items on the batch's lanes (tb_lanes.h), one wave, while the
 * expected values are prepared on another thread (run_prepare needs
 * nothing of the simulation, the simulation only the quantized inputs):
 * TB_OK with the figures run_collect gives, or 1 with r->engine_why when
 * the lanes do not give the kernel's results (the kernel runs then, on
 * the prepared values). */
typedef struct lanes_par {
    run_mem *m;
    const unit_desc *u;
    const unit_cfg *cfg;
    const unit_fmts *fmts;
    const vec_set *vs;
    tb_result *r;
    tb_lanes *x;
    tb_lanes_wave w;
    int rc;
    char why[300];
} lanes_par;

static void lanes_item(void *ctx, size_t i)
{
    lanes_par *p = ctx;
    if (i == 0) {
        int64_t scratch[UNIT_MAX_IO];   /* the inputs again: the simulation has them already */
        run_prepare(p->m, p->u, p->cfg, p->fmts, p->vs, p->r, scratch);
    } else if (p->x) {
        p->rc = tb_lanes_wave_run(p->x, &p->w, p->why, sizeof p->why);
    }
}

static int run_lanes(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts, const vec_set *vs,
                     run_mem *m, tb_result *r, int threads)
{
    /* the inputs as tb_prep quantizes them (its in_ovf counts come from it) */
    sim_fx_conv cv[UNIT_MAX_IO];
    for (int i = 0, k = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_IN) sim_fx_conv_init(&cv[k++], fmts->f[i], cfg->rnd, cfg->ovf);
    for (size_t it = 0; it < m->n; it++) {
        const double *row = vec_row(vs, it);
        for (int i = 0; i < r->n_in; i++) m->in_raw[it * (size_t)r->n_in + (size_t)i] = sim_fx_conv_real(&cv[i], row[i], NULL);
    }
    lanes_par p = { m, u, cfg, fmts, vs, r, NULL, { m->in_raw, m->n, 0, 0, 1, r->beat_cycle, r->raw, 0 }, 1, "" };
    p.x = tb_lanes_new(u, cfg, fmts, threads, p.why, sizeof p.why);
    /* the preparation beside the lanes' groups: one thread more */
    base_par_for(2, threads < 2 ? 1 : 2, lanes_item, &p);
    int rc = 1;
    if (p.rc) {
        snprintf(r->engine_why, sizeof r->engine_why, "%.150s", p.why);
        goto done;
    }
    tb_lanes_out lo;
    tb_lanes_result(p.x, &lo);
    r->lanes = lo.lanes;
    r->stats.clocks = lo.clocks;
    /* the signals' overflow counts: their constants' (at build) and the lanes' (tb_lanes_result) */
    run_figures(m, lo.c, lo.sc, r);
    tb_range_finish(lo.rg, lo.sc, lo.io, m->in_ovf, r);
    tb_energy_fill_counts(r, lo.rg, lo.toggles, NULL, lo.c, r->stats.clocks);
    metrics(r, vs, m->ideal, m->exact, m->exact_den, m->exact_hi, m->exact_ok, &m->gold);
    tb_verdict(r, NULL);
    rc = TB_OK;
done:
    tb_lanes_free(p.x);
    return rc;
}

int tb_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
           const vec_set *vs, const tb_opts *o, tb_result *r, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->unit = u; r->cfg = *cfg; r->fmts = *fmts;
    r->n_in = unit_n_in(u); r->n_out = unit_n_out(u); r->beats = u->beats(cfg);
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(u, cfg, &hdr);
    if (!header_matches(vs, &hdr, err, errlen)) return TB_BADINPUT;
    if (vs->n_rows == 0) { snprintf(err, errlen, "no vectors"); return TB_BADINPUT; }
    r->vectors = vs->n_rows;

    run_mem m;
    if (run_mem_alloc(&m, u, r, vs->n_rows, err, errlen)) return TB_FAIL;
    if (o && o->lanes && !o->vcd_path && !o->reference) {
        int t = run_lanes(u, cfg, fmts, vs, &m, r, o->threads ? o->threads : 2);   /* prepares too */
        if (t != 1) { run_mem_free(&m); return t; }
        /* the kernel from a clean slate: the lanes may have written some */
        memset(r->raw, 0, m.nvals * sizeof *r->raw);
        memset(r->beat_cycle, 0, m.nbeats * sizeof *r->beat_cycle);
    } else {
        run_prepare(&m, u, cfg, fmts, vs, r, NULL);
    }
    run_sim s;
    memset(&s, 0, sizeof s);
    int rc = run_build(&s, u, cfg, fmts, vs, o, &m, r, err, errlen);
    if (rc == TB_OK) rc = run_simulate(&s, u, &m, r, err, errlen);
    if (rc == TB_OK) run_collect(&s, &m, vs, r);
    if (s.vcd) { sim_vcd_abort(s.vcd); tb_wave_free(&s.wave); }
    sim_toggle_free(s.tog);
    sim_free(s.c);
    run_mem_free(&m);
    tb_range_free(&s.st.rg);
    return rc;
}

void tb_result_free(tb_result *r)
{
    free(r->sigs);
    r->sigs = NULL;
    r->nsigs = 0;
    free(r->raw);
    free(r->beat_cycle);
    r->raw = NULL;
    r->beat_cycle = NULL;
}
