/* tb_netlist_read.c - netlist text built back into a unit (tb_netlist.h,
 * docs/netlist.md).
 *
 * Reading is two passes: the lines into element records (each checked on
 * its own: kind, name, format, attributes), then the names resolved and
 * the records checked against each other (operands declared, before their
 * use where the constructors need them, truth tables of the right size,
 * ports). Every mistake is one message "PATH:LINE: what", and nothing is
 * built until the whole file is read. Building (tb_netlist_build, called
 * by tb_build) then only calls the constructors of sim_prim.h in the
 * file's order, so it cannot fail.
 */
#include "testbench/tb_netlist_int.h"
#include "units/units_brdf.h"
#include "sim/sim_prim.h"
#include "base/base_line.h"
#include "base/base_num.h"
#include "base/base_out.h"
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NL_LINE_MAX ((size_t)1 << 20)   /* a table of 2^12 entries of 16 digits fits */
#define NL_NONE (-1)
#define NL_CLK  (-2)                     /* the clock, as an operand */
#define NL_ERR  (-3)                     /* a name that did not resolve (message given) */

typedef struct nl_el {
    int         line;
    sim_kind    kind;
    char       *name;       /* path below the unit's scope */
    const char *leaf;       /* its last part */
    int         scope;      /* index into nl.scopes, NL_NONE: the unit's */
    sim_fmt     fmt;
    int         r, o;       /* round=, overflow=: the mode, or NL_NONE */
    /* operands: names as read, then indices into nl.el (NL_CLK, NL_NONE) */
    char       *ref[5];
    int         op[5];      /* OP_A, OP_B, OP_C, OP_RST, OP_CLK */
    int         n;
    char      **in_ref;
    int        *in;
    long long   raw, rst_raw;
    unsigned long long ovf;
    int         shift;
    double      area;
    int         has_area, depth, csd, fn_unit;
    char       *verilog;
    const char *table_hex;
    uint64_t   *table;
    sim_logic_fn fn;        /* fn=unit: the built-in unit's */
    void       *user;
} nl_el;
enum { OP_A, OP_B, OP_C, OP_RST, OP_CLK };

typedef struct nl_table { int n, w[8]; const uint64_t *v; } nl_table;

typedef struct nl {
    unit_desc   desc;       /* the unit it builds (first: the registry's key) */
    const unit_desc *base;  /* the built-in unit it names */
    unit_cfg    cfg;
    unit_fmts   fm;
    char      **fmt;        /* fmt lines */
    int         nfmt;
    char       *clk;
    char      **scopes;
    int        *scope_parent;
    int         nscope;
    nl_el      *el;
    int         nel, cap;
    char      **port_ref[5];   /* in, out, in_valid, in_ready, out_valid */
    int        *port[5];
    int         nport[5];
    int         port_line[5][UNIT_MAX_IO];
    tb_built    ref;        /* the built-in unit, built for fn=unit (ref.c NULL: not) */
    void      **mem;        /* every allocation, freed with it */
    size_t      nmem, capmem;
    const char *path;
    int         version;    /* the netlist line seen */
    int         line;
    char       *err;
    size_t      errlen;
} nl;
enum { P_IN, P_OUT, P_IN_VALID, P_IN_READY, P_OUT_VALID };
static const char *const port_names[5] = { "in", "out", "in_valid", "in_ready", "out_valid" };

/* ------------------------------------------------------------ memory */

static void *nl_alloc(nl *x, size_t n)
{
    if (x->nmem == x->capmem) {
        x->capmem = x->capmem ? 2 * x->capmem : 64;
        void **m = realloc(x->mem, x->capmem * sizeof *m);
        if (!m) base_out_of_memory();
        x->mem = m;
    }
    void *p = calloc(1, n ? n : 1);
    if (!p) base_out_of_memory();
    x->mem[x->nmem++] = p;
    return p;
}

static char *nl_strdup(nl *x, const char *s, size_t n)
{
    char *p = nl_alloc(x, n + 1);
    memcpy(p, s, n);
    return p;
}

/* ------------------------------------------------------------ messages */

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int bad_at(nl *x, int line, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0) snprintf(x->err, x->errlen, "%s:%d: %s", x->path, line, msg);
    else snprintf(x->err, x->errlen, "%s: %s", x->path, msg);
    return -1;
}
#define BAD(...) bad_at(x, x->line, __VA_ARGS__)

/* ------------------------------------------------------------ shared text helpers */

const char *nl_real_str(double v, char *buf, size_t len)
{
    for (int p = 15; p <= 17; p++) {
        snprintf(buf, len, "%.*g", p, v);
        if (strtod(buf, NULL) == v) break;
    }
    return buf;
}

void nl_put_quoted(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') { fputc('\\', f); fputc(*s, f); }
        else if (*s == '\n') fputs("\\n", f);
        else fputc(*s, f);
    }
    fputc('"', f);
}

/* ------------------------------------------------------------ tokens */

/* Split line into tokens at spaces and tabs; a '"' opens a quoted part
 * (up to the next unescaped '"', spaces kept) inside a token. Quoted parts
 * are unescaped in place. Returns the count, or -1 after a message. */
