/* sim_vcd.c - IEEE 1364-2005 section 18 four-state VCD, two states used.
 *
 * Header: $version, $timescale, one `$scope module` per sim_scope with a
 * `$var wire W id name [W-1:0] $end` per signal, $enddefinitions. Body: at
 * the first time step `#0 $dumpvars ... $end` with every value, afterwards
 * `#t` and the signals whose value differs from what was last written.
 * Vector values are `b` + binary digits without leading zeros + space + id.
 * Real variables a testbench declares (`$var real 64`) follow the design's
 * scopes under the root, one `$scope module` per scope name; their values
 * are `r` + %.17g (read back exactly) + space + id.
 *
 * What the writer keeps per signal (id, last value written, whether it
 * changed during a hold) is in its own arrays indexed by sim_signal.index.
 */
#define _XOPEN_SOURCE 700          /* realpath */
#include "sim/sim_vcd.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Value changes are formatted by hand into buf and handed to stdio in
 * large pieces (a printf per value was most of a dump's cost). */
#define VCD_BUF  (1 << 16)
#define VCD_LINE 96             /* longest line: 'b', 64 digits, ' ', id, '\n' */

typedef struct vcd_real {
    char   *scope, *name;
    char    id[8];
    double  cur, last;    /* value now; last written */
    int     dirty;
} vcd_real;

struct sim_vcd {
    sim_ctx *ctx;
    FILE    *f;           /* the caller's */
    char    *timescale;
    uint32_t nsig;        /* signals dumped: those that existed at open */
    char   (*id)[8];      /* per signal: identifier code */
    int64_t *last;        /* per signal: value last written */
    uint8_t *held;        /* per signal: in heldl */
    sim_signal **heldl;   /* changed while held, in order of first change */
    uint32_t nheld;
    int      header;      /* header written */
    int      started;     /* $dumpvars written */
    int      mode;        /* SIM_VCD_WRITE / HOLD / LAST */
    int      io_error;
    vcd_real *reals;
    int      nreals, capreals;
    sim_vcd_hook hook;
    void    *hook_data;
    size_t   n;           /* bytes in buf */
    char     buf[VCD_BUF];
};

static void flush_buf(sim_vcd *v)
{
    if (v->n && fwrite(v->buf, 1, v->n, v->f) != v->n) v->io_error = 1;
    v->n = 0;
}

/* Binary digits of each byte value, most significant first, eight bytes
 * per value (and eight of padding, so that 8-byte copies stay inside). */
#define B1(b, i) (char)('0' + (((b) >> (7 - (i))) & 1))
#define B8(b) B1(b, 0), B1(b, 1), B1(b, 2), B1(b, 3), B1(b, 4), B1(b, 5), B1(b, 6), B1(b, 7)
#define B8x4(b) B8(b), B8((b) + 1), B8((b) + 2), B8((b) + 3)
#define B8x16(b) B8x4(b), B8x4((b) + 4), B8x4((b) + 8), B8x4((b) + 12)
#define B8x64(b) B8x16(b), B8x16((b) + 16), B8x16((b) + 32), B8x16((b) + 48)
static const char bin8[256 * 8 + 8] = { B8x64(0), B8x64(64), B8x64(128), B8x64(192) };
#undef B1
#undef B8
#undef B8x4
#undef B8x16
#undef B8x64

/* Identifier codes: printable ASCII '!'..'~' in base 94, shortest first. */
static void make_id(uint32_t n, char *out)
{
    int i = 0;
    do { out[i++] = (char)('!' + n % 94); n /= 94; } while (n && i < 7);
    out[i] = 0;
}

/* The real variables of scope name sc, in the order they were added. */
static void write_real_scope(sim_vcd *v, const char *sc)
{
    fprintf(v->f, "$scope module %s $end\n", sc);
    for (int i = 0; i < v->nreals; i++)
        if (!strcmp(v->reals[i].scope, sc))
            fprintf(v->f, "$var real 64 %s %s $end\n", v->reals[i].id, v->reals[i].name);
    fputs("$upscope $end\n", v->f);
}

static void write_scope(sim_vcd *v, const sim_scope *sc)
{
    fprintf(v->f, "$scope module %s $end\n", sc->name);
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) {
        if (s->index >= v->nsig) continue;
        if (s->fmt.width == 1)
            fprintf(v->f, "$var wire 1 %s %s $end\n", v->id[s->index], s->name);
        else
            fprintf(v->f, "$var wire %d %s %s [%d:0] $end\n", s->fmt.width, v->id[s->index],
                    s->name, s->fmt.width - 1);
    }
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) write_scope(v, ch);
    if (sc == sim_root(v->ctx))
        for (int i = 0; i < v->nreals; i++) {
            int first = 1;   /* the first real of its scope name */
            for (int j = 0; j < i && first; j++) first = strcmp(v->reals[j].scope, v->reals[i].scope) != 0;
            if (first) write_real_scope(v, v->reals[i].scope);
        }
    fputs("$upscope $end\n", v->f);
}

