/* test_speed_hw.c - the hardware speed claims (testbench/study/tb_speed_hw.c)
 * against the algebra of the units they are built from, and against the
 * units' own figures as `shadesim run --json` prints them.
 * Clocks: the restoring divider takes a clock per quotient bit (W at
 * width W), a power x^g on the one-multiplier engine log2 g clocks (1 for
 * the squarer, 4 for d_approx's and ward_approx's 16th power). Wired,
 * squarer and divider take 1 + 1 + W clocks an item (the operand registers
 * load one clock after the squarer's result): Ward's exp term; exact D adds
 * a squarer and a divider, 1 + W more.
 * Time: each design runs at the clock its critical path allows; a chain is
 * one clocked design, at its slowest stage's period. The rows' ratios are
 * recomputed here as (clocks x period) over (clocks x period) from the
 * approximations' and the stages' `run --json` figures. */
#include "tests/tst.h"
#include "testbench/study/tb_speed_hw.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* `shadesim run ARGS --json`: its cycles per item and critical path, ps. */
static int run_json(const char *args, double *clocks, double *ps)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "%s run %s --json 2>/dev/null", tst_shadesim(), args);
    FILE *p = popen(cmd, "r");
    if (!p) return -1;
    static char out[1 << 16];
    size_t len = fread(out, 1, sizeof out - 1, p);
    out[len] = 0;
    int st = pclose(p);
    const char *c = strstr(out, "\"cycles_per_item\": "), *k = strstr(out, "\"critical_path\": {");
    const char *s = k ? strstr(k, "\"ps\": ") : NULL;
    if (st != 0 || !c || !s) return -1;
    *clocks = strtod(c + strlen("\"cycles_per_item\": "), NULL);
    *ps = strtod(s + strlen("\"ps\": "), NULL);
    return 0;
}

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
    /* clocks alone along the ladder: the old rows' figures */
    for (int i = 0; i < TB_SPEED_NW; i++) {
        double W = tb_speed_widths[i];
        TST_NEAR(h.clk_d[i], (2 + W + 1 + W) / 4, 1e-12);
        TST_NEAR(h.clk_w[i], (2 + W) / 4, 1e-12);
    }
}

/* The rows in time, from the units' own run --json figures. */
static void rows_in_time(void)
{
    tb_speed_hw h;
    tb_speed_hw_measure(16, &h);
    double cd, pd, cw, pw, cq, pq, cv, pv;
    int bad = run_json("d_approx --width 16", &cd, &pd) | run_json("ward_approx --width 16", &cw, &pw)
            | run_json("powg --param g=2 --width 16", &cq, &pq) | run_json("div --width 16", &cv, &pv);
    TST_CHECK(!bad, "run --json of d_approx, ward_approx, powg, div");
    if (bad) return;
    /* the units' periods are theirs as run prints them */
    TST_NEAR(h.d16.period_ps, pd, 0);
    TST_NEAR(h.ward16.period_ps, pw, 0);
    TST_NEAR(h.sq.period_ps, pq, 0);
    TST_NEAR(h.div.period_ps, pv, 0);
    /* the wired design holds both units: its path is at least theirs */
    TST_CHECK(h.wired.period_ps >= fmax(pq, pv), "wired %g ps < units' %g, %g", h.wired.period_ps, pq, pv);
    double chain = fmax(h.wired.period_ps, fmax(pq, pv));
    TST_NEAR(h.exact_w_period_ps, h.wired.period_ps, 0);
    TST_NEAR(h.exact_d_period_ps, chain, 0);
    claim_result rows[2];
    TST_EQ_INT((long)tb_speed_hw_rows(&h, rows), 2);
    double want_d = (1 + 1 + 16 + cq + cv) * chain / (cd * pd);
    double want_w = (1 + 1 + 16) * h.wired.period_ps / (cw * pw);
    TST_NEAR(rows[0].measured, want_d, 1e-12 * want_d);
    TST_NEAR(rows[1].measured, want_w, 1e-12 * want_w);
    /* the divider's step is shorter than d_approx's multiplier: time gives
     * less than clocks */
    TST_CHECK(rows[0].measured < 35.0 / 4 && rows[1].measured < 18.0 / 4, "time %g, %g", rows[0].measured,
              rows[1].measured);
    /* the ladder's ratio at 16 is the row's; both grow with the width */
    TST_NEAR(h.lad_d[1], rows[0].measured, 1e-12);
    TST_NEAR(h.lad_w[1], rows[1].measured, 1e-12);
    for (int i = 1; i < TB_SPEED_NW; i++)
        TST_CHECK(h.lad_d[i] > h.lad_d[i - 1] && h.lad_w[i] > h.lad_w[i - 1], "ladder not growing at %d", i);
    /* the verdict from the ladder: every width, or the wider ones, or none */
    int nd = 0, nw = 0;
    for (int i = 0; i < TB_SPEED_NW; i++) { nd += h.lad_d[i] >= 4.34; nw += h.lad_w[i] > 2.0; }
    TST_CHECK(nd == 0 ? !strcmp(rows[0].verdict, CLAIM_FAILS) : claims_verdict_kind(rows[0].verdict) >= 0,
              "d16: %d widths, %s", nd, rows[0].verdict);
    TST_CHECK(nw == 0 ? !strcmp(rows[1].verdict, CLAIM_FAILS) : claims_verdict_kind(rows[1].verdict) >= 0,
              "ward: %d widths, %s", nw, rows[1].verdict);
    if (nd == 2) TST_CHECK(strstr(rows[0].verdict, "16 bits and more") != NULL, "d16: %s", rows[0].verdict);
    if (nw == 2) TST_CHECK(strstr(rows[1].verdict, "16 bits and more") != NULL, "ward: %s", rows[1].verdict);
}

int main(void)
{
    TST_RUN(chains_match_algebra);
    TST_RUN(rows_in_time);
    TST_EXIT();
}
