/* tb_speed_hw.c - the papers' speed claims in hardware, measured: built
 * units against chains of built units (tb_speed_hw.h). */
#include "testbench/study/tb_speed_hw.h"
#include "sim/sim_prim.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

const int tb_speed_widths[TB_SPEED_NW] = { 8, 16, 24 };

int tb_hw_point_run(const char *name, const unit_cfg *cfg, size_t nvec, tb_hw_phys phys, double peak,
                    tb_hw_point *pt)
{
    const unit_desc *u = unit_find(name);
    memset(pt, 0, sizeof *pt);
    pt->unit = name;
    if (!u || !u->ref) return -1;
    unit_fmts fm;
    vec_set vs;
    tb_result r;
    char err[600];
    if (tb_formats(u, cfg, NULL, 0, &fm, err, sizeof err)) return -1;
    vec_set_init(&vs);
    vec_set_header(&vs, u->ref, &cfg->model);
    if (u->ref->gen(&cfg->model, nvec, 1, &vs)) { vec_set_free(&vs); return -1; }
    int rc = tb_run(u, cfg, &fm, &vs, NULL, &r, err, sizeof err);
    if (rc == TB_OK) {
        pt->clocks = r.cycles_per_item;
        pt->area = r.area_ge;
        pt->period_ps = r.ppa.crit_ps;
        pt->unbounded = r.bound_check == TB_CHECK_NO_BOUND;
        if (phys)
            for (size_t i = 0; i < vs.n_rows; i++) {
                double hw = sim_fx_to_real(r.raw[i * (size_t)r.n_out], r.out[0].fmt);
                double e = fabs(hw - phys(vec_row(&vs, i)[0], cfg)) / peak;
                if (e > pt->max_err_peak) pt->max_err_peak = e;
            }
        pt->ok = 1;
    }
    tb_result_free(&r);
    vec_set_free(&vs);
    return pt->ok ? 0 : -1;
}

/* The chains at a width: the squarer and the divider measured alone, and
 * Ward's exp argument wired as one design (tb_speed_ward_chain): Ward's
 * exp term = that design; exact D = that design, then a squarer (c^4)
 * and a divider run after it (their glue not counted); without the
 * exponential. Also the approximations. A chain is clocked as one design:
 * its period is its slowest stage's. */
typedef struct chain_fig {
    tb_hw_point d16, w16, sq, div, wired;
    double wired_err, cl_d, ar_d, pd_d, cl_w, ar_w, pd_w;
} chain_fig;

static int chains(int width, chain_fig *f)
{
    unit_cfg cfg;
    unit_cfg_default(NULL, &cfg);       /* shared by the units below (their m, alpha) */
    cfg.width = width;
    unit_cfg sqc = cfg;
    sqc.g = 2;
    const size_t nv = 64;
    int bad = 0;
    bad |= tb_hw_point_run("d_approx", &cfg, nv, NULL, 1, &f->d16);
    bad |= tb_hw_point_run("ward_approx", &cfg, nv, NULL, 1, &f->w16);
    bad |= tb_hw_point_run("powg", &sqc, nv, NULL, 1, &f->sq);
    bad |= tb_hw_point_run("div", &cfg, nv, NULL, 1, &f->div);
    bad |= tb_speed_ward_chain(width, &f->wired, &f->wired_err);
    f->cl_w = f->wired.clocks;
    f->ar_w = f->wired.area;
    f->pd_w = f->wired.period_ps;
    f->cl_d = f->wired.clocks + f->sq.clocks + f->div.clocks;
    f->ar_d = f->wired.area + f->sq.area + f->div.area;
    f->pd_d = fmax(f->wired.period_ps, fmax(f->sq.period_ps, f->div.period_ps));
    return bad;
}

/* Time per item, ps: clocks x period. */
static double item_ps(double clocks, double period_ps) { return clocks * period_ps; }
static double ratio(double num, double den) { return den > 0 ? num / den : NAN; }

/* ------------------------------------------- the chain wired together */

/* Ward's exp argument as one design: powg g=2 (c^2) and div wired by a
 * subtractor (1 - c^2) and a holding register for each operand (the
 * divider reads its divisor every clock), loaded when the squarer's
 * result is valid; a valid flag offers the pair to the divider until it
 * takes it. Driven one item at a time: the next c enters when the divider
 * takes its last step with the current one. */
