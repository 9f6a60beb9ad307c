/* sim_timing.c - arrival times over the element graph (a depth-first walk
 * from every signal back to where its paths start, each signal once), the
 * latest endpoint, and the path back to its start. */
#include "sim/sim_timing.h"
#include "sim/sim_delay.h"
#include "sim/sim_prim.h"
#include "sim/sim_live.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct walk {
    const sim_ctx *c;
    sim_carry carry;      /* the carries the flow leaves (sim_delay.h) */
    double  *load;        /* each signal's extra delay for the pins its bits drive (sim_delay_load_ps) */
    unsigned char *csa;   /* 1: an adder merged into the multi-operand adder of its one reader (sim_delay_csa) */
    sim_delay *al, *am;   /* arrival of each signal's least and most significant bit (NONE: no path) */
    int32_t *pred;        /* the input its most significant bit came through, or -1 at a start */
    unsigned char *st;    /* 0 not seen, 1 on the walk's stack, 2 done */
    char    *err;
    size_t   errlen;
} walk;

static int is_addsub(sim_kind k) { return k == SIM_KIND_ADD || k == SIM_KIND_SUB; }

/* The live spans of the terms a multi-operand adder adds: an operand
 * merged into it (csa) by its own operands, any other by its own. */
#define TERMS_MAX 32
static void terms(const struct walk *w, const sim_signal *s, int *lo, int *hi, int *n, int depth);

/* Later arrival wins (by ps; at a tie, more levels); NONE loses. */
static int later(sim_delay a, sim_delay b) { return a.lv >= 0 && (b.lv < 0 || a.ps > b.ps || (a.ps == b.ps && a.lv > b.lv)); }

static void terms(const walk *w, const sim_signal *s, int *lo, int *hi, int *n, int depth)
{
    sim_prim_info in;
    if (w->csa[s->index] && depth < 8 && !sim_prim_describe(s, &in) && in.a && in.b) {
        terms(w, in.a, lo, hi, n, depth + 1);
        terms(w, in.b, lo, hi, n, depth + 1);
    } else if (*n < TERMS_MAX) {
        sim_live_span(s, &lo[*n], &hi[*n]);
        (*n)++;
    }
}

static int visit(walk *w, const sim_signal *s)
{
    uint32_t i = s->index;
    if (w->st[i] == 2) return 0;
    if (w->st[i] == 1) {
        char path[256];
        snprintf(w->err, w->errlen, "combinational loop through %s", sim_signal_path(s, path, sizeof path));
        return -1;
    }
    w->st[i] = 1;
    w->al[i] = w->am[i] = SIM_DELAY_NONE;
    w->pred[i] = -1;
    sim_prim_info in;
    const sim_delay zero = { 0, 0.0 };
    if (s->kind == SIM_KIND_CONST || s->kind == SIM_KIND_CLOCK) {
        /* no path starts at a tied value or at the clock (as data) */
    } else if (!s->driver || sim_prim_describe(s, &in)) {
        w->al[i] = w->am[i] = zero;     /* an input, or a process whose timing is its own */
    } else if (in.kind == SIM_KIND_REG) {
        w->al[i] = w->am[i] = sim_arcs_of(s).mm;   /* clock-to-q */
    } else {
        const sim_signal **r = malloc((size_t)(10 + (in.n > 0 ? in.n : 0)) * sizeof *r);
        if (!r) { snprintf(w->err, w->errlen, "out of memory"); return -1; }
        int nr = sim_prim_reads(&in, r);
        sim_arcs a = w->csa[i] ? sim_delay_csa() : sim_prim_arcs(s, w->carry);
        if (!w->csa[i] && is_addsub(in.kind) && !in.qlogic && ((in.a && w->csa[in.a->index]) || (in.b && w->csa[in.b->index]))) {
            /* the last adder of a multi-operand chain: its carry runs over
             * all the chain's bits (sim_live_adder) */
            int chain, ext, low, lo[TERMS_MAX], hi[TERMS_MAX], n = 0;
            terms(w, in.a, lo, hi, &n, 0);
            terms(w, in.b, lo, hi, &n, 0);
            sim_live_chain(lo, hi, n, s->fmt, &chain, &ext, &low);
            a = in.kind == SIM_KIND_SUB ? sim_delay_sub_span(chain, ext, low, w->carry) : sim_delay_add_span(chain, ext, low, w->carry);
        }
        for (int k = 0; k < nr; k++) {
            if (visit(w, r[k])) { free(r); return -1; }
            uint32_t j = r[k]->index;
            const sim_delay l[2] = { sim_delay_then(w->al[j], a.ll), sim_delay_then(w->am[j], a.ml) };
            const sim_delay m[2] = { sim_delay_then(w->al[j], a.lm), sim_delay_then(w->am[j], a.mm) };
            for (int e = 0; e < 2; e++) {
                if (later(l[e], w->al[i])) w->al[i] = l[e];
                if (later(m[e], w->am[i])) { w->am[i] = m[e]; w->pred[i] = (int32_t)j; }
            }
        }
        free(r);
    }
    if (w->al[i].lv >= 0) w->al[i].ps += w->load[i];
    if (w->am[i].lv >= 0) w->am[i].ps += w->load[i];
    w->st[i] = 2;
    return 0;
}

