/* sim_delay.h - delay of each element from its bit widths, in gate levels
 * and in picoseconds, beside the area model (sim_area.h).
 *
 * A gate level is one 2-input cell (AND2, XOR2, MUX2; an adder cell's
 * carry counts two, the AND and the OR of its majority): the unit of
 * Yosys's `ltp` over generic gates, so the two can be compared. The
 * picoseconds are those of the NanGate 45 nm Open Cell Library, typical
 * corner (1.10 V, 25 C), X1 cells, read from its Liberty file
 * (NangateOpenCellLibrary_typical.lib) at one table point: input slew
 * index_1[2] = 17.2 ps and the load index_2 point nearest a fanout of
 * four (about 7.5 fF; 6.3-6.5 fF in the tables of the small cells that
 * stop at 25 fF). Each constant is the worse of cell_rise and cell_fall
 * of the named arc; a carry is the pair of inverting cells mapped
 * netlists ripple it through. A net that drives more than the tables'
 * load adds the driver's slope times the excess (sim_delay_load_ps).
 * docs/timing.md has the table, the comparison with OpenSTA on mapped
 * netlists that set these choices, and what the model leaves out.
 *
 * Bits of a word need not arrive together: a ripple-carry adder's sum
 * bits settle from the least significant up, and an adder fed by another
 * starts on its low bits while the high ones still ripple (so two chained
 * W-bit adders take about 2W levels, not 4W, as in synthesized gates).
 * So a signal has two arrival times, of its least (L) and most (M)
 * significant bit, and an element four arcs: from an input's L or M to
 * its own L or M.
 */
#ifndef SIM_DELAY_H
#define SIM_DELAY_H

#define SIM_PS_AND2      49.2   /* AND2_X1  A2 -> ZN, rise, 7.57 fF */
#define SIM_PS_XOR2      59.8   /* XNOR2_X1 B -> ZN (A = 0), rise, 6.50 fF (stands for XOR2_X1) */
#define SIM_PS_MUX2      74.7   /* MUX2_X1  B -> Z (A = S = 1), fall, 7.56 fF */
#define SIM_PS_MUX2_S    73.1   /* MUX2_X1  S -> Z (A = 1, B = 0), fall, 7.56 fF */
/* A ripple carry through two bits as mapped netlists build it: an AOI21
 * then an OAI21, the carry on a B input of each; the worse polarity
 * (AOI21_X1 B2 -> ZN rise 57.8 at 6.33 fF, OAI21_X1 B2 -> ZN fall 29.4 at
 * 6.51 fF; the other, 27.1 + 59.6 = 86.7). */
#define SIM_PS_CARRY2    87.2
#define SIM_PS_HA_S      71.1   /* HA_X1    B -> S (A = 0), rise, 6.31 fF */
#define SIM_PS_DFF_CQ   104.7   /* DFF_X1   CK -> Q, rise, 7.59 fF */
#define SIM_PS_DFF_SU    39.8   /* DFF_X1   setup_rising on D, fall_constraint, D and CK slew 44.9 ps */

/* Load: every figure above is at about 7.5 fF (SIM_FF_REF); a net that
 * drives more pins is slower by the driver's slope times the extra load.
 * The slope is the rise table's between its 3.3 and 13.4 fF points of the
 * NOR2_X1, AOI21_X1, OAI21_X1 and XOR2_X1 the mapped netlists drive their
 * wide nets with (5.09 to 5.12 ps/fF at 17.2 ps slew), DFF_X1's for a
 * register's Q (CK -> Q rise, 7.53 to 30.1 fF: 2.44 ps/fF). Pins: MUX2_X1
 * S (1.92 fF) for a select, enable or key bit, AOI21_X1 B1 (1.65 fF) for
 * any other. */
#define SIM_FF_REF        7.5
#define SIM_PS_PER_FF     5.09
#define SIM_PS_PER_FF_Q   2.44
#define SIM_FF_PIN_SEL    1.92
#define SIM_FF_PIN        1.65
/* A net beyond the reference load is, in the flow `synth --sta` runs, no
 * longer driven by one X1 cell: ABC's `buffer` splits it into a tree of
 * buffers and upsizes its driver, so its delay grows with the log of its
 * load, not linearly: a stage of BUF_X1 at a fanout of four (A -> Z, fall,
 * 17.2 ps slew, 7.58 fF: 40.6 ps) for each factor of four of load
 * (sim_delay_load_ps charges the smaller of the two). */
#define SIM_PS_BUF       40.6
#define SIM_BUF_GAIN      4.0

/* The carries a flow leaves in the adders (and a product's final adder,
 * a rounding incrementer): Yosys's `synth` builds every one as a
 * Brent-Kung prefix adder ($lcu in its techmap.v), which ABC's default
 * script restructures into the AOI21/OAI21 ripple the constants above
 * were read for (RIPPLE), and its light script maps as it is (PREFIX: a
 * carry across w bits through 2 ceil(log2 w) - 1 AOI21/OAI21 cells,
 * SIM_PS_CARRY2 / 2 each). docs/timing.md, "Carries as the flow leaves
 * them". */
typedef enum sim_carry { SIM_CARRY_RIPPLE = 0, SIM_CARRY_PREFIX } sim_carry;

