/* unit_pow_n.c - pow_n: y = x^n (Blinn/Phong cos^n) for any n in 1..1024
 * by left-to-right square and multiply on the power engine of
 * unit_powg.c.
 *
 * Reading n's bits after the leading one: each bit squares RG, and a 1 bit
 * then multiplies by x. The first squaring squares x itself ("II"), so
 * no clock is spent loading x; n = 1 is one clock, x * 1 ("I1").
 * Clocks per item: (bits of n - 1) squarings + (ones of n - 1) multiplies
 * (at least 1): 10 for n = 1024, 18 for n = 1023, 6 for the default 32.
 */
#include "units/unit.h"
#include "units/units_brdf.h"
#include "vectors/ref_brdf.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

extern const unit_desc unit_pow_n;

#define PN_MAX_N PW_N_MAX
#define PN_PROG_LEN PW_N_PROG_LEN

/* The program for n, or NULL when n is out of range (shade runs it too). */
const char *pow_n_prog(int n, char *buf)
{
    if (n < 1 || n > PN_MAX_N) return NULL;
    if (n == 1) { strcpy(buf, "I1"); return buf; }
    size_t k = 0;
    for (int bit = brdf_bitlen((uint64_t)n) - 2; bit >= 0; bit--) {
        memcpy(buf + k, k ? "RR" : "II", 2);          /* square */
        k += 2;
        if (n >> bit & 1) { memcpy(buf + k, "RI", 2); k += 2; }   /* multiply by x */
    }
    buf[k] = 0;
    return buf;
}

#define POW_N_SIGS(X) \
    X(PN_X,   "x", IN, "base (a cosine), in [0, 1]") \
    X(PN_Y,   "y", OUT, "x^n (RG after the last step)") \
    X(PN_MXA, "mx_a", INTERNAL, "operand mux A: x in the first clock, then RG") \
    X(PN_MXB, "mx_b", INTERNAL, "operand mux B: x (first clock, multiplies) or RG (squarings); " "absent when n is a power of two") \
    X(PN_MUL, "mul", INTERNAL, "multiplier MUL = MX_A * MX_B, quantized to its own format") \
    X(PN_RG,  "rg", INTERNAL, "register RG <= MUL every clock")
enum { POW_N_SIGS(UNIT_SIG_ID) PN_NSIGS };

/* n = 1 multiplies x by 1 (no mux); a power of two only squares (one
 * mux drives both operands, no mx_b). */
static int pow_n_sig_used(const unit_cfg *cfg, int i)
{
    char prog[PN_PROG_LEN];
    return pw_sig_built(&unit_pow_n, pow_n_prog(cfg->n, prog), i);
}

static void pow_n_formats(const unit_cfg *cfg, unit_fmts *out)
{
    for (int i = 0; i < PN_NSIGS; i++) out->f[i] = unit_fmt(0, 1, cfg->width - 1);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

static int pow_n_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                       const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    char prog[PN_PROG_LEN];
    if (!pow_n_prog(cfg->n, prog)) { snprintf(err, errlen, "pow_n: n = %d is outside 1..%d", cfg->n, PN_MAX_N); return -1; }
    io->in[0] = sim_signal_new(c, sc, "x", f->f[PN_X], SIM_KIND_INPUT);
    sim_signal *rg = pw_build(&unit_pow_n, c, sc, clk, f, io, io->in[0], prog);
    io->out[0] = sim_shift(c, sc, "y", f->f[PN_Y], rg, 0);
    io->scope = sc;
    return 0;
}

static void pow_n_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = pow(in[0], cfg->n);
}

/* x^n exactly, or between two bounds when too long (units_brdf.h). */
static int pow_n_interval(const unit_cfg *cfg, const sim_dy *in, sim_dy *lo, sim_dy *hi)
{
    return brdf_pow_interval(&in[0], cfg->n, lo, hi);
}

static int pow_n_exact(const unit_cfg *cfg, const sim_dy *in, sim_dy *out)
{
    return brdf_pow_exact(&in[0], cfg->n, out);
}

static void pow_n_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    char prog[PN_PROG_LEN];
    double e = INFINITY, m = 1;
    int eff = f->f[PN_RG].fbits;
    if (pow_n_prog(cfg->n, prog) && brdf_holds(f->f[PN_X], 0, 1))
        e = pw_bound(&unit_pow_n, f, cfg->rnd, f->f[PN_X], 0, 1, prog, &m, &eff);
    e += unit_qerr(f->f[PN_Y], eff, cfg->rnd);
    if (!isfinite(e) || !brdf_holds(f->f[PN_Y], 0, m + e)) e = brdf_range_bound(f->f[PN_Y], 1);
    /* An input format that cannot hold [0, 1] wraps inputs anywhere: no bound. */
    per_out[0] = brdf_holds(f->f[PN_X], 0, 1) ? e : INFINITY;
}

const unit_desc unit_pow_n = {
    .name = "pow_n",
    .ref = &ref_model_pow_n,
    .summary = "y = x^n (Blinn/Phong cos^n), n = 1..1024, square and multiply on one multiplier",
    .source = "Zavalniuk et al. (2022), eq. 13 (F_B = cos^n x), the exact reference of the Schlick forms",
    UNIT_SIGS(POW_N_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "sqmul", "left-to-right square and multiply: a squaring per bit of n after the "
                          "leading one, a multiply per further 1 bit" } },
    .nparams = 1,
    .params = { { "n", UNIT_P_INT, offsetof(unit_cfg, n), 1, PN_MAX_N, 32, NULL, "exponent" } },
    .fmt_rule = "every signal u1.(W-1) (values in [0, 1])",
    .formats = pow_n_formats, .beats = beats1, .build = pow_n_build,
    .ideal = pow_n_ideal, .bound = pow_n_bound, .ideal_exact = pow_n_exact, .ideal_interval = pow_n_interval,
    .sig_used = pow_n_sig_used,
};
