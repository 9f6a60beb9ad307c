/* unit_span_bound.c - the span units' error bound (docs/bounds.md): the
 * coefficient networks' and the datapath's errors, as interp's, plus t's
 * quantization (the reciprocal ROM's words and t's format) times the
 * largest slope of the polynomial over every node value the input formats
 * hold, by interval arithmetic.
 */
#include "units/unit_span.h"
#include <math.h>

/* t's error and fraction bits for a ROM of format frcp: t_hw = Q_t(k rcp)
 * differs from k/dv by k (1/dv - rcp) (at most its largest at k = dv, *rom)
 * plus t's own quantization from the fraction bits k rcp really has, at
 * most those of the ROM's words (*src: the most any word has). */
static void rom_err(const unit_cfg *cfg, sim_fmt frcp, double *rom, int *src)
{
    int L = span_valid_L(cfg->L) ? cfg->L : 8;
    span_rom r;
    span_rom_fill(&r, L, frcp);
    *rom = 0;
    *src = 0;
    for (int dv = 1; dv <= L; dv++) {
        /* dv (1/dv - w) = (2^F - dv raw) 2^-F, the numerator exact in 128 bits */
        sim_wide num = ((sim_wide)1 << frcp.fbits) - (sim_wide)dv * r.raw[dv];
        *rom = fmax(*rom, ldexp(fabs((double)num), -frcp.fbits));
        int fb = frcp.fbits;
        for (int64_t x = r.raw[dv]; x && !(x & 1) && fb > 0; x >>= 1) fb--;
        if (r.raw[dv] && fb > *src) *src = fb;
    }
}

/* --------------------------------------------------------------- bound */

/* Range of g(x) = c2 x^2 + c1 x + c0 over [u, v]. */
static void quad_range(double c2, double c1, double c0, double u, double v, double *lo, double *hi)
{
    double a = (c2 * u + c1) * u + c0, b = (c2 * v + c1) * v + c0;
    *lo = fmin(a, b);
    *hi = fmax(a, b);
    if (c2 != 0) {
        double x = -c1 / (2 * c2);
        if (x > u && x < v) {
            double m = (c2 * x + c1) * x + c0;
            *lo = fmin(*lo, m);
            *hi = fmax(*hi, m);
        }
    }
}

/* An upper bound on |p'(x)| for x in [0, 1] and every input I_i in
 * [lo_i, hi_i], p(x) = sum_j coef_j x^(deg-j) with coef_j = coef[j].lin . I:
 * p'(x) = sum_i I_i g_i(x), each g_i a polynomial of degree deg-1 <= 2.
 * Interval arithmetic on 512 pieces of [0, 1]: on each, g_i's exact range
 * times I_i's range, summed; sound, and within a few percent of the true
 * maximum. */
static double deriv_max(int deg, const unet_val *coef, const double *lo, const double *hi, int nin)
{
    enum { PIECES = 512 };
    double best = 0;
    for (int p = 0; p < PIECES; p++) {
        double u = (double)p / PIECES, v = (double)(p + 1) / PIECES, slo = 0, shi = 0;
        for (int i = 0; i < nin; i++) {
            double c[3] = { 0, 0, 0 };     /* c2 c1 c0 of g_i */
            for (int j = 0; j < deg; j++) c[3 - (deg - j)] = (deg - j) * coef[j].lin[i];
            double gl, gh;
            quad_range(c[0], c[1], c[2], u, v, &gl, &gh);
            double pr[4] = { lo[i] * gl, lo[i] * gh, hi[i] * gl, hi[i] * gh };
            double mn = pr[0], mx = pr[0];
            for (int k = 1; k < 4; k++) { mn = fmin(mn, pr[k]); mx = fmax(mx, pr[k]); }
            slo += mn;
            shi += mx;
        }
        best = fmax(best, fmax(fabs(slo), fabs(shi)));
    }
    return best * (1 + 1e-9);      /* the double roundings of the sums above */
}

/* A value as the datapath walks see it (as unit_horner.c's h_val): its
 * worst-case error and the fraction bits it can really have, so that a
 * quantization counts only the bits it drops below those (widening a
 * signal moves a truncation downstream instead of adding one). */
typedef struct sp_val { double e; int eff; } sp_val;

static int imin(int a, int b) { return a < b ? a : b; }
static int imax(int a, int b) { return a > b ? a : b; }

/* v into format f. */
static sp_val sp_pass(sp_val v, sim_fmt f, sim_round r)
{
    return (sp_val){ v.e + unit_qerr(f, v.eff, r), imin(f.fbits, v.eff) };
}
/* a + b into format f. */
static sp_val sp_add(sp_val a, sp_val b, sim_fmt f, sim_round r)
{
    return sp_pass((sp_val){ a.e + b.e, imax(a.eff, b.eff) }, f, r);
}

/* span1's datapath error for coefficients exact in ra, rb with fa_eff,
 * fb_eff fraction bits and t exact with ft_eff: the quantizations of its
 * elements (as the Horner's bound walks its table; multiplying by t in
 * [0, 1] does not grow an error). paper: RG <= MX2(B) + 0, then RG <=
 * MX2(MUL) + BK(RG); mac and pipe: RG <= MUL + RB. */
