/* tb_stability.c - the stability atlas (tb_stability.h): each method
 * driven past the point where it stops working, the boundary found by
 * running the units cycle by cycle through tb_run (the BRDF rows sample
 * their double references, whose approximation error dominates any width).
 * docs/stability.md gives each boundary's algebra.
 */
#include "testbench/study/tb_stability.h"
#include "testbench/tb.h"
#include "sim/sim_area.h"
#include "vectors/ref_brdf.h"
#include "base/base_join.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ------------------------------------------------------------ running */

/* The unit's vectors: its generator's first n rows (named spans), then
 * every 0/1 pattern of the node inputs when nodes > 0 (the coefficients
 * are linear in the nodes: the corners reach their extremes). */
static int make_vectors(const unit_desc *u, const unit_cfg *cfg, size_t n, int nodes, vec_set *vs)
{
    const vec_model *m = u->ref;
    if (!m) return -1;
    const vec_params *p = &cfg->model;
    vec_set_init(vs);
    vec_set_header(vs, m, p);
    if (m->gen(p, n, 1, vs)) { vec_set_free(vs); return -1; }
    double row[VEC_MAX_PORTS * 2 + 80];
    for (int b = 0; nodes > 0 && b < (1 << nodes); b++) {
        for (int i = 0; i < nodes; i++) row[i] = (double)((b >> i) & 1);
        m->eval(p, row, row + vs->n_in);
        if (vec_set_push(vs, row)) { vec_set_free(vs); return -1; }
    }
    return 0;
}

/* Run u with formats fm (NULL: the rule's) on vs; TB_OK and r filled. */
static int run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs, tb_result *r)
{
    unit_fmts f;
    char err[400];
    memset(r, 0, sizeof *r);
    if (!fm) {
        if (tb_formats(u, cfg, NULL, 0, &f, err, sizeof err)) return -1;
        fm = &f;
    }
    if (tb_run(u, cfg, fm, vs, NULL, r, err, sizeof err) != TB_OK) { tb_result_free(r); return -1; }
    return 0;
}

/* Max |hw - ideal| over every output and beat. */
static double err_ideal(const tb_result *r)
{
    double e = 0;
    for (int o = 0; o < r->n_out; o++) e = fmax(e, r->out[o].max_err_ideal);
    return e;
}

/* ------------------------------------------------ forward differencing */

static const char *const FWD_REGS[] = { "fy", "fd1", "fd2", "fd3" };

double tb_stab_fwd_err(int deg, int L, int F)
{
    const unit_desc *u = unit_find(deg == 2 ? "interp2" : "interp3");
    if (!u) return -1;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = 24;
    cfg.L = L;
    cfg.schedule = unit_sched_find(u, "fwd");
    unit_fmts fm;
    char err[400];
    if (cfg.schedule < 0 || tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) return -1;
    for (int j = 0; j <= deg; j++) {
        int i = unit_sig_must(u, FWD_REGS[j]);
        fm.f[i] = unit_fmt(1, fm.f[i].ibits, F);
    }
    vec_set vs;
    if (make_vectors(u, &cfg, 24, deg + 1, &vs)) return -1;
    tb_result r;
    int rc = run(u, &cfg, &fm, &vs, &r);
    double e = rc ? -1 : r.overflows ? INFINITY : err_ideal(&r);
    if (!rc) tb_result_free(&r);
    vec_set_free(&vs);
    return e;
}

int tb_stab_fwd_min_frac(int deg, int L, double target)
{
    for (int F = 8; F <= 48; F++) {
        double e = tb_stab_fwd_err(deg, L, F);
        if (e < 0) return -1;
        if (e <= target) return F;
    }
    return -1;
}

/* ------------------------------------------------- coefficient ranges */

