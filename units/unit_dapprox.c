/* unit_dapprox.c - d_approx and ward_approx: a clamped linear base raised
 * to a power of two on the power engine of unit_powg.c, one builder for
 * both (they differ only in constants, which a table supplies).
 *
 *   d_approx     D_g = c0 max(0, 1 - k (1 - c))^g,  k = (2/m^2 - 4)/g, c0 = 1/(4m^2)
 *   ward_approx  e   =    max(0, 1 - k (1 - c))^16, k = 1/(8 alpha^2)
 *
 * Datapath (combinational in front of the engine, then the engine's
 * squarings, then a constant scale for d_approx):
 *
 *   OM    = 1 - c                    subtractor
 *   P     = k * OM                   constant multiplier (shift-and-add)
 *   BASE  = 1 - P                    subtractor
 *   CLAMP = BASE >= 0 ? BASE : 0     block key on BASE's sign bit
 *   RG    <= CLAMP^2, then RG^2 ...  powg's program, log2(g) clocks
 *   d     = c0 * RG                  constant multiplier (d_approx only)
 *
 * The base is formed as 1 - k (1 - c), not (1 - k) + k c: at the peak,
 * c = 1, it is exactly 1 whatever the rounding of k, so the output's peak
 * is exactly quant(c0) <= c0. The clamp is what the papers' printed form
 * lacks: beyond the cosine 1 - 1/k (about 49 deg for m = 0.2) their even
 * power of a negative base rises again.
 */
#include "units/unit_net.h"
#include "units/units_brdf.h"
#include "vectors/ref_brdf.h"
#include <math.h>
#include <stddef.h>

/* The signals of both units, one list (unit.h, UNIT_SIG_ID): they differ
 * in the output's name and d_approx's c0 at the end. */
#define DA_SIGS(X, out_name, out_what) \
    X(S_C,     "c", IN, "cos g = N.H, in [0, 1]") \
    X(S_OUT,   out_name, OUT, out_what) \
    X(S_OM,    "om", INTERNAL, "subtractor OM = 1 - c") \
    X(S_K,     "k", INTERNAL, "constant k (slope of the base)") \
    X(S_P,     "p", INTERNAL, "constant multiplier P = k * OM (shift-and-add)") \
    X(S_BASE,  "base", INTERNAL, "subtractor BASE = 1 - P") \
    X(S_CLAMP, "clamp", INTERNAL, "block key: BASE, or 0 when BASE < 0") \
    X(S_MX,    "mx", INTERNAL, "operand mux: CLAMP in the first clock, then RG (drives both inputs)") \
    X(S_MUL,   "mul", INTERNAL, "multiplier MUL = MX * MX (a squarer)") \
    X(S_RG,    "rg", INTERNAL, "register RG <= MUL every clock")
#define D_SIGS(X) DA_SIGS(X, "d", "D_g, in [0, 1/(4m^2)]") \
    X(S_C0,    "c0", INTERNAL, "constant c0 = 1/(4m^2); d = c0 * RG by a constant multiplier")
#define W_SIGS(X) DA_SIGS(X, "e", "the 16th power, in [0, 1]")
enum { D_SIGS(UNIT_SIG_ID) S_NSIGS };

/* What distinguishes the two units. */
typedef struct da_kind {
    const unit_desc *u;
    int has_c0;                       /* d_approx: the output is c0 * RG */
    void (*consts)(const unit_cfg *cfg, double *k, double *c0, int *g);
    double (*ref)(const unit_cfg *cfg, double c);
} da_kind;

static void d_consts(const unit_cfg *cfg, double *k, double *c0, int *g)
{
    double m2 = cfg->m * cfg->m;
    *g = cfg->g;
    *k = (2.0 / m2 - 4.0) / cfg->g;
    *c0 = 1.0 / (4.0 * m2);
}
static void w_consts(const unit_cfg *cfg, double *k, double *c0, int *g)
{
    *g = 16;
    *k = 1.0 / (8.0 * cfg->alpha * cfg->alpha);
    *c0 = 1.0;
}
static double d_ref(const unit_cfg *cfg, double c) { return ref_brdf_dg_clamped(c, cfg->m, cfg->g); }
static double w_ref(const unit_cfg *cfg, double c) { return ref_brdf_ward_exp_approx_clamped(c, cfg->alpha); }

extern const unit_desc unit_d_approx, unit_ward_approx;
static const da_kind K_D = { &unit_d_approx, 1, d_consts, d_ref };
static const da_kind K_W = { &unit_ward_approx, 0, w_consts, w_ref };

