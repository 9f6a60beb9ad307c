/* unit_horner.c - the Horner datapath of seed 000, Fig. 9, and its faster
 * schedules (unit_horner.h; docs/schedules.md compares them).
 *
 * paper:  MUL = MX1 * t        MX1 in {A, RG}
 *         Sm  = MX2 + BK(RG)   MX2 in {MUL, B, C, D}, BK passes RG or forces 0
 *         RG <= Sm             every clock
 * mac:    RG <= MX1 * t + MX2  MX1 in {A, RG}, MX2 in {B, C, D}
 * pipe:   rgJ <= (A or rgJ-1) * t + coefficient J, one stage per J
 *
 * A schedule is a table (h_sched): for paper one control word a clock
 * (MX1 select, MX2 select, BK mode); for mac and pipe one multiply-add a
 * row, acc <= (A or acc) * t + coefficient k, which mac runs one a clock on
 * a single multiplier-adder and pipe unrolls into a stage each. A step
 * counter walks the sequential tables once per pixel; the bound walks the
 * same tables. horner3 and horner2 are the same datapaths with different
 * tables and coefficient counts, so one builder serves both.
 */
#include "units/unit_horner.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

enum { MX1_A = 0, MX1_RG = 1 };
enum { MX2_MUL = 0 };   /* paper: MX2 input k >= 1 is coefficient k (b, c, d) */

typedef struct h_step { uint8_t mx1, mx2, bk; } h_step;

struct h_sched {
    int deg;                /* polynomial degree: coefficients 0..deg */
    int sched;              /* HORNER_PAPER, _MAC or _PIPE: how the rows run */
    int nsteps;             /* rows: clocks per pixel (paper, mac), stages (pipe) */
    int step_bits;          /* width of the step counter (paper, mac) */
    h_step step[8];         /* mac, pipe: mx2 is the coefficient k, bk unused */
};

/* SPEC 2.3, the paper's text: six clocks per pixel. Where the paper leaves
 * MX1 free ("-") it selects RG. */
static const h_sched h3_paper = { 3, HORNER_PAPER, 6, 3, {
    { MX1_RG, 1,       0 },   /* RG <= B */
    { MX1_A,  MX2_MUL, 1 },   /* RG <= A t + B */
    { MX1_RG, MX2_MUL, 0 },   /* RG <= (A t + B) t */
    { MX1_RG, 2,       1 },   /* RG <= (A t + B) t + C */
    { MX1_RG, MX2_MUL, 0 },   /* RG <= ((A t + B) t + C) t */
    { MX1_RG, 3,       1 },   /* RG <= I */
} };

/* The same sequence for the quadratic: four clocks per pixel. Its step
 * counter is 3 bits wide like horner3's (2 bits would do for four steps):
 * horner2's paper schedule is horner3's controller cut short, and the area
 * docs/area.md gives for it counts the 3-bit counter. */
static const h_sched h2_paper = { 2, HORNER_PAPER, 4, 3, {
    { MX1_RG, 1,       0 },   /* RG <= B */
    { MX1_A,  MX2_MUL, 1 },   /* RG <= A t + B */
    { MX1_RG, MX2_MUL, 0 },   /* RG <= (A t + B) t */
    { MX1_RG, 2,       1 },   /* RG <= (A t + B) t + C */
} };

/* Horner's rule as multiply-adds, one a row. */
#define H3_MADD { { MX1_A, 1, 0 } /* A t + B */, { MX1_RG, 2, 0 } /* (.) t + C */, { MX1_RG, 3, 0 } /* (.) t + D */ }
#define H2_MADD { { MX1_A, 1, 0 } /* A t + B */, { MX1_RG, 2, 0 } /* (.) t + C */ }
static const h_sched h3_mac = { 3, HORNER_MAC, 3, 2, H3_MADD };
static const h_sched h2_mac = { 2, HORNER_MAC, 2, 1, H2_MADD };
static const h_sched h3_pipe = { 3, HORNER_PIPE, 3, 0, H3_MADD };
static const h_sched h2_pipe = { 2, HORNER_PIPE, 2, 0, H2_MADD };

