/* unit_interp.c - interpolation along a span (Nechyporuk & Romanyuk (2020), sec. IV): the
 * coefficient unit (Fig. 8) and the Horner datapath (Fig. 9) composed, or
 * forward differencing in its place.
 *
 *   i1..i4 -> [coef] -> a b c d -> ra rb rc rd (latched when an item is
 *   accepted) -> [horner] -> y, one pixel t = k/L per Horner pass
 *
 * An item is one interval's node intensities; its L beats are the pixels
 * k = 0..L-1. The node inputs are read only in the accept cycle: the
 * coefficient registers hold the item while the Horner runs its schedule
 * (paper 6 clocks a pixel for the cubic, 4 for the quadratic; mac 3 and 2;
 * pipe 1). The next item is accepted in the last step of the last pixel,
 * at the same edge where the Horner takes that pixel's last operands, so
 * back-to-back items take exactly steps * L clocks each with no gap (the
 * pipe's coefficient registers carry the old item's C and D on).
 *
 * t is k wired with its binary point moved left by log2 L: no gates, and
 * exact when t's format has log2 L fraction bits.
 *
 * Schedule fwd replaces the Horner by forward differencing with adders
 * only (docs/schedules.md): shift-and-add networks make the start value
 * and the differences of step h = 1/L from the coefficients, loaded into
 * registers fy, fd1, fd2 (, fd3) when an item is accepted; then every
 * clock fy += fd1, fd1 += fd2, fd2 += fd3: a pixel a clock. Its errors
 * accumulate over the pixels, so its bound is per pixel (bound_beats).
 */
#include "units/unit_coef.h"
#include "units/unit_horner.h"
#include "vectors/ref_interp.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

enum { INTERP_FWD = HORNER_NSCHED };     /* paper, mac, pipe, then fwd */
#define I_HORNER (H_P | H_M | H_PP)      /* signals of the Horner schedules */
#define I_FWD UNIT_SCHED(INTERP_FWD)

/* ------------------------------------------------- forward differencing */

/* The start differences as shift-and-add networks of the coefficients,
 * h = 1/L = 2^-log2 L. Each line: X(name, op, a, b, hs, k, what) with op
 * SHL (a * 2^k * h^hs: wiring) or ADD; operands are the coefficients
 * a b c d or earlier lines. With p(t) = A t^3 + B t^2 + C t + D:
 *   p(h) - p(0) = A h^3 + B h^2 + C h,  second difference 6 A h^3 + 2 B h^2,
 *   third 6 A h^3 (6 = 4 + 2). */
#define FWD3_NET(X) \
    X(ah3,   SHL, a,     _,     3, 0, "fwd: A h^3 = A >> 3 log2 L") \
    X(bh2,   SHL, b,     _,     2, 0, "fwd: B h^2") \
    X(ch,    SHL, c,     _,     1, 0, "fwd: C h") \
    X(ab,    ADD, ah3,   bh2,   0, 0, "fwd: A h^3 + B h^2") \
    X(d1i,   ADD, ab,    ch,    0, 0, "fwd: first difference at t = 0, A h^3 + B h^2 + C h") \
    X(ah3x4, SHL, ah3,   _,     0, 2, "fwd: 4 A h^3") \
    X(ah3x2, SHL, ah3,   _,     0, 1, "fwd: 2 A h^3") \
    X(d3i,   ADD, ah3x4, ah3x2, 0, 0, "fwd: third difference 6 A h^3") \
    X(bh2x2, SHL, bh2,   _,     0, 1, "fwd: 2 B h^2") \
    X(d2i,   ADD, d3i,   bh2x2, 0, 0, "fwd: second difference at t = 0, 6 A h^3 + 2 B h^2")
/* p(t) = A t^2 + B t + C: p(h) - p(0) = A h^2 + B h, second difference 2 A h^2. */
#define FWD2_NET(X) \
    X(ah2,   SHL, a,     _,     2, 0, "fwd: A h^2") \
    X(bh,    SHL, b,     _,     1, 0, "fwd: B h") \
    X(d1i,   ADD, ah2,   bh,    0, 0, "fwd: first difference at t = 0, A h^2 + B h") \
    X(d2i,   SHL, ah2,   _,     0, 1, "fwd: second difference 2 A h^2")

