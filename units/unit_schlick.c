/* unit_schlick.c - Schlick's F_SH = c / (n - n c + c) and Zavalniuk et al. (2022)'s
 * modified F_MSH = 2c / (1.25 (n - n c + 1.25 c)^2), both on the restoring
 * divider of unit_div.c.
 *
 * schlick: the denominator DEN = n - (n - 1) c is in [1, n] and exact in
 * u(I_n).(W-1) (a constant multiplier by the integer n - 1 and a
 * subtractor). The divider needs no normalization: it divides by any
 * DEN > 0 whose quotient fits, and c/DEN <= 1 fits q's one integer bit.
 * It is I_n bits wider than a [1/2, 1] divider instead (area +I_n
 * flip-flops, full adders and mux bits, about 16 GE a bit), which is
 * cheaper than the leading-zero counter and two barrel shifters that
 * normalizing would take (docs/brdf.md compares the two).
 *
 * mschlick: U = n - (n - 1.25) c is in [1.25, n]; its square would need
 * 2 I_n integer bits and a (W + I_n)-bit multiplier, so U is normalized:
 *
 *   E   = bits of U's integer part (leading-one detector), U = UN 2^E,
 *   UN  = U 2^-E in [1/2, 1)      barrel shifter (truncates)
 *   V   = UN * UN in [1/4, 1)     W x W multiplier
 *   DEN = V + V/4 = 1.25 V        adder (V/4 is wiring)
 *   F   = 2c 2^(-2E) / DEN        the divider, its dividend shifted right
 *                                 by 2E as it is loaded into R and Q
 *
 * F_MSH(1) = 2/1.25^3 = 1.024 for every n, so q and f keep one integer bit.
 */
#include "units/unit_net.h"
#include "units/units_brdf.h"
#include "vectors/ref_brdf.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stddef.h>

extern const unit_desc unit_schlick, unit_mschlick;

#define MSH_PEAK 1.024      /* F_MSH(1) = 2 / 1.25^3 */

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* Integer bits of n (the largest denominator). */
static int n_ibits(int n) { return brdf_ibits(fmax(n, 1.25)); }

/* ---------------------------------------------------------------- schlick */

#define SH_SIGS(X) \
    X(SH_C,   "c", IN, "cos x, in [0, 1]") \
    X(SH_F,   "f", OUT, "F_SH, in [0, 1]") \
    X(SH_K,   "k", INTERNAL, "constant n - 1") \
    X(SH_T,   "t", INTERNAL, "constant multiplier T = (n - 1) c (shift-and-add)") \
    X(SH_DEN, "den", INTERNAL, "subtractor DEN = n - T, in [1, n]") \
    X(SH_Q,   "q", INTERNAL, "divider's quotient register Q") \
    X(SH_R,   "r", INTERNAL, "divider's remainder register R")
enum { SH_SIGS(UNIT_SIG_ID) SH_NSIGS };

static void sh_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, in = n_ibits(cfg->n);
    out->f[SH_C] = unit_fmt(0, 1, W - 1);
    out->f[SH_F] = unit_fmt(0, 1, W - 1);
    out->f[SH_K] = unit_fmt(0, brdf_ibits(cfg->n - 1), 0);     /* the integer n - 1 */
    out->f[SH_T] = unit_fmt(0, in, W - 1);                      /* (n-1) c, exact */
    out->f[SH_DEN] = unit_fmt(0, in, W - 1);
    out->f[SH_Q] = unit_fmt(0, 1, W - 1);                       /* F_SH(1) = 1 */
    out->f[SH_R] = out->f[SH_DEN];
}

/* The datapath, written once and walked (unit_net.h): building (n->c
 * set), it makes the elements into io; bounding, every value carries its
 * worst-case error and -1 says a format cannot hold its value (no bound).
 * *out is the output's value. docs/brdf.md, "schlick": T and DEN are
 * walk elements (DEN's error e is 0 in the default formats); the divider
 * is a loop, not an element the walk knows: c/DEN moves by at most
 * e/(1 - e), since DEN >= 1 and c <= 1, the quotient is truncated (< 1
 * LSB of q), and f may requantize q. */
