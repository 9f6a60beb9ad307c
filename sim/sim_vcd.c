/* sim_vcd.c - IEEE 1364-2005 section 18 four-state VCD, two states used.
 *
 * Header: $version, $timescale, one `$scope module` per sim_scope with a
 * `$var wire W id name [W-1:0] $end` per signal, $enddefinitions. Body: at
 * the first time step `#0 $dumpvars ... $end` with every value, afterwards
 * `#t` and the signals whose value differs from what was last written.
 * Vector values are `b` + binary digits without leading zeros + space + id.
 */
#include "sim/sim_vcd.h"
#include "sim/sim_out.h"
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Value changes are formatted by hand into buf and handed to stdio in
 * large pieces (a printf per value was most of a dump's cost). */
#define VCD_BUF  (1 << 16)
#define VCD_LINE 96             /* longest line: 'b', 64 digits, ' ', id, '\n' */

struct sim_vcd {
    sim_ctx *ctx;
    FILE    *f;           /* sim_out_file(out) */
    sim_out *out;         /* temporary + rename, or written through, or stdout */
    int      started;     /* $dumpvars written */
    int      io_error;
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

static void write_scope(sim_vcd *v, const sim_scope *sc)
{
    fprintf(v->f, "$scope module %s $end\n", sc->name);
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) {
        if (s->fmt.width == 1)
            fprintf(v->f, "$var wire 1 %s %s $end\n", s->vcd_id, s->name);
        else
            fprintf(v->f, "$var wire %d %s %s [%d:0] $end\n", s->fmt.width, s->vcd_id,
                    s->name, s->fmt.width - 1);
    }
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) write_scope(v, ch);
    fputs("$upscope $end\n", v->f);
}

sim_vcd *sim_vcd_open(sim_ctx *c, const char *path, const char *timescale,
                      char *err, size_t errlen)
{
    sim_vcd *v = calloc(1, sizeof *v);
    if (!v) {
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    /* A dump can be hundreds of MB: sim_out registers its temporary so
     * that SIGINT/SIGTERM/SIGHUP remove it; "-" streams to stdout. */
    if (!(v->out = sim_out_open(path, err, errlen))) {
        free(v);
        return NULL;
    }
    v->f = sim_out_file(v->out);
    v->ctx = c;
    for (uint32_t i = 0, ns = sim_signal_count(c); i < ns; i++) {
        sim_signal *s = sim_signal_at(c, i);
        make_id(i, s->vcd_id);
        s->vcd_last = 0;
    }
    fprintf(v->f, "$version shadesim $end\n$timescale %s $end\n", timescale);
    write_scope(v, sim_root(c));
    fputs("$enddefinitions $end\n", v->f);
    sim_attach_vcd(c, v);
    return v;
}

/* "1!" / "b1010 #" and a newline at p; returns the end. */
static char *put_value(char *p, const sim_signal *s, int64_t raw)
{
    int w = s->fmt.width;
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
    const char *id = s->vcd_id;
    do *p++ = *id++; while (*id);
    *p++ = '\n';
    return p;
}

static void write_value(sim_vcd *v, const sim_signal *s, int64_t raw)
{
    if (v->n > VCD_BUF - VCD_LINE) flush_buf(v);
    v->n = (size_t)(put_value(v->buf + v->n, s, raw) - v->buf);
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

void sim_vcd_step(sim_vcd *v, sim_time t)
{
    uint32_t n;
    sim_signal **d = sim__vcd_take_dirty(v->ctx, &n);
    int stamped = 0;
    if (!v->started) {
        v->started = 1;
        write_time(v, t);
        write_text(v, "$dumpvars\n");
        for (uint32_t i = 0, ns = sim_signal_count(v->ctx); i < ns; i++) {
            sim_signal *s = sim_signal_at(v->ctx, i);
            s->vcd_dirty = 0;
            s->vcd_last = s->cur;
            write_value(v, s, s->cur);
        }
        write_text(v, "$end\n");
        return;
    }
    for (uint32_t i = 0; i < n; i++) {
        sim_signal *s = d[i];
        s->vcd_dirty = 0;
        /* A value that changed and changed back within the step is no
         * change at all to a waveform viewer. */
        if (s->cur == s->vcd_last) continue;
        if (!stamped) { write_time(v, t); stamped = 1; }
        s->vcd_last = s->cur;
        write_value(v, s, s->cur);
    }
}

int sim_vcd_close(sim_vcd *v)
{
    if (!v) return 0;
    flush_buf(v);
    /* sim_out_close checks the stream (a failed fwrite left its error
     * flag), renames, and on failure removes the temporary and leaves
     * errno at the cause (ENOSPC...), which is what the caller reports. */
    char msg[256];
    int rc = sim_out_close(v->out, msg, sizeof msg);
    int e = errno;
    sim_attach_vcd(v->ctx, NULL);
    free(v);
    errno = e;
    return rc;
}

void sim_vcd_abort(sim_vcd *v)
{
    if (!v) return;
    sim_out_abort(v->out);
    sim_attach_vcd(v->ctx, NULL);
    free(v);
}

static void gtkw_scope(FILE *f, const sim_scope *sc, const char *prefix)
{
    char path[512];
    snprintf(path, sizeof path, "%s%s", prefix, sc->name);
    if (sc->first_sig) {
        /* 0x800200 / 0x1000200: group begin / end (blank trace);
         * 0x424: signed decimal, right-justified; 0x28: binary. */
        fprintf(f, "@800200\n-%s\n", path);
        for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) {
            if (s->fmt.width == 1) fprintf(f, "@28\n%s.%s\n", path, s->name);
            else fprintf(f, "@%s\n%s.%s[%d:0]\n", s->fmt.is_signed ? "424" : "24",
                         path, s->name, s->fmt.width - 1);
        }
        fprintf(f, "@1000200\n-%s\n", path);
    }
    char child_prefix[520];
    snprintf(child_prefix, sizeof child_prefix, "%s.", path);
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling)
        gtkw_scope(f, ch, child_prefix);
}

int sim_vcd_write_gtkw(sim_ctx *c, const char *vcd_path, const char *gtkw_path)
{
    char msg[256];
    sim_out *o = sim_out_open(gtkw_path, msg, sizeof msg);
    if (!o) return -1;                          /* errno from the open */
    FILE *f = sim_out_file(o);
    /* GTKWave resolves a relative dumpfile against the save file's folder. */
    const char *base = strrchr(vcd_path, '/');
    fprintf(f, "[*] shadesim: open with  gtkwave %s\n[dumpfile] \"%s\"\n[timestart] 0\n",
            gtkw_path, base ? base + 1 : vcd_path);
    fprintf(f, "[treeopen] %s.\n", sim_root(c)->name);
    gtkw_scope(f, sim_root(c), "");
    return sim_out_close(o, msg, sizeof msg);   /* errno = the cause on -1 */
}
