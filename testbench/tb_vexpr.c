/* tb_vexpr.c - the Verilog subset of a logic element's text, evaluated
 * (tb_vexpr.h). A recursive-descent parser into a node array; names
 * (%t_NAME wires, regs and functions) resolved when the text is read
 * whole; evaluation on demand, each wire once per call (a wire may be
 * used before the line that declares it, as in Verilog). Values are 64
 * bits wide at most, with their width and signedness. */
#include "testbench/tb_vexpr.h"
#include "base/base_out.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { N_NUM, N_IN, N_NAME, N_SEL, N_SIGNED, N_CAT, N_REP, N_UN, N_BIN, N_TERN, N_CALL, N_CASE };
#define VX_MAX_NAMES 24

typedef struct vnode {
    int kind, op, a, b, c;      /* operands: node indices (-1: none) */
    int w, hi, lo;              /* N_NUM/N_SEL: width, bits */
    uint64_t k;                 /* N_NUM: the value; N_IN/N_NAME: the input or name */
    int *list, n;               /* N_CAT: items; N_CASE: keys' nodes and values (2 a pair), default in c */
} vnode;

typedef struct vname { char id[32]; int w, sgn, expr, is_fn, arg_w; } vname;

struct tb_vexpr {
    vnode *nd;
    int nn, cap;
    vname nm[VX_MAX_NAMES];
    int nnames, out, nin, in_w[8], out_w;
    const char *p, *text;
    char *err;
    size_t errlen;
    int bad, depth;
};

typedef struct vval { uint64_t v; int w, sgn; } vval;

static uint64_t mask(int w) { return w >= 64 ? UINT64_MAX : (((uint64_t)1 << w) - 1); }
/* v's bits to 64, sign-extended when signed */
static uint64_t ext(vval x)
{
    if (x.w <= 0) return 0;
    uint64_t v = x.v & mask(x.w);
    if (x.sgn && x.w < 64 && (v >> (x.w - 1) & 1)) v |= ~mask(x.w);
    return v;
}

static int fail(tb_vexpr *x, const char *what)
{
    if (!x->bad) snprintf(x->err, x->errlen, "verilog text, at character %d: %s", (int)(x->p - x->text) + 1, what);
    x->bad = 1;
    return -1;
}

static void ws(tb_vexpr *x)
{
    while (*x->p == ' ' || *x->p == '\n' || *x->p == '\t') x->p++;
}
static int eat(tb_vexpr *x, const char *s)
{
    ws(x);
    size_t n = strlen(s);
    if (strncmp(x->p, s, n)) return 0;
    x->p += n;
    return 1;
}
static int need(tb_vexpr *x, const char *s)
{
    if (eat(x, s)) return 0;
    char m[40];
    snprintf(m, sizeof m, "'%s' expected", s);
    return fail(x, m);
}

static int node(tb_vexpr *x, int kind)
{
    if (x->nn == x->cap) {
        x->cap = x->cap ? 2 * x->cap : 64;
        vnode *n = realloc(x->nd, (size_t)x->cap * sizeof *n);
        if (!n) base_out_of_memory();
        x->nd = n;
    }
    vnode *n = &x->nd[x->nn];
    memset(n, 0, sizeof *n);
    n->kind = kind;
    n->a = n->b = n->c = -1;
    return x->nn++;
}

static long whole(tb_vexpr *x)
{
    ws(x);
    if (*x->p < '0' || *x->p > '9') return fail(x, "a number expected");
    long v = 0;
    while (*x->p >= '0' && *x->p <= '9' && v < 100000) v = v * 10 + (*x->p++ - '0');
    return v;
}

/* A name %t_ID: its index (declared or not yet). */
static int name_ref(tb_vexpr *x)
{
    const char *s = x->p;
    size_t n = 0;
    while ((s[n] >= 'a' && s[n] <= 'z') || (s[n] >= 'A' && s[n] <= 'Z') || (s[n] >= '0' && s[n] <= '9') || s[n] == '_') n++;
    if (!n || n >= 32) return fail(x, "a name expected after %t_");
    x->p += n;
    for (int i = 0; i < x->nnames; i++) if (strlen(x->nm[i].id) == n && !strncmp(x->nm[i].id, s, n)) return i;
    if (x->nnames == VX_MAX_NAMES) return fail(x, "too many names");
    vname *m = &x->nm[x->nnames];
    memcpy(m->id, s, n);
    m->id[n] = 0;
    m->expr = -1;
    return x->nnames++;
}

