/* sim_batch_eval.c - the batch mode's evaluation (sim_batch.h): each
 * element's scalar loop over the lanes, the settle in schedule order, the
 * clock edge, and the toggles and ranges counted after a settle. The
 * schedule is sim_batch.c's; the vector loops (sim_batch_vec.h) take a
 * group of lanes where they can.
 *
 * Each element's operation is sim_op.h's, in uint64_t on the fast path
 * and in sim_wide on the exact one, and its quantization sim_quant_into's,
 * step for step (sim_quant.h): the same fast path and the same general
 * path, so a lane's values are the kernel's.
 */
#include "sim/sim_batch_int.h"
#include "sim/sim_quant.h"
#include "sim/sim_toggle.h"
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ quantization */

/* sim_quant_into without the signal: the overflow flags the lane. */
static int64_t quant(const bop *p, sim_wide raw, int src_f, unsigned char *ovf)
{
    int64_t v;
    if (sim__quant_fits(raw, src_f, p->fy.fbits, p->lo, p->hi, p->r, &v)) return v;
    int o = 0;
    v = sim_fx_requant(raw, src_f, p->fy, p->r, p->o, &o);
    if (o) {
        *ovf = 1;
        if (p->owner->oc) sim__batch_ovf_note(p, ovf);
    }
    return v;
}

/* ------------------------------------------------------------- evaluation */

/* sim_op.h's alignment in the fast path's type and in the exact one. */
#define ALIGN64(x, k) SIM_OP_ALIGN(uint64_t, x, k)
#define ALIGNW(x, k)  SIM_OP_ALIGN(sim_wide, x, k)

/* Which lanes an element is evaluated in, and which lanes its output
 * changed in, are bit masks over the lanes (64 a word): an element is
 * evaluated only in the lanes where one of its inputs changed at this
 * edge, as the kernel wakes an element only on a change. Where every lane
 * of a word needs it (the datapath, busy every clock) the loop runs over
 * the word's 64 lanes without looking at bits; where a few do (a
 * coefficient network that changes once an item) only those. */
#define FOR_LANES(l, m, nw, body) do {                                         \
        for (uint32_t w_ = 0; w_ < (nw); w_++) {                               \
            uint64_t m_ = (m)[w_], acc_ = 0;                                   \
            if (m_ == UINT64_MAX) {                                            \
                for (uint32_t l = w_ * 64; l < w_ * 64 + 64; l++) { body }      \
            } else {                                                           \
                while (m_) {                                                   \
                    uint32_t l = w_ * 64 + (uint32_t)__builtin_ctzll(m_);       \
                    m_ &= m_ - 1;                                              \
                    body                                                       \
                }                                                              \
            }                                                                  \
            om[w_] |= acc_;                                                    \
        }                                                                      \
    } while (0)
/* Lane l's new value v of the output y (a local: stores through y may
 * alias any int64_t, so nothing the loop needs is read through p). */
#define PUT(l, v) do { int64_t v_ = (v);                                       \
        acc_ |= (uint64_t)(y[l] != v_) << ((l) & 63);                          \
        y[l] = v_; } while (0)
/* The fast result s (exact, |s| < 2^62) quantized, or the exact path when
 * it lands out of range (an overflow). */
#define FAST_Q(s, l) do {                                                      \
        int64_t s_ = (s);                                                      \
        int64_t x_ = SIM_OP_QUANT(s_, radd, k);                                \
        if (__builtin_expect(!SIM_OP_IN_SPAN(x_, ulo, span), 0))               \
            x_ = quant(p, s_, p->src_f, &ovf[l]);                              \
        PUT(l, x_);                                                            \
    } while (0)

/* Evaluate p in the lanes of mask m (nw words); the lanes its output
 * changed in go into om. */
