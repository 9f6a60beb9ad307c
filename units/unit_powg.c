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
 * One walk of the program (pw_walk, a unet walk) builds the engine and
 * bounds its error.
 */
#include "units/unit_net.h"
#include "units/units_brdf.h"
#include "vectors/ref_brdf.h"
#include <stdio.h>
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

/* ------------------------------------------------------- build and bound */

/* Whether v's format holds its value: [0, ideal bound + error] (every
 * value of the engine is >= 0). */
static int pw_holds(unet_val v) { return brdf_holds(v.f, 0, v.imag + v.err); }

/* The engine's construction, written once and walked (unit_net.h):
 * building (n->c set), the first clock's walk makes RG, each operand's
 * multiplexer (where it has more than one source, with the decoder of its
 * select) and MUL, then stops; bounding, it walks every clock of the
 * program, every value carrying its worst-case error and the bound on its
 * ideal value (in [0, M]: a squaring doubles the error, a multiply by IN
 * adds e_in M), and returns -1 where a format cannot hold its value (an
 * override that may overflow: no bound). *rg: RG's value. */
static int pw_walk(unet *n, const pw_plan *p, const char *prog, sim_signal *next, unet_val in, unet_val *rg_out)
{
    const unit_desc *u = n->u;
    unet_val rg = unet_reg(n, p->irg, "rg"), one;
    int have_one = 0;
    for (int s = 0; s < p->nsteps; s++) {
        unet_val op[2];
        for (int k = 0; k < 2; k++) {
            if (k == 1 && p->shared) { op[1] = op[0]; break; }
            const char *srcs = k ? p->src_b : p->src_a;
            int ns = (int)strlen(srcs), sig = k ? p->ib : p->ia;
            unet_val v[3];
            for (int i = 0; i < ns; i++) {
                if (srcs[i] == 'I') v[i] = in;
                else if (srcs[i] == 'R') v[i] = rg;
                else {
                    if (!have_one) {        /* the constant 1, made where first used */
                        sim_fmt f1 = unit_fmt(0, 1, 0);
                        one = unet_wrap(n->c ? sim_const_raw(n->c, n->sc, "one", f1, 1) : NULL, f1, -1);
                        one.mag = one.imag = 1;
                        have_one = 1;
                    }
                    v[i] = one;
                }
            }
            int pick = (int)(strchr(srcs, prog[2 * s + k]) - srcs);
            if (ns == 1) { op[k] = v[0]; continue; }    /* a single source: plain wiring */
            sim_signal *sel = NULL;
            if (n->c) {
                uint8_t table[PW_MAX_STEPS];
                char sn[32];
                for (int t = 0; t < p->nsteps; t++) table[t] = (uint8_t)(strchr(srcs, prog[2 * t + k]) - srcs);
                snprintf(sn, sizeof sn, "%s_sel", u->sigs[sig].name);
                sel = brdf_decode(n->c, n->sc, n->clk, sn, next, table, p->nsteps);
            }
            op[k] = unet_mux(n, sig, u->sigs[sig].name, sel, ns, v, pick);
            if (!n->c && !pw_holds(op[k])) return -1;
        }
        /* The bound takes the product as B * A: the same error, with the
         * terms in the order of docs/brdf.md's e_a (M_b + e_b) + M_a e_b,
         * so that its rounding is that derivation's. */
        unet_val mul = n->c ? unet_mul(n, p->imul, "mul", op[0], op[1]) : unet_mul(n, p->imul, "mul", op[1], op[0]);
        if (!n->c && !pw_holds(mul)) return -1;
        unet_reg_set(n, &rg, mul);
        if (n->c) break;            /* the hardware: built once */
        if (!pw_holds(rg)) return -1;
    }
    *rg_out = rg;
    return 0;
}

int pw_engine(unet *n, unit_io *io, const char *prog, unet_val in, unet_val *rg)
{
    pw_plan p;
    if (pw_make_plan(n->u, prog, &p)) return -1;
    sim_signal *next = NULL, *first;
    if (n->c) {
        brdf_seq(n->c, n->sc, n->clk, p.nsteps, io, &next, &first);
        (void)first;
    }
    return pw_walk(n, &p, prog, next, in, rg);
}

/* Builds the sequencer and the engine around IN; returns RG. */
sim_signal *pw_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                     const unit_fmts *f, unit_io *io, sim_signal *in, const char *prog)
{
    unet n;
    unet_init(&n, u, f, SIM_RND_TRUNC);     /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    unet_val rg;
    if (pw_engine(&n, io, prog, unet_wrap(in, in->fmt, 0), &rg)) return NULL;
    return rg.s;
}

