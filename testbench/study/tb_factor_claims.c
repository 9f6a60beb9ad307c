/* tb_factor_claims.c - the factorization paper's claims as claims rows
 * (tb_factor_claims.h): measured on held-out direction pairs against the
 * rank-1..4 sums of products (SVD), the operation counts from the
 * structure, Fig. 1 through the simulated hf_lookup unit. */
#include "testbench/study/tb_factor_claims.h"
#include "testbench/tb.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define SEED "Romanyuk et al. (2020)"

/* Operations per light of the exact Ward specular term as the reference
 * evaluates it (vectors/ref_factor.c): h = norm(d0 + di) (1 sqrt, 1
 * divide), the exponent (2 divides by ax, ay, 1 by (h.n)^2), exp, and
 * 1/(4 pi ax ay sqrt(N.L N.V)) (1 sqrt, 1 divide): 2 sqrt, 5 divides, 1 exp.
 * The factorized form: 3 lookups and 2 multiplications. */
#define WARD_SQRT 2
#define WARD_DIV 5
#define WARD_EXP 1
#define FACT_OPS 5

static claim_result *row(claim_result *out, size_t *n, size_t max, const char *id, const char *seed,
                         const char *claim, double measured, int holds)
{
    if (*n >= max) return NULL;
    claim_result *r = &out[(*n)++];
    memset(r, 0, sizeof *r);
    r->id = id;
    r->source = seed;
    r->claim = claim;
    r->claimed = NAN;
    r->measured = isfinite(measured) ? measured : 0;
    r->verdict = holds ? CLAIM_HOLDS : CLAIM_FAILS;
    return r;
}

