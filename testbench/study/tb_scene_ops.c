/* tb_scene_ops.c - the operations a scene's lighting costs per point
 * (tb_scene_point_ops): the reference's per-pixel work, and the method's
 * per shaded node; tb_scene.c adds the method's coefficient and Horner
 * arithmetic. */
#include "testbench/study/tb_scene.h"

/* The operations of one evaluation of the lighting model at a point, from
 * the interpolated (not normalized) normal and the position, counted as an
 * efficient per-pixel shader does them: the reference does this at every
 * covered pixel, the method at every shaded node, by the same rules.
 *
 * What varies over the frame is the normal N and the position P. Work on
 * frame constants alone is done once per frame and not counted per point
 * (both sides alike; spread over the covered pixels it is a few dozen
 * operations / pixels): L of a directional light, V of an orthographic
 * camera, and from them H = normalize(L + V), L.V, L.H = V.H, a Fresnel
 * factor of L.H, 2/V.H; products of constants (I0 kd, I0 ks with the
 * BRDF's own factors 1/pi, 1/(4 m^2), 1/(4 pi a^2), the Schlick forms'
 * constants). So L is normalized per point only for a point light, V only
 * for a perspective camera, H only where one of them varies. Further:
 * comparisons, max(0, .), min, clamps and shifts (a factor 2) are free;
 * a value used twice is computed once (L.H = V.H; N.V; c^2 and 1/c^2);
 * a vector normalized is its dot with itself (2 add, 3 mul), a sqrt, a
 * reciprocal (div) and 3 mul; x^n with the material's real exponent and
 * exp are one "pow", x^g with the fixed integer g of D_g (4, 8, 16) and
 * Ward's ^16 are multiplies by repeated squaring. One table, a row per
 * step; a row counts when its condition holds, once or per light; the
 * specular rows only when ks != 0. c = N.H in D and Ward, L.H in F.
 *
 *  step                                        when                      add mul div sqrt pow
 *  normalize N: N.N, sqrt, 1/|N|, 3 mul        always                      2   6   1   1   0
 *  V = eye - P, normalized                     perspective                 5   6   1   1   0
 *  L = light - P, normalized                   point light                 5   6   1   1   0
 *  N.L                                         light                       2   3   0   0   0
 *  (I0 kd) N.L, summed (from the ambient)     light                       1   1   0   0   0
 *  (I0 ks) spec, added                         specular                    1   1   0   0   0
 *  phong R.V = 2 (N.L)(N.V) - L.V: N.V, 1 mul  phong, L and V constant     3   4   0   0   0
 *  phong R = 2 (N.L) N - L, R.V                phong, L or V varies        5   6   0   0   0
 *  (R.V)^n or (N.H)^n                          phong, blinn                0   0   0   0   1
 *  H = normalize(L + V)                        half-vector BRDF, L or V    5   6   1   1   0
 *                                              varies (blinn, cook, ward)
 *  N.H                                         blinn, cook, ward           2   3   0   0   0
 *  N.V                                         cook, ward                  2   3   0   0   0
 *  L.H (= V.H)                                 cook, L or V varies         2   3   0   0   0
 *  Beckmann D: c^2, r = 1/c^2, tan^2 = r - 1,
 *    x (-1/m^2), exp, x r^2                    cook, exact D               1   4   1   0   1
 *  D_g: k c + (1 - k), ^g by squaring          cook, D_g                   1   1+s 0   0   0
 *  G = min(1, 2 (N.H) min(N.V, N.L) / V.H)     cook, L or V varies         0   1   1   0   0
 *    the same, x (2/V.H) a constant            cook, L and V constant      0   2   0   0   0
 *  D G / ((N.L)(N.V))                          cook                        0   2   1   0   0
 *  x F                                         cook with F, L or V varies  0   1   0   0   0
 *  Schlick F = c / (n + (1 - n) c)             the same, schlick           1   1   1   0   0
 *  modified Schlick 1.6 c / u^2,
 *    u = n + (1.25 - n) c                      the same, mschlick          1   2   1   0   0
 *  Ward exact e: c^2, 1/c^2, - 1, x (-1/a^2),
 *    exp                                       ward exact                  1   2   1   0   1
 *  Ward polynomial e: k c + (1 - k), ^16       ward poly16                 1   5   0   0   0
 *  e / sqrt((N.L)(N.V))                        ward                        0   1   1   1   0
 * (s: the squarings and multiplies of x^g, floor(log2 g) + popcount(g) - 1:
 * 2, 3, 4 for g = 4, 8, 16.)
 *
 * The method, per covered pixel: (shaded nodes x the same per-point cost)
 * / pixels; the coefficient network's adders per interval / pixels (every
 * ADD/SUB element of the network of the interval's degree, each /3
 * network its terms' subtractors: `terms` for the paper series, terms - 1
 * for the quarter series; shifts are wiring); Horner per pixel: deg mul +
 * deg add; t = k * (1/dv): 1 mul per pixel (the reciprocal is a ROM).
 * Costs weigh the counts with the description's weights (cost key); the
 * long operations are div + sqrt + pow, unweighted. */
