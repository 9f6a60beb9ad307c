/* sim_batch_vec.h - the body of the batch mode's vector loops, written
 * once over a small vocabulary that sim_batch_avx2.c and
 * sim_batch_avx512.c each define for their instruction set and then
 * include this file (it is not a header of its own):
 *
 *   VEC, MASK        a vector of W int64_t lanes; a mask of its lanes
 *   VTARGET          the function attribute that enables the instructions
 *   VNAME(f)         f with the set's suffix (f_avx2, f_avx512)
 *   V_LD(p) V_ST(p, x) V_SET1(x) V_ZERO
 *   V_ADD V_SUB V_SLL(x, c) V_SRA(x, c, c64) V_MUL V_AND V_OR
 *                    c, c64: shift counts k and 64 - k in an __m128i
 *   V_GT(a, b) V_EQ(a, b)          lanes where a > b, a == b (a MASK)
 *   M_AND M_OR M_NOT M_NONE M_ANY(m) M_BITS(m)   masks; M_BITS: bit i is lane i
 *   V_BLEND(m, a, b) V_MASKZ(m, x)        m ? b : a; m ? x : 0
 *   V_GATHER(tab, ix)                     tab[ix] in every lane
 *   V_LUT (optional) V_LUT_T V_LUT_LOAD(tab) V_LUT_OK(fmt) V_LUT_BITS
 *                    tab[ix] from a table of 16 entries held in registers,
 *                    for ix < 2^V_LUT_BITS and entries of format fmt
 *
 * Every loop computes what sim_batch_eval.c's scalar loop computes for the
 * element, lane for lane (see sim_batch_avx2.c for why the results are
 * the same bits).
 */

/* Store x over y[l..l+W-1]; the lanes it changed, as bits l.. of a word. */
static VTARGET inline uint64_t VNAME(put)(int64_t *y, uint32_t l, VEC x)
{
    VEC old = V_LD(y + l);
    V_ST(y + l, x);
    return (uint64_t)M_BITS(M_NOT(V_EQ(old, x))) << (l & 63);
}

static VTARGET inline MASK VNAME(outside)(VEC x, VEC lo, VEC hi)
{
    return M_OR(V_GT(lo, x), V_GT(x, hi));
}

#define GROUP ((uint64_t)((1u << W) - 1) << (l & 63))   /* the lanes l..l+W-1 of a word */

/* The group l..l+W-1 by the scalar loop (a result out of y's range);
 * acc stays in a register. */
#define FALL() do {                                                            \
        uint64_t t_ = 0;                                                       \
        sim__batch_lanes(p, GROUP, ovf, &t_);                                  \
        acc |= t_;                                                             \
        ++*fell;                                                               \
    } while (0)

/* The common tail: q = (s + radd) >> k (s itself without `shift`: no
 * rounding shift, most registers, adders and keys) checked against y's
 * range in the lanes of `live`; stored, or the group done by the scalar
 * loop. */
#define TAIL(s, live, shift) do {                                              \
        VEC q_ = (s);                                                          \
        if (shift) q_ = V_SRA(V_ADD(q_, radd), kk, kk64);                      \
        MASK o_ = M_AND(VNAME(outside)(q_, lo, hi), (live));                   \
        if (__builtin_expect(M_ANY(o_), 0)) FALL();                            \
        else acc |= VNAME(put)(y, l, V_MASKZ((live), q_));                     \
    } while (0)

/* TAIL over every group, a loop of its own with and without the shift. */
#define LOOP(s, live) do {                                                     \
        if (k0) for (l = 0; l < nl; l += W) TAIL(s, live, 0);                  \
        else for (l = 0; l < nl; l += W) TAIL(s, live, 1);                     \
    } while (0)

/* The multiplexer's loops (sim__batch_vec_comb's B_MUX): 0 when p has
 * none here. */
