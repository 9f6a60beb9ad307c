/* tb_cosim.c - co-simulation against shadesim (see tb_verilog.h): the
 * export, or the user's own RTL whose top module and ports the external
 * simulator itself reports (so parameters, macros and both port-list
 * styles are resolved as the simulator resolves them). */
#define _XOPEN_SOURCE 700          /* realpath */
#include "testbench/tb_verilog.h"
#include "base/base_out.h"
#include "base/base_proc.h"
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A beat line "CYCLE RAW...": the raws alone (by_items), else all of it. */
static const char *beat_text(const char *line, int by_items)
{
    const char *sp = by_items ? strchr(line, ' ') : NULL;
    return sp ? sp : line;
}

/* A tool's command line (it starts with "cd DIR &&"), as base_proc runs
 * it: in a process group of its own that a signal to shadesim ends (the
 * caller then sees base_proc_signal), within limit_s seconds of wall
 * time, and with every file it writes capped at cap_bytes (ulimit -f: an
 * RTL printing without end, `initial forever $display`, filled the
 * temporary folder at 50 MB/s). Its exit status; RUN_TIMEOUT past the
 * limit; RUN_CAPPED when a file reached the cap (SIGXFSZ); -1 when no
 * process could be made or a signal ended it. */
enum { RUN_TIMEOUT = -2, RUN_CAPPED = -3 };
static int run_tool(const char *cmd, const char *step, double limit_s, unsigned long long cap_bytes)
{
    char err[200];
    size_t n = strlen(cmd) + 64;
    char *c = malloc(n);
    if (!c) base_out_of_memory();
    /* POSIX ulimit -f counts 512-byte blocks (dash; bash counts 1024,
     * which only doubles the cap) */
    snprintf(c, n, "ulimit -f %llu && %s", cap_bytes / 512 + 1, cmd);
    base_proc p = { "cosim", step, NULL, NULL, NULL, base_proc_now(), limit_s, 0, 0, 0 };
    int r = base_proc_run(c, &p, err, sizeof err);
    free(c);
    if (r == BASE_PROC_TIMEOUT) return RUN_TIMEOUT;
    if (r != BASE_PROC_DONE) return -1;
    return p.status == 128 + SIGXFSZ ? RUN_CAPPED : p.status;
}

/* The message of a tool run that ended by run_tool's limits, into msg: 1,
 * else 0 (rc is the tool's own exit status or -1). */
static int limit_msg(int rc, const char *sname, double limit_s, unsigned long long cap, char *msg, size_t msglen)
{
    if (rc == RUN_TIMEOUT)
        snprintf(msg, msglen, "cosim: %s stopped after its time limit of %g s (a zero-delay loop in the RTL "
                 "keeps simulated time from advancing; --timeout S gives more)", sname, limit_s);
    else if (rc == RUN_CAPPED)
        snprintf(msg, msglen, "cosim: %s stopped: a file it wrote reached %llu MiB (an RTL that prints "
                 "without end?)", sname, cap >> 20);
    else return 0;
    return 1;
}

/* Files the tools may write: compiled designs and logs, and the results,
 * a line of at most 24 bytes and 17 per output for each beat. */
static unsigned long long file_cap(size_t beats, int n_out)
{
    return (64ULL << 20) + (unsigned long long)beats * (24 + 17 * (unsigned long long)n_out);
}

/* First differing line of two files: 0 same, -1 a file missing, else its
 * number (1-based); both lines (without newline) and the lines read.
 * by_items: the cycles are not compared, only the raws, in order. */
static long first_diff(const char *pa, const char *pb, char *la, char *lb, size_t len, long *lines, int by_items)
{
    FILE *a = fopen(pa, "r"), *b = fopen(pb, "r");
    long n = 0, bad = 0;
    la[0] = lb[0] = 0;
    while (a && b) {
        char *x = fgets(la, (int)len, a), *y = fgets(lb, (int)len, b);
        if (!x && !y) break;
        n++;
        if (!x) la[0] = 0;
        if (!y) lb[0] = 0;
        if (!x || !y || strcmp(beat_text(la, by_items), beat_text(lb, by_items))) { bad = n; break; }
    }
    if (!a || !b) bad = -1;
    if (a) fclose(a);
    if (b) fclose(b);
    la[strcspn(la, "\n")] = 0;
    lb[strcspn(lb, "\n")] = 0;
    *lines = n;
    return bad;
}

/* s single-quoted for sh, appended to buf (no room: the text cut, which
 * the caller's bounded buffers make a failed command, never a wrong one). */
