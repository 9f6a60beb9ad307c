/* cli_scene.c - shadesim scene: a scene rendered through the simulated
 * span hardware; images, JSON and a table of the figures; the format
 * search (--target-nmse), the sweep (--sweep) and the side-by-side of the
 * paper's configuration and a corrected one (--compare). */
#include "testbench/cli/cli.h"
#include "base/base_join.h"
#include "base/base_near.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/study/tb_scene.h"
#include "testbench/study/tb_scene_search.h"
#include "testbench/study/tb_scene_pipes.h"
#include "testbench/tb_widths.h"
#include "base/base_out.h"
#include "units/unit_net.h"
#include <sys/stat.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The divide-by-3 network's terms that the corrected configuration of
 * --compare uses: the fewest that keep the default face scene's NMSE under
 * 1e-4 (measured with shadesim scene face --set terms=N; docs/scenes.md). */
#define COMPARE_TERMS 5
#define COMPARE_TARGET 1e-4

typedef struct scene_args {
    const char *what, *dir, *vcd, *sweep_spec;
    const char *sets[256];
    int nsets, json, jobs, heldout, sweep, cmp, no_batch;
    double max_nmse, target;
} scene_args;

static int o_set(void *base, const char *opt, const char *v)
{
    scene_args *a = base;
    (void)opt;
    if (a->nsets == 256) return cli_usage_error("--set: at most 256");
    a->sets[a->nsets++] = v;
    return 0;
}

static int o_target(void *base, const char *opt, const char *v)
{
    scene_args *a = base;
    if (cli_parse_real(opt, v, 0, HUGE_VAL, "a number >= 0", &a->target)) return CLI_USAGE;
    if (a->target <= 0) return cli_usage_error("--target-nmse %s: expected a number > 0", v);
    return 0;
}

static int o_sweep(void *base, const char *opt, const char *v)
{
    scene_args *a = base;
    (void)opt;
    a->sweep = 1;
    if (v) a->sweep_spec = v;
    return 0;
}

static int scene_arg(void *base, const char *arg)
{
    scene_args *a = base;
    if (a->what) return cli_usage_error("scene: one scene at most ('%s' and '%s')", a->what, arg);
    a->what = arg;
    return 0;
}

