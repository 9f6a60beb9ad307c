/* scene_shade.c - the double-precision reference shading of a surface point.
 *
 *   I = ambient + sum over lights of I0 (kd max(0, N.L) + ks spec)
 *
 * clamped to [0, 1]: the result is a display intensity (an 8-bit grey after
 * scaling), and the interpolation hardware works on intensities in [0, 1],
 * so the reference is the value the screen shows. A NaN (only possible from
 * a degenerate normal passed in) is returned as 0.
 *
 * Vectors, all unit length:
 *   N  the surface normal as given (the caller normalizes it);
 *   L  towards the light: a directional light's v (normalized here), or
 *      from the point towards a point light's position. No distance
 *      attenuation: a point light only changes L across the surface.
 *      A point light at the surface point contributes nothing;
 *   V  towards the viewer: from the point to the eye (perspective) or the
 *      constant direction target -> eye (orthographic);
 *   H  normalize(L + V); R = 2 (N.L) N - L.
 *
 * Specular terms (spec), zero wherever N.L <= 0 (a highlight on a side the
 * light does not reach would float on the shadow):
 *   phong  (R.V)^n, n = shininess, 0 where R.V <= 0;
 *   blinn  (N.H)^n, 0 where N.H <= 0;
 *   cook   F D G / (pi (N.L)(N.V)): the Cook-Torrance form the papers print,
 *          F D G / ((V.N)(L.N)), with Cook and Torrance's own 1/pi. No other
 *          factor: with the papers' Beckmann D (peak 1/(4m^2), no pi) the
 *          head-on peak (N = L = V) is 1/(4 pi m^2) = 0.884 for m = 0.3
 *          (1.99 at m = 0.2, 0.22 at m = 0.6), so ks = 1 gives a highlight of
 *          order 1 and the [0, 1] clamp is not what one sees at m = 0.3.
 *            D  cos g = N.H; dg = 0: exact Beckmann exp(-tan^2 g/m^2) /
 *               (4 m^2 cos^4 g); dg = 4, 8, 16: the one-function form
 *               D_g = (1/(4m^2)) (((2/m^2 - 4)/g)(cos g - 1) + 1)^g with the
 *               base clamped at 0, as the hardware unit does.
 *            F  on c = L.H: none 1; schlick c/(n - n c + c); mschlick the
 *               modified Schlick 2c/(1.25 (n - n c + 1.25 c)^2), n =
 *               fresnel_n. These are the papers' rational factors as printed:
 *               1 (1.024 for mschlick) at L.H = 1, falling away from it, so
 *               they dim highlights seen at a grazing half-angle; they are
 *               not a physical Fresnel term (which rises there).
 *            G  min(1, 2(N.H)(N.V)/(V.H), 2(N.H)(N.L)/(V.H)).
 *          Zero where N.V <= 0 (the division has no meaning there).
 *   ward   isotropic Ward, the standard form
 *            rho_s e / (4 pi a^2 sqrt((N.L)(N.V))), rho_s = 1,
 *          e = exp(-tan^2 g / a^2) (dg = 0) or the papers' polynomial
 *          ((1/(8a^2))(cos g - 1) + 1)^16, base clamped at 0 (dg = 16);
 *          cos g = N.H, a = alpha. Zero where N.V <= 0. The same scale as
 *          cook: head-on peak 1/(4 pi a^2), 0.884 at a = 0.3.
 * The specular functions are the ones of vectors/ref_brdf.h (the hardware
 * units' exact references), so a scene and a unit test agree on them.
 */
#include "scene/scene.h"
#include "vectors/ref_brdf.h"
#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* v / |v| into out; 0 if v has no length (out untouched then). */
static int unit3(const double v[3], double out[3])
{
    double len = sqrt(dot3(v, v));
    if (!(len > 0.0)) return 0;
    out[0] = v[0] / len; out[1] = v[1] / len; out[2] = v[2] / len;
    return 1;
}

/* The specular term of the material for unit L, N, V, with nl = N.L > 0. */
static double spec_term(const scn_material *mat, const double l[3], const double n[3],
                        const double v[3], double nl)
{
    switch (mat->spec) {
    case SCN_SPEC_PHONG:
        return ref_brdf_phong(l, n, v, mat->shininess);
    case SCN_SPEC_BLINN:
        return ref_brdf_blinn(l, n, v, mat->shininess);
    case SCN_SPEC_COOK: {
        double nv = dot3(n, v);
        if (nv <= 0.0) return 0.0;
        double hs[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] }, h[3];
        if (!unit3(hs, h)) return 0.0;
        double nh = dot3(n, h), vh = dot3(v, h), lh = dot3(l, h);
        if (nh <= 0.0 || vh <= 0.0) return 0.0;
        double d = mat->dg ? ref_brdf_dg_clamped(nh, mat->m, mat->dg)
                           : ref_brdf_beckmann(nh, mat->m);
        double f = 1.0;
        if (mat->fresnel == SCN_FRESNEL_SCHLICK) f = ref_brdf_schlick(lh, mat->fresnel_n);
        else if (mat->fresnel == SCN_FRESNEL_MSCHLICK) f = ref_brdf_mschlick(lh, mat->fresnel_n);
        double g = fmin(1.0, fmin(2.0 * nh * nv / vh, 2.0 * nh * nl / vh));
        return f * d * g / (M_PI * nl * nv);
    }
    case SCN_SPEC_WARD: {
        double nv = dot3(n, v);
        if (nv <= 0.0) return 0.0;
        if (!mat->dg) return ref_brdf_ward(l, n, v, 1.0, mat->alpha);
        double nh = ref_brdf_blinn_cos(l, n, v);
        if (nh <= 0.0) return 0.0;
        double a = mat->alpha;
        return ref_brdf_ward_exp_approx_clamped(nh, a) / (4.0 * M_PI * a * a * sqrt(nl * nv));
    }
    default:
        return 0.0;
    }
}

double scn_shade(const scn_material *mat, const scn_view *view, const double pos[3],
                 const double nrm[3])
{
    const scn_camera *cam = &view->cam;
    double v[3];
    double vs[3];
    if (cam->perspective) {
        vs[0] = cam->eye[0] - pos[0]; vs[1] = cam->eye[1] - pos[1]; vs[2] = cam->eye[2] - pos[2];
    } else {
        vs[0] = cam->eye[0] - cam->target[0]; vs[1] = cam->eye[1] - cam->target[1];
        vs[2] = cam->eye[2] - cam->target[2];
    }
    int have_v = unit3(vs, v);

    double sum = mat->ambient;
    int nl_count = view->nlights < SCN_MAX_LIGHTS ? view->nlights : SCN_MAX_LIGHTS;
    for (int i = 0; i < nl_count; i++) {
        const scn_light *lt = &view->light[i];
        double ls[3], l[3];
        if (lt->point) {
            ls[0] = lt->v[0] - pos[0]; ls[1] = lt->v[1] - pos[1]; ls[2] = lt->v[2] - pos[2];
        } else {
            ls[0] = lt->v[0]; ls[1] = lt->v[1]; ls[2] = lt->v[2];
        }
        if (!unit3(ls, l)) continue;
        double nl = dot3(nrm, l);
        if (nl <= 0.0) continue;               /* neither diffuse nor specular */
        double s = mat->kd * nl;
        if (have_v && mat->ks != 0.0) s += mat->ks * spec_term(mat, l, nrm, v, nl);
        sum += lt->intensity * s;
    }
    if (!(sum > 0.0)) return 0.0;              /* also NaN */
    return sum < 1.0 ? sum : 1.0;
}
