/* cli.h - the command line: one function per verb, and the options that
 * several verbs share (unit, width, formats, modes, parameters, vectors).
 *
 * The public header of testbench/cli/: main.c, the option parser
 * (cli_opt.h), and one file per verb (cli_VERB.c; the sweep's in
 * cli_sweep*.c). A verb parses its options, calls the engine
 * (testbench/tb.h) or a study (testbench/study/study.h), and prints or
 * writes what they return; no verb calls another verb, and nothing below
 * includes this folder (tests/cli_layers.sh).
 *
 * Exit status: 0 success, 1 a testbench's error bound exceeded or the
 * simulation failed, 2 bad usage or bad input (one line on stderr), 3 out
 * of memory (base_out_of_memory, the one place that decides it). A verb
 * turns a testbench's TB_OK / TB_FAIL / TB_BADINPUT into 0 / 1 / 2 only
 * through cli_from_tb. docs/cli.md, "Exit status".
 */
#ifndef CLI_H
#define CLI_H
#include <stdio.h>
#include "testbench/tb.h"

enum { CLI_OK = 0, CLI_FAIL = 1, CLI_USAGE = 2, CLI_OOM = 3 /* = BASE_EXIT_OOM */ };

typedef struct cli_verb {
    const char *name;
    int (*fn)(int argc, char **argv);   /* argv[0] is the verb */
    const char *summary;
} cli_verb;
extern const cli_verb cli_verbs[];

int cli_list(int argc, char **argv);
int cli_vectors(int argc, char **argv);
int cli_run(int argc, char **argv);
int cli_claims(int argc, char **argv);
int cli_sweep(int argc, char **argv);
int cli_merge(int argc, char **argv);
int cli_scene(int argc, char **argv);
int cli_factor(int argc, char **argv);
int cli_chart(int argc, char **argv);
int cli_report(int argc, char **argv);
int cli_stability(int argc, char **argv);
int cli_verilog(int argc, char **argv);
int cli_cosim(int argc, char **argv);
int cli_synth(int argc, char **argv);
int cli_netlist(int argc, char **argv);

/* Print "shadesim: " + message + newline to stderr; returns CLI_USAGE.
 * Control bytes and bytes that are not UTF-8 go out as \xNN (messages
 * echo user text), so it serves every one-line error message. */
int cli_usage_error(const char *fmt, ...);
/* The one mapping from a testbench's result to an exit status: TB_OK is
 * CLI_OK (nothing printed); TB_BADINPUT is CLI_USAGE and TB_FAIL (or any
 * other failure) CLI_FAIL, each after the message fmt formats as one line
 * on stderr (as cli_usage_error; no line when fmt is NULL or the message
 * is empty). */
int cli_from_tb(int t, const char *fmt, ...);
/* A verb's results went to stdout: a write error there (full disk, closed
 * pipe) must not pass as success. rc, or CLI_USAGE after the error's line;
 * every verb that prints results returns through it. */
int cli_stdout_done(int rc);
/* Strict numbers for option values: the whole text must be the number
 * (decimal digits, a leading '-' only when lo < 0; reals also a fraction
 * and an exponent; no spaces, '+', hex, inf or nan), within lo..hi.
 * 0 and *out, or CLI_USAGE after "OPT TEXT: expected WHAT" on stderr
 * (what: NULL says "a whole number LO..HI" / "a number LO..HI"). */
int cli_parse_long(const char *opt, const char *text, long lo, long hi, const char *what, long *out);
int cli_parse_u64(const char *opt, const char *text, const char *what, uint64_t *out);
int cli_parse_real(const char *opt, const char *text, double lo, double hi, const char *what, double *out);
/* 1 if text is a plain decimal real as above (no range check). */
int cli_is_real(const char *text);
/* User text made printable for a message: bytes outside 0x20..0x7e as
 * \xNN (cut to fit buf). Returns buf. */
const char *cli_esc(const char *text, char *buf, size_t len);
/* mkdir -p for an output folder (-o DIR): CLI_OK, or CLI_USAGE after one
 * line on stderr. */
int cli_make_dir(const char *dir);
/* True if stderr is a terminal (progress displays only then). */
int cli_stderr_tty(void);

/* Options shared by run and sweep. */
#define CLI_MAX_FMT 64
typedef struct cli_unit_opts {
    const unit_desc *u;
    unit_cfg    cfg;
    const char *fmt[CLI_MAX_FMT];   /* --fmt NAME=sI.F, in order */
    int         nfmt;
    const char *vectors;            /* --vectors FILE, or NULL */
} cli_unit_opts;

/* Select the unit (and its defaults) by name; CLI_USAGE with a message. */
int cli_unit_select(cli_unit_opts *o, const char *name);
/* The usage error for a unit name that is none: exit status 2, the
 * nearest unit suggested when the name is a likely typo. */
int cli_unknown_unit(const char *name);
/* The shared options themselves (--width, --fmt, ...) are the table
 * cli_unit_opt_tab of cli_opt.h. */

/* The vectors: --vectors FILE, else the unit's checked-in default file
 * (vectors/UNIT.vec beside the binary's tree) when the parameters are the
 * defaults, else generated from the float reference. 0 or CLI_USAGE. */
int cli_load_vectors(const cli_unit_opts *o, vec_set *vs);
/* The vector file cli_load_vectors would read: 1 and *path (in buf when it
 * is the unit's default file), 0 when the vectors are generated instead
 * (parameters other than the defaults, no --vectors), -1 when the default
 * file is missing (message printed). */
int cli_vectors_file(const cli_unit_opts *o, char *buf, size_t len, const char **path);
/* Path of the checked-in default vectors of a unit. */
const char *cli_default_vectors_path(const char *unit, char *buf, size_t len);

/* "--schedule NAME: unit U has schedules: a, b": CLI_USAGE. */
int cli_unit_sched_error(const unit_desc *u, const char *name);
#endif