static int sh_walk(unet *n, const unit_cfg *cfg, unit_io *io, unet_val *out, char *err, size_t errlen)
{
    const sim_fmt *F = n->fm.f;
    int hw = n->c != NULL;
    double nd = cfg->n;
    unet_val c = unet_input(n, "c", 0);
    c.imag = 1;                                                 /* c in [0, 1] */
    if (!hw && (!brdf_holds(F[SH_C], 0, 1) || !brdf_holds(F[SH_K], 0, nd - 1))) return -1;
    unet_val nc = brdf_uconst(n, unit_fmt(0, n_ibits(cfg->n), 0), "nconst", nd);
    unet_val k = brdf_uconst(n, F[SH_K], "k", nd - 1);
    unet_val t = unet_cmul(n, SH_T, "t", c, k, brdf_cmul);
    unet_val den = unet_sub(n, SH_DEN, "den", nc, t);
    if (hw) {
        io->in[0] = c.s;
        sim_signal *q = dv_build(&unit_schlick, n->c, n->sc, n->clk, &n->fm, io, c.s, den.s, NULL, 0, err, errlen);
        if (!q) return -1;
        *out = unet_shift(n, SH_F, "f", unet_wrap(q, F[SH_Q], -1), 0);
        return 0;
    }
    sim_round r = n->r;
    double e_den = den.err;
    if (e_den >= 0.5 || !brdf_holds(F[SH_T], 0, nd - 1 + t.err) || !brdf_holds(F[SH_DEN], 1 - e_den, nd + e_den))
        return -1;
    double e = e_den / (1 - e_den), qmax = 1 + e;
    if (!brdf_holds(F[SH_Q], 0, qmax)) return -1;
    e += sim_fmt_lsb(F[SH_Q]) + unit_qerr(F[SH_F], F[SH_Q].fbits, r);
    if (!brdf_holds(F[SH_F], 0, 1 + e)) return -1;
    out->err = e;
    return 0;
}

static int sh_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    unet n;
    unet_init(&n, &unit_schlick, f, SIM_RND_TRUNC);     /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    unet_val out;
    if (sh_walk(&n, cfg, io, &out, err, errlen)) return -1;
    io->out[0] = out.s;
    io->scope = sc;
    return 0;
}

static void sh_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = ref_brdf_schlick(in[0], cfg->n);
}

/* The same exactly: c / (n - n c + c), c dyadic, n whole. */
static int sh_ratio(const unit_cfg *cfg, const sim_dy *in, sim_dy *num, sim_dy *den)
{
    sim_dy n, k, t, z;
    sim_dy_int(&n, cfg->n, 0);
    sim_dy_int(&k, cfg->n - 1, 0);
    sim_dy_mul(&t, &k, &in[0]);
    sim_dy_sub(den, &n, &t);
    *num = in[0];
    sim_dy_int(&z, 0, 0);
    return den->ovf || sim_dy_cmp(den, &z) <= 0 ? -1 : 0;
}

/* The walk's bound (sh_walk); INFINITY when a format cannot hold its
 * range. */
static double sh_bound_core(const unit_cfg *cfg, const unit_fmts *f)
{
    unet n;
    unet_init(&n, &unit_schlick, f, cfg->rnd);
    unet_val out;
    return sh_walk(&n, cfg, NULL, &out, NULL, 0) ? INFINITY : out.err;
}

static void sh_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    double e = sh_bound_core(cfg, f);
    per_out[0] = isfinite(e) ? e : brdf_range_bound(f->f[SH_F], 1);
    /* An input format that cannot hold [0, 1] wraps inputs anywhere (and
     * n - (n-1)c can reach 0): no bound. */
    if (!brdf_holds(f->f[SH_C], 0, 1)) per_out[0] = INFINITY;
}

const unit_desc unit_schlick = {
    .name = "schlick",
    .ref = &ref_model_schlick,
    .fmt_fixed = { "q" },
    .summary = "F_SH = c/(n - n c + c) (Schlick's stand-in for cos^n) on the restoring divider",
    .source = "Zavalniuk et al. (2022), eq. 2",
    UNIT_SIGS(SH_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "restoring", "one quotient bit a clock: W clocks" } },
    .nparams = 1,
    .params = { { "n", UNIT_P_INT, offsetof(unit_cfg, n), 1, 1024, 32, NULL, "specular exponent n" } },
    .fmt_rule = "c, f, q u1.(W-1); k u(I).0 for the integer n-1; t, den, r uI.(W-1) with I the "
                "integer bits of n",
    .formats = sh_formats, .beats = beats1, .build = sh_build, .ideal = sh_ideal, .bound = sh_bound, .ideal_ratio = sh_ratio,
};

