/* sim_prim.h - datapath primitives built on the kernel.
 *
 * Each constructor creates the element's output signal (in scope sc, with
 * format fmt), a process that computes it, and the element's area in gate
 * equivalents (sim_area.h), and returns the output signal.
 *
 * Arithmetic is exact before quantization: operands are aligned to a common
 * fraction point in 128-bit integers, summed or multiplied exactly, then
 * quantized once into the output format with the format's own rounding
 * and overflow modes (sim_fixed.h), or, for a format without them, the
 * modes the context had when the element was built (sim_set_quant).
 * A multiplier's output is quantized to its own format, as a W-bit hardware
 * multiplier's output would be, before anything else sees it.
 *
 * Overflows are counted on the output signal (sim_signal.overflows).
 * Used values: an overflow counts in overflows only when the value it
 * settled on is used that clock (sim__value_used in sim_internal.h: a
 * register holds it or an enabled one takes it, it is an output
 * (sim_signal_output), a process that is not a primitive reads it, or a
 * selecting mux, a passing block key or any other element passes it on to
 * a used value); otherwise in ovf_discarded. The batch mode counts them
 * the same way per lane (sim_batch_ovf.c).
 */
#ifndef SIM_PRIM_H
#define SIM_PRIM_H
#include "sim/sim.h"
#include "sim/sim_delay.h"

/* A constant of format fmt holding the quantized value of x. */
sim_signal *sim_const(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt, double x);
/* A constant holding a raw value (for control words, selects). */
sim_signal *sim_const_raw(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt, int64_t raw);

/* Register: on clk's rising edge, q <= quant(d) when en (NULL: always);
 * when rst (NULL: none) is 1 at the edge, q <= rst_raw (synchronous reset). */
sim_signal *sim_reg(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *clk, sim_signal *d, sim_signal *en,
                    sim_signal *rst, int64_t rst_raw);

/* A register's D input may be given later (d NULL at creation), for the
 * feedback paths every datapath has (RG -> BK -> Sm -> RG). Connect it
 * before the simulation starts; returns -1 if q is not a register. */
int sim_reg_connect(sim_signal *q, sim_signal *d);

/* Continuous assignment into an existing wire (Verilog `assign dst = src`):
 * declare a wire with sim_signal_new, use it as an input, drive it later.
 * Costs one process and one delta cycle; registers prefer sim_reg_connect.
 * A wire has one driver: assigning into a signal that already has one (an
 * element's output, an earlier sim_assign, a constant, a clock) is an
 * elaboration error (sim_run returns SIM_ERR_ELAB, naming dst). */
void sim_assign(sim_ctx *c, sim_signal *dst, sim_signal *src);

/* N:1 multiplexer: y = quant(in[sel]); sel out of range gives 0. */
sim_signal *sim_mux(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *sel, int n, sim_signal *const *in);

/* Block key (BK in the paper's Fig. 9): y = pass ? quant(x) : 0. */
sim_signal *sim_bk(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                   sim_signal *pass, sim_signal *x);

/* Adder / subtractor: y = quant(a + b) or quant(a - b). */
sim_signal *sim_add(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b);
sim_signal *sim_sub(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b);

/* Multiplier: y = quant(a * b), the product exact before quantization. */
sim_signal *sim_mul(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b);

/* A multiplier by a constant built as another network (units model a
 * shift-and-add one): its own delay arcs net replace the array
 * multiplier's, its quantization's stay. -1 if y is not a sim_mul. */
int sim_mul_network_delay(sim_signal *y, sim_arcs net);

/* Constant shift (wiring): y = quant(x * 2^sh); sh < 0 shifts right. */
sim_signal *sim_shift(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      sim_signal *x, int sh);

/* Combinational logic with a user function over up to 8 inputs' raw values
 * (more is an elaboration error: sim_run returns SIM_ERR_ELAB), for small
 * controllers (decoders of a step counter, comparators). The
 * function must be defined for every raw value of its inputs' formats,
 * reachable or not, and depend on nothing else: the Verilog export and the
 * batch mode tabulate it over all of them, and so does the kernel when the
 * first sim_run starts, for an element of at most 8 input bits in all
 * (it then calls the function only for a raw forced outside its input's
 * format). area_ge is the caller's estimate of the logic's gates. */
typedef int64_t (*sim_logic_fn)(const int64_t *in, void *user);
sim_signal *sim_logic(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      int n, sim_signal *const *in, sim_logic_fn fn, void *user,
                      double area_ge);

/* Optional, for exporters: a logic element's function as Verilog-2001
 * statements (the element's inputs are too wide to tabulate). In text,
 * %y stands for the output (a wire of y's width, to be assigned), %t for
 * a prefix unique to the element (for its own wires: %t_e), %0..%7 for the
 * inputs (bit vectors of their formats' widths; signedness as their
 * formats say, to be handled by the text). The text must compute exactly
 * what the C function computes, raw bits of y's format; the co-simulation
 * tests check it. Copied. */
void sim_logic_verilog(sim_signal *y, const char *text);
/* A logic element's depth in gate levels (AND2 each), where its unit
 * knows it better than the estimate from its input bits: 0 for wiring
 * (bits concatenated or selected), 1 for an inverter. */
