/* unit_shade_cook.c - shade_cook: one pixel of the scene's Cook-Torrance
 * shading with the papers' D_g (scene/scene_shade.c, specular cook,
 * distribution d4/d8/d16) in hardware, the per-pixel side of the
 * comparison where a scene selects that form (vectors/ref_shade.h gives
 * the function and why its two clamps change nothing on a frame):
 *
 *   u = N/|N|, nl = u.L, nv = u.V, nh = (nl + nv) hs    (hs = 1/|L + V|)
 *   i = clamp(ka + kd nl + kc D_g(nh) min(1/a, 4 hs nh) / b, 0, 1)
 *   a = max(min(nl, nv), 1/4), b = max(max(nl, nv), 2^-e)
 *
 * The geometric term over nl nv, G / (nl nv) with G = min(1, 2 nh nv /
 * (V.H), 2 nh nl / (V.H)), is min(1/a, 2 nh / V.H) / b for the smaller a
 * and the larger b of nl and nv, and 2 / V.H = 4 hs: two reciprocals and
 * no divider. The clamps keep both reciprocals' operands away from 0
 * (1/a only counts below 4 hs nh <= 4; b >= nh / (2 hs) >= 2^-e wherever
 * D_g is not 0), so their errors stay bounded. Datapath, pipelined (a
 * pixel a clock):
 *
 *   NN, DL, DV      exact dot products (their signs exact), a stage each
 *                   for the products and the sums
 *   DLQ, DVQ, HSQ   block keys: DL where DL > 0; DV and hs where DL > 0 and
 *                   DV > 0 (else 0: no highlight, D_g(0) = 0)
 *   ROOT, RINV      the two digit recurrences (unit_nrm.c)
 *   NL, NV          DLQ RINV, DVQ RINV
 *   NS, NH          NL + NV, NS HSQ (u.H);  A, B  the clamped min and max
 *   RA, RB          1/A and 1/B: restoring reciprocals (unit_rec.c, the
 *                   divisor above 2^-2 and 2^-e), a stage a bit;
 *                   beside them C = 4 HSQ NH and D_g(NH) as d_approx forms
 *                   it (OM = 1 - NH, P = k OM, BASE = 1 - P clamped at 0,
 *                   the power unrolled a stage a squaring, D = c0 RG)
 *   X = min(RA, C), Y = X RB, S = D Y, KSP = kc S, DIF = kd NL
 *   i = min(ka + DIF + KSP, 1)
 *
 * The bound is the walk's (unit_net.h) with the reciprocals' errors
 * derived, |1/a_hw - 1/a| <= |a_hw - a| / a_min^2 then truncation, and
 * S's refined where 1/B and D_g are large apart (s_err_scan;
 * docs/bounds.md, "shade_cook").
 */
#include "units/unit_nrm.h"
#include "units/units_brdf.h"
#include "vectors/ref_shade.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stdio.h>
#include <stddef.h>
#include <string.h>

