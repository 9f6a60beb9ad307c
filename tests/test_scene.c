/* test_scene.c - the scene testbench (testbench/study/tb_scene.c) against
 * references written here: the interval cutting and node placement redone
 * from the rules of docs/scenes.md with a Lagrange evaluation of its own,
 * a synthetic surface whose intensity is exactly quadratic (and cubic)
 * along rows, the metrics recomputed from the two images, and the bytes of
 * the outputs for one thread and several. */
#include "tst.h"
#include "tst_ref.h"
#include "testbench/study/tb_scene.h"
#include "testbench/tb.h"
#include "units/unit_net.h"
#include <stdint.h>

/* The wide formats at which the hardware is float interpolation. */
static void wide(scn_desc *d)
{
    d->nfmt = 1;
    snprintf(d->fmt[0], sizeof d->fmt[0], "all=s8.40");
    snprintf(d->fmt_width, sizeof d->fmt_width, "48");
    snprintf(d->terms, sizeof d->terms, "20");
}

static scn_mesh face;
static int face_ok;

static int load_face(void)
{
    if (face_ok) return 1;
    char err[300];
    if (scn_mesh_builtin("face", 1, &face, err, sizeof err)) { printf("  face: %s\n", err); return 0; }
    return face_ok = 1;
}

static double node_shade(const scn_desc *d, const scn_gbuf *g, const scn_span *s, double x)
{
    double p[3], n[3];
    scn_span_at(g, s, x, p, n);
    return scn_shade(&d->mat, &d->view, p, n);
}

/* The expected hardware image, redone from the rules: intervals of L from
 * the span's left end; dv = L, the span's last interval max(len - 1, 1);
 * nodes at t = 0, 1, 1/2, 1/4 or 3/4; the degree from the policy; then the
 * Lagrange polynomial through the degree's nodes at t = k/dv. Counts the
 * intervals and the distinct nodes shaded. */
static void expected(const scn_desc *d, const scn_gbuf *g, double *img, size_t *nint, size_t *nnodes)
{
    scn_span *sp;
    size_t ns = scn_spans(g, &sp);
    int L = atoi(d->L);                 /* every caller sets it */
    int n2 = d->policy == SCN_POL_CUBIC_N2 ||
             (d->policy >= SCN_POL_ADAPTIVE_REGION && d->auto_cubic_nodes == 2);
    *nint = *nnodes = 0;
    for (size_t k = 0; k < ns; k++) {
        const scn_span *s = &sp[k];
        int n = s->x1 - s->x0, nj = (n + L - 1) / L;
        (*nnodes)++;                                   /* the span's first node */
        for (int j = 0; j < nj; j++) {
            int x0 = s->x0 + j * L, len = j == nj - 1 ? n - j * L : L;
            double dv = j == nj - 1 ? (len - 1 > 1 ? len - 1 : 1) : L;
            double t[4] = { 0, 1, 0.5, n2 ? 0.75 : 0.25 }, I[4];
            (*nint)++;
            if (len == 1 && j == nj - 1) {             /* one pixel at t = 0 */
                img[(size_t)s->y * g->w + x0] = node_shade(d, g, s, x0);
                continue;
            }
            for (int i = 0; i < 4; i++) I[i] = node_shade(d, g, s, x0 + dv * t[i]);
            int deg;
            switch (d->policy) {
            case SCN_POL_LINEAR: deg = 1; break;
            case SCN_POL_QUADRATIC: deg = 2; break;
            case SCN_POL_ADAPTIVE_REGION: deg = d->region_deg[s->region] == 2 ? 2 : 3; break;
            case SCN_POL_ADAPTIVE_AUTO: deg = fabs(I[0] + I[1] - 2 * I[2]) > d->auto_threshold ? 3 : 2; break;
            default: deg = 3;
            }
            *nnodes += (size_t)deg;
            for (int p = 0; p < len; p++)
                img[(size_t)s->y * g->w + x0 + p] = tst_lagrange(t, I, deg + 1, p / dv);
        }
    }
    free(sp);
}

/* At s8.40 and a 20-term /3 network the hardware is the float
 * interpolation of the same nodes within 1e-9, for every policy, at a
 * power-of-two L and at another. */
