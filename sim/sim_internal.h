/* sim_internal.h - NOT part of the API: the kernel's own record of a
 * process, with the fast-path fields of the primitives the kernel
 * evaluates itself, the context both halves of the kernel share
 * (sim_kernel.c: signals, processes, observers; sim_sched.c: timers, time
 * steps, the delta loop), and the hooks between them and sim_prim.c.
 * Included by those files only; anything else uses sim.h.
 *
 * A process is one sim__proc. Its public part (struct sim_proc: data,
 * ctx, no_init) is the last member, and what sim_proc_new hands out is a
 * pointer to it; sim__proc_of goes back. The fields the evaluate loop
 * touches come first, in the 64-byte line the record starts on (processes
 * are allocated on cache-line boundaries).
 */
#ifndef SIM_INTERNAL_H
#define SIM_INTERNAL_H
#include "sim/sim.h"
#include <stddef.h>

/* What the kernel computes itself: SIM__OP_FN calls fn. For arithmetic
 * the kernel computes v = op(a, b, c), then y <= (v + op_radd) >> op_k
 * when that lands in [op_lo, op_hi], and otherwise calls fn, the general
 * evaluation (which counts the overflow). The *_X variants are the same
 * operations when op_k and op_radd are 0 (the result already has y's
 * fraction bits, as in most registers, multiplexers and adders): only the
 * range check is left. Logic: y <= the low 64 - op_k bits of
 * op_logic(inputs), sign-extended (LOGIC_S) or masked with op_radd
 * (LOGIC_U). A logic element with few input bits is tabulated when the
 * simulation starts (sim_sched.c): LUT1, one input, y <= op_tab[a -
 * op_lo] when a - op_lo <= op_hi (its format's span); LUTN, the inputs'
 * offsets side by side (op_tin); an input outside its format calls fn. */
/* One row per operation: X(OP, label, x), the enum SIM__OP_OP (in this
 * order, from 0), the label of its code in the evaluate loop (sim_deltas.h,
 * which sim_sched.c compiles; the dispatch table is made from this list),
 * and x, the *_X variant set_native (sim_prim.c) takes for it when k and
 * radd are 0 (OP itself when it has none). */
#define SIM__OP_LIST(X)                    \
    X(FN,      general,    FN)             \
    X(COPY,    op_copy,    COPY_X)         \
    X(ADD,     op_add,     ADD_X)          \
    X(SUB,     op_sub,     SUB_X)          \
    X(MUL,     op_mul,     MUL)            \
    X(MUX,     op_mux,     MUX_X)          \
    X(BK,      op_bk,      BK_X)           \
    X(LOGIC_S, op_logic_s, LOGIC_S)        \
    X(LOGIC_U, op_logic_u, LOGIC_U)        \
    X(COPY_X,  op_copy_x,  COPY_X)         \
    X(ADD_X,   op_add_x,   ADD_X)          \
    X(SUB_X,   op_sub_x,   SUB_X)          \
    X(MUX_X,   op_mux_x,   MUX_X)          \
    X(BK_X,    op_bk_x,    BK_X)           \
    X(LUT1,    op_lut1,    LUT1)           \
    X(LUTN,    op_lutn,    LUTN)
enum {
#define SIM__OP_ENUM(O, label, x) SIM__OP_##O,
    SIM__OP_LIST(SIM__OP_ENUM)
#undef SIM__OP_ENUM
    SIM__OP__COUNT
};

/* Debug asserts of the fast paths' preconditions, SQLite-style: checked
 * in the sanitizer build (-DSIM_DEBUG, the Makefile's ASAN_FLAGS), nothing
 * in the product's. */
#ifdef SIM_DEBUG
#include <assert.h>
#define SIM__ASSERT(c) assert(c)
#else
#define SIM__ASSERT(c) ((void)0)
#endif

/* One input of a tabulated logic element: its offset from lo, at most
 * span, is at bit sh of the index. */
typedef struct sim__lut_in {
    int64_t  lo;
    uint64_t span;
    int      sh;
} sim__lut_in;

/* Inputs of a logic element the kernel gathers (sim_logic's limit). */
#define SIM__LOGIC_MAX 8

typedef struct sim__proc {
    /* hot: read or written on every evaluation */
    uint64_t    listed;     /* in the run list being built while it equals the
                             * context's generation (sim_sched.c) */
    uint8_t     op;         /* SIM__OP_* */
    int8_t      op_k;
    uint32_t    op_n;       /* mux or logic inputs */
    sim_signal *op_y, *op_a, *op_b, *op_c;
    int64_t     op_lo, op_hi;
    int64_t     op_radd;
    uint64_t    runs;       /* evaluations */
    sim_signal *const *op_in;
    int64_t   (*op_logic)(const int64_t *in, void *user);   /* sim_logic_fn */
    void       *op_user;
    sim_proc_fn fn;         /* the general evaluation */
    const int64_t *op_tab;  /* LUT1, LUTN: the table */
    const sim__lut_in *op_tin;  /* LUTN: op_n inputs */
    /* cold */
    const struct sim_prim_info *elem;   /* a primitive's record (sim_prim.h), else NULL */
    const char *name;
    sim_proc    pub;        /* what users hold */
} sim__proc;