#define NL_MAX_TOK 64
static int tokenize(nl *x, char *line, char **tok)
{
    int n = 0;
    char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\r') p++;
        if (!*p) return n;
        if (n == NL_MAX_TOK) return BAD("more than %d words on a line", NL_MAX_TOK);
        char *out = p;
        tok[n++] = out;
        while (*p && *p != ' ' && *p != '\t' && *p != '\r') {
            if (*p != '"') { *out++ = *p++; continue; }
            for (p++;; p++) {
                if (!*p) return BAD("a quoted text without its closing '\"'");
                if (*p == '"') { p++; break; }
                if (*p == '\\') {
                    p++;
                    if (*p == 'n') *out++ = '\n';
                    else if (*p == '\\' || *p == '"') *out++ = *p;
                    else return BAD("'\\%c' in a quoted text (only \\\\, \\\" and \\n)", *p ? *p : '0');
                } else *out++ = *p;
            }
        }
        int more = *p != 0;    /* p is at a space: the line goes on */
        *out = 0;
        if (!more) return n;
        p++;
    }
}

static int name_ok(const char *s)
{
    if (!*s || *s == '.') return 0;
    for (; *s; s++)
        if (!(nl_name_char(*s) || (*s == '.' && s[1] && s[1] != '.'))) return 0;
    return 1;
}

/* ------------------------------------------------------------ the lines */

static int parse_fmt(nl *x, const char *s, sim_fmt *f)
{
    char e[200];
    if (sim_fmt_parse(s, f, e, sizeof e)) return BAD("format %s: %s", s, e);
    return 0;
}

static int scope_index(const nl *x, const char *path, size_t len)
{
    for (int i = 0; i < x->nscope; i++)
        if (strlen(x->scopes[i]) == len && !strncmp(x->scopes[i], path, len)) return i;
    return NL_NONE - 1;
}

static int whole(nl *x, const char *key, const char *v, long long lo, long long hi, long long *out)
{
    if (base_num_whole(v, lo < 0, out) || *out < lo || *out > hi)
        return BAD("%s=%s: expected a whole number %lld..%lld", key, v, lo, hi);
    return 0;
}

/* The attributes each kind takes (KEY=VALUE). */
static const char *const kind_keys[SIM_KIND__COUNT] = {
    [SIM_KIND_WIRE] = "from round overflow",
    [SIM_KIND_INPUT] = "from round overflow",
    [SIM_KIND_CONST] = "raw overflows",
    [SIM_KIND_REG] = "d en rst init clk round overflow",
    [SIM_KIND_MUX] = "sel in round overflow",
    [SIM_KIND_BK] = "pass x round overflow",
    [SIM_KIND_ADD] = "a b round overflow",
    [SIM_KIND_SUB] = "a b round overflow",
    [SIM_KIND_MUL] = "a b round overflow net",
    [SIM_KIND_SHIFT] = "x by round overflow",
    [SIM_KIND_LOGIC] = "in area depth verilog table fn",
};

static int key_of(const char *keys, const char *k, size_t n)
{
    for (const char *p = keys; *p;) {
        size_t m = strcspn(p, " ");
        if (m == n && !strncmp(p, k, n)) return 1;
        p += m;
        while (*p == ' ') p++;
    }
    return 0;
}

/* A list "a,b,c" of names into an array. */
static int name_list(nl *x, const char *key, char *v, char ***out)
{
    int n = 1;
    for (const char *p = v; *p; p++) n += *p == ',';
    if (n > 1024) return BAD("%s=: more than 1024 names", key);
    char **r = nl_alloc(x, (size_t)n * sizeof *r);
    for (int i = 0; i < n; i++) {
        size_t m = strcspn(v, ",");
        r[i] = nl_strdup(x, v, m);
        if (!m) return BAD("%s=: an empty name in the list", key);
        v += m + (v[m] == ',');
    }
    *out = r;
    return n;
}

