/* ref_shade.c - reference models of the per-pixel shading units (ref_shade.h).
 *
 * Generators: a few fixed rows (the head-on highlight, the terminator
 * N.L = 0, a normal at the domain's shortest), then random draws from a
 * stream seeded by (seed, model name): directions uniform on the sphere,
 * normals' lengths uniform in the domain kept 2^-7 inside its ends (so that
 * quantizing to as few as 10 fraction bits keeps them in it), materials
 * uniform in [0, 1]. H is drawn within 90 degrees of L, as a half vector
 * between L and any view direction is.
 */
#include "vectors/ref_shade.h"
#include "vectors/ref_brdf.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define SHADE_ROWS 256
#define SHADE_EDGE 0x1p-7

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double ref_shade_blinn(const double n[3], const double l[3], const double h[3],
                       double ka, double kd, double ks, int e)
{
    double len = sqrt(dot(n, n)), sum = ka;
    if (len > 0) {
        double u[3] = { n[0] / len, n[1] / len, n[2] / len };
        double nl = dot(u, l);
        if (nl > 0) {
            double nh = dot(u, h);
            sum += kd * nl + ks * (nh > 0 ? pow(nh, e) : 0.0);
        }
    }
    if (!(sum > 0)) return 0;
    return sum < 1 ? sum : 1;
}

int ref_shade_cook_e(double m, int g)
{
    double k = (2.0 / (m * m) - 4.0) / g;
    if (!(k > 1)) return 0;
    int e = 0;
    while (ldexp(1.0, -e) > (1.0 - 1.0 / k) / 2.0) e++;
    return e;
}

double ref_shade_cook(const double n[3], const double l[3], const double v[3], double hs,
                      double ka, double kd, double kc, double m, int g)
{
    double len = sqrt(dot(n, n)), sum = ka;
    if (len > 0) {
        double u[3] = { n[0] / len, n[1] / len, n[2] / len };
        double nl = dot(u, l), nv = dot(u, v);
        if (nl > 0) {
            sum += kd * nl;
            if (nv > 0) {
                double nh = (nl + nv) * hs, d = ref_brdf_dg_clamped(nh, m, g);
                double a = fmax(fmin(nl, nv), 0.25), b = fmax(fmax(nl, nv), ldexp(1.0, -ref_shade_cook_e(m, g)));
                sum += kc * d * fmin(1.0 / a, 4.0 * hs * nh) / b;
            }
        }
    }
    if (!(sum > 0)) return 0;
    return sum < 1 ? sum : 1;
}

/* ---- ports ---- */

static void names(char dst[][16], int *n, const char *list)
{
    char buf[200];
    snprintf(buf, sizeof buf, "%s", list);
    *n = 0;
    for (char *t = strtok(buf, " "); t; t = strtok(NULL, " ")) snprintf(dst[(*n)++], 16, "%s", t);
}
#define PORTS(fn, INS, OUTS) \
    static void fn(const vec_params *p, int *n_in, char in[][16], int *n_out, char out[][16]) \
    { (void)p; names(in, n_in, INS); names(out, n_out, OUTS); }
PORTS(ports_sqrt, "x", "y")
PORTS(ports_dot3, "ax ay az bx by bz", "y")
PORTS(ports_norm3, "nx ny nz", "ux uy uz")
PORTS(ports_shade, "nx ny nz lx ly lz hx hy hz ka kd ks", "i")
PORTS(ports_shade_cook, "nx ny nz lx ly lz vx vy vz hs ka kd kc", "i")

/* ---- eval ---- */

static void eval_sqrt(const vec_params *p, const double *in, double *out)
{ (void)p; out[0] = sqrt(in[0]); }
static void eval_dot3(const vec_params *p, const double *in, double *out)
{ (void)p; out[0] = dot(in, in + 3); }
static void eval_norm3(const vec_params *p, const double *in, double *out)
{
    (void)p;
    double len = sqrt(dot(in, in));
    for (int k = 0; k < 3; k++) out[k] = len > 0 ? in[k] / len : 0;
}
static void eval_shade(const vec_params *p, const double *in, double *out)
{ out[0] = ref_shade_blinn(in, in + 3, in + 6, in[9], in[10], in[11], p->n); }

