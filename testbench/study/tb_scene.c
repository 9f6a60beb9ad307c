/* tb_scene.c - a scene shaded through the simulated span hardware.
 *
 * The hardware path, row band by row band:
 *   1. every covered pixel is shaded in double precision: the reference;
 *   2. each span of n pixels is cut into intervals of L pixels from its
 *      left end, the last one shorter (n mod L, or L). Interval j starts
 *      at x0 + jL; its divisor dv is L, except the span's last interval
 *      where dv = max(len - 1, 1), so that its t = 1 node is the span's
 *      last pixel. Pixel k of an interval has t = k/dv;
 *   3. the nodes x = start + dv * {0, 1, 1/2, 1/4 (N1) or 3/4 (N2)} are
 *      shaded exactly (scn_span_at, then the lighting). The t = 1 node of
 *      an interval is the t = 0 node of the next one: it is shaded once.
 *      A last interval of one pixel needs only its t = 0 node (the other
 *      node inputs repeat it: a constant; adaptive-auto gives it degree 2). Only the nodes the interval's
 *      degree reads are shaded, and counted;
 *   4. the degree: fixed by the policy; adaptive-region: the table of the
 *      description (region -> 2 or 3); adaptive-auto: from the nodes the
 *      hardware has anyway, the second difference
 *          c = |I(0) + I(1) - 2 I(1/2)|
 *      (4 times the deviation of the midpoint from the chord, zero for a
 *      straight profile): degree 3 when c > auto_threshold, else 2; the
 *      I(1/4) or I(3/4) node is shaded only for degree 3;
 *   5. one tb_span_run per band with all of the band's intervals, on a
 *      fresh simulation of the policy's unit; the pixels come back in
 *      order and are written into the hardware image.
 * The rows are split into a fixed number of bands (TB_SCENE_BANDS, or one
 * per row when there are fewer rows) whatever the number of threads, and
 * the bands' figures are summed in band order: the output is the same for
 * any -j.
 *
 * Metrics over covered pixels, on the hardware's raw values (not clamped:
 * an overshoot of the interpolation is an error like any other):
 *   NMSE = sum (hw - ref)^2 / sum ref^2, max_abs_err = max |hw - ref|
 *   (NMSE is the one every 1e-4 verdict and --max-nmse use).
 * On 8 bits, v8 = round(255 clamp(v, 0, 1)) (also the PNG images):
 *   NMSE8 = sum (hw8 - ref8)^2 / sum ref8^2, what the images show,
 *   PSNR = 10 log10(255^2 / mean (hw8 - ref8)^2) (infinite when equal),
 *   max_err8 = max |hw8 - ref8|, diff8_share = share of pixels with
 *   hw8 != ref8.
 * clocks_per_pixel = clocks of all bands' simulations / covered pixels.
 */
#include "testbench/study/tb_scene.h"
#include "testbench/tb.h"
#include "base/base_out.h"
#include "units/unit_coef.h"
#include "units/unit_net.h"
#include "base/base_par.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* CPU seconds of the calling thread: a render's time accounting
 * (tb_scene_result.cpu_sim, cpu_render) sums what each of its threads
 * spends, so that it reads the same on a busy machine and for any -j. */
static double cpu_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts)) return 0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Adders of a coefficient network (ADD and SUB elements; a /3 network is
 * its subtractors or adders). */
static int net_adds(const coef_net *net, int terms, int series)
{
    int n = 0;
    for (int i = 0; i < net->nnodes; i++) {
        if (net->node[i].op == COEF_ADD || net->node[i].op == COEF_SUB) n++;
        else if (net->node[i].op == COEF_DIV3) n += series == DIV3_QUARTER ? terms - 1 : terms;
    }
    return n;
}

/* Adders of the coefficients of one interval of degree deg, on the unit
 * configured as cfg (n2: node set N2). */
static int coef_adds(const unit_cfg *cfg, int n2, int deg)
{
    if (deg <= 1) return 1;                              /* B = I2 - I1 */
    if (deg == 2) return net_adds(&coef_net_q, cfg->terms, cfg->series);
    return net_adds(n2 ? &coef_net_n2 : &coef_net_n1, cfg->terms, cfg->series);
}

/* ------------------------------------------------------------ render */

