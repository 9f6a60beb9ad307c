/* test_scene_shade.c - reference shading (scn_shade) against formulas
 * written out here, and the scene description file: defaults, every key,
 * write -> read round trip, each class of bad input, scn_desc_set. */
#include "tests/tst.h"
#include "scene/scene.h"
#include <errno.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char tdir[512];

/* ------------------------------------------------ vector helpers (test) */

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void norm(double v[3])
{
    double l = sqrt(dot(v, v));
    v[0] /= l; v[1] /= l; v[2] /= l;
}

static void half(const double l[3], const double v[3], double h[3])
{
    h[0] = l[0] + v[0]; h[1] = l[1] + v[1]; h[2] = l[2] + v[2];
    norm(h);
}

static double clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

/* A view with one directional light and an orthographic camera on +z. */
static scn_view view1(double lx, double ly, double lz)
{
    scn_view v;
    memset(&v, 0, sizeof v);
    v.cam.eye[2] = 4.0;
    v.cam.up[1] = 1.0;
    v.cam.fov_deg = 30.0;
    v.cam.ortho_height = 2.0;
    v.nlights = 1;
    v.light[0].v[0] = lx; v.light[0].v[1] = ly; v.light[0].v[2] = lz;
    v.light[0].intensity = 1.0;
    return v;
}

static scn_material mat0(void)
{
    scn_material m;
    memset(&m, 0, sizeof m);
    m.ambient = 0.05;
    m.kd = 0.6;
    m.m = 0.3;
    m.alpha = 0.3;
    m.fresnel_n = 2.0;
    return m;
}

/* ------------------------------------------------------------ shading */

static void shade_diffuse(void)
{
    scn_material m = mat0();
    m.ks = 0.0;
    double L[3] = { -1, 2, 2 };         /* length 3 on purpose: scn_shade normalizes */
    scn_view v = view1(L[0], L[1], L[2]);
    double pos[3] = { 0.1, 0.2, 0.3 };
    double n[3] = { 0.3, 0.4, 0.5 };
    norm(n);
    norm(L);
    TST_NEAR(scn_shade(&m, &v, pos, n), 0.05 + 0.6 * dot(n, L), 1e-14);
    /* Intensity scales the light's part, not the ambient. */
    v.light[0].intensity = 0.5;
    TST_NEAR(scn_shade(&m, &v, pos, n), 0.05 + 0.3 * dot(n, L), 1e-14);
    /* Light behind the surface: ambient only. */
    double nb[3] = { 0, 0, -1 };
    v.light[0].v[0] = 0; v.light[0].v[1] = 0; v.light[0].v[2] = 1;
    TST_NEAR(scn_shade(&m, &v, pos, nb), 0.05, 1e-15);
    /* Two lights add. */
    scn_view w = view1(1, 0, 0);
    w.nlights = 2;
    w.light[1] = (scn_light){ 0, { 0, 1, 0 }, 0.5 };
    double n2[3] = { 1, 1, 1 };
    norm(n2);
    TST_NEAR(scn_shade(&m, &w, pos, n2), 0.05 + 0.6 * n2[0] + 0.3 * n2[1], 1e-14);
}

static void shade_blinn(void)
{
    scn_material m = mat0();
    m.ks = 0.35;
    m.shininess = 24;
    m.spec = SCN_SPEC_BLINN;
    double L[3] = { -0.48, 0.6, 0.64 };
    scn_view v = view1(L[0], L[1], L[2]);
    double V[3] = { 0, 0, 1 }, pos[3] = { 0.3, -0.2, 0.1 };
    for (int k = 0; k < 5; k++) {
        double n[3] = { -0.2 + 0.1 * k, 0.3 - 0.05 * k, 1 };
        norm(n);
        double H[3];
        half(L, V, H);
        double want = 0.05 + 0.6 * dot(n, L) + 0.35 * pow(dot(n, H), 24);
        TST_NEAR(scn_shade(&m, &v, pos, n), clamp01(want), 1e-13);
    }
}

static void shade_phong(void)
{
    scn_material m = mat0();
    m.ks = 0.5;
    m.shininess = 10;
    m.spec = SCN_SPEC_PHONG;
    double L[3] = { 0.6, 0, 0.8 };
    scn_view v = view1(L[0], L[1], L[2]);
    double V[3] = { 0, 0, 1 }, pos[3] = { 0, 0, 0 };
    double n[3] = { 0.1, 0.05, 1 };
    norm(n);
    double nl = dot(n, L);
    double R[3] = { 2 * nl * n[0] - L[0], 2 * nl * n[1] - L[1], 2 * nl * n[2] - L[2] };
    double rv = dot(R, V);
    TST_CHECK(rv > 0, "geometry: R.V = %g", rv);
    TST_NEAR(scn_shade(&m, &v, pos, n), clamp01(0.05 + 0.6 * nl + 0.5 * pow(rv, 10)), 1e-13);
    /* R.V < 0: no highlight. */
    double n2[3] = { -0.6, 0, 0.8 };
    nl = dot(n2, L);            /* 0.28 > 0 */
    TST_NEAR(scn_shade(&m, &v, pos, n2), 0.05 + 0.6 * nl, 1e-14);
}

