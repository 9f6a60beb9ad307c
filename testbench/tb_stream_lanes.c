/* tb_stream_lanes.c - tb_run_stream on the batch's lanes (tb_stream.h): a
 * vector file or a pipe of any length, read a block at a time, its items
 * simulated a wave at a time (tb_lanes.h), memory independent of its
 * length.
 *
 * A wave: the rows read (the first block alone, the second too, then
 * twice the blocks each wave up to a wave's items; with more than one
 * thread, the next wave's read on a thread of its own meanwhile: the
 * threads are base_pool's, made once), each item prepared (tb_prep: the quantized inputs,
 * what the unit should give) on the threads, the wave's pieces simulated
 * side by side and joined to the stream, then every item whose beats are
 * all in folded into the metrics in item order (tb_acc: the sums added in
 * the same order as the kernel's run, so the same bytes) and handed to the
 * caller (--out), on a thread of its own while the next wave simulates.
 * So there are two buffers, used in turn; the wave's last items are
 * copied to the front of the other one for the next wave: its first
 * lane's warm-up, and the items still in flight at the junction.
 *
 * The first wave is the first block alone, so that when the lanes do not
 * take the stream there (a unit they cannot evaluate, an overflow whose
 * count they cannot tell in the first rows), the stream can be handed back unread to the kernel, pipes
 * too.
 */
#include "testbench/tb_stream.h"
#include "testbench/tb_lanes.h"
#include "testbench/tb_energy.h"
#include "base/base_mem.h"
#include "base/base_out.h"
#include "base/base_pool.h"
#include <stdlib.h>
#include <string.h>

/* A wave takes items up to about WAVE_BYTES of their rows and prepared
 * figures (a unit with many output beats an item takes fewer), between
 * WAVE_MIN and WAVE_MAX items (256 lanes of 512), and at least the block
 * it reads. Smaller waves keep the buffers in the caches and page them in
 * less, but pay the lanes' warm-ups and the batch's costs a clock more
 * often (callgrind on 200,000 horner3 items: +0.7% instructions at 8 MB,
 * +8% at 2 MB). Here the caches win: that run took 2,900 page faults at
 * 2 MB (5,900 at 8 MB) and 0.39-0.42 of the C++ Verilator harness's time
 * (bench/verilog/run.sh's job, best of 9 interleaved at the highest
 * priority: 1 MB 0.37-0.38, 4 MB 0.45-0.47, 8 MB 0.52-0.54); 10^6 rows
 * piped, -j 1, took 0.72 s of CPU at 2 MB, 0.80 s at 8 MB. */
#define WAVE_BYTES ((size_t)2 << 20)
#define WAVE_MIN   ((size_t)1 << 12)
#define WAVE_MAX   ((size_t)1 << 17)

/* A wave's items by position in the buffer: first the items kept from
 * the wave before (own of them), then the wave's own. Their rows are not
 * copied in: the own items' are the reader's set (fresh), those kept a
 * copy of theirs (a warm-up's and the items in flight: a few hundred). */
typedef struct wbuf {
    size_t cap, own, rows_cap;
    int n_in, nv, beats, ncol;  /* ncol: a row's inputs and expected values */
    double   *rows;             /* [pos][ncol], pos < own */
    const double *fresh;        /* [pos - own][ncol], pos >= own: the reader's */
    int64_t  *in_raw;           /* [pos][n_in] */
    int64_t  *raw;              /* [pos][nv] */
    double   *ideal;            /* [pos][4][nv]: ideal, ideal_r, ideal_u, ref_u */
    sim_dy   *exact, *den, *hi; /* [pos][nv], where the unit has them */
    double   *exact_d;          /* [pos][nv], instead of exact for a unit with exact alone (tb_item) */
    unsigned char *exact_ok;    /* [pos] */
    uint64_t *cycle;            /* [pos][beat] */
} wbuf;

/* p with room for n things of size bytes, paged in (base_mem.h: the
 * waves fill it at once, and use it again) */
static void *grow(void *p, size_t n, size_t size)
{
    if (!size) return p;
    void *q = realloc(p, (n ? n : 1) * size);
    if (!q) base_out_of_memory();
    base_mem_populate(q, (n ? n : 1) * size);
    return q;
}

/* Room for cap items (kept as they are), and a quarter more: the waves
 * after the first few differ by a few hundred items (the block's rows,
 * the items carried over), which would each grow (copy) every array. */
