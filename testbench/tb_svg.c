/* tb_svg.c - SVG chart writer; see tb_svg.h for what it promises.
 *
 * The chart only records what it is given. All layout happens in
 * tb_chart_write: the whole file is rendered into a memory buffer first, so
 * the file is written in one go and an out-of-memory midway never leaves a
 * half-written chart.
 */
#include "testbench/tb_svg.h"
#include "base/base_out.h"

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- layout constants (pixels of the 800x500 viewBox) ---------------- */

#define TB_SVG_VW       800
#define TB_SVG_VH       500
#define TB_SVG_MAXINT   8       /* at most this many tick intervals */
#define TB_SVG_MAXMAJ   (TB_SVG_MAXINT + 2)
#define TB_SVG_MAXMIN   128
#define TB_SVG_MAXMLAB  8
#define TB_SVG_CHARW    0.6     /* mean advance of a sans-serif glyph, in em;
                                   a little generous for DejaVu Sans so that
                                   estimated boxes err towards more room */
#define TB_SVG_FS_TITLE 16
#define TB_SVG_FS_AXIS  13
#define TB_SVG_FS_TICK  11
#define TB_SVG_FS_SMALL 10

/* Okabe & Ito, "Color Universal Design" (2008), without the yellow, which
 * is invisible on white. Readable for the common colour-vision deficiencies;
 * the marker shapes (and dashes past the 7th series) back the colours up in
 * greyscale prints. */
static const char *const tb_svg_palette[] = {
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"
};
#define TB_SVG_NCOLOR 7
#define TB_SVG_NSHAPE 5

/* ---- the chart as recorded ------------------------------------------- */

typedef struct { double x, y; } tb_svg_pt;

typedef struct {
    char      *label;
    int        style;
    tb_svg_pt *pt;
    size_t     n, cap;
    char       colour[8];   /* "#rrggbb", or "" for the palette's */
    int        shape;       /* marker shape, or -1 for the series index's */
    int        dash;        /* 1 dashed, 0 solid, -1 by index (dashed past the palette) */
    int        key;         /* a legend entry only (tb_chart_legend_key) */
} tb_svg_series;

typedef struct { int series; size_t idx; char *text; } tb_svg_plabel;
typedef struct { double x0, x1; char *label; } tb_svg_band;
typedef struct { double y; char *label; } tb_svg_hl;

struct tb_chart {
    char *title, *xlabel, *ylabel;
    int   log_x, log_y;
    int   int_x;          /* x ticks at whole numbers only */
    tb_svg_series *ser;   size_t nser, capser;
    tb_svg_plabel *pl;    size_t npl, cappl;
    tb_svg_band   *band;  size_t nband, capband;
    tb_svg_hl     *hl;    size_t nhl, caphl;
    char  err[128];       /* first building error; reported by write */
};

/* Make room for need elements in *p (capacity *cap, element size sz). */
static int tb_svg_grow(void **p, size_t *cap, size_t need, size_t sz)
{
    if (need <= *cap) return 0;
    size_t nc = *cap ? *cap : 8;
    while (nc < need) {
        if (nc > SIZE_MAX / 2) return -1;
        nc *= 2;
    }
    if (nc > SIZE_MAX / sz) return -1;
    void *q = realloc(*p, nc * sz);
    if (!q) return -1;
    *p = q;
    *cap = nc;
    return 0;
}

static char *tb_svg_strdup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static void tb_chart_fail(tb_chart *c, const char *msg)
{
    if (!c->err[0]) snprintf(c->err, sizeof c->err, "%s", msg);
}

/* Copy of an optional text; NULL stays NULL, a failed copy is an error. */
static char *tb_chart_text(tb_chart *c, const char *s)
{
    if (!s) return NULL;
    char *d = tb_svg_strdup(s);
    if (!d) tb_chart_fail(c, "out of memory");
    return d;
}

tb_chart *tb_chart_new(const char *title, const char *xlabel, const char *ylabel)
{
    tb_chart *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->title = tb_chart_text(c, title);
    c->xlabel = tb_chart_text(c, xlabel);
    c->ylabel = tb_chart_text(c, ylabel);
    if (c->err[0]) { tb_chart_free(c); return NULL; }
    return c;
}

void tb_chart_free(tb_chart *c)
{
    if (!c) return;
    free(c->title); free(c->xlabel); free(c->ylabel);
    for (size_t i = 0; i < c->nser; i++) { free(c->ser[i].label); free(c->ser[i].pt); }
    free(c->ser);
    for (size_t i = 0; i < c->npl; i++) free(c->pl[i].text);
    free(c->pl);
    for (size_t i = 0; i < c->nband; i++) free(c->band[i].label);
    free(c->band);
    for (size_t i = 0; i < c->nhl; i++) free(c->hl[i].label);
    free(c->hl);
    free(c);
}

void tb_chart_log_x(tb_chart *c, int on) { if (c) c->log_x = !!on; }
void tb_chart_log_y(tb_chart *c, int on) { if (c) c->log_y = !!on; }
void tb_chart_int_x(tb_chart *c, int on) { if (c) c->int_x = !!on; }

int tb_chart_series(tb_chart *c, const char *label, int style)
{
    if (!c) return -1;
    if (c->nser >= INT_MAX ||
        tb_svg_grow((void **)&c->ser, &c->capser, c->nser + 1, sizeof *c->ser)) {
        tb_chart_fail(c, "out of memory");
        return -1;
    }
    /* A series with neither bit would be invisible: default to points. */
    if (!(style & (TB_LINE | TB_POINTS | TB_STEP))) style = TB_POINTS;
    tb_svg_series *s = &c->ser[c->nser];
    memset(s, 0, sizeof *s);
    s->style = style;
    s->shape = -1;
    s->dash = -1;
    if (label && *label && !(s->label = tb_chart_text(c, label))) return -1;
    return (int)c->nser++;
}

void tb_chart_series_look(tb_chart *c, int series, const char *colour, int shape, int dashed)
{
    if (!c || series < 0 || (size_t)series >= c->nser) return;
    tb_svg_series *s = &c->ser[series];
    /* Only "#rrggbb": the colour goes into an attribute unescaped. */
    if (colour && strlen(colour) == 7 && colour[0] == '#' && strspn(colour + 1, "0123456789abcdefABCDEF") == 6)
        memcpy(s->colour, colour, 8);
    if (shape >= 0) s->shape = shape % 5;
    if (dashed >= 0) s->dash = !!dashed;
}

int tb_chart_legend_key(tb_chart *c, const char *label, const char *colour, int shape, int style)
{
    if (!c || !label || !*label) return -1;
    int k = tb_chart_series(c, label, style ? style : TB_POINTS);
    if (k < 0) return -1;
    c->ser[k].key = style ? 1 : 2;          /* 2: a heading, text only */
    tb_chart_series_look(c, k, colour ? colour : "#444444", shape, 0);
    return k;
}

/* Append a point; its index in the series, or SIZE_MAX after an error. */
static size_t tb_chart_add(tb_chart *c, int series, double x, double y)
{
    if (!c) return SIZE_MAX;
    if (series < 0 || (size_t)series >= c->nser) {
        char m[64];
        snprintf(m, sizeof m, "point for nonexistent series %d", series);
        tb_chart_fail(c, m);
        return SIZE_MAX;
    }
    tb_svg_series *s = &c->ser[series];
    if (tb_svg_grow((void **)&s->pt, &s->cap, s->n + 1, sizeof *s->pt)) {
        tb_chart_fail(c, "out of memory");
        return SIZE_MAX;
    }
    s->pt[s->n].x = x;
    s->pt[s->n].y = y;
    return s->n++;
}

void tb_chart_point(tb_chart *c, int series, double x, double y)
{
    tb_chart_add(c, series, x, y);
}

void tb_chart_point_label(tb_chart *c, int series, double x, double y, const char *label)
{
    size_t idx = tb_chart_add(c, series, x, y);
    if (idx == SIZE_MAX || !label || !*label) return;
    if (tb_svg_grow((void **)&c->pl, &c->cappl, c->npl + 1, sizeof *c->pl)) {
        tb_chart_fail(c, "out of memory");
        return;
    }
    char *t = tb_chart_text(c, label);
    if (!t) return;
    c->pl[c->npl].series = series;
    c->pl[c->npl].idx = idx;
    c->pl[c->npl].text = t;
    c->npl++;
}

