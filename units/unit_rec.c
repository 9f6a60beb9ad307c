/* unit_rec.c - the restoring square root and reciprocal, one result bit a
 * step, built iterative or unrolled from one step (unit_rec.h).
 *
 * Every value of a step is an integer raw in an unsigned format uW.0 (the
 * subtractor's result signed): the wiring (4R + two bits, 4Q + 1, 2Q + bit)
 * are logic elements with their Verilog, the subtractor and the restore
 * multiplexer primitives. The restore multiplexer keeps T's format, as the
 * divider's (unit_div.c): its select arrives a delta after its data, and a
 * register quantizes the settled value. */
#include "units/unit_rec.h"
#include "units/units_brdf.h"
#include "sim/sim_area.h"
#include <stdio.h>
#include <string.h>

static sim_fmt uint_fmt(int w) { return unit_fmt(0, w, 0); }
static uint64_t mask_of(int w) { return w >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << w) - 1; }

/* Width of the radicand's register X at the start: x's raw, one zero bit
 * above it and, for an odd F_x, one below, so that X's top bit is N's and
 * X is taken two bits a step. */
static int x_width0(const rec_spec *s) { return s->f_in + 2 + (s->f_in & 1); }

int rec_steps(const rec_spec *s) { return s->kind == REC_SQRT ? s->f_q + 1 : s->f_q + 2 + s->e; }

sim_fmt rec_out_fmt(const rec_spec *s) { return unit_fmt(0, s->kind == REC_SQRT ? 1 : 2 + s->e, s->f_q); }

