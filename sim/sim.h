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
#include "sim/sim_elem.h"

typedef struct sim_ctx    sim_ctx;
typedef struct sim_signal sim_signal;
typedef struct sim_proc   sim_proc;
typedef struct sim_scope  sim_scope;
struct sim__proc;                /* the kernel's record of a process (private) */
typedef uint64_t sim_time;

typedef void (*sim_proc_fn)(sim_proc *p);

typedef enum { SIM_EDGE_ANY, SIM_EDGE_POS, SIM_EDGE_NEG } sim_edge;

/* What drives a signal: one value per row of sim_elem.h's list, in its
 * order (SIM_KIND_WIRE, SIM_KIND_INPUT, SIM_KIND_CLOCK, SIM_KIND_CONST,
 * SIM_KIND_REG, SIM_KIND_MUX, SIM_KIND_BK, SIM_KIND_ADD, SIM_KIND_SUB,
 * SIM_KIND_MUL, SIM_KIND_SHIFT, SIM_KIND_LOGIC). */
typedef enum {
#define SIM__KIND_ENUM(K, ...) SIM_KIND_##K,
    SIM_ELEM_LIST(SIM__KIND_ENUM)
#undef SIM__KIND_ENUM
    SIM_KIND__COUNT
} sim_kind;

/* The kind's name ("add"), its role (SIM_ELEM_SOURCE, _COMB, _SEQ), the
 * kind whose evaluation a primitive driving it takes, and whether it has
 * area and delay of its own: sim_elem.h's columns. NULL, -1 or 0 for a
 * value that is no kind. */
const char *sim_kind_name(sim_kind k);
int         sim_kind_role(sim_kind k);
sim_kind    sim_kind_eval(sim_kind k);
int         sim_kind_has_area(sim_kind k);
int         sim_kind_has_delay(sim_kind k);

struct sim_fanout { sim_proc *proc; uint8_t edge; };

/* The fields a delta cycle touches come first, in one 64-byte line (the
 * kernel allocates signals on a cache-line boundary; sim_kernel.c checks
 * the layout). */
struct sim_signal {
    int64_t     cur;        /* value now */
    int64_t     nxt;        /* value written this delta */
    sim_ctx    *ctx;
    /* Processes a change wakes, in the order they were made sensitive:
     * wake[0] when the new value is 0 (edges ANY and NEG), wake[1] when it
     * is nonzero (ANY and POS). Built by sim_sensitive from fan. */
    struct sim__proc **wake[2];
    uint32_t    nwake[2];
    /* Flags the kernel writes are not char: a store through a
     * char type may alias anything, which would make the compiler reload
     * every other pointer and count around it. */
    uint32_t    queued;     /* in the update list */
    uint16_t    noted;      /* in the kernel's list of signals changed this time
                             * step (sim_changed) when it holds the list's epoch */
    uint8_t     kind;       /* sim_kind */
    uint64_t    changes;    /* value changes (events) */
    /* cold */
    sim_fmt     fmt;        /* width and meaning of the raw value */
    struct sim_fanout *fan; /* processes sensitive to this signal */
    uint32_t    nfan, capfan;
    uint32_t    capwake[2];
    int64_t     raw_min, raw_max;  /* range of fmt, cached for quantization */
    uint64_t    overflows;  /* time steps that settled on an overflowed quantization
                             * whose value is used (sim_prim.h, "used values") */
    uint64_t    ovf_discarded; /* the same on values no consumer took that clock */
    int64_t     ovf_raw;    /* the last overflowed result this time step */
    uint64_t    ovf_run;    /* the driver's evaluations when it overflowed */
    uint32_t    ovf_pending;/* in the kernel's list of overflows to settle */
    double      area_ge;    /* area of the element driving it, NAND2 eq. */
    /* Its delay (sim_delay.h, sim_arcs): from an input's least or most
     * significant bit to its own, [ll, lm, ml, mm], in ps and in gate
     * levels, < 0 where one does not depend on the other; a register's
     * are its clock-to-q. */
    double      dly_ps[4];
    int         dly_lv[4];
    sim_proc   *driver;     /* process computing it (NULL: input, constant, clock) */
    const char *name;
    sim_scope  *scope;
    sim_signal *next_in_scope;
    uint32_t    index;      /* creation order: sim_signal_at(ctx, index) is this */
    uint8_t     is_output;  /* sim_signal_output: its value leaves the design */
    int8_t      use_memo;   /* sim_prim.c: is the settled value used, at use_epoch */
    uint64_t    use_epoch;
    struct sim__use *uses;  /* the elements reading it (built at the first overflow) */
    uint32_t    nuses;
};

