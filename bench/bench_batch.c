/* bench_batch.c - batch mode against the event-driven kernel on the same
 * independent streams, one core (no threads), best of 5 (kernel and batch
 * runs taking turns):
 *  - the span units as a scene drives them: 200,000 pixels of random
 *    intervals cut into 64 streams (lanes), tb_span_run_lanes with the
 *    batch on and off (off = tb_span_run on each stream);
 *  - horner3: 200,000 items in 64 streams, tb_batch_run against the same
 *    driver and monitor on the kernel (the simulation tb_run does, without
 *    its exact checks).
 * Outputs are compared (pixels, clocks, overflows): a difference fails the
 * bench. Prints items per second (process CPU time) and the speed-up. */
#include "testbench/study/tb_span.h"
#include "bench/bench_items.h"
#include "testbench/tb_batch.h"
#include "testbench/tb_drive.h"
#include "sim/sim_batch.h"
#include "testbench/tb.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PIXELS 200000
#define LANES 64
#define REPS 5   /* best of: the machine's load moves single runs by tens of percent */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);   /* CPU time: one core, less at the mercy of the load */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double lo_x = 1e9, hi_x = 0;   /* the smallest and largest speed-up */
static void note(double x) { if (x < lo_x) lo_x = x; if (x > hi_x) hi_x = x; }

static int spans(void)
{
    static const char *const units[] = { "span1", "span2", "span3", "span23" };
    static const char *const scheds[] = { "paper", "mac", "pipe" };
    int L = 8;
    tb_span_item *it = calloc(PIXELS, sizeof *it);
    double *pix[2];
    pix[0] = malloc(PIXELS * sizeof *pix[0]);
    pix[1] = malloc(PIXELS * sizeof *pix[1]);
    if (!it || !pix[0] || !pix[1]) return 1;
    size_t ni = bench_span_items(it, PIXELS, L), np = PIXELS;
    for (int u = 0; u < 4; u++)
        for (int sc = 0; sc < 3; sc++) {
            const unit_desc *ud = unit_find(units[u]);
            unit_cfg cfg;
            unit_fmts f;
            bench_span_unit(ud, scheds[sc], L, &cfg, &f);
            tb_span_lane lanes[2][LANES];
            double best[2] = { 1e9, 1e9 };
            for (int mode = 0; mode < 2; mode++) bench_span_lanes(it, ni, pix[mode], lanes[mode], LANES);
            /* kernel and batch in turns, so that both see the same
             * stretches of the machine's load */
            for (int rep = 0; rep < REPS; rep++)
                for (int mode = 0; mode < 2; mode++) {
                    double t0 = now_s();
                    tb_span_run_lanes(ud, &cfg, &f, lanes[mode], LANES, mode);
                    double dt = now_s() - t0;
                    if (dt < best[mode]) best[mode] = dt;
                }
            uint64_t clocks = 0;
            int batched = 0;
            for (int k = 0; k < LANES; k++) {
                const tb_span_lane *x = &lanes[0][k], *y = &lanes[1][k];
                if (x->rc != TB_OK || y->rc != x->rc || x->st.clocks != y->st.clocks || x->st.overflows != y->st.overflows) {
                    fprintf(stderr, "bench: %s %s lane %d: batch and kernel differ\n", units[u], scheds[sc], k);
                    return 1;
                }
                clocks += x->st.clocks;
                batched += y->batched;
            }
            if (memcmp(pix[0], pix[1], np * sizeof *pix[0])) {
                fprintf(stderr, "bench: %s %s: pixels differ\n", units[u], scheds[sc]);
                return 1;
            }
            printf("batch   %-7s %-6s %zu items in %d lanes (%d batched): kernel %.3f s, batch %.3f s: "
                   "%.2f M -> %.2f M items/s, %.1fx\n", units[u], scheds[sc], ni, LANES, batched, best[0], best[1],
                   ni / best[0] / 1e6, ni / best[1] / 1e6, best[0] / best[1]);
            note(best[0] / best[1]);
            (void)clocks;
        }
    free(it);
    free(pix[0]);
    free(pix[1]);
    return 0;
}

/* ------------------------------------------------ horner3 on the kernel */

/* tb_run's driver (tb_drive.h) and monitor */
typedef struct ktb {
    tb_drive drv;
    const unit_io *io;
    int n_out;
    size_t n, got;
    int64_t *raw;
} ktb;

