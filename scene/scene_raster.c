/* scene_raster.c - cameras and the scanline rasterizer (see scene.h).
 *
 * Camera: f = normalize(target - eye), r = normalize(f x up), u = r x f.
 * A point p has view coordinates xv = (p-eye).r, yv = (p-eye).u and
 * depth z = (p-eye).f (distance along the view axis, positive in front
 * of the eye, smaller is nearer). Screen (pixels, y down, origin at the
 * top-left corner of the image):
 *   perspective:  X = w/2 + s xv / z,  Y = h/2 - s yv / z,  s = (h/2) / tan(fov/2)
 *   orthographic: X = w/2 + s xv,      Y = h/2 - s yv,      s = h / ortho_height
 * Pixels are square; the vertical extent is what fov / ortho_height set.
 *
 * Coverage is exact: vertices are snapped to a 1/256-pixel grid and the
 * edge functions are evaluated in 128-bit integers, so a pixel centre
 * (x + 0.5, y + 0.5) on an edge is decided by the top-left rule with no
 * rounding: inside when every edge function is > 0, or == 0 on a left
 * edge (interior to its right) or a top edge (horizontal, interior
 * below). Two front-facing triangles sharing an edge run it in opposite
 * directions, so exactly one of them takes such a centre. For each row
 * the three edge inequalities are solved for the exact run of covered
 * centres (no per-pixel edge tests).
 *
 * Attributes use the unsnapped screen positions: screen barycentrics
 * divided by each vertex's depth (perspective) give the point of the
 * triangle's plane on the pixel's ray, to rounding. A centre covered by
 * the snapped triangle can lie up to 1/512 pixel outside the exact one;
 * the barycentrics then extrapolate slightly (exact on the plane). Only
 * when one is below -0.05 (slivers thinner than ~1/20 pixel) are they
 * clamped to the triangle.
 *
 * Back faces (clockwise as the viewer sees them: the mesh's triangles are
 * counter-clockwise seen from outside) and triangles of zero snapped area
 * are culled. Triangles are clipped against the near plane
 * z = 1e-4 |target - eye| (perspective) or z = 0 (orthographic: nothing
 * behind the eye is drawn); the clipped polygon (3 or 4 vertices) is
 * fanned into triangles. A triangle with a vertex projecting farther
 * than 2^40 pixels from the image (large coordinates, a tiny fov or
 * ortho height, geometry grazing the near plane) is clipped in screen
 * space to a guard band 2^20 pixels around the image, its new vertices'
 * attributes interpolated perspective-correct, and drawn: its pixels are
 * those of the unclipped triangle (the band's edges never cross the
 * image). A clipped edge's point is computed from its lower end
 * (lexicographic X, Y), so two triangles sharing that edge get the same
 * point and the shared-edge rule still holds. Only a non-finite
 * coordinate (or one whose interpolation overflows) drops a triangle.
 *
 * The z-test is strict (<): of two fragments at equal depth the one of
 * the lower triangle index stays. Deterministic: one thread, mesh order.
 * Uncovered pixels: tri -1, depth +inf, region, pos, nrm 0.
 *
 * Errors (-1 with a message; out of memory ends the program): image
 * size outside 1..32768 per side or 2^28 pixels, eye == target, up zero
 * or along the view, fov outside (0, 180), ortho height <= 0, more than
 * INT32_MAX triangles. 128-bit integers are the GNU __int128, as in
 * sim/sim_fixed.c.
 */
#include "base/base_out.h"
#include "scene/scene.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define SUB 256                         /* subpixel grid: 1/256 pixel */
#define MAX_SCREEN 1099511627776.0      /* 2^40 pixels */
#define GUARD      1048576.0            /* 2^20 pixels: the clip band around the image */

typedef __int128 i128;

typedef struct {
    double r[3], u[3], f[3], eye[3];
    int    persp;
    double s, cx, cy, near;
} xform;

/* A vertex ready to rasterize. */
typedef struct {
    double  X, Y, z;                    /* screen (unsnapped), depth */
    int64_t ix, iy;                     /* snapped, 1/SUB pixel */
    double  p[3], n[3];                 /* world position, normal */
    int     ok;                         /* projected inside the 2^40 bound */
} rvert;

typedef struct {
    scn_gbuf *g;
    int       persp;
} rctx;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int unit3(double v[3])
{
    double l = sqrt(dot3(v, v));
    if (!(l > 0) || !isfinite(l)) return -1;
    v[0] /= l; v[1] /= l; v[2] /= l;
    return 0;
}

static int xform_init(const scn_camera *c, int w, int h, xform *x, char *err, size_t errlen);

