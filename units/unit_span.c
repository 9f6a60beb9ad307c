/* unit_span.c - interpolation along a raster span with intervals of any
 * length: the units a scene drives (span1, span2, span3, span23).
 *
 *   i1..i4 -> [coef] -> a b c d -> ra rb rc rd (latched when an item is
 *   accepted) -> [Horner] -> y, one pixel t = k/dv per Horner pass
 *   n, dv -> rn, rdv (latched) ; rdv -> [1/dv ROM] -> rcp ; t = k * rcp
 *
 * An item is one interval: its node intensities, its pixel count n
 * (1..L) and its divisor dv (pixel k has t = k/dv; a scene gives dv = L
 * for a full interval and n - 1 for a span's last one). The unit gives n
 * beats, pixels k = 0..n-1, and takes the next item in the last step of
 * the last pixel, so back-to-back items cost exactly steps * n clocks each
 * (as interp3/interp2, whose structure this generalizes: unit_interp.c).
 *
 * t is made by hardware, not wiring: a ROM of the L reciprocals 1/dv and a
 * small multiplier k * rcp (k has ceil(log2(L+1)) bits). The ROM holds
 * 1/dv rounded down to its format, which keeps G = ceil(log2(L+1)) guard
 * bits beyond t's, so that k * rcp <= k/dv <= 1 (t never passes 1, which
 * the Horner's bound needs) and k * (1/dv - rcp) < one LSB of t. Where dv
 * is a power of two 2^j the ROM word is exact and t = k 2^-j is exact when
 * t has j fraction bits.
 *
 * span23 is the adaptive unit: the quadratic and the cubic coefficient
 * networks side by side, one Horner datapath. A degree-2 item runs the
 * quadratic's sequence, which is the first 4 (paper) or 2 (mac) steps of
 * the cubic's with A2 B2 C2 in the places of A B C, so it takes the
 * quadratic's clocks per pixel; the pipe takes (0, A2, B2, C2) through its
 * three stages (a pixel a clock either way). Its paper and mac controllers
 * are the Horner's own of degree 2 and 3 (unit_horner.h), each running
 * for its items, their decoders selected by the item's degree.
 *
 * span1 is linear, I1 + (I2 - I1) t: the Horner datapath has no degree 1,
 * so it has its own multiply-add: paper the Fig. 9 elements at degree 1
 * (RG <= B, then RG <= A t + RG: 2 clocks a pixel), mac and pipe one
 * multiply-add a clock (at degree 1 they are the same datapath).
 *
 * Error bound (docs/bounds.md): the ideal is the polynomial through the
 * held nodes, with the network's 1/3, at the exact t = k/dv; the bound
 * adds to the coefficient and datapath errors (as interp) the effect of
 * t's quantization, max |p'| * max |t_hw - k/dv|, with max |p'| over every
 * node value the input formats hold, by interval arithmetic.
 */
#include "units/unit_coef.h"
#include "units/unit_horner.h"
#include "vectors/ref_seed000.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

#define SPAN_LMAX 64

enum { K_LIN = 1, K_QUAD = 2, K_CUBE = 3, K_ADAPT = 23 };

typedef struct span_kind {
    const unit_desc *u;
    int kind;           /* K_LIN, K_QUAD, K_CUBE, K_ADAPT */
    int nin;            /* node inputs i1.. */
} span_kind;

static const char *const in_names[] = { "i1", "i2", "i3", "i4" };
static const char *const coef_names[] = { "a", "b", "c", "d" };
static const char *const reg_names[] = { "ra", "rb", "rc", "rd" };

/* ------------------------------------------------------------ networks */

/* span1: A = I2 - I1, B = I1. */
static void formula_lin(const double *I, double th, double *o)
{
    (void)th;
    o[0] = I[1] - I[0];
    o[1] = I[0];
}
static const coef_node lin_nodes[] = {
    { "a", COEF_SUB, "i2", "i1", 0, 1 },
    { "b", COEF_SHL, "i1", "_", 0, 1 },
};
static const coef_net net_lin = { 2, 2, 2, lin_nodes, formula_lin };

/* span23's quadratic network: coef2's, its elements named q_<name> so that
 * they do not clash with the cubic's (a, b, c, i3x4, qb are in both). The
 * operand names map through SQ_<name>: inputs stay, elements get q_. */
#define SQ_i1 "i1"
#define SQ_i2 "i2"
#define SQ_i3 "i3"
#define SQ__ "_"
#define SQ_s12 "q_s12"
#define SQ_s12x2 "q_s12x2"
#define SQ_i3x4 "q_i3x4"
#define SQ_a "q_a"
#define SQ_i1x2 "q_i1x2"
#define SQ_i1x3 "q_i1x3"
#define SQ_qb "q_qb"
#define SQ_b "q_b"
#define SQ_c "q_c"
#define SQ_NODE_X(name, op, a, b, k, what) { "q_" #name, COEF_##op, SQ_##a, SQ_##b, k, 0 },
#define SQ_NODE_O(name, op, a, b, k, what) { "q_" #name, COEF_##op, SQ_##a, SQ_##b, k, 1 },
#define SQ_SIG(name, op, a, b, k, what) { "q_" #name, UNIT_SIG_INTERNAL, "quadratic network: " what, 0 },
#define S_NET(name, op, a, b, k, what) { #name, UNIT_SIG_INTERNAL, what, 0 },
static const coef_node q2_nodes[] = { COEF2_NET(SQ_NODE_X, SQ_NODE_O) };
static void formula_q2(const double *I, double th, double *o)
{
    (void)th;
    o[0] = 2 * I[0] + 2 * I[1] - 4 * I[2];
    o[1] = 4 * I[2] - 3 * I[0] - I[1];
    o[2] = I[0];
}
static const coef_net net_q2 = { 3, 3, COEF2_NODES, q2_nodes, formula_q2 };

/* The network of the unit's (main) degree, and for span23 the quadratic. */
static const coef_net *main_net(const span_kind *K, const unit_cfg *cfg)
{
    switch (K->kind) {
    case K_LIN: return &net_lin;
    case K_QUAD: return &coef_net_q;
    default: return cfg->nodes ? &coef_net_n2 : &coef_net_n1;
    }
}
static int main_deg(const span_kind *K) { return K->kind == K_ADAPT ? 3 : K->kind; }

/* -------------------------------------------------------------- helpers */

/* Bits of k = 0..L, of n and dv: ceil(log2(L+1)). */
static int kbits(int L) { int b = 1; while ((1 << b) < L + 1) b++; return b; }
static int sig(const span_kind *K, const char *name) { return unit_sig_index(K->u, name); }
static int valid_L(int L) { return L >= 2 && L <= SPAN_LMAX; }

/* ------------------------------------------------------------- formats */