static void wbuf_reserve(wbuf *B, size_t cap, int has_exact, int has_exact_d, int has_den, int has_hi)
{
    if (cap <= B->cap) return;
    cap += cap / 4;
    size_t nv = (size_t)B->nv;
    B->in_raw = grow(B->in_raw, cap, (size_t)B->n_in * sizeof *B->in_raw);
    B->raw = grow(B->raw, cap, nv * sizeof *B->raw);
    B->ideal = grow(B->ideal, cap, 4 * nv * sizeof *B->ideal);
    if (has_exact) B->exact = grow(B->exact, cap, nv * sizeof *B->exact);
    if (has_exact_d) B->exact_d = grow(B->exact_d, cap, nv * sizeof *B->exact_d);
    if (has_den) B->den = grow(B->den, cap, nv * sizeof *B->den);
    if (has_hi) B->hi = grow(B->hi, cap, nv * sizeof *B->hi);
    B->exact_ok = grow(B->exact_ok, cap, 1);
    B->cycle = grow(B->cycle, cap, (size_t)B->beats * sizeof *B->cycle);
    B->cap = cap;
}

static const double *wbuf_row(const wbuf *B, size_t pos)
{
    return pos < B->own ? B->rows + pos * (size_t)B->ncol : B->fresh + (pos - B->own) * (size_t)B->ncol;
}

/* Items [k, n) of F to the front of T (room for them reserved, but for
 * their rows). */
static void wbuf_tail(wbuf *T, const wbuf *F, size_t k, size_t n)
{
    size_t m = n - k, nv = (size_t)F->nv, ncol = (size_t)F->ncol;
    if (m > T->rows_cap) {
        T->rows = grow(T->rows, m, ncol * sizeof *T->rows);
        T->rows_cap = m;
    }
    for (size_t p = k, q; p < n; p = q) {   /* the rows kept, then the own ones */
        q = p < F->own && n > F->own ? F->own : n;
        memcpy(T->rows + (p - k) * ncol, wbuf_row(F, p), (q - p) * ncol * sizeof *T->rows);
    }
#define TAIL(a, per) do { if (F->a) memcpy(T->a, F->a + k * (per), m * (per) * sizeof *F->a); } while (0)
    TAIL(in_raw, (size_t)F->n_in);
    TAIL(raw, nv);
    TAIL(ideal, 4 * nv);
    TAIL(exact, nv);
    TAIL(exact_d, nv);
    TAIL(den, nv);
    TAIL(hi, nv);
    TAIL(exact_ok, (size_t)1);
    TAIL(cycle, (size_t)F->beats);
#undef TAIL
}

static void wbuf_free(wbuf *B)
{
    free(B->rows); free(B->in_raw); free(B->raw); free(B->ideal);
    free(B->exact); free(B->exact_d); free(B->den); free(B->hi); free(B->exact_ok); free(B->cycle);
}

static tb_item wbuf_item(const wbuf *B, size_t pos)
{
    size_t nv = (size_t)B->nv;
    double *id = B->ideal + pos * 4 * nv;
    tb_item it = { B->in_raw + pos * (size_t)B->n_in, id, id + nv, id + 2 * nv, id + 3 * nv,
                   B->exact ? B->exact + pos * nv : NULL, B->den ? B->den + pos * nv : NULL,
                   B->hi ? B->hi + pos * nv : NULL, B->exact_ok + pos, B->exact_d ? B->exact_d + pos * nv : NULL };
    return it;
}

/* The preparation of items [from, to) in chunks on the threads, each
 * chunk's input overflows its own (summed after: whole numbers). What a
 * chunk writes item after item (its overflow counts, its room for the
 * exact ideal) is on cache lines of its own: with two threads writing one
 * line in turn, perf counted a third more time in the preparation's
 * functions at -j 2 than at -j 1 (now a tenth to a sixth more). */
#define PREP_CHUNKS 16
/* Items below which the preparation stays on the calling thread (handing
 * chunks to other threads costs more than it saves; a stream of one such
 * wave makes no thread at all). */
#define PREP_PAR_MIN 2048
typedef struct prep_job {
    const tb_prep_ctx *pc;
    wbuf *B;
    size_t from, to;
    sim_dy *tmp;                /* [chunk][tmp_stride]: the exact ideal's room, with exact_d */
    size_t tmp_stride;
    uint64_t ovf[PREP_CHUNKS][UNIT_MAX_IO];
} prep_job;