static int parse_element(nl *x, sim_kind kind, char **tok, int nt)
{
    if (nt < 3) return BAD("%s: expected %s NAME FORMAT [KEY=VALUE ...]", tok[0], tok[0]);
    if (!name_ok(tok[1])) return BAD("%s: a name is letters, digits and '_' (a path: such names joined by '.')", tok[1]);
    if (x->nel == x->cap) {
        x->cap = x->cap ? 2 * x->cap : 256;
        nl_el *e = realloc(x->el, (size_t)x->cap * sizeof *e);
        if (!e) base_out_of_memory();
        x->el = e;
    }
    nl_el *e = &x->el[x->nel];
    memset(e, 0, sizeof *e);
    e->line = x->line;
    e->kind = kind;
    e->name = nl_strdup(x, tok[1], strlen(tok[1]));
    const char *dot = strrchr(e->name, '.');
    e->leaf = dot ? dot + 1 : e->name;
    e->scope = NL_NONE;
    if (dot) {
        e->scope = scope_index(x, e->name, (size_t)(dot - e->name));
        if (e->scope < 0) return BAD("%s: scope %.*s is not declared (scope PATH)", e->name, (int)(dot - e->name), e->name);
    }
    if (parse_fmt(x, tok[2], &e->fmt)) return -1;
    e->r = e->o = NL_NONE;
    for (int i = 0; i < 5; i++) e->op[i] = NL_NONE;
    e->depth = -1;
    int seen_raw = 0;
    for (int i = 3; i < nt; i++) {
        char *eq = strchr(tok[i], '=');
        if (!eq) return BAD("%s: expected KEY=VALUE", tok[i]);
        size_t kn = (size_t)(eq - tok[i]);
        char *v = eq + 1;
        if (!key_of(kind_keys[kind], tok[i], kn))
            return BAD("%.*s=: not an attribute of %s (it takes: %s)", (int)kn, tok[i], sim_kind_name(kind), kind_keys[kind]);
        for (int j = 3; j < i; j++)
            if (!strncmp(tok[j], tok[i], kn + 1)) return BAD("%.*s= given twice", (int)kn, tok[i]);
#define KEY(s) (kn == strlen(s) && !strncmp(tok[i], s, kn))
        long long w;
        if (KEY("round")) {
            sim_round r;
            if (sim_round_parse(v, &r)) return BAD("round=%s: expected trunc, half-up or even", v);
            e->r = (int)r;
        } else if (KEY("overflow")) {
            sim_ovf o;
            if (sim_ovf_parse(v, &o)) return BAD("overflow=%s: expected wrap or sat", v);
            e->o = (int)o;
        } else if (KEY("raw")) {
            if (whole(x, "raw", v, INT64_MIN, INT64_MAX, &w)) return -1;
            e->raw = w;
            seen_raw = 1;
        } else if (KEY("overflows")) {
            if (whole(x, "overflows", v, 0, INT64_MAX, &w)) return -1;
            e->ovf = (unsigned long long)w;
        } else if (KEY("init")) {
            if (whole(x, "init", v, INT64_MIN, INT64_MAX, &w)) return -1;
            e->rst_raw = w;
        } else if (KEY("by")) {
            if (whole(x, "by", v, -64, 64, &w)) return -1;
            e->shift = (int)w;
        } else if (KEY("depth")) {
            if (whole(x, "depth", v, 0, 10000, &w)) return -1;
            e->depth = (int)w;
        } else if (KEY("area")) {
            if (base_num_real(v, 0, &e->area)) return BAD("area=%s: expected a number >= 0 (gate equivalents)", v);
            e->has_area = 1;
        } else if (KEY("net")) {
            if (strcmp(v, "csd")) return BAD("net=%s: the one network is csd (a constant's shift-and-add)", v);
            e->csd = 1;
        } else if (KEY("fn")) {
            if (strcmp(v, "unit")) return BAD("fn=%s: expected fn=unit (the built-in unit's function)", v);
            e->fn_unit = 1;
        } else if (KEY("verilog")) {
            e->verilog = nl_strdup(x, v, strlen(v));
        } else if (KEY("table")) {
            e->table_hex = nl_strdup(x, v, strlen(v));
        } else if (KEY("in")) {
            int n = name_list(x, "in", v, &e->in_ref);
            if (n < 0) return -1;
            e->n = n;
        } else {
            static const char *const refk[][2] = {
                { "from", "" }, { "d", "" }, { "a", "" }, { "x", "" }, { "b", "" }, { "en", "" }, { "sel", "" },
                { "pass", "" }, { "rst", "" }, { "clk", "" } };
            static const int refop[] = { OP_A, OP_A, OP_A, OP_A, OP_B, OP_C, OP_C, OP_C, OP_RST, OP_CLK };
            for (size_t k = 0; k < sizeof refop / sizeof refop[0]; k++)
                if (KEY(refk[k][0])) {
                    if (!name_ok(v)) return BAD("%s=%s: not a name", refk[k][0], v);
                    e->ref[refop[k]] = nl_strdup(x, v, strlen(v));
                }
        }
#undef KEY
    }
    /* what each kind needs */
    static const struct { sim_kind k; int op; const char *key; } need[] = {
        { SIM_KIND_WIRE, OP_A, "from" }, { SIM_KIND_REG, OP_CLK, "clk" }, { SIM_KIND_MUX, OP_C, "sel" },
        { SIM_KIND_BK, OP_C, "pass" }, { SIM_KIND_BK, OP_A, "x" }, { SIM_KIND_ADD, OP_A, "a" },
        { SIM_KIND_ADD, OP_B, "b" }, { SIM_KIND_SUB, OP_A, "a" }, { SIM_KIND_SUB, OP_B, "b" },
        { SIM_KIND_MUL, OP_A, "a" }, { SIM_KIND_MUL, OP_B, "b" }, { SIM_KIND_SHIFT, OP_A, "x" } };
    for (size_t k = 0; k < sizeof need / sizeof need[0]; k++)
        if (need[k].k == kind && !e->ref[need[k].op]) return BAD("%s %s: needs %s=NAME", tok[0], e->name, need[k].key);
    if (kind == SIM_KIND_CONST && !seen_raw) return BAD("const %s: needs raw=VALUE", e->name);
    if (kind == SIM_KIND_MUX && !e->in_ref) return BAD("mux %s: needs in=NAME,NAME,...", e->name);
    if (kind == SIM_KIND_LOGIC) {
        if (!e->in_ref) return BAD("logic %s: needs in=NAME,...", e->name);
        if (e->n > 8) return BAD("logic %s: %d inputs (at most 8)", e->name, e->n);
        if (!e->has_area) return BAD("logic %s: needs area=GE (its gates, NAND2 equivalents)", e->name);
        if (!e->table_hex == !e->fn_unit) return BAD("logic %s: needs one of table=HEX and fn=unit", e->name);
    }
    x->nel++;
    return 0;
}

