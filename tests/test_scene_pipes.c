/* test_scene_pipes.c - both pipelines in hardware (testbench/study/
 * tb_scene_pipes.c) against a recomputation here: the face rasterized
 * again, each covered pixel's inputs to the shade unit built from the
 * scene's light and camera (the normal scaled by a power of two into
 * [1/2, 1), L, H = normalize(L + V), ka, kd, ks), the unit run on the
 * event-driven kernel (tb_run, not the batch's lanes), and the NMSE of its
 * outputs against per-pixel shading in double; the method's NMSE from its
 * written image; and the nodes from hardware changing the method's NMSE
 * only by the shade unit's own error. The same for Cook-Torrance with D16
 * on shade_cook (its inputs L, V, hs = 1/|L + V|, ka, kd, ks / pi: no
 * Fresnel factor in the face's material). */
#include "tst.h"
#include "testbench/study/tb_scene_pipes.h"
#include "sim/sim_fixed.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void unit_vec(const double *v, double *u)
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++) u[k] = v[k] / l;
}

static void check_scene(int cook)
{
    const unit_desc *u = unit_find(cook ? "shade_cook" : "shade");
    TST_CHECK(u != NULL, "no unit");
    if (!u) return;
    scn_desc d;
    scn_mesh m;
    scn_gbuf g;
    char err[600];
    TST_EQ_INT(scn_desc_builtin("face", &d), 0);
    d.width = d.height = 28;
    if (cook) {
        d.mat.spec = SCN_SPEC_COOK;
        d.mat.dg = 16;
    }
    TST_EQ_INT(scn_mesh_builtin(d.mesh, d.detail, &m, err, sizeof err), 0);
    tb_scene_opts o = { 2, 0, NULL, NULL, 0, 1, NULL, NULL };
    tb_scene_result r;
    tb_scene_pipes p;
    TST_EQ_INT(tb_scene_render_pipes(&d, &m, NULL, &o, TB_PIPES_BOTH, &r, &p, err, sizeof err), TB_OK);
    TST_CHECK(p.ok && p.nrows >= 2 && !p.row[0].method && p.row[1].method, "pipelines: %s", p.why);
    if (!p.ok) { scn_mesh_free(&m); return; }
    /* the inputs, rebuilt */
    TST_EQ_INT(scn_raster(&m, &d.view.cam, d.width, d.height, &g, err, sizeof err), 0);
    double L[3], V[3], H[3], vs[3];
    unit_vec(d.view.light[0].v, L);
    for (int k = 0; k < 3; k++) vs[k] = d.view.cam.eye[k] - d.view.cam.target[k];
    unit_vec(vs, V);
    for (int k = 0; k < 3; k++) H[k] = L[k] + V[k];
    unit_vec(H, H);
    unit_cfg cfg;
    unit_fmts f;
    unit_cfg_default(u, &cfg);
    cfg.width = 16;
    if (cook) { cfg.m = d.mat.m; cfg.g = 16; }
    else cfg.n = (int)d.mat.shininess;
    double hs = 1 / sqrt((L[0] + V[0]) * (L[0] + V[0]) + (L[1] + V[1]) * (L[1] + V[1]) + (L[2] + V[2]) * (L[2] + V[2]));
    TST_EQ_INT(tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err), 0);
    vec_set vs1;
    vec_set_init(&vs1);
    vec_set_header(&vs1, u->ref, &cfg.model);
    size_t np = (size_t)g.w * g.h;
    for (size_t i = 0; i < np; i++) {
        if (g.tri[i] < 0) continue;
        double row[14] = { 0 }, len = sqrt(g.nrm[i][0] * g.nrm[i][0] + g.nrm[i][1] * g.nrm[i][1] + g.nrm[i][2] * g.nrm[i][2]);
        double s = 1;
        while (len * s >= 1) s /= 2;
        while (len * s < 0.5) s *= 2;
        double I0 = d.view.light[0].intensity;
        for (int k = 0; k < 3; k++) { row[k] = g.nrm[i][k] * s; row[3 + k] = L[k]; row[6 + k] = cook ? V[k] : H[k]; }
        if (cook) {
            row[9] = hs;
            row[10] = d.mat.ambient;
            row[11] = d.mat.kd * I0;
            row[12] = d.mat.ks * I0 / M_PI;
        } else {
            row[9] = d.mat.ambient;
            row[10] = d.mat.kd * I0;
            row[11] = d.mat.ks * I0;
        }
        TST_EQ_INT(vec_set_push(&vs1, row), 0);
    }
    tb_result tr;
    TST_EQ_INT(tb_run(u, &cfg, &f, &vs1, NULL, &tr, err, sizeof err), TB_OK);
    double se = 0, sr = 0, se2 = 0;
    size_t k = 0;
    for (size_t i = 0; i < np; i++) {
        if (g.tri[i] < 0) continue;
        double n[3];
        unit_vec(g.nrm[i], n);
        double ref = scn_shade(&d.mat, &d.view, g.pos[i], n);
        double hw = sim_fx_to_real(tr.raw[k++ * (size_t)tr.n_out], tr.out[0].fmt);
        se += (hw - ref) * (hw - ref);
        sr += ref * ref;
        TST_NEAR(r.ref[i], ref, 0);                         /* the same float image */
        se2 += (p.hw_nodes[i] - ref) * (p.hw_nodes[i] - ref);
    }
    TST_EQ_INT(k, r.covered);
    TST_NEAR(p.row[0].nmse, se / sr, 1e-12 * se / sr);
    TST_NEAR(p.row[1].nmse, se2 / sr, 1e-12 * se2 / sr);
    /* the clocks per pixel and area of the reference are the unit's own */
    TST_NEAR(p.row[0].clocks_per_pixel, tr.cycles_per_item, 0);
    TST_NEAR(p.row[0].area_ge, tr.area_ge, 1e-9);
    /* nodes from hardware: the method's NMSE moves by the unit's error only */
    TST_CHECK(fabs(p.row[1].nmse - r.nmse) <= 0.01 * r.nmse, "method NMSE %g with hardware nodes, %g exact",
              p.row[1].nmse, r.nmse);
    TST_CHECK(p.row[1].nmse != r.nmse, "the hardware nodes changed nothing (%g)", r.nmse);
    tb_result_free(&tr);
    vec_set_free(&vs1);
    scn_gbuf_free(&g);
    tb_scene_free(&r);
    tb_scene_pipes_free(&p);
    scn_mesh_free(&m);
}

static void reference_nmse_recomputed(void) { check_scene(0); }
static void cook_reference_nmse_recomputed(void) { check_scene(1); }

int main(void)
{
    TST_RUN(reference_nmse_recomputed);
    TST_RUN(cook_reference_nmse_recomputed);
    TST_EXIT();
}
