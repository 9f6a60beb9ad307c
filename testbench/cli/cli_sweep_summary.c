/* cli_sweep_summary.c - what a whole sweep writes: the Pareto front, the
 * charts (drawn as `shadesim chart` draws them), the summary table and the
 * acceptance line, saved as one set into the output folder. */
#include "testbench/cli/cli_sweep.h"
#include "chart/chart.h"
#include "base/base_proc.h"
#include "testbench/study/tb_sweep_chart.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* printf spells a NaN "-nan" when its sign bit is set (0/0, inf/inf on
 * x86): the tables print every NaN as "nan", like the CSV. */
static double pnan(double v) { return isnan(v) ? NAN : v; }

static int row_ok(const tb_sweep *s, size_t i) { return s->row[i].status == TB_OK; }

/* Pareto front of the successful rows over max error, area and seconds
 * per pixel at f_max (per output beat: an interpolation unit's item is L
 * pixels), as the charts draw it (tb_sweep_chart.h). */
static unsigned char *front_of(const tb_sweep *s, size_t *nfront)
{
    double *x = malloc(s->n * sizeof *x), *y = malloc(s->n * sizeof *y), *z = malloc(s->n * sizeof *z);
    unsigned char *on = calloc(s->n ? s->n : 1, 1);
    *nfront = 0;
    if (!x || !y || !z || !on) { free(x); free(y); free(z); free(on); return NULL; }
    /* Without timing in some row (as an older CSV without pixels_per_s
     * gives the charts), clocks per pixel stand for the speed. */
    int pps = 1;
    for (size_t i = 0; i < s->n; i++) pps &= !row_ok(s, i) || tb_pixels_per_s(&s->row[i].r) > 0;
    for (size_t i = 0; i < s->n; i++) {
        x[i] = row_ok(s, i) ? s->row[i].r.max_abs_err : NAN;
        y[i] = row_ok(s, i) ? s->row[i].r.area_ge : NAN;
        z[i] = !row_ok(s, i) ? NAN : pps ? 1.0 / tb_pixels_per_s(&s->row[i].r) : s->row[i].r.cycles_per_beat;
    }
    *nfront = chart_pareto3(x, y, z, s->n, on);
    free(x);
    free(y);
    free(z);
    return on;
}

typedef struct fpt { double x, y; size_t i; } fpt;
static int fpt_cmp(const void *a, const void *b)
{
    const fpt *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    return p->i < q->i ? -1 : p->i > q->i;
}

static int write_chart(chart *c, oset *os, const char *name, char *files, size_t flen)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/%s", os->dir, name);
    if (!c) base_out_of_memory();
    FILE *f = sweep_oset_open(os, name);
    int rc = f ? chart_fwrite(c, f, path, err, sizeof err) : 0;
    chart_free(c);
    if (!f) return CLI_USAGE;
    if (rc) return cli_usage_error("%s", err);
    strncat(files, ", ", flen - strlen(files) - 1);
    strncat(files, name, flen - strlen(files) - 1);
    return 0;
}

/* The charts, drawn from the CSV text as `shadesim chart` draws them
 * (tb_sweep_chart.h), so both give the same bytes; the sweep adds the
 * target search's designs. drawn[k]: chart k was drawn. */
