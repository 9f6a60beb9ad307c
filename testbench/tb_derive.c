/* tb_derive.c - derived ranges: the unit's schedule simulated on
 * intervals (sim_ival.h), driven as tb_run drives it (tb_derive.h). */
#include "testbench/tb_derive.h"
#include "testbench/tb_range.h"
#include "sim/sim_aff.h"
#include "base/base_num.h"
#include "base/base_out.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Items simulated before the state must have settled, and clocks in all. */
#define DERIVE_MAX_ITEMS  256
#define DERIVE_MAX_CLOCKS 2000000

int tb_ranges_parse(const unit_desc *u, const char *spec, tb_ranges *rg, char *err, size_t errlen)
{
    const char *eq = strchr(spec, '='), *colon = eq ? strchr(eq + 1, ':') : NULL;
    if (!eq || !colon) {
        snprintf(err, errlen, "--range %s: expected NAME=LO:HI", spec);
        return -1;
    }
    int sig = -1;
    for (int i = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_IN && strlen(u->sigs[i].name) == (size_t)(eq - spec)
            && !strncmp(u->sigs[i].name, spec, (size_t)(eq - spec))) sig = i;
    if (sig < 0) {
        snprintf(err, errlen, "--range %s: '%.*s' is not an input of %s", spec, (int)(eq - spec), spec, u->name);
        return -1;
    }
    /* Both ends in the program's one number syntax (base_num.h): no
     * spaces, '+', hexadecimal, inf or nan; an underflow is 0. */
    char lo_s[64];
    size_t n = (size_t)(colon - eq - 1);
    double lo = 0, hi = 0;
    int bad = n >= sizeof lo_s;
    if (!bad) {
        memcpy(lo_s, eq + 1, n);
        lo_s[n] = 0;
        bad = base_num_real(lo_s, 1, &lo) || base_num_real(colon + 1, 1, &hi);
    }
    if (bad) {
        snprintf(err, errlen, "--range %s: LO and HI must be finite decimal numbers", spec);
        return -1;
    }
    if (lo > hi) {
        snprintf(err, errlen, "--range %s: LO %g is above HI %g", spec, lo, hi);
        return -1;
    }
    rg->set[sig] = 1;
    rg->lo[sig] = lo;
    rg->hi[sig] = hi;
    return 0;
}

/* x quantized to f's fraction bits with rounding r, no overflow handling
 * (inputs are quantized as tb_prep does: sim_fx_from_real's rounding). */
static sim_wide round_real(double x, sim_fmt f, sim_round r)
{
    double y = ldexp(x, f.fbits), q;
    r = sim_fmt_round(f, r);
    if (r == SIM_RND_TRUNC) q = floor(y);
    else if (r == SIM_RND_HALF_UP) { q = floor(y); if (y - q >= 0.5) q += 1; }
    else q = nearbyint(y);
    if (q > 0x1p125) q = 0x1p125;
    if (q < -0x1p125) q = -0x1p125;
    return (sim_wide)q;
}

static double wide_real(sim_wide v, int fbits) { return ldexp((double)v, -fbits); }

/* The schedule's state: one interval per signal (what it settles to),
 * the hull of each one's value before overflow handling, and the
 * combinational elements in an order where operands come first. */
typedef struct dsim {
    sim_ctx *c;
    uint32_t n;
    sim_ival *val, *hull, *nxt_pre, *nxt_post, *bound;
    /* the same values as affine forms (sim_aff.h): the relations between
     * signals a linear network keeps, so that its intervals are its exact
     * hulls; each narrows the interval it goes with */
    sim_aff *aval, *anxt;
    uint32_t nsym;                  /* noise symbols made so far */
    const unit_io *io;
    uint32_t *order, norder;        /* combinational elements */
    uint32_t *regs, nregs;
    unsigned char *mark;
    unsigned char *data;            /* depends on the data inputs (mark_data) */
    sim_ival *memo;                 /* [n][MEMO_IN + 1]: a logic element's inputs and interval (logic_memo_eval) */
    unsigned char *memo_set;
    const sim_signal *below_lo, *below_hi;  /* the unit's precondition lo < hi (unit_desc.below), or NULL */
    sim_ival *snap;                 /* [nsnap][n]: the state after each acceptance but the last */
    size_t *snap_got, nsnap, capsnap;   /* output beats by then */
} dsim;

