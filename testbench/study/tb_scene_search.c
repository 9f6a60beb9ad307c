/* tb_scene_search.c - the smallest formats a scene needs, found by
 * rendering it, and checked on a view the search never saw.
 *
 * The search (docs/scenes.md, "what the scene needs"):
 *  1. the smallest uniform width W of the span unit's default-format rule
 *     whose render of the scene's view meets the target: the scene's own
 *     width first, then steps of 4 down (or up) until one fails (meets),
 *     then bisection, so W - 1 is known to fail;
 *  2. from W's formats, each signal's fraction bits are cut, one signal at
 *     a time, dearest first (the area one fraction bit of it costs, from
 *     the unit built at W; ties in the unit's signal order); per signal a
 *     try of one bit less (a signal the target needs whole costs one
 *     render), then of none at all (a signal the view hardly uses costs
 *     two), then bisection down to the fewest bits that still hold;
 *  3. passes of single-bit removals over every signal from the current
 *     formats, each pass going on after a removal that holds, until a pass
 *     keeps none: at the end, removing one more fraction bit from any
 *     signal breaks the target. A pass's candidates are rendered
 *     speculatively on `jobs` threads and the first that holds in order
 *     wins, as a one-at-a-time pass would: the result and the render count
 *     do not depend on jobs.
 * "Holds" = the render succeeded, NMSE <= target and no overflow anywhere
 * (input quantization included). Integer bits are left as the rule gives
 * them: the rule sizes them from the range the hardware can see (any node
 * intensity in [0, 1]), which holds for every view; trimming them to one
 * view's observed range would not be sound for another.
 * Signals pinned by the description's fmt overrides keep their formats.
 *
 * Every render uses the scene's own resolution; the surface buffers of the
 * view and of the held-out view are rasterized once, and what no format
 * changes (the reference image, the shaded nodes, the intervals) is made
 * once for each (tb_scene_prep): a render only simulates and measures.
 * Steps 2 and 3 only ask whether a render holds, so their renders stop as
 * soon as their error is sure to pass the target
 * (tb_scene_render_prep_budget): a failed render's figures are never
 * shown, and a render that holds runs to its end.
 * From step 2 on every render is of the description at width W with the
 * formats given, as `scene --set width=W --set fmt=...` renders them; the
 * accepted render of the found formats is kept and written with its
 * images into DIR/found/ (tests/cli_scene_exact.sh renders it so again).
 * "renders" counts what a one-at-a-time search renders (the speculative
 * candidates of step 3 not among them), so the output is the same for any
 * jobs; tb_scene_work has the renders run and their CPU time.
 */
#include "testbench/study/tb_scene_search.h"
#include "testbench/study/tb_sweep.h"
#include "base/base_out.h"
#include "base/base_par.h"
#include "base/base_json.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define W_MIN 4
#define W_MAX 48

/* ------------------------------------------------------------ evaluation */

typedef struct eval {
    int      status;
    double   nmse, psnr, area;
    int      max_err8;
    uint64_t ovf;
    unit_fmts fmts;
    double   cpu_sim, cpu_render;   /* the render's (tb_scene_result) */
    char     err[256];
} eval;

typedef struct search {
    const scn_desc *d;
    const scn_desc *dr;           /* what renders use: d, from step 2 on d at the uniform width W */
    const scn_gbuf *gv, *gh;      /* view, held-out view */
    tb_scene_prep *pv, *ph;       /* their references and intervals, made once */
    int      jobs;
    int      no_batch;    /* tb_scene_opts.no_batch of every render */
    double   target;
    size_t   renders;     /* the renders the result needs (a one-at-a-time search's) */
    int      tty;
    /* measured, never in the output: tb_scene_work, and the progress line */
    size_t   renders_run;
    double   cpu_sim, cpu_render;
    double   t0;          /* monotonic seconds at the start */
    size_t   expected;    /* estimate of renders in all (the progress line) */
    tb_scene_result found_r;      /* the images of the render rp->found came from */
} search;

/* r is the render of the formats found so far: keep its images. */
static void keep_found(search *s, tb_scene_result *r)
{
    tb_scene_free(&s->found_r);
    s->found_r = *r;
    memset(r, 0, sizeof *r);
}

