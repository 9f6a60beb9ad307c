/* chart.c - SVG chart writer; see chart.h for what it promises.
 *
 * The chart only records what it is given. All layout happens in
 * chart_write: the whole file is rendered into a memory buffer first, so
 * the file is written in one go and an out-of-memory midway never leaves a
 * half-written chart.
 */
#include "chart/chart.h"
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

/* Okabe & Ito, "Color Universal Design" (2008), without the yellow, which
 * is invisible on white. Readable for the common colour-vision deficiencies;
 * the marker shapes (and dashes past the 7th series) back the colours up in
 * greyscale prints. */
static const char *const chart_palette[] = {
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"
};
#define CHART_NCOLOR 7
#define CHART_NSHAPE 5

/* ---- the chart as recorded ------------------------------------------- */

typedef struct { double x, y; } chart_pt;

typedef struct {
    char      *label;
    int        style;
    chart_pt *pt;
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
    chart_ser *ser;   size_t nser, capser;
    chart_plabel *pl;    size_t npl, cappl;
    chart_band   *band;  size_t nband, capband;
    chart_hl     *hl;    size_t nhl, caphl;
    char  err[128];       /* first building error; reported by write */
};

/* Make room for need elements in *p (capacity *cap, element size sz). */
static int chart_grow(void **p, size_t *cap, size_t need, size_t sz)
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

static char *chart_strdup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static void chart_fail(chart *c, const char *msg)
{
    if (!c->err[0]) snprintf(c->err, sizeof c->err, "%s", msg);
}

/* Copy of an optional text; NULL stays NULL, a failed copy is an error. */
static char *chart_dup_text(chart *c, const char *s)
{
    if (!s) return NULL;
    char *d = chart_strdup(s);
    if (!d) chart_fail(c, "out of memory");
    return d;
}

chart *chart_new(const char *title, const char *xlabel, const char *ylabel)
{
    chart *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->title = chart_dup_text(c, title);
    c->xlabel = chart_dup_text(c, xlabel);
    c->ylabel = chart_dup_text(c, ylabel);
    if (c->err[0]) { chart_free(c); return NULL; }
    return c;
}

void chart_free(chart *c)
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

void chart_log_x(chart *c, int on) { if (c) c->log_x = !!on; }
void chart_log_y(chart *c, int on) { if (c) c->log_y = !!on; }
void chart_int_x(chart *c, int on) { if (c) c->int_x = !!on; }

int chart_series(chart *c, const char *label, int style)
{
    if (!c) return -1;
    if (c->nser >= INT_MAX ||
        chart_grow((void **)&c->ser, &c->capser, c->nser + 1, sizeof *c->ser)) {
        chart_fail(c, "out of memory");
        return -1;
    }
    /* A series with neither bit would be invisible: default to points. */
    if (!(style & (CHART_LINE | CHART_POINTS | CHART_STEP))) style = CHART_POINTS;
    chart_ser *s = &c->ser[c->nser];
    memset(s, 0, sizeof *s);
    s->style = style;
    s->shape = -1;
    s->dash = -1;
    if (label && *label && !(s->label = chart_dup_text(c, label))) return -1;
    return (int)c->nser++;
}

void chart_series_look(chart *c, int series, const char *colour, int shape, int dashed)
{
    if (!c || series < 0 || (size_t)series >= c->nser) return;
    chart_ser *s = &c->ser[series];
    /* Only "#rrggbb": the colour goes into an attribute unescaped. */
    if (colour && strlen(colour) == 7 && colour[0] == '#' && strspn(colour + 1, "0123456789abcdefABCDEF") == 6)
        memcpy(s->colour, colour, 8);
    if (shape >= 0) s->shape = shape % 5;
    if (dashed >= 0) s->dash = !!dashed;
}

