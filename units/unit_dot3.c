/* unit_dot3.c - dot3: y = a.b for three-component vectors, the dot
 * product of shade's u.L and u.H (unit_nrm.c's nrm_dot, one construction
 * for both): three multipliers and two adders, every product kept exact,
 * and y the exact sum quantized once.
 *
 *   comb   combinational: an item a clock, no register;
 *   pipe   the products registered, then the adders: an item a clock, one
 *          clock of latency, the multiplier and the adders in separate
 *          clock periods.
 */
#include "units/unit_nrm.h"
#include "units/units_brdf.h"
#include "vectors/ref_shade.h"
#include <math.h>
#include <stdio.h>

#define D3_SIGS(X) \
    X(D_AX, "ax", IN, "a, x (|a| <= 1)") \
    X(D_AY, "ay", IN, "a, y") \
    X(D_AZ, "az", IN, "a, z") \
    X(D_BX, "bx", IN, "b, x (|b| <= 1)") \
    X(D_BY, "by", IN, "b, y") \
    X(D_BZ, "bz", IN, "b, z") \
    X(D_Y,  "y", OUT, "a.b quantized to y's format") \
    X(D_DOT, "dot", INTERNAL, "adders DOT = the three products' sum; the products (dot_x, dot_y, dot_z) and the partial sum in its format, all exact")
enum { D3_SIGS(UNIT_SIG_ID) D3_NSIGS };
enum { D3_COMB, D3_PIPE };

extern const unit_desc unit_dot3;

static void d3_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int F = cfg->width - 2;
    for (int k = D_AX; k <= D_BZ; k++) out->f[k] = unit_fmt(1, 2, F);
    out->f[D_Y] = unit_fmt(1, 2, F);
    out->f[D_DOT] = unit_fmt(1, 3, nrm_prod_fbits(cfg->width));    /* |a.b| <= 3 whatever the vectors */
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* The datapath, built or walked: y's value. */
static unet_val d3_walk(unet *n, const unit_cfg *cfg, unit_io *io)
{
    unet_val in[6];
    for (int k = 0; k < 6; k++) {
        in[k] = unet_input(n, n->u->sigs[k].name, -1);
        if (io) io->in[k] = in[k].s;
    }
    unet_val d = nrm_dot(n, D_DOT, "dot", in, in + 3, 3.0 * 4.0, cfg->schedule == D3_PIPE);
    return unet_shift(n, D_Y, "y", d, 0);
}

static int d3_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    (void)err; (void)errlen;
    unet n;
    unet_init(&n, &unit_dot3, f, SIM_RND_TRUNC);    /* the context's modes quantize */
    unet_hw(&n, c, sc);
    unet_clock(&n, clk);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    io->out[0] = d3_walk(&n, cfg, io).s;
    sim_fmt u1 = unit_fmt(0, 1, 0);
    io->in_ready = sim_const_raw(c, sc, "in_ready", u1, 1);
    if (cfg->schedule == D3_PIPE) {
        io->out_valid = rec_delay(c, sc, clk, "v", io->in_valid, 1);
    } else {
        io->out_valid = sim_signal_new(c, sc, "out_valid", u1, SIM_KIND_WIRE);
        sim_assign(c, io->out_valid, io->in_valid);
    }
    io->scope = sc;
    return 0;
}

static void d3_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    out[0] = in[0] * in[3] + in[1] * in[4] + in[2] * in[5];
}

static int d3_exact(const unit_cfg *cfg, const sim_dy *in, sim_dy *out)
{
    (void)cfg;
    sim_dy p;
    sim_dy_mul(out, &in[0], &in[3]);
    for (int k = 1; k < 3; k++) {
        sim_dy_mul(&p, &in[k], &in[k + 3]);
        sim_dy_add(out, out, &p);
    }
    return out->ovf ? -1 : 0;
}

/* The walk's: the products' and sums' quantizations (none with the
 * default formats) and y's (docs/bounds.md, "dot3"). */
static void d3_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    unet n;
    unet_init(&n, &unit_dot3, f, cfg->rnd);
    per_out[0] = d3_walk(&n, cfg, NULL).err;
}

const unit_desc unit_dot3 = {
    .name = "dot3",
    .ref = &ref_model_dot3,
    .summary = "y = a.b for three-component vectors: three exact products and two adders",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV (N.L and N.H of the per-pixel reference)",
    UNIT_SIGS(D3_SIGS(UNIT_SIG_ROW)),
    .nsched = 2,
    .sched = { { "comb", "combinational: an item a clock" },
               { "pipe", "the products registered, then the adders: an item a clock, one clock of latency" } },
    .nparams = 0,
    .fmt_rule = "a, b, y s2.(W-2) (components in [-1, 1]); dot and its products s3.P, P = 2W-4 (exact) up to W = 25, W+21 above",
    .formats = d3_formats, .beats = beats1, .build = d3_build, .ideal = d3_ideal, .bound = d3_bound,
    .ideal_exact = d3_exact,
    .bound_own_modes = 1,   /* the unet walk's */
};
