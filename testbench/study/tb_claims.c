/* tb_claims.c - the claims study (tb_claims.h): the table's rows from
 * every part that measures them, the failure regions of the
 * approximations, and the charts. */
#include "testbench/study/tb_claims.h"
#include "testbench/study/tb_scene_claims.h"
#include "testbench/study/tb_factor_claims.h"
#include "vectors/ref_brdf.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define DEG (M_PI / 180.0)

/* ------------------------------------------------------------------ rows */

size_t tb_claims_table(claim_result *rows, const char **kind, int width, tb_speed_hw *hc, char *err, size_t errlen)
{
    tb_speed_hw own;
    if (!hc) hc = &own;
    size_t n = claims_compute(rows, CLAIMS_MAX);
    for (size_t i = 0; i < n; i++) kind[i] = "accuracy";
    tb_speed_hw_measure(width, hc);
    if (n + 2 <= CLAIMS_MAX) {
        size_t k = tb_speed_hw_rows(hc, &rows[n]);
        for (size_t i = 0; i < k; i++) kind[n + i] = "speed_hw";
        n += k;
    }
    if (n + TB_FACTOR_CLAIMS_ROWS <= CLAIMS_MAX) {
        char ferr[300];
        size_t k = tb_factor_claims(&rows[n], CLAIMS_MAX - n, ferr, sizeof ferr);
        if (!k) { snprintf(err, errlen, "factorization: %s", ferr); return 0; }
        for (size_t i = 0; i < k; i++) kind[n + i] = "factor";
        n += k;
    }
    if (n + TB_SCENE_CLAIMS_ROWS <= CLAIMS_MAX) {
        char serr[300];
        size_t k = tb_scene_claims(&rows[n], CLAIMS_MAX - n, TB_SCENE_CLAIMS_RES, 2, serr, sizeof serr);
        if (!k) { snprintf(err, errlen, "face scene: %s", serr); return 0; }
        for (size_t i = 0; i < k; i++) kind[n + i] = "scene";
        n += k;
    }
    return n;
}

/* ----------------------------------------------------- failure regions */

static double d16c(double c, double m) { return ref_brdf_dg_clamped(c, m, 16); }
static double d16u(double c, double m) { return ref_brdf_dg(c, m, 16); }
static double beck(double c, double m) { return ref_brdf_beckmann(c, m); }
static double wpoly(double c, double a) { return ref_brdf_ward_exp_approx_clamped(c, a); }
static double wexp(double c, double a) { return ref_brdf_ward_exp(c, a); }
static double fsh(double c, double n) { return ref_brdf_schlick(c, n); }
static double fmsh(double c, double n) { return ref_brdf_mschlick(c, n); }
static double blinn(double c, double n) { return ref_brdf_cos_pow(c, n); }

#define N_ANG 1800             /* 0.05 deg steps over [0, 90] */

static double ang_at(int i) { return 90.0 * i / N_ANG; }

static int failing(const tb_claims_approx *a, int i)
{
    double c = cos(ang_at(i) * DEG), e = a->exact(c, a->p);
    return e > TB_CLAIMS_FAIL_FLOOR * a->peak && fabs(a->f(c, a->p) / e - 1) > TB_CLAIMS_FAIL_REL;
}

void tb_claims_failure_bands(const tb_claims_approx *a, tb_claims_bands *b)
{
    memset(b, 0, sizeof *b);
    int start = -1;
    for (int i = 0; i <= N_ANG + 1; i++) {
        int fl = i <= N_ANG && failing(a, i);
        if (i <= N_ANG) {
            double c = cos(ang_at(i) * DEG), e = a->exact(c, a->p);
            if (e > TB_CLAIMS_FAIL_FLOOR * a->peak) b->worst = fmax(b->worst, fabs(a->f(c, a->p) / e - 1));
        }
        if (fl && start < 0) start = i;
        if (!fl && start >= 0) {
            if (b->n < TB_CLAIMS_MAX_BANDS) {
                b->lo[b->n] = ang_at(start);
                b->hi[b->n] = ang_at(i - 1);
                b->n++;
            }
            start = -1;
        }
    }
}