int chart_legend_key(chart *c, const char *label, const char *colour, int shape, int style)
{
    if (!c || !label || !*label) return -1;
    int k = chart_series(c, label, style ? style : CHART_POINTS);
    if (k < 0) return -1;
    c->ser[k].key = style ? 1 : 2;          /* 2: a heading, text only */
    chart_series_look(c, k, colour ? colour : "#444444", shape, 0);
    return k;
}

/* Append a point; its index in the series, or SIZE_MAX after an error. */
static size_t chart_add(chart *c, int series, double x, double y)
{
    if (!c) return SIZE_MAX;
    if (series < 0 || (size_t)series >= c->nser) {
        char m[64];
        snprintf(m, sizeof m, "point for nonexistent series %d", series);
        chart_fail(c, m);
        return SIZE_MAX;
    }
    chart_ser *s = &c->ser[series];
    if (chart_grow((void **)&s->pt, &s->cap, s->n + 1, sizeof *s->pt)) {
        chart_fail(c, "out of memory");
        return SIZE_MAX;
    }
    s->pt[s->n].x = x;
    s->pt[s->n].y = y;
    return s->n++;
}

void chart_point(chart *c, int series, double x, double y)
{
    chart_add(c, series, x, y);
}

void chart_point_label(chart *c, int series, double x, double y, const char *label)
{
    size_t idx = chart_add(c, series, x, y);
    if (idx == SIZE_MAX || !label || !*label) return;
    if (chart_grow((void **)&c->pl, &c->cappl, c->npl + 1, sizeof *c->pl)) {
        chart_fail(c, "out of memory");
        return;
    }
    char *t = chart_dup_text(c, label);
    if (!t) return;
    c->pl[c->npl].series = series;
    c->pl[c->npl].idx = idx;
    c->pl[c->npl].text = t;
    c->npl++;
}

void chart_hband(chart *c, double x0, double x1, const char *label)
{
    if (!c) return;
    if (chart_grow((void **)&c->band, &c->capband, c->nband + 1, sizeof *c->band)) {
        chart_fail(c, "out of memory");
        return;
    }
    char *t = NULL;
    if (label && *label && !(t = chart_dup_text(c, label))) return;
    c->band[c->nband].x0 = x0 <= x1 ? x0 : x1;
    c->band[c->nband].x1 = x0 <= x1 ? x1 : x0;
    c->band[c->nband].label = t;
    c->nband++;
}

void chart_hline(chart *c, double y, const char *label)
{
    if (!c) return;
    if (chart_grow((void **)&c->hl, &c->caphl, c->nhl + 1, sizeof *c->hl)) {
        chart_fail(c, "out of memory");
        return;
    }
    char *t = NULL;
    if (label && *label && !(t = chart_dup_text(c, label))) return;
    c->hl[c->nhl].y = y;
    c->hl[c->nhl].label = t;
    c->nhl++;
}

/* ---- Pareto front ----------------------------------------------------- */

typedef struct { double x, y; size_t i; } chart_pp;

static int chart_pp_cmp(const void *pa, const void *pb)
{
    const chart_pp *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);   /* qsort is not stable */
}

