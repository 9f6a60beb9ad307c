/* tb_scene_claims.c - the paper's face-scene claims, measured through the
 * simulated hardware path (tb_scene_render): every pixel of the face is
 * interpolated by the cycle-accurate span unit and compared with per-pixel
 * Phong shading in double precision.
 *
 * Rows (verdicts follow from the measured numbers, never fixed):
 *   scene_nmse_paper  adaptive-region (degree by face region), L 8, the
 *                     paper's 3-term divide-by-3 network, width 16;
 *   scene_nmse_terms  the first setting that meets NMSE <= 1e-4: terms
 *                     3, 4, 5, 6, 8, 12 at L 8, then the same at L 4;
 *   scene_nmse_auto   adaptive-auto (degree from the node differences)
 *                     at L 8 with 3 terms, and at the setting found;
 *   scene_speedup     operations per pixel of an efficient per-pixel
 *                     Phong/Blinn shader over the method's (frame
 *                     constants hoisted on both sides, docs/scenes.md),
 *                     read two ways: all operations weighted, and the long
 *                     operations (div, sqrt, pow) alone; at L 8, and when
 *                     the weighted figure is below 3 at the longer
 *                     intervals 16 and 32 too (3 terms), with their NMSE.
 *                     The verdict takes the shortest L at which a reading
 *                     reaches 3, the weighted one first.
 */
#include "testbench/study/tb_scene_claims.h"
#include "testbench/study/tb_scene.h"
#include "testbench/tb.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define CLAIM_NMSE 1e-4

/* The settings row (b) tries, in order, and the verdict of each. */
static const int L_TRY[] = { 8, 4 }, T_TRY[] = { 3, 4, 5, 6, 8, 12 };
#define N_L 2
#define N_T 6
#define VT(L, T) CLAIM_HOLDS_ONLY "L = " #L " with " #T " terms in the divide-by-3 network"
static const char *const VERDICT[N_L * N_T] = {
    VT(8, 3), VT(8, 4), VT(8, 5), VT(8, 6), VT(8, 8), VT(8, 12),
    VT(4, 3), VT(4, 4), VT(4, 5), VT(4, 6), VT(4, 8), VT(4, 12) };

typedef struct meas { int ok; double nmse, speedup, speedup_long, deg2, cost_ref, cost_hw, long_ref; } meas;

static int measure(const scn_desc *d0, const scn_gbuf *g, scn_policy pol, int L, int terms, int jobs, meas *out,
                   char *err, size_t errlen)
{
    scn_desc d = *d0;
    d.policy = pol;
    snprintf(d.L, sizeof d.L, "%d", L);
    snprintf(d.terms, sizeof d.terms, "%d", terms);
    tb_scene_opts o = { jobs, 0, NULL, NULL, 0, 0, NULL };
    tb_scene_result r;
    memset(&r, 0, sizeof r);
    memset(out, 0, sizeof *out);
    int rc = tb_scene_render_gbuf(&d, g, NULL, NULL, &o, &r, err, errlen);
    if (rc == TB_OK) {
        out->ok = 1;
        out->nmse = r.nmse;
        out->speedup = r.speedup;
        out->speedup_long = r.speedup_long;
        out->long_ref = r.long_ref;
        out->deg2 = r.deg2_share;
        out->cost_ref = r.cost_ref;
        out->cost_hw = r.cost_hw;
    }
    tb_scene_free(&r);
    return rc == TB_OK ? 0 : -1;
}

/* What the rows read: the renders, and the setting (b) found. */
typedef struct all {
    meas pa, pk, au3, auk, sp16, sp32;   /* (a); (b)'s last; (c) at L 8, at (b)'s; (d) at L 16, 32 */
    int KL, KT, ci;                      /* (b)'s setting (KL 0: none) and its index into VERDICT */
} all;

/* The renders of the four rows, on face d rasterized into g. */
static int measure_all(const scn_desc *d, const scn_gbuf *g, int jobs, all *a, char *err, size_t errlen)
{
    memset(a, 0, sizeof *a);
    a->ci = -1;
    /* (a) the paper's configuration. */
    if (measure(d, g, SCN_POL_ADAPTIVE_REGION, 8, 3, jobs, &a->pa, err, errlen)) return -1;
    /* (b) the first setting, in the order of T_TRY within L_TRY, that
     * holds: more terms at the paper's L 8 first, then shorter intervals. */
    for (int li = 0; li < N_L && !a->KL; li++)
        for (int ti = 0; ti < N_T && !a->KL; ti++) {
            meas q;
            if (L_TRY[li] == 8 && T_TRY[ti] == 3) q = a->pa;
            else if (measure(d, g, SCN_POL_ADAPTIVE_REGION, L_TRY[li], T_TRY[ti], jobs, &q, err, errlen)) return -1;
            a->pk = q;
            if (q.nmse <= CLAIM_NMSE) { a->KL = L_TRY[li]; a->KT = T_TRY[ti]; a->ci = li * N_T + ti; }
        }
    /* (c) automatic degree: the paper's setting, and (b)'s. */
    if (measure(d, g, SCN_POL_ADAPTIVE_AUTO, 8, 3, jobs, &a->au3, err, errlen)) return -1;
    if (a->KL && !(a->KL == 8 && a->KT == 3) &&
        measure(d, g, SCN_POL_ADAPTIVE_AUTO, a->KL, a->KT, jobs, &a->auk, err, errlen))
        return -1;
    /* (d) longer intervals, if L 8 falls short of 3x. */
    if (a->pa.speedup < 3) {
        if (measure(d, g, SCN_POL_ADAPTIVE_REGION, 16, 3, jobs, &a->sp16, err, errlen)) return -1;
        if (a->sp16.speedup < 3 && measure(d, g, SCN_POL_ADAPTIVE_REGION, 32, 3, jobs, &a->sp32, err, errlen))
            return -1;
    }
    return 0;
}

