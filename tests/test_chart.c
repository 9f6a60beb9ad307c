/* test_chart.c - the SVG chart writer (chart/).
 *
 * Checks chart_pareto against the O(n^2) definition, the tick placement, and
 * that every chart file is well-formed XML by an independent little checker
 * here, and by xmllint and rsvg-convert where they are installed (a test
 * that needs a missing tool says skip). Set TST_SVG_KEEP=DIR to keep the
 * sample charts and their PNGs in DIR for looking at.
 */
#include "tests/tst.h"
#include "chart/chart.h"
#include "tests/tst_svgtext.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- scratch directory ------------------------------------------------ */

static char tdir[512];

static const char *tpath(const char *name)
{
    static char p[4][700];     /* a few live at once in one expression */
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", tdir, name);
    return p[k];
}


/* Names in dir, sorted into one string "a b c" for comparisons. */
static void dir_list(const char *dir, char *out, size_t cap)
{
    char names[64][256];
    int n = 0;
    out[0] = 0;
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)) && n < 64) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(names[n++], sizeof names[0], "%s", e->d_name);
    }
    closedir(d);
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && strcmp(names[j - 1], names[j]) > 0; j--) {
            char t[256];
            memcpy(t, names[j], sizeof t);
            memcpy(names[j], names[j - 1], sizeof t);
            memcpy(names[j - 1], t, sizeof t);
        }
    size_t len = 0;
    for (int i = 0; i < n && len < cap; i++)
        len += (size_t)snprintf(out + len, cap - len, "%s%s", i ? " " : "", names[i]);
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, n = 0;
    char *b = malloc(cap + 1);
    size_t r;
    while (b && (r = fread(b + n, 1, cap - n, f)) > 0) {
        n += r;
        if (n == cap) {
            char *q = realloc(b, 2 * cap + 1);
            if (!q) { free(b); b = NULL; break; }
            b = q;
            cap *= 2;
        }
    }
    fclose(f);
    if (b) b[n] = 0;
    if (len) *len = n;
    return b;
}

static int have_tool(const char *name)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", name);
    return system(cmd) == 0;
}

/* ---- an independent XML well-formedness checker ------------------------ */

static int xml_namech(int c, int first)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == ':' ||
           (!first && ((c >= '0' && c <= '9') || c == '-' || c == '.'));
}

static const char *xml_entity(const char *p)   /* p at '&'; past ';' or NULL */
{
    static const char *const named[] = { "&amp;", "&lt;", "&gt;", "&quot;", "&apos;" };
    for (int i = 0; i < 5; i++)
        if (!strncmp(p, named[i], strlen(named[i]))) return p + strlen(named[i]);
    if (p[1] != '#') return NULL;
    const char *q = p + 2;
    int hex = *q == 'x';
    if (hex) q++;
    const char *d = q;
    while (hex ? isxdigit((unsigned char)*q) : isdigit((unsigned char)*q)) q++;
    return q > d && *q == ';' ? q + 1 : NULL;
}

static int utf8_ok(const unsigned char *s, size_t n)
{
    for (size_t i = 0; i < n;) {
        unsigned c = s[i];
        int len = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 :
                  (c & 0xF8) == 0xF0 ? 4 : 0;
        if (!len || i + (size_t)len > n) return 0;
        if (len == 1 && c < 0x20 && c != '\n' && c != '\t' && c != '\r') return 0;
        for (int k = 1; k < len; k++) if ((s[i + k] & 0xC0) != 0x80) return 0;
        if (len == 2 && c < 0xC2) return 0;
        i += (size_t)len;
    }
    return 1;
}

/* 0 if doc is well-formed (tags balance, one root, attributes quoted and
 * unique, only valid entities, no raw '<' or '&' in text or values). */
static int xml_check(const char *doc, char *why, size_t wl)
{
#define XBAD(...) do { snprintf(why, wl, __VA_ARGS__); return -1; } while (0)
    if (!utf8_ok((const unsigned char *)doc, strlen(doc))) XBAD("invalid UTF-8 or control char");
    const char *p = doc;
    char stack[64][64];
    int depth = 0, roots = 0;
    if (!strncmp(p, "<?xml", 5)) {
        p = strstr(p, "?>");
        if (!p) XBAD("unterminated XML declaration");
        p += 2;
    }
    while (*p) {
        if (*p != '<') {
            if (*p == '&') {
                const char *q = xml_entity(p);
                if (!q) XBAD("bad entity at offset %ld", (long)(p - doc));
                if (!depth) XBAD("entity outside the root");
                p = q;
                continue;
            }
            if (*p == '>') XBAD("raw '>' in text at offset %ld", (long)(p - doc));
            if (!depth && !isspace((unsigned char)*p)) XBAD("text outside the root");
            p++;
            continue;
        }
        if (!strncmp(p, "<!--", 4)) {
            const char *q = strstr(p + 4, "--");
            if (!q || q[2] != '>') XBAD("bad comment");
            p = q + 3;
            continue;
        }
        if (p[1] == '!' || p[1] == '?') XBAD("unexpected <%c", p[1]);
        int closing = p[1] == '/';
        p += closing ? 2 : 1;
        const char *n0 = p;
        if (!xml_namech((unsigned char)*p, 1)) XBAD("bad tag name at offset %ld", (long)(p - doc));
        while (xml_namech((unsigned char)*p, 0)) p++;
        size_t nl = (size_t)(p - n0);
        if (nl >= sizeof stack[0]) XBAD("tag name too long");
        if (closing) {
            while (isspace((unsigned char)*p)) p++;
            if (*p != '>') XBAD("bad end tag");
            if (!depth || strlen(stack[depth - 1]) != nl || strncmp(stack[depth - 1], n0, nl))
                XBAD("end tag </%.*s> does not match", (int)nl, n0);
            depth--;
            p++;
            continue;
        }
        char attrs[64][64];
        int na = 0;
        for (;;) {
            int ws = 0;
            while (isspace((unsigned char)*p)) { p++; ws = 1; }
            if (*p == '>' || (p[0] == '/' && p[1] == '>')) break;
            if (!ws) XBAD("no space before attribute at offset %ld", (long)(p - doc));
            const char *a0 = p;
            if (!xml_namech((unsigned char)*p, 1)) XBAD("bad attribute name at offset %ld", (long)(p - doc));
            while (xml_namech((unsigned char)*p, 0)) p++;
            size_t al = (size_t)(p - a0);
            if (al >= sizeof attrs[0] || na >= 64) XBAD("attribute too long or too many");
            for (int i = 0; i < na; i++)
                if (strlen(attrs[i]) == al && !strncmp(attrs[i], a0, al)) XBAD("duplicate attribute %.*s", (int)al, a0);
            memcpy(attrs[na], a0, al);
            attrs[na++][al] = 0;
            if (*p != '=') XBAD("attribute %.*s without value", (int)al, a0);
            p++;
            char qc = *p;
            if (qc != '"' && qc != '\'') XBAD("unquoted attribute %.*s", (int)al, a0);
            p++;
            while (*p && *p != qc) {
                if (*p == '<') XBAD("'<' in attribute value");
                if (*p == '&') {
                    const char *q = xml_entity(p);
                    if (!q) XBAD("bad entity in attribute value");
                    p = q;
                } else p++;
            }
            if (!*p) XBAD("unterminated attribute value");
            p++;
        }
        if (!depth && roots++) XBAD("more than one root element");
        if (*p == '/') { p += 2; continue; }       /* empty element */
        if (depth >= 64) XBAD("nesting too deep");
        memcpy(stack[depth], n0, nl);
        stack[depth++][nl] = 0;
        p++;
    }
    if (depth) XBAD("unclosed <%s>", stack[depth - 1]);
    if (roots != 1) XBAD("no root element");
    return 0;
#undef XBAD
}

