/* unit.h - what a hardware unit is, described once.
 *
 * A unit_desc says everything the command line, the docs and the tests need:
 * its ports and internal signals with a default-format rule from one width
 * W, its schedules, its parameters (with their ranges and defaults), how
 * to build it into a simulation, the function it computes in exact
 * arithmetic (ideal), its error bound, and its float reference (ref: the
 * independent oracle in vectors/, whose gen is the unit's default
 * stimulus, vectors/NAME.vec).
 * The registry (unit.c) is the one list of units: adding a unit is its own
 * file(s) and one registry line (docs/adding-a-unit.md).
 *
 * Handshake of every unit (testbench/ drives it):
 *  - inputs in[] are written by the source; the unit may read them during
 *    every clock of an item, so the source holds them until accepted;
 *  - the item is accepted at a rising edge where in_valid && in_ready;
 *  - results appear on out[] in the clock cycles where out_valid is 1, one
 *    "beat" per cycle, `beats` beats per item (interp units: L pixels).
 * Combinational units tie in_ready to 1 and out_valid to in_valid.
 *
 * This layer knows nothing of files or testbenches.
 */
#ifndef UNIT_H
#define UNIT_H
#include "sim/sim.h"
#include "sim/sim_prim.h"
/* The float reference (the oracle) sits below units/ in the include graph:
 * vectors/ includes nothing of units/, and each descriptor points at its
 * reference model (unit_desc.ref), so there is one registry, this one. */
#include "vectors/vectors.h"

#define UNIT_MAX_SIGS   80    /* interp3: paper's 38 + the pipe's and fwd's own */
#define UNIT_MAX_IO     13   /* shade_cook: N, L, V, hs and three coefficients */
#define UNIT_MAX_SCHED  6
#define UNIT_MAX_PARAMS 6

/* Parameters of every unit, one struct; a unit reads the fields it lists in
 * its params[] table (their ranges and defaults are there, so each unit
 * has its own; unit_cfg_default(u, cfg) sets them). The reference model's
 * parameters (vectors.h: L, g, n, m, alpha, nodes) are not copied:
 * cfg->model is them as the model takes them, and the same storage by name
 * (cfg->L), one anonymous union. */
typedef struct unit_cfg {
    int    width;       /* W of the default-format rule */
    int    schedule;    /* index into the unit's schedules */
    int    terms;       /* div3: subtracted (paper) or added (quarter) terms */
    int    series;      /* div3: 0 = paper x/2 - x/8 - ..., 1 = quarter x/4 + x/16 + ... */
    union {
        vec_params model;                   /* &cfg->model: the reference's parameters */
        struct { VEC_PARAMS_FIELDS };       /* cfg->L, cfg->g, ...: the same fields */
    };
    sim_round rnd;
    sim_ovf   ovf;
} unit_cfg;
/* Same members in the same order (the union's common initial sequence):
 * the same layout, so writing cfg->L is reading cfg->model.L. */
_Static_assert(sizeof(vec_params) == sizeof(struct { VEC_PARAMS_FIELDS }), "vec_params layout");

/* UNIT_P_POW2: a whole number that must be a power of two (L, g). */
typedef enum { UNIT_P_INT, UNIT_P_REAL, UNIT_P_ENUM, UNIT_P_POW2 } unit_ptype;

typedef struct unit_param {
    const char *name;       /* as on the command line: --param terms=3 */
    unit_ptype  type;
    size_t      offset;     /* offsetof(unit_cfg, field) */
    double      min, max;   /* allowed range (ints: inclusive) */
    double      def;        /* default, in the range (enum: its choice's index) */
    const char *choices;    /* UNIT_P_ENUM: "paper quarter" (index stored) */
    const char *help;
} unit_param;

typedef enum { UNIT_SIG_IN, UNIT_SIG_OUT, UNIT_SIG_INTERNAL } unit_role;

/* A unit whose schedules are different datapaths lists the union of their
 * signals; scheds says which schedules build a signal (bit i: schedule i,
 * UNIT_SCHED(i)), 0 for all of them. list, run --json, --fmt and the VCD
 * show only the selected schedule's signals. Inputs and outputs are the
 * unit's ports and belong to every schedule. */
#define UNIT_SCHED(i) (1u << (i))

/* In a descriptor: UNIT_SIGS(sig, sig, ...) sets .sigs and .nsigs, the
 * count taken by the compiler from the list itself (the size of the same
 * list as an array), so that no hand-kept count can drift from the data. */
#define UNIT_SIGS(...) \
    .nsigs = (int)(sizeof((unit_sig[]){ __VA_ARGS__ }) / sizeof(unit_sig)), .sigs = { __VA_ARGS__ }