typedef struct chain_tb {
    sim_signal *c_in, *v_in, *rdy1, *v2, *rdy2, *ov2, *q;
    const double *c;
    size_t n, next, ndone;
    int offered, chain_free;
    uint64_t *done;
    int64_t *qraw;
} chain_tb;

/* At each rising edge: collect a quotient; withdraw c once the squarer has
 * taken it; offer the next c as soon as the divider takes its last step
 * with the current item (one item in the chain at a time, no idle clock). */
static void chain_driver(sim_proc *p)
{
    chain_tb *t = p->data;
    if (t->ov2->cur) {
        t->done[t->ndone] = sim_get_stats(p->ctx)->clocks - 1;
        t->qraw[t->ndone++] = t->q->cur;
        if (t->ndone == t->n) { sim_stop(p->ctx); return; }
    }
    if (t->offered && t->v_in->cur && t->rdy1->cur) { sim_write(t->v_in, 0); t->offered = 0; }
    if (t->v2->cur && t->rdy2->cur) t->chain_free = 1;
    if (t->chain_free && !t->offered && t->next < t->n) {
        sim_write(t->c_in, sim_fx_from_real(t->c[t->next++], t->c_in->fmt, SIM_RND_TRUNC, SIM_OVF_SAT, NULL));
        sim_write(t->v_in, 1);
        t->offered = 1;
        t->chain_free = 0;
    }
}

static int64_t valid_next(const int64_t *in, void *u) { (void)u; return in[0] | (in[1] & !in[2]); }

static int build_unit(sim_ctx *c, sim_scope *parent, sim_signal *clk, const char *name, const unit_cfg *cfg,
                      unit_io *io)
{
    const unit_desc *u = unit_find(name);
    unit_fmts f;
    char err[600];
    memset(io, 0, sizeof *io);
    if (!u || tb_formats(u, cfg, NULL, 0, &f, err, sizeof err)) return -1;
    return u->build(c, sim_scope_new(c, parent, name), clk, cfg, &f, io, err, sizeof err);
}

int tb_speed_ward_chain(int width, tb_hw_point *pt, double *max_err_lsb)
{
    enum { N = 32 };
    memset(pt, 0, sizeof *pt);
    pt->unit = "ward_exp_arg";
    unit_cfg cfg;
    unit_cfg_default(NULL, &cfg);
    cfg.width = width;
    unit_cfg sqc = cfg;
    sqc.g = 2;
    sim_ctx *c = sim_new();
    sim_set_quant(c, cfg.rnd, cfg.ovf);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_clock(c, clk, 5, 5);
    sim_scope *top = sim_scope_new(c, NULL, "ward_exp_arg");
    unit_io sq, dv;
    int rc = -1;
    double cv[N];
    uint64_t done[N];
    int64_t qraw[N];
    if (build_unit(c, top, clk, "powg", &sqc, &sq) || build_unit(c, top, clk, "div", &cfg, &dv)) goto out;
    sim_scope *g = sim_scope_new(c, top, "glue");
    sim_fmt fn = dv.in[0]->fmt, fd = dv.in[1]->fmt, u1 = unit_fmt(0, 1, 0);
    sim_signal *one = sim_const(c, g, "one", fn, 1.0);
    sim_signal *num = sim_sub(c, g, "num", fn, one, sq.out[0]);
    sim_signal *hn = sim_reg(c, g, "hn", fn, clk, num, sq.out_valid, NULL, 0);
    sim_signal *hd = sim_reg(c, g, "hd", fd, clk, sq.out[0], sq.out_valid, NULL, 0);
    sim_signal *v = sim_reg(c, g, "v", u1, clk, NULL, NULL, NULL, 0);
    sim_signal *vin[3] = { sq.out_valid, v, dv.in_ready };
    sim_reg_connect(v, sim_logic(c, g, "v_next", u1, 3, vin, valid_next, NULL, 2 * SIM_GE_NAND2));
    sim_assign(c, dv.in[0], hn);
    sim_assign(c, dv.in[1], hd);
    sim_assign(c, dv.in_valid, v);
    for (int i = 0; i < N; i++) cv[i] = 0.75 + 0.25 * i / N;     /* c^2 > 1/2: the quotient stays below 1 */
    chain_tb t = { sq.in[0], sq.in_valid, sq.in_ready, v, dv.in_ready, dv.out_valid, dv.out[0], cv, N, 0, 0, 0, 1,
                   done, qraw };
    sim_proc *drv = sim_proc_new(c, "tb.driver", chain_driver, &t);
    sim_sensitive(drv, clk, SIM_EDGE_POS);
    drv->no_init = 1;
    if (sim_run(c, (sim_time)N * (width + 16) * 10) != SIM_OK || t.ndone != N) goto out;
    pt->clocks = (double)(done[N - 1] - done[0]) / (N - 1);
    pt->area = sim_scope_area(top);
    tb_ppa ppa;
    char terr[200];
    if (tb_ppa_timing(c, top, pt->clocks, &ppa, terr, sizeof terr)) goto out;
    pt->period_ps = ppa.crit_ps;
    double worst = 0, lsb = sim_fmt_lsb(dv.out[0]->fmt);
    for (int i = 0; i < N; i++) {
        double x = sim_fx_to_real(sim_fx_from_real(cv[i], sq.in[0]->fmt, SIM_RND_TRUNC, SIM_OVF_SAT, NULL),
                                  sq.in[0]->fmt);
        worst = fmax(worst, fabs(sim_fx_to_real(qraw[i], dv.out[0]->fmt) - (1 - x * x) / (x * x)) / lsb);
    }
    *max_err_lsb = worst;
    pt->ok = 1;
    rc = 0;
out:
    sim_free(c);
    return rc;
}

