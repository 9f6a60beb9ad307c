/* unit_shade.c - shade: one pixel of the scene's default shading in
 * hardware (scene/scene_shade.c's Blinn path for one directional light of
 * intensity 1), the per-pixel side of the comparison of Nechyporuk &
 * Romanyuk (2020), sec. IV:
 *
 *   i = clamp(ka + kd max(0, u.L) + ks (u.L > 0 && u.H > 0 ? (u.H)^n : 0), 0, 1),
 *   u = N/|N|
 *
 * for the normal N as interpolated (|N| in [1/2, 1]) and the frame's
 * constant unit vectors L and H. Datapath (unit_nrm.c, unit_rec.c, the
 * power engine's program of unit_pow_n.c):
 *
 *   NN = N.N, DL = N.L, DH = N.H     exact dot products (their signs exact)
 *   DLQ = DL > 0 ? DL : 0            block keys, quantized to the working
 *   DHQ = DL > 0 && DH > 0 ? DH : 0  format (the gates are exact)
 *   ROOT = sqrt(NN), RINV = 1/ROOT   the two digit recurrences
 *   NL = DLQ RINV, NH = DHQ RINV     u.L and u.H where they count
 *   HL = NH^n                        square and multiply (the highlight)
 *   DIF = kd NL, KSH = ks HL, SUM = ka + DIF + KSH
 *   i = SUM >= 1 ? 1 : SUM
 *
 * Because the gates read the exact dot products, the hardware switches
 * the highlight on exactly where the ideal does: the bound needs no term
 * for a highlight the hardware shows and the ideal does not.
 */
#include "units/unit_nrm.h"
#include "units/units_brdf.h"
#include "vectors/ref_shade.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stdio.h>
#include <stddef.h>
#include <string.h>

#define SH_SIGS(X) \
    X(S_NX, "nx", IN, "normal N as interpolated, x (|N| in [1/2, 1])") \
    X(S_NY, "ny", IN, "normal, y") \
    X(S_NZ, "nz", IN, "normal, z") \
    X(S_LX, "lx", IN, "unit vector L towards the light, x (a frame constant)") \
    X(S_LY, "ly", IN, "L, y") \
    X(S_LZ, "lz", IN, "L, z") \
    X(S_HX, "hx", IN, "unit half vector H = normalize(L + V), x (a frame constant)") \
    X(S_HY, "hy", IN, "H, y") \
    X(S_HZ, "hz", IN, "H, z") \
    X(S_KA, "ka", IN, "ambient term, in [0, 1]") \
    X(S_KD, "kd", IN, "diffuse coefficient, in [0, 1]") \
    X(S_KS, "ks", IN, "specular coefficient, in [0, 1]") \
    X(S_I,  "i", OUT, "intensity, clamp(ka + kd u.L + ks (u.H)^n, 0, 1)") \
    X(S_NN, "nn", INTERNAL, "N.N: three squares and two adders, exact (so are their elements)") \
    X(S_DL, "dl", INTERNAL, "N.L, exact") \
    X(S_DH, "dh", INTERNAL, "N.H, exact") \
    X(S_DLQ, "dlq", INTERNAL, "block key: DL where DL > 0, else 0, in the working format") \
    X(S_DHQ, "dhq", INTERNAL, "block key: DH where DL > 0 and DH > 0, else 0") \
    X(S_ROOT, "root", INTERNAL, "sqrt(NN), truncated (restoring recurrence)") \
    X(S_RINV, "rinv", INTERNAL, "1/ROOT, truncated (restoring recurrence)") \
    X(S_NL, "nl", INTERNAL, "multiplier NL = DLQ RINV: max(0, u.L)") \
    X(S_NH, "nh", INTERNAL, "multiplier NH = DHQ RINV: u.H where the highlight counts") \
    X(S_HL, "hl", INTERNAL, "the highlight NH^n by square and multiply (each step's product and register)") \
    X(S_DIF, "dif", INTERNAL, "multiplier DIF = kd NL") \
    X(S_KSH, "ksh", INTERNAL, "multiplier KSH = ks HL") \
    X(S_SUM, "sum", INTERNAL, "adders SUM = ka + DIF + KSH") \
    X(S_CLAMP, "clamp", INTERNAL, "1 where SUM >= 1: the output multiplexer's select")