/* The operands an element's value depends on within one clock. */
static int operands(const sim_signal *y, const sim_signal **ops, int max)
{
    sim_prim_info pi;
    int k = 0;
    if (sim_prim_describe(y, &pi) || pi.kind == SIM_KIND_REG || pi.kind == SIM_KIND_CONST) return 0;
    if (pi.a && k < max) ops[k++] = pi.a;
    if (pi.b && k < max) ops[k++] = pi.b;
    if (pi.c && k < max) ops[k++] = pi.c;
    for (int i = 0; i < pi.n && k < max; i++) ops[k++] = pi.in[i];
    return k;
}

/* Depth-first, operands first; a combinational loop is an error. */
static int visit(dsim *d, const sim_signal *y, char *err, size_t errlen)
{
    if (d->mark[y->index] == 2) return 0;
    if (d->mark[y->index] == 1) {
        char p[200];
        snprintf(err, errlen, "derived ranges: combinational loop through %s", sim_signal_path(y, p, sizeof p));
        return -1;
    }
    d->mark[y->index] = 1;
    const sim_signal *ops[80];
    int k = operands(y, ops, 80);
    for (int i = 0; i < k; i++) if (visit(d, ops[i], err, errlen)) return -1;
    d->mark[y->index] = 2;
    sim_prim_info pi;
    if (!sim_prim_describe(y, &pi) && pi.kind != SIM_KIND_REG && pi.kind != SIM_KIND_CONST)
        d->order[d->norder++] = y->index;
    return 0;
}

static void dsim_free(dsim *d)
{
    free(d->val); free(d->hull); free(d->nxt_pre); free(d->nxt_post); free(d->bound);
    free(d->aval); free(d->anxt);
    free(d->order); free(d->regs); free(d->mark);
    free(d->data); free(d->snap); free(d->snap_got);
    free(d->memo); free(d->memo_set);
}

static int pt(sim_ival v) { return v.lo == v.hi; }

/* A logic element's interval is its function over its inputs' values
 * (up to 2^16 of them, sim_ival.c): the same inputs' intervals as at its
 * last evaluation (most clocks: the data's intervals stay) give the same
 * interval, kept here. Other elements are evaluated. */
#define MEMO_IN 8
static void logic_memo_eval(dsim *d, const sim_signal *y, sim_ival *pre, sim_ival *post)
{
    sim_prim_info pi;
    if (sim_prim_describe(y, &pi) || sim_kind_eval(pi.kind) != SIM_KIND_LOGIC || pi.n > MEMO_IN) {
        sim_ival_eval(y, d->val, pre, post);
        return;
    }
    sim_ival *m = d->memo + (size_t)y->index * (MEMO_IN + 1);
    int same = d->memo_set[y->index];
    for (int k = 0; k < pi.n && same; k++)
        same = m[k].lo == d->val[pi.in[k]->index].lo && m[k].hi == d->val[pi.in[k]->index].hi;
    if (!same) {
        sim_ival_eval(y, d->val, &m[MEMO_IN], post);
        for (int k = 0; k < pi.n; k++) m[k] = d->val[pi.in[k]->index];
        d->memo_set[y->index] = 1;
    }
    *pre = *post = m[MEMO_IN];      /* a logic element's pre is its post */
}

/* One clock: the inputs (valid as given; the data inputs keep their
 * intervals), the combinational elements in order, each one's value
 * before overflow handling into its hull; then the rising edge. Returns
 * 1 if an item is accepted at the edge, + 2 if an output beat is valid in
 * the cycle; -1 with a message when the handshake is not a point. */
