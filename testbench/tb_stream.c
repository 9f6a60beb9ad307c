/* tb_stream.c - the testbench one item at a time: preparing an item,
 * accumulating the metrics, and tb_run_stream, which drives a unit from a
 * vector file read a block at a time.
 *
 * tb_run_stream keeps the prepared items in a ring of a fixed size (a few
 * MB): the driver prepares rows a batch at a time as it needs them,
 * reading the next block of the file when a batch is used up, and the
 * monitor folds each item into the metrics (and hands it to the caller,
 * for --out) once its last beat is in, which frees its slot. Items in
 * flight in a unit are a handful, far below the ring's size.
 *
 * Everything else is tb_run's: the same driver handshake, the same range
 * logging, the same clock bound (1000 + 4096 per beat, growing as rows
 * are read, so that it is tb_run's once the file's end is known), the
 * same kernel, hence the same clocks, events and deltas.
 */
#include "testbench/tb_stream.h"
#include "testbench/tb_range.h"
#include "testbench/tb_energy.h"
#include "testbench/tb_drive.h"
#include "base/base_out.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- items */

void tb_prep_init(tb_prep_ctx *p, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts)
{
    memset(p, 0, sizeof *p);
    p->u = u; p->cfg = cfg; p->fmts = fmts;
    p->model = u->ref;
    p->vp = cfg->model;
    p->n_in = unit_n_in(u);
    p->nv = u->beats(cfg) * unit_n_out(u);
    for (int i = 0, k = 0; i < u->nsigs; i++) if (u->sigs[i].role == UNIT_SIG_IN) p->in_idx[k++] = i;
    for (int i = 0; i < p->n_in; i++) {
        sim_fmt f = fmts->f[p->in_idx[i]];
        p->in_fmt[i] = f;
        p->in_rnd[i] = sim_fmt_round(f, cfg->rnd);    /* the input's own mode, if it has one */
        p->in_up[i] = ldexp(1.0, f.fbits);
        p->in_down[i] = ldexp(1.0, -f.fbits);
        sim_fx_conv_init(&p->in_cv[i], f, cfg->rnd, cfg->ovf);
    }
}

/* floor(z), without the call when z is below 2^52 in magnitude (the
 * conversions to and from int64_t are then exact); a whole z, -0 among
 * them, is its own floor. */
static inline double floor_fast(double z)
{
    if (!(__builtin_fabs(z) < 0x1p52)) return floor(z);
    double t = (double)(int64_t)z;
    if (t == z) return z;
    return t > z ? t - 1.0 : t;
}

void tb_prep(const tb_prep_ctx *p, const double *row, const tb_item *it, uint64_t *in_ovf)
{
    /* Quantize inputs as the hardware will hold them, and compute what the
     * unit should give for exactly those inputs; for the golden check also
     * the ideal of the inputs rounded but not wrapped, of the file's own
     * inputs, and the float reference of those. */
    const unit_desc *u = p->u;
    const unit_cfg *cfg = p->cfg;
    double q[UNIT_MAX_IO], qr[UNIT_MAX_IO], x[UNIT_MAX_IO];
    sim_dy qd[UNIT_MAX_IO];
    for (int i = 0; i < p->n_in; i++) {
        int ov = 0;
        sim_fmt f = p->in_fmt[i];
        x[i] = row[i];
        it->in_raw[i] = sim_fx_conv_real(&p->in_cv[i], x[i], &ov);
        in_ovf[i] += (uint64_t)ov;
        /* sim_fx_to_real: a product by a power of two is exact or
         * correctly rounded, as ldexp is */
        q[i] = (double)it->in_raw[i] * p->in_down[i];
        sim_dy_raw(&qd[i], it->in_raw[i], f);
        /* Rounded to f's fraction bits with an unlimited integer part
         * (exact in double: a value of more than 52 bits after the
         * scaling is already a whole number). */
        double y = x[i] * p->in_up[i];
        sim_round rr = p->in_rnd[i];
        y = rr == SIM_RND_TRUNC ? floor_fast(y) : rr == SIM_RND_HALF_UP ? floor_fast(y + 0.5) : nearbyint(y);
        qr[i] = y * p->in_down[i];
    }
    u->ideal(cfg, q, it->ideal);
    u->ideal(cfg, qr, it->ideal_r);
    u->ideal(cfg, x, it->ideal_u);
    if (p->model) p->model->eval(&p->vp, x, it->ref_u);
    else for (int j = 0; j < p->nv; j++) it->ref_u[j] = row[p->n_in + j];
    *it->exact_ok = 0;
    if (u->ideal_ratio) *it->exact_ok = u->ideal_ratio(cfg, qd, it->exact, it->den) == 0;
    else if (it->exact) *it->exact_ok = u->ideal_exact(cfg, qd, it->exact) == 0;
    if (it->exact && !*it->exact_ok && u->ideal_interval)
        *it->exact_ok = u->ideal_interval(cfg, qd, it->exact, it->hi) == 0 ? 2 : 0;
    if (it->exact_d)
        for (int j = 0; j < p->nv; j++) it->exact_d[j] = it->exact[j].ovf ? NAN : sim_dy_to_double(&it->exact[j]);
}

