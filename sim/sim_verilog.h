/* sim_verilog.h - a built design as synthesizable Verilog-2001.
 *
 * The module is written from the simulation itself: every signal of a
 * scope (and its sub-scopes, flattened: "div3_a.t1" becomes div3_a_t1) and
 * the primitive driving it (sim_prim_describe), with its operands, its
 * output format and its own rounding and overflow modes. Arithmetic is
 * written exact (operands sign-extended and aligned to a width that cannot
 * overflow) and then quantized by the same steps as sim_fixed.c: floor,
 * a rounding increment (half-up: the first dropped bit; even: that bit and
 * (any lower bit or the kept LSB)), then wrap (low W bits) or saturate.
 * Logic elements (C functions) are tabulated: every combination of their
 * input bits is evaluated at export time into a case statement, exact by
 * construction; inputs of more than SIM_VERILOG_MAX_LOGIC_BITS bits in
 * total are refused.
 *
 * Every register has a reset value, the value the simulation starts it
 * at. With a reset input (SIM_VRESET_SYNC or _ASYNC: port `rst`, active
 * high, right after clk) rst puts every register at that value, on the
 * clock's edge or at once; an ASIC flow needs it, since synthesis ignores
 * initial blocks. With SIM_VRESET_NONE there is no rst port and registers
 * start from initial blocks (FPGA flows and simulators honour them).
 */
#ifndef SIM_VERILOG_H
#define SIM_VERILOG_H
#include <stdio.h>
#include "sim/sim.h"

#define SIM_VERILOG_MAX_LOGIC_BITS 12

typedef enum { SIM_VRESET_SYNC = 0, SIM_VRESET_ASYNC = 1, SIM_VRESET_NONE = 2 } sim_vreset;

typedef struct sim_vport {
    const char *name;       /* port name */
    sim_signal *sig;
    int         is_output;
} sim_vport;

/* Write module `module` for the signals in scope sc, clocked by clk (a
 * signal outside sc), with the given ports (clk first, then rst unless
 * reset is SIM_VRESET_NONE, implicitly). Every
 * signal in sc must be a port input, a constant or driven by a primitive.
 * 0, or -1 with a one-line message (nothing useful written). */
int sim_verilog_module(FILE *f, const sim_ctx *c, const sim_scope *sc, const char *module,
                       const sim_signal *clk, sim_vreset reset, const sim_vport *ports, int nports,
                       char *err, size_t errlen);


#endif
