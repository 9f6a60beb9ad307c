/* tb_batch.c - tb_run's testbench over lanes of sim_batch (tb_batch.h).
 *
 * The driver (tb_drive.h, a lane's vector rows as its source) and the
 * monitor do per lane, from the values before each edge, what tb_run's
 * processes do: offer the next item once the unit accepted the last
 * (valid and ready before the edge), record each beat the unit marks
 * valid, with the clock it came in. */
#include "testbench/tb_batch.h"
#include "base/base_out.h"
#include "sim/sim_batch.h"
#include "testbench/tb_range.h"
#include "testbench/tb_energy.h"
#include "testbench/tb_drive.h"
#include <stdlib.h>
#include <string.h>

/* A lane's driver (tb_drive.h) quantizes each row as it offers it, as
 * tb_run does (tb_prep's first step), and counts its overflows once (a
 * lane that stops short, or whose overflow counts the batch cannot tell,
 * goes to the kernel, which counts them again); no quantized copy of the
 * vectors is kept. */
typedef struct lane_st {
    size_t   got, total;
    uint64_t budget;        /* tb_run's clock budget */
    int      done;
    tb_drive drv;
} lane_st;

/* The handshake signals' lanes that are high (bit k%64 of word k/64),
 * and the lanes still running: the driver and monitor act where these
 * say, not in every lane at every edge. */
typedef struct hs {
    size_t   nw;
    uint64_t iv[SIM_BATCH_MAX_LANES / 64], ir[SIM_BATCH_MAX_LANES / 64], ov[SIM_BATCH_MAX_LANES / 64];
    uint64_t live[SIM_BATCH_MAX_LANES / 64];
} hs;

/* m's bits from s's values: in every lane (all), or in the lanes s
 * changed in at the last edge. */
static void hs_lanes(uint64_t *m, const sim_batch *b, const sim_signal *s, size_t n, size_t nw, int all)
{
    const int64_t *v = sim_batch_val(b, s);
    const uint64_t *chg = sim_batch_changed(b, s);
    int uni = sim_batch_uniform(b, s);   /* lanes in step: lane 0 says it for all */
    for (size_t w = 0; w < nw; w++) {
        uint64_t c = all ? (w + 1 < nw || n % 64 == 0 ? UINT64_MAX : ((uint64_t)1 << (n % 64)) - 1) : chg[w];
        uint64_t set = 0;
        if (uni) set = v[0] ? c : 0;
        else
            for (uint64_t x = c; x; x &= x - 1) {
                unsigned l = (unsigned)__builtin_ctzll(x);
                set |= (uint64_t)(v[w * 64 + l] != 0) << l;
            }
        m[w] = (m[w] & ~c) | set;
    }
}

static void hs_update(hs *h, const sim_batch *b, const unit_io *io, size_t n, int all)
{
    hs_lanes(h->iv, b, io->in_valid, n, h->nw, all);
    hs_lanes(h->ir, b, io->in_ready, n, h->nw, all);
    hs_lanes(h->ov, b, io->out_valid, n, h->nw, all);
}

/* Lane k from tb_run (the kernel). */
static int from_kernel(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, tb_batch_lane *L,
                       char *err, size_t errlen)
{
    tb_result r;
    int rc = tb_run(u, cfg, fm, L->vs, NULL, &r, err, errlen);
    if (rc != TB_OK) return rc;
    free(L->raw);
    free(L->beat_cycle);
    L->raw = r.raw;
    L->beat_cycle = r.beat_cycle;
    r.raw = NULL;
    r.beat_cycle = NULL;
    L->clocks = r.stats.clocks;
    L->overflows = r.overflows - r.in_overflows;
    L->in_overflows = r.in_overflows;
    L->batched = 0;
    if (L->energy) {
        free(L->sig_toggles);
        L->sig_toggles = malloc((size_t)(r.nsigs ? r.nsigs : 1) * sizeof *L->sig_toggles);
        if (!L->sig_toggles) base_out_of_memory();
        for (int i = 0; i < r.nsigs; i++) L->sig_toggles[i] = r.sigs[i].toggles;
        L->nsig = r.nsigs;
        L->toggles = r.ppa.toggles;
        L->energy_pj_per_item = r.ppa.energy_pj_per_item;
    }
    tb_result_free(&r);
    return TB_OK;
}