size_t tb_factor_claims_rows(rf_brdf *b, const rf_fact *f, const rf_opts *o, long heldout,
                             const tb_factor_scene_result *sr, claim_result *out, size_t max,
                             char *err, size_t errlen)
{
    rf_err fe, fl, s1;
    uint64_t hs = o->seed + 1000;
    rf_error(rf_brdf_fn, b, rf_fact_fn, (void *)f, heldout, hs, o->floor, &fe);
    rf_error(rf_brdf_fn, b, rf_fact_log_fn, (void *)f, heldout, hs, o->floor, &fl);
    rf_svd s;
    int rs = o->R < 32 ? o->R : 32;
    if (rf_svd_fit(rf_brdf_fn, b, rs, 4, &s, err, errlen)) return 0;
    double neg_svd = 0, recip_svd = 0;
    for (int k = 1; k <= 4; k++) {
        rf_err e;
        s.k_used = k;
        rf_error(rf_brdf_fn, b, rf_svd_fn, &s, heldout, hs, o->floor, &e);
        if (e.neg_share > neg_svd) neg_svd = e.neg_share;
        if (e.recip_max > recip_svd) recip_svd = e.recip_max;
    }
    s.k_used = 1;
    rf_error(rf_brdf_fn, b, rf_svd_fn, &s, heldout, hs, o->floor, &s1);
    rf_svd_free(&s);

    size_t n = 0;
    char desc[160];
    rf_brdf_describe(b, desc, sizeof desc);
    claim_result *r = row(out, &n, max, "positive_factors", SEED ", abstract",
        "the factorization has only positive factors (the SVD has negative values)",
        fmin(f->lam_min, f->pi_min), f->lam_min > 0 && f->pi_min > 0 && fe.neg_share == 0);
    if (r) {
        tb_settext(r->measured_text, sizeof r->measured_text,
                   "smallest texel lambda %.3g pi %.3g; negative values: factorization %.2f%%, sum of products "
                   "rank 1..4 up to %.3f%%", f->lam_min, f->pi_min, 100 * fe.neg_share, 100 * neg_svd);
        tb_settext(r->note, sizeof r->note, "%s, %dx%d maps, %ld held-out pairs; measured: the smallest texel",
                   desc, o->R, o->R, heldout);
    }
    r = row(out, &n, max, "reciprocity", SEED, "the approximation always satisfies Helmholtz reciprocity",
            fe.recip_max, fe.recip_max == 0);
    if (r) {
        tb_settext(r->measured_text, sizeof r->measured_text,
                   "max |f(a,b) - f(b,a)| / max f: factorization %.3g, sum of products %.3g", fe.recip_max, recip_svd);
        tb_settext(r->note, sizeof r->note, "%s, %dx%d maps, %ld held-out pairs, each with its swap", desc, o->R,
                   o->R, heldout);
    }
    r = row(out, &n, max, "relative_error", SEED ", abstract",
            "it minimizes relative rather than absolute error (two 2D maps, one term)", fl.rel_rms,
            fl.rel_rms < s1.rel_rms);
    if (r) {
        tb_settext(r->measured_text, sizeof r->measured_text,
                   "relative RMS %.4f (fitted model %.4f) against %.4f for the rank-1 sum of products; NRMS %.4f "
                   "against %.4f", fe.rel_rms, fl.rel_rms, s1.rel_rms, fe.nrms, s1.nrms);
        tb_settext(r->note, sizeof r->note, "%s, %dx%d maps, %ld held-out pairs; measured: the fitted model's "
                   "relative RMS; holds when below the rank-1 sum of products' (the same storage)", desc, o->R,
                   o->R, heldout);
    }
    r = row(out, &n, max, "few_operations", SEED, "a BRDF from a few texture lookups and multiplications",
            FACT_OPS, b->kind == RF_WARD);
    if (r) {
        tb_settext(r->measured_text, sizeof r->measured_text,
                   "per light: 3 bilinear lookups and 2 multiplications, no sqrt, divide or exp (the exact Ward: "
                   "%d sqrt, %d divides, %d exp)", WARD_SQRT, WARD_DIV, WARD_EXP);
        tb_settext(r->note, sizeof r->note,
                   "in hf_lookup the addresses and filters add 6 multipliers a lookup, one evaluation a clock "
                   "(counts from the structure, not a timing); measured: lookups + multiplications");
    }
    if (sr) {
        r = row(out, &n, max, "fig1_vertex_vs_pixel", SEED ", Fig. 1",
                "factorized per pixel looks closer to the BRDF than its exact values at the vertices "
                "interpolated (Fig. 1)", sr->nmse_factor, sr->nmse_factor < sr->nmse_vertex);
        if (r) {
            tb_settext(r->measured_text, sizeof r->measured_text,
                       "specular NMSE against exact per pixel: factorized per pixel (hf_lookup) %.3e, exact at "
                       "vertices interpolated %.3e (%dx%d)", sr->nmse_factor, sr->nmse_vertex, sr->w, sr->h);
            tb_settext(r->note, sizeof r->note, "%s, %dx%d maps, hf_lookup simulated clock by clock (%llu "
                       "clocks, %.0f GE); measured: the factorized NMSE", desc, o->R, o->R,
                       (unsigned long long)sr->clocks, sr->area_ge);
        }
    }
    return n;
}

size_t tb_factor_claims(claim_result *out, size_t max, char *err, size_t errlen)
{
    rf_brdf b;
    if (rf_brdf_init(&b, "ward", err, errlen)) return 0;
    rf_opts o;
    rf_opts_default(&o);
    rf_fact f;
    if (rf_factorize(rf_brdf_fn, &b, &o, &f, err, errlen)) return 0;
    tb_factor_scene_result sr;
    size_t n = 0;
    if (!tb_factor_scene(TB_FACTOR_CLAIMS_SCENE, o.R, b.ax, TB_FACTOR_CLAIMS_WIDTH, TB_FACTOR_CLAIMS_RES, NULL, &sr,
                         err, errlen))
        n = tb_factor_claims_rows(&b, &f, &o, TB_FACTOR_HELDOUT, &sr, out, max, err, errlen);
    rf_fact_free(&f);
    return n;
}
