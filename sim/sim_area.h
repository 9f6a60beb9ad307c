/* sim_area.h - area estimates in gate equivalents (GE).
 *
 * One GE is the area of a 2-input NAND. The cell areas are those of the
 * NanGate 45 nm Open Cell Library (X1 drive strength) divided by NAND2_X1's
 * 0.798 um^2; see docs/area.md for the table and what the model leaves out.
 */
#ifndef SIM_AREA_H
#define SIM_AREA_H
#include <stdint.h>

#define SIM_GE_NAND2 1.00   /* NAND2_X1  0.798 um^2 */
#define SIM_GE_INV   0.67   /* INV_X1    0.532 um^2 */
#define SIM_GE_AND2  1.33   /* AND2_X1   1.064 um^2 */
#define SIM_GE_OR2   1.33   /* OR2_X1    1.064 um^2 */
#define SIM_GE_XOR2  2.00   /* XOR2_X1   1.596 um^2 */
#define SIM_GE_MUX2  2.33   /* MUX2_X1   1.862 um^2 */
#define SIM_GE_HA    3.33   /* HA_X1     2.660 um^2 */
#define SIM_GE_FA    5.33   /* FA_X1     4.256 um^2 */
#define SIM_GE_DFF   5.67   /* DFF_X1    4.522 um^2 */
#define SIM_GE_DFFR  6.67   /* DFFR_X1   5.320 um^2 (with reset) */
#define SIM_GE_BUF   1.33   /* BUF_X2    1.064 um^2 */

/* Element models, by bit widths. */
double sim_area_reg(int w, int has_en, int has_rst);   /* w flip-flops (+ a 2:1 mux per bit for enable) */
double sim_area_mux(int w, int n);                     /* (n-1) 2:1 muxes per bit */
double sim_area_bk(int w);                             /* an AND gate per bit */
double sim_area_add(int w);                            /* ripple-carry: w full adders */
double sim_area_sub(int w);                            /* w full adders + w inverters */
double sim_area_mul(int wa, int wb);                   /* array: wa*wb AND2 + (min-1)*max FA */
/* An adder or subtractor as synthesis maps it, by the bits where its
 * operands vary (sim_live_chain): a carry chain of `chain` bits where both
 * do, at the mapped GE a bit of an adder (subtractor) that wide; an
 * incrementer (a half adder a bit) over the `ext` bits above, where one
 * does; the carry alone out of the `low` bits below the output's lowest
 * bit; an incrementer over the `neg` bits below the chain where only a
 * subtrahend varies (0 - b: its inverse plus one). The other bits where
 * one operand is a constant zero below the chain are wires. The figures a bit by kind and width, measured on whole adders
 * through Yosys and the NanGate45 Liberty (scripts/add_area.sh;
 * docs/area.md, "Adders as mapped"). */
enum { SIM_ADD_ADD, SIM_ADD_SUB, SIM_ADD_CARRY, SIM_ADD_KINDS };
double sim_area_add_fit(int kind, int n);
double sim_area_addsub(int sub, int chain, int ext, int low, int neg);
/* A product by a constant k (its magnitude; neg: k < 0) as Yosys builds
 * it: no array and no canonical signed digits, a row of x (wx live bits)
 * for each 1 of k's binary form, summed as a multi-operand adder: one
 * adder of wx bits at the mapped GE a bit of a wx-bit adder
 * (sim_area_add_fit) for each row after the first, a subtractor's for one
 * of them when k < 0. Measured on y = x * k (scripts/cmul_area.sh;
 * docs/area.md, "Constant products as mapped"). */
double sim_area_cmul(int wx, uint64_t k, int neg);
/* The array for an output that keeps only some of the product's wa + wb
 * bits: drop_hi columns above its top need no logic (their partial
 * products and adders go, in proportion), drop_lo below its bottom still
 * carry into it but need no sum bit (an XOR2 less each). A narrow format
 * (--fmt mul=sI.F) so costs less than the full array. */
double sim_area_mul_cols(int wa, int wb, int drop_lo, int drop_hi);
/* A product as synthesis maps it, over the array of sim_area_mul: ABC's
 * delay-driven mapping (XOR2/XNOR2 and AOI/OAI cells, no FA_X1) makes a
 * full product larger than the array, a signed x signed one larger still
 * (Yosys sign-extends both operands), and a square (one operand twice)
 * smaller (its partial products a_i b_j and a_j b_i are one). The ratio
 * by kind at n = the narrower operand's live bits, measured on full
 * products through Yosys and the NanGate45 Liberty
 * (scripts/mul_area.sh; docs/area.md, "Products as mapped"). */
enum { SIM_MUL_UU, SIM_MUL_SU, SIM_MUL_SS, SIM_MUL_SQ_U, SIM_MUL_SQ_S, SIM_MUL_KINDS };
double sim_area_mul_fit(int kind, int n);
/* Quantization logic at an element's output of w bits: rounding to nearest
 * where it drops fraction bits (an incrementer: w half adders), saturation
 * where its exact result has `extra` integer bits more than the output
 * (extra XOR2 to detect, a MUX2 per bit to clamp). */
double sim_area_round(int w);
double sim_area_sat(int w, int extra);
/* A constant table (ROM) of n words of w bits, words[0..n-1] its raw
 * contents, as logic: a one-hot address decoder (an AND of the address
 * bits a word line, with the address inverted once) and, per output bit,
 * an OR tree over the word lines whose word has a 1 there. Synthesis would
 * minimize further: an upper estimate (docs/area.md). */
double sim_area_rom(const int64_t *words, int n, int w);
/* The buffer tree of one bit's net driving pins_sel select pins and pins
 * other pins (sim_timing_pins), GE. */
double sim_area_buffers(double pins_sel, double pins);
#endif