static void write_header(sim_vcd *v)
{
    if (v->header) return;
    v->header = 1;
    fprintf(v->f, "$version shadesim $end\n$timescale %s $end\n", v->timescale);
    write_scope(v, sim_root(v->ctx));
    fputs("$enddefinitions $end\n", v->f);
}

static void step(sim_ctx *c, sim_time t, void *data);
static void free_vcd(sim_vcd *v);

sim_vcd *sim_vcd_open(sim_ctx *c, FILE *f, const char *timescale)
{
    sim_vcd *v = calloc(1, sizeof *v);
    if (!v) return NULL;
    v->ctx = c;
    v->f = f;
    v->nsig = sim_signal_count(c);
    size_t n = v->nsig ? v->nsig : 1;
    v->timescale = strdup(timescale);
    v->id = malloc(n * sizeof *v->id);
    v->last = calloc(n, sizeof *v->last);
    v->held = calloc(n, sizeof *v->held);
    v->heldl = malloc(n * sizeof *v->heldl);
    if (!v->timescale || !v->id || !v->last || !v->held || !v->heldl
        || sim_observe(c, step, v, SIM_OBS_CHANGES)) {
        free_vcd(v);
        return NULL;
    }
    for (uint32_t i = 0; i < v->nsig; i++) make_id(i, v->id[i]);
    return v;
}

int sim_vcd_add_real(sim_vcd *v, const char *scope, const char *name)
{
    if (v->header) return -1;
    if (v->nreals == v->capreals) {
        int cap = v->capreals ? 2 * v->capreals : 8;
        vcd_real *r = realloc(v->reals, (size_t)cap * sizeof *r);
        if (!r) return -1;
        v->reals = r;
        v->capreals = cap;
    }
    vcd_real *r = &v->reals[v->nreals];
    memset(r, 0, sizeof *r);
    r->scope = strdup(scope);
    r->name = strdup(name);
    if (!r->scope || !r->name) { free(r->scope); free(r->name); return -1; }
    /* ids after the signals' */
    make_id(sim_signal_count(v->ctx) + (uint32_t)v->nreals, r->id);
    return v->nreals++;
}

void sim_vcd_set_real(sim_vcd *v, int idx, double value)
{
    if (idx < 0 || idx >= v->nreals) return;
    v->reals[idx].cur = value;
    v->reals[idx].dirty = 1;
}

void sim_vcd_on_step(sim_vcd *v, sim_vcd_hook fn, void *data)
{
    v->hook = fn;
    v->hook_data = data;
}

void sim_vcd_window(sim_vcd *v, int mode)
{
    v->mode = mode;
}

/* "1!" / "b1010 #" and a newline at p; returns the end. */
static char *put_value(char *p, int w, const char *id, int64_t raw)
{
    if (w == 1) {
        *p++ = raw & 1 ? '1' : '0';
    } else {
        uint64_t u = (uint64_t)raw;
        if (w < 64) u &= ((uint64_t)1 << w) - 1;
        *p++ = 'b';
        /* Digits without leading zeros (at least one): the top byte's
         * significant digits, then eight per byte. */
        int nd = u ? 64 - __builtin_clzll(u) : 1;
        int top = (nd - 1) / 8;                 /* index of the top byte */
        int k = nd - 8 * top;                   /* its digits, 1..8 */
        memcpy(p, bin8 + 8 * ((u >> (8 * top)) & 0xff) + 8 - k, 8);
        p += k;
        for (int b = top - 1; b >= 0; b--) {
            memcpy(p, bin8 + 8 * ((u >> (8 * b)) & 0xff), 8);
            p += 8;
        }
        *p++ = ' ';
    }
    do *p++ = *id++; while (*id);
    *p++ = '\n';
    return p;
}

static void write_value(sim_vcd *v, const sim_signal *s, int64_t raw)
{
    if (v->n > VCD_BUF - VCD_LINE) flush_buf(v);
    v->n = (size_t)(put_value(v->buf + v->n, s->fmt.width, v->id[s->index], raw) - v->buf);
}

