/* unit_span_hw.c - the span units' hardware (unit_span.c describes the
 * units): the reciprocal ROM and t = k * rcp, the item control (busy, the
 * pixel counter k, n and dv latched, in_ready), span1's own multiply-add,
 * span23's degree-switched controller, and the build that joins them to
 * the coefficient networks and the Horner datapath (unit_horner.h).
 */
#include "units/unit_span.h"
#include "sim/sim_area.h"
#include <string.h>

/* ---------------------------------------------------- the reciprocal ROM */

/* dv = 1..L (span_rom in unit_span.h). */
void span_rom_fill(span_rom *r, int L, sim_fmt f)
{
    memset(r, 0, sizeof *r);
    r->L = L;
    int64_t mx = sim_fmt_raw_max(f);
    for (int dv = 1; dv <= L && dv <= SPAN_LMAX; dv++) {
        sim_wide one = f.fbits >= 0 ? (sim_wide)1 << f.fbits : 0;
        sim_wide q = one / dv;
        r->raw[dv] = q > mx ? mx : (int64_t)q;
    }
}

/* in: dv. The ROM's word. */
static int64_t f_rom(const int64_t *in, void *user)
{
    const span_rom *r = user;
    return in[0] >= 0 && in[0] <= r->L ? r->raw[in[0]] : 0;
}

/* ------------------------------------------------------------- control */

/* The fraction bits of an integer input's format (f_is2 drops them). */
typedef struct int_in { int fbits; } int_in;

/* in: k, rn. The item's last pixel: k + 1 >= n (n = 0 counts as 1). */
static int64_t f_kend(const int64_t *in, void *u) { (void)u; return in[0] + 1 >= in[1]; }
/* in: busy, kend, last. Ready when idle or in the last step of the last pixel. */
static int64_t f_ready(const int64_t *in, void *u) { (void)u; return !in[0] || (in[1] && in[2]); }
static int64_t f_and(const int64_t *in, void *u) { (void)u; return in[0] && in[1]; }
static int64_t f_andn(const int64_t *in, void *u) { (void)u; return in[0] && !in[1]; }
/* in: k, kend, last. */
static int64_t f_k_next(const int64_t *in, void *u) { (void)u; return in[2] ? (in[1] ? 0 : in[0] + 1) : in[0]; }
/* in: accept, busy, kend, last. */
static int64_t f_busy_next(const int64_t *in, void *u)
{
    (void)u;
    return in[0] || (in[1] && !(in[2] && in[3]));
}
/* in: deg (raw, fbits in user). 1 for a degree-2 item. */
static int64_t f_is2(const int64_t *in, void *u)
{
    const int_in *q = u;
    return (q->fbits >= 0 ? in[0] >> q->fbits : in[0]) == 2;
}
/* span1 paper, in: step, run. Two steps a pixel; waits at 0. */
static int64_t f_step1(const int64_t *in, void *u) { (void)u; return in[0] ? 0 : in[1] != 0; }
static int64_t f_copy(const int64_t *in, void *u) { (void)u; return in[0]; }
static int64_t f_not(const int64_t *in, void *u) { (void)u; return !in[0]; }

typedef struct span_ctl {
    sim_signal *busy, *k, *rn, *rdv, *kend, *accept;
} span_ctl;

/* A register that loads x on accept and holds otherwise (its load mux
 * built once accept exists: hold_connect). */
static sim_signal *hold_reg(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt f, sim_signal *clk)
{
    return sim_reg(c, sc, name, f, clk, NULL, NULL, NULL, 0);
}
static void hold_connect(sim_ctx *c, sim_scope *sc, const char *name, sim_signal *r, sim_signal *accept,
                         sim_signal *x)
{
    sim_signal *in[2] = { r, x };
    sim_reg_connect(r, sim_mux(c, sc, name, r->fmt, accept, 2, in));
}