/* The file is well-formed, has no script or external reference, and no
 * number in markup (coordinates) with more than two decimals. */
static void check_file(const char *path)
{
    char why[200] = "";
    char *s = slurp(path, NULL);
    TST_CHECK(s != NULL, "cannot read %s", path);
    if (!s) return;
    TST_CHECK(xml_check(s, why, sizeof why) == 0, "%s: %s", path, why);
    TST_CHECK(!strstr(s, "<script") && !strstr(s, "href") && !strstr(s, "url("),
              "%s: script or external reference", path);
    const char *h = strstr(s, "http");
    TST_CHECK(!h || (!strncmp(h - 7, "xmlns=\"", 7) && !strstr(h + 4, "http")),
              "%s: URL other than the xmlns", path);
    const char *body = strstr(s, "<svg");   /* past version="1.0" */
    int intag = 0;
    for (const char *p = body ? body : s; *p; p++) {
        if (*p == '<' || *p == '>') intag = *p == '<';
        if (intag && *p == '.' && isdigit((unsigned char)p[1])) {
            int n = 0;
            while (isdigit((unsigned char)p[1 + n])) n++;
            TST_CHECK(n <= 2, "%s: number with %d decimals near \"%.20s\"", path, n, p - 5);
            p += n;
        }
    }
    free(s);
}

static int write_ok(chart *c, const char *path)
{
    char err[256] = "";
    int r = chart_write(c, path, err, sizeof err);
    TST_CHECK(r == 0, "write %s: %s", path, err);
    return r == 0;
}

/* ---- sample charts (deterministic data) -------------------------------- */

static uint64_t rng_state;
static double urand(void)   /* [0, 1), xorshift64* */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
}

static chart *sample_error_width(void)
{
    chart *c = chart_new("Max error vs bit width", "bit width (bits)", "max |error| (rad)");
    chart_log_y(c, 1);
    int a = chart_series(c, "CORDIC", CHART_LINE | CHART_POINTS);
    int b = chart_series(c, "LUT + linear interp.", CHART_LINE | CHART_POINTS);
    int p = chart_series(c, "polynomial (deg 3)", CHART_LINE | CHART_POINTS);
    for (int w = 8; w <= 24; w += 2) {
        chart_point(c, a, w, 3.1 * ldexp(1.0, -w + 1));
        chart_point(c, b, w, w < 18 ? 0.8 * ldexp(1.0, -w) : 0.8 * ldexp(1.0, -18) * (1 + 0.05 * (w - 18)));
        chart_point(c, p, w, 0.5 * ldexp(1.0, -w) + 2e-7);
    }
    chart_hline(c, 1e-5, "target 1e-5");
    return c;
}

static chart *sample_area_pareto(void)
{
    chart *c = chart_new("Area vs error (Pareto front marked)", "max |error| (ulp)", "area (gate equivalents)");
    chart_log_x(c, 1);
    int all = chart_series(c, "design points", CHART_POINTS);
    int fr = chart_series(c, "Pareto front", CHART_STEP | CHART_POINTS);
    enum { N = 40 };
    double x[N], y[N];
    int w[N];
    unsigned char on[N];
    rng_state = 12345;
    for (int i = 0; i < N; i++) {
        w[i] = 8 + (int)(urand() * 17);
        x[i] = ldexp(1.0, 20 - w[i]) * (1 + 3 * urand());
        y[i] = 40.0 * w[i] * w[i] * (0.6 + urand());
        chart_point(c, all, x[i], y[i]);
    }
    chart_pareto(x, y, N, on);
    /* the front in order of increasing error, for the staircase */
    int idx[N], m = 0;
    for (int i = 0; i < N; i++) if (on[i]) idx[m++] = i;
    for (int i = 1; i < m; i++)
        for (int j = i; j > 0 && x[idx[j - 1]] > x[idx[j]]; j--) { int t = idx[j]; idx[j] = idx[j - 1]; idx[j - 1] = t; }
    for (int i = 0; i < m; i++) {
        char lab[16];
        snprintf(lab, sizeof lab, "w=%d", w[idx[i]]);
        chart_point_label(c, fr, x[idx[i]], y[idx[i]], lab);
    }
    return c;
}

static chart *sample_angle(void)
{
    chart *c = chart_new("Error vs angle, 12-bit CORDIC", "angle (degrees)", "|error| (ulp)");
    int s = chart_series(c, "sin", CHART_LINE);
    int k = chart_series(c, "cos", CHART_LINE);
    for (int d = 0; d <= 360; d += 2) {
        double r = d * 3.14159265358979 / 180;
        double bump = exp(-pow((d % 180 - 90) / 4.0, 2)) * 6;
        chart_point(c, s, d, 0.6 + 0.3 * fabs(sin(3 * r)) + bump);
        chart_point(c, k, d, 0.5 + 0.3 * fabs(cos(5 * r)) + (d > 350 ? 4 : 0));
    }
    chart_hband(c, 84, 96, "fails: |err| > 2 ulp");
    chart_hband(c, 264, 276, "fails");
    chart_hband(c, 350, INFINITY, "fails");
    chart_hline(c, 2, "limit 2 ulp");
    return c;
}

static chart *sample_clocks(void)
{
    chart *c = chart_new("Clocks per item vs error", "max |error| (ulp)", "clocks / item");
    const char *names[] = { "CORDIC serial", "CORDIC unrolled x2", "CORDIC unrolled x4",
                            "LUT", "poly Horner", "poly Estrin", "hybrid", "CORDIC + LUT seed",
                            "a very long series label that will not fit the legend box" };
    for (int i = 0; i < 9; i++) {
        int s = chart_series(c, names[i], i % 3 == 0 ? CHART_POINTS : CHART_LINE | CHART_POINTS);
        for (int j = 0; j < 6; j++) chart_point(c, s, 0.5 + j * 0.7 + i * 0.05, 2 + i * 2.5 + 12.0 / (j + 1));
    }
    return c;
}

typedef chart *(*sample_fn)(void);
static const struct { const char *name; sample_fn fn; } samples[] = {
    { "error_width.svg", sample_error_width },
    { "area_pareto.svg", sample_area_pareto },
    { "error_angle.svg", sample_angle },
    { "clocks.svg", sample_clocks },
};
#define NSAMPLES (sizeof samples / sizeof samples[0])

static void write_samples(void)
{
    for (size_t i = 0; i < NSAMPLES; i++) {
        chart *c = samples[i].fn();
        TST_CHECK(c != NULL, "%s", samples[i].name);
        if (c) write_ok(c, tpath(samples[i].name));
        chart_free(c);
    }
    chart *e = chart_new("Empty", "x", "y");
    write_ok(e, tpath("empty.svg"));
    chart_free(e);
}

/* ---- tests ------------------------------------------------------------- */

static size_t pareto_ref(const double *x, const double *y, size_t n, unsigned char *on)
{
    size_t cnt = 0;
    for (size_t i = 0; i < n; i++) {
        int dom = isnan(x[i]) || isnan(y[i]);
        for (size_t j = 0; j < n && !dom; j++)
            dom = x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i]);
        on[i] = !dom;
        cnt += !dom;
    }
    return cnt;
}