static void shade_point_light(void)
{
    scn_material m = mat0();
    m.ks = 0.4;
    m.shininess = 16;
    m.spec = SCN_SPEC_BLINN;
    scn_view v = view1(0, 0, 1);
    v.light[0] = (scn_light){ 1, { 1.0, 2.0, 3.0 }, 0.8 };
    double pos[3] = { 0.5, -0.5, 0.2 }, n[3] = { 0.2, 0.3, 1 };
    norm(n);
    double L[3] = { 1.0 - 0.5, 2.0 + 0.5, 3.0 - 0.2 }, V[3] = { 0, 0, 1 }, H[3];
    norm(L);
    half(L, V, H);
    double want = 0.05 + 0.8 * (0.6 * dot(n, L) + 0.4 * pow(dot(n, H), 16));
    TST_NEAR(scn_shade(&m, &v, pos, n), clamp01(want), 1e-13);
    /* A different point sees the light from another direction. */
    double pos2[3] = { -0.5, 0.5, 0.0 };
    double L2[3] = { 1.5, 1.5, 3.0 };
    norm(L2);
    half(L2, V, H);
    want = 0.05 + 0.8 * (0.6 * dot(n, L2) + 0.4 * pow(dot(n, H), 16));
    TST_NEAR(scn_shade(&m, &v, pos2, n), clamp01(want), 1e-13);
}

static void shade_view_vector(void)
{
    scn_material m = mat0();
    m.kd = 0.0;
    m.ambient = 0.0;
    m.ks = 1.0;
    m.shininess = 8;
    m.spec = SCN_SPEC_BLINN;
    scn_view v = view1(0, 0, 1);
    v.cam.eye[0] = 1.0; v.cam.eye[1] = 0.0; v.cam.eye[2] = 3.0;
    v.cam.target[0] = 0.0; v.cam.target[1] = 0.5; v.cam.target[2] = 0.0;
    double pos[3] = { -0.7, 0.4, 0.3 }, n[3] = { 0, 0, 1 }, L[3] = { 0, 0, 1 }, H[3];
    /* orthographic: V = eye - target everywhere */
    double Vo[3] = { 1.0, -0.5, 3.0 };
    norm(Vo);
    half(L, Vo, H);
    double ortho = pow(dot(n, H), 8);
    TST_NEAR(scn_shade(&m, &v, pos, n), ortho, 1e-13);
    /* perspective: V = eye - pos */
    v.cam.perspective = 1;
    double Vp[3] = { 1.0 + 0.7, 0.0 - 0.4, 3.0 - 0.3 };
    norm(Vp);
    half(L, Vp, H);
    double persp = pow(dot(n, H), 8);
    TST_NEAR(scn_shade(&m, &v, pos, n), persp, 1e-13);
    TST_CHECK(fabs(ortho - persp) > 1e-3, "the two views should differ: %g %g", ortho, persp);
}