typedef struct fwd_node { const char *name; coef_op op; const char *a, *b; int hs, k; } fwd_node;
#define FWD_NODE(name, op, a, b, hs, k, what) { #name, COEF_##op, #a, #b, hs, k },
#define FWD_SIG(nm_, op, a, b, hs, k, wh_) { .name = #nm_, .role = UNIT_SIG_INTERNAL, .what = wh_, .scheds = I_FWD },
#define FWD_COUNT(name, op, a, b, hs, k, what) + 1
static const fwd_node fwd3_nodes[] = { FWD3_NET(FWD_NODE) };
static const fwd_node fwd2_nodes[] = { FWD2_NET(FWD_NODE) };

/* The registers: fy the pixel's value, fdJ the J-th difference. Each one's
 * adder (fy + fd1, ...) and load multiplexer take its format. */
static const char *const fwd_regs[] = { "fy", "fd1", "fd2", "fd3" };
static const char *const fwd_init[] = { NULL, "d1i", "d2i", "d3i" };   /* fy starts at the constant coefficient */
#define FWD_REG(nm_, wh_) { .name = nm_, .role = UNIT_SIG_INTERNAL, .what = wh_, .scheds = I_FWD }
#define FWD_REGS3 \
    FWD_REG("fy", "fwd register of the pixel value: fy <= fy + fd1 each clock (its adder and load mux share this format)"), \
    FWD_REG("fd1", "fwd register of the first difference: fd1 <= fd1 + fd2"), \
    FWD_REG("fd2", "fwd register of the second difference: fd2 <= fd2 + fd3"), \
    FWD_REG("fd3", "fwd register of the third difference, constant over the interval")
#define FWD_REGS2 \
    FWD_REG("fy", "fwd register of the pixel value: fy <= fy + fd1 each clock (its adder and load mux share this format)"), \
    FWD_REG("fd1", "fwd register of the first difference: fd1 <= fd1 + fd2"), \
    FWD_REG("fd2", "fwd register of the second difference, constant over the interval")

#define FWD_MAXK 65     /* pixels 0..L for L <= 64 */

typedef struct interp_kind {
    const unit_desc *u;
    const coef_net  *net;
    int              deg;
    const fwd_node  *fwd;
    int              nfwd;
} interp_kind;

extern const unit_desc unit_interp3, unit_interp2;
static const interp_kind k3 = { &unit_interp3, &coef_net_n1, 3, fwd3_nodes, 0 FWD3_NET(FWD_COUNT) };
static const interp_kind k2 = { &unit_interp2, &coef_net_q, 2, fwd2_nodes, 0 FWD2_NET(FWD_COUNT) };

/* The cubic's node set is a parameter (nodes: n1 = I(0), I(1), I(1/2),
 * I(1/4), the paper's choice; n2 = ... I(3/4)); the quadratic has one. */
static const coef_net *net_of(const interp_kind *K, const unit_cfg *cfg)
{
    return K->deg == 3 && cfg->nodes ? &coef_net_n2 : K->net;
}

static const char *const in_names[] = { "i1", "i2", "i3", "i4" };
static const char *const coef_names[] = { "a", "b", "c", "d" };
static const char *const reg_names[] = { "ra", "rb", "rc", "rd" };

static int lg2(int L) { int k = 0; while ((1 << k) < L) k++; return k; }
static int is_pow2(int L) { return L >= 1 && (L & (L - 1)) == 0; }

/* Walk the start networks from the coefficients coef[0..deg] (built,
 * bounded or formatted by n); init[j] is register j's start value. */
static int fwd_walk(unet *n, const interp_kind *K, int lgL, const unet_val *coef, unet_val *init)
{
    unet_val v[16];
    for (int i = 0; i < K->nfwd && i < 16; i++) {
        const fwd_node *e = &K->fwd[i];
        unet_val op[2];
        const char *nm[2] = { e->a, e->b };
        for (int o = 0; o < 2; o++) {
            if (!strcmp(nm[o], "_")) continue;
            int found = 0;
            for (int j = 0; j <= K->deg && !found; j++)
                if (!strcmp(nm[o], coef_names[j])) { op[o] = coef[j]; found = 1; }
            for (int j = 0; j < i && !found; j++)
                if (!strcmp(nm[o], K->fwd[j].name)) { op[o] = v[j]; found = 1; }
            if (!found) { snprintf(n->why, sizeof n->why, "fwd network of %s: no operand '%s'", n->u->name, nm[o]); return -1; }
        }
        int sig = unet_sig(n, e->name);
        v[i] = e->op == COEF_SHL ? unet_shift(n, sig, e->name, op[0], e->k - e->hs * lgL)
                                 : unet_add(n, sig, e->name, op[0], op[1]);
    }
    init[0] = coef[K->deg];
    for (int j = 1; j <= K->deg; j++)
        for (int i = 0; i < K->nfwd; i++)
            if (!strcmp(K->fwd[i].name, fwd_init[j])) init[j] = v[i];
    return n->why[0] ? -1 : 0;
}