static VTARGET inline __attribute__((always_inline))
int VNAME(vec_mux)(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *fell, uint64_t *om)
{
    const int64_t *c = p->c;
    int64_t *y = p->y;
    const VEC lo = V_SET1(p->lo), hi = V_SET1(p->hi), zero = V_ZERO;
    uint64_t acc = 0;
    uint32_t l;
    /* each input's own shift; a select past the inputs gives 0 */
    if (!p->fast || p->n > 8) return 0;
    int n = p->n;
    __m128i ik[8], ik64[8];
    VEC ir[8];
    int shifts = 0;         /* some input has fraction bits to drop */
    for (int i = 0; i < n; i++) {
        ik[i] = _mm_cvtsi32_si128(p->in_k[i]);
        ik64[i] = _mm_cvtsi32_si128(64 - p->in_k[i]);
        ir[i] = V_SET1(p->in_radd[i]);
        shifts |= p->in_k[i] != 0 || p->in_radd[i] != 0;
    }
    /* every input in every lane, blended by the select (no branch on
     * which inputs a group selects: selects differ lane to lane); a
     * lane that selects none holds 0, which is in y's range, so one
     * range check of the result covers the lanes that select one.
     * The common two inputs without shifts: a loop of their own, the
     * pointers in locals (stores to y may alias p's fields; copying
     * an array of them, the compiler calls a string move) */
    if (n == 2 && !shifts) {
        const int64_t *i0 = p->in[0], *i1 = p->in[1];
        const VEC one = V_SET1(1);
        for (l = 0; l < nl; l += W) {
            const VEC sel = V_LD(c + l);
            VEC q = V_BLEND(V_EQ(sel, zero), zero, V_LD(i0 + l));
            q = V_BLEND(V_EQ(sel, one), q, V_LD(i1 + l));
            if (__builtin_expect(M_ANY(VNAME(outside)(q, lo, hi)), 0)) FALL();
            else acc |= VNAME(put)(y, l, q);
        }
        goto out;
    }
    if (n <= 4) {
        /* up to four inputs (the Horner datapath's coefficient
         * select), unrolled, their pointers in locals */
        const int64_t *ip0 = p->in[0], *ip1 = n > 1 ? p->in[1] : ip0;
        const int64_t *ip2 = n > 2 ? p->in[2] : ip0, *ip3 = n > 3 ? p->in[3] : ip0;
#define MUX_IN(i, ip) if (n > i) {                                             \
            VEC qi = V_LD(ip + l);                                         \
            if (shifts) qi = V_SRA(V_ADD(qi, ir[i]), ik[i], ik64[i]);      \
            q = V_BLEND(V_EQ(sel, V_SET1(i)), q, qi);                      \
        }
        for (l = 0; l < nl; l += W) {
            const VEC sel = V_LD(c + l);
            VEC q = zero;
            MUX_IN(0, ip0) MUX_IN(1, ip1) MUX_IN(2, ip2) MUX_IN(3, ip3)
            if (__builtin_expect(M_ANY(VNAME(outside)(q, lo, hi)), 0)) FALL();
            else acc |= VNAME(put)(y, l, q);
        }
#undef MUX_IN
        goto out;
    }
    for (l = 0; l < nl; l += W) {
        const VEC sel = V_LD(c + l);
        VEC q = zero;
        for (int i = 0; i < n; i++) {
            VEC qi = V_LD(p->in[i] + l);
            if (shifts) qi = V_SRA(V_ADD(qi, ir[i]), ik[i], ik64[i]);
            q = V_BLEND(V_EQ(sel, V_SET1(i)), q, qi);
        }
        if (__builtin_expect(M_ANY(VNAME(outside)(q, lo, hi)), 0)) FALL();
        else acc |= VNAME(put)(y, l, q);
    }
out:
    *om |= acc;
    return 1;
}

/* A logic element's loops (sim__batch_vec_comb's B_LOGIC), from its
 * table: 0 when p has none here. */
