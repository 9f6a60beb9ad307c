/* tb_wave.c - a unit's dump as tb_run writes it: expected and error
 * traces per output beat, the item window, FILE.gtkw, FST. */
#include "testbench/tb_wave.h"
#include "sim/sim_fixed.h"
#include "base/base_out.h"
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* The VCD's hook, at every time step with every signal settled. A cycle
 * starts at time 0 and at each rising edge (the clock is high only in
 * the steps of rising edges); its values hold until the next edge, so
 * what is seen here is what the testbench's monitor samples at the end of
 * the cycle: the k-th cycle with out_valid high holds beat k. */
static void hook(sim_vcd *v, sim_time t, void *data)
{
    tb_wave *w = data;
    if (!(t == 0 || w->clk->cur)) return;
    /* the item the driver offers from this edge on (its rule: an item
     * handed over in the previous cycle makes way for the next) */
    if (t != 0 && w->accepting) w->offered++;
    w->accepting = w->io->in_valid->cur && w->io->in_ready->cur;
    size_t total = w->n_items * (size_t)w->beats;
    if (w->o->vcd_window) {
        if (!w->started && w->io->in_valid->cur && w->offered >= w->from) {
            w->started = 1;
            sim_vcd_window(v, SIM_VCD_WRITE);
        }
        /* this edge samples the window's last beat: write it, then stop */
        if (w->prev_beat >= 0 && (size_t)w->prev_beat + 1 == (w->to + 1) * (size_t)w->beats)
            sim_vcd_window(v, SIM_VCD_LAST);
    }
    w->prev_beat = -1;
    if (w->io->out_valid->cur && w->beats_seen < total) {
        size_t k = w->beats_seen++, item = k / (size_t)w->beats;
        int b = (int)(k % (size_t)w->beats);
        const double *row = vec_row(w->vs, item);
        for (int o = 0; o < w->n_out; o++) {
            double want = row[w->n_in + b * w->n_out + o];
            double hw = sim_fx_to_real(w->io->out[o]->cur, w->io->out[o]->fmt);
            sim_vcd_set_real(v, w->real_idx[2 * o], want);
            sim_vcd_set_real(v, w->real_idx[2 * o + 1], hw - want);
        }
        w->prev_beat = (long long)k;
    }
}

int tb_wave_have_vcd2fst(void)
{
    const char *path = getenv("PATH");
    if (!path) return 0;
    char *dup = strdup(path), *save = NULL;
    int found = 0;
    for (char *d = dup ? strtok_r(dup, ":", &save) : NULL; d && !found; d = strtok_r(NULL, ":", &save)) {
        char f[4096];
        snprintf(f, sizeof f, "%s/vcd2fst", *d ? d : ".");
        found = access(f, X_OK) == 0;
    }
    free(dup);
    return found;
}

sim_vcd *tb_wave_open(tb_wave *w, sim_ctx *c, const tb_opts *o, const unit_io *io,
                      const sim_signal *clk, const unit_desc *u, const unit_cfg *cfg,
                      const vec_set *vs, char *err, size_t errlen)
{
    memset(w, 0, sizeof *w);
    w->o = o; w->io = io; w->clk = clk; w->vs = vs;
    w->n_in = unit_n_in(u); w->n_out = unit_n_out(u);
    w->beats = u->beats(cfg);
    w->n_items = vs->n_rows;
    w->prev_beat = -1;
    w->from = o->vcd_from; w->to = o->vcd_to;
    size_t n = strlen(o->vcd_path) + 32;
    if (!(w->dump_path = malloc(n))) base_out_of_memory();
    /* --fst: the VCD goes to a temporary beside the FST (same file system,
     * so the conversion's output can be renamed into place) */
    if (o->fst) snprintf(w->dump_path, n, "%s.%ld.tmp.vcd", o->vcd_path, (long)getpid());
    else snprintf(w->dump_path, n, "%s", o->vcd_path);
    /* A dump can be hundreds of MB: base_out writes it to a temporary that
     * SIGINT/SIGTERM/SIGHUP remove, renamed into place when complete; "-"
     * streams to stdout. */
    if (!(w->out = base_out_open(w->dump_path, err, errlen))) {
        /* name the user's path, not our temporary */
        if (o->fst) snprintf(err, errlen, "%s: cannot create: %s", o->vcd_path, strerror(errno));
        tb_wave_free(w);
        return NULL;
    }
    sim_vcd *v = sim_vcd_open(c, base_out_file(w->out), "1ns");
    if (!v) base_out_of_memory();
    for (int k = 0; k < w->n_out; k++) {
        char name[64];
        snprintf(name, sizeof name, "expected_%s", io->out[k]->name);
        w->real_idx[2 * k] = sim_vcd_add_real(v, "tb", name);
        snprintf(name, sizeof name, "err_%s", io->out[k]->name);
        w->real_idx[2 * k + 1] = sim_vcd_add_real(v, "tb", name);
    }
    sim_vcd_on_step(v, hook, w);
    if (o->vcd_window) sim_vcd_window(v, SIM_VCD_HOLD);
    return v;
}

void tb_wave_free(tb_wave *w)
{
    if (w->out) base_out_abort(w->out);
    w->out = NULL;
    free(w->dump_path);
    w->dump_path = NULL;
}