static void prep_chunk(void *ctx, size_t c)
{
    prep_job *j = ctx;
    size_t n = j->to - j->from, a = j->from + n * c / PREP_CHUNKS, b = j->from + n * (c + 1) / PREP_CHUNKS;
    uint64_t ovf[UNIT_MAX_IO] = { 0 };
    for (size_t p = a; p < b; p++) {
        tb_item it = wbuf_item(j->B, p);
        if (j->tmp) it.exact = j->tmp + c * j->tmp_stride;
        tb_prep(j->pc, wbuf_row(j->B, p), &it, ovf);
    }
    memcpy(j->ovf[c], ovf, sizeof ovf);
}

/* Room for PREP_CHUNKS + 1 exact ideals of nv values (the chunks', then
 * the metrics'), each on cache lines of its own: *stride values apart. */
static sim_dy *tmp_alloc(size_t nv, size_t *stride)
{
    size_t st = nv;
    while ((st * sizeof(sim_dy)) % 64) st++;
    *stride = st;
    sim_dy *t = aligned_alloc(64, (PREP_CHUNKS + 1) * st * sizeof(sim_dy));
    if (!t) base_out_of_memory();
    memset(t, 0, (PREP_CHUNKS + 1) * st * sizeof(sim_dy));
    return t;
}

/* Where the stream is: its number of the item at the buffer's pos 0, and
 * the items in the buffer. */
typedef struct sl_state {
    size_t base, n;
} sl_state;

/* The metrics' side: the items whose beats are all in (beats_done of
 * the stream's), folded into the metrics and handed to the caller in
 * item order, from a wave's buffer (on a thread of its own while the next
 * wave simulates, with more than one thread). */
typedef struct folder {
    const wbuf *B;
    size_t base, beats_done;
    size_t acc_next;            /* the stream's next item for the metrics */
    uint64_t first_cycle, last_item_cycle, last_cycle;
    tb_acc *acc;
    tb_result *r;
    tb_row_fn row;
    void *row_data;
} folder;

static void fold(void *arg)
{
    folder *f = arg;
    const wbuf *B = f->B;
    size_t nb = (size_t)B->beats;
    while ((f->acc_next + 1) * nb <= f->beats_done) {
        size_t it = f->acc_next, pos = it - f->base;
        const uint64_t *cyc = B->cycle + pos * nb;
        const int64_t *raw = B->raw + pos * (size_t)B->nv;
        const double *expected = wbuf_row(B, pos) + B->n_in;
        tb_item ti = wbuf_item(B, pos);
        if (it == 0) f->first_cycle = cyc[0];
        f->last_item_cycle = cyc[0];
        f->last_cycle = cyc[nb - 1];
        tb_acc_item(f->acc, f->r, it, raw, expected, &ti);
        if (f->row) f->row(f->row_data, f->r, it, cyc[0], raw, expected);
        f->acc_next++;
    }
}

/* The rows of the next wave, read while the wave before is simulated
 * (on a thread of its own, with more than one thread): up to `blocks`
 * blocks and `most` items. The first wave is the first block alone, and
 * the second (read before anything runs beside it) the next one; then
 * twice the blocks each wave, so that the reading soon runs beside the
 * simulation, as much of it as can. A wave's rows stay in their set
 * until the wave is folded, as the next wave's are read: three sets, in
 * turn; the first block's stay in the stream's own (which later blocks,
 * appended to the sets, leave as they are). */
typedef struct reader {
    vec_stream *vs;
    size_t most, ncol;
    int blocks, calls;
    size_t block_rows;          /* the most rows a block has given */
    vec_set sets[3];            /* [n][ncol]: parsed into straight from the text (after the first block) */
    const vec_set *rows;        /* the set the last call read */
    int last, failed;           /* the file's end was read; a bad row (err) */
    char err[600];
} reader;

static void reader_run(void *arg)
{
    reader *R = arg;
    vec_set *to = &R->sets[R->calls % 3];
    R->rows = to;
    to->n_rows = 0;
    /* room for what the call reads (it stops at `most` rows, but for the
     * last block's), paged in: the parser's growth would fault it in a
     * page at a time */
    size_t want = R->most + R->block_rows;
    if (R->calls && want > to->cap_rows) {
        to->data = grow(to->data, want, R->ncol * sizeof *to->data);
        to->cap_rows = want;
    }
    R->last = R->failed = 0;
    int got = 0;
    do {
        int rc;
        if (R->calls == 0) {
            /* the first block in the stream's own set, so that it can
             * be handed back unread (and it has the header's shape) */
            const vec_set *rows;
            rc = vec_stream_next(R->vs, &rows);
            if (rc > 0) {
                for (int i = 0; i < 3; i++) { R->sets[i].n_in = rows->n_in; R->sets[i].n_out = rows->n_out; }
                R->rows = rows;
                R->block_rows = rows->n_rows;
            }
        } else {
            rc = vec_stream_append(R->vs, to);
        }
        if (rc < 0) { R->failed = 1; snprintf(R->err, sizeof R->err, "%s", vec_stream_error(R->vs)); return; }
        if (rc == 0) break;
    } while (++got < R->blocks && !vec_stream_done(R->vs) && R->rows->n_rows < R->most);
    R->last = vec_stream_done(R->vs);
    if (++R->calls >= 2 && R->blocks < (1 << 20)) R->blocks *= 2;
}

