/* claims.c - the seeds' numerical claims against the double references
 * (see claims.h). One function per claim family; each fills rows of the
 * table with the seed's statement, our measurement and a verdict that
 * follows from the numbers (nothing is hard-wired to the expected answer).
 */
#include "vectors/claims.h"
#include "vectors/ref_brdf.h"
#include "vectors/ref_seed000.h"
#include "vectors/ref_shading.h"
#include "base/base_join.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define HALF_PI (M_PI / 2)
#define RAD2DEG (180.0 / M_PI)

/* Our reading of the seeds' "high accuracy": relative error <= 5%. */
#define ACCURATE_PCT 5.0

/* ---- the table being filled ---- */

typedef struct table {
    claim_result *out;
    size_t max, n;
    claim_result spare;        /* rows beyond max are computed into this */
} table;

static claim_result *add(table *t, const char *id, const char *seed,
                         const char *claim, double claimed)
{
    claim_result *r = t->n < t->max ? &t->out[t->n] : &t->spare;
    t->n++;
    memset(r, 0, sizeof *r);
    r->id = id;
    r->seed = seed;
    r->claim = claim;
    r->claimed = claimed;
    r->measured = NAN;
    r->verdict = CLAIM_FAILS;
    return r;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void text(char *dst, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, size, fmt, ap);
    va_end(ap);
}

int claims_verdict_kind(const char *v)
{
    if (!v) return -2;
    if (!strcmp(v, CLAIM_HOLDS)) return 1;
    if (!strcmp(v, CLAIM_FAILS)) return -1;
    size_t k = strlen(CLAIM_HOLDS_ONLY);
    if (!strncmp(v, CLAIM_HOLDS_ONLY, k) && v[k]) return 0;
    return -2;
}

/* ---- numerical helpers ---- */

typedef double (*fn_cp)(double c, double p);   /* a function of cos and one parameter */

/* Angle in [0, pi/2] where a decreasing f(cos th, p) crosses level. */
static double angle_where(fn_cp f, double p, double level)
{
    double lo = 0.0, hi = HALF_PI;
    for (int i = 0; i < 100; i++) {
        double mid = 0.5 * (lo + hi);
        if (f(cos(mid), p) > level) lo = mid; else hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* max |a/r - 1| in percent over N+1 angles in [0, th_max] (ends included;
 * the bands end where the error usually peaks). */
static double max_rel_pct(fn_cp a, fn_cp r, double p, double th_max, int N)
{
    double worst = 0.0;
    for (int i = 0; i <= N; i++) {
        double c = cos(th_max * i / N), rv = r(c, p);
        if (rv > 0.0) worst = fmax(worst, fabs(a(c, p) / rv - 1.0));
    }
    return 100.0 * worst;
}

/* max |a - r| over N+1 angles in [th0, th1]. */
static double max_abs(fn_cp a, fn_cp r, double p, double th0, double th1, int N)
{
    double worst = 0.0;
    for (int i = 0; i <= N; i++) {
        double c = cos(th0 + (th1 - th0) * i / N);
        worst = fmax(worst, fabs(a(c, p) - r(c, p)));
    }
    return worst;
}

/* Maximum over [0, pi/2] of |a - r|: a grid, then golden-section search in
 * the bracket around the best grid point (the error curves are smooth and
 * have a few wide humps, which a 512-point grid separates). */
static double max_abs_refined(fn_cp a, fn_cp r, double p)
{
    enum { N = 512 };
    double best = -1.0;
    int bi = 0;
    for (int i = 0; i <= N; i++) {
        double c = cos(HALF_PI * i / N), e = fabs(a(c, p) - r(c, p));
        if (e > best) { best = e; bi = i; }
    }
    double lo = HALF_PI * (bi > 0 ? bi - 1 : 0) / N, hi = HALF_PI * (bi < N ? bi + 1 : N) / N;
    const double k = 0.6180339887498949;
    for (int it = 0; it < 60; it++) {
        double x1 = hi - k * (hi - lo), x2 = lo + k * (hi - lo);
        double e1 = fabs(a(cos(x1), p) - r(cos(x1), p));
        double e2 = fabs(a(cos(x2), p) - r(cos(x2), p));
        if (e1 > e2) hi = x2; else lo = x1;
        best = fmax(best, fmax(e1, e2));
    }
    return best;
}

/* ---- seed 000: divide by 3 ---- */

static void claim_div3(table *t)
{
    claim_result *r = add(t, "div3_network", "Nechyporuk & Romanyuk (2020), sec. IV, Fig. 7",
        "1/3 ~ 1/2 - 1/8 - 1/32 - 1/128 (shifts and three subtractors): "
        "relative error no more than 0.79%", 0.79);
    double v = 0.5 - 0.125 - 0.03125 - 0.0078125;     /* exact in binary */
    r->measured = 100.0 * (v * 3.0 - 1.0);
    text(r->measured_text, sizeof r->measured_text,
         "%.7g = 43/128, relative error +%.5f%% (always too large)", v, r->measured);
    r->verdict = r->measured <= r->claimed ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "exact: 3 x 43/128 = 129/128, so +1/128 = +0.78125%%; the series "
         "1/2 - sum 2^-(2i+1) converges to 1/3, one more term gives +0.195%%");
}

/* ---- seed 000: interpolation against Phong ---- */

/* NMSE of the float cubic (node set N1) through each interval of L pixels
 * against the exact shading of every pixel of a 64-pixel span. Float only:
 * the hardware adds its own error (`shadesim run interp3`). */
static double span_nmse(const shade_span *s, int L)
{
    enum { PIXELS = 64 };
    double se = 0, sr = 0, y[32];
    for (int j = 0; j < PIXELS / L; j++) {
        double x0 = (double)j * L / PIXELS, h = (double)L / PIXELS;
        double I[4] = { shade_span_eval(s, x0), shade_span_eval(s, x0 + h),
                        shade_span_eval(s, x0 + h / 2), shade_span_eval(s, x0 + h / 4) };
        ref_interp3(I, L, y);
        for (int k = 0; k < L; k++) {
            double e = shade_span_eval(s, x0 + h * k / L);
            se += (y[k] - e) * (y[k] - e);
            sr += e * e;
        }
    }
    return sr > 0 ? se / sr : 0;
}

static void claim_interp_nmse(table *t)
{
    claim_result *r = add(t, "interp_nmse", "Nechyporuk & Romanyuk (2020), sec. IV (conclusion)",
        "interpolating diffuse and specular intensity by polynomials of degree 2 and 3 "
        "achieves NMSE no more than 0.0001 against Phong (visually indistinguishable)", 1e-4);
    double worst = 0;
    int n = 0, bad = 0;
    char failing[200] = "";
    const char *worst_name = "";
    for (size_t i = 0; i < shade_span_count(); i++) {
        const shade_span *s = shade_span_at(i);
        double e = span_nmse(s, 8);
        n++;
        if (e > worst) { worst = e; worst_name = s->name; }
        if (e > r->claimed) {
            bad++;
            base_join_addf(failing, sizeof failing, ", ", "%s %.2g", s->name, e);
        }
    }
    r->measured = worst;
    text(r->measured_text, sizeof r->measured_text,
         "worst NMSE %.3g (%s); %d of %d spans above 1e-4", worst, worst_name, bad, n);
    r->verdict = !bad ? CLAIM_HOLDS : bad < n ? CLAIM_HOLDS_ONLY "smooth spans (no highlight narrower than a few intervals)"
                                               : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "cubic N1, 8-pixel intervals, 64-pixel spans (vectors/ref_shading.c), float; above 1e-4: %s; "
         "the hardware adds the 1/3 network's error (run interp3 --param terms=N)", bad ? failing : "none");
}