#define SC_SIGS(X) \
    X(S_NX, "nx", IN, "normal N as interpolated, x (|N| in [1/2, 1])") \
    X(S_NY, "ny", IN, "normal, y") \
    X(S_NZ, "nz", IN, "normal, z") \
    X(S_LX, "lx", IN, "unit vector L towards the light, x (a frame constant)") \
    X(S_LY, "ly", IN, "L, y") \
    X(S_LZ, "lz", IN, "L, z") \
    X(S_VX, "vx", IN, "unit vector V towards the viewer, x (a frame constant; L.V >= -1/2)") \
    X(S_VY, "vy", IN, "V, y") \
    X(S_VZ, "vz", IN, "V, z") \
    X(S_HS, "hs", IN, "1/|L + V| in [1/2, 1] (a frame constant: H = (L + V) hs)") \
    X(S_KA, "ka", IN, "ambient term, in [0, 1]") \
    X(S_KD, "kd", IN, "diffuse coefficient, in [0, 1]") \
    X(S_KC, "kc", IN, "specular coefficient ks F / pi, in [0, 1] (F, 1/pi: frame constants)") \
    X(S_I,  "i", OUT, "intensity, clamp(ka + kd u.L + kc D_g G / (u.L u.V), 0, 1)") \
    X(S_NN, "nn", INTERNAL, "N.N, exact: three squares and two adders") \
    X(S_DL, "dl", INTERNAL, "N.L, exact") \
    X(S_DV, "dv", INTERNAL, "N.V, exact") \
    X(S_DLQ, "dlq", INTERNAL, "block key: DL where DL > 0, else 0") \
    X(S_DVQ, "dvq", INTERNAL, "block keys: DV and hs where DL > 0 and DV > 0, else 0") \
    X(S_ROOT, "root", INTERNAL, "sqrt(NN), truncated (restoring recurrence)") \
    X(S_RINV, "rinv", INTERNAL, "1/ROOT, truncated (restoring recurrence)") \
    X(S_NL, "nl", INTERNAL, "multipliers NL = DLQ RINV, NV = DVQ RINV (u.L, u.V)") \
    X(S_NS, "ns", INTERNAL, "adder NS = NL + NV") \
    X(S_NH, "nh", INTERNAL, "multiplier NH = NS HSQ (u.H)") \
    X(S_A, "a", INTERNAL, "comparators and multiplexers A = max(min(NL, NV), 1/4)") \
    X(S_B, "b", INTERNAL, "comparators and multiplexers B = max(max(NL, NV), 2^-e)") \
    X(S_RA, "ra", INTERNAL, "1/A, truncated (restoring reciprocal, A >= 1/4)") \
    X(S_RB, "rb", INTERNAL, "1/B, truncated (restoring reciprocal, B >= 2^-e)") \
    X(S_C,  "c", INTERNAL, "multiplier C = 4 HSQ NH (2 nh / V.H)") \
    X(S_OM, "om", INTERNAL, "subtractor OM = 1 - NH") \
    X(S_K,  "k", INTERNAL, "constant k = (2/m^2 - 4)/g") \
    X(S_P,  "p", INTERNAL, "constant multiplier P = k OM") \
    X(S_BASE, "base", INTERNAL, "subtractor BASE = 1 - P") \
    X(S_CL, "dclamp", INTERNAL, "block key: BASE, or 0 where BASE < 0") \
    X(S_PW, "pw", INTERNAL, "the power CLAMP^g, a stage a squaring") \
    X(S_C0, "c0", INTERNAL, "constant c0 = 1/(4 m^2)") \
    X(S_D,  "d", INTERNAL, "constant multiplier D = c0 PW (D_g)") \
    X(S_X,  "x", INTERNAL, "comparator and multiplexer X = min(RA, C)") \
    X(S_Y,  "y", INTERNAL, "multiplier Y = X RB (G / (nl nv))") \
    X(S_S,  "s", INTERNAL, "multiplier S = D Y") \
    X(S_KSP, "ksp", INTERNAL, "multiplier KSP = kc S") \
    X(S_DIF, "dif", INTERNAL, "multiplier DIF = kd NL") \
    X(S_SUM, "sum", INTERNAL, "adders SUM = ka + DIF + KSP")
enum { SC_SIGS(UNIT_SIG_ID) SC_NSIGS };

extern const unit_desc unit_shade_cook;

#define SC_IN 13
/* the working format's fraction bits: 6 guard bits over the output's, for
 * the reciprocals' gains (up to 2^(2e)) and the power's */
static int sc_fw(int W) { return W + 5; }

static void sc_consts(const unit_cfg *cfg, double *k, double *c0, int *e)
{
    *k = (2.0 / (cfg->m * cfg->m) - 4.0) / cfg->g;
    *c0 = 1.0 / (4.0 * cfg->m * cfg->m);
    *e = ref_shade_cook_e(cfg->m, cfg->g);
}