/* Walk a network to choose its formats (rule) into n. */
static void rule_walk(unet *n, const coef_net *net, const unit_cfg *cfg)
{
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    for (int i = 0; i < net->nin; i++) in[i] = unet_input(n, in_names[i], i);
    coef_walk(n, net, in, cfg->terms, cfg->series, o);
}

/* The rule: inputs i* u1.(W-1), n and dv u<G>.0 (G = ceil(log2(L+1))),
 * deg u2.0; the coefficient networks as in the coefficient units (lossless
 * internals); degree >= 2: coefficients, their registers, y and the Horner
 * datapath s7.(W-7) (the Horner's rule); span1: a, ra, y and its datapath
 * s2.(W-2) (|A| <= 1, A t + B in [0, 1]), b and rb u1.(W-1); t u1.(W-1);
 * rcp u1.(W-1+G). */
static void formats(const span_kind *K, const unit_cfg *cfg, unit_fmts *out)
{
    static const double lo[UNET_MAXIN] = { 0, 0, 0, 0 }, hi[UNET_MAXIN] = { 1, 1, 1, 1 };
    const unit_desc *u = K->u;
    int W = cfg->width, L = valid_L(cfg->L) ? cfg->L : 8, G = kbits(L);
    unet n;
    unet_init(&n, u, NULL, cfg->rnd);
    unet_rule(&n, W, lo, hi, K->nin);
    for (int i = 0; i < K->nin; i++) n.fm.f[sig(K, in_names[i])] = coef_input_fmt(W);
    n.fm.f[sig(K, "n")] = unit_fmt(0, G, 0);
    n.fm.f[sig(K, "dv")] = unit_fmt(0, G, 0);
    if (K->kind == K_ADAPT) n.fm.f[sig(K, "deg")] = unit_fmt(0, 2, 0);
    /* span3/span23 declare both cubic networks' elements; the other node
     * set's own ones are not built (sig_used) and keep no format. */
    rule_walk(&n, main_net(K, cfg), cfg);
    if (K->kind == K_ADAPT) rule_walk(&n, &net_q2, cfg);
    int deg = main_deg(K);
    sim_fmt dp = deg == 1 ? unit_fmt(1, 2, W - 2) : unit_fmt(1, HORNER_IBITS, W - HORNER_IBITS);
    for (int j = 0; j <= deg; j++) {
        sim_fmt f = deg == 1 && j == 1 ? coef_input_fmt(W) : dp;
        n.fm.f[sig(K, coef_names[j])] = f;
        n.fm.f[sig(K, reg_names[j])] = f;
    }
    n.fm.f[sig(K, "t")] = unit_fmt(0, 1, W - 1);
    n.fm.f[sig(K, "rcp")] = unit_fmt(0, 1, W - 1 + G);
    n.fm.f[sig(K, "y")] = dp;
    if (deg == 1) {
        static const char *const dpn[] = { "mul", "mx2", "bk", "sm", "rg" };
        for (int i = 0; i < 5; i++) n.fm.f[sig(K, dpn[i])] = dp;
    } else {
        horner_default_fmts(u, deg, W, &n.fm);
    }
    *out = n.fm;
}

static int beats(const unit_cfg *cfg) { return valid_L(cfg->L) ? cfg->L : 8; }

static int in_net(const coef_net *net, const char *name)
{
    for (int i = 0; i < net->nnodes; i++)
        if (!strcmp(net->node[i].name, name)) return 1;
    return 0;
}

/* span3, span23: an element of either cubic network is built only when
 * it is one of the chosen node set's (n1's i1x7 or n2's i1x2 are not in
 * the other); everything else (ports, registers, t, the Horner datapath,
 * span23's quadratic network) is built for both. */
static int cube_sig_used(const span_kind *K, const unit_cfg *cfg, int i)
{
    const char *nm = K->u->sigs[i].name;
    if (!in_net(&coef_net_n1, nm) && !in_net(&coef_net_n2, nm)) return 1;
    return in_net(cfg->nodes ? &coef_net_n2 : &coef_net_n1, nm);
}

/* ---------------------------------------------------- the reciprocal ROM */

typedef struct rcp_rom {
    int L;
    int64_t raw[SPAN_LMAX + 1];     /* raw[dv], dv = 1..L; raw[0] = 0 (dv = 0: only t = 0 is asked) */
} rcp_rom;

/* 1/dv rounded down to format f (its largest value at most 1/dv), for
 * dv = 1..L: rounding down keeps k * rcp <= k/dv. */
static void rom_fill(rcp_rom *r, int L, sim_fmt f)
{
    memset(r, 0, sizeof *r);
    r->L = L;
    int64_t mx = sim_fmt_raw_max(f);
    for (int dv = 1; dv <= L && dv <= SPAN_LMAX; dv++) {
        sim_wide one = f.fbits >= 0 ? (sim_wide)1 << f.fbits : 0;
        sim_wide q = one / dv;
        r->raw[dv] = q > mx ? mx : (int64_t)q;
    }
}

/* in: dv. The ROM's word. */
static int64_t f_rom(const int64_t *in, void *user)
{
    const rcp_rom *r = user;
    return in[0] >= 0 && in[0] <= r->L ? r->raw[in[0]] : 0;
}

/* t's error and fraction bits for a ROM of format frcp: t_hw = Q_t(k rcp)
 * differs from k/dv by k (1/dv - rcp) (at most its largest at k = dv, *rom)
 * plus t's own quantization from the fraction bits k rcp really has, at
 * most those of the ROM's words (*src: the most any word has). */
static void rom_err(const unit_cfg *cfg, sim_fmt frcp, double *rom, int *src)
{
    int L = valid_L(cfg->L) ? cfg->L : 8;
    rcp_rom r;
    rom_fill(&r, L, frcp);
    *rom = 0;
    *src = 0;
    for (int dv = 1; dv <= L; dv++) {
        /* dv (1/dv - w) = (2^F - dv raw) 2^-F, the numerator exact in 128 bits */
        sim_wide num = ((sim_wide)1 << frcp.fbits) - (sim_wide)dv * r.raw[dv];
        *rom = fmax(*rom, ldexp(fabs((double)num), -frcp.fbits));
        int fb = frcp.fbits;
        for (int64_t x = r.raw[dv]; x && !(x & 1) && fb > 0; x >>= 1) fb--;
        if (r.raw[dv] && fb > *src) *src = fb;
    }
}

/* ------------------------------------------------------------- control */

/* The fraction bits of an integer input's format (f_is2 drops them). */
typedef struct int_in { int fbits; } int_in;

