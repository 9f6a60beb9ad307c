/* test_base.c - the base layer's small pieces: JSON numbers and strings,
 * name lists, the parallel-for. (Output files: test_out.c.)
 *
 * References are independent of the code under test: a number printed at
 * d digits is checked by reading it back with strtod against the bound
 * half a unit in the d-th digit gives; a cut list against the prefix of
 * the whole list made by snprintf; the parallel-for by counting, per item,
 * how often it ran.
 */
#include "tst.h"
#include "base/base_json.h"
#include "base/base_join.h"
#include "base/base_near.h"
#include "base/base_par.h"
#include "base/base_pool.h"
#include "base/base_num.h"
#include "base/base_line.h"
#include <float.h>
#include <stdatomic.h>

/* What f printed into a memory stream (caller frees). */
typedef struct { FILE *f; char *p; size_t n; } mem;
static void mem_open(mem *m) { m->p = NULL; m->n = 0; m->f = open_memstream(&m->p, &m->n); }
static char *mem_close(mem *m) { fclose(m->f); return m->p; }

static char *num_text(double v, int digits)
{
    mem m;
    mem_open(&m);
    base_json_num(m.f, v, digits);
    return mem_close(&m);
}

static const double nums[] = { 0.0, 1.0, -1.0, 0.1, 1.0 / 3, -2.0 / 3, 3.141592653589793, 6.02214076e23,
                               1e-300, 4.9406564584124654e-324, 2.2250738585072014e-308, DBL_MAX, -DBL_MAX,
                               123456789.0, 0.000123456789012345678, 1e22, 9.999999999999999e-5 };
#define NNUMS (sizeof nums / sizeof nums[0])

/* Non-finite numbers are null (JSON has no inf or NaN), at any precision. */
static void json_nonfinite_is_null(void)
{
    const double bad[] = { NAN, -NAN, INFINITY, -INFINITY };
    for (size_t i = 0; i < 4; i++)
        for (int d = 1; d <= 17; d += 8) {
            char *t = num_text(bad[i], d);
            TST_EQ_STR(t, "null");
            free(t);
        }
}

/* 17 digits read back as the very same double. */
static void json_17_digits_round_trip(void)
{
    for (size_t i = 0; i < NNUMS; i++) {
        char *t = num_text(nums[i], 17);
        char *end;
        double back = strtod(t, &end);
        TST_CHECK(*end == 0, "\"%s\" is one number", t);
        TST_CHECK(back == nums[i] && signbit(back) == signbit(nums[i]), "%s reads back as %.17g, wrote %.17g",
                  t, back, nums[i]);
        free(t);
    }
}

/* Fewer digits: within half a unit of the last digit, and no more
 * significant digits than asked for. */
static void json_fewer_digits_within_half_unit(void)
{
    const int ds[] = { 1, 6, 9, 10, 15 };
    for (size_t k = 0; k < sizeof ds / sizeof ds[0]; k++)
        for (size_t i = 0; i < NNUMS; i++) {
            double v = nums[i];
            if (v != 0 && fabs(v) < DBL_MIN) continue;   /* subnormals: fewer digits exist */
            if (fabs(v) > 1e300) continue;   /* rounded up past DBL_MAX: reads back as inf */
            char *t = num_text(v, ds[k]);
            double back = strtod(t, NULL);
            double unit = v == 0 ? 0 : pow(10, floor(log10(fabs(v))) - (ds[k] - 1));
            TST_CHECK(fabs(back - v) <= 0.5 * unit * (1 + 1e-12), "%s for %.17g at %d digits", t, v, ds[k]);
            int sig = 0, lead = 1;
            for (const char *p = t; *p && *p != 'e'; p++) {
                if (*p < '0' || *p > '9') continue;
                if (lead && *p == '0') continue;
                lead = 0;
                sig++;
            }
            TST_CHECK(sig <= ds[k], "%s has %d significant digits, asked %d", t, sig, ds[k]);
            free(t);
        }
}

