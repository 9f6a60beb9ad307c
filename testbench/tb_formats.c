/* tb_formats.c - a unit's signal formats for one configuration: the unit's
 * own rules, then the user's --fmt NAME=sI.F[:ROUND][:OVERFLOW] overrides,
 * checked against the signals this configuration actually builds. */
#include "testbench/tb.h"
#include "base/base_join.h"
#include <stdio.h>
#include <string.h>

/* A format's own rounding and overflow modes act where a primitive
 * quantizes into it (sim_prim.h) or the testbench quantizes an input. A
 * signal that the unit computes with its own logic (a table, a normalizer:
 * sim_logic or a process of its own) gets raw bits from that logic, so a
 * mode on it would be printed and not obeyed: refuse it. Building the unit
 * once is the only way to see which element drives each signal; only runs
 * that give modes pay for it. who[i]: the override that set signal i. */
static int modes_check(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                       const char *const *ov, const int *who, char *err, size_t errlen)
{
    int any = 0;
    for (int i = 0; i < u->nsigs; i++) any |= unit_sig_built(u, i, cfg) && sim_fmt_has_modes(f->f[i]);
    if (!any) return 0;
    char berr[256];
    tb_built bu;
    int rc = 0;
    /* a unit that does not build says why when it is run */
    if (tb_build(u, cfg, f, &bu, berr, sizeof berr) == 0)
        for (uint32_t k = 0, n = sim_signal_count(bu.c); k < n && !rc; k++) {
            sim_signal *s = sim_signal_at(bu.c, k);
            sim_prim_info in;
            if (!sim_fmt_has_modes(s->fmt) || s->kind == SIM_KIND_INPUT || s->kind == SIM_KIND_CONST) continue;
            if (sim_prim_describe(s, &in) == 0 && in.kind != SIM_KIND_LOGIC) continue;
            /* The override to blame: the signal's own, else one that gave
             * this very format (an element may take another signal's:
             * hf_lookup's ROM reads t00..t11 have rom's). */
            int i = unit_sig_index(u, s->name);
            if (i < 0 || who[i] < 0)
                for (int j = 0; j < u->nsigs; j++)
                    if (who[j] >= 0 && !memcmp(&f->f[j], &s->fmt, sizeof s->fmt)) { i = j; break; }
            char fb[SIM_FMT_STRLEN];
            snprintf(err, errlen, "--fmt %s: unit %s computes signal %s (%s) with its own logic, which takes "
                     "no rounding or overflow mode; give it a plain format", i >= 0 && who[i] >= 0 ? ov[who[i]] : "",
                     u->name, s->name, sim_fmt_str(s->fmt, fb));
            rc = -1;
        }
    sim_free(bu.c);
    return rc;
}

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
    int who[UNIT_MAX_SIGS];
    for (int i = 0; i < UNIT_MAX_SIGS; i++) who[i] = -1;
    for (int k = 0; k < n; k++) {
        const char *eq = strchr(ov[k], '=');
        if (!eq) { snprintf(err, errlen, "--fmt %s: expected NAME=sI.F[:ROUND][:OVERFLOW] (e.g. mul=s4.12, mul=s4.12:half-up:sat or all=s8.8)", ov[k]); return -1; }
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)(eq - ov[k]), ov[k]);
        sim_fmt f;
        char ferr[160];
        if (sim_fmt_parse(eq + 1, &f, ferr, sizeof ferr)) { snprintf(err, errlen, "--fmt %s: %s", ov[k], ferr); return -1; }
        if (!strcmp(name, "all")) {
            for (int i = 0; i < u->nsigs; i++) { out->f[i] = f; who[i] = k; }
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
        who[i] = k;
    }
    return modes_check(u, cfg, out, ov, who, err, errlen);
}