/* in: k, rn. The item's last pixel: k + 1 >= n (n = 0 counts as 1). */
static int64_t f_kend(const int64_t *in, void *u) { (void)u; return in[0] + 1 >= in[1]; }
/* in: busy, kend, last. Ready when idle or in the last step of the last pixel. */
static int64_t f_ready(const int64_t *in, void *u) { (void)u; return !in[0] || (in[1] && in[2]); }
static int64_t f_and(const int64_t *in, void *u) { (void)u; return in[0] && in[1]; }
static int64_t f_andn(const int64_t *in, void *u) { (void)u; return in[0] && !in[1]; }
/* in: k, kend, last. */
static int64_t f_k_next(const int64_t *in, void *u) { (void)u; return in[2] ? (in[1] ? 0 : in[0] + 1) : in[0]; }
/* in: accept, busy, kend, last. */
static int64_t f_busy_next(const int64_t *in, void *u)
{
    (void)u;
    return in[0] || (in[1] && !(in[2] && in[3]));
}
/* in: deg (raw, fbits in user). 1 for a degree-2 item. */
static int64_t f_is2(const int64_t *in, void *u)
{
    const int_in *q = u;
    return (q->fbits >= 0 ? in[0] >> q->fbits : in[0]) == 2;
}
/* span1 paper, in: step, run. Two steps a pixel; waits at 0. */
static int64_t f_step1(const int64_t *in, void *u) { (void)u; return in[0] ? 0 : in[1] != 0; }
static int64_t f_copy(const int64_t *in, void *u) { (void)u; return in[0]; }
static int64_t f_not(const int64_t *in, void *u) { (void)u; return !in[0]; }

typedef struct span_ctl {
    sim_signal *busy, *k, *rn, *rdv, *kend, *accept;
} span_ctl;

/* A register that loads x on accept and holds otherwise (its load mux
 * built once accept exists: hold_connect). */
static sim_signal *hold_reg(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt f, sim_signal *clk)
{
    return sim_reg(c, sc, name, f, clk, NULL, NULL, NULL, 0);
}
static void hold_connect(sim_ctx *c, sim_scope *sc, const char *name, sim_signal *r, sim_signal *accept,
                         sim_signal *x)
{
    sim_signal *in[2] = { r, x };
    sim_reg_connect(r, sim_mux(c, sc, name, r->fmt, accept, 2, in));
}

/* The item's state: busy, the pixel counter k, n and dv latched. */
static void state_regs(sim_ctx *c, sim_scope *sc, sim_signal *clk, int G, span_ctl *ctl)
{
    sim_fmt fk = unit_fmt(0, G, 0);
    ctl->busy = sim_reg(c, sc, "busy", unit_fmt(0, 1, 0), clk, NULL, NULL, NULL, 0);
    ctl->k = sim_reg(c, sc, "k", fk, clk, NULL, NULL, NULL, 0);
    ctl->rn = hold_reg(c, sc, "rn", fk, clk);
    ctl->rdv = hold_reg(c, sc, "rdv", fk, clk);
    sim_signal *ke_in[2] = { ctl->k, ctl->rn };
    /* a G-bit comparator: about a full adder a bit */
    ctl->kend = sim_logic(c, sc, "kend", unit_fmt(0, 1, 0), 2, ke_in, f_kend, NULL, G * SIM_GE_FA);
}

/* in_ready, accept, the next k and busy around `last` (1 in the clock a
 * pixel's last step runs); n and dv load on an accept. */
static void control(sim_ctx *c, sim_scope *sc, int G, sim_signal *last, sim_signal *n_in, sim_signal *dv_in,
                    unit_io *io, span_ctl *ctl)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *rdy_in[3] = { ctl->busy, ctl->kend, last };
    io->in_ready = sim_logic(c, sc, "in_ready", u1, 3, rdy_in, f_ready, NULL, 2 * SIM_GE_NAND2);
    sim_signal *acc_in[2] = { io->in_valid, io->in_ready };
    ctl->accept = sim_logic(c, sc, "accept", u1, 2, acc_in, f_and, NULL, SIM_GE_AND2);
    sim_signal *kn_in[3] = { ctl->k, ctl->kend, last };
    /* an incrementer, a clear and an enable mux a bit */
    sim_reg_connect(ctl->k, sim_logic(c, sc, "k_next", ctl->k->fmt, 3, kn_in, f_k_next, NULL,
                                      G * (SIM_GE_HA + SIM_GE_AND2 + SIM_GE_MUX2)));
    sim_signal *bn_in[4] = { ctl->accept, ctl->busy, ctl->kend, last };
    sim_reg_connect(ctl->busy, sim_logic(c, sc, "busy_next", u1, 4, bn_in, f_busy_next, NULL, 3 * SIM_GE_NAND2));
    hold_connect(c, sc, "rn_in", ctl->rn, ctl->accept, n_in);
    hold_connect(c, sc, "rdv_in", ctl->rdv, ctl->accept, dv_in);
}

/* ------------------------------------------------------------ datapaths */

enum { SP_PAPER = HORNER_PAPER, SP_MAC = HORNER_MAC, SP_PIPE = HORNER_PIPE };

/* span1's multiply-add. paper: step 0 RG <= B (MX2 = B, BK zero), step 1
 * RG <= A t + RG (MX2 = MUL, BK passes); mac and pipe: RG <= A t + B every
 * clock. Returns the result register; *last is 1 in the clock a pixel's
 * last step runs (the register holds the pixel after that edge). */
static sim_signal *dp_lin(sim_ctx *c, sim_scope *sc, sim_signal *clk, int sched, sim_signal *run,
                          sim_signal *ra, sim_signal *rb, sim_signal *t, const span_kind *K,
                          const unit_fmts *f, sim_signal **last)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *rg = sim_reg(c, sc, "rg", f->f[sig(K, "rg")], clk, NULL, NULL, NULL, 0);
    sim_signal *mul = sim_mul(c, sc, "mul", f->f[sig(K, "mul")], ra, t);
    if (sched == SP_PAPER) {
        sim_signal *step = sim_reg(c, sc, "step", u1, clk, NULL, NULL, NULL, 0);
        sim_signal *nx_in[2] = { step, run };
        sim_reg_connect(step, sim_logic(c, sc, "step_next", u1, 2, nx_in, f_step1, NULL, 2 * SIM_GE_NAND2));
        /* step 1 selects MUL and passes RG: the step bit is both selects */
        sim_signal *mx2_sel = sim_logic(c, sc, "mx2_sel", u1, 1, &step, f_not, NULL, SIM_GE_INV);
        sim_signal *bk_pass = sim_logic(c, sc, "bk_pass", u1, 1, &step, f_copy, NULL, 0);
        sim_signal *mx2_in[2] = { mul, rb };
        sim_signal *mx2 = sim_mux(c, sc, "mx2", f->f[sig(K, "mx2")], mx2_sel, 2, mx2_in);
        sim_signal *bk = sim_bk(c, sc, "bk", f->f[sig(K, "bk")], bk_pass, rg);
        sim_reg_connect(rg, sim_add(c, sc, "sm", f->f[sig(K, "sm")], mx2, bk));
        *last = sim_logic(c, sc, "last", u1, 1, &step, f_copy, NULL, 0);
    } else {
        sim_reg_connect(rg, sim_add(c, sc, "sm", f->f[sig(K, "sm")], mul, rb));
        *last = run;
    }
    return rg;
}

