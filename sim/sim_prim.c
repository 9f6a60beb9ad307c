/* sim_prim.c - registers, multiplexers, block keys, adders, multipliers,
 * shifters and constants as kernel processes.
 *
 * Every element keeps its operands' fraction bits and its quantization modes
 * (its output format's own, else the context's) in its own small struct,
 * so evaluation is: read raws, one exact 128-bit operation, one
 * requantization, one sim_write.
 */
#include "sim/sim_prim.h"
#include "sim/sim_area.h"
#include "sim/sim_delay.h"
#include "sim/sim_live.h"
#include "sim/sim_internal.h"
#include "sim/sim_quant.h"
#include <string.h>

typedef struct prim {
    sim_prim_info e;             /* the element's record (sim_prim.h) */
    /* the fast path's constants, made from it */
    int64_t     lo, hi;          /* y's raw range */
    int64_t     radd;            /* added before the shift (half-up) */
    int         k;               /* right shift from src_f to y */
} prim;

int64_t sim_quant_into(sim_signal *s, sim_wide raw, int src_fbits, sim_round r, sim_ovf o)
{
    r = sim_fmt_round(s->fmt, r);   /* the signal's own modes, if it has them */
    o = sim_fmt_ovf(s->fmt, o);
    int64_t v;
    /* The reference kernel takes no shortcut, here either (units' own
     * processes call this). */
    if (!s->ctx->reference && sim__quant_fits(raw, src_fbits, s->fmt.fbits, s->raw_min, s->raw_max, r, &v)) {
        s->ctx->stats.fast_paths++;
        return v;
    }
    int ovf = 0;
    v = sim_fx_requant(raw, src_fbits, s->fmt, r, o, &ovf);
    if (ovf) sim__overflow(s, v);
    return v;
}

/* ---- specialized quantization ----
 * An element whose exact result provably fits 62 bits (operand widths and
 * alignment shifts known when it is built) computes it in int64_t and, for
 * trunc and half-up into fewer or equal fraction bits, quantizes with one
 * add, one shift and a range check; the result is the general path's
 * (floor((s + 2^(k-1)) / 2^k) is half-up rounding, and in range nothing
 * else applies). Out of range, or any other case, takes sim_quant_into. */

/* Exact value s (int64_t, |s| < 2^62) with p->e.src_f fraction bits into y. */
static inline int64_t q64(prim *p, int64_t s)
{
    p->e.y->ctx->stats.fast_paths++;
    SIM__ASSERT(p->k >= 0 && p->k <= 61 && s > -((int64_t)1 << 62) && s < ((int64_t)1 << 62));
    int64_t x = SIM_OP_QUANT(s, p->radd, p->k);
    if (__builtin_expect(x >= p->lo && x <= p->hi, 1)) return x;
    return sim_quant_into(p->e.y, s, p->e.src_f, p->e.r, p->e.o);
}

/* A value passed through unchanged (register, mux, block key). */
static int copy_fits(const sim_signal *s) { return sim__op_fits_copy(sim__raw_bits(s)); }

/* Set the fast-path constants for an exact result with src_f fraction
 * bits; 1 if the fast path applies (trunc or half-up, 0 <= k < 62). The
 * record's src_f is the arithmetic elements' own (set by them). */
static int fast_quant_setup(prim *p, int src_f)
{
    p->lo = p->e.y->raw_min;
    p->hi = p->e.y->raw_max;
    return sim__quant_fast(src_f, p->e.y->fmt.fbits, p->e.r, &p->k, &p->radd);
}

/* Let the kernel evaluate the element itself (sim_internal.h, SIM__OP_*);
 * fn stays the general evaluation, which the kernel calls when the fast
 * result would be out of range. p's fast-path constants must be set. */
