/* sim_batch.c - levelized evaluation of a primitive netlist over lanes.
 *
 * This file builds the schedule (sim_batch_new: elements set up by
 * sim_batch_op.c, levelized, registers ordered) and answers the accessors;
 * sim_batch_eval.c evaluates it. Built from what sim_prim_describe says
 * of each element (the same record the Verilog export reads), so the
 * batch mode and the kernel share one description of the hardware. Each
 * element's quantization is sim_quant_into's, step for step (sim_quant.h),
 * so a lane's values are the kernel's.
 *
 * Where the time goes: one pass over the schedule per clock, each element
 * a loop over the lanes that reads its operands' arrays and writes its
 * output's; no event lists, no per-element dispatch per lane. An element
 * whose exact result provably fits 62 bits does the arithmetic in int64_t
 * (as the kernel's fast path); the rest, and any lane whose fast result
 * falls out of range, take the exact 128-bit path.
 */
#include "sim/sim_batch_int.h"
#include "sim/sim_prim.h"
#include "sim/sim_toggle.h"
#include <stdlib.h>
#include <string.h>

/* The widest vector loops a batch may use (the tests lower it); read
 * when a batch is made. */
static uint32_t vec_most = 8;

uint32_t sim_batch_vector(uint32_t most)
{
    vec_most = most;
    return sim__batch_vec_width(most);
}


void sim_batch_free(sim_batch *b)
{
    if (!b) return;
    sim__batch_free_ops(b->comb, b->ncomb);
    sim__batch_free_ops(b->reg, b->nreg);
    free(b->val); free(b->pend); free(b->inslot); free(b->in_sig); free(b->in_mark); free(b->regnx); free(b->regm); free(b->ovf); free(b->chg); free(b->uni);
    free(b->tog); free(b->tprev); free(b->fmask); free(b->rmin); free(b->rmax);
    sim__batch_ovf_free(b);
    free(b);
}

/* Order the combinational elements so that each comes after every element
 * whose output it reads (Kahn's algorithm over signal indices); -1 with the
 * signals of a loop named when there is none. */
static int levelize(sim_batch *b, const sim_ctx *c, bop *ops, uint32_t nops, const sim_prim_info *info,
                    const uint32_t *op_of_sig, char *err, size_t errlen)
{
    uint32_t *indeg = calloc(nops ? nops : 1, sizeof *indeg);
    uint32_t *order = malloc((nops ? nops : 1) * sizeof *order);
    uint32_t *fstart = calloc((size_t)nops + 1, sizeof *fstart);
    uint32_t *fan = NULL, nfan = 0;
    if (!indeg || !order || !fstart) goto oom;
    /* Edges producer -> consumer, counted then filled (CSR). */
    for (uint32_t pass = 0; pass < 2; pass++) {
        uint32_t *fill = NULL;
        if (pass) {
            for (uint32_t i = 0; i < nops; i++) fstart[i + 1] += fstart[i];
            nfan = fstart[nops];
            fan = malloc((nfan ? nfan : 1) * sizeof *fan);
            fill = calloc(nops ? nops : 1, sizeof *fill);
            if (!fan || !fill) { free(fill); goto oom; }
        }
        for (uint32_t i = 0; i < nops; i++) {
            const sim_signal *r[10 + 256];
            const sim_prim_info *in = &info[i];
            int nr = in->kind == SIM_KIND_MUX && in->n > 256 ? -1 : sim_prim_reads(in, r);
            if (nr < 0) { free(fill); snprintf(err, errlen, "a multiplexer with more than 256 inputs"); goto fail; }
            for (int j = 0; j < nr; j++) {
                uint32_t src = op_of_sig[r[j]->index];
                if (src == UINT32_MAX) continue;
                if (!pass) { fstart[src + 1]++; indeg[i]++; }
                else fan[fstart[src] + fill[src]++] = i;
            }
        }
        free(fill);
    }
    uint32_t head = 0, tail = 0;
    for (uint32_t i = 0; i < nops; i++) if (!indeg[i]) order[tail++] = i;
    while (head < tail) {
        uint32_t i = order[head++];
        for (uint32_t e = fstart[i]; e < fstart[i + 1]; e++)
            if (!--indeg[fan[e]]) order[tail++] = fan[e];
    }
    if (tail < nops) {
        char path[256];
        uint32_t k = 0;
        while (k < nops && !indeg[k]) k++;
        snprintf(err, errlen, "combinational loop through %s",
                 sim_signal_path(sim_signal_at(c, ops[k].sig), path, sizeof path));
        goto fail;
    }
    b->comb = malloc((nops ? nops : 1) * sizeof *b->comb);
    if (!b->comb) goto oom;
    for (uint32_t i = 0; i < nops; i++) b->comb[i] = ops[order[i]];
    b->ncomb = nops;
    free(indeg); free(order); free(fstart); free(fan);
    return 0;
oom:
    snprintf(err, errlen, "out of memory");
fail:
    free(indeg); free(order); free(fstart); free(fan);
    return -1;
}