static void eval_comb(const bop *p, const uint64_t *m, uint32_t nw, unsigned char *ovf, uint64_t *om)
{
    const int64_t *a = p->a, *b = p->b, *c = p->c;
    int64_t *const y = p->y;
    const uint64_t ulo = (uint64_t)p->lo, span = (uint64_t)p->hi - ulo;   /* in range: x - lo <= span */
    const uint64_t radd = (uint64_t)p->radd;
    const int k = p->k, sa = p->sa, sb = p->sb, fa = p->fa, src_f = p->src_f, n = p->n;
    int64_t *const *in = p->in;
    switch (p->kind) {
    case B_WIRE:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q(a[l], l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, a[l], fa, &ovf[l])););
        break;
    case B_ADD:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)SIM_OP_ADD(uint64_t, ALIGN64(a[l], sa), ALIGN64(b[l], sb)), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, SIM_OP_ADD(sim_wide, ALIGNW(a[l], sa), ALIGNW(b[l], sb)), src_f, &ovf[l])););
        break;
    case B_SUB:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)SIM_OP_SUB(uint64_t, ALIGN64(a[l], sa), ALIGN64(b[l], sb)), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, SIM_OP_SUB(sim_wide, ALIGNW(a[l], sa), ALIGNW(b[l], sb)), src_f, &ovf[l])););
        break;
    case B_MUL:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)SIM_OP_MUL(uint64_t, a[l], b[l]), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, SIM_OP_MUL(sim_wide, a[l], b[l]), src_f, &ovf[l])););
        break;
    case B_SHIFT:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)ALIGN64(a[l], sa), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, ALIGNW(a[l], sa), src_f, &ovf[l])););
        break;
    case B_BK:
        FOR_LANES(l, m, nw, {
            if (!c[l]) PUT(l, 0);
            else if (p->fast) FAST_Q(a[l], l);
            else PUT(l, quant(p, a[l], fa, &ovf[l]));
        });
        break;
    case B_MUX:
        if (p->fast) {
            /* each input's own shift: a multiplexer of operands with
             * different fraction bits (the adaptive unit's coefficient
             * select) stays on the fast path */
            const int *ik = p->in_k;
            const int64_t *ir = p->in_radd;
            FOR_LANES(l, m, nw, {
                uint64_t sel = (uint64_t)c[l];
                if (!SIM_OP_SEL_IN(sel, n)) { PUT(l, 0); continue; }
                int64_t raw = in[sel][l];
                int64_t x = SIM_OP_QUANT(raw, ir[sel], ik[sel]);
                if (__builtin_expect(!SIM_OP_IN_SPAN(x, ulo, span), 0)) x = quant(p, raw, p->in_f[sel], &ovf[l]);
                PUT(l, x);
            });
            break;
        }
        FOR_LANES(l, m, nw, {
            int64_t sel = c[l];
            if (!SIM_OP_SEL_IN(sel, n)) PUT(l, 0);
            else PUT(l, quant(p, in[sel][l], p->in_f[sel], &ovf[l]));
        });
        break;
    case B_LOGIC:
        if (p->tab) {
            /* the index's pieces in locals (stores to y may alias p's
             * fields); one and two inputs, the common control logic,
             * without the inner loop */
            const int64_t *tab = p->tab;
            const int64_t *i0 = n > 0 ? in[0] : NULL, *i1 = n > 1 ? in[1] : i0;
            const uint64_t m0 = p->tmask[0], m1 = n > 1 ? p->tmask[1] : 0;
            const int s1 = n > 1 ? p->tsh[1] : 0;
            if (n == 1) {
                FOR_LANES(l, m, nw, PUT(l, tab[(uint64_t)i0[l] & m0]););
            } else if (n == 2) {
                FOR_LANES(l, m, nw, PUT(l, tab[((uint64_t)i0[l] & m0) | (((uint64_t)i1[l] & m1) << s1)]););
            } else {
                /* more inputs: a full word of lanes builds its 64 indices
                 * input by input (loops the compiler vectorizes), a sparse
                 * word lane by lane */
                uint64_t tm[8];
                int ts[8];
                for (int i = 0; i < n; i++) { tm[i] = p->tmask[i]; ts[i] = p->tsh[i]; }
                for (uint32_t w = 0; w < nw; w++) {
                    uint64_t mw = m[w], acc_ = 0;
                    if (mw == UINT64_MAX) {
                        uint64_t ix[64];
                        const uint32_t l0 = w * 64;
                        for (uint32_t j = 0; j < 64; j++) ix[j] = (uint64_t)i0[l0 + j] & tm[0];
                        for (int i = 1; i < n; i++) {
                            const int64_t *v = in[i] + l0;
                            const uint64_t mi = tm[i];
                            const int si = ts[i];
                            for (uint32_t j = 0; j < 64; j++) ix[j] |= ((uint64_t)v[j] & mi) << si;
                        }
                        for (uint32_t j = 0; j < 64; j++) PUT(l0 + j, tab[ix[j]]);
                    } else {
                        while (mw) {
                            uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(mw);
                            mw &= mw - 1;
                            uint64_t ix = 0;
                            for (int i = 0; i < n; i++) ix |= ((uint64_t)in[i][l] & tm[i]) << ts[i];
                            PUT(l, tab[ix]);
                        }
                    }
                    om[w] |= acc_;
                }
            }
            break;
        }
        FOR_LANES(l, m, nw, {
            int64_t v[8];
            for (int i = 0; i < n; i++) v[i] = in[i][l];
            PUT(l, sim__canon(p->fn(v, p->user), p->fy));
        });
        break;
    }
}

