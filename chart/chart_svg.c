/* chart_svg.c - the buffer a chart is rendered into, and what writes
 * into it: numbers that no locale can change, XML-escaped UTF-8 text cut
 * to a length, text width estimates, a small printf for SVG. */
#include "base/base_out.h"
#include "chart/chart_int.h"
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void chart_put(chart_buf *b, const char *s, size_t len)
{
    if (len >= SIZE_MAX - b->n) base_out_of_memory();
    chart_grow((void **)&b->p, &b->cap, b->n + len + 1, 1);
    memcpy(b->p + b->n, s, len);
    b->n += len;
    b->p[b->n] = 0;
}

void chart_puts(chart_buf *b, const char *s) { chart_put(b, s, strlen(s)); }

/* v with dec decimals (0..9) into out; trim drops trailing zeros. Done by
 * hand rather than with printf so that no locale can turn the point into a
 * comma, and so that -0 never appears. Values are clamped to +-1e9 and NaN
 * becomes 0: nothing in an 800x500 picture needs more. */
size_t chart_fixed(char *out, size_t cap, double v, int dec, int trim)
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

double chart_textw(const char *s, double size, size_t maxcp)
{
    return (double)chart_ncp(s, maxcp) * CHART_CHARW * size;
}

/* How many code points of text fit in width px at font size. */
size_t chart_fit(double width, double size)
{
    double n = floor(width / (CHART_CHARW * size));
    return n < 1 ? 1 : (size_t)n;
}

/* Text content or attribute value: XML-escaped, control characters as
 * spaces (XML 1.0 forbids most of them), invalid UTF-8 as U+FFFD, and cut
 * to maxcp code points with an ellipsis as the last one. */
void chart_text(chart_buf *b, const char *s, size_t maxcp)
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
void chart_f(chart_buf *b, const char *fmt, ...)
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
