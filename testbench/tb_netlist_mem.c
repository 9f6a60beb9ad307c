/* tb_netlist_mem.c - what every part of the netlist and datapath reader
 * uses (tb_netlist_int.h): memory owned by the reader, its one-line
 * messages, names, and new element records. Calls none of them. */
#include "testbench/tb_netlist_int.h"
#include "base/base_out.h"
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ memory */

void *nl_alloc(nl *x, size_t n)
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

char *nl_strdup(nl *x, const char *s, size_t n)
{
    char *p = nl_alloc(x, n + 1);
    memcpy(p, s, n);
    return p;
}

/* ------------------------------------------------------------ messages */

int nl_bad(nl *x, int line, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    for (char *p = msg; *p; p++) if (*p == '\n' || *p == '\r') *p = ' ';   /* a quoted value's lines: one line */
    if (line > 0) snprintf(x->err, x->errlen, "%s:%d: %s", x->path, line, msg);
    else snprintf(x->err, x->errlen, "%s: %s", x->path, msg);
    return -1;
}
int nl_name_ok(const char *s)
{
    if (!*s || *s == '.') return 0;
    for (; *s; s++)
        if (!(nl_name_char(*s) || (*s == '.' && s[1] && s[1] != '.'))) return 0;
    return 1;
}

nl_el *nl_el_new(nl *x, sim_kind kind, const char *name, sim_fmt f)
{
    if (x->nel == x->cap) {
        x->cap = x->cap ? 2 * x->cap : 256;
        nl_el *e = realloc(x->el, (size_t)x->cap * sizeof *e);
        if (!e) base_out_of_memory();
        x->el = e;
    }
    nl_el *e = &x->el[x->nel++];
    memset(e, 0, sizeof *e);
    e->line = x->line;
    e->kind = kind;
    e->name = nl_strdup(x, name, strlen(name));
    const char *dot = strrchr(e->name, '.');
    e->leaf = dot ? dot + 1 : e->name;
    e->scope = NL_NONE;
    e->fmt = f;
    e->r = e->o = NL_NONE;
    for (int i = 0; i < 5; i++) e->op[i] = NL_NONE;
    e->depth = -1;
    e->sig = -1;
    return e;
}