static int coef_run(const char *unit, const char *sig, int ibits, int sat, tb_result *r)
{
    const unit_desc *u = unit_find(unit);
    if (!u || unit_sig_index(u, sig) < 0) return -1;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = 16;
    cfg.ovf = sat ? SIM_OVF_SAT : SIM_OVF_WRAP;
    unit_fmts fm;
    char err[400];
    if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) return -1;
    int i = unit_sig_must(u, sig);
    if (ibits > 0) fm.f[i] = unit_fmt(1, ibits, fm.f[i].fbits);
    vec_set vs;
    if (make_vectors(u, &cfg, 16, unit_n_in(u), &vs)) return -1;
    int rc = run(u, &cfg, &fm, &vs, r);
    vec_set_free(&vs);
    return rc;
}

static const tb_sig *find_sig(const tb_result *r, const char *name)
{
    for (int i = 0; i < r->nsigs; i++)
        if (!strcmp(r->sigs[i].name, name)) return &r->sigs[i];
    return NULL;
}

int tb_stab_coef_ibits(const char *unit, const char *sig)
{
    tb_result r;
    if (coef_run(unit, sig, 0, 0, &r)) return -1;
    const tb_sig *s = find_sig(&r, sig);
    int I = -1;
    if (s && s->seen) {
        /* the fewest signed integer bits with -2^(I-1) <= value < 2^(I-1) */
        double lo = ldexp((double)s->min, -s->fmt.fbits), hi = ldexp((double)s->max, -s->fmt.fbits);
        for (I = 1; I < 40; I++)
            if (lo >= -ldexp(1, I - 1) && hi < ldexp(1, I - 1)) break;
    }
    tb_result_free(&r);
    return I;
}

int tb_stab_coef_missing(const char *unit, const char *sig, int ibits, int sat, uint64_t *overflows, double *max_err)
{
    tb_result r;
    if (coef_run(unit, sig, ibits, sat, &r)) return -1;
    const tb_sig *s = find_sig(&r, sig);
    *overflows = s ? s->overflows : 0;
    *max_err = 0;
    for (int o = 0; o < r.n_out; o++)
        if (!strcmp(r.out[o].name, sig)) *max_err = r.out[o].max_err_ideal;
    tb_result_free(&r);
    return 0;
}

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
    int rc = run(u, &cfg, NULL, &vs, &r);
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

/* ------------------------------------------------------------- div3 */

/* One run of div3 at width W with `terms` paper-series terms over its
 * vectors: the largest |hw - x/3| with x the unit's input (the vector
 * quantized to its format x, as the network sees it: the quantization is
 * the testbench's, not the network's), and whether every item is within
 * one output LSB. The rule is decided exactly on the dyadic values,
 * |3 hw - x| <= 3 * 2^-(W-1): x/3 has no double, and a unit that reaches
 * exactly one LSB holds, rather than losing by a rounding. */
static int div3_measure(int W, int terms, double *err, int *holds)
{
    const unit_desc *u = unit_find("div3");
    if (!u) return -1;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = W;
    cfg.terms = terms;
    cfg.series = 0;
    vec_set vs;
    if (make_vectors(u, &cfg, 64, 0, &vs)) return -1;
    tb_result r;
    int rc = run(u, &cfg, NULL, &vs, &r);
    if (rc) { vec_set_free(&vs); return -1; }
    sim_dy three, lim, x, hw, d, worst;
    sim_dy_int(&three, 3, 0);
    sim_dy_int(&lim, 3, W - 1);          /* 3 output LSBs */
    sim_dy_int(&worst, 0, 0);
    sim_fmt fx = r.fmts.f[0];            /* the input x */
    for (size_t i = 0; i < r.vectors; i++) {
        int ovf = 0;
        sim_dy_raw(&x, sim_fx_from_real(vec_row(&vs, i)[0], fx, cfg.rnd, cfg.ovf, &ovf), fx);
        sim_dy_raw(&hw, r.raw[i * (size_t)r.n_out], r.out[0].fmt);
        sim_dy_mul(&d, &hw, &three);
        sim_dy_sub(&d, &d, &x);
        sim_dy_abs(&d, &d);
        if (sim_dy_cmp(&d, &worst) > 0) worst = d;
    }
    *holds = sim_dy_cmp(&worst, &lim) <= 0;
    *err = sim_dy_to_double(&worst) / 3;
    vec_set_free(&vs);
    tb_result_free(&r);
    return 0;
}

