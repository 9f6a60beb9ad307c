/* tb_span.c - a stream of intervals of any length through a span unit
 * (tb_span.h): one build, the testbench's driver (tb_drive.h, the span
 * items as its source) offering item after item through the valid/ready
 * handshake, a monitor that collects the n beats of each; on the kernel
 * or on a batch's lanes.
 *
 * Nothing is allocated per item or per clock: the driver quantizes an
 * item's inputs when it first offers it, the monitor writes pixels straight
 * into the caller's array. */
#include "testbench/study/tb_span.h"
#include "testbench/tb.h"
#include "testbench/tb_range.h"
#include "sim/sim_vcd.h"
#include "testbench/tb_wave.h"
#include "base/base_out.h"
#include "sim/sim_batch.h"
#include "sim/sim_toggle.h"
#include "testbench/tb_energy.h"
#include "testbench/tb_drive.h"
#include <stddef.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

typedef struct span_tb {
    tb_drive drv;                   /* the driver (tb_drive.h), on the items */
    const unit_io *io;
    size_t nitems;
    uint64_t last_pixel;
    const sim_ctx *ctx;
    /* monitor */
    const sim_signal *y;
    double lsb;
    double *pix;
    size_t got, total;
} span_tb;

/* The clocks a stream may take: 6 a pixel at most (paper, cubic), a few
 * per item; a unit that stops answering is a failure, not a hang. */
static uint64_t clock_budget(size_t pixels, size_t items)
{
    return 1000 + 8 * (uint64_t)pixels + 8 * (uint64_t)items;
}

static void monitor(sim_proc *p)
{
    span_tb *s = p->data;
    if (!s->io->out_valid->cur || s->got >= s->total) return;
    s->pix[s->got++] = (double)s->y->cur * s->lsb;
    if (s->got == s->total) {
        s->last_pixel = sim_get_stats(s->ctx)->clocks;
        sim_stop(p->ctx);
    }
}

/* Map the unit's input ports to item fields (the driver's records: each
 * port's offset in tb_span_item, and whether an int); 0, or -1 if it is
 * not a span unit. */
static int map_inputs(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, size_t *off,
                      unsigned char *is_int, sim_fx_conv *conv, int *nin, int *has_deg)
{
    static const size_t node[4] = { offsetof(tb_span_item, node[0]), offsetof(tb_span_item, node[1]),
                                    offsetof(tb_span_item, node[2]), offsetof(tb_span_item, node[3]) };
    int k = 0, has_n = 0, has_dv = 0;
    *has_deg = 0;
    for (int i = 0; i < u->nsigs && k < UNIT_MAX_IO; i++) {
        const char *nm = u->sigs[i].name;
        if (u->sigs[i].role != UNIT_SIG_IN) continue;
        is_int[k] = 1;
        if (nm[0] == 'i' && nm[1] >= '1' && nm[1] <= '4' && !nm[2]) { off[k] = node[nm[1] - '1']; is_int[k] = 0; }
        else if (!strcmp(nm, "n")) { off[k] = offsetof(tb_span_item, n); has_n = 1; }
        else if (!strcmp(nm, "dv")) { off[k] = offsetof(tb_span_item, dv); has_dv = 1; }
        else if (!strcmp(nm, "deg")) { off[k] = offsetof(tb_span_item, deg); *has_deg = 1; }
        else return -1;
        sim_fx_conv_init(&conv[k++], f->f[i], cfg->rnd, cfg->ovf);
    }
    *nin = k;
    return has_n && has_dv ? 0 : -1;
}

/* An item the hardware can run: 1 <= n <= L, t = k/dv within [0, 1] for
 * every pixel (n - 1 <= dv <= L; dv >= 1, except that a one-pixel interval,
 * t = 0 only, may give 0), degree 2 or 3 where the unit has deg. */
