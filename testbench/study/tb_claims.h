/* tb_claims.h - the claims study: the whole claims table (every numerical
 * claim of the papers with what we measure and a verdict), where each
 * approximation fails, and the charts of both. The verb claims prints and
 * writes them (testbench/cli/cli_claims.c); the verb report shows the table
 * too, both through tb_claims_table, so they cannot disagree.
 *
 * The rows, in order and by kind:
 *   "accuracy"  testbench/study/tb_ref_claims.c on the double-precision references;
 *   "speed_hw"  the speed claims as clocks x area of our units
 *               (tb_speed_hw.h) at a width;
 *   "factor"    the factorization paper's (tb_factor_claims.h);
 *   "scene"     the face scene's, through the span hardware
 *               (tb_scene_claims.h).
 * Deterministic: the same rows on every run and machine (no timing).
 */
#ifndef TB_CLAIMS_H
#define TB_CLAIMS_H
#include <stddef.h>
#include "testbench/study/tb_ref_claims.h"
#include "chart/chart.h"
#include "testbench/study/tb_speed_hw.h"

/* Every row of the table (at most CLAIMS_MAX) into rows and its kind into
 * kind[i]; the hardware figures at width (the units' measurements into hc
 * when hc is not NULL). Returns the rows, 0 with a message in err when a
 * part cannot be measured (the face or the Fig. 1 scene not rendered). */
size_t tb_claims_table(claim_result *rows, const char **kind, int width, tb_speed_hw *hc, char *err, size_t errlen);

/* ------------------------------------------------------ failure regions */

/* A failure: relative error above TB_CLAIMS_FAIL_REL where the exact value
 * is above TB_CLAIMS_FAIL_FLOOR of its peak, over angles 0..90 degrees
 * between N and H in steps of 0.05 degrees. */
#define TB_CLAIMS_FAIL_REL   0.10
#define TB_CLAIMS_FAIL_FLOOR 0.01
#define TB_CLAIMS_MAX_BANDS  8

/* An approximation at one parameter value against its exact function. */
typedef struct tb_claims_approx {
    const char *name;      /* "D16" */
    const char *pname;     /* "m" */
    double p;
    double (*f)(double c, double p), (*exact)(double c, double p);
    double peak;           /* of the exact function (at 0 deg) */
} tb_claims_approx;

/* The approximations the failure regions are given for. */
#define TB_CLAIMS_NAPPROX 12
extern const tb_claims_approx tb_claims_approx_tab[TB_CLAIMS_NAPPROX];

/* Contiguous runs of failing angles (degrees; at most TB_CLAIMS_MAX_BANDS)
 * and the worst relative error where the exact value is above the floor. */
typedef struct tb_claims_bands {
    int n;
    double lo[TB_CLAIMS_MAX_BANDS], hi[TB_CLAIMS_MAX_BANDS];
    double worst;
} tb_claims_bands;
void tb_claims_failure_bands(const tb_claims_approx *a, tb_claims_bands *b);

/* --------------------------------------------------------------- charts */

/* The claims charts, each a file name and the chart (NULL: out of memory;
 * chart_free it); a NULL file ends the table: error against angle with the
 * failure bands shaded, why d_approx clamps its base, and clocks x area
 * against error of the specular units over widths (hardware runs). */
typedef struct tb_claims_chart {
    const char *file;      /* "claims_d16.svg" */
    chart *(*make)(void);
} tb_claims_chart;
extern const tb_claims_chart tb_claims_charts[];
#endif