static double mono_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A render run (the result's or a speculative one), in the work figures. */
static void account(search *s, const eval *e)
{
    s->renders_run++;
    s->cpu_sim += e->cpu_sim;
    s->cpu_render += e->cpu_render;
}

static int holds(const search *s, const eval *e)
{
    return e->status == TB_OK && e->ovf == 0 && e->nmse <= s->target;
}

/* Render description d (its own formats when f is NULL) on the view or
 * the held-out view with `threads` bands. keep: NULL, or where the render
 * goes (its images; empty when it failed), the caller's to free. budget:
 * INFINITY, or the render stops, failed, as soon as its NMSE is sure to
 * pass it (where only whether it holds matters: steps 2 and 3, whose
 * failed renders' figures are never shown). */
static void render_b(const search *s, const scn_desc *d, const unit_fmts *f, int heldout, int threads, double budget,
                     eval *e, tb_scene_result *keep)
{
    tb_scene_opts o = { threads, heldout, NULL, f, s->no_batch, 0, NULL, NULL };
    tb_scene_result r;
    memset(&r, 0, sizeof r);
    if (keep) memset(keep, 0, sizeof *keep);
    memset(e, 0, sizeof *e);
    e->status = tb_scene_render_prep_budget(d, heldout ? s->ph : s->pv, &o, budget, &r, e->err, sizeof e->err);
    e->cpu_sim = r.cpu_sim;          /* a failed render's too */
    e->cpu_render = r.cpu_render;
    if (e->status == TB_OK) {
        e->nmse = r.nmse;
        e->psnr = r.psnr;
        e->area = r.hwst.area_ge;
        e->max_err8 = r.max_err8;
        e->ovf = r.hwst.overflows;
        e->fmts = r.fmts;
        if (keep) {
            *keep = r;
            return;
        }
    }
    tb_scene_free(&r);
}

static void render(const search *s, const scn_desc *d, const unit_fmts *f, int heldout, int threads, eval *e,
                   tb_scene_result *keep)
{
    render_b(s, d, f, heldout, threads, INFINITY, e, keep);
}

/* "about 1 min 5 s left" from the time per render so far and the
 * renders still expected (an estimate: the search's length depends on what
 * holds); empty until two renders are done. */
void tb_scene_eta(char *buf, size_t len, double elapsed, size_t done, size_t total)
{
    buf[0] = 0;
    if (done < 2 || total <= done || !(elapsed > 0)) return;
    double left = elapsed / (double)done * (double)(total - done);
    long t = (long)(left + 0.5);
    if (t >= 60) snprintf(buf, len, "about %ld min %02ld s left", t / 60, t % 60);
    else snprintf(buf, len, "about %ld s left", t < 1 ? 1 : t);
}

static void progress(search *s, const char *what)
{
    if (!s->tty) return;
    char eta[64];
    size_t tot = s->expected > s->renders ? s->expected : s->renders + 1;
    tb_scene_eta(eta, sizeof eta, mono_now() - s->t0, s->renders, tot);
    fprintf(stderr, "\rscene search: %zu of about %zu renders, %-18.18s %-26s\033[K", s->renders, tot, what, eta);
    fflush(stderr);
}

/* The render at uniform width w (the description's overrides applied). */
static void at_width(search *s, int w, eval *e)
{
    scn_desc dw = *s->d;
    snprintf(dw.fmt_width, sizeof dw.fmt_width, "%d", w);
    char what[64];
    snprintf(what, sizeof what, "uniform width %d", w);
    progress(s, what);
    tb_scene_result r;
    render(s, &dw, NULL, 0, s->jobs, e, &r);
    s->renders++;
    account(s, e);
    if (holds(s, e)) keep_found(s, &r);
    tb_scene_free(&r);
}

/* Candidate renders of a pass, run together. */
typedef struct cand {
    const search *s;
    unit_fmts f;
    eval e;
    tb_scene_result r;
    int sig, pos;
} cand;

static void cand_run(void *ctx, size_t i)
{
    cand *c = (cand *)ctx + i;
    render_b(c->s, c->s->dr, &c->f, 0, 1, c->s->target, &c->e, &c->r);
}

/* A signal the description fixes with an fmt override (NAME=... or all=). */
static int pinned(const scn_desc *d, const char *name)
{
    for (int k = 0; k < d->nfmt; k++) {
        const char *o = d->fmt[k];
        size_t n = strcspn(o, "=");
        if ((n == 3 && !strncmp(o, "all", 3)) || (n == strlen(name) && !strncmp(o, name, n))) return 1;
    }
    return 0;
}

/* Area of unit u built at formats f (no simulation); -1 if it cannot be
 * built. Orders the signals only: the figures come from the renders. */
static double unit_area(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f)
{
    char err[256];
    tb_built b;
    double a = tb_build(u, cfg, f, &b, err, sizeof err) ? -1 : sim_scope_area(b.sc);
    sim_free(b.c);
    return a;
}

/* A unit signal is built when a signal or a sub-scope (a network such as
 * the divide-by-3, whose format is its output's) of the build has its name. */
static void mark_name(const unit_desc *u, const char *name, unsigned char *built)
{
    if (!name) return;
    for (int i = 0; i < u->nsigs; i++)
        if (!strcmp(name, u->sigs[i].name)) built[i] = 1;
}

static void mark_scope(const unit_desc *u, const sim_scope *sc, unsigned char *built)
{
    for (const sim_signal *g = sc->first_sig; g; g = g->next_in_scope) mark_name(u, g->name, built);
    for (const sim_scope *c = sc->first_child; c; c = c->next_sibling) {
        mark_name(u, c->name, built);
        mark_scope(u, c, built);
    }
}

/* Which of the unit's signals the build at cfg actually makes (a node-set
 * or degree option can leave some out): a signal not built has nothing to
 * trim. If the build fails or names nothing, every signal counts. */
static void built_signals(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, unsigned char *built)
{
    char err[256];
    int any = 0;
    memset(built, 0, UNIT_MAX_SIGS);
    tb_built b;
    if (!tb_build(u, cfg, f, &b, err, sizeof err)) mark_scope(u, b.sc, built);
    sim_free(b.c);
    for (int i = 0; i < u->nsigs; i++) any |= built[i];
    if (!any) memset(built, 1, UNIT_MAX_SIGS);
}

/* The fewest fraction bits signal sig can have. */
static int fmin_of(sim_fmt f) { return f.ibits >= 1 ? 0 : 1; }

static sim_fmt with_fbits(sim_fmt f, int fb)
{
    f.fbits = (int8_t)fb;
    f.width = (uint8_t)(f.ibits + fb);
    return f;
}

/* The renders step 2 takes for a signal of format f, about: one bit
 * less, none at all, then bisection of the bits between. */
static size_t est_signal(sim_fmt f)
{
    size_t n = 2;
    for (int span = f.fbits - fmin_of(f); span > 1; span = (span + 1) / 2) n++;
    return n;
}

typedef struct order_t { int sig; double saving; } order_t;
static int order_cmp(const void *a, const void *b)
{
    const order_t *x = a, *y = b;
    if (x->saving != y->saving) return x->saving > y->saving ? -1 : 1;
    return x->sig - y->sig;
}

/* ---------------------------------------------------------------- report */

typedef struct report {
    const scn_desc *d;
    const unit_desc *u;
    double target;
    int met, wu;                 /* a uniform width met the target; it */
    int sched, L, terms, width;  /* the unit's schedule index, L, terms, width (tb_scene_unit's) */
    int below_w;                 /* width of uni_below */
    unsigned char built[UNIT_MAX_SIGS];   /* signals the build makes (listed, trimmed) */
    int floor_stop;              /* stopped going up: the method's own error is above the target */
    eval uni, uni_below, uni_held, found, found_held;
    int have_below;
    int nsig, sig[UNIT_MAX_SIGS];   /* signals trimmed, in the order tried */
    size_t renders;
    int verdict;                 /* TB_OK / TB_FAIL */
} report;

static double saved_pct(const report *rp)
{
    return rp->uni.area > 0 ? 100.0 * (rp->uni.area - rp->found.area) / rp->uni.area : 0;
}

static void verdict_text(const report *rp, char *buf, size_t len)
{
    if (!rp->met)
        snprintf(buf, len, "FAIL: no uniform width %d..%d meets NMSE <= %g on the view%s (NMSE %.3g at W = %d)",
                 W_MIN, W_MAX, rp->target,
                 rp->floor_stop ? ": the method's own error is above the target, change L, terms or policy" : "",
                 rp->uni_below.nmse, rp->below_w);
    else if (rp->verdict == TB_OK)
        snprintf(buf, len, "ok: the held-out view meets NMSE <= %g with the per-signal formats (NMSE %.3g%s)",
                 rp->target, rp->found_held.nmse,
                 rp->found_held.ovf ? ", overflows" : "");
    else if (rp->found_held.status != TB_OK)
        snprintf(buf, len, "FAIL: the held-out view could not be rendered: %s", rp->found_held.err);
    else {
        int uni_ok = rp->uni_held.status == TB_OK && rp->uni_held.ovf == 0 && rp->uni_held.nmse <= rp->target;
        snprintf(buf, len, "FAIL: the held-out view does NOT meet NMSE <= %g with the per-signal formats "
                 "(NMSE %.3g, %llu overflows); %s", rp->target, rp->found_held.nmse,
                 (unsigned long long)rp->found_held.ovf,
                 uni_ok ? "the uniform width meets it there: the per-signal formats overfitted the view"
                        : "the uniform width misses it there too: the held-out view is harder than the view");
    }
}

static void print_json(FILE *f, const report *rp)
{
    char fb[SIM_FMT_STRLEN], fb2[SIM_FMT_STRLEN], v[512];
    const scn_desc *d = rp->d;
    fputs("{\n  \"search\": {\n    \"target_nmse\": ", f);
    base_json_num(f, rp->target, 9);
    fprintf(f, ",\n    \"resolution\": [%d, %d],\n    \"mesh\": ", d->width, d->height);
    base_json_str(f, d->mesh);
    fputs(",\n    \"policy\": ", f);
    base_json_str(f, scn_policy_name(d->policy));
    fprintf(f, ",\n    \"L\": %d,\n    \"terms\": %d,\n    \"schedule\": ", rp->L, rp->terms);
    base_json_str(f, rp->u ? rp->u->sched[rp->sched].name : "");
    fputs(",\n    \"unit\": ", f);
    base_json_str(f, rp->u ? rp->u->name : "");
    fprintf(f, ",\n    \"uniform_met\": %s", rp->met ? "true" : "false");
    if (rp->met) {
        fprintf(f, ",\n    \"uniform_width\": %d,\n    \"uniform_area_ge\": ", rp->wu);
        base_json_num(f, rp->uni.area, 9);
        fputs(",\n    \"uniform_nmse\": ", f); base_json_num(f, rp->uni.nmse, 9);
        fputs(",\n    \"uniform_heldout_nmse\": ", f); base_json_num(f, rp->uni_held.nmse, 9);
        fprintf(f, ",\n    \"uniform_heldout_overflows\": %llu", (unsigned long long)rp->uni_held.ovf);
        fprintf(f, ",\n    \"uniform_heldout_meets\": %s", rp->uni_held.status == TB_OK && rp->uni_held.ovf == 0
                && rp->uni_held.nmse <= rp->target ? "true" : "false");
        if (rp->have_below) {
            fputs(",\n    \"width_below_nmse\": ", f);
            base_json_num(f, rp->uni_below.status == TB_OK ? rp->uni_below.nmse : NAN, 9);
        }
        fputs(",\n    \"area_ge\": ", f); base_json_num(f, rp->found.area, 9);
        fputs(",\n    \"area_saved_pct\": ", f); base_json_num(f, saved_pct(rp), 9);
        fputs(",\n    \"nmse\": ", f); base_json_num(f, rp->found.nmse, 9);
        fputs(",\n    \"psnr\": ", f); base_json_num(f, rp->found.psnr, 9);
        fputs(",\n    \"heldout_nmse\": ", f); base_json_num(f, rp->found_held.status == TB_OK ? rp->found_held.nmse : NAN, 9);
        fprintf(f, ",\n    \"heldout_overflows\": %llu", (unsigned long long)rp->found_held.ovf);
        fputs(",\n    \"signals\": [", f);
        int first = 1;
        for (int i = 0; i < rp->u->nsigs; i++) {
            sim_fmt a = rp->uni.fmts.f[i], b = rp->found.fmts.f[i];
            if (!a.width || !rp->built[i] || !unit_sig_used(rp->u, i, rp->sched)) continue;
            fprintf(f, "%s\n      {\"name\": ", first ? "" : ",");
            first = 0;
            base_json_str(f, rp->u->sigs[i].name);
            fprintf(f, ", \"uniform\": \"%s\", \"found\": \"%s\"}", sim_fmt_str(a, fb), sim_fmt_str(b, fb2));
        }
        fputs("\n    ]", f);
    }
    fprintf(f, ",\n    \"renders\": %zu", rp->renders);
    fprintf(f, ",\n    \"heldout_meets\": %s", rp->verdict == TB_OK ? "true" : "false");
    verdict_text(rp, v, sizeof v);
    fputs(",\n    \"verdict\": ", f);
    base_json_str(f, v);
    fputs("\n  }\n}\n", f);
}

static void print_text(FILE *f, const report *rp)
{
    const scn_desc *d = rp->d;
    char fb[SIM_FMT_STRLEN], fb2[SIM_FMT_STRLEN], v[512];
    fprintf(f, "scene search: NMSE <= %g on %s %dx%d, policy %s, L %d, terms %d, schedule %s (unit %s)\n",
            rp->target, d->mesh, d->width, d->height, scn_policy_name(d->policy), rp->L, rp->terms,
            rp->u ? rp->u->sched[rp->sched].name : "?",
            rp->u ? rp->u->name : "?");
    if (rp->met) {
        fprintf(f, "smallest uniform width: W = %d", rp->wu);
        if (rp->have_below) {
            if (rp->uni_below.status == TB_OK)
                fprintf(f, " (W = %d: NMSE %.3g, %llu overflows)", rp->wu - 1, rp->uni_below.nmse,
                        (unsigned long long)rp->uni_below.ovf);
            else fprintf(f, " (W = %d cannot be built)", rp->wu - 1);
        }
        fputs("\n\n", f);
        fprintf(f, "  %-10s %-9s %-9s\n", "signal", "uniform", "found");
        for (int i = 0; i < rp->u->nsigs; i++) {
            sim_fmt a = rp->uni.fmts.f[i], b = rp->found.fmts.f[i];
            if (!a.width || !rp->built[i] || !unit_sig_used(rp->u, i, rp->sched)) continue;
            fprintf(f, "  %-10s %-9s %-9s%s\n", rp->u->sigs[i].name, sim_fmt_str(a, fb), sim_fmt_str(b, fb2),
                    pinned(d, rp->u->sigs[i].name) ? "  (pinned)" : "");
        }
        fprintf(f, "\n  %-22s %10s %12s %14s %10s\n", "", "area (GE)", "NMSE view", "NMSE held-out", "meets");
        fprintf(f, "  uniform W = %-10d %10.0f %12.4g %14.4g %10s\n", rp->wu, rp->uni.area, rp->uni.nmse,
                rp->uni_held.nmse, rp->uni_held.status == TB_OK && !rp->uni_held.ovf &&
                rp->uni_held.nmse <= rp->target ? "yes" : "no");
        fprintf(f, "  %-22s %10.0f %12.4g %14.4g %10s\n", "per-signal", rp->found.area, rp->found.nmse,
                rp->found_held.nmse, rp->verdict == TB_OK ? "yes" : "no");
        fprintf(f, "  area saved: %.1f%%  renders: %zu\n", saved_pct(rp), rp->renders);
    } else {
        fprintf(f, "renders: %zu\n", rp->renders);
    }
    verdict_text(rp, v, sizeof v);
    fprintf(f, "%s\n", v);
}

static int write_report(const report *rp, const char *outdir, char *err, size_t errlen)
{
    char path[1100];
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/%s", outdir, k ? "search.txt" : "search.json");
        base_out *o = base_out_open(path, err, errlen);
        if (!o) return -1;
        if (k) print_text(base_out_file(o), rp);
        else print_json(base_out_file(o), rp);
        if (base_out_close(o, err, errlen)) return -1;
    }
    return 0;
}