static void set_native(sim_proc *pub, int op, const prim *p)
{
    sim__proc *pr = sim__proc_of(pub);
    /* No rounding shift: the variant that only checks the range. */
#define OP_X(O, label, x) [SIM__OP_##O] = SIM__OP_##x,
    static const uint8_t op_x[SIM__OP__COUNT] = { SIM__OP_LIST(OP_X) };
#undef OP_X
    /* what the inline operations assume (sim_deltas.h): a shift a 64-bit
     * value takes, a range to land in, operands whose exact result fits
     * 62 bits, aligned fractions for the adder (no shift per input) */
    SIM__ASSERT(p->k >= 0 && p->k <= 61 && p->lo <= p->hi);
    SIM__ASSERT(op != SIM__OP_MUL || sim__op_fits_mul(p->e.a->fmt.width, p->e.b->fmt.width));
    SIM__ASSERT((op != SIM__OP_ADD && op != SIM__OP_SUB) ||
                (p->e.a->fmt.fbits == p->e.b->fmt.fbits && p->e.sa == 0 && p->e.sb == 0 &&
                 sim__op_fits_aligned(p->e.a->fmt.width, 0) && sim__op_fits_aligned(p->e.b->fmt.width, 0)));
    SIM__ASSERT((op != SIM__OP_COPY && op != SIM__OP_MUX && op != SIM__OP_BK) || !p->e.a ||
                sim__op_fits_copy(p->e.a->fmt.width));
    if (!p->k && !p->radd) op = op_x[op];
    pr->op = (uint8_t)op;
    pr->op_y = p->e.y; pr->op_a = p->e.a; pr->op_b = p->e.b; pr->op_c = p->e.c;
    pr->op_lo = p->lo; pr->op_hi = p->hi; pr->op_radd = p->radd;
    pr->op_k = (int8_t)p->k;
    pr->op_n = (uint32_t)p->e.n;
    pr->op_in = p->e.in;
}

static prim *prim_new(sim_ctx *c, sim_signal *y)
{
    prim *p = sim_alloc(c, sizeof *p);
    p->e.y = y;
    p->e.kind = (sim_kind)y->kind;
    /* The output format's own modes, else the context's defaults. */
    p->e.r = sim_fmt_round(y->fmt, sim_get_round(c));
    p->e.o = sim_fmt_ovf(y->fmt, sim_get_ovf(c));
    p->lo = y->raw_min;
    p->hi = y->raw_max;
    return p;
}

static sim_proc *prim_proc(sim_ctx *c, sim_signal *y, sim_proc_fn fn, prim *p)
{
    char name[160];
    snprintf(name, sizeof name, "%s.%s", y->scope->name, y->name);
    y->driver = sim_proc_new(c, name, fn, p);
    sim__proc_of(y->driver)->elem = &p->e;   /* a primitive: the reference evaluates its record */
    return y->driver;
}

static int imax(int a, int b) { return a > b ? a : b; }

/* The logic an element's quantization needs besides truncation and wrap,
 * for an exact result with src_f fraction and src_i integer bits:
 * rounding to nearest where it drops fraction bits, saturation where it
 * drops integer bits. Its area into *area, its arcs after dl's. */
static sim_arcs quant_cost(const prim *p, sim_fmt f, int src_f, int src_i, double *area, sim_arcs dl, sim_carry k)
{
    double q = 0;
    if (src_f > f.fbits && p->e.r != SIM_RND_TRUNC) {
        q += sim_area_round(f.width);
        dl = sim_arcs_then(dl, sim_delay_round(f.width, k));
    }
    if (src_i > f.ibits && p->e.o == SIM_OVF_SAT) {
        q += sim_area_sat(f.width, src_i - f.ibits);
        dl = sim_arcs_then(dl, sim_delay_sat(src_i - f.ibits));
    }
    *area = q;
    return dl;
}

/* Set the element's area and delay: its own logic (area, dl), then its
 * quantization's. */
static void set_cost(sim_signal *y, prim *p, double area, sim_arcs dl, int src_f, int src_i)
{
    double q;
    dl = quant_cost(p, y->fmt, src_f, src_i, &q, dl, SIM_CARRY_RIPPLE);
    p->e.qlogic = q > 0;
    y->area_ge = area + q;
    sim_arcs_set(y, dl);
}

static sim_arcs no_delay(void) { sim_delay z = { 0, 0.0 }; return sim_arcs_bitwise(z); }

/* ---------------------------------------------------------------- constant */

sim_signal *sim_const_raw(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt, int64_t raw)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_CONST);
    y->cur = y->nxt = sim_fx_canon(raw, fmt);
    return y;   /* tied wires: no process, no area */
}

sim_signal *sim_const(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt, double x)
{
    int ovf = 0;
    int64_t raw = sim_fx_from_real(x, fmt, sim_get_round(c), sim_get_ovf(c), &ovf);
    sim_signal *y = sim_const_raw(c, sc, name, fmt, raw);
    y->overflows += (uint64_t)ovf;
    return y;
}

/* ---------------------------------------------------------------- register */

