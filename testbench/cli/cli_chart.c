/* cli_chart.c - the verb chart: a sweep's charts from its CSV (sweep.csv,
 * a shard's, or merge's), the same bytes the sweep itself draws. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include <stddef.h>
#include "testbench/study/tb_sweep_chart.h"
#include "testbench/study/tb_sweep.h"
#include "base/base_line.h"
#include "base/base_out.h"
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct chart_args { const char *csv, *dir; int png; } chart_args;

static int chart_csv(void *base, const char *arg)
{
    chart_args *a = base;
    if (a->csv) return cli_usage_error("chart: one CSV at a time (shadesim merge joins shards)");
    a->csv = arg;
    return 0;
}

static const cli_opt chart_tab[] = {
    { "-o", NULL, CLI_OPT_STR, offsetof(chart_args, dir), 0, 0, NULL, "chart: -o needs a folder", NULL, CLI_OPT_NONEMPTY,
      "  -o DIR               output folder (default: the CSV's folder), made if missing\n" },
    { "--png", NULL, CLI_OPT_FLAG, offsetof(chart_args, png), 0, 0, NULL, NULL, NULL, 0,
      "  --png                also write each chart as CHART.png with rsvg-convert\n"
      "                       (an error when rsvg-convert is not installed)\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_chart_spec = {
    "chart", { chart_tab }, chart_csv, 1, "chart: unknown option '%s' (see shadesim chart --help)",
    "usage: shadesim chart SWEEP.csv [-o DIR] [--png]\n\n"
    "Draws a sweep's charts from its CSV: sweep.csv, a shard's CSV or the CSV\n"
    "that shadesim merge joins from shards. The charts are the bytes the sweep\n"
    "itself writes (without its target search's marks):\n"
    "  error_vs_width.svg   max |e| (line) and RMS e (dashed) against width\n"
    "  area_vs_error.svg    area against max error, the Pareto front ringed\n"
    "  cycles_vs_error.svg  clocks per pixel against max error (when they vary)\n"
    "  throughput_vs_error.svg  pixels per second at f_max against max error\n"
    "  energy_vs_error.svg  energy per pixel against max error\n"
    "The Pareto front: configurations that no other matches in max error, area\n"
    "and pixels per second while beating it in one. Up to 7 settings groups get a\n"
    "colour each; more are coloured by the setting with the most values (a scale\n"
    "when it has more than 7) and shaped by a second one.\n\n"
    "options:\n",
    "\nexit status: 0 done, 2 bad usage, an unreadable or malformed CSV, an\n"
    "unwritable DIR or a failed PNG conversion\n"
};


/* Is prog on PATH? */
static int on_path(const char *prog)
{
    const char *path = getenv("PATH");
    char buf[4200];
    for (const char *p = path ? path : "/usr/bin:/bin"; *p;) {
        size_t k = strcspn(p, ":");
        snprintf(buf, sizeof buf, "%.*s/%s", (int)k, k ? p : ".", prog);
        if (access(buf, X_OK) == 0) return 1;
        p += k;
        if (*p) p++;
    }
    return 0;
}

/* svg -> png with rsvg-convert (no shell), its output into a base_out so
 * that the PNG appears only when complete. */
static int to_png(const char *svg, const char *png)
{
    char err[600];
    base_out *o = base_out_open(png, err, sizeof err);
    if (!o) return cli_usage_error("%s", err);
    FILE *f = base_out_file(o);
    fflush(f);
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0) { base_out_abort(o); return cli_usage_error("%s: cannot start rsvg-convert: %s", png, strerror(errno)); }
    if (pid == 0) {
        if (dup2(fileno(f), 1) < 0) _exit(126);
        execlp("rsvg-convert", "rsvg-convert", base_out_pending(svg), (char *)NULL);
        _exit(127);
    }
    int st;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) { base_out_abort(o); return cli_usage_error("%s: rsvg-convert: %s", png, strerror(errno)); }
    if (!WIFEXITED(st) || WEXITSTATUS(st)) { base_out_abort(o); return cli_usage_error("%s: rsvg-convert failed", png); }
    if (base_out_close(o, err, sizeof err)) return cli_usage_error("%s", err);
    return CLI_OK;
}

int cli_chart(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_chart_spec);
    chart_args ca = { NULL, NULL, 0 };
    void *base[] = { &ca };
    if (cli_opt_parse(&cli_chart_spec, base, argc, argv, 1)) return CLI_USAGE;
    const char *csv = ca.csv, *dir = ca.dir;
    int png = ca.png;
    if (!csv) return cli_usage_error("chart: which CSV? (shadesim chart out/sweep-UNIT/sweep.csv)");
    if (png && !on_path("rsvg-convert"))
        return cli_usage_error("chart: --png needs rsvg-convert, which is not installed (Debian: librsvg2-bin)");
    char defdir[4096];
    if (!dir) {
        const char *sl = strrchr(csv, '/');
        if (!sl || !strcmp(csv, "-")) snprintf(defdir, sizeof defdir, ".");
        else snprintf(defdir, sizeof defdir, "%.*s", (int)(sl - csv) ? (int)(sl - csv) : 1, csv);
        dir = defdir;
    }
    size_t len = 0;
    char err[800];
    char *text = base_text_read(csv, TB_SWEEP_MAX_LINE, &len, err, sizeof err);
    if (!text) return cli_usage_error("%s", err);
    tb_sc *sc = tb_sc_read(text, len, csv, err, sizeof err);
    free(text);
    if (!sc) return cli_usage_error("%s", err);
    if (cli_make_dir(dir)) { tb_sc_free(sc); return CLI_USAGE; }
    int rc = CLI_OK;
    /* the charts (and PNGs) are one set: all appear, or none */
    base_outset *set = base_outset_begin();
    if (!set) base_out_of_memory();
    for (int k = 0; k < TB_SC_NCHARTS && rc == CLI_OK; k++) {
        if (!tb_sc_chart_drawn(sc, k)) continue;
        char path[4200], ppath[4200];
        snprintf(path, sizeof path, "%s/%s", dir, tb_sc_chart_file[k]);
        chart *c = tb_sc_chart(sc, k, NULL);
        if (!c) base_out_of_memory();
        if (chart_write(c, path, err, sizeof err)) rc = cli_usage_error("%s", err);
        chart_free(c);
        if (rc) break;
        printf("wrote %s\n", path);
        if (png) {
            snprintf(ppath, sizeof ppath, "%.*s.png", (int)(strlen(path) - 4), path);
            rc = to_png(path, ppath);
            if (rc == CLI_OK) printf("wrote %s\n", ppath);
        }
    }
    tb_sc_free(sc);
    if (rc == CLI_OK && base_outset_commit(set, err, sizeof err)) rc = cli_usage_error("%s", err);
    else if (rc != CLI_OK) base_outset_abort(set);
    char e[300];
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return rc;
}