static void shade_clamp(void)
{
    scn_material m = mat0();
    m.ambient = 0.5;
    m.kd = 1.0;
    m.ks = 1.0;
    m.shininess = 1;
    m.spec = SCN_SPEC_BLINN;
    scn_view v = view1(0, 0, 1);
    double pos[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
    TST_NEAR(scn_shade(&m, &v, pos, n), 1.0, 0);        /* 2.5 unclamped */
    /* Light just below the horizon: the specular term is 0 too (not only
     * the diffuse), so the result is the ambient alone. */
    m.ambient = 0.1;
    v.light[0].v[0] = 1; v.light[0].v[1] = 0; v.light[0].v[2] = -0.01;
    TST_NEAR(scn_shade(&m, &v, pos, n), 0.1, 1e-15);
    /* A zero-length normal gives a finite result in [0, 1]. */
    double z[3] = { 0, 0, 0 };
    double r = scn_shade(&m, &v, pos, z);
    TST_CHECK(r >= 0 && r <= 1, "zero normal: %g", r);
}

/* The Cook-Torrance term written out independently. */
static double cook_direct(double m, int g, int fresnel, double fn,
                          const double L[3], const double N[3], const double V[3])
{
    double H[3];
    half(L, V, H);
    double nl = dot(N, L), nv = dot(N, V), nh = dot(N, H), vh = dot(V, H), lh = dot(L, H);
    if (nl <= 0 || nv <= 0) return 0;
    double D;
    if (g == 0) {
        double t2 = (1 - nh * nh) / (nh * nh);
        D = exp(-t2 / (m * m)) / (4 * m * m * pow(nh, 4));
    } else {
        double base = 1 + (2 / (m * m) - 4) / g * (nh - 1);
        D = base > 0 ? pow(base, g) / (4 * m * m) : 0;
    }
    double F = 1;
    if (fresnel == 1) F = lh / (fn - fn * lh + lh);
    if (fresnel == 2) F = 2 * lh / (1.25 * pow(fn - fn * lh + 1.25 * lh, 2));
    double G = 1;
    if (2 * nh * nv / vh < G) G = 2 * nh * nv / vh;
    if (2 * nh * nl / vh < G) G = 2 * nh * nl / vh;
    return F * D * G / (M_PI * nl * nv);
}

static void shade_cook(void)
{
    static const int gs[] = { 0, 4, 8, 16 };
    static const double ms[] = { 0.2, 0.3, 0.5 };
    scn_material mt = mat0();
    mt.ambient = 0.02;
    mt.kd = 0.3;
    mt.ks = 0.25;
    mt.spec = SCN_SPEC_COOK;
    double L[3] = { -0.3, 0.4, 1 }, V[3] = { 0, 0, 1 }, pos[3] = { 0, 0, 0 };
    norm(L);
    scn_view v = view1(L[0], L[1], L[2]);
    int tested = 0, nonzero = 0;
    for (int gi = 0; gi < 4; gi++)
        for (int fr = 0; fr < 3; fr++)
            for (int mi = 0; mi < 3; mi++)
                for (int k = 0; k < 6; k++) {
                    mt.dg = gs[gi];
                    mt.fresnel = (scn_fresnel)fr;
                    mt.fresnel_n = 3.0;
                    mt.m = ms[mi];
                    double n[3] = { -0.25 + 0.1 * k, 0.3 - 0.08 * k, 1 };
                    norm(n);
                    double s = cook_direct(mt.m, mt.dg, fr, 3.0, L, n, V);
                    double want = clamp01(0.02 + 0.3 * dot(n, L) + 0.25 * s);
                    TST_NEAR(scn_shade(&mt, &v, pos, n), want, 1e-12 * (1 + want));
                    tested++;
                    nonzero += s > 1e-3;
                }
    TST_CHECK(nonzero > tested / 3, "too few highlights tested: %d of %d", nonzero, tested);
    /* Normalization: head-on (N = L = V), ks = 1, m = 0.3, no ambient or
     * diffuse: F = G = 1, D = 1/(4 m^2), so 1/(4 pi m^2) = 0.884. */
    scn_material p = mt;
    p.ambient = 0; p.kd = 0; p.ks = 1; p.m = 0.3; p.dg = 0; p.fresnel = SCN_FRESNEL_NONE;
    scn_view h = view1(0, 0, 1);
    double nz[3] = { 0, 0, 1 };
    TST_NEAR(scn_shade(&p, &h, pos, nz), 1.0 / (4 * M_PI * 0.09), 1e-12);
    TST_CHECK(scn_shade(&p, &h, pos, nz) > 0.5 && scn_shade(&p, &h, pos, nz) < 1.0,
              "peak of order 1 below the clamp");
}

static void shade_ward(void)
{
    scn_material mt = mat0();
    mt.ambient = 0;
    mt.kd = 0.2;
    mt.ks = 0.3;
    mt.spec = SCN_SPEC_WARD;
    double L[3] = { 0.5, 0.2, 1 }, V[3] = { 0, 0, 1 }, pos[3] = { 0, 0, 0 };
    norm(L);
    scn_view v = view1(L[0], L[1], L[2]);
    for (int form = 0; form < 2; form++)
        for (int ai = 0; ai < 3; ai++)
            for (int k = 0; k < 5; k++) {
                double a = 0.15 + 0.1 * ai;
                mt.alpha = a;
                mt.dg = form ? 16 : 0;
                double n[3] = { 0.05 * k, 0.02 * k, 1 }, H[3];
                norm(n);
                half(L, V, H);
                double nh = dot(n, H), nl = dot(n, L), nv = dot(n, V), e;
                if (form == 0) e = exp(-((1 - nh * nh) / (nh * nh)) / (a * a));
                else {
                    double b = 1 + (nh - 1) / (8 * a * a);
                    e = b > 0 ? pow(b, 16) : 0;
                }
                double s = e / (4 * M_PI * a * a * sqrt(nl * nv));
                double want = clamp01(0.2 * nl + 0.3 * s);
                TST_NEAR(scn_shade(&mt, &v, pos, n), want, 1e-12);
            }
    /* Viewer below the surface: no Ward highlight. */
    double n[3] = { 1, 0, 0.05 };
    norm(n);
    mt.dg = 0;
    mt.kd = 0;
    scn_view w = view1(1, 0, 0);
    w.cam.eye[0] = -4; w.cam.eye[2] = 0;    /* V = (-1, 0, 0): N.V < 0 */
    TST_NEAR(scn_shade(&mt, &w, pos, n), 0.0, 0);
}

/* ---------------------------------------------------------- scene files */

static const char *write_tmp(const char *name, const char *text)
{
    static char path[700];
    snprintf(path, sizeof path, "%s/%s", tdir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return NULL;
    fputs(text, f);
    fclose(f);
    return path;
}

static void desc_defaults(void)
{
    scn_desc d;
    scn_desc_default(&d);
    TST_EQ_INT(d.version, 1);
    TST_EQ_STR(d.mesh, "face");
    TST_EQ_INT(d.width, 512);
    TST_EQ_INT(d.height, 512);
    TST_EQ_INT(d.view.cam.perspective, 0);
    TST_EQ_INT(d.view.nlights, 1);
    TST_EQ_INT(d.view.light[0].point, 0);
    const double *l = d.view.light[0].v;
    TST_CHECK(l[0] < 0 && l[1] > 0 && l[2] > 0, "light from upper left front");
    TST_NEAR(dot(l, l), 1.0, 1e-15);
    TST_NEAR(d.view.light[0].intensity, 1.0, 0);
    TST_NEAR(d.mat.ambient, 0.05, 0);
    TST_NEAR(d.mat.kd, 0.6, 0);
    TST_NEAR(d.mat.ks, 0.35, 0);
    TST_NEAR(d.mat.shininess, 24, 0);
    TST_EQ_INT(d.mat.spec, SCN_SPEC_BLINN);
    TST_EQ_INT(d.policy, SCN_POL_CUBIC_N1);
    /* the unit's configuration: not set, its defaults (test_scene.c) */
    TST_EQ_STR(d.L, "");
    TST_EQ_STR(d.terms, "");
    TST_EQ_STR(d.series, "");
    TST_EQ_STR(d.fmt_width, "");
    TST_EQ_STR(d.rnd, "");
    TST_EQ_STR(d.ovf, "");
    TST_EQ_STR(d.schedule, "");
    TST_EQ_INT(d.nfmt, 0);
    for (int r = 0; r < SCN_MAX_REGIONS; r++)
        TST_EQ_INT(d.region_deg[r], (r == 2 || r == 4 || r == 7) ? 2 : 3);
    TST_NEAR(d.cost[SCN_OP_ADD], 1, 0);
    TST_NEAR(d.cost[SCN_OP_DIV], 4, 0);
    TST_NEAR(d.cost[SCN_OP_POW], 8, 0);
    TST_EQ_STR(scn_op_name[SCN_OP_SQRT], "sqrt");
    TST_EQ_STR(scn_policy_name(SCN_POL_ADAPTIVE_REGION), "adaptive-region");
    /* Held-out view: eye turned 20 degrees about up (+y) around the
     * target, same distance; the light turned to the other side. */
    const double *e = d.view.cam.eye, *he = d.heldout.cam.eye;
    double r0 = sqrt(dot(e, e)), r1 = sqrt(dot(he, he));
    TST_NEAR(r1, r0, 1e-12);
    TST_NEAR(he[1], e[1], 1e-12);
    TST_NEAR(acos(dot(e, he) / (r0 * r1)) * 180 / M_PI, 20.0, 1e-9);
    TST_EQ_INT(d.heldout.nlights, 1);
    TST_CHECK(d.heldout.light[0].v[0] > 0, "held-out light from the right: %g",
              d.heldout.light[0].v[0]);
    TST_NEAR(d.heldout.light[0].v[1], l[1], 1e-12);
    /* Built-ins. */
    scn_desc b;
    TST_EQ_INT(scn_desc_builtin("face", &b), 0);
    TST_EQ_STR(b.mesh, "face");
    TST_EQ_INT(scn_desc_builtin("torus", &b), 0);
    TST_EQ_STR(b.mesh, "torus");
    TST_EQ_INT(b.view.cam.perspective, 1);
    TST_EQ_INT(scn_desc_builtin("sphere", &b), 0);
    TST_EQ_STR(b.mesh, "sphere");
    TST_EQ_INT(scn_desc_builtin("cube", &b), -1);
}

/* A file that sets every key to something other than its default. */
static const char *EVERY =
    "# every key\n"
    "\n"
    "   shadesim-scene   1   # version\n"
    "mesh sub/head model.obj\n"
    "detail 3\n"
    "resolution 640x480\n"
    "camera perspective\n"
    "eye 1 2 3\n"
    "target 0.5, -0.5, 0\n"
    "up 0 0 1\n"
    "fov 45.5\n"
    "ortho-height 3.25\n"
    "light point 1 1 4 0.7\n"
    "light directional 0 0 2\n"
    "heldout-eye -3 2 1\n"
    "heldout-target 0.25 0 0\n"
    "heldout-light directional 1 0 0 0.5\n"
    "ambient 0.1\n"
    "kd 0.5\n"
    "ks 0.45\n"
    "shininess 60\n"
    "specular cook\n"
    "distribution d8\n"
    "ward-form poly16\n"
    "roughness 0.25\n"
    "ward-alpha 0.2\n"
    "fresnel mschlick\n"
    "fresnel-n 5\n"
    "policy adaptive-region\n"
    "region-degree 0 2\n"
    "region-degree 4 3\n"
    "auto-threshold 0.125\n"
    "auto-nodes n2\n"
    "L 12\n"
    "terms 5\n"
    "series quarter\n"
    "width 20\n"
    "fmt all=s3.17 y=s2.18\n"
    "fmt a=u1.15\n"
    "round even\n"
    "overflow sat\n"
    "schedule mac\n"
    "unit sub/my span.dp\n"
    "cost div=8 pow=16\n"
    "cost sqrt=5.5";                    /* no final newline */

static void check_every(const scn_desc *d, const char *meshpath)
{
    TST_EQ_STR(d->mesh, meshpath);
    TST_EQ_INT(d->detail, 3);
    TST_EQ_INT(d->width, 640);
    TST_EQ_INT(d->height, 480);
    const scn_camera *c = &d->view.cam;
    TST_EQ_INT(c->perspective, 1);
    TST_NEAR(c->eye[0], 1, 0); TST_NEAR(c->eye[1], 2, 0); TST_NEAR(c->eye[2], 3, 0);
    TST_NEAR(c->target[0], 0.5, 0); TST_NEAR(c->target[1], -0.5, 0); TST_NEAR(c->target[2], 0, 0);
    TST_NEAR(c->up[2], 1, 0);
    TST_NEAR(c->fov_deg, 45.5, 0);
    TST_NEAR(c->ortho_height, 3.25, 0);
    TST_EQ_INT(d->view.nlights, 2);                 /* the default light replaced */
    TST_EQ_INT(d->view.light[0].point, 1);
    TST_NEAR(d->view.light[0].v[2], 4, 0);
    TST_NEAR(d->view.light[0].intensity, 0.7, 0);
    TST_EQ_INT(d->view.light[1].point, 0);
    TST_NEAR(d->view.light[1].v[2], 1, 0);          /* normalized */
    TST_NEAR(d->view.light[1].intensity, 1, 0);
    TST_NEAR(d->heldout.cam.eye[0], -3, 0);
    TST_NEAR(d->heldout.cam.target[0], 0.25, 0);
    TST_EQ_INT(d->heldout.cam.perspective, 1);
    TST_NEAR(d->heldout.cam.fov_deg, 45.5, 0);
    TST_EQ_INT(d->heldout.nlights, 1);
    TST_NEAR(d->heldout.light[0].v[0], 1, 0);
    TST_NEAR(d->heldout.light[0].intensity, 0.5, 0);
    TST_NEAR(d->mat.ambient, 0.1, 0);
    TST_NEAR(d->mat.kd, 0.5, 0);
    TST_NEAR(d->mat.ks, 0.45, 0);
    TST_NEAR(d->mat.shininess, 60, 0);
    TST_EQ_INT(d->mat.spec, SCN_SPEC_COOK);
    TST_EQ_INT(d->mat.dg, 8);                       /* cook's, not ward-form's */
    TST_EQ_INT(d->ward_dg, 16);
    TST_NEAR(d->mat.m, 0.25, 0);
    TST_NEAR(d->mat.alpha, 0.2, 0);
    TST_EQ_INT(d->mat.fresnel, SCN_FRESNEL_MSCHLICK);
    TST_NEAR(d->mat.fresnel_n, 5, 0);
    TST_EQ_INT(d->policy, SCN_POL_ADAPTIVE_REGION);
    TST_EQ_INT(d->region_deg[0], 2);
    TST_EQ_INT(d->region_deg[4], 3);
    TST_EQ_INT(d->region_deg[2], 2);
    TST_NEAR(d->auto_threshold, 0.125, 0);
    TST_EQ_INT(d->auto_cubic_nodes, 2);
    TST_EQ_STR(d->L, "12");
    TST_EQ_STR(d->terms, "5");
    TST_EQ_STR(d->series, "quarter");
    TST_EQ_STR(d->fmt_width, "20");
    TST_EQ_INT(d->nfmt, 3);
    TST_EQ_STR(d->fmt[0], "all=s3.17");
    TST_EQ_STR(d->fmt[1], "y=s2.18");
    TST_EQ_STR(d->fmt[2], "a=u1.15");
    TST_EQ_STR(d->rnd, "even");
    TST_EQ_STR(d->ovf, "sat");
    TST_EQ_STR(d->schedule, "mac");
    TST_NEAR(d->cost[SCN_OP_ADD], 1, 0);
    TST_NEAR(d->cost[SCN_OP_DIV], 8, 0);
    TST_NEAR(d->cost[SCN_OP_SQRT], 5.5, 0);
    TST_NEAR(d->cost[SCN_OP_POW], 16, 0);
}

static void desc_every_key(void)
{
    const char *p = write_tmp("every.scene", EVERY);
    TST_CHECK(p != NULL, "cannot write");
    if (!p) return;
    scn_desc d;
    char err[600], want[800];
    int rc = scn_desc_read(p, &d, err, sizeof err);
    TST_EQ_INT(rc, 0);
    if (rc) { printf("  %s\n", err); return; }
    snprintf(want, sizeof want, "%s/sub/head model.obj", tdir);
    check_every(&d, want);
    snprintf(want, sizeof want, "%s/sub/my span.dp", tdir);   /* unit: a path, relative to the file's folder */
    TST_EQ_STR(d.unit, want);
    /* Every key of the table appears in the test file. */
    for (int k = 0; scn_desc_keys[k]; k++) {
        char pat[64];
        snprintf(pat, sizeof pat, "\n%s ", scn_desc_keys[k]);
        TST_CHECK(strstr(EVERY, pat) != NULL, "key %s not tested", scn_desc_keys[k]);
    }
}

static int write_desc(const scn_desc *d, const char *name, char *text, size_t cap)
{
    char path[700];
    snprintf(path, sizeof path, "%s/%s", tdir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    int rc = scn_desc_write(f, d);
    fclose(f);
    f = fopen(path, "rb");
    size_t n = fread(text, 1, cap - 1, f);
    text[n] = 0;
    fclose(f);
    return rc;
}

/* Field by field (struct padding may differ). */
static int cam_eq(const scn_camera *a, const scn_camera *b)
{
    return a->perspective == b->perspective && !memcmp(a->eye, b->eye, sizeof a->eye) &&
           !memcmp(a->target, b->target, sizeof a->target) && !memcmp(a->up, b->up, sizeof a->up) &&
           a->fov_deg == b->fov_deg && a->ortho_height == b->ortho_height;
}

static int view_eq(const scn_view *a, const scn_view *b)
{
    if (!cam_eq(&a->cam, &b->cam) || a->nlights != b->nlights) return 0;
    for (int i = 0; i < a->nlights; i++)
        if (a->light[i].point != b->light[i].point || a->light[i].intensity != b->light[i].intensity
            || memcmp(a->light[i].v, b->light[i].v, sizeof a->light[i].v)) return 0;
    return 1;
}

static int mat_eq(const scn_material *a, const scn_material *b)
{
    return a->ambient == b->ambient && a->kd == b->kd && a->ks == b->ks &&
           a->shininess == b->shininess && a->spec == b->spec && a->dg == b->dg &&
           a->m == b->m && a->alpha == b->alpha && a->fresnel == b->fresnel &&
           a->fresnel_n == b->fresnel_n;
}

static void desc_roundtrip(void)
{
    static char t1[20000], t2[20000];
    const char *srcs[3] = { NULL, EVERY, NULL };
    for (int s = 0; s < 3; s++) {
        scn_desc d, e;
        char err[600], p2[700];
        if (s == 0) scn_desc_default(&d);
        else if (s == 1) {
            const char *p = write_tmp("rt.scene", srcs[1]);
            TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), 0);
        } else {
            scn_desc_builtin("torus", &d);
            /* odd values that must survive %.17g */
            d.mat.ks = 0.1 + 0.2;
            d.view.light[0].v[0] = 1.0 / 3.0;
            d.view.nlights = 0;
            scn_desc_sync(&d);
            /* directions normalized when set must read back bit for bit */
            for (int i = 1; i <= 3; i++) {
                char txt[64];
                snprintf(txt, sizeof txt, "directional %d %d %d 0.%d", i, 2 * i + 1, 7 - i, i);
                TST_EQ_INT(scn_desc_set(&d, "light", txt, err, sizeof err), 0);
                TST_EQ_INT(scn_desc_set(&d, "heldout-light", txt, err, sizeof err), 0);
            }
            TST_EQ_INT(d.heldout.nlights, 3);
        }
        TST_EQ_INT(write_desc(&d, "w1.scene", t1, sizeof t1), 0);
        snprintf(p2, sizeof p2, "%s/w1.scene", tdir);
        int rc = scn_desc_read(p2, &e, err, sizeof err);
        TST_EQ_INT(rc, 0);
        if (rc) { printf("  %s\n", err); continue; }
        if (s == 1) check_every(&e, d.mesh);
        /* Field by field, the parts a renderer uses. */
        TST_EQ_STR(e.mesh, d.mesh);
        TST_CHECK(view_eq(&e.view, &d.view), "view differs (case %d)", s);
        TST_CHECK(view_eq(&e.heldout, &d.heldout), "held-out view differs (case %d)", s);
        TST_CHECK(mat_eq(&e.mat, &d.mat), "material differs (case %d)", s);
        TST_EQ_INT(e.heldout_given, d.heldout_given);
        TST_EQ_INT(e.nfmt, d.nfmt);
        TST_CHECK(!memcmp(e.cost, d.cost, sizeof d.cost), "cost differs");
        TST_CHECK(!memcmp(e.region_deg, d.region_deg, sizeof d.region_deg), "regions differ");
        TST_EQ_STR(e.L, d.L);
        TST_EQ_STR(e.terms, d.terms);
        TST_EQ_STR(e.series, d.series);
        TST_EQ_INT(e.width, d.width);
        TST_EQ_STR(e.fmt_width, d.fmt_width);
        TST_EQ_STR(e.rnd, d.rnd);
        TST_EQ_STR(e.ovf, d.ovf);
        TST_EQ_STR(e.schedule, d.schedule);
        /* And the text is a fixed point. */
        TST_EQ_INT(write_desc(&e, "w2.scene", t2, sizeof t2), 0);
        TST_CHECK(!strcmp(t1, t2), "write(read(write(d))) != write(d) (case %d)", s);
    }
}

/* Each bad line: the message starts "PATH:LINE:" and says what. */
static void desc_errors(void)
{
    static const struct { const char *body; int line; const char *what; } C[] = {
        { "fvo 30\n", 2, "did you mean \"fov\"" },
        { "resolutoin 4x4\n", 2, "did you mean \"resolution\"" },
        { "widht 14\n", 2, "did you mean \"width\"" },   /* a swap: not "light" (a tie before) */
        { "lumi\xc3\xa8re 1\n", 2, "unknown key \"lumi\xc3\xa8re\"" },   /* UTF-8 kept (it was "lumi??re") */
        { "x\xffy 2\n", 2, "unknown key \"x\xffy\"" },                 /* the CLI writes \xff */
        { "\n# c\nzzzzzzzzzzzz 1\n", 4, "unknown key" },
        { "eye 1 2\n", 2, "3 values" },
        { "eye 1 2 3 4\n", 2, "3 values" },
        { "kd\n", 2, "1 value" },
        { "kd abc\n", 2, "not a finite number" },
        { "kd nan\n", 2, "not a finite number" },
        { "kd inf\n", 2, "not a finite number" },
        { "kd 0.5x\n", 2, "not a finite number" },
        { "kd 1.5\n", 2, "out of range" },
        { "L 8.5\n", 2, "not an integer" },    /* its range is the unit's: test_scene.c */
        { "width 3\n", 2, "out of range" },
        { "resolution 0x10\n", 2, "out of range" },
        { "resolution 4097x10\n", 2, "out of range" },
        { "resolution 10\n", 2, "not WxH" },
        { "fov 180\n", 2, "out of range" },
        { "ortho-height 0\n", 2, "> 0" },
        { "up 0 0 0\n", 2, "length 0" },
        { "camera fisheye\n", 2, "not one of ortho, perspective" },
        { "specular lambert\n", 2, "not one of" },
        { "distribution d32\n", 2, "not one of" },
        { "policy cubic\n", 2, "not one of" },
        { "fresnel fast\n", 2, "not one of" },
        { "region-degree 16 2\n", 2, "out of range" },
        { "region-degree 3 4\n", 2, "out of range" },
        { "fmt y=s2\n", 2, "NAME=sI.F" },
        { "fmt Y=s2.14\n", 2, "NAME=sI.F" },
        { "fmt y=s40.40\n", 2, "width" },
        { "fmt y=u63.1\n", 2, "width" },
        { "cost mul\n", 2, "OP=W" },
        { "cost mod=3\n", 2, "not one of" },
        { "cost div=-1\n", 2, "out of range" },
        { "light directional 0 0 0\n", 2, "length 0" },
        { "light spot 0 0 1\n", 2, "not one of" },
        { "light point 0 0 1 -1\n", 2, "out of range" },
        { "light directional 1 0 0\nlight directional 1 0 0\nlight directional 1 0 0\n"
          "light directional 1 0 0\nlight directional 0 1 0\n", 6, "too many lights" },
        { "heldout-eye 1 2\n", 2, "values" },
        { "detail 9\n", 2, "out of range" },
        { "eye 0 0 0\n", 2, "same point" },
        { "mesh\n", 2, "mesh" },
        { "shadesim-scene 1\n", 2, "version line" },
    };
    char err[600], want[800], name[32];
    for (size_t i = 0; i < sizeof C / sizeof C[0]; i++) {
        char body[600];
        snprintf(body, sizeof body, "shadesim-scene 1\n%s", C[i].body);
        snprintf(name, sizeof name, "bad%zu.scene", i);
        const char *p = write_tmp(name, body);
        scn_desc d;
        scn_desc_default(&d);
        snprintf(d.L, sizeof d.L, "33");           /* must stay untouched */
        err[0] = 0;
        int rc = scn_desc_read(p, &d, err, sizeof err);
        TST_EQ_INT(rc, -1);
        snprintf(want, sizeof want, "%s:%d: ", p, C[i].line);
        TST_CHECK(!strncmp(err, want, strlen(want)), "case %zu: \"%s\" should start \"%s\"",
                  i, err, want);
        TST_CHECK(strstr(err, C[i].what) != NULL, "case %zu: \"%s\" should say \"%s\"", i, err,
                  C[i].what);
        TST_EQ_STR(d.L, "33");
    }
    /* A duplicate key is fine: the last wins. */
    const char *p = write_tmp("dup.scene", "shadesim-scene 1\nresolution 8x8\nresolution 16x4\n");
    scn_desc d;
    TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), 0);
    TST_EQ_INT(d.width, 16);
    TST_EQ_INT(d.height, 4);
    /* A missing file. */
    snprintf(want, sizeof want, "%s/none.scene", tdir);
    TST_EQ_INT(scn_desc_read(want, &d, err, sizeof err), -1);
    TST_CHECK(!strncmp(err, want, strlen(want)), "%s", err);
}

