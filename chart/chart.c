/* chart.c - SVG chart writer; see chart.h for what it promises.
 *
 * The chart only records what it is given. All layout happens in
 * chart_write: the whole file is rendered into a memory buffer first, so
 * the file is written in one go and an out-of-memory midway never leaves a
 * half-written chart. (chart_int.h lists the module's other files.)
 */
#include "chart/chart_int.h"
#include "base/base_out.h"
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Make room for need elements in *p (capacity *cap, element size sz);
 * out of memory (or a size past the address space) ends the program. */
void chart_grow(void **p, size_t *cap, size_t need, size_t sz)
{
    if (need <= *cap) return;
    size_t nc = *cap ? *cap : 8;
    while (nc < need) {
        if (nc > SIZE_MAX / 2) base_out_of_memory();
        nc *= 2;
    }
    if (nc > SIZE_MAX / sz) base_out_of_memory();
    void *q = realloc(*p, nc * sz);
    if (!q) base_out_of_memory();
    *p = q;
    *cap = nc;
}

static void chart_fail(chart *c, const char *msg)
{
    if (!c->err[0]) snprintf(c->err, sizeof c->err, "%s", msg);
}

/* Copy of an optional text; NULL stays NULL (out of memory exits). */
static char *chart_dup_text(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (!d) base_out_of_memory();
    return memcpy(d, s, n);
}

chart *chart_new(const char *title, const char *xlabel, const char *ylabel)
{
    chart *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->title = chart_dup_text(title);
    c->xlabel = chart_dup_text(xlabel);
    c->ylabel = chart_dup_text(ylabel);
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
    if (c->nser >= INT_MAX) base_out_of_memory();
    chart_grow((void **)&c->ser, &c->capser, c->nser + 1, sizeof *c->ser);
    /* A series with neither bit would be invisible: default to points. */
    if (!(style & (CHART_LINE | CHART_POINTS | CHART_STEP))) style = CHART_POINTS;
    chart_ser *s = &c->ser[c->nser];
    memset(s, 0, sizeof *s);
    s->style = style;
    s->shape = -1;
    s->dash = -1;
    if (label && *label) s->label = chart_dup_text(label);
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
    chart_grow((void **)&s->pt, &s->cap, s->n + 1, sizeof *s->pt);
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
    chart_grow((void **)&c->pl, &c->cappl, c->npl + 1, sizeof *c->pl);
    char *t = chart_dup_text(label);
    if (!t) return;
    c->pl[c->npl].series = series;
    c->pl[c->npl].idx = idx;
    c->pl[c->npl].text = t;
    c->npl++;
}

void chart_hband(chart *c, double x0, double x1, const char *label)
{
    if (!c) return;
    chart_grow((void **)&c->band, &c->capband, c->nband + 1, sizeof *c->band);
    char *t = NULL;
    if (label && *label) t = chart_dup_text(label);
    c->band[c->nband].x0 = x0 <= x1 ? x0 : x1;
    c->band[c->nband].x1 = x0 <= x1 ? x1 : x0;
    c->band[c->nband].label = t;
    c->nband++;
}

void chart_hline(chart *c, double y, const char *label)
{
    if (!c) return;
    chart_grow((void **)&c->hl, &c->caphl, c->nhl + 1, sizeof *c->hl);
    char *t = NULL;
    if (label && *label) t = chart_dup_text(label);
    c->hl[c->nhl].y = y;
    c->hl[c->nhl].label = t;
    c->nhl++;
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
