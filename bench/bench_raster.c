/* bench_raster.c - the geometry of the scene layer alone: building the
 * built-in face (detail 1 and 2), rasterizing it at 512x512 and 2048x2048
 * (perspective, the face filling most of the image), cutting the spans,
 * and reading an OBJ of the detail-2 face written to /tmp once. Best of
 * 5 runs each. */
#include "scene/scene.h"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int write_obj(const char *path, const scn_mesh *m)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    for (size_t v = 0; v < m->nv; v++) fprintf(f, "v %.9g %.9g %.9g\n", m->pos[v][0], m->pos[v][1], m->pos[v][2]);
    for (size_t v = 0; v < m->nv; v++) fprintf(f, "vn %.9g %.9g %.9g\n", m->nrm[v][0], m->nrm[v][1], m->nrm[v][2]);
    for (size_t t = 0; t < m->nt; t++)
        fprintf(f, "f %u//%u %u//%u %u//%u\n", m->tri[t][0] + 1, m->tri[t][0] + 1, m->tri[t][1] + 1,
                m->tri[t][1] + 1, m->tri[t][2] + 1, m->tri[t][2] + 1);
    return fclose(f);
}

int main(void)
{
    char err[512];
    scn_mesh m;
    for (int detail = 1; detail <= 2; detail++) {
        double best = 1e9;
        for (int k = 0; k < 5; k++) {
            double t0 = now_s();
            if (scn_mesh_builtin("face", detail, &m, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
            double dt = now_s() - t0;
            if (dt < best) best = dt;
            if (k < 4) scn_mesh_free(&m);
        }
        printf("face detail %d: %zu triangles, built in %.3f s\n", detail, m.nt, best);
        scn_camera cam = { 1, { 0, 0, 3.2 }, { 0, 0, 0 }, { 0, 1, 0 }, 40, 0 };
        for (int res = 512; res <= 2048; res *= 4) {
            double br = 1e9, bs = 1e9;
            size_t nsp = 0, cov = 0;
            for (int k = 0; k < 5; k++) {
                scn_gbuf g;
                double t0 = now_s();
                if (scn_raster(&m, &cam, res, res, &g, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
                double t1 = now_s();
                scn_span *s;
                nsp = scn_spans(&g, &s);
                double t2 = now_s();
                if (t1 - t0 < br) br = t1 - t0;
                if (t2 - t1 < bs) bs = t2 - t1;
                cov = 0;
                for (size_t i = 0; i < (size_t)res * res; i++) cov += g.tri[i] >= 0;
                free(s);
                scn_gbuf_free(&g);
            }
            printf("  raster %dx%d: %.4f s (%zu pixels covered); spans: %.4f s (%zu spans)\n", res, res,
                   br, cov, bs, nsp);
        }
        if (detail == 2) {
            const char *path = "/tmp/shadesim_bench_face.obj";
            if (write_obj(path, &m)) { fprintf(stderr, "cannot write %s\n", path); return 1; }
            double best_obj = 1e9;
            scn_mesh o;
            for (int k = 0; k < 5; k++) {
                double t0 = now_s();
                if (scn_mesh_obj(path, &o, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
                double dt = now_s() - t0;
                if (dt < best_obj) best_obj = dt;
                scn_mesh_free(&o);
            }
            printf("  OBJ read back (%zu v, %zu vn, %zu f): %.3f s\n", m.nv, m.nv, m.nt, best_obj);
            remove(path);
        }
        scn_mesh_free(&m);
    }
    return 0;
}
