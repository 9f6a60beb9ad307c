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
#include "testbench/study/tb_scene.h"

/* What a search or a sweep did, measured (so never in its output, which
 * is the same bytes for any jobs); bench/bench_scene.c prints it. */
typedef struct tb_scene_work {
    size_t renders;       /* the renders the result needed: the output's "renders" (a search:
                           * as one at a time; a sweep: its distinct grid points) */
    size_t renders_run;   /* renders run: a search with jobs > 1 also renders candidates
                           * speculatively that a one-at-a-time search would not */
    double cpu_sim, cpu_render;   /* CPU seconds over the renders run (tb_scene_result's) */
} tb_scene_work;

/* work: NULL, or filled. */
int tb_scene_search(const scn_desc *d, const scn_mesh *m, int jobs, int no_batch, double target_nmse,
                    const char *outdir, int json, FILE *out, tb_scene_work *work, char *err, size_t errlen);
/* spec: NULL for the default grid, or "KEY=V1,V2,...;KEY=..." with keys
 * L, policy, terms, width, schedule. */
int tb_scene_sweep(const scn_desc *d, const scn_mesh *m, int jobs, int no_batch, const char *spec,
                   const char *outdir, int json, FILE *out, tb_scene_work *work, char *err, size_t errlen);
/* The progress lines' estimate of the time left ("about 1 min 05 s
 * left"), from the seconds elapsed for done renders of total; empty
 * before two are done. */
void tb_scene_eta(char *buf, size_t len, double elapsed, size_t done, size_t total);
#endif