static int write_charts(const tb_sweep *s, const target_info *t, oset *os, char *files, size_t flen, int *drawn)
{
    char *text = NULL, err[600];
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (!m) base_out_of_memory();
    tb_sweep_print_csv(s, m, 0, 0);
    if (fclose(m)) base_out_of_memory();
    tb_sc *sc = tb_sc_read(text, len, "sweep.csv", err, sizeof err);
    free(text);
    if (!sc) return cli_usage_error("%s", err);
    double *te = NULL, *ta = NULL;
    tb_sc_target tg = { 0, 0, 0, 0, NULL, NULL };
    if (t->on) {
        te = calloc(s->ngroups, sizeof *te);
        ta = calloc(s->ngroups, sizeof *ta);
        if (!te || !ta) base_out_of_memory();
        tg.on = 1;
        tg.nmse = t->kind == TB_TARGET_NMSE;
        tg.value = t->value;
        for (size_t g = 0; g < s->ngroups; g++)
            if (t->res[g].met) { te[tg.n] = t->res[g].r.max_abs_err; ta[tg.n] = t->res[g].r.area_ge; tg.n++; }
        tg.err = te;
        tg.area = ta;
    }
    int rc = 0;
    for (int k = 0; k < TB_SC_NCHARTS && !rc; k++) {
        drawn[k] = tb_sc_chart_drawn(sc, k);
        if (!drawn[k]) continue;
        rc = write_chart(tb_sc_chart(sc, k, t->on ? &tg : NULL), os, tb_sc_chart_file[k], files, flen);
    }
    free(te);
    free(ta);
    tb_sc_free(sc);
    return rc;
}

/* -------------------------------------------------------------- summary */

static void print_table(FILE *f, const tb_sweep *s, const unsigned char *on)
{
    fprintf(f, "%5s  %-22s %11s %11s %11s %9s %10s %8s %7s %9s %8s %5s %-6s %s\n", "width", "settings", "max|e|",
            "rms e", "nmse", "max LSB", "area GE", "clk/item", "MHz", "Mpx/s", "pJ/px", "ovf", "bound", "front");
    for (size_t i = 0; i < s->n; i++) {
        char gl[200];
        const tb_result *r = &s->row[i].r;
        tb_sweep_group_label(s, s->cfg[i].group, gl, sizeof gl);
        if (!*gl) snprintf(gl, sizeof gl, "-");
        if (!row_ok(s, i)) {
            fprintf(f, "%5d  %-22s %s: %s\n", s->cfg[i].cfg.width, gl,
                    s->row[i].status == TB_BADINPUT ? "not buildable" : "failed", s->row[i].err);
            continue;
        }
        fprintf(f, "%5d  %-22s %11.4g %11.4g %11.4g %9.3g %10.1f %8.3g %7.0f %9.4g %8.3g %5llu %-6s %s\n",
                s->cfg[i].cfg.width, gl, pnan(r->max_abs_err), pnan(r->rms_err), pnan(r->nmse), pnan(r->max_err_lsb),
                r->area_ge, r->cycles_per_item, pnan(r->ppa.fmax_mhz), pnan(tb_pixels_per_s(r) / 1e6),
                pnan(tb_energy_pj_per_pixel(r)),
                (unsigned long long)r->overflows, r->within_bound ? "ok" : r->bound_check == TB_CHECK_NO_BOUND ? "none" : "EXCEED", on && on[i] ? "*" : "");
    }
}

/* The widths of each group whose rows pass `want` (1: on the front, 0:
 * successful but off it), as ranges: "w=8..12, 14" per group. */
static void print_ranges(FILE *f, const tb_sweep *s, const unsigned char *on, int want)
{
    int any = 0;
    for (size_t g = 0; g < s->ngroups; g++) {
        int run_lo = -1, prev = -2, first = 1;
        for (size_t i = g;; i += s->ngroups) {
            int w = i < s->n ? s->cfg[i].cfg.width : -1;
            int in = i < s->n && row_ok(s, i) && on[i] == want;
            if (in && w == prev + 1 && run_lo >= 0) { prev = w; continue; }
            if (run_lo >= 0) {
                if (first) {
                    char gl[200];
                    tb_sweep_group_label(s, g, gl, sizeof gl);
                    fprintf(f, "%s%s%sw=", any ? "; " : " ", gl, *gl ? " " : "");
                    first = 0;
                    any = 1;
                } else fputs(", ", f);
                if (prev > run_lo) fprintf(f, "%d..%d", run_lo, prev);
                else fprintf(f, "%d", run_lo);
                run_lo = -1;
            }
            if (i >= s->n) break;
            if (in) run_lo = prev = w;
        }
    }
    if (!any) fputs(" none", f);
}