/* DIR/found/: the images and scene.json of the accepted render of the
 * found formats, as `scene --set width=W --set fmt=...` writes them
 * (without its energy per pixel: the search does not count switching). */
static int write_found(search *s, const report *rp, const char *outdir, char *err, size_t errlen)
{
    char dir[1100];
    snprintf(dir, sizeof dir, "%s/found", outdir);
    if (!s->found_r.hw) { snprintf(err, errlen, "scene search: no images of the found formats"); return -1; }
    if (tb_scene_speed_of(&s->found_r, rp->wu, err, errlen)) return -1;
    return tb_scene_write(s->dr, &s->found_r, dir, err, errlen);
}

/* No formats found: an earlier search's DIR/found/ would mislead. */
static void remove_found(const char *outdir)
{
    static const char *const files[] = { "ref.png", "hw.png", "degree.png", "region.png", "ref-hw.png", "hw-nodes.png",
                                         "degree-key.svg", "region-key.svg", "err-key.svg", "scene.json" };
    char path[1200];
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(path, sizeof path, "%s/found/%s", outdir, files[i]);
        unlink(path);
    }
    for (int k = 1; k <= 4096; k *= 4) {
        snprintf(path, sizeof path, "%s/found/err-x%d.png", outdir, k);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/found", outdir);
    rmdir(path);
}