int tb_prep_exact(const tb_prep_ctx *p, const int64_t *in_raw, sim_dy *exact)
{
    sim_dy qd[UNIT_MAX_IO];
    for (int i = 0; i < p->n_in; i++) sim_dy_raw(&qd[i], in_raw[i], p->in_fmt[i]);
    return p->u->ideal_exact(p->cfg, qd, exact);
}

/* -------------------------------------------------------------- metrics */

void tb_acc_begin(tb_acc *a, tb_result *r)
{
    memset(a, 0, sizeof *a);
    r->within_bound = 1;
    r->bound_check = TB_CHECK_OK;
    r->golden_ok = 1;
    r->max_abs_err = r->max_err_lsb = 0;
    for (int o = 0; o < r->n_out; o++) {
        tb_metrics *m = &r->out[o];
        m->max_abs_err = m->max_err_ideal = m->max_method_err = m->max_input_err = 0;
        m->sum_e2 = m->sum_ref2 = 0;
        m->n = 0;
        m->golden_ok = 1;
        a->has_bound[o] = isfinite(m->bound) && m->bound >= 0;
        m->check = a->has_bound[o] ? TB_CHECK_OK : TB_CHECK_NO_BOUND;
        sim_dy_double(&a->b[o], a->has_bound[o] ? m->bound : 0);
        a->bd[o] = sim_dy_to_double(&a->b[o]);
        a->lsb[o] = sim_fmt_lsb(m->fmt);
        a->out_scale[o] = fmax(fabs(sim_fmt_real_min(m->fmt)), fabs(sim_fmt_real_max(m->fmt)));
    }
}

void tb_acc_item(tb_acc *a, tb_result *r, size_t idx, const int64_t *raw, const double *expected,
                 const tb_item *it)
{
    int no = r->n_out, nb = r->beats;
    int ex = (it->exact || it->exact_d) && *it->exact_ok, iv = ex && *it->exact_ok == 2;
    const sim_dy *exact = it->exact;    /* exact_d's: worked out again once, if a value needs it */
    for (int o = 0; o < no; o++) {
        tb_metrics *m = &r->out[o];
        for (int bt = 0; bt < nb; bt++) {
            int k = bt * no + o;
            double hw = (double)raw[k] * a->lsb[o];     /* sim_fx_to_real: exact, a product by 2^-F */
            double ref = expected[k];
            double e = hw - ref, ei;
            int c = -1;
            if (ex && !exact) {
                c = tb_check_quick(raw[k], m->fmt, a->lsb[o], it->exact_d[k], a->bd[o], &ei);
                if (c < 0) { (void)tb_prep_exact(a->pc, it->in_raw, a->exact_tmp); exact = a->exact_tmp; }
            }
            if (c < 0)
                c = tb_check_value_at(raw[k], m->fmt, a->lsb[o], ex ? &exact[k] : NULL,
                                      ex && !iv && it->den ? &it->den[k] : NULL, iv ? &it->hi[k] : NULL, it->ideal[k],
                                      &a->b[o], a->bd[o], &ei);
            a->se[o] += e;
            m->sum_e2 += e * e;
            m->sum_ref2 += ref * ref;
            if (fabs(e) > m->max_abs_err) m->max_abs_err = fabs(e);
            if (ei > m->max_err_ideal) m->max_err_ideal = ei;
            if (a->has_bound[o] && c == TB_CHECK_EXCEEDED && !a->any_exceeded[o]) { a->any_exceeded[o] = 1; a->first_exceeded[o] = idx; }
            if (a->has_bound[o] && c == TB_CHECK_UNCHECKED && !a->any_unchecked[o]) { a->any_unchecked[o] = 1; a->first_unchecked[o] = idx; }
            /* Golden: the bound, plus what rounding the inputs moves the
             * ideal by, plus the method's own approximation (the ideal
             * against the float reference), plus the doubles' rounding in
             * those three, relative to the terms' size (docs/bounds.md). */
            double dq = fabs(it->ideal_r[k] - it->ideal_u[k]), dm = fabs(it->ideal_u[k] - it->ref_u[k]);
            if (dm > m->max_method_err) m->max_method_err = dm;
            if (dq > m->max_input_err) m->max_input_err = dq;
            double slack = TB_DOUBLE_IDEAL_REL * (fabs(it->ideal_r[k]) + fabs(it->ideal_u[k]) + fabs(it->ref_u[k])
                                                  + fabs(ref) + a->out_scale[o]);
            double allowed = m->bound + dq + dm + slack;
            if (a->has_bound[o] && !(fabs(e) <= allowed) && m->golden_ok) {
                m->golden_ok = 0;
                m->golden_first = idx;
                m->golden_err = fabs(e);
                m->golden_allowed = allowed;
            }
            m->n++;
        }
    }
}

