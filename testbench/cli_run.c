/* cli_run.c - the verbs that read the unit descriptors: list, vectors, run. */
#include "testbench/cli.h"
#include "base/base_join.h"
#include "testbench/cli_opt.h"
#include "testbench/tb_stream.h"
#include "testbench/tb_wave.h"
#include "testbench/tb_widths.h"
#include "vectors/vec_file.h"
#include "base/base_out.h"
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* Results went to stdout: a write error there (full disk, closed pipe)
 * must not pass as success. Every verb returns through this. */
static int stdout_done(int rc)
{
    char e[300];
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return rc;
}

/* ------------------------------------------------------------------- list */

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
    fprintf(f, "%s — %s\n  from %s\n  schedules:", u->name, u->summary, u->seed);
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
    fprintf(f, "## %s\n\n%s. From %s.\n\n", u->name, u->summary, u->seed);
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
    if (only && !unit_find(only)) return cli_usage_error("unknown unit '%s'", only);
    int si = -1;
    if (sched) {
        if (!only) return cli_usage_error("list: --schedule %s needs a unit (shadesim list UNIT --schedule NAME)", sched);
        si = unit_sched_find(unit_find(only), sched);
        if (si < 0) return cli_unit_sched_error(unit_find(only), sched);
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
    return stdout_done(CLI_OK);
}

/* ---------------------------------------------------------------- vectors */

typedef struct vectors_args {
    cli_unit_opts o;        /* the unit, and --param once it is chosen */
    const char *unit, *out;
    long n;
    uint64_t seed;
} vectors_args;

static int vectors_unit_arg(void *base, const char *arg)
{
    vectors_args *va = base;
    if (va->unit) return CLI_OPT_UNKNOWN;
    va->unit = arg;
    return cli_unit_select(&va->o, arg);
}

