/* tb_synth.h - a unit through the real back ends: the export (tb_verilog.h)
 * mapped by Yosys to a standard-cell Liberty and timed by OpenSTA, or
 * synthesized by Yosys for an iCE40 and placed and routed by nextpnr.
 * Each tool runs in dir (the caller's folder, kept or removed by it)
 * through base_proc: in a process group of its own, under one time limit
 * for the whole flow, with a progress line on a terminal.
 *
 * Files left in dir: UNIT.v (the export), yosys.log, stat.txt; for STA
 * liberty.lib (the library, unpacked when it was gzipped, else a link to
 * it), mapped.v, sta.tcl, sta.log; for the FPGA UNIT.json, nextpnr.log.
 */
#ifndef TB_SYNTH_H
#define TB_SYNTH_H
#include "testbench/tb.h"
#include "base/base_proc.h"

/* Results: OK; BADINPUT (a tool or file missing, the device too small:
 * the message says which); FAILED (a tool failed: the message names its
 * log); TIMEOUT; SIGNAL (shadesim got run->signal: the caller cleans up
 * and calls base_proc_reraise). */
enum { TB_SYNTH_OK = 0, TB_SYNTH_BADINPUT, TB_SYNTH_FAILED, TB_SYNTH_TIMEOUT, TB_SYNTH_SIGNAL };

/* How the tools run: start, limit_s and progress as base_proc has them
 * (verb, step, detail and dir are set per tool); signal out. */
typedef struct tb_synth_run {
    double start, limit_s;
    int progress;
    int signal;
} tb_synth_run;

/* One tool's command line run in dir through base_proc (step names it
 * on the progress line; yosys: 1 when it writes dir/yosys.log, whose pass
 * the line shows), within run's limit. TB_SYNTH_OK, FAILED (a non-zero
 * exit status), TIMEOUT or SIGNAL, with a message for the last two. */
int tb_synth_tool(tb_synth_run *run, const char *step, const char *dir, const char *cmd, int yosys,
                  char *err, size_t errlen);

#define TB_STA_CELLS 256
typedef struct tb_sta {
    double period_ps;           /* the clock the design was timed at */
    double arrival_ps;          /* data arrival at the critical endpoint (clock-to-q included) */
    double setup_ps;            /* the endpoint's setup (0 at an output port) */
    double slack_ps;            /* period - arrival - setup */
    double crit_ps;             /* period - slack = arrival + setup: what f_max uses */
    double fmax_mhz;            /* 1e6 / crit_ps */
    char start[128], end[128];  /* a register (by the net its Q drives) or a port */
    char start_kind[32], end_kind[32];  /* OpenSTA's words: "rising edge-triggered flip-flop", "input port" */
    int npath;                  /* cells along the path, from the start */
    char path[TB_STA_CELLS][64];
    long cells;                 /* mapped cells in all */
    double area;                /* Yosys's stat -liberty: the library's area unit (um^2) */
    double ge_area;             /* the area of one gate equivalent: ge_cell's */
    char ge_cell[64];           /* NAND2_X1 (else the smallest NAND2 cell of the library) */
    double area_ge;             /* area / ge_area */
} tb_sta;

/* ABC's script for the mapping: the default one Yosys runs for a Liberty
 * (its restructuring, &fraig -x, scorr, dc2, &dch -f, before &nf), or
 * the light one (&nf alone, after dretime), for networks on which the
 * restructuring does not finish (docs/timing.md, "Big designs"); each
 * followed by buffer -p. */
enum { TB_ABC_FULL = 0, TB_ABC_LIGHT };
/* --abc auto's choice: the light script past TB_ABC_LIGHT_GE of the
 * model's area (ABC's restructuring of a network that large runs for
 * hours), else the default one. */
#define TB_ABC_LIGHT_GE 100000.0
int tb_abc_auto(double model_ge);

/* The flow of `synth --sta`: the export, Yosys (synth -top UNIT;
 * dfflibmap and abc on the library with script abc, TB_ABC_*; opt_clean;
 * stat -liberty; write_verilog), OpenSTA (create_clock on clk at
 * period_ps, zero input and output delays on the other ports,
 * report_checks -path_delay max). liberty: a Liberty file, gzipped or not. */
int tb_synth_sta(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *liberty,
                 double period_ps, int abc, const char *dir, tb_synth_run *run, tb_sta *r, char *err, size_t errlen);

typedef struct tb_fpga {
    char device[16], package[16];
    double freq_mhz;            /* nextpnr's target (--freq; 0: its default) */
    long luts, ffs, carries, dsps, rams;   /* Yosys's cells: SB_LUT4, SB_DFF*, SB_CARRY, SB_MAC16, SB_RAM40_4K */
    long lcs, lcs_avail;        /* nextpnr's ICESTORM_LC used / on the device */
    long ios, ios_avail;        /* SB_IO used / on the package */
    double fmax_mhz;            /* nextpnr's last "Max frequency for clock" of clk */
    double target_mhz;          /* the target nextpnr checked (its default when freq_mhz is 0) */
    double in_ns, out_ns, comb_ns;  /* nextpnr's "Max delay" of port -> clk, clk -> port and
                                     * port -> port paths (0: none); a design without a
                                     * clocked path has only comb_ns, and fmax_mhz = 1000 / it */
    int clocked;                /* 1: fmax_mhz is clk's, reg to reg */
    int met;                    /* 1 PASS at the target, 0 FAIL */
} tb_fpga;

/* The flow of `synth --fpga ice40`: the export, Yosys synth_ice40 -json,
 * nextpnr-ice40 --DEVICE --package PACKAGE [--freq F]. r->device,
 * r->package and r->freq_mhz are read (the caller sets them). A missed
 * --freq target is a result (met = 0); ports beyond the package's pins
 * are TB_SYNTH_BADINPUT, saying so. */
int tb_synth_fpga(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *dir,
                  tb_synth_run *run, tb_fpga *r, char *err, size_t errlen);
#endif