static void sq(char *buf, size_t len, const char *s)
{
    size_t o = strlen(buf);
    if (o + 1 < len) buf[o++] = '\'';
    for (; *s && o + 5 < len; s++) {
        if (*s == '\'') { memcpy(buf + o, "'\\''", 4); o += 4; }
        else buf[o++] = *s;
    }
    if (o + 1 < len) buf[o++] = '\'';
    buf[o < len ? o : len - 1] = 0;
}

/* "cd 'DIR'" into buf: a relative DIR as './DIR', so that a folder named
 * "-x" is not an option of cd, nor "-" its previous folder. */
static void cd_dir(char *buf, size_t len, const char *dir)
{
    size_t n = strlen(dir) + 3;
    char *d = malloc(n);
    if (!d) base_out_of_memory();
    snprintf(d, n, "%s%s", dir[0] == '/' ? "" : "./", dir);
    snprintf(buf, len, "cd ");
    sq(buf, len, d);
    free(d);
    /* the tools' own temporaries (iverilog's ivrl*) in the folder too: a
     * signal that stops them midway leaves nothing in $TMPDIR */
    size_t at = strlen(buf);
    snprintf(buf + at, len - at, " && TMPDIR=\"$PWD\" && export TMPDIR");
}

/* The first line of a log that says "error" (else its first line), for a
 * one-line message. */
static void log_line(const char *path, char *out, size_t len)
{
    FILE *f = fopen(path, "r");
    char line[400], first[400] = "";
    out[0] = 0;
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!first[0]) snprintf(first, sizeof first, "%s", line);
        if (strstr(line, "rror")) { snprintf(out, len, "%s", line); break; }
    }
    if (f) fclose(f);
    if (!out[0]) snprintf(out, len, "%s", first[0] ? first : "no message");
}

static int ext_sv(const char *const *files, int n)
{
    for (int i = 0; i < n; i++) {
        size_t l = strlen(files[i]);
        if (l > 3 && !strcmp(files[i] + l - 3, ".sv")) return 1;
    }
    return 0;
}

/* The value of attribute `key` in an XML tag (copied to buf), or NULL. */
static const char *xml_attr(const char *tag, const char *key, char *buf, size_t len)
{
    char pat[40];
    snprintf(pat, sizeof pat, " %s=\"", key);
    const char *p = strstr(tag, pat), *end = strchr(tag, '>');
    if (!p || (end && p > end)) return NULL;
    p += strlen(pat);
    size_t n = strcspn(p, "\"");
    if (n >= len) n = len - 1;
    memcpy(buf, p, n);
    buf[n] = 0;
    return buf;
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n + 4096 + 1 > cap) {
            cap = cap ? 2 * cap : 65536;
            char *nb = realloc(buf, cap);
            if (!nb) { free(buf); fclose(f); return NULL; }
            buf = nb;
        }
        size_t r = fread(buf + n, 1, 4096, f);
        n += r;
        if (r == 0) break;
    }
    fclose(f);
    buf[n] = 0;
    return buf;
}

/* The top-level modules the simulator found, any number of them, names
 * of any length (a fixed 16 of 127 characters lost the one named like the
 * unit among more, and miscounted them); after[i]: where root i's lines
 * go on in the simulator's file (Icarus). */
typedef struct rtl_roots {
    char **name;
    const char **after;
    int n, cap;
} rtl_roots;

static void roots_add(rtl_roots *r, const char *name, size_t len, const char *after)
{
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 16;
        char **nn = realloc(r->name, (size_t)r->cap * sizeof *nn);
        if (!nn) base_out_of_memory();
        r->name = nn;
        const char **na = realloc(r->after, (size_t)r->cap * sizeof *na);
        if (!na) base_out_of_memory();
        r->after = na;
    }
    if (!(r->name[r->n] = strndup(name, len))) base_out_of_memory();
    r->after[r->n++] = after;
}

static void roots_free(rtl_roots *r)
{
    for (int i = 0; i < r->n; i++) free(r->name[i]);
    free(r->name);
    free(r->after);
}

/* The module to check among the top-level ones the simulator found: the
 * one asked for, else one named like the unit, else the only one. Its
 * index, or -1 with a message (the names as they fit, their count). */