static void sc_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, F = W - 2, Fw = sc_fw(W), Pb = nrm_prod_fbits(W), e;
    double k, c0;
    sc_consts(cfg, &k, &c0, &e);
    if (e < 1) e = 1;
    /* u.H as held may pass 1 by a few LSBs (sc_walk's nhmax), the base
     * 1 by k times that, its power by g times more: at narrow widths the
     * power needs more integer bits */
    double nhmax = 1 + 4 * ldexp(1.0, 2 - W) + 2 * ldexp(1.0, 1 - W), bmax = 1 + k * (nhmax - 1);
    double p1 = pow(bmax, cfg->g), pmax = 1.25 * p1;     /* room for its error */
    int ik = brdf_ibits(k), i0 = brdf_ibits(c0), id = brdf_ibits(c0 * pmax), is = brdf_ibits(10 * c0 * p1) + 1;
    for (int j = S_NX; j <= S_VZ; j++) out->f[j] = unit_fmt(1, 2, F);
    for (int j = S_HS; j <= S_KC; j++) out->f[j] = unit_fmt(0, 1, W - 1);
    out->f[S_I] = unit_fmt(0, 1, W - 1);
    out->f[S_NN] = unit_fmt(0, 1, Pb);
    out->f[S_DL] = out->f[S_DV] = unit_fmt(1, 2, Pb);
    out->f[S_DLQ] = out->f[S_DVQ] = out->f[S_ROOT] = unit_fmt(0, 1, Fw);
    out->f[S_RINV] = unit_fmt(0, 2, Fw);
    out->f[S_NL] = out->f[S_NH] = out->f[S_A] = out->f[S_B] = out->f[S_DIF] = unit_fmt(0, 1, Fw);
    out->f[S_CL] = unit_fmt(0, brdf_ibits(bmax), Fw);
    out->f[S_PW] = unit_fmt(0, brdf_ibits(pmax), Fw);
    out->f[S_NS] = unit_fmt(0, 2, Fw);
    out->f[S_RA] = unit_fmt(0, 4, Fw);
    out->f[S_RB] = unit_fmt(0, 2 + e, Fw);
    out->f[S_C] = out->f[S_X] = unit_fmt(0, 3, Fw);
    out->f[S_Y] = unit_fmt(0, e + 3, Fw);
    out->f[S_OM] = unit_fmt(1, 2, Fw);
    out->f[S_K] = unit_fmt(0, ik, Fw);
    out->f[S_P] = unit_fmt(1, ik + 1, Fw);
    out->f[S_BASE] = unit_fmt(1, ik + 2, Fw);
    out->f[S_C0] = unit_fmt(0, i0, Fw);
    out->f[S_D] = unit_fmt(0, id, Fw);
    out->f[S_S] = out->f[S_KSP] = unit_fmt(0, is, Fw);
    out->f[S_SUM] = unit_fmt(0, is + 1, Fw);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* ------------------------------------------------------------ the logic */

/* a >= b on raws of the same fraction bits, unsigned */
static int64_t f_ge(const int64_t *in, void *u) { (void)u; return in[0] >= in[1]; }
static sim_signal *ge(sim_ctx *c, sim_scope *sc, const char *name, sim_signal *a, sim_signal *b)
{
    sim_signal *in[2] = { a, b };
    int w = a->fmt.width > b->fmt.width ? a->fmt.width : b->fmt.width;
    sim_signal *g = sim_logic(c, sc, name, unit_fmt(0, 1, 0), 2, in, f_ge, NULL, w * SIM_GE_NAND2);
    /* the narrower operand zero-extended (lint: equal widths) */
    char t[120];
    int wa = a->fmt.width, wb = b->fmt.width;
    if (wa < wb) snprintf(t, sizeof t, "assign %%y = {%d'd0, %%0} >= %%1;", wb - wa);
    else if (wb < wa) snprintf(t, sizeof t, "assign %%y = %%0 >= {%d'd0, %%1};", wa - wb);
    else snprintf(t, sizeof t, "assign %%y = %%0 >= %%1;");
    sim_logic_verilog(g, t);
    return g;
}

/* BASE >= 0, read as P <= 1 (P's raw against 1's): as d_approx, so that
 * the key sees BASE and its sign in the same delta cycle */
static int64_t f_le(const int64_t *in, void *u) { return in[0] <= *(const int64_t *)u; }
static sim_signal *base_pos(sim_ctx *c, sim_scope *sc, sim_signal *p)
{
    int64_t *one = sim_alloc(c, sizeof *one);
    sim_fmt f = p->fmt;
    *one = (int64_t)1 << f.fbits;
    sim_signal *g = sim_logic(c, sc, "base_pos", unit_fmt(0, 1, 0), 1, &p, f_le, one, f.width * SIM_GE_NAND2 / 2);
    char t[160];
    snprintf(t, sizeof t, "assign %%y = $signed(%%0) <= $signed(%d'h%llx);", f.width, (unsigned long long)*one);
    sim_logic_verilog(g, t);
    return g;
}

/* ------------------------------------------------------------ the walk */

/* min (lo 1) or max of a and b on a comparator's select; bounding, the
 * error the larger of theirs (min and max are 1-Lipschitz in each). */
