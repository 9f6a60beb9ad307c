/* unit_interp.c - interpolation along a span (seed 000 IV): the
 * coefficient unit (Fig. 8) and the Horner datapath (Fig. 9) composed.
 *
 *   i1..i4 -> [coef] -> a b c d -> ra rb rc rd (latched when an item is
 *   accepted) -> [horner] -> y, one pixel t = k/L per Horner pass
 *
 * An item is one interval's node intensities; its L beats are the pixels
 * k = 0..L-1. The node inputs are read only in the accept cycle: the
 * coefficient registers hold the item while the Horner runs its paper
 * schedule (6 clocks a pixel for the cubic, 4 for the quadratic). The next
 * item is accepted in the last step of the last pixel, at the same edge
 * where RG takes that pixel's result, so back-to-back items take exactly
 * steps * L clocks each (interp3: 6L, interp2: 4L) with no gap.
 *
 * t is k wired with its binary point moved left by log2 L: no gates, and
 * exact when t's format has log2 L fraction bits.
 */
#include "units/unit_coef.h"
#include "units/unit_horner.h"
#include "vectors/ref_seed000.h"
#include "sim/sim_area.h"
#include <stddef.h>
#include <string.h>

typedef struct interp_kind {
    const unit_desc *u;
    const coef_net  *net;
    int              deg;
} interp_kind;

extern const unit_desc unit_interp3, unit_interp2;
static const interp_kind k3 = { &unit_interp3, &coef_net_n1, 3 };
static const interp_kind k2 = { &unit_interp2, &coef_net_q, 2 };

static const char *const in_names[] = { "i1", "i2", "i3", "i4" };
static const char *const coef_names[] = { "a", "b", "c", "d" };
static const char *const reg_names[] = { "ra", "rb", "rc", "rd" };

static int lg2(int L) { int k = 0; while ((1 << k) < L) k++; return k; }
static int is_pow2(int L) { return L >= 1 && (L & (L - 1)) == 0; }

/* Index of the first Horner internal (mx1; the others follow). */
static int horner_first(const unit_desc *u) { return unit_sig_index(u, "mx1"); }

/* ------------------------------------------------------------- formats */

/* The rule: the coefficient network as in the coefficient units (inputs
 * u1.(W-1), lossless internals, /3 networks with guard bits); the
 * coefficients, their registers and the Horner datapath in the Horner's
 * rule, s7.(W-7), so that latching a coefficient drops nothing; t u1.(W-1). */
static void formats(const interp_kind *K, const unit_cfg *cfg, unit_fmts *out)
{
    static const double lo[UNET_MAXIN] = { 0, 0, 0, 0 }, hi[UNET_MAXIN] = { 1, 1, 1, 1 };
    const unit_desc *u = K->u;
    int W = cfg->width;
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, NULL, cfg->rnd);
    unet_rule(&n, W, lo, hi, K->net->nin);
    for (int i = 0; i < K->net->nin; i++) {
        n.fm.f[unit_sig_index(u, in_names[i])] = coef_input_fmt(W);
        in[i] = unet_input(&n, in_names[i], i);
    }
    coef_walk(&n, K->net, in, cfg->terms, cfg->series, o);
    sim_fmt dp = unit_fmt(1, HORNER_IBITS, W - HORNER_IBITS);
    for (int j = 0; j <= K->deg; j++) {
        n.fm.f[unit_sig_index(u, coef_names[j])] = dp;
        n.fm.f[unit_sig_index(u, reg_names[j])] = dp;
    }
    n.fm.f[unit_sig_index(u, "t")] = unit_fmt(0, 1, W - 1);
    n.fm.f[unit_sig_index(u, "y")] = dp;
    for (int i = 0; i < HORNER_NINT; i++) n.fm.f[horner_first(u) + i] = dp;
    *out = n.fm;
}

static int beats(const unit_cfg *cfg) { return cfg->L; }

/* ------------------------------------------------------------- control */

/* in: busy, k, last; L in user. Ready when idle, or in the last step of
 * the last pixel (the next item follows without a gap). */
static int64_t f_ready(const int64_t *in, void *L)
{
    return !in[0] || (in[1] == *(const int *)L - 1 && in[2]);
}
static int64_t f_and(const int64_t *in, void *u) { (void)u; return in[0] && in[1]; }
/* in: k, last. The pixel counter steps after each pixel's last step and
 * wraps at L, so a new item always starts at pixel 0. */
static int64_t f_k_next(const int64_t *in, void *L)
{
    return in[1] ? (in[0] + 1) % *(const int *)L : in[0];
}
/* in: accept, busy, k, last. Busy from an accept to the end of the item. */
static int64_t f_busy_next(const int64_t *in, void *L)
{
    return in[0] || (in[1] && !(in[2] == *(const int *)L - 1 && in[3]));
}

