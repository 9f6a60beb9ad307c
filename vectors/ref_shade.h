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

extern const vec_model ref_model_sqrt, ref_model_dot3, ref_model_norm3, ref_model_shade;

/* The smallest and largest |N| of the shading units' domain. */
#define REF_SHADE_NMIN 0.5
#define REF_SHADE_NMAX 1.0

/* The shading above for one pixel: n[3], l[3], h[3], ka, kd, ks, exponent e. */
double ref_shade_blinn(const double n[3], const double l[3], const double h[3],
                       double ka, double kd, double ks, int e);
#endif