int scn_camera_check(const scn_camera *c, char *err, size_t errlen)
{
    xform x;
    return xform_init(c, 64, 64, &x, err, errlen);
}

static int xform_init(const scn_camera *c, int w, int h, xform *x, char *err, size_t errlen)
{
    double f[3] = { c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2] };
    double dist = sqrt(dot3(f, f));
    if (unit3(f)) {
        snprintf(err, errlen, "camera: eye and target coincide");
        return -1;
    }
    double up[3] = { c->up[0], c->up[1], c->up[2] }, r[3];
    r[0] = f[1] * up[2] - f[2] * up[1];
    r[1] = f[2] * up[0] - f[0] * up[2];
    r[2] = f[0] * up[1] - f[1] * up[0];
    if (unit3(r) || sqrt(dot3(up, up)) == 0) {
        snprintf(err, errlen, "camera: up is zero or parallel to the view direction");
        return -1;
    }
    memcpy(x->f, f, sizeof f);
    memcpy(x->r, r, sizeof r);
    x->u[0] = r[1] * f[2] - r[2] * f[1];
    x->u[1] = r[2] * f[0] - r[0] * f[2];
    x->u[2] = r[0] * f[1] - r[1] * f[0];
    memcpy(x->eye, c->eye, sizeof x->eye);
    x->persp = c->perspective != 0;
    x->cx = w / 2.0;
    x->cy = h / 2.0;
    if (x->persp) {
        if (!(c->fov_deg > 0 && c->fov_deg < 180)) {
            snprintf(err, errlen, "camera: fov %g out of range (0, 180) degrees", c->fov_deg);
            return -1;
        }
        x->s = (h / 2.0) / tan(c->fov_deg * M_PI / 360);
        x->near = 1e-4 * dist;
    } else {
        if (!(c->ortho_height > 0) || !isfinite(c->ortho_height)) {
            snprintf(err, errlen, "camera: ortho height %g must be > 0", c->ortho_height);
            return -1;
        }
        x->s = h / c->ortho_height;
        x->near = 0;
    }
    return 0;
}

/* Depth and screen position of a point whose view coordinates are known. */
static void project(const xform *x, double xv, double yv, rvert *v)
{
    double X, Y;
    if (x->persp) {
        X = x->cx + x->s * xv / v->z;
        Y = x->cy - x->s * yv / v->z;
    } else {
        X = x->cx + x->s * xv;
        Y = x->cy - x->s * yv;
    }
    v->X = X;
    v->Y = Y;
    v->ok = fabs(X) < MAX_SCREEN && fabs(Y) < MAX_SCREEN;   /* false for NaN too */
    if (v->ok) {
        v->ix = (int64_t)floor(X * SUB + 0.5);
        v->iy = (int64_t)floor(Y * SUB + 0.5);
    }
}

static void view_of(const xform *x, const double p[3], double *xv, double *yv, double *z)
{
    double d[3] = { p[0] - x->eye[0], p[1] - x->eye[1], p[2] - x->eye[2] };
    *xv = dot3(d, x->r);
    *yv = dot3(d, x->u);
    *z = dot3(d, x->f);
}

static i128 floor_div(i128 a, i128 b)     /* b > 0 */
{
    i128 q = a / b;
    if (a % b != 0 && a < 0) q--;
    return q;
}

static i128 ceil_div(i128 a, i128 b)      /* b > 0 */
{
    return -floor_div(-a, b);
}

/* Barycentrics into the triangle (negative parts to 0, renormalized). */
static void clamp_bary(double l[3])
{
    double s = 0;
    for (int k = 0; k < 3; k++) {
        if (!(l[k] > 0)) l[k] = 0;
        s += l[k];
    }
    for (int k = 0; k < 3; k++) l[k] = s > 0 ? l[k] / s : 1.0 / 3;
}

/* Attribute weights and depth from screen barycentrics l: perspective
 * divides each by its vertex depth (iz = 1/z) and renormalizes. 0 when
 * the result is not usable (a non-positive or non-finite 1/z sum). */
static int weights(int persp, const double l[3], const double iz[3], const rvert *const v[3],
                   double wgt[3], double *z)
{
    if (persp) {
        double sum = 0;
        for (int k = 0; k < 3; k++) sum += wgt[k] = l[k] * iz[k];
        if (!(sum > 0) || !isfinite(sum)) return 0;
        *z = 1 / sum;
        for (int k = 0; k < 3; k++) wgt[k] *= *z;
    } else {
        *z = 0;
        for (int k = 0; k < 3; k++) *z += (wgt[k] = l[k]) * v[k]->z;
        if (!isfinite(*z)) return 0;
    }
    return 1;
}

