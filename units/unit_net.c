/* unit_net.c - datapaths walked to build, bound or choose formats
 * (unit_net.h). */
#include "units/unit_net.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int imax(int a, int b) { return a > b ? a : b; }
static int imin(int a, int b) { return a < b ? a : b; }

void unet_init(unet *n, const unit_desc *u, const unit_fmts *fm, sim_round r)
{
    memset(n, 0, sizeof *n);
    n->u = u;
    if (fm) n->fm = *fm;
    n->r = r;
    n->fcap = 64;
}

void unet_hw(unet *n, sim_ctx *c, sim_scope *sc)
{
    n->c = c;
    n->sc = sc;
}

void unet_fixed(unet *n, sim_fmt dflt)
{
    n->choose = UNET_FIXED;
    n->dflt = dflt;
}

void unet_clock(unet *n, sim_signal *clk) { n->clk = clk; }

void unet_rule(unet *n, int width, const double *lo, const double *hi, int nin)
{
    n->choose = 1;
    n->width = width;
    for (int i = 0; i < nin && i < UNET_MAXIN; i++) { n->lo[i] = lo[i]; n->hi[i] = hi[i]; }
}

int unet_sig(unet *n, const char *name)
{
    /* The names come from the unit's own network tables: one the unit
     * does not declare is a bug, and a format rule walk (which has no
     * error path) must not carry on with a made-up format. */
    return unit_sig_must(n->u, name);
}

/* Largest |value| a format holds. */
static double fmt_maxabs(sim_fmt f) { return ldexp(1.0, f.is_signed ? f.ibits - 1 : f.ibits); }

/* |x| through a quantization into f: a bound that is a multiple of f's
 * LSB stays one (rounding onto a grid that holds +-mag never passes it);
 * otherwise it may grow by the quantization's error. */
static double copy_mag(unet_val x, sim_fmt f, int src_f, sim_round r)
{
    double g = ldexp(x.mag, f.fbits);
    return g == floor(g) ? x.mag : x.mag + unit_qerr(f, src_f, r);
}

/* Exact range of a linear form over the input box. */
static void lin_range(const unet *n, const double *lin, double *lo, double *hi)
{
    *lo = *hi = 0;
    for (int i = 0; i < UNET_MAXIN; i++) {
        double a = lin[i] * n->lo[i], b = lin[i] * n->hi[i];
        *lo += fmin(a, b);
        *hi += fmax(a, b);
    }
}

/* The smallest format of the rule holding [lo, hi] widened by the error
 * the value has in it: base (from its operands) plus its own quantization
 * from src_f fraction bits. */
static sim_fmt rule_fmt(const unet *n, int is_out, int may_unsigned, const double *lin,
                        double base, int src_f, int f_nat)
{
    double lo, hi;
    lin_range(n, lin, &lo, &hi);
    for (int I = 1; I < 64; I++)
        for (int sg = !may_unsigned; sg <= 1; sg++) {   /* unsigned first: a bit cheaper */
            sim_fmt f = unit_fmt(sg, I, is_out ? n->width - I : f_nat);
            double e = base + unit_qerr(f, src_f, n->r);
            /* The hardware value lies in [lo - e, hi + e] and is a multiple
             * of the LSB, so hi + e < 2^I (unsigned) keeps it <= the
             * format's max; powers of two compare exactly at any width,
             * unlike a 60-bit format's max as a double. */
            double top = ldexp(1.0, sg ? I - 1 : I), bottom = sg ? -top : 0;
            if (lo - e >= bottom && hi + e < top) return f;
        }
    return unit_fmt(1, 64, 0);
}

/* The smallest format holding both a's and b's values, with the finer LSB. */
static sim_fmt fmt_union(sim_fmt a, sim_fmt b)
{
    int sg = a.is_signed || b.is_signed;
    int ia = a.ibits + (sg && !a.is_signed), ib = b.ibits + (sg && !b.is_signed);
    return unit_fmt(sg, imax(ia, ib), imax(a.fbits, b.fbits));
}

/* The format of an element: given (build, bound) or chosen (rule).
 * may_unsigned: the element's value is >= 0 whatever errors its operands
 * carry (a shift or sum of unsigned values; never a difference, which a
 * truncated operand can push below zero when a --fmt override coarsens
 * it), so the rule may pick an unsigned format when the range allows. */