/* ---- seeds 000 III / 001 3: Beckmann D, its cos-power form and D16 ---- */

static const double ROUGHNESS[] = { 0.2, 0.3, 0.4, 0.5, 0.6 };
#define N_ROUGH (sizeof ROUGHNESS / sizeof ROUGHNESS[0])

static double d_norm(double c, double m) { return ref_brdf_beckmann(c, m) * 4.0 * m * m; }
static double d_exact(double c, double m) { return ref_brdf_beckmann(c, m); }
static double d_cpow(double c, double m) { return ref_brdf_beckmann_cpow(c, m); }
static double d_16c(double c, double m) { return ref_brdf_dg_clamped(c, m, 16); }
static double d_16u(double c, double m) { return ref_brdf_dg(c, m, 16); }

/* Relative error of approx vs D where D > frac of its peak (D is
 * decreasing on [0, 90) deg for m < 1/sqrt 2, peak 1/(4m^2) at 0). */
static double d_band_rel(fn_cp approx, double m, double frac)
{
    return max_rel_pct(approx, d_exact, m, angle_where(d_norm, m, frac), 4000);
}

static void claim_cpow(table *t)
{
    static const char *const ids[N_ROUGH] = { "cpow_m0.2", "cpow_m0.3", "cpow_m0.4", "cpow_m0.5", "cpow_m0.6" };
    for (size_t i = 0; i < N_ROUGH; i++) {
        double m = ROUGHNESS[i], peak = 1.0 / (4.0 * m * m);
        claim_result *r = add(t, ids[i], "Nechyporuk & Romanyuk (2020), sec. III, Figs. 2-3; S. O. Romanyuk et al. (SPIE), sec. 3, Figs. 1-2",
            "D ~ cos^(2/m^2-4)(g)/(4m^2) (from exp(-tg^2 g/m^2) ~ cos^(2/m^2) g): good "
            "convergence with D, high accuracy over a significant interval (m 0.2..0.6)", NAN);
        double abs_pk = 100.0 * max_abs(d_cpow, d_exact, m, 0.0, HALF_PI, 8000) / peak;
        double r50 = d_band_rel(d_cpow, m, 0.5), r10 = d_band_rel(d_cpow, m, 0.1);
        /* SPEC's "cos-power form off by 10-48% of the peak" (m >= 0.4) are
         * D16's figures; the cos-power step alone is off by less. */
        double abs16 = 100.0 * max_abs(d_16c, d_exact, m, 0.0, HALF_PI, 8000) / peak;
        r->measured = abs_pk;
        text(r->measured_text, sizeof r->measured_text,
             "m=%.1f: max |err| %.3g%% of peak (D16: %.3g%%); relative %.3g%% where D > 50%% "
             "of peak, %.3g%% where D > 10%%", m, abs_pk, abs16, r50, r10);
        r->verdict = r10 <= ACCURATE_PCT ? CLAIM_HOLDS
                   : r50 <= ACCURATE_PCT ? CLAIM_HOLDS_ONLY "the epicenter (D > 50% of peak)"
                   : CLAIM_FAILS;
        text(r->note, sizeof r->note,
             "measured: max over [0,90] deg of |cos-power - D| / D(0); criterion for "
             "'high accuracy': relative error <= %g%% where D > 10%% of peak "
             "(epicenter: D > 50%%)", ACCURATE_PCT);
    }
}