double tb_stab_div3_err(int W, int terms)
{
    double e;
    int holds;
    return div3_measure(W, terms, &e, &holds) ? -1 : e;
}

int tb_stab_div3_holds(int W, int terms)
{
    double e;
    int holds;
    return div3_measure(W, terms, &e, &holds) ? -1 : holds;
}

int tb_stab_div3_terms(int W)
{
    const unit_desc *u = unit_find("div3");
    int max = u ? (int)u->params[0].max : 0;
    for (int t = 1; t <= max; t++) {
        int h = tb_stab_div3_holds(W, t);
        if (h < 0) return -1;
        if (h) return t;
    }
    return -1;
}

/* ------------------------------------------------------------- BRDF */

static double brdf_pair(int kind, double c, double p, double *exact)
{
    switch (kind) {
    case 4: case 8: case 16: *exact = ref_brdf_beckmann(c, p); return ref_brdf_dg_clamped(c, p, kind);
    case 1: *exact = ref_brdf_beckmann(c, p); return ref_brdf_beckmann_cpow(c, p);
    case 2: *exact = ref_brdf_ward_exp(c, p); return ref_brdf_ward_exp_approx_clamped(c, p);
    case 3: *exact = ref_brdf_cos_pow(c, p); return ref_brdf_schlick(c, p);
    default: *exact = ref_brdf_cos_pow(c, p); return ref_brdf_mschlick(c, p);
    }
}

double tb_stab_brdf_err(int kind, double p, double floor)
{
    enum { N = 3600 };
    double peak, worst = 0;
    brdf_pair(kind, 1.0, p, &peak);
    for (int i = 0; i <= N; i++) {
        double c = cos(0.5 * M_PI * i / N), ex, a = brdf_pair(kind, c, p, &ex);
        if (ex > floor * peak) worst = fmax(worst, fabs(a / ex - 1));
    }
    return worst;
}

/* ------------------------------------------------- divider and powers */

int tb_stab_unit(const char *unit, int W, int v, double *err_lsb, double *clocks)
{
    const unit_desc *u = unit_find(unit);
    if (!u) return -1;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = W;
    if (!strcmp(unit, "pow_n")) cfg.n = v;
    if (!strcmp(unit, "powg")) cfg.g = v;
    vec_set vs;
    if (make_vectors(u, &cfg, 64, 0, &vs)) return -1;
    tb_result r;
    int rc = run(u, &cfg, NULL, &vs, &r);
    vec_set_free(&vs);
    if (rc) return -1;
    *err_lsb = ldexp(err_ideal(&r), r.out[0].fmt.fbits);
    *clocks = r.cycles_per_item;
    tb_result_free(&r);
    return 0;
}

/* ============================================================ the atlas */

static tb_stab_row *row(tb_stab *s, const char *id, const char *method)
{
    tb_stab_row *r = &s->rows[s->nrows < TB_STAB_MAX_ROWS ? s->nrows++ : TB_STAB_MAX_ROWS - 1];
    memset(r, 0, sizeof *r);
    tb_settext(r->id, sizeof r->id, "%s", id);
    tb_settext(r->method, sizeof r->method, "%s", method);
    return r;
}

static void keep_chart(tb_stab *s, chart *c, const char *file)
{
    if (s->ncharts < TB_STAB_MAX_CHARTS) {
        s->charts[s->ncharts] = c;
        s->chart_files[s->ncharts++] = file;
    } else chart_free(c);
}

/* binomial sum 1 + L + C(L,2) + ... + C(L,deg): how many truncations reach fy */
static double fwd_reach(int deg, int L)
{
    double s = 0, b = 1;
    for (int j = 0; j <= deg; j++) { s += b; b = b * (L - j) / (j + 1); }
    return s;
}