enum { SH_SIGS(UNIT_SIG_ID) SH_NSIGS };
enum { SH_PIPE };

extern const unit_desc unit_shade;

/* F: the vectors' fraction bits (s2.F holds +-1); the working format
 * keeps 4 more than the inputs so that the power's gain (about n times
 * the error of NH) eats guard bits rather than the output's. */
static int sh_f(int W) { return W - 2; }
static int sh_fw(int W) { return W + 2; }

static void sh_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, F = sh_f(W), Fw = sh_fw(W);
    for (int k = S_NX; k <= S_HZ; k++) out->f[k] = unit_fmt(1, 2, F);
    for (int k = S_KA; k <= S_KS; k++) out->f[k] = unit_fmt(0, 1, W - 1);
    out->f[S_I] = unit_fmt(0, 1, W - 1);
    out->f[S_NN] = unit_fmt(0, 1, nrm_prod_fbits(W));
    out->f[S_DL] = out->f[S_DH] = unit_fmt(1, 2, nrm_prod_fbits(W));
    out->f[S_DLQ] = out->f[S_DHQ] = unit_fmt(0, 1, Fw);
    out->f[S_ROOT] = unit_fmt(0, 1, Fw);
    out->f[S_RINV] = unit_fmt(0, 2, Fw);
    out->f[S_NL] = out->f[S_NH] = out->f[S_HL] = out->f[S_DIF] = out->f[S_KSH] = unit_fmt(0, 1, Fw);
    out->f[S_SUM] = unit_fmt(0, 2, Fw);
    out->f[S_CLAMP] = unit_fmt(0, 1, 0);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* ------------------------------------------------------------ the logic */

/* DL > 0 (and DH > 0): the sign bits and an OR over the bits. */
static int64_t f_pos(const int64_t *in, void *u) { (void)u; return in[0] > 0; }
static int64_t f_pos2(const int64_t *in, void *u) { (void)u; return in[0] > 0 && in[1] > 0; }
/* SUM >= 1: its raw against 1's */
static int64_t f_ge1(const int64_t *in, void *u) { return in[0] >= *(const int64_t *)u; }

static const char *pos_vl(char *buf, size_t len, sim_fmt f, int k)
{
    if (f.is_signed) snprintf(buf, len, "(~%%%d[%d] & (|%%%d))", k, f.width - 1, k);
    else snprintf(buf, len, "(|%%%d)", k);
    return buf;
}

static sim_signal *gate(sim_ctx *c, sim_scope *sc, const char *name, sim_signal *a, sim_signal *b)
{
    sim_signal *in[2] = { a, b };
    int two = b != NULL;
    double ge = (a->fmt.width + (two ? b->fmt.width : 0)) * SIM_GE_NAND2 / 2;
    sim_signal *g = sim_logic(c, sc, name, unit_fmt(0, 1, 0), two ? 2 : 1, in, two ? f_pos2 : f_pos, NULL, ge);
    char t[200], p0[60], p1[60];
    if (two) snprintf(t, sizeof t, "assign %%y = %s & %s;", pos_vl(p0, sizeof p0, a->fmt, 0), pos_vl(p1, sizeof p1, b->fmt, 1));
    else snprintf(t, sizeof t, "assign %%y = %s;", pos_vl(p0, sizeof p0, a->fmt, 0));
    sim_logic_verilog(g, t);
    return g;
}

static sim_signal *ge_one(sim_ctx *c, sim_scope *sc, sim_signal *x)
{
    int64_t *one = sim_alloc(c, sizeof *one);
    sim_fmt f = x->fmt;
    *one = (int64_t)1 << f.fbits;
    sim_signal *g = sim_logic(c, sc, "clamp", unit_fmt(0, 1, 0), 1, &x, f_ge1, one, f.width * SIM_GE_NAND2 / 2);
    char t[160];
    if (f.is_signed) snprintf(t, sizeof t, "assign %%y = $signed(%%0) >= $signed(%d'h%llx);", f.width, (unsigned long long)*one);
    else snprintf(t, sizeof t, "assign %%y = %%0 >= %d'h%llx;", f.width, (unsigned long long)*one);
    sim_logic_verilog(g, t);
    return g;
}