/* ---------------------------------------------------------------- search */

/* The renders expected after step 2's signals ord[from..no-1] (formats
 * cur): theirs, then step 3, about two passes over the signals (one that
 * removes bits, one that finds none to remove), then the two held-out
 * renders. For the progress line only. */
static size_t est_rest(const order_t *ord, int from, int no, const unit_fmts *cur)
{
    size_t n = 2 + 2 * (size_t)no;
    for (int k = from; k < no; k++) n += est_signal(cur->f[ord[k].sig]);
    return n;
}

/* The renders expected in all before step 1 (formats f0): a few steps and
 * the bisection, then the rest as at the scene's own width. */
static size_t est_all(const report *rp, const unit_cfg *cfg, const unit_fmts *f0)
{
    order_t o0[UNIT_MAX_SIGS];
    unsigned char b0[UNIT_MAX_SIGS];
    int n0 = 0;
    built_signals(rp->u, cfg, f0, b0);
    for (int i = 0; i < rp->u->nsigs; i++)
        if (f0->f[i].width && b0[i] && unit_sig_used(rp->u, i, cfg->schedule) && !pinned(rp->d, rp->u->sigs[i].name) &&
            f0->f[i].fbits > fmin_of(f0->f[i]))
            o0[n0++] = (order_t){ i, 0 };
    return 5 + est_rest(o0, 0, n0, f0);
}