static void test_wide_equals_float(void)
{
    if (!load_face()) { tst_fail(__FILE__, __LINE__, "no face mesh"); return; }
    static const scn_policy pols[] = { SCN_POL_LINEAR, SCN_POL_QUADRATIC, SCN_POL_CUBIC_N1, SCN_POL_CUBIC_N2,
                                       SCN_POL_ADAPTIVE_REGION, SCN_POL_ADAPTIVE_AUTO };
    static const int Ls[] = { 8, 5 };
    for (size_t pi = 0; pi < sizeof pols / sizeof pols[0]; pi++)
        for (size_t li = 0; li < 2; li++) {
            scn_desc d;
            scn_desc_default(&d);
            d.width = d.height = 64;
            d.policy = pols[pi];
            snprintf(d.L, sizeof d.L, "%d", Ls[li]);
            wide(&d);
            tb_scene_opts o = { 1, 0, NULL, NULL, 0, 0, NULL, NULL };
            tb_scene_result r;
            char err[600];
            int rc = tb_scene_render(&d, &face, &o, &r, err, sizeof err);
            TST_CHECK(rc == TB_OK, "%s L=%s: %s", scn_policy_name(d.policy), d.L, err);
            if (rc != TB_OK) continue;
            scn_gbuf g;
            TST_CHECK(!scn_raster(&face, &d.view.cam, 64, 64, &g, err, sizeof err), "%s", err);
            double *img = calloc(64 * 64, sizeof *img);
            size_t nint, nnodes;
            expected(&d, &g, img, &nint, &nnodes);
            double worst = 0;
            size_t cov = 0;
            for (size_t i = 0; i < 64 * 64; i++) {
                if (g.tri[i] < 0) { TST_CHECK(r.deg[i] == 0 && r.hw[i] == 0, "uncovered pixel %zu", i); continue; }
                cov++;
                double e = fabs(r.hw[i] - img[i]);
                if (e > worst || isnan(e)) worst = e;
            }
            TST_CHECK(worst <= 1e-9, "%s L=%s: max |hw - float| = %g", scn_policy_name(d.policy), d.L, worst);
            TST_EQ_INT(r.covered, cov);
            TST_EQ_INT(r.intervals, nint);
            TST_EQ_INT(r.nodes_shaded, nnodes);
            TST_CHECK(cov > 500, "the face covers %zu pixels of 64x64", cov);
            free(img);
            scn_gbuf_free(&g);
            tb_scene_free(&r);
        }
}

/* A synthetic surface buffer: every pixel of a w x h image covered, the
 * world position of pixel (x, y) is (x, y, 0); the shader returns a
 * polynomial of x. */
static void synth_gbuf(scn_gbuf *g, int w, int h)
{
    memset(g, 0, sizeof *g);
    size_t n = (size_t)w * h;
    g->w = w; g->h = h;
    g->tri = calloc(n, sizeof *g->tri);
    g->region = calloc(n, 1);
    g->depth = calloc(n, sizeof *g->depth);
    g->pos = calloc(n, sizeof *g->pos);
    g->nrm = calloc(n, sizeof *g->nrm);
    g->frags = calloc(n, sizeof *g->frags);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            g->depth[i] = 1;
            g->pos[i][0] = x; g->pos[i][1] = y;
            g->nrm[i][2] = 1;
            g->frags[i] = 1;
        }
}

static double poly_c[4];
static double poly_shader(void *ctx, const double pos[3], const double nrm[3])
{
    (void)ctx; (void)nrm;
    double x = pos[0];
    return ((poly_c[3] * x + poly_c[2]) * x + poly_c[1]) * x + poly_c[0];
}

