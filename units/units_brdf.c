/* units_brdf.c - the few pieces of hardware and arithmetic the BRDF
 * approximation units of the interpolation, SPIE and Schlick papers share (prefix brdf_).
 *
 *   powg, pow_n, d_approx, ward_approx   one-multiplier power engine (unit_powg.c)
 *   div, schlick, mschlick               restoring divider (unit_div.c)
 *
 * The registry (unit.c) reaches the units through the table units_brdf[]
 * below; units_brdf.h declares what they share (brdf_*, the power
 * engine's pw_*, the divider's dv_*) for the files that use it.
 */
#include "units/units_brdf.h"
#include "sim/sim_area.h"
#include "sim/sim_delay.h"
#include <math.h>
#include <stdlib.h>

/* ------------------------------------------------------------- sequencer */

/* Step counter of a multi-clock unit, Horner's convention (unit_horner.c):
 * it waits at step 0 until an item is offered, runs steps 0..n-1 reading
 * the held inputs, and raises in_ready in the last step, so the item is
 * accepted at the edge that ends its computation; out_valid follows one
 * clock later, while the result registers hold it.
 *
 * Control signals that steer data (mux selects, "first step") are
 * registered: decoded from the next step and clocked, they change in the
 * same delta cycle as the data registers, so no mux ever passes a new
 * register value under an old select (a one-delta glitch in which, e.g.,
 * the power engine would square its final result and count an overflow).
 * *next_out is the next-step signal to decode from (brdf_decode). */
static int64_t seq_next(const int64_t *in, void *u)
{
    int64_t n = (int64_t)(intptr_t)u;
    if (in[0] == 0 && !in[1]) return 0;
    return in[0] >= n - 1 ? 0 : in[0] + 1;
}
static int64_t seq_is0(const int64_t *in, void *u) { (void)u; return in[0] == 0; }
static int64_t seq_last(const int64_t *in, void *u) { return in[0] == (int64_t)(intptr_t)u - 1; }
static int64_t seq_and(const int64_t *in, void *u) { (void)u; return in[0] && in[1]; }

int brdf_bitlen(uint64_t v)
{
    int n = 0;
    while (v) { n++; v >>= 1; }
    return n;
}

void brdf_seq(sim_ctx *c, sim_scope *sc, sim_signal *clk, int nsteps, unit_io *io,
              sim_signal **next_out, sim_signal **first_out)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    if (nsteps <= 1) {
        /* One clock per item: nothing to count. */
        *next_out = sim_const_raw(c, sc, "step_next", u1, 0);
        *first_out = sim_const_raw(c, sc, "first", u1, 1);
        io->in_ready = sim_const_raw(c, sc, "in_ready", u1, 1);
    } else {
        int bits = brdf_bitlen((uint64_t)(nsteps - 1));
        sim_fmt fs = unit_fmt(0, bits, 0);
        void *n = (void *)(intptr_t)nsteps;
        sim_signal *step = sim_reg(c, sc, "step", fs, clk, NULL, NULL, NULL, 0);
        sim_signal *nx_in[2] = { step, io->in_valid };
        /* An incrementer (a half adder a bit), the wrap compare, a hold gate. */
        sim_signal *next = sim_logic(c, sc, "step_next", fs, 2, nx_in, seq_next, n,
                                     bits * (SIM_GE_HA + SIM_GE_NAND2) + 2);
        sim_reg_connect(step, next);
        *next_out = next;
        sim_signal *is0 = sim_logic(c, sc, "first_next", u1, 1, &next, seq_is0, NULL, bits * SIM_GE_NAND2);
        *first_out = sim_reg(c, sc, "first", u1, clk, is0, NULL, NULL, 1);
        io->in_ready = sim_logic(c, sc, "in_ready", u1, 1, &step, seq_last, n, bits * SIM_GE_NAND2);
    }
    sim_signal *ov_in[2] = { io->in_ready, io->in_valid };
    sim_signal *ov = sim_logic(c, sc, "done", u1, 2, ov_in, seq_and, NULL, SIM_GE_AND2);
    io->out_valid = sim_reg(c, sc, "out_valid", u1, clk, ov, NULL, NULL, 0);
}

/* A registered decoder of a step-indexed control table (a small ROM of n
 * words): name <= table[next step] at every edge, so it holds table[step]. */