/* The header lines: 0, 1 (not a header line), or -1. */
static int parse_header(nl *x, char **tok, int nt)
{
    const char *k = tok[0];
    int unit_line = !strcmp(k, "unit");
    if (strcmp(k, "schedule") && strcmp(k, "width") && strcmp(k, "round") && strcmp(k, "overflow") && strcmp(k, "param")
        && strcmp(k, "fmt") && strcmp(k, "clock") && strcmp(k, "scope") && !unit_line)
        return 1;
    if (nt != (strcmp(k, "param") ? 2 : 3)) return BAD("%s: expected %s", k, strcmp(k, "param") ? "one value" : "NAME VALUE");
    const char *v = tok[1];
    if (unit_line) {
        if (x->base) return BAD("unit given twice");
        x->base = unit_find(v);
        if (!x->base) return BAD("unit %s: no such built-in unit (shadesim list)", v);
        unit_cfg_default(x->base, &x->cfg);
        return 0;
    }
    if (!x->base && strcmp(k, "clock") && strcmp(k, "scope")) return BAD("%s before unit NAME", k);
    char e[300];
    long long w;
    if (!strcmp(k, "schedule")) {
        int s = unit_sched_find(x->base, v);
        if (s < 0) return BAD("schedule %s: unit %s has no such schedule", v, x->base->name);
        x->cfg.schedule = s;
    } else if (!strcmp(k, "width")) {
        if (base_num_whole(v, 0, &w) || w < 1 || w > 64) return BAD("width %s: expected a whole number 1..64", v);
        x->cfg.width = (int)w;
    } else if (!strcmp(k, "round")) {
        if (sim_round_parse(v, &x->cfg.rnd)) return BAD("round %s: expected trunc, half-up or even", v);
    } else if (!strcmp(k, "overflow")) {
        if (sim_ovf_parse(v, &x->cfg.ovf)) return BAD("overflow %s: expected wrap or sat", v);
    } else if (!strcmp(k, "param")) {
        if (unit_param_set(x->base, &x->cfg, v, tok[2], e, sizeof e)) return BAD("param %s %s: %s", v, tok[2], e);
    } else if (!strcmp(k, "fmt")) {
        char **f = nl_alloc(x, (size_t)(x->nfmt + 1) * sizeof *f);
        if (x->nfmt) memcpy(f, x->fmt, (size_t)x->nfmt * sizeof *f);
        f[x->nfmt++] = nl_strdup(x, v, strlen(v));
        x->fmt = f;
    } else if (!strcmp(k, "clock")) {
        if (x->clk) return BAD("clock given twice (a unit has one clock)");
        if (!name_ok(v) || strchr(v, '.')) return BAD("clock %s: not a name", v);
        x->clk = nl_strdup(x, v, strlen(v));
    } else {   /* scope */
        if (!name_ok(v)) return BAD("scope %s: a path of names joined by '.'", v);
        if (scope_index(x, v, strlen(v)) >= 0) return BAD("scope %s declared twice", v);
        const char *dot = strrchr(v, '.');
        int parent = NL_NONE;
        if (dot && (parent = scope_index(x, v, (size_t)(dot - v))) < 0)
            return BAD("scope %s: its parent %.*s is not declared before it", v, (int)(dot - v), v);
        char **s = nl_alloc(x, (size_t)(x->nscope + 1) * sizeof *s);
        int *pp = nl_alloc(x, (size_t)(x->nscope + 1) * sizeof *pp);
        if (x->nscope) { memcpy(s, x->scopes, (size_t)x->nscope * sizeof *s); memcpy(pp, x->scope_parent, (size_t)x->nscope * sizeof *pp); }
        s[x->nscope] = nl_strdup(x, v, strlen(v));
        pp[x->nscope++] = parent;
        x->scopes = s;
        x->scope_parent = pp;
    }
    return 0;
}

static int parse_port(nl *x, char **tok, int nt)
{
    if (nt != 3) return BAD("port: expected port ROLE NAME (ROLE: in, out, in_valid, in_ready, out_valid)");
    int r = -1;
    for (int i = 0; i < 5; i++) if (!strcmp(tok[1], port_names[i])) r = i;
    if (r < 0) return BAD("port %s: expected in, out, in_valid, in_ready or out_valid", tok[1]);
    if (r >= P_IN_VALID && x->nport[r]) return BAD("port %s given twice", tok[1]);
    if (x->nport[r] == UNIT_MAX_IO) return BAD("port %s: more than %d", tok[1], UNIT_MAX_IO);
    if (!name_ok(tok[2])) return BAD("port %s %s: not a name", tok[1], tok[2]);
    if (!x->port_ref[r]) x->port_ref[r] = nl_alloc(x, UNIT_MAX_IO * sizeof(char *));
    x->port_line[r][x->nport[r]] = x->line;
    x->port_ref[r][x->nport[r]++] = nl_strdup(x, tok[2], strlen(tok[2]));
    return 0;
}

