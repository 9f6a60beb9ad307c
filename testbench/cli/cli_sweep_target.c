/* cli_sweep_target.c - the sweep's target search (--target-error,
 * --target-nmse): the search per settings group and its check on held-out
 * stimuli (testbench/study/tb_sweep.h, tb_sweep_check.h), and what it
 * prints and writes (target.json, target.csv). */
#include "testbench/cli/cli_sweep.h"
#include "testbench/study/tb_sweep_check.h"
#include "base/base_json.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The formats of the signals configuration cfg builds. */
static void fmt_list(FILE *f, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *pre, const char *sep)
{
    char fb[SIM_FMT_STRLEN];
    for (int i = 0, first = 1; i < u->nsigs; i++) {
        if (!unit_sig_built(u, i, cfg)) continue;
        fprintf(f, "%s%s%s=%s", first ? "" : sep, pre, u->sigs[i].name, sim_fmt_str(fm->f[i], fb));
        first = 0;
    }
}

static const char *metric_name(tb_target_kind k) { return k == TB_TARGET_NMSE ? "NMSE" : "max |e|"; }
static double metric_of(tb_target_kind k, const tb_result *r) { return k == TB_TARGET_NMSE ? r->nmse : r->max_abs_err; }

/* Row of the smallest width of group g that meets the target itself (no
 * margin), or s->n. */
static size_t uniform_at(const tb_sweep *s, size_t g, tb_target_kind k, double target)
{
    for (size_t i = g; i < s->n; i += s->ngroups)
        if (tb_sweep_holds(s, &s->row[i].r, s->row[i].status, k, target, UINT64_MAX)) return i;
    return s->n;
}

/* The search's speed and energy limits in words into b, "" without any. */
static const char *limits_text(const tb_sweep *s, char *b, size_t n)
{
    const tb_ppa_limits *l = &s->spec.ppa;
    b[0] = 0;
    if (l->min_items_per_s > 0) snprintf(b, n, ", at least %.6g items per second at f_max", l->min_items_per_s);
    if (l->max_energy_pj > 0) snprintf(b + strlen(b), n - strlen(b), ", at most %.6g pJ per item", l->max_energy_pj);
    return b;
}

void sweep_print_target(FILE *f, const tb_sweep *s, const target_info *t)
{
    for (size_t g = 0; g < s->ngroups; g++) {
        const tb_target_res *x = &t->res[g];
        char gl[200];
        tb_sweep_group_label(s, g, gl, sizeof gl);
        fprintf(f, "target %s <= %g%s%s%s: ", metric_name(t->kind), t->value, *gl ? " (" : "", gl, *gl ? ")" : "");
        if (!x->met && x->limits_why[0]) {
            fprintf(f, "the cheapest per-signal formats that meet it miss the limits: %s\n", x->limits_why);
            continue;
        }
        if (!x->met) {
            fprintf(f, "no width in %d..%d meets it within the error bound\n", s->spec.wlo, s->spec.whi);
            continue;
        }
        const tb_result *ru = &s->row[x->uniform].r;
        double saved = ru->area_ge - x->r.area_ge;
        char lb[160];
        fprintf(f, "uniform width %d: %.1f GE, %s %.4g; per-signal formats: %.1f GE, %s %.4g, saving %.1f GE (%.1f%%), %zu runs\n",
                s->cfg[x->uniform].cfg.width, ru->area_ge, metric_name(t->kind), metric_of(t->kind, ru), x->r.area_ge,
                metric_name(t->kind), metric_of(t->kind, &x->r), saved, ru->area_ge > 0 ? 100 * saved / ru->area_ge : 0.0,
                x->runs);
        limits_text(s, lb, sizeof lb);
        fprintf(f, "  speed and energy: uniform %.0f MHz, %.4g M items/s, %.3g pJ/item; chosen %.0f MHz, %.4g M items/s, "
                "%.3g pJ/item%s%s%s\n", ru->ppa.fmax_mhz, ru->ppa.items_per_s / 1e6, ru->ppa.energy_pj_per_item,
                x->r.ppa.fmax_mhz, x->r.ppa.items_per_s / 1e6, x->r.ppa.energy_pj_per_item, lb[0] ? " (limits: " : "",
                lb[0] ? lb + 2 : "", lb[0] ? ")" : "");
        fputs("  formats:", f);
        fmt_list(f, s->spec.u, &s->cfg[x->uniform].cfg, &x->fmts, " ", "");
        fputc('\n', f);
        if (t->margin > 0) {
            fprintf(f, "  searched for %s <= %g (margin %g bits)", metric_name(t->kind), t->goal, t->margin);
            size_t ua = uniform_at(s, g, t->kind, t->value);
            if (ua < s->n) {
                double sv = s->row[ua].r.area_ge - x->r.area_ge;
                fprintf(f, "; against the smallest uniform width that meets the target itself, %d (%.1f GE): saving %.1f GE (%.1f%%)",
                        s->cfg[ua].cfg.width, s->row[ua].r.area_ge, sv, 100 * sv / s->row[ua].r.area_ge);
            }
            fputc('\n', f);
        }
        if (x->heldout)
            fprintf(f, "  held-out check (seed %llu, %zu vectors): %s %.4g (uniform width %d: %.4g): %s%s\n",
                    t->ho_seed, t->ho_rows, metric_name(t->kind), metric_of(t->kind, &x->heldout_r),
                    s->cfg[x->uniform].cfg.width, metric_of(t->kind, &x->heldout_u),
                    x->heldout_ok ? "passed" : "FAILED: ", x->heldout_why);
        sweep_ranges_print(f, t, g);
    }
}

