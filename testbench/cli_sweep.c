/* cli_sweep.c - the verbs sweep and merge: arguments, output folder,
 * charts, the summary and target.json around the engine in tb_sweep.c. */
#include "testbench/cli.h"
#include "chart/chart.h"
#include "testbench/tb_sweep.h"
#include "testbench/tb_sweep_chart.h"
#include "base/base_out.h"
#include "base/base_json.h"
#include "base/base_join.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static const char sweep_help[] =
    "usage: shadesim sweep UNIT --widths LO:HI [options]\n\n"
    "Runs UNIT's testbench at every width LO..HI (the unit's default-format rule,\n"
    "`shadesim list UNIT`), crossed with the listed settings, and writes into DIR:\n"
    "  sweep.csv            one row per configuration, every figure of run --json\n"
    "  error_vs_width.svg   max and RMS error against width (log scale)\n"
    "  area_vs_error.svg    area against max error, the Pareto front ringed\n"
    "  cycles_vs_error.svg  clocks per pixel against max error (when they vary)\n"
    "                       (the front: no other configuration is as good in\n"
    "                       max error, area and clocks per pixel and better in one;\n"
    "                       `shadesim chart` draws the charts from any sweep CSV)\n"
    "  summary.txt          what is printed on stdout\n"
    "  target.json          with --target-error/--target-nmse: the chosen formats\n"
    "  target.csv           ... and the same per settings group as one CSV row each\n"
    "Order of the rows: width-major, then schedule, each --param in the order\n"
    "given, round, overflow (the last varies fastest). docs/sweeps.md has more.\n\n"
    "options:\n"
    "  --widths LO:HI       widths to sweep, within 1..64 (or one width W)\n"
    "  --round LIST         rounding modes, e.g. trunc,half-up,even (default trunc)\n"
    "  --overflow LIST      overflow modes, e.g. wrap,sat (default wrap)\n"
    "  --schedule LIST      the unit's schedules, e.g. paper,... (default its first)\n"
    "  --param NAME=LIST    a unit parameter's values, e.g. terms=2,3,4 (repeatable)\n"
    "  --fmt NAME=sI.F      pin a signal's format in every configuration (repeatable)\n"
    "  --vectors FILE       golden vectors (default: the unit's file in vectors/)\n"
    "  -n N [--seed S]      instead, N vectors made by the float reference (seed 1)\n"
    "  --target-error E     cheapest per-signal formats with max |error| <= E,\n"
    "                       re-checked on held-out stimuli (another seed)\n"
    "  --target-nmse E      ... with NMSE <= E\n"
    "  --margin BITS        the search aims at E / 2^BITS (NMSE: E / 4^BITS), so\n"
    "                       that the held-out check at E has room (default 0)\n"
    "  --max-error E        acceptance: a row meets it when max |error| <= E\n"
    "  --max-nmse X         ... when NMSE <= X\n"
    "  --max-lsb K          ... when max |error| <= K LSB of the output format;\n"
    "                       the CSV's meets_target says which rows do\n"
    "  -j N                 run on N threads (default 1); the output is the same\n"
    "  --shard K/N          run only configurations i with i mod N = K-1 and write\n"
    "                       DIR/sweep-K-of-N.csv; join them with shadesim merge\n"
    "  -o DIR               output folder (default out/sweep-UNIT), made if missing\n\n"
    "The files are written in full, then moved into DIR together: an interrupted\n"
    "sweep leaves DIR as it was, and of two sweeps into one DIR the folder keeps\n"
    "the complete set of the one that finished last (they take turns on the lock\n"
    "file DIR/.sweep.lock).\n\n"
    "exit status: 0 done (a width over its error bound is data: within_bound),\n"
    "1 some configuration's simulation failed, a row misses --max-error/--max-nmse/\n"
    "--max-lsb, or a target search's result failed its held-out check; 2 bad usage\n"
    "or input\n";

static const char merge_help[] =
    "usage: shadesim merge SHARD.csv ... -o OUT.csv\n\n"
    "Joins the CSVs of a sweep's shards (shadesim sweep --shard K/N) into exactly\n"
    "the sweep.csv that the whole sweep writes: rows back in configuration order.\n"
    "The headers must be identical and the rows of one sweep (same sweep_id);\n"
    "a configuration given twice or missing is an error (exit status 2).\n"
    "-o - writes to stdout; an existing OUT.csv is replaced only once complete\n"
    "(a symbolic link is followed and kept; a device or FIFO is written to in place).\n";

static int is_help(const char *a) { return !strcmp(a, "--help") || !strcmp(a, "-h"); }

/* Results went to stdout: a write error there (full disk, closed pipe)
 * must not pass as success. */
static int stdout_done(int rc)
{
    char e[300];
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return rc;
}

/* "--opt VALUE" or "--opt=VALUE": 1 and the value (NULL if missing), or 0. */
static int opt(const char *name, int argc, char **argv, int *i, const char **val)
{
    size_t n = strlen(name);
    if (strncmp(argv[*i], name, n)) return 0;
    if (argv[*i][n] == '=') { *val = argv[*i] + n + 1; return 1; }
    if (argv[*i][n]) return 0;
    *val = *i + 1 < argc ? argv[++*i] : NULL;
    return 1;
}