static void reg_eval(sim_proc *pr)
{
    prim *p = pr->data;
    if (p->e.rst && p->e.rst->cur) { sim_write(p->e.y, p->e.rst_raw); return; }
    if ((p->e.c && !p->e.c->cur) || !p->e.a) return;
    sim_write(p->e.y, sim_quant_into(p->e.y, p->e.a->cur, p->e.a->fmt.fbits, p->e.r, p->e.o));
}

static void copy_slow(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->e.y, sim_quant_into(p->e.y, p->e.a->cur, p->e.a->fmt.fbits, p->e.r, p->e.o));
}

/* Choose a register's evaluation for its current D input. */
static void reg_setup(sim_proc *pr)
{
    prim *p = pr->data;
    sim__proc_of(pr)->op = SIM__OP_FN;
    if (!p->e.rst && !p->e.c && p->e.a && copy_fits(p->e.a) && fast_quant_setup(p, p->e.a->fmt.fbits))
        set_native(pr, SIM__OP_COPY, p);
}

sim_signal *sim_reg(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *clk, sim_signal *d, sim_signal *en,
                    sim_signal *rst, int64_t rst_raw)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_REG);
    prim *p = prim_new(c, y);
    p->e.a = d; p->e.c = en; p->e.rst = rst; p->e.clk = clk;
    p->e.rst_raw = sim_fx_canon(rst_raw, fmt);
    y->cur = y->nxt = p->e.rst_raw;
    sim_proc *pr = prim_proc(c, y, reg_eval, p);
    reg_setup(pr);
    sim_sensitive(pr, clk, SIM_EDGE_POS);
    pr->no_init = 1;   /* a register changes on edges only */
    y->area_ge = sim_area_reg(fmt.width, en != NULL, rst != NULL);
    sim_arcs_set(y, sim_arcs_all(sim_delay_reg_cq()));
    return y;
}

int sim_reg_connect(sim_signal *q, sim_signal *d)
{
    if (q->kind != SIM_KIND_REG || !q->driver) return -1;
    ((prim *)q->driver->data)->e.a = d;
    reg_setup(q->driver);
    sim__uses_stale(q->ctx);
    return 0;
}

void sim_assign(sim_ctx *c, sim_signal *dst, sim_signal *src)
{
    if (dst->driver || dst->kind == SIM_KIND_CONST || dst->kind == SIM_KIND_CLOCK) {
        /* Two drivers of one wire: the hardware would short them, and the
         * kernel would keep whichever evaluated last. */
        char path[256], from[256];
        sim__elab_error(c, "%s: two drivers: sim_assign from %s into a signal already driven by %s%s",
                        sim_signal_path(dst, path, sizeof path), sim_signal_path(src, from, sizeof from),
                        dst->driver ? "process " : "",
                        dst->driver ? sim_proc_name(dst->driver)
                        : dst->kind == SIM_KIND_CONST ? "a constant" : "a clock");
        return;
    }
    prim *p = prim_new(c, dst);
    p->e.a = src;
    sim_proc *pr = prim_proc(c, dst, copy_slow, p);
    if (copy_fits(src) && fast_quant_setup(p, src->fmt.fbits)) set_native(pr, SIM__OP_COPY, p);
    sim_sensitive(pr, src, SIM_EDGE_ANY);
}

/* --------------------------------------------------------------------- mux */

static void mux_eval(sim_proc *pr)
{
    prim *p = pr->data;
    int64_t sel = p->e.c->cur;
    if (!SIM_OP_SEL_IN(sel, p->e.n)) { sim_write(p->e.y, 0); return; }
    const sim_signal *x = p->e.in[sel];
    sim_write(p->e.y, sim_quant_into(p->e.y, x->cur, x->fmt.fbits, p->e.r, p->e.o));
}

sim_signal *sim_mux(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *sel, int n, sim_signal *const *in)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_MUX);
    prim *p = prim_new(c, y);
    sim_signal **copy = sim_alloc(c, (size_t)n * sizeof *copy);
    for (int i = 0; i < n; i++) copy[i] = in[i];
    p->e.c = sel; p->e.n = n; p->e.in = copy;
    int same = n > 0 && copy_fits(in[0]);
    for (int i = 1; i < n; i++) same &= in[i]->fmt.fbits == in[0]->fmt.fbits && copy_fits(in[i]);
    sim_proc *pr = prim_proc(c, y, mux_eval, p);
    /* Every input with the same fraction bits: one quantization for all. */
    if (same && fast_quant_setup(p, in[0]->fmt.fbits)) set_native(pr, SIM__OP_MUX, p);
    sim_sensitive(pr, sel, SIM_EDGE_ANY);
    for (int i = 0; i < n; i++) sim_sensitive(pr, copy[i], SIM_EDGE_ANY);
    int mf = 0, mi = 0;
    for (int i = 0; i < n; i++) { mf = imax(mf, in[i]->fmt.fbits); mi = imax(mi, in[i]->fmt.ibits); }
    set_cost(y, p, sim_area_mux(fmt.width, n), sim_delay_mux(n), mf, mi);
    return y;
}

