/* sim_area.c - gate-equivalent area of each element from its widths.
 * The models are the textbook structures (ripple-carry adder, array
 * multiplier, mux tree, D flip-flops, and at an element's output the
 * rounding incrementer and saturation clamp its modes need); docs/area.md
 * says what they leave out (carry-lookahead, Booth recoding, wiring). */
#include "sim/sim_area.h"
#include "sim/sim_delay.h"
#include <math.h>

/* Mapped GE a bit (scripts/add_area.sh prints them) at n = 4, 8, 16,
 * 24; linear between, the end values beyond. */
static const double add_fit[SIM_ADD_KINDS][4] = {
    { 5.583, 6.125, 6.812, 7.111 },   /* a + b */
    { 5.750, 6.917, 7.646, 7.583 },   /* a - b */
    { 2.167, 2.208, 3.292, 3.569 },   /* the carry out of a + b alone */
};

static double fit4(const double *f, int n)
{
    static const int at[4] = { 4, 8, 16, 24 };
    if (n <= at[0]) return f[0];
    for (int i = 1; i < 4; i++)
        if (n <= at[i]) return f[i - 1] + (f[i] - f[i - 1]) * (n - at[i - 1]) / (double)(at[i] - at[i - 1]);
    return f[3];
}

double sim_area_add_fit(int kind, int n) { return kind >= 0 && kind < SIM_ADD_KINDS ? fit4(add_fit[kind], n) : SIM_GE_FA; }

double sim_area_addsub(int sub, int chain, int ext, int low, int neg)
{
    double ge = chain > 0 ? chain * sim_area_add_fit(sub ? SIM_ADD_SUB : SIM_ADD_ADD, chain) : 0.0;
    if (ext + neg > 0) ge += (ext + neg) * SIM_GE_HA;
    if (low > 0) ge += low * sim_area_add_fit(SIM_ADD_CARRY, low);
    return ge;
}

double sim_area_cmul(int wx, uint64_t k, int neg)
{
    int rows = 0;
    for (; k; k &= k - 1) rows++;
    if (wx < 1 || rows < 1) return 0.0;
    /* one row of x a 1 of k; the first needs no adder, a negative k
     * makes one of the others a subtractor (or, alone, a negator) */
    double add = wx * sim_area_add_fit(SIM_ADD_ADD, wx), sub = wx * sim_area_add_fit(SIM_ADD_SUB, wx);
    if (!neg) return (rows - 1) * add;
    return sub + (rows > 1 ? (rows - 2) * add : 0.0);
}

double sim_area_reg(int w, int has_en, int has_rst)
{
    double ff = has_rst ? SIM_GE_DFFR : SIM_GE_DFF;
    return w * (ff + (has_en ? SIM_GE_MUX2 : 0.0));
}

double sim_area_mux(int w, int n) { return n > 1 ? (double)w * (n - 1) * SIM_GE_MUX2 : 0.0; }
double sim_area_bk(int w) { return w * SIM_GE_AND2; }
double sim_area_add(int w) { return w * SIM_GE_FA; }
double sim_area_sub(int w) { return w * (SIM_GE_FA + SIM_GE_INV); }

double sim_area_mul(int wa, int wb)
{
    /* wa*wb partial-product ANDs, reduced by a row of full adders as wide
     * as the wider operand for each bit of the narrower but one. */
    int lo = wa < wb ? wa : wb, hi = wa < wb ? wb : wa;
    return (double)wa * wb * SIM_GE_AND2 + (double)(lo - 1) * hi * SIM_GE_FA;
}

double sim_area_mul_cols(int wa, int wb, int drop_lo, int drop_hi)
{
    double full = sim_area_mul(wa, wb);
    if (wa < 1 || wb < 1) return full;
    int cols = wa + wb;                      /* product bits 0 .. wa + wb - 1 */
    if (drop_hi > cols) drop_hi = cols;
    if (drop_lo > cols - drop_hi) drop_lo = cols - drop_hi;
    /* columns above the output's top: their partial products (column k
     * holds min(k + 1, wa, wb, wa + wb - 1 - k) of them) and the adders
     * that reduce them, in proportion */
    int lo = wa < wb ? wa : wb, pp = 0;
    for (int k = cols - drop_hi; k < cols - 1; k++) {
        int n = k + 1;
        if (n > lo) n = lo;
        if (n > cols - 1 - k) n = cols - 1 - k;
        pp += n;
    }
    double ge = full * (1.0 - (double)pp / ((double)wa * wb));
    /* columns below the output's bottom still carry into it: each loses
     * the XOR2 of its own sum bit */
    if (drop_lo > 0) ge -= drop_lo * SIM_GE_XOR2;
    return ge > 0 ? ge : 0.0;
}

double sim_area_round(int w) { return w * SIM_GE_HA; }
double sim_area_sat(int w, int extra) { return extra > 0 ? w * SIM_GE_MUX2 + extra * SIM_GE_XOR2 : 0.0; }

double sim_area_rom(const int64_t *words, int n, int w)
{
    if (n <= 0 || w <= 0) return 0.0;
    int a = 0;
    while (a < 31 && (1 << a) < n) a++;          /* address bits */
    double ge = a * SIM_GE_INV + (a > 1 ? (double)n * (a - 1) * SIM_GE_AND2 : 0.0);
    for (int b = 0; b < w && b < 64; b++) {
        int ones = 0;
        for (int i = 0; i < n; i++) ones += (int)(((uint64_t)words[i] >> b) & 1u);
        if (ones > 1) ge += (ones - 1) * SIM_GE_OR2;
    }
    return ge;
}

/* Mapped GE / sim_area_mul(n, n) of a full n x n product (scripts/mul_area.sh
 * prints them), at n = 4, 8, 16, 24; linear between, the end values
 * beyond. A square's first point is its 8-bit one: ABC makes a 4-bit
 * square two-level logic, no array at all. */
static const double mul_fit[SIM_MUL_KINDS][4] = {
    { 1.068, 1.218, 1.245, 1.284 },   /* unsigned x unsigned */
    { 1.032, 1.279, 1.263, 1.292 },   /* signed x unsigned (zero-extended by a bit) */
    { 1.107, 1.481, 1.426, 1.419 },   /* signed x signed */
    { 0.728, 0.728, 0.979, 1.025 },   /* unsigned square */
    { 1.040, 1.040, 1.137, 1.171 },   /* signed square */
};

double sim_area_mul_fit(int kind, int n) { return kind >= 0 && kind < SIM_MUL_KINDS ? fit4(mul_fit[kind], n) : 1.0; }

double sim_area_buffers(double pins_sel, double pins)
{
    double u = (pins_sel * SIM_FF_PIN_SEL + pins * SIM_FF_PIN) / SIM_FF_REF;
    if (u <= 1.0) return 0.0;
    return ceil((u - 1.0) / (SIM_BUF_GAIN - 1.0)) * SIM_GE_BUF;
}