static void test_pareto_vs_bruteforce(void)
{
    enum { MAXN = 80 };
    double x[MAXN], y[MAXN];
    unsigned char a[MAXN], r[MAXN];
    rng_state = 0x9E3779B97F4A7C15ULL;
    for (int t = 0; t < 3000; t++) {
        size_t n = (size_t)(urand() * MAXN);
        int mode = t % 4;   /* small integers (many ties), reals, with NaN, with inf */
        for (size_t i = 0; i < n; i++) {
            if (mode == 0) { x[i] = (int)(urand() * 6); y[i] = (int)(urand() * 6); }
            else { x[i] = urand() * 100; y[i] = urand() * 100; }
            if (mode == 2 && urand() < 0.1) { if (urand() < 0.5) x[i] = NAN; else y[i] = NAN; }
            if (mode == 3 && urand() < 0.1) { if (urand() < 0.5) x[i] = INFINITY; else y[i] = -INFINITY; }
            if (i && urand() < 0.1) { x[i] = x[i - 1]; y[i] = y[i - 1]; }   /* exact duplicate */
        }
        memset(a, 7, sizeof a);
        size_t na = chart_pareto(x, y, n, a), nr = pareto_ref(x, y, n, r);
        TST_EQ_INT(na, nr);
        for (size_t i = 0; i < n; i++) TST_EQ_INT(a[i], r[i]);
        if (n) TST_CHECK(nr > 0 || mode == 2, "a non-empty set without NaN has a front");
    }
    /* documented ties: duplicates are both on the front; equal x, larger y is not */
    double tx[] = { 1, 1, 1, 2, 0.5 }, ty[] = { 3, 3, 4, 2, 5 };
    unsigned char on[5];
    TST_EQ_INT(chart_pareto(tx, ty, 5, on), 4);
    TST_CHECK(on[0] && on[1] && !on[2] && on[3] && on[4], "ties");
    TST_EQ_INT(chart_pareto(tx, ty, 0, on), 0);
}

/* The three-cost front by its definition, O(n^2). */
static size_t pareto3_ref(const double *x, const double *y, const double *z, size_t n, unsigned char *on)
{
    size_t cnt = 0;
    for (size_t i = 0; i < n; i++) {
        int dom = isnan(x[i]) || isnan(y[i]) || isnan(z[i]);
        for (size_t j = 0; j < n && !dom; j++)
            dom = x[j] <= x[i] && y[j] <= y[i] && z[j] <= z[i] && (x[j] < x[i] || y[j] < y[i] || z[j] < z[i]);
        on[i] = !dom;
        cnt += !dom;
    }
    return cnt;
}

static void test_pareto3_vs_bruteforce(void)
{
    enum { MAXN = 90 };
    double x[MAXN], y[MAXN], z[MAXN];
    unsigned char a[MAXN], r[MAXN];
    rng_state = 0x2545F4914F6CDD1DULL;
    for (int t = 0; t < 3000; t++) {
        size_t n = (size_t)(urand() * MAXN);
        int mode = t % 4;   /* small integers (ties), reals, with NaN, with inf */
        for (size_t i = 0; i < n; i++) {
            if (mode == 0) { x[i] = (int)(urand() * 5); y[i] = (int)(urand() * 5); z[i] = (int)(urand() * 3); }
            else { x[i] = urand() * 100; y[i] = urand() * 100; z[i] = urand() < 0.5 ? 1 : 6; }
            if (mode == 2 && urand() < 0.1) z[i] = NAN;
            if (mode == 3 && urand() < 0.1) { if (urand() < 0.5) x[i] = INFINITY; else y[i] = -INFINITY; }
            if (i && urand() < 0.1) { x[i] = x[i - 1]; y[i] = y[i - 1]; z[i] = z[i - 1]; }
        }
        memset(a, 7, sizeof a);
        size_t na = chart_pareto3(x, y, z, n, a), nr = pareto3_ref(x, y, z, n, r);
        TST_EQ_INT(na, nr);
        for (size_t i = 0; i < n; i++) TST_EQ_INT(a[i], r[i]);
    }
    /* A point slower but smaller and more accurate than none other is kept:
     * the third cost alone can put a point on the front. */
    double ex[] = { 0.1, 0.1, 0.2 }, ar[] = { 3000, 2000, 2000 }, ck[] = { 1, 3, 3 };
    unsigned char on[3];
    TST_EQ_INT(chart_pareto3(ex, ar, ck, 3, on), 2);
    TST_CHECK(on[0] && on[1] && !on[2], "fast one kept, dominated one dropped");
    /* with z constant it is the two-cost front */
    double zc[] = { 1, 1, 1 };
    TST_EQ_INT(chart_pareto3(ex, ar, zc, 3, on), 1);
    TST_CHECK(!on[0] && on[1] && !on[2], "2-d front");
}

/* Labels crowded on purpose: a cluster of labelled points, a reference
 * line's label among them, more band labels than rows. */
static chart *sample_crowded(void)
{
    chart *c = chart_new("Crowded labels", "max |e| (output units)", "area (GE)");
    chart_log_x(c, 1);
    int s = chart_series(c, "configurations", CHART_POINTS);
    rng_state = 777;
    for (int i = 0; i < 60; i++) {
        char lab[32];
        snprintf(lab, sizeof lab, "width %d", 8 + i % 20);
        chart_point_label(c, s, 0.01 * (1 + urand()), 1000 + 200 * urand(), lab);
    }
    chart_point_label(c, s, 1, 3000, "an isolated point");
    chart_hline(c, 1100, "target line label");
    for (int k = 0; k < 6; k++) chart_hband(c, 0.011 + 0.0001 * k, 0.012 + 0.0001 * k, "a band label that is long");
    return c;
}

/* No two texts of a chart overlap: the sample charts and a crowded one,
 * boxes computed from the written SVG (tests/tst_svgtext.h). */
static void test_svg_no_text_overlap(void)
{
    char why[400];
    /* the checker itself sees an overlap where there is one */
    const char *bad = "<svg font-size=\"11\"><text x=\"10\" y=\"20\">width 12</text>"
                      "<text x=\"30\" y=\"22\">width 13</text></svg>";
    TST_CHECK(tst_svg_text_overlap(bad, why, sizeof why) == 1, "the checker misses an overlap");
    const char *good = "<svg font-size=\"11\"><text x=\"10\" y=\"20\">w</text><text x=\"10\" y=\"40\">w</text></svg>";
    TST_CHECK(tst_svg_text_overlap(good, why, sizeof why) == 0, "the checker sees an overlap in %s", good);
    for (size_t i = 0; i <= NSAMPLES; i++) {
        chart *c = i < NSAMPLES ? samples[i].fn() : sample_crowded();
        const char *name = i < NSAMPLES ? samples[i].name : "crowded.svg";
        if (!c || !write_ok(c, tpath(name))) { chart_free(c); continue; }
        chart_free(c);
        size_t len;
        char *svg = slurp(tpath(name), &len);
        TST_CHECK(svg != NULL, "read %s", name);
        if (!svg) continue;
        TST_CHECK(!tst_svg_text_overlap(svg, why, sizeof why), "%s: %s", name, why);
        if (i == NSAMPLES) {
            /* the crowded chart keeps some labels and drops others */
            int kept = 0;
            for (const char *p = strstr(svg, ">width "); p; p = strstr(p + 1, ">width ")) kept++;
            TST_CHECK(kept > 0 && kept < 60, "%d of 60 point labels kept", kept);
            TST_CHECK(strstr(svg, "target line label") != NULL, "the reference line keeps its label");
        }
        free(svg);
    }
}

/* The legend lists what is drawn: not a series without a shown point nor a
 * line of one point; keys and headings are listed; series looks apply. */