/* max |hw - profile| over the image. */
static double synth_err(const scn_desc *d, int *ok)
{
    scn_gbuf g;
    synth_gbuf(&g, 45, 3);       /* spans of 45: intervals 8*5 + 5, dv = 4 in the last */
    tb_scene_opts o = { 2, 0, NULL, NULL, 0, 0, NULL, NULL };
    tb_scene_result r;
    char err[600];
    *ok = tb_scene_render_gbuf(d, &g, poly_shader, NULL, &o, &r, err, sizeof err) == TB_OK;
    TST_CHECK(*ok, "%s", err);
    double worst = 0;
    if (*ok) {
        for (size_t i = 0; i < 45 * 3; i++) {
            double e = fabs(r.hw[i] - poly_shader(NULL, g.pos[i], NULL));
            if (e > worst || isnan(e)) worst = e;
            /* the reference image is the shader at every pixel */
            TST_NEAR(r.ref[i], poly_shader(NULL, g.pos[i], NULL), 0);
        }
        TST_EQ_INT(r.covered, 45 * 3);
        TST_EQ_INT(r.spans, 3);
        TST_EQ_INT(r.intervals, 3 * 6);
        tb_scene_free(&r);
    }
    scn_gbuf_free(&g);
    return worst;
}

/* A profile quadratic in x is reproduced by degree 2 (and a cubic by
 * degree 3, both node sets); a lower degree does not reproduce it. */
static void test_polynomial_profiles(void)
{
    scn_desc d;
    scn_desc_default(&d);
    wide(&d);
    snprintf(d.L, sizeof d.L, "8");
    int ok;
    /* 0.1 + 0.8 (x/44)^2 over x = 0..44 */
    memset(poly_c, 0, sizeof poly_c);
    poly_c[0] = 0.1; poly_c[2] = 0.8 / (44.0 * 44.0);
    d.policy = SCN_POL_QUADRATIC;
    double e = synth_err(&d, &ok);
    TST_CHECK(ok && e <= 1e-9, "quadratic by degree 2: max error %g", e);
    d.policy = SCN_POL_LINEAR;
    e = synth_err(&d, &ok);
    TST_CHECK(ok && e > 1e-4, "quadratic by degree 1 should not be exact: max error %g", e);
    /* 0.5 + 0.4 ((x - 22)/22)^3 */
    double s = 1.0 / 22;
    poly_c[0] = 0.5 - 0.4; poly_c[1] = 0.4 * 3 * s; poly_c[2] = -0.4 * 3 * s * s; poly_c[3] = 0.4 * s * s * s;
    for (int p = SCN_POL_CUBIC_N1; p <= SCN_POL_CUBIC_N2; p++) {
        d.policy = (scn_policy)p;
        e = synth_err(&d, &ok);
        TST_CHECK(ok && e <= 1e-9, "cubic by %s: max error %g", scn_policy_name(d.policy), e);
    }
    d.policy = SCN_POL_QUADRATIC;
    e = synth_err(&d, &ok);
    TST_CHECK(ok && e > 1e-5, "cubic by degree 2 should not be exact: max error %g", e);
}

static uint8_t v8(double v) { return (uint8_t)(v <= 0 ? 0 : v >= 1 ? 255 : floor(255 * v + 0.5)); }

/* NMSE, PSNR, the 8-bit errors and the operation counts' weighting,
 * recomputed from the two images, at the default (narrow) formats. */