/* printf spells a NaN "-nan" when its sign bit is set (0/0, inf/inf on
 * x86): the tables print every NaN as "nan", like the CSV. */
static double pnan(double v) { return isnan(v) ? NAN : v; }

/* The n characters at s as a whole number lo..hi: digits only (no sign,
 * space or junk, nothing cut off). */
static int parse_long_n(const char *s, size_t n, long lo, long hi, long *v)
{
    long x = 0;
    if (!n) return -1;
    for (size_t k = 0; k < n; k++) {
        if (s[k] < '0' || s[k] > '9') return -1;
        if (x > 100000000000L) return -1;      /* far past any hi used here */
        x = x * 10 + (s[k] - '0');
    }
    if (x < lo || x > hi) return -1;
    *v = x;
    return 0;
}

static int parse_long(const char *s, long lo, long hi, long *v) { return parse_long_n(s, strlen(s), lo, hi, v); }

static int parse_widths(const char *v, int *lo, int *hi)
{
    const char *colon = strchr(v, ':');
    size_t na = colon ? (size_t)(colon - v) : strlen(v);
    const char *b = colon ? colon + 1 : v;
    long x, y;
    if (parse_long_n(v, na, 0, 1000000, &x) || parse_long(b, 0, 1000000, &y)) {
        char e[200];
        return cli_usage_error("--widths %s: expected LO:HI with whole numbers, e.g. 8:24", cli_esc(v, e, sizeof e));
    }
    if (x < 1 || y > 64 || y < 1 || x > 64)
        return cli_usage_error("--widths %s: widths must be within 1..64", v);
    if (x > y) return cli_usage_error("--widths %s: LO is greater than HI", v);
    *lo = (int)x;
    *hi = (int)y;
    return 0;
}

/* Split a comma list into at most cap distinct items of up to 31
 * characters; messages quote the option as given: "OPT SHOWN: ...". */
static int split_list(const char *opt_name, const char *shown, const char *list, char items[][32], int cap, int *n)
{
    *n = 0;
    for (const char *p = list;;) {
        size_t k = strcspn(p, ",");
        if (k == 0 || k > 31) return cli_usage_error("%s %s: expected a comma-separated list of values", opt_name, shown);
        if (*n == cap) return cli_usage_error("%s %s: at most %d values", opt_name, shown, cap);
        snprintf(items[*n], 32, "%.*s", (int)k, p);
        for (int j = 0; j < *n; j++)
            if (!strcmp(items[j], items[*n])) return cli_usage_error("%s %s: '%s' is listed twice", opt_name, shown, items[j]);
        ++*n;
        if (!p[k]) return 0;
        p += k + 1;
    }
}

static int parse_real(const char *s, double *v)
{
    char *end;
    errno = 0;
    if (!cli_is_real(s)) return -1;
    *v = strtod(s, &end);
    return !*s || *end || errno || !isfinite(*v) || *v < 0 ? -1 : 0;
}

/* ------------------------------------------------------------- progress */

typedef struct progress { const char *unit; double t0, last; int shown; } progress;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void on_progress(void *arg, size_t done, size_t total)
{
    progress *p = arg;
    double t = now_s();
    if (done < total && t - p->last < 0.1) return;
    p->last = t;
    p->shown = 1;
    fprintf(stderr, "\rshadesim sweep %s: %zu/%zu configurations, %.1f s ", p->unit, done, total, t - p->t0);
    fflush(stderr);
}

static void progress_clear(progress *p)
{
    if (p->shown) fputs("\r\033[K", stderr);
    p->shown = 0;
}

/* --------------------------------------------------------------- charts */

static int row_ok(const tb_sweep *s, size_t i) { return s->row[i].status == TB_OK; }

/* Pareto front of the successful rows over max error, area and clocks
 * per pixel (per output beat: an interpolation unit's item is L pixels),
 * as the charts draw it (tb_sweep_chart.h). */
