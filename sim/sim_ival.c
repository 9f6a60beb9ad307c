/* sim_ival.c - interval evaluation of the primitives: each element's
 * exact result over its operands' intervals, rounded as the element
 * rounds (sim_elem_eval's operations, sim_op.h's, on the ends of
 * intervals: which ends, and the rounding of an interval, are this
 * file's own). */
#include "sim/sim_ival.h"
#include "sim/sim_op.h"
#include <math.h>

sim_wide sim_ival_round(sim_wide x, int src_f, int dst_f, sim_round r)
{
    int sh = src_f - dst_f;
    if (sh <= 0) return sh <= -126 ? x : x * ((sim_wide)1 << -sh);
    if (sh >= 127) return (r == SIM_RND_TRUNC && x < 0) ? -1 : 0;
    sim_wide q = x >> sh;       /* arithmetic on gcc/clang: floor */
    if (r != SIM_RND_TRUNC) {
        unsigned __int128 rem = (unsigned __int128)x & (((unsigned __int128)1 << sh) - 1);
        unsigned __int128 half = (unsigned __int128)1 << (sh - 1);
        if (rem > half || (rem == half && (r == SIM_RND_HALF_UP || (q & 1)))) q++;
    }
    return q;
}

sim_ival sim_ival_fit(sim_ival v, sim_fmt f, sim_ovf o)
{
    sim_wide lo = sim_fmt_raw_min(f), hi = sim_fmt_raw_max(f);
    if (v.lo >= lo && v.hi <= hi) return v;
    if (o == SIM_OVF_SAT) {
        sim_ival s = { v.lo < lo ? lo : v.lo > hi ? hi : v.lo, v.hi < lo ? lo : v.hi > hi ? hi : v.hi };
        return s;
    }
    /* Wrap: the ends wrapped, when the set lies within one period. */
    sim_wide period = hi - lo + 1;
    if (v.hi - v.lo < period) {
        sim_wide a = ((v.lo - lo) % period + period) % period + lo;
        sim_wide b = a + (v.hi - v.lo);
        if (b <= hi) return (sim_ival){ a, b };
    }
    return (sim_ival){ lo, hi };
}

int sim_ival_ibits(sim_ival v, sim_fmt f)
{
    if (!f.is_signed && v.lo < 0) return -1;
    for (int ib = f.is_signed ? 1 : 0; ib + f.fbits <= (f.is_signed ? 64 : 63); ib++) {
        if (ib + f.fbits < 1) continue;
        int w = ib + f.fbits;
        sim_wide lo = f.is_signed ? -((sim_wide)1 << (w - 1)) : 0;
        sim_wide hi = f.is_signed ? ((sim_wide)1 << (w - 1)) - 1 : ((sim_wide)1 << w) - 1;
        if (v.lo >= lo && v.hi <= hi) return ib;
    }
    return -1;
}

/* x (raw with fbits sf) quantized into y: pre and post. */
static void into(const sim_signal *y, sim_ival x, int sf, sim_round r, sim_ovf o, sim_ival *pre, sim_ival *post)
{
    pre->lo = sim_ival_round(x.lo, sf, y->fmt.fbits, r);
    pre->hi = sim_ival_round(x.hi, sf, y->fmt.fbits, r);
    *post = sim_ival_fit(*pre, y->fmt, o);
}

static int has_zero(sim_ival v) { return v.lo <= 0 && v.hi >= 0; }
static int has_nonzero(sim_ival v) { return v.lo != 0 || v.hi != 0; }

/* Accumulate a part of an element's outcome. */
static void take(int *any, sim_ival *pre, sim_ival *post, sim_ival p, sim_ival q)
{
    if (!*any) { *pre = p; *post = q; *any = 1; return; }
    *pre = sim_ival_hull(*pre, p);
    *post = sim_ival_hull(*post, q);
}

/* A logic element: its function over every combination of the inputs'
 * values when there are at most this many, else its whole format. An
 * input that is itself a one-input logic element of another input (the
 * reciprocal ROM's address zq = z's top bits beside z) is not a free
 * choice: its value is computed from that input's, as the circuit
 * settles, so only the free inputs are enumerated. */
#define LOGIC_ENUM_MAX (1 << 16)

