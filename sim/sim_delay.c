/* sim_delay.c - gate levels and picoseconds of each element from its
 * widths. The structures are the area model's (sim_area.c): ripple-carry
 * adders, the array multiplier, MUX2 trees, D flip-flops, and the
 * rounding incrementer and saturation clamp at an element's output. The
 * adder is a ripple carry because that is what Yosys's `synth` and ABC
 * leave of `$add` (docs/timing.md measures it: 2(w-1) levels, linear in
 * w); mapped to NanGate cells its carry runs through AOI21/OAI21 pairs,
 * and the multiplier's carry-save rows through XOR2s (docs/timing.md,
 * "Against OpenSTA"). */
#include "sim/sim_delay.h"
#include "sim/sim.h"
#include <math.h>

const sim_delay SIM_DELAY_NONE = { -1, -1.0 };

static sim_delay d(int lv, double ps) { sim_delay r = { lv, ps }; return r; }

static int clog2(int n)
{
    int k = 0;
    while (k < 31 && (1 << k) < n) k++;
    return k;
}

sim_delay sim_delay_then(sim_delay a, sim_delay b)
{
    if (a.lv < 0 || b.lv < 0) return SIM_DELAY_NONE;
    return d(a.lv + b.lv, a.ps + b.ps);
}

/* The later of two ways (by ps; at a tie, more levels); NONE loses. */
static sim_delay later(sim_delay a, sim_delay b)
{
    if (a.lv < 0) return b;
    if (b.lv < 0) return a;
    return b.ps > a.ps || (b.ps == a.ps && b.lv > a.lv) ? b : a;
}

sim_arcs sim_arcs_then(sim_arcs a, sim_arcs b)
{
    sim_arcs r;
    r.ll = later(sim_delay_then(a.ll, b.ll), sim_delay_then(a.lm, b.ml));
    r.lm = later(sim_delay_then(a.ll, b.lm), sim_delay_then(a.lm, b.mm));
    r.ml = later(sim_delay_then(a.ml, b.ll), sim_delay_then(a.mm, b.ml));
    r.mm = later(sim_delay_then(a.ml, b.lm), sim_delay_then(a.mm, b.mm));
    return r;
}

sim_arcs sim_arcs_bitwise(sim_delay x) { sim_arcs r = { x, x, SIM_DELAY_NONE, x }; return r; }
sim_arcs sim_arcs_all(sim_delay x) { sim_arcs r = { x, x, x, x }; return r; }

sim_arcs sim_arcs_of(const sim_signal *s)
{
    sim_delay a[4];
    for (int i = 0; i < 4; i++) a[i] = s->dly_lv[i] < 0 ? SIM_DELAY_NONE : d(s->dly_lv[i], s->dly_ps[i]);
    sim_arcs r = { a[0], a[1], a[2], a[3] };
    return r;
}

void sim_arcs_set(sim_signal *s, sim_arcs a)
{
    const sim_delay x[4] = { a.ll, a.lm, a.ml, a.mm };
    for (int i = 0; i < 4; i++) { s->dly_lv[i] = x[i].lv; s->dly_ps[i] = x[i].lv < 0 ? -1.0 : x[i].ps; }
}

sim_delay sim_delay_reg_cq(void) { return d(0, SIM_PS_DFF_CQ); }
sim_delay sim_delay_reg_d(int has_en) { return has_en ? d(1, SIM_PS_MUX2 + SIM_PS_DFF_SU) : d(0, SIM_PS_DFF_SU); }
sim_delay sim_delay_reg_en(void) { return d(1, SIM_PS_MUX2_S + SIM_PS_DFF_SU); }
sim_delay sim_delay_reg_rst(void) { return d(1, SIM_PS_AND2 + SIM_PS_DFF_SU); }

sim_arcs sim_delay_mux(int n)
{
    int k = clog2(n);
    return sim_arcs_bitwise(k ? d(k, SIM_PS_MUX2_S + (k - 1) * SIM_PS_MUX2) : d(0, 0));
}

sim_arcs sim_delay_bk(void) { return sim_arcs_bitwise(d(1, SIM_PS_AND2)); }

sim_arcs sim_delay_add(int w)
{
    if (w <= 1) return sim_arcs_bitwise(d(1, SIM_PS_XOR2));
    sim_arcs r;
    r.ll = d(1, SIM_PS_XOR2);          /* bit 0: the operands' XOR */
    /* bit 0's carry from its operands (an AND), w-2 carries rippling as
     * the mapped AOI21/OAI21 pairs do, the top sum (an XOR) */
    r.lm = d(2 * (w - 1), SIM_PS_AND2 + (w - 2) * SIM_PS_CARRY2 / 2 + SIM_PS_XOR2);
    r.ml = SIM_DELAY_NONE;             /* low sum bits do not see high operand bits */
    r.mm = d(2, 2 * SIM_PS_XOR2);      /* the top operand bits into the top sum: two XORs */
    return r;
}

