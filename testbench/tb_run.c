/* tb_run.c - the generic testbench: a driver and a monitor process around
 * any unit, then error metrics against the golden vectors. */
#include "testbench/tb.h"
#include "sim/sim_vcd.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct tb_state {
    const unit_io *io;
    int n_in, n_out, beats;
    size_t n_items;
    const int64_t *in_raw;       /* [item][input] quantized inputs */
    size_t next;                 /* item being offered */
    size_t got;                  /* beats collected */
    int started;
    const sim_ctx *ctx;
    uint64_t *beat_cycle;
    int64_t  *raw;
} tb_state;

/* Driver, at each rising edge: if the unit accepted the offered item (valid
 * and ready before the edge), offer the next one. */
static void driver(sim_proc *p)
{
    tb_state *s = p->data;
    const unit_io *io = s->io;
    if (s->started && io->in_valid->cur && io->in_ready->cur) s->next++;
    s->started = 1;
    if (s->next < s->n_items) {
        const int64_t *v = s->in_raw + s->next * (size_t)s->n_in;
        for (int i = 0; i < s->n_in; i++) sim_write(io->in[i], v[i]);
        sim_write(io->in_valid, 1);
    } else {
        sim_write(io->in_valid, 0);
    }
}

/* Monitor, at each rising edge: the values before the edge are those of the
 * cycle that just ended. */
static void monitor(sim_proc *p)
{
    tb_state *s = p->data;
    if (!s->io->out_valid->cur) return;
    size_t total = s->n_items * (size_t)s->beats;
    if (s->got >= total) return;
    s->beat_cycle[s->got] = sim_get_stats(s->ctx)->clocks - 1;
    for (int o = 0; o < s->n_out; o++) s->raw[s->got * (size_t)s->n_out + o] = s->io->out[o]->cur;
    if (++s->got == total) sim_stop(p->ctx);
}

void tb_vec_params(const unit_cfg *cfg, vec_params *p)
{
    vec_params_default(p);
    p->L = cfg->L; p->g = cfg->g; p->n = cfg->n; p->m = cfg->m; p->alpha = cfg->alpha;
}

void tb_expected_header(const unit_desc *u, const unit_cfg *cfg, vec_set *h)
{
    int beats = u->beats(cfg);
    snprintf(h->unit, sizeof h->unit, "%s", u->name);
    h->n_in = h->n_out = 0;
    for (int i = 0; i < u->nsigs; i++) {
        if (u->sigs[i].role == UNIT_SIG_IN) snprintf(h->in_names[h->n_in++], 16, "%s", u->sigs[i].name);
    }
    for (int b = 0; b < beats; b++)
        for (int i = 0; i < u->nsigs; i++) {
            if (u->sigs[i].role != UNIT_SIG_OUT || h->n_out >= VEC_MAX_PORTS) continue;
            if (beats == 1) snprintf(h->out_names[h->n_out++], 16, "%s", u->sigs[i].name);
            else snprintf(h->out_names[h->n_out++], 16, "%.10s%d", u->sigs[i].name, b & 1023);
        }
}

static int header_matches(const vec_set *a, const vec_set *b, char *err, size_t errlen)
{
    if (strcmp(a->unit, b->unit)) { snprintf(err, errlen, "vectors are for unit '%s', not '%s'", a->unit, b->unit); return 0; }
    if (a->n_in != b->n_in || a->n_out != b->n_out) {
        snprintf(err, errlen, "vectors have %d inputs and %d outputs; unit %s needs %d and %d",
                 a->n_in, a->n_out, b->unit, b->n_in, b->n_out);
        return 0;
    }
    for (int i = 0; i < a->n_in; i++)
        if (strcmp(a->in_names[i], b->in_names[i])) { snprintf(err, errlen, "input %d is '%s', unit %s expects '%s'", i + 1, a->in_names[i], b->unit, b->in_names[i]); return 0; }
    for (int i = 0; i < a->n_out; i++)
        if (strcmp(a->out_names[i], b->out_names[i])) { snprintf(err, errlen, "output %d is '%s', unit %s expects '%s'", i + 1, a->out_names[i], b->unit, b->out_names[i]); return 0; }
    return 1;
}

