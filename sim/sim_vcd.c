/* sim_vcd.c - IEEE 1364-2005 section 18 four-state VCD, two states used.
 *
 * Header: $version, $timescale, one `$scope module` per sim_scope with a
 * `$var wire W id name [W-1:0] $end` per signal, $enddefinitions. Body: at
 * the first time step `#0 $dumpvars ... $end` with every value, afterwards
 * `#t` and the signals whose value differs from what was last written.
 * Vector values are `b` + binary digits without leading zeros + space + id.
 */
#include "sim/sim_vcd.h"
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct sim_vcd {
    sim_ctx *ctx;
    FILE    *f;
    char    *path, *tmp;
    int      started;     /* $dumpvars written */
    int      io_error;
};

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
    size_t n = strlen(path);
    if (!v || !(v->path = malloc(n + 1)) || !(v->tmp = malloc(n + 8))) {
        snprintf(err, errlen, "%s: out of memory", path);
        goto fail;
    }
    memcpy(v->path, path, n + 1);
    snprintf(v->tmp, n + 8, "%s.XXXXXX", path);
    int fd = mkstemp(v->tmp);
    if (fd < 0 || !(v->f = fdopen(fd, "w"))) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        if (fd >= 0) { close(fd); unlink(v->tmp); }
        goto fail;
    }
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
fail:
    if (v) { free(v->path); free(v->tmp); free(v); }
    return NULL;
}

static void write_value(FILE *f, const sim_signal *s, int64_t raw)
{
    if (s->fmt.width == 1) { fprintf(f, "%c%s\n", raw & 1 ? '1' : '0', s->vcd_id); return; }
    uint64_t u = (uint64_t)raw;
    if (s->fmt.width < 64) u &= ((uint64_t)1 << s->fmt.width) - 1;
    char bits[66];
    int i = 65;
    bits[i] = 0;
    do { bits[--i] = (char)('0' + (u & 1)); u >>= 1; } while (u);
    fprintf(f, "b%s %s\n", bits + i, s->vcd_id);
}

void sim_vcd_step(sim_vcd *v, sim_time t)
{
    uint32_t n;
    sim_signal **d = sim__vcd_take_dirty(v->ctx, &n);
    int stamped = 0;
    if (!v->started) {
        v->started = 1;
        fprintf(v->f, "#%llu\n$dumpvars\n", (unsigned long long)t);
        for (uint32_t i = 0, ns = sim_signal_count(v->ctx); i < ns; i++) {
            sim_signal *s = sim_signal_at(v->ctx, i);
            s->vcd_dirty = 0;
            s->vcd_last = s->cur;
            write_value(v->f, s, s->cur);
        }
        fputs("$end\n", v->f);
        return;
    }
    for (uint32_t i = 0; i < n; i++) {
        sim_signal *s = d[i];
        s->vcd_dirty = 0;
        /* A value that changed and changed back within the step is no
         * change at all to a waveform viewer. */
        if (s->cur == s->vcd_last) continue;
        if (!stamped) { fprintf(v->f, "#%llu\n", (unsigned long long)t); stamped = 1; }
        s->vcd_last = s->cur;
        write_value(v->f, s, s->cur);
    }
}

int sim_vcd_close(sim_vcd *v)
{
    if (!v) return 0;
    int rc = 0;
    if (ferror(v->f)) rc = -1;
    if (fclose(v->f) != 0) rc = -1;
    if (rc == 0 && rename(v->tmp, v->path) != 0) rc = -1;
    if (rc) unlink(v->tmp);
    sim_attach_vcd(v->ctx, NULL);
    free(v->path); free(v->tmp); free(v);
    return rc;
}

void sim_vcd_abort(sim_vcd *v)
{
    if (!v) return;
    fclose(v->f);
    unlink(v->tmp);
    sim_attach_vcd(v->ctx, NULL);
    free(v->path); free(v->tmp); free(v);
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
    size_t n = strlen(gtkw_path);
    char *tmp = malloc(n + 8);
    if (!tmp) return -1;
    snprintf(tmp, n + 8, "%s.XXXXXX", gtkw_path);
    int fd = mkstemp(tmp);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f) { if (fd >= 0) { close(fd); unlink(tmp); } free(tmp); return -1; }
    /* GTKWave resolves a relative dumpfile against the save file's folder. */
    const char *base = strrchr(vcd_path, '/');
    fprintf(f, "[*] shadesim: open with  gtkwave %s\n[dumpfile] \"%s\"\n[timestart] 0\n",
            gtkw_path, base ? base + 1 : vcd_path);
    fprintf(f, "[treeopen] %s.\n", sim_root(c)->name);
    gtkw_scope(f, sim_root(c), "");
    int rc = (ferror(f) | fclose(f)) ? -1 : 0;
    if (rc == 0 && rename(tmp, gtkw_path) != 0) rc = -1;
    if (rc) unlink(tmp);
    free(tmp);
    return rc;
}