static void claim_d16(table *t)
{
    static const char *const ids[N_ROUGH] = { "d16_m0.2", "d16_m0.3", "d16_m0.4", "d16_m0.5", "d16_m0.6" };
    for (size_t i = 0; i < N_ROUGH; i++) {
        double m = ROUGHNESS[i], peak = 1.0 / (4.0 * m * m);
        claim_result *r = add(t, ids[i], "Nechyporuk & Romanyuk (2020), sec. III, Figs. 4-5; S. O. Romanyuk et al. (SPIE), sec. 3, Figs. 3-4",
            "D16 = (1/(4m^2))[(1/(8m^2) - 1/4)(cos g - 1) + 1]^16 approximates D with high "
            "accuracy both at the epicenter of the bell and in its blooming zone", NAN);
        double r1 = d_band_rel(d_16c, m, 0.01), r50 = d_band_rel(d_16c, m, 0.5);
        double abs_pk = 100.0 * max_abs(d_16c, d_exact, m, 0.0, HALF_PI, 8000) / peak;
        double c0 = ref_brdf_dg_base_zero_cos(m, 16);
        /* How far the seed's unclamped form rises again past the zero. */
        double rise = c0 > 0.0 ? max_abs(d_16u, d_exact, m, acos(c0), HALF_PI, 2000) / peak : 0.0;
        r->measured = r1;
        if (c0 > 0.0)
            text(r->measured_text, sizeof r->measured_text,
                 "m=%.1f: rel. %.3g%% where D > 1%% of peak (%.2g%% where > 50%%); max |err| "
                 "%.3g%% of peak; base < 0 beyond %.1f deg", m, r1, r50, abs_pk, acos(c0) * RAD2DEG);
        else
            text(r->measured_text, sizeof r->measured_text,
                 "m=%.1f: rel. %.3g%% where D > 1%% of peak (%.2g%% where > 50%%); max |err| "
                 "%.3g%% of peak; base > 0 on [0,90] deg", m, r1, r50, abs_pk);
        if (r1 <= ACCURATE_PCT)
            r->verdict = rise > 0.01 ? CLAIM_HOLDS_ONLY "the clamped form (base >= 0)" : CLAIM_HOLDS;
        else
            r->verdict = r50 <= ACCURATE_PCT ? CLAIM_HOLDS_ONLY "the epicenter (D > 50% of peak)"
                                             : CLAIM_FAILS;
        if (rise > 0.01)
            text(r->note, sizeof r->note,
                 "clamped D16 (hardware form) vs D; criterion: rel. error <= %g%% where D > 1%% of "
                 "peak. Unclamped as printed, the 16th power of the negative base rises again, "
                 "to %.3g x the peak at 90 deg", ACCURATE_PCT, rise);
        else
            text(r->note, sizeof r->note,
                 "clamped D16 (hardware form) vs D; criterion: rel. error <= %g%% where D > 1%% of "
                 "peak (blooming zone), or where D > 50%% (epicenter)", ACCURATE_PCT);
    }
}

/* ---- seeds 000 III / 001 3: Ward's exponential as a 16th power ---- */

static double w_exact(double c, double a) { return ref_brdf_ward_exp(c, a); }
static double w_poly(double c, double a) { return ref_brdf_ward_exp_approx_clamped(c, a); }

/* Angle where exp(-tan^2/a^2) = level, in closed form. */
static double ward_band(double a, double level) { return atan(a * sqrt(-log(level))); }

static void claim_ward(table *t)
{
    static const double A[] = { 0.1, 0.2, 0.3, 0.4, 0.5, 0.6 };
    static const char *const ids[] = { "ward_a0.1", "ward_a0.2", "ward_a0.3", "ward_a0.4",
                                       "ward_a0.5", "ward_a0.6" };
    for (size_t i = 0; i < sizeof A / sizeof A[0]; i++) {
        double a = A[i];
        claim_result *r = add(t, ids[i], "Nechyporuk & Romanyuk (2020), sec. III; S. O. Romanyuk et al. (SPIE), sec. 3",
            "the relative error of approximating exp(-tg^2 g/a^2) by "
            "((1/(8a^2))(cos g - 1) + 1)^16 does not exceed 1.3%", 1.3);
        double e5 = max_rel_pct(w_poly, w_exact, a, ward_band(a, 0.5), 4000);
        double e1 = max_rel_pct(w_poly, w_exact, a, ward_band(a, 0.1), 4000);
        double e01 = max_rel_pct(w_poly, w_exact, a, ward_band(a, 0.01), 4000);
        /* SPEC's independent check sampled whole degrees; give that too. */
        double e1deg = 0.0;
        for (int d = 0; d < 90; d++) {
            double c = cos(d / RAD2DEG), w = w_exact(c, a);
            if (w > 0.1) e1deg = fmax(e1deg, 100.0 * fabs(w_poly(c, a) / w - 1.0));
        }
        r->measured = e1;
        text(r->measured_text, sizeof r->measured_text,
             "a=%.1f: %.3g%% where exp > 0.5, %.3g%% where > 0.1, %.3g%% where > 0.01",
             a, e5, e1, e01);
        r->verdict = e01 <= r->claimed ? CLAIM_HOLDS
                   : e1 <= r->claimed ? CLAIM_HOLDS_ONLY "the bell where exp > 0.1"
                   : e5 <= r->claimed ? CLAIM_HOLDS_ONLY "the core where exp > 0.5"
                   : CLAIM_FAILS;
        text(r->note, sizeof r->note,
             "measured: max |poly/exp - 1| where exp > 0.1 (poly clamped at base 0, c < 1 - 8a^2); "
             "on whole degrees only (a coarser check), %.3g%%. a = 0.2 is a sweet spot: "
             "the two approximation steps cancel", e1deg);
    }
}

/* ---- seed 004: Schlick and modified Schlick vs Blinn ---- */

static double f_sh(double c, double n) { return ref_brdf_schlick(c, n); }
static double f_msh(double c, double n) { return ref_brdf_mschlick(c, n); }
static double f_b(double c, double n) { return ref_brdf_cos_pow(c, n); }

/* "Relative error at the epicenter" (seed 004, eq. 6, Fig. 4): F_apr vs
 * Blinn F_B = cos^n x, both with the same n (the seed compares the three
 * functions for one specular exponent n, eqs. 2, 5, 13), at the x where
 * F_B = 0.3, for n = 2..1000. With the exact abscissa cos x = 0.3^(1/n),
 * F_B = 0.3 and the maxima are 15.66% (F_MSH, at n = 2) and 51.19% (F_SH,
 * at n = 1000; its limit for large n is 1/(0.3 (1 - ln 0.3)) - 1 = 51.24%).
 * The seed's eq. 6 writes x_ep = acos(exp(-1.2/n)), rounding ln 0.3 =
 * -1.20397 to -1.2: there F_B = e^-1.2 = 0.3012 and, comparing against
 * that F_B, the maxima are 15.55% and 50.87%. Both readings are within the
 * claims; SPEC's 15.7%/51.2% is the exact reading, used for `measured`. */
