/* tb_sweep_chart.c - a sweep's charts from its CSV; see tb_sweep_chart.h. */
#include "testbench/study/tb_sweep_chart.h"
#include "base/base_out.h"
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SC_MAXID   24      /* identity columns besides the width */
#define SC_MAXVAL  64      /* values of one column */
#define SC_SMALL   7       /* groups drawn one colour each up to this many */

typedef struct sc_col {
    char   name[40];
    int    param;          /* a unit parameter (written name=value) */
    size_t nval;
    char   val[SC_MAXVAL][32];
} sc_col;

struct tb_sc {
    char       unit[64];
    size_t     n, ngroups;
    tb_sc_row *row;
    int        nid;
    sc_col     id[SC_MAXID];
    unsigned char (*gval)[SC_MAXID];   /* [group][column]: value index */
    char      (*glabel)[160];          /* [group] */
    int        have_pps, have_energy;  /* every ok row has pixels/s, energy per pixel */
};

static void sc_err(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || !errlen) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

void tb_sc_free(tb_sc *sc)
{
    if (!sc) return;
    free(sc->row);
    free(sc->gval);
    free(sc->glabel);
    free(sc);
}

size_t tb_sc_rows(const tb_sc *sc) { return sc->n; }
const tb_sc_row *tb_sc_row_at(const tb_sc *sc, size_t i) { return &sc->row[i]; }
const char *tb_sc_unit(const tb_sc *sc) { return sc->unit; }
const char *tb_sc_group_label(const tb_sc *sc, size_t g) { return sc->glabel[g]; }

/* Split line (NUL-terminated, modified) at commas into at most cap fields. */
static int sc_split(char *line, char **f, int cap)
{
    int n = 0;
    for (char *p = line;;) {
        if (n == cap) return -1;
        f[n++] = p;
        p = strchr(p, ',');
        if (!p) return n;
        *p++ = 0;
    }
}

static int sc_find(char **h, int n, const char *name)
{
    for (int i = 0; i < n; i++) if (!strcmp(h[i], name)) return i;
    return -1;
}

static int sc_num(const char *s, double *v)
{
    char *end;
    if (!*s) return -1;
    *v = strtod(s, &end);
    return *end ? -1 : 0;
}

static int sc_cfg_cmp(const void *a, const void *b)
{
    const tb_sc_row *x = a, *y = b;
    return (x->config > y->config) - (x->config < y->config);
}

/* Columns the charts need; the identity columns are schedule, what lies
 * between width and round (the unit's parameters), round, overflow. */
enum { C_CONFIG, C_UNIT, C_SCHED, C_WIDTH, C_ROUND, C_OVF, C_STATUS, C_CPB, C_MAXE, C_RMS, C_AREA, C_N };
static const char *const sc_need[C_N] = { "config", "unit", "schedule", "width", "round", "overflow", "status",
                                          "cycles_per_beat", "max_abs_err", "rms_err", "area_ge" };

/* Group of a row from its identity values: a hash table of value-index
 * tuples, so that a million rows stay quick. */
typedef struct sc_hash { size_t cap; size_t *slot; } sc_hash;

static uint64_t sc_key(const unsigned char *v, int n)
{
    uint64_t h = 14695981039346656037ull;
    for (int i = 0; i < n; i++) { h ^= v[i]; h *= 1099511628211ull; }
    return h;
}

/* What reading a CSV keeps between its lines: where the columns are. */
typedef struct sc_rd {
    const char *what;          /* the file's name, for messages */
    int col[C_N], idcol[SC_MAXID], col_pps, col_e, nh;
    size_t rowcap, gcap;       /* allocated rows of sc->row, sc->gval */
} sc_rd;

/* The header line: the columns the charts need, and the identity columns
 * (schedule, the unit's parameters between width and round, round,
 * overflow). */