/* --------------------------------------------------------------- mschlick */

#define MS_SIGS(X) \
    X(MS_C,   "c", IN, "cos x, in [0, 1]") \
    X(MS_F,   "f", OUT, "F_MSH, in [0, 1.024]") \
    X(MS_K,   "k", INTERNAL, "constant n - 1.25") \
    X(MS_T,   "t", INTERNAL, "constant multiplier T = (n - 1.25) c") \
    X(MS_U,   "u", INTERNAL, "subtractor U = n - T, in [1.25, n]") \
    X(MS_E,   "e", INTERNAL, "leading-one detector: bits of U's integer part") \
    X(MS_UN,  "un", INTERNAL, "barrel shifter UN = U 2^-E, in [1/2, 1)") \
    X(MS_V,   "v", INTERNAL, "multiplier V = UN * UN") \
    X(MS_DEN, "den", INTERNAL, "adder DEN = V + V/4 = 1.25 V") \
    X(MS_Q,   "q", INTERNAL, "divider's quotient register Q = 2c 2^-2E / DEN") \
    X(MS_R,   "r", INTERNAL, "divider's remainder register R")
enum { MS_SIGS(UNIT_SIG_ID) MS_NSIGS };

static void ms_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, in = n_ibits(cfg->n);
    double k = cfg->n - 1.25;
    int neg = k < 0, ik = brdf_ibits(fabs(k));
    out->f[MS_C] = unit_fmt(0, 1, W - 1);
    out->f[MS_F] = unit_fmt(0, 1, W - 1);                       /* up to 1.024 */
    out->f[MS_K] = unit_fmt(neg, ik + neg, 2);                  /* n - 1.25, exact */
    out->f[MS_T] = unit_fmt(neg, ik + neg, W + 1);              /* k c, exact */
    out->f[MS_U] = unit_fmt(0, in, W + 1);                      /* exact */
    out->f[MS_E] = unit_fmt(0, brdf_bitlen((uint64_t)in), 0);
    out->f[MS_UN] = unit_fmt(0, 0, W);
    out->f[MS_V] = unit_fmt(0, 0, W);
    out->f[MS_DEN] = unit_fmt(0, 1, W + 2);                     /* V + V/4, exact */
    out->f[MS_Q] = unit_fmt(0, 1, W - 1);
    out->f[MS_R] = out->f[MS_DEN];
}

/* E = bit length of U's integer part (U >= 1, so E >= 1): a leading-one
 * detector. */
typedef struct ms_norm { int fu, fun, fe; } ms_norm;
static int lzd(int64_t u_raw, int fu) { return brdf_bitlen((uint64_t)(u_raw >> fu)); }
static int64_t f_lzd(const int64_t *in, void *u)
{
    const ms_norm *nm = u;
    return (int64_t)((uint64_t)lzd(in[0], nm->fu) << nm->fe);    /* E's real value in E's format */
}
/* UN = floor(U 2^-E) in UN's format: the barrel shifter drops bits. It
 * takes its shift from U's own leading one rather than from the signal E,
 * so that UN never sees a new U with the old E (a one-delta glitch that
 * would reach V as a spurious overflow). */
static int64_t f_norm(const int64_t *in, void *u)
{
    const ms_norm *nm = u;
    int sh = nm->fu + lzd(in[0], nm->fu) - nm->fun;    /* right shift of U's raw */
    if (sh >= 63) return 0;
    if (sh <= -63) return 0;
    return sh >= 0 ? in[0] >> sh : (int64_t)((uint64_t)in[0] << -sh);
}
/* The dividend's right shift, 2E, as an integer. */
static int64_t f_twice(const int64_t *in, void *u)
{
    const ms_norm *nm = u;
    return 2 * (in[0] >> nm->fe);
}

/* For the Verilog export: E's leading-one detector and UN's barrel shifter
 * as RTL (sim_logic_verilog), the same functions as f_lzd and f_norm. The
 * bit length of U's integer part (64 for a negative U, as lzd computes it
 * on the raw as unsigned) as %t_l, 7 bits. */