/* Largest base and largest power: for k < 0 (m > 1/sqrt 2) the base
 * exceeds 1 away from the peak, up to 1 - k at c = 0. */
static double base_max(double k) { return k < 0 ? 1.0 - k : 1.0; }
static double chain_max(double k, int g) { return pow(base_max(k), g); }

/* "II" then "RR": powg's program for g = 2^k; NULL if g is not one. */
static const char *da_prog(int g, char *buf, size_t len)
{
    if (g < 2 || (g & (g - 1)) || len < 2 * 7 + 1) return NULL;
    size_t n = 0;
    for (int p = 1; p < g; p *= 2, n += 2) { buf[n] = n ? 'R' : 'I'; buf[n + 1] = n ? 'R' : 'I'; }
    buf[n] = 0;
    return buf;
}

/* g = 2 squares CLAMP once: the operand is CLAMP itself, no mux. */
static int da_sig_used(const da_kind *kd, const unit_cfg *cfg, int i)
{
    double k, c0;
    int g;
    char prog[16];
    kd->consts(cfg, &k, &c0, &g);
    return pw_sig_built(kd->u, da_prog(g, prog, sizeof prog), i);
}
static int d_sig_used(const unit_cfg *cfg, int i) { return da_sig_used(&K_D, cfg, i); }
static int w_sig_used(const unit_cfg *cfg, int i) { return da_sig_used(&K_W, cfg, i); }

/* ---------------------------------------------------------------- formats */

static void da_formats(const da_kind *kd, const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, g;
    double k, c0;
    kd->consts(cfg, &k, &c0, &g);
    int neg = k < 0, ik = brdf_ibits(fabs(k));
    int ic = brdf_ibits(chain_max(k, g)), ib = brdf_ibits(fmax(1.0, fabs(1.0 - k))) + 1;
    sim_fmt frac = unit_fmt(0, 1, W - 1), core = unit_fmt(0, ic, W - ic);
    out->f[S_C] = frac;
    out->f[S_OM] = frac;
    out->f[S_K] = unit_fmt(neg, ik + neg, W - ik);          /* W significant bits */
    out->f[S_P] = unit_fmt(neg, ik + neg, W - 1);           /* the base's precision */
    out->f[S_BASE] = unit_fmt(1, ib, W - 1);
    out->f[S_CLAMP] = out->f[S_MX] = out->f[S_MUL] = out->f[S_RG] = core;
    if (kd->has_c0) {
        int i0 = brdf_ibits(c0), id = brdf_ibits(c0 * chain_max(k, g));
        out->f[S_C0] = unit_fmt(0, i0, W - i0);
        out->f[S_OUT] = unit_fmt(0, id, W - id);
    } else {
        out->f[S_OUT] = core;
    }
}
static void d_formats(const unit_cfg *cfg, unit_fmts *out) { da_formats(&K_D, cfg, out); }
static void w_formats(const unit_cfg *cfg, unit_fmts *out) { da_formats(&K_W, cfg, out); }

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* ------------------------------------------------------------------ build */

/* BASE >= 0, i.e. P <= 1 (P's raw against 1 in P's format): the
 * subtractor's borrow. Taken from P rather than from BASE so that the
 * block key sees BASE and its sign change in the same delta cycle (a sign
 * computed from BASE arrives a delta later, and the key would pass a
 * negative BASE for one delta: a glitch the overflow counters would
 * count). */
static int64_t f_base_pos(const int64_t *in, void *u) { return in[0] <= *(const int64_t *)u; }

static sim_signal *da_base_pos(sim_ctx *c, sim_scope *sc, sim_fmt fp, sim_signal *p)
{
    int64_t *one_p = sim_alloc(c, sizeof *one_p);
    *one_p = fp.fbits < 62 ? (int64_t)1 << fp.fbits : INT64_MAX;
    sim_signal *pos = sim_logic(c, sc, "base_pos", unit_fmt(0, 1, 0), 1, &p, f_base_pos, one_p, 0.67);
    /* the same comparison as RTL, for the Verilog export */
    char vt[160];
    if (*one_p > sim_fmt_raw_max(fp)) snprintf(vt, sizeof vt, "assign %%y = 1'b1;");
    else snprintf(vt, sizeof vt, fp.is_signed ? "assign %%y = $signed(%%0) <= $signed(%d'h%llx);" : "assign %%y = %%0 <= %d'h%llx;",
                  fp.width, (unsigned long long)*one_p);
    sim_logic_verilog(pos, vt);
    return pos;
}

