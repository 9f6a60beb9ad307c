/* cli_report.c - the verb report: one HTML page with what the simulator
 * says about every unit, the papers' claims with verdicts, two sweeps'
 * charts, the face scene and a waveform of one unit.
 *
 * The page is self-contained: inline CSS, the charts and images embedded
 * as data: URIs (<img>, so that any HTML parser reads the page, not only
 * an HTML5 one), no script. The files it was made from sit beside it in
 * DIR (sweep CSVs, the scene's PNGs and JSON, a VCD with its GTKWave save
 * file) and are linked. Same inputs, same bytes: no dates, no timings.
 *
 * The figures come from the functions the other verbs use: tb_run and
 * tb_verdict (as run all), tb_claims_table (claims), tb_sweep and
 * tb_sweep_chart (sweep, chart), tb_scene_render (scene).
 */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include <stddef.h>
#include "testbench/study/tb_scene.h"
#include "testbench/study/tb_sweep.h"
#include "testbench/study/tb_sweep_chart.h"
#include "testbench/study/tb_stability.h"
#include "testbench/study/tb_claims.h"
#include "testbench/study/tb_ref_claims.h"
#include "base/base_out.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct report_args { const char *dir; } report_args;

static const cli_opt report_tab[] = {
    { "-o", NULL, CLI_OPT_STR, offsetof(report_args, dir), 0, 0, NULL, "report: -o needs a folder", NULL, CLI_OPT_NONEMPTY,
      "  -o DIR               output folder, made if missing (default out/report)\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_report_spec = {
    "report", { report_tab }, NULL, 0, "report: unexpected argument '%s' (see shadesim report --help)",
    "usage: shadesim report [-o DIR]\n\n"
    "Writes DIR/report.html (default DIR: out/report), one page that any browser\n"
    "shows without scripts or network:\n"
    "  - every unit on its default vectors: clocks, area, error, bound and verdict\n"
    "    (what `shadesim run all` prints);\n"
    "  - the papers' numerical claims with our measurement and a verdict (what\n"
    "    `shadesim claims` prints);\n"
    "  - two sweeps' charts (horner3 over widths; interp3 over schedules and the\n"
    "    divide-by-3 network's terms), as `shadesim sweep` draws them;\n"
    "  - the built-in face scene at 128x128 through the simulated span hardware:\n"
    "    reference, hardware, error, degree and region images and the figures;\n"
    "  - where each method stops working (what `shadesim stability` prints), with\n"
    "    its charts;\n"
    "  - a waveform of horner3 (VCD and GTKWave save file) to open in GTKWave.\n"
    "Beside the page in DIR: sweep-horner3.csv, sweep-interp3.csv, scene/ and\n"
    "horner3.vcd with horner3.vcd.gtkw. The page embeds its charts and images,\n"
    "so report.html alone can be mailed or archived. The same inputs give the\n"
    "same bytes.\n\n"
    "options:\n",
    "\nexit status: 0 written (a unit that fails its verdict is reported on the\n"
    "page, not an error), 2 bad usage or an unwritable DIR\n"
};


#define SCENE_RES 128

/* ------------------------------------------------------------ utilities */

/* Text for HTML: & < > " escaped. */
static void h(FILE *f, const char *s)
{
    for (; s && *s; s++)
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
}

static void base64(FILE *f, const unsigned char *p, size_t n)
{
    static const char T[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)p[i] << 16 | (i + 1 < n ? (unsigned)p[i + 1] << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
        fputc(T[v >> 18 & 63], f);
        fputc(T[v >> 12 & 63], f);
        fputc(i + 1 < n ? T[v >> 6 & 63] : '=', f);
        fputc(i + 2 < n ? T[v & 63] : '=', f);
    }
}

/* <img> of bytes as a data: URI. */
static void img(FILE *f, const char *mime, const void *p, size_t n, const char *alt, int w, int hgt)
{
    fprintf(f, "<img width=\"%d\" height=\"%d\" alt=\"", w, hgt);
    h(f, alt);
    fprintf(f, "\" src=\"data:%s;base64,", mime);
    base64(f, p, n);
    fputs("\">", f);
}

static unsigned char *read_all(const char *path, size_t *n)
{
    FILE *f = fopen(base_out_pending(path), "rb");    /* written, not yet moved in */
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0;
    unsigned char *b = malloc(cap);
    for (size_t k; b && (k = fread(b + len, 1, cap - len, f)) > 0;) {
        len += k;
        if (len == cap) {
            unsigned char *nb = realloc(b, cap * 2);
            if (!nb) { free(b); b = NULL; break; }
            b = nb;
            cap *= 2;
        }
    }
    fclose(f);
    *n = len;
    return b;
}

static void progress(const char *what)
{
    if (cli_stderr_tty()) fprintf(stderr, "\rshadesim report: %-40s\r", what);
}

/* ---------------------------------------------------------------- style */

static const char css[] =
    "body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,'DejaVu Sans',sans-serif;color:#222;"
    "max-width:1180px;margin:0 auto;padding:16px 24px 48px;line-height:1.45;background:#fff}\n"
    "h1{font-size:1.7em;margin:0.4em 0 0.2em}h2{font-size:1.3em;margin:1.6em 0 0.4em;border-bottom:2px solid #ddd;"
    "padding-bottom:0.15em}h3{font-size:1.08em;margin:1.2em 0 0.3em}\n"
    "p{margin:0.4em 0 0.7em}code{font-family:'DejaVu Sans Mono',monospace;font-size:0.92em;background:#f3f3f3;"
    "padding:0 3px;border-radius:3px}\n"
    "div.toc ul{margin:0.2em 0;padding-left:1.2em}\n"
    "table{border-collapse:collapse;margin:0.5em 0 1em;font-size:0.9em}\n"
    "th,td{border:1px solid #d4d4d4;padding:3px 7px;vertical-align:top}\n"
    "th{background:#eef1f5;text-align:left;font-weight:600}\n"
    "tr:nth-child(even) td{background:#fafafa}\n"
    "td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}\n"
    "td.id{white-space:nowrap;font-family:'DejaVu Sans Mono',monospace;font-size:0.92em}\n"
    ".ok{color:#0a5d1c;font-weight:600}.bad{color:#a40000;font-weight:600}.cond{color:#8a4b00;font-weight:600}\n"
    "td.v-ok{background:#e3f4e6 !important}td.v-bad{background:#fbe1e1 !important}td.v-cond{background:#fdf0dc !important}\n"
    ".note{color:#555;font-size:0.92em;margin-top:2px}\n"
    ".charts img,.scene img{border:1px solid #ddd;max-width:100%;height:auto;margin:4px 8px 8px 0}\n"
    ".scene div.fig{display:inline-block;margin:0 12px 10px 0;text-align:center;vertical-align:top;width:212px}\n"
    ".scene img{image-rendering:pixelated;width:210px;height:210px}\n"
    ".scene div.cap{font-size:0.88em;color:#444}\n"
    ".summary{background:#f5f7fa;border-left:4px solid #8aa4c8;padding:6px 10px}\n";

/* ---------------------------------------------------------------- units */

static int section_units(FILE *f, int *nfail)
{
    fputs("<h2 id=\"units\">Units on their default vectors</h2>\n"
          "<p>Each unit driven clock by clock with its checked-in golden vectors at its default formats "
          "(<code>--width 16</code> rule), as <code>shadesim run all</code> does. <em>bound</em>: every output "
          "within the error bound derived from its formats, checked against the unit's ideal function of the "
          "quantized inputs; <em>golden</em>: within that bound plus input rounding and the method's own "
          "approximation of the true function; <em>method error</em>: how far the unit's ideal is from the true "
          "function. Clocks per pixel are clocks per output beat: an interpolation unit's item is L pixels.</p>\n"
          "<table>\n<tr><th>unit</th><th>schedule</th><th>width</th><th>clocks / item</th><th>clocks / pixel</th>"
          "<th>latency</th><th>area (GE)</th><th>max |e|</th><th>NMSE</th><th>method error</th><th>overflows</th>"
          "<th>bound</th><th>golden</th><th>verdict</th></tr>\n", f);
    *nfail = 0;
    int n = 0;
    for (size_t i = 0, nu = unit_count(); i < nu; i++) {
        cli_unit_opts o;
        cli_unit_select(&o, unit_at(i)->name);
        progress(o.u->name);
        vec_set vs;
        if (cli_load_vectors(&o, &vs)) return CLI_USAGE;
        unit_fmts fm;
        char err[600];
        tb_result r;
        memset(&r, 0, sizeof r);
        int t = tb_formats(o.u, &o.cfg, NULL, 0, &fm, err, sizeof err) ? TB_BADINPUT
              : tb_run(o.u, &o.cfg, &fm, &vs, NULL, &r, err, sizeof err);
        fprintf(f, "<tr id=\"unit-%s\"><td class=\"id\">%s</td><td>%s</td><td class=\"n\">%d</td>", o.u->name,
                o.u->name, o.u->sched[o.cfg.schedule].name, o.cfg.width);
        if (t != TB_OK) {
            fputs("<td colspan=\"10\">simulation failed: ", f);
            h(f, err);
            fputs("</td><td class=\"v-bad\"><span class=\"bad\">FAIL</span></td></tr>\n", f);
            ++*nfail;
        } else {
            tb_verdict(&r, NULL);
            double me = 0;
            for (int k = 0; k < r.n_out; k++) if (r.out[k].max_method_err > me) me = r.out[k].max_method_err;
            const char *bc = r.overflows ? "overflow" : tb_check_name(r.bound_check);
            fprintf(f, "<td class=\"n\">%.4g</td><td class=\"n\">%.4g</td><td class=\"n\">%llu</td><td class=\"n\">%.1f</td>"
                       "<td class=\"n\">%.4g</td><td class=\"n\">%.4g</td><td class=\"n\">%.3g</td><td class=\"n\">%llu</td>",
                    r.cycles_per_item, r.cycles_per_beat, (unsigned long long)r.latency, r.area_ge, r.max_abs_err,
                    r.nmse, me, (unsigned long long)r.overflows);
            fprintf(f, "<td class=\"%s\">%s</td><td class=\"%s\">%s</td>",
                    !r.overflows && r.bound_check == TB_CHECK_OK ? "v-ok" : "v-bad", bc,
                    r.golden_ok ? "v-ok" : "v-bad", r.golden_ok ? "ok" : "exceeded");
            fprintf(f, "<td class=\"%s\"><span class=\"%s\">%s</span>", r.ok ? "v-ok" : "v-bad", r.ok ? "ok" : "bad",
                    r.ok ? "ok" : "FAIL");
            if (!r.ok) { fputs("<div class=\"note\">", f); h(f, r.why); fputs("</div>", f); }
            fputs("</td></tr>\n", f);
            if (!r.ok) ++*nfail;
        }
        n++;
        tb_result_free(&r);
        vec_set_free(&vs);
    }
    fputs("</table>\n", f);
    fprintf(f, "<p class=\"summary\">%d units: %d with verdict ok, %d failing. Rerun: <code>shadesim run all</code>; "
               "one unit in detail: <code>shadesim run UNIT</code>.</p>\n", n, n - *nfail, *nfail);
    return CLI_OK;
}

/* --------------------------------------------------------------- claims */

static int section_claims(FILE *f)
{
    claim_result *rows = calloc(CLAIMS_MAX, sizeof *rows);
    const char *kind[CLAIMS_MAX];
    char err[400];
    if (!rows) base_out_of_memory();
    progress("claims");
    size_t n = tb_claims_table(rows, kind, 16, NULL, err, sizeof err);
    if (!n) { free(rows); return cli_usage_error("report: claims: %s", err); }
    int nh = 0, no = 0, nf = 0;
    for (size_t i = 0; i < n; i++) {
        int k = claims_verdict_kind(rows[i].verdict);
        nh += k == 1; no += k == 0; nf += k == -1;
    }
    fputs("<h2 id=\"claims\">The papers' claims</h2>\n"
          "<p>Each numerical claim of the papers beside what we measure, with a verdict: <span class=\"ok\">holds</span>, "
          "<span class=\"cond\">holds only for</span> a condition, or <span class=\"bad\">does not hold</span>. "
          "Accuracy claims are measured on the double-precision references; speed claims as clocks and area of our "
          "hardware units (width 16) against chains of our units for the exact functions (their exponential left out); "
          "the factorization paper's as <code>shadesim factor ward --claims</code> measures them; the face scene's claims through the "
          "simulated span hardware at 256x256. Rerun: <code>shadesim claims</code> (<code>--json</code> for the same "
          "rows as data).</p>\n", f);
    fprintf(f, "<p class=\"summary\">%zu claims: %d hold, %d hold only under a condition, %d do not hold.</p>\n", n, nh, no, nf);
    fputs("<table>\n<tr><th>id</th><th>kind</th><th>where</th><th>claim</th><th>paper</th><th>measured</th><th>verdict</th></tr>\n", f);
    for (size_t i = 0; i < n; i++) {
        const claim_result *r = &rows[i];
        int k = claims_verdict_kind(r->verdict);
        fprintf(f, "<tr id=\"claim-%s\"><td class=\"id\">", r->id);
        h(f, r->id);
        fprintf(f, "</td><td>%s</td><td>", kind[i]);
        h(f, r->source);
        fputs("</td><td>", f);
        h(f, r->claim);
        fputs("<div class=\"note\">", f);
        h(f, r->note);
        fputs("</div></td><td class=\"n\">", f);
        if (isfinite(r->claimed)) fprintf(f, "%g", r->claimed);
        else fputs("&mdash;", f);
        fprintf(f, "</td><td><span class=\"n\">%.4g</span><div class=\"note\">", r->measured);
        h(f, r->measured_text);
        fprintf(f, "</div></td><td class=\"%s\"><span class=\"%s\">", k == 1 ? "v-ok" : k == 0 ? "v-cond" : "v-bad",
                k == 1 ? "ok" : k == 0 ? "cond" : "bad");
        h(f, r->verdict);
        fputs("</span></td></tr>\n", f);
    }
    fputs("</table>\n", f);
    free(rows);
    return CLI_OK;
}

/* --------------------------------------------------------------- sweeps */

typedef struct sweep_def {
    const char *unit, *cmd, *what;
    int wlo, whi;
    const char *sched;          /* comma list or NULL */
    const char *param;          /* "name=v1,v2" or NULL */
} sweep_def;

static const sweep_def SWEEPS[] = {
    { "horner3", "shadesim sweep horner3 --widths 8:20",
      "The cubic Horner datapath over the width of its default-format rule: error falls by about half a bit "
      "per bit of width until the coefficients' own rounding dominates; area grows with it.", 8, 20, NULL, NULL },
    { "interp3", "shadesim sweep interp3 --widths 10:16 --schedule paper,mac,pipe --param terms=2,3,4,6",
      "Cubic span interpolation over width, schedule and the terms of the divide-by-3 network. The schedules "
      "compute the same values (one error per width and terms) at different clocks per pixel and area, so the "
      "Pareto front over error, area and clocks per pixel keeps the fast pipelined schedule as well as the small one.",
      10, 16, "paper,mac,pipe", "terms=2,3,4,6" },
};

/* Split "a,b,c" into items[][32]; returns the count. */
static int split(const char *s, char items[][32], int cap)
{
    int n = 0;
    while (s && *s && n < cap) {
        size_t k = strcspn(s, ",");
        snprintf(items[n++], 32, "%.*s", (int)k, s);
        s += k + (s[k] == ',');
    }
    return n;
}

static int run_sweep(const sweep_def *d, const char *dir, FILE *f)
{
    cli_unit_opts o;
    if (cli_unit_select(&o, d->unit)) return CLI_USAGE;
    tb_sweep_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.u = o.u;
    sp.base = o.cfg;
    sp.wlo = d->wlo;
    sp.whi = d->whi;
    char items[TB_SWEEP_MAX_VALUES][32];
    sp.nsched = 1;
    sp.sched[0] = o.cfg.schedule;
    if (d->sched) {
        sp.nsched = split(d->sched, items, UNIT_MAX_SCHED);
        for (int k = 0; k < sp.nsched; k++) sp.sched[k] = unit_sched_find(o.u, items[k]);
    }
    sp.nrnd = 1; sp.rnd[0] = o.cfg.rnd;
    sp.novf = 1; sp.ovf[0] = o.cfg.ovf;
    if (d->param) {
        const char *eq = strchr(d->param, '=');
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)(eq - d->param), d->param);
        tb_sweep_paxis *ax = &sp.pax[sp.npax++];
        ax->param = -1;
        for (int k = 0; k < o.u->nparams; k++) if (!strcmp(o.u->params[k].name, name)) ax->param = k;
        ax->n = split(eq + 1, ax->val, TB_SWEEP_MAX_VALUES);
    }
    tb_sweep s;
    char err[600];
    if (tb_sweep_init(&s, &sp, err, sizeof err)) return cli_usage_error("report: %s", err);
    vec_set *sets = calloc(s.npsets, sizeof *sets);
    int rc = CLI_OK;
    if (!sets) base_out_of_memory();
    size_t loaded = 0;
    for (; loaded < s.npsets; loaded++) {
        cli_unit_opts po = o;
        po.cfg = *tb_sweep_pset_cfg(&s, loaded);
        if (cli_load_vectors(&po, &sets[loaded])) { rc = CLI_USAGE; break; }
        s.vs[loaded] = &sets[loaded];
    }
    char *csv = NULL;
    size_t len = 0;
    tb_sc *sc = NULL;
    if (rc == CLI_OK) {
        char ferr[300];
        (void)tb_sweep_fingerprint(&s, ferr, sizeof ferr);   /* held vectors: nothing to fail */
        tb_sweep_run(&s, 2, 0, 0, NULL, NULL);
        FILE *m = open_memstream(&csv, &len);
        if (!m) base_out_of_memory();
        else {
            tb_sweep_print_csv(&s, m, 0, 0);
            if (fclose(m)) base_out_of_memory();
        }
    }
    char path[4200], name[64];
    snprintf(name, sizeof name, "sweep-%s.csv", d->unit);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (rc == CLI_OK && base_out_write_all(path, csv, len, err, sizeof err)) rc = cli_usage_error("%s", err);
    if (rc == CLI_OK && !(sc = tb_sc_read(csv, len, name, err, sizeof err))) rc = cli_usage_error("report: %s", err);
    if (rc == CLI_OK) {
        unsigned char *on = calloc(tb_sc_rows(sc), 1);
        size_t nf = on ? tb_sc_front(sc, on) : 0, nok = 0;
        for (size_t i = 0; i < tb_sc_rows(sc); i++) nok += tb_sc_row_at(sc, i)->ok;
        fprintf(f, "<h3 id=\"sweep-%s\">%s</h3>\n<p>", d->unit, d->unit);
        h(f, d->what);
        fprintf(f, "</p>\n<p>%zu configurations (%zu ran), %zu on the Pareto front. Data: <a href=\"%s\">%s</a>. "
                   "Rerun: <code>", s.n, nok, nf, name, name);
        h(f, d->cmd);
        fprintf(f, "</code>; the same charts from the CSV: <code>shadesim chart %s</code>.</p>\n<div class=\"charts\">\n", name);
        free(on);
        for (int k = 0; k < TB_SC_NCHARTS && rc == CLI_OK; k++) {
            if (!tb_sc_chart_drawn(sc, k)) continue;
            chart *c = tb_sc_chart(sc, k, NULL);
            char *svg = NULL;
            size_t sl = 0;
            FILE *m = open_memstream(&svg, &sl);
            if (!c || !m) base_out_of_memory();
            if (chart_fwrite(c, m, tb_sc_chart_file[k], err, sizeof err)) rc = cli_usage_error("report: %s", err);
            if (fclose(m)) base_out_of_memory();
            if (rc == CLI_OK) {
                char alt[128];
                snprintf(alt, sizeof alt, "%s: %s", d->unit, tb_sc_chart_file[k]);
                img(f, "image/svg+xml", svg, sl, alt, 800, 500);
                fputc('\n', f);
            }
            free(svg);
            chart_free(c);
        }
        fputs("</div>\n", f);
    }
    tb_sc_free(sc);
    free(csv);
    for (size_t p = 0; p < loaded; p++) vec_set_free(&sets[p]);
    free(sets);
    tb_sweep_free(&s);
    return rc;
}