/* What the front says: which configurations are on it, which buy nothing
 * (dominated), and what a halving of the error costs along it. */
static void print_front(FILE *f, const tb_sweep *s, const unsigned char *on, size_t nfront)
{
    size_t nok = 0;
    for (size_t i = 0; i < s->n; i++) nok += row_ok(s, i);
    fprintf(f, "Pareto front (max |e|, area, pixels per second), %zu of %zu configurations:", nfront, nok);
    print_ranges(f, s, on, 1);
    fputc('\n', f);
    if (nfront < nok) {
        fputs("  dominated (another is no worse in error, area and pixels per second, and better in one):", f);
        print_ranges(f, s, on, 0);
        fputc('\n', f);
    }
    fpt *p = malloc((nfront ? nfront : 1) * sizeof *p);
    if (!p) return;
    size_t n = 0;
    for (size_t i = 0; i < s->n; i++)
        if (on[i]) p[n++] = (fpt){ s->row[i].r.area_ge, s->row[i].r.max_abs_err, i };
    qsort(p, n, sizeof *p, fpt_cmp);
    /* Area per halving of the error between neighbours on the front, over
     * the cheap half of the steps and the accurate half: the price of
     * accuracy at either end (sums, so that one step that buys almost
     * nothing does not swamp the figure). */
    double sa[2] = { 0, 0 }, sh[2] = { 0, 0 };
    size_t nsteps = 0, k2 = 0;
    for (size_t k = 1; k < n; k++) nsteps += p[k].y > 0 && p[k - 1].y > p[k].y;
    for (size_t k = 1; k < n; k++) {
        double e0 = p[k - 1].y, e1 = p[k].y;
        if (!(e1 > 0 && e0 > e1)) continue;
        int half = 2 * k2++ >= nsteps;
        sa[half] += p[k].x - p[k - 1].x;
        sh[half] += log2(e0 / e1);
    }
    /* A front whose error spans less than a tenth of a halving has no price per
     * halving to quote: the quotient would extrapolate a hair of error
     * (two widths whose max |e| differ in the fifth digit) into any
     * number of gate equivalents. */
    if (n > 1 && sh[0] + sh[1] > 0 && sh[0] + sh[1] < 0.1)
        fprintf(f, "  along it, max |e| falls only from %.4g to %.4g (less than a tenth of a halving): no area per halving to quote\n",
                p[0].y, p[n - 1].y);
    else if (sh[0] + sh[1] > 0) {
        fprintf(f, "  along it, halving max |e| costs %.0f GE on average", (sa[0] + sa[1]) / (sh[0] + sh[1]));
        if (sh[0] > 0 && sh[1] > 0)
            fprintf(f, " (%.0f GE in its cheaper half, %.0f GE in its more accurate half)", sa[0] / sh[0], sa[1] / sh[1]);
        fputc('\n', f);
    }
    free(p);
}


void sweep_print_accept(FILE *f, const tb_sweep *s, int shard_k, int shard_n, size_t *misses)
{
    const tb_accept *ac = &s->spec.accept;
    *misses = 0;
    if (!(ac->max_error > 0 || ac->max_nmse > 0 || ac->max_lsb > 0)) return;
    unsigned char *miss = calloc(s->n ? s->n : 1, 1);
    size_t nrun = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (!tb_sweep_in_shard(i, shard_k, shard_n) || !row_ok(s, i)) continue;
        nrun++;
        if (!s->row[i].r.target_met) { ++*misses; if (miss) miss[i] = 1; }
    }
    fputs("acceptance (", f);
    int k = 0;
    if (ac->max_error > 0) fprintf(f, "%smax |e| <= %g", k++ ? ", " : "", ac->max_error);
    if (ac->max_nmse > 0) fprintf(f, "%sNMSE <= %g", k++ ? ", " : "", ac->max_nmse);
    if (ac->max_lsb > 0) fprintf(f, "%smax LSB <= %g", k++ ? ", " : "", ac->max_lsb);
    fprintf(f, "): %zu of %zu configurations miss it", *misses, nrun);
    if (*misses && miss && !shard_n) { fputs(":", f); print_ranges(f, s, miss, 1); }
    fputc('\n', f);
    free(miss);
}

