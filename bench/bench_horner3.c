/* bench_horner3.c - horner3 over 200,000 pixels (1.2M clocks), VCD off:
 * clocks per second inside the simulation, and the whole process
 * (`shadesim run horner3 --vectors FILE`, parsing included) timed from
 * outside; also the vector file's reading alone (vec_file_read). The
 * vectors are the float reference's, written to /tmp once. */
#include "testbench/tb.h"
#include "vectors/vec_file.h"
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define PIXELS 200000

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    vec_set vs;
    char err[600];
    if (tb_make_vectors(u, &cfg, PIXELS, 7, &vs, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
    const char *path = "/tmp/shadesim_bench_horner3.vec";
    if (vec_file_write(path, &vs, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }

    /* Reading the file back (vectors/vec_file.c): strtod on every number. */
    double best_read = 1e9;
    for (int k = 0; k < 3; k++) {
        vec_set back;
        double t0 = now_s();
        if (vec_file_read(path, &back, NULL, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        double dt = now_s() - t0;
        if (dt < best_read) best_read = dt;
        vec_set_free(&back);
    }
    printf("horner3 %d pixels, vector file read (%.1f MB, %d numbers): %.3f s (best of 3)\n", PIXELS,
           (double)file_size(path) / 1e6, PIXELS * 6, best_read);

    unit_fmts fm;
    tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err);
    double best = 1e9;
    tb_result r;
    for (int k = 0; k < 3; k++) {
        double t0 = now_s();
        if (tb_run(u, &cfg, &fm, &vs, NULL, &r, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        double dt = now_s() - t0;
        if (dt < best) best = dt;
        if (k < 2) tb_result_free(&r);
    }
    printf("horner3 %d pixels, %llu clocks, in-process testbench: %.3f s = %.2f M clocks/s (best of 3)\n",
           PIXELS, (unsigned long long)r.stats.clocks, best, r.stats.clocks / best / 1e6);
    tb_result_free(&r);
    vec_set_free(&vs);

    const char *bin = getenv("SHADESIM") ? getenv("SHADESIM") : "bin/shadesim";
    char cmd[512];
    snprintf(cmd, sizeof cmd, "%s run horner3 --vectors %s --json > /dev/null", bin, path);
    best = 1e9;
    for (int k = 0; k < 3; k++) {
        double t0 = now_s();
        int rc = system(cmd);
        double dt = now_s() - t0;
        if (rc != 0) { fprintf(stderr, "bench: '%s' failed\n", cmd); return 1; }
        if (dt < best) best = dt;
    }
    printf("horner3 %d pixels, whole process (parse + simulate + report): %.3f s (best of 3)\n", PIXELS, best);
    unlink(path);
    return 0;
}
