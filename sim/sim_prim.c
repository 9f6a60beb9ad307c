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
#include "sim/sim_internal.h"
#include "sim/sim_quant.h"
#include <string.h>

typedef struct prim {
    /* what every evaluation reads first */
    sim_signal *y, *a, *b, *c;   /* output; operands (c: enable / select) */
    int64_t     lo, hi;          /* y's raw range */
    int64_t     radd;            /* fast path: added before the shift (half-up) */
    int         k;               /* fast path: right shift from src_f to y */
    int         sa, sb;          /* left shifts aligning a, b to src_f */
    int         src_f;           /* fraction bits of the exact result */
    sim_round   r;
    sim_ovf     o;
    sim_signal *rst;
    int64_t     rst_raw;
    int         n;               /* mux inputs */
    sim_signal *const *in;
    sim_logic_fn fn;
    void       *user;
    sim_signal *clk;             /* register's clock (for sim_prim_describe) */
    const char *verilog;         /* logic: sim_logic_verilog's text */
    int         qlogic;          /* rounding or saturation logic after the element */
} prim;

int64_t sim_quant_into(sim_signal *s, sim_wide raw, int src_fbits, sim_round r, sim_ovf o)
{
    r = sim_fmt_round(s->fmt, r);   /* the signal's own modes, if it has them */
    o = sim_fmt_ovf(s->fmt, o);
    int64_t v;
    if (sim__quant_fits(raw, src_fbits, s->fmt.fbits, s->raw_min, s->raw_max, r, &v)) return v;
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

/* Exact value s (int64_t, |s| < 2^62) with p->src_f fraction bits into y. */
static inline int64_t q64(prim *p, int64_t s)
{
    int64_t x = (int64_t)((uint64_t)s + (uint64_t)p->radd) >> p->k;
    if (__builtin_expect(x >= p->lo && x <= p->hi, 1)) return x;
    return sim_quant_into(p->y, s, p->src_f, p->r, p->o);
}

/* Bits bounding a signal's raw: |raw| <= 2^bits. */
static int raw_bits(const sim_signal *s) { return s->fmt.width; }
/* A value passed through unchanged (register, mux, block key) must stay
 * below 2^62 too, so that adding the rounding constant cannot overflow. */
static int copy_fits(const sim_signal *s) { return raw_bits(s) <= 62; }

/* Set the fast-path constants for an exact result with src_f fraction
 * bits; 1 if the fast path applies (trunc or half-up, 0 <= k < 62). */
static int fast_quant_setup(prim *p, int src_f)
{
    p->src_f = src_f;
    p->lo = p->y->raw_min;
    p->hi = p->y->raw_max;
    return sim__quant_fast(src_f, p->y->fmt.fbits, p->r, &p->k, &p->radd);
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
    if (!p->k && !p->radd) op = op_x[op];
    pr->op = (uint8_t)op;
    pr->op_y = p->y; pr->op_a = p->a; pr->op_b = p->b; pr->op_c = p->c;
    pr->op_lo = p->lo; pr->op_hi = p->hi; pr->op_radd = p->radd;
    pr->op_k = (int8_t)p->k;
    pr->op_n = (uint32_t)p->n;
    pr->op_in = p->in;
}

static prim *prim_new(sim_ctx *c, sim_signal *y)
{
    prim *p = sim_alloc(c, sizeof *p);
    p->y = y;
    /* The output format's own modes, else the context's defaults. */
    p->r = sim_fmt_round(y->fmt, sim_get_round(c));
    p->o = sim_fmt_ovf(y->fmt, sim_get_ovf(c));
    p->lo = y->raw_min;
    p->hi = y->raw_max;
    return p;
}

static sim_proc *prim_proc(sim_ctx *c, sim_signal *y, sim_proc_fn fn, prim *p)
{
    char name[160];
    snprintf(name, sizeof name, "%s.%s", y->scope->name, y->name);
    y->driver = sim_proc_new(c, name, fn, p);
    return y->driver;
}

/* Multiplying by 2^k instead of shifting keeps negative values defined. */
static inline sim_wide align(int64_t raw, int k) { return (sim_wide)raw * ((sim_wide)1 << k); }

static int imax(int a, int b) { return a > b ? a : b; }

/* The logic an element's quantization needs besides truncation and wrap,
 * for an exact result with src_f fraction and src_i integer bits:
 * rounding to nearest where it drops fraction bits, saturation where it
 * drops integer bits. Its area into *area, its arcs after dl's. */
static sim_arcs quant_cost(const prim *p, sim_fmt f, int src_f, int src_i, double *area, sim_arcs dl)
{
    double q = 0;
    if (src_f > f.fbits && p->r != SIM_RND_TRUNC) {
        q += sim_area_round(f.width);
        dl = sim_arcs_then(dl, sim_delay_round(f.width));
    }
    if (src_i > f.ibits && p->o == SIM_OVF_SAT) {
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
    dl = quant_cost(p, y->fmt, src_f, src_i, &q, dl);
    p->qlogic = q > 0;
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
    if (p->rst && p->rst->cur) { sim_write(p->y, p->rst_raw); return; }
    if ((p->c && !p->c->cur) || !p->a) return;
    sim_write(p->y, sim_quant_into(p->y, p->a->cur, p->a->fmt.fbits, p->r, p->o));
}

static void copy_slow(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->y, sim_quant_into(p->y, p->a->cur, p->a->fmt.fbits, p->r, p->o));
}

/* Choose a register's evaluation for its current D input. */
static void reg_setup(sim_proc *pr)
{
    prim *p = pr->data;
    sim__proc_of(pr)->op = SIM__OP_FN;
    if (!p->rst && !p->c && p->a && copy_fits(p->a) && fast_quant_setup(p, p->a->fmt.fbits))
        set_native(pr, SIM__OP_COPY, p);
}

sim_signal *sim_reg(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *clk, sim_signal *d, sim_signal *en,
                    sim_signal *rst, int64_t rst_raw)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_REG);
    prim *p = prim_new(c, y);
    p->a = d; p->c = en; p->rst = rst; p->clk = clk;
    p->rst_raw = sim_fx_canon(rst_raw, fmt);
    y->cur = y->nxt = p->rst_raw;
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
    ((prim *)q->driver->data)->a = d;
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
    p->a = src;
    sim_proc *pr = prim_proc(c, dst, copy_slow, p);
    if (copy_fits(src) && fast_quant_setup(p, src->fmt.fbits)) set_native(pr, SIM__OP_COPY, p);
    sim_sensitive(pr, src, SIM_EDGE_ANY);
}