/* The summary (malloc'd), or NULL when out of memory. */
static char *summary_text(sweep_args *a, const tb_sweep *s, const unsigned char *on, size_t nfront)
{
    char *text = NULL;
    size_t tlen = 0;
    FILE *m = open_memstream(&text, &tlen);
    if (!m) return NULL;
    fprintf(m, "sweep %s: %zu configurations (widths %d..%d", s->spec.u->name, s->n, s->spec.wlo, s->spec.whi);
    if (s->ngroups > 1) fprintf(m, " x %zu settings", s->ngroups);
    fprintf(m, "), %zu vectors", tb_sweep_rows(s, 0));
    if (s->npsets > 1) fputs(" per parameter set", m);
    fprintf(m, ", sweep_id %016llx\n", (unsigned long long)s->id);
    print_table(m, s, on);
    sweep_print_accept(m, s, 0, 0, &a->misses);
    print_front(m, s, on, nfront);
    if (a->t.on) sweep_print_target(m, s, &a->t);
    fclose(m);
    return text;
}

int sweep_outputs(sweep_args *a, tb_sweep *s, double t0, int tty)
{
    char files[600] = "sweep.csv";
    oset os = { a->dir, 0, NULL };
    FILE *csv = sweep_oset_open(&os, "sweep.csv");
    if (!csv) return CLI_USAGE;
    tb_sweep_print_csv(s, csv, 0, 0);
    if (a->t.on && sweep_target_search(a, s, tty)) { sweep_oset_abort(&os); return CLI_USAGE; }
    size_t nfront = 0;
    unsigned char *on = front_of(s, &nfront);
    int drawn[TB_SC_NCHARTS] = { 0 };
    if (!on) base_out_of_memory();
    if (write_charts(s, &a->t, &os, files, sizeof files, drawn)) {
        free(on);
        sweep_oset_abort(&os);
        return CLI_USAGE;
    }
    /* Files of an earlier sweep in DIR that this one does not write would
     * contradict its sweep.csv: they go, when this set moves in. */
    const char *gone[2 + TB_SC_NCHARTS];
    int ngone = 0;
    for (int k = 0; k < TB_SC_NCHARTS; k++)
        if (!drawn[k]) gone[ngone++] = tb_sc_chart_file[k];
    if (a->t.on) {
        if (sweep_write_target_json(s, &a->t, &os) || sweep_write_target_csv(s, &a->t, &os)) { free(on); sweep_oset_abort(&os); return CLI_USAGE; }
        strncat(files, ", target.json, target.csv", sizeof files - strlen(files) - 1);
    } else {
        gone[ngone++] = "target.json";
        gone[ngone++] = "target.csv";
    }
    strncat(files, ", summary.txt", sizeof files - strlen(files) - 1);

    /* The summary, printed and saved: the same text. */
    char *text = summary_text(a, s, on, nfront);
    free(on);
    if (!text) base_out_of_memory();
    FILE *sf = sweep_oset_open(&os, "summary.txt");
    if (!sf) { free(text); sweep_oset_abort(&os); return CLI_USAGE; }
    fputs(text, sf);
    int rc = sweep_oset_commit(&os, gone, ngone);
    if (rc == 0) {
        fputs(text, stdout);
        /* Timings are not output (the same inputs give the same bytes): only
         * a terminal's stderr hears how long it took. */
        printf("wrote %s/: %s\n", a->dir, files);
        if (tty) fprintf(stderr, "shadesim sweep %s: %.2f s on %d thread%s\n", s->spec.u->name, base_proc_now() - t0,
                         a->threads, a->threads > 1 ? "s" : "");
    }
    free(text);
    return rc;
}
