/* sim_batch.c - levelized evaluation of a primitive netlist over lanes.
 *
 * Built from what sim_prim_describe says of each element (the same record
 * the Verilog export reads), so the batch mode and the kernel share one
 * description of the hardware. Each element's quantization is
 * sim_quant_into's, step for step: the same fast path (drop k low bits of
 * a value under 2^62 by truncation or half-up, in range) and the same
 * general path (sim_fx_requant), so a lane's values are the kernel's.
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

struct sim_batch {
    uint32_t lanes, nsig;
    int64_t *val;               /* nsig x lanes: every signal's values */
    int64_t *pend;              /* inputs' values for the next edge */
    int32_t *inslot;            /* per signal: its row in pend, or -1 */
    uint32_t nin;
    uint32_t *in_sig;           /* per input row: the signal */
    bop     *comb;  uint32_t ncomb;   /* in topological order */
    bop     *reg;   uint32_t nreg;
    int64_t *regnx;             /* nreg x lanes */
    uint64_t *regm;             /* nreg x nw: lanes to evaluate at the next edge */
    unsigned char *ovf;         /* per lane: some quantization overflowed */
    uint32_t nw;                /* 64-lane words of a mask */
    uint64_t *chg;              /* per signal: lanes it changed in at this edge (nw words) */
    unsigned char *uni;         /* per signal: 1 if every lane holds the same value */
    uint64_t all[SIM_BATCH_MAX_LANES / 64];   /* every lane */
    int      started;
    int      reg_inplace;       /* registers update in place, in b->reg's order (order_regs) */
    uint32_t vw;                /* lanes per vector of the vector loops (0: none; sim_batch_new) */
    uint32_t vgroups;           /* lanes / vw (a division per element was measurable) */
    int    (*vcomb)(const bop *, uint32_t, unsigned char *, uint64_t *, uint64_t *);
    int    (*vreg)(const bop *, uint32_t, unsigned char *, uint64_t *, uint64_t *);
    uint64_t (*vtake)(int64_t *, const int64_t *, uint32_t, unsigned char *);
    uint64_t (*vfill)(int64_t *, int64_t, uint32_t, int);
    int    (*vsame)(const int64_t *, uint32_t);
    int    (*vsparse)(const bop *, uint64_t, unsigned char *, uint64_t *);
    uint64_t vec_groups, vec_fell;   /* groups of lanes (a vector each) they did, and handed back (sim_batch_vector_stats) */
    /* toggle counting (sim_batch_toggles_on), NULL when off */
    uint64_t *tog;              /* nsig x lanes: bit toggles so far */
    int64_t  *tprev;            /* nsig x lanes: the values they are counted from */
    uint64_t *fmask;            /* per signal: its format's bits (sim_toggle_mask) */
    sim__batch_count_fn *vcount;   /* the count in every lane at once (sim_batch_int.h) */
    /* range tracking (sim_batch_ranges_on), NULL when off */
    int64_t  *rmin, *rmax;      /* nsig x lanes: smallest and largest settled value */
};

/* The widest vector loops a batch may use (the tests lower it); read
 * when a batch is made. */
static uint32_t vec_most = 8;

uint32_t sim_batch_vector(uint32_t most)
{
    vec_most = most;
    return sim__batch_vec_width(most);
}

/* ------------------------------------------------------------ quantization */

/* sim_quant_into without the signal: the overflow flags the lane. */
static int64_t quant(const bop *p, sim_wide raw, int src_f, unsigned char *ovf)
{
    int k = src_f - p->fy.fbits;
    if ((unsigned)k < 63 && raw >= -((sim_wide)1 << 62) && raw < ((sim_wide)1 << 62) && p->r != SIM_RND_EVEN) {
        int64_t x = (int64_t)raw;
        if (k && p->r == SIM_RND_HALF_UP) x += (int64_t)1 << (k - 1);
        x >>= k;
        if (x >= p->lo && x <= p->hi) return x;
    }
    int o = 0;
    int64_t v = sim_fx_requant(raw, src_f, p->fy, p->r, p->o, &o);
    if (o) *ovf = 1;
    return v;
}

/* Low W bits of v, sign- or zero-extended (a logic element's output). */
static int64_t canon(int64_t v, sim_fmt f)
{
    int sh = 64 - f.width;
    if (f.is_signed) return (int64_t)((uint64_t)v << sh) >> sh;
    return (int64_t)((uint64_t)v & (UINT64_MAX >> sh));
}

static sim_wide align(int64_t raw, int k) { return (sim_wide)raw * ((sim_wide)1 << k); }

