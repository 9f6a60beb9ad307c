/* sim_aff.c - affine evaluation of the primitives (sim_aff.h): the
 * element's exact operation on forms, then its rounding as a remainder,
 * its overflow as the interval engine's answer. */
#include "sim/sim_aff.h"
#include <math.h>
#include <string.h>

/* Outward by a relative 2^-48 of every magnitude in the form: each double
 * operation errs by at most 2^-53 of its result. */
static void widen(sim_aff *a)
{
    double m = fabs(a->c0) + fmax(fabs(a->rlo), fabs(a->rhi));
    for (int i = 0; i < a->n; i++) m += fabs(a->co[i]);
    double e = m * 0x1p-48 + 0x1p-1000;
    a->rlo -= e;
    a->rhi += e;
}

static sim_aff aff_const(double v)
{
    sim_aff a;
    a.c0 = v;
    a.rlo = a.rhi = 0;
    a.n = 0;
    return a;
}

sim_aff sim_aff_symbol(double lo, double hi, uint32_t *next)
{
    sim_aff a = aff_const((lo + hi) / 2);
    double r = (hi - lo) / 2;
    if (r > 0) { a.n = 1; a.sym[0] = (*next)++; a.co[0] = r; }
    widen(&a);
    return a;
}

static double raw_real(sim_wide raw, int fbits) { return ldexp((double)raw, -fbits); }

sim_aff sim_aff_of_ival(sim_ival v, sim_fmt f, uint32_t *next)
{
    if (v.lo == v.hi) return aff_const(raw_real(v.lo, f.fbits));
    return sim_aff_symbol(raw_real(v.lo, f.fbits), raw_real(v.hi, f.fbits), next);
}

void sim_aff_hull(const sim_aff *a, double *lo, double *hi)
{
    double s = 0;
    for (int i = 0; i < a->n; i++) s += fabs(a->co[i]);
    *lo = a->c0 - s + a->rlo;
    *hi = a->c0 + s + a->rhi;
}

/* k times the interval [lo, hi]. */
static void scale_iv(double k, double lo, double hi, double *olo, double *ohi)
{
    double p = k * lo, q = k * hi;
    *olo = fmin(p, q);
    *ohi = fmax(p, q);
}

/* Terms beyond SIM_AFF_TERMS: the smallest into the remainder. */
static void push_term(sim_aff *r, uint32_t sym, double co)
{
    if (co == 0) return;
    if (r->n < SIM_AFF_TERMS) { r->sym[r->n] = sym; r->co[r->n++] = co; return; }
    int m = 0;
    for (int i = 1; i < r->n; i++) if (fabs(r->co[i]) < fabs(r->co[m])) m = i;
    double small = fabs(co) < fabs(r->co[m]) ? fabs(co) : fabs(r->co[m]);
    if (fabs(co) > fabs(r->co[m])) {           /* the new term stays, in order */
        memmove(r->sym + m, r->sym + m + 1, (size_t)(r->n - m - 1) * sizeof *r->sym);
        memmove(r->co + m, r->co + m + 1, (size_t)(r->n - m - 1) * sizeof *r->co);
        r->sym[r->n - 1] = sym;
        r->co[r->n - 1] = co;
    }
    r->rlo -= small;
    r->rhi += small;
}

/* ka a + kb b: the terms merged by symbol (both lists ascending, and the
 * result too: push_term only appends larger symbols, or keeps order when
 * it drops one). */
static sim_aff lin(double ka, const sim_aff *a, double kb, const sim_aff *b)
{
    sim_aff r = aff_const(ka * a->c0 + kb * b->c0);
    double l1, h1, l2, h2;
    scale_iv(ka, a->rlo, a->rhi, &l1, &h1);
    scale_iv(kb, b->rlo, b->rhi, &l2, &h2);
    r.rlo = l1 + l2;
    r.rhi = h1 + h2;
    int i = 0, j = 0;
    while (i < a->n || j < b->n) {
        if (j >= b->n || (i < a->n && a->sym[i] < b->sym[j])) { push_term(&r, a->sym[i], ka * a->co[i]); i++; }
        else if (i >= a->n || b->sym[j] < a->sym[i]) { push_term(&r, b->sym[j], kb * b->co[j]); j++; }
        else { push_term(&r, a->sym[i], ka * a->co[i] + kb * b->co[j]); i++; j++; }
    }
    widen(&r);
    return r;
}

