/* tb_sweep.h - the sweep engine: a unit's testbench over a grid of widths
 * and other settings, on several threads or in deterministic shards, with
 * the results as one CSV, and the search for the cheapest per-signal
 * formats that meet an error target.
 *
 * Configuration order (contract, docs/sweeps.md): width-major, then
 * schedule, then each swept --param in the order given, then round, then
 * overflow; the last axis varies fastest. Configuration i therefore has
 * width lo + i / ngroups, and "group" i % ngroups: the combination of
 * everything but the width. A shard K/N (K = 1..N) holds the configurations
 * with i % N == K - 1.
 *
 * tb_run builds a fresh simulation per call and the run path keeps no
 * global mutable state, so configurations run on separate threads with no
 * locking beyond handing out indices; every result lands in its own slot,
 * and the CSV is written in configuration order, so it is the same bytes
 * whatever the thread count or shard split.
 */
#ifndef TB_SWEEP_H
#define TB_SWEEP_H
#include <stdio.h>
#include "testbench/tb.h"
#include "testbench/tb_derive.h"

#define TB_SWEEP_MAX_VALUES  64        /* values of one axis */
#define TB_SWEEP_MAX_CONFIGS 1000000   /* a bigger grid is a usage error */
/* A sweep CSV's line is a few hundred bytes; a longer one is not one
 * (merge or chart of /dev/zero, a binary file) and stops the reading. */
#define TB_SWEEP_MAX_LINE    ((size_t)1 << 20)

/* One swept unit parameter: --param NAME=V1,V2,... */
typedef struct tb_sweep_paxis {
    int  param;                           /* index into u->params */
    int  n;
    char val[TB_SWEEP_MAX_VALUES][32];    /* as given */
} tb_sweep_paxis;

typedef struct tb_sweep_spec {
    const unit_desc *u;
    unit_cfg   base;                      /* defaults; axes overwrite their fields */
    int        wlo, whi;                  /* widths, inclusive */
    int        nsched, sched[UNIT_MAX_SCHED];
    int        nrnd;  sim_round rnd[3];
    int        novf;  sim_ovf   ovf[2];
    int        npax;  tb_sweep_paxis pax[UNIT_MAX_PARAMS];
    const char *const *fmt;               /* --fmt overrides, applied to every configuration */
    int        nfmt;
    tb_accept  accept;                    /* --max-error/--max-nmse/--max-lsb: each row's meets_target */
    tb_ppa_limits ppa;                    /* --min-throughput/--max-energy: the target search's limits */
    const tb_ranges *ranges;              /* --ranges derived: the target search's integer bits
                                           * come from derived ranges (NULL: observed) */
} tb_sweep_spec;

typedef struct tb_sweep_cfg {
    unit_cfg  cfg;
    unit_fmts fmts;
    size_t    group;                      /* i % ngroups */
    size_t    pset;                       /* index of its parameter values (its vectors) */
} tb_sweep_cfg;

enum { TB_SWEEP_NOT_RUN = -1 };           /* row status besides TB_OK/TB_FAIL/TB_BADINPUT */

typedef struct tb_sweep_row {
    int        status;
    char       err[240];                  /* the message when status is not TB_OK */
    tb_result  r;                         /* raw and beat_cycle already freed */
} tb_sweep_row;

typedef struct tb_sweep {
    tb_sweep_spec   spec;
    size_t          n, ngroups, npsets;
    tb_sweep_cfg   *cfg;                  /* [n] */
    tb_sweep_row   *row;                  /* [n] */
    const vec_set **vs;                   /* [npsets]: the caller loads them (tb_sweep_pset_cfg) */
    uint64_t        id;                   /* fingerprint of configurations and vectors */
    /* Streamed vectors (tb_sweep_stream): each configuration generates its
     * parameter set's gen_n rows from gen_seed as it runs, a block at a
     * time, instead of reading vs's rows (vs then holds the headers alone). */
    int             stream;
    size_t          gen_n;                /* rows (a file's: counted by tb_sweep_fingerprint) */
    uint64_t        gen_seed;
    const char     *path;                 /* tb_sweep_stream_file: read from it instead */
} tb_sweep;

/* Enumerate the configurations; 0, or -1 with a message (bad --fmt, too
 * many configurations, out of memory). */
