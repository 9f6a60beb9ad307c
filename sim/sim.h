/* sim.h - the simulation kernel: signals, processes, delta cycles, time.
 *
 * Semantics follow SystemC's evaluate/update (Verilog non-blocking
 * assignment): a process reads signals' current values and writes their
 * next values; writes take effect only in the update phase, after every
 * runnable process of this delta cycle has run. A signal whose value
 * changes in the update phase wakes the processes sensitive to it for the
 * next delta cycle. Delta cycles repeat until nothing is runnable; then
 * time advances to the next timed event (e.g. a clock edge).
 *
 * So registers never race: a clocked process sensitive to clk's rising edge
 * reads its D input as it was before the edge, whatever order processes run.
 *
 * Everything is allocated while the design is built (elaboration); once
 * sim_run starts, the kernel allocates nothing.
 */
#ifndef SIM_H
#define SIM_H
#include <stdint.h>
#include <stdio.h>
#include "sim/sim_fixed.h"

typedef struct sim_ctx    sim_ctx;
typedef struct sim_signal sim_signal;
typedef struct sim_proc   sim_proc;
typedef struct sim_scope  sim_scope;
typedef uint64_t sim_time;

typedef void (*sim_proc_fn)(sim_proc *p);

typedef enum { SIM_EDGE_ANY, SIM_EDGE_POS, SIM_EDGE_NEG } sim_edge;

/* What drives a signal, for area and documentation. */
typedef enum {
    SIM_KIND_WIRE, SIM_KIND_INPUT, SIM_KIND_CLOCK, SIM_KIND_CONST,
    SIM_KIND_REG, SIM_KIND_MUX, SIM_KIND_BK, SIM_KIND_ADD, SIM_KIND_SUB,
    SIM_KIND_MUL, SIM_KIND_SHIFT, SIM_KIND_LOGIC, SIM_KIND__COUNT
} sim_kind;

struct sim_fanout { sim_proc *proc; uint8_t edge; };

/* The fields a delta cycle touches come first, in one 64-byte line (the
 * kernel allocates signals on a cache-line boundary). */
struct sim_signal {
    int64_t     cur;        /* value now */
    int64_t     nxt;        /* value written this delta */
    sim_ctx    *ctx;
    /* Processes a change wakes, in the order they were made sensitive:
     * wake[0] when the new value is 0 (edges ANY and NEG), wake[1] when it
     * is nonzero (ANY and POS). Built by sim_sensitive from fan. */
    sim_proc  **wake[2];
    uint32_t    nwake[2];
    /* Flags the kernel writes are not char: a store through a
     * char type may alias anything, which would make the compiler reload
     * every other pointer and count around it. */
    uint32_t    queued;     /* in the update list */
    uint16_t    vcd_dirty;  /* changed since the last VCD time stamp */
    uint8_t     kind;       /* sim_kind */
    uint64_t    changes;    /* value changes (events) */
    /* cold */
    sim_fmt     fmt;        /* width and meaning of the raw value */
    struct sim_fanout *fan; /* processes sensitive to this signal */
    uint32_t    nfan, capfan;
    uint32_t    capwake[2];
    int64_t     raw_min, raw_max;  /* range of fmt, cached for quantization */
    uint64_t    overflows;  /* time steps that settled on an overflowed quantization */
    int64_t     ovf_raw;    /* the last overflowed result this time step */
    uint64_t    ovf_run;    /* driver->runs when it overflowed (see sim__overflow) */
    uint32_t    ovf_pending;/* in the kernel's list of overflows to settle */
    double      area_ge;    /* area of the element driving it, NAND2 eq. */
    sim_proc   *driver;     /* process computing it (NULL: input, constant) */
    int64_t     vcd_last;   /* last value written to the VCD */
    char        vcd_id[8];
    const char *name;
    sim_scope  *scope;
    sim_signal *next_in_scope;
    uint32_t    index;
};

struct sim_proc {
    uint32_t    queued;     /* runnable in the next delta (not char: see sim_signal) */
    uint8_t     no_init;    /* clocked: not run at initialization (SystemC dont_initialize) */
    /* Internal: a primitive the kernel evaluates itself (sim_prim.c sets
     * this up; op 0 = SIM__OP_FN: call fn). For arithmetic the kernel
     * computes v = op(a, b, c), then y <= (v + op_radd) >> op_k when that
     * lands in [op_lo, op_hi], and otherwise calls fn, the general
     * evaluation. Logic: y <= low 64 - op_k bits of op_logic(inputs),
     * sign-extended (LOGIC_S) or masked with op_radd (LOGIC_U). */
    uint8_t     op;
    int8_t      op_k;
    uint32_t    op_n;       /* mux inputs */
    sim_signal *op_y, *op_a, *op_b, *op_c;
    int64_t     op_lo, op_hi, op_radd;
    sim_signal *const *op_in;
    int64_t   (*op_logic)(const int64_t *in, void *user);   /* sim_logic_fn */
    void       *op_user;
    sim_proc_fn fn;
    void       *data;       /* the process's own state */
    uint64_t    runs;
    sim_ctx    *ctx;
    const char *name;
};
enum { SIM__OP_FN = 0, SIM__OP_COPY, SIM__OP_ADD, SIM__OP_SUB, SIM__OP_MUL,
       SIM__OP_MUX, SIM__OP_BK, SIM__OP_LOGIC_S, SIM__OP_LOGIC_U };