static int64_t table_at(const int64_t *in, void *u) { return ((const uint8_t *)u)[in[0]]; }

sim_signal *brdf_decode(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *name,
                        sim_signal *next, const uint8_t *table, int n)
{
    /* Zero-filled past n up to every value next's format holds: the
     * Verilog export tabulates the decoder over all of them. */
    size_t cap = next->fmt.width <= 12 && ((size_t)1 << next->fmt.width) > (size_t)n ? (size_t)1 << next->fmt.width : (size_t)n;
    uint8_t *t = sim_alloc(c, cap);
    int maxv = 0;
    for (int i = 0; i < n; i++) { t[i] = table[i]; if (t[i] > maxv) maxv = t[i]; }
    int bits = brdf_bitlen((uint64_t)maxv);
    sim_fmt f = unit_fmt(0, bits ? bits : 1, 0);
    char dname[64];
    snprintf(dname, sizeof dname, "%s_next", name);
    /* A gate per 1 of the table (summed over its output bits) and an
     * inverter per step bit: ABC merges the minterms of neighbouring
     * steps, so a table costs about its ones, not its steps. Measured:
     * shade's six decoders of a 6-bit step (51 steps) map to 77 GE in
     * all (4 to 22 each; docs/area.md), as this counts; two gates per
     * step and output bit, the estimate before, made them 1224. */
    int ones = 0;
    for (int i = 0; i < n; i++)
        for (unsigned v = t[i]; v; v &= v - 1) ones++;
    sim_signal *d = sim_logic(c, sc, dname, f, 1, &next, table_at, t,
                              ones * SIM_GE_NAND2 + next->fmt.width * SIM_GE_INV);
    return sim_reg(c, sc, name, f, clk, d, NULL, NULL, t[0]);
}

/* ------------------------------------------------------ constant multiply */

/* Non-zero digits of v in canonical signed-digit form, and the distance
 * from its lowest to its highest digit. */
static int csd_digits(uint64_t v, int *span)
{
    int n = 0, lo = -1, hi = 0;
    for (int pos = 0; v; pos++, v >>= 1) {
        if (v & 1) {
            if ((v & 3) == 3) v += 1;      /* digit -1: ...11 -> ...(1)0(-1) */
            else v -= 1;                   /* digit +1 */
            n++;
            if (lo < 0) lo = pos;
            hi = pos;
        }
    }
    *span = lo < 0 ? 0 : hi - lo + 1;
    return n;
}

/* y = x * k for a constant k: the product is exact before y's quantization,
 * as sim_mul's, but the element is a shift-and-add network. Its area is
 * the network synthesis builds, a row of x for each 1 of k
 * (sim_area_cmul); its delay, the model's own, that of a network of one
 * adder per CSD digit of k after the first (a power of two is wiring),
 * each as wide as x plus the digits' span. */
sim_signal *brdf_cmul(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fy,
                      sim_signal *x, sim_signal *k)
{
    sim_signal *y = sim_mul(c, sc, name, fy, x, k);
    int64_t kr = k->cur;
    uint64_t mag = kr < 0 ? (uint64_t)0 - (uint64_t)kr : (uint64_t)kr;
    int span, digits = csd_digits(mag, &span);
    int w = x->fmt.width + span, adders = digits - 1;
    /* sim_mul charged an array multiplier plus y's quantization logic
     * (rounding incrementer, saturation clamp): swap only the multiplier
     * for the network; the quantization logic is still there. A negative
     * k makes one of the adders a subtractor (or, for a power of two,
     * adds a negator). */
    double quant = y->area_ge - sim_area_mul(sim_prim_live_bits(x), sim_prim_live_bits(k));
    /* Synthesis does not recode k: Yosys sums a row of x for every 1 of
     * k's binary form (sim_area_cmul), so 31 = 11111b costs four adders,
     * not the one of 32 - 1 (schlick at 24 mapped to 1465 GE where the
     * CSD network made the model 1100) */
    y->area_ge = sim_area_cmul(sim_prim_live_bits(x), mag, kr < 0) + quant;
    /* The delay likewise: the network's adders as a balanced tree (a
     * negative k: an inverter on one branch, or the negator). */
    sim_arcs dn = sim_arcs_bitwise((sim_delay){ 0, 0.0 });
    for (int a = adders; a > 0; a = a / 2) dn = sim_arcs_then(dn, sim_delay_add(w));
    if (kr < 0) dn = sim_arcs_then(dn, adders == 0 ? sim_delay_sub(w) : sim_arcs_bitwise((sim_delay){ 1, SIM_PS_XOR2 }));
    sim_mul_network_delay(y, dn);
    return y;
}