int  tb_sweep_init(tb_sweep *s, const tb_sweep_spec *spec, char *err, size_t errlen);
void tb_sweep_free(tb_sweep *s);
/* The smallest width every configuration of the spec can be built at
 * without the format rule widening a signal (unit_min_width over the
 * schedules and parameter values; 1 when --fmt all=... sets every format);
 * *limit_sig, *limit_cfg: the signal that limits it and a configuration
 * where it does. */
int  tb_sweep_min_width(const tb_sweep_spec *spec, int *limit_sig, unit_cfg *limit_cfg);
/* A configuration with parameter set p, to load or make its vectors. */
const unit_cfg *tb_sweep_pset_cfg(const tb_sweep *s, size_t p);
/* After the vectors are in place: the sweep's fingerprint (s->id), which
 * the CSV carries so that merge refuses shards of different sweeps.
 * Streamed vectors are generated once for it. 0, or -1 with a message
 * (a generator that fails or does not give n rows). */
int  tb_sweep_fingerprint(tb_sweep *s, char *err, size_t errlen);
/* Stream the vectors: n rows of the unit's reference generator from seed
 * per parameter set, made by each configuration as it runs (memory a few
 * blocks per thread, whatever n is) instead of held; the same rows, so
 * the same results, as vs holding tb_make_vectors(n, seed)'s. vs must
 * hold each set's header (vec_set_header). */
void tb_sweep_stream(tb_sweep *s, size_t n, uint64_t seed);
/* The same with the rows of a vector file (one parameter set), read a
 * block at a time by each configuration; tb_sweep_fingerprint reads it
 * first (its count, then its rows), and says what is wrong with it. */
void tb_sweep_stream_file(tb_sweep *s, const char *path);
/* The vectors of parameter set p: rows (streamed or held). */
size_t tb_sweep_rows(const tb_sweep *s, size_t p);

/* Shard K of N (1-based) holds configuration i? N = 0: no sharding. */
int  tb_sweep_in_shard(size_t i, int k, int n);
/* Called after each configuration, serialised; done counts this run's. */
typedef void (*tb_sweep_progress_fn)(void *arg, size_t done, size_t total);
/* Run the configurations of shard k/n (n = 0: all) on `threads` threads.
 * Returns the number of configurations whose simulation failed (their
 * rows say why); the others are TB_OK rows, within bound or not. */
size_t tb_sweep_run(tb_sweep *s, int threads, int shard_k, int shard_n,
                    tb_sweep_progress_fn progress, void *arg);

/* One configuration's group described for people: "half-up sat", "paper
 * terms=3"; only the axes with more than one value; "" if none. */
void tb_sweep_group_label(const tb_sweep *s, size_t group, char *buf, size_t len);

/* The CSV of the run rows (shard k/n, or all with n = 0), atomically. */
int  tb_sweep_write_csv(const tb_sweep *s, const char *path, int shard_k, int shard_n,
                        char *err, size_t errlen);
/* The same CSV to an open stream (write errors left in its error flag). */
void tb_sweep_print_csv(const tb_sweep *s, FILE *f, int shard_k, int shard_n);
/* merge: shards' CSVs into the whole run's CSV; 0, or -1 with a message. */
int  tb_sweep_merge(const char *const *paths, int n, const char *out, char *err, size_t errlen);

/* ---------------------------------------------------------- target search */

typedef enum { TB_TARGET_MAX_ABS_ERR, TB_TARGET_NMSE } tb_target_kind;

typedef struct tb_target_res {
    size_t    group;
    int       met;            /* some uniform width of the sweep met the target, and the
                               * chosen formats meet the speed and energy limits */
    char      limits_why[160];/* met 0 with a uniform start: the limit the result missed
                               * ("" otherwise) */
    size_t    uniform;        /* its row index: the smallest such width */
    unit_fmts fmts;           /* the chosen per-signal formats */
    tb_result r;              /* their result (raw freed) */
    size_t    runs;           /* tb_run calls of a one-at-a-time search */
    /* The held-out check (tb_sweep_target_heldout): */
    int       heldout;        /* 1 once checked */
    int       heldout_ok;     /* the chosen design met the target there */
    int       heldout_status; /* tb_run's status for the chosen design */
    tb_result heldout_r;      /* the chosen design on the held-out stimuli */
    tb_result heldout_u;      /* the uniform design on them */
    char      heldout_why[240];   /* why it failed ("" when it passed) */
} tb_target_res;