static int section_sweeps(FILE *f, const char *dir)
{
    fputs("<h2 id=\"sweeps\">Sweeps</h2>\n"
          "<p>A unit run over a grid of widths and settings. <em>Error against width</em>: max |e| (solid) and RMS "
          "error (dashed) against the float reference. <em>Area against max error</em> and <em>clocks per pixel "
          "against max error</em>: every configuration, the Pareto front ringed (no other configuration is at least as "
          "good in max error, area and clocks per pixel and better in one), a few front points labelled with their "
          "width.</p>\n", f);
    for (size_t i = 0; i < sizeof SWEEPS / sizeof SWEEPS[0]; i++) {
        progress(SWEEPS[i].cmd);
        int rc = run_sweep(&SWEEPS[i], dir, f);
        if (rc) return rc;
    }
    return CLI_OK;
}

/* ---------------------------------------------------------------- scene */

/* The same face under other settings: what the divide-by-3 network's
 * terms and the degree policy change. */
static int scene_compare(FILE *f)
{
    static const struct { const char *policy, *terms; } cf[] = {
        { NULL, NULL }, { NULL, "5" }, { "adaptive-region", NULL }, { "adaptive-region", "5" }, { "adaptive-auto", "5" },
    };
    scn_desc d0;
    scn_mesh m;
    char err[600];
    memset(&m, 0, sizeof m);
    if (scn_desc_builtin("face", &d0)) return cli_usage_error("report: no built-in face scene");
    d0.width = d0.height = SCENE_RES;
    if (scn_mesh_builtin(d0.mesh, d0.detail, &m, err, sizeof err)) return cli_usage_error("report: %s", err);
    fprintf(f, "<h3>Other settings</h3>\n<p>The same face at %dx%d with other settings (rerun each with "
               "<code>shadesim scene face --set resolution=%dx%d --set KEY=VALUE ...</code>):</p>\n<table>\n"
               "<tr><th>settings</th><th>policy</th><th>terms</th><th>NMSE</th><th>PSNR (dB)</th><th>max 8-bit error</th>"
               "<th>degree 2</th><th>clocks / pixel</th><th>area (GE)</th><th>speed-up</th></tr>\n",
            SCENE_RES, SCENE_RES, SCENE_RES, SCENE_RES);
    int rc = CLI_OK;
    for (size_t k = 0; k < sizeof cf / sizeof cf[0] && rc == CLI_OK; k++) {
        scn_desc d = d0;
        if ((cf[k].policy && scn_desc_set(&d, "policy", cf[k].policy, err, sizeof err)) ||
            (cf[k].terms && scn_desc_set(&d, "terms", cf[k].terms, err, sizeof err))) {
            rc = cli_usage_error("report: %s", err);
            break;
        }
        tb_scene_opts o = { 2, 0, NULL, NULL, 0, 0, NULL, NULL };
        tb_scene_result r;
        memset(&r, 0, sizeof r);
        int t = tb_scene_render(&d, &m, &o, &r, err, sizeof err);
        if (t != TB_OK) rc = cli_from_tb(t, "report: face scene: %s", err);
        else {
            char set[120] = "";
            if (cf[k].policy) snprintf(set, sizeof set, "--set policy=%s", cf[k].policy);
            if (cf[k].terms) snprintf(set + strlen(set), sizeof set - strlen(set), "%s--set terms=%s", *set ? " " : "", cf[k].terms);
            fprintf(f, "<tr><td>%s%s%s</td><td>%s</td><td class=\"n\">%d</td><td class=\"n\">%.3g</td>"
                       "<td class=\"n\">%.2f</td><td class=\"n\">%d</td><td class=\"n\">%.0f%%</td><td class=\"n\">%.3g</td>"
                       "<td class=\"n\">%.0f</td><td class=\"n\">%.2fx</td></tr>\n",
                    *set ? "<code>" : "", *set ? set : "as above", *set ? "</code>" : "", scn_policy_name(d.policy),
                    r.cfg.terms, r.nmse, r.psnr, r.max_err8, 100 * r.deg2_share, r.clocks_per_pixel, r.hwst.area_ge, r.speedup);
        }
        tb_scene_free(&r);
    }
    scn_mesh_free(&m);
    fputs("</table>\n", f);
    return rc;
}

