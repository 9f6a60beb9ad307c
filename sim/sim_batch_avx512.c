/* sim_batch_avx512.c - the batch mode's vector loops eight lanes at a
 * time (AVX-512F and DQ: 64-bit arithmetic shifts and products, and
 * compares into mask registers, all native). The loops themselves are
 * sim_batch_vec.h's; sim_batch_avx2.c says why their results are the
 * scalar loop's and when they are used. */
#include "sim/sim_batch_int.h"

#if SIM_BATCH_X86
#include <immintrin.h>

#define VTARGET __attribute__((target("avx512f,avx512dq,bmi,bmi2")))
#define VNAME(f) f##_avx512
#define W 8
#define VEC __m512i
#define MASK __mmask8
#define V_LD(p) _mm512_loadu_si512((const void *)(p))
#define V_ST(p, x) _mm512_storeu_si512((void *)(p), (x))
#define V_SET1(x) _mm512_set1_epi64(x)
#define V_ZERO _mm512_setzero_si512()
#define V_ADD _mm512_add_epi64
#define V_SUB _mm512_sub_epi64
#define V_AND _mm512_and_si512
#define V_OR _mm512_or_si512
#define V_SLL(x, c) _mm512_sll_epi64((x), (c))
#define V_SRA(x, c, c64) ((void)(c64), _mm512_sra_epi64((x), (c)))   /* native: c64 unused */
#define V_MUL _mm512_mullo_epi64
#define V_GT _mm512_cmpgt_epi64_mask
#define V_EQ _mm512_cmpeq_epi64_mask
#define M_AND(a, b) ((MASK)((a) & (b)))
#define M_OR(a, b) ((MASK)((a) | (b)))
#define M_NOT(m) ((MASK)~(m))
#define M_NONE ((MASK)0)
#define M_ANY(m) ((m) != 0)
#define M_BITS(m) ((unsigned)(m))
#define V_BLEND(m, a, b) _mm512_mask_blend_epi64((m), (a), (b))
#define V_MASKZ(m, x) _mm512_maskz_mov_epi64((m), (x))
#define V_GATHER(tab, ix) _mm512_i64gather_epi64((ix), (const void *)(tab), 8)

/* A logic element's table of at most 16 entries in two registers: one
 * vpermt2q picks entry ix (bit 3 of ix chooses the register). */
typedef struct lut_avx512 { __m512i lo, hi; } lut_avx512_t;
#define V_LUT(t, ix) _mm512_permutex2var_epi64((t).lo, (ix), (t).hi)
#define V_LUT_T lut_avx512_t
#define V_LUT_LOAD(tab) ((lut_avx512_t){ V_LD(tab), V_LD((tab) + 8) })
#define V_LUT_OK(f) 1
#define V_LUT_BITS 4

#include "sim/sim_batch_vec.h"

/* sim__batch_count_dense (sim_batch_int.h), eight lanes an instruction:
 * the bits counted per byte and the bytes summed by shifts (vpsadbw is
 * AVX-512BW, not asked for here); the range by vpminsq and vpmaxsq. */
VTARGET void sim__batch_count_dense_avx512(const int64_t *v, int64_t *pv, uint64_t *t, uint64_t mask, int64_t *lo,
                                           int64_t *hi, uint32_t nl)
{
    const __m512i m55 = _mm512_set1_epi64(0x5555555555555555ll), m33 = _mm512_set1_epi64(0x3333333333333333ll);
    const __m512i m0f = _mm512_set1_epi64(0x0f0f0f0f0f0f0f0fll), mk = _mm512_set1_epi64((long long)mask);
    const __m512i m7f = _mm512_set1_epi64(0x7f);
    uint32_t l = 0;
    for (; l + 8 <= nl; l += 8) {
        __m512i a = _mm512_loadu_si512(v + l), x = _mm512_and_si512(_mm512_xor_si512(a, _mm512_loadu_si512(pv + l)), mk);
        x = _mm512_sub_epi64(x, _mm512_and_si512(_mm512_srli_epi64(x, 1), m55));
        x = _mm512_add_epi64(_mm512_and_si512(x, m33), _mm512_and_si512(_mm512_srli_epi64(x, 2), m33));
        x = _mm512_and_si512(_mm512_add_epi64(x, _mm512_srli_epi64(x, 4)), m0f);
        x = _mm512_add_epi64(x, _mm512_srli_epi64(x, 8));
        x = _mm512_add_epi64(x, _mm512_srli_epi64(x, 16));
        x = _mm512_and_si512(_mm512_add_epi64(x, _mm512_srli_epi64(x, 32)), m7f);
        _mm512_storeu_si512(t + l, _mm512_add_epi64(_mm512_loadu_si512(t + l), x));
        _mm512_storeu_si512(pv + l, a);
        if (lo) {
            _mm512_storeu_si512(lo + l, _mm512_min_epi64(_mm512_loadu_si512(lo + l), a));
            _mm512_storeu_si512(hi + l, _mm512_max_epi64(_mm512_loadu_si512(hi + l), a));
        }
    }
    if (l < nl) sim__batch_count_dense(v + l, pv + l, t + l, mask, lo ? lo + l : NULL, hi ? hi + l : NULL, nl - l);
}

#else
typedef int sim_batch_avx512_none;   /* ISO C wants a declaration in every file */
#endif