static int sc_header(tb_sc *sc, sc_rd *rd, char *line, char *err, size_t errlen)
{
    const char *what = rd->what;
    char *hdr[4096];
    int nh = rd->nh = sc_split(line, hdr, 4096);
    if (nh < 0) { sc_err(err, errlen, "%s:1: too many columns", what); return -1; }
    for (int k = 0; k < C_N; k++)
        if ((rd->col[k] = sc_find(hdr, nh, sc_need[k])) < 0) {
            sc_err(err, errlen, "%s:1: not a sweep CSV (no column '%s')", what, sc_need[k]);
            return -1;
        }
    /* Speed and energy: optional (a CSV made before them has neither). */
    rd->col_pps = sc_find(hdr, nh, "pixels_per_s");
    rd->col_e = sc_find(hdr, nh, "energy_pj_per_pixel");
    sc->have_pps = rd->col_pps >= 0;
    sc->have_energy = rd->col_e >= 0;
    const int *col = rd->col;
    if (col[C_ROUND] <= col[C_WIDTH] || col[C_ROUND] - col[C_WIDTH] - 1 + 3 > SC_MAXID) {
        sc_err(err, errlen, "%s:1: not a sweep CSV (columns out of order)", what);
        return -1;
    }
    rd->idcol[sc->nid++] = col[C_SCHED];
    for (int k = col[C_WIDTH] + 1; k < col[C_ROUND]; k++) rd->idcol[sc->nid++] = k;
    rd->idcol[sc->nid++] = col[C_ROUND];
    rd->idcol[sc->nid++] = col[C_OVF];
    for (int k = 0; k < sc->nid; k++) {
        snprintf(sc->id[k].name, sizeof sc->id[k].name, "%s", hdr[rd->idcol[k]]);
        sc->id[k].param = k > 0 && k < sc->nid - 2;
    }
    return 0;
}

/* Row r's figures from fields f: configuration, width, status and, for
 * an ok row, its errors, area, clocks, speed and energy. */
static int sc_figures(tb_sc *sc, const sc_rd *rd, char **f, int lineno, tb_sc_row *r, char *err, size_t errlen)
{
    const char *what = rd->what;
    const int *col = rd->col;
    double cfg, w;
    if (sc_num(f[col[C_CONFIG]], &cfg) || cfg < 0 || cfg != floor(cfg) || cfg > 1e12) {
        sc_err(err, errlen, "%s:%d: config '%s' is not a configuration number", what, lineno, f[col[C_CONFIG]]);
        return -1;
    }
    if (sc_num(f[col[C_WIDTH]], &w) || w < 1 || w > 64 || w != floor(w)) {
        sc_err(err, errlen, "%s:%d: width '%s' is not 1..64", what, lineno, f[col[C_WIDTH]]);
        return -1;
    }
    r->config = (size_t)cfg;
    r->width = (int)w;
    const char *st = f[col[C_STATUS]];
    if (strcmp(st, "ok") && strcmp(st, "failed") && strcmp(st, "not_buildable")) {
        sc_err(err, errlen, "%s:%d: status '%s' is not ok, failed or not_buildable", what, lineno, st);
        return -1;
    }
    r->ok = !strcmp(st, "ok");
    if (r->ok) {
        const int nc[4] = { C_MAXE, C_RMS, C_AREA, C_CPB };
        double *dst[4] = { &r->max_err, &r->rms_err, &r->area, &r->clocks_per_pixel };
        for (int k = 0; k < 4; k++)
            if (sc_num(f[col[nc[k]]], dst[k])) {
                sc_err(err, errlen, "%s:%d: %s '%s' is not a number", what, lineno, sc_need[nc[k]], f[col[nc[k]]]);
                return -1;
            }
        /* Empty or non-positive: unknown (no timing or energy for this row). */
        if (rd->col_pps < 0 || sc_num(f[rd->col_pps], &r->pixels_per_s) || !(r->pixels_per_s > 0)) {
            r->pixels_per_s = NAN;
            sc->have_pps = 0;
        }
        if (rd->col_e < 0 || sc_num(f[rd->col_e], &r->energy_pp) || !(r->energy_pp > 0)) {
            r->energy_pp = NAN;
            sc->have_energy = 0;
        }
    }
    return 0;
}

