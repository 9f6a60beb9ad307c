/* sim_batch_op.c - one element of the batch mode's schedule, set up from
 * what sim_prim_describe says of it (the record the Verilog export reads
 * too): its kind (the evaluation sim_elem.h's eval column names), operand
 * rows, and whether the int64_t fast path applies. */
#include "sim/sim_batch_int.h"
#include "sim/sim_quant.h"
#include "sim/sim_lut.h"
#include <stdlib.h>

/* The fast path's constants for an exact result with src_f fraction bits;
 * 1 when it applies (as sim_prim.c's fast_quant_setup). */
static int fast_setup(bop *p, int src_f)
{
    p->src_f = src_f;
    return sim__quant_fast(src_f, p->fy.fbits, p->r, &p->k, &p->radd);
}

/* An exact result with fewer fraction bits than y (an adder's or a
 * shift's, whose operands of wa and wb bits are aligned by left shifts
 * sa, sb; wb 0: no second operand) is aligned to y's fraction bits at
 * once: the same value, so the same quantization, and the fast path
 * (which only shifts right) then applies. Only when the aligned operands
 * stay within the fast path's 61 bits; otherwise nothing changes. */
static void widen_src(bop *p, int wa, int wb)
{
    int d = p->fy.fbits - p->src_f;
    if (d <= 0 || !sim__op_fits_aligned(wa, p->sa + d) || (wb && !sim__op_fits_aligned(wb, p->sb + d))) return;
    p->sa += d;
    p->sb += d;
    p->src_f += d;
}

/* A logic element whose inputs have at most SIM_LUT_BITS bits in all is
 * tabulated once (sim_lut.h, in the two's complement code: an index is
 * the inputs' low bits, masked and shifted side by side), so that
 * evaluating it is an index and a load instead of a call per lane. */
static void logic_table(bop *p, const sim_prim_info *in)
{
    int bits = sim_lut_layout(in->n, in->in, SIM_LUT_BITS, p->tsh, p->tmask);
    if (bits < 0) return;
    /* at least 16 entries (zeros after the table's): the vector loops
     * load a small table whole into registers */
    int64_t *t = calloc(bits < 4 ? 16 : (size_t)1 << bits, sizeof *t);
    if (!t) return;   /* evaluated by calls instead */
    sim_lut_fill(t, bits, in->n, in->in, p->tmask, SIM_LUT_TWOS, in->fn, in->user, p->fy);
    p->tab = t;
}

#define ROW(s) (b->val + (size_t)(s)->index * b->lanes)

/* A multiplexer's or a logic element's inputs: 0, -1 out of memory, 1
 * when one of them is the clock. A multiplexer is fast when every input
 * is (as fast_setup for each one's fraction bits). */
static int setup_mux(sim_batch *b, bop *p, const sim_prim_info *in, const sim_signal *clk)
{
    size_t n = (size_t)(in->n ? in->n : 1);
    p->n = in->n;
    p->in = malloc(n * sizeof *p->in);
    p->in_f = malloc(n * sizeof *p->in_f);
    p->in_k = malloc(n * sizeof *p->in_k);
    p->in_radd = malloc(n * sizeof *p->in_radd);
    if (!p->in || !p->in_f || !p->in_k || !p->in_radd) return -1;
    int fast = in->n > 0;
    for (int i = 0; i < in->n; i++) {
        p->in[i] = ROW(in->in[i]);
        p->in_f[i] = in->in[i]->fmt.fbits;
        int k;
        p->in_radd[i] = 0;
        int fi = sim__quant_fast(p->in_f[i], p->fy.fbits, p->r, &k, &p->in_radd[i]);
        fast &= sim__op_fits_copy(sim__raw_bits(in->in[i])) && fi;
        p->in_k[i] = fi ? k : 0;
    }
    p->fast = fast;
    for (int i = 0; i < in->n; i++)
        if (in->in[i] == clk) return 1;
    return 0;
}

static int setup_logic(sim_batch *b, bop *p, const sim_prim_info *in, const sim_signal *clk)
{
    p->n = in->n;
    p->fn = in->fn;
    p->user = in->user;
    p->in = malloc((size_t)(in->n ? in->n : 1) * sizeof *p->in);
    if (!p->in) return -1;
    for (int i = 0; i < in->n; i++) {
        p->in[i] = ROW(in->in[i]);
        if (in->in[i] == clk) return 1;
    }
    logic_table(p, in);
    return 0;
}

