/* bench_kernel.c - kernel speed on a 16-bit, 6-register pipeline:
 *   in -> r0 -> (+1) -> r1 -> (+1) -> ... -> r5
 * with the input changing every clock, VCD off and on. Prints clocks/s and
 * events/s (signal value changes per second). Not a test: figures vary. */
#define _DEFAULT_SOURCE   /* mkstemps */
#include "sim/sim.h"
#include "sim/sim_prim.h"
#include "sim/sim_vcd.h"
#include "base/base_out.h"
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

/* Changes the pipeline input on every rising edge. */
static void stim(sim_proc *p)
{
    sim_signal *in = p->data;
    sim_write(in, (in->cur + 12345) & 0x7fff);
}

static void one(int vcd_on, uint64_t clocks)
{
    sim_ctx *c = sim_new();
    sim_fmt f16 = { .is_signed = 1, .ibits = 16, .fbits = 0, .width = 16 };
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *sc = sim_scope_new(c, NULL, "pipe");
    sim_signal *in = sim_signal_new(c, sc, "in", f16, SIM_KIND_INPUT);
    sim_signal *one_ = sim_const(c, sc, "one", f16, 1.0);
    sim_signal *x = in;
    for (int i = 0; i < 6; i++) {
        char n[8];
        snprintf(n, sizeof n, "r%d", i);
        sim_signal *r = sim_reg(c, sc, n, f16, clk, x, NULL, NULL, 0);
        snprintf(n, sizeof n, "a%d", i);
        x = i < 5 ? sim_add(c, sc, n, f16, r, one_) : r;
    }
    sim_proc *p = sim_proc_new(c, "stim", stim, in);
    sim_sensitive(p, clk, SIM_EDGE_POS);
    sim_clock(c, clk, 5, 5);
    char path[] = "/tmp/shadesim_bench_XXXXXX.vcd", err[200];
    sim_vcd *v = NULL;
    base_out *out = NULL;
    if (vcd_on) {
        int fd = mkstemps(path, 4);
        if (fd >= 0) close(fd);
        out = base_out_open(path, err, sizeof err);   /* as the testbenches write dumps */
        if (!out) { fprintf(stderr, "bench: %s\n", err); exit(1); }
        v = sim_vcd_open(c, base_out_file(out), "1ns");
        if (!v) { fprintf(stderr, "bench: out of memory\n"); exit(1); }
    }
    double t0 = now_s();
    sim_run(c, clocks * 10);
    double dt = now_s() - t0;
    const sim_stats *st = sim_get_stats(c);
    printf("kernel  6-register 16-bit pipeline, VCD %-3s: %8.2f M clocks/s  %8.2f M events/s  (%llu clocks, %llu events, %.3f s)\n",
           vcd_on ? "on" : "off", st->clocks / dt / 1e6, st->events / dt / 1e6,
           (unsigned long long)st->clocks, (unsigned long long)st->events, dt);
    if (v) { sim_vcd_close(v); base_out_close(out, err, sizeof err); unlink(path); }
    sim_free(c);
}

int main(void)
{
    one(0, 4000000);
    one(1, 1000000);
    return 0;
}
