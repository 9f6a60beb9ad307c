/* sim_batch_avx2.c - the batch mode's busiest loops, four lanes at a time.
 *
 * When every lane of a batch needs an element at an edge (the datapath,
 * busy every clock), sim_batch.c's loop does per lane: load the operands,
 * add or multiply, shift, check y's range, compare with the old value,
 * store. Here the same steps run on four lanes per instruction with AVX2
 * (x86-64), compiled for it by a function attribute (a GNU extension gcc
 * and clang share) and used only when the CPU has it (sim__batch_vec_ok),
 * so the binary still runs on any x86-64.
 *
 * The result is the scalar loop's, bit for bit: the same exact integer
 * operations (a 64-bit product's low half is the exact product, which the
 * fast path keeps under 2^62; an arithmetic right shift is the floor),
 * and a group of four lanes where any fast result leaves y's range goes
 * through the scalar loop whole (it quantizes exactly and flags the
 * overflow). What AVX2 lacks is built from what it has: a 64-bit
 * arithmetic shift from a logical one and the sign, a 64-bit product from
 * three 32x32-bit ones. tests/test_batch.c runs every case with these
 * loops on and off.
 */
#include "sim/sim_batch_int.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

#define AVX2 __attribute__((target("avx2")))

int sim__batch_vec_ok(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
}

static AVX2 inline __m256i ld(const int64_t *p) { return _mm256_loadu_si256((const __m256i *)(const void *)p); }

/* x >> k, arithmetic (floor), 0 <= k <= 63: the logical shift with the
 * sign's ones shifted in (a shift by 64 gives 0, so k = 0 is x). */
static AVX2 inline __m256i sra(__m256i x, __m128i k, __m128i k64)
{
    __m256i neg = _mm256_cmpgt_epi64(_mm256_setzero_si256(), x);
    return _mm256_or_si256(_mm256_srl_epi64(x, k), _mm256_sll_epi64(neg, k64));
}

/* The low 64 bits of a * b: lo*lo + ((hi*lo + lo*hi) << 32). */
static AVX2 inline __m256i mul64(__m256i a, __m256i b)
{
    __m256i ll = _mm256_mul_epu32(a, b);
    __m256i hl = _mm256_mul_epu32(_mm256_srli_epi64(a, 32), b);
    __m256i lh = _mm256_mul_epu32(a, _mm256_srli_epi64(b, 32));
    return _mm256_add_epi64(ll, _mm256_slli_epi64(_mm256_add_epi64(hl, lh), 32));
}

/* Lanes of x outside [lo, hi]. */
static AVX2 inline __m256i outside(__m256i x, __m256i lo, __m256i hi)
{
    return _mm256_or_si256(_mm256_cmpgt_epi64(lo, x), _mm256_cmpgt_epi64(x, hi));
}

/* Store x over y[l..l+3]; the lanes it changed, as bits l..l+3. */
static AVX2 inline uint64_t put(int64_t *y, uint32_t l, __m256i x)
{
    __m256i old = ld(y + l);
    _mm256_storeu_si256((__m256i *)(void *)(y + l), x);
    unsigned same = (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpeq_epi64(old, x)));
    return (uint64_t)(~same & 15u) << (l & 63);
}

/* The common tail: q = (s + radd) >> k checked against y's range (only in
 * the lanes of `live`, all ones where every lane counts); stored, or the
 * group done by the scalar loop. */
#define TAIL(s, live) do {                                                     \
        __m256i q_ = sra(_mm256_add_epi64((s), radd), kk, kk64);               \
        __m256i o_ = _mm256_and_si256(outside(q_, lo, hi), (live));            \
        if (__builtin_expect(!_mm256_testz_si256(o_, o_), 0)) {                \
            sim__batch_lanes(p, (uint64_t)15 << (l & 63), ovf, &acc);          \
            ++*fell;                                                           \
        }                                                                      \
        else acc |= put(y, l, _mm256_and_si256(q_, (live)));                   \
    } while (0)