static int check_item(const tb_span_item *it, size_t i, int L, int has_deg, char *err, size_t errlen)
{
    if (it->n < 1 || it->n > L) {
        snprintf(err, errlen, "interval %zu: n = %d pixels is outside 1..L = %d", i, it->n, L);
        return -1;
    }
    if (it->dv > L || it->dv < (it->n == 1 ? 0 : 1)) {
        snprintf(err, errlen, "interval %zu: divisor dv = %d is outside 1..L = %d", i, it->dv, L);
        return -1;
    }
    if (it->n - 1 > it->dv) {
        snprintf(err, errlen, "interval %zu: n = %d pixels with dv = %d puts t = %d/%d past 1 (n - 1 <= dv)",
                 i, it->n, it->dv, it->n - 1, it->dv);
        return -1;
    }
    if (has_deg && it->deg != 2 && it->deg != 3) {
        snprintf(err, errlen, "interval %zu: degree %d is not 2 or 3", i, it->deg);
        return -1;
    }
    for (int k = 0; k < 4; k++)
        if (!isfinite(it->node[k])) {
            snprintf(err, errlen, "interval %zu: node intensity %d is not finite", i, k + 1);
            return -1;
        }
    return 0;
}

/* The checks both paths make before simulating: s's input map, every
 * item's range, st's item counts. -1 with err (TB_BADINPUT), else 0. */
static int prepare(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, const tb_span_item *items,
                   size_t nitems, span_tb *s, tb_span_stats *st, char *err, size_t errlen)
{
    memset(st, 0, sizeof *st);
    memset(s, 0, sizeof *s);
    size_t off[UNIT_MAX_IO];
    unsigned char is_int[UNIT_MAX_IO];
    int nin = 0, has_deg = 0;
    sim_fx_conv conv[UNIT_MAX_IO];
    if (!u || map_inputs(u, cfg, f, off, is_int, conv, &nin, &has_deg)) {
        snprintf(err, errlen, "unit %s is not a span unit (inputs i1.., n, dv)", u ? u->name : "(none)");
        return -1;
    }
    if (cfg->L < 2 || cfg->L > 64) { snprintf(err, errlen, "%s: L = %d is outside 2..64", u->name, cfg->L); return -1; }
    size_t total = 0;
    for (size_t i = 0; i < nitems; i++) {
        if (check_item(&items[i], i, cfg->L, has_deg, err, errlen)) return -1;
        total += (size_t)items[i].n;
        st->items_deg2 += has_deg && items[i].deg == 2;
    }
    st->items = nitems;
    tb_drive_recs(&s->drv, nin, items, sizeof *items, nitems, off, is_int, conv);
    s->nitems = nitems; s->total = total;
    return 0;
}

/* The kernel's counts, for tb_energy_pj. */
static uint64_t kernel_toggles(const sim_signal *s, void *data) { return sim_toggle_count(data, s); }