typedef struct epicenter { double msh, sh; int n_msh, n_sh; } epicenter;

static epicenter epicenter_errors(int eq6)
{
    epicenter e = { 0.0, 0.0, 0, 0 };
    for (int n = 2; n <= 1000; n++) {
        double c = eq6 ? exp(-1.2 / n) : pow(0.3, 1.0 / n);
        double b = eq6 ? exp(-1.2) : 0.3;
        double em = 100.0 * fabs(f_msh(c, n) / b - 1.0), es = 100.0 * fabs(f_sh(c, n) / b - 1.0);
        if (em > e.msh) { e.msh = em; e.n_msh = n; }
        if (es > e.sh) { e.sh = es; e.n_sh = n; }
    }
    return e;
}

static void claim_epicenter(table *t)
{
    epicenter e = epicenter_errors(0), e6 = epicenter_errors(1);
    int n_under = 0;                    /* first n where F_MSH < F_B there */
    for (int n = 2; n <= 1000 && !n_under; n++)
        if (f_msh(pow(0.3, 1.0 / n), n) < 0.3) n_under = n;
    double at1000 = 100.0 * (f_msh(pow(0.3, 1e-3), 1000) / 0.3 - 1.0);

    claim_result *r = add(t, "mschlick_epicenter", "Zavalniuk et al. (2022), eq. 6, Fig. 4",
        "relative error of F_MSH vs Blinn cos^n x at the highlight epicenter (F_B = 0.3), "
        "n in [2, 1000]: no more than 16%", 16.0);
    r->measured = e.msh;
    text(r->measured_text, sizeof r->measured_text,
         "%.3g%% (at n = %d; F_MSH is below F_B from n = %d on, %+.3g%% at n = 1000)",
         e.msh, e.n_msh, n_under, at1000);
    r->verdict = e.msh <= r->claimed ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "at cos x = 0.3^(1/n) exactly; with the paper's eq. 6 abscissa acos(exp(-1.2/n)), "
         "where F_B = e^-1.2 = 0.3012: %.4g%%", e6.msh);

    r = add(t, "schlick_epicenter", "Zavalniuk et al. (2022), eq. 6, Fig. 4",
        "relative error of F_SH vs Blinn cos^n x at the highlight epicenter (F_B = 0.3), "
        "n in [2, 1000]: no more than 52%", 52.0);
    r->measured = e.sh;
    text(r->measured_text, sizeof r->measured_text,
         "%.3g%% (at n = %d; limit for large n 1/(0.3 (1 - ln 0.3)) - 1 = %.4g%%)",
         e.sh, e.n_sh, 100.0 * (1.0 / (0.3 * (1.0 - log(0.3))) - 1.0));
    r->verdict = e.sh <= r->claimed ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "at cos x = 0.3^(1/n) exactly; with the paper's eq. 6 abscissa: %.4g%%", e6.sh);
}

static void claim_abs_half(table *t)
{
    double am60 = max_abs_refined(f_msh, f_b, 60), as60 = max_abs_refined(f_sh, f_b, 60);
    double am = 0.0, as = 0.0;
    for (int n = 2; n <= 1000; n++) {
        am = fmax(am, max_abs(f_msh, f_b, n, 0.0, HALF_PI, 256));
        as = fmax(as, max_abs(f_sh, f_b, n, 0.0, HALF_PI, 256));
    }
    claim_result *r = add(t, "abs_error_half", "Zavalniuk et al. (2022), eq. 7, Figs. 3, 5",
        "the largest absolute error |F_MSH - cos^n x| is about half the largest "
        "|F_SH - cos^n x| (ratio ~0.5)", 0.5);
    r->measured = am60 / as60;
    text(r->measured_text, sizeof r->measured_text,
         "n = 60 over [0, pi/2]: %.3f vs %.3f, ratio %.3f; over n = 2..1000: %.3f vs %.3f (%.3f)",
         am60, as60, am60 / as60, am, as, am / as);
    r->verdict = r->measured <= 0.65 ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "n = 60 as in the paper's Fig. 3; F_MSH's largest error is somewhat less than half "
         "(better than claimed); 'about half' taken as ratio <= 0.65");
}

/* Max relative error (eq. 17) of F_SH and F_MSH over the interval of
 * computation; ratio sh/msh per n, q fixed. The seed stops its 0.01-rad
 * loop at gran(n); we read gran as Blinn's cut-off (eq. 14), where the
 * reference itself reaches 2^-q: with each function's own cut-off (eqs. 10,
 * 12) the relative error against a Blinn of ~1e-90 is meaningless. */
static void rel_ratio_range(double q, double *lo, double *hi, int *n_below_15,
                            double *sh_worst, double *msh_worst)
{
    *lo = INFINITY;
    *hi = 0.0;
    *n_below_15 = 1;
    *sh_worst = *msh_worst = 0.0;
    for (int n = 2; n <= 1000; n++) {
        double x = ref_brdf_cutoff_blinn(n, q);
        double es = max_rel_pct(f_sh, f_b, n, x, 128), em = max_rel_pct(f_msh, f_b, n, x, 128);
        double ratio = es / em;
        *lo = fmin(*lo, ratio);
        *hi = fmax(*hi, ratio);
        if (ratio < 1.5) *n_below_15 = n;
        *sh_worst = fmax(*sh_worst, es);
        *msh_worst = fmax(*msh_worst, em);
    }
}

