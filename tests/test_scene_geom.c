/* test_scene_geom.c - the geometry half of the scene layer: built-in
 * meshes, the OBJ reader, the rasterizer (coverage, fill rule, culling,
 * perspective-correct attributes, near-plane clipping) and spans.
 *
 * References are computed here, independently: pixel centres inside
 * rectangles and squares by the top-left rule, rays through pixel centres
 * from the camera formulas of scene.h intersected with planes and spheres
 * in closed form, mesh closedness by counting directed edges. */
#include "tests/tst.h"
#include "scene/scene.h"
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ------------------------------------------------------------ helpers */

static uint64_t rng_state = 88172645463325252ull;
static uint64_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}

/* A mesh by hand: room for nv vertices and nt triangles. */
static void mesh_new(scn_mesh *m, size_t nv, size_t nt)
{
    memset(m, 0, sizeof *m);
    m->pos = calloc(nv, sizeof *m->pos);
    m->nrm = calloc(nv, sizeof *m->nrm);
    m->tri = calloc(nt, sizeof *m->tri);
    m->region = calloc(nt, 1);
    m->nregions = 1;
    m->region_name[0] = "rest";
    if (!m->pos || !m->nrm || !m->tri || !m->region) abort();
}

static uint32_t add_v(scn_mesh *m, double x, double y, double z)
{
    double *p = m->pos[m->nv], *n = m->nrm[m->nv];
    p[0] = x; p[1] = y; p[2] = z;
    n[0] = 0; n[1] = 0; n[2] = 1;
    return (uint32_t)m->nv++;
}

static void add_t(scn_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    m->tri[m->nt][0] = a; m->tri[m->nt][1] = b; m->tri[m->nt][2] = c;
    m->nt++;
}

static scn_camera ortho_cam(double height)
{
    scn_camera c = { 0, { 0, 0, 5 }, { 0, 0, 0 }, { 0, 1, 0 }, 40, height };
    return c;
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double len(const double a[3]) { return sqrt(dot(a, a)); }
static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static void unitv(double a[3]) { double l = len(a); a[0] /= l; a[1] /= l; a[2] /= l; }

/* Ray of pixel centre (x + 0.5, y + 0.5) for a perspective camera, from
 * the formulas in scene.h: d = f + ((X - w/2) r - (Y - h/2) u) / s. */
static void pixel_ray(const scn_camera *c, int w, int h, int x, int y, double o[3], double d[3],
                      double f[3])
{
    double r[3], u[3];
    for (int k = 0; k < 3; k++) f[k] = c->target[k] - c->eye[k];
    unitv(f);
    cross(f, c->up, r);
    unitv(r);
    cross(r, f, u);
    double s = (h / 2.0) / tan(c->fov_deg * M_PI / 360);
    double a = (x + 0.5 - w / 2.0) / s, b = -(y + 0.5 - h / 2.0) / s;
    for (int k = 0; k < 3; k++) {
        o[k] = c->eye[k];
        d[k] = f[k] + a * r[k] + b * u[k];
    }
}

static int raster(const scn_mesh *m, const scn_camera *c, int w, int h, scn_gbuf *g)
{
    char err[256] = "";
    int r = scn_raster(m, c, w, h, g, err, sizeof err);
    if (r) printf("  scn_raster: %s\n", err);
    return r;
}

/* ------------------------------------------------------- fill rule */

/* A square of 8 x 8 cells of 4 pixels (alternating diagonals), the
 * cell (3, 3) a fan of 4 triangles around a vertex on a pixel centre.
 * Every vertex and every horizontal / vertical edge lies on pixel
 * centres; with jitter, the interior vertices (but the fan cell's
 * corners) move by up to half a pixel in multiples of 1/256 pixel. Ortho
 * camera, 16 pixels per world unit: pixel X = 32 + 16 x, Y = 32 - 16 y,
 * the whole turned by angle about the view axis. Inside = centres with
 * 16.5 <= X < 48.5 and 16.5 <= Y < 48.5 in the square's frame (its left
 * and top edges are in, by the top-left rule). */
static uint32_t grid_v(scn_mesh *m, double X, double Y, double angle)
{
    double x = (X - 32) / 16, y = (32 - Y) / 16, ca = cos(angle), sa = sin(angle);
    return add_v(m, ca * x - sa * y, sa * x + ca * y, 0);
}

static void grid_mesh(scn_mesh *m, int jitter, double angle)
{
    mesh_new(m, 100, 200);
    uint32_t id[9][9];
    for (int j = 0; j <= 8; j++)
        for (int i = 0; i <= 8; i++) {
            double X = 16.5 + 4 * i, Y = 16.5 + 4 * j;
            int fan_corner = (i == 3 || i == 4) && (j == 3 || j == 4);
            if (jitter && i > 0 && i < 8 && j > 0 && j < 8 && !fan_corner) {
                X += (double)((int)(rng() % 257) - 128) / 256;
                Y += (double)((int)(rng() % 257) - 128) / 256;
            }
            id[j][i] = grid_v(m, X, Y, angle);
        }
    uint32_t ctr = grid_v(m, 30.5, 30.5, angle);
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++) {
            /* a top-left, b top-right, c bottom-left, d bottom-right on
             * screen; counter-clockwise seen from +z is a c d / a d b. */
            uint32_t a = id[j][i], b = id[j][i + 1], c = id[j + 1][i], d = id[j + 1][i + 1];
            if (i == 3 && j == 3) {
                add_t(m, ctr, a, c);
                add_t(m, ctr, c, d);
                add_t(m, ctr, d, b);
                add_t(m, ctr, b, a);
            } else if ((i + j) & 1) {
                add_t(m, a, c, d);
                add_t(m, a, d, b);
            } else {
                add_t(m, a, c, b);
                add_t(m, b, c, d);
            }
        }
}

static void check_square_cover(const scn_gbuf *g, double angle, const char *what)
{
    int bad = 0;
    double ca = cos(angle), sa = sin(angle);
    for (int y = 0; y < g->h; y++)
        for (int x = 0; x < g->w; x++) {
            /* Turn the centre back into the square's frame. */
            double wx = (x + 0.5 - 32) / 16, wy = (32 - (y + 0.5)) / 16;
            double ux = ca * wx + sa * wy, uy = -sa * wx + ca * wy;
            double SX = 32 + 16 * ux, SY = 32 - 16 * uy;
            int inside;
            if (angle == 0) {
                inside = SX >= 16.5 && SX < 48.5 && SY >= 16.5 && SY < 48.5;
            } else {
                /* Turned, the outline's vertices are snapped to 1/256
                 * pixel: centres within 1/100 pixel of it may go either way. */
                double m = fmin(fmin(SX - 16.5, 48.5 - SX), fmin(SY - 16.5, 48.5 - SY));
                if (fabs(m) < 0.01) continue;
                inside = m > 0;
            }
            size_t i = (size_t)y * g->w + x;
            if (g->frags[i] != (uint32_t)inside && bad++ < 5)
                printf("  %s: pixel (%d, %d) has %u fragments, expected %d\n", what, x, y, g->frags[i], inside);
            if ((g->tri[i] >= 0) != inside && bad++ < 5)
                printf("  %s: pixel (%d, %d) tri %d\n", what, x, y, g->tri[i]);
        }
    TST_EQ_INT(bad, 0);
}