sim_aff sim_aff_lin(double ka, const sim_aff *a, double kb, const sim_aff *b) { return lin(ka, a, kb, b); }

static sim_aff scaled(double k, const sim_aff *a)
{
    sim_aff z = aff_const(0);
    return lin(k, a, 0, &z);
}

/* a b: the centres' product and the linear terms exactly; the rest, the
 * product of the two deviations, bounded by the product of their radii. */
static sim_aff mul(const sim_aff *a, const sim_aff *b)
{
    sim_aff da = *a, db = *b;
    da.c0 = db.c0 = 0;
    sim_aff r = lin(b->c0, &da, a->c0, &db);
    r.c0 += a->c0 * b->c0;
    /* lin scaled the remainders by the other centre; the deviations'
     * product is within +-(radius a)(radius b) */
    double ra = fmax(fabs(a->rlo), fabs(a->rhi)), rb = fmax(fabs(b->rlo), fabs(b->rhi));
    for (int i = 0; i < a->n; i++) ra += fabs(a->co[i]);
    for (int i = 0; i < b->n; i++) rb += fabs(b->co[i]);
    r.rlo -= ra * rb;
    r.rhi += ra * rb;
    widen(&r);
    return r;
}

/* v, exact with src_f fraction bits, rounded to y's format with mode r:
 * the rounding's error range added to the remainder. */
static sim_aff rounded(sim_aff v, int src_f, const sim_signal *y, sim_round r)
{
    if (src_f <= y->fmt.fbits) return v;
    double lsb = ldexp(1, -y->fmt.fbits);
    if (r == SIM_RND_TRUNC) v.rlo -= lsb;
    else { v.rlo -= lsb / 2; v.rhi += lsb / 2; }
    widen(&v);
    return v;
}

/* The raws of y's format the form can take: rounded values are whole
 * raws, so the hull's ends go inward to the nearest raw. 0, or -1 when
 * the form is beyond what a double resolves of a raw (2^62). */
static int raw_hull(const sim_aff *a, int fbits, sim_ival *out)
{
    double lo, hi;
    sim_aff_hull(a, &lo, &hi);
    lo = ceil(ldexp(lo, fbits));
    hi = floor(ldexp(hi, fbits));
    if (!(fabs(lo) < 0x1p62) || !(fabs(hi) < 0x1p62) || lo > hi) return -1;
    out->lo = (sim_wide)lo;
    out->hi = (sim_wide)hi;
    return 0;
}

static double pow2(int e) { return ldexp(1, e); }

/* The reals x can be, where x's form is X, when z (form Z) is within
 * [zlo, zhi]: X's hull, and z plus the hull of X - Z (X = Z + (X - Z)). */
static void bound_given(const sim_aff *X, const sim_aff *Z, double zlo, double zhi, double *lo, double *hi)
{
    sim_aff d = lin(1, X, -1, Z);
    double dl, dh;
    sim_aff_hull(X, lo, hi);
    sim_aff_hull(&d, &dl, &dh);
    if (zlo + dl > *lo) *lo = zlo + dl;
    if (zhi + dh < *hi) *hi = zhi + dh;
}

/* A multiplexer whose select depends on the data and is a one-input
 * logic element g(z) (a sign test of z = p - q): each input s is taken
 * only where g(z) is s (sim_ival_where), so the value it passes, and its
 * difference from q, are bounded given z there (bound_given). ipre is
 * narrowed to the hull over the inputs that can be selected. When every
 * such input lies on one side of q (the restoring divider's remainder
 * below its divisor: r - d in [-d, -lsb]), the output's form is q's plus
 * that difference as a symbol of its own, which keeps the relation into
 * the next clock, where the interval alone would lose it. 0, or -1 when
 * the select is no such element (the caller then takes the interval). */