static void draw(rctx *c, const rvert *v0, const rvert *v1, const rvert *v2,
                 int32_t tri, uint8_t region);

static void snap(rvert *v)
{
    v->ok = fabs(v->X) < MAX_SCREEN && fabs(v->Y) < MAX_SCREEN;
    if (v->ok) {
        v->ix = (int64_t)floor(v->X * SUB + 0.5);
        v->iy = (int64_t)floor(v->Y * SUB + 0.5);
    }
}

/* The point of edge ab on the line (axis 0: X, 1: Y) = bound; attributes
 * perspective-correct (1/z is linear on screen). From the lower end, so
 * that the edge gives the same point whichever way it is walked. 0 when
 * something overflows. */
static int cut(int persp, const rvert *a, const rvert *b, int axis, double bound, rvert *o)
{
    if (b->X < a->X || (b->X == a->X && b->Y < a->Y)) { const rvert *t = a; a = b; b = t; }
    double ca = axis ? a->Y : a->X, cb = axis ? b->Y : b->X;
    double s = (bound - ca) / (cb - ca);
    if (!(s >= 0 && s <= 1)) s = s > 1 ? 1 : 0;
    double t = s, z;
    if (persp) {
        double ia = (1 - s) / a->z, ib = s / b->z;
        z = 1 / (ia + ib);
        t = ib * z;
    } else {
        z = a->z + s * (b->z - a->z);
    }
    o->X = axis ? a->X + s * (b->X - a->X) : bound;
    o->Y = axis ? bound : a->Y + s * (b->Y - a->Y);
    o->z = z;
    int fin = isfinite(o->X) && isfinite(o->Y) && isfinite(z) && isfinite(t);
    for (int e = 0; e < 3; e++) {
        o->p[e] = a->p[e] + t * (b->p[e] - a->p[e]);
        o->n[e] = a->n[e] + t * (b->n[e] - a->n[e]);
        fin = fin && isfinite(o->p[e]) && isfinite(o->n[e]);
    }
    snap(o);
    return fin;
}

/* A triangle with a vertex beyond the 2^40 bound: Sutherland-Hodgman
 * against the guard band's four sides (at most 7 vertices), fanned. */
static void draw_clipped(rctx *c, const rvert *v0, const rvert *v1, const rvert *v2,
                         int32_t tri, uint8_t region)
{
    const rvert *t3[3] = { v0, v1, v2 };
    for (int k = 0; k < 3; k++)
        if (!isfinite(t3[k]->X) || !isfinite(t3[k]->Y)) return;
    rvert poly[2][8];
    int n = 3, cur = 0;
    for (int k = 0; k < 3; k++) poly[0][k] = *t3[k];
    const double lim[4] = { -GUARD, c->g->w + GUARD, -GUARD, c->g->h + GUARD };
    for (int side = 0; side < 4 && n >= 3; side++) {
        int axis = side / 2, upper = side & 1, m = 0;
        const rvert *in = poly[cur];
        rvert *out = poly[!cur];
        for (int k = 0; k < n; k++) {
            const rvert *a = &in[k], *b = &in[(k + 1) % n];
            double ca = axis ? a->Y : a->X, cb = axis ? b->Y : b->X;
            int ina = upper ? ca <= lim[side] : ca >= lim[side];
            int inb = upper ? cb <= lim[side] : cb >= lim[side];
            if (ina) out[m++] = *a;
            if (ina != inb && !cut(c->persp, a, b, axis, lim[side], &out[m++])) return;
        }
        n = m;
        cur = !cur;
    }
    for (int k = 1; k + 1 < n; k++) draw(c, &poly[cur][0], &poly[cur][k], &poly[cur][k + 1], tri, region);
}

