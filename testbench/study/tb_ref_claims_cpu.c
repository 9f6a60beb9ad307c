/* tb_ref_claims_cpu.c - the CPU speed claims (tb_ref_claims.h): D16 against
 * Beckmann's D and Ward's 16th-power approximation against its
 * exponential, timed as float loops on this CPU. Timing-dependent: never
 * among claims_compute's rows.
 */
#include "testbench/study/tb_ref_claims_int.h"
#include <math.h>
#include <stdio.h>
#include <time.h>

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
    claim_result *r = claims_add(&t, "d16_speed", "Nechyporuk & Romanyuk (2020), sec. III results; S. O. Romanyuk et al. (SPIE), sec. 4",
        "computing D16 instead of D = exp(-tg^2 g/m^2)/(4m^2 cos^4 g) raises its speed 4.34 times", 4.34);
    r->measured = d / d16;
    claims_text(r->measured_text, sizeof r->measured_text,
         "%.2fx on this CPU (float: D %.2f ns, D16 %.2f ns per evaluation)", r->measured, d, d16);
    r->verdict = r->measured >= r->claimed ? CLAIM_HOLDS
               : r->measured > 1.0 ? CLAIM_HOLDS_ONLY "a smaller speed-up on this CPU"
               : CLAIM_FAILS;
    claims_text(r->note, sizeof r->note,
         "timing of float loops over 1024 cosines, best of 3 runs; depends on compiler, libm and "
         "vectorization (the papers' environment is not stated)");

    r = claims_add(&t, "ward_speed", "Nechyporuk & Romanyuk (2020), sec. III results; S. O. Romanyuk et al. (SPIE), sec. 4",
        "for the Ward model, the speed gain of the approximation is more than twice", 2.0);
    r->measured = w / w16;
    claims_text(r->measured_text, sizeof r->measured_text,
         "%.2fx on this CPU (float specular term: exp %.2f ns, 16th power %.2f ns)", r->measured, w, w16);
    r->verdict = r->measured > r->claimed ? CLAIM_HOLDS
               : r->measured > 1.0 ? CLAIM_HOLDS_ONLY "a smaller speed-up on this CPU"
               : CLAIM_FAILS;
    claims_text(r->note, sizeof r->note,
         "both kernels include the common 1/sqrt((N.L)(N.V)) and constants; timing as for D16");
    return t.n < max ? t.n : max;
}
