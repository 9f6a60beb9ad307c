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
#include "units/unit.h"
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

/* Signal indices in the descriptors below (inputs, output, internals). */
enum { S_MX1 = 0, S_MUL, S_MX2, S_BK, S_SM, S_RG, S_NINT };

static const h_prog *prog_of(const unit_desc *u) { return !strcmp(u->name, "horner3") ? &h3_paper : &h2_paper; }

/* ------------------------------------------------------------- controller */

/* Next step: wrap after the last; wait at step 0 until an item is
 * offered (in[1] = in_valid); once started, an item runs to its end. */
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

static int horner_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                        const unit_fmts *f, unit_io *io)
{
    const h_prog *p = prog_of(u);
    int nin = p->deg + 2;                       /* coefficients and t */
    sim_fmt u1 = unit_fmt(0, 1, 0), u2 = unit_fmt(0, 2, 0), u3 = unit_fmt(0, 3, 0);
    for (int i = 0; i < nin; i++)
        io->in[i] = sim_signal_new(c, sc, u->sigs[i].name, f->f[i], SIM_KIND_INPUT);
    sim_signal *t = io->in[nin - 1];
    const sim_fmt *fi = &f->f[nin + 1];         /* internals follow y */

    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    sim_signal *step = sim_reg(c, sc, "step", u3, clk, NULL, NULL, NULL, 0);
    sim_signal *nx_in[2] = { step, io->in_valid };
    sim_signal *nx = sim_logic(c, sc, "step_next", u3, 2, nx_in, f_next, (void *)p, 3 * SIM_GE_HA + 6);
    sim_reg_connect(step, nx);
    sim_signal *mx1_sel = sim_logic(c, sc, "mx1_sel", u1, 1, &step, f_mx1, (void *)p, decoder_ge(p));
    sim_signal *mx2_sel = sim_logic(c, sc, "mx2_sel", u2, 1, &step, f_mx2, (void *)p, 2 * decoder_ge(p));
    sim_signal *bk_pass = sim_logic(c, sc, "bk_pass", u1, 1, &step, f_bk, (void *)p, decoder_ge(p));
    io->in_ready = sim_logic(c, sc, "in_ready", u1, 1, &step, f_last, (void *)p, decoder_ge(p));

    /* Datapath. */
    sim_signal *rg = sim_reg(c, sc, "rg", fi[S_RG], clk, NULL, NULL, NULL, 0);
    sim_signal *mx1_in[2] = { io->in[0], rg };
    sim_signal *mx1 = sim_mux(c, sc, "mx1", fi[S_MX1], mx1_sel, 2, mx1_in);
    sim_signal *mul = sim_mul(c, sc, "mul", fi[S_MUL], mx1, t);
    sim_signal *mx2_in[4] = { mul, io->in[1], io->in[2], p->deg >= 3 ? io->in[3] : NULL };
    sim_signal *mx2 = sim_mux(c, sc, "mx2", fi[S_MX2], mx2_sel, p->deg + 1, mx2_in);
    sim_signal *bk = sim_bk(c, sc, "bk", fi[S_BK], bk_pass, rg);
    sim_signal *sm = sim_add(c, sc, "sm", fi[S_SM], mx2, bk);
    sim_reg_connect(rg, sm);
    /* y is RG's output seen through the output port's format. */
    io->out[0] = sim_shift(c, sc, "y", f->f[nin], rg, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", u1, clk, io->in_ready, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}

static int build3(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen);
static int build2(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen);

/* ------------------------------------------------------------------ formats */

/* Integer bits of the datapath: the coefficients of real intensity profiles
 * reach |A| <= 24, |B| <= 34, |C| <= 11 for node intensities in [0, 1]
 * (SPEC 2.1 formulas at their extremes), and every partial sum of Horner's
 * rule stays below |A| + |B| + |C| + |D| < 64 for t in [0, 1]. */
#define H_IBITS 7

static void horner_formats(const unit_cfg *cfg, unit_fmts *out, int deg)
{
    int W = cfg->width;
    sim_fmt dp = unit_fmt(1, H_IBITS, W - H_IBITS);
    int nin = deg + 2;
    for (int i = 0; i < nin - 1; i++) out->f[i] = dp;      /* coefficients */
    out->f[nin - 1] = unit_fmt(0, 1, W - 1);                /* t in [0, 1] */
    out->f[nin] = dp;                                       /* y */
    for (int i = 0; i < S_NINT; i++) out->f[nin + 1 + i] = dp;
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
static void horner_bound(const h_prog *p, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    int nin = p->deg + 2;
    const sim_fmt *fi = &f->f[nin + 1];
    sim_fmt t = f->f[nin - 1];
    sim_round r = cfg->rnd;
    double e_rg = 0;
    for (int s = 0; s < p->nsteps; s++) {
        const h_step *st = &p->step[s];
        double e_mx2, e_bk = 0;
        int f_mx2_src;
        if (st->mx2 == MX2_MUL) {
            sim_fmt src = st->mx1 == MX1_A ? f->f[0] : fi[S_RG];
            double e_mx1 = (st->mx1 == MX1_A ? 0 : e_rg) + unit_qerr(fi[S_MX1], src.fbits, r);
            double e_mul = e_mx1 + unit_qerr(fi[S_MUL], fi[S_MX1].fbits + t.fbits, r);
            e_mx2 = e_mul + unit_qerr(fi[S_MX2], fi[S_MUL].fbits, r);
        } else {
            f_mx2_src = f->f[st->mx2].fbits;
            e_mx2 = unit_qerr(fi[S_MX2], f_mx2_src, r);
        }
        if (st->bk) e_bk = e_rg + unit_qerr(fi[S_BK], fi[S_RG].fbits, r);
        int fsum = fi[S_MX2].fbits > fi[S_BK].fbits ? fi[S_MX2].fbits : fi[S_BK].fbits;
        double e_sm = e_mx2 + e_bk + unit_qerr(fi[S_SM], fsum, r);
        e_rg = e_sm + unit_qerr(fi[S_RG], fi[S_SM].fbits, r);
    }
    per_out[0] = e_rg + unit_qerr(f->f[nin], fi[S_RG].fbits, r);
}
static void bound3(const unit_cfg *cfg, const unit_fmts *f, double *o) { horner_bound(&h3_paper, cfg, f, o); }
static void bound2(const unit_cfg *cfg, const unit_fmts *f, double *o) { horner_bound(&h2_paper, cfg, f, o); }

/* -------------------------------------------------------------- descriptors */

#define H_INTERNALS \
    { "mx1", UNIT_SIG_INTERNAL, "multiplexer MX1: A or RG into the multiplier" }, \
    { "mul", UNIT_SIG_INTERNAL, "multiplier MUL = MX1 * t, quantized to its own format" }, \
    { "mx2", UNIT_SIG_INTERNAL, "multiplexer MX2: MUL or a coefficient into the adder" }, \
    { "bk",  UNIT_SIG_INTERNAL, "block key BK: passes RG or forces zero" }, \
    { "sm",  UNIT_SIG_INTERNAL, "adder Sm = MX2 + BK" }, \
    { "rg",  UNIT_SIG_INTERNAL, "register RG <= Sm every clock" }

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
        H_INTERNALS },
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
        H_INTERNALS },
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