void tb_acc_end(tb_acc *a, tb_result *r)
{
    double sum_e2 = 0, sum_ref2 = 0, sum_e = 0;
    size_t cnt = 0;
    for (int o = 0; o < r->n_out; o++) {
        tb_metrics *m = &r->out[o];
        double se = a->se[o];
        if (a->any_exceeded[o]) m->check = TB_CHECK_EXCEEDED;
        else if (a->any_unchecked[o] && a->has_bound[o]) m->check = TB_CHECK_UNCHECKED;
        /* the run's check: exceeded beats no bound beats unchecked beats ok */
        static const int rank[] = { 0, 3, 1, 2 };
        if (rank[m->check] > rank[r->bound_check]) r->bound_check = m->check;
        if (m->check != TB_CHECK_OK && r->within_bound) {
            r->within_bound = 0;
            r->first_violation = a->any_exceeded[o] ? a->first_exceeded[o] : a->first_unchecked[o];
        } else if (m->check == TB_CHECK_EXCEEDED && a->first_exceeded[o] < r->first_violation) {
            r->first_violation = a->first_exceeded[o];
        }
        if (!m->golden_ok) r->golden_ok = 0;
        m->mean_err = m->n ? se / (double)m->n : 0;
        m->rms_err = m->n ? sqrt(m->sum_e2 / (double)m->n) : 0;
        m->nmse = m->sum_ref2 > 0 ? m->sum_e2 / m->sum_ref2 : (m->sum_e2 > 0 ? INFINITY : 0);
        m->max_err_lsb = m->max_abs_err / sim_fmt_lsb(m->fmt);
        sum_e2 += m->sum_e2; sum_ref2 += m->sum_ref2; sum_e += se; cnt += m->n;
        if (m->max_abs_err > r->max_abs_err) r->max_abs_err = m->max_abs_err;
        if (m->max_err_lsb > r->max_err_lsb) r->max_err_lsb = m->max_err_lsb;
    }
    r->mean_err = cnt ? sum_e / (double)cnt : 0;
    r->rms_err = cnt ? sqrt(sum_e2 / (double)cnt) : 0;
    r->nmse = sum_ref2 > 0 ? sum_e2 / sum_ref2 : (sum_e2 > 0 ? INFINITY : 0);
}

/* ------------------------------------------------------- the report */

void tb_stream_outputs(tb_result *r, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts)
{
    double bound[UNIT_MAX_IO];
    unit_bound(u, cfg, fmts, bound);
    for (int i = 0, oi = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_OUT) {
            snprintf(r->out[oi].name, sizeof r->out[oi].name, "%s", u->sigs[i].name);
            r->out[oi].fmt = fmts->f[i];
            r->out[oi].bound = bound[oi];
            oi++;
        }
}