static int section_scene(FILE *f, const char *dir)
{
    scn_desc d;
    scn_mesh m;
    tb_scene_result r;
    char err[600], sdir[4200];
    memset(&m, 0, sizeof m);
    memset(&r, 0, sizeof r);
    progress("face scene");
    if (scn_desc_builtin("face", &d)) return cli_usage_error("report: no built-in face scene");
    d.width = d.height = SCENE_RES;
    if (scn_mesh_builtin(d.mesh, d.detail, &m, err, sizeof err)) return cli_usage_error("report: %s", err);
    tb_scene_opts o = { 2, 0, NULL, NULL, 0, 0, NULL, NULL };
    int rc = tb_scene_render(&d, &m, &o, &r, err, sizeof err);
    scn_mesh_free(&m);
    if (rc != TB_OK) { tb_scene_free(&r); return cli_from_tb(rc, "report: face scene: %s", err); }
    snprintf(sdir, sizeof sdir, "%s/scene", dir);
    if (tb_scene_write(&d, &r, sdir, err, sizeof err)) { tb_scene_free(&r); return cli_usage_error("%s", err); }
    fprintf(f, "<h2 id=\"scene\">The face scene through the hardware</h2>\n"
               "<p>The built-in face at %dx%d: each span cut into intervals of L = %d pixels, the nodes shaded exactly, "
               "every pixel between them interpolated by the cycle-accurate %s unit (%s policy, %d-term divide-by-3 "
               "network, width %d), against per-pixel shading in double precision. Rerun: "
               "<code>shadesim scene face --set resolution=%dx%d -o scene</code>. Files: <a href=\"scene/scene.json\">"
               "scene/scene.json</a> and the PNGs in <code>scene/</code>.</p>\n",
            r.w, r.h, r.cfg.L, r.unit ? r.unit->name : "span", scn_policy_name(d.policy), r.cfg.terms, r.cfg.width, r.w,
            r.h);
    fputs("<div class=\"scene\">\n", f);
    int K = tb_scene_err_scale(&r);
    char errname[32], errcap[160];
    snprintf(errname, sizeof errname, "err-x%d.png", K);
    snprintf(errcap, sizeof errcap, "|error| x %d: black 0, blue 0.25/%d, red 0.5/%d, yellow 0.75/%d, "
             "white 1/%d or more", K, K, K, K, K);
    const char *files[5] = { "ref.png", "hw.png", errname, "degree.png", "region.png" };
    /* the colours are scn_label_rgb's (scene.json's "legend" lists them) */
    const char *caps[5] = { "reference (per-pixel, double)", "hardware (interpolated)", errcap,
                            "degree per interval: red 1, green 2, yellow 3",
                            "face regions: grey rest, red brows, green forehead, yellow eyes, blue cheeks, "
                            "orange nose, purple lips, cyan chin" };
    for (int k = 0; k < 5; k++) {
        char p[4300];
        size_t n = 0;
        snprintf(p, sizeof p, "%s/%s", sdir, files[k]);
        unsigned char *b = read_all(p, &n);
        if (!b) { tb_scene_free(&r); return cli_usage_error("%s: cannot read back: %s", p, strerror(errno)); }
        fputs("<div class=\"fig\">", f);
        img(f, "image/png", b, n, caps[k], 210, 210);
        fputs("<div class=\"cap\">", f);
        h(f, caps[k]);
        fprintf(f, " &middot; <a href=\"scene/%s\">%s</a></div></div>\n", files[k], files[k]);
        free(b);
    }
    fputs("</div>\n<table>\n<tr><th>figure</th><th>value</th><th>what</th></tr>\n", f);
    fprintf(f, "<tr><td>NMSE</td><td class=\"n\">%.4g</td><td>sum (hw - ref)^2 / sum ref^2 over the %zu covered pixels</td></tr>\n",
            r.nmse, r.covered);
    fprintf(f, "<tr><td>PSNR</td><td class=\"n\">%.2f dB</td><td>on 8-bit values</td></tr>\n", r.psnr);
    fprintf(f, "<tr><td>max |e|</td><td class=\"n\">%.4g</td><td>largest intensity error; %d in 8-bit values, "
               "%.1f%% of pixels differ in 8 bits</td></tr>\n", r.max_abs_err, r.max_err8, 100 * r.diff8_share);
    fprintf(f, "<tr><td>clocks per pixel</td><td class=\"n\">%.3g</td><td>of the span unit, %zu spans, %zu intervals "
               "(%.0f%% of degree 2)</td></tr>\n", r.clocks_per_pixel, r.spans, r.intervals, 100 * r.deg2_share);
    fprintf(f, "<tr><td>area</td><td class=\"n\">%.0f GE</td><td>gate equivalents of the instantiated unit</td></tr>\n",
            r.hwst.area_ge);
    fprintf(f, "<tr><td>speed-up</td><td class=\"n\">%.2fx</td><td>weighted operations of per-pixel shading over the "
               "method's (%.4g / %.4g per pixel)</td></tr>\n", r.speedup, r.cost_ref, r.cost_hw);
    fprintf(f, "<tr><td>speed-up, long ops</td><td class=\"n\">%.2fx</td><td>divides, square roots and powers alone "
               "(%.4g / %.4g per pixel)</td></tr>\n</table>\n", r.speedup_long, r.long_ref, r.long_hw);
    tb_scene_free(&r);
    return scene_compare(f);
}