static int parse_line(nl *x, char *line)
{
    char *tok[NL_MAX_TOK];
    int nt = tokenize(x, line, tok);
    if (nt <= 0 || tok[0][0] == '#') return nt < 0 ? -1 : 0;
    if (!strcmp(tok[0], "netlist")) {
        if (x->version) return BAD("netlist given twice");
        if (nt != 2 || strcmp(tok[1], "1")) return BAD("netlist %s: this reader knows version 1", nt > 1 ? tok[1] : "");
        x->version = 1;
        return 0;
    }
    if (!x->version) return BAD("expected 'netlist 1' first: not a netlist file (shadesim netlist UNIT writes one)");
    if (!strcmp(tok[0], "port")) return parse_port(x, tok, nt);
    int h = parse_header(x, tok, nt);
    if (h <= 0) return h;
    for (int k = 0; k < SIM_KIND__COUNT; k++)
        if (!strcmp(tok[0], sim_kind_name((sim_kind)k)) && k != SIM_KIND_CLOCK) {
            if (!x->base) return BAD("%s before unit NAME", tok[0]);
            return parse_element(x, (sim_kind)k, tok, nt);
        }
    return BAD("%s: not a line of a netlist (netlist, unit, schedule, width, round, overflow, param, fmt, clock, "
               "scope, port, or an element: input wire const reg mux bk add sub mul shift logic)", tok[0]);
}

/* ------------------------------------------------------------ names */

/* An index of the elements by name: open addressing over their names. */
typedef struct nl_names { int *slot; size_t cap; } nl_names;

static size_t hash(const char *s)
{
    size_t h = 1469598103934665603u;
    for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211u;
    return h;
}

static int find(const nl *x, const nl_names *t, const char *name)
{
    if (x->clk && !strcmp(name, x->clk)) return NL_CLK;
    for (size_t i = hash(name) & (t->cap - 1);; i = (i + 1) & (t->cap - 1)) {
        if (t->slot[i] < 0) return NL_NONE;
        if (!strcmp(x->el[t->slot[i]].name, name)) return t->slot[i];
    }
}

/* Operand name of element i into its index: declared, and before element i
 * unless forward (a register's d, a wire's from); the clock only where
 * clock_ok (a register's clk). NL_ERR after a message. */
static int resolve(nl *x, const nl_names *t, int i, const char *key, const char *name, int forward, int clock_ok)
{
    nl_el *e = &x->el[i];
    const char *kn = sim_kind_name(e->kind);
    int k = find(x, t, name);
    if (k == NL_NONE) bad_at(x, e->line, "%s %s: %s=%s is not declared", kn, e->name, key, name);
    else if (k == NL_CLK && !clock_ok)
        bad_at(x, e->line, "%s %s: %s=%s is the clock, which only a register's clk= takes", kn, e->name, key, name);
    else if (k != NL_CLK && clock_ok)
        bad_at(x, e->line, "%s %s: clk=%s is not the clock (%s)", kn, e->name, name, x->clk);
    else if (k >= i && !forward)
        bad_at(x, e->line, "%s %s: %s=%s is made at line %d, after it (only a register's d= and from= may name a "
               "later signal)", kn, e->name, key, name, x->el[k].line);
    else return k;
    return NL_ERR;
}

static int hexval(char ch)
{
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    return -1;
}

static int check_logic(nl *x, nl_el *e)
{
    int bits = 0;
    for (int j = 0; j < e->n; j++) bits += x->el[e->in[j]].fmt.width;
    if (e->table_hex) {
        if (bits > TB_NETLIST_TABLE_BITS)
            return bad_at(x, e->line, "logic %s: inputs of %d bits in all: a table takes at most %d", e->name, bits,
                          TB_NETLIST_TABLE_BITS);
        size_t rows = (size_t)1 << bits, dig = (size_t)(e->fmt.width + 3) / 4;
        if (strlen(e->table_hex) != rows * dig)
            return bad_at(x, e->line, "logic %s: table= has %zu hex digits, its %zu rows of %zu need %zu", e->name,
                          strlen(e->table_hex), rows, dig, rows * dig);
        e->table = nl_alloc(x, rows * sizeof *e->table);
        const char *p = e->table_hex;
        uint64_t mask = e->fmt.width >= 64 ? UINT64_MAX : (((uint64_t)1 << e->fmt.width) - 1);
        for (size_t r = 0; r < rows; r++) {
            uint64_t v = 0;
            for (size_t d = 0; d < dig; d++, p++) {
                int h = hexval(*p);
                if (h < 0) return bad_at(x, e->line, "logic %s: table=: '%c' is not a lower-case hex digit", e->name, *p);
                v = v << 4 | (uint64_t)h;
            }
            if (v & ~mask)
                return bad_at(x, e->line, "logic %s: table= row %zu: %llx has more bits than %s's %d", e->name, r,
                              (unsigned long long)v, e->name, e->fmt.width);
            e->table[r] = v;
        }
    }
    return 0;
}

/* fn=unit: the function of the built-in unit's logic element of the same
 * path and inputs, from the unit built once with the file's configuration. */
static int take_unit_fn(nl *x, nl_el *e)
{
    char err[600];
    if (!x->ref.c) {
        unit_fmts fm;
        if (tb_formats(x->base, &x->cfg, (const char *const *)x->fmt, x->nfmt, &fm, err, sizeof err)
            || tb_build(x->base, &x->cfg, &fm, &x->ref, err, sizeof err)) {
            if (x->ref.c) { sim_free(x->ref.c); x->ref.c = NULL; }
            return bad_at(x, e->line, "logic %s: fn=unit, but unit %s does not build with the file's configuration (%s)",
                          e->name, x->base->name, err);
        }
    }
    sim_signal *s = sim_find(x->ref.c, x->ref.sc, e->name);
    sim_prim_info in;
    int same = s && s->kind == SIM_KIND_LOGIC && !sim_prim_describe(s, &in) && in.n == e->n
               && !memcmp(&s->fmt, &e->fmt, sizeof s->fmt);
    for (int j = 0; same && j < e->n; j++) same = !memcmp(&in.in[j]->fmt, &x->el[e->in[j]].fmt, sizeof(sim_fmt));
    if (!same)
        return bad_at(x, e->line, "logic %s: fn=unit, but unit %s has no logic element %s with this format and inputs",
                      e->name, x->base->name, e->name);
    e->fn = in.fn;
    e->user = in.user;
    if (!e->verilog) e->verilog = (char *)in.verilog;
    return 0;
}