static int choose_top(const rtl_roots *r, const char *want, const char *unit, char *err, size_t errlen)
{
    if (want && *want) {
        for (int i = 0; i < r->n; i++) if (!strcmp(r->name[i], want)) return i;
        snprintf(err, errlen, "cosim: no top-level module %s in the RTL", want);
        return -1;
    }
    for (int i = 0; i < r->n; i++) if (!strcmp(r->name[i], unit)) return i;
    if (r->n == 1) return 0;
    if (r->n == 0) { snprintf(err, errlen, "cosim: the RTL has no module"); return -1; }
    size_t o = (size_t)snprintf(err, errlen, "cosim: %d top-level modules in the RTL (", r->n);
    int shown = 0;
    for (int i = 0; i < r->n && o + strlen(r->name[i]) + 48 < errlen; i++, shown++)
        o += (size_t)snprintf(err + o, errlen - o, "%s%.200s", i ? ", " : "", r->name[i]);
    if (shown < r->n && o < errlen) o += (size_t)snprintf(err + o, errlen - o, ", ...");
    if (o < errlen) snprintf(err + o, errlen - o, "): choose one with --top NAME");
    return -1;
}

static int add_port(tb_port *p, char **names, int n, int maxp, const char *name, int width, int is_output,
                    char *err, size_t errlen)
{
    if (n >= maxp) { snprintf(err, errlen, "cosim: the RTL's top module has more than %d ports", maxp); return -1; }
    names[n] = strdup(name);
    if (!names[n]) base_out_of_memory();
    p[n] = (tb_port){ names[n], width, is_output };
    return n + 1;
}

/* One line of txt from *at: its start and length (no newline); 0 at the
 * end. */
static int next_line(const char **at, const char **line, size_t *len)
{
    if (!**at) return 0;
    size_t n = strcspn(*at, "\n");
    *line = *at;
    *len = n;
    *at += n + ((*at)[n] == '\n');
    return 1;
}

/* In line[0..len): the text between the quotes after `key` (key ends
 * with the opening quote), its start and length; NULL when absent. */
static const char *quoted_after(const char *line, size_t len, const char *key, size_t *qlen)
{
    size_t kl = strlen(key);
    for (size_t i = 0; i + kl <= len; i++)
        if (!memcmp(line + i, key, kl)) {
            const char *q = line + i + kl, *e = memchr(q, '"', len - (size_t)(q - line));
            if (!e) return NULL;
            *qlen = (size_t)(e - q);
            return q;
        }
    return NULL;
}

/* 1 if line[0..len) holds text. */
static int has_text(const char *line, size_t len, const char *text)
{
    size_t tl = strlen(text);
    for (size_t i = 0; i + tl <= len; i++) if (!memcmp(line + i, text, tl)) return 1;
    return 0;
}

/* Icarus's compiled file: ".scope module, "inst" "type" FILE LINE;" for a
 * root (a child's ends ", S_parent;"), then its ".port_info K /INPUT
 * WIDTH "name";" lines, before the next scope. */
static int ports_icarus(const char *txt, const char *want, const char *unit, char *top, size_t toplen,
                        tb_port *p, char **names, int maxp, char *err, size_t errlen)
{
    rtl_roots r = { NULL, NULL, 0, 0 };
    const char *line;
    size_t len;
    int n = 0;
    for (const char *at = txt; next_line(&at, &line, &len); ) {
        size_t il, tl;
        const char *inst = quoted_after(line, len, " .scope module, \"", &il);
        if (!inst) continue;
        const char *rest = inst + il + 1;
        const char *type = quoted_after(rest, len - (size_t)(rest - line), " \"", &tl);
        if (!type) continue;
        const char *tail = type + tl + 1;
        /* a child scope names its parent at its line's end: ", S_0x..." */
        if (!has_text(tail, len - (size_t)(tail - line), ", S_")) roots_add(&r, type, tl, at);
    }
    int t = choose_top(&r, want, unit, err, errlen);
    if (t < 0) { roots_free(&r); return -1; }
    if (strlen(r.name[t]) >= toplen) {
        snprintf(err, errlen, "cosim: the top module's name has more than %zu characters", toplen - 1);
        roots_free(&r);
        return -1;
    }
    snprintf(top, toplen, "%s", r.name[t]);
    for (const char *at = r.after[t]; n >= 0 && next_line(&at, &line, &len) && !has_text(line, len, ".scope "); ) {
        char dir[16], name[1100], buf[1200];
        int k, w;
        if (len >= sizeof buf) continue;
        memcpy(buf, line, len);
        buf[len] = 0;
        if (sscanf(buf, " .port_info %d /%15s %d \"%1099[^\"]\"", &k, dir, &w, name) != 4) continue;
        n = add_port(p, names, n, maxp, name, w, !strcmp(dir, "INPUT") ? 0 : !strcmp(dir, "OUTPUT") ? 1 : 2, err, errlen);
    }
    roots_free(&r);
    return n;
}

