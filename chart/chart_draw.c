/* chart_draw.c - a chart drawn back to front from its layout
 * (chart_layout.c decides it first). */
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

/* A text that stays readable where it crosses lines: a white outline is
 * painted under the glyphs. */
#define CHART_HALO "stroke=\"#fff\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\""

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
            chart_addbox(&obst, bx);
        }
    const double fs = CHART_FS_SMALL, asc = 0.75 * fs, dsc = 0.22 * fs, gap = 5;
    /* The reference lines' labels (chart_draw_hlabels) are texts too. */
    for (size_t i = 0; i < c->nhl; i++) {
        const chart_hl *h = &c->hl[i];
        if (!h->label || !chart_shown_hl(c, h->y)) continue;
        double p = chart_pix(&l->ay, h->y), ty = p - 4 - 10 < l->T ? p + 13 : p - 4;
        double w = chart_textw(h->label, fs, chart_fit(l->R - l->L - 8, fs));
        chart_box bx = { l->R - 4 - w, ty - fs, l->R - 4, ty + 0.3 * fs };
        chart_addbox(&lab, bx);
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
    for (size_t k = 0; k < c->npl; k++) {
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
        chart_addbox(&lab, bx);
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
                chart_marker_paint(b, c, s, d.p);
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