static void write_time(sim_vcd *v, sim_time t)
{
    if (v->n > VCD_BUF - VCD_LINE) flush_buf(v);
    char d[24];
    int k = 0;
    do { d[k++] = (char)('0' + t % 10); t /= 10; } while (t);
    char *p = v->buf + v->n;
    *p++ = '#';
    while (k) *p++ = d[--k];
    *p++ = '\n';
    v->n = (size_t)(p - v->buf);
}

static void write_text(sim_vcd *v, const char *text)
{
    size_t k = strlen(text);
    if (v->n + k > VCD_BUF) flush_buf(v);
    memcpy(v->buf + v->n, text, k);
    v->n += k;
}

/* "r0.25 id" and a newline. A value that is not finite (no reader
 * agrees on its spelling) is written as 0. */
static void write_real(sim_vcd *v, vcd_real *r)
{
    if (v->n > VCD_BUF - VCD_LINE) flush_buf(v);
    double x = isfinite(r->cur) ? r->cur : 0;
    int k = snprintf(v->buf + v->n, VCD_LINE, "r%.17g %s\n", x, r->id);
    if (k > 0 && k < VCD_LINE) v->n += (size_t)k;
    r->last = r->cur;
    r->dirty = 0;
}

/* Add the signals in d to the held list (each once, first change first). */
static void hold(sim_vcd *v, sim_signal *const *d, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        uint32_t k = d[i]->index;
        if (k < v->nsig && !v->held[k]) { v->held[k] = 1; v->heldl[v->nheld++] = d[i]; }
    }
}

static void drop_held(sim_vcd *v)
{
    for (uint32_t i = 0; i < v->nheld; i++) v->held[v->heldl[i]->index] = 0;
    v->nheld = 0;
}

/* The observer: time step t has finished; dump what changed. */
static void step(sim_ctx *c, sim_time t, void *data)
{
    sim_vcd *v = data;
    if (v->hook) v->hook(v, t, v->hook_data);
    uint32_t n;
    sim_signal *const *d = sim_changed(c, &n);
    /* Held: the changed signals are remembered (each once), so that the
     * first step written afterwards writes what changed meanwhile. */
    if (v->mode == SIM_VCD_HOLD) { hold(v, d, n); return; }
    if (v->mode == SIM_VCD_LAST) v->mode = SIM_VCD_HOLD;
    write_header(v);
    int stamped = 0;
    if (!v->started) {
        v->started = 1;
        drop_held(v);
        write_time(v, t);
        write_text(v, "$dumpvars\n");
        for (uint32_t i = 0; i < v->nsig; i++) {
            sim_signal *s = sim_signal_at(c, i);
            v->last[i] = s->cur;
            write_value(v, s, s->cur);
        }
        for (int i = 0; i < v->nreals; i++) write_real(v, &v->reals[i]);
        write_text(v, "$end\n");
        return;
    }
    if (v->nheld) {
        hold(v, d, n);
        d = v->heldl;
        n = v->nheld;
    }
    /* The hot loop of a dump: what it reads is kept in locals, since the
     * char stores into buf may alias anything. */
    int64_t *last = v->last;
    char (*id)[8] = v->id;
    uint32_t nsig = v->nsig;
    char *buf = v->buf;
    size_t at = v->n;
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = d[i];
        uint32_t k = s->index;
        int64_t cur = s->cur;
        /* A value that changed and changed back within the step is no
         * change at all to a waveform viewer. */
        if (k >= nsig || cur == last[k]) continue;
        if (!stamped) { v->n = at; write_time(v, t); at = v->n; stamped = 1; }
        last[k] = cur;
        if (at > VCD_BUF - VCD_LINE) { v->n = at; flush_buf(v); at = 0; }
        at = (size_t)(put_value(buf + at, s->fmt.width, id[k], cur) - buf);
    }
    v->n = at;
    if (v->nheld) drop_held(v);
    for (int i = 0; i < v->nreals; i++) {
        vcd_real *r = &v->reals[i];
        if (!r->dirty) continue;
        if (r->cur == r->last || (isnan(r->cur) && isnan(r->last))) { r->dirty = 0; continue; }
        if (!stamped) { write_time(v, t); stamped = 1; }
        write_real(v, r);
    }
}

static void free_vcd(sim_vcd *v)
{
    for (int i = 0; i < v->nreals; i++) { free(v->reals[i].scope); free(v->reals[i].name); }
    free(v->reals);
    free(v->timescale);
    free(v->id); free(v->last); free(v->held); free(v->heldl);
    free(v);
}

int sim_vcd_close(sim_vcd *v)
{
    if (!v) return 0;
    write_header(v);      /* a dump with no time step written still has one */
    flush_buf(v);
    int bad = v->io_error || fflush(v->f) != 0 || ferror(v->f);
    int e = errno;
    sim_unobserve(v->ctx, step, v);
    free_vcd(v);
    errno = e;
    return bad ? -1 : 0;
}