/* One lane's counts of the batch, for tb_energy_pj. */
typedef struct lane_count { const sim_batch *b; uint32_t lane; } lane_count;
static uint64_t lane_toggles(const sim_signal *s, void *data)
{
    const lane_count *x = data;
    const uint64_t *t = sim_batch_toggles(x->b, s);
    return t ? t[x->lane] : 0;
}

/* Lane k's toggles per signal (tb_range's signals: tb_run's r->sigs),
 * their sum and the energy per item, from the batch's counts. */
static int lane_energy(const sim_batch *b, sim_ctx *c, const sim_scope *sc, const sim_signal *clk,
                       tb_batch_lane *L, uint32_t k)
{
    tb_range g;
    if (tb_range_init(&g, c, sc, clk)) { tb_range_free(&g); return -1; }
    free(L->sig_toggles);
    L->sig_toggles = malloc((size_t)(g.nsmp ? g.nsmp : 1) * sizeof *L->sig_toggles);
    if (!L->sig_toggles) { tb_range_free(&g); return -1; }
    for (int i = 0; i < g.nsmp; i++) L->sig_toggles[i] = sim_batch_toggles(b, g.smp[i])[k];
    L->nsig = g.nsmp;
    lane_count x = { b, k };
    double pj = tb_energy_pj(c, sc, lane_toggles, &x, L->clocks, &L->toggles);
    L->energy_pj_per_item = L->vs->n_rows ? pj / (double)L->vs->n_rows : 0;
    tb_range_free(&g);
    return 0;
}

/* Lane k's overflows on used values, every signal's summed. */
static uint64_t lane_overflows(const sim_batch *b, const sim_ctx *c, uint32_t k)
{
    uint64_t n = 0;
    for (uint32_t i = 0, ns = sim_signal_count(c); i < ns; i++) n += sim_batch_ovf_used(b, sim_signal_at(c, i))[k];
    return n;
}