/* Strings: quotes and backslashes escaped, control bytes as \u00XX,
 * everything else (UTF-8 too) as it is, NULL as "". */
static void json_string_escapes(void)
{
    const char *in[] = { "", "plain", "a\"b", "back\\slash", "tab\tnl\ncr\r", "\x01\x1f", "caf\xc3\xa9 \x7f", NULL };
    for (size_t i = 0; i < sizeof in / sizeof in[0]; i++) {
        mem m;
        mem_open(&m);
        base_json_str(m.f, in[i]);
        char *t = mem_close(&m);
        /* the expected text, from the JSON grammar byte by byte */
        char want[128];
        size_t k = 0;
        want[k++] = '"';
        for (const unsigned char *p = (const unsigned char *)(in[i] ? in[i] : ""); *p; p++) {
            if (*p == '"' || *p == '\\') { want[k++] = '\\'; want[k++] = (char)*p; }
            else if (*p < 0x20) k += (size_t)sprintf(want + k, "\\u%04x", *p);
            else want[k++] = (char)*p;
        }
        want[k++] = '"';
        want[k] = 0;
        TST_EQ_STR(t, want);
        /* and nothing below 0x20 is left raw */
        for (const char *p = t; *p; p++) TST_CHECK((unsigned char)*p >= 0x20, "raw control byte in %s", t);
        free(t);
    }
}

/* Edit distances worked by hand: kitten -> sitting is k->s, e->i and an
 * added g (3); a swap of two neighbours is one edit (widht -> width), two
 * swaps two, and a swap is not one across a third letter (abc -> cba:
 * a->c, c->a, 2); widht -> light is w->l, d->g (2); case is ignored; the
 * empty word is as far as the other word is long. */
static void near_distance_by_hand(void)
{
    TST_CHECK(base_near_distance("kitten", "sitting") == 3, "kitten/sitting");
    TST_CHECK(base_near_distance("widht", "width") == 1, "transposition");
    TST_CHECK(base_near_distance("iwdht", "width") == 2, "two transpositions");
    TST_CHECK(base_near_distance("abc", "cba") == 2, "no swap across a letter");
    TST_CHECK(base_near_distance("widht", "light") == 2, "widht/light");
    TST_CHECK(base_near_distance("ca", "abc") == 3, "OSA: ca -> abc is 3, not 2");
    TST_CHECK(base_near_distance("Horner3", "horner3") == 0, "case");
    TST_CHECK(base_near_distance("", "abc") == 3 && base_near_distance("abc", "") == 3, "empty");
    TST_CHECK(base_near_distance("run", "run") == 0, "same");
    char longw[60];
    memset(longw, 'a', sizeof longw - 1);
    longw[sizeof longw - 1] = 0;
    TST_CHECK(base_near_distance(longw, "a") == 99, "over 40 characters");
}

/* The nearest name: within 2 edits or a third of the word; ties go to
 * the first listed; NULL entries are skipped; nothing near gives NULL. */
static void near_choice(void)
{
    const char *const names[] = { "run", NULL, "sweep", "scene", "synth" };
    TST_CHECK(base_near("rnu", names, 5) == names[0], "rnu -> run");
    TST_CHECK(base_near("swep", names, 5) == names[2], "swep -> sweep");
    TST_CHECK(base_near("scena", names, 5) == names[3], "scena -> scene (before synth)");
    TST_CHECK(base_near("qqqqqqq", names, 5) == NULL, "nothing near");
    TST_CHECK(base_near("x", names, 0) == NULL, "empty list");
    const char *const ties[] = { "ab", "ba" };
    TST_CHECK(base_near("aa", ties, 2) == ties[0], "tie: the first");
    /* the scene's keys: light is listed before width, and a swap is nearer */
    const char *const keys[] = { "light", "width" };
    TST_CHECK(base_near("widht", keys, 2) == keys[1], "widht -> width, not light");
}

