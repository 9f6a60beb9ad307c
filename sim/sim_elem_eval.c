/* sim_elem_eval.c - the one executable definition of every element kind:
 * the exact operation in 128-bit integers, then the one requantization
 * through sim_fx_requant (sim_fixed.c), with no fast path at all. The
 * reference kernel evaluates every primitive with it (sim_prim.c,
 * sim__elem_step), and tests/test_cells.c holds every other engine (the
 * kernel's inline operations, the batch's scalar and vector loops, the
 * intervals, the Verilog export) to it, exhaustively for narrow formats.
 *
 * It reads the operands' formats, never the record's alignment shifts
 * (src_f, sa, sb), which the fast paths take: working them out again here
 * is what lets a wrong shift in the record show up as a difference. The
 * operations themselves are sim_op.h's, in sim_wide: the ones every other
 * scalar evaluation expands in its own type.
 */
#include "sim/sim_prim.h"
#include "sim/sim_op.h"

static int64_t requant(const sim_prim_info *e, sim_wide exact, int src_f, int *ovf)
{
    return sim_fx_requant(exact, src_f, e->y->fmt, e->r, e->o, ovf);
}

int sim_elem_nin(const sim_prim_info *e)
{
    switch (sim_kind_eval(e->kind)) {
    case SIM_KIND_REG:   return 3;
    case SIM_KIND_MUX:   return 1 + e->n;
    case SIM_KIND_LOGIC: return e->n;
    case SIM_KIND_BK: case SIM_KIND_ADD: case SIM_KIND_SUB: case SIM_KIND_MUL: return 2;
    case SIM_KIND_WIRE: case SIM_KIND_SHIFT: return 1;
    default:             return 0;
    }
}

void sim_elem_read(const sim_prim_info *e, int64_t *v)
{
    if (sim_kind_eval(e->kind) == SIM_KIND_REG) {
        v[0] = e->a ? e->a->cur : 0;
        v[1] = e->c ? e->c->cur : 1;
        v[2] = e->rst ? e->rst->cur : 0;
        return;
    }
    if (sim_kind_eval(e->kind) == SIM_KIND_MUX) {
        v[0] = e->c->cur;
        for (int i = 0; i < e->n; i++) v[1 + i] = e->in[i]->cur;
        return;
    }
    if (sim_kind_eval(e->kind) == SIM_KIND_LOGIC) {
        for (int i = 0; i < e->n; i++) v[i] = e->in[i]->cur;
        return;
    }
    if (sim_kind_eval(e->kind) == SIM_KIND_BK) { v[0] = e->c->cur; v[1] = e->a->cur; return; }
    if (e->a) v[0] = e->a->cur;
    if (e->b) v[1] = e->b->cur;
}

int sim_elem_eval(const sim_prim_info *e, const int64_t *in, int64_t *out, int *ovf)
{
    *ovf = 0;
    const sim_signal *a = e->a, *b = e->b;
    switch (sim_kind_eval(e->kind)) {
    case SIM_KIND_WIRE:      /* a copy: y = quant(a) */
        *out = requant(e, in[0], a->fmt.fbits, ovf);
        return 1;
    case SIM_KIND_REG:       /* at the clock's edge: reset, else load if enabled */
        if (in[2]) { *out = e->rst_raw; return 1; }
        if (!in[1] || !a) return 0;
        *out = requant(e, in[0], a->fmt.fbits, ovf);
        return 1;
    case SIM_KIND_MUX: {     /* a select out of range gives 0 */
        int64_t sel = in[0];
        if (!SIM_OP_SEL_IN(sel, e->n)) { *out = 0; return 1; }
        *out = requant(e, in[1 + sel], e->in[sel]->fmt.fbits, ovf);
        return 1;
    }
    case SIM_KIND_BK:        /* y = pass ? quant(x) : 0 */
        *out = in[0] ? requant(e, in[1], a->fmt.fbits, ovf) : 0;
        return 1;
    case SIM_KIND_ADD:
    case SIM_KIND_SUB: {     /* both aligned to the finer operand's fraction bits */
        int f = a->fmt.fbits > b->fmt.fbits ? a->fmt.fbits : b->fmt.fbits;
        sim_wide x = SIM_OP_ALIGN(sim_wide, in[0], f - a->fmt.fbits);
        sim_wide z = SIM_OP_ALIGN(sim_wide, in[1], f - b->fmt.fbits);
        *out = requant(e, sim_kind_eval(e->kind) == SIM_KIND_ADD ? SIM_OP_ADD(sim_wide, x, z) : SIM_OP_SUB(sim_wide, x, z),
                       f, ovf);
        return 1;
    }
    case SIM_KIND_MUL:       /* the whole product, fraction bits added */
        *out = requant(e, SIM_OP_MUL(sim_wide, in[0], in[1]), a->fmt.fbits + b->fmt.fbits, ovf);
        return 1;
    case SIM_KIND_SHIFT:     /* x 2^sh: the same raw with sh fewer fraction bits */
        *out = requant(e, in[0], a->fmt.fbits - e->shift, ovf);
        return 1;
    case SIM_KIND_LOGIC:     /* the user's function, its low W bits */
        *out = sim_fx_canon(e->fn(in, e->user), e->y->fmt);
        return 1;
    default:                 /* a constant, a clock: no evaluation */
        return 0;
    }
}
