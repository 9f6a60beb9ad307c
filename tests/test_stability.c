/* test_stability.c - each boundary of the stability atlas pinned from both
 * sides (one step before it fails, at it holds) by running the units, and
 * placed against an independent algebraic estimate computed here. */
#include "tests/tst.h"
#include "testbench/study/tb_stability.h"
#include "testbench/tb.h"
#include <stdint.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define TGT TB_STAB_TARGET

/* fy's error after L clocks sums a truncation (< 2^-F) of every register
 * through C(k, j) paths: F = 8 + log2(1 + L + C(L,2) + C(L,3)) suffices. */
static int fwd_alg(int deg, int L)
{
    double s = 0, b = 1;
    for (int j = 0; j <= deg; j++) { s += b; b = b * (L - j) / (j + 1); }
    return (int)ceil(8 + log2(s));
}

static void fwd_l32_boundary(void)
{
    for (int deg = 2; deg <= 3; deg++) {
        int F = tb_stab_fwd_min_frac(deg, 32, TGT);
        TST_CHECK(F > 8, "deg %d: F = %d", deg, F);
        double e_at = tb_stab_fwd_err(deg, 32, F), e_below = tb_stab_fwd_err(deg, 32, F - 1);
        TST_CHECK(e_at >= 0 && e_at <= TGT, "deg %d: F = %d err %g", deg, F, e_at);
        TST_CHECK(e_below > TGT, "deg %d: F - 1 = %d err %g should fail", deg, F - 1, e_below);
        /* the worst case sums every truncation; trunc errors all have one sign,
         * so the measured need sits at most 3 bits below the algebra's */
        int a = fwd_alg(deg, 32);
        TST_CHECK(F <= a && F >= a - 3, "deg %d: measured F = %d, algebra %d", deg, F, a);
    }
    /* longer intervals need more bits */
    TST_CHECK(tb_stab_fwd_min_frac(3, 8, TGT) < tb_stab_fwd_min_frac(3, 32, TGT), "monotone in L");
}

/* A, B, C, D of the N1 cubic through nodes I(0), I(1), I(1/2), I(1/4), from
 * the Lagrange form (independent of the networks): p(t) = A t^3 + B t^2 + C t + D. */
static void n1_coefs(const double I[4], double co[4])
{
    static const double tn[4] = { 0, 1, 0.5, 0.25 };
    for (int k = 0; k < 4; k++) co[k] = 0;
    for (int i = 0; i < 4; i++) {
        double poly[4] = { 1, 0, 0, 0 }, den = 1;     /* ascending powers */
        for (int j = 0; j < 4; j++) {
            if (j == i) continue;
            for (int p = 3; p >= 1; p--) poly[p] = poly[p - 1] - tn[j] * poly[p];
            poly[0] = -tn[j] * poly[0];
            den *= tn[i] - tn[j];
        }
        for (int p = 0; p < 4; p++) co[3 - p] += I[i] * poly[p] / den;
    }
}

static void coef_ranges(void)
{
    /* the extremes of a linear form of [0,1] inputs are at the corners */
    double lo[4] = { 0 }, hi[4] = { 0 };
    for (int b = 0; b < 16; b++) {
        double I[4], co[4];
        for (int i = 0; i < 4; i++) I[i] = (b >> i) & 1;
        n1_coefs(I, co);
        for (int k = 0; k < 4; k++) { lo[k] = fmin(lo[k], co[k]); hi[k] = fmax(hi[k], co[k]); }
    }
    static const char *const nm[4] = { "a", "b", "c", "d" };
    for (int k = 0; k < 4; k++) {
        int want = 1;
        while (!(lo[k] >= -ldexp(1, want - 1) && hi[k] < ldexp(1, want - 1))) want++;
        int got = tb_stab_coef_ibits("coef3_n1", nm[k]);
        TST_EQ_INT(got, want);
    }
    /* B one bit short: both modes overflow, wrap errs by about 2^(I-1), sat less */
    int I = tb_stab_coef_ibits("coef3_n1", "b");
    uint64_t ow = 0, os = 0, o_ok = 1;
    double ew = 0, es = 0, e_ok = 1;
    TST_CHECK(!tb_stab_coef_missing("coef3_n1", "b", I - 1, 0, &ow, &ew), "wrap run");
    TST_CHECK(!tb_stab_coef_missing("coef3_n1", "b", I - 1, 1, &os, &es), "sat run");
    TST_CHECK(!tb_stab_coef_missing("coef3_n1", "b", I, 0, &o_ok, &e_ok), "full run");
    TST_CHECK(ow > 0 && os > 0, "overflows wrap %llu sat %llu", (unsigned long long)ow, (unsigned long long)os);
    TST_CHECK(ew >= ldexp(1, I - 2), "wrap error %g", ew);
    TST_CHECK(es < ew, "sat %g < wrap %g", es, ew);
    TST_CHECK(o_ok == 0 && e_ok < 0.01, "at s%d: %llu overflows, error %g", I, (unsigned long long)o_ok, e_ok);
}

