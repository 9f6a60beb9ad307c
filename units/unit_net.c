/* unit_net.c - shift-and-add networks walked to build, bound or choose
 * formats (unit_net.h). */
#include "units/unit_net.h"
#include <math.h>
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
        if (!n->why[0]) snprintf(n->why, sizeof n->why, "unit %s: element without a signal", n->u->name);
        return unit_fmt(1, 8, 8);
    }
    if (!n->choose) return n->fm.f[sig];
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
    v.err = base + unit_qerr(v.f, eff_src, n->r);
    v.eff = imin(v.f.fbits, eff_src);
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
    v.err = base + unit_qerr(v.f, eff_src, n->r);
    v.eff = imin(v.f.fbits, eff_src);
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