static int clock_step(dsim *d, const unit_io *io, int valid, char *err, size_t errlen)
{
    d->val[io->in_valid->index] = (sim_ival){ valid, valid };
    d->hull[io->in_valid->index] = sim_ival_hull(d->hull[io->in_valid->index], (sim_ival){ valid, valid });
    for (uint32_t k = 0; k < d->norder; k++) {
        uint32_t i = d->order[k];
        sim_ival pre, post;
        sim_aff apre;
        logic_memo_eval(d, sim_signal_at(d->c, i), &pre, &post);
        sim_aff_eval(sim_signal_at(d->c, i), d->aval, d->val, &pre, &post, &apre, &d->aval[i], &d->nsym);
        d->val[i] = post;
        d->hull[i] = sim_ival_hull(d->hull[i], pre);
    }
    sim_ival rdy = d->val[io->in_ready->index], ov = d->val[io->out_valid->index];
    if (!pt(rdy) || !pt(ov)) {
        snprintf(err, errlen, "derived ranges: %s's handshake (%s) depends on the data; not supported",
                 io->scope ? io->scope->name : "the unit", !pt(rdy) ? "in_ready" : "out_valid");
        return -1;
    }
    for (uint32_t k = 0; k < d->nregs; k++) {
        uint32_t i = d->regs[k];
        sim_aff apre;
        sim_ival_eval(sim_signal_at(d->c, i), d->val, &d->nxt_pre[i], &d->nxt_post[i]);
        sim_aff_eval(sim_signal_at(d->c, i), d->aval, d->val, &d->nxt_pre[i], &d->nxt_post[i], &apre, &d->anxt[i],
                     &d->nsym);
        d->hull[i] = sim_ival_hull(d->hull[i], d->nxt_pre[i]);
    }
    for (uint32_t k = 0; k < d->nregs; k++) {
        d->val[d->regs[k]] = d->nxt_post[d->regs[k]];
        d->aval[d->regs[k]] = d->anxt[d->regs[k]];
    }
    return (valid && rdy.lo ? 1 : 0) + (ov.lo ? 2 : 0);
}

/* The simulation's arrays for the build's n signals. */
static void dsim_alloc(dsim *d, sim_ctx *c)
{
    memset(d, 0, sizeof *d);
    d->c = c;
    d->n = sim_signal_count(c);
    size_t n = d->n ? d->n : 1;
    d->val = calloc(n, sizeof *d->val); d->hull = calloc(n, sizeof *d->hull);
    d->nxt_pre = calloc(n, sizeof *d->nxt_pre); d->nxt_post = calloc(n, sizeof *d->nxt_post);
    d->bound = calloc(n, sizeof *d->bound);
    d->order = calloc(n, sizeof *d->order); d->regs = calloc(n, sizeof *d->regs); d->mark = calloc(n, 1);
    d->data = calloc(n, 1);
    d->aval = calloc(n, sizeof *d->aval);
    d->anxt = calloc(n, sizeof *d->anxt);
    d->memo = calloc(n * (MEMO_IN + 1), sizeof *d->memo);
    d->memo_set = calloc(n, 1);
    if (!d->aval || !d->anxt || !d->memo || !d->memo_set) base_out_of_memory();
    if (!d->val || !d->hull || !d->nxt_pre || !d->nxt_post || !d->bound || !d->order || !d->regs || !d->mark ||
        !d->data)
        base_out_of_memory();
}

/* The precondition lo < hi between two inputs (unit_desc.below), as the
 * unit holds them: hi - lo is at least the finer of their LSBs (gap).
 * Their intervals: lo's below hi's top, hi's above lo's bottom. */
static double below_gap(const dsim *d, int *g)
{
    *g = d->below_lo->fmt.fbits > d->below_hi->fmt.fbits ? d->below_lo->fmt.fbits : d->below_hi->fmt.fbits;
    return ldexp(1, -*g);
}

static void below_narrow(dsim *d)
{
    int g;
    below_gap(d, &g);
    sim_ival *lo = &d->val[d->below_lo->index], *hi = &d->val[d->below_hi->index];
    int fl = d->below_lo->fmt.fbits, fh = d->below_hi->fmt.fbits;
    /* on the common grid 2^-g: lo <= hi's top - 1, hi >= lo's bottom + 1 */
    sim_wide top = hi->hi * ((sim_wide)1 << (g - fh)) - 1, bot = lo->lo * ((sim_wide)1 << (g - fl)) + 1;
    sim_wide lo_max = top >> (g - fl), hi_min = -((-bot) >> (g - fh));    /* floor, ceil */
    if (lo_max < lo->hi) lo->hi = lo_max;
    if (hi_min > hi->lo) hi->lo = hi_min;
    if (lo->lo > lo->hi) lo->hi = lo->lo;           /* no item meets it: left to the runs */
    if (hi->lo > hi->hi) hi->lo = hi->hi;
    d->hull[d->below_lo->index] = *lo;
    d->hull[d->below_hi->index] = *hi;
}

