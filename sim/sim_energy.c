/* sim_energy.c - energy per toggle of each element kind and clock energy
 * (sim_energy.h; the constants' sources are there and in docs/timing.md). */
#include "sim/sim_energy.h"
#include "sim/sim_prim.h"

/* 1/2 C V^2 of the load, fJ (fF V^2 = fJ). */
#define E_LOAD (0.5 * SIM_E_CLOAD * SIM_E_VDD * SIM_E_VDD)

static double add_bit(void) { return SIM_E_FA_S + E_LOAD + 0.5 * (SIM_E_FA_CO + E_LOAD); }

/* One model per value of sim_elem.h's energy column: the energy of one
 * bit toggle of s's output, fJ. */
static double toggle_none(const sim_signal *s) { (void)s; return 0.0; }   /* wires, ports outside */
static double toggle_load(const sim_signal *s) { (void)s; return E_LOAD; }
static double toggle_dff(const sim_signal *s) { (void)s; return SIM_E_DFF_Q + E_LOAD; }
static double toggle_and2(const sim_signal *s) { (void)s; return SIM_E_AND2 + E_LOAD; }
static double toggle_add(const sim_signal *s) { (void)s; return add_bit(); }

static double toggle_mux(const sim_signal *s)
{
    sim_prim_info in;
    int n = sim_prim_describe(s, &in) ? 2 : in.n, lv = 0;
    while (lv < 30 && (1 << lv) < n) lv++;
    return (lv ? lv : 1) * (SIM_E_MUX2 + E_LOAD);
}

static double toggle_mul(const sim_signal *s)
{
    sim_prim_info in;
    if (sim_prim_describe(s, &in) || !in.a || !in.b) return add_bit();
    double wa = in.a->fmt.width, wb = in.b->fmt.width, wy = s->fmt.width;
    double cells = wa * wb * (SIM_E_AND2 + E_LOAD) + (wa - 1) * wb * add_bit();
    return cells / (wy > 0 ? wy : 1);
}

double sim_energy_toggle_fj(const sim_signal *s)
{
#define TOGGLE_OF(K, name, role, eval, vlog, energy, ...) [SIM_KIND_##K] = toggle_##energy,
    static double (*const toggle[SIM_KIND__COUNT])(const sim_signal *) = { SIM_ELEM_LIST(TOGGLE_OF) };
#undef TOGGLE_OF
    return s->kind < SIM_KIND__COUNT ? toggle[s->kind](s) : 0.0;
}

uint64_t sim_energy_flops(const sim_ctx *c)
{
    uint64_t n = 0;
    for (uint32_t i = 0, ns = sim_signal_count(c); i < ns; i++) {
        const sim_signal *s = sim_signal_at(c, i);
        if (s->kind == SIM_KIND_REG) n += (uint64_t)s->fmt.width;
    }
    return n;
}

double sim_energy_clock_fj(const sim_ctx *c)
{
    return (double)sim_energy_flops(c) * SIM_E_DFF_CLOCK;
}