static void metrics(tb_result *r, const vec_set *vs, const double *ideal)
{
    int no = r->n_out, nb = r->beats;
    double sum_e2 = 0, sum_ref2 = 0, sum_e = 0;
    size_t cnt = 0;
    r->within_bound = 1;
    r->max_abs_err = r->max_err_lsb = 0;
    for (int o = 0; o < no; o++) {
        tb_metrics *m = &r->out[o];
        double se = 0;
        m->max_abs_err = m->max_err_ideal = 0;
        m->sum_e2 = m->sum_ref2 = 0;
        m->n = 0;
        for (size_t it = 0; it < r->vectors; it++)
            for (int b = 0; b < nb; b++) {
                size_t k = (it * (size_t)nb + (size_t)b) * (size_t)no + (size_t)o;
                double hw = sim_fx_to_real(r->raw[k], m->fmt);
                double ref = vec_row(vs, it)[r->n_in + b * no + o];
                double e = hw - ref, ei = fabs(hw - ideal[k]);
                se += e;
                m->sum_e2 += e * e;
                m->sum_ref2 += ref * ref;
                if (fabs(e) > m->max_abs_err) m->max_abs_err = fabs(e);
                if (ei > m->max_err_ideal) m->max_err_ideal = ei;
                /* The bound is exact arithmetic on the formats; allow only
                 * the double rounding of the ideal computation itself. */
                if (ei > m->bound + 1e-12 * (1 + fabs(ideal[k])) && r->within_bound) {
                    r->within_bound = 0;
                    r->first_violation = it;
                }
                m->n++;
            }
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

static uint64_t scope_overflows(const sim_scope *sc)
{
    uint64_t n = 0;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) n += s->overflows;
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) n += scope_overflows(ch);
    return n;
}