/* The datapath, written once and walked (unit_net.h): building (n->c
 * set), it makes the elements into io; bounding, every value carries its
 * worst-case error and -1 says a format cannot hold its value (no bound).
 * *out is the output's value. docs/brdf.md, "d_approx and ward_approx":
 * the base's error (constant k, quantized products), through the
 * 1-Lipschitz clamp, into the power engine's walk, then the output scale.
 * The clamp refines the walk: k's error enters P as ek (1 - c), and
 * beyond 1 - c = t_max both the hardware's and the ideal base are clamped
 * to 0, so where CLAMP passes BASE its error is ek t_max plus the rest. */
static int da_walk(unet *n, const da_kind *kd, const unit_cfg *cfg, unit_io *io, unet_val *out)
{
    int g;
    double k, c0;
    char prog[16];
    kd->consts(cfg, &k, &c0, &g);
    if (!da_prog(g, prog, sizeof prog)) return -1;
    const unit_desc *u = kd->u;
    const sim_fmt *F = n->fm.f;
    int hw = n->c != NULL;
    unet_val c = unet_input(n, u->sigs[S_C].name, 0);
    if (hw) io->in[0] = c.s;
    if (!hw && !brdf_holds(F[S_C], 0, 1)) return -1;
    sim_fmt f1 = unit_fmt(0, 1, 0);
    unet_val one = unet_wrap(hw ? sim_const_raw(n->c, n->sc, "one", f1, 1) : NULL, f1, -1);
    unet_val om = unet_sub(n, S_OM, "om", one, c);
    unet_val kc = brdf_uconst(n, F[S_K], "k", k);
    unet_val p = unet_cmul(n, S_P, "p", om, kc, brdf_cmul);
    unet_val base = unet_sub(n, S_BASE, "base", one, p);
    sim_signal *pos = hw ? da_base_pos(n->c, n->sc, F[S_P], p.s) : NULL;
    if (!hw) {
        double e_om = om.err, ek = kc.err, kh = fabs(k) + ek;      /* kh bounds |k_h| */
        double p_hi = kh * (1 + e_om) + p.q;
        if (!brdf_holds(F[S_OM], 0, 1 + e_om) || !brdf_holds(F[S_K], fmin(k, 0), fmax(k, 0))
            || !brdf_holds(F[S_P], k < 0 ? -p_hi : 0, k < 0 ? 0 : p_hi)
            || !brdf_holds(F[S_BASE], k < 0 ? 1 - base.q : 1 - p_hi - base.q, k < 0 ? 1 + p_hi + base.q : 1))
            return -1;
        /* BASE's error away from the k term, and the largest 1 - c where
         * either base can still be positive */
        double e0 = kh * e_om + p.q + base.q, t_max = 1.0;
        if (k > ek) t_max = fmin(1.0, (1.0 + e0) / (k - ek));
        base.err = ek * t_max + e0;
    }
    unet_val clamp = unet_bk(n, S_CLAMP, "clamp", pos, base, 1);
    /* CLAMP's ideal value is in [0, max(1, 1 - k)]; the engine takes its
     * magnitude as its format's largest (docs/brdf.md) */
    clamp.imag = base_max(k);
    clamp.mag = ldexp(1.0, F[S_CLAMP].is_signed ? F[S_CLAMP].ibits - 1 : F[S_CLAMP].ibits);
    if (!hw && !brdf_holds(F[S_CLAMP], 0, clamp.imag + clamp.err)) return -1;
    unet_val rg;
    if (pw_engine(n, io, prog, clamp, &rg)) return -1;
    if (kd->has_c0) {
        if (!hw && !brdf_holds(F[S_C0], 0, c0)) return -1;
        unet_val c0c = brdf_uconst(n, F[S_C0], "c0", c0);
        *out = unet_cmul(n, S_OUT, u->sigs[S_OUT].name, rg, c0c, brdf_cmul);
    } else {
        *out = unet_shift(n, S_OUT, u->sigs[S_OUT].name, rg, 0);
    }
    if (!hw && !brdf_holds(F[S_OUT], 0, c0 * rg.imag + out->err)) return -1;
    return 0;
}

static int da_build(const da_kind *kd, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                    const unit_cfg *cfg, const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    int g;
    double k, c0;
    char prog[16];
    kd->consts(cfg, &k, &c0, &g);
    if (!da_prog(g, prog, sizeof prog)) {
        snprintf(err, errlen, "%s: g = %d is not a power of two (2, 4, ..., 64)", kd->u->name, g);
        return -1;
    }
    unet n;
    unet_init(&n, kd->u, f, SIM_RND_TRUNC);     /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    unet_val out;
    if (da_walk(&n, kd, cfg, io, &out)) { snprintf(err, errlen, "%s: internal: bad engine program", kd->u->name); return -1; }
    io->out[0] = out.s;
    io->scope = sc;
    return 0;
}
static int d_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                   const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{ return da_build(&K_D, c, sc, clk, cfg, f, io, err, errlen); }
static int w_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                   const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{ return da_build(&K_W, c, sc, clk, cfg, f, io, err, errlen); }