int tb_batch_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm,
                 tb_batch_lane *lanes, size_t n, char *err, size_t errlen)
{
    if (n < 1 || n > SIM_BATCH_MAX_LANES) { snprintf(err, errlen, "%zu lanes: 1 to %d", n, SIM_BATCH_MAX_LANES); return TB_BADINPUT; }
    int n_in = unit_n_in(u), n_out = unit_n_out(u), beats = u->beats(cfg);
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(u, cfg, &hdr);
    for (size_t k = 0; k < n; k++) {
        const vec_set *vs = lanes[k].vs;
        if (strcmp(vs->unit, hdr.unit) || vs->n_in != hdr.n_in || vs->n_out != hdr.n_out || !vs->n_rows) {
            snprintf(err, errlen, "lane %zu: vectors are not %s's (or empty)", k, u->name);
            return TB_BADINPUT;
        }
    }
    tb_built bu;
    int unbuilt = tb_build(u, cfg, fm, &bu, err, errlen);
    sim_ctx *c = bu.c;
    sim_signal *clk = bu.clk;
    sim_scope *sc = bu.sc;
    unit_io io = bu.io;
    sim_batch *b = NULL;
    lane_st *S = calloc(n, sizeof *S);
    int rc = TB_OK;
    if (!S) base_out_of_memory();
    if (unbuilt) { rc = TB_BADINPUT; goto done; }
    if (!(b = sim_batch_new(c, clk, (uint32_t)n, err, errlen))) { rc = TB_UNSUPPORTED; goto done; }
    int energy = 0;
    for (size_t k = 0; k < n; k++) energy |= lanes[k].energy;
    if ((energy && sim_batch_toggles_on(b)) || sim_batch_overflows_on(b)) base_out_of_memory();
    uint64_t const_ovf = tb_scope_overflows(sc);
    size_t nv = (size_t)beats * (size_t)n_out;
    tb_drive_lanes dw;      /* the drivers' writes */
    dw.valid = sim_batch_next(b, io.in_valid);
    const int64_t *out[UNIT_MAX_IO];
    for (int i = 0; i < n_in; i++) dw.in[i] = sim_batch_next(b, io.in[i]);
    for (int o = 0; o < n_out; o++) out[o] = sim_batch_val(b, io.out[o]);
    sim_fx_conv cv[UNIT_MAX_IO];   /* each input port's quantization */
    for (int i = 0, k = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_IN) sim_fx_conv_init(&cv[k++], fm->f[i], cfg->rnd, cfg->ovf);
    for (size_t k = 0; k < n; k++) {
        tb_batch_lane *L = &lanes[k];
        tb_drive_rows(&S[k].drv, n_in, L->vs, cv);
        S[k].total = L->vs->n_rows * (size_t)beats;
        S[k].budget = 1000 + S[k].total * 4096;
        L->raw = calloc(L->vs->n_rows * nv, sizeof *L->raw);
        L->beat_cycle = calloc(S[k].total, sizeof *L->beat_cycle);
        if (!L->raw || !L->beat_cycle) base_out_of_memory();
        tb_drive_lane_offer(&S[k].drv, &dw, (uint32_t)k);   /* the driver's run at initialization */
    }
    sim_batch_start(b);
    size_t active = n;
    uint64_t e = 0, first_budget = UINT64_MAX;   /* no lane is looked at for its budget before */
    for (size_t k = 0; k < n; k++) if (S[k].budget < first_budget) first_budget = S[k].budget;
    hs h = { .nw = (n + 63) / 64 };
    for (size_t k = 0; k < n; k++) h.live[k >> 6] |= (uint64_t)1 << (k & 63);
    hs_update(&h, b, &io, n, 1);
    while (active) {
        e++;
        size_t nfin = 0;
        uint64_t fired = 0;
        for (size_t w = 0; w < h.nw; w++) {
            /* monitor (the cycle that just ended) and driver, in the
             * lanes where they act: out_valid high; in_valid and in_ready
             * high (the driver runs in a lane the monitor just finished too) */
            uint64_t mon = h.ov[w] & h.live[w], fire = h.iv[w] & h.ir[w] & h.live[w];
            fired |= fire;
            while (mon) {
                size_t k = w * 64 + (size_t)__builtin_ctzll(mon);
                mon &= mon - 1;
                lane_st *s = &S[k];
                tb_batch_lane *L = &lanes[k];
                L->beat_cycle[s->got] = e - 1;
                for (int o = 0; o < n_out; o++) L->raw[s->got * (size_t)n_out + (size_t)o] = out[o][k];
                if (++s->got == s->total) { s->done = 1; nfin++; L->clocks = e; h.live[w] &= ~((uint64_t)1 << (k & 63)); }
            }
            while (fire) {
                size_t k = w * 64 + (size_t)__builtin_ctzll(fire);
                fire &= fire - 1;
                tb_drive_lane_accept(&S[k].drv, &dw, (uint32_t)k, e);
            }
        }
        if (fired) {   /* what the driver wrote: the edge compares those inputs alone */
            sim_batch_mark(b, io.in_valid);
            for (int i = 0; i < n_in; i++) sim_batch_mark(b, io.in[i]);
        }
        /* tb_run's budget: past it the kernel says what went wrong */
        if (e >= first_budget)
            for (size_t k = 0; k < n; k++)
                if (!S[k].done && e >= S[k].budget) { S[k].done = 2; nfin++; h.live[k >> 6] &= ~((uint64_t)1 << (k & 63)); }
        sim_batch_cycle(b);
        hs_update(&h, b, &io, n, 0);
        if (!nfin) continue;
        active -= nfin;
        for (size_t k = 0; k < n; k++)
            if (S[k].done == 1 && lanes[k].clocks == e) {
                /* the kernel's counts (sim_batch_ovf.c), unless they depend on its delta cycles */
                lanes[k].batched = !sim_batch_ovf_unsure(b, (uint32_t)k);
                lanes[k].overflows = const_ovf + lane_overflows(b, c, (uint32_t)k);
                /* counted through the last edge's settling, where tb_run stops */
                if (energy && lanes[k].batched && lane_energy(b, c, sc, clk, &lanes[k], (uint32_t)k))
                    base_out_of_memory();
            }
    }
    for (size_t k = 0; k < n; k++) lanes[k].in_overflows = S[k].drv.in_ovf;
    for (size_t k = 0; k < n && rc == TB_OK; k++)
        if (!lanes[k].batched) rc = from_kernel(u, cfg, fm, &lanes[k], err, errlen);
done:
    free(S);
    sim_batch_free(b);
    sim_free(c);
    return rc;
}