/* 1. The smallest uniform width (rp->met, rp->wu, rp->uni, the width
 * below). TB_BADINPUT (err set): the scene's own width cannot render. */
static int find_uniform(search *s, report *rp, char *err, size_t errlen)
{
    eval e;
    int w = rp->width < W_MIN ? W_MIN : rp->width > W_MAX ? W_MAX : rp->width;
    at_width(s, w, &e);
    if (e.status == TB_BADINPUT && w == rp->width) {
        snprintf(err, errlen, "%s", e.err);
        return TB_BADINPUT;
    }
    int lo = 0, hi = 0;          /* a failing and a holding width */
    if (holds(s, &e)) {
        hi = w;
        rp->uni = e;
        for (;;) {
            if (hi == W_MIN) { lo = W_MIN - 1; break; }
            int x = hi - 4 < W_MIN ? W_MIN : hi - 4;
            at_width(s, x, &e);
            if (holds(s, &e)) { hi = x; rp->uni = e; }
            else { lo = x; rp->uni_below = e; rp->below_w = x; break; }
        }
    } else {
        lo = w;
        rp->uni_below = e;
        rp->below_w = w;
        double prev = e.status == TB_OK ? e.nmse : INFINITY;
        for (int x = w + 4; x <= W_MAX; x += 4) {
            at_width(s, x, &e);
            if (holds(s, &e)) { hi = x; rp->uni = e; break; }
            lo = x;
            rp->uni_below = e;
            rp->below_w = x;
            /* The error has stopped falling with width: what is left is the
             * method's own (interpolation) error, which no width removes. */
            if (e.status == TB_OK && e.ovf == 0 && e.nmse > 0.9 * prev && e.nmse > 2 * s->target) {
                rp->floor_stop = 1;
                break;
            }
            if (e.status == TB_OK) prev = e.nmse;
        }
    }
    if (!hi) { rp->met = 0; return TB_OK; }
    while (hi - lo > 1) {
        int mid = lo + (hi - lo) / 2;
        at_width(s, mid, &e);
        if (holds(s, &e)) { hi = mid; rp->uni = e; }
        else { lo = mid; rp->uni_below = e; rp->below_w = mid; }
    }
    rp->met = 1;
    rp->wu = hi;
    rp->have_below = lo >= W_MIN;
    if (!rp->have_below) memset(&rp->uni_below, 0, sizeof rp->uni_below);
    return TB_OK;
}