/* Worst-case error E[j][k] of register j at pixel k = 0..L, for start
 * values init[] and register formats rf[] (docs/schedules.md): register j
 * starts with its start value's error plus its own quantization e_j, and
 * each clock adds register j+1's error and its adder's quantization a_j,
 * so fy's error at pixel k is
 *   e_y + k (e_1 + a_y) + C(k,2) (e_2 + a_1) + C(k,3) (e_3 + a_2). */
static void fwd_errs(int deg, int L, const unet_val *init, const sim_fmt *rf, sim_round r, double E[4][FWD_MAXK])
{
    double a[4] = { 0, 0, 0, 0 };
    for (int j = 0; j <= deg; j++) E[j][0] = init[j].err + unit_qerr(rf[j], init[j].eff, r);
    for (int j = 0; j < deg; j++)
        a[j] = unit_qerr(rf[j], rf[j].fbits > rf[j + 1].fbits ? rf[j].fbits : rf[j + 1].fbits, r);
    for (int k = 1; k <= L && k < FWD_MAXK; k++) {
        E[deg][k] = E[deg][0];
        for (int j = 0; j < deg; j++) E[j][k] = E[j][k - 1] + E[j + 1][k - 1] + a[j];
    }
}

/* Exact range of register j over pixels k = 0..L and node intensities in
 * [0, 1]: it holds the j-th difference of p at k h, a linear form of the
 * inputs (coef[m].lin, with the network's 1/3). */
static void fwd_range(const interp_kind *K, int L, const unet_val *coef, int j, double *lo, double *hi)
{
    *lo = *hi = 0;
    for (int k = 0; k <= L; k++) {
        double lin[UNET_MAXIN] = { 0 }, binom = 1, l = 0, h = 0;
        for (int i = 0; i <= j; i++) {          /* sum (-1)^(j-i) C(j,i) p((k+i) h) */
            double t = (double)(k + i) / L, w = ((j - i) & 1 ? -binom : binom);
            for (int m = 0; m <= K->deg; m++)
                for (int q = 0; q < UNET_MAXIN; q++) lin[q] += w * coef[m].lin[q] * pow(t, K->deg - m);
            binom = binom * (j - i) / (i + 1);
        }
        for (int q = 0; q < UNET_MAXIN; q++) { l += fmin(lin[q], 0); h += fmax(lin[q], 0); }
        if (k == 0 || l < *lo) *lo = l;
        if (k == 0 || h > *hi) *hi = h;
    }
}

/* The start values and their errors for formats fm, with the start
 * networks' own formats chosen by the rule when choose (lossless
 * internals) or taken from fm. */
static int fwd_values(const interp_kind *K, const unit_cfg *cfg, unit_fmts *fm, int choose,
                      unet_val *coef, unet_val *init)
{
    static const double lo[UNET_MAXIN] = { 0, 0, 0, 0 }, hi[UNET_MAXIN] = { 1, 1, 1, 1 };
    unet n;
    unet_val in[UNET_MAXIN];
    unet_init(&n, K->u, fm, cfg->rnd);
    for (int i = 0; i < net_of(K, cfg)->nin; i++) in[i] = unet_input(&n, in_names[i], i);
    if (coef_walk(&n, net_of(K, cfg), in, cfg->terms, cfg->series, coef)) return -1;
    if (choose) unet_rule(&n, cfg->width, lo, hi, net_of(K, cfg)->nin);
    if (fwd_walk(&n, K, lg2(cfg->L), coef, init)) return -1;
    *fm = n.fm;
    return 0;
}

/* The rule of the fwd registers: W bits each, signed, the fewest integer
 * bits (1 to 7) holding the register's exact range widened by its
 * worst-case error, found by iterating (fewer integer bits, more fraction
 * bits, smaller errors). Its values are up to L^j times smaller than the
 * coefficients, so W bits of a difference register are mostly fraction. */
