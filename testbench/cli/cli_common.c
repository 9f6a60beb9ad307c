/* cli_common.c - options shared by the verbs, and where vectors come from. */
#include "base/base_near.h"
#include "testbench/cli/cli.h"
#include "base/base_join.h"
#include "base/base_num.h"
#include "testbench/cli/cli_opt.h"
#include "base/base_out.h"
#include "vectors/vec_file.h"
#include "testbench/tb_netlist.h"
#include <sys/stat.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Length of the valid UTF-8 sequence at p (a printable character beyond
 * ASCII), 0 when the bytes there are not one. */
static size_t utf8_len(const unsigned char *p)
{
    size_t n = p[0] >= 0xf0 && p[0] <= 0xf4 ? 4 : p[0] >= 0xe0 ? 3 : p[0] >= 0xc2 && p[0] < 0xe0 ? 2 : 0;
    if (p[0] >= 0xf5) return 0;
    for (size_t k = 1; k < n; k++)
        if ((p[k] & 0xc0) != 0x80) return 0;
    if (n == 3 && ((p[0] == 0xe0 && p[1] < 0xa0) || (p[0] == 0xed && p[1] >= 0xa0))) return 0;  /* overlong, surrogate */
    if (n == 4 && ((p[0] == 0xf0 && p[1] < 0x90) || (p[0] == 0xf4 && p[1] >= 0x90))) return 0;
    return n;
}

/* The message goes out with every byte a terminal could take for a control
 * (C0, DEL, bytes that are not UTF-8) as \xNN: messages echo option values,
 * paths and file text as the user gave them. */
/* The message of fmt and ap as one line "shadesim: ..." on stderr, bytes
 * escaped; nothing when it is empty and skip_empty. */
static void vmessage(int skip_empty, const char *fmt, va_list ap)
{
    char small[1024], *msg = small;
    va_list again;
    va_copy(again, ap);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    if (n >= (int)sizeof small && (msg = malloc((size_t)n + 1))) vsnprintf(msg, (size_t)n + 1, fmt, again);
    else if (n >= (int)sizeof small) msg = small;
    va_end(again);
    if (skip_empty && !msg[0]) return;
    fputs("shadesim: ", stderr);
    for (const unsigned char *p = (const unsigned char *)msg; *p;) {
        size_t u = *p >= 0x80 ? utf8_len(p) : 0;
        if (u) { fwrite(p, 1, u, stderr); p += u; }
        else if (*p < 0x20 || *p >= 0x7f) fprintf(stderr, "\\x%02x", *p++);
        else fputc(*p++, stderr);
    }
    fputc('\n', stderr);
    if (msg != small) free(msg);
}

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(0, fmt, ap);
    va_end(ap);
    return CLI_USAGE;
}

_Static_assert(CLI_OOM == BASE_EXIT_OOM, "one out-of-memory status");

int cli_from_tb(int t, const char *fmt, ...)
{
    if (t == TB_OK) return CLI_OK;
    if (fmt) {
        va_list ap;
        va_start(ap, fmt);
        vmessage(1, fmt, ap);
        va_end(ap);
    }
    return t == TB_BADINPUT ? CLI_USAGE : CLI_FAIL;
}

int cli_stdout_done(int rc)
{
    char e[300];
    if (base_out_stdout_check(e, sizeof e)) return cli_usage_error("%s", e);
    return rc;
}

int cli_make_dir(const char *dir)
{
    char err[4400];
    if (base_out_mkdirs(dir, err, sizeof err)) return cli_usage_error("%s", err);
    return CLI_OK;
}

int cli_stderr_tty(void) { return isatty(2); }

const char *cli_esc(const char *text, char *buf, size_t len)
{
    size_t k = 0;
    if (!len) return buf;
    for (const unsigned char *p = (const unsigned char *)(text ? text : ""); *p; p++) {
        char one[5];
        int n = *p >= 0x20 && *p < 0x7f && *p != '\\' ? snprintf(one, sizeof one, "%c", *p)
              : *p == '\\' ? snprintf(one, sizeof one, "\\\\") : snprintf(one, sizeof one, "\\x%02x", *p);
        if (k + (size_t)n >= len) break;
        memcpy(buf + k, one, (size_t)n);
        k += (size_t)n;
    }
    buf[k] = 0;
    return buf;
}

int cli_is_real(const char *s) { return base_num_is_real(s); }

