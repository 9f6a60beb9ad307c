/* cli_factor.c - shadesim factor: a BRDF factorized into lambda(d0) pi(h)
 * lambda(di) (vectors/ref_factor.c), its error against the BRDF and
 * against the rank-K sum-of-products baseline, the maps as PNG and raw
 * floats, and a study over resolutions and sample counts. The study, the
 * claims and the Fig. 1 scene through the hardware are
 * testbench/study/tb_factor_*.c's; this file parses, prints and writes. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include <stddef.h>
#include "vectors/ref_factor.h"
#include "testbench/study/tb_factor_scene.h"
#include "testbench/study/tb_factor_claims.h"
#include "testbench/study/tb_factor_study.h"
#include "scene/scene.h"
#include "base/base_near.h"
#include "base/base_out.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A map as grey PNG: log of the texel scaled from [lo, hi] to 0..255,
 * each texel a square of k pixels (k: the image at least 256 wide). */
static int write_map_png(const char *path, const double *logtex, int R, double *lo_out, double *hi_out,
                         char *err, size_t errlen)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int j = 0; j < R * R; j++) {
        if (logtex[j] < lo) lo = logtex[j];
        if (logtex[j] > hi) hi = logtex[j];
    }
    *lo_out = lo; *hi_out = hi;
    int k = R >= 256 ? 1 : (256 + R - 1) / R, W = R * k;
    uint8_t *pix = malloc((size_t)W * W);
    if (!pix) base_out_of_memory();
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            /* image rows top to bottom = v from +1 to -1 */
            double t = hi > lo ? (logtex[(R - 1 - y / k) * R + x / k] - lo) / (hi - lo) : 0.5;
            pix[(size_t)y * W + x] = (uint8_t)lrint(255 * t);
        }
    uint8_t *png = NULL;
    size_t len = 0;
    int rc = scn_png_encode(W, W, 1, pix, &png, &len);
    free(pix);
    if (rc) base_out_of_memory();
    rc = base_out_write_all(path, png, len, err, errlen);
    free(png);
    return rc;
}

static int write_f32(const char *path, const rf_fact *f, char *err, size_t errlen)
{
    size_t T = (size_t)f->R * f->R;
    uint8_t *buf = malloc(8 * T);
    if (!buf) base_out_of_memory();
    for (size_t j = 0; j < 2 * T; j++) {
        float v = (float)(j < T ? f->lam[j] : f->pi[j - T]);
        uint32_t u;
        memcpy(&u, &v, 4);
        for (int b = 0; b < 4; b++) buf[4 * j + b] = (uint8_t)(u >> (8 * b));
    }
    int rc = base_out_write_all(path, buf, 8 * T, err, errlen);
    free(buf);
    return rc;
}

static void print_line(const char *method, const rf_err *e)
{
    printf("  %-14s rel RMS %8.4f  NRMS %8.4f  max rel %9.3f at (%4.1f, %4.1f) deg  negative %6.2f%%  reciprocity %.1e\n",
           method, e->rel_rms, e->nrms, e->rel_max, e->max_t0, e->max_ti, 100 * e->neg_share, e->recip_max);
}

/* The claims (tb_factor_claims_rows, shared with the claims verb): a line
 * each on stdout, DIR/claims.csv (tb_factor_claims_csv). */
static int write_claims(rf_brdf *b, const rf_fact *f, const rf_opts *o, long heldout, const char *dir,
                        const tb_factor_scene_result *sr, char *err, size_t errlen, int *fails)
{
    claim_result rows[TB_FACTOR_CLAIMS_ROWS];
    size_t n = tb_factor_claims_rows(b, f, o, heldout, sr, rows, TB_FACTOR_CLAIMS_ROWS, err, errlen);
    if (!n) return -1;
    char *buf = NULL;
    size_t len = 0;
    FILE *cf = open_memstream(&buf, &len);
    if (!cf) base_out_of_memory();
    tb_factor_claims_csv(cf, rows, n, sr != NULL);
    printf("claims (%dx%d maps, %ld held-out pairs):\n", o->R, o->R, heldout);
    for (size_t i = 0; i < n; i++) {
        const claim_result *r = &rows[i];
        int holds = claims_verdict_kind(r->verdict) == 1;
        printf("  %-22s %-13s %s\n", r->id, holds ? "holds" : "DOES NOT HOLD", r->measured_text);
        if (!holds) ++*fails;
    }
    if (!sr) printf("  %-22s %-13s %s\n", "fig1_vertex_vs_pixel", "not measured", "give --scene NAME");
    fclose(cf);
    char path[700];
    snprintf(path, sizeof path, "%s/claims.csv", dir);
    int rc = base_out_write_all(path, buf, len, err, errlen);
    free(buf);
    return rc;
}