static void fwd_formats(const interp_kind *K, const unit_cfg *cfg, unit_fmts *fm)
{
    unet_val coef[4], init[4];
    if (fwd_values(K, cfg, fm, 1, coef, init)) return;
    int L = cfg->L < FWD_MAXK ? cfg->L : FWD_MAXK - 1, W = cfg->width, ib[4];
    double lo[4], hi[4], E[4][FWD_MAXK];
    sim_fmt rf[4];
    for (int j = 0; j <= K->deg; j++) { fwd_range(K, L, coef, j, &lo[j], &hi[j]); ib[j] = 0; }
    for (int it = 0; it < 16; it++) {
        int changed = 0;
        for (int j = 0; j <= K->deg; j++) {
            double e = 0;
            if (it) for (int k = 0; k <= L; k++) e = fmax(e, E[j][k]);
            int I = 1;
            while (I < HORNER_IBITS && !(lo[j] - e >= -ldexp(1, I - 1) && hi[j] + e < ldexp(1, I - 1))) I++;
            changed |= I != ib[j];
            ib[j] = I;
            rf[j] = unit_fmt(1, I, W - I);
        }
        if (!changed) break;
        fwd_errs(K->deg, L, init, rf, cfg->rnd, E);
    }
    for (int j = 0; j <= K->deg; j++) fm->f[unit_sig_must(K->u, fwd_regs[j])] = rf[j];
}

/* ------------------------------------------------------------- formats */

/* The rule: the coefficient network as in the coefficient units (inputs
 * u1.(W-1), lossless internals, /3 networks with guard bits); the
 * coefficients, their registers and the Horner datapaths in the Horner's
 * rule, s7.(W-7), so that latching a coefficient drops nothing; t and its
 * pipe copies u1.(W-1); fwd as fwd_formats says. */
static void formats(const interp_kind *K, const unit_cfg *cfg, unit_fmts *out)
{
    static const double lo[UNET_MAXIN] = { 0, 0, 0, 0 }, hi[UNET_MAXIN] = { 1, 1, 1, 1 };
    const unit_desc *u = K->u;
    int W = cfg->width;
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, NULL, cfg->rnd);
    unet_rule(&n, W, lo, hi, net_of(K, cfg)->nin);
    for (int i = 0; i < net_of(K, cfg)->nin; i++) {
        n.fm.f[unit_sig_must(u, in_names[i])] = coef_input_fmt(W);
        in[i] = unet_input(&n, in_names[i], i);
    }
    /* interp3 declares both node sets' elements; the other set's own ones
     * are not built (sig_used) and keep no format. */
    coef_walk(&n, net_of(K, cfg), in, cfg->terms, cfg->series, o);
    sim_fmt dp = unit_fmt(1, HORNER_IBITS, W - HORNER_IBITS);
    for (int j = 0; j <= K->deg; j++) {
        n.fm.f[unit_sig_must(u, coef_names[j])] = dp;
        n.fm.f[unit_sig_must(u, reg_names[j])] = dp;
    }
    n.fm.f[unit_sig_must(u, "t")] = unit_fmt(0, 1, W - 1);
    n.fm.f[unit_sig_must(u, "y")] = dp;
    horner_default_fmts(u, K->deg, W, &n.fm);
    *out = n.fm;
    fwd_formats(K, cfg, out);
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
/* fwd, in: accept, busy, k. The registers load on an accept and step
 * after every pixel but the item's last, so that they only ever hold
 * pixels 0..L-1 (their adders see pixel L: the formats' ranges include it). */
static int64_t f_adv(const int64_t *in, void *L)
{
    return in[0] || (in[1] && in[2] != *(const int *)L - 1);
}

static const int L_values[] = { 1, 2, 4, 8, 16, 32 };

typedef struct interp_ctl {
    sim_signal *busy, *k, *accept;
} interp_ctl;

/* in_ready, accept and the next busy and k around `last` (1 in the clock
 * a pixel's last step runs; fwd: every busy clock). */
static void control(sim_ctx *c, sim_scope *sc, const int *Lp, int lgL, sim_signal *busy, sim_signal *k,
                    sim_signal *last, unit_io *io, interp_ctl *ctl)
{
    sim_fmt u1 = unit_fmt(0, 1, 0), fk = k->fmt;
    sim_signal *rdy_in[3] = { busy, k, last };
    io->in_ready = sim_logic(c, sc, "in_ready", u1, 3, rdy_in, f_ready, (void *)Lp, lgL + 2 * SIM_GE_NAND2);
    sim_signal *acc_in[2] = { io->in_valid, io->in_ready };
    ctl->accept = sim_logic(c, sc, "accept", u1, 2, acc_in, f_and, NULL, SIM_GE_AND2);
    sim_signal *kn_in[2] = { k, last };
    /* an incrementer (half adder a bit) and an enable mux a bit */
    sim_reg_connect(k, sim_logic(c, sc, "k_next", fk, 2, kn_in, f_k_next, (void *)Lp,
                                 lgL * (SIM_GE_HA + SIM_GE_MUX2)));
    sim_signal *bn_in[4] = { ctl->accept, busy, k, last };
    sim_reg_connect(busy, sim_logic(c, sc, "busy_next", u1, 4, bn_in, f_busy_next, (void *)Lp,
                                    lgL + 3 * SIM_GE_NAND2));
    ctl->busy = busy;
    ctl->k = k;
}