void tb_speed_hw_measure(int width, tb_speed_hw *h)
{
    memset(h, 0, sizeof *h);
    h->width = width;
    chain_fig f;
    int bad = chains(width, &f);
    h->d16 = f.d16; h->ward16 = f.w16; h->sq = f.sq; h->div = f.div; h->wired = f.wired;
    h->wired_err_lsb = f.wired_err;
    h->exact_d_clocks = f.cl_d; h->exact_d_area = f.ar_d; h->exact_d_period_ps = f.pd_d;
    h->exact_w_clocks = f.cl_w; h->exact_w_area = f.ar_w; h->exact_w_period_ps = f.pd_w;
    unit_cfg cfg;
    unit_cfg_default(NULL, &cfg);
    cfg.width = width;
    unit_cfg pd = cfg, pw = cfg;
    pd.n = (int)lround(2.0 / (cfg.m * cfg.m) - 4.0);
    pw.n = (int)lround(2.0 / (cfg.alpha * cfg.alpha));
    bad |= tb_hw_point_run("pow_n", &pd, 64, NULL, 1, &h->pow_d);
    bad |= tb_hw_point_run("pow_n", &pw, 64, NULL, 1, &h->pow_w);
    h->n_d = pd.n;
    h->n_w = pw.n;
    snprintf(h->pow_d.label, sizeof h->pow_d.label, "pow_n n=%d", pd.n);
    snprintf(h->pow_w.label, sizeof h->pow_w.label, "pow_n n=%d", pw.n);
    for (int i = 0; i < TB_SPEED_NW; i++) {
        chain_fig g;
        bad |= chains(tb_speed_widths[i], &g);
        double td = item_ps(g.d16.clocks, g.d16.period_ps), tw = item_ps(g.w16.clocks, g.w16.period_ps);
        double slow = fmax(g.sq.clocks, g.div.clocks);
        h->lad_d[i] = ratio(item_ps(g.cl_d, g.pd_d), td);
        h->lad_w[i] = ratio(item_ps(g.cl_w, g.pd_w), tw);
        h->clk_d[i] = ratio(g.cl_d, g.d16.clocks);
        h->clk_w[i] = ratio(g.cl_w, g.w16.clocks);
        h->ovl_d[i] = ratio(item_ps(slow, g.pd_d), td);
        h->ovl_w[i] = ratio(item_ps(slow, g.pd_w), tw);
    }
    h->ok = !bad;
}

/* Holds when the approximation beats the claim in time per item at every
 * width of the ladder both one item at a time and against the chain's
 * stages overlapped; only one item at a time; only at some widths; or
 * nowhere. strict: "more than" the claim. */
