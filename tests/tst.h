/* tst.h - the smallest test framework that does the job.
 *
 * A test is a function; TST_RUN(fn) runs it and prints one line,
 * "ok NAME", "FAIL NAME" or "skip NAME: why". tests/run.sh counts those
 * lines over every test binary and prints the closing "N passed, N failed".
 * A failed check prints file:line and the message, and the test goes on so
 * that one run shows every broken assertion (up to a limit per test).
 */
#ifndef TST_H
#define TST_H
#include <stdio.h>
#include <stdarg.h>
#include <string.h>
#include <math.h>
#include <stdlib.h>

static int tst_failed_checks;   /* failures in the current test */
static int tst_skipped;         /* set by TST_SKIP */
static char tst_skip_why[256];
static int tst_any_failed;

static void tst_fail(const char *file, int line, const char *fmt, ...)
{
    if (tst_failed_checks++ >= 10) return;      /* keep the log readable */
    va_list ap;
    fprintf(stdout, "  %s:%d: ", file, line);
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
    fputc('\n', stdout);
}

#define TST_CHECK(cond, ...) do { if (!(cond)) \
    tst_fail(__FILE__, __LINE__, "check failed: " #cond " | " __VA_ARGS__); } while (0)
/* |a - b| <= tol */
#define TST_NEAR(a, b, tol) do { double tst_a_ = (a), tst_b_ = (b); \
    if (!(fabs(tst_a_ - tst_b_) <= (tol))) tst_fail(__FILE__, __LINE__, \
    "%s = %.17g, expected %s = %.17g (tol %g)", #a, tst_a_, #b, tst_b_, (double)(tol)); } while (0)
#define TST_EQ_INT(a, b) do { long long tst_a_ = (long long)(a), tst_b_ = (long long)(b); \
    if (tst_a_ != tst_b_) tst_fail(__FILE__, __LINE__, "%s = %lld, expected %lld", \
    #a, tst_a_, tst_b_); } while (0)
#define TST_EQ_STR(a, b) do { const char *tst_a_ = (a), *tst_b_ = (b); \
    if (!tst_a_ || !tst_b_ || strcmp(tst_a_, tst_b_)) tst_fail(__FILE__, __LINE__, \
    "%s = \"%s\", expected \"%s\"", #a, tst_a_ ? tst_a_ : "(null)", tst_b_ ? tst_b_ : "(null)"); } while (0)
#define TST_SKIP(...) do { tst_skipped = 1; \
    snprintf(tst_skip_why, sizeof tst_skip_why, __VA_ARGS__); return; } while (0)

static void tst_run(const char *name, void (*fn)(void))
{
    tst_failed_checks = 0;
    tst_skipped = 0;
    fn();
    fflush(stdout);
    if (tst_failed_checks) { printf("FAIL %s\n", name); tst_any_failed = 1; }
    else if (tst_skipped) printf("skip %s: %s\n", name, tst_skip_why);
    else printf("ok %s\n", name);
    fflush(stdout);
}
#define TST_RUN(fn) tst_run(#fn, fn)
#define TST_EXIT() return tst_any_failed ? 1 : 0

/* Remove everything below dir (not dir itself): test scratch folders. */
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>
static inline void tst_rmtree(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char p[1024];
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        if (snprintf(p, sizeof p, "%s/%s", dir, e->d_name) >= (int)sizeof p) continue;
        struct stat st;
        if (!lstat(p, &st) && S_ISDIR(st.st_mode)) { tst_rmtree(p); rmdir(p); }
        else unlink(p);
    }
    closedir(d);
}

/* Path of the bin/shadesim under test (set by tests/run.sh). */
static inline const char *tst_shadesim(void)
{
    const char *p = getenv("SHADESIM");
    return p ? p : "bin/shadesim";
}
/* True under make test-quick (tests/run.sh with TST_QUICK=1, the edit
 * loop's subset): a program's long random sweeps may take a tenth of
 * their draws there (the same checks; make test draws them all). */
static inline int tst_quick(void)
{
    const char *q = getenv("TST_QUICK");
    return q && !strcmp(q, "1");
}
/* True when this program is the sanitizer build's (tests/run.sh sets
 * TST_BUILD to the build folder, "...-asan"): tool-driven checks, which
 * read bytes no build changes, run in the plain build only. */
static inline int tst_asan_build(void)
{
    const char *b = getenv("TST_BUILD");
    size_t n = b ? strlen(b) : 0;
    return n >= 5 && !strcmp(b + n - 5, "-asan");
}
/* True unless this program is the sanitizer build's or the portable
 * build's (TST_BUILD "...-portable": sim/ without its vector loops, the
 * kernel's switch dispatch): for checks of what neither changes. */
static inline int tst_plain_build(void)
{
    const char *b = getenv("TST_BUILD");
    size_t n = b ? strlen(b) : 0;
    return !tst_asan_build() && !(n >= 9 && !strcmp(b + n - 9, "-portable"));
}
/* True where a program's long random sweeps take a tenth of their draws:
 * make test-quick, and the sanitizer build, where a memory error shows on
 * the first draws that reach its path and a draw costs three to five
 * times the plain build's (the same checks; the plain build of make test
 * draws them all). */
static inline int tst_fewer(void) { return tst_quick() || tst_asan_build(); }
#endif
