/* unit_powg.c - the one-multiplier power engine, and powg: y = x^g for
 * g = 2^k by repeated squaring, k clocks.
 *
 *   MX_A, MX_B  operand multiplexers: the engine input IN, RG, or 1
 *   MUL = MX_A * MX_B, quantized to its own format
 *   RG <= MUL   every clock
 *
 * What the engine computes is a program: one (A, B) operand pair a clock,
 * written as two characters, 'I' (IN), 'R' (RG), '1' (the constant one).
 * powg is "II" then "RR" k-1 times; pow_n (unit_pow_n.c) is square and
 * multiply, "RR"/"RI"; d_approx and ward_approx (unit_dapprox.c) feed IN
 * from their clamped base and run powg's program. An operand with a single
 * source in the whole program needs no multiplexer, and when A and B always
 * select the same source one multiplexer drives both inputs (a squarer's
 * wiring), so each unit pays only for the muxes its program uses.
 */
#include "units/unit.h"
#include "units/units_brdf.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

extern const unit_desc unit_powg;

#define PW_MAX_STEPS 64

/* ------------------------------------------------------------------ plan */

/* Which sources each operand uses, in order of first use; whether one mux
 * serves both operands. */
typedef struct pw_plan {
    int nsteps;
    char src_a[4], src_b[4];   /* NUL-terminated source lists */
    int shared;
    int ia, ib;                /* signal indices of the A and B muxes (-1: none) */
    int imul, irg;
} pw_plan;

static void add_src(char *list, char s)
{
    if (!strchr(list, s)) { size_t n = strlen(list); list[n] = s; list[n + 1] = 0; }
}

static int pw_make_plan(const unit_desc *u, const char *prog, pw_plan *p)
{
    memset(p, 0, sizeof *p);
    size_t len = strlen(prog);
    if (len < 2 || len % 2 || len / 2 > PW_MAX_STEPS) return -1;
    p->nsteps = (int)(len / 2);
    p->shared = 1;
    for (int s = 0; s < p->nsteps; s++) {
        char a = prog[2 * s], b = prog[2 * s + 1];
        if (!strchr("IR1", a) || !strchr("IR1", b)) return -1;
        add_src(p->src_a, a);
        add_src(p->src_b, b);
        if (a != b) p->shared = 0;
    }
    p->ia = unit_sig_index(u, "mx");
    if (p->ia < 0) p->ia = unit_sig_index(u, "mx_a");
    p->ib = p->shared ? p->ia : unit_sig_index(u, "mx_b");
    p->imul = unit_sig_index(u, "mul");
    p->irg = unit_sig_index(u, "rg");
    if (p->ia < 0 || p->ib < 0 || p->imul < 0 || p->irg < 0) return -1;
    return 0;
}

/* Whether the engine for prog builds signal i: an operand with a single
 * source is wiring, not a mux, and a shared operand has no B mux. */
int pw_sig_built(const unit_desc *u, const char *prog, int i)
{
    pw_plan p;
    if (!prog || pw_make_plan(u, prog, &p)) return 1;
    if (i == p.ia) return strlen(p.src_a) > 1;
    if (i == unit_sig_index(u, "mx_b")) return !p.shared && strlen(p.src_b) > 1;
    return 1;
}

/* ----------------------------------------------------------------- build */

static sim_signal *operand(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *name, sim_fmt f,
                           sim_signal *next, const char *prog, int col, const char *srcs,
                           int nsteps, sim_signal *in, sim_signal *rg, sim_signal **one)
{
    sim_signal *sig[3];
    int n = (int)strlen(srcs);
    for (int i = 0; i < n; i++) {
        if (srcs[i] == 'I') sig[i] = in;
        else if (srcs[i] == 'R') sig[i] = rg;
        else {
            if (!*one) *one = sim_const_raw(c, sc, "one", unit_fmt(0, 1, 0), 1);
            sig[i] = *one;
        }
    }
    if (n == 1) return sig[0];           /* a single source: plain wiring */
    uint8_t table[PW_MAX_STEPS];
    for (int s = 0; s < nsteps; s++) table[s] = (uint8_t)(strchr(srcs, prog[2 * s + col]) - srcs);
    char sel[32];
    snprintf(sel, sizeof sel, "%s_sel", name);
    return sim_mux(c, sc, name, f, brdf_decode(c, sc, clk, sel, next, table, nsteps), n, sig);
}