static void desc_version(void)
{
    static const struct { const char *body; int line; const char *what; } C[] = {
        { "", 1, "shadesim-scene 1" },
        { "# only a comment\n\n", 3, "shadesim-scene 1" },
        { "mesh face\n", 1, "not a shadesim scene" },
        { "shadesim-scene 2\nmesh face\n", 1, "version 2" },
        { "\n# x\nshadesim-scene 17\n", 3, "version 17" },
        { "shadesim-scene\n", 1, "version line" },
        { "shadesim-scene 1 1\n", 1, "version line" },
    };
    char err[600], want[800];
    for (size_t i = 0; i < sizeof C / sizeof C[0]; i++) {
        const char *p = write_tmp("ver.scene", C[i].body);
        scn_desc d;
        TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), -1);
        snprintf(want, sizeof want, "%s:%d: ", p, C[i].line);
        TST_CHECK(!strncmp(err, want, strlen(want)), "case %zu: \"%s\" vs \"%s\"", i, err, want);
        TST_CHECK(strstr(err, C[i].what) != NULL, "case %zu: \"%s\" should say \"%s\"", i, err,
                  C[i].what);
    }
    /* CR LF line ends and tabs are fine. */
    const char *q = write_tmp("crlf.scene", "shadesim-scene 1\r\nkd\t0.5\r\nmesh sphere\r\n");
    scn_desc c;
    TST_EQ_INT(scn_desc_read(q, &c, err, sizeof err), 0);
    TST_NEAR(c.mat.kd, 0.5, 0);
    TST_EQ_STR(c.mesh, "sphere");
    /* Just the version line: the defaults. */
    const char *p = write_tmp("ver.scene", "shadesim-scene 1");
    scn_desc d, def;
    TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), 0);
    scn_desc_default(&def);
    TST_CHECK(mat_eq(&d.mat, &def.mat), "defaults");
    TST_CHECK(view_eq(&d.view, &def.view) && view_eq(&d.heldout, &def.heldout), "defaults");
}

