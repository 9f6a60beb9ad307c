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

/* The signals, one list: X(ID, "name", ROLE, schedules, "what"), the
 * schedules B (both), P (pipe) or S (shared). */
#define SH_B 0
#define SH_P UNIT_SCHED(SH_PIPE)
#define SH_S UNIT_SCHED(SH_SHARED)
#define SH_SIGS(X) \
    X(S_NX, "nx", IN, SH_B, "normal N as interpolated, x (|N| in [1/2, 1])") \
    X(S_NY, "ny", IN, SH_B, "normal, y") \
    X(S_NZ, "nz", IN, SH_B, "normal, z") \
    X(S_LX, "lx", IN, SH_B, "unit vector L towards the light, x (a frame constant)") \
    X(S_LY, "ly", IN, SH_B, "L, y") \
    X(S_LZ, "lz", IN, SH_B, "L, z") \
    X(S_HX, "hx", IN, SH_B, "unit half vector H = normalize(L + V), x (a frame constant)") \
    X(S_HY, "hy", IN, SH_B, "H, y") \
    X(S_HZ, "hz", IN, SH_B, "H, z") \
    X(S_KA, "ka", IN, SH_B, "ambient term, in [0, 1]") \
    X(S_KD, "kd", IN, SH_B, "diffuse coefficient, in [0, 1]") \
    X(S_KS, "ks", IN, SH_B, "specular coefficient, in [0, 1]") \
    X(S_I,  "i", OUT, SH_B, "intensity, clamp(ka + kd u.L + ks (u.H)^n, 0, 1)") \
    X(S_NN, "nn", INTERNAL, SH_B, "N.N, exact: three squares and two adders (shared: ACC read as N.N)") \
    X(S_DL, "dl", INTERNAL, SH_B, "N.L, exact (shared: a register loaded from the adder)") \
    X(S_DH, "dh", INTERNAL, SH_B, "N.H, exact (shared: a register loaded from the adder)") \
    X(S_DLQ, "dlq", INTERNAL, SH_B, "block key: DL where DL > 0, else 0, in the working format") \
    X(S_DHQ, "dhq", INTERNAL, SH_B, "block key: DH where DL > 0 and DH > 0, else 0") \
    X(S_ROOT, "root", INTERNAL, SH_B, "sqrt(NN), truncated (restoring recurrence)") \
    X(S_RINV, "rinv", INTERNAL, SH_B, "1/ROOT, truncated (restoring recurrence)") \
    X(S_NL, "nl", INTERNAL, SH_B, "NL = DLQ RINV: max(0, u.L) (pipe: a multiplier; shared: a register)") \
    X(S_NH, "nh", INTERNAL, SH_B, "NH = DHQ RINV: u.H where the highlight counts") \
    X(S_HL, "hl", INTERNAL, SH_B, "the highlight NH^n by square and multiply (pipe: each step's product and register)") \
    X(S_CLAMP, "clamp", INTERNAL, SH_B, "1 where the sum >= 1: the output multiplexer's select") \
    X(S_DIF, "dif", INTERNAL, SH_P, "multiplier DIF = kd NL") \
    X(S_KSH, "ksh", INTERNAL, SH_P, "multiplier KSH = ks HL") \
    X(S_SUM, "sum", INTERNAL, SH_P, "adders SUM = ka + DIF + KSH") \
    X(S_CN, "cn", INTERNAL, SH_S, "multiplexer: the component of N the step reads") \
    X(S_CV, "cv", INTERNAL, SH_S, "multiplexer: the component of L or H the step reads") \
    X(S_KC, "kc", INTERNAL, SH_S, "multiplexer: kd or ks") \
    X(S_MXA, "mx_a", INTERNAL, SH_S, "operand multiplexer A: CN, RINV, NH, HL or NL") \
    X(S_MXB, "mx_b", INTERNAL, SH_S, "operand multiplexer B: CN, CV, DLQ, DHQ, NH, HL, KC or 1") \
    X(S_MUL, "mul", INTERNAL, SH_S, "the one multiplier MUL = MX_A MX_B") \
    X(S_MXC, "mx_c", INTERNAL, SH_S, "addend multiplexer: 0, ACC or ka") \
    X(S_ACC, "acc", INTERNAL, SH_S, "the one adder's register ACC <= MUL + MX_C")
#define SH_ID(id, nm, role_, sch, wh) id,
#define SH_ROW(id, nm, role_, sch, wh) { .name = nm, .role = UNIT_SIG_##role_, .what = wh, .scheds = sch },
/* shared first: the default, and the design small enough for Yosys to
 * synthesize in seconds (the pipe takes minutes at W = 16) */