/* Pins one bit of each signal drives: a select, enable, reset or key bit
 * one per bit of the element it steers (per bit of a multiplexer's first
 * level), a multiplier operand's bit one per live bit of the other, an
 * adder operand's two (its XOR and its carry gate), any other one; a
 * constant shift is wiring, so its pins are its source's. */
void sim_timing_pins(const sim_ctx *c, double *sel, double *oth, int *reads, int *adds)
{
    uint32_t n = sim_signal_count(c);
    for (uint32_t i = 0; i < n; i++) { sel[i] = oth[i] = 0; if (reads) reads[i] = adds[i] = 0; }
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *y = sim_signal_at(c, i);
        sim_prim_info in;
        if (!y->driver || sim_prim_describe(y, &in)) continue;
        const sim_signal *ops[3] = { in.a, in.b, in.c };
        if (reads) {
            for (int k = 0; k < 3; k++)
                if (ops[k]) { reads[ops[k]->index]++; adds[ops[k]->index] += is_addsub(in.kind) && k < 2; }
            if (in.rst) reads[in.rst->index]++;
            for (int k = 0; k < in.n; k++) reads[in.in[k]->index]++;
        }
        int w = y->fmt.width;
        if (in.c) sel[in.c->index] += in.kind == SIM_KIND_MUX ? w * ((in.n + 1) / 2) : w;
        if (in.rst) sel[in.rst->index] += w;
        if (in.kind == SIM_KIND_MUL) {
            oth[in.a->index] += sim_prim_live_bits(in.b);
            oth[in.b->index] += sim_prim_live_bits(in.a);
            continue;
        }
        double per = in.kind == SIM_KIND_ADD || in.kind == SIM_KIND_SUB ? 2 : 1;
        if (in.a) oth[in.a->index] += per;
        if (in.b) oth[in.b->index] += per;
        if (in.kind == SIM_KIND_MUX || in.kind == SIM_KIND_LOGIC)
            for (int k = 0; k < in.n; k++) oth[in.in[k]->index] += 1;
    }
    /* latest first: a shift of a shift passes its pins on down */
    for (uint32_t i = n; i-- > 0;) {
        const sim_signal *y = sim_signal_at(c, i);
        sim_prim_info in;
        if (y->kind != SIM_KIND_SHIFT || sim_prim_describe(y, &in) || !in.a) continue;
        sel[in.a->index] += sel[i]; oth[in.a->index] += oth[i];
        sel[i] = oth[i] = 0;
    }
}

/* Each signal's pins as picoseconds (sim_delay_load_ps) into load[]; csa[]
 * the adders merged into their one reader's multi-operand adder. */