/* ------------------------------------------------------------ stability */

/* The stability atlas (testbench/study/tb_stability.c): every failure boundary
 * as a table row, and its charts with the boundaries marked. */
static int section_stability(FILE *f)
{
    tb_stab *s = calloc(1, sizeof *s);
    char err[400];
    if (!s) base_out_of_memory();
    progress("stability");
    if (tb_stability(s, 1, err, sizeof err)) { tb_stab_free(s); free(s); return cli_usage_error("report: %s", err); }
    fputs("<h2 id=\"stability\">Where each method stops working</h2>\n"
          "<p>Each method driven past its failure boundary, found by running the units clock by clock (the BRDF "
          "rows sample their double references); target 2^-8 unless a row says otherwise. Rerun: "
          "<code>shadesim stability</code> (<code>-o DIR</code> for the charts); docs/stability.md explains "
          "each boundary.</p>\n<table>\n<tr><th>method</th><th>condition</th><th>measured</th><th>verdict</th></tr>\n", f);
    for (int i = 0; i < s->nrows; i++) {
        const tb_stab_row *r = &s->rows[i];
        fprintf(f, "<tr id=\"stab-%s\"><td class=\"id\">", r->id);
        h(f, r->method);
        fputs("</td><td>", f);
        h(f, r->condition);
        fputs("</td><td>", f);
        h(f, r->measured);
        fputs("</td><td>", f);
        h(f, r->verdict);
        fputs("</td></tr>\n", f);
    }
    fputs("</table>\n<div class=\"charts\">\n", f);
    int rc = CLI_OK;
    for (int k = 0; k < s->ncharts && rc == CLI_OK; k++) {
        char *svg = NULL;
        size_t sl = 0;
        FILE *m = open_memstream(&svg, &sl);
        if (!m) base_out_of_memory();
        if (chart_fwrite(s->charts[k], m, s->chart_files[k], err, sizeof err)) rc = cli_usage_error("report: %s", err);
        if (fclose(m)) base_out_of_memory();
        if (rc == CLI_OK) {
            img(f, "image/svg+xml", svg, sl, s->chart_files[k], 800, 500);
            fputc('\n', f);
        }
        free(svg);
    }
    fputs("</div>\n", f);
    tb_stab_free(s);
    free(s);
    return rc;
}

