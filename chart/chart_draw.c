/* chart_draw.c - layout (margins, legend, band label rows, point label
 * places) decided first, then drawing back to front. */
#include "chart/chart_int.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Okabe & Ito, "Color Universal Design" (2008), without the yellow, which
 * is invisible on white. Readable for the common colour-vision deficiencies;
 * the marker shapes (and dashes past the 7th series) back the colours up in
 * greyscale prints. */
static const char *const chart_palette[] = {
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"
};
#define CHART_NCOLOR 7
#define CHART_NSHAPE 5

typedef struct { double x0, y0, x1, y1; } chart_box;

typedef struct {
    chart_box *v;
    size_t n, cap;
} chart_boxes;

static void chart_addbox(chart_boxes *bs, chart_box b, chart_buf *out)
{
    if (chart_grow((void **)&bs->v, &bs->cap, bs->n + 1, sizeof *bs->v)) { out->oom = 1; return; }
    bs->v[bs->n++] = b;
}

static int chart_overlap(chart_box a, chart_box b)
{
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/* Is point i of series s drawn? Else why not (for the footnote). */
enum { CHART_SHOWN, CHART_NONFINITE, CHART_NONPOS };

static int chart_visible(const chart *c, double x, double y)
{
    if (!isfinite(x) || !isfinite(y)) return CHART_NONFINITE;
    if ((c->log_x && x <= 0) || (c->log_y && y <= 0)) return CHART_NONPOS;
    return CHART_SHOWN;
}

static void chart_marker(chart_buf *b, int shape, double x, double y, double r)
{
    switch (shape) {
    case 0:   /* circle, as two arcs (a path holds all markers of a series) */
        chart_f(b, "M%f %fa%f %f 0 1 0 %f 0a%f %f 0 1 0 %f 0Z",
                 x - r, y, r, r, 2 * r, r, r, -2 * r);
        break;
    case 1: { /* square, area close to the circle's */
        double h = 0.9 * r;
        chart_f(b, "M%f %fh%fv%fh%fZ", x - h, y - h, 2 * h, 2 * h, -2 * h);
        break;
    }
    case 2:   /* triangle up */
        chart_f(b, "M%f %fl%f %fh%fZ", x, y - 1.25 * r, 1.15 * r, 2 * r, -2.3 * r);
        break;
    case 3:   /* diamond */
        chart_f(b, "M%f %fl%f %fl%f %fl%f %fZ", x, y - 1.3 * r, 1.3 * r, 1.3 * r,
                 -1.3 * r, 1.3 * r, -1.3 * r, -1.3 * r);
        break;
    default:  /* triangle down */
        chart_f(b, "M%f %fl%f %fh%fZ", x, y + 1.25 * r, 1.15 * r, -2 * r, -2.3 * r);
        break;
    }
}

/* Series i's colour and marker shape: its own (chart_series_look) or
 * the palette's by index. */
static const char *chart_colour(const chart *c, size_t i)
{
    return c->ser[i].colour[0] ? c->ser[i].colour : chart_palette[i % CHART_NCOLOR];
}
static int chart_shape(const chart *c, size_t i)
{
    return c->ser[i].shape >= 0 ? c->ser[i].shape : (int)(i % CHART_NSHAPE);
}

/* Stroke attributes of series i's line. */
static void chart_linestyle(chart_buf *b, const chart *c, size_t i)
{
    int dash = c->ser[i].dash >= 0 ? c->ser[i].dash : i >= CHART_NCOLOR;
    chart_f(b, "fill=\"none\" stroke=\"%s\" stroke-width=\"%s\" "
             "stroke-linejoin=\"round\" stroke-linecap=\"round\"",
             chart_colour(c, i), dash ? "1.4" : "1.8");
    if (dash) chart_puts(b, " stroke-dasharray=\"6 3\"");
}

static double chart_marker_r(int style)
{
    return style & CHART_HOLLOW ? 6.5 : style & (CHART_LINE | CHART_STEP) ? 3.2 : 3.8;
}

/* The markers of a series (path data d) filled, or as rings (CHART_HOLLOW). */
static void chart_marker_paint(chart_buf *b, const chart *c, size_t s, const char *d)
{
    if (c->ser[s].style & CHART_HOLLOW)
        chart_f(b, "<path fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" d=\"%s\"/>\n", chart_colour(c, s), d);
    else    /* a thin white edge keeps overlapping markers apart */
        chart_f(b, "<path fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.6\" d=\"%s\"/>\n", chart_colour(c, s), d);
}

/* Does series s draw anything (a marker, or a line of two points)? A
 * legend lists only what is drawn. */
static int chart_draws(const chart *c, size_t s)
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

/* A text that stays readable where it crosses lines: a white outline is
 * painted under the glyphs. */
#define CHART_HALO "stroke=\"#fff\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\""

/* Append "N things why" to the footnote, "; "-separated. */
static void chart_footnote(char *s, size_t cap, size_t *len, size_t n,
                            const char *thing, const char *why)
{
    if (!n || *len + 1 >= cap) return;
    int r = snprintf(s + *len, cap - *len, "%s%zu %s%s %s", *len ? "; " : "", n,
                     thing, n == 1 ? "" : "s", why);
    if (r > 0) *len += (size_t)r < cap - *len ? (size_t)r : cap - *len - 1;
}

/* Everything the drawing steps share: the plot rectangle (frame) in whole
 * pixels, the fitted axes, and what was decided about legend and bands. */
typedef struct {
    const chart *c;
    chart_buf *b;
    int    have;            /* something to draw: else "no data" */
    double L, R, T, B;      /* frame */
    chart_axis ax, ay;
    size_t nleg;            /* labelled series */
    double legw;
    char   foot[200];
    size_t flen;
    double *bx0, *bx1;      /* per band: its pixels, cut to the frame */
    int   *brow;            /* per band: label row above the plot, or -1 */
    double *dodge;          /* per point (series s from doff[s]): x offset in pixels */
    size_t *doff;
    int   *same;            /* per series: an earlier series of the same points, or -1 */
} chart_lay;

#define CHART_PAD      10  /* end ticks this far inside the frame */
#define CHART_LEGMAX   26  /* legend text wrapped at this many characters */
#define CHART_LEGLINES 3   /* ... onto at most this many lines, the last cut */
#define CHART_DODGE    5   /* markers of equal value in different series: this far apart */
#define CHART_DQ       2000 /* "equal" position: the same 1/2000 of the data range */
#define CHART_BANDMAX  30  /* band labels likewise */
#define CHART_PLMAX    20  /* point labels likewise */
#define CHART_BANDROWS 4   /* rows for band labels; a label that fits none is dropped */

static int chart_shown_hl(const chart *c, double y)
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
            if (!clash) { l->brow[i] = r; chart_addbox(&placed, bx, l->b); }
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
static int chart_twin(const chart_lay *l, size_t s)
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
    for (size_t s = 0; l->doff && s < c->nser; s++) { l->doff[s] = tot; tot += c->ser[s].n; }
    l->dodge = calloc(tot ? tot : 1, sizeof *l->dodge);
    chart_dkey *k = malloc((tot ? tot : 1) * sizeof *k);
    if (!l->doff || !l->dodge || !k) { l->b->oom = 1; free(k); return 0; }
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
static double chart_px(const chart_lay *l, size_t s, size_t i)
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
static void chart_leg_text(const chart_lay *l, size_t s, char *buf, size_t cap)
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
static int chart_wrap(const char *s, size_t max, size_t st[CHART_LEGLINES], size_t ln[CHART_LEGLINES])
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
static void chart_text_n(chart_buf *b, const char *s, size_t n, size_t maxcp)
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
static void chart_layout(chart_lay *l)
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
    if (!l->same) l->b->oom = 1;
    for (size_t s = 0; l->same && s < c->nser; s++) l->same[s] = chart_same_series(c, s);
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
        if (!l->bx0 || !l->bx1 || !l->brow) { l->b->oom = 1; l->have = 0; }
        else l->T += 13 * chart_layout_bands(l);
    }
    l->ay.p0 = l->B - CHART_PAD;
    l->ay.p1 = l->T + CHART_PAD;
}