static void kmonitor(sim_proc *p)
{
    ktb *s = p->data;
    if (!s->io->out_valid->cur || s->got >= s->n) return;
    for (int o = 0; o < s->n_out; o++) s->raw[s->got * (size_t)s->n_out + (size_t)o] = s->io->out[o]->cur;
    if (++s->got == s->n) sim_stop(p->ctx);
}

/* One stream on the kernel: the raws of its outputs. */
static int kernel_stream(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, const int64_t *in, size_t n,
                         int64_t *raw)
{
    char err[300];
    tb_built b;
    if (tb_build(u, cfg, f, &b, err, sizeof err)) { fprintf(stderr, "%s\n", err); sim_free(b.c); return -1; }
    sim_ctx *c = b.c;
    sim_signal *clk = b.clk;
    unit_io io = b.io;
    sim_clock(c, clk, 5, 5);
    ktb s = { .io = &io, .n_out = unit_n_out(u), .n = n, .raw = raw };
    tb_drive_raws(&s.drv, unit_n_in(u), in, n);
    s.drv.io = &io; s.drv.ctx = c;
    sim_proc *d = sim_proc_new(c, "tb.driver", tb_drive_proc, &s.drv);
    sim_sensitive(d, clk, SIM_EDGE_POS);
    sim_proc *m = sim_proc_new(c, "tb.monitor", kmonitor, &s);
    sim_sensitive(m, clk, SIM_EDGE_POS);
    m->no_init = 1;
    sim_run(c, (sim_time)-1);
    sim_free(c);
    return s.got == n ? 0 : -1;
}

/* horner3's 200,000 items in 64 lanes (tb_batch_run, no toggles): best
 * of REPS (CPU s) and the clocks of all lanes; clocks_only: nothing else. */