/* The target search's result per group as CSV (target.csv). */
int sweep_write_target_csv(const tb_sweep *s, const target_info *t, oset *os)
{
    const unit_desc *u = s->spec.u;
    FILE *f = sweep_oset_open(os, "target.csv");
    if (!f) return CLI_USAGE;
    fputs("group,unit,schedule", f);
    for (int i = 0; i < u->nparams; i++) fprintf(f, ",%s", u->params[i].name);
    fputs(",round,overflow,metric,target,margin_bits,goal,met,uniform_width,uniform_area_ge,uniform_metric,"
          "chosen_area_ge,chosen_metric,area_saved_ge,area_saved_pct,runs,uniform_fmax_mhz,uniform_items_per_s,"
          "uniform_energy_pj_per_item,chosen_fmax_mhz,chosen_items_per_s,chosen_energy_pj_per_item,heldout_seed,"
          "heldout_vectors,heldout_metric,heldout_uniform_metric,heldout_overflows,heldout_passed,formats\n", f);
    for (size_t g = 0; g < s->ngroups; g++) {
        const tb_target_res *x = &t->res[g];
        const unit_cfg *c = &s->cfg[g].cfg;
        fprintf(f, "%zu,%s,%s", g, u->name, u->sched[c->schedule].name);
        for (int i = 0; i < u->nparams; i++) {
            char v[64];
            unit_param_get(&u->params[i], c, v, sizeof v);
            fprintf(f, ",%s", v);
        }
        fprintf(f, ",%s,%s,%s,%.17g,%g,%.17g,%s", sim_round_name(c->rnd), sim_ovf_name(c->ovf),
                t->kind == TB_TARGET_NMSE ? "nmse" : "max_abs_err", t->value, t->margin, t->goal,
                x->met ? "true" : "false");
        if (!x->met) { fputs(",,,,,,,,,,,,,,,,,,,,,,\n", f); continue; }
        const tb_result *ru = &s->row[x->uniform].r;
        double saved = ru->area_ge - x->r.area_ge;
        fprintf(f, ",%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu", s->cfg[x->uniform].cfg.width, ru->area_ge,
                metric_of(t->kind, ru), x->r.area_ge, metric_of(t->kind, &x->r), saved,
                ru->area_ge > 0 ? 100 * saved / ru->area_ge : 0.0, x->runs);
        fprintf(f, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", ru->ppa.fmax_mhz, ru->ppa.items_per_s,
                ru->ppa.energy_pj_per_item, x->r.ppa.fmax_mhz, x->r.ppa.items_per_s, x->r.ppa.energy_pj_per_item);
        fprintf(f, ",%llu,%zu,%.17g,%.17g,%llu,%s,", t->ho_seed, t->ho_rows, metric_of(t->kind, &x->heldout_r),
                metric_of(t->kind, &x->heldout_u), (unsigned long long)x->heldout_r.overflows,
                x->heldout_ok ? "true" : "false");
        fmt_list(f, u, c, &x->fmts, "", " ");
        fputc('\n', f);
    }
    return 0;
}

