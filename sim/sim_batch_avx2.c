/* sim_batch_avx2.c - the batch mode's busiest loops, four lanes at a time
 * (AVX2), and where the vector loops are chosen.
 *
 * When most lanes of a batch need an element at an edge (the datapath,
 * busy every clock), sim_batch_eval.c's loop does per lane: load the operands,
 * add or multiply, shift, check y's range, compare with the old value,
 * store. The vector loops (sim_batch_vec.h) run the same steps on four
 * lanes per instruction here, eight with AVX-512 (sim_batch_avx512.c),
 * each compiled for its instructions by a function attribute (a GNU
 * extension gcc and clang share) and used only when the CPU has them
 * (sim__batch_vec_width), so the binary still runs on any x86-64.
 *
 * The results are the scalar loop's, bit for bit: the same exact integer
 * operations (a 64-bit product's low half is the exact product, which the
 * fast path keeps under 2^62; an arithmetic right shift is the floor),
 * and a group of lanes where any fast result leaves y's range goes
 * through the scalar loop whole (it quantizes exactly and flags the
 * overflow). What AVX2 lacks is built from what it has: a 64-bit
 * arithmetic shift from a logical one and the sign, a 64-bit product from
 * three 32x32-bit ones, masks as vectors of all-ones lanes.
 * tests/test_batch.c runs every case with the scalar loops and each set
 * the CPU has.
 */
#include "sim/sim_batch_int.h"

#if SIM_BATCH_X86
#include <immintrin.h>

/* (The CPU's features are read by the compiler's runtime before main, so
 * no __builtin_cpu_init: batches are made from several threads.) */
uint32_t sim__batch_vec_width(uint32_t most)
{
    /* BMI2 (shifts by a register's count in one instruction) came with
     * AVX2 on every CPU that has it; asked for all the same */
    if (!__builtin_cpu_supports("bmi2")) return 0;
    if (most >= 8 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")) return 8;
    if (most >= 4 && __builtin_cpu_supports("avx2")) return 4;
    return 0;
}

#define VTARGET __attribute__((target("avx2,bmi,bmi2")))
#define VNAME(f) f##_avx2
#define W 4
#define VEC __m256i
#define MASK __m256i
#define V_LD(p) _mm256_loadu_si256((const __m256i *)(const void *)(p))
#define V_ST(p, x) _mm256_storeu_si256((__m256i *)(void *)(p), (x))
#define V_SET1(x) _mm256_set1_epi64x(x)
#define V_ZERO _mm256_setzero_si256()
#define V_ADD _mm256_add_epi64
#define V_SUB _mm256_sub_epi64
#define V_AND _mm256_and_si256
#define V_OR _mm256_or_si256
#define V_SLL(x, c) _mm256_sll_epi64((x), (c))
#define V_SRA(x, c, c64) sra_avx2((x), (c), (c64))
#define V_MUL(a, b) mul_avx2((a), (b))
#define V_GT _mm256_cmpgt_epi64
#define V_EQ _mm256_cmpeq_epi64
#define M_AND _mm256_and_si256
#define M_OR _mm256_or_si256
#define M_NOT(m) _mm256_xor_si256((m), _mm256_set1_epi64x(-1))
#define M_NONE _mm256_setzero_si256()
#define M_ANY(m) (!_mm256_testz_si256((m), (m)))
#define M_BITS(m) ((unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(m)))
#define V_BLEND(m, a, b) _mm256_blendv_epi8((a), (b), (m))
#define V_MASKZ(m, x) _mm256_and_si256((m), (x))
#define V_GATHER(tab, ix) _mm256_i64gather_epi64((tab), (ix), 8)

/* x >> k, arithmetic (floor), 0 <= k <= 63: the logical shift with the
 * sign's ones shifted in (a shift by 64 gives 0, so k = 0 is x). */
static VTARGET inline __m256i sra_avx2(__m256i x, __m128i k, __m128i k64)
{
    __m256i neg = _mm256_cmpgt_epi64(_mm256_setzero_si256(), x);
    return _mm256_or_si256(_mm256_srl_epi64(x, k), _mm256_sll_epi64(neg, k64));
}

/* The low 64 bits of a * b: lo*lo + ((hi*lo + lo*hi) << 32). */
static VTARGET inline __m256i mul_avx2(__m256i a, __m256i b)
{
    __m256i ll = _mm256_mul_epu32(a, b);
    __m256i hl = _mm256_mul_epu32(_mm256_srli_epi64(a, 32), b);
    __m256i lh = _mm256_mul_epu32(a, _mm256_srli_epi64(b, 32));
    return _mm256_add_epi64(ll, _mm256_slli_epi64(_mm256_add_epi64(hl, lh), 32));
}

/* A logic element's table of at most 16 entries, each fitting 32 bits
 * (its output's width: at most 31 bits, 32 signed), as two vectors of
 * eight 32-bit entries. The four indices (each under 16, the low half of
 * its lane) are packed into the low half of a vector; vpermd picks entry
 * ix & 7 from each table, bit 3 of ix chooses between them, and the four
 * entries are sign-extended back to 64 bits. Six instructions on
 * registers instead of a gather's four loads. */
typedef struct lut_avx2 { __m256i lo, hi; } lut_avx2_t;

static VTARGET inline __m256i lut_half_avx2(const int64_t *t)
{
    const __m256i low = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);   /* the low halves first */
    __m256i a = _mm256_permutevar8x32_epi32(V_LD(t), low), b = _mm256_permutevar8x32_epi32(V_LD(t + 4), low);
    return _mm256_permute2x128_si256(a, b, 0x20);
}