static const h_sched *const by_deg[2][HORNER_NSCHED] = {
    { &h2_paper, &h2_mac, &h2_pipe }, { &h3_paper, &h3_mac, &h3_pipe } };

static const h_sched *sched_of(int deg, int sched)
{
    if ((deg != 2 && deg != 3) || sched < 0 || sched >= HORNER_NSCHED) return NULL;
    return by_deg[deg - 2][sched];
}

int horner_steps(int deg, int sched)
{
    const h_sched *p = sched_of(deg, sched);
    return !p ? -1 : p->sched == HORNER_PIPE ? 1 : p->nsteps;
}
int horner_latency(int deg, int sched)
{
    const h_sched *p = sched_of(deg, sched);
    return p ? p->nsteps : -1;
}

static int imax(int a, int b) { return a > b ? a : b; }
static int imin(int a, int b) { return a < b ? a : b; }
static int bits_for(int v) { int b = 1; while ((1 << b) <= v) b++; return b; }

/* Format of u's signal `name` in f (the builders and the bound take every
 * format by name: the pipe's signals are not contiguous). A name the unit
 * does not have is a bug here, not a reason for a default format. */
static sim_fmt fmt_of(const unit_desc *u, const unit_fmts *f, const char *name)
{
    return f->f[unit_sig_must(u, name)];
}

/* ------------------------------------------------------------- controller */

/* Next step: wrap after the last; wait at step 0 until told to run
 * (in[1]: horner3's in_valid); once started, a pixel runs to its end. */
static int64_t f_next(const int64_t *in, void *u)
{
    const h_sched *p = u;
    if (in[0] == 0 && !in[1]) return 0;
    return in[0] >= p->nsteps - 1 ? 0 : in[0] + 1;
}
static int64_t f_mx1(const int64_t *in, void *u) { return ((const h_sched *)u)->step[in[0]].mx1; }
/* paper: MX2's input is the table's; mac: its inputs are B, C, D only. */
static int64_t f_mx2(const int64_t *in, void *u)
{
    const h_sched *p = u;
    return p->step[in[0]].mx2 - (p->sched == HORNER_MAC);
}
static int64_t f_bk(const int64_t *in, void *u) { return ((const h_sched *)u)->step[in[0]].bk; }
static int64_t f_last(const int64_t *in, void *u) { return in[0] == ((const h_sched *)u)->nsteps - 1; }

/* A decoder output from the step: about two gates per step it decodes. */
static double decoder_ge(const h_sched *p) { return 2.0 * p->nsteps; }

int horner_ctl_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, int deg, int sched, sim_signal *run,
                  const char *last_name, horner_hw *hw)
{
    const h_sched *p = sched_of(deg, sched);
    if (!p) return -1;
    memset(hw, 0, sizeof *hw);
    hw->deg = deg;
    hw->sched = sched;
    hw->s = p;
    if (p->sched == HORNER_PIPE) {      /* a pixel enters every clock */
        hw->last = run;
        return 0;
    }
    int sb = p->step_bits, mb = bits_for(p->sched == HORNER_MAC ? deg - 1 : deg);
    sim_fmt u1 = unit_fmt(0, 1, 0), us = unit_fmt(0, sb, 0), um = unit_fmt(0, mb, 0);
    sim_signal *step = sim_reg(c, sc, "step", us, clk, NULL, NULL, NULL, 0);
    sim_signal *nx_in[2] = { step, run };
    /* an incrementer and the wrap/wait logic: a half adder and two gates a bit */
    sim_signal *nx = sim_logic(c, sc, "step_next", us, 2, nx_in, f_next, (void *)p, sb * SIM_GE_HA + 2 * sb);
    sim_reg_connect(step, nx);
    hw->mx1_sel = sim_logic(c, sc, "mx1_sel", u1, 1, &step, f_mx1, (void *)p, decoder_ge(p));
    hw->mx2_sel = sim_logic(c, sc, "mx2_sel", um, 1, &step, f_mx2, (void *)p, mb * decoder_ge(p));
    if (p->sched == HORNER_PAPER)
        hw->bk_pass = sim_logic(c, sc, "bk_pass", u1, 1, &step, f_bk, (void *)p, decoder_ge(p));
    hw->last = sim_logic(c, sc, last_name, u1, 1, &step, f_last, (void *)p, decoder_ge(p));
    return 0;
}

