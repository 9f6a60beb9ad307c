/* ref_factor.c - BRDF models, parabolic maps, the log-space factorization
 * and the SVD baseline (see ref_factor.h). */
#include "base/base_out.h"
#include "vectors/ref_factor.h"
#include "vectors/ref_brdf.h"
#include "base/base_num.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

const char *const rf_brdf_names[] = { "blinn", "ct", "ward", "ward-aniso", NULL };
static const char *const dist_names[] = { "beckmann", "d4", "d8", "d16", "schlick", "mschlick", NULL };

double rf_rand(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* ------------------------------------------------------------ BRDFs */

int rf_brdf_init(rf_brdf *b, const char *name, char *err, size_t len)
{
    memset(b, 0, sizeof *b);
    b->e = 32; b->m = 0.3; b->n = 32; b->f0 = 0.05; b->fresnel = 1; b->shadow = 1;
    b->ax = b->ay = 0.3; b->rho = 1;
    b->dist = RF_D_BECKMANN;
    if (!strcmp(name, "blinn")) b->kind = RF_BLINN;
    else if (!strcmp(name, "ct")) b->kind = RF_CT;
    else if (!strcmp(name, "ward")) b->kind = RF_WARD;
    else if (!strcmp(name, "ward-aniso")) { b->kind = RF_WARD; b->ax = 0.15; b->ay = 0.5; }
    else {
        snprintf(err, len, "unknown BRDF '%s' (blinn, ct, ward, ward-aniso)", name);
        return -1;
    }
    return 0;
}

static int pick(const char *const *names, const char *v)
{
    for (int i = 0; names[i]; i++) if (!strcmp(names[i], v)) return i;
    return -1;
}

int rf_brdf_param(rf_brdf *b, const char *kv, char *err, size_t len)
{
    const char *eq = strchr(kv, '=');
    if (!eq || eq == kv || !eq[1]) { snprintf(err, len, "--param %s: expected KEY=VALUE", kv); return -1; }
    char key[32];
    size_t kl = (size_t)(eq - kv);
    if (kl >= sizeof key) kl = sizeof key - 1;
    memcpy(key, kv, kl);
    key[kl] = 0;
    const char *v = eq + 1;
    if (!strcmp(key, "dist")) {
        int i = pick(dist_names, v);
        if (i < 0) { snprintf(err, len, "--param dist=%s: expected beckmann, d4, d8, d16, schlick or mschlick", v); return -1; }
        b->dist = i;
        return 0;
    }
    if (!strcmp(key, "fresnel")) {
        static const char *const fn[] = { "none", "schlick", NULL };
        int i = pick(fn, v);
        if (i < 0) { snprintf(err, len, "--param fresnel=%s: expected none or schlick", v); return -1; }
        b->fresnel = i;
        return 0;
    }
    double x;
    if (base_num_real(v, 1, &x)) { snprintf(err, len, "--param %s: not a finite number", kv); return -1; }
    struct { const char *k; double *p; double lo, hi; } t[] = {
        { "e", &b->e, 1, 10000 }, { "m", &b->m, 0.05, 0.7 }, { "n", &b->n, 1.5, 10000 },
        { "f0", &b->f0, 0.001, 1 }, { "ax", &b->ax, 0.02, 1 }, { "ay", &b->ay, 0.02, 1 },
        { "alpha", &b->ax, 0.02, 1 }, { "rho", &b->rho, 1e-6, 1e6 },
    };
    if (!strcmp(key, "shadow")) {
        if (x != 0 && x != 1) { snprintf(err, len, "--param %s: expected 0 or 1", kv); return -1; }
        b->shadow = (int)x;
        return 0;
    }
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        if (strcmp(t[i].k, key)) continue;
        if (x < t[i].lo || x > t[i].hi) {
            snprintf(err, len, "--param %s: out of range [%g, %g]", kv, t[i].lo, t[i].hi);
            return -1;
        }
        *t[i].p = x;
        if (!strcmp(key, "alpha")) b->ay = x;
        return 0;
    }
    snprintf(err, len, "--param %s: unknown parameter (e, m, n, dist, fresnel, f0, shadow, ax, ay, alpha, rho)", kv);
    return -1;
}

