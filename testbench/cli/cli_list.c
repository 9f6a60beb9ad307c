/* cli_list.c - `shadesim list`: the units, their signals, parameters and
 * schedules, as text or as the Markdown of docs/units.md. */
#include "testbench/cli/cli.h"
#include "base/base_join.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/tb_widths.h"
#include <stddef.h>
#include <string.h>

/* A unit's default configuration and formats at a width and schedule. */
static void defaults_at(const unit_desc *u, int width, int sched, unit_cfg *cfg, unit_fmts *fm)
{
    unit_cfg_default(u, cfg);
    cfg->width = width;
    cfg->schedule = sched;
    u->formats(cfg, fm);
}

/* 1 if the unit's schedules are different datapaths (masked signals). */
static int has_masks(const unit_desc *u)
{
    for (int i = 0; i < u->nsigs; i++) if (u->sigs[i].scheds) return 1;
    return 0;
}

/* The schedules that build signal i, "a, b" (all: "all"). */
static void sched_names(const unit_desc *u, int i, char *buf, size_t len)
{
    buf[0] = 0;
    if (!u->sigs[i].scheds) { snprintf(buf, len, "all"); return; }
    for (int s = 0; s < u->nsched; s++)
        if (unit_sig_used(u, i, s)) base_join_add(buf, len, ", ", u->sched[s].name);
}

/* Signals of schedule sched (its datapath's). */
static void list_unit(FILE *f, const unit_desc *u, int width, int sched)
{
    unit_cfg cfg;
    unit_fmts fm;
    defaults_at(u, width, sched, &cfg, &fm);
    char fb[SIM_FMT_STRLEN];
    fprintf(f, "%s — %s\n  from %s\n  schedules:", u->name, u->summary, u->source);
    for (int i = 0; i < u->nsched; i++) fprintf(f, "%s %s (%s)", i ? "," : "", u->sched[i].name, u->sched[i].what);
    fputs("\n  parameters:", f);
    if (!u->nparams) fputs(" none", f);
    for (int i = 0; i < u->nparams; i++) {
        char v[64];
        unit_param_get(&u->params[i], &cfg, v, sizeof v);
        fprintf(f, "\n    %-8s default %-8s %s", u->params[i].name, v, u->params[i].help);
        if (u->params[i].type == UNIT_P_ENUM) fprintf(f, " (%s)", u->params[i].choices);
        else fprintf(f, " (%g..%g)", u->params[i].min, u->params[i].max);
    }
    fprintf(f, "\n  default formats for --width %d: %s\n", width, u->fmt_rule);
    char why[400];
    int wmax = tb_width_max(u, &cfg, why, sizeof why);
    fprintf(f, "  --width range: %d..%d (default parameters)", unit_min_width(u, &cfg, NULL), wmax);
    if (wmax < 64) fprintf(f, "; wider, the default formats do not build: %s", why);
    fputc('\n', f);
    if (has_masks(u))
        fprintf(f, "  signals of schedule %s (list %s --schedule NAME shows another's):\n", u->sched[sched].name, u->name);
    else
        fputs("  signals:\n", f);
    static const char *const role[] = { "in", "out", "" };
    for (int i = 0; i < u->nsigs; i++)
        if (unit_sig_built(u, i, &cfg))
            fprintf(f, "    %-4s %-10s %-8s %s\n", role[u->sigs[i].role], u->sigs[i].name,
                    sim_fmt_str(fm.f[i], fb), u->sigs[i].what);
}

/* The same facts as list_unit, as the Markdown of docs/units.md. sched < 0:
 * every schedule's signals, with a column naming the schedules of each
 * where they differ. */
