/* tb_span.c - a stream of intervals of any length through a span unit
 * (tb_span.h): one build, a driver that offers item after item through
 * the valid/ready handshake, a monitor that collects the n beats of each.
 *
 * Nothing is allocated per item or per clock: the driver quantizes an
 * item's inputs when it first offers it, the monitor writes pixels straight
 * into the caller's array. */
#include "testbench/tb_span.h"
#include "testbench/tb.h"
#include "testbench/tb_range.h"
#include "sim/sim_vcd.h"
#include "sim/sim_out.h"
#include <math.h>
#include <string.h>

enum { IN_NODE = 0, IN_N = 4, IN_DV = 5, IN_DEG = 6 };

typedef struct span_tb {
    const unit_io *io;
    const unit_cfg *cfg;
    const tb_span_item *items;
    size_t nitems, next, offered;   /* offered: the item on the inputs (nitems: none yet) */
    int started;
    int nin;
    int what[UNIT_MAX_IO];          /* IN_NODE + i, IN_N, IN_DV, IN_DEG per input port */
    sim_fmt fmt[UNIT_MAX_IO];
    uint64_t in_ovf, first_accept, last_pixel;
    const sim_ctx *ctx;
    /* monitor */
    const sim_signal *y;
    double lsb;
    double *pix;
    size_t got, total;
} span_tb;

static void offer(span_tb *s, size_t i)
{
    const tb_span_item *it = &s->items[i];
    for (int p = 0; p < s->nin; p++) {
        int w = s->what[p];
        double v = w < IN_N ? it->node[w] : w == IN_N ? it->n : w == IN_DV ? it->dv : it->deg;
        int ov = 0;
        sim_write(s->io->in[p], sim_fx_from_real(v, s->fmt[p], s->cfg->rnd, s->cfg->ovf, &ov));
        s->in_ovf += (uint64_t)ov;
    }
    s->offered = i;
}

/* At each rising edge: the offered item was accepted if valid and ready
 * held before the edge; then offer the next. */
static void driver(sim_proc *p)
{
    span_tb *s = p->data;
    const unit_io *io = s->io;
    if (s->started && io->in_valid->cur && io->in_ready->cur) {
        if (s->next == 0) s->first_accept = sim_get_stats(s->ctx)->clocks;
        s->next++;
    }
    s->started = 1;
    if (s->next < s->nitems) {
        if (s->offered != s->next) offer(s, s->next);
        sim_write(io->in_valid, 1);
    } else {
        sim_write(io->in_valid, 0);
    }
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

/* Map the unit's input ports to item fields; 0, or -1 if it is not a span
 * unit. */
static int map_inputs(const unit_desc *u, span_tb *s, const unit_fmts *f)
{
    int k = 0, has_n = 0, has_dv = 0;
    for (int i = 0; i < u->nsigs && k < UNIT_MAX_IO; i++) {
        const char *nm = u->sigs[i].name;
        if (u->sigs[i].role != UNIT_SIG_IN) continue;
        if (nm[0] == 'i' && nm[1] >= '1' && nm[1] <= '4' && !nm[2]) s->what[k] = IN_NODE + (nm[1] - '1');
        else if (!strcmp(nm, "n")) { s->what[k] = IN_N; has_n = 1; }
        else if (!strcmp(nm, "dv")) { s->what[k] = IN_DV; has_dv = 1; }
        else if (!strcmp(nm, "deg")) s->what[k] = IN_DEG;
        else return -1;
        s->fmt[k++] = f->f[i];
    }
    s->nin = k;
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

int tb_span_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                const tb_span_item *items, size_t nitems, double *pix,
                tb_span_stats *st, const char *vcd_path, char *err, size_t errlen)
{
    memset(st, 0, sizeof *st);
    span_tb s;
    memset(&s, 0, sizeof s);
    if (!u || map_inputs(u, &s, f)) {
        snprintf(err, errlen, "unit %s is not a span unit (inputs i1.., n, dv)", u ? u->name : "(none)");
        return TB_BADINPUT;
    }
    if (cfg->L < 2 || cfg->L > 64) { snprintf(err, errlen, "%s: L = %d is outside 2..64", u->name, cfg->L); return TB_BADINPUT; }
    int has_deg = 0;
    for (int p = 0; p < s.nin; p++) has_deg |= s.what[p] == IN_DEG;
    size_t total = 0;
    for (size_t i = 0; i < nitems; i++) {
        if (check_item(&items[i], i, cfg->L, has_deg, err, errlen)) return TB_BADINPUT;
        total += (size_t)items[i].n;
        st->items_deg2 += has_deg && items[i].deg == 2;
    }
    st->items = nitems;
    if (!nitems) return TB_OK;

    sim_ctx *c = sim_new();
    sim_set_quant(c, cfg->rnd, cfg->ovf);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *sc = sim_scope_new(c, NULL, u->name);
    unit_io io;
    memset(&io, 0, sizeof io);
    int rc = TB_OK;
    sim_vcd *vcd = NULL;
    sim_out *vout = NULL;
    if (u->build(c, sc, clk, cfg, f, &io, err, errlen)) { rc = TB_BADINPUT; goto done; }
    sim_clock(c, clk, 5, 5);
    s.io = &io; s.cfg = cfg; s.items = items; s.nitems = nitems; s.offered = nitems; s.ctx = c;
    s.y = io.out[0];
    s.lsb = ldexp(1.0, -io.out[0]->fmt.fbits);
    s.pix = pix; s.total = total;
    sim_proc *drv = sim_proc_new(c, "tb.driver", driver, &s);
    sim_sensitive(drv, clk, SIM_EDGE_POS);
    sim_proc *mon = sim_proc_new(c, "tb.monitor", monitor, &s);
    sim_sensitive(mon, clk, SIM_EDGE_POS);
    mon->no_init = 1;
    if (vcd_path) {
        /* A dump can be hundreds of MB: sim_out writes it to a temporary
         * that SIGINT/SIGTERM/SIGHUP remove, renamed into place when
         * complete; "-" streams to stdout. */
        if (!(vout = sim_out_open(vcd_path, err, errlen))) { rc = TB_BADINPUT; goto done; }
        if (!(vcd = sim_vcd_open(c, sim_out_file(vout), "1ns"))) {
            snprintf(err, errlen, "%s: out of memory", vcd_path);
            rc = TB_BADINPUT;
            goto done;
        }
    }
    /* 6 clocks a pixel at most (paper, cubic), a few per item; a unit that
     * stops answering is a failure, not a hang. */
    uint64_t max_clocks = 1000 + 8 * (uint64_t)total + 8 * (uint64_t)nitems;
    sim_status ss = sim_run(c, max_clocks * 10);
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
        bad |= sim_out_close(vout, msg, sizeof msg);
        if (bad && rc == TB_OK) {
            snprintf(err, errlen, "%s: write failed", vcd_path);
            rc = TB_BADINPUT;
        }
        vcd = NULL;
        vout = NULL;
    }
    if (rc == TB_OK) st->clocks = s.last_pixel - s.first_accept;
    st->pixels = s.got;
    st->overflows = s.in_ovf + tb_scope_overflows(sc);
    st->area_ge = sim_scope_area(sc);
done:
    if (vcd) sim_vcd_abort(vcd);
    if (vout) sim_out_abort(vout);
    sim_free(c);
    return rc;
}