static inline sim__proc *sim__proc_of(const sim_proc *p)
{
    return (sim__proc *)(void *)((char *)(uintptr_t)p - offsetof(sim__proc, pub));
}

/* The reference kernel's evaluation of a primitive (p->elem set): its
 * inputs' values, sim_elem_eval, the overflow counted, the write (sim_prim.c;
 * the write and the update after it are the fast kernel's own). */
void sim__elem_step(sim__proc *p);

/* Record an elaboration error (the first one is kept): sim_run then
 * returns SIM_ERR_ELAB without simulating, sim_error gives the text. */
void sim__elab_error(sim_ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A quantization into s overflowed and gave raw. It is counted in
 * s->overflows only if the evaluation that overflowed is the last one of
 * s's driver in this time step (so s settles on raw): a glitch while a
 * combinational network settles (an operand updated one delta before the
 * other) is not an overflow of the hardware, even when a later,
 * in-range evaluation happens to give the same raw. So the count depends
 * only on settled values, whatever order the elements are evaluated in
 * (the batch mode's levelized evaluation relies on it: sim_batch.h). */
void sim__overflow(sim_signal *s, int64_t raw);

/* Used values (sim_prim.h): one element reading a signal; prim NULL for a
 * process that is not a primitive (its use cannot be seen into: used). */
struct sim__use { const void *prim; };
/* Build every signal's list of readers (sim_prim.c); the kernel calls it
 * before the first overflow it settles, and again when the design grew or
 * a register's D was connected since (sim__uses_stale). */
void sim__uses_build(sim_ctx *c);
void sim__uses_stale(sim_ctx *c);
/* Whether the value s settled on in this time step is used: held by a
 * register (s is one, or an enabled register takes it at the next edge),
 * an output, read by a process that is not a primitive, or passed on by
 * a combinational element (a multiplexer that selects it, a block key
 * that passes it, any other) to a used value. epoch: one per settling,
 * for the memo every signal carries. */
int  sim__value_used(sim_signal *s, uint64_t epoch);

/* ---- the context (sim_kernel.c builds it, sim_sched.c runs it) ---- */

/* A timed event: at time `at`, fn(data). Clocks are the only users so far;
 * a binary heap keeps them ordered (seq breaks ties first-come first). */
typedef struct sim__timer {
    sim_time at;
    uint64_t seq;
    void   (*fn)(sim_ctx *c, void *data);
    void    *data;
} sim__timer;

typedef struct sim__obs {
    sim_observer_fn fn;
    void    *data;
    unsigned flags;
} sim__obs;

struct sim__chunk { struct sim__chunk *next; };

struct sim_ctx {
    sim_updq     q;                          /* written this delta (first: see sim_write) */
    sim_signal **sigs;   uint32_t nsig, capsig;
    sim__proc  **procs;  uint32_t nproc, capproc;
    sim__proc  **run;    uint32_t nrun;      /* runnable this delta; capacity capproc */
    sim__proc  **run2;   uint32_t nrun2;     /* woken for the next delta */
    sim_signal **chg;    uint32_t nchg;      /* changed this time step (sim_changed) */
    sim_signal **chg_on;                     /* chg while an observer reads it, else NULL */
    uint32_t     epoch;                      /* a signal is in chg iff its noted is this */
    uint64_t     gen;                        /* a process is in the run list being built iff
                                              * its listed is this (one per delta: never wraps) */
    sim_signal **ovfq;   uint32_t novfq;     /* overflowed this time step (sim__overflow) */
    uint32_t     uses_nsig;                  /* signals when the readers were listed (0: not) */
    uint64_t     use_epoch;                  /* one per settling that met an overflow */
    sim__timer  *heap;   uint32_t nheap, capheap;
    uint64_t     timer_seq;
    sim_time     now;
    sim_stats    stats;
    sim_round    rnd;
    sim_ovf      ovf;
    uint32_t     max_deltas;
    uint32_t     changed;                    /* signals the last update changed */
    int          started, stop;
    int          reference;                  /* sim_set_reference: no fast path */
    int          stepped;                    /* a time step ran, the last at step_time */
    sim_time     step_time;
    sim__obs    *obs;    uint32_t nobs, capobs;
    uint32_t     track;                      /* observers reading sim_changed */
    int          elab_err;                   /* err holds an elaboration error */
    sim_scope    root;
    struct sim__chunk *mem;
    char         err[512];
};

/* Grow an array of elem-byte items to hold need (doubling; exits when
 * out of memory). */
void *sim__grow(void *p, uint32_t *cap, size_t elem, uint32_t need);
/* Start a new list of changed signals (sim_changed). */
void sim__clear_changed(sim_ctx *c);
#endif