/* A Verilator dtype's width in bits: a basic type's from its bounds, a
 * reference's or a typedef's from what it refers to, a (packed) struct's
 * or union's from its members (sum, or widest), a packed array's from
 * its range times its element. -1 when unknown (e.g. unpacked). */
static int dtype_width(const char *txt, const char *id, int depth)
{
    if (depth > 32) return -1;
    char pat[48];
    snprintf(pat, sizeof pat, " id=\"%.30s\"", id);
    for (const char *d = strstr(txt, pat); d; d = strstr(d + 1, pat)) {
        const char *tag = d;
        while (tag > txt && *tag != '<') tag--;
        char kind[32], lb[32], rb[32], sub[32];
        size_t kl = strcspn(tag + 1, " >");
        if (kl >= sizeof kind) continue;
        memcpy(kind, tag + 1, kl);
        kind[kl] = 0;
        if (!strcmp(kind, "basicdtype")) {
            if (xml_attr(tag, "left", lb, sizeof lb) && xml_attr(tag, "right", rb, sizeof rb))
                return abs(atoi(lb) - atoi(rb)) + 1;
            return 1;
        }
        if (!strcmp(kind, "refdtype") || !strcmp(kind, "typedef") || !strcmp(kind, "enumdtype")) {
            if (!xml_attr(tag, "sub_dtype_id", sub, sizeof sub)) return -1;
            return dtype_width(txt, sub, depth + 1);
        }
        if (!strcmp(kind, "structdtype") || !strcmp(kind, "uniondtype")) {
            /* (Verilator 5 writes no packed="..."; a port's struct is packed) */
            const char *end = strstr(tag, kind[0] == 's' ? "</structdtype>" : "</uniondtype>");
            int w = 0;
            for (const char *m = strstr(tag, "<memberdtype "); m && (!end || m < end); m = strstr(m + 1, "<memberdtype ")) {
                if (!xml_attr(m, "sub_dtype_id", sub, sizeof sub)) return -1;
                int mw = dtype_width(txt, sub, depth + 1);
                if (mw < 0) return -1;
                w = kind[0] == 's' ? w + mw : (mw > w ? mw : w);
            }
            return w ? w : -1;
        }
        if (!strcmp(kind, "packarraydtype")) {
            if (!xml_attr(tag, "sub_dtype_id", sub, sizeof sub)) return -1;
            int ew = dtype_width(txt, sub, depth + 1);
            const char *end = strstr(tag, "</packarraydtype>"), *rg = strstr(tag, "<range");
            if (ew < 0 || !rg || (end && rg > end)) return -1;
            /* the range's bounds: its two <const name="32'sh..."> children */
            const char *c1 = strstr(rg, "<const "), *c2 = c1 ? strstr(c1 + 1, "<const ") : NULL;
            char v1[48], v2[48];
            if (!c1 || !c2 || !xml_attr(c1, "name", v1, sizeof v1) || !xml_attr(c2, "name", v2, sizeof v2)) return -1;
            const char *h1 = strchr(v1, 'h'), *h2 = strchr(v2, 'h');
            if (!h1 || !h2) return -1;
            long a = strtol(h1 + 1, NULL, 16), b2 = strtol(h2 + 1, NULL, 16);
            return (int)(labs(a - b2) + 1) * ew;
        }
        return -1;
    }
    return -1;
}

/* Verilator's --xml-only file: top-level cells (hier without a dot) name
 * the roots; the module's <var dir=...> tags its ports, their dtypes
 * their widths (dtype_width). */
static int ports_verilator(const char *txt, const char *want, const char *unit, char *top, size_t toplen,
                           tb_port *p, char **names, int maxp, char *err, size_t errlen)
{
    rtl_roots r = { NULL, NULL, 0, 0 };
    char buf[1100], hier[1100];
    int n = 0;
    for (const char *c = strstr(txt, "<cell "); c; c = strstr(c + 1, "<cell "))
        if (xml_attr(c, "hier", hier, sizeof hier) && !strchr(hier, '.') && xml_attr(c, "submodname", buf, sizeof buf))
            roots_add(&r, buf, strlen(buf), NULL);
    int t = choose_top(&r, want, unit, err, errlen);
    if (t >= 0) snprintf(top, toplen, "%s", r.name[t]);
    roots_free(&r);
    if (t < 0) return -1;
    const char *m = txt;
    while ((m = strstr(m, "<module ")) && !(xml_attr(m, "name", buf, sizeof buf) && !strcmp(buf, top))) m++;
    if (!m) { snprintf(err, errlen, "cosim: verilator did not describe module %s", top); return -1; }
    const char *end = strstr(m, "</module>");
    for (const char *v = strstr(m, "<var "); v && (!end || v < end); v = strstr(v + 1, "<var ")) {
        char name[1100], dir[16], id[32];
        if (!xml_attr(v, "dir", dir, sizeof dir) || !xml_attr(v, "name", name, sizeof name)
            || !xml_attr(v, "dtype_id", id, sizeof id)) continue;
        n = add_port(p, names, n, maxp, name, dtype_width(txt, id, 0), !strcmp(dir, "input") ? 0 : !strcmp(dir, "output") ? 1 : 2,
                     err, errlen);
        if (n < 0) return -1;
    }
    return n;
}

