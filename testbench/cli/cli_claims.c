/* cli_claims.c - the verb claims: every numerical claim of the papers next
 * to what we measure, with a verdict, the papers' speed claims measured as
 * hardware clocks and area of our units against chains of our units for
 * the exact functions, the failure region of each approximation, and with
 * -o DIR the charts (docs/brdf.md). The study measures them all
 * (testbench/study/tb_claims.h); this file parses the options, prints the
 * text or JSON and writes the charts. Deterministic: the same bytes on
 * every machine; CPU timings of float code are `make bench`'s
 * (bench/bench_claims.c). */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/study/tb_claims.h"
#include "testbench/study/tb_scene_claims.h"
#include "testbench/study/tb_factor_claims.h"
#include "base/base_out.h"
#include "base/base_json.h"
#include <stddef.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* --------------------------------------------------------------- charts */

static int write_chart(chart *c, const char *dir, const char *file, char paths[][600], int *np)
{
    char path[600], err[700];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    if (!c) base_out_of_memory();
    int rc = chart_write(c, path, err, sizeof err);
    chart_free(c);
    if (rc) return cli_usage_error("%s", err);
    snprintf(paths[(*np)++], 600, "%s", path);
    return CLI_OK;
}

static int write_charts(const char *dir, char paths[][600], int *np)
{
    if (cli_make_dir(dir)) return CLI_USAGE;
    /* the charts are one set: all appear, or none */
    base_outset *set = base_outset_begin();
    char err[600];
    if (!set) base_out_of_memory();
    for (const tb_claims_chart *c = tb_claims_charts; c->file; c++)
        if (write_chart(c->make(), dir, c->file, paths, np)) {
            base_outset_abort(set);
            return CLI_USAGE;
        }
    if (base_outset_commit(set, err, sizeof err)) return cli_usage_error("%s", err);
    return CLI_OK;
}

/* ---------------------------------------------------------------- output */

typedef struct report {
    claim_result rows[CLAIMS_MAX];
    const char *kind[CLAIMS_MAX];     /* "accuracy", "speed_hw", "factor", "scene" */
    size_t n;
    tb_speed_hw hc;
    tb_claims_bands fb[TB_CLAIMS_NAPPROX];
} report;

static void print_row(FILE *f, const claim_result *r)
{
    fprintf(f, "%s (%s): %s\n", r->id, r->source, r->verdict);
    fprintf(f, "  claim:    %s\n", r->claim);
    if (isfinite(r->claimed)) fprintf(f, "  paper:    %g    measured: %.4g\n", r->claimed, r->measured);
    else fprintf(f, "  paper:    (no number)    measured: %.4g\n", r->measured);
    fprintf(f, "  ours:     %s\n", r->measured_text);
    fprintf(f, "  note:     %s\n\n", r->note);
}

/* The units of the speed table that derive no error bound at its width,
 * each quoted with q, into buf ("" when none); how many. */
static int no_bound(const tb_speed_hw *h, char *buf, size_t len, const char *q)
{
    const tb_hw_point *pts[] = { &h->d16, &h->ward16, &h->pow_d, &h->pow_w, &h->sq, &h->div };
    int k = 0;
    buf[0] = 0;
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        char name[40];
        snprintf(name, sizeof name, "%s%s%s", q, pts[i]->unit, q);
        if (!pts[i]->unbounded || strstr(buf, name)) continue;
        snprintf(buf + strlen(buf), len - strlen(buf), "%s%s", k++ ? ", " : "", name);
    }
    return k;
}