typedef struct band {
    int y0, y1;
    size_t s0, s1;                 /* its spans */
    tb_span_item *items;           /* its intervals, for the batch (NULL: simulated already) */
    size_t nitems, npix;
    int borrowed;                  /* items belong to a tb_scene_prep: not freed here */
    double *refpix;                /* a prep's: the reference at the band's pixels, in their order */
    double *pix;
    tb_span_stats st;
    size_t intervals, deg2, nodes;
    double coef_adds, horner_deg;  /* sums over intervals / pixels */
    double cpu_sim, cpu_other;     /* CPU seconds: simulating its intervals; the rest of its work */
    int rc;
    char err[300];
} band;

typedef struct job {
    const scn_desc *d;
    const scn_gbuf *g;
    const scn_view *view;
    tb_scene_shader fn;
    void *ctx;
    const unit_desc *u;
    const unit_cfg *cfg;
    const unit_fmts *fmts;
    const scn_span *spans;
    band *bands;
    int nbands, vcd_band;
    const char *vcd_path;
    int batch;                     /* simulate bands side by side (tb_span_run_lanes) */
    int energy;                    /* count toggles and energy (tb_scene_opts) */
    tb_scene_nodes *nodes;         /* record normals / replay node intensities (tb_scene_opts) */
    int ngroups;                   /* the batch: bands in this many groups, one a thread */
    double gcpu_sim[TB_SCENE_BANDS], gcpu_other[TB_SCENE_BANDS];   /* per group, as band's */
    double max_se;                 /* the batch stops past this squared error (INFINITY: never) */
    tb_scene_result *r;
} job;

static double shade_at(const job *J, const double pos[3], const double nrm[3])
{
    if (J->fn) return J->fn(J->ctx, pos, nrm);
    return scn_shade(&J->d->mat, J->view, pos, nrm);
}

/* A normal appended to a recording (its pixel index too, pix != NULL). */
static void rec_push(double (**a)[3], size_t **ix, size_t *n, size_t *cap, const double v[3], size_t pix)
{
    if (*n == *cap) {
        *cap = *cap ? 2 * *cap : 1024;
        if (!(*a = realloc(*a, *cap * sizeof **a)) || (ix && !(*ix = realloc(*ix, *cap * sizeof **ix))))
            base_out_of_memory();
    }
    memcpy((*a)[*n], v, sizeof (*a)[*n]);
    if (ix) (*ix)[*n] = pix;
    (*n)++;
}

/* A node's intensity: shaded exactly (and its normal recorded), or the
 * next replayed one. */
static double node_at(const job *J, band *b, const scn_span *s, double x)
{
    tb_scene_nodes_band *nb = J->nodes ? &J->nodes->band[b - J->bands] : NULL;
    if (nb && J->nodes->replay) return nb->next < nb->nnodes ? nb->val[nb->next++] : NAN;
    double p[3], n[3];
    if (x > s->x1 - 1) x = s->x1 - 1;   /* guards rounding only: nodes lie in the span */
    scn_span_at(J->g, s, x, p, n);
    if (nb) rec_push(&nb->nn, NULL, &nb->nnodes, &nb->cap_nodes, n, 0);
    return shade_at(J, p, n);
}

void tb_scene_nodes_free(tb_scene_nodes *n)
{
    for (int k = 0; n && k < TB_SCENE_BANDS; k++) {
        free(n->band[k].pn);
        free(n->band[k].pix);
        free(n->band[k].nn);
        memset(&n->band[k], 0, sizeof n->band[k]);
    }
}

/* Degree of an interval before its nodes are known (0: decided from them). */
static int policy_deg(const scn_desc *d, int region)
{
    switch (d->policy) {
    case SCN_POL_LINEAR: return 1;
    case SCN_POL_QUADRATIC: return 2;
    case SCN_POL_CUBIC_N1: case SCN_POL_CUBIC_N2: return 3;
    case SCN_POL_ADAPTIVE_REGION:
        return region < SCN_MAX_REGIONS && d->region_deg[region] == 2 ? 2 : 3;
    default: return 0;
    }
}

/* A band's hardware pixels into the image, span by span. */
static void band_pixels(const job *J, const band *b, const double *pix)
{
    int W = J->g->w;
    size_t p = 0;
    for (size_t k = b->s0; k < b->s1; k++) {
        const scn_span *s = &J->spans[k];
        for (int x = s->x0; x < s->x1; x++) J->r->hw[(size_t)s->y * W + x] = pix[p++];
    }
}