static sim_ival logic_eval(const sim_signal *y, const sim_prim_info *pi, const sim_ival *vals)
{
    sim_ival full = { sim_fmt_raw_min(y->fmt), sim_fmt_raw_max(y->fmt) };
    int64_t lo[8], v[8];
    int from[8];                    /* -1: free; else the input it is computed from */
    sim_prim_info dep[8];
    double combos = 1;
    if (pi->n > 8) return full;
    for (int i = 0; i < pi->n; i++) {
        from[i] = -1;
        if (!sim_prim_describe(pi->in[i], &dep[i]) && sim_kind_eval(dep[i].kind) == SIM_KIND_LOGIC && dep[i].n == 1)
            for (int k = 0; k < pi->n; k++)
                if (k != i && pi->in[k] == dep[i].in[0]) from[i] = k;
    }
    for (int i = 0; i < pi->n; i++)         /* a chain (x of y of z) is enumerated at y */
        if (from[i] >= 0 && from[from[i]] >= 0) from[i] = -1;
    for (int i = 0; i < pi->n; i++) {
        sim_ival x = vals[pi->in[i]->index];
        if (from[i] < 0) combos *= (double)(x.hi - x.lo) + 1;
        lo[i] = v[i] = (int64_t)x.lo;
    }
    if (combos > LOGIC_ENUM_MAX) return full;
    sim_ival out = { 0, 0 };
    for (int first = 1;;) {
        for (int i = 0; i < pi->n; i++)
            if (from[i] >= 0) v[i] = sim__canon(dep[i].fn(&v[from[i]], dep[i].user), pi->in[i]->fmt);
        int64_t r = sim__canon(pi->fn(v, pi->user), y->fmt);
        if (first) { out.lo = out.hi = r; first = 0; }
        else out = sim_ival_hull(out, (sim_ival){ r, r });
        int i = 0;
        for (; i < pi->n; i++) {           /* odometer over the free inputs */
            if (from[i] >= 0) continue;
            if (v[i] < (int64_t)vals[pi->in[i]->index].hi) { v[i]++; break; }
            v[i] = lo[i];
        }
        if (i == pi->n) break;
    }
    return out;
}

/* An arithmetic element (add, subtract, multiply, shift, wire) of y over
 * operand intervals x (pi->a's) and z (pi->b's): 0, or -1 for another
 * kind. */
static int arith(const sim_signal *y, const sim_prim_info *pi, sim_ival x, sim_ival z, sim_round r, sim_ovf o,
                 sim_ival *pre, sim_ival *post)
{
    switch (sim_kind_eval(pi->kind)) {
    case SIM_KIND_WIRE:
        into(y, x, pi->a->fmt.fbits, r, o, pre, post);
        return 0;
    case SIM_KIND_ADD: case SIM_KIND_SUB: {
        sim_ival s;
        x = (sim_ival){ SIM_OP_ALIGN(sim_wide, x.lo, pi->sa), SIM_OP_ALIGN(sim_wide, x.hi, pi->sa) };
        z = (sim_ival){ SIM_OP_ALIGN(sim_wide, z.lo, pi->sb), SIM_OP_ALIGN(sim_wide, z.hi, pi->sb) };
        if (pi->kind == SIM_KIND_ADD) s = (sim_ival){ SIM_OP_ADD(sim_wide, x.lo, z.lo), SIM_OP_ADD(sim_wide, x.hi, z.hi) };
        else s = (sim_ival){ SIM_OP_SUB(sim_wide, x.lo, z.hi), SIM_OP_SUB(sim_wide, x.hi, z.lo) };
        into(y, s, pi->src_f, r, o, pre, post);
        return 0;
    }
    case SIM_KIND_MUL: {
        sim_wide c[4] = { SIM_OP_MUL(sim_wide, x.lo, z.lo), SIM_OP_MUL(sim_wide, x.lo, z.hi),
                          SIM_OP_MUL(sim_wide, x.hi, z.lo), SIM_OP_MUL(sim_wide, x.hi, z.hi) };
        sim_ival s = { c[0], c[0] };
        for (int i = 1; i < 4; i++) s = sim_ival_hull(s, (sim_ival){ c[i], c[i] });
        into(y, s, pi->src_f, r, o, pre, post);
        return 0;
    }
    case SIM_KIND_SHIFT:
        /* x * 2^sh is x's raw with fewer fraction bits, scaled up (sa)
         * past the binary point */
        into(y, (sim_ival){ SIM_OP_ALIGN(sim_wide, x.lo, pi->sa), SIM_OP_ALIGN(sim_wide, x.hi, pi->sa) }, pi->src_f, r,
             o, pre, post);
        return 0;
    default:
        return -1;
    }
}

