/* sim_batch_int.h - what the batch mode's files share: the batch itself,
 * one element of the schedule, and the entry points of each file.
 *   sim_batch.c       construction: the schedule, levelized; accessors
 *   sim_batch_op.c    one element's setup from its description
 *   sim_batch_eval.c  evaluation: scalar loops, settle, clock, toggles
 *   sim_batch_vec.h   the vector loops (sim_batch_avx2.c, _avx512.c)
 * Not for other layers. */
#ifndef SIM_BATCH_INT_H
#define SIM_BATCH_INT_H
#include "sim/sim_batch.h"
#include "sim/sim_prim.h"
#include "sim/sim_op.h"

/* An element's kind in the schedule: the evaluation its sim_kind takes
 * (sim_kind_eval, sim_elem.h's eval column; B_WIRE a copy), numbered
 * by this list. Every value of the eval column has one (the table
 * sim_batch_op.c makes from the element list does not compile without
 * it); CLOCK and CONST, last, are never evaluated. The order is the one
 * the scalar loops were measured in: numbering the kinds as sim_kind
 * does costs 0.35% more instructions on span2's scalar loops
 * (valgrind --tool=callgrind build/bench/bench_batch --vector 0 one span2
 * paper batch), from the jump table's block layout alone. */
#define SIM__BATCH_KINDS(X) X(WIRE) X(ADD) X(SUB) X(MUL) X(SHIFT) X(MUX) X(BK) X(LOGIC) X(REG) X(CLOCK) X(CONST)
enum {
#define B_ENUM(K) B_##K,
    SIM__BATCH_KINDS(B_ENUM)
#undef B_ENUM
};

/* One element of the schedule. Operand pointers are the lane arrays of
 * the signals it reads. */
typedef struct bop {
    int      kind;
    int      fast;        /* the int64_t path applies (sim_batch_op.c) */
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
    int64_t *tab;         /* logic: y for every input value (sim_batch_op.c, logic_table), or NULL */
    int      tsh[8];      /* logic: where input i's bits go in the table index */
    uint64_t tmask[8];
    int64_t *nx;          /* register: value after the edge */
    uint32_t sig;         /* y's signal index */
    uint32_t *dep;        /* combinational: the signals it reads */
    int      ndep;
    struct sim_batch *owner;   /* the batch: where an overflow is noted (sim_batch_ovf.c) */
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
 * inputs changed in: they compute what they hold, see sim_batch_eval.c), ORs
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
 * (sim_batch_eval.c's count after a settle, when many lanes changed): t[l] +=
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
 * of the one-word mask m (sim_batch_eval.c). */
void sim__batch_lanes(const bop *p, uint64_t m, unsigned char *ovf, uint64_t *om);

struct sim_batch {
    uint32_t lanes, nsig;
    sim_ctx *ctx;               /* the design (sim_batch_new's; read by the overflow counts) */
    int64_t *val;               /* nsig x lanes: every signal's values */
    int64_t *pend;              /* inputs' values for the next edge */
    int32_t *inslot;            /* per signal: its row in pend, or -1 */
    uint32_t nin;
    uint32_t *in_sig;           /* per input row: the signal */
    unsigned char *in_mark;     /* per input row: written since the last edge (sim_batch_mark) */
    int      marking;           /* 1 once sim_batch_mark was called: unmarked inputs are not compared */
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
    /* overflow counting (sim_batch_overflows_on, sim_batch_ovf.c), NULL when off */
    struct sim__batch_ovf *oc;
    int      in_uniform;        /* eval_uniform's lane 0 stands for every lane */
};

/* Overflow counting (sim_batch_ovf.c). The evaluation loops call note
 * when a quantization of p overflowed in the lane of ovf (an element of
 * b->ovf, or lane 0 for all in eval_uniform); the edge calls before_edge
 * ahead of the registers and step after each settle. */
void sim__batch_ovf_note(const bop *p, const unsigned char *ovf);
void sim__batch_ovf_before_edge(sim_batch *b);
void sim__batch_ovf_step(sim_batch *b);
void sim__batch_ovf_free(sim_batch *b);

/* Fill p from the element driving y (sim_batch_op.c); -1 (err) for what
 * the batch mode cannot evaluate. */
int  sim__batch_op_setup(sim_batch *b, bop *p, const sim_signal *y, const sim_prim_info *in,
                         const sim_signal *clk, char *err, size_t errlen);
/* Free n elements' own arrays, then ops. */
void sim__batch_free_ops(bop *ops, uint32_t n);
#endif