static int resolve_all(nl *x)
{
    if (!x->base) return bad_at(x, 0, "no unit NAME line (the built-in unit whose reference the design is run against)");
    if (!x->clk) return bad_at(x, 0, "no clock NAME line");
    nl_names t;
    t.cap = 16;
    while (t.cap < 2 * (size_t)x->nel) t.cap *= 2;
    t.slot = nl_alloc(x, t.cap * sizeof *t.slot);
    memset(t.slot, 0xff, t.cap * sizeof *t.slot);
    for (int i = 0; i < x->nel; i++) {
        if (!strcmp(x->el[i].name, x->clk)) return bad_at(x, x->el[i].line, "%s: the clock's name", x->el[i].name);
        int k = find(x, &t, x->el[i].name);
        if (k >= 0) return bad_at(x, x->el[i].line, "%s: declared twice (first at line %d)", x->el[i].name, x->el[k].line);
        for (int j = 0; j < x->nscope; j++)
            if (!strcmp(x->scopes[j], x->el[i].name)) return bad_at(x, x->el[i].line, "%s: also a scope's name", x->el[i].name);
        size_t h = hash(x->el[i].name) & (t.cap - 1);
        while (t.slot[h] >= 0) h = (h + 1) & (t.cap - 1);
        t.slot[h] = i;
    }
    static const char *const keys[5] = { "a", "b", "c", "rst", "clk" };
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        for (int k = 0; k < 5; k++) {
            if (!e->ref[k]) continue;
            const char *key = keys[k];
            if (e->kind == SIM_KIND_REG && k == OP_A) key = "d";
            else if (e->kind == SIM_KIND_REG && k == OP_C) key = "en";
            else if (e->kind == SIM_KIND_MUX) key = "sel";
            else if (e->kind == SIM_KIND_BK) key = k == OP_C ? "pass" : "x";
            else if (e->kind == SIM_KIND_SHIFT) key = "x";
            else if (e->kind == SIM_KIND_WIRE || e->kind == SIM_KIND_INPUT) key = "from";
            int fwd = k == OP_A && (e->kind == SIM_KIND_REG || e->kind == SIM_KIND_WIRE || e->kind == SIM_KIND_INPUT);
            if ((e->op[k] = resolve(x, &t, i, key, e->ref[k], fwd, k == OP_CLK)) == NL_ERR) return -1;
            if (k == OP_A && e->op[k] == i && e->kind != SIM_KIND_REG) return bad_at(x, e->line, "%s %s: %s=%s names itself", sim_kind_name(e->kind), e->name, key, e->name);
        }
        if (e->n) {
            e->in = nl_alloc(x, (size_t)e->n * sizeof *e->in);
            for (int j = 0; j < e->n; j++)
                if ((e->in[j] = resolve(x, &t, i, "in", e->in_ref[j], 0, 0)) == NL_ERR) return -1;
        }
        if (e->kind == SIM_KIND_MUL && e->csd && x->el[e->op[OP_B]].kind != SIM_KIND_CONST)
            return bad_at(x, e->line, "mul %s: net=csd needs a constant b=", e->name);
        if (e->kind == SIM_KIND_LOGIC && check_logic(x, e)) return -1;
        if (e->kind == SIM_KIND_SHIFT) {
            /* a left shift past the binary point is made on the raw: it
             * must stay within the exact 128-bit value */
            sim_fmt f = x->el[e->op[OP_A]].fmt;
            int sa = e->shift > f.fbits ? e->shift - f.fbits : 0;
            if (f.width + sa > 126)
                return bad_at(x, e->line, "shift %s: by=%d takes %s's %d bits past 126", e->name, e->shift,
                              e->ref[OP_A], f.width + sa);
        }
    }
    for (int r = 0; r < 5; r++) {
        x->port[r] = nl_alloc(x, UNIT_MAX_IO * sizeof(int));
        for (int j = 0; j < x->nport[r]; j++) {
            int k = find(x, &t, x->port_ref[r][j]);
            if (k < 0) return bad_at(x, x->port_line[r][j], "port %s %s is not declared", port_names[r], x->port_ref[r][j]);
            x->port[r][j] = k;
            /* the testbench drives these: inputs nothing else drives */
            if ((r == P_IN || r == P_IN_VALID) && (x->el[k].kind != SIM_KIND_INPUT || x->el[k].ref[OP_A]))
                return bad_at(x, x->port_line[r][j], "port %s %s: not an input without from= (the testbench drives it)",
                              port_names[r], x->port_ref[r][j]);
        }
    }
    int nin = unit_n_in(x->base), nout = unit_n_out(x->base);
    if (x->nport[P_IN] != nin || x->nport[P_OUT] != nout)
        return bad_at(x, 0, "%d input and %d output ports; unit %s has %d and %d", x->nport[P_IN], x->nport[P_OUT],
                      x->base->name, nin, nout);
    if (!x->nport[P_IN_VALID] || !x->nport[P_IN_READY] || !x->nport[P_OUT_VALID])
        return bad_at(x, 0, "needs the handshake's ports: port in_valid, port in_ready and port out_valid");
    for (int i = 0; i < x->nel; i++)
        if (x->el[i].fn_unit && take_unit_fn(x, &x->el[i])) return -1;
    return 0;
}

