/* bench_scene.c - the default face scene at 512x512, every covered pixel
 * through the cycle-accurate span unit, with -j 1 and -j 2: wall time
 * (rasterization, reference shading, node shading and simulation, all of
 * tb_scene_render), covered pixels per second, simulated clocks per
 * second, and the share of the render's CPU time spent simulating the span
 * unit (tb_scene_result.cpu_sim / cpu_render). The two renders must give
 * the same images and figures (exit 1 if not). Target: 5 s or less with
 * -j 1.
 *
 * Then, as `shadesim scene face ... -j 2` runs them (issue 28's targets):
 *  - the format search of the 512x512 face, adaptive-region with 5 terms,
 *    NMSE <= 1e-4 (docs/scenes.md): wall and CPU time, the renders it
 *    needs and the renders it ran (speculative candidates included), CPU
 *    per render and the share of it simulating; its answer (NMSE on the
 *    view and on the held-out view, area saved). Targets: 60 s wall
 *    (stretch 20 s), simulating >= 50% of a render, the answer within
 *    the target and within 1 point of 42.3% saved (exit 1 if the answer
 *    is not; times only reported);
 *  - the default sweep of the face: the same figures; target 10 s wall.
 * One run each (a search takes tens of seconds): wall time swings with
 * the machine's load, printed beside it; CPU time and the share much
 * less.
 *
 * And the face at 512x512 through both pipelines in hardware, as
 * `shadesim scene face -j 2` renders it (issue 32's target: 3 s wall):
 * the render recording its normals, the shade unit over every covered
 * pixel and every node on the batch's lanes, and the render again with
 * the nodes from hardware; best of three, wall and CPU, the -j 1 and -j 2
 * figures compared (exit 1 if they differ). */
#include "testbench/study/tb_scene.h"
#include "testbench/study/tb_scene_search.h"
#include "testbench/study/tb_scene_pipes.h"
#include "testbench/tb.h"
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double load1(void)
{
    double l = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1) l = NAN;
        fclose(f);
    }
    return l;
}

static double jnum(const char *js, const char *key)
{
    char k[64];
    snprintf(k, sizeof k, "\"%s\": ", key);
    const char *p = js ? strstr(js, k) : NULL;
    return p ? strtod(p + strlen(k), NULL) : NAN;
}

static void work_line(const char *what, double wall, double cpu, const tb_scene_work *w)
{
    printf("%s: %.1f s wall, %.1f s CPU (load %.1f at the end), %zu renders needed, %zu run; "
           "per render %.1f ms CPU, %.0f%% of it simulating the span unit (%.1f ms)\n", what, wall, cpu, load1(),
           w->renders, w->renders_run, w->renders_run ? 1e3 * w->cpu_render / (double)w->renders_run : 0,
           w->cpu_render > 0 ? 100 * w->cpu_sim / w->cpu_render : 0,
           w->renders_run ? 1e3 * w->cpu_sim / (double)w->renders_run : 0);
}

/* The face's format search and default sweep on 2 threads. 0, or 1 if
 * the search's answer is off or either fails. */
static int search_and_sweep(const scn_mesh *m)
{
    scn_desc d;
    char err[600];
    int bad = 0;
    if (scn_desc_builtin("face", &d)) return 1;
    d.policy = SCN_POL_ADAPTIVE_REGION;
    snprintf(d.terms, sizeof d.terms, "5");
    char *js = NULL;
    size_t jl = 0;
    FILE *out = open_memstream(&js, &jl);
    if (!out) return 1;
    tb_scene_work w;
    double t0 = now_s(), c0 = cpu_s();
    int rc = tb_scene_search(&d, m, 2, 0, 1e-4, NULL, 1, out, &w, err, sizeof err);
    double wall = now_s() - t0, cpu = cpu_s() - c0;
    fclose(out);
    if (rc != TB_OK) { printf("scene search face: FAILED: %s\n", err); free(js); return 1; }
    work_line("scene search face 512x512 adaptive-region terms 5 NMSE <= 1e-4 -j 2", wall, cpu, &w);
    double nv = jnum(js, "nmse"), nh = jnum(js, "heldout_nmse"), saved = jnum(js, "area_saved_pct");
    double rj = jnum(js, "renders");
    int answer = nv <= 1e-4 && nh <= 1e-4 && fabs(saved - 42.3) <= 1 && rj == (double)w.renders;
    printf("scene search face: NMSE %.4g on the view, %.4g held-out, area saved %.1f%%, renders in its JSON %.0f: "
           "answer %s; %s the 60 s target (stretch 20 s: %s); simulating %s the 50%% target\n", nv, nh, saved, rj,
           answer ? "as before" : "CHANGED", wall <= 60 ? "meets" : "MISSES", wall <= 20 ? "meets" : "misses",
           w.cpu_sim >= 0.5 * w.cpu_render ? "meets" : "MISSES");
    bad |= !answer;
    free(js);

    if (scn_desc_builtin("face", &d)) return 1;
    out = fopen("/dev/null", "w");
    if (!out) return 1;
    t0 = now_s();
    c0 = cpu_s();
    rc = tb_scene_sweep(&d, m, 2, 0, NULL, NULL, 0, out, &w, err, sizeof err);
    wall = now_s() - t0;
    cpu = cpu_s() - c0;
    fclose(out);
    if (rc != TB_OK) { printf("scene sweep face: FAILED: %s\n", err); return 1; }
    work_line("scene sweep face 512x512 default grid -j 2", wall, cpu, &w);
    printf("scene sweep face: %s the 10 s target; simulating %s the 50%% target\n", wall <= 10 ? "meets" : "MISSES",
           w.cpu_sim >= 0.5 * w.cpu_render ? "meets" : "MISSES");
    return bad;
}

