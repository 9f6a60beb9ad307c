/* tb_scene_sweep.c - a scene over interval length, degree policy, terms of
 * the divide-by-3 network, width and schedule: sweep.csv, four charts
 * (NMSE against operations per pixel, clocks per pixel, pixels per second
 * at the span unit's f_max and energy per pixel, each with its Pareto
 * front) and a summary.
 *
 * The grid (docs/scenes.md): the product of the axes, in the order
 * schedule, width, policy, L, terms (the last fastest). Default axes:
 * policy all six, L 4 8 16 32, terms 3 5 8, width 16, schedule paper;
 * with the default width axis, two more points per extra width 12 and 20:
 * the paper's configuration (adaptive-region, L 8, 3 terms) and the same
 * with 8 terms, so that the charts show where narrowing breaks. A spec
 * "KEY=V1,V2;KEY=..." replaces the axes it names (keys L, policy, terms,
 * width, schedule); the extra width points are then dropped if it names
 * width.
 *
 * Grid points that build the same hardware on the same scene (the linear
 * and quadratic units do not use the divide-by-3 network, so their rows
 * for different terms are equal) are rendered once and their rows copied;
 * the charts draw each distinct point once. Distinct points render on
 * `jobs` threads, one band each; each result lands in its own slot and
 * the CSV is written in grid order: the same bytes for any jobs.
 */
#include "base/base_json.h"
#include "testbench/study/tb_scene_search.h"
#include "testbench/study/tb_scene_pipes.h"
#include "testbench/tb_items_memo.h"
#include "testbench/study/tb_sweep.h"
#include "chart/chart.h"
#include "base/base_out.h"
#include "base/base_par.h"
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define AX_MAX 16

typedef struct axes {
    int nL, L[AX_MAX];
    int npol, pol[AX_MAX];
    int nterms, terms[AX_MAX];
    int nwidth, width[AX_MAX];
    int nsched; char sched[AX_MAX][16];
    int width_given;
} axes;

typedef struct pt {
    int L, pol, terms, width;
    char sched[16];
    int extra;                  /* an extra width point of the default grid */
    int same_as;                /* index of the point rendered in its place, or -1 */
    char key[256];
    /* results */
    int status;
    char err[200];
    char unit[32];
    double nmse, psnr, max_abs, cpp, cost_hw, cost_ref, speedup, area, deg2, ops_hw;
    double fmax, pps, epp;      /* f_max (MHz), pixels per second at it, energy per pixel (pJ) */
    int max_err8;
    uint64_t ovf;
    int front[4], jump[4];      /* by metric (M_*) */
    /* both pipelines in hardware (tb_scene_pipes.h): the method's row of
     * the most pixels per second per kGE over the shade unit's schedules */
    int pipes;                  /* measured */
    double pnmse, ppk, ppj;     /* NMSE with nodes from hardware, pixels/s per kGE, pJ/px */
    int pspans;
    char psched[16];
} pt;

/* What a chart and a front set NMSE against. */
enum { M_OPS, M_CLK, M_SPEED, M_ENERGY, M_N };

/* The metric as drawn, and as minimised (pixels per second: its inverse,
 * seconds per pixel, so that every front minimises both coordinates). */
static double m_val(const pt *p, int m)
{
    return m == M_OPS ? p->cost_hw : m == M_CLK ? p->cpp : m == M_SPEED ? p->pps : p->epp;
}
static double m_key(const pt *p, int m) { return m == M_SPEED ? 1.0 / p->pps : m_val(p, m); }

/* ------------------------------------------------------------------ spec */

static int policy_find(const char *s)
{
    for (int p = 0; p < SCN_POL__COUNT; p++)
        if (!strcmp(s, scn_policy_name((scn_policy)p))) return p;
    return -1;
}

static int parse_int(const char *s, int lo, int hi, int *v)
{
    char *end;
    if (*s == '-' || *s == '+' || (*s && strspn(s, "0123456789") != strlen(s))) return -1;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (!*s || *end || errno || x < lo || x > hi) return -1;
    *v = (int)x;
    return 0;
}

static void axes_default(axes *a)
{
    memset(a, 0, sizeof *a);
    static const int Ls[] = { 4, 8, 16, 32 }, Ts[] = { 3, 5, 8 };
    a->nL = 4; memcpy(a->L, Ls, sizeof Ls);
    a->npol = SCN_POL__COUNT;
    for (int p = 0; p < SCN_POL__COUNT; p++) a->pol[p] = p;
    a->nterms = 3; memcpy(a->terms, Ts, sizeof Ts);
    a->nwidth = 1; a->width[0] = 16;
    a->nsched = 1; snprintf(a->sched[0], 16, "paper");
}

