/* cli_sweep_opts.c - the sweep's options: the widths, the lists of
 * settings and parameter values that make its grid, the target search's
 * and acceptance options, sharding; one table (cli_opt.h) that also prints
 * `shadesim sweep --help`. */
#include "testbench/cli/cli_sweep.h"
#include "testbench/cli/cli_opt.h"
#include "base/base_num.h"
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* The n characters at s as a whole number lo..hi: digits only (no sign,
 * space or junk, nothing cut off). */
static int parse_long_n(const char *s, size_t n, long lo, long hi, long *v)
{
    long x = 0;
    if (!n) return -1;
    for (size_t k = 0; k < n; k++) {
        if (s[k] < '0' || s[k] > '9') return -1;
        if (x > 100000000000L) return -1;      /* far past any hi used here */
        x = x * 10 + (s[k] - '0');
    }
    if (x < lo || x > hi) return -1;
    *v = x;
    return 0;
}

static int parse_long(const char *s, long lo, long hi, long *v) { return parse_long_n(s, strlen(s), lo, hi, v); }

static int parse_widths(const char *v, int *lo, int *hi)
{
    const char *colon = strchr(v, ':');
    size_t na = colon ? (size_t)(colon - v) : strlen(v);
    const char *b = colon ? colon + 1 : v;
    long x, y;
    if (parse_long_n(v, na, 0, 1000000, &x) || parse_long(b, 0, 1000000, &y)) {
        char e[200];
        return cli_usage_error("--widths %s: expected LO:HI with whole numbers, e.g. 8:24", cli_esc(v, e, sizeof e));
    }
    if (x < 1 || y > 64 || y < 1 || x > 64)
        return cli_usage_error("--widths %s: widths must be within 1..64", v);
    if (x > y) return cli_usage_error("--widths %s: LO is greater than HI", v);
    *lo = (int)x;
    *hi = (int)y;
    return 0;
}

/* Split a comma list into at most cap distinct items of up to 31
 * characters; messages quote the option as given: "OPT SHOWN: ...". */
static int split_list(const char *opt_name, const char *shown, const char *list, char items[][32], int cap, int *n)
{
    *n = 0;
    for (const char *p = list;;) {
        size_t k = strcspn(p, ",");
        if (k == 0 || k > 31) return cli_usage_error("%s %s: expected a comma-separated list of values", opt_name, shown);
        if (*n == cap) return cli_usage_error("%s %s: at most %d values", opt_name, shown, cap);
        snprintf(items[*n], 32, "%.*s", (int)k, p);
        for (int j = 0; j < *n; j++)
            if (!strcmp(items[j], items[*n])) return cli_usage_error("%s %s: '%s' is listed twice", opt_name, shown, items[j]);
        ++*n;
        if (!p[k]) return 0;
        p += k + 1;
    }
}

static int parse_real(const char *s, double *v)
{
    return base_num_real(s, 0, v);
}

/* ---------------------------------------------------------------- options */

/* The options' calls: each takes one option's value into the arguments. */

static int o_widths(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    (void)opt;
    if (parse_widths(v, &a->sp.wlo, &a->sp.whi)) return CLI_USAGE;
    a->have_w = 1;
    return 0;
}

static int o_width(void *b, const char *opt, const char *v)
{
    (void)b, (void)opt, (void)v;
    return cli_usage_error("sweep: use --widths LO:HI (or --widths W for one width)");
}

static int o_round(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    char items[TB_SWEEP_MAX_VALUES][32];
    int n;
    if (split_list(opt, v, v, items, 3, &n)) return CLI_USAGE;
    for (int k = 0; k < n; k++)
        if (sim_round_parse(items[k], &a->sp.rnd[k])) return cli_usage_error("--round %s: '%s' is not trunc, half-up or even", v, items[k]);
    a->sp.nrnd = n;
    return 0;
}

static int o_overflow(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    char items[TB_SWEEP_MAX_VALUES][32];
    int n;
    if (split_list(opt, v, v, items, 2, &n)) return CLI_USAGE;
    for (int k = 0; k < n; k++)
        if (sim_ovf_parse(items[k], &a->sp.ovf[k])) return cli_usage_error("--overflow %s: '%s' is not wrap or sat", v, items[k]);
    a->sp.novf = n;
    return 0;
}

static int o_schedule(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    char items[TB_SWEEP_MAX_VALUES][32];
    int n;
    if (split_list(opt, v, v, items, UNIT_MAX_SCHED, &n)) return CLI_USAGE;
    for (int k = 0; k < n; k++)
        if ((a->sp.sched[k] = unit_sched_find(a->o.u, items[k])) < 0) return cli_unit_sched_error(a->o.u, items[k]);
    a->sp.nsched = n;
    return 0;
}

