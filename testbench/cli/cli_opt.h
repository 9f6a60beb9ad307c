/* cli_opt.h - one option parser for every verb.
 *
 * A verb describes its options once, as a table: the name (and another
 * spelling), what kind of value it takes and where the value goes, the
 * message for a missing or bad value, and the option's lines of --help.
 * cli_opt_parse reads argv against the tables; cli_opt_help prints the
 * verb's --help from the same tables, so an option cannot be accepted and
 * left out of the help (tests/test_cli_opt.c checks every verb).
 *
 * Rules every verb shares:
 *   - an option that takes a value is written "--opt VALUE" or
 *     "--opt=VALUE" (also "-o DIR" / "-o=DIR");
 *   - numbers are strict (cli_parse_long/u64/real): the whole text is the
 *     number, within the option's range;
 *   - --help or -h anywhere prints the verb's help (cli_opt_help_wanted);
 *   - a bad option is one line on stderr and status 2 (CLI_USAGE).
 */
#ifndef CLI_OPT_H
#define CLI_OPT_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef enum cli_opt_kind {
    CLI_OPT_FLAG,   /* no value: int at base+off set to 1 */
    CLI_OPT_STR,    /* const char * at base+off (the argv text) */
    CLI_OPT_INT,    /* int at base+off, a whole number lo..hi */
    CLI_OPT_LONG,   /* long at base+off, a whole number lo..hi */
    CLI_OPT_U64,    /* uint64_t at base+off, a whole number 0..2^64-1 */
    CLI_OPT_REAL,   /* double at base+off, a number lo..hi */
    CLI_OPT_CALL,   /* call(base, option, value) takes the value */
    CLI_OPT_CALL0   /* call(base, option, NULL): a flag with work to do */
} cli_opt_kind;

/* flags */
enum {
    CLI_OPT_GT_LO    = 1,   /* REAL: the value must be > lo (same message) */
    CLI_OPT_NONEMPTY = 2,   /* an empty value counts as missing */
    CLI_OPT_MAYBE    = 4,   /* CALL: the value is optional: "--opt=V", or the next
                             * argument when it holds '=' and does not start with
                             * '-'; else call gets NULL */
    CLI_OPT_HIDDEN   = 8,   /* not in --help: an old spelling kept for its message */
};

/* What a CALL returns: 0 (taken), CLI_USAGE (after its one-line message),
 * or CLI_OPT_UNKNOWN: not an option here after all (the verb's "unknown
 * option" message follows, e.g. a unit option before the unit). */
enum { CLI_OPT_UNKNOWN = -1 };

typedef struct cli_opt {
    const char *name;       /* "--width", "-o"; NULL ends a table */
    const char *alias;      /* another spelling, or NULL */
    cli_opt_kind kind;
    size_t off;             /* where the value goes (offsetof in the group's struct) */
    double lo, hi;          /* INT, LONG, REAL: the range */
    const char *what;       /* "OPT TEXT: expected WHAT"; NULL: "a whole number LO..HI",
                             * "a number LO..HI" */
    const char *missing;    /* format of the message for a missing value, %s the
                             * option as typed; NULL: "%s needs a value" */
    int (*call)(void *base, const char *opt, const char *val);
    unsigned flags;
    const char *help;       /* the option's lines of --help, as printed (each
                             * line "  --opt ...\n"); "" when the lines of an
                             * entry above describe it too; NULL: printed in the
                             * verb's own text (help_head), not as a line */
} cli_opt;

#define CLI_OPT_GROUPS 4

/* A verb's options: up to CLI_OPT_GROUPS tables, each with its own struct
 * (the bases given to cli_opt_parse, in the same order); an option of an
 * earlier table hides one of the same name in a later one. */
typedef struct cli_optspec {
    const char *verb;
    const cli_opt *tab[CLI_OPT_GROUPS];
    /* An argument that is not an option (does not start with '-'; "-"
     * alone too when dash_is_arg): pos(base[0], arg) -> 0, CLI_USAGE or
     * CLI_OPT_UNKNOWN; NULL: every such argument is unknown. */
    int (*pos)(void *base, const char *arg);
    int dash_is_arg;
    const char *unknown;    /* format, %s the argument: "run: unknown option '%s' ..." */
    const char *help_head;  /* --help: this, the tables' help lines, help_tail */
    const char *help_tail;
} cli_optspec;

/* 1 if --help or -h is among argv[1..argc-1]. */
int cli_opt_help_wanted(int argc, char **argv);
/* Print the verb's --help on stdout and check the write: CLI_OK, or
 * CLI_USAGE after the message. */
int cli_opt_help(const cli_optspec *sp);
/* The tables' help lines alone, in table order. */
void cli_opt_help_lines(FILE *f, const cli_optspec *sp);

/* Parse argv[first..argc-1]: each option into its table's base, each other
 * argument to sp->pos. 0, or CLI_USAGE after one line on stderr. */
int cli_opt_parse(const cli_optspec *sp, void *const *base, int argc, char **argv, int first);

/* One step: if argv[*i] is an option of tab, take it (and its value,
 * moving *i past it) and return 1; 0 if it is not one of tab's; CLI_USAGE
 * after the message; CLI_OPT_UNKNOWN when the option's call refused it. */
int cli_opt_step(const cli_opt *tab, void *base, int argc, char **argv, int *i);

/* The entry of tab (the tables of sp) named name (either spelling), or NULL. */
const cli_opt *cli_opt_find(const cli_opt *tab, const char *name);

/* The options run, verilog, cosim and synth share (--width, --fmt, --round,
 * --overflow, --schedule, --param, --vectors) on a cli_unit_opts (cli.h),
 * and the calls behind them that other verbs' tables use too. */
extern const cli_opt cli_unit_opt_tab[];
int cli_unit_width(void *unit_opts, const char *opt, const char *val);
int cli_unit_fmt(void *unit_opts, const char *opt, const char *val);
int cli_unit_param(void *unit_opts, const char *opt, const char *val);

/* Each verb's options (in that verb's file). */
extern const cli_optspec cli_list_spec, cli_vectors_spec, cli_run_spec, cli_claims_spec, cli_sweep_spec,
    cli_merge_spec, cli_scene_spec, cli_verilog_spec, cli_cosim_spec, cli_synth_spec, cli_stability_spec,
    cli_factor_spec, cli_chart_spec, cli_report_spec, cli_netlist_spec;

/* Every verb's option spec with the verb's function ({NULL, NULL} ends
 * it; cli_optverbs.c), for the test that holds each verb's --help to its
 * tables (tests/test_cli_opt.c). */
typedef struct cli_optverb {
    const cli_optspec *spec;
    int (*fn)(int argc, char **argv);
} cli_optverb;
extern const cli_optverb cli_optverbs[];
#endif