/* span23's paper and mac controller: the Horner's controllers of degree 2
 * and 3, each run by its own items (run && is2, run && !is2), their
 * decoders selected by the item's degree. Both rest at step 0 between
 * their items, so the switch needs no gap. */
static void ctl_adapt(sim_ctx *c, sim_scope *hsc, sim_signal *clk, int sched, sim_signal *run, sim_signal *is2,
                      horner_hw *hw)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *r2_in[2] = { run, is2 };
    sim_signal *run2 = sim_logic(c, hsc, "run2", u1, 2, r2_in, f_and, NULL, SIM_GE_AND2);
    sim_signal *run3 = sim_logic(c, hsc, "run3", u1, 2, r2_in, f_andn, NULL, SIM_GE_AND2 + SIM_GE_INV);
    horner_hw h2, h3;
    horner_ctl_on(c, sim_scope_new(c, hsc, "ctl2"), clk, 2, sched, run2, "last", &h2);
    horner_ctl_on(c, sim_scope_new(c, hsc, "ctl3"), clk, 3, sched, run3, "last", &h3);
    *hw = h3;
    sim_signal *in[2];
    in[0] = h3.mx1_sel; in[1] = h2.mx1_sel;
    hw->mx1_sel = sim_mux(c, hsc, "mx1_sel", h3.mx1_sel->fmt, is2, 2, in);
    in[0] = h3.mx2_sel; in[1] = h2.mx2_sel;
    hw->mx2_sel = sim_mux(c, hsc, "mx2_sel", h3.mx2_sel->fmt, is2, 2, in);
    if (sched == SP_PAPER) {
        in[0] = h3.bk_pass; in[1] = h2.bk_pass;
        hw->bk_pass = sim_mux(c, hsc, "bk_pass", u1, is2, 2, in);
    }
    in[0] = h3.last; in[1] = h2.last;
    hw->last = sim_mux(c, hsc, "last", u1, is2, 2, in);
}

/* --------------------------------------------------------------- build */