AVX2 int sim__batch_vec_comb(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell)
{
    const int64_t *a = p->a, *b = p->b, *c = p->c;
    int64_t *y = p->y;
    const __m256i lo = _mm256_set1_epi64x(p->lo), hi = _mm256_set1_epi64x(p->hi);
    const __m256i radd = _mm256_set1_epi64x(p->radd), ones = _mm256_set1_epi64x(-1);
    const __m128i kk = _mm_cvtsi32_si128(p->k), kk64 = _mm_cvtsi32_si128(64 - p->k);
    const __m128i ssa = _mm_cvtsi32_si128(p->sa), ssb = _mm_cvtsi32_si128(p->sb);
    uint64_t acc = 0;
    uint32_t l;
    switch (p->kind) {
    case B_COPY:
        if (!p->fast) return 0;
        for (l = 0; l < nl; l += 4) TAIL(ld(a + l), ones);
        break;
    case B_ADD:
        if (!p->fast) return 0;
        for (l = 0; l < nl; l += 4)
            TAIL(_mm256_add_epi64(_mm256_sll_epi64(ld(a + l), ssa), _mm256_sll_epi64(ld(b + l), ssb)), ones);
        break;
    case B_SUB:
        if (!p->fast) return 0;
        for (l = 0; l < nl; l += 4)
            TAIL(_mm256_sub_epi64(_mm256_sll_epi64(ld(a + l), ssa), _mm256_sll_epi64(ld(b + l), ssb)), ones);
        break;
    case B_SHIFT:
        if (!p->fast) return 0;
        for (l = 0; l < nl; l += 4) TAIL(_mm256_sll_epi64(ld(a + l), ssa), ones);
        break;
    case B_MUL:
        if (!p->fast) return 0;
        for (l = 0; l < nl; l += 4) TAIL(mul64(ld(a + l), ld(b + l)), ones);
        break;
    case B_BK:
        /* key 0: y is 0 (no range check there) */
        if (!p->fast) return 0;
        for (l = 0; l < nl; l += 4) {
            __m256i on = _mm256_xor_si256(_mm256_cmpeq_epi64(ld(c + l), _mm256_setzero_si256()), ones);
            TAIL(ld(a + l), on);
        }
        break;
    case B_MUX: {
        /* each input's own shift; a select past the inputs gives 0 */
        if (!p->fast || p->n > 8) return 0;
        int n = p->n;
        __m128i ik[8], ik64[8];
        __m256i ir[8];
        for (int i = 0; i < n; i++) {
            ik[i] = _mm_cvtsi32_si128(p->in_k[i]);
            ik64[i] = _mm_cvtsi32_si128(64 - p->in_k[i]);
            ir[i] = _mm256_set1_epi64x(p->in_radd[i]);
        }
        for (l = 0; l < nl; l += 4) {
            __m256i sel = ld(c + l), q = _mm256_setzero_si256(), o = _mm256_setzero_si256();
            for (int i = 0; i < n; i++) {
                __m256i hit = _mm256_cmpeq_epi64(sel, _mm256_set1_epi64x(i));
                if (_mm256_testz_si256(hit, hit)) continue;
                __m256i qi = sra(_mm256_add_epi64(ld(p->in[i] + l), ir[i]), ik[i], ik64[i]);
                q = _mm256_or_si256(q, _mm256_and_si256(qi, hit));
                o = _mm256_or_si256(o, _mm256_and_si256(outside(qi, lo, hi), hit));
            }
            if (__builtin_expect(!_mm256_testz_si256(o, o), 0)) {
                sim__batch_lanes(p, (uint64_t)15 << (l & 63), ovf, &acc);
                ++*fell;
            } else {
                acc |= put(y, l, q);
            }
        }
        break;
    }
    case B_LOGIC: {
        /* a table: the index built input by input, then a gather */
        if (!p->tab || p->n < 1 || p->n > 8) return 0;
        const long long *tab = (const long long *)p->tab;
        int n = p->n;
        __m256i mk[8];
        __m128i sh[8];
        for (int i = 0; i < n; i++) {
            mk[i] = _mm256_set1_epi64x((int64_t)p->tmask[i]);
            sh[i] = _mm_cvtsi32_si128(p->tsh[i]);
        }
        for (l = 0; l < nl; l += 4) {
            __m256i ix = _mm256_and_si256(ld(p->in[0] + l), mk[0]);
            for (int i = 1; i < n; i++)
                ix = _mm256_or_si256(ix, _mm256_sll_epi64(_mm256_and_si256(ld(p->in[i] + l), mk[i]), sh[i]));
            acc |= put(y, l, _mm256_i64gather_epi64(tab, ix, 8));
        }
        break;
    }
    default:
        return 0;
    }
    *om |= acc;
    return 1;
}

AVX2 int sim__batch_vec_reg(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell)
{
    /* q <= d, or with an enable: q <= en ? d : q (a reset: the scalar loop) */
    if (!p->fast || !p->a || p->rst) return 0;
    const int64_t *a = p->a, *en = p->c;
    int64_t *y = p->y;
    const __m256i lo = _mm256_set1_epi64x(p->lo), hi = _mm256_set1_epi64x(p->hi);
    const __m256i radd = _mm256_set1_epi64x(p->radd), ones = _mm256_set1_epi64x(-1);
    const __m128i kk = _mm_cvtsi32_si128(p->k), kk64 = _mm_cvtsi32_si128(64 - p->k);
    uint64_t acc = 0;
    for (uint32_t l = 0; l < nl; l += 4) {
        __m256i q = sra(_mm256_add_epi64(ld(a + l), radd), kk, kk64), on = ones;
        if (en) on = _mm256_xor_si256(_mm256_cmpeq_epi64(ld(en + l), _mm256_setzero_si256()), ones);
        __m256i o = _mm256_and_si256(outside(q, lo, hi), on);
        if (__builtin_expect(!_mm256_testz_si256(o, o), 0)) {
            sim__batch_lanes(p, (uint64_t)15 << (l & 63), ovf, &acc);
            ++*fell;
            continue;
        }
        if (en) q = _mm256_blendv_epi8(ld(y + l), q, on);
        acc |= put(y, l, q);
    }
    *om |= acc;
    return 1;
}

AVX2 uint64_t sim__batch_vec_take(int64_t *v, const int64_t *p, uint32_t nl)
{
    uint64_t acc = 0;
    for (uint32_t l = 0; l < nl; l += 4) acc |= put(v, l, ld(p + l));
    return acc;
}

#else   /* no AVX2 build: the scalar loops everywhere */

int sim__batch_vec_ok(void) { return 0; }
int sim__batch_vec_comb(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell)
{
    (void)p; (void)nl; (void)ovf; (void)om; (void)fell;
    return 0;
}
int sim__batch_vec_reg(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell)
{
    (void)p; (void)nl; (void)ovf; (void)om; (void)fell;
    return 0;
}
uint64_t sim__batch_vec_take(int64_t *v, const int64_t *p, uint32_t nl)
{
    (void)v; (void)p; (void)nl;
    return 0;
}
#endif