static void t_fill_rule_grid(void)
{
    for (int variant = 0; variant < 6; variant++) {
        int jitter = variant & 1;
        double angle = variant >= 2 ? 0.1 + 0.37 * variant : 0;
        scn_mesh m;
        grid_mesh(&m, jitter, angle);
        scn_camera c = ortho_cam(4);
        scn_gbuf g;
        if (raster(&m, &c, 64, 64, &g)) { TST_CHECK(0, "raster failed"); scn_mesh_free(&m); return; }
        char what[64];
        snprintf(what, sizeof what, "grid jitter %d angle %g", jitter, angle);
        check_square_cover(&g, angle, what);
        scn_gbuf_free(&g);
        /* The same mesh seen from behind: every triangle is a back face. */
        scn_camera back = c;
        back.eye[2] = -5;
        if (!raster(&m, &back, 64, 64, &g)) {
            size_t n = 0;
            for (int i = 0; i < 64 * 64; i++) n += g.frags[i];
            TST_EQ_INT(n, 0);
            scn_gbuf_free(&g);
        }
        /* Perspective, looking slightly down at the square: no pixel
         * twice, no hole inside (the inner rows and columns, away from
         * the outline). */
        scn_camera p = { 1, { 0.2, 0.3, 3 }, { 0, 0, 0 }, { 0, 1, 0 }, 45, 0 };
        if (!raster(&m, &p, 64, 64, &g)) {
            size_t twice = 0, drawn = 0;
            for (int i = 0; i < 64 * 64; i++) {
                twice += g.frags[i] > 1;
                drawn += g.tri[i] >= 0;
                if ((g.tri[i] >= 0) != (g.frags[i] == 1)) twice++;
            }
            TST_EQ_INT(twice, 0);
            TST_CHECK(drawn > 500, "perspective: %zu pixels", drawn);
            scn_gbuf_free(&g);
        }
        scn_mesh_free(&m);
    }
}

/* Rectangles of two triangles with corners on the 1/256 grid (often on
 * pixel centres): covered pixels = centres with X0 <= cx < X1 and
 * Y0 <= cy < Y1 (left and top edges in). */
static void t_rectangle_exact_count(void)
{
    int bad = 0;
    for (int k = 0; k < 300; k++) {
        double X0, X1, Y0, Y1;
        for (;;) {
            int q = k % 3;     /* 0: any 1/256, 1: on centres, 2: on pixel borders */
            double a = (double)(rng() % (60 * 256)) / 256 + 1, b = (double)(rng() % (60 * 256)) / 256 + 1;
            double cc = (double)(rng() % (60 * 256)) / 256 + 1, d = (double)(rng() % (60 * 256)) / 256 + 1;
            if (q == 1) { a = floor(a) + 0.5; b = floor(b) + 0.5; cc = floor(cc) + 0.5; d = floor(d) + 0.5; }
            if (q == 2) { a = floor(a); b = floor(b); cc = floor(cc); d = floor(d); }
            X0 = fmin(a, b); X1 = fmax(a, b); Y0 = fmin(cc, d); Y1 = fmax(cc, d);
            if (X1 > X0 && Y1 > Y0) break;
        }
        scn_mesh m;
        mesh_new(&m, 4, 2);
        /* world x = (X - 32) / 16, y = (32 - Y) / 16 */
        uint32_t tl = add_v(&m, (X0 - 32) / 16, (32 - Y0) / 16, 0);
        uint32_t tr = add_v(&m, (X1 - 32) / 16, (32 - Y0) / 16, 0);
        uint32_t bl = add_v(&m, (X0 - 32) / 16, (32 - Y1) / 16, 0);
        uint32_t br = add_v(&m, (X1 - 32) / 16, (32 - Y1) / 16, 0);
        if (k & 1) { add_t(&m, tl, bl, br); add_t(&m, tl, br, tr); }
        else { add_t(&m, tl, bl, tr); add_t(&m, tr, bl, br); }
        scn_camera c = ortho_cam(4);
        scn_gbuf g;
        if (raster(&m, &c, 64, 64, &g)) { scn_mesh_free(&m); TST_CHECK(0, "raster"); return; }
        long expect = 0, got = 0;
        for (int y = 0; y < 64; y++)
            for (int x = 0; x < 64; x++) {
                double cx = x + 0.5, cy = y + 0.5;
                int in = cx >= X0 && cx < X1 && cy >= Y0 && cy < Y1;
                uint32_t fr = g.frags[y * 64 + x];
                expect += in;
                got += fr;
                if (fr != (uint32_t)in && bad++ < 5)
                    printf("  rect [%g, %g) x [%g, %g): pixel (%d, %d) frags %u, expected %d\n",
                           X0, X1, Y0, Y1, x, y, fr, in);
            }
        if (got != expect && bad++ < 5) printf("  rect: %ld fragments, expected %ld\n", got, expect);
        scn_gbuf_free(&g);
        scn_mesh_free(&m);
    }
    TST_EQ_INT(bad, 0);
}

/* ------------------------------------------------- perspective-correct */

/* A tilted plane of two big triangles; normals set to an affine function
 * of the position, so that perspective-correct interpolation must give
 * exactly N(P) at the true hit point P. */
static void t_perspective_plane(void)
{
    double n[3] = { 0.3, 0.5, 0.81 }, p0[3] = { 0.1, -0.05, -0.2 };
    unitv(n);
    double a[3], b[3], tmp[3] = { 1, 0, 0 };
    cross(n, tmp, a); unitv(a);
    cross(n, a, b);                          /* a, b span the plane */
    scn_mesh m;
    mesh_new(&m, 4, 2);
    double cs[4][2] = { { -2, -2 }, { 2, -2 }, { 2, 2 }, { -2, 2 } };
    for (int k = 0; k < 4; k++) {
        double *p = m.pos[k], *q = m.nrm[k];
        for (int e = 0; e < 3; e++) p[e] = p0[e] + cs[k][0] * a[e] + cs[k][1] * b[e];
        q[0] = 0.5 * p[0] - 0.25 * p[2] + 1; q[1] = 2 * p[1] + 0.125; q[2] = p[0] + p[1] - 3;
        m.nv++;
    }
    /* Orientation: counter-clockwise seen from the side n points to. */
    double e1[3], e2[3], cr[3];
    for (int e = 0; e < 3; e++) { e1[e] = m.pos[1][e] - m.pos[0][e]; e2[e] = m.pos[2][e] - m.pos[0][e]; }
    cross(e1, e2, cr);
    if (dot(cr, n) > 0) { add_t(&m, 0, 1, 2); add_t(&m, 0, 2, 3); }
    else { add_t(&m, 0, 2, 1); add_t(&m, 0, 3, 2); }
    scn_camera c = { 1, { 0.4, 0.3, 3 }, { 0, 0.1, 0 }, { 0.1, 1, 0 }, 50, 0 };
    int W = 97, H = 83;
    scn_gbuf g;
    if (raster(&m, &c, W, H, &g)) { scn_mesh_free(&m); TST_CHECK(0, "raster"); return; }
    int covered = 0;
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            if (g.tri[i] < 0) continue;
            covered++;
            double o[3], d[3], f[3], P[3];
            pixel_ray(&c, W, H, x, y, o, d, f);
            double diff[3] = { p0[0] - o[0], p0[1] - o[1], p0[2] - o[2] };
            double t = dot(n, diff) / dot(n, d);
            for (int e = 0; e < 3; e++) P[e] = o[e] + t * d[e];
            double N[3] = { 0.5 * P[0] - 0.25 * P[2] + 1, 2 * P[1] + 0.125, P[0] + P[1] - 3 };
            double depth = (P[0] - o[0]) * f[0] + (P[1] - o[1]) * f[1] + (P[2] - o[2]) * f[2];
            for (int e = 0; e < 3; e++) {
                worst = fmax(worst, fabs(g.pos[i][e] - P[e]) / len(P));
                worst = fmax(worst, fabs(g.nrm[i][e] - N[e]) / len(N));
            }
            worst = fmax(worst, fabs(g.depth[i] - depth) / depth);
        }
    TST_CHECK(covered > W * H / 2, "covered %d of %d", covered, W * H);
    TST_CHECK(worst <= 1e-9, "worst relative error %g", worst);
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
}

/* A ground plane y = -1 reaching behind the eye: clipped at the near
 * plane. Pixels whose ray goes down (centre below the horizon row) are
 * covered once, at the ray-plane point; the others not at all. */
