/* tb_scene_claims.c - the paper's face-scene claims, measured through the
 * simulated hardware path (tb_scene_render): every pixel of the face is
 * interpolated by the cycle-accurate span unit and compared with per-pixel
 * Phong shading in double precision.
 *
 * Rows (verdicts follow from the measured numbers, never fixed):
 *   scene_nmse_paper  adaptive-region (degree by face region), L 8, the
 *                     paper's 3-term divide-by-3 network, width 16;
 *   scene_nmse_terms  the same with the fewest terms (3..MAX_TERMS) that
 *                     meet NMSE <= 1e-4;
 *   scene_nmse_auto   adaptive-auto (degree from the node differences)
 *                     with 3 terms, else with that fewest number;
 *   scene_speedup     cost of per-pixel Phong over the method's cost
 *                     (weighted operation counts, docs/scenes.md) at L 8;
 *                     when below 3, the longer intervals 16 and 32 are
 *                     tried, with their NMSE.
 */
#include "testbench/tb_scene_claims.h"
#include "testbench/tb_scene.h"
#include "testbench/tb.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define MAX_TERMS 12
#define CLAIM_NMSE 1e-4

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void settext(char *dst, size_t size, const char *fmt, ...)
{
    char tmp[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    size_t n = strlen(tmp);
    if (n >= size) n = size - 1;
    memcpy(dst, tmp, n);
    dst[n] = 0;
}

typedef struct meas { int ok; double nmse, speedup, deg2, cost_ref, cost_hw; } meas;

static int measure(const scn_desc *d0, const scn_gbuf *g, scn_policy pol, int L, int terms, int jobs, meas *out,
                   char *err, size_t errlen)
{
    scn_desc d = *d0;
    d.policy = pol;
    d.L = L;
    d.terms = terms;
    tb_scene_opts o = { jobs, 0, NULL, NULL };
    tb_scene_result r;
    memset(&r, 0, sizeof r);
    memset(out, 0, sizeof *out);
    int rc = tb_scene_render_gbuf(&d, g, NULL, NULL, &o, &r, err, errlen);
    if (rc == TB_OK) {
        out->ok = 1;
        out->nmse = r.nmse;
        out->speedup = r.speedup;
        out->deg2 = r.deg2_share;
        out->cost_ref = r.cost_ref;
        out->cost_hw = r.cost_hw;
    }
    tb_scene_free(&r);
    return rc == TB_OK ? 0 : -1;
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
    d.fmt_width = 16;
    snprintf(d.schedule, sizeof d.schedule, "paper");
    size_t n = 0;
    if (scn_mesh_builtin(d.mesh, d.detail, &m, err, errlen) ||
        scn_raster(&m, &d.view.cam, d.width, d.height, &g, err, errlen))
        goto done;

    /* (a) the paper's configuration. */
    meas pa, pk = { 0 }, au3, auk = { 0 }, sp16 = { 0 }, sp32 = { 0 };
    if (measure(&d, &g, SCN_POL_ADAPTIVE_REGION, 8, 3, jobs, &pa, err, errlen)) goto done;
    /* (b) the fewest terms that hold. */
    int K = 0;
    if (pa.nmse <= CLAIM_NMSE) { K = 3; pk = pa; }
    for (int t = 4; !K && t <= MAX_TERMS; t++) {
        if (measure(&d, &g, SCN_POL_ADAPTIVE_REGION, 8, t, jobs, &pk, err, errlen)) goto done;
        if (pk.nmse <= CLAIM_NMSE) K = t;
    }
    /* (c) automatic degree. */
    if (measure(&d, &g, SCN_POL_ADAPTIVE_AUTO, 8, 3, jobs, &au3, err, errlen)) goto done;
    if (K > 3 && measure(&d, &g, SCN_POL_ADAPTIVE_AUTO, 8, K, jobs, &auk, err, errlen)) goto done;
    /* (d) longer intervals, if L 8 falls short of 3x. */
    if (pa.speedup < 3) {
        if (measure(&d, &g, SCN_POL_ADAPTIVE_REGION, 16, K ? K : 3, jobs, &sp16, err, errlen)) goto done;
        if (sp16.speedup < 3 && measure(&d, &g, SCN_POL_ADAPTIVE_REGION, 32, K ? K : 3, jobs, &sp32, err, errlen))
            goto done;
    }

    memset(out, 0, TB_SCENE_CLAIMS_ROWS * sizeof *out);
    const char *where = "000 sec. IV (conclusion)";
    claim_result *r = &out[n++];
    r->id = "scene_nmse_paper";
    r->seed = where;
    r->claim = "adaptive degree 2/3 on a face gives NMSE no more than 0.0001 against Phong "
               "(here: degree by face region, the paper's 3-term divide-by-3 network, through the simulated hardware)";
    r->claimed = CLAIM_NMSE;
    r->measured = pa.nmse;
    settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g (adaptive-region, L 8, 3 terms, width 16); "
            "%.0f%% of intervals degree 2", pa.nmse, 100 * pa.deg2);
    r->verdict = pa.nmse <= CLAIM_NMSE ? CLAIM_HOLDS
               : K ? CLAIM_HOLDS_ONLY "more terms of the divide-by-3 network (see scene_nmse_terms)"
                   : CLAIM_FAILS;
    settext(r->note, sizeof r->note, "built-in face at %dx%d (lower than the default 512x512 to keep claims fast), "
            "every pixel through the cycle-accurate span unit, per-pixel Phong in double as reference; "
            "the 3-term network's 1/3 is 43/128", res, res);

    r = &out[n++];
    r->id = "scene_nmse_terms";
    r->seed = where;
    r->claim = "the same with enough terms in the divide-by-3 network (the fewest that meet NMSE 0.0001)";
    r->claimed = CLAIM_NMSE;
    r->measured = pk.nmse;
    if (K) settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g with %d terms (3 terms: %.3g)",
                   pk.nmse, K, pa.nmse);
    else settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g with %d terms, still above; 3 terms: %.3g",
                 pk.nmse, MAX_TERMS, pa.nmse);
    r->verdict = K == 3 ? CLAIM_HOLDS : K ? CLAIM_HOLDS_ONLY "the number of terms in measured (or more)"
                                          : CLAIM_FAILS;
    settext(r->note, sizeof r->note, "adaptive-region, L 8, width 16, face %dx%d; terms tried 3..%d in order, the "
            "first that meets 1e-4 is reported", res, res, MAX_TERMS);

    r = &out[n++];
    r->id = "scene_nmse_auto";
    r->seed = where;
    r->claim = "the same with the degree chosen automatically per interval (second difference of the nodes "
               "against a threshold) instead of by face region";
    r->claimed = CLAIM_NMSE;
    int auto_k = au3.nmse <= CLAIM_NMSE ? 3 : K > 3 && auk.nmse <= CLAIM_NMSE ? K : 0;
    r->measured = auto_k == 3 || K <= 3 ? au3.nmse : auk.nmse;
    if (K > 3)
        settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g with 3 terms, %.3g with %d terms; "
                "%.0f%% of intervals degree 2", au3.nmse, auk.nmse, K, 100 * au3.deg2);
    else
        settext(r->measured_text, sizeof r->measured_text, "NMSE %.3g with 3 terms; %.0f%% of intervals degree 2",
                au3.nmse, 100 * au3.deg2);
    r->verdict = auto_k == 3 ? CLAIM_HOLDS : auto_k ? CLAIM_HOLDS_ONLY "the number of terms of scene_nmse_terms"
                                                    : CLAIM_FAILS;
    settext(r->note, sizeof r->note, "adaptive-auto, L 8, width 16, face %dx%d, the scene's threshold %g on "
            "|I(0) + I(1) - 2 I(1/2)|", res, res, d.auto_threshold);

    r = &out[n++];
    r->id = "scene_speedup";
    r->seed = where;
    r->claim = "compared with Phong, up to 3 times faster on a face by fewer costly operations "
               "(here: weighted operation counts per pixel)";
    r->claimed = 3;
    double best = pa.speedup;
    int bestL = 8;
    if (sp16.speedup > best) { best = sp16.speedup; bestL = 16; }
    if (sp32.speedup > best) { best = sp32.speedup; bestL = 32; }
    r->measured = best;
    if (bestL == 8)
        settext(r->measured_text, sizeof r->measured_text, "%.3gx at L 8 (Phong %.3g, method %.3g per pixel)",
                pa.speedup, pa.cost_ref, pa.cost_hw);
    else
        settext(r->measured_text, sizeof r->measured_text, "%.3gx at L 8 (NMSE %.3g); %.3gx at L %d (NMSE %.3g, "
                "%d terms)", pa.speedup, pa.nmse, best, bestL, bestL == 16 ? sp16.nmse : sp32.nmse, K ? K : 3);
    const meas *bm = bestL == 8 ? &pa : bestL == 16 ? &sp16 : &sp32;
    r->verdict = pa.speedup >= 3 ? CLAIM_HOLDS
               : best >= 3 && bm->nmse <= CLAIM_NMSE ? CLAIM_HOLDS_ONLY "longer intervals than L 8 (see measured)"
               : best >= 3 ? CLAIM_HOLDS_ONLY "longer intervals than L 8, where NMSE exceeds 0.0001"
               : best > 1 ? CLAIM_HOLDS_ONLY "a smaller speed-up than 3x"
                          : CLAIM_FAILS;
    settext(r->note, sizeof r->note, "face %dx%d, adaptive-region; node shading costs what a Phong pixel costs, "
            "plus the coefficient network per interval and Horner per pixel; default weights (docs/scenes.md)",
            res, res);
done:
    scn_gbuf_free(&g);
    scn_mesh_free(&m);
    return n;
}
