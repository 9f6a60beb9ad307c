/* scene_mesh.c - built-in procedural meshes: a head ("face"), a UV sphere
 * and a torus; the vertex-normal helper the OBJ reader shares.
 *
 * Frame of every built-in: +y up, the viewer on +z looking towards -z,
 * centred near the origin, about unit size. Triangles are
 * counter-clockwise seen from outside (outward facing) and every mesh is
 * closed: each edge is used by exactly two triangles, in opposite
 * directions.
 *
 * face: an ellipsoid (half-axes 0.72 wide, 0.95 tall, 0.80 deep), its
 *   lower half narrowed towards the jaw, whose front (+z) is displaced
 *   along z by a sum of Gaussian bumps and dents (smooth everywhere):
 *   forehead, brow ridges, eye sockets with eyeballs, a nose (a ridge
 *   rising to a tip, nostril wings), cheek bones and hollows, upper and
 *   lower lips, the dent under the lips, chin and jaw angles. The
 *   displacement fades out smoothly towards the sides. Tessellation: a
 *   latitude-longitude grid (poles on the y axis: top of the skull and
 *   neck), denser towards the front; detail 1 = 120 x 160 -> 38 080
 *   triangles. Normals are those of the smooth surface (cross product of
 *   the parameter derivatives, by central differences), not of the mesh.
 *
 *   Regions, one label per triangle, from the undeformed front
 *   coordinates (X, Y) of its centroid (X = x, to the viewer's right;
 *   Y = y, up) and how far it faces the viewer (uz = z
 *   component of the direction on the ellipsoid; "front" means uz > 0.35
 *   and -0.85 < Y < 0.80). First match wins:
 *
 *     label name      where
 *     ----- --------  ------------------------------------------------
 *       5   nose      front, -0.27 < Y < 0.19, |X| < 0.05 + 0.30 (0.19 - Y)
 *                     (capped at 0.14)
 *       3   eyes      front, ellipse centre (+-0.26, 0.11), half-axes 0.16 x 0.095
 *       1   brows     front, 0.205 <= Y < 0.33, 0.06 < |X| < 0.47
 *       2   forehead  front, Y >= 0.33, |X| < 0.52
 *       6   lips      front, ellipse centre (0, -0.405), half-axes 0.20 x 0.10
 *       7   chin      front, ellipse centre (0, -0.70), half-axes 0.27 x 0.19
 *       4   cheeks    front, -0.55 < Y < 0.205, |X| < 0.58
 *       0   rest      everything else: skull, sides, back, jaw, neck
 *
 *   (The paper's Fig. 10 gives degree 2 to its regions 2, 4 and 7; the
 *   flattest parts, forehead, cheeks and chin, carry those labels here.)
 *
 * sphere: UV sphere of radius 1, poles on the y axis, 64 x 128 at detail
 *   1 (16 128 triangles); exact normals (the position). Region 0.
 * torus: tube radius 0.3 around a circle of radius 0.7, its axis tilted
 *   60 degrees from the view axis (axis = (0, -sin 60, cos 60)) so that
 *   the viewer sees the hole and the near part of the tube in front of
 *   the far part; 128 x 64 at detail 1 (16 384 triangles); exact normals.
 *   Region 0.
 *
 * detail (1..8) multiplies both grid counts.
 */
#include "base/base_out.h"
#include "scene/scene_geom.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const scn_mesh_builtin_names[] = { "face", "sphere", "torus", NULL };

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define MAX_DETAIL 8

/* ----------------------------------------------------------- helpers */

int scn_mesh_alloc(scn_mesh *m, size_t nv, size_t nt)
{
    memset(m, 0, sizeof *m);
    if (nv > UINT32_MAX || nv > SIZE_MAX / (3 * sizeof(double)) ||
        nt > SIZE_MAX / (3 * sizeof(double)))
        return -1;
    m->pos = malloc((nv ? nv : 1) * sizeof *m->pos);
    m->nrm = malloc((nv ? nv : 1) * sizeof *m->nrm);
    m->tri = malloc((nt ? nt : 1) * sizeof *m->tri);
    m->region = calloc(nt ? nt : 1, 1);
    if (!m->pos || !m->nrm || !m->tri || !m->region) base_out_of_memory();
    m->nv = nv;
    m->nt = nt;
    m->nregions = 1;
    m->region_name[0] = "rest";
    return 0;
}