/* --------------------------------------------------------------------- mux */

static void mux_eval(sim_proc *pr)
{
    prim *p = pr->data;
    int64_t sel = p->c->cur;
    if (sel < 0 || sel >= p->n) { sim_write(p->y, 0); return; }
    const sim_signal *x = p->in[sel];
    sim_write(p->y, sim_quant_into(p->y, x->cur, x->fmt.fbits, p->r, p->o));
}

sim_signal *sim_mux(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *sel, int n, sim_signal *const *in)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_MUX);
    prim *p = prim_new(c, y);
    sim_signal **copy = sim_alloc(c, (size_t)n * sizeof *copy);
    for (int i = 0; i < n; i++) copy[i] = in[i];
    p->c = sel; p->n = n; p->in = copy;
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
    sim_write(p->y, p->c->cur ? sim_quant_into(p->y, p->a->cur, p->a->fmt.fbits, p->r, p->o) : 0);
}

sim_signal *sim_bk(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                   sim_signal *pass, sim_signal *x)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_BK);
    prim *p = prim_new(c, y);
    p->a = x; p->c = pass;
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
    sim_wide s = align(p->a->cur, p->sa) + align(p->b->cur, p->sb);
    sim_write(p->y, sim_quant_into(p->y, s, p->src_f, p->r, p->o));
}

static void sub_eval(sim_proc *pr)
{
    prim *p = pr->data;
    sim_wide s = align(p->a->cur, p->sa) - align(p->b->cur, p->sb);
    sim_write(p->y, sim_quant_into(p->y, s, p->src_f, p->r, p->o));
}

/* Aligned operands each under 2^61: shifting left by s is exact (done
 * unsigned: defined for negative raws). */
static void add_fast_al(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->y, q64(p, (int64_t)(((uint64_t)p->a->cur << p->sa) + ((uint64_t)p->b->cur << p->sb))));
}

static void sub_fast_al(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->y, q64(p, (int64_t)(((uint64_t)p->a->cur << p->sa) - ((uint64_t)p->b->cur << p->sb))));
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

