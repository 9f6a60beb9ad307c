/* tb_sweep_chart.h - a sweep's charts, drawn from its CSV.
 *
 * The charts are made from the CSV alone (sweep.csv, a shard's, or the
 * CSV merge joins), so `shadesim sweep` and `shadesim chart sweep.csv`
 * draw the same bytes: the sweep prints its CSV, reads it back here and
 * draws from that.
 *
 * Settings: the CSV's identity columns besides the width (schedule, every
 * unit parameter, round, overflow). A "group" is one combination of their
 * values; a "dimension" is a column that takes more than one value. Groups
 * and values are numbered in order of first appearance in configuration
 * order, which is the sweep's own order of its settings.
 *
 * Looks: up to 7 groups get a colour and marker shape each, labelled with
 * the settings spelled out ("mac terms=3 half-up"). More groups are drawn
 * by dimension: colour by the dimension with the most values (a palette
 * colour per value up to 7, else a sequential scale with some values
 * named in the legend), marker shape by a second one of at most 5 values;
 * the legend names the dimensions, not the groups, so it stays short.
 *
 * Throughput is pixels per second at the design's f_max: the CSV's
 * pixels_per_s (an interpolation unit gives L pixels, one per beat, per
 * item; the other units one result per item), from its clocks per pixel
 * (cycles_per_beat) and its critical path (docs/timing.md). The Pareto
 * front is over max |error|, area and seconds per pixel, all three
 * minimised; a CSV without pixels_per_s (an older one) gives the front
 * over clocks per pixel instead, and no speed or energy chart.
 */
#ifndef TB_SWEEP_CHART_H
#define TB_SWEEP_CHART_H
#include <stddef.h>
#include "chart/chart.h"

typedef struct tb_sc tb_sc;

/* Read a sweep CSV held in memory (text, len); what names it in messages
 * ("FILE:LINE: what is wrong"). NULL with a message on a bad CSV. */
tb_sc *tb_sc_read(const char *text, size_t len, const char *what, char *err, size_t errlen);
void   tb_sc_free(tb_sc *sc);

/* The rows, in configuration order. ok: the simulation ran (status ok). */
typedef struct tb_sc_row {
    size_t config, group;
    int    width, ok;
    double max_err, rms_err, area, clocks_per_pixel;
    double pixels_per_s, energy_pp;    /* NaN when the CSV has no such column */
} tb_sc_row;
size_t           tb_sc_rows(const tb_sc *sc);
const tb_sc_row *tb_sc_row_at(const tb_sc *sc, size_t i);
const char      *tb_sc_unit(const tb_sc *sc);
/* A group's settings, spelled out ("mac terms=3"), only its dimensions;
 * "" when nothing varies. */
const char      *tb_sc_group_label(const tb_sc *sc, size_t group);

/* Pareto front over (max |e|, area, seconds per pixel) of the ok rows
 * (clocks per pixel where the CSV gives no pixels per second): on[i] for
 * row i; returns its size. */
size_t tb_sc_front(const tb_sc *sc, unsigned char *on);

/* What the sweep adds to its own charts (not in the CSV): the target
 * search's designs and the target. NULL: nothing. */
typedef struct tb_sc_target {
    int    on, nmse;          /* nmse: the target is an NMSE, not a max |e| */
    double value;
    size_t n;                 /* designs found */
    const double *err, *area;
} tb_sc_target;

enum { TB_SC_ERROR_WIDTH, TB_SC_AREA_ERROR, TB_SC_CLOCKS_ERROR, TB_SC_SPEED_ERROR, TB_SC_ENERGY_ERROR,
       TB_SC_NCHARTS };
/* File names: error_vs_width.svg, area_vs_error.svg, cycles_vs_error.svg,
 * throughput_vs_error.svg, energy_vs_error.svg. */
extern const char *const tb_sc_chart_file[TB_SC_NCHARTS];
/* Is chart `which` drawn? The clocks chart only when clocks per pixel
 * differ between rows (else it is one flat row of points); the speed and
 * energy charts when the CSV has their columns. */
int    tb_sc_chart_drawn(const tb_sc *sc, int which);
/* The chart (caller frees), NULL for a `which` there is none of (out of
 * memory: base_out_of_memory). */
chart *tb_sc_chart(const tb_sc *sc, int which, const tb_sc_target *t);
#endif