static unet_val minmax(unet *n, int sig, const char *name, int lo, unet_val a, unet_val b)
{
    char nm[48];
    sim_signal *sel = NULL;
    if (n->c) {
        snprintf(nm, sizeof nm, "%s_ge", name);
        sel = ge(n->c, n->sc, nm, a.s, b.s);
    }
    /* sel = a >= b: min picks b there, max a */
    unet_val two[2] = { lo ? a : b, lo ? b : a };
    unet_val v = unet_mux(n, sig, name, sel, 2, two, 0);
    if (!n->c) {
        unet_val w = unet_mux(n, sig, name, NULL, 2, two, 1);
        v.err = fmax(v.err, w.err);
        v.q = fmax(v.q, w.q);
        v.mag = fmax(v.mag, w.mag);
        v.imag = lo ? fmin(v.imag, w.imag) : fmax(v.imag, w.imag);
        v.eff = v.eff > w.eff ? v.eff : w.eff;
    }
    return v;
}

/* 1/d for d >= 2^-e (the caller's clamp): the restoring reciprocal
 * unrolled, K stages (*stages); bounding, |1/d_hw - 1/d| <= err_d
 * 2^(2e) plus the truncation, below one LSB. */
static int rcp(unet *n, int sig, const char *name, unet_val d, int e, unet_val *out, int *stages,
               char *err, size_t errlen)
{
    sim_fmt fq = n->fm.f[sig];
    rec_spec rs = { REC_RECIP, d.f.fbits, fq.fbits, e };
    if (d.f.is_signed || d.f.ibits != 1 || fq.is_signed || fq.ibits < 2 + e) {
        snprintf(err, errlen, "shade_cook: %s needs an unsigned u1 divisor and a result of %d integer bits", name, 2 + e);
        return -1;
    }
    if (rec_check(&rs, err, errlen)) return -1;
    *stages = rec_steps(&rs);
    unet_val v = d;
    v.f = fq;
    v.lin[0] = v.lin[1] = v.lin[2] = v.lin[3] = 0;
    if (n->c) {
        char nm[48];
        snprintf(nm, sizeof nm, "%s_", name);
        sim_signal *q = rec_pipe(n->c, n->sc, n->clk, nm, &rs, d.s);
        v.s = sim_shift(n->c, n->sc, name, fq, q, -fq.fbits);
    } else {
        double lsb = sim_fmt_lsb(fq), g = ldexp(1.0, 2 * e);
        v.q = lsb;
        v.err = d.err * g + lsb;
        v.imag = v.mag = ldexp(1.0, e);
        v.eff = fq.fbits;
    }
    *out = v;
    return 0;
}

/* S = D Y's error, the walk's product rule refined by where its factors
 * are large: |D_hw Y_hw - D Y| <= |D_hw - D| Y + D_hw |Y_hw - Y|, with
 * Y <= 8 (ref_shade.h), and |Y_hw - Y| <= eX RB_hw + X |RB_hw - RB| + qY,
 * RB_hw <= 1/m, |RB_hw - RB| <= eB / (B m) + qRB, m = max(B - eB, 2^-e),
 * X <= C = 4 hs NH. Over B, NH <= 2 hs B (NH = (nl + nv) hs) and D_g is
 * increasing in NH: where 1/B is large D_g is small. The maximum over B in
 * [2^-e, bmax] is taken interval by interval, each factor at its interval's
 * worst end (hs <= 1), so it bounds the continuum. The product rule alone
 * takes D's largest value with 1/B's: 2^(2e) times looser at m = 0.3. */
static double s_err_scan(double k, double c0, int g, int e, double nhmax, double bmax, double eD, double eX,
                         double eB, double qRB, double qY)
{
    const int N = 2048;
    double lo = ldexp(1.0, -e), worst = 0;
    for (int j = 0; j < N; j++) {
        double b0 = lo + (bmax - lo) * j / N, b1 = lo + (bmax - lo) * (j + 1) / N;
        double nh = fmin(nhmax, 2 * b1), base = 1 - k * (1 - nh), d = base > 0 ? c0 * pow(base, g) : 0;
        double m = fmax(b0 - eB, lo);
        double t = (d + eD) * (eX / m + 4 * nh * (eB / (b0 * m) + qRB) + qY);
        if (t > worst) worst = t;
    }
    return 8 * eD + worst;
}

/* What the front of the datapath hands on, registered at one stage:
 * u.L and u.V, hs behind the highlight's key, the coefficients; K the
 * root's and reciprocal's stages. */
typedef struct sc_front { unet_val nl, nv, hsq, ka, kd, kc; int K; } sc_front;

