/* tb_factor_scene.c - the Fig. 1 comparison of the factorization paper
 * (Romanyuk, Vyatkin, Voitko, Romanyuk 2020) on a scene: the specular
 * term of the isotropic Ward BRDF
 *   (a) evaluated exactly at the vertices and interpolated over each
 *       triangle (Gouraud: the approach the paper compares with),
 *   (b) factorized, evaluated per pixel through the simulated hf_lookup
 *       unit (its ROM maps, fixed point, cycle by cycle),
 *   (c) evaluated exactly per pixel (the reference),
 * with the NMSE of (a) and (b) against (c) and an image of each.
 * Specular only (kd = 0), one directional or point light of the scene;
 * the local frame's tangent is normalize(y_world x n) (any tangent will
 * do for an isotropic BRDF). */
#include "testbench/study/tb_factor_scene.h"
#include "testbench/tb.h"
#include "scene/scene.h"
#include "vectors/ref_factor.h"
#include "vectors/vectors.h"
#include "base/base_out.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void sub3(const double a[3], const double b[3], double o[3]) { for (int k = 0; k < 3; k++) o[k] = a[k] - b[k]; }
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void norm3(double a[3]) { double l = sqrt(dot3(a, a)); if (l > 0) for (int k = 0; k < 3; k++) a[k] /= l; }
static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1]; o[1] = a[2] * b[0] - a[0] * b[2]; o[2] = a[0] * b[1] - a[1] * b[0];
}

/* d0, di and h in the local frame of normal n at pos; 0 if either
 * direction is below the surface. */
static int local_dirs(const scn_view *v, const double pos[3], const double nrm[3], double d0[3], double di[3],
                      double h[3])
{
    double n[3] = { nrm[0], nrm[1], nrm[2] }, t[3], s[3], up[3] = { 0, 1, 0 }, vw[3], lw[3];
    norm3(n);
    cross3(up, n, t);
    if (dot3(t, t) < 1e-12) { double ax[3] = { 1, 0, 0 }; cross3(ax, n, t); }
    norm3(t);
    cross3(n, t, s);
    sub3(v->cam.eye, pos, vw);
    norm3(vw);
    const scn_light *L = &v->light[0];
    if (L->point) sub3(L->v, pos, lw); else memcpy(lw, L->v, sizeof lw);
    norm3(lw);
    d0[0] = dot3(vw, t); d0[1] = dot3(vw, s); d0[2] = dot3(vw, n);
    di[0] = dot3(lw, t); di[1] = dot3(lw, s); di[2] = dot3(lw, n);
    if (d0[2] <= 0 || di[2] <= 0) return 0;
    for (int k = 0; k < 3; k++) h[k] = d0[k] + di[k];
    norm3(h);
    return 1;
}

/* Exact specular radiance: f(d0, di) (N.L) I0. */
static double exact_at(const rf_brdf *b, const scn_view *v, const double pos[3], const double nrm[3])
{
    double d0[3], di[3], h[3];
    if (!local_dirs(v, pos, nrm, d0, di, h)) return 0;
    return rf_brdf_eval(b, d0, di) * di[2] * v->light[0].intensity;
}

static int write_png(const char *path, const double *img, int w, int h, double scale, char *err, size_t len)
{
    uint8_t *pix = malloc((size_t)w * h);
    if (!pix) base_out_of_memory();
    for (int i = 0; i < w * h; i++) {
        double t = img[i] / scale;
        pix[i] = (uint8_t)lrint(255 * (t < 0 ? 0 : t > 1 ? 1 : t));
    }
    uint8_t *png = NULL;
    size_t n = 0;
    int rc = scn_png_encode(w, h, 1, pix, &png, &n);
    free(pix);
    if (rc) { snprintf(err, len, "out of memory"); return -1; }
    rc = base_out_write_all(path, png, n, err, len);
    free(png);
    return rc;
}