typedef enum { W_ALWAYS, W_PERSP, W_POINT, W_LIGHT, W_SPEC, W_PHONG_CONST, W_PHONG_VAR, W_POW,
               W_H_VAR, W_HALF, W_NV, W_LH_VAR, W_COOK_EXACT, W_COOK_DG, W_G_VAR, W_G_CONST, W_COOK,
               W_F_VAR, W_SCHLICK_VAR, W_MSCHLICK_VAR, W_WARD_EXACT, W_WARD_POLY, W_WARD } ops_when;
typedef struct ops_row { ops_when when; int per_light; double n[SCN_OP__COUNT]; } ops_row;
static const ops_row ops_table[] = {
    /*  when              per light  add mul div sqrt pow */
    { W_ALWAYS,         0, { 2, 6, 1, 1, 0 } },   /* normalize N */
    { W_PERSP,          0, { 5, 6, 1, 1, 0 } },   /* V */
    { W_POINT,          1, { 5, 6, 1, 1, 0 } },   /* L of a point light */
    { W_LIGHT,          1, { 2, 3, 0, 0, 0 } },   /* N.L */
    { W_LIGHT,          1, { 1, 1, 0, 0, 0 } },   /* (I0 kd) N.L, summed */
    { W_SPEC,           1, { 1, 1, 0, 0, 0 } },   /* (I0 ks) spec, added */
    { W_PHONG_CONST,    1, { 3, 4, 0, 0, 0 } },   /* N.V, 2 (N.L)(N.V) - L.V */
    { W_PHONG_VAR,      1, { 5, 6, 0, 0, 0 } },   /* R, R.V */
    { W_POW,            1, { 0, 0, 0, 0, 1 } },   /* ^n */
    { W_H_VAR,          1, { 5, 6, 1, 1, 0 } },   /* H normalized */
    { W_HALF,           1, { 2, 3, 0, 0, 0 } },   /* N.H */
    { W_NV,             1, { 2, 3, 0, 0, 0 } },   /* N.V */
    { W_LH_VAR,         1, { 2, 3, 0, 0, 0 } },   /* L.H = V.H */
    { W_COOK_EXACT,     1, { 1, 4, 1, 0, 1 } },   /* Beckmann D */
    { W_COOK_DG,        1, { 1, 1, 0, 0, 0 } },   /* D_g base; + the squarings of ^g */
    { W_G_VAR,          1, { 0, 1, 1, 0, 0 } },   /* G, / V.H */
    { W_G_CONST,        1, { 0, 2, 0, 0, 0 } },   /* G, x 2/V.H */
    { W_COOK,           1, { 0, 2, 1, 0, 0 } },   /* D G / ((N.L)(N.V)) */
    { W_F_VAR,          1, { 0, 1, 0, 0, 0 } },   /* x F */
    { W_SCHLICK_VAR,    1, { 1, 1, 1, 0, 0 } },   /* Schlick */
    { W_MSCHLICK_VAR,   1, { 1, 2, 1, 0, 0 } },   /* modified Schlick */
    { W_WARD_EXACT,     1, { 1, 2, 1, 0, 1 } },   /* exact Ward e */
    { W_WARD_POLY,      1, { 1, 5, 0, 0, 0 } },   /* polynomial Ward e, ^16 in 4 mul */
    { W_WARD,           1, { 0, 1, 1, 1, 0 } },   /* e / sqrt((N.L)(N.V)) */
};