static unsigned char *front_of(const tb_sweep *s, size_t *nfront)
{
    double *x = malloc(s->n * sizeof *x), *y = malloc(s->n * sizeof *y), *z = malloc(s->n * sizeof *z);
    unsigned char *on = calloc(s->n ? s->n : 1, 1);
    *nfront = 0;
    if (!x || !y || !z || !on) { free(x); free(y); free(z); free(on); return NULL; }
    for (size_t i = 0; i < s->n; i++) {
        x[i] = row_ok(s, i) ? s->row[i].r.max_abs_err : NAN;
        y[i] = row_ok(s, i) ? s->row[i].r.area_ge : NAN;
        z[i] = row_ok(s, i) ? s->row[i].r.cycles_per_beat : NAN;
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

/* ------------------------------------------------------- the file set */

/* A sweep's files are written in full first, each to its own temporary
 * (base_out: removed if the process is interrupted), and only then moved
 * into DIR one after the other under a lock on DIR/.sweep.lock. So an
 * interrupted sweep changes nothing in DIR, and two sweeps into one folder
 * move their sets in turn: the folder ends up with the whole set of the
 * one that finished last (a file the other wrote and this one does not,
 * e.g. target.json, is removed under the same lock). */
#define OSET_MAX 8
typedef struct oset {
    const char *dir;
    int n;
    base_out *o[OSET_MAX];
} oset;

/* Open DIR/name as one of the set; NULL after printing the error. */
static FILE *oset_open(oset *os, const char *name)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/%s", os->dir, name);
    if (os->n == OSET_MAX) { cli_usage_error("%s: too many output files", path); return NULL; }
    base_out *o = base_out_open(path, err, sizeof err);
    if (!o) { cli_usage_error("%s", err); return NULL; }
    os->o[os->n++] = o;
    return base_out_file(o);
}

static void oset_abort(oset *os)
{
    for (int i = 0; i < os->n; i++) base_out_abort(os->o[i]);
    os->n = 0;
}

/* Move the set in (and remove DIR/gone[k]) under the folder's lock. */
static int oset_commit(oset *os, const char *const *gone, int ngone)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/.sweep.lock", os->dir);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) {
        oset_abort(os);
        return cli_usage_error("%s: cannot open: %s", path, strerror(errno));
    }
    struct flock lk;
    memset(&lk, 0, sizeof lk);
    lk.l_type = F_WRLCK;
    lk.l_whence = SEEK_SET;
    /* Where locks are not supported (ENOLCK) the set still moves in, only
     * without the guarantee against a concurrent sweep. */
    while (fcntl(fd, F_SETLKW, &lk) == -1 && errno == EINTR) {}
    int rc = 0;
    for (int i = 0; i < os->n; i++) {
        if (rc) base_out_abort(os->o[i]);
        else if (base_out_close(os->o[i], err, sizeof err)) rc = cli_usage_error("%s", err);
    }
    os->n = 0;
    for (int k = 0; k < ngone && !rc; k++) {
        snprintf(path, sizeof path, "%s/%s", os->dir, gone[k]);
        unlink(path);
    }
    close(fd);                  /* releases the lock */
    return rc;
}

static int write_chart(chart *c, oset *os, const char *name, char *files, size_t flen)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/%s", os->dir, name);
    if (!c) return cli_usage_error("%s: out of memory", path);
    FILE *f = oset_open(os, name);
    int rc = f ? chart_fwrite(c, f, path, err, sizeof err) : 0;
    chart_free(c);
    if (!f) return CLI_USAGE;
    if (rc) return cli_usage_error("%s", err);
    strncat(files, ", ", flen - strlen(files) - 1);
    strncat(files, name, flen - strlen(files) - 1);
    return 0;
}

typedef struct target_info {
    int on;
    tb_target_kind kind;
    double value;
    double margin;          /* --margin BITS */
    double goal;            /* what the search aims at: value less the margin */
    unsigned long long ho_seed;   /* seed of the held-out stimuli */
    size_t ho_rows;         /* their vectors per parameter set */
    tb_target_res *res;     /* [ngroups] */
} target_info;

/* The charts, drawn from the CSV text as `shadesim chart` draws them
 * (tb_sweep_chart.h), so both give the same bytes; the sweep adds the
 * target search's designs. *drawn: the clocks chart was drawn. */