/* Builds the sequencer and the engine around IN; returns RG. */
sim_signal *pw_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                     const unit_fmts *f, unit_io *io, sim_signal *in, const char *prog)
{
    pw_plan p;
    if (pw_make_plan(u, prog, &p)) return NULL;
    sim_signal *next, *first, *one = NULL;
    brdf_seq(c, sc, clk, p.nsteps, io, &next, &first);
    (void)first;
    sim_signal *rg = sim_reg(c, sc, "rg", f->f[p.irg], clk, NULL, NULL, NULL, 0);
    sim_signal *a = operand(c, sc, clk, u->sigs[p.ia].name, f->f[p.ia], next, prog, 0, p.src_a,
                            p.nsteps, in, rg, &one);
    sim_signal *b = p.shared ? a
                  : operand(c, sc, clk, u->sigs[p.ib].name, f->f[p.ib], next, prog, 1, p.src_b,
                            p.nsteps, in, rg, &one);
    sim_signal *mul = sim_mul(c, sc, "mul", f->f[p.imul], a, b);
    sim_reg_connect(rg, mul);
    return rg;
}

/* ----------------------------------------------------------------- bound */

/* Worst-case |RG - ideal| after the program (docs/brdf.md, "power engine").
 * Every value is in [0, M] with M tracked per step (m_in bounds IN); an
 * error e_a on A and e_b on B give |ab - AB| <= e_a (M_b + e_b) + M_a e_b,
 * so a squaring doubles the error and a multiply by IN adds e_in M. Each
 * element that drops fraction bits adds its quantization error. Returns
 * INFINITY when some format cannot hold its value (an override that may
 * overflow); *m_out is the largest ideal value of RG. */
double pw_bound(const unit_desc *u, const unit_fmts *f, sim_round r, sim_fmt in_fmt,
                double e_in, double m_in, const char *prog, double *m_out, int *eff_out)
{
    pw_plan p;
    if (pw_make_plan(u, prog, &p)) return INFINITY;
    sim_fmt fa = f->f[p.ia], fb = f->f[p.ib], fm = f->f[p.imul], fr = f->f[p.irg];
    int mux_a = strlen(p.src_a) > 1, mux_b = !p.shared && strlen(p.src_b) > 1;
    double e_rg = 0, m_rg = 0;
    int eff_rg = fr.fbits;      /* fraction bits RG's value really has */
    for (int s = 0; s < p.nsteps; s++) {
        double e[2], m[2];
        int fbits[2];
        for (int k = 0; k < 2; k++) {
            char src = prog[2 * s + k];
            int has_mux = k == 0 ? mux_a : (p.shared ? mux_a : mux_b);
            sim_fmt fmx = k == 0 || p.shared ? fa : fb;
            int sf = src == 'I' ? in_fmt.fbits : src == 'R' ? eff_rg : 0;
            e[k] = src == 'I' ? e_in : src == 'R' ? e_rg : 0;
            m[k] = src == 'I' ? m_in : src == 'R' ? m_rg : 1;
            if (has_mux) {
                e[k] += unit_qerr(fmx, sf, r);
                if (!brdf_holds(fmx, 0, m[k] + e[k])) return INFINITY;
                sf = sf < fmx.fbits ? sf : fmx.fbits;
            }
            fbits[k] = sf;
        }
        double m_mul = m[0] * m[1];
        double e_mul = e[0] * (m[1] + e[1]) + m[0] * e[1] + unit_qerr(fm, fbits[0] + fbits[1], r);
        if (!brdf_holds(fm, 0, m_mul + e_mul)) return INFINITY;
        int eff_mul = fbits[0] + fbits[1] < fm.fbits ? fbits[0] + fbits[1] : fm.fbits;
        e_rg = e_mul + unit_qerr(fr, eff_mul, r);
        eff_rg = eff_mul < fr.fbits ? eff_mul : fr.fbits;
        m_rg = m_mul;
        if (!brdf_holds(fr, 0, m_rg + e_rg)) return INFINITY;
    }
    if (m_out) *m_out = m_rg;
    if (eff_out) *eff_out = eff_rg;
    return e_rg;
}

/* ------------------------------------------------------------------ powg */

/* "II" then "RR" k-1 times for g = 2^k; NULL if g is not a power of two. */
static const char *powg_prog(int g, char *buf, size_t len)
{
    if (g < 2 || (g & (g - 1))) return NULL;
    size_t n = 0;
    for (int p = 1; p < g && n + 3 <= len; p *= 2, n += 2) memcpy(buf + n, n ? "RR" : "II", 2);
    buf[n] = 0;
    return buf;
}