static void test_svg_legend_drawn_only(void)
{
    chart *c = chart_new("Legend", "x", "y");
    int a = chart_series(c, "drawn points", CHART_POINTS);
    chart_point(c, a, 1, 1);
    chart_point(c, a, 2, 3);
    int e = chart_series(c, "empty series", CHART_POINTS);
    (void)e;
    int one = chart_series(c, "one-point line", CHART_STEP);
    chart_point(c, one, 1.5, 2);
    int nan = chart_series(c, "only NaN", CHART_POINTS);
    chart_point(c, nan, NAN, 1);
    int r = chart_series(c, "rings", CHART_POINTS | CHART_HOLLOW);
    chart_point(c, r, 2, 3);
    chart_series_look(c, r, "#123456", 0, -1);
    chart_legend_key(c, "colour: terms", NULL, -1, 0);
    chart_legend_key(c, "terms=5", "#abcdef", 2, CHART_POINTS);
    if (!write_ok(c, tpath("legend.svg"))) { chart_free(c); return; }
    chart_free(c);
    size_t len;
    char *svg = slurp(tpath("legend.svg"), &len);
    if (!svg) { TST_CHECK(0, "read legend.svg"); return; }
    TST_CHECK(strstr(svg, ">drawn points<") != NULL, "a drawn series is listed");
    TST_CHECK(strstr(svg, ">empty series<") == NULL, "an empty series is listed");
    TST_CHECK(strstr(svg, ">one-point line<") == NULL, "a line that draws nothing is listed");
    TST_CHECK(strstr(svg, ">only NaN<") == NULL, "a series of skipped points is listed");
    TST_CHECK(strstr(svg, ">rings<") != NULL && strstr(svg, "fill=\"none\" stroke=\"#123456\"") != NULL,
              "hollow markers in their own colour");
    TST_CHECK(strstr(svg, ">colour: terms<") != NULL && strstr(svg, ">terms=5<") != NULL, "keys are listed");
    TST_CHECK(strstr(svg, "fill=\"#abcdef\"") != NULL, "a key's colour");
    TST_CHECK(strstr(svg, "more<") == NULL, "no '+N more'");
    free(svg);
}

static int is_125(double step)
{
    double e = floor(log10(step));
    double m = step / pow(10, e);
    return fabs(m - 1) < 1e-9 || fabs(m - 2) < 1e-9 || fabs(m - 5) < 1e-9 || fabs(m - 10) < 1e-9;
}

/* Large linear values with an SI prefix, as the tables write throughput:
 * items per second from 8e7 to 1.15e8 are "100 M", not "1x10^8" or
 * "0.3x10^8"; 1e16 (past T) keeps the mantissa times 10^E; below 1e6
 * plain numbers. */
static void test_svg_si_labels(void)
{
    static const struct { double lo, hi; const char *want, *not; } cases[] = {
        { 8e7, 1.15e8, ">100 M</text>", "\xC3\x97" "10<tspan" },
        { 0, 3e7, ">30 M</text>", "\xC3\x97" "10<tspan" },
        { 1e9, 4e9, " G</text>", " M</text>" },
        { 1e5, 4e5, ">200000</text>", " M</text>" },
        { 1e16, 4e16, "\xC3\x97" "10<tspan", " T</text>" },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        chart *c = chart_new("si", "x", "items / s");
        int s = chart_series(c, "s", CHART_POINTS);
        chart_point(c, s, 1, cases[k].lo);
        chart_point(c, s, 2, cases[k].hi);
        if (!write_ok(c, tpath("si.svg"))) { chart_free(c); return; }
        chart_free(c);
        char *f = slurp(tpath("si.svg"), NULL);
        TST_CHECK(f && strstr(f, cases[k].want), "[%g, %g]: no %s", cases[k].lo, cases[k].hi, cases[k].want);
        TST_CHECK(f && !strstr(f, cases[k].not), "[%g, %g]: has %s", cases[k].lo, cases[k].hi, cases[k].not);
        free(f);
    }
}

static void test_ticks_linear(void)
{
    static const double ranges[][2] = {
        { 0, 1 }, { 0, 0.3 }, { -3.7, 12.1 }, { 1e-6, 3e-6 }, { 5, 5 }, { 0, 0 }, { -1e9, 1e9 },
        { 0.1, 0.7 }, { 12, 16 }, { 1e5, 1.2e5 }, { -0.5, -0.1 }, { 8, 24 }, { 0, 360 },
        { 0.123456, 0.123457 }, { -2, 2 }, { 999, 1001 }, { 3, 1 }, { -5e-324, 5e-324 },
        { 1, 1 + 1e-15 }, { -1e308, 1.2e308 }, { 1e300, 1.5e300 },
    };
    double t[32], lo, hi;
    rng_state = 42;
    for (size_t k = 0; k < sizeof ranges / sizeof ranges[0] + 500; k++) {
        double a, b;
        if (k < sizeof ranges / sizeof ranges[0]) { a = ranges[k][0]; b = ranges[k][1]; }
        else {
            double sc = pow(10, urand() * 20 - 10);
            a = (urand() - 0.5) * sc;
            b = a + urand() * sc * (urand() < 0.5 ? 1 : 0.001);
        }
        double dmin = fmin(a, b), dmax = fmax(a, b);
        size_t n = chart_ticks(a, b, 0, t, 32, &lo, &hi);
        TST_CHECK(n >= 2 && n <= 9, "[%g, %g]: %zu ticks", a, b, n);
        if (n < 2 || n > 32) continue;
        double step = t[1] - t[0];
        TST_CHECK(step > 0 && is_125(step), "[%g, %g]: step %g is not 1/2/5 x 10^k", a, b, step);
        for (size_t i = 1; i < n; i++)
            TST_CHECK(fabs(t[i] - t[i - 1] - step) <= 1e-9 * step * (1 + fabs(t[i]) / step * 1e-6),
                      "[%g, %g]: uneven ticks", a, b);
        for (size_t i = 0; i < n; i++)
            TST_CHECK(fabs(t[i] / step - nearbyint(t[i] / step)) < 1e-6 * fmax(1, fabs(t[i] / step)),
                      "[%g, %g]: tick %g not a multiple of the step", a, b, t[i]);
        TST_CHECK(t[0] <= dmin + 1e-9 * step && t[n - 1] >= dmax - 1e-9 * step,
                  "[%g, %g]: ticks %g..%g do not cover", a, b, t[0], t[n - 1]);
        TST_CHECK(lo == t[0] && hi == t[n - 1], "limits are the end ticks");
    }
    /* the readable choices for common ranges */
    TST_EQ_INT(chart_ticks(0, 1, 0, t, 32, &lo, &hi), 6);
    TST_NEAR(t[1], 0.2, 1e-12);
    TST_EQ_INT(chart_ticks(8, 24, 0, t, 32, &lo, &hi), 9);
    TST_NEAR(t[0], 8, 0);
    TST_NEAR(t[1], 10, 0);
    TST_EQ_INT(chart_ticks(0, 0.3, 0, t, 32, &lo, &hi), 7);   /* 0.05 steps, no extra for 0.3 */
    TST_NEAR(hi, 0.3, 1e-12);
    TST_EQ_INT(chart_ticks(NAN, 1, 0, t, 32, &lo, &hi), 0);
    TST_EQ_INT(chart_ticks(0, INFINITY, 0, t, 32, &lo, &hi), 0);
}