static int write_charts(const tb_sweep *s, const target_info *t, oset *os, char *files, size_t flen, int *drawn)
{
    char *text = NULL, err[600];
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (!m) return cli_usage_error("sweep: out of memory");
    tb_sweep_print_csv(s, m, 0, 0);
    if (fclose(m)) { free(text); return cli_usage_error("sweep: out of memory"); }
    tb_sc *sc = tb_sc_read(text, len, "sweep.csv", err, sizeof err);
    free(text);
    if (!sc) return cli_usage_error("%s", err);
    double *te = NULL, *ta = NULL;
    tb_sc_target tg = { 0, 0, 0, 0, NULL, NULL };
    if (t->on) {
        te = calloc(s->ngroups, sizeof *te);
        ta = calloc(s->ngroups, sizeof *ta);
        if (!te || !ta) { free(te); free(ta); tb_sc_free(sc); return cli_usage_error("sweep: out of memory"); }
        tg.on = 1;
        tg.nmse = t->kind == TB_TARGET_NMSE;
        tg.value = t->value;
        for (size_t g = 0; g < s->ngroups; g++)
            if (t->res[g].met) { te[tg.n] = t->res[g].r.max_abs_err; ta[tg.n] = t->res[g].r.area_ge; tg.n++; }
        tg.err = te;
        tg.area = ta;
    }
    int rc = 0;
    *drawn = 0;
    for (int k = 0; k < TB_SC_NCHARTS && !rc; k++) {
        if (!tb_sc_chart_drawn(sc, k)) continue;
        if (k == TB_SC_CLOCKS_ERROR) *drawn = 1;
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
    fprintf(f, "%5s  %-22s %11s %11s %11s %9s %10s %8s %5s %-6s %s\n", "width", "settings", "max|e|", "rms e",
            "nmse", "max LSB", "area GE", "clk/item", "ovf", "bound", "front");
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
        fprintf(f, "%5d  %-22s %11.4g %11.4g %11.4g %9.3g %10.1f %8.3g %5llu %-6s %s\n", s->cfg[i].cfg.width, gl,
                pnan(r->max_abs_err), pnan(r->rms_err), pnan(r->nmse), pnan(r->max_err_lsb), r->area_ge, r->cycles_per_item,
                (unsigned long long)r->overflows, r->within_bound ? "ok" : "EXCEED", on && on[i] ? "*" : "");
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
    fprintf(f, "Pareto front (max |e|, area, clocks per pixel), %zu of %zu configurations:", nfront, nok);
    print_ranges(f, s, on, 1);
    fputc('\n', f);
    if (nfront < nok) {
        fputs("  dominated (another is no worse in error, area and clocks per pixel, and better in one):", f);
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
    if (sh[0] + sh[1] > 0) {
        fprintf(f, "  along it, halving max |e| costs %.0f GE on average", (sa[0] + sa[1]) / (sh[0] + sh[1]));
        if (sh[0] > 0 && sh[1] > 0)
            fprintf(f, " (%.0f GE in its cheaper half, %.0f GE in its more accurate half)", sa[0] / sh[0], sa[1] / sh[1]);
        fputc('\n', f);
    }
    free(p);
}

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
        if (tb_target_holds(&s->row[i].r, s->row[i].status, k, target, UINT64_MAX)) return i;
    return s->n;
}

static void print_target(FILE *f, const tb_sweep *s, const target_info *t)
{
    for (size_t g = 0; g < s->ngroups; g++) {
        const tb_target_res *x = &t->res[g];
        char gl[200];
        tb_sweep_group_label(s, g, gl, sizeof gl);
        fprintf(f, "target %s <= %g%s%s%s: ", metric_name(t->kind), t->value, *gl ? " (" : "", gl, *gl ? ")" : "");
        if (!x->met) {
            fprintf(f, "no width in %d..%d meets it within the error bound\n", s->spec.wlo, s->spec.whi);
            continue;
        }
        const tb_result *ru = &s->row[x->uniform].r;
        double saved = ru->area_ge - x->r.area_ge;
        fprintf(f, "uniform width %d: %.1f GE, %s %.4g; per-signal formats: %.1f GE, %s %.4g, saving %.1f GE (%.1f%%), %zu runs\n",
                s->cfg[x->uniform].cfg.width, ru->area_ge, metric_name(t->kind), metric_of(t->kind, ru), x->r.area_ge,
                metric_name(t->kind), metric_of(t->kind, &x->r), saved, ru->area_ge > 0 ? 100 * saved / ru->area_ge : 0.0,
                x->runs);
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
    }
}

/* The target search's result per group as CSV (target.csv). */
static int write_target_csv(const tb_sweep *s, const target_info *t, oset *os)
{
    const unit_desc *u = s->spec.u;
    FILE *f = oset_open(os, "target.csv");
    if (!f) return CLI_USAGE;
    fputs("group,unit,schedule", f);
    for (int i = 0; i < u->nparams; i++) fprintf(f, ",%s", u->params[i].name);
    fputs(",round,overflow,metric,target,margin_bits,goal,met,uniform_width,uniform_area_ge,uniform_metric,"
          "chosen_area_ge,chosen_metric,area_saved_ge,area_saved_pct,runs,heldout_seed,heldout_vectors,"
          "heldout_metric,heldout_uniform_metric,heldout_overflows,heldout_passed,formats\n", f);
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
        if (!x->met) { fputs(",,,,,,,,,,,,,,,,\n", f); continue; }
        const tb_result *ru = &s->row[x->uniform].r;
        double saved = ru->area_ge - x->r.area_ge;
        fprintf(f, ",%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu,%llu,%zu,%.17g,%.17g,%llu,%s,",
                s->cfg[x->uniform].cfg.width, ru->area_ge, metric_of(t->kind, ru), x->r.area_ge,
                metric_of(t->kind, &x->r), saved, ru->area_ge > 0 ? 100 * saved / ru->area_ge : 0.0, x->runs,
                t->ho_seed, t->ho_rows, metric_of(t->kind, &x->heldout_r), metric_of(t->kind, &x->heldout_u),
                (unsigned long long)x->heldout_r.overflows, x->heldout_ok ? "true" : "false");
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
    fprintf(f, ", \"overflows\": %llu, \"within_bound\": %s}", (unsigned long long)r->overflows,
            r->within_bound ? "true" : "false");
}

static int write_target_json(const tb_sweep *s, const target_info *t, oset *os)
{
    const unit_desc *u = s->spec.u;
    FILE *f = oset_open(os, "target.json");
    if (!f) return CLI_USAGE;
    fprintf(f, "{\n  \"unit\": \"%s\",\n  \"target\": {\"metric\": \"%s\", \"value\": ", u->name,
            t->kind == TB_TARGET_NMSE ? "nmse" : "max_abs_err");
    base_json_num(f, t->value, 17);
    fputs(", \"margin_bits\": ", f);
    base_json_num(f, t->margin, 17);
    fputs(", \"goal\": ", f);
    base_json_num(f, t->goal, 17);
    fprintf(f, "},\n  \"rule\": \"metric <= goal (the target less the margin), every output within its bound, no more "
               "overflows than the uniform design\",\n  \"held_out\": {\"seed\": %llu, \"vectors\": %zu, \"rule\": "
               "\"metric <= target, every output within its bound, no more overflows than the uniform design on the "
               "same stimuli\"},\n  \"groups\": [", t->ho_seed, t->ho_rows);
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
        }
        fputc('}', f);
    }
    fputs("\n  ]\n}\n", f);
    return 0;
}

/* ---------------------------------------------------------------- sweep */

typedef struct sweep_args {
    cli_unit_opts o;
    tb_sweep_spec sp;
    const char *dir;
    int threads, shard_k, shard_n;
    long long nvec;
    unsigned long long seed;
    target_info t;
    int ho_failed;          /* some group's held-out check failed */
    size_t misses;          /* rows that miss --max-error/--max-nmse/--max-lsb */
} sweep_args;