/* One data line's fields f: its row, and its identity values' indices
 * beside it in gval (the group is found later, in config order). */
static int sc_row(tb_sc *sc, sc_rd *rd, char **f, int lineno, char *err, size_t errlen)
{
    const char *what = rd->what, *unit = f[rd->col[C_UNIT]];
    if (!sc->n) snprintf(sc->unit, sizeof sc->unit, "%s", unit);
    else if (strcmp(sc->unit, unit)) {
        sc_err(err, errlen, "%s:%d: unit %s, the rows before are %s", what, lineno, unit, sc->unit);
        return -1;
    }
    if (sc->n == rd->rowcap) {
        size_t nc = rd->rowcap ? 2 * rd->rowcap : 64;
        tb_sc_row *r = realloc(sc->row, nc * sizeof *r);
        if (!r) base_out_of_memory();
        sc->row = r;
        rd->rowcap = nc;
    }
    tb_sc_row *r = &sc->row[sc->n];
    memset(r, 0, sizeof *r);
    if (sc_figures(sc, rd, f, lineno, r, err, errlen)) return -1;
    unsigned char v[SC_MAXID];
    for (int k = 0; k < sc->nid; k++) {
        sc_col *c = &sc->id[k];
        const char *s = f[rd->idcol[k]];
        size_t j = 0;
        while (j < c->nval && strcmp(c->val[j], s)) j++;
        if (j == c->nval) {
            if (c->nval == SC_MAXVAL || strlen(s) > 31) {
                sc_err(err, errlen, "%s:%d: column %s: more than %d values, or a value longer than 31 characters",
                       what, lineno, c->name, SC_MAXVAL);
                return -1;
            }
            snprintf(c->val[c->nval++], 32, "%s", s);
        }
        v[k] = (unsigned char)j;
    }
    sc->n++;
    if (sc->n > rd->gcap) {
        size_t nc = rd->gcap ? 2 * rd->gcap : 64;
        unsigned char (*g)[SC_MAXID] = realloc(sc->gval, nc * sizeof *g);
        if (!g) base_out_of_memory();
        sc->gval = g;
        rd->gcap = nc;
    }
    memcpy(sc->gval[sc->n - 1], v, SC_MAXID);
    return 0;
}

/* Configuration order (a merged CSV is already in it; shards are not
 * complete, which the charts accept). The tuples move with the rows. */
static int sc_sort(tb_sc *sc, const char *what, char *err, size_t errlen)
{
    tb_sc_row *sorted = malloc((sc->n ? sc->n : 1) * sizeof *sorted);
    unsigned char (*gv)[SC_MAXID] = malloc((sc->n ? sc->n : 1) * sizeof *gv);
    if (!sorted || !gv) base_out_of_memory();
    for (size_t i = 0; i < sc->n; i++) { sorted[i] = sc->row[i]; sorted[i].group = i; }
    qsort(sorted, sc->n, sizeof *sorted, sc_cfg_cmp);
    for (size_t i = 0; i < sc->n; i++) {
        memcpy(gv[i], sc->gval[sorted[i].group], SC_MAXID);
        if (i && sorted[i].config == sorted[i - 1].config) {
            sc_err(err, errlen, "%s: configuration %zu is given twice", what, sorted[i].config);
            free(sorted);
            free(gv);
            return -1;
        }
    }
    free(sc->row);
    free(sc->gval);
    sc->row = sorted;
    sc->gval = gv;
    return 0;
}

/* Each column's values renumbered in order of first appearance in
 * configuration order. */
static void sc_value_order(tb_sc *sc)
{
    for (int k = 0; k < sc->nid; k++) {
        sc_col *c = &sc->id[k];
        int map[SC_MAXVAL], nmap = 0;
        for (size_t j = 0; j < c->nval; j++) map[j] = -1;
        for (size_t i = 0; i < sc->n; i++) {
            int o = sc->gval[i][k];
            if (map[o] < 0) map[o] = nmap++;
        }
        char tmp[SC_MAXVAL][32];
        for (size_t j = 0; j < c->nval; j++) memcpy(tmp[map[j]], c->val[j], 32);
        memcpy(c->val, tmp, c->nval * 32);
        for (size_t i = 0; i < sc->n; i++) sc->gval[i][k] = (unsigned char)map[sc->gval[i][k]];
    }
}

