/* test_speed_hw.c - the hardware speed claims (testbench/tb_speed_hw.c)
 * against the algebra of the units they are built from: the restoring
 * divider takes a clock per quotient bit (W at width W), a power x^g on
 * the one-multiplier engine log2 g clocks (1 for the squarer, 4 for
 * d_approx's and ward_approx's 16th power), so exact D without its
 * exponential (squarer, divider, squarer, divider) takes 2 + 2W clocks,
 * Ward's exp term (squarer, divider) 1 + W, and with the stages
 * overlapped an item every W clocks. The verdicts follow from those. */
#include "tests/tst.h"
#include "testbench/tb_speed_hw.h"

static void chains_match_algebra(void)
{
    tb_speed_hw h;
    tb_speed_hw_measure(16, &h);
    TST_CHECK(h.ok, "every unit ran");
    TST_EQ_INT((long)h.div.clocks, 16);
    TST_EQ_INT((long)h.sq.clocks, 1);
    TST_EQ_INT((long)h.d16.clocks, 4);
    TST_EQ_INT((long)h.ward16.clocks, 4);
    TST_NEAR(h.exact_d_clocks, 2 + 2 * 16, 0);
    TST_NEAR(h.exact_w_clocks, 1 + 16, 0);
    /* area: one instance a stage, each as simulated */
    TST_NEAR(h.exact_d_area, 2 * h.sq.area + 2 * h.div.area, 1e-9);
    TST_NEAR(h.exact_w_area, h.sq.area + h.div.area, 1e-9);
    TST_CHECK(h.sq.area > 0 && h.div.area > 0, "areas measured");
    for (int i = 0; i < TB_SPEED_NW; i++) {
        double W = tb_speed_widths[i];
        TST_NEAR(h.lad_d[i], (2 + 2 * W) / 4, 1e-12);
        TST_NEAR(h.lad_w[i], (1 + W) / 4, 1e-12);
        TST_NEAR(h.ovl_d[i], W / 4, 1e-12);
        TST_NEAR(h.ovl_w[i], W / 4, 1e-12);
    }
    claim_result rows[2];
    TST_EQ_INT((long)tb_speed_hw_rows(&h, rows), 2);
    TST_NEAR(rows[0].measured, (2 + 2 * 16.0) / 4, 1e-12);
    TST_NEAR(rows[1].measured, (1 + 16.0) / 4, 1e-12);
    /* one after another: D (2 + 2W)/4 >= 4.34 and Ward (1 + W)/4 > 2 at
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
