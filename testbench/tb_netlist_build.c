/* tb_netlist_build.c - a netlist's or datapath file's elements built
 * into a simulation (tb_netlist_int.h: nl_build): the constructors of
 * sim_prim.h in the order of the records, which the reader has checked,
 * so building cannot fail; a datapath file's control tabulated from the
 * chosen schedule. */
#include "testbench/tb_netlist_int.h"
#include "units/units_brdf.h"
#include "sim/sim_area.h"
#include "sim/sim_prim.h"
#include <stdint.h>
#include <string.h>

typedef struct nl_table { int n, w[8]; const uint64_t *v; } nl_table;

static int64_t table_fn(const int64_t *in, void *user)
{
    const nl_table *t = user;
    uint64_t k = 0;
    for (int i = 0; i < t->n; i++) k = k << t->w[i] | ((uint64_t)in[i] & (((uint64_t)1 << t->w[i]) - 1));
    return (int64_t)t->v[k];
}

/* A datapath file's control element (NL_GEN_*) as a table of the step
 * (and in_valid) for schedule s, with its area: the built-in Horner
 * unit's estimates (units/unit_horner.c): an incrementer and the
 * wrap/wait logic, a half adder and two gates a bit; a decoder, two gates
 * per step it decodes and bit it gives. */
static void gen_table(const nl *x, const nl_el *e, int s, sim_ctx *c, nl_table *t, double *area)
{
    int sb = x->step_bits, C = x->sched_clocks[s];
    size_t rows = (size_t)1 << (sb + (e->gen == NL_GEN_NEXT));
    uint64_t *v = sim_alloc(c, rows * sizeof *v);
    for (size_t r = 0; r < rows; r++) {
        int step = (int)(e->gen == NL_GEN_NEXT ? r >> 1 : r);
        if (e->gen == NL_GEN_NEXT) v[r] = (step == 0 && !(r & 1)) || step >= C - 1 ? 0 : (uint64_t)step + 1;
        else if (e->gen == NL_GEN_LAST) v[r] = step == C - 1;
        else v[r] = step < C ? (uint64_t)x->ctl[e->ctl].val[s][step] : 0;
    }
    t->n = e->n;
    t->w[0] = sb;
    t->w[1] = 1;
    t->v = v;
    *area = e->gen == NL_GEN_NEXT ? sb * SIM_GE_HA + 2 * sb : 2.0 * C * e->fmt.width;
}