/* lo's form as hi's less a symbol of its own over the gaps an item can
 * have, [LSB, hi's top - lo's bottom]: the relation the unit's datapath
 * relies on (div's remainder stays below the divisor from its load on). */
static void below_forms(dsim *d)
{
    int g;
    double gap = below_gap(d, &g);
    const sim_signal *ls = d->below_lo, *hs = d->below_hi;
    double top = ldexp((double)d->val[hs->index].hi, -hs->fmt.fbits), bot = ldexp((double)d->val[ls->index].lo, -ls->fmt.fbits);
    if (top - bot < gap) return;
    sim_aff u = sim_aff_symbol(gap, top - bot, &d->nsym);
    d->aval[ls->index] = sim_aff_lin(1, &d->aval[hs->index], -1, &u);
}

/* Everything starts at its value after elaboration (registers their
 * reset value); the data inputs hold their declared interval (rg's when
 * it sets one) and are marked data. */
static void dsim_start(dsim *d, const tb_built *b, const unit_desc *u, const unit_cfg *cfg, const tb_ranges *rg)
{
    d->io = &b->io;
    for (uint32_t i = 0; i < d->n; i++) {
        sim_signal *s = sim_signal_at(b->c, i);
        d->val[i] = d->hull[i] = (sim_ival){ s->cur, s->cur };
        d->aval[i] = sim_aff_of_ival(d->val[i], s->fmt, &d->nsym);
        if (s->kind == SIM_KIND_REG) d->regs[d->nregs++] = i;
    }
    for (int i = 0, k = 0; i < u->nsigs; i++) {
        if (u->sigs[i].role != UNIT_SIG_IN) continue;
        sim_signal *s = b->io.in[k++];
        sim_ival pre = { s->raw_min, s->raw_max };
        if (rg && rg->set[i]) pre = (sim_ival){ round_real(rg->lo[i], s->fmt, cfg->rnd), round_real(rg->hi[i], s->fmt, cfg->rnd) };
        d->hull[s->index] = pre;
        d->val[s->index] = sim_ival_fit(pre, s->fmt, sim_fmt_ovf(s->fmt, cfg->ovf));
        d->aval[s->index] = sim_aff_of_ival(d->val[s->index], s->fmt, &d->nsym);
        d->data[s->index] = 1;
        if (u->below.lo && !strcmp(u->sigs[i].name, u->below.lo)) d->below_lo = s;
        if (u->below.hi && !strcmp(u->sigs[i].name, u->below.hi)) d->below_hi = s;
    }
    if (d->below_lo && d->below_hi) {
        below_narrow(d);
        below_forms(d);
    } else d->below_lo = d->below_hi = NULL;
}

/* The next item on the inputs: their forms new symbols, unrelated to the
 * item before. */
static void new_item(dsim *d)
{
    for (int k = 0; k < UNIT_MAX_IO && d->io->in[k]; k++) {
        const sim_signal *s = d->io->in[k];
        d->aval[s->index] = sim_aff_of_ival(d->val[s->index], s->fmt, &d->nsym);
    }
    if (d->below_lo) below_forms(d);
}

/* State joined (or restored) as intervals: each register's form becomes
 * its interval as a symbol of its own (the relations between registers
 * are dropped, which only widens; within one register's uses, kept). */
static void regs_as_intervals(dsim *d, int data_only)
{
    for (uint32_t k = 0; k < d->nregs; k++) {
        uint32_t i = d->regs[k];
        if (data_only && !d->data[i]) continue;
        d->aval[i] = sim_aff_of_ival(d->val[i], sim_signal_at(d->c, i)->fmt, &d->nsym);
    }
}

