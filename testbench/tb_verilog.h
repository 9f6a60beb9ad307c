/* tb_verilog.h - a unit as Verilog: the module (sim/sim_verilog.h, from
 * the unit built exactly as tb_run builds it), a testbench reading the
 * stimulus with $readmemh, and the stimulus and expected results; and the
 * co-simulation of that module, or of the user's own RTL with the same
 * ports, against shadesim.
 *
 * Ports, in this order: clk, rst (unless the reset is SIM_VRESET_NONE),
 * the unit's inputs, in_valid, in_ready, the unit's outputs, out_valid;
 * names as in `shadesim list UNIT`. rst is active high; the testbench
 * holds it for TB_RESET_CLOCKS rising edges with in_valid 0, then counts
 * cycles from 0.
 *
 * Stimulus (FILE): one line per item, the quantized input raws in hex
 * (each the low W bits of its port), in port order. Expected (FILE.expect)
 * and the testbench's output: one line per output beat, "CYCLE RAW..."
 * with the cycle in decimal (0 = the cycle that ends at the first rising
 * edge after the reset, as tb_run counts) and each output's raw bits in
 * hex, zero-padded to the port's width. So the check in any simulator is
 * a diff.
 */
#ifndef TB_VERILOG_H
#define TB_VERILOG_H
#include "testbench/tb.h"
#include "sim/sim_verilog.h"

#define TB_RESET_CLOCKS 2

/* Write DIR/UNIT.v and DIR/UNIT_tb.v (DIR is made if missing) with the
 * given reset; paths (NULL: not wanted) get the two paths, malloc'd. 0,
 * or -1 with a one-line message (a file that cannot be written, a logic
 * element too wide to tabulate). tb_verilog_export: synchronous reset. */
int tb_verilog_write(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, sim_vreset reset,
                     const char *dir, char *paths[2], char *err, size_t errlen);
int tb_verilog_export(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm,
                      const char *dir, char *err, size_t errlen);
/* The module text alone, malloc'd (NULL with a message). */
char *tb_verilog_module_text(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, sim_vreset reset,
                             char *err, size_t errlen);
/* The testbench text instantiating module `dut` (the unit's name, or the
 * user's top module), malloc'd (NULL: out of memory). */
char *tb_verilog_tb_text(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, sim_vreset reset,
                         const char *dut);

/* The unit's ports as the export has them (clk and rst included): name,
 * width, 1 for an output. Returns their number (at most TB_MAX_PORTS). */
#define TB_MAX_PORTS (2 * UNIT_MAX_IO + 6)
typedef struct tb_port { const char *name; int width, is_output; } tb_port;
int tb_verilog_ports(const unit_desc *u, const unit_fmts *fm, sim_vreset reset, tb_port *p);
/* shadesim's area estimate of the unit (NAND2 gate equivalents), or -1
 * with a message. */
double tb_verilog_area(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm,
                       char *err, size_t errlen);

/* Stimulus of vs quantized as tb_run quantizes it, to in_path; the
 * expected beats of r (a tb_run of the same vectors) to exp_path (NULL:
 * not written). 0 or -1 with a message. */
int tb_stimulus_write(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm,
                      const vec_set *vs, const tb_result *r, const char *in_path,
                      const char *exp_path, char *err, size_t errlen);

/* Input k (signal index sig) of item `item` quantized as tb_run does. */
int64_t tb_stimulus_raw(const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs, size_t item, int sig, int k);

/* Co-simulation: tb_run on vs, the export (or the user's RTL), stimulus
 * and expected results into dir (an existing folder), the external
 * simulator run on them, and the results compared line for line (every
 * output raw, every beat's cycle). Verilator builds into
 * dir/obj_verilator. msg gets one line: "bit-exact, N items, M clocks
 * (icarus)", the first mismatch, or what failed. tb_cosim: the export,
 * synchronous reset. */
enum { TB_SIM_ICARUS = 0, TB_SIM_VERILATOR = 1 };
enum { TB_COSIM_EXACT = 0, TB_COSIM_MISMATCH = 1, TB_COSIM_FAILED = 2, TB_COSIM_BADINPUT = 3 };
typedef struct tb_cosim_opts {
    sim_vreset reset;
    const char *const *rtl;     /* the user's Verilog files instead of the export (nrtl > 0) */
    int nrtl;
    const char *top;            /* their top module; NULL: the only top-level module, or UNIT */
    int match_items;            /* compare the output raws item by item in order, not their
                                 * cycles (a re-timed design); msg then gives the RTL's
                                 * latency and items per clock beside shadesim's */
    double timeout_s;           /* wall seconds for the tools, the compile included; <= 0:
                                 * TB_COSIM_TIMEOUT_S (a zero-delay loop never lets
                                 * simulated time, and so the clock limit, advance) */
} tb_cosim_opts;
#define TB_COSIM_TIMEOUT_S 600.0
int tb_cosim(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs,
             int sim, const char *dir, char *msg, size_t msglen);
int tb_cosim_opt(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs,
                 const tb_cosim_opts *o, int sim, const char *dir, char *msg, size_t msglen);

/* The user's RTL (tb_cosim.c): the top module and its ports as the
 * simulator elaborates them (Icarus: the .port_info lines of its compiled
 * file; Verilator: its --xml-only output), in dir. top in/out: the
 * wanted top (NULL or "" to find it), the found one in topbuf. Returns
 * the number of ports (names in names, malloc'd one by one), or -1 with
 * a message. */
int tb_rtl_ports(const char *const *files, int nfiles, const char *want_top, const char *unit,
                 int sim, double timeout_s, const char *dir, char *topbuf, size_t toplen, tb_port *p, char **names, int maxp,
                 char *err, size_t errlen);
#endif
