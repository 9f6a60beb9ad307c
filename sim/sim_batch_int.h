/* sim_batch_int.h - what sim_batch.c shares with its vector loops
 * (sim_batch_avx2.c): one element of the schedule and the entry points of
 * each side. Not for other layers. */
#ifndef SIM_BATCH_INT_H
#define SIM_BATCH_INT_H
#include "sim/sim_batch.h"
#include "sim/sim_prim.h"

enum { B_COPY, B_ADD, B_SUB, B_MUL, B_SHIFT, B_MUX, B_BK, B_LOGIC, B_REG };

/* One element of the schedule. Operand pointers are the lane arrays of
 * the signals it reads. */
typedef struct bop {
    int      kind;
    int      fast;        /* the int64_t path applies (see op_setup) */
    int      sa, sb;      /* left shifts aligning a, b to src_f */
    int      src_f;       /* fraction bits of the exact result */
    int      k;           /* fast path: right shift from src_f to y */
    int64_t  radd;        /* fast path: added before the shift (half-up) */
    int64_t  lo, hi;      /* y's raw range */
    sim_fmt  fy;
    sim_round r;
    sim_ovf  o;
    int64_t *y, *a, *b, *c, *rst;
    int      fa;          /* fraction bits of a (copy, register, block key) */
    int64_t  rst_raw;
    int      n;           /* mux, logic: inputs */
    int64_t **in;
    int     *in_f;        /* mux: each input's fraction bits */
    int     *in_k;        /* mux, fast: each input's right shift to y, */
    int64_t *in_radd;     /* and what is added before it (inputs may differ in fraction bits) */
    sim_logic_fn fn;
    void    *user;
    int64_t *tab;         /* logic: y for every input value (see logic_table), or NULL */
    int      tsh[8];      /* logic: where input i's bits go in the table index */
    uint64_t tmask[8];
    int64_t *nx;          /* register: value after the edge */
    uint32_t sig;         /* y's signal index */
    uint32_t *dep;        /* combinational: the signals it reads */
    int      ndep;
} bop;

/* Vector loops (sim_batch_vec.h, built for AVX2 in sim_batch_avx2.c and
 * for AVX-512 in sim_batch_avx512.c) on x86-64 with gcc or clang;
 * CFLAGS=-DSIM_BATCH_X86=0 builds without them (the scalar loops only, as
 * on other CPUs). */
#ifndef SIM_BATCH_X86
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SIM_BATCH_X86 1
#else
#define SIM_BATCH_X86 0
#endif
#endif
/* The widest vector loops (8: AVX-512, 4: AVX2, 0: none) this CPU runs,
 * of at most `most` lanes. */
uint32_t sim__batch_vec_width(uint32_t most);
/* Each evaluates p in lanes 0..nl-1 (nl a multiple of the width, at most
 * 64) exactly as the scalar loop would (also in the lanes none of p's
 * inputs changed in: they compute what they hold, see sim_batch.c), ORs
 * the lanes its output changed in into *om and returns 1; 0 when it has
 * no loop for p (the caller runs the scalar one). A group of lanes in
 * which a fast result leaves y's range (an overflow, or a value the fast
 * path does not cover) is handed to sim__batch_lanes and counted in
 * *fell. vec_take: v[l] = p[l], the lanes where that changed v (and
 * when some did, *same = every lane of p holds p[0]); vec_fill: y[l] = v,
 * the lanes where that changed y (when asked: `changes`); vec_same: 1 if
 * every lane of v holds v[0]; vec_sparse: the scalar loop of p in the few
 * lanes of m, for the common fast elements (0: not one of them). */
int sim__batch_vec_comb_avx2(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell);
int sim__batch_vec_reg_avx2(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell);
uint64_t sim__batch_vec_take_avx2(int64_t *v, const int64_t *p, uint32_t nl, unsigned char *same);
uint64_t sim__batch_vec_fill_avx2(int64_t *y, int64_t v, uint32_t nl, int changes);
int sim__batch_vec_same_avx2(const int64_t *v, uint32_t nl);
int sim__batch_vec_sparse_avx2(const bop *p, uint64_t m, unsigned char *ovf, uint64_t *om);
int sim__batch_vec_comb_avx512(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell);
int sim__batch_vec_reg_avx512(const bop *p, uint32_t nl, unsigned char *ovf, uint64_t *om, uint64_t *fell);
uint64_t sim__batch_vec_take_avx512(int64_t *v, const int64_t *p, uint32_t nl, unsigned char *same);
uint64_t sim__batch_vec_fill_avx512(int64_t *y, int64_t v, uint32_t nl, int changes);
int sim__batch_vec_same_avx512(const int64_t *v, uint32_t nl);
int sim__batch_vec_sparse_avx512(const bop *p, uint64_t m, unsigned char *ovf, uint64_t *om);
/* Toggles and ranges of one signal in every lane 0..nl-1 at once
 * (sim_batch.c's count after a settle, when many lanes changed): t[l] +=
 * the bits of `mask` in which v[l] differs from pv[l], pv[l] = v[l], and
 * lo/hi (when not NULL) widened to take v[l]. In a lane where v did not
 * change, v[l] == pv[l] and v[l] is already in its range: nothing moves,
 * so no mask of lanes is needed. The population count is the SWAR one
 * (no multiply: SSE2 and AVX2 have no 64-bit product), so that the
 * compiler can vectorize the loop for each target that includes this. */
#define SIM__BATCH_COUNT_DENSE(ATTR, NAME) \
ATTR void NAME(const int64_t *v, int64_t *pv, uint64_t *t, uint64_t mask, int64_t *lo, int64_t *hi, uint32_t nl) \
{ \
    for (uint32_t l = 0; l < nl; l++) { \
        uint64_t x = ((uint64_t)v[l] ^ (uint64_t)pv[l]) & mask; \
        x = x - ((x >> 1) & 0x5555555555555555ull); \
        x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull); \
        x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full; \
        x += x >> 8; x += x >> 16; x += x >> 32; \
        t[l] += x & 0x7f; \
        pv[l] = v[l]; \
    } \
    if (!lo) return; \
    for (uint32_t l = 0; l < nl; l++) { \
        lo[l] = v[l] < lo[l] ? v[l] : lo[l]; \
        hi[l] = v[l] > hi[l] ? v[l] : hi[l]; \
    } \
}
typedef void sim__batch_count_fn(const int64_t *v, int64_t *pv, uint64_t *t, uint64_t mask, int64_t *lo, int64_t *hi,
                                 uint32_t nl);
sim__batch_count_fn sim__batch_count_dense, sim__batch_count_dense_avx2, sim__batch_count_dense_avx512;
/* The scalar loop of p (combinational or register, in place) in the lanes
 * of the one-word mask m (sim_batch.c). */
void sim__batch_lanes(const bop *p, uint64_t m, unsigned char *ovf, uint64_t *om);
#endif
