/* unit_horner.c - the Horner datapath of Nechyporuk & Romanyuk (2020), Fig. 9, and its faster
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
#include "units/unit_net.h"
#include "vectors/ref_interp.h"
#include <stdio.h>
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

/* The paper's text (sec. IV): six clocks per pixel. Where the paper leaves
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

static int bits_for(int v) { int b = 1; while ((1 << b) <= v) b++; return b; }

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

/* The datapath of schedule p, written once and walked three ways
 * (unit_net.h): building (n->c set) it makes the hardware in n->sc, driven
 * by hw's controller, and stops after the first clock's walk; in a
 * fixed-rule walk it gives each signal it has its format; bounding, it
 * goes through every clock (paper, mac) or stage (pipe) of one pixel, each
 * value carrying its worst-case error. coef[0..deg] (A, B, ...) and t are
 * its inputs. Returns the result register's value; *done (building) the
 * signal that is 1 the clock before it holds a finished pixel.
 *
 * paper: per clock, MX1 picks A or RG into the multiplier, MX2 the product
 * or a coefficient into the adder, BK passes RG or forces 0, RG <= Sm.
 * mac: RG <= MX1 * t + MX2, MX1 in {A, RG}, MX2 in {B, C, D}: the adder
 * takes the product directly, so it never passes MX2, RG and BK.
 * pipe: stage j multiplies the previous stage's result (A for stage 1) by
 * t as it entered, and adds coefficient j; registers tJ and <coef>J carry
 * t and the coefficients still to come, so that a new pixel can enter
 * behind it in the next clock; vJ carries the valid bit. */
static unet_val h_walk(unet *n, const h_sched *p, const horner_hw *hw, sim_signal *run,
                       const unet_val *coef, unet_val t, sim_signal **done)
{
    int deg = p->deg;
    char nm[16];
#define S(name_) unet_sig(n, name_)
    if (p->sched != HORNER_PIPE) {
        int paper = p->sched == HORNER_PAPER;
        unet_val rg = unet_reg(n, S("rg"), "rg");
        for (int s = 0; s < p->nsteps; s++) {
            const h_step *st = &p->step[s];
            unet_val m1[2] = { coef[0], rg };
            unet_val mx1 = unet_mux(n, S("mx1"), "mx1", hw ? hw->mx1_sel : NULL, 2, m1, st->mx1);
            unet_val mul = unet_mul(n, S("mul"), "mul", mx1, t);
            unet_val sm;
            if (paper) {
                unet_val m2[4] = { mul, coef[1], coef[2], coef[3] };
                unet_val mx2 = unet_mux(n, S("mx2"), "mx2", hw ? hw->mx2_sel : NULL, deg + 1, m2, st->mx2);
                unet_val bk = unet_bk(n, S("bk"), "bk", hw ? hw->bk_pass : NULL, rg, st->bk);
                sm = unet_add(n, S("sm"), "sm", mx2, bk);
            } else {
                unet_val mx2 = unet_mux(n, S("mx2"), "mx2", hw ? hw->mx2_sel : NULL, deg, coef + 1, st->mx2 - 1);
                sm = unet_add(n, S("sm"), "sm", mul, mx2);
            }
            unet_reg_set(n, &rg, sm);
            if (n->c) break;        /* the hardware: built once */
        }
        if (done) *done = hw ? hw->last : NULL;
        return rg;
    }
    unet_val carry[4], acc = coef[0], tt = t;
    sim_signal *v = run;
    for (int k = 0; k <= deg; k++) carry[k] = coef[k];
    for (int j = 1; j <= p->nsteps; j++) {
        const h_step *st = &p->step[j - 1];
        unet_val x = st->mx1 == MX1_A ? coef[0] : acc;
        snprintf(nm, sizeof nm, "mul%d", j);
        unet_val mul = unet_mul(n, S(nm), nm, x, tt);
        snprintf(nm, sizeof nm, "sm%d", j);
        unet_val sm = unet_add(n, S(nm), nm, mul, carry[st->mx2]);
        snprintf(nm, sizeof nm, "rg%d", j);
        acc = unet_reg_of(n, S(nm), nm, sm);
        if (j == p->nsteps) break;
        snprintf(nm, sizeof nm, "t%d", j);
        tt = unet_reg_of(n, S(nm), nm, tt);
        for (int k = st->mx2 + 1; k <= deg; k++) {
            snprintf(nm, sizeof nm, "%c%d", "abcd"[k], j);
            carry[k] = unet_reg_of(n, S(nm), nm, carry[k]);
        }
        if (n->c) {
            snprintf(nm, sizeof nm, "v%d", j);
            v = sim_reg(n->c, n->sc, nm, unit_fmt(0, 1, 0), n->clk, v, NULL, NULL, 0);
        }
    }
#undef S
    if (done) *done = v;
    return acc;
}

/* The walk's inputs: coefficients of formats cf, and t, whose hardware
 * value lies in [0, 1] (a product's error grows by no more than its other
 * operand's). Signals when building. */
static void h_inputs(int deg, sim_signal *const *cs, const sim_fmt *cf, sim_signal *ts, sim_fmt tf,
                     unet_val *coef, unet_val *t)
{
    memset(coef, 0, 4 * sizeof *coef);
    for (int k = 0; k <= deg; k++) coef[k] = unet_wrap(cs ? cs[k] : NULL, cf[k], k);
    *t = unet_wrap(ts, tf, -1);
    t->mag = fmin(t->mag, 1.0);
    t->imag = fmin(t->imag, 1.0);
}