static void t_near_clip(void)
{
    scn_mesh m;
    mesh_new(&m, 4, 2);
    add_v(&m, -1000, -1, -1000);
    add_v(&m, -1000, -1, 1000);
    add_v(&m, 1000, -1, 1000);
    add_v(&m, 1000, -1, -1000);
    for (int k = 0; k < 4; k++) { m.nrm[k][0] = 0; m.nrm[k][1] = 1; m.nrm[k][2] = 0; }
    add_t(&m, 0, 1, 2);           /* counter-clockwise seen from above */
    add_t(&m, 0, 2, 3);
    scn_camera c = { 1, { 0, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 }, 60, 0 };
    int W = 48, H = 40;
    scn_gbuf g;
    if (raster(&m, &c, W, H, &g)) { scn_mesh_free(&m); TST_CHECK(0, "raster"); return; }
    int bad = 0;
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            int down = y + 0.5 > H / 2.0;
            if (g.frags[i] != (uint32_t)down && bad++ < 5)
                printf("  pixel (%d, %d): %u fragments, expected %d\n", x, y, g.frags[i], down);
            if (!down || g.tri[i] < 0) continue;
            double o[3], d[3], f[3];
            pixel_ray(&c, W, H, x, y, o, d, f);
            double t = -1 / d[1];
            for (int e = 0; e < 3; e++) worst = fmax(worst, fabs(g.pos[i][e] - (o[e] + t * d[e])) / (t * len(d)));
        }
    TST_EQ_INT(bad, 0);
    TST_CHECK(worst <= 1e-9, "worst relative error %g", worst);
    scn_gbuf_free(&g);
    /* Every vertex behind the eye (the eye far out at +z, looking on
     * towards +z): nothing drawn, no crash. */
    scn_camera away = { 1, { 0, 0, 2000 }, { 0, 0, 2001 }, { 0, 1, 0 }, 60, 0 };
    if (!raster(&m, &away, W, H, &g)) {
        size_t n = 0;
        for (int i = 0; i < W * H; i++) n += g.frags[i];
        TST_EQ_INT(n, 0);
        scn_gbuf_free(&g);
    }
    scn_mesh_free(&m);
}

/* ------------------------------------------------------------ sphere */

/* Smallest distance from the origin to a triangle's plane, and the
 * largest vertex distance: the mesh lies between these spheres. */
static void shell(const scn_mesh *m, double *rin, double *rout)
{
    *rin = INFINITY;
    *rout = 0;
    for (size_t t = 0; t < m->nt; t++) {
        const double *a = m->pos[m->tri[t][0]], *b = m->pos[m->tri[t][1]], *c = m->pos[m->tri[t][2]];
        double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] }, n[3];
        cross(e1, e2, n);
        if (len(n) == 0) continue;
        unitv(n);
        *rin = fmin(*rin, fabs(dot(n, a)));
    }
    for (size_t v = 0; v < m->nv; v++) *rout = fmax(*rout, len(m->pos[v]));
}

static void t_sphere_cover_normals(void)
{
    scn_mesh m;
    char err[256];
    if (scn_mesh_builtin("sphere", 1, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    double rin, rout;
    shell(&m, &rin, &rout);
    TST_CHECK(rin > 0.99 && rout <= 1 + 1e-12, "shell %g %g", rin, rout);
    scn_camera c = { 1, { 0.3, 0.5, 4 }, { 0, 0, 0 }, { 0, 1, 0 }, 40, 0 };
    int W = 160, H = 144;
    scn_gbuf g;
    if (raster(&m, &c, W, H, &g)) { scn_mesh_free(&m); TST_CHECK(0, "raster"); return; }
    int bad = 0, inner = 0, checked_n = 0;
    double worst_excess = -1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            double o[3], d[3], f[3];
            pixel_ray(&c, W, H, x, y, o, d, f);
            unitv(d);
            /* distance from the centre to the ray */
            double oc = -dot(o, d), cl[3] = { o[0] + oc * d[0], o[1] + oc * d[1], o[2] + oc * d[2] };
            double dist = len(cl);
            /* Pixel size in world units at the sphere ~ 4.2 * 2 tan(20 deg) / 144:
             * keep 1% of a pixel clear of either shell for the snapping. */
            double margin = 1e-4;
            uint32_t fr = g.frags[i];
            if (dist < rin - margin) {
                inner++;
                if (fr != 1 && bad++ < 5) printf("  inside pixel (%d, %d): %u fragments\n", x, y, fr);
            } else if (dist > rout + margin) {
                if (fr != 0 && bad++ < 5) printf("  outside pixel (%d, %d): %u fragments\n", x, y, fr);
            } else if (fr > 1 && bad++ < 5) {
                printf("  outline pixel (%d, %d): %u fragments\n", x, y, fr);
            }
            if (g.tri[i] >= 0 && fr != 1 && bad++ < 5) printf("  pixel (%d, %d) drawn with %u\n", x, y, fr);
            /* Normals where the ray meets the sphere at no more than 60
             * degrees from its normal (dist < sin 60). The interpolated
             * normal of this mesh is the direction of the hit point P on
             * the facet (normal = position at the vertices, same weights),
             * and P lies on the ray between the unit sphere and the
             * sphere of radius rin: its direction differs from the true
             * hit H by at most acos(dist) - acos(dist / rin). */
            if (dist < 0.866 && g.tri[i] >= 0) {
                double tH = oc - sqrt(1 - dist * dist), Hp[3];
                for (int e = 0; e < 3; e++) Hp[e] = o[e] + tH * d[e];
                double nn[3] = { g.nrm[i][0], g.nrm[i][1], g.nrm[i][2] };
                unitv(nn);
                double ang = acos(fmin(1, dot(nn, Hp)));
                double bound = acos(dist) - acos(dist / rin);
                worst_excess = fmax(worst_excess, ang - bound);
                checked_n++;
            }
        }
    TST_EQ_INT(bad, 0);
    TST_CHECK(inner > 1000, "only %d inner pixels", inner);
    TST_CHECK(checked_n > 1000, "only %d normals checked", checked_n);
    /* 1e-6 rad: the 1/512-pixel extrapolation past a facet edge. */
    TST_CHECK(worst_excess <= 1e-6, "normal off its bound by %g rad", worst_excess);
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
}

/* ----------------------------------------------------------- meshes */

/* Closed and consistently oriented: every directed edge once, and its
 * reverse once. */
static int cmp_edge(const void *a, const void *b)
{
    const uint64_t *x = a, *y = b;
    return *x < *y ? -1 : *x > *y;
}

static void check_closed(const scn_mesh *m, const char *name)
{
    size_t ne = 3 * m->nt;
    uint64_t *e = malloc(ne * sizeof *e);
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++)
            e[3 * t + k] = (uint64_t)m->tri[t][k] << 32 | m->tri[t][(k + 1) % 3];
    qsort(e, ne, sizeof *e, cmp_edge);
    size_t dup = 0, unmatched = 0;
    for (size_t i = 0; i < ne; i++) {
        if (i + 1 < ne && e[i] == e[i + 1]) dup++;
        uint64_t r = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        if (!bsearch(&r, e, ne, sizeof *e, cmp_edge)) unmatched++;
    }
    TST_CHECK(dup == 0, "%s: %zu directed edges used twice", name, dup);
    TST_CHECK(unmatched == 0, "%s: %zu edges without their reverse (boundary)", name, unmatched);
    /* Outward: positive enclosed volume; each triangle's geometric
     * normal agrees with its vertex normals. */
    double vol = 0;
    size_t against = 0;
    for (size_t t = 0; t < m->nt; t++) {
        const double *a = m->pos[m->tri[t][0]], *b = m->pos[m->tri[t][1]], *c = m->pos[m->tri[t][2]];
        double bc[3], e1[3], e2[3], n[3];
        cross(b, c, bc);
        vol += dot(a, bc) / 6;
        for (int k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
        cross(e1, e2, n);
        double s[3] = { 0, 0, 0 };
        for (int q = 0; q < 3; q++)
            for (int k = 0; k < 3; k++) s[k] += m->nrm[m->tri[t][q]][k];
        if (dot(n, s) <= 0) against++;
    }
    TST_CHECK(vol > 0, "%s: volume %g", name, vol);
    TST_CHECK(against == 0, "%s: %zu triangles against their normals", name, against);
    free(e);
}

static void check_normals_unit(const scn_mesh *m, const char *name)
{
    size_t bad = 0;
    for (size_t v = 0; v < m->nv; v++) {
        double l = len(m->nrm[v]);
        if (!(fabs(l - 1) < 1e-12)) bad++;
    }
    TST_CHECK(bad == 0, "%s: %zu normals not unit (or NaN)", name, bad);
}

static void t_builtin_sphere_torus(void)
{
    char err[256];
    scn_mesh m;
    for (int det = 1; det <= 2; det++) {
        TST_EQ_INT(scn_mesh_builtin("sphere", det, &m, err, sizeof err), 0);
        check_closed(&m, "sphere");
        check_normals_unit(&m, "sphere");
        double worst = 0;
        for (size_t v = 0; v < m.nv; v++) {
            worst = fmax(worst, fabs(len(m.pos[v]) - 1));
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(m.nrm[v][k] - m.pos[v][k]));
        }
        TST_CHECK(worst < 1e-15, "sphere: normal vs position %g", worst);
        scn_mesh_free(&m);
    }
    size_t nt1 = 0;
    for (int det = 1; det <= 2; det++) {
        TST_EQ_INT(scn_mesh_builtin("torus", det, &m, err, sizeof err), 0);
        check_closed(&m, "torus");
        check_normals_unit(&m, "torus");
        if (det == 1) nt1 = m.nt;
        else TST_EQ_INT(m.nt, 4 * nt1);
        /* Exact normals: (P - C) / r, C the nearest point of the centre
         * circle (radius 0.7, axis (0, -sin 60, cos 60)). */
        double ax[3] = { 0, -sin(M_PI / 3), cos(M_PI / 3) }, worst = 0;
        for (size_t v = 0; v < m.nv; v++) {
            double *p = m.pos[v], h = dot(p, ax), q[3];
            for (int k = 0; k < 3; k++) q[k] = p[k] - h * ax[k];
            double lq = len(q);
            for (int k = 0; k < 3; k++) {
                double C = 0.7 * q[k] / lq;
                worst = fmax(worst, fabs((p[k] - C) / 0.3 - m.nrm[v][k]));
            }
        }
        TST_CHECK(worst < 1e-12, "torus normal error %g", worst);
        scn_mesh_free(&m);
    }
    TST_EQ_INT(scn_mesh_builtin("cube", 1, &m, err, sizeof err), -1);
    TST_CHECK(strstr(err, "cube") != NULL, "%s", err);
    TST_EQ_INT(scn_mesh_builtin("face", 0, &m, err, sizeof err), -1);
    TST_EQ_INT(scn_mesh_builtin("face", 99, &m, err, sizeof err), -1);
    int n = 0;
    for (const char *const *p = scn_mesh_builtin_names; *p; p++) n++;
    TST_EQ_INT(n, 3);
}