static const int L_values[] = { 1, 2, 4, 8, 16, 32 };

static int build(const interp_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                 const unit_cfg *cfg, const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    const unit_desc *u = K->u;
    int L = cfg->L, lgL = lg2(L);
    if (!is_pow2(L) || L > 32) {
        snprintf(err, errlen, "%s: L = %d is not a power of two in 1..32 (1, 2, 4, 8, 16 or 32)", u->name, L);
        return -1;
    }
    sim_fmt ft = f->f[unit_sig_index(u, "t")];
    if (ft.fbits < lgL || sim_fmt_real_max(ft) < (double)(L - 1) / L) {
        char b[SIM_FMT_STRLEN];
        snprintf(err, errlen, "%s: t format %s cannot hold k/L exactly for L = %d (needs %d fraction bits)",
                 u->name, sim_fmt_str(ft, b), L, lgL);
        return -1;
    }
    const int *Lp = &L_values[lgL];     /* a pointer that outlives the build */
    sim_fmt u1 = unit_fmt(0, 1, 0), fk = unit_fmt(0, lgL > 0 ? lgL : 1, 0);

    /* Node inputs and the coefficient network (combinational). */
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    unet_hw(&n, c, sc);
    for (int i = 0; i < K->net->nin; i++) {
        in[i] = unet_input(&n, in_names[i], i);
        io->in[i] = in[i].s;
    }
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    n.sc = sim_scope_new(c, sc, "coef");
    if (coef_walk(&n, K->net, in, cfg->terms, cfg->series, o)) { snprintf(err, errlen, "%s", n.why); return -1; }

    /* Control: busy, the pixel counter k, the Horner's step controller. */
    sim_signal *busy = sim_reg(c, sc, "busy", u1, clk, NULL, NULL, NULL, 0);
    sim_signal *k = sim_reg(c, sc, "k", fk, clk, NULL, NULL, NULL, 0);
    sim_scope *hsc = sim_scope_new(c, sc, "horner");
    horner_hw hw;
    horner_ctl_on(c, hsc, clk, K->deg, busy, "last", &hw);
    sim_signal *rdy_in[3] = { busy, k, hw.last };
    io->in_ready = sim_logic(c, sc, "in_ready", u1, 3, rdy_in, f_ready, (void *)Lp, lgL + 2 * SIM_GE_NAND2);
    sim_signal *acc_in[2] = { io->in_valid, io->in_ready };
    sim_signal *accept = sim_logic(c, sc, "accept", u1, 2, acc_in, f_and, NULL, SIM_GE_AND2);
    sim_signal *kn_in[2] = { k, hw.last };
    /* an incrementer (half adder a bit) and an enable mux a bit */
    sim_reg_connect(k, sim_logic(c, sc, "k_next", fk, 2, kn_in, f_k_next, (void *)Lp,
                                 lgL * (SIM_GE_HA + SIM_GE_MUX2)));
    sim_signal *bn_in[4] = { accept, busy, k, hw.last };
    sim_reg_connect(busy, sim_logic(c, sc, "busy_next", u1, 4, bn_in, f_busy_next, (void *)Lp,
                                    lgL + 3 * SIM_GE_NAND2));

    /* Coefficient registers, t, and the Horner datapath. */
    sim_signal *r[4];
    for (int j = 0; j <= K->deg; j++)
        r[j] = sim_reg(c, sc, reg_names[j], f->f[unit_sig_index(u, reg_names[j])], clk, o[j].s, accept, NULL, 0);
    sim_signal *t = sim_shift(c, sc, "t", ft, k, -lgL);
    horner_dp_on(c, hsc, clk, &hw, r, t, &f->f[horner_first(u)]);

    io->out[0] = sim_shift(c, sc, "y", f->f[unit_sig_index(u, "y")], hw.rg, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", u1, clk, hw.last, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}

/* ------------------------------------------------------- ideal, bound */

/* The coefficients with the network's 1/3, exact otherwise, evaluated at
 * the L pixels t = k/L. */
static void ideal(const interp_kind *K, const unit_cfg *cfg, const double *in, double *out)
{
    double co[4];
    K->net->formula(in, ref_div3_factor(cfg->terms, cfg->series), co);
    for (int k = 0; k < cfg->L; k++) {
        double t = (double)k / cfg->L, y = co[0];
        for (int j = 1; j <= K->deg; j++) y = y * t + co[j];
        out[k] = y;
    }
}

/* A coefficient's error e_j reaches y times t^(deg-j) <= 1, so y's bound
 * is the sum of the latched coefficients' errors (the network's walk plus
 * the register's quantization) plus the Horner datapath's own bound for
 * coefficients held in the registers' formats (t = k/L is exact: build
 * checks t's format). */
static void bound(const interp_kind *K, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    const unit_desc *u = K->u;
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    for (int i = 0; i < K->net->nin; i++) in[i] = unet_input(&n, in_names[i], i);
    coef_walk(&n, K->net, in, cfg->terms, cfg->series, o);
    double e = 0;
    sim_fmt rf[4];
    for (int j = 0; j <= K->deg; j++) {
        rf[j] = f->f[unit_sig_index(u, reg_names[j])];
        e += o[j].err + unit_qerr(rf[j], o[j].f.fbits, cfg->rnd);
    }
    per_out[0] = e + horner_bound_on(K->deg, rf, f->f[unit_sig_index(u, "t")], &f->f[horner_first(u)],
                                     f->f[unit_sig_index(u, "y")], cfg->rnd);
}

/* ---------------------------------------------------------- descriptors */

#define INTERP_FNS(sfx, K) \
    static void formats_##sfx(const unit_cfg *cfg, unit_fmts *out) { formats(&K, cfg, out); } \
    static int build_##sfx(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, \
                           const unit_fmts *f, unit_io *io, char *err, size_t errlen) \
    { return build(&K, c, sc, clk, cfg, f, io, err, errlen); } \
    static void ideal_##sfx(const unit_cfg *cfg, const double *in, double *out) { ideal(&K, cfg, in, out); } \
    static void bound_##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { bound(&K, cfg, f, o); }

INTERP_FNS(3, k3)
INTERP_FNS(2, k2)

#define P_L { "L", UNIT_P_POW2, offsetof(unit_cfg, L), 2, 32, NULL, "pixels per interval (beats per item)" }
#define P_TERMS { "terms", UNIT_P_INT, offsetof(unit_cfg, terms), 1, DIV3_MAX_TERMS, NULL, \
                  "terms of each /3 network (see div3); 3 is the paper's" }