static sim_signal *addsub(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                          sim_signal *a, sim_signal *b, int sub)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, sub ? SIM_KIND_SUB : SIM_KIND_ADD);
    prim *p = prim_new(c, y);
    p->a = a; p->b = b;
    /* Formats have at most 64 fraction bits and 64-bit raws, so the aligned
     * operands need at most 63 + 64 bits: the sum fits in 128. */
    p->src_f = imax(a->fmt.fbits, b->fmt.fbits);
    p->sa = p->src_f - a->fmt.fbits;
    p->sb = p->src_f - b->fmt.fbits;
    sim_proc_fn fn = sub ? sub_eval : add_eval;
    /* |a 2^sa| and |b 2^sb| below 2^61: the sum is below 2^62. */
    int fast = raw_bits(a) + p->sa <= 61 && raw_bits(b) + p->sb <= 61 && fast_quant_setup(p, p->src_f);
    if (fast && (p->sa || p->sb)) fn = sub ? sub_fast_al : add_fast_al;
    sim_proc *pr = prim_proc(c, y, fn, p);
    if (fast && !p->sa && !p->sb) set_native(pr, sub ? SIM__OP_SUB : SIM__OP_ADD, p);
    sim_sensitive(pr, a, SIM_EDGE_ANY);
    sim_sensitive(pr, b, SIM_EDGE_ANY);
    int w = adder_width(a->fmt, b->fmt, fmt);
    set_cost(y, p, sub ? sim_area_sub(w) : sim_area_add(w), sub ? sim_delay_sub(w) : sim_delay_add(w),
             p->src_f, imax(a->fmt.ibits, b->fmt.ibits) + 1);
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
    sim_wide prod = (sim_wide)p->a->cur * (sim_wide)p->b->cur;
    sim_write(p->y, sim_quant_into(p->y, prod, p->src_f, p->r, p->o));
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
    p->a = a; p->b = b;
    p->src_f = a->fmt.fbits + b->fmt.fbits;
    sim_proc *pr = prim_proc(c, y, mul_eval, p);
    /* Operand widths summing to at most 62 bits: the product fits int64_t. */
    if (raw_bits(a) + raw_bits(b) <= 62 && fast_quant_setup(p, p->src_f)) set_native(pr, SIM__OP_MUL, p);
    sim_sensitive(pr, a, SIM_EDGE_ANY);
    sim_sensitive(pr, b, SIM_EDGE_ANY);
    /* the array synthesis builds: the operands' live bits only */
    int la = sim_prim_live_bits(a), lb = sim_prim_live_bits(b);
    set_cost(y, p, sim_area_mul(la, lb), sim_delay_mul(la, lb, fmt.width), p->src_f, a->fmt.ibits + b->fmt.ibits);
    return y;
}

/* ----------------------------------------------------------------- shifter */

static void shift_eval(sim_proc *pr)
{
    prim *p = pr->data;
    /* x * 2^sh is the same raw read with sh fewer fraction bits; a left
     * shift past the binary point is applied to the raw (sa). */
    sim_write(p->y, sim_quant_into(p->y, align(p->a->cur, p->sa), p->src_f, p->r, p->o));
}

static void shift_fast(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->y, q64(p, (int64_t)((uint64_t)p->a->cur << p->sa)));
}

sim_signal *sim_shift(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      sim_signal *x, int sh)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_SHIFT);
    prim *p = prim_new(c, y);
    p->a = x;
    int f = x->fmt.fbits - sh;
    p->sa = f < 0 ? -f : 0;
    p->src_f = f < 0 ? 0 : f;
    int fast = raw_bits(x) + p->sa <= 61 && fast_quant_setup(p, p->src_f);
    sim_proc *pr = prim_proc(c, y, fast && p->sa ? shift_fast : shift_eval, p);
    if (fast && !p->sa) set_native(pr, SIM__OP_COPY, p);
    sim_sensitive(pr, x, SIM_EDGE_ANY);
    set_cost(y, p, 0.0, no_delay(), f, x->fmt.ibits + sh);   /* the shift itself is wires */
    return y;
}

/* ------------------------------------------------------------------- logic */