/* The item's state registers: busy from an accept to the end of the item,
 * and the pixel counter k. */
static void state_regs(sim_ctx *c, sim_scope *sc, sim_signal *clk, int lgL, sim_signal **busy, sim_signal **k)
{
    *busy = sim_reg(c, sc, "busy", unit_fmt(0, 1, 0), clk, NULL, NULL, NULL, 0);
    *k = sim_reg(c, sc, "k", unit_fmt(0, lgL > 0 ? lgL : 1, 0), clk, NULL, NULL, NULL, 0);
}

/* Forward differencing: start networks, then registers that load on an
 * accept and otherwise add the next difference. */
static int build_fwd(const interp_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                     const unit_fmts *f, unet *n, const unet_val *o, const int *Lp, unit_io *io,
                     char *err, size_t errlen)
{
    const unit_desc *u = K->u;
    int L = cfg->L, lgL = lg2(L), deg = K->deg;
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *busy, *k;
    state_regs(c, sc, clk, lgL, &busy, &k);
    interp_ctl ctl;
    control(c, sc, Lp, lgL, busy, k, busy, io, &ctl);
    sim_signal *adv_in[3] = { ctl.accept, busy, ctl.k };
    sim_signal *adv = sim_logic(c, sc, "adv", u1, 3, adv_in, f_adv, (void *)Lp, lgL + 2 * SIM_GE_NAND2);

    n->sc = sim_scope_new(c, sc, "fwd");
    unet_val init[4];
    if (fwd_walk(n, K, lgL, o, init)) { snprintf(err, errlen, "%s", n->why); return -1; }
    sim_signal *reg[4];
    sim_fmt rf[4];
    for (int j = 0; j <= deg; j++) {
        rf[j] = f->f[unit_sig_must(u, fwd_regs[j])];
        /* the last difference is constant: it loads on an accept only */
        reg[j] = sim_reg(c, n->sc, fwd_regs[j], rf[j], clk, j == deg ? init[j].s : NULL,
                         j == deg ? ctl.accept : adv, NULL, 0);
    }
    for (int j = 0; j < deg; j++) {
        char nm[24];
        snprintf(nm, sizeof nm, "%s_next", fwd_regs[j]);
        sim_signal *sum = sim_add(c, n->sc, nm, rf[j], reg[j], reg[j + 1]);
        snprintf(nm, sizeof nm, "%s_in", fwd_regs[j]);
        sim_signal *mx_in[2] = { sum, init[j].s };
        sim_reg_connect(reg[j], sim_mux(c, n->sc, nm, rf[j], ctl.accept, 2, mx_in));
    }
    io->out[0] = sim_shift(c, sc, "y", f->f[unit_sig_must(u, "y")], reg[0], 0);
    /* fy holds pixel k of the item in every busy clock */
    io->out_valid = sim_shift(c, sc, "out_valid", u1, busy, 0);
    io->scope = sc;
    return 0;
}

