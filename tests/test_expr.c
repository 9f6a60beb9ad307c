/* test_expr.c - the ideal function's expressions (testbench/tb_expr.h):
 * each evaluated in double against the same formula written in C over
 * random inputs; the exact evaluation against sim_dy arithmetic done by
 * hand; which expressions are exact; precedence and associativity; and
 * malformed expressions refused with the column of the mistake. */
#include "tests/tst.h"
#include "testbench/tb_expr.h"
#include "vectors/vectors.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const vars[] = { "a", "b", "c", "d", "t", "x_1" };

static tb_expr *compile(const char *text)
{
    tb_expr *e = NULL;
    char err[300];
    if (tb_expr_parse(text, 6, vars, &e, err, sizeof err)) {
        TST_CHECK(0, "%s: %s", text, err);
        return NULL;
    }
    return e;
}

typedef double (*ref_fn)(const double *v);
static double r_horner(const double *v) { return ((v[0] * v[4] + v[1]) * v[4] + v[2]) * v[4] + v[3]; }
static double r_prec(const double *v) { return v[0] + v[1] * v[2] - v[3] / v[4]; }
static double r_left(const double *v) { return v[0] - v[1] - v[2]; }
static double r_div(const double *v) { return v[0] / v[1] / v[2]; }
static double r_neg(const double *v) { return -v[0] * -(v[1] - 2.5e-3); }
static double r_fns(const double *v) { return sqrt(fabs(v[0])) + fmin(v[1], v[2]) * fmax(v[3], -v[5]); }
static double r_num(const double *v) { return 1e-3 * v[0] + .5 + 2E2 * v[5]; }

static void t_double_against_c(void)
{
    static const struct { const char *text; ref_fn f; } cases[] = {
        { "((a * t + b) * t + c) * t + d", r_horner }, { "a + b*c - d/t", r_prec }, { "a - b - c", r_left },
        { "a / b / c", r_div }, { "-a * -(b - 2.5e-3)", r_neg },
        { "sqrt(abs(a)) + min(b, c) * max( d , -x_1 )", r_fns }, { "1e-3*a + .5 + 2E2 * x_1", r_num } };
    vec_rng r = { 7 };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tb_expr *e = compile(cases[k].text);
        if (!e) continue;
        for (int i = 0; i < 1000; i++) {
            double v[6];
            for (int j = 0; j < 6; j++) v[j] = vec_rng_range(&r, -4, 4);
            double got = tb_expr_eval(e, v), want = cases[k].f(v);
            if (!(got == want || (isnan(got) && isnan(want)))) {
                TST_CHECK(0, "%s at %g %g ...: %.17g, C gives %.17g", cases[k].text, v[0], v[1], got, want);
                break;
            }
        }
        tb_expr_free(e);
    }
}

static void t_exact(void)
{
    /* exact where the value is a dyadic rational of the inputs */
    static const struct { const char *text; int exact; } cases[] = {
        { "a * t + 0.375", 1 }, { "a * 0.1", 0 }, { "a / 2", 0 }, { "sqrt(a)", 0 }, { "min(a, b) - abs(c)", 1 },
        { "a * 1.5e-3", 0 }, { "a * 6.25e-2", 1 }, { "a * 3e2", 1 } };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tb_expr *e = compile(cases[k].text);
        if (!e) continue;
        TST_CHECK(tb_expr_is_exact(e) == cases[k].exact, "%s: exact %d", cases[k].text, tb_expr_is_exact(e));
        tb_expr_free(e);
    }
    /* a t + 0.375 at a = 3 * 2^-40, t = 1 - 2^-52: the exact value, which a
     * double cannot hold, by sim_dy's own operations */
    tb_expr *e = compile("a * t + 0.375");
    if (!e) return;
    sim_dy x[6], got, want, k, p;
    for (int j = 0; j < 6; j++) sim_dy_int(&x[j], 0, 0);
    sim_dy_int(&x[0], 3, 40);
    sim_dy_int(&x[4], ((int64_t)1 << 52) - 1, 52);
    TST_EQ_INT(tb_expr_exact(e, x, &got), 0);
    sim_dy_int(&k, 3, 3);
    sim_dy_mul(&p, &x[0], &x[4]);
    sim_dy_add(&want, &p, &k);
    TST_EQ_INT(sim_dy_cmp(&got, &want), 0);
    double xd[6] = { ldexp(3, -40), 0, 0, 0, 1 - ldexp(1, -52), 0 };
    TST_NEAR(tb_expr_eval(e, xd), sim_dy_to_double(&want), 1e-16);
    tb_expr_free(e);
    /* min and max pick exactly */
    e = compile("max(a, b) - min(a, b)");
    sim_dy_int(&x[0], -5, 3);
    sim_dy_int(&x[1], 7, 5);
    sim_dy_int(&want, 27, 5);    /* 7/32 + 5/8 */
    TST_CHECK(e && !tb_expr_exact(e, x, &got) && !sim_dy_cmp(&got, &want), "max - min");
    if (e) tb_expr_free(e);
    e = compile("a / b");
    TST_CHECK(e && tb_expr_exact(e, x, &got) == -1, "a division is not exact");
    if (e) tb_expr_free(e);
}

static void t_malformed(void)
{
    static const struct { const char *text, *msg; } cases[] = {
        { "a +", "column 4: the expression ends too soon" },
        { "a + * b", "column 5: '*' where a number, an input or '(' belongs" },
        { "(a + b", "column 7: ')' expected" },
        { "a + b)", "column 6: ')' without its '('" },
        { "a b", "column 3: 'b' where an operator belongs" },
        { "q * 2", "column 1: q is not an input" },
        { "cos(a)", "column 1: cos(: no such function (sqrt, abs, min, max)" },
        { "min(a)", "column 6: ',' expected in min() (it takes 2 arguments)" },
        { "sqrt(a, b)", "column 7: ')' expected in sqrt() (it takes 1 argument)" },
        { "", "column 1: the expression ends too soon" },
        { "a + $", "column 5: '$' where a number, an input or '(' belongs" } };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tb_expr *e = NULL;
        char err[300] = "";
        TST_CHECK(tb_expr_parse(cases[k].text, 6, vars, &e, err, sizeof err) == -1 && !e, "%s: accepted", cases[k].text);
        TST_EQ_STR(err, cases[k].msg);
    }
    /* nesting deeper than the parser recurses: refused, not a crash */
    char deep[400];
    memset(deep, '(', 300);
    strcpy(deep + 300, "a");
    tb_expr *e = NULL;
    char err[300];
    TST_CHECK(tb_expr_parse(deep, 6, vars, &e, err, sizeof err) == -1 && strstr(err, "nested deeper than 64"), "%s", err);
}

int main(void)
{
    TST_RUN(t_double_against_c);
    TST_RUN(t_exact);
    TST_RUN(t_malformed);
    TST_EXIT();
}