void scn_mesh_free(scn_mesh *m)
{
    if (!m) return;
    free(m->pos);
    free(m->nrm);
    free(m->tri);
    free(m->region);
    memset(m, 0, sizeof *m);
}

int scn_normalize_or(double v[3], const double fb[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    /* 1e-300: below it the division could overflow to inf. */
    if (!(l > 1e-300) || !isfinite(l)) {
        v[0] = fb[0]; v[1] = fb[1]; v[2] = fb[2];
        return 0;
    }
    v[0] /= l; v[1] /= l; v[2] /= l;
    return 1;
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

void scn_vertex_normals(const double (*pos)[3], size_t nv, const uint32_t (*tri)[3], size_t nt,
                        double (*nrm)[3])
{
    static const double fb[3] = { 0, 0, 1 };
    memset(nrm, 0, nv * sizeof *nrm);
    for (size_t t = 0; t < nt; t++) {
        const double *a = pos[tri[t][0]], *b = pos[tri[t][1]], *c = pos[tri[t][2]];
        double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
        double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
        double n[3];
        cross3(e1, e2, n);           /* length = twice the area: area weighting */
        if (!isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2])) continue;
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++) nrm[tri[t][k]][i] += n[i];
    }
    for (size_t v = 0; v < nv; v++) scn_normalize_or(nrm[v], fb);
}

/* ------------------------------------------------ latitude-longitude */

/* A closed grid over (theta, phi): vertex 0 is the pole theta = 0, then
 * rings i = 1..nlat-1 of nlon vertices, then the pole theta = pi. The
 * builder fills positions; triangles are laid out here. */
static int latlong_alloc(scn_mesh *m, int nlat, int nlon)
{
    size_t nv = (size_t)(nlat - 1) * nlon + 2;
    size_t nt = (size_t)2 * nlon * (nlat - 1);
    if (scn_mesh_alloc(m, nv, nt)) return -1;
    size_t t = 0, S = nv - 1;
    for (int j = 0; j < nlon; j++) {
        int j1 = (j + 1) % nlon;
        /* Counter-clockwise from outside: ring index grows away from the
         * theta = 0 pole, phi grows to the viewer's right at the front. */
        m->tri[t][0] = 0;
        m->tri[t][1] = (uint32_t)(1 + j);
        m->tri[t][2] = (uint32_t)(1 + j1);
        t++;
        for (int i = 1; i < nlat - 1; i++) {
            uint32_t a = (uint32_t)(1 + (size_t)(i - 1) * nlon + j);
            uint32_t b = (uint32_t)(1 + (size_t)(i - 1) * nlon + j1);
            uint32_t c = (uint32_t)(1 + (size_t)i * nlon + j);
            uint32_t d = (uint32_t)(1 + (size_t)i * nlon + j1);
            m->tri[t][0] = a; m->tri[t][1] = c; m->tri[t][2] = b; t++;
            m->tri[t][0] = b; m->tri[t][1] = c; m->tri[t][2] = d; t++;
        }
        m->tri[t][0] = (uint32_t)(1 + (size_t)(nlat - 2) * nlon + j);
        m->tri[t][1] = (uint32_t)S;
        m->tri[t][2] = (uint32_t)(1 + (size_t)(nlat - 2) * nlon + j1);
        t++;
    }
    return 0;
}

/* Direction on the unit sphere, theta from +y, phi from +z towards +x. */
static void sph_dir(double th, double ph, double u[3])
{
    u[0] = sin(th) * sin(ph);
    u[1] = cos(th);
    u[2] = sin(th) * cos(ph);
}

