/* tb_ref_claims_int.h - what the files of the claims table share; not for use
 * outside them (the public interface is tb_ref_claims.h).
 *
 *   tb_ref_claims_rows.c    the table's rows and the numerical helpers (a
 *                     leaf: the other files call it)
 *   tb_ref_claims.c         the whole table (claims_compute), the claims of
 *                     Nechyporuk & Romanyuk (2020) and Romanyuk et al.
 *                     (SPIE): divide by 3, interpolation, D and Ward
 *                     approximations, node sets
 *   tb_ref_claims_schlick.c the claims of Zavalniuk et al. (2022): Schlick and
 *                     modified Schlick against Blinn
 *   tb_ref_claims_cpu.c     the CPU speed claims (timing; not in claims_compute)
 */
#ifndef TB_REF_CLAIMS_INT_H
#define TB_REF_CLAIMS_INT_H
#include "testbench/study/tb_ref_claims.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define HALF_PI (M_PI / 2)
#define RAD2DEG (180.0 / M_PI)

/* Our reading of the papers' "high accuracy": relative error <= 5%. */
#define ACCURATE_PCT 5.0

/* The table being filled. */
typedef struct table {
    claim_result *out;
    size_t max, n;
    claim_result spare;        /* rows beyond max are computed into this */
} table;

/* The table's next row (the spare one past max), cleared: measured NAN,
 * verdict "does not hold" until the caller decides. */
claim_result *claims_add(table *t, const char *id, const char *seed, const char *claim, double claimed);
/* snprintf into a row's text field. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void claims_text(char *dst, size_t size, const char *fmt, ...);

typedef double (*fn_cp)(double c, double p);   /* a function of cos and one parameter */

/* Angle in [0, pi/2] where a decreasing f(cos th, p) crosses level. */
double claims_angle_where(fn_cp f, double p, double level);
/* max |a/r - 1| in percent over N+1 angles in [0, th_max]. */
double claims_max_rel_pct(fn_cp a, fn_cp r, double p, double th_max, int N);
/* max |a - r| over N+1 angles in [th0, th1]. */
double claims_max_abs(fn_cp a, fn_cp r, double p, double th0, double th1, int N);
/* Maximum over [0, pi/2] of |a - r|, refined by golden-section search. */
double claims_max_abs_refined(fn_cp a, fn_cp r, double p);

/* The rows of Zavalniuk et al. (2022), in their order (claims_schlick.c). */
void claims_schlick(table *t);
#endif