static int expr(tb_vexpr *x);

static int number(tb_vexpr *x)
{
    long w = whole(x);
    int i = node(x, N_NUM);
    if (*x->p != '\'') { x->nd[i].k = (uint64_t)w; x->nd[i].w = 32; x->nd[i].op = 1; return i; }   /* op 1: signed */
    x->p++;
    int base = *x->p == 'h' ? 16 : *x->p == 'b' ? 2 : *x->p == 'd' ? 10 : 0;
    if (!base || w < 1 || w > 64) return fail(x, "a sized number N'h, N'b or N'd of 1..64 bits expected");
    x->p++;
    uint64_t v = 0;
    int any = 0;
    for (;; x->p++, any = 1) {
        int d = *x->p >= '0' && *x->p <= '9' ? *x->p - '0' : *x->p >= 'a' && *x->p <= 'f' ? *x->p - 'a' + 10 : 99;
        if (d >= base) break;
        v = v * (uint64_t)base + (uint64_t)d;
    }
    if (!any) return fail(x, "digits expected");
    x->nd[i].k = v & mask((int)w);
    x->nd[i].w = (int)w;
    return i;
}

static int select(tb_vexpr *x, int base)
{
    if (!eat(x, "[")) return base;
    long hi = whole(x), lo = hi;
    if (eat(x, ":")) lo = whole(x);
    if (need(x, "]") || hi < lo || hi > 63) return fail(x, "a select [H:L] within 64 bits expected");
    int i = node(x, N_SEL);
    x->nd[i].a = base;
    x->nd[i].hi = (int)hi;
    x->nd[i].lo = (int)lo;
    return i;
}

static int primary(tb_vexpr *x)
{
    ws(x);
    if (eat(x, "(")) { int e = expr(x); return need(x, ")") ? -1 : e; }
    if (eat(x, "$signed(")) {
        int i = node(x, N_SIGNED), e = expr(x);
        x->nd[i].a = e;
        return need(x, ")") ? -1 : i;
    }
    if (eat(x, "%t_")) {
        int k = name_ref(x);
        if (k < 0) return -1;
        if (eat(x, "(")) {     /* a function call */
            int i = node(x, N_CALL), e = expr(x);
            x->nd[i].k = (uint64_t)k;
            x->nd[i].a = e;
            return need(x, ")") ? -1 : i;
        }
        int i = node(x, N_NAME);
        x->nd[i].k = (uint64_t)k;
        return select(x, i);
    }
    if (eat(x, "%")) {
        long k = whole(x);
        if (k >= x->nin) return fail(x, "no such input");
        int i = node(x, N_IN);
        x->nd[i].k = (uint64_t)k;
        return select(x, i);
    }
    if (eat(x, "{")) {
        int first = expr(x);
        if (first < 0) return -1;
        if (x->nd[first].kind == N_NUM && eat(x, "{")) {   /* replication N{...} */
            int i = node(x, N_REP), e = expr(x);
            x->nd[i].a = e;
            x->nd[i].hi = (int)x->nd[first].k;
            return need(x, "}") || need(x, "}") ? -1 : i;
        }
        int i = node(x, N_CAT), n = 1;
        int *l = malloc(sizeof *l * 65);
        if (!l) base_out_of_memory();
        l[0] = first;
        while (eat(x, ",") && n < 64) if ((l[n++] = expr(x)) < 0) { free(l); return -1; }
        x->nd[i].list = l;
        x->nd[i].n = n;
        return need(x, "}") ? -1 : i;
    }
    if (*x->p >= '0' && *x->p <= '9') return number(x);
    return fail(x, "an operand expected");
}

static int unary(tb_vexpr *x)
{
    ws(x);
    static const char ops[] = "~!-|&^";
    if (*x->p && strchr(ops, *x->p) && x->p[1] != '=' && !(x->p[0] == '&' && x->p[1] == '&') && !(x->p[0] == '|' && x->p[1] == '|')) {
        if (++x->depth > 100) return fail(x, "nested too deep");
        int i = node(x, N_UN);
        x->nd[i].op = *x->p++;
        int a = unary(x);
        x->depth--;
        x->nd[i].a = a;
        return a < 0 ? -1 : i;
    }
    return primary(x);
}