/* Rasterize one triangle (any orientation on screen; back faces culled). */
static void draw(rctx *c, const rvert *v0, const rvert *v1, const rvert *v2,
                 int32_t tri, uint8_t region)
{
    scn_gbuf *g = c->g;
    if (!v0->ok || !v1->ok || !v2->ok) {
        draw_clipped(c, v0, v1, v2, tri, region);
        return;
    }
    i128 D = (i128)(v1->ix - v0->ix) * (v2->iy - v0->iy) - (i128)(v2->ix - v0->ix) * (v1->iy - v0->iy);
    /* Counter-clockwise in a y-up view is D < 0 with y down: front. */
    if (D >= 0) return;
    const rvert *v[3] = { v0, v2, v1 };           /* now D > 0: interior has E > 0 */

    int64_t ymin = v[0]->iy, ymax = v[0]->iy;
    for (int k = 1; k < 3; k++) {
        if (v[k]->iy < ymin) ymin = v[k]->iy;
        if (v[k]->iy > ymax) ymax = v[k]->iy;
    }
    /* Rows whose centre y*SUB + SUB/2 lies in [ymin, ymax]. */
    i128 ya = ceil_div((i128)ymin - SUB / 2, SUB), yb = floor_div((i128)ymax - SUB / 2, SUB);
    if (ya < 0) ya = 0;
    if (yb > g->h - 1) yb = g->h - 1;
    if (ya > yb) return;

    int64_t edx[3], edy[3], eax[3], eay[3];
    int bias[3];
    for (int k = 0; k < 3; k++) {
        const rvert *a = v[k], *b = v[(k + 1) % 3];
        edx[k] = b->ix - a->ix;
        edy[k] = b->iy - a->iy;
        eax[k] = a->ix;
        eay[k] = a->iy;
        /* E(P) = dx (Py - ay) - dy (Px - ax); dE/dPx = -dy, dE/dPy = dx.
         * Left edge: interior to the right (dy < 0); top edge: horizontal
         * with the interior below (dy == 0, dx > 0). */
        int topleft = edy[k] < 0 || (edy[k] == 0 && edx[k] > 0);
        bias[k] = topleft ? 0 : 1;
    }

    /* Interpolation setup in doubles, unsnapped positions. */
    double X0 = v[0]->X, Y0 = v[0]->Y;
    double e1x = v[1]->X - X0, e1y = v[1]->Y - Y0, e2x = v[2]->X - X0, e2y = v[2]->Y - Y0;
    double Dd = e1x * e2y - e1y * e2x;
    int dgood = Dd != 0 && isfinite(Dd);
    double iz[3];
    for (int k = 0; k < 3; k++) iz[k] = c->persp ? 1 / v[k]->z : 0;

    for (int y = (int)ya; y <= (int)yb; y++) {
        i128 PY = (i128)y * SUB + SUB / 2;
        i128 xl = 0, xr = g->w - 1;
        int empty = 0;
        for (int k = 0; k < 3 && !empty; k++) {
            /* E at Px = x SUB + SUB/2: alpha x + beta0; need >= bias. */
            i128 alpha = -(i128)edy[k] * SUB;
            i128 beta = -(i128)edy[k] * (SUB / 2) + (i128)edx[k] * (PY - eay[k])
                        + (i128)edy[k] * eax[k] - bias[k];
            if (alpha > 0) {
                i128 lo = ceil_div(-beta, alpha);
                if (lo > xl) xl = lo;
            } else if (alpha < 0) {
                i128 hi = floor_div(beta, -alpha);
                if (hi < xr) xr = hi;
            } else if (beta < 0) {
                empty = 1;
            }
        }
        if (empty || xl > xr) continue;
        double py = y + 0.5 - Y0;
        size_t row = (size_t)y * g->w;
        for (int x = (int)xl; x <= (int)xr; x++) {
            size_t i = row + x;
            g->frags[i]++;
            double px = x + 0.5 - X0, l1, l2;
            if (dgood) {
                l1 = (px * e2y - py * e2x) / Dd;
                l2 = (e1x * py - e1y * px) / Dd;
            } else {
                l1 = l2 = 1.0 / 3;
            }
            double l[3] = { 1 - l1 - l2, l1, l2 }, wgt[3], z;
            if (!(l[0] >= -0.05 && l[1] >= -0.05 && l[2] >= -0.05)) clamp_bary(l);
            if (!weights(c->persp, l, iz, v, wgt, &z)) {
                clamp_bary(l);
                if (!weights(c->persp, l, iz, v, wgt, &z)) continue;
            }
            if (z < g->depth[i]) {
                g->depth[i] = z;
                g->tri[i] = tri;
                g->region[i] = region;
                for (int e = 0; e < 3; e++) {
                    g->pos[i][e] = wgt[0] * v[0]->p[e] + wgt[1] * v[1]->p[e] + wgt[2] * v[2]->p[e];
                    g->nrm[i][e] = wgt[0] * v[0]->n[e] + wgt[1] * v[1]->n[e] + wgt[2] * v[2]->n[e];
                }
            }
        }
    }
}

/* Point where the edge from the inside vertex a to the outside vertex b
 * crosses z = near. Always computed from the inside end, so the two
 * triangles sharing an edge get the same point. */
