/* tb_netlist_parse.c - the netlist text's lines into the reader's records
 * (tb_netlist_int.h): each line checked on its own (its kind, name,
 * format and attributes); names are resolved afterwards
 * (tb_netlist_read.c). */
#include "testbench/tb_netlist_int.h"
#include "base/base_num.h"
#include "base/base_out.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

const char *const nl_port_names[5] = { "in", "out", "in_valid", "in_ready", "out_valid" };

#define BAD(...) nl_bad(x, x->line, __VA_ARGS__)

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
#define NL_MAX_TOK (NL_MAX_CLOCKS + 8)   /* a ctl row of the longest schedule */
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
    [SIM_KIND_WIRE] = "from round overflow what",
    [SIM_KIND_INPUT] = "from round overflow range draw what",
    [SIM_KIND_CONST] = "raw value overflows what",
    [SIM_KIND_REG] = "d en rst init clk round overflow what",
    [SIM_KIND_MUX] = "sel in round overflow what",
    [SIM_KIND_BK] = "pass x round overflow what",
    [SIM_KIND_ADD] = "a b round overflow what",
    [SIM_KIND_SUB] = "a b round overflow what",
    [SIM_KIND_MUL] = "a b round overflow net what",
    [SIM_KIND_SHIFT] = "x by round overflow what",
    [SIM_KIND_LOGIC] = "in area depth verilog table bits fn what",
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


/* "LO,HI" with LO < HI. */
static int real_pair(nl *x, const char *key, const char *v, double *out)
{
    char a[64];
    size_t m = strcspn(v, ",");
    if (m >= sizeof a || !v[m]) return BAD("%s=%s: expected LO,HI", key, v);
    memcpy(a, v, m);
    a[m] = 0;
    if (base_num_real(a, 1, &out[0]) || base_num_real(v + m + 1, 1, &out[1]) || !(out[0] < out[1]))
        return BAD("%s=%s: expected LO,HI, two numbers with LO < HI", key, v);
    return 0;
}

