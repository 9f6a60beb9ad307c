/* test_speed_hw.c - the hardware speed claims (testbench/study/tb_speed_hw.c)
 * against the algebra of the units they are built from: the restoring
 * divider takes a clock per quotient bit (W at width W), a power x^g on
 * the one-multiplier engine log2 g clocks (1 for the squarer, 4 for
 * d_approx's and ward_approx's 16th power). Wired, squarer and divider
 * take 1 + 1 + W clocks an item (the operand registers load one clock
 * after the squarer's result): Ward's exp term; exact D adds a squarer and
 * a divider, 1 + W more; with the stages overlapped an item every W
 * clocks. The verdicts follow from those. */
#include "tests/tst.h"
#include "testbench/study/tb_speed_hw.h"

static void chains_match_algebra(void)
{
    tb_speed_hw h;
    tb_speed_hw_measure(16, &h);
    TST_CHECK(h.ok, "every unit ran");
    TST_EQ_INT((long)h.div.clocks, 16);
    TST_EQ_INT((long)h.sq.clocks, 1);
    TST_EQ_INT((long)h.d16.clocks, 4);
    TST_EQ_INT((long)h.ward16.clocks, 4);
    TST_NEAR(h.wired.clocks, 1 + 1 + 16, 0);
    TST_NEAR(h.exact_w_clocks, 1 + 1 + 16, 0);
    TST_NEAR(h.exact_d_clocks, (1 + 1 + 16) + (1 + 16), 0);
    /* area: the wired design holds both units and its glue */
    TST_CHECK(h.wired.area > h.sq.area + h.div.area, "wired %g GE, units %g + %g", h.wired.area, h.sq.area,
              h.div.area);
    TST_NEAR(h.exact_w_area, h.wired.area, 1e-9);
    TST_NEAR(h.exact_d_area, h.wired.area + h.sq.area + h.div.area, 1e-9);
    /* it computes (1 - c^2)/c^2: a truncating divider and a truncated c^2 */
    TST_CHECK(h.wired_err_lsb <= 1.5, "wired chain error %g LSB", h.wired_err_lsb);
    for (int i = 0; i < TB_SPEED_NW; i++) {
        double W = tb_speed_widths[i];
        TST_NEAR(h.lad_d[i], (2 + W + 1 + W) / 4, 1e-12);
        TST_NEAR(h.lad_w[i], (2 + W) / 4, 1e-12);
        TST_NEAR(h.ovl_d[i], W / 4, 1e-12);
        TST_NEAR(h.ovl_w[i], W / 4, 1e-12);
    }
    claim_result rows[2];
    TST_EQ_INT((long)tb_speed_hw_rows(&h, rows), 2);
    TST_NEAR(rows[0].measured, (3 + 2 * 16.0) / 4, 1e-12);
    TST_NEAR(rows[1].measured, (2 + 16.0) / 4, 1e-12);
    /* one after another: D (3 + 2W)/4 >= 4.34 and Ward (2 + W)/4 > 2 at
     * W = 8, 16, 24; overlapped: W/4 = 2 at W = 8 misses both */
    TST_CHECK(claims_verdict_kind(rows[0].verdict) == 0 && strstr(rows[0].verdict, "one after another"),
              "d16: %s", rows[0].verdict);
    TST_CHECK(claims_verdict_kind(rows[1].verdict) == 0 && strstr(rows[1].verdict, "one after another"),
              "ward: %s", rows[1].verdict);
}

int main(void)
{
    TST_RUN(chains_match_algebra);
    TST_EXIT();
}
