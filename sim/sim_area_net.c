/* sim_area_net.c - a design's area terms that depend on its readers
 * (sim_area_net.h): buffer trees and merged adders' incrementers; and
 * sim_scope_area (sim.h), the elements' areas with them. */
#include "sim/sim_area_net.h"
#include "sim/sim_area.h"
#include "sim/sim_live.h"
#include "sim/sim_prim.h"
#include "sim/sim_timing.h"
#include <stdlib.h>

typedef struct net {
    double *sel, *oth;      /* pins one bit drives (sim_timing_pins) */
    int *reads, *adds;      /* its readers, the adders among them */
} net;

static const sim_ctx *scope_ctx(const sim_scope *sc)
{
    if (sc->first_sig) return sc->first_sig->ctx;
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) {
        const sim_ctx *c = scope_ctx(ch);
        if (c) return c;
    }
    return NULL;
}

/* An adder read by one adder alone, as an operand, with no rounding or
 * saturation between: its bits above the chain (an incrementer by the
 * shorter operand's sign or carry, sim_area_addsub) are the multi-operand
 * adder's top bits, which its last adder's incrementer makes once. */
static double merged_ext(const sim_signal *s, const net *n)
{
    sim_prim_info in;
    if ((s->kind != SIM_KIND_ADD && s->kind != SIM_KIND_SUB) || n->reads[s->index] != 1 || n->adds[s->index] != 1
        || sim_prim_describe(s, &in) || in.qlogic || !in.a || !in.b) return 0.0;
    int lo[2], hi[2], chain, ext, low;
    sim_live_span(in.a, &lo[0], &hi[0]);
    sim_live_span(in.b, &lo[1], &hi[1]);
    sim_live_chain(lo, hi, 2, s->fmt, &chain, &ext, &low);
    return ext * SIM_GE_HA;
}

static double walk(const sim_scope *sc, const net *n)
{
    double a = 0;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) {
        if (s->kind == SIM_KIND_CONST || s->kind == SIM_KIND_CLOCK) continue;
        a += s->fmt.width * sim_area_buffers(n->sel[s->index], n->oth[s->index]) - merged_ext(s, n);
    }
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) a += walk(ch, n);
    return a;
}

double sim_area_net(const sim_scope *sc)
{
    const sim_ctx *c = scope_ctx(sc);
    uint32_t k = c ? sim_signal_count(c) : 0;
    if (!k) return 0.0;
    net n = { malloc(k * sizeof *n.sel), malloc(k * sizeof *n.oth), malloc(k * sizeof *n.reads), malloc(k * sizeof *n.adds) };
    double a = 0.0;
    if (n.sel && n.oth && n.reads && n.adds) {
        sim_timing_pins(c, n.sel, n.oth, n.reads, n.adds);
        a = walk(sc, &n);
    }
    free(n.sel); free(n.oth); free(n.reads); free(n.adds);
    return a;
}

static double elements(const sim_scope *sc)
{
    double a = 0;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) a += s->area_ge;
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) a += elements(ch);
    return a;
}

double sim_scope_area(const sim_scope *sc) { return elements(sc) + sim_area_net(sc); }
