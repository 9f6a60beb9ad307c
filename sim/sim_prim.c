/* sim_prim.c - registers, multiplexers, block keys, adders, multipliers,
 * shifters and constants as kernel processes.
 *
 * Every element keeps its operands' fraction bits and its quantization modes
 * in its own small struct, so evaluation is: read raws, one exact 128-bit
 * operation, one requantization, one sim_write.
 */
#include "sim/sim_prim.h"
#include "sim/sim_area.h"

typedef struct prim {
    sim_signal *y, *a, *b, *c;   /* output; operands (c: enable / select) */
    sim_signal *rst;
    int64_t     rst_raw;
    int         sa, sb;          /* left shifts aligning a, b to fy_src */
    int         src_f;           /* fraction bits of the exact result */
    sim_round   r;
    sim_ovf     o;
    int         n;               /* mux inputs */
    sim_signal *const *in;
    sim_logic_fn fn;
    void       *user;
} prim;

int64_t sim_quant_into(sim_signal *s, sim_wide raw, int src_fbits, sim_round r, sim_ovf o)
{
    /* Fast path for what datapaths do on almost every clock: drop k < 63
     * low bits of a value that fits 63 bits by truncation or half-up, and
     * land in range. Anything else takes the general path, which is the
     * definition (tests compare both through the primitives). */
    int k = src_fbits - s->fmt.fbits;
    if ((unsigned)k < 63 && raw >= -((sim_wide)1 << 62) && raw < ((sim_wide)1 << 62) && r != SIM_RND_EVEN) {
        int64_t x = (int64_t)raw;
        if (k && r == SIM_RND_HALF_UP) x += (int64_t)1 << (k - 1);
        x >>= k;   /* arithmetic shift: floor division by 2^k (gcc, clang) */
        if (x >= s->raw_min && x <= s->raw_max) return x;
    }
    int ovf = 0;
    int64_t v = sim_fx_requant(raw, src_fbits, s->fmt, r, o, &ovf);
    s->overflows += (uint64_t)ovf;
    return v;
}

static prim *prim_new(sim_ctx *c, sim_signal *y)
{
    prim *p = sim_alloc(c, sizeof *p);
    p->y = y;
    p->r = sim_get_round(c);
    p->o = sim_get_ovf(c);
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

sim_signal *sim_reg(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *clk, sim_signal *d, sim_signal *en,
                    sim_signal *rst, int64_t rst_raw)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_REG);
    prim *p = prim_new(c, y);
    p->a = d; p->c = en; p->rst = rst;
    p->rst_raw = sim_fx_canon(rst_raw, fmt);
    y->cur = y->nxt = p->rst_raw;
    sim_proc *pr = prim_proc(c, y, reg_eval, p);
    sim_sensitive(pr, clk, SIM_EDGE_POS);
    pr->no_init = 1;   /* a register changes on edges only */
    y->area_ge = sim_area_reg(fmt.width, en != NULL, rst != NULL);
    return y;
}

int sim_reg_connect(sim_signal *q, sim_signal *d)
{
    if (q->kind != SIM_KIND_REG || !q->driver) return -1;
    ((prim *)q->driver->data)->a = d;
    return 0;
}

static void assign_eval(sim_proc *pr)
{
    prim *p = pr->data;
    sim_write(p->y, sim_quant_into(p->y, p->a->cur, p->a->fmt.fbits, p->r, p->o));
}

void sim_assign(sim_ctx *c, sim_signal *dst, sim_signal *src)
{
    prim *p = prim_new(c, dst);
    p->a = src;
    sim_proc *pr = prim_proc(c, dst, assign_eval, p);
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
    sim_proc *pr = prim_proc(c, y, mux_eval, p);
    sim_sensitive(pr, sel, SIM_EDGE_ANY);
    for (int i = 0; i < n; i++) sim_sensitive(pr, copy[i], SIM_EDGE_ANY);
    y->area_ge = sim_area_mux(fmt.width, n);
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
    sim_sensitive(pr, pass, SIM_EDGE_ANY);
    sim_sensitive(pr, x, SIM_EDGE_ANY);
    y->area_ge = sim_area_bk(fmt.width);
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
    sim_proc *pr = prim_proc(c, y, sub ? sub_eval : add_eval, p);
    sim_sensitive(pr, a, SIM_EDGE_ANY);
    sim_sensitive(pr, b, SIM_EDGE_ANY);
    int w = adder_width(a->fmt, b->fmt, fmt);
    y->area_ge = sub ? sim_area_sub(w) : sim_area_add(w);
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

sim_signal *sim_mul(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                    sim_signal *a, sim_signal *b)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_MUL);
    prim *p = prim_new(c, y);
    p->a = a; p->b = b;
    p->src_f = a->fmt.fbits + b->fmt.fbits;
    sim_proc *pr = prim_proc(c, y, mul_eval, p);
    sim_sensitive(pr, a, SIM_EDGE_ANY);
    sim_sensitive(pr, b, SIM_EDGE_ANY);
    y->area_ge = sim_area_mul(a->fmt.width, b->fmt.width);
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

sim_signal *sim_shift(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      sim_signal *x, int sh)
{
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_SHIFT);
    prim *p = prim_new(c, y);
    p->a = x;
    int f = x->fmt.fbits - sh;
    p->sa = f < 0 ? -f : 0;
    p->src_f = f < 0 ? 0 : f;
    sim_proc *pr = prim_proc(c, y, shift_eval, p);
    sim_sensitive(pr, x, SIM_EDGE_ANY);
    y->area_ge = 0;   /* wires */
    return y;
}

/* ------------------------------------------------------------------- logic */

static void logic_eval(sim_proc *pr)
{
    prim *p = pr->data;
    int64_t v[8];
    for (int i = 0; i < p->n; i++) v[i] = p->in[i]->cur;
    sim_write(p->y, sim_fx_canon(p->fn(v, p->user), p->y->fmt));
}

sim_signal *sim_logic(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fmt,
                      int n, sim_signal *const *in, sim_logic_fn fn, void *user,
                      double area_ge)
{
    if (n > 8) n = 8;
    sim_signal *y = sim_signal_new(c, sc, name, fmt, SIM_KIND_LOGIC);
    prim *p = prim_new(c, y);
    sim_signal **copy = sim_alloc(c, (size_t)(n ? n : 1) * sizeof *copy);
    for (int i = 0; i < n; i++) copy[i] = in[i];
    p->n = n; p->in = copy; p->fn = fn; p->user = user;
    sim_proc *pr = prim_proc(c, y, logic_eval, p);
    for (int i = 0; i < n; i++) sim_sensitive(pr, copy[i], SIM_EDGE_ANY);
    y->area_ge = area_ge;
    return y;
}
