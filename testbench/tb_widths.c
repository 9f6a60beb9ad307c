/* tb_widths.c - the largest width a unit's default formats build at: build
 * the unit (no simulation) from 64 down until one builds. Most units build
 * at 64, so this is one build; a unit whose rule outgrows a primitive
 * (schlick's divider) takes a few more. */
#include "testbench/tb_widths.h"
#include <stdio.h>
#include <string.h>

static int builds(const unit_desc *u, const unit_cfg *cfg, char *err, size_t errlen)
{
    unit_fmts f;
    u->formats(cfg, &f);
    tb_built b;
    int ok = !tb_build(u, cfg, &f, &b, err, errlen);
    sim_free(b.c);
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

int tb_width_refuse(const unit_desc *u, const unit_cfg *cfg, char *msg, size_t len)
{
    char why[400];
    int wmax = tb_width_max(u, cfg, why, sizeof why);
    if (cfg->width <= wmax) return 0;
    snprintf(msg, len, "unit %s builds with its default formats at widths %d..%d only (%s)", u->name, unit_min_width(u, cfg, NULL), wmax, why);
    return 1;
}