static void eval_shade_cook(const vec_params *p, const double *in, double *out)
{ out[0] = ref_shade_cook(in, in + 3, in + 6, in[9], in[10], in[11], in[12], p->m, p->g); }

/* ---- generation ---- */

static uint64_t name_hash(const char *s)
{
    uint64_t h = 0xcbf29ce484222325ull;
    while (*s) { h ^= (unsigned char)*s++; h *= 0x100000001b3ull; }
    return h;
}

/* A direction uniform on the sphere, times len. */
static void direction(vec_rng *r, double len, double *v)
{
    double z = vec_rng_range(r, -1, 1), a = vec_rng_range(r, 0, 2 * 3.14159265358979323846);
    double s = sqrt(1 - z * z);
    v[0] = len * s * cos(a); v[1] = len * s * sin(a); v[2] = len * z;
}
static double nlen(vec_rng *r) { return vec_rng_range(r, REF_SHADE_NMIN + SHADE_EDGE, REF_SHADE_NMAX - SHADE_EDGE); }

/* Row i's inputs: fixed rows first, then draws. */
typedef void (*row_fn)(vec_rng *r, size_t i, double *in);

static void row_sqrt(vec_rng *r, size_t i, double *in)
{
    static const double fixed[] = { 0, 1, 0.25, 0.5, 2 - 0x1p-8, 0x1p-8 };
    in[0] = i < 6 ? fixed[i] : (i & 1) ? vec_rng_range(r, 0, 2 - 0x1p-8) : vec_rng_range(r, 0.25, 1);
}
static void row_dot3(vec_rng *r, size_t i, double *in)
{
    static const double fixed[3][6] = { { 0, 0, 1, 0, 0, 1 }, { 1, 0, 0, 0, 1, 0 }, { -1, 0, 0, 1, 0, 0 } };
    if (i < 3) { memcpy(in, fixed[i], sizeof fixed[i]); return; }
    direction(r, vec_rng_unit(r), in);
    direction(r, 1, in + 3);
}
static void row_norm3(vec_rng *r, size_t i, double *in)
{
    static const double fixed[3][3] = { { 0, 0, 1 }, { 0, 0.5, 0 }, { -0.5, 0.5, 0.5 } };
    if (i < 3) { memcpy(in, fixed[i], sizeof fixed[i]); return; }
    direction(r, nlen(r), in);
}
static void row_shade(vec_rng *r, size_t i, double *in)
{
    /* head-on (the scene's default material), the terminator, a normal
     * half as long, a back face, a grazing highlight */
    static const double fixed[5][12] = {
        { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0.1, 0.7, 0.3 },
        { 1, 0, 0, 0, 0, 1, 0.6, 0, 0.8, 0.1, 0.7, 0.3 },
        { 0, 0, 0.5, 0.6, 0, 0.8, 0.316227766016838, 0, 0.948683298050514, 0.2, 0.6, 0.5 },
        { 0, 0, -1, 0, 0, 1, 0, 0, 1, 0.3, 0.7, 0.3 },
        { 0.8, 0, 0.6, 0.6, 0, 0.8, 0.707106781186548, 0, 0.707106781186548, 0, 1, 1 } };
    if (i < 5) { memcpy(in, fixed[i], sizeof fixed[i]); return; }
    direction(r, nlen(r), in);
    direction(r, 1, in + 3);
    do direction(r, 1, in + 6); while (dot(in + 3, in + 6) < 0);
    /* half the normals near H, where the highlight is */
    if (i & 1) {
        double t = vec_rng_range(r, 0, 0.3), len = sqrt(dot(in, in));
        for (int k = 0; k < 3; k++) in[k] = (1 - t) * in[6 + k] + t * in[k] / len;
        double l2 = sqrt(dot(in, in)), want = nlen(r);
        for (int k = 0; k < 3; k++) in[k] *= want / l2;
    }
    for (int k = 9; k < 12; k++) in[k] = vec_rng_unit(r);
}