static void print_text(FILE *f, const report *rp, char paths[][600], int np)
{
    fputs("The papers' numerical claims next to what the double-precision references measure.\n"
          "Verdicts: holds / holds only for <condition> / does not hold.\n\n", f);
    for (size_t i = 0; i < rp->n; i++)
        if (!strcmp(rp->kind[i], "accuracy")) print_row(f, &rp->rows[i]);

    const tb_speed_hw *h = &rp->hc;
    fprintf(f, "Speed claims in hardware: our units at width %d, each simulated (clocks per item, area in GE,\n"
               "clock period = the design's critical path, time per item = clocks x period)\n", h->width);
    if (!h->ok) fputs("  (some unit failed to run; figures may be missing)\n", f);
    fprintf(f, "  %-40s %6s %7s %9s %7s %11s\n", "", "clocks", "area", "period ps", "ns/item", "ns x kGE");
    struct { const char *name; double cl, ar, pd; } t[] = {
        { "d_approx (D16, m=0.2)", h->d16.clocks, h->d16.area, h->d16.period_ps },
        { "exact D without its exp", h->exact_d_clocks, h->exact_d_area, h->exact_d_period_ps },
        { h->pow_d.label, h->pow_d.clocks, h->pow_d.area, h->pow_d.period_ps },
        { "ward_approx (a=0.2)", h->ward16.clocks, h->ward16.area, h->ward16.period_ps },
        { "Ward exp term without its exp (wired)", h->exact_w_clocks, h->exact_w_area, h->exact_w_period_ps },
        { h->pow_w.label, h->pow_w.clocks, h->pow_w.area, h->pow_w.period_ps },
        { "  stage: powg g=2 (squarer)", h->sq.clocks, h->sq.area, h->sq.period_ps },
        { "  stage: div (restoring divider)", h->div.clocks, h->div.area, h->div.period_ps },
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        double ns = t[i].cl * t[i].pd / 1e3;
        fprintf(f, "  %-40s %6.0f %7.0f %9.0f %7.1f %11.1f\n", t[i].name, t[i].cl, t[i].ar, t[i].pd, ns,
                ns * t[i].ar / 1e3);
    }
    /* a width where run would say NO BOUND: said here too */
    char nb[200];
    int k = no_bound(h, nb, sizeof nb, "");
    if (k)
        fprintf(f, "  note: at width %d, %s derive%s no error bound for %s formats (run says NO BOUND):\n"
                   "  %s figures are measured, %s errors not checked against a bound\n", h->width, nb,
                k > 1 ? "" : "s", k > 1 ? "their" : "its", k > 1 ? "their" : "its", k > 1 ? "their" : "its");
    fprintf(f, "  exact D = c^2 (squarer) -> (1-c^2)/c^2 (divider) -> exp -> c^4 (squarer on c^2) ->\n"
          "  exp/c^4 (divider). The first two stages are wired into one design (1 - c^2 by a\n"
          "  subtractor, operand registers, a valid flag) and simulated end to end, one item\n"
          "  at a time: Ward's exp term (max error %.2f quotient LSBs on c in [0.75, 1)); exact\n"
          "  D adds the squarer's and the divider's own clocks and areas, each simulated alone\n"
          "  (their glue not counted). The exponential has no unit: it is not counted, so both\n"
          "  exact figures are lower bounds. A chain is one clocked design: its period is its\n"
          "  slowest stage's (exact D's: the wired design's). pow_n rows: the papers'\n"
          "  intermediate cos^(2/m^2-4) and cos^(2/a^2) forms computed exactly.\n\n", h->wired_err_lsb);
    for (size_t i = 0; i < rp->n; i++)
        if (!strcmp(rp->kind[i], "speed_hw")) print_row(f, &rp->rows[i]);

    fprintf(f, "Claims of the factorization paper: Ward (isotropic) factorized at 32x32, as `shadesim factor\n"
               "ward --claims --scene %s --scene-res %d` measures them\n\n", TB_FACTOR_CLAIMS_SCENE,
            TB_FACTOR_CLAIMS_RES);
    for (size_t i = 0; i < rp->n; i++)
        if (!strcmp(rp->kind[i], "factor")) print_row(f, &rp->rows[i]);

    fprintf(f, "Claims on the face scene (%dx%d) through the simulated hardware path\n\n", TB_SCENE_CLAIMS_RES,
            TB_SCENE_CLAIMS_RES);
    for (size_t i = 0; i < rp->n; i++)
        if (!strcmp(rp->kind[i], "scene")) print_row(f, &rp->rows[i]);

    fputs("Speed on a CPU (float code) depends on the machine, compiler and libm: `make bench`\n"
          "times it (bench/bench_claims); it is not part of these verdicts.\n\n", f);

    fputs("Failure regions: relative error above 10% where the exact value is above 1% of its peak\n", f);
    for (size_t k = 0; k < TB_CLAIMS_NAPPROX; k++) {
        const tb_claims_approx *a = &tb_claims_approx_tab[k];
        const tb_claims_bands *b = &rp->fb[k];
        fprintf(f, "  %-12s %s = %-4g worst %7.3g%%  ", a->name, a->pname, a->p, 100 * b->worst);
        if (!b->n) fputs("no failure", f);
        for (int j = 0; j < b->n; j++) fprintf(f, "%s%.2f..%.2f deg", j ? ", " : "fails at ", b->lo[j], b->hi[j]);
        fputc('\n', f);
    }

    int nh = 0, no = 0, nf = 0;
    for (size_t i = 0; i < rp->n; i++) {
        int k = claims_verdict_kind(rp->rows[i].verdict);
        nh += k == 1; no += k == 0; nf += k == -1;
    }
    fprintf(f, "\n%zu claims: %d hold, %d hold only under a condition, %d do not hold\n", rp->n, nh, no, nf);
    for (int i = 0; i < np; i++) fprintf(f, "wrote %s\n", paths[i]);
}

