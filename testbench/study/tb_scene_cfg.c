/* tb_scene_cfg.c - the unit of a scene's policy and its configuration.
 *
 * A scene's hardware keys are the unit's configuration: the description
 * keeps them as written, or "" when not set, and here they are applied
 * over the unit's defaults (unit_cfg_default): L, terms and series
 * through the unit's own parameter setters (unit_param_set), the
 * schedule by the unit's name for it (unit_sched_find), round and
 * overflow by the simulator's mode names (sim_round_parse,
 * sim_ovf_parse), the width as the whole number it is. So a range,
 * choice or default of theirs lives in the unit descriptor (or the
 * simulator) alone. Everything downstream (the render's intervals, its
 * operation counts, the table, scene.json, the searches) reads the
 * configuration this gives.
 */
#include "testbench/study/tb_scene.h"
#include "base/base_join.h"
#include "base/base_num.h"
#include "testbench/tb_netlist.h"
#include <pthread.h>
#include <stdio.h>
#include <string.h>

/* unit=FILE: a datapath file that names the policy's unit for its
 * reference (netlist span3 --datapath, edited), loaded once a process
 * (the render's threads and the searches build it many times) and kept. */
static int file_unit(const char *path, const unit_desc *span, const unit_desc **up, unit_cfg *cfg, char *err, size_t errlen)
{
    static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
    static struct { char path[256]; const unit_desc *u; unit_cfg cfg; } cache[4];
    pthread_mutex_lock(&lock);
    int k = 0;
    while (k < 4 && cache[k].u && strcmp(cache[k].path, path)) k++;
    const unit_desc *u = k < 4 ? cache[k].u : NULL;
    char e[1400] = "";
    if (!u && k < 4) {
        unit_fmts fm;
        if ((u = tb_netlist_load(path, &cache[k].cfg, &fm, e, sizeof e)) && !tb_datapath_is(u)) {
            tb_netlist_free(u);
            u = NULL;
            snprintf(e, sizeof e, "%s: a netlist, not a datapath file (netlist %s --datapath writes one)", path, span->name);
        }
        if (u) { snprintf(cache[k].path, sizeof cache[k].path, "%s", path); cache[k].u = u; }
    } else if (!u) snprintf(e, sizeof e, "%s: more than 4 unit files in one process", path);
    unit_cfg c = k < 4 ? cache[k].cfg : (unit_cfg){ 0 };
    pthread_mutex_unlock(&lock);
    if (!u) { snprintf(err, errlen, "unit: %s", e); return -1; }
    if (tb_datapath_base(u) != span) {
        snprintf(err, errlen, "unit: %s: the policy's unit is %s, and the file's ideal line does not name it (ideal unit=%s)",
                 path, span->name, span->name);
        return -1;
    }
    *up = u;
    *cfg = c;
    return 0;
}

static int has_param(const unit_desc *u, const char *name)
{
    for (int i = 0; i < u->nparams; i++)
        if (!strcmp(u->params[i].name, name)) return 1;
    return 0;
}

/* A parameter the policy's unit does not have (span1's terms) is still
 * judged, by the row of span23, which has every one a scene sets. */
int tb_scene_cfg(const scn_desc *d, const unit_desc **up, unit_cfg *cfg, char *err, size_t errlen)
{
    static const char *const uname[SCN_POL__COUNT] = { "span1", "span2", "span3", "span3", "span23", "span23" };
    if ((int)d->policy < 0 || d->policy >= SCN_POL__COUNT) { snprintf(err, errlen, "unknown policy"); return -1; }
    const unit_desc *u = unit_find(uname[d->policy]), *all = unit_find("span23");
    if (!u || !all) { snprintf(err, errlen, "unit %s is not built into this shadesim", u ? "span23" : uname[d->policy]); return -1; }
    unit_cfg_default(u, cfg);
    if (*d->unit && file_unit(d->unit, u, &u, cfg, err, errlen)) return -1;
    long long w;
    if (*d->fmt_width && (base_num_whole(d->fmt_width, 0, &w) || w < 1 || w > 64)) {
        snprintf(err, errlen, "width: '%s' is not a whole number 1..64", d->fmt_width);
        return -1;
    }
    if (*d->fmt_width) cfg->width = (int)w;
    char list[64] = "";
    if (*d->rnd && sim_round_parse(d->rnd, &cfg->rnd)) {
        for (int m = SIM_RND_TRUNC; m <= SIM_RND_EVEN; m++) base_join_add(list, sizeof list, ", ", sim_round_name((sim_round)m));
        snprintf(err, errlen, "round: \"%s\" is not one of %s", d->rnd, list);
        return -1;
    }
    if (*d->ovf && sim_ovf_parse(d->ovf, &cfg->ovf)) {
        for (int m = SIM_OVF_WRAP; m <= SIM_OVF_SAT; m++) base_join_add(list, sizeof list, ", ", sim_ovf_name((sim_ovf)m));
        snprintf(err, errlen, "overflow: \"%s\" is not one of %s", d->ovf, list);
        return -1;
    }
    if (*d->schedule) {
        int s = unit_sched_find(u, d->schedule);
        if (s < 0) {
            char list[200] = "";
            for (int j = 0; j < u->nsched; j++) base_join_add(list, sizeof list, ", ", u->sched[j].name);
            snprintf(err, errlen, "schedule %s: unit %s has schedules: %s", d->schedule, u->name, list);
            return -1;
        }
        cfg->schedule = s;
    }
    /* the node set is the policy's (and auto-nodes'), always set */
    const char *const set[][2] = { { "L", d->L }, { "terms", d->terms }, { "series", d->series },
                                   { "nodes", tb_scene_nodes_n2(d) ? "n2" : "n1" } };
    for (size_t k = 0; k < sizeof set / sizeof set[0]; k++)
        if (*set[k][1] && unit_param_set(has_param(u, set[k][0]) ? u : all, cfg, set[k][0], set[k][1], err, errlen))
            return -1;
    *up = u;
    return 0;
}

int tb_scene_unit(const scn_desc *d, const unit_desc **up, unit_cfg *cfg, unit_fmts *f,
                  char *err, size_t errlen)
{
    const unit_desc *u;
    if (tb_scene_cfg(d, &u, cfg, err, errlen)) return -1;
    const char *ov[SCN_MAX_FMT];
    for (int i = 0; i < d->nfmt && i < SCN_MAX_FMT; i++) ov[i] = d->fmt[i];
    if (tb_formats(u, cfg, ov, d->nfmt, f, err, errlen)) {
        /* here the overrides come from the scene key fmt, not --fmt */
        if (!strncmp(err, "--fmt ", 6)) memmove(err, err + 2, strlen(err + 2) + 1);
        return -1;
    }
    *up = u;
    return 0;
}

/* 1 if the policy's cubic intervals use node set N2 (I(3/4)). Both
 * adaptive policies run on the span23 unit and take its node set from the
 * auto-nodes key (auto_cubic_nodes). */
int tb_scene_nodes_n2(const scn_desc *d)
{
    if (d->policy == SCN_POL_CUBIC_N2) return 1;
    if (d->policy == SCN_POL_ADAPTIVE_REGION || d->policy == SCN_POL_ADAPTIVE_AUTO) return d->auto_cubic_nodes == 2;
    return 0;
}