static void run_band(job *J, band *b)
{
    const scn_desc *d = J->d;
    const scn_gbuf *g = J->g;
    tb_scene_result *r = J->r;
    int W = g->w, L = J->cfg->L, n2 = tb_scene_nodes_n2(d);     /* the unit's L: intervals */
    double c0 = cpu_now();
    /* reference */
    for (int y = b->y0; y < b->y1; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            if (g->tri[i] < 0) continue;
            double n[3] = { g->nrm[i][0], g->nrm[i][1], g->nrm[i][2] };
            double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (len > 0) { n[0] /= len; n[1] /= len; n[2] /= len; }
            r->ref[i] = shade_at(J, g->pos[i], n);
            tb_scene_nodes_band *nb = J->nodes && !J->nodes->replay ? &J->nodes->band[b - J->bands] : NULL;
            if (nb) rec_push(&nb->pn, &nb->pix, &nb->npix, &nb->cap_pix, g->nrm[i], i);
        }
    /* intervals */
    size_t nitems = 0, npix = 0;
    for (size_t k = b->s0; k < b->s1; k++) {
        int n = J->spans[k].x1 - J->spans[k].x0;
        nitems += (size_t)(n + L - 1) / L;
        npix += (size_t)n;
    }
    b->npix = npix;
    if (!nitems) { b->cpu_other += cpu_now() - c0; return; }
    tb_span_item *items = calloc(nitems, sizeof *items);
    double *pix = malloc(npix * sizeof *pix);
    if (!items || !pix) base_out_of_memory();
    size_t it = 0;
    for (size_t k = b->s0; k < b->s1; k++) {
        const scn_span *s = &J->spans[k];
        int fixed = policy_deg(d, s->region);
        double i0 = node_at(J, b, s, s->x0);
        b->nodes++;
        for (int start = s->x0; start < s->x1; start += L) {
            tb_span_item *m = &items[it++];
            int len = s->x1 - start < L ? s->x1 - start : L;
            int last = start + L >= s->x1;
            int dv = last ? (len - 1 > 1 ? len - 1 : 1) : L;
            m->n = len;
            m->dv = dv;
            m->node[0] = i0;
            int deg = fixed;
            if (last && len == 1) {
                /* one pixel, t = 0: a constant interval, nothing to shade */
                m->node[1] = m->node[2] = m->node[3] = i0;
                if (!deg) deg = 2;
            } else {
                m->node[1] = node_at(J, b, s, start + dv);
                b->nodes++;
                if (deg != 1) {
                    m->node[2] = node_at(J, b, s, start + dv * 0.5);
                    b->nodes++;
                }
                /* recorded or replayed, adaptive-auto's fourth node is taken whatever the degree */
                double xq = start + dv * (n2 ? 0.75 : 0.25);
                int early = !fixed && J->nodes;
                double q = early ? node_at(J, b, s, xq) : 0;
                if (!deg) deg = fabs(m->node[0] + m->node[1] - 2 * m->node[2]) > d->auto_threshold ? 3 : 2;
                if (deg == 3) {
                    m->node[3] = early ? q : node_at(J, b, s, xq);
                    b->nodes++;
                }
            }
            m->deg = deg;
            i0 = m->node[1];
            b->intervals++;
            if (deg == 2) b->deg2++;
            b->coef_adds += coef_adds(J->cfg, n2, deg);
            b->horner_deg += (double)deg * len;
            for (int x = start; x < start + len; x++) r->deg[(size_t)s->y * W + x] = (uint8_t)deg;
        }
    }
    const char *vcd = J->vcd_band == (int)(b - J->bands) ? J->vcd_path : NULL;
    if (J->batch && !vcd) {
        /* simulated with the other bands of its group (run_group) */
        b->items = items;
        b->nitems = nitems;
        b->pix = pix;
        b->cpu_other += cpu_now() - c0;
        return;
    }
    double c1 = cpu_now();
    b->rc = J->energy ? tb_span_run_energy(J->u, J->cfg, J->fmts, items, nitems, pix, &b->st, vcd, b->err, sizeof b->err)
                      : tb_span_run(J->u, J->cfg, J->fmts, items, nitems, pix, &b->st, vcd, b->err, sizeof b->err);
    double c2 = cpu_now();
    if (b->rc == TB_OK) band_pixels(J, b, pix);
    free(items);
    free(pix);
    b->cpu_sim += c2 - c1;
    b->cpu_other += (c1 - c0) + (cpu_now() - c2);
}

