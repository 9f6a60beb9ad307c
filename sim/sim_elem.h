/* sim_elem.h - the element kinds, one row each: the one list the per-kind
 * tables are made from (the kind enum and names, the batch's kinds, the
 * Verilog and energy dispatch) and tests/test_elem.c walks. The kernel's
 * inline operations (sim_internal.h) and the vector loops are not made
 * from it: tests/test_cells.c holds them to sim_elem_eval.
 *
 * The list is an X-macro, SIM_ELEM_LIST(X), with one
 * X(KIND, name, role, eval, vlog, energy, area, delay) per kind:
 *   KIND    SIM_KIND_KIND (sim.h: the enum is made from this list, in its
 *           order; outputs and files depend on the values, so rows are
 *           only ever appended)
 *   name    the kind's name in text (sim_kind_name)
 *   role    SIM_ELEM_SOURCE: no process computes it (an input, a clock,
 *           a constant); SIM_ELEM_COMB: combinational; SIM_ELEM_SEQ:
 *           state, loaded on a clock edge
 *   eval    the kind whose evaluation a signal of this kind takes when a
 *           primitive drives it (sim_elem_eval): an input a sim_assign
 *           drives is a copy, as a wire is. The batch mode's element
 *           kinds (sim_batch_int.h, B_*) and the interval propagation
 *           (sim_ival.c) dispatch on it
 *   vlog    sim_verilog.c's emitter for it (emit_VLOG)
 *   energy  sim_energy.c's energy per toggle of its output (toggle_ENERGY)
 *   area    1: an element of this kind has area of its own (sim_area.h,
 *           set when it is built, sim_prim.c); 0: it is wires or a port
 *   delay   1: it has a delay of its own (sim_delay.h, sim_arcs); 0: it
 *           passes values in no time or drives them from outside
 *
 * Adding a kind is one row here, its operation once in sim_op.h, and its
 * use of it once per engine: its constructor in sim_prim.c (process, fast
 * path, area, delay), the kernel's SIM__OP_* if it evaluates it inline
 * (sim_internal.h), the batch mode's scalar loop (sim_batch_eval.c) and
 * setup (sim_batch_op.c), emit_VLOG, toggle_ENERGY, sim_ival.c's case; the
 * tables made from this list do not compile until each engine names its
 * function, and tests/test_elem.c runs every kind through every engine.
 * Its one executable definition is its case of sim_elem_eval
 * (sim_elem_eval.c), which the reference kernel runs and
 * tests/test_cells.c holds every engine to.
 */
#ifndef SIM_ELEM_H
#define SIM_ELEM_H

#define SIM_ELEM_LIST(X)                                                  \
    /* KIND   name     role             eval   vlog    energy area delay */ \
    X(WIRE,   "wire",  SIM_ELEM_COMB,   WIRE,  copy,   none,  0,   0)     \
    X(INPUT,  "input", SIM_ELEM_SOURCE, WIRE,  copy,   load,  0,   0)     \
    X(CLOCK,  "clock", SIM_ELEM_SOURCE, CLOCK, none,   none,  0,   0)     \
    X(CONST,  "const", SIM_ELEM_SOURCE, CONST, const,  none,  0,   0)     \
    X(REG,    "reg",   SIM_ELEM_SEQ,    REG,   reg,    dff,   1,   1)     \
    X(MUX,    "mux",   SIM_ELEM_COMB,   MUX,   mux,    mux,   1,   1)     \
    X(BK,     "bk",    SIM_ELEM_COMB,   BK,    bk,     and2,  1,   1)     \
    X(ADD,    "add",   SIM_ELEM_COMB,   ADD,   arith,  add,   1,   1)     \
    X(SUB,    "sub",   SIM_ELEM_COMB,   SUB,   arith,  add,   1,   1)     \
    X(MUL,    "mul",   SIM_ELEM_COMB,   MUL,   arith,  mul,   1,   1)     \
    X(SHIFT,  "shift", SIM_ELEM_COMB,   SHIFT, arith,  none,  0,   0)     \
    X(LOGIC,  "logic", SIM_ELEM_COMB,   LOGIC, logic,  and2,  1,   1)

enum { SIM_ELEM_SOURCE, SIM_ELEM_COMB, SIM_ELEM_SEQ };

#endif