static int atlas_fwd(tb_stab *s, int charts)
{
    static const int LS[] = { 4, 8, 16, 32 };
    chart *c = charts ? chart_new("Forward differencing: register fraction bits for max error <= 2^-8",
                                        "interval length L (pixels)", "fraction bits F of fy, fd1.. needed") : NULL;
    int sr[2] = { -1, -1 }, sa = -1;
    if (c) {
        chart_log_x(c, 1);
        sr[0] = chart_series(c, "interp3 fwd (measured)", CHART_LINE | CHART_POINTS);
        sr[1] = chart_series(c, "interp2 fwd (measured)", CHART_LINE | CHART_POINTS);
        sa = chart_series(c, "8 + log2(sum C(L,j)), cubic", CHART_LINE);
        chart_hline(c, 8, "output's 8 bits");
    }
    for (int dg = 3; dg >= 2; dg--) {
        int fmin[4];
        char list[160] = "";
        for (size_t i = 0; i < 4; i++) {
            fmin[i] = tb_stab_fwd_min_frac(dg, LS[i], TB_STAB_TARGET);
            if (fmin[i] < 0) return -1;
            base_join_addf(list, sizeof list, ", ", "L=%d: F=%d", LS[i], fmin[i]);
            if (c) {
                chart_point(c, sr[3 - dg], LS[i], fmin[i]);
                if (dg == 3) chart_point(c, sa, LS[i], 8 + log2(fwd_reach(3, LS[i])));
            }
        }
        char id[16], m[32];
        snprintf(id, sizeof id, "fwd%d", dg);
        snprintf(m, sizeof m, "interp%d fwd", dg);
        tb_stab_row *r = row(s, id, m);
        r->boundary = fmin[3];
        tb_settext(r->condition, sizeof r->condition,
            "fraction bits F of every fwd register for max |hw - ideal| <= 2^-8, L = 4..32 (width-24 coefficients)");
        tb_settext(r->measured, sizeof r->measured, "%s; at L=32: F=%d holds, F=%d fails (%d bits beyond the output's 8)",
            list, fmin[3], fmin[3] - 1, fmin[3] - 8);
        tb_settext(r->verdict, sizeof r->verdict,
            "fails with the output's own 8 bits at every L; each doubling of L costs about %d more bits "
            "(truncations summed over C(k,j) clocks)", dg);
    }
    /* error against F at L = 32 */
    if (charts) {
        chart *e = chart_new("Forward differencing at L = 32: error against register fraction bits",
                                   "fraction bits F of fy, fd1..", "max |hw - ideal|");
        if (e) {
            chart_log_y(e, 1);
            for (int dg = 3; dg >= 2; dg--) {
                int se = chart_series(e, dg == 3 ? "interp3 fwd, L=32" : "interp2 fwd, L=32", CHART_LINE | CHART_POINTS);
                for (int F = 8; F <= 26; F += 2) {
                    double v = tb_stab_fwd_err(dg, 32, F);
                    if (v >= 0 && isfinite(v)) chart_point(e, se, F, v);
                }
            }
            chart_hline(e, TB_STAB_TARGET, "2^-8");
            int f3 = (int)s->rows[s->nrows - 2].boundary;
            chart_hband(e, f3 - 0.1, f3 + 0.1, "cubic boundary");
            keep_chart(s, e, "stability_fwd_err.svg");
        }
    }
    if (c) keep_chart(s, c, "stability_fwd.svg");
    return 0;
}