/* Groups, numbered in order of first appearance; gval becomes the
 * groups' tuples, and each group gets its label. */
static void sc_groups(tb_sc *sc)
{
    sc_hash ht = { 64, NULL };
    while (ht.cap < 2 * sc->n) ht.cap *= 2;
    ht.slot = malloc(ht.cap * sizeof *ht.slot);
    unsigned char (*gt)[SC_MAXID] = malloc((sc->n ? sc->n : 1) * sizeof *gt);
    if (!ht.slot || !gt) base_out_of_memory();
    for (size_t k = 0; k < ht.cap; k++) ht.slot[k] = SIZE_MAX;
    for (size_t i = 0; i < sc->n; i++) {
        size_t h = (size_t)(sc_key(sc->gval[i], sc->nid) & (ht.cap - 1));
        while (ht.slot[h] != SIZE_MAX && memcmp(gt[ht.slot[h]], sc->gval[i], (size_t)sc->nid)) h = (h + 1) & (ht.cap - 1);
        if (ht.slot[h] == SIZE_MAX) {
            ht.slot[h] = sc->ngroups;
            memcpy(gt[sc->ngroups++], sc->gval[i], SC_MAXID);
        }
        sc->row[i].group = ht.slot[h];
    }
    free(ht.slot);
    free(sc->gval);
    sc->gval = gt;
    sc->glabel = calloc(sc->ngroups ? sc->ngroups : 1, sizeof *sc->glabel);
    if (!sc->glabel) base_out_of_memory();
    for (size_t g = 0; g < sc->ngroups; g++) {
        size_t k = 0, cap = sizeof sc->glabel[g];
        char *b = sc->glabel[g];
        for (int d = 0; d < sc->nid && k < cap; d++) {
            const sc_col *c = &sc->id[d];
            if (c->nval < 2) continue;
            int m = c->param ? snprintf(b + k, cap - k, "%s%s=%s", k ? " " : "", c->name, c->val[sc->gval[g][d]])
                             : snprintf(b + k, cap - k, "%s%s", k ? " " : "", c->val[sc->gval[g][d]]);
            if (m > 0) k += (size_t)m;
        }
    }
}

tb_sc *tb_sc_read(const char *text, size_t len, const char *what, char *err, size_t errlen)
{
    tb_sc *sc = calloc(1, sizeof *sc);
    char *buf = malloc(len + 1);
    char **f = malloc(4096 * sizeof *f);
    sc_rd rd = { .what = what, .col_pps = -1, .col_e = -1 };
    if (!sc || !buf || !f) base_out_of_memory();
    memcpy(buf, text, len);
    buf[len] = 0;
    char *line = buf, *next;
    int lineno = 1;
    next = strchr(line, '\n');
    if (!next) { sc_err(err, errlen, "%s:1: not a sweep CSV (no header line)", what); goto bad; }
    *next = 0;
    if (next > line && next[-1] == '\r') next[-1] = 0;
    if (sc_header(sc, &rd, line, err, errlen)) goto bad;
    for (line = next + 1; *line; line = next ? next + 1 : line + strlen(line)) {
        lineno++;
        next = strchr(line, '\n');
        if (next) *next = 0;
        size_t ll = strlen(line);
        if (ll && line[ll - 1] == '\r') line[--ll] = 0;
        if (!ll) {
            if (!next) break;
            sc_err(err, errlen, "%s:%d: empty line", what, lineno);
            goto bad;
        }
        int nf = sc_split(line, f, 4096);
        if (nf != rd.nh) {
            sc_err(err, errlen, "%s:%d: %d fields, the header has %d", what, lineno, nf < 0 ? 4096 : nf, rd.nh);
            goto bad;
        }
        if (sc_row(sc, &rd, f, lineno, err, errlen)) goto bad;
    }
    if (!sc->n) { sc_err(err, errlen, "%s: no rows", what); goto bad; }
    if (sc_sort(sc, what, err, errlen)) goto bad;
    sc_value_order(sc);
    sc_groups(sc);
    free(f);
    free(buf);
    return sc;
bad:
    free(f);
    free(buf);
    tb_sc_free(sc);
    return NULL;
}