/* Binary levels, loosest first; each operator a code (two characters
 * where Verilog writes two). */
static const char *const levels[] = { "|| ", "&& ", "| ", "^ ", "& ", "== != ", "<= >= < > ", "<< >> ", "+ - ", "* " };
#define NLEV ((int)(sizeof levels / sizeof levels[0]))

static int binary(tb_vexpr *x, int lev)
{
    if (lev == NLEV) return unary(x);
    int a = binary(x, lev + 1);
    for (;;) {
        if (a < 0) return -1;
        ws(x);
        const char *hit = NULL;
        size_t hn = 0;
        for (const char *o = levels[lev]; *o;) {
            size_t n = strcspn(o, " ");
            /* | is not ||, & not &&, < not <=, << or <<< */
            if (!strncmp(x->p, o, n) && !(n == 1 && (x->p[1] == *o || x->p[1] == '=')) && !(n == 2 && x->p[2] == *o)) { hit = o; hn = n; break; }
            o += n + 1;
        }
        if (!hit) return a;
        x->p += hn;
        int i = node(x, N_BIN);
        x->nd[i].op = hit[0] << 8 | (hn > 1 ? hit[1] : 0);
        x->nd[i].a = a;
        x->nd[i].b = binary(x, lev + 1);
        if (x->nd[i].b < 0) return -1;
        a = i;
    }
}

static int expr(tb_vexpr *x)
{
    if (x->bad) return -1;
    if (++x->depth > 100) return fail(x, "nested too deep");
    int c = binary(x, 0);
    x->depth--;
    if (c < 0 || !eat(x, "?")) return c;
    int i = node(x, N_TERN);
    x->nd[i].c = c;
    x->nd[i].a = expr(x);
    if (x->nd[i].a < 0 || need(x, ":")) return -1;
    x->nd[i].b = expr(x);
    return x->nd[i].b < 0 ? -1 : i;
}

/* [H:0] or nothing (one bit). */
static int range(tb_vexpr *x)
{
    if (!eat(x, "[")) return 1;
    long hi = whole(x);
    if (need(x, ":") || whole(x) != 0 || need(x, "]") || hi > 63) return fail(x, "a range [H:0] within 64 bits expected");
    return (int)hi + 1;
}

/* case (SEL) K: TARGET = EXPR; ... [default: TARGET = EXPR;] endcase:
 * a N_CASE node of SEL (the node given, or parsed) */
static int case_block(tb_vexpr *x, int sel)
{
    if (need(x, "case") || need(x, "(")) return -1;
    int s = sel;
    if (sel >= 0 ? need(x, "i") : (s = expr(x)) < 0) return -1;   /* a function's case is of its argument i */
    if (need(x, ")")) return -1;
    int i = node(x, N_CASE), cap = 64;
    x->nd[i].a = s;
    x->nd[i].list = malloc(sizeof(int) * (size_t)cap);
    if (!x->nd[i].list) base_out_of_memory();
    while (!eat(x, "endcase")) {
        int def = eat(x, "default"), key = def ? -1 : expr(x);
        if ((!def && key < 0) || need(x, ":") || need(x, "%t_") || name_ref(x) < 0 || need(x, "=")) return -1;
        int v = expr(x);
        if (v < 0 || need(x, ";")) return -1;
        if (def) { x->nd[i].c = v; continue; }
        if (x->nd[i].n + 2 > cap) {
            cap *= 2;
            int *l = realloc(x->nd[i].list, sizeof(int) * (size_t)cap);
            if (!l) base_out_of_memory();
            x->nd[i].list = l;
        }
        x->nd[i].list[x->nd[i].n++] = key;
        x->nd[i].list[x->nd[i].n++] = v;
    }
    return i;
}

