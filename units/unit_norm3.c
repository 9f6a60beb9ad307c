/* unit_norm3.c - norm3: u = N/|N| for a normal as interpolated, |N| in
 * [1/2, 1], on unit_nrm.c's construction (shade's normalization):
 *
 *   NN = N.N                  three squares, two adders, exact
 *   ROOT = sqrt(NN)           restoring recurrence, truncated
 *   RINV = 1/ROOT             restoring recurrence, truncated
 *   u = N RINV                three multipliers
 *
 *   pipe       a stage for the squares, one for their sum, a stage a root
 *              bit and a reciprocal bit: an item a clock;
 *   restoring  a clock for N.N into its register, the two recurrences one
 *              after the other, a bit a clock, then a clock for the
 *              products into the output registers.
 */
#include "units/unit_nrm.h"
#include "units/units_brdf.h"
#include "vectors/ref_shade.h"
#include <math.h>
#include <stdio.h>

#define N3_SIGS(X) \
    X(N_NX, "nx", IN, "normal, x (|N| in [1/2, 1])") \
    X(N_NY, "ny", IN, "normal, y") \
    X(N_NZ, "nz", IN, "normal, z") \
    X(N_UX, "ux", OUT, "nx/|N|: multiplier nx RINV (restoring: its register)") \
    X(N_UY, "uy", OUT, "ny/|N|") \
    X(N_UZ, "uz", OUT, "nz/|N|") \
    X(N_NN, "nn", INTERNAL, "N.N, exact (the squares and the partial sum in its format)") \
    X(N_ROOT, "root", INTERNAL, "sqrt(NN), truncated (restoring recurrence)") \
    X(N_RINV, "rinv", INTERNAL, "1/ROOT, truncated (restoring recurrence)")
enum { N3_SIGS(UNIT_SIG_ID) N3_NSIGS };
enum { N3_ITER, N3_PIPE };     /* the smaller design the default */

extern const unit_desc unit_norm3;

static void n3_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, F = W - 2;
    for (int k = N_NX; k <= N_UZ; k++) out->f[k] = unit_fmt(1, 2, F);
    out->f[N_NN] = unit_fmt(0, 1, nrm_prod_fbits(W));
    out->f[N_ROOT] = unit_fmt(0, 1, W + 2);
    out->f[N_RINV] = unit_fmt(0, 2, W + 2);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* The datapath, built (n->c) or walked; out[3] the outputs. 0, or -1. */