static void test_metrics(void)
{
    if (!load_face()) { tst_fail(__FILE__, __LINE__, "no face mesh"); return; }
    scn_desc d;
    scn_desc_default(&d);
    d.width = d.height = 96;
    tb_scene_opts o = { 1, 0, NULL, NULL, 0, 0, NULL, NULL };
    tb_scene_result r;
    char err[600];
    int rc = tb_scene_render(&d, &face, &o, &r, err, sizeof err);
    TST_CHECK(rc == TB_OK, "%s", err);
    if (rc != TB_OK) return;
    double se = 0, sr = 0, s8 = 0, mx = 0;
    long n = 0, diff = 0, mx8 = 0;
    for (int i = 0; i < r.w * r.h; i++) {
        if (!r.deg[i]) continue;
        double e = r.hw[i] - r.ref[i];
        se += e * e; sr += r.ref[i] * r.ref[i];
        if (fabs(e) > mx) mx = fabs(e);
        long e8 = labs((long)v8(r.hw[i]) - (long)v8(r.ref[i]));
        s8 += (double)(e8 * e8);
        if (e8) diff++;
        if (e8 > mx8) mx8 = e8;
        n++;
    }
    TST_EQ_INT(r.covered, n);
    TST_NEAR(r.nmse, se / sr, 1e-12 * (se / sr));
    TST_CHECK(r.nmse > 0, "narrow formats give some error");
    TST_NEAR(r.max_abs_err, mx, 0);
    TST_EQ_INT(r.max_err8, mx8);
    TST_NEAR(r.diff8_share, (double)diff / n, 1e-15);
    if (s8 > 0) TST_NEAR(r.psnr, 10 * log10(65025.0 * n / s8), 1e-9);
    else TST_CHECK(isinf(r.psnr), "PSNR of equal 8-bit images is infinite");
    TST_NEAR(r.clocks_per_pixel, (double)r.hwst.clocks / n, 1e-12);
    double cr = 0, ch = 0;
    for (int k = 0; k < SCN_OP__COUNT; k++) { cr += r.ops_ref[k] * d.cost[k]; ch += r.ops_hw[k] * d.cost[k]; }
    TST_NEAR(r.speedup, cr / ch, 1e-12);
    double lr = r.ops_ref[SCN_OP_DIV] + r.ops_ref[SCN_OP_SQRT] + r.ops_ref[SCN_OP_POW];
    double lh = r.ops_hw[SCN_OP_DIV] + r.ops_hw[SCN_OP_SQRT] + r.ops_hw[SCN_OP_POW];
    TST_NEAR(r.long_ref, lr, 0);
    TST_NEAR(r.long_hw, lh, 1e-12);
    TST_NEAR(r.speedup_long, lr / lh, 1e-12);
    TST_CHECK(r.speedup > 1, "interpolation is cheaper than shading every pixel: %g", r.speedup);
    TST_CHECK(r.hwst.area_ge > 0, "area");
    tb_scene_free(&r);
}

/* The operation counts of the reference, derived here by hand from the
 * operations an efficient per-pixel shader does, built from primitives:
 *   DOT   a.b of 3-vectors: 3 mul, 2 add;
 *   NORM  v / |v| given v: DOT(v, v), 1 sqrt, 1 reciprocal (div), 3 mul;
 *   SUB   a - b or a + b of 3-vectors: 3 add.
 * What varies over the frame is N and P. L of a directional light, V of
 * an orthographic camera, and everything made of them alone (H, L.V,
 * L.H = V.H, 2/V.H, a Fresnel factor of L.H) and every product of
 * constants (I0 kd, I0 ks, 1/pi, 1/(4 m^2), ...) are made once per frame
 * and cost nothing per pixel. A factor 2 is a shift, min/max/clamps free.
 * Every pixel: N normalized (NORM). Per light:
 *   N.L (DOT); (I0 kd) N.L added to the sum that starts at the ambient
 *   term (1 mul, 1 add); with ks != 0, (I0 ks) spec added (1 mul, 1 add);
 *   a point light: L = light - P (SUB) normalized (NORM);
 *   a perspective camera (once, not per light): V = eye - P, SUB + NORM;
 *   blinn: H = L + V (SUB) normalized (NORM) only when L or V varies;
 *     N.H (DOT); (N.H)^n one pow (n is any real: no squarings);
 *   phong, L and V constant: R.V = 2 (N.L)(N.V) - L.V with L.V a frame
 *     constant: N.V (DOT), 1 mul, 1 add; then ^n, one pow;
 *   phong, L or V varies: R = 2 (N.L) N - L (3 mul, SUB), R.V (DOT), pow;
 *   cook: N.H, N.V (DOT each); L.H (DOT) only when H varies;
 *     Beckmann D on c = N.H: c^2 (mul), r = 1/c^2 (div), tan^2 = r - 1
 *     (add), times -1/m^2 (mul), exp (pow), times r^2 (2 mul);
 *     D16: k c + (1 - k) (mul, add), ^16 by 4 squarings (4 mul);
 *     G = min(1, 2 (N.H) min(N.V, N.L) / V.H): 1 mul and a div, or with
 *     V.H constant 2 mul (times the constant 2/V.H);
 *     D G / ((N.L)(N.V)): 2 mul, 1 div; F varies only with H: then times F
 *     (mul) and Schlick c / (n + (1 - n) c) on c = L.H (mul, add, div);
 *   ward exact: N.H, N.V (DOT each); e on c = N.H: c^2 (mul), 1/c^2 (div),
 *     - 1 (add), times -1/a^2 (mul), exp (pow); e / sqrt((N.L)(N.V)): mul,
 *     sqrt, div. */
