/* bench_strtod.c - base_strtod against strtod: bit for bit on ten
 * million strings of the tests/tst_num.h corpus (random doubles, random
 * digit strings, halfway cases and their neighbours, exponents near the
 * limits, oddities), then the speed of both on what vector files hold
 * (%.17g of values in [-8, 8)). Fails (exit 1) on any difference. */
#include "base/base_strtod.h"
#include "tests/tst_num.h"
#include <stdlib.h>
#include <time.h>

#define CORPUS 10000000u
#define SPEED  1000000u

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    char buf[128], why[300];
    unsigned long bad = 0;
    double t0 = now_s();
    for (uint64_t i = 0; i < CORPUS; i++) {
        tst_num_make(2, i, buf, sizeof buf);
        if (tst_num_check(buf, why, sizeof why) && bad++ < 10) fprintf(stderr, "bench: %s\n", why);
    }
    printf("numbers base_strtod vs strtod on %u strings: %lu differ (%.1f s)\n", CORPUS, bad, now_s() - t0);

    /* Speed: one text of SPEED numbers, parsed by each, best of 3. */
    char *text = malloc((size_t)SPEED * 26 + 1), *p = text;
    if (!text) return 1;
    uint64_t st = 42;
    for (unsigned i = 0; i < SPEED; i++)
        p += sprintf(p, "%.17g ", (double)(int64_t)(tst_num_rand(&st) >> 1) * 0x1p-59 - 8.0);
    double best[2] = { 1e9, 1e9 }, sum[2] = { 0, 0 };
    for (int k = 0; k < 6; k++) {
        int which = k & 1;
        double s = 0, t = now_s();
        char *q = text, *e;
        for (unsigned i = 0; i < SPEED; i++, q = e + 1)
            s += which ? strtod(q, &e) : base_strtod(q, &e);
        t = now_s() - t;
        if (t < best[which]) best[which] = t;
        sum[which] = s;
    }
    free(text);
    if (sum[0] != sum[1]) bad++;
    printf("numbers %u %%.17g values: base_strtod %.1f ns/number, strtod %.1f ns/number (%.1fx; best of 3)\n",
           SPEED, best[0] / SPEED * 1e9, best[1] / SPEED * 1e9, best[1] / best[0]);
    return bad ? 1 : 0;
}
