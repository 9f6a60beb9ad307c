/* unit_net.h - datapaths written once, walked three ways.
 *
 * The divide-by-3 network (Fig. 7), the coefficient units (Fig. 8) and the
 * coefficient part of the interpolators are constant shifts, adders and
 * subtractors; the Horner datapath (Fig. 9) adds multipliers, multiplexers,
 * a block key and registers. A unit's construction code is written once
 * against this API and walked
 *  - to build: the elements go into a simulation (unet_hw);
 *  - to bound: no simulation; every value carries its worst-case error
 *    |hardware - ideal| for the formats given (an element's error is its
 *    operands' errors times their gains plus its own unit_qerr);
 *  - to choose formats (unet_rule): the default rule picks each signal's
 *    format as the walk reaches it, from the value's exact range over the
 *    inputs' ranges and its worst-case error.
 * So the bound and the default formats come from the same structure as the
 * hardware, for any --fmt override, with no hand formula per output.
 *
 * A value's ideal (exact) meaning is a linear form of the unit's inputs,
 * with /3 replaced by the network's own factor. Its range over a box of
 * input ranges is exact: the max of sum c_i x_i is sum max(c_i lo_i, c_i hi_i).
 * A product is no linear form: a walk with multipliers chooses formats by
 * a fixed rule (unet_fixed), not from ranges.
 *
 * A sequential datapath is walked the same way, one clock at a time: a
 * register (unet_reg) is a value the walk updates at unet_reg_set, and a
 * multiplexer (unet_mux) follows the input the clock's control word
 * selects. Building, the first clock's walk makes the hardware (the
 * multiplexer gets every input and its select signal, the register its
 * input) and the caller stops; bounding, the walk goes through every clock
 * of an item and each value carries its worst-case error.
 */
#ifndef UNIT_NET_H
#define UNIT_NET_H
#include "units/unit.h"
#include <stddef.h>

#define UNET_MAXIN 4    /* inputs a network's values are linear forms of */

typedef struct unet_val {
    sim_signal *s;                  /* the element's output; NULL unless building */
    sim_fmt     f;                  /* its format */
    double      lin[UNET_MAXIN];    /* ideal value = sum lin[i] * input i */
    double      err;                /* worst-case |hardware - ideal| */
    /* The part of err this element added by quantizing its own result
     * (err = its operands' part + q): what a unit whose bound refines
     * the walk's (d_approx's clamp) reads of each element. */
    double      q;
    /* Fraction bits the value can really have: its format's, or fewer
     * when its operands have fewer (a wide register holding a coarse
     * value). A requantization drops bits only below these, so widening a
     * signal moves a quantization downstream rather than adding one
     * (with trunc, the bound never grows). */
    int         eff;
    /* Bounds on |hardware value| (mag: the format's largest magnitude, or
     * less where the caller knows it, e.g. t in [0, 1], and copies keep
     * it) and on |ideal value| (imag: from the inputs' through the
     * operations). A product's error uses them: a_hw b_hw - a b =
     * (a_hw - a) b + a_hw (b_hw - b), so |.| <= err_a imag_b +
     * min(mag_a, imag_a + err_a) err_b. */
    double      mag, imag;
} unet_val;

typedef struct unet {
    sim_ctx         *c;             /* NULL: walk without building */
    sim_scope       *sc;            /* where elements are built (callers may switch it) */
    const unit_desc *u;             /* signal name -> index into fm */
    unit_fmts        fm;            /* formats by signal index (chosen ones land here) */
    sim_round        r;
    sim_signal      *clk;           /* registers' clock (unet_clock) */
    /* The default rule, when choose is 1 (from ranges, shift-and-add
     * only) or UNET_FIXED (unet_fixed: every element `dflt`, a pipeline
     * register its source's format): */
    int              choose;
    sim_fmt          dflt;
    int              width;         /* W: outputs get sI.(W-I) */
    int              fcap;          /* fraction bits a right shift may keep at most */
    double           lo[UNET_MAXIN], hi[UNET_MAXIN];   /* input ranges */
    unsigned char    chosen[UNIT_MAX_SIGS];
    char             why[160];      /* first construction error ("" if none) */
} unet;

/* A walk of unit u with formats fm (NULL: all zero, for unet_rule) and
 * rounding r; it builds nothing until unet_hw. */
void unet_init(unet *n, const unit_desc *u, const unit_fmts *fm, sim_round r);
/* Build elements into c, scope sc, as the walk goes. */
void unet_hw(unet *n, sim_ctx *c, sim_scope *sc);
/* Choose formats by the default rule: inputs i range over [lo, hi]; an
 * output gets W bits, sI.(W-I); an internal keeps every fraction bit its
 * operation produces (lossless: a left shift by k needs k fewer, an adder
 * the larger of its operands'), right shifts at most fcap; I is the
 * fewest integer bits that hold the range widened by the value's
 * worst-case error, unsigned where the value cannot go negative (shifts
 * and sums of unsigned values, not differences). Input formats are set in
 * n->fm by the caller before the walk. */
