/* cli_verilog.c - the verbs from simulation to RTL: verilog (export),
 * cosim (the export against shadesim in Icarus Verilog or Verilator,
 * every output raw and its cycle), synth (Yosys cell counts beside the
 * area model). */
#include "testbench/cli.h"
#include "testbench/tb_verilog.h"
#include "base/base_out.h"
#include "sim/sim_area.h"
#include <stdlib.h>
#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int is_help(const char *a) { return !strcmp(a, "--help") || !strcmp(a, "-h"); }

static int stdout_done(int rc)
{
    char e[300];
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return rc;
}

static int have_tool(const char *tool)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* Shared parsing: UNIT, the unit options, and the verb's own options
 * (handled by own(); returns 1 consumed, 0 not ours, -1 error). */
typedef int (*own_fn)(void *st, int argc, char **argv, int *i);
static int parse(const char *verb, int argc, char **argv, cli_unit_opts *o, own_fn own, void *st)
{
    int have = 0;
    for (int i = 1; i < argc; i++) {
        if (!have && argv[i][0] != '-') {
            if (cli_unit_select(o, argv[i])) return CLI_USAGE;
            have = 1;
            continue;
        }
        int r = own ? own(st, argc, argv, &i) : 0;
        if (r < 0) return CLI_USAGE;
        if (r) continue;
        if (have) {
            r = cli_unit_option(o, argc, argv, &i);
            if (r < 0) return CLI_USAGE;
            if (r) continue;
        }
        return cli_usage_error("%s: unexpected argument '%s' (see shadesim %s --help)", verb, argv[i], verb);
    }
    if (!have) return cli_usage_error("%s: no unit given (shadesim list shows the units)", verb);
    return CLI_OK;
}

static int formats(cli_unit_opts *o, unit_fmts *fm)
{
    char err[600];
    if (tb_formats(o->u, &o->cfg, o->fmt, o->nfmt, fm, err, sizeof err)) return cli_usage_error("%s", err);
    return CLI_OK;
}

/* ----------------------------------------------------------------- verilog */

static const char verilog_help[] =
    "usage: shadesim verilog UNIT [options] -o DIR\n"
    "Write DIR/UNIT.v, synthesizable Verilog-2001 of the unit exactly as shadesim\n"
    "builds it (same formats, rounding, overflow, schedule and handshake), and\n"
    "DIR/UNIT_tb.v, a testbench that reads the stimulus (--stimulus-hex) with\n"
    "$readmemh and writes each output beat with its cycle.\n"
    "options:\n"
    "  -o DIR               output folder (made if missing)\n"
    "  --stimulus-hex FILE  also write the stimulus of the vectors (--vectors, or the\n"
    "                       unit's default ones) to FILE and shadesim's results to\n"
    "                       FILE.expect, what the testbench must write:\n"
    "                       vvp -n tb.vvp +in=FILE +items=N +out=OUT && diff FILE.expect OUT\n";

typedef struct verilog_st { const char *dir, *hex; } verilog_st;
static int own_o(void *stp, int argc, char **argv, int *i)
{
    verilog_st *st = stp;
    int o = !strcmp(argv[*i], "-o"), h = !strcmp(argv[*i], "--stimulus-hex");
    if (!o && !h) return 0;
    if (*i + 1 >= argc) { cli_usage_error("%s needs a %s", argv[*i], o ? "folder" : "file"); return -1; }
    if (o) st->dir = argv[++*i]; else st->hex = argv[++*i];
    return 1;
}

int cli_verilog(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (is_help(argv[i])) { fputs(verilog_help, stdout); fputs(cli_unit_opts_help, stdout); return stdout_done(CLI_OK); }
    cli_unit_opts o;
    verilog_st st = { NULL, NULL };
    int rc = parse("verilog", argc, argv, &o, own_o, &st);
    if (rc) return rc;
    if (!st.dir) return cli_usage_error("verilog: -o DIR is required");
    unit_fmts fm;
    if (formats(&o, &fm)) return CLI_USAGE;
    char err[600];
    if (tb_verilog_export(o.u, &o.cfg, &fm, st.dir, err, sizeof err)) return cli_usage_error("%s", err);
    if (st.hex) {
        vec_set vs;
        if (cli_load_vectors(&o, &vs)) return CLI_USAGE;
        tb_result r;
        int t = tb_run(o.u, &o.cfg, &fm, &vs, NULL, &r, err, sizeof err);
        if (t != TB_OK) { vec_set_free(&vs); return t == TB_BADINPUT ? cli_usage_error("%s", err) : (fprintf(stderr, "shadesim: %s\n", err), CLI_FAIL); }
        size_t pl = strlen(st.hex) + 8;
        char *ex = malloc(pl);
        if (!ex) rc = cli_usage_error("out of memory");
        else {
            snprintf(ex, pl, "%s.expect", st.hex);
            if (tb_stimulus_write(o.u, &o.cfg, &fm, &vs, &r, st.hex, ex, err, sizeof err)) rc = cli_usage_error("%s", err);
            else if (cli_stderr_tty()) fprintf(stderr, "%zu items: +items=%zu\n", vs.n_rows, vs.n_rows);
        }
        free(ex);
        tb_result_free(&r);
        vec_set_free(&vs);
    }
    return stdout_done(rc);
}