static int parse_sweep(int argc, char **argv, sweep_args *a)
{
    memset(a, 0, sizeof *a);
    a->threads = 1;
    a->nvec = -1;
    a->seed = 1;
    if (argc < 2 || argv[1][0] == '-') return cli_usage_error("sweep: which unit? (shadesim list)");
    if (cli_unit_select(&a->o, argv[1])) return CLI_USAGE;
    const unit_desc *u = a->o.u;
    tb_sweep_spec *sp = &a->sp;
    sp->u = u;
    int have_w = 0;
    for (int i = 2; i < argc; i++) {
        const char *v = NULL, *name = argv[i];
        char items[TB_SWEEP_MAX_VALUES][32];
        int n;
        long x;
        if (opt("--widths", argc, argv, &i, &v)) {
            if (!v) return cli_usage_error("--widths needs LO:HI");
            if (parse_widths(v, &sp->wlo, &sp->whi)) return CLI_USAGE;
            have_w = 1;
        } else if (opt("--width", argc, argv, &i, &v)) {
            return cli_usage_error("sweep: use --widths LO:HI (or --widths W for one width)");
        } else if (opt("--round", argc, argv, &i, &v)) {
            if (!v || split_list("--round", v, v, items, 3, &n)) return v ? CLI_USAGE : cli_usage_error("--round needs a value");
            for (int k = 0; k < n; k++)
                if (sim_round_parse(items[k], &sp->rnd[k])) return cli_usage_error("--round %s: '%s' is not trunc, half-up or even", v, items[k]);
            sp->nrnd = n;
        } else if (opt("--overflow", argc, argv, &i, &v)) {
            if (!v || split_list("--overflow", v, v, items, 2, &n)) return v ? CLI_USAGE : cli_usage_error("--overflow needs a value");
            for (int k = 0; k < n; k++)
                if (sim_ovf_parse(items[k], &sp->ovf[k])) return cli_usage_error("--overflow %s: '%s' is not wrap or sat", v, items[k]);
            sp->novf = n;
        } else if (opt("--schedule", argc, argv, &i, &v)) {
            if (!v || split_list("--schedule", v, v, items, UNIT_MAX_SCHED, &n)) return v ? CLI_USAGE : cli_usage_error("--schedule needs a value");
            for (int k = 0; k < n; k++)
                if ((sp->sched[k] = unit_sched_find(u, items[k])) < 0) {
                    char list[200] = "";
                    for (int j = 0; j < u->nsched; j++) {
                        base_join_add(list, sizeof list, ", ", u->sched[j].name);
                    }
                    return cli_usage_error("--schedule %s: unit %s has schedules: %s", items[k], u->name, list);
                }
            sp->nsched = n;
        } else if (opt("--param", argc, argv, &i, &v)) {
            if (!v) return cli_usage_error("--param needs NAME=VALUES");
            const char *eq = strchr(v, '=');
            if (!eq) return cli_usage_error("--param %s: expected NAME=V1,V2,...", v);
            char pname[64], err[300];
            snprintf(pname, sizeof pname, "%.*s", (int)(eq - v), v);
            int pi = -1;
            for (int k = 0; k < u->nparams; k++)
                if (!strcmp(u->params[k].name, pname)) pi = k;
            unit_cfg scratch = a->o.cfg;
            if (pi < 0 && unit_param_set(u, &scratch, pname, eq + 1, err, sizeof err)) return cli_usage_error("--param %s: %s", v, err);
            for (int k = 0; k < sp->npax; k++)
                if (sp->pax[k].param == pi) return cli_usage_error("--param %s: %s is given twice", v, pname);
            tb_sweep_paxis *ax = &sp->pax[sp->npax];
            if (split_list("--param", v, eq + 1, items, TB_SWEEP_MAX_VALUES, &n)) return CLI_USAGE;
            for (int k = 0; k < n; k++) {
                if (unit_param_set(u, &scratch, pname, items[k], err, sizeof err)) return cli_usage_error("--param %s: %s", v, err);
                memcpy(ax->val[k], items[k], sizeof ax->val[k]);
            }
            ax->param = pi;
            ax->n = n;
            sp->npax++;
        } else if (opt("-j", argc, argv, &i, &v)) {
            if (!v || parse_long(v, 1, 256, &x)) return cli_usage_error("-j %s: expected 1..256 threads", v ? v : "");
            a->threads = (int)x;
        } else if (opt("--shard", argc, argv, &i, &v)) {
            long k, m;
            const char *sl = v ? strchr(v, '/') : NULL;
            char e[200];
            if (!sl) return cli_usage_error("--shard %s: expected K/N, e.g. 1/4", cli_esc(v ? v : "", e, sizeof e));
            if (parse_long_n(v, (size_t)(sl - v), 0, 1000000, &k) || parse_long(sl + 1, 0, 1000000, &m))
                return cli_usage_error("--shard %s: expected K/N with whole numbers, e.g. 1/4", cli_esc(v, e, sizeof e));
            if (m < 1 || k < 1 || k > m) return cli_usage_error("--shard %s: K must be 1..N (shards are numbered from 1)", v);
            a->shard_k = (int)k;
            a->shard_n = (int)m;
        } else if (opt("-o", argc, argv, &i, &v)) {
            if (!v || !*v) return cli_usage_error("-o needs a folder");
            a->dir = v;
        } else if (opt("-n", argc, argv, &i, &v)) {
            if (!v || parse_long(v, 1, 10000000, &x)) return cli_usage_error("-n %s: expected 1..10000000 vectors", v ? v : "");
            a->nvec = x;
        } else if (opt("--seed", argc, argv, &i, &v)) {
            if (!v) return cli_usage_error("--seed needs a whole number");
            uint64_t sd;
            if (cli_parse_u64("--seed", v, NULL, &sd)) return CLI_USAGE;
            a->seed = sd;
        } else if (opt("--margin", argc, argv, &i, &v)) {
            if (!v || parse_real(v, &a->t.margin) || a->t.margin > 32 || a->t.margin != floor(a->t.margin))
                return cli_usage_error("--margin %s: expected whole bits 0..32", v ? v : "");
        } else if (opt("--max-error", argc, argv, &i, &v) || opt("--max-nmse", argc, argv, &i, &v) ||
                   opt("--max-lsb", argc, argv, &i, &v)) {
            double *dst = strstr(name, "nmse") ? &sp->accept.max_nmse : strstr(name, "lsb") ? &sp->accept.max_lsb
                        : &sp->accept.max_error;
            if (!v || parse_real(v, dst) || !(*dst > 0))
                return cli_usage_error("%s %s: expected a number > 0, e.g. 1e-3", name, v ? v : "");
        } else if (opt("--target-error", argc, argv, &i, &v) || opt("--target-nmse", argc, argv, &i, &v)) {
            int nmse = strstr(name, "nmse") != NULL;
            if (a->t.on) return cli_usage_error("sweep: one target at a time (--target-error or --target-nmse)");
            if (!v || parse_real(v, &a->t.value)) return cli_usage_error("%s %s: expected a number >= 0, e.g. 1e-3", nmse ? "--target-nmse" : "--target-error", v ? v : "");
            a->t.on = 1;
            a->t.kind = nmse ? TB_TARGET_NMSE : TB_TARGET_MAX_ABS_ERR;
        } else {
            int r = cli_unit_option(&a->o, argc, argv, &i);
            if (r < 0) return CLI_USAGE;
            if (!r) return cli_usage_error("sweep: unknown option '%s' (see shadesim sweep --help)", argv[i]);
        }
    }
    if (!have_w) return cli_usage_error("sweep: --widths LO:HI is required, e.g. --widths 8:24");
    if (a->nvec > 0 && a->o.vectors) return cli_usage_error("sweep: -n makes vectors; --vectors reads them: give one");
    if (a->shard_n && a->t.on) return cli_usage_error("sweep: the target search needs the whole sweep, not a shard");
    if (a->t.margin > 0 && !a->t.on) return cli_usage_error("sweep: --margin goes with --target-error or --target-nmse");
    a->t.goal = a->t.on ? tb_target_goal(a->t.kind, a->t.value, a->t.margin) : 0;
    sp->base = a->o.cfg;
    if (!sp->nsched) { sp->nsched = 1; sp->sched[0] = a->o.cfg.schedule; }
    if (!sp->nrnd) { sp->nrnd = 1; sp->rnd[0] = a->o.cfg.rnd; }
    if (!sp->novf) { sp->novf = 1; sp->ovf[0] = a->o.cfg.ovf; }
    sp->fmt = a->o.fmt;
    sp->nfmt = a->o.nfmt;
    return 0;
}