static int build(const interp_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                 const unit_cfg *cfg, const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    const unit_desc *u = K->u;
    int L = cfg->L, lgL = lg2(L), sched = cfg->schedule;
    if (!is_pow2(L) || L > 32) {
        snprintf(err, errlen, "%s: L = %d is not a power of two in 1..32 (1, 2, 4, 8, 16 or 32)", u->name, L);
        return -1;
    }
    if (sched < 0 || sched > INTERP_FWD) { snprintf(err, errlen, "%s: no schedule %d", u->name, sched); return -1; }
    sim_fmt ft = f->f[unit_sig_must(u, "t")];
    if (sched != INTERP_FWD && (ft.fbits < lgL || sim_fmt_real_max(ft) < (double)(L - 1) / L)) {
        char b[SIM_FMT_STRLEN];
        snprintf(err, errlen, "%s: t format %s cannot hold k/L exactly for L = %d (needs %d fraction bits)",
                 u->name, sim_fmt_str(ft, b), L, lgL);
        return -1;
    }
    const int *Lp = &L_values[lgL];     /* a pointer that outlives the build */
    sim_fmt u1 = unit_fmt(0, 1, 0);

    /* Node inputs and the coefficient network (combinational). */
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    unet_hw(&n, c, sc);
    for (int i = 0; i < net_of(K, cfg)->nin; i++) {
        in[i] = unet_input(&n, in_names[i], i);
        io->in[i] = in[i].s;
    }
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    n.sc = sim_scope_new(c, sc, "coef");
    if (coef_walk(&n, net_of(K, cfg), in, cfg->terms, cfg->series, o)) { snprintf(err, errlen, "%s", n.why); return -1; }
    if (sched == INTERP_FWD) return build_fwd(K, c, sc, clk, cfg, f, &n, o, Lp, io, err, errlen);

    /* Control: busy, the pixel counter k, the Horner's step controller. */
    sim_signal *busy, *k;
    state_regs(c, sc, clk, lgL, &busy, &k);
    sim_scope *hsc = sim_scope_new(c, sc, "horner");
    horner_hw hw;
    horner_ctl_on(c, hsc, clk, K->deg, sched, busy, "last", &hw);
    interp_ctl ctl;
    control(c, sc, Lp, lgL, busy, k, hw.last, io, &ctl);

    /* Coefficient registers, t, and the Horner datapath. */
    sim_signal *r[4];
    for (int j = 0; j <= K->deg; j++)
        r[j] = sim_reg(c, sc, reg_names[j], f->f[unit_sig_must(u, reg_names[j])], clk, o[j].s, ctl.accept, NULL, 0);
    sim_signal *t = sim_shift(c, sc, "t", ft, ctl.k, -lgL);
    horner_dp_on(c, hsc, clk, &hw, busy, r, t, u, f);

    io->out[0] = sim_shift(c, sc, "y", f->f[unit_sig_must(u, "y")], hw.rg, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", u1, clk, hw.done, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}

/* ------------------------------------------------------- ideal, bound */

/* The coefficients with the network's 1/3, exact otherwise, evaluated at
 * the L pixels t = k/L (every schedule computes this polynomial). */
static void ideal(const interp_kind *K, const unit_cfg *cfg, const double *in, double *out)
{
    double co[4];
    net_of(K, cfg)->formula(in, ref_div3_factor(cfg->terms, cfg->series), co);
    for (int k = 0; k < cfg->L; k++) {
        double t = (double)k / cfg->L, y = co[0];
        for (int j = 1; j <= K->deg; j++) y = y * t + co[j];
        out[k] = y;
    }
}

/* The same exactly: t = k/L is dyadic (L a power of two). */
static int ideal_exact(const interp_kind *K, const unit_cfg *cfg, const sim_dy *in, sim_dy *out)
{
    sim_dy co[4];
    if (coef_exact(net_of(K, cfg), ref_div3_factor(cfg->terms, cfg->series), in, co)) return -1;
    int bad = 0;
    for (int k = 0; k < cfg->L; k++) {
        sim_dy t, y = co[0];
        sim_dy_double(&t, (double)k / cfg->L);
        for (int j = 1; j <= K->deg; j++) {
            sim_dy_mul(&y, &y, &t);
            sim_dy_add(&y, &y, &co[j]);
        }
        out[k] = y;
        bad |= y.ovf;
    }
    return bad ? -1 : 0;
}

/* Per pixel. Horner schedules: a coefficient's error e_j reaches y times
 * t^(deg-j) <= 1, so y's bound is the sum of the latched coefficients'
 * errors (the network's walk plus the register's quantization) plus the
 * Horner datapath's own bound for coefficients held in the registers'
 * formats (t = k/L is exact: build checks t's format); the same at every
 * pixel. fwd: fwd_errs at pixel k plus y's own quantization. */
static void bound_beats(const interp_kind *K, const unit_cfg *cfg, const unit_fmts *f, double *per_beat)
{
    const unit_desc *u = K->u;
    int L = cfg->L < FWD_MAXK ? cfg->L : FWD_MAXK - 1;
    sim_fmt fy = f->f[unit_sig_must(u, "y")];
    if (cfg->schedule == INTERP_FWD) {
        unit_fmts fm = *f;
        unet_val coef[4], init[4];
        double E[4][FWD_MAXK];
        sim_fmt rf[4];
        if (fwd_values(K, cfg, &fm, 0, coef, init)) { for (int k = 0; k < cfg->L; k++) per_beat[k] = INFINITY; return; }
        for (int j = 0; j <= K->deg; j++) rf[j] = f->f[unit_sig_must(u, fwd_regs[j])];
        fwd_errs(K->deg, L, init, rf, cfg->rnd, E);
        for (int k = 0; k < cfg->L; k++) per_beat[k] = E[0][k < FWD_MAXK ? k : FWD_MAXK - 1] + unit_qerr(fy, rf[0].fbits, cfg->rnd);
        return;
    }
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    for (int i = 0; i < net_of(K, cfg)->nin; i++) in[i] = unet_input(&n, in_names[i], i);
    coef_walk(&n, net_of(K, cfg), in, cfg->terms, cfg->series, o);
    double e = 0;
    sim_fmt rf[4];
    for (int j = 0; j <= K->deg; j++) {
        rf[j] = f->f[unit_sig_must(u, reg_names[j])];
        e += o[j].err + unit_qerr(rf[j], o[j].eff, cfg->rnd);
        /* the Horner walk sees the fraction bits the register really
         * holds (fewer than its format's when the coefficient has fewer) */
        if (o[j].eff < rf[j].fbits) rf[j] = unit_fmt(rf[j].is_signed, rf[j].ibits, o[j].eff < 0 ? 0 : o[j].eff);
    }
    /* t = k/L: lg L fraction bits whatever its format (build checks it holds them) */
    sim_fmt tf = f->f[unit_sig_must(u, "t")];
    int lgL = 0;
    while ((1 << lgL) < cfg->L) lgL++;
    if (tf.fbits > lgL) tf = unit_fmt(tf.is_signed, tf.ibits, lgL);
    e += horner_bound_on(K->deg, cfg->schedule, rf, tf, u, f, fy, cfg->rnd);
    for (int k = 0; k < cfg->L; k++) per_beat[k] = e;
}

/* The port's bound: the largest pixel's (fwd: the last). */
static void bound(const interp_kind *K, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    double b[64];
    unit_cfg c = *cfg;
    if (c.L > 64) c.L = 64;
    bound_beats(K, &c, f, b);
    per_out[0] = 0;
    for (int k = 0; k < c.L; k++) per_out[0] = fmax(per_out[0], b[k]);
}

/* ---------------------------------------------------------- descriptors */

#define INTERP_FNS(sfx, K) \
    static void formats_##sfx(const unit_cfg *cfg, unit_fmts *out) { formats(&K, cfg, out); } \
    static int build_##sfx(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, \
                           const unit_fmts *f, unit_io *io, char *err, size_t errlen) \
    { return build(&K, c, sc, clk, cfg, f, io, err, errlen); } \
    static void ideal_##sfx(const unit_cfg *cfg, const double *in, double *out) { ideal(&K, cfg, in, out); } \
    static void bound_##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { bound(&K, cfg, f, o); } \
    static void beats_##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { bound_beats(&K, cfg, f, o); } \
    static int exact_##sfx(const unit_cfg *cfg, const sim_dy *in, sim_dy *out) { return ideal_exact(&K, cfg, in, out); }

INTERP_FNS(3, k3)
INTERP_FNS(2, k2)

static int in_net(const coef_net *net, const char *name)
{
    for (int i = 0; i < net->nnodes; i++)
        if (!strcmp(net->node[i].name, name)) return 1;
    return 0;
}

/* interp3: an element of either cubic network is built only when it is
 * the chosen node set's; everything else is built for both. */
static int sig_used_3(const unit_cfg *cfg, int i)
{
    const char *nm = unit_interp3.sigs[i].name;
    if (!in_net(&coef_net_n1, nm) && !in_net(&coef_net_n2, nm)) return 1;
    return in_net(cfg->nodes ? &coef_net_n2 : &coef_net_n1, nm);
}

#define P_L { "L", UNIT_P_POW2, offsetof(unit_cfg, L), 2, 32, 8, NULL, "pixels per interval (beats per item)" }
#define P_NODES { "nodes", UNIT_P_ENUM, offsetof(unit_cfg, nodes), 0, 1, 0, "n1 n2", \
                  "node set of the cubic: n1 = I(0), I(1), I(1/2), I(1/4) (the paper's choice); n2 = I(0), I(1), I(1/2), I(3/4)" }