/* vcd2fst IN OUT, quietly; 0 if it succeeded. */
static int run_vcd2fst(const char *in, const char *out)
{
    posix_spawn_file_actions_t fa;
    if (posix_spawn_file_actions_init(&fa)) return -1;
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    char *argv[] = { "vcd2fst", (char *)in, (char *)out, NULL };
    pid_t pid;
    int rc = posix_spawnp(&pid, "vcd2fst", &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc) return -1;
    int st;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(st) && WEXITSTATUS(st) == 0 ? 0 : -1;
}

/* The file at from into the output file to (base/base_out.h). 0 or -1. */
static int copy_out(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb");
    if (!in) return -1;
    char e[256];
    base_out *o = base_out_open(to, e, sizeof e);
    if (!o) { fclose(in); return -1; }
    char buf[1 << 16];
    size_t k;
    int rc = 0;
    while ((k = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, k, base_out_file(o)) != k) { rc = -1; break; }
    if (ferror(in)) rc = -1;
    fclose(in);
    if (rc) { base_out_abort(o); return -1; }
    return base_out_close(o, e, sizeof e);
}

int tb_wave_gtkw(sim_ctx *c, const char *vcd_path, const char *title, const sim_gtkw_trace *lead, int nlead,
                 char *err, size_t errlen)
{
    struct stat st;
    char msg[256];
    /* The companion goes beside a dump in a file (not stdout, not
     * /dev/null: no /dev/null.gtkw), any path length; a companion that
     * cannot be written is an error, not a silent omission. */
    /* (a dump still waiting in an output set is at its temporary name) */
    if (stat(base_out_pending(vcd_path), &st) != 0 || !S_ISREG(st.st_mode)) return 0;
    size_t gl = strlen(vcd_path) + sizeof ".gtkw";
    char *g = malloc(gl);
    if (!g) base_out_of_memory();
    snprintf(g, gl, "%s.gtkw", vcd_path);
    base_out *go = base_out_open(g, msg, sizeof msg);   /* errno: the cause */
    int gbad = !go;
    if (go && sim_vcd_write_gtkw(base_out_file(go), c, vcd_path, g, title, lead, nlead)) {
        int e = errno;
        base_out_abort(go);
        errno = e;
        gbad = 1;
    } else if (go) {
        gbad = base_out_close(go, msg, sizeof msg) != 0;
    }
    if (gbad) snprintf(err, errlen, "%s: cannot write: %s", g, strerror(errno));
    free(g);
    return gbad ? -1 : 0;
}

int tb_wave_close(tb_wave *w, sim_ctx *c, sim_vcd *v, const unit_desc *u, int rc,
                  char *err, size_t errlen)
{
    const tb_opts *o = w->o;
    char msg[256];
    int bad = sim_vcd_close(v);
    bad |= base_out_close(w->out, msg, sizeof msg);   /* errno: the cause */
    w->out = NULL;
    if (bad) {
        if (rc == TB_OK) {
            snprintf(err, errlen, "%s: write failed: %s", o->vcd_path, strerror(errno));
            rc = TB_BADINPUT;
        }
        if (o->fst) unlink(w->dump_path);
        tb_wave_free(w);
        return rc;
    }
    if (o->fst) {
        /* vcd2fst writes a scratch file beside the dump (it unlinks the
         * name it is given first, so it never gets the real path: a device
         * would be replaced, a file's permissions lost); the FST is then
         * copied into place as every output file is, complete or not at
         * all. */
        size_t n = strlen(w->dump_path) + 8;
        char *tmp = malloc(n);
        int ok = 0;
        if (tmp) {
            snprintf(tmp, n, "%s.fst", w->dump_path);
            ok = run_vcd2fst(w->dump_path, tmp) == 0 && copy_out(tmp, o->vcd_path) == 0;
            unlink(tmp);
            free(tmp);
        }
        unlink(w->dump_path);
        if (!ok && rc == TB_OK) {
            snprintf(err, errlen, "%s: vcd2fst could not convert the dump", o->vcd_path);
            rc = TB_BADINPUT;
        }
    }
    if (o->gtkw && rc == TB_OK) {
        sim_gtkw_trace lead[1 + 3 * UNIT_MAX_IO];
        char names[2 * UNIT_MAX_IO][80];
        int nl = 0;
        lead[nl++] = (sim_gtkw_trace){ w->io->out_valid, NULL };
        for (int k = 0; k < w->n_out; k++) {
            lead[nl++] = (sim_gtkw_trace){ w->io->out[k], NULL };
            snprintf(names[2 * k], sizeof names[0], "tb.expected_%s", w->io->out[k]->name);
            snprintf(names[2 * k + 1], sizeof names[0], "tb.err_%s", w->io->out[k]->name);
            lead[nl++] = (sim_gtkw_trace){ NULL, names[2 * k] };
            lead[nl++] = (sim_gtkw_trace){ NULL, names[2 * k + 1] };
        }
        char title[96];
        snprintf(title, sizeof title, "%s outputs, expected, error", u->name);
        if (tb_wave_gtkw(c, o->vcd_path, title, lead, nl, err, errlen)) rc = TB_BADINPUT;
    }
    tb_wave_free(w);
    return rc;
}