/* ---------------------------------------------------------------- datapath */

static void dp_paper(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw,
                     sim_signal *const *coef, sim_signal *t, const unit_desc *u, const unit_fmts *f)
{
    int deg = hw->deg;
    sim_signal *rg = sim_reg(c, sc, "rg", fmt_of(u, f, "rg"), clk, NULL, NULL, NULL, 0);
    sim_signal *mx1_in[2] = { coef[0], rg };
    sim_signal *mx1 = sim_mux(c, sc, "mx1", fmt_of(u, f, "mx1"), hw->mx1_sel, 2, mx1_in);
    sim_signal *mul = sim_mul(c, sc, "mul", fmt_of(u, f, "mul"), mx1, t);
    sim_signal *mx2_in[4] = { mul, coef[1], coef[2], deg >= 3 ? coef[3] : NULL };
    sim_signal *mx2 = sim_mux(c, sc, "mx2", fmt_of(u, f, "mx2"), hw->mx2_sel, deg + 1, mx2_in);
    sim_signal *bk = sim_bk(c, sc, "bk", fmt_of(u, f, "bk"), hw->bk_pass, rg);
    sim_signal *sm = sim_add(c, sc, "sm", fmt_of(u, f, "sm"), mx2, bk);
    sim_reg_connect(rg, sm);
    hw->rg = rg;
    hw->done = hw->last;
}

/* One multiply-add a clock: the adder takes the product directly, so the
 * product never passes through MX2, RG and BK as it does in paper. */
static void dp_mac(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw,
                   sim_signal *const *coef, sim_signal *t, const unit_desc *u, const unit_fmts *f)
{
    sim_signal *rg = sim_reg(c, sc, "rg", fmt_of(u, f, "rg"), clk, NULL, NULL, NULL, 0);
    sim_signal *mx1_in[2] = { coef[0], rg };
    sim_signal *mx1 = sim_mux(c, sc, "mx1", fmt_of(u, f, "mx1"), hw->mx1_sel, 2, mx1_in);
    sim_signal *mul = sim_mul(c, sc, "mul", fmt_of(u, f, "mul"), mx1, t);
    sim_signal *mx2 = sim_mux(c, sc, "mx2", fmt_of(u, f, "mx2"), hw->mx2_sel, hw->deg, coef + 1);
    sim_signal *sm = sim_add(c, sc, "sm", fmt_of(u, f, "sm"), mul, mx2);
    sim_reg_connect(rg, sm);
    hw->rg = rg;
    hw->done = hw->last;
}

/* Stage j (1-based) multiplies the previous stage's result (A for stage 1)
 * by t as it entered, and adds coefficient j; registers tJ and <coef>J
 * carry t and the coefficients still to come, so that a new pixel can
 * enter behind it in the next clock; vJ carries the valid bit. */
static void dp_pipe(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw, sim_signal *run,
                    sim_signal *const *coef, sim_signal *t, const unit_desc *u, const unit_fmts *f)
{
    const h_sched *p = hw->s;
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *carry[4], *acc = NULL, *tt = t, *v = run;
    for (int k = 0; k <= hw->deg; k++) carry[k] = coef[k];
    for (int j = 1; j <= p->nsteps; j++) {
        const h_step *st = &p->step[j - 1];
        char nm[16];
        sim_signal *x = st->mx1 == MX1_A ? coef[0] : acc;
        snprintf(nm, sizeof nm, "mul%d", j);
        sim_signal *mul = sim_mul(c, sc, nm, fmt_of(u, f, nm), x, tt);
        snprintf(nm, sizeof nm, "sm%d", j);
        sim_signal *sm = sim_add(c, sc, nm, fmt_of(u, f, nm), mul, carry[st->mx2]);
        snprintf(nm, sizeof nm, "rg%d", j);
        acc = sim_reg(c, sc, nm, fmt_of(u, f, nm), clk, sm, NULL, NULL, 0);
        if (j == p->nsteps) break;
        snprintf(nm, sizeof nm, "t%d", j);
        tt = sim_reg(c, sc, nm, fmt_of(u, f, nm), clk, tt, NULL, NULL, 0);
        for (int k = st->mx2 + 1; k <= hw->deg; k++) {
            snprintf(nm, sizeof nm, "%c%d", "abcd"[k], j);
            carry[k] = sim_reg(c, sc, nm, fmt_of(u, f, nm), clk, carry[k], NULL, NULL, 0);
        }
        snprintf(nm, sizeof nm, "v%d", j);
        v = sim_reg(c, sc, nm, u1, clk, v, NULL, NULL, 0);
    }
    hw->rg = acc;
    hw->done = v;
}

