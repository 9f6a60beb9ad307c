/* ref_shading.c - exact Phong-shaded intensity along a span, and the named
 * example spans (the hard cases for cubic/quadratic interpolation). */
#include "vectors/ref_shading.h"
#include <math.h>
#include <string.h>

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Normalize v into out; 0, or -1 (out zeroed) when v has no direction. */
static int unit3(const double v[3], double out[3])
{
    double len = sqrt(dot3(v, v));
    if (!(len > 1e-300) || !isfinite(len)) {
        out[0] = out[1] = out[2] = 0;
        return -1;
    }
    for (int i = 0; i < 3; i++) out[i] = v[i] / len;
    return 0;
}

/* Unit direction from the surface point p towards a light or the viewer. */
static int toward(shade_kind kind, const double q[3], const double p[3], double out[3])
{
    if (kind == SHADE_DIRECTIONAL) return unit3(q, out);
    double d[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
    return unit3(d, out);
}

double shade_span_eval(const shade_span *s, double x)
{
    if (!(x >= 0)) x = 0;               /* also catches NaN */
    if (x > 1) x = 1;
    /* Phong shading: the vertex normals are unit vectors; the per-pixel
     * normal is their linear interpolation, renormalized. */
    double e0[3], e1[3], nx[3], N[3], p[3], L[3], V[3];
    if (unit3(s->n0, e0) || unit3(s->n1, e1)) return 0;
    for (int i = 0; i < 3; i++) {
        nx[i] = (1 - x) * e0[i] + x * e1[i];
        p[i] = (1 - x) * s->p0[i] + x * s->p1[i];
    }
    if (unit3(nx, N)) return 0;
    if (toward(s->light_kind, s->light, p, L)) return 0;
    if (toward(s->view_kind, s->view, p, V)) return 0;

    double nl = dot3(N, L);
    int diffuse = s->model == SHADE_DIFFUSE || s->model == SHADE_DIFFUSE_PHONG
               || s->model == SHADE_DIFFUSE_BLINN;
    int phong = s->model == SHADE_PHONG || s->model == SHADE_DIFFUSE_PHONG;
    int blinn = s->model == SHADE_BLINN || s->model == SHADE_DIFFUSE_BLINN;

    double I = 0;
    if (diffuse) I += s->kd * fmax(0.0, nl);
    if ((phong || blinn) && nl > 0) {   /* no highlight from a light behind */
        double c = 0;
        if (phong) {
            double R[3];
            for (int i = 0; i < 3; i++) R[i] = 2 * nl * N[i] - L[i];
            c = dot3(R, V);
        } else {
            double h[3] = { L[0] + V[0], L[1] + V[1], L[2] + V[2] }, H[3];
            if (unit3(h, H) == 0) c = dot3(N, H);
        }
        if (c > 0) I += s->ks * pow(fmin(c, 1.0), s->n);
    }
    if (!(I > 0)) return 0;
    return I < 1 ? I : 1;
}

/* The named spans. Most live in the xz-plane with the viewer along +z. With
 * the light at angle +b and the viewer at angle -b from the z axis, the
 * halfway vector and the mirror direction are both +z, so a highlight sits
 * exactly where the interpolated normal has no x component: for end normals
 * at angles a0 < 0 < a1 that is x* = sin a0 / (sin a0 - sin a1) (angles of
 * the normalized end normals).
 *
 * The generators split each span into 1, 2, 4 or 8 intervals, so x = 1/2
 * is an interval edge for every split but one, and x in (1/4, 1/2) is
 * strictly inside an interval of the 4-split. */
#define S_B 0.479425538604203   /* sin 0.5 */
#define C_B 0.877582561890373   /* cos 0.5 */
static const shade_span spans[] = {
    /* Highlight much narrower than one interval (about 0.06 of the span
     * above half its peak), peak inside an interval: normals (-0.37,0,1),
     * (0.63,0,1) put it at x* = 0.394. */
    { "narrow_highlight", SHADE_PHONG, { -0.37, 0, 1 }, { 0.63, 0, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { S_B, 0, C_B },
      SHADE_DIRECTIONAL, { -S_B, 0, C_B }, 0, 0.95, 400 },
    /* Symmetric normals: the peak is exactly at x = 1/2, an interval edge
     * (node), so the two neighbouring cubics both end on the peak. Pure
     * specular: a diffuse term would shift the peak off 1/2. */
    { "highlight_at_edge", SHADE_BLINN, { -0.3, 0, 1 }, { 0.3, 0, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { S_B, 0, C_B },
      SHADE_DIRECTIONAL, { -S_B, 0, C_B }, 0, 0.9, 128 },
    /* Flat shading: one normal, directional light at 60 degrees:
     * I = 0.8 cos 60 = 0.4 everywhere. */
    { "flat", SHADE_DIFFUSE, { 0, 0, 1 }, { 0, 0, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 0.86602540378443865, 0, 0.5 },
      SHADE_DIRECTIONAL, { 0, 0, 1 }, 0.8, 0, 1 },
    /* Light behind the surface: N.L < 0 along the whole span, all zero
     * (the specular term is gated off too). */
    { "dark", SHADE_DIFFUSE_PHONG, { -0.2, 0, 1 }, { 0.2, 0, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 0, 0.3, -1 },
      SHADE_DIRECTIONAL, { 0, 0, 1 }, 0.7, 0.3, 20 },
    /* Across a cylinder seen head-on, light from the viewer: a wide cosine
     * falloff from ~0.18 up to 1 and back. */
    { "wide_diffuse", SHADE_DIFFUSE, { -1, 0, 0.18 }, { 1, 0, 0.18 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 0, 0, 1 },
      SHADE_DIRECTIONAL, { 0, 0, 1 }, 1, 0, 1 },
    /* The terminator (N.L = 0) crosses the span: max(0, .) puts a kink that
     * no polynomial follows. */
    { "terminator", SHADE_DIFFUSE, { -1, 0, 0.3 }, { 1, 0, 0.6 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 0.6, 0, 0.8 },
      SHADE_DIRECTIONAL, { 0, 0, 1 }, 0.9, 0, 1 },
    /* A point light just above the span and a nearby eye: L and V vary
     * along the span, not only N. */
    { "point_light_close", SHADE_DIFFUSE_BLINN, { -0.2, 0, 1 }, { 0.2, 0, 1 },
      { -1, 0, 0 }, { 1, 0, 0 }, SHADE_POINT, { 0.4, 0, 0.3 },
      SHADE_POINT, { 0, 0, 3 }, 0.7, 0.3, 32 },
    /* Diffuse + specular above 1 around the highlight: the clamp to 1 makes
     * a plateau with two kinks. */
    { "clamped_sum", SHADE_DIFFUSE_PHONG, { -0.5, 0, 1 }, { 0.3, 0, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 0.29552020666133957, 0, 0.95533648912560601 },
      SHADE_DIRECTIONAL, { -0.29552020666133957, 0, 0.95533648912560601 }, 0.75, 0.5, 10 },
    /* The easy, common case: gently curved surface, broad highlight. */
    { "gentle_phong", SHADE_DIFFUSE_PHONG, { -0.15, 0.05, 1 }, { 0.25, -0.05, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 0.4, 0.2, 1 },
      SHADE_DIRECTIONAL, { 0, 0, 1 }, 0.6, 0.3, 8 },
    /* Normals swinging out of the plane of light and view. */
    { "blinn_tilted", SHADE_BLINN, { -0.3, -0.4, 1 }, { 0.5, 0.6, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { 1, 1, 2 },
      SHADE_DIRECTIONAL, { 0, 0, 1 }, 0, 0.8, 16 },
    /* A pinpoint highlight (Blinn n = 2000, ~0.04 of the span wide) inside
     * the last interval of the 2-split: normals (-0.6,0,1), (0.35,0,1)
     * give x* = 0.609. */
    { "pinpoint", SHADE_DIFFUSE_BLINN, { -0.6, 0, 1 }, { 0.35, 0, 1 },
      { 0, 0, 0 }, { 1, 0, 0 }, SHADE_DIRECTIONAL, { S_B, 0, C_B },
      SHADE_DIRECTIONAL, { -S_B, 0, C_B }, 0.3, 0.7, 2000 },
};

size_t shade_span_count(void) { return sizeof spans / sizeof spans[0]; }

const shade_span *shade_span_at(size_t i)
{
    return i < shade_span_count() ? &spans[i] : NULL;
}

const shade_span *shade_span_find(const char *name)
{
    for (size_t i = 0; i < shade_span_count(); i++)
        if (name && !strcmp(spans[i].name, name)) return &spans[i];
    return NULL;
}

/* A random unit vector within the cone z >= zmin around +z. */
static void rand_cone(vec_rng *r, double zmin, double out[3])
{
    double z = vec_rng_range(r, zmin, 1);
    double phi = vec_rng_range(r, 0, 6.283185307179586);
    double s = sqrt(fmax(0.0, 1 - z * z));
    out[0] = s * cos(phi); out[1] = s * sin(phi); out[2] = z;
}

void shade_span_random(vec_rng *r, shade_span *s)
{
    memset(s, 0, sizeof *s);
    s->name = "random";
    s->model = (shade_model)(vec_rng_next(r) % SHADE_N_MODELS);
    /* End normals at most ~55 degrees off +z each, so never opposite. */
    rand_cone(r, 0.57, s->n0);
    rand_cone(r, 0.57, s->n1);
    double len = vec_rng_range(r, 0.2, 2);
    s->p0[0] = -len / 2; s->p1[0] = len / 2;
    s->p1[1] = vec_rng_range(r, -0.2, 0.2);
    if (vec_rng_unit(r) < 0.7) {
        s->light_kind = SHADE_DIRECTIONAL;
        rand_cone(r, -0.3, s->light);       /* sometimes below the horizon */
    } else {
        s->light_kind = SHADE_POINT;
        rand_cone(r, 0.1, s->light);
        double d = vec_rng_range(r, 0.3, 4);
        for (int i = 0; i < 3; i++) s->light[i] *= d;
    }
    if (vec_rng_unit(r) < 0.7) {
        s->view_kind = SHADE_DIRECTIONAL;
        rand_cone(r, 0.8, s->view);
    } else {
        s->view_kind = SHADE_POINT;
        rand_cone(r, 0.5, s->view);
        double d = vec_rng_range(r, 1, 6);
        for (int i = 0; i < 3; i++) s->view[i] *= d;
    }
    s->kd = vec_rng_range(r, 0.2, 1);
    s->ks = vec_rng_range(r, 0.05, 0.9);
    s->n = exp(vec_rng_range(r, 0, log(512.0)));
}

const char *shade_model_name(shade_model m)
{
    switch (m) {
    case SHADE_DIFFUSE: return "diffuse";
    case SHADE_PHONG: return "phong";
    case SHADE_BLINN: return "blinn";
    case SHADE_DIFFUSE_PHONG: return "diffuse+phong";
    case SHADE_DIFFUSE_BLINN: return "diffuse+blinn";
    default: return "?";
    }
}