void horner_dp_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw, sim_signal *run,
                  sim_signal *const *coef, sim_signal *t, const unit_desc *u, const unit_fmts *f)
{
    unet n;
    unet_init(&n, u, f, SIM_RND_TRUNC);     /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    sim_fmt cf[4];
    for (int k = 0; k <= hw->deg; k++) cf[k] = coef[k]->fmt;
    unet_val co[4], tv;
    h_inputs(hw->deg, coef, cf, t, t->fmt, co, &tv);
    hw->rg = h_walk(&n, hw->s, hw, run, co, tv, &hw->done).s;
}

static int horner_build(const unit_desc *u, int deg, int sched, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                        const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
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

/* The fixed rule, from the walk of every schedule: each element the
 * datapath has s7.(W-7) (dp), a pipeline register its value's format
 * (the pipe's copies of t u1.(W-1), of the coefficients dp). */
void horner_default_fmts(const unit_desc *u, int deg, int width, unit_fmts *out)
{
    sim_fmt dp = unit_fmt(1, HORNER_IBITS, width - HORNER_IBITS), cf[4] = { dp, dp, dp, dp };
    for (int sched = 0; sched < HORNER_NSCHED; sched++) {
        unet n;
        unet_init(&n, u, out, SIM_RND_TRUNC);
        unet_fixed(&n, dp);
        unet_val co[4], t;
        h_inputs(deg, NULL, cf, NULL, unit_fmt(0, 1, width - 1), co, &t);
        h_walk(&n, sched_of(deg, sched), NULL, NULL, co, t, NULL);
        *out = n.fm;
    }
}

/* Integer bits of the datapath (HORNER_IBITS = 7): the coefficients of real intensity profiles
 * reach |A| <= 24, |B| <= 34, |C| <= 11 for node intensities in [0, 1]
 * (coefficient formulas (docs/units.md) at their extremes), and every partial sum of Horner's
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
    horner_default_fmts(u, deg, W, out);
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

/* The walk's error of RG after one pixel (docs/bounds.md): every element
 * that drops fraction bits adds its quantization error; multiplying by t
 * (|t| <= 1) does not grow an error; then RG seen through y's format. */
double horner_bound_on(int deg, int sched, const sim_fmt *coef_f, sim_fmt t, const unit_desc *u,
                       const unit_fmts *f, sim_fmt y_f, sim_round r)
{
    const h_sched *p = sched_of(deg, sched);
    if (!p) return INFINITY;
    unet n;
    unet_init(&n, u, f, r);
    unet_val co[4], tv;
    h_inputs(deg, NULL, coef_f, NULL, t, co, &tv);
    unet_val v = h_walk(&n, p, NULL, NULL, co, tv, NULL);
    return v.err + unit_qerr(y_f, v.eff, r);
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
    { return horner_build(&unit_horner##sfx, deg, cfg->schedule, c, sc, clk, f, io, err, errlen); }

HORNER_FNS(3, 3)
HORNER_FNS(2, 2)

const unit_desc unit_horner3 = {
    .name = "horner3",
    .ref = &ref_model_horner3,
    .summary = "cubic I = ((A t + B) t + C) t + D on the Fig. 9 datapath (RG, MX1, MX2, BK, Sm, MUL)",
    .source = "Nechyporuk & Romanyuk (2020), Fig. 9",
    UNIT_SIGS(
        { .name = "a", .role = UNIT_SIG_IN, .what = "coefficient A" }, { .name = "b", .role = UNIT_SIG_IN, .what = "coefficient B" },
        { .name = "c", .role = UNIT_SIG_IN, .what = "coefficient C" }, { .name = "d", .role = UNIT_SIG_IN, .what = "coefficient D" },
        { .name = "t", .role = UNIT_SIG_IN, .what = "position in the interval, k/L" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "intensity I(t) (RG after the last step)" },
        HORNER_SIGS3),
    .nsched = 3,
    .sched = H_SCHEDS("the paper's sequence, six clocks per pixel", "3", "3"),
    .nparams = 0,
    .fmt_rule = H_RULE,
    .formats = formats3, .beats = beats1, .build = build3, .ideal = ideal3, .bound = bound3, .ideal_exact = ideal3_exact,
};

const unit_desc unit_horner2 = {
    .name = "horner2",
    .ref = &ref_model_horner2,
    .summary = "quadratic I = (A t + B) t + C on the same datapath, four clocks per pixel",
    .source = "Nechyporuk & Romanyuk (2020), Fig. 9 (degree 2)",
    UNIT_SIGS(
        { .name = "a", .role = UNIT_SIG_IN, .what = "coefficient A" }, { .name = "b", .role = UNIT_SIG_IN, .what = "coefficient B" },
        { .name = "c", .role = UNIT_SIG_IN, .what = "coefficient C" },
        { .name = "t", .role = UNIT_SIG_IN, .what = "position in the interval, k/L" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "intensity I(t)" },
        HORNER_SIGS2),
    .nsched = 3,
    .sched = H_SCHEDS("the paper's sequence cut to degree 2, four clocks per pixel", "2", "2"),
    .nparams = 0,
    .fmt_rule = H_RULE,
    .formats = formats2, .beats = beats1, .build = build2, .ideal = ideal2, .bound = bound2, .ideal_exact = ideal2_exact,
};