static int build_sphere(int detail, scn_mesh *m)
{
    int nlat = 64 * detail, nlon = 128 * detail;
    if (latlong_alloc(m, nlat, nlon)) return -1;
    size_t v = 0;
    for (int i = 0; i <= nlat; i++) {
        double th = M_PI * i / nlat;
        for (int j = 0; j < nlon; j++) {
            double ph = 2 * M_PI * j / nlon - M_PI;
            sph_dir(th, ph, m->pos[v]);
            if (i == 0) m->pos[v][0] = m->pos[v][2] = 0, m->pos[v][1] = 1;
            if (i == nlat) m->pos[v][0] = m->pos[v][2] = 0, m->pos[v][1] = -1;
            memcpy(m->nrm[v], m->pos[v], sizeof m->nrm[v]);
            v++;
            if (i == 0 || i == nlat) break;      /* one vertex per pole */
        }
    }
    return 0;
}

/* ------------------------------------------------------------- torus */

static int build_torus(int detail, scn_mesh *m)
{
    const double R = 0.7, r = 0.3, tilt = 60 * M_PI / 180;
    int nu = 128 * detail, nw = 64 * detail;
    if (scn_mesh_alloc(m, (size_t)nu * nw, (size_t)2 * nu * nw)) return -1;
    double ct = cos(tilt), st = sin(tilt);
    for (int i = 0; i < nu; i++) {
        double u = 2 * M_PI * i / nu;
        for (int j = 0; j < nw; j++) {
            double w = 2 * M_PI * j / nw;
            /* Local frame: axis z. Then rotate about x by the tilt. */
            double n[3] = { cos(w) * cos(u), cos(w) * sin(u), sin(w) };
            double p[3] = { R * cos(u) + r * n[0], R * sin(u) + r * n[1], r * n[2] };
            size_t v = (size_t)i * nw + j;
            m->pos[v][0] = p[0];
            m->pos[v][1] = p[1] * ct - p[2] * st;
            m->pos[v][2] = p[1] * st + p[2] * ct;
            m->nrm[v][0] = n[0];
            m->nrm[v][1] = n[1] * ct - n[2] * st;
            m->nrm[v][2] = n[1] * st + n[2] * ct;
        }
    }
    size_t t = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nw; j++) {
            uint32_t a = (uint32_t)((size_t)i * nw + j);
            uint32_t b = (uint32_t)((size_t)((i + 1) % nu) * nw + j);
            uint32_t c = (uint32_t)((size_t)i * nw + (j + 1) % nw);
            uint32_t d = (uint32_t)((size_t)((i + 1) % nu) * nw + (j + 1) % nw);
            /* du x dw points outwards (n = du x dw / |.| for this
             * parametrization), so a -> b -> c is counter-clockwise. */
            m->tri[t][0] = a; m->tri[t][1] = b; m->tri[t][2] = c; t++;
            m->tri[t][0] = c; m->tri[t][1] = b; m->tri[t][2] = d; t++;
        }
    return 0;
}

/* -------------------------------------------------------------- face */

#define AX 0.72
#define AY 0.95
#define AZ 0.80

typedef struct { double cx, cy, sx, sy, amp; } bump;

/* Bumps and dents of the front, (X, Y) on the undeformed head, height
 * along +z. Mirrored pairs are listed with cx > 0 and marked by sym. */
static const struct { bump b; int sym; } face_bumps[] = {
    { { 0.00,  0.50, 0.35, 0.20,  0.030 }, 0 },   /* forehead */
    { { 0.00,  0.22, 0.06, 0.05,  0.020 }, 0 },   /* glabella, between the brows */
    { { 0.26,  0.25, 0.13, 0.04,  0.040 }, 1 },   /* brow ridges */
    { { 0.26,  0.12, 0.10, 0.07, -0.100 }, 1 },   /* eye sockets */
    { { 0.26,  0.11, 0.06, 0.04,  0.050 }, 1 },   /* eyeballs under the lids */
    { { 0.00, -0.15, 0.05, 0.05,  0.040 }, 0 },   /* nose tip */
    { { 0.075,-0.19, 0.035,0.035, 0.045 }, 1 },   /* nostril wings */
    { { 0.00, -0.265,0.05, 0.03, -0.015 }, 0 },   /* under the nose */
    { { 0.33, -0.04, 0.10, 0.07,  0.050 }, 1 },   /* cheek bones */
    { { 0.30, -0.30, 0.08, 0.10, -0.025 }, 1 },   /* cheek hollows */
    { { 0.00, -0.36, 0.13, 0.035, 0.045 }, 0 },   /* upper lip */
    { { 0.00, -0.45, 0.11, 0.035, 0.045 }, 0 },   /* lower lip */
    { { 0.00, -0.405,0.12, 0.028,-0.012 }, 0 },   /* the line between the lips */
    { { 0.14, -0.405,0.035,0.035,-0.020 }, 1 },   /* mouth corners */
    { { 0.00, -0.56, 0.10, 0.03, -0.020 }, 0 },   /* dent under the lower lip */
    { { 0.00, -0.70, 0.12, 0.08,  0.050 }, 0 },   /* chin */
    { { 0.48, -0.52, 0.08, 0.10,  0.020 }, 1 },   /* jaw angles */
};