/* Joining: the first item without a separator, the next with one. */
static void join_empty_and_one(void)
{
    char b[32] = "";
    TST_EQ_INT(base_join_add(b, sizeof b, ", ", "alpha"), 0);
    TST_EQ_STR(b, "alpha");
    TST_EQ_INT(base_join_add(b, sizeof b, ", ", "beta"), 0);
    TST_EQ_STR(b, "alpha, beta");
    TST_EQ_INT(base_join_add(b, sizeof b, " ", "x"), 0);
    TST_EQ_STR(b, "alpha, beta x");
    char e[8] = "";
    TST_EQ_INT(base_join_add(e, sizeof e, ", ", ""), 0);
    TST_EQ_STR(e, "");
    char z[4] = "abc";
    TST_EQ_INT(base_join_add(z, 0, ", ", "q"), -1);     /* cap 0: untouched */
    TST_EQ_STR(z, "abc");
    char f[32] = "";
    TST_EQ_INT(base_join_addf(f, sizeof f, ", ", "W=%d: %d", 16, 3), 0);
    TST_EQ_INT(base_join_addf(f, sizeof f, ", ", "%c s%d", 'B', 2), 0);
    TST_EQ_STR(f, "W=16: 3, B s2");
}

/* Every capacity from 1 up: the cut list is the whole list's prefix, -1
 * exactly when something was cut, and the buffer is never overrun. */
static void join_truncation(void)
{
    const char *items[] = { "horner3", "div3", "x", "interp2" };
    char whole[128] = "";
    size_t wl = 0;
    for (int i = 0; i < 4; i++) wl += (size_t)snprintf(whole + wl, sizeof whole - wl, "%s%s", i ? ", " : "", items[i]);
    for (size_t cap = 1; cap <= wl + 3; cap++) {
        char buf[160];
        memset(buf, '#', sizeof buf);
        buf[0] = 0;
        int cut = 0;
        for (int i = 0; i < 4; i++) cut |= base_join_add(buf, cap, ", ", items[i]) != 0;
        size_t want = wl < cap - 1 ? wl : cap - 1;
        TST_EQ_INT(strlen(buf), want);
        TST_CHECK(!strncmp(buf, whole, want), "cap %zu: \"%s\" is not a prefix of \"%s\"", cap, buf, whole);
        TST_EQ_INT(cut, wl > cap - 1);
        for (size_t j = cap; j < sizeof buf; j++) TST_CHECK(buf[j] == '#', "cap %zu: byte %zu written", cap, j);
    }
}

/* ---- parallel-for ---- */

typedef struct { int *count; atomic_int order; int *seq; } pctx;

static void bump(void *arg, size_t i)
{
    pctx *c = arg;
    c->count[i]++;                       /* item i's own slot */
    c->seq[atomic_fetch_add(&c->order, 1)] = (int)i;
}

/* Each item exactly once for 1..4 threads (and more threads than items);
 * with one thread, in order on the caller's thread. */
static void par_every_item_once(void)
{
    const size_t ns[] = { 0, 1, 2, 3, 7, 1000 };
    for (int th = 0; th <= 5; th++)
        for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++) {
            size_t n = ns[k];
            int *count = calloc(n + 1, sizeof *count), *seq = calloc(n + 1, sizeof *seq);
            pctx c = { count, 0, seq };
            base_par_for(n, th, bump, &c);
            size_t bad = 0;
            for (size_t i = 0; i < n; i++) bad += count[i] != 1;
            TST_CHECK(bad == 0, "threads %d, n %zu: %zu items not run exactly once", th, n, bad);
            TST_EQ_INT(atomic_load(&c.order), n);
            if (th <= 1)
                for (size_t i = 0; i < n; i++) TST_CHECK(seq[i] == (int)i, "one thread: item %d ran %zu-th", seq[i], i);
            free(count);
            free(seq);
        }
}