static void chart_draw_bands(const chart_lay *l)
{
    const chart *c = l->c;
    for (size_t i = 0; i < c->nband; i++) {
        if (l->bx1[i] <= l->bx0[i]) continue;
        chart_f(l->b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" "
                 "fill=\"#888\" fill-opacity=\"0.18\"/>\n",
                 l->bx0[i], l->T, l->bx1[i] - l->bx0[i], l->B - l->T);
        if (l->brow[i] < 0) continue;
        double w = chart_textw(c->band[i].label, CHART_FS_SMALL, CHART_BANDMAX);
        double cx = fmax(l->L + w / 2, fmin(l->R - w / 2, (l->bx0[i] + l->bx1[i]) / 2));
        chart_f(l->b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"%d\" "
                 "fill=\"#555\">", cx, l->T - 5 - 13 * l->brow[i], CHART_FS_SMALL);
        chart_text(l->b, c->band[i].label, CHART_BANDMAX);
        chart_puts(l->b, "</text>\n");
    }
}

/* Grid lines at the major ticks (not over the frame), light grey. */
static void chart_draw_grid(const chart_lay *l)
{
    chart_puts(l->b, "<path fill=\"none\" stroke=\"#e3e3e3\" stroke-width=\"1\" d=\"");
    for (size_t i = 0; i < l->ax.nmaj; i++) {
        double p = chart_snap(chart_upix(&l->ax, l->ax.maj[i]));
        if (p > l->L + 1 && p < l->R - 1) chart_f(l->b, "M%f %fV%f", p, l->T, l->B);
    }
    for (size_t i = 0; i < l->ay.nmaj; i++) {
        double p = chart_snap(chart_upix(&l->ay, l->ay.maj[i]));
        if (p > l->T + 1 && p < l->B - 1) chart_f(l->b, "M%f %fH%f", l->L, p, l->R);
    }
    chart_puts(l->b, "\"/>\n");
}