/* Registers update in place (each writes its new value straight over the
 * old) when every register that reads another's output directly comes
 * before it in b->reg: the reader has then sampled the old value. A
 * pipeline of registers is put in that order (readers first: a topological
 * order of "reads" edges, Kahn's algorithm); a register reading itself
 * samples its own old value anyway. Registers in a ring (two or more
 * reading each other) have no such order: b->reg_inplace stays 0 and a
 * cycle computes every new value before storing any. -1 if out of memory. */
static int order_regs(sim_batch *b)
{
    uint32_t n = b->nreg;
    b->reg_inplace = 1;
    if (n < 2) return 0;
    uint32_t *reg_of_sig = malloc((size_t)b->nsig * sizeof *reg_of_sig);
    uint32_t *indeg = calloc(n, sizeof *indeg), *order = malloc(n * sizeof *order);
    bop *sorted = malloc(n * sizeof *sorted);
    if (!reg_of_sig || !indeg || !order || !sorted) {
        free(reg_of_sig); free(indeg); free(order); free(sorted);
        return -1;
    }
    for (uint32_t i = 0; i < b->nsig; i++) reg_of_sig[i] = UINT32_MAX;
    for (uint32_t i = 0; i < n; i++) reg_of_sig[b->reg[i].sig] = i;
    /* edge reader -> read: the read register waits for its readers */
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < b->reg[i].ndep; k++) {
            uint32_t j = reg_of_sig[b->reg[i].dep[k]];
            if (j != UINT32_MAX && j != i) indeg[j]++;
        }
    uint32_t head = 0, tail = 0;
    for (uint32_t i = 0; i < n; i++) if (!indeg[i]) order[tail++] = i;
    while (head < tail) {
        const bop *p = &b->reg[order[head++]];
        for (int k = 0; k < p->ndep; k++) {
            uint32_t j = reg_of_sig[p->dep[k]];
            if (j != UINT32_MAX && j != reg_of_sig[p->sig] && !--indeg[j]) order[tail++] = j;
        }
    }
    if (tail == n) {
        for (uint32_t i = 0; i < n; i++) sorted[i] = b->reg[order[i]];
        memcpy(b->reg, sorted, n * sizeof *sorted);
    } else {
        b->reg_inplace = 0;
    }
    free(reg_of_sig); free(indeg); free(order); free(sorted);
    return 0;
}

/* The vector loops b uses (none: the scalar ones): one word of lanes, a
 * multiple of the vector's, registers in place; vec_most caps the width
 * (sim_batch_new). */
static void pick_vector_loops(sim_batch *b, uint32_t lanes, uint32_t vec_most)
{
    uint32_t vw = lanes <= 64 && b->reg_inplace ? sim__batch_vec_width(vec_most) : 0;
    if (vw == 8 && lanes % 8) vw = sim__batch_vec_width(4);
    if (vw && lanes % vw) vw = 0;
#if SIM_BATCH_X86
    if (vw == 8) {
        b->vcomb = sim__batch_vec_comb_avx512; b->vreg = sim__batch_vec_reg_avx512; b->vtake = sim__batch_vec_take_avx512;
        b->vfill = sim__batch_vec_fill_avx512; b->vsame = sim__batch_vec_same_avx512;
        b->vsparse = sim__batch_vec_sparse_avx512;
    } else if (vw == 4) {
        b->vcomb = sim__batch_vec_comb_avx2; b->vreg = sim__batch_vec_reg_avx2; b->vtake = sim__batch_vec_take_avx2;
        b->vfill = sim__batch_vec_fill_avx2; b->vsame = sim__batch_vec_same_avx2;
        b->vsparse = sim__batch_vec_sparse_avx2;
    }
#endif
    b->vw = b->vcomb ? vw : 0;
    b->vgroups = b->vw ? lanes / b->vw : 0;
    b->vcount = sim__batch_count_dense;
#if SIM_BATCH_X86
    uint32_t cw = sim__batch_vec_width(vec_most);
    if (cw == 8) b->vcount = sim__batch_count_dense_avx512;
    else if (cw == 4) b->vcount = sim__batch_count_dense_avx2;
#endif
}

