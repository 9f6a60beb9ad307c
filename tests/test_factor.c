/* test_factor.c - the homomorphic factorization (vectors/ref_factor.c):
 * the parabolic map and its inverse, bilinear weights, the BRDF models
 * against the independent references of vectors/ref_brdf.c, an exactly
 * separable function recovered, positivity, exact reciprocity, and the
 * half/difference parameterization of the baseline. Small maps (< 1 s). */
#include "tests/tst.h"
#include "vectors/ref_factor.h"
#include "vectors/ref_brdf.h"
#include "vectors/vectors.h"
#include "testbench/tb.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void rand_dir(uint64_t *st, double d[3])
{
    double z = 0.02 + 0.98 * rf_rand(st), ph = 2 * M_PI * rf_rand(st), r = sqrt(1 - z * z);
    d[0] = r * cos(ph); d[1] = r * sin(ph); d[2] = z;
}

static void t_parabolic_round_trip(void)
{
    uint64_t st = 11;
    for (int k = 0; k < 1000; k++) {
        double d[3], e[3], u, v;
        rand_dir(&st, d);
        rf_parab_fwd(d, &u, &v);
        /* the map's definition, written here */
        TST_NEAR(u, d[0] / (1 + d[2]), 1e-15);
        TST_NEAR(v, d[1] / (1 + d[2]), 1e-15);
        TST_CHECK(u * u + v * v < 1, "inside the unit disk");
        rf_parab_inv(u, v, e);
        for (int c = 0; c < 3; c++) TST_NEAR(e[c], d[c], 1e-14);
    }
    double n[3];
    rf_parab_inv(0, 0, n);
    TST_NEAR(n[2], 1, 0);
    rf_parab_inv(1, 0, n);          /* the rim is the horizon */
    TST_NEAR(n[2], 0, 1e-15);
}

static void t_bilinear_weights(void)
{
    uint64_t st = 5;
    int R = 8;
    double tex[64];
    /* a linear function of the texel centres is reproduced exactly inside */
    for (int j = 0; j < R * R; j++) {
        double u = -1 + (j % R + 0.5) * 2.0 / R, v = -1 + (j / R + 0.5) * 2.0 / R;
        tex[j] = 3 * u - 2 * v + 0.5;
    }
    for (int k = 0; k < 1000; k++) {
        double u = 2 * rf_rand(&st) - 1, v = 2 * rf_rand(&st) - 1;
        rf_tap t;
        rf_bilin(R, u, v, &t);
        double s = 0;
        for (int i = 0; i < 4; i++) { s += t.w[i]; TST_CHECK(t.w[i] >= 0, "weight %g", t.w[i]); }
        TST_NEAR(s, 1, 1e-15);
        if (fabs(u) < 1 - 1.0 / R && fabs(v) < 1 - 1.0 / R)
            TST_NEAR(rf_tap_apply(&t, tex), 3 * u - 2 * v + 0.5, 1e-13);
    }
}

static void t_models_match_references(void)
{
    uint64_t st = 3;
    const double n[3] = { 0, 0, 1 };
    rf_brdf w, b;
    char err[200];
    TST_CHECK(!rf_brdf_init(&w, "ward", err, sizeof err), "%s", err);
    TST_CHECK(!rf_brdf_param(&w, "alpha=0.25", err, sizeof err), "%s", err);
    TST_CHECK(!rf_brdf_init(&b, "blinn", err, sizeof err), "%s", err);
    for (int k = 0; k < 500; k++) {
        double d0[3], di[3];
        rand_dir(&st, d0);
        rand_dir(&st, di);
        double r = ref_brdf_ward(di, n, d0, 1, 0.25);
        TST_NEAR(rf_brdf_eval(&w, d0, di), r, 1e-12 * (1 + r));
        TST_NEAR(rf_brdf_eval(&b, d0, di), ref_brdf_blinn(di, n, d0, 32), 1e-12);
    }
}

/* An exactly separable function in the fit's own form: the exp of the
 * bilinear lookups of two random smooth log tables, evaluated here with
 * a bilinear lookup written in the test. */
#define SR 8
static double lt[SR * SR], pt[SR * SR];

static double look(const double *tab, const double d[3])
{
    double u = d[0] / (1 + d[2]), v = d[1] / (1 + d[2]);
    double s = (u + 1) * SR / 2 - 0.5, t = (v + 1) * SR / 2 - 0.5;
    s = s < 0 ? 0 : s > SR - 1 ? SR - 1 : s;
    t = t < 0 ? 0 : t > SR - 1 ? SR - 1 : t;
    int i = s >= SR - 1 ? SR - 2 : (int)s, j = t >= SR - 1 ? SR - 2 : (int)t;
    double a = s - i, c = t - j;
    return (1 - a) * (1 - c) * tab[j * SR + i] + a * (1 - c) * tab[j * SR + i + 1]
         + (1 - a) * c * tab[(j + 1) * SR + i] + a * c * tab[(j + 1) * SR + i + 1];
}