void tb_chart_hband(tb_chart *c, double x0, double x1, const char *label)
{
    if (!c) return;
    if (tb_svg_grow((void **)&c->band, &c->capband, c->nband + 1, sizeof *c->band)) {
        tb_chart_fail(c, "out of memory");
        return;
    }
    char *t = NULL;
    if (label && *label && !(t = tb_chart_text(c, label))) return;
    c->band[c->nband].x0 = x0 <= x1 ? x0 : x1;
    c->band[c->nband].x1 = x0 <= x1 ? x1 : x0;
    c->band[c->nband].label = t;
    c->nband++;
}

void tb_chart_hline(tb_chart *c, double y, const char *label)
{
    if (!c) return;
    if (tb_svg_grow((void **)&c->hl, &c->caphl, c->nhl + 1, sizeof *c->hl)) {
        tb_chart_fail(c, "out of memory");
        return;
    }
    char *t = NULL;
    if (label && *label && !(t = tb_chart_text(c, label))) return;
    c->hl[c->nhl].y = y;
    c->hl[c->nhl].label = t;
    c->nhl++;
}

/* ---- Pareto front ----------------------------------------------------- */

typedef struct { double x, y; size_t i; } tb_svg_pp;

static int tb_svg_pp_cmp(const void *pa, const void *pb)
{
    const tb_svg_pp *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);   /* qsort is not stable */
}

size_t tb_pareto(const double *x, const double *y, size_t n, unsigned char *on_front)
{
    if (!on_front || n == 0) return 0;
    memset(on_front, 0, n);
    if (!x || !y) return 0;

    size_t count = 0;
    tb_svg_pp *p = n <= SIZE_MAX / sizeof *p ? malloc(n * sizeof *p) : NULL;
    if (!p) {
        /* No memory for the sort: the quadratic definition still works. */
        for (size_t i = 0; i < n; i++) {
            if (isnan(x[i]) || isnan(y[i])) continue;
            int dom = 0;
            for (size_t j = 0; j < n && !dom; j++)
                dom = x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i]);
            on_front[i] = !dom;
            count += !dom;
        }
        return count;
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (!isnan(x[i]) && !isnan(y[i])) { p[m].x = x[i]; p[m].y = y[i]; p[m].i = i; m++; }
    qsort(p, m, sizeof *p, tb_svg_pp_cmp);

    /* Sweep by increasing x. A group of equal x is sorted by y, so only its
     * smallest y (and exact copies of it) can be on the front, and only if
     * it beats every point of strictly smaller x: equal y there would be
     * dominated by the smaller x. */
    double best = 0;
    int have_best = 0;
    for (size_t g = 0; g < m;) {
        size_t h = g;
        while (h < m && p[h].x == p[g].x) h++;
        double ymin = p[g].y;
        int front = !have_best || ymin < best;
        for (size_t k = g; k < h; k++) {
            unsigned char on = front && p[k].y == ymin;
            on_front[p[k].i] = on;
            count += on;
        }
        if (front) { best = ymin; have_best = 1; }
        g = h;
    }
    free(p);
    return count;
}

typedef struct { double v[3]; size_t i; } tb_svg_p3;

static int tb_svg_p3_cmp(const void *pa, const void *pb)
{
    const tb_svg_p3 *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

/* b dominates a: no worse in every coordinate, better in one. */
static int tb_svg_dom3(const double *b, const double *a)
{
    return b[0] <= a[0] && b[1] <= a[1] && b[2] <= a[2] && (b[0] < a[0] || b[1] < a[1] || b[2] < a[2]);
}

size_t tb_pareto3(const double *x, const double *y, const double *z, size_t n, unsigned char *on_front)
{
    if (!on_front || n == 0) return 0;
    memset(on_front, 0, n);
    if (!x || !y || !z) return 0;
    tb_svg_p3 *p = n <= SIZE_MAX / sizeof *p ? malloc(n * sizeof *p) : NULL;
    size_t *front = n <= SIZE_MAX / sizeof *front ? malloc(n * sizeof *front) : NULL;
    size_t m = 0, nf = 0;
    if (!p || !front) {
        free(p);
        free(front);
        /* No memory for the sort: the quadratic definition. */
        for (size_t i = 0; i < n; i++) {
            double a[3] = { x[i], y[i], z[i] };
            if (isnan(a[0]) || isnan(a[1]) || isnan(a[2])) continue;
            int dom = 0;
            for (size_t j = 0; j < n && !dom; j++) {
                double b[3] = { x[j], y[j], z[j] };
                dom = tb_svg_dom3(b, a);
            }
            on_front[i] = !dom;
            nf += !dom;
        }
        return nf;
    }
    for (size_t i = 0; i < n; i++)
        if (!isnan(x[i]) && !isnan(y[i]) && !isnan(z[i])) {
            p[m].v[0] = x[i]; p[m].v[1] = y[i]; p[m].v[2] = z[i]; p[m].i = i; m++;
        }
    qsort(p, m, sizeof *p, tb_svg_p3_cmp);
    /* In lexicographic order a point's dominators all come before it, and
     * dominance is transitive, so some dominator is on the front: checking
     * against the front found so far is enough. */
    for (size_t k = 0; k < m; k++) {
        int dom = 0;
        for (size_t j = 0; j < nf && !dom; j++) dom = tb_svg_dom3(p[front[j]].v, p[k].v);
        if (!dom) { front[nf++] = k; on_front[p[k].i] = 1; }
    }
    free(p);
    free(front);
    return nf;
}

/* ---- output buffer and locale-independent formatting ------------------ */

typedef struct { char *p; size_t n, cap; int oom; } tb_svg_buf;

static void tb_svg_put(tb_svg_buf *b, const char *s, size_t len)
{
    if (b->oom) return;
    if (len >= SIZE_MAX - b->n ||
        tb_svg_grow((void **)&b->p, &b->cap, b->n + len + 1, 1)) {
        b->oom = 1;
        return;
    }
    memcpy(b->p + b->n, s, len);
    b->n += len;
    b->p[b->n] = 0;
}

static void tb_svg_puts(tb_svg_buf *b, const char *s) { tb_svg_put(b, s, strlen(s)); }

/* v with dec decimals (0..9) into out; trim drops trailing zeros. Done by
 * hand rather than with printf so that no locale can turn the point into a
 * comma, and so that -0 never appears. Values are clamped to +-1e9 and NaN
 * becomes 0: nothing in an 800x500 picture needs more. */
static size_t tb_svg_fixed(char *out, size_t cap, double v, int dec, int trim)
{
    static const long long p10[] = {
        1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000, 1000000000
    };
    if (dec < 0) dec = 0;
    if (dec > 9) dec = 9;
    if (isnan(v)) v = 0;
    if (v > 1e9) v = 1e9;
    if (v < -1e9) v = -1e9;
    long long q = llround(v * (double)p10[dec]);
    int neg = q < 0;
    unsigned long long u = neg ? (unsigned long long)-q : (unsigned long long)q;
    unsigned long long ip = u / (unsigned long long)p10[dec];
    unsigned long long fp = u % (unsigned long long)p10[dec];
    char frac[16];
    int nf = 0;
    for (int d = dec - 1; d >= 0; d--) frac[nf++] = (char)('0' + (fp / (unsigned long long)p10[d]) % 10);
    if (trim) while (nf > 0 && frac[nf - 1] == '0') nf--;
    int n = snprintf(out, cap, "%s%llu%s%.*s", neg && u ? "-" : "", ip, nf ? "." : "", nf, frac);
    return n < 0 ? 0 : (size_t)n < cap ? (size_t)n : cap ? cap - 1 : 0;
}

static void tb_svg_num(tb_svg_buf *b, double v)
{
    char t[40];
    tb_svg_put(b, t, tb_svg_fixed(t, sizeof t, v, 2, 1));
}

/* Next code point of UTF-8 text; invalid bytes decode as U+FFFD one at a
 * time, so any input yields well-formed output. */
static unsigned long tb_svg_utf8(const unsigned char **ps)
{
    const unsigned char *s = *ps;
    unsigned long c = s[0];
    int len = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 :
              (c & 0xF8) == 0xF0 ? 4 : 0;
    if (len == 1) { *ps = s + 1; return c; }
    if (len == 0) { *ps = s + 1; return 0xFFFD; }
    c &= 0x3F >> (len - 1);
    for (int i = 1; i < len; i++) {
        if ((s[i] & 0xC0) != 0x80) { *ps = s + 1; return 0xFFFD; }
        c = c << 6 | (s[i] & 0x3F);
    }
    static const unsigned long minv[] = { 0, 0, 0x80, 0x800, 0x10000 };
    if (c < minv[len] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) {
        *ps = s + 1;
        return 0xFFFD;
    }
    *ps = s + len;
    return c;
}

/* Code points of s as written by tb_svg_text (at most maxcp, with the
 * ellipsis when cut): the basis of every text width estimate. */
static size_t tb_svg_ncp(const char *s, size_t maxcp)
{
    size_t n = 0;
    if (!s) return 0;
    const unsigned char *p = (const unsigned char *)s;
    while (*p) { tb_svg_utf8(&p); n++; }
    return n > maxcp ? maxcp : n;
}

static double tb_svg_textw(const char *s, double size, size_t maxcp)
{
    return (double)tb_svg_ncp(s, maxcp) * TB_SVG_CHARW * size;
}

/* How many code points of text fit in width px at font size. */
static size_t tb_svg_fit(double width, double size)
{
    double n = floor(width / (TB_SVG_CHARW * size));
    return n < 1 ? 1 : (size_t)n;
}

/* Text content or attribute value: XML-escaped, control characters as
 * spaces (XML 1.0 forbids most of them), invalid UTF-8 as U+FFFD, and cut
 * to maxcp code points with an ellipsis as the last one. */
static void tb_svg_text(tb_svg_buf *b, const char *s, size_t maxcp)
{
    if (!s) return;
    size_t total = tb_svg_ncp(s, SIZE_MAX), k = 0;
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        if (total > maxcp && k + 1 == maxcp) { tb_svg_puts(b, "\xE2\x80\xA6"); break; }
        unsigned long c = tb_svg_utf8(&p);
        k++;
        switch (c) {
        case '&':  tb_svg_puts(b, "&amp;");  continue;
        case '<':  tb_svg_puts(b, "&lt;");   continue;
        case '>':  tb_svg_puts(b, "&gt;");   continue;
        case '"':  tb_svg_puts(b, "&quot;"); continue;
        case '\'': tb_svg_puts(b, "&apos;"); continue;
        default: break;
        }
        if (c < 0x20 || c == 0x7F) c = ' ';
        if (c == 0xFFFE || c == 0xFFFF) c = 0xFFFD;
        char u[4];
        size_t n;
        if (c < 0x80) { u[0] = (char)c; n = 1; }
        else if (c < 0x800) { u[0] = (char)(0xC0 | c >> 6); u[1] = (char)(0x80 | (c & 0x3F)); n = 2; }
        else if (c < 0x10000) {
            u[0] = (char)(0xE0 | c >> 12); u[1] = (char)(0x80 | (c >> 6 & 0x3F));
            u[2] = (char)(0x80 | (c & 0x3F)); n = 3;
        } else {
            u[0] = (char)(0xF0 | c >> 18); u[1] = (char)(0x80 | (c >> 12 & 0x3F));
            u[2] = (char)(0x80 | (c >> 6 & 0x3F)); u[3] = (char)(0x80 | (c & 0x3F)); n = 4;
        }
        tb_svg_put(b, u, n);
    }
}