void unet_rule(unet *n, int width, const double *lo, const double *hi, int nin);

/* The fixed rule (multiplier datapaths): every element gets format dflt,
 * a register of a value (unet_reg_of) its value's format. */
#define UNET_FIXED 2
void unet_fixed(unet *n, sim_fmt dflt);
/* The clock of the registers the walk builds. */
void unet_clock(unet *n, sim_signal *clk);

/* Index of signal name in the unit; a name the unit does not declare is
 * a bug in the unit (unit_sig_must: reported, aborted). */
int unet_sig(unet *n, const char *name);

/* Input k of the unit: signal name, format from n->fm, exact (err 0). */
unet_val unet_input(unet *n, const char *name, int k);
/* Wrap an existing signal (built elsewhere) as input k. */
unet_val unet_wrap(sim_signal *s, sim_fmt f, int k);
/* Elements; `sig` indexes the format (several elements may share one, e.g.
 * a sub-network), `name` is the element's signal name in n->sc. */
unet_val unet_shift(unet *n, int sig, const char *name, unet_val x, int k);   /* x * 2^k */
unet_val unet_add(unet *n, int sig, const char *name, unet_val a, unet_val b);
unet_val unet_sub(unet *n, int sig, const char *name, unet_val a, unet_val b);
/* a * b, quantized to its format (a fixed-rule or given-format walk). */
unet_val unet_mul(unet *n, int sig, const char *name, unet_val a, unet_val b);
/* x * k for a constant k, built by make (e.g. brdf_cmul, a shift-and-add
 * network: make(c, sc, name, format, x, k)) or, when make is NULL, by a
 * multiplier; bounded as unet_mul(k, x) bounds k * x: k_hw x_hw - k x =
 * (k_hw - k) x + k_hw (x_hw - x). */
typedef sim_signal *(*unet_make2)(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt f,
                                  sim_signal *a, sim_signal *b);
unet_val unet_cmul(unet *n, int sig, const char *name, unet_val x, unet_val k, unet_make2 make);
/* Multiplexer: building, select sel picks among v[0..nv-1]; a walk that
 * does not build follows v[k], the input this clock selects. */
unet_val unet_mux(unet *n, int sig, const char *name, sim_signal *sel, int nv, const unet_val *v, int k);
/* Block key: x where pass is 1, else 0 (the walk: on). */
unet_val unet_bk(unet *n, int sig, const char *name, sim_signal *pass, unet_val x, int on);
/* A register with its input connected later (a feedback loop): 0, exact,
 * before the first clock. unet_reg_set connects d (building) and makes the
 * walk's r the value r holds after the clock edge. */
unet_val unet_reg(unet *n, int sig, const char *name);
void     unet_reg_set(unet *n, unet_val *r, unet_val d);
/* A pipeline register of d (in the fixed rule: d's format). */
unet_val unet_reg_of(unet *n, int sig, const char *name, unet_val d);

/* ---- the divide-by-3 network (unit_div3.c) ---- */

enum { DIV3_PAPER = 0, DIV3_QUARTER = 1 };
#define DIV3_MAX_TERMS 20
#define DIV3_PAPER_TERMS 3     /* the paper's network: x/2 - x/8 - x/32 - x/128 */

/* The parameter rows of a unit built around /3 networks (coef3_n1,
 * coef3_n2, interp3, span3, span23): one definition, so that the range,
 * default and help of terms and series are the same in every such unit
 * (div3 itself words its own). */
#define DIV3_P_TERMS { "terms", UNIT_P_INT, offsetof(unit_cfg, terms), 1, DIV3_MAX_TERMS, DIV3_PAPER_TERMS, NULL, \
                       "terms of each /3 network (see div3); 3 is the paper's" }
#define DIV3_P_SERIES { "series", UNIT_P_ENUM, offsetof(unit_cfg, series), 0, 1, DIV3_PAPER, "paper quarter", \
                        "series of each /3 network (see div3)" }

/* Fraction bits the network's terms keep beyond x's: enough that the
 * truncations of its terms add up to at most one LSB of x. */
int div3_guard_bits(int terms);

/* x/3 by the network, built in n->sc: terms t0 (x/2, paper only),
 * t1..tN, partial sums s1..sN (quarter: s2..sN) and a view y of the last.
 * group >= 0: every element takes the format of signal `group` (a
 * sub-network inside a larger unit); group < 0: each takes the format of
 * the unit's signal of the same name (the div3 unit). */
unet_val div3_walk(unet *n, unet_val x, int terms, int series, int group);
#endif