int nl_build(nl *x, const sim_fmt *fmt, int sched, sim_ctx *c, sim_scope *sc, sim_signal *clk, unit_io *io,
             char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    sim_scope **scs = sim_alloc(c, (size_t)(x->nscope + 1) * sizeof *scs);
    for (int i = 0; i < x->nscope; i++) {
        const char *dot = strrchr(x->scopes[i], '.');
        scs[i] = sim_scope_new(c, x->scope_parent[i] < 0 ? sc : scs[x->scope_parent[i]], dot ? dot + 1 : x->scopes[i]);
    }
    sim_signal **s = sim_alloc(c, (size_t)(x->nel + 1) * sizeof *s);
#define S(k) ((k) == NL_CLK ? clk : (k) == NL_NONE ? NULL : s[k])
    sim_round r0 = sim_get_round(c);
    sim_ovf o0 = sim_get_ovf(c);
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        sim_fmt ef = fmt ? fmt[i] : e->fmt;
        sim_scope *in_sc = e->scope < 0 ? sc : scs[e->scope];
        sim_set_quant(c, e->r >= 0 ? (sim_round)e->r : r0, e->o >= 0 ? (sim_ovf)e->o : o0);
        sim_signal *in[8], **mi = NULL;
        for (int j = 0; j < e->n && j < 8; j++) in[j] = s[e->in[j]];
        switch (e->kind) {
        case SIM_KIND_INPUT: case SIM_KIND_WIRE:
            s[i] = sim_signal_new(c, in_sc, e->leaf, ef, e->kind);
            break;
        case SIM_KIND_CONST:
            s[i] = e->has_value ? sim_const(c, in_sc, e->leaf, ef, e->value) : sim_const_raw(c, in_sc, e->leaf, ef, e->raw);
            if (!e->has_value) s[i]->overflows = e->ovf;   /* value=: sim_const counts its own */
            break;
        case SIM_KIND_REG:
            s[i] = sim_reg(c, in_sc, e->leaf, ef, clk, e->op[OP_A] < i ? S(e->op[OP_A]) : NULL, S(e->op[OP_C]),
                           S(e->op[OP_RST]), e->rst_raw);
            break;
        case SIM_KIND_MUX:
            mi = sim_alloc(c, (size_t)e->n * sizeof *mi);
            for (int j = 0; j < e->n; j++) mi[j] = s[e->in[j]];
            s[i] = sim_mux(c, in_sc, e->leaf, ef, S(e->op[OP_C]), e->n, mi);
            break;
        case SIM_KIND_BK: s[i] = sim_bk(c, in_sc, e->leaf, ef, S(e->op[OP_C]), S(e->op[OP_A])); break;
        case SIM_KIND_ADD: s[i] = sim_add(c, in_sc, e->leaf, ef, S(e->op[OP_A]), S(e->op[OP_B])); break;
        case SIM_KIND_SUB: s[i] = sim_sub(c, in_sc, e->leaf, ef, S(e->op[OP_A]), S(e->op[OP_B])); break;
        case SIM_KIND_MUL:
            s[i] = (e->csd ? brdf_cmul : sim_mul)(c, in_sc, e->leaf, ef, S(e->op[OP_A]), S(e->op[OP_B]));
            break;
        case SIM_KIND_SHIFT: s[i] = sim_shift(c, in_sc, e->leaf, ef, S(e->op[OP_A]), e->shift); break;
        case SIM_KIND_LOGIC: {
            sim_logic_fn fn = e->fn;
            void *user = e->user;
            if (e->bits) {
                nl_bits *b = sim_alloc(c, sizeof *b);
                *b = *e->bits;
                fn = nl_bits_fn;
                user = b;
            } else if (e->table) {
                nl_table *t = sim_alloc(c, sizeof *t);
                t->n = e->n;
                for (int j = 0; j < e->n; j++) t->w[j] = fmt ? fmt[e->in[j]].width : x->el[e->in[j]].fmt.width;
                t->v = e->table;
                fn = table_fn;
                user = t;
            }
            double area = e->area;
            if (e->gen) {
                nl_table *t = sim_alloc(c, sizeof *t);
                gen_table(x, e, sched, c, t, &area);
                fn = table_fn;
                user = t;
            }
            s[i] = sim_logic(c, in_sc, e->leaf, ef, e->n, in, fn, user, area);
            if (e->depth >= 0) sim_logic_depth(s[i], e->depth);
            if (e->verilog) sim_logic_verilog(s[i], e->verilog);
            break;
        }
        default: break;
        }
    }
    sim_set_quant(c, r0, o0);
    /* the forward connections, in the file's order */
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        if (e->kind == SIM_KIND_REG && e->op[OP_A] >= i) sim_reg_connect(s[i], s[e->op[OP_A]]);
        if ((e->kind == SIM_KIND_WIRE || e->kind == SIM_KIND_INPUT) && e->op[OP_A] >= 0) {
            sim_set_quant(c, e->r >= 0 ? (sim_round)e->r : r0, e->o >= 0 ? (sim_ovf)e->o : o0);
            sim_assign(c, s[i], s[e->op[OP_A]]);
            sim_set_quant(c, r0, o0);
        }
    }
    memset(io, 0, sizeof *io);
    for (int j = 0; j < x->nport[P_IN]; j++) io->in[j] = s[x->port[P_IN][j]];
    for (int j = 0; j < x->nport[P_OUT]; j++) io->out[j] = s[x->port[P_OUT][j]];
    io->in_valid = s[x->port[P_IN_VALID][0]];
    io->in_ready = s[x->port[P_IN_READY][0]];
    io->out_valid = s[x->port[P_OUT_VALID][0]];
    io->scope = sc;
#undef S
    return 0;
}