/* Vectors per parameter set: each set's own (a parameter like L changes
 * the outputs), loaded once and shared read-only by the threads. */
static int load_vectors(sweep_args *a, tb_sweep *s, vec_set *sets)
{
    for (size_t p = 0; p < s->npsets; p++) {
        cli_unit_opts o = a->o;
        o.cfg = *tb_sweep_pset_cfg(s, p);
        if (a->nvec > 0) {
            char err[600];
            if (cli_make_vectors(o.u, &o.cfg, (size_t)a->nvec, a->seed, &sets[p], err, sizeof err)) return cli_usage_error("%s", err);
        } else if (cli_load_vectors(&o, &sets[p])) {
            return CLI_USAGE;
        }
        s->vs[p] = &sets[p];
    }
    return 0;
}

/* The target search's results on held-out stimuli: vectors of another
 * seed (the sweep's seed + 1; the default files are seed 1's), as many as
 * the sweep used, made once per parameter set; the generators put their
 * full-range corner values first whatever the seed. */
static int heldout_check(sweep_args *a, tb_sweep *s)
{
    vec_set *ho = calloc(s->npsets, sizeof *ho);
    unsigned char *made = calloc(s->npsets, 1);
    char err[600];
    int rc = 0;
    if (!ho || !made) { free(ho); free(made); return cli_usage_error("sweep: out of memory"); }
    a->t.ho_seed = (a->nvec > 0 ? a->seed : 1) + 1;
    a->t.ho_rows = s->vs[0]->n_rows;
    for (size_t g = 0; g < s->ngroups && !rc; g++) {
        tb_target_res *x = &a->t.res[g];
        size_t p = s->cfg[g].pset;
        if (!x->met) continue;
        if (!made[p]) {
            if (cli_make_vectors(a->o.u, tb_sweep_pset_cfg(s, p), s->vs[p]->n_rows, a->t.ho_seed, &ho[p], err, sizeof err)) {
                rc = cli_usage_error("held-out stimuli: %s", err);
                break;
            }
            made[p] = 1;
        }
        if (tb_sweep_target_heldout(s, &ho[p], a->t.kind, a->t.value, x, err, sizeof err)) rc = cli_usage_error("%s", err);
        else if (!x->heldout_ok) a->ho_failed = 1;
    }
    for (size_t p = 0; p < s->npsets; p++) if (made[p]) vec_set_free(&ho[p]);
    free(ho);
    free(made);
    return rc;
}