const tb_claims_approx tb_claims_approx_tab[TB_CLAIMS_NAPPROX] = {
    { "D16", "m", 0.2, d16c, beck, 1 / (4 * 0.04) },
    { "D16", "m", 0.3, d16c, beck, 1 / (4 * 0.09) },
    { "D16", "m", 0.4, d16c, beck, 1 / (4 * 0.16) },
    { "D16", "m", 0.6, d16c, beck, 1 / (4 * 0.36) },
    { "Ward poly16", "a", 0.1, wpoly, wexp, 1 },
    { "Ward poly16", "a", 0.2, wpoly, wexp, 1 },
    { "Ward poly16", "a", 0.3, wpoly, wexp, 1 },
    { "Ward poly16", "a", 0.4, wpoly, wexp, 1 },
    { "F_SH", "n", 60, fsh, blinn, 1 },
    { "F_MSH", "n", 60, fmsh, blinn, 1 },
    { "F_SH", "n", 500, fsh, blinn, 1 },
    { "F_MSH", "n", 500, fmsh, blinn, 1 },
};

/* --------------------------------------------------------------- charts */

/* |relative error| in percent against angle, where the exact value is
 * above 0.1% of its peak; failure bands shaded. first..last index
 * tb_claims_approx_tab. */
static chart *error_chart(const char *title, size_t first, size_t last)
{
    chart *c = chart_new(title, "angle between N and H (deg)", "|relative error| (%)");
    if (!c) return NULL;
    chart_log_y(c, 1);
    for (size_t k = first; k <= last; k++) {
        const tb_claims_approx *a = &tb_claims_approx_tab[k];
        char label[64];
        snprintf(label, sizeof label, "%s, %s = %g", a->name, a->pname, a->p);
        int s = chart_series(c, label, CHART_LINE);
        for (int i = 0; i <= N_ANG; i += 4) {
            double cc = cos(ang_at(i) * DEG), e = a->exact(cc, a->p);
            if (e > 1e-3 * a->peak) chart_point(c, s, ang_at(i), 100 * fabs(a->f(cc, a->p) / e - 1));
        }
        tb_claims_bands b;
        tb_claims_failure_bands(a, &b);
        for (int j = 0; j < b.n; j++) {
            snprintf(label, sizeof label, "%s=%g fails", a->pname, a->p);
            chart_hband(c, b.lo[j], b.hi[j], label);
        }
    }
    chart_hline(c, 100 * TB_CLAIMS_FAIL_REL, "10%");
    return c;
}

static chart *d16_chart(void) { return error_chart("D16 (clamped) against Beckmann D", 0, 3); }
static chart *ward_chart(void) { return error_chart("Ward's exponential as a 16th power", 4, 7); }
static chart *schlick_chart(void) { return error_chart("Schlick and modified Schlick against Blinn cos^n", 8, 11); }

/* Why d_approx clamps: D, D16 clamped and D16 as The papers print it, as
 * fractions of D's peak, m = 0.2; past the cosine where the base turns
 * negative the printed even power rises again, to 2.3e4 x the peak. */
