/* tb_stability_prof.c - the stability atlas's rows on highlight profiles
 * (tb_stability_int.h): Gaussian and Phong-lobe intensity profiles over
 * one interval, run through the interp2/interp3 units cycle by cycle, for
 * the cubic's overshoot, the adaptive policy's degree against curvature,
 * and the cubic's two node sets. docs/stability.md gives the algebra.
 */
#include "testbench/study/tb_stability_int.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ profiles */

typedef double (*profile_fn)(const double *par, double t);

static double prof_gauss(const double *par, double t)     /* base + amp exp(-(t-x0)^2/(2 s^2)) */
{
    double d = (t - par[0]) / par[1];
    return par[2] + par[3] * exp(-0.5 * d * d);
}

static double prof_phong(const double *par, double t)     /* base + amp cos^n(phi0 + dphi t) */
{
    double a = par[0] + par[1] * t;
    double c = cos(a);
    return par[2] + par[3] * (c > 0 ? pow(c, par[4]) : 0);
}

typedef struct profile { profile_fn f; double par[5]; } profile;

/* Run interp{deg} (paper schedule, width 16, L = 8) over the profiles;
 * y[p * 8 + k] the hardware's pixel k of profile p. 0, or -1. */
#define PROF_L 8
#define PROF_W 20         /* y is s7.(W-7): 13 fraction bits, well below 2^-8 */
#define PROF_TERMS 10     /* /3 networks with 10 terms: below the output LSB at width 20 */
static int run_profiles_nodes(int deg, int nodes, const profile *pr, size_t np, double *y, double *area)
{
    const unit_desc *u = unit_find(deg == 2 ? "interp2" : "interp3");
    if (!u) return -1;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = PROF_W;
    cfg.L = PROF_L;
    cfg.terms = PROF_TERMS;
    cfg.nodes = nodes;
    const vec_model *m = u->ref;
    const vec_params *p = &cfg.model;
    vec_set vs;
    vec_set_init(&vs);
    vec_set_header(&vs, m, p);
    static const double tn3[4] = { 0, 1, 0.5, 0.25 }, tn3b[4] = { 0, 1, 0.5, 0.75 }, tn2[3] = { 0, 1, 0.5 };
    const double *tn = deg == 2 ? tn2 : nodes ? tn3b : tn3;
    for (size_t i = 0; i < np; i++) {
        double row[4 + PROF_L];
        for (int j = 0; j <= deg; j++) row[j] = pr[i].f(pr[i].par, tn[j]);
        m->eval(p, row, row + deg + 1);
        if (vec_set_push(&vs, row)) { vec_set_free(&vs); return -1; }
    }
    tb_result r;
    int rc = tb_stab_run(u, &cfg, NULL, &vs, &r);
    vec_set_free(&vs);
    if (rc) return -1;
    for (size_t i = 0; i < np * PROF_L; i++) y[i] = sim_fx_to_real(r.raw[i * (size_t)r.n_out], r.out[0].fmt);
    if (area) *area = r.area_ge;
    tb_result_free(&r);
    return 0;
}

static int run_profiles(int deg, const profile *pr, size_t np, double *y, double *area)
{
    return run_profiles_nodes(deg, 0, pr, np, y, area);
}

/* ------------------------------------------------------ cubic overshoot */

static const double OVS_CENTRES[] = { 0.375, 0.5, 0.625, 0.75 };
#define N_OVS (sizeof OVS_CENTRES / sizeof OVS_CENTRES[0])