static void test_ticks_log(void)
{
    static const double ranges[][2] = {
        { 1e-7, 3e-2 }, { 1, 1 }, { 3, 7 }, { 1e-30, 1 }, { 0.001, 1000 }, { 1e-300, 1e300 },
        { 2.5e-5, 2.5e-5 }, { 1, 10 }, { 0.999, 1.001 }, { 123, 98765 },
    };
    double t[32], lo, hi;
    rng_state = 7;
    for (size_t k = 0; k < sizeof ranges / sizeof ranges[0] + 500; k++) {
        double a, b;
        if (k < sizeof ranges / sizeof ranges[0]) { a = ranges[k][0]; b = ranges[k][1]; }
        else { a = pow(10, urand() * 40 - 20); b = a * pow(10, urand() * urand() * 30); }
        size_t n = chart_ticks(a, b, 1, t, 32, &lo, &hi);
        TST_CHECK(n >= 1 && n <= 9, "[%g, %g]: %zu ticks", a, b, n);
        if (n < 1 || n > 32) continue;
        double dec = n > 1 ? log10(t[1]) - log10(t[0]) : 1;
        TST_CHECK(dec >= 1 - 1e-9 && fabs(dec - nearbyint(dec)) < 1e-6, "[%g, %g]: %g decades apart", a, b, dec);
        for (size_t i = 0; i < n; i++) {
            double e = log10(t[i]);
            TST_CHECK(t[i] == 0 || fabs(e - nearbyint(e)) < 1e-9, "[%g, %g]: tick %g not a decade", a, b, t[i]);
            if (i) TST_CHECK(t[i] == 0 || fabs(log10(t[i]) - log10(t[i - 1]) - dec) < 1e-6, "uneven decades");
        }
        /* the limits cover the data, hold the ticks, are 1, 2 or 5 x 10^k,
         * and leave less than half a decade empty at either end (one with
         * every other decade or more labelled, or where the data hold no
         * whole decade, as [3, 7]) */
        TST_CHECK(lo <= a && hi >= b, "[%g, %g]: limits %g..%g do not cover", a, b, lo, hi);
        TST_CHECK(lo <= t[0] * (1 + 1e-12) && hi >= t[n - 1] * (1 - 1e-12), "[%g, %g]: ticks outside the limits", a, b);
        for (int end = 0; end < 2; end++) {
            double v = end ? hi : lo, m = v / pow(10, floor(log10(v) + 1e-12));
            TST_CHECK(fabs(m - 1) < 1e-9 || fabs(m - 2) < 1e-9 || fabs(m - 5) < 1e-9 || fabs(m - 10) < 1e-9,
                      "[%g, %g]: limit %g not 1, 2 or 5 x 10^k", a, b, v);
        }
        int tight = dec == 1 && floor(log10(b) + 1e-12) - ceil(log10(a) - 1e-12) >= 1;
        double gap = tight ? 0.41 : 1.0 * dec;
        if (lo > 0 && isfinite(hi) && a > 1e-290 && b < 1e290)
            TST_CHECK(log10(a / lo) < gap && log10(hi / b) < gap, "[%g, %g]: limits %g..%g: more than %g decade empty",
                      a, b, lo, hi, gap);
    }
    TST_EQ_INT(chart_ticks(1e-7, 3e-2, 1, t, 32, &lo, &hi), 6);   /* every decade */
    TST_NEAR(lo, 1e-7, 1e-20);
    TST_NEAR(hi, 5e-2, 1e-15);                                    /* not 1e-1 */
    TST_EQ_INT(chart_ticks(4, 32, 1, t, 32, &lo, &hi), 1);         /* stability_fwd's L: 2..50 */
    TST_NEAR(lo, 2, 1e-15);
    TST_NEAR(hi, 50, 1e-13);
    TST_EQ_INT(chart_ticks(3, 7, 1, t, 32, &lo, &hi), 1);          /* 2..10: 10^1 and 2, 3, 5 x 10^0 */
    TST_NEAR(lo, 2, 1e-15);
    TST_NEAR(hi, 10, 1e-15);
    TST_EQ_INT(chart_ticks(2.1, 4.9, 1, t, 32, &lo, &hi), 2);      /* no decade in 2..5: 1..10 */
    TST_NEAR(lo, 1, 1e-15);
    TST_NEAR(hi, 10, 1e-15);
    TST_EQ_INT(chart_ticks(0, 1, 1, t, 32, &lo, &hi), 0);
    TST_EQ_INT(chart_ticks(-1, 1, 1, t, 32, &lo, &hi), 0);
}

static void test_svg_well_formed(void)
{
    write_samples();
    for (size_t i = 0; i < NSAMPLES; i++) check_file(tpath(samples[i].name));
    check_file(tpath("empty.svg"));
    /* the checker itself catches what it is meant to */
    char why[100];
    TST_CHECK(xml_check("<a><b></a></b>", why, sizeof why), "crossed tags");
    TST_CHECK(xml_check("<a x=1/>", why, sizeof why), "unquoted attribute");
    TST_CHECK(xml_check("<a>&foo;</a>", why, sizeof why), "bad entity");
    TST_CHECK(xml_check("<a>x & y</a>", why, sizeof why), "raw &");
    TST_CHECK(xml_check("<a x='<'/>", why, sizeof why), "raw < in value");
    TST_CHECK(xml_check("<a x='1' x='2'/>", why, sizeof why), "duplicate attribute");
    TST_CHECK(!xml_check("<?xml version=\"1.0\"?>\n<a x='&amp;&#38;&#x26;'>t&lt;<b/></a>\n", why, sizeof why),
              "valid: %s", why);
}

static void test_svg_xmllint(void)
{
    if (!have_tool("xmllint")) TST_SKIP("xmllint not installed");
    write_samples();
    const char *extra[] = { "empty.svg" };
    for (size_t i = 0; i <= NSAMPLES; i++) {
        const char *f = tpath(i < NSAMPLES ? samples[i].name : extra[0]);
        char cmd[1024];
        snprintf(cmd, sizeof cmd, "xmllint --noout '%s' 2>&1", f);
        FILE *p = popen(cmd, "r");
        TST_CHECK(p != NULL, "popen");
        if (!p) return;
        char out[512];
        size_t n = fread(out, 1, sizeof out - 1, p);
        out[n] = 0;
        int rc = pclose(p);
        TST_CHECK(rc == 0 && n == 0, "xmllint %s: %s", f, out);
    }
}

static void test_svg_rsvg(void)
{
    if (!have_tool("rsvg-convert")) TST_SKIP("rsvg-convert not installed");
    write_samples();
    /* a tenth of a second of CPU each: every fourth in make test-quick */
    for (size_t i = 0; i <= NSAMPLES; i += tst_quick() ? 4 : 1) {
        const char *name = i < NSAMPLES ? samples[i].name : "empty.svg";
        char png[700], cmd[2048];
        snprintf(png, sizeof png, "%s", tpath(name));
        strcpy(png + strlen(png) - 4, ".png");
        snprintf(cmd, sizeof cmd, "rsvg-convert -o '%s' '%s' 2>&1", png, tpath(name));
        TST_CHECK(system(cmd) == 0, "%s", cmd);
        size_t len = 0;
        char *b = slurp(png, &len);
        TST_CHECK(b && len > 1000 && !memcmp(b, "\x89PNG\r\n\x1a\n", 8), "%s: no PNG (%zu bytes)", png, len);
        free(b);
    }
}

static void test_svg_escaping(void)
{
    const char *nasty = "a & b < c > d \"e\" 'f' <script>";
    chart *c = chart_new(nasty, "x & y", "<y>");
    int s = chart_series(c, "</text>&amp;", CHART_POINTS);
    chart_point_label(c, s, 1, 1, "w<12>&\"'");
    chart_point(c, s, 2, 3);
    chart_hband(c, 1.2, 1.5, "band & <x>");
    chart_hline(c, 2, "line 'q' \"q\"");
    /* control characters and broken UTF-8 must not break the XML either */
    int s2 = chart_series(c, "bad \x01\x1f utf8 \xff\xc3( caf\xc3\xa9", CHART_LINE);
    chart_point(c, s2, 1, 2);
    chart_point(c, s2, 2, 2.5);
    if (!write_ok(c, tpath("esc.svg"))) { chart_free(c); return; }
    chart_free(c);
    check_file(tpath("esc.svg"));
    char *f = slurp(tpath("esc.svg"), NULL);
    TST_CHECK(f != NULL, "read");
    if (!f) return;
    TST_CHECK(strstr(f, "a &amp; b &lt; c &gt; d &quot;e&quot; &apos;f&apos; &lt;script&gt;"), "title escaped");
    TST_CHECK(!strstr(f, "<script") && !strstr(f, "<y>") && !strstr(f, "'f'"), "raw text leaked");
    TST_CHECK(strstr(f, "&lt;/text&gt;&amp;amp;"), "legend escaped");
    TST_CHECK(strstr(f, "w&lt;12&gt;&amp;&quot;&apos;"), "point label escaped");
    TST_CHECK(strstr(f, "band &amp; &lt;x&gt;"), "band label escaped");
    TST_CHECK(strstr(f, "caf\xc3\xa9"), "valid UTF-8 kept");
    free(f);
}

