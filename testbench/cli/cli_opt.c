/* cli_opt.c - the option parser every verb uses (cli_opt.h). */
#include "base/base_near.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/cli/cli.h"
#include "base/base_out.h"
#include <limits.h>
#include <string.h>

static int is_help(const char *a) { return !strcmp(a, "--help") || !strcmp(a, "-h"); }

int cli_opt_help_wanted(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) if (is_help(argv[i])) return 1;
    return 0;
}

/* Is option o hidden by an entry of the same name in an earlier table? */
static int hidden(const cli_optspec *sp, int g, const cli_opt *o)
{
    for (int k = 0; k < g; k++)
        if (cli_opt_find(sp->tab[k], o->name)) return 1;
    return 0;
}

void cli_opt_help_lines(FILE *f, const cli_optspec *sp)
{
    for (int g = 0; g < CLI_OPT_GROUPS && sp->tab[g]; g++)
        for (const cli_opt *o = sp->tab[g]; o->name; o++)
            if (o->help && !hidden(sp, g, o)) fputs(o->help, f);
}

int cli_opt_help(const cli_optspec *sp)
{
    char e[300];
    if (sp->help_head) fputs(sp->help_head, stdout);
    cli_opt_help_lines(stdout, sp);
    if (sp->help_tail) fputs(sp->help_tail, stdout);
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return CLI_OK;
}

const cli_opt *cli_opt_find(const cli_opt *tab, const char *name)
{
    for (const cli_opt *o = tab; o && o->name; o++)
        if (!strcmp(o->name, name) || (o->alias && !strcmp(o->alias, name))) return o;
    return NULL;
}

/* Does arg name option o, alone ("--opt") or with its value ("--opt=V")?
 * *eq: the value after '=', or NULL. */
static int names(const cli_opt *o, const char *arg, const char **eq)
{
    const char *spell[2] = { o->name, o->alias };
    for (int k = 0; k < 2; k++) {
        if (!spell[k]) continue;
        size_t n = strlen(spell[k]);
        if (strncmp(arg, spell[k], n)) continue;
        if (!arg[n]) { *eq = NULL; return 1; }
        if (arg[n] == '=' && o->kind != CLI_OPT_FLAG && o->kind != CLI_OPT_CALL0) { *eq = arg + n + 1; return 1; }
    }
    return 0;
}

/* The value as its kind says, stored at base + off. */
static int store(const cli_opt *o, void *base, const char *opt, const char *v)
{
    char *at = (char *)base + o->off;
    long l;
    double d;
    switch (o->kind) {
    case CLI_OPT_FLAG: *(int *)at = 1; return 0;
    case CLI_OPT_STR: *(const char **)at = v; return 0;
    case CLI_OPT_INT:
    case CLI_OPT_LONG: {
        /* (double)LONG_MAX rounds up past LONG_MAX: the table's way to say "no limit". */
        long hi = o->hi >= (double)LONG_MAX ? LONG_MAX : (long)o->hi;
        if (cli_parse_long(opt, v, (long)o->lo, hi, o->what, &l)) return CLI_USAGE;
        if (o->kind == CLI_OPT_INT) *(int *)at = (int)l;
        else *(long *)at = l;
        return 0;
    }
    case CLI_OPT_U64: return cli_parse_u64(opt, v, o->what, (uint64_t *)at) ? CLI_USAGE : 0;
    case CLI_OPT_REAL:
        if (cli_parse_real(opt, v, o->lo, o->hi, o->what, &d)) return CLI_USAGE;
        if ((o->flags & CLI_OPT_GT_LO) && !(d > o->lo)) {
            char e[200];
            return cli_usage_error("%s %s: expected %s", opt, cli_esc(v, e, sizeof e), o->what ? o->what : "a larger number");
        }
        *(double *)at = d;
        return 0;
    case CLI_OPT_CALL:
    case CLI_OPT_CALL0: return o->call(base, opt, v);
    }
    return CLI_USAGE;
}

int cli_opt_step(const cli_opt *tab, void *base, int argc, char **argv, int *i)
{
    const char *arg = argv[*i], *v = NULL;
    for (const cli_opt *o = tab; o->name; o++) {
        if (!names(o, arg, &v)) continue;
        /* Messages name the option as the table spells it. */
        const char *opt = o->name;
        if (o->alias && strncmp(arg, o->name, strlen(o->name))) opt = o->alias;
        if (o->kind == CLI_OPT_FLAG || o->kind == CLI_OPT_CALL0) {
            int r = store(o, base, opt, NULL);
            return r ? r : 1;
        }
        if (!v && (o->flags & CLI_OPT_MAYBE)) {
            if (*i + 1 < argc && argv[*i + 1][0] != '-' && strchr(argv[*i + 1], '=')) v = argv[++*i];
            int r = store(o, base, opt, v);
            return r ? r : 1;
        }
        if (!v && *i + 1 < argc) v = argv[++*i];
        if (!v || ((o->flags & CLI_OPT_NONEMPTY) && !*v)) {
            char m[300];
            snprintf(m, sizeof m, o->missing ? o->missing : "%s needs a value", opt);
            return cli_usage_error("%s", m);
        }
        int r = store(o, base, opt, v);
        return r ? r : 1;
    }
    return 0;
}

/* An unknown argument; a long option near one the verb has (a typo) gets
 * "did you mean" (hidden options are not suggested). */
static int unknown(const cli_optspec *sp, const char *arg)
{
    char m[1200];
    snprintf(m, sizeof m, sp->unknown, arg);
    /* Long options only: a one-letter option is one edit from any other. */
    if (arg[0] == '-' && arg[1] == '-' && arg[2]) {
        const char *names[256];
        size_t n = 0;
        char opt[64];
        snprintf(opt, sizeof opt, "%.*s", (int)strcspn(arg, "="), arg);
        for (int g = 0; g < CLI_OPT_GROUPS && sp->tab[g]; g++)
            for (const cli_opt *o = sp->tab[g]; o->name && n < 254; o++)
                if (!(o->flags & CLI_OPT_HIDDEN)) { names[n++] = o->name; names[n++] = o->alias; }
        const char *near = base_near(opt, names, n);
        /* Into the message's closing parenthesis, "(see ... --help)", if any. */
        char *par = strrchr(m, '(');
        size_t ml = strlen(m);
        if (near && strcmp(near, opt) && par && ml && m[ml - 1] == ')')
            return cli_usage_error("%.*sdid you mean '%s'? %s", (int)(par + 1 - m), m, near, par + 1);
        if (near && strcmp(near, opt)) return cli_usage_error("%s (did you mean '%s'?)", m, near);
    }
    return cli_usage_error("%s", m);
}

int cli_opt_parse(const cli_optspec *sp, void *const *base, int argc, char **argv, int first)
{
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || (sp->dash_is_arg && !a[1])) {
            int r = sp->pos ? sp->pos(base[0], a) : CLI_OPT_UNKNOWN;
            if (r == CLI_OPT_UNKNOWN) return unknown(sp, a);
            if (r) return CLI_USAGE;
            continue;
        }
        int r = 0;
        for (int g = 0; g < CLI_OPT_GROUPS && sp->tab[g] && !r; g++) r = cli_opt_step(sp->tab[g], base[g], argc, argv, &i);
        if (r == 0 || r == CLI_OPT_UNKNOWN) return unknown(sp, a);
        if (r != 1) return CLI_USAGE;
    }
    return 0;
}
