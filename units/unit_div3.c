/* unit_div3.c - the divide-by-3 shift network of Nechyporuk & Romanyuk (2020), Fig. 7.
 *
 *   paper:   y = x/2 - x/8 - x/32 - x/128 - ...   (terms subtracted terms)
 *   quarter: y = x/4 + x/16 + x/64 + ...          (terms terms)
 *
 * Every term is x shifted right (wiring, no gates) and every partial sum
 * is one subtractor (adder), so `terms` = 3 is the paper's three
 * subtractors and factor 0.3359375 (+0.78125%). The paper series
 * converges to 1/3 from above, the quarter series from below, by a factor
 * 4 per term.
 *
 * Signals are named by term index, not by shift, so that one list serves
 * both series: t0 = x/2 (paper only), ti = the i-th term, si = the i-th
 * partial sum. sigs[] declares all 20 terms' signals; a network of N
 * terms builds t0..tN and s1..sN (quarter: t1..tN and s2..sN, since its
 * first partial sum is t1 itself), and only those exist for list, run,
 * --fmt and the VCD (sig_used).
 */
#include "units/unit_net.h"
#include "vectors/ref_interp.h"
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

int div3_guard_bits(int terms)
{
    int g = 0;
    while ((1 << g) < terms + 1) g++;
    return g;
}

unet_val div3_walk(unet *n, unet_val x, int terms, int series, int group)
{
    char tn[16], sn[16];
    int paper = series == DIV3_PAPER;
    if (terms < 1) terms = 1;
    if (terms > DIV3_MAX_TERMS) terms = DIV3_MAX_TERMS;
    int cap = n->fcap;
    n->fcap = x.f.fbits + div3_guard_bits(terms);
#define SIG(name) (group >= 0 ? group : unet_sig(n, name))
    unet_val acc;
    if (paper) acc = unet_shift(n, SIG("t0"), "t0", x, -1);
    for (int i = 1; i <= terms; i++) {
        snprintf(tn, sizeof tn, "t%d", i);
        snprintf(sn, sizeof sn, "s%d", i);
        unet_val t = unet_shift(n, SIG(tn), tn, x, paper ? -(2 * i + 1) : -2 * i);
        if (paper) acc = unet_sub(n, SIG(sn), sn, acc, t);
        else acc = i == 1 ? t : unet_add(n, SIG(sn), sn, acc, t);
    }
    unet_val y = unet_shift(n, SIG("y"), "y", acc, 0);   /* the output port: a view */
#undef SIG
    n->fcap = cap;
    return y;
}

/* ------------------------------------------------------------ the unit */

extern const unit_desc unit_div3;

/* x spans [-1, 1) (the reference's vectors); the rule reads it as s1.(W-1). */
static const double x_lo[1] = { -1 }, x_hi[1] = { 1 };

static void formats(const unit_cfg *cfg, unit_fmts *out)
{
    unet n;
    unet_init(&n, &unit_div3, NULL, cfg->rnd);
    unet_rule(&n, cfg->width, x_lo, x_hi, 1);
    n.fm.f[0] = unit_fmt(1, 1, cfg->width - 1);
    div3_walk(&n, unet_input(&n, "x", 0), cfg->terms, cfg->series, -1);
    /* Terms and sums past cfg->terms are not built (sig_used says so) and
     * keep no format: list, run and --fmt do not show them. */
    *out = n.fm;
}

/* The network of cfg->terms terms builds t0 and s1 (paper series only),
 * t1..tN and s2..sN; the signal list declares all 20 terms' signals. */
static int sig_used(const unit_cfg *cfg, int i)
{
    const char *nm = unit_div3.sigs[i].name;
    int paper = cfg->series == DIV3_PAPER, k = nm[1] ? atoi(nm + 1) : -1;
    int terms = cfg->terms < 1 ? 1 : cfg->terms > DIV3_MAX_TERMS ? DIV3_MAX_TERMS : cfg->terms;
    if (nm[0] == 't' && k >= 0) return k == 0 ? paper : k <= terms;
    if (nm[0] == 's' && k >= 1) return k == 1 ? paper : k <= terms;
    return 1;   /* x, y */
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

static int build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                 const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    (void)clk;
    unet n;
    unet_init(&n, &unit_div3, f, cfg->rnd);
    unet_hw(&n, c, sc);
    unet_val x = unet_input(&n, "x", 0);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    unet_val y = div3_walk(&n, x, cfg->terms, cfg->series, -1);
    if (n.why[0]) { snprintf(err, errlen, "%s", n.why); return -1; }
    io->in[0] = x.s;
    io->out[0] = y.s;
    /* Combinational: always ready, output valid with the input. */
    sim_fmt u1 = unit_fmt(0, 1, 0);
    io->in_ready = sim_const_raw(c, sc, "in_ready", u1, 1);
    io->out_valid = sim_signal_new(c, sc, "out_valid", u1, SIM_KIND_WIRE);
    sim_assign(c, io->out_valid, io->in_valid);
    io->scope = sc;
    return 0;
}