/* Step 2's signals, dearest first: those the build at cur makes
 * (rp->built), the schedule uses and no override pins, with a fraction bit
 * to lose; dearest = the most area one bit fewer saves. Returns how many. */
static int trim_order(report *rp, const unit_cfg *cfg, const unit_fmts *cur, order_t *ord)
{
    const unit_desc *u = rp->u;
    int no = 0;
    double a0 = unit_area(u, cfg, cur);
    built_signals(u, cfg, cur, rp->built);
    for (int i = 0; i < u->nsigs; i++) {
        sim_fmt fi = cur->f[i];
        if (!fi.width || !rp->built[i] || !unit_sig_used(u, i, cfg->schedule) || pinned(rp->d, u->sigs[i].name))
            continue;
        if (fi.fbits <= fmin_of(fi)) continue;
        unit_fmts t = *cur;
        t.f[i] = with_fbits(fi, fi.fbits - 1);
        double a = unit_area(u, cfg, &t);
        ord[no++] = (order_t){ i, a >= 0 && a0 >= 0 ? a0 - a : 0 };
    }
    qsort(ord, (size_t)no, sizeof *ord, order_cmp);
    return no;
}

/* A step 2 render of formats t; when it holds, the found one. */
static int try_trim(search *s, report *rp, const unit_fmts *t, const char *what)
{
    eval e;
    tb_scene_result r;
    progress(s, what);
    render_b(s, s->dr, t, 0, s->jobs, s->target, &e, &r);
    s->renders++;
    account(s, &e);
    int ok = holds(s, &e);
    if (ok) keep_found(s, &r), rp->found = e;
    tb_scene_free(&r);
    return ok;
}

