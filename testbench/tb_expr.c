/* tb_expr.c - expressions of a datapath file's ideal function (tb_expr.h):
 * a recursive-descent parser into a postfix program, and its two
 * evaluators (double, exact). */
#include "testbench/tb_expr.h"
#include "base/base_out.h"
#include "base/base_strtod.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum { X_NUM, X_VAR, X_NEG, X_ADD, X_SUB, X_MUL, X_DIV, X_SQRT, X_ABS, X_MIN, X_MAX } x_op;

typedef struct x_ins { x_op op; int var; double k; } x_ins;

#define X_MAX_INS 512    /* instructions of one expression */
#define X_MAX_DEPTH 64   /* nesting (parentheses, calls): the parser's recursion */

struct tb_expr {
    int n, exact, stack;    /* instructions, tb_expr_is_exact, largest stack */
    x_ins ins[X_MAX_INS];
};

typedef struct x_parser {
    const char *s, *p;
    int nvar;
    const char *const *vars;
    tb_expr *e;
    int depth, sp;
    char *err;
    size_t errlen;
} x_parser;

static int x_bad(x_parser *q, const char *fmt, ...)
{
    char msg[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(q->err, q->errlen, "column %d: %s", (int)(q->p - q->s) + 1, msg);
    return -1;
}

static void skip(x_parser *q) { while (*q->p == ' ' || *q->p == '\t') q->p++; }

static int emit(x_parser *q, x_op op, int var, double k)
{
    if (q->e->n == X_MAX_INS) return x_bad(q, "more than %d operations", X_MAX_INS);
    x_ins *i = &q->e->ins[q->e->n++];
    i->op = op;
    i->var = var;
    i->k = k;
    /* the stack a postfix program needs: operands push, binaries pop one */
    int binary = op == X_ADD || op == X_SUB || op == X_MUL || op == X_DIV || op == X_MIN || op == X_MAX;
    q->sp += op == X_NUM || op == X_VAR ? 1 : binary ? -1 : 0;
    if (q->sp > q->e->stack) q->e->stack = q->sp;
    return 0;
}

/* 1 if the decimal text [a, b) is a dyadic rational (m * 2^-k): its value
 * N * 10^-n with 5^n dividing N. Long mantissas count as not exact. */
static int dyadic_text(const char *a, const char *b)
{
    unsigned long long N = 0;
    int digits = 0, n = 0, frac = 0;
    const char *p = a;
    for (; p < b && *p != 'e' && *p != 'E'; p++) {
        if (*p == '.') { frac = 1; continue; }
        if (N == 0 && *p == '0') { n += frac; continue; }
        if (++digits > 18) return 0;
        N = N * 10 + (unsigned long long)(*p - '0');
        n += frac;
    }
    if (p < b) n -= atoi(p + 1);
    if (N == 0) return 1;
    for (; n > 0 && N % 5 == 0; n--) N /= 5;
    return n <= 0;
}

static int parse_sum(x_parser *q);

static int parse_primary(x_parser *q)
{
    skip(q);
    if (++q->depth > X_MAX_DEPTH) return x_bad(q, "nested deeper than %d", X_MAX_DEPTH);
    int rc = 0;
    const char *t = q->p;
    if ((*t >= '0' && *t <= '9') || *t == '.') {
        char *end;
        double v = base_strtod(t, &end);
        if (end == t || !isfinite(v)) return x_bad(q, "a number expected");
        if (!dyadic_text(t, end)) q->e->exact = 0;
        q->p = end;
        rc = emit(q, X_NUM, 0, v);
    } else if ((*t >= 'a' && *t <= 'z') || (*t >= 'A' && *t <= 'Z') || *t == '_') {
        const char *b = t;
        while ((*b >= 'a' && *b <= 'z') || (*b >= 'A' && *b <= 'Z') || (*b >= '0' && *b <= '9') || *b == '_') b++;
        size_t len = (size_t)(b - t);
        q->p = b;
        skip(q);
        if (*q->p == '(') {
            static const struct { const char *name; x_op op; int args; } fn[] = {
                { "sqrt", X_SQRT, 1 }, { "abs", X_ABS, 1 }, { "min", X_MIN, 2 }, { "max", X_MAX, 2 } };
            int f = -1;
            for (int i = 0; i < 4; i++) if (strlen(fn[i].name) == len && !strncmp(fn[i].name, t, len)) f = i;
            if (f < 0) { q->p = t; return x_bad(q, "%.*s(: no such function (sqrt, abs, min, max)", (int)len, t); }
            q->p++;
            for (int a = 0; a < fn[f].args; a++) {
                if (parse_sum(q)) return -1;
                skip(q);
                char want = a + 1 < fn[f].args ? ',' : ')';
                if (*q->p != want)
                    return x_bad(q, "'%c' expected in %s() (it takes %d argument%s)", want, fn[f].name, fn[f].args,
                                 fn[f].args > 1 ? "s" : "");
                q->p++;
            }
            if (fn[f].op == X_SQRT) q->e->exact = 0;
            rc = emit(q, fn[f].op, 0, 0);
        } else {
            int v = -1;
            for (int i = 0; i < q->nvar; i++) if (strlen(q->vars[i]) == len && !strncmp(q->vars[i], t, len)) v = i;
            if (v < 0) { q->p = t; return x_bad(q, "%.*s is not an input", (int)len, t); }
            rc = emit(q, X_VAR, v, 0);
        }
    } else if (*t == '(') {
        q->p++;
        if (parse_sum(q)) return -1;
        skip(q);
        if (*q->p != ')') return x_bad(q, "')' expected");
        q->p++;
    } else if (*t == '-' || *t == '+') {
        q->p++;
        if (parse_primary(q)) return -1;
        if (*t == '-') rc = emit(q, X_NEG, 0, 0);
    } else return x_bad(q, *t ? "'%c' where a number, an input or '(' belongs" : "the expression ends too soon", *t);
    q->depth--;
    return rc;
}

static int parse_product(x_parser *q)
{
    if (parse_primary(q)) return -1;
    for (;;) {
        skip(q);
        char c = *q->p;
        if (c != '*' && c != '/') return 0;
        q->p++;
        if (parse_primary(q) || emit(q, c == '*' ? X_MUL : X_DIV, 0, 0)) return -1;
        if (c == '/') q->e->exact = 0;
    }
}

static int parse_sum(x_parser *q)
{
    if (parse_product(q)) return -1;
    for (;;) {
        skip(q);
        char c = *q->p;
        if (c != '+' && c != '-') return 0;
        q->p++;
        if (parse_product(q) || emit(q, c == '+' ? X_ADD : X_SUB, 0, 0)) return -1;
    }
}

int tb_expr_parse(const char *text, int nvar, const char *const *vars, tb_expr **out, char *err, size_t errlen)
{
    tb_expr *e = calloc(1, sizeof *e);
    if (!e) base_out_of_memory();
    e->exact = 1;
    x_parser q = { text, text, nvar, vars, e, 0, 0, err, errlen };
    int rc = parse_sum(&q);
    if (!rc) {
        skip(&q);
        if (*q.p) rc = x_bad(&q, *q.p == ')' ? "')' without its '('" : "'%c' where an operator belongs", *q.p);
    }
    if (rc) { free(e); return -1; }
    *out = e;
    return 0;
}

void tb_expr_free(tb_expr *e) { free(e); }
int tb_expr_is_exact(const tb_expr *e) { return e->exact; }

double tb_expr_eval(const tb_expr *e, const double *x)
{
    double st[X_MAX_INS];
    int sp = 0;
    for (int i = 0; i < e->n; i++) {
        const x_ins *in = &e->ins[i];
        double b = sp > 0 ? st[sp - 1] : 0;
        switch (in->op) {
        case X_NUM: st[sp++] = in->k; break;
        case X_VAR: st[sp++] = x[in->var]; break;
        case X_NEG: st[sp - 1] = -b; break;
        case X_SQRT: st[sp - 1] = sqrt(b); break;
        case X_ABS: st[sp - 1] = fabs(b); break;
        case X_ADD: st[sp - 2] += b; sp--; break;
        case X_SUB: st[sp - 2] -= b; sp--; break;
        case X_MUL: st[sp - 2] *= b; sp--; break;
        case X_DIV: st[sp - 2] /= b; sp--; break;
        case X_MIN: st[sp - 2] = fmin(st[sp - 2], b); sp--; break;
        case X_MAX: st[sp - 2] = fmax(st[sp - 2], b); sp--; break;
        }
    }
    return st[0];
}

int tb_expr_exact(const tb_expr *e, const sim_dy *x, sim_dy *out)
{
    if (!e->exact) return -1;
    sim_dy *st = malloc((size_t)(e->stack + 1) * sizeof *st), zero;
    if (!st) base_out_of_memory();
    sim_dy_int(&zero, 0, 0);
    int sp = 0;
    for (int i = 0; i < e->n; i++) {
        const x_ins *in = &e->ins[i];
        sim_dy *a = sp > 1 ? &st[sp - 2] : NULL, *b = sp > 0 ? &st[sp - 1] : NULL, r;
        switch (in->op) {
        case X_NUM: sim_dy_double(&st[sp++], in->k); break;
        case X_VAR: st[sp++] = x[in->var]; break;
        case X_NEG: sim_dy_sub(&r, &zero, b); *b = r; break;
        case X_ABS: sim_dy_abs(&r, b); *b = r; break;
        case X_ADD: sim_dy_add(&r, a, b); *a = r; sp--; break;
        case X_SUB: sim_dy_sub(&r, a, b); *a = r; sp--; break;
        case X_MUL: sim_dy_mul(&r, a, b); *a = r; sp--; break;
        case X_MIN: case X_MAX:
            if (a->ovf || b->ovf) a->ovf = 1;
            else if ((sim_dy_cmp(a, b) > 0) == (in->op == X_MIN)) *a = *b;
            sp--;
            break;
        default: free(st); return -1;
        }
        if (st[sp - 1].ovf) { free(st); return -1; }
    }
    *out = st[0];
    free(st);
    return 0;
}
