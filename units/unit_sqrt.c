/* unit_sqrt.c - sqrt: y = sqrt(x) by the restoring digit recurrence of
 * unit_rec.c, one root bit a clock (restoring) or a stage (pipe).
 *
 * x in [0, 2) as u1.F_x; y in [0, sqrt 2) as u1.F_y, F_y >= F_x / 2. The
 * recurrence computes floor(sqrt(x) 2^F_y) exactly for the x the hardware
 * holds: y is the root truncated to its own format, 0 <= sqrt(x) - y <
 * 2^-F_y, whatever the rounding mode (no rounding happens inside: every
 * value is an integer raw, and R, Q, X are as wide as their values).
 */
#include "units/unit_rec.h"
#include "units/units_brdf.h"
#include "vectors/ref_shade.h"
#include <math.h>
#include <stdio.h>

enum { SQ_X, SQ_Y, SQ_NSIGS };
enum { SQ_ITER, SQ_PIPE };

static void sq_formats(const unit_cfg *cfg, unit_fmts *out)
{
    out->f[SQ_X] = unit_fmt(0, 1, cfg->width - 1);
    out->f[SQ_Y] = unit_fmt(0, 1, cfg->width - 1);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

extern const unit_desc unit_sqrt;

static int sq_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    sim_fmt fx = f->f[SQ_X], fy = f->f[SQ_Y];
    char b1[SIM_FMT_STRLEN];
    if (fx.is_signed || fx.ibits > 1) {
        snprintf(err, errlen, "sqrt: x=%s must be unsigned with at most one integer bit (x < 2)", sim_fmt_str(fx, b1));
        return -1;
    }
    rec_spec s = { REC_SQRT, fx.fbits, fy.fbits, 0 };
    if (rec_check(&s, err, errlen)) return -1;
    io->in[0] = sim_signal_new(c, sc, "x", fx, SIM_KIND_INPUT);
    sim_signal *q;
    if (cfg->schedule == SQ_ITER) {
        sim_signal *next, *first;
        brdf_seq(c, sc, clk, rec_steps(&s), io, &next, &first);
        (void)next;
        q = rec_iter(c, sc, clk, "rt_", &s, io->in[0], first, NULL);
    } else {
        io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
        io->in_ready = sim_const_raw(c, sc, "in_ready", unit_fmt(0, 1, 0), 1);
        q = rec_pipe(c, sc, clk, "rt", &s, io->in[0]);
        io->out_valid = rec_delay(c, sc, clk, "v", io->in_valid, rec_steps(&s));
    }
    /* the root's raw read as u1.F_y (wiring), then y */
    sim_signal *root = sim_shift(c, sc, "root", rec_out_fmt(&s), q, -fy.fbits);
    io->out[0] = sim_shift(c, sc, "y", fy, root, 0);
    io->scope = sc;
    return 0;
}

static void sq_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    out[0] = sqrt(in[0] > 0 ? in[0] : 0);
}

/* The root truncated to y's format: below one LSB of y (docs/bounds.md,
 * "sqrt"), when y holds every root (< sqrt 2); no bound otherwise. */
static void sq_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    (void)cfg;
    sim_fmt fx = f->f[SQ_X], fy = f->f[SQ_Y];
    int ok = !fx.is_signed && fx.ibits <= 1 && brdf_holds(fy, 0, sqrt(2.0));
    per_out[0] = ok ? sim_fmt_lsb(fy) : NAN;
}

const unit_desc unit_sqrt = {
    .name = "sqrt",
    .ref = &ref_model_sqrt,
    .summary = "y = sqrt(x) by the restoring digit recurrence, one root bit a clock or a stage",
    .source = "Nechyporuk & Romanyuk (2020), sec. IV (the per-pixel reference normalizes N); the restoring square root of Parhami's Computer Arithmetic (docs/references.md)",
    UNIT_SIGS(
        { .name = "x", .role = UNIT_SIG_IN, .what = "radicand, in [0, 2)" },
        { .name = "y", .role = UNIT_SIG_OUT, .what = "floor(sqrt(x) 2^F_y) 2^-F_y: the root truncated to y's format" }),
    .nsched = 2,
    .sched = { { "restoring", "one root bit a clock on one subtractor: F_y + 1 clocks per item" },
               { "pipe", "the recurrence unrolled, a stage a root bit: an item a clock, F_y + 1 clocks of latency" } },
    .nparams = 0,
    .fmt_rule = "x, y u1.(W-1); inside, every value an integer as wide as it can be (R: remainder, "
                "Q: root so far, X: radicand bits to come)",
    .formats = sq_formats, .beats = beats1, .build = sq_build, .ideal = sq_ideal, .bound = sq_bound,
    .bound_own_modes = 1,   /* no quantization inside: every mode gives the same bound */
};
