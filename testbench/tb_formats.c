/* tb_formats.c - a unit's signal formats for one configuration: the unit's
 * own rules, then the user's --fmt NAME=sI.F overrides, checked against the
 * signals this configuration actually builds. */
#include "testbench/tb.h"
#include "base/base_join.h"
#include <stdio.h>
#include <string.h>

int tb_formats(const unit_desc *u, const unit_cfg *cfg, const char *const *ov, int n,
               unit_fmts *out, char *err, size_t errlen)
{
    /* No silent widening: below its minimum width the rule would hand
     * some signal more bits than --width says (unit_fmt's clamp), so the
     * run would print one width and build another. all=FMT sets every
     * format itself, and then the width does not matter. */
    int all = 0;
    for (int k = 0; k < n; k++) all |= !strncmp(ov[k], "all=", 4);
    int lim, wmin = unit_min_width(u, cfg, &lim);
    if (!all && cfg->width < wmin) {
        unit_cfg c = *cfg;
        unit_fmts f;
        c.width = wmin;
        u->formats(&c, &f);
        if (lim >= 0)
            snprintf(err, errlen, "--width %d: unit %s needs --width >= %d (signal %s's integer part is %c%d)",
                     cfg->width, u->name, wmin, u->sigs[lim].name, f.f[lim].is_signed ? 's' : 'u', f.f[lim].ibits);
        else
            snprintf(err, errlen, "--width %d: unit %s needs --width >= %d", cfg->width, u->name, wmin);
        return -1;
    }
    u->formats(cfg, out);
    for (int k = 0; k < n; k++) {
        const char *eq = strchr(ov[k], '=');
        if (!eq) { snprintf(err, errlen, "--fmt %s: expected NAME=sI.F (e.g. mul=s4.12 or all=s8.8)", ov[k]); return -1; }
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)(eq - ov[k]), ov[k]);
        sim_fmt f;
        char ferr[160];
        if (sim_fmt_parse(eq + 1, &f, ferr, sizeof ferr)) { snprintf(err, errlen, "--fmt %s: %s", ov[k], ferr); return -1; }
        if (!strcmp(name, "all")) {
            for (int i = 0; i < u->nsigs; i++) out->f[i] = f;
            continue;
        }
        int i = unit_sig_index(u, name);
        if (i >= 0 && unit_sig_used(u, i, cfg->schedule) && !unit_sig_built(u, i, cfg)) {
            /* Declared, but these parameters do not build it (div3's t7
             * with terms=3): name the parameters and what they build. */
            char list[600] = "", pv[200] = "";
            for (int j = 0; j < u->nsigs; j++)
                if (unit_sig_built(u, j, cfg)) {
                    base_join_add(list, sizeof list, " ", u->sigs[j].name);
                }
            for (int p = 0; p < u->nparams; p++) {
                char v[64];
                unit_param_get(&u->params[p], cfg, v, sizeof v);
                size_t k = strlen(pv);
                snprintf(pv + k, sizeof pv - k, "%s%s=%s", p ? " " : "", u->params[p].name, v);
            }
            snprintf(err, errlen, "--fmt %s: unit %s with %s does not build signal '%s' (it builds: %s)",
                     ov[k], u->name, pv, name, list);
            return -1;
        }
        if (i < 0 || !unit_sig_used(u, i, cfg->schedule)) {
            /* A signal of another schedule's datapath: say whose. */
            const char *sn = u->sched[cfg->schedule].name;
            char list[600] = "";
            if (i >= 0) {       /* the schedules that have it */
                for (int j = 0; j < u->nsched; j++)
                    if (unit_sig_used(u, i, j)) {
                        base_join_add(list, sizeof list, ", ", u->sched[j].name);
                    }
            } else {            /* the signals this schedule has */
                for (int j = 0; j < u->nsigs; j++)
                    if (unit_sig_built(u, j, cfg)) {
                        base_join_add(list, sizeof list, " ", u->sigs[j].name);
                    }
            }
            if (i >= 0)
                snprintf(err, errlen, "--fmt %s: schedule %s of unit %s has no signal '%s' (it is in %s %s; "
                         "shadesim list %s --schedule %s shows %s's)", ov[k], sn, u->name, name,
                         strchr(list, ',') ? "schedules" : "schedule", list, u->name, sn, sn);
            else
                snprintf(err, errlen, "--fmt %s: unit %s has no signal '%s' (signals: %s)", ov[k], u->name, name, list);
            return -1;
        }
        out->f[i] = f;
    }
    return 0;
}