/* A unit whose code indexes its signals writes them as one list, a line
 *     X(ID, "name", ROLE, "what")     ROLE: IN, OUT or INTERNAL
 * each, and expands it twice: into the index enum (UNIT_SIG_ID: ID is the
 * row's position) and into the descriptor's rows,
 *     enum { MY_SIGS(UNIT_SIG_ID) MY_NSIGS };  ...  UNIT_SIGS(MY_SIGS(UNIT_SIG_ROW)),
 * so that an index and its row cannot drift apart (unit_coef.h's networks
 * are the same idea: one list, two expansions). */
#define UNIT_SIG_ID(id, nm, role_, wh) id,
#define UNIT_SIG_ROW(id, nm, role_, wh) { .name = nm, .role = UNIT_SIG_##role_, .what = wh },

typedef struct unit_sig {
    const char *name;       /* lower case; also the --fmt NAME and VCD name */
    unit_role   role;
    const char *what;       /* one line: "multiplier MUL = MX1 * t" */
    unsigned    scheds;     /* schedules that have it (0: all) */
} unit_sig;

typedef struct unit_sched {
    const char *name;       /* "paper" */
    const char *what;       /* one line */
} unit_sched;

/* Formats of a unit's signals, indexed like unit_desc.sigs. */
typedef struct unit_fmts { sim_fmt f[UNIT_MAX_SIGS]; } unit_fmts;

/* A built unit's handshake and data signals. */
typedef struct unit_io {
    sim_signal *in[UNIT_MAX_IO];    /* in desc input order */
    sim_signal *out[UNIT_MAX_IO];   /* in desc output order */
    sim_signal *in_valid;           /* created by the unit, driven by the source */
    sim_signal *in_ready;
    sim_signal *out_valid;
    sim_scope  *scope;
} unit_io;

typedef struct unit_desc unit_desc;
struct unit_desc {
    const char *name;               /* also its reference model's and vector file's */
    const char *summary;            /* one line for `shadesim list` */
    const char *source;             /* the paper it comes from (docs/references.md): "Nechyporuk & Romanyuk (2020), Fig. 9" */
    int nsigs;
    unit_sig sigs[UNIT_MAX_SIGS];   /* inputs first, then outputs, then internals */
    int nsched;
    unit_sched sched[UNIT_MAX_SCHED];
    int nparams;
    unit_param params[UNIT_MAX_PARAMS];
    const char *fmt_rule;           /* the default-format rule in words */
    /* The float reference: ports (the unit's, beats expanded), exact
     * outputs, and the default stimulus (gen with n = 0, seed 1: the
     * checked-in vectors/NAME.vec). Independent code (vectors/). */
    const vec_model *ref;

    /* Default format of every signal for cfg->width. */
    void (*formats)(const unit_cfg *cfg, unit_fmts *out);
    /* Beats (outputs per item), usually 1. */
    int  (*beats)(const unit_cfg *cfg);
    /* Build into scope sc, clocked by clk, with the context's quantization
     * modes already set from cfg. 0, or -1 with a message (bad formats). */
    int  (*build)(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                  const unit_fmts *f, unit_io *io, char *err, size_t errlen);
    /* The unit's function in exact arithmetic, for inputs as the hardware
     * holds them (already quantized): e.g. coefficients with the network's
     * 1/3, a clamped D_g. out has n_out * beats values, beat-major. */
    void (*ideal)(const unit_cfg *cfg, const double *in, double *out);
    /* Bound on |hardware - ideal| per output port, from the formats and
     * modes alone; docs/bounds.md derives each. */
    void (*bound)(const unit_cfg *cfg, const unit_fmts *f, double *per_out);
    /* Optional (NULL: every beat has the port's bound): the bound of each
     * beat, n_out * beats values beat-major like ideal, where it differs
     * by beat (interp's forward differencing accumulates its errors over
     * the pixels); bound is their maximum per port. */
    void (*bound_beats)(const unit_cfg *cfg, const unit_fmts *f, double *per_beat);
    /* Optional: a precondition between two inputs, lo < hi on every item
     * as the unit holds them (div: the dividend below the divisor, n < d;
     * NULL names: none). Derived ranges assume it (tb_derive.h); stimuli
     * that break it are outside the unit's domain. */
    struct { const char *lo, *hi; } below;
    /* Optional: signals whose format is the structure, not a range (div's
     * quotient register: its width is the number of clocks, and its value
     * spans the whole format whatever the format, older bits shifting out
     * at the top). Derived ranges never size them (tb_derive_fmts): a
     * wider one would only add clocks. NULL-terminated. */
    const char *fmt_fixed[4];
    /* Optional (NULL: every signal of the schedule is built): whether
     * configuration cfg builds signal i, for units whose signal set depends
     * on a parameter (div3's terms and series). Only asked about signals
     * of cfg->schedule; unit_sig_built combines the two. */
    int  (*sig_used)(const unit_cfg *cfg, int i);
    /* Optional (NULL: the testbench has only the double ideal): ideal in
     * exact dyadic arithmetic, for the exact values of the quantized
     * inputs; out as ideal's. 0, or -1 when the value does not fit a
     * sim_dy (the testbench then says it could not check). Units whose
     * ideal is a dyadic rational of the inputs provide it, so that the
     * bound check holds at every width (a double ideal loses bits beyond
     * 53). */
    int  (*ideal_exact)(const unit_cfg *cfg, const sim_dy *in, sim_dy *out);
    /* Optional, for units whose ideal divides (a rational of the inputs):
     * ideal = num / den exactly, den > 0, one value per output and beat.
     * 0, or -1 when a value does not fit a sim_dy. */
    int  (*ideal_ratio)(const unit_cfg *cfg, const sim_dy *in, sim_dy *num, sim_dy *den);
    /* Optional, where ideal_exact's value is too long for a sim_dy (a high
     * power): an interval [lo, hi] that contains the ideal exactly (e.g.
     * products cut down and up to a few hundred fraction bits). 0, or -1. */
    int  (*ideal_interval)(const unit_cfg *cfg, const sim_dy *in, sim_dy *lo, sim_dy *hi);
    /* 1 if bound takes each signal's own rounding mode (sim_fmt) into
     * account: a unit whose bound is the unet walk alone, whose every
     * quantization is an element of the walk with its signal's format
     * (unit_qerr reads the format's mode). 0: unit_bound gives no bound
     * when a signal's own rounding differs from cfg->rnd. */
    int  bound_own_modes;
};