/* A guarded block key: the pass signal is a one-input logic element of
 * some z (pass = g(z)), and the value x it passes is z itself or an
 * arithmetic element with z as an operand. x and the pass signal are
 * then computed from the same value of z in the same delta cycle (one
 * element each from z), so whenever the key passes, z is among the
 * values where g is nonzero, and x is x's element over those alone. The
 * clamp max(0, 1 - P) is such a key (pass = P <= 1, x = 1 - P): without
 * the guard its interval is 1 - P over all of P's, below 0. The values
 * where g passes are found by trying z's values from each end of its
 * interval, at most GUARD_SCAN each (the interval stays as it was past
 * that). */
#define GUARD_SCAN (1 << 20)

static int passes(const sim_prim_info *g, const sim_signal *gy, int64_t v)
{
    return sim__canon(g->fn(&v, g->user), gy->fmt) != 0;
}

static void guarded(const sim_prim_info *pi, const sim_ival *vals, sim_ival *x)
{
    sim_prim_info g, e;
    if (!pi->c || !pi->a || sim_prim_describe(pi->c, &g) || sim_kind_eval(g.kind) != SIM_KIND_LOGIC || g.n != 1) return;
    const sim_signal *z = g.in[0];
    sim_ival zv = vals[z->index];
    if (zv.lo < INT64_MIN || zv.hi > INT64_MAX) return;
    sim_wide lo = zv.lo, hi = zv.hi;
    for (sim_wide k = 0; lo <= zv.hi && !passes(&g, pi->c, (int64_t)lo); lo++)
        if (++k > GUARD_SCAN) return;
    if (lo > zv.hi) return;                     /* never passes: the key's 0 alone (left to the caller) */
    for (sim_wide k = 0; hi > lo && !passes(&g, pi->c, (int64_t)hi); hi--)
        if (++k > GUARD_SCAN) return;
    sim_ival zp = { lo, hi }, pre, post;
    if (pi->a == z) { *x = zp; return; }
    if (sim_prim_describe(pi->a, &e) || (e.a != z && e.b != z)) return;
    sim_ival ea = e.a ? vals[e.a->index] : (sim_ival){ 0, 0 }, eb = e.b ? vals[e.b->index] : (sim_ival){ 0, 0 };
    if (e.a == z) ea = zp;
    if (e.b == z) eb = zp;
    if (arith(pi->a, &e, ea, eb, sim_fmt_round(pi->a->fmt, e.r), sim_fmt_ovf(pi->a->fmt, e.o), &pre, &post)) return;
    /* both sound: their intersection */
    if (post.lo > x->lo) x->lo = post.lo;
    if (post.hi < x->hi) x->hi = post.hi;
    if (x->lo > x->hi) x->hi = x->lo;           /* cannot happen; stay an interval */
}

/* The interpolation y = a + m, m = t dd, dd = b - a (a linear filter's
 * step: a bilinear lookup's top, bot and val): with t in [0, 1], y is
 * (1 - t) a + t b within hull(a, b), which the intervals of a and of
 * t (b - a) taken apart lose (a in [0, 1], b - a in [-1, 1]: y in
 * [-1, 2]). The roundings are exact terms: dd = b - a + e1 and m =
 * t dd + e2 with e1, e2 in their elements' rounding ranges, so y's exact
 * sum is (1 - t) a + t b + t e1 + e2, t e1 between 0 and e1; it is a
 * multiple of y's source LSB, so its ends go inward to one, then y's
 * rounding (monotone) takes the ends. Only when each step keeps its
 * value: alignments that shift no value, and dd and m within their
 * formats (an overflow breaks the identity). Values on a common grid of
 * 2^-G, G at most INTERP_G. */
#define INTERP_G 60

/* An element's rounding error from src_f to dst_f fraction bits, in
 * units of 2^-g: [-(2^sh - 1), 0] for trunc, within +-2^(sh-1) else. */
static void round_err(int src_f, int dst_f, sim_round r, int g, sim_wide *lo, sim_wide *hi)
{
    int sh = src_f - dst_f;
    *lo = *hi = 0;
    if (sh <= 0) return;
    sim_wide u = (sim_wide)1 << (g - src_f);
    if (r == SIM_RND_TRUNC) *lo = -(((sim_wide)1 << sh) - 1) * u;
    else { *lo = -((sim_wide)1 << (sh - 1)) * u; *hi = -*lo; }
}

