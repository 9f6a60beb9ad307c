/* ref_shading.h - exact (double) shading along one raster span.
 *
 * This is the "true" intensity that Nechyporuk & Romanyuk (2020) approximates with a cubic or a
 * quadratic per interval: Phong shading, i.e. the normal is interpolated
 * linearly between the span's two end normals and renormalized at every
 * pixel, then Lambert diffuse and Phong or Blinn-Phong specular are applied.
 * The golden vectors of the coefficient and interpolation units sample their
 * node intensities from these spans, so the vectors look like real data
 * (smooth falloffs, narrow highlights, clamped terminators) rather than
 * uniform noise.
 *
 * A span is parametrized by x in [0, 1] (x = 0 at the first end). All
 * vectors are in one right-handed world frame; they need not be unit length
 * (end normals and directions are normalized here).
 */
#ifndef REF_SHADING_H
#define REF_SHADING_H
#include <stddef.h>
#include "vectors/vectors.h"

typedef enum shade_model {
    SHADE_DIFFUSE,          /* kd * max(0, N.L) */
    SHADE_PHONG,            /* ks * max(0, R.V)^n, R = 2 (N.L) N - L */
    SHADE_BLINN,            /* ks * max(0, N.H)^n, H = norm(L + V) */
    SHADE_DIFFUSE_PHONG,    /* diffuse + Phong specular */
    SHADE_DIFFUSE_BLINN,    /* diffuse + Blinn specular */
    SHADE_N_MODELS
} shade_model;

/* Where a light or the viewer is: a direction (towards the light/viewer,
 * the same at every pixel) or a point (the direction depends on the pixel's
 * position on the span). */
typedef enum shade_kind { SHADE_DIRECTIONAL, SHADE_POINT } shade_kind;

typedef struct shade_span {
    const char *name;           /* for the named examples; may be NULL */
    shade_model model;
    double n0[3], n1[3];        /* normals at x = 0 and x = 1 */
    double p0[3], p1[3];        /* surface positions at x = 0 and x = 1 */
    shade_kind light_kind;
    double light[3];            /* direction to the light, or its position */
    shade_kind view_kind;
    double view[3];             /* direction to the viewer, or the eye */
    double kd, ks;              /* diffuse and specular coefficients */
    double n;                   /* specular exponent, >= 0 */
} shade_span;

/* Intensity at x in [0, 1] (x outside is clamped), in [0, 1]: the sum of
 * the components is clamped to [0, 1]. The specular term is zero where the
 * light is behind the surface (N.L <= 0), as in every practical Phong
 * shader. Degenerate geometry (interpolated normal of zero length, a point
 * light or eye on the surface) gives 0. */
double shade_span_eval(const shade_span *s, double x);

/* Named example spans, the hard cases included (see ref_shading.c). */
size_t            shade_span_count(void);
const shade_span *shade_span_at(size_t i);            /* NULL past the end */
const shade_span *shade_span_find(const char *name);  /* NULL if unknown */

/* A random but plausible span (name "random"): front-facing end normals
 * up to ~110 degrees apart, light directional or a nearby point (sometimes
 * behind the surface), any model, exponent log-uniform in [1, 512]. */
void shade_span_random(vec_rng *r, shade_span *s);

const char *shade_model_name(shade_model m);
#endif