/* ------------------------------------------------------------ ideal, bound */

static void d_ideal(const unit_cfg *cfg, const double *in, double *out) { out[0] = d_ref(cfg, in[0]); }
static void w_ideal(const unit_cfg *cfg, const double *in, double *out) { out[0] = w_ref(cfg, in[0]); }

/* The bound is the walk's (da_walk): INFINITY when a format cannot hold
 * its range. */
static double da_bound_core(const da_kind *kd, const unit_cfg *cfg, const unit_fmts *f, double *ideal_max)
{
    int g;
    double k, c0;
    kd->consts(cfg, &k, &c0, &g);
    *ideal_max = c0 * chain_max(k, g);
    unet n;
    unet_init(&n, kd->u, f, cfg->rnd);
    unet_val out;
    return da_walk(&n, kd, cfg, NULL, &out) ? INFINITY : out.err;
}

static void da_bound(const da_kind *kd, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    double imax, e = da_bound_core(kd, cfg, f, &imax);
    per_out[0] = isfinite(e) ? e : brdf_range_bound(f->f[S_OUT], imax);
    /* An input format that cannot hold [0, 1] wraps inputs anywhere: no bound. */
    if (!brdf_holds(f->f[S_C], 0, 1)) per_out[0] = INFINITY;
}
static void d_bound(const unit_cfg *cfg, const unit_fmts *f, double *o) { da_bound(&K_D, cfg, f, o); }
static void w_bound(const unit_cfg *cfg, const unit_fmts *f, double *o) { da_bound(&K_W, cfg, f, o); }

/* ------------------------------------------------------------- descriptors */

const unit_desc unit_d_approx = {
    .name = "d_approx",
    .ref = &ref_model_d_approx,
    .summary = "D_g = (1/(4m^2)) max(0, ((2/m^2-4)/g)(c-1)+1)^g: Beckmann D as one clamped power",
    .source = "Nechyporuk & Romanyuk (2020), sec. III; S. O. Romanyuk et al. (SPIE), sec. 3 (D4, D8, D16)",
    UNIT_SIGS(D_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "square", "base and first squaring in one clock, then a squaring a clock: log2(g) clocks" } },
    .nparams = 2,
    .params = {
        { "m", UNIT_P_REAL, offsetof(unit_cfg, m), 0.05, 1.0, 0.2, NULL, "Beckmann roughness" },
        { "g", UNIT_P_POW2, offsetof(unit_cfg, g), 2, 64, 16, NULL, "power, a power of two" } },
    .fmt_rule = "c, om u1.(W-1); k uI.(W-I) and p uI.(W-1) with I = integer bits of k (signed "
                "when m > 1/sqrt 2); base s(I+1).(W-1); clamp, mx, mul, rg uJ.(W-J), J = integer "
                "bits of the largest power (1 for m <= 1/sqrt 2); c0 and d the same rule for c0 and "
                "its peak",
    .formats = d_formats, .beats = beats1, .build = d_build, .ideal = d_ideal, .bound = d_bound,
    .sig_used = d_sig_used,
};

const unit_desc unit_ward_approx = {
    .name = "ward_approx",
    .ref = &ref_model_ward_approx,
    .summary = "e = max(0, (c-1)/(8 alpha^2)+1)^16 ~ exp(-tan^2/alpha^2), Ward's exponential as a power",
    .source = "Nechyporuk & Romanyuk (2020), sec. III; S. O. Romanyuk et al. (SPIE), sec. 3 (Ward)",
    UNIT_SIGS(W_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "square", "base and first squaring in one clock, then a squaring a clock: 4 clocks" } },
    .nparams = 1,
    .params = { { "alpha", UNIT_P_REAL, offsetof(unit_cfg, alpha), 0.05, 1.0, 0.2, NULL, "Ward roughness" } },
    .fmt_rule = "c, om u1.(W-1); k uI.(W-I) and p uI.(W-1) with I = integer bits of 1/(8 alpha^2); "
                "base s(I+1).(W-1); clamp, mx, mul, rg, e u1.(W-1)",
    .formats = w_formats, .beats = beats1, .build = w_build, .ideal = w_ideal, .bound = w_bound,
    .sig_used = w_sig_used,
};