#define SC_FLAG(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_FLAG, offsetof(scene_args, FIELD), 0, 0, NULL, NULL, NULL, 0, HELP }
static const cli_opt scene_tab[] = {
    { "--set", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs KEY=VALUE", o_set, 0,
      "  --set KEY=VALUE  set a scene key as a line of the file would (repeatable,\n"
      "                   applied after the file), e.g. --set policy=cubic-n1\n"
      "                   --set terms=5 --set resolution=256x256 --set light=...\n" },
    { "-o", NULL, CLI_OPT_STR, offsetof(scene_args, dir), 0, 0, NULL, "%s needs a folder", NULL, 0,
      "  -o DIR           output folder (default out/scene-NAME; created). It gets\n"
      "                   ref.png (per-pixel shading), hw.png (the hardware's pixels),\n"
      "                   err-xK.png (|hw - ref| heat map, full white = 1/K; K in\n"
      "                   4^0..4^6, the largest that shows the maximum error),\n"
      "                   degree.png (degree of each interval), region.png (mesh\n"
      "                   regions), ref-hw.png and hw-nodes.png (the reference\n"
      "                   and the method with its nodes on the shade unit) and\n"
      "                   scene.json (the figures, and under \"legend\" the\n"
      "                   colours of the maps)\n" },
    SC_FLAG("--json", json, "  --json           print the JSON summary on stdout instead of the table\n"),
    { "-j", NULL, CLI_OPT_INT, offsetof(scene_args, jobs), 1, 256, NULL, "%s needs a number of threads", NULL, 0,
      "  -j N             threads (default: the machine's cores); the output is the\n"
      "                   same for any N\n" },
    SC_FLAG("--no-batch", no_batch,
      "  --no-batch       simulate each band of rows on the event-driven kernel alone\n"
      "                   (default: the bands side by side as lanes of the batch\n"
      "                   mode, levelized; the output is the same bytes either way)\n"),
    SC_FLAG("--heldout", heldout, "  --heldout        render the scene's held-out view (other camera and light)\n"),
    { "--vcd", NULL, CLI_OPT_STR, offsetof(scene_args, vcd), 0, 0, NULL, "%s needs a file name", NULL, 0,
      "  --vcd FILE       VCD of the hardware of the first band of rows that has spans\n" },
    { "--max-nmse", NULL, CLI_OPT_REAL, offsetof(scene_args, max_nmse), 0, HUGE_VAL, "a number >= 0",
      "%s needs a number", NULL, 0, "  --max-nmse X     exit status 1 when the NMSE exceeds X\n" },
    { "--target-nmse", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs a number", o_target, 0,
      "  --target-nmse X  find the smallest per-signal formats that keep the NMSE\n"
      "                   under X, check them on the held-out view, report the area\n"
      "                   saved against the smallest uniform width (exit 1: not met);\n"
      "                   DIR gets search.txt, search.json and found/ (the images\n"
      "                   and scene.json of the render at the found formats)\n" },
    { "--sweep", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, o_sweep, CLI_OPT_MAYBE,
      "  --sweep [GRID]   sweep L, policy, terms, width, schedule: CSV and SVG charts\n"
      "                   of NMSE against operations and clocks per pixel, Pareto\n"
      "                   front, and both pipelines in hardware against the shade\n"
      "                   unit's widths and schedules; GRID like \"L=4,8;terms=3,5\"\n"
      "                   (default grid)\n" },
    SC_FLAG("--compare", cmp,
      "  --compare        the scene twice: the paper's configuration (adaptive-region,\n"
      "                   3-term /3 network) and a corrected one (enough terms for\n"
      "                   NMSE <= 1e-4), and adaptive-auto; a table, then both\n"
      "                   pipelines in hardware for each; images in DIR/*/\n"),
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_scene_spec = {
    "scene", { scene_tab }, scene_arg, 1, "scene: unknown option '%s' (see shadesim scene --help)",
    "usage: shadesim scene [NAME|FILE] [options]\n\n"
    "Renders a scene through the simulated interpolation hardware: every span of\n"
    "every row is cut into intervals of L pixels whose node intensities are shaded\n"
    "exactly; the span unit of the scene's policy (linear, quadratic, cubic with\n"
    "node set N1 or N2, or degree 2/3 adaptive) interpolates every pixel clock by\n"
    "clock at the scene's fixed-point formats. Prints NMSE, PSNR, errors on 8 bits,\n"
    "clocks per pixel, area, the span unit's critical path, f_max, pixels per\n"
    "second and energy per pixel; both pipelines in hardware: the per-pixel\n"
    "reference on the shade unit, and the method with its nodes shaded on it\n"
    "(NMSE, clocks per pixel, area, f_max, M pixels/s, per kGE, pJ per pixel;\n"
    "docs/scenes.md); and the operations per pixel, by kind, of the\n"
    "method and of an efficient per-pixel shader (work constant over the frame\n"
    "done once), with two speed-ups: all operations weighted, and the long ones\n"
    "(div, sqrt, pow) alone.\n\n"
    "NAME is a built-in scene: face (default), sphere, torus. Anything else is a\n"
    "scene file (key value lines, docs/scenes.md); write ./face for a file of that\n"
    "name.\n\n"
    "options:\n",
    "\nMetrics over covered pixels: NMSE = sum (hw - ref)^2 / sum ref^2 on the\n"
    "hardware's raw output (not clamped); 8-bit values round(255 clamp(v)) give\n"
    "PSNR, the largest 8-bit error and the share of pixels whose 8-bit value\n"
    "differs. Operation counts and cost weights: docs/scenes.md (scene key cost).\n\n"
    "exit status: 0 done, 1 NMSE over --max-nmse / target not met / simulation\n"
    "failed, 2 bad usage or input (a bad scene file names FILE:LINE).\n"
};

static int is_builtin(const char *name)
{
    for (const char *const *n = scn_desc_builtin_names; *n; n++) if (!strcmp(*n, name)) return 1;
    return 0;
}

static int mesh_is_builtin(const char *name)
{
    for (const char *const *n = scn_mesh_builtin_names; *n; n++) if (!strcmp(*n, name)) return 1;
    return 0;
}

/* out/scene-NAME: NAME is the built-in's name or the file's base name
 * without its extension. */
static void default_dir(const char *what, char *buf, size_t len)
{
    const char *b = strrchr(what, '/');
    b = b ? b + 1 : what;
    const char *dot = strrchr(b, '.');
    int n = dot && dot != b ? (int)(dot - b) : (int)strlen(b);
    snprintf(buf, len, "out/scene-%.*s", n, b);
}

static void fmt_nmse(char *buf, size_t len, double v)
{
    if (isfinite(v)) snprintf(buf, len, "%.3e", v);
    else snprintf(buf, len, "inf");
}

static void fmt_psnr(char *buf, size_t len, double v)
{
    if (isfinite(v)) snprintf(buf, len, "%.2f dB", v);
    else snprintf(buf, len, "inf");
}

/* The operations per pixel of the reference and of the method, the cost
 * weights, and the two speed-ups, each the ratio of the figures printed
 * above it (docs/scenes.md, "Operation counts"). */
/* A speed-up as the table prints it: "2.04x", or "nan" where the ratio is
 * not defined (all-zero weights: 0 / 0; docs/cli.md's rule, not "-nanx") */
static void speedup_text(char *a, size_t n, double v)
{
    if (isnan(v)) snprintf(a, n, "nan");
    else if (isinf(v)) snprintf(a, n, "%s", v > 0 ? "inf" : "-inf");
    else snprintf(a, n, "%.2fx", v);
}

static void print_ops(FILE *f, const scn_desc *d, const tb_scene_result *r)
{
    const double *row[3] = { r->ops_ref, r->ops_hw, d->cost };
    static const char *const name[3] = { "reference", "method", "weight" };
    fprintf(f, "  %-20s", "operations / pixel");
    for (int k = 0; k < SCN_OP__COUNT; k++) fprintf(f, " %8s", scn_op_name[k]);
    fprintf(f, " %10s %9s\n", "weighted", "long ops");
    for (int i = 0; i < 3; i++) {
        fprintf(f, "    %-18s", name[i]);
        for (int k = 0; k < SCN_OP__COUNT; k++) fprintf(f, i < 2 ? " %8.3f" : " %8g", row[i][k]);
        if (i < 2) fprintf(f, " %10.3f %9.3f", i ? r->cost_hw : r->cost_ref, i ? r->long_hw : r->long_ref);
        fputc('\n', f);
    }
    char a[32];
    speedup_text(a, sizeof a, r->speedup);
    fprintf(f, "  %-22s %-14s weighted cost, reference / method: %.3f / %.3f\n", "speed-up (weighted)", a,
            r->cost_ref, r->cost_hw);
    speedup_text(a, sizeof a, r->speedup_long);
    fprintf(f, "  %-22s %-14s div + sqrt + pow, unweighted, reference / method: %.3f / %.3f\n",
            "speed-up (long ops)", a, r->long_ref, r->long_hw);
}

static void print_table(FILE *f, const scn_desc *d, const tb_scene_result *r, const char *dir, double max_nmse)
{
    char a[64], b[64];
    const unit_desc *u = r->unit;
    fprintf(f, "scene %s %dx%d, %s view; policy %s, L %d, /3 network %d terms (%s series), width %d, schedule %s\n",
            d->mesh, r->w, r->h, r->heldout ? "held-out" : "main", scn_policy_name(d->policy), r->cfg.L,
            r->cfg.terms, r->cfg.series == DIV3_QUARTER ? "quarter" : "paper", r->cfg.width, u->sched[r->cfg.schedule].name);
    if (!r->covered) fputs("  (nothing covered: the camera sees no part of the mesh)\n", f);
    fmt_nmse(a, sizeof a, r->nmse);
    fprintf(f, "  %-22s %-14s %s\n", "NMSE", a,
            "sum (hw - ref)^2 / sum ref^2 over covered pixels (raw; verdicts use it)");
    fmt_nmse(a, sizeof a, r->nmse8);
    fprintf(f, "  %-22s %-14s %s\n", "NMSE 8-bit", a, "the same on the 8-bit values of ref.png and hw.png");
    if (max_nmse >= 0) {
        snprintf(a, sizeof a, "%.3e", max_nmse);
        fprintf(f, "  %-22s %-14s %s\n", "target (--max-nmse)", a,
                r->nmse <= max_nmse ? "meets your target" : "does NOT meet your target");
    }
    fmt_psnr(a, sizeof a, r->psnr);
    fprintf(f, "  %-22s %-14s %s\n", "PSNR", a, "on 8-bit values round(255 clamp(v))");
    snprintf(a, sizeof a, "%.3g", r->max_abs_err);
    fprintf(f, "  %-22s %-14s %s\n", "max |hw - ref|", a, "intensity, full scale 1");
    snprintf(a, sizeof a, "%d", r->max_err8);
    snprintf(b, sizeof b, "%.2f%%", 100 * r->diff8_share);
    fprintf(f, "  %-22s %-14s pixels whose 8-bit value differs: %s\n", "max 8-bit error", a, b);
    snprintf(a, sizeof a, "%zu", r->covered);
    fprintf(f, "  %-22s %-14s spans %zu, intervals %zu (degree 2: %.1f%%), nodes shaded %zu\n", "covered pixels", a,
            r->spans, r->intervals, 100 * r->deg2_share, r->nodes_shaded);
    snprintf(a, sizeof a, "%.3f", r->clocks_per_pixel);
    fprintf(f, "  %-22s %-14s %llu clocks of unit %s, overflows %llu\n", "clocks / pixel", a,
            (unsigned long long)r->hwst.clocks, u->name, (unsigned long long)r->hwst.overflows);
    snprintf(a, sizeof a, "%.0f GE", r->hwst.area_ge);
    fprintf(f, "  %-22s %-14s %s\n", "area", a, "gate equivalents of the instantiated unit");
    tb_scene_speed_print(f, r);
    tb_scene_pipes_print(f, r->pipes);
    print_ops(f, d, r);
    if (dir) fprintf(f, "  %-22s %s/ (ref.png hw.png err-x%d.png degree.png region.png%s, the maps' keys "
                        "*-key.svg, scene.json)\n", "images", dir,
                     tb_scene_err_scale(r), r->pipes && r->pipes->ok ? " ref-hw.png hw-nodes.png" : "");
}

/* Load the description's mesh (built-in name or OBJ path). */
static int load_mesh(const scn_desc *d, scn_mesh *m)
{
    char err[600];
    int rc = mesh_is_builtin(d->mesh) ? scn_mesh_builtin(d->mesh, d->detail, m, err, sizeof err)
                                      : scn_mesh_obj(d->mesh, m, err, sizeof err);
    static const char *const keys[] = { "mesh", "detail", NULL };
    char where[300];
    if (!rc) return 0;
    cli_usage_error("%s%s", scn_desc_where(d, keys, where, sizeof where), err);
    return -1;
}

/* A refusal of the scene's unit (tb_scene_unit, tb_build), named at the
 * line of the key that set the value last: exit status 2. */
static int unit_error(const scn_desc *d, const char *err)
{
    static const char *const sched[] = { "schedule", "policy", NULL };
    static const char *const fmts[] = { "fmt", "width", "L", "terms", "series", "policy", NULL };
    char where[300], pk[16];
    const char *param[] = { pk, NULL };
    const char *const *keys = strstr(err, "schedule") ? sched : fmts;
    /* a unit parameter's own message names it: "parameter L: ..." */
    if (!strncmp(err, "parameter ", 10)) {
        snprintf(pk, sizeof pk, "%.*s", (int)strcspn(err + 10, ":"), err + 10);
        keys = param;
    }
    /* and a setting every unit has, "round: ..." (tb_scene_cfg) */
    static const char *const own[] = { "width", "round", "overflow", "unit" };
    for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
        if (!strncmp(err, own[k], strlen(own[k])) && err[strlen(own[k])] == ':') {
            snprintf(pk, sizeof pk, "%s", own[k]);
            keys = param;
        }
    return cli_usage_error("%s%s", scn_desc_where(d, keys, where, sizeof where), err);
}

/* The scene's width against every unit a render builds at it besides its
 * span unit: the per-pixel shader and the divider that bounds the
 * reference. Past one's range: one line at the width key's line, exit 2
 * (a width of 63 failed deep in the divider, naming an option the scene
 * does not have). 0, or -1 after the message. */
static int width_error(const scn_desc *d, const unit_cfg *span)
{
    const unit_desc *us[] = { tb_scene_pipes_unit(d), unit_find("div") };
    static const char *const what[] = { "the per-pixel shader", "the reference's divider bound" };
    for (size_t k = 0; k < sizeof us / sizeof us[0]; k++) {
        if (!us[k]) continue;
        unit_cfg c;
        char msg[400];
        unit_cfg_default(us[k], &c);
        c.width = span->width;
        if (!tb_width_refuse(us[k], &c, msg, sizeof msg)) continue;
        static const char *const keys[] = { "width", NULL };
        char where[300];
        cli_usage_error("%swidth %d: %s (%s)", scn_desc_where(d, keys, where, sizeof where), span->width, msg, what[k]);
        return -1;
    }
    return 0;
}

static void progress(const char *what)
{
    if (cli_stderr_tty()) fprintf(stderr, "\r%-70s\r", what);
}

/* --compare's second table: both pipelines in hardware, the reference
 * once (its rows are the same in every configuration) and each
 * configuration's method, against the reference at the same schedule. */
static void print_pipes_compare(const char *const *names, const tb_scene_pipes *pp, int n)
{
    if (!n || !pp[0].ok) {
        printf("both pipelines: %s\n", n ? pp[0].why : "none");
        return;
    }
    printf("\nboth pipelines in hardware (unit %s, width %d, %s %d; per-pixel: the reference on it; node+span: the "
           "method, its nodes on it):\n",
           pp[0].unit, pp[0].width, strcmp(pp[0].unit, "shade") ? "g" : "n", pp[0].n);
    printf("%-10s %-9s %-9s %5s %11s %10s %9s %9s %8s %10s %7s %9s\n", "config", "side", "schedule", "spans", "NMSE",
           "clocks/px", "area GE", "f_max", "Mpx/s", "Mpx/s/kGE", "pJ/px", "vs ref.");
    for (int c = -1; c < n; c++)
        for (int i = 0; i < pp[c < 0 ? 0 : c].nrows; i++) {
            const tb_pipe_row *w = &pp[c < 0 ? 0 : c].row[i];
            if (w->method != (c >= 0)) continue;
            const tb_pipe_row *ref = tb_scene_pipes_ref(&pp[c < 0 ? 0 : c], w->sched);
            char k[16] = "-", a[32], v[32] = "";
            if (w->method) {
                snprintf(k, sizeof k, "%d", w->spans);
                snprintf(v, sizeof v, "%.3gx", ref ? w->pps_per_kge / ref->pps_per_kge : NAN);
            }
            fmt_nmse(a, sizeof a, w->nmse);
            printf("%-10s %-9s %-9s %5s %11s %10.3f %9.0f %5.0f MHz %8.4g %10.4g %7.3g %9s  %s\n",
                   c < 0 ? "-" : names[c], w->method ? "node+span" : "per-pixel", w->sched, k, a, w->clocks_per_pixel,
                   w->area_ge, w->fmax_mhz, w->pixels_per_s / 1e6, w->pps_per_kge / 1e6, w->pj_per_pixel, v,
                   w->nmse <= COMPARE_TARGET ? "NMSE <= 1e-4" : "NMSE > 1e-4");
        }
    printf("vs ref.: the method's pixels/s per kGE over the reference's at the same schedule (the area at equal\n"
           "pixels/s is its inverse; energy per pixel does not change with the copies)\n");
}

/* --compare: the paper's configuration next to the corrected ones. */
static int compare(const scn_desc *d0, const scn_mesh *m, int jobs, int no_batch, const char *dir, int json)
{
    static const struct { const char *name; int policy, terms; } cfgs[] = {
        { "paper", SCN_POL_ADAPTIVE_REGION, 3 },
        { "corrected", SCN_POL_ADAPTIVE_REGION, COMPARE_TERMS },
        { "auto", SCN_POL_ADAPTIVE_AUTO, COMPARE_TERMS },
    };
    enum { N = sizeof cfgs / sizeof cfgs[0] };
    const char *names[N];
    tb_scene_pipes pp[N];
    int n = 0, rc = CLI_OK;
    if (json) puts("[");
    else printf("%-10s %-46s %11s %11s %10s %9s %9s %13s %9s %8s %9s %7s\n", "config", "policy, divide-by-3 network",
                "NMSE", "NMSE 8-bit", "PSNR", "speed-up", "long ops", "clocks/pixel", "area GE", "f_max", "Mpx/s", "pJ/px");
    double ref_max = NAN, ref_e = NAN;
    for (int i = 0; i < N && rc == CLI_OK; i++) {
        scn_desc d = *d0;
        d.policy = (scn_policy)cfgs[i].policy;
        snprintf(d.terms, sizeof d.terms, "%d", cfgs[i].terms);
        if (i == 0) snprintf(d.series, sizeof d.series, "paper");   /* the paper's x/2 - x/8 - x/32 - x/128 */
        tb_scene_opts o = { jobs, 0, NULL, NULL, no_batch, 1, NULL, NULL };
        tb_scene_result r;
        char err[600], sub[4200];
        progress(cfgs[i].name);
        int t = tb_scene_render_pipes(&d, m, NULL, &o, TB_PIPES_BOTH, &r, &pp[n], err, sizeof err);
        progress("");
        if (t != TB_OK) { rc = cli_from_tb(t, "%s", err); break; }
        names[n++] = cfgs[i].name;
        ref_max = r.speed.ref_pixels_per_s_max;
        ref_e = r.speed.ref_energy_pj_per_pixel_min;
        snprintf(sub, sizeof sub, "%s/%s", dir, cfgs[i].name);
        if (tb_scene_write(&d, &r, sub, err, sizeof err)) rc = cli_usage_error("%s", err);
        else if (json) {
            printf("%s", i ? ",\n" : "");
            tb_scene_json(stdout, &d, &r);
        } else {
            char a[32], a8[32], b[32], what[64];
            fmt_nmse(a, sizeof a, r.nmse);
            fmt_nmse(a8, sizeof a8, r.nmse8);
            fmt_psnr(b, sizeof b, r.psnr);
            char sw[32], sl[32];
            speedup_text(sw, sizeof sw, r.speedup);
            speedup_text(sl, sizeof sl, r.speedup_long);
            snprintf(what, sizeof what, "%s, /3 network %d terms", scn_policy_name(d.policy), r.cfg.terms);
            printf("%-10s %-46s %11s %11s %10s %9s %9s %13.3f %9.0f %4.0f MHz %9.4g %7.3g  %s\n", cfgs[i].name,
                   what, a, a8, b, sw, sl, r.clocks_per_pixel, r.hwst.area_ge, r.speed.hw.fmax_mhz,
                   r.speed.pixels_per_s / 1e6, r.speed.energy_pj_per_pixel,
                   r.nmse <= COMPARE_TARGET ? "NMSE <= 1e-4" : "NMSE > 1e-4");
        }
        tb_scene_free(&r);
    }
    if (rc == CLI_OK && json) puts("]");
    else if (rc == CLI_OK) {
        printf("verdicts on NMSE of the raw output (exact nodes); NMSE 8-bit is that of the images' 8-bit values\n");
        if (!pp[0].ok)     /* the reference unmeasured: the divider bounds it */
            printf("reference: <= %.4g M pixels/s, >= %.3g pJ/pixel (its divides on unit div; docs/scenes.md)\n",
                   ref_max / 1e6, ref_e);
        print_pipes_compare(names, pp, n);
        printf("images: %s/{paper,corrected,auto}/ (ref.png hw.png err-x*.png degree.png region.png ref-hw.png "
               "hw-nodes.png *-key.svg scene.json)\n", dir);
    }
    for (int i = 0; i < n; i++) tb_scene_pipes_free(&pp[i]);
    return rc;
}

/* -j when not given: one thread a core online (the output is the same
 * for any -j), at most the option's own limit. */
static int default_jobs(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

int cli_scene(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_scene_spec);
    scene_args sa;
    memset(&sa, 0, sizeof sa);
    sa.jobs = default_jobs();
    sa.max_nmse = sa.target = -1;
    void *base[] = { &sa };
    if (cli_opt_parse(&cli_scene_spec, base, argc, argv, 1)) return CLI_USAGE;
    const char *what = sa.what, *dir = sa.dir, *vcd = sa.vcd, *sweep_spec = sa.sweep_spec;
    const char *const *sets = sa.sets;
    int nsets = sa.nsets, json = sa.json, jobs = sa.jobs, heldout = sa.heldout, sweep = sa.sweep, cmp = sa.cmp;
    int no_batch = sa.no_batch;
    double max_nmse = sa.max_nmse, target = sa.target;
    if ((target > 0) + sweep + cmp > 1) return cli_usage_error("scene: --target-nmse, --sweep and --compare go one at a time");
    if (!what) what = "face";

    scn_desc d;
    char err[600];
    if (is_builtin(what)) {
        scn_desc_builtin(what, &d);
    } else if (scn_desc_read(what, &d, err, sizeof err)) {
        /* A bare word that is no file was meant as a built-in scene. */
        struct stat st;
        if (!strchr(what, '/') && !strchr(what, '.') && stat(what, &st) != 0) {
            char list[200] = "";
            for (const char *const *n = scn_desc_builtin_names; *n; n++) base_join_add(list, sizeof list, ", ", *n);
            size_t nb = 0;
            while (scn_desc_builtin_names[nb]) nb++;
            const char *near = base_near(what, scn_desc_builtin_names, nb);
            if (near) return cli_usage_error("scene: no built-in scene or scene file '%s' (did you mean '%s'? built-in: %s)",
                                             what, near, list);
            return cli_usage_error("scene: no built-in scene or scene file '%s' (built-in: %s)", what, list);
        }
        return cli_usage_error("%s", err);
    }
    for (int k = 0; k < nsets; k++) {
        const char *eq = strchr(sets[k], '=');
        if (!eq || eq == sets[k]) return cli_usage_error("--set %s: expected KEY=VALUE", sets[k]);
        char key[64];
        if ((size_t)(eq - sets[k]) >= sizeof key) return cli_usage_error("--set %s: no such key", sets[k]);
        snprintf(key, sizeof key, "%.*s", (int)(eq - sets[k]), sets[k]);
        if (scn_desc_set(&d, key, eq + 1, err, sizeof err)) return cli_usage_error("--set %s: %s", sets[k], err);
    }
    char dbuf[4096];
    if (!dir) { default_dir(what, dbuf, sizeof dbuf); dir = dbuf; }

    /* the unit and formats first: a bad format is a usage error before any work */
    const unit_desc *u;
    unit_cfg cfg;
    unit_fmts fm;
    if (scn_desc_check_camera(&d, err, sizeof err)) return cli_usage_error("%s", err);
    int bad = tb_scene_unit(&d, &u, &cfg, &fm, err, sizeof err);
    if (!bad) {
        /* the unit built once, so that what it refuses (t must hold 1, ...)
         * is named at the scene line too, before any work */
        tb_built b;
        bad = tb_build(u, &cfg, &fm, &b, err, sizeof err);
        sim_free(b.c);
    }
    if (bad) return unit_error(&d, err);
    if (width_error(&d, &cfg)) return CLI_USAGE;

    scn_mesh m;
    if (load_mesh(&d, &m)) return CLI_USAGE;
    int rc = CLI_OK;
    /* Every file of the run (--compare's three folders, --sweep's and
     * --target-nmse's files, a render's images and VCD) is one set. */
    base_outset *set = base_outset_begin();
    if (!set) base_out_of_memory();
    if (cmp) {
        rc = compare(&d, &m, jobs, no_batch, dir, json);
    } else if (target > 0 || sweep) {
        progress(sweep ? "sweeping..." : "searching formats...");
        int t = sweep ? tb_scene_sweep(&d, &m, jobs, no_batch, sweep_spec, dir, json, stdout, NULL, err, sizeof err)
                      : tb_scene_search(&d, &m, jobs, no_batch, target, dir, json, stdout, NULL, err, sizeof err);
        progress("");
        rc = cli_from_tb(t, "%s", err);
    } else {
        tb_scene_opts o = { jobs, heldout, vcd, NULL, no_batch, 1, NULL, NULL };
        tb_scene_result r;
        tb_scene_pipes pp;
        progress("rendering...");
        int t = tb_scene_render_pipes(&d, &m, NULL, &o, TB_PIPES_BOTH, &r, &pp, err, sizeof err);
        progress("");
        if (t != TB_OK) {
            rc = cli_from_tb(t, "%s", err);
        } else {
            if (tb_scene_write(&d, &r, dir, err, sizeof err)) rc = cli_usage_error("%s", err);
            else {
                if (json) tb_scene_json(stdout, &d, &r);
                else print_table(stdout, &d, &r, dir, max_nmse);
                if (max_nmse >= 0 && !(r.nmse <= max_nmse)) rc = CLI_FAIL;
            }
            tb_scene_free(&r);
            tb_scene_pipes_free(&pp);
        }
    }
    /* a missed target (exit 1) still writes its files: they are data */
    if (rc == CLI_USAGE) base_outset_abort(set);
    else if (base_outset_commit(set, err, sizeof err)) rc = cli_usage_error("%s", err);
    scn_mesh_free(&m);
    if (base_out_stdout_check(err, sizeof err)) return cli_usage_error("%s", err);
    return rc;
}
