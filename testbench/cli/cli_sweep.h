/* cli_sweep.h - what the files of the sweep verb share (not a public
 * header): its arguments, the set of output files, and the target search.
 *   cli_sweep.c          the verb: vectors, the run, a shard's CSV
 *   cli_sweep_opts.c     its options (the grid, targets, shards)
 *   cli_sweep_files.c    the output folder's file set, moved in together
 *   cli_sweep_summary.c  Pareto front, charts, summary table, the whole set
 *   cli_sweep_target.c   the target search, its held-out check, target.json/.csv
 */
#ifndef CLI_SWEEP_H
#define CLI_SWEEP_H
#include "testbench/cli/cli.h"
#include "testbench/study/tb_sweep.h"
#include "base/base_out.h"

/* The files of one sweep, a base_outset moved into DIR together
 * (cli_sweep_files.c); set is made at the first open. */
typedef struct oset {
    const char *dir;
    int n;
    base_outset *set;
} oset;

typedef struct target_info {
    int on;
    tb_target_kind kind;
    double value;
    double margin;          /* --margin BITS */
    double goal;            /* what the search aims at: value less the margin */
    unsigned long long ho_seed;   /* seed of the held-out stimuli */
    size_t ho_rows;         /* their vectors per parameter set */
    tb_target_res *res;     /* [ngroups] */
    /* --ranges derived (cli_sweep_ranges.c): per group, the chosen design's
     * derived intervals and its run with observed ranges */
    tb_derived *dres;       /* [ngroups] */
    tb_result  *dobs;       /* [ngroups] */
    char box[600];          /* the box the stimuli were drawn from (the first parameter set's) */
    size_t box_items;       /* stimuli added over it, per parameter set */
} target_info;

typedef struct sweep_args {
    cli_unit_opts o;
    tb_sweep_spec sp;
    const char *dir;
    int threads, shard_k, shard_n;
    int have_w;             /* --widths given */
    long nvec;              /* -n: vectors made by the reference; -1: read them */
    uint64_t seed;
    target_info t;
    int ho_failed;          /* some group's held-out check failed */
    int t_missed;           /* settings groups whose target search found nothing (met 0) */
    size_t misses;          /* rows that miss --max-error/--max-nmse/--max-lsb */
    int derived;            /* --ranges derived */
    int nrange;             /* --range NAME=LO:HI given */
    tb_ranges ranges;
} sweep_args;

/* The options (argv[1] the unit): 0, or CLI_USAGE after the message. */
int sweep_parse(int argc, char **argv, sweep_args *a);

/* Open DIR/name as one of the set; NULL after printing the error. */
FILE *sweep_oset_open(oset *os, const char *name);
void sweep_oset_abort(oset *os);
/* Move the set in (and remove DIR/gone[k]) under the folder's lock. */
int sweep_oset_commit(oset *os, const char *const *gone, int ngone);

/* Rows (of shard k/n; n = 0: all) that miss the user's acceptance
 * (--max-error/--max-nmse/--max-lsb): a line saying which, counted in
 * *misses; nothing when no acceptance option was given. */
void sweep_print_accept(FILE *f, const tb_sweep *s, int shard_k, int shard_n, size_t *misses);
/* The whole sweep's files into a->dir and the summary on stdout. */
int sweep_outputs(sweep_args *a, tb_sweep *s, double t0, int tty);

/* The target search over every settings group, then its held-out check
 * (a->t.res filled): 0 or CLI_USAGE after the message. */
int sweep_target_search(sweep_args *a, tb_sweep *s, int tty);
void sweep_print_target(FILE *f, const tb_sweep *s, const target_info *t);
int sweep_write_target_csv(const tb_sweep *s, const target_info *t, oset *os);
int sweep_write_target_json(const tb_sweep *s, const target_info *t, oset *os);
/* --ranges and --range (cli_sweep_ranges.c): the option calls; the
 * check after every option; after the target search, each group's chosen
 * design derived and run again for its observed ranges; the table of both
 * (text) and the array (JSON) for group g. */
int  sweep_o_ranges(void *base, const char *opt, const char *val);
int  sweep_o_range(void *base, const char *opt, const char *val);
int  sweep_ranges_check(sweep_args *a);
int  sweep_ranges_collect(sweep_args *a, tb_sweep *s);
void sweep_ranges_print(FILE *f, const target_info *t, size_t g);
void sweep_ranges_json(FILE *f, const target_info *t, size_t g);
void sweep_ranges_free(target_info *t, size_t ngroups);
/* --ranges derived: stimuli over the declared ranges added to the
 * sweep's vectors (each parameter set's). */
int  sweep_ranges_stimuli(sweep_args *a, tb_sweep *s, vec_set *sets);
#endif