/* X's shapes, which of the exact ideal's arrays they keep, and the items
 * a wave takes. */
static size_t wave_setup(wbuf X[2], const unit_desc *u, const tb_result *r, int nv, int *has_exact, int *has_exact_d)
{
    for (int i = 0; i < 2; i++) {
        X[i].n_in = r->n_in; X[i].nv = nv; X[i].beats = r->beats; X[i].ncol = r->n_in + nv;
    }
    /* a unit with an exact ideal alone keeps its double (tb_item's
     * exact_d): 8 bytes a value instead of a sim_dy's 80 */
    *has_exact_d = u->ideal_exact && !u->ideal_ratio && !u->ideal_interval;
    *has_exact = !*has_exact_d && (u->ideal_exact || u->ideal_ratio || u->ideal_interval);
    size_t ndy = (size_t)*has_exact + !!u->ideal_ratio + !!u->ideal_interval;
    size_t per = (size_t)X[0].ncol * 8 + (size_t)X[0].n_in * 8
               + (size_t)nv * (8 + 32 + 8 * (size_t)*has_exact_d + ndy * sizeof(sim_dy)) + 1 + (size_t)X[0].beats * 8;
    size_t most = WAVE_BYTES / per;
    return most < WAVE_MIN ? WAVE_MIN : most > WAVE_MAX ? WAVE_MAX : most;
}