/* Garbage never crashes; long lines and NUL bytes are reported. */
static void desc_garbage(void)
{
    char err[600], path[700];
    snprintf(path, sizeof path, "%s/g.scene", tdir);
    uint32_t s = 12345;
    for (int k = 0; k < 200; k++) {
        FILE *f = fopen(path, "wb");
        if (!f) break;
        if (k % 2) fputs("shadesim-scene 1\n", f);
        int n = (k * 37) % 3000;
        for (int i = 0; i < n; i++) {
            s = s * 1103515245u + 12345u;
            int c = (s >> 16) & 0xFF;
            if (k % 4 == 1) c = " \nabcdefgiklmnoprstuwxyz0123456789.-=,#"[c % 38];
            fputc(c, f);
        }
        fclose(f);
        scn_desc d;
        int rc = scn_desc_read(path, &d, err, sizeof err);
        TST_CHECK(rc == 0 || !strncmp(err, path, strlen(path)), "k=%d: %s", k, err);
    }
    /* A line over the limit. */
    FILE *f = fopen(path, "wb");
    fputs("shadesim-scene 1\nmesh ", f);
    for (int i = 0; i < 10000; i++) fputc('a', f);
    fputs("\nkd 0.1\n", f);
    fclose(f);
    scn_desc d;
    TST_EQ_INT(scn_desc_read(path, &d, err, sizeof err), -1);
    char want[800];
    snprintf(want, sizeof want, "%s:2: line longer", path);
    TST_CHECK(!strncmp(err, want, strlen(want)), "%s", err);
    f = fopen(path, "wb");
    fputs("shadesim-scene 1\nkd 0.1\nks 0", f);
    fputc(0, f);
    fputs(".2\n", f);
    fclose(f);
    TST_EQ_INT(scn_desc_read(path, &d, err, sizeof err), -1);
    snprintf(want, sizeof want, "%s:3: NUL", path);
    TST_CHECK(!strncmp(err, want, strlen(want)), "%s", err);
    /* A path that fits the line but not the mesh field. */
    f = fopen(path, "wb");
    fputs("shadesim-scene 1\nmesh /", f);
    for (int i = 0; i < 300; i++) fputc('b', f);
    fclose(f);
    TST_EQ_INT(scn_desc_read(path, &d, err, sizeof err), -1);
    TST_CHECK(strstr(err, "too long") != NULL, "%s", err);
}