/* The face through both pipelines, -j 1 and -j 2, best of three. 0, or
 * 1 if a render fails or the two differ. */
static int both_pipelines(const scn_desc *d, const scn_mesh *m)
{
    double best[2] = { 1e9, 1e9 }, cpu[2] = { 0, 0 };
    tb_scene_pipes keep[2];
    char err[600];
    int bad = 0;
    memset(keep, 0, sizeof keep);
    for (int k = 0; k < 2; k++)
        for (int rep = 0; rep < 3; rep++) {
            tb_scene_opts o = { k + 1, 0, NULL, NULL, 0, 1, NULL, NULL };
            tb_scene_result r;
            tb_scene_pipes p;
            double t0 = now_s(), c0 = cpu_s();
            int rc = tb_scene_render_pipes(d, m, NULL, &o, TB_PIPES_BOTH, &r, &p, err, sizeof err);
            double e = now_s() - t0, c = cpu_s() - c0;
            if (rc != TB_OK) { printf("scene face both pipelines -j %d: FAILED: %s\n", k + 1, err); return 1; }
            if (e < best[k]) { best[k] = e; cpu[k] = c; }
            tb_scene_free(&r);
            if (rep == 0) keep[k] = p;
            else tb_scene_pipes_free(&p);
        }
    const tb_scene_pipes *p = &keep[1];
    size_t n = (size_t)p->w * (size_t)p->h;
    if (!p->ok) printf("scene face both pipelines: not measured: %s\n", p->why);
    else if (keep[0].nrows != p->nrows || memcmp(keep[0].row, p->row, sizeof p->row) ||
             memcmp(keep[0].ref_hw, p->ref_hw, n * sizeof *p->ref_hw) ||
             memcmp(keep[0].hw_nodes, p->hw_nodes, n * sizeof *p->hw_nodes)) {
        printf("scene face both pipelines: -j 1 and -j 2 DIFFER\n");
        bad = 1;
    }
    /* The target is wall time on an idle machine. On a busy one the wall
     * time says little; the CPU time bounds it: a run that waits for
     * nothing but the processor takes no longer than its CPU time once it
     * has a core to itself (and -j 2 splits it over two). */
    double ld = load1();
    for (int k = 0; k < 2; k++) {
        printf("scene face 512x512 through both pipelines -j %d: %.3f s wall (best of 3), %.3f s CPU (load %.1f)",
               k + 1, best[k], cpu[k], ld);
        if (k) printf("; %s the 3 s target%s", best[1] <= 3 ? "meets" : "MISSES",
                      best[1] > 3 && cpu[1] <= 3 ? " in wall time at this load; its CPU time, which bounds the wall "
                                                   "time on an idle machine, meets it" : "");
        putchar('\n');
    }
    for (int k = 0; k < 2; k++) tb_scene_pipes_free(&keep[k]);
    return bad;
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
    double dt[3], csim[3], cren[3];   /* the best run's time, and its CPU split */
    int bad = 0;
    /* Best of three runs for each -j (the machine may be busy); the
     * first run's output is the one compared. */
    /* -j 1 and -j 2 with the batch mode (the default), -j 1 on the kernel
     * alone (--no-batch) */
    for (int k = 0; k < 3; k++) {
        tb_scene_opts o = { k == 1 ? 2 : 1, 0, NULL, NULL, k == 2, 0, NULL, NULL };
        dt[k] = 1e9;
        for (int rep = 0; rep < 3; rep++) {
            tb_scene_result t;
            memset(&t, 0, sizeof t);
            double t0 = now_s();
            int rc = tb_scene_render(&d, &m, &o, &t, err, sizeof err);
            double e = now_s() - t0;
            if (rc != TB_OK) { fprintf(stderr, "bench_scene: -j %d: %s\n", o.jobs, err); return 1; }
            if (e < dt[k]) { dt[k] = e; csim[k] = t.cpu_sim; cren[k] = t.cpu_render; }
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
    printf("scene face 512x512 -j 1 (best run): %.1f ms CPU a render, %.0f%% of it simulating the span unit "
           "(%.1f ms); --no-batch: %.0f%%\n", 1e3 * cren[0], 100 * csim[0] / cren[0], 1e3 * csim[0],
           100 * csim[2] / cren[2]);
    for (int k = 0; k < 3; k++) tb_scene_free(&r[k]);
    bad |= both_pipelines(&d, &m);
    bad |= search_and_sweep(&m);
    scn_mesh_free(&m);
    return bad;
}