int tb_factor_scene(const char *scene, int L, double alpha, int width, int res, const char *dir,
                    tb_factor_scene_result *r, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    scn_desc d;
    if (scn_desc_builtin(scene, &d)) { snprintf(err, errlen, "unknown built-in scene '%s'", scene); return -1; }
    if (res > 0) d.width = d.height = res;
    scn_mesh m;
    if (scn_mesh_builtin(d.mesh, d.detail, &m, err, errlen)) return -1;
    scn_gbuf g;
    if (scn_raster(&m, &d.view.cam, d.width, d.height, &g, err, errlen)) { scn_mesh_free(&m); return -1; }
    rf_brdf b;
    rf_brdf_init(&b, "ward", err, errlen);
    b.ax = b.ay = alpha;
    const rf_maps *maps = rf_ward_maps(L, alpha);
    const unit_desc *u = unit_find("hf_lookup");
    const vec_model *vm = u ? u->ref : NULL;
    int W = g.w, H = g.h, rc = -1;
    size_t np = (size_t)W * H;
    double *img[3] = { calloc(np, sizeof(double)), calloc(np, sizeof(double)), calloc(np, sizeof(double)) };
    size_t *pix_of = malloc(np * sizeof *pix_of);
    vec_set vs;
    vec_set_init(&vs);
    tb_result tr;
    memset(&tr, 0, sizeof tr);
    if (!maps || !u || !vm) { snprintf(err, errlen, "hf_lookup or its maps are not available"); goto out; }
    if (!img[0] || !img[1] || !img[2] || !pix_of) base_out_of_memory();
    vec_params vp;
    vec_params_default(&vp);
    vp.L = L; vp.alpha = alpha;
    vec_set_header(&vs, vm, &vp);
    double scale = maps->lam_scale * maps->lam_scale * maps->pi_scale;
    size_t nitems = 0;
    for (size_t i = 0; i < np; i++) {
        int t = g.tri[i];
        if (t < 0) continue;
        r->covered++;
        /* (c) exact per pixel */
        img[2][i] = exact_at(&b, &d.view, g.pos[i], g.nrm[i]);
        /* (a) exact at the triangle's vertices, interpolated with the
         * pixel's barycentric coordinates (from its world position) */
        const uint32_t *tv = m.tri[t];
        double e0[3], e1[3], ep[3];
        sub3(m.pos[tv[1]], m.pos[tv[0]], e0);
        sub3(m.pos[tv[2]], m.pos[tv[0]], e1);
        sub3(g.pos[i], m.pos[tv[0]], ep);
        double d00 = dot3(e0, e0), d01 = dot3(e0, e1), d11 = dot3(e1, e1), d20 = dot3(ep, e0), d21 = dot3(ep, e1);
        double den = d00 * d11 - d01 * d01;
        double wb = den != 0 ? (d11 * d20 - d01 * d21) / den : 0, wc = den != 0 ? (d00 * d21 - d01 * d20) / den : 0;
        double wa = 1 - wb - wc;
        img[0][i] = wa * exact_at(&b, &d.view, m.pos[tv[0]], m.nrm[tv[0]])
                  + wb * exact_at(&b, &d.view, m.pos[tv[1]], m.nrm[tv[1]])
                  + wc * exact_at(&b, &d.view, m.pos[tv[2]], m.nrm[tv[2]]);
        /* (b) an item for the hardware */
        double row[10];
        if (!local_dirs(&d.view, g.pos[i], g.nrm[i], row, row + 3, row + 6)) continue;
        row[9] = rf_maps_lookup(maps, row, row + 3, row + 6);
        if (vec_set_push(&vs, row)) base_out_of_memory();
        pix_of[nitems++] = i;
    }
    if (nitems) {
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        cfg.width = width; cfg.L = L; cfg.alpha = alpha;
        unit_fmts f;
        u->formats(&cfg, &f);
        if (tb_run(u, &cfg, &f, &vs, NULL, &tr, err, errlen) != TB_OK) goto out;
        sim_fmt fy = f.f[unit_sig_index(u, "y")];
        for (size_t k = 0; k < nitems; k++) {
            size_t i = pix_of[k];
            double y = ldexp((double)tr.raw[k], -fy.fbits);
            img[1][i] = y * scale * (vs.data[k * 10 + 5]) * d.view.light[0].intensity;   /* f (N.L) I0 */
        }
        r->clocks = tr.cycles;
        r->area_ge = tr.area_ge;
    }
    double s2 = 0, ea = 0, eb = 0, mx = 0;
    for (size_t i = 0; i < np; i++) {
        if (g.tri[i] < 0) continue;
        s2 += img[2][i] * img[2][i];
        ea += (img[0][i] - img[2][i]) * (img[0][i] - img[2][i]);
        eb += (img[1][i] - img[2][i]) * (img[1][i] - img[2][i]);
        if (img[2][i] > mx) mx = img[2][i];
    }
    r->nmse_vertex = s2 > 0 ? ea / s2 : 0;
    r->nmse_factor = s2 > 0 ? eb / s2 : 0;
    r->w = W; r->h = H; r->items = nitems;
    if (dir) {
        static const char *const names[3] = { "vertex.png", "factorized.png", "exact.png" };
        for (int k = 0; k < 3; k++) {
            char path[700];
            snprintf(path, sizeof path, "%s/%s", dir, names[k]);
            if (write_png(path, img[k], W, H, mx > 0 ? mx : 1, err, errlen)) goto out;
        }
    }
    rc = 0;
out:
    tb_result_free(&tr);
    vec_set_free(&vs);
    for (int k = 0; k < 3; k++) free(img[k]);
    free(pix_of);
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
    return rc;
}
