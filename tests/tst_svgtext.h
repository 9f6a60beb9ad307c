/* tst_svgtext.h - the texts of an SVG chart as boxes, to check that no two
 * overlap. Computed from the file alone, as a reader would: each <text>'s
 * x, y, text-anchor, font-size (inherited from <svg> when absent; a
 * <tspan>'s own size for its characters) and its number of characters
 * (an entity or a UTF-8 sequence is one), at 0.6 em a character and from
 * 0.8 em above the baseline to 0.2 em below. A text rotated by -90 degrees
 * (the y axis label) stands upright around its anchor. Included by the
 * tests that need it; everything is static.
 */
#ifndef TST_SVGTEXT_H
#define TST_SVGTEXT_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct tst_tbox { double x0, y0, x1, y1; char text[64]; } tst_tbox;

/* The value of attribute name in the tag [p, end), or NULL. */
static const char *tst_attr(const char *p, const char *end, const char *name, char *buf, size_t cap)
{
    size_t n = strlen(name);
    for (const char *q = p; q && q < end; q++) {
        if ((q == p || q[-1] == ' ') && !strncmp(q, name, n) && q[n] == '=' && q[n + 1] == '"') {
            const char *v = q + n + 2, *e = strchr(v, '"');
            if (!e || e > end) return NULL;
            snprintf(buf, cap, "%.*s", (int)(e - v), v);
            return buf;
        }
    }
    return NULL;
}

/* Characters from s up to the next '<': entities and UTF-8 sequences count
 * one each; *s is moved past them; the text is appended to out. */
static double tst_chars(const char **s, char *out, size_t cap)
{
    double n = 0;
    const char *p = *s;
    while (*p && *p != '<') {
        size_t k = strlen(out);
        if (k + 1 < cap) { out[k] = *p; out[k + 1] = 0; }
        if (*p == '&') { const char *e = strchr(p, ';'); p = e ? e + 1 : p + 1; }
        else if ((unsigned char)*p >= 0x80) { p++; while ((*p & 0xC0) == 0x80) p++; }
        else p++;
        n++;
    }
    *s = p;
    return n;
}

/* Up to cap text boxes of svg; returns how many there are. */
static int tst_svg_text_boxes(const char *svg, tst_tbox *box, int cap)
{
    char v[128];
    double root = 16;
    const char *sv = strstr(svg, "<svg");
    if (sv && tst_attr(sv, strchr(sv, '>'), "font-size", v, sizeof v)) root = atof(v);
    int n = 0;
    for (const char *p = strstr(svg, "<text"); p; p = strstr(p + 1, "<text")) {
        const char *end = strchr(p, '>');
        if (!end) break;
        double x = tst_attr(p, end, "x", v, sizeof v) ? atof(v) : 0;
        double y = tst_attr(p, end, "y", v, sizeof v) ? atof(v) : 0;
        double fs = tst_attr(p, end, "font-size", v, sizeof v) ? atof(v) : root;
        const char *anchor = tst_attr(p, end, "text-anchor", v, sizeof v) ? (strcmp(v, "middle") ? strcmp(v, "end") ? "s" : "e" : "m") : "s";
        int rot = tst_attr(p, end, "transform", v, sizeof v) && strstr(v, "rotate(-90") != NULL;
        /* the content, with tspans at their own size */
        tst_tbox b;
        memset(&b, 0, sizeof b);
        double w = 0;
        const char *c = end + 1;
        while (*c && strncmp(c, "</text>", 7)) {
            if (!strncmp(c, "<tspan", 6)) {
                const char *te = strchr(c, '>');
                if (!te) break;
                double ts = tst_attr(c, te, "font-size", v, sizeof v) ? atof(v) : fs;
                c = te + 1;
                w += 0.6 * ts * tst_chars(&c, b.text, sizeof b.text);
                if (!strncmp(c, "</tspan>", 8)) c += 8;
            } else if (*c == '<') {
                c = strchr(c, '>');
                if (!c) break;
                c++;
            } else w += 0.6 * fs * tst_chars(&c, b.text, sizeof b.text);
        }
        double a0 = *anchor == 's' ? 0 : *anchor == 'm' ? -w / 2 : -w;
        if (rot) { b.x0 = x - 0.8 * fs; b.x1 = x + 0.2 * fs; b.y0 = y - a0 - w; b.y1 = y - a0; }
        else { b.x0 = x + a0; b.x1 = x + a0 + w; b.y0 = y - 0.8 * fs; b.y1 = y + 0.2 * fs; }
        if (n < cap) box[n] = b;
        n++;
    }
    return n;
}

/* The first pair of texts whose boxes overlap (by more than half a pixel
 * each way) into why; 0 when none does, 1 when some do. */
static int tst_svg_text_overlap(const char *svg, char *why, size_t wl)
{
    enum { CAP = 2000 };
    tst_tbox *b = malloc(CAP * sizeof *b);
    if (!b) { snprintf(why, wl, "out of memory"); return 1; }
    int n = tst_svg_text_boxes(svg, b, CAP);
    if (n > CAP) n = CAP;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (b[i].x0 + 0.5 < b[j].x1 && b[j].x0 + 0.5 < b[i].x1 && b[i].y0 + 0.5 < b[j].y1 && b[j].y0 + 0.5 < b[i].y1) {
                snprintf(why, wl, "'%s' (%.1f,%.1f..%.1f,%.1f) overlaps '%s' (%.1f,%.1f..%.1f,%.1f)", b[i].text, b[i].x0,
                         b[i].y0, b[i].x1, b[i].y1, b[j].text, b[j].x0, b[j].y0, b[j].x1, b[j].y1);
                free(b);
                return 1;
            }
    free(b);
    return 0;
}
#endif