/* Levels and picoseconds along an arc; lv < 0: no arc. */
typedef struct sim_delay { int lv; double ps; } sim_delay;
extern const sim_delay SIM_DELAY_NONE;
/* a then b, in series (NONE if either is). */
sim_delay sim_delay_then(sim_delay a, sim_delay b);

/* An element's four arcs: ll from an input's least significant bit to
 * the output's, lm to the output's most significant bit, ml and mm from
 * the input's most significant bit. */
typedef struct sim_arcs { sim_delay ll, lm, ml, mm; } sim_arcs;
/* a then b: the max-plus product (each arc the later of the two ways
 * through the middle signal's bits). */
sim_arcs sim_arcs_then(sim_arcs a, sim_arcs b);
/* d from every bit to the same bit (multiplexers, block keys: bitwise). */
sim_arcs sim_arcs_bitwise(sim_delay d);
/* d from every bit to every bit (logic that mixes them). */
sim_arcs sim_arcs_all(sim_delay d);
/* The arcs on a signal (sim_signal.dly_*), and set them. */
struct sim_signal;
sim_arcs sim_arcs_of(const struct sim_signal *s);
void     sim_arcs_set(struct sim_signal *s, sim_arcs a);

/* Register: from the clock edge to q (clock-to-q, no level, every bit);
 * and the extra time its inputs need before the edge: D (through the
 * load-enable MUX2 when it has one), the enable (the MUX2's select), a
 * synchronous reset (one AND2 forcing D), each plus the flip-flop's
 * setup. */
sim_delay sim_delay_reg_cq(void);
sim_delay sim_delay_reg_d(int has_en);
sim_delay sim_delay_reg_en(void);
sim_delay sim_delay_reg_rst(void);

sim_arcs sim_delay_mux(int n);             /* ceil(log2 n) MUX2, the first from its select */
sim_arcs sim_delay_bk(void);               /* an AND2 */
sim_arcs sim_delay_add(int w);             /* ripple carry, w bits: 2(w-1) levels from L to M, SIM_PS_CARRY2 per 2 bits */
sim_arcs sim_delay_sub(int w);             /* a conditional inverter (XOR2), then the adder */
/* An adder whose operands both vary over only `chain` of its bits (low
 * bits where one operand is constant zero need no carry): the ripple
 * over those, then `ext` bits above them where only one operand varies
 * (an incrementer by the carry, as synthesis builds it once constants
 * are propagated: sim_live.h); `low` bits below the output's lowest that
 * only carry into the chain, by a prefix tree. sim_delay_add(w) is chain
 * w, ext 0, low 0, RIPPLE. With PREFIX the carry runs across the
 * low + chain + ext bits as one prefix adder. */
sim_arcs sim_delay_add_span(int chain, int ext, int low, sim_carry k);
sim_arcs sim_delay_sub_span(int chain, int ext, int low, sim_carry k);
/* An adder or subtractor whose one reader is another: synthesis (Yosys's
 * alumacc) makes the chain one multi-operand adder, a carry-save stage
 * each (a full adder's sum, two XOR2, bit to bit: no carry ripples) and
 * one ripple at the end, the last adder's. */
sim_arcs sim_delay_csa(void);
/* Array multiplier wa x wb quantized to wy bits (wa, wb the operands'
 * live bits: sim_prim.c): a partial product (AND2), min(wa, wb) - 1
 * carry-save rows (an XOR2 each), a max(wa, wb) - 1 bit ripple-carry
 * adder whose sum bits, the output's, settle from L up; PREFIX: a prefix
 * adder across the wa + wb bits of the product, every bit at once. */
sim_arcs sim_delay_mul(int wa, int wb, int wy, sim_carry k);
/* The XOR levels of the carry-save reduction of rows + 1 partial
 * products: one a row, as the array's, up to 15 rows (16 x 16); beyond,
 * ABC's delay-driven mapping reduces them as a tree: two XOR levels per
 * Dadda stage (3:2 counters) plus three, min(rows, 2 stages + 3). Fitted
 * to a registered W x W product through the same flow (W = 4 to 32,
 * docs/timing.md, "Wide multipliers"). */
int sim_delay_mul_rows(int rows);
sim_arcs sim_delay_round(int w, sim_carry k);  /* incrementer: a w-bit half-adder chain (PREFIX: its carry an AND2 tree) */
/* A carry across w bits (w >= 2) as a prefix adder: 2 ceil(log2 w) - 1
 * cells, two levels each. */
sim_delay sim_delay_prefix(int w);
sim_arcs sim_delay_sat(int extra);         /* detect (XOR2, OR tree) from the top bits, clamp (MUX2 select) */
/* A logic element of `bits` input bits in all: a balanced tree of 2-input
 * gates over them, ceil(log2 bits) + 1 levels of AND2 (an estimate: the
 * elements are small decoders and comparators). */
sim_arcs sim_delay_logic(int bits);
/* The extra delay of a net whose bit drives pins_sel select-like and
 * pins other inputs, beyond the figures' load (from_reg: a register's Q). */
double sim_delay_load_ps(double pins_sel, double pins, int from_reg);
#endif
