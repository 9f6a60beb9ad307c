/* ref_brdf.c - double-precision BRDF references (see ref_brdf.h). */
#include "vectors/ref_brdf.h"
#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* tan^2 from the cosine without calling tan(): (1 - c^2) / c^2. */
static double tan2_of_cos(double c) { return (1.0 - c * c) / (c * c); }

/* ---- Beckmann ---- */

double ref_brdf_beckmann(double c, double m)
{
    if (c <= 0.0) return 0.0;
    double c2 = c * c;
    return exp(-tan2_of_cos(c) / (m * m)) / (4.0 * m * m * c2 * c2);
}

double ref_brdf_beckmann_cpow(double c, double m)
{
    if (c <= 0.0) return 0.0;
    return pow(c, 2.0 / (m * m) - 4.0) / (4.0 * m * m);
}

double ref_brdf_dg_base(double c, double m, int g)
{
    return ((2.0 / (m * m) - 4.0) / g) * (c - 1.0) + 1.0;
}

double ref_brdf_dg(double c, double m, int g)
{
    return pow(ref_brdf_dg_base(c, m, g), g) / (4.0 * m * m);
}

double ref_brdf_dg_clamped(double c, double m, int g)
{
    double b = ref_brdf_dg_base(c, m, g);
    return b > 0.0 ? pow(b, g) / (4.0 * m * m) : 0.0;
}

double ref_brdf_dg_base_zero_cos(double m, int g)
{
    return 1.0 - g / (2.0 / (m * m) - 4.0);
}

double ref_brdf_powg(double x, int g) { return pow(x, g); }

/* ---- Ward ---- */

double ref_brdf_ward_exp(double c, double alpha)
{
    if (c <= 0.0) return 0.0;
    return exp(-tan2_of_cos(c) / (alpha * alpha));
}

double ref_brdf_ward_exp_approx(double c, double alpha)
{
    return pow((c - 1.0) / (8.0 * alpha * alpha) + 1.0, 16);
}

double ref_brdf_ward_exp_approx_clamped(double c, double alpha)
{
    double b = (c - 1.0) / (8.0 * alpha * alpha) + 1.0;
    return b > 0.0 ? pow(b, 16) : 0.0;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double ref_brdf_ward(const double l[3], const double n[3], const double v[3],
                     double rho_s, double alpha)
{
    double nl = dot3(n, l), nv = dot3(n, v);
    if (nl <= 0.0 || nv <= 0.0) return 0.0;
    double e = ref_brdf_ward_exp(ref_brdf_blinn_cos(l, n, v), alpha);
    return rho_s * e / (4.0 * M_PI * alpha * alpha * sqrt(nl * nv));
}

/* ---- Blinn, Phong ---- */

double ref_brdf_cos_pow(double c, double n) { return c > 0.0 ? pow(c, n) : 0.0; }

double ref_brdf_blinn_cos(const double l[3], const double n[3], const double v[3])
{
    double h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
    double len = sqrt(dot3(h, h));
    if (len == 0.0) return 0.0;          /* L = -V: H undefined, no highlight */
    return dot3(n, h) / len;
}

double ref_brdf_phong_cos(const double l[3], const double n[3], const double v[3])
{
    double ln2 = 2.0 * dot3(l, n);
    double r[3] = { ln2 * n[0] - l[0], ln2 * n[1] - l[1], ln2 * n[2] - l[2] };
    return dot3(v, r);
}

double ref_brdf_blinn(const double l[3], const double n[3], const double v[3], double e)
{
    return ref_brdf_cos_pow(ref_brdf_blinn_cos(l, n, v), e);
}

double ref_brdf_phong(const double l[3], const double n[3], const double v[3], double e)
{
    return ref_brdf_cos_pow(ref_brdf_phong_cos(l, n, v), e);
}

/* ---- Schlick, modified Schlick ---- */

double ref_brdf_schlick(double c, double n) { return c / (n - n * c + c); }

double ref_brdf_mschlick(double c, double n)
{
    double u = n - n * c + 1.25 * c;
    return 2.0 * c / (1.25 * u * u);
}

/* ---- cut-off intervals (Zavalniuk et al., 2022) ----
 * The paper writes the inequalities as 0 <= F <= 2^-q (eqs. 9, 11, 13) but
 * means the interval of computation 0 <= x <= x_cut where F >= 2^-q
 * (eqs. 10, 12, 14): every F here decreases in x, so x_cut is where it
 * crosses 2^-q. */

double ref_brdf_cutoff_schlick(double n, double q)
{
    return acos(n / (exp2(q) + n - 1.0));
}

double ref_brdf_cutoff_mschlick_eq12(double n, double q)
{
    double t = exp2(q), ti = exp2(-q);
    double num = 4.0 * (16.0 * t + 20.0 * n * n - 25.0 * n
                        - 4.0 * exp2(q + 0.5) * sqrt(8.0 + 20.0 * ti * n * n - 25.0 * ti * n));
    return acos(num / (5.0 * (16.0 * n * n - 40.0 * n + 25.0)));
}

double ref_brdf_cutoff_mschlick(double n, double q)
{
    double k = n - 1.25, t2 = exp2(q + 1.0);
    double c = 2.5 * n * n / (2.5 * n * k + t2 * (1.0 + sqrt(1.0 + 2.5 * n * k * exp2(-q))));
    return acos(c);
}

double ref_brdf_cutoff_blinn(double n, double q)
{
    return acos(exp2(-q / n));
}