static double gauss2(const bump *b, double x, double y)
{
    double dx = (x - b->cx) / b->sx, dy = (y - b->cy) / b->sy;
    return b->amp * exp(-0.5 * (dx * dx + dy * dy));
}

/* C2 step from 0 (t <= 0) to 1 (t >= 1). */
static double smoother(double t)
{
    if (t <= 0) return 0;
    if (t >= 1) return 1;
    return t * t * t * (t * (t * 6 - 15) + 10);
}

/* Height of the front at (X, Y). */
static double face_height(double X, double Y)
{
    double h = 0;
    for (size_t k = 0; k < sizeof face_bumps / sizeof face_bumps[0]; k++) {
        h += gauss2(&face_bumps[k].b, X, Y);
        if (face_bumps[k].sym) {
            bump m = face_bumps[k].b;
            m.cx = -m.cx;
            h += gauss2(&m, X, Y);
        }
    }
    /* Nose: a ridge along X = 0 rising from the bridge (Y = 0.22) to the
     * tip (Y = -0.16), widening, and falling off fast below the tip
     * (the squared max() keeps it C1). */
    double rise = smoother((0.22 - Y) / 0.38);
    double below = Y < -0.16 ? (-0.16 - Y) / 0.05 : 0;
    double sx = 0.035 + 0.025 * rise;
    h += (0.03 + 0.14 * rise) * smoother((0.30 - Y) / 0.12) * exp(-0.5 * below * below)
         * exp(-0.5 * (X / sx) * (X / sx));
    return h;
}

/* Width factor of the head at height uy: the jaw narrows it below. */
static double face_jaw(double uy)
{
    return 1 - 0.14 * smoother((0.05 - uy) / 0.85);
}

/* The head surface at direction u: undeformed (X, Y) and the point. */
static void face_point(const double u[3], double p[3])
{
    double X = AX * u[0] * face_jaw(u[1]), Y = AY * u[1];
    double w = smoother((u[2] - 0.05) / 0.45);      /* front weight */
    p[0] = X;
    p[1] = Y;
    p[2] = AZ * u[2] + (w > 0 ? w * face_height(X, Y) : 0);
}

/* Grid parameters -> angles, denser towards the front (t = 0). */
#define FACE_C 0.8
static double face_warp(double t) { return (t + FACE_C * t * t * t) / (1 + FACE_C); }
static double face_theta(double t) { return M_PI / 2 + M_PI / 2 * face_warp(t); }
static double face_phi(double s) { return M_PI * face_warp(s); }

static int face_region(double X, double Y, double uz)
{
    double ax = fabs(X);
    if (!(uz > 0.35 && Y > -0.85 && Y < 0.80)) return 0;
    double nw = 0.05 + 0.30 * (0.19 - Y);
    if (nw > 0.14) nw = 0.14;
    if (Y > -0.27 && Y < 0.19 && ax < nw) return 5;
    double ex = (ax - 0.26) / 0.16, ey = (Y - 0.11) / 0.095;
    if (ex * ex + ey * ey < 1) return 3;
    if (Y >= 0.205 && Y < 0.33 && ax > 0.06 && ax < 0.47) return 1;
    if (Y >= 0.33 && ax < 0.52) return 2;
    double lx = X / 0.20, ly = (Y + 0.405) / 0.10;
    if (lx * lx + ly * ly < 1) return 6;
    double cx = X / 0.27, cy = (Y + 0.70) / 0.19;
    if (cx * cx + cy * cy < 1) return 7;
    if (Y > -0.55 && Y < 0.205 && ax < 0.58) return 4;
    return 0;
}