typedef struct factor_args {
    rf_opts o;
    rf_brdf *b;
    long svd_k, heldout, hw_width, scene_res;
    int study, claims;
    const char *scene, *dir;
} factor_args;

static int o_floor(void *base, const char *opt, const char *v)
{
    factor_args *a = base;
    if (cli_parse_real(opt, v, 0, HUGE_VAL, "a finite number >= 0", &a->o.floor)) return CLI_USAGE;
    if (a->o.floor >= 1) return cli_usage_error("--floor %s: expected a number in [0, 1)", v);
    return 0;
}

static int o_param(void *base, const char *opt, const char *v)
{
    char err[600];
    (void)opt;
    if (rf_brdf_param(((factor_args *)base)->b, v, err, sizeof err)) return cli_usage_error("%s", err);
    return 0;
}

static int o_seed(void *base, const char *opt, const char *v)
{
    long x;
    if (cli_parse_long(opt, v, 0, 1000000000, NULL, &x)) return CLI_USAGE;
    ((factor_args *)base)->o.seed = (uint64_t)x;
    return 0;
}

#define F_MISSING "%s: missing value (see shadesim factor --help)"
#define F_NUM(NAME, KIND, FIELD, LO, HI, HELP) { NAME, NULL, KIND, offsetof(factor_args, FIELD), LO, HI, NULL, \
    F_MISSING, NULL, 0, HELP }