void tb_stream_figures(tb_result *r, size_t n, uint64_t first_cycle, uint64_t last_item_cycle, uint64_t last_cycle,
                       sim_ctx *c, const sim_scope *sc, const uint64_t *in_ovf)
{
    size_t nbeats = n * (size_t)r->beats;
    r->latency = first_cycle;
    r->cycles = last_cycle + 1;
    r->cycles_per_item = n > 1 ? (double)(last_item_cycle - first_cycle) / (double)(n - 1) : (double)r->cycles;
    r->cycles_per_beat = nbeats > 1 ? (double)(last_cycle - first_cycle) / (double)(nbeats - 1) : (double)r->cycles;
    r->area_ge = sim_scope_area(sc);
    char terr[300];
    if (tb_ppa_timing(c, sc, r->cycles_per_item, &r->ppa, terr, sizeof terr)) { /* the run found no loop */ }
    r->overflows = tb_scope_overflows(sc);
    r->ovf_discarded = tb_scope_ovf_discarded(sc);
    for (int i = 0; i < r->n_in; i++) { r->in_overflows += in_ovf[i]; r->overflows += in_ovf[i]; }
}

/* ------------------------------------------------------------ streaming */

/* Prepared items, slot = item & (cap - 1). */
typedef struct ring {
    size_t cap;
    int64_t *in_raw, *raw;
    double *ideal, *expected;   /* expected: nv; ideal: 4 nv (ideal, _r, _u, ref_u) */
    sim_dy *exact, *den, *hi;
    unsigned char *exact_ok;
    uint64_t *cycle;            /* first beat's cycle */
} ring;

typedef struct st_state {
    tb_drive drv;               /* the driver (tb_drive.h), on the ring's items */
    tb_prep_ctx pc;
    const unit_io *io;
    int n_in, n_out, beats, nv;
    ring R;
    vec_stream *src;
    const vec_set *rows;
    size_t row_at;              /* next row of rows to prepare */
    size_t prepared, done, got; /* items prepared, finished; beats got */
    size_t got_item;            /* got as item and beat: got / beats, got % beats */
    int    got_beat;
    int eof, failed, finished;
    uint64_t in_ovf[UNIT_MAX_IO];
    const sim_ctx *ctx;
    tb_acc acc;
    tb_result *r;
    tb_row_fn row;
    void *row_data;
    uint64_t first_cycle, last_item_cycle, last_cycle;
    char why[600];
    tb_range rg;                /* range logging (tb_range.h) */
} st_state;

static tb_item ring_item(const st_state *s, size_t idx)
{
    size_t k = idx & (s->R.cap - 1), nv = (size_t)s->nv;
    tb_item it = {
        s->R.in_raw + k * (size_t)s->n_in,
        s->R.ideal + 4 * k * nv, s->R.ideal + (4 * k + 1) * nv, s->R.ideal + (4 * k + 2) * nv,
        s->R.ideal + (4 * k + 3) * nv,
        s->R.exact ? s->R.exact + k * nv : NULL, s->R.den ? s->R.den + k * nv : NULL,
        s->R.hi ? s->R.hi + k * nv : NULL, s->R.exact_ok + k, NULL
    };
    return it;
}

/* Prepare more rows (reading the next block when the last is used up):
 * 1 if something was prepared, 0 at the end or on an error (failed). */
static int prepare_more(st_state *s)
{
    if (s->eof || s->failed) return 0;
    if (s->row_at == s->rows->n_rows) {
        int rc = vec_stream_next(s->src, &s->rows);
        s->row_at = 0;
        if (rc < 0) { s->failed = 1; snprintf(s->why, sizeof s->why, "%s", vec_stream_error(s->src)); return 0; }
        if (rc == 0) { s->eof = 1; return 0; }
    }
    size_t room = s->R.cap - (s->prepared - s->done), batch = s->R.cap / 4;
    if (!room) {
        s->failed = 1;
        snprintf(s->why, sizeof s->why, "unit %s holds more than %zu items at once", s->pc.u->name, s->R.cap);
        return 0;
    }
    if (batch > room) batch = room;
    size_t left = s->rows->n_rows - s->row_at;
    if (batch > left) batch = left;
    for (size_t i = 0; i < batch; i++, s->row_at++, s->prepared++) {
        const double *row = vec_row(s->rows, s->row_at);
        tb_item it = ring_item(s, s->prepared);
        tb_prep(&s->pc, row, &it, s->in_ovf);
        memcpy(s->R.expected + (s->prepared & (s->R.cap - 1)) * (size_t)s->nv, row + s->n_in,
               (size_t)s->nv * sizeof *row);
    }
    return 1;
}