static int atlas_coef(tb_stab *s, int charts)
{
    static const struct { const char *unit, *label; int n; } U[] = {
        { "coef3_n1", "cubic N1", 4 }, { "coef3_n2", "cubic N2", 4 }, { "coef2", "quadratic", 3 } };
    static const char *const C[] = { "a", "b", "c", "d" };
    chart *ch = charts ? chart_new("Integer bits each coefficient needs (intensities in [0, 1])",
                                         "coefficient (0 = A, 1 = B, 2 = C, 3 = D)", "signed integer bits") : NULL;
    for (size_t k = 0; k < 3; k++) {
        int ib[4] = { 0, 0, 0, 0 };
        char list[120] = "";
        int se = ch ? chart_series(ch, U[k].label, CHART_LINE | CHART_POINTS) : -1;
        for (int j = 0; j < U[k].n; j++) {
            ib[j] = tb_stab_coef_ibits(U[k].unit, C[j]);
            if (ib[j] < 0) return -1;
            base_join_addf(list, sizeof list, ", ", "%c s%d", 'A' + j, ib[j]);
            if (ch) chart_point(ch, se, j, ib[j]);
        }
        /* the widest coefficient one bit short, wrap and sat */
        int jw = 0;
        for (int j = 1; j < U[k].n; j++) if (ib[j] > ib[jw]) jw = j;
        uint64_t ow, os;
        double ew, es, e_ok;
        uint64_t o_ok;
        if (tb_stab_coef_missing(U[k].unit, C[jw], ib[jw] - 1, 0, &ow, &ew) ||
            tb_stab_coef_missing(U[k].unit, C[jw], ib[jw] - 1, 1, &os, &es) ||
            tb_stab_coef_missing(U[k].unit, C[jw], ib[jw], 0, &o_ok, &e_ok)) return -1;
        char id[32];
        snprintf(id, sizeof id, "coef_%s", U[k].unit);
        tb_stab_row *r = row(s, id, U[k].unit);
        r->boundary = ib[jw];
        tb_settext(r->condition, sizeof r->condition,
            "integer bits per coefficient for node intensities in [0, 1] (every 0/1 pattern), width 16");
        tb_settext(r->measured, sizeof r->measured,
            "%s; %c one bit short (s%d): wrap %llu overflows, max error %.3g; sat %llu, max error %.3g; "
            "at s%d: %llu overflows, error %.2g",
            list, 'A' + jw, ib[jw] - 1, (unsigned long long)ow, ew, (unsigned long long)os, es, ib[jw],
            (unsigned long long)o_ok, e_ok);
        tb_settext(r->verdict, sizeof r->verdict, "%c needs s%d; missing one bit, wrap errs by %.3g (a sign flip), "
            "sat by %.3g (clipped)", 'A' + jw, ib[jw], ew, es);
    }
    if (ch) keep_chart(s, ch, "stability_coef.svg");
    return 0;
}

static int atlas_overshoot(tb_stab *s, int charts)
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
    tb_stab_row *r = row(s, "overshoot", "interp3 (cubic N1)");
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
        keep_chart(s, c, "stability_overshoot.svg");
    }
    return 0;
}

#define AUTO_DEFAULT 0.01     /* the scene's adaptive-auto threshold (scene/scene.h) */

static int atlas_degree(tb_stab *s, int charts)
{
    deg_data *d = malloc(sizeof *d);
    if (!d || deg_measure(d)) { free(d); return -1; }
    double c2 = min_c_failing(d, d->e2, d->e3, TB_STAB_TARGET), c1 = min_c_failing(d, d->e1, d->e2, TB_STAB_TARGET);
    int none = 0;
    for (size_t i = 0; i < d->n; i++) none += d->e3[i] > TB_STAB_TARGET;
    tb_stab_row *r = row(s, "degree_auto", "degree 2 vs 3 vs 1");
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
            keep_chart(s, c, "stability_degree.svg");
        }
    }
    free(d);
    return 0;
}

/* The cubic's two node sets on the same profiles, through interp3. */
static int atlas_nodes(tb_stab *s, int charts)
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
            tb_stab_row *r = row(s, "nodes_n1_n2", "interp3 nodes n1 vs n2");
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