static void list_unit_md(FILE *f, const unit_desc *u, int width, int sched)
{
    unit_cfg cfg;
    unit_fmts fm;
    defaults_at(u, width, sched < 0 ? 0 : sched, &cfg, &fm);
    char fb[SIM_FMT_STRLEN];
    fprintf(f, "## %s\n\n%s. From %s.\n\n", u->name, u->summary, u->source);
    fputs("| schedule | what |\n| --- | --- |\n", f);
    for (int i = 0; i < u->nsched; i++) fprintf(f, "| `%s` | %s |\n", u->sched[i].name, u->sched[i].what);
    if (u->nparams) {
        fputs("\n| parameter | default | range | what |\n| --- | --- | --- | --- |\n", f);
        for (int i = 0; i < u->nparams; i++) {
            char v[64];
            unit_param_get(&u->params[i], &cfg, v, sizeof v);
            if (u->params[i].type == UNIT_P_ENUM)
                fprintf(f, "| `%s` | %s | %s | %s |\n", u->params[i].name, v, u->params[i].choices, u->params[i].help);
            else
                fprintf(f, "| `%s` | %s | %g..%g | %s |\n", u->params[i].name, v, u->params[i].min, u->params[i].max, u->params[i].help);
        }
    }
    int col = sched < 0 && has_masks(u);
    char why[400];
    int wmax = tb_width_max(u, &cfg, why, sizeof why);
    fprintf(f, "\nDefault formats from `--width W`: %s. Smallest W with the default parameters: %d "
               "(narrower, the rule could only widen some signal: docs/formats.md).", u->fmt_rule,
            unit_min_width(u, &cfg, NULL));
    if (wmax < 64) fprintf(f, " Largest W: %d (wider, the default formats do not build: %s).", wmax, why);
    fputs("\n\n", f);
    if (sched >= 0 && has_masks(u)) fprintf(f, "Signals of schedule `%s`.\n\n", u->sched[sched].name);
    fprintf(f, "| signal | role | format at W = %d | what |%s\n| --- | --- | --- | --- |%s\n",
            width, col ? " schedules |" : "", col ? " --- |" : "");
    static const char *const role[] = { "input", "output", "internal" };
    for (int i = 0; i < u->nsigs; i++) {
        if (sched >= 0 ? !unit_sig_built(u, i, &cfg) : u->sig_used && !u->sig_used(&cfg, i)) continue;
        fprintf(f, "| `%s` | %s | `%s` | %s |", u->sigs[i].name, role[u->sigs[i].role], sim_fmt_str(fm.f[i], fb), u->sigs[i].what);
        if (col) {
            char sn[120];
            sched_names(u, i, sn, sizeof sn);
            fprintf(f, " %s |", sn);
        }
        fputc('\n', f);
    }
    fputc('\n', f);
}

typedef struct list_args {
    cli_unit_opts o;        /* --width, parsed as run parses it */
    int md;
    const char *only, *sched;
} list_args;

static int list_unit_arg(void *base, const char *arg)
{
    list_args *l = base;
    if (l->only) return cli_usage_error("list: one unit at most");
    l->only = arg;
    return 0;
}

static const cli_opt list_tab[] = {
    { "--schedule", NULL, CLI_OPT_STR, offsetof(list_args, sched), 0, 0, NULL, NULL, NULL, 0, NULL },
    { "--markdown", NULL, CLI_OPT_FLAG, offsetof(list_args, md), 0, 0, NULL, NULL, NULL, 0, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};
static const cli_opt list_width_tab[] = {
    { "--width", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, cli_unit_width, 0, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_list_spec = {
    "list", { list_tab, list_width_tab }, list_unit_arg, 0, "list: unknown option '%s'",
    "usage: shadesim list [UNIT [--schedule NAME]] [--width W] [--markdown]\n\n"
    "Lists every unit (or one) with its schedules, parameters, signals and\n"
    "their default formats at width W (default 16). Where a unit's schedules\n"
    "are different datapaths, the signals are those of schedule NAME (default\n"
    "the unit's first; --markdown without --schedule: all, with a column\n"
    "naming each one's schedules). --markdown prints the same as\n"
    "docs/units.md is made of.\n", NULL
};

int cli_list(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_list_spec);
    list_args la;
    memset(&la, 0, sizeof la);
    unit_cfg_default(NULL, &la.o.cfg);     /* no unit yet: only --width is read */
    la.o.cfg.width = 16;
    void *base[] = { &la, &la.o };
    if (cli_opt_parse(&cli_list_spec, base, argc, argv, 1)) return CLI_USAGE;
    const char *only = la.only, *sched = la.sched;
    int width = la.o.cfg.width, md = la.md;
    /* a unit, or a datapath file (docs/datapaths.md) */
    cli_unit_opts file;
    const unit_desc *one = NULL;
    if (only && !(one = unit_find(only))) {
        if (cli_unit_select(&file, only)) return CLI_USAGE;
        one = file.u;
    }
    int si = -1;
    if (sched) {
        if (!only) return cli_usage_error("list: --schedule %s needs a unit (shadesim list UNIT --schedule NAME)", sched);
        si = unit_sched_find(one, sched);
        if (si < 0) return cli_unit_sched_error(one, sched);
    }
    if (one && !unit_find(only)) {
        if (md) list_unit_md(stdout, one, width, si);
        else list_unit(stdout, one, width, si < 0 ? 0 : si);
        return cli_stdout_done(CLI_OK);
    }
    if (md && !only)
        printf("# Units\n\nGenerated by `shadesim list --markdown` (`make docs`) from the unit\n"
               "descriptors the simulator itself uses; `make test` checks it is current.\n\n");
    for (size_t i = 0, n = unit_count(); i < n; i++) {
        const unit_desc *u = unit_at(i);
        if (only && strcmp(only, u->name)) continue;
        if (md) { list_unit_md(stdout, u, width, si); continue; }
        list_unit(stdout, u, width, si < 0 ? 0 : si);
        if (!only && i + 1 < n) putchar('\n');
    }
    return cli_stdout_done(CLI_OK);
}