static void clip_point(const xform *x, const rvert *a, const rvert *b, double xva, double yva,
                       double xvb, double yvb, rvert *o)
{
    double t = (x->near - a->z) / (b->z - a->z);
    for (int e = 0; e < 3; e++) {
        o->p[e] = a->p[e] + t * (b->p[e] - a->p[e]);
        o->n[e] = a->n[e] + t * (b->n[e] - a->n[e]);
    }
    o->z = x->near;
    project(x, xva + t * (xvb - xva), yva + t * (yvb - yva), o);
}

int scn_raster(const scn_mesh *m, const scn_camera *cam, int w, int h, scn_gbuf *g,
               char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    if (w < 1 || h < 1 || w > 32768 || h > 32768 || (size_t)w * h > ((size_t)1 << 28)) {
        snprintf(err, errlen, "image size %dx%d out of range (1..32768 each, 2^28 pixels)", w, h);
        return -1;
    }
    if (m->nt > INT32_MAX) {
        snprintf(err, errlen, "mesh has %zu triangles, at most %d", m->nt, INT32_MAX);
        return -1;
    }
    xform x;
    if (xform_init(cam, w, h, &x, err, errlen)) return -1;
    size_t n = (size_t)w * h;
    g->w = w;
    g->h = h;
    g->tri = malloc(n * sizeof *g->tri);
    g->region = calloc(n, 1);
    g->depth = malloc(n * sizeof *g->depth);
    g->pos = calloc(n, sizeof *g->pos);
    g->nrm = calloc(n, sizeof *g->nrm);
    g->frags = calloc(n, sizeof *g->frags);
    rvert *vs = malloc((m->nv ? m->nv : 1) * sizeof *vs);
    double (*vv)[2] = malloc((m->nv ? m->nv : 1) * sizeof *vv);     /* xv, yv */
    if (!g->tri || !g->region || !g->depth || !g->pos || !g->nrm || !g->frags || !vs || !vv) {
        base_out_of_memory();
    }
    for (size_t i = 0; i < n; i++) {
        g->tri[i] = -1;
        g->depth[i] = INFINITY;
    }
    if (x.persp) {
        g->foot0 = 0;
        g->foot1 = 1 / x.s;
    } else {
        g->foot0 = 1 / x.s;
        g->foot1 = 0;
    }
    for (size_t i = 0; i < m->nv; i++) {
        rvert *v = &vs[i];
        memcpy(v->p, m->pos[i], sizeof v->p);
        memcpy(v->n, m->nrm[i], sizeof v->n);
        view_of(&x, v->p, &vv[i][0], &vv[i][1], &v->z);
        if (v->z >= x.near) project(&x, vv[i][0], vv[i][1], v);
        else v->ok = 0;
    }
    rctx c = { g, x.persp };
    for (size_t t = 0; t < m->nt; t++) {
        const uint32_t *ti = m->tri[t];
        if (ti[0] >= m->nv || ti[1] >= m->nv || ti[2] >= m->nv) continue;
        const rvert *a = &vs[ti[0]], *b = &vs[ti[1]], *d = &vs[ti[2]];
        int in[3] = { a->z >= x.near, b->z >= x.near, d->z >= x.near };
        int nin = in[0] + in[1] + in[2];
        if (nin == 3) {
            draw(&c, a, b, d, (int32_t)t, m->region[t]);
            continue;
        }
        if (nin == 0) continue;
        if (!(isfinite(a->z) && isfinite(b->z) && isfinite(d->z))) continue;
        /* Sutherland-Hodgman against z >= near: 3 or 4 vertices, in order. */
        rvert poly[4];
        int np = 0;
        for (int k = 0; k < 3; k++) {
            uint32_t ia = ti[k], ib = ti[(k + 1) % 3];
            int ina = in[k], inb = in[(k + 1) % 3];
            if (ina) poly[np++] = vs[ia];
            if (ina != inb) {
                if (ina)
                    clip_point(&x, &vs[ia], &vs[ib], vv[ia][0], vv[ia][1], vv[ib][0], vv[ib][1], &poly[np++]);
                else
                    clip_point(&x, &vs[ib], &vs[ia], vv[ib][0], vv[ib][1], vv[ia][0], vv[ia][1], &poly[np++]);
            }
        }
        for (int k = 1; k + 1 < np; k++) draw(&c, &poly[0], &poly[k], &poly[k + 1], (int32_t)t, m->region[t]);
    }
    free(vs);
    free(vv);
    return 0;
}

void scn_gbuf_free(scn_gbuf *g)
{
    if (!g) return;
    free(g->tri);
    free(g->region);
    free(g->depth);
    free(g->pos);
    free(g->nrm);
    free(g->frags);
    memset(g, 0, sizeof *g);
}
