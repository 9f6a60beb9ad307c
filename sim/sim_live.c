/* sim_live.c - the bits of a signal that can vary (sim_live.h), from the
 * elements that drive it: constant shifts, adders, multiplexers and
 * registers pass their inputs' spans on; any other element varies over
 * its whole format. The walk back is bounded (a loop through a register,
 * or a deep network, ends at the whole format: never narrower than true). */
#include "sim/sim_live.h"
#include "sim/sim_prim.h"

#define LIVE_DEPTH 10

static int imin(int a, int b) { return a < b ? a : b; }
static int imax(int a, int b) { return a > b ? a : b; }

/* The bit length of v (0 for 0). */
static int bitlen(uint64_t v)
{
    int n = 0;
    for (; v; v >>= 1) n++;
    return n;
}

static void span(const sim_signal *s, int depth, int *lo, int *hi)
{
    const sim_fmt f = s->fmt;
    int flo = -f.fbits, fhi = f.ibits - 1;
    *lo = flo; *hi = fhi;
    sim_prim_info in;
    if (depth >= LIVE_DEPTH || sim_prim_describe(s, &in)) return;
    int l = 0, h = 0, l2 = 0, h2 = 0;
    switch (in.kind) {
    case SIM_KIND_CONST: {
        /* a constant varies nowhere: its bits from the lowest one to the
         * highest that differs from the sign, as the span a sum inherits */
        uint64_t v = (uint64_t)s->cur, m = f.width >= 64 ? UINT64_MAX : (((uint64_t)1 << f.width) - 1);
        v &= m;
        if (!v) { *hi = flo; return; }
        int tz = 0;
        while (!((v >> tz) & 1)) tz++;
        uint64_t mag = s->cur < 0 ? ~(uint64_t)s->cur & m : v;
        l = flo + tz;
        h = flo + bitlen(mag);
        break;
    }
    case SIM_KIND_SHIFT:
        span(in.a, depth + 1, &l, &h);
        l += in.shift; h += in.shift;
        break;
    case SIM_KIND_REG:
    case SIM_KIND_WIRE:
        if (!in.a) return;
        span(in.a, depth + 1, &l, &h);
        break;
    case SIM_KIND_ADD:
    case SIM_KIND_SUB:
        span(in.a, depth + 1, &l, &h);
        span(in.b, depth + 1, &l2, &h2);
        l = imin(l, l2);
        h = imax(h, h2) + 1;
        break;
    case SIM_KIND_MUX:
        if (in.n < 1) return;
        span(in.in[0], depth + 1, &l, &h);
        for (int k = 1; k < in.n; k++) {
            span(in.in[k], depth + 1, &l2, &h2);
            l = imin(l, l2); h = imax(h, h2);
        }
        break;
    default:
        return;
    }
    /* within the format: lower bits truncated, higher ones wrapped */
    *lo = imin(imax(l, flo), fhi);
    *hi = imax(imin(h, fhi), *lo);
}

void sim_live_span(const sim_signal *s, int *lo, int *hi) { span(s, 0, lo, hi); }

/* the second largest of v[0..n-1] (the largest for n < 2) */
static int second(const int *v, int n, int sign)
{
    int a = sign * v[0], b = a;
    for (int k = 1; k < n; k++) {
        int x = sign * v[k];
        if (x > a) { b = a; a = x; }
        else if (x > b || k == 1) b = x;
    }
    return sign * (n < 2 ? a : b);
}

void sim_live_chain(const int *lo, const int *hi, int n, sim_fmt y, int *chain, int *ext, int *low)
{
    int top = y.ibits - 1, hmax = hi[0];
    for (int k = 1; k < n; k++) hmax = imax(hmax, hi[k]);
    top = imin(hmax + 1, top);
    /* the bits below y's lowest give only their carry into it, which
     * synthesis takes by a tree beside the operands' first levels: the
     * chain starts at y's lowest bit */
    int chi = imin(second(hi, n, 1), top), lo2 = second(lo, n, -1), clo = imax(lo2, -y.fbits);
    *low = imax(imin(clo, chi + 1) - lo2, 0);
    *chain = imax(imin(chi - clo + 1, y.width), 1);
    *ext = imax(top - chi, 0);
}
