/* cli_stability.c - the verb stability: where each method stops working
 * (testbench/study/tb_stability.c measures it), as one table and charts. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include <stddef.h>
#include "testbench/study/tb_stability.h"
#include "base/base_out.h"
#include "base/base_json.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>


static int write_charts(const tb_stab *s, const char *dir, char paths[][600], int *np)
{
    if (cli_make_dir(dir)) return CLI_USAGE;
    /* the charts are one set: all appear, or none */
    base_outset *set = base_outset_begin();
    char err[800];
    if (!set) base_out_of_memory();
    for (int i = 0; i < s->ncharts; i++) {
        snprintf(paths[*np], 600, "%s/%s", dir, s->chart_files[i]);
        if (chart_write(s->charts[i], paths[*np], err, sizeof err)) {
            base_outset_abort(set);
            return cli_usage_error("stability: %s", err);
        }
        (*np)++;
    }
    if (base_outset_commit(set, err, sizeof err)) return cli_usage_error("stability: %s", err);
    return CLI_OK;
}

static void print_text(FILE *f, const tb_stab *s, char paths[][600], int np)
{
    fputs("Where each method stops working, measured (targets 2^-8 unless a row says otherwise)\n\n"
          "method | condition | measured | verdict\n", f);
    for (int i = 0; i < s->nrows; i++) {
        const tb_stab_row *r = &s->rows[i];
        fprintf(f, "%s | %s | %s | %s\n", r->method, r->condition, r->measured, r->verdict);
    }
    fprintf(f, "\n%d rows\n", s->nrows);
    for (int i = 0; i < np; i++) fprintf(f, "wrote %s\n", paths[i]);
}

static void print_json(FILE *f, const tb_stab *s, char paths[][600], int np)
{
    fputs("{\n  \"target\": 0.00390625,\n  \"rows\": [\n", f);
    for (int i = 0; i < s->nrows; i++) {
        const tb_stab_row *r = &s->rows[i];
        fputs("    {\"id\": ", f); base_json_str(f, r->id);
        fputs(", \"method\": ", f); base_json_str(f, r->method);
        fputs(",\n     \"condition\": ", f); base_json_str(f, r->condition);
        fputs(",\n     \"measured\": ", f); base_json_str(f, r->measured);
        fputs(",\n     \"verdict\": ", f); base_json_str(f, r->verdict);
        fputs(",\n     \"boundary\": ", f);
        base_json_num(f, r->boundary, 10);
        fprintf(f, "}%s\n", i + 1 < s->nrows ? "," : "");
    }
    fputs("  ],\n  \"charts\": [", f);
    for (int i = 0; i < np; i++) { fputs(i ? ", " : "", f); base_json_str(f, paths[i]); }
    fputs("]\n}\n", f);
}

typedef struct stability_args { int json; const char *dir; } stability_args;

static const cli_opt stability_tab[] = {
    { "--json", NULL, CLI_OPT_FLAG, offsetof(stability_args, json), 0, 0, NULL, NULL, NULL, 0,
      "  --json     one JSON object instead of the table\n" },
    { "-o", NULL, CLI_OPT_STR, offsetof(stability_args, dir), 0, 0, NULL, "stability: -o needs a folder", NULL,
      CLI_OPT_NONEMPTY,
      "  -o DIR     also write the charts into DIR (made if missing), each marking\n"
      "             its boundary: stability_fwd.svg, stability_fwd_err.svg,\n"
      "             stability_coef.svg, stability_overshoot.svg,\n"
      "             stability_degree.svg, stability_div3.svg,\n"
      "             stability_brdf_d.svg, stability_brdf_schlick.svg,\n"
      "             stability_pow.svg\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_stability_spec = {
    "stability", { stability_tab }, NULL, 0, "stability: unknown argument '%s' (see shadesim stability --help)",
    "usage: shadesim stability [--json] [-o DIR]\n\n"
    "The stability atlas: each method driven past the point where it stops\n"
    "working, one row per failure boundary, as \"method | condition | measured |\n"
    "verdict\". The boundaries are found by running the units clock by clock:\n"
    "forward differencing (register bits against interval length), the\n"
    "coefficient networks' integer ranges (and what wrap and sat do one bit\n"
    "short), cubic overshoot on narrow highlights (and an output clamp's cost),\n"
    "degree 1, 2 and 3 against the adaptive policy's curvature measure, the /3\n"
    "network's terms against width, the restoring divider and the power units;\n"
    "the BRDF approximations' parameter ranges come from their double\n"
    "references sampled densely. Targets: 2^-8 (one LSB of an 8-bit intensity)\n"
    "unless a row says otherwise. The same bytes on every run (no timings);\n"
    "docs/stability.md explains each boundary.\n\noptions:\n",
    "\n"
    "exit status: 0 done (a boundary is a finding, not an error), 2 bad usage,\n"
    "an unwritable DIR or a unit that failed to run\n"
};

int cli_stability(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_stability_spec);
    stability_args sa = { 0, NULL };
    void *base[] = { &sa };
    if (cli_opt_parse(&cli_stability_spec, base, argc, argv, 1)) return CLI_USAGE;
    int json = sa.json;
    const char *dir = sa.dir;
    tb_stab *s = calloc(1, sizeof *s);
    if (!s) base_out_of_memory();
    char err[300];
    if (tb_stability(s, dir != NULL, err, sizeof err)) {
        tb_stab_free(s);
        free(s);
        return cli_usage_error("%s", err);
    }
    char paths[TB_STAB_MAX_CHARTS][600];
    int np = 0, rc = CLI_OK;
    if (dir) rc = write_charts(s, dir, paths, &np);
    if (rc == CLI_OK) {
        if (json) print_json(stdout, s, paths, np);
        else print_text(stdout, s, paths, np);
        if (base_out_stdout_check(err, sizeof err)) rc = cli_usage_error("stability: %s", err);
    }
    tb_stab_free(s);
    free(s);
    return rc;
}