/* ------------------------------------------------------------ the unit */

static nl **reg;
static size_t nreg;

static nl *nl_of(const unit_desc *u)
{
    for (size_t i = 0; i < nreg; i++) if (&reg[i]->desc == u) return reg[i];
    return NULL;
}

int tb_netlist_is(const unit_desc *u) { return nl_of(u) != NULL; }

static void nl_free(nl *x)
{
    if (x->ref.c) sim_free(x->ref.c);
    for (size_t i = 0; i < x->nmem; i++) free(x->mem[i]);
    free(x->mem);
    free(x->el);
    free(x);
}

void tb_netlist_free(const unit_desc *u)
{
    for (size_t i = 0; i < nreg; i++)
        if (&reg[i]->desc == u) {
            nl_free(reg[i]);
            reg[i] = reg[--nreg];
            if (!nreg) { free(reg); reg = NULL; }
            return;
        }
}

static int64_t table_fn(const int64_t *in, void *user)
{
    const nl_table *t = user;
    uint64_t k = 0;
    for (int i = 0; i < t->n; i++) k = k << t->w[i] | ((uint64_t)in[i] & (((uint64_t)1 << t->w[i]) - 1));
    return (int64_t)t->v[k];
}

int tb_netlist_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk, unit_io *io,
                     char *err, size_t errlen)
{
    nl *x = nl_of(u);
    if (!x) { snprintf(err, errlen, "not a netlist's unit"); return -1; }
    sim_scope **scs = sim_alloc(c, (size_t)(x->nscope + 1) * sizeof *scs);
    for (int i = 0; i < x->nscope; i++) {
        const char *dot = strrchr(x->scopes[i], '.');
        scs[i] = sim_scope_new(c, x->scope_parent[i] < 0 ? sc : scs[x->scope_parent[i]], dot ? dot + 1 : x->scopes[i]);
    }
    sim_signal **s = sim_alloc(c, (size_t)(x->nel + 1) * sizeof *s);
#define S(k) ((k) == NL_CLK ? clk : (k) == NL_NONE ? NULL : s[k])
    sim_round r0 = sim_get_round(c);
    sim_ovf o0 = sim_get_ovf(c);
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        sim_scope *in_sc = e->scope < 0 ? sc : scs[e->scope];
        sim_set_quant(c, e->r >= 0 ? (sim_round)e->r : r0, e->o >= 0 ? (sim_ovf)e->o : o0);
        sim_signal *in[8], **mi = NULL;
        for (int j = 0; j < e->n && j < 8; j++) in[j] = s[e->in[j]];
        switch (e->kind) {
        case SIM_KIND_INPUT: case SIM_KIND_WIRE:
            s[i] = sim_signal_new(c, in_sc, e->leaf, e->fmt, e->kind);
            break;
        case SIM_KIND_CONST:
            s[i] = sim_const_raw(c, in_sc, e->leaf, e->fmt, e->raw);
            s[i]->overflows = e->ovf;
            break;
        case SIM_KIND_REG:
            s[i] = sim_reg(c, in_sc, e->leaf, e->fmt, clk, e->op[OP_A] < i ? S(e->op[OP_A]) : NULL, S(e->op[OP_C]),
                           S(e->op[OP_RST]), e->rst_raw);
            break;
        case SIM_KIND_MUX:
            mi = sim_alloc(c, (size_t)e->n * sizeof *mi);
            for (int j = 0; j < e->n; j++) mi[j] = s[e->in[j]];
            s[i] = sim_mux(c, in_sc, e->leaf, e->fmt, S(e->op[OP_C]), e->n, mi);
            break;
        case SIM_KIND_BK: s[i] = sim_bk(c, in_sc, e->leaf, e->fmt, S(e->op[OP_C]), S(e->op[OP_A])); break;
        case SIM_KIND_ADD: s[i] = sim_add(c, in_sc, e->leaf, e->fmt, S(e->op[OP_A]), S(e->op[OP_B])); break;
        case SIM_KIND_SUB: s[i] = sim_sub(c, in_sc, e->leaf, e->fmt, S(e->op[OP_A]), S(e->op[OP_B])); break;
        case SIM_KIND_MUL:
            s[i] = (e->csd ? brdf_cmul : sim_mul)(c, in_sc, e->leaf, e->fmt, S(e->op[OP_A]), S(e->op[OP_B]));
            break;
        case SIM_KIND_SHIFT: s[i] = sim_shift(c, in_sc, e->leaf, e->fmt, S(e->op[OP_A]), e->shift); break;
        case SIM_KIND_LOGIC: {
            sim_logic_fn fn = e->fn;
            void *user = e->user;
            if (e->table) {
                nl_table *t = sim_alloc(c, sizeof *t);
                t->n = e->n;
                for (int j = 0; j < e->n; j++) t->w[j] = x->el[e->in[j]].fmt.width;
                t->v = e->table;
                fn = table_fn;
                user = t;
            }
            s[i] = sim_logic(c, in_sc, e->leaf, e->fmt, e->n, in, fn, user, e->area);
            if (e->depth >= 0) sim_logic_depth(s[i], e->depth);
            if (e->verilog) sim_logic_verilog(s[i], e->verilog);
            break;
        }
        default: break;
        }
    }
    sim_set_quant(c, r0, o0);
    /* the forward connections, in the file's order */
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        if (e->kind == SIM_KIND_REG && e->op[OP_A] >= i) sim_reg_connect(s[i], s[e->op[OP_A]]);
        if ((e->kind == SIM_KIND_WIRE || e->kind == SIM_KIND_INPUT) && e->op[OP_A] >= 0) {
            sim_set_quant(c, e->r >= 0 ? (sim_round)e->r : r0, e->o >= 0 ? (sim_ovf)e->o : o0);
            sim_assign(c, s[i], s[e->op[OP_A]]);
            sim_set_quant(c, r0, o0);
        }
    }
    memset(io, 0, sizeof *io);
    for (int j = 0; j < x->nport[P_IN]; j++) io->in[j] = s[x->port[P_IN][j]];
    for (int j = 0; j < x->nport[P_OUT]; j++) io->out[j] = s[x->port[P_OUT][j]];
    io->in_valid = s[x->port[P_IN_VALID][0]];
    io->in_ready = s[x->port[P_IN_READY][0]];
    io->out_valid = s[x->port[P_OUT_VALID][0]];
    io->scope = sc;