static void t_builtin_face(void)
{
    static const char *const names[8] = { "rest", "brows", "forehead", "eyes", "cheeks", "nose", "lips", "chin" };
    char err[256];
    scn_mesh m;
    if (scn_mesh_builtin("face", 1, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    TST_EQ_INT(m.nregions, 8);
    for (int k = 0; k < 8; k++) TST_EQ_STR(m.region_name[k], names[k]);
    TST_CHECK(m.nt >= 20000 && m.nt <= 40000, "face has %zu triangles", m.nt);
    check_closed(&m, "face");
    check_normals_unit(&m, "face");
    /* Every region used, on both halves for the paired ones; centroids
     * where the region's name says (the nose in front of the eyes, the
     * forehead above the brows above the eyes above the lips above the
     * chin). */
    size_t cnt[8] = { 0 }, left[8] = { 0 }, right[8] = { 0 };
    double cy[8] = { 0 }, cz[8] = { 0 };
    double lo[3] = { 1e9, 1e9, 1e9 }, hi[3] = { -1e9, -1e9, -1e9 };
    for (size_t v = 0; v < m.nv; v++)
        for (int k = 0; k < 3; k++) { lo[k] = fmin(lo[k], m.pos[v][k]); hi[k] = fmax(hi[k], m.pos[v][k]); }
    for (size_t t = 0; t < m.nt; t++) {
        int r = m.region[t];
        if (r >= 8) { TST_CHECK(0, "region %d", r); break; }
        double c[3] = { 0, 0, 0 };
        for (int q = 0; q < 3; q++)
            for (int k = 0; k < 3; k++) c[k] += m.pos[m.tri[t][q]][k] / 3;
        cnt[r]++;
        if (c[0] < -0.05) left[r]++;
        if (c[0] > 0.05) right[r]++;
        cy[r] += c[1];
        cz[r] += c[2];
    }
    for (int r = 0; r < 8; r++) {
        TST_CHECK(cnt[r] > 50, "region %s has %zu triangles", names[r], cnt[r]);
        if (cnt[r]) { cy[r] /= cnt[r]; cz[r] /= cnt[r]; }
    }
    for (int r = 1; r < 8; r++) {
        if (r == 5 || r == 6 || r == 7) continue;     /* on the middle line */
        double ratio = (double)left[r] / (double)(right[r] ? right[r] : 1);
        TST_CHECK(ratio > 0.95 && ratio < 1.05, "region %s: %zu left, %zu right", names[r], left[r], right[r]);
    }
    TST_CHECK(cy[2] > cy[1] && cy[1] > cy[3] && cy[3] > cy[5] && cy[5] > cy[6] && cy[6] > cy[7],
              "region heights %g %g %g %g %g %g", cy[2], cy[1], cy[3], cy[5], cy[6], cy[7]);
    TST_CHECK(cz[5] > cz[3] && cz[5] > cz[4], "nose depth %g eyes %g cheeks %g", cz[5], cz[3], cz[4]);
    /* Roughly unit size, taller than wide, the nose the front-most part. */
    TST_CHECK(hi[1] - lo[1] > hi[0] - lo[0], "height %g width %g", hi[1] - lo[1], hi[0] - lo[0]);
    TST_CHECK(hi[1] - lo[1] > 1.5 && hi[1] - lo[1] < 2.5, "height %g", hi[1] - lo[1]);
    TST_CHECK(fabs(hi[0] + lo[0]) < 1e-9, "not symmetric: x %g..%g", lo[0], hi[0]);
    /* Normals of the smooth surface agree with the mesh: the angle to the
     * area-weighted normal of the neighbouring triangles is small (no
     * inverted or wild normals). */
    double (*an)[3] = calloc(m.nv, sizeof *an);
    for (size_t t = 0; t < m.nt; t++) {
        const double *a = m.pos[m.tri[t][0]], *b = m.pos[m.tri[t][1]], *c = m.pos[m.tri[t][2]];
        double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] }, n[3];
        cross(e1, e2, n);
        for (int q = 0; q < 3; q++)
            for (int k = 0; k < 3; k++) an[m.tri[t][q]][k] += n[k];
    }
    double worst = 0;
    size_t close = 0;
    for (size_t v = 0; v < m.nv; v++) {
        unitv(an[v]);
        double ang = acos(fmin(1, dot(an[v], m.nrm[v])));
        worst = fmax(worst, ang);
        close += ang < 0.04;
    }
    /* The sharpest features (lip line, nose tip) span a few grid steps:
     * 0.15 rad there, 0.04 rad for 98% of the vertices. */
    TST_CHECK(worst < 0.15, "worst angle between surface and mesh normal %g rad", worst);
    TST_CHECK(close > 0.98 * m.nv, "%zu of %zu normals within 0.04 rad of the mesh's", close, m.nv);
    free(an);
    /* Seen from +z every region shows. */
    scn_camera c = { 1, { 0, 0, 4 }, { 0, 0, 0 }, { 0, 1, 0 }, 35, 0 };
    scn_gbuf g;
    if (!raster(&m, &c, 256, 256, &g)) {
        size_t px[8] = { 0 };
        for (int i = 0; i < 256 * 256; i++)
            if (g.tri[i] >= 0) px[g.region[i]]++;
        for (int r = 0; r < 8; r++) TST_CHECK(px[r] > 20, "region %s: %zu pixels", names[r], px[r]);
        scn_gbuf_free(&g);
    }
    scn_mesh_free(&m);
    /* detail 2: four times the triangles, still closed. */
    if (!scn_mesh_builtin("face", 2, &m, err, sizeof err)) {
        TST_CHECK(m.nt > 3 * 20000, "detail 2: %zu", m.nt);
        check_closed(&m, "face detail 2");
        scn_mesh_free(&m);
    }
}