enum { SH_SHARED, SH_PIPE };
enum { SH_SIGS(SH_ID) SH_NSIGS };

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
    out->f[S_CLAMP] = unit_fmt(0, cfg->schedule == SH_SHARED ? 2 : 1, 0);   /* shared: also below 0 */
    /* shared: one multiplier and one adder keep every bit of the dot
     * products (P fraction bits; |values| < 8 whatever the operands), DL
     * and DH are loaded from the adder in its format */
    int Pb = nrm_prod_fbits(W);
    out->f[S_CN] = out->f[S_CV] = unit_fmt(1, 2, F);
    out->f[S_KC] = unit_fmt(0, 1, W - 1);
    out->f[S_MXA] = unit_fmt(1, 3, Fw);         /* CN s2.F, RINV u2, NH, HL, NL u1 */
    out->f[S_MXB] = unit_fmt(1, 2, Fw);         /* CN, CV s2.F, DLQ, DHQ, NH, HL u1, KC, 1 */
    out->f[S_MUL] = out->f[S_MXC] = out->f[S_ACC] = unit_fmt(1, 4, Pb);
    if (cfg->schedule == SH_SHARED) out->f[S_DL] = out->f[S_DH] = out->f[S_ACC];
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* ------------------------------------------------------------ the logic */

/* the shared schedule's CV select, 3 v + k */
static int64_t f_vk(const int64_t *in, void *u) { (void)u; return 3 * in[0] + in[1]; }

/* ACC's low bits as N.N (a view: wiring; the other clocks' values are
 * not N.N and are not read) */
static int64_t f_low(const int64_t *in, void *u) { return (int64_t)((uint64_t)in[0] & *(const uint64_t *)u); }
static sim_signal *low_bits(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt f, sim_signal *x)
{
    uint64_t *m = sim_alloc(c, sizeof *m);
    *m = f.width >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << f.width) - 1;
    sim_signal *y = sim_logic(c, sc, name, f, 1, &x, f_low, m, 0);
    char t[80];
    snprintf(t, sizeof t, "assign %%y = %%0[%d:0];", f.width - 1);
    sim_logic_verilog(y, t);
    return y;
}

/* The shared output's select: 0 in [0, 1), 1 at 1 and above, 2 below 0. */
static int64_t f_clamp3(const int64_t *in, void *u)
{
    return in[0] < 0 ? 2 : in[0] >= *(const int64_t *)u;
}
static sim_signal *clamp3(sim_ctx *c, sim_scope *sc, sim_signal *x)
{
    int64_t *one = sim_alloc(c, sizeof *one);
    sim_fmt f = x->fmt;
    *one = (int64_t)1 << f.fbits;
    sim_signal *g = sim_logic(c, sc, "clamp", unit_fmt(0, 2, 0), 1, &x, f_clamp3, one, f.width * SIM_GE_NAND2 / 2);
    char t[200];
    snprintf(t, sizeof t, "assign %%y = $signed(%%0) < 0 ? 2'd2 : ($signed(%%0) >= $signed(%d'h%llx) ? 2'd1 : 2'd0);",
             f.width, (unsigned long long)*one);
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
        snprintf(err, errlen, "shade: dl and dh are exact only up to width 25 (their gates need exact signs)");
        return -1;
    }
    sim_signal *gl = hw ? nrm_gate(n->c, n->sc, "gate_l", dl.s, NULL) : NULL;
    sim_signal *gh = hw ? nrm_gate(n->c, n->sc, "gate_h", dl.s, dh.s) : NULL;
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
    sim_signal *sel = hw ? nrm_ge_one(n->c, n->sc, sum.s) : NULL;
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

/* ------------------------------------------------ the shared schedule */

/* The shared schedule's program: a control word a clock. Sources of the
 * operand multiplexers and the addend's: */
enum { A_CN, A_RINV, A_NH, A_HL, A_NL };
enum { B_CN, B_CV, B_DLQ, B_DHQ, B_NH, B_HL, B_KC, B_ONE };
enum { C_ZERO, C_ACC, C_KA };
/* Register loads and the recurrences' controls, one bit each. */
enum { E_DL = 1, E_DH = 2, E_NL = 4, E_NH = 8, E_HL = 16, E_SQ0 = 32, E_SQ = 64, E_RC0 = 128 };
#define SH_MAX_STEPS 128
typedef struct sh_word { uint8_t a, b, c, k, v, kc, en, rc; } sh_word;

