/* ref_hflookup.c - the float reference of the hf_lookup unit: the maps it
 * holds in ROM (a Ward factorization, cached per resolution and
 * roughness) and their lookup; the vector model "hf_lookup". */
#include "vectors/ref_factor.h"
#include "vectors/vectors.h"
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAPS_CACHE 32
static rf_maps cache[MAPS_CACHE];
static int ncache;
static pthread_mutex_t cache_lock = PTHREAD_MUTEX_INITIALIZER;

static double normalize(double *t, int n)
{
    double mx = 0;
    for (int j = 0; j < n; j++) if (t[j] > mx) mx = t[j];
    for (int j = 0; j < n; j++) t[j] /= mx;
    return mx;
}

const rf_maps *rf_ward_maps(int R, double alpha)
{
    const rf_maps *found = NULL;
    pthread_mutex_lock(&cache_lock);
    for (int k = 0; k < ncache && !found; k++)
        if (cache[k].R == R && cache[k].alpha == alpha) found = &cache[k];
    if (!found && ncache < MAPS_CACHE) {
        rf_brdf b;
        char err[200];
        rf_opts o;
        rf_fact f;
        rf_brdf_init(&b, "ward", err, sizeof err);
        b.ax = b.ay = alpha;
        rf_opts_default(&o);
        o.R = R;
        o.samples = 12L * R * R;
        o.tol = 1e-7;
        o.refine = 0;       /* the paper's log-space solution: Gauss-Newton on the
                               values can leave a texel outside the disk far above
                               the rest, and the ROM's scale follows the largest */
        if (!rf_factorize(rf_brdf_fn, &b, &o, &f, err, sizeof err)) {
            rf_maps *m = &cache[ncache++];
            m->R = R; m->alpha = alpha;
            m->lam = f.lam; m->pi = f.pi;       /* kept for the program's life */
            f.lam = f.pi = NULL;
            rf_fact_free(&f);
            m->lam_scale = normalize(m->lam, R * R);
            m->pi_scale = normalize(m->pi, R * R);
            found = m;
        }
    }
    pthread_mutex_unlock(&cache_lock);
    return found;
}

static double look(int R, const double *tex, const double d[3])
{
    rf_tap t;
    double u = d[0] / (1 + d[2]), v = d[1] / (1 + d[2]);
    rf_bilin(R, u, v, &t);
    return rf_tap_apply(&t, tex);
}

double rf_maps_lookup(const rf_maps *m, const double d0[3], const double di[3], const double h[3])
{
    return (look(m->R, m->lam, d0) * look(m->R, m->lam, di)) * look(m->R, m->pi, h);
}

/* ------------------------------------------------------ vector model */

static const char *const in_names[9] = { "x0", "y0", "z0", "xi", "yi", "zi", "xh", "yh", "zh" };

static void hf_ports(const vec_params *p, int *n_in, char in[][16], int *n_out, char out[][16])
{
    (void)p;
    *n_in = 9;
    for (int i = 0; i < 9; i++) strcpy(in[i], in_names[i]);
    *n_out = 1;
    strcpy(out[0], "y");
}

static void hf_eval(const vec_params *p, const double *in, double *out)
{
    const rf_maps *m = rf_ward_maps(p->L, p->alpha);
    out[0] = m ? rf_maps_lookup(m, in, in + 3, in + 6) : NAN;
}

/* Pairs uniform over the hemisphere's solid angle (z >= 0.01) and a
 * quarter of them near the mirror direction (the lobe), h = norm(d0 + di). */
static int hf_gen(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    vec_rng r = { seed };
    if (!n) n = 1000;
    for (size_t k = 0; k < n; k++) {
        double row[10], *d0 = row, *di = row + 3, *h = row + 6;
        for (int side = 0; side < 2; side++) {
            double *d = side ? di : d0;
            double z = vec_rng_range(&r, 0.01, 1), ph = vec_rng_range(&r, 0, 2 * M_PI), s = sqrt(1 - z * z);
            d[0] = s * cos(ph); d[1] = s * sin(ph); d[2] = z;
        }
        if (k % 4 == 3 && d0[2] > 0.2) {     /* di near the mirror of d0 */
            di[0] = -d0[0] + vec_rng_range(&r, -0.1, 0.1);
            di[1] = -d0[1] + vec_rng_range(&r, -0.1, 0.1);
            di[2] = d0[2];
            double l = sqrt(di[0] * di[0] + di[1] * di[1] + di[2] * di[2]);
            for (int c = 0; c < 3; c++) di[c] /= l;
        }
        double l = 0;
        for (int c = 0; c < 3; c++) { h[c] = d0[c] + di[c]; l += h[c] * h[c]; }
        l = sqrt(l);
        for (int c = 0; c < 3; c++) h[c] /= l;
        hf_eval(p, row, row + 9);
        if (vec_set_push(out, row)) return -1;
    }
    return 0;
}

/* factorized BRDF: lambda(d0) pi(h) lambda(di) by parabolic-map bilinear lookups (Ward maps) */
const vec_model ref_model_hf_lookup = {
    .name = "hf_lookup",
    .ports = hf_ports, .eval = hf_eval, .gen = hf_gen,
};