static double separable(const double d0[3], const double di[3], void *user)
{
    (void)user;
    double h[3] = { d0[0] + di[0], d0[1] + di[1], d0[2] + di[2] }, l = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (int c = 0; c < 3; c++) h[c] /= l;
    return exp(look(lt, d0) + look(pt, h) + look(lt, di));
}

static void t_separable_recovered(void)
{
    for (int j = 0; j < SR * SR; j++) {
        int x = j % SR, y = j / SR;
        lt[j] = 0.3 * sin(0.7 * x + 0.2) + 0.2 * cos(0.9 * y);
        pt[j] = -0.5 * ((x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5)) / 8 + 0.1 * x;
    }
    rf_opts o;
    rf_opts_default(&o);
    o.R = SR; o.samples = 4000; o.smooth = 0; o.floor = 0; o.tol = 1e-14; o.max_iter = 5000;
    rf_fact f;
    char err[200];
    if (rf_factorize(separable, NULL, &o, &f, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    TST_CHECK(f.used == 4000 - f.skipped, "every sample in the fit");
    uint64_t st = 99;
    double worst = 0;
    for (int k = 0; k < 2000; k++) {
        double d0[3], di[3];
        rand_dir(&st, d0);
        rand_dir(&st, di);
        double r = separable(d0, di, NULL), a = rf_fact_eval_log(&f, d0, di);
        if (fabs(a / r - 1) > worst) worst = fabs(a / r - 1);
    }
    TST_CHECK(worst <= 1e-6, "largest relative error %g", worst);
    rf_fact_free(&f);
}

static void t_positive_and_reciprocal(void)
{
    static const char *const names[] = { "ct", "ward-aniso" };
    for (int m = 0; m < 2; m++) {
        rf_brdf b;
        char err[200];
        TST_CHECK(!rf_brdf_init(&b, names[m], err, sizeof err), "%s", err);
        if (m == 0) TST_CHECK(!rf_brdf_param(&b, "dist=d8", err, sizeof err), "%s", err);
        rf_opts o;
        rf_opts_default(&o);
        o.R = 8;
        rf_fact f;
        if (rf_factorize(rf_brdf_fn, &b, &o, &f, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
        for (int j = 0; j < 64; j++) {
            TST_CHECK(f.lam[j] > 0 && isfinite(f.lam[j]), "lambda[%d] = %g", j, f.lam[j]);
            TST_CHECK(f.pi[j] > 0 && isfinite(f.pi[j]), "pi[%d] = %g", j, f.pi[j]);
        }
        uint64_t st = 17;
        for (int k = 0; k < 2000; k++) {
            double d0[3], di[3];
            rand_dir(&st, d0);
            rand_dir(&st, di);
            double a = rf_fact_eval(&f, d0, di), b2 = rf_fact_eval(&f, di, d0);
            TST_CHECK(a > 0, "approximation %g", a);
            TST_CHECK(a == b2, "f(a, b) = %.17g, f(b, a) = %.17g", a, b2);
            TST_CHECK(rf_fact_eval_log(&f, d0, di) == rf_fact_eval_log(&f, di, d0), "log model not reciprocal");
        }
        rf_fact_free(&f);
    }
}

/* The Gauss-Newton refinement fits the texel values: the texture-lookup
 * evaluation's relative error falls, the factors stay positive and the
 * log-space solution (llam, lpi) is the same with or without it. */
static void t_refine_helps(void)
{
    rf_brdf b;
    char err[200];
    TST_CHECK(!rf_brdf_init(&b, "ward", err, sizeof err), "%s", err);
    rf_opts o;
    rf_opts_default(&o);
    o.R = 8;
    rf_fact f0, f3;
    o.refine = 0;
    if (rf_factorize(rf_brdf_fn, &b, &o, &f0, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    o.refine = 3;
    if (rf_factorize(rf_brdf_fn, &b, &o, &f3, err, sizeof err)) { TST_CHECK(0, "%s", err); rf_fact_free(&f0); return; }
    rf_err e0, e3;
    rf_error(rf_brdf_fn, &b, rf_fact_fn, &f0, 3000, 77, 1e-4, &e0);
    rf_error(rf_brdf_fn, &b, rf_fact_fn, &f3, 3000, 77, 1e-4, &e3);
    TST_CHECK(e3.rel_rms < 0.9 * e0.rel_rms, "refined %g, unrefined %g", e3.rel_rms, e0.rel_rms);
    for (int j = 0; j < 64; j++) {
        TST_CHECK(f3.lam[j] > 0 && f3.pi[j] > 0, "texel %d", j);
        TST_NEAR(f3.llam[j], f0.llam[j], 0);
    }
    rf_fact_free(&f0);
    rf_fact_free(&f3);
}

static void t_half_difference(void)
{
    uint64_t st = 23;
    for (int k = 0; k < 500; k++) {
        double d0[3], di[3], h[3], d[3];
        rand_dir(&st, d0);
        rand_dir(&st, di);
        rf_half_diff(d0, di, h, d);
        double hl = sqrt((d0[0] + di[0]) * (d0[0] + di[0]) + (d0[1] + di[1]) * (d0[1] + di[1]) + (d0[2] + di[2]) * (d0[2] + di[2]));
        TST_NEAR(h[2], (d0[2] + di[2]) / hl, 1e-14);
        /* a rotation: unit length, and the angle to h becomes the angle to the normal */
        TST_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1, 1e-14);
        TST_NEAR(d[2], (h[0] * di[0] + h[1] * di[1] + h[2] * di[2]), 1e-14);
    }
}

static void t_bad_parameters(void)
{
    rf_brdf b;
    char err[200];
    TST_CHECK(rf_brdf_init(&b, "phong2", err, sizeof err) == -1, "unknown name accepted");
    TST_CHECK(!rf_brdf_init(&b, "ct", err, sizeof err), "%s", err);
    TST_CHECK(rf_brdf_param(&b, "m=nan", err, sizeof err) == -1, "nan accepted");
    TST_CHECK(rf_brdf_param(&b, "m=inf", err, sizeof err) == -1, "inf accepted");
    TST_CHECK(rf_brdf_param(&b, "m=5", err, sizeof err) == -1, "m out of range accepted");
    TST_CHECK(rf_brdf_param(&b, "q=1", err, sizeof err) == -1, "unknown key accepted");
    TST_CHECK(rf_brdf_param(&b, "dist=d3", err, sizeof err) == -1, "unknown distribution accepted");
}

/* The hf_lookup unit at wide formats: the hardware equals the float
 * lookup (the vector model's expected outputs, computed here again from
 * the maps) within the unit's derived bound, and the bound is small. */
static void t_hf_lookup_wide(void)
{
    const unit_desc *u = unit_find("hf_lookup");
    const vec_model *m = u ? u->ref : NULL;
    if (!u || !m) { TST_CHECK(0, "hf_lookup not registered"); return; }
    static const int L[2] = { 8, 16 }, W[2] = { 24, 32 };
    for (int k = 0; k < 2; k++) {
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        cfg.width = W[k];
        cfg.L = L[k];
        vec_params p;
        vec_params_default(&p);
        p.L = L[k];
        p.alpha = cfg.alpha;
        vec_set vs;
        vec_set_init(&vs);
        vec_set_header(&vs, m, &p);
        TST_CHECK(!m->gen(&p, 200, 5, &vs), "vectors");
        const rf_maps *mp = rf_ward_maps(L[k], cfg.alpha);
        TST_CHECK(mp != NULL, "maps");
        /* the expected output is the product of three bilinear lookups */
        for (size_t i = 0; mp && i < vs.n_rows; i++) {
            const double *r = vec_row(&vs, i);
            TST_NEAR(r[9], rf_maps_lookup(mp, r, r + 3, r + 6), 1e-15);
        }
        unit_fmts f;
        u->formats(&cfg, &f);
        tb_result res;
        char err[300];
        int rc = tb_run(u, &cfg, &f, &vs, NULL, &res, err, sizeof err);
        TST_CHECK(rc == TB_OK, "%s", err);
        if (rc == TB_OK) {
            TST_CHECK(res.bound_check == TB_CHECK_OK, "check %s", tb_check_name(res.bound_check));
            TST_CHECK(res.out[0].max_abs_err <= res.out[0].bound + 1e-12, "golden error %g over bound %g",
                      res.out[0].max_abs_err, res.out[0].bound);
            TST_CHECK(res.out[0].bound < (W[k] == 32 ? 1e-5 : 1e-3), "bound %g", res.out[0].bound);
            TST_EQ_INT(res.overflows, 0);
            TST_NEAR(res.cycles_per_item, 1, 0);
        }
        tb_result_free(&res);
        vec_set_free(&vs);
    }
}

int main(void)
{
    TST_RUN(t_parabolic_round_trip);
    TST_RUN(t_bilinear_weights);
    TST_RUN(t_models_match_references);
    TST_RUN(t_separable_recovered);
    TST_RUN(t_positive_and_reciprocal);
    TST_RUN(t_refine_helps);
    TST_RUN(t_half_difference);
    TST_RUN(t_bad_parameters);
    TST_RUN(t_hf_lookup_wide);
    TST_EXIT();
}