typedef struct opc { double add, mul, div, sqrt, pow; } opc;
static opc op_sum(opc a, opc b) { return (opc){ a.add + b.add, a.mul + b.mul, a.div + b.div, a.sqrt + b.sqrt, a.pow + b.pow }; }
static const opc DOT = { 2, 3, 0, 0, 0 }, NORM = { 2, 6, 1, 1, 0 }, SUB = { 3, 0, 0, 0, 0 };
static const opc MUL = { 0, 1, 0, 0, 0 }, ADD = { 1, 0, 0, 0, 0 }, DIV = { 0, 0, 1, 0, 0 };
static const opc SQRT = { 0, 0, 0, 1, 0 }, POW = { 0, 0, 0, 0, 1 };

static opc ops_of(const opc *parts, int n)
{
    opc t = { 0, 0, 0, 0, 0 };
    for (int i = 0; i < n; i++) t = op_sum(t, parts[i]);
    return t;
}

static void check_ops(const char *what, const scn_desc *d, opc want)
{
    double p[SCN_OP__COUNT];
    tb_scene_point_ops(d, &d->view, p);
    double w[SCN_OP__COUNT] = { want.add, want.mul, want.div, want.sqrt, want.pow };
    for (int k = 0; k < SCN_OP__COUNT; k++)
        TST_CHECK(p[k] == w[k], "%s: %s %g, by hand %g", what, scn_op_name[k], p[k], w[k]);
    TST_NEAR(tb_scene_long_ops(p), want.div + want.sqrt + want.pow, 0);
}

/* The reference's counts in eleven configurations against the derivation
 * above; the method's from the nodes, intervals and pixels a render
 * reports. */