/* --------------------------------------------------------------- front */

size_t tb_sc_front(const tb_sc *sc, unsigned char *on)
{
    size_t n1 = sc->n ? sc->n : 1;
    double *x = malloc(n1 * sizeof *x), *y = malloc(n1 * sizeof *y), *z = malloc(n1 * sizeof *z);
    if (!x || !y || !z) base_out_of_memory();
    for (size_t i = 0; i < sc->n; i++) {
        const tb_sc_row *r = &sc->row[i];
        x[i] = r->ok ? r->max_err : NAN;
        y[i] = r->ok ? r->area : NAN;
        z[i] = !r->ok ? NAN : sc->have_pps ? 1.0 / r->pixels_per_s : r->clocks_per_pixel;
    }
    size_t nf = chart_pareto3(x, y, z, sc->n, on);
    free(x); free(y); free(z);
    return nf;
}

/* --------------------------------------------------------------- looks */

static const char *const sc_palette[SC_SMALL] = {
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"
};

/* A sequential scale, dark purple to green (viridis without its yellow
 * end, which is too light on white), at u in [0, 1]. */
static void sc_scale(double u, char out[8])
{
    static const int stop[5][3] = { { 68, 1, 84 }, { 65, 68, 135 }, { 42, 120, 142 }, { 34, 168, 132 }, { 122, 209, 81 } };
    if (!(u >= 0)) u = 0;
    if (u > 1) u = 1;
    double p = u * 4;
    int i = p >= 4 ? 3 : (int)p;
    double t = p - i;
    int rgb[3];
    for (int k = 0; k < 3; k++) rgb[k] = (int)lround(stop[i][k] + t * (stop[i + 1][k] - stop[i][k]));
    snprintf(out, 8, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
}

/* How groups look: per group (few groups) or per dimension. */
typedef struct sc_look {
    int per_group;
    int dc, ds;                  /* colour and shape dimensions (-1: none) */
} sc_look;

static sc_look sc_look_of(const tb_sc *sc)
{
    sc_look l = { sc->ngroups <= SC_SMALL, -1, -1 };
    if (l.per_group) return l;
    for (int d = 0; d < sc->nid; d++)
        if (sc->id[d].nval > 1 && (l.dc < 0 || sc->id[d].nval > sc->id[l.dc].nval)) l.dc = d;
    for (int d = 0; d < sc->nid; d++)
        if (d != l.dc && sc->id[d].nval > 1 && sc->id[d].nval <= 5 && (l.ds < 0 || sc->id[d].nval > sc->id[l.ds].nval)) l.ds = d;
    return l;
}

static void sc_group_look(const tb_sc *sc, const sc_look *l, size_t g, char colour[8], int *shape)
{
    if (l->per_group) {
        snprintf(colour, 8, "%s", sc_palette[g % SC_SMALL]);
        *shape = (int)(g % 5);
        return;
    }
    size_t nv = sc->id[l->dc].nval, v = sc->gval[g][l->dc];
    if (nv <= SC_SMALL) snprintf(colour, 8, "%s", sc_palette[v]);
    else sc_scale((double)v / (double)(nv - 1), colour);
    *shape = l->ds >= 0 ? sc->gval[g][l->ds] : 0;
}

/* "terms=3" for a parameter, the bare value otherwise. */
static void sc_value_label(const sc_col *c, size_t v, char *buf, size_t len)
{
    if (c->param) snprintf(buf, len, "%s=%s", c->name, c->val[v]);
    else snprintf(buf, len, "%s", c->val[v]);
}

/* The legend for a per-dimension look: which colour is which value of
 * one dimension (some of them, on a scale), which shape of another, and
 * what else varies without its own look. */
static void sc_keys(chart *c, const tb_sc *sc, const sc_look *l, int style)
{
    if (l->per_group) return;
    char lab[96], col[8];
    const sc_col *dc = &sc->id[l->dc];
    size_t nv = dc->nval, shown = nv <= 8 ? nv : 6;
    if (shown < nv) snprintf(lab, sizeof lab, "colour: %s, %zu of %zu", dc->name, shown, nv);
    else snprintf(lab, sizeof lab, "colour: %s", dc->name);
    chart_legend_key(c, lab, NULL, -1, 0);
    for (size_t k = 0; k < shown; k++) {
        size_t v = shown == nv ? k : (size_t)lround((double)k * (double)(nv - 1) / (double)(shown - 1));
        if (nv <= SC_SMALL) snprintf(col, sizeof col, "%s", sc_palette[v]);
        else sc_scale((double)v / (double)(nv - 1), col);
        sc_value_label(dc, v, lab, sizeof lab);
        chart_legend_key(c, lab, col, 0, style);
    }
    if (l->ds >= 0) {
        const sc_col *ds = &sc->id[l->ds];
        snprintf(lab, sizeof lab, "shape: %s", ds->name);
        chart_legend_key(c, lab, NULL, -1, 0);
        for (size_t v = 0; v < ds->nval; v++) {
            sc_value_label(ds, v, lab, sizeof lab);
            chart_legend_key(c, lab, "#555555", (int)v, CHART_POINTS);
        }
    }
    size_t k = 0;
    char rest[96] = "";
    for (int d = 0; d < sc->nid; d++)
        if (d != l->dc && d != l->ds && sc->id[d].nval > 1) {
            int m = snprintf(rest + k, sizeof rest - k, "%s%s", k ? ", " : "also varied: ", sc->id[d].name);
            if (m > 0 && (size_t)m < sizeof rest - k) k += (size_t)m;
        }
    if (k) chart_legend_key(c, rest, NULL, -1, 0);
}

/* A series for group g with its look; labelled with its settings in the
 * per-group look. */
static int sc_series(chart *c, const tb_sc *sc, const sc_look *l, size_t g, int style, int label)
{
    char colour[8];
    int shape;
    const char *gl = sc->glabel[g];
    int s = chart_series(c, label && l->per_group ? (*gl ? gl : "all configurations") : NULL, style);
    sc_group_look(sc, l, g, colour, &shape);
    chart_series_look(c, s, colour, shape, 0);
    return s;
}

/* -------------------------------------------------------------- charts */

const char *const tb_sc_chart_file[TB_SC_NCHARTS] = { "error_vs_width.svg", "area_vs_error.svg", "cycles_vs_error.svg",
                                                      "throughput_vs_error.svg", "energy_vs_error.svg" };

int tb_sc_chart_drawn(const tb_sc *sc, int which)
{
    if (which == TB_SC_SPEED_ERROR) return sc->have_pps;
    if (which == TB_SC_ENERGY_ERROR) return sc->have_energy;
    if (which != TB_SC_CLOCKS_ERROR) return which >= 0 && which < TB_SC_NCHARTS;
    double c0 = NAN;
    for (size_t i = 0; i < sc->n; i++)
        if (sc->row[i].ok) {
            if (isnan(c0)) c0 = sc->row[i].clocks_per_pixel;
            else if (sc->row[i].clocks_per_pixel != c0) return 1;
        }
    return 0;
}

static chart *sc_error_width(const tb_sc *sc, const sc_look *l, const tb_sc_target *t)
{
    /* Lines need two widths; with one, the RMS error (a dashed line)
     * would not show, and neither does its key. */
    int lines = 0;
    for (size_t i = 1; i < sc->n && !lines; i++)
        for (size_t j = 0; j < i && !lines; j++)
            lines = sc->row[i].ok && sc->row[j].ok && sc->row[i].group == sc->row[j].group &&
                    sc->row[i].width != sc->row[j].width;
    char title[200];
    snprintf(title, sizeof title, lines ? "%s: max and RMS error against width" : "%s: max error against width", sc->unit);
    chart *c = chart_new(title, "width W (bits, the unit's format rule)", "error vs float reference (output units)");
    if (!c) base_out_of_memory();          /* its one failure */
    chart_log_y(c, 1);
    chart_int_x(c, 1);
    for (size_t g = 0; g < sc->ngroups; g++) {
        int smax = sc_series(c, sc, l, g, CHART_LINE | CHART_POINTS, 1);
        int srms = lines ? sc_series(c, sc, l, g, CHART_LINE, 0) : -1;
        if (lines) chart_series_look(c, srms, NULL, -1, 1);
        for (size_t i = 0; i < sc->n; i++) {
            const tb_sc_row *r = &sc->row[i];
            if (r->group != g) continue;
            chart_point(c, smax, r->width, r->ok ? r->max_err : NAN);
            if (lines) chart_point(c, srms, r->width, r->ok ? r->rms_err : NAN);
        }
    }
    sc_keys(c, sc, l, CHART_POINTS);
    if (lines) {
        chart_legend_key(c, "line: max |e|", "#444444", 0, CHART_LINE | CHART_POINTS);
        int k = chart_legend_key(c, "dashed: RMS e", "#444444", -1, CHART_LINE);
        chart_series_look(c, k, NULL, -1, 1);
    } else chart_legend_key(c, "points: max |e|", "#444444", 0, CHART_POINTS);
    if (t && t->on && !t->nmse) {
        char lab[64];
        snprintf(lab, sizeof lab, "target %g", t->value);
        chart_hline(c, t->value, lab);
    }
    return c;
}

/* The y value of a row on chart `which` (area, clocks, pixels/s, energy). */
static double sc_y(const tb_sc_row *r, int which)
{
    switch (which) {
    case TB_SC_CLOCKS_ERROR: return r->clocks_per_pixel;
    case TB_SC_SPEED_ERROR: return r->pixels_per_s;
    case TB_SC_ENERGY_ERROR: return r->energy_pp;
    default: return r->area;
    }
}

/* Ring the front's points and label a few with their width. */
static void sc_front(chart *c, const tb_sc *sc, const unsigned char *on, int which)
{
    int sf = chart_series(c, "Pareto front", CHART_POINTS | CHART_HOLLOW);
    chart_series_look(c, sf, "#000000", 0, -1);
    size_t nf = 0;
    for (size_t i = 0; i < sc->n; i++) nf += on[i];
    size_t every = nf <= 16 ? 1 : (nf + 15) / 16, k = 0;
    for (size_t i = 0; i < sc->n; i++) {
        if (!on[i]) continue;
        const tb_sc_row *r = &sc->row[i];
        char lab[32];
        snprintf(lab, sizeof lab, "width %d", r->width);
        chart_point_label(c, sf, r->max_err, sc_y(r, which), k++ % every == 0 ? lab : NULL);
    }
    chart_legend_key(c, sc->have_pps ? "(error, area, pixels/s)" : "(error, area, clocks/pixel)", NULL, -1, 0);
}

/* Whether the front is the two-dimensional one of the area chart: the
 * speed (pixels per second, or clocks per pixel without timing) is the
 * same in every row. */
static int sc_speed_flat(const tb_sc *sc)
{
    int which = sc->have_pps ? TB_SC_SPEED_ERROR : TB_SC_CLOCKS_ERROR;
    double v0 = NAN;
    for (size_t i = 0; i < sc->n; i++)
        if (sc->row[i].ok) {
            double v = sc_y(&sc->row[i], which);
            if (isnan(v0)) v0 = v;
            else if (v != v0) return 0;
        }
    return 1;
}

static const char *const sc_title[TB_SC_NCHARTS] = {
    NULL, "%s: area against max error", "%s: clocks per pixel against max error",
    "%s: pixels per second at f_max against max error", "%s: energy per pixel against max error" };
static const char *const sc_ylabel[TB_SC_NCHARTS] = {
    NULL, "area (GE, NAND2 gate equivalents)", "clocks per pixel (output beat), steady state",
    "pixels (output beats) per second at f_max", "energy per pixel (pJ, switching and clock)" };

static chart *sc_area_error(const tb_sc *sc, const sc_look *l, const tb_sc_target *t, int which)
{
    char title[200];
    snprintf(title, sizeof title, sc_title[which], sc->unit);
    chart *c = chart_new(title, "max |e| vs float reference (output units)", sc_ylabel[which]);
    if (!c) base_out_of_memory();
    chart_log_x(c, 1);
    double lo = INFINITY, hi = 0;
    for (size_t i = 0; i < sc->n; i++)
        if (sc->row[i].ok) {
            double v = sc_y(&sc->row[i], which);
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
    chart_log_y(c, lo > 0 && hi > 10 * lo);
    for (size_t g = 0; g < sc->ngroups; g++) {
        int s = sc_series(c, sc, l, g, CHART_POINTS, 1);
        for (size_t i = 0; i < sc->n; i++) {
            const tb_sc_row *r = &sc->row[i];
            if (r->group == g && r->ok) chart_point(c, s, r->max_err, sc_y(r, which));
        }
    }
    unsigned char *on = calloc(sc->n ? sc->n : 1, 1);
    if (!on) base_out_of_memory();
    tb_sc_front(sc, on);
    /* When the speed does not vary the front is the two-dimensional one of
     * this plane: a staircase through it reads as the best area at each
     * error. */
    if (which == TB_SC_AREA_ERROR && sc_speed_flat(sc)) {
        int st = chart_series(c, NULL, CHART_STEP);
        chart_series_look(c, st, "#000000", -1, 0);
        /* the front in order of error */
        size_t nf = 0;
        for (size_t i = 0; i < sc->n; i++) nf += on[i];
        size_t *ix = malloc((nf ? nf : 1) * sizeof *ix);
        if (!ix) base_out_of_memory();
        size_t m = 0;
        for (size_t i = 0; i < sc->n; i++) if (on[i]) ix[m++] = i;
        for (size_t a = 1; a < m; a++)     /* insertion sort: fronts are short */
            for (size_t b = a; b > 0; b--) {
                const tb_sc_row *p = &sc->row[ix[b - 1]], *q = &sc->row[ix[b]];
                if (p->max_err < q->max_err || (p->max_err == q->max_err && p->area <= q->area)) break;
                size_t tmp = ix[b]; ix[b] = ix[b - 1]; ix[b - 1] = tmp;
            }
        for (size_t k = 0; k < m; k++) chart_point(c, st, sc->row[ix[k]].max_err, sc->row[ix[k]].area);
        free(ix);
    }
    sc_keys(c, sc, l, CHART_POINTS);
    sc_front(c, sc, on, which);
    free(on);
    if (t && t->on && which == TB_SC_AREA_ERROR) {
        int st = chart_series(c, "target search", CHART_POINTS);
        chart_series_look(c, st, "#000000", 3, -1);
        for (size_t k = 0; k < t->n; k++) chart_point(c, st, t->err[k], t->area[k]);
        if (!t->nmse) {
            char lab[64];
            snprintf(lab, sizeof lab, "over the target %g", t->value);
            chart_hband(c, t->value, INFINITY, lab);
        }
    }
    return c;
}

chart *tb_sc_chart(const tb_sc *sc, int which, const tb_sc_target *t)
{
    sc_look l = sc_look_of(sc);
    switch (which) {
    case TB_SC_ERROR_WIDTH: return sc_error_width(sc, &l, t);
    case TB_SC_AREA_ERROR: case TB_SC_CLOCKS_ERROR: case TB_SC_SPEED_ERROR: case TB_SC_ENERGY_ERROR:
        return sc_area_error(sc, &l, t, which);
    default: return NULL;
    }
}