static VTARGET inline lut_avx2_t lut_load_avx2(const int64_t *t)
{
    return (lut_avx2_t){ lut_half_avx2(t), lut_half_avx2(t + 8) };
}

static VTARGET inline __m256i lut_avx2(lut_avx2_t t, __m256i ix)
{
    __m256i ixp = _mm256_permutevar8x32_epi32(ix, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6));
    __m256 r0 = _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(t.lo, ixp));
    __m256 r1 = _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(t.hi, ixp));
    __m256 r = _mm256_blendv_ps(r0, r1, _mm256_castsi256_ps(_mm256_slli_epi32(ixp, 28)));
    return _mm256_cvtepi32_epi64(_mm256_castsi256_si128(_mm256_castps_si256(r)));
}

#define V_LUT(t, ix) lut_avx2((t), (ix))
#define V_LUT_T lut_avx2_t
#define V_LUT_LOAD(tab) lut_load_avx2(tab)
#define V_LUT_OK(f) ((f).width < 32 || ((f).width == 32 && (f).is_signed))
#define V_LUT_BITS 4

#include "sim/sim_batch_vec.h"

/* sim__batch_count_dense (sim_batch_int.h), four lanes an instruction: the
 * bits counted per byte, the bytes summed by vpsadbw; the range by
 * compare and blend (AVX2 has no 64-bit min and max). */
VTARGET void sim__batch_count_dense_avx2(const int64_t *v, int64_t *pv, uint64_t *t, uint64_t mask, int64_t *lo,
                                         int64_t *hi, uint32_t nl)
{
    const __m256i m55 = _mm256_set1_epi64x(0x5555555555555555ll), m33 = _mm256_set1_epi64x(0x3333333333333333ll);
    const __m256i m0f = _mm256_set1_epi64x(0x0f0f0f0f0f0f0f0fll), mk = _mm256_set1_epi64x((long long)mask);
    uint32_t l = 0;
    for (; l + 4 <= nl; l += 4) {
        __m256i a = V_LD(v + l), x = _mm256_and_si256(_mm256_xor_si256(a, V_LD(pv + l)), mk);
        x = _mm256_sub_epi64(x, _mm256_and_si256(_mm256_srli_epi64(x, 1), m55));
        x = _mm256_add_epi64(_mm256_and_si256(x, m33), _mm256_and_si256(_mm256_srli_epi64(x, 2), m33));
        x = _mm256_and_si256(_mm256_add_epi64(x, _mm256_srli_epi64(x, 4)), m0f);
        V_ST(t + l, _mm256_add_epi64(V_LD(t + l), _mm256_sad_epu8(x, _mm256_setzero_si256())));
        V_ST(pv + l, a);
        if (lo) {
            __m256i b = V_LD(lo + l), c = V_LD(hi + l);
            V_ST(lo + l, _mm256_blendv_epi8(b, a, _mm256_cmpgt_epi64(b, a)));
            V_ST(hi + l, _mm256_blendv_epi8(c, a, _mm256_cmpgt_epi64(a, c)));
        }
    }
    if (l < nl) sim__batch_count_dense(v + l, pv + l, t + l, mask, lo ? lo + l : NULL, hi ? hi + l : NULL, nl - l);
}

#else   /* not x86-64: the scalar loops everywhere */

uint32_t sim__batch_vec_width(uint32_t most) { (void)most; return 0; }

#endif