/* --param NAME=V1,V2,...: one axis of the sweep; each value is checked
 * on a scratch configuration now, so a bad one is refused before any run. */
static int o_param(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    const unit_desc *u = a->o.u;
    tb_sweep_spec *sp = &a->sp;
    const char *eq = strchr(v, '=');
    if (!eq) return cli_usage_error("--param %s: expected NAME=V1,V2,...", v);
    char pname[64], err[300], items[TB_SWEEP_MAX_VALUES][32];
    int n, pi = -1;
    snprintf(pname, sizeof pname, "%.*s", (int)(eq - v), v);
    for (int k = 0; k < u->nparams; k++)
        if (!strcmp(u->params[k].name, pname)) pi = k;
    unit_cfg scratch = a->o.cfg;
    if (pi < 0 && unit_param_set(u, &scratch, pname, eq + 1, err, sizeof err)) return cli_usage_error("--param %s: %s", v, err);
    for (int k = 0; k < sp->npax; k++)
        if (sp->pax[k].param == pi) return cli_usage_error("--param %s: %s is given twice", v, pname);
    tb_sweep_paxis *ax = &sp->pax[sp->npax];
    if (split_list(opt, v, eq + 1, items, TB_SWEEP_MAX_VALUES, &n)) return CLI_USAGE;
    for (int k = 0; k < n; k++) {
        if (unit_param_set(u, &scratch, pname, items[k], err, sizeof err)) return cli_usage_error("--param %s: %s", v, err);
        memcpy(ax->val[k], items[k], sizeof ax->val[k]);
    }
    ax->param = pi;
    ax->n = n;
    sp->npax++;
    return 0;
}

static int o_fmt(void *b, const char *opt, const char *v) { return cli_unit_fmt(&((sweep_args *)b)->o, opt, v); }

static int o_shard(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    long k, m;
    const char *sl = strchr(v, '/');
    char e[200];
    (void)opt;
    if (!sl) return cli_usage_error("--shard %s: expected K/N, e.g. 1/4", cli_esc(v, e, sizeof e));
    if (parse_long_n(v, (size_t)(sl - v), 0, 1000000, &k) || parse_long(sl + 1, 0, 1000000, &m))
        return cli_usage_error("--shard %s: expected K/N with whole numbers, e.g. 1/4", cli_esc(v, e, sizeof e));
    if (m < 1 || k < 1 || k > m) return cli_usage_error("--shard %s: K must be 1..N (shards are numbered from 1)", v);
    a->shard_k = (int)k;
    a->shard_n = (int)m;
    return 0;
}

static int o_margin(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    (void)opt;
    long m;
    if (cli_parse_long("--margin", v, 0, 32, "whole bits 0..32", &m)) return CLI_USAGE;
    a->t.margin = (double)m;
    return 0;
}

static int o_target(void *b, const char *opt, const char *v)
{
    sweep_args *a = b;
    int nmse = !strcmp(opt, "--target-nmse");
    if (a->t.on) return cli_usage_error("sweep: one target at a time (--target-error or --target-nmse)");
    if (parse_real(v, &a->t.value)) return cli_usage_error("%s %s: expected a number >= 0, e.g. 1e-3", opt, v);
    a->t.on = 1;
    a->t.kind = nmse ? TB_TARGET_NMSE : TB_TARGET_MAX_ABS_ERR;
    return 0;
}

#define SW_CALL(NAME, FN, MISSING, HELP) { NAME, NULL, CLI_OPT_CALL, 0, 0, 0, NULL, MISSING, FN, 0, HELP }
#define SW_ACCEPT(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_REAL, offsetof(sweep_args, sp.accept.FIELD), 0, HUGE_VAL, \
    "a number > 0, e.g. 1e-3", "%s : expected a number > 0, e.g. 1e-3", NULL, CLI_OPT_GT_LO, HELP }
