/* chart.h - shadesim's own chart writer: small, self-contained SVG.
 *
 * shadesim draws its charts itself (error vs bit width, area vs error with
 * the Pareto front, clocks/item vs error, error vs angle with the failure
 * regions shaded) so that it needs no plotting package. The files must read
 * well at a glance in a browser and in rsvg-convert, so the writer does what
 * a plotting package would: 1-2-5 ticks on linear axes, decades with minor
 * ticks on log axes, light grey grid, a legend outside the plot on the
 * right, a colour-blind-safe palette (Okabe & Ito) with a distinct marker
 * shape per series.
 *
 * The file is one fixed 800x500 viewBox, font-family sans-serif, no scripts
 * and no external resources. Every coordinate is printed with at most two
 * decimals by a locale-independent formatter, so the same chart gives the
 * same bytes on every run, and on every platform short of a libm that
 * rounds log10/pow differently right at a printed digit.
 *
 * What is not drawn is said: points that are NaN/inf, or <= 0 on a log
 * axis, are skipped and counted in a footnote ("3 points <= 0 not shown");
 * a chart with nothing to draw still writes a valid SVG saying "no data".
 * Nothing hides silently either: markers of different series on the same
 * spot are set a few pixels apart side by side (the footnote counts them),
 * a series that repeats another's points whole says "(= other)" in the
 * legend, point labels keep off grid lines where they can, and a long
 * legend text wraps onto up to three lines before it is cut.
 *
 * Errors while building (out of memory, a bad series index) are sticky:
 * the building calls return nothing, and chart_write reports the first
 * one. A chart holds no global state; separate charts may be used from
 * separate threads.
 *
 * A module of its own: it knows nothing of units, sweeps or scenes (only
 * base/base_out.h, to write the file), so any layer above may draw with
 * it; sweeps, scenes, the stability study and the report do.
 */
#ifndef CHART_H
#define CHART_H
#include <stddef.h>
#include <stdio.h>

typedef struct chart chart;

/* Series styles, combinable: CHART_LINE|CHART_POINTS. CHART_STEP draws
 * the line as a staircase (horizontal, then vertical: "steps-post"), which
 * is how a Pareto front reads; it implies a line. Lines join points in the order
 * they were added and break where a point is skipped. */
enum { CHART_LINE = 1, CHART_POINTS = 2, CHART_STEP = 4, CHART_HOLLOW = 8 };
/* CHART_HOLLOW (with CHART_POINTS): large rings instead of filled
 * markers, to circle points of other series (e.g. on a Pareto front). */

/* A new empty chart; any text may be NULL (none). NULL when out of memory.
 * Labels should carry units, e.g. "error (ulp)". */
chart *chart_new(const char *title, const char *xlabel, const char *ylabel);
void   chart_free(chart *c);

/* Logarithmic axes: limits at the 1, 2 or 5 x 10^k nearest the data, ticks
 * at the decades between labelled 10^k, minor ticks between (on an axis of
 * up to two decades, 2 and 5 x 10^k are labelled too). */
void chart_log_x(chart *c, int on);
void chart_log_y(chart *c, int on);
/* Whole-number x data (e.g. bit widths): ticks at whole numbers only. */
void chart_int_x(chart *c, int on);

/* Add a series; returns its index (0, 1, ...), -1 when out of memory.
 * Series i gets palette colour i mod 7 and marker shape i mod 5, and from
 * the 8th on a dashed line. A NULL or empty label keeps the series out of
 * the legend. A style without any bit means CHART_POINTS. */
int  chart_series(chart *c, const char *label, int style);
void chart_point(chart *c, int series, double x, double y);
/* Give a series its own look: colour "#rrggbb" (NULL: the palette's),
 * marker shape 0..4 (circle, square, triangle up, diamond, triangle down;
 * -1: by index), dashed line 1/0 (-1: by index). For charts that encode
 * one setting by colour and another by shape. */