static int guarded_mux(const sim_signal *y, const sim_prim_info *pi, const sim_aff *forms, const sim_ival *vals,
                       sim_round r, sim_ovf o, sim_ival *ipre, sim_ival *ipost, sim_aff *pre, sim_aff *post,
                       uint32_t *next)
{
    sim_prim_info g, ze;
    sim_ival sel = vals[pi->c->index];
    if (sel.lo < 0 || sel.hi >= pi->n || sim_prim_describe(pi->c, &g) || sim_kind_eval(g.kind) != SIM_KIND_LOGIC
        || g.n != 1)
        return -1;
    const sim_signal *z = g.in[0], *q = NULL;
    if (!sim_prim_describe(z, &ze) && sim_kind_eval(ze.kind) == SIM_KIND_SUB && ze.b
        && ze.a->fmt.fbits + ze.sa == ze.src_f && ze.b->fmt.fbits + ze.sb == ze.src_f)
        q = ze.b;
    const sim_aff *Z = &forms[z->index];
    double lo = INFINITY, hi = -INFINITY, dlo = INFINITY, dhi = -INFINITY;
    for (sim_wide s = sel.lo; s <= sel.hi; s++) {
        sim_ival zs = vals[z->index];
        if (sim_ival_where(pi->c, vals, (int64_t)s, &zs) == 0) continue;
        double zlo = raw_real(zs.lo, z->fmt.fbits), zhi = raw_real(zs.hi, z->fmt.fbits), l, h;
        const sim_signal *x = pi->in[(int)s];
        sim_aff X = rounded(forms[x->index], x->fmt.fbits, y, r);
        bound_given(&X, Z, zlo, zhi, &l, &h);
        lo = fmin(lo, l);
        hi = fmax(hi, h);
        if (q) {
            sim_aff T = lin(1, &X, -1, &forms[q->index]);
            bound_given(&T, Z, zlo, zhi, &l, &h);
            dlo = fmin(dlo, l);
            dhi = fmax(dhi, h);
        }
    }
    if (lo > hi) return -1;                         /* no input can be selected: cannot happen */
    /* y's values are raws of its format: the ends inward to one */
    sim_aff hullf = aff_const((lo + hi) / 2);
    hullf.rlo = -(hi - lo) / 2;
    hullf.rhi = (hi - lo) / 2;
    sim_ival ap;
    if (!raw_hull(&hullf, y->fmt.fbits, &ap)) {
        if (ap.lo > ipre->lo) ipre->lo = ap.lo;
        if (ap.hi < ipre->hi) ipre->hi = ap.hi;
        if (ipre->lo > ipre->hi) ipre->hi = ipre->lo;   /* cannot happen; stay an interval */
    }
    *ipost = sim_ival_fit(*ipre, y->fmt, o);
    int fits = sim_ival_within(*ipre, (sim_ival){ sim_fmt_raw_min(y->fmt), sim_fmt_raw_max(y->fmt) });
    if (q && fits) {
        /* y - q is a multiple of the finer of their LSBs: inward to one;
         * and within y's interval less q's */
        double ql, qh, yl = raw_real(ipre->lo, y->fmt.fbits), yh = raw_real(ipre->hi, y->fmt.fbits);
        sim_aff_hull(&forms[q->index], &ql, &qh);
        dlo = fmax(dlo, yl - qh);
        dhi = fmin(dhi, yh - ql);
        int gb = y->fmt.fbits > q->fmt.fbits ? y->fmt.fbits : q->fmt.fbits;
        dlo = ldexp(ceil(ldexp(dlo, gb) - 0x1p-20), -gb);
        dhi = ldexp(floor(ldexp(dhi, gb) + 0x1p-20), -gb);
        if (dlo <= dhi && (dhi < 0 || dlo > 0)) {
            sim_aff e = sim_aff_symbol(dlo, dhi, next);
            *pre = *post = lin(1, &forms[q->index], 1, &e);
            return 0;
        }
    }
    *pre = sim_aff_of_ival(*ipre, y->fmt, next);
    *post = ipost->lo == ipre->lo && ipost->hi == ipre->hi ? *pre : sim_aff_of_ival(*ipost, y->fmt, next);
    return 0;
}

