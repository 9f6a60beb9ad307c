/* chart_axis.c - axes: where the ticks go (1-2-5 steps on linear axes,
 * decades on log axes), their labels, and data to pixels. */
#include "chart/chart_int.h"
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static double chart_pow10(int e) { return pow(10.0, (double)e); }

/* Linear ticks: the smallest 1/2/5 x 10^k step whose multiples cover the
 * data in at most maxint intervals. */
int chart_lin_fit(chart_axis *a, double dmin, double dmax, int maxint)
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

/* Log axes: the limits are the nearest 1, 2 or 5 x 10^k around the data
 * (so no axis spends most of a decade on each side with nothing in it:
 * 4..32 gets 2..50, not 1..100), the major ticks the decades inside them,
 * every s-th decade when there are more than maxint. Where those limits
 * would hold no decade at all (3..7), the axis is the decade around the
 * data. Minor ticks at 2..9 x 10^k, or, when majors skip decades, at every
 * decade (every s/5-th for strides of 10 and more). */
int chart_log_fit(chart_axis *a, double dmin, double dmax, int maxint)
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
    /* the tight limits: 10^e0 <= dmin and 10^e1 >= dmax hold here */
    double lo = e0, hi = e1, lov = chart_pow10(e0), hiv = chart_pow10(e1);
    if (5 * chart_pow10(e0) <= dmin) { lo = e0 + log10(5.0); lov = 5 * chart_pow10(e0); }
    else if (2 * chart_pow10(e0) <= dmin) { lo = e0 + log10(2.0); lov = 2 * chart_pow10(e0); }
    if (2 * chart_pow10(e1 - 1) >= dmax) { hi = e1 - 1 + log10(2.0); hiv = 2 * chart_pow10(e1 - 1); }
    else if (5 * chart_pow10(e1 - 1) >= dmax) { hi = e1 - 1 + log10(5.0); hiv = 5 * chart_pow10(e1 - 1); }
    if (ceil(lo) > floor(hi)) { lo = e0; hi = e1; lov = chart_pow10(e0); hiv = chart_pow10(e1); }
    static const int strides[] = { 1, 2, 3, 5, 10, 20, 50, 100, 200, 500 };
    int s = 1;
    for (size_t i = 0; i < sizeof strides / sizeof *strides; i++) {
        s = strides[i];
        int f0 = (int)floor((double)e0 / s), f1 = (int)ceil((double)e1 / s);
        if (f1 - f0 <= maxint) break;
    }
    /* with a stride, the limits widen to its multiples only where no
     * multiple lies inside (the axis needs two major ticks) */
    int m0 = (int)ceil(lo / s - 1e-9), m1 = (int)floor(hi / s + 1e-9);
    if (s > 1 && m1 - m0 < 1) {
        int f0 = (int)floor((double)e0 / s), f1 = (int)ceil((double)e1 / s);
        lo = f0 * s; hi = f1 * s; lov = chart_pow10(f0 * s); hiv = chart_pow10(f1 * s);
        m0 = f0; m1 = f1;
    }
    a->log = 1;
    a->step = s;
    a->lo = lo;
    a->hi = hi;
    a->lov = lov;
    a->hiv = hiv;
    a->nmaj = 0;
    a->nmin = 0;
    for (int m = m0; m <= m1 && a->nmaj < CHART_MAXMAJ; m++) a->maj[a->nmaj++] = m * s;
    int ms = s <= 5 ? 1 : s / 5;
    for (int e = (int)floor(lo); e < (int)ceil(hi); e++) {
        if (s == 1) {
            for (int m = 2; m <= 9 && a->nmin < CHART_MAXMIN; m++) {
                double t = e + log10((double)m);
                if (t >= lo - 1e-9 && t <= hi + 1e-9) a->min[a->nmin++] = t;
            }
        } else if (e % s != 0 && e % ms == 0 && e >= lo && a->nmin < CHART_MAXMIN) {
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
    if (lo) *lo = a.log ? a.lov : a.lo;
    if (hi) *hi = a.log ? a.hiv : a.hi;
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
 * needs, the same on every label; large numbers (>= 1e6, below 1e15)
 * with an SI prefix, the way the tables write throughput ("30 M", not
 * "0.3x10^8": the largest tick's thousands, so the mantissas stay whole
 * where the step allows); small ones (all below 1e-3) as a mantissa times
 * 10^E. */
void chart_labels(chart_axis *a)
{
    int sci = 0, E = 0, dec = a->k < 0 ? -a->k : 0, si = 0;
    if (!a->log) {
        double big = fmax(fabs(a->lo), fabs(a->hi));
        E = big > 0 ? (int)floor(log10(big)) : 0;
        if (E >= 6 && E < 15) { si = E / 3 * 3; dec = si - a->k; if (dec < 0) dec = 0; }
        else if (E >= 15 || E <= -4) { sci = 1; dec = E - a->k; if (dec < 0) dec = 0; }
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
        if (si) {
            static const char *const prefix[] = { " M", " G", " T" };
            size_t n = v == 0 ? chart_fixed(l->base, sizeof l->base, 0, 0, 0)
                              : chart_fixed(l->base, sizeof l->base, v / chart_pow10(si), dec, 0);
            if (v != 0) snprintf(l->base + n, sizeof l->base - n, "%s", prefix[si / 3 - 2]);
        } else if (sci && v != 0) {
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
        for (int e = (int)floor(a->lo); e < (int)ceil(a->hi); e++)
            for (size_t j = 0; j < nm && a->nmlab < CHART_MAXMLAB; j++) {
                double t = e + log10((double)m[j]);
                if (t < a->lo - 1e-9 || t > a->hi + 1e-9) continue;
                chart_lab *l = &a->mlab[a->nmlab];
                a->mlabpos[a->nmlab++] = t;
                snprintf(l->base, sizeof l->base, "%d\xC3\x97" "10", m[j]);
                snprintf(l->sup, sizeof l->sup, "%d", e);
                chart_minus(l->sup, sizeof l->sup);
            }
    }
}

static double chart_labw(const chart_lab *l, double size)
{
    return chart_textw(l->base, size, SIZE_MAX) +
           chart_textw(l->sup, size * CHART_SUPSCALE, SIZE_MAX);
}

double chart_maxlabw(const chart_axis *a, double size)
{
    double w = 0;
    for (size_t i = 0; i < a->nmaj; i++) w = fmax(w, chart_labw(&a->lab[i], size));
    for (size_t i = 0; i < a->nmlab; i++) w = fmax(w, chart_labw(&a->mlab[i], size));
    return w;
}

/* Pixel of an axis-unit position (tick positions). Halved operands keep
 * the differences finite for limits near +-DBL_MAX. */
double chart_upix(const chart_axis *a, double t)
{
    return a->p0 + (t / 2 - a->lo / 2) / (a->hi / 2 - a->lo / 2) * (a->p1 - a->p0);
}

/* Pixel of a data value (log axes take the value, not its log). */
double chart_pix(const chart_axis *a, double v)
{
    return chart_upix(a, a->log ? log10(v) : v);
}

/* Thin lines at pixel centres, so that the grid and frame are crisp. */
double chart_snap(double v) { return floor(v) + 0.5; }

/* minor: a minor tick's label, in grey so the decades still stand out */
void chart_ticklabel(chart_buf *b, const chart_lab *l, double x, double y,
                             const char *anchor, int minor)
{
    chart_f(b, "<text x=\"%f\" y=\"%f\" text-anchor=\"%s\"%s>%t", x, y, anchor,
             minor ? " fill=\"#666\"" : "", l->base);
    if (l->sup[0])
        chart_f(b, "<tspan dy=\"-5\" font-size=\"%f\">%t</tspan>",
                 CHART_FS_TICK * CHART_SUPSCALE, l->sup);
    chart_puts(b, "</text>\n");
}