static int n3_walk(unet *n, const unit_cfg *cfg, unit_io *io, unet_val *out, char *err, size_t errlen)
{
    int hw = n->c != NULL, pipe = cfg->schedule == N3_PIPE;
    unet_val in[3];
    for (int k = 0; k < 3; k++) {
        in[k] = unet_input(n, n->u->sigs[k].name, -1);
        in[k].imag = fmin(in[k].imag, NRM_NMAX);          /* |n_k| <= |N| */
        if (hw) io->in[k] = in[k].s;
    }
    sim_signal *first = NULL, *first_rcp = NULL, *root_run = NULL, *rcp_run = NULL;
    int ks, kq;
    nrm_steps(n->fm.f[N_NN], n->fm.f[N_ROOT], n->fm.f[N_RINV], &ks, &kq);
    if (hw && !pipe) {
        sim_signal *next;
        int nsteps = 1 + ks + kq + 1;
        brdf_seq(n->c, n->sc, n->clk, nsteps, io, &next, &first);
        /* the control words by step: 0 NN, 1..ks the root, ks+1..ks+kq the
         * reciprocal, then the products */
        uint8_t f_sq[128] = { 0 }, f_rc[128] = { 0 }, r_sq[128] = { 0 }, r_rc[128] = { 0 };
        if (nsteps > 128) { snprintf(err, errlen, "norm3: too many steps"); return -1; }
        f_sq[1] = f_rc[1 + ks] = 1;
        for (int t = 1; t <= ks; t++) r_sq[t] = 1;
        for (int t = 1 + ks; t <= ks + kq; t++) r_rc[t] = 1;
        first = brdf_decode(n->c, n->sc, n->clk, "root_first", next, f_sq, nsteps);
        first_rcp = brdf_decode(n->c, n->sc, n->clk, "rcp_first", next, f_rc, nsteps);
        root_run = brdf_decode(n->c, n->sc, n->clk, "root_run", next, r_sq, nsteps);
        rcp_run = brdf_decode(n->c, n->sc, n->clk, "rcp_run", next, r_rc, nsteps);
    }
    unet_val nn = nrm_dot(n, N_NN, "nn", in, in, NRM_NMAX * NRM_NMAX, pipe);
    int K = 0;
    nn = nrm_delay(n, "nn_r", nn, 1);       /* restoring: NN in clock 0, the root from clock 1 */
    unet_val rinv;
    if (nrm_rsqrt(n, nn, N_ROOT, N_RINV, pipe, first, root_run, first_rcp, rcp_run, &rinv, &K, err, errlen)) return -1;
    /* restoring: RINV is final in the last step only; the multipliers see
     * 0 in the others (a block key), so that no product of a partial
     * reciprocal overflows (a value nothing takes, but the batch mode
     * would leave the run to the kernel) */
    if (!pipe) rinv = unet_bk(n, N_RINV, "rinv_last", hw ? io->in_ready : NULL, rinv, 1);
    for (int k = 0; k < 3; k++) {
        const char *nm = n->u->sigs[N_UX + k].name;
        char pn[16];
        if (pipe) {
            unet_val x = nrm_delay(n, nm[1] == 'x' ? "nx_d" : nm[1] == 'y' ? "ny_d" : "nz_d", in[k], 2 + K);
            out[k] = unet_mul(n, N_UX + k, nm, x, rinv);
        } else {
            /* the output registers take the products in the last step only
             * (rinv is final there; the other clocks' products are not used) */
            snprintf(pn, sizeof pn, "%s_p", nm);
            unet_val p = unet_mul(n, N_UX + k, pn, in[k], rinv);
            if (hw) out[k].s = sim_reg(n->c, n->sc, nm, n->fm.f[N_UX + k], n->clk, p.s, io->in_ready, NULL, 0);
            else out[k] = unet_reg_of(n, N_UX + k, nm, p);
        }
        if (hw) io->out[k] = out[k].s;
    }
    if (hw && pipe) {
        io->in_ready = sim_const_raw(n->c, n->sc, "in_ready", unit_fmt(0, 1, 0), 1);
        io->out_valid = rec_delay(n->c, n->sc, n->clk, "v", io->in_valid, 2 + K);
    }
    return 0;
}

static int n3_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    unet n;
    unet_init(&n, &unit_norm3, f, SIM_RND_TRUNC);   /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    if (cfg->schedule == N3_PIPE) io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    unet_val out[3];
    if (n3_walk(&n, cfg, io, out, err, errlen)) return -1;
    io->scope = sc;
    return 0;
}

static void n3_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    double len = sqrt(in[0] * in[0] + in[1] * in[1] + in[2] * in[2]);
    for (int k = 0; k < 3; k++) out[k] = len > 0 ? in[k] / len : 0;
}

/* The walk's (docs/bounds.md, "norm3"): |n_k| times RINV's derived error
 * plus the product's quantization, on the domain |N| in [1/2, 1]. */
static void n3_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    unet n;
    unet_init(&n, &unit_norm3, f, cfg->rnd);
    unet_val out[3];
    char err[200];
    int bad = n3_walk(&n, cfg, NULL, out, err, sizeof err);
    for (int k = 0; k < 3; k++) per_out[k] = bad ? NAN : out[k].err;
}

const unit_desc unit_norm3 = {
    .name = "norm3",
    .ref = &ref_model_norm3,
    .summary = "u = N/|N|: N.N exact, its root and the root's reciprocal by digit recurrences, three products",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV (the normal renormalized per pixel by the reference)",
    UNIT_SIGS(N3_SIGS(UNIT_SIG_ROW)),
    .nsched = 2,
    .sched = { { "restoring", "N.N, then the root and the reciprocal, a bit a clock each, then the products: "
                              "1 + (W + 3) + (W + 4) + 1 clocks an item" },
               { "pipe", "fully pipelined, an item a clock: squares, their sum, a stage a root bit and a "
                         "reciprocal bit, the products" } },
    .nparams = 0,
    .fmt_rule = "N, u s2.(W-2); nn u1.P, P = 2W-4 (exact) up to W = 25, W+21 above; root u1.(W+2); rinv u2.(W+2)",
    .formats = n3_formats, .beats = beats1, .build = n3_build, .ideal = n3_ideal, .bound = n3_bound,
};