#undef S
    return 0;
}

/* The formats of the unit's signals: its rule at the file's width with its
 * fmt lines, then each signal's as the element of its name at the top of
 * the unit's scope has it (the ports' formats are the elements'). */
static int formats_of(nl *x)
{
    char err[600];
    if (tb_formats(x->base, &x->cfg, (const char *const *)x->fmt, x->nfmt, &x->fm, err, sizeof err))
        return bad_at(x, 0, "the configuration: %s", err);
    for (int i = 0; i < x->base->nsigs; i++)
        for (int k = 0; k < x->nel; k++)
            if (x->el[k].scope == NL_NONE && !strcmp(x->el[k].name, x->base->sigs[i].name)) x->fm.f[i] = x->el[k].fmt;
    return 0;
}

static const unit_desc *finish(nl *x, unit_cfg *cfg, unit_fmts *fm)
{
    if (resolve_all(x) || formats_of(x)) { nl_free(x); return NULL; }
    x->desc = *x->base;
    nl **r = realloc(reg, (nreg + 1) * sizeof *r);
    if (!r) base_out_of_memory();
    reg = r;
    reg[nreg++] = x;
    *cfg = x->cfg;
    *fm = x->fm;
    return &x->desc;
}

static nl *nl_new(const char *path, char *err, size_t errlen)
{
    nl *x = calloc(1, sizeof *x);
    if (!x) base_out_of_memory();
    x->path = path;
    x->err = err;
    x->errlen = errlen;
    return x;
}

const unit_desc *nl_load_text(const char *text, size_t len, const char *path, unit_cfg *cfg, unit_fmts *fm,
                              char *err, size_t errlen)
{
    nl *x = nl_new(path, err, errlen);
    const char *p = text, *end = text + len;
    while (p < end) {
        const char *nlc = memchr(p, '\n', (size_t)(end - p));
        size_t n = nlc ? (size_t)(nlc - p) : (size_t)(end - p);
        char *line = malloc(n + 1);
        if (!line) base_out_of_memory();
        memcpy(line, p, n);
        line[n] = 0;
        x->line++;
        int rc = memchr(p, 0, n) ? BAD("not a text file (NUL byte)") : parse_line(x, line);
        free(line);
        if (rc) { nl_free(x); return NULL; }
        p += n + 1;
    }
    x->line = 0;
    return finish(x, cfg, fm);
}

const unit_desc *tb_netlist_load(const char *path, unit_cfg *cfg, unit_fmts *fm, char *err, size_t errlen)
{
    int std = !strcmp(path, "-");
    FILE *f = std ? stdin : fopen(path, "rb");
    if (!f) { snprintf(err, errlen, "%s: %s", path, strerror(errno)); return NULL; }
    nl *x = nl_new(path, err, errlen);
    char *line = malloc(NL_LINE_MAX + 1);
    if (!line) base_out_of_memory();
    int rc = 0;
    for (;;) {
        long n = base_line_read(f, line, NL_LINE_MAX);
        if (n == BASE_LINE_EOF) break;
        x->line++;
        if (n == BASE_LINE_LONG) rc = BAD("line longer than %zu bytes", NL_LINE_MAX);
        else if (n == BASE_LINE_NUL) rc = BAD("not a text file (NUL byte)");
        else if (n == BASE_LINE_ERR) rc = BAD("%s", strerror(errno));
        else rc = parse_line(x, line);
        if (rc) break;
    }
    free(line);
    if (!std) fclose(f);
    if (rc) { nl_free(x); return NULL; }
    if (x->line == 0) { bad_at(x, 0, "empty: not a netlist"); nl_free(x); return NULL; }
    x->line = 0;
    return finish(x, cfg, fm);
}