/* A tiny printf for SVG: %s raw string, %t escaped text (no length cap),
 * %d int, %f coordinate (at most 2 decimals), %% itself. Not the C printf:
 * its %f goes through tb_svg_fixed for locale independence. */
static void tb_svg_f(tb_svg_buf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    for (const char *p = fmt; *p; p++) {
        const char *q = p;
        while (*q && *q != '%') q++;
        if (q > p) { tb_svg_put(b, p, (size_t)(q - p)); p = q; }
        if (!*p) break;
        char t[24];
        int n;
        switch (*++p) {
        case 's': tb_svg_puts(b, va_arg(ap, const char *)); break;
        case 't': tb_svg_text(b, va_arg(ap, const char *), SIZE_MAX); break;
        case 'd':
            n = snprintf(t, sizeof t, "%d", va_arg(ap, int));
            tb_svg_put(b, t, (size_t)n);
            break;
        case 'f': tb_svg_num(b, va_arg(ap, double)); break;
        case '%': tb_svg_put(b, "%", 1); break;
        default: p--; tb_svg_put(b, "%", 1); break;
        }
    }
    va_end(ap);
}

/* ---- axes ------------------------------------------------------------- */

/* A tick label: base text, and for "10^k" forms an exponent drawn raised. */
typedef struct { char base[40]; char sup[16]; } tb_svg_lab;

typedef struct {
    int    log;
    double lo, hi;                /* limits; for log axes in decades (log10) */
    double step;                  /* linear step, or decades per major tick */
    int    k;                     /* linear: step = m * 10^k */
    size_t nmaj, nmin;
    double maj[TB_SVG_MAXMAJ];    /* in axis units (log10 on log axes) */
    double min[TB_SVG_MAXMIN];
    tb_svg_lab lab[TB_SVG_MAXMAJ];
    size_t nmlab;                 /* labelled minor ticks (short log axes) */
    double mlabpos[TB_SVG_MAXMLAB];
    tb_svg_lab mlab[TB_SVG_MAXMLAB];
    double p0, p1;                /* pixels of lo and hi */
} tb_svg_axis;

static double tb_svg_pow10(int e) { return pow(10.0, (double)e); }

/* Linear ticks: the smallest 1/2/5 x 10^k step whose multiples cover the
 * data in at most maxint intervals. */
static int tb_svg_lin_fit(tb_svg_axis *a, double dmin, double dmax, int maxint)
{
    if (!isfinite(dmin) || !isfinite(dmax)) return -1;
    if (dmin > dmax) { double t = dmin; dmin = dmax; dmax = t; }
    /* span / maxint without overflowing for spans near DBL_MAX */
    double raw = dmax / maxint - dmin / maxint;
    if (dmax - dmin <= 1e-7 * fmax(fabs(dmin), fabs(dmax)) || !(raw >= DBL_MIN)) {
        /* One value, or values equal to 7 digits (which no tick labels of
         * sensible length could tell apart), or a span too small for a
         * double step: room either side of it. */
        double mid = dmin / 2 + dmax / 2;
        double pad = fabs(mid) >= 1e-300 ? fabs(mid) / 16 : 1;
        dmin = mid - pad;
        dmax = mid + pad;
        if (!isfinite(dmin)) dmin = -DBL_MAX;
        if (!isfinite(dmax)) dmax = DBL_MAX;
        raw = dmax / maxint - dmin / maxint;
    }
    int k = (int)floor(log10(raw));
    static const int mant[] = { 1, 2, 5 };
    double s = 0, i0 = 0, i1 = 0;
    int found = 0;
    /* From a step a bit under span/maxint up; the tolerance keeps a data
     * value that is a multiple of the step up to rounding (0.3/0.1) from
     * costing a whole extra interval. */
    for (int kk = k - 1; kk <= k + 2 && !found; kk++)
        for (int mi = 0; mi < 3 && !found; mi++) {
            s = mant[mi] * tb_svg_pow10(kk);
            if (!(s > 0) || !isfinite(s)) continue;
            i0 = floor(dmin / s + 1e-9);
            i1 = ceil(dmax / s - 1e-9);
            if (i1 - i0 <= maxint) { found = 1; a->k = kk; }
        }
    if (!found) return -1;
    a->log = 0;
    a->step = s;
    a->lo = i0 * s;
    a->hi = i1 * s;
    /* Within a step of DBL_MAX the covering tick does not exist: the limit
     * is then the data's own. */
    if (!isfinite(a->lo)) a->lo = dmin;
    if (!isfinite(a->hi)) a->hi = dmax;
    a->nmaj = 0;
    a->nmin = 0;
    for (double i = i0; i <= i1 && a->nmaj < TB_SVG_MAXMAJ; i++) {
        double v = i * s;
        if (!isfinite(v)) continue;
        if (fabs(v) < s * 1e-6) v = 0;     /* no -0 or 1e-17 at zero */
        a->maj[a->nmaj++] = v;
    }
    /* No minor ticks: on a linear axis they add clutter, not reading
     * precision (matplotlib's default too). */
    return 0;
}

