/* tb_netlist_read.c - netlist text built back into a unit (tb_netlist.h,
 * docs/netlist.md).
 *
 * Reading is two passes: the lines into element records (each checked on
 * its own: kind, name, format, attributes; tb_netlist_parse.c), then the
 * names resolved and
 * the records checked against each other (operands declared, before their
 * use where the constructors need them, truth tables of the right size,
 * ports). Every mistake is one message "PATH:LINE: what", and nothing is
 * built until the whole file is read. Building (tb_netlist_build, called
 * by tb_build) then only calls the constructors of sim_prim.h in the
 * file's order (nl_build, tb_netlist_build.c), so it cannot fail. A
 * datapath file (tb_datapath_parse.c, tb_datapath.c) is read by the same
 * passes and becomes a unit of its own.
 */
#include "testbench/tb_netlist_int.h"
#include "sim/sim_prim.h"
#include "base/base_line.h"
#include "testbench/tb_vexpr.h"
#include "base/base_out.h"
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NL_LINE_MAX ((size_t)1 << 20)   /* a table of 2^12 entries of 16 digits fits */
#define BAD(...) nl_bad(x, x->line, __VA_ARGS__)


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
    if (k == NL_NONE) nl_bad(x, e->line, "%s %s: %s=%s is not declared", kn, e->name, key, name);
    else if (k == NL_CLK && !clock_ok)
        nl_bad(x, e->line, "%s %s: %s=%s is the clock, which only a register's clk= takes", kn, e->name, key, name);
    else if (k != NL_CLK && clock_ok)
        nl_bad(x, e->line, "%s %s: clk=%s is not the clock (%s)", kn, e->name, name, x->clk);
    else if (k >= i && !forward)
        nl_bad(x, e->line, "%s %s: %s=%s is made at line %d, after it (only a register's d= and from= may name a "
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
    int bits = 0, w[8];
    for (int j = 0; j < e->n; j++) bits += (w[j] = x->el[e->in[j]].fmt.width);
    if (e->bits_text) {
        e->bits = nl_alloc(x, sizeof *e->bits);
        if (nl_bits_parse(e->bits_text, e->n, w, e->bits))
            return nl_bad(x, e->line, "logic %s: bits=%s: expected {ITEM,...} of %%K, %%K[B], %%K[H:L] (K an input, "
                          "bits within its width), ~ before one, W'bBITS or W'hHEX; 64 bits at most", e->name,
                          e->bits_text);
    }
    if (e->fn_verilog) {
        char err[300];
        tb_vexpr *p = tb_vexpr_compile(e->verilog, e->n, w, e->fmt.width, err, sizeof err);
        if (!p) return nl_bad(x, e->line, "logic %s: fn=verilog: %s", e->name, err);
        tb_vexpr **v = realloc(x->vx, (size_t)(x->nvx + 1) * sizeof *v);
        if (!v) base_out_of_memory();
        x->vx = v;
        x->vx[x->nvx++] = p;
        e->fn = tb_vexpr_fn;
        e->user = p;
    }
    if (e->table_hex) {
        if (bits > TB_NETLIST_TABLE_BITS)
            return nl_bad(x, e->line, "logic %s: inputs of %d bits in all: a table takes at most %d", e->name, bits,
                          TB_NETLIST_TABLE_BITS);
        size_t rows = (size_t)1 << bits, dig = (size_t)(e->fmt.width + 3) / 4;
        if (strlen(e->table_hex) != rows * dig)
            return nl_bad(x, e->line, "logic %s: table= has %zu hex digits, its %zu rows of %zu need %zu", e->name,
                          strlen(e->table_hex), rows, dig, rows * dig);
        e->table = nl_alloc(x, rows * sizeof *e->table);
        const char *p = e->table_hex;
        uint64_t mask = e->fmt.width >= 64 ? UINT64_MAX : (((uint64_t)1 << e->fmt.width) - 1);
        for (size_t r = 0; r < rows; r++) {
            uint64_t v = 0;
            for (size_t d = 0; d < dig; d++, p++) {
                int h = hexval(*p);
                if (h < 0) return nl_bad(x, e->line, "logic %s: table=: '%c' is not a lower-case hex digit", e->name, *p);
                v = v << 4 | (uint64_t)h;
            }
            if (v & ~mask)
                return nl_bad(x, e->line, "logic %s: table= row %zu: %llx has more bits than %s's %d", e->name, r,
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
            return nl_bad(x, e->line, "logic %s: fn=unit, but unit %s does not build with the file's configuration (%s)",
                          e->name, x->base->name, err);
        }
    }
    sim_signal *s = sim_find(x->ref.c, x->ref.sc, e->name);
    sim_prim_info in;
    int same = s && s->kind == SIM_KIND_LOGIC && !sim_prim_describe(s, &in) && in.n == e->n
               && !memcmp(&s->fmt, &e->fmt, sizeof s->fmt);
    for (int j = 0; same && j < e->n; j++) same = !memcmp(&in.in[j]->fmt, &x->el[e->in[j]].fmt, sizeof(sim_fmt));
    if (!same)
        return nl_bad(x, e->line, "logic %s: fn=unit, but unit %s has no logic element %s with this format and inputs",
                      e->name, x->base->name, e->name);
    e->fn = in.fn;
    e->user = in.user;
    if (!e->verilog) e->verilog = (char *)in.verilog;
    return 0;
}

int nl_resolve_all(nl *x)
{
    if (!x->base && !x->dp) return nl_bad(x, 0, "no unit NAME line (the built-in unit whose reference the design is run against)");
    if (!x->clk) return nl_bad(x, 0, "no clock NAME line");
    nl_names t;
    t.cap = 16;
    while (t.cap < 2 * (size_t)x->nel) t.cap *= 2;
    t.slot = nl_alloc(x, t.cap * sizeof *t.slot);
    memset(t.slot, 0xff, t.cap * sizeof *t.slot);
    for (int i = 0; i < x->nel; i++) {
        if (!strcmp(x->el[i].name, x->clk)) return nl_bad(x, x->el[i].line, "%s: the clock's name", x->el[i].name);
        int k = find(x, &t, x->el[i].name);
        if (k >= 0) return nl_bad(x, x->el[i].line, "%s: declared twice (first at line %d)", x->el[i].name, x->el[k].line);
        for (int j = 0; j < x->nscope; j++)
            if (!strcmp(x->scopes[j], x->el[i].name)) return nl_bad(x, x->el[i].line, "%s: also a scope's name", x->el[i].name);
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
            if ((e->op[k] = resolve(x, &t, i, key, e->ref[k], fwd || x->dp, k == OP_CLK)) == NL_ERR) return -1;
            if (k == OP_A && e->op[k] == i && e->kind != SIM_KIND_REG) return nl_bad(x, e->line, "%s %s: %s=%s names itself", sim_kind_name(e->kind), e->name, key, e->name);
        }
        if (e->n) {
            e->in = nl_alloc(x, (size_t)e->n * sizeof *e->in);
            for (int j = 0; j < e->n; j++)
                if ((e->in[j] = resolve(x, &t, i, "in", e->in_ref[j], x->dp, 0)) == NL_ERR) return -1;
        }
        if (e->kind == SIM_KIND_MUL && e->csd && x->el[e->op[OP_B]].kind != SIM_KIND_CONST)
            return nl_bad(x, e->line, "mul %s: net=csd needs a constant b=", e->name);
        if (e->kind == SIM_KIND_LOGIC && !e->gen && check_logic(x, e)) return -1;
        if (x->dp && (e->kind == SIM_KIND_MUX || e->kind == SIM_KIND_BK) && !e->gen) {
            /* a select is a whole number: a control word, not a value with fraction bits */
            const nl_el *sel = &x->el[e->op[OP_C]];
            if (sel->fmt.fbits || sel->rule)
                return nl_bad(x, e->line, "%s %s: %s=%s is a number of format %s; a select takes a control signal (ctl) "
                              "or another whole number", sim_kind_name(e->kind), e->name, e->kind == SIM_KIND_MUX ? "sel" : "pass",
                              sel->name, sel->rule ? sel->rule->text : "with fraction bits");
        }
        if (e->kind == SIM_KIND_SHIFT) {
            /* a left shift past the binary point is made on the raw: it
             * must stay within the exact 128-bit value */
            sim_fmt f = x->el[e->op[OP_A]].fmt;
            int sa = e->shift > f.fbits ? e->shift - f.fbits : 0;
            if (f.width + sa > 126)
                return nl_bad(x, e->line, "shift %s: by=%d takes %s's %d bits past 126", e->name, e->shift,
                              e->ref[OP_A], f.width + sa);
        }
    }
    for (int r = 0; r < 5; r++) {
        x->port[r] = nl_alloc(x, UNIT_MAX_IO * sizeof(int));
        for (int j = 0; j < x->nport[r]; j++) {
            int k = find(x, &t, x->port_ref[r][j]);
            if (k < 0) return nl_bad(x, x->port_line[r][j], "port %s %s is not declared", nl_port_names[r], x->port_ref[r][j]);
            x->port[r][j] = k;
            /* the testbench drives these: inputs nothing else drives */
            if ((r == P_IN || r == P_IN_VALID) && (x->el[k].kind != SIM_KIND_INPUT || x->el[k].ref[OP_A]))
                return nl_bad(x, x->port_line[r][j], "port %s %s: not an input without from= (the testbench drives it)",
                              nl_port_names[r], x->port_ref[r][j]);
        }
    }
    if (x->dp) {
        for (int i = 0; i < x->nel; i++)
            if (x->el[i].fn_unit && take_unit_fn(x, &x->el[i])) return -1;
        return 0;
    }
    int nin = unit_n_in(x->base), nout = unit_n_out(x->base);
    if (x->nport[P_IN] != nin || x->nport[P_OUT] != nout)
        return nl_bad(x, 0, "%d input and %d output ports; unit %s has %d and %d", x->nport[P_IN], x->nport[P_OUT],
                      x->base->name, nin, nout);
    if (!x->nport[P_IN_VALID] || !x->nport[P_IN_READY] || !x->nport[P_OUT_VALID])
        return nl_bad(x, 0, "needs the handshake's ports: port in_valid, port in_ready and port out_valid");
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

int tb_netlist_is(const unit_desc *u)
{
    const nl *x = nl_of(u);
    return x && !x->dp;
}

void nl_free(nl *x)
{
    if (x->dp) nl_dp_release(x);
    if (x->ref.c) sim_free(x->ref.c);
    for (int i = 0; i < x->nvx; i++) tb_vexpr_free(x->vx[i]);
    free(x->vx);
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


int tb_netlist_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk, unit_io *io,
                     char *err, size_t errlen)
{
    nl *x = nl_of(u);
    if (!x) { snprintf(err, errlen, "not a netlist's unit"); return -1; }
    return nl_build(x, NULL, 0, c, sc, clk, io, err, errlen);
}

/* The formats of the unit's signals: its rule at the file's width with its
 * fmt lines, then each signal's as the element of its name at the top of
 * the unit's scope has it (the ports' formats are the elements'). */
static int formats_of(nl *x)
{
    char err[600];
    if (tb_formats(x->base, &x->cfg, (const char *const *)x->fmt, x->nfmt, &x->fm, err, sizeof err))
        return nl_bad(x, 0, "the configuration: %s", err);
    for (int i = 0; i < x->base->nsigs; i++)
        for (int k = 0; k < x->nel; k++)
            if (x->el[k].scope == NL_NONE && !strcmp(x->el[k].name, x->base->sigs[i].name)) x->fm.f[i] = x->el[k].fmt;
    return 0;
}

static const unit_desc *finish(nl *x, unit_cfg *cfg, unit_fmts *fm)
{
    if (x->dp) {
        const unit_desc *d = NULL;
        if (nl_dp_close(x) || nl_dp_rules(x) || nl_resolve_all(x) || !(d = nl_dp_finish(x, cfg, fm))) { nl_free(x); return NULL; }
    } else {
        if (nl_resolve_all(x) || formats_of(x)) { nl_free(x); return NULL; }
        x->desc = *x->base;
    }
    nl **r = realloc(reg, (nreg + 1) * sizeof *r);
    if (!r) base_out_of_memory();
    reg = r;
    reg[nreg++] = x;
    if (!x->dp) {
        *cfg = x->cfg;
        *fm = x->fm;
    }
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
        int rc = memchr(p, 0, n) ? BAD("not a text file (NUL byte)") : nl_parse_line(x, line);
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
        else if (n == BASE_LINE_ERR) rc = nl_bad(x, 0, "%s", strerror(errno));
        else rc = nl_parse_line(x, line);
        if (rc) break;
    }
    free(line);
    if (!std) fclose(f);
    if (rc) { nl_free(x); return NULL; }
    if (x->line == 0) { nl_bad(x, 0, "empty: not a netlist"); nl_free(x); return NULL; }
    x->line = 0;
    return finish(x, cfg, fm);
}