/* Bands [g * nb / ngroups, (g + 1) * nb / ngroups) whose intervals wait,
 * as lanes of one batch: each band's figures are tb_span_run's. */
static void run_group(job *J, int g)
{
    int k0 = (int)((long long)J->nbands * g / J->ngroups), k1 = (int)((long long)J->nbands * (g + 1) / J->ngroups);
    tb_span_lane lanes[TB_SCENE_BANDS];
    int which[TB_SCENE_BANDS], n = 0;
    for (int k = k0; k < k1; k++) {
        band *b = &J->bands[k];
        if (!b->items) continue;
        which[n] = k;
        lanes[n++] = (tb_span_lane){ .items = b->items, .nitems = b->nitems, .pix = b->pix, .energy = J->energy,
                                     .ref = b->refpix };
    }
    if (!n) return;
    double c0 = cpu_now();
    tb_span_run_lanes_budget(J->u, J->cfg, J->fmts, lanes, (size_t)n, 1, J->max_se);
    double c1 = cpu_now();
    for (int i = 0; i < n; i++) {
        band *b = &J->bands[which[i]];
        b->st = lanes[i].st;
        b->rc = lanes[i].rc;
        snprintf(b->err, sizeof b->err, "%s", lanes[i].err);
        if (b->rc == TB_OK) band_pixels(J, b, b->pix);
        if (!b->borrowed) free(b->items);
        free(b->pix);
        b->items = NULL;
        b->pix = NULL;
    }
    J->gcpu_sim[g] = c1 - c0;
    J->gcpu_other[g] = cpu_now() - c1;
}

static void band_item(void *arg, size_t b)
{
    job *J = arg;
    run_band(J, &J->bands[b]);
}

/* A band of a prepared render (its intervals made already) on the kernel
 * alone: run_band's simulation. */
static void sim_band_item(void *arg, size_t k)
{
    job *J = arg;
    band *b = &J->bands[k];
    if (!b->items) return;
    double c0 = cpu_now();
    b->rc = J->energy ? tb_span_run_energy(J->u, J->cfg, J->fmts, b->items, b->nitems, b->pix, &b->st, NULL, b->err, sizeof b->err)
                      : tb_span_run(J->u, J->cfg, J->fmts, b->items, b->nitems, b->pix, &b->st, NULL, b->err, sizeof b->err);
    double c1 = cpu_now();
    if (b->rc == TB_OK) band_pixels(J, b, b->pix);
    free(b->pix);
    b->pix = NULL;
    b->cpu_sim += c1 - c0;
    b->cpu_other += cpu_now() - c1;
}

/* What every render of one view of a description shares, whatever its
 * formats: the reference image, the degree and region images, the spans
 * and each band's intervals with their node intensities and counts. */
struct tb_scene_prep {
    scn_desc d;                    /* the description it was made from */
    const scn_gbuf *g;
    int heldout, nb;
    size_t nspans;
    scn_span *spans;
    double *ref;
    uint8_t *deg, *region;
    band bands[TB_SCENE_BANDS];    /* items kept (pix NULL), refpix made */
    double sum_ref2;               /* sum ref^2 over covered pixels: NMSE's denominator */
    double cpu;
    /* tb_scene_prep_unit: the unit and configuration of ud */
    int have_unit;
    scn_desc ud;
    const unit_desc *u;
    unit_cfg cfg;
};

/* d renders like p's description but for its width and formats (and
 * what only the unit or the operation weights read): the prepared
 * intervals are d's. */
static int prep_fits(const tb_scene_prep *p, const scn_desc *d)
{
    scn_desc a = *d, b = p->d;
    memcpy(a.fmt_width, b.fmt_width, sizeof a.fmt_width);
    a.nfmt = b.nfmt;
    memcpy(a.fmt, b.fmt, sizeof a.fmt);
    memcpy(a.rnd, b.rnd, sizeof a.rnd);
    memcpy(a.ovf, b.ovf, sizeof a.ovf);
    memcpy(a.schedule, b.schedule, sizeof a.schedule);
    memcpy(a.cost, b.cost, sizeof a.cost);
    return !memcmp(&a, &b, sizeof a);
}

static void group_item(void *arg, size_t g)
{
    run_group(arg, (int)g);
}

