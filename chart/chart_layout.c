/* chart_layout.c - a chart's layout, decided before anything is drawn
 * (chart_int.h): axes, margins, the legend and its wrapped text, band
 * label rows, the spreading of markers that share a spot, and which
 * points are drawn at all. chart_draw.c draws from it. */
#include "base/base_out.h"
#include "chart/chart_int.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void chart_addbox(chart_boxes *bs, chart_box b)
{
    chart_grow((void **)&bs->v, &bs->cap, bs->n + 1, sizeof *bs->v);
    bs->v[bs->n++] = b;
}

int chart_overlap(chart_box a, chart_box b)
{
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/* Is the point (x, y) drawn? Else why not (for the footnote). */
int chart_visible(const chart *c, double x, double y)
{
    if (!isfinite(x) || !isfinite(y)) return CHART_NONFINITE;
    if ((c->log_x && x <= 0) || (c->log_y && y <= 0)) return CHART_NONPOS;
    return CHART_SHOWN;
}

/* Does series s draw anything (a marker, or a line of two points)? A
 * legend lists only what is drawn. */
int chart_draws(const chart *c, size_t s)
{
    const chart_ser *se = &c->ser[s];
    if (se->key) return 1;
    int prev = 0;
    for (size_t i = 0; i < se->n; i++) {
        int shown = chart_visible(c, se->pt[i].x, se->pt[i].y) == CHART_SHOWN;
        if (shown && (se->style & CHART_POINTS)) return 1;
        if (shown && prev) return 1;
        prev = shown;
    }
    return 0;
}

/* Append "N things why" to the footnote, "; "-separated. */
static void chart_footnote(char *s, size_t cap, size_t *len, size_t n,
                            const char *thing, const char *why)
{
    if (!n || *len + 1 >= cap) return;
    int r = snprintf(s + *len, cap - *len, "%s%zu %s%s %s", *len ? "; " : "", n,
                     thing, n == 1 ? "" : "s", why);
    if (r > 0) *len += (size_t)r < cap - *len ? (size_t)r : cap - *len - 1;
}

int chart_shown_hl(const chart *c, double y)
{
    return isfinite(y) && !(c->log_y && y <= 0);
}

/* Band pixels and label rows. Labels go above the plot, in up to three
 * rows, so that they hide no data; returns the number of rows used. */
static int chart_layout_bands(chart_lay *l)
{
    const chart *c = l->c;
    chart_boxes placed = { 0 };
    int nrows = 0;
    for (size_t i = 0; i < c->nband; i++) {
        double x0 = c->band[i].x0, x1 = c->band[i].x1;
        l->brow[i] = -1;
        l->bx0[i] = l->bx1[i] = 0;
        if (isnan(x0) || isnan(x1) || (c->log_x && x1 <= 0)) continue;
        double p0 = c->log_x && x0 <= 0 ? l->L : chart_pix(&l->ax, x0);
        double p1 = chart_pix(&l->ax, x1);
        l->bx0[i] = p0 = fmax(l->L, fmin(l->R, p0));
        l->bx1[i] = p1 = fmax(l->L, fmin(l->R, p1));
        if (p1 <= p0 || !c->band[i].label) continue;
        double w = chart_textw(c->band[i].label, CHART_FS_SMALL, CHART_BANDMAX);
        double cx = fmax(l->L + w / 2, fmin(l->R - w / 2, (p0 + p1) / 2));
        for (int r = 0; r < CHART_BANDROWS && l->brow[i] < 0; r++) {
            /* rows as y bands [r, r+0.5]: overlap only within a row */
            chart_box bx = { cx - w / 2 - 4, r, cx + w / 2 + 4, r + 0.5 };
            int clash = 0;
            for (size_t j = 0; j < placed.n; j++) clash |= chart_overlap(bx, placed.v[j]);
            if (!clash) { l->brow[i] = r; chart_addbox(&placed, bx); }
        }
        if (l->brow[i] + 1 > nrows) nrows = l->brow[i] + 1;
    }
    free(placed.v);
    return nrows;
}

/* ---- series of equal values --------------------------------------------- */

/* Where points of different series fall on the same spot, one hides the
 * other (a sweep over overflow modes where wrap and sat never differ).
 * Such points, at the same 1/CHART_DQ of the data range each way, are set
 * side by side, CHART_DODGE pixels apart in x (closer when more than three
 * meet, to stay within the frame's padding), in series order: markers,
 * and the lines of series that repeat another whole (chart_twin); the
 * footnote says how many points moved. Rings (CHART_HOLLOW)
 * and staircases (CHART_STEP) mark other series' points on purpose and
 * stay where they are. Returns the number of points moved. */
typedef struct { long long qx, qy; size_t s, i; } chart_dkey;

static int chart_dcmp(const void *pa, const void *pb)
{
    const chart_dkey *a = pa, *b = pb;
    if (a->qx != b->qx) return a->qx < b->qx ? -1 : 1;
    if (a->qy != b->qy) return a->qy < b->qy ? -1 : 1;
    if (a->s != b->s) return a->s < b->s ? -1 : 1;
    return a->i < b->i ? -1 : a->i > b->i;
}

static double chart_q(double v, double lo, double span, int lg)
{
    return ((lg ? log10(v) : v) - lo) / span * CHART_DQ;
}

/* Is series s one of a set of series with the same points? Their lines
 * are moved with their markers (in parallel, where nothing else meets
 * them); other lines stay where they are, so that partly equal series get
 * no kinks, and only their markers step aside. */
int chart_twin(const chart_lay *l, size_t s)
{
    if (!l->same) return 0;
    if (l->same[s] >= 0) return 1;
    for (size_t t = s + 1; t < l->c->nser; t++)
        if (l->same[t] == (int)s) return 1;
    return 0;
}

static size_t chart_layout_dodge(chart_lay *l, double xmin, double xmax, double ymin, double ymax)
{
    const chart *c = l->c;
    size_t tot = 0, moved = 0;
    l->doff = calloc(c->nser + 1, sizeof *l->doff);
    if (!l->doff) base_out_of_memory();
    for (size_t s = 0; s < c->nser; s++) { l->doff[s] = tot; tot += c->ser[s].n; }
    l->dodge = calloc(tot ? tot : 1, sizeof *l->dodge);
    chart_dkey *k = malloc((tot ? tot : 1) * sizeof *k);
    if (!l->dodge || !k) base_out_of_memory();
    double x0 = c->log_x ? log10(xmin) : xmin, y0 = c->log_y ? log10(ymin) : ymin;
    double sx = (c->log_x ? log10(xmax) : xmax) - x0, sy = (c->log_y ? log10(ymax) : ymax) - y0;
    if (!(sx > 0) || !isfinite(sx)) sx = 1;
    if (!(sy > 0) || !isfinite(sy)) sy = 1;
    size_t nk = 0;
    for (size_t s = 0; s < c->nser; s++) {
        const chart_ser *se = &c->ser[s];
        if (se->key || (se->style & (CHART_HOLLOW | CHART_STEP)) || !((se->style & CHART_POINTS) || chart_twin(l, s)))
            continue;
        for (size_t i = 0; i < se->n; i++) {
            if (chart_visible(c, se->pt[i].x, se->pt[i].y) != CHART_SHOWN) continue;
            k[nk].qx = llround(chart_q(se->pt[i].x, x0, sx, c->log_x));
            k[nk].qy = llround(chart_q(se->pt[i].y, y0, sy, c->log_y));
            k[nk].s = s;
            k[nk++].i = i;
        }
    }
    qsort(k, nk, sizeof *k, chart_dcmp);
    for (size_t a = 0, b; a < nk; a = b) {
        size_t nd = 1;
        for (b = a + 1; b < nk && k[b].qx == k[a].qx && k[b].qy == k[a].qy; b++) nd += k[b].s != k[b - 1].s;
        if (nd < 2) continue;
        /* many series at one spot: closer, within the frame's padding */
        double step = fmin(CHART_DODGE, 2.0 * (CHART_PAD - 2) / (double)(nd - 1));
        size_t r = 0;
        for (size_t j = a; j < b; j++) {
            if (j > a && k[j].s != k[j - 1].s) r++;
            l->dodge[l->doff[k[j].s] + k[j].i] = ((double)r - (double)(nd - 1) / 2) * step;
        }
        moved += b - a;
    }
    free(k);
    return moved;
}

/* x pixel of point i of series s, set aside when it shares its spot. */
double chart_px(const chart_lay *l, size_t s, size_t i)
{
    double x = chart_pix(&l->ax, l->c->ser[s].pt[i].x);
    return l->dodge ? x + l->dodge[l->doff[s] + i] : x;
}

/* The series before s with exactly s's points, or -1. Rings and
 * staircases repeat other series' points on purpose: never twins. */
static int chart_same_series(const chart *c, size_t s)
{
    const int marks = CHART_HOLLOW | CHART_STEP;
    const chart_ser *a = &c->ser[s];
    if (a->key || !a->n || (a->style & marks)) return -1;
    for (size_t t = 0; t < s; t++) {
        const chart_ser *b = &c->ser[t];
        if (b->key || b->n != a->n || (b->style & marks)) continue;
        size_t i = 0;
        for (; i < a->n; i++) {
            double ax = a->pt[i].x, ay = a->pt[i].y, bx = b->pt[i].x, by = b->pt[i].y;
            if (!((ax == bx || (isnan(ax) && isnan(bx))) && (ay == by || (isnan(ay) && isnan(by))))) break;
        }
        if (i == a->n) return (int)t;
    }
    return -1;
}

/* ---- legend text ---------------------------------------------------------- */

/* Series s's legend text: its label, and "(= other)" when it repeats the
 * points of an earlier labelled series, which then hides it. */
void chart_leg_text(const chart_lay *l, size_t s, char *buf, size_t cap)
{
    const chart *c = l->c;
    int t = l->same ? l->same[s] : -1;
    if (t >= 0 && c->ser[t].label && *c->ser[t].label)
        snprintf(buf, cap, "%s (= %s)", c->ser[s].label, c->ser[t].label);
    else snprintf(buf, cap, "%s", c->ser[s].label);
}

/* Byte offset of code point k of s (or of its end). */
static size_t chart_cpoff(const char *s, size_t k)
{
    size_t b = 0;
    for (size_t n = 0; s[b] && n < k; n++) {
        b++;
        while (((unsigned char)s[b] & 0xC0) == 0x80) b++;
    }
    return b;
}

/* s in lines of at most max code points, broken at spaces where it can,
 * at most CHART_LEGLINES (the last one keeps the rest, to be cut with an
 * ellipsis). Line k is s[st[k] .. st[k] + ln[k]). Returns the count. */
int chart_wrap(const char *s, size_t max, size_t st[CHART_LEGLINES], size_t ln[CHART_LEGLINES])
{
    size_t pos = 0;
    int n = 0;
    while (n < CHART_LEGLINES) {
        const char *r = s + pos;
        size_t end = chart_cpoff(r, max);
        if (!r[end] || n == CHART_LEGLINES - 1) { st[n] = pos; ln[n++] = strlen(r); break; }
        size_t cut = 0;
        for (size_t b = 0; b <= end; b++)
            if (r[b] == ' ') cut = b;
        if (!cut) cut = end;
        st[n] = pos;
        ln[n++] = cut;
        pos += cut;
        while (s[pos] == ' ') pos++;
        if (!s[pos]) break;
    }
    return n;
}

/* A piece of a label (at most a line and a bit) as XML text, cut to maxcp. */
void chart_text_n(chart_buf *b, const char *s, size_t n, size_t maxcp)
{
    char tmp[512];
    if (n >= sizeof tmp) {
        n = sizeof tmp - 1;
        while (n && ((unsigned char)s[n] & 0xC0) == 0x80) n--;
    }
    memcpy(tmp, s, n);
    tmp[n] = 0;
    chart_text(b, tmp, maxcp);
}

/* Width of the widest line of the wrapped text at font size. */
static double chart_wrapw(const char *s, size_t max, double size)
{
    size_t st[CHART_LEGLINES], ln[CHART_LEGLINES];
    int n = chart_wrap(s, max, st, ln);
    double w = 0;
    char tmp[512];
    for (int k = 0; k < n; k++) {
        size_t m = ln[k] < sizeof tmp ? ln[k] : sizeof tmp - 1;
        memcpy(tmp, s + st[k], m);
        tmp[m] = 0;
        w = fmax(w, chart_textw(tmp, size, max));
    }
    return w;
}

/* Decide everything before drawing anything: axes, margins, legend. */
void chart_layout(chart_lay *l)
{
    const chart *c = l->c;
    size_t nshown = 0, nnonfin = 0, nnonpos = 0, lnonfin = 0, lnonpos = 0;
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (size_t s = 0; s < c->nser; s++)
        for (size_t i = 0; i < c->ser[s].n; i++) {
            double x = c->ser[s].pt[i].x, y = c->ser[s].pt[i].y;
            switch (chart_visible(c, x, y)) {
            case CHART_NONFINITE: nnonfin++; continue;
            case CHART_NONPOS: nnonpos++; continue;
            default: break;
            }
            nshown++;
            xmin = fmin(xmin, x); xmax = fmax(xmax, x);
            ymin = fmin(ymin, y); ymax = fmax(ymax, y);
        }
    /* A reference line is meant to be seen against the data: its y widens
     * the axis (but alone it does not make a chart). */
    for (size_t i = 0; i < c->nhl; i++) {
        double y = c->hl[i].y;
        if (!isfinite(y)) lnonfin++;
        else if (c->log_y && y <= 0) lnonpos++;
        else if (nshown) { ymin = fmin(ymin, y); ymax = fmax(ymax, y); }
    }
    l->same = malloc((c->nser ? c->nser : 1) * sizeof *l->same);
    if (!l->same) base_out_of_memory();
    for (size_t s = 0; s < c->nser; s++) l->same[s] = chart_same_series(c, s);
    size_t ndodge = nshown ? chart_layout_dodge(l, xmin, xmax, ymin, ymax) : 0;
    chart_footnote(l->foot, sizeof l->foot, &l->flen, ndodge, "point", "of equal value in two series or more set side by side");
    chart_footnote(l->foot, sizeof l->foot, &l->flen, nnonpos, "point", "<= 0 not shown");
    chart_footnote(l->foot, sizeof l->foot, &l->flen, nnonfin, "point", "NaN/inf not shown");
    chart_footnote(l->foot, sizeof l->foot, &l->flen, lnonpos, "line", "at y <= 0 not shown");
    chart_footnote(l->foot, sizeof l->foot, &l->flen, lnonfin, "line", "at NaN/inf not shown");

    /* y first: its tick labels' width sets the left margin, which sets the
     * room for the x tick labels. */
    l->have = nshown > 0;
    if (l->have) {
        if (c->log_y ? chart_log_fit(&l->ay, ymin, ymax, CHART_MAXINT)
                     : chart_lin_fit(&l->ay, ymin, ymax, CHART_MAXINT)) l->have = 0;
        else chart_labels(&l->ay);
    }

    /* The legend stands outside the plot on the right, so it never covers
     * data; long labels are cut rather than squeezing the plot. */
    double legtw = 0;
    for (size_t s = 0; s < c->nser; s++)
        if (c->ser[s].label && chart_draws(c, s)) {
            char t[512];
            chart_leg_text(l, s, t, sizeof t);
            l->nleg++;
            legtw = fmax(legtw, c->ser[s].key == 2 ? chart_wrapw(t, CHART_LEGMAX + 6, CHART_FS_TICK) - 32
                                                  : chart_wrapw(t, CHART_LEGMAX, CHART_FS_TICK));
        }
    l->legw = l->nleg ? 10 + 24 + 8 + legtw + 10 : 0;

    l->T = c->title && *c->title ? 48 : 24;
    l->B = CHART_VH - 52 - (l->flen ? 14 : 0);
    double ylw = l->have ? chart_maxlabw(&l->ay, CHART_FS_TICK) : 0;
    l->L = fmax(50, ceil(8 + (c->ylabel && *c->ylabel ? CHART_FS_AXIS + 10 : 0) + ylw + 9));
    l->R = floor(CHART_VW - (l->nleg ? l->legw + 15 + 8 : 24));

    /* x: fewer intervals while the tick labels would crowd each other. */
    if (l->have) {
        int ok = 0, m0 = CHART_MAXINT;
        double x0 = xmin, x1 = xmax;
        /* Whole-number data (bit widths): no tick between two of them. */
        if (c->int_x && !c->log_x) {
            if (x1 - x0 < 1) { x0 -= 1; x1 += 1; }
            if (x1 - x0 < m0) m0 = (int)floor(x1 - x0);
        }
        for (int mi = m0; mi >= 1 && !ok; mi--) {
            if (c->log_x ? chart_log_fit(&l->ax, x0, x1, mi)
                         : chart_lin_fit(&l->ax, x0, x1, mi)) break;
            chart_labels(&l->ax);
            double room = (l->R - l->L - 2 * CHART_PAD) / (double)(l->ax.nmaj > 1 ? l->ax.nmaj - 1 : 1);
            ok = mi == 1 || chart_maxlabw(&l->ax, CHART_FS_TICK) + 12 <= room;
        }
        if (!ok) l->have = 0;
    }
    /* The end ticks sit a little inside the frame, so that markers at the
     * data's extremes are not cut by it and the corner labels keep apart. */
    l->ax.p0 = l->L + CHART_PAD;
    l->ax.p1 = l->R - CHART_PAD;

    if (l->have && c->nband) {
        l->bx0 = calloc(c->nband, sizeof *l->bx0);
        l->bx1 = calloc(c->nband, sizeof *l->bx1);
        l->brow = calloc(c->nband, sizeof *l->brow);
        if (!l->bx0 || !l->bx1 || !l->brow) base_out_of_memory();
        l->T += 13 * chart_layout_bands(l);
    }
    l->ay.p0 = l->B - CHART_PAD;
    l->ay.p1 = l->T + CHART_PAD;
}