/* ------------------------------------------------------------------- cosim */

static const char cosim_help[] =
    "usage: shadesim cosim UNIT [options] [--sim icarus|verilator] [-n N] [--keep DIR]\n"
    "Export the unit (as `shadesim verilog`), run the same stimulus in shadesim and in\n"
    "the external simulator, and compare every output raw and the cycle of every beat.\n"
    "Prints \"bit-exact, N items, M clocks\" or the first mismatch; exit 1 on a mismatch.\n"
    "options:\n"
    "  --sim NAME           icarus (default; Debian package iverilog) or verilator\n"
    "  -n N                 items (default 50), generated from the float reference,\n"
    "                       unless --vectors FILE is given\n"
    "  --seed S             seed of the generated items (default 1)\n"
    "  --keep DIR           leave the export, stimulus and results in DIR\n";

typedef struct cosim_st { const char *sim, *keep; long n; unsigned long long seed; } cosim_st;

static int own_cosim(void *stp, int argc, char **argv, int *i)
{
    cosim_st *st = stp;
    const char *a = argv[*i];
    if (strcmp(a, "--sim") && strcmp(a, "-n") && strcmp(a, "--keep") && strcmp(a, "--seed")) return 0;
    if (*i + 1 >= argc) { cli_usage_error("%s needs a value", a); return -1; }
    const char *v = argv[++*i];
    if (!strcmp(a, "--sim")) {
        if (strcmp(v, "icarus") && strcmp(v, "verilator")) { cli_usage_error("--sim %s: expected icarus or verilator", v); return -1; }
        st->sim = v;
    } else if (!strcmp(a, "--keep")) st->keep = v;
    else {
        char *end;
        errno = 0;
        unsigned long long x = strtoull(v, &end, 10);
        if (!*v || *end || strspn(v, "0123456789") != strlen(v) || errno || (a[1] == 'n' && (x < 1 || x > 1000000))) {
            cli_usage_error("%s %s: expected a whole number%s", a, v, a[1] == 'n' ? " 1..1000000" : "");
            return -1;
        }
        if (a[1] == 'n') st->n = (long)x; else st->seed = x;
    }
    return 1;
}

/* Remove a folder we made and the files in it. */
static void rm_tree(const char *dir)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) { /* a temporary left behind is harmless */ }
}

int cli_cosim(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (is_help(argv[i])) { fputs(cosim_help, stdout); fputs(cli_unit_opts_help, stdout); return stdout_done(CLI_OK); }
    cli_unit_opts o;
    cosim_st st = { "icarus", NULL, 50, 1 };
    int rc = parse("cosim", argc, argv, &o, own_cosim, &st);
    if (rc) return rc;
    int icarus = !strcmp(st.sim, "icarus");
    if (icarus && (!have_tool("iverilog") || !have_tool("vvp")))
        return cli_usage_error("cosim: iverilog not found (install the Debian package iverilog)");
    if (!icarus && !have_tool("verilator"))
        return cli_usage_error("cosim: verilator not found (install the Debian package verilator)");
    unit_fmts fm;
    if (formats(&o, &fm)) return CLI_USAGE;
    char err[600];
    vec_set vs;
    if (o.vectors) { if (cli_load_vectors(&o, &vs)) return CLI_USAGE; }
    else if (cli_make_vectors(o.u, &o.cfg, (size_t)st.n, st.seed, &vs, err, sizeof err)) return cli_usage_error("%s", err);
    char tmpl[] = "/tmp/shadesim_cosim_XXXXXX";
    const char *dir = st.keep;
    if (!dir && !mkdtemp(tmpl)) { vec_set_free(&vs); return cli_usage_error("cosim: cannot make a temporary folder"); }
    if (!dir) dir = tmpl;
    char msg[1200];
    int t = tb_cosim(o.u, &o.cfg, &fm, &vs, icarus ? TB_SIM_ICARUS : TB_SIM_VERILATOR, dir, msg, sizeof msg);
    if (t == TB_COSIM_EXACT) { printf("%s\n", msg); rc = CLI_OK; }
    else if (t == TB_COSIM_MISMATCH) { printf("%s\n", msg); rc = CLI_FAIL; }
    else if (t == TB_COSIM_BADINPUT) rc = cli_usage_error("%s", msg);
    else { fprintf(stderr, "shadesim: %s\n", msg); rc = CLI_FAIL; }
    vec_set_free(&vs);
    if (!st.keep) rm_tree(dir);
    return stdout_done(rc);
}

/* ------------------------------------------------------------------- synth */