static void chart_draw_hlines(const chart_lay *l)
{
    for (size_t i = 0; i < l->c->nhl; i++)
        if (chart_shown_hl(l->c, l->c->hl[i].y))
            chart_f(l->b, "<path d=\"M%f %fH%f\" stroke=\"#444\" stroke-width=\"1.2\" "
                     "stroke-dasharray=\"7 4\"/>\n", l->L, chart_pix(&l->ay, l->c->hl[i].y), l->R);
}

/* Each series as one path for its line and one for its markers. */
static void chart_draw_series(const chart_lay *l)
{
    const chart *c = l->c;
    chart_buf d = { 0 };
    for (size_t s = 0; s < c->nser; s++) {
        const chart_ser *se = &c->ser[s];
        if (se->style & (CHART_LINE | CHART_STEP)) {
            d.n = 0;
            int pen = 0, twin = chart_twin(l, s);
            double px = 0, py = 0;
            for (size_t i = 0; i < se->n; i++) {
                if (chart_visible(c, se->pt[i].x, se->pt[i].y) != CHART_SHOWN) {
                    pen = 0;            /* a skipped point breaks the line */
                    continue;
                }
                double x = twin ? chart_px(l, s, i) : chart_pix(&l->ax, se->pt[i].x);
                double y = chart_pix(&l->ay, se->pt[i].y);
                if (!pen) chart_f(&d, "M%f %f", x, y);
                else if (se->style & CHART_STEP) {
                    if (x != px) chart_f(&d, "H%f", x);
                    if (y != py) chart_f(&d, "V%f", y);
                } else chart_f(&d, "L%f %f", x, y);
                pen = 1;
                px = x;
                py = y;
            }
            if (d.n) {
                chart_puts(l->b, "<path ");
                chart_linestyle(l->b, c, s);
                chart_f(l->b, " d=\"%s\"/>\n", d.p);
            }
        }
        if (se->style & CHART_POINTS) {
            d.n = 0;
            double r = chart_marker_r(se->style);
            for (size_t i = 0; i < se->n; i++)
                if (chart_visible(c, se->pt[i].x, se->pt[i].y) == CHART_SHOWN)
                    chart_marker(&d, chart_shape(c, s), chart_px(l, s, i),
                                  chart_pix(&l->ay, se->pt[i].y), r);
            if (d.n) chart_marker_paint(l->b, c, s, d.p);
        }
    }
    if (d.oom) l->b->oom = 1;
    free(d.p);
}