static void test_svg_log_skips(void)
{
    chart *c = chart_new("log", "x", "y");
    chart_log_y(c, 1);
    int s = chart_series(c, "s", CHART_LINE | CHART_POINTS);
    for (int i = 1; i <= 5; i++) chart_point(c, s, i, pow(10, -i));
    chart_point(c, s, 6, 0);
    chart_point(c, s, 7, -1);
    chart_point_label(c, s, 8, -2, "gone");
    chart_point(c, s, NAN, 1);
    chart_point(c, s, 9, INFINITY);
    chart_hline(c, 0, "zero");
    if (!write_ok(c, tpath("log.svg"))) { chart_free(c); return; }
    chart_free(c);
    check_file(tpath("log.svg"));
    char *f = slurp(tpath("log.svg"), NULL);
    if (!f) { TST_CHECK(0, "read"); return; }
    TST_CHECK(strstr(f, "3 points &lt;= 0 not shown"), "footnote for <= 0");
    TST_CHECK(strstr(f, "2 points NaN/inf not shown"), "footnote for NaN/inf");
    TST_CHECK(strstr(f, "1 line at y &lt;= 0 not shown"), "footnote for the line");
    TST_CHECK(!strstr(f, "gone") && !strstr(f, "no data"), "skipped point's label");
    TST_CHECK(strstr(f, "10<tspan"), "decade labels 10^k");
    free(f);

    /* log x too, and one point on it is enough to count in the singular */
    c = chart_new("logx", "x", "y");
    chart_log_x(c, 1);
    s = chart_series(c, "s", CHART_POINTS);
    chart_point(c, s, 1, 1);
    chart_point(c, s, 100, 2);
    chart_point(c, s, -5, 2);
    write_ok(c, tpath("logx.svg"));
    chart_free(c);
    f = slurp(tpath("logx.svg"), NULL);
    TST_CHECK(f && strstr(f, "1 point &lt;= 0 not shown"), "singular footnote");
    /* two decades: 2 and 5 x 10^k are labelled too, else only 3 numbers */
    TST_CHECK(f && strstr(f, ">5\xC3\x97" "10<tspan"), "minor labels on a short log axis");
    TST_CHECK(f && !strstr(f, ">3\xC3\x97" "10<tspan"), "3 x 10^k only on a single decade");
    free(f);
}

static void test_svg_empty(void)
{
    chart *c = chart_new(NULL, NULL, NULL);
    write_ok(c, tpath("e1.svg"));
    chart_free(c);
    c = chart_new("only bad points", "x", "y");
    chart_log_x(c, 1);
    int s = chart_series(c, "s", CHART_LINE);
    chart_point(c, s, 0, 1);
    chart_point(c, s, NAN, NAN);
    chart_hline(c, 3, "t");
    chart_hband(c, 1, 2, "b");
    write_ok(c, tpath("e2.svg"));
    chart_free(c);
    const char *names[] = { "e1.svg", "e2.svg" };
    for (int i = 0; i < 2; i++) {
        check_file(tpath(names[i]));
        char *f = slurp(tpath(names[i]), NULL);
        TST_CHECK(f && strstr(f, ">no data<"), "%s says no data", names[i]);
        TST_CHECK(f && strstr(f, "</svg>\n"), "%s complete", names[i]);
        if (i == 1) TST_CHECK(f && strstr(f, "1 point &lt;= 0") && strstr(f, "1 point NaN/inf"), "footnote");
        free(f);
    }
}

/* Ranges at the ends of double, single points, many points: the file is
 * still complete and well-formed. */
static void test_svg_extremes(void)
{
    static const double pts[][4] = {   /* x0 y0 x1 y1 */
        { -1e300, 1e300, 1e300, -1e300 }, { 1, 1, 1, 1 }, { 0, 0, 0, 0 },
        { 1, 1 + 1e-15, 2, 1 }, { -DBL_MAX, DBL_MAX, DBL_MAX, -DBL_MAX },
        { 5e-324, 1.7e308, 1e308, 5e-324 }, { 1e-7, 1e-7, 1e-7, 1e-7 },
        { -5e-324, 5e-324, 5e-324, -5e-324 }, { 1e-310, 1, 2e-310, 1 },
    };
    for (size_t k = 0; k < sizeof pts / sizeof pts[0]; k++)
        for (int lg = 0; lg < 4; lg++) {
            chart *c = chart_new("extreme", "x", "y");
            chart_log_x(c, lg & 1);
            chart_log_y(c, lg & 2);
            int s = chart_series(c, "s", CHART_LINE | CHART_POINTS);
            chart_point_label(c, s, pts[k][0], pts[k][1], "a");
            chart_point_label(c, s, pts[k][2], pts[k][3], "b");
            chart_hband(c, -INFINITY, INFINITY, "all");
            char name[32];
            snprintf(name, sizeof name, "x%zu_%d.svg", k, lg);
            if (write_ok(c, tpath(name))) check_file(tpath(name));
            chart_free(c);
        }
    /* many points and labels: growth, and the label placement stays sane */
    chart *c = chart_new("many", "x", "y");
    int s = chart_series(c, "s", CHART_POINTS);
    rng_state = 99;
    for (int i = 0; i < 20000; i++) {
        double x = urand(), y = urand();   /* in this order on any compiler */
        if (i % 100) chart_point(c, s, x, y);
        else chart_point_label(c, s, x, y, "label");
    }
    if (write_ok(c, tpath("many.svg"))) check_file(tpath("many.svg"));
    chart_free(c);
}

static void test_svg_deterministic(void)
{
    for (size_t i = 0; i < NSAMPLES; i++) {
        chart *a = samples[i].fn(), *b = samples[i].fn();
        write_ok(a, tpath("d1.svg"));
        write_ok(b, tpath("d2.svg"));
        write_ok(a, tpath("d3.svg"));       /* writing does not change the chart */
        chart_free(a);
        chart_free(b);
        size_t n1, n2, n3;
        char *f1 = slurp(tpath("d1.svg"), &n1), *f2 = slurp(tpath("d2.svg"), &n2),
             *f3 = slurp(tpath("d3.svg"), &n3);
        TST_CHECK(f1 && f2 && f3 && n1 == n2 && n1 == n3 && !memcmp(f1, f2, n1) && !memcmp(f1, f3, n1),
                  "%s: identical input, different bytes", samples[i].name);
        free(f1); free(f2); free(f3);
    }
}

static void test_svg_write_errors(void)
{
    char before[2048], after[2048], err[256];
    chart *c = sample_angle();

    /* a directory that does not exist */
    dir_list(tdir, before, sizeof before);
    strcpy(err, "x");
    TST_EQ_INT(chart_write(c, tpath("no/such/dir/x.svg"), err, sizeof err), -1);
    TST_CHECK(err[0] && !strchr(err, '\n') && strstr(err, "no/such/dir/x.svg"), "message: %s", err);
    dir_list(tdir, after, sizeof after);
    TST_EQ_STR(after, before);

    /* the rename fails (the target is a directory): the temp file must go */
    mkdir(tpath("isdir"), 0755);
    dir_list(tdir, before, sizeof before);
    TST_EQ_INT(chart_write(c, tpath("isdir"), err, sizeof err), -1);
    TST_CHECK(err[0] && !strchr(err, '\n'), "message: %s", err);
    dir_list(tdir, after, sizeof after);
    TST_EQ_STR(after, before);

    /* a path with a newline still gives a one-line message; NULL err is fine */
    TST_EQ_INT(chart_write(c, tpath("no\nsuch/x.svg"), err, sizeof err), -1);
    TST_CHECK(!strchr(err, '\n'), "message: %s", err);
    TST_EQ_INT(chart_write(c, tpath("no/such/x.svg"), NULL, 0), -1);

    /* replacing an existing chart works and leaves only the chart */
    TST_EQ_INT(chart_write(c, tpath("ok.svg"), err, sizeof err), 0);
    TST_EQ_INT(chart_write(c, tpath("ok.svg"), err, sizeof err), 0);
    dir_list(tdir, after, sizeof after);
    TST_CHECK(!strstr(after, ".tmp"), "temp file left: %s", after);
    chart_free(c);

    /* building errors are reported by write */
    c = chart_new("t", "x", "y");
    chart_point(c, 3, 1, 1);
    TST_EQ_INT(chart_write(c, tpath("bad.svg"), err, sizeof err), -1);
    TST_CHECK(strstr(err, "series 3") != NULL, "message: %s", err);
    TST_CHECK(access(tpath("bad.svg"), F_OK) != 0, "no file for a bad chart");
    chart_free(c);
    TST_EQ_INT(chart_write(NULL, tpath("n.svg"), err, sizeof err), -1);
}