static const char synth_help[] =
    "usage: shadesim synth UNIT [options] [--keep DIR]\n"
    "Export the unit and synthesize it with Yosys to generic gates (synth; abc -g\n"
    "AND,NAND,OR,NOR,XOR,XNOR,MUX; no cell library): prints Yosys's cells by type\n"
    "and in total, weighted with the area model's NAND2 gate equivalents per gate,\n"
    "beside shadesim's area estimate.\n"
    "Needs yosys (Debian package yosys).\n"
    "options:\n"
    "  --keep DIR           leave the export and Yosys's log in DIR\n";

/* A Yosys generic cell in NAND2 gate equivalents, with the constants of
 * sim/sim_area.h (NanGate 45 nm): flip-flops with an enable add a MUX2,
 * with a synchronous reset an AND2. */
static double cell_ge(const char *c)
{
    if (!strncmp(c, "NAND", 4) || !strncmp(c, "NOR", 3)) return SIM_GE_NAND2;
    if (!strncmp(c, "NOT", 3)) return SIM_GE_INV;
    if (!strncmp(c, "AND", 3) || !strncmp(c, "OR", 2)) return SIM_GE_AND2;
    if (!strncmp(c, "XOR", 3) || !strncmp(c, "XNOR", 4)) return SIM_GE_XOR2;
    if (!strncmp(c, "MUX", 3)) return SIM_GE_MUX2;
    if (strstr(c, "DFF")) {
        double g = SIM_GE_DFF;
        if (c[0] == 'S') g += SIM_GE_AND2;
        if (strstr(c, "DFFE") || strstr(c, "DFFCE")) g += SIM_GE_MUX2;
        return g;
    }
    return SIM_GE_NAND2;
}

static int own_keep(void *stp, int argc, char **argv, int *i)
{
    const char **keep = stp;
    if (strcmp(argv[*i], "--keep")) return 0;
    if (*i + 1 >= argc) { cli_usage_error("--keep needs a folder"); return -1; }
    *keep = argv[++*i];
    return 1;
}

int cli_synth(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (is_help(argv[i])) { fputs(synth_help, stdout); fputs(cli_unit_opts_help, stdout); return stdout_done(CLI_OK); }
    cli_unit_opts o;
    const char *keep = NULL;
    int rc = parse("synth", argc, argv, &o, own_keep, &keep);
    if (rc) return rc;
    if (!have_tool("yosys")) return cli_usage_error("synth: yosys not found (install the Debian package yosys)");
    unit_fmts fm;
    if (formats(&o, &fm)) return CLI_USAGE;
    char err[600];
    double ge = tb_verilog_area(o.u, &o.cfg, &fm, err, sizeof err);
    if (ge < 0) return cli_usage_error("%s", err);
    char tmpl[] = "/tmp/shadesim_synth_XXXXXX";
    const char *dir = keep;
    if (!dir && !mkdtemp(tmpl)) return cli_usage_error("synth: cannot make a temporary folder");
    if (!dir) dir = tmpl;
    if (tb_verilog_export(o.u, &o.cfg, &fm, dir, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    size_t cl = 3 * strlen(dir) + 512;
    char *cmd = malloc(cl);
    if (!cmd) { rc = cli_usage_error("out of memory"); goto done; }
    snprintf(cmd, cl, "cd '%s' && yosys -q -p 'read_verilog %s.v; synth -top %s; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX; "
             "opt_clean; tee -o stat.txt stat' >yosys.log 2>&1", dir, o.u->name, o.u->name);
    int sr = system(cmd);
    free(cmd);
    if (sr != 0) { fprintf(stderr, "shadesim: synth: yosys failed (see yosys.log: use --keep DIR)\n"); rc = CLI_FAIL; goto done; }
    char path[1200], line[300];
    snprintf(path, sizeof path, "%s/stat.txt", dir);
    FILE *f = fopen(path, "r");
    long total = -1;
    printf("%s --width %d --schedule %s (%s, %s): Yosys generic gates\n", o.u->name, o.cfg.width,
           o.u->sched[o.cfg.schedule].name, sim_round_name(o.cfg.rnd), sim_ovf_name(o.cfg.ovf));
    double yge = 0;
    while (f && fgets(line, sizeof line, f)) {
        char cell[100];
        long n;
        if (strstr(line, "Number of cells:")) total = atol(strchr(line, ':') + 1);
        else if (sscanf(line, " %99s %ld", cell, &n) == 2 && !strncmp(cell, "$_", 2)) {
            double w = cell_ge(cell + 2);
            yge += w * (double)n;
            printf("  %-12s %6ld  x %.2f GE\n", cell + 2, n, w);
        }
    }
    if (f) fclose(f);
    printf("  cells        %6ld  = %.0f GE with the area model's gate constants\n", total, yge);
    printf("  shadesim     %.0f GE (area model)\n", ge);
    if (yge > 0) printf("  ratio        %.2f (shadesim / Yosys)\n", ge / yge);
done:
    if (!keep) {
        char c2[1200];
        snprintf(c2, sizeof c2, "rm -rf '%s'", dir);
        if (system(c2)) { /* best effort */ }
    }
    return stdout_done(rc);
}