static void claim_rel_ratio(table *t)
{
    double lo8, hi8, lo12, hi12, lo16, hi16, s8, m8, s, m;
    int nb8, nb;
    rel_ratio_range(8, &lo8, &hi8, &nb8, &s8, &m8);
    rel_ratio_range(12, &lo12, &hi12, &nb, &s, &m);
    rel_ratio_range(16, &lo16, &hi16, &nb, &s, &m);
    claim_result *r = add(t, "maxrel_ratio", "Zavalniuk et al. (2022), eq. 17, Figs. 8-9",
        "the maximum relative errors of F_MSH are 1.5 to 7 times smaller than those of F_SH "
        "over the sequence of n (angles up to the cut-off)", 1.5);
    r->measured = lo8;
    text(r->measured_text, sizeof r->measured_text,
         "q=8: %.3g..%.3g (min at n = 2); q=12: %.3g..%.3g; q=16: %.3g..%.3g",
         lo8, hi8, lo12, hi12, lo16, hi16);
    r->verdict = nb8 <= 1 && hi8 <= 7.0 ? CLAIM_HOLDS
               : nb8 == 2 ? CLAIM_HOLDS_ONLY "n >= 3"
               : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "n = 2..1000, angles up to Blinn's cut-off (eq. 14) for 2^-q (q not given; 8 = an "
         "8-bit output); ratio < 1.5 up to n = %d; the upper end depends on q. Both errors "
         "are large there: up to %.0f%% (F_SH) and %.0f%% (F_MSH)", nb8, s8, m8);
}

/* F(x_cut) = 2^-q for each closed form; worst relative deviation. Eq. 12
 * as printed is checked against its own rounding bound: it cancels terms of
 * size 2^q (see ref_brdf.h), so it is held to 1e-6, the others to 1e-9. */
static void claim_cutoff_forms(table *t)
{
    double worst = 0.0, worst12 = 0.0;
    for (int q = 1; q <= 16; q++)
        for (int n = 2; n <= 1000; n += (n < 20 ? 1 : 7)) {
            double th = exp2(-q);
            worst = fmax(worst, fabs(f_sh(cos(ref_brdf_cutoff_schlick(n, q)), n) / th - 1.0));
            worst = fmax(worst, fabs(f_b(cos(ref_brdf_cutoff_blinn(n, q)), n) / th - 1.0));
            worst = fmax(worst, fabs(f_msh(cos(ref_brdf_cutoff_mschlick(n, q)), n) / th - 1.0));
            worst12 = fmax(worst12, fabs(f_msh(cos(ref_brdf_cutoff_mschlick_eq12(n, q)), n) / th - 1.0));
        }
    claim_result *r = add(t, "cutoff_forms", "Zavalniuk et al. (2022), eqs. 9-14",
        "the interval of computation (F >= 2^-q) ends at x = acos(n/(2^q + n - 1)) for F_SH "
        "(eq. 10), the eq. 12 expression for F_MSH, acos(2^(-q/n)) for F_B (eq. 14)", 0.0);
    r->measured = fmax(worst, worst12);
    text(r->measured_text, sizeof r->measured_text,
         "|F(x_cut)/2^-q - 1| <= %.2g over n = 2..1000, q = 1..16 (eq. 12 evaluated as "
         "printed: %.2g, rounding)", worst, worst12);
    r->verdict = worst <= 1e-9 && worst12 <= 1e-6 ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "eqs. 9, 11, 13 are printed as 0 <= F <= 2^-q but the intervals solve F >= 2^-q. Eq. 12 "
         "is exact (the smaller root) but cancels terms of size 2^q; a conjugate form avoids it");
}

/* Spot sizes (eqs. 15-16): R = x_cut(F) / x_cut(F_B). */
static void claim_spot_ratio(table *t)
{
    double worst = 0.0, s_lo = INFINITY, s_hi = 0.0, m_lo = INFINITY, m_hi = 0.0;
    for (int q = 4; q <= 16; q += 2)
        for (int n = 2; n <= 1000; n++) {
            double b = ref_brdf_cutoff_blinn(n, q);
            double rs = ref_brdf_cutoff_schlick(n, q) / b, rm = ref_brdf_cutoff_mschlick(n, q) / b;
            worst = fmax(worst, rm / rs);
            if (q == 8) {
                s_lo = fmin(s_lo, rs); s_hi = fmax(s_hi, rs);
                m_lo = fmin(m_lo, rm); m_hi = fmax(m_hi, rm);
            }
        }
    claim_result *r = add(t, "spot_ratio", "Zavalniuk et al. (2022), eqs. 15-16, Fig. 7",
        "the blooming zone of F_MSH is computed on a shorter interval than that of F_SH "
        "(spot size ratios to Blinn: R_MSH < R_SH)", NAN);
    r->measured = worst;
    text(r->measured_text, sizeof r->measured_text,
         "max R_MSH/R_SH = %.7f (n 2..1000, q 4..16); q=8: R_SH %.3g..%.3g, R_MSH %.3g..%.3g",
         worst, s_lo, s_hi, m_lo, m_hi);
    r->verdict = worst < 1.0 ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "the ratios tend to 1 for small n and large q; for large n F_SH's spot is up to 10x "
         "Blinn's, F_MSH's up to 5x (q = 16): both still larger than Blinn's");
}