static int have_item(st_state *s, size_t idx)
{
    while (idx >= s->prepared)
        if (!prepare_more(s)) return 0;
    return 1;
}

/* The driver's source: item i's raws, prepared if need be (NULL at the
 * end, or on an error, which stops the run). */
static const int64_t *st_item(tb_drive *d, size_t i)
{
    st_state *s = d->data;
    if (!have_item(s, i)) {
        d->failed = s->failed;
        return NULL;
    }
    return s->R.in_raw + (i & (s->R.cap - 1)) * (size_t)s->n_in;
}

/* An output beat is in: keep it; a finished item goes to the metrics and
 * the caller, and its slot is free again. */
static __attribute__((noinline)) void st_collect(st_state *s, sim_proc *p)
{
    size_t it = s->got_item;
    int b = s->got_beat;
    if (it >= s->prepared) return;     /* (at the end: every item is in) */
    uint64_t cyc = sim_get_stats(s->ctx)->clocks - 1;
    size_t k = it & (s->R.cap - 1);
    int64_t *raw = s->R.raw + k * (size_t)s->nv;
    if (b == 0) { s->R.cycle[k] = cyc; s->last_item_cycle = cyc; }
    if (s->got == 0) s->first_cycle = cyc;
    s->last_cycle = cyc;
    for (int o = 0; o < s->n_out; o++) raw[b * s->n_out + o] = s->io->out[o]->cur;
    s->got++;
    if (++s->got_beat == s->beats) { s->got_beat = 0; s->got_item++; }
    if (b == s->beats - 1) {
        tb_item ti = ring_item(s, it);
        const double *expected = s->R.expected + k * (size_t)s->nv;
        tb_acc_item(&s->acc, s->r, it, raw, expected, &ti);
        if (s->row) s->row(s->row_data, s->r, it, s->R.cycle[k], raw, expected);
        s->done++;
    }
    if (s->eof && s->done == s->prepared) { s->finished = 1; sim_stop(p->ctx); }
}

/* Monitor, at each rising edge: tb_run's (range logging, then the output
 * beat when there is one). */
static void st_monitor(sim_proc *p)
{
    st_state *s = p->data;
    tb_range_sample(&s->rg);
    if (s->io->out_valid->cur) st_collect(s, p);
}

static void ring_alloc(ring *R, int n_in, int nv, const unit_desc *u)
{
    /* About 4 MB of prepared items, at least 256. */
    size_t per = (size_t)n_in * 8 + (size_t)nv * (8 + 5 * 8 + 8) + 16
               + (size_t)nv * sizeof(sim_dy) * (size_t)(!!(u->ideal_exact || u->ideal_ratio || u->ideal_interval)
                                                        + !!u->ideal_ratio + !!u->ideal_interval);
    size_t cap = 256;
    while (cap * 2 * per <= ((size_t)4 << 20)) cap *= 2;
    R->cap = cap;
    R->in_raw = calloc(cap * (size_t)n_in, sizeof *R->in_raw);
    R->raw = calloc(cap * (size_t)nv, sizeof *R->raw);
    R->ideal = calloc(cap * 4 * (size_t)nv, sizeof *R->ideal);
    R->expected = calloc(cap * (size_t)nv, sizeof *R->expected);
    R->exact = u->ideal_exact || u->ideal_ratio || u->ideal_interval ? calloc(cap * (size_t)nv, sizeof *R->exact) : NULL;
    R->den = u->ideal_ratio ? calloc(cap * (size_t)nv, sizeof *R->den) : NULL;
    R->hi = u->ideal_interval ? calloc(cap * (size_t)nv, sizeof *R->hi) : NULL;
    R->exact_ok = calloc(cap, 1);
    R->cycle = calloc(cap, sizeof *R->cycle);
    if (!(R->in_raw && R->raw && R->ideal && R->expected && R->exact_ok && R->cycle
          && (R->exact || !(u->ideal_exact || u->ideal_ratio || u->ideal_interval))
          && (R->den || !u->ideal_ratio) && (R->hi || !u->ideal_interval)))
        base_out_of_memory();
}

static void ring_free(ring *R)
{
    free(R->in_raw); free(R->raw); free(R->ideal); free(R->expected);
    free(R->exact); free(R->den); free(R->hi); free(R->exact_ok); free(R->cycle);
}