/* The unit's bound per output for formats f (u->bound), or INFINITY (no
 * bound) for every output when a signal cfg builds has a rounding mode of
 * its own (sim_fmt) other than cfg->rnd and the unit's bound does not
 * follow such modes (bound_own_modes): most bounds are derived for one
 * rounding mode throughout, and some use its sign (trunc only lowers a
 * value), so a mix is not covered. Own overflow modes leave the bound as
 * it is: a bound holds for runs without overflow, and an overflow is
 * counted whether it wraps or saturates. */
void unit_bound(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, double *per_out);

/* The registry. */
size_t           unit_count(void);
const unit_desc *unit_at(size_t i);
const unit_desc *unit_find(const char *name);

/* The default configuration of unit u: width 16, its first schedule,
 * trunc and wrap, and each of its parameters at the default its params[]
 * table gives. A field u does not list is not a parameter of u but may
 * still be read by its code or its model: it holds the one value every
 * unit shares (terms and series: the paper's /3 network; the model's
 * fields: vec_params_default). u NULL (no unit chosen yet): those shared
 * values only. */
void unit_cfg_default(const unit_desc *u, unit_cfg *cfg);
int  unit_n_in(const unit_desc *u);
int  unit_n_out(const unit_desc *u);
int  unit_sig_index(const unit_desc *u, const char *name);   /* -1 if none */
/* 1 if signal i's format is the unit's structure (unit_desc.fmt_fixed). */
int  unit_sig_fmt_fixed(const unit_desc *u, int i);
/* 1 if schedule sched builds signal i (its scheds mask). */
int  unit_sig_used(const unit_desc *u, int i, int sched);
/* 1 if configuration cfg builds signal i: its schedule has it and the
 * unit's sig_used hook (if any) says the parameters build it. list, run,
 * --fmt, the JSON/CSV formats and the target search show exactly these. */
int  unit_sig_built(const unit_desc *u, int i, const unit_cfg *cfg);
/* Index of a signal the unit's own code names: it must exist (a misspelt
 * name is a bug, reported and aborted, never a silent default format). */
int  unit_sig_must(const unit_desc *u, const char *name);
/* Set a parameter from "value" text; 0, or -1 with a message. */
int  unit_param_set(const unit_desc *u, unit_cfg *cfg, const char *name,
                    const char *value, char *err, size_t errlen);
/* Value of a parameter as text (enum: its choice name). */
void unit_param_get(const unit_param *p, const unit_cfg *cfg, char *buf, size_t len);
int  unit_sched_find(const unit_desc *u, const char *name);  /* -1 if none */

/* The smallest width W whose default formats hold the unit's integer
 * range without the rule widening a signal: every signal whose format
 * follows W gets a format of its own at W (not the same as at W - 1,
 * which is what unit_fmt's clamp to F >= 0 produces). *limit_sig (if not
 * NULL) is the signal with the widest integer part among those that
 * limit it (-1 if none). Depends on cfg's parameters, not its width. */
int  unit_min_width(const unit_desc *u, const unit_cfg *cfg, int *limit_sig);

/* Helpers for format rules and bounds. */
sim_fmt unit_fmt(int is_signed, int ibits, int fbits);   /* clamps F >= 0, W <= 64 */
/* Largest error one quantization from src_f fraction bits into f adds:
 * 0 if no bits are dropped, an LSB less 2^-src_f for trunc, half an LSB
 * when rounding; with f's own rounding mode if it has one, else r. */
double  unit_qerr(sim_fmt f, int src_f, sim_round r);
#endif
