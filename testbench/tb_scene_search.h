/* tb_scene_search.h - what a scene needs, found by simulation:
 *
 *  tb_scene_search: the smallest per-signal formats of the scene's span
 *  unit that keep the scene's NMSE under a target, found on the scene's
 *  view and then checked on its held-out view (another camera and light
 *  that the search never saw); reports the area saved against the
 *  smallest uniform width that meets the target, and whether the
 *  held-out view still meets it.
 *
 *  tb_scene_sweep: the scene over interval length, degree policy, terms of
 *  the divide-by-3 network, width (and schedule): a CSV and SVG charts of
 *  NMSE against operations and against clocks per pixel, Pareto front,
 *  the paper's configuration marked.
 *
 * Both write into outdir (created if needed) and print a summary to out
 * (a table, or JSON when json is 1). TB_OK, TB_FAIL (target not met, or
 * held-out check failed) or TB_BADINPUT with a message.
 */
#ifndef TB_SCENE_SEARCH_H
#define TB_SCENE_SEARCH_H
#include "testbench/tb_scene.h"

int tb_scene_search(const scn_desc *d, const scn_mesh *m, int jobs, int no_batch, double target_nmse,
                    const char *outdir, int json, FILE *out, char *err, size_t errlen);
/* spec: NULL for the default grid, or "KEY=V1,V2,...;KEY=..." with keys
 * L, policy, terms, width, schedule. */
int tb_scene_sweep(const scn_desc *d, const scn_mesh *m, int jobs, int no_batch, const char *spec,
                   const char *outdir, int json, FILE *out, char *err, size_t errlen);
#endif