/* On 8 bits: round(255 clamp(v, 0, 1)), what the images show. */
uint8_t tb_scene_to8(double v)
{
    if (!(v > 0)) return 0;     /* NaN too */
    if (v >= 1) return 255;
    return (uint8_t)floor(255 * v + 0.5);
}

/* The figures over covered pixels, from the two images. */
static void metrics(const scn_gbuf *g, tb_scene_result *r)
{
    double se = 0, sr = 0, se8 = 0, sr8 = 0, maxe = 0;
    int max8 = 0;
    size_t diff = 0, n = 0;
    for (size_t i = 0; i < (size_t)g->w * g->h; i++) {
        if (g->tri[i] < 0) continue;
        double e = r->hw[i] - r->ref[i];
        se += e * e;
        sr += r->ref[i] * r->ref[i];
        if (fabs(e) > maxe || isnan(e)) maxe = fabs(e);
        int r8 = tb_scene_to8(r->ref[i]), e8 = abs((int)tb_scene_to8(r->hw[i]) - r8);
        se8 += (double)e8 * e8;
        sr8 += (double)r8 * r8;
        if (e8 > max8) max8 = e8;
        if (e8) diff++;
        n++;
    }
    r->covered = n;
    r->nmse = sr > 0 ? se / sr : (se > 0 ? INFINITY : 0);
    r->nmse8 = sr8 > 0 ? se8 / sr8 : (se8 > 0 ? INFINITY : 0);
    r->max_abs_err = maxe;
    r->max_err8 = max8;
    r->diff8_share = n ? (double)diff / n : 0;
    r->psnr = se8 > 0 ? 10 * log10(255.0 * 255.0 / (se8 / n)) : INFINITY;
}

/* r's images (copied from prep p, or empty), the spans (p's, or g's own)
 * and nb bands (p's intervals borrowed, with room for their pixels). Out
 * of memory: base_out_of_memory. */
static void render_alloc(const scn_gbuf *g, const tb_scene_prep *p, tb_scene_result *r, scn_span **spansp,
                         size_t *nspansp, int *nbp, band **bandsp)
{
    size_t np = (size_t)g->w * g->h;
    r->w = g->w;
    r->h = g->h;
    r->ref = p ? malloc((np ? np : 1) * sizeof *r->ref) : calloc(np ? np : 1, sizeof *r->ref);
    r->hw = calloc(np ? np : 1, sizeof *r->hw);
    r->deg = p ? malloc(np ? np : 1) : calloc(np ? np : 1, 1);
    r->region = p ? malloc(np ? np : 1) : calloc(np ? np : 1, 1);
    scn_span *spans = NULL;
    size_t nspans = p ? p->nspans : scn_spans(g, &spans);
    if (p) spans = p->spans;
    int nb = g->h < TB_SCENE_BANDS ? g->h : TB_SCENE_BANDS;
    band *bands = calloc(nb > 0 ? nb : 1, sizeof *bands);
    for (int k = 0; p && bands && k < nb; k++) {
        bands[k] = p->bands[k];
        bands[k].borrowed = 1;
        bands[k].cpu_sim = bands[k].cpu_other = 0;
        if (bands[k].items && !(bands[k].pix = malloc(bands[k].npix * sizeof *bands[k].pix))) base_out_of_memory();
    }
    if (!r->ref || !r->hw || !r->deg || !r->region || !bands || (nspans && !spans)) base_out_of_memory();
    if (p) {
        memcpy(r->ref, p->ref, np * sizeof *r->ref);
        memcpy(r->deg, p->deg, np);
        memcpy(r->region, p->region, np);
    } else
        for (size_t i = 0; i < np; i++) if (g->tri[i] >= 0) r->region[i] = g->region[i];
    r->spans = nspans;
    *spansp = spans;
    *nspansp = nspans;
    *nbp = nb;
    *bandsp = bands;
}

/* Bands of equal rows (spans are in row order); the VCD, if any, is of
 * the first band with a span. */
static void split_bands(job *J, size_t nspans)
{
    const scn_gbuf *g = J->g;
    int nb = J->nbands;
    size_t s = 0;
    for (int k = 0; k < nb; k++) {
        band *b = &J->bands[k];
        b->y0 = (int)((long long)g->h * k / nb);
        b->y1 = (int)((long long)g->h * (k + 1) / nb);
        while (s < nspans && J->spans[s].y < b->y0) s++;
        b->s0 = s;
        while (s < nspans && J->spans[s].y < b->y1) s++;
        b->s1 = s;
        if (J->vcd_band < 0 && b->s1 > b->s0) J->vcd_band = k;
    }
}