static void loads(const sim_ctx *c, double *load, unsigned char *csa)
{
    uint32_t n = sim_signal_count(c);
    double *sel = calloc(n ? n : 1, sizeof *sel), *oth = calloc(n ? n : 1, sizeof *oth);
    int *reads = calloc(n ? n : 1, sizeof *reads), *adds = calloc(n ? n : 1, sizeof *adds);
    memset(csa, 0, n ? n : 1);
    if (!sel || !oth || !reads || !adds) {
        free(sel); free(oth); free(reads); free(adds);
        memset(load, 0, (n ? n : 1) * sizeof *load);
        return;
    }
    sim_timing_pins(c, sel, oth, reads, adds);
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *y = sim_signal_at(c, i);
        int driven = y->driver && y->kind != SIM_KIND_INPUT && y->kind != SIM_KIND_CONST;
        load[i] = driven ? sim_delay_load_ps(sel[i], oth[i], y->kind == SIM_KIND_REG) : 0.0;
        sim_prim_info in;
        if (is_addsub(y->kind) && reads[i] == 1 && adds[i] == 1 && !sim_prim_describe(y, &in) && !in.qlogic)
            csa[i] = 1;
    }
    free(sel); free(oth); free(reads); free(adds);
}

int sim_timing_analyze(const sim_ctx *c, sim_timing *out, char *err, size_t errlen)
{
    return sim_timing_analyze_carry(c, SIM_CARRY_RIPPLE, out, err, errlen);
}

int sim_timing_analyze_carry(const sim_ctx *c, sim_carry carry, sim_timing *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    uint32_t n = sim_signal_count(c);
    walk w = { c, carry, malloc((n ? n : 1) * sizeof(double)), malloc(n ? n : 1), malloc((n ? n : 1) * sizeof(sim_delay)), malloc((n ? n : 1) * sizeof(sim_delay)),
               malloc((n ? n : 1) * sizeof(int32_t)), calloc(n ? n : 1, 1), err, errlen };
    int32_t *chain = malloc((size_t)(n + 1) * sizeof *chain);
    int rc = -1;
    if (!w.load || !w.csa || !w.al || !w.am || !w.pred || !w.st || !chain) { snprintf(err, errlen, "out of memory"); goto done; }
    loads(c, w.load, w.csa);
    for (uint32_t i = 0; i < n; i++)
        if (visit(&w, sim_signal_at(c, i))) goto done;
    /* Endpoints: every signal as it is (a port no register captures ends
     * there), and every register's sampled inputs plus what they need. */
    sim_delay best = SIM_DELAY_NONE;
    int32_t best_src = -1, best_reg = -1;
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = sim_signal_at(c, i);
        if (later(w.am[i], best)) { best = w.am[i]; best_src = (int32_t)i; best_reg = -1; }
        sim_prim_info in;
        if (s->kind != SIM_KIND_REG || !s->driver || sim_prim_describe(s, &in) || in.kind != SIM_KIND_REG) continue;
        const sim_signal *src[3] = { in.a, in.c, in.rst };
        const sim_delay need[3] = { sim_delay_reg_d(in.c != NULL), sim_delay_reg_en(), sim_delay_reg_rst() };
        for (int k = 0; k < 3; k++) {
            if (!src[k]) continue;
            sim_delay t = sim_delay_then(w.am[src[k]->index], need[k]);
            if (later(t, best)) { best = t; best_src = (int32_t)src[k]->index; best_reg = (int32_t)i; }
        }
    }
    if (best_src >= 0) {
        int m = 0;
        if (best_reg >= 0) chain[m++] = best_reg;
        for (int32_t j = best_src; j >= 0 && m <= (int)n; j = w.pred[j]) chain[m++] = j;
        out->levels = best.lv;
        out->ps = best.ps;
        out->fmax_mhz = best.ps > 0 ? 1e6 / best.ps : 0;
        out->nfull = m;
        /* start first; a path too long keeps its beginning and its end */
        int keep = m < SIM_TIMING_PATH_MAX ? m : SIM_TIMING_PATH_MAX;
        for (int k = 0; k < keep - 1; k++) out->path[k] = sim_signal_at(c, (uint32_t)chain[m - 1 - k]);
        if (keep > 0) out->path[keep - 1] = sim_signal_at(c, (uint32_t)chain[0]);
        out->npath = keep;
    }
    rc = 0;
done:
    free(w.load); free(w.csa); free(w.al); free(w.am); free(w.pred); free(w.st); free(chain);
    return rc;
}
