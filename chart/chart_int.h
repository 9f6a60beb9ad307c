/* chart_int.h - what the files of the chart module share; not for use
 * outside chart/ (the public interface is chart.h).
 *
 *   chart.c         the chart as recorded (the building calls) and writing
 *   chart_svg.c     the output buffer: locale-independent numbers, XML text,
 *                   text width estimates, a small printf for SVG
 *   chart_axis.c    axes: 1-2-5 and decade ticks, tick labels, pixels
 *   chart_layout.c  layout: margins, legend, band label rows, markers set
 *                   apart, which points are drawn
 *   chart_draw.c    drawing, back to front
 *   chart_pareto.c  Pareto fronts (uses nothing of the others)
 */
#ifndef CHART_INT_H
#define CHART_INT_H
#include "chart/chart.h"
#include <stddef.h>

/* ---- layout constants (pixels of the 800x500 viewBox) ---------------- */

#define CHART_VW       800
#define CHART_VH       500
#define CHART_MAXINT   8       /* at most this many tick intervals */
#define CHART_MAXMAJ   (CHART_MAXINT + 2)
#define CHART_MAXMIN   128
#define CHART_MAXMLAB  8
#define CHART_CHARW    0.6     /* mean advance of a sans-serif glyph, in em;
                                   a little generous for DejaVu Sans so that
                                   estimated boxes err towards more room */
#define CHART_FS_TITLE 16
#define CHART_FS_AXIS  13
#define CHART_FS_TICK  11
#define CHART_FS_SMALL 10
#define CHART_SUPSCALE 0.75   /* exponent size relative to the label */

/* ---- the chart as recorded ------------------------------------------- */

typedef struct { double x, y; } chart_pt;

typedef struct {
    char      *label;
    int        style;
    chart_pt  *pt;
    size_t     n, cap;
    char       colour[8];   /* "#rrggbb", or "" for the palette's */
    int        shape;       /* marker shape, or -1 for the series index's */
    int        dash;        /* 1 dashed, 0 solid, -1 by index (dashed past the palette) */
    int        key;         /* a legend entry only (chart_legend_key) */
} chart_ser;

typedef struct { int series; size_t idx; char *text; } chart_plabel;
typedef struct { double x0, x1; char *label; } chart_band;
typedef struct { double y; char *label; } chart_hl;

struct chart {
    char *title, *xlabel, *ylabel;
    int   log_x, log_y;
    int   int_x;          /* x ticks at whole numbers only */
    chart_ser    *ser;   size_t nser, capser;
    chart_plabel *pl;    size_t npl, cappl;
    chart_band   *band;  size_t nband, capband;
    chart_hl     *hl;    size_t nhl, caphl;
    char  err[128];       /* first building error; reported by write */
};

/* Make room for need elements in *p (capacity *cap, element size sz). */
void chart_grow(void **p, size_t *cap, size_t need, size_t sz);

/* ---- output buffer and locale-independent formatting ------------------ */

typedef struct { char *p; size_t n, cap; } chart_buf;

void   chart_puts(chart_buf *b, const char *s);
/* v with dec decimals, by hand (no locale, never -0); trim: no trailing 0s. */
size_t chart_fixed(char *out, size_t cap, double v, int dec, int trim);
/* Estimated width of s (at most maxcp code points) at font size. */
double chart_textw(const char *s, double size, size_t maxcp);
/* How many code points fit in width at font size. */
size_t chart_fit(double width, double size);
/* s as XML text, cut to maxcp code points with an ellipsis. */
void   chart_text(chart_buf *b, const char *s, size_t maxcp);
/* printf for SVG: %s raw, %t escaped text, %d int, %f coordinate, %%. */
void   chart_f(chart_buf *b, const char *fmt, ...);

/* ---- axes ------------------------------------------------------------- */

/* A tick label: base text, and for "10^k" forms an exponent drawn raised. */
typedef struct { char base[40]; char sup[16]; } chart_lab;

typedef struct {
    int    log;
    double lo, hi;                /* limits; for log axes in decades (log10) */
    double lov, hiv;              /* log axes: the limits as values (1, 2 or 5 x 10^k) */
    double step;                  /* linear step, or decades per major tick */
    int    k;                     /* linear: step = m * 10^k */
    size_t nmaj, nmin;
    double maj[CHART_MAXMAJ];     /* in axis units (log10 on log axes) */
    double min[CHART_MAXMIN];
    chart_lab lab[CHART_MAXMAJ];
    size_t nmlab;                 /* labelled minor ticks (short log axes) */
    double mlabpos[CHART_MAXMLAB];
    chart_lab mlab[CHART_MAXMLAB];
    double p0, p1;                /* pixels of lo and hi */
} chart_axis;

/* Ticks covering [dmin, dmax] in at most maxint intervals; 0, or -1 when
 * the range is unusable. */
int    chart_lin_fit(chart_axis *a, double dmin, double dmax, int maxint);
int    chart_log_fit(chart_axis *a, double dmin, double dmax, int maxint);
void   chart_labels(chart_axis *a);           /* the tick labels of a fitted axis */
double chart_maxlabw(const chart_axis *a, double size);
double chart_upix(const chart_axis *a, double t);   /* axis units to pixels */
double chart_pix(const chart_axis *a, double v);    /* data to pixels */
double chart_snap(double v);                        /* to a pixel centre */
void   chart_ticklabel(chart_buf *b, const chart_lab *l, double x, double y,
                       const char *anchor, int minor);

/* ---- layout (chart_layout.c), read by the drawing (chart_draw.c) ------- */

/* Boxes of placed text, kept apart (chart_overlap). */
typedef struct { double x0, y0, x1, y1; } chart_box;

typedef struct {
    chart_box *v;
    size_t n, cap;
} chart_boxes;

/* Whether a point is drawn, else why not (chart_visible). */
enum { CHART_SHOWN, CHART_NONFINITE, CHART_NONPOS };

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

void   chart_addbox(chart_boxes *bs, chart_box b);
int    chart_overlap(chart_box a, chart_box b);
int    chart_visible(const chart *c, double x, double y);   /* CHART_SHOWN or why not */
int    chart_draws(const chart *c, size_t s);   /* series s draws a marker or a line: listed */
int    chart_shown_hl(const chart *c, double y);   /* a horizontal line at y can be drawn */
void   chart_layout(chart_lay *l);   /* decide everything from l->c before drawing */
/* x pixel of point i of series s, set aside when it shares its spot. */
double chart_px(const chart_lay *l, size_t s, size_t i);
/* Series s is one of a set with the same points (their lines move too). */
int    chart_twin(const chart_lay *l, size_t s);
/* Series s's legend text: its label, "(= other)" when it repeats one. */
void   chart_leg_text(const chart_lay *l, size_t s, char *buf, size_t cap);
/* s in lines of at most max code points (starts st, lengths ln); returns
 * the number of lines. */
int    chart_wrap(const char *s, size_t max, size_t st[CHART_LEGLINES], size_t ln[CHART_LEGLINES]);
/* A piece of a label as XML text, cut to maxcp code points. */
void   chart_text_n(chart_buf *b, const char *s, size_t n, size_t maxcp);

/* The whole SVG of c into b. */
void   chart_render(const chart *c, chart_buf *b);
#endif