static const char *const WHERE = "Nechyporuk & Romanyuk (2020), sec. IV (conclusion)";

static void row_paper(claim_result *r, const all *a, int res)
{
    r->id = "scene_nmse_paper";
    r->source = WHERE;
    r->claim = "adaptive degree 2/3 on a face gives NMSE no more than 0.0001 against Phong "
               "(here: degree by face region, L 8, the paper's 3-term divide-by-3 network, through the simulated hardware)";
    r->claimed = CLAIM_NMSE;
    r->measured = a->pa.nmse;
    tb_settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g (adaptive-region, L 8, 3 terms, width 16); "
            "%.0f%% of intervals degree 2", a->pa.nmse, 100 * a->pa.deg2);
    /* The row is about the paper's own setting: other settings are row (b). */
    r->verdict = a->pa.nmse <= CLAIM_NMSE ? CLAIM_HOLDS : CLAIM_FAILS;
    tb_settext(r->note, sizeof r->note, "built-in face at %dx%d (lower than the default 512x512 to keep claims fast), "
            "every pixel through the cycle-accurate span unit, per-pixel shading in double (Phong normal "
            "interpolation) as reference; the 3-term network's 1/3 is 43/128", res, res);
}

static void row_terms(claim_result *r, const all *a, int res)
{
    int KL = a->KL, KT = a->KT;
    r->id = "scene_nmse_terms";
    r->source = WHERE;
    r->claim = "the same with enough terms in the divide-by-3 network (and, if that is not enough, shorter intervals)";
    r->claimed = CLAIM_NMSE;
    r->measured = a->pk.nmse;
    if (KL) tb_settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g at L %d with %d terms (L 8 with 3 terms: %.3g)",
                    a->pk.nmse, KL, KT, a->pa.nmse);
    else tb_settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g at L %d with %d terms, the last tried, still "
                 "above; L 8 with 3 terms: %.3g", a->pk.nmse, L_TRY[N_L - 1], T_TRY[N_T - 1], a->pa.nmse);
    r->verdict = KL == 8 && KT == 3 ? CLAIM_HOLDS : KL ? VERDICT[a->ci] : CLAIM_FAILS;
    tb_settext(r->note, sizeof r->note, "adaptive-region, width 16, face %dx%d; tried in order L 8 then L 4, each with "
            "terms 3, 4, 5, 6, 8, 12; the first that meets 1e-4 is reported (more terms is not always better at "
            "width 16: the network's own rounding grows)", res, res);
}

static void row_auto(claim_result *r, const all *a, int res, double threshold)
{
    int KL = a->KL, KT = a->KT;
    const meas *au3 = &a->au3, *auk = &a->auk;
    r->id = "scene_nmse_auto";
    r->source = WHERE;
    r->claim = "the same with the degree chosen automatically per interval (second difference of the nodes "
               "against a threshold) instead of by face region";
    r->claimed = CLAIM_NMSE;
    int auto_ok3 = au3->nmse <= CLAIM_NMSE, auto_okk = KL && !(KL == 8 && KT == 3) && auk->nmse <= CLAIM_NMSE;
    r->measured = auto_ok3 || !KL || (KL == 8 && KT == 3) ? au3->nmse : auk->nmse;
    if (KL && !(KL == 8 && KT == 3))
        tb_settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g at L 8 with 3 terms (%.0f%% of intervals "
                "degree 2), %.3g at L %d with %d terms (%.0f%%)", au3->nmse, 100 * au3->deg2, auk->nmse, KL, KT,
                100 * auk->deg2);
    else
        tb_settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g at L 8 with 3 terms; %.0f%% of intervals "
                "degree 2", au3->nmse, 100 * au3->deg2);
    r->verdict = auto_ok3 ? CLAIM_HOLDS : auto_okk ? VERDICT[a->ci] : CLAIM_FAILS;
    tb_settext(r->note, sizeof r->note, "adaptive-auto, width 16, face %dx%d, the scene's threshold %g on "
            "|I(0) + I(1) - 2 I(1/2)|; at the settings of scene_nmse_terms", res, res, threshold);
}