int tb_rtl_ports(const char *const *files, int nfiles, const char *want_top, const char *unit,
                 int sim, double timeout_s, const char *dir, char *topbuf, size_t toplen, tb_port *p, char **names, int maxp,
                 char *err, size_t errlen)
{
    size_t cl = 2048;
    for (int i = 0; i < nfiles; i++) cl += 4 * strlen(files[i]) + 4;
    cl += 4 * strlen(dir) + (want_top ? 4 * strlen(want_top) : 0);
    char *cmd = calloc(1, cl), out[PATH_MAX + 32], log[PATH_MAX + 32];
    if (!cmd) base_out_of_memory();
    const char *sname = sim == TB_SIM_ICARUS ? "icarus" : "verilator";
    cd_dir(cmd, cl, dir);
    if (sim == TB_SIM_ICARUS) {
        snprintf(cmd + strlen(cmd), cl - strlen(cmd), " && iverilog -g%s -o rtlports.vvp", ext_sv(files, nfiles) ? "2012" : "2005");
        if (want_top && *want_top) { strcat(cmd, " -s "); sq(cmd, cl, want_top); }
    } else {
        snprintf(cmd + strlen(cmd), cl - strlen(cmd), " && verilator --xml-only -Wno-fatal -Wno-lint -Wno-style "
                 "--timescale 1ns/1ps --Mdir obj_rtlports --xml-output rtlports.xml");
        if (want_top && *want_top) { strcat(cmd, " --top-module "); sq(cmd, cl, want_top); }
    }
    for (int i = 0; i < nfiles; i++) { strcat(cmd, " "); sq(cmd, cl, files[i]); }
    strcat(cmd, " >rtlports.log 2>&1");
    snprintf(out, sizeof out, "%s/%s", dir, sim == TB_SIM_ICARUS ? "rtlports.vvp" : "rtlports.xml");
    snprintf(log, sizeof log, "%s/rtlports.log", dir);
    remove(out);
    double lim = timeout_s > 0 ? timeout_s : TB_COSIM_TIMEOUT_S;
    int rc = run_tool(cmd, sname, lim, file_cap(0, 0));
    free(cmd);
    if (limit_msg(rc, sname, lim, file_cap(0, 0), err, errlen)) return -1;
    if (rc != 0) {
        char line[400];
        log_line(log, line, sizeof line);
        snprintf(err, errlen, "cosim: %s cannot read the RTL: %s", sname, line);
        return -1;
    }
    char *txt = slurp(out);
    if (!txt) { snprintf(err, errlen, "cosim: %s described no design", sname); return -1; }
    int n = sim == TB_SIM_ICARUS ? ports_icarus(txt, want_top, unit, topbuf, toplen, p, names, maxp, err, errlen)
                                 : ports_verilator(txt, want_top, unit, topbuf, toplen, p, names, maxp, err, errlen);
    free(txt);
    return n;
}

/* The user's top module against the unit's ports: every port there with
 * its direction and width; more outputs are allowed (left unconnected),
 * more inputs are not (they would float). 0, or -1 with a message. */
static int check_ports(const unit_desc *u, const unit_fmts *fm, sim_vreset reset, const char *top,
                       const tb_port *got, int ngot, char *err, size_t errlen)
{
    tb_port want[TB_MAX_PORTS];
    int nw = tb_verilog_ports(u, fm, reset, want);
    static const char *const dirs[] = { "an input", "an output", "an inout" };
    for (int i = 0; i < nw; i++) {
        int k = 0;
        while (k < ngot && strcmp(got[k].name, want[i].name)) k++;
        if (k == ngot) {
            snprintf(err, errlen, "cosim: module %s has no port %s (%s of %d bit%s)%s", top, want[i].name,
                     dirs[want[i].is_output], want[i].width, want[i].width == 1 ? "" : "s",
                     !strcmp(want[i].name, "rst") ? "; --reset none for a design without reset" : "");
            return -1;
        }
        if (got[k].is_output != want[i].is_output) {
            snprintf(err, errlen, "cosim: module %s: port %s is %s, expected %s", top, want[i].name,
                     dirs[got[k].is_output], dirs[want[i].is_output]);
            return -1;
        }
        if (got[k].width != want[i].width) {
            snprintf(err, errlen, "cosim: module %s: port %s has %d bit%s, expected %d (its format at these options)",
                     top, want[i].name, got[k].width, got[k].width == 1 ? "" : "s", want[i].width);
            return -1;
        }
    }
    for (int k = 0; k < ngot; k++) {
        if (got[k].is_output == 1) continue;
        int i = 0;
        while (i < nw && strcmp(got[k].name, want[i].name)) i++;
        if (i == nw) {
            snprintf(err, errlen, "cosim: module %s has %s port %s that the unit does not have", top,
                     dirs[got[k].is_output], got[k].name);
            return -1;
        }
    }
    return 0;
}

