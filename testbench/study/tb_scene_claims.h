/* tb_scene_claims.h - the paper's scene claims measured on the face scene
 * through the simulated hardware path, as rows of the claims table
 * (testbench/study/tb_ref_claims.h): NMSE <= 1e-4 against per-pixel Phong with the
 * paper's 3-term divide-by-3 network, with enough terms, with the
 * automatic degree choice, and the operation-count speed-up.
 * Deterministic: renders only, no timing.
 */
#ifndef TB_SCENE_CLAIMS_H
#define TB_SCENE_CLAIMS_H
#include "testbench/study/tb_ref_claims.h"

#define TB_SCENE_CLAIMS_ROWS 4
#define TB_SCENE_CLAIMS_RES  256     /* resolution of the rows in `shadesim claims` */

/* The rows on the built-in face at res x res (square), renders on `jobs`
 * threads. Returns the rows written (up to max; 0 when the scene cannot be
 * rendered, with a message in err). */
size_t tb_scene_claims(claim_result *out, size_t max, int res, int jobs, char *err, size_t errlen);
#endif
