/* unit_horner.c - the Horner datapath of seed 000, Fig. 9.
 *
 *   MUL = MX1 * t        MX1 in {A, RG}
 *   Sm  = MX2 + BK(RG)   MX2 in {MUL, B, C, D}, BK passes RG or forces 0
 *   RG <= Sm             every clock
 *
 * A schedule is a table of control words, one per clock (MX1 select, MX2
 * select, BK mode); a step counter walks it once per pixel. horner3 and
 * horner2 are the same datapath with different tables and coefficient
 * counts, so one builder serves both.
 */
#include "units/unit_horner.h"
#include "sim/sim_area.h"
#include <stddef.h>
#include <string.h>

enum { MX1_A = 0, MX1_RG = 1 };
enum { MX2_MUL = 0 };   /* MX2 input k >= 1 is coefficient k (b, c, d) */

typedef struct h_step { uint8_t mx1, mx2, bk; } h_step;

typedef struct h_prog {
    int deg;                /* polynomial degree: coefficients 0..deg */
    int nsteps;
    h_step step[8];
} h_prog;

/* SPEC 2.3, the paper's text: six clocks per pixel. Where the paper leaves
 * MX1 free ("-") it selects RG. */
static const h_prog h3_paper = { 3, 6, {
    { MX1_RG, 1,       0 },   /* RG <= B */
    { MX1_A,  MX2_MUL, 1 },   /* RG <= A t + B */
    { MX1_RG, MX2_MUL, 0 },   /* RG <= (A t + B) t */
    { MX1_RG, 2,       1 },   /* RG <= (A t + B) t + C */
    { MX1_RG, MX2_MUL, 0 },   /* RG <= ((A t + B) t + C) t */
    { MX1_RG, 3,       1 },   /* RG <= I */
} };

/* The same sequence for the quadratic: four clocks per pixel. */
static const h_prog h2_paper = { 2, 4, {
    { MX1_RG, 1,       0 },   /* RG <= B */
    { MX1_A,  MX2_MUL, 1 },   /* RG <= A t + B */
    { MX1_RG, MX2_MUL, 0 },   /* RG <= (A t + B) t */
    { MX1_RG, 2,       1 },   /* RG <= (A t + B) t + C */
} };

static const h_prog *prog_of(const unit_desc *u) { return !strcmp(u->name, "horner3") ? &h3_paper : &h2_paper; }

/* ------------------------------------------------------------- controller */

/* Next step: wrap after the last; wait at step 0 until told to run
 * (in[1]: horner3's in_valid); once started, a pixel runs to its end. */
static int64_t f_next(const int64_t *in, void *u)
{
    const h_prog *p = u;
    if (in[0] == 0 && !in[1]) return 0;
    return in[0] >= p->nsteps - 1 ? 0 : in[0] + 1;
}
static int64_t f_mx1(const int64_t *in, void *u) { return ((const h_prog *)u)->step[in[0]].mx1; }
static int64_t f_mx2(const int64_t *in, void *u) { return ((const h_prog *)u)->step[in[0]].mx2; }
static int64_t f_bk(const int64_t *in, void *u) { return ((const h_prog *)u)->step[in[0]].bk; }
static int64_t f_last(const int64_t *in, void *u) { return in[0] == ((const h_prog *)u)->nsteps - 1; }

/* A decoder output from a 3-bit step: about two gates per step it decodes. */
static double decoder_ge(const h_prog *p) { return 2.0 * p->nsteps; }

int horner_steps(int deg) { return deg == 3 ? h3_paper.nsteps : h2_paper.nsteps; }

static const h_prog *prog_deg(int deg) { return deg == 3 ? &h3_paper : deg == 2 ? &h2_paper : NULL; }

int horner_ctl_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, int deg, sim_signal *run,
                  const char *last_name, horner_hw *hw)
{
    const h_prog *p = prog_deg(deg);
    if (!p) return -1;
    sim_fmt u1 = unit_fmt(0, 1, 0), u2 = unit_fmt(0, 2, 0), u3 = unit_fmt(0, 3, 0);
    hw->deg = deg;
    sim_signal *step = sim_reg(c, sc, "step", u3, clk, NULL, NULL, NULL, 0);
    sim_signal *nx_in[2] = { step, run };
    sim_signal *nx = sim_logic(c, sc, "step_next", u3, 2, nx_in, f_next, (void *)p, 3 * SIM_GE_HA + 6);
    sim_reg_connect(step, nx);
    hw->mx1_sel = sim_logic(c, sc, "mx1_sel", u1, 1, &step, f_mx1, (void *)p, decoder_ge(p));
    hw->mx2_sel = sim_logic(c, sc, "mx2_sel", u2, 1, &step, f_mx2, (void *)p, 2 * decoder_ge(p));
    hw->bk_pass = sim_logic(c, sc, "bk_pass", u1, 1, &step, f_bk, (void *)p, decoder_ge(p));
    hw->last = sim_logic(c, sc, last_name, u1, 1, &step, f_last, (void *)p, decoder_ge(p));
    return 0;
}