/* 2. The fewest fraction bits of signal ord[k] that hold, into cur. */
static void trim_signal(search *s, report *rp, const order_t *ord, int k, int no, unit_fmts *cur)
{
    int i = ord[k].sig;
    rp->sig[rp->nsig++] = i;
    sim_fmt fi = cur->f[i];
    int good = fi.fbits, bad = fmin_of(fi) - 1;
    char what[64];
    snprintf(what, sizeof what, "signal %s", rp->u->sigs[i].name);
    /* One bit less first: a signal the target already needs whole
     * costs one render. */
    unit_fmts t = *cur;
    t.f[i] = with_fbits(fi, good - 1);
    int ok = try_trim(s, rp, &t, what);
    s->expected = s->renders + est_rest(ord, k + 1, no, cur);
    if (!ok) return;
    good--;
    /* Then none at all (a signal this view hardly uses, such as the
     * quadratic network where every interval is cubic): one render. */
    if (good - bad > 1) {
        t.f[i] = with_fbits(fi, bad + 1);
        if (try_trim(s, rp, &t, what)) good = bad + 1;
        else bad++;
    }
    while (good - bad > 1) {
        int mid = bad + (good - bad) / 2;
        t.f[i] = with_fbits(fi, mid);
        if (try_trim(s, rp, &t, what)) good = mid;
        else bad = mid;
    }
    cur->f[i] = with_fbits(fi, good);
    s->expected = s->renders + est_rest(ord, k + 1, no, cur);
}

/* 3. Passes of single-bit removals until none holds: `jobs` candidates
 * at a time in cj; the first that holds wins, the pass going on after it
 * as a one-at-a-time pass would. */
static void final_passes(search *s, report *rp, cand *cj, const order_t *ord, int no, unit_fmts *cur)
{
    int jobs = s->jobs;
    for (int changed = 1; changed;) {
        changed = 0;
        for (int next = 0; next < no;) {
            int nb = 0;
            while (next < no && nb < jobs) {
                int i = ord[next++].sig;
                if (cur->f[i].fbits <= fmin_of(cur->f[i])) continue;
                cj[nb].s = s;
                cj[nb].f = *cur;
                cj[nb].f.f[i] = with_fbits(cur->f[i], cur->f[i].fbits - 1);
                cj[nb].sig = i;
                cj[nb].pos = next - 1;
                nb++;
            }
            if (!nb) break;
            /* expected: this pass's candidates left, a whole pass more if
             * this one removed a bit (the last pass removes none) */
            size_t left = 0, all = 0;
            for (int k = 0; k < no; k++) {
                int i = ord[k].sig, can = cur->f[i].fbits > fmin_of(cur->f[i]);
                all += (size_t)can;
                left += (size_t)(can && k >= cj[0].pos);
            }
            s->expected = s->renders + left + (changed ? all : 0) + 2;
            progress(s, "final passes");
            base_par_for((size_t)nb, jobs, cand_run, cj);
            for (int b = 0; b < nb; b++) account(s, &cj[b].e);
            for (int b = 0; b < nb; b++) {
                s->renders++;
                if (holds(s, &cj[b].e)) {
                    *cur = cj[b].f;
                    rp->found = cj[b].e;
                    keep_found(s, &cj[b].r);
                    changed = 1;
                    next = cj[b].pos + 1;
                    break;
                }
            }
            for (int b = 0; b < nb; b++) tb_scene_free(&cj[b].r);
        }
    }
}

/* The search's outcome rc out: the work figures, DIR/search.{json,txt}
 * and DIR/found/, the report on out, and for TB_FAIL the reason in err.
 * Returns rc, or TB_BADINPUT when a file cannot be written. */
static int report_out(search *s, report *rp, int rc, const char *outdir, int json, FILE *out, tb_scene_work *work,
                      char *err, size_t errlen)
{
    if (s->tty) fputs("\r\033[K", stderr);
    rp->renders = s->renders;
    if (work) {
        work->renders = s->renders;
        work->renders_run = s->renders_run;
        work->cpu_sim = s->cpu_sim;
        work->cpu_render = s->cpu_render;
    }
    rp->verdict = rc;
    if (outdir && write_report(rp, outdir, err, errlen)) return TB_BADINPUT;
    if (outdir && rp->met && write_found(s, rp, outdir, err, errlen)) return TB_BADINPUT;
    if (outdir && !rp->met) remove_found(outdir);
    if (json) print_json(out, rp);
    else print_text(out, rp);
    if (rc == TB_FAIL) {
        /* The reason, for the caller's one line on stderr. */
        char v[512];
        verdict_text(rp, v, sizeof v);
        snprintf(err, errlen, "scene search: %s", strncmp(v, "FAIL: ", 6) ? v : v + 6);
    }
    return rc;
}