static const cli_opt sweep_tab[] = {
    SW_CALL("--widths", o_widths, "--widths needs LO:HI",
        "  --widths LO:HI       widths to sweep, within 1..64 (or one width W)\n"),
    { "--width", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, o_width, CLI_OPT_MAYBE | CLI_OPT_HIDDEN, NULL },
    SW_CALL("--round", o_round, NULL,
        "  --round LIST         rounding modes, e.g. trunc,half-up,even (default trunc)\n"),
    SW_CALL("--overflow", o_overflow, NULL,
        "  --overflow LIST      overflow modes, e.g. wrap,sat (default wrap)\n"),
    SW_CALL("--schedule", o_schedule, NULL,
        "  --schedule LIST      the unit's schedules, e.g. paper,... (default its first)\n"),
    SW_CALL("--param", o_param, "--param needs NAME=VALUES",
        "  --param NAME=LIST    a unit parameter's values, e.g. terms=2,3,4 (repeatable)\n"),
    SW_CALL("--fmt", o_fmt, NULL,
        "  --fmt NAME=sI.F      pin a signal's format in every configuration (repeatable;\n"
        "                       sI.F:ROUND:OVERFLOW: its own modes, as for run)\n"),
    { "--vectors", NULL, CLI_OPT_STR, offsetof(sweep_args, o.vectors), 0, 0, NULL, NULL, NULL, 0,
        "  --vectors FILE       golden vectors (default: the unit's file in vectors/)\n" },
    { "-n", NULL, CLI_OPT_LONG, offsetof(sweep_args, nvec), 1, 10000000, "1..10000000 vectors",
        "%s : expected 1..10000000 vectors", NULL, 0,
        "  -n N [--seed S]      instead, N vectors made by the float reference (seed 1)\n" },
    { "--seed", NULL, CLI_OPT_U64, offsetof(sweep_args, seed), 0, 0, NULL, "--seed needs a whole number", NULL, 0, "" },
    SW_CALL("--target-error", o_target, "%s : expected a number >= 0, e.g. 1e-3",
        "  --target-error E     cheapest per-signal formats with max |error| <= E,\n"
        "                       re-checked on held-out stimuli (another seed)\n"),
    SW_CALL("--target-nmse", o_target, "%s : expected a number >= 0, e.g. 1e-3",
        "  --target-nmse E      ... with NMSE <= E\n"),
    SW_CALL("--margin", o_margin, "%s : expected whole bits 0..32",
        "  --margin BITS        the search aims at E / 2^BITS (NMSE: E / 4^BITS), so\n"
        "                       that the held-out check at E has room (default 0)\n"),
    SW_ACCEPT("--max-error", max_error, "  --max-error E        acceptance: a row meets it when max |error| <= E\n"),
    SW_ACCEPT("--max-nmse", max_nmse, "  --max-nmse X         ... when NMSE <= X\n"),
    SW_ACCEPT("--max-lsb", max_lsb,
        "  --max-lsb K          ... when max |error| <= K LSB of the output format;\n"
        "                       the CSV's meets_target says which rows do\n"),
    { "--min-throughput", NULL, CLI_OPT_REAL, offsetof(sweep_args, sp.ppa.min_items_per_s), 0, HUGE_VAL,
      "a number > 0, e.g. 2e8", "%s : expected items per second > 0, e.g. 2e8", NULL, CLI_OPT_GT_LO,
        "  --min-throughput R   the target search keeps only designs of at least R items\n"
        "                       per second at their f_max (docs/timing.md)\n" },
    { "--max-energy", NULL, CLI_OPT_REAL, offsetof(sweep_args, sp.ppa.max_energy_pj), 0, HUGE_VAL,
      "a number > 0, e.g. 5", "%s : expected picojoules per item > 0, e.g. 5", NULL, CLI_OPT_GT_LO,
        "  --max-energy PJ      ... and at most PJ picojoules per item (held-out too)\n" },
    SW_CALL("--ranges", sweep_o_ranges, "%s : expected observed or derived",
        "  --ranges MODE        the target search's integer bits: observed (default: from\n"
        "                       the ranges seen on the stimuli) or derived (hold every\n"
        "                       value for any input in the declared ranges; no overflow)\n"),
    SW_CALL("--range", sweep_o_range, "%s : expected NAME=LO:HI",
        "  --range NAME=LO:HI   an input's declared range for --ranges derived (default:\n"
        "                       its format's; repeatable)\n"),
    { "-j", NULL, CLI_OPT_INT, offsetof(sweep_args, threads), 1, 256, "1..256 threads", "%s : expected 1..256 threads",
        NULL, 0, "  -j N                 run on N threads (default 1); the output is the same\n" },
    SW_CALL("--shard", o_shard, "%s : expected K/N, e.g. 1/4",
        "  --shard K/N          run only configurations i with i mod N = K-1 and write\n"
        "                       DIR/sweep-K-of-N.csv; join them with shadesim merge\n"),
    { "-o", NULL, CLI_OPT_STR, offsetof(sweep_args, dir), 0, 0, NULL, "-o needs a folder", NULL, CLI_OPT_NONEMPTY,
        "  -o DIR               output folder (default out/sweep-UNIT), made if missing\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_sweep_spec = {
    "sweep", { sweep_tab }, NULL, 0, "sweep: unknown option '%s' (see shadesim sweep --help)",
    "usage: shadesim sweep UNIT --widths LO:HI [options]\n\n"
    "Runs UNIT's testbench at every width LO..HI (the unit's default-format rule,\n"
    "`shadesim list UNIT`), crossed with the listed settings, and writes into DIR:\n"
    "  sweep.csv            one row per configuration, every figure of run --json\n"
    "  error_vs_width.svg   max and RMS error against width (log scale)\n"
    "  area_vs_error.svg    area against max error, the Pareto front ringed\n"
    "  cycles_vs_error.svg  clocks per pixel against max error (when they vary)\n"
    "  throughput_vs_error.svg  pixels per second at f_max against max error\n"
    "  energy_vs_error.svg  energy per pixel against max error\n"
    "                       (the front: no other configuration is as good in\n"
    "                       max error, area and pixels per second and better in one;\n"
    "                       `shadesim chart` draws the charts from any sweep CSV)\n"
    "  summary.txt          what is printed on stdout\n"
    "  target.json          with --target-error/--target-nmse: the chosen formats\n"
    "  target.csv           ... and the same per settings group as one CSV row each\n"
    "Order of the rows: width-major, then schedule, each --param in the order\n"
    "given, round, overflow (the last varies fastest). docs/sweeps.md has more.\n\n"
    "options:\n",
    "\nThe files are written in full, then moved into DIR together: an interrupted\n"
    "sweep leaves DIR as it was, and of two sweeps into one DIR the folder keeps\n"
    "the complete set of the one that finished last (they take turns on the lock\n"
    "file DIR/.sweep.lock).\n\n"
    "exit status: 0 done (a width over its error bound is data: within_bound),\n"
    "1 some configuration's simulation failed, a row misses --max-error/--max-nmse/\n"
    "--max-lsb, or a target search's result failed its held-out check; 2 bad usage\n"
    "or input\n"
};

/* After the options: what they say together. */
static int sweep_check(const sweep_args *a)
{
    if (!a->have_w) return cli_usage_error("sweep: --widths LO:HI is required, e.g. --widths 8:24");
    if (a->nvec > 0 && a->o.vectors) return cli_usage_error("sweep: -n makes vectors; --vectors reads them: give one");
    if (a->shard_n && a->t.on) return cli_usage_error("sweep: the target search needs the whole sweep, not a shard");
    if (a->t.margin > 0 && !a->t.on) return cli_usage_error("sweep: --margin goes with --target-error or --target-nmse");
    if ((a->sp.ppa.min_items_per_s > 0 || a->sp.ppa.max_energy_pj > 0) && !a->t.on)
        return cli_usage_error("sweep: --min-throughput and --max-energy go with --target-error or --target-nmse");
    return 0;
}

/* The settings not swept take the unit options' single values. */
static void sweep_defaults(sweep_args *a)
{
    tb_sweep_spec *sp = &a->sp;
    a->t.goal = a->t.on ? tb_target_goal(a->t.kind, a->t.value, a->t.margin) : 0;
    sp->base = a->o.cfg;
    if (!sp->nsched) { sp->nsched = 1; sp->sched[0] = a->o.cfg.schedule; }
    if (!sp->nrnd) { sp->nrnd = 1; sp->rnd[0] = a->o.cfg.rnd; }
    if (!sp->novf) { sp->novf = 1; sp->ovf[0] = a->o.cfg.ovf; }
    sp->fmt = a->o.fmt;
    sp->nfmt = a->o.nfmt;
}

int sweep_parse(int argc, char **argv, sweep_args *a)
{
    memset(a, 0, sizeof *a);
    a->threads = 1;
    a->nvec = -1;
    a->seed = 1;
    if (argc < 2 || argv[1][0] == '-') return cli_usage_error("sweep: which unit? (shadesim list)");
    if (cli_unit_select(&a->o, argv[1])) return CLI_USAGE;
    a->sp.u = a->o.u;
    void *base[] = { a };
    if (cli_opt_parse(&cli_sweep_spec, base, argc, argv, 2) || sweep_check(a) || sweep_ranges_check(a)) return CLI_USAGE;
    sweep_defaults(a);
    return 0;
}