#define P_SERIES { "series", UNIT_P_ENUM, offsetof(unit_cfg, series), 0, 1, "paper quarter", \
                   "series of each /3 network (see div3)" }
#define REG(name, what) { name, UNIT_SIG_INTERNAL, what }
#define T_SIG { "t", UNIT_SIG_INTERNAL, "t = k/L, the pixel counter k with its binary point moved (wiring)" }
#define Y_SIG { "y", UNIT_SIG_OUT, "intensity I(k/L) of pixel k, one beat per pixel (RG after the last step)" }
#define INTERP_RULE(coefs) "i* u1.(W-1); the coefficient network as in the coefficient units; " coefs \
    ", their registers, y and the Horner datapath s7.(W-7) (the Horner's rule); t u1.(W-1)"

const unit_desc unit_interp3 = {
    .name = "interp3",
    .summary = "cubic interpolation of a span interval: coef3_n1 + registers + the Fig. 9 Horner, L pixels per item",
    .seed = "000 IV, Figs. 8 and 9",
    .nsigs = 5 + COEF3_N1_NODES + 4 + 1 + HORNER_NINT,
    .sigs = { COEF_SIGS_I123, COEF_SIG_I4_N1, Y_SIG,
              COEF3_N1_NET(COEF_SIG_INT, COEF_SIG_INT)
              REG("ra", "register of A, loaded when an item is accepted"),
              REG("rb", "register of B"), REG("rc", "register of C"), REG("rd", "register of D"),
              T_SIG, HORNER_SIGS },
    .nsched = 1,
    .sched = { { "paper", "coefficients once per item, then the paper's Horner sequence: 6 clocks per pixel, 6L per item" } },
    .nparams = 3, .params = { P_L, P_TERMS, P_SERIES },
    .fmt_rule = INTERP_RULE("a b c d"),
    .formats = formats_3, .beats = beats, .build = build_3, .ideal = ideal_3, .bound = bound_3,
};

const unit_desc unit_interp2 = {
    .name = "interp2",
    .summary = "quadratic interpolation of a span interval: coef2 + registers + the Horner cut to degree 2, L pixels per item",
    .seed = "000 IV, Fig. 9 (degree 2)",
    .nsigs = 4 + COEF2_NODES + 3 + 1 + HORNER_NINT,
    .sigs = { COEF_SIGS_I123, Y_SIG,
              COEF2_NET(COEF_SIG_INT, COEF_SIG_INT)
              REG("ra", "register of A, loaded when an item is accepted"),
              REG("rb", "register of B"), REG("rc", "register of C"),
              T_SIG, HORNER_SIGS },
    .nsched = 1,
    .sched = { { "paper", "coefficients once per item, then the Horner sequence cut to degree 2: 4 clocks per pixel, 4L per item" } },
    .nparams = 1, .params = { P_L },
    .fmt_rule = INTERP_RULE("a b c"),
    .formats = formats_2, .beats = beats, .build = build_2, .ideal = ideal_2, .bound = bound_2,
};