/* The float N1 cubic of the highlight at pixel t. */
static double cubic_at(double s, double x0, double t)
{
    static const double tn[4] = { 0, 1, 0.5, 0.25 };
    double y = 0;
    for (int i = 0; i < 4; i++) {
        double l = 1, d = (tn[i] - x0) / s;
        for (int j = 0; j < 4; j++) if (j != i) l *= (t - tn[j]) / (tn[i] - tn[j]);
        y += l * exp(-0.5 * d * d);
    }
    return y;
}

static double float_excursion(double s)
{
    static const double X0[] = { 0.375, 0.5, 0.625, 0.75 };
    double ex = 0;
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 8; k++) {
            double y = cubic_at(s, X0[c], k / 8.0);
            ex = fmax(ex, fmax(y - 1, -y));
        }
    return ex;
}

static void overshoot_boundary(void)
{
    double b = tb_stab_overshoot_width(TGT);
    TST_CHECK(b > 0 && b < 2, "boundary %g", b);
    double ex, er, ec;
    TST_CHECK(!tb_stab_overshoot(b, &ex, &er, &ec) && ex > TGT, "at %g: excursion %g", b, ex);
    TST_CHECK(ec <= er, "clamped %g <= raw %g", ec, er);
    TST_CHECK(!tb_stab_overshoot(b + 1 / 64.0, &ex, &er, &ec) && ex <= TGT, "at %g: excursion %g", b + 1 / 64.0, ex);
    /* the method's own cubic overshoots there too (hardware adds < 2^-11) */
    TST_CHECK(float_excursion(b) > TGT - ldexp(1, -11), "float excursion %g at %g", float_excursion(b), b);
    TST_CHECK(float_excursion(b + 1 / 64.0) <= TGT + ldexp(1, -11), "float at %g: %g", b + 1 / 64.0,
              float_excursion(b + 1 / 64.0));
}

static void degree_thresholds(void)
{
    /* linear's error at the midpoint pixel (t = 1/2, k = 4 of 8) is c/2
     * exactly, so linear fails every profile with c > 2 target */
    double c1 = tb_stab_lin_threshold(TGT);
    TST_CHECK(c1 > 0 && c1 <= 2 * TGT, "linear threshold %g", c1);
    int n = 0;
    double c2 = tb_stab_deg_threshold(TGT, &n);
    TST_CHECK(n > 100, "profiles %d", n);
    TST_CHECK(c2 > 0 && isfinite(c2), "degree-2 threshold %g", c2);
    /* a looser target moves the boundary out (or keeps it) */
    TST_CHECK(tb_stab_deg_threshold(4 * TGT, NULL) >= c2, "monotone in the target");
}

/* The largest |3 hw - x| in output LSBs over the stability vectors of div3
 * at width W with t terms, x the input quantized by floor (the default
 * rounding, trunc) to s1.(W-1), in integers: hw and x share the output's
 * LSB, so |hw - x/3| <= 1 LSB is exactly |3 hw - x| <= 3. */