static int num_error(const char *opt, const char *text, const char *what, const char *dflt)
{
    char e[200];
    return cli_usage_error("%s %s: expected %s", opt, cli_esc(text, e, sizeof e), what ? what : dflt);
}

int cli_parse_long(const char *opt, const char *text, long lo, long hi, const char *what, long *out)
{
    char d[80];
    snprintf(d, sizeof d, "a whole number %ld..%ld", lo, hi);
    long long v;
    if (!text) return num_error(opt, "", what, d);
    if (base_num_whole(text, 1, &v) || v < lo || v > hi || (*text == '-' && lo >= 0)) return num_error(opt, text, what, d);
    *out = (long)v;
    return 0;
}

int cli_parse_u64(const char *opt, const char *text, const char *what, uint64_t *out)
{
    const char *d = "a whole number 0..18446744073709551615";
    if (!text) return num_error(opt, "", what, d);
    const char *p = text;
    while (*p >= '0' && *p <= '9') p++;
    if (p == text || *p) return num_error(opt, text, what, d);
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || *end) return num_error(opt, text, what, d);
    *out = (uint64_t)v;
    return 0;
}

/* A '-' only where the range has negative values: "-0" for a value >= 0
 * is refused like any other sign. */
int cli_parse_real(const char *opt, const char *text, double lo, double hi, const char *what, double *out)
{
    char d[80];
    snprintf(d, sizeof d, "a number %g..%g", lo, hi);
    double v;
    if (!text) return num_error(opt, "", what, d);
    if (base_num_real(text, 1, &v) || v < lo || v > hi || (*text == '-' && lo >= 0)) return num_error(opt, text, what, d);
    *out = v;
    return 0;
}

int cli_unknown_unit(const char *name)
{
    const char *names[64];
    size_t n = 0;
    for (size_t k = 0; k < unit_count() && n < 64; k++) names[n++] = unit_at(k)->name;
    const char *near = base_near(name, names, n);
    if (near) return cli_usage_error("unknown unit '%s' (did you mean '%s'? shadesim list shows the units)", name, near);
    return cli_usage_error("unknown unit '%s' (shadesim list shows the units)", name);
}

int cli_unit_select(cli_unit_opts *o, const char *name)
{
    memset(o, 0, sizeof *o);
    o->u = unit_find(name);
    struct stat st;
    if (!o->u && !stat(name, &st)) {
        /* a datapath file (docs/datapaths.md): a unit read from its text */
        char err[1400];
        unit_fmts fm;
        const unit_desc *u = tb_netlist_load(name, &o->cfg, &fm, err, sizeof err);
        if (!u) return cli_usage_error("%s", err);
        if (!tb_datapath_is(u)) {
            tb_netlist_free(u);
            return cli_usage_error("%s: a netlist of a built-in unit, which only run takes (a datapath file says "
                                   "datapath NAME: docs/datapaths.md)", name);
        }
        o->u = u;
        return CLI_OK;
    }
    unit_cfg_default(o->u, &o->cfg);
    if (!o->u) return cli_unknown_unit(name);
    return CLI_OK;
}

/* The values of the shared options (cli_unit_opt_tab; list, sweep and the
 * Verilog verbs use the same functions in their own tables). Each is a
 * cli_opt call on a cli_unit_opts; one before the unit is chosen is not an
 * option yet (the verb's "unknown" message). */

int cli_unit_width(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    long w;
    if (cli_parse_long(opt, v, 1, 64, NULL, &w)) return CLI_USAGE;
    o->cfg.width = (int)w;
    return 0;
}

int cli_unit_fmt(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    (void)opt;
    if (o->nfmt == CLI_MAX_FMT) return cli_usage_error("too many --fmt options (at most %d)", CLI_MAX_FMT);
    o->fmt[o->nfmt++] = v;
    return 0;
}

static int unit_round(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    (void)opt;
    if (!o->u) return CLI_OPT_UNKNOWN;
    if (sim_round_parse(v, &o->cfg.rnd)) return cli_usage_error("--round %s: expected trunc, half-up or even", v);
    return 0;
}

static int unit_overflow(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    (void)opt;
    if (!o->u) return CLI_OPT_UNKNOWN;
    if (sim_ovf_parse(v, &o->cfg.ovf)) return cli_usage_error("--overflow %s: expected wrap or sat", v);
    return 0;
}

int cli_unit_sched_error(const unit_desc *u, const char *name)
{
    char list[200] = "";
    for (int j = 0; j < u->nsched; j++) base_join_add(list, sizeof list, ", ", u->sched[j].name);
    return cli_usage_error("--schedule %s: unit %s has schedules: %s", name, u->name, list);
}