/* ------------------------------------------------------------- evaluation */

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
        int64_t x_ = (int64_t)((uint64_t)s_ + radd) >> k;                      \
        if (__builtin_expect((uint64_t)x_ - ulo > span, 0))                    \
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
    case B_COPY:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q(a[l], l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, a[l], fa, &ovf[l])););
        break;
    case B_ADD:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)(((uint64_t)a[l] << sa) + ((uint64_t)b[l] << sb)), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, align(a[l], sa) + align(b[l], sb), src_f, &ovf[l])););
        break;
    case B_SUB:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)(((uint64_t)a[l] << sa) - ((uint64_t)b[l] << sb)), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, align(a[l], sa) - align(b[l], sb), src_f, &ovf[l])););
        break;
    case B_MUL:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)((uint64_t)a[l] * (uint64_t)b[l]), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, (sim_wide)a[l] * (sim_wide)b[l], src_f, &ovf[l])););
        break;
    case B_SHIFT:
        if (p->fast) FOR_LANES(l, m, nw, FAST_Q((int64_t)((uint64_t)a[l] << sa), l););
        else FOR_LANES(l, m, nw, PUT(l, quant(p, align(a[l], sa), src_f, &ovf[l])););
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
                if (sel >= (uint64_t)n) { PUT(l, 0); continue; }
                int64_t raw = in[sel][l];
                int64_t x = (int64_t)((uint64_t)raw + (uint64_t)ir[sel]) >> ik[sel];
                if (__builtin_expect((uint64_t)x - ulo > span, 0)) x = quant(p, raw, p->in_f[sel], &ovf[l]);
                PUT(l, x);
            });
            break;
        }
        FOR_LANES(l, m, nw, {
            int64_t sel = c[l];
            if (sel < 0 || sel >= n) PUT(l, 0);
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
            PUT(l, canon(p->fn(v, p->user), p->fy));
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
        int64_t x = (int64_t)((uint64_t)r->a[l] + r->radd) >> r->k;
        if ((uint64_t)x - (uint64_t)r->lo <= r->span) return x;
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
                int64_t x = (int64_t)((uint64_t)a[l] + radd) >> k;
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
 * are marked. */
static void apply_inputs(sim_batch *b)
{
    size_t L = b->lanes;
    for (uint32_t i = 0; i < b->nin; i++) {
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
    if (!b->vsparse || !b->vsparse(p, one, &f, &om0)) sim__batch_lanes(p, one, &f, &om0);
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
    memset(chg, 0, (size_t)b->nsig * sizeof *chg);
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
    memset(chg, 0, (size_t)b->nsig * nw * sizeof *chg);
}

void sim_batch_start(sim_batch *b)
{
    for (uint32_t i = 0; i < b->nsig; i++) b->uni[i] = (unsigned char)same_lanes(b->val + (size_t)i * b->lanes, b->lanes);
    apply_inputs(b);
    settle(b);
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
                int64_t x = (int64_t)((uint64_t)a[l] + radd) >> k;
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
                int64_t x = (int64_t)((uint64_t)a[l] + radd) >> k;
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
     * (regm) are evaluated. */
    uint32_t nw = b->nw;
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
}

/* ------------------------------------------------------------ construction */

static int raw_bits(const sim_signal *s) { return s->fmt.width; }

/* The fast path's constants for an exact result with src_f fraction bits;
 * 1 when it applies (as sim_prim.c's fast_quant_setup). */
static int fast_setup(bop *p, int src_f)
{
    p->src_f = src_f;
    p->k = src_f - p->fy.fbits;
    if (p->k < 0 || p->k > 61 || p->r == SIM_RND_EVEN) return 0;
    p->radd = (p->r == SIM_RND_HALF_UP && p->k) ? (int64_t)1 << (p->k - 1) : 0;
    return 1;
}

static int imax(int a, int b) { return a > b ? a : b; }

/* An exact result with fewer fraction bits than y (an adder's or a
 * shift's, whose operands of wa and wb bits are aligned by left shifts
 * sa, sb; wb 0: no second operand) is aligned to y's fraction bits at
 * once: the same value, so the same quantization, and the fast path
 * (which only shifts right) then applies. Only when the aligned operands
 * stay within the fast path's 61 bits; otherwise nothing changes. */
static void widen_src(bop *p, int wa, int wb)
{
    int d = p->fy.fbits - p->src_f;
    if (d <= 0 || wa + p->sa + d > 61 || (wb && wb + p->sb + d > 61)) return;
    p->sa += d;
    p->sb += d;
    p->src_f += d;
}

/* A logic element whose inputs have at most LOGIC_TAB_BITS bits in all is
 * tabulated once (its function is defined for every raw value of its
 * inputs' formats: sim_prim.h), so that evaluating it is an index and a
 * load instead of a call per lane. The index is the inputs' raw bits side
 * by side; a raw is its low W bits, sign-extended back by the format. */
#define LOGIC_TAB_BITS 12
static void logic_table(bop *p, const sim_prim_info *in)
{
    int bits = 0;
    for (int i = 0; i < in->n; i++) {
        p->tsh[i] = bits;
        p->tmask[i] = UINT64_MAX >> (64 - in->in[i]->fmt.width);
        bits += in->in[i]->fmt.width;
        if (bits > LOGIC_TAB_BITS) return;
    }
    /* at least 16 entries (zeros after the table's): the vector loops
     * load a small table whole into registers */
    int64_t *t = calloc(bits < 4 ? 16 : (size_t)1 << bits, sizeof *t);
    if (!t) return;   /* evaluated by calls instead */
    for (uint64_t ix = 0; ix < ((uint64_t)1 << bits); ix++) {
        int64_t v[8];
        for (int i = 0; i < in->n; i++) v[i] = canon((int64_t)((ix >> p->tsh[i]) & p->tmask[i]), in->in[i]->fmt);
        t[ix] = canon(in->fn(v, in->user), p->fy);
    }
    p->tab = t;
}

/* Fill p from the element driving y; -1 (err) for what the batch mode
 * cannot evaluate. */
static int op_setup(sim_batch *b, bop *p, const sim_signal *y, const sim_prim_info *in,
                    const sim_signal *clk, char *err, size_t errlen)
{
    char path[256];
#define ROW(s) (b->val + (size_t)(s)->index * b->lanes)
    p->fy = y->fmt;
    p->lo = y->raw_min;
    p->hi = y->raw_max;
    p->r = in->r;
    p->o = in->o;
    p->sig = y->index;
    p->y = ROW(y);
    const sim_signal *reads[10];
    int nreads = 0;
    switch (in->kind) {
    case SIM_KIND_REG:
        if (in->clk != clk) {
            snprintf(err, errlen, "register %s is not clocked by %s", sim_signal_path(y, path, sizeof path), clk->name);
            return -1;
        }
        p->kind = B_REG;
        p->a = in->a ? ROW(in->a) : NULL;
        p->c = in->c ? ROW(in->c) : NULL;
        p->rst = in->rst ? ROW(in->rst) : NULL;
        p->rst_raw = in->rst_raw;
        if (in->a) {
            p->fa = in->a->fmt.fbits;
            p->fast = raw_bits(in->a) <= 62 && fast_setup(p, p->fa);
        }
        return 0;
    case SIM_KIND_WIRE:   /* sim_assign */
    case SIM_KIND_BK:
        p->kind = in->kind == SIM_KIND_BK ? B_BK : B_COPY;
        p->a = ROW(in->a);
        p->fa = in->a->fmt.fbits;
        p->fast = raw_bits(in->a) <= 62 && fast_setup(p, p->fa);
        reads[nreads++] = in->a;
        if (in->kind == SIM_KIND_BK) { p->c = ROW(in->c); reads[nreads++] = in->c; }
        break;
    case SIM_KIND_ADD:
    case SIM_KIND_SUB:
        p->kind = in->kind == SIM_KIND_ADD ? B_ADD : B_SUB;
        p->a = ROW(in->a);
        p->b = ROW(in->b);
        p->src_f = imax(in->a->fmt.fbits, in->b->fmt.fbits);
        p->sa = p->src_f - in->a->fmt.fbits;
        p->sb = p->src_f - in->b->fmt.fbits;
        widen_src(p, raw_bits(in->a), raw_bits(in->b));
        p->fast = raw_bits(in->a) + p->sa <= 61 && raw_bits(in->b) + p->sb <= 61 && fast_setup(p, p->src_f);
        reads[nreads++] = in->a;
        reads[nreads++] = in->b;
        break;
    case SIM_KIND_MUL:
        p->kind = B_MUL;
        p->a = ROW(in->a);
        p->b = ROW(in->b);
        p->src_f = in->a->fmt.fbits + in->b->fmt.fbits;
        p->fast = raw_bits(in->a) + raw_bits(in->b) <= 62 && fast_setup(p, p->src_f);
        reads[nreads++] = in->a;
        reads[nreads++] = in->b;
        break;
    case SIM_KIND_SHIFT: {
        p->kind = B_SHIFT;
        p->a = ROW(in->a);
        int f = in->a->fmt.fbits - in->shift;
        p->sa = f < 0 ? -f : 0;
        p->src_f = f < 0 ? 0 : f;
        widen_src(p, raw_bits(in->a), 0);
        p->fast = raw_bits(in->a) + p->sa <= 61 && fast_setup(p, p->src_f);
        reads[nreads++] = in->a;
        break;
    }
    case SIM_KIND_MUX: {
        p->kind = B_MUX;
        p->c = ROW(in->c);
        reads[nreads++] = in->c;
        p->n = in->n;
        p->in = malloc((size_t)(in->n ? in->n : 1) * sizeof *p->in);
        p->in_f = malloc((size_t)(in->n ? in->n : 1) * sizeof *p->in_f);
        p->in_k = malloc((size_t)(in->n ? in->n : 1) * sizeof *p->in_k);
        p->in_radd = malloc((size_t)(in->n ? in->n : 1) * sizeof *p->in_radd);
        if (!p->in || !p->in_f || !p->in_k || !p->in_radd) { snprintf(err, errlen, "out of memory"); return -1; }
        /* fast when every input is (as fast_setup for each one's fraction bits) */
        int fast = in->n > 0 && p->r != SIM_RND_EVEN;
        for (int i = 0; i < in->n; i++) {
            p->in[i] = ROW(in->in[i]);
            p->in_f[i] = in->in[i]->fmt.fbits;
            int k = in->in[i]->fmt.fbits - p->fy.fbits;
            fast &= raw_bits(in->in[i]) <= 62 && k >= 0 && k <= 61;
            p->in_k[i] = k >= 0 && k <= 61 ? k : 0;
            p->in_radd[i] = p->r == SIM_RND_HALF_UP && k > 0 && k <= 61 ? (int64_t)1 << (k - 1) : 0;
        }
        p->fast = fast;
        for (int i = 0; i < in->n; i++) {
            if (in->in[i] == clk) goto reads_clock;
        }
        break;
    }
    case SIM_KIND_LOGIC:
        p->kind = B_LOGIC;
        p->n = in->n;
        p->fn = in->fn;
        p->user = in->user;
        if (in->n > 8) { snprintf(err, errlen, "%s: more than 8 inputs", sim_signal_path(y, path, sizeof path)); return -1; }
        p->in = malloc((size_t)(in->n ? in->n : 1) * sizeof *p->in);
        if (!p->in) { snprintf(err, errlen, "out of memory"); return -1; }
        for (int i = 0; i < in->n; i++) {
            p->in[i] = ROW(in->in[i]);
            if (in->in[i] == clk) goto reads_clock;
        }
        logic_table(p, in);
        break;
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
#undef ROW
}

static void free_ops(bop *ops, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        free(ops[i].in); free(ops[i].in_f); free(ops[i].in_k); free(ops[i].in_radd); free(ops[i].dep); free(ops[i].tab);
    }
    free(ops);
}

void sim_batch_free(sim_batch *b)
{
    if (!b) return;
    free_ops(b->comb, b->ncomb);
    free_ops(b->reg, b->nreg);
    free(b->val); free(b->pend); free(b->inslot); free(b->in_sig); free(b->regnx); free(b->regm); free(b->ovf); free(b->chg); free(b->uni);
    free(b->tog); free(b->tprev); free(b->fmask); free(b->rmin); free(b->rmax);
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
        bop *p = in.kind == SIM_KIND_REG ? &b->reg[b->nreg] : &comb[ncomb];
        if (op_setup(b, p, s, &in, clk, err, errlen)) goto fail;
        if (in.kind == SIM_KIND_REG) {
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
    /* the vector loops: one word of lanes, a multiple of the vector's,
     * registers in place */
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
    if (sim_proc_count(c) != ndriven) {
        snprintf(err, errlen, "the design has %u processes that drive no signal (testbench or user processes)",
                 sim_proc_count(c) - ndriven);
        goto fail;
    }
    if (levelize(b, c, comb, ncomb, info, op_of_sig, err, errlen)) goto fail;
    free(comb); comb = NULL;   /* the ops moved into b->comb (their arrays with them) */
    b->pend = malloc((size_t)(b->nin ? b->nin : 1) * lanes * sizeof *b->pend);
    b->regnx = malloc((size_t)(b->nreg ? b->nreg : 1) * lanes * sizeof *b->regnx);
    b->regm = calloc((size_t)(b->nreg ? b->nreg : 1) * b->nw, sizeof *b->regm);
    if (!b->pend || !b->regnx || !b->regm) goto oom;
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
    if (comb) free_ops(comb, ncomb < nsig ? ncomb + 1 : ncomb);
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

int64_t *sim_batch_next(sim_batch *b, const sim_signal *s)
{
    if (s->index >= b->nsig || b->inslot[s->index] < 0) return NULL;
    return b->pend + (size_t)b->inslot[s->index] * b->lanes;
}

int sim_batch_set(sim_batch *b, const sim_signal *s, uint32_t lane, int64_t v)
{
    if (s->index >= b->nsig || b->inslot[s->index] < 0 || lane >= b->lanes) return -1;
    b->pend[(size_t)b->inslot[s->index] * b->lanes + lane] = v;
    return 0;
}
