/* bench_scene.c - the default face scene at 512x512, every covered pixel
 * through the cycle-accurate span unit, with -j 1 and -j 2: wall time
 * (rasterization, reference shading, node shading and simulation, all of
 * tb_scene_render), covered pixels per second, simulated clocks per
 * second. The two renders must give the same images and figures (exit 1
 * if not). Target: 5 s or less with -j 1. */
#include "testbench/tb_scene.h"
#include "testbench/tb.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    scn_desc d;
    scn_mesh m;
    char err[600];
    memset(&m, 0, sizeof m);
    if (scn_desc_builtin("face", &d)) { fprintf(stderr, "bench_scene: no built-in face\n"); return 1; }
    d.width = d.height = 512;
    if (scn_mesh_builtin(d.mesh, d.detail, &m, err, sizeof err)) { fprintf(stderr, "bench_scene: %s\n", err); return 1; }
    tb_scene_result r[3];
    double dt[3];
    int bad = 0;
    /* Best of three runs for each -j (the machine may be busy); the
     * first run's output is the one compared. */
    /* -j 1 and -j 2 with the batch mode (the default), -j 1 on the kernel
     * alone (--no-batch) */
    for (int k = 0; k < 3; k++) {
        tb_scene_opts o = { k == 1 ? 2 : 1, 0, NULL, NULL, k == 2, 0 };
        dt[k] = 1e9;
        for (int rep = 0; rep < 3; rep++) {
            tb_scene_result t;
            memset(&t, 0, sizeof t);
            double t0 = now_s();
            int rc = tb_scene_render(&d, &m, &o, &t, err, sizeof err);
            double e = now_s() - t0;
            if (rc != TB_OK) { fprintf(stderr, "bench_scene: -j %d: %s\n", o.jobs, err); return 1; }
            if (e < dt[k]) dt[k] = e;
            if (rep == 0) r[k] = t;
            else tb_scene_free(&t);
        }
        printf("scene face 512x512 %s -j %d%s: %.3f s (best of 3), %zu covered pixels, %.3g pixels/s, "
               "%llu clocks, %.3g clocks/s\n", scn_policy_name(d.policy), o.jobs, k == 2 ? " --no-batch" : "", dt[k], r[k].covered,
               (double)r[k].covered / dt[k], (unsigned long long)r[k].hwst.clocks, (double)r[k].hwst.clocks / dt[k]);
    }
    size_t n = (size_t)r[0].w * (size_t)r[0].h;
    for (int k = 1; k < 3; k++)
        if (r[0].w != r[k].w || r[0].h != r[k].h || memcmp(r[0].hw, r[k].hw, n * sizeof *r[0].hw) ||
            memcmp(r[0].ref, r[k].ref, n * sizeof *r[0].ref) || memcmp(r[0].deg, r[k].deg, n) ||
            r[0].hwst.clocks != r[k].hwst.clocks || r[0].hwst.overflows != r[k].hwst.overflows ||
            r[0].nmse != r[k].nmse) {
            printf("scene face 512x512: %s outputs DIFFER\n", k == 1 ? "-j 1 and -j 2" : "batch and --no-batch");
            bad = 1;
        }
    if (!bad)
        printf("scene face 512x512: -j 1, -j 2 and --no-batch outputs identical; -j 2 speed-up %.2fx, batch against "
               "--no-batch %.2fx; -j 1 %s the 5 s target\n", dt[0] / dt[1], dt[2] / dt[0], dt[0] <= 5.0 ? "meets" : "MISSES");
    for (int k = 0; k < 3; k++) tb_scene_free(&r[k]);
    scn_mesh_free(&m);
    return bad;
}