static int statement(tb_vexpr *x)
{
    if (eat(x, "assign")) {
        if (need(x, "%y") || need(x, "=")) return -1;
        if ((x->out = expr(x)) < 0) return -1;
        return need(x, ";");
    }
    int fn = eat(x, "function"), reg = !fn && eat(x, "reg");
    if (!fn && !reg && !eat(x, "wire")) return fail(x, "wire, reg, function or assign expected");
    int w = range(x);
    if (w < 0 || need(x, "%t_")) return -1;
    int k = name_ref(x);
    if (k < 0) return -1;
    vname *m = &x->nm[k];
    if (m->w) return fail(x, "a name declared twice");
    m->w = w;
    if (fn) {            /* function [W:0] F; input [N:0] i; case (i) ... endcase endfunction */
        m->is_fn = 1;
        if (need(x, ";") || need(x, "input")) return -1;
        m->arg_w = range(x);
        if (m->arg_w < 0 || need(x, "i") || need(x, ";")) return -1;
        int arg = node(x, N_IN);
        x->nd[arg].k = 8;           /* the call's argument */
        if ((m->expr = case_block(x, arg)) < 0) return -1;
        return need(x, "endfunction");
    }
    if (reg) {           /* reg [W:0] R; always @* begin case (...) ... endcase end */
        if (need(x, ";") || need(x, "always") || need(x, "@*") || need(x, "begin")) return -1;
        if ((m->expr = case_block(x, -1)) < 0) return -1;
        return need(x, "end");
    }
    if (need(x, "=") || (m->expr = expr(x)) < 0) return -1;
    return need(x, ";");
}

/* ------------------------------------------------------------ evaluation */

typedef struct vctx { const tb_vexpr *x; const int64_t *in; vval wire[VX_MAX_NAMES]; unsigned done, busy; vval arg; } vctx;

static vval ev(vctx *c, int i);

static vval name_val(vctx *c, int k)
{
    const vname *m = &c->x->nm[k];
    if (c->done >> k & 1) return c->wire[k];
    vval r = { 0, m->w, 0 };
    if (c->busy >> k & 1) return r;     /* a loop: 0 (the writer's check refuses it) */
    c->busy |= 1u << k;
    r.v = ev(c, m->expr).v & mask(m->w);
    c->wire[k] = r;
    c->done |= 1u << k;
    return r;
}

static vval bin(int op, vval a, vval b)
{
    int w = a.w > b.w ? a.w : b.w, sg = a.sgn && b.sgn;
    a.sgn = b.sgn = sg;
    uint64_t x = ext(a), y = ext(b);
    vval r = { 0, w, sg };
    int64_t sx = (int64_t)x, sy = (int64_t)y;
    uint64_t mx = x & mask(w), my = y & mask(w);
    vval one = { 0, 1, 0 };
    switch (op) {
    case '+' << 8: r.v = x + y; break;
    case '-' << 8: r.v = x - y; break;
    case '*' << 8: r.v = x * y; break;
    case '&' << 8: r.v = x & y; break;
    case '|' << 8: r.v = x | y; break;
    case '^' << 8: r.v = x ^ y; break;
    case ('<' << 8 | '<'): r = a; r.v = (b.v & mask(b.w)) >= 64 ? 0 : x << (b.v & mask(b.w)); break;
    case ('>' << 8 | '>'): r = a; r.v = (b.v & mask(b.w)) >= 64 ? 0 : (x & mask(a.w)) >> (b.v & mask(b.w)); break;
    case '<' << 8: one.v = sg ? sx < sy : mx < my; return one;
    case '>' << 8: one.v = sg ? sx > sy : mx > my; return one;
    case ('<' << 8 | '='): one.v = sg ? sx <= sy : mx <= my; return one;
    case ('>' << 8 | '='): one.v = sg ? sx >= sy : mx >= my; return one;
    case ('=' << 8 | '='): one.v = mx == my; return one;
    case ('!' << 8 | '='): one.v = mx != my; return one;
    case ('&' << 8 | '&'): one.v = (a.v & mask(a.w)) && (b.v & mask(b.w)); return one;
    case ('|' << 8 | '|'): one.v = (a.v & mask(a.w)) || (b.v & mask(b.w)); return one;
    default: break;
    }
    return r;
}