static int build(const span_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                 const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    const unit_desc *u = K->u;
    int L = cfg->L, sched = cfg->schedule, deg = main_deg(K);
    if (!valid_L(L)) { snprintf(err, errlen, "%s: L = %d is outside 2..%d", u->name, L, SPAN_LMAX); return -1; }
    if (sched < 0 || sched >= u->nsched) { snprintf(err, errlen, "%s: no schedule %d", u->name, sched); return -1; }
    if (cfg->nodes < 0 || cfg->nodes > 1) { snprintf(err, errlen, "%s: no node set %d", u->name, cfg->nodes); return -1; }
    sim_fmt ft = f->f[sig(K, "t")], frcp = f->f[sig(K, "rcp")];
    if (sim_fmt_real_max(ft) < 1 || sim_fmt_real_max(frcp) < 1.0 / L) {
        char b1[SIM_FMT_STRLEN], b2[SIM_FMT_STRLEN];
        snprintf(err, errlen, "%s: t format %s must hold 1 and rcp format %s 1/L = 1/%d", u->name,
                 sim_fmt_str(ft, b1), sim_fmt_str(frcp, b2), L);
        return -1;
    }
    static const char *const ints[] = { "n", "dv", "deg" };
    for (int i = 0; i < (K->kind == K_ADAPT ? 3 : 2); i++) {
        sim_fmt fi = f->f[sig(K, ints[i])];
        int need = i < 2 ? L : 3;
        if (sim_fmt_real_max(fi) < need) {
            char b[SIM_FMT_STRLEN];
            snprintf(err, errlen, "%s: %s format %s cannot hold %d", u->name, ints[i], sim_fmt_str(fi, b), need);
            return -1;
        }
    }
    int G = kbits(L);
    sim_fmt u1 = unit_fmt(0, 1, 0);
    const coef_net *net = main_net(K, cfg);

    /* Inputs, in the descriptor's order, and the coefficient networks. */
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN], q[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    unet_hw(&n, c, sc);
    for (int i = 0; i < K->nin; i++) {
        in[i] = unet_input(&n, in_names[i], i);
        io->in[i] = in[i].s;
    }
    sim_signal *n_in = sim_signal_new(c, sc, "n", f->f[sig(K, "n")], SIM_KIND_INPUT);
    sim_signal *dv_in = sim_signal_new(c, sc, "dv", f->f[sig(K, "dv")], SIM_KIND_INPUT);
    io->in[K->nin] = n_in;
    io->in[K->nin + 1] = dv_in;
    sim_signal *is2_in = NULL;
    if (K->kind == K_ADAPT) {
        sim_fmt fd = f->f[sig(K, "deg")];
        io->in[K->nin + 2] = sim_signal_new(c, sc, "deg", fd, SIM_KIND_INPUT);
        int_in *qi = sim_alloc(c, sizeof *qi);
        qi->fbits = fd.fbits;
        is2_in = sim_logic(c, sc, "is2", u1, 1, &io->in[K->nin + 2], f_is2, qi, fd.width * SIM_GE_AND2);
    }
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    n.sc = sim_scope_new(c, sc, "coef");
    if (coef_walk(&n, net, in, cfg->terms, cfg->series, o)) { snprintf(err, errlen, "%s", n.why); return -1; }
    if (K->kind == K_ADAPT && coef_walk(&n, &net_q2, in, cfg->terms, cfg->series, q)) {
        snprintf(err, errlen, "%s", n.why);
        return -1;
    }

    /* Control, the Horner's controller (or span1's), t. */
    span_ctl ctl;
    state_regs(c, sc, clk, G, &ctl);
    sim_scope *hsc = sim_scope_new(c, sc, deg == 1 ? "dp" : "horner");
    horner_hw hw;
    memset(&hw, 0, sizeof hw);
    sim_signal *rdeg = NULL, *last = NULL;
    if (K->kind == K_ADAPT) {
        rdeg = hold_reg(c, sc, "rdeg", u1, clk);
        if (sched == SP_PIPE) horner_ctl_on(c, hsc, clk, 3, sched, ctl.busy, "last", &hw);
        else ctl_adapt(c, hsc, clk, sched, ctl.busy, rdeg, &hw);
        last = hw.last;
    } else if (deg >= 2) {
        horner_ctl_on(c, hsc, clk, deg, sched, ctl.busy, "last", &hw);
        last = hw.last;
    } else if (sched == SP_PAPER) {
        /* span1 paper: the controller is part of dp_lin; its `last` is
         * needed by the control first, so a wire driven later */
        last = sim_signal_new(c, hsc, "last_w", u1, SIM_KIND_WIRE);
    } else {
        last = ctl.busy;
    }
    control(c, sc, G, last, n_in, dv_in, io, &ctl);
    if (rdeg) hold_connect(c, sc, "rdeg_in", rdeg, ctl.accept, is2_in);

    rcp_rom *rom = sim_alloc(c, sizeof *rom);
    rom_fill(rom, L, frcp);
    sim_signal *rcp = sim_logic(c, sc, "rcp", frcp, 1, &ctl.rdv, f_rom, rom,
                                sim_area_rom(rom->raw + 1, L, frcp.width));
    sim_signal *t = sim_mul(c, sc, "t", ft, ctl.k, rcp);

    /* Coefficient registers, loaded on an accept. */
    sim_signal *r[4];
    for (int j = 0; j <= deg; j++) {
        sim_fmt rf = f->f[sig(K, reg_names[j])];
        sim_signal *d = o[j].s;
        if (K->kind == K_ADAPT) {
            /* paper, mac: A2 B2 C2 in A B C's places (D unused); pipe:
             * (0, A2, B2, C2) through the cubic stages */
            sim_signal *q2 = NULL;
            if (sched == SP_PIPE) q2 = j == 0 ? sim_const_raw(c, sc, "zero", rf, 0) : q[j - 1].s;
            else if (j < 3) q2 = q[j].s;
            if (q2) {
                char nm[8];
                snprintf(nm, sizeof nm, "m%s", coef_names[j]);
                sim_signal *mx_in[2] = { d, q2 };
                d = sim_mux(c, sc, nm, rf, is2_in, 2, mx_in);
            }
        }
        r[j] = sim_reg(c, sc, reg_names[j], rf, clk, d, ctl.accept, NULL, 0);
    }

    sim_signal *res, *done;
    if (deg == 1) {
        sim_signal *lst = NULL;
        res = dp_lin(c, hsc, clk, sched, ctl.busy, r[0], r[1], t, K, f, &lst);
        if (sched == SP_PAPER) sim_assign(c, last, lst);
        done = sched == SP_PAPER ? lst : ctl.busy;
    } else {
        horner_dp_on(c, hsc, clk, &hw, ctl.busy, r, t, u, f);
        res = hw.rg;
        done = hw.done;
    }
    io->out[0] = sim_shift(c, sc, "y", f->f[sig(K, "y")], res, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", u1, clk, done, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}

/* ------------------------------------------------------------- ideal */

/* The polynomial through the held nodes (network's 1/3) at t = k/dv, k =
 * 0..L-1 (pixels past n follow the same polynomial). */
static void ideal(const span_kind *K, const unit_cfg *cfg, const double *in, double *out)
{
    int L = beats(cfg), deg = main_deg(K);
    const coef_net *net = main_net(K, cfg);
    double dv = floor(in[K->nin + 1]);
    if (K->kind == K_ADAPT && floor(in[K->nin + 2]) == 2) { net = &net_q2; deg = 2; }
    double co[4];
    net->formula(in, ref_div3_factor(cfg->terms, cfg->series), co);
    for (int k = 0; k < L; k++) {
        double t = dv > 0 ? k / dv : 0, y = co[0];
        for (int j = 1; j <= deg; j++) y = y * t + co[j];
        out[k] = y;
    }
}

/* The same exactly, as a ratio (k/dv is not dyadic): with co_j the
 * coefficients (dyadic: the network's factor is a sum of powers of two),
 * p(k/dv) = sum_j co_j k^(deg-j) dv^j / dv^deg. dv = 0 gives t = 0 as
 * ideal does (den 1, num the constant coefficient). */
static int ideal_ratio(const span_kind *K, const unit_cfg *cfg, const sim_dy *in, sim_dy *num, sim_dy *den)
{
    int L = beats(cfg), deg = main_deg(K);
    const coef_net *net = main_net(K, cfg);
    double dvd = floor(sim_dy_to_double(&in[K->nin + 1]));
    if (K->kind == K_ADAPT && floor(sim_dy_to_double(&in[K->nin + 2])) == 2) { net = &net_q2; deg = 2; }
    if (!(dvd >= 0 && dvd <= 1e9)) return -1;
    int64_t dv = (int64_t)dvd;
    sim_dy co[4], vdv, vden;
    if (coef_exact(net, ref_div3_factor(cfg->terms, cfg->series), in, co)) return -1;
    sim_dy_int(&vdv, dv > 0 ? dv : 1, 0);
    sim_dy_int(&vden, 1, 0);
    for (int j = 0; j < deg; j++) sim_dy_mul(&vden, &vden, &vdv);
    int bad = vden.ovf;
    for (int k = 0; k < L; k++) {
        /* Horner in k and dv: y = co_0; y = y k + co_j dv^j */
        sim_dy y = co[0], kk, pw = vdv, term;
        sim_dy_int(&kk, dv > 0 ? k : 0, 0);
        for (int j = 1; j <= deg; j++) {
            sim_dy_mul(&y, &y, &kk);
            sim_dy_mul(&term, &co[j], &pw);
            sim_dy_add(&y, &y, &term);
            sim_dy_mul(&pw, &pw, &vdv);
        }
        num[k] = y;
        den[k] = vden;
        bad |= y.ovf;
    }
    return bad ? -1 : 0;
}

/* --------------------------------------------------------------- bound */

/* Range of g(x) = c2 x^2 + c1 x + c0 over [u, v]. */
static void quad_range(double c2, double c1, double c0, double u, double v, double *lo, double *hi)
{
    double a = (c2 * u + c1) * u + c0, b = (c2 * v + c1) * v + c0;
    *lo = fmin(a, b);
    *hi = fmax(a, b);
    if (c2 != 0) {
        double x = -c1 / (2 * c2);
        if (x > u && x < v) {
            double m = (c2 * x + c1) * x + c0;
            *lo = fmin(*lo, m);
            *hi = fmax(*hi, m);
        }
    }
}

/* An upper bound on |p'(x)| for x in [0, 1] and every input I_i in
 * [lo_i, hi_i], p(x) = sum_j coef_j x^(deg-j) with coef_j = coef[j].lin . I:
 * p'(x) = sum_i I_i g_i(x), each g_i a polynomial of degree deg-1 <= 2.
 * Interval arithmetic on 512 pieces of [0, 1]: on each, g_i's exact range
 * times I_i's range, summed; sound, and within a few percent of the true
 * maximum. */
static double deriv_max(int deg, const unet_val *coef, const double *lo, const double *hi, int nin)
{
    enum { PIECES = 512 };
    double best = 0;
    for (int p = 0; p < PIECES; p++) {
        double u = (double)p / PIECES, v = (double)(p + 1) / PIECES, slo = 0, shi = 0;
        for (int i = 0; i < nin; i++) {
            double c[3] = { 0, 0, 0 };     /* c2 c1 c0 of g_i */
            for (int j = 0; j < deg; j++) c[3 - (deg - j)] = (deg - j) * coef[j].lin[i];
            double gl, gh;
            quad_range(c[0], c[1], c[2], u, v, &gl, &gh);
            double pr[4] = { lo[i] * gl, lo[i] * gh, hi[i] * gl, hi[i] * gh };
            double mn = pr[0], mx = pr[0];
            for (int k = 1; k < 4; k++) { mn = fmin(mn, pr[k]); mx = fmax(mx, pr[k]); }
            slo += mn;
            shi += mx;
        }
        best = fmax(best, fmax(fabs(slo), fabs(shi)));
    }
    return best * (1 + 1e-9);      /* the double roundings of the sums above */
}

/* A value as the datapath walks see it (as unit_horner.c's h_val): its
 * worst-case error and the fraction bits it can really have, so that a
 * quantization counts only the bits it drops below those (widening a
 * signal moves a truncation downstream instead of adding one). */
typedef struct sp_val { double e; int eff; } sp_val;

static int imin(int a, int b) { return a < b ? a : b; }
static int imax(int a, int b) { return a > b ? a : b; }

/* v into format f. */
static sp_val sp_pass(sp_val v, sim_fmt f, sim_round r)
{
    return (sp_val){ v.e + unit_qerr(f, v.eff, r), imin(f.fbits, v.eff) };
}
/* a + b into format f. */
static sp_val sp_add(sp_val a, sp_val b, sim_fmt f, sim_round r)
{
    return sp_pass((sp_val){ a.e + b.e, imax(a.eff, b.eff) }, f, r);
}

/* span1's datapath error for coefficients exact in ra, rb with fa_eff,
 * fb_eff fraction bits and t exact with ft_eff: the quantizations of its
 * elements (as the Horner's bound walks its table; multiplying by t in
 * [0, 1] does not grow an error). paper: RG <= MX2(B) + 0, then RG <=
 * MX2(MUL) + BK(RG); mac and pipe: RG <= MUL + RB. */
static double lin_dp_bound(const span_kind *K, int sched, const unit_fmts *f, int fa_eff, int fb_eff,
                           int ft_eff, sim_round r)
{
    sim_fmt fmul = f->f[sig(K, "mul")], fsm = f->f[sig(K, "sm")], frg = f->f[sig(K, "rg")], fy = f->f[sig(K, "y")];
    sp_val mul = sp_pass((sp_val){ 0, fa_eff + ft_eff }, fmul, r), b = { 0, fb_eff }, rg;
    if (sched == SP_PAPER) {
        sim_fmt fmx2 = f->f[sig(K, "mx2")], fbk = f->f[sig(K, "bk")];
        sp_val zero = { 0, -64 };           /* BK forcing zero: exact, no fraction bits */
        rg = sp_pass(sp_add(sp_pass(b, fmx2, r), zero, fsm, r), frg, r);
        rg = sp_pass(sp_add(sp_pass(mul, fmx2, r), sp_pass(rg, fbk, r), fsm, r), frg, r);
    } else {
        rg = sp_pass(sp_add(mul, b, fsm, r), frg, r);
    }
    return sp_pass(rg, fy, r).e;
}

/* A register's format as the datapath sees it: no more fraction bits than
 * the value it holds has (eff), so that the walk does not count bits a
 * wide register never holds. */
static sim_fmt held_fmt(sim_fmt f, int eff)
{
    return eff < f.fbits ? unit_fmt(f.is_signed, f.ibits, eff < 0 ? 0 : eff) : f;
}

/* The bound of items of one degree: network net's coefficients go to the
 * registers slot[0..deg_poly] and run on the datapath of degree hdeg
 * (span23's quadratic: slots 0-2 on the degree-2 sequence, or 1-3 on the
 * cubic pipe with ra = 0). Coefficient errors (the network's walk plus the
 * register's quantization) reach y times t^m <= 1; the datapath's own from
 * horner_bound_on (span1: lin_dp_bound) for the fraction bits the
 * registers and t really hold; t's error et times max |p'|. */
static double path_bound(const span_kind *K, const unit_cfg *cfg, const unit_fmts *f, const coef_net *net,
                         int deg_poly, const int *slot, int hdeg, int nrom, const double *et, const int *t_eff)
{
    const unit_desc *u = K->u;
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    for (int i = 0; i < net->nin; i++) in[i] = unet_input(&n, in_names[i], i);
    if (coef_walk(&n, net, in, cfg->terms, cfg->series, o)) return INFINITY;
    double e = 0;
    sim_fmt rf[4];
    int hd = main_deg(K);
    /* registers no coefficient of this degree is loaded into hold 0 (span23's ra on the pipe) */
    for (int j = 0; j <= hd; j++) rf[j] = held_fmt(f->f[sig(K, reg_names[j])], 0);
    for (int j = 0; j <= deg_poly; j++) {
        sim_fmt fr = f->f[sig(K, reg_names[slot[j]])];
        e += o[j].err + unit_qerr(fr, o[j].eff, cfg->rnd);
        rf[slot[j]] = held_fmt(fr, o[j].eff);
    }
    double lo[UNET_MAXIN], hi[UNET_MAXIN];
    for (int i = 0; i < net->nin; i++) {
        sim_fmt fi = f->f[sig(K, in_names[i])];
        lo[i] = sim_fmt_real_min(fi);
        hi[i] = sim_fmt_real_max(fi);
    }
    double D = deriv_max(deg_poly, o, lo, hi, net->nin), worst = 0;
    sim_fmt fy = f->f[sig(K, "y")];
    for (int i = 0; i < nrom; i++) {
        /* t as the Horner sees it: the fraction bits its values really have */
        sim_fmt ft = held_fmt(f->f[sig(K, "t")], t_eff[i]);
        double h = hdeg == 1 ? lin_dp_bound(K, cfg->schedule, f, rf[0].fbits, rf[1].fbits, ft.fbits, cfg->rnd)
                             : horner_bound_on(hdeg, cfg->schedule, rf, ft, u, f, fy, cfg->rnd);
        worst = fmax(worst, e + h + D * et[i]);
    }
    return worst;
}

/* The bound is the largest over ROMs of rcp's format and every wider one
 * (up to 63 bits): a wider ROM word can gain a fraction bit (more for t's
 * quantization and the multipliers to drop) without lowering the worst
 * pixel's ROM error, and a --fmt that widens rcp must not make the bound
 * grow. Each is a bound of the unit with that ROM; the one of rcp's own
 * format is among them, so the largest is sound. */
static void bound(const span_kind *K, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    static const int s0[4] = { 0, 1, 2, 3 }, s1[3] = { 1, 2, 3 };
    sim_fmt frcp = f->f[sig(K, "rcp")], ft = f->f[sig(K, "t")];
    double et[64];
    int t_eff[64], nrom = 0;
    for (int F = frcp.fbits; nrom < 64; F++) {
        sim_fmt fr = unit_fmt(frcp.is_signed, frcp.ibits, F);
        if (fr.fbits != F) break;                       /* the widest format there is */
        double rom;
        int src;
        rom_err(cfg, fr, &rom, &src);
        et[nrom] = rom + unit_qerr(ft, src, cfg->rnd);
        t_eff[nrom++] = src < ft.fbits ? src : ft.fbits;
    }
    if (!nrom) { per_out[0] = INFINITY; return; }
    int deg = main_deg(K);
    double e = path_bound(K, cfg, f, main_net(K, cfg), deg, s0, deg, nrom, et, t_eff);
    if (K->kind == K_ADAPT) {
        int pipe = cfg->schedule == SP_PIPE;
        e = fmax(e, path_bound(K, cfg, f, &net_q2, 2, pipe ? s1 : s0, pipe ? 3 : 2, nrom, et, t_eff));
    }
    per_out[0] = e;
}

/* ---------------------------------------------------------- descriptors */

extern const unit_desc unit_span1, unit_span2, unit_span3, unit_span23;
static const span_kind k1 = { &unit_span1, K_LIN, 2 };
static const span_kind k2 = { &unit_span2, K_QUAD, 3 };
static const span_kind k3 = { &unit_span3, K_CUBE, 4 };
static const span_kind k23 = { &unit_span23, K_ADAPT, 4 };

#define SPAN_FNS(sfx, K) \
    static void formats_##sfx(const unit_cfg *cfg, unit_fmts *out) { formats(&K, cfg, out); } \
    static int build_##sfx(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, \
                           const unit_fmts *f, unit_io *io, char *err, size_t errlen) \
    { return build(&K, c, sc, clk, cfg, f, io, err, errlen); } \
    static void ideal_##sfx(const unit_cfg *cfg, const double *in, double *out) { ideal(&K, cfg, in, out); } \
    static void bound_##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { bound(&K, cfg, f, o); } \
    static int ratio_##sfx(const unit_cfg *cfg, const sim_dy *in, sim_dy *num, sim_dy *den) \
    { return ideal_ratio(&K, cfg, in, num, den); }

SPAN_FNS(1, k1)
SPAN_FNS(2, k2)
SPAN_FNS(3, k3)
SPAN_FNS(23, k23)

static int sig_used_3(const unit_cfg *cfg, int i) { return cube_sig_used(&k3, cfg, i); }
static int sig_used_23(const unit_cfg *cfg, int i) { return cube_sig_used(&k23, cfg, i); }

#define P_L { "L", UNIT_P_INT, offsetof(unit_cfg, L), 2, SPAN_LMAX, 8, NULL, \
              "pixels per interval, any 2..64: beats per item in `run`, the largest n and dv" }