static int span_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                    const tb_span_item *items, size_t nitems, double *pix,
                    tb_span_stats *st, const char *vcd_path, int energy, char *err, size_t errlen)
{
    span_tb s;
    if (prepare(u, cfg, f, items, nitems, &s, st, err, errlen)) return TB_BADINPUT;
    size_t total = s.total;
    if (!nitems) return TB_OK;

    tb_built bu;
    int unbuilt = tb_build(u, cfg, f, &bu, err, errlen);
    sim_ctx *c = bu.c;
    sim_signal *clk = bu.clk;
    sim_scope *sc = bu.sc;
    unit_io io = bu.io;
    int rc = TB_OK;
    sim_vcd *vcd = NULL;
    base_out *vout = NULL;
    sim_toggle *tog = NULL;
    if (unbuilt) { rc = TB_BADINPUT; goto done; }
    sim_clock(c, clk, 5, 5);
    s.io = &io; s.ctx = c;
    s.drv.io = &io; s.drv.ctx = c;
    s.y = io.out[0];
    s.lsb = ldexp(1.0, -io.out[0]->fmt.fbits);
    s.pix = pix; s.total = total;
    sim_proc *drv = sim_proc_new(c, "tb.driver", tb_drive_proc, &s.drv);
    sim_sensitive(drv, clk, SIM_EDGE_POS);
    sim_proc *mon = sim_proc_new(c, "tb.monitor", monitor, &s);
    sim_sensitive(mon, clk, SIM_EDGE_POS);
    mon->no_init = 1;
    if (energy && !(tog = sim_toggle_new(c))) base_out_of_memory();
    if (vcd_path) {
        /* A dump can be hundreds of MB: base_out writes it to a temporary
         * that SIGINT/SIGTERM/SIGHUP remove, renamed into place when
         * complete; "-" streams to stdout. */
        if (!(vout = base_out_open(vcd_path, err, errlen))) { rc = TB_BADINPUT; goto done; }
        if (!(vcd = sim_vcd_open(c, base_out_file(vout), "1ns"))) base_out_of_memory();
    }
    sim_status ss = sim_run(c, clock_budget(total, nitems) * 10);
    if (ss != SIM_OK) {         /* a loop, or a design that is not well formed */
        snprintf(err, errlen, "%s", sim_error(c));
        rc = TB_FAIL;
    } else if (s.got < total) {
        snprintf(err, errlen, "unit %s gave %zu of %zu pixels in %llu clocks", u->name, s.got, total,
                 (unsigned long long)sim_get_stats(c)->clocks);
        rc = TB_FAIL;
    }
    if (vcd) {
        char msg[256];
        int bad = sim_vcd_close(vcd);
        bad |= base_out_close(vout, msg, sizeof msg);
        if (bad && rc == TB_OK) {
            snprintf(err, errlen, "%s: write failed", vcd_path);
            rc = TB_BADINPUT;
        }
        vcd = NULL;
        vout = NULL;
        /* The GTKWave save file beside it, as run writes: valid, pixel. */
        sim_gtkw_trace lead[2] = { { io.out_valid, NULL }, { io.out[0], NULL } };
        char title[96];
        snprintf(title, sizeof title, "%s: pixels out", u->name);
        if (rc == TB_OK && tb_wave_gtkw(c, vcd_path, title, lead, 2, err, errlen)) rc = TB_BADINPUT;
    }
    if (rc == TB_OK) st->clocks = s.last_pixel - s.drv.first_accept;
    st->pixels = s.got;
    st->overflows = s.drv.in_ovf + tb_scope_overflows(sc);
    st->area_ge = sim_scope_area(sc);
    if (tog) st->energy_pj = tb_energy_pj(c, sc, kernel_toggles, tog, s.last_pixel, &st->toggles);
done:
    sim_toggle_free(tog);
    if (vcd) sim_vcd_abort(vcd);
    if (vout) base_out_abort(vout);
    sim_free(c);
    return rc;
}

int tb_span_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                const tb_span_item *items, size_t nitems, double *pix,
                tb_span_stats *st, const char *vcd_path, char *err, size_t errlen)
{
    return span_run(u, cfg, f, items, nitems, pix, st, vcd_path, 0, err, errlen);
}

int tb_span_run_energy(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                       const tb_span_item *items, size_t nitems, double *pix,
                       tb_span_stats *st, const char *vcd_path, char *err, size_t errlen)
{
    return span_run(u, cfg, f, items, nitems, pix, st, vcd_path, 1, err, errlen);
}

/* One lane's counts of the batch, for tb_energy_pj. */
typedef struct lane_count { const sim_batch *b; uint32_t lane; } lane_count;
static uint64_t lane_toggles(const sim_signal *s, void *data)
{
    const lane_count *x = data;
    const uint64_t *t = sim_batch_toggles(x->b, s);
    return t ? t[x->lane] : 0;
}

/* ------------------------------------------------------------- batch mode */

/* A lane of the batch: the scalar testbench's state (its driver and
 * monitor read the batch's lane values instead of signals). */
typedef struct lane_tb {
    span_tb  s;
    uint32_t lane;        /* index in the batch */
    int      in_batch, done;
} lane_tb;

/* The batch's arrays the lane testbench reads and writes. */
typedef struct lane_io {
    tb_drive_lanes w;                          /* the drivers' writes (next values) */
    const int64_t *in_valid, *in_ready, *out_valid, *y;
} lane_io;

/* What lane_edge reads of a lane at every edge, packed (two lanes a
 * cache line): the rest of lane_tb is read at an accept only. */