/* Making a prep: keep in it what the simulation would read (the spans,
 * each band's intervals and reference pixels) and the images; bands and
 * r are freed. */
static int keep_prep(tb_scene_prep *make, const job *J, scn_span *spans, size_t nspans, char *err, size_t errlen)
{
    const scn_gbuf *g = J->g;
    tb_scene_result *r = J->r;
    size_t np = (size_t)g->w * g->h;
    int rc = TB_OK;
    make->g = g;
    make->heldout = r->heldout;
    make->nb = J->nbands;
    make->nspans = nspans;
    make->spans = spans;
    make->ref = r->ref;
    make->deg = r->deg;
    make->region = r->region;
    for (size_t i = 0; i < np; i++)
        if (g->tri[i] >= 0) make->sum_ref2 += make->ref[i] * make->ref[i];
    r->ref = NULL;
    r->deg = r->region = NULL;
    for (int k = 0; k < J->nbands; k++) {
        band *b = &J->bands[k];
        make->cpu += b->cpu_sim + b->cpu_other;
        free(b->pix);
        b->pix = NULL;
        if (b->rc != TB_OK && rc == TB_OK) {
            rc = b->rc;
            snprintf(err, errlen, "%s", b->err);
        }
        if (b->items && !(b->refpix = malloc(b->npix * sizeof *b->refpix))) base_out_of_memory();
        for (size_t q = 0, j = b->s0; b->refpix && j < b->s1; j++)
            for (int x = spans[j].x0; x < spans[j].x1; x++)
                b->refpix[q++] = make->ref[(size_t)spans[j].y * g->w + x];
        make->bands[k] = *b;
    }
    free(J->bands);
    tb_scene_free(r);
    return rc;
}

/* The bands' figures summed into r in band order (the first band's
 * error, if any, in err); adds, hdeg: the coefficient network's and
 * Horner's adds over all intervals and pixels. */
static int sum_bands(const job *J, double *adds, double *hdeg, char *err, size_t errlen)
{
    tb_scene_result *r = J->r;
    int rc = TB_OK;
    *adds = *hdeg = 0;
    for (int k = 0; k < J->nbands; k++) {
        const band *b = &J->bands[k];
        if (b->rc != TB_OK && rc == TB_OK) {
            rc = b->rc;
            snprintf(err, errlen, "%s", b->err);
        }
        r->hwst.clocks += b->st.clocks;
        r->hwst.pixels += b->st.pixels;
        r->hwst.items += b->st.items;
        r->hwst.items_deg2 += b->st.items_deg2;
        r->hwst.overflows += b->st.overflows;
        if (b->st.area_ge > r->hwst.area_ge) r->hwst.area_ge = b->st.area_ge;
        r->hwst.toggles += b->st.toggles;
        r->hwst.energy_pj += b->st.energy_pj;
        r->intervals += b->intervals;
        r->intervals_deg2 += b->deg2;
        r->nodes_shaded += b->nodes;
        *adds += b->coef_adds;
        *hdeg += b->horner_deg;
        r->cpu_sim += b->cpu_sim;
        r->cpu_render += b->cpu_sim + b->cpu_other;
    }
    for (int k = 0; J->batch && k < J->ngroups; k++) {
        r->cpu_sim += J->gcpu_sim[k];
        r->cpu_render += J->gcpu_sim[k] + J->gcpu_other[k];
    }
    return rc;
}

/* The figures per covered pixel: clocks, energy, the operation counts
 * and costs of the reference and of the method, and the speedups. */