static int atlas_div3(tb_stab *s, int charts)
{
    static const int WS[] = { 8, 12, 16, 24 };
    chart *c = charts ? chart_new("The /3 shift network: error against terms (paper series)",
                                        "terms", "max |hw - x/3| in output LSBs") : NULL;
    if (c) chart_log_y(c, 1);
    char list[160] = "";
    int t16 = -1;
    for (size_t i = 0; i < 4; i++) {
        int t = tb_stab_div3_terms(WS[i]);
        if (t < 0) return -1;
        if (WS[i] == 16) t16 = t;
        base_join_addf(list, sizeof list, ", ", "W=%d: %d", WS[i], t);
        if (c) {
            char lab[24];
            snprintf(lab, sizeof lab, "width %d", WS[i]);
            int se = chart_series(c, lab, CHART_LINE | CHART_POINTS);
            for (int n = 1; n <= 12; n++) {
                double e = tb_stab_div3_err(WS[i], n);
                if (e >= 0) chart_point(c, se, n, ldexp(e, WS[i] - 1));
            }
        }
    }
    double e3 = tb_stab_div3_err(16, 3);
    tb_stab_row *r = row(s, "div3_terms", "div3 (paper series)");
    r->boundary = t16;
    tb_settext(r->condition, sizeof r->condition, "terms for max |hw - x/3| <= 1 output LSB (exact), x the input in [-1, 1), widths 8..24");
    tb_settext(r->measured, sizeof r->measured, "%s terms; the paper's 3 terms at W=16: %.3g (%.0f LSB)", list, e3,
        ldexp(e3, 15));
    tb_settext(r->verdict, sizeof r->verdict,
        "each term adds 2 bits: the paper's 3 terms hold to about 7 bits only; in interp3 the error of A is "
        "amplified by up to 24");
    if (c) {
        chart_hline(c, 1, "1 LSB");
        keep_chart(s, c, "stability_div3.svg");
    }
    return 0;
}

/* Smallest and largest parameter (on a grid) where err <= tol; NAN if none. */
static void holds_range(int kind, const double *grid, int n, double floor, double tol, double *lo, double *hi)
{
    *lo = *hi = NAN;
    for (int i = 0; i < n; i++)
        if (tb_stab_brdf_err(kind, grid[i], floor) <= tol) {
            if (isnan(*lo)) *lo = grid[i];
            *hi = grid[i];
        }
}