static void test_op_counts(void)
{
    if (!load_face()) { tst_fail(__FILE__, __LINE__, "no face mesh"); return; }
    scn_desc d;
    scn_desc_default(&d);
    d.width = d.height = 80;
    d.policy = SCN_POL_LINEAR;
    d.view.cam.perspective = 0;
    d.view.nlights = 1;
    d.view.light[0].point = 0;
    d.mat.spec = SCN_SPEC_BLINN;
    d.mat.ks = 0.3;
    /* light: N.L, kd term summed; spec: ks term added */
    const opc LIGHT[] = { DOT, MUL, ADD }, SPECULAR[] = { MUL, ADD };
    opc light = ops_of(LIGHT, 3), spec = ops_of(SPECULAR, 2);
    /* (1) Blinn, directional light, orthographic: H constant: 8 add 14 mul
     * 1 div 1 sqrt 1 pow */
    const opc A[] = { NORM, light, spec, DOT, POW };
    opc a = ops_of(A, 5);
    TST_CHECK(a.add == 8 && a.mul == 14 && a.div == 1 && a.sqrt == 1 && a.pow == 1, "the derivation adds up");
    check_ops("blinn directional ortho", &d, a);
    /* (2) a point light: L = light - P normalized, and H per pixel */
    d.view.light[0].point = 1;
    d.view.light[0].v[0] = 1; d.view.light[0].v[1] = 2; d.view.light[0].v[2] = 4;
    const opc B[] = { NORM, SUB, NORM, light, spec, SUB, NORM, DOT, POW };
    check_ops("blinn point ortho", &d, ops_of(B, 9));
    /* (3) a perspective camera, directional light: V = eye - P, H */
    d.view.light[0].point = 0;
    d.view.cam.perspective = 1;
    const opc C[] = { NORM, SUB, NORM, light, spec, SUB, NORM, DOT, POW };
    check_ops("blinn directional perspective", &d, ops_of(C, 9));
    /* (4) both: V and L per pixel, H */
    d.view.light[0].point = 1;
    const opc D[] = { NORM, SUB, NORM, SUB, NORM, light, spec, SUB, NORM, DOT, POW };
    check_ops("blinn point perspective", &d, ops_of(D, 11));
    /* (5) two directional lights, orthographic: each its own N.L, N.H */
    d.view.cam.perspective = 0;
    d.view.light[0].point = 0;
    d.view.nlights = 2;
    d.view.light[1] = d.view.light[0];
    const opc E[] = { NORM, light, spec, DOT, POW, light, spec, DOT, POW };
    check_ops("blinn two directional ortho", &d, ops_of(E, 9));
    d.view.nlights = 1;
    /* (6) phong, directional, orthographic: N.V, 2 (N.L)(N.V) - L.V */
    d.mat.spec = SCN_SPEC_PHONG;
    const opc F[] = { NORM, light, spec, DOT, MUL, ADD, POW };
    check_ops("phong directional ortho", &d, ops_of(F, 7));
    /* (7) phong, point light: L, R = 2 (N.L) N - L, R.V */
    d.view.light[0].point = 1;
    const opc G[] = { NORM, SUB, NORM, light, spec, MUL, MUL, MUL, SUB, DOT, POW };
    check_ops("phong point ortho", &d, ops_of(G, 11));
    /* (8) cook, exact Beckmann, no Fresnel factor, directional, ortho */
    d.view.light[0].point = 0;
    d.mat.spec = SCN_SPEC_COOK;
    d.mat.dg = 0;
    d.mat.fresnel = SCN_FRESNEL_NONE;
    const opc H[] = { NORM, light, spec, DOT, DOT, /* N.H, N.V */
                      MUL, DIV, ADD, MUL, POW, MUL, MUL, /* D */
                      MUL, MUL, /* G */ MUL, MUL, DIV };
    check_ops("cook beckmann directional ortho", &d, ops_of(H, 17));
    /* (9) cook D16 with Schlick's F, point light: H, L.H, G and F vary */
    d.mat.dg = 16;
    d.mat.fresnel = SCN_FRESNEL_SCHLICK;
    d.view.light[0].point = 1;
    const opc I[] = { NORM, SUB, NORM, light, spec, SUB, NORM, DOT, DOT, DOT, /* H; N.H, N.V, L.H */
                      MUL, ADD, MUL, MUL, MUL, MUL, /* D16 */ MUL, DIV, /* G */ MUL, MUL, DIV,
                      MUL, /* x F */ MUL, ADD, DIV /* Schlick */ };
    check_ops("cook d16 schlick point ortho", &d, ops_of(I, 25));
    /* (10) ward exact, directional, orthographic */
    d.view.light[0].point = 0;
    d.mat.spec = SCN_SPEC_WARD;
    d.mat.dg = 0;
    d.mat.fresnel = SCN_FRESNEL_NONE;
    const opc J[] = { NORM, light, spec, DOT, DOT, MUL, DIV, ADD, MUL, POW, MUL, SQRT, DIV };
    check_ops("ward exact directional ortho", &d, ops_of(J, 13));
    /* (11) no specular term: N, N.L, the kd term */
    d.mat.ks = 0;
    const opc K[] = { NORM, light };
    check_ops("diffuse only", &d, ops_of(K, 2));

    /* The method on a render of (1). */
    d.mat.spec = SCN_SPEC_BLINN;
    d.mat.ks = 0.3;
    d.mat.dg = 0;
    double want[SCN_OP__COUNT] = { a.add, a.mul, a.div, a.sqrt, a.pow };
    tb_scene_opts o = { 1, 0, NULL, NULL, 0, 0, NULL, NULL };
    tb_scene_result r;
    char err[600];
    int rc = tb_scene_render(&d, &face, &o, &r, err, sizeof err);
    TST_CHECK(rc == TB_OK, "%s", err);
    if (rc != TB_OK) return;
    double px = (double)r.covered, nodes = (double)r.nodes_shaded / px;
    for (int k = 0; k < SCN_OP__COUNT; k++) TST_NEAR(r.ops_ref[k], want[k], 0);
    /* linear: B = I2 - I1 per interval; Horner 1 mul 1 add; t 1 mul */
    TST_NEAR(r.ops_hw[SCN_OP_ADD], nodes * want[SCN_OP_ADD] + r.intervals / px + 1, 1e-12);
    TST_NEAR(r.ops_hw[SCN_OP_MUL], nodes * want[SCN_OP_MUL] + 2, 1e-12);
    TST_NEAR(r.ops_hw[SCN_OP_DIV], nodes * want[SCN_OP_DIV], 1e-12);
    TST_NEAR(r.ops_hw[SCN_OP_SQRT], nodes * want[SCN_OP_SQRT], 1e-12);
    TST_NEAR(r.ops_hw[SCN_OP_POW], nodes * want[SCN_OP_POW], 1e-12);
    /* long operations: 3 per pixel; the method's only at its nodes */
    TST_NEAR(r.long_ref, 3, 0);
    TST_NEAR(r.long_hw, 3 * nodes, 1e-12);
    TST_NEAR(r.speedup_long, px / (double)r.nodes_shaded, 1e-12);
    tb_scene_free(&r);
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *b = NULL;
    size_t cap = 0;
    *len = 0;
    for (;;) {
        if (*len + 65536 > cap) { cap = cap * 2 + 65536; b = realloc(b, cap); }
        size_t k = fread(b + *len, 1, cap - *len, f);
        if (!k) break;
        *len += k;
    }
    fclose(f);
    return b;
}