/* Log ticks: decades covering the data; every s-th decade when there are
 * more than maxint. Minor ticks at 2..9 x 10^k, or, when majors skip
 * decades, at every decade (every s/5-th for strides of 10 and more). */
static int tb_svg_log_fit(tb_svg_axis *a, double dmin, double dmax, int maxint)
{
    if (dmin > dmax) { double t = dmin; dmin = dmax; dmax = t; }
    if (!(dmin > 0) || !isfinite(dmin) || !isfinite(dmax)) return -1;
    int e0 = (int)floor(log10(dmin)), e1 = (int)ceil(log10(dmax));
    /* log10 of a value next to a power of ten may round across it */
    if (e0 < 308 && tb_svg_pow10(e0 + 1) <= dmin) e0++;
    if (tb_svg_pow10(e0) > dmin) e0--;
    if (e1 > -330 && tb_svg_pow10(e1 - 1) >= dmax) e1--;
    if (tb_svg_pow10(e1) < dmax) e1++;
    if (e0 >= e1) { e0--; e1++; }           /* a single power of ten */
    static const int strides[] = { 1, 2, 3, 5, 10, 20, 50, 100, 200, 500 };
    int s = 1;
    for (size_t i = 0; i < sizeof strides / sizeof *strides; i++) {
        s = strides[i];
        int f0 = (int)floor((double)e0 / s), f1 = (int)ceil((double)e1 / s);
        if (f1 - f0 <= maxint) { e0 = f0 * s; e1 = f1 * s; break; }
    }
    a->log = 1;
    a->step = s;
    a->lo = e0;
    a->hi = e1;
    a->nmaj = 0;
    a->nmin = 0;
    for (int e = e0; e <= e1 && a->nmaj < TB_SVG_MAXMAJ; e += s) a->maj[a->nmaj++] = e;
    int ms = s <= 5 ? 1 : s / 5;
    for (int e = e0; e < e1; e++) {
        if (s == 1) {
            for (int m = 2; m <= 9 && a->nmin < TB_SVG_MAXMIN; m++)
                a->min[a->nmin++] = e + log10((double)m);
        } else if (e % s != 0 && e % ms == 0 && a->nmin < TB_SVG_MAXMIN) {
            a->min[a->nmin++] = e;
        }
    }
    return 0;
}

size_t tb_svg_ticks(double dmin, double dmax, int log_scale,
                    double *ticks, size_t cap, double *lo, double *hi)
{
    tb_svg_axis a;
    int r = log_scale ? tb_svg_log_fit(&a, dmin, dmax, TB_SVG_MAXINT)
                      : tb_svg_lin_fit(&a, dmin, dmax, TB_SVG_MAXINT);
    if (r) return 0;
    for (size_t i = 0; i < a.nmaj && i < cap && ticks; i++)
        ticks[i] = a.log ? tb_svg_pow10((int)a.maj[i]) : a.maj[i];
    if (lo) *lo = a.log ? tb_svg_pow10((int)a.lo) : a.lo;
    if (hi) *hi = a.log ? tb_svg_pow10((int)a.hi) : a.hi;
    return a.nmaj;
}

/* Replace a leading '-' by U+2212 MINUS SIGN, which typesets as wide as
 * '+' and lines up with the digits (as matplotlib does). */
static void tb_svg_minus(char *s, size_t cap)
{
    size_t n = strlen(s);
    if (s[0] != '-' || n + 3 > cap) return;
    memmove(s + 3, s + 1, n);
    memcpy(s, "\xE2\x88\x92", 3);
}

/* Tick labels: "10^k" on log axes; on linear axes the decimals the step
 * needs, the same on every label, or a mantissa times 10^E when the
 * numbers are large (>= 1e6) or small (all below 1e-3). */
static void tb_svg_labels(tb_svg_axis *a)
{
    int sci = 0, E = 0, dec = a->k < 0 ? -a->k : 0;
    if (!a->log) {
        double big = fmax(fabs(a->lo), fabs(a->hi));
        E = big > 0 ? (int)floor(log10(big)) : 0;
        if (E >= 6 || E <= -4) { sci = 1; dec = E - a->k; if (dec < 0) dec = 0; }
    }
    for (size_t i = 0; i < a->nmaj; i++) {
        tb_svg_lab *l = &a->lab[i];
        l->sup[0] = 0;
        if (a->log) {
            snprintf(l->base, sizeof l->base, "10");
            snprintf(l->sup, sizeof l->sup, "%d", (int)a->maj[i]);
            tb_svg_minus(l->sup, sizeof l->sup);
            continue;
        }
        double v = a->maj[i];
        if (sci && v != 0) {
            size_t n = tb_svg_fixed(l->base, sizeof l->base, v / tb_svg_pow10(E), dec, 0);
            snprintf(l->base + n, sizeof l->base - n, "\xC3\x97" "10");
            snprintf(l->sup, sizeof l->sup, "%d", E);
            tb_svg_minus(l->sup, sizeof l->sup);
        } else {
            tb_svg_fixed(l->base, sizeof l->base, v, sci ? 0 : dec, 0);
        }
        tb_svg_minus(l->base, sizeof l->base);
    }
    /* A log axis of one or two decades would carry only two or three
     * numbers: label 2 and 5 (and 3 on one decade) x 10^k as well, as
     * matplotlib does. */
    a->nmlab = 0;
    if (a->log && a->step == 1 && a->hi - a->lo <= 2) {
        static const int m1[] = { 2, 3, 5 }, m2[] = { 2, 5 };
        const int *m = a->hi - a->lo <= 1 ? m1 : m2;
        size_t nm = a->hi - a->lo <= 1 ? 3 : 2;
        for (int e = (int)a->lo; e < (int)a->hi; e++)
            for (size_t j = 0; j < nm && a->nmlab < TB_SVG_MAXMLAB; j++) {
                tb_svg_lab *l = &a->mlab[a->nmlab];
                a->mlabpos[a->nmlab++] = e + log10((double)m[j]);
                snprintf(l->base, sizeof l->base, "%d\xC3\x97" "10", m[j]);
                snprintf(l->sup, sizeof l->sup, "%d", e);
                tb_svg_minus(l->sup, sizeof l->sup);
            }
    }
}

#define TB_SVG_SUPSCALE 0.75   /* exponent size relative to the label */

static double tb_svg_labw(const tb_svg_lab *l, double size)
{
    return tb_svg_textw(l->base, size, SIZE_MAX) +
           tb_svg_textw(l->sup, size * TB_SVG_SUPSCALE, SIZE_MAX);
}

static double tb_svg_maxlabw(const tb_svg_axis *a, double size)
{
    double w = 0;
    for (size_t i = 0; i < a->nmaj; i++) w = fmax(w, tb_svg_labw(&a->lab[i], size));
    for (size_t i = 0; i < a->nmlab; i++) w = fmax(w, tb_svg_labw(&a->mlab[i], size));
    return w;
}

/* Pixel of an axis-unit position (tick positions). Halved operands keep
 * the differences finite for limits near +-DBL_MAX. */
static double tb_svg_upix(const tb_svg_axis *a, double t)
{
    return a->p0 + (t / 2 - a->lo / 2) / (a->hi / 2 - a->lo / 2) * (a->p1 - a->p0);
}

/* Pixel of a data value (log axes take the value, not its log). */
static double tb_svg_pix(const tb_svg_axis *a, double v)
{
    return tb_svg_upix(a, a->log ? log10(v) : v);
}

/* Thin lines at pixel centres, so that the grid and frame are crisp. */
static double tb_svg_snap(double v) { return floor(v) + 0.5; }

/* minor: a minor tick's label, in grey so the decades still stand out */
static void tb_svg_ticklabel(tb_svg_buf *b, const tb_svg_lab *l, double x, double y,
                             const char *anchor, int minor)
{
    tb_svg_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"%s\"%s>%t", x, y, anchor,
             minor ? " fill=\"#666\"" : "", l->base);
    if (l->sup[0])
        tb_svg_f(b, "<tspan dy=\"-5\" font-size=\"%f\">%t</tspan>",
                 TB_SVG_FS_TICK * TB_SVG_SUPSCALE, l->sup);
    tb_svg_puts(b, "</text>\n");
}