/* The signals that depend on the data (d->data grows to them): only
 * their registers' states are joined at acceptances; control state (step
 * counters, pipeline valid bits) stays a point, and the state has settled
 * when it repeats. */
static void mark_data(dsim *d)
{
    unsigned char *is_in = d->data;
    for (int changed = 1; changed;) {
        changed = 0;
        for (uint32_t i = 0; i < d->n; i++) {
            const sim_signal *y = sim_signal_at(d->c, i);
            sim_prim_info pi;
            if (is_in[i] || sim_prim_describe(y, &pi) || pi.kind == SIM_KIND_CONST) continue;
            int dep = (pi.a && is_in[pi.a->index]) || (pi.b && is_in[pi.b->index]) || (pi.c && is_in[pi.c->index])
                      || (pi.rst && is_in[pi.rst->index]);
            for (int k = 0; k < pi.n && !dep; k++) dep = is_in[pi.in[k]->index];
            if (dep) { is_in[i] = 1; changed = 1; }
        }
    }
}

/* The state after an acceptance, kept for the runs of that many items. */
static void snap_keep(dsim *d, size_t got)
{
    size_t n = d->n ? d->n : 1;
    if (d->nsnap == d->capsnap) {
        d->capsnap = d->capsnap ? 2 * d->capsnap : 8;
        sim_ival *ns = realloc(d->snap, d->capsnap * n * sizeof *d->snap);
        size_t *ng = realloc(d->snap_got, d->capsnap * sizeof *d->snap_got);
        if (ns) d->snap = ns;
        if (ng) d->snap_got = ng;
        if (!ns || !ng) base_out_of_memory();
    }
    memcpy(d->snap + d->nsnap * n, d->val, n * sizeof *d->snap);
    d->snap_got[d->nsnap++] = got;
}

/* Items offered one after another until the state after an acceptance
 * lies within the join of the states at the acceptances before (and a
 * few items are in), then drained to the last beat. *items, *clocks: the
 * items accepted and the clocks run. The state after each acceptance but
 * the last is kept (snap_keep) for drain_runs. */
static int run_items(dsim *d, const tb_built *b, const unit_desc *u, int beats, int *items, uint64_t *clocks,
                     char *err, size_t errlen)
{
    int valid = 1, have_bound = 0, st;
    size_t accepted = 0, got = 0;
    uint64_t clk = 0;
    for (;; clk++) {
        if (clk >= DERIVE_MAX_CLOCKS) {
            snprintf(err, errlen, "derived ranges: %s did not finish in %d clocks", u->name, DERIVE_MAX_CLOCKS);
            return -1;
        }
        if ((st = clock_step(d, &b->io, valid, err, errlen)) < 0) return -1;
        got += (size_t)(st & 2) / 2;
        if (!valid && got >= accepted * (size_t)beats) break;   /* the last beat: tb_run stops here */
        if (!(st & 1)) continue;
        accepted++;
        /* An item accepted: the state now, joined with the state at the
         * last acceptance. Within it (and a few items in): settled. */
        int inside = have_bound;
        for (uint32_t k = 0; k < d->nregs && inside; k++)
            inside = sim_ival_within(d->val[d->regs[k]], d->bound[d->regs[k]]);
        if (inside && accepted >= 3) { valid = 0; continue; }
        if (accepted >= DERIVE_MAX_ITEMS) {
            uint32_t w = 0;
            for (uint32_t k = 0; k < d->nregs; k++)
                if (!sim_ival_within(d->val[d->regs[k]], d->bound[d->regs[k]])) { w = d->regs[k]; break; }
            char p[200];
            snprintf(err, errlen, "derived ranges: %s keeps growing over %d items (an accumulator never cleared?)",
                     sim_signal_path(sim_signal_at(b->c, w), p, sizeof p), DERIVE_MAX_ITEMS);
            return -1;
        }
        snap_keep(d, got);
        for (uint32_t k = 0; k < d->nregs; k++) {
            uint32_t i = d->regs[k];
            if (have_bound && d->data[i]) d->val[i] = sim_ival_hull(d->val[i], d->bound[i]);
            d->bound[i] = d->val[i];
        }
        if (have_bound) regs_as_intervals(d, 1);
        new_item(d);
        have_bound = 1;
    }
    *items = (int)accepted;
    *clocks = clk + 1;
    return 0;
}