/* Results do not depend on the thread count: each item fills its slot. */
static void sq(void *arg, size_t i) { ((double *)arg)[i] = sqrt((double)i) * 3.5; }
static void par_same_result_any_threads(void)
{
    enum { N = 500 };
    static double ref[N], got[N];
    for (size_t i = 0; i < N; i++) ref[i] = sqrt((double)i) * 3.5;
    for (int th = 1; th <= 4; th++) {
        memset(got, 0, sizeof got);
        base_par_for(N, th, sq, got);
        TST_CHECK(!memcmp(ref, got, sizeof ref), "threads %d: results differ", th);
    }
}

/* The pool (base_pool.h): every loop's items exactly once, many loops on
 * the same threads, a task that runs a loop of its own beside the
 * caller's, a task nobody took run by its waiter; none of it depends on
 * the thread count. */
typedef struct { base_pool *p; pctx c; size_t n; double out[64]; } ptask;
static void task_loop(void *arg)
{
    ptask *t = arg;
    base_pool_for(t->p, t->n, bump, &t->c);
    for (int i = 0; i < 64; i++) t->out[i] = sqrt((double)i) * 3.5;
}
static void pool_loops_and_tasks(void)
{
    enum { N = 300 };
    static double ref[N], got[N];
    for (size_t i = 0; i < N; i++) ref[i] = sqrt((double)i) * 3.5;
    for (int th = 1; th <= 4; th++)
        for (int tasks = 0; tasks <= 2; tasks++) {
            base_pool *p = base_pool_new(th, tasks);
            TST_CHECK((p == NULL) == (th == 1 && tasks == 0), "threads %d, tasks %d: pool %p", th, tasks, (void *)p);
            for (int rep = 0; rep < 50; rep++) {
                memset(got, 0, sizeof got);
                int *count = calloc(N + 1, sizeof *count), *seq = calloc(N + 1, sizeof *seq);
                ptask t = { p, { count, 0, seq }, N, { 0 } };
                base_task bt;
                base_pool_start(p, &bt, task_loop, &t);
                base_pool_for(p, N, sq, got);
                base_pool_wait(p, &bt);
                TST_CHECK(bt.state == 3, "threads %d, tasks %d: the task did not end", th, tasks);
                TST_CHECK(!memcmp(ref, got, sizeof ref), "threads %d, tasks %d, rep %d: loop results differ", th, tasks, rep);
                TST_CHECK(!memcmp(ref, t.out, sizeof t.out), "threads %d, tasks %d: the task's results differ", th, tasks);
                size_t bad = 0;
                for (size_t i = 0; i < N; i++) bad += count[i] != 1;
                TST_CHECK(bad == 0, "threads %d, tasks %d: %zu of the task's loop items not run exactly once", th, tasks, bad);
                free(count);
                free(seq);
            }
            base_pool_free(p);
        }
}