/* ---- rendering -------------------------------------------------------- */

typedef struct { double x0, y0, x1, y1; } tb_svg_box;

typedef struct {
    tb_svg_box *v;
    size_t n, cap;
} tb_svg_boxes;

static void tb_svg_addbox(tb_svg_boxes *bs, tb_svg_box b, tb_svg_buf *out)
{
    if (tb_svg_grow((void **)&bs->v, &bs->cap, bs->n + 1, sizeof *bs->v)) { out->oom = 1; return; }
    bs->v[bs->n++] = b;
}

static int tb_svg_overlap(tb_svg_box a, tb_svg_box b)
{
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/* Is point i of series s drawn? Else why not (for the footnote). */
enum { TB_SVG_SHOWN, TB_SVG_NONFINITE, TB_SVG_NONPOS };

static int tb_svg_visible(const tb_chart *c, double x, double y)
{
    if (!isfinite(x) || !isfinite(y)) return TB_SVG_NONFINITE;
    if ((c->log_x && x <= 0) || (c->log_y && y <= 0)) return TB_SVG_NONPOS;
    return TB_SVG_SHOWN;
}

static void tb_svg_marker(tb_svg_buf *b, int shape, double x, double y, double r)
{
    switch (shape) {
    case 0:   /* circle, as two arcs (a path holds all markers of a series) */
        tb_svg_f(b, "M%f %fa%f %f 0 1 0 %f 0a%f %f 0 1 0 %f 0Z",
                 x - r, y, r, r, 2 * r, r, r, -2 * r);
        break;
    case 1: { /* square, area close to the circle's */
        double h = 0.9 * r;
        tb_svg_f(b, "M%f %fh%fv%fh%fZ", x - h, y - h, 2 * h, 2 * h, -2 * h);
        break;
    }
    case 2:   /* triangle up */
        tb_svg_f(b, "M%f %fl%f %fh%fZ", x, y - 1.25 * r, 1.15 * r, 2 * r, -2.3 * r);
        break;
    case 3:   /* diamond */
        tb_svg_f(b, "M%f %fl%f %fl%f %fl%f %fZ", x, y - 1.3 * r, 1.3 * r, 1.3 * r,
                 -1.3 * r, 1.3 * r, -1.3 * r, -1.3 * r);
        break;
    default:  /* triangle down */
        tb_svg_f(b, "M%f %fl%f %fh%fZ", x, y + 1.25 * r, 1.15 * r, -2 * r, -2.3 * r);
        break;
    }
}

/* Series i's colour and marker shape: its own (tb_chart_series_look) or
 * the palette's by index. */
static const char *tb_svg_colour(const tb_chart *c, size_t i)
{
    return c->ser[i].colour[0] ? c->ser[i].colour : tb_svg_palette[i % TB_SVG_NCOLOR];
}
static int tb_svg_shape(const tb_chart *c, size_t i)
{
    return c->ser[i].shape >= 0 ? c->ser[i].shape : (int)(i % TB_SVG_NSHAPE);
}

/* Stroke attributes of series i's line. */
static void tb_svg_linestyle(tb_svg_buf *b, const tb_chart *c, size_t i)
{
    int dash = c->ser[i].dash >= 0 ? c->ser[i].dash : i >= TB_SVG_NCOLOR;
    tb_svg_f(b, "fill=\"none\" stroke=\"%s\" stroke-width=\"%s\" "
             "stroke-linejoin=\"round\" stroke-linecap=\"round\"",
             tb_svg_colour(c, i), dash ? "1.4" : "1.8");
    if (dash) tb_svg_puts(b, " stroke-dasharray=\"6 3\"");
}

static double tb_svg_marker_r(int style)
{
    return style & TB_HOLLOW ? 6.5 : style & (TB_LINE | TB_STEP) ? 3.2 : 3.8;
}

/* The markers of a series (path data d) filled, or as rings (TB_HOLLOW). */
static void tb_svg_marker_paint(tb_svg_buf *b, const tb_chart *c, size_t s, const char *d)
{
    if (c->ser[s].style & TB_HOLLOW)
        tb_svg_f(b, "<path fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" d=\"%s\"/>\n", tb_svg_colour(c, s), d);
    else    /* a thin white edge keeps overlapping markers apart */
        tb_svg_f(b, "<path fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.6\" d=\"%s\"/>\n", tb_svg_colour(c, s), d);
}

/* Does series s draw anything (a marker, or a line of two points)? A
 * legend lists only what is drawn. */
static int tb_svg_draws(const tb_chart *c, size_t s)
{
    const tb_svg_series *se = &c->ser[s];
    if (se->key) return 1;
    int prev = 0;
    for (size_t i = 0; i < se->n; i++) {
        int shown = tb_svg_visible(c, se->pt[i].x, se->pt[i].y) == TB_SVG_SHOWN;
        if (shown && (se->style & TB_POINTS)) return 1;
        if (shown && prev) return 1;
        prev = shown;
    }
    return 0;
}

/* A text that stays readable where it crosses lines: a white outline is
 * painted under the glyphs. */
#define TB_SVG_HALO "stroke=\"#fff\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\""

/* Append "N things why" to the footnote, "; "-separated. */
static void tb_svg_footnote(char *s, size_t cap, size_t *len, size_t n,
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
    const tb_chart *c;
    tb_svg_buf *b;
    int    have;            /* something to draw: else "no data" */
    double L, R, T, B;      /* frame */
    tb_svg_axis ax, ay;
    size_t nleg;            /* labelled series */
    double legw;
    char   foot[200];
    size_t flen;
    double *bx0, *bx1;      /* per band: its pixels, cut to the frame */
    int   *brow;            /* per band: label row above the plot, or -1 */
} tb_svg_lay;

#define TB_SVG_PAD      10  /* end ticks this far inside the frame */
#define TB_SVG_LEGMAX   26  /* legend text cut to this many characters */
#define TB_SVG_BANDMAX  30  /* band labels likewise */
#define TB_SVG_PLMAX    20  /* point labels likewise */
#define TB_SVG_BANDROWS 4   /* rows for band labels; a label that fits none is dropped */

static int tb_svg_shown_hl(const tb_chart *c, double y)
{
    return isfinite(y) && !(c->log_y && y <= 0);
}

/* Band pixels and label rows. Labels go above the plot, in up to three
 * rows, so that they hide no data; returns the number of rows used. */
static int tb_svg_layout_bands(tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    tb_svg_boxes placed = { 0 };
    int nrows = 0;
    for (size_t i = 0; i < c->nband; i++) {
        double x0 = c->band[i].x0, x1 = c->band[i].x1;
        l->brow[i] = -1;
        l->bx0[i] = l->bx1[i] = 0;
        if (isnan(x0) || isnan(x1) || (c->log_x && x1 <= 0)) continue;
        double p0 = c->log_x && x0 <= 0 ? l->L : tb_svg_pix(&l->ax, x0);
        double p1 = tb_svg_pix(&l->ax, x1);
        l->bx0[i] = p0 = fmax(l->L, fmin(l->R, p0));
        l->bx1[i] = p1 = fmax(l->L, fmin(l->R, p1));
        if (p1 <= p0 || !c->band[i].label) continue;
        double w = tb_svg_textw(c->band[i].label, TB_SVG_FS_SMALL, TB_SVG_BANDMAX);
        double cx = fmax(l->L + w / 2, fmin(l->R - w / 2, (p0 + p1) / 2));
        for (int r = 0; r < TB_SVG_BANDROWS && l->brow[i] < 0; r++) {
            /* rows as y bands [r, r+0.5]: overlap only within a row */
            tb_svg_box bx = { cx - w / 2 - 4, r, cx + w / 2 + 4, r + 0.5 };
            int clash = 0;
            for (size_t j = 0; j < placed.n; j++) clash |= tb_svg_overlap(bx, placed.v[j]);
            if (!clash) { l->brow[i] = r; tb_svg_addbox(&placed, bx, l->b); }
        }
        if (l->brow[i] + 1 > nrows) nrows = l->brow[i] + 1;
    }
    free(placed.v);
    return nrows;
}

/* Decide everything before drawing anything: axes, margins, legend. */
static void tb_svg_layout(tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    size_t nshown = 0, nnonfin = 0, nnonpos = 0, lnonfin = 0, lnonpos = 0;
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (size_t s = 0; s < c->nser; s++)
        for (size_t i = 0; i < c->ser[s].n; i++) {
            double x = c->ser[s].pt[i].x, y = c->ser[s].pt[i].y;
            switch (tb_svg_visible(c, x, y)) {
            case TB_SVG_NONFINITE: nnonfin++; continue;
            case TB_SVG_NONPOS: nnonpos++; continue;
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
    tb_svg_footnote(l->foot, sizeof l->foot, &l->flen, nnonpos, "point", "<= 0 not shown");
    tb_svg_footnote(l->foot, sizeof l->foot, &l->flen, nnonfin, "point", "NaN/inf not shown");
    tb_svg_footnote(l->foot, sizeof l->foot, &l->flen, lnonpos, "line", "at y <= 0 not shown");
    tb_svg_footnote(l->foot, sizeof l->foot, &l->flen, lnonfin, "line", "at NaN/inf not shown");

    /* y first: its tick labels' width sets the left margin, which sets the
     * room for the x tick labels. */
    l->have = nshown > 0;
    if (l->have) {
        if (c->log_y ? tb_svg_log_fit(&l->ay, ymin, ymax, TB_SVG_MAXINT)
                     : tb_svg_lin_fit(&l->ay, ymin, ymax, TB_SVG_MAXINT)) l->have = 0;
        else tb_svg_labels(&l->ay);
    }

    /* The legend stands outside the plot on the right, so it never covers
     * data; long labels are cut rather than squeezing the plot. */
    double legtw = 0;
    for (size_t s = 0; s < c->nser; s++)
        if (c->ser[s].label && tb_svg_draws(c, s)) {
            l->nleg++;
            legtw = fmax(legtw, c->ser[s].key == 2 ? tb_svg_textw(c->ser[s].label, TB_SVG_FS_TICK, TB_SVG_LEGMAX + 6) - 32
                                                  : tb_svg_textw(c->ser[s].label, TB_SVG_FS_TICK, TB_SVG_LEGMAX));
        }
    l->legw = l->nleg ? 10 + 24 + 8 + legtw + 10 : 0;

    l->T = c->title && *c->title ? 48 : 24;
    l->B = TB_SVG_VH - 52 - (l->flen ? 14 : 0);
    double ylw = l->have ? tb_svg_maxlabw(&l->ay, TB_SVG_FS_TICK) : 0;
    l->L = fmax(50, ceil(8 + (c->ylabel && *c->ylabel ? TB_SVG_FS_AXIS + 10 : 0) + ylw + 9));
    l->R = floor(TB_SVG_VW - (l->nleg ? l->legw + 15 + 8 : 24));

    /* x: fewer intervals while the tick labels would crowd each other. */
    if (l->have) {
        int ok = 0, m0 = TB_SVG_MAXINT;
        double x0 = xmin, x1 = xmax;
        /* Whole-number data (bit widths): no tick between two of them. */
        if (c->int_x && !c->log_x) {
            if (x1 - x0 < 1) { x0 -= 1; x1 += 1; }
            if (x1 - x0 < m0) m0 = (int)floor(x1 - x0);
        }
        for (int mi = m0; mi >= 1 && !ok; mi--) {
            if (c->log_x ? tb_svg_log_fit(&l->ax, x0, x1, mi)
                         : tb_svg_lin_fit(&l->ax, x0, x1, mi)) break;
            tb_svg_labels(&l->ax);
            double room = (l->R - l->L - 2 * TB_SVG_PAD) / (double)(l->ax.nmaj > 1 ? l->ax.nmaj - 1 : 1);
            ok = mi == 1 || tb_svg_maxlabw(&l->ax, TB_SVG_FS_TICK) + 12 <= room;
        }
        if (!ok) l->have = 0;
    }
    /* The end ticks sit a little inside the frame, so that markers at the
     * data's extremes are not cut by it and the corner labels keep apart. */
    l->ax.p0 = l->L + TB_SVG_PAD;
    l->ax.p1 = l->R - TB_SVG_PAD;

    if (l->have && c->nband) {
        l->bx0 = calloc(c->nband, sizeof *l->bx0);
        l->bx1 = calloc(c->nband, sizeof *l->bx1);
        l->brow = calloc(c->nband, sizeof *l->brow);
        if (!l->bx0 || !l->bx1 || !l->brow) { l->b->oom = 1; l->have = 0; }
        else l->T += 13 * tb_svg_layout_bands(l);
    }
    l->ay.p0 = l->B - TB_SVG_PAD;
    l->ay.p1 = l->T + TB_SVG_PAD;
}

static void tb_svg_draw_bands(const tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    for (size_t i = 0; i < c->nband; i++) {
        if (l->bx1[i] <= l->bx0[i]) continue;
        tb_svg_f(l->b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" "
                 "fill=\"#888\" fill-opacity=\"0.18\"/>\n",
                 l->bx0[i], l->T, l->bx1[i] - l->bx0[i], l->B - l->T);
        if (l->brow[i] < 0) continue;
        double w = tb_svg_textw(c->band[i].label, TB_SVG_FS_SMALL, TB_SVG_BANDMAX);
        double cx = fmax(l->L + w / 2, fmin(l->R - w / 2, (l->bx0[i] + l->bx1[i]) / 2));
        tb_svg_f(l->b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"%d\" "
                 "fill=\"#555\">", cx, l->T - 5 - 13 * l->brow[i], TB_SVG_FS_SMALL);
        tb_svg_text(l->b, c->band[i].label, TB_SVG_BANDMAX);
        tb_svg_puts(l->b, "</text>\n");
    }
}

/* Grid lines at the major ticks (not over the frame), light grey. */
static void tb_svg_draw_grid(const tb_svg_lay *l)
{
    tb_svg_puts(l->b, "<path fill=\"none\" stroke=\"#e3e3e3\" stroke-width=\"1\" d=\"");
    for (size_t i = 0; i < l->ax.nmaj; i++) {
        double p = tb_svg_snap(tb_svg_upix(&l->ax, l->ax.maj[i]));
        if (p > l->L + 1 && p < l->R - 1) tb_svg_f(l->b, "M%f %fV%f", p, l->T, l->B);
    }
    for (size_t i = 0; i < l->ay.nmaj; i++) {
        double p = tb_svg_snap(tb_svg_upix(&l->ay, l->ay.maj[i]));
        if (p > l->T + 1 && p < l->B - 1) tb_svg_f(l->b, "M%f %fH%f", l->L, p, l->R);
    }
    tb_svg_puts(l->b, "\"/>\n");
}

static void tb_svg_draw_hlines(const tb_svg_lay *l)
{
    for (size_t i = 0; i < l->c->nhl; i++)
        if (tb_svg_shown_hl(l->c, l->c->hl[i].y))
            tb_svg_f(l->b, "<path d=\"M%f %fH%f\" stroke=\"#444\" stroke-width=\"1.2\" "
                     "stroke-dasharray=\"7 4\"/>\n", l->L, tb_svg_pix(&l->ay, l->c->hl[i].y), l->R);
}

/* Each series as one path for its line and one for its markers. */
static void tb_svg_draw_series(const tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    tb_svg_buf d = { 0 };
    for (size_t s = 0; s < c->nser; s++) {
        const tb_svg_series *se = &c->ser[s];
        if (se->style & (TB_LINE | TB_STEP)) {
            d.n = 0;
            int pen = 0;
            double px = 0, py = 0;
            for (size_t i = 0; i < se->n; i++) {
                if (tb_svg_visible(c, se->pt[i].x, se->pt[i].y) != TB_SVG_SHOWN) {
                    pen = 0;            /* a skipped point breaks the line */
                    continue;
                }
                double x = tb_svg_pix(&l->ax, se->pt[i].x), y = tb_svg_pix(&l->ay, se->pt[i].y);
                if (!pen) tb_svg_f(&d, "M%f %f", x, y);
                else if (se->style & TB_STEP) {
                    if (x != px) tb_svg_f(&d, "H%f", x);
                    if (y != py) tb_svg_f(&d, "V%f", y);
                } else tb_svg_f(&d, "L%f %f", x, y);
                pen = 1;
                px = x;
                py = y;
            }
            if (d.n) {
                tb_svg_puts(l->b, "<path ");
                tb_svg_linestyle(l->b, c, s);
                tb_svg_f(l->b, " d=\"%s\"/>\n", d.p);
            }
        }
        if (se->style & TB_POINTS) {
            d.n = 0;
            double r = tb_svg_marker_r(se->style);
            for (size_t i = 0; i < se->n; i++)
                if (tb_svg_visible(c, se->pt[i].x, se->pt[i].y) == TB_SVG_SHOWN)
                    tb_svg_marker(&d, tb_svg_shape(c, s), tb_svg_pix(&l->ax, se->pt[i].x),
                                  tb_svg_pix(&l->ay, se->pt[i].y), r);
            if (d.n) tb_svg_marker_paint(l->b, c, s, d.p);
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
static void tb_svg_draw_plabels(const tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    tb_svg_buf *b = l->b;
    tb_svg_boxes obst = { 0 }, lab = { 0 };
    for (size_t s = 0; s < c->nser; s++)
        for (size_t i = 0; i < c->ser[s].n; i++) {
            const tb_svg_pt *pt = &c->ser[s].pt[i];
            if (tb_svg_visible(c, pt->x, pt->y) != TB_SVG_SHOWN) continue;
            double x = tb_svg_pix(&l->ax, pt->x), y = tb_svg_pix(&l->ay, pt->y);
            tb_svg_box bx = { x - 4, y - 4, x + 4, y + 4 };
            tb_svg_addbox(&obst, bx, b);
        }
    const double fs = TB_SVG_FS_SMALL, asc = 0.75 * fs, dsc = 0.22 * fs, gap = 5;
    /* The reference lines' labels (tb_svg_draw_hlabels) are texts too. */
    for (size_t i = 0; i < c->nhl; i++) {
        const tb_svg_hl *h = &c->hl[i];
        if (!h->label || !tb_svg_shown_hl(c, h->y)) continue;
        double p = tb_svg_pix(&l->ay, h->y), ty = p - 4 - 10 < l->T ? p + 13 : p - 4;
        double w = tb_svg_textw(h->label, fs, tb_svg_fit(l->R - l->L - 8, fs));
        tb_svg_box bx = { l->R - 4 - w, ty - fs, l->R - 4, ty + 0.3 * fs };
        tb_svg_addbox(&lab, bx, b);
    }
    for (size_t k = 0; k < c->npl && !b->oom; k++) {
        const tb_svg_pt *pt = &c->ser[c->pl[k].series].pt[c->pl[k].idx];
        if (tb_svg_visible(c, pt->x, pt->y) != TB_SVG_SHOWN) continue;
        double x = tb_svg_pix(&l->ax, pt->x), y = tb_svg_pix(&l->ay, pt->y);
        double w = tb_svg_textw(c->pl[k].text, fs, TB_SVG_PLMAX);
        /* per spot: offset of the text's left edge, of its baseline */
        const double spot[6][2] = {
            { gap, -gap }, { gap, gap + asc }, { -gap - w, -gap },
            { -gap - w, gap + asc }, { -w / 2, -gap - 3 }, { -w / 2, gap + 3 + asc },
        };
        int best = 0;
        size_t bestscore = SIZE_MAX;
        for (int q = 0; q < 6 && bestscore; q++) {
            tb_svg_box bx = { x + spot[q][0], y + spot[q][1] - asc,
                              x + spot[q][0] + w, y + spot[q][1] + dsc };
            size_t score = 0;
            if (bx.x0 < l->L || bx.x1 > l->R || bx.y0 < l->T || bx.y1 > l->B) score += 1000;
            for (size_t j = 0; j < lab.n; j++) score += 100 * (size_t)tb_svg_overlap(bx, lab.v[j]);
            for (size_t j = 0; j < obst.n; j++) score += (size_t)tb_svg_overlap(bx, obst.v[j]);
            if (score < bestscore) { bestscore = score; best = q; }
        }
        if (bestscore >= 100) continue;       /* on another text or outside: dropped */
        tb_svg_box bx = { x + spot[best][0], y + spot[best][1] - asc,
                          x + spot[best][0] + w, y + spot[best][1] + dsc };
        tb_svg_addbox(&lab, bx, b);
        tb_svg_f(b, "<text x=\"%f\" y=\"%f\" font-size=\"%d\" fill=\"#333\" " TB_SVG_HALO ">",
                 bx.x0, y + spot[best][1], TB_SVG_FS_SMALL);
        tb_svg_text(b, c->pl[k].text, TB_SVG_PLMAX);
        tb_svg_puts(b, "</text>\n");
    }
    free(obst.v);
    free(lab.v);
}

/* Reference line labels at the right end, above the line (below it when
 * the line runs along the top). */
static void tb_svg_draw_hlabels(const tb_svg_lay *l)
{
    for (size_t i = 0; i < l->c->nhl; i++) {
        const tb_svg_hl *h = &l->c->hl[i];
        if (!h->label || !tb_svg_shown_hl(l->c, h->y)) continue;
        double p = tb_svg_pix(&l->ay, h->y);
        double ty = p - 4 - 10 < l->T ? p + 13 : p - 4;
        tb_svg_f(l->b, "<text x=\"%f\" y=\"%f\" text-anchor=\"end\" font-size=\"%d\" fill=\"#333\" "
                 TB_SVG_HALO ">", l->R - 4, ty, TB_SVG_FS_SMALL);
        tb_svg_text(l->b, h->label, tb_svg_fit(l->R - l->L - 8, TB_SVG_FS_SMALL));
        tb_svg_puts(l->b, "</text>\n");
    }
}

/* Ticks outward (majors 5 px, minors 3 px) and their labels. */
static void tb_svg_draw_ticks(const tb_svg_lay *l)
{
    const tb_svg_axis *ax = &l->ax, *ay = &l->ay;
    tb_svg_puts(l->b, "<path fill=\"none\" stroke=\"#444\" stroke-width=\"1\" d=\"");
    for (size_t i = 0; i < ax->nmaj; i++)
        tb_svg_f(l->b, "M%f %fv5", tb_svg_snap(tb_svg_upix(ax, ax->maj[i])), l->B + 1);
    for (size_t i = 0; i < ay->nmaj; i++)
        tb_svg_f(l->b, "M%f %fh-5", l->L, tb_svg_snap(tb_svg_upix(ay, ay->maj[i])));
    for (size_t i = 0; i < ax->nmin; i++)
        tb_svg_f(l->b, "M%f %fv3", tb_svg_snap(tb_svg_upix(ax, ax->min[i])), l->B + 1);
    for (size_t i = 0; i < ay->nmin; i++)
        tb_svg_f(l->b, "M%f %fh-3", l->L, tb_svg_snap(tb_svg_upix(ay, ay->min[i])));
    tb_svg_puts(l->b, "\"/>\n");
    for (size_t i = 0; i < ax->nmaj; i++)
        tb_svg_ticklabel(l->b, &ax->lab[i], tb_svg_upix(ax, ax->maj[i]), l->B + 19, "middle", 0);
    for (size_t i = 0; i < ax->nmlab; i++)
        tb_svg_ticklabel(l->b, &ax->mlab[i], tb_svg_upix(ax, ax->mlabpos[i]), l->B + 19, "middle", 1);
    for (size_t i = 0; i < ay->nmaj; i++)
        tb_svg_ticklabel(l->b, &ay->lab[i], l->L - 8, tb_svg_upix(ay, ay->maj[i]) + 4, "end", 0);
    for (size_t i = 0; i < ay->nmlab; i++)
        tb_svg_ticklabel(l->b, &ay->mlab[i], l->L - 8, tb_svg_upix(ay, ay->mlabpos[i]) + 4, "end", 1);
}

/* Title and axis labels, each cut to the room it has. */
static void tb_svg_draw_texts(const tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    tb_svg_buf *b = l->b;
    if (c->title && *c->title) {
        /* Centred over the plot, or over the picture when too long for it. */
        double w = tb_svg_textw(c->title, TB_SVG_FS_TITLE, SIZE_MAX);
        double cx = w <= l->R - l->L ? (l->L + l->R) / 2 : TB_SVG_VW / 2.0;
        tb_svg_f(b, "<text x=\"%f\" y=\"30\" text-anchor=\"middle\" font-size=\"%d\">",
                 cx, TB_SVG_FS_TITLE);
        tb_svg_text(b, c->title, tb_svg_fit(TB_SVG_VW - 20, TB_SVG_FS_TITLE));
        tb_svg_puts(b, "</text>\n");
    }
    if (c->xlabel && *c->xlabel) {
        tb_svg_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"%d\">",
                 (l->L + l->R) / 2, l->B + 42, TB_SVG_FS_AXIS);
        tb_svg_text(b, c->xlabel, tb_svg_fit(l->R - l->L, TB_SVG_FS_AXIS));
        tb_svg_puts(b, "</text>\n");
    }
    if (c->ylabel && *c->ylabel) {
        /* Rotated, the glyphs extend left of the (vertical) baseline: it
         * sits one font height in from the edge. */
        double x = 8 + TB_SVG_FS_AXIS, y = (l->T + l->B) / 2;
        tb_svg_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"%d\" "
                 "transform=\"rotate(-90 %f %f)\">", x, y, TB_SVG_FS_AXIS, x, y);
        tb_svg_text(b, c->ylabel, tb_svg_fit(l->B - l->T, TB_SVG_FS_AXIS));
        tb_svg_puts(b, "</text>\n");
    }
    if (l->flen)
        tb_svg_f(b, "<text x=\"8\" y=\"%d\" font-size=\"%d\" fill=\"#555\">%t</text>\n",
                 TB_SVG_VH - 8, TB_SVG_FS_SMALL, l->foot);
}

/* Legend right of the plot, top-aligned with it: as many entries as fit
 * its height, then "+N more". */
static void tb_svg_draw_legend(const tb_svg_lay *l)
{
    const tb_chart *c = l->c;
    tb_svg_buf *b = l->b;
    const double rowh = 18;
    size_t fit = (size_t)((l->B - l->T - 12) / rowh), shown = l->nleg;
    if (fit < 1) fit = 1;
    if (shown > fit) shown = fit - 1;
    double lx = l->R + 15, ly = l->T;
    double lh = 8 + rowh * (double)(shown + (shown < l->nleg)) + 2;
    tb_svg_f(b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" fill=\"#fff\" "
             "stroke=\"#ccc\" stroke-width=\"1\" rx=\"3\"/>\n",
             tb_svg_snap(lx), tb_svg_snap(ly), floor(l->legw), floor(lh));
    size_t row = 0;
    for (size_t s = 0; s < c->nser && row < shown; s++) {
        const tb_svg_series *se = &c->ser[s];
        if (!se->label || !tb_svg_draws(c, s)) continue;
        double cy = ly + 4 + rowh * (double)row + rowh / 2;
        if (se->key == 2) {             /* a heading: the text from the left edge */
            tb_svg_f(b, "<text x=\"%f\" y=\"%f\" fill=\"#555\">", lx + 10, cy + 4);
            tb_svg_text(b, se->label, TB_SVG_LEGMAX + 6);
            tb_svg_puts(b, "</text>\n");
            row++;
            continue;
        }
        if (se->style & (TB_LINE | TB_STEP)) {
            tb_svg_f(b, "<path d=\"M%f %fh24\" ", lx + 10, cy);
            tb_svg_linestyle(b, c, s);
            tb_svg_puts(b, "/>\n");
        }
        if (se->style & TB_POINTS) {
            tb_svg_buf d = { 0 };
            tb_svg_marker(&d, tb_svg_shape(c, s), lx + 22, cy, tb_svg_marker_r(se->style));
            if (d.oom) b->oom = 1;
            else tb_svg_marker_paint(b, c, s, d.p);
            free(d.p);
        }
        tb_svg_f(b, "<text x=\"%f\" y=\"%f\">", lx + 42, cy + 4);
        tb_svg_text(b, se->label, TB_SVG_LEGMAX);
        tb_svg_puts(b, "</text>\n");
        row++;
    }
    if (shown < l->nleg)
        tb_svg_f(b, "<text x=\"%f\" y=\"%f\" fill=\"#666\">+%d more</text>\n",
                 lx + 42, ly + 4 + rowh * (double)shown + rowh / 2 + 4, (int)(l->nleg - shown));
}

static void tb_svg_render(const tb_chart *c, tb_svg_buf *b)
{
    tb_svg_lay l;
    memset(&l, 0, sizeof l);
    l.c = c;
    l.b = b;
    tb_svg_layout(&l);

    tb_svg_f(b, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
             "viewBox=\"0 0 %d %d\" font-family=\"sans-serif\" font-size=\"%d\" fill=\"#222\">\n",
             TB_SVG_VW, TB_SVG_VH, TB_SVG_VW, TB_SVG_VH, TB_SVG_FS_TICK);
    if (c->title && *c->title) tb_svg_f(b, "<title>%t</title>\n", c->title);
    tb_svg_f(b, "<rect width=\"%d\" height=\"%d\" fill=\"#fff\"/>\n", TB_SVG_VW, TB_SVG_VH);
    /* Back to front: bands, grid, reference lines, data, labels on top. */
    if (l.have) {
        tb_svg_draw_bands(&l);
        tb_svg_draw_grid(&l);
        tb_svg_draw_hlines(&l);
        tb_svg_draw_series(&l);
        tb_svg_draw_plabels(&l);
        tb_svg_draw_hlabels(&l);
    } else {
        tb_svg_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"middle\" font-size=\"14\" "
                 "fill=\"#888\">no data</text>\n", (l.L + l.R) / 2, (l.T + l.B) / 2 + 5);
    }
    tb_svg_f(b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" fill=\"none\" "
             "stroke=\"#444\" stroke-width=\"1\"/>\n", l.L + 0.5, l.T + 0.5, l.R - l.L, l.B - l.T);
    if (l.have) tb_svg_draw_ticks(&l);
    tb_svg_draw_texts(&l);
    if (l.nleg) tb_svg_draw_legend(&l);
    tb_svg_puts(b, "</svg>\n");
    free(l.bx0);
    free(l.bx1);
    free(l.brow);
}

/* ---- writing ---------------------------------------------------------- */

/* One-line message: the path may hold newlines, the message may not. */
static void tb_svg_err(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || !errlen) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    for (char *p = err; *p; p++)
        if ((unsigned char)*p < 0x20) *p = '?';
}

/* The rendered SVG in b (caller frees b->p); 0, or -1 with a message
 * naming `what` (the path). */
static int tb_svg_rendered(const tb_chart *c, const char *what, tb_svg_buf *b, char *err, size_t errlen)
{
    if (err && errlen) err[0] = 0;
    if (!c || !what || !*what) {
        tb_svg_err(err, errlen, "chart: no chart or no path");
        return -1;
    }
    if (c->err[0]) {
        tb_svg_err(err, errlen, "%s: chart is incomplete: %s", what, c->err);
        return -1;
    }
    tb_svg_render(c, b);
    if (b->oom) {
        free(b->p);
        b->p = NULL;
        tb_svg_err(err, errlen, "%s: out of memory", what);
        return -1;
    }
    return 0;
}

int tb_chart_fwrite(const tb_chart *c, FILE *f, const char *what, char *err, size_t errlen)
{
    tb_svg_buf b = { 0 };
    if (tb_svg_rendered(c, what, &b, err, errlen)) return -1;
    /* A write error stays in the stream's flag for whoever closes it. */
    if (b.n) fwrite(b.p, 1, b.n, f);
    free(b.p);
    return 0;
}

int tb_chart_write(const tb_chart *c, const char *path, char *err, size_t errlen)
{
    tb_svg_buf b = { 0 };
    if (tb_svg_rendered(c, path, &b, err, errlen)) return -1;

    /* base_out: a temporary beside a regular file, renamed once complete
     * (with the umask's permissions), removed on SIGINT/TERM/HUP; a device
     * or FIFO written through; "-" is stdout. */
    int rc = base_out_write_all(path, b.p, b.n, err, errlen);
    free(b.p);
    return rc;
}