/* The user's RTL mismatch, spelled out: the item, its input raws (and
 * values), each output's expected and actual raw and the clock. */
static void rtl_mismatch(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs,
                         long beat, int beats, const char *exp, const char *got, const char *sname,
                         char *msg, size_t msglen)
{
    size_t item = (size_t)(beat / beats), o = 0;
    #define ADD(...) do { if (o < msglen) o += (size_t)snprintf(msg + o, msglen - o, __VA_ARGS__); } while (0)
    ADD("MISMATCH at item %zu", item);
    if (beats > 1) ADD(" beat %ld", beat % beats);
    ADD(" (inputs");
    for (int i = 0, k = 0; i < u->nsigs && item < vs->n_rows; i++) {
        if (u->sigs[i].role != UNIT_SIG_IN) continue;
        sim_fmt q = fm->f[i];
        int64_t raw = tb_stimulus_raw(cfg, fm, vs, item, i, k++);
        uint64_t m = q.width >= 64 ? UINT64_MAX : (((uint64_t)1 << q.width) - 1);
        ADD(" %s=%0*llx (%.6g)", u->sigs[i].name, (q.width + 3) / 4, (unsigned long long)((uint64_t)raw & m),
            sim_fx_to_real(raw, q));
    }
    ADD("): expected");
    /* "CYCLE RAW..." both */
    char e[512], g[512];
    snprintf(e, sizeof e, "%s", exp);
    snprintf(g, sizeof g, "%s", got);
    char *se, *sg, *te = strtok_r(e, " ", &se), *tg = strtok_r(g, " ", &sg);
    const char *ecyc = te ? te : "?", *gcyc = tg;
    char gv[300] = "";
    size_t go = 0;
    for (int i = 0; i < u->nsigs; i++) {
        if (u->sigs[i].role != UNIT_SIG_OUT) continue;
        te = strtok_r(NULL, " ", &se);
        tg = gcyc ? strtok_r(NULL, " ", &sg) : NULL;
        ADD(" %s=%s", u->sigs[i].name, te ? te : "?");
        if (go < sizeof gv) go += (size_t)snprintf(gv + go, sizeof gv - go, " %s=%s", u->sigs[i].name, tg ? tg : "?");
    }
    ADD(" at clock %s, %s", ecyc, sname);
    if (gcyc) ADD(" gave%s at clock %s", gv, gcyc);
    else ADD(" gave nothing (no more output beats)");
    #undef ADD
}

/* The cycle of beat lines k0 and k1 (0-based) of a results file: 0, or
 * -1 when it has fewer lines. */
static int beat_cycles(const char *path, long k0, long k1, unsigned long long *c0, unsigned long long *c1)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int got = 0;
    for (long k = 0; f && got < 2 && fgets(line, sizeof line, f); k++) {
        if (k == k0) { *c0 = strtoull(line, NULL, 10); got++; }
        if (k == k1) { *c1 = strtoull(line, NULL, 10); got += k1 != k0; }
    }
    if (f) fclose(f);
    return got == 2 ? 0 : -1;
}

/* --match items, all equal: the RTL's latency (the cycle of its first
 * beat) and items per clock (steady state, first beats of the first and
 * last items, as tb_run measures the model's) beside shadesim's. */