static void claim_mschlick_shape(table *t)
{
    /* Zero: bisection of F_MSH(x) on [1, 2] (it changes sign at pi/2). */
    double lo = 1.0, hi = 2.0;
    for (int i = 0; i < 200 && hi - lo > 0; i++) {
        double mid = 0.5 * (lo + hi);
        if (f_msh(cos(mid), 60) > 0.0) lo = mid; else hi = mid;
    }
    claim_result *r = add(t, "mschlick_zero", "Zavalniuk et al. (2022), after eq. 7",
        "F_MSH reaches zero at x = 1.570796, approximately pi/2", 1.570796);
    r->measured = 0.5 * (lo + hi);
    text(r->measured_text, sizeof r->measured_text,
         "root at x = %.9f (n = 60): exactly pi/2, where cos x = 0", r->measured);
    r->verdict = fabs(r->measured - r->claimed) < 1e-6 ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "the numerator 2 cos x is the only factor that vanishes; F_MSH(0) = 2/1.25^3 = 1.024 "
         "for every n, so its peak exceeds 1");

    /* Monotonic: eq. 8 as printed, checked against a central difference. */
    double dmax = -INFINITY, dev = 0.0;
    for (int n = 2; n <= 1000; n++)
        for (int i = 1; i <= 256; i++) {
            double x = HALF_PI * i / 256, s = sin(x), c = cos(x);
            double u = n - n * c + 1.25 * c;
            double d8 = -1.6 * s / (u * u) - 3.2 * c / (u * u * u) * (n * s - 1.25 * s);
            double h = 1e-6, num = (f_msh(cos(x + h), n) - f_msh(cos(x - h), n)) / (2 * h);
            dmax = fmax(dmax, d8);
            dev = fmax(dev, fabs(d8 - num));
        }
    r = add(t, "mschlick_monotone", "Zavalniuk et al. (2022), eq. 8, Fig. 6",
        "F_MSH decreases monotonically on [0, pi/2]: its derivative (eq. 8) is negative", 0.0);
    r->measured = dmax;
    text(r->measured_text, sizeof r->measured_text,
         "max of eq. 8 over x in (0, pi/2], n = 2..1000: %.3g (< 0); eq. 8 matches a numerical "
         "derivative to %.1g", dmax, dev);
    r->verdict = dmax < 0.0 ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "both terms of eq. 8 are <= 0 for n >= 1.25, since n - n cos x + 1.25 cos x >= 1.25");
}

/* Table 1: mean absolute deviation of the chosen model (no. 2) from Blinn. */
static void claim_mad(table *t)
{
    double sm = 0.0, ss = 0.0;
    long k = 0;
    for (int n = 1; n <= 1000; n++)
        for (int d = 0; d <= 90; d++, k++) {
            double c = d == 90 ? 0.0 : cos(d / RAD2DEG), b = f_b(c, n);
            sm += fabs(f_msh(c, n) - b);
            ss += fabs(f_sh(c, n) - b);
        }
    claim_result *r = add(t, "mschlick_mad", "Zavalniuk et al. (2022), Table 1, model 2",
        "mean absolute deviation of F_MSH (eq. 5, model 2) from Blinn over angles [0, 90] and "
        "n [1, 1000]: 0.0066", 0.0066);
    r->measured = sm / k;
    text(r->measured_text, sizeof r->measured_text,
         "%.5f (F_SH: %.4f) over whole degrees 0..90, n = 1..1000", sm / k, ss / k);
    r->verdict = fabs(r->measured - r->claimed) < 0.00005 ? CLAIM_HOLDS : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "the paper's fitting program (Fig. 2) sampled degrees and n on these grids; "
         "agreement to the 2 digits printed");
}

/* Table 1's other models: the general form (eq. 4)
 *   a1 cos^b1 x / (a2 (a3 n^b3 - a3 (n cos x)^b4 + a5 cos^b5 x)^b2)
 * with the coefficients (2, 1.25, 1, 1, 1.25) and each row's powers. */
static double msh_model(double c, double n, const int *b)
{
    double u = pow(n, b[2]) - pow(n * c, b[3]) + 1.25 * pow(c, b[4]);
    return 2.0 * pow(c, b[0]) / (1.25 * pow(u, b[1]));
}

static void claim_mad_models(table *t)
{
    static const struct { const char *id; int b[5]; double mad; } M[] = {
        { "mschlick_mad_model0", { 2, 2, 1, 1, 2 }, 0.0063 },
        { "mschlick_mad_model1", { 3, 2, 1, 1, 3 }, 0.0062 },
        { "mschlick_mad_model3", { 2, 2, 1, 1, 3 }, 0.0066 },
        { "mschlick_mad_model4", { 1, 2, 1, 1, 2 }, 0.0070 },
    };
    for (size_t k = 0; k < sizeof M / sizeof M[0]; k++) {
        double sm = 0.0;
        long cnt = 0;
        for (int n = 1; n <= 1000; n++)
            for (int d = 0; d <= 90; d++, cnt++) {
                double c = d == 90 ? 0.0 : cos(d / RAD2DEG);
                sm += fabs(msh_model(c, n, M[k].b) - f_b(c, n));
            }
        static const char *const seeds[] = { "Zavalniuk et al. (2022), Table 1, model 0", "Zavalniuk et al. (2022), Table 1, model 1",
                                             "Zavalniuk et al. (2022), Table 1, model 3", "Zavalniuk et al. (2022), Table 1, model 4" };
        static const char *const claims[] = {
            "model 0, 2cos^2 x / (1.25 (n - n cos x + 1.25 cos^2 x)^2): mean absolute deviation from Blinn 0.0063 (second best, 3 raisings to powers)",
            "model 1, 2cos^3 x / (1.25 (n - n cos x + 1.25 cos^3 x)^2): mean absolute deviation from Blinn 0.0062 (the most accurate, 5 raisings)",
            "model 3, 2cos^2 x / (1.25 (n - n cos x + 1.25 cos^3 x)^2): mean absolute deviation from Blinn 0.0066",
            "model 4, 2cos x / (1.25 (n - n cos x + 1.25 cos^2 x)^2): mean absolute deviation from Blinn 0.0070" };
        claim_result *r = add(t, M[k].id, seeds[k], claims[k], M[k].mad);
        r->measured = sm / cnt;
        text(r->measured_text, sizeof r->measured_text,
             "%.5f over whole degrees 0..90, n = 1..1000 (powers b1..b5 = %d %d %d %d %d)", r->measured,
             M[k].b[0], M[k].b[1], M[k].b[2], M[k].b[3], M[k].b[4]);
        r->verdict = fabs(r->measured - r->claimed) <= 0.00005 + 1e-12 ? CLAIM_HOLDS : CLAIM_FAILS;
        text(r->note, sizeof r->note,
             "same grid and metric as model 2's row; agreement to the 2 digits printed; the ranking 1 < 0 < 2 "
             "= 3 < 4 of the table is reproduced");
    }
}

/* ---- seeds 000 III / 001 3: which power g of D_g is best at each m ---- */