sim_batch *sim_batch_new(sim_ctx *c, const sim_signal *clk, uint32_t lanes, char *err, size_t errlen)
{
    if (lanes < 1 || lanes > SIM_BATCH_MAX_LANES) {
        snprintf(err, errlen, "batch of %u lanes: 1 to %d", lanes, SIM_BATCH_MAX_LANES);
        return NULL;
    }
    uint32_t nsig = sim_signal_count(c);
    sim_batch *b = calloc(1, sizeof *b);
    bop *comb = NULL;
    sim_prim_info *info = NULL;
    uint32_t *op_of_sig = NULL;
    uint32_t ncomb = 0, ndriven = 0;
    if (!b) goto oom;
    b->lanes = lanes;
    b->nsig = nsig;
    b->ctx = c;
    b->val = malloc((size_t)(nsig ? nsig : 1) * lanes * sizeof *b->val);
    b->inslot = malloc((nsig ? nsig : 1) * sizeof *b->inslot);
    b->ovf = calloc(lanes, 1);
    b->nw = (lanes + 63) / 64;
    for (uint32_t l = 0; l < lanes; l++) b->all[l >> 6] |= (uint64_t)1 << (l & 63);
    b->chg = calloc((size_t)(nsig ? nsig : 1) * b->nw, sizeof *b->chg);
    b->uni = calloc(nsig ? nsig : 1, 1);
    comb = calloc(nsig ? nsig : 1, sizeof *comb);
    info = calloc(nsig ? nsig : 1, sizeof *info);
    op_of_sig = malloc((nsig ? nsig : 1) * sizeof *op_of_sig);
    b->reg = calloc(nsig ? nsig : 1, sizeof *b->reg);
    b->in_sig = malloc((nsig ? nsig : 1) * sizeof *b->in_sig);
    b->fmask = malloc((nsig ? nsig : 1) * sizeof *b->fmask);
    if (!b->val || !b->inslot || !b->ovf || !b->chg || !b->uni || !comb || !info || !op_of_sig || !b->reg || !b->in_sig || !b->fmask) goto oom;

    /* Every signal's value now in every lane; classify the drivers. */
    char path[256];
    for (uint32_t i = 0; i < nsig; i++) {
        sim_signal *s = sim_signal_at(c, i);
        for (uint32_t l = 0; l < lanes; l++) b->val[(size_t)i * lanes + l] = s->cur;
        b->fmask[i] = sim_toggle_mask(s);
        op_of_sig[i] = UINT32_MAX;
        b->inslot[i] = -1;
        if (s->kind == SIM_KIND_CONST) continue;
        if (!s->driver) {
            if (s != clk) { b->inslot[i] = (int32_t)b->nin; b->in_sig[b->nin++] = i; }
            continue;
        }
        ndriven++;
        sim_prim_info in;
        if (sim_prim_describe(s, &in)) {
            snprintf(err, errlen, "%s is driven by a process that is not a primitive",
                     sim_signal_path(s, path, sizeof path));
            goto fail;
        }
        bop *p = sim_kind_role(in.kind) == SIM_ELEM_SEQ ? &b->reg[b->nreg] : &comb[ncomb];
        if (sim__batch_op_setup(b, p, s, &in, clk, err, errlen)) goto fail;
        if (sim_kind_role(in.kind) == SIM_ELEM_SEQ) {
            /* what it samples: input, enable, reset */
            p->dep = malloc(3 * sizeof *p->dep);
            if (!p->dep) goto oom;
            if (in.a) p->dep[p->ndep++] = in.a->index;
            if (in.c) p->dep[p->ndep++] = in.c->index;
            if (in.rst) p->dep[p->ndep++] = in.rst->index;
            b->nreg++;
            continue;
        }
        const sim_signal *r[10 + 256];
        int nr = in.kind == SIM_KIND_MUX && in.n > 256 ? 0 : sim_prim_reads(&in, r);
        p->dep = malloc((size_t)(nr ? nr : 1) * sizeof *p->dep);
        if (!p->dep) goto oom;
        for (int k = 0; k < nr; k++) p->dep[k] = r[k]->index;
        p->ndep = nr;
        info[ncomb] = in;
        op_of_sig[i] = ncomb++;
    }
    if (order_regs(b)) goto oom;
    pick_vector_loops(b, lanes, vec_most);
    if (sim_proc_count(c) != ndriven) {
        snprintf(err, errlen, "the design has %u processes that drive no signal (testbench or user processes)",
                 sim_proc_count(c) - ndriven);
        goto fail;
    }
    if (levelize(b, c, comb, ncomb, info, op_of_sig, err, errlen)) goto fail;
    free(comb); comb = NULL;   /* the ops moved into b->comb (their arrays with them) */
    b->pend = malloc((size_t)(b->nin ? b->nin : 1) * lanes * sizeof *b->pend);
    b->in_mark = calloc(b->nin ? b->nin : 1, 1);
    b->regnx = malloc((size_t)(b->nreg ? b->nreg : 1) * lanes * sizeof *b->regnx);
    b->regm = calloc((size_t)(b->nreg ? b->nreg : 1) * b->nw, sizeof *b->regm);
    if (!b->pend || !b->in_mark || !b->regnx || !b->regm) goto oom;
    for (uint32_t i = 0; i < b->nin; i++)
        memcpy(b->pend + (size_t)i * lanes, b->val + (size_t)b->in_sig[i] * lanes, lanes * sizeof *b->pend);
    for (uint32_t i = 0; i < b->nreg; i++) b->reg[i].nx = b->regnx + (size_t)i * lanes;
    free(info);
    free(op_of_sig);
    return b;
oom:
    snprintf(err, errlen, "out of memory");
fail:
    /* ops not moved into b->comb own their arrays (one more may be half
     * set up; calloc left the rest NULL) */
    if (comb) sim__batch_free_ops(comb, ncomb < nsig ? ncomb + 1 : ncomb);
    free(info);
    free(op_of_sig);
    sim_batch_free(b);
    return NULL;
}

