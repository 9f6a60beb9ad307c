/* tb_out.c - a testbench result as JSON, CSV and a readable table. */
#include "testbench/tb.h"
#include "testbench/tb_stream.h"
#include "base/base_out.h"
#include "base/base_json.h"
#include <stdarg.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A figure for the table and CSV: printf's %g spells a NaN "nan" or "-nan"
 * by its sign bit; one spelling, "nan", everywhere (JSON: null). */
static const char *tnum(char *b, size_t n, const char *fmt, double v)
{
    if (isnan(v)) snprintf(b, n, "nan");
    else snprintf(b, n, fmt, v);
    return b;
}

static void jmetrics(FILE *f, const tb_metrics *m, const char *ind)
{
    char fb[SIM_FMT_STRLEN];
    fprintf(f, "{\n%s  \"format\": \"%s\",\n%s  \"max_abs_err\": ", ind, sim_fmt_str(m->fmt, fb), ind);
    base_json_num(f, m->max_abs_err, 17);
    fprintf(f, ",\n%s  \"mean_err\": ", ind); base_json_num(f, m->mean_err, 17);
    fprintf(f, ",\n%s  \"rms_err\": ", ind); base_json_num(f, m->rms_err, 17);
    fprintf(f, ",\n%s  \"nmse\": ", ind); base_json_num(f, m->nmse, 17);
    fprintf(f, ",\n%s  \"max_err_lsb\": ", ind); base_json_num(f, m->max_err_lsb, 17);
    fprintf(f, ",\n%s  \"bound\": ", ind); base_json_num(f, m->bound, 17);
    fprintf(f, ",\n%s  \"max_err_vs_ideal\": ", ind); base_json_num(f, m->max_err_ideal, 17);
    fprintf(f, ",\n%s  \"bound_check\": \"%s\"", ind, tb_check_name(m->check));
    fprintf(f, ",\n%s  \"golden_check\": \"%s\"", ind, m->golden_ok ? "ok" : "exceeded");
    fprintf(f, ",\n%s  \"max_method_err\": ", ind); base_json_num(f, m->max_method_err, 17);
    fprintf(f, "\n%s}", ind);
}

/* Speed and energy (tb_ppa): the critical path, f_max, items per second,
 * the settled bit toggles per signal and the energy per item. */
static void jppa(FILE *f, const tb_result *r)
{
    const tb_ppa *p = &r->ppa;
    fputs(",\n  \"critical_path\": ", f);
    tb_ppa_json_path(f, p);
    fputs(",\n  \"fmax_mhz\": ", f); base_json_num(f, p->fmax_mhz, 17);
    fputs(",\n  \"items_per_s\": ", f); base_json_num(f, p->items_per_s, 17);
    fprintf(f, ",\n  \"toggles\": {\"total\": %llu, \"per_signal\": {", (unsigned long long)p->toggles);
    for (int i = 0; i < r->nsigs; i++) {
        fputs(i ? ", " : "", f);
        base_json_str(f, r->sigs[i].name);
        fprintf(f, ": %llu", (unsigned long long)r->sigs[i].toggles);
    }
    fputs("}},\n  \"energy_pj_per_item\": ", f); base_json_num(f, p->energy_pj_per_item, 17);
}

/* "critical path 34 levels, 812 ps (rg -> mul -> sm -> rg), f_max 1231 MHz,
 * 205 M items/s"; a path of more than ten signals shows its first and
 * last four. */
static void print_crit(FILE *f, const tb_ppa *p)
{
    if (p->npath <= 0) return;
    char path[1200];
    tb_ppa_path_text(p, path, sizeof path);
    fprintf(f, "critical path %d levels, %.0f ps (%s", p->levels, p->crit_ps, path);
    fprintf(f, "), f_max %.0f MHz", p->fmax_mhz);
    if (p->items_per_s > 0) fprintf(f, ", %.4g M items/s", p->items_per_s / 1e6);
    fputc('\n', f);
}