static void claim_dg_best(table *t)
{
    static const char *const ids[N_ROUGH] = { "dg_best_m0.2", "dg_best_m0.3", "dg_best_m0.4", "dg_best_m0.5",
                                              "dg_best_m0.6" };
    static const int G[3] = { 4, 8, 16 };
    for (size_t i = 0; i < N_ROUGH; i++) {
        double m = ROUGHNESS[i], peak = 1.0 / (4.0 * m * m), e[3];
        int best = 0;
        for (int k = 0; k < 3; k++) {
            double worst = 0;
            for (int j = 0; j <= 8000; j++) {
                double c = cos(HALF_PI * j / 8000);
                worst = fmax(worst, fabs(ref_brdf_dg_clamped(c, m, G[k]) - d_exact(c, m)));
            }
            e[k] = 100.0 * worst / peak;
            if (e[k] < e[best]) best = k;
        }
        claim_result *r = add(t, ids[i], "Nechyporuk & Romanyuk (2020), sec. III, Figs. 4-5; S. O. Romanyuk et al. (SPIE), sec. 3",
            "of D4, D8 and D16 (cos^(2/m^2-4) as a g-th power, g = 4, 8, 16), D16 is the one to compute "
            "(the papers choose g = 16 for every m)", 16);
        r->measured = G[best];
        text(r->measured_text, sizeof r->measured_text,
             "m=%.1f: max |D_g - D| / peak: D4 %.3g%%, D8 %.3g%%, D16 %.3g%%; best D%d", m, e[0], e[1], e[2], G[best]);
        r->verdict = best == 2 ? CLAIM_HOLDS : CLAIM_FAILS;
        text(r->note, sizeof r->note,
             "clamped forms (base >= 0) on [0, 90] deg; a larger g follows cos^(2/m^2-4) more closely, but that "
             "form itself departs from D as m grows, and a smaller g's error partly cancels it");
    }
}

/* ---- seed 000 IV: node set N1 against N2 ---- */

static double span_nmse_nodes(const shade_span *s, int L, const double *tn)
{
    enum { PIXELS = 64 };
    double se = 0, sr = 0;
    for (int j = 0; j < PIXELS / L; j++) {
        double x0 = (double)j * L / PIXELS, h = (double)L / PIXELS, I[4];
        for (int i = 0; i < 4; i++) I[i] = shade_span_eval(s, x0 + h * tn[i]);
        for (int k = 0; k < L; k++) {
            double tt = (double)k / L, y = 0;
            for (int i = 0; i < 4; i++) {
                double l = 1;
                for (int q = 0; q < 4; q++) if (q != i) l *= (tt - tn[q]) / (tn[i] - tn[q]);
                y += l * I[i];
            }
            double e = shade_span_eval(s, x0 + h * tt);
            se += (y - e) * (y - e);
            sr += e * e;
        }
    }
    return sr > 0 ? se / sr : 0;
}

static void claim_nodes(table *t)
{
    static const double n1[4] = { 0, 1, 0.5, 0.25 }, n2[4] = { 0, 1, 0.5, 0.75 };
    double w1 = 0, w2 = 0, g1 = 0, g2 = 0;
    int better1 = 0, n = 0;
    for (size_t i = 0; i < shade_span_count(); i++) {
        const shade_span *s = shade_span_at(i);
        double e1 = span_nmse_nodes(s, 8, n1), e2 = span_nmse_nodes(s, 8, n2);
        w1 = fmax(w1, e1);
        w2 = fmax(w2, e2);
        g1 += log(e1 + 1e-300);
        g2 += log(e2 + 1e-300);
        better1 += e1 <= e2;
        n++;
    }
    /* coefficient ranges for nodes in [0, 1]: every 0/1 pattern */
    double r1 = 0, r2 = 0;
    for (int b = 0; b < 16; b++) {
        double I[4], c1[4], c2[4];
        for (int k = 0; k < 4; k++) I[k] = (b >> k) & 1;
        ref_coef3_n1(I, c1);
        ref_coef3_n2(I, c2);
        for (int k = 0; k < 4; k++) { r1 = fmax(r1, fabs(c1[k])); r2 = fmax(r2, fabs(c2[k])); }
    }
    claim_result *r = add(t, "nodes_n1_n2", "Nechyporuk & Romanyuk (2020), sec. IV (two node sets)",
        "of the two node sets, t = 0, 1/4, 1/2, 1 (N1) and t = 0, 1/2, 3/4, 1 (N2), the first is the most "
        "appropriate", NAN);
    r->measured = w1 / w2;
    text(r->measured_text, sizeof r->measured_text,
         "worst span NMSE N1 %.3g vs N2 %.3g (geometric mean ratio %.3g); N1 as good or better on %d of %d spans; "
         "largest |coefficient| N1 %.0f, N2 %.0f", w1, w2, exp((g1 - g2) / n), better1, n, r1, r2);
    r->verdict = r1 <= r2 && better1 * 2 >= n ? CLAIM_HOLDS
               : r1 <= r2 ? CLAIM_HOLDS_ONLY "the hardware's ranges (N2 is the more accurate on most spans)"
               : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "float cubic, 8-pixel intervals, 64-pixel spans as interp_nmse; the hardware comparison: shadesim scene "
         "with cubic_nodes n1/n2, or run interp3 --param nodes=n2; shadesim stability compares both in hardware");
}

size_t claims_compute(claim_result *out, size_t max)
{
    table t = { out, max, 0, { 0 } };
    claim_div3(&t);
    claim_interp_nmse(&t);
    claim_cpow(&t);
    claim_d16(&t);
    claim_ward(&t);
    claim_epicenter(&t);
    claim_abs_half(&t);
    claim_rel_ratio(&t);
    claim_cutoff_forms(&t);
    claim_spot_ratio(&t);
    claim_mschlick_shape(&t);
    claim_mad(&t);
    claim_mad_models(&t);
    claim_dg_best(&t);
    claim_nodes(&t);
    return t.n < max ? t.n : max;
}