static long div3_worst3(int W, int t)
{
    const unit_desc *u = unit_find("div3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = W;
    cfg.terms = t;
    cfg.series = 0;
    vec_set vs;
    vec_set_init(&vs);
    vec_set_header(&vs, u->ref, &cfg.model);
    if (u->ref->gen(&cfg.model, 64, 1, &vs)) return -1;
    unit_fmts f;
    tb_result r;
    char err[400];
    long worst = -1;
    if (!tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err) &&
        tb_run(u, &cfg, &f, &vs, NULL, &r, err, sizeof err) == TB_OK) {
        if (r.out[0].fmt.fbits == W - 1)
            for (size_t i = 0; i < r.vectors; i++) {
                long x = (long)floor(ldexp(vec_row(&vs, i)[0], W - 1));
                long d = labs(3 * (long)r.raw[i * (size_t)r.n_out] - x);
                if (d > worst) worst = d;
            }
        tb_result_free(&r);
    }
    vec_set_free(&vs);
    return worst;
}

static void div3_terms(void)
{
    for (int W = 8; W <= 24; W += 4) {
        int t = tb_stab_div3_terms(W);
        TST_CHECK(t > 1, "W=%d terms %d", W, t);
        /* the stated rule, decided here in integers */
        long at = div3_worst3(W, t), below = div3_worst3(W, t - 1);
        TST_CHECK(at >= 0 && at <= 3, "W=%d: %d terms hold (3 x error %ld LSB)", W, t, at);
        TST_CHECK(below > 3, "W=%d: %d terms fail (3 x error %ld LSB)", W, t - 1, below);
        TST_CHECK(tb_stab_div3_holds(W, t) == 1 && tb_stab_div3_holds(W, t - 1) == 0, "W=%d: holds", W);
        /* the reported error is that measure */
        TST_CHECK(tb_stab_div3_err(W, t) == ldexp(at / 3.0, -(W - 1)), "W=%d: error %g vs %ld/3 LSB",
                  W, tb_stab_div3_err(W, t), at);
        /* the series' own error 4^-t/6 (|x| < 1) must reach one LSB, plus
         * up to one term for the truncations */
        int a = (int)ceil((W - 1 - log2(6.0)) / 2);
        TST_CHECK(t >= a && t <= a + 1, "W=%d: measured %d, algebra %d", W, t, a);
    }
}

/* Relative error of D16 (clamped) against Beckmann where D > 1% of its
 * peak, from the formulas written out here. */
static double d16_rel(double m)
{
    double worst = 0, peak = 1 / (4 * m * m);
    for (int i = 0; i <= 3600; i++) {
        double c = cos(0.5 * M_PI * i / 3600), c2 = c * c;
        double d = exp(-(1 - c2) / (c2 * m * m)) / (4 * m * m * c2 * c2);
        double base = ((2 / (m * m) - 4) / 16) * (c - 1) + 1;
        double a = base > 0 ? pow(base, 16) / (4 * m * m) : 0;
        if (d > 0.01 * peak) worst = fmax(worst, fabs(a / d - 1));
    }
    return worst;
}

static void brdf_d16_range(void)
{
    /* the atlas's grid: holds at 0.200, fails at 0.205 and at 0.190 */
    TST_NEAR(tb_stab_brdf_err(16, 0.2, 0.01), d16_rel(0.2), 1e-9);
    TST_CHECK(d16_rel(0.200) <= 0.05 && tb_stab_brdf_err(16, 0.200, 0.01) <= 0.05, "0.200 holds");
    TST_CHECK(d16_rel(0.205) > 0.05 && tb_stab_brdf_err(16, 0.205, 0.01) > 0.05, "0.205 fails");
    TST_CHECK(d16_rel(0.190) > 0.05 && tb_stab_brdf_err(16, 0.190, 0.01) > 0.05, "0.190 fails");
}

