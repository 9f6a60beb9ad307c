/* tb_lanes.c - one stream of items on the batch's lanes (tb_lanes.h).
 *
 * Lane k drives items [from - warm, end) from reset, with tb_run's driver
 * (tb_drive.h) and monitor (tb_batch.c's, per lane): offer the next item
 * once the unit accepted the last, record each beat the unit marks valid.
 * Its junction
 * in is the edge at which it offers item `from`, its junction out the one
 * at which it offers `end` (the next lane's `from`). What the kernel does
 * at an edge (sample the values before it, collect a beat, offer an item)
 * belongs to the lane whose piece holds that edge: the junction out's to
 * lane k, edges after the junction in to lane k + 1 (the two edges are
 * the same edge of the stream).
 */
#include "testbench/tb_lanes.h"
#include "sim/sim_batch.h"
#include "testbench/tb_drive.h"
#include <stdlib.h>
#include <string.h>

/* Lanes of at least this many items of their own: the warm-up is paid
 * once per lane. */
#define LANES_MIN_ITEMS 32
#define LANES_MAX       64
/* Items before a lane's own, from reset: enough for most units' items
 * in flight; a unit that needs more fails the junction check, and is run
 * again with the long warm-up (a deep pipeline: shade's, norm3's), then
 * on the kernel. */
#define LANES_WARM      16
#define LANES_WARM_LONG 128

typedef struct lane {
    size_t   begin, from, end;  /* items driven: [begin, end); its own from `from` */
    size_t   got;               /* beats collected, counted from begin's first */
    int      phase;             /* 0 warm-up, 1 its piece, 2 done */
    uint64_t e_in, e_out;       /* the junction edges (lane 0: 0, and its last edge) */
    size_t   beat_in, beat_out; /* stream beats before its piece, and at its end */
    int64_t  *state_in, *state_out;   /* every signal's value at the junctions */
    uint64_t *tog_in, *tog_out;       /* each logged signal's toggles at the junctions */
    int64_t  *mn, *mx;                /* each live signal's range over its piece */
    uint64_t *ovf_in, *ovf_out;       /* every signal's overflows (used, then discarded) at the junctions */
    uint64_t unsure_in, unsure_out;   /* the batch's unsure steps at the junctions (sim_batch_ovf_unsure) */
    tb_drive drv;               /* the driver (tb_drive.h): items [begin, end) of the inputs */
} lane;

static void snap_state(const sim_batch *b, const sim_ctx *c, uint32_t l, int64_t *to)
{
    for (uint32_t i = 0, n = sim_signal_count(c); i < n; i++) to[i] = sim_batch_val(b, sim_signal_at(c, i))[l];
}

static void snap_tog(const sim_batch *b, const tb_range *g, uint32_t l, uint64_t *to)
{
    for (int i = 0; i < g->nsmp; i++) to[i] = sim_batch_toggles(b, g->smp[i])[l];
}

/* every signal's overflow counts, used then discarded (2 nsig), and the
 * steps whose counts the batch cannot tell */
static void snap_ovf(const sim_batch *b, const sim_ctx *c, uint32_t l, uint64_t *to, uint64_t *unsure)
{
    uint32_t n = sim_signal_count(c);
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = sim_signal_at(c, i);
        to[i] = sim_batch_ovf_used(b, s)[l];
        to[n + i] = sim_batch_ovf_discarded(b, s)[l];
    }
    *unsure = sim_batch_ovf_unsure(b, l);
}

static void snap_range(const sim_batch *b, const tb_range *g, uint32_t l, int64_t *mn, int64_t *mx)
{
    for (int i = 0; i < g->nlive; i++) sim_batch_range(b, g->lv[i].sig, l, &mn[i], &mx[i]);
}

/* Lane k of L drives items [begin, end) of the n: its own piece
 * [from, end) after `warm` items of warm-up (lane 0 none; a lane whose
 * piece starts earlier starts from the stream's first item, as the
 * stream does). -1: out of memory. */
static int lanes_init(const tb_lanes_job *j, lane *S, size_t L, uint32_t nsig, const tb_range *g, size_t warm)
{
    size_t n = j->n_items;
    for (size_t k = 0; k < L; k++) {
        lane *s = &S[k];
        s->from = k * n / L;
        s->end = (k + 1) * n / L;
        s->begin = k && s->from > warm ? s->from - warm : 0;
        /* the source ends at the lane's end: valid drops past it */
        tb_drive_raws(&s->drv, j->n_in, j->in_raw, s->end);
        s->drv.next = s->begin;
        s->phase = k ? 0 : 1;
        s->state_in = malloc(((size_t)nsig + 1) * sizeof *s->state_in);
        s->state_out = malloc(((size_t)nsig + 1) * sizeof *s->state_out);
        s->tog_in = calloc((size_t)g->nsmp + 1, sizeof *s->tog_in);
        s->tog_out = calloc((size_t)g->nsmp + 1, sizeof *s->tog_out);
        s->mn = malloc(((size_t)g->nlive + 1) * sizeof *s->mn);
        s->mx = malloc(((size_t)g->nlive + 1) * sizeof *s->mx);
        s->ovf_in = calloc(2 * (size_t)nsig + 1, sizeof *s->ovf_in);    /* lane 0: from the start */
        s->ovf_out = calloc(2 * (size_t)nsig + 1, sizeof *s->ovf_out);
        if (!s->state_in || !s->state_out || !s->tog_in || !s->tog_out || !s->mn || !s->mx || !s->ovf_in || !s->ovf_out)
            return -1;
    }
    return 0;
}