int tb_write_json(FILE *f, const tb_result *r)
{
    const unit_desc *u = r->unit;
    char fb[SIM_FMT_STRLEN];
    fprintf(f, "{\n  \"unit\": \"%s\",\n  \"schedule\": \"%s\",\n  \"width\": %d,\n", u->name,
            u->sched[r->cfg.schedule].name, r->cfg.width);
    fputs("  \"params\": {", f);
    for (int i = 0; i < u->nparams; i++) {
        char v[64];
        unit_param_get(&u->params[i], &r->cfg, v, sizeof v);
        if (u->params[i].type == UNIT_P_ENUM) fprintf(f, "%s\"%s\": \"%s\"", i ? ", " : "", u->params[i].name, v);
        else fprintf(f, "%s\"%s\": %s", i ? ", " : "", u->params[i].name, v);
    }
    fputs("},\n  \"formats\": {", f);
    /* the signals of the schedule that ran */
    for (int i = 0, n = 0; i < u->nsigs; i++)
        if (unit_sig_built(u, i, &r->cfg))
            fprintf(f, "%s\"%s\": \"%s\"", n++ ? ", " : "", u->sigs[i].name, sim_fmt_str(r->fmts.f[i], fb));
    fprintf(f, "},\n  \"round\": \"%s\",\n  \"overflow\": \"%s\",\n", sim_round_name(r->cfg.rnd), sim_ovf_name(r->cfg.ovf));
    fprintf(f, "  \"vectors\": %zu,\n  \"beats_per_item\": %d,\n  \"cycles\": %llu,\n", r->vectors, r->beats,
            (unsigned long long)r->cycles);
    fputs("  \"cycles_per_item\": ", f); base_json_num(f, r->cycles_per_item, 17);
    fputs(",\n  \"cycles_per_beat\": ", f); base_json_num(f, r->cycles_per_beat, 17);
    fprintf(f, ",\n  \"latency\": %llu,\n  \"max_abs_err\": ", (unsigned long long)r->latency);
    base_json_num(f, r->max_abs_err, 17);
    fputs(",\n  \"mean_err\": ", f); base_json_num(f, r->mean_err, 17);
    fputs(",\n  \"rms_err\": ", f); base_json_num(f, r->rms_err, 17);
    fputs(",\n  \"nmse\": ", f); base_json_num(f, r->nmse, 17);
    fputs(",\n  \"max_err_lsb\": ", f); base_json_num(f, r->max_err_lsb, 17);
    fprintf(f, ",\n  \"overflows\": %llu,\n  \"overflows_discarded\": %llu,\n  \"area_ge\": ",
            (unsigned long long)r->overflows, (unsigned long long)r->ovf_discarded);
    base_json_num(f, r->area_ge, 17);
    jppa(f, r);
    fprintf(f, ",\n  \"within_bound\": %s,\n  \"bound_check\": \"%s\",\n  \"golden_check\": \"%s\",\n",
            r->within_bound ? "true" : "false", tb_check_name(r->bound_check), r->golden_ok ? "ok" : "exceeded");
    fprintf(f, "  \"input_overflows\": %llu,\n  \"target\": \"%s\",\n  \"verdict\": \"%s\",\n  \"why\": \"%s\",\n",
            (unsigned long long)r->in_overflows, !r->target_set ? "none" : r->target_met ? "met" : "missed",
            r->ok ? "ok" : "fail", r->why);
    fputs("  \"signals\": [", f);
    for (int i = 0; i < r->nsigs; i++) {
        const tb_sig *g = &r->sigs[i];
        fprintf(f, "%s\n    {\"name\": \"%s\", \"fmt\": \"%s\", \"overflows\": %llu, ", i ? "," : "", g->name,
                sim_fmt_str(g->fmt, fb), (unsigned long long)g->overflows);
        if (g->seen) fprintf(f, "\"min\": %lld, \"max\": %lld, ", (long long)g->min, (long long)g->max);
        else fputs("\"min\": null, \"max\": null, ", f);
        fprintf(f, "\"range_min\": %lld, \"range_max\": %lld, \"overflows_discarded\": %llu}",
                (long long)sim_fmt_raw_min(g->fmt), (long long)sim_fmt_raw_max(g->fmt),
                (unsigned long long)g->ovf_discarded);
    }
    fputs(r->nsigs ? "\n  ],\n  \"outputs\": {" : "],\n  \"outputs\": {", f);
    for (int o = 0; o < r->n_out; o++) {
        fprintf(f, "%s\n    \"%s\": ", o ? "," : "", r->out[o].name);
        jmetrics(f, &r->out[o], "    ");
    }
    /* the engine that ran; the kernel's own counters only when it did */
    if (r->lanes)
        fprintf(f, "\n  },\n  \"sim\": {\"engine\": \"batch\", \"lanes\": %u, \"clocks\": %llu}\n}\n", (unsigned)r->lanes,
                (unsigned long long)r->stats.clocks);
    else {
        fprintf(f, "\n  },\n  \"sim\": {\"engine\": \"%s\", \"clocks\": %llu, \"events\": %llu, \"delta_cycles\": %llu, \"process_runs\": %llu",
                r->reference ? "reference" : "kernel", (unsigned long long)r->stats.clocks, (unsigned long long)r->stats.events,
                (unsigned long long)r->stats.deltas, (unsigned long long)r->stats.proc_runs);
        /* why the lanes did not take the run (the table's engine line says it too) */
        if (r->engine_why[0]) { fputs(", \"not_on_lanes\": ", f); base_json_str(f, r->engine_why); }
        fputs("}\n}\n", f);
    }
    return ferror(f) ? -1 : 0;
}