static void divider_and_powers(void)
{
    for (int W = 8; W <= 24; W += 8) {
        double e, cl;
        TST_CHECK(!tb_stab_unit("div", W, 0, &e, &cl), "div W=%d", W);
        TST_CHECK(e < 1, "div W=%d: %g LSB", W, e);          /* restoring: the remainder is < d */
        TST_NEAR(cl, W, 0);                                    /* a quotient bit a clock */
    }
    /* pow_n at width 16: n = 8 within 8 LSB, n = 16 not */
    double e8 = 0, e16 = 0, c8 = 0, c16 = 0;
    TST_CHECK(!tb_stab_unit("pow_n", 16, 8, &e8, &c8) && !tb_stab_unit("pow_n", 16, 16, &e16, &c16), "pow_n runs");
    TST_CHECK(e8 <= 8 && e16 > 8, "n=8 %g LSB, n=16 %g LSB", e8, e16);
    /* square and multiply: log2 n squarings, a clock each */
    TST_NEAR(c8, 3, 0);
    TST_NEAR(c16, 4, 0);
}

/* interp3 with nodes=n2 computes the cubic through I(0), I(1), I(1/2),
 * I(3/4): its pixels against the Lagrange form written out here. */
static void interp3_n2_is_lagrange(void)
{
    static const double tn[4] = { 0, 1, 0.5, 0.75 };
    const unit_desc *u = unit_find("interp3");
    TST_CHECK(u != NULL, "interp3");
    if (!u) return;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = 24;
    cfg.terms = 12;
    cfg.L = 8;
    char err[400];
    TST_CHECK(!unit_param_set(u, &cfg, "nodes", "n2", err, sizeof err), "%s", err);
    unit_fmts fm;
    TST_CHECK(!tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err), "%s", err);
    vec_set vs;
    vec_set_init(&vs);
    vec_set_header(&vs, u->ref, &cfg.model);
    double I[8][4], row[12];
    for (int it = 0; it < 8; it++) {
        for (int i = 0; i < 4; i++) I[it][i] = row[i] = fmod(0.37 * (it + 1) * (i + 2) + 0.11 * i, 1.0);
        for (int k = 0; k < 8; k++) row[4 + k] = 0;
        vec_set_push(&vs, row);
    }
    tb_result r;
    TST_CHECK(tb_run(u, &cfg, &fm, &vs, NULL, &r, err, sizeof err) == TB_OK, "%s", err);
    double worst = 0;
    for (int it = 0; it < 8; it++)
        for (int k = 0; k < 8; k++) {
            double t = k / 8.0, y = 0;
            for (int i = 0; i < 4; i++) {
                double l = 1;
                for (int j = 0; j < 4; j++) if (j != i) l *= (t - tn[j]) / (tn[i] - tn[j]);
                y += l * I[it][i];
            }
            worst = fmax(worst, fabs(sim_fx_to_real(r.raw[it * 8 + k], r.out[0].fmt) - y));
        }
    TST_CHECK(worst < 1e-4, "max |hw - Lagrange N2| = %g", worst);
    tb_result_free(&r);
    vec_set_free(&vs);
}

static void atlas_rows(void)
{
    static tb_stab s;
    char err[300];
    TST_CHECK(!tb_stability(&s, 0, err, sizeof err), "%s", err);
    TST_CHECK(s.nrows >= 15, "rows %d", s.nrows);
    for (int i = 0; i < s.nrows; i++)
        TST_CHECK(s.rows[i].method[0] && s.rows[i].condition[0] && s.rows[i].measured[0] && s.rows[i].verdict[0],
                  "row %d (%s) incomplete", i, s.rows[i].id);
    TST_EQ_INT((int)s.rows[0].boundary, tb_stab_fwd_min_frac(3, 32, TGT));
    tb_stab_free(&s);
}

int main(void)
{
    TST_RUN(fwd_l32_boundary);
    TST_RUN(coef_ranges);
    TST_RUN(overshoot_boundary);
    TST_RUN(degree_thresholds);
    TST_RUN(div3_terms);
    TST_RUN(brdf_d16_range);
    TST_RUN(divider_and_powers);
    TST_RUN(interp3_n2_is_lagrange);
    TST_RUN(atlas_rows);
    TST_EXIT();
}
