/* tb_stability.c - the stability atlas (tb_stability.h): each method
 * driven past the point where it stops working, the boundary found by
 * running the units cycle by cycle through tb_run (the BRDF rows sample
 * their double references, whose approximation error dominates any width).
 * The rows on highlight profiles are tb_stability_prof.c's.
 * docs/stability.md gives each boundary's algebra.
 */
#include "testbench/study/tb_stability.h"
#include "testbench/study/tb_stability_int.h"
#include "testbench/tb.h"
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
    int rc = tb_stab_run(u, &cfg, &fm, &vs, &r);
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
    int rc = tb_stab_run(u, &cfg, &fm, &vs, r);
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
    int rc = tb_stab_run(u, &cfg, NULL, &vs, &r);
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
    int rc = tb_stab_run(u, &cfg, NULL, &vs, &r);
    vec_set_free(&vs);
    if (rc) return -1;
    *err_lsb = ldexp(err_ideal(&r), r.out[0].fmt.fbits);
    *clocks = r.cycles_per_item;
    tb_result_free(&r);
    return 0;
}

/* ============================================================ the atlas */

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
        tb_stab_row *r = tb_stab_row_add(s, id, m);
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
            tb_stab_keep_chart(s, e, "stability_fwd_err.svg");
        }
    }
    if (c) tb_stab_keep_chart(s, c, "stability_fwd.svg");
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
        tb_stab_row *r = tb_stab_row_add(s, id, U[k].unit);
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
    if (ch) tb_stab_keep_chart(s, ch, "stability_coef.svg");
    return 0;
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
    tb_stab_row *r = tb_stab_row_add(s, "div3_terms", "div3 (paper series)");
    r->boundary = t16;
    tb_settext(r->condition, sizeof r->condition, "terms for max |hw - x/3| <= 1 output LSB (exact), x the input in [-1, 1), widths 8..24");
    tb_settext(r->measured, sizeof r->measured, "%s terms; the paper's 3 terms at W=16: %.3g (%.0f LSB)", list, e3,
        ldexp(e3, 15));
    tb_settext(r->verdict, sizeof r->verdict,
        "each term adds 2 bits: the paper's 3 terms hold to about 7 bits only; in interp3 the error of A is "
        "amplified by up to 24");
    if (c) {
        chart_hline(c, 1, "1 LSB");
        tb_stab_keep_chart(s, c, "stability_div3.svg");
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
        tb_stab_row *r = tb_stab_row_add(s, id, D[k].name);
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
        tb_stab_keep_chart(s, c, "stability_brdf_d.svg");
    }
    /* Ward's 16th power, the paper's 1.3% where exp > 0.1 */
    double lo, hi;
    holds_range(2, mg, nm, 0.1, 0.013, &lo, &hi);
    tb_stab_row *r = tb_stab_row_add(s, "brdf_ward", "Ward 16th power");
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
        tb_stab_row *q = tb_stab_row_add(s, kind == 3 ? "brdf_schlick" : "brdf_mschlick", kind == 3 ? "Schlick" : "modified Schlick");
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
    if (cs) { chart_hline(cs, 0.10, "10%"); tb_stab_keep_chart(s, cs, "stability_brdf_schlick.svg"); }
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
    tb_stab_row *r = tb_stab_row_add(s, "div", "div (restoring)");
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
    r = tb_stab_row_add(s, "pow_n", "pow_n (square and multiply)");
    r->boundary = nmax;
    tb_settext(r->condition, sizeof r->condition, "max |hw - x^n| at width 16 against n; holds while <= 8 LSB (2^-12)");
    tb_settext(r->measured, sizeof r->measured, "%s", pl);
    tb_settext(r->verdict, sizeof r->verdict, "error grows with the number of truncating multiplies (about 2 log2 n)");
    if (c) { chart_hline(c, 8, "8 LSB"); tb_stab_keep_chart(s, c, "stability_pow.svg"); }
    /* powg against g */
    char gl[160] = "";
    for (int g = 2; g <= 32; g *= 2) {
        if (tb_stab_unit("powg", 16, g, &e, &cl)) return -1;
        size_t k = strlen(gl);
        snprintf(gl + k, sizeof gl - k, "%sg=%d: %.1f LSB %.0f clk", g > 2 ? "; " : "", g, e, cl);
    }
    r = tb_stab_row_add(s, "powg", "powg (repeated squaring)");
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
        { "cubic overshoot", tb_stab_atlas_overshoot }, { "degree and curvature", tb_stab_atlas_degree },
        { "node sets", tb_stab_atlas_nodes },
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