typedef struct lane_hot {
    double  *pix;
    const double *ref;     /* tb_span_lane's (NULL: not compared) */
    uint32_t lane, i;      /* index in the batch; in T */
    size_t   got, total;   /* span_tb's, while the lane runs */
    uint64_t max_clocks;
} lane_hot;

/* monitor() then driver() for lane h at edge e, once started (the driver
 * has offered the first item): after that the driver has work only when
 * the offered item is accepted, since valid and the inputs stay set from
 * edge to edge. 1 when the lane's last pixel came. */
static inline int lane_edge(const lane_io *x, lane_hot *h, lane_tb *T, uint64_t e, double lsb, double *se)
{
    const uint32_t l = h->lane;
    int last = 0;
    if (x->out_valid[l] && h->got < h->total) {
        double v = (double)x->y[l] * lsb;
        if (h->ref) {
            double d = v - h->ref[h->got];
            *se += d * d;
        }
        h->pix[h->got++] = v;
        if (h->got == h->total) { T[h->i].s.last_pixel = e; last = 1; }
    }
    if (x->in_valid[l] && x->in_ready[l]) {
        tb_drive_lane_accept(&T[h->i].s.drv, &x->w, l, e);
    }
    return last;
}

/* The lanes marked in_batch, side by side; a lane the batch cannot give
 * exactly (an overflow count that depends on the kernel's delta cycles,
 * or no answer within its clock budget) is left in_batch = 0 for
 * tb_span_run. */
static void run_batch(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                      tb_span_lane *L, lane_tb *T, size_t n, uint32_t nb, int energy, double max_se)
{
    char err[300];
    tb_built bu;
    int unbuilt = tb_build(u, cfg, f, &bu, err, sizeof err);
    sim_ctx *c = bu.c;
    sim_signal *clk = bu.clk;
    sim_scope *sc = bu.sc;
    unit_io io = bu.io;
    sim_batch *b = NULL;
    if (unbuilt || !(b = sim_batch_new(c, clk, nb, err, sizeof err))) {
        for (size_t i = 0; i < n; i++) T[i].in_batch = 0;
        sim_free(c);
        return;
    }
    if ((energy && sim_batch_toggles_on(b)) || sim_batch_overflows_on(b)) {
        for (size_t i = 0; i < n; i++) T[i].in_batch = 0;
        sim_batch_free(b);
        sim_free(c);
        return;
    }
    uint64_t const_ovf = tb_scope_overflows(sc);
    double area = sim_scope_area(sc), lsb = ldexp(1.0, -io.out[0]->fmt.fbits);
    lane_io x;
    memset(&x, 0, sizeof x);
    for (int p = 0; p < UNIT_MAX_IO && io.in[p]; p++) x.w.in[p] = sim_batch_next(b, io.in[p]);
    x.w.valid = sim_batch_next(b, io.in_valid);
    x.in_valid = sim_batch_val(b, io.in_valid);
    x.in_ready = sim_batch_val(b, io.in_ready);
    x.out_valid = sim_batch_val(b, io.out_valid);
    x.y = sim_batch_val(b, io.out[0]);
    /* act: the lanes still running, in lane order (a lane leaves the list
     * when it finishes) */
    lane_hot *act = malloc(n * sizeof *act);
    uint32_t *fin = malloc(n * sizeof *fin), active = 0;
    for (size_t i = 0; i < n && act && fin; i++) {
        lane_tb *t = &T[i];
        if (!t->in_batch) continue;
        t->s.io = &io; t->s.y = io.out[0]; t->s.lsb = lsb; t->s.pix = L[i].pix;
        /* the driver's run in the kernel's initialization, before any
         * edge: the first item offered (a lane here has one at least) */
        t->s.drv.started = 1;
        tb_drive_lane_offer(&t->s.drv, &x.w, t->lane);
        act[active++] = (lane_hot){ L[i].pix, L[i].ref, t->lane, (uint32_t)i, t->s.got, t->s.total,
                                    clock_budget(t->s.total, t->s.nitems) };
    }
    double se = 0;     /* squared error of the pixels so far against the lanes' ref */
    sim_batch_start(b);
    for (uint64_t e = 1; active && fin; e++) {
        uint32_t nfin = 0, keep = 0;
        if (se > max_se) {
            /* past the budget: the lanes still running stop, failed */
            for (uint32_t k = 0; k < active; k++) {
                tb_span_lane *ln = &L[act[k].i];
                ln->rc = TB_FAIL;
                ln->stopped = 1;
                snprintf(ln->err, sizeof ln->err, "stopped: the squared error passed the budget");
                T[act[k].i].done = 1;
            }
            break;
        }
        for (uint32_t k = 0; k < active; k++) {
            lane_hot *h = &act[k];
            int last = lane_edge(&x, h, T, e, lsb, &se);
            if (last || e >= h->max_clocks) {
                lane_tb *t = &T[h->i];
                fin[nfin++] = h->i;
                t->done = 1;
                t->s.got = h->got;
                if (!last) t->in_batch = 0;   /* past its clock budget: tb_span_run says why */
            } else if (keep++ != k) {
                act[keep - 1] = *h;
            }
        }
        active = keep;
        sim_batch_cycle(b);
        /* the last edge's settling belongs to the lane's run too */
        for (uint32_t k = 0; k < nfin; k++) {
            lane_tb *t = &T[fin[k]];
            if (!t->in_batch) continue;
            /* the kernel's overflow counts, unless they depend on its delta cycles */
            if (sim_batch_ovf_unsure(b, t->lane)) { t->in_batch = 0; continue; }
            tb_span_stats *st = &L[fin[k]].st;
            st->clocks = t->s.last_pixel - t->s.drv.first_accept;
            st->pixels = t->s.got;
            st->overflows = t->s.drv.in_ovf + const_ovf;
            for (uint32_t i = 0, ns = sim_signal_count(c); i < ns; i++)
                st->overflows += sim_batch_ovf_used(b, sim_signal_at(c, i))[t->lane];
            st->area_ge = area;
            if (L[fin[k]].energy) {
                lane_count lc = { b, t->lane };
                st->energy_pj = tb_energy_pj(c, sc, lane_toggles, &lc, t->s.last_pixel, &st->toggles);
            }
        }
    }
    if (!fin || !act) for (size_t i = 0; i < n; i++) T[i].in_batch = 0;
    free(act);
    free(fin);
    sim_batch_free(b);
    sim_free(c);
}

