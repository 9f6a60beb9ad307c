/* tb_factor_study.c - the factorization study's tables (tb_factor_study.h). */
#include "testbench/study/tb_factor_study.h"

const char tb_factor_csv_head[] =
    "method,res,samples,rank,rel_rms,nrms,rel_max,rel_max_theta0,rel_max_thetai,neg_share,recip_max,heldout,under_floor\n";

void tb_factor_csv_row(FILE *f, const char *method, int R, long samples, int rank, const rf_err *e)
{
    fprintf(f, "%s,%d,%ld,%d,%.6g,%.6g,%.6g,%.2f,%.2f,%.6g,%.6g,%ld,%ld\n", method, R, samples, rank, e->rel_rms,
            e->nrms, e->rel_max, e->max_t0, e->max_ti, e->neg_share, e->recip_max, e->n, e->n_zero);
}

/* One factorization and its two error rows (texture lookups, log model). */
static int fact_rows(rf_brdf *b, const rf_opts *o, long heldout, double flr, FILE *csv, char *err, size_t errlen)
{
    rf_fact f;
    if (rf_factorize(rf_brdf_fn, b, o, &f, err, errlen)) return -1;
    rf_err e;
    long ns = o->samples > 0 ? o->samples : 24L * o->R * o->R;
    rf_error(rf_brdf_fn, b, rf_fact_fn, &f, heldout, o->seed + 1000, flr, &e);
    tb_factor_csv_row(csv, "factor", o->R, ns, 1, &e);
    rf_error(rf_brdf_fn, b, rf_fact_log_fn, &f, heldout, o->seed + 1000, flr, &e);
    tb_factor_csv_row(csv, "factor-log", o->R, ns, 1, &e);
    rf_fact_free(&f);
    return 0;
}

int tb_factor_study(rf_brdf *b, const rf_opts *o, long heldout, FILE *csv, char *err, size_t errlen)
{
    fputs(tb_factor_csv_head, csv);
    static const int res[] = { 8, 16, 32, 64 };
    for (size_t k = 0; k < sizeof res / sizeof res[0]; k++) {
        rf_opts q = *o;
        q.R = res[k];
        q.samples = 0;
        if (fact_rows(b, &q, heldout, o->floor, csv, err, errlen)) return -1;
    }
    static const int mult[] = { 6, 24, 96 };
    for (size_t k = 0; k < sizeof mult / sizeof mult[0]; k++) {
        rf_opts q = *o;
        q.samples = (long)mult[k] * o->R * o->R;
        if (fact_rows(b, &q, heldout, o->floor, csv, err, errlen)) return -1;
    }
    return 0;
}

void tb_factor_claims_csv(FILE *f, const claim_result *rows, size_t n, int fig1_measured)
{
    fputs("claim,paper,measured,verdict\n", f);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%s,\"%s\",\"%s\",%s\n", rows[i].id, rows[i].claim, rows[i].measured_text, rows[i].verdict);
    if (!fig1_measured)
        fputs("fig1_vertex_vs_pixel,\"factorized per pixel looks closer to the BRDF than its exact values at the "
              "vertices interpolated (Fig. 1)\",\"not measured: give --scene NAME\",not measured\n", f);
}