/* The acceptance rule of the search (docs/sweeps.md): the run succeeded,
 * every output is within its bound, the metric meets the target, and there
 * are no more overflows than max_ovf (those of the uniform design). The
 * search starts from the smallest uniform width that meets it, and asks
 * for the sweep's speed and energy limits of its result (tb_sweep_holds):
 * until its design meets them it takes any bit removal that keeps the
 * rule, then only those that keep them met. */
int  tb_target_holds(const tb_result *r, int status, tb_target_kind k, double target, uint64_t max_ovf);
/* tb_target_holds, and the sweep's speed and energy limits (spec.ppa) met. */
int  tb_sweep_holds(const tb_sweep *s, const tb_result *r, int status, tb_target_kind k, double target,
                    uint64_t max_ovf);
/* Cheapest formats for one group: start from the smallest uniform width of
 * the (already run) sweep that holds, then greedy passes, each trying to
 * drop one fraction bit and one integer bit of every signal in turn
 * (keeping a drop when the rule still holds), until a pass changes
 * nothing; so at the end no single-bit removal holds. A pass takes the
 * removals in order of the area each saves from the start (tried once,
 * all at once), dearest first. Signals pinned with --fmt are left alone.
 * Deterministic for any thread count: candidates are tried speculatively
 * in batches of `threads`, and the first that holds in order wins, as a
 * one-at-a-time search would; `runs` counts what that search would run.
 * out->met = 0 (and 0 returned) when no width of the sweep holds. 0, or
 * -1 with a message (out of memory). */
int  tb_sweep_target(const tb_sweep *s, size_t group, tb_target_kind k, double target,
                     int threads, tb_target_res *out, char *err, size_t errlen);

/* --ranges derived (tb_sweep_ranges.c). f with every signal's integer
 * bits derived for configuration c's settings (keep[i]: signal i pinned):
 * 0, or -1 with a message. */
int  tb_sweep_derive(const tb_sweep *s, const tb_sweep_cfg *c, const unsigned char *keep, unit_fmts *f,
                     char *err, size_t errlen);
/* The search's start under derived ranges: the smallest width of group
 * whose default design with derived integer bits holds the target with
 * no overflow, those formats and their result in out (out->uniform
 * that width's row). 0 (out->met 0 if none holds), or -1 with a message. */
int  tb_sweep_derived_start(const tb_sweep *s, size_t group, tb_target_kind k, double target,
                            const unsigned char *keep, tb_target_res *out, char *err, size_t errlen);

/* The acceptance rule under derived ranges: tb_target_holds with no
 * overflow, and for max |e| also each output's worst case on the box
 * stimuli, tb_derived_err, within the target. */
int  tb_target_holds_derived(const tb_result *r, int status, tb_target_kind k, double target);
/* The largest over the outputs of bound + max_input_err + max_method_err:
 * the datapath's error for any input (the derived bound) plus what
 * rounding the inputs and the method moved the ideal by on r's stimuli;
 * inf when an output has no bound. */
double tb_derived_err(const tb_result *r);

/* The target with a margin of `bits` bits: max |e| target / 2^bits, NMSE
 * target / 4^bits (NMSE is a squared error). The search aims at this; the
 * held-out check asks for the target itself. */
double tb_target_goal(tb_target_kind k, double target, double bits);

/* Re-check a search's result on held-out stimuli `ho` (vectors the search
 * never saw: another seed, with the generator's full-range corner values):
 * the chosen formats and the uniform design it started from both run on
 * them; it passes when the chosen design's run succeeds, every output is
 * within its bound, its metric meets `target`, and it has no more
 * overflows than the uniform design on the same stimuli. Sets out->heldout*
 * (nothing for a group whose target was not met). 0, or -1 when a run
 * could not be made (message). */
int  tb_sweep_target_heldout(const tb_sweep *s, const vec_set *ho, tb_target_kind k, double target,
                             tb_target_res *out, char *err, size_t errlen);

/* ------------------------------------------------------------- utilities */

/* A file written atomically: a temporary in the same directory, renamed
 * over path by tb_afile_commit; nothing is left behind on failure (nor on
 * SIGINT/TERM/HUP). Devices and FIFOs are written through, "-" is stdout
 * (base/base_out.h). */
typedef struct tb_afile { FILE *f; struct base_out *out; const char *path; } tb_afile;
int  tb_afile_open(tb_afile *a, const char *path, char *err, size_t errlen);
int  tb_afile_commit(tb_afile *a, char *err, size_t errlen);
void tb_afile_abort(tb_afile *a);
#endif
