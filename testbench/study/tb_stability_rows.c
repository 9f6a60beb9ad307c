/* tb_stability_rows.c - what the atlas's files (tb_stability.c,
 * tb_stability_prof.c) share: a unit's run, the atlas's next row, a chart
 * kept. A leaf, so that neither file calls the other for them. */
#include "testbench/study/tb_stability_int.h"
#include "testbench/tb.h"
#include <string.h>

/* Run u with formats fm (NULL: the rule's) on vs; TB_OK and r filled. */
int tb_stab_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs, tb_result *r)
{
    unit_fmts f;
    char err[400];
    memset(r, 0, sizeof *r);
    if (!fm) {
        if (tb_formats(u, cfg, NULL, 0, &f, err, sizeof err)) return -1;
        fm = &f;
    }
    if (tb_run(u, cfg, fm, vs, NULL, r, err, sizeof err) != TB_OK) { tb_result_free(r); return -1; }
    return 0;
}

tb_stab_row *tb_stab_row_add(tb_stab *s, const char *id, const char *method)
{
    tb_stab_row *r = &s->rows[s->nrows < TB_STAB_MAX_ROWS ? s->nrows++ : TB_STAB_MAX_ROWS - 1];
    memset(r, 0, sizeof *r);
    tb_settext(r->id, sizeof r->id, "%s", id);
    tb_settext(r->method, sizeof r->method, "%s", method);
    return r;
}

void tb_stab_keep_chart(tb_stab *s, chart *c, const char *file)
{
    if (s->ncharts < TB_STAB_MAX_CHARTS) {
        s->charts[s->ncharts] = c;
        s->chart_files[s->ncharts++] = file;
    } else chart_free(c);
}