/* ------------------------------------------------------------ the walk */

/* The datapath, written once (unit_net.h): building (n->c), it makes the
 * hardware into io; bounding, every value carries its worst-case error
 * and *out is the output's. 0, or -1 with a message. */
static int sh_walk(unet *n, const unit_cfg *cfg, unit_io *io, unet_val *out, char *err, size_t errlen)
{
    const sim_fmt *F = n->fm.f;
    int hw = n->c != NULL;
    char prog[PW_N_PROG_LEN];
    if (!pow_n_prog(cfg->n, prog)) {
        snprintf(err, errlen, "shade: n = %d is outside 1..%d", cfg->n, PW_N_MAX);
        return -1;
    }
    unet_val in[12];
    for (int k = 0; k < 12; k++) {
        in[k] = unet_input(n, n->u->sigs[k].name, -1);
        if (hw) io->in[k] = in[k].s;
        if (k >= S_KA) in[k].imag = in[k].mag = 1;      /* coefficients in [0, 1] */
    }
    /* |L|, |H| <= 1 before their quantization, so as held at most
     * 1 + sqrt(3) 2^-F; |N| <= NRM_NMAX as held (the domain) */
    double lmax = 1 + 2 * sim_fmt_lsb(F[S_LX]);
    /* stage 1: the products; stage 2: their sums, the gates and keys */
    unet_val nn = nrm_dot(n, S_NN, "nn", in + S_NX, in + S_NX, NRM_NMAX * NRM_NMAX, 1);
    unet_val dl = nrm_dot(n, S_DL, "dl", in + S_NX, in + S_LX, NRM_NMAX * lmax, 1);
    unet_val dh = nrm_dot(n, S_DH, "dh", in + S_NX, in + S_HX, NRM_NMAX * lmax, 1);
    if (!hw && (dl.err > 0 || dh.err > 0)) {
        /* a gate on an inexact sign may switch the highlight where the
         * ideal does not: no bound */
        snprintf(err, errlen, "shade: dl and dh are exact only up to width 26 (their gates need exact signs)");
        return -1;
    }
    sim_signal *gl = hw ? gate(n->c, n->sc, "gate_l", dl.s, NULL) : NULL;
    sim_signal *gh = hw ? gate(n->c, n->sc, "gate_h", dl.s, dh.s) : NULL;
    unet_val dlq = unet_bk(n, S_DLQ, "dlq", gl, dl, 1), dhq = unet_bk(n, S_DHQ, "dhq", gh, dh, 1);
    sim_signal *v = hw ? io->in_valid : NULL;
    nn = nrm_delay(n, "nn_r", nn, 1);
    dlq = nrm_delay(n, "dlq_r", dlq, 1);
    dhq = nrm_delay(n, "dhq_r", dhq, 1);
    unet_val ka = nrm_delay(n, "ka_r", in[S_KA], 2), kd = nrm_delay(n, "kd_r", in[S_KD], 2);
    unet_val ks = nrm_delay(n, "ks_r", in[S_KS], 2);
    int K = 0, P = 0;
    unet_val rinv;
    if (nrm_rsqrt(n, nn, S_ROOT, S_RINV, 1, NULL, NULL, NULL, NULL, &rinv, &K, err, errlen)) return -1;
    dlq = nrm_delay(n, "dlq_d", dlq, K);
    dhq = nrm_delay(n, "dhq_d", dhq, K);
    ka = nrm_delay(n, "ka_d", ka, K);
    kd = nrm_delay(n, "kd_d", kd, K);
    ks = nrm_delay(n, "ks_d", ks, K);
    unet_val nl = unet_mul(n, S_NL, "nl", dlq, rinv), nh = unet_mul(n, S_NH, "nh", dhq, rinv);
    nl.imag = nh.imag = lmax;           /* u.L, u.H: |u| = 1 */
    /* stage K + 3: NL, NH registered */
    nl = nrm_delay(n, "nl_r", nl, 1);
    nh = nrm_delay(n, "nh_r", nh, 1);
    ka = nrm_delay(n, "ka_e", ka, 1);
    kd = nrm_delay(n, "kd_e", kd, 1);
    ks = nrm_delay(n, "ks_e", ks, 1);
    unet_val dif = unet_mul(n, S_DIF, "dif", nl, kd), hl;
    if (!hw && (!brdf_holds(F[S_NL], 0, nl.imag + nl.err) || !brdf_holds(F[S_NH], 0, nh.imag + nh.err))) {
        snprintf(err, errlen, "shade: nl, nh must hold [0, 1]");
        return -1;
    }
    if (pw_unrolled(n, prog, nh, S_HL, "pw", "hl", &hl, &P)) {
        snprintf(err, errlen, "shade: internal: bad power program");
        return -1;
    }
    dif = nrm_delay(n, "dif_p", dif, P);
    ka = nrm_delay(n, "ka_p", ka, P);
    ks = nrm_delay(n, "ks_p", ks, P);
    unet_val ksh = unet_mul(n, S_KSH, "ksh", hl, ks);
    unet_val sum = unet_add(n, S_SUM, "sum", unet_add(n, S_SUM, "sum_a", ka, dif), ksh);
    unet_val one = brdf_uconst(n, F[S_I], "one_i", 1.0);
    sim_signal *sel = hw ? ge_one(n->c, n->sc, sum.s) : NULL;
    unet_val two[2] = { sum, one };
    /* min(SUM, 1) is 1-Lipschitz: its error is SUM's, then i's quantization */
    *out = unet_mux(n, S_I, "i", sel, 2, two, 0);
    if (hw) {
        io->in_ready = sim_const_raw(n->c, n->sc, "in_ready", unit_fmt(0, 1, 0), 1);
        io->out_valid = rec_delay(n->c, n->sc, n->clk, "v", v, 2 + K + 1 + P);
        io->out[0] = out->s;
    }
    if (!hw && !brdf_holds(F[S_SUM], 0, sum.imag + sum.err)) {
        snprintf(err, errlen, "shade: sum must hold [0, 3]");
        return -1;
    }
    return 0;
}

