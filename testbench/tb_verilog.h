/* tb_verilog.h - a unit as Verilog: the module (sim/sim_verilog.h, from
 * the unit built exactly as tb_run builds it), a testbench reading the
 * stimulus with $readmemh, and the stimulus and expected results.
 *
 * Ports, in this order: clk, the unit's inputs, in_valid, in_ready, the
 * unit's outputs, out_valid; names as in `shadesim list UNIT`.
 *
 * Stimulus (FILE): one line per item, the quantized input raws in hex
 * (each the low W bits of its port), in port order. Expected (FILE.expect)
 * and the testbench's output: one line per output beat, "CYCLE RAW..."
 * with the cycle in decimal (0 = the cycle that ends at the first rising
 * edge, as tb_run counts) and each output's raw bits in hex, zero-padded
 * to the port's width. So the check in any simulator is a diff.
 */
#ifndef TB_VERILOG_H
#define TB_VERILOG_H
#include "testbench/tb.h"

/* Write DIR/UNIT.v and DIR/UNIT_tb.v (DIR is made if missing). 0, or -1
 * with a one-line message (a file that cannot be written, a logic element
 * too wide to tabulate). */
int tb_verilog_export(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm,
                      const char *dir, char *err, size_t errlen);
/* The module text alone, malloc'd (NULL with a message). */
char *tb_verilog_module_text(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm,
                             char *err, size_t errlen);
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

/* Co-simulation: tb_run on vs, the export, stimulus and expected results
 * into dir (an existing folder), the external simulator run on them, and
 * the results compared line for line (every output raw, every beat's
 * cycle). Verilator builds into dir/obj_verilator. msg gets one line:
 * "bit-exact, N items, M clocks (icarus)", the first mismatch, or what
 * failed. */
enum { TB_SIM_ICARUS = 0, TB_SIM_VERILATOR = 1 };
enum { TB_COSIM_EXACT = 0, TB_COSIM_MISMATCH = 1, TB_COSIM_FAILED = 2, TB_COSIM_BADINPUT = 3 };
int tb_cosim(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs,
             int sim, const char *dir, char *msg, size_t msglen);
#endif