static void per_pixel(const scn_desc *d, const scn_view *view, tb_scene_result *r, double adds, double hdeg)
{
    size_t px = r->covered;
    r->clocks_per_pixel = px ? (double)r->hwst.clocks / px : 0;
    r->energy_pj_per_pixel = r->hwst.pixels ? r->hwst.energy_pj / (double)r->hwst.pixels : 0;
    r->deg2_share = r->intervals ? (double)r->intervals_deg2 / r->intervals : 0;
    double pt[SCN_OP__COUNT];
    tb_scene_point_ops(d, view, pt);
    for (int k = 0; k < SCN_OP__COUNT; k++) {
        r->ops_ref[k] = px ? pt[k] : 0;
        r->ops_hw[k] = px ? pt[k] * (double)r->nodes_shaded / px : 0;
    }
    if (px) {
        r->ops_hw[SCN_OP_ADD] += adds / px + hdeg / px;     /* network; Horner adds */
        r->ops_hw[SCN_OP_MUL] += hdeg / px + 1;             /* Horner muls; t = k * (1/dv) */
    }
    for (int k = 0; k < SCN_OP__COUNT; k++) {
        r->cost_ref += r->ops_ref[k] * d->cost[k];
        r->cost_hw += r->ops_hw[k] * d->cost[k];
    }
    /* a ratio of two totals, whatever they are: all-zero weights give
     * 0 / 0, not defined, so nan (null in JSON, docs/cli.md), never 0 */
    r->speedup = r->cost_ref / r->cost_hw;
    r->long_ref = tb_scene_long_ops(r->ops_ref);
    r->long_hw = tb_scene_long_ops(r->ops_hw);
    r->speedup_long = r->long_ref / r->long_hw;
}

/* The render. p: NULL, or the reference, degrees and intervals prepared
 * already (then only the simulation and what follows; no VCD). make:
 * NULL, or the reference, degrees and intervals are moved into it and no
 * simulation is done (r is left empty). */
static int render(const scn_desc *d, const scn_gbuf *g, tb_scene_shader fn, void *ctx, const tb_scene_opts *o,
                  const tb_scene_prep *p, tb_scene_prep *make, double max_nmse, tb_scene_result *r, char *err,
                  size_t errlen)
{
    double c0 = cpu_now();
    memset(r, 0, sizeof *r);
    tb_scene_opts dflt = { 1, 0, NULL, NULL, 0, 0, NULL, NULL };
    if (!o) o = &dflt;
    r->heldout = p ? p->heldout : o->heldout;
    if (p && p->have_unit && o->fmts && !memcmp(&p->ud, d, sizeof *d)) {
        /* the formats are given: the rule's would be thrown away */
        r->unit = p->u;
        r->cfg = p->cfg;
    } else if (tb_scene_unit(d, &r->unit, &r->cfg, &r->fmts, err, errlen)) {
        /* making a prep simulates nothing: it needs the configuration
         * (the intervals are cut by its L), not formats */
        if (!make || tb_scene_cfg(d, &r->unit, &r->cfg, err, errlen)) return TB_BADINPUT;
    }
    if (o->fmts) r->fmts = *o->fmts;
    const scn_view *view = r->heldout ? &d->heldout : &d->view;
    scn_span *spans;
    size_t nspans;
    int nb;
    band *bands;
    render_alloc(g, p, r, &spans, &nspans, &nb, &bands);
    job J = { .d = d, .g = g, .view = view, .fn = fn, .ctx = ctx, .u = r->unit, .cfg = &r->cfg,
              .fmts = &r->fmts, .spans = spans, .bands = bands, .nbands = nb, .vcd_band = -1,
              .vcd_path = p || make ? NULL : o->vcd_path, .batch = make || !o->no_batch, .energy = o->energy,
              .nodes = p || make ? NULL : o->nodes, .r = r, .max_se = INFINITY };
    /* a budget only with a prep (its reference in band order); a margin
     * far above the rounding of sums in another order, so that a render
     * within max_nmse is never stopped */
    if (p && max_nmse >= 0 && isfinite(max_nmse)) J.max_se = max_nmse * p->sum_ref2 * (1 + 1e-6);
    if (!p) split_bands(&J, nspans);
    int jobs = o->jobs < 1 ? 1 : o->jobs > 256 ? 256 : o->jobs;
    if (jobs > nb) jobs = nb;
    double c1 = cpu_now();
    if (!p) base_par_for((size_t)(nb > 0 ? nb : 0), jobs, band_item, &J);
    else if (!J.batch) base_par_for((size_t)(nb > 0 ? nb : 0), jobs, sim_band_item, &J);
    if (make) {
        int rc = keep_prep(make, &J, spans, nspans, err, errlen);
        make->cpu += c1 - c0;
        return rc;
    }
    if (J.batch) {
        /* then the bands' hardware, a group of lanes a thread */
        J.ngroups = jobs;
        base_par_for((size_t)J.ngroups, jobs, group_item, &J);
    }
    double c2 = cpu_now();
    double adds, hdeg;
    int rc = sum_bands(&J, &adds, &hdeg, err, errlen);
    free(bands);
    if (!p) free(spans);
    if (rc != TB_OK) { tb_scene_free(r); return rc; }
    metrics(g, r);
    per_pixel(d, view, r, adds, hdeg);
    r->cpu_render += (c1 - c0) + (cpu_now() - c2);
    return TB_OK;
}