size_t chart_pareto(const double *x, const double *y, size_t n, unsigned char *on_front)
{
    if (!on_front || n == 0) return 0;
    memset(on_front, 0, n);
    if (!x || !y) return 0;

    size_t count = 0;
    chart_pp *p = n <= SIZE_MAX / sizeof *p ? malloc(n * sizeof *p) : NULL;
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
    qsort(p, m, sizeof *p, chart_pp_cmp);

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

typedef struct { double v[3]; size_t i; } chart_p3;

static int chart_p3_cmp(const void *pa, const void *pb)
{
    const chart_p3 *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

/* b dominates a: no worse in every coordinate, better in one. */
static int chart_dom3(const double *b, const double *a)
{
    return b[0] <= a[0] && b[1] <= a[1] && b[2] <= a[2] && (b[0] < a[0] || b[1] < a[1] || b[2] < a[2]);
}

size_t chart_pareto3(const double *x, const double *y, const double *z, size_t n, unsigned char *on_front)
{
    if (!on_front || n == 0) return 0;
    memset(on_front, 0, n);
    if (!x || !y || !z) return 0;
    chart_p3 *p = n <= SIZE_MAX / sizeof *p ? malloc(n * sizeof *p) : NULL;
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
                dom = chart_dom3(b, a);
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
    qsort(p, m, sizeof *p, chart_p3_cmp);
    /* In lexicographic order a point's dominators all come before it, and
     * dominance is transitive, so some dominator is on the front: checking
     * against the front found so far is enough. */
    for (size_t k = 0; k < m; k++) {
        int dom = 0;
        for (size_t j = 0; j < nf && !dom; j++) dom = chart_dom3(p[front[j]].v, p[k].v);
        if (!dom) { front[nf++] = k; on_front[p[k].i] = 1; }
    }
    free(p);
    free(front);
    return nf;
}

/* ---- output buffer and locale-independent formatting ------------------ */

typedef struct { char *p; size_t n, cap; int oom; } chart_buf;

static void chart_put(chart_buf *b, const char *s, size_t len)
{
    if (b->oom) return;
    if (len >= SIZE_MAX - b->n ||
        chart_grow((void **)&b->p, &b->cap, b->n + len + 1, 1)) {
        b->oom = 1;
        return;
    }
    memcpy(b->p + b->n, s, len);
    b->n += len;
    b->p[b->n] = 0;
}

static void chart_puts(chart_buf *b, const char *s) { chart_put(b, s, strlen(s)); }

/* v with dec decimals (0..9) into out; trim drops trailing zeros. Done by
 * hand rather than with printf so that no locale can turn the point into a
 * comma, and so that -0 never appears. Values are clamped to +-1e9 and NaN
 * becomes 0: nothing in an 800x500 picture needs more. */
static size_t chart_fixed(char *out, size_t cap, double v, int dec, int trim)
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

static void chart_num(chart_buf *b, double v)
{
    char t[40];
    chart_put(b, t, chart_fixed(t, sizeof t, v, 2, 1));
}

/* Next code point of UTF-8 text; invalid bytes decode as U+FFFD one at a
 * time, so any input yields well-formed output. */
static unsigned long chart_utf8(const unsigned char **ps)
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

/* Code points of s as written by chart_text (at most maxcp, with the
 * ellipsis when cut): the basis of every text width estimate. */
static size_t chart_ncp(const char *s, size_t maxcp)
{
    size_t n = 0;
    if (!s) return 0;
    const unsigned char *p = (const unsigned char *)s;
    while (*p) { chart_utf8(&p); n++; }
    return n > maxcp ? maxcp : n;
}

static double chart_textw(const char *s, double size, size_t maxcp)
{
    return (double)chart_ncp(s, maxcp) * CHART_CHARW * size;
}

/* How many code points of text fit in width px at font size. */
static size_t chart_fit(double width, double size)
{
    double n = floor(width / (CHART_CHARW * size));
    return n < 1 ? 1 : (size_t)n;
}

/* Text content or attribute value: XML-escaped, control characters as
 * spaces (XML 1.0 forbids most of them), invalid UTF-8 as U+FFFD, and cut
 * to maxcp code points with an ellipsis as the last one. */
static void chart_text(chart_buf *b, const char *s, size_t maxcp)
{
    if (!s) return;
    size_t total = chart_ncp(s, SIZE_MAX), k = 0;
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        if (total > maxcp && k + 1 == maxcp) { chart_puts(b, "\xE2\x80\xA6"); break; }
        unsigned long c = chart_utf8(&p);
        k++;
        switch (c) {
        case '&':  chart_puts(b, "&amp;");  continue;
        case '<':  chart_puts(b, "&lt;");   continue;
        case '>':  chart_puts(b, "&gt;");   continue;
        case '"':  chart_puts(b, "&quot;"); continue;
        case '\'': chart_puts(b, "&apos;"); continue;
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
        chart_put(b, u, n);
    }
}

/* A tiny printf for SVG: %s raw string, %t escaped text (no length cap),
 * %d int, %f coordinate (at most 2 decimals), %% itself. Not the C printf:
 * its %f goes through chart_fixed for locale independence. */
static void chart_f(chart_buf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    for (const char *p = fmt; *p; p++) {
        const char *q = p;
        while (*q && *q != '%') q++;
        if (q > p) { chart_put(b, p, (size_t)(q - p)); p = q; }
        if (!*p) break;
        char t[24];
        int n;
        switch (*++p) {
        case 's': chart_puts(b, va_arg(ap, const char *)); break;
        case 't': chart_text(b, va_arg(ap, const char *), SIZE_MAX); break;
        case 'd':
            n = snprintf(t, sizeof t, "%d", va_arg(ap, int));
            chart_put(b, t, (size_t)n);
            break;
        case 'f': chart_num(b, va_arg(ap, double)); break;
        case '%': chart_put(b, "%", 1); break;
        default: p--; chart_put(b, "%", 1); break;
        }
    }
    va_end(ap);
}

/* ---- axes ------------------------------------------------------------- */

/* A tick label: base text, and for "10^k" forms an exponent drawn raised. */
typedef struct { char base[40]; char sup[16]; } chart_lab;

typedef struct {
    int    log;
    double lo, hi;                /* limits; for log axes in decades (log10) */
    double step;                  /* linear step, or decades per major tick */
    int    k;                     /* linear: step = m * 10^k */
    size_t nmaj, nmin;
    double maj[CHART_MAXMAJ];    /* in axis units (log10 on log axes) */
    double min[CHART_MAXMIN];
    chart_lab lab[CHART_MAXMAJ];
    size_t nmlab;                 /* labelled minor ticks (short log axes) */
    double mlabpos[CHART_MAXMLAB];
    chart_lab mlab[CHART_MAXMLAB];
    double p0, p1;                /* pixels of lo and hi */
} chart_axis;

static double chart_pow10(int e) { return pow(10.0, (double)e); }

/* Linear ticks: the smallest 1/2/5 x 10^k step whose multiples cover the
 * data in at most maxint intervals. */
static int chart_lin_fit(chart_axis *a, double dmin, double dmax, int maxint)
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
            s = mant[mi] * chart_pow10(kk);
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
    for (double i = i0; i <= i1 && a->nmaj < CHART_MAXMAJ; i++) {
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
static int chart_log_fit(chart_axis *a, double dmin, double dmax, int maxint)
{
    if (dmin > dmax) { double t = dmin; dmin = dmax; dmax = t; }
    if (!(dmin > 0) || !isfinite(dmin) || !isfinite(dmax)) return -1;
    int e0 = (int)floor(log10(dmin)), e1 = (int)ceil(log10(dmax));
    /* log10 of a value next to a power of ten may round across it */
    if (e0 < 308 && chart_pow10(e0 + 1) <= dmin) e0++;
    if (chart_pow10(e0) > dmin) e0--;
    if (e1 > -330 && chart_pow10(e1 - 1) >= dmax) e1--;
    if (chart_pow10(e1) < dmax) e1++;
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
    for (int e = e0; e <= e1 && a->nmaj < CHART_MAXMAJ; e += s) a->maj[a->nmaj++] = e;
    int ms = s <= 5 ? 1 : s / 5;
    for (int e = e0; e < e1; e++) {
        if (s == 1) {
            for (int m = 2; m <= 9 && a->nmin < CHART_MAXMIN; m++)
                a->min[a->nmin++] = e + log10((double)m);
        } else if (e % s != 0 && e % ms == 0 && a->nmin < CHART_MAXMIN) {
            a->min[a->nmin++] = e;
        }
    }
    return 0;
}

size_t chart_ticks(double dmin, double dmax, int log_scale,
                    double *ticks, size_t cap, double *lo, double *hi)
{
    chart_axis a;
    int r = log_scale ? chart_log_fit(&a, dmin, dmax, CHART_MAXINT)
                      : chart_lin_fit(&a, dmin, dmax, CHART_MAXINT);
    if (r) return 0;
    for (size_t i = 0; i < a.nmaj && i < cap && ticks; i++)
        ticks[i] = a.log ? chart_pow10((int)a.maj[i]) : a.maj[i];
    if (lo) *lo = a.log ? chart_pow10((int)a.lo) : a.lo;
    if (hi) *hi = a.log ? chart_pow10((int)a.hi) : a.hi;
    return a.nmaj;
}

/* Replace a leading '-' by U+2212 MINUS SIGN, which typesets as wide as
 * '+' and lines up with the digits (as matplotlib does). */
static void chart_minus(char *s, size_t cap)
{
    size_t n = strlen(s);
    if (s[0] != '-' || n + 3 > cap) return;
    memmove(s + 3, s + 1, n);
    memcpy(s, "\xE2\x88\x92", 3);
}

/* Tick labels: "10^k" on log axes; on linear axes the decimals the step
 * needs, the same on every label, or a mantissa times 10^E when the
 * numbers are large (>= 1e6) or small (all below 1e-3). */
static void chart_labels(chart_axis *a)
{
    int sci = 0, E = 0, dec = a->k < 0 ? -a->k : 0;
    if (!a->log) {
        double big = fmax(fabs(a->lo), fabs(a->hi));
        E = big > 0 ? (int)floor(log10(big)) : 0;
        if (E >= 6 || E <= -4) { sci = 1; dec = E - a->k; if (dec < 0) dec = 0; }
    }
    for (size_t i = 0; i < a->nmaj; i++) {
        chart_lab *l = &a->lab[i];
        l->sup[0] = 0;
        if (a->log) {
            snprintf(l->base, sizeof l->base, "10");
            snprintf(l->sup, sizeof l->sup, "%d", (int)a->maj[i]);
            chart_minus(l->sup, sizeof l->sup);
            continue;
        }
        double v = a->maj[i];
        if (sci && v != 0) {
            size_t n = chart_fixed(l->base, sizeof l->base, v / chart_pow10(E), dec, 0);
            snprintf(l->base + n, sizeof l->base - n, "\xC3\x97" "10");
            snprintf(l->sup, sizeof l->sup, "%d", E);
            chart_minus(l->sup, sizeof l->sup);
        } else {
            chart_fixed(l->base, sizeof l->base, v, sci ? 0 : dec, 0);
        }
        chart_minus(l->base, sizeof l->base);
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
            for (size_t j = 0; j < nm && a->nmlab < CHART_MAXMLAB; j++) {
                chart_lab *l = &a->mlab[a->nmlab];
                a->mlabpos[a->nmlab++] = e + log10((double)m[j]);
                snprintf(l->base, sizeof l->base, "%d\xC3\x97" "10", m[j]);
                snprintf(l->sup, sizeof l->sup, "%d", e);
                chart_minus(l->sup, sizeof l->sup);
            }
    }
}

#define CHART_SUPSCALE 0.75   /* exponent size relative to the label */

static double chart_labw(const chart_lab *l, double size)
{
    return chart_textw(l->base, size, SIZE_MAX) +
           chart_textw(l->sup, size * CHART_SUPSCALE, SIZE_MAX);
}

static double chart_maxlabw(const chart_axis *a, double size)
{
    double w = 0;
    for (size_t i = 0; i < a->nmaj; i++) w = fmax(w, chart_labw(&a->lab[i], size));
    for (size_t i = 0; i < a->nmlab; i++) w = fmax(w, chart_labw(&a->mlab[i], size));
    return w;
}

/* Pixel of an axis-unit position (tick positions). Halved operands keep
 * the differences finite for limits near +-DBL_MAX. */
static double chart_upix(const chart_axis *a, double t)
{
    return a->p0 + (t / 2 - a->lo / 2) / (a->hi / 2 - a->lo / 2) * (a->p1 - a->p0);
}

/* Pixel of a data value (log axes take the value, not its log). */
static double chart_pix(const chart_axis *a, double v)
{
    return chart_upix(a, a->log ? log10(v) : v);
}

/* Thin lines at pixel centres, so that the grid and frame are crisp. */
static double chart_snap(double v) { return floor(v) + 0.5; }

/* minor: a minor tick's label, in grey so the decades still stand out */
static void chart_ticklabel(chart_buf *b, const chart_lab *l, double x, double y,
                             const char *anchor, int minor)
{
    chart_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"%s\"%s>%t", x, y, anchor,
             minor ? " fill=\"#666\"" : "", l->base);
    if (l->sup[0])
        chart_f(b, "<tspan dy=\"-5\" font-size=\"%f\">%t</tspan>",
                 CHART_FS_TICK * CHART_SUPSCALE, l->sup);
    chart_puts(b, "</text>\n");
}

/* ---- rendering -------------------------------------------------------- */

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
} chart_lay;

#define CHART_PAD      10  /* end ticks this far inside the frame */
#define CHART_LEGMAX   26  /* legend text cut to this many characters */
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
            l->nleg++;
            legtw = fmax(legtw, c->ser[s].key == 2 ? chart_textw(c->ser[s].label, CHART_FS_TICK, CHART_LEGMAX + 6) - 32
                                                  : chart_textw(c->ser[s].label, CHART_FS_TICK, CHART_LEGMAX));
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
            int pen = 0;
            double px = 0, py = 0;
            for (size_t i = 0; i < se->n; i++) {
                if (chart_visible(c, se->pt[i].x, se->pt[i].y) != CHART_SHOWN) {
                    pen = 0;            /* a skipped point breaks the line */
                    continue;
                }
                double x = chart_pix(&l->ax, se->pt[i].x), y = chart_pix(&l->ay, se->pt[i].y);
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
                    chart_marker(&d, chart_shape(c, s), chart_pix(&l->ax, se->pt[i].x),
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
            double x = chart_pix(&l->ax, pt->x), y = chart_pix(&l->ay, pt->y);
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
    for (size_t k = 0; k < c->npl && !b->oom; k++) {
        const chart_pt *pt = &c->ser[c->pl[k].series].pt[c->pl[k].idx];
        if (chart_visible(c, pt->x, pt->y) != CHART_SHOWN) continue;
        double x = chart_pix(&l->ax, pt->x), y = chart_pix(&l->ay, pt->y);
        double w = chart_textw(c->pl[k].text, fs, CHART_PLMAX);
        /* per spot: offset of the text's left edge, of its baseline */
        const double spot[6][2] = {
            { gap, -gap }, { gap, gap + asc }, { -gap - w, -gap },
            { -gap - w, gap + asc }, { -w / 2, -gap - 3 }, { -w / 2, gap + 3 + asc },
        };
        int best = 0;
        size_t bestscore = SIZE_MAX;
        for (int q = 0; q < 6 && bestscore; q++) {
            chart_box bx = { x + spot[q][0], y + spot[q][1] - asc,
                              x + spot[q][0] + w, y + spot[q][1] + dsc };
            size_t score = 0;
            if (bx.x0 < l->L || bx.x1 > l->R || bx.y0 < l->T || bx.y1 > l->B) score += 1000;
            for (size_t j = 0; j < lab.n; j++) score += 100 * (size_t)chart_overlap(bx, lab.v[j]);
            for (size_t j = 0; j < obst.n; j++) score += (size_t)chart_overlap(bx, obst.v[j]);
            if (score < bestscore) { bestscore = score; best = q; }
        }
        if (bestscore >= 100) continue;       /* on another text or outside: dropped */
        chart_box bx = { x + spot[best][0], y + spot[best][1] - asc,
                          x + spot[best][0] + w, y + spot[best][1] + dsc };
        chart_addbox(&lab, bx, b);
        chart_f(b, "<text x=\"%f\" y=\"%f\" font-size=\"%d\" fill=\"#333\" " CHART_HALO ">",
                 bx.x0, y + spot[best][1], CHART_FS_SMALL);
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
 * its height, then "+N more". */
static void chart_draw_legend(const chart_lay *l)
{
    const chart *c = l->c;
    chart_buf *b = l->b;
    const double rowh = 18;
    size_t fit = (size_t)((l->B - l->T - 12) / rowh), shown = l->nleg;
    if (fit < 1) fit = 1;
    if (shown > fit) shown = fit - 1;
    double lx = l->R + 15, ly = l->T;
    double lh = 8 + rowh * (double)(shown + (shown < l->nleg)) + 2;
    chart_f(b, "<rect x=\"%f\" y=\"%f\" width=\"%f\" height=\"%f\" fill=\"#fff\" "
             "stroke=\"#ccc\" stroke-width=\"1\" rx=\"3\"/>\n",
             chart_snap(lx), chart_snap(ly), floor(l->legw), floor(lh));
    size_t row = 0;
    for (size_t s = 0; s < c->nser && row < shown; s++) {
        const chart_ser *se = &c->ser[s];
        if (!se->label || !chart_draws(c, s)) continue;
        double cy = ly + 4 + rowh * (double)row + rowh / 2;
        if (se->key == 2) {             /* a heading: the text from the left edge */
            chart_f(b, "<text x=\"%f\" y=\"%f\" fill=\"#555\">", lx + 10, cy + 4);
            chart_text(b, se->label, CHART_LEGMAX + 6);
            chart_puts(b, "</text>\n");
            row++;
            continue;
        }
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
        chart_f(b, "<text x=\"%f\" y=\"%f\">", lx + 42, cy + 4);
        chart_text(b, se->label, CHART_LEGMAX);
        chart_puts(b, "</text>\n");
        row++;
    }
    if (shown < l->nleg)
        chart_f(b, "<text x=\"%f\" y=\"%f\" fill=\"#666\">+%d more</text>\n",
                 lx + 42, ly + 4 + rowh * (double)shown + rowh / 2 + 4, (int)(l->nleg - shown));
}

static void chart_render(const chart *c, chart_buf *b)
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
}

/* ---- writing ---------------------------------------------------------- */

/* One-line message: the path may hold newlines, the message may not. */
static void chart_err(char *err, size_t errlen, const char *fmt, ...)
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
static int chart_rendered(const chart *c, const char *what, chart_buf *b, char *err, size_t errlen)
{
    if (err && errlen) err[0] = 0;
    if (!c || !what || !*what) {
        chart_err(err, errlen, "chart: no chart or no path");
        return -1;
    }
    if (c->err[0]) {
        chart_err(err, errlen, "%s: chart is incomplete: %s", what, c->err);
        return -1;
    }
    chart_render(c, b);
    if (b->oom) {
        free(b->p);
        b->p = NULL;
        chart_err(err, errlen, "%s: out of memory", what);
        return -1;
    }
    return 0;
}

int chart_fwrite(const chart *c, FILE *f, const char *what, char *err, size_t errlen)
{
    chart_buf b = { 0 };
    if (chart_rendered(c, what, &b, err, errlen)) return -1;
    /* A write error stays in the stream's flag for whoever closes it. */
    if (b.n) fwrite(b.p, 1, b.n, f);
    free(b.p);
    return 0;
}

int chart_write(const chart *c, const char *path, char *err, size_t errlen)
{
    chart_buf b = { 0 };
    if (chart_rendered(c, path, &b, err, errlen)) return -1;

    /* base_out: a temporary beside a regular file, renamed once complete
     * (with the umask's permissions), removed on SIGINT/TERM/HUP; a device
     * or FIFO written through; "-" is stdout. */
    int rc = base_out_write_all(path, b.p, b.n, err, errlen);
    free(b.p);
    return rc;
}