/* -------------------------------------------------------------- OBJ */

static char tmpdir[512];

static const char *wfile(const char *name, const void *data, size_t n)
{
    static char paths[8][600];
    static int k;
    char *p = paths[k++ & 7];
    snprintf(p, 600, "%s/%s", tmpdir, name);
    FILE *f = fopen(p, "wb");
    if (!f) { printf("  cannot write %s\n", p); return p; }
    fwrite(data, 1, n, f);
    fclose(f);
    return p;
}
static const char *wtext(const char *name, const char *s) { return wfile(name, s, strlen(s)); }

static int make_tmpdir(void)
{
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/shadesim-geo-XXXXXX", base && *base ? base : "/tmp");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static void t_obj_good(void)
{
    if (make_tmpdir()) TST_SKIP("no temporary directory");
    char err[512];
    scn_mesh m;
    /* A cube of quads with per-face normals (v//vn), comments, groups. */
    const char *cube =
        "# cube\nmtllib x.mtl\no cube\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 2 0 0\n"
        "g sides\ns off\nusemtl red\n"
        "f 1//1 4//1 3//1 2//1\nf 5//2 6//2 7//2 8//2\nf 1//3 2//3 6//3 5//3\n"
        "f 4//4 8//4 7//4 3//4\nf 1//5 5//5 8//5 4//5\nf 2//6 3//6 7//6 6//6   # trailing\n";
    const char *p = wtext("cube.obj", cube);
    if (scn_mesh_obj(p, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); }
    else {
        TST_EQ_INT(m.nt, 12);
        TST_EQ_INT(m.nv, 24);                 /* each corner position with 3 normals */
        TST_EQ_INT(m.ignored, 5);             /* mtllib o g s usemtl */
        {   /* Geometric normals equal the given (normalized) ones. */
            size_t bad = 0;
            for (size_t t = 0; t < m.nt; t++) {
                const double *a = m.pos[m.tri[t][0]], *b = m.pos[m.tri[t][1]], *c = m.pos[m.tri[t][2]];
                double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] }, n[3];
                cross(e1, e2, n);
                unitv(n);
                for (int q = 0; q < 3; q++)
                    for (int k = 0; k < 3; k++)
                        if (fabs(m.nrm[m.tri[t][q]][k] - n[k]) > 1e-15) bad++;
            }
            TST_EQ_INT(bad, 0);
        }
        scn_mesh_free(&m);
    }
    /* Negative indices, v/vt/vn and v/vt, a pentagon, CRLF, no normals on
     * some corners. */
    const char *neg =
        "v 0 0 0\r\nv 2 0 0\r\nv 2 1 0\r\nv 1 2 0\r\nv 0 1 0\r\nvt 0 0\r\nvt 1 1\r\nvn 0 0 1\r\n"
        "f -5/-2/-1 -4/1/1 -3/2 -2/1/-1 -1/-1\r\n";
    p = wtext("neg.obj", neg);
    if (scn_mesh_obj(p, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); }
    else {
        TST_EQ_INT(m.nt, 3);                   /* pentagon fanned */
        TST_EQ_INT(m.ignored, 2);              /* the vt lines */
        /* Corners 1, 2, 4 have normal 1; corners 3 and 5 none: 5 vertices,
         * all with normal +z (the polygon is flat). Fan: 1 2 3, 1 3 4, 1 4 5. */
        TST_EQ_INT(m.nv, 5);
        double want[3][3][2] = { { { 0, 0 }, { 2, 0 }, { 2, 1 } }, { { 0, 0 }, { 2, 1 }, { 1, 2 } },
                                 { { 0, 0 }, { 1, 2 }, { 0, 1 } } };
        for (size_t t = 0; t < m.nt && t < 3; t++)
            for (int q = 0; q < 3; q++) {
                TST_NEAR(m.pos[m.tri[t][q]][0], want[t][q][0], 0);
                TST_NEAR(m.pos[m.tri[t][q]][1], want[t][q][1], 0);
                TST_NEAR(m.nrm[m.tri[t][q]][2], 1, 1e-15);
            }
        scn_mesh_free(&m);
    }
    /* No normals: area-weighted. A "roof" of two triangles sharing the
     * edge 1-2 (run in opposite directions): A = 1 2 3 in the plane z = 0,
     * B = 1 4 2 in the plane y = 0, twice as large. */
    const char *roof = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 2\nf 1 2 3\nf 1 4 2\n";
    p = wtext("roof.obj", roof);
    if (scn_mesh_obj(p, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); }
    else {
        /* Independent: cross products. A: (1,0,0) x (0,1,0) = (0,0,1)
         * (twice area 1). B: (0,0,2) x (1,0,0) = (0,2,0) (twice area 2).
         * Shared vertices 1, 2: normalize(0, 2, 1); vertex 3: (0,0,1);
         * vertex 4: (0,1,0). */
        TST_EQ_INT(m.nv, 4);
        double s5 = sqrt(5.0);
        for (size_t v = 0; v < m.nv; v++) {
            const double *q = m.pos[v], *n = m.nrm[v];
            double w[3];
            if (q[1] == 1) { w[0] = 0; w[1] = 0; w[2] = 1; }
            else if (q[2] == 2) { w[0] = 0; w[1] = 1; w[2] = 0; }
            else { w[0] = 0; w[1] = 2 / s5; w[2] = 1 / s5; }
            for (int k = 0; k < 3; k++) TST_NEAR(n[k], w[k], 1e-15);
        }
        scn_mesh_free(&m);
    }
    /* A zero normal falls back to the computed one; a degenerate face
     * gives a finite fallback normal, never NaN. */
    const char *zero = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvn 0 0 0\nf 1//1 2//1 3//1\nf 4 4 4\n";
    p = wtext("zero.obj", zero);
    if (scn_mesh_obj(p, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); }
    else {
        for (size_t v = 0; v < m.nv; v++) {
            TST_NEAR(len(m.nrm[v]), 1, 1e-15);
            if (m.pos[v][0] < 5) TST_NEAR(m.nrm[v][2], 1, 1e-15);
        }
        scn_mesh_free(&m);
    }
    /* Long lines: a comment of 200 000 characters and a polygon of 3000
     * corners on one line. */
    size_t big = 600000;
    char *s = malloc(big), *w = s;
    w[0] = '#';
    memset(w + 1, 'x', 200000);
    w += 200001;
    *w++ = '\n';
    for (int k = 0; k < 3000; k++) {
        double a = 2 * M_PI * k / 3000;
        w += sprintf(w, "v %.17g %.17g 0\n", cos(a), sin(a));
    }
    w += sprintf(w, "f");
    for (int k = 1; k <= 3000; k++) w += sprintf(w, " %d", k);
    *w++ = '\n';
    p = wfile("long.obj", s, (size_t)(w - s));
    free(s);
    if (scn_mesh_obj(p, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); }
    else {
        TST_EQ_INT(m.nt, 2998);
        TST_EQ_INT(m.nv, 3000);
        scn_mesh_free(&m);
    }
}

/* Bad files: -1 and a message starting "PATH:LINE:" (or "PATH:" for the
 * whole file); the mesh left empty. */