static void row_shade_cook(vec_rng *r, size_t i, double *in)
{
    /* head-on (N = L = V), the terminator, a grazing view with the light
     * head-on, L.V = -1/2 (hs = 1, the domain's end) */
    static const double fixed[4][13] = {
        { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0.5, 0.05, 0.6, 0.1 },
        { 1, 0, 0, 0, 0, 1, 0, 0, 1, 0.5, 0.1, 0.7, 0.3 },
        { 0, 0, 0.75, 0, 0, 1, 0.8, 0, 0.6, 0.632455532033676, 0.1, 0.5, 0.3 },
        { 0, 0, 1, 0.866025403784439, 0, 0.5, -0.866025403784439, 0, 0.5, 1, 0, 0.5, 0.3 } };
    if (i < 4) { memcpy(in, fixed[i], sizeof fixed[i]); return; }
    direction(r, nlen(r), in);
    direction(r, 1, in + 6);
    do direction(r, 1, in + 3); while (dot(in + 3, in + 6) < -0.5);
    double h[3] = { in[3] + in[6], in[4] + in[7], in[5] + in[8] }, hl = sqrt(dot(h, h));
    in[9] = 1 / hl;
    /* half the normals near H, where the highlight is */
    if (i & 1) {
        double t = vec_rng_range(r, 0, 0.3), len = sqrt(dot(in, in));
        for (int k = 0; k < 3; k++) in[k] = (1 - t) * h[k] / hl + t * in[k] / len;
        double l2 = sqrt(dot(in, in)), want = nlen(r);
        for (int k = 0; k < 3; k++) in[k] *= want / l2;
    }
    in[10] = vec_rng_unit(r);
    in[11] = vec_rng_unit(r);
    in[12] = vec_rng_unit(r) / 3;       /* ks F / pi <= 1.024 / pi */
}

static int gen_with(const vec_model *self, row_fn row, const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    vec_set_header(out, self, p);
    if (n == 0) n = SHADE_ROWS;
    vec_rng r = { seed ^ name_hash(self->name) };
    double v[VEC_MAX_PORTS];
    for (size_t i = 0; i < n; i++) {
        row(&r, i, v);
        self->eval(p, v, v + out->n_in);
        if (vec_set_push(out, v) != 0) return -1;
    }
    return 0;
}
static int gen_sqrt(const vec_params *p, size_t n, uint64_t s, vec_set *o) { return gen_with(&ref_model_sqrt, row_sqrt, p, n, s, o); }
static int gen_dot3(const vec_params *p, size_t n, uint64_t s, vec_set *o) { return gen_with(&ref_model_dot3, row_dot3, p, n, s, o); }
static int gen_norm3(const vec_params *p, size_t n, uint64_t s, vec_set *o) { return gen_with(&ref_model_norm3, row_norm3, p, n, s, o); }
static int gen_shade(const vec_params *p, size_t n, uint64_t s, vec_set *o)
{
    if (p->n < 1) return -1;
    return gen_with(&ref_model_shade, row_shade, p, n, s, o);
}

static int gen_shade_cook(const vec_params *p, size_t n, uint64_t s, vec_set *o)
{
    if (ref_shade_cook_e(p->m, p->g) < 1) return -1;
    return gen_with(&ref_model_shade_cook, row_shade_cook, p, n, s, o);
}

/* y = sqrt(x), x in [0, 2) */
const vec_model ref_model_sqrt = { "sqrt", ports_sqrt, eval_sqrt, gen_sqrt };
/* y = a.b, |a|, |b| <= 1 */
const vec_model ref_model_dot3 = { "dot3", ports_dot3, eval_dot3, gen_dot3 };
/* u = N/|N|, |N| in [1/2, 1] */
const vec_model ref_model_norm3 = { "norm3", ports_norm3, eval_norm3, gen_norm3 };
/* one pixel's Blinn shading, one directional light of intensity 1 */
const vec_model ref_model_shade = { "shade", ports_shade, eval_shade, gen_shade };
/* one pixel's Cook-Torrance shading with D_g, one directional light of intensity 1 */
const vec_model ref_model_shade_cook = { "shade_cook", ports_shade_cook, eval_shade_cook, gen_shade_cook };