static int sh_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    if (!f->f[S_DL].is_signed || !f->f[S_DH].is_signed) {
        snprintf(err, errlen, "shade: dl and dh must be signed (their signs gate the terms)");
        return -1;
    }
    unet n;
    unet_init(&n, &unit_shade, f, SIM_RND_TRUNC);   /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    unet_val out;
    if (sh_walk(&n, cfg, io, &out, err, errlen)) return -1;
    io->scope = sc;
    return 0;
}

static void sh_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = ref_shade_blinn(in, in + 3, in + 6, in[9], in[10], in[11], cfg->n);
}

/* The walk's error of i (docs/bounds.md, "shade"), on the domain |N| in
 * [1/2, 1]; no bound where a format cannot hold its values. */
static void sh_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    unet n;
    unet_init(&n, &unit_shade, f, cfg->rnd);
    unet_val out;
    char err[200];
    per_out[0] = sh_walk(&n, cfg, NULL, &out, err, sizeof err) ? NAN : out.err;
}

const unit_desc unit_shade = {
    .name = "shade",
    .ref = &ref_model_shade,
    .summary = "one pixel of Blinn shading: normalize N, u.L and u.H, ka + kd u.L + ks (u.H)^n, clamped",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV (the per-pixel Phong/Blinn reference the method is compared with)",
    UNIT_SIGS(SH_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "pipe", "fully pipelined, a pixel a clock: a stage of products and one of sums, a stage a "
                         "root bit and one a reciprocal bit, the products by 1/|N|, a stage a step of the power" } },
    .nparams = 1,
    .params = { { "n", UNIT_P_INT, offsetof(unit_cfg, n), 1, PW_N_MAX, 24, NULL, "shininess: the exponent of (u.H)^n" } },
    .fmt_rule = "N, L, H s2.(W-2); ka, kd, ks, i u1.(W-1); nn u1.P, dl, dh s2.P, P = 2W-4 (exact) up to "
                "W = 26, W+22 above (no bound: the gates need exact signs); "
                "root, dlq, dhq, nl, nh, hl, dif, ksh u1.(W+2); rinv, sum u2.(W+2)",
    .formats = sh_formats, .beats = beats1, .build = sh_build, .ideal = sh_ideal, .bound = sh_bound,
};