static int ms_vl_lzd(char *t, size_t len, sim_fmt fu)
{
    int wi = fu.width - fu.fbits, n = snprintf(t, len, "wire [6:0] %%t_l = ");
    for (int j = wi - 1; j >= 0; j--)
        n += snprintf(t + n, len - (size_t)n, "%%0[%d] ? 7'd%d : ", fu.fbits + j, fu.is_signed && j == wi - 1 ? 64 : j + 1);
    n += snprintf(t + n, len - (size_t)n, "7'd0;\n");
    return n;
}

static void ms_vl(sim_signal *e, sim_signal *un, sim_fmt fu, sim_fmt fe, sim_fmt fun)
{
    char t[8192];
    int n = ms_vl_lzd(t, sizeof t, fu), T = 7 + fe.fbits;
    char zeros[32] = "";
    if (fe.fbits) snprintf(zeros, sizeof zeros, ", %d'b0", fe.fbits);
    n += snprintf(t + n, sizeof t - (size_t)n, "wire [%d:0] %%t_s = {%%t_l%s};\n", T - 1, zeros);
    if (fe.width <= T) snprintf(t + n, sizeof t - (size_t)n, "assign %%y = %%t_s[%d:0];\n", fe.width - 1);
    else snprintf(t + n, sizeof t - (size_t)n, "assign %%y = {%d'b0, %%t_s};\n", fe.width - T);
    sim_logic_verilog(e, t);

    /* UN = floor(U 2^-sh), sh = fu + lzd - fun, for each lzd U can have */
    int wi = fu.width - fu.fbits, wu = fu.width, wn = fun.width;
    int shmin = 1000, shmax = -1000;
    for (int l = 0; l <= wi; l++) {
        int sh = fu.fbits + (fu.is_signed && l == wi ? 64 : l) - fun.fbits;
        if (sh <= -63 || sh >= 63) continue;
        if (sh < shmin) shmin = sh;
        if (sh > shmax) shmax = sh;
    }
    n = ms_vl_lzd(t, sizeof t, fu);
    if (shmin > shmax) { snprintf(t, sizeof t, "assign %%y = %d'b0;", wn); sim_logic_verilog(un, t); return; }
    int base = shmin < 0 ? -shmin : 0, top = base + (shmax > 0 ? shmax : 0) + wn + 1, ext = top - base - wu;
    if (ext < 1) ext = 1;
    int TT = base + wu + ext;
    char sg[32], bz[32] = "";
    snprintf(sg, sizeof sg, fu.is_signed ? "%%0[%d]" : "1'b0", wu - 1);
    if (base) snprintf(bz, sizeof bz, ", %d'b0", base);
    n += snprintf(t + n, sizeof t - (size_t)n, "wire [%d:0] %%t_e = {{%d{%s}}, %%0%s};\n", TT - 1, ext, sg, bz);
    n += snprintf(t + n, sizeof t - (size_t)n, "reg [%d:0] %%t_r;\nalways @* begin\n    case (%%t_l)\n", wn - 1);
    for (int l = 0; l <= wi; l++) {
        int L = fu.is_signed && l == wi ? 64 : l, sh = fu.fbits + L - fun.fbits;
        if (sh <= -63 || sh >= 63) n += snprintf(t + n, sizeof t - (size_t)n, "        7'd%d: %%t_r = %d'b0;\n", L, wn);
        else n += snprintf(t + n, sizeof t - (size_t)n, "        7'd%d: %%t_r = %%t_e[%d:%d];\n", L, base + sh + wn - 1, base + sh);
    }
    snprintf(t + n, sizeof t - (size_t)n, "        default: %%t_r = %d'b0;\n    endcase\nend\nassign %%y = %%t_r;\n", wn);
    sim_logic_verilog(un, t);
}