#define P_NODES { "nodes", UNIT_P_ENUM, offsetof(unit_cfg, nodes), 0, 1, 0, "n1 n2", \
                  "node set of the cubic: n1 = I(0), I(1), I(1/2), I(1/4); n2 = I(0), I(1), I(1/2), I(3/4)" }

#define S_IN(name, what) { name, UNIT_SIG_IN, what, 0 }
#define S_INT(name, what) { name, UNIT_SIG_INTERNAL, what, 0 }
#define S_I12 S_IN("i1", "I1 = I(0)"), S_IN("i2", "I2 = I(1)")
#define S_I3 S_IN("i3", "I3 = I(1/2)")
#define S_I4 S_IN("i4", "I4 = I(1/4) (nodes=n1) or I(3/4) (nodes=n2)")
#define S_NDV S_IN("n", "pixels of the interval, 1..L: the item's beats (`run` gives every item L beats: its vectors have n = L)"), \
              S_IN("dv", "divisor, 1..L: pixel k has t = k/dv (L for a full interval, n-1 for a span's last)")
#define S_DEG S_IN("deg", "degree of the item: 2 (the quadratic through I1, I2, I3) or 3 (the cubic)")
#define S_Y { "y", UNIT_SIG_OUT, "intensity I(k/dv) of pixel k, one beat per pixel, n beats per item", 0 }
#define S_REGS3 S_INT("ra", "register of A, loaded when an item is accepted"), S_INT("rb", "register of B"), \
                S_INT("rc", "register of C"), S_INT("rd", "register of D")
