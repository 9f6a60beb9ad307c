/* tb_stability.h - the stability atlas: where each method stops working,
 * found by simulating the units (or, for the BRDF approximations, by
 * sampling their double references densely), one row per failure boundary.
 *
 * Every row names a method, the condition swept, the boundary measured and
 * a verdict. The boundary finders are public so that the tests can pin each
 * boundary from both sides (the value one step before it fails, the value
 * at it holds). Everything is deterministic: fixed vector seeds, no timings.
 * docs/stability.md explains each boundary.
 */
#ifndef TB_STABILITY_H
#define TB_STABILITY_H
#include <stddef.h>
#include <stdint.h>
#include "chart/chart.h"

#define TB_STAB_TARGET   0.00390625   /* 2^-8: one LSB of an 8-bit intensity */
#define TB_STAB_MAX_ROWS 40
#define TB_STAB_MAX_CHARTS 10

typedef struct tb_stab_row {
    char id[32];            /* stable key: "fwd3_L32" */
    char method[48];        /* "interp3 fwd" */
    char condition[128];    /* what is swept and the target */
    char measured[240];     /* the boundary, in words */
    char verdict[320];      /* what it means for a user */
    double boundary;        /* the boundary as a number (bits, terms, m, ...) */
} tb_stab_row;

typedef struct tb_stab {
    tb_stab_row rows[TB_STAB_MAX_ROWS];
    int nrows;
    chart *charts[TB_STAB_MAX_CHARTS];
    const char *chart_files[TB_STAB_MAX_CHARTS];
    int ncharts;
} tb_stab;

/* Compute every row (and the charts when charts != 0). 0, or -1 with a
 * message (a unit failed to build or run). Free with tb_stab_free. */
int  tb_stability(tb_stab *s, int charts, char *err, size_t errlen);
void tb_stab_free(tb_stab *s);

/* ---- the boundary finders (each runs the units it names) ---- */

/* interp{deg} (deg 2 or 3), schedule fwd, L pixels, width-24 rule for the
 * coefficients, the fwd registers fy, fd1.. with F fraction bits each
 * (integer bits as the rule gives them): max |hw - ideal| over the pixels
 * of interval vectors that include every 0/1 node pattern. <0 on failure. */
double tb_stab_fwd_err(int deg, int L, int F);
/* Smallest F (8..48) with tb_stab_fwd_err <= target; -1 if none. */
int    tb_stab_fwd_min_frac(int deg, int L, double target);

/* A coefficient unit (coef3_n1, coef3_n2, coef2) at width 16: the signed
 * integer bits its coefficient signal sig needs to hold the raw range the
 * simulation observes for node intensities in [0, 1] (every 0/1 pattern
 * included). -1 on failure. */
int    tb_stab_coef_ibits(const char *unit, const char *sig);
/* The same unit with sig given ibits integer bits (fraction as the rule),
 * overflow mode sat (1) or wrap (0): overflows counted on sig and the max
 * |hw - ideal| of that output. 0, or -1. */
int    tb_stab_coef_missing(const char *unit, const char *sig, int ibits, int sat,
                            uint64_t *overflows, double *max_err);

/* interp3 (paper schedule, L = 8, width 20, 10-term /3 networks) on one interval of a highlight
 * I(x) = exp(-(x - 0.5)^2 / (2 s^2)), x in [0, 1] across the interval, s
 * its width in intervals: how far the hardware's pixels leave [0, 1]
 * (max of y - 1 and -y, 0 if never), and the max |y - I| with (clamped)
 * and without the output clamp. 0, or -1. */
int    tb_stab_overshoot(double s, double *excursion, double *err_raw, double *err_clamped);
/* The largest s (in steps of 1/64 from 1/64 to 1) whose excursion exceeds
 * target: highlights at or below it overshoot by more. */
double tb_stab_overshoot_width(double target);

/* Degree against curvature: profiles of highlights across one interval
 * (interp2, interp3 and linear at width 20, L = 8). For each the measure
 * the scene's adaptive-auto policy uses, c = |I(0) + I(1) - 2 I(1/2)|, and
 * the max error of each degree against the profile. The threshold is the
 * smallest c of a profile whose degree-2 error exceeds target: below it
 * degree 2 always holds. n_profiles (may be NULL) gets the count. */
double tb_stab_deg_threshold(double target, int *n_profiles);
/* The same for linear interpolation (degree 1): the smallest c whose
 * linear error exceeds target. */
double tb_stab_lin_threshold(double target);

/* div3 at width W (output s1.(W-1)) with `terms` paper-series terms: max
 * |hw - x/3| over its vectors. <0 on failure. */
double tb_stab_div3_err(int W, int terms);
/* 1 if every item has |hw - x/3| <= one output LSB (2^-(W-1)), decided
 * exactly on the dyadic values (|3 hw - x| <= 3 LSB); 0 if not; -1. */
int    tb_stab_div3_holds(int W, int terms);
/* Fewest terms for which tb_stab_div3_holds; -1. */
int    tb_stab_div3_terms(int W);

/* A BRDF approximation's relative error (fraction) against its exact
 * function where the exact value is above `floor` of its peak:
 * kind 4, 8, 16: D_g (clamped) vs Beckmann, p = m; kind 1: the cos-power
 * form vs Beckmann, p = m; kind 2: Ward's 16th power vs exp, p = alpha;
 * kind 3: Schlick vs cos^n, kind 5: modified Schlick vs cos^n, p = n. */
double tb_stab_brdf_err(int kind, double p, double floor);

/* A unit run at width W with parameter value v (pow_n: n; powg: g; div:
 * unused): max |hw - ideal| in output LSBs and clocks per item. 0, or -1. */
int    tb_stab_unit(const char *unit, int W, int v, double *err_lsb, double *clocks);
#endif