/* ------------------------------------------------------------- block key */

static void bk_eval(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->e.y, p->e.c->cur ? sim_quant_into(p->e.y, p->e.a->cur, p->e.a->fmt.fbits, p->e.r, p->e.o) : 0);
}

sim_signal *sim_bk(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                   sim_signal *pass, sim_signal *x)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_BK);
    prim *p = prim_new(c, y);
    p->e.a = x; p->e.c = pass;
    sim_proc *pr = prim_proc(c, y, bk_eval, p);
    if (copy_fits(x) && fast_quant_setup(p, x->fmt.fbits)) set_native(pr, SIM__OP_BK, p);
    sim_sensitive(pr, pass, SIM_EDGE_ANY);
    sim_sensitive(pr, x, SIM_EDGE_ANY);
    set_cost(y, p, sim_area_bk(fmt.width), sim_delay_bk(), x->fmt.fbits, x->fmt.ibits);
    return y;
}

/* ------------------------------------------------------ adder, subtractor */

static void add_eval(sim_proc *pr)
{
    prim *p = pr->data;
    sim_wide s = SIM_OP_ADD(sim_wide, SIM_OP_ALIGN(sim_wide, p->e.a->cur, p->e.sa),
                            SIM_OP_ALIGN(sim_wide, p->e.b->cur, p->e.sb));
    sim_write(p->e.y, sim_quant_into(p->e.y, s, p->e.src_f, p->e.r, p->e.o));
}

static void sub_eval(sim_proc *pr)
{
    prim *p = pr->data;
    sim_wide s = SIM_OP_SUB(sim_wide, SIM_OP_ALIGN(sim_wide, p->e.a->cur, p->e.sa),
                            SIM_OP_ALIGN(sim_wide, p->e.b->cur, p->e.sb));
    sim_write(p->e.y, sim_quant_into(p->e.y, s, p->e.src_f, p->e.r, p->e.o));
}

/* Aligned operands each under 2^61: the uint64_t forms are exact. */
static void add_fast_al(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->e.y, q64(p, (int64_t)SIM_OP_ADD(uint64_t, SIM_OP_ALIGN(uint64_t, p->e.a->cur, p->e.sa),
                                                 SIM_OP_ALIGN(uint64_t, p->e.b->cur, p->e.sb))));
}

static void sub_fast_al(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->e.y, q64(p, (int64_t)SIM_OP_SUB(uint64_t, SIM_OP_ALIGN(uint64_t, p->e.a->cur, p->e.sa),
                                                 SIM_OP_ALIGN(uint64_t, p->e.b->cur, p->e.sb))));
}

/* Bits an adder really has: the operands' integer part (plus a carry, but
 * no more than the output keeps) and every fraction bit of the operands,
 * since dropped low bits still carry into the kept ones. */
static int adder_width(sim_fmt a, sim_fmt b, sim_fmt y)
{
    int ib = imax(a.ibits, b.ibits) + 1;
    if (ib > y.ibits) ib = y.ibits;
    int w = ib + imax(a.fbits, b.fbits);
    return w < 1 ? 1 : w;
}

/* The carry chain of adder y over the bits where both operands vary, the
 * bits above and below it (sim_live.h); the operands' spans into lo, hi. */
static void addsub_spans(const sim_signal *y, int *chain, int *ext, int *low, int *lo, int *hi)
{
    const prim *p = y->driver->data;
    const sim_signal *a = p->e.a, *b = p->e.b;
    int w = adder_width(a->fmt, b->fmt, y->fmt);
    sim_live_span(a, &lo[0], &hi[0]);
    sim_live_span(b, &lo[1], &hi[1]);
    sim_live_chain(lo, hi, 2, y->fmt, chain, ext, low);
    if (*chain > w) *chain = w;
}

/* The delay of adder, subtractor or multiplier y before its output's
 * quantization, with the carries k; the integer bits of its exact result
 * into *src_i. One definition for the element's own arcs (ripple, at
 * construction) and for sim_prim_arcs (the carries a flow leaves). */