sim_delay sim_delay_prefix(int w)
{
    int n = w < 2 ? 0 : 2 * clog2(w) - 1;
    return d(2 * n, n * SIM_PS_CARRY2 / 2);
}

/* Ext bits above a carry arriving at `carry`: an incrementer by it, each
 * bit the XOR of its own with the carry ANDed with the bits below it,
 * their AND a tree (ceil(log2 ext) levels) from the operands in parallel
 * with the chain: the carry out of the chain, one AND2 (none for one
 * bit), the XOR. Into r's L -> M and M -> M. */
static void incrementer(sim_arcs *r, sim_delay carry, int ext)
{
    sim_delay top = sim_delay_then(carry, ext == 1 ? d(1, SIM_PS_XOR2) : d(2, SIM_PS_AND2 + SIM_PS_XOR2));
    int k = clog2(ext);
    r->lm = later(top, d(k + 2, k * SIM_PS_AND2 + SIM_PS_AND2 + SIM_PS_XOR2));
    r->mm = later(r->mm, d(k + 2, k * SIM_PS_AND2 + SIM_PS_AND2 + SIM_PS_XOR2));
}

sim_arcs sim_delay_add_span(int chain, int ext, int low, sim_carry kind)
{
    if (chain < 1) chain = 1;
    if (kind == SIM_CARRY_PREFIX) {
        /* one prefix adder over the low bits' carry, the chain and the
         * bits above it: bit 0's generate (an AND2), the prefix, the top
         * sum (an XOR2) */
        sim_arcs r = sim_delay_add(1);
        int w = low + chain + ext;
        if (w >= 2) {
            r.lm = sim_delay_then(sim_delay_then(d(1, SIM_PS_AND2), sim_delay_prefix(w)), d(1, SIM_PS_XOR2));
            r.mm = d(2, 2 * SIM_PS_XOR2);
        }
        return r;
    }
    sim_arcs r = sim_delay_add(chain);
    /* The carry out of `low` bits below the chain and of its own lowest
     * bit: a prefix tree of generate and propagate over those low + 1
     * bits, one AOI21/OAI21 a level (ceil(log2(low + 1)) levels), where
     * the chain alone would take that bit's AND2; the ripple then runs
     * from the chain's second bit. */
    sim_delay carry = chain < 2 ? d(1, SIM_PS_AND2) : d(2 * chain - 1, SIM_PS_AND2 + (chain - 1) * SIM_PS_CARRY2 / 2);
    if (low > 0) {
        int k = clog2(low + 1);
        sim_delay start = d(2 * k, k * SIM_PS_CARRY2 / 2);
        carry = sim_delay_then(start, d(2 * (chain - 1), (chain - 1) * SIM_PS_CARRY2 / 2));
        if (chain >= 2)
            r.lm = sim_delay_then(sim_delay_then(start, d(2 * (chain - 2), (chain - 2) * SIM_PS_CARRY2 / 2)), d(1, SIM_PS_XOR2));
    }
    /* above the chain only one operand varies: an incrementer by the
     * chain's carry (and the other operand's sign) */
    if (ext > 0) incrementer(&r, carry, ext);
    return r;
}

sim_arcs sim_delay_sub_span(int chain, int ext, int low, sim_carry kind)
{
    /* the subtrahend's inversion is free: mapped, it becomes the XNOR and
     * the inverting AOI/OAI cells of the adder (no cell of its own on
     * OpenSTA's paths through coef2's and div3's subtractors) */
    return sim_delay_add_span(chain, ext, low, kind);
}

sim_arcs sim_delay_csa(void)
{
    sim_arcs r = { d(2, 2 * SIM_PS_XOR2), SIM_DELAY_NONE, SIM_DELAY_NONE, d(2, 2 * SIM_PS_XOR2) };
    return r;
}

sim_arcs sim_delay_sub(int w) { return sim_arcs_then(sim_arcs_bitwise(d(1, SIM_PS_XOR2)), sim_delay_add(w)); }

int sim_delay_mul_rows(int rows)
{
    /* Dadda's stage count for n = rows + 1 partial products: the largest
     * height d_j (2, 3, 4, 6, 9, 13, ...; d_{j+1} = floor(3 d_j / 2))
     * below n is reached after j stages */
    int stages = 0;
    for (int h = 2; h < rows + 1; h = h * 3 / 2) stages++;
    int tree = 2 * stages + 3;
    return rows < tree ? rows : tree;
}