/* The L lanes side by side until each has driven its piece (the last
 * lane: until the stream's last beat), their beats' cycles and outputs
 * into j and their junction states, toggles and ranges into S. 1 if a
 * lane gave no answer in time. */
static int lanes_simulate(tb_lanes_job *j, sim_batch *b, lane *S, size_t L)
{
    size_t n = j->n_items, beats = (size_t)j->beats, nout = (size_t)j->n_out;
    tb_range *g = j->rg;
    tb_drive_lanes w;
    w.valid = sim_batch_next(b, j->io->in_valid);
    const int64_t *out[UNIT_MAX_IO];
    for (int i = 0; i < j->n_in; i++) w.in[i] = sim_batch_next(b, j->io->in[i]);
    for (size_t o = 0; o < nout; o++) out[o] = sim_batch_val(b, j->io->out[o]);
    for (size_t k = 0; k < L; k++) tb_drive_lane_offer(&S[k].drv, &w, (uint32_t)k);
    sim_batch_start(b);
    for (size_t k = 0; k < L; k++) sim_batch_range_reset(b, (uint32_t)k);   /* lane 0's piece starts here */
    const int64_t *iv = sim_batch_val(b, j->io->in_valid), *ir = sim_batch_val(b, j->io->in_ready);
    const int64_t *ov = sim_batch_val(b, j->io->out_valid);
    size_t active = L, total = n * beats;
    uint64_t e = 0, budget = 1000 + (uint64_t)total * 4096;
    int late = 0;
    while (active) {
        e++;
        for (size_t k = 0; k < L; k++) {
            lane *s = &S[k];
            if (s->phase == 2) continue;
            /* monitor: the cycle that just ended */
            if (ov[k]) {
                size_t at = s->begin * beats + s->got;
                if (s->phase == 1 && at < total) {
                    j->beat_cycle[at] = e - 1;
                    for (size_t o = 0; o < nout; o++) j->raw[at * nout + o] = out[o][k];
                }
                s->got++;
                if (k == L - 1 && at + 1 == total) {
                    /* the stream's last beat: tb_run stops after this edge, its driver's
                     * writes at it taken (a combinational unit's valid falls) */
                    s->phase = 2;
                    s->e_out = e;
                    s->beat_out = total;
                    snap_range(b, g, (uint32_t)k, s->mn, s->mx);
                    snap_ovf(b, j->c, (uint32_t)k, s->ovf_out, &s->unsure_out);
                    active--;
                    if (iv[k] && ir[k]) tb_drive_lane_accept(&s->drv, &w, (uint32_t)k, e);
                    continue;
                }
            }
            /* driver */
            if (iv[k] && ir[k]) {
                /* the accept; the offer after the junctions' snapshots */
                s->drv.next++;
                if (s->phase == 0 && s->drv.next == s->from) {
                    s->phase = 1;
                    s->e_in = e;
                    s->beat_in = s->begin * beats + s->got;
                    snap_state(b, j->c, (uint32_t)k, s->state_in);
                    snap_tog(b, g, (uint32_t)k, s->tog_in);
                    snap_ovf(b, j->c, (uint32_t)k, s->ovf_in, &s->unsure_in);
                    sim_batch_range_reset(b, (uint32_t)k);
                } else if (s->phase == 1 && k < L - 1 && s->drv.next == s->end) {
                    s->phase = 2;
                    s->e_out = e;
                    s->beat_out = s->begin * beats + s->got;
                    snap_state(b, j->c, (uint32_t)k, s->state_out);
                    snap_tog(b, g, (uint32_t)k, s->tog_out);
                    snap_ovf(b, j->c, (uint32_t)k, s->ovf_out, &s->unsure_out);
                    snap_range(b, g, (uint32_t)k, s->mn, s->mx);
                    active--;
                    continue;
                }
                tb_drive_lane_offer(&s->drv, &w, (uint32_t)k);
            }
            if (e >= budget) { late = 1; s->phase = 2; active--; }
        }
        sim_batch_cycle(b);
    }
    /* the last lane's toggles through the last edge's settling, where tb_run stops */
    snap_tog(b, g, (uint32_t)(L - 1), S[L - 1].tog_out);
    snap_ovf(b, j->c, (uint32_t)(L - 1), S[L - 1].ovf_out, &S[L - 1].unsure_out);
    return late;
}

/* Whether the pieces join into the one-lane run: every piece's overflow
 * counts sure, and each lane's state at its junction in is its
 * predecessor's at its junction out (else the warm-up was too short). 0,
 * or 1 with why. */