static int horner(int clocks_only)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts f;
    char err[600];
    tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err);
    vec_set vs[LANES];
    tb_batch_lane lanes[LANES];
    memset(lanes, 0, sizeof lanes);
    size_t per = PIXELS / LANES;
    for (int k = 0; k < LANES; k++) {
        if (tb_make_vectors(u, &cfg, per, 100 + (uint64_t)k, &vs[k], err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        lanes[k].vs = &vs[k];
    }
    int n_in = unit_n_in(u), n_out = unit_n_out(u), idx[UNIT_MAX_IO];
    for (int i = 0, k = 0; i < u->nsigs; i++) if (u->sigs[i].role == UNIT_SIG_IN) idx[k++] = i;
    sim_fx_conv cv[UNIT_MAX_IO];   /* each port's quantization, as tb_run and tb_batch_run prepare it */
    for (int i = 0; i < n_in; i++) sim_fx_conv_init(&cv[i], f.f[idx[i]], cfg.rnd, cfg.ovf);
    int64_t *in = malloc(per * (size_t)n_in * sizeof *in), *raw = malloc(per * (size_t)n_out * sizeof *raw);
    double bk = 1e9, bb = 1e9;
    for (int rep = 0; rep < REPS; rep++) {
        double t0 = now_s();
        if (clocks_only) goto batch;
        for (int k = 0; k < LANES; k++) {
            for (size_t r = 0; r < per; r++)
                for (int i = 0; i < n_in; i++)
                    in[r * (size_t)n_in + (size_t)i] = sim_fx_conv_real(&cv[i], vec_row(&vs[k], r)[i], NULL);
            if (kernel_stream(u, &cfg, &f, in, per, raw)) return 1;
            if (rep == 0 && k == LANES - 1) {
                /* compared below with the batch's last lane */
            }
        }
        double dt = now_s() - t0;
        if (dt < bk) bk = dt;
    batch:
        t0 = now_s();
        for (int k = 0; k < LANES; k++) { free(lanes[k].raw); free(lanes[k].beat_cycle); lanes[k].raw = NULL; lanes[k].beat_cycle = NULL; }
        if (tb_batch_run(u, &cfg, &f, lanes, LANES, err, sizeof err) != TB_OK) { fprintf(stderr, "%s\n", err); return 1; }
        dt = now_s() - t0;
        if (dt < bb) bb = dt;
    }
    unsigned long long clocks = 0;
    for (int k = 0; k < LANES; k++) clocks += lanes[k].clocks;
    if (clocks_only) {
        /* bench/verilog/run.sh sets it beside Verilator's eval loop */
        printf("%.6f %llu\n", bb, clocks);
        for (int k = 0; k < LANES; k++) { free(lanes[k].raw); free(lanes[k].beat_cycle); vec_set_free(&vs[k]); }
        free(in); free(raw);
        return 0;
    }
    if (memcmp(raw, lanes[LANES - 1].raw, per * (size_t)n_out * sizeof *raw)) {
        fprintf(stderr, "bench: horner3: batch and kernel differ\n");
        return 1;
    }
    int batched = 0;
    for (int k = 0; k < LANES; k++) batched += lanes[k].batched;
    printf("batch   horner3 paper  %zu items in %d lanes (%d batched): kernel %.3f s, batch %.3f s: "
           "%.2f M -> %.2f M items/s, %.1fx; batch %.1f M clocks/s\n", per * LANES, LANES, batched, bk, bb,
           per * LANES / bk / 1e6, per * LANES / bb / 1e6, bk / bb, (double)clocks / bb / 1e6);
    note(bk / bb);
    for (int k = 0; k < LANES; k++) { free(lanes[k].raw); free(lanes[k].beat_cycle); vec_set_free(&vs[k]); }
    free(in);
    free(raw);
    return 0;
}

/* `bench_batch one UNIT SCHEDULE kernel|batch`: the bench's span streams
 * through one side once, nothing timed or compared, for counting
 * instructions (valgrind --tool=callgrind), which unlike seconds do not
 * depend on the machine's load: docs/batch.md's table. */
static int one(const char *unit, const char *sched, const char *side)
{
    const unit_desc *ud = unit_find(unit);
    int batch = !strcmp(side, "batch");
    if (!ud || (!batch && strcmp(side, "kernel"))) {
        fprintf(stderr, "usage: bench_batch [--vector 0|4|8] [one SPAN_UNIT SCHEDULE kernel|batch]\n");
        return 2;
    }
    int L = 8;
    unit_cfg cfg;
    unit_fmts f;
    if (bench_span_unit(ud, sched, L, &cfg, &f)) { fprintf(stderr, "bench_batch: %s has no schedule %s\n", unit, sched); return 2; }
    tb_span_item *it = calloc(PIXELS, sizeof *it);
    double *pix = malloc(PIXELS * sizeof *pix);
    tb_span_lane *lanes = calloc(LANES, sizeof *lanes);
    if (!it || !pix || !lanes) return 1;
    size_t ni = bench_span_items(it, PIXELS, L);
    bench_span_lanes(it, ni, pix, lanes, LANES);
    tb_span_run_lanes(ud, &cfg, &f, lanes, LANES, batch);
    int rc = 0;
    for (int k = 0; k < LANES; k++) rc |= lanes[k].rc != TB_OK;
    printf("batch   %s %s %s: %zu items in %d lanes%s\n", unit, sched, side, ni, LANES, rc ? ", FAILED" : "");
    free(it);
    free(pix);
    free(lanes);
    return rc;
}

static const char *vector_name(uint32_t w)
{
    return w == 8 ? "AVX-512, 8 lanes an instruction" : w == 4 ? "AVX2, 4 lanes an instruction" : "none (scalar loops)";
}

int main(int argc, char **argv)
{
    /* --vector N: the widest vector loops the batch may use (8, 4 or 0),
     * to compare them on one CPU */
    uint32_t most = 8;
    if (argc >= 3 && !strcmp(argv[1], "--vector")) {
        char *end;
        unsigned long v = strtoul(argv[2], &end, 10);
        if (*end || (v != 0 && v != 4 && v != 8)) { fprintf(stderr, "bench_batch: --vector takes 0, 4 or 8\n"); return 2; }
        most = (uint32_t)v;
        argc -= 2;
        argv += 2;
    }
    uint32_t w = sim_batch_vector(most);
    if (argc == 5 && !strcmp(argv[1], "one")) return one(argv[2], argv[3], argv[4]);
    if (argc == 2 && !strcmp(argv[1], "clocks")) return horner(1);
    if (argc != 1) { fprintf(stderr, "usage: bench_batch [--vector 0|4|8] [one SPAN_UNIT SCHEDULE kernel|batch | clocks]\n"); return 2; }
    printf("batch   vector loops: %s\n", vector_name(w));
    if (horner(0) || spans()) return 1;
    printf("batch   speed-up over the kernel, same items, one core: %.1fx to %.1fx (target 4x)\n", lo_x, hi_x);
    return 0;
}