static sim_arcs op_arcs(const sim_signal *y, sim_carry k, int *src_i)
{
    const prim *p = y->driver->data;
    const sim_signal *a = p->e.a, *b = p->e.b;
    if (y->kind == SIM_KIND_MUL) {
        /* the array synthesis builds: the operands' live bits only; a
         * product by a constant too: the export writes it as a product,
         * which Yosys builds as its own multiplier (a row per nonzero bit),
         * the shift-and-add network (sim_mul_network_delay) being what
         * ABC's restructuring makes of it */
        *src_i = a->fmt.ibits + b->fmt.ibits;
        return sim_delay_mul(sim_prim_live_bits(a), sim_prim_live_bits(b), y->fmt.width, k);
    }
    int chain, ext, low, lo[2], hi[2];
    addsub_spans(y, &chain, &ext, &low, lo, hi);
    *src_i = imax(a->fmt.ibits, b->fmt.ibits) + 1;
    return y->kind == SIM_KIND_SUB ? sim_delay_sub_span(chain, ext, low, k) : sim_delay_add_span(chain, ext, low, k);
}

static sim_signal *addsub(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                          sim_signal *a, sim_signal *b, int sub)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, sub ? SIM_KIND_SUB : SIM_KIND_ADD);
    prim *p = prim_new(c, y);
    p->e.a = a; p->e.b = b;
    /* Formats have at most 64 fraction bits and 64-bit raws, so the aligned
     * operands need at most 63 + 64 bits: the sum fits in 128. */
    p->e.src_f = imax(a->fmt.fbits, b->fmt.fbits);
    p->e.sa = p->e.src_f - a->fmt.fbits;
    p->e.sb = p->e.src_f - b->fmt.fbits;
    sim_proc_fn fn = sub ? sub_eval : add_eval;
    /* |a 2^sa| and |b 2^sb| below 2^61: the sum is below 2^62. */
    int fast = sim__op_fits_aligned(sim__raw_bits(a), p->e.sa) && sim__op_fits_aligned(sim__raw_bits(b), p->e.sb) &&
               fast_quant_setup(p, p->e.src_f);
    if (fast && (p->e.sa || p->e.sb)) fn = sub ? sub_fast_al : add_fast_al;
    sim_proc *pr = prim_proc(c, y, fn, p);
    if (fast && !p->e.sa && !p->e.sb) set_native(pr, sub ? SIM__OP_SUB : SIM__OP_ADD, p);
    sim_sensitive(pr, a, SIM_EDGE_ANY);
    sim_sensitive(pr, b, SIM_EDGE_ANY);
    int chain, ext, low, lo[2], hi[2];
    addsub_spans(y, &chain, &ext, &low, lo, hi);
    /* area over the same spans: the chain as mapped, an incrementer above,
     * the carry alone below, and the negation of a subtrahend's bits below
     * the chain where the minuend is zero (sim_area_addsub) */
    int ylo = -fmt.fbits, clo = imax(imax(lo[0], lo[1]), ylo);
    int neg = sub && lo[1] < lo[0] ? imax(clo - imax(lo[1], ylo), 0) : 0;
    int src_i;
    sim_arcs dl = op_arcs(y, SIM_CARRY_RIPPLE, &src_i);
    set_cost(y, p, sim_area_addsub(sub, chain, ext, low, neg), dl, p->e.src_f, src_i);
    return y;
}

sim_signal *sim_add(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b)
{
    return addsub(c, sc, name, fmt, a, b, 0);
}

sim_signal *sim_sub(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b)
{
    return addsub(c, sc, name, fmt, a, b, 1);
}

/* -------------------------------------------------------------- multiplier */

static void mul_eval(sim_proc *pr)
{
    prim *p = pr->data;
    sim_wide prod = SIM_OP_MUL(sim_wide, p->e.a->cur, p->e.b->cur);
    sim_write(p->e.y, sim_quant_into(p->e.y, prod, p->e.src_f, p->e.r, p->e.o));
}

int sim_prim_live_bits(const sim_signal *s)
{
    sim_prim_info in;
    for (int depth = 0; depth < 16 && s->kind == SIM_KIND_SHIFT && !sim_prim_describe(s, &in) && in.a; depth++) {
        /* a constant shift is wiring: its other bits are constant zeros */
        if (in.a->kind != SIM_KIND_SHIFT) {
            int w = sim_prim_live_bits(in.a);
            return w < s->fmt.width ? w : s->fmt.width;
        }
        s = in.a;
    }
    if (s->kind == SIM_KIND_CONST) {
        uint64_t m = s->fmt.width >= 64 ? UINT64_MAX : (((uint64_t)1 << s->fmt.width) - 1);
        uint64_t v = (s->cur < 0 ? (uint64_t)0 - (uint64_t)s->cur : (uint64_t)s->cur) & m;
        int k = 0;
        for (; v; v &= v - 1) k++;
        return k ? k : 1;
    }
    return s->fmt.width;
}

