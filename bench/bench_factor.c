/* bench_factor.c - a 32x32 Cook-Torrance factorization (Beckmann m = 0.3,
 * Schlick Fresnel, shadowing-masking; 24 R^2 samples, default smoothness)
 * on one core, sampling and solve included; the target is under 2 s.
 * Best of 3. Also the rank-4 SVD baseline at 32x32. */
#include "vectors/ref_factor.h"
#include <stdio.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    rf_brdf b;
    char err[200];
    if (rf_brdf_init(&b, "ct", err, sizeof err)) return 1;
    rf_opts o;
    rf_opts_default(&o);
    o.R = 32;
    double best = 1e9, best_svd = 1e9;
    int iters = 0;
    for (int rep = 0; rep < 3; rep++) {
        rf_fact f;
        double t0 = now_s();
        if (rf_factorize(rf_brdf_fn, &b, &o, &f, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        double t = now_s() - t0;
        iters = f.iters;
        rf_fact_free(&f);
        if (t < best) best = t;
        rf_svd s;
        t0 = now_s();
        if (rf_svd_fit(rf_brdf_fn, &b, 32, 4, &s, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        t = now_s() - t0;
        rf_svd_free(&s);
        if (t < best_svd) best_svd = t;
    }
    printf("factor ct 32x32: %.3f s (%d CG iterations; target < 2 s: %s)\n", best, iters, best < 2 ? "met" : "MISSED");
    printf("svd rank 4 32x32: %.3f s\n", best_svd);
    return best < 2 ? 0 : 1;
}