/* Rows (of shard k/n; n = 0: all) that miss the user's acceptance
 * (--max-error/--max-nmse/--max-lsb): a line saying which, counted in
 * *misses; nothing when no acceptance option was given. */
static void print_accept(FILE *f, const tb_sweep *s, int shard_k, int shard_n, size_t *misses)
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

static int outputs(sweep_args *a, tb_sweep *s, double t0, int tty)
{
    char err[600], files[600] = "sweep.csv";
    oset os = { a->dir, 0, { 0 } };
    FILE *csv = oset_open(&os, "sweep.csv");
    if (!csv) return CLI_USAGE;
    tb_sweep_print_csv(s, csv, 0, 0);
    if (a->t.on) {
        a->t.res = calloc(s->ngroups, sizeof *a->t.res);
        if (!a->t.res) { oset_abort(&os); return cli_usage_error("target search: out of memory"); }
        for (size_t g = 0; g < s->ngroups; g++) {
            if (tty) fprintf(stderr, "\rshadesim sweep %s: target search, settings %zu/%zu \033[K", s->spec.u->name, g + 1, s->ngroups);
            int bad = tb_sweep_target(s, g, a->t.kind, a->t.goal, a->threads, &a->t.res[g], err, sizeof err);
            if (tty) fputs("\r\033[K", stderr);
            if (bad) { oset_abort(&os); return cli_usage_error("%s", err); }
        }
        if (heldout_check(a, s)) { oset_abort(&os); return CLI_USAGE; }
    }
    size_t nfront = 0;
    unsigned char *on = front_of(s, &nfront);
    int drawn = 0;
    if (!on) { oset_abort(&os); return cli_usage_error("sweep: out of memory"); }
    if (write_charts(s, &a->t, &os, files, sizeof files, &drawn)) {
        free(on);
        oset_abort(&os);
        return CLI_USAGE;
    }
    /* Files of an earlier sweep in DIR that this one does not write would
     * contradict its sweep.csv: they go, when this set moves in. */
    const char *gone[3];
    int ngone = 0;
    if (!drawn) gone[ngone++] = "cycles_vs_error.svg";
    if (a->t.on) {
        if (write_target_json(s, &a->t, &os) || write_target_csv(s, &a->t, &os)) { free(on); oset_abort(&os); return CLI_USAGE; }
        strncat(files, ", target.json, target.csv", sizeof files - strlen(files) - 1);
    } else {
        gone[ngone++] = "target.json";
        gone[ngone++] = "target.csv";
    }
    strncat(files, ", summary.txt", sizeof files - strlen(files) - 1);

    /* The summary, printed and saved: the same text. */
    char *text = NULL;
    size_t tlen = 0;
    FILE *m = open_memstream(&text, &tlen);
    if (!m) { free(on); oset_abort(&os); return cli_usage_error("sweep: out of memory"); }
    fprintf(m, "sweep %s: %zu configurations (widths %d..%d", s->spec.u->name, s->n, s->spec.wlo, s->spec.whi);
    if (s->ngroups > 1) fprintf(m, " x %zu settings", s->ngroups);
    fprintf(m, "), %zu vectors", s->vs[0]->n_rows);
    if (s->npsets > 1) fputs(" per parameter set", m);
    fprintf(m, ", sweep_id %016llx\n", (unsigned long long)s->id);
    print_table(m, s, on);
    print_accept(m, s, 0, 0, &a->misses);
    print_front(m, s, on, nfront);
    if (a->t.on) print_target(m, s, &a->t);
    fclose(m);
    free(on);
    FILE *sf = oset_open(&os, "summary.txt");
    if (!sf) { free(text); oset_abort(&os); return CLI_USAGE; }
    fputs(text, sf);
    int rc = oset_commit(&os, gone, ngone);
    if (rc == 0) {
        fputs(text, stdout);
        /* Timings are not output (the same inputs give the same bytes): only
         * a terminal's stderr hears how long it took. */
        printf("wrote %s/: %s\n", a->dir, files);
        if (tty) fprintf(stderr, "shadesim sweep %s: %.2f s on %d thread%s\n", s->spec.u->name, now_s() - t0,
                         a->threads, a->threads > 1 ? "s" : "");
    }
    free(text);
    return rc;
}