sim_signal *sim_mul(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_MUL);
    prim *p = prim_new(c, y);
    p->e.a = a; p->e.b = b;
    p->e.src_f = a->fmt.fbits + b->fmt.fbits;
    sim_proc *pr = prim_proc(c, y, mul_eval, p);
    /* Operand widths summing to at most 62 bits: the product fits int64_t. */
    if (sim__op_fits_mul(sim__raw_bits(a), sim__raw_bits(b)) && fast_quant_setup(p, p->e.src_f)) set_native(pr, SIM__OP_MUL, p);
    sim_sensitive(pr, a, SIM_EDGE_ANY);
    sim_sensitive(pr, b, SIM_EDGE_ANY);
    /* the array synthesis builds: the operands' live bits only */
    int la = sim_prim_live_bits(a), lb = sim_prim_live_bits(b);
    /* the product's columns the output does not keep (constant operands:
     * a shift-and-add, whose rows are the constant's bits, left whole) */
    int lo = 0, hi = 0;
    if (a->kind != SIM_KIND_CONST && b->kind != SIM_KIND_CONST && la == a->fmt.width && lb == b->fmt.width) {
        lo = p->e.src_f - fmt.fbits;
        hi = a->fmt.ibits + b->fmt.ibits - fmt.ibits;
    }
    double ge = sim_area_mul_cols(la, lb, lo > 0 ? lo : 0, hi > 0 ? hi : 0);
    /* the array as ABC maps it (sim_area_mul_fit): by the operands'
     * signs, a square apart; a constant's shift-and-add is no array */
    if (a->kind != SIM_KIND_CONST && b->kind != SIM_KIND_CONST) {
        int sa = a->fmt.is_signed, sb = b->fmt.is_signed;
        int kind = a == b ? (sa ? SIM_MUL_SQ_S : SIM_MUL_SQ_U) : sa && sb ? SIM_MUL_SS : sa || sb ? SIM_MUL_SU : SIM_MUL_UU;
        ge *= sim_area_mul_fit(kind, la < lb ? la : lb);
    }
    int src_i;
    sim_arcs dl = op_arcs(y, SIM_CARRY_RIPPLE, &src_i);
    set_cost(y, p, ge, dl, p->e.src_f, src_i);
    return y;
}

/* ----------------------------------------------------------------- shifter */

static void shift_eval(sim_proc *pr)
{
    prim *p = pr->data;
    /* x * 2^sh is the same raw read with sh fewer fraction bits; a left
     * shift past the binary point is applied to the raw (sa). */
    sim_write(p->e.y, sim_quant_into(p->e.y, SIM_OP_ALIGN(sim_wide, p->e.a->cur, p->e.sa), p->e.src_f, p->e.r, p->e.o));
}

static void shift_fast(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->e.y, q64(p, (int64_t)SIM_OP_ALIGN(uint64_t, p->e.a->cur, p->e.sa)));
}

sim_signal *sim_shift(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      sim_signal *x, int sh)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_SHIFT);
    prim *p = prim_new(c, y);
    p->e.a = x;
    p->e.shift = sh;
    int f = x->fmt.fbits - sh;
    p->e.sa = f < 0 ? -f : 0;
    p->e.src_f = f < 0 ? 0 : f;
    int fast = sim__op_fits_aligned(sim__raw_bits(x), p->e.sa) && fast_quant_setup(p, p->e.src_f);
    sim_proc *pr = prim_proc(c, y, fast && p->e.sa ? shift_fast : shift_eval, p);
    if (fast && !p->e.sa) set_native(pr, SIM__OP_COPY, p);
    sim_sensitive(pr, x, SIM_EDGE_ANY);
    set_cost(y, p, 0.0, no_delay(), f, x->fmt.ibits + sh);   /* the shift itself is wires */
    return y;
}

/* ------------------------------------------------------------------- logic */

static void logic_eval(sim_proc *pr)
{
    prim *p = pr->data;
    int64_t v[SIM__LOGIC_MAX];
    for (int i = 0; i < p->e.n; i++) v[i] = p->e.in[i]->cur;
    sim_write(p->e.y, sim__canon(p->e.fn(v, p->e.user), p->e.y->fmt));
}

