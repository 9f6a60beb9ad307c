/* bench_sweep.c - wall time of the default interp3 sweep over widths 8..32
 * on two threads (`shadesim sweep interp3 --widths 8:32 -j 2`), the whole
 * process timed from outside, and of horner3's target search with one bit
 * of margin (without it the search's result fails its held-out check and
 * the sweep exits 1, as docs/sweeps.md shows). Goal: the
 * sweep under 10 s (a miss is printed, not an error: the bench measures).
 * Falls back to horner3 where interp3 is not built. */
#include "units/unit.h"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Best of three runs of cmd; -1 if it fails. */
static double best_of_3(const char *cmd)
{
    double best = 1e9;
    for (int k = 0; k < 3; k++) {
        double t0 = now_s();
        if (system(cmd) != 0) { fprintf(stderr, "bench: '%s' failed\n", cmd); return -1; }
        double dt = now_s() - t0;
        if (dt < best) best = dt;
    }
    return best;
}

int main(void)
{
    const char *bin = getenv("SHADESIM") ? getenv("SHADESIM") : "bin/shadesim";
    const char *unit = unit_find("interp3") ? "interp3" : "horner3";
    char vec[340] = "", cmd[1200], vpath[300];
    /* The unit's checked-in vectors if there are any, else the same set
     * made by the float reference (what the file would hold). */
    snprintf(vpath, sizeof vpath, "vectors/%s.vec", unit);
    if (access(vpath, R_OK) != 0) {
        snprintf(vpath, sizeof vpath, "/tmp/shadesim_bench_sweep_%ld.vec", (long)getpid());
        snprintf(cmd, sizeof cmd, "%s vectors %s -o %s", bin, unit, vpath);
        if (system(cmd) != 0) { fprintf(stderr, "bench: '%s' failed\n", cmd); return 1; }
        snprintf(vec, sizeof vec, " --vectors %s", vpath);
    }
    snprintf(cmd, sizeof cmd, "%s sweep %s --widths 8:32 -j 2%s -o /tmp/shadesim_bench_sweep > /dev/null", bin, unit, vec);
    double t = best_of_3(cmd);
    if (t < 0) return 1;
    printf("sweep %s --widths 8:32 -j 2 (25 configurations, CSV + charts): %.3f s (best of 3; goal < 10 s%s)%s\n",
           unit, t, t < 10 ? "" : ": MISSED", unit[0] == 'h' ? " [interp3 not built: horner3 instead]" : "");
    snprintf(cmd, sizeof cmd, "%s sweep horner3 --widths 8:24 -j 2 --target-error 1e-3 --margin 1 -o /tmp/shadesim_bench_sweep > /dev/null", bin);
    double tt = best_of_3(cmd);
    if (tt < 0) return 1;
    printf("sweep horner3 --widths 8:24 -j 2 --target-error 1e-3 --margin 1 (sweep + per-signal search): %.3f s (best of 3)\n", tt);
    if (vec[0]) unlink(vpath);
    if (system("rm -rf /tmp/shadesim_bench_sweep") != 0) return 1;
    return 0;
}
