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
 *
 * This file: the networks, formats, ideal and the descriptors; the
 * hardware is unit_span_hw.c, the bound unit_span_bound.c (unit_span.h).
 */
#include "units/unit_span.h"
#include "vectors/ref_interp.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

const char *const span_in_names[4] = { "i1", "i2", "i3", "i4" };
const char *const span_coef_names[4] = { "a", "b", "c", "d" };
const char *const span_reg_names[4] = { "ra", "rb", "rc", "rd" };

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
const coef_net span_net_q2 = { 3, 3, COEF2_NODES, q2_nodes, formula_q2 };

/* The network of the unit's (main) degree, and for span23 the quadratic. */
const coef_net *span_main_net(const span_kind *K, const unit_cfg *cfg)
{
    switch (K->kind) {
    case K_LIN: return &net_lin;
    case K_QUAD: return &coef_net_q;
    default: return cfg->nodes ? &coef_net_n2 : &coef_net_n1;
    }
}

/* ------------------------------------------------------------- formats */

/* Walk a network to choose its formats (rule) into n. */
static void rule_walk(unet *n, const coef_net *net, const unit_cfg *cfg)
{
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    for (int i = 0; i < net->nin; i++) in[i] = unet_input(n, span_in_names[i], i);
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
    int W = cfg->width, L = span_valid_L(cfg->L) ? cfg->L : 8, G = span_kbits(L);
    unet n;
    unet_init(&n, u, NULL, cfg->rnd);
    unet_rule(&n, W, lo, hi, K->nin);
    for (int i = 0; i < K->nin; i++) n.fm.f[span_sig(K, span_in_names[i])] = coef_input_fmt(W);
    n.fm.f[span_sig(K, "n")] = unit_fmt(0, G, 0);
    n.fm.f[span_sig(K, "dv")] = unit_fmt(0, G, 0);
    if (K->kind == K_ADAPT) n.fm.f[span_sig(K, "deg")] = unit_fmt(0, 2, 0);
    /* span3/span23 declare both cubic networks' elements; the other node
     * set's own ones are not built (sig_used) and keep no format. */
    rule_walk(&n, span_main_net(K, cfg), cfg);
    if (K->kind == K_ADAPT) rule_walk(&n, &span_net_q2, cfg);
    int deg = span_main_deg(K);
    sim_fmt dp = deg == 1 ? unit_fmt(1, 2, W - 2) : unit_fmt(1, HORNER_IBITS, W - HORNER_IBITS);
    for (int j = 0; j <= deg; j++) {
        sim_fmt f = deg == 1 && j == 1 ? coef_input_fmt(W) : dp;
        n.fm.f[span_sig(K, span_coef_names[j])] = f;
        n.fm.f[span_sig(K, span_reg_names[j])] = f;
    }
    n.fm.f[span_sig(K, "t")] = unit_fmt(0, 1, W - 1);
    n.fm.f[span_sig(K, "rcp")] = unit_fmt(0, 1, W - 1 + G);
    n.fm.f[span_sig(K, "y")] = dp;
    if (deg == 1) {
        static const char *const dpn[] = { "mul", "mx2", "bk", "sm", "rg" };
        for (int i = 0; i < 5; i++) n.fm.f[span_sig(K, dpn[i])] = dp;
    } else {
        horner_default_fmts(u, deg, W, &n.fm);
    }
    *out = n.fm;
}

static int beats(const unit_cfg *cfg) { return span_valid_L(cfg->L) ? cfg->L : 8; }

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

/* ------------------------------------------------------------- ideal */

/* The polynomial through the held nodes (network's 1/3) at t = k/dv, k =
 * 0..L-1 (pixels past n follow the same polynomial). */
static void ideal(const span_kind *K, const unit_cfg *cfg, const double *in, double *out)
{
    int L = beats(cfg), deg = span_main_deg(K);
    const coef_net *net = span_main_net(K, cfg);
    double dv = floor(in[K->nin + 1]);
    if (K->kind == K_ADAPT && floor(in[K->nin + 2]) == 2) { net = &span_net_q2; deg = 2; }
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
    int L = beats(cfg), deg = span_main_deg(K);
    const coef_net *net = span_main_net(K, cfg);
    double dvd = floor(sim_dy_to_double(&in[K->nin + 1]));
    if (K->kind == K_ADAPT && floor(sim_dy_to_double(&in[K->nin + 2])) == 2) { net = &span_net_q2; deg = 2; }
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
    { return span_build(&K, c, sc, clk, cfg, f, io, err, errlen); } \
    static void ideal_##sfx(const unit_cfg *cfg, const double *in, double *out) { ideal(&K, cfg, in, out); } \
    static void bound_##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { span_bound(&K, cfg, f, o); } \
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
    .source = "Nechyporuk & Romanyuk (2020), sec. IV (degree 1, for comparison)",
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
    .source = "Nechyporuk & Romanyuk (2020), sec. IV, Fig. 9 (degree 2)",
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
    .source = "Nechyporuk & Romanyuk (2020), sec. IV, Figs. 8 and 9",
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
    .source = "Nechyporuk & Romanyuk (2020), sec. IV, Figs. 8 and 9; degree chosen per interval",
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