static int build_face(int detail, scn_mesh *m)
{
    static const char *const names[8] = { "rest", "brows", "forehead", "eyes",
                                          "cheeks", "nose", "lips", "chin" };
    int nlat = 120 * detail, nlon = 160 * detail;
    if (latlong_alloc(m, nlat, nlon)) return -1;
    m->nregions = 8;
    for (int k = 0; k < 8; k++) m->region_name[k] = names[k];
    /* Per vertex: undeformed front coordinates for the region labels. */
    double (*fr)[3] = malloc(m->nv * sizeof *fr);
    if (!fr) base_out_of_memory();
    const double h = 1e-5;          /* central-difference step in grid units */
    size_t v = 0;
    for (int i = 0; i <= nlat; i++) {
        double t = 2.0 * i / nlat - 1;
        for (int j = 0; j < nlon; j++) {
            double s = 2.0 * j / nlon - 1;
            double u[3];
            sph_dir(face_theta(t), face_phi(s), u);
            if (i == 0 || i == nlat) {           /* the poles: exactly on the axis */
                u[0] = u[2] = 0;
                u[1] = i ? -1 : 1;
            }
            face_point(u, m->pos[v]);
            fr[v][0] = AX * u[0] * face_jaw(u[1]);
            fr[v][1] = AY * u[1];
            fr[v][2] = u[2];
            if (i == 0 || i == nlat) {
                /* The front weight is 0 near the poles: the ellipsoid's normal. */
                m->nrm[v][0] = m->nrm[v][2] = 0;
                m->nrm[v][1] = i ? -1 : 1;
                v++;
                break;
            }
            double a[3], b[3], pa[3], pb[3], dt[3], ds[3];
            sph_dir(face_theta(t + h), face_phi(s), a); face_point(a, pa);
            sph_dir(face_theta(t - h), face_phi(s), b); face_point(b, pb);
            for (int k = 0; k < 3; k++) dt[k] = pa[k] - pb[k];
            sph_dir(face_theta(t), face_phi(s + h), a); face_point(a, pa);
            sph_dir(face_theta(t), face_phi(s - h), b); face_point(b, pb);
            for (int k = 0; k < 3; k++) ds[k] = pa[k] - pb[k];
            /* theta grows downwards, phi to the right (at the front):
             * d/dt x d/ds = (-y) x (+x) = +z points outwards. */
            cross3(dt, ds, m->nrm[v]);
            scn_normalize_or(m->nrm[v], u);
            v++;
        }
    }
    for (size_t k = 0; k < m->nt; k++) {
        double c[3] = { 0, 0, 0 };
        for (int q = 0; q < 3; q++)
            for (int e = 0; e < 3; e++) c[e] += fr[m->tri[k][q]][e] / 3;
        m->region[k] = (uint8_t)face_region(c[0], c[1], c[2]);
    }
    free(fr);
    return 0;
}

int scn_mesh_builtin(const char *name, int detail, scn_mesh *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    if (detail < 1 || detail > MAX_DETAIL) {
        snprintf(err, errlen, "detail %d out of range 1..%d", detail, MAX_DETAIL);
        return -1;
    }
    int r;
    if (!name) name = "(null)";
    if (!strcmp(name, "face")) r = build_face(detail, m);
    else if (!strcmp(name, "sphere")) r = build_sphere(detail, m);
    else if (!strcmp(name, "torus")) r = build_torus(detail, m);
    else {
        snprintf(err, errlen, "unknown built-in mesh '%s' (face, sphere, torus)", name);
        return -1;
    }
    if (r) {
        snprintf(err, errlen, "mesh %s: too many vertices", name);
        return -1;
    }
    return 0;
}