/* ---- CPU speed (float), for the CLI ---- */

#define CPU_N 1024
#define CPU_M 0.2f         /* m of the D kernels and alpha of the Ward kernels */

static float run_d(const float *c, const float *w, size_t n)
{
    (void)w;
    const float k = 1.0f / (4.0f * CPU_M * CPU_M), im2 = 1.0f / (CPU_M * CPU_M);
    float s = 0.0f;
    for (size_t i = 0; i < n; i++) {
        float c2 = c[i] * c[i];
        s += k * expf(-(1.0f - c2) / c2 * im2) / (c2 * c2);
    }
    return s;
}

static float run_d16(const float *c, const float *w, size_t n)
{
    (void)w;
    const float k = 1.0f / (4.0f * CPU_M * CPU_M);
    const float a = 1.0f / (8.0f * CPU_M * CPU_M) - 0.25f;
    float s = 0.0f;
    for (size_t i = 0; i < n; i++) {
        float b = a * (c[i] - 1.0f) + 1.0f;
        b = b > 0.0f ? b : 0.0f;
        b *= b; b *= b; b *= b; b *= b;
        s += k * b;
    }
    return s;
}

/* Ward's specular term; w[i] stands for (N.L)(N.V). */
static float run_ward(const float *c, const float *w, size_t n)
{
    const float k = 1.0f / (4.0f * 3.14159265f * CPU_M * CPU_M), ia2 = 1.0f / (CPU_M * CPU_M);
    float s = 0.0f;
    for (size_t i = 0; i < n; i++) {
        float c2 = c[i] * c[i];
        s += k * expf(-(1.0f - c2) / c2 * ia2) / sqrtf(w[i]);
    }
    return s;
}

static float run_ward16(const float *c, const float *w, size_t n)
{
    const float k = 1.0f / (4.0f * 3.14159265f * CPU_M * CPU_M);
    const float a = 1.0f / (8.0f * CPU_M * CPU_M);
    float s = 0.0f;
    for (size_t i = 0; i < n; i++) {
        float b = a * (c[i] - 1.0f) + 1.0f;
        b = b > 0.0f ? b : 0.0f;
        b *= b; b *= b; b *= b; b *= b;
        s += k * b / sqrtf(w[i]);
    }
    return s;
}

static float (*const RUNNERS[CLAIMS_CPU_COUNT])(const float *, const float *, size_t) = {
    run_d, run_d16, run_ward, run_ward16
};
static const char *const KERNEL_NAMES[CLAIMS_CPU_COUNT] = {
    "beckmann_d", "d16", "ward", "ward_poly16"
};

const char *claims_kernel_name(claims_kernel k)
{
    return (unsigned)k < CLAIMS_CPU_COUNT ? KERNEL_NAMES[k] : "?";
}

static double seconds_now(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double claims_cpu_ns(claims_kernel k, double min_seconds)
{
    if ((unsigned)k >= CLAIMS_CPU_COUNT) return -1.0;
    float c[CPU_N], w[CPU_N];
    for (int i = 0; i < CPU_N; i++) {           /* highlight angles 0..60 deg */
        c[i] = (float)cos((M_PI / 3) * i / CPU_N);
        w[i] = 0.25f + 0.75f * (float)i / CPU_N;
    }
    volatile float sink = 0.0f;                 /* keeps the work observable */
    double best = INFINITY;
    for (int run = 0; run < 3; run++) {
        size_t passes = 0;
        double t0 = seconds_now(), el;
        do {
            for (int j = 0; j < 16; j++, passes++) sink = sink + RUNNERS[k](c, w, CPU_N);
            el = seconds_now() - t0;
        } while (el < min_seconds);
        best = fmin(best, 1e9 * el / ((double)passes * CPU_N));
    }
    return best;
}

size_t claims_speed(claim_result *out, size_t max, double min_seconds)
{
    table t = { out, max, 0, { 0 } };
    double d = claims_cpu_ns(CLAIMS_CPU_D, min_seconds), d16 = claims_cpu_ns(CLAIMS_CPU_D16, min_seconds);
    double w = claims_cpu_ns(CLAIMS_CPU_WARD, min_seconds), w16 = claims_cpu_ns(CLAIMS_CPU_WARD16, min_seconds);
    claim_result *r = add(&t, "d16_speed", "Nechyporuk & Romanyuk (2020), sec. III results; S. O. Romanyuk et al. (SPIE), sec. 4",
        "computing D16 instead of D = exp(-tg^2 g/m^2)/(4m^2 cos^4 g) raises its speed 4.34 times", 4.34);
    r->measured = d / d16;
    text(r->measured_text, sizeof r->measured_text,
         "%.2fx on this CPU (float: D %.2f ns, D16 %.2f ns per evaluation)", r->measured, d, d16);
    r->verdict = r->measured >= r->claimed ? CLAIM_HOLDS
               : r->measured > 1.0 ? CLAIM_HOLDS_ONLY "a smaller speed-up on this CPU"
               : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "timing of float loops over 1024 cosines, best of 3 runs; depends on compiler, libm and "
         "vectorization (the papers' environment is not stated)");

    r = add(&t, "ward_speed", "Nechyporuk & Romanyuk (2020), sec. III results; S. O. Romanyuk et al. (SPIE), sec. 4",
        "for the Ward model, the speed gain of the approximation is more than twice", 2.0);
    r->measured = w / w16;
    text(r->measured_text, sizeof r->measured_text,
         "%.2fx on this CPU (float specular term: exp %.2f ns, 16th power %.2f ns)", r->measured, w, w16);
    r->verdict = r->measured > r->claimed ? CLAIM_HOLDS
               : r->measured > 1.0 ? CLAIM_HOLDS_ONLY "a smaller speed-up on this CPU"
               : CLAIM_FAILS;
    text(r->note, sizeof r->note,
         "both kernels include the common 1/sqrt((N.L)(N.V)) and constants; timing as for D16");
    return t.n < max ? t.n : max;
}
