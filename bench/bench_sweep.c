/* bench_sweep.c - wall time of the default interp3 sweep over widths 8..32
 * on two threads (`shadesim sweep interp3 --widths 8:32 -j 2`), the whole
 * process timed from outside, and of horner3's target search with one bit
 * of margin (without it the search's result fails its held-out check and
 * the sweep exits 1, as docs/sweeps.md shows). Goal: the
 * sweep under 10 s (a miss is printed, not an error: the bench measures).
 * Falls back to horner3 where interp3 is not built. Then the peak memory
 * of a sweep over 10^7 vectors a design point on two threads (the vectors
 * streamed, docs/sweeps.md; goal under 200 MB), with the load average.
 * */
#define _DEFAULT_SOURCE   /* wait4 */
#include "units/unit.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
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

/* argv run as a child of its own (stdout to /dev/null): its peak resident
 * memory in KiB (wait4's ru_maxrss, the child alone) and wall time; -1
 * if it fails. */
static long peak_kib(char *const *argv, double *secs)
{
    double t0 = now_s();
    fflush(stdout);   /* the child would write what stdout holds again */
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stdout)) _exit(127);
        execvp(argv[0], argv);
        _exit(127);
    }
    int st;
    struct rusage ru;
    if (wait4(pid, &st, 0, &ru) != pid || !WIFEXITED(st) || WEXITSTATUS(st) != 0) return -1;
    *secs = now_s() - t0;
    return ru.ru_maxrss;
}

static int sweep_memory(const char *bin)
{
    char *argv[] = { (char *)bin, "sweep", "horner3", "--widths", "15:16", "-n", "10000000", "-j", "2",
                     "-o", "/tmp/shadesim_bench_sweep_mem", NULL };
    double l0 = load1(), secs = 0;
    long kib = peak_kib(argv, &secs);
    double l1 = load1();
    if (system("rm -rf /tmp/shadesim_bench_sweep_mem") != 0 || kib < 0) {
        fprintf(stderr, "bench: %s sweep horner3 --widths 15:16 -n 10000000 -j 2 failed\n", bin);
        return 1;
    }
    printf("sweep horner3 --widths 15:16 -n 10000000 -j 2 (vectors streamed): peak RSS %.1f MB (goal < 200 MB%s), "
           "%.1f s, load %.2f to %.2f\n", (double)kib / 1024, kib < 200 * 1024 ? "" : ": MISSED", secs, l0, l1);
    return 0;
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
    return sweep_memory(bin);
}