/* A register's fields the per-lane step reads, copied into locals once
 * per register: y's stores may alias whatever an int64_t pointer reaches,
 * so read through p they would be reloaded on every lane. */
typedef struct regv {
    const int64_t *a, *en, *rst, *y;
    int64_t  rst_raw, lo;
    uint64_t span, radd;      /* in range: (uint64_t)(x - lo) <= span */
    int      k, fast, fa;
} regv;

static inline regv reg_view(const bop *p)
{
    return (regv){ p->a, p->c, p->rst, p->y, p->rst_raw, p->lo, (uint64_t)p->hi - (uint64_t)p->lo,
                   (uint64_t)p->radd, p->k, p->fast, p->fa };
}

/* Register p's value after the edge in lane l, from the values before it. */
static inline int64_t reg_next(const regv *r, const bop *p, uint32_t l, unsigned char *ovf)
{
    if (r->rst && r->rst[l]) return r->rst_raw;
    if ((r->en && !r->en[l]) || !r->a) return r->y[l];
    if (r->fast) {
        int64_t x = SIM_OP_QUANT(r->a[l], r->radd, r->k);
        if (SIM_OP_IN_SPAN(x, (uint64_t)r->lo, r->span)) return x;
    }
    return quant(p, r->a[l], r->fa, &ovf[l]);
}

static void eval_reg(const bop *p, const uint64_t *m, uint32_t nw, unsigned char *ovf)
{
    const regv r = reg_view(p);
    int64_t *nx = p->nx;
    const int64_t *a = p->a, lo = p->lo, hi = p->hi;
    const uint64_t radd = (uint64_t)p->radd;
    const int k = p->k, plain = p->fast && a && !p->c && !p->rst;
    for (uint32_t w = 0; w < nw; w++) {
        uint64_t mw = m[w];
        int d = mw == UINT64_MAX;
        if (d && plain) {
            /* the common register, q <= d, in every lane of the word */
            for (uint32_t l = w * 64; l < w * 64 + 64; l++) {
                int64_t x = SIM_OP_QUANT(a[l], radd, k);
                nx[l] = x >= lo && x <= hi ? x : quant(p, a[l], p->fa, &ovf[l]);
            }
        } else if (d) {
            for (uint32_t l = w * 64; l < w * 64 + 64; l++) nx[l] = reg_next(&r, p, l, ovf);
        } else {
            while (mw) {
                uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(mw);
                mw &= mw - 1;
                nx[l] = reg_next(&r, p, l, ovf);
            }
        }
    }
}