/* The network in exact arithmetic. */
static void ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = in[0] * ref_div3_factor(cfg->terms, cfg->series);
}

/* Exactly: the network's factor is a sum of a few powers of two, so the
 * double holds it exactly. */
static int ideal_exact(const unit_cfg *cfg, const sim_dy *in, sim_dy *out)
{
    sim_dy k;
    sim_dy_double(&k, ref_div3_factor(cfg->terms, cfg->series));
    sim_dy_mul(out, &in[0], &k);
    return out->ovf ? -1 : 0;
}

/* The walk's error of y: every term's and sum's quantization, no gain. */
static void bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    unet n;
    unet_init(&n, &unit_div3, f, cfg->rnd);
    per_out[0] = div3_walk(&n, unet_input(&n, "x", 0), cfg->terms, cfg->series, -1).err;
}

/* t<i>: the i-th term, x/2^p in the paper series, x/2^q in the quarter. */
#define TERM(i, p, q) { .name = "t" #i, .role = UNIT_SIG_INTERNAL, .what = "term " #i ": x/2^" #p " (paper), x/2^" #q " (quarter)" }
#define SUM(i) { .name = "s" #i, .role = UNIT_SIG_INTERNAL, .what = "partial sum s" #i " = s" #i "-1 - t" #i " (paper), + t" #i " (quarter)" }

const unit_desc unit_div3 = {
    .name = "div3",
    .ref = &ref_model_div3,
    .summary = "x/3 by the Fig. 7 shift network: x/2 - x/8 - x/32 - ... (or x/4 + x/16 + ...), combinational",
    .source = "Nechyporuk & Romanyuk (2020), Fig. 7",
    UNIT_SIGS(
        { .name = "x", .role = UNIT_SIG_IN, .what = "dividend" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "x/3 by the network (a view of the last partial sum)" },
        { .name = "t0", .role = UNIT_SIG_INTERNAL, .what = "x/2, the paper series' first term" },
        TERM(1, 3, 2), TERM(2, 5, 4), TERM(3, 7, 6), TERM(4, 9, 8), TERM(5, 11, 10),
        TERM(6, 13, 12), TERM(7, 15, 14), TERM(8, 17, 16), TERM(9, 19, 18), TERM(10, 21, 20),
        TERM(11, 23, 22), TERM(12, 25, 24), TERM(13, 27, 26), TERM(14, 29, 28), TERM(15, 31, 30),
        TERM(16, 33, 32), TERM(17, 35, 34), TERM(18, 37, 36), TERM(19, 39, 38), TERM(20, 41, 40),
        { .name = "s1", .role = UNIT_SIG_INTERNAL, .what = "partial sum s1 = t0 - t1 (paper; the quarter series starts at s2 = t1 + t2)" },
        SUM(2), SUM(3), SUM(4), SUM(5), SUM(6), SUM(7), SUM(8), SUM(9), SUM(10), SUM(11),
        SUM(12), SUM(13), SUM(14), SUM(15), SUM(16), SUM(17), SUM(18), SUM(19), SUM(20)),
    .nsched = 1,
    .sched = { { "comb", "combinational: one item per clock" } },
    .nparams = 2,
    .params = {
        { "terms", UNIT_P_INT, offsetof(unit_cfg, terms), 1, DIV3_MAX_TERMS, DIV3_PAPER_TERMS, NULL,
          "subtracted terms after x/2 (paper) or added terms (quarter); 3 is the paper's network" },
        { "series", UNIT_P_ENUM, offsetof(unit_cfg, series), 0, 1, DIV3_PAPER, "paper quarter",
          "paper: x/2 - x/8 - x/32 - ... (from above); quarter: x/4 + x/16 + ... (from below)" },
    },
    .fmt_rule = "x s1.(W-1) (x in [-1, 1)); y s1.(W-1); terms and partial sums s1.(W-1+G), "
                "G = ceil(log2(terms+1)) guard bits so that their truncations add up to at most 1 LSB of x; "
                "only the terms and sums of the configured network are built",
    .formats = formats, .beats = beats1, .build = build, .ideal = ideal, .bound = bound, .ideal_exact = ideal_exact,
    .sig_used = sig_used,
    .bound_own_modes = 1,   /* the unet walk's */
};