static const cli_opt vectors_tab[] = {
    { "-n", NULL, CLI_OPT_LONG, offsetof(vectors_args, n), 0, 10000000, NULL, NULL, NULL, 0, NULL },
    { "--seed", NULL, CLI_OPT_U64, offsetof(vectors_args, seed), 0, 0, NULL, NULL, NULL, 0, NULL },
    { "-o", NULL, CLI_OPT_STR, offsetof(vectors_args, out), 0, 0, NULL, "-o needs a FILE", NULL, 0, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};
static const cli_opt vectors_param_tab[] = {
    { "--param", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, cli_unit_param, 0, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_vectors_spec = {
    "vectors", { vectors_tab, vectors_param_tab }, vectors_unit_arg, 0,
    "vectors: unexpected argument '%s' (see shadesim vectors --help)",
    "usage: shadesim vectors UNIT [-n N] [--seed S] [--param NAME=VALUE ...] [-o FILE]\n\n"
    "Golden vectors for UNIT from the double-precision float reference, in the\n"
    "text vector format (stdout, or FILE written atomically). With the default\n"
    "N (0: the unit's default set) and seed 1 this is the checked-in\n"
    "vectors/UNIT.vec.\n\n"
    "-o FILE: a regular file is replaced only once complete (a symbolic link is\n"
    "followed and kept); a device or FIFO is written to in place; -o - is stdout.\n", NULL
};

int cli_vectors(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_vectors_spec);
    vectors_args va;
    memset(&va, 0, sizeof va);
    va.seed = 1;
    void *base[] = { &va, &va.o };
    if (cli_opt_parse(&cli_vectors_spec, base, argc, argv, 1)) return CLI_USAGE;
    cli_unit_opts o = va.o;
    const char *unit = va.unit, *out = va.out;
    long n = va.n;
    uint64_t seed = va.seed;
    if (!unit) return cli_usage_error("vectors: which unit? (shadesim list)");
    vec_set vs;
    char err[600];
    if (cli_make_vectors(o.u, &o.cfg, (size_t)n, seed, &vs, err, sizeof err)) return cli_usage_error("%s", err);
    int rc = CLI_OK;
    /* "-" (and no -o) is stdout, checked for write errors like a file. */
    if (vec_file_write(out ? out : "-", &vs, err, sizeof err)) rc = cli_usage_error("%s", err);
    vec_set_free(&vs);
    return rc == CLI_OK ? stdout_done(rc) : rc;
}

/* -------------------------------------------------------------------- run */

typedef struct run_args {
    const char *vcd, *csv;
    int json, fst, ranges;
    long vfrom, vto;
} run_args;

#define ACC_OPT(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_REAL, offsetof(tb_accept, FIELD), 0, 1e300, \
    "a positive number", "%s needs a number", NULL, CLI_OPT_GT_LO, HELP }
/* The acceptance options (run UNIT and run all). */
static const cli_opt accept_tab[] = {
    ACC_OPT("--max-error", max_error, "  --max-error E        target: max |hardware - expected| <= E\n"),
    ACC_OPT("--max-nmse", max_nmse, "  --max-nmse X         target: NMSE against the expected outputs <= X\n"),
    ACC_OPT("--max-lsb", max_lsb, "  --max-lsb K          target: max |hardware - expected| <= K output LSBs\n"),
    { "--allow-overflow", NULL, CLI_OPT_FLAG, offsetof(tb_accept, allow_overflow), 0, 0, NULL, NULL, NULL, 0,
      "  --allow-overflow     an overflow does not fail the verdict (it is still reported)\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

#define VCD_ITEM(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_LONG, offsetof(run_args, FIELD), 0, (double)LONG_MAX, \
    "an item number (0, 1, ...)", "%s needs an item number", NULL, 0, HELP }
static const cli_opt run_tab[] = {
    { "--ranges", NULL, CLI_OPT_FLAG, offsetof(run_args, ranges), 0, 0, NULL, NULL, NULL, 0,
      "  --ranges             list every signal's observed raw range, not only those that overflowed\n" },
    { "--json", NULL, CLI_OPT_FLAG, offsetof(run_args, json), 0, 0, NULL, NULL, NULL, 0,
      "  --json               print the result as one JSON object\n" },
    { "--out", NULL, CLI_OPT_STR, offsetof(run_args, csv), 0, 0, NULL, "%s needs a file name", NULL, 0,
      "  --out FILE.csv       one row per vector: index, cycle, NAME_raw/_real/_expected/_err\n" },
    { "--vcd", NULL, CLI_OPT_STR, offsetof(run_args, vcd), 0, 0, NULL, "%s needs a file name", NULL, 0,
      "  --vcd FILE           dump every register, mux, adder and multiplier (IEEE 1364 VCD)\n"
      "                       and each output beat's expected value and error (tb.expected_NAME,\n"
      "                       tb.err_NAME), with FILE.gtkw, a GTKWave save file: a group of the\n"
      "                       outputs with their expected values and errors, then one per unit,\n"
      "                       values in fixed point (docs/vcd.md)\n" },
    VCD_ITEM("--vcd-from", vfrom,
      "  --vcd-from N, --vcd-to M  dump only items N..M (from 0, as --out's index): from the\n"
      "                       edge where item N is offered to the one that samples M's last beat\n"),
    VCD_ITEM("--vcd-to", vto, ""),
    { "--fst", NULL, CLI_OPT_FLAG, offsetof(run_args, fst), 0, 0, NULL, NULL, NULL, 0,
      "  --fst                FILE is an FST dump (GTKWave's compact format), converted by\n"
      "                       vcd2fst (Debian package gtkwave)\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_run_spec = {
    "run", { cli_unit_opt_tab, accept_tab, run_tab }, NULL, 0,
    "run: unknown option '%s' (see shadesim run --help)",
    "usage: shadesim run UNIT [options]\n"
    "       shadesim run all [acceptance options]   every unit on its default vectors, one summary table\n\n"
    "Drives UNIT clock by clock with golden vectors (inputs quantized to the unit's\n"
    "input formats with --round), reports cycles, area, quantization error and\n"
    "every signal's overflows, and gives a verdict (docs/bounds.md). Exit 0 when\n"
    "the verdict is ok: no signal overflowed, every output is within the error\n"
    "bound derived from the formats (checked exactly against the unit's ideal\n"
    "function of the quantized inputs), the golden check against the vector\n"
    "file's expected outputs holds, and your targets, if set, are met. Exit 1\n"
    "otherwise, also when the bound cannot be decided (\"unchecked\") or the unit\n"
    "derives none for the formats (\"no bound\").\n\noptions:\n",
    "\nOutput files: a regular file is replaced only once complete (a symbolic link is\n"
    "followed and kept); a device or FIFO is written to in place. --out - or --vcd -\n"
    "writes that file to stdout (no .gtkw then) and the report goes to stderr; only\n"
    "one of --out -, --vcd - and --json can have stdout.\n"
};

/* run all: the acceptance options only. */
static const cli_optspec run_all_spec = {
    "run all", { accept_tab }, NULL, 0,
    "run all: unknown option '%s' (it takes --max-error, --max-nmse, --max-lsb, --allow-overflow)", NULL, NULL
};

static int run_all(const tb_accept *acc)
{
    int target = acc->max_error > 0 || acc->max_nmse > 0 || acc->max_lsb > 0;
    printf("%-11s %-9s %6s %12s %12s %12s %10s %-9s %-8s %s\n", "unit", "schedule", "width", "clocks/item",
           "max|e|", "nmse", "area GE", "bound", "golden", target ? "target" : "method error");
    int rc = CLI_OK, bad = 0, missed = 0;
    char far[400] = "";
    for (size_t i = 0, n = unit_count(); i < n; i++) {
        cli_unit_opts o;
        cli_unit_select(&o, unit_at(i)->name);
        vec_set vs;
        if (cli_load_vectors(&o, &vs)) { rc = CLI_USAGE; continue; }
        unit_fmts fm;
        char err[600];
        tb_result r;
        tb_formats(o.u, &o.cfg, NULL, 0, &fm, err, sizeof err);
        int t = tb_run(o.u, &o.cfg, &fm, &vs, NULL, &r, err, sizeof err);
        if (t != TB_OK) {
            (void)cli_usage_error("%s: %s", o.u->name, err);
            rc = t == TB_BADINPUT ? CLI_USAGE : CLI_FAIL;
        } else {
            tb_verdict(&r, acc);
            double me = 0;
            for (int k = 0; k < r.n_out; k++) if (r.out[k].max_method_err > me) me = r.out[k].max_method_err;
            if (me > 1e-3 && strlen(far) < sizeof far - 40)
                snprintf(far + strlen(far), sizeof far - strlen(far), " %s (%.3g)", o.u->name, me);
            const char *bc = r.overflows && !acc->allow_overflow ? "OVERFLOW" : r.bound_check == TB_CHECK_OK ? "ok"
                           : r.bound_check == TB_CHECK_EXCEEDED ? "EXCEEDED" : r.bound_check == TB_CHECK_NO_BOUND ? "NO BOUND" : "UNCHECKED";
            char last[32];
            if (target) snprintf(last, sizeof last, "%s", r.target_met ? "met" : "MISSED");
            else snprintf(last, sizeof last, "%.3g", me);
            printf("%-11s %-9s %6d %12.4g %12.4g %12.4g %10.1f %-9s %-8s %s\n", o.u->name, o.u->sched[o.cfg.schedule].name,
                   o.cfg.width, r.cycles_per_item, isnan(r.max_abs_err) ? NAN : r.max_abs_err,
                   isnan(r.nmse) ? NAN : r.nmse, r.area_ge, bc, r.golden_ok ? "ok" : "EXCEEDED", last);
            if (!r.ok) {
                if (r.target_set && !r.target_met && r.within_bound && r.golden_ok) missed++;
                else bad++;
                if (rc == CLI_OK) rc = CLI_FAIL;
            }
        }
        tb_result_free(&r);
        vec_set_free(&vs);
    }
    printf("\nbound ok: no overflow and every output within the bound derived from its formats, checked\n"
           "against the unit's ideal function (exactly; units whose ideal is only a double: to 2^-40\n"
           "relative, else \"unchecked\"); golden ok: within that bound plus input rounding\n"
           "plus the method's own approximation of the true function. max|e| is against the true\n"
           "function: a unit can be within its bound and far from it (interp3's 3-term 1/3).\n%s\n",
           target ? "target: your --max-error / --max-nmse / --max-lsb." :
           "method error: how far the unit's ideal is from the true function; no target set\n"
           "(--max-error, --max-nmse, --max-lsb make a miss fail the run).");
    if (bad) printf("summary: %d unit(s) fail the derived-bound or golden check\n", bad);
    else printf("summary: every unit within its derived bound and golden check\n");
    if (far[0]) printf("summary: within their bound but far from the true function (method error > 1e-3):%s\n", far);
    if (target) printf("summary: %s\n", missed ? "some units MISS your target" : "every unit meets your target");
    return stdout_done(rc);
}

static void csv_row(void *data, const tb_result *r, size_t idx, uint64_t cycle, const int64_t *raw,
                    const double *expected)
{
    tb_csv_row(base_out_file(data), r, idx, cycle, raw, expected);
}

/* run UNIT on a vector file, streamed (tb_run_stream): the same report,
 * --out rows written as items complete. The header and first rows are
 * read first, so a bad file is reported before anything is written. */
static int run_streamed(const cli_unit_opts *o, const unit_fmts *fm, const char *path, const char *csv,
                        int json, int ranges, FILE *report, const tb_accept *acc)
{
    char err[600];
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(o->u, &o->cfg, &hdr);
    vec_stream *vs = vec_stream_open(path, &hdr, err, sizeof err);
    if (!vs) return cli_usage_error("%s", err);
    const vec_set *rows;
    if (vec_stream_next(vs, &rows) < 0) {
        cli_usage_error("%s", vec_stream_error(vs));
        vec_stream_close(vs);
        return CLI_USAGE;
    }
    vec_stream_unread(vs);
    base_out *out = NULL;
    if (csv) {
        out = base_out_open(csv, err, sizeof err);
        if (!out) { vec_stream_close(vs); return cli_usage_error("%s", err); }
        tb_csv_header(base_out_file(out), rows->n_out, (const char (*)[16])rows->out_names);
    }
    tb_result r;
    int t = tb_run_stream(o->u, &o->cfg, fm, vs, csv ? csv_row : NULL, out, &r, err, sizeof err);
    vec_stream_close(vs);
    int rc = CLI_OK;
    if (t != TB_OK) {
        if (out) base_out_abort(out);
        rc = cli_usage_error("%s", err);
        if (t == TB_FAIL) rc = CLI_FAIL;
    } else {
        if (out && base_out_close(out, err, sizeof err)) rc = cli_usage_error("%s", err);
        tb_verdict(&r, acc);
        if (json) tb_write_json(stdout, &r);
        else {
            tb_print_table(report, &r);
            if (ranges) tb_print_ranges(report, &r, 1);
        }
        if (rc == CLI_OK && !r.ok) rc = CLI_FAIL;
    }
    tb_result_free(&r);
    return rc == CLI_USAGE ? rc : stdout_done(rc);
}

int cli_run(int argc, char **argv)
{
    cli_unit_opts o;
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_run_spec);
    if (argc < 2 || argv[1][0] == '-') return cli_usage_error("run: which unit? (shadesim list, or run all)");
    const char *unit = argv[1];
    tb_accept acc;
    memset(&acc, 0, sizeof acc);
    if (!strcmp(unit, "all")) {
        void *base[] = { &acc };
        if (cli_opt_parse(&run_all_spec, base, argc, argv, 2)) return CLI_USAGE;
        return run_all(&acc);
    }
    if (cli_unit_select(&o, unit)) return CLI_USAGE;
    run_args ra = { NULL, NULL, 0, 0, 0, -1, -1 };
    void *base[] = { &o, &acc, &ra };
    if (cli_opt_parse(&cli_run_spec, base, argc, argv, 2)) return CLI_USAGE;
    const char *vcd = ra.vcd, *csv = ra.csv;
    int json = ra.json, fst = ra.fst, ranges = ra.ranges;
    long long vfrom = ra.vfrom, vto = ra.vto;
    /* "-" is stdout for each output option; stdout holds one stream. */
    int vcd_out = vcd && !strcmp(vcd, "-"), csv_out = csv && !strcmp(csv, "-");
    if (vcd_out + csv_out + json > 1)
        return cli_usage_error("run: only one of --out -, --vcd - and --json can write to stdout");
    if ((vfrom >= 0 || vto >= 0 || fst) && !vcd)
        return cli_usage_error("run: %s needs --vcd FILE", fst ? "--fst" : vfrom >= 0 ? "--vcd-from" : "--vcd-to");
    if (vfrom >= 0 && vto >= 0 && vfrom > vto)
        return cli_usage_error("run: --vcd-from %lld is after --vcd-to %lld", vfrom, vto);
    if (fst && vcd_out) return cli_usage_error("run: --fst needs a file, not --vcd -");
    if (fst && !tb_wave_have_vcd2fst())
        return cli_usage_error("run: --fst needs vcd2fst, which is not installed (Debian package gtkwave)");
    FILE *report = vcd_out || csv_out ? stderr : stdout;
    unit_fmts fm;
    char err[600];
    if (tb_formats(o.u, &o.cfg, o.fmt, o.nfmt, &fm, err, sizeof err)) return cli_usage_error("%s", err);
    if (!o.nfmt) {
        /* Past the top of the unit's range the build would refuse with a
         * hint about one signal; say the range instead (shadesim list). */
        int wmax = tb_width_max(o.u, &o.cfg, err, sizeof err);
        if (o.cfg.width > wmax)
            return cli_usage_error("--width %d: unit %s builds with its default formats at widths %d..%d only (%s)",
                                   o.cfg.width, o.u->name, unit_min_width(o.u, &o.cfg, NULL), wmax, err);
    }
    /* Without a dump, a vector file is read a block at a time: memory
     * does not grow with the number of vectors. */
    char vpath[4200];
    const char *vfile = NULL;
    if (!vcd) {
        int f = cli_vectors_file(&o, vpath, sizeof vpath, &vfile);
        if (f < 0) return CLI_USAGE;
        if (f) return run_streamed(&o, &fm, vfile, csv, json, ranges, report, &acc);
    }
    vec_set vs;
    if (cli_load_vectors(&o, &vs)) return CLI_USAGE;
    tb_opts opts = { .vcd_path = vcd, .gtkw = !vcd_out, .fst = fst };
    if (vfrom >= 0 || vto >= 0) {
        int bad_from = vfrom >= 0 && (size_t)vfrom >= vs.n_rows;
        if (bad_from || (vto >= 0 && (size_t)vto >= vs.n_rows)) {
            size_t n = vs.n_rows;
            vec_set_free(&vs);
            return cli_usage_error("run: --vcd-%s %lld: the vectors have %zu items (0..%zu)", bad_from ? "from" : "to",
                                   bad_from ? vfrom : vto, n, n ? n - 1 : 0);
        }
        opts.vcd_window = 1;
        opts.vcd_from = vfrom >= 0 ? (size_t)vfrom : 0;
        opts.vcd_to = vto >= 0 ? (size_t)vto : vs.n_rows - 1;
    }
    tb_result r;
    int t = tb_run(o.u, &o.cfg, &fm, &vs, &opts, &r, err, sizeof err);
    int rc = CLI_OK;
    if (t != TB_OK) {
        /* The vectors' header was checked when they were read, so this is
         * about the unit (formats it cannot build with) or an output file. */
        rc = cli_usage_error("%s", err);
        if (t == TB_FAIL) rc = CLI_FAIL;
    } else {
        if (csv && tb_write_csv(csv, &r, &vs, err, sizeof err)) rc = cli_usage_error("%s", err);
        tb_verdict(&r, &acc);
        if (json) tb_write_json(stdout, &r);
        else {
            tb_print_table(report, &r);
            if (ranges) tb_print_ranges(report, &r, 1);
        }
        if (rc == CLI_OK && !r.ok) rc = CLI_FAIL;
    }
    tb_result_free(&r);
    vec_set_free(&vs);
    return rc == CLI_USAGE ? rc : stdout_done(rc);
}