int sim_aff_eval(const sim_signal *y, const sim_aff *forms, const sim_ival *vals, sim_ival *ipre, sim_ival *ipost,
                 sim_aff *pre, sim_aff *post, uint32_t *next)
{
    sim_prim_info pi;
    if (sim_prim_describe(y, &pi)) return -1;
    sim_round r = sim_fmt_round(y->fmt, pi.r);
    sim_ovf o = sim_fmt_ovf(y->fmt, pi.o);
    sim_aff v;
    int src_f = y->fmt.fbits, known = 1;
    switch (sim_kind_eval(pi.kind)) {
    case SIM_KIND_CONST:
        *pre = *post = aff_const(raw_real(y->cur, y->fmt.fbits));
        return 0;
    case SIM_KIND_WIRE:
        if (!pi.a) return -1;
        v = forms[pi.a->index];
        src_f = pi.a->fmt.fbits;
        break;
    case SIM_KIND_REG: {
        sim_ival rst = pi.rst ? vals[pi.rst->index] : (sim_ival){ 0, 0 };
        sim_ival en = pi.c ? vals[pi.c->index] : (sim_ival){ 1, 1 };
        if (rst.lo != rst.hi || en.lo != en.hi) known = 0;
        else if (rst.lo) v = aff_const(raw_real(pi.rst_raw, y->fmt.fbits));
        else if (!en.lo || !pi.a) v = forms[y->index];
        else { v = forms[pi.a->index]; src_f = pi.a->fmt.fbits; }
        break;
    }
    case SIM_KIND_MUX: {
        sim_ival sel = vals[pi.c->index];
        if (sel.lo != sel.hi && !guarded_mux(y, &pi, forms, vals, r, o, ipre, ipost, pre, post, next)) return 0;
        if (sel.lo != sel.hi) known = 0;
        else if (sel.lo < 0 || sel.lo >= pi.n) v = aff_const(0);    /* a select out of range gives 0 */
        else { const sim_signal *x = pi.in[(int)sel.lo]; v = forms[x->index]; src_f = x->fmt.fbits; }
        break;
    }
    case SIM_KIND_BK: {
        sim_ival pass = vals[pi.c->index];
        if (pass.lo != pass.hi) known = 0;
        else if (!pass.lo) v = aff_const(0);
        else { v = forms[pi.a->index]; src_f = pi.a->fmt.fbits; }
        break;
    }
    case SIM_KIND_ADD: case SIM_KIND_SUB: {
        double ka = pow2(pi.a->fmt.fbits + pi.sa - pi.src_f), kb = pow2(pi.b->fmt.fbits + pi.sb - pi.src_f);
        /* (the factors are 1 when the alignment keeps each value: raws
         * shifted to src_f fraction bits) */
        v = lin(ka, &forms[pi.a->index], pi.kind == SIM_KIND_ADD ? kb : -kb, &forms[pi.b->index]);
        src_f = pi.src_f;
        break;
    }
    case SIM_KIND_MUL: {
        sim_aff p = mul(&forms[pi.a->index], &forms[pi.b->index]);
        v = scaled(pow2(pi.a->fmt.fbits + pi.b->fmt.fbits - pi.src_f), &p);
        src_f = pi.src_f;
        break;
    }
    case SIM_KIND_SHIFT:
        v = scaled(pow2(pi.a->fmt.fbits + pi.sa - pi.src_f), &forms[pi.a->index]);
        src_f = pi.src_f;
        break;
    case SIM_KIND_LOGIC:
        if (pi.lin) {
            /* stated linear: k x + e, e in [lo, hi] (its rounding
             * included) a symbol of its own, so that the forms computed
             * from y share it (y - d and a trial difference y - d alike) */
            sim_aff e = sim_aff_symbol(pi.lin->lo, pi.lin->hi, next);
            v = lin(pi.lin->k, &forms[pi.in[pi.lin->i]->index], 1, &e);
        } else known = 0;
        break;
    default:
        return -1;
    }
    sim_ival ap;
    if (known) {
        *pre = rounded(v, src_f, y, r);
        if (!raw_hull(pre, y->fmt.fbits, &ap)) {
            /* both sound: their intersection */
            if (ap.lo > ipre->lo) ipre->lo = ap.lo;
            if (ap.hi < ipre->hi) ipre->hi = ap.hi;
            if (ipre->lo > ipre->hi) ipre->hi = ipre->lo;     /* cannot happen; stay an interval */
            *ipost = sim_ival_fit(*ipre, y->fmt, o);
        }
        if (sim_ival_within(*ipre, (sim_ival){ sim_fmt_raw_min(y->fmt), sim_fmt_raw_max(y->fmt) })) {
            *post = *pre;
            return 0;
        }
    } else {
        *pre = sim_aff_of_ival(*ipre, y->fmt, next);
    }
    /* what the forms do not follow: the interval, as a symbol of its own */
    if (ipost->lo == ipre->lo && ipost->hi == ipre->hi && !known) *post = *pre;
    else *post = sim_aff_of_ival(*ipost, y->fmt, next);
    return 0;
}