/* The program: N.N, N.L, N.H on the multiplier-adder (three clocks each),
 * the root from the clock after N.N (while N.L and N.H are formed), then
 * the reciprocal; NL and NH; the power's program; ka + kd NL, + ks HL.
 * Returns the steps, or 0 when they do not fit. */
static int sh_len(int ks, int kq, const char *pw) { return 3 + ks + kq + 2 + (int)strlen(pw) / 2 + 2; }
static int sh_prog(int ks, int kq, const char *pw, sh_word *w)
{
    int np = (int)strlen(pw) / 2, r0 = 3 + ks + kq, n = sh_len(ks, kq, pw);
    if (n > SH_MAX_STEPS || ks < 7) return 0;
    memset(w, 0, (size_t)n * sizeof *w);
    for (int t = 0; t < 9; t++) {               /* the dot products */
        w[t].a = A_CN;
        w[t].b = t < 3 ? B_CN : B_CV;
        w[t].k = (uint8_t)(t % 3);
        w[t].v = t < 6 ? 0 : 1;                 /* CV: L, then H */
        w[t].c = t % 3 ? C_ACC : C_ZERO;
    }
    w[3].en |= E_SQ0;                           /* ACC holds N.N */
    for (int t = 3; t < 3 + ks; t++) w[t].en |= E_SQ;
    w[5].en |= E_DL;                            /* the adder forms N.L */
    w[8].en |= E_DH;                            /* the adder forms N.H */
    w[3 + ks].en |= E_RC0;
    for (int t = 3 + ks; t < r0; t++) w[t].rc = 1;
    w[r0] = (sh_word){ .a = A_RINV, .b = B_DLQ, .en = E_NL };
    w[r0 + 1] = (sh_word){ .a = A_RINV, .b = B_DHQ, .en = E_NH };
    for (int j = 0; j < np; j++) {
        char ca = pw[2 * j], cb = pw[2 * j + 1];
        w[r0 + 2 + j] = (sh_word){ .a = ca == 'I' ? A_NH : A_HL,
                                   .b = cb == 'I' ? B_NH : cb == 'R' ? B_HL : B_ONE, .en = E_HL };
    }
    w[n - 2] = (sh_word){ .a = A_NL, .b = B_KC, .kc = 0, .c = C_KA };
    w[n - 1] = (sh_word){ .a = A_HL, .b = B_KC, .kc = 1, .c = C_ACC };
    return n;
}

/* The registered decoder of one field of the program (the building walk). */
static sim_signal *sh_dec(unet *n, sim_signal *next, const sh_word *w, int ns, const char *name,
                          size_t off, uint8_t bit)
{
    uint8_t t[SH_MAX_STEPS];
    for (int i = 0; i < ns; i++) {
        uint8_t v = *((const uint8_t *)&w[i] + off);
        t[i] = bit ? (v & bit) != 0 : v;
    }
    return brdf_decode(n->c, n->sc, n->clk, name, next, t, ns);
}

/* A register of signal sig loading where en is 1 (NULL: every clock). */
static unet_val sh_reg(unet *n, int sig, const char *name, sim_signal *en)
{
    if (!n->c) return unet_reg(n, sig, name);
    unet_val r = unet_wrap(sim_reg(n->c, n->sc, name, n->fm.f[sig], n->clk, NULL, en, NULL, 0), n->fm.f[sig], -1);
    r.mag = r.imag = 0;
    return r;
}
static void sh_load(unet *n, unet_val *r, unet_val d, int on)
{
    if (n->c) sim_reg_connect(r->s, d.s);
    else if (on) unet_reg_set(n, r, d);
}

/* The shared datapath, walked as pw_walk is (unit_powg.c): building, its
 * first clock makes the hardware (every multiplexer with its decoder) and
 * stops; bounding, every clock of the program. */