static void bad_obj(const char *name, const void *data, size_t n, int line, const char *word)
{
    const char *p = wfile(name, data, n);
    char err[512] = "", want[700];
    scn_mesh m;
    memset(&m, 0x55, sizeof m);
    int r = scn_mesh_obj(p, &m, err, sizeof err);
    TST_CHECK(r == -1, "%s accepted", name);
    if (line) snprintf(want, sizeof want, "%s:%d: ", p, line);
    else snprintf(want, sizeof want, "%s: ", p);
    TST_CHECK(strncmp(err, want, strlen(want)) == 0, "%s: message \"%s\", expected it to start \"%s\"", name, err, want);
    TST_CHECK(!word || strstr(err, word), "%s: message \"%s\" lacks \"%s\"", name, err, word);
    TST_CHECK(m.pos == NULL && m.nt == 0, "%s: mesh not left empty", name);
    if (!r) scn_mesh_free(&m);
}
#define BAD(name, text, line, word) bad_obj(name, text, strlen(text), line, word)

static void t_obj_bad(void)
{
    if (!*tmpdir && make_tmpdir()) TST_SKIP("no temporary directory");
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    char buf[256];
    snprintf(buf, sizeof buf, "%sf 1 2 5\n", tri);
    BAD("range.obj", buf, 4, "out of range");
    snprintf(buf, sizeof buf, "%s\n# c\nf 1 -4 2\n", tri);
    BAD("negrange.obj", buf, 6, "out of range");
    snprintf(buf, sizeof buf, "%sf 0 1 2\n", tri);
    BAD("zero.obj", buf, 4, "index 0");
    snprintf(buf, sizeof buf, "%sf 1//2 2 3\n", tri);
    BAD("nrange.obj", buf, 4, "normal");
    BAD("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "finite");
    BAD("inf.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, "finite");
    /* beyond 1e150 the camera's products overflowed: a triangle at 1e307
     * covering the view was drawn as nothing covered */
    BAD("huge.obj", "v 0 0 0\nv 1e307 0 0\nv 0 1 0\nf 1 2 3\n", 2, "too large");
    BAD("hugen.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -2e150\nf 1 2 3\n", 4, "too large");
    BAD("word.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", 2, "not a number");
    snprintf(buf, sizeof buf, "%sf 1 2\n", tri);
    BAD("two.obj", buf, 4, "corners");
    snprintf(buf, sizeof buf, "%sf 1 2 x\n", tri);
    BAD("corner.obj", buf, 4, NULL);
    snprintf(buf, sizeof buf, "%sf 1/ 2 3\n", tri);
    BAD("slash.obj", buf, 4, NULL);
    BAD("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n# no face\n", 0, "no faces");
    BAD("empty.obj", "", 0, NULL);
    BAD("fewv.obj", "v 0 0 0\nf 1 1 1\n", 0, "too few vertices");
    BAD("trunc.obj", "v 0 0 0\nv 1 0 0\nv 0 1", 3, "3 numbers");
    BAD("truncf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2", 4, "corners");
    BAD("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1 2 3 4\nf 1 2 3\n", 4, NULL);
    /* Binary garbage: bytes from a generator, first control byte on the
     * first line by construction. */
    unsigned char g[4096];
    for (size_t i = 0; i < sizeof g; i++) g[i] = (unsigned char)(rng() >> 56);
    g[0] = 'v'; g[1] = ' '; g[2] = 0x01;
    bad_obj("garbage.obj", g, sizeof g, 1, "binary");
    /* NUL inside a line. */
    bad_obj("nul.obj", "v 0 0 0\nv 1\0 0 0\n", 17, 2, "binary");
    /* Not there; a directory. */
    char err[512];
    scn_mesh m;
    char path[700];
    snprintf(path, sizeof path, "%s/missing.obj", tmpdir);
    TST_EQ_INT(scn_mesh_obj(path, &m, err, sizeof err), -1);
    TST_CHECK(strstr(err, path) != NULL, "%s", err);
    TST_EQ_INT(scn_mesh_obj(tmpdir, &m, err, sizeof err), -1);
    TST_CHECK(strstr(err, "directory") != NULL, "%s", err);
    /* A sparse file of 2 GiB: refused by its size (reading it would give
     * a "binary data" message instead, after a NUL byte). */
    snprintf(path, sizeof path, "%s/huge.obj", tmpdir);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0 && ftruncate(fd, (off_t)2 << 30) == 0) {
        close(fd);
        TST_EQ_INT(scn_mesh_obj(path, &m, err, sizeof err), -1);
        TST_CHECK(strstr(err, "MiB") != NULL && strstr(err, path) == err, "%s", err);
        unlink(path);
    } else {
        if (fd >= 0) close(fd);
        printf("  (sparse 2 GiB file not possible here: %s)\n", strerror(errno));
    }
    tst_rmtree(tmpdir);
    rmdir(tmpdir);
}

/* Random edits of good files: never a crash (the ASan run watches),
 * either a sound mesh or -1 with "PATH:" in front of the message. */
static void t_obj_fuzz(void)
{
    if (make_tmpdir()) TST_SKIP("no temporary directory");
    static const char base[] =
        "# fuzz\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nvt 0 0\nvn 0 0 1\nvn 0 0 -1\n"
        "f 1//2 4//2 3//2 2//2\nf 1/1 2/1 5/1\nf -4 -3 -1\nf 3//1 4//1 5//1\nf 4 1 5\n";
    static const char alphabet[] = "0123456789-+/ .\nfvnt#eExX\t\r";
    char buf[512], err[512], head[600];
    size_t bad = 0, accepted = 0;
    for (int k = 0; k < 400; k++) {
        size_t n = sizeof base - 1;
        memcpy(buf, base, n);
        int edits = 1 + (int)(rng() % 4);
        for (int e = 0; e < edits; e++) {
            size_t at = rng() % n;
            switch (rng() % 4) {
            case 0: buf[at] = alphabet[rng() % (sizeof alphabet - 1)]; break;
            case 1: memmove(buf + at, buf + at + 1, n - at - 1); n--; break;
            case 2: if (n + 8 < sizeof buf) { memmove(buf + at + 1, buf + at, n - at); buf[at] = alphabet[rng() % (sizeof alphabet - 1)]; n++; } break;
            default: buf[at] = (char)(rng() & 0xff); break;
            }
        }
        const char *p = wfile("fuzz.obj", buf, n);
        scn_mesh m;
        int r = scn_mesh_obj(p, &m, err, sizeof err);
        if (r == 0) {
            accepted++;
            for (size_t t = 0; t < m.nt; t++)
                for (int q = 0; q < 3; q++) if (m.tri[t][q] >= m.nv) bad++;
            for (size_t v = 0; v < m.nv; v++) {
                if (!(fabs(len(m.nrm[v]) - 1) < 1e-12)) bad++;
                for (int q = 0; q < 3; q++) if (!isfinite(m.pos[v][q])) bad++;
            }
            scn_mesh_free(&m);
        } else {
            snprintf(head, sizeof head, "%s:", p);
            if (r != -1 || strncmp(err, head, strlen(head)) || m.pos || m.nt) bad++;
        }
    }
    TST_EQ_INT(bad, 0);
    TST_CHECK(accepted > 20 && accepted < 400, "%zu of 400 edited files accepted", accepted);
    tst_rmtree(tmpdir);
    rmdir(tmpdir);
    tmpdir[0] = 0;
}

/* Vertices at NaN, infinity, 1e300 and on the eye among sound ones: those
 * triangles go, the rest is drawn, nothing non-finite in the buffer. */
static void t_raster_hostile(void)
{
    scn_mesh m;
    mesh_new(&m, 16, 16);
    uint32_t a = add_v(&m, -1, -1, 0), b = add_v(&m, 1, -1, 0), c = add_v(&m, 0, 1, 0);
    uint32_t nan_v = add_v(&m, NAN, 0, 0), inf_v = add_v(&m, 0, INFINITY, 0);
    uint32_t big = add_v(&m, 1e300, -1e300, 1e300), eye = add_v(&m, 0, 0, 4), near = add_v(&m, 1e-9, 0, 4 - 1e-12);
    add_t(&m, nan_v, a, b);
    add_t(&m, a, inf_v, b);
    add_t(&m, big, a, b);
    add_t(&m, a, b, eye);
    add_t(&m, near, a, b);
    add_t(&m, c, near, eye);
    add_t(&m, a, b, c);                      /* the sound one, drawn last */
    m.nrm[nan_v][0] = NAN;
    scn_camera cams[3] = { { 1, { 0, 0, 4 }, { 0, 0, 0 }, { 0, 1, 0 }, 50, 0 },
                           { 0, { 0, 0, 4 }, { 0, 0, 0 }, { 0, 1, 0 }, 0, 3 },
                           { 1, { 0.3, 0.2, 1e-3 }, { 0, 0, -1 }, { 0, 1, 0 }, 170, 0 } };
    for (int k = 0; k < 3; k++) {
        scn_gbuf g;
        if (raster(&m, &cams[k], 40, 30, &g)) { TST_CHECK(0, "raster"); continue; }
        size_t bad = 0, drawn = 0;
        for (int i = 0; i < 40 * 30; i++) {
            if (g.tri[i] < 0) continue;
            drawn++;
            if (g.frags[i] < 1 || !isfinite(g.depth[i])) bad++;
            for (int q = 0; q < 3; q++) if (!isfinite(g.pos[i][q]) || !isfinite(g.nrm[i][q])) bad++;
        }
        TST_EQ_INT(bad, 0);
        if (k < 2) TST_CHECK(drawn > 100, "camera %d: %zu pixels of the sound triangle", k, drawn);
        scn_gbuf_free(&g);
    }
    scn_mesh_free(&m);
}

/* Vertices far beyond the 2^40-pixel bound: the triangle is clipped, not
 * dropped. Reference: each pixel centre tested against the exact
 * (world) triangle by hand; centres on the edge are left out. */
static void t_raster_far(void)
{
    scn_mesh m;
    mesh_new(&m, 8, 4);
    /* Below the diagonal y = x of the view, corners at +-1e12. */
    uint32_t a = add_v(&m, -1e12, -1e12, 0), c = add_v(&m, 1e12, -1e12, 0), b = add_v(&m, 1e12, 1e12, 0);
    add_t(&m, a, c, b);
    scn_camera cam = ortho_cam(2);
    scn_gbuf g;
    if (raster(&m, &cam, 32, 32, &g)) { TST_CHECK(0, "raster"); scn_mesh_free(&m); return; }
    int wrong = 0, far = 0, n = 0;
    for (int py = 0; py < 32; py++)
        for (int px = 0; px < 32; px++) {
            if (px + py == 31) continue;                 /* on the edge */
            double x = (px + 0.5 - 16) / 16, y = (16 - py - 0.5) / 16;
            size_t i = (size_t)py * 32 + px;
            int want = y < x;
            if ((g.tri[i] == 0) != want) wrong++;
            if (g.tri[i] == 0) {
                n++;
                if (!(fabs(g.pos[i][0] - x) < 1e-6 && fabs(g.pos[i][1] - y) < 1e-6 && fabs(g.pos[i][2]) < 1e-6))
                    far++;
            }
        }
    TST_CHECK(wrong == 0, "%d pixel centres decided against the exact triangle", wrong);
    TST_CHECK(far == 0, "%d of %d positions off the pixel's point of the plane", far, n);
    TST_EQ_INT(n, 32 * 31 / 2);
    scn_gbuf_free(&g);
    /* The other half: the two share the clipped diagonal, and every
     * centre (those on it too) is taken exactly once. */
    uint32_t d = add_v(&m, -1e12, 1e12, 0);
    add_t(&m, a, b, d);
    if (raster(&m, &cam, 32, 32, &g)) { TST_CHECK(0, "raster"); scn_mesh_free(&m); return; }
    int twice = 0;
    for (int i = 0; i < 32 * 32; i++) twice += g.frags[i] != 1;
    TST_CHECK(twice == 0, "%d centres not taken exactly once", twice);
    scn_gbuf_free(&g);
    /* Perspective with a tiny field of view on a unit quad at z = 0: the
     * view (1e-11 wide) is all inside it, at depth 5, points ~ (0, 0, 0). */
    m.nv = m.nt = 0;
    uint32_t q0 = add_v(&m, -1, -1, 0), q1 = add_v(&m, 1, -1, 0), q2 = add_v(&m, 1, 1, 0), q3 = add_v(&m, -1, 1, 0);
    add_t(&m, q0, q1, q2);
    add_t(&m, q0, q2, q3);
    scn_camera pc = { 1, { 0, 0, 5 }, { 0, 0, 0 }, { 0, 1, 0 }, 1e-10, 0 };
    if (raster(&m, &pc, 16, 16, &g)) { TST_CHECK(0, "raster"); scn_mesh_free(&m); return; }
    int unc = 0, off = 0;
    for (int i = 0; i < 16 * 16; i++) {
        if (g.tri[i] < 0) { unc++; continue; }
        if (!(fabs(g.depth[i] - 5) < 1e-9 && fabs(g.pos[i][0]) < 1e-9 && fabs(g.pos[i][1]) < 1e-9)) off++;
    }
    TST_EQ_INT(unc, 0);
    TST_EQ_INT(off, 0);
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
}

/* ------------------------------------------------------------- spans */

static void check_spans_partition(const scn_gbuf *g, const scn_span *s, size_t n, const char *what)
{
    unsigned char *seen = calloc((size_t)g->w * g->h, 1);
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        if (k && (s[k].y < s[k - 1].y || (s[k].y == s[k - 1].y && s[k].x0 < s[k - 1].x1))) bad++;
        if (s[k].x0 >= s[k].x1 || s[k].x0 < 0 || s[k].x1 > g->w) { bad++; continue; }
        for (int x = s[k].x0; x < s[k].x1; x++) {
            size_t i = (size_t)s[k].y * g->w + x;
            if (g->tri[i] < 0 || g->region[i] != s[k].region) bad++;
            seen[i]++;
        }
    }
    for (size_t i = 0; i < (size_t)g->w * g->h; i++)
        if (seen[i] != (g->tri[i] >= 0)) bad++;
    TST_CHECK(bad == 0, "%s: %d span faults", what, bad);
    free(seen);
}