/* Point labels: the first of a few spots around the point where the text
 * overlaps no placed label and no marker and stays inside the frame;
 * failing that, the spot with the fewest marker overlaps; a label that
 * would overlap another text or leave the frame wherever it goes is
 * dropped. Greedy in the order the labels were given, which keeps the
 * output deterministic. */
static void chart_draw_plabels(const chart_lay *l)
{
    const chart *c = l->c;
    chart_buf *b = l->b;
    chart_boxes obst = { 0 }, lab = { 0 };
    for (size_t s = 0; s < c->nser; s++)
        for (size_t i = 0; i < c->ser[s].n; i++) {
            const chart_pt *pt = &c->ser[s].pt[i];
            if (chart_visible(c, pt->x, pt->y) != CHART_SHOWN) continue;
            double x = chart_px(l, s, i), y = chart_pix(&l->ay, pt->y);
            chart_box bx = { x - 4, y - 4, x + 4, y + 4 };
            chart_addbox(&obst, bx, b);
        }
    const double fs = CHART_FS_SMALL, asc = 0.75 * fs, dsc = 0.22 * fs, gap = 5;
    /* The reference lines' labels (chart_draw_hlabels) are texts too. */
    for (size_t i = 0; i < c->nhl; i++) {
        const chart_hl *h = &c->hl[i];
        if (!h->label || !chart_shown_hl(c, h->y)) continue;
        double p = chart_pix(&l->ay, h->y), ty = p - 4 - 10 < l->T ? p + 13 : p - 4;
        double w = chart_textw(h->label, fs, chart_fit(l->R - l->L - 8, fs));
        chart_box bx = { l->R - 4 - w, ty - fs, l->R - 4, ty + 0.3 * fs };
        chart_addbox(&lab, bx, b);
    }
    /* the grid lines a label should not sit on (chart_draw_grid's) */
    double gx[CHART_MAXMAJ], gy[CHART_MAXMAJ];
    size_t ngx = 0, ngy = 0;
    for (size_t i = 0; i < l->ax.nmaj; i++) {
        double p = chart_snap(chart_upix(&l->ax, l->ax.maj[i]));
        if (p > l->L + 1 && p < l->R - 1) gx[ngx++] = p;
    }
    for (size_t i = 0; i < l->ay.nmaj; i++) {
        double p = chart_snap(chart_upix(&l->ay, l->ay.maj[i]));
        if (p > l->T + 1 && p < l->B - 1) gy[ngy++] = p;
    }
    /* nudges of a spot, nearest first: dx away from the point (towards
     * it when negative; right and left for a centred spot), dy up or down */
    static const double nudge[][2] = { { 0, 0 }, { 0, -3 }, { 0, 3 }, { 3, 0 }, { 0, -6 }, { 0, 6 },
                                       { 3, -3 }, { 3, 3 }, { 6, 0 }, { 0, -9 }, { 0, 9 }, { -3, 0 } };
    const int nn = (int)(sizeof nudge / sizeof nudge[0]);
    for (size_t k = 0; k < c->npl && !b->oom; k++) {
        size_t ps = (size_t)c->pl[k].series;
        const chart_pt *pt = &c->ser[ps].pt[c->pl[k].idx];
        if (chart_visible(c, pt->x, pt->y) != CHART_SHOWN) continue;
        double x = chart_px(l, ps, c->pl[k].idx), y = chart_pix(&l->ay, pt->y);
        double w = chart_textw(c->pl[k].text, fs, CHART_PLMAX);
        /* per spot: offset of the text's left edge, of its baseline; the
         * side it lies on (+1 right, -1 left, 0 centred) */
        const double spot[6][3] = {
            { gap, -gap, 1 }, { gap, gap + asc, 1 }, { -gap - w, -gap, -1 },
            { -gap - w, gap + asc, -1 }, { -w / 2, -gap - 3, 0 }, { -w / 2, gap + 3 + asc, 0 },
        };
        /* score: outside the frame 1000, on a placed text 100 each, on a
         * grid line 10 each, on a marker 1 each; the first best wins */
        double bestx = 0, besty = 0;
        size_t bestscore = SIZE_MAX;
        for (int m = 0; m < nn && bestscore; m++)
            for (int q = 0; q < 6 && bestscore; q++) {
                double ox = spot[q][0] + (spot[q][2] != 0 ? spot[q][2] : 1) * nudge[m][0];
                double oy = spot[q][1] + nudge[m][1];
                chart_box bx = { x + ox, y + oy - asc, x + ox + w, y + oy + dsc };
                size_t score = 0;
                if (bx.x0 < l->L || bx.x1 > l->R || bx.y0 < l->T || bx.y1 > l->B) score += 1000;
                for (size_t j = 0; j < lab.n; j++) score += 100 * (size_t)chart_overlap(bx, lab.v[j]);
                /* a pixel of margin: a reader's box of the glyphs is a bit taller */
                for (size_t j = 0; j < ngx; j++) score += 10 * (size_t)(gx[j] > bx.x0 - 1 && gx[j] < bx.x1 + 1);
                for (size_t j = 0; j < ngy; j++) score += 10 * (size_t)(gy[j] > bx.y0 - 1 && gy[j] < bx.y1 + 1);
                for (size_t j = 0; j < obst.n; j++) score += (size_t)chart_overlap(bx, obst.v[j]);
                if (score < bestscore) { bestscore = score; bestx = ox; besty = oy; }
            }
        if (bestscore >= 100) continue;       /* on another text or outside: dropped */
        chart_box bx = { x + bestx, y + besty - asc, x + bestx + w, y + besty + dsc };
        chart_addbox(&lab, bx, b);
        chart_f(b, "<text x=\"%f\" y=\"%f\" font-size=\"%d\" fill=\"#333\" " CHART_HALO ">",
                 bx.x0, y + besty, CHART_FS_SMALL);
        chart_text(b, c->pl[k].text, CHART_PLMAX);
        chart_puts(b, "</text>\n");
    }
    free(obst.v);
    free(lab.v);
}