/* ---- readability: equal series, labels off the grid, legend, log axes -- */

/* Write c to name and read it back (NULL on failure). */
static char *write_read(chart *c, const char *name)
{
    if (!c || !write_ok(c, tpath(name))) { chart_free(c); return NULL; }
    chart_free(c);
    size_t len;
    return slurp(tpath(name), &len);
}

/* The marker centres drawn in colour col: the path after fill="col" holds
 * one circle per marker, "M x-r y a r r ...", r read from the arc. */
static int marker_centres(const char *svg, const char *col, double (*xy)[2], int cap)
{
    char key[64];
    snprintf(key, sizeof key, "<path fill=\"%s\" stroke=\"#fff\"", col);
    const char *p = strstr(svg, key);
    if (!p || !(p = strstr(p, " d=\""))) return 0;
    p += 4;
    int n = 0;
    while (*p && *p != '"') {
        if (*p == 'M') {
            double x, y, r;
            if (sscanf(p + 1, "%lf %lfa%lf", &x, &y, &r) == 3 && n < cap) { xy[n][0] = x + r; xy[n][1] = y; n++; }
        }
        p++;
    }
    return n;
}

/* Series of equal values: wrap and sat with the same points, a third that
 * meets them at one width. No two markers of different series at the same
 * spot; the moved ones stay within 16 pixels of each other (the frame's
 * padding), at the same height;
 * the footnote says so and the legend names the twin. */
static void test_svg_equal_series(void)
{
    chart *c = chart_new("Equal series", "width (bits)", "max |e|");
    chart_log_y(c, 1);
    chart_int_x(c, 1);
    static const char *col[3] = { "#111111", "#222222", "#333333" };
    const char *name[3] = { "wrap", "sat", "other" };
    int s[3];
    for (int k = 0; k < 3; k++) {
        s[k] = chart_series(c, name[k], CHART_LINE | CHART_POINTS);
        chart_series_look(c, s[k], col[k], 0, 0);
    }
    for (int w = 8; w <= 16; w++) {
        double e = ldexp(3.0, -w);
        chart_point(c, s[0], w, e);
        chart_point(c, s[1], w, e);
        chart_point(c, s[2], w, w == 12 ? e : 2 * e);
    }
    char *svg = write_read(c, "equal.svg");
    TST_CHECK(svg != NULL, "equal.svg");
    if (!svg) return;
    double m[3][16][2];
    int n[3];
    for (int k = 0; k < 3; k++) n[k] = marker_centres(svg, col[k], m[k], 16);
    TST_CHECK(n[0] == 9 && n[1] == 9 && n[2] == 9, "markers %d %d %d", n[0], n[1], n[2]);
    int same = 0, far = 0;
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++)
            for (int i = 0; i < n[a]; i++)
                for (int j = 0; j < n[b]; j++) {
                    if (fabs(m[a][i][0] - m[b][j][0]) < 0.5 && fabs(m[a][i][1] - m[b][j][1]) < 0.5) same++;
                    /* the twin of point i: at the same height, a few pixels aside */
                    if (i == j && fabs(m[a][i][1] - m[b][j][1]) < 0.01 && fabs(m[a][i][0] - m[b][j][0]) > 16.01) far++;
                }
    TST_EQ_INT(same, 0);
    TST_EQ_INT(far, 0);
    /* 9 + 9 wrap/sat points, and the third series' point at width 12 */
    TST_CHECK(strstr(svg, ">19 points of equal value in two series or more set side by side<") != NULL,
              "no footnote for the moved points");
    TST_CHECK(strstr(svg, ">sat (= wrap)<") != NULL && strstr(svg, ">wrap<") && strstr(svg, ">other<"),
              "the legend does not name sat's twin");
    free(svg);
    /* Rings and staircases mark other points on purpose: not moved. */
    c = chart_new("Front", "e", "area");
    int p = chart_series(c, "points", CHART_POINTS);
    chart_series_look(c, p, col[0], 0, 0);
    int r = chart_series(c, "front", CHART_POINTS | CHART_HOLLOW);
    for (int i = 1; i <= 5; i++) { chart_point(c, p, i, 10 - i); chart_point(c, r, i, 10 - i); }
    svg = write_read(c, "rings.svg");
    TST_CHECK(svg && !strstr(svg, "side by side"), "rings moved");
    TST_CHECK(svg && strstr(svg, ">front<") && !strstr(svg, "(= "), "rings called a twin");
    free(svg);
}

/* The grid lines of an SVG (chart_draw_grid's path): x of the vertical,
 * y of the horizontal ones. */
static void grid_lines(const char *svg, double *gx, int *ngx, double *gy, int *ngy)
{
    *ngx = *ngy = 0;
    const char *p = strstr(svg, "stroke=\"#e3e3e3\"");
    if (!p || !(p = strstr(p, " d=\""))) return;
    for (p += 4; *p && *p != '"'; p++) {
        double x, y, z;
        char k;
        if (*p == 'M' && sscanf(p + 1, "%lf %lf%c%lf", &x, &y, &k, &z) == 4) {
            if (k == 'V' && *ngx < 64) gx[(*ngx)++] = x;
            if (k == 'H' && *ngy < 64) gy[(*ngy)++] = y;
        }
    }
}

/* A staircase front with a label per point on a log x axis, as the
 * sweep's area chart draws it. */
static chart *sample_front_labels(void)
{
    chart *c = chart_new("horner3: area against max error", "max |e|", "area (GE)");
    chart_log_x(c, 1);
    int a = chart_series(c, "trunc", CHART_POINTS), b = chart_series(c, "half-up", CHART_POINTS);
    int f = chart_series(c, "Pareto front", CHART_POINTS | CHART_HOLLOW);
    for (int w = 8; w <= 24; w++) {
        double e = 3.5 * ldexp(1.0, -w + 1), area = 8.0 * w * w + 150 * w;
        chart_point(c, a, e * 1.9, area * 1.05);
        chart_point(c, b, e, area);
        char lab[32];
        snprintf(lab, sizeof lab, "width %d", w);
        chart_point_label(c, f, e, area, lab);
    }
    return c;
}

/* Point labels (10 px, #333, no anchor) do not cross a grid line: boxes
 * by tst_svgtext.h's reading of the file. */