/* Element e (of y) keeps its operands' values when aligned: a shift by
 * sa (sb) to src_f fraction bits scales none. */
static int aligned(const sim_prim_info *e)
{
    return e->a->fmt.fbits + e->sa == e->src_f && (!e->b || e->b->fmt.fbits + e->sb == e->src_f);
}

/* The element of y, its operands' intervals from vals: pre within y's format. */
static int no_overflow(const sim_signal *y, const sim_ival *vals)
{
    sim_ival pre, post;
    if (sim_ival_eval(y, vals, &pre, &post)) return 0;
    return sim_ival_within(pre, (sim_ival){ sim_fmt_raw_min(y->fmt), sim_fmt_raw_max(y->fmt) });
}

static sim_wide div_floor(sim_wide x, sim_wide d) { sim_wide q = x / d; return q * d > x ? q - 1 : q; }
static sim_wide div_ceil(sim_wide x, sim_wide d) { return -div_floor(-x, d); }

static void interpolated(const sim_signal *y, const sim_prim_info *pi, const sim_ival *vals, sim_round r,
                         sim_ival *pre)
{
    if (sim_kind_eval(pi->kind) != SIM_KIND_ADD || !pi->b || !aligned(pi)) return;
    for (int k = 0; k < 2; k++) {
        const sim_signal *a = k ? pi->b : pi->a, *m = k ? pi->a : pi->b;
        sim_prim_info pm, pd;
        if (sim_prim_describe(m, &pm) || sim_kind_eval(pm.kind) != SIM_KIND_MUL
            || pm.a->fmt.fbits + pm.b->fmt.fbits != pm.src_f)
            continue;
        for (int j = 0; j < 2; j++) {
            const sim_signal *t = j ? pm.b : pm.a, *dd = j ? pm.a : pm.b;
            if (sim_prim_describe(dd, &pd) || sim_kind_eval(pd.kind) != SIM_KIND_SUB || pd.b != a || !aligned(&pd))
                continue;
            const sim_signal *b = pd.a;
            sim_ival tv = vals[t->index], av = vals[a->index], bv = vals[b->index];
            int g = pi->src_f;
            if (pm.src_f > g) g = pm.src_f;
            if (pd.src_f > g) g = pd.src_f;
            /* t in [0, 1] as it is held (its rounding is in its value) */
            if (tv.lo < 0 || t->fmt.fbits > 120 || tv.hi > ((sim_wide)1 << t->fmt.fbits) || g > INTERP_G
                || a->fmt.fbits > g || b->fmt.fbits > g || !no_overflow(dd, vals) || !no_overflow(m, vals))
                continue;
            sim_wide ua = (sim_wide)1 << (g - a->fmt.fbits), ub = (sim_wide)1 << (g - b->fmt.fbits);
            sim_wide lo = av.lo * ua < bv.lo * ub ? av.lo * ua : bv.lo * ub;
            sim_wide hi = av.hi * ua > bv.hi * ub ? av.hi * ua : bv.hi * ub;
            sim_wide e1lo, e1hi, e2lo, e2hi;
            round_err(pd.src_f, dd->fmt.fbits, sim_fmt_round(dd->fmt, pd.r), g, &e1lo, &e1hi);
            round_err(pm.src_f, m->fmt.fbits, sim_fmt_round(m->fmt, pm.r), g, &e2lo, &e2hi);
            lo += (e1lo < 0 ? e1lo : 0) + e2lo;
            hi += (e1hi > 0 ? e1hi : 0) + e2hi;
            sim_wide u = (sim_wide)1 << (g - pi->src_f);
            sim_wide qlo = sim_ival_round(div_ceil(lo, u), pi->src_f, y->fmt.fbits, r);
            sim_wide qhi = sim_ival_round(div_floor(hi, u), pi->src_f, y->fmt.fbits, r);
            /* both sound: their intersection */
            if (qlo > pre->lo) pre->lo = qlo;
            if (qhi < pre->hi) pre->hi = qhi;
            if (pre->lo > pre->hi) pre->hi = pre->lo;   /* cannot happen; stay an interval */
            return;
        }
    }
}

/* A logic element stated linear (sim_logic_linear): y = k x + e, e in
 * [lo, hi], x's interval v (fx fraction bits); y's values are raws of
 * its format, so the ends go inward to one (after a relative 2^-50
 * outward, far above the doubles' rounding). */