/* Reference line labels at the right end, above the line (below it when
 * the line runs along the top). */
static void chart_draw_hlabels(const chart_lay *l)
{
    for (size_t i = 0; i < l->c->nhl; i++) {
        const chart_hl *h = &l->c->hl[i];
        if (!h->label || !chart_shown_hl(l->c, h->y)) continue;
        double p = chart_pix(&l->ay, h->y);
        double ty = p - 4 - 10 < l->T ? p + 13 : p - 4;
        chart_f(l->b, "<text x=\"%f\" y=\"%f\" text-anchor=\"end\" font-size=\"%d\" fill=\"#333\" "
                 CHART_HALO ">", l->R - 4, ty, CHART_FS_SMALL);
        chart_text(l->b, h->label, chart_fit(l->R - l->L - 8, CHART_FS_SMALL));
        chart_puts(l->b, "</text>\n");
    }
}

/* Ticks outward (majors 5 px, minors 3 px) and their labels. */
static void chart_draw_ticks(const chart_lay *l)
{
    const chart_axis *ax = &l->ax, *ay = &l->ay;
    chart_puts(l->b, "<path fill=\"none\" stroke=\"#444\" stroke-width=\"1\" d=\"");
    for (size_t i = 0; i < ax->nmaj; i++)
        chart_f(l->b, "M%f %fv5", chart_snap(chart_upix(ax, ax->maj[i])), l->B + 1);
    for (size_t i = 0; i < ay->nmaj; i++)
        chart_f(l->b, "M%f %fh-5", l->L, chart_snap(chart_upix(ay, ay->maj[i])));
    for (size_t i = 0; i < ax->nmin; i++)
        chart_f(l->b, "M%f %fv3", chart_snap(chart_upix(ax, ax->min[i])), l->B + 1);
    for (size_t i = 0; i < ay->nmin; i++)
        chart_f(l->b, "M%f %fh-3", l->L, chart_snap(chart_upix(ay, ay->min[i])));
    chart_puts(l->b, "\"/>\n");
    for (size_t i = 0; i < ax->nmaj; i++)
        chart_ticklabel(l->b, &ax->lab[i], chart_upix(ax, ax->maj[i]), l->B + 19, "middle", 0);
    for (size_t i = 0; i < ax->nmlab; i++)
        chart_ticklabel(l->b, &ax->mlab[i], chart_upix(ax, ax->mlabpos[i]), l->B + 19, "middle", 1);
    for (size_t i = 0; i < ay->nmaj; i++)
        chart_ticklabel(l->b, &ay->lab[i], l->L - 8, chart_upix(ay, ay->maj[i]) + 4, "end", 0);
    for (size_t i = 0; i < ay->nmlab; i++)
        chart_ticklabel(l->b, &ay->mlab[i], l->L - 8, chart_upix(ay, ay->mlabpos[i]) + 4, "end", 1);
}