/* The one number syntax: each text with what it must give, by hand. */
static void num_strict_syntax(void)
{
    static const struct { const char *s; int neg_ok, ok; double v; } R[] = {
        { "0.35", 0, 1, 0.35 }, { "-1e-3", 1, 1, -1e-3 }, { ".5", 0, 1, 0.5 }, { "5.", 0, 1, 5 },
        { "1E+2", 0, 1, 100 }, { "1e-999", 0, 1, 0 },
        { "0x0.8", 0, 0, 0 }, { "0x10", 1, 0, 0 }, { "+1", 0, 0, 0 }, { " 1", 0, 0, 0 }, { "1 ", 0, 0, 0 },
        { "inf", 1, 0, 0 }, { "nan", 1, 0, 0 }, { "1e999", 0, 0, 0 }, { "", 0, 0, 0 }, { "-", 1, 0, 0 },
        { ".", 0, 0, 0 }, { "1e", 0, 0, 0 }, { "e5", 0, 0, 0 }, { "-0", 0, 0, 0 }, { "-0", 1, 1, 0 },
        { "-2", 0, 0, 0 },
    };
    for (size_t i = 0; i < sizeof R / sizeof R[0]; i++) {
        double v = -12345;
        int rc = base_num_real(R[i].s, R[i].neg_ok, &v);
        TST_CHECK(rc == (R[i].ok ? 0 : -1), "real '%s' neg_ok %d: rc %d", R[i].s, R[i].neg_ok, rc);
        if (R[i].ok && !rc) TST_CHECK(v == R[i].v, "real '%s' = %.17g", R[i].s, v);
    }
    static const struct { const char *s; int neg_ok, ok; long long v; } W[] = {
        { "10", 0, 1, 10 }, { "016", 0, 1, 16 }, { "-7", 1, 1, -7 }, { "9223372036854775807", 0, 1, 9223372036854775807LL },
        { "9223372036854775808", 0, 0, 0 }, { "1e1", 0, 0, 0 }, { "10.0", 0, 0, 0 }, { "0.1e2", 0, 0, 0 },
        { "8e0", 0, 0, 0 }, { "-0", 0, 0, 0 }, { "-1", 0, 0, 0 }, { "+1", 0, 0, 0 }, { "0x8", 0, 0, 0 },
        { " 8", 0, 0, 0 }, { "", 0, 0, 0 }, { "-", 1, 0, 0 },
    };
    for (size_t i = 0; i < sizeof W / sizeof W[0]; i++) {
        long long v = -12345;
        int rc = base_num_whole(W[i].s, W[i].neg_ok, &v);
        TST_CHECK(rc == (W[i].ok ? 0 : -1), "whole '%s' neg_ok %d: rc %d", W[i].s, W[i].neg_ok, rc);
        if (W[i].ok && !rc) TST_CHECK(v == W[i].v, "whole '%s' = %lld", W[i].s, v);
    }
}

/* Lines: the limit is max bytes, a longer line or a NUL stops the
 * reading there (the bytes after it are still unread). */
static void line_bounded(void)
{
    char text[] = "abc\n\nxyzw\nlast";
    FILE *f = fmemopen(text, strlen(text), "r");
    char buf[8];
    TST_EQ_INT(base_line_read(f, buf, 4), 3); TST_EQ_STR(buf, "abc");
    TST_EQ_INT(base_line_read(f, buf, 4), 0); TST_EQ_STR(buf, "");
    TST_EQ_INT(base_line_read(f, buf, 4), 4); TST_EQ_STR(buf, "xyzw");
    TST_EQ_INT(base_line_read(f, buf, 4), 4); TST_EQ_STR(buf, "last");
    TST_EQ_INT(base_line_read(f, buf, 4), BASE_LINE_EOF);
    fclose(f);
    char longer[] = "abcdefgh\n";
    f = fmemopen(longer, strlen(longer), "r");
    TST_EQ_INT(base_line_read(f, buf, 4), BASE_LINE_LONG);
    TST_EQ_INT(ftell(f), 5);        /* max + 1 bytes read, no more */
    fclose(f);
    char nul[] = "ab\0cd\n";
    f = fmemopen(nul, 6, "r");
    TST_EQ_INT(base_line_read(f, buf, 4), BASE_LINE_NUL);
    TST_EQ_INT(ftell(f), 3);
    fclose(f);
    /* A stream that never ends: the reading stops at the limit. */
    f = fopen("/dev/zero", "r");
    if (f) {
        TST_EQ_INT(base_line_read(f, buf, 4), BASE_LINE_NUL);
        fclose(f);
    }
}

int main(void)
{
    TST_RUN(json_nonfinite_is_null);
    TST_RUN(num_strict_syntax);
    TST_RUN(line_bounded);
    TST_RUN(json_17_digits_round_trip);
    TST_RUN(json_fewer_digits_within_half_unit);
    TST_RUN(json_string_escapes);
    TST_RUN(near_distance_by_hand);
    TST_RUN(near_choice);
    TST_RUN(join_empty_and_one);
    TST_RUN(join_truncation);
    TST_RUN(par_every_item_once);
    TST_RUN(par_same_result_any_threads);
    TST_RUN(pool_loops_and_tasks);
    TST_EXIT();
}