static VTARGET inline __attribute__((always_inline))
int VNAME(vec_logic)(const bop *p, uint32_t nl, uint64_t *om)
{
    int64_t *y = p->y;
    uint64_t acc = 0;
    uint32_t l;
    /* a table: the index built input by input, then a gather */
    if (!p->tab || p->n < 1 || p->n > 8) return 0;
    const long long *tab = (const long long *)p->tab;
    int n = p->n;
    VEC mk[8];
    __m128i sh[8];
    for (int i = 0; i < n; i++) {
        mk[i] = V_SET1((int64_t)p->tmask[i]);
        sh[i] = _mm_cvtsi32_si128(p->tsh[i]);
    }
    /* one and two inputs (most control logic) from locals, as the
     * multiplexer's */
    const int64_t *i0 = p->in[0], *i1 = n > 1 ? p->in[1] : i0;
#define LOGIC_IX(ix) VEC ix = V_AND(V_LD(i0 + l), mk[0]);                             \
    if (n == 2) ix = V_OR(ix, V_SLL(V_AND(V_LD(i1 + l), mk[1]), sh[1]));            \
    else for (int i = 1; i < n; i++) ix = V_OR(ix, V_SLL(V_AND(V_LD(p->in[i] + l), mk[i]), sh[i]))
#ifdef V_LUT
    /* a table of at most 2^V_LUT_BITS entries (logic_table pads it
     * to 16) held in registers: permutes instead of a gather */
    const int bits = p->tsh[n - 1] + 64 - __builtin_clzll(p->tmask[n - 1]);
    if (bits <= V_LUT_BITS && V_LUT_OK(p->fy)) {
        const V_LUT_T t = V_LUT_LOAD(p->tab);
        for (l = 0; l < nl; l += W) {
            LOGIC_IX(ix);
            acc |= VNAME(put)(y, l, V_LUT(t, ix));
        }
        goto out;
    }
#endif
    for (l = 0; l < nl; l += W) {
        LOGIC_IX(ix);
        acc |= VNAME(put)(y, l, V_GATHER(tab, ix));
    }
#undef LOGIC_IX
out:
    *om |= acc;
    return 1;
}

VTARGET int VNAME(sim__batch_vec_comb)(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell)
{
    const int64_t *a = p->a, *b = p->b, *c = p->c;
    int64_t *y = p->y;
    const VEC lo = V_SET1(p->lo), hi = V_SET1(p->hi), radd = V_SET1(p->radd), zero = V_ZERO;
    const MASK all = V_EQ(zero, zero);
    const __m128i kk = _mm_cvtsi32_si128(p->k), kk64 = _mm_cvtsi32_si128(64 - p->k);
    const __m128i ssa = _mm_cvtsi32_si128(p->sa), ssb = _mm_cvtsi32_si128(p->sb);
    const int k0 = p->k == 0 && p->radd == 0;
    uint64_t acc = 0;
    uint32_t l;
    switch (p->kind) {
    case B_WIRE:
        if (!p->fast) return 0;
        LOOP(V_LD(a + l), all);
        break;
    case B_ADD:
        if (!p->fast) return 0;
        LOOP(V_ADD(V_SLL(V_LD(a + l), ssa), V_SLL(V_LD(b + l), ssb)), all);
        break;
    case B_SUB:
        if (!p->fast) return 0;
        LOOP(V_SUB(V_SLL(V_LD(a + l), ssa), V_SLL(V_LD(b + l), ssb)), all);
        break;
    case B_SHIFT:
        if (!p->fast) return 0;
        LOOP(V_SLL(V_LD(a + l), ssa), all);
        break;
    case B_MUL:
        if (!p->fast) return 0;
        LOOP(V_MUL(V_LD(a + l), V_LD(b + l)), all);
        break;
    case B_BK:
        /* key 0: y is 0 (no range check there) */
        if (!p->fast) return 0;
        LOOP(V_LD(a + l), M_NOT(V_EQ(V_LD(c + l), zero)));
        break;
    case B_MUX:
        return VNAME(vec_mux)(p, nl, ovf, fell, om);
    case B_LOGIC:
        return VNAME(vec_logic)(p, nl, om);
    default:
        return 0;
    }
    *om |= acc;
    return 1;
}

