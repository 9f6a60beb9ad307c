/* tb_vexpr.h - a logic element's Verilog text as its function (the
 * netlist's and datapath file's fn=verilog, docs/netlist.md).
 *
 * The export's text of a logic element is, for most of the built-in
 * units' wide ones, a small combinational Verilog body: wires of given
 * widths, a function or an always block holding a case (a ROM, a
 * normalizing shifter), and `assign %y = EXPR;`. This evaluates that
 * subset on the inputs' raws (%0 .. %7), with Verilog's widths for wires
 * and selects, concatenation and replication, $signed, the arithmetic,
 * shift, relational, equality, bitwise, reduction and logical operators
 * and ?:. Where an expression's width depends on its context in ways the
 * subset does not model, the result can differ from a Verilog tool's: the
 * netlist writer uses fn=verilog only where the evaluation equals the
 * element's own function on every input it tries.
 */
#ifndef TB_VEXPR_H
#define TB_VEXPR_H
#include <stddef.h>
#include <stdint.h>

typedef struct tb_vexpr tb_vexpr;
/* text for inputs of widths in_width[0..nin-1] and an output of out_width
 * bits: the program, or NULL with "what is wrong" (and where) in err. */
tb_vexpr *tb_vexpr_compile(const char *text, int nin, const int *in_width, int out_width, char *err, size_t errlen);
/* A sim_logic_fn (user: the program): the output's raw bits, unsigned. */
int64_t tb_vexpr_fn(const int64_t *in, void *user);
void tb_vexpr_free(tb_vexpr *p);
#endif