static void row_speedup(claim_result *r, const all *a, int res)
{
    int KL = a->KL, KT = a->KT;
    r->id = "scene_speedup";
    r->source = WHERE;
    r->claim = "compared with Phong, up to 3 times faster on a face by fewer costly operations "
               "(here: operations per pixel against an efficient per-pixel shader, weighted, and long ones alone)";
    r->claimed = 3;
    /* the settings measured, shortest L first; the verdict's: the first
     * that reaches 3 in a reading, weighted before long */
    const meas *at[3] = { &a->pa, &a->sp16, &a->sp32 };
    static const int atL[3] = { 8, 16, 32 };
    int hit = -1, hit_long = 0;
    double best = 0;
    for (int i = 0; i < 3; i++) {
        if (!at[i]->ok) continue;
        if (at[i]->speedup > best) best = at[i]->speedup;
        if (at[i]->speedup_long > best) best = at[i]->speedup_long;
        if (hit < 0 && (at[i]->speedup >= 3 || at[i]->speedup_long >= 3)) {
            hit = i;
            hit_long = at[i]->speedup < 3;
        }
    }
    r->measured = hit < 0 ? best : hit_long ? at[hit]->speedup_long : at[hit]->speedup;
    char buf[256] = "", one[128];
    for (int i = 0; i < 3; i++) {
        if (!at[i]->ok) continue;
        snprintf(one, sizeof one, i ? "%s%.3gx/%.3gx at L %d (%.3g)" : "%s%.3gx/%.3gx at L %d (NMSE %.3g)",
                 i ? ", " : "weighted/long ops: ", at[i]->speedup, at[i]->speedup_long, atL[i], at[i]->nmse);
        strncat(buf, one, sizeof buf - strlen(buf) - 1);
    }
    if (KL && !(KL == 8 && KT == 3)) {
        snprintf(one, sizeof one, "; %.3gx/%.3gx at L %d, %d terms (NMSE met)", a->pk.speedup, a->pk.speedup_long,
                 KL, KT);
        strncat(buf, one, sizeof buf - strlen(buf) - 1);
    }
    tb_settext(r->measured_text, sizeof r->measured_text, "%s", buf);
    int meets = hit >= 0 && at[hit]->nmse <= CLAIM_NMSE;
    r->verdict = hit == 0 && !hit_long ? CLAIM_HOLDS
               : hit == 0 ? CLAIM_HOLDS_ONLY "the long operations alone (div, sqrt, pow; weighted: below 3x)"
               : hit > 0 && !hit_long && meets ? CLAIM_HOLDS_ONLY "longer intervals than L 8 (see measured)"
               : hit > 0 && !hit_long ? CLAIM_HOLDS_ONLY "intervals longer than L 8, where NMSE exceeds 0.0001"
               : hit > 0 && meets ? CLAIM_HOLDS_ONLY "the long operations alone (div, sqrt, pow) and intervals "
                                    "longer than L 8 (see measured)"
               : hit > 0 ? CLAIM_HOLDS_ONLY "the long operations alone (div, sqrt, pow) and intervals longer "
                           "than L 8, where NMSE exceeds 0.0001"
               : best > 1 ? CLAIM_HOLDS_ONLY "a smaller speed-up than 3x"
                          : CLAIM_FAILS;
    tb_settext(r->note, sizeof r->note, "face %dx%d, adaptive-region, 3 terms; a Phong pixel costs %.3g weighted, %.3g long "
            "ops (L, V, H once per frame: directional light, orthographic), a node the same, plus network and "
            "Horner; weights add 1 mul 1 div 4 sqrt 4 pow 8 (docs/scenes.md)",
            res, res, a->pa.cost_ref, a->pa.long_ref);
}

size_t tb_scene_claims(claim_result *out, size_t max, int res, int jobs, char *err, size_t errlen)
{
    if (max < TB_SCENE_CLAIMS_ROWS) return 0;
    scn_desc d;
    scn_mesh m;
    scn_gbuf g;
    memset(&m, 0, sizeof m);
    memset(&g, 0, sizeof g);
    if (scn_desc_builtin("face", &d)) { snprintf(err, errlen, "no built-in face scene"); return 0; }
    d.width = d.height = res;
    snprintf(d.fmt_width, sizeof d.fmt_width, "16");
    snprintf(d.schedule, sizeof d.schedule, "paper");
    size_t n = 0;
    all a;
    if (scn_mesh_builtin(d.mesh, d.detail, &m, err, errlen) ||
        scn_raster(&m, &d.view.cam, d.width, d.height, &g, err, errlen) ||
        measure_all(&d, &g, jobs, &a, err, errlen))
        goto done;
    memset(out, 0, TB_SCENE_CLAIMS_ROWS * sizeof *out);
    row_paper(&out[n++], &a, res);
    row_terms(&out[n++], &a, res);
    row_auto(&out[n++], &a, res, d.auto_threshold);
    row_speedup(&out[n++], &a, res);
done:
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
    return n;
}
