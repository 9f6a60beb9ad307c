/* test_brdf_cmul.c - the constant multiplier's area: the shift-and-add
 * network for the constant's CSD digits plus the output's quantization
 * logic (rounding incrementer, saturation clamp), from the cell areas of
 * docs/area.md computed here by hand. */
#include "tests/tst.h"
#include "units/units_brdf.h"

/* Cell areas (GE) of docs/area.md, repeated so the test does not lean on
 * the model it checks. */
#define FA 5.33
#define HA 3.33
#define INV 0.67
#define MUX2 2.33
#define XOR2 2.00

static double cmul_area(sim_round r, sim_ovf o, sim_fmt fx, sim_fmt fk, int64_t kraw, sim_fmt fy)
{
    sim_ctx *c = sim_new();
    sim_set_quant(c, r, o);
    sim_scope *sc = sim_root(c);
    sim_signal *x = sim_signal_new(c, sc, "x", fx, SIM_KIND_INPUT);
    sim_signal *k = sim_const_raw(c, sc, "k", fk, kraw);
    double a = brdf_cmul(c, sc, "y", fy, x, k)->area_ge;
    sim_free(c);
    return a;
}

/* k = 5 = 101b: two CSD digits spanning 3 bits, one adder of 8 + 3 bits. */
static void cmul_trunc_wrap_is_the_adder(void)
{
    double a = cmul_area(SIM_RND_TRUNC, SIM_OVF_WRAP, unit_fmt(1, 1, 7), unit_fmt(0, 3, 0), 5, unit_fmt(1, 4, 4));
    TST_NEAR(a, 11 * FA, 1e-9);
}

/* Rounding to nearest where y drops fraction bits (7 -> 4) adds an
 * incrementer of y's 8 bits: the area the old code overwrote. */
static void cmul_rounding_adds_incrementer(void)
{
    double a = cmul_area(SIM_RND_HALF_UP, SIM_OVF_WRAP, unit_fmt(1, 1, 7), unit_fmt(0, 3, 0), 5, unit_fmt(1, 4, 4));
    TST_NEAR(a, 11 * FA + 8 * HA, 1e-9);
}

/* Saturation where y has one integer bit fewer than the product (4 -> 3):
 * one XOR to detect, a MUX2 per output bit to clamp. */
static void cmul_saturation_adds_clamp(void)
{
    double a = cmul_area(SIM_RND_TRUNC, SIM_OVF_SAT, unit_fmt(1, 1, 7), unit_fmt(0, 3, 0), 5, unit_fmt(1, 3, 4));
    TST_NEAR(a, 11 * FA + 7 * MUX2 + 1 * XOR2, 1e-9);
}

/* k = -3 = -(4 - 1): a subtractor (full adders and inverters) of 8 + 3
 * bits, plus the rounding incrementer. */
static void cmul_negative_constant(void)
{
    double a = cmul_area(SIM_RND_HALF_UP, SIM_OVF_WRAP, unit_fmt(1, 1, 7), unit_fmt(1, 3, 0), -3, unit_fmt(1, 4, 4));
    TST_NEAR(a, 11 * (FA + INV) + 8 * HA, 1e-9);
}

int main(void)
{
    TST_RUN(cmul_trunc_wrap_is_the_adder);
    TST_RUN(cmul_rounding_adds_incrementer);
    TST_RUN(cmul_saturation_adds_clamp);
    TST_RUN(cmul_negative_constant);
    TST_EXIT();
}