static void items_verdict(const tb_result *r, const char *res, const char *sname, char *msg, size_t msglen)
{
    unsigned long long c0 = 0, c1 = 0;
    long last = (long)((r->vectors ? r->vectors - 1 : 0) * (size_t)r->beats);
    size_t o = (size_t)snprintf(msg, msglen, "bit-exact item by item, %zu items (%s)", r->vectors, sname);
    if (o >= msglen || beat_cycles(res, 0, last, &c0, &c1)) return;
    o += (size_t)snprintf(msg + o, msglen - o, ": RTL latency %llu clocks", c0);
    if (o < msglen && r->vectors > 1 && c1 > c0)
        o += (size_t)snprintf(msg + o, msglen - o, ", %.4g items per clock", (double)(r->vectors - 1) / (double)(c1 - c0));
    if (o < msglen)
        o += (size_t)snprintf(msg + o, msglen - o, "; shadesim latency %llu clocks", (unsigned long long)r->latency);
    if (o < msglen && r->vectors > 1 && r->cycles_per_item > 0)
        snprintf(msg + o, msglen - o, ", %.4g items per clock", 1.0 / r->cycles_per_item);
}

int tb_cosim_opt(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs,
                 const tb_cosim_opts *o, int sim, const char *dir, char *msg, size_t msglen)
{
    static const tb_cosim_opts dflt = { SIM_VRESET_SYNC, NULL, 0, NULL, 0, 0 };
    if (!o) o = &dflt;
    tb_result r;
    char err[600];
    int t = tb_run(u, cfg, fm, vs, NULL, &r, err, sizeof err);
    if (t != TB_OK) { snprintf(msg, msglen, "%s", err); return t == TB_BADINPUT ? TB_COSIM_BADINPUT : TB_COSIM_FAILED; }
    if (base_proc_signal()) {   /* held by the caller (base_proc_hold): nothing written yet */
        tb_result_free(&r);
        snprintf(msg, msglen, "cosim: interrupted");
        return TB_COSIM_FAILED;
    }
    int rc = TB_COSIM_FAILED;
    const char *sname = sim == TB_SIM_ICARUS ? "icarus" : "verilator";
    size_t pl = strlen(dir) + 64, cl = 4 * pl + 1024;
    for (int i = 0; i < o->nrtl; i++) cl += 4 * (strlen(o->rtl[i]) + PATH_MAX) + 4;   /* each quoted absolute path */
    char *in = malloc(pl), *ex = malloc(pl), *res = malloc(pl), *cmd = calloc(1, cl), *files = calloc(1, cl);
    char *names[64] = { NULL };
    char top[256];
    if (!in || !ex || !res || !cmd || !files) base_out_of_memory();
    const char *n = u->name;
    if (base_out_mkdirs(dir, msg, msglen)) { rc = TB_COSIM_BADINPUT; goto done; }
    if (o->nrtl) {
        /* the user's files by their absolute paths (the tools run in dir) */
        int ng = -1;
        tb_port got[64];
        char **absv = calloc((size_t)o->nrtl, sizeof *absv);
        if (!absv) base_out_of_memory();
        for (int i = 0; i < o->nrtl && ng == -1; i++) {
            absv[i] = realpath(o->rtl[i], NULL);
            if (!absv[i]) { snprintf(msg, msglen, "cosim: --rtl %s: %s", o->rtl[i], strerror(errno)); ng = -2; break; }
            /* a FIFO would block the simulator's reader for ever, a folder
             * gives its message without the name: regular files only */
            struct stat st;
            if (stat(absv[i], &st) || !S_ISREG(st.st_mode)) {
                snprintf(msg, msglen, "cosim: --rtl %s: not a regular file (%s)", o->rtl[i],
                         S_ISDIR(st.st_mode) ? "a folder" : S_ISFIFO(st.st_mode) ? "a FIFO" : "a device or socket");
                ng = -2;
                break;
            }
            strcat(files, " ");
            sq(files, cl, absv[i]);
        }
        if (ng == -1)
            ng = tb_rtl_ports((const char *const *)absv, o->nrtl, o->top, n, sim, o->timeout_s, dir, top, sizeof top, got, names, 64, msg, msglen);
        for (int i = 0; i < o->nrtl; i++) free(absv[i]);
        free(absv);
        if (ng < 0 || check_ports(u, fm, o->reset, top, got, ng, msg, msglen)) { rc = TB_COSIM_BADINPUT; goto done; }
        char *tb = tb_verilog_tb_text(u, cfg, fm, o->reset, top);
        snprintf(in, pl, "%s/%s_tb.v", dir, n);
        int w = tb ? base_out_write_all(in, tb, strlen(tb), msg, msglen) : (snprintf(msg, msglen, "out of memory"), -1);
        free(tb);
        if (w) { rc = TB_COSIM_BADINPUT; goto done; }
    } else {
        if (tb_verilog_write(u, cfg, fm, o->reset, dir, NULL, msg, msglen)) { rc = TB_COSIM_BADINPUT; goto done; }
        snprintf(files, cl, " %s.v", n);
        snprintf(top, sizeof top, "%s", n);
    }
    snprintf(in, pl, "%s/stimulus.hex", dir);
    snprintf(ex, pl, "%s/stimulus.hex.expect", dir);
    snprintf(res, pl, "%s/%s.out", dir, sname);
    if (tb_stimulus_write(u, cfg, fm, vs, &r, in, ex, msg, msglen)) { rc = TB_COSIM_BADINPUT; goto done; }
    remove(res);
    size_t words = vs->n_rows * (size_t)unit_n_in(u);
    /* a design slower than shadesim's by more than 2x, or stuck, stops */
    unsigned long long limit = 2 * (unsigned long long)r.cycles + 1000;
    cd_dir(cmd, cl, dir);
    size_t at = strlen(cmd);
    if (sim == TB_SIM_ICARUS)
        snprintf(cmd + at, cl - at,
                 " && iverilog -g%s -s %s_tb -P %s_tb.MAXWORDS=%zu -o %s_tb.vvp %s_tb.v%s >iverilog.log 2>&1 && "
                 "vvp -n %s_tb.vvp +in=stimulus.hex +items=%zu +limit=%llu +out=icarus.out >vvp.log 2>&1",
                 o->nrtl && ext_sv(o->rtl, o->nrtl) ? "2012" : "2005", n, n, words, n, n, files, n, vs->n_rows, limit);
    else
        snprintf(cmd + at, cl - at,
                 " && verilator --binary -j 2 -Wno-fatal -Wno-lint -Wno-style --timescale 1ns/1ps -GMAXWORDS=%zu "
                 "--top-module %s_tb -o %s_vtb --Mdir obj_verilator %s_tb.v%s >verilator.log 2>&1 && "
                 "obj_verilator/%s_vtb +in=stimulus.hex +items=%zu +limit=%llu +out=verilator.out >vtb.log 2>&1",
                 words, n, n, n, files, n, vs->n_rows, limit);
    double lim = o->timeout_s > 0 ? o->timeout_s : TB_COSIM_TIMEOUT_S;
    unsigned long long cap = file_cap(r.vectors * (size_t)r.beats, r.n_out);
    int trc = run_tool(cmd, sname, lim, cap);
    if (limit_msg(trc, sname, lim, cap, msg, msglen)) goto done;
    if (trc != 0) {
        if (o->nrtl) {
            /* the compile's log, or the run's once the compile made the
             * simulation (Verilator's make lines are not its error) */
            char line[400], log[PATH_MAX + 32];
            snprintf(log, sizeof log, "%s/%s", dir, sim == TB_SIM_ICARUS ? "vvp.log" : "vtb.log");
            if (access(log, F_OK))
                snprintf(log, sizeof log, "%s/%s", dir, sim == TB_SIM_ICARUS ? "iverilog.log" : "verilator.log");
            log_line(log, line, sizeof line);
            snprintf(msg, msglen, "cosim: %s failed on the RTL: %s", sname, line);
        } else
            snprintf(msg, msglen, "cosim: %s failed (its log is in the folder: use --keep DIR)", sname);
        goto done;
    }
    char la[512], lb[512];
    long lines = 0, bad = first_diff(ex, res, la, lb, sizeof la, &lines, o->match_items);
    size_t nb = r.vectors * (size_t)r.beats;
    if (bad == 0 && (size_t)lines == nb) {
        if (o->match_items) items_verdict(&r, res, sname, msg, msglen);
        else snprintf(msg, msglen, "bit-exact, %zu items, %llu clocks (%s)", r.vectors, (unsigned long long)r.cycles, sname);
        rc = TB_COSIM_EXACT;
    } else if (bad < 0) {
        snprintf(msg, msglen, "cosim: %s wrote no results", sname);
    } else {
        long beat = bad ? bad - 1 : lines;
        if (o->nrtl) rtl_mismatch(u, cfg, fm, vs, beat, r.beats, la, lb, sname, msg, msglen);
        else
            snprintf(msg, msglen, "MISMATCH at item %ld beat %ld: shadesim \"%s\", %s \"%s\" (cycle, then the output raws in hex)",
                     beat / r.beats, beat % r.beats, la, sname, lb[0] ? lb : "nothing");
        rc = TB_COSIM_MISMATCH;
    }
done:
    for (int i = 0; i < 64; i++) free(names[i]);
    free(in); free(ex); free(res); free(cmd); free(files);
    tb_result_free(&r);
    return rc;
}

int tb_cosim(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs,
             int sim, const char *dir, char *msg, size_t msglen)
{
    return tb_cosim_opt(u, cfg, fm, vs, NULL, sim, dir, msg, msglen);
}