/* One thread or three: the same images, JSON and files, byte for byte. */
static void test_jobs_same_bytes(void)
{
    if (!load_face()) { tst_fail(__FILE__, __LINE__, "no face mesh"); return; }
    scn_desc d;
    scn_desc_default(&d);
    d.width = 100; d.height = 90;
    d.policy = SCN_POL_ADAPTIVE_AUTO;
    char dir[2][64];
    for (int k = 0; k < 2; k++) {
        snprintf(dir[k], sizeof dir[k], "/tmp/shadesim_test_scene.%d.%d", (int)getpid(), k);
        tb_scene_opts o = { k ? 3 : 1, 0, NULL, NULL, 0, 0, NULL, NULL };
        tb_scene_result r;
        char err[600];
        int rc = tb_scene_render(&d, &face, &o, &r, err, sizeof err);
        TST_CHECK(rc == TB_OK, "%s", err);
        if (rc != TB_OK) return;
        TST_CHECK(!tb_scene_write(&d, &r, dir[k], err, sizeof err), "%s", err);
        tb_scene_free(&r);
    }
    static const char *const files[] = { "ref.png", "hw.png", "degree.png", "region.png", "scene.json" };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char p0[128], p1[128];
        snprintf(p0, sizeof p0, "%s/%s", dir[0], files[i]);
        snprintf(p1, sizeof p1, "%s/%s", dir[1], files[i]);
        size_t n0, n1;
        char *b0 = slurp(p0, &n0), *b1 = slurp(p1, &n1);
        TST_CHECK(b0 && b1 && n0 == n1 && !memcmp(b0, b1, n0), "%s differs between -j 1 and -j 3", files[i]);
        TST_CHECK(b0 && n0 > 8, "%s written", files[i]);
        free(b0); free(b1);
    }
    for (int k = 0; k < 2; k++) { tst_rmtree(dir[k]); rmdir(dir[k]); }
}

/* The hardware keys are the unit's parameters: the scene file keeps a
 * number or a name as written, and tb_scene_unit sets them through the
 * unit's setters (round and overflow by the simulator's mode names).
 * The ranges here are docs/scenes.md's (L any 2..64, terms 1..20, series
 * paper or quarter, schedules paper, mac, pipe, round trunc, half-up,
 * even, overflow wrap, sat), written by hand; terms of a policy whose
 * unit has no /3 network (linear: span1) is judged all the same. */
