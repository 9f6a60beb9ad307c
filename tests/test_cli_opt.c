/* test_cli_opt.c - the option parser every verb uses (testbench/cli/cli_opt.h):
 * values, missing and bad values, repeats, both spellings of a value, and
 * that every verb's --help lists exactly the options of its tables. */
#include "tests/tst.h"
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include <limits.h>
#include <stddef.h>
#include <unistd.h>

/* ------------------------------------------------ capturing stdout/stderr */

static char cap_text[65536];

/* Run fn(arg) with file descriptor fd going to a temporary file; the text
 * written is left in cap_text. Returns fn's result. */
static int capture(int fd, int (*fn)(void *), void *arg)
{
    FILE *tmp = tmpfile();
    cap_text[0] = 0;
    if (!tmp) return -100;
    fflush(stdout);
    fflush(stderr);
    int saved = dup(fd);
    dup2(fileno(tmp), fd);
    int r = fn(arg);
    fflush(stdout);
    fflush(stderr);
    dup2(saved, fd);
    close(saved);
    rewind(tmp);
    size_t n = fread(cap_text, 1, sizeof cap_text - 1, tmp);
    cap_text[n] = 0;
    fclose(tmp);
    return r;
}

/* ------------------------------------------------------ a table to parse */

typedef struct t_args {
    int flag, n, calls;
    long big;
    uint64_t seed;
    double r, pos;
    const char *s, *o, *maybe, *args[8];
    int nargs, maybe_calls;
    char joined[200];
} t_args;

static int t_append(void *base, const char *opt, const char *v)
{
    t_args *a = base;
    (void)opt;
    a->calls++;
    strncat(a->joined, v, sizeof a->joined - strlen(a->joined) - 2);
    strcat(a->joined, ";");
    return 0;
}

static int t_maybe(void *base, const char *opt, const char *v)
{
    t_args *a = base;
    (void)opt;
    a->maybe_calls++;
    a->maybe = v;
    return 0;
}

static int t_refuse(void *base, const char *opt, const char *v)
{
    (void)base, (void)opt, (void)v;
    return CLI_OPT_UNKNOWN;
}

static int t_pos(void *base, const char *arg)
{
    t_args *a = base;
    if (a->nargs == 8) return cli_usage_error("t: too many");
    a->args[a->nargs++] = arg;
    return 0;
}

