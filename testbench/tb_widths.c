/* tb_widths.c - the largest width a unit's default formats build at: build
 * the unit (no simulation) from 64 down until one builds. Most units build
 * at 64, so this is one build; a unit whose rule outgrows a primitive
 * (schlick's divider) takes a few more. */
#include "testbench/tb_widths.h"
#include <string.h>

static int builds(const unit_desc *u, const unit_cfg *cfg, char *err, size_t errlen)
{
    unit_fmts f;
    u->formats(cfg, &f);
    sim_ctx *c = sim_new();
    if (!c) { snprintf(err, errlen, "out of memory"); return 0; }
    sim_set_quant(c, cfg->rnd, cfg->ovf);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *sc = sim_scope_new(c, NULL, u->name);
    unit_io io;
    memset(&io, 0, sizeof io);
    int ok = !u->build(c, sc, clk, cfg, &f, &io, err, errlen);
    sim_free(c);
    return ok;
}

int tb_width_max(const unit_desc *u, const unit_cfg *cfg, char *err, size_t errlen)
{
    unit_cfg c = *cfg;
    char e[400];
    int wmin = unit_min_width(u, cfg, NULL);
    if (errlen) err[0] = 0;
    for (int w = 64; w >= wmin; w--) {
        c.width = w;
        if (builds(u, &c, e, sizeof e)) return w;
        if (errlen) snprintf(err, errlen, "%s", e);     /* the message at max + 1 */
    }
    return 0;
}
