/* tb_factor_study.h - the factorization study's tables (docs/
 * factorization.md): one CSV row per approximation's error on held-out
 * pairs, the series over resolutions and sample counts, and the claims as
 * CSV. The verb factor (testbench/cli/cli_factor.c) runs the factorization
 * it prints and saves these tables beside its maps. */
#ifndef TB_FACTOR_STUDY_H
#define TB_FACTOR_STUDY_H
#include <stdio.h>
#include "testbench/study/tb_ref_claims.h"
#include "vectors/ref_factor.h"

/* The header line of report.csv and study.csv, and one row: method
 * ("factor", "factor-log", "svd"), texture side, samples, rank, errors. */
extern const char tb_factor_csv_head[];
void tb_factor_csv_row(FILE *f, const char *method, int R, long samples, int rank, const rf_err *e);

/* study.csv (header and rows): b factorized with o at R = 8, 16, 32, 64,
 * then at o->R with 6, 24, 96 R^2 samples, each with its two error rows
 * (texture lookups, log model) on heldout pairs. 0, or -1 with err. */
int tb_factor_study(rf_brdf *b, const rf_opts *o, long heldout, FILE *csv, char *err, size_t errlen);

/* claims.csv: a header, then the n rows; when fig1_measured is 0 also the
 * Fig. 1 claim as not measured (it needs a scene). */
void tb_factor_claims_csv(FILE *f, const claim_result *rows, size_t n, int fig1_measured);
#endif