static void json_row(FILE *f, const claim_result *r, const char *kind)
{
    fputs("    {\"id\": ", f); base_json_str(f, r->id);
    fputs(", \"kind\": ", f); base_json_str(f, kind);
    fputs(", \"source\": ", f); base_json_str(f, r->source);
    fputs(",\n     \"claim\": ", f); base_json_str(f, r->claim);
    fputs(",\n     \"claimed\": ", f); base_json_num(f, r->claimed, 10);
    fputs(", \"measured\": ", f); base_json_num(f, r->measured, 10);
    fputs(", \"verdict\": ", f); base_json_str(f, r->verdict);
    fputs(",\n     \"measured_text\": ", f); base_json_str(f, r->measured_text);
    fputs(",\n     \"note\": ", f); base_json_str(f, r->note);
    fputs("}", f);
}

static void json_hw(FILE *f, const char *name, double cl, double ar, double pd, int n, int last)
{
    fputs("      ", f); base_json_str(f, name);
    fputs(": {\"clocks_per_item\": ", f); base_json_num(f, cl, 10);
    fputs(", \"area_ge\": ", f); base_json_num(f, ar, 10);
    fputs(", \"period_ps\": ", f); base_json_num(f, pd, 10);
    fputs(", \"ns_per_item\": ", f); base_json_num(f, cl * pd / 1e3, 10);
    if (n) fprintf(f, ", \"n\": %d", n);
    fprintf(f, "}%s\n", last ? "" : ",");
}

static void print_json(FILE *f, const report *rp, char paths[][600], int np)
{
    fputs("{\n  \"claims\": [\n", f);
    for (size_t i = 0; i < rp->n; i++) {
        json_row(f, &rp->rows[i], rp->kind[i]);
        fputs(i + 1 < rp->n ? ",\n" : "\n", f);
    }
    const tb_speed_hw *h = &rp->hc;
    fprintf(f, "  ],\n  \"hardware\": {\n    \"width\": %d,\n    \"units\": {\n", h->width);
    json_hw(f, "d_approx", h->d16.clocks, h->d16.area, h->d16.period_ps, 0, 0);
    json_hw(f, "ward_approx", h->ward16.clocks, h->ward16.area, h->ward16.period_ps, 0, 0);
    json_hw(f, "powg_g2", h->sq.clocks, h->sq.area, h->sq.period_ps, 0, 0);
    json_hw(f, "div", h->div.clocks, h->div.area, h->div.period_ps, 0, 0);
    json_hw(f, "pow_n_cos_power_d", h->pow_d.clocks, h->pow_d.area, h->pow_d.period_ps, h->n_d, 0);
    json_hw(f, "pow_n_cos_power_ward", h->pow_w.clocks, h->pow_w.area, h->pow_w.period_ps, h->n_w, 0);
    json_hw(f, "exact_d_without_exp", h->exact_d_clocks, h->exact_d_area, h->exact_d_period_ps, 0, 0);
    json_hw(f, "ward_exp_term_without_exp", h->exact_w_clocks, h->exact_w_area, h->exact_w_period_ps, 0, 1);
    char nb[200];
    no_bound(h, nb, sizeof nb, "\"");
    fprintf(f, "    },\n    \"no_bound\": [%s],\n    \"model\": ", nb);
    base_json_str(f, "built units, time per item = clocks x the critical path of each design (a chain: its "
            "slowest stage's): Ward's exp term = squarer and divider wired into one design and simulated; exact D = "
            "that design, then a squarer and a divider each simulated alone; the exponential (no unit) not counted: "
            "lower bounds");
    fputs("\n  },\n  \"failure_regions\": [\n", f);
    for (size_t k = 0; k < TB_CLAIMS_NAPPROX; k++) {
        const tb_claims_approx *a = &tb_claims_approx_tab[k];
        const tb_claims_bands *b = &rp->fb[k];
        fputs("    {\"approximation\": ", f); base_json_str(f, a->name);
        fputs(", \"param\": ", f); base_json_str(f, a->pname);
        fputs(", \"value\": ", f); base_json_num(f, a->p, 10);
        fputs(", \"worst_rel_err\": ", f); base_json_num(f, b->worst, 10);
        fputs(", \"fails_deg\": [", f);
        for (int j = 0; j < b->n; j++) {
            fprintf(f, "%s[", j ? ", " : "");
            base_json_num(f, b->lo[j], 10); fputs(", ", f); base_json_num(f, b->hi[j], 10);
            fputs("]", f);
        }
        fprintf(f, "]}%s\n", k + 1 < TB_CLAIMS_NAPPROX ? "," : "");
    }
    fputs("  ],\n  \"charts\": [", f);
    for (int i = 0; i < np; i++) { fputs(i ? ", " : "", f); base_json_str(f, paths[i]); }
    fputs("]\n}\n", f);
}

