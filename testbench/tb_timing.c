/* tb_timing.c - a unit's critical path, f_max and throughput in the
 * testbench's terms (tb_ppa): the analysis is sim/sim_timing.c's, on the
 * design tb_build makes; names are made relative to the unit's scope. */
#include "testbench/tb.h"
#include "testbench/tb_range.h"
#include "testbench/tb_synth.h"
#include "sim/sim_timing.h"
#include <string.h>

void tb_ppa_rate(tb_ppa *p, double cycles_per_item)
{
    p->items_per_s = cycles_per_item > 0 ? p->fmax_mhz * 1e6 / cycles_per_item : 0;
}

/* abc < 0: as --abc auto chooses the script */
static int ppa_timing(const sim_ctx *c, const sim_scope *sc, double cycles_per_item, int abc, tb_ppa *p,
                      char *err, size_t errlen)
{
    sim_timing t;
    if (abc < 0) abc = tb_abc_auto(sim_scope_area(sc));
    if (sim_timing_analyze_carry(c, abc == TB_ABC_LIGHT ? SIM_CARRY_PREFIX : SIM_CARRY_RIPPLE, &t, err, errlen)) return -1;
    p->levels = t.levels;
    p->crit_ps = t.ps;
    p->fmax_mhz = t.fmax_mhz;
    p->npath = t.npath < TB_PATH_MAX ? t.npath : TB_PATH_MAX;
    for (int i = 0; i < p->npath; i++) tb_range_name(t.path[i], sc, p->path[i], sizeof p->path[i]);
    tb_ppa_rate(p, cycles_per_item);
    return 0;
}

int tb_ppa_timing(const sim_ctx *c, const sim_scope *sc, double cycles_per_item, tb_ppa *p,
                  char *err, size_t errlen)
{
    return ppa_timing(c, sc, cycles_per_item, -1, p, err, errlen);
}

int tb_unit_timing_abc(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, int abc, tb_ppa *p,
                       char *err, size_t errlen)
{
    tb_built b;
    int rc = tb_build(u, cfg, f, &b, err, errlen);
    if (!rc) rc = ppa_timing(b.c, b.sc, 0, abc, p, err, errlen);
    sim_free(b.c);
    return rc ? -1 : 0;
}

int tb_unit_timing(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, tb_ppa *p,
                   char *err, size_t errlen)
{
    return tb_unit_timing_abc(u, cfg, f, -1, p, err, errlen);
}