void sim_logic_depth(sim_signal *y, int levels);
/* Optional, for range analysis (sim_ival.h, sim_aff.h), where a logic
 * function is otherwise opaque: the unit states what it knows of it, and
 * test_derive checks each statement against the function over every
 * input raw of small formats. sim_logic_linear: in reals, y is k times
 * its input i plus an error within [lo, hi] (a shift with bits shifted
 * in, a floor): y = k in_i + e. sim_logic_monotone: a one-input element
 * whose raw does not decrease as its input's grows (a sign test, a
 * comparator), so that where it takes a value is found by bisection. */
void sim_logic_linear(sim_signal *y, int i, double k, double lo, double hi);
void sim_logic_monotone(sim_signal *y);
typedef struct sim_logic_lin { int i; double k, lo, hi; } sim_logic_lin;

/* Quantize an exact wide value with src_fbits into s's format using the
 * element's modes r, o (s's format's own modes win), count an overflow on s; used by the primitives and by
 * units that model an element the primitives do not cover. */
int64_t sim_quant_into(sim_signal *s, sim_wide raw, int src_fbits,
                       sim_round r, sim_ovf o);
/* The bits of s a multiplier builds partial products for: a constant's
 * nonzero bits (a shift-and-add of that many rows), a constant shift's
 * source's (wiring, as `t` = a pixel counter with its binary point moved:
 * the other bits are constant zeros synthesis drops), else its width. */
int sim_prim_live_bits(const sim_signal *s);

/* The element record: what an element is, written once by its
 * constructor into the context (the netlist), and read by every engine:
 * the kernel's processes, the reference (sim_elem_eval), the batch's
 * set-up, the Verilog export, the interval, delay and energy models.
 * y: the output; kind is y's kind; a, b: operands (register: D; mux:
 * unused, see in); c: register enable, mux select, block-key pass (NULL:
 * none); rst and rst_raw: a register's synchronous reset; clk: the
 * register's clock; shift: sim_shift's sh; n, in: mux inputs or logic
 * inputs; fn, user: the logic function; r, o: the element's quantization
 * modes (its output format's own, else the context's); src_f, sa, sb
 * (adder, subtractor, multiplier, shifter): the exact result's fraction
 * bits, and the left shifts of a's and b's raws that align them to it
 * (what the fast paths and the export read; sim_elem_eval works them out
 * from the operands' formats on its own, so a wrong one here is caught).
 * A WIRE with a driver is a sim_assign of a. */
typedef struct sim_prim_info {
    sim_kind    kind;
    sim_signal *y;
    sim_signal *a, *b, *c, *rst, *clk;
    int64_t     rst_raw;
    int         shift;
    int         src_f, sa, sb;
    int         n;
    sim_signal *const *in;
    sim_logic_fn fn;
    void       *user;
    sim_round   r;
    sim_ovf     o;
    const char *verilog;     /* logic: sim_logic_verilog's text, or NULL */
    int         qlogic;      /* 1: rounding or saturation logic after the element (sim_area_round, sim_area_sat) */
    const sim_logic_lin *lin;  /* logic: sim_logic_linear's statement, or NULL */
    int         monotone;    /* logic: sim_logic_monotone said so */
} sim_prim_info;
/* 0 and *out filled with y's element record for a signal driven by a
 * primitive (or a constant: kind, y, trunc and wrap); -1 for an input, a
 * clock, or a signal a user process drives. */
int sim_prim_describe(const sim_signal *y, sim_prim_info *out);
/* An element's arcs with the carries k leaves (sim_delay.h): with
 * SIM_CARRY_RIPPLE those it was built with (sim_arcs_of), with PREFIX an
 * adder's, subtractor's or multiplier's worked out again for prefix
 * carries (a multiplier by a constant as Yosys's own product, not the
 * shift-and-add network a unit may have given it), with its rounding. */
sim_arcs sim_prim_arcs(const sim_signal *y, sim_carry k);
/* The signals a combinational element reads (mux: select, then inputs;
 * logic: its inputs; block key: pass, then x; others: a, b), into r,
 * which must hold 10 + in->n entries; returns how many. Not for registers
 * (they sample a, c and rst at the edge). The batch mode levelizes by it,
 * the timing analysis walks it. */
int sim_prim_reads(const sim_prim_info *in, const sim_signal **r);

/* ---- the one executable definition of every element (sim_elem_eval.c) ----
 * sim_elem_eval: the element's value for the input values in (the
 * order of sim_elem_read), computed in the plainest way: the exact
 * operation in 128-bit integers, then the one requantization
 * (sim_fx_requant) into y's format with the element's modes; no fast path
 * of any kind. *ovf is set to 1 when that quantization overflowed, else 0.
 * Returns 1 with the value in *out, or 0 when the element holds its
 * value (a register not loading; a constant). The reference kernel runs
 * every primitive through it; the tests hold every other engine to it. */
int sim_elem_eval(const sim_prim_info *e, const int64_t *in, int64_t *out, int *ovf);
/* The number of input values sim_elem_eval reads, and the inputs' current
 * values in its order into v (which holds sim_elem_nin(e)): a register's
 * D (0 if none), enable (1 if none), reset (0 if none); any other
 * element's sim_prim_reads. */
int  sim_elem_nin(const sim_prim_info *e);
void sim_elem_read(const sim_prim_info *e, int64_t *v);
#endif