VTARGET int VNAME(sim__batch_vec_reg)(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell)
{
    /* q <= d, or with an enable: q <= en ? d : q (a reset: the scalar loop) */
    if (!p->fast || !p->a || p->rst) return 0;
    const int64_t *a = p->a, *en = p->c;
    int64_t *y = p->y;
    const VEC lo = V_SET1(p->lo), hi = V_SET1(p->hi), radd = V_SET1(p->radd), zero = V_ZERO;
    const MASK all = V_EQ(zero, zero);
    const __m128i kk = _mm_cvtsi32_si128(p->k), kk64 = _mm_cvtsi32_si128(64 - p->k);
    const int k0 = p->k == 0 && p->radd == 0;
    uint64_t acc = 0;
    uint32_t l;
    /* a loop of its own for each case (the common register has neither
     * an enable nor a rounding shift) */
#define REG_LOOP(EN, SHIFT) for (l = 0; l < nl; l += W) {                     \
        VEC q = V_LD(a + l);                                                   \
        MASK on = EN ? M_NOT(V_EQ(V_LD(en + l), zero)) : all;                  \
        if (SHIFT) q = V_SRA(V_ADD(q, radd), kk, kk64);                        \
        MASK o = M_AND(VNAME(outside)(q, lo, hi), on);                         \
        if (__builtin_expect(M_ANY(o), 0)) { FALL(); continue; }               \
        if (EN) q = V_BLEND(on, V_LD(y + l), q);                               \
        acc |= VNAME(put)(y, l, q);                                            \
    }
    if (en) {
        if (k0) REG_LOOP(1, 0) else REG_LOOP(1, 1)
    } else {
        if (k0) REG_LOOP(0, 0) else REG_LOOP(0, 1)
    }
#undef REG_LOOP
    *om |= acc;
    return 1;
}

/* The few lanes of m (a coefficient network woken in the lanes whose
 * interval was just accepted; a register loading it) one by one: the
 * scalar loop's steps for the common fast elements, with nothing else in
 * the function, so that the per-call cost (what a lane or five share) is
 * a few loads. A lane whose result leaves y's range is left to the
 * scalar loop (sim__batch_lanes), after the others. 0 for an element it
 * does not take. */
#define SPARSE(...) do {                                                       \
        for (uint64_t m_ = m; m_; m_ &= m_ - 1) {                              \
            const uint32_t l = (uint32_t)__builtin_ctzll(m_);                  \
            int64_t x;                                                         \
            __VA_ARGS__                                                        \
            if (__builtin_expect(!SIM_OP_IN_SPAN(x, ulo, span), 0)) {          \
                bad |= m_ & -m_;                                               \
                continue;                                                      \
            }                                                                  \
            acc |= (uint64_t)(y[l] != x) << l;                                 \
            y[l] = x;                                                          \
        }                                                                      \
    } while (0)
/* sim_op.h's operations and fast quantization, as the scalar loop's */
#define FASTQ(s) x = SIM_OP_QUANT(s, radd, k)
#define ALIGN64(v, s) SIM_OP_ALIGN(uint64_t, v, s)