void sim_vcd_abort(sim_vcd *v)
{
    if (!v) return;
    sim_unobserve(v->ctx, step, v);
    free_vcd(v);
}

/* One trace: its flags line, the fixed-point shift, its name. Flags are
 * GTKWave's TraceEntFlagBits: 0x4 decimal, 0x20 right-justified, 0x8
 * binary, 0x400 signed, 0x40000000 fixed-point shift ([fpshift_count]). */
static void gtkw_signal(FILE *f, const sim_signal *s)
{
    char path[600];
    sim_signal_path(s, path, sizeof path);
    if (s->fmt.width == 1) { fprintf(f, "@28\n%s\n", path); return; }
    unsigned long flags = 0x24 | (s->fmt.is_signed ? 0x400 : 0);
    int fp = s->fmt.fbits >= 1 && s->fmt.fbits <= SIM_GTKW_MAX_FPSHIFT;
    if (fp) fprintf(f, "@%lx\n[fpshift_count] %d\n", flags | 0x40000000ul, s->fmt.fbits);
    else fprintf(f, "@%lx\n", flags);
    fprintf(f, "%s[%d:0]\n", path, s->fmt.width - 1);
}

static void gtkw_scope(FILE *f, const sim_scope *sc, const char *prefix)
{
    char path[512];
    snprintf(path, sizeof path, "%s%s", prefix, sc->name);
    if (sc->first_sig) {
        /* 0x800200 / 0x1000200: group begin / end (blank trace) */
        fprintf(f, "@800200\n-%s\n", path);
        for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) gtkw_signal(f, s);
        fprintf(f, "@1000200\n-%s\n", path);
    }
    char child_prefix[520];
    snprintf(child_prefix, sizeof child_prefix, "%s.", path);
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling)
        gtkw_scope(f, ch, child_prefix);
}

/* path made absolute: its folder resolved (links too), then its name;
 * NULL with errno. The caller frees. */
static char *abs_path(const char *path)
{
    const char *slash = strrchr(path, '/');
    char *dir = !slash ? strdup(".") : slash == path ? strdup("/") : strndup(path, (size_t)(slash - path));
    if (!dir) { errno = ENOMEM; return NULL; }
    char *real = realpath(dir, NULL);
    free(dir);
    if (!real) return NULL;
    const char *base = slash ? slash + 1 : path;
    size_t n = strlen(real) + strlen(base) + 2;
    char *out = malloc(n);
    if (out) snprintf(out, n, "%s%s%s", real, strcmp(real, "/") ? "/" : "", base);
    else errno = ENOMEM;
    free(real);
    return out;
}

int sim_vcd_write_gtkw(FILE *f, sim_ctx *c, const char *dump_path, const char *gtkw_path,
                       const char *lead_title, const sim_gtkw_trace *lead, int nlead)
{
    char *dump = abs_path(dump_path), *save = abs_path(gtkw_path);
    if (!dump || !save) { int e = errno; free(dump); free(save); errno = e; return -1; }
    /* Beside each other (as run writes them), both by their names alone:
     * the bytes do not depend on where the run was, and GTKWave finds a
     * relative dump from the save file's own folder (its find_dumpfile,
     * from [savefile] to [dumpfile]). Apart, the dump's absolute path. */
    const char *ds = strrchr(dump, '/'), *ss = strrchr(save, '/');
    int together = ds && ss && ds - dump == ss - save && !strncmp(dump, save, (size_t)(ds - dump));
    fprintf(f, "[*] shadesim: open with  gtkwave %s\n[dumpfile] \"%s\"\n[savefile] \"%s\"\n[timestart] 0\n",
            together ? ss + 1 : save, together ? ds + 1 : dump, together ? ss + 1 : save);
    free(dump);
    free(save);
    fprintf(f, "[treeopen] %s.\n", sim_root(c)->name);
    if (nlead > 0) {
        fprintf(f, "@800200\n-%s\n", lead_title ? lead_title : "check");
        for (int i = 0; i < nlead; i++) {
            if (lead[i].sig) gtkw_signal(f, lead[i].sig);
            /* a real variable keeps its own (real) display: no number-base flag */
            else if (lead[i].real) fprintf(f, "@20\n%s.%s\n", sim_root(c)->name, lead[i].real);
        }
        fprintf(f, "@1000200\n-%s\n", lead_title ? lead_title : "check");
    }
    gtkw_scope(f, sim_root(c), "");
    return 0;
}