/* A process: a function the kernel calls when a signal it is sensitive to
 * changes. The kernel's own record (how it evaluates, how often it ran)
 * is private; these are the fields users set. */
struct sim_proc {
    void       *data;       /* the process's own state (sim_proc_new's data) */
    sim_ctx    *ctx;        /* its context (read only), e.g. for sim_stop */
    uint8_t     no_init;    /* set before sim_run: not run at initialization
                             * (clocked processes; SystemC dont_initialize) */
};

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
    uint64_t time_steps;  /* distinct times the kernel stopped at (a sim_run
                           * resuming at the time the last one ended continues
                           * that time step) */
    uint64_t fast_paths;  /* a check, not a measure: entries into a fast path
                           * (the fast delta loop, a clock edge in place, a
                           * table made, a shortcut of a primitive's
                           * quantization); 0 under sim_set_reference */
} sim_stats;

/* SIM_ERR_ELAB: the design is not well formed (a signal with two drivers,
 * a logic element with too many inputs...); nothing is simulated. */
typedef enum { SIM_OK = 0, SIM_ERR_LOOP = 1, SIM_ERR_IO = 2, SIM_ERR_ELAB = 3 } sim_status;

sim_ctx   *sim_new(void);
void       sim_free(sim_ctx *c);
/* Default rounding/overflow for primitives built from now on. */
void       sim_set_quant(sim_ctx *c, sim_round r, sim_ovf o);
sim_round  sim_get_round(const sim_ctx *c);
sim_ovf    sim_get_ovf(const sim_ctx *c);
/* Delta cycles allowed per time step before a loop is reported (default
 * 1000). */
void       sim_set_max_deltas(sim_ctx *c, uint32_t n);
/* The reference kernel (on != 0): the plain evaluate/update loop with
 * none of the evaluation's fast paths (sim_sched.c): every primitive is
 * evaluated by sim_elem_eval from its record (sim_prim.h: the exact
 * operation, then one requantization; no inline operation, no table, no
 * shortcut), every other process runs its function (sim_quant_into takes
 * no shortcut either), and every clock edge goes through the timers and a
 * full update (sim_stats.fast_paths stays 0). What it shares with the fast
 * kernel, and so does not check: the update phase (sim_write, the update
 * of the written signals and the waking of their readers), the order of
 * the processes, and the design as built. Values, overflow counts,
 * observers and every counter (sim_stats, each signal's changes, each
 * process's runs) are the fast kernel's; only the time taken differs. 0
 * (the default) is the fast kernel. It may change between runs (the
 * tables are made at the first sim_run, if the kernel is fast then). */
void       sim_set_reference(sim_ctx *c, int on);

sim_scope *sim_root(sim_ctx *c);
sim_scope *sim_scope_new(sim_ctx *c, sim_scope *parent, const char *name);
/* Full dotted name "top.horner3.rg" into buf (cut short to fit). */
const char *sim_signal_path(const sim_signal *s, char *buf, size_t len);
/* The dotted name below scope top ("coef.div3_a.t1" below the unit's
 * scope; top NULL: the full name): 0, or -1 when s is not below top or
 * the name does not fit in len (buf then holds what fits). The one
 * writer of a signal's path (the VCD's, the messages', the netlist's). */
int sim_signal_path_below(const sim_signal *s, const sim_scope *top, char *buf, size_t len);

/* A signal of format fmt, initial raw value 0. Names are copied. */
sim_signal *sim_signal_new(sim_ctx *c, sim_scope *sc, const char *name,
                           sim_fmt fmt, sim_kind kind);
/* A 1-bit unsigned signal (u1.0). */
sim_signal *sim_bit_new(sim_ctx *c, sim_scope *sc, const char *name, sim_kind kind);

sim_proc *sim_proc_new(sim_ctx *c, const char *name, sim_proc_fn fn, void *data);
/* Iterate: every process in creation order. Name as given to sim_proc_new
 * (primitives: "scope.signal"); runs: evaluations so far. */