uint32_t sim_batch_lanes(const sim_batch *b) { return b->lanes; }

void sim_batch_vector_stats(const sim_batch *b, uint64_t *groups, uint64_t *fell)
{
    *groups = b->vec_groups;
    *fell = b->vec_fell;
}
uint32_t sim_batch_elements(const sim_batch *b) { return b->ncomb + b->nreg; }
int sim_batch_overflowed(const sim_batch *b, uint32_t lane) { return lane < b->lanes && b->ovf[lane]; }

const int64_t *sim_batch_val(const sim_batch *b, const sim_signal *s)
{
    return b->val + (size_t)s->index * b->lanes;
}

const uint64_t *sim_batch_changed(const sim_batch *b, const sim_signal *s)
{
    return b->chg + (size_t)s->index * b->nw;
}

int sim_batch_uniform(const sim_batch *b, const sim_signal *s)
{
    return b->uni[s->index];
}

int64_t *sim_batch_next(sim_batch *b, const sim_signal *s)
{
    if (s->index >= b->nsig || b->inslot[s->index] < 0) return NULL;
    return b->pend + (size_t)b->inslot[s->index] * b->lanes;
}

int sim_batch_set(sim_batch *b, const sim_signal *s, uint32_t lane, int64_t v)
{
    if (s->index >= b->nsig || b->inslot[s->index] < 0 || lane >= b->lanes) return -1;
    b->pend[(size_t)b->inslot[s->index] * b->lanes + lane] = v;
    b->in_mark[b->inslot[s->index]] = 1;
    return 0;
}

void sim_batch_mark(sim_batch *b, const sim_signal *s)
{
    if (s->index >= b->nsig || b->inslot[s->index] < 0) return;
    b->in_mark[b->inslot[s->index]] = 1;
    b->marking = 1;
}