static void desc_mesh_paths(void)
{
    char err[600], want[800];
    scn_desc d;
    const char *p = write_tmp("m1.scene", "shadesim-scene 1\nmesh torus\n");
    TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), 0);
    TST_EQ_STR(d.mesh, "torus");
    p = write_tmp("m2.scene", "shadesim-scene 1\nmesh /abs/x.obj\n");
    TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), 0);
    TST_EQ_STR(d.mesh, "/abs/x.obj");
    p = write_tmp("m3.scene", "shadesim-scene 1\nmesh ./face  # a file named face\n");
    TST_EQ_INT(scn_desc_read(p, &d, err, sizeof err), 0);
    snprintf(want, sizeof want, "%s/./face", tdir);
    TST_EQ_STR(d.mesh, want);
    /* scn_desc_set: relative to the working folder, unchanged. */
    TST_EQ_INT(scn_desc_set(&d, "mesh", "m/x.obj", err, sizeof err), 0);
    TST_EQ_STR(d.mesh, "m/x.obj");
}

static void desc_set(void)
{
    scn_desc d;
    char err[600];
    scn_desc_default(&d);
    double he0 = d.heldout.cam.eye[0];
    TST_EQ_INT(scn_desc_set(&d, "kd", "0.25", err, sizeof err), 0);
    TST_NEAR(d.mat.kd, 0.25, 0);
    TST_EQ_INT(scn_desc_set(&d, "eye", "0,0,10", err, sizeof err), 0);
    TST_NEAR(d.view.cam.eye[2], 10, 0);
    /* The derived held-out eye follows: 10 sin 20 deg. */
    TST_NEAR(d.heldout.cam.eye[0], 10 * sin(20 * M_PI / 180), 1e-12);
    TST_CHECK(d.heldout.cam.eye[0] != he0, "held-out eye did not follow");
    /* light appends */
    TST_EQ_INT(scn_desc_set(&d, "light", "point 0 0 3", err, sizeof err), 0);
    TST_EQ_INT(d.view.nlights, 2);
    TST_EQ_INT(d.heldout.nlights, 2);
    TST_EQ_INT(scn_desc_set(&d, "light", "none", err, sizeof err), 0);
    TST_EQ_INT(d.view.nlights, 0);
    /* explicit held-out values stop following */
    TST_EQ_INT(scn_desc_set(&d, "heldout-eye", "1 1 1", err, sizeof err), 0);
    TST_EQ_INT(scn_desc_set(&d, "eye", "0 0 7", err, sizeof err), 0);
    TST_NEAR(d.heldout.cam.eye[0], 1, 0);
    TST_EQ_INT(scn_desc_set(&d, "heldout-eye", "auto", err, sizeof err), 0);
    TST_NEAR(d.heldout.cam.eye[0], 7 * sin(20 * M_PI / 180), 1e-12);
    /* dg follows the model whichever key comes first */
    TST_EQ_INT(scn_desc_set(&d, "distribution", "d16", err, sizeof err), 0);
    TST_EQ_INT(d.mat.dg, 0);                   /* still blinn */
    TST_EQ_INT(scn_desc_set(&d, "specular", "cook", err, sizeof err), 0);
    TST_EQ_INT(d.mat.dg, 16);
    TST_EQ_INT(scn_desc_set(&d, "specular", "ward", err, sizeof err), 0);
    TST_EQ_INT(d.mat.dg, 0);
    TST_EQ_INT(scn_desc_set(&d, "ward-form", "poly16", err, sizeof err), 0);
    TST_EQ_INT(d.mat.dg, 16);
    /* fmt: appends, none clears */
    TST_EQ_INT(scn_desc_set(&d, "fmt", "y=s2.14", err, sizeof err), 0);
    TST_EQ_INT(scn_desc_set(&d, "fmt", "a=s3.13", err, sizeof err), 0);
    TST_EQ_INT(d.nfmt, 2);
    TST_EQ_INT(scn_desc_set(&d, "fmt", "none", err, sizeof err), 0);
    TST_EQ_INT(d.nfmt, 0);
    /* errors: "KEY: what", d unchanged */
    scn_desc before = d;
    TST_EQ_INT(scn_desc_set(&d, "kd", "2", err, sizeof err), -1);
    TST_CHECK(!strncmp(err, "kd: ", 4), "%s", err);
    TST_EQ_INT(scn_desc_set(&d, "shinyness", "2", err, sizeof err), -1);
    TST_CHECK(!strncmp(err, "shinyness: ", 11) && strstr(err, "shininess"), "%s", err);
    TST_EQ_INT(scn_desc_set(&d, "eye", "1 2", err, sizeof err), -1);
    TST_CHECK(!strncmp(err, "eye: ", 5), "%s", err);
    TST_EQ_INT(scn_desc_set(&d, "eye", "0 0 0", err, sizeof err), -1);
    TST_CHECK(!strncmp(err, "eye: ", 5) && strstr(err, "same point"), "%s", err);
    TST_EQ_INT(scn_desc_set(&d, "policy", "", err, sizeof err), -1);
    TST_CHECK(!strncmp(err, "policy: ", 8), "%s", err);
    TST_CHECK(mat_eq(&before.mat, &d.mat) && view_eq(&before.view, &d.view), "changed on error");
    for (int i = 0; i < 4; i++) scn_desc_set(&d, "light", "directional 0 1 0", err, sizeof err);
    TST_EQ_INT(d.view.nlights, 4);
    TST_EQ_INT(scn_desc_set(&d, "light", "directional 0 1 0", err, sizeof err), -1);
    TST_CHECK(strstr(err, "too many lights") != NULL, "%s", err);
}

int main(void)
{
    const char *t = getenv("TMPDIR");
    snprintf(tdir, sizeof tdir, "%s/test_scene_shade.XXXXXX", t && *t ? t : "/tmp");
    if (!mkdtemp(tdir)) { printf("FAIL test_scene_shade: mkdtemp: %s\n", strerror(errno)); return 1; }
    TST_RUN(shade_diffuse);
    TST_RUN(shade_blinn);
    TST_RUN(shade_phong);
    TST_RUN(shade_point_light);
    TST_RUN(shade_view_vector);
    TST_RUN(shade_clamp);
    TST_RUN(shade_cook);
    TST_RUN(shade_ward);
    TST_RUN(desc_defaults);
    TST_RUN(desc_every_key);
    TST_RUN(desc_roundtrip);
    TST_RUN(desc_errors);
    TST_RUN(desc_version);
    TST_RUN(desc_garbage);
    TST_RUN(desc_mesh_paths);
    TST_RUN(desc_set);
    tst_rmtree(tdir);
    rmdir(tdir);
    TST_EXIT();
}