int sim__batch_op_setup(sim_batch *b, bop *p, const sim_signal *y, const sim_prim_info *in,
                        const sim_signal *clk, char *err, size_t errlen)
{
    char path[256];
    p->fy = y->fmt;
    p->lo = y->raw_min;
    p->hi = y->raw_max;
    p->r = in->r;
    p->o = in->o;
    p->sig = y->index;
    p->owner = b;
    p->y = ROW(y);
    const sim_signal *reads[10];
    int nreads = 0;
    /* the evaluation the kind takes (an input a sim_assign drives is a
     * copy: sim_elem.h), and the schedule's kind is that one */
    const sim_kind ev = sim_kind_eval(in->kind);
#define B_OF(K, name, role, eval, ...) [SIM_KIND_##K] = B_##eval,
    static const unsigned char b_kind[SIM_KIND__COUNT] = { SIM_ELEM_LIST(B_OF) };
#undef B_OF
    p->kind = b_kind[ev];
    switch (ev) {
    case SIM_KIND_REG:
        if (in->clk != clk) {
            snprintf(err, errlen, "register %s is not clocked by %s", sim_signal_path(y, path, sizeof path), clk->name);
            return -1;
        }
        p->a = in->a ? ROW(in->a) : NULL;
        p->c = in->c ? ROW(in->c) : NULL;
        p->rst = in->rst ? ROW(in->rst) : NULL;
        p->rst_raw = in->rst_raw;
        if (in->a) {
            p->fa = in->a->fmt.fbits;
            p->fast = sim__op_fits_copy(sim__raw_bits(in->a)) && fast_setup(p, p->fa);
        }
        return 0;
    case SIM_KIND_WIRE:   /* sim_assign */
    case SIM_KIND_BK:
        p->a = ROW(in->a);
        p->fa = in->a->fmt.fbits;
        p->fast = sim__op_fits_copy(sim__raw_bits(in->a)) && fast_setup(p, p->fa);
        reads[nreads++] = in->a;
        if (ev == SIM_KIND_BK) { p->c = ROW(in->c); reads[nreads++] = in->c; }
        break;
    case SIM_KIND_ADD:
    case SIM_KIND_SUB:
        p->a = ROW(in->a);
        p->b = ROW(in->b);
        p->src_f = in->src_f;
        p->sa = in->sa;
        p->sb = in->sb;
        widen_src(p, sim__raw_bits(in->a), sim__raw_bits(in->b));
        p->fast = sim__op_fits_aligned(sim__raw_bits(in->a), p->sa) && sim__op_fits_aligned(sim__raw_bits(in->b), p->sb) &&
                  fast_setup(p, p->src_f);
        reads[nreads++] = in->a;
        reads[nreads++] = in->b;
        break;
    case SIM_KIND_MUL:
        p->a = ROW(in->a);
        p->b = ROW(in->b);
        p->src_f = in->src_f;
        p->fast = sim__op_fits_mul(sim__raw_bits(in->a), sim__raw_bits(in->b)) && fast_setup(p, p->src_f);
        reads[nreads++] = in->a;
        reads[nreads++] = in->b;
        break;
    case SIM_KIND_SHIFT: {
        p->a = ROW(in->a);
        p->sa = in->sa;
        p->src_f = in->src_f;
        widen_src(p, sim__raw_bits(in->a), 0);
        p->fast = sim__op_fits_aligned(sim__raw_bits(in->a), p->sa) && fast_setup(p, p->src_f);
        reads[nreads++] = in->a;
        break;
    }
    case SIM_KIND_MUX:
        p->c = ROW(in->c);
        reads[nreads++] = in->c;
        /* its inputs, as a logic element's: */
        /* fall through */
    case SIM_KIND_LOGIC: {
        if (ev == SIM_KIND_LOGIC && in->n > 8) {
            snprintf(err, errlen, "%s: more than 8 inputs", sim_signal_path(y, path, sizeof path));
            return -1;
        }
        int r = ev == SIM_KIND_MUX ? setup_mux(b, p, in, clk) : setup_logic(b, p, in, clk);
        if (r < 0) { snprintf(err, errlen, "out of memory"); return -1; }
        if (r > 0) goto reads_clock;
        break;
    }
    default:
        snprintf(err, errlen, "%s: an element the batch mode does not know", sim_signal_path(y, path, sizeof path));
        return -1;
    }
    for (int i = 0; i < nreads; i++)
        if (reads[i] == clk) goto reads_clock;
    return 0;
reads_clock:
    snprintf(err, errlen, "%s reads the clock as data", sim_signal_path(y, path, sizeof path));
    return -1;
}
#undef ROW

void sim__batch_free_ops(bop *ops, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        free(ops[i].in); free(ops[i].in_f); free(ops[i].in_k); free(ops[i].in_radd); free(ops[i].dep); free(ops[i].tab);
    }
    free(ops);
}