static void test_hw_keys_are_the_units(void)
{
    static const struct { const char *key, *value; int ok; const char *what; } C[] = {
        { "L", "2", 1, NULL },       { "L", "64", 1, NULL },      { "L", "1", 0, "2..64" },
        { "L", "65", 0, "2..64" },   { "L", "-3", 0, "2..64" },   { "terms", "1", 1, NULL },
        { "terms", "20", 1, NULL },  { "terms", "0", 0, "1..20" }, { "terms", "21", 0, "1..20" },
        { "series", "quarter", 1, NULL }, { "series", "half", 0, "paper quarter" },
        { "schedule", "pipe", 1, NULL }, { "schedule", "fast", 0, "paper, mac, pipe" },
        { "width", "20", 1, NULL },  { "round", "even", 1, NULL }, { "round", "nearest", 0, "trunc, half-up, even" },
        { "overflow", "sat", 1, NULL }, { "overflow", "clamp", 0, "wrap, sat" },
    };
    static const char *const pols[] = { "linear", "quadratic", "cubic-n1", "cubic-n2", "adaptive-region", "adaptive-auto" };
    for (size_t p = 0; p < sizeof pols / sizeof pols[0]; p++)
        for (size_t i = 0; i < sizeof C / sizeof C[0]; i++) {
            scn_desc d;
            char err[300] = "";
            scn_desc_default(&d);
            TST_EQ_INT(scn_desc_set(&d, "policy", pols[p], err, sizeof err), 0);
            TST_CHECK(scn_desc_set(&d, C[i].key, C[i].value, err, sizeof err) == 0,
                      "the scene file takes %s %s: %s", C[i].key, C[i].value, err);
            const unit_desc *u;
            unit_cfg cfg;
            unit_fmts f;
            int rc = tb_scene_unit(&d, &u, &cfg, &f, err, sizeof err);
            TST_CHECK(rc == (C[i].ok ? 0 : -1), "%s, %s %s: rc %d (%s)", pols[p], C[i].key, C[i].value, rc, err);
            if (!C[i].ok) {
                TST_CHECK(strstr(err, C[i].key) && strstr(err, C[i].what), "%s, %s %s: \"%s\" should name %s and %s",
                          pols[p], C[i].key, C[i].value, err, C[i].key, C[i].what);
            } else if (!strcmp(C[i].key, "L")) {
                TST_EQ_INT(cfg.L, atoi(C[i].value));
            } else if (!strcmp(C[i].key, "terms")) {
                TST_EQ_INT(cfg.terms, atoi(C[i].value));
            } else if (!strcmp(C[i].key, "series")) {
                TST_EQ_INT(cfg.series, DIV3_QUARTER);
            } else if (!strcmp(C[i].key, "width")) {
                TST_EQ_INT(cfg.width, 20);
            } else if (!strcmp(C[i].key, "round")) {
                TST_EQ_INT(cfg.rnd, SIM_RND_EVEN);
            } else if (!strcmp(C[i].key, "overflow")) {
                TST_EQ_INT(cfg.ovf, SIM_OVF_SAT);
            }
        }
    /* A scene that sets none of them (the description holds "") gets the
     * unit's defaults: L 8, terms 3, the paper's series, width 16, trunc,
     * wrap, its first schedule (unit_cfg_default of each policy's unit,
     * from its descriptor's rows). */
    for (size_t p = 0; p < sizeof pols / sizeof pols[0]; p++) {
        scn_desc d;
        char err[300];
        scn_desc_default(&d);
        TST_EQ_INT(scn_desc_set(&d, "policy", pols[p], err, sizeof err), 0);
        TST_CHECK(!*d.L && !*d.terms && !*d.series && !*d.schedule && !*d.fmt_width && !*d.rnd && !*d.ovf,
                  "%s: hardware keys set by default", pols[p]);
        const unit_desc *u;
        unit_cfg cfg, def;
        unit_fmts f;
        TST_EQ_INT(tb_scene_unit(&d, &u, &cfg, &f, err, sizeof err), 0);
        unit_cfg_default(unit_find("span23"), &def);
        TST_EQ_INT(cfg.L, def.L);
        TST_EQ_INT(cfg.terms, def.terms);
        TST_EQ_INT(cfg.series, def.series);
        unit_cfg_default(u, &def);
        TST_EQ_INT(cfg.width, def.width);
        TST_EQ_INT(cfg.rnd, def.rnd);
        TST_EQ_INT(cfg.ovf, def.ovf);
        TST_EQ_INT(cfg.schedule, 0);
        TST_EQ_INT(cfg.L, 8);
        TST_EQ_INT(cfg.terms, 3);
        TST_EQ_INT(cfg.width, 16);              /* docs/scenes.md: width 16, trunc, wrap */
        TST_EQ_INT(cfg.rnd, SIM_RND_TRUNC);
        TST_EQ_INT(cfg.ovf, SIM_OVF_WRAP);
    }
}

int main(void)
{
    TST_RUN(test_wide_equals_float);
    TST_RUN(test_polynomial_profiles);
    TST_RUN(test_metrics);
    TST_RUN(test_op_counts);
    TST_RUN(test_jobs_same_bytes);
    TST_RUN(test_hw_keys_are_the_units);
    if (face_ok) scn_mesh_free(&face);
    TST_EXIT();
}