int tb_stab_overshoot(double s, double *excursion, double *err_raw, double *err_clamped)
{
    profile pr[N_OVS];
    double y[N_OVS * PROF_L];
    for (size_t i = 0; i < N_OVS; i++) pr[i] = (profile){ prof_gauss, { OVS_CENTRES[i], s, 0, 1, 0 } };
    if (run_profiles(3, pr, N_OVS, y, NULL)) return -1;
    *excursion = *err_raw = *err_clamped = 0;
    for (size_t i = 0; i < N_OVS; i++)
        for (int k = 0; k < PROF_L; k++) {
            double v = y[i * PROF_L + k], ex = pr[i].f(pr[i].par, (double)k / PROF_L);
            *excursion = fmax(*excursion, fmax(v - 1, -v));
            *err_raw = fmax(*err_raw, fabs(v - ex));
            *err_clamped = fmax(*err_clamped, fabs(fmin(fmax(v, 0), 1) - ex));
        }
    return 0;
}

double tb_stab_overshoot_width(double target)
{
    for (int i = 128; i >= 1; i--) {
        double ex, e1, e2;
        if (tb_stab_overshoot(i / 64.0, &ex, &e1, &e2)) return -1;
        if (ex > target) return i / 64.0;
    }
    return 0;
}

/* Area of an output clamp to [0, 1] on y's format (sI.F): an OR of the
 * integer bits below the sign (y >= 1), then per bit a 2:1 mux to 1.0's
 * pattern and an AND with the inverted sign (y < 0 -> 0). */
static double clamp_area(sim_fmt y)
{
    return (y.ibits - 1) * SIM_GE_OR2 + SIM_GE_INV + y.width * (SIM_GE_MUX2 + SIM_GE_AND2);
}

/* ------------------------------------------------ degree and curvature */

#define DEG_MAX_PROF 512

static size_t deg_profiles(profile *pr)
{
    size_t n = 0;
    for (int is = 0; is < 16; is++) {                 /* highlight widths 0.2 .. 8 intervals */
        double s = 0.2 * pow(40.0, is / 15.0);
        for (int ix = 0; ix < 9; ix++) {             /* centres -1 .. 2 */
            double x0 = -1 + 3.0 * ix / 8;
            for (int ia = 0; ia < 2; ia++)
                if (n < DEG_MAX_PROF) pr[n++] = (profile){ prof_gauss, { x0, s, 0.1, ia ? 0.85 : 0.4, 0 } };
        }
    }
    static const double EXPO[] = { 1, 4, 16, 64, 256 }, SPAN[] = { 0.02, 0.05, 0.1, 0.2, 0.4 };
    for (size_t e = 0; e < 5; e++)
        for (size_t d = 0; d < 5; d++)
            for (int ph = 0; ph < 4; ph++)
                if (n < DEG_MAX_PROF) pr[n++] = (profile){ prof_phong, { -0.2 + 0.2 * ph - SPAN[d] / 2, SPAN[d], 0.05, 0.9, EXPO[e] } };
    return n;
}

typedef struct deg_data {
    size_t n;
    double c[DEG_MAX_PROF], e1[DEG_MAX_PROF], e2[DEG_MAX_PROF], e3[DEG_MAX_PROF];
} deg_data;

static int deg_measure(deg_data *d)
{
    profile *pr = malloc(DEG_MAX_PROF * sizeof *pr);
    double *y2 = malloc(DEG_MAX_PROF * PROF_L * sizeof *y2), *y3 = malloc(DEG_MAX_PROF * PROF_L * sizeof *y3);
    int rc = -1;
    if (pr && y2 && y3) {
        d->n = deg_profiles(pr);
        if (!run_profiles(2, pr, d->n, y2, NULL) && !run_profiles(3, pr, d->n, y3, NULL)) {
            for (size_t i = 0; i < d->n; i++) {
                double i0 = pr[i].f(pr[i].par, 0), i1 = pr[i].f(pr[i].par, 1), ih = pr[i].f(pr[i].par, 0.5);
                d->c[i] = fabs(i0 + i1 - 2 * ih);
                d->e1[i] = d->e2[i] = d->e3[i] = 0;
                for (int k = 0; k < PROF_L; k++) {
                    double t = (double)k / PROF_L, ex = pr[i].f(pr[i].par, t);
                    /* linear: exact adders in hardware (I0 + k (I1 - I0)/L at
                     * the output's precision); evaluated in double */
                    d->e1[i] = fmax(d->e1[i], fabs(i0 + t * (i1 - i0) - ex));
                    d->e2[i] = fmax(d->e2[i], fabs(y2[i * PROF_L + k] - ex));
                    d->e3[i] = fmax(d->e3[i], fabs(y3[i * PROF_L + k] - ex));
                }
            }
            rc = 0;
        }
    }
    free(pr); free(y2); free(y3);
    return rc;
}