enum { PG_X, PG_Y, PG_MX, PG_MUL, PG_RG, PG_NSIGS };

/* g = 2 squares x once: the operand is x itself, no mux. */
static int powg_sig_used(const unit_cfg *cfg, int i)
{
    char prog[2 * PW_MAX_STEPS + 1];
    return pw_sig_built(&unit_powg, powg_prog(cfg->g, prog, sizeof prog), i);
}

static void powg_formats(const unit_cfg *cfg, unit_fmts *out)
{
    /* Every value is in [0, 1]: one integer bit holds 1 exactly. */
    for (int i = 0; i < PG_NSIGS; i++) out->f[i] = unit_fmt(0, 1, cfg->width - 1);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

static int powg_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                      const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    char prog[2 * PW_MAX_STEPS + 1];
    if (!powg_prog(cfg->g, prog, sizeof prog)) {
        snprintf(err, errlen, "powg: g = %d is not a power of two (2, 4, ..., 64)", cfg->g);
        return -1;
    }
    io->in[0] = sim_signal_new(c, sc, "x", f->f[PG_X], SIM_KIND_INPUT);
    sim_signal *rg = pw_build(&unit_powg, c, sc, clk, f, io, io->in[0], prog);
    io->out[0] = sim_shift(c, sc, "y", f->f[PG_Y], rg, 0);
    io->scope = sc;
    return 0;
}

static void powg_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = pow(in[0], cfg->g);
}

/* x^g exactly, or between two bounds when too long (units_brdf.h). */
static int powg_interval(const unit_cfg *cfg, const sim_dy *in, sim_dy *lo, sim_dy *hi)
{
    return brdf_pow_interval(&in[0], cfg->g, lo, hi);
}

static int powg_exact(const unit_cfg *cfg, const sim_dy *in, sim_dy *out)
{
    return brdf_pow_exact(&in[0], cfg->g, out);
}

static void powg_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    char prog[2 * PW_MAX_STEPS + 1];
    double e = INFINITY, m = 1;
    int eff = f->f[PG_RG].fbits;
    if (powg_prog(cfg->g, prog, sizeof prog) && brdf_holds(f->f[PG_X], 0, 1))
        e = pw_bound(&unit_powg, f, cfg->rnd, f->f[PG_X], 0, 1, prog, &m, &eff);
    e += unit_qerr(f->f[PG_Y], eff, cfg->rnd);
    if (!isfinite(e) || !brdf_holds(f->f[PG_Y], 0, m + e)) e = brdf_range_bound(f->f[PG_Y], 1);
    /* An input format that cannot hold [0, 1] wraps inputs anywhere: no bound. */
    per_out[0] = brdf_holds(f->f[PG_X], 0, 1) ? e : INFINITY;
}

const unit_desc unit_powg = {
    .name = "powg",
    .summary = "y = x^g, g = 2^k, by repeated squaring: k clocks on one multiplier",
    .seed = "Nechyporuk & Romanyuk (2020), sec. III; S. O. Romanyuk et al. (SPIE), sec. 3 (the power of D_g)",
    UNIT_SIGS(
        { .name = "x", .role = UNIT_SIG_IN, .what = "base, in [0, 1]" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "x^g (RG after the last squaring)" },
        { .name = "mx", .role = UNIT_SIG_INTERNAL, .what = "operand mux: x in the first clock, then RG (drives both inputs)" },
        { .name = "mul", .role = UNIT_SIG_INTERNAL, .what = "multiplier MUL = MX * MX (a squarer), quantized to its own format" },
        { .name = "rg", .role = UNIT_SIG_INTERNAL, .what = "register RG <= MUL every clock" }),
    .nsched = 1,
    .sched = { { "square", "one squaring a clock: log2(g) clocks per item" } },
    .nparams = 1,
    .params = { { "g", UNIT_P_POW2, offsetof(unit_cfg, g), 2, 64, NULL, "power, a power of two" } },
    .fmt_rule = "every signal u1.(W-1) (values in [0, 1])",
    .formats = powg_formats, .beats = beats1, .build = powg_build,
    .ideal = powg_ideal, .bound = powg_bound, .ideal_exact = powg_exact, .ideal_interval = powg_interval,
    .sig_used = powg_sig_used,
};