static int sh_walk_shared(unet *n, const unit_cfg *cfg, unit_io *io, unet_val *out, char *err, size_t errlen)
{
    const sim_fmt *F = n->fm.f;
    int hw = n->c != NULL, ks, kq;
    char prog[PW_N_PROG_LEN];
    sh_word w[SH_MAX_STEPS];
    if (!pow_n_prog(cfg->n, prog)) {
        snprintf(err, errlen, "shade: n = %d is outside 1..%d", cfg->n, PW_N_MAX);
        return -1;
    }
    /* the recurrences' own limits first: they set the program's length */
    if (nrm_check(n, F[S_NN], S_ROOT, S_RINV, err, errlen)) return -1;
    nrm_steps(F[S_NN], F[S_ROOT], F[S_RINV], &ks, &kq);
    int ns = sh_prog(ks, kq, prog, w);
    if (!ns) {
        snprintf(err, errlen, "shade: the shared program needs %d clocks, more than %d", sh_len(ks, kq, prog), SH_MAX_STEPS);
        return -1;
    }
    sim_signal *next = NULL, *first, *d[16] = { NULL };
    if (hw) {
        brdf_seq(n->c, n->sc, n->clk, ns, io, &next, &first);
        (void)first;
        static const struct { const char *nm; size_t off; uint8_t bit; } f[] = {
            { "a_sel", offsetof(sh_word, a), 0 }, { "b_sel", offsetof(sh_word, b), 0 },
            { "c_sel", offsetof(sh_word, c), 0 }, { "k_sel", offsetof(sh_word, k), 0 },
            { "v_sel", offsetof(sh_word, v), 0 }, { "kc_sel", offsetof(sh_word, kc), 0 },
            { "dl_en", offsetof(sh_word, en), E_DL }, { "dh_en", offsetof(sh_word, en), E_DH },
            { "nl_en", offsetof(sh_word, en), E_NL }, { "nh_en", offsetof(sh_word, en), E_NH },
            { "hl_en", offsetof(sh_word, en), E_HL }, { "root_first", offsetof(sh_word, en), E_SQ0 },
            { "root_run", offsetof(sh_word, en), E_SQ }, { "rcp_first", offsetof(sh_word, en), E_RC0 },
            { "rcp_run", offsetof(sh_word, rc), 0 } };
        for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) d[i] = sh_dec(n, next, w, ns, f[i].nm, f[i].off, f[i].bit);
    }
    enum { D_A, D_B, D_C, D_K, D_V, D_KC, D_DL, D_DH, D_NL, D_NH, D_HL, D_SQ0, D_SQ, D_RC0, D_RC };
    unet_val in[12];
    for (int k = 0; k < 12; k++) {
        in[k] = unet_input(n, n->u->sigs[k].name, -1);
        if (hw) io->in[k] = in[k].s;
        if (k >= S_KA) in[k].imag = in[k].mag = 1;
    }
    double lmax = 1 + 2 * sim_fmt_lsb(F[S_LX]);
    unet_val acc = sh_reg(n, S_ACC, "acc", NULL), dl = sh_reg(n, S_DL, "dl", d[D_DL]);
    unet_val dh = sh_reg(n, S_DH, "dh", d[D_DH]), nl = sh_reg(n, S_NL, "nl", d[D_NL]);
    unet_val nh = sh_reg(n, S_NH, "nh", d[D_NH]), hl = sh_reg(n, S_HL, "hl", d[D_HL]);
    unet_val rinv, nn, zero = brdf_uconst(n, F[S_MXC], "zero", 0), one = brdf_uconst(n, F[S_MXB], "one", 1);
    memset(&rinv, 0, sizeof rinv);
    sim_signal *gl = NULL, *gh = NULL;
    if (hw) {
        gl = nrm_gate(n->c, n->sc, "gate_l", dl.s, NULL);
        gh = nrm_gate(n->c, n->sc, "gate_h", dl.s, dh.s);
    }
    for (int t = 0; t < ns; t++) {
        const sh_word *c = &w[t];
        if (hw || t == 3) {
            /* N.N: ACC read in the narrower format (wiring); the root and
             * the reciprocal, their errors derived (unit_nrm.c) */
            nn = acc;
            nn.f = F[S_NN];
            if (hw) nn.s = low_bits(n->c, n->sc, "nn", F[S_NN], acc.s);
            nn.imag = NRM_NMAX * NRM_NMAX;
            if (nrm_rsqrt(n, nn, S_ROOT, S_RINV, 0, d[D_SQ0], d[D_SQ], d[D_RC0], d[D_RC], &rinv, NULL, err, errlen)) return -1;
        }
        unet_val dlq = unet_bk(n, S_DLQ, "dlq", gl, dl, 1), dhq = unet_bk(n, S_DHQ, "dhq", gh, dh, 1);
        unet_val cn = unet_mux(n, S_CN, "cn", d[D_K], 3, in + S_NX, c->k);
        unet_val cv6[6] = { in[S_LX], in[S_LY], in[S_LZ], in[S_HX], in[S_HY], in[S_HZ] };
        sim_signal *vk = NULL;
        if (hw) {
            /* CV's select: 3 v + k */
            sim_signal *vs[2] = { d[D_V], d[D_K] };
            vk = sim_logic(n->c, n->sc, "cv_sel", unit_fmt(0, 3, 0), 2, vs, f_vk, NULL, 4);
            sim_logic_verilog(vk, "assign %y = (%0 ? 3'd3 : 3'd0) + {1'b0, %1};");
        }
        unet_val cv = unet_mux(n, S_CV, "cv", vk, 6, cv6, 3 * c->v + c->k);
        unet_val kc = unet_mux(n, S_KC, "kc", d[D_KC], 2, in + S_KD, c->kc);
        unet_val av[5] = { cn, rinv, nh, hl, nl }, bv[8] = { cn, cv, dlq, dhq, nh, hl, kc, one };
        unet_val ma = unet_mux(n, S_MXA, "mx_a", d[D_A], 5, av, c->a);
        unet_val mb = unet_mux(n, S_MXB, "mx_b", d[D_B], 8, bv, c->b);
        unet_val mul = unet_mul(n, S_MUL, "mul", ma, mb);
        unet_val cs[3] = { zero, acc, in[S_KA] };
        unet_val add = unet_add(n, S_ACC, "add", mul, unet_mux(n, S_MXC, "mx_c", d[D_C], 3, cs, c->c));
        /* the loads at the edge that ends the clock */
        sh_load(n, &acc, add, 1);
        sh_load(n, &dl, add, c->en & E_DL);
        sh_load(n, &dh, add, c->en & E_DH);
        sh_load(n, &nl, mul, c->en & E_NL);
        sh_load(n, &nh, mul, c->en & E_NH);
        sh_load(n, &hl, mul, c->en & E_HL);
        /* what the ideal values are bounded by (|N.L| <= |N| |L|, |u.L| <= |L|) */
        if (c->en & E_DL) dl.imag = NRM_NMAX * lmax;
        if (c->en & E_DH) dh.imag = NRM_NMAX * lmax;
        if (c->en & E_NL) nl.imag = lmax;
        if (c->en & E_NH) nh.imag = lmax;
        if (!hw && (c->en & (E_DL | E_DH)) && add.err > 0) {
            snprintf(err, errlen, "shade: dl and dh are exact only up to width 25 (their gates need exact signs)");
            return -1;
        }
        if (hw) break;              /* the hardware: built once */
    }
    /* ACC holds other values between the pixels (the dot products may be
     * negative): the output clamps at 0 too, so that it never overflows */
    sim_signal *sel = hw ? clamp3(n->c, n->sc, acc.s) : NULL;
    unet_val three[3] = { acc, brdf_uconst(n, F[S_I], "one_i", 1.0), brdf_uconst(n, F[S_I], "zero_i", 0.0) };
    *out = unet_mux(n, S_I, "i", sel, 3, three, 0);
    if (hw) io->out[0] = out->s;
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
    unet_val out;
    if (cfg->schedule == SH_SHARED) {
        if (sh_walk_shared(&n, cfg, io, &out, err, errlen)) return -1;
    } else {
        io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
        if (sh_walk(&n, cfg, io, &out, err, errlen)) return -1;
    }
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
    int bad = cfg->schedule == SH_SHARED ? sh_walk_shared(&n, cfg, NULL, &out, err, sizeof err)
                                         : sh_walk(&n, cfg, NULL, &out, err, sizeof err);
    per_out[0] = bad ? NAN : out.err;
}