static int parse_spec(const char *spec, axes *a, char *err, size_t errlen)
{
    char buf[1024];
    if (snprintf(buf, sizeof buf, "%s", spec) >= (int)sizeof buf) {
        snprintf(err, errlen, "--sweep: spec too long");
        return -1;
    }
    unsigned seen = 0;
    char *save1 = NULL;
    for (char *part = strtok_r(buf, ";", &save1); part; part = strtok_r(NULL, ";", &save1)) {
        char *eq = strchr(part, '=');
        if (!eq || eq == part || !eq[1]) {
            snprintf(err, errlen, "--sweep: '%s': expected KEY=V1,V2,... (keys L, policy, terms, width, schedule)", part);
            return -1;
        }
        *eq = 0;
        const char *key = part;
        static const char *const keys[] = { "L", "policy", "terms", "width", "schedule" };
        int k = -1;
        for (int i = 0; i < 5; i++) if (!strcmp(key, keys[i])) k = i;
        if (k < 0) {
            snprintf(err, errlen, "--sweep: unknown key '%s' (keys L, policy, terms, width, schedule)", key);
            return -1;
        }
        if (seen & (1u << k)) { snprintf(err, errlen, "--sweep: key %s given twice", key); return -1; }
        seen |= 1u << k;
        int n = 0;
        char *save2 = NULL;
        for (char *v = strtok_r(eq + 1, ",", &save2); v; v = strtok_r(NULL, ",", &save2)) {
            if (n >= AX_MAX) { snprintf(err, errlen, "--sweep: more than %d values for %s", AX_MAX, key); return -1; }
            int x = 0, bad = 0;
            switch (k) {
            case 0: bad = parse_int(v, 2, 64, &x); a->L[n] = x; break;
            case 1: x = policy_find(v); bad = x < 0; a->pol[n] = x; break;
            case 2: bad = parse_int(v, 1, 20, &x); a->terms[n] = x; break;
            case 3: bad = parse_int(v, 4, 64, &x); a->width[n] = x; break;
            case 4: bad = strlen(v) >= 16 || !*v; if (!bad) snprintf(a->sched[n], 16, "%s", v); break;
            }
            if (bad) {
                static const char *const what[] = { "a whole number 2..64", ("linear, quadratic, cubic-n1, cubic-n2, "
                    "adaptive-region or adaptive-auto"), "a whole number 1..20", "a whole number 4..64",
                    "a schedule name (paper, mac, pipe)" };
                snprintf(err, errlen, "--sweep: %s=%s: expected %s", key, v, what[k]);
                return -1;
            }
            n++;
        }
        if (!n) { snprintf(err, errlen, "--sweep: no values for %s", key); return -1; }
        switch (k) {
        case 0: a->nL = n; break;
        case 1: a->npol = n; break;
        case 2: a->nterms = n; break;
        case 3: a->nwidth = n; a->width_given = 1; break;
        case 4: a->nsched = n; break;
        }
    }
    return 0;
}

/* --------------------------------------------------------------- running */

typedef struct sweep {
    const scn_desc *d;
    const scn_mesh *m;
    const scn_gbuf *g;
    pt *p;
    size_t n, *todo, ntodo, done;
    pthread_mutex_t mu;
    int tty;
    int no_batch;     /* tb_scene_opts.no_batch of every render */
    double t0;        /* monotonic seconds at the start (the progress line) */
    double cpu_sim, cpu_render;   /* tb_scene_work's */
    tb_items_memo *memo;          /* the shade unit's runs over nodes, kept: grid points with the
                                   * same nodes (terms, the span schedule) shade them once */
} sweep;

static double mono_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void desc_of(const scn_desc *d, const pt *p, scn_desc *out)
{
    *out = *d;
    snprintf(out->L, sizeof out->L, "%d", p->L);
    out->policy = (scn_policy)p->pol;
    snprintf(out->terms, sizeof out->terms, "%d", p->terms);
    snprintf(out->fmt_width, sizeof out->fmt_width, "%d", p->width);
    snprintf(out->schedule, sizeof out->schedule, "%s", p->sched);
}