static int unit_schedule(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    (void)opt;
    if (!o->u) return CLI_OPT_UNKNOWN;
    int s = unit_sched_find(o->u, v);
    if (s < 0) return cli_unit_sched_error(o->u, v);
    o->cfg.schedule = s;
    return 0;
}

int cli_unit_param(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    (void)opt;
    if (!o->u) return CLI_OPT_UNKNOWN;
    const char *eq = strchr(v, '=');
    if (!eq) return cli_usage_error("--param %s: expected NAME=VALUE", v);
    char name[64], err[300];
    snprintf(name, sizeof name, "%.*s", (int)(eq - v), v);
    if (unit_param_set(o->u, &o->cfg, name, eq + 1, err, sizeof err)) return cli_usage_error("--param %s: %s", v, err);
    return 0;
}

/* In the shared table: an option before the unit is chosen is not one yet. */
static int u_width(void *base, const char *opt, const char *v)
{
    return ((cli_unit_opts *)base)->u ? cli_unit_width(base, opt, v) : CLI_OPT_UNKNOWN;
}

static int u_fmt(void *base, const char *opt, const char *v)
{
    return ((cli_unit_opts *)base)->u ? cli_unit_fmt(base, opt, v) : CLI_OPT_UNKNOWN;
}

static int u_vectors(void *base, const char *opt, const char *v)
{
    cli_unit_opts *o = base;
    (void)opt;
    if (!o->u) return CLI_OPT_UNKNOWN;
    o->vectors = v;
    return 0;
}

#define UOPT(NAME, FN, HELP) { NAME, NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, FN, 0, HELP }
const cli_opt cli_unit_opt_tab[] = {
    UOPT("--width", u_width,
         "  --width W            default-format rule width (the unit's range: `shadesim list UNIT`); default 16\n"),
    UOPT("--fmt", u_fmt,
         "  --fmt NAME=sI.F      override one signal's format; --fmt all=sI.F sets every signal;\n"
         "                       later --fmt arguments override earlier ones (repeatable);\n"
         "                       NAME=sI.F:ROUND:OVERFLOW gives the signal its own modes\n"
         "                       (either optional, e.g. mul=s4.12:half-up:sat)\n"),
    UOPT("--round", unit_round, "  --round MODE         trunc (default), half-up, even\n"),
    UOPT("--overflow", unit_overflow, "  --overflow MODE      wrap (default), sat\n"),
    UOPT("--schedule", unit_schedule, "  --schedule NAME      the unit's schedule (default: its first)\n"),
    UOPT("--param", cli_unit_param, "  --param NAME=VALUE   a unit parameter, e.g. --param terms=5 (repeatable)\n"),
    UOPT("--vectors", u_vectors, "  --vectors FILE       golden vectors (default: the unit's file in vectors/)\n"),
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

/* True if dir is a shadesim source tree: its Makefile and units/. */
static int in_source_tree(const char *dir)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/Makefile", dir);
    if (access(p, R_OK)) return 0;
    snprintf(p, sizeof p, "%s/units", dir);
    return !access(p, F_OK);
}

/* The default vectors file p of unit is not there: one line, with the way
 * to make it that fits where it was looked for (a source tree's vectors/:
 * make vectors; else SHADESIM_HOME or make install). */
static int vectors_missing(const char *p, const char *unit)
{
    char tree[4200];
    snprintf(tree, sizeof tree, "%s", p);
    char *s = strrchr(tree, '/');
    if (s) *s = 0; else tree[0] = 0;            /* the file's folder */
    char *base = strrchr(tree, '/');
    base = base ? base + 1 : tree;
    if (strcmp(base, "vectors")) tree[0] = 0;   /* not a vectors/ folder */
    else if (base == tree) snprintf(tree, sizeof tree, ".");
    else base[-1] = 0;                          /* the folder that holds vectors/ */
    if (tree[0] && in_source_tree(tree))
        return cli_usage_error("%s: the default vectors of %s are not there (make vectors writes them in this "
                               "source tree; or give --vectors FILE)", p, unit);
    return cli_usage_error("%s: the default vectors of %s are not there (set SHADESIM_HOME to the "
                           "folder that holds vectors/, install with make install, or give --vectors FILE)",
                           p, unit);
}