/* N2's own elements (coef3_n2's network), built only with nodes=n2; the
 * names both sets share are described by N1's formulas. */
#define N2_SIG(nm_, wh_) { .name = nm_, .role = UNIT_SIG_INTERNAL, .what = "nodes=n2 only: " wh_ }
#define N2_SIGS \
    N2_SIG("i1x2", "2 I1"), N2_SIG("i1x3", "3 I1 = 2 I1 + I1"), N2_SIG("i2x4", "4 I2"), \
    N2_SIG("i2x5", "5 I2 = 4 I2 + I2"), N2_SIG("i3x16", "16 I3"), N2_SIG("i3x14", "14 I3 = 16 I3 - 2 I3"), \
    N2_SIG("uc", "I2 + 4 I3"), N2_SIG("ucx2", "2 (I2 + 4 I3)"), N2_SIG("ucx3", "3 (I2 + 4 I3)"), \
    N2_SIG("i1x4", "4 I1"), N2_SIG("i1x12", "12 I1 = 8 I1 + 4 I1"), N2_SIG("i1x13", "13 I1 = 12 I1 + I1")
#define REG(nm_, wh_) { .name = nm_, .role = UNIT_SIG_INTERNAL, .what = wh_, .scheds = I_HORNER }
#define T_SIG { .name = "t", .role = UNIT_SIG_INTERNAL, .what = "t = k/L, the pixel counter k with its binary point moved (wiring)", .scheds = I_HORNER }
#define Y_SIG { .name = "y", .role = UNIT_SIG_OUT, .what = "intensity I(k/L) of pixel k, one beat per pixel (the Horner's result; fwd: fy)" }
#define INTERP_RULE(coefs) "i* u1.(W-1); the coefficient network as in the coefficient units; " coefs \
    ", their registers, y and the Horner datapaths s7.(W-7) (the Horner's rule); t and its copies u1.(W-1); " \
    "fwd: start networks lossless, registers fy, fd* W bits with the fewest integer bits (1..7) for their range and error"