/* ------------------------------------------------------------------ verb */

typedef struct claims_args { int json, width; const char *dir; } claims_args;

static int o_cpu_seconds(void *base, const char *opt, const char *v)
{
    (void)base, (void)opt, (void)v;
    return cli_usage_error("claims: --cpu-seconds is gone: CPU timings are machine-dependent and not "
                           "verdicts; make bench times them (bench/bench_claims)");
}

static const cli_opt claims_tab[] = {
    { "--json", NULL, CLI_OPT_FLAG, offsetof(claims_args, json), 0, 0, NULL, NULL, NULL, 0,
      "  --json               one JSON object instead of text\n" },
    { "-o", NULL, CLI_OPT_STR, offsetof(claims_args, dir), 0, 0, NULL, "claims: -o needs a folder", NULL, CLI_OPT_NONEMPTY,
      "  -o DIR               also write the charts into DIR (made if missing):\n"
      "                       claims_d16.svg, claims_ward.svg, claims_schlick.svg\n"
      "                       (error against angle, failure regions shaded),\n"
      "                       claims_d16_clamp.svg (why d_approx clamps its base) and\n"
      "                       claims_cost.svg (time x area against error, our units)\n" },
    { "--width", NULL, CLI_OPT_INT, offsetof(claims_args, width), 4, 48, NULL, "claims: --width needs a whole number 4..48",
      NULL, 0,
      "  --width W            width of the hardware units for the speed and cost\n"
      "                       figures (default 16)\n" },
    { "--cpu-seconds", NULL, CLI_OPT_CALL0, 0, 0, 0, NULL, NULL, o_cpu_seconds, CLI_OPT_HIDDEN, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_claims_spec = {
    "claims", { claims_tab }, NULL, 0, "claims: unknown argument '%s' (see shadesim claims --help)",
    "usage: shadesim claims [--json] [-o DIR] [--width W]\n\n"
    "Prints each numerical claim of the papers (docs/references.md) beside what the\n"
    "double-precision references measure, and a verdict: holds, holds only for\n"
    "<condition>, or does not hold. Then the papers' speed claims (D16 4.34x faster\n"
    "than D, the Ward approximation more than 2x), measured as clocks and area of\n"
    "our hardware units against chains of our units computing the exact functions\n"
    "(their exponential, which has no unit, left out). Last, where\n"
    "each approximation fails: relative error above 10% where the exact value is\n"
    "above 1% of its peak. The factorization paper's claims are those of\n"
    "`shadesim factor ward --claims --scene sphere --scene-res 256`.\n"
    "The face scene's claims (NMSE against per-pixel Phong,\n"
    "operation-count speed-up) are measured at 256x256 through the simulated\n"
    "span hardware. The output is the same bytes on every run and machine;\n"
    "CPU timings of the float kernels are machine-dependent and live in `make\n"
    "bench` (bench/bench_claims), not in these verdicts.\n\noptions:\n",
    "\nexit status: 0 done (a claim that does not hold is a finding, not an error),\n"
    "2 bad usage or an unwritable DIR\n"
};

int cli_claims(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_claims_spec);
    claims_args ca = { 0, 16, NULL };
    void *base[] = { &ca };
    if (cli_opt_parse(&cli_claims_spec, base, argc, argv, 1)) return CLI_USAGE;
    int json = ca.json, width = ca.width;
    const char *dir = ca.dir;

    report *rp = calloc(1, sizeof *rp);
    if (!rp) base_out_of_memory();
    char serr[300];
    rp->n = tb_claims_table(rp->rows, rp->kind, width, &rp->hc, serr, sizeof serr);
    if (!rp->n) { free(rp); return cli_usage_error("claims: %s", serr); }
    for (size_t k = 0; k < TB_CLAIMS_NAPPROX; k++) tb_claims_failure_bands(&tb_claims_approx_tab[k], &rp->fb[k]);

    char paths[8][600];
    int np = 0, rc = CLI_OK;
    if (dir) rc = write_charts(dir, paths, &np);
    if (rc == CLI_OK) {
        if (json) print_json(stdout, rp, paths, np);
        else print_text(stdout, rp, paths, np);
        /* fflush alone misses an error whose write happened earlier. */
        char e[300];
        if (base_out_stdout_check(e, sizeof e)) rc = cli_usage_error("claims: %s", e);
    }
    free(rp);
    return rc;
}