static void jstr_fmts(FILE *f, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm)
{
    char fb[SIM_FMT_STRLEN];
    fputc('{', f);
    for (int i = 0, first = 1; i < u->nsigs; i++) {
        if (!unit_sig_built(u, i, cfg)) continue;
        fprintf(f, "%s\"%s\": \"%s\"", first ? "" : ", ", u->sigs[i].name, sim_fmt_str(fm->f[i], fb));
        first = 0;
    }
    fputc('}', f);
}

static void jdesign(FILE *f, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const tb_result *r)
{
    fputs("{\"formats\": ", f);
    jstr_fmts(f, u, cfg, fm);
    fputs(", \"max_abs_err\": ", f); base_json_num(f, r->max_abs_err, 17);
    fputs(", \"rms_err\": ", f); base_json_num(f, r->rms_err, 17);
    fputs(", \"nmse\": ", f); base_json_num(f, r->nmse, 17);
    fputs(", \"area_ge\": ", f); base_json_num(f, r->area_ge, 17);
    fputs(", \"fmax_mhz\": ", f); base_json_num(f, r->ppa.fmax_mhz, 17);
    fputs(", \"items_per_s\": ", f); base_json_num(f, r->ppa.items_per_s, 17);
    fputs(", \"energy_pj_per_item\": ", f); base_json_num(f, r->ppa.energy_pj_per_item, 17);
    fprintf(f, ", \"overflows\": %llu, \"within_bound\": %s}", (unsigned long long)r->overflows,
            r->within_bound ? "true" : "false");
}