/* The front: the exact dot products, the gates and keys, 1/|N| and the
 * products by it (shade's walk with V for H). */
static int sc_front_walk(unet *n, unit_io *io, double lmax, sc_front *o, char *err, size_t errlen)
{
    int hw = n->c != NULL;
    unet_val in[SC_IN];
    for (int j = 0; j < SC_IN; j++) {
        in[j] = unet_input(n, n->u->sigs[j].name, -1);
        if (hw) io->in[j] = in[j].s;
        if (j >= S_HS) in[j].imag = in[j].mag = 1;
    }
    unet_val nn = nrm_dot(n, S_NN, "nn", in + S_NX, in + S_NX, NRM_NMAX * NRM_NMAX, 1);
    unet_val dl = nrm_dot(n, S_DL, "dl", in + S_NX, in + S_LX, NRM_NMAX * lmax, 1);
    unet_val dv = nrm_dot(n, S_DV, "dv", in + S_NX, in + S_VX, NRM_NMAX * lmax, 1);
    if (!hw && (dl.err > 0 || dv.err > 0)) {
        snprintf(err, errlen, "shade_cook: dl and dv are exact only up to width 25 (their gates need exact signs)");
        return -1;
    }
    sim_signal *gl = hw ? nrm_gate(n->c, n->sc, "gate_l", dl.s, NULL) : NULL;
    sim_signal *gs = hw ? nrm_gate(n->c, n->sc, "gate_s", dl.s, dv.s) : NULL;
    unet_val hs = nrm_delay(n, "hs_r", in[S_HS], 1);
    unet_val dlq = unet_bk(n, S_DLQ, "dlq", gl, dl, 1), dvq = unet_bk(n, S_DVQ, "dvq", gs, dv, 1);
    unet_val hsq = unet_bk(n, S_DVQ, "hsq", gs, hs, 1);
    unet_val ka = nrm_delay(n, "ka_r", in[S_KA], 2), kd = nrm_delay(n, "kd_r", in[S_KD], 2);
    unet_val kc = nrm_delay(n, "kc_r", in[S_KC], 2);
    nn = nrm_delay(n, "nn_r", nn, 1);
    dlq = nrm_delay(n, "dlq_r", dlq, 1);
    dvq = nrm_delay(n, "dvq_r", dvq, 1);
    hsq = nrm_delay(n, "hsq_r", hsq, 1);
    int K = 0;
    unet_val rinv;
    if (nrm_rsqrt(n, nn, S_ROOT, S_RINV, 1, NULL, NULL, NULL, NULL, &rinv, &K, err, errlen)) return -1;
    dlq = nrm_delay(n, "dlq_d", dlq, K);
    dvq = nrm_delay(n, "dvq_d", dvq, K);
    hsq = nrm_delay(n, "hsq_d", hsq, K);
    ka = nrm_delay(n, "ka_d", ka, K);
    kd = nrm_delay(n, "kd_d", kd, K);
    kc = nrm_delay(n, "kc_d", kc, K);
    unet_val nl = unet_mul(n, S_NL, "nl", dlq, rinv), nv = unet_mul(n, S_NL, "nv", dvq, rinv);
    nl.imag = nv.imag = lmax;
    nl = nrm_delay(n, "nl_r", nl, 1);
    nv = nrm_delay(n, "nv_r", nv, 1);
    hsq = nrm_delay(n, "hsq_e", hsq, 1);
    ka = nrm_delay(n, "ka_e", ka, 1);
    kd = nrm_delay(n, "kd_e", kd, 1);
    kc = nrm_delay(n, "kc_e", kc, 1);
    *o = (sc_front){ nl, nv, hsq, ka, kd, kc, K };
    return 0;
}

/* D_g of NH as d_approx forms it (OM = 1 - NH, P = k OM, BASE = 1 - P
 * keyed at 0, a register, the power unrolled, D = c0 PW): *d, its
 * stages *P, the ideal's largest value *dmax. */