struct sim_scope {
    const char *name;
    sim_scope  *parent, *first_child, *next_sibling;
    sim_signal *first_sig, *last_sig;
};

/* Kernel counters, reported by benches and testbenches. */
typedef struct sim_stats {
    uint64_t clocks;      /* rising edges of clocks made by sim_clock */
    uint64_t events;      /* signal value changes */
    uint64_t deltas;      /* delta cycles */
    uint64_t proc_runs;   /* process evaluations */
    uint64_t time_steps;  /* distinct times at which something happened */
} sim_stats;

typedef enum { SIM_OK = 0, SIM_ERR_LOOP = 1, SIM_ERR_IO = 2 } sim_status;

sim_ctx   *sim_new(void);
void       sim_free(sim_ctx *c);
/* Default rounding/overflow for primitives built from now on. */
void       sim_set_quant(sim_ctx *c, sim_round r, sim_ovf o);
sim_round  sim_get_round(const sim_ctx *c);
sim_ovf    sim_get_ovf(const sim_ctx *c);
/* Delta cycles allowed per time step before a loop is reported (default
 * 1000). */
void       sim_set_max_deltas(sim_ctx *c, uint32_t n);

sim_scope *sim_root(sim_ctx *c);
sim_scope *sim_scope_new(sim_ctx *c, sim_scope *parent, const char *name);
/* Full dotted name "top.horner3.rg" into buf. */
const char *sim_signal_path(const sim_signal *s, char *buf, size_t len);

/* A signal of format fmt, initial raw value 0. Names are copied. */
sim_signal *sim_signal_new(sim_ctx *c, sim_scope *sc, const char *name,
                           sim_fmt fmt, sim_kind kind);
/* A 1-bit unsigned signal (u1.0). */
sim_signal *sim_bit_new(sim_ctx *c, sim_scope *sc, const char *name, sim_kind kind);

sim_proc *sim_proc_new(sim_ctx *c, const char *name, sim_proc_fn fn, void *data);
/* Make p run when s changes (edge ANY) or rises/falls (POS/NEG, 1-bit). */
void      sim_sensitive(sim_proc *p, sim_signal *s, sim_edge e);
/* Memory owned by the context, freed by sim_free; zeroed. */
void     *sim_alloc(sim_ctx *c, size_t n);
char     *sim_strdup(sim_ctx *c, const char *s);

/* Write the value a signal takes in the next update phase. */
static inline void sim_write(sim_signal *s, int64_t v);
/* Set a signal's value now, outside any process (before sim_run or between
 * runs); wakes its fanout as a change would. */
void sim_force(sim_signal *s, int64_t v);

/* A clock toggling every half_period time units, first rising edge at
 * first_rise. Counts rising edges in stats.clocks. */
void sim_clock(sim_ctx *c, sim_signal *clk, sim_time half_period, sim_time first_rise);

/* Run until time `until` (inclusive), until sim_stop, or until an error.
 * The first call runs every process once (initialization, as SystemC). */
sim_status sim_run(sim_ctx *c, sim_time until);
void       sim_stop(sim_ctx *c);           /* from a process: finish this time step and return */
sim_time   sim_now(const sim_ctx *c);
const sim_stats *sim_get_stats(const sim_ctx *c);
/* After SIM_ERR_LOOP: "combinational loop at time T: a -> b -> a" etc. */
const char *sim_error(const sim_ctx *c);

/* Iterate: every process in creation order. */
uint32_t    sim_proc_count(const sim_ctx *c);
sim_proc   *sim_proc_at(const sim_ctx *c, uint32_t i);
/* Iterate: every signal of the design in creation order. */
uint32_t    sim_signal_count(const sim_ctx *c);
sim_signal *sim_signal_at(const sim_ctx *c, uint32_t i);
/* Find by dotted path relative to scope (NULL scope: root). */
sim_signal *sim_find(const sim_ctx *c, const sim_scope *sc, const char *path);
/* Sum of area_ge of every signal in scope and its children. */
double      sim_scope_area(const sim_scope *sc);

/* Hooks used by the VCD writer (sim_vcd.h). */
typedef struct sim_vcd sim_vcd;
void sim_attach_vcd(sim_ctx *c, sim_vcd *v);
/* The signals changed since the last call (each once); resets the list. */
sim_signal **sim__vcd_take_dirty(sim_ctx *c, uint32_t *n);
/* A quantization into s overflowed and gave raw. It is counted in
 * s->overflows only if the evaluation that overflowed is the last one of
 * s's driver in this time step (so s settles on raw): a glitch while a
 * combinational network settles (an operand updated one delta before the
 * other) is not an overflow of the hardware, even when a later,
 * in-range evaluation happens to give the same raw. So the count depends
 * only on settled values, whatever order the kernel evaluates in (a
 * levelized evaluation, sim_batch.h, counts the same). */
void sim__overflow(sim_signal *s, int64_t raw);

/* ---- inline fast path ----
 * The update list is the first member of every sim_ctx, so that a write,
 * the most frequent operation of all, costs no call. A write of the value
 * a signal already has, when nothing else is pending for it, changes
 * nothing in the update phase, so it is not queued at all. */
typedef struct sim_updq { sim_signal **upd; uint32_t nupd; } sim_updq;
static inline void sim_write(sim_signal *s, int64_t v)
{
    s->nxt = v;
    if (!s->queued && v != s->cur) {
        sim_updq *q = (sim_updq *)(void *)s->ctx;
        s->queued = 1;
        q->upd[q->nupd++] = s;
    }
}
#endif