int sweep_write_target_json(const tb_sweep *s, const target_info *t, oset *os)
{
    const unit_desc *u = s->spec.u;
    FILE *f = sweep_oset_open(os, "target.json");
    if (!f) return CLI_USAGE;
    char lb[160];
    limits_text(s, lb, sizeof lb);
    fprintf(f, "{\n  \"unit\": \"%s\",\n  \"target\": {\"metric\": \"%s\", \"value\": ", u->name,
            t->kind == TB_TARGET_NMSE ? "nmse" : "max_abs_err");
    base_json_num(f, t->value, 17);
    fputs(", \"margin_bits\": ", f);
    base_json_num(f, t->margin, 17);
    fputs(", \"goal\": ", f);
    base_json_num(f, t->goal, 17);
    /* --min-throughput, --max-energy: null when not given */
    fputs("},\n  \"limits\": {\"min_items_per_s\": ", f);
    base_json_num(f, s->spec.ppa.min_items_per_s > 0 ? s->spec.ppa.min_items_per_s : NAN, 17);
    fputs(", \"max_energy_pj_per_item\": ", f);
    base_json_num(f, s->spec.ppa.max_energy_pj > 0 ? s->spec.ppa.max_energy_pj : NAN, 17);
    fprintf(f, "},\n  \"rule\": \"metric <= goal (the target less the margin), every output within its bound, no more "
               "overflows than the uniform design%s\",\n  \"held_out\": {\"seed\": %llu, \"vectors\": %zu, \"rule\": "
               "\"metric <= target, every output within its bound, no more overflows than the uniform design on the "
               "same stimuli%s\"},\n  \"groups\": [", lb, t->ho_seed, t->ho_rows, lb);
    for (size_t g = 0; g < s->ngroups; g++) {
        const tb_target_res *x = &t->res[g];
        const unit_cfg *c = &s->cfg[g].cfg;
        fprintf(f, "%s\n    {\"schedule\": \"%s\", \"params\": {", g ? "," : "", u->sched[c->schedule].name);
        for (int i = 0; i < u->nparams; i++) {
            char v[64];
            unit_param_get(&u->params[i], c, v, sizeof v);
            fprintf(f, "%s\"%s\": \"%s\"", i ? ", " : "", u->params[i].name, v);
        }
        fprintf(f, "}, \"round\": \"%s\", \"overflow\": \"%s\",\n     \"met\": %s", sim_round_name(c->rnd),
                sim_ovf_name(c->ovf), x->met ? "true" : "false");
        if (x->met) {
            const tb_result *ru = &s->row[x->uniform].r;
            fprintf(f, ",\n     \"uniform\": {\"width\": %d, \"design\": ", s->cfg[x->uniform].cfg.width);
            jdesign(f, u, c, &s->cfg[x->uniform].fmts, ru);
            fputs("},\n     \"chosen\": ", f);
            jdesign(f, u, c, &x->fmts, &x->r);
            fputs(",\n     \"area_saved_ge\": ", f); base_json_num(f, ru->area_ge - x->r.area_ge, 17);
            fputs(", \"area_saved_pct\": ", f);
            base_json_num(f, ru->area_ge > 0 ? 100 * (ru->area_ge - x->r.area_ge) / ru->area_ge : 0, 17);
            fprintf(f, ", \"runs\": %zu,\n     \"run_args\": \"--round %s --overflow %s", x->runs, sim_round_name(c->rnd),
                    sim_ovf_name(c->ovf));
            fmt_list(f, u, c, &x->fmts, " --fmt ", "");
            fputc('"', f);
            fputs(",\n     \"held_out\": {\"passed\": ", f);
            fputs(x->heldout_ok ? "true" : "false", f);
            fputs(", \"metric\": ", f); base_json_num(f, metric_of(t->kind, &x->heldout_r), 17);
            fputs(", \"uniform_metric\": ", f); base_json_num(f, metric_of(t->kind, &x->heldout_u), 17);
            fprintf(f, ", \"overflows\": %llu, \"uniform_overflows\": %llu, \"why\": \"",
                    (unsigned long long)x->heldout_r.overflows, (unsigned long long)x->heldout_u.overflows);
            for (const char *q = x->heldout_why; *q; q++)
                if (*q == '"' || *q == '\\') fprintf(f, "\\%c", *q);
                else if ((unsigned char)*q >= 0x20) fputc(*q, f);
            fputs("\"}", f);
            sweep_ranges_json(f, t, g);
        }
        fputc('}', f);
    }
    fputs("\n  ]\n}\n", f);
    return 0;
}

int sweep_target_search(sweep_args *a, tb_sweep *s, int tty)
{
    char err[600];
    a->t.res = calloc(s->ngroups, sizeof *a->t.res);
    if (!a->t.res) base_out_of_memory();
    for (size_t g = 0; g < s->ngroups; g++) {
        if (tty) fprintf(stderr, "\rshadesim sweep %s: target search, settings %zu/%zu \033[K", s->spec.u->name, g + 1, s->ngroups);
        int bad = tb_sweep_target(s, g, a->t.kind, a->t.goal, a->threads, &a->t.res[g], err, sizeof err);
        if (tty) fputs("\r\033[K", stderr);
        if (bad) return cli_usage_error("%s", err);
    }
    /* held-out stimuli: the sweep's seed + 1 (the default files are seed 1's) */
    a->t.ho_seed = (a->nvec > 0 ? a->seed : 1) + 1;
    a->t.ho_rows = s->vs[0]->n_rows;
    if (tb_sweep_heldout_all(s, a->t.res, a->t.kind, a->t.value, a->t.ho_seed, &a->ho_failed, err, sizeof err))
        return cli_usage_error("%s", err);
    /* a target no design meets (nor its speed and energy limits) is a
     * result that failed: exit 1, as docs/cli.md says of every --target-* */
    a->t_missed = 0;
    for (size_t g = 0; g < s->ngroups; g++) a->t_missed += !a->t.res[g].met;
    return sweep_ranges_collect(a, s);
}