static sim_fmt fmt_of(unet *n, int sig, int may_unsigned, const double *lin, double base,
                      int src_f, int f_nat)
{
    if (sig < 0 || sig >= n->u->nsigs) {
        /* a bug in the unit's walk: no made-up format, in any walk */
        fprintf(stderr, "shadesim: internal error: unit %s: element without a signal (%d)\n", n->u->name, sig);
        abort();
    }
    if (!n->choose) return n->fm.f[sig];
    if (n->choose == UNET_FIXED) return n->fm.f[sig] = n->dflt;
    sim_fmt f = rule_fmt(n, n->u->sigs[sig].role == UNIT_SIG_OUT, may_unsigned, lin, base, src_f, f_nat);
    if (n->chosen[sig]) f = fmt_union(n->fm.f[sig], f);
    n->chosen[sig] = 1;
    n->fm.f[sig] = f;
    return f;
}

unet_val unet_wrap(sim_signal *s, sim_fmt f, int k)
{
    unet_val v;
    memset(&v, 0, sizeof v);
    v.s = s;
    v.f = f;
    v.eff = f.fbits;
    v.mag = v.imag = ldexp(1.0, f.is_signed ? f.ibits - 1 : f.ibits);
    if (k >= 0 && k < UNET_MAXIN) v.lin[k] = 1;
    return v;
}

unet_val unet_input(unet *n, const char *name, int k)
{
    sim_fmt f = n->fm.f[unet_sig(n, name)];
    sim_signal *s = n->c ? sim_signal_new(n->c, n->sc, name, f, SIM_KIND_INPUT) : NULL;
    return unet_wrap(s, f, k);
}

unet_val unet_shift(unet *n, int sig, const char *name, unet_val x, int k)
{
    unet_val v = x;
    for (int i = 0; i < UNET_MAXIN; i++) v.lin[i] = ldexp(x.lin[i], k);
    double base = ldexp(x.err, k);                  /* a shift scales the error too */
    int src_f = x.f.fbits - k;
    /* Lossless: a left shift needs k fewer fraction bits, a right shift k
     * more, up to the cap (terms of the /3 network). */
    int f_nat = k >= 0 ? imax(0, src_f) : imin(src_f, imax(n->fcap, x.f.fbits));
    v.f = fmt_of(n, sig, !x.f.is_signed, v.lin, base, src_f, f_nat);
    int eff_src = x.eff - k;                        /* the bits the shifted value really has */
    v.q = unit_qerr(v.f, eff_src, n->r);
    v.err = base + v.q;
    v.eff = imin(v.f.fbits, eff_src);
    v.mag = fmt_maxabs(v.f);
    if (k == 0) v.mag = fmin(v.mag, copy_mag(x, v.f, eff_src, n->r));   /* a view */
    v.imag = ldexp(x.imag, k);
    v.s = n->c ? sim_shift(n->c, n->sc, name, v.f, x.s, k) : NULL;
    return v;
}

static unet_val addsub(unet *n, int sig, const char *name, unet_val a, unet_val b, int sub)
{
    unet_val v = a;
    for (int i = 0; i < UNET_MAXIN; i++) v.lin[i] = sub ? a.lin[i] - b.lin[i] : a.lin[i] + b.lin[i];
    double base = a.err + b.err;
    int src_f = imax(a.f.fbits, b.f.fbits);         /* the exact sum's fraction bits */
    v.f = fmt_of(n, sig, !sub && !a.f.is_signed && !b.f.is_signed, v.lin, base, src_f, src_f);
    int eff_src = imax(a.eff, b.eff);
    v.q = unit_qerr(v.f, eff_src, n->r);
    v.err = base + v.q;
    v.eff = imin(v.f.fbits, eff_src);
    v.mag = fmt_maxabs(v.f);
    v.imag = a.imag + b.imag;
    v.s = !n->c ? NULL : sub ? sim_sub(n->c, n->sc, name, v.f, a.s, b.s)
                             : sim_add(n->c, n->sc, name, v.f, a.s, b.s);
    return v;
}

unet_val unet_add(unet *n, int sig, const char *name, unet_val a, unet_val b)
{
    return addsub(n, sig, name, a, b, 0);
}

unet_val unet_sub(unet *n, int sig, const char *name, unet_val a, unet_val b)
{
    return addsub(n, sig, name, a, b, 1);
}

/* ------------------------------------------------ multiplier datapaths */

/* An element that is no shift or sum: its format in a rule walk. The
 * range rule has no range for it (a product is no linear form): a unit
 * that walks one there has a bug. */