static int atlas_brdf(tb_stab *s, int charts)
{
    double mg[160];
    int nm = 0;
    for (int i = 10; i <= 140; i++) mg[nm++] = i / 200.0;           /* m, alpha 0.05 .. 0.70 */
    static const struct { int kind; const char *name; } D[] = {
        { 4, "D4" }, { 8, "D8" }, { 16, "D16" }, { 1, "cos-power form" } };
    chart *c = charts ? chart_new("BRDF approximations against Beckmann D (where D > 1% of its peak)",
                                        "roughness m", "max |relative error|") : NULL;
    if (c) chart_log_y(c, 1);
    for (size_t k = 0; k < 4; k++) {
        double lo, hi;
        holds_range(D[k].kind, mg, nm, 0.01, 0.05, &lo, &hi);
        char id[24];
        snprintf(id, sizeof id, "brdf_%s", D[k].kind == 1 ? "cpow" : D[k].name);
        tb_stab_row *r = row(s, id, D[k].name);
        r->boundary = hi;
        tb_settext(r->condition, sizeof r->condition, "m in 0.05..0.70 (steps 0.005): relative error <= 5%% where D > 1%% of its peak");
        char neg[100] = "";
        if (D[k].kind != 1) {
            /* the base 1 + (1/(2 g m^2) - 1/4)(c - 1) turns negative within
             * [0, 90] deg when the slope exceeds 1: m below sqrt(2/(g (1+1/4)))... found on the grid */
            double mneg = NAN, z;
            for (int i = 0; i < nm; i++)
                if ((z = ref_brdf_dg_base_zero_cos(mg[i], D[k].kind)) > 0 && z < 1) mneg = mg[i];
            if (!isnan(mneg)) snprintf(neg, sizeof neg, "; base < 0 before 90 deg for m <= %.3f (clamped)", mneg);
            else snprintf(neg, sizeof neg, "; base >= 0 on the grid");
        }
        if (isnan(lo)) tb_settext(r->measured, sizeof r->measured, "holds nowhere on the grid%s", neg);
        else tb_settext(r->measured, sizeof r->measured, "holds for m in %.3f..%.3f%s", lo, hi, neg);
        tb_settext(r->verdict, sizeof r->verdict, isnan(lo) ? "use another form" : "outside this range the error passes 5%%");
        if (c) {
            int se = chart_series(c, D[k].name, CHART_LINE);
            for (int i = 0; i < nm; i += 1) chart_point(c, se, mg[i], tb_stab_brdf_err(D[k].kind, mg[i], 0.01));
        }
    }
    if (c) {
        chart_hline(c, 0.05, "5%");
        double m16 = NAN;
        for (int i = 0; i < nm; i++) {
            double z = ref_brdf_dg_base_zero_cos(mg[i], 16);
            if (z > 0 && z < 1) m16 = mg[i];
        }
        if (!isnan(m16)) chart_hband(c, 0, m16, "D16 base < 0");
        keep_chart(s, c, "stability_brdf_d.svg");
    }
    /* Ward's 16th power, the paper's 1.3% where exp > 0.1 */
    double lo, hi;
    holds_range(2, mg, nm, 0.1, 0.013, &lo, &hi);
    tb_stab_row *r = row(s, "brdf_ward", "Ward 16th power");
    r->boundary = hi;
    tb_settext(r->condition, sizeof r->condition, "alpha in 0.05..0.70: relative error <= 1.3%% where exp(-tan^2/a^2) > 0.1");
    if (isnan(lo)) tb_settext(r->measured, sizeof r->measured, "holds nowhere on the grid");
    else tb_settext(r->measured, sizeof r->measured, "holds for alpha in %.3f..%.3f (error %.3g%% at 0.2, %.3g%% at 0.4)", lo, hi,
             100 * tb_stab_brdf_err(2, 0.2, 0.1), 100 * tb_stab_brdf_err(2, 0.4, 0.1));
    tb_settext(r->verdict, sizeof r->verdict, "the 1.3%% claim is a narrow band of alpha, not a general bound");
    /* Schlick forms against Blinn's cos^n, n = 2..1000 */
    int ng = 0;
    double nn[64];
    for (int n = 2; n <= 16; n++) nn[ng++] = n;                        /* n = 2..16, then 25% steps */
    for (double n = 20; n <= 1000 && ng < 64; n *= 1.25) nn[ng++] = round(n);
    chart *cs = charts ? chart_new("Schlick forms against Blinn's cos^n (where cos^n > 0.3)",
                                         "specular exponent n", "max |relative error|") : NULL;
    if (cs) { chart_log_x(cs, 1); chart_log_y(cs, 1); }
    for (int kind = 3; kind <= 5; kind += 2) {
        holds_range(kind, nn, ng, 0.3, 0.10, &lo, &hi);
        tb_stab_row *q = row(s, kind == 3 ? "brdf_schlick" : "brdf_mschlick", kind == 3 ? "Schlick" : "modified Schlick");
        q->boundary = isnan(lo) ? NAN : lo;
        tb_settext(q->condition, sizeof q->condition,
            "n in 2..1000: relative error <= 10%% where cos^n > 0.3 (the highlight's epicentre level)");
        if (isnan(lo)) tb_settext(q->measured, sizeof q->measured, "holds for no n (%.3g at n=2, %.3g at n=%.0f)",
                           tb_stab_brdf_err(kind, 2, 0.3), tb_stab_brdf_err(kind, nn[ng - 1], 0.3), nn[ng - 1]);
        else tb_settext(q->measured, sizeof q->measured, "holds for n in %.0f..%.0f (%.3g at n=2, %.3g at n=%.0f)", lo, hi,
                 tb_stab_brdf_err(kind, 2, 0.3), tb_stab_brdf_err(kind, nn[ng - 1], 0.3), nn[ng - 1]);
        tb_settext(q->verdict, sizeof q->verdict, "compared with cos^n, the papers' reference (not Fresnel)");
        if (cs) {
            int se = chart_series(cs, kind == 3 ? "Schlick" : "modified Schlick", CHART_LINE);
            for (int i = 0; i < ng; i++) chart_point(cs, se, nn[i], tb_stab_brdf_err(kind, nn[i], 0.3));
        }
    }
    if (cs) { chart_hline(cs, 0.10, "10%"); keep_chart(s, cs, "stability_brdf_schlick.svg"); }
    return 0;
}

