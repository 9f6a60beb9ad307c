/* tb_derive.h - derived ranges: every signal's interval for any input in
 * declared ranges, by an interval simulation of the unit's schedule.
 *
 * The unit is built as a testbench builds it (tb_build); then, with no
 * kernel run, every element is evaluated on intervals (sim/sim_ival.h)
 * clock by clock, driven as tb_run drives it: the data inputs hold their
 * declared interval on every clock (whatever item is on them), valid is
 * offered on every clock. Control (step counters, decoders, selects) that
 * depends on no data stays a point, so the schedule is followed exactly;
 * a data-dependent select takes the hull of its inputs. Each signal's
 * derived interval is the hull over every clock of its value before
 * overflow handling (what its format must hold).
 *
 * A precondition the unit states between two inputs (unit_desc.below:
 * div's n < d) narrows their intervals and makes the lower one's form the
 * upper one's less a positive symbol, on every item.
 *
 * Items come one after another until the register state at an item's
 * acceptance lies within the state at the previous acceptance (the state
 * there is the hull of every earlier one, so the sequence grows and
 * stops): from then on nothing new can happen, the last items drain, and
 * the hull covers every item of any run of any length. A state that keeps
 * growing (an accumulator never cleared) is reported, as is a handshake
 * that depends on data.
 */
#ifndef TB_DERIVE_H
#define TB_DERIVE_H
#include "testbench/tb.h"
#include "sim/sim_ival.h"

/* Declared input ranges (--range NAME=LO:HI); an input without one takes
 * its format's whole range. */
typedef struct tb_ranges {
    int    set[UNIT_MAX_SIGS];        /* by unit signal index (inputs only) */
    double lo[UNIT_MAX_SIGS], hi[UNIT_MAX_SIGS];
} tb_ranges;

/* "NAME=LO:HI" into rg (NAME an input of u; LO <= HI, finite numbers):
 * 0, or -1 with a message naming the option. */
int tb_ranges_parse(const unit_desc *u, const char *spec, tb_ranges *rg, char *err, size_t errlen);

typedef struct tb_dsig {
    char     name[48];      /* path below the unit's scope, as tb_sig's */
    sim_fmt  fmt;
    int      kind;          /* sim_kind */
    sim_ival pre;           /* derived interval: raws of fmt, before overflow handling */
    double   lo, hi;        /* the same in reals */
    int      fits;          /* fmt holds it */
} tb_dsig;

typedef struct tb_derived {
    tb_dsig *sigs;                    /* every signal of the unit, creation order (tb_result's order) */
    int      nsigs;
    int      at[UNIT_MAX_SIGS];       /* index in sigs of each unit signal; -1: not built */
    int      nfail;                   /* signals whose format cannot hold their interval */
    int      items;                   /* items simulated until the state settled */
    uint64_t clocks;
} tb_derived;

/* Derive the ranges of u under cfg with formats f. 0, or -1 with a
 * message (the unit refuses the formats; ranges that do not settle;
 * control that depends on data). */
int  tb_derive(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, const tb_ranges *rg,
               tb_derived *out, char *err, size_t errlen);
void tb_derived_free(tb_derived *d);

/* Formats whose integer bits are derived: each unit signal (but those
 * with keep[i] set, and inputs without a declared range) gets the
 * smallest integer bits that hold its derived interval, signed as its
 * format is, fraction bits as in `in`. Values that do not overflow do not
 * depend on integer bits, so one derivation with every integer part wide
 * gives the intervals of the result. 0, or -1 with a message. */
int  tb_derive_fmts(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *in, const tb_ranges *rg,
                    const unsigned char *keep, unit_fmts *out, char *err, size_t errlen);

/* One line per signal whose format cannot hold its derived interval
 * (all: every signal, with observed ranges from r when r has them). */
void tb_derived_print(FILE *f, const tb_derived *d, const tb_result *r, int all);
/* The intervals as a JSON array (observed from r when given). */
void tb_derived_json(FILE *f, const tb_derived *d, const tb_result *r);
#endif