static sim_fmt fmt_nonlin(unet *n, int sig, const unet_val *copy_of)
{
    if (n->choose == 1) {
        fprintf(stderr, "shadesim: internal error: unit %s: a multiplier datapath in a range-rule walk\n", n->u->name);
        abort();
    }
    if (n->choose == UNET_FIXED && copy_of) {
        (void)fmt_of(n, sig, 0, NULL, 0, 0, 0);     /* checks sig */
        return n->fm.f[sig] = copy_of->f;
    }
    return fmt_of(n, sig, 0, NULL, 0, 0, 0);
}

/* v (error e, src fraction bits) into format f: a copy's value. */
static unet_val requant(unet_val v, sim_fmt f, sim_round r)
{
    unet_val o = v;
    o.s = NULL;
    o.f = f;
    o.q = unit_qerr(f, v.eff, r);
    o.err = v.err + o.q;
    o.eff = imin(f.fbits, v.eff);
    o.mag = fmin(fmt_maxabs(f), copy_mag(v, f, v.eff, r));
    return o;
}

/* a * b, built by make (NULL: a multiplier) from operands ma, mb. */
static unet_val mul_by(unet *n, int sig, const char *name, unet_val a, unet_val b,
                       unet_make2 make, sim_signal *ma, sim_signal *mb)
{
    unet_val v;
    memset(&v, 0, sizeof v);
    v.f = fmt_nonlin(n, sig, NULL);
    /* a_hw b_hw - a b = (a_hw - a) b + a_hw (b_hw - b), with |b| <=
     * imag_b and |a_hw| <= min(mag_a, imag_a + err_a); an exact b (err 0)
     * adds nothing, whatever a's magnitude */
    double base = a.err * b.imag + (b.err > 0 ? fmin(a.mag, a.imag + a.err) * b.err : 0);
    int src = a.eff + b.eff;
    v.q = unit_qerr(v.f, src, n->r);
    v.err = base + v.q;
    v.eff = imin(v.f.fbits, src);
    v.mag = fmt_maxabs(v.f);
    v.imag = a.imag * b.imag;
    v.s = n->c ? (make ? make : sim_mul)(n->c, n->sc, name, v.f, ma, mb) : NULL;
    return v;
}

unet_val unet_mul(unet *n, int sig, const char *name, unet_val a, unet_val b)
{
    return mul_by(n, sig, name, a, b, NULL, a.s, b.s);
}

unet_val unet_cmul(unet *n, int sig, const char *name, unet_val x, unet_val k, unet_make2 make)
{
    return mul_by(n, sig, name, k, x, make, x.s, k.s);
}

unet_val unet_mux(unet *n, int sig, const char *name, sim_signal *sel, int nv, const unet_val *v, int k)
{
    sim_fmt f = fmt_nonlin(n, sig, NULL);
    unet_val o = requant(v[k < 0 ? 0 : k >= nv ? nv - 1 : k], f, n->r);
    if (n->c) {
        sim_signal *in[8] = { NULL };
        for (int i = 0; i < nv && i < 8; i++) in[i] = v[i].s;
        o.s = sim_mux(n->c, n->sc, name, f, sel, nv, in);
    }
    return o;
}

unet_val unet_bk(unet *n, int sig, const char *name, sim_signal *pass, unet_val x, int on)
{
    sim_fmt f = fmt_nonlin(n, sig, NULL);
    unet_val o;
    if (on) {
        o = requant(x, f, n->r);
    } else {               /* forced zero: exact, no fraction bits */
        memset(&o, 0, sizeof o);
        o.f = f;
        o.eff = -64;
    }
    o.s = n->c ? sim_bk(n->c, n->sc, name, f, pass, x.s) : NULL;
    return o;
}

unet_val unet_reg(unet *n, int sig, const char *name)
{
    unet_val r;
    memset(&r, 0, sizeof r);
    r.f = fmt_nonlin(n, sig, NULL);
    r.mag = fmt_maxabs(r.f);
    r.s = n->c ? sim_reg(n->c, n->sc, name, r.f, n->clk, NULL, NULL, NULL, 0) : NULL;
    return r;
}

void unet_reg_set(unet *n, unet_val *r, unet_val d)
{
    if (n->c) { sim_reg_connect(r->s, d.s); return; }
    *r = requant(d, r->f, n->r);
}

unet_val unet_reg_of(unet *n, int sig, const char *name, unet_val d)
{
    unet_val o = requant(d, fmt_nonlin(n, sig, &d), n->r);
    o.s = n->c ? sim_reg(n->c, n->sc, name, o.f, n->clk, d.s, NULL, NULL, 0) : NULL;
    return o;
}