static int atlas_units(tb_stab *s, int charts)
{
    static const int WS[] = { 8, 12, 16, 24, 32 };
    char list[200] = "";
    double e, cl, worst = 0;
    for (size_t i = 0; i < 5; i++) {
        if (tb_stab_unit("div", WS[i], 0, &e, &cl)) return -1;
        worst = fmax(worst, e);
        size_t k = strlen(list);
        snprintf(list + k, sizeof list - k, "%sW=%d: %.2f LSB, %.0f clocks", i ? "; " : "", WS[i], e, cl);
    }
    tb_stab_row *r = row(s, "div", "div (restoring)");
    r->boundary = worst;
    tb_settext(r->condition, sizeof r->condition, "max |hw - n/d| in quotient LSBs and clocks per item, widths 8..32");
    tb_settext(r->measured, sizeof r->measured, "%s", list);
    tb_settext(r->verdict, sizeof r->verdict, "%s: one clock per quotient bit, error below one LSB at every width",
        worst < 1 ? "no failure" : "fails");
    /* pow_n against n at width 16 */
    static const int NS[] = { 2, 4, 8, 16, 32, 64, 128, 255 };
    chart *c = charts ? chart_new("Power unit pow_n at width 16: error against the exponent",
                                        "exponent n", "max |hw - x^n| (output LSBs)") : NULL;
    int se = -1;
    if (c) { chart_log_x(c, 1); chart_log_y(c, 1); se = chart_series(c, "pow_n, width 16", CHART_LINE | CHART_POINTS); }
    int nmax = -1;
    char pl[220] = "";
    for (size_t i = 0; i < sizeof NS / sizeof NS[0]; i++) {
        if (tb_stab_unit("pow_n", 16, NS[i], &e, &cl)) return -1;
        if (e <= 8) nmax = NS[i];
        size_t k = strlen(pl);
        snprintf(pl + k, sizeof pl - k, "%sn=%d: %.1f LSB %.0f clk", i ? "; " : "", NS[i], e, cl);
        if (c) chart_point(c, se, NS[i], e);
    }
    r = row(s, "pow_n", "pow_n (square and multiply)");
    r->boundary = nmax;
    tb_settext(r->condition, sizeof r->condition, "max |hw - x^n| at width 16 against n; holds while <= 8 LSB (2^-12)");
    tb_settext(r->measured, sizeof r->measured, "%s", pl);
    tb_settext(r->verdict, sizeof r->verdict, "error grows with the number of truncating multiplies (about 2 log2 n)");
    if (c) { chart_hline(c, 8, "8 LSB"); keep_chart(s, c, "stability_pow.svg"); }
    /* powg against g */
    char gl[160] = "";
    for (int g = 2; g <= 32; g *= 2) {
        if (tb_stab_unit("powg", 16, g, &e, &cl)) return -1;
        size_t k = strlen(gl);
        snprintf(gl + k, sizeof gl - k, "%sg=%d: %.1f LSB %.0f clk", g > 2 ? "; " : "", g, e, cl);
    }
    r = row(s, "powg", "powg (repeated squaring)");
    r->boundary = NAN;
    tb_settext(r->condition, sizeof r->condition, "max |hw - x^g| at width 16 against g = 2..32");
    tb_settext(r->measured, sizeof r->measured, "%s", gl);
    tb_settext(r->verdict, sizeof r->verdict, "log2 g squarings, one truncation each: the error in LSBs grows with g");
    return 0;
}

int tb_stability(tb_stab *s, int charts, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    static const struct { const char *what; int (*fn)(tb_stab *, int); } PARTS[] = {
        { "forward differencing", atlas_fwd }, { "coefficient ranges", atlas_coef },
        { "cubic overshoot", atlas_overshoot }, { "degree and curvature", atlas_degree },
        { "node sets", atlas_nodes },
        { "divide-by-3 network", atlas_div3 }, { "BRDF approximations", atlas_brdf },
        { "divider and powers", atlas_units } };
    for (size_t i = 0; i < sizeof PARTS / sizeof PARTS[0]; i++)
        if (PARTS[i].fn(s, charts)) {
            snprintf(err, errlen, "stability: the %s sweep failed (a unit did not build or run)", PARTS[i].what);
            return -1;
        }
    return 0;
}

void tb_stab_free(tb_stab *s)
{
    for (int i = 0; i < s->ncharts; i++) chart_free(s->charts[i]);
    s->ncharts = 0;
}