static int ms_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    int n = cfg->n, in = n_ibits(n);
    const sim_fmt *F = f->f;
    sim_signal *cin = io->in[0] = sim_signal_new(c, sc, "c", F[MS_C], SIM_KIND_INPUT);
    sim_signal *nc = brdf_const(c, sc, "nconst", unit_fmt(0, in, 0), n);
    sim_signal *k = brdf_const(c, sc, "k", F[MS_K], n - 1.25);
    sim_signal *t = brdf_cmul(c, sc, "t", F[MS_T], cin, k);
    sim_signal *u = sim_sub(c, sc, "u", F[MS_U], nc, t);
    ms_norm *nm = sim_alloc(c, sizeof *nm);
    nm->fu = F[MS_U].fbits;
    nm->fun = F[MS_UN].fbits;
    nm->fe = F[MS_E].fbits;
    int ubits = F[MS_U].ibits;
    sim_signal *e = sim_logic(c, sc, "e", F[MS_E], 1, &u, f_lzd, nm, 3.0 * ubits);
    double shifter = brdf_bitlen((uint64_t)ubits) * F[MS_UN].width * SIM_GE_MUX2;
    sim_signal *un = sim_logic(c, sc, "un", F[MS_UN], 1, &u, f_norm, nm, shifter);
    ms_vl(e, un, F[MS_U], F[MS_E], F[MS_UN]);
    sim_signal *v = sim_mul(c, sc, "v", F[MS_V], un, un);
    sim_fmt fv = F[MS_V];
    sim_signal *v4 = sim_shift(c, sc, "v4", unit_fmt(fv.is_signed, fv.ibits, fv.fbits + 2), v, -2);
    sim_signal *den = sim_add(c, sc, "den", F[MS_DEN], v, v4);
    /* Dividend 2c (wiring), shifted right by 2E (wiring of E). */
    sim_signal *c2 = sim_shift(c, sc, "c2", unit_fmt(0, F[MS_C].ibits + 1, F[MS_C].fbits), cin, 1);
    sim_signal *shr = sim_logic(c, sc, "shr", unit_fmt(0, brdf_bitlen((uint64_t)ubits) + 1, 0), 1, &e, f_twice, nm, 0);
    sim_signal *q = dv_build(&unit_mschlick, c, sc, clk, f, io, c2, den, shr, 2 * ubits, err, errlen);
    if (!q) return -1;
    io->out[0] = sim_shift(c, sc, "f", F[MS_F], q, 0);
    io->scope = sc;
    return 0;
}

static void ms_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = ref_brdf_mschlick(in[0], cfg->n);
}

/* The same exactly: 2c / (1.25 u^2), u = n - (n - 1.25) c. */
static int ms_ratio(const unit_cfg *cfg, const sim_dy *in, sim_dy *num, sim_dy *den)
{
    sim_dy n, k, t, u, c54, z, two;
    sim_dy_int(&n, cfg->n, 0);
    sim_dy_int(&k, 4 * (int64_t)cfg->n - 5, 2);      /* n - 1.25 */
    sim_dy_int(&c54, 5, 2);                          /* 1.25 */
    sim_dy_int(&two, 2, 0);
    sim_dy_mul(&t, &k, &in[0]);
    sim_dy_sub(&u, &n, &t);
    sim_dy_mul(&u, &u, &u);
    sim_dy_mul(den, &c54, &u);
    sim_dy_mul(num, &two, &in[0]);
    sim_dy_int(&z, 0, 0);
    return den->ovf || num->ovf || sim_dy_cmp(den, &z) <= 0 ? -1 : 0;
}

/* docs/brdf.md, "mschlick". Errors of U (0 in the default formats) move
 * 1.6c/U^2 by at most 1.6 e (2U + e)/(U^2 (U - e)^2), largest at the
 * smallest U. Normalizing is exact; UN's truncation, V's quantization and
 * DEN's make DEN off by a relative delta, which moves the quotient by at
 * most F delta/(1 - delta); the quotient is truncated; f requantizes. */