void rf_brdf_describe(const rf_brdf *b, char *buf, size_t len)
{
    if (b->kind == RF_BLINN) snprintf(buf, len, "blinn e=%g", b->e);
    else if (b->kind == RF_WARD) snprintf(buf, len, "ward ax=%g ay=%g rho=%g", b->ax, b->ay, b->rho);
    else {
        char d[48];
        if (b->dist == RF_D_SCHLICK || b->dist == RF_D_MSCHLICK) snprintf(d, sizeof d, "%s n=%g", dist_names[b->dist], b->n);
        else snprintf(d, sizeof d, "%s m=%g", dist_names[b->dist], b->m);
        if (!b->fresnel) snprintf(buf, len, "ct dist=%s fresnel=none shadow=%d", d, b->shadow);
        else snprintf(buf, len, "ct dist=%s fresnel=schlick f0=%g shadow=%d", d, b->f0, b->shadow);
    }
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void norm3(double a[3])
{
    double l = sqrt(dot3(a, a));
    a[0] /= l; a[1] /= l; a[2] /= l;
}

double rf_brdf_eval(const rf_brdf *b, const double d0[3], const double di[3])
{
    double nv = d0[2], nl = di[2];
    if (nv <= 0 || nl <= 0) return 0;
    double h[3] = { d0[0] + di[0], d0[1] + di[1], d0[2] + di[2] };
    norm3(h);
    double nh = h[2], vh = dot3(d0, h);
    if (b->kind == RF_BLINN) return ref_brdf_cos_pow(nh, b->e);
    if (b->kind == RF_WARD) {
        /* Ward's anisotropic lobe: exp(-((h.t/ax)^2 + (h.s/ay)^2) / (h.n)^2). */
        double tx = h[0] / b->ax, ty = h[1] / b->ay;
        return b->rho * exp(-(tx * tx + ty * ty) / (nh * nh)) / (4 * M_PI * b->ax * b->ay * sqrt(nl * nv));
    }
    double D;
    switch (b->dist) {
    case RF_D_D4:       D = ref_brdf_dg_clamped(nh, b->m, 4); break;
    case RF_D_D8:       D = ref_brdf_dg_clamped(nh, b->m, 8); break;
    case RF_D_D16:      D = ref_brdf_dg_clamped(nh, b->m, 16); break;
    case RF_D_SCHLICK:  D = ref_brdf_schlick(nh, b->n); break;
    case RF_D_MSCHLICK: D = ref_brdf_mschlick(nh, b->n); break;
    default:            D = ref_brdf_beckmann(nh, b->m); break;
    }
    double F = 1;
    if (b->fresnel) { double k = 1 - vh; F = b->f0 + (1 - b->f0) * k * k * k * k * k; }
    double G = 1;
    if (b->shadow) {
        double g1 = 2 * nh * nv / vh, g2 = 2 * nh * nl / vh;
        G = g1 < g2 ? g1 : g2;
        if (G > 1) G = 1;
    }
    return D * F * G / (4 * nl * nv);
}

double rf_brdf_fn(const double d0[3], const double di[3], void *user)
{
    return rf_brdf_eval((const rf_brdf *)user, d0, di);
}

/* ------------------------------------------------ the parabolic map */

void rf_parab_fwd(const double d[3], double *u, double *v)
{
    *u = d[0] / (1 + d[2]);
    *v = d[1] / (1 + d[2]);
}

void rf_parab_inv(double u, double v, double d[3])
{
    double r2 = u * u + v * v;
    d[0] = 2 * u / (1 + r2);
    d[1] = 2 * v / (1 + r2);
    d[2] = (1 - r2) / (1 + r2);
}

static void axis(int R, double u, int *i0, int *i1, double *a)
{
    double s = (u + 1) * R * 0.5 - 0.5;
    if (s <= 0) { *i0 = *i1 = 0; *a = 0; return; }
    if (s >= R - 1) { *i0 = *i1 = R - 1; *a = 0; return; }
    int i = (int)s;
    *i0 = i; *i1 = i + 1; *a = s - i;
}

void rf_bilin(int R, double u, double v, rf_tap *t)
{
    int x0, x1, y0, y1;
    double a, b;
    axis(R, u, &x0, &x1, &a);
    axis(R, v, &y0, &y1, &b);
    t->idx[0] = y0 * R + x0; t->w[0] = (1 - a) * (1 - b);
    t->idx[1] = y0 * R + x1; t->w[1] = a * (1 - b);
    t->idx[2] = y1 * R + x0; t->w[2] = (1 - a) * b;
    t->idx[3] = y1 * R + x1; t->w[3] = a * b;
}

double rf_tap_apply(const rf_tap *t, const double *tex)
{
    return t->w[0] * tex[t->idx[0]] + t->w[1] * tex[t->idx[1]] + t->w[2] * tex[t->idx[2]] + t->w[3] * tex[t->idx[3]];
}

static void dir_tap(int R, const double d[3], rf_tap *t)
{
    double u, v;
    rf_parab_fwd(d, &u, &v);
    rf_bilin(R, u, v, t);
}

/* --------------------------------------------------- factorization */

static void half(const double d0[3], const double di[3], double h[3])
{
    for (int c = 0; c < 3; c++) h[c] = d0[c] + di[c];   /* a + b == b + a: symmetric */
    norm3(h);
}


void rf_opts_default(rf_opts *o)
{
    o->R = 32;
    o->samples = 0;         /* 0: 24 R^2 */
    o->smooth = 0.3;
    o->seed = 1;
    o->max_iter = 3000;
    o->tol = 1e-9;
    o->floor = 1e-4;
    o->refine = 3;
}

/* A direction uniform over the parabolic disk (the same count per texel). */
static void rand_parab(uint64_t *st, double d[3])
{
    double u, v;
    do { u = 2 * rf_rand(st) - 1; v = 2 * rf_rand(st) - 1; } while (u * u + v * v >= 1);
    rf_parab_inv(u, v, d);
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sparse rows: data rows have 12 entries, smoothness rows 2. */
typedef struct sp {
    long rows, nnz, cap;
    long *ptr;
    int *col;
    double *val, *rhs;
} sp;

static int sp_row(sp *a, const int *col, const double *val, int n, double rhs)
{
    if (a->nnz + n > a->cap) return -1;
    for (int k = 0; k < n; k++) { a->col[a->nnz] = col[k]; a->val[a->nnz] = val[k]; a->nnz++; }
    a->rhs[a->rows] = rhs;
    a->ptr[++a->rows] = a->nnz;
    return 0;
}

/* y = A x */
static void sp_mul(const sp *a, const double *x, double *y)
{
    for (long r = 0; r < a->rows; r++) {
        double s = 0;
        for (long k = a->ptr[r]; k < a->ptr[r + 1]; k++) s += a->val[k] * x[a->col[k]];
        y[r] = s;
    }
}

/* z = A^T y */
static void sp_tmul(const sp *a, const double *y, double *z, int ncol)
{
    memset(z, 0, sizeof(double) * (size_t)ncol);
    for (long r = 0; r < a->rows; r++)
        for (long k = a->ptr[r]; k < a->ptr[r + 1]; k++) z[a->col[k]] += a->val[k] * y[r];
}

static double vdot(const double *a, const double *b, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

/* CGLS: min |A x - b| from x = 0; returns iterations. */
static int cgls(const sp *a, int n, double *x, int max_iter, double tol, double *relres)
{
    double *r = malloc(sizeof(double) * (size_t)a->rows), *q = malloc(sizeof(double) * (size_t)a->rows);
    double *s = malloc(sizeof(double) * (size_t)n), *p = malloc(sizeof(double) * (size_t)n);
    if (!r || !q || !s || !p) { free(r); free(q); free(s); free(p); return -1; }
    memset(x, 0, sizeof(double) * (size_t)n);
    memcpy(r, a->rhs, sizeof(double) * (size_t)a->rows);
    sp_tmul(a, r, s, n);
    memcpy(p, s, sizeof(double) * (size_t)n);
    double g = vdot(s, s, n), g0 = g;
    int it = 0;
    while (it < max_iter && g > tol * tol * g0 && g0 > 0) {
        sp_mul(a, p, q);
        double qq = vdot(q, q, (int)a->rows);
        if (qq <= 0) break;
        double al = g / qq;
        for (int i = 0; i < n; i++) x[i] += al * p[i];
        for (long i = 0; i < a->rows; i++) r[i] -= al * q[i];
        sp_tmul(a, r, s, n);
        double g1 = vdot(s, s, n);
        double be = g1 / g;
        g = g1;
        for (int i = 0; i < n; i++) p[i] = s[i] + be * p[i];
        it++;
    }
    *relres = g0 > 0 ? sqrt(g / g0) : 0;
    free(r); free(q); free(s); free(p);
    return it;
}

/* Sum of squared residuals of the texture model at x (logs of the texel
 * values): data rows log(L(d0)) + log(L(di)) + log(P(h)) - log f, with
 * L, P bilinear in the values e^x; smoothness rows linear in x. Fills
 * res (rows) and, when jv is not NULL, the Jacobian's values. */
static double tex_resid(const sp *a, long ndata, const double *x, double *res, double *jv)
{
    double ss = 0;
    for (long r = 0; r < a->rows; r++) {
        long k0 = a->ptr[r];
        if (r < ndata) {
            double part[3] = { 0, 0, 0 };
            for (int k = 0; k < 12; k++) part[k / 4] += a->val[k0 + k] * exp(x[a->col[k0 + k]]);
            res[r] = log(part[0]) + log(part[1]) + log(part[2]) - a->rhs[r];
            if (jv) for (int k = 0; k < 12; k++) jv[k0 + k] = a->val[k0 + k] * exp(x[a->col[k0 + k]]) / part[k / 4];
        } else {
            double v = 0;
            for (long k = k0; k < a->ptr[r + 1]; k++) {
                v += a->val[k] * x[a->col[k]];
                if (jv) jv[k] = a->val[k];
            }
            res[r] = v - a->rhs[r];
        }
        ss += res[r] * res[r];
    }
    return ss;
}

/* Gauss-Newton on the texture model (what bilinear texture hardware
 * evaluates), from the log-space solution: each step solves J d = -res by
 * CGLS and halves d until the sum of squares falls. Still positive (the
 * unknowns are logs) and reciprocal (lambda is shared). -1: no memory. */
static int refine(const sp *a, long ndata, int n, double *x, int steps, int max_iter)
{
    sp j = *a;
    double *res = malloc(sizeof(double) * (size_t)a->rows), *d = malloc(sizeof(double) * (size_t)n);
    double *xt = malloc(sizeof(double) * (size_t)n);
    j.val = malloc(sizeof(double) * (size_t)a->nnz);
    j.rhs = malloc(sizeof(double) * (size_t)a->rows);
    int rc = -1;
    if (!res || !d || !xt || !j.val || !j.rhs) goto out;
    double ss = tex_resid(a, ndata, x, res, j.val);
    for (int s = 0; s < steps; s++) {
        for (long r = 0; r < a->rows; r++) j.rhs[r] = -res[r];
        double rr;
        if (cgls(&j, n, d, max_iter, 1e-6, &rr) < 0) goto out;
        double t = 1, s1 = INFINITY;
        for (int h = 0; h < 8; h++, t /= 2) {
            for (int i = 0; i < n; i++) xt[i] = x[i] + t * d[i];
            s1 = tex_resid(a, ndata, xt, res, NULL);
            if (s1 < ss) break;
        }
        if (!(s1 < ss)) break;
        memcpy(x, xt, sizeof(double) * (size_t)n);
        ss = tex_resid(a, ndata, x, res, j.val);
    }
    rc = 0;
out:
    free(res); free(d); free(xt); free(j.val); free(j.rhs);
    return rc;
}

static int in_disk(int R, int j)
{
    double u = -1 + (j % R + 0.5) * 2.0 / R, v = -1 + (j / R + 0.5) * 2.0 / R;
    return u * u + v * v < 1;
}

/* N sample pairs (d0, di) of fn into pd, 7 doubles each (d0, di, f): odd
 * ones drawn around a random half vector (the lobe's samples). Pairs below
 * the horizon or with a value that is not a finite f >= 0 are skipped
 * (f->skipped); f->fmax gets the largest value. Returns how many. */
static long sample_pairs(rf_fn fn, void *user, uint64_t seed, long N, double *pd, rf_fact *f)
{
    uint64_t st = seed;
    long np = 0;
    double fmax = 0;
    for (long s = 0; s < N; s++) {
        double *d0 = pd + 7 * np, *di = d0 + 3, h[3];
        if (s % 2 == 0) { rand_parab(&st, d0); rand_parab(&st, di); }
        else {
            int tries = 0;
            do {
                rand_parab(&st, h);
                rand_parab(&st, d0);
                double k = 2 * dot3(d0, h);
                for (int c = 0; c < 3; c++) di[c] = k * h[c] - d0[c];
            } while (di[2] <= 1e-9 && ++tries < 64);
            if (di[2] <= 1e-9) { f->skipped++; continue; }
        }
        double v = fn(d0, di, user);
        if (!(v >= 0) || !isfinite(v)) { f->skipped++; continue; }
        d0[6] = v;
        if (v > fmax) fmax = v;
        np++;
    }
    f->fmax = fmax;
    return np;
}

/* The 99th percentile of the np samples' values; -1: out of memory. */
static double percentile99(const double *pd, long np)
{
    double *q = malloc(sizeof(double) * (size_t)np);
    if (!q) return -1;
    for (long s = 0; s < np; s++) q[s] = pd[7 * s + 6];
    qsort(q, (size_t)np, sizeof *q, cmp_dbl);
    double v = q[(long)(0.99 * (double)(np - 1))];
    free(q);
    return v;
}

/* A row per sample at or above the floor: log f = log lambda(d0) +
 * log lambda(di) + log pi(h), each map's four bilinear taps. */
static void sample_rows(sp *a, const double *pd, long np, int R, rf_fact *f)
{
    int T = R * R;
    for (long s = 0; s < np; s++) {
        const double *d0 = pd + 7 * s, *di = d0 + 3;
        double v = d0[6], h[3];
        if (v < f->floor) { f->floored++; continue; }
        half(d0, di, h);
        rf_tap t0, ti, th;
        dir_tap(R, d0, &t0); dir_tap(R, di, &ti); dir_tap(R, h, &th);
        int col[12];
        double val[12];
        for (int k = 0; k < 4; k++) {
            col[k] = t0.idx[k]; val[k] = t0.w[k];
            col[4 + k] = ti.idx[k]; val[4 + k] = ti.w[k];
            col[8 + k] = T + th.idx[k]; val[8 + k] = th.w[k];
        }
        sp_row(a, col, val, 12, log(v));
        f->used++;
    }
}

/* The smoothness rows: each map's horizontal and vertical neighbours
 * equal, with weight sqrt(smooth * used / pairs). */
static void smooth_rows(sp *a, double smooth, int R, long pairs, const rf_fact *f)
{
    int T = R * R;
    double w = sqrt(smooth * (double)f->used / (double)pairs);
    for (int m = 0; m < 2; m++)
        for (int j = 0; j < T; j++) {
            int col[2] = { m * T + j, 0 };
            double val[2] = { w, -w };
            if (j % R < R - 1) { col[1] = m * T + j + 1; sp_row(a, col, val, 2, 0); }
            if (j / R < R - 1) { col[1] = m * T + j + R; sp_row(a, col, val, 2, 0); }
        }
}

/* The maps from the solution x (log lambda, log pi) and its refinement
 * xr, in the gauge where lambda's largest disk texel is 1 (lambda c,
 * pi / c^2 fit alike); the ranges over the disk. */
static void gauge(rf_fact *f, const double *x, const double *xr)
{
    int R = f->R, T = R * R;
    double mx = -INFINITY, mr = -INFINITY;
    for (int j = 0; j < T; j++) if (in_disk(R, j) && x[j] > mx) mx = x[j];
    for (int j = 0; j < T; j++) if (in_disk(R, j) && xr[j] > mr) mr = xr[j];
    f->lam_min = f->pi_min = INFINITY;
    f->lam_max = f->pi_max = -INFINITY;
    for (int j = 0; j < T; j++) {
        f->llam[j] = x[j] - mx;
        f->lpi[j] = x[T + j] + 2 * mx;
        f->lam[j] = exp(xr[j] - mr);
        f->pi[j] = exp(xr[T + j] + 2 * mr);
        if (in_disk(R, j)) {
            if (f->lam[j] < f->lam_min) f->lam_min = f->lam[j];
            if (f->lam[j] > f->lam_max) f->lam_max = f->lam[j];
            if (f->pi[j] < f->pi_min) f->pi_min = f->pi[j];
            if (f->pi[j] > f->pi_max) f->pi_max = f->pi[j];
        }
    }
}

int rf_factorize(rf_fn fn, void *user, const rf_opts *o, rf_fact *f, char *err, size_t len)
{
    memset(f, 0, sizeof *f);
    int R = o->R, T = R * R, n = 2 * T;
    long N = o->samples > 0 ? o->samples : 24L * T;
    long pairs = 2L * 2 * R * (R - 1);      /* two maps, horizontal and vertical neighbours */
    sp a = { 0 };
    a.cap = 12 * N + 2 * pairs;
    a.ptr = malloc(sizeof(long) * (size_t)(N + pairs + 1));
    a.col = malloc(sizeof(int) * (size_t)a.cap);
    a.val = malloc(sizeof(double) * (size_t)a.cap);
    a.rhs = malloc(sizeof(double) * (size_t)(N + pairs));
    double *x = malloc(sizeof(double) * (size_t)n);
    f->llam = malloc(sizeof(double) * (size_t)T); f->lpi = malloc(sizeof(double) * (size_t)T);
    f->lam = malloc(sizeof(double) * (size_t)T); f->pi = malloc(sizeof(double) * (size_t)T);
    int rc = -1;
    if (!a.ptr || !a.col || !a.val || !a.rhs || !x || !f->llam || !f->lpi || !f->lam || !f->pi)
        base_out_of_memory();
    f->R = R;
    a.ptr[0] = 0;
    /* Pairs first (their f gives the floor), then the rows. */
    double *pd = malloc(sizeof(double) * 7 * (size_t)N);
    if (!pd) base_out_of_memory();
    long np = sample_pairs(fn, user, o->seed, N, pd, f);
    if (!(f->fmax > 0)) { free(pd); snprintf(err, len, "the BRDF is 0 at every sample"); goto out; }
    /* The floor is relative to the 99th percentile, not the largest: the
     * largest is often a 1/(N.L N.V) near the horizon, orders of magnitude
     * above the lobe, and a floor against it would drop the lobe's tails. */
    f->fref = percentile99(pd, np);
    if (f->fref < 0) base_out_of_memory();
    f->floor = o->floor * f->fref;
    sample_rows(&a, pd, np, R, f);
    free(pd);
    if (!f->used) { snprintf(err, len, "the BRDF is 0 at every sample"); goto out; }
    if (o->smooth > 0) smooth_rows(&a, o->smooth, R, pairs, f);
    f->iters = cgls(&a, n, x, o->max_iter, o->tol, &f->relres);
    if (f->iters < 0) base_out_of_memory();
    double *xr = malloc(sizeof(double) * (size_t)n);
    if (!xr) base_out_of_memory();
    memcpy(xr, x, sizeof(double) * (size_t)n);
    if (o->refine > 0 && refine(&a, f->used, n, xr, o->refine, o->max_iter) < 0) base_out_of_memory();
    gauge(f, x, xr);
    free(xr);
    rc = 0;
out:
    free(a.ptr); free(a.col); free(a.val); free(a.rhs); free(x);
    if (rc) rf_fact_free(f);
    return rc;
}

void rf_fact_free(rf_fact *f)
{
    free(f->llam); free(f->lpi); free(f->lam); free(f->pi);
    f->llam = f->lpi = f->lam = f->pi = NULL;
}


double rf_fact_eval(const rf_fact *f, const double d0[3], const double di[3])
{
    if (d0[2] <= 0 || di[2] <= 0) return 0;
    double h[3];
    rf_tap t;
    half(d0, di, h);
    dir_tap(f->R, d0, &t); double l0 = rf_tap_apply(&t, f->lam);
    dir_tap(f->R, di, &t); double li = rf_tap_apply(&t, f->lam);
    dir_tap(f->R, h, &t);  double p = rf_tap_apply(&t, f->pi);
    return (l0 * li) * p;
}

double rf_fact_eval_log(const rf_fact *f, const double d0[3], const double di[3])
{
    if (d0[2] <= 0 || di[2] <= 0) return 0;
    double h[3];
    rf_tap t;
    half(d0, di, h);
    dir_tap(f->R, d0, &t); double l0 = rf_tap_apply(&t, f->llam);
    dir_tap(f->R, di, &t); double li = rf_tap_apply(&t, f->llam);
    dir_tap(f->R, h, &t);  double p = rf_tap_apply(&t, f->lpi);
    return exp((l0 + li) + p);
}

double rf_fact_fn(const double d0[3], const double di[3], void *user)
{
    return rf_fact_eval((const rf_fact *)user, d0, di);
}

double rf_fact_log_fn(const double d0[3], const double di[3], void *user)
{
    return rf_fact_eval_log((const rf_fact *)user, d0, di);
}

/* ------------------------------------------------ the SVD baseline */

/* Rotation about z by angle a, then about y by b, applied to v. */
static void rot_zy(const double v[3], double a, double b, double out[3])
{
    double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b);
    double x = ca * v[0] - sa * v[1], y = sa * v[0] + ca * v[1], z = v[2];
    out[0] = cb * x + sb * z; out[1] = y; out[2] = -sb * x + cb * z;
}

void rf_half_diff(const double d0[3], const double di[3], double h[3], double d[3])
{
    half(d0, di, h);
    double th = acos(h[2] > 1 ? 1 : h[2]), ph = atan2(h[1], h[0]);
    /* di rotated by -phi_h about z, then by -theta_h about y */
    double ca = cos(-ph), sa = sin(-ph), cb = cos(-th), sb = sin(-th);
    double x = ca * di[0] - sa * di[1], y = sa * di[0] + ca * di[1], z = di[2];
    d[0] = cb * x + sb * z; d[1] = y; d[2] = -sb * x + cb * z;
}

int rf_svd_fit(rf_fn fn, void *user, int R, int K, rf_svd *s, char *err, size_t len)
{
    memset(s, 0, sizeof *s);
    if (R < 2 || R > 48 || K < 1 || K > 16) { snprintf(err, len, "svd: resolution 2..48, rank 1..16"); return -1; }
    int T = R * R;
    double *M = malloc(sizeof(double) * (size_t)T * (size_t)T);
    s->u = calloc((size_t)K * (size_t)T, sizeof(double));
    s->v = calloc((size_t)K * (size_t)T, sizeof(double));
    s->sv = calloc((size_t)K, sizeof(double));
    double *w = malloc(sizeof(double) * (size_t)T);
    if (!M || !s->u || !s->v || !s->sv || !w) base_out_of_memory();
    s->R = R; s->K = K; s->k_used = K;
    /* M[h][d]: f at the texel centres; di from (h, d), d0 its mirror about h. */
    for (int a = 0; a < T; a++) {
        double h[3];
        rf_parab_inv(-1 + (a % R + 0.5) * 2.0 / R, -1 + (a / R + 0.5) * 2.0 / R, h);
        double th = acos(h[2]), ph = atan2(h[1], h[0]);
        for (int b = 0; b < T; b++) {
            double d[3], di[3], d0[3];
            double *m = &M[(size_t)a * T + b];
            *m = 0;
            if (!in_disk(R, a) || !in_disk(R, b)) continue;
            rf_parab_inv(-1 + (b % R + 0.5) * 2.0 / R, -1 + (b / R + 0.5) * 2.0 / R, d);
            rot_zy(d, 0, th, di);           /* about y by theta_h ... */
            double t2[3] = { di[0], di[1], di[2] };
            rot_zy(t2, ph, 0, di);          /* ... then about z by phi_h */
            double k = 2 * dot3(di, h);
            for (int c = 0; c < 3; c++) d0[c] = k * h[c] - di[c];
            if (di[2] <= 0 || d0[2] <= 0) continue;
            double v = fn(d0, di, user);
            *m = isfinite(v) ? v : 0;
        }
    }
    /* Power iteration on M M^T with deflation, fixed start, fixed count. */
    for (int k = 0; k < K; k++) {
        double *u = s->u + (size_t)k * T, *v = s->v + (size_t)k * T;
        for (int i = 0; i < T; i++) v[i] = 1.0 + 0.001 * (i % 7);
        double sig = 0;
        for (int it = 0; it < 200; it++) {
            for (int i = 0; i < T; i++) u[i] = vdot(&M[(size_t)i * T], v, T);
            double nu = sqrt(vdot(u, u, T));
            if (nu == 0) break;
            for (int i = 0; i < T; i++) u[i] /= nu;
            memset(w, 0, sizeof(double) * (size_t)T);
            for (int i = 0; i < T; i++) {
                const double *row = &M[(size_t)i * T];
                for (int j = 0; j < T; j++) w[j] += row[j] * u[i];
            }
            double nv = sqrt(vdot(w, w, T));
            if (nv == 0) break;
            double change = fabs(nv - sig) / nv;
            sig = nv;
            for (int j = 0; j < T; j++) v[j] = w[j] / nv;
            if (change < 1e-13 && it > 5) break;
        }
        s->sv[k] = sig;
        for (int j = 0; j < T; j++) v[j] *= sig;      /* u_k unit, v_k carries sigma */
        for (int i = 0; i < T; i++)
            for (int j = 0; j < T; j++) M[(size_t)i * T + j] -= u[i] * v[j];
    }
    free(M); free(w);
    return 0;
}

void rf_svd_free(rf_svd *s)
{
    free(s->u); free(s->v); free(s->sv);
    s->u = s->v = s->sv = NULL;
}

double rf_svd_eval(const rf_svd *s, const double d0[3], const double di[3])
{
    if (d0[2] <= 0 || di[2] <= 0) return 0;
    double h[3], d[3];
    rf_half_diff(d0, di, h, d);
    rf_tap th, td;
    dir_tap(s->R, h, &th);
    if (d[2] <= 0) d[2] = 0;    /* below h's horizon: the disk's rim */
    dir_tap(s->R, d, &td);
    double sum = 0;
    int T = s->R * s->R;
    for (int k = 0; k < s->k_used; k++)
        sum += rf_tap_apply(&th, s->u + (size_t)k * T) * rf_tap_apply(&td, s->v + (size_t)k * T);
    return sum;
}

double rf_svd_fn(const double d0[3], const double di[3], void *user)
{
    return rf_svd_eval((const rf_svd *)user, d0, di);
}

/* ---------------------------------------------------------- errors */

static void rand_solid(uint64_t *st, double d[3])
{
    double z = rf_rand(st), ph = 2 * M_PI * rf_rand(st), r = sqrt(1 - z * z);
    d[0] = r * cos(ph); d[1] = r * sin(ph); d[2] = z;
}

void rf_error(rf_fn fn, void *fu, rf_fn approx, void *au, long n, uint64_t seed, double floor, rf_err *e)
{
    memset(e, 0, sizeof *e);
    uint64_t st = seed;
    /* The largest f of the set first: relative figures count f >= floor * it. */
    double fmax = 0;
    for (long k = 0; k < n; k++) {
        double d0[3], di[3];
        rand_solid(&st, d0);
        rand_solid(&st, di);
        if (d0[2] < 1e-6 || di[2] < 1e-6) { k--; continue; }
        double f = fn(d0, di, fu);
        if (f > fmax) fmax = f;
    }
    double fl = floor * fmax;
    st = seed;
    double sw = 0, srel = 0, sabs = 0, sref = 0, amax = 0, rdiff = 0;
    for (long k = 0; k < n; k++) {
        double d0[3], di[3];
        rand_solid(&st, d0);
        rand_solid(&st, di);
        if (d0[2] < 1e-6 || di[2] < 1e-6) { k--; continue; }   /* never the horizon itself */
        double f = fn(d0, di, fu), a = approx(d0, di, au), b = approx(di, d0, au);
        e->n++;
        if (a < 0) e->neg_share += 1;
        if (fabs(a) > amax) amax = fabs(a);
        if (fabs(a - b) > rdiff) rdiff = fabs(a - b);
        double w = di[2] * d0[2];   /* both projected solid angles */
        sabs += w * (a - f) * (a - f);
        sref += w * f * f;
        if (!(f >= fl) || !(f > 0)) { e->n_zero++; continue; }
        double rel = (a - f) / f;
        sw += w;
        srel += w * rel * rel;
        if (fabs(rel) > e->rel_max) {
            e->rel_max = fabs(rel);
            e->max_t0 = acos(d0[2]) * 180 / M_PI;
            e->max_ti = acos(di[2]) * 180 / M_PI;
        }
    }
    e->rel_rms = sw > 0 ? sqrt(srel / sw) : 0;
    e->nrms = sref > 0 ? sqrt(sabs / sref) : 0;
    e->neg_share = e->n ? e->neg_share / e->n : 0;
    e->recip_max = amax > 0 ? rdiff / amax : 0;
}