static void run_pt(void *ctx, size_t k)
{
    sweep *s = ctx;
    pt *p = &s->p[s->todo[k]];
    scn_desc dd;
    desc_of(s->d, p, &dd);
    tb_scene_opts o = { 1, 0, NULL, NULL, s->no_batch, 1, NULL, s->memo };
    tb_scene_result r;
    memset(&r, 0, sizeof r);
    tb_scene_pipes pipes;
    p->status = tb_scene_render_pipes(&dd, NULL, s->g, &o, TB_PIPES_METHOD, &r, &pipes, p->err, sizeof p->err);
    if (p->status == TB_OK) {
        const tb_pipe_row *best = NULL;
        for (int i = 0; i < pipes.nrows; i++)
            if (!best || pipes.row[i].pps_per_kge > best->pps_per_kge) best = &pipes.row[i];
        if (pipes.ok && best) {
            p->pipes = 1;
            p->pnmse = best->nmse;
            p->ppk = best->pps_per_kge;
            p->ppj = best->pj_per_pixel;
            p->pspans = best->spans;
            snprintf(p->psched, sizeof p->psched, "%s", best->sched);
        }
        tb_scene_pipes_free(&pipes);
        p->fmax = r.speed.hw.fmax_mhz;
        p->pps = r.speed.pixels_per_s;
        p->epp = r.energy_pj_per_pixel;
        p->nmse = r.nmse;
        p->psnr = r.psnr;
        p->max_abs = r.max_abs_err;
        p->max_err8 = r.max_err8;
        p->cpp = r.clocks_per_pixel;
        p->cost_hw = r.cost_hw;
        p->cost_ref = r.cost_ref;
        p->speedup = r.speedup;
        p->area = r.hwst.area_ge;
        p->ovf = r.hwst.overflows;
        p->deg2 = r.deg2_share;
        p->ops_hw = 0;
        for (int k = 0; k < SCN_OP__COUNT; k++) p->ops_hw += r.ops_hw[k];
    }
    tb_scene_free(&r);
    pthread_mutex_lock(&s->mu);
    s->done++;
    s->cpu_sim += r.cpu_sim;
    s->cpu_render += r.cpu_render;
    if (s->tty) {
        char eta[64];
        tb_scene_eta(eta, sizeof eta, mono_now() - s->t0, s->done, s->ntodo);
        fprintf(stderr, "\rscene sweep: %zu/%zu renders, %s\033[K", s->done, s->ntodo, eta);
        fflush(stderr);
    }
    pthread_mutex_unlock(&s->mu);
}

/* ----------------------------------------------------------------- front */

/* Pareto front of the usable distinct points on (metric m, nmse), and
 * the points whose NMSE jumps above 10x the front's staircase at their
 * cost. */
static void fronts(pt *p, size_t n, int m)
{
    if (!n) return;
    double *x = calloc(n, sizeof *x), *y = calloc(n, sizeof *y);
    unsigned char *on = calloc(n, 1);
    if (!x || !y || !on) base_out_of_memory();
    for (size_t i = 0; i < n; i++) {
        int use = p[i].same_as < 0 && p[i].status == TB_OK && p[i].ovf == 0;
        x[i] = use ? m_key(&p[i], m) : NAN;
        y[i] = use ? p[i].nmse : NAN;
    }
    chart_pareto(x, y, n, on);
    for (size_t i = 0; i < n; i++) {
        double xi = m_key(&p[i], m), best = INFINITY;
        for (size_t j = 0; j < n; j++)
            if (on[j] && x[j] <= xi && y[j] < best) best = y[j];
        p[i].front[m] = on[i];
        p[i].jump[m] = p[i].status == TB_OK && isfinite(best) && p[i].nmse > 10 * best;
    }
    free(x); free(y); free(on);
}

static int is_paper(const pt *p)
{
    return p->pol == SCN_POL_ADAPTIVE_REGION && p->L == 8 && p->terms == 3 && p->width == 16 &&
           !strcmp(p->sched, "paper");
}

static int pt_ok(const pt *p) { return p->status == TB_OK; }

static void draw_chart(const scn_desc *d, const pt *p, size_t n, int m, const char *path, char *err, size_t errlen,
                  int *rc)
{
    static const char *const what[M_N] = { "operations per pixel", "clocks per pixel", "pixels per second",
                                           "energy per pixel" };
    static const char *const xlabel[M_N] = {
        "operation cost per pixel (weighted, method)", "clocks per pixel of the simulated span unit",
        "pixels per second at the span unit's f_max", "energy per pixel of the span unit (pJ)" };
    char title[200];
    const char *b = strrchr(d->mesh, '/');
    snprintf(title, sizeof title, "%.60s %dx%d: NMSE against %s", b ? b + 1 : d->mesh, d->width, d->height, what[m]);
    chart *c = chart_new(title, xlabel[m], "NMSE vs per-pixel reference");
    if (!c) base_out_of_memory();          /* its one failure */
    chart_log_y(c, 1);
    /* The front first (a line under the points), then the marked kinds,
     * then one series per policy. */
    int s_front = chart_series(c, "Pareto front (no overflow)", CHART_STEP);
    int s_paper = chart_series(c, "paper (L8, 3 terms, W16)", CHART_POINTS);
    int s_break = chart_series(c, "breaks: ovf or >10x front", CHART_POINTS);
    int s_pol[SCN_POL__COUNT];
    for (int q = 0; q < SCN_POL__COUNT; q++) s_pol[q] = chart_series(c, scn_policy_name((scn_policy)q), CHART_POINTS);
    /* Front points in increasing x as drawn. */
    size_t *idx = malloc((n ? n : 1) * sizeof *idx), nf = 0;
    if (!idx) base_out_of_memory();
    for (size_t i = 0; i < n; i++)
        if (p[i].front[m]) idx[nf++] = i;
    for (size_t a = 1; a < nf; a++)
        for (size_t b = a; b > 0; b--) {
            double xa = m_val(&p[idx[b]], m), xb = m_val(&p[idx[b - 1]], m);
            if (xa < xb || (xa == xb && p[idx[b]].nmse > p[idx[b - 1]].nmse)) {
                size_t t = idx[b]; idx[b] = idx[b - 1]; idx[b - 1] = t;
            } else break;
        }
    for (size_t k = 0; k < nf; k++) chart_point(c, s_front, m_val(&p[idx[k]], m), p[idx[k]].nmse);
    free(idx);
    for (size_t i = 0; i < n; i++) {
        const pt *q = &p[i];
        if (q->same_as >= 0 || !pt_ok(q)) continue;
        double x = m_val(q, m);
        int brk = q->ovf > 0 || q->jump[m];
        if (is_paper(q)) chart_point_label(c, s_paper, x, q->nmse, "paper");
        else if (brk) chart_point(c, s_break, x, q->nmse);
        else if (q->extra) {
            char lab[16];
            snprintf(lab, sizeof lab, "W%d", q->width);
            chart_point_label(c, s_pol[q->pol], x, q->nmse, lab);
        } else chart_point(c, s_pol[q->pol], x, q->nmse);
    }
    chart_hline(c, 1e-4, "NMSE 1e-4 (the paper's claim)");
    if (chart_write(c, path, err, errlen)) *rc = -1;
    chart_free(c);
}