static chart *clamp_chart(void)
{
    const double m = 0.2, peak = 1 / (4 * m * m);
    chart *c = chart_new("D16 with and without the clamp, m = 0.2", "angle between N and H (deg)",
                               "value / peak of D");
    if (!c) return NULL;
    chart_log_y(c, 1);
    int s_d = chart_series(c, "Beckmann D", CHART_LINE);
    int s_u = chart_series(c, "D16 as printed", CHART_LINE);
    int s_c = chart_series(c, "D16 clamped (d_approx)", CHART_LINE);   /* drawn over the printed */
    /* Values below 1e-12 of the peak are left out (D reaches 1e-300), as
     * NaN so that the lines break there. */
    for (int i = 0; i <= N_ANG; i += 4) {
        double a = ang_at(i), cc = cos(a * DEG);
        double v[3] = { beck(cc, m) / peak, d16c(cc, m) / peak, d16u(cc, m) / peak };
        int s[3] = { s_d, s_c, s_u };
        for (int k = 0; k < 3; k++)
            chart_point(c, s[k], a, v[k] >= 1e-12 ? v[k] : NAN);
    }
    double c0 = ref_brdf_dg_base_zero_cos(m, 16);
    char lab[64];
    snprintf(lab, sizeof lab, "base < 0 from %.1f deg", acos(c0) / DEG);
    if (c0 > 0) chart_hband(c, acos(c0) / DEG, 90, lab);
    chart_hline(c, 1, "peak");
    return c;
}

/* Time x area against error for the specular units at several widths:
 * time per item = clocks x the unit's own clock period (its critical
 * path), since the units' clocks differ in length. */
static double phys_beckmann(double c, const unit_cfg *cfg) { return ref_brdf_beckmann(c, cfg->m); }
static double phys_ward(double c, const unit_cfg *cfg) { return ref_brdf_ward_exp(c, cfg->alpha); }
static double phys_blinn(double c, const unit_cfg *cfg) { return ref_brdf_cos_pow(c, cfg->n); }

typedef struct cost_unit { const char *unit, *label; tb_hw_phys phys; } cost_unit;
static const cost_unit COST_UNITS[] = {
    { "d_approx", "d_approx vs D, m=0.2", phys_beckmann },
    { "ward_approx", "ward_approx vs exp, a=0.2", phys_ward },
    { "pow_n", "pow_n vs cos^32", phys_blinn },
    { "schlick", "schlick vs cos^32", phys_blinn },
    { "mschlick", "mschlick vs cos^32", phys_blinn },
};
#define N_COST_UNITS (sizeof COST_UNITS / sizeof COST_UNITS[0])
static const int COST_WIDTHS[] = { 8, 12, 16, 20, 24 };
#define N_COST_WIDTHS (sizeof COST_WIDTHS / sizeof COST_WIDTHS[0])

static chart *cost_chart(void)
{
    chart *c = chart_new("Which specular model buys the most accuracy per time x area",
                         "time per item x area (ns x kGE: clocks x period x area)",
                         "max |error| / peak of the exact function");
    if (!c) return NULL;
    chart_log_x(c, 1);
    chart_log_y(c, 1);
    for (size_t k = 0; k < N_COST_UNITS; k++) {
        int s = chart_series(c, COST_UNITS[k].label, CHART_LINE | CHART_POINTS);
        for (size_t w = 0; w < N_COST_WIDTHS; w++) {
            unit_cfg cfg;
            unit_cfg_default(unit_find(COST_UNITS[k].unit), &cfg);
            cfg.width = COST_WIDTHS[w];
            double peak = !strcmp(COST_UNITS[k].unit, "d_approx") ? 1 / (4 * cfg.m * cfg.m) : 1;
            tb_hw_point pt;
            if (tb_hw_point_run(COST_UNITS[k].unit, &cfg, 0, COST_UNITS[k].phys, peak, &pt)) continue;
            char lab[16];
            snprintf(lab, sizeof lab, "width %d", COST_WIDTHS[w]);
            double at = pt.clocks * pt.period_ps / 1e3 * pt.area / 1e3;
            if (w == 0 || w == N_COST_WIDTHS - 1) chart_point_label(c, s, at, pt.max_err_peak, lab);
            else chart_point(c, s, at, pt.max_err_peak);
        }
    }
    return c;
}

const tb_claims_chart tb_claims_charts[] = {
    { "claims_d16.svg", d16_chart },
    { "claims_ward.svg", ward_chart },
    { "claims_schlick.svg", schlick_chart },
    { "claims_d16_clamp.svg", clamp_chart },
    { "claims_cost.svg", cost_chart },
    { NULL, NULL }
};