static double lin_dp_bound(const span_kind *K, int sched, const unit_fmts *f, int fa_eff, int fb_eff,
                           int ft_eff, sim_round r)
{
    sim_fmt fmul = f->f[span_sig(K, "mul")], fsm = f->f[span_sig(K, "sm")], frg = f->f[span_sig(K, "rg")], fy = f->f[span_sig(K, "y")];
    sp_val mul = sp_pass((sp_val){ 0, fa_eff + ft_eff }, fmul, r), b = { 0, fb_eff }, rg;
    if (sched == SP_PAPER) {
        sim_fmt fmx2 = f->f[span_sig(K, "mx2")], fbk = f->f[span_sig(K, "bk")];
        sp_val zero = { 0, -64 };           /* BK forcing zero: exact, no fraction bits */
        rg = sp_pass(sp_add(sp_pass(b, fmx2, r), zero, fsm, r), frg, r);
        rg = sp_pass(sp_add(sp_pass(mul, fmx2, r), sp_pass(rg, fbk, r), fsm, r), frg, r);
    } else {
        rg = sp_pass(sp_add(mul, b, fsm, r), frg, r);
    }
    return sp_pass(rg, fy, r).e;
}

/* A register's format as the datapath sees it: no more fraction bits than
 * the value it holds has (eff), so that the walk does not count bits a
 * wide register never holds. */
static sim_fmt held_fmt(sim_fmt f, int eff)
{
    return eff < f.fbits ? unit_fmt(f.is_signed, f.ibits, eff < 0 ? 0 : eff) : f;
}

/* The bound of items of one degree: network net's coefficients go to the
 * registers slot[0..deg_poly] and run on the datapath of degree hdeg
 * (span23's quadratic: slots 0-2 on the degree-2 sequence, or 1-3 on the
 * cubic pipe with ra = 0). Coefficient errors (the network's walk plus the
 * register's quantization) reach y times t^m <= 1; the datapath's own from
 * horner_bound_on (span1: lin_dp_bound) for the fraction bits the
 * registers and t really hold; t's error et times max |p'|. */
static double path_bound(const span_kind *K, const unit_cfg *cfg, const unit_fmts *f, const coef_net *net,
                         int deg_poly, const int *slot, int hdeg, int nrom, const double *et, const int *t_eff)
{
    const unit_desc *u = K->u;
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    for (int i = 0; i < net->nin; i++) in[i] = unet_input(&n, span_in_names[i], i);
    if (coef_walk(&n, net, in, cfg->terms, cfg->series, o)) return INFINITY;
    double e = 0;
    sim_fmt rf[4];
    int hd = span_main_deg(K);
    /* registers no coefficient of this degree is loaded into hold 0 (span23's ra on the pipe) */
    for (int j = 0; j <= hd; j++) rf[j] = held_fmt(f->f[span_sig(K, span_reg_names[j])], 0);
    for (int j = 0; j <= deg_poly; j++) {
        sim_fmt fr = f->f[span_sig(K, span_reg_names[slot[j]])];
        e += o[j].err + unit_qerr(fr, o[j].eff, cfg->rnd);
        rf[slot[j]] = held_fmt(fr, o[j].eff);
    }
    double lo[UNET_MAXIN], hi[UNET_MAXIN];
    for (int i = 0; i < net->nin; i++) {
        sim_fmt fi = f->f[span_sig(K, span_in_names[i])];
        lo[i] = sim_fmt_real_min(fi);
        hi[i] = sim_fmt_real_max(fi);
    }
    double D = deriv_max(deg_poly, o, lo, hi, net->nin), worst = 0;
    sim_fmt fy = f->f[span_sig(K, "y")];
    for (int i = 0; i < nrom; i++) {
        /* t as the Horner sees it: the fraction bits its values really have */
        sim_fmt ft = held_fmt(f->f[span_sig(K, "t")], t_eff[i]);
        double h = hdeg == 1 ? lin_dp_bound(K, cfg->schedule, f, rf[0].fbits, rf[1].fbits, ft.fbits, cfg->rnd)
                             : horner_bound_on(hdeg, cfg->schedule, rf, ft, u, f, fy, cfg->rnd);
        worst = fmax(worst, e + h + D * et[i]);
    }
    return worst;
}

/* The bound is the largest over ROMs of rcp's format and every wider one
 * (up to 63 bits): a wider ROM word can gain a fraction bit (more for t's
 * quantization and the multipliers to drop) without lowering the worst
 * pixel's ROM error, and a --fmt that widens rcp must not make the bound
 * grow. Each is a bound of the unit with that ROM; the one of rcp's own
 * format is among them, so the largest is sound. */
void span_bound(const span_kind *K, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    static const int s0[4] = { 0, 1, 2, 3 }, s1[3] = { 1, 2, 3 };
    sim_fmt frcp = f->f[span_sig(K, "rcp")], ft = f->f[span_sig(K, "t")];
    double et[64];
    int t_eff[64], nrom = 0;
    for (int F = frcp.fbits; nrom < 64; F++) {
        sim_fmt fr = unit_fmt(frcp.is_signed, frcp.ibits, F);
        if (fr.fbits != F) break;                       /* the widest format there is */
        double rom;
        int src;
        rom_err(cfg, fr, &rom, &src);
        et[nrom] = rom + unit_qerr(ft, src, cfg->rnd);
        t_eff[nrom++] = src < ft.fbits ? src : ft.fbits;
    }
    if (!nrom) { per_out[0] = INFINITY; return; }
    int deg = span_main_deg(K);
    double e = path_bound(K, cfg, f, span_main_net(K, cfg), deg, s0, deg, nrom, et, t_eff);
    if (K->kind == K_ADAPT) {
        int pipe = cfg->schedule == SP_PIPE;
        e = fmax(e, path_bound(K, cfg, f, &span_net_q2, 2, pipe ? s1 : s0, pipe ? 3 : 2, nrom, et, t_eff));
    }
    per_out[0] = e;
}