/* ------------------------------------------------------ both pipelines */

/* The shader's configurations the sweep sets beside the method's: the
 * shade unit alone, per pixel, at these widths and every schedule. */
static const int SHADE_W[] = { 10, 12, 14, 16, 20 };
#define N_SHADE_W ((int)(sizeof SHADE_W / sizeof SHADE_W[0]))
#define N_SHADE_ROWS (N_SHADE_W * UNIT_MAX_SCHED)

/* NMSE against pixels per second per kGE (energy 0) or pJ per pixel
 * (energy 1) of both pipelines in hardware: the method's points (node
 * shader + span units, nodes from hardware) by policy, the paper's
 * marked, and the per-pixel shader's configurations labelled by width
 * and schedule. */
static void draw_pipes_chart(const scn_desc *d, const pt *p, size_t n, const tb_pipe_row *ref, int nref, int energy,
                             const char *path, char *err, size_t errlen, int *rc)
{
    char title[200];
    const char *b = strrchr(d->mesh, '/');
    snprintf(title, sizeof title, "%.60s %dx%d: NMSE against %s, both pipelines in hardware", b ? b + 1 : d->mesh,
             d->width, d->height, energy ? "energy per pixel" : "pixels per second per kGE");
    chart *c = chart_new(title, energy ? "energy per pixel (pJ): shade unit per pixel, or node shader + span units"
                                       : "M pixels per second per kGE (pixels per second at equal area)",
                         "NMSE vs the float reference image");
    if (!c) base_out_of_memory();
    chart_log_y(c, 1);
    int s_ref = chart_series(c, "per-pixel shader (unit shade)", CHART_POINTS);
    int s_paper = chart_series(c, "paper (L8, 3 terms, W16)", CHART_POINTS);
    int s_pol[SCN_POL__COUNT];
    for (int q = 0; q < SCN_POL__COUNT; q++) s_pol[q] = chart_series(c, scn_policy_name((scn_policy)q), CHART_POINTS);
    for (int i = 0; i < nref; i++) {
        char lab[32];
        snprintf(lab, sizeof lab, "W%d %s", ref[i].width, ref[i].sched);
        chart_point_label(c, s_ref, energy ? ref[i].pj_per_pixel : ref[i].pps_per_kge / 1e6,
                          fmax(ref[i].nmse, 1e-12), lab);
    }
    for (size_t i = 0; i < n; i++) {
        const pt *q = &p[i];
        if (q->same_as >= 0 || !pt_ok(q) || !q->pipes) continue;
        double x = energy ? q->ppj : q->ppk / 1e6;
        if (is_paper(q)) chart_point_label(c, s_paper, x, q->pnmse, "paper");
        else chart_point(c, s_pol[q->pol], x, q->pnmse);
    }
    chart_hline(c, 1e-4, "NMSE 1e-4 (the paper's claim)");
    if (chart_write(c, path, err, errlen)) *rc = -1;
    chart_free(c);
}

/* The shader's configurations as CSV rows. */
static void write_shader_csv(FILE *f, const tb_pipe_row *ref, int nref)
{
    fputs("width,schedule,nmse,clocks_per_pixel,area_ge,fmax_mhz,pixels_per_s,pixels_per_s_per_kge,"
          "energy_pj_per_pixel,overflows\n", f);
    for (int i = 0; i < nref; i++) {
        const tb_pipe_row *w = &ref[i];
        fprintf(f, "%d,%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%llu\n", w->width, w->sched, w->nmse,
                w->clocks_per_pixel, w->area_ge, w->fmax_mhz, w->pixels_per_s, w->pps_per_kge, w->pj_per_pixel,
                (unsigned long long)w->overflows);
    }
}