int rec_check(const rec_spec *s, char *err, size_t errlen)
{
    int K = rec_steps(s);
    if (s->kind == REC_SQRT && (2 * s->f_q < s->f_in + (s->f_in & 1) || x_width0(s) > 62 || K + 5 > 62)) {
        snprintf(err, errlen, "square root: %d result fraction bits for a radicand of %d (need at least half, "
                 "and at most 57)", s->f_q, s->f_in);
        return -1;
    }
    if (s->kind == REC_RECIP && (s->e < 0 || s->f_in < 2 + s->e || s->f_in + 4 > 62 || K > 62)) {
        snprintf(err, errlen, "reciprocal: divisor of %d fraction bits above 2^-%d (need %d to 58, "
                 "and at most 62 steps)", s->f_in, s->e, 2 + s->e);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ the logic */

/* Widths a logic element needs: its inputs' and output's. */
typedef struct rec_w { int a, b, y; } rec_w;

/* sqrt: R2 = 4 R + the top two bits of X (X absent: zeros) */
static int64_t f_r2_sqrt(const int64_t *in, void *u)
{
    const rec_w *w = u;
    uint64_t r = (uint64_t)in[0] << 2;
    if (w->b >= 2) r |= ((uint64_t)in[1] >> (w->b - 2)) & 3;
    return (int64_t)(r & mask_of(w->y));
}
/* recip: R2 = 2 R */
static int64_t f_r2_recip(const int64_t *in, void *u)
{
    const rec_w *w = u;
    return (int64_t)(((uint64_t)in[0] << 1) & mask_of(w->y));
}
/* sqrt: 4 Q + 1 */
static int64_t f_dq(const int64_t *in, void *u)
{
    const rec_w *w = u;
    return (int64_t)((((uint64_t)in[0] << 2) | 1) & mask_of(w->y));
}
static int64_t f_sel(const int64_t *in, void *u) { (void)u; return in[0] >= 0; }
/* Q' = 2 Q + bit, kept to Q''s width */
static int64_t f_qn(const int64_t *in, void *u)
{
    const rec_w *w = u;
    return (int64_t)((((uint64_t)in[0] << 1) | (uint64_t)in[1]) & mask_of(w->y));
}
/* X': the bits after the top two, top-aligned: shifted up (same width,
 * iterative) or the low bits (two fewer, unrolled) */
static int64_t f_xn(const int64_t *in, void *u)
{
    const rec_w *w = u;
    uint64_t x = (uint64_t)in[0];
    return (int64_t)(w->y == w->a ? (x << 2) & mask_of(w->y) : x & mask_of(w->y));
}

static rec_w *widths(sim_ctx *c, int a, int b, int y)
{
    rec_w *w = sim_alloc(c, sizeof *w);
    w->a = a; w->b = b; w->y = y;
    return w;
}

static void name3(char *buf, size_t len, const char *prefix, int k, const char *what)
{
    if (k >= 0) snprintf(buf, len, "%s%d_%s", prefix, k, what);
    else snprintf(buf, len, "%s%s", prefix, what);
}

/* One step's state: registers' values going in. */
typedef struct rec_st { sim_signal *r, *q, *x, *d; } rec_st;

/* One step from st, its elements named by (prefix, k); the next state's
 * widths wr, wq, wx (0: no X) are the caller's. Returns the next state's
 * values before their registers (r: T's format). */
static rec_st rec_step(sim_ctx *c, sim_scope *sc, const char *prefix, int k, const rec_spec *s,
                       rec_st st, int wq_n, int wx_n)
{
    char nm[48], vt[160];
    int wr = st.r->fmt.width, wq = st.q->fmt.width, wx = st.x ? st.x->fmt.width : 0;
    sim_signal *r2, *sub;
    if (s->kind == REC_SQRT) {
        sim_signal *in2[2] = { st.r, st.x };
        rec_w *w = widths(c, wr, wx, wr + 2);
        name3(nm, sizeof nm, prefix, k, "r2");
        r2 = sim_logic(c, sc, nm, uint_fmt(wr + 2), st.x ? 2 : 1, in2, f_r2_sqrt, w, 0);
        if (st.x) snprintf(vt, sizeof vt, "assign %%y = {%%0, %%1[%d:%d]};", wx - 1, wx - 2);
        else snprintf(vt, sizeof vt, "assign %%y = {%%0, 2'b00};");
        sim_logic_verilog(r2, vt);
        sim_logic_depth(r2, 0);     /* 4R and X's top two bits: wiring */
        name3(nm, sizeof nm, prefix, k, "dq");
        sub = sim_logic(c, sc, nm, uint_fmt(wq + 2), 1, &st.q, f_dq, widths(c, wq, 0, wq + 2), 0);
        sim_logic_verilog(sub, "assign %y = {%0, 2'b01};");
        sim_logic_depth(sub, 0);
    } else {
        name3(nm, sizeof nm, prefix, k, "r2");
        r2 = sim_logic(c, sc, nm, uint_fmt(wr + 1), 1, &st.r, f_r2_recip, widths(c, wr, 0, wr + 1), 0);
        sim_logic_verilog(r2, "assign %y = {%0, 1'b0};");
        sim_logic_depth(r2, 0);
        sub = st.d;
    }
    int wt = (r2->fmt.width > sub->fmt.width ? r2->fmt.width : sub->fmt.width) + 1;
    name3(nm, sizeof nm, prefix, k, "t");
    sim_signal *t = sim_sub(c, sc, nm, unit_fmt(1, wt, 0), r2, sub);
    name3(nm, sizeof nm, prefix, k, "bit");
    sim_signal *sel = sim_logic(c, sc, nm, uint_fmt(1), 1, &t, f_sel, NULL, SIM_GE_INV);
    snprintf(vt, sizeof vt, "assign %%y = ~%%0[%d];", wt - 1);
    sim_logic_verilog(sel, vt);
    sim_logic_depth(sel, 1);        /* an inverter of the trial's sign */
    rec_st o = st;
    sim_signal *rs[2] = { r2, t };
    name3(nm, sizeof nm, prefix, k, "rn");
    o.r = sim_mux(c, sc, nm, t->fmt, sel, 2, rs);
    sim_signal *qs[2] = { st.q, sel };
    name3(nm, sizeof nm, prefix, k, "qn");
    o.q = sim_logic(c, sc, nm, uint_fmt(wq_n), 2, qs, f_qn, widths(c, wq, 1, wq_n), 0);
    if (wq_n == wq + 1) snprintf(vt, sizeof vt, "assign %%y = {%%0, %%1};");
    else if (wq >= 2) snprintf(vt, sizeof vt, "assign %%y = {%%0[%d:0], %%1};", wq - 2);
    else snprintf(vt, sizeof vt, "assign %%y = %%1;");
    sim_logic_verilog(o.q, vt);
    sim_logic_depth(o.q, 0);        /* Q shifted left, the new bit in: wiring */
    o.x = NULL;
    if (st.x && wx_n > 0) {
        name3(nm, sizeof nm, prefix, k, "xn");
        o.x = sim_logic(c, sc, nm, uint_fmt(wx_n), 1, &st.x, f_xn, widths(c, wx, 0, wx_n), 0);
        if (wx_n == wx) snprintf(vt, sizeof vt, "assign %%y = {%%0[%d:0], 2'b00};", wx - 3);
        else snprintf(vt, sizeof vt, "assign %%y = %%0[%d:0];", wx_n - 1);
        sim_logic_verilog(o.x, vt);
        sim_logic_depth(o.x, 0);
    }
    return o;
}

/* The divisor 1 (raw 2^F_d) in place of 0: an empty slot of a pipeline
 * (registers start at 0) or a zero vector divides by 1 instead of letting
 * R double every step until it overflows. */
static int64_t f_d_raw(const int64_t *in, void *u)
{
    return in[0] ? in[0] : (int64_t)1 << *(const int *)u;
}

/* The operand as an integer raw: the radicand's X (x_raw shifted up by
 * one for an odd F_x: wiring) or the divisor's d_raw (d, or 1 for 0). */
static sim_signal *operand_raw(sim_ctx *c, sim_scope *sc, const char *name, const rec_spec *s, sim_signal *in)
{
    if (s->kind == REC_SQRT) return sim_shift(c, sc, name, uint_fmt(x_width0(s)), in, s->f_in + (s->f_in & 1));
    int *fd = sim_alloc(c, sizeof *fd), w = s->f_in + 1;
    *fd = s->f_in;
    sim_signal *d = sim_logic(c, sc, name, uint_fmt(w), 1, &in, f_d_raw, fd, w * SIM_GE_NAND2 / 2 + w * SIM_GE_MUX2);
    char vt[160];
    snprintf(vt, sizeof vt, "assign %%y = (%%0 == %d'd0) ? %d'h%llx : %%0;", w, w, (unsigned long long)1 << s->f_in);
    sim_logic_verilog(d, vt);
    return d;
}

/* R's first value: 0 (root) or 2^(F_d - 2 - e) (reciprocal: N / 2^K). */
static int64_t r0_raw(const rec_spec *s) { return s->kind == REC_SQRT ? 0 : (int64_t)1 << (s->f_in - 2 - s->e); }

/* Width of R: the root's remainder is at most 2 Q, K + 1 bits at the end;
 * the reciprocal's stays below d < 2^(F_d + 1). */
static int r_width(const rec_spec *s, int step)
{
    return s->kind == REC_SQRT ? step + 1 : s->f_in + 1;
}

sim_signal *rec_iter(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *prefix,
                     const rec_spec *s, sim_signal *in, sim_signal *first, sim_signal *en)
{
    char nm[48];
    /* R: for a root held past its K steps (en 0), the next step's R2 =
     * 4R + 3 still forms at R's input; two more bits hold it, so that
     * the value the register does not take never overflows either */
    int K = rec_steps(s), wr = r_width(s, K) + (en && s->kind == REC_SQRT ? 2 : 0);
    int wx = s->kind == REC_SQRT ? x_width0(s) : 0;
    snprintf(nm, sizeof nm, "%sr", prefix);
    sim_signal *r = sim_reg(c, sc, nm, uint_fmt(wr), clk, NULL, en, NULL, 0);
    snprintf(nm, sizeof nm, "%sq", prefix);
    sim_signal *q = sim_reg(c, sc, nm, uint_fmt(K), clk, NULL, en, NULL, 0);
    snprintf(nm, sizeof nm, "%sr0", prefix);
    sim_signal *r0 = sim_const_raw(c, sc, nm, uint_fmt(wr), r0_raw(s));
    snprintf(nm, sizeof nm, "%sq0", prefix);
    sim_signal *q0 = sim_const_raw(c, sc, nm, uint_fmt(K), 0);
    sim_signal *rs[2] = { r, r0 }, *qs[2] = { q, q0 };
    rec_st st = { 0 };
    snprintf(nm, sizeof nm, "%sr_in", prefix);
    st.r = sim_mux(c, sc, nm, uint_fmt(wr), first, 2, rs);
    snprintf(nm, sizeof nm, "%sq_in", prefix);
    st.q = sim_mux(c, sc, nm, uint_fmt(K), first, 2, qs);
    sim_signal *x = NULL;
    if (s->kind == REC_SQRT) {
        snprintf(nm, sizeof nm, "%sx", prefix);
        x = sim_reg(c, sc, nm, uint_fmt(wx), clk, NULL, en, NULL, 0);
        snprintf(nm, sizeof nm, "%sx_load", prefix);
        sim_signal *xs[2] = { x, operand_raw(c, sc, nm, s, in) };
        snprintf(nm, sizeof nm, "%sx_in", prefix);
        st.x = sim_mux(c, sc, nm, uint_fmt(wx), first, 2, xs);
    } else {
        snprintf(nm, sizeof nm, "%sd_raw", prefix);
        st.d = operand_raw(c, sc, nm, s, in);
    }
    rec_st nx = rec_step(c, sc, prefix, -1, s, st, K, wx);
    sim_reg_connect(r, nx.r);
    sim_reg_connect(q, nx.q);
    if (x) sim_reg_connect(x, nx.x);
    return q;
}

sim_signal *rec_pipe(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *prefix,
                     const rec_spec *s, sim_signal *in)
{
    char nm[48];
    int K = rec_steps(s);
    rec_st st = { 0 };
    snprintf(nm, sizeof nm, "%s0_r", prefix);
    st.r = sim_const_raw(c, sc, nm, uint_fmt(r_width(s, 0)), r0_raw(s));
    snprintf(nm, sizeof nm, "%s0_q", prefix);
    st.q = sim_const_raw(c, sc, nm, uint_fmt(1), 0);
    snprintf(nm, sizeof nm, "%s0_%s", prefix, s->kind == REC_SQRT ? "x" : "d");
    if (s->kind == REC_SQRT) st.x = operand_raw(c, sc, nm, s, in);
    else st.d = operand_raw(c, sc, nm, s, in);
    for (int k = 0; k < K; k++) {
        int wq_n = k + 1, wx_n = st.x ? st.x->fmt.width - 2 : 0;
        rec_st nx = rec_step(c, sc, prefix, k, s, st, wq_n, wx_n);
        /* the stage's registers: R, Q, what is left of X, the divisor */
        snprintf(nm, sizeof nm, "%s%d_r", prefix, k + 1);
        st.r = sim_reg(c, sc, nm, uint_fmt(r_width(s, k + 1)), clk, nx.r, NULL, NULL, 0);
        snprintf(nm, sizeof nm, "%s%d_q", prefix, k + 1);
        st.q = sim_reg(c, sc, nm, uint_fmt(wq_n), clk, nx.q, NULL, NULL, 0);
        if (k == K - 1) break;
        if (nx.x) {
            snprintf(nm, sizeof nm, "%s%d_x", prefix, k + 1);
            st.x = sim_reg(c, sc, nm, nx.x->fmt, clk, nx.x, NULL, NULL, 0);
        } else {
            st.x = NULL;
        }
        if (st.d) {
            snprintf(nm, sizeof nm, "%s%d_d", prefix, k + 1);
            st.d = sim_reg(c, sc, nm, st.d->fmt, clk, st.d, NULL, NULL, (int64_t)1 << s->f_in);
        }
    }
    return st.q;
}

sim_signal *rec_delay(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *prefix,
                      sim_signal *v, int k)
{
    char nm[48];
    for (int j = 1; j <= k; j++) {
        snprintf(nm, sizeof nm, "%s%d", prefix, j);
        v = sim_reg(c, sc, nm, v->fmt, clk, v, NULL, NULL, 0);
    }
    return v;
}