/* The item's state: busy, the pixel counter k, n and dv latched. */
static void state_regs(sim_ctx *c, sim_scope *sc, sim_signal *clk, int G, span_ctl *ctl)
{
    sim_fmt fk = unit_fmt(0, G, 0);
    ctl->busy = sim_reg(c, sc, "busy", unit_fmt(0, 1, 0), clk, NULL, NULL, NULL, 0);
    ctl->k = sim_reg(c, sc, "k", fk, clk, NULL, NULL, NULL, 0);
    ctl->rn = hold_reg(c, sc, "rn", fk, clk);
    ctl->rdv = hold_reg(c, sc, "rdv", fk, clk);
    sim_signal *ke_in[2] = { ctl->k, ctl->rn };
    /* a G-bit comparator: about a full adder a bit */
    ctl->kend = sim_logic(c, sc, "kend", unit_fmt(0, 1, 0), 2, ke_in, f_kend, NULL, G * SIM_GE_FA);
}

/* in_ready, accept, the next k and busy around `last` (1 in the clock a
 * pixel's last step runs); n and dv load on an accept. */
static void control(sim_ctx *c, sim_scope *sc, int G, sim_signal *last, sim_signal *n_in, sim_signal *dv_in,
                    unit_io *io, span_ctl *ctl)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *rdy_in[3] = { ctl->busy, ctl->kend, last };
    io->in_ready = sim_logic(c, sc, "in_ready", u1, 3, rdy_in, f_ready, NULL, 2 * SIM_GE_NAND2);
    sim_signal *acc_in[2] = { io->in_valid, io->in_ready };
    ctl->accept = sim_logic(c, sc, "accept", u1, 2, acc_in, f_and, NULL, SIM_GE_AND2);
    sim_signal *kn_in[3] = { ctl->k, ctl->kend, last };
    /* an incrementer, a clear and an enable mux a bit */
    sim_reg_connect(ctl->k, sim_logic(c, sc, "k_next", ctl->k->fmt, 3, kn_in, f_k_next, NULL,
                                      G * (SIM_GE_HA + SIM_GE_AND2 + SIM_GE_MUX2)));
    sim_signal *bn_in[4] = { ctl->accept, ctl->busy, ctl->kend, last };
    sim_reg_connect(ctl->busy, sim_logic(c, sc, "busy_next", u1, 4, bn_in, f_busy_next, NULL, 3 * SIM_GE_NAND2));
    hold_connect(c, sc, "rn_in", ctl->rn, ctl->accept, n_in);
    hold_connect(c, sc, "rdv_in", ctl->rdv, ctl->accept, dv_in);
}

/* ------------------------------------------------------------ datapaths */

/* span1's multiply-add. paper: step 0 RG <= B (MX2 = B, BK zero), step 1
 * RG <= A t + RG (MX2 = MUL, BK passes); mac and pipe: RG <= A t + B every
 * clock. Returns the result register; *last is 1 in the clock a pixel's
 * last step runs (the register holds the pixel after that edge). */
static sim_signal *dp_lin(sim_ctx *c, sim_scope *sc, sim_signal *clk, int sched, sim_signal *run,
                          sim_signal *ra, sim_signal *rb, sim_signal *t, const span_kind *K,
                          const unit_fmts *f, sim_signal **last)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *rg = sim_reg(c, sc, "rg", f->f[span_sig(K, "rg")], clk, NULL, NULL, NULL, 0);
    sim_signal *mul = sim_mul(c, sc, "mul", f->f[span_sig(K, "mul")], ra, t);
    if (sched == SP_PAPER) {
        sim_signal *step = sim_reg(c, sc, "step", u1, clk, NULL, NULL, NULL, 0);
        sim_signal *nx_in[2] = { step, run };
        sim_reg_connect(step, sim_logic(c, sc, "step_next", u1, 2, nx_in, f_step1, NULL, 2 * SIM_GE_NAND2));
        /* step 1 selects MUL and passes RG: the step bit is both selects */
        sim_signal *mx2_sel = sim_logic(c, sc, "mx2_sel", u1, 1, &step, f_not, NULL, SIM_GE_INV);
        sim_signal *bk_pass = sim_logic(c, sc, "bk_pass", u1, 1, &step, f_copy, NULL, 0);
        sim_signal *mx2_in[2] = { mul, rb };
        sim_signal *mx2 = sim_mux(c, sc, "mx2", f->f[span_sig(K, "mx2")], mx2_sel, 2, mx2_in);
        sim_signal *bk = sim_bk(c, sc, "bk", f->f[span_sig(K, "bk")], bk_pass, rg);
        sim_reg_connect(rg, sim_add(c, sc, "sm", f->f[span_sig(K, "sm")], mx2, bk));
        *last = sim_logic(c, sc, "last", u1, 1, &step, f_copy, NULL, 0);
    } else {
        sim_reg_connect(rg, sim_add(c, sc, "sm", f->f[span_sig(K, "sm")], mul, rb));
        *last = run;
    }
    return rg;
}