/* Worst-case |RG - ideal| after the program (docs/brdf.md, "power engine"),
 * from the walk: IN has error e_in and ideal value in [0, m_in], in_fmt's
 * fbits the bits it really has. INFINITY when some format cannot hold its
 * value; *m_out is the largest ideal value of RG. */
double pw_bound(const unit_desc *u, const unit_fmts *f, sim_round r, sim_fmt in_fmt,
                double e_in, double m_in, const char *prog, double *m_out, int *eff_out)
{
    unet n;
    unet_init(&n, u, f, r);
    unet_val in = unet_wrap(NULL, in_fmt, 0), rg;
    in.err = e_in;
    in.imag = m_in;
    if (pw_engine(&n, NULL, prog, in, &rg)) return INFINITY;
    if (m_out) *m_out = rg.imag;
    if (eff_out) *eff_out = rg.eff;
    return rg.err;
}

int pw_unrolled(unet *n, const char *prog, unet_val in, int sig, const char *pfx,
                const char *last, unet_val *rg, int *stages)
{
    size_t len = strlen(prog);
    if (len < 2 || len % 2) return -1;
    int ns = (int)(len / 2);
    char nm[48];
    sim_fmt f1 = unit_fmt(0, 1, 0);
    int has_one = strchr(prog, '1') != NULL;
    unet_val r, x = in, one = unet_wrap(n->c && has_one ? sim_const_raw(n->c, n->sc, "one", f1, 1) : NULL, f1, -1);
    memset(&r, 0, sizeof r);
    one.mag = one.imag = 1;
    for (int s = 0; s < ns; s++) {
        unet_val op[2];
        for (int k = 0; k < 2; k++) {
            char ch = prog[2 * s + k];
            if (!strchr("IR1", ch) || (ch == 'R' && s == 0)) return -1;
            op[k] = ch == 'I' ? x : ch == 'R' ? r : one;
        }
        snprintf(nm, sizeof nm, "%s%d_mul", pfx, s + 1);
        /* the bound takes the product as B * A, as pw_walk does */
        unet_val mul = n->c ? unet_mul(n, sig, nm, op[0], op[1]) : unet_mul(n, sig, nm, op[1], op[0]);
        if (s == ns - 1) snprintf(nm, sizeof nm, "%s", last);
        else snprintf(nm, sizeof nm, "%s%d", pfx, s + 1);
        r = unet_reg_of(n, sig, nm, mul);
        /* IN travels beside the products while a later step reads it */
        if (n->c && strchr(prog + 2 * (s + 1), 'I')) {
            snprintf(nm, sizeof nm, "%s%d_in", pfx, s + 1);
            x.s = sim_reg(n->c, n->sc, nm, x.s->fmt, n->clk, x.s, NULL, NULL, 0);
        }
    }
    *rg = r;
    if (stages) *stages = ns;
    return 0;
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

#define POWG_SIGS(X) \
    X(PG_X,   "x", IN, "base, in [0, 1]") \
    X(PG_Y,   "y", OUT, "x^g (RG after the last squaring)") \
    X(PG_MX,  "mx", INTERNAL, "operand mux: x in the first clock, then RG (drives both inputs)") \
    X(PG_MUL, "mul", INTERNAL, "multiplier MUL = MX * MX (a squarer), quantized to its own format") \
    X(PG_RG,  "rg", INTERNAL, "register RG <= MUL every clock")
enum { POWG_SIGS(UNIT_SIG_ID) PG_NSIGS };

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
    .ref = &ref_model_powg,
    .summary = "y = x^g, g = 2^k, by repeated squaring: k clocks on one multiplier",
    .source = "Nechyporuk & Romanyuk (2020), sec. III; S. O. Romanyuk et al. (SPIE), sec. 3 (the power of D_g)",
    UNIT_SIGS(POWG_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "square", "one squaring a clock: log2(g) clocks per item" } },
    .nparams = 1,
    .params = { { "g", UNIT_P_POW2, offsetof(unit_cfg, g), 2, 64, 16, NULL, "power, a power of two" } },
    .fmt_rule = "every signal u1.(W-1) (values in [0, 1])",
    .formats = powg_formats, .beats = beats1, .build = powg_build,
    .ideal = powg_ideal, .bound = powg_bound, .ideal_exact = powg_exact, .ideal_interval = powg_interval,
    .sig_used = powg_sig_used,
};
