/* cli_verilog.c - the verbs from simulation to RTL: verilog (export),
 * cosim (the export against shadesim in Icarus Verilog or Verilator,
 * every output raw and its cycle), synth (Yosys cell counts beside the
 * area model; its --sta and --fpga flows in cli_synth.c). */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/cli/cli_synth.h"
#include "testbench/tb_verilog.h"
#include "testbench/tb_synth.h"
#include "testbench/tb_widths.h"
#include "base/base_out.h"
#include "base/base_proc.h"
#include "sim/sim_area.h"
#include <stddef.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CLI_MAX_RTL 64

static int have_tool(const char *tool)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* UNIT, the first argument that is not an option; the unit options
 * (cli_unit_opt_tab) are options once it is chosen. */
static int unit_arg(void *base, const char *arg)
{
    cli_unit_opts *o = base;
    if (o->u) return CLI_OPT_UNKNOWN;
    return cli_unit_select(o, arg);
}

/* The verb's options, then the unit's: CLI_OK or CLI_USAGE. */
static int parse(const cli_optspec *sp, int argc, char **argv, cli_unit_opts *o, void *own)
{
    memset(o, 0, sizeof *o);
    void *base[] = { o, own, o };
    if (cli_opt_parse(sp, base, argc, argv, 1)) return CLI_USAGE;
    if (!o->u) return cli_usage_error("%s: no unit given (shadesim list shows the units)", sp->verb);
    return CLI_OK;
}

static int formats(cli_unit_opts *o, unit_fmts *fm)
{
    char err[600];
    if (tb_formats(o->u, &o->cfg, o->fmt, o->nfmt, fm, err, sizeof err)) return cli_usage_error("%s", err);
    /* past the top of the range: the range, as run says it */
    if (!o->nfmt && tb_width_refuse(o->u, &o->cfg, err, sizeof err))
        return cli_usage_error("--width %d: %s", o->cfg.width, err);
    return CLI_OK;
}

/* ----------------------------------------------------------------- verilog */

/* --reset sync|async|none, into the sim_vreset that starts the verb's
 * own struct (verilog_st, cosim_st). */
static int reset_opt(void *base, const char *opt, const char *v)
{
    static const char *const names[] = { "sync", "async", "none" };
    for (int i = 0; i < 3; i++)
        if (!strcmp(v, names[i])) { *(sim_vreset *)base = (sim_vreset)i; return 0; }
    return cli_usage_error("%s %s: expected sync, async or none", opt, v);
}