/* span23's paper and mac controller: the Horner's controllers of degree 2
 * and 3, each run by its own items (run && is2, run && !is2), their
 * decoders selected by the item's degree. Both rest at step 0 between
 * their items, so the switch needs no gap. */
static void ctl_adapt(sim_ctx *c, sim_scope *hsc, sim_signal *clk, int sched, sim_signal *run, sim_signal *is2,
                      horner_hw *hw)
{
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *r2_in[2] = { run, is2 };
    sim_signal *run2 = sim_logic(c, hsc, "run2", u1, 2, r2_in, f_and, NULL, SIM_GE_AND2);
    sim_signal *run3 = sim_logic(c, hsc, "run3", u1, 2, r2_in, f_andn, NULL, SIM_GE_AND2 + SIM_GE_INV);
    horner_hw h2, h3;
    horner_ctl_on(c, sim_scope_new(c, hsc, "ctl2"), clk, 2, sched, run2, "last", &h2);
    horner_ctl_on(c, sim_scope_new(c, hsc, "ctl3"), clk, 3, sched, run3, "last", &h3);
    *hw = h3;
    sim_signal *in[2];
    in[0] = h3.mx1_sel; in[1] = h2.mx1_sel;
    hw->mx1_sel = sim_mux(c, hsc, "mx1_sel", h3.mx1_sel->fmt, is2, 2, in);
    in[0] = h3.mx2_sel; in[1] = h2.mx2_sel;
    hw->mx2_sel = sim_mux(c, hsc, "mx2_sel", h3.mx2_sel->fmt, is2, 2, in);
    if (sched == SP_PAPER) {
        in[0] = h3.bk_pass; in[1] = h2.bk_pass;
        hw->bk_pass = sim_mux(c, hsc, "bk_pass", u1, is2, 2, in);
    }
    in[0] = h3.last; in[1] = h2.last;
    hw->last = sim_mux(c, hsc, "last", u1, is2, 2, in);
}

/* --------------------------------------------------------------- build */

/* What the build cannot make: an L, schedule or node set out of range,
 * formats of t and rcp that cannot hold 1 and 1/L, of n, dv (and deg)
 * that cannot hold L (and 3). 0, or -1 with a message. */
static int build_check(const span_kind *K, const unit_cfg *cfg, const unit_fmts *f, char *err, size_t errlen)
{
    const unit_desc *u = K->u;
    int L = cfg->L;
    if (!span_valid_L(L)) { snprintf(err, errlen, "%s: L = %d is outside 2..%d", u->name, L, SPAN_LMAX); return -1; }
    if (cfg->schedule < 0 || cfg->schedule >= u->nsched) { snprintf(err, errlen, "%s: no schedule %d", u->name, cfg->schedule); return -1; }
    if (cfg->nodes < 0 || cfg->nodes > 1) { snprintf(err, errlen, "%s: no node set %d", u->name, cfg->nodes); return -1; }
    sim_fmt ft = f->f[span_sig(K, "t")], frcp = f->f[span_sig(K, "rcp")];
    if (sim_fmt_real_max(ft) < 1 || sim_fmt_real_max(frcp) < 1.0 / L) {
        char b1[SIM_FMT_STRLEN], b2[SIM_FMT_STRLEN];
        snprintf(err, errlen, "%s: t format %s must hold 1 and rcp format %s 1/L = 1/%d", u->name,
                 sim_fmt_str(ft, b1), sim_fmt_str(frcp, b2), L);
        return -1;
    }
    static const char *const ints[] = { "n", "dv", "deg" };
    for (int i = 0; i < (K->kind == K_ADAPT ? 3 : 2); i++) {
        sim_fmt fi = f->f[span_sig(K, ints[i])];
        int need = i < 2 ? L : 3;
        if (sim_fmt_real_max(fi) < need) {
            char b[SIM_FMT_STRLEN];
            snprintf(err, errlen, "%s: %s format %s cannot hold %d", u->name, ints[i], sim_fmt_str(fi, b), need);
            return -1;
        }
    }
    return 0;
}