static vval ev(vctx *c, int i)
{
    const vnode *n = &c->x->nd[i];
    vval r = { 0, 1, 0 }, a;
    switch (n->kind) {
    case N_NUM: r.v = n->k; r.w = n->w; r.sgn = n->op; return r;
    case N_IN:
        if (n->k == 8) return c->arg;
        r.w = c->x->in_w[n->k];
        r.v = (uint64_t)c->in[n->k] & mask(r.w);
        return r;
    case N_NAME: return name_val(c, (int)n->k);
    case N_SEL:
        a = ev(c, n->a);
        r.w = n->hi - n->lo + 1;
        r.v = (a.v & mask(a.w)) >> n->lo & mask(r.w);
        return r;
    case N_SIGNED: r = ev(c, n->a); r.sgn = 1; return r;
    case N_CAT:
        r.w = 0;
        for (int j = 0; j < n->n; j++) {
            a = ev(c, n->list[j]);
            r.v = (a.w >= 64 ? 0 : r.v << a.w) | (a.v & mask(a.w));
            r.w += a.w;
        }
        if (r.w > 64) r.w = 64;
        return r;
    case N_REP:
        a = ev(c, n->a);
        r.w = 0;
        for (int j = 0; j < n->hi && r.w < 64; j++) { r.v = (a.w >= 64 ? 0 : r.v << a.w) | (a.v & mask(a.w)); r.w += a.w; }
        if (r.w > 64) r.w = 64;
        return r;
    case N_UN:
        a = ev(c, n->a);
        switch (n->op) {
        case '~': a.v = ~a.v & mask(a.w); return a;
        case '-': a.v = -ext(a); return a;
        case '!': r.v = !(a.v & mask(a.w)); return r;
        case '|': r.v = (a.v & mask(a.w)) != 0; return r;
        case '&': r.v = (a.v & mask(a.w)) == mask(a.w); return r;
        default: r.v = (uint64_t)__builtin_parityll(a.v & mask(a.w)); return r;
        }
    case N_BIN: return bin(n->op, ev(c, n->a), ev(c, n->b));
    case N_TERN: {
        vval t = ev(c, n->c), x = ev(c, (t.v & mask(t.w)) ? n->a : n->b), o = ev(c, (t.v & mask(t.w)) ? n->b : n->a);
        x.sgn = x.sgn && o.sgn;
        x.v = ext(x);
        if (o.w > x.w) x.w = o.w;
        return x;
    }
    case N_CALL: {
        const vname *m = &c->x->nm[n->k];
        vval keep = c->arg;
        c->arg = ev(c, n->a);
        c->arg.v &= mask(m->arg_w);
        c->arg.w = m->arg_w;
        c->arg.sgn = 0;
        r = ev(c, m->expr);
        r.v &= mask(m->w);
        r.w = m->w;
        r.sgn = 0;
        c->arg = keep;
        return r;
    }
    case N_CASE: {
        a = ev(c, n->a);
        for (int j = 0; j + 1 < n->n; j += 2) {
            vval k = ev(c, n->list[j]);
            if (bin('=' << 8 | '=', a, k).v) return ev(c, n->list[j + 1]);
        }
        if (n->c >= 0) return ev(c, n->c);
        r.w = 1;
        return r;
    }
    default: return r;
    }
}

int64_t tb_vexpr_fn(const int64_t *in, void *user)
{
    vctx c;
    memset(&c, 0, sizeof c);
    c.x = user;
    c.in = in;
    return (int64_t)(ev(&c, c.x->out).v & mask(c.x->out_w));
}

tb_vexpr *tb_vexpr_compile(const char *text, int nin, const int *in_width, int out_width, char *err, size_t errlen)
{
    tb_vexpr *x = calloc(1, sizeof *x);
    if (!x) base_out_of_memory();
    x->text = x->p = text;
    x->err = err;
    x->errlen = errlen;
    x->out = -1;
    x->nin = nin > 8 ? 8 : nin;
    for (int i = 0; i < x->nin; i++) x->in_w[i] = in_width[i];
    x->out_w = out_width;
    for (ws(x); *x->p && !x->bad; ws(x)) statement(x);
    if (!x->bad && x->out < 0) fail(x, "no assign %y = ...;");
    for (int k = 0; k < x->nnames && !x->bad; k++)
        if (!x->nm[k].w) { char m[60]; snprintf(m, sizeof m, "%%t_%s is not declared", x->nm[k].id); fail(x, m); }
    for (int i = 0; i < x->nn && !x->bad; i++)
        if (x->nd[i].kind == N_CALL && !x->nm[x->nd[i].k].is_fn) fail(x, "a call of a name that is no function");
    if (x->bad) { tb_vexpr_free(x); return NULL; }
    return x;
}

void tb_vexpr_free(tb_vexpr *p)
{
    if (!p) return;
    for (int i = 0; i < p->nn; i++) free(p->nd[i].list);
    free(p->nd);
    free(p);
}