/* Runs of fewer items: from the state after their last acceptance,
 * offering nothing more, to their last beat (a pipelined schedule drains
 * differently with fewer items in flight). */
static int drain_runs(dsim *d, const tb_built *b, const unit_desc *u, int beats, char *err, size_t errlen)
{
    size_t n = d->n ? d->n : 1;
    int st;
    for (size_t j = 0; j < d->nsnap; j++) {
        memcpy(d->val, d->snap + j * n, n * sizeof *d->snap);
        regs_as_intervals(d, 0);
        new_item(d);
        size_t g = d->snap_got[j];
        for (uint64_t c = 0; g < (j + 1) * (size_t)beats; c++) {
            if (c >= DERIVE_MAX_CLOCKS || (st = clock_step(d, &b->io, 0, err, errlen)) < 0) {
                if (c >= DERIVE_MAX_CLOCKS) snprintf(err, errlen, "derived ranges: %s did not drain", u->name);
                return -1;
            }
            g += (size_t)(st & 2) / 2;
        }
    }
    return 0;
}

/* out's signals: each signal of the unit's scope with its hull, as reals,
 * and whether it fits its format. */
static void collect(tb_derived *out, const dsim *d, const tb_built *b, const unit_desc *u)
{
    out->sigs = calloc(d->n ? d->n : 1, sizeof *out->sigs);
    if (!out->sigs) base_out_of_memory();
    for (uint32_t i = 0; i < d->n; i++) {
        sim_signal *s = sim_signal_at(b->c, i);
        if (s == b->clk || !tb_range_in_scope(s, b->sc)) continue;
        tb_dsig *t = &out->sigs[out->nsigs];
        tb_range_name(s, b->sc, t->name, sizeof t->name);
        t->fmt = s->fmt;
        t->kind = s->kind;
        t->pre = d->hull[i];
        t->lo = wide_real(t->pre.lo, s->fmt.fbits);
        t->hi = wide_real(t->pre.hi, s->fmt.fbits);
        t->fits = sim_ival_within(t->pre, (sim_ival){ s->raw_min, s->raw_max });
        out->nfail += !t->fits;
        for (int k = 0; k < u->nsigs; k++)
            if (!strcmp(u->sigs[k].name, t->name)) out->at[k] = out->nsigs;
        out->nsigs++;
    }
}

int tb_derive(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, const tb_ranges *rg,
              tb_derived *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; i < UNIT_MAX_SIGS; i++) out->at[i] = -1;
    tb_built b;
    if (tb_build(u, cfg, f, &b, err, errlen)) { sim_free(b.c); return -1; }
    dsim d;
    int rc = -1, bad = 0;
    dsim_alloc(&d, b.c);
    dsim_start(&d, &b, u, cfg, rg);
    for (uint32_t i = 0; i < d.n && !bad; i++) bad = visit(&d, sim_signal_at(b.c, i), err, errlen);
    if (bad) goto done;
    mark_data(&d);
    int beats = u->beats(cfg), items;
    uint64_t clocks;
    if (run_items(&d, &b, u, beats, &items, &clocks, err, errlen) || drain_runs(&d, &b, u, beats, err, errlen))
        goto done;
    out->items = items;
    out->clocks = clocks;
    collect(out, &d, &b, u);
    rc = 0;
done:
    dsim_free(&d);
    sim_free(b.c);
    if (rc) tb_derived_free(out);
    return rc;
}

void tb_derived_free(tb_derived *d)
{
    free(d->sigs);
    d->sigs = NULL;
    d->nsigs = 0;
}