static int sc_dg(unet *n, const unit_cfg *cfg, double k, double c0, const char *prog, unet_val nh, double nhmax,
                 unet_val *dout, int *P, double *dmax, char *err, size_t errlen)
{
    const sim_fmt *F = n->fm.f;
    int hw = n->c != NULL;
    sim_fmt f1 = unit_fmt(0, 1, 0);
    unet_val one = unet_wrap(hw ? sim_const_raw(n->c, n->sc, "one", f1, 1) : NULL, f1, -1);
    one.imag = one.mag = 1;
    unet_val om = unet_sub(n, S_OM, "om", one, nh);
    unet_val kk = brdf_uconst(n, F[S_K], "k", k);
    unet_val p = unet_cmul(n, S_P, "p", om, kk, brdf_cmul);
    unet_val base = unet_sub(n, S_BASE, "base", one, p);
    double bmax = 1 + k * (nhmax - 1);
    if (!hw && (!brdf_holds(F[S_OM], -(nhmax - 1) - nh.err, 1 + nh.err) || !brdf_holds(F[S_K], 0, k)
                || !brdf_holds(F[S_P], -2 * k * (nhmax - 1 + nh.err) - p.q, (k + kk.err) * (1 + om.err) + p.q)
                || !brdf_holds(F[S_BASE], 1 - (k + kk.err) * (1 + om.err) - p.q - base.q, bmax + base.err))) {
        snprintf(err, errlen, "shade_cook: om, k, p and base must hold their ranges");
        return -1;
    }
    sim_signal *pos = hw ? base_pos(n->c, n->sc, p.s) : NULL;
    unet_val cl = unet_bk(n, S_CL, "dclamp", pos, base, 1);
    cl.imag = bmax;
    cl.mag = fmax(cl.mag, bmax + cl.err);
    if (!hw && !brdf_holds(F[S_CL], 0, bmax + cl.err)) {
        snprintf(err, errlen, "shade_cook: dclamp must hold [0, %g]", bmax);
        return -1;
    }
    cl = nrm_delay(n, "dclamp_r", cl, 1);         /* a stage before the squarings */
    unet_val rg;
    if (pw_unrolled(n, prog, cl, S_PW, "pw", "pw", &rg, P)) {
        snprintf(err, errlen, "shade_cook: internal: bad power program");
        return -1;
    }
    if (!hw && !brdf_holds(F[S_C0], 0, c0)) {
        snprintf(err, errlen, "shade_cook: c0 = %g does not fit c0=%d integer bits", c0, F[S_C0].ibits);
        return -1;
    }
    unet_val d = unet_cmul(n, S_D, "d", rg, brdf_uconst(n, F[S_C0], "c0", c0), brdf_cmul);
    *dmax = c0 * pow(bmax, cfg->g);
    d.imag = *dmax;
    *dout = d;
    if (!hw && (!brdf_holds(F[S_PW], 0, pow(bmax, cfg->g) + rg.err) || !brdf_holds(F[S_D], 0, *dmax + d.err))) {
        snprintf(err, errlen, "shade_cook: pw and d must hold their ranges");
        return -1;
    }
    return 0;
}