static void linear_narrow(const sim_signal *y, const sim_logic_lin *l, sim_ival v, int fx, sim_ival *pre)
{
    double a = l->k * ldexp((double)v.lo, -fx), b = l->k * ldexp((double)v.hi, -fx);
    double lo = fmin(a, b) + l->lo, hi = fmax(a, b) + l->hi, m = fmax(fabs(lo), fabs(hi)) * 0x1p-50;
    lo = ceil(ldexp(lo - m, y->fmt.fbits));
    hi = floor(ldexp(hi + m, y->fmt.fbits));
    if (!(fabs(lo) < 0x1p62) || !(fabs(hi) < 0x1p62) || lo > hi) return;
    if ((sim_wide)lo > pre->lo) pre->lo = (sim_wide)lo;
    if ((sim_wide)hi < pre->hi) pre->hi = (sim_wide)hi;
    if (pre->lo > pre->hi) pre->hi = pre->lo;       /* cannot happen; stay an interval */
}

/* g's value (a one-input logic element's, as its signal holds it) at z. */
static int64_t g_at(const sim_prim_info *g, const sim_signal *gy, int64_t z)
{
    return sim__canon(g->fn(&z, g->user), gy->fmt);
}

int sim_ival_where(const sim_signal *g, const sim_ival *vals, int64_t s, sim_ival *zs)
{
    sim_prim_info pg;
    if (sim_prim_describe(g, &pg) || sim_kind_eval(pg.kind) != SIM_KIND_LOGIC || pg.n != 1 || !pg.monotone) return -1;
    sim_ival zv = vals[pg.in[0]->index];
    if (zv.lo < INT64_MIN || zv.hi > INT64_MAX) return -1;
    /* the first z where g reaches s, then the last where it has not passed s */
    int64_t a = (int64_t)zv.lo, b = (int64_t)zv.hi;
    if (g_at(&pg, g, b) < s || g_at(&pg, g, a) > s) return 0;
    int64_t lo = a, hi = b;
    while (lo < hi) { int64_t m = (int64_t)(((sim_wide)lo + hi) >> 1); if (g_at(&pg, g, m) >= s) hi = m; else lo = m + 1; }
    if (g_at(&pg, g, lo) != s) return 0;
    int64_t first = lo;
    hi = b;
    while (lo < hi) { int64_t m = (int64_t)(((sim_wide)lo + hi + 1) >> 1); if (g_at(&pg, g, m) <= s) lo = m; else hi = m - 1; }
    *zs = (sim_ival){ first, lo };
    return 1;
}

/* A multiplexer whose select is a one-input logic element g(z) (a sign
 * test of a trial difference): input s is passed only when z is among
 * the values where g is s (zs), so s's interval is narrowed by it when
 * s's input is z itself, or an operand p of z = p - q or z = p + q that
 * z keeps exactly (no rounding, no overflow): p = z + q, or z - q. x:
 * the input's interval, narrowed in place. */
static void branch_narrow(const sim_signal *x, const sim_signal *z, sim_ival zs, const sim_ival *vals, sim_ival *x_iv)
{
    sim_ival n = { 0, 0 };
    sim_prim_info e;
    if (x == z) n = zs;
    else {
        if (sim_prim_describe(z, &e) || (sim_kind_eval(e.kind) != SIM_KIND_SUB && sim_kind_eval(e.kind) != SIM_KIND_ADD)
            || e.a != x || x->fmt.fbits != z->fmt.fbits || e.src_f != z->fmt.fbits || !aligned(&e) || !no_overflow(z, vals))
            return;
        sim_ival q = vals[e.b->index];
        int sh = z->fmt.fbits - e.b->fmt.fbits;     /* q's raws on z's grid: aligned, sh >= 0 */
        if (sh < 0 || sh > 60) return;
        q.lo *= (sim_wide)1 << sh;
        q.hi *= (sim_wide)1 << sh;
        n = sim_kind_eval(e.kind) == SIM_KIND_SUB ? (sim_ival){ zs.lo + q.lo, zs.hi + q.hi }
                                                   : (sim_ival){ zs.lo - q.hi, zs.hi - q.lo };
    }
    if (n.lo > x_iv->lo) x_iv->lo = n.lo;
    if (n.hi < x_iv->hi) x_iv->hi = n.hi;
    if (x_iv->lo > x_iv->hi) x_iv->hi = x_iv->lo;   /* cannot happen; stay an interval */
}