static void test_svg_labels_off_grid(void)
{
    const struct { const char *name; sample_fn fn; } ch[] = {
        { "front_labels.svg", sample_front_labels }, { "area_pareto2.svg", sample_area_pareto } };
    for (size_t k = 0; k < sizeof ch / sizeof ch[0]; k++) {
        char *svg = write_read(ch[k].fn(), ch[k].name);
        TST_CHECK(svg != NULL, "%s", ch[k].name);
        if (!svg) continue;
        double gx[64], gy[64];
        int ngx, ngy, nlab = 0, bad = 0;
        grid_lines(svg, gx, &ngx, gy, &ngy);
        TST_CHECK(ngx >= 3 && ngy >= 3, "%s: %d and %d grid lines", ch[k].name, ngx, ngy);
        const char *root = "<svg font-size=\"11\">";
        for (const char *p = strstr(svg, "<text"); p; p = strstr(p + 1, "<text")) {
            const char *e = strstr(p, "</text>");
            if (!e) break;
            const char *gt = strchr(p, '>');
            const char *fs = strstr(p, "font-size=\"10\" fill=\"#333\""), *ta = strstr(p, "text-anchor");
            if (!fs || fs > gt || (ta && ta < gt)) continue;
            char one[400];
            snprintf(one, sizeof one, "%s%.*s</svg>", root, (int)(e + 7 - p), p);
            tst_tbox b;
            if (tst_svg_text_boxes(one, &b, 1) != 1) continue;
            nlab++;
            for (int i = 0; i < ngx; i++)
                if (gx[i] > b.x0 && gx[i] < b.x1) { bad++; TST_CHECK(0, "%s: '%s' on x = %g", ch[k].name, b.text, gx[i]); }
            for (int i = 0; i < ngy; i++)
                if (gy[i] > b.y0 && gy[i] < b.y1) { bad++; TST_CHECK(0, "%s: '%s' on y = %g", ch[k].name, b.text, gy[i]); }
        }
        TST_CHECK(nlab >= 5, "%s: %d point labels", ch[k].name, nlab);
        TST_EQ_INT(bad, 0);
        free(svg);
    }
}

/* Legend texts stay inside the picture and whole: a long label wraps
 * onto more lines instead of losing its end (stability_fwd's model line
 * "8 + log2(sum C(L,j)), cubic" lost "ic"). */
static void test_svg_legend_whole(void)
{
    chart *c = chart_new("Forward differencing", "interval length L (pixels)", "fraction bits");
    chart_log_x(c, 1);
    const char *lab[3] = { "interp3 fwd (measured)", "8 + log2(sum C(L,j)), cubic",
                           "a very long series label that will not fit the legend box" };
    for (int k = 0; k < 3; k++) {
        int s = chart_series(c, lab[k], CHART_LINE | CHART_POINTS);
        for (int L = 4; L <= 32; L *= 2) chart_point(c, s, L, 10 + k + log2(L) * (1 + k));
    }
    char *svg = write_read(c, "legend_whole.svg");
    TST_CHECK(svg != NULL, "legend_whole.svg");
    if (!svg) return;
    /* the legend box: <rect x=".." ... stroke="#ccc"; its texts lie right of it */
    const char *leg = strstr(svg, "stroke=\"#ccc\""), *r = leg;
    while (r && r > svg && strncmp(r, "<rect", 5)) r--;
    double lx = r ? atof(strstr(r, "x=\"") + 3) : 1e9;
    TST_CHECK(leg != NULL && lx > 400 && lx < 800, "no legend box");
    tst_tbox b[200];
    int n = tst_svg_text_boxes(svg, b, 200);
    char all[600] = "";
    for (int i = 0; i < n && i < 200; i++) {
        if (b[i].x0 <= lx || b[i].y0 < 40) continue;          /* not a legend text */
        TST_CHECK(b[i].x1 <= 800 && b[i].x0 >= 0, "'%s' ends at x = %.1f of 800", b[i].text, b[i].x1);
        TST_CHECK(!strstr(b[i].text, "\xE2\x80\xA6"), "'%s' cut", b[i].text);
        if (strlen(all) + strlen(b[i].text) + 2 < sizeof all) { if (*all) strcat(all, " "); strcat(all, b[i].text); }
    }
    for (int k = 0; k < 3; k++) TST_CHECK(strstr(all, lab[k]) != NULL, "'%s' not whole in: %s", lab[k], all);
    free(svg);
}

/* A log axis fits the data: L from 4 to 32 gets 2..50 (labels 2x10^0,
 * 5x10^0, 10^1, 2x10^1, 5x10^1), not 10^0..10^2 with half of it empty; the
 * pixels of the ticks put 4 and 32 within the labelled range. */
static void test_svg_log_fit(void)
{
    chart *c = chart_new("L", "L (pixels)", "bits");
    chart_log_x(c, 1);
    int s = chart_series(c, "fwd", CHART_LINE | CHART_POINTS);
    for (int L = 4; L <= 32; L *= 2) chart_point(c, s, L, log2(L));
    char *svg = write_read(c, "logfit.svg");
    TST_CHECK(svg != NULL, "logfit.svg");
    if (!svg) return;
    /* decade labels are "10<tspan ...>k</tspan>", the others "m×10<tspan>k" */
    TST_CHECK(!strstr(svg, "\">10<tspan dy=\"-5\" font-size=\"8.25\">0<") &&
              !strstr(svg, "\">10<tspan dy=\"-5\" font-size=\"8.25\">2<"), "a decade with no data labelled");
    TST_CHECK(strstr(svg, ">2\xC3\x97" "10<tspan dy=\"-5\" font-size=\"8.25\">0<") &&
              strstr(svg, ">5\xC3\x97" "10<tspan dy=\"-5\" font-size=\"8.25\">1<") &&
              strstr(svg, "\">10<tspan dy=\"-5\" font-size=\"8.25\">1<"), "labels 2x10^0 .. 5x10^1 missing");
    free(svg);
    /* every log axis stays within half a decade of its data at each end,
     * over many ranges (chart_ticks gives the limits the charts use) */
    rng_state = 99;
    for (int k = 0; k < 2000; k++) {
        double a = pow(10, urand() * 20 - 10), b = a * pow(10, 0.5 + urand() * 7), lo, hi, t[16];
        size_t nt = chart_ticks(a, b, 1, t, 16, &lo, &hi);
        TST_CHECK(nt >= 1 && lo <= a && hi >= b && log10(a / lo) < 1 && log10(hi / b) < 1,
                  "[%g, %g]: axis %g..%g", a, b, lo, hi);
        if (nt && t[1] / t[0] < 11)
            TST_CHECK(log10(a / lo) < 0.41 && log10(hi / b) < 0.41, "[%g, %g]: axis %g..%g", a, b, lo, hi);
    }
}

int main(void)
{
    const char *keep = getenv("TST_SVG_KEEP");
    if (keep && *keep) {
        snprintf(tdir, sizeof tdir, "%s", keep);
        mkdir(tdir, 0755);
    } else {
        const char *t = getenv("TMPDIR");
        snprintf(tdir, sizeof tdir, "%s/test_svg.XXXXXX", t && *t ? t : "/tmp");
        if (!mkdtemp(tdir)) { printf("FAIL test_svg: mkdtemp: %s\n", strerror(errno)); return 1; }
    }
    TST_RUN(test_pareto_vs_bruteforce);
    TST_RUN(test_pareto3_vs_bruteforce);
    TST_RUN(test_svg_no_text_overlap);
    TST_RUN(test_svg_legend_drawn_only);
    TST_RUN(test_ticks_linear);
    TST_RUN(test_svg_si_labels);
    TST_RUN(test_ticks_log);
    TST_RUN(test_svg_well_formed);
    TST_RUN(test_svg_xmllint);
    TST_RUN(test_svg_rsvg);
    TST_RUN(test_svg_escaping);
    TST_RUN(test_svg_log_skips);
    TST_RUN(test_svg_empty);
    TST_RUN(test_svg_extremes);
    TST_RUN(test_svg_deterministic);
    TST_RUN(test_svg_write_errors);
    TST_RUN(test_svg_equal_series);
    TST_RUN(test_svg_labels_off_grid);
    TST_RUN(test_svg_legend_whole);
    TST_RUN(test_svg_log_fit);
    if (!(keep && *keep)) { tst_rmtree(tdir); rmdir(tdir); }
    TST_EXIT();
}