static int sc_walk(unet *n, const unit_cfg *cfg, unit_io *io, unet_val *out, char *err, size_t errlen)
{
    const sim_fmt *F = n->fm.f;
    int hw = n->c != NULL, e;
    double k, c0;
    sc_consts(cfg, &k, &c0, &e);
    char prog[PW_N_PROG_LEN];
    if (e < 1 || !pow_n_prog(cfg->g, prog)) {
        snprintf(err, errlen, "shade_cook: (2/m^2 - 4)/g = %.4g must exceed 1 (D_g reaches 0 away from the "
                 "highlight): m = %g, g = %d", k, cfg->m, cfg->g);
        return -1;
    }
    if (!hw && (!F[S_DL].is_signed || !F[S_DV].is_signed)) {
        snprintf(err, errlen, "shade_cook: dl and dv must be signed (their signs gate the terms)");
        return -1;
    }
    double lsbF = sim_fmt_lsb(F[S_LX]), lmax = 1 + 2 * lsbF;
    /* u.H = u.(L + V) hs as held: at most 1 + 2 sqrt(3) 2^-F + 2 lsb(hs)
     * for unit L, V and hs = 1/|L + V| before their quantization */
    double nhmax = 1 + 4 * lsbF + 2 * sim_fmt_lsb(F[S_HS]);
    sc_front fr;
    if (sc_front_walk(n, io, lmax, &fr, err, errlen)) return -1;
    unet_val nl = fr.nl, nv = fr.nv, hsq = fr.hsq, ka = fr.ka, kd = fr.kd, kc = fr.kc;
    int K = fr.K;
    /* NS, A, B: a stage; then NH, a stage */
    unet_val ns = unet_add(n, S_NS, "ns", nl, nv);
    unet_val a = minmax(n, S_A, "amin", 1, nl, nv), b = minmax(n, S_B, "bmax", 0, nl, nv);
    unet_val quarter = brdf_uconst(n, F[S_A], "quarter", 0.25), floor_b = brdf_uconst(n, F[S_B], "bfloor", ldexp(1.0, -e));
    a = minmax(n, S_A, "a", 0, a, quarter);
    b = minmax(n, S_B, "b", 0, b, floor_b);
    unet_val dif = unet_mul(n, S_DIF, "dif", nl, kd);
    ns = nrm_delay(n, "ns_r", ns, 1);
    unet_val hsn = nrm_delay(n, "hsq_n", hsq, 1);
    unet_val nh = unet_mul(n, S_NH, "nh", ns, hsn);
    nh.imag = nhmax;
    if (!hw && (!brdf_holds(F[S_NL], 0, lmax + nl.err) || !brdf_holds(F[S_NS], 0, 2 * lmax + ns.err)
                || !brdf_holds(F[S_NH], 0, nhmax + nh.err) || !brdf_holds(F[S_A], 0, lmax + a.err) || !brdf_holds(F[S_B], 0, lmax + b.err))) {
        snprintf(err, errlen, "shade_cook: nl, nv, nh, a and b must hold [0, 1], ns [0, 2]");
        return -1;
    }
    a = nrm_delay(n, "a_r", a, 1);
    b = nrm_delay(n, "b_r", b, 1);
    nh = nrm_delay(n, "nh_r", nh, 1);
    hsq = nrm_delay(n, "hsq_f", hsn, 1);
    dif = nrm_delay(n, "dif_r", dif, 1);
    ka = nrm_delay(n, "ka_f", ka, 1);
    kc = nrm_delay(n, "kc_f", kc, 1);
    /* the reciprocals, and beside them C and D */
    int KA = 0, KB = 0, P = 0;
    unet_val ra, rb;
    if (rcp(n, S_RA, "ra", a, 2, &ra, &KA, err, errlen) || rcp(n, S_RB, "rb", b, e, &rb, &KB, err, errlen)) return -1;
    unet_val c = unet_shift(n, S_C, "c", unet_mul(n, S_C, "c_m", nh, hsq), 2);
    c.imag = 4 * nhmax;
    unet_val d;
    double dmax;
    if (sc_dg(n, cfg, k, c0, prog, nh, nhmax, &d, &P, &dmax, err, errlen)) return -1;
    /* align on the longer reciprocal */
    int KM = KA > KB ? KA : KB;
    ra = nrm_delay(n, "ra_d", ra, KM - KA);
    rb = nrm_delay(n, "rb_d", rb, KM - KB);
    c = nrm_delay(n, "c_d", c, KM - 1);
    d = nrm_delay(n, "d_d", d, KM - P - 2);
    dif = nrm_delay(n, "dif_d", dif, KM);
    ka = nrm_delay(n, "ka_g", ka, KM);
    kc = nrm_delay(n, "kc_g", kc, KM);
    /* X, Y: a stage */
    unet_val x = minmax(n, S_X, "x", 1, ra, c);
    unet_val y = unet_mul(n, S_Y, "y", x, rb);
    y.imag = 8;                 /* min(1/a, c) / b <= 8 hs^2 (ref_shade.h); as held at most 4 2^e (x <= 1/a <= 4) */
    if (!hw && (!brdf_holds(F[S_X], 0, 4 * nhmax + x.err) || !brdf_holds(F[S_Y], 0, 4 * rb.mag))) {
        snprintf(err, errlen, "shade_cook: x and y must hold their ranges");
        return -1;
    }
    y = nrm_delay(n, "y_r", y, 1);
    d = nrm_delay(n, "d_r", d, 1);
    dif = nrm_delay(n, "dif_e", dif, 1);
    ka = nrm_delay(n, "ka_h", ka, 1);
    kc = nrm_delay(n, "kc_h", kc, 1);
    /* S: a stage */
    unet_val s = unet_mul(n, S_S, "s", d, y);
    s.imag = 8 * dmax;
    if (!hw) s.err = fmin(s.err, s_err_scan(k, c0, cfg->g, e, nhmax, lmax, d.err, x.err, b.err, rb.q, y.q) + s.q);
    if (!hw && !brdf_holds(F[S_S], 0, s.imag + s.err)) {
        snprintf(err, errlen, "shade_cook: s must hold [0, %g]", s.imag);
        return -1;
    }
    s = nrm_delay(n, "s_r", s, 1);
    dif = nrm_delay(n, "dif_f", dif, 1);
    ka = nrm_delay(n, "ka_i", ka, 1);
    kc = nrm_delay(n, "kc_i", kc, 1);
    /* the sum and the clamp */
    unet_val ksp = unet_mul(n, S_KSP, "ksp", s, kc);
    unet_val sum = unet_add(n, S_SUM, "sum", unet_add(n, S_SUM, "sum_a", ka, dif), ksp);
    if (!hw && !brdf_holds(F[S_SUM], 0, sum.imag + sum.err)) {
        snprintf(err, errlen, "shade_cook: sum must hold [0, %g]", sum.imag);
        return -1;
    }
    unet_val onei = brdf_uconst(n, F[S_I], "one_i", 1.0);
    sim_signal *sel = hw ? nrm_ge_one(n->c, n->sc, sum.s) : NULL;
    unet_val two[2] = { sum, onei };
    *out = unet_mux(n, S_I, "i", sel, 2, two, 0);
    if (hw) {
        io->in_ready = sim_const_raw(n->c, n->sc, "in_ready", unit_fmt(0, 1, 0), 1);
        io->out_valid = rec_delay(n->c, n->sc, n->clk, "v", io->in_valid, 2 + K + 1 + 1 + KM + 1 + 1);
        io->out[0] = out->s;
    }
    return 0;
}