static void t_spans_synthetic(void)
{
    /* 12 x 3 by hand; foot0 = foot1 = 0: coverage and regions only. */
    static const char *rows[3] = { "..aaabb.a.cc", "aaaaaaaaaaaa", "b.b.bbba...." };
    scn_gbuf g = { 0 };
    g.w = 12; g.h = 3;
    int32_t tri[36]; uint8_t reg[36]; double dep[36], pos[36][3], nrm[36][3];
    g.tri = tri; g.region = reg; g.depth = dep; g.pos = pos; g.nrm = nrm;
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 12; x++) {
            int i = y * 12 + x;
            char ch = rows[y][x];
            tri[i] = ch == '.' ? -1 : 0;
            reg[i] = ch == '.' ? 0 : (uint8_t)(ch - 'a' + 1);
            dep[i] = ch == '.' ? INFINITY : 1 + (x == 6 ? 100 : 0);   /* a jump, ignored */
            pos[i][0] = x; pos[i][1] = -y; pos[i][2] = x * x;
            nrm[i][0] = x; nrm[i][1] = 1; nrm[i][2] = 0;
        }
    scn_span *s;
    size_t n = scn_spans(&g, &s);
    /* Runs by the rule, counted here: */
    int want[][3] = { { 0, 2, 5 }, { 0, 5, 7 }, { 0, 8, 9 }, { 0, 10, 12 }, { 1, 0, 12 },
                      { 2, 0, 1 }, { 2, 2, 3 }, { 2, 4, 7 }, { 2, 7, 8 } };
    TST_EQ_INT(n, 9);
    for (size_t k = 0; k < n && k < 9; k++) {
        TST_EQ_INT(s[k].y, want[k][0]);
        TST_EQ_INT(s[k].x0, want[k][1]);
        TST_EQ_INT(s[k].x1, want[k][2]);
    }
    check_spans_partition(&g, s, n, "synthetic");
    /* Along the full row 1: x = 3.25 between pixels 3 and 4. */
    double p[3], q[3];
    scn_span_at(&g, &s[4], 3.25, p, q);
    TST_NEAR(p[0], 3.25, 1e-15);
    TST_NEAR(p[2], 0.75 * 9 + 0.25 * 16, 1e-14);
    double nx = 3.25, l = sqrt(nx * nx + 1);
    TST_NEAR(q[0], nx / l, 1e-15);
    TST_NEAR(q[1], 1 / l, 1e-15);
    scn_span_at(&g, &s[4], 11, p, q);           /* the last pixel */
    TST_NEAR(p[0], 11, 0);
    scn_span_at(&g, &s[4], 40, p, q);           /* clamped */
    TST_NEAR(p[0], 11, 0);
    scn_span_at(&g, &s[4], -3, p, q);
    TST_NEAR(p[0], 0, 0);
    scn_span_at(&g, &s[4], NAN, p, q);
    TST_NEAR(p[0], 0, 0);
    scn_span_at(&g, &s[2], 8.5, p, q);          /* a 1-pixel span */
    TST_NEAR(p[0], 8, 0);
    free(s);

    /* Depth jumps with a footprint of 1: a step of 20 between flat parts
     * breaks; a ramp of 20 a pixel (steep, but every step like its
     * neighbours) does not; a 1-pixel spike (steps of opposite signs)
     * breaks on both sides. */
    g.foot0 = 1; g.foot1 = 0;
    for (int x = 0; x < 12; x++) {
        for (int y = 0; y < 3; y++) { tri[y * 12 + x] = 0; reg[y * 12 + x] = 0; }
        dep[x] = x < 5 ? 10 + 0.5 * x : 40 + 0.5 * x;   /* step at x = 5 */
        dep[12 + x] = 20.0 * x;                           /* ramp */
        dep[24 + x] = x == 6 ? 0 : 50;                    /* spike at 6 */
    }
    n = scn_spans(&g, &s);
    int want2[][3] = { { 0, 0, 5 }, { 0, 5, 12 }, { 1, 0, 12 }, { 2, 0, 6 }, { 2, 6, 7 }, { 2, 7, 12 } };
    TST_EQ_INT(n, 6);
    for (size_t k = 0; k < n && k < 6; k++) {
        TST_EQ_INT(s[k].y, want2[k][0]);
        TST_EQ_INT(s[k].x0, want2[k][1]);
        TST_EQ_INT(s[k].x1, want2[k][2]);
    }
    free(s);
    /* Below the threshold (8 footprints), no break: a step of 7. */
    for (int x = 0; x < 12; x++) dep[x] = x < 5 ? 10 : 17;
    n = scn_spans(&g, &s);
    TST_CHECK(n == 5 && s[0].x1 == 12, "step of 7 footprints broke a span (%zu spans)", n);
    free(s);
}