VTARGET int VNAME(sim__batch_vec_sparse)(const bop *p, uint64_t m, unsigned char *ovf, uint64_t *om)
{
    const int64_t *a = p->a, *b = p->b, *c = p->c;
    int64_t *y = p->y;
    const uint64_t ulo = (uint64_t)p->lo, span = (uint64_t)p->hi - ulo, radd = (uint64_t)p->radd;
    const int k = p->k, sa = p->sa, sb = p->sb;
    uint64_t acc = 0, bad = 0;
    if (p->kind != B_LOGIC && !p->fast) return 0;
    switch (p->kind) {
    case B_WIRE: SPARSE(FASTQ(a[l]);); break;
    case B_ADD: SPARSE(FASTQ(SIM_OP_ADD(uint64_t, ALIGN64(a[l], sa), ALIGN64(b[l], sb)));); break;
    case B_SUB: SPARSE(FASTQ(SIM_OP_SUB(uint64_t, ALIGN64(a[l], sa), ALIGN64(b[l], sb)));); break;
    case B_SHIFT: SPARSE(FASTQ(ALIGN64(a[l], sa));); break;
    case B_MUL: SPARSE(FASTQ(SIM_OP_MUL(uint64_t, a[l], b[l]));); break;
    case B_BK: SPARSE(if (c[l]) FASTQ(a[l]); else x = 0;); break;   /* key 0: y is 0, in range */
    case B_MUX: {
        /* a select past the inputs gives 0 */
        const uint64_t n = (uint64_t)p->n;
        int64_t *const *in = p->in;
        const int *ik = p->in_k;
        const int64_t *ir = p->in_radd;
        SPARSE(uint64_t s = (uint64_t)c[l];
               x = SIM_OP_SEL_IN(s, n) ? SIM_OP_QUANT(in[s][l], ir[s], ik[s]) : 0;);
        break;
    }
    case B_LOGIC: {
        if (!p->tab || p->n < 1 || p->n > 2) return 0;
        const int64_t *tab = p->tab, *i0 = p->in[0], *i1 = p->n > 1 ? p->in[1] : p->in[0];
        const uint64_t m0 = p->tmask[0], m1 = p->n > 1 ? p->tmask[1] : 0;
        const int s1 = p->n > 1 ? p->tsh[1] : 0;
        /* a table's entries are in y's range */
        SPARSE(x = tab[((uint64_t)i0[l] & m0) | (((uint64_t)i1[l] & m1) << s1)];);
        break;
    }
    case B_REG: {
        /* in place, as vec_reg: q <= d, with an enable q <= en ? d : q */
        if (!a || p->rst) return 0;
        if (c) SPARSE(if (c[l]) FASTQ(a[l]); else x = y[l];);
        else SPARSE(FASTQ(a[l]););
        break;
    }
    default:
        return 0;
    }
    if (bad) {
        uint64_t t = 0;   /* (acc stays in a register) */
        sim__batch_lanes(p, bad, ovf, &t);
        acc |= t;
    }
    *om |= acc;
    return 1;
}

#undef SPARSE
#undef FASTQ
#undef ALIGN64

VTARGET uint64_t VNAME(sim__batch_vec_take)(int64_t *v, const int64_t *p, uint32_t nl, unsigned char *same)
{
    const VEC p0 = V_SET1(p[0]);
    MASK d = M_NONE;   /* lanes of p that differ from p[0] */
    uint64_t acc = 0;
    for (uint32_t l = 0; l < nl; l += W) {
        VEC x = V_LD(p + l);
        d = M_OR(d, M_NOT(V_EQ(x, p0)));
        acc |= VNAME(put)(v, l, x);
    }
    if (acc) *same = !M_ANY(d);
    return acc;
}

VTARGET uint64_t VNAME(sim__batch_vec_fill)(int64_t *y, int64_t v, uint32_t nl, int changes)
{
    const VEC x = V_SET1(v);
    uint64_t acc = 0;
    if (!changes) {
        uint32_t l = 0;
        for (; l + 4 * W <= nl; l += 4 * W) {   /* (64 lanes: four stores an iteration) */
            V_ST(y + l, x); V_ST(y + l + W, x); V_ST(y + l + 2 * W, x); V_ST(y + l + 3 * W, x);
        }
        for (; l < nl; l += W) V_ST(y + l, x);
        return 0;
    }
    for (uint32_t l = 0; l < nl; l += W) acc |= VNAME(put)(y, l, x);
    return acc;
}

VTARGET int VNAME(sim__batch_vec_same)(const int64_t *v, uint32_t nl)
{
    /* a data row differs within the first lanes: stop there */
    const VEC v0 = V_SET1(v[0]);
    for (uint32_t l = 0; l < nl; l += W)
        if (M_BITS(V_EQ(V_LD(v + l), v0)) != (1u << W) - 1) return 0;
    return 1;
}

#undef GROUP
#undef FALL
#undef TAIL
#undef LOOP