static int parse_element(nl *x, sim_kind kind, char **tok, int nt)
{
    if (nt < 3) return BAD("%s: expected %s NAME FORMAT [KEY=VALUE ...]", tok[0], tok[0]);
    if (!nl_name_ok(tok[1])) return BAD("%s: a name is letters, digits and '_' (a path: such names joined by '.')", tok[1]);
    sim_fmt f0;
    memset(&f0, 0, sizeof f0);
    nl_el *e = nl_el_new(x, kind, tok[1], f0);
    x->nel--;     /* counted once the line is read whole */
    const char *dot = strrchr(e->name, '.');
    if (dot) {
        e->scope = scope_index(x, e->name, (size_t)(dot - e->name));
        if (e->scope < 0) return BAD("%s: scope %.*s is not declared (scope PATH)", e->name, (int)(dot - e->name), e->name);
    }
    if (x->dp ? nl_dp_format(x, e, tok[2]) : parse_fmt(x, tok[2], &e->fmt)) return -1;
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
            if (strcmp(v, "unit") && strcmp(v, "verilog"))
                return BAD("fn=%s: expected fn=verilog (its verilog= text's function) or fn=unit (the built-in unit's)", v);
            e->fn_unit = !strcmp(v, "unit");
            e->fn_verilog = !e->fn_unit;
        } else if (KEY("range")) {
            if (real_pair(x, "range", v, e->range)) return -1;
            e->has_range = 1;
        } else if (KEY("draw")) {
            if (real_pair(x, "draw", v, e->draw)) return -1;
            e->has_draw = 1;
        } else if (KEY("value")) {
            if (base_num_real(v, 1, &e->value)) return BAD("value=%s: expected a number", v);
            e->has_value = 1;
        } else if (KEY("what")) {
            e->what = nl_strdup(x, v, strlen(v));
        } else if (KEY("verilog")) {
            e->verilog = nl_strdup(x, v, strlen(v));
        } else if (KEY("bits")) {
            e->bits_text = nl_strdup(x, v, strlen(v));
        } else if (KEY("table")) {
            e->table_hex = nl_strdup(x, v, strlen(v));
        } else if (KEY("in")) {
            int n = name_list(x, "in", v, &e->in_ref);
            if (n < 0) return -1;
            e->n = n;
        } else {
            /* an operand by name: the key and the record's slot */
            static const struct { const char *key; int op; } refs[] = {
                { "from", OP_A }, { "d", OP_A }, { "a", OP_A }, { "x", OP_A }, { "b", OP_B }, { "en", OP_C },
                { "sel", OP_C }, { "pass", OP_C }, { "rst", OP_RST }, { "clk", OP_CLK } };
            for (size_t k = 0; k < sizeof refs / sizeof refs[0]; k++)
                if (KEY(refs[k].key)) {
                    if (!nl_name_ok(v)) return BAD("%s=%s: not a name", refs[k].key, v);
                    e->ref[refs[k].op] = nl_strdup(x, v, strlen(v));
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
    if (kind == SIM_KIND_CONST && seen_raw + e->has_value != 1) return BAD("const %s: needs one of raw=RAW and value=NUMBER", e->name);
    if (e->has_value && !x->dp) return BAD("const %s: value= is a datapath file's (a netlist gives raw=)", e->name);
    if (e->fn_unit && x->dp && !x->base)
        return BAD("logic %s: fn=unit names a built-in unit's function: a datapath file gives table= or bits=, or names the "
                   "unit first (ideal unit=NAME)", e->name);
    if (kind == SIM_KIND_MUX && !e->in_ref) return BAD("mux %s: needs in=NAME,NAME,...", e->name);
    if (kind == SIM_KIND_LOGIC) {
        if (!e->in_ref) return BAD("logic %s: needs in=NAME,...", e->name);
        if (e->n > 8) return BAD("logic %s: %d inputs (at most 8)", e->name, e->n);
        if (!e->has_area) return BAD("logic %s: needs area=GE (its gates, NAND2 equivalents)", e->name);
        if ((e->table_hex != NULL) + (e->bits_text != NULL) + e->fn_unit + e->fn_verilog != 1)
            return BAD("logic %s: needs one of table=HEX, bits=WIRING, fn=verilog and fn=unit", e->name);
        if (e->fn_verilog && !e->verilog) return BAD("logic %s: fn=verilog needs its verilog=\"TEXT\"", e->name);
    }
    x->nel++;
    return 0;
}

/* The header lines: 0, 1 (not a header line), or -1. */
static int parse_header(nl *x, char **tok, int nt)
{
    const char *k = tok[0];
    int unit_line = !strcmp(k, "unit");
    if (!strcmp(k, "datapath")) {
        if (x->base || x->dp) return BAD("%s: a file has one unit NAME or datapath NAME line", k);
        if (nt < 2 || nt > 3) return BAD("datapath: expected datapath NAME [\"what it computes\"]");
        if (!nl_name_ok(tok[1]) || strchr(tok[1], '.') || strlen(tok[1]) > 31) return BAD("datapath %s: not a name (letters, digits and '_', at most 31)", tok[1]);
        x->dp = 1;
        x->dp_line = x->line;
        x->dp_name = nl_strdup(x, tok[1], strlen(tok[1]));
        x->dp_summary = nl_strdup(x, nt == 3 ? tok[2] : "a datapath file", strlen(nt == 3 ? tok[2] : "a datapath file"));
        unit_cfg_default(NULL, &x->cfg);
        x->cfg.schedule = 0;
        return 0;
    }
    if (strcmp(k, "schedule") && strcmp(k, "width") && strcmp(k, "round") && strcmp(k, "overflow") && strcmp(k, "param")
        && strcmp(k, "fmt") && strcmp(k, "clock") && strcmp(k, "scope") && !unit_line)
        return 1;
    if (nt != (strcmp(k, "param") ? 2 : 3)) return BAD("%s: expected %s", k, strcmp(k, "param") ? "one value" : "NAME VALUE");
    const char *v = tok[1];
    if (unit_line) {
        if (x->dp) return BAD("unit: a file has one unit NAME or datapath NAME line");
        if (x->base) return BAD("unit given twice");
        x->base = unit_find(v);
        if (!x->base) return BAD("unit %s: no such built-in unit (shadesim list)", v);
        unit_cfg_default(x->base, &x->cfg);
        return 0;
    }
    if (x->dp && !strcmp(k, "fmt")) return BAD("fmt: a datapath file gives each element its format (or rule of W)");
    if (x->dp && !x->base && !strcmp(k, "param"))
        return BAD("param: a datapath file has parameters only from the unit its ideal line names (ideal unit=NAME, before)");
    if (!x->base && !x->dp && strcmp(k, "clock") && strcmp(k, "scope")) return BAD("%s before unit NAME", k);
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
        if (!nl_name_ok(v) || strchr(v, '.')) return BAD("clock %s: not a name", v);
        x->clk = nl_strdup(x, v, strlen(v));
    } else {   /* scope */
        if (!nl_name_ok(v)) return BAD("scope %s: a path of names joined by '.'", v);
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
    for (int i = 0; i < 5; i++) if (!strcmp(tok[1], nl_port_names[i])) r = i;
    if (r < 0) return BAD("port %s: expected in, out, in_valid, in_ready or out_valid", tok[1]);
    if (r >= P_IN_VALID && x->nport[r]) return BAD("port %s given twice", tok[1]);
    if (x->nport[r] == UNIT_MAX_IO) return BAD("port %s: more than %d", tok[1], UNIT_MAX_IO);
    if (!nl_name_ok(tok[2])) return BAD("port %s %s: not a name", tok[1], tok[2]);
    if (!x->port_ref[r]) x->port_ref[r] = nl_alloc(x, UNIT_MAX_IO * sizeof(char *));
    x->port_line[r][x->nport[r]] = x->line;
    x->port_ref[r][x->nport[r]++] = nl_strdup(x, tok[2], strlen(tok[2]));
    return 0;
}

int nl_parse_line(nl *x, char *line)
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
    if (x->dp) {
        int d = nl_dp_line(x, tok, nt);
        if (d <= 0) return d;
    }
    if (!strcmp(tok[0], "port")) return parse_port(x, tok, nt);
    int h = parse_header(x, tok, nt);
    if (h <= 0) return h;
    for (int k = 0; k < SIM_KIND__COUNT; k++)
        if (!strcmp(tok[0], sim_kind_name((sim_kind)k)) && k != SIM_KIND_CLOCK) {
            if (!x->base && !x->dp) return BAD("%s before unit NAME (or datapath NAME)", tok[0]);
            return parse_element(x, (sim_kind)k, tok, nt);
        }
    return BAD("%s: not a line of a netlist (netlist, unit, datapath, schedule, ctl, ideal, width, round, overflow, param, fmt, clock, "
               "scope, port, or an element: input wire const reg mux bk add sub mul shift logic)", tok[0]);
}
