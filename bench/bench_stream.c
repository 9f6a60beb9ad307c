/* bench_stream.c - `shadesim run horner3 --vectors FILE --json`'s peak
 * memory (maximum resident set, from wait4's rusage) on 1 million and 10
 * million vector rows: run reads its file a block at a time, so the peak
 * does not grow with the rows. The 10M file is the 1M file's rows ten
 * times over (1 GB in /tmp while the bench runs). */
#define _DEFAULT_SOURCE   /* wait4 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
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

/* Run bin with args, stdout to /dev/null; peak RSS in kB, -1 on failure. */
static long peak_kb(const char *bin, const char *path, double *secs)
{
    double t0 = now_s();
    fflush(stdout);   /* the child must not write our buffered lines again */
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stdout)) _exit(127);
        execl(bin, bin, "run", "horner3", "--vectors", path, "--json", (char *)NULL);
        _exit(127);
    }
    int st;
    struct rusage ru;
    if (wait4(pid, &st, 0, &ru) != pid || !WIFEXITED(st) || WEXITSTATUS(st) > 1) return -1;
    *secs = now_s() - t0;
    return ru.ru_maxrss;
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
    const char *paths[2] = { p1, p10 };
    const char *names[2] = { "1M", "10M" };
    int rc = 0;
    for (int i = 0; i < 2; i++) {
        double s = 0;
        long kb = peak_kb(bin, paths[i], &s);
        FILE *f = fopen(paths[i], "r");
        long mb = 0;
        if (f) { fseek(f, 0, SEEK_END); mb = ftell(f) >> 20; fclose(f); }
        if (kb < 0) { fprintf(stderr, "bench: run on %s failed\n", paths[i]); rc = 1; continue; }
        printf("stream  run horner3 on %3s rows (%5ld MB of text): peak RSS %6.1f MB, %.1f s\n",
               names[i], mb, kb / 1024.0, s);
    }
    unlink(p1);
    unlink(p10);
    return rc;
}
