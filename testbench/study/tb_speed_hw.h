/* tb_speed_hw.h - the papers' speed claims (D16 4.34x faster than D, the
 * Ward approximation more than 2x) measured in hardware: built units
 * against built units, each simulated clock by clock at a width
 * (tb_speed_hw.c; docs/brdf.md, "Speed claims in hardware").
 *
 * The approximations are units (d_approx, ward_approx). The exact
 * functions are chains of units:
 *   exact D   c^2 (powg g=2) -> (1 - c^2)/c^2 (div) -> [exp] ->
 *             c^4 (powg g=2 on c^2) -> exp(.)/c^4 (div)
 *   Ward exp  c^2 (powg g=2) -> (1 - c^2)/c^2 (div) -> [exp]
 * The first two stages are wired into one design (operand registers and a
 * valid flag between them) and simulated end to end; exact D adds the
 * last two stages' clocks and areas, each unit simulated alone (their glue
 * not counted).
 * Speed is time per item: clocks x the clock period each design allows
 * (its critical path, the delay model of docs/timing.md); the designs
 * differ in period (a divider step is shorter than a multiplier), so
 * clocks alone overstate the gain.
 * The exponential is the one piece without a unit: it is left out of the
 * measured figures (so they are lower bounds for the exact functions) and
 * only named beside them. The subtractor 1 - c^2 and the constant factors
 * (1/m^2, 1/(4 m^2)) are combinational: area, no clocks; not counted. */
#ifndef TB_SPEED_HW_H
#define TB_SPEED_HW_H
#include "testbench/tb.h"
#include "testbench/study/tb_ref_claims.h"

/* One unit run on its reference model's vectors at a width. */
typedef struct tb_hw_point {
    const char *unit;
    char   label[64];
    double clocks, area, max_err_peak;   /* max |hw - phys| / peak (phys given) */
    double period_ps;                    /* its critical path (docs/timing.md): the clock it allows */
    int    ok;
    int    unbounded;                    /* the unit derives no error bound at these formats */
} tb_hw_point;

typedef double (*tb_hw_phys)(double c, const unit_cfg *cfg);
/* Run unit `name` with cfg on nvec vectors (0: the generator's default);
 * with phys, the largest |hw - phys(c)| / peak. 0, or -1 (pt->ok 0). */
int tb_hw_point_run(const char *name, const unit_cfg *cfg, size_t nvec, tb_hw_phys phys, double peak,
                    tb_hw_point *pt);

#define TB_SPEED_NW 3                    /* the widths of the ladder: 8, 16, 24 */
extern const int tb_speed_widths[TB_SPEED_NW];

typedef struct tb_speed_hw {
    int width, n_d, n_w;                 /* pow_n's exponents: 2/m^2 - 4 and 2/a^2 */
    tb_hw_point d16, ward16, sq, div, pow_d, pow_w;
    tb_hw_point wired;                   /* Ward's exp argument wired (tb_speed_ward_chain) */
    double wired_err_lsb;                /* its largest error, quotient LSBs */
    /* the exact functions' chains without the exponential, measured; a
     * chain is one clocked design, so its period is its slowest stage's */
    double exact_d_clocks, exact_d_area, exact_w_clocks, exact_w_area;
    double exact_d_period_ps, exact_w_period_ps;
    /* time ratios (clocks x period per item, exact over approximation) at
     * tb_speed_widths, and the clock ratios alone beside them */
    double lad_d[TB_SPEED_NW], lad_w[TB_SPEED_NW];
    double clk_d[TB_SPEED_NW], clk_w[TB_SPEED_NW];
    /* the time ratios with the chains' stages overlapped (an item in each
     * stage at once: an item per slowest stage's clocks) */
    double ovl_d[TB_SPEED_NW], ovl_w[TB_SPEED_NW];
    int ok;
} tb_speed_hw;

/* Ward's exp argument (1 - c^2)/c^2 as one wired design: powg g=2 and
 * div joined by a subtractor, operand registers and a valid flag, driven
 * one item at a time on c in [0.75, 1): its clocks per item and area (the
 * glue included) into pt, and its largest error against (1 - c^2)/c^2 of
 * the quantized c in quotient LSBs. 0, or -1. */
int    tb_speed_ward_chain(int width, tb_hw_point *pt, double *max_err_lsb);
/* Measure everything above at width (the ladder at its own widths). */
void   tb_speed_hw_measure(int width, tb_speed_hw *h);
/* The two claims rows (d16_speed_hw, ward_speed_hw) into out[0..1]; 2. */
size_t tb_speed_hw_rows(const tb_speed_hw *h, claim_result *out);
#endif