/* -------------------------------------------------- formats and bounds */

/* Integer bits of an unsigned format holding every value up to x (with a
 * little room so that a rounded-up constant still fits). */
int brdf_ibits(double x)
{
    int i = 0;
    while (i < 63 && ldexp(1.0, i) <= x * (1 + 0x1p-20)) i++;
    return i;
}

/* Whether format f holds every real in [lo, hi]. */
int brdf_holds(sim_fmt f, double lo, double hi)
{
    return lo >= sim_fmt_real_min(f) && hi <= sim_fmt_real_max(f);
}

/* When some format cannot hold its signal's range (a user's --fmt
 * override) the derivation does not apply: there is no bound (NaN, which
 * the testbench reports as "no bound"), not a made-up one (issue 9). */
double brdf_range_bound(sim_fmt out, double ideal_max)
{
    (void)out; (void)ideal_max;
    return NAN;
}

/* A hard-wired constant: x truncated (toward minus infinity) to f, so
 * that a scale like c0 = 1/(4m^2) never makes an output exceed the exact
 * peak; but x within 2^-30 LSB of a representable value is that value,
 * whatever the double arithmetic that made it: 2/0.2^2 - 4 comes out as
 * 45.99999999999999, and truncating it would cost a CSD digit and an adder
 * for nothing. */
static int64_t const_raw(double x, sim_fmt f, int *ovf)
{
    double y = ldexp(x, f.fbits), r = nearbyint(y);
    if (fabs(y - r) <= 0x1p-30 * fmax(1.0, fabs(y))) x = ldexp(r, -f.fbits);
    return sim_fx_from_real(x, f, SIM_RND_TRUNC, SIM_OVF_SAT, ovf);
}
/* A constant that does not fit its format saturates; it counts as one
 * overflow of its signal, so that the run reports it (issue 9). */
sim_signal *brdf_const(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt f, double x)
{
    int ovf = 0;
    sim_signal *s = sim_const_raw(c, sc, name, f, const_raw(x, f, &ovf));
    s->overflows += (uint64_t)ovf;
    return s;
}
int brdf_const_eff(double x, sim_fmt f)
{
    int64_t raw = const_raw(x, f, NULL);
    if (!raw) return -64;
    return f.fbits - __builtin_ctzll((uint64_t)raw);
}
unet_val brdf_uconst(unet *n, sim_fmt f, const char *name, double x)
{
    unet_val v = unet_wrap(n->c ? brdf_const(n->c, n->sc, name, f, x) : NULL, f, -1);
    v.err = brdf_const_err(x, f);
    v.eff = brdf_const_eff(x, f);
    v.imag = fabs(x);
    return v;
}
/* |x - the constant brdf_const stores|. */
double brdf_const_err(double x, sim_fmt f)
{
    return fabs(sim_fx_to_real(const_raw(x, f, NULL), f) - x);
}

int brdf_pow_exact(const sim_dy *x0, int e, sim_dy *out)
{
    sim_dy y, x = *x0;
    sim_dy_int(&y, 1, 0);
    for (; e && !y.ovf; e >>= 1) {
        if (e & 1) sim_dy_mul(&y, &y, &x);
        if (e > 1) sim_dy_mul(&x, &x, &x);
    }
    *out = y;
    return y.ovf ? -1 : 0;
}

int brdf_pow_interval(const sim_dy *x0, int e0, sim_dy *lo, sim_dy *hi)
{
    sim_dy z;
    sim_dy_int(&z, 0, 0);
    if (sim_dy_cmp(x0, &z) < 0) return -1;
    for (int side = 0; side < 2; side++) {
        sim_dy y, x = *x0;
        sim_dy_int(&y, 1, 0);
        for (int e = e0; e && !y.ovf && !x.ovf; e >>= 1) {
            if (e & 1) { sim_dy_mul(&y, &y, &x); sim_dy_cut(&y, 240, side); }
            if (e > 1) { sim_dy_mul(&x, &x, &x); sim_dy_cut(&x, 240, side); }
        }
        if (y.ovf || x.ovf) return -1;
        *(side ? hi : lo) = y;
    }
    return 0;
}