/* The inputs, in the descriptor's order (io->in), and the coefficient
 * networks in scope "coef": the main one's coefficients into o, span23's
 * quadratic's into q and its degree decoded (*is2: 1 for a degree-2
 * item). 0, or -1 with a message. */
static int build_nets(const span_kind *K, sim_ctx *c, sim_scope *sc, const unit_cfg *cfg, const unit_fmts *f,
                      unit_io *io, unet_val *o, unet_val *q, sim_signal **is2, char *err, size_t errlen)
{
    unet n;
    unet_val in[UNET_MAXIN];
    unet_init(&n, K->u, f, cfg->rnd);
    unet_hw(&n, c, sc);
    for (int i = 0; i < K->nin; i++) {
        in[i] = unet_input(&n, span_in_names[i], i);
        io->in[i] = in[i].s;
    }
    io->in[K->nin] = sim_signal_new(c, sc, "n", f->f[span_sig(K, "n")], SIM_KIND_INPUT);
    io->in[K->nin + 1] = sim_signal_new(c, sc, "dv", f->f[span_sig(K, "dv")], SIM_KIND_INPUT);
    *is2 = NULL;
    if (K->kind == K_ADAPT) {
        sim_fmt fd = f->f[span_sig(K, "deg")];
        io->in[K->nin + 2] = sim_signal_new(c, sc, "deg", fd, SIM_KIND_INPUT);
        int_in *qi = sim_alloc(c, sizeof *qi);
        qi->fbits = fd.fbits;
        *is2 = sim_logic(c, sc, "is2", unit_fmt(0, 1, 0), 1, &io->in[K->nin + 2], f_is2, qi, fd.width * SIM_GE_AND2);
    }
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    n.sc = sim_scope_new(c, sc, "coef");
    if (coef_walk(&n, span_main_net(K, cfg), in, cfg->terms, cfg->series, o)
        || (K->kind == K_ADAPT && coef_walk(&n, &span_net_q2, in, cfg->terms, cfg->series, q))) {
        snprintf(err, errlen, "%s", n.why);
        return -1;
    }
    return 0;
}

/* The item control and the Horner's controller (or span1's) in scope
 * hsc: hw's selects, and the signal `last` the control counts pixels by
 * (span1 paper: a wire its datapath drives later). span23: *rdeg, the
 * item's latched degree, loaded once the control's accept exists. */
static sim_signal *build_ctl(const span_kind *K, sim_ctx *c, sim_scope *sc, sim_scope *hsc, sim_signal *clk,
                             int sched, span_ctl *ctl, horner_hw *hw, sim_signal **rdeg)
{
    int deg = span_main_deg(K);
    sim_fmt u1 = unit_fmt(0, 1, 0);
    memset(hw, 0, sizeof *hw);
    *rdeg = NULL;
    if (K->kind == K_ADAPT) {
        *rdeg = hold_reg(c, sc, "rdeg", u1, clk);
        if (sched == SP_PIPE) horner_ctl_on(c, hsc, clk, 3, sched, ctl->busy, "last", hw);
        else ctl_adapt(c, hsc, clk, sched, ctl->busy, *rdeg, hw);
        return hw->last;
    }
    if (deg >= 2) {
        horner_ctl_on(c, hsc, clk, deg, sched, ctl->busy, "last", hw);
        return hw->last;
    }
    /* span1 paper: the controller is part of dp_lin; its `last` is
     * needed by the control first, so a wire driven later */
    if (sched == SP_PAPER) return sim_signal_new(c, hsc, "last_w", u1, SIM_KIND_WIRE);
    return ctl->busy;
}

