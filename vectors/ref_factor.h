/* ref_factor.h - homomorphic factorization of a BRDF (Romanyuk, Vyatkin,
 * Voitko, Romanyuk 2020, "The method of factorizing the function of the
 * distribution of bidirectional reflection in three-dimensional scenes"),
 * in double precision: the float reference the hf_lookup unit is checked
 * against.
 *
 *   f(d0, di) ~ lambda(d0) pi(h) lambda(di),   h = norm(d0 + di)
 *
 * Each factor is an R x R texture over the hemisphere in the parabolic map
 * (u, v) = (x, y) / (1 + z); the fit takes logarithms (a sum of table
 * entries, linear) and solves the sparse least-squares problem with a
 * smoothness term by conjugate gradients on the normal equations. Plus the
 * baseline the paper compares with: a rank-K sum of separable products in
 * the half-angle / difference parameterization, by power iteration.
 *
 * Directions are in the local frame: normal z, tangent x, bitangent y.
 * Depends on libm only.
 */
#ifndef REF_FACTOR_H
#define REF_FACTOR_H
#include <stddef.h>
#include <stdint.h>
#include "vectors/vectors.h"

/* The reference model of the hf_lookup unit (ref_hflookup.c), which the
 * unit's descriptor points at. */
extern const vec_model ref_model_hf_lookup;

/* ------------------------------------------------------------ BRDFs */

enum { RF_BLINN, RF_CT, RF_WARD };
/* Cook-Torrance distributions: Beckmann (the papers' form, no 1/pi), the
 * one-function forms D_g (base clamped at 0), and the rational stand-ins
 * for cos^n: Schlick's c/(n - nc + c) and the modified Schlick. */
enum { RF_D_BECKMANN, RF_D_D4, RF_D_D8, RF_D_D16, RF_D_SCHLICK, RF_D_MSCHLICK };

typedef struct rf_brdf {
    int    kind;        /* RF_BLINN, RF_CT, RF_WARD */
    double e;           /* blinn: exponent of N.H */
    int    dist;        /* ct: RF_D_* */
    double m;           /* ct: roughness (Beckmann, D_g) */
    double n;           /* ct: exponent of the schlick/mschlick distributions */
    int    fresnel;     /* ct: 0 none, 1 Schlick's F0 + (1 - F0)(1 - V.H)^5 */
    double f0;
    int    shadow;      /* ct: 1 Cook-Torrance's G = min(1, 2 NH NV / VH, 2 NH NL / VH), 0 G = 1 */
    double ax, ay;      /* ward: roughness along the tangent and the bitangent */
    double rho;         /* ward: rho_s */
} rf_brdf;

/* Names accepted by rf_brdf_init: "blinn", "ct", "ward" (isotropic) and
 * "ward-aniso"; NULL-terminated. */
extern const char *const rf_brdf_names[];
/* Defaults of the named BRDF. 0, or -1 with a message (unknown name). */
int    rf_brdf_init(rf_brdf *b, const char *name, char *err, size_t len);
/* KEY=VALUE parameter: e, m, n, f0, ax, ay, alpha (both), rho, dist
 * (beckmann d4 d8 d16 schlick mschlick), fresnel (none schlick), shadow
 * (0 1). 0, or -1 with a message (unknown key, non-finite or out of range). */
int    rf_brdf_param(rf_brdf *b, const char *kv, char *err, size_t len);
/* One line naming the BRDF and its parameters. */
void   rf_brdf_describe(const rf_brdf *b, char *buf, size_t len);
/* f(d0, di) for unit vectors; 0 when either is at or below the horizon. */
double rf_brdf_eval(const rf_brdf *b, const double d0[3], const double di[3]);
/* The same as a callback (user = const rf_brdf *). */
double rf_brdf_fn(const double d0[3], const double di[3], void *user);

typedef double (*rf_fn)(const double d0[3], const double di[3], void *user);

/* ------------------------------------------------ the parabolic map */

/* (u, v) = (x, y) / (1 + z): the upper hemisphere onto the unit disk. */
void   rf_parab_fwd(const double d[3], double *u, double *v);
/* The inverse: z = (1 - r^2)/(1 + r^2), (x, y) = 2 (u, v)/(1 + r^2). */
void   rf_parab_inv(double u, double v, double d[3]);

/* Bilinear taps of an R x R texture over [-1, 1]^2 whose texel j has its
 * centre at -1 + (j + 1/2) 2/R: texel coordinate s = (u + 1) R/2 - 1/2,
 * clamped to [0, R - 1] (edge texels extend to the border). */
typedef struct rf_tap { int idx[4]; double w[4]; } rf_tap;
void   rf_bilin(int R, double u, double v, rf_tap *t);
/* sum w_k tex[idx_k] */
double rf_tap_apply(const rf_tap *t, const double *tex);

/* --------------------------------------------------- factorization */

typedef struct rf_opts {
    int      R;         /* texture side, 2..256 */
    long     samples;   /* pairs of directions sampled */
    double   smooth;    /* smoothness weight S >= 0 (see rf_factorize) */
    uint64_t seed;      /* sampling seed */
    int      max_iter;  /* conjugate-gradient iterations at most */
    double   tol;       /* stop when |A^T r| <= tol |A^T b| */
    double   floor;     /* samples below floor * (99th percentile of the samples) are left out */
    int      refine;    /* Gauss-Newton steps fitting the texture values themselves (0: none) */
} rf_opts;
void rf_opts_default(rf_opts *o);

