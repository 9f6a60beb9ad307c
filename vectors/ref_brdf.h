/* ref_brdf.h - double-precision reference of the BRDF approximations of
 * Nechyporuk & Romanyuk (2020, sec. III), Romanyuk et al. (SPIE) and Zavalniuk et al. (2022): Beckmann D and its one-function forms,
 * Ward and its polynomial exponential, Blinn/Phong, Schlick and the modified
 * Schlick of Zavalniuk et al. (2022), and Zavalniuk et al. (2022)'s cut-off intervals for a 2^-q threshold.
 *
 * Plain functions of doubles, no state. Angles are in radians; `c` is always
 * a cosine, cos g = N.H for the micro-facet models. Names follow the units
 * (units/) so a reader can match a hardware unit to its exact function.
 */
#ifndef REF_BRDF_H
#define REF_BRDF_H
#include "vectors/vectors.h"

/* The reference models (ref_brdf_models.c) of the BRDF units; each unit's
 * descriptor (units/) points at its own. */
extern const vec_model ref_model_powg, ref_model_d_approx, ref_model_ward_approx, ref_model_pow_n,
                       ref_model_div, ref_model_schlick, ref_model_mschlick;

/* ---- Beckmann D (Cook-Torrance), as Nechyporuk & Romanyuk (2020) and Romanyuk et al. (SPIE) write it: no 1/pi ---- */

/* D = exp(-tan^2 g / m^2) / (4 m^2 cos^4 g); 0 for c <= 0. Its peak, at
 * c = 1 for m < 1/sqrt(2) (all of the papers' range 0.2..0.6), is 1/(4m^2). */
double ref_brdf_beckmann(double c, double m);
/* The papers' first step: exp(-tan^2 g/m^2) ~ cos^(2/m^2) g, hence
 * D ~ cos^(2/m^2 - 4) g / (4 m^2); 0 for c <= 0. */
double ref_brdf_beckmann_cpow(double c, double m);

/* Second step, cos^n ~ ((n/g)(c - 1) + 1)^g with n = 2/m^2 - 4:
 * the base ((2/m^2 - 4)/g)(c - 1) + 1, ... */
double ref_brdf_dg_base(double c, double m, int g);
/* ... D_g = (1/(4m^2)) base^g exactly as the paper prints it (unclamped: for
 * even g a negative base makes the power rise again away from the peak) ... */
double ref_brdf_dg(double c, double m, int g);
/* ... and the form the hardware implements: base clamped at 0 first. For
 * m <= 1/sqrt(2) it never exceeds its value at c = 1, 1/(4m^2). */
double ref_brdf_dg_clamped(double c, double m, int g);
/* Cosine at which the base reaches 0, 1 - g/(2/m^2 - 4). The base is
 * negative for c below it; a value <= 0 means never within [0, 90] deg. */
double ref_brdf_dg_base_zero_cos(double m, int g);

/* x^g for the powg unit (g a power of two in the hardware; any g >= 0 here). */
double ref_brdf_powg(double x, int g);

/* ---- Ward (isotropic) ---- */

/* The exponential factor exp(-tan^2 g / a^2); 0 for c <= 0. */
double ref_brdf_ward_exp(double c, double alpha);
/* Nechyporuk & Romanyuk (2020) and Romanyuk et al. (SPIE): exp(-tan^2 g/a^2) ~ ((1/(8a^2))(c - 1) + 1)^16 (from
 * cos^(2/a^2) with g = 16). Unclamped as printed, and clamped at base 0
 * (the ward_approx unit). The base reaches 0 at c = 1 - 8a^2. */
double ref_brdf_ward_exp_approx(double c, double alpha);
double ref_brdf_ward_exp_approx_clamped(double c, double alpha);

/* Specular term of the standard isotropic Ward model,
 *   rho_s exp(-tan^2 d / a^2) / (4 pi a^2 sqrt((N.L)(N.V))),
 * d = angle(N, H), H = normalize(L + V); 0 when N.L <= 0 or N.V <= 0.
 * L, N, V are unit vectors. The papers print 1/sqrt(V.N + L.H) in place of
 * 1/sqrt((N.L)(N.V)); that is not Ward's model (and is not even symmetric
 * in the same way), so we implement the standard form. */
double ref_brdf_ward(const double l[3], const double n[3], const double v[3],
                     double rho_s, double alpha);

/* ---- Blinn, Phong ---- */

/* max(c, 0)^n: Blinn when c = N.H, Phong when c = V.R. F_B of Zavalniuk et al. (2022). */
double ref_brdf_cos_pow(double c, double n);
/* N.H with H = normalize(L + V) (Blinn); V.R with R = 2(L.N)N - L (Phong).
 * L, N, V are unit vectors. */
double ref_brdf_blinn_cos(const double l[3], const double n[3], const double v[3]);
double ref_brdf_phong_cos(const double l[3], const double n[3], const double v[3]);
double ref_brdf_blinn(const double l[3], const double n[3], const double v[3], double e);
double ref_brdf_phong(const double l[3], const double n[3], const double v[3], double e);

/* ---- Schlick and modified Schlick (Zavalniuk et al., 2022) ---- */

/* F_SH = c / (n - n c + c)  (eq. 2): Schlick's rational stand-in for c^n. */
double ref_brdf_schlick(double c, double n);
/* F_MSH = 2c / (1.25 (n - n c + 1.25 c)^2)  (eq. 5). Note F_MSH(1) =
 * 2/1.25^3 = 1.024 for every n: the output needs an integer bit. */
double ref_brdf_mschlick(double c, double n);

/* ---- Zavalniuk et al. (2022)'s cut-off intervals: the angle x beyond which each function
 * stays below the threshold 2^-q (computation of the specular term stops).
 * q is real, q >= 0; n >= 2 (n >= 1 for Schlick and Blinn). ---- */

/* eq. 10: x = acos(n / (2^q + n - 1)). */
double ref_brdf_cutoff_schlick(double n, double q);
/* eq. 12 exactly as printed:
 *   x = acos(4(16 2^q + 20n^2 - 25n - 4 2^(q+0.5) sqrt(8 + 20 2^-q n^2 - 25 2^-q n))
 *            / (5 (16n^2 - 40n + 25)))
 * It is the smaller root of 1.25 (n - (n - 1.25)c)^2 = 2^(q+1) c, and exact,
 * but it subtracts terms of size ~2^q to get a result of size ~n^2 2^-q:
 * about 0.3 4^q / (n (n - 1.25))^2 ulps are lost (cos x_cut off by 1.5e-7
 * relative at q = 16, n = 2; harmless for large n); undefined at n = 1.25. */
double ref_brdf_cutoff_mschlick_eq12(double n, double q);
/* The same root without the cancellation (conjugate form):
 *   c = 2.5 n^2 / (2.5 n k + 2^(q+1) (1 + sqrt(1 + 2.5 n k 2^-q))), k = n - 1.25. */
double ref_brdf_cutoff_mschlick(double n, double q);
/* eq. 14: x = acos(2^(-q/n)). */
double ref_brdf_cutoff_blinn(double n, double q);

#endif
