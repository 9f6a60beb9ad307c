/* bench_span.c - tb_span_run over 200,000 pixels in intervals of random
 * length (1..L, L = 8, dv = L or n - 1, as a scene cuts spans), VCD off:
 * clocks per second of each span unit and schedule, the build included
 * (a scene builds once per band). Best of 3. */
#include "testbench/study/tb_span.h"
#include "bench/bench_items.h"
#include "testbench/tb.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PIXELS 200000

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    static const char *const units[] = { "span1", "span2", "span3", "span23" };
    static const char *const scheds[] = { "paper", "mac", "pipe" };
    int L = 8;
    tb_span_item *it = calloc(PIXELS, sizeof *it);
    double *pix = malloc(PIXELS * sizeof *pix);
    if (!it || !pix) return 1;
    size_t ni = bench_span_items(it, PIXELS, L);
    for (int u = 0; u < 4; u++)
        for (int sc = 0; sc < 3; sc++) {
            const unit_desc *ud = unit_find(units[u]);
            unit_cfg cfg;
            unit_fmts f;
            bench_span_unit(ud, scheds[sc], L, &cfg, &f);
            double best = 1e9;
            tb_span_stats st;
            char err[300];
            for (int rep = 0; rep < 3; rep++) {
                double t0 = now_s();
                if (tb_span_run(ud, &cfg, &f, it, ni, pix, &st, NULL, err, sizeof err) != TB_OK) {
                    fprintf(stderr, "%s: %s\n", units[u], err);
                    return 1;
                }
                double dt = now_s() - t0;
                if (dt < best) best = dt;
            }
            printf("%-7s %-6s %zu items, %llu pixels, %llu clocks: %.3f s = %.2f M clocks/s\n", units[u], scheds[sc], ni,
                   (unsigned long long)st.pixels, (unsigned long long)st.clocks, best, (double)st.clocks / best / 1e6);
        }
    free(it);
    free(pix);
    return 0;
}
