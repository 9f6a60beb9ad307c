/* tb_ref_claims_rows.c - what the claim families (tb_ref_claims.c, tb_ref_claims_schlick.c,
 * tb_ref_claims_cpu.c) share: the table's rows and the numerical helpers that
 * measure a claim against the double references. A leaf, so that the
 * families call it and not each other's files. */
#include "testbench/study/tb_ref_claims_int.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

claim_result *claims_add(table *t, const char *id, const char *seed, const char *claim, double claimed)
{
    claim_result *r = t->n < t->max ? &t->out[t->n] : &t->spare;
    t->n++;
    memset(r, 0, sizeof *r);
    r->id = id;
    r->source = seed;
    r->claim = claim;
    r->claimed = claimed;
    r->measured = NAN;
    r->verdict = CLAIM_FAILS;
    return r;
}

void claims_text(char *dst, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, size, fmt, ap);
    va_end(ap);
}

/* ---- numerical helpers ---- */

/* Angle in [0, pi/2] where a decreasing f(cos th, p) crosses level. */
double claims_angle_where(fn_cp f, double p, double level)
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
double claims_max_rel_pct(fn_cp a, fn_cp r, double p, double th_max, int N)
{
    double worst = 0.0;
    for (int i = 0; i <= N; i++) {
        double c = cos(th_max * i / N), rv = r(c, p);
        if (rv > 0.0) worst = fmax(worst, fabs(a(c, p) / rv - 1.0));
    }
    return 100.0 * worst;
}

/* max |a - r| over N+1 angles in [th0, th1]. */
double claims_max_abs(fn_cp a, fn_cp r, double p, double th0, double th1, int N)
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
double claims_max_abs_refined(fn_cp a, fn_cp r, double p)
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
