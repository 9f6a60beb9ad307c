/* cli_synth.c - synth --sta (Yosys and OpenSTA on the user's Liberty) and
 * synth --fpga ice40 (Yosys and nextpnr): the tools' figures printed
 * beside the model's (the critical path and area `run` reports), with
 * the ratios model / tool; --json for a machine. */
#define _XOPEN_SOURCE 700          /* mkdtemp */
#include "testbench/cli/cli_synth.h"
#include "testbench/tb_synth.h"
#include "testbench/tb_verilog.h"
#include "base/base_json.h"
#include "base/base_proc.h"
#include <stdlib.h>
#include <string.h>

const char *cli_synth_dir(const cli_synth_st *st, char *tmpl, size_t len)
{
    if (st->keep) return cli_make_dir(st->keep) ? NULL : st->keep;
    const char *t = getenv("TMPDIR");
    snprintf(tmpl, len, "%s/shadesim_synth_XXXXXX", t && *t ? t : "/tmp");
    if (!mkdtemp(tmpl)) { cli_usage_error("synth: cannot make a temporary folder in %s", t && *t ? t : "/tmp"); return NULL; }
    return tmpl;
}

void cli_synth_cleanup(const cli_synth_st *st, const char *dir, int signal)
{
    if (!st->keep) base_proc_rmtree(dir);
    if (signal) base_proc_reraise(signal);
}

/* The model's figures: critical path and f_max (tb_unit_timing), area. */
typedef struct model_fig { tb_ppa p; double ge; int ok; char why[600]; } model_fig;

/* The model's figures, its carries those of ABC's script: --abc's, or
 * by the model's area (tb_abc_auto) into *abc (TB_ABC_*). */
static void model_figures(const cli_unit_opts *o, const unit_fmts *fm, int abc_opt, model_fig *m, int *abc)
{
    memset(m, 0, sizeof *m);
    m->ge = tb_verilog_area(o->u, &o->cfg, fm, m->why, sizeof m->why);
    *abc = abc_opt == CLI_SYNTH_ABC_LIGHT ? TB_ABC_LIGHT : abc_opt == CLI_SYNTH_ABC_FULL ? TB_ABC_FULL : tb_abc_auto(m->ge);
    m->ok = m->ge >= 0 && !tb_unit_timing_abc(o->u, &o->cfg, fm, *abc, &m->p, m->why, sizeof m->why);
}

static void head(const cli_unit_opts *o, const char *what)
{
    printf("%s --width %d --schedule %s (%s, %s): %s\n", o->u->name, o->cfg.width,
           o->u->sched[o->cfg.schedule].name, sim_round_name(o->cfg.rnd), sim_ovf_name(o->cfg.ovf), what);
}

/* The cell types along the path, a run of one type as "TYPE xN",
 * wrapped after about 72 columns under an indent. */
static void print_cells(const tb_sta *r)
{
    int col = 0;
    for (int i = 0; i < r->npath; ) {
        int k = i;
        while (k < r->npath && !strcmp(r->path[k], r->path[i])) k++;
        char item[48];
        if (k - i > 1) snprintf(item, sizeof item, "%s x%d", r->path[i], k - i);
        else snprintf(item, sizeof item, "%s", r->path[i]);
        if (col && col + (int)strlen(item) > 72) { printf(",\n"); col = 0; }
        col += printf("%s%s", col ? ", " : "    ", item);
        i = k;
    }
    if (col) printf("\n");
}

static const char *point_kind(const char *k)
{
    return strstr(k, "flip-flop") ? "register" : strstr(k, "input") ? "input port" : strstr(k, "output") ? "output port" : k;
}