static int beats(double v, double claimed, int strict) { return strict ? v > claimed : v >= claimed; }
static const char *verdict(const double *lad, const double *ovl, double claimed, int strict)
{
    int n = 0, no = 0, first = -1, suffix = 1;
    for (int i = 0; i < TB_SPEED_NW; i++) {
        int b = beats(lad[i], claimed, strict);
        n += b;
        no += beats(ovl[i], claimed, strict);
        if (b && first < 0) first = i;
        if (!b && first >= 0) suffix = 0;
    }
    if (n == TB_SPEED_NW && no == TB_SPEED_NW) return CLAIM_HOLDS;
    if (n == TB_SPEED_NW) return CLAIM_HOLDS_ONLY "items computed one after another (not against the exact "
                                                  "chain's stages overlapped at every width: the note)";
    /* the ratio grows with the width (a divider step a quotient bit): the
     * widths that hold are the wider ones, named from the ladder */
    static const char *const from[TB_SPEED_NW] = {
        "", CLAIM_HOLDS_ONLY "widths of 16 bits and more (of 8, 16, 24), items computed one after another",
        CLAIM_HOLDS_ONLY "widths of 24 bits and more (of 8, 16, 24), items computed one after another" };
    if (n && suffix && first > 0) return from[first];
    if (n) return CLAIM_HOLDS_ONLY "some of the widths 8, 16, 24 (the note gives each)";
    return CLAIM_FAILS;
}

/* One row: the approximation a against the exact chain (clocks, period,
 * area), in time per item; the note the ladder's time ratios. */
typedef struct row_in {
    const char *id, *claim, *exact_name, *chain_note;
    double claimed;
    int strict;
    const tb_hw_point *a;
    double ex_cl, ex_pd, ex_ar;
    const double *lad, *clk, *ovl;
} row_in;

static void speed_row(const tb_speed_hw *h, const row_in *in, claim_result *r)
{
    double ta = item_ps(in->a->clocks, in->a->period_ps), te = item_ps(in->ex_cl, in->ex_pd);
    r->id = in->id;
    r->source = "Nechyporuk & Romanyuk (2020), sec. III results; S. O. Romanyuk et al. (SPIE), sec. 4";
    r->claim = in->claim;
    r->claimed = in->claimed;
    r->measured = ta > 0 ? te / ta : 0;
    tb_settext(r->measured_text, sizeof r->measured_text,
               "%.3gx less time per item: %s %.0f clocks x %.0f ps, %s %.0f x %.0f ps (W %d); %.3gx in clocks "
               "alone; time x area %.3gx", r->measured, in->a->unit, in->a->clocks, in->a->period_ps,
               in->exact_name, in->ex_cl, in->ex_pd, h->width, ratio(in->ex_cl, in->a->clocks),
               ratio(te * in->ex_ar, ta * in->a->area));
    r->verdict = verdict(in->lad, in->ovl, r->claimed, in->strict);
    tb_settext(r->note, sizeof r->note,
               "%s, at the slowest stage's clock; exp not counted (lower bound). Time ratio at W=8, 16, 24: "
               "%.3gx, %.3gx, %.3gx (clocks %.3gx, %.3gx, %.3gx); stages overlapped: %.3gx, %.3gx, %.3gx",
               in->chain_note, in->lad[0], in->lad[1], in->lad[2], in->clk[0], in->clk[1], in->clk[2], in->ovl[0],
               in->ovl[1], in->ovl[2]);
}

size_t tb_speed_hw_rows(const tb_speed_hw *h, claim_result *out)
{
    memset(out, 0, 2 * sizeof *out);
    const row_in in[2] = {
        { "d16_speed_hw", "computing D16 instead of D raises the speed 4.34 times (here: time per item in our "
          "hardware)", "exact D w/o exp", "exact D: powg g=2 + div wired as one design, then powg, div", 4.34, 0, &h->d16, h->exact_d_clocks, h->exact_d_period_ps, h->exact_d_area,
          h->lad_d, h->clk_d, h->ovl_d },
        { "ward_speed_hw", "for the Ward model the speed gain of the approximation is more than twice (here: time "
          "per item)", "exp term w/o exp", "exp(-tan^2/a^2)'s argument: powg g=2 + div wired as one design", 2.0, 1, &h->ward16, h->exact_w_clocks,
          h->exact_w_period_ps, h->exact_w_area, h->lad_w, h->clk_w, h->ovl_w },
    };
    for (int i = 0; i < 2; i++) speed_row(h, &in[i], &out[i]);
    return 2;
}