/* 1 if every lane of v holds v[0]. A data row usually differs within the
 * first lanes, so the scan stops at the first block of 8 that differs; a
 * control row in lanes that run in step is read whole. */
static int same_lanes(const int64_t *v, uint32_t n)
{
    const int64_t v0 = v[0];
    uint32_t l = 1;
    for (; l + 8 <= n; l += 8) {
        uint64_t d = 0;
        for (uint32_t j = 0; j < 8; j++) d |= (uint64_t)(v[l + j] ^ v0);
        if (d) return 0;
    }
    for (; l < n; l++) if (v[l] != v0) return 0;
    return 1;
}

/* same_lanes of a row of b, by the vector loop when b has one. */
static inline unsigned char row_same(const sim_batch *b, const int64_t *v)
{
    return (unsigned char)(b->vsame ? b->vsame(v, b->lanes) : same_lanes(v, b->lanes));
}

/* Inputs take the values set for this edge; the lanes each changed in
 * are marked. A testbench that marks what it writes (sim_batch_mark)
 * spares the comparison of the inputs it did not write. */
static void apply_inputs(sim_batch *b)
{
    size_t L = b->lanes;
    for (uint32_t i = 0; i < b->nin; i++) {
        if (b->marking && b->started && !b->in_mark[i]) continue;
        b->in_mark[i] = 0;
        uint32_t sig = b->in_sig[i];
        int64_t *v = b->val + (size_t)sig * L;
        const int64_t *p = b->pend + (size_t)i * L;
        if (!memcmp(v, p, L * sizeof *v)) continue;
        uint64_t *om = b->chg + (size_t)sig * b->nw;
        if (b->vw) {
            /* one pass: the compare, the copy and the uniform check */
            *om |= b->vtake(v, p, b->lanes, &b->uni[sig]);
            continue;
        }
        for (size_t w = 0; w < b->nw; w++) {
            /* the word's bits in a local: om may alias v and p (int64_t
             * and uint64_t), so a store through it would reload them */
            uint64_t acc = 0;
            size_t end = L < 64 * w + 64 ? L : 64 * w + 64;
            for (size_t l = 64 * w; l < end; l++) {
                acc |= (uint64_t)(v[l] != p[l]) << (l & 63);
                v[l] = p[l];
            }
            om[w] |= acc;
        }
        b->uni[sig] = (unsigned char)same_lanes(v, b->lanes);
    }
}

/* p's inputs hold one value in every lane (control, in lanes that run in
 * step): evaluate lane 0 alone and copy it. Returns 0 if they do not.
 * For a register too (in place, at the edge: its inputs' values before
 * it). */
static int eval_uniform(sim_batch *b, const bop *p)
{
    for (int k = 0; k < p->ndep; k++) if (!b->uni[p->dep[k]]) return 0;
    uint64_t one = 1, om0 = 0;
    unsigned char f = 0;
    int64_t *y = p->y, old0 = y[0];
    int was = b->uni[p->sig];
    b->in_uniform = 1;   /* an overflow noted in lane 0 is every lane's */
    if (!b->vsparse || !b->vsparse(p, one, &f, &om0)) sim__batch_lanes(p, one, &f, &om0);
    b->in_uniform = 0;
    if (f) memset(b->ovf, 1, b->lanes);   /* every lane computed the same overflow */
    int64_t v = y[0];
    uint64_t *om = b->chg + (size_t)p->sig * b->nw;
    if (was) {
        if (v == old0) return 1;   /* changed in no lane */
        if (b->vfill) b->vfill(y, v, b->lanes, 0);
        else for (uint32_t l = 1; l < b->lanes; l++) y[l] = v;
        for (uint32_t w = 0; w < b->nw; w++) om[w] = b->all[w];   /* (a word or two: no memcpy call) */
    } else if (b->vfill) {
        om[0] |= om0 | b->vfill(y, v, b->lanes, 1);   /* one word of lanes (vw) */
    } else {
        om[0] |= om0;
        for (uint32_t l = 1; l < b->lanes; l++) {
            om[l >> 6] |= (uint64_t)(y[l] != v) << (l & 63);
            y[l] = v;
        }
    }
    b->uni[p->sig] = 1;
    return 1;
}