const unit_desc unit_shade = {
    .name = "shade",
    .ref = &ref_model_shade,
    .summary = "one pixel of Blinn shading: normalize N, u.L and u.H, ka + kd u.L + ks (u.H)^n, clamped",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV (the per-pixel Phong/Blinn reference the method is compared with)",
    UNIT_SIGS(SH_SIGS(SH_ROW)),
    .nsched = 2,
    .sched = { { "shared", "one multiplier and one adder for every product and sum, the root and the "
                           "reciprocal a bit a clock: 3 + (W + 3) + (W + 4) + 2 + (power steps) + 2 clocks a pixel" },
               { "pipe", "fully pipelined, a pixel a clock: a stage of products and one of sums, a stage a "
                         "root bit and one a reciprocal bit, the products by 1/|N|, a stage a step of the power" } },
    .nparams = 1,
    .params = { { "n", UNIT_P_INT, offsetof(unit_cfg, n), 1, PW_N_MAX, 24, NULL, "shininess: the exponent of (u.H)^n" } },
    .fmt_rule = "N, L, H s2.(W-2); ka, kd, ks, i u1.(W-1); nn u1.P, dl, dh s2.P, P = 2W-4 (exact) up to "
                "W = 25, W+21 above (no bound: the gates need exact signs); "
                "root, dlq, dhq, nl, nh, hl, dif, ksh u1.(W+2); rinv, sum u2.(W+2)",
    .formats = sh_formats, .beats = beats1, .build = sh_build, .ideal = sh_ideal, .bound = sh_bound,
};