/* ------------------------------------------------------------------- CSV */

static void cnum(FILE *f, double v)
{
    if (isnan(v)) fputs(",nan", f);
    else if (isinf(v)) fputs(v > 0 ? ",inf" : ",-inf", f);
    else fprintf(f, ",%.9g", v);
}

static void write_csv(FILE *f, const pt *p, size_t n)
{
    fputs("config,policy,L,terms,width,schedule,unit,status,same_as,nmse,psnr,max_abs_err,max_err8,"
          "clocks_per_pixel,ops_per_pixel,cost_per_pixel,cost_ref_per_pixel,speedup,area_ge,overflows,deg2_share,"
          "front_ops,front_clocks,breaks_ops,breaks_clocks,paper,fmax_mhz,pixels_per_s,energy_pj_per_pixel,"
          "front_speed,front_energy,pipe_schedule,pipe_spans,pipe_nmse,pipe_pixels_per_s_per_kge,"
          "pipe_energy_pj_per_pixel\n", f);
    for (size_t i = 0; i < n; i++) {
        const pt *q = &p[i];
        const pt *r = q->same_as >= 0 ? &p[q->same_as] : q;
        fprintf(f, "%zu,%s,%d,%d,%d,%s,%s,%s,", i, scn_policy_name((scn_policy)q->pol), q->L, q->terms, q->width,
                q->sched, r->unit, r->status == TB_OK ? "ok" : "failed");
        if (q->same_as >= 0) fprintf(f, "%d", q->same_as);
        if (r->status == TB_OK) {
            cnum(f, r->nmse); cnum(f, r->psnr); cnum(f, r->max_abs);
            fprintf(f, ",%d", r->max_err8);
            cnum(f, r->cpp); cnum(f, r->ops_hw); cnum(f, r->cost_hw); cnum(f, r->cost_ref); cnum(f, r->speedup); cnum(f, r->area);
            fprintf(f, ",%llu", (unsigned long long)r->ovf);
            cnum(f, r->deg2);
            fprintf(f, ",%d,%d,%d,%d,%d", q->front[M_OPS], q->front[M_CLK], r->ovf > 0 || r->jump[M_OPS],
                    r->ovf > 0 || r->jump[M_CLK], is_paper(q));
            cnum(f, r->fmax); cnum(f, r->pps); cnum(f, r->epp);
            fprintf(f, ",%d,%d", q->front[M_SPEED], q->front[M_ENERGY]);
            if (r->pipes) {
                fprintf(f, ",%s,%d", r->psched, r->pspans);
                cnum(f, r->pnmse); cnum(f, r->ppk); cnum(f, r->ppj);
                fputc('\n', f);
            } else fputs(",,,,,\n", f);
        } else {
            fprintf(f, ",,,,,,,,,,,,,,,,%d,,,,,,,,,,\n", is_paper(q));
        }
    }
}

/* ------------------------------------------------------------------ verb */

/* The grid's points in config order: schedule, width, policy, L, terms;
 * then, unless the widths are given, the extras (adaptive-region at L 8
 * with 3 and 8 terms at widths 12 and 20, per schedule). */
static pt *grid_points(const axes *a, size_t *np)
{
    size_t n = (size_t)a->nsched * (size_t)a->nwidth * (size_t)a->npol * (size_t)a->nL * (size_t)a->nterms;
    static const int extra_w[] = { 12, 20 }, extra_t[] = { 3, 8 };
    size_t nx = a->width_given ? 0 : 2 * 2 * (size_t)a->nsched;
    pt *p = calloc(n + nx, sizeof *p);
    if (!p) base_out_of_memory();
    size_t k = 0;
    for (int s = 0; s < a->nsched; s++)
        for (int w = 0; w < a->nwidth; w++)
            for (int q = 0; q < a->npol; q++)
                for (int l = 0; l < a->nL; l++)
                    for (int t = 0; t < a->nterms; t++) {
                        pt *x = &p[k++];
                        x->L = a->L[l]; x->pol = a->pol[q]; x->terms = a->terms[t]; x->width = a->width[w];
                        snprintf(x->sched, sizeof x->sched, "%s", a->sched[s]);
                    }
    for (int s = 0; s < (nx ? a->nsched : 0); s++)
        for (int t = 0; t < 2; t++)
            for (int w = 0; w < 2; w++) {
                pt *x = &p[k++];
                x->L = 8; x->pol = SCN_POL_ADAPTIVE_REGION; x->terms = extra_t[t]; x->width = extra_w[w];
                x->extra = 1;
                snprintf(x->sched, sizeof x->sched, "%s", a->sched[s]);
            }
    *np = k;
    return p;
}

/* Every point's hardware checked before anything renders, and the points
 * that build the same hardware found: each is the same_as of the first
 * with its key; the others go into sw->todo. */