/* ------------------------------------------------------------ waveforms */

static int section_wave(FILE *f, const char *dir)
{
    cli_unit_opts o;
    if (cli_unit_select(&o, "horner3")) return CLI_USAGE;
    progress("horner3 waveform");
    unit_fmts fm;
    vec_set few;
    char err[600], path[4200];
    if (tb_formats(o.u, &o.cfg, NULL, 0, &fm, err, sizeof err)) return cli_usage_error("report: %s", err);
    /* A short dump reads better than the whole vector file: 16 items. */
    if (tb_make_vectors(o.u, &o.cfg, 16, 1, &few, err, sizeof err)) return cli_usage_error("report: %s", err);
    snprintf(path, sizeof path, "%s/horner3.vcd", dir);
    tb_opts to = { .vcd_path = path, .gtkw = 1 };
    tb_result r;
    int t = tb_run(o.u, &o.cfg, &fm, &few, &to, &r, err, sizeof err);
    if (t == TB_OK) tb_verdict(&r, NULL);
    fputs("<h2 id=\"waves\">Waveforms</h2>\n", f);
    if (t != TB_OK) {
        tb_result_free(&r);
        vec_set_free(&few);
        return cli_from_tb(t, "report: %s", err);
    }
    fprintf(f, "<p>horner3 on 16 vectors from its float reference (%llu clocks): every register, multiplexer, adder "
               "and multiplier as a VCD, with a GTKWave save file that groups the unit's signals. "
               "<a href=\"horner3.vcd\">horner3.vcd</a> &middot; <a href=\"horner3.vcd.gtkw\">horner3.vcd.gtkw</a>. "
               "Open with <code>gtkwave horner3.vcd.gtkw</code> in this folder. Rerun: "
               "<code>shadesim run horner3 --vectors FILE --vcd horner3.vcd</code>.</p>\n",
            (unsigned long long)r.cycles);
    tb_result_free(&r);
    vec_set_free(&few);
    return CLI_OK;
}