int tb_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
           const vec_set *vs, const tb_opts *o, tb_result *r, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->unit = u; r->cfg = *cfg; r->fmts = *fmts;
    r->n_in = unit_n_in(u); r->n_out = unit_n_out(u); r->beats = u->beats(cfg);
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(u, cfg, &hdr);
    if (!header_matches(vs, &hdr, err, errlen)) return TB_BADINPUT;
    if (vs->n_rows == 0) { snprintf(err, errlen, "no vectors"); return TB_BADINPUT; }
    r->vectors = vs->n_rows;

    size_t n = vs->n_rows, nbeats = n * (size_t)r->beats, nvals = nbeats * (size_t)r->n_out;
    int64_t *in_raw = malloc(n * (size_t)r->n_in * sizeof *in_raw);
    double *ideal = malloc(nvals * sizeof *ideal);
    r->raw = calloc(nvals, sizeof *r->raw);
    r->beat_cycle = calloc(nbeats, sizeof *r->beat_cycle);
    if (!in_raw || !ideal || !r->raw || !r->beat_cycle) {
        free(in_raw); free(ideal);
        snprintf(err, errlen, "out of memory for %zu vectors", n);
        return TB_FAIL;
    }

    /* Quantize inputs as the hardware will hold them, and compute what the
     * unit should give for exactly those inputs. */
    uint64_t in_ovf = 0;
    int in_idx[UNIT_MAX_IO], k = 0;
    for (int i = 0; i < u->nsigs; i++) if (u->sigs[i].role == UNIT_SIG_IN) in_idx[k++] = i;
    for (size_t it = 0; it < n; it++) {
        double q[UNIT_MAX_IO];
        for (int i = 0; i < r->n_in; i++) {
            int ov = 0;
            sim_fmt f = fmts->f[in_idx[i]];
            in_raw[it * (size_t)r->n_in + i] = sim_fx_from_real(vec_row(vs, it)[i], f, cfg->rnd, cfg->ovf, &ov);
            in_ovf += (uint64_t)ov;
            q[i] = sim_fx_to_real(in_raw[it * (size_t)r->n_in + i], f);
        }
        u->ideal(cfg, q, ideal + it * (size_t)r->beats * (size_t)r->n_out);
    }

    double bound[UNIT_MAX_IO];
    u->bound(cfg, fmts, bound);
    for (int i = 0, oi = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_OUT) {
            snprintf(r->out[oi].name, sizeof r->out[oi].name, "%s", u->sigs[i].name);
            r->out[oi].fmt = fmts->f[i];
            r->out[oi].bound = bound[oi];
            oi++;
        }

    sim_ctx *c = sim_new();
    sim_set_quant(c, cfg->rnd, cfg->ovf);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *sc = sim_scope_new(c, NULL, u->name);
    unit_io io;
    memset(&io, 0, sizeof io);
    int rc = TB_OK;
    sim_vcd *vcd = NULL;
    if (u->build(c, sc, clk, cfg, fmts, &io, err, errlen)) { rc = TB_BADINPUT; goto done; }
    /* 100 MHz in a 1 ns timescale: rising edges at 5, 15, 25, ... */
    sim_clock(c, clk, 5, 5);
    tb_state st = { &io, r->n_in, r->n_out, r->beats, n, in_raw, 0, 0, 0, c, r->beat_cycle, r->raw };
    sim_proc *drv = sim_proc_new(c, "tb.driver", driver, &st);
    sim_sensitive(drv, clk, SIM_EDGE_POS);
    sim_proc *mon = sim_proc_new(c, "tb.monitor", monitor, &st);
    sim_sensitive(mon, clk, SIM_EDGE_POS);
    mon->no_init = 1;
    if (o && o->vcd_path) {
        vcd = sim_vcd_open(c, o->vcd_path, "1ns", err, errlen);
        if (!vcd) { rc = TB_BADINPUT; goto done; }
    }
    /* No unit needs more than a few thousand clocks per beat (pow_n at
     * n = 1024 takes about 20); a unit that never answers is a failure. */
    uint64_t max_clocks = 1000 + nbeats * 4096;
    sim_status ss = sim_run(c, max_clocks * 10);
    r->stats = *sim_get_stats(c);
    if (ss == SIM_ERR_LOOP) {
        snprintf(err, errlen, "%s", sim_error(c));
        rc = TB_FAIL;
    } else if (st.got < nbeats) {
        snprintf(err, errlen, "unit %s gave %zu of %zu outputs in %llu clocks", u->name, st.got, nbeats,
                 (unsigned long long)r->stats.clocks);
        rc = TB_FAIL;
    }
    if (vcd) {
        if (sim_vcd_close(vcd) && rc == TB_OK) {
            snprintf(err, errlen, "%s: write failed", o->vcd_path);
            rc = TB_BADINPUT;
        } else if (o->gtkw && rc == TB_OK) {
            char g[1024];
            snprintf(g, sizeof g, "%s.gtkw", o->vcd_path);
            sim_vcd_write_gtkw(c, o->vcd_path, g);
        }
        vcd = NULL;
    }
    if (rc == TB_OK) {
        r->latency = r->beat_cycle[0];
        r->cycles = r->beat_cycle[nbeats - 1] + 1;
        size_t nb = (size_t)r->beats;
        r->cycles_per_item = n > 1 ? (double)(r->beat_cycle[(n - 1) * nb] - r->beat_cycle[0]) / (double)(n - 1)
                                   : (double)r->cycles;
        r->cycles_per_beat = nbeats > 1 ? (double)(r->beat_cycle[nbeats - 1] - r->beat_cycle[0]) / (double)(nbeats - 1)
                                        : (double)r->cycles;
        r->area_ge = sim_scope_area(sc);
        r->overflows = in_ovf + scope_overflows(sc);
        metrics(r, vs, ideal);
    }
done:
    if (vcd) sim_vcd_abort(vcd);
    sim_free(c);
    free(in_raw);
    free(ideal);
    return rc;
}

void tb_result_free(tb_result *r)
{
    free(r->raw);
    free(r->beat_cycle);
    r->raw = NULL;
    r->beat_cycle = NULL;
}