static void t_spans_rendered(void)
{
    char err[256];
    const char *names[3] = { "sphere", "torus", "face" };
    for (int k = 0; k < 3; k++) {
        scn_mesh m;
        if (scn_mesh_builtin(names[k], 1, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); continue; }
        scn_camera c = { 1, { 0, 0, 4 }, { 0, 0, 0 }, { 0, 1, 0 }, 35, 0 };
        scn_gbuf g;
        if (raster(&m, &c, 200, 180, &g)) { scn_mesh_free(&m); continue; }
        scn_span *s;
        size_t n = scn_spans(&g, &s);
        check_spans_partition(&g, s, n, names[k]);
        /* Where two spans touch in one region, the depth step between
         * them is over 8 footprints (the documented threshold). */
        size_t jumps = 0, bad = 0;
        for (size_t i = 0; i + 1 < n; i++) {
            if (s[i + 1].y != s[i].y || s[i + 1].x0 != s[i].x1) continue;
            size_t a = (size_t)s[i].y * g.w + s[i].x1 - 1;
            if (g.region[a] != g.region[a + 1]) continue;
            jumps++;
            double z = fmin(g.depth[a], g.depth[a + 1]);
            if (!(fabs(g.depth[a + 1] - g.depth[a]) > 8 * (g.foot0 + g.foot1 * z))) bad++;
        }
        TST_EQ_INT(bad, 0);
        if (k == 0) TST_EQ_INT(jumps, 0);          /* a sphere has no occlusion */
        if (k == 1) TST_CHECK(jumps > 5, "torus: %zu depth breaks (the near tube covers the far one)", jumps);
        if (k == 0) {
            /* Footprint of the perspective camera: 2 tan(fov/2) / h per unit depth. */
            TST_NEAR(g.foot1, 2 * tan(35 * M_PI / 360) / 180, 1e-15);
            TST_NEAR(g.foot0, 0, 0);
        }
        free(s);
        scn_gbuf_free(&g);
        scn_mesh_free(&m);
    }
}

/* Bad cameras and sizes: -1 with a message, nothing allocated. */
static void t_raster_bad(void)
{
    scn_mesh m;
    char err[256];
    if (scn_mesh_builtin("sphere", 1, &m, err, sizeof err)) return;
    scn_gbuf g;
    scn_camera c = { 1, { 0, 0, 4 }, { 0, 0, 4 }, { 0, 1, 0 }, 35, 0 };
    TST_EQ_INT(scn_raster(&m, &c, 10, 10, &g, err, sizeof err), -1);
    TST_CHECK(strstr(err, "eye") != NULL, "%s", err);
    c.target[2] = 0;
    c.up[1] = 0; c.up[2] = 1;
    TST_EQ_INT(scn_raster(&m, &c, 10, 10, &g, err, sizeof err), -1);
    c.up[1] = 1; c.up[2] = 0;
    c.fov_deg = 180;
    TST_EQ_INT(scn_raster(&m, &c, 10, 10, &g, err, sizeof err), -1);
    c.fov_deg = 35;
    TST_EQ_INT(scn_raster(&m, &c, 0, 10, &g, err, sizeof err), -1);
    c.perspective = 0;
    c.ortho_height = 0;
    TST_EQ_INT(scn_raster(&m, &c, 10, 10, &g, err, sizeof err), -1);
    c.ortho_height = 3;
    TST_EQ_INT(scn_raster(&m, &c, 10, 10, &g, err, sizeof err), 0);
    TST_NEAR(g.foot0, 0.3, 1e-15);
    scn_gbuf_free(&g);
    /* The eye inside the sphere: only the far side's inside faces would
     * show, and those are back faces: nothing drawn, no crash. */
    scn_camera in = { 1, { 0, 0, 0.2 }, { 0, 0, -1 }, { 0, 1, 0 }, 90, 0 };
    TST_EQ_INT(scn_raster(&m, &in, 32, 32, &g, err, sizeof err), 0);
    size_t fr = 0;
    for (int i = 0; i < 32 * 32; i++) fr += g.frags[i];
    TST_EQ_INT(fr, 0);
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
}

int main(void)
{
    TST_RUN(t_fill_rule_grid);
    TST_RUN(t_rectangle_exact_count);
    TST_RUN(t_perspective_plane);
    TST_RUN(t_near_clip);
    TST_RUN(t_sphere_cover_normals);
    TST_RUN(t_builtin_sphere_torus);
    TST_RUN(t_builtin_face);
    TST_RUN(t_obj_good);
    TST_RUN(t_obj_bad);
    TST_RUN(t_obj_fuzz);
    TST_RUN(t_spans_synthetic);
    TST_RUN(t_spans_rendered);
    TST_RUN(t_raster_bad);
    TST_RUN(t_raster_hostile);
    TST_RUN(t_raster_far);
    TST_EXIT();
}