/* Multiplies of x^g by repeated squaring (g >= 1). */
static int pow_muls(int g)
{
    int n = -1;
    for (int k = g; k > 0; k >>= 1) n += 1 + (k > 1 && (k & 1));
    return n > 0 ? n : 0;
}

static int ops_applies(ops_when w, const scn_material *m, const scn_view *v, const scn_light *l)
{
    int cook = m->spec == SCN_SPEC_COOK, ward = m->spec == SCN_SPEC_WARD, phong = m->spec == SCN_SPEC_PHONG;
    int half = m->spec == SCN_SPEC_BLINN || cook || ward;
    int fresnel = cook && m->fresnel != SCN_FRESNEL_NONE;
    /* L or V varies over the frame, so do H, L.V, L.H (per light) */
    int var = v->cam.perspective || (l && l->point);
    if (w >= W_SPEC && m->ks == 0) return 0;     /* no specular term is evaluated */
    switch (w) {
    case W_ALWAYS: return 1;
    case W_PERSP: return v->cam.perspective;
    case W_POINT: return l && l->point;
    case W_LIGHT: return 1;
    case W_SPEC: return phong || half;
    case W_PHONG_CONST: return phong && !var;
    case W_PHONG_VAR: return phong && var;
    case W_POW: return phong || m->spec == SCN_SPEC_BLINN;
    case W_H_VAR: return half && var;
    case W_HALF: return half;
    case W_NV: return cook || ward;
    case W_LH_VAR: return cook && var;
    case W_COOK_EXACT: return cook && m->dg == 0;
    case W_COOK_DG: return cook && m->dg > 0;
    case W_G_VAR: return cook && var;
    case W_G_CONST: return cook && !var;
    case W_COOK: return cook;
    case W_F_VAR: return fresnel && var;
    case W_SCHLICK_VAR: return cook && var && m->fresnel == SCN_FRESNEL_SCHLICK;
    case W_MSCHLICK_VAR: return cook && var && m->fresnel == SCN_FRESNEL_MSCHLICK;
    case W_WARD_EXACT: return ward && m->dg == 0;
    case W_WARD_POLY: return ward && m->dg > 0;
    case W_WARD: return ward;
    }
    return 0;
}

static void ops_add_row(const ops_row *r, const scn_material *m, double ops[SCN_OP__COUNT])
{
    for (int k = 0; k < SCN_OP__COUNT; k++) ops[k] += r->n[k];
    if (r->when == W_COOK_DG) ops[SCN_OP_MUL] += pow_muls(m->dg);
}

void tb_scene_point_ops(const scn_desc *d, const scn_view *v, double ops[SCN_OP__COUNT])
{
    for (int k = 0; k < SCN_OP__COUNT; k++) ops[k] = 0;
    for (size_t i = 0; i < sizeof ops_table / sizeof ops_table[0]; i++) {
        const ops_row *r = &ops_table[i];
        if (!r->per_light) {
            if (ops_applies(r->when, &d->mat, v, NULL)) ops_add_row(r, &d->mat, ops);
            continue;
        }
        for (int l = 0; l < v->nlights; l++)
            if (ops_applies(r->when, &d->mat, v, &v->light[l])) ops_add_row(r, &d->mat, ops);
    }
}

double tb_scene_long_ops(const double ops[SCN_OP__COUNT])
{
    return ops[SCN_OP_DIV] + ops[SCN_OP_SQRT] + ops[SCN_OP_POW];
}
