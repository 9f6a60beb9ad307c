/* test_units_shade.c - the per-pixel shading units (sqrt, dot3, norm3,
 * shade) against shading computed here in double, by a few lines of our
 * own (not the reference models' functions), on random normals, lights,
 * half vectors and materials: every schedule, widths 12, 16 and 24, every
 * hardware output within the unit's derived bound of the value computed
 * from the inputs as the hardware holds them, no overflow, and the bound
 * not vacuous (below 2^-(W-9) and reached to within a factor 64 on
 * shade, where the power amplifies the errors most); shade_cook (D16, m
 * 0.3) on frames with V.H >= 0.55 against Cook-Torrance as printed. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include <stdint.h>

#define ROWS 400

static uint64_t rng_s;
static double rnd(void)
{
    uint64_t z = (rng_s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}
static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
/* A direction uniform on the sphere (Marsaglia), times len. */
static void sphere(double len, double *v)
{
    double a, b, s;
    do { a = 2 * rnd() - 1; b = 2 * rnd() - 1; s = a * a + b * b; } while (s >= 1);
    double t = 2 * sqrt(1 - s);
    v[0] = len * a * t; v[1] = len * b * t; v[2] = len * (1 - 2 * s);
}
static double len_in_domain(void) { return 0.5 + 0x1p-7 + (0.5 - 0x1p-6) * rnd(); }

/* The inputs of one random row of unit `name` (before quantization). */
static void draw(const char *name, double *in)
{
    if (!strcmp(name, "shade_cook")) {
        /* V, then L with L.V >= -0.4 (hs <= 0.913: the unit's clamps
         * change nothing, so the textbook form below is its function),
         * hs = 1/|L + V|, N near H half the time */
        sphere(len_in_domain(), in);
        sphere(1, in + 6);
        do sphere(1, in + 3); while (dot(in + 3, in + 6) < -0.4);
        double h[3] = { in[3] + in[6], in[4] + in[7], in[5] + in[8] }, hl = sqrt(dot(h, h));
        in[9] = 1 / hl;
        if (rnd() < 0.5) {
            double t = 0.3 * rnd(), l = sqrt(dot(in, in));
            for (int k = 0; k < 3; k++) in[k] = (1 - t) * h[k] / hl + t * in[k] / l;
            l = len_in_domain() / sqrt(dot(in, in));
            for (int k = 0; k < 3; k++) in[k] *= l;
        }
        in[10] = rnd(); in[11] = rnd(); in[12] = rnd() / 3;
        return;
    }
    if (!strcmp(name, "sqrt")) { in[0] = (2 - 0x1p-8) * rnd(); return; }
    if (!strcmp(name, "dot3")) { sphere(rnd(), in); sphere(1, in + 3); return; }
    sphere(len_in_domain(), in);
    if (!strcmp(name, "norm3")) return;
    sphere(1, in + 3);
    do sphere(1, in + 6); while (dot(in + 3, in + 6) < 0);
    if (rnd() < 0.5) {              /* a normal near H: the highlight */
        double t = 0.3 * rnd(), l = sqrt(dot(in, in));
        for (int k = 0; k < 3; k++) in[k] = (1 - t) * in[6 + k] + t * in[k] / l;
        l = len_in_domain() / sqrt(dot(in, in));
        for (int k = 0; k < 3; k++) in[k] *= l;
    }
    for (int k = 9; k < 12; k++) in[k] = rnd();
}

/* What the unit should give for inputs q (as held), in double. */
static void expect(const char *name, int e, const double *q, double *out)
{
    if (!strcmp(name, "sqrt")) { out[0] = sqrt(q[0]); return; }
    if (!strcmp(name, "dot3")) { out[0] = dot(q, q + 3); return; }
    double len = sqrt(dot(q, q));
    if (!strcmp(name, "shade_cook")) {
        /* Cook-Torrance as printed, F / pi in kc: kc D G / (nl nv), G =
         * min(1, 2 nh nv / vh, 2 nh nl / vh), 2 / vh = 4 hs, nh = N.H with
         * H = (L + V) hs; D the papers' D_g at m = 0.3, g = 16 */
        double nl = dot(q, q + 3) / len, nv = dot(q, q + 6) / len, hs = q[9], s = q[10];
        if (nl > 0) {
            s += q[11] * nl;
            if (nv > 0) {
                double nh = (nl + nv) * hs, m = 0.3, base = 1 + (2 / (m * m) - 4) / 16 * (nh - 1), d = 0;
                if (base > 0) { d = 1 / (4 * m * m); for (int k = 0; k < 16; k++) d *= base; }
                double g = fmin(1, fmin(4 * hs * nh * nv, 4 * hs * nh * nl));
                s += q[12] * d * g / (nl * nv);
            }
        }
        out[0] = s < 1 ? s : 1;
        return;
    }
    if (!strcmp(name, "norm3")) { for (int k = 0; k < 3; k++) out[k] = q[k] / len; return; }
    double cl = dot(q, q + 3) / len, ch = dot(q, q + 6) / len, s = q[9];
    if (cl > 0) {
        double p = 1;
        for (int k = 0; k < e; k++) p *= ch;
        s += q[10] * cl + (ch > 0 ? q[11] * p : 0);
    }
    out[0] = s < 1 ? s : 1;
}