int cli_sweep(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (is_help(argv[i])) { fputs(sweep_help, stdout); return stdout_done(CLI_OK); }
    sweep_args a;
    if (parse_sweep(argc, argv, &a)) return CLI_USAGE;
    char defdir[300];
    if (!a.dir) {
        snprintf(defdir, sizeof defdir, "out/sweep-%s", a.o.u->name);
        a.dir = defdir;
    }
    tb_sweep s;
    char err[600];
    /* No silent widening: widths below what the unit's integer part needs
     * would all build the same formats; the sweep starts at the smallest
     * honest width and says so, once. */
    int lim;
    unit_cfg limc;
    int wmin = tb_sweep_min_width(&a.sp, &lim, &limc);
    if (wmin > a.sp.wlo) {
        char why[200] = "";
        if (lim >= 0) {
            unit_fmts f;
            limc.width = wmin;
            a.o.u->formats(&limc, &f);
            snprintf(why, sizeof why, " (signal %s's integer part is %c%d)", a.o.u->sigs[lim].name,
                     f.f[lim].is_signed ? 's' : 'u', f.f[lim].ibits);
        }
        if (wmin > a.sp.whi)
            return cli_usage_error("--widths %d:%d: unit %s needs widths >= %d%s", a.sp.wlo, a.sp.whi, a.o.u->name, wmin, why);
        fprintf(stderr, "shadesim: sweep %s: widths below %d are too narrow for its integer part%s; starting at %d\n",
                a.o.u->name, wmin, why, wmin);
        a.sp.wlo = wmin;
    }
    if (tb_sweep_init(&s, &a.sp, err, sizeof err)) return cli_usage_error("%s", err);
    vec_set *sets = calloc(s.npsets, sizeof *sets);
    int rc = CLI_OK;
    if (!sets) { tb_sweep_free(&s); return cli_usage_error("sweep: out of memory"); }
    /* Everything that can be refused is refused before the long part. */
    if (load_vectors(&a, &s, sets) || cli_make_dir(a.dir)) { rc = CLI_USAGE; goto done; }
    tb_sweep_fingerprint(&s);

    progress pr = { a.o.u->name, now_s(), 0, 0 };
    int tty = cli_stderr_tty();
    size_t failed = tb_sweep_run(&s, a.threads, a.shard_k, a.shard_n, tty ? on_progress : NULL, &pr);
    progress_clear(&pr);
    double secs = now_s() - pr.t0;
    /* A configuration the unit cannot be built at (past the top of its
     * width range, say: shadesim list) is "not buildable", a row of the
     * results like any other, not a failed simulation. */
    size_t unbuilt = 0;
    for (size_t i = 0; i < s.n; i++) {
        if (s.row[i].status == TB_OK || s.row[i].status == TB_SWEEP_NOT_RUN) continue;
        int nb = s.row[i].status == TB_BADINPUT;
        unbuilt += (size_t)nb;
        (void)cli_usage_error("%s width %d (configuration %zu)%s: %s", a.o.u->name, s.cfg[i].cfg.width, i,
                              nb ? " not buildable" : "", s.row[i].err);
    }
    failed -= unbuilt;
    if (a.shard_n) {
        char path[4200];
        snprintf(path, sizeof path, "%s/sweep-%d-of-%d.csv", a.dir, a.shard_k, a.shard_n);
        if (tb_sweep_write_csv(&s, path, a.shard_k, a.shard_n, err, sizeof err)) rc = cli_usage_error("%s", err);
        else {
            size_t mine = 0;
            for (size_t i = 0; i < s.n; i++) mine += (size_t)tb_sweep_in_shard(i, a.shard_k, a.shard_n);
            printf("sweep %s shard %d/%d: %zu of %zu configurations, sweep_id %016llx\n", a.o.u->name,
                   a.shard_k, a.shard_n, mine, s.n, (unsigned long long)s.id);
            print_accept(stdout, &s, a.shard_k, a.shard_n, &a.misses);
            printf("wrote %s\n", path);
            if (tty) fprintf(stderr, "shadesim sweep %s: %.2f s\n", a.o.u->name, secs);
        }
    } else {
        rc = outputs(&a, &s, pr.t0, tty);
    }
    if (rc == CLI_OK && (failed || a.misses || a.ho_failed)) rc = CLI_FAIL;
done:
    for (size_t p = 0; p < s.npsets; p++) vec_set_free(&sets[p]);
    free(sets);
    free(a.t.res);
    tb_sweep_free(&s);
    return rc == CLI_USAGE ? rc : stdout_done(rc);
}

/* ---------------------------------------------------------------- merge */

int cli_merge(int argc, char **argv)
{
    const char *out = NULL;
    const char **in = calloc((size_t)argc, sizeof *in);
    int n = 0;
    if (!in) return cli_usage_error("merge: out of memory");
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (is_help(argv[i])) { free(in); fputs(merge_help, stdout); return stdout_done(CLI_OK); }
        if (opt("-o", argc, argv, &i, &v)) {
            if (!v || !*v) { free(in); return cli_usage_error("-o needs a file name"); }
            out = v;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            free(in);
            return cli_usage_error("merge: unknown option '%s' (see shadesim merge --help)", argv[i]);
        } else in[n++] = argv[i];
    }
    int rc = CLI_OK;
    char err[800];
    if (!n) rc = cli_usage_error("merge: which CSV files? (shadesim merge A.csv B.csv -o OUT.csv)");
    else if (!out) rc = cli_usage_error("merge: -o OUT.csv is required");
    else if (tb_sweep_merge(in, n, out, err, sizeof err)) rc = cli_usage_error("%s", err);
    free(in);
    return rc == CLI_USAGE ? rc : stdout_done(rc);
}