sim_signal *sim_logic(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      int n, sim_signal *const *in, sim_logic_fn fn, void *user,
                      double area_ge)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_LOGIC);
    if (n < 0 || n > SIM__LOGIC_MAX) {
        /* The element is left without inputs (and its output at 0); the
         * run will not start. */
        char path[256];
        sim__elab_error(c, "%s: sim_logic with %d inputs (at most %d)",
                        sim_signal_path(y, path, sizeof path), n, SIM__LOGIC_MAX);
        n = 0;
    }
    prim *p = prim_new(c, y);
    sim_signal **copy = sim_alloc(c, (size_t)(n ? n : 1) * sizeof *copy);
    for (int i = 0; i < n; i++) copy[i] = in[i];
    p->e.n = n; p->e.in = copy; p->e.fn = fn; p->e.user = user;
    sim_proc *pr = prim_proc(c, y, logic_eval, p);
    if (n >= 1) {
        set_native(pr, fmt.is_signed ? SIM__OP_LOGIC_S : SIM__OP_LOGIC_U, p);
        sim__proc *k = sim__proc_of(pr);
        k->op_a = copy[0];
        k->op_k = (int8_t)(64 - fmt.width);
        k->op_radd = (int64_t)(UINT64_MAX >> (64 - fmt.width));
        k->op_logic = fn;
        k->op_user = user;
    }
    for (int i = 0; i < n; i++) sim_sensitive(pr, copy[i], SIM_EDGE_ANY);
    y->area_ge = area_ge;
    int bits = 0;
    for (int i = 0; i < n; i++) bits += copy[i]->fmt.width;
    sim_arcs_set(y, sim_delay_logic(bits));
    return y;
}

/* ---------------------------------------------------------------- reference */

void sim__elem_step(sim__proc *pr)
{
    const sim_prim_info *e = pr->elem;
    int n = sim_elem_nin(e);
    int64_t v[n > 0 ? n : 1], out;
    int ovf;
    sim_elem_read(e, v);
    if (!sim_elem_eval(e, v, &out, &ovf)) return;
    if (ovf) sim__overflow(e->y, out);
    sim_write(e->y, out);
}

/* ------------------------------------------------------------ description */

/* The element record of the primitive driving y, or NULL (an input, a
 * clock, a constant, a user process). */
static const sim_prim_info *elem_of(const sim_signal *y)
{
    return y->driver ? sim__proc_of(y->driver)->elem : NULL;
}

int sim_prim_describe(const sim_signal *y, sim_prim_info *out)
{
    const sim_prim_info *e = elem_of(y);
    if (e) { *out = *e; return 0; }
    memset(out, 0, sizeof *out);
    out->kind = (sim_kind)y->kind;
    out->y = (sim_signal *)(uintptr_t)y;
    if (y->kind == SIM_KIND_CONST) { out->r = SIM_RND_TRUNC; out->o = SIM_OVF_WRAP; return 0; }
    return -1;
}

int sim_mul_network_delay(sim_signal *y, sim_arcs net)
{
    if (y->kind != SIM_KIND_MUL || !elem_of(y)) return -1;
    const prim *p = y->driver->data;
    double q;
    sim_arcs_set(y, quant_cost(p, y->fmt, p->e.src_f, p->e.a->fmt.ibits + p->e.b->fmt.ibits, &q, net, SIM_CARRY_RIPPLE));
    return 0;
}

sim_arcs sim_prim_arcs(const sim_signal *y, sim_carry k)
{
    const sim_prim_info *e = elem_of(y);
    if (k == SIM_CARRY_RIPPLE || !e || (e->kind != SIM_KIND_ADD && e->kind != SIM_KIND_SUB && e->kind != SIM_KIND_MUL))
        return sim_arcs_of(y);
    const prim *p = y->driver->data;
    int src_i;
    sim_arcs dl = op_arcs(y, k, &src_i);
    double q;
    return quant_cost(p, y->fmt, e->src_f, src_i, &q, dl, k);
}

int sim_prim_reads(const sim_prim_info *in, const sim_signal **r)
{
    int n = 0;
    switch (in->kind) {
    case SIM_KIND_MUX:
        r[n++] = in->c;
        for (int i = 0; i < in->n; i++) r[n++] = in->in[i];
        break;
    case SIM_KIND_LOGIC:
        for (int i = 0; i < in->n && i < SIM__LOGIC_MAX; i++) r[n++] = in->in[i];
        break;
    case SIM_KIND_BK:
        r[n++] = in->c;
        /* fall through */
    default:
        if (in->a) r[n++] = in->a;
        if (in->b) r[n++] = in->b;
        break;
    }
    return n;
}