/* u's formats for cfg and an empty vector set with u's ports. */
static int setup(const unit_desc *u, const unit_cfg *cfg, unit_fmts *f, vec_set *vs)
{
    char err[600];
    int rc = tb_formats(u, cfg, NULL, 0, f, err, sizeof err);
    TST_CHECK(rc == 0, "%s", err);
    vec_set_init(vs);
    tb_expected_header(u, cfg, vs);
    return rc;
}

/* Every schedule of `name` at width W with parameter n = e (shade). */
static void check_unit(const char *name, int W, int e, uint64_t seed)
{
    const unit_desc *u = unit_find(name);
    TST_CHECK(u != NULL, "no unit %s", name);
    if (!u) return;
    for (int s = 0; s < u->nsched; s++) {
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        cfg.width = W;
        cfg.schedule = s;
        if (strcmp(name, "shade_cook")) cfg.n = e;
        unit_fmts f;
        char err[600];
        vec_set vs;
        if (setup(u, &cfg, &f, &vs)) return;
        int nin = vs.n_in, nout = vs.n_out;
        rng_s = seed;
        for (int r = 0; r < ROWS; r++) {
            double row[16];
            draw(name, row);
            for (int k = 0; k < nin; k++) {       /* as the hardware holds them */
                sim_fmt fk = f.f[unit_sig_must(u, vs.in_names[k])];
                row[k] = sim_fx_to_real(sim_fx_from_real(row[k], fk, SIM_RND_TRUNC, SIM_OVF_SAT, NULL), fk);
            }
            expect(name, e, row, row + nin);
            TST_CHECK(vec_set_push(&vs, row) == 0, "push");
        }
        tb_result res;
        int rc = tb_run(u, &cfg, &f, &vs, NULL, &res, err, sizeof err);
        TST_CHECK(rc == TB_OK, "%s %s W=%d: %s", name, u->sched[s].name, W, err);
        if (rc == TB_OK) {
            TST_EQ_INT(res.vectors, ROWS);
            TST_EQ_INT(res.overflows, 0);
            for (int o = 0; o < nout; o++) {
                const tb_metrics *m = &res.out[o];
                TST_CHECK(isfinite(m->bound) && m->bound < ldexp(1.0, 9 - W),
                          "%s %s W=%d %s: bound %g", name, u->sched[s].name, W, m->name, m->bound);
                TST_CHECK(m->max_abs_err <= m->bound, "%s %s W=%d %s: |hw - double| %g above the bound %g",
                          name, u->sched[s].name, W, m->name, m->max_abs_err, m->bound);
                if (!strcmp(name, "shade"))
                    TST_CHECK(m->max_abs_err >= m->bound / 64, "%s %s W=%d: bound %g, worst %g: vacuous",
                              name, u->sched[s].name, W, m->bound, m->max_abs_err);
            }
            tb_result_free(&res);
        }
        vec_set_free(&vs);
    }
}

static void widths(const char *name, int e)
{
    static const int W[] = { 12, 16, 24 };
    for (int k = 0; k < 3; k++) check_unit(name, W[k], e, 0x5eed0000u + (uint64_t)(k * 7 + e));
}

static void sqrt_within_bound(void) { widths("sqrt", 1); }
static void dot3_within_bound(void) { widths("dot3", 1); }
static void norm3_within_bound(void) { widths("norm3", 1); }
static void shade_within_bound(void) { widths("shade", 24); }
static void shade_cook_within_bound(void) { widths("shade_cook", 1); }
/* Other exponents: n = 1 (a multiply by one), 7 (square and multiply), 64 */
static void shade_other_n(void)
{
    check_unit("shade", 16, 1, 11);
    check_unit("shade", 16, 7, 12);
    check_unit("shade", 16, 64, 13);
}

/* Hand-checked pixels at width 16: head-on (N = L = H, |N| = 1/2) gives
 * ka + kd + ks clamped; a normal at the terminator's back side gives ka. */
static void shade_hand_pixels(void)
{
    const unit_desc *u = unit_find("shade");
    TST_CHECK(u != NULL, "no shade");
    if (!u) return;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts f;
    char err[600];
    vec_set vs;
    if (setup(u, &cfg, &f, &vs)) return;
    double rows[3][13] = {
        { 0, 0, 0.5, 0, 0, 1, 0, 0, 1, 0.125, 0.5, 0.25, 0.875 },
        { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0.5, 0.5, 0.5, 1 },
        { 0, 0, -0.75, 0, 0, 1, 0, 0, 1, 0.25, 0.5, 0.5, 0.25 } };
    for (int r = 0; r < 3; r++) TST_CHECK(vec_set_push(&vs, rows[r]) == 0, "push");
    tb_result res;
    TST_EQ_INT(tb_run(u, &cfg, &f, &vs, NULL, &res, err, sizeof err), TB_OK);
    TST_CHECK(res.out[0].max_abs_err <= res.out[0].bound, "hand pixels: %g over %g", res.out[0].max_abs_err, res.out[0].bound);
    tb_result_free(&res);
    vec_set_free(&vs);
}

int main(void)
{
    TST_RUN(sqrt_within_bound);
    TST_RUN(dot3_within_bound);
    TST_RUN(norm3_within_bound);
    TST_RUN(shade_within_bound);
    TST_RUN(shade_cook_within_bound);
    TST_RUN(shade_other_n);
    TST_RUN(shade_hand_pixels);
    TST_EXIT();
}