#define RESET_OPT \
    { "--reset", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs sync, async or none", reset_opt, 0, \
      "  --reset KIND         the reset input rst (active high): sync (default; at a\n" \
      "                       rising edge), async (at once), or none (no rst port;\n" \
      "                       registers start from initial blocks, FPGA only)\n" }

typedef struct verilog_st { sim_vreset reset; const char *dir, *hex; } verilog_st;

static const cli_opt verilog_tab[] = {
    RESET_OPT,
    { "-o", NULL, CLI_OPT_STR, offsetof(verilog_st, dir), 0, 0, NULL, "%s needs a folder", NULL, 0,
      "  -o DIR               output folder (made if missing)\n" },
    { "--stimulus-hex", NULL, CLI_OPT_STR, offsetof(verilog_st, hex), 0, 0, NULL, "%s needs a file", NULL, 0,
      "  --stimulus-hex FILE  also write the stimulus of the vectors (--vectors, or the\n"
      "                       unit's default ones) to FILE and shadesim's results to\n"
      "                       FILE.expect, what the testbench must write:\n"
      "                       vvp -n tb.vvp +in=FILE +items=N +out=OUT && diff FILE.expect OUT\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

/* tab[0] is empty: the unit's table comes after the verb's, as the help
 * lists them, and parse() passes the unit options' base first for UNIT. */
static const cli_opt no_opts[] = { { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL } };

const cli_optspec cli_verilog_spec = {
    "verilog", { no_opts, verilog_tab, cli_unit_opt_tab }, unit_arg, 0,
    "verilog: unexpected argument '%s' (see shadesim verilog --help)",
    "usage: shadesim verilog UNIT [options] -o DIR\n"
    "Write DIR/UNIT.v, synthesizable Verilog-2001 of the unit exactly as shadesim\n"
    "builds it (same formats, rounding, overflow, schedule and handshake), with a\n"
    "reset input rst, and DIR/UNIT_tb.v, a testbench that resets it, reads the\n"
    "stimulus (--stimulus-hex) with $readmemh and writes each output beat with its\n"
    "cycle. Prints a line per file written.\n"
    "options:\n", NULL
};

int cli_verilog(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_verilog_spec);
    cli_unit_opts o;
    verilog_st st = { SIM_VRESET_SYNC, NULL, NULL };
    int rc = parse(&cli_verilog_spec, argc, argv, &o, &st);
    if (rc) return rc;
    if (!st.dir) return cli_usage_error("verilog: -o DIR is required");
    unit_fmts fm;
    if (formats(&o, &fm)) return CLI_USAGE;
    char err[600], *paths[2];
    if (tb_verilog_write(o.u, &o.cfg, &fm, st.reset, st.dir, paths, err, sizeof err)) return cli_usage_error("%s", err);
    for (int i = 0; i < 2; i++) { printf("wrote %s\n", paths[i]); free(paths[i]); }
    if (st.hex) {
        vec_set vs;
        if (cli_load_vectors(&o, &vs)) return CLI_USAGE;
        tb_result r;
        int t = tb_run(o.u, &o.cfg, &fm, &vs, NULL, &r, err, sizeof err);
        if (t != TB_OK) { vec_set_free(&vs); return cli_from_tb(t, "%s", err); }
        size_t pl = strlen(st.hex) + 8;
        char *ex = malloc(pl);
        if (!ex) base_out_of_memory();
        else {
            snprintf(ex, pl, "%s.expect", st.hex);
            if (tb_stimulus_write(o.u, &o.cfg, &fm, &vs, &r, st.hex, ex, err, sizeof err)) rc = cli_usage_error("%s", err);
            else printf("wrote %s (%zu items: +items=%zu)\nwrote %s\n", st.hex, vs.n_rows, vs.n_rows, ex);
        }
        free(ex);
        tb_result_free(&r);
        vec_set_free(&vs);
    }
    return cli_stdout_done(rc);
}

/* ------------------------------------------------------------------- cosim */

typedef struct cosim_st {
    sim_vreset reset;
    const char *sim, *keep, *top;
    long n;                 /* 0: not given */
    uint64_t seed;
    const char *rtl[CLI_MAX_RTL];
    int nrtl;
    int match_items;
    double timeout;         /* --timeout S; 0: TB_COSIM_TIMEOUT_S */
} cosim_st;

static int cosim_match(void *base, const char *opt, const char *v)
{
    if (strcmp(v, "items") && strcmp(v, "clocks")) return cli_usage_error("%s %s: expected items or clocks", opt, v);
    ((cosim_st *)base)->match_items = !strcmp(v, "items");
    return 0;
}

static int cosim_rtl(void *base, const char *opt, const char *v)
{
    cosim_st *st = base;
    if (st->nrtl == CLI_MAX_RTL) return cli_usage_error("%s %s: at most %d files", opt, v, CLI_MAX_RTL);
    st->rtl[st->nrtl++] = v;
    return 0;
}

static int cosim_sim(void *base, const char *opt, const char *v)
{
    (void)opt;
    if (strcmp(v, "icarus") && strcmp(v, "verilator")) return cli_usage_error("--sim %s: expected icarus or verilator", v);
    ((cosim_st *)base)->sim = v;
    return 0;
}

static const cli_opt cosim_tab[] = {
    { "--rtl", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs a Verilog file", cosim_rtl, CLI_OPT_NONEMPTY,
      "  --rtl FILE           your own RTL instead of the export (repeat for more\n"
      "                       files): its top module must have the export's ports\n"
      "                       and handshake (docs/verilog.md); checked on the unit's\n"
      "                       default vectors unless -n or --vectors\n" },
    { "--top", NULL, CLI_OPT_STR, offsetof(cosim_st, top), 0, 0, NULL, "%s needs a module name", NULL, CLI_OPT_NONEMPTY,
      "  --top NAME           the top module of the --rtl files (default: the only\n"
      "                       top-level one, or the one named like the unit)\n" },
    { "--match", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs items or clocks", cosim_match, 0,
      "  --match WHAT         clocks (default): every output raw and the clock of\n"
      "                       every beat as shadesim has them; items: the raws item\n"
      "                       by item in order, whatever the latency (RTL re-timed or\n"
      "                       pipelined deeper), with the RTL's latency and items per\n"
      "                       clock printed beside shadesim's\n" },
    RESET_OPT,
    { "--sim", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, cosim_sim, 0,
      "  --sim NAME           icarus (default; Debian package iverilog) or verilator\n" },
    { "-n", NULL, CLI_OPT_LONG, offsetof(cosim_st, n), 1, 1000000, NULL, NULL, NULL, 0,
      "  -n N                 items (default 50, with --rtl the unit's default\n"
      "                       vectors), generated from the float reference, unless\n"
      "                       --vectors FILE is given\n" },
    { "--seed", NULL, CLI_OPT_U64, offsetof(cosim_st, seed), 0, 0, "a whole number", NULL, NULL, 0,
      "  --seed S             seed of the generated items (default 1)\n" },
    { "--keep", NULL, CLI_OPT_STR, offsetof(cosim_st, keep), 0, 0, NULL, NULL, NULL, 0,
      "  --keep DIR           leave the export, stimulus and results in DIR\n" },
    { "--timeout", NULL, CLI_OPT_REAL, offsetof(cosim_st, timeout), 0, 1e6, "seconds above 0", NULL, NULL,
      CLI_OPT_GT_LO,
      "  --timeout S          stop the simulator (compile included) after S seconds of\n"
      "                       wall time (default 600): an RTL whose zero-delay loop\n"
      "                       never lets time advance ends there, reported; every file\n"
      "                       the tools write is capped too (64 MiB and the results')\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_cosim_spec = {
    "cosim", { no_opts, cosim_tab, cli_unit_opt_tab }, unit_arg, 0,
    "cosim: unexpected argument '%s' (see shadesim cosim --help)",
    "usage: shadesim cosim UNIT [options] [--rtl FILE.v ...] [--sim icarus|verilator] [-n N]\n"
    "Export the unit (as `shadesim verilog`), or take your own RTL (--rtl), run the\n"
    "same stimulus in shadesim and in the external simulator, and compare every\n"
    "output raw and the cycle of every beat. Prints \"bit-exact, N items, M clocks\"\n"
    "or the first mismatch (the item, its inputs, the expected and the actual raws\n"
    "and clock); exit 1 on a mismatch, 2 when the RTL's ports differ from the unit's.\n"
    "options:\n", NULL
};

int cli_cosim(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_cosim_spec);
    cli_unit_opts o;
    cosim_st st = { SIM_VRESET_SYNC, "icarus", NULL, NULL, 0, 1, { NULL }, 0, 0, 0 };
    int rc = parse(&cli_cosim_spec, argc, argv, &o, &st);
    if (rc) return rc;
    if (st.top && !st.nrtl) return cli_usage_error("cosim: --top needs --rtl FILE");
    int icarus = !strcmp(st.sim, "icarus");
    if (icarus && (!have_tool("iverilog") || !have_tool("vvp")))
        return cli_usage_error("cosim: iverilog not found (install the Debian package iverilog)");
    if (!icarus && !have_tool("verilator"))
        return cli_usage_error("cosim: verilator not found (install the Debian package verilator)");
    unit_fmts fm;
    if (formats(&o, &fm)) return CLI_USAGE;
    char err[600];
    vec_set vs;
    /* the export: 50 generated items; the user's RTL: the unit's vectors */
    if (o.vectors || (st.nrtl && !st.n)) { if (cli_load_vectors(&o, &vs)) return CLI_USAGE; }
    else if (tb_make_vectors(o.u, &o.cfg, (size_t)(st.n ? st.n : 50), st.seed, &vs, err, sizeof err)) return cli_usage_error("%s", err);
    /* From the temporary folder's making to its removal a signal is held
     * (only recorded): it ends the tool that runs, and then the folder
     * goes before shadesim dies by it. A signal's default action in
     * between had left the folder behind. */
    base_proc_hold();
    const char *tdir = getenv("TMPDIR");
    char tmpl[4200];
    snprintf(tmpl, sizeof tmpl, "%s/shadesim_cosim_XXXXXX", tdir && *tdir ? tdir : "/tmp");
    const char *dir = st.keep;
    if (!dir && !mkdtemp(tmpl)) {
        base_proc_release();
        vec_set_free(&vs);
        return cli_usage_error("cosim: cannot make a temporary folder in %s", tdir && *tdir ? tdir : "/tmp");
    }
    if (!dir) dir = tmpl;
    char msg[1200];
    tb_cosim_opts co = { st.reset, st.rtl, st.nrtl, st.top, st.match_items, st.timeout };
    int t = tb_cosim_opt(o.u, &o.cfg, &fm, &vs, &co, icarus ? TB_SIM_ICARUS : TB_SIM_VERILATOR, dir, msg, sizeof msg);
    if (base_proc_signal()) {           /* SIGINT/TERM/HUP: no verdict */
        if (!st.keep) base_proc_rmtree(dir);
        base_proc_release();
        vec_set_free(&vs);
        base_proc_reraise(base_proc_signal());
    }
    if (t == TB_COSIM_EXACT) { printf("%s\n", msg); rc = CLI_OK; }
    else if (t == TB_COSIM_MISMATCH) { printf("%s\n", msg); rc = CLI_FAIL; }
    else rc = cli_from_tb(t == TB_COSIM_BADINPUT ? TB_BADINPUT : TB_FAIL, "%s", msg);
    vec_set_free(&vs);
    if (!st.keep) base_proc_rmtree(dir);
    base_proc_release();
    if (base_proc_signal()) base_proc_reraise(base_proc_signal());     /* one that came at the very end */
    return cli_stdout_done(rc);
}

/* ------------------------------------------------------------------- synth */

static int synth_fpga(void *base, const char *opt, const char *v)
{
    if (strcmp(v, "ice40")) return cli_usage_error("%s %s: expected ice40 (the FPGA family nextpnr-ice40 places)", opt, v);
    ((cli_synth_st *)base)->fpga = v;
    return 0;
}

static int synth_device(void *base, const char *opt, const char *v)
{
    static const char *const dev[] = { "lp384", "lp1k", "lp4k", "lp8k", "hx1k", "hx4k", "hx8k", "up3k", "up5k", "u1k", "u2k", "u4k" };
    for (size_t i = 0; i < sizeof dev / sizeof dev[0]; i++)
        if (!strcmp(v, dev[i])) { ((cli_synth_st *)base)->device = v; return 0; }
    return cli_usage_error("%s %s: expected an iCE40 device of nextpnr-ice40: lp384, lp1k, lp4k, lp8k, hx1k, hx4k, hx8k, "
                           "up3k, up5k, u1k, u2k or u4k", opt, v);
}

static int synth_abc(void *base, const char *opt, const char *v)
{
    static const char *const name[] = { "auto", "full", "light" };
    for (int i = 0; i < 3; i++)
        if (!strcmp(v, name[i])) { ((cli_synth_st *)base)->abc = i; return 0; }
    return cli_usage_error("%s %s: expected auto, full or light", opt, v);
}

static const cli_opt synth_tab[] = {
    { "--sta", NULL, CLI_OPT_FLAG, offsetof(cli_synth_st, sta), 0, 0, NULL, NULL, NULL, 0,
      "  --sta                map to a standard-cell library with Yosys (dfflibmap, abc\n"
      "                       -liberty, its buffering of heavy nets) and time the\n"
      "                       netlist with OpenSTA (Debian package opensta): its\n"
      "                       critical path (cells, start and end), f_max and\n"
      "                       mapped area beside the model's, with the ratios\n"
      "                       model / tool; needs --liberty\n" },
    { "--liberty", NULL, CLI_OPT_STR, offsetof(cli_synth_st, liberty), 0, 0, NULL, "%s needs a Liberty file", NULL, CLI_OPT_NONEMPTY,
      "  --liberty FILE       the cell library (.lib, or gzipped); 1 GE is its NAND2_X1\n" },
    { "--clock-ps", NULL, CLI_OPT_REAL, offsetof(cli_synth_st, clock_ps), 1, 1e9, NULL, NULL, NULL, 0,
      "  --clock-ps P         the clock OpenSTA times against (default 10000 ps); the\n"
      "                       critical path is P less the worst slack\n" },
    { "--abc", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs auto, full or light", synth_abc, 0,
      "  --abc S              with --sta, ABC's script: full (Yosys's default for a\n"
      "                       Liberty, with its restructuring), light (the mapping\n"
      "                       alone: for networks the restructuring does not finish\n"
      "                       on), auto (default: light past 100000 GE of the\n"
      "                       model's area, else full); the model's carries follow\n"
      "                       it (ripple, or the light script's prefix carries)\n" },
    { "--fpga", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs ice40", synth_fpga, 0,
      "  --fpga ice40         synthesize for an iCE40 (Yosys synth_ice40), place and\n"
      "                       route with nextpnr-ice40 (Debian package nextpnr-ice40):\n"
      "                       LUTs, flip-flops, carries, DSPs, logic cells and\n"
      "                       nextpnr's f_max for clk\n" },
    { "--device", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs an iCE40 device", synth_device, 0,
      "  --device D           the iCE40 device (default hx8k)\n" },
    { "--package", NULL, CLI_OPT_STR, offsetof(cli_synth_st, package), 0, 0, NULL, "%s needs a package", NULL, CLI_OPT_NONEMPTY,
      "  --package P          its package (default ct256)\n" },
    { "--freq", NULL, CLI_OPT_REAL, offsetof(cli_synth_st, freq_mhz), 0, 1e4, NULL, NULL, NULL, CLI_OPT_GT_LO,
      "  --freq MHZ           nextpnr's target frequency (default its own, 12 MHz); a\n"
      "                       missed target is reported, not an error\n" },
    { "--timeout", NULL, CLI_OPT_REAL, offsetof(cli_synth_st, timeout_s), 0, 1e7, NULL, NULL, NULL, 0,
      "  --timeout SECONDS    stop the tools after this long in all (default 600; 0:\n"
      "                       no limit): exit status 2\n" },
    { "--json", NULL, CLI_OPT_FLAG, offsetof(cli_synth_st, json), 0, 0, NULL, NULL, NULL, 0,
      "  --json               with --sta or --fpga: one JSON object on stdout\n" },
    { "--keep", NULL, CLI_OPT_STR, offsetof(cli_synth_st, keep), 0, 0, NULL, "%s needs a folder", NULL, 0,
      "  --keep DIR           leave the export, the tools' scripts and logs in DIR\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_synth_spec = {
    "synth", { no_opts, synth_tab, cli_unit_opt_tab }, unit_arg, 0,
    "synth: unexpected argument '%s' (see shadesim synth --help)",
    "usage: shadesim synth UNIT [options] [--sta --liberty FILE | --fpga ice40] [--keep DIR]\n"
    "Export the unit and synthesize it with Yosys to generic gates (synth; abc -g\n"
    "AND,NAND,OR,NOR,XOR,XNOR,MUX; no cell library): prints Yosys's cells by type\n"
    "and in total, weighted with the area model's NAND2 gate equivalents per gate,\n"
    "beside shadesim's area estimate; then Yosys's longest topological path (ltp\n"
    "-noff after flatten) beside shadesim's critical path in gate levels and ps.\n"
    "With --sta, the real flow on a cell library instead (Yosys, then OpenSTA);\n"
    "with --fpga ice40, Yosys and nextpnr (docs/timing.md, \"Against OpenSTA and\n"
    "nextpnr\"). Needs yosys (Debian package yosys). A progress line on stderr when\n"
    "it is a terminal; a tool still running at --timeout is stopped (exit 2).\n"
    "options:\n", NULL
};

/* A Yosys generic cell in NAND2 gate equivalents, with the constants of
 * sim/sim_area.h (NanGate 45 nm): flip-flops with an enable add a MUX2,
 * with a synchronous reset ($_SDFF*) an AND2; one with an asynchronous
 * reset ($_DFF_PP0_, $_DFFE_PP0P_: a reset value in its name) is a DFFR. */
static double cell_ge(const char *c)
{
    if (!strncmp(c, "NAND", 4) || !strncmp(c, "NOR", 3)) return SIM_GE_NAND2;
    if (!strncmp(c, "NOT", 3)) return SIM_GE_INV;
    if (!strncmp(c, "AND", 3) || !strncmp(c, "OR", 2)) return SIM_GE_AND2;
    if (!strncmp(c, "XOR", 3) || !strncmp(c, "XNOR", 4)) return SIM_GE_XOR2;
    if (!strncmp(c, "MUX", 3)) return SIM_GE_MUX2;
    if (strstr(c, "DFF")) {
        double g = SIM_GE_DFF;
        const char *pol = strchr(c, '_');
        if (c[0] == 'S') g += SIM_GE_AND2;
        else if (pol && strpbrk(pol, "01")) g = SIM_GE_DFFR;
        if (strstr(c, "DFFE") || strstr(c, "DFFCE")) g += SIM_GE_MUX2;
        return g;
    }
    return SIM_GE_NAND2;
}

/* Yosys's longest topological path (ltp -noff: flip-flops cut it, so it
 * is the most gates between registers or ports) beside shadesim's
 * critical path in gate levels (docs/timing.md compares them). */
static void synth_paths(const char *dir, const cli_unit_opts *o, const unit_fmts *fm)
{
    char path[1200], line[400], err[600];
    snprintf(path, sizeof path, "%s/ltp.txt", dir);
    FILE *f = fopen(path, "r");
    long len = -1;
    while (f && fgets(line, sizeof line, f)) {
        const char *l = strstr(line, "(length=");
        if (strstr(line, "Longest topological path") && l) len = atol(l + 8);
    }
    if (f) fclose(f);
    tb_ppa p;
    memset(&p, 0, sizeof p);
    /* abc -g runs ABC's default script, whose restructuring leaves ripple
     * carries whatever the design's size */
    int bad = tb_unit_timing_abc(o->u, &o->cfg, fm, TB_ABC_FULL, &p, err, sizeof err);
    printf("Yosys longest topological path (ltp -noff) against shadesim's critical path:\n");
    if (len >= 0) printf("  Yosys        %6ld gates\n", len);
    else printf("  Yosys        (no ltp result: see yosys.log with --keep DIR)\n");
    if (bad) { printf("  shadesim     (no critical path: %s)\n", err); return; }
    char ptext[1200];
    tb_ppa_path_text(&p, ptext, sizeof ptext);
    printf("  shadesim     %6d levels, %.0f ps, f_max %.0f MHz (%s)\n", p.levels, p.crit_ps, p.fmax_mhz, ptext);
    if (len > 0) printf("  ratio        %.2f (shadesim levels / Yosys gates)\n", p.levels / (double)len);
}

/* The generic flow: Yosys to generic gates, its cells and longest path
 * beside the model's. */
static int synth_generic(const cli_unit_opts *o, const unit_fmts *fm, const cli_synth_st *st)
{
    char err[600];
    double ge = tb_verilog_area(o->u, &o->cfg, fm, err, sizeof err);
    if (ge < 0) return cli_usage_error("%s", err);
    char tmpl[4096];
    const char *dir = cli_synth_dir(st, tmpl, sizeof tmpl);
    if (!dir) return CLI_USAGE;
    tb_synth_run run = { base_proc_now(), st->timeout_s < 0 ? CLI_SYNTH_TIMEOUT : st->timeout_s, cli_stderr_tty(), 0 };
    int rc = CLI_OK, t = TB_SYNTH_OK;
    if (tb_verilog_export(o->u, &o->cfg, fm, dir, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "yosys -q -l yosys.log -p 'read_verilog %s.v; synth -top %s; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX; "
             "opt_clean; tee -q -o stat.txt stat; flatten; tee -q -o ltp.txt ltp -noff' >/dev/null 2>&1", o->u->name, o->u->name);
    t = tb_synth_tool(&run, "yosys", dir, cmd, 1, err, sizeof err);
    if (t == TB_SYNTH_FAILED) { fprintf(stderr, "shadesim: synth: yosys failed (see yosys.log: use --keep DIR)\n"); rc = CLI_FAIL; goto done; }
    if (t != TB_SYNTH_OK) { rc = t == TB_SYNTH_SIGNAL ? CLI_FAIL : cli_usage_error("%s", err); goto done; }
    char path[1200], line[300];
    snprintf(path, sizeof path, "%s/stat.txt", dir);
    FILE *f = fopen(path, "r");
    long total = -1;
    printf("%s --width %d --schedule %s (%s, %s): Yosys generic gates\n", o->u->name, o->cfg.width,
           o->u->sched[o->cfg.schedule].name, sim_round_name(o->cfg.rnd), sim_ovf_name(o->cfg.ovf));
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
    synth_paths(dir, o, fm);
done:
    cli_synth_cleanup(st, dir, t == TB_SYNTH_SIGNAL ? run.signal : 0);
    return cli_stdout_done(rc);
}

int cli_synth(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_synth_spec);
    cli_unit_opts o;
    cli_synth_st st = { NULL, 0, 0, NULL, 0, NULL, NULL, NULL, 0, -1, -1 };
    int rc = parse(&cli_synth_spec, argc, argv, &o, &st);
    if (rc) return rc;
    if (st.sta && st.fpga) return cli_usage_error("synth: --sta and --fpga are two flows: choose one");
    if (st.sta && !st.liberty) return cli_usage_error("synth: --sta needs --liberty FILE (a Liberty cell library, e.g. NanGate45's; docs/timing.md)");
    if (st.liberty && !st.sta) return cli_usage_error("synth: --liberty goes with --sta");
    if (st.clock_ps > 0 && !st.sta) return cli_usage_error("synth: --clock-ps goes with --sta");
    if (st.abc >= 0 && !st.sta) return cli_usage_error("synth: --abc goes with --sta");
    if ((st.device || st.package || st.freq_mhz > 0) && !st.fpga) return cli_usage_error("synth: --device, --package and --freq go with --fpga ice40");
    if (st.json && !st.sta && !st.fpga) return cli_usage_error("synth: --json goes with --sta or --fpga");
    unit_fmts fm;
    if (formats(&o, &fm)) return CLI_USAGE;
    if (st.sta || st.fpga) return cli_synth_flow(&o, &fm, &st);
    if (!have_tool("yosys")) return cli_usage_error("synth: yosys not found (install the Debian package yosys)");
    return synth_generic(&o, &fm, &st);
}