int tb_write_csv(const char *path, const tb_result *r, const vec_set *vs, char *err, size_t errlen)
{
    /* base_out: atomic replace of a regular file, written through to a
     * device or FIFO, "-" for stdout; every write error reported. */
    base_out *o = base_out_open(path, err, errlen);
    if (!o) return -1;
    FILE *f = base_out_file(o);
    size_t nv = (size_t)r->beats * (size_t)r->n_out;
    tb_csv_header(f, vs->n_out, (const char (*)[16])vs->out_names);
    for (size_t it = 0; it < r->vectors; it++)
        /* The item's output appeared with its first beat. */
        tb_csv_row(f, r, it, r->beat_cycle[it * (size_t)r->beats], r->raw + it * nv, vec_row(vs, it) + r->n_in);
    return base_out_close(o, err, errlen);
}

void tb_csv_header(FILE *f, int n_out, const char names[][16])
{
    fputs("index,cycle", f);
    for (int k = 0; k < n_out; k++) {
        const char *nm = names[k];
        fprintf(f, ",%s_raw,%s_real,%s_expected,%s_err", nm, nm, nm, nm);
    }
    fputc('\n', f);
}

void tb_csv_row(FILE *f, const tb_result *r, size_t idx, uint64_t cycle, const int64_t *raw,
                const double *expected)
{
    int nb = r->beats, no = r->n_out;
    fprintf(f, "%zu,%llu", idx, (unsigned long long)cycle);
    for (int b = 0; b < nb; b++)
        for (int o = 0; o < no; o++) {
            int k = b * no + o;
            double hw = sim_fx_to_real(raw[k], r->out[o].fmt);
            char x[3][32];
            fprintf(f, ",%lld,%s,%s,%s", (long long)raw[k], tnum(x[0], 32, "%.17g", hw),
                    tnum(x[1], 32, "%.17g", expected[k]), tnum(x[2], 32, "%.17g", hw - expected[k]));
        }
    fputc('\n', f);
}

void tb_print_ranges(FILE *f, const tb_result *r, int all)
{
    char fb[SIM_FMT_STRLEN];
    int shown = 0, fw = 8;   /* the format column, as in tb_print_table */
    for (int i = 0; i < r->nsigs; i++) {
        int n = (int)strlen(sim_fmt_str(r->sigs[i].fmt, fb));
        if ((all || r->sigs[i].overflows) && n > fw) fw = n;
    }
    for (int i = 0; i < r->nsigs; i++) {
        const tb_sig *g = &r->sigs[i];
        if (!all && !g->overflows) continue;
        if (!shown++)
            fprintf(f, "%-22s %-*s %10s %21s %21s %21s %21s\n", all ? "signal (range logging)" : "signal (overflowed)",
                    fw, "format", "overflows", "min raw", "max raw", "format min", "format max");
        char mn[24] = "-", mx[24] = "-";
        if (g->seen) { snprintf(mn, sizeof mn, "%lld", (long long)g->min); snprintf(mx, sizeof mx, "%lld", (long long)g->max); }
        fprintf(f, "%-22s %-*s %10llu %21s %21s %21lld %21lld\n", g->name, fw, sim_fmt_str(g->fmt, fb),
                (unsigned long long)g->overflows, mn, mx, (long long)sim_fmt_raw_min(g->fmt),
                (long long)sim_fmt_raw_max(g->fmt));
    }
}