int tb_run_stream(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
                  vec_stream *vs, tb_row_fn row, void *row_data, const tb_opts *o, tb_result *r,
                  char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->unit = u; r->cfg = *cfg; r->fmts = *fmts;
    r->n_in = unit_n_in(u); r->n_out = unit_n_out(u); r->beats = u->beats(cfg);
    st_state st;
    memset(&st, 0, sizeof st);
    tb_prep_init(&st.pc, u, cfg, fmts);
    st.n_in = r->n_in; st.n_out = r->n_out; st.beats = r->beats; st.nv = st.pc.nv;
    st.src = vs; st.r = r; st.row = row; st.row_data = row_data;
    static const vec_set none;
    st.rows = &none;
    ring_alloc(&st.R, st.n_in, st.nv, u);
    /* The first rows before anything is built: an empty or bad file is
     * reported as vec_file_read would. */
    if (!have_item(&st, 0)) {
        snprintf(err, errlen, "%s", st.failed ? st.why : "no vectors");
        ring_free(&st.R);
        return TB_BADINPUT;
    }

    tb_stream_outputs(r, u, cfg, fmts);
    tb_acc_begin(&st.acc, r);

    tb_built bu;
    int unbuilt = tb_build(u, cfg, fmts, &bu, err, errlen);
    sim_ctx *c = bu.c;
    sim_signal *clk = bu.clk;
    sim_scope *sc = bu.sc;
    unit_io io = bu.io;
    int rc = TB_OK;
    sim_toggle *tog = NULL;      /* switching activity (tb_energy.h) */
    if (unbuilt) { rc = TB_BADINPUT; goto done; }
    if (o && o->reference) { sim_set_reference(c, 1); r->reference = 1; }
    sim_clock(c, clk, 5, 5);
    st.io = &io; st.ctx = c;
    tb_drive_fn_source(&st.drv, st.n_in, st_item, &st);
    st.drv.io = &io; st.drv.ctx = c;
    if (tb_range_init(&st.rg, c, sc, clk)) base_out_of_memory();     /* its one failure */
    sim_proc *drv = sim_proc_new(c, "tb.driver", tb_drive_proc, &st.drv);
    sim_sensitive(drv, clk, SIM_EDGE_POS);
    sim_proc *mon = sim_proc_new(c, "tb.monitor", st_monitor, &st);
    sim_sensitive(mon, clk, SIM_EDGE_POS);
    mon->no_init = 1;
    /* every signal exists now: toggles counted from initialization on */
    if (!(tog = sim_toggle_new(c))) base_out_of_memory();
    /* tb_run's bound, 1000 clocks + 4096 per beat, over the items read so
     * far: it grows while the file is read, and is tb_run's at its end. */
    sim_status ss;
    for (;;) {
        uint64_t max_clocks = 1000 + st.prepared * (size_t)st.beats * 4096;
        ss = sim_run(c, max_clocks * 10);
        if (ss != SIM_OK || st.finished || st.failed) break;
        if (1000 + st.prepared * (size_t)st.beats * 4096 == max_clocks) break;
    }
    r->stats = *sim_get_stats(c);
    r->vectors = st.prepared;
    if (ss != SIM_OK) {         /* a loop, or a design that is not well formed */
        snprintf(err, errlen, "%s", sim_error(c));
        rc = TB_FAIL;
    } else if (st.failed) {
        snprintf(err, errlen, "%s", st.why);
        rc = TB_BADINPUT;
    } else if (!st.finished) {
        snprintf(err, errlen, "unit %s gave %zu of %zu outputs in %llu clocks", u->name, st.got,
                 st.prepared * (size_t)st.beats, (unsigned long long)r->stats.clocks);
        rc = TB_FAIL;
    }
    if (rc == TB_OK) {
        tb_stream_figures(r, st.prepared, st.first_cycle, st.last_item_cycle, st.last_cycle, c, sc, st.in_ovf);
        tb_range_finish(&st.rg, sc, &io, st.in_ovf, r);
        tb_energy_fill(r, &st.rg, tog, c, r->stats.clocks);
        tb_acc_end(&st.acc, r);
        tb_verdict(r, NULL);
    }
done:
    sim_toggle_free(tog);
    sim_free(c);
    ring_free(&st.R);
    tb_range_free(&st.rg);
    return rc;
}