#define F_CALL(NAME, FN, HELP) { NAME, NULL, CLI_OPT_CALL, 0, 0, 0, NULL, F_MISSING, FN, 0, HELP }
#define F_STR(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_STR, offsetof(factor_args, FIELD), 0, 0, NULL, F_MISSING, NULL, 0, HELP }
#define F_FLAG(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_FLAG, offsetof(factor_args, FIELD), 0, 0, NULL, NULL, NULL, 0, HELP }
static const cli_opt factor_tab[] = {
    F_NUM("--res", CLI_OPT_INT, o.R, 2, 256, "  --res R          texture side, 2..256 (default 32)\n"),
    F_NUM("--samples", CLI_OPT_LONG, o.samples, 1, 10000000,
          "  --samples N      direction pairs sampled, 1..10000000 (default 24 R^2)\n"),
    { "--smooth", NULL, CLI_OPT_REAL, offsetof(factor_args, o.smooth), 0, HUGE_VAL, "a finite number >= 0", F_MISSING,
      NULL, 0, "  --smooth S       smoothness weight >= 0 (default 0.3)\n" },
    F_CALL("--floor", o_floor,
           "  --floor F        samples below F times the 99th percentile are left out of\n"
           "                   the fit and of the relative errors (default 1e-4)\n"),
    F_CALL("--param", o_param,
           "  --param K=V      BRDF parameter (repeatable): blinn e; ct dist=beckmann|d4|\n"
           "                   d8|d16|schlick|mschlick, m, n, fresnel=none|schlick, f0,\n"
           "                   shadow=0|1; ward alpha (= ax = ay), ax, ay, rho\n"),
    F_NUM("--svd", CLI_OPT_LONG, svd_k, 0, 8,
          "  --svd K          rank of the baseline, 0..8 (default 4; its resolution is\n"
          "                   min(R, 32))\n"),
    F_NUM("--heldout", CLI_OPT_LONG, heldout, 100, 10000000,
          "  --heldout N      held-out pairs for the errors (default 20000)\n"),
    F_NUM("--refine", CLI_OPT_INT, o.refine, 0, 50,
          "  --refine N       Gauss-Newton steps fitting the texel values themselves, as\n"
          "                   bilinear texture hardware reads them, from the log-space\n"
          "                   solution (default 3; 0: the log-space solution only)\n"),
    F_CALL("--seed", o_seed, "  --seed N         sampling seed (default 1)\n"),
    F_FLAG("--claims", claims,
           "  --claims         also DIR/claims.csv: what the paper states (positive\n"
           "                   factors, reciprocity, relative-error minimization, few\n"
           "                   costly operations) next to what we measure, with a verdict\n"),
    F_STR("--scene", scene,
          "  --scene NAME     the paper's Fig. 1 on a built-in scene (face, sphere, torus):\n"
          "                   Ward's specular term exact at the vertices and interpolated,\n"
          "                   factorized per pixel through the simulated hf_lookup unit\n"
          "                   (maps at --res, which must be 4, 8, 16 or 32; roughness\n"
          "                   --param alpha), exact per pixel: NMSE of each against the\n"
          "                   last; DIR/vertex.png, factorized.png, exact.png (ward only)\n"),
    F_NUM("--width", CLI_OPT_LONG, hw_width, 8, 32, "  --width W        hf_lookup's width for --scene, 8..32 (default 16)\n"),
    F_NUM("--scene-res", CLI_OPT_LONG, scene_res, 16, 1024,
          "  --scene-res N    image side for --scene, 16..1024 (default the scene's)\n"),
    F_FLAG("--study", study,
           "  --study          also DIR/study.csv: the errors over R = 8, 16, 32, 64 and\n"
           "                   over samples = 6, 24, 96 R^2 at the chosen R\n"),
    F_STR("-o", dir,
          "  -o DIR           output folder (default out/factor-BRDF; created): lambda.png,\n"
          "                   pi.png (log-scaled grey, the range in report.csv),\n"
          "                   factors.f32 (little-endian float32: lambda's R*R texels,\n"
          "                   then pi's, rows of v from -1, u from -1), report.csv\n"),
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_factor_spec = {
    "factor", { factor_tab }, NULL, 0, "factor: unknown option '%s' (see shadesim factor --help)",
    "usage: shadesim factor BRDF [options]\n\n"
    "Factorizes a BRDF as f(d0, di) ~ lambda(d0) pi(h) lambda(di), h = norm(d0 + di)\n"
    "(homomorphic factorization, Romanyuk, Vyatkin, Voitko, Romanyuk 2020): both\n"
    "factors are R x R textures over the hemisphere in the parabolic map\n"
    "(u, v) = (x, y) / (1 + z); the fit is linear least squares on log f with a\n"
    "smoothness term, solved by conjugate gradients. Prints the error of the\n"
    "factorization against the BRDF on held-out direction pairs, next to the\n"
    "rank-1..K sum-of-products (SVD) approximation in the half/difference\n"
    "parameterization. docs/factorization.md explains every figure.\n\n"
    "BRDF: blinn, ct (Cook-Torrance), ward (isotropic), ward-aniso.\n\n"
    "options:\n",
    "\nexit status: 0 done, 1 --claims: a claim does not hold, 2 bad usage or input.\n"
};

/* The error rows on held-out pairs: the factorization (and its log form),
 * then the rank-1..svd_k sums of products; printed and added to csv. */
static int error_rows(FILE *csv, rf_brdf *b, rf_fact *f, const rf_opts *o, long heldout, long svd_k,
                      char *err, size_t errlen)
{
    rf_err e;
    uint64_t hseed = o->seed + 1000;
    long ns = o->samples > 0 ? o->samples : 24L * o->R * o->R;
    rf_error(rf_brdf_fn, b, rf_fact_fn, f, heldout, hseed, o->floor, &e);
    print_line("factorized", &e);
    tb_factor_csv_row(csv, "factor", o->R, ns, 1, &e);
    rf_error(rf_brdf_fn, b, rf_fact_log_fn, f, heldout, hseed, o->floor, &e);
    print_line("factorized-log", &e);
    tb_factor_csv_row(csv, "factor-log", o->R, ns, 1, &e);
    if (svd_k <= 0) return 0;
    rf_svd s;
    int rs = o->R < 32 ? o->R : 32;
    if (rf_svd_fit(rf_brdf_fn, b, rs, (int)svd_k, &s, err, errlen)) return -1;
    for (int k = 1; k <= svd_k; k++) {
        char name[32];
        s.k_used = k;
        rf_error(rf_brdf_fn, b, rf_svd_fn, &s, heldout, hseed, o->floor, &e);
        snprintf(name, sizeof name, "svd rank %d", k);
        print_line(name, &e);
        tb_factor_csv_row(csv, "svd", rs, 0, k, &e);
    }
    rf_svd_free(&s);
    return 0;
}

/* --study: the resolution and sample-count study into DIR/study.csv. */
static int write_study(rf_brdf *b, const rf_opts *o, long heldout, const char *dir, char *err, size_t errlen)
{
    char *sb = NULL, path[700];
    size_t sl = 0;
    FILE *sf = open_memstream(&sb, &sl);
    if (!sf) base_out_of_memory();
    int bad = tb_factor_study(b, o, heldout, sf, err, errlen);
    fclose(sf);
    snprintf(path, sizeof path, "%s/study.csv", dir);
    if (!bad) bad = base_out_write_all(path, sb, sl, err, errlen);
    free(sb);
    return bad ? -1 : 0;
}

int cli_factor(int argc, char **argv)
{
    base_outset *set = NULL;
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_factor_spec);
    if (argc < 2 || argv[1][0] == '-')
        return cli_usage_error("factor: which BRDF? (blinn, ct, ward, ward-aniso; see shadesim factor --help)");
    char err[600];
    rf_brdf b;
    if (rf_brdf_init(&b, argv[1], err, sizeof err)) {
        /* the message of every other verb: the verb, the name, the nearest */
        size_t n = 0;
        while (rf_brdf_names[n]) n++;
        const char *near = base_near(argv[1], rf_brdf_names, n);
        if (near) return cli_usage_error("factor: unknown BRDF '%s' (did you mean '%s'? one of blinn, ct, ward, ward-aniso)",
                                         argv[1], near);
        return cli_usage_error("factor: unknown BRDF '%s' (one of blinn, ct, ward, ward-aniso)", argv[1]);
    }
    factor_args fa;
    memset(&fa, 0, sizeof fa);
    rf_opts_default(&fa.o);
    fa.b = &b;
    fa.svd_k = 4;
    fa.heldout = TB_FACTOR_HELDOUT;
    fa.hw_width = 16;
    void *base[] = { &fa };
    if (cli_opt_parse(&cli_factor_spec, base, argc, argv, 2)) return CLI_USAGE;
    rf_opts o = fa.o;
    long svd_k = fa.svd_k, heldout = fa.heldout, hw_width = fa.hw_width, scene_res = fa.scene_res;
    int study = fa.study, claims = fa.claims, fails = 0;
    const char *scene = fa.scene, *dir = fa.dir;
    if (scene && (b.kind != RF_WARD || b.ax != b.ay))
        return cli_usage_error("--scene: the hf_lookup unit holds isotropic Ward maps (BRDF ward)");
    if (scene && (o.R < 4 || o.R > 32 || (o.R & (o.R - 1))))
        return cli_usage_error("--scene: --res %d: the hf_lookup unit's maps are 4, 8, 16 or 32 texels wide", o.R);
    if (scene && (b.ax < 0.1 || b.ax > 0.6)) return cli_usage_error("--scene: alpha %g: the unit takes 0.1..0.6", b.ax);
    char dbuf[300];
    if (!dir) { snprintf(dbuf, sizeof dbuf, "out/factor-%s", argv[1]); dir = dbuf; }
    if (cli_make_dir(dir)) return CLI_USAGE;

    rf_fact f;
    if (rf_factorize(rf_brdf_fn, &b, &o, &f, err, sizeof err)) return cli_usage_error("%s", err);
    char desc[160], path[700];
    rf_brdf_describe(&b, desc, sizeof desc);
    long ns = o.samples > 0 ? o.samples : 24L * o.R * o.R;
    printf("factor %s: %dx%d maps, %ld samples (%ld in the fit, %ld under the floor, %ld without a mirror),\n"
           "  smoothness %g, CG %d iterations, relative residual %.1e\n",
           desc, o.R, o.R, ns, f.used, f.floored, f.skipped, o.smooth, f.iters, f.relres);
    printf("  lambda in [%.4g, %.4g], pi in [%.4g, %.4g] over the disk's texels\n", f.lam_min, f.lam_max, f.pi_min, f.pi_max);

    char *csvbuf = NULL;
    size_t csvlen = 0;
    FILE *csv = open_memstream(&csvbuf, &csvlen);
    if (!csv) base_out_of_memory();
    fputs(tb_factor_csv_head, csv);
    int rc = CLI_OK;
    if (error_rows(csv, &b, &f, &o, heldout, svd_k, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    double llo, lhi, plo, phi;
    /* Every file from here on is one set: they appear together at the
     * commit below, or (any failure) none of them. */
    set = base_outset_begin();
    if (!set) base_out_of_memory();
    snprintf(path, sizeof path, "%s/lambda.png", dir);
    if (write_map_png(path, f.llam, o.R, &llo, &lhi, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    snprintf(path, sizeof path, "%s/pi.png", dir);
    if (write_map_png(path, f.lpi, o.R, &plo, &phi, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    fprintf(csv, "# lambda.png: grey 0..255 = log lambda %.6g..%.6g; pi.png: log pi %.6g..%.6g\n", llo, lhi, plo, phi);
    snprintf(path, sizeof path, "%s/factors.f32", dir);
    if (write_f32(path, &f, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    if (study && write_study(&b, &o, heldout, dir, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    tb_factor_scene_result sr;
    if (scene) {
        if (tb_factor_scene(scene, o.R, b.ax, (int)hw_width, (int)scene_res, dir, &sr, err, sizeof err)) {
            rc = cli_usage_error("--scene %s: %s", scene, err);
            goto done;
        }
        printf("scene %s %dx%d, Ward alpha %g specular, %zu pixels lit and seen:\n", scene, sr.w, sr.h, b.ax, sr.items);
        printf("  exact at vertices, interpolated   NMSE %.3e\n", sr.nmse_vertex);
        printf("  factorized per pixel (hf_lookup)  NMSE %.3e  (%dx%d maps, width %ld, %llu clocks, %.0f GE)\n",
               sr.nmse_factor, o.R, o.R, hw_width, (unsigned long long)sr.clocks, sr.area_ge);
    }
    if (claims && write_claims(&b, &f, &o, heldout, dir, scene ? &sr : NULL, err, sizeof err, &fails)) {
        rc = cli_usage_error("%s", err);
        goto done;
    }
    fclose(csv);
    csv = NULL;
    snprintf(path, sizeof path, "%s/report.csv", dir);
    if (base_out_write_all(path, csvbuf, csvlen, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    rc = base_outset_commit(set, err, sizeof err) ? cli_usage_error("%s", err) : rc;
    set = NULL;
    if (rc) goto done;
    printf("  wrote %s/{lambda.png, pi.png, factors.f32, report.csv%s%s%s}\n", dir, study ? ", study.csv" : "",
           claims ? ", claims.csv" : "", scene ? ", vertex.png, factorized.png, exact.png" : "");
    if (base_out_stdout_check(err, sizeof err)) rc = cli_usage_error("%s", err);
    else if (fails) rc = CLI_FAIL;
done:
    base_outset_abort(set);
    if (csv) fclose(csv);
    free(csvbuf);
    rf_fact_free(&f);
    return rc;
}
