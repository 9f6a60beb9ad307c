/* ref_shade.h - double-precision references of the per-pixel shading
 * units (ref_shade.c): sqrt, dot3, norm3 and shade, the per-pixel side of
 * the comparison of Nechyporuk & Romanyuk (2020), sec. IV.
 *
 * shade is the scene's default model for one directional light of
 * intensity 1 (scene/scene_shade.c, Blinn): with u = N/|N|,
 *   i = clamp(ka + kd max(0, u.L) + ks (u.L > 0 && u.H > 0 ? (u.H)^n : 0), 0, 1)
 * for the normal N as interpolated (|N| in [1/2, 1]) and the frame's
 * constant unit vectors L (towards the light) and H (the half vector). */
#ifndef REF_SHADE_H
#define REF_SHADE_H
#include "vectors/vectors.h"

extern const vec_model ref_model_sqrt, ref_model_dot3, ref_model_norm3, ref_model_shade, ref_model_shade_cook;

/* The smallest and largest |N| of the shading units' domain. */
#define REF_SHADE_NMIN 0.5
#define REF_SHADE_NMAX 1.0

/* The shading above for one pixel: n[3], l[3], h[3], ka, kd, ks, exponent e. */
double ref_shade_blinn(const double n[3], const double l[3], const double h[3],
                       double ka, double kd, double ks, int e);

/* shade_cook: the scene's Cook-Torrance form with the papers' D_g
 * (scene/scene_shade.c, cook, distribution d4/d8/d16) for one directional
 * light, V constant, the Fresnel factor and 1/pi (constant over a frame:
 * L.H is) folded into kc = ks F / pi. With u = N/|N|, nl = u.L, nv = u.V,
 * and hs = 1/|L + V| (so that u.H = (nl + nv) hs, H = (L + V) hs):
 *   nh = (nl + nv) hs,  a = max(min(nl, nv), 1/4),  b = max(max(nl, nv), 2^-e),
 *   spec = kc D_g(nh) min(1/a, 4 hs nh) / b   (0 where nl <= 0 or nv <= 0),
 *   i = clamp(ka + kd max(0, nl) + spec, 0, 1).
 * For unit L, V with L.V >= -1/2 (hs <= 1) this is kc D G / (nl nv) with
 * G = min(1, 2 nh nv / (V.H), 2 nh nl / (V.H)) exactly: the clamps change
 * nothing where D > 0 (docs/bounds.md, "shade_cook"). e is
 * ref_shade_cook_e(m, g). */
double ref_shade_cook(const double n[3], const double l[3], const double v[3], double hs,
                      double ka, double kd, double kc, double m, int g);
/* The smallest e with 2^-e <= (1 - 1/k) / 2, k = (2/m^2 - 4)/g: where D_g
 * is not 0, max(nl, nv) >= 2^-e. 0 when k <= 1 (D_g never reaches 0). */
int ref_shade_cook_e(double m, int g);
#endif