sim_arcs sim_delay_mul(int wa, int wb, int wy, sim_carry kind)
{
    if (wa < 1) wa = 1;
    if (wb < 1) wb = 1;
    if (wy < 1) wy = 1;
    int rows = sim_delay_mul_rows((wa < wb ? wa : wb) - 1), rip = (wa < wb ? wb : wa) - 1;
    /* Every output bit sees every operand bit; the last one settles after
     * the partial product, the carry-save rows of the narrower operand and
     * the ripple across the wider; the output's bits are the ripple's top
     * ones (quantization keeps the high part), its lowest up to wy-1
     * carries earlier. */
    sim_delay full = d(1 + 2 * rows + 2 * rip, SIM_PS_AND2 + rows * SIM_PS_XOR2 + rip * SIM_PS_CARRY2 / 2);
    int early = wy - 1 < rip ? wy - 1 : rip;
    sim_delay low = d(full.lv - 2 * early, full.ps - early * SIM_PS_CARRY2 / 2);
    if (kind == SIM_CARRY_PREFIX) {
        /* the final adder a prefix one across the product's bits (the
         * partial product's AND2, the rows, the prefix, the sum's XOR2),
         * its output bits settling together */
        full = sim_delay_then(d(1 + 2 * rows, SIM_PS_AND2 + rows * SIM_PS_XOR2), sim_delay_prefix(wa + wb));
        full = sim_delay_then(full, d(1, SIM_PS_XOR2));
        low = full;
    }
    /* An output that keeps the product's low bits (exact, as dot3's three
     * products into their sum): its lowest, bit k0, is the array's column
     * k0, which settles after k0 rows, before the reduction ends (the
     * adder after it ripples from there while the high columns reduce,
     * as ABC's mapping of dot3's sum of products does at 16 x 16 and 24 x
     * 24). Narrower, ABC finishes each product with its own final carry
     * before the sum (OpenSTA's path through dot3 at 8 x 8: five AND3/OR3
     * pairs, then the sum's XORs), so its low bits wait for the ripple as
     * a kept high part's do. Measured at 8, 16 and 24 only: the switch at
     * 16 partial products is where the reduction becomes a tree
     * (sim_delay_mul_rows). */
    int k0 = wa + wb - wy, n = wa < wb ? wa : wb;
    if (k0 < rows && n >= 16) low = d(1 + 2 * (k0 > 0 ? k0 : 0), SIM_PS_AND2 + (k0 > 0 ? k0 : 0) * SIM_PS_XOR2);
    sim_arcs r = { low, full, low, full };
    return r;
}

sim_arcs sim_delay_round(int w, sim_carry kind)
{
    if (w < 1) w = 1;
    sim_arcs r;
    r.ll = d(1, SIM_PS_HA_S);                                  /* the rounding bit into bit 0 */
    r.lm = d(w, (w - 1) * SIM_PS_AND2 + SIM_PS_HA_S);          /* its carry up the chain */
    if (kind == SIM_CARRY_PREFIX) r.lm = d(1 + clog2(w), clog2(w) * SIM_PS_AND2 + SIM_PS_HA_S);  /* or an AND2 tree */
    r.ml = SIM_DELAY_NONE;
    r.mm = d(1, SIM_PS_HA_S);
    return r;
}

sim_arcs sim_delay_sat(int extra)
{
    if (extra <= 0) return sim_arcs_bitwise(d(0, 0));
    int k = clog2(extra);
    /* overflow found from the top bits, then it selects every bit */
    sim_delay det = d(1 + k + 1, SIM_PS_XOR2 + k * SIM_PS_AND2 + SIM_PS_MUX2_S);
    sim_arcs r = { d(1, SIM_PS_MUX2), d(1, SIM_PS_MUX2), det, det };
    return r;
}

sim_arcs sim_delay_logic(int bits)
{
    int lv = bits <= 1 ? 1 : clog2(bits) + 1;
    return sim_arcs_all(d(lv, lv * SIM_PS_AND2));
}

double sim_delay_load_ps(double pins_sel, double pins, int from_reg)
{
    double c = pins_sel * SIM_FF_PIN_SEL + pins * SIM_FF_PIN;
    if (c <= SIM_FF_REF) return 0.0;
    /* the X1 driver's slope over the extra load, or, where that is more,
     * the buffered net: a stage of SIM_PS_BUF for each factor of
     * SIM_BUF_GAIN beyond the reference load (sim_delay.h) */
    double lin = (c - SIM_FF_REF) * (from_reg ? SIM_PS_PER_FF_Q : SIM_PS_PER_FF);
    double tree = SIM_PS_BUF * log(c / SIM_FF_REF) / log(SIM_BUF_GAIN);
    return tree < lin ? tree : lin;
}