/* Title and axis labels, each cut to the room it has. */
static void chart_draw_texts(const chart_lay *l)
{
    const chart *c = l->c;
    chart_buf *b = l->b;
    if (c->title && *c->title) {
        /* Centred over the plot, or over the picture when too long for it. */
        double w = chart_textw(c->title, CHART_FS_TITLE, SIZE_MAX);
        double cx = w <= l->R - l->L ? (l->L + l->R) / 2 : CHART_VW / 2.0;
        chart_f(b, "<text x=\"%f\" y=\"30\" text-anchor=\"middle\" font-size=\"%d\">",
                 cx, CHART_FS_TITLE);
        chart_text(b, c->title, chart_fit(CHART_VW - 20, CHART_FS_TITLE));
        chart_puts(b, "</text>\n");
    }
    if (c->xlabel && *c->xlabel) {
        chart_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"%d\">",
                 (l->L + l->R) / 2, l->B + 42, CHART_FS_AXIS);
        chart_text(b, c->xlabel, chart_fit(l->R - l->L, CHART_FS_AXIS));
        chart_puts(b, "</text>\n");
    }
    if (c->ylabel && *c->ylabel) {
        /* Rotated, the glyphs extend left of the (vertical) baseline: it
         * sits one font height in from the edge. */
        double x = 8 + CHART_FS_AXIS, y = (l->T + l->B) / 2;
        chart_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"%d\" "
                 "transform=\"rotate(-90 %f %f)\">", x, y, CHART_FS_AXIS, x, y);
        chart_text(b, c->ylabel, chart_fit(l->B - l->T, CHART_FS_AXIS));
        chart_puts(b, "</text>\n");
    }
    if (l->flen)
        chart_f(b, "<text x=\"8\" y=\"%d\" font-size=\"%d\" fill=\"#555\">%t</text>\n",
                 CHART_VH - 8, CHART_FS_SMALL, l->foot);
}

/* Legend right of the plot, top-aligned with it: as many entries as fit
 * its height, then "+N more". A long text takes more lines (chart_wrap),
 * 13 pixels each below an entry's first. */