void sim_logic_depth(sim_signal *y, int levels)
{
    if (y->kind != SIM_KIND_LOGIC || !y->driver || sim__proc_of(y->driver)->fn != logic_eval) return;
    sim_delay dl = { levels, levels * SIM_PS_AND2 };
    sim_arcs_set(y, sim_arcs_all(dl));
}

void sim_logic_verilog(sim_signal *y, const char *text)
{
    if (y->kind != SIM_KIND_LOGIC || !elem_of(y)) return;
    ((prim *)y->driver->data)->e.verilog = sim_strdup(y->ctx, text);
}

void sim_logic_linear(sim_signal *y, int i, double k, double lo, double hi)
{
    if (y->kind != SIM_KIND_LOGIC || !elem_of(y)) return;
    prim *p = y->driver->data;
    if (i < 0 || i >= p->e.n || !(lo <= hi)) return;
    sim_logic_lin *l = sim_alloc(y->ctx, sizeof *l);
    *l = (sim_logic_lin){ i, k, lo, hi };
    p->e.lin = l;
}

void sim_logic_monotone(sim_signal *y)
{
    if (y->kind != SIM_KIND_LOGIC || !elem_of(y)) return;
    prim *p = y->driver->data;
    if (p->e.n == 1) p->e.monotone = 1;
}

/* ------------------------------------------------------------ used values */

static void add_use(sim_signal *s, const void *pr, int fill)
{
    if (fill) s->uses[s->nuses].prim = pr;
    s->nuses++;
}

void sim__uses_build(sim_ctx *c)
{
    uint32_t ns = sim_signal_count(c);
    for (int fill = 0; fill < 2; fill++) {
        for (uint32_t i = 0; i < ns; i++) {
            sim_signal *s = sim_signal_at(c, i);
            if (fill) s->uses = s->nuses ? sim_alloc(c, s->nuses * sizeof *s->uses) : NULL;
            s->nuses = 0;
        }
        for (uint32_t i = 0; i < ns; i++) {
            sim_signal *y = sim_signal_at(c, i);
            /* every primitive reading a signal, the registers (sensitive to
             * their clock only) among them */
            if (elem_of(y)) {
                const prim *p = y->driver->data;
                sim_signal *fixed[4] = { p->e.a, p->e.b, p->e.c, p->e.rst };   /* a register's clock aside */
                for (int j = 0; j < 4; j++) if (fixed[j]) add_use(fixed[j], p, fill);
                for (int j = 0; j < p->e.n; j++) if (p->e.in[j]) add_use((sim_signal *)(uintptr_t)p->e.in[j], p, fill);
            }
            /* and every other process woken by it */
            for (uint32_t j = 0; j < y->nfan; j++)
                if (!sim__proc_of(y->fan[j].proc)->elem) add_use(y, NULL, fill);
        }
    }
}

int sim__value_used(sim_signal *s, uint64_t epoch)
{
    if (s->kind == SIM_KIND_REG || s->is_output || !s->nuses) return 1;   /* state, a port, an end */
    if (s->use_epoch == epoch) return s->use_memo;
    int used = 0;
    for (uint32_t i = 0; i < s->nuses && !used; i++) {
        const prim *p = s->uses[i].prim;
        if (!p) { used = 1; break; }
        switch (p->e.y->kind) {
        case SIM_KIND_REG:      /* D: taken at the next edge if enabled and not reset */
            used = s != p->e.a || ((!p->e.c || p->e.c->cur) && !(p->e.rst && p->e.rst->cur));
            break;
        case SIM_KIND_MUX:
            if (s == p->e.c) used = sim__value_used(p->e.y, epoch);
            else {
                int64_t sel = p->e.c->cur;
                used = SIM_OP_SEL_IN(sel, p->e.n) && p->e.in[sel] == s && sim__value_used(p->e.y, epoch);
            }
            break;
        case SIM_KIND_BK:
            used = (s == p->e.c || p->e.c->cur) && sim__value_used(p->e.y, epoch);
            break;
        default:
            used = sim__value_used(p->e.y, epoch);
        }
    }
    s->use_epoch = epoch;
    s->use_memo = (int8_t)used;
    return used;
}