void tb_span_run_lanes(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                       tb_span_lane *L, size_t n, int batch)
{
    tb_span_run_lanes_budget(u, cfg, f, L, n, batch, INFINITY);
}

void tb_span_run_lanes_budget(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                              tb_span_lane *L, size_t n, int batch, double max_se)
{
    lane_tb *T = batch && n ? calloc(n, sizeof *T) : NULL;
    uint32_t nb = 0;
    int energy = 0;
    for (size_t i = 0; i < n; i++) energy |= L[i].energy;
    for (size_t i = 0; i < n && T; i++) {
        L[i].rc = TB_OK;
        L[i].err[0] = 0;
        L[i].stopped = 0;
        /* bad input and empty streams: tb_span_run's answer as it is */
        if (nb >= SIM_BATCH_MAX_LANES || !L[i].nitems
            || prepare(u, cfg, f, L[i].items, L[i].nitems, &T[i].s, &L[i].st, L[i].err, sizeof L[i].err))
            continue;
        T[i].in_batch = 1;
        T[i].lane = nb++;
    }
    if (nb) run_batch(u, cfg, f, L, T, n, nb, energy, max_se);
    for (size_t i = 0; i < n; i++) {
        if (T && T[i].in_batch) { L[i].batched = 1; continue; }
        if (T && L[i].stopped) { L[i].batched = 1; continue; }   /* failed: nothing to simulate again */
        L[i].batched = 0;
        L[i].rc = span_run(u, cfg, f, L[i].items, L[i].nitems, L[i].pix, &L[i].st, NULL, L[i].energy, L[i].err,
                           sizeof L[i].err);
    }
    free(T);
}