static int check_points(sweep *sw, char *err, size_t errlen)
{
    pt *p = sw->p;
    for (size_t i = 0; i < sw->n; i++) {
        scn_desc dd;
        const unit_desc *u;
        unit_cfg cfg;
        unit_fmts f;
        desc_of(sw->d, &p[i], &dd);
        char e2[300];
        if (tb_scene_unit(&dd, &u, &cfg, &f, e2, sizeof e2)) {
            snprintf(err, errlen, "--sweep: %s L=%d terms=%d width=%d schedule=%s: %s",
                     scn_policy_name((scn_policy)p[i].pol), p[i].L, p[i].terms, p[i].width, p[i].sched, e2);
            return TB_BADINPUT;
        }
        snprintf(p[i].unit, sizeof p[i].unit, "%s", u->name);
        size_t kl = (size_t)snprintf(p[i].key, sizeof p[i].key, "%s|%s|%d|%s|%d",
                                     scn_policy_name((scn_policy)p[i].pol), u->name, p[i].width, p[i].sched, p[i].L);
        for (int j = 0; j < u->nparams && kl < sizeof p[i].key; j++) {
            char v[64];
            unit_param_get(&u->params[j], &cfg, v, sizeof v);
            kl += (size_t)snprintf(p[i].key + kl, sizeof p[i].key - kl, "|%s=%s", u->params[j].name, v);
        }
        p[i].same_as = -1;
        for (size_t j = 0; j < i; j++)
            if (p[j].same_as < 0 && !strcmp(p[j].key, p[i].key)) { p[i].same_as = (int)j; break; }
        if (p[i].same_as < 0) sw->todo[sw->ntodo++] = i;
    }
    return TB_OK;
}

/* The points the summary names ((size_t)-1: none) and the failed renders. */
typedef struct picks { size_t nfail, paper, best, cheap; } picks;

static picks pick_points(const pt *p, size_t n)
{
    picks k = { 0, (size_t)-1, (size_t)-1, (size_t)-1 };
    for (size_t i = 0; i < n; i++) {
        if (p[i].same_as >= 0) continue;
        if (p[i].status != TB_OK) { k.nfail++; continue; }
        if (is_paper(&p[i])) k.paper = i;
        if (p[i].ovf == 0 && (k.best == (size_t)-1 || p[i].nmse < p[k.best].nmse)) k.best = i;
        /* The cheapest point that meets 1e-4 without overflow. */
        if (p[i].ovf == 0 && p[i].nmse <= 1e-4 &&
            (k.cheap == (size_t)-1 || p[i].cost_hw < p[k.cheap].cost_hw ||
             (p[i].cost_hw == p[k.cheap].cost_hw && p[i].nmse < p[k.cheap].nmse)))
            k.cheap = i;
    }
    return k;
}

#define N_FILES (1 + M_N + 3)
static const char *const sweep_files[N_FILES] = { "sweep.csv", "sweep_ops.svg", "sweep_clocks.svg",
                                                  "sweep_speed.svg", "sweep_energy.svg", "sweep_shader.csv",
                                                  "sweep_pipes_speed.svg", "sweep_pipes_energy.svg" };

/* DIR/sweep.csv and the charts; paths gets their names. */
static int write_files(const scn_desc *d, const pt *p, size_t n, const tb_pipe_row *ref, int nref,
                       const char *outdir, char paths[][1100], char *err, size_t errlen)
{
    for (int j = 0; j < N_FILES; j++) snprintf(paths[j], 1100, "%s/%s", outdir, sweep_files[j]);
    base_out *o = base_out_open(paths[0], err, errlen);
    if (!o) return TB_BADINPUT;
    write_csv(base_out_file(o), p, n);
    if (base_out_close(o, err, errlen)) return TB_BADINPUT;
    int crc = 0;
    for (int m = 0; m < M_N && !crc; m++) draw_chart(d, p, n, m, paths[1 + m], err, errlen, &crc);
    if (!crc && !(o = base_out_open(paths[1 + M_N], err, errlen))) crc = -1;
    if (!crc) {
        write_shader_csv(base_out_file(o), ref, nref);
        if (base_out_close(o, err, errlen)) crc = -1;
    }
    for (int e = 0; e < 2 && !crc; e++) draw_pipes_chart(d, p, n, ref, nref, e, paths[2 + M_N + e], err, errlen, &crc);
    return crc ? TB_BADINPUT : TB_OK;
}