/* The smallest c of a profile that fails with error e but that the next
 * degree up (e_up) holds: profiles no degree holds (a highlight narrower
 * than the node spacing) say nothing about the choice of degree. */
static double min_c_failing(const deg_data *d, const double *e, const double *e_up, double target)
{
    double c = INFINITY;
    for (size_t i = 0; i < d->n; i++)
        if (e[i] > target && (!e_up || e_up[i] <= target)) c = fmin(c, d->c[i]);
    return c;
}

double tb_stab_deg_threshold(double target, int *n_profiles)
{
    deg_data *d = malloc(sizeof *d);
    double c = -1;
    if (d && !deg_measure(d)) {
        c = min_c_failing(d, d->e2, d->e3, target);
        if (n_profiles) *n_profiles = (int)d->n;
    }
    free(d);
    return c;
}

double tb_stab_lin_threshold(double target)
{
    deg_data *d = malloc(sizeof *d);
    double c = -1;
    if (d && !deg_measure(d)) c = min_c_failing(d, d->e1, d->e2, target);
    free(d);
    return c;
}

/* ------------------------------------------------------------ the atlas */

int tb_stab_atlas_overshoot(tb_stab *s, int charts)
{
    chart *c = charts ? chart_new("Cubic overshoot on a highlight inside one interval (interp3, L = 8)",
                                        "highlight width s (intervals)", "max excursion outside [0, 1]") : NULL;
    int se = -1, sr = -1, sc = -1;
    if (c) {
        chart_log_x(c, 1);
        chart_log_y(c, 1);
        se = chart_series(c, "excursion outside [0, 1]", CHART_LINE | CHART_POINTS);
        sr = chart_series(c, "max error, no clamp", CHART_LINE);
        sc = chart_series(c, "max error, clamped", CHART_LINE);
    }
    double worst = 0, s_w = 0, er_w = 0, ec_w = 0;
    for (int i = 1; i <= 128; i++) {
        double sw = i / 64.0, ex, er, ec;
        if (tb_stab_overshoot(sw, &ex, &er, &ec)) return -1;
        if (ex > worst) { worst = ex; s_w = sw; er_w = er; ec_w = ec; }
        if (c && (i <= 16 || i % 4 == 0)) {
            chart_point(c, se, sw, ex);
            chart_point(c, sr, sw, er);
            chart_point(c, sc, sw, ec);
        }
    }
    double b = tb_stab_overshoot_width(TB_STAB_TARGET);
    if (b < 0) return -1;
    /* the clamp's area against the interp3 unit's */
    const unit_desc *u = unit_find("interp3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = PROF_W;
    unit_fmts fm;
    char err[300];
    if (!u || tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) return -1;
    profile pr = { prof_gauss, { 0.5, 0.5, 0, 1, 0 } };
    double y[PROF_L], area = 0;
    if (run_profiles(3, &pr, 1, y, &area)) return -1;
    double ca = clamp_area(fm.f[unit_sig_must(u, "y")]);
    tb_stab_row *r = tb_stab_row_add(s, "overshoot", "interp3 (cubic N1)");
    r->boundary = b;
    tb_settext(r->condition, sizeof r->condition,
        "highlight exp(-(x-x0)^2/2s^2), peak 1, x0 = 3/8..3/4 of one interval (L = 8, width 20, 10-term /3)");
    tb_settext(r->measured, sizeof r->measured,
        "leaves [0, 1] by more than 2^-8 for s <= %.3g intervals (s = %.3g: holds); worst excursion %.3g "
        "(s = %.3g); an output clamp (%.0f GE, %.1f%% of interp3's %.0f GE) cuts that case's max error %.3g -> %.3g",
        b, b + 1 / 64.0, worst, s_w, ca, 100 * ca / area, area, er_w, ec_w);
    tb_settext(r->verdict, sizeof r->verdict,
        "highlights narrower than %.2g of an interval leave [0, 1]; the clamp removes the excursion, "
        "not the error inside [0, 1]", b);
    if (c) {
        chart_hline(c, TB_STAB_TARGET, "2^-8");
        chart_hband(c, 0, b, "overshoots");
        tb_stab_keep_chart(s, c, "stability_overshoot.svg");
    }
    return 0;
}

#define AUTO_DEFAULT 0.01     /* the scene's adaptive-auto threshold (scene/scene.h) */

int tb_stab_atlas_degree(tb_stab *s, int charts)
{
    deg_data *d = malloc(sizeof *d);
    if (!d || deg_measure(d)) { free(d); return -1; }
    double c2 = min_c_failing(d, d->e2, d->e3, TB_STAB_TARGET), c1 = min_c_failing(d, d->e1, d->e2, TB_STAB_TARGET);
    int none = 0;
    for (size_t i = 0; i < d->n; i++) none += d->e3[i] > TB_STAB_TARGET;
    tb_stab_row *r = tb_stab_row_add(s, "degree_auto", "degree 2 vs 3 vs 1");
    r->boundary = c2;
    tb_settext(r->condition, sizeof r->condition,
        "c = |I(0) + I(1) - 2 I(1/2)| of %zu highlight profiles on one interval; max error <= 2^-8 (L = 8, width 20, 10-term /3)",
        d->n);
    tb_settext(r->measured, sizeof r->measured,
        "degree 2 first fails (where 3 holds) at c = %.3g; linear (where 2 holds) at c = %.3g; %d profiles "
        "fail every degree (narrower than the node spacing)", c2, c1, none);
    /* failures (degree 2 chosen, degree 3 would hold) and cubic intervals
     * for a ladder of thresholds */
    static const double LAD[] = { 0.001, 0.003, 0.01, 0.03, 0.1 };
    char lad[200] = "";
    int fails_at[5];
    for (int k = 0; k < 5; k++) {
        int f = 0, cub = 0;
        for (size_t i = 0; i < d->n; i++) {
            if (d->e3[i] > TB_STAB_TARGET) continue;
            if (d->c[i] > LAD[k]) cub++;
            else f += d->e2[i] > TB_STAB_TARGET;
        }
        fails_at[k] = f;
        size_t l = strlen(lad);
        snprintf(lad + l, sizeof lad - l, "%s%g: %d fail, %d cubic", k ? "; " : "", LAD[k], f, cub);
    }
    if (c2 > AUTO_DEFAULT)
        tb_settext(r->verdict, sizeof r->verdict,
            "0.01 is safe but cautious: raise it to %.3g (every profile the cubic holds stays within 2^-8). %s",
            c2 * 0.9, lad);
    else {
        int cub_safe = 0, cub_def = 0;
        for (size_t i = 0; i < d->n; i++) {
            if (d->e3[i] > TB_STAB_TARGET) continue;
            cub_safe += d->c[i] >= c2 * 0.9;
            cub_def += d->c[i] > AUTO_DEFAULT;
        }
        tb_settext(r->verdict, sizeof r->verdict,
            "change it: 0.01 gives %d profiles degree 2 that miss 2^-8; %.2g is safe here (%d cubic intervals "
            "instead of %d). Ladder (profiles the cubic holds): %s", fails_at[2], c2 * 0.9, cub_safe, cub_def, lad);
    }
    if (charts) {
        chart *c = chart_new("Interpolation error against the adaptive policy's curvature measure",
                                   "c = |I(0) + I(1) - 2 I(1/2)|", "max |hw - profile|");
        if (c) {
            chart_log_x(c, 1);
            chart_log_y(c, 1);
            int s1 = chart_series(c, "linear", CHART_POINTS);
            int s2 = chart_series(c, "degree 2 (interp2)", CHART_POINTS);
            int s3 = chart_series(c, "degree 3 (interp3)", CHART_POINTS);
            for (size_t i = 0; i < d->n; i++) {
                chart_point(c, s1, d->c[i], d->e1[i]);
                chart_point(c, s2, d->c[i], d->e2[i]);
                chart_point(c, s3, d->c[i], d->e3[i]);
            }
            chart_hline(c, TB_STAB_TARGET, "2^-8");
            chart_hband(c, c2, INFINITY, "degree 2 can fail");
            chart_hband(c, AUTO_DEFAULT * 0.97, AUTO_DEFAULT * 1.03, "scene default 0.01");
            tb_stab_keep_chart(s, c, "stability_degree.svg");
        }
    }
    free(d);
    return 0;
}

/* The cubic's two node sets on the same profiles, through interp3. */
int tb_stab_atlas_nodes(tb_stab *s, int charts)
{
    (void)charts;
    profile *pr = malloc(DEG_MAX_PROF * sizeof *pr);
    double *y1 = malloc(DEG_MAX_PROF * PROF_L * sizeof *y1), *y2 = malloc(DEG_MAX_PROF * PROF_L * sizeof *y2);
    double a1 = 0, a2 = 0;
    int rc = -1;
    if (pr && y1 && y2) {
        size_t n = deg_profiles(pr);
        if (!run_profiles_nodes(3, 0, pr, n, y1, &a1) && !run_profiles_nodes(3, 1, pr, n, y2, &a2)) {
            int h1 = 0, h2 = 0, better1 = 0, better2 = 0;
            for (size_t i = 0; i < n; i++) {
                double e1 = 0, e2 = 0;
                for (int k = 0; k < PROF_L; k++) {
                    double ex = pr[i].f(pr[i].par, (double)k / PROF_L);
                    e1 = fmax(e1, fabs(y1[i * PROF_L + k] - ex));
                    e2 = fmax(e2, fabs(y2[i * PROF_L + k] - ex));
                }
                h1 += e1 <= TB_STAB_TARGET;
                h2 += e2 <= TB_STAB_TARGET;
                better1 += e1 < e2;
                better2 += e2 < e1;
            }
            tb_stab_row *r = tb_stab_row_add(s, "nodes_n1_n2", "interp3 nodes n1 vs n2");
            r->boundary = h1 - h2;
            tb_settext(r->condition, sizeof r->condition,
                "the same %zu profiles through interp3 with nodes=n1 and nodes=n2 (L = 8, width 20, 10-term /3)", n);
            tb_settext(r->measured, sizeof r->measured,
                "within 2^-8: n1 %d, n2 %d profiles; n1 smaller error on %d, n2 on %d; area n1 %.0f GE, n2 %.0f GE",
                h1, h2, better1, better2, a1, a2);
            tb_settext(r->verdict, sizeof r->verdict,
                "%s, and n1 is %.0f GE %s (its network has fewer adders); the node at 1/4 or 3/4 favours "
                "highlights on its side of the interval, so the profiles' placement decides the accuracy",
                h1 >= h2 && better1 >= better2 ? "n1 as accurate or better here (the paper's choice holds)"
                                               : "n2 more accurate here", fabs(a2 - a1), a1 <= a2 ? "smaller" : "larger");
            rc = 0;
        }
    }
    free(pr); free(y1); free(y2);
    return rc;
}