int tb_derive_fmts(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *in, const tb_ranges *rg,
                   const unsigned char *keep, unit_fmts *out, char *err, size_t errlen)
{
    unit_fmts wide = *in;
    /* Integer parts wide enough that nothing overflows (40 bits: values
     * up to 2^39; a signal needing more is reported as not fitting). */
    for (int i = 0; i < u->nsigs; i++) {
        if (u->sigs[i].role == UNIT_SIG_IN || (keep && keep[i]) || unit_sig_fmt_fixed(u, i)) continue;
        sim_fmt *g = &wide.f[i];
        int max = (g->is_signed ? 64 : 63) - g->fbits, ib = max < 40 ? max : 40;
        if (ib > g->ibits) { g->ibits = (int8_t)ib; g->width = (uint8_t)(ib + g->fbits); }
    }
    tb_derived d;
    if (tb_derive(u, cfg, &wide, rg, &d, err, errlen)) return -1;
    *out = *in;
    int rc = 0;
    for (int i = 0; i < u->nsigs && !rc; i++) {
        if ((keep && keep[i]) || unit_sig_fmt_fixed(u, i) || d.at[i] < 0) continue;
        if (u->sigs[i].role == UNIT_SIG_IN && !(rg && rg->set[i])) continue;
        const tb_dsig *t = &d.sigs[d.at[i]];
        int ib = sim_ival_ibits(t->pre, in->f[i]);
        if (ib < 0) {
            snprintf(err, errlen, "derived ranges: %s's interval [%g, %g] fits no %s format of %d fraction bits",
                     u->sigs[i].name, t->lo, t->hi, in->f[i].is_signed ? "signed" : "unsigned", in->f[i].fbits);
            rc = -1;
            break;
        }
        out->f[i].ibits = (int8_t)ib;
        out->f[i].width = (uint8_t)(ib + in->f[i].fbits);
    }
    tb_derived_free(&d);
    return rc;
}

/* The observed range of signal name in r ("-" when none). */
static void observed(char *buf, size_t len, const tb_result *r, const char *name)
{
    snprintf(buf, len, "-");
    if (!r || !r->sigs) return;
    for (int i = 0; i < r->nsigs; i++)
        if (!strcmp(r->sigs[i].name, name) && r->sigs[i].seen)
            snprintf(buf, len, "[%.6g, %.6g]", sim_fx_to_real(r->sigs[i].min, r->sigs[i].fmt),
                     sim_fx_to_real(r->sigs[i].max, r->sigs[i].fmt));
}

void tb_derived_print(FILE *f, const tb_derived *d, const tb_result *r, int all)
{
    char fb[SIM_FMT_STRLEN], ob[80];
    for (int i = 0; i < d->nsigs; i++) {
        const tb_dsig *t = &d->sigs[i];
        if (!all && t->fits) continue;
        if (t->kind == SIM_KIND_CONST) continue;
        char db[80];
        snprintf(db, sizeof db, "[%.6g, %.6g]", t->lo, t->hi);
        if (r && r->sigs) {
            observed(ob, sizeof ob, r, t->name);
            fprintf(f, "  %-14s %-12s derived %-28s observed %-28s %s\n", t->name, sim_fmt_str(t->fmt, fb), db, ob,
                    t->fits ? "fits" : "DOES NOT FIT");
        } else {
            fprintf(f, "  %-14s %-12s derived %-28s %s\n", t->name, sim_fmt_str(t->fmt, fb), db,
                    t->fits ? "fits" : "DOES NOT FIT");
        }
    }
}

void tb_derived_json(FILE *f, const tb_derived *d, const tb_result *r)
{
    char fb[SIM_FMT_STRLEN];
    fputc('[', f);
    for (int i = 0, first = 1; i < d->nsigs; i++) {
        const tb_dsig *t = &d->sigs[i];
        if (t->kind == SIM_KIND_CONST) continue;
        fprintf(f, "%s{\"name\": \"%s\", \"format\": \"%s\", \"derived\": [%.17g, %.17g], \"fits\": %s", first ? "" : ", ",
                t->name, sim_fmt_str(t->fmt, fb), t->lo, t->hi, t->fits ? "true" : "false");
        first = 0;
        if (r && r->sigs)
            for (int k = 0; k < r->nsigs; k++)
                if (!strcmp(r->sigs[k].name, t->name) && r->sigs[k].seen)
                    fprintf(f, ", \"observed\": [%.17g, %.17g]", sim_fx_to_real(r->sigs[k].min, r->sigs[k].fmt),
                            sim_fx_to_real(r->sigs[k].max, r->sigs[k].fmt));
        fputc('}', f);
    }
    fputc(']', f);
}