static void chart_draw_legend(const chart_lay *l)
{
    const chart *c = l->c;
    chart_buf *b = l->b;
    const double rowh = 18, lineh = 13, avail = l->B - l->T - 12;
    char t[512];
    size_t st[CHART_LEGLINES], ln[CHART_LEGLINES];
    /* how many entries fit, with a row kept for "+N more" when not all do */
    double used = 0, h[64];
    size_t shown = 0, n = 0;
    for (size_t s = 0; s < c->nser; s++) {
        if (!c->ser[s].label || !chart_draws(c, s)) continue;
        chart_leg_text(l, s, t, sizeof t);
        double hh = rowh + lineh * (chart_wrap(t, c->ser[s].key == 2 ? CHART_LEGMAX + 6 : CHART_LEGMAX, st, ln) - 1);
        if (n < 64) h[n] = hh;
        n++;
        if (used + hh <= avail && shown + 1 == n) { used += hh; shown++; }
    }
    if (shown < l->nleg) {
        while (shown > 0 && used + rowh > avail) used -= h[--shown < 64 ? shown : 63];
    }
    double lx = l->R + 15, ly = l->T;
    double lh = 8 + used + rowh * (shown < l->nleg) + 2;
    chart_f(b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" fill=\"#fff\" "
             "stroke=\"#ccc\" stroke-width=\"1\" rx=\"3\"/>\n",
             chart_snap(lx), chart_snap(ly), floor(l->legw), floor(lh));
    size_t row = 0;
    double top = ly + 4;                /* top of the next entry */
    for (size_t s = 0; s < c->nser && row < shown; s++) {
        const chart_ser *se = &c->ser[s];
        if (!se->label || !chart_draws(c, s)) continue;
        double cy = top + rowh / 2;
        int head = se->key == 2;
        size_t max = head ? CHART_LEGMAX + 6 : CHART_LEGMAX;
        chart_leg_text(l, s, t, sizeof t);
        int nl = chart_wrap(t, max, st, ln);
        if (!head) {
            if (se->style & (CHART_LINE | CHART_STEP)) {
                chart_f(b, "<path d=\"M%f %fh24\" ", lx + 10, cy);
                chart_linestyle(b, c, s);
                chart_puts(b, "/>\n");
            }
            if (se->style & CHART_POINTS) {
                chart_buf d = { 0 };
                chart_marker(&d, chart_shape(c, s), lx + 22, cy, chart_marker_r(se->style));
                if (d.oom) b->oom = 1;
                else chart_marker_paint(b, c, s, d.p);
                free(d.p);
            }
        }
        /* a heading's text from the left edge, in grey */
        for (int k = 0; k < nl; k++) {
            chart_f(b, "<text x=\"%f\" y=\"%f\"%s>", lx + (head ? 10 : 42), cy + 4 + lineh * k,
                    head ? " fill=\"#555\"" : "");
            chart_text_n(b, t + st[k], ln[k], max);
            chart_puts(b, "</text>\n");
        }
        top += rowh + lineh * (nl - 1);
        row++;
    }
    if (shown < l->nleg)
        chart_f(b, "<text x=\"%f\" y=\"%f\" fill=\"#666\">+%d more</text>\n",
                 lx + 42, top + rowh / 2 + 4, (int)(l->nleg - shown));
}

void chart_render(const chart *c, chart_buf *b)
{
    chart_lay l;
    memset(&l, 0, sizeof l);
    l.c = c;
    l.b = b;
    chart_layout(&l);

    chart_f(b, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
             "viewBox=\"0 0 %d %d\" font-family=\"sans-serif\" font-size=\"%d\" fill=\"#222\">\n",
             CHART_VW, CHART_VH, CHART_VW, CHART_VH, CHART_FS_TICK);
    if (c->title && *c->title) chart_f(b, "<title>%t</title>\n", c->title);
    chart_f(b, "<rect width=\"%d\" height=\"%d\" fill=\"#fff\"/>\n", CHART_VW, CHART_VH);
    /* Back to front: bands, grid, reference lines, data, labels on top. */
    if (l.have) {
        chart_draw_bands(&l);
        chart_draw_grid(&l);
        chart_draw_hlines(&l);
        chart_draw_series(&l);
        chart_draw_plabels(&l);
        chart_draw_hlabels(&l);
    } else {
        chart_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"14\" "
                 "fill=\"#888\">no data</text>\n", (l.L + l.R) / 2, (l.T + l.B) / 2 + 5);
    }
    chart_f(b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" fill=\"none\" "
             "stroke=\"#444\" stroke-width=\"1\"/>\n", l.L + 0.5, l.T + 0.5, l.R - l.L, l.B - l.T);
    if (l.have) chart_draw_ticks(&l);
    chart_draw_texts(&l);
    if (l.nleg) chart_draw_legend(&l);
    chart_puts(b, "</svg>\n");
    free(l.bx0);
    free(l.bx1);
    free(l.brow);
    free(l.dodge);
    free(l.doff);
    free(l.same);
}