static void print_json(FILE *out, const scn_desc *d, const pt *p, size_t n, size_t renders, const picks *k,
                       const char *outdir, char paths[][1100])
{
    fprintf(out, "{\n  \"sweep\": {\n    \"points\": %zu,\n    \"renders\": %zu,\n    \"failed\": %zu,\n",
            n, renders, k->nfail);
    fprintf(out, "    \"resolution\": [%d, %d],\n", d->width, d->height);
    const size_t sel[3] = { k->paper, k->best, k->cheap };
    const char *const nm[3] = { "paper", "lowest_nmse", "cheapest_meeting_1e-4" };
    for (int j = 0; j < 3; j++) {
        fprintf(out, "    \"%s\": ", nm[j]);
        if (sel[j] == (size_t)-1) { fputs("null,\n", out); continue; }
        const pt *q = &p[sel[j]];
        /* 9 digits; a figure that is not finite (NMSE of a failed
         * render) is null, as JSON has no inf */
        fprintf(out, "{\"config\": %zu, \"policy\": \"%s\", \"L\": %d, \"terms\": %d, \"width\": %d, "
                "\"schedule\": \"%s\", \"nmse\": ", sel[j], scn_policy_name((scn_policy)q->pol), q->L,
                q->terms, q->width, q->sched);
        base_json_num(out, q->nmse, 9);
        fputs(", \"cost_per_pixel\": ", out); base_json_num(out, q->cost_hw, 9);
        fputs(", \"clocks_per_pixel\": ", out); base_json_num(out, q->cpp, 9);
        fputs(", \"speedup\": ", out); base_json_num(out, q->speedup, 9);
        fputs(", \"area_ge\": ", out); base_json_num(out, q->area, 9);
        fputs(", \"fmax_mhz\": ", out); base_json_num(out, q->fmax, 9);
        fputs(", \"pixels_per_s\": ", out); base_json_num(out, q->pps, 9);
        fputs(", \"energy_pj_per_pixel\": ", out); base_json_num(out, q->epp, 9);
        fputs("},\n", out);
    }
    fputs("    \"files\": [", out);
    for (int j = 0; outdir && j < N_FILES; j++) fprintf(out, "%s\"%s\"", j ? ", " : "", paths[j]);
    fputs("]\n  }\n}\n", out);
}

/* Both pipelines at NMSE <= 1e-4: the method's point and the shader's
 * configuration of the most pixels per second per kGE that meet it
 * (without overflow); -1: none. */
static void best_pipes(const pt *p, size_t n, const tb_pipe_row *ref, int nref, long *bm, int *br)
{
    *bm = -1;
    *br = -1;
    for (size_t i = 0; i < n; i++)
        if (p[i].same_as < 0 && pt_ok(&p[i]) && p[i].pipes && p[i].ovf == 0 && p[i].pnmse <= 1e-4 &&
            (*bm < 0 || p[i].ppk > p[*bm].ppk))
            *bm = (long)i;
    for (int j = 0; j < nref; j++)
        if (ref[j].nmse <= 1e-4 && ref[j].overflows == 0 && (*br < 0 || ref[j].pps_per_kge > ref[*br].pps_per_kge))
            *br = j;
}

static void print_pipes(FILE *out, const pt *p, size_t n, const tb_pipe_row *ref, int nref)
{
    long bm;
    int br;
    best_pipes(p, n, ref, nref, &bm, &br);
    if (!nref) { fputs("  both pipelines: not measured (the scene's lighting does not fit the shade unit)\n", out); return; }
    fputs("  both pipelines at NMSE <= 1e-4, the most pixels/s per kGE:", out);
    if (bm >= 0) fprintf(out, " method %.4g M (%s, L %d, %d terms, W%d, shade %s, %d span units, NMSE %.3g)",
                         p[bm].ppk / 1e6, scn_policy_name((scn_policy)p[bm].pol), p[bm].L, p[bm].terms, p[bm].width,
                         p[bm].psched, p[bm].pspans, p[bm].pnmse);
    else fputs(" no method point", out);
    if (br >= 0) fprintf(out, ", per-pixel shader %.4g M (W%d %s, NMSE %.3g)", ref[br].pps_per_kge / 1e6,
                         ref[br].width, ref[br].sched, ref[br].nmse);
    else fputs(", no shader configuration", out);
    if (bm >= 0 && br >= 0) fprintf(out, ": %.3gx", p[bm].ppk / ref[br].pps_per_kge);
    fputc('\n', out);
}

