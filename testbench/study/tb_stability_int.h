/* tb_stability_int.h - what the files of the stability atlas share; not
 * for use outside them (the public interface is tb_stability.h).
 *
 *   tb_stability_rows.c  a unit's run, the atlas's next row, a chart
 *                        kept (a leaf: the other two call it)
 *   tb_stability.c       forward differencing, coefficient ranges, div3,
 *                        BRDF, divider and powers; the whole atlas
 *   tb_stability_prof.c  highlight profiles through interp2/interp3:
 *                        cubic overshoot, degree against curvature, the
 *                        cubic's node sets
 */
#ifndef TB_STABILITY_INT_H
#define TB_STABILITY_INT_H
#include "testbench/study/tb_stability.h"
#include "testbench/tb.h"

/* Run u with formats fm (NULL: the rule's) on vs; 0 and r filled, or -1. */
int tb_stab_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs, tb_result *r);
/* The atlas's next row, cleared, with its id and method. */
tb_stab_row *tb_stab_row_add(tb_stab *s, const char *id, const char *method);
/* Chart c into the atlas as file (freed when the atlas is full). */
void tb_stab_keep_chart(tb_stab *s, chart *c, const char *file);
/* The rows (and, when charts, the charts) of tb_stability_prof.c; 0 or -1. */
int tb_stab_atlas_overshoot(tb_stab *s, int charts);
int tb_stab_atlas_degree(tb_stab *s, int charts);
int tb_stab_atlas_nodes(tb_stab *s, int charts);
#endif