int tb_scene_search(const scn_desc *d, const scn_mesh *m, int jobs, int no_batch, double target_nmse,
                    const char *outdir, int json, FILE *out, tb_scene_work *work, char *err, size_t errlen)
{
    if (errlen) err[0] = 0;
    if (work) memset(work, 0, sizeof *work);
    if (!(target_nmse > 0) || !isfinite(target_nmse)) {
        snprintf(err, errlen, "--target-nmse: needs a positive number");
        return TB_BADINPUT;
    }
    if (jobs < 1) jobs = 1;
    if (jobs > 64) jobs = 64;
    if (outdir && base_out_mkdirs(outdir, err, errlen)) return TB_BADINPUT;

    scn_gbuf gv, gh;
    memset(&gv, 0, sizeof gv);
    memset(&gh, 0, sizeof gh);
    if (scn_raster(m, &d->view.cam, d->width, d->height, &gv, err, errlen) ||
        scn_raster(m, &d->heldout.cam, d->width, d->height, &gh, err, errlen)) {
        scn_gbuf_free(&gv);
        scn_gbuf_free(&gh);
        return TB_BADINPUT;
    }
    search s = { .d = d, .dr = d, .gv = &gv, .gh = &gh, .jobs = jobs, .no_batch = no_batch, .target = target_nmse,
                 .tty = isatty(2), .t0 = mono_now() };
    report *rp = calloc(1, sizeof *rp);
    cand *cj = calloc((size_t)jobs, sizeof *cj);
    int rc = TB_FAIL;
    if (!rp || !cj) base_out_of_memory();
    /* What no format changes, once for each view: the reference, the
     * nodes and intervals (every render reads them; none recomputes). */
    rc = tb_scene_prep_new(d, &gv, 0, jobs, &s.pv, err, errlen);
    if (rc == TB_OK) rc = tb_scene_prep_new(d, &gh, 1, jobs, &s.ph, err, errlen);
    if (rc != TB_OK) goto done;
    s.cpu_render += tb_scene_prep_cpu(s.pv) + tb_scene_prep_cpu(s.ph);
    rc = TB_FAIL;
    rp->d = d;
    rp->target = target_nmse;
    unit_cfg cfg;
    unit_fmts f0;
    if (tb_scene_unit(d, &rp->u, &cfg, &f0, err, errlen)) { rc = TB_BADINPUT; goto done; }
    rp->sched = cfg.schedule, rp->L = cfg.L, rp->terms = cfg.terms, rp->width = cfg.width;

    /* 1. The smallest uniform width. */
    if (s.tty) s.expected = est_all(rp, &cfg, &f0);
    if (find_uniform(&s, rp, err, errlen) == TB_BADINPUT) { rc = TB_BADINPUT; goto done; }
    if (!rp->met) { rc = report_out(&s, rp, TB_FAIL, outdir, json, out, work, err, errlen); goto done; }

    /* 2. Fraction bits, signal by signal, dearest first, on the unit at W. */
    {
        scn_desc dw = *d;
        snprintf(dw.fmt_width, sizeof dw.fmt_width, "%d", rp->wu);
        unit_fmts fw;
        const unit_desc *u2;
        if (tb_scene_unit(&dw, &u2, &cfg, &fw, err, errlen)) { rc = TB_BADINPUT; goto done; }
    }
    /* From here every render is of the description at width W with the
     * formats given, as `scene --set width=W --set fmt=...` renders them. */
    scn_desc dwu = *d;
    snprintf(dwu.fmt_width, sizeof dwu.fmt_width, "%d", rp->wu);
    s.dr = &dwu;
    if (tb_scene_prep_unit(s.pv, &dwu, err, errlen) || tb_scene_prep_unit(s.ph, &dwu, err, errlen)) {
        rc = TB_BADINPUT;
        goto done;
    }
    unit_fmts cur = rp->uni.fmts;
    rp->found = rp->uni;
    order_t ord[UNIT_MAX_SIGS];
    int no = trim_order(rp, &cfg, &cur, ord);
    s.expected = s.renders + est_rest(ord, 0, no, &cur);
    for (int k = 0; k < no; k++) trim_signal(&s, rp, ord, k, no, &cur);

    final_passes(&s, rp, cj, ord, no, &cur);

    /* 4. The held-out view, with the found formats and with uniform W. */
    progress(&s, "held-out view");
    render(&s, s.dr, &cur, 1, jobs, &rp->found_held, NULL);
    render(&s, s.dr, &rp->uni.fmts, 1, jobs, &rp->uni_held, NULL);
    s.renders += 2;
    account(&s, &rp->found_held);
    account(&s, &rp->uni_held);
    rp->found.fmts = cur;
    rc = report_out(&s, rp, holds(&s, &rp->found_held) ? TB_OK : TB_FAIL, outdir, json, out, work, err, errlen);
done:
    tb_scene_free(&s.found_r);
    tb_scene_prep_free(s.pv);
    tb_scene_prep_free(s.ph);
    free(rp);
    free(cj);
    scn_gbuf_free(&gv);
    scn_gbuf_free(&gh);
    return rc;
}