void horner_dp_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw,
                  sim_signal *const *coef, sim_signal *t, const sim_fmt *fi)
{
    int deg = hw->deg;
    sim_signal *rg = sim_reg(c, sc, "rg", fi[HORNER_RG], clk, NULL, NULL, NULL, 0);
    sim_signal *mx1_in[2] = { coef[0], rg };
    sim_signal *mx1 = sim_mux(c, sc, "mx1", fi[HORNER_MX1], hw->mx1_sel, 2, mx1_in);
    sim_signal *mul = sim_mul(c, sc, "mul", fi[HORNER_MUL], mx1, t);
    sim_signal *mx2_in[4] = { mul, coef[1], coef[2], deg >= 3 ? coef[3] : NULL };
    sim_signal *mx2 = sim_mux(c, sc, "mx2", fi[HORNER_MX2], hw->mx2_sel, deg + 1, mx2_in);
    sim_signal *bk = sim_bk(c, sc, "bk", fi[HORNER_BK], hw->bk_pass, rg);
    sim_signal *sm = sim_add(c, sc, "sm", fi[HORNER_SM], mx2, bk);
    sim_reg_connect(rg, sm);
    hw->rg = rg;
}

static int horner_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                        const unit_fmts *f, unit_io *io)
{
    const h_prog *p = prog_of(u);
    int nin = p->deg + 2;                       /* coefficients and t */
    for (int i = 0; i < nin; i++)
        io->in[i] = sim_signal_new(c, sc, u->sigs[i].name, f->f[i], SIM_KIND_INPUT);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    /* The inputs are held by the source for the whole item, so the
     * datapath reads them directly; the item ends with its last step. */
    horner_hw hw;
    horner_ctl_on(c, sc, clk, p->deg, io->in_valid, "in_ready", &hw);
    horner_dp_on(c, sc, clk, &hw, io->in, io->in[nin - 1], &f->f[nin + 1]);
    io->in_ready = hw.last;
    /* y is RG's output seen through the output port's format. */
    io->out[0] = sim_shift(c, sc, "y", f->f[nin], hw.rg, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", unit_fmt(0, 1, 0), clk, io->in_ready, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}

static int build3(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen);
static int build2(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen);

/* ------------------------------------------------------------------ formats */

/* Integer bits of the datapath (HORNER_IBITS = 7): the coefficients of real intensity profiles
 * reach |A| <= 24, |B| <= 34, |C| <= 11 for node intensities in [0, 1]
 * (SPEC 2.1 formulas at their extremes), and every partial sum of Horner's
 * rule stays below |A| + |B| + |C| + |D| < 64 for t in [0, 1]. */
static void horner_formats(const unit_cfg *cfg, unit_fmts *out, int deg)
{
    int W = cfg->width;
    sim_fmt dp = unit_fmt(1, HORNER_IBITS, W - HORNER_IBITS);
    int nin = deg + 2;
    for (int i = 0; i < nin - 1; i++) out->f[i] = dp;      /* coefficients */
    out->f[nin - 1] = unit_fmt(0, 1, W - 1);                /* t in [0, 1] */
    out->f[nin] = dp;                                       /* y */
    for (int i = 0; i < HORNER_NINT; i++) out->f[nin + 1 + i] = dp;
}
static void formats3(const unit_cfg *cfg, unit_fmts *out) { horner_formats(cfg, out, 3); }
static void formats2(const unit_cfg *cfg, unit_fmts *out) { horner_formats(cfg, out, 2); }

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

/* Walk the schedule accumulating the worst-case error of RG (docs/bounds.md):
 * every element that drops fraction bits adds its quantization error;
 * multiplying by t (|t| <= 1) does not grow an error. */
double horner_bound_on(int deg, const sim_fmt *coef_f, sim_fmt t, const sim_fmt *fi,
                       sim_fmt y_f, sim_round r)
{
    const h_prog *p = prog_deg(deg);
    double e_rg = 0;
    for (int s = 0; s < p->nsteps; s++) {
        const h_step *st = &p->step[s];
        double e_mx2, e_bk = 0;
        if (st->mx2 == MX2_MUL) {
            sim_fmt src = st->mx1 == MX1_A ? coef_f[0] : fi[HORNER_RG];
            double e_mx1 = (st->mx1 == MX1_A ? 0 : e_rg) + unit_qerr(fi[HORNER_MX1], src.fbits, r);
            double e_mul = e_mx1 + unit_qerr(fi[HORNER_MUL], fi[HORNER_MX1].fbits + t.fbits, r);
            e_mx2 = e_mul + unit_qerr(fi[HORNER_MX2], fi[HORNER_MUL].fbits, r);
        } else {
            e_mx2 = unit_qerr(fi[HORNER_MX2], coef_f[st->mx2].fbits, r);
        }
        if (st->bk) e_bk = e_rg + unit_qerr(fi[HORNER_BK], fi[HORNER_RG].fbits, r);
        int fsum = fi[HORNER_MX2].fbits > fi[HORNER_BK].fbits ? fi[HORNER_MX2].fbits : fi[HORNER_BK].fbits;
        double e_sm = e_mx2 + e_bk + unit_qerr(fi[HORNER_SM], fsum, r);
        e_rg = e_sm + unit_qerr(fi[HORNER_RG], fi[HORNER_SM].fbits, r);
    }
    return e_rg + unit_qerr(y_f, fi[HORNER_RG].fbits, r);
}

static void horner_bound(const h_prog *p, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    int nin = p->deg + 2;
    per_out[0] = horner_bound_on(p->deg, f->f, f->f[nin - 1], &f->f[nin + 1], f->f[nin], cfg->rnd);
}
static void bound3(const unit_cfg *cfg, const unit_fmts *f, double *o) { horner_bound(&h3_paper, cfg, f, o); }
static void bound2(const unit_cfg *cfg, const unit_fmts *f, double *o) { horner_bound(&h2_paper, cfg, f, o); }

/* -------------------------------------------------------------- descriptors */

#define H_RULE "coefficients, y and every datapath signal s7.(W-7) (|partial sums| < 64); t u1.(W-1)"

const unit_desc unit_horner3 = {
    .name = "horner3",
    .summary = "cubic I = ((A t + B) t + C) t + D on the Fig. 9 datapath (RG, MX1, MX2, BK, Sm, MUL)",
    .seed = "000 Fig. 9",
    .nsigs = 12,
    .sigs = {
        { "a", UNIT_SIG_IN, "coefficient A" }, { "b", UNIT_SIG_IN, "coefficient B" },
        { "c", UNIT_SIG_IN, "coefficient C" }, { "d", UNIT_SIG_IN, "coefficient D" },
        { "t", UNIT_SIG_IN, "position in the interval, k/L" },
        { "y", UNIT_SIG_OUT, "intensity I(t) (RG after the last step)" },
        HORNER_SIGS },
    .nsched = 1,
    .sched = { { "paper", "the paper's sequence, six clocks per pixel (SPEC 2.3)" } },
    .nparams = 0,
    .fmt_rule = H_RULE,
    .formats = formats3, .beats = beats1, .build = build3, .ideal = ideal3, .bound = bound3,
};

const unit_desc unit_horner2 = {
    .name = "horner2",
    .summary = "quadratic I = (A t + B) t + C on the same datapath, four clocks per pixel",
    .seed = "000 Fig. 9 (degree 2)",
    .nsigs = 11,
    .sigs = {
        { "a", UNIT_SIG_IN, "coefficient A" }, { "b", UNIT_SIG_IN, "coefficient B" },
        { "c", UNIT_SIG_IN, "coefficient C" },
        { "t", UNIT_SIG_IN, "position in the interval, k/L" },
        { "y", UNIT_SIG_OUT, "intensity I(t)" },
        HORNER_SIGS },
    .nsched = 1,
    .sched = { { "paper", "the paper's sequence cut to degree 2, four clocks per pixel" } },
    .nparams = 0,
    .fmt_rule = H_RULE,
    .formats = formats2, .beats = beats1, .build = build2, .ideal = ideal2, .bound = bound2,
};

static int build3(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    (void)cfg; (void)err; (void)errlen;
    return horner_build(&unit_horner3, c, sc, clk, f, io);
}
static int build2(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    (void)cfg; (void)err; (void)errlen;
    return horner_build(&unit_horner2, c, sc, clk, f, io);
}