void horner_dp_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw, sim_signal *run,
                  sim_signal *const *coef, sim_signal *t, const unit_desc *u, const unit_fmts *f)
{
    if (hw->sched == HORNER_PAPER) dp_paper(c, sc, clk, hw, coef, t, u, f);
    else if (hw->sched == HORNER_MAC) dp_mac(c, sc, clk, hw, coef, t, u, f);
    else dp_pipe(c, sc, clk, hw, run, coef, t, u, f);
}

static int horner_build(const unit_desc *u, int sched, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                        const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    int deg = !strcmp(u->name, "horner3") ? 3 : 2;
    int nin = deg + 2;                          /* coefficients and t */
    for (int i = 0; i < nin; i++)
        io->in[i] = sim_signal_new(c, sc, u->sigs[i].name, f->f[i], SIM_KIND_INPUT);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    /* The inputs are held by the source for the whole item, so the
     * datapath reads them directly; the item ends with its last step
     * (pipe: the clock it enters, after which it travels on its own). */
    horner_hw hw;
    if (horner_ctl_on(c, sc, clk, deg, sched, io->in_valid, "in_ready", &hw)) {
        snprintf(err, errlen, "%s: no schedule %d", u->name, sched);
        return -1;
    }
    horner_dp_on(c, sc, clk, &hw, io->in_valid, io->in, io->in[nin - 1], u, f);
    io->in_ready = sched == HORNER_PIPE ? sim_const_raw(c, sc, "in_ready", unit_fmt(0, 1, 0), 1) : hw.last;
    /* y is the result seen through the output port's format. */
    io->out[0] = sim_shift(c, sc, "y", f->f[nin], hw.rg, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", unit_fmt(0, 1, 0), clk, hw.done, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}

/* ------------------------------------------------------------------ formats */

/* The datapath's signals and the copies of t (the pipe's t1, t2). */
static const char *const dp_names[] = { "mx1", "mul", "mx2", "bk", "sm", "rg", "mul1", "sm1", "rg1", "c1", "d1",
                                        "mul2", "sm2", "rg2", "d2", "mul3", "sm3", "rg3" };
static const char *const t_names[] = { "t1", "t2" };

void horner_default_fmts(const unit_desc *u, int width, unit_fmts *out)
{
    sim_fmt dp = unit_fmt(1, HORNER_IBITS, width - HORNER_IBITS);
    for (size_t k = 0; k < sizeof dp_names / sizeof dp_names[0]; k++) {
        int i = unit_sig_index(u, dp_names[k]);
        if (i >= 0) out->f[i] = dp;
    }
    for (size_t k = 0; k < sizeof t_names / sizeof t_names[0]; k++) {
        int i = unit_sig_index(u, t_names[k]);
        if (i >= 0) out->f[i] = unit_fmt(0, 1, width - 1);
    }
}

/* Integer bits of the datapath (HORNER_IBITS = 7): the coefficients of real intensity profiles
 * reach |A| <= 24, |B| <= 34, |C| <= 11 for node intensities in [0, 1]
 * (SPEC 2.1 formulas at their extremes), and every partial sum of Horner's
 * rule stays below |A| + |B| + |C| + |D| < 64 for t in [0, 1]. The same
 * holds for every schedule: they compute the same partial sums. */
static void horner_formats(const unit_desc *u, const unit_cfg *cfg, unit_fmts *out, int deg)
{
    int W = cfg->width;
    sim_fmt dp = unit_fmt(1, HORNER_IBITS, W - HORNER_IBITS);
    int nin = deg + 2;
    for (int i = 0; i < nin - 1; i++) out->f[i] = dp;      /* coefficients */
    out->f[nin - 1] = unit_fmt(0, 1, W - 1);                /* t in [0, 1] */
    out->f[nin] = dp;                                       /* y */
    horner_default_fmts(u, W, out);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* ------------------------------------------------------------ ideal, bound */

static void ideal3(const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    double t = in[4];
    out[0] = ((in[0] * t + in[1]) * t + in[2]) * t + in[3];
}
static void ideal2(const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    double t = in[3];
    out[0] = (in[0] * t + in[1]) * t + in[2];
}

/* The same polynomials exactly (the inputs are dyadic, so is y). */
static int horner_exact(int deg, const sim_dy *in, sim_dy *out)
{
    sim_dy y = in[0];
    for (int j = 1; j <= deg; j++) {
        sim_dy_mul(&y, &y, &in[deg + 1]);
        sim_dy_add(&y, &y, &in[j]);
    }
    *out = y;
    return y.ovf ? -1 : 0;
}
static int ideal3_exact(const unit_cfg *cfg, const sim_dy *in, sim_dy *out) { (void)cfg; return horner_exact(3, in, out); }
static int ideal2_exact(const unit_cfg *cfg, const sim_dy *in, sim_dy *out) { (void)cfg; return horner_exact(2, in, out); }

/* A value as the bound sees it: its format, worst-case error, and the
 * fraction bits it can really have (eff <= f.fbits: a wide register
 * holding a coarser value). Quantizations count only bits dropped below
 * eff, so that widening a signal moves a truncation downstream instead of
 * adding one: with trunc the bound never grows (unit_qerr's 2^-F - 2^-src
 * telescopes). */
typedef struct h_val { sim_fmt f; double e; int eff; } h_val;

/* Largest |value| a format holds. */
static double fmt_maxabs(sim_fmt f) { return ldexp(1.0, f.is_signed ? f.ibits - 1 : f.ibits); }

/* An exact input (coefficient, t) of format f. */
static h_val exact_of(sim_fmt f) { return (h_val){ f, 0, f.fbits }; }

/* v's exact value with src fraction bits (and error e) into format f. */
static h_val requant(sim_fmt f, double e, int src, sim_round r)
{
    return (h_val){ f, e + unit_qerr(f, src, r), imin(f.fbits, src) };
}

/* A value through a register or multiplexer of format f. */
static h_val pass(h_val v, sim_fmt f, sim_round r) { return requant(f, v.e, v.eff, r); }

/* One multiply-add acc = x * t + c through the multiplier, the adder and
 * the result register. x_hw t_hw - x t = (x_hw - x) t_hw + x_hw (t_hw - t)
 * with |t_hw| <= 1: x's error passes unchanged, t's is scaled by |x_hw|,
 * which its format bounds (t's error is 0 unless a pipe register of t is
 * narrower than t). */
static h_val madd(h_val x, h_val t, h_val c, sim_fmt fmul, sim_fmt fsm, sim_fmt frg, sim_round r)
{
    h_val mul = requant(fmul, x.e + (t.e > 0 ? fmt_maxabs(x.f) * t.e : 0), x.eff + t.eff, r);
    h_val sm = requant(fsm, mul.e + c.e, imax(mul.eff, c.eff), r);
    return pass(sm, frg, r);
}

/* Walk the paper table accumulating the worst-case error of RG
 * (docs/bounds.md): every element that drops fraction bits adds its
 * quantization error; multiplying by t (|t| <= 1) does not grow an error. */
static h_val bound_paper(const h_sched *p, const sim_fmt *coef_f, sim_fmt t, const unit_desc *u,
                         const unit_fmts *f, sim_round r)
{
    sim_fmt fmx1 = fmt_of(u, f, "mx1"), fmul = fmt_of(u, f, "mul"), fmx2 = fmt_of(u, f, "mx2"),
            fbk = fmt_of(u, f, "bk"), fsm = fmt_of(u, f, "sm"), frg = fmt_of(u, f, "rg");
    h_val rg = { frg, 0, 0 };       /* RG starts at 0 */
    for (int s = 0; s < p->nsteps; s++) {
        const h_step *st = &p->step[s];
        h_val mx2, bk = { fbk, 0, -64 };   /* forced zero: exact, no fraction bits */
        if (st->mx2 == MX2_MUL) {
            h_val mx1 = pass(st->mx1 == MX1_A ? exact_of(coef_f[0]) : rg, fmx1, r);
            h_val mul = requant(fmul, mx1.e, mx1.eff + t.fbits, r);
            mx2 = pass(mul, fmx2, r);
        } else {
            mx2 = pass(exact_of(coef_f[st->mx2]), fmx2, r);
        }
        if (st->bk) bk = pass(rg, fbk, r);
        h_val sm = requant(fsm, mx2.e + bk.e, imax(mx2.eff, bk.eff), r);
        rg = pass(sm, frg, r);
    }
    return rg;
}

/* mac: each row's operands pass MX1 (A or RG) and MX2 (a coefficient). */
static h_val bound_mac(const h_sched *p, const sim_fmt *coef_f, sim_fmt t, const unit_desc *u,
                       const unit_fmts *f, sim_round r)
{
    sim_fmt fmx1 = fmt_of(u, f, "mx1"), fmx2 = fmt_of(u, f, "mx2");
    h_val acc = { fmt_of(u, f, "rg"), 0, 0 };
    for (int s = 0; s < p->nsteps; s++) {
        const h_step *st = &p->step[s];
        h_val x = pass(st->mx1 == MX1_A ? exact_of(coef_f[0]) : acc, fmx1, r);
        h_val c = pass(exact_of(coef_f[st->mx2]), fmx2, r);
        acc = madd(x, exact_of(t), c, fmt_of(u, f, "mul"), fmt_of(u, f, "sm"), fmt_of(u, f, "rg"), r);
    }
    return acc;
}

/* pipe: row j is stage j+1; t and the coefficients still to come pass a
 * pipeline register per stage (lossless in the default rule). */
static h_val bound_pipe(const h_sched *p, const sim_fmt *coef_f, sim_fmt t_f, const unit_desc *u,
                        const unit_fmts *f, sim_round r)
{
    h_val carry[4], acc = exact_of(coef_f[0]), t = exact_of(t_f);
    for (int k = 0; k <= p->deg; k++) carry[k] = exact_of(coef_f[k]);
    for (int j = 1; j <= p->nsteps; j++) {
        const h_step *st = &p->step[j - 1];
        char m[16], s[16], g[16];
        snprintf(m, sizeof m, "mul%d", j);
        snprintf(s, sizeof s, "sm%d", j);
        snprintf(g, sizeof g, "rg%d", j);
        h_val x = st->mx1 == MX1_A ? exact_of(coef_f[0]) : acc;
        acc = madd(x, t, carry[st->mx2], fmt_of(u, f, m), fmt_of(u, f, s), fmt_of(u, f, g), r);
        if (j == p->nsteps) break;
        snprintf(m, sizeof m, "t%d", j);
        t = pass(t, fmt_of(u, f, m), r);
        for (int k = st->mx2 + 1; k <= p->deg; k++) {
            snprintf(m, sizeof m, "%c%d", "abcd"[k], j);
            carry[k] = pass(carry[k], fmt_of(u, f, m), r);
        }
    }
    return acc;
}

double horner_bound_on(int deg, int sched, const sim_fmt *coef_f, sim_fmt t, const unit_desc *u,
                       const unit_fmts *f, sim_fmt y_f, sim_round r)
{
    const h_sched *p = sched_of(deg, sched);
    if (!p) return INFINITY;
    h_val v = p->sched == HORNER_PAPER ? bound_paper(p, coef_f, t, u, f, r)
            : p->sched == HORNER_MAC   ? bound_mac(p, coef_f, t, u, f, r)
                                       : bound_pipe(p, coef_f, t, u, f, r);
    return v.e + unit_qerr(y_f, v.eff, r);
}

static void horner_bound(const unit_desc *u, int deg, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    int nin = deg + 2;
    per_out[0] = horner_bound_on(deg, cfg->schedule, f->f, f->f[nin - 1], u, f, f->f[nin], cfg->rnd);
}

/* -------------------------------------------------------------- descriptors */

#define H_RULE "coefficients, y and every datapath signal s7.(W-7) (|partial sums| < 64); t and its pipe copies u1.(W-1)"
#define H_SCHEDS(paper_what, steps, deg) \
    { { "paper", paper_what }, \
      { "mac", "one multiply-add a clock, RG <= MX1 * t + MX2 (no BK): " steps " clocks per pixel" }, \
      { "pipe", "fully pipelined: " deg " multiply-add stages, a pixel per clock, result " deg " clocks after it entered" } }

extern const unit_desc unit_horner3, unit_horner2;

#define HORNER_FNS(sfx, deg) \
    static void formats##sfx(const unit_cfg *cfg, unit_fmts *out) { horner_formats(&unit_horner##sfx, cfg, out, deg); } \
    static void bound##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { horner_bound(&unit_horner##sfx, deg, cfg, f, o); } \
    static int build##sfx(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, \
                          const unit_fmts *f, unit_io *io, char *err, size_t errlen) \
    { return horner_build(&unit_horner##sfx, cfg->schedule, c, sc, clk, f, io, err, errlen); }

HORNER_FNS(3, 3)
HORNER_FNS(2, 2)

const unit_desc unit_horner3 = {
    .name = "horner3",
    .summary = "cubic I = ((A t + B) t + C) t + D on the Fig. 9 datapath (RG, MX1, MX2, BK, Sm, MUL)",
    .seed = "Nechyporuk & Romanyuk (2020), Fig. 9",
    .nsigs = 6 + HORNER_NSIGS3,
    .sigs = {
        { .name = "a", .role = UNIT_SIG_IN, .what = "coefficient A" }, { .name = "b", .role = UNIT_SIG_IN, .what = "coefficient B" },
        { .name = "c", .role = UNIT_SIG_IN, .what = "coefficient C" }, { .name = "d", .role = UNIT_SIG_IN, .what = "coefficient D" },
        { .name = "t", .role = UNIT_SIG_IN, .what = "position in the interval, k/L" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "intensity I(t) (RG after the last step)" },
        HORNER_SIGS3 },
    .nsched = 3,
    .sched = H_SCHEDS("the paper's sequence, six clocks per pixel", "3", "3"),
    .nparams = 0,
    .fmt_rule = H_RULE,
    .formats = formats3, .beats = beats1, .build = build3, .ideal = ideal3, .bound = bound3, .ideal_exact = ideal3_exact,
};

const unit_desc unit_horner2 = {
    .name = "horner2",
    .summary = "quadratic I = (A t + B) t + C on the same datapath, four clocks per pixel",
    .seed = "Nechyporuk & Romanyuk (2020), Fig. 9 (degree 2)",
    .nsigs = 5 + HORNER_NSIGS2,
    .sigs = {
        { .name = "a", .role = UNIT_SIG_IN, .what = "coefficient A" }, { .name = "b", .role = UNIT_SIG_IN, .what = "coefficient B" },
        { .name = "c", .role = UNIT_SIG_IN, .what = "coefficient C" },
        { .name = "t", .role = UNIT_SIG_IN, .what = "position in the interval, k/L" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "intensity I(t)" },
        HORNER_SIGS2 },
    .nsched = 3,
    .sched = H_SCHEDS("the paper's sequence cut to degree 2, four clocks per pixel", "2", "2"),
    .nparams = 0,
    .fmt_rule = H_RULE,
    .formats = formats2, .beats = beats1, .build = build2, .ideal = ideal2, .bound = bound2, .ideal_exact = ideal2_exact,
};