static void sta_text(const cli_unit_opts *o, const cli_synth_st *st, int abc, const tb_sta *r, const model_fig *m)
{
    char what[400];
    snprintf(what, sizeof what, "Yosys and OpenSTA on %s (%s = 1 GE = %.3f um^2)%s", st->liberty, r->ge_cell, r->ge_area,
             abc == TB_ABC_LIGHT ? ", ABC's light script" : "");
    head(o, what);
    printf("                 shadesim model   OpenSTA          model / tool\n");
    if (m->ok) {
        printf("  critical path  %8.0f ps      %8.1f ps      %.2f\n", m->p.crit_ps, r->crit_ps, m->p.crit_ps / r->crit_ps);
        printf("  f_max          %8.0f MHz     %8.0f MHz     %.2f\n", m->p.fmax_mhz, r->fmax_mhz, m->p.fmax_mhz / r->fmax_mhz);
        printf("  area           %8.0f GE      %8.0f GE      %.2f (mapped: %.1f um^2, %ld cells)\n", m->ge, r->area_ge,
               m->ge / r->area_ge, r->area, r->cells);
    } else {
        printf("  critical path  (no model: %s)   %.1f ps\n", m->why, r->crit_ps);
        printf("  area           %.0f GE (%.1f um^2, %ld cells)\n", r->area_ge, r->area, r->cells);
    }
    printf("OpenSTA's critical path at a %.0f ps clock: arrival %.1f ps + setup %.1f ps = %.1f ps (slack %.1f ps)\n",
           r->period_ps, r->arrival_ps, r->setup_ps, r->crit_ps, r->slack_ps);
    printf("  from %s (%s) to %s (%s), %d cells:\n", r->start, point_kind(r->start_kind), r->end,
           point_kind(r->end_kind), r->npath);
    print_cells(r);
    if (m->ok) {
        char ptext[1200];
        tb_ppa_path_text(&m->p, ptext, sizeof ptext);
        printf("shadesim's critical path: %d levels (%s)\n", m->p.levels, ptext);
    }
}

static void json_ratio(const char *key, double a, double b, int last)
{
    printf("\"%s\": ", key);
    base_json_num(stdout, b > 0 ? a / b : 0, 4);
    printf("%s", last ? "" : ", ");
}

static void json_head(const cli_unit_opts *o, const char *flow)
{
    printf("{\"unit\": ");
    base_json_str(stdout, o->u->name);
    printf(", \"width\": %d, \"schedule\": ", o->cfg.width);
    base_json_str(stdout, o->u->sched[o->cfg.schedule].name);
    printf(", \"flow\": \"%s\"", flow);
}

static void json_model(const model_fig *m)
{
    printf(", \"model\": ");
    if (!m->ok) { printf("null"); return; }
    printf("{\"crit_ps\": ");
    base_json_num(stdout, m->p.crit_ps, 6);
    printf(", \"fmax_mhz\": ");
    base_json_num(stdout, m->p.fmax_mhz, 6);
    printf(", \"levels\": %d, \"area_ge\": ", m->p.levels);
    base_json_num(stdout, m->ge, 6);
    printf("}");
}

static void sta_json(const cli_unit_opts *o, const cli_synth_st *st, int abc, const tb_sta *r, const model_fig *m)
{
    json_head(o, "sta");
    printf(", \"liberty\": ");
    base_json_str(stdout, st->liberty);
    printf(", \"abc\": \"%s\"", abc == TB_ABC_LIGHT ? "light" : "full");
    printf(", \"sta\": {\"period_ps\": %.1f, \"arrival_ps\": %.1f, \"setup_ps\": %.1f, \"slack_ps\": %.1f, "
           "\"crit_ps\": %.1f, \"fmax_mhz\": ", r->period_ps, r->arrival_ps, r->setup_ps, r->slack_ps, r->crit_ps);
    base_json_num(stdout, r->fmax_mhz, 6);
    printf(", \"start\": ");
    base_json_str(stdout, r->start);
    printf(", \"end\": ");
    base_json_str(stdout, r->end);
    printf(", \"cells\": [");
    for (int i = 0; i < r->npath; i++) { printf("%s", i ? ", " : ""); base_json_str(stdout, r->path[i]); }
    printf("]}, \"area\": {\"lib_units\": %.3f, \"cells\": %ld, \"ge_cell\": ", r->area, r->cells);
    base_json_str(stdout, r->ge_cell);
    printf(", \"ge_area\": %.6g, \"ge\": ", r->ge_area);
    base_json_num(stdout, r->area_ge, 6);
    printf("}");
    json_model(m);
    printf(", \"ratio\": {");
    if (m->ok) {
        json_ratio("crit_ps", m->p.crit_ps, r->crit_ps, 0);
        json_ratio("fmax", m->p.fmax_mhz, r->fmax_mhz, 0);
        json_ratio("area", m->ge, r->area_ge, 1);
    }
    printf("}}\n");
}