/* At least one lane in vw of the batch's (vw: the vector's lanes) is in
 * m: the vector loops then take all of them (four lanes an instruction
 * beat one lane at a time even with three in four computing what they
 * hold; eight, with seven in eight: measured on the span units, where a
 * coefficient network wakes in the few lanes whose interval was just
 * accepted). The bits are counted without the popcnt instruction, which
 * the baseline x86-64 lacks (the compiler would call a library function). */
static inline int wide_enough(uint64_t m, uint32_t lanes, uint32_t vw)
{
    m = m - ((m >> 1) & 0x5555555555555555ull);
    m = (m & 0x3333333333333333ull) + ((m >> 2) & 0x3333333333333333ull);
    m = (m + (m >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return (uint32_t)((m * 0x0101010101010101ull) >> 56) * vw >= lanes;
}

/* After a settle, before the change masks are cleared: each signal's
 * toggles in the lanes it changed in since the last count (every value
 * change of a cycle is in chg: the registers', the inputs' and the
 * combinational elements'). */
SIM__BATCH_COUNT_DENSE(, sim__batch_count_dense)

static void count_toggles(sim_batch *b)
{
    const uint32_t nw = b->nw;
    const size_t L = b->lanes;
    for (uint32_t i = 0; i < b->nsig; i++) {
        const uint64_t *m = b->chg + (size_t)i * nw;
        const int64_t *v = b->val + (size_t)i * L;
        int64_t *pv = b->tprev + (size_t)i * L;
        uint64_t *t = b->tog + (size_t)i * L;
        int64_t *lo = b->rmin ? b->rmin + (size_t)i * L : NULL, *hi = b->rmax ? b->rmax + (size_t)i * L : NULL;
        const uint64_t mask = b->fmask[i];
        if (nw == 1) {
            /* many lanes changed: every lane, with no mask (a datapath busy every clock) */
            if (!m[0]) continue;
            if (wide_enough(m[0], b->lanes, 4)) { b->vcount(v, pv, t, mask, lo, hi, (uint32_t)L); continue; }
        }
        for (uint32_t w = 0; w < nw; w++) {
            uint64_t mw = m[w];
            /* a word of lanes mostly changed: all its lanes by the vector
             * loop, as for one word above (more than 64 lanes: a unit over
             * a list of items, tb_items.c, 128 lanes a group) */
            uint32_t l0 = w * 64, wl = L - l0 < 64 ? (uint32_t)(L - l0) : 64;
            if (nw > 1 && mw && wide_enough(mw, wl, 4)) {
                b->vcount(v + l0, pv + l0, t + l0, mask, lo ? lo + l0 : NULL, hi ? hi + l0 : NULL, wl);
                continue;
            }
            while (mw) {
                uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(mw);
                mw &= mw - 1;
                t[l] += sim_toggle_popcount(((uint64_t)v[l] ^ (uint64_t)pv[l]) & mask);
                pv[l] = v[l];
                /* a value a lane settles on is one it holds before the next edge */
                if (lo) {
                    if (v[l] < lo[l]) lo[l] = v[l];
                    if (v[l] > hi[l]) hi[l] = v[l];
                }
            }
        }
    }
}

/* Settle: each element in order, in the lanes where one of its inputs
 * changed (the others would compute what they hold). */
/* settle for at most 64 lanes once started (a scene's bands, the bench's
 * streams): each mask one word, no loops over words (for which the
 * compiler called memset and looped per element). An element whose inputs
 * changed in one lane alone is evaluated there without the uniform check:
 * lanes that hold one value change together. (Visiting only the elements
 * an input change reaches, with readers' lists, was slower on the span
 * units: most of their elements have an input that changes in some lane
 * at every edge.) */
static void settle1(sim_batch *b)
{
    uint64_t *chg = b->chg;
    const unsigned char *uni = b->uni;
    const bop *p = b->comb, *end = p + b->ncomb;
    for (; p < end; p++) {
        /* the lanes to evaluate, and whether every input is uniform (the
         * loads side by side: no call to eval_uniform when one is not) */
        uint64_t m = 0;
        unsigned u = 1;
        const uint32_t *dep = p->dep;
        for (int k = 0; k < p->ndep; k++) { m |= chg[dep[k]]; u &= uni[dep[k]]; }
        if (!m) continue;
        if ((m & (m - 1)) && u && p->ndep && eval_uniform(b, p)) continue;
        if (!b->vw) eval_comb(p, &m, 1, b->ovf, chg + p->sig);
        else if (wide_enough(m, b->lanes, b->vw) && b->vcomb(p, b->lanes, b->ovf, chg + p->sig, &b->vec_fell))
            b->vec_groups += b->vgroups;
        else if (!b->vsparse(p, m, b->ovf, chg + p->sig))
            eval_comb(p, &m, 1, b->ovf, chg + p->sig);
        b->uni[p->sig] = 0;
    }
    for (uint32_t i = 0; i < b->nreg; i++) {
        const bop *r = &b->reg[i];
        uint64_t rm = b->regm[i];
        for (int k = 0; k < r->ndep; k++) rm |= chg[r->dep[k]];
        b->regm[i] = rm;
    }
    if (b->tog) count_toggles(b);
}

static void settle(sim_batch *b)
{
    uint32_t nw = b->nw;
    if (nw == 1 && b->started) { settle1(b); return; }
    uint64_t *chg = b->chg, m[SIM_BATCH_MAX_LANES / 64];
    for (uint32_t i = 0; i < b->ncomb; i++) {
        const bop *p = &b->comb[i];
        uint64_t any = 0;
        if (!b->started) {
            for (uint32_t w = 0; w < nw; w++) m[w] = b->all[w];
            any = 1;
        } else {
            for (uint32_t w = 0; w < nw; w++) m[w] = 0;
            for (int k = 0; k < p->ndep; k++) {
                const uint64_t *dm = chg + (size_t)p->dep[k] * nw;
                for (uint32_t w = 0; w < nw; w++) m[w] |= dm[w];
            }
            for (uint32_t w = 0; w < nw; w++) any |= m[w];
        }
        if (!any) continue;
        if (b->started && p->ndep && eval_uniform(b, p)) continue;
        eval_comb(p, m, nw, b->ovf, chg + (size_t)p->sig * nw);
        b->uni[p->sig] = !b->started ? (unsigned char)same_lanes(p->y, b->lanes) : 0;
    }
    /* what each register must look at in the next edge */
    for (uint32_t i = 0; i < b->nreg; i++) {
        const bop *p = &b->reg[i];
        uint64_t *rm = b->regm + (size_t)i * nw;
        if (!b->started) { memcpy(rm, b->all, nw * sizeof *rm); continue; }
        for (int k = 0; k < p->ndep; k++) {
            const uint64_t *dm = chg + (size_t)p->dep[k] * nw;
            for (uint32_t w = 0; w < nw; w++) rm[w] |= dm[w];
        }
    }
    if (b->tog && b->started) count_toggles(b);
}

void sim_batch_start(sim_batch *b)
{
    for (uint32_t i = 0; i < b->nsig; i++) b->uni[i] = (unsigned char)same_lanes(b->val + (size_t)i * b->lanes, b->lanes);
    apply_inputs(b);
    settle(b);
    if (b->oc) sim__batch_ovf_step(b);
    b->started = 1;
    if (b->tog) memcpy(b->tprev, b->val, (size_t)b->nsig * b->lanes * sizeof *b->tprev);
}

int sim_batch_toggles_on(sim_batch *b)
{
    if (b->tog) return 0;
    size_t n = (size_t)(b->nsig ? b->nsig : 1) * b->lanes;
    b->tog = calloc(n, sizeof *b->tog);
    b->tprev = malloc(n * sizeof *b->tprev);
    if (!b->tog || !b->tprev) {
        free(b->tog); free(b->tprev);
        b->tog = NULL; b->tprev = NULL;
        return -1;
    }
    memcpy(b->tprev, b->val, (size_t)b->nsig * b->lanes * sizeof *b->tprev);
    return 0;
}

int sim_batch_ranges_on(sim_batch *b)
{
    if (b->rmin) return 0;
    if (sim_batch_toggles_on(b)) return -1;
    size_t n = (size_t)(b->nsig ? b->nsig : 1) * b->lanes;
    b->rmin = malloc(n * sizeof *b->rmin);
    b->rmax = malloc(n * sizeof *b->rmax);
    if (!b->rmin || !b->rmax) {
        free(b->rmin); free(b->rmax);
        b->rmin = b->rmax = NULL;
        return -1;
    }
    for (uint32_t l = 0; l < b->lanes; l++) sim_batch_range_reset(b, l);
    return 0;
}

void sim_batch_range_reset(sim_batch *b, uint32_t lane)
{
    if (!b->rmin) return;
    for (uint32_t i = 0; i < b->nsig; i++) {
        size_t at = (size_t)i * b->lanes + lane;
        b->rmin[at] = b->rmax[at] = b->val[at];
    }
}

void sim_batch_range(const sim_batch *b, const sim_signal *s, uint32_t lane, int64_t *mn, int64_t *mx)
{
    size_t at = (size_t)s->index * b->lanes + lane;
    *mn = b->rmin ? b->rmin[at] : b->val[at];
    *mx = b->rmax ? b->rmax[at] : b->val[at];
}

const uint64_t *sim_batch_toggles(const sim_batch *b, const sim_signal *s)
{
    return b->tog && s->index < b->nsig ? b->tog + (size_t)s->index * b->lanes : NULL;
}

/* Register p in place, in the lanes of rm (then cleared): its new value
 * straight into y, the lanes it changed in into om. Right only in
 * b->reg's order when b->reg_inplace (order_regs): every register reading
 * p's output directly has sampled it before, and nothing else reads a
 * register's output before the settle. */
static uint64_t reg_inplace(const bop *p, uint64_t *rm, uint64_t *om, uint32_t nw, unsigned char *ovf)
{
    const regv r = reg_view(p);
    int64_t *y = p->y;
    const int64_t *a = p->a, lo = p->lo, hi = p->hi;
    const uint64_t radd = (uint64_t)p->radd;
    const int k = p->k, plain = p->fast && a && !p->c && !p->rst;
    uint64_t any = 0;
    for (uint32_t w = 0; w < nw; w++) {
        uint64_t mw = rm[w], acc = 0;
        int d = mw == UINT64_MAX;
        if (d && plain) {
            for (uint32_t l = w * 64; l < w * 64 + 64; l++) {
                int64_t x = SIM_OP_QUANT(a[l], radd, k);
                if (__builtin_expect(x < lo || x > hi, 0)) x = quant(p, a[l], p->fa, &ovf[l]);
                acc |= (uint64_t)(y[l] != x) << (l & 63);
                y[l] = x;
            }
        } else if (d) {
            for (uint32_t l = w * 64; l < w * 64 + 64; l++) {
                int64_t x = reg_next(&r, p, l, ovf);
                acc |= (uint64_t)(y[l] != x) << (l & 63);
                y[l] = x;
            }
        } else if (plain) {
            while (mw) {
                uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(mw);
                mw &= mw - 1;
                int64_t x = SIM_OP_QUANT(a[l], radd, k);
                if (__builtin_expect(x < lo || x > hi, 0)) x = quant(p, a[l], p->fa, &ovf[l]);
                acc |= (uint64_t)(y[l] != x) << (l & 63);
                y[l] = x;
            }
        } else {
            while (mw) {
                uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(mw);
                mw &= mw - 1;
                int64_t x = reg_next(&r, p, l, ovf);
                acc |= (uint64_t)(y[l] != x) << (l & 63);
                y[l] = x;
            }
        }
        om[w] |= acc;
        any |= acc;
        rm[w] = 0;
    }
    return any;
}

void sim__batch_lanes(const bop *p, uint64_t m, unsigned char *ovf, uint64_t *om)
{
    if (p->kind == B_REG) reg_inplace(p, &m, om, 1, ovf);
    else eval_comb(p, &m, 1, ovf, om);
}

void sim_batch_cycle(sim_batch *b)
{
    /* Every register reads the values before the edge, then all change at
     * once: the kernel's evaluate/update, without the lists. A register
     * whose input, enable and reset did not change in a lane since the
     * last edge would load what it holds there: only the other lanes
     * (regm) are evaluated. The last edge's change masks are cleared
     * here, not after its settle: sim_batch_changed reads them. */
    uint32_t nw = b->nw;
    memset(b->chg, 0, (size_t)b->nsig * nw * sizeof *b->chg);
    if (b->oc) sim__batch_ovf_before_edge(b);
    if (b->reg_inplace) {
        for (uint32_t i = 0; i < b->nreg; i++) {
            bop *p = &b->reg[i];
            if (b->vw && b->regm[i]) {
                /* a control register in lanes that run in step: lane 0, copied */
                if (eval_uniform(b, p)) { b->regm[i] = 0; continue; }
                uint64_t om = 0;
                int wide = wide_enough(b->regm[i], b->lanes, b->vw);
                if (wide ? b->vreg(p, b->lanes, b->ovf, &om, &b->vec_fell) : b->vsparse(p, b->regm[i], b->ovf, &om)) {
                    if (wide) b->vec_groups += b->vgroups;
                    b->regm[i] = 0;
                    b->chg[p->sig] |= om;
                    if (om) b->uni[p->sig] = row_same(b, p->y);
                    continue;
                }
            }
            if (reg_inplace(p, b->regm + (size_t)i * nw, b->chg + (size_t)p->sig * nw, nw, b->ovf))
                b->uni[p->sig] = row_same(b, p->y);
        }
        apply_inputs(b);
        settle(b);
        if (b->oc) sim__batch_ovf_step(b);
        return;
    }
    for (uint32_t i = 0; i < b->nreg; i++) eval_reg(&b->reg[i], b->regm + (size_t)i * nw, nw, b->ovf);
    for (uint32_t i = 0; i < b->nreg; i++) {
        bop *p = &b->reg[i];
        uint64_t *rm = b->regm + (size_t)i * nw, *om = b->chg + (size_t)p->sig * nw, any = 0;
        int64_t *y = p->y;
        const int64_t *nx = p->nx;
        for (uint32_t w = 0; w < nw; w++) {
            uint64_t mw = rm[w], acc = 0;
            if (mw == UINT64_MAX) {
                for (uint32_t l = w * 64; l < w * 64 + 64; l++) {
                    acc |= (uint64_t)(y[l] != nx[l]) << (l & 63);
                    y[l] = nx[l];
                }
                mw = 0;
            }
            while (mw) {
                uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(mw);
                mw &= mw - 1;
                acc |= (uint64_t)(y[l] != nx[l]) << (l & 63);
                y[l] = nx[l];
            }
            om[w] |= acc;
            any |= acc;
            rm[w] = 0;
        }
        if (any) b->uni[p->sig] = (unsigned char)same_lanes(p->y, b->lanes);
    }
    apply_inputs(b);
    settle(b);
    if (b->oc) sim__batch_ovf_step(b);
}
