/* tb_netlist.h - a built unit as text, and the text built back (docs/netlist.md).
 *
 * tb_netlist_write builds a unit as tb_build does and writes what the
 * context holds: the configuration it was built with, the clock, the
 * scopes, then one line per signal in creation order (its element's kind,
 * name, format, quantization modes, operands by name, shifts, a logic
 * element's truth table and area), then the ports. tb_netlist_load reads
 * such a file back: it returns a unit whose build makes the same context
 * from the text (tb_build dispatches to it), with the built-in unit's
 * float reference, vectors, ideal function and bound, so every testbench
 * runs it as it runs the unit itself.
 */
#ifndef TB_NETLIST_H
#define TB_NETLIST_H
#include "testbench/tb.h"
#include <stdio.h>

/* A logic element of at most this many input bits in all is written as a
 * truth table; a wider one (wiring of wide words: a divider's shifted
 * remainder, a ROM's address) names the built-in unit's function. */
#define TB_NETLIST_TABLE_BITS 12

/* The text of unit u built with cfg and the --fmt overrides fmt[0..nfmt-1]
 * (in order), to f. 0, or -1 with a message (the unit refuses the
 * configuration; an element the text cannot say). */
int tb_netlist_write(FILE *f, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                     char *err, size_t errlen);
/* The same unit as a datapath file (docs/datapaths.md) that names it for
 * its reference (ideal unit=NAME): the formats as rules of W where builds
 * at the neighbouring widths agree, the control as schedule rows where it
 * is the step counter the reader makes, else written out. */
int tb_netlist_write_dp(FILE *f, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                        char *err, size_t errlen);

/* Read the netlist file at path ("-": standard input): the unit it builds
 * (a copy of the built-in unit it names, built from the text), its
 * configuration into *cfg and its formats into *fm. NULL with
 * "PATH:LINE: what is wrong" (or "PATH: ...") in err. The unit lives until
 * tb_netlist_free. */
const unit_desc *tb_netlist_load(const char *path, unit_cfg *cfg, unit_fmts *fm, char *err, size_t errlen);
void tb_netlist_free(const unit_desc *u);

/* For tb_build: 1 if u came from tb_netlist_load, and then its build: the
 * elements of the text into c, scope sc, clocked by clk; 0 or -1 with a
 * message. */
int tb_netlist_is(const unit_desc *u);
/* 1 if u came from a datapath file (datapath NAME, docs/datapaths.md): a
 * unit of its own, built by its descriptor's functions like a built-in
 * one, with no vector file of its own (its vectors are drawn from the
 * file's input ranges). */
int tb_datapath_is(const unit_desc *u);
/* The built-in unit a datapath file runs with (ideal unit=NAME: its
 * reference, vectors, ideal and bound), or NULL. */
const unit_desc *tb_datapath_base(const unit_desc *u);
int tb_netlist_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk, unit_io *io,
                     char *err, size_t errlen);
#endif