void chart_series_look(chart *c, int series, const char *colour, int shape, int dashed);
/* A legend entry that draws no data: the key to a colour, shape or line
 * style that unlabelled series use (style as for a series; colour NULL:
 * dark grey). Style 0 makes a heading: text only. Returns its index. The
 * legend lists keys and the labelled series that draw something (a marker
 * or a line between two shown points), in the order they were added. */
int  chart_legend_key(chart *c, const char *label, const char *colour, int shape, int style);
/* A point with a small text beside it (e.g. "width 12"); the text is
 * placed where it overlaps no other point label or marker, if such a place
 * exists; where it would overlap another text or leave the plot wherever
 * it goes, it is dropped (no two texts of a chart overlap). */
void chart_point_label(chart *c, int series, double x, double y,
                          const char *label);

/* A shaded band across the whole plot height over x in [x0, x1] (e.g. a
 * failure region); its label is written above the plot, in one of four
 * rows (dropped when it overlaps a label in each). The band does not
 * widen the x axis: it is cut to the plot area (x0/x1 may be +-inf). */
void chart_hband(chart *c, double x0, double x1, const char *label);
/* A dashed horizontal line at y (e.g. a target error), labelled at its
 * right end. Its y is included in the y axis range. */
void chart_hline(chart *c, double y, const char *label);

/* Write the SVG to path atomically (a temporary file in the same directory,
 * then rename). 0 on success; -1 with a one-line message in err (no
 * newline) on failure, leaving no temporary file behind. err may be NULL. */
int  chart_write(const chart *c, const char *path, char *err, size_t errlen);
/* The same SVG to an open stream (e.g. a base_out that the caller commits
 * with others); `what` names it in messages. 0, or -1 with a message
 * (incomplete chart, out of memory) and nothing written. Write errors are
 * left in the stream's error flag. */
int  chart_fwrite(const chart *c, FILE *f, const char *what, char *err, size_t errlen);

/* Pareto front for minimisation of both x (cost) and y (error).
 * on_front[i] = 1 when no other point is at least as good in both and
 * strictly better in one, else 0. Ties: exact duplicates do not dominate
 * each other, so all copies of a front point are on the front; of two
 * points with equal x, only the smaller y can be on it (and likewise for
 * equal y). Points with a NaN coordinate are never on the front and never
 * dominate. Returns the number of points on the front. O(n log n). */
size_t chart_pareto(const double *x, const double *y, size_t n, unsigned char *on_front);
/* The same over three costs (e.g. error, area, clocks per pixel): a point
 * is on the front when no other is at least as good in all three and
 * strictly better in one; exact duplicates do not dominate each other;
 * NaN: never on the front. O(n x front size). */
size_t chart_pareto3(const double *x, const double *y, const double *z, size_t n, unsigned char *on_front);

/* The axis ticks the charts use, exposed for tests and for callers that
 * want the same scale elsewhere. For the data range [dmin, dmax]:
 * linear: steps of 1, 2 or 5 x 10^k, at most 8 intervals, the first tick
 * <= dmin and the last >= dmax; log (dmin > 0): limits lo <= dmin and
 * hi >= dmax at the nearest 1, 2 or 5 x 10^k (the decades around the data
 * when no decade would lie between those), ticks the decades 10^k within
 * them (every second, third... decade when there are more than 8); at
 * least one.
 * Writes up to cap ascending major ticks to ticks and the axis limits to
 * lo and hi (either may be NULL); returns the number of ticks (0 when the
 * range is unusable: NaN, inf, or dmin <= 0 on a log axis). At the ends
 * of double: linear data within a step of +-DBL_MAX gets the data's own
 * limit there, as the covering tick would overflow; log data reaching past
 * 1e+-300 may get outer decades past the double range, which come back as
 * 0 or inf (the charts label decades by exponent and are not affected). */
size_t chart_ticks(double dmin, double dmax, int log_scale,
                    double *ticks, size_t cap, double *lo, double *hi);
#endif