static double ms_bound_core(const unit_cfg *cfg, const unit_fmts *f)
{
    const sim_fmt *F = f->f;
    sim_round r = cfg->rnd;
    double n = cfg->n, k = n - 1.25, umin = fmin(n, 1.25), umax = fmax(n, 1.25);
    if (!brdf_holds(F[MS_C], 0, 1) || !brdf_holds(F[MS_K], fmin(k, 0), fmax(k, 0))) return INFINITY;
    int src_t = F[MS_C].fbits + brdf_const_eff(k, F[MS_K]);
    int eff_t = src_t < F[MS_T].fbits ? src_t : F[MS_T].fbits;
    double e_t = brdf_const_err(k, F[MS_K]) + unit_qerr(F[MS_T], src_t, r);
    double q_u = unit_qerr(F[MS_U], eff_t < 0 ? 0 : eff_t, r);
    double e_u = e_t + q_u;                                                       /* U = n - T */
    /* trunc lowers T (so raises U) and lowers U by at most q_u: U stays
     * above umin - q_u; rounding may move either way */
    double ulo = umin - (r == SIM_RND_TRUNC ? q_u : e_u);
    /* T = k c keeps k's sign whatever its rounding (a quantization of a
     * value >= 0 is >= 0): only the far end widens by e_t. A wider c used to
     * fail this with lo = -e_t and fall back to a made-up bound (issue 9). */
    if (ulo < 1 || !brdf_holds(F[MS_T], k < 0 ? k - e_t : 0, k < 0 ? 0 : k + e_t)
        || !brdf_holds(F[MS_U], ulo, umax + e_u) || !brdf_holds(F[MS_E], 0, F[MS_U].ibits))
        return INFINITY;
    double e_f = 1.6 * e_u * (2 * umin + e_u) / (umin * umin * ulo * ulo);
    /* UN in [1/2, 1): exact when UN keeps every bit U can have below its
     * leading one, else below one LSB (the shifter truncates). */
    double q_un = F[MS_UN].fbits >= F[MS_U].fbits + F[MS_U].ibits ? 0 : sim_fmt_lsb(F[MS_UN]);
    double q_v = unit_qerr(F[MS_V], 2 * F[MS_UN].fbits, r);
    double q_den = unit_qerr(F[MS_DEN], F[MS_V].fbits + 2, r);
    double un_max = 1 - sim_fmt_lsb(F[MS_UN]);                /* UN < 1 after truncation */
    int v_ovf = 0;
    sim_fx_from_real(un_max * un_max, F[MS_V], r, SIM_OVF_SAT, &v_ovf);    /* V's largest value */
    if (!brdf_holds(F[MS_UN], 0, un_max) || v_ovf || !brdf_holds(F[MS_V], 0, 0)) return INFINITY;
    /* Relative to UN^2 >= 1/4 and to DEN >= 5/16. */
    double delta = 4 * q_un + 4 * q_v + q_den / 0.3125;
    if (delta >= 0.5 || !brdf_holds(F[MS_DEN], 0, 1.25 * (1 + delta))) return INFINITY;
    /* 1.6 c / U^2 peaks at c = 1 (1.024); U off by e_u raises it at most so. */
    double fmax_hw = MSH_PEAK * (umin / ulo) * (umin / ulo);
    e_f += fmax_hw * delta / (1 - delta);
    double qmax = fmax_hw / (1 - delta);
    if (!brdf_holds(F[MS_Q], 0, qmax)) return INFINITY;
    e_f += sim_fmt_lsb(F[MS_Q]) + unit_qerr(F[MS_F], F[MS_Q].fbits, r);
    if (!brdf_holds(F[MS_F], 0, MSH_PEAK + e_f)) return INFINITY;
    return e_f;
}

static void ms_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    double e = ms_bound_core(cfg, f);
    per_out[0] = isfinite(e) ? e : brdf_range_bound(f->f[MS_F], MSH_PEAK);
    if (!brdf_holds(f->f[MS_C], 0, 1)) per_out[0] = INFINITY;     /* as schlick */
}

const unit_desc unit_mschlick = {
    .name = "mschlick",
    .ref = &ref_model_mschlick,
    .fmt_fixed = { "q" },
    .summary = "F_MSH = 2c/(1.25 (n - n c + 1.25 c)^2): normalize, square, divide",
    .source = "Zavalniuk et al. (2022), eq. 5",
    UNIT_SIGS(MS_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "restoring", "one quotient bit a clock: W clocks" } },
    .nparams = 1,
    .params = { { "n", UNIT_P_INT, offsetof(unit_cfg, n), 1, 1024, 32, NULL, "specular exponent n" } },
    .fmt_rule = "c, f, q u1.(W-1); k uI.2, t uI.(W+1) for n - 1.25; u uI.(W+1) with I the integer "
                "bits of n; e u(bits of I).0; un, v u0.W; den, r u1.(W+2)",
    .formats = ms_formats, .beats = beats1, .build = ms_build, .ideal = ms_ideal, .bound = ms_bound, .ideal_ratio = ms_ratio,
};