void tb_print_table(FILE *f, const tb_result *r)
{
    const unit_desc *u = r->unit;
    char fb[SIM_FMT_STRLEN];
    fprintf(f, "unit %s, schedule %s, width %d, round %s, overflow %s\n", u->name,
            u->sched[r->cfg.schedule].name, r->cfg.width, sim_round_name(r->cfg.rnd), sim_ovf_name(r->cfg.ovf));
    for (int i = 0; i < u->nparams; i++) {
        char v[64];
        unit_param_get(&u->params[i], &r->cfg, v, sizeof v);
        fprintf(f, "%s%s=%s", i ? " " : "params: ", u->params[i].name, v);
        if (i == u->nparams - 1) fputc('\n', f);
    }
    fputs("formats:", f);
    for (int i = 0; i < u->nsigs; i++)
        if (unit_sig_built(u, i, &r->cfg)) fprintf(f, " %s=%s", u->sigs[i].name, sim_fmt_str(r->fmts.f[i], fb));
    char x[7][32];
    fprintf(f, "\nvectors %zu, cycles %llu, cycles/item %s, cycles/beat %s, latency %llu, area %s GE, overflows %llu\n",
            r->vectors, (unsigned long long)r->cycles, tnum(x[0], 32, "%.3g", r->cycles_per_item),
            tnum(x[1], 32, "%.3g", r->cycles_per_beat), (unsigned long long)r->latency,
            tnum(x[2], 32, "%.1f", r->area_ge), (unsigned long long)r->overflows);
    if (r->ovf_discarded)
        fprintf(f, "  (and %llu overflows on values no element took that clock, not counted: docs/formats.md)\n",
                (unsigned long long)r->ovf_discarded);
    print_crit(f, &r->ppa);
    fprintf(f, "switching %llu bit toggles, %s pJ/item (docs/timing.md)\n", (unsigned long long)r->ppa.toggles,
            tnum(x[3], 32, "%.3g", r->ppa.energy_pj_per_item));
    /* the engine that ran (docs/batch.md); the kernel's own counters only when it did */
    if (r->lanes)
        fprintf(f, "engine batch: %u lanes, levelized, the kernel's results (--kernel: its event counts)\n",
                (unsigned)r->lanes);
    else
        fprintf(f, "engine %s: %llu events, %llu delta cycles, %llu process runs%s%s%s\n",
                r->reference ? "reference" : "kernel", (unsigned long long)r->stats.events, (unsigned long long)r->stats.deltas,
                (unsigned long long)r->stats.proc_runs, r->engine_why[0] ? " (not on lanes: " : "",
                r->engine_why, r->engine_why[0] ? ")" : "");
    /* the format column as wide as its longest entry (a format with its
     * own modes, "s7.9:half-up:sat", is longer than the usual 8) */
    int fw = 8;
    for (int o = 0; o < r->n_out; o++) {
        int n = (int)strlen(sim_fmt_str(r->out[o].fmt, fb));
        if (n > fw) fw = n;
    }
    fprintf(f, "%-8s %-*s %12s %12s %12s %12s %10s %12s %12s %-9s %s\n", "output", fw, "format", "max|e|", "mean e",
            "rms e", "nmse", "max LSB", "bound", "max|e-ideal|", "bound", "golden");
    for (int o = 0; o < r->n_out; o++) {
        const tb_metrics *m = &r->out[o];
        char b[16];
        if (m->check == TB_CHECK_NO_BOUND) snprintf(b, sizeof b, "no bound");
        else tnum(b, sizeof b, "%.4g", m->bound);
        fprintf(f, "%-8s %-*s %12s %12s %12s %12s %10s %12s %12s %-9s %s\n", m->name, fw, sim_fmt_str(m->fmt, fb),
                tnum(x[0], 32, "%.4g", m->max_abs_err), tnum(x[1], 32, "%.4g", m->mean_err),
                tnum(x[2], 32, "%.4g", m->rms_err), tnum(x[3], 32, "%.4g", m->nmse),
                tnum(x[4], 32, "%.3g", m->max_err_lsb), b, tnum(x[5], 32, "%.4g", m->max_err_ideal),
                tb_check_name(m->check), m->check == TB_CHECK_NO_BOUND ? "-" : m->golden_ok ? "ok" : "exceeded");
    }
    tb_print_ranges(f, r, 0);
    fputs("errors: max|e| .. max LSB are against the vector file's expected outputs (the golden error);\n"
          "  max|e-ideal| is against the unit's ideal function of the quantized inputs, which the bound\n"
          "  limits (docs/bounds.md); golden ok: |e| <= bound + input rounding + method error\n", f);
    for (int o = 0; o < r->n_out; o++)
        if (r->out[o].max_method_err > 4 * sim_fmt_lsb(r->out[o].fmt))
            fprintf(f, "method: %s's ideal is up to %.4g from the true function (the unit's own approximation)\n",
                    r->out[o].name, r->out[o].max_method_err);
    if (r->bound_check == TB_CHECK_OK) fputs("bound: every output within its bound\n", f);
    else if (r->bound_check == TB_CHECK_EXCEEDED) fprintf(f, "bound: EXCEEDED, first at vector %zu\n", r->first_violation);
    else if (r->bound_check == TB_CHECK_NO_BOUND) fputs("bound: NONE derived for these formats (not checked)\n", f);
    else fprintf(f, "bound: UNCHECKED from vector %zu (the unit's ideal is a double, too coarse at this width)\n",
                 r->first_violation);
    fprintf(f, "verdict: %s\n", r->why);
}

void tb_settext(char *dst, size_t size, const char *fmt, ...)
{
    char tmp[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    size_t n = strlen(tmp);
    if (n >= size) n = size - 1;
    memcpy(dst, tmp, n);
    dst[n] = 0;
}