#define INTERP_SCHEDS(paper_what, mac, pipe) \
    { { "paper", paper_what }, \
      { "mac", "the Horner as one multiply-add a clock: " mac }, \
      { "pipe", "the Horner fully pipelined, a pixel a clock: " pipe }, \
      { "fwd", "forward differencing with adders only, a pixel a clock: L per item, first pixel 1 clock after the accept" } }

const unit_desc unit_interp3 = {
    .name = "interp3",
    .ref = &ref_model_interp3,
    .summary = "cubic interpolation of a span interval: coef3_n1 + registers + the Fig. 9 Horner, L pixels per item",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV, Figs. 8 and 9",
    UNIT_SIGS(COEF_SIGS_I123, { .name = "i4", .role = UNIT_SIG_IN, .what = "I4 = I(1/4) (nodes=n1) or I(3/4) (nodes=n2)" },
              Y_SIG,
              COEF3_N1_NET(COEF_SIG_INT, COEF_SIG_INT) N2_SIGS,
              REG("ra", "register of A, loaded when an item is accepted"),
              REG("rb", "register of B"), REG("rc", "register of C"), REG("rd", "register of D"),
              T_SIG, HORNER_SIGS3,
              FWD3_NET(FWD_SIG) FWD_REGS3),
    .nsched = 4,
    .sched = INTERP_SCHEDS("coefficients once per item, then the paper's Horner sequence: 6 clocks per pixel, 6L per item",
                           "3 clocks per pixel, 3L per item", "L per item, first pixel 4 clocks after the accept"),
    .nparams = 4, .params = { P_L, DIV3_P_TERMS, DIV3_P_SERIES, P_NODES },
    .fmt_rule = INTERP_RULE("a b c d"),
    .formats = formats_3, .beats = beats, .build = build_3, .ideal = ideal_3, .bound = bound_3, .ideal_exact = exact_3,
    .bound_beats = beats_3, .sig_used = sig_used_3,
};

const unit_desc unit_interp2 = {
    .name = "interp2",
    .ref = &ref_model_interp2,
    .summary = "quadratic interpolation of a span interval: coef2 + registers + the Horner cut to degree 2, L pixels per item",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV, Fig. 9 (degree 2)",
    UNIT_SIGS(COEF_SIGS_I123, Y_SIG,
              COEF2_NET(COEF_SIG_INT, COEF_SIG_INT)
              REG("ra", "register of A, loaded when an item is accepted"),
              REG("rb", "register of B"), REG("rc", "register of C"),
              T_SIG, HORNER_SIGS2,
              FWD2_NET(FWD_SIG) FWD_REGS2),
    .nsched = 4,
    .sched = INTERP_SCHEDS("coefficients once per item, then the Horner sequence cut to degree 2: 4 clocks per pixel, 4L per item",
                           "2 clocks per pixel, 2L per item", "L per item, first pixel 3 clocks after the accept"),
    .nparams = 1, .params = { P_L },
    .fmt_rule = INTERP_RULE("a b c"),
    .formats = formats_2, .beats = beats, .build = build_2, .ideal = ideal_2, .bound = bound_2, .ideal_exact = exact_2,
    .bound_beats = beats_2,
};