static const cli_opt t_tab[] = {
    { "--flag", "-f", CLI_OPT_FLAG, offsetof(t_args, flag), 0, 0, NULL, NULL, NULL, 0, "  --flag, -f   a flag\n" },
    { "--n", NULL, CLI_OPT_INT, offsetof(t_args, n), 0, 10, NULL, NULL, NULL, 0, "  --n N        0..10\n" },
    { "--big", NULL, CLI_OPT_LONG, offsetof(t_args, big), -5, (double)LONG_MAX, "an item", "%s wants an item", NULL, 0,
      "  --big N      -5..\n" },
    { "--seed", NULL, CLI_OPT_U64, offsetof(t_args, seed), 0, 0, NULL, NULL, NULL, 0, "  --seed S\n" },
    { "--r", NULL, CLI_OPT_REAL, offsetof(t_args, r), 0, 1, NULL, NULL, NULL, 0, "  --r X        0..1\n" },
    { "--pos", NULL, CLI_OPT_REAL, offsetof(t_args, pos), 0, 1e300, "a positive number", NULL, NULL, CLI_OPT_GT_LO,
      "  --pos X\n" },
    { "--s", NULL, CLI_OPT_STR, offsetof(t_args, s), 0, 0, NULL, NULL, NULL, 0, "  --s TEXT\n" },
    { "-o", NULL, CLI_OPT_STR, offsetof(t_args, o), 0, 0, NULL, "-o needs a folder", NULL, CLI_OPT_NONEMPTY, "  -o DIR\n" },
    { "--add", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, t_append, 0, "  --add V      (repeatable)\n" },
    { "--maybe", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, t_maybe, CLI_OPT_MAYBE, "  --maybe [K=V]\n" },
    { "--refuse", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, t_refuse, 0, "" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

/* A second table whose --n the first one's hides. */
static const cli_opt t_tab2[] = {
    { "--n", NULL, CLI_OPT_FLAG, 0, 0, 0, NULL, NULL, NULL, 0, "  --n (hidden)\n" },
    { "--late", NULL, CLI_OPT_FLAG, 0, 0, 0, NULL, NULL, NULL, 0, "  --late\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

static const cli_optspec t_spec = {
    "t", { t_tab, t_tab2 }, t_pos, 1, "t: unknown option '%s'", "usage: t\n", "end\n"
};

typedef struct t_call { int argc; char **argv; t_args a; int late; } t_call;

static int t_parse(void *p)
{
    t_call *c = p;
    memset(&c->a, 0, sizeof c->a);
    c->late = 0;
    void *base[] = { &c->a, &c->late };
    return cli_opt_parse(&t_spec, base, c->argc, c->argv, 1);
}

/* Parse "t" + words (at most 15; NULL-terminated) with stderr captured. */
#define PARSE(c, ...) parse_words(&(c), (const char *[]){ "t", __VA_ARGS__, NULL })
static int parse_words(t_call *c, const char **w)
{
    static char *argv[16];
    int n = 0;
    while (w[n] && n < 15) { argv[n] = (char *)w[n]; n++; }
    argv[n] = NULL;
    c->argc = n;
    c->argv = argv;
    return capture(2, t_parse, c);
}

static void values_both_spellings(void)
{
    t_call c, d;
    TST_EQ_INT(PARSE(c, "--n", "7", "--r", "0.25", "--s", "x y", "--seed", "18446744073709551615", "-f"), 0);
    TST_EQ_INT(PARSE(d, "--n=7", "--r=0.25", "--s=x y", "--seed=18446744073709551615", "--flag"), 0);
    TST_EQ_STR(cap_text, "");
    TST_EQ_INT(c.a.n, 7); TST_EQ_INT(d.a.n, 7);
    TST_NEAR(c.a.r, 0.25, 0); TST_NEAR(d.a.r, 0.25, 0);
    TST_EQ_STR(c.a.s, "x y"); TST_EQ_STR(d.a.s, "x y");
    TST_CHECK(c.a.seed == UINT64_MAX && d.a.seed == UINT64_MAX, "seed");
    TST_EQ_INT(c.a.flag, 1); TST_EQ_INT(d.a.flag, 1);
    /* a value may start with '-' when written apart; -5 is within --big's range */
    TST_EQ_INT(PARSE(c, "--s", "-x", "--big", "-5"), 0);
    TST_EQ_STR(c.a.s, "-x");
    TST_EQ_INT(c.a.big, -5);
    TST_EQ_INT(PARSE(c, "--big", "9223372036854775807"), 0);
    TST_CHECK(c.a.big == LONG_MAX, "LONG_MAX is within a range up to (double)LONG_MAX");
    TST_EQ_INT(PARSE(c, "--s="), 0);
    TST_EQ_STR(c.a.s, "");
}

static void unknown_and_missing(void)
{
    t_call c;
    TST_EQ_INT(PARSE(c, "--nope"), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: t: unknown option '--nope'\n");
    TST_EQ_INT(PARSE(c, "--flag=1"), CLI_USAGE);        /* a flag takes no value */
    TST_EQ_STR(cap_text, "shadesim: t: unknown option '--flag=1'\n");
    TST_EQ_INT(PARSE(c, "--nn", "1"), CLI_USAGE);       /* no prefixes */
    TST_EQ_STR(cap_text, "shadesim: t: unknown option '--nn' (did you mean '--n'?)\n");
    TST_EQ_INT(PARSE(c, "--refuse", "v"), CLI_USAGE);   /* a call that says "not mine" */
    TST_EQ_STR(cap_text, "shadesim: t: unknown option '--refuse'\n");
    TST_EQ_INT(PARSE(c, "--n"), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: --n needs a value\n");
    TST_EQ_INT(PARSE(c, "--big"), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: --big wants an item\n");
    TST_EQ_INT(PARSE(c, "-o", ""), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: -o needs a folder\n");
    TST_EQ_INT(PARSE(c, "-o="), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: -o needs a folder\n");
}

static void bad_numbers(void)
{
    static const char *const junk_int[] = { "11", "-1", "5x", " 5", "+5", "0x5", "1e1", "", "99999999999999999999" };
    for (size_t k = 0; k < sizeof junk_int / sizeof junk_int[0]; k++) {
        t_call c;
        char want[200];
        TST_EQ_INT(PARSE(c, "--n", junk_int[k]), CLI_USAGE);
        snprintf(want, sizeof want, "shadesim: --n %s: expected a whole number 0..10\n", junk_int[k]);
        TST_EQ_STR(cap_text, want);
        TST_EQ_INT(c.a.n, 0);
    }
    static const char *const junk_real[] = { "1.5", "-0.1", "nan", "inf", "1e999", ".", "0x1p-2", "1,5", "1e" };
    for (size_t k = 0; k < sizeof junk_real / sizeof junk_real[0]; k++) {
        t_call c;
        char want[200];
        TST_EQ_INT(PARSE(c, "--r", junk_real[k]), CLI_USAGE);
        snprintf(want, sizeof want, "shadesim: --r %s: expected a number 0..1\n", junk_real[k]);
        TST_EQ_STR(cap_text, want);
    }
    t_call c;
    TST_EQ_INT(PARSE(c, "--pos", "0"), CLI_USAGE);      /* > lo, not >= */
    TST_EQ_STR(cap_text, "shadesim: --pos 0: expected a positive number\n");
    TST_EQ_INT(PARSE(c, "--pos", "1e-3"), 0);
    TST_NEAR(c.a.pos, 1e-3, 0);
    TST_EQ_INT(PARSE(c, "--seed", "18446744073709551616"), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: --seed 18446744073709551616: expected a whole number 0..18446744073709551615\n");
    TST_EQ_INT(PARSE(c, "--n", "a\x01"), CLI_USAGE);   /* a control byte goes out escaped */
    TST_EQ_STR(cap_text, "shadesim: --n a\\x01: expected a whole number 0..10\n");
}

static void repeats_and_order(void)
{
    t_call c;
    /* a value option given twice: the last wins; a call sees every one */
    TST_EQ_INT(PARSE(c, "--n", "1", "--add", "a", "--n=9", "--add=b", "--add", "c"), 0);
    TST_EQ_INT(c.a.n, 9);
    TST_EQ_INT(c.a.calls, 3);
    TST_EQ_STR(c.a.joined, "a;b;c;");
    /* arguments that are not options, in order; "-" is one here */
    TST_EQ_INT(PARSE(c, "x", "--flag", "-", "y"), 0);
    TST_EQ_INT(c.a.nargs, 3);
    TST_EQ_STR(c.a.args[0], "x"); TST_EQ_STR(c.a.args[1], "-"); TST_EQ_STR(c.a.args[2], "y");
    /* the first table's --n hides the second's; the second's own options work */
    TST_EQ_INT(PARSE(c, "--n", "3", "--late"), 0);
    TST_EQ_INT(c.a.n, 3);
    TST_EQ_INT(c.late, 1);
    /* an optional value: taken when written with '=' or when the next
     * argument looks like K=V; else the call gets none */
    TST_EQ_INT(PARSE(c, "--maybe", "k=v"), 0);
    TST_EQ_STR(c.a.maybe, "k=v");
    TST_EQ_INT(c.a.nargs, 0);
    TST_EQ_INT(PARSE(c, "--maybe", "file"), 0);
    TST_CHECK(c.a.maybe == NULL && c.a.maybe_calls == 1, "no value");
    TST_EQ_INT(c.a.nargs, 1);
    TST_EQ_INT(PARSE(c, "--maybe", "-x=1"), CLI_USAGE);
    TST_EQ_STR(cap_text, "shadesim: t: unknown option '-x=1'\n");
    TST_EQ_INT(PARSE(c, "--maybe=a"), 0);
    TST_EQ_STR(c.a.maybe, "a");
}

static int t_help(void *p) { return cli_opt_help(p); }

static void help_from_the_tables(void)
{
    TST_EQ_INT(capture(1, t_help, (void *)&t_spec), CLI_OK);
    /* t_tab2's --n is hidden by t_tab's: its line is not printed */
    TST_EQ_STR(cap_text, "usage: t\n  --flag, -f   a flag\n  --n N        0..10\n  --big N      -5..\n  --seed S\n"
                         "  --r X        0..1\n  --pos X\n  --s TEXT\n  -o DIR\n  --add V      (repeatable)\n"
                         "  --maybe [K=V]\n  --late\nend\n");
    char *argv[] = { "t", "a", "-h", NULL };
    TST_EQ_INT(cli_opt_help_wanted(3, argv), 1);
    TST_EQ_INT(cli_opt_help_wanted(2, argv), 0);
}

/* ------------------------------------------- every verb's help vs tables */

/* Does name occur in text as a whole option (not inside --widths, say)? */
static int has_word(const char *text, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = text; (p = strstr(p, name)); p++) {
        int before = p == text || !(p[-1] == '-' || (p[-1] >= 'a' && p[-1] <= 'z') || (p[-1] >= 'A' && p[-1] <= 'Z'));
        char c = p[n];
        int after = !(c == '-' || c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'));
        if (before && after) return 1;
    }
    return 0;
}

/* The option a help line "  --opt ARG  text" starts with, or "" when the
 * line does not start with two spaces and a dash. */
static void line_option(const char *line, char *buf, size_t len)
{
    buf[0] = 0;
    if (strncmp(line, "  -", 3) || line[3] == ' ') return;     /* "  - a list item" */
    size_t k = strcspn(line + 2, " ,[=\n");
    snprintf(buf, len, "%.*s", (int)(k < len ? k : len - 1), line + 2);
}

static const cli_opt *spec_find(const cli_optspec *sp, const char *name)
{
    for (int g = 0; g < CLI_OPT_GROUPS && sp->tab[g]; g++) {
        const cli_opt *o = cli_opt_find(sp->tab[g], name);
        if (o) return o;
    }
    return NULL;
}

typedef struct verb_call { const cli_optverb *v; } verb_call;
static int verb_help(void *p)
{
    const cli_optverb *v = ((verb_call *)p)->v;
    char a0[32], a1[] = "--help";
    snprintf(a0, sizeof a0, "%s", v->spec->verb);
    char *argv[] = { a0, a1, NULL };
    return v->fn(2, argv);
}

static void every_verb_help_lists_its_options(void)
{
    int nverbs = 0;
    for (const cli_optverb *v = cli_optverbs; v->spec; v++, nverbs++) {
        const cli_optspec *sp = v->spec;
        verb_call vc = { v };
        TST_EQ_INT(capture(1, verb_help, &vc), CLI_OK);
        TST_CHECK(strlen(cap_text) > 40, "%s --help printed %zu bytes", sp->verb, strlen(cap_text));
        /* the help is the head, the tables' lines and the tail, nothing else */
        char *m = NULL;
        size_t ml = 0;
        FILE *f = open_memstream(&m, &ml);
        if (f) {
            fputs(sp->help_head ? sp->help_head : "", f);
            cli_opt_help_lines(f, sp);
            fputs(sp->help_tail ? sp->help_tail : "", f);
            fclose(f);
            TST_CHECK(m && !strcmp(m, cap_text), "%s --help is not built from its tables", sp->verb);
            free(m);
        }
        /* every option of the tables is in the help (hidden ones: old
         * spellings kept for their message) */
        for (int g = 0; g < CLI_OPT_GROUPS && sp->tab[g]; g++)
            for (const cli_opt *o = sp->tab[g]; o->name; o++) {
                if (o->flags & CLI_OPT_HIDDEN) {
                    TST_CHECK(!o->help, "%s %s is hidden but has help lines", sp->verb, o->name);
                    continue;
                }
                TST_CHECK(has_word(cap_text, o->name), "%s: option %s is not in --help", sp->verb, o->name);
                if (o->alias) TST_CHECK(has_word(cap_text, o->alias), "%s: %s is not in --help", sp->verb, o->alias);
                /* "" help: the lines of an entry above name it */
                if (o->help && !o->help[0]) {
                    int named = 0;
                    for (const cli_opt *p = sp->tab[g]; p < o; p++)
                        if (p->help && has_word(p->help, o->name)) named = 1;
                    TST_CHECK(named, "%s: %s has no help line of its own and none above names it", sp->verb, o->name);
                }
            }
        /* every option line of the help is an option of the tables */
        for (const char *l = cap_text; *l;) {
            char opt[64];
            line_option(l, opt, sizeof opt);
            if (opt[0]) {
                const cli_opt *o = spec_find(sp, opt);
                TST_CHECK(o && !(o->flags & CLI_OPT_HIDDEN), "%s --help lists %s, which its tables do not take", sp->verb, opt);
            }
            const char *nl = strchr(l, '\n');
            l = nl ? nl + 1 : l + strlen(l);
        }
    }
    TST_EQ_INT(nverbs, 15);
}

/* The options run shares with verilog, cosim and synth are one table:
 * its help lines are in each of their --help texts, in order. */
static void unit_options_shared(void)
{
    const cli_optspec *specs[] = { &cli_run_spec, &cli_verilog_spec, &cli_cosim_spec, &cli_synth_spec };
    char *lines = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&lines, &len);
    if (!f) return;
    for (const cli_opt *o = cli_unit_opt_tab; o->name; o++) fputs(o->help, f);
    fclose(f);
    for (size_t k = 0; k < 4; k++) {
        char *m = NULL;
        size_t ml = 0;
        FILE *g = open_memstream(&m, &ml);
        if (!g) continue;
        cli_opt_help_lines(g, specs[k]);
        fclose(g);
        TST_CHECK(m && strstr(m, lines), "%s: the unit options' lines", specs[k]->verb);
        free(m);
    }
    free(lines);
}

/* ------------------------------------------ testbench results to status */

typedef struct from_tb_call { int t; const char *fmt, *arg; } from_tb_call;
static int from_tb(void *p)
{
    const from_tb_call *c = p;
    return c->fmt ? cli_from_tb(c->t, c->fmt, c->arg) : cli_from_tb(c->t, NULL);
}

/* cli_from_tb against docs/cli.md's table: a testbench's TB_OK is status 0
 * with nothing on stderr; TB_FAIL (the simulation failed) 1 and
 * TB_BADINPUT (input the unit cannot take) 2, each after one line
 * "shadesim: MESSAGE" (bytes escaped as everywhere); an empty message or
 * none prints no line. */
static void from_tb_statuses(void)
{
    static const struct { int t; const char *fmt, *arg; int want; const char *line; } cases[] = {
        { TB_OK, "%s", "not printed", 0, "" },
        { TB_FAIL, "u: %s", "no output in time", 1, "shadesim: u: no output in time\n" },
        { TB_BADINPUT, "%s", "v.vec:3: 2 inputs", 2, "shadesim: v.vec:3: 2 inputs\n" },
        { TB_BADINPUT, "%s", "a\tb", 2, "shadesim: a\\x09b\n" },
        { TB_FAIL, "%s", "", 1, "" },
        { TB_FAIL, NULL, NULL, 1, "" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        from_tb_call c = { cases[i].t, cases[i].fmt, cases[i].arg };
        TST_EQ_INT(capture(2, from_tb, &c), cases[i].want);
        TST_CHECK(!strcmp(cap_text, cases[i].line), "case %zu: stderr '%s', expected '%s'", i, cap_text, cases[i].line);
    }
    /* out of memory has its own status, beside 0, 1 and 2 */
    TST_EQ_INT(CLI_OOM, 3);
}

int main(void)
{
    TST_RUN(values_both_spellings);
    TST_RUN(unknown_and_missing);
    TST_RUN(bad_numbers);
    TST_RUN(repeats_and_order);
    TST_RUN(help_from_the_tables);
    TST_RUN(every_verb_help_lists_its_options);
    TST_RUN(unit_options_shared);
    TST_RUN(from_tb_statuses);
    TST_EXIT();
}
