/* bench_items.h - the stream of span intervals the span benches share:
 * random lengths 1..L (a scene's spans cut into intervals), dv = L or
 * n - 1, degree 2 or 3, node intensities in [0, 1], `pixels` pixels in
 * all; the same sequence every time (a fixed LCG). Also the span unit as
 * these benches configure it and the cut of the stream into lanes. */
#ifndef BENCH_ITEMS_H
#define BENCH_ITEMS_H
#include "testbench/study/tb_span.h"
#include <stdint.h>

/* Fills it[] (room for `pixels` items) and returns the number of items. */
static inline size_t bench_span_items(tb_span_item *it, size_t pixels, int L)
{
    size_t ni = 0, np = 0;
    uint64_t s = 12345;
    while (np < pixels) {
        tb_span_item *m = &it[ni++];
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        m->n = 1 + (int)((s >> 33) % (uint64_t)L);
        if (np + (size_t)m->n > pixels) m->n = (int)(pixels - np);
        m->dv = (s >> 40) & 1 ? L : (m->n > 1 ? m->n - 1 : 1);
        m->deg = (s >> 41) & 1 ? 2 : 3;
        for (int k = 0; k < 4; k++) m->node[k] = (double)((s >> (20 + 5 * k)) & 1023) / 1023;
        np += (size_t)m->n;
    }
    return ni;
}
/* A span unit at interval length L in schedule sched (-1 if it has none),
 * with its default formats, as the span benches run it. */
static inline int bench_span_unit(const unit_desc *u, const char *sched, int L, unit_cfg *cfg, unit_fmts *f)
{
    unit_cfg_default(u, cfg);
    cfg->L = L;
    cfg->schedule = unit_sched_find(u, sched);
    if (cfg->schedule < 0) return -1;
    u->formats(cfg, f);
    return 0;
}

/* The ni items cut into n streams (lanes) of about equal counts, each
 * writing its pixels after the previous one's in pix. */
static inline void bench_span_lanes(const tb_span_item *it, size_t ni, double *pix, tb_span_lane *lanes, int n)
{
    size_t p0 = 0;
    for (int k = 0; k < n; k++) {
        size_t a = ni * (size_t)k / (size_t)n, b = ni * (size_t)(k + 1) / (size_t)n;
        lanes[k] = (tb_span_lane){ .items = it + a, .nitems = b - a, .pix = pix + p0 };
        for (size_t i = a; i < b; i++) p0 += (size_t)it[i].n;
    }
}
#endif