#define S_T S_INT("rcp", "reciprocal ROM: 1/dv rounded down, L words addressed by the latched dv"), \
            S_INT("t", "t = k * rcp, the pixel counter times the reciprocal (a small multiplier)")

/* The elements of both cubic networks (coef3_n1, coef3_n2): a unit built
 * with one node set has the other's own elements unbuilt (marked). */
#define S_CUBE \
    S_INT("i4x8", "8 I4"), \
    S_INT("pa", "n1: I2 + 8 I4; n2: I2 + 2 I3"), \
    S_INT("div3_a", "/3 network (scope div3_a) of n1: (I2 + 8 I4)/3, n2: (8 I4 + I1)/3; its terms, sums and output"), \
    S_INT("i3x2", "2 I3"), \
    S_INT("qa", "n1: I1 + 2 I3; n2: 8 I4 + I1"), \
    S_INT("da", "n1: (I2 + 8 I4)/3 - (I1 + 2 I3); n2: (I2 + 2 I3) - (8 I4 + I1)/3"), \
    S_INT("a", "A = 8 da"), \
    S_INT("i1x8", "8 I1"), \
    S_INT("pb", "n1: 7 I1 - I2; n2: 3 I1 - 5 I2"), \
    S_INT("i4x16", "16 I4"), \
    S_INT("qb", "n1: 10 I3 - 16 I4; n2: 16 I4 - 14 I3"), \
    S_INT("sb", "pb + qb"), \
    S_INT("b", "B = 2 sb"), \
    S_INT("i4x32", "32 I4"), \
    S_INT("pc", "n1: I2 + 32 I4; n2: 13 I1 + 32 I4"), \
    S_INT("div3_c", "/3 network (scope div3_c) of pc: its terms, sums and output"), \
    S_INT("i3x4", "4 I3"), \
    S_INT("c", "C; n1: (I2 + 32 I4)/3 - (7 I1 + 4 I3); n2: 3 (I2 + 4 I3) - (13 I1 + 32 I4)/3"), \
    S_INT("d", "D = I1"), \
    S_INT("i1x7", "n1 only: 7 I1 = 8 I1 - I1"), \
    S_INT("i3x8", "n1 only: 8 I3"), \
    S_INT("i3x10", "n1 only: 10 I3 = 8 I3 + 2 I3"), \
    S_INT("qc", "n1 only: 7 I1 + 4 I3"), \
    S_INT("i1x2", "n2 only: 2 I1"), \
    S_INT("i1x3", "n2 only: 3 I1 = 2 I1 + I1"), \
    S_INT("i2x4", "n2 only: 4 I2"), \
    S_INT("i2x5", "n2 only: 5 I2 = 4 I2 + I2"), \
    S_INT("i3x16", "n2 only: 16 I3"), \
    S_INT("i3x14", "n2 only: 14 I3 = 16 I3 - 2 I3"), \
    S_INT("uc", "n2 only: I2 + 4 I3"), \
    S_INT("ucx2", "n2 only: 2 (I2 + 4 I3)"), \
    S_INT("ucx3", "n2 only: 3 (I2 + 4 I3)"), \
    S_INT("i1x4", "n2 only: 4 I1"), \
    S_INT("i1x12", "n2 only: 12 I1 = 8 I1 + 4 I1"), \
    S_INT("i1x13", "n2 only: 13 I1 = 12 I1 + I1")