static void print_text(FILE *out, const scn_desc *d, const pt *p, size_t n, size_t renders, const picks *k,
                       const char *outdir, char paths[][1100])
{
    fprintf(out, "scene sweep: %s %dx%d, %zu grid points, %zu distinct renders\n", d->mesh, d->width,
            d->height, n, renders);
    if (k->nfail) fprintf(out, "  %zu renders failed (their rows say so)\n", k->nfail);
    fprintf(out, "  %-16s %3s %5s %5s %-6s %11s %9s %9s %8s %9s %5s %6s %7s %6s\n", "policy", "L", "terms",
            "width", "sched", "NMSE", "cost/px", "clk/px", "speedup", "area GE", "ovf", "MHz", "Mpx/s", "pJ/px");
    const size_t sel[3] = { k->paper, k->cheap, k->best };
    const char *const nm[3] = { "paper", "cheapest <=1e-4", "lowest NMSE" };
    for (int j = 0; j < 3; j++) {
        if (sel[j] == (size_t)-1) { fprintf(out, "  %s: not in the grid\n", nm[j]); continue; }
        const pt *q = &p[sel[j]];
        fprintf(out, "  %-16s %3d %5d %5d %-6s %11.4g %9.3g %9.3g %8.3g %9.0f %5llu %6.0f %7.4g %6.3g  %s\n",
                scn_policy_name((scn_policy)q->pol), q->L, q->terms, q->width, q->sched, q->nmse, q->cost_hw,
                q->cpp, q->speedup, q->area, (unsigned long long)q->ovf, q->fmax, q->pps / 1e6, q->epp, nm[j]);
    }
    size_t nf[M_N] = { 0 }, nb = 0;
    for (size_t i = 0; i < n; i++) {
        if (p[i].same_as >= 0 || p[i].status != TB_OK) continue;
        for (int m = 0; m < M_N; m++) nf[m] += (size_t)p[i].front[m];
        nb += p[i].ovf > 0 || p[i].jump[M_OPS];
    }
    fprintf(out, "  Pareto front: %zu points (operations), %zu (clocks), %zu (pixels/s), %zu (energy); %zu points "
            "break (overflow or NMSE > 10x the front)\n", nf[M_OPS], nf[M_CLK], nf[M_SPEED], nf[M_ENERGY], nb);
    for (int j = 0; outdir && j < N_FILES; j++) fprintf(out, "wrote %s\n", paths[j]);
}

int tb_scene_sweep(const scn_desc *d, const scn_mesh *m, int jobs, int no_batch, const char *spec,
                   const char *outdir, int json, FILE *out, tb_scene_work *work, char *err, size_t errlen)
{
    axes a;
    if (errlen) err[0] = 0;
    if (work) memset(work, 0, sizeof *work);
    axes_default(&a);
    if (spec && *spec && parse_spec(spec, &a, err, errlen)) return TB_BADINPUT;
    if (jobs < 1) jobs = 1;
    if (jobs > 64) jobs = 64;
    size_t n = 0;
    pt *p = grid_points(&a, &n);

    int rc = TB_OK;
    sweep sw = { .d = d, .m = m, .p = p, .n = n, .mu = PTHREAD_MUTEX_INITIALIZER, .tty = isatty(2),
                 .no_batch = no_batch, .t0 = mono_now(), .memo = tb_items_memo_new() };
    scn_gbuf g;
    memset(&g, 0, sizeof g);
    sw.todo = malloc((n ? n : 1) * sizeof *sw.todo);
    if (!sw.todo) base_out_of_memory();
    if ((rc = check_points(&sw, err, errlen)) != TB_OK) goto done;
    if (outdir && base_out_mkdirs(outdir, err, errlen)) { rc = TB_BADINPUT; goto done; }
    if (scn_raster(m, &d->view.cam, d->width, d->height, &g, err, errlen)) { rc = TB_BADINPUT; goto done; }
    sw.g = &g;
    base_par_for(sw.ntodo, jobs, run_pt, &sw);
    if (sw.tty) fputs("\r\033[K", stderr);
    if (work) {
        work->renders = work->renders_run = sw.ntodo;
        work->cpu_sim = sw.cpu_sim;
        work->cpu_render = sw.cpu_render;
    }
    /* the per-pixel shader's configurations, over the same pixels */
    tb_pipe_row ref[N_SHADE_ROWS];
    int nref = 0;
    tb_scene_opts ro = { jobs, 0, NULL, NULL, no_batch, 1, NULL, NULL };
    if ((rc = tb_scene_pipes_refs(d, NULL, &g, &ro, SHADE_W, N_SHADE_W, ref, &nref, err, errlen)) != TB_OK) goto done;
    for (int m = 0; m < M_N; m++) fronts(p, n, m);
    picks k = pick_points(p, n);
    char paths[N_FILES][1100];
    if (outdir && (rc = write_files(d, p, n, ref, nref, outdir, paths, err, errlen)) != TB_OK) goto done;
    if (json) print_json(out, d, p, n, sw.ntodo, &k, outdir, paths);
    else {
        print_text(out, d, p, n, sw.ntodo, &k, NULL, paths);
        print_pipes(out, p, n, ref, nref);
        for (int j = 0; outdir && j < N_FILES; j++) fprintf(out, "wrote %s\n", paths[j]);
    }
    if (k.nfail) {
        rc = TB_FAIL;
        snprintf(err, errlen, "scene sweep: %zu of %zu renders failed (their rows in sweep.csv are marked failed)",
                 k.nfail, sw.ntodo);
    }
done:
    tb_items_memo_free(sw.memo);
    free(sw.todo);
    free(p);
    scn_gbuf_free(&g);
    pthread_mutex_destroy(&sw.mu);
    return rc;
}