/* The coefficient registers r[0..deg], loaded on an accept; span23's
 * through a degree mux (paper, mac: A2 B2 C2 in A B C's places, D unused;
 * pipe: (0, A2, B2, C2) through the cubic stages). */
static void coef_regs(const span_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk, int sched, const unit_fmts *f,
                      const unet_val *o, const unet_val *q, sim_signal *is2, sim_signal *accept, sim_signal **r)
{
    for (int j = 0; j <= span_main_deg(K); j++) {
        sim_fmt rf = f->f[span_sig(K, span_reg_names[j])];
        sim_signal *d = o[j].s;
        if (K->kind == K_ADAPT) {
            sim_signal *q2 = NULL;
            if (sched == SP_PIPE) q2 = j == 0 ? sim_const_raw(c, sc, "zero", rf, 0) : q[j - 1].s;
            else if (j < 3) q2 = q[j].s;
            if (q2) {
                char nm[8];
                snprintf(nm, sizeof nm, "m%s", span_coef_names[j]);
                sim_signal *mx_in[2] = { d, q2 };
                d = sim_mux(c, sc, nm, rf, is2, 2, mx_in);
            }
        }
        r[j] = sim_reg(c, sc, span_reg_names[j], rf, clk, d, accept, NULL, 0);
    }
}

int span_build(const span_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
               const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    if (build_check(K, cfg, f, err, errlen)) return -1;
    int L = cfg->L, sched = cfg->schedule, deg = span_main_deg(K), G = span_kbits(L);
    sim_fmt u1 = unit_fmt(0, 1, 0), ft = f->f[span_sig(K, "t")], frcp = f->f[span_sig(K, "rcp")];
    unet_val o[UNET_MAXIN], q[UNET_MAXIN];
    sim_signal *is2_in, *rdeg;
    if (build_nets(K, c, sc, cfg, f, io, o, q, &is2_in, err, errlen)) return -1;

    /* Control, the Horner's controller (or span1's), t. */
    span_ctl ctl;
    state_regs(c, sc, clk, G, &ctl);
    sim_scope *hsc = sim_scope_new(c, sc, deg == 1 ? "dp" : "horner");
    horner_hw hw;
    sim_signal *last = build_ctl(K, c, sc, hsc, clk, sched, &ctl, &hw, &rdeg);
    control(c, sc, G, last, io->in[K->nin], io->in[K->nin + 1], io, &ctl);
    if (rdeg) hold_connect(c, sc, "rdeg_in", rdeg, ctl.accept, is2_in);

    span_rom *rom = sim_alloc(c, sizeof *rom);
    span_rom_fill(rom, L, frcp);
    sim_signal *rcp = sim_logic(c, sc, "rcp", frcp, 1, &ctl.rdv, f_rom, rom,
                                sim_area_rom(rom->raw + 1, L, frcp.width));
    sim_signal *t = sim_mul(c, sc, "t", ft, ctl.k, rcp);

    sim_signal *r[4];
    coef_regs(K, c, sc, clk, sched, f, o, q, is2_in, ctl.accept, r);

    sim_signal *res, *done;
    if (deg == 1) {
        sim_signal *lst = NULL;
        res = dp_lin(c, hsc, clk, sched, ctl.busy, r[0], r[1], t, K, f, &lst);
        if (sched == SP_PAPER) sim_assign(c, last, lst);
        done = sched == SP_PAPER ? lst : ctl.busy;
    } else {
        horner_dp_on(c, hsc, clk, &hw, ctl.busy, r, t, K->u, f);
        res = hw.rg;
        done = hw.done;
    }
    io->out[0] = sim_shift(c, sc, "y", f->f[span_sig(K, "y")], res, 0);
    io->out_valid = sim_reg(c, sc, "out_valid", u1, clk, done, NULL, NULL, 0);
    io->scope = sc;
    return 0;
}