int tb_scene_render_gbuf(const scn_desc *d, const scn_gbuf *g, tb_scene_shader fn, void *ctx,
                         const tb_scene_opts *o, tb_scene_result *r, char *err, size_t errlen)
{
    return render(d, g, fn, ctx, o, NULL, NULL, INFINITY, r, err, errlen);
}

void tb_scene_prep_free(tb_scene_prep *p)
{
    if (!p) return;
    for (int k = 0; k < p->nb; k++) {
        free(p->bands[k].items);
        free(p->bands[k].refpix);
    }
    free(p->spans);
    free(p->ref);
    free(p->deg);
    free(p->region);
    free(p);
}

int tb_scene_prep_new(const scn_desc *d, const scn_gbuf *g, int heldout, int jobs, tb_scene_prep **out,
                      char *err, size_t errlen)
{
    *out = NULL;
    /* the intervals are cut by L: the unit's range first (formats may
     * still be bad: a prep needs none) */
    const unit_desc *u;
    unit_cfg cfg;
    if (tb_scene_cfg(d, &u, &cfg, err, errlen)) return TB_BADINPUT;
    tb_scene_prep *p = calloc(1, sizeof *p);
    if (!p) base_out_of_memory();
    p->d = *d;
    tb_scene_opts o = { jobs, heldout, NULL, NULL, 0, 0, NULL, NULL };
    tb_scene_result r;
    int rc = render(d, g, NULL, NULL, &o, NULL, p, INFINITY, &r, err, errlen);
    if (rc != TB_OK) { tb_scene_prep_free(p); return rc; }
    *out = p;
    return TB_OK;
}

int tb_scene_prep_unit(tb_scene_prep *p, const scn_desc *d, char *err, size_t errlen)
{
    unit_fmts f;
    p->have_unit = 0;
    if (!prep_fits(p, d)) { snprintf(err, errlen, "tb_scene_prep_unit: the description does not fit the prep"); return -1; }
    if (tb_scene_unit(d, &p->u, &p->cfg, &f, err, errlen)) return -1;
    p->ud = *d;
    p->have_unit = 1;
    return 0;
}

double tb_scene_prep_cpu(const tb_scene_prep *p)
{
    return p ? p->cpu : 0;
}

int tb_scene_render_prep_budget(const scn_desc *d, const tb_scene_prep *p, const tb_scene_opts *o, double max_nmse,
                                tb_scene_result *r, char *err, size_t errlen)
{
    tb_scene_opts dflt = { 1, 0, NULL, NULL, 0, 0, NULL, NULL };
    tb_scene_opts q = o ? *o : dflt;
    q.heldout = p->heldout;
    if (!prep_fits(p, d)) return render(d, p->g, NULL, NULL, &q, NULL, NULL, INFINITY, r, err, errlen);
    return render(d, p->g, NULL, NULL, &q, p, NULL, max_nmse, r, err, errlen);
}

int tb_scene_render_prep(const scn_desc *d, const tb_scene_prep *p, const tb_scene_opts *o, tb_scene_result *r,
                         char *err, size_t errlen)
{
    return tb_scene_render_prep_budget(d, p, o, INFINITY, r, err, errlen);
}


int tb_scene_render(const scn_desc *d, const scn_mesh *m, const tb_scene_opts *o,
                    tb_scene_result *r, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    double c0 = cpu_now();
    const scn_view *view = o && o->heldout ? &d->heldout : &d->view;
    scn_gbuf g;
    if (scn_raster(m, &view->cam, d->width, d->height, &g, err, errlen)) return TB_BADINPUT;
    double c1 = cpu_now();
    int rc = tb_scene_render_gbuf(d, &g, NULL, NULL, o, r, err, errlen);
    scn_gbuf_free(&g);
    if (rc == TB_OK) r->cpu_render += c1 - c0;    /* the rasterization */
    return rc;
}

void tb_scene_free(tb_scene_result *r)
{
    free(r->ref);
    free(r->hw);
    free(r->deg);
    free(r->region);
    r->ref = r->hw = NULL;
    r->deg = r->region = NULL;
}