static void fpga_text(const cli_unit_opts *o, const tb_fpga *r, const model_fig *m)
{
    char what[200];
    snprintf(what, sizeof what, "Yosys synth_ice40 and nextpnr-ice40 --%s --package %s", r->device, r->package);
    head(o, what);
    printf("  LUTs (SB_LUT4)        %7ld\n", r->luts);
    printf("  flip-flops (SB_DFF*)  %7ld\n", r->ffs);
    printf("  carries (SB_CARRY)    %7ld\n", r->carries);
    printf("  DSPs (SB_MAC16)       %7ld\n", r->dsps);
    if (r->rams) printf("  RAMs (SB_RAM40_4K)    %7ld\n", r->rams);
    printf("  logic cells           %7ld of %ld\n", r->lcs, r->lcs_avail);
    printf("  I/O cells             %7ld of %ld\n", r->ios, r->ios_avail);
    if (r->clocked)
        printf("  f_max (clk)           %7.2f MHz (nextpnr after routing; %s the %.2f MHz target)\n", r->fmax_mhz,
               r->met ? "meets" : "misses", r->target_mhz);
    else
        printf("  f_max (port to port)  %7.2f MHz (no clocked path: 1 / nextpnr's longest path, %.2f ns)\n",
               r->fmax_mhz, r->comb_ns);
    if (r->clocked && (r->in_ns > 0 || r->out_ns > 0 || r->comb_ns > 0)) {
        printf("  port paths           ");
        if (r->in_ns > 0) printf(" in -> clk %.2f ns", r->in_ns);
        if (r->out_ns > 0) printf("%s clk -> out %.2f ns", r->in_ns > 0 ? "," : "", r->out_ns);
        if (r->comb_ns > 0) printf("%s in -> out %.2f ns", r->in_ns > 0 || r->out_ns > 0 ? "," : "", r->comb_ns);
        printf(" (pads included; not in f_max)\n");
    }
    if (m->ok)
        printf("  shadesim model        %7.0f MHz (%.0f ps on NanGate 45 nm cells: an ASIC model, not this FPGA's)\n",
               m->p.fmax_mhz, m->p.crit_ps);
}

static void fpga_json(const cli_unit_opts *o, const tb_fpga *r, const model_fig *m)
{
    json_head(o, "ice40");
    printf(", \"device\": ");
    base_json_str(stdout, r->device);
    printf(", \"package\": ");
    base_json_str(stdout, r->package);
    printf(", \"luts\": %ld, \"ffs\": %ld, \"carries\": %ld, \"dsps\": %ld, \"rams\": %ld, \"logic_cells\": %ld, "
           "\"logic_cells_avail\": %ld, \"ios\": %ld, \"ios_avail\": %ld, \"fmax_mhz\": ", r->luts, r->ffs, r->carries,
           r->dsps, r->rams, r->lcs, r->lcs_avail, r->ios, r->ios_avail);
    base_json_num(stdout, r->fmax_mhz, 6);
    printf(", \"target_mhz\": ");
    base_json_num(stdout, r->target_mhz, 6);
    printf(", \"clocked\": %s, \"met\": %s, \"in_ns\": %.2f, \"out_ns\": %.2f, \"comb_ns\": %.2f",
           r->clocked ? "true" : "false", r->met ? "true" : "false", r->in_ns, r->out_ns, r->comb_ns);
    json_model(m);
    printf("}\n");
}

int cli_synth_flow(const cli_unit_opts *o, const unit_fmts *fm, const cli_synth_st *st)
{
    model_fig m;
    int abc;
    model_figures(o, fm, st->abc, &m, &abc);
    char tmpl[4096], err[800];
    const char *dir = cli_synth_dir(st, tmpl, sizeof tmpl);
    if (!dir) return CLI_USAGE;
    tb_synth_run run = { base_proc_now(), st->timeout_s < 0 ? CLI_SYNTH_TIMEOUT : st->timeout_s, cli_stderr_tty(), 0 };
    tb_sta sr;
    tb_fpga fr;
    int t;
    if (st->sta)
        t = tb_synth_sta(o->u, &o->cfg, fm, st->liberty, st->clock_ps > 0 ? st->clock_ps : 10000, abc, dir, &run, &sr, err, sizeof err);
    else {
        memset(&fr, 0, sizeof fr);
        snprintf(fr.device, sizeof fr.device, "%s", st->device ? st->device : "hx8k");
        snprintf(fr.package, sizeof fr.package, "%s", st->package ? st->package : "ct256");
        fr.freq_mhz = st->freq_mhz;
        t = tb_synth_fpga(o->u, &o->cfg, fm, dir, &run, &fr, err, sizeof err);
    }
    cli_synth_cleanup(st, dir, t == TB_SYNTH_SIGNAL ? run.signal : 0);
    if (t == TB_SYNTH_FAILED) return cli_from_tb(TB_FAIL, "%s", err);
    if (t != TB_SYNTH_OK) return cli_usage_error("%s", err);   /* missing tool or file, too small a device, time limit */
    if (st->sta) { if (st->json) sta_json(o, st, abc, &sr, &m); else sta_text(o, st, abc, &sr, &m); }
    else if (st->json) fpga_json(o, &fr, &m);
    else fpga_text(o, &fr, &m);
    return cli_stdout_done(CLI_OK);
}