#define S_CUBE_N 35

#define SPAN_SCHEDS(paper, mac, pipe) \
    { { "paper", paper }, { "mac", "one multiply-add a clock: " mac }, { "pipe", "fully pipelined, a pixel a clock: " pipe } }
#define SPAN_RULE(dp) "i* u1.(W-1); n, dv uG.0 with G = ceil(log2(L+1)); the coefficient networks as in the " \
    "coefficient units; " dp "; t u1.(W-1); rcp u1.(W-1+G) (G guard bits)"
#define SPAN_SUMMARY " of a span interval of n <= L pixels at t = k/dv (any L in 2..64), t from a 1/dv ROM"

const unit_desc unit_span1 = {
    .name = "span1",
    .ref = &ref_model_span1,
    .summary = "linear I1 + (I2 - I1) t" SPAN_SUMMARY,
    .seed = "Nechyporuk & Romanyuk (2020), sec. IV (degree 1, for comparison)",
    UNIT_SIGS(S_I12, S_NDV, S_Y,
              S_INT("a", "A = I2 - I1 (a subtractor)"), S_INT("b", "B = I1 (wiring)"),
              S_INT("ra", "register of A, loaded when an item is accepted"), S_INT("rb", "register of B"),
              S_T,
              S_INT("mul", "multiplier MUL = RA * t"),
              { "mx2", UNIT_SIG_INTERNAL, "multiplexer MX2: RB or MUL into the adder", H_P },
              { "bk", UNIT_SIG_INTERNAL, "block key BK: passes RG or forces zero", H_P },
              S_INT("sm", "adder Sm: paper MX2 + BK, mac and pipe MUL + RB"),
              S_INT("rg", "result register RG <= Sm")),
    .nsched = 3,
    .sched = SPAN_SCHEDS("the Fig. 9 elements at degree 1, RG <= B then RG <= A t + RG: 2 clocks per pixel",
                         "RG <= A t + B, 1 clock per pixel", "the same single stage as mac at degree 1"),
    .nparams = 1, .params = { P_L },
    .fmt_rule = SPAN_RULE("a, ra, y and the datapath s2.(W-2); b, rb u1.(W-1)"),
    .formats = formats_1, .beats = beats, .build = build_1, .ideal = ideal_1, .bound = bound_1,
    .ideal_ratio = ratio_1,
};

const unit_desc unit_span2 = {
    .name = "span2",
    .ref = &ref_model_span2,
    .summary = "quadratic through I(0), I(1), I(1/2)" SPAN_SUMMARY,
    .seed = "Nechyporuk & Romanyuk (2020), sec. IV, Fig. 9 (degree 2)",
    UNIT_SIGS(S_I12, S_I3, S_NDV, S_Y,
              COEF2_NET(S_NET, S_NET)
              S_INT("ra", "register of A, loaded when an item is accepted"), S_INT("rb", "register of B"),
              S_INT("rc", "register of C"),
              S_T, HORNER_SIGS2),
    .nsched = 3,
    .sched = SPAN_SCHEDS("the Horner sequence cut to degree 2: 4 clocks per pixel", "2 clocks per pixel",
                         "result 2 clocks after the pixel entered"),
    .nparams = 1, .params = { P_L },
    .fmt_rule = SPAN_RULE("a b c, their registers, y and the Horner datapath s7.(W-7)"),
    .formats = formats_2, .beats = beats, .build = build_2, .ideal = ideal_2, .bound = bound_2,
    .ideal_ratio = ratio_2,
};

const unit_desc unit_span3 = {
    .name = "span3",
    .ref = &ref_model_span3,
    .summary = "cubic through node set N1 or N2" SPAN_SUMMARY,
    .seed = "Nechyporuk & Romanyuk (2020), sec. IV, Figs. 8 and 9",
    UNIT_SIGS(S_I12, S_I3, S_I4, S_NDV, S_Y, S_CUBE, S_REGS3, S_T, HORNER_SIGS3),
    .nsched = 3,
    .sched = SPAN_SCHEDS("the paper's Horner sequence: 6 clocks per pixel", "3 clocks per pixel",
                         "result 3 clocks after the pixel entered"),
    .nparams = 4, .params = { P_L, DIV3_P_TERMS, DIV3_P_SERIES, P_NODES },
    .fmt_rule = SPAN_RULE("a b c d, their registers, y and the Horner datapath s7.(W-7)"),
    .formats = formats_3, .beats = beats, .build = build_3, .ideal = ideal_3, .bound = bound_3,
    .ideal_ratio = ratio_3, .sig_used = sig_used_3,
};

const unit_desc unit_span23 = {
    .name = "span23",
    .ref = &ref_model_span23,
    .summary = "adaptive: quadratic or cubic per item (input deg), both networks, one Horner" SPAN_SUMMARY,
    .seed = "Nechyporuk & Romanyuk (2020), sec. IV, Figs. 8 and 9; degree chosen per interval",
    UNIT_SIGS(S_I12, S_I3, S_I4, S_NDV, S_DEG, S_Y, S_CUBE,
              COEF2_NET(SQ_SIG, SQ_SIG)
              S_REGS3, S_T, HORNER_SIGS3),
    .nsched = 3,
    .sched = SPAN_SCHEDS("the paper's Horner sequence, 6 clocks per pixel of a cubic item, its first 4 for a "
                         "quadratic item", "3 clocks per pixel of a cubic item, 2 of a quadratic",
                         "a quadratic item enters as (0, A2, B2, C2); result 3 clocks after the pixel entered"),
    .nparams = 4, .params = { P_L, DIV3_P_TERMS, DIV3_P_SERIES, P_NODES },
    .fmt_rule = SPAN_RULE("both networks' coefficients, the registers (loaded through a degree mux), y and the "
                          "Horner datapath s7.(W-7)"),
    .formats = formats_23, .beats = beats, .build = build_23, .ideal = ideal_23, .bound = bound_23,
    .ideal_ratio = ratio_23, .sig_used = sig_used_23,
};