static int lanes_check(const lane *S, size_t L, uint32_t nsig, size_t warm, char *why, size_t len)
{
    for (size_t k = 0; k < L; k++)
        if (S[k].unsure_out != S[k].unsure_in) {
            snprintf(why, len, "an overflow whose count depends on the kernel's delta cycles (a glitch may rerun its element)");
            return 1;
        }
    for (size_t k = 1; k < L; k++) {
        const lane *p = &S[k - 1], *s = &S[k];
        if (p->beat_out != s->beat_in || memcmp(p->state_out, s->state_in, (size_t)nsig * sizeof *s->state_in)) {
            snprintf(why, len, "item %zu depends on more than the %zu items before it", s->from, warm);
            return 2;
        }
    }
    return 0;
}

/* The pieces joined: each piece's clocks shifted by the stream's before
 * it, the toggles summed, the live signals' ranges joined. */
static void lanes_join(tb_lanes_job *j, const lane *S, size_t L)
{
    tb_range *g = j->rg;
    uint64_t at_edge = 0;       /* the stream's edge at lane k's junction in */
    for (size_t k = 0; k < L; k++) {
        const lane *s = &S[k];
        for (size_t x = s->beat_in; x < s->beat_out; x++) j->beat_cycle[x] += at_edge - s->e_in;
        at_edge += s->e_out - s->e_in;
    }
    j->clocks = at_edge;
    for (int i = 0; i < g->nsmp; i++) {
        uint64_t t = 0;
        for (size_t k = 0; k < L; k++) t += S[k].tog_out[i] - S[k].tog_in[i];
        j->toggles[i] = t;
    }
    for (int i = 0; i < g->nlive; i++) {
        int64_t lo = S[0].mn[i], hi = S[0].mx[i];
        for (size_t k = 1; k < L; k++) {
            if (S[k].mn[i] < lo) lo = S[k].mn[i];
            if (S[k].mx[i] > hi) hi = S[k].mx[i];
        }
        g->lv[i].lo = lo;
        g->lv[i].span = (uint64_t)hi - (uint64_t)lo;
    }
    g->sampled = 1;
    /* every signal's overflows, each piece's between its junctions, onto
     * what the design holds from its build (its constants') */
    uint32_t nsig = sim_signal_count(j->c);
    for (uint32_t i = 0; i < nsig; i++) {
        uint64_t u = 0, x = 0;
        for (size_t k = 0; k < L; k++) {
            u += S[k].ovf_out[i] - S[k].ovf_in[i];
            x += S[k].ovf_out[nsig + i] - S[k].ovf_in[nsig + i];
        }
        sim_signal *s = sim_signal_at(j->c, i);
        s->overflows += u;
        s->ovf_discarded += x;
    }
    j->lanes = (uint32_t)L;
}

/* One try with a warm-up of `warm` items: 0 done, 2 the warm-up was too
 * short, 1 not taken, -1 out of memory. */
static int lanes_try(tb_lanes_job *j, size_t warm, char *why, size_t len)
{
    size_t n = j->n_items;
    size_t L = n / LANES_MIN_ITEMS;
    if (L > LANES_MAX) L = LANES_MAX;
    if (L >= 8) L &= ~(size_t)7;        /* the vector loops take multiples of their width */
    if (L < 2) { snprintf(why, len, "%zu items: too few for lanes", n); return 1; }
    char err[300];
    sim_batch *b = sim_batch_new(j->c, j->clk, (uint32_t)L, err, sizeof err);
    if (!b) { snprintf(why, len, "%s", err); return 1; }
    uint32_t nsig = sim_signal_count(j->c);
    lane *S = calloc(L, sizeof *S);
    int rc = -1;
    if (!S || sim_batch_ranges_on(b) || sim_batch_overflows_on(b) || lanes_init(j, S, L, nsig, j->rg, warm)) goto done;
    rc = 1;
    if (lanes_simulate(j, b, S, L)) { snprintf(why, len, "a lane gave no answer in time"); goto done; }
    if ((rc = lanes_check(S, L, nsig, warm, why, len)) != 0) goto done;
    lanes_join(j, S, L);
    rc = 0;
done:
    if (S)
        for (size_t k = 0; k < L; k++) {
            free(S[k].state_in); free(S[k].state_out); free(S[k].tog_in); free(S[k].tog_out);
            free(S[k].mn); free(S[k].mx); free(S[k].ovf_in); free(S[k].ovf_out);
        }
    free(S);
    sim_batch_free(b);
    return rc;
}

int tb_lanes_run(tb_lanes_job *j, char *why, size_t len)
{
    int rc = lanes_try(j, LANES_WARM, why, len);
    if (rc == 2) {
        /* the pieces did not join: a deep pipeline, again with the long warm-up
         * (the ranges start over: tb_range_init's state, as the first try found it) */
        rc = lanes_try(j, LANES_WARM_LONG, why, len);
    }
    return rc == 2 ? 1 : rc;
}