uint32_t    sim_proc_count(const sim_ctx *c);
sim_proc   *sim_proc_at(const sim_ctx *c, uint32_t i);
const char *sim_proc_name(const sim_proc *p);
uint64_t    sim_proc_runs(const sim_proc *p);
/* Make p run when s changes (edge ANY) or rises/falls (POS/NEG, 1-bit). */
void      sim_sensitive(sim_proc *p, sim_signal *s, sim_edge e);
/* Memory owned by the context, freed by sim_free; zeroed. */
void     *sim_alloc(sim_ctx *c, size_t n);
char     *sim_strdup(sim_ctx *c, const char *s);

/* Write the value a signal takes in the next update phase. */
static inline void sim_write(sim_signal *s, int64_t v);
/* Write a signal from outside any process (before sim_run, between runs,
 * or from a timer): s->cur does not change at once; v is queued for the
 * next update phase (the first delta cycle of the next sim_run, or of
 * the time step a timer runs in), where s takes it and wakes its fanout
 * as any change does. Unlike sim_write, v is
 * queued even when it equals s->cur: a time step with a force always has
 * that delta cycle (which changes nothing and wakes nobody when v is the
 * current value). */
void sim_force(sim_signal *s, int64_t v);

/* A clock toggling every half_period time units, first rising edge at
 * first_rise. Counts rising edges in stats.clocks. */
void sim_clock(sim_ctx *c, sim_signal *clk, sim_time half_period, sim_time first_rise);

/* Run until time `until` (inclusive), until sim_stop, or until an error.
 * The first call runs every process once (initialization, as SystemC).
 * After an elaboration error (see SIM_ERR_ELAB) it returns that at once. */
sim_status sim_run(sim_ctx *c, sim_time until);
void       sim_stop(sim_ctx *c);           /* from a process: finish this time step and return */
sim_time   sim_now(const sim_ctx *c);
const sim_stats *sim_get_stats(const sim_ctx *c);
/* The last error, one line: "combinational loop at time T: ... a -> b",
 * or the first elaboration error, naming the signal's path. */
const char *sim_error(const sim_ctx *c);

/* Mark s as an output of the design (a unit's port): an overflowed value
 * settled on it is always used (sim_prim.h, "used values"). */
void        sim_signal_output(sim_signal *s);

/* Iterate: every signal of the design in creation order. */
uint32_t    sim_signal_count(const sim_ctx *c);
sim_signal *sim_signal_at(const sim_ctx *c, uint32_t i);
/* Find by dotted path relative to scope (NULL scope: root). */
sim_signal *sim_find(const sim_ctx *c, const sim_scope *sc, const char *path);
/* Sum of area_ge of every signal in scope and its children, with the
 * terms that depend on what reads them (sim_area_net.h). */
double      sim_scope_area(const sim_scope *sc);

/* ---- observers ----
 * An observer is called at the end of every time step, once every signal
 * has settled and its overflows are counted (and at the step a loop was
 * found in, before sim_run returns SIM_ERR_LOOP), in the order the
 * observers were added. now is the step's time; a sim_run resuming at the
 * time the last one stopped calls them again with the same now. This is
 * how value change dumps and loggers watch a run without the kernel
 * knowing them. Observers read signals; they must not write them, nor
 * add or remove observers.
 *
 * flags SIM_OBS_CHANGES: the observer reads sim_changed. The kernel keeps
 * the list of changed signals only while such an observer is added, so a
 * run nobody watches pays nothing for it. */
typedef void (*sim_observer_fn)(sim_ctx *c, sim_time now, void *data);
enum { SIM_OBS_CHANGES = 1 };
/* 0, or -1 when out of memory. */
int  sim_observe(sim_ctx *c, sim_observer_fn fn, void *data, unsigned flags);
/* Remove the observer added with fn and data (nothing if none). */
void sim_unobserve(sim_ctx *c, sim_observer_fn fn, void *data);
/* In an observer: the signals whose value changed in this time step (since
 * the previous observer call; the first call: since the observer was
 * added), each once, in the order of their first change. A signal that
 * changed and changed back is in it too. NULL with *n = 0 when no
 * SIM_OBS_CHANGES observer is added. */
sim_signal *const *sim_changed(const sim_ctx *c, uint32_t *n);

/* ---- inline fast path ----
 * The update list is the first member of every sim_ctx (sim_kernel.c
 * asserts it), so that a write, the most frequent operation of all,
 * costs no call. A write of the value a signal already has, when nothing
 * else is pending for it, changes nothing in the update phase, so it is
 * not queued at all. */
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