int tb_run_stream_lanes(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts, vec_stream *vs,
                        tb_row_fn row, void *row_data, int threads, tb_result *r, int *rewound,
                        char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->unit = u; r->cfg = *cfg; r->fmts = *fmts;
    r->n_in = unit_n_in(u); r->n_out = unit_n_out(u); r->beats = u->beats(cfg);
    *rewound = 0;
    if (threads < 1) threads = 1;
    char why[300];
    tb_lanes *x = tb_lanes_new(u, cfg, fmts, threads, why, sizeof why);
    if (!x) {
        snprintf(r->engine_why, sizeof r->engine_why, "%.150s", why);
        *rewound = 1;
        return TB_STREAM_KERNEL;
    }
    tb_prep_ctx pc;
    tb_prep_init(&pc, u, cfg, fmts);
    tb_stream_outputs(r, u, cfg, fmts);
    tb_acc acc;
    tb_acc_begin(&acc, r);
    /* two buffers: a wave simulates in one while the wave before is
     * folded from the other */
    wbuf X[2] = { { 0 }, { 0 } };
    int has_exact, has_exact_d;
    size_t nv = (size_t)pc.nv, most = wave_setup(X, u, r, pc.nv, &has_exact, &has_exact_d);
    sl_state s = { 0 };
    folder F = { NULL, 0, 0, 0, 0, 0, 0, &acc, r, row, row_data };
    uint64_t in_ovf[UNIT_MAX_IO] = { 0 };
    prep_job *pj = calloc(1, sizeof *pj);
    size_t tmp_stride = 0;
    sim_dy *exact_tmp = has_exact_d ? tmp_alloc(nv, &tmp_stride) : NULL;
    if (!pj) base_out_of_memory();
    acc.pc = &pc;
    acc.exact_tmp = exact_tmp ? exact_tmp + PREP_CHUNKS * tmp_stride : NULL;
    vec_stream_threads(vs, threads);
    base_pool *pool = NULL;     /* the threads, made once (below) */
    reader R;
    memset(&R, 0, sizeof R);
    R.vs = vs; R.most = most; R.ncol = (size_t)X[0].ncol; R.blocks = 1;
    for (int i = 0; i < 3; i++) vec_set_init(&R.sets[i]);
    base_task rt, ft;
    int reading = 0, folding = 0;   /* rt reads the next wave; ft folds the wave before */
    int rc = TB_OK, last = 0;
    reader_run(&R);
    for (size_t wi = 0; !last; wi++) {
        wbuf *B = &X[wi & 1];
        size_t own = s.n;
        if (reading) { base_pool_wait(pool, &rt); reading = 0; }
        if (R.failed) { snprintf(err, errlen, "%s", R.err); rc = TB_BADINPUT; goto done; }
        wbuf_reserve(B, s.n + R.rows->n_rows, has_exact, has_exact_d, !!u->ideal_ratio, !!u->ideal_interval);
        B->own = own;
        B->fresh = R.rows->data;
        s.n += R.rows->n_rows;
        last = R.last;
        if (s.n == own) { snprintf(err, errlen, "no vectors"); rc = TB_BADINPUT; goto done; }   /* (the reader says it first) */
        /* the threads, made once, when there is more than a small wave:
         * the loops' (the preparation, the lanes' groups, the halves of a
         * block of text), the reader's and the folder's */
        if (!pool && threads > 1 && (!last || s.n - own >= PREP_PAR_MIN)) {
            pool = base_pool_new(threads, 2);
            vec_stream_pool(vs, pool);
            tb_lanes_pool(x, pool);
        }
        /* the next wave read beside this one (not beside the first: its
         * block is handed back to the kernel if the lanes do not take it) */
        if (!last && wi > 0 && pool) { base_pool_start(pool, &rt, reader_run, &R); reading = 1; }
        /* the wave's own items prepared */
        memset(pj, 0, sizeof *pj);
        pj->pc = &pc; pj->B = B; pj->from = own; pj->to = s.n; pj->tmp = exact_tmp; pj->tmp_stride = tmp_stride;
        base_pool_for(s.n - own < PREP_PAR_MIN ? NULL : pool, PREP_CHUNKS, prep_chunk, pj);
        for (int c = 0; c < PREP_CHUNKS; c++)
            for (int i = 0; i < r->n_in; i++) in_ovf[i] += pj->ovf[c][i];
        tb_lanes_wave w = { B->in_raw, s.n, own, s.base, last, B->cycle, B->raw, 0 };
        int taken = !tb_lanes_wave_run(x, &w, why, sizeof why);
        if (folding) { base_pool_wait(pool, &ft); folding = 0; }
        if (!taken) {
            snprintf(r->engine_why, sizeof r->engine_why, "%.150s", why);
            if (wi == 0) { vec_stream_unread(vs); *rewound = 1; }
            r->vectors = s.base + s.n;
            rc = TB_STREAM_KERNEL;
            goto done;
        }
        F.B = B; F.base = s.base; F.beats_done = w.beats_done;
        if (last) { fold(&F); break; }
        base_pool_start(pool, &ft, fold, &F);
        folding = 1;
        if (!reading) reader_run(&R);
        /* the next buffer starts with the items the next wave's warm-ups
         * reach back to, and those not yet all in */
        size_t keep = s.n > TB_LANES_WARM_MAX ? s.n - TB_LANES_WARM_MAX : 0, done_items = w.beats_done / (size_t)r->beats;
        if (done_items - s.base < keep) keep = done_items - s.base;
        wbuf *N = &X[(wi + 1) & 1];
        wbuf_reserve(N, s.n - keep, has_exact, has_exact_d, !!u->ideal_ratio, !!u->ideal_interval);
        wbuf_tail(N, B, keep, s.n);
        s.base += keep;
        s.n -= keep;
    }
    r->vectors = s.base + s.n;
    tb_lanes_out lo;
    tb_lanes_result(x, &lo);
    r->lanes = lo.lanes;
    r->stats.clocks = lo.clocks;
    /* the signals' overflow counts: their constants' (at build) and the lanes' (tb_lanes_result) */
    tb_stream_figures(r, r->vectors, F.first_cycle, F.last_item_cycle, F.last_cycle, lo.c, lo.sc, in_ovf);
    tb_range_finish(lo.rg, lo.sc, lo.io, in_ovf, r);
    tb_energy_fill_counts(r, lo.rg, lo.toggles, NULL, lo.c, r->stats.clocks);
    tb_acc_end(&acc, r);
    tb_verdict(r, NULL);
done:
    if (reading) base_pool_wait(pool, &rt);
    if (folding) base_pool_wait(pool, &ft);
    vec_stream_pool(vs, NULL);
    base_pool_free(pool);
    for (int i = 0; i < 3; i++) vec_set_free(&R.sets[i]);
    free(pj);
    free(exact_tmp);
    wbuf_free(&X[0]);
    wbuf_free(&X[1]);
    tb_lanes_free(x);
    return rc;
}
