/* bench_stream.c - `shadesim run horner3 --vectors - --json` fed from a
 * pipe (cat FILE | ...): its peak memory (maximum resident set, from
 * wait4's rusage) on 1 million and 10 million rows, and its time on 10
 * million rows with -j 1 and -j 2 (the best wall time of three runs each,
 * in turns, and the CPU time that run used: user and system), with the
 * machine's load average before and after, since the machine may be
 * shared. run reads the pipe a block at a time and
 * simulates it on the batch's lanes a wave at a time, so the peak does
 * not grow with the rows (docs/batch.md, "Streams of any length"). The
 * 10M file is the 1M file's rows ten times over (1 GB in /tmp while the
 * bench runs). With the CPU time of -j 2 and of cat, which feeds the pipe on
 * the same cores, it prints what two cores allow at most. */
#define _DEFAULT_SOURCE   /* wait4, getloadavg */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct runst { long kb; double wall, user, sys, feed; } runst;   /* feed: cat's CPU seconds */

static double cpu_s(const struct rusage *ru)
{
    return (double)ru->ru_utime.tv_sec + 1e-6 * (double)ru->ru_utime.tv_usec
         + (double)ru->ru_stime.tv_sec + 1e-6 * (double)ru->ru_stime.tv_usec;
}

/* cat path | bin run horner3 --vectors - --json -j jobs, stdout to
 * /dev/null: 0 with its figures, -1 on failure. */
static int piped(const char *bin, const char *path, int jobs, runst *r)
{
    int fd[2];
    char j[16];
    snprintf(j, sizeof j, "%d", jobs);
    fflush(stdout);   /* the children must not write our buffered lines again */
    if (pipe(fd)) return -1;
    double t0 = now_s();
    pid_t feed = fork();
    if (feed < 0) return -1;
    if (feed == 0) {
        if (dup2(fd[1], 1) < 0) _exit(127);
        close(fd[0]); close(fd[1]);
        execlp("cat", "cat", path, (char *)NULL);
        _exit(127);
    }
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        if (dup2(fd[0], 0) < 0 || !freopen("/dev/null", "w", stdout)) _exit(127);
        close(fd[0]); close(fd[1]);
        execl(bin, bin, "run", "horner3", "--vectors", "-", "--json", "-j", j, (char *)NULL);
        _exit(127);
    }
    close(fd[0]); close(fd[1]);
    int st, fst;
    struct rusage ru, fru;
    if (wait4(pid, &st, 0, &ru) != pid) return -1;
    r->wall = now_s() - t0;
    if (wait4(feed, &fst, 0, &fru) != feed || !WIFEXITED(st) || WEXITSTATUS(st) > 1) return -1;
    r->feed = cpu_s(&fru);
    r->kb = ru.ru_maxrss;
    r->user = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec;
    r->sys = (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
    return 0;
}

static long size_mb(const char *path)
{
    struct stat st;
    return stat(path, &st) ? 0 : (long)(st.st_size >> 20);
}

static void load(const char *when)
{
    double l[3];
    if (getloadavg(l, 3) == 3) printf("stream  load average %s: %.2f %.2f %.2f\n", when, l[0], l[1], l[2]);
}

/* The 1M file's rows k times after its header into out. */
static int repeat_rows(const char *in, const char *out, int k)
{
    FILE *o = fopen(out, "w");
    if (!o) return -1;
    char *line = NULL;
    size_t cap = 0;
    for (int r = 0; r < k; r++) {
        FILE *f = fopen(in, "r");
        if (!f) { fclose(o); return -1; }
        ssize_t n;
        while ((n = getline(&line, &cap, f)) > 0)
            if (line[0] != '#' || r == 0) fwrite(line, 1, (size_t)n, o);
        fclose(f);
    }
    free(line);
    return fclose(o);
}

int main(void)
{
    const char *bin = getenv("SHADESIM") ? getenv("SHADESIM") : "bin/shadesim";
    const char *p1 = "/tmp/shadesim_bench_stream_1m.vec", *p10 = "/tmp/shadesim_bench_stream_10m.vec";
    char cmd[512];
    snprintf(cmd, sizeof cmd, "%s vectors horner3 -n 1000000 --seed 7 -o %s", bin, p1);
    if (system(cmd)) { fprintf(stderr, "bench: '%s' failed\n", cmd); return 1; }
    if (repeat_rows(p1, p10, 10)) { fprintf(stderr, "bench: cannot write %s\n", p10); unlink(p1); return 1; }
    int rc = 0;
    load("before");
    /* the peak at 1M and 10M rows (-j 2); then 10M rows on one thread and
     * on two, in turns, three times each, the best of each (a shared
     * machine's load comes and goes) */
    runst r1, r10, t1 = { 0, 1e300, 0, 0, 0 }, t2 = { 0, 1e300, 0, 0, 0 };
    int bad = piped(bin, p1, 2, &r1) || piped(bin, p10, 2, &r10);
    for (int k = 0; k < 3 && !bad; k++) {
        runst a, b;
        bad = piped(bin, p10, 1, &a) || piped(bin, p10, 2, &b);
        if (!bad && a.wall < t1.wall) t1 = a;
        if (!bad && b.wall < t2.wall) t2 = b;
    }
    if (bad) {
        fprintf(stderr, "bench: run horner3 --vectors - failed\n");
        rc = 1;
    } else {
        printf("stream  cat FILE | run horner3 --vectors -: peak RSS %.1f MB on 1M rows (%ld MB of text), "
               "%.1f MB on 10M rows (%ld MB; %.3f times the 1M peak)\n", r1.kb / 1024.0, size_mb(p1),
               r10.kb / 1024.0, size_mb(p10), (double)r10.kb / (double)r1.kb);
        printf("stream  10M rows -j 1 (best of 3): %.2f s wall, %.2f s user, %.2f s system\n", t1.wall, t1.user, t1.sys);
        printf("stream  10M rows -j 2 (best of 3): %.2f s wall, %.2f s user, %.2f s system\n", t2.wall, t2.user, t2.sys);
        printf("stream  -j 2 against -j 1: %.2fx the speed (wall; the load above shares the cores)\n",
               t1.wall / t2.wall);
        /* What two cores allow: -j 2's CPU time and cat's, which feeds
         * the pipe on the same cores, spread over both without a wait;
         * against it, the -j 1 run's wall (cat then runs on the other
         * core). */
        double c1 = t1.user + t1.sys, c2 = t2.user + t2.sys;
        printf("stream  -j 2 used %.2f s of CPU (%+.0f%% on -j 1's %.2f s), cat %.2f s beside it: both on two cores "
               "take at least %.2f s, at most %.2fx; the run took %.0f%% of the two cores' time\n",
               c2, 100 * (c2 / c1 - 1), c1, t2.feed, (c2 + t2.feed) / 2, t1.wall / ((c2 + t2.feed) / 2),
               100 * (c2 + t2.feed) / (2 * t2.wall));
    }
    load("after");
    unlink(p1);
    unlink(p10);
    return rc;
}