int sim_ival_eval(const sim_signal *y, const sim_ival *vals, sim_ival *pre, sim_ival *post)
{
    sim_prim_info pi;
    if (sim_prim_describe(y, &pi)) return -1;
    sim_round r = sim_fmt_round(y->fmt, pi.r);
    sim_ovf o = sim_fmt_ovf(y->fmt, pi.o);
    int any = 0;
    sim_ival p, q;
    switch (sim_kind_eval(pi.kind)) {   /* an input a sim_assign drives: a copy (sim_elem.h) */
    case SIM_KIND_CONST:
        pre->lo = pre->hi = y->cur;
        *post = *pre;
        return 0;
    case SIM_KIND_WIRE:
        if (!pi.a) return -1;
        return arith(y, &pi, vals[pi.a->index], (sim_ival){ 0, 0 }, r, o, pre, post);
    case SIM_KIND_REG: {
        sim_ival cur = vals[y->index];
        sim_ival rst = pi.rst ? vals[pi.rst->index] : (sim_ival){ 0, 0 };
        sim_ival en = pi.c ? vals[pi.c->index] : (sim_ival){ 1, 1 };
        if (has_nonzero(rst)) take(&any, pre, post, (sim_ival){ pi.rst_raw, pi.rst_raw }, (sim_ival){ pi.rst_raw, pi.rst_raw });
        if (has_zero(rst)) {
            if (has_zero(en) || !pi.a) take(&any, pre, post, cur, cur);
            if (has_nonzero(en) && pi.a) {
                into(y, vals[pi.a->index], pi.a->fmt.fbits, r, o, &p, &q);
                take(&any, pre, post, p, q);
            }
        }
        return 0;
    }
    case SIM_KIND_MUX: {
        sim_ival sel = vals[pi.c->index];
        /* a select out of range gives 0 */
        if (!SIM_OP_SEL_IN(sel.lo, pi.n) || !SIM_OP_SEL_IN(sel.hi, pi.n))
            take(&any, pre, post, (sim_ival){ 0, 0 }, (sim_ival){ 0, 0 });
        sim_wide a = sel.lo < 0 ? 0 : sel.lo, b = sel.hi >= pi.n ? pi.n - 1 : sel.hi;
        for (sim_wide s = a; s <= b; s++) {
            const sim_signal *x = pi.in[(int)s];
            sim_ival xv = vals[x->index], zs;
            if (a < b) {                /* a data select: where its guard gives s */
                int w = sim_ival_where(pi.c, vals, (int64_t)s, &zs);
                if (w == 0) continue;   /* never selected */
                sim_prim_info g;
                if (w > 0 && !sim_prim_describe(pi.c, &g)) branch_narrow(x, g.in[0], zs, vals, &xv);
            }
            into(y, xv, x->fmt.fbits, r, o, &p, &q);
            take(&any, pre, post, p, q);
        }
        if (!any) *pre = *post = (sim_ival){ 0, 0 };    /* no input can be selected: cannot happen */
        return 0;
    }
    case SIM_KIND_BK: {
        sim_ival pass = vals[pi.c->index];
        if (has_zero(pass)) take(&any, pre, post, (sim_ival){ 0, 0 }, (sim_ival){ 0, 0 });
        if (has_nonzero(pass)) {
            sim_ival x = vals[pi.a->index];
            if (has_zero(pass)) guarded(&pi, vals, &x);
            into(y, x, pi.a->fmt.fbits, r, o, &p, &q);
            take(&any, pre, post, p, q);
        }
        return 0;
    }
    case SIM_KIND_ADD: case SIM_KIND_SUB: case SIM_KIND_MUL: case SIM_KIND_SHIFT: {
        sim_ival none = { 0, 0 };
        if (arith(y, &pi, vals[pi.a->index], pi.b ? vals[pi.b->index] : none, r, o, pre, post)) return -1;
        interpolated(y, &pi, vals, r, pre);
        *post = sim_ival_fit(*pre, y->fmt, o);
        return 0;
    }
    case SIM_KIND_LOGIC:
        *pre = *post = logic_eval(y, &pi, vals);
        if (pi.lin) linear_narrow(y, pi.lin, vals[pi.in[pi.lin->i]->index], pi.in[pi.lin->i]->fmt.fbits, pre);
        *post = *pre;
        return 0;
    default:
        return -1;
    }
}