static int sc_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    if (!f->f[S_DL].is_signed || !f->f[S_DV].is_signed) {
        snprintf(err, errlen, "shade_cook: dl and dv must be signed (their signs gate the terms)");
        return -1;
    }
    unet n;
    unet_init(&n, &unit_shade_cook, f, SIM_RND_TRUNC);
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    unet_val out;
    if (sc_walk(&n, cfg, io, &out, err, errlen)) return -1;
    io->scope = sc;
    return 0;
}

static void sc_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    out[0] = ref_shade_cook(in, in + 3, in + 6, in[9], in[10], in[11], in[12], cfg->m, cfg->g);
}

/* The walk's error of i (docs/bounds.md, "shade_cook"); no bound where a
 * format cannot hold its values. */
static void sc_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    unet n;
    unet_init(&n, &unit_shade_cook, f, cfg->rnd);
    unet_val out;
    char err[200];
    per_out[0] = sc_walk(&n, cfg, NULL, &out, err, sizeof err) ? NAN : out.err;
}

const unit_desc unit_shade_cook = {
    .name = "shade_cook",
    .ref = &ref_model_shade_cook,
    .summary = "one pixel of Cook-Torrance shading with D_g: u.L, u.V, u.H, ka + kd u.L + kc D_g G / (u.L u.V), clamped",
    .source = "Nechyporuk & Romanyuk (2020), sec. III-IV; S. O. Romanyuk et al. (SPIE), sec. 3 (D_g)",
    UNIT_SIGS(SC_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "pipe", "fully pipelined, a pixel a clock: products, sums, a stage a bit of the root and of "
                         "1/|N|, then of 1/a and 1/b side by side with D_g's squarings beside them, then G, D G "
                         "and the sum" } },
    .nparams = 2,
    .params = {
        { "m", UNIT_P_REAL, offsetof(unit_cfg, m), 0.05, 0.31, 0.3, NULL,
          "Beckmann roughness (below sqrt(2/(g+4)): D_g reaches 0)" },
        { "g", UNIT_P_POW2, offsetof(unit_cfg, g), 4, 16, 16, NULL, "the power of D_g: 4, 8 or 16" } },
    .fmt_rule = "N, L, V s2.(W-2); hs, ka, kd, kc, i u1.(W-1); nn u1.P, dl, dv s2.P, P = 2W-4 (exact) up to "
                "W = 25; the rest .(W+5): root, dlq, dvq, nl, nh, a, b, dif u1; rinv, ns u2; ra u4, "
                "rb u(2+e), c, x u3, y u(e+3); om s2, k, p, base, dclamp, pw, c0, d, s, ksp, sum with the integer "
                "bits of their ranges (dclamp, pw u1 from W = 10; e from m and g: 2^-e <= (1 - 1/k)/2)",
    .formats = sc_formats, .beats = beats1, .build = sc_build, .ideal = sc_ideal, .bound = sc_bound,
};