/* The data folders, in the order searched (docs/cli.md, "Data files"):
 *   1. $SHADESIM_HOME, when set (and then only it: an explicit choice that
 *      does not hold the file is an error, not a fallback);
 *   2. PREFIX/share/shadesim beside an installed PREFIX/bin/shadesim;
 *   3. the source tree of a binary built in it (bin/shadesim, build/shadesim:
 *      one folder up from the executable's folder);
 *   4. the current folder.
 * Each holds vectors/UNIT.vec. The first that has the file wins; when none
 * has it, the path of 2 or 3 that fits the binary's place is returned, so
 * that the message names where the file was expected. */
const char *cli_default_vectors_path(const char *unit, char *buf, size_t len)
{
    const char *home = getenv("SHADESIM_HOME");
    if (home && *home) {
        snprintf(buf, len, "%s/vectors/%s.vec", home, unit);
        return buf;
    }
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *s = strrchr(exe, '/');
        if (s) *s = 0;                  /* the executable's folder */
        s = strrchr(exe, '/');
        const char *dir = s ? s + 1 : exe;
        if (s) *s = 0;                  /* one up: PREFIX, or the source tree */
        else snprintf(exe, sizeof exe, ".");
        snprintf(buf, len, "%s/share/shadesim/vectors/%s.vec", exe, unit);
        if (!access(buf, R_OK)) return buf;
        snprintf(buf, len, "%s/vectors/%s.vec", exe, unit);
        if (!access(buf, R_OK)) return buf;
        char cwd[600];
        snprintf(cwd, sizeof cwd, "vectors/%s.vec", unit);
        if (!access(cwd, R_OK)) { snprintf(buf, len, "%s", cwd); return buf; }
        /* Not found: name the installed place for an installed binary,
         * the tree's vectors/ for one built in a source tree (its
         * Makefile and units/ one up from bin/) */
        if (!strcmp(dir, "bin") && access(buf, F_OK) && !in_source_tree(exe))
            snprintf(buf, len, "%s/share/shadesim/vectors/%s.vec", exe, unit);
        return buf;
    }
    snprintf(buf, len, "vectors/%s.vec", unit);
    return buf;
}

/* True if every parameter of the unit has its default value, so the
 * checked-in file (made with the defaults) applies. */
static int params_default(const unit_desc *u, const unit_cfg *cfg)
{
    unit_cfg d;
    unit_cfg_default(u, &d);
    for (int i = 0; i < u->nparams; i++) {
        char a[64], b[64];
        unit_param_get(&u->params[i], cfg, a, sizeof a);
        unit_param_get(&u->params[i], &d, b, sizeof b);
        if (strcmp(a, b)) return 0;
    }
    return 1;
}

/* The unit whose checked-in vectors u runs on: a datapath file's that
 * names a built-in unit (ideal unit=NAME) takes the unit's. */
static const char *vec_name(const unit_desc *u)
{
    const unit_desc *b = tb_datapath_base(u);
    return b ? b->name : u->name;
}

int cli_vectors_file(const cli_unit_opts *o, char *buf, size_t len, const char **path)
{
    *path = NULL;
    if (!o->vectors && (!params_default(o->u, &o->cfg) || (tb_datapath_is(o->u) && !tb_datapath_base(o->u)))) return 0;
    const char *p = o->vectors ? o->vectors : cli_default_vectors_path(vec_name(o->u), buf, len);
    if (!o->vectors && access(p, R_OK)) {
        vectors_missing(p, o->u->name);
        return -1;
    }
    *path = p;
    return 1;
}

int cli_load_vectors(const cli_unit_opts *o, vec_set *vs)
{
    char err[600], path[4200];
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(o->u, &o->cfg, &hdr);
    vec_set_init(vs);
    if (!o->vectors && (!params_default(o->u, &o->cfg) || (tb_datapath_is(o->u) && !tb_datapath_base(o->u)))) {
        /* made from the reference: a datapath file has no checked-in vectors */
        if (tb_make_vectors(o->u, &o->cfg, 0, 1, vs, err, sizeof err)) return cli_usage_error("%s", err);
        return CLI_OK;
    }
    const char *p = o->vectors ? o->vectors : cli_default_vectors_path(vec_name(o->u), path, sizeof path);
    if (!o->vectors && access(p, R_OK)) return vectors_missing(p, vec_name(o->u));
    if (vec_file_read(p, vs, &hdr, err, sizeof err)) { vec_set_free(vs); return cli_usage_error("%s", err); }
    return CLI_OK;
}