typedef struct rf_fact {
    int     R;
    double *llam, *lpi;     /* log lambda, log pi: R*R texels each, row-major (v rows, u columns) */
    double *lam, *pi;       /* the texel values: exp of the logs, or the refined values (rf_opts.refine);
                               lambda's largest disk texel is 1 */
    int     iters;          /* CG iterations done */
    double  relres;         /* |A^T r| / |A^T b| at the end */
    long    used, skipped;  /* samples in the fit, samples skipped (no mirror direction, f not finite) */
    long    floored;        /* samples fitted at the floor */
    double  fmax, fref, floor; /* largest sample, 99th percentile, the floor's value */
    double  lam_min, lam_max, pi_min, pi_max;   /* over texels whose centre is in the disk */
} rf_fact;

/* Fit f(d0, di) ~ lambda(d0) pi(h) lambda(di) to fn. Rows: one per
 * sample with f > 0, log f = sum of the 12 bilinear taps of log lambda at
 * d0 and di and log pi at h; smoothness rows sqrt(w) (x_a - x_b) for every
 * pair of neighbouring texels of either map, w = S * (data rows) / (pairs),
 * so S weighs the smoothness against the data independently of the sample
 * count. Samples: half with d0 and di uniform over the parabolic disk
 * (the same count per texel), half with h and d0 uniform there and di the
 * mirror of d0 about h (the same count per texel of pi). The gauge
 * (lambda c, pi / c^2) is fixed by lambda's largest disk texel = 1.
 * 0, or -1 with a message (out of memory, no sample with f > 0). */
int  rf_factorize(rf_fn fn, void *user, const rf_opts *o, rf_fact *f, char *err, size_t len);
void rf_fact_free(rf_fact *f);
/* The hardware's evaluation: bilinear lookups of the three textures,
 * lambda(d0) * lambda(di) first (so f(a, b) == f(b, a) bit for bit). */
double rf_fact_eval(const rf_fact *f, const double d0[3], const double di[3]);
/* The fitted model itself: exp of the bilinear lookups of the logs. */
double rf_fact_eval_log(const rf_fact *f, const double d0[3], const double di[3]);
double rf_fact_fn(const double d0[3], const double di[3], void *user);
double rf_fact_log_fn(const double d0[3], const double di[3], void *user);

/* ------------------------------------------------ the SVD baseline */

/* f(d0, di) ~ sum_k u_k(h) v_k(d): h the half vector, d the difference
 * vector (di in the frame that takes h to the normal: rotate by -phi_h
 * about the normal, then by -theta_h about the bitangent), both R x R
 * parabolic tables. The R^2 x R^2 matrix of f at texel centres (0 where
 * a direction falls below the horizon) is approximated by its K largest
 * singular triplets (power iteration with deflation). R <= 48. */
typedef struct rf_svd { int R, K, k_used; double *u, *v; double *sv; } rf_svd;
int  rf_svd_fit(rf_fn fn, void *user, int R, int K, rf_svd *s, char *err, size_t len);
void rf_svd_free(rf_svd *s);
/* The rank-k_used approximation (bilinear lookups); may be negative. */
double rf_svd_eval(const rf_svd *s, const double d0[3], const double di[3]);
double rf_svd_fn(const double d0[3], const double di[3], void *user);
/* h and d of a pair (exposed for the tests). */
void rf_half_diff(const double d0[3], const double di[3], double h[3], double d[3]);

/* ---------------------------------------------------------- errors */

/* Against fn over n held-out pairs (d0, di uniform over the hemisphere's
 * solid angle, seed), weighted by cos theta_0 cos theta_i (the BRDF as an
 * image shows it; without cos theta_0 the 1/(N.L N.V) of Ward and
 * Cook-Torrance make the sums diverge at grazing); pairs where fn is below
 * floor times the set's largest f are left out of the relative figures
 * (a ratio to a value near 0 says nothing about the image) and counted in
 * n_zero; nrms counts every pair. */
typedef struct rf_err {
    long   n, n_zero;          /* pairs, pairs under the floor */
    double rel_rms;         /* sqrt(sum w ((a - f)/f)^2 / sum w) */
    double nrms;            /* sqrt(sum w (a - f)^2 / sum w f^2) */
    double rel_max;         /* max |a - f| / f */
    double max_t0, max_ti;  /* theta_0, theta_i (degrees) where rel_max is */
    double neg_share;       /* share of pairs where a < 0 */
    double recip_max;       /* max |a(d0, di) - a(di, d0)| / max(|a|) */
} rf_err;
void rf_error(rf_fn fn, void *fu, rf_fn approx, void *au, long n, uint64_t seed, double floor, rf_err *e);

/* ------------------------------- the maps of the hf_lookup unit */

/* The factorization of the isotropic Ward BRDF (roughness alpha, rho 1)
 * at R x R (12 R^2 samples, smoothness 0.3, seed 1, no refinement), each map divided by
 * its largest texel (outside the disk included) so that every ROM entry
 * is in (0, 1]: f ~ lam_scale^2 pi_scale lam(d0) pi(h) lam(di).
 * Computed once per (R, alpha) and kept (thread-safe); NULL if the
 * factorization fails. vectors/ref_hflookup.c. */
typedef struct rf_maps { int R; double alpha; double *lam, *pi; double lam_scale, pi_scale; } rf_maps;
const rf_maps *rf_ward_maps(int R, double alpha);
/* The unit's function: bilinear lookups of lam at the parabolic
 * coordinates of d0 and di and of pi at those of h (each (x, y)/(1 + z) of
 * the vector as given, not renormalized), multiplied: lam lam first. */
double rf_maps_lookup(const rf_maps *m, const double d0[3], const double di[3], const double h[3]);

/* Uniform double in [0, 1) from a splitmix64 state. */
double rf_rand(uint64_t *state);
#endif
