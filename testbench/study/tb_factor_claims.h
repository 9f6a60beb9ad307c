/* tb_factor_claims.h - the factorization paper's claims (Romanyuk et al.,
 * 2020: positive factors, reciprocity, relative error, few operations,
 * Fig. 1) as rows of the claims table, computed in one place for both
 * verbs that show them: `factor --claims` (with its BRDF and options) and
 * `claims` (tb_factor_claims: `factor ward --claims --scene sphere
 * --scene-res 256`, the defaults otherwise). docs/factorization.md. */
#ifndef TB_FACTOR_CLAIMS_H
#define TB_FACTOR_CLAIMS_H
#include "testbench/study/tb_ref_claims.h"
#include "vectors/ref_factor.h"
#include "testbench/study/tb_factor_scene.h"

#define TB_FACTOR_CLAIMS_ROWS  5
#define TB_FACTOR_CLAIMS_SCENE "sphere"
#define TB_FACTOR_CLAIMS_RES   256       /* image side of the Fig. 1 scene */
#define TB_FACTOR_CLAIMS_WIDTH 16        /* hf_lookup's width there */
#define TB_FACTOR_HELDOUT      20000     /* held-out pairs: the factor verb's default */

/* The rows for BRDF b factorized as f with options o, errors on `heldout`
 * held-out pairs; the Fig. 1 row from sr (NULL: no such row, 4 rows).
 * Returns the rows written (at most max), 0 with err on failure. */
size_t tb_factor_claims_rows(rf_brdf *b, const rf_fact *f, const rf_opts *o, long heldout,
                             const tb_factor_scene_result *sr, claim_result *out, size_t max,
                             char *err, size_t errlen);
/* The claims verb's rows: isotropic Ward with the factor verb's defaults
 * (32 x 32 maps, TB_FACTOR_HELDOUT held-out pairs) and Fig. 1 on TB_FACTOR_CLAIMS_SCENE. */
size_t tb_factor_claims(claim_result *out, size_t max, char *err, size_t errlen);
#endif