/* ----------------------------------------------------------------- verb */

int cli_report(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_report_spec);
    report_args ra = { "out/report" };
    void *base[] = { &ra };
    if (cli_opt_parse(&cli_report_spec, base, argc, argv, 1)) return CLI_USAGE;
    const char *dir = ra.dir;
    if (cli_make_dir(dir)) return CLI_USAGE;
    char *html = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&html, &len);
    if (!f) base_out_of_memory();
    /* Every file of the report (sweep CSVs, the scene's images, the page)
     * is one set: they appear together at the end, or none of them. */
    base_outset *set = base_outset_begin();
    if (!set) base_out_of_memory();
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
               "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
               "<title>shadesim report</title>\n<style>\n%s</style>\n</head>\n<body>\n", css);
    fputs("<h1>shadesim report</h1>\n"
          "<p>What the cycle-accurate simulator of the fixed-point shading hardware measures: every unit on its "
          "golden vectors, the papers' numerical claims, sweeps over bit widths and settings, a scene rendered "
          "through the simulated interpolation hardware, and a waveform to open in GTKWave. Made by "
          "<code>shadesim report</code>; every number below comes from a command named beside it, and the same "
          "build gives the same page byte for byte. docs/references.md lists the papers.</p>\n"
          "<div class=\"toc\"><ul><li><a href=\"#units\">Units</a></li><li><a href=\"#claims\">Claims</a></li>"
          "<li><a href=\"#sweeps\">Sweeps</a></li><li><a href=\"#scene\">Face scene</a></li><li><a href=\"#stability\">Stability</a></li>"
          "<li><a href=\"#waves\">Waveforms</a></li></ul></div>\n", f);
    int nfail = 0;
    int rc = section_units(f, &nfail);
    if (!rc) rc = section_claims(f);
    if (!rc) rc = section_sweeps(f, dir);
    if (!rc) rc = section_scene(f, dir);
    if (!rc) rc = section_stability(f);
    if (!rc) rc = section_wave(f, dir);
    fputs("</body>\n</html>\n", f);
    int bad = fclose(f);
    if (cli_stderr_tty()) fprintf(stderr, "\r\033[K");
    if (!rc && bad) base_out_of_memory();
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/report.html", dir);
    if (!rc && base_out_write_all(path, html, len, err, sizeof err)) rc = cli_usage_error("%s", err);
    free(html);
    if (!rc && base_outset_commit(set, err, sizeof err)) rc = cli_usage_error("%s", err);
    else if (rc) base_outset_abort(set);
    if (rc) return rc;          /* (the abort also took back the scene folder it made) */
    printf("wrote %s (%d units, %d failing their verdict)\n", path, (int)unit_count(), nfail);
    char e[300];
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return CLI_OK;
}