static void logic_eval(sim_proc *pr)
{
    prim *p = pr->data;
    int64_t v[SIM__LOGIC_MAX];
    for (int i = 0; i < p->n; i++) v[i] = p->in[i]->cur;
    sim_write(p->y, sim__canon(p->fn(v, p->user), p->y->fmt));
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
    p->n = n; p->in = copy; p->fn = fn; p->user = user;
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

/* ------------------------------------------------------------ description */

/* Whether fn is one of this file's evaluations (the process is a prim). */
static int is_prim_fn(sim_proc_fn fn)
{
    static const sim_proc_fn fns[] = { reg_eval, copy_slow, mux_eval, bk_eval, add_eval, sub_eval,
                                       add_fast_al, sub_fast_al, mul_eval, shift_eval, shift_fast,
                                       logic_eval };
    for (size_t i = 0; i < sizeof fns / sizeof fns[0]; i++) if (fns[i] == fn) return 1;
    return 0;
}

int sim_prim_describe(const sim_signal *y, sim_prim_info *out)
{
    memset(out, 0, sizeof *out);
    out->kind = (sim_kind)y->kind;
    if (y->kind == SIM_KIND_CONST) { out->r = SIM_RND_TRUNC; out->o = SIM_OVF_WRAP; return 0; }
    if (!y->driver || !is_prim_fn(sim__proc_of(y->driver)->fn)) return -1;
    const prim *p = y->driver->data;
    out->a = p->a; out->b = p->b; out->c = p->c;
    out->rst = p->rst; out->rst_raw = p->rst_raw; out->clk = p->clk;
    out->n = p->n; out->in = p->in; out->fn = p->fn; out->user = p->user;
    out->r = p->r; out->o = p->o;
    out->qlogic = p->qlogic;
    out->verilog = p->verilog;
    /* sim_shift kept f = fbits(x) - sh as src_f - sa (one of them 0) */
    if (y->kind == SIM_KIND_SHIFT) out->shift = p->a->fmt.fbits - (p->src_f - p->sa);
    if (y->kind == SIM_KIND_ADD || y->kind == SIM_KIND_SUB || y->kind == SIM_KIND_MUL || y->kind == SIM_KIND_SHIFT) {
        out->src_f = p->src_f;
        out->sa = p->sa;
        out->sb = p->sb;
    }
    return 0;
}

int sim_mul_network_delay(sim_signal *y, sim_arcs net)
{
    if (y->kind != SIM_KIND_MUL || !y->driver || sim__proc_of(y->driver)->fn != mul_eval) return -1;
    const prim *p = y->driver->data;
    double q;
    sim_arcs_set(y, quant_cost(p, y->fmt, p->src_f, p->a->fmt.ibits + p->b->fmt.ibits, &q, net));
    return 0;
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
    if (y->kind != SIM_KIND_LOGIC || !y->driver || sim__proc_of(y->driver)->fn != logic_eval) return;
    ((prim *)y->driver->data)->verilog = sim_strdup(y->ctx, text);
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
            if (y->driver && is_prim_fn(sim__proc_of(y->driver)->fn)) {
                const prim *p = y->driver->data;
                sim_signal *fixed[4] = { p->a, p->b, p->c, p->rst };   /* a register's clock aside */
                for (int j = 0; j < 4; j++) if (fixed[j]) add_use(fixed[j], p, fill);
                for (int j = 0; j < p->n; j++) if (p->in[j]) add_use((sim_signal *)(uintptr_t)p->in[j], p, fill);
            }
            /* and every other process woken by it */
            for (uint32_t j = 0; j < y->nfan; j++)
                if (!is_prim_fn(sim__proc_of(y->fan[j].proc)->fn)) add_use(y, NULL, fill);
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
        switch (p->y->kind) {
        case SIM_KIND_REG:      /* D: taken at the next edge if enabled and not reset */
            used = s != p->a || ((!p->c || p->c->cur) && !(p->rst && p->rst->cur));
            break;
        case SIM_KIND_MUX:
            if (s == p->c) used = sim__value_used(p->y, epoch);
            else {
                int64_t sel = p->c->cur;
                used = sel >= 0 && sel < p->n && p->in[sel] == s && sim__value_used(p->y, epoch);
            }
            break;
        case SIM_KIND_BK:
            used = (s == p->c || p->c->cur) && sim__value_used(p->y, epoch);
            break;
        default:
            used = sim__value_used(p->y, epoch);
        }
    }
    s->use_epoch = epoch;
    s->use_memo = (int8_t)used;
    return used;
}
