/* test_vcd.c - the VCD writer: a small design's dump equals a checked-in
 * file; a 3-pixel horner3 run read back shows RG's Horner sequence and the
 * expected/error traces; a window of items is the whole dump's state over
 * exactly its time span; every dump is accepted by GTKWave's vcd2fst when
 * it is installed; the .gtkw names its dump by a path that resolves. */
#define _XOPEN_SOURCE 700   /* realpath */
#include "tests/tst.h"
#include "sim/sim.h"
#include "sim/sim_prim.h"
#include "sim/sim_vcd.h"
#include "base/base_out.h"
#include "testbench/tb.h"
#include <unistd.h>

static char tmpdir[] = "/tmp/shadesim_vcd_XXXXXX";

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long sz = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)sz + 1);
    if (b && fread(b, 1, (size_t)sz, f) != (size_t)sz) { free(b); b = NULL; }
    if (b) b[sz] = 0;
    fclose(f);
    if (n) *n = (size_t)sz;
    return b;
}

/* A 3-bit counter with a 4-bit accumulator and a carry flag; 6 clocks. */
static void small_design(const char *path)
{
    sim_ctx *c = sim_new();
    sim_fmt u3 = { .is_signed = 0, .ibits = 3, .fbits = 0, .width = 3 },
            s4 = { .is_signed = 1, .ibits = 2, .fbits = 2, .width = 4 };
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *top = sim_scope_new(c, NULL, "counter");
    sim_scope *acc = sim_scope_new(c, top, "acc");
    sim_signal *one = sim_const_raw(c, top, "one", u3, 1);
    sim_signal *q = sim_reg(c, top, "q", u3, clk, NULL, NULL, NULL, 0);
    sim_signal *n = sim_add(c, top, "n", u3, q, one);
    sim_reg_connect(q, n);
    sim_signal *a = sim_reg(c, acc, "a", s4, clk, NULL, NULL, NULL, 0);
    sim_signal *s = sim_add(c, acc, "s", s4, a, q);   /* wraps in s2.2 */
    sim_reg_connect(a, s);
    sim_clock(c, clk, 5, 5);
    char err[200];
    base_out *o = base_out_open(path, err, sizeof err);
    TST_CHECK(o != NULL, "%s", err);
    if (!o) { sim_free(c); return; }
    sim_vcd *v = sim_vcd_open(c, base_out_file(o), "1ns");
    TST_CHECK(v != NULL, "out of memory");
    sim_run(c, 60);
    TST_EQ_INT(sim_vcd_close(v), 0);
    TST_EQ_INT(base_out_close(o, err, sizeof err), 0);
    sim_free(c);
}

static int have(const char *tool)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

static void vcd2fst_accepts(const char *vcd)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "vcd2fst %s %s.fst >/dev/null 2>&1", vcd, vcd);
    TST_CHECK(system(cmd) == 0, "vcd2fst rejected %s", vcd);
    snprintf(cmd, sizeof cmd, "%s.fst", vcd);
    FILE *f = fopen(cmd, "rb");
    TST_CHECK(f != NULL, "vcd2fst wrote no %s", cmd);
    if (f) fclose(f);
    unlink(cmd);
}

static void t_golden_small(void)
{
    char path[128];
    snprintf(path, sizeof path, "%s/small.vcd", tmpdir);
    small_design(path);
    size_t n1, n2;
    char *got = slurp(path, &n1), *want = slurp("tests/data/small.vcd", &n2);
    TST_CHECK(got && want, "missing file (expected tests/data/small.vcd)");
    if (got && want) TST_CHECK(n1 == n2 && !memcmp(got, want, n1), "dump differs from tests/data/small.vcd: diff %s tests/data/small.vcd", path);
    /* No temporary file is left beside it. */
    char cmd[300];
    snprintf(cmd, sizeof cmd, "ls %s | grep -v '^small.vcd$' | grep -q .", tmpdir);
    TST_CHECK(system(cmd) != 0, "temporary file left in %s", tmpdir);
    free(got); free(want);
    unlink(path);
}

static void t_unwritable(void)
{
    /* A stream that cannot take the dump: close says so. */
    FILE *f = fopen("/dev/full", "wb");
    if (!f) TST_SKIP("no /dev/full");
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_clock(c, clk, 5, 5);
    sim_vcd *v = sim_vcd_open(c, f, "1ns");
    TST_CHECK(v != NULL, "out of memory");
    sim_run(c, 100000);   /* more than the writer's buffer */
    TST_EQ_INT(sim_vcd_close(v), -1);
    fclose(f);
    sim_free(c);
}

/* Parse a VCD: map id -> name for scope "horner3", then list every value
 * change of `rg` as raw integers (two's complement of its width). */
static int rg_history(const char *text, int64_t *vals, int max)
{
    char id[16] = "";
    int width = 0, n = 0;
    const char *p = text;
    while ((p = strstr(p, "$var wire "))) {
        int w;
        char i[16], name[64];
        if (sscanf(p, "$var wire %d %15s %63s", &w, i, name) == 3 && !strcmp(name, "rg")) {
            snprintf(id, sizeof id, "%s", i);
            width = w;
        }
        p++;
    }
    if (!width) return -1;
    const char *body = strstr(text, "$enddefinitions");
    for (const char *l = body; l && *l; l = strchr(l, '\n'), l = l ? l + 1 : NULL) {
        char bits[80], i[16];
        if (*l == 'b' && sscanf(l, "b%79s %15s", bits, i) == 2 && !strcmp(i, id) && n < max) {
            uint64_t u = 0;
            for (char *b = bits; *b; b++) u = u << 1 | (uint64_t)(*b == '1');
            int64_t v = (int64_t)u;
            if (width < 64 && (u >> (width - 1)) & 1) v = (int64_t)(u | ~(((uint64_t)1 << width) - 1));
            vals[n++] = v;
        }
    }
    return n;
}

/* The values written for the real variable `name`, in order. */
static int real_history(const char *text, const char *name, double *vals, int max)
{
    char id[16] = "", want[80];
    snprintf(want, sizeof want, " %s $end", name);
    for (const char *p = text; (p = strstr(p, "$var real 64 ")); p++) {
        const char *e = strchr(p, '\n');
        char line[200];
        snprintf(line, sizeof line, "%.*s", e ? (int)(e - p) : 0, p);
        if (strstr(line, want)) sscanf(line, "$var real 64 %15s", id);
    }
    if (!id[0]) return -1;
    int n = 0;
    for (const char *l = strstr(text, "$enddefinitions"); l && *l; l = strchr(l, '\n'), l = l ? l + 1 : NULL) {
        char i[16];
        double v;
        if (*l == 'r' && sscanf(l, "r%lf %15s", &v, i) == 2 && !strcmp(i, id) && n < max) vals[n++] = v;
    }
    return n;
}

/* A dump as events: for each value change, its time, variable index and
 * value text; the variables' ids in declaration order. */
typedef struct vcd_ev { unsigned long long t; int var; char val[72]; } vcd_ev;
typedef struct vcd_dump { char ids[64][8]; char names[64][32]; int nvars; vcd_ev *ev; int nev; } vcd_dump;

static int vcd_var(const vcd_dump *d, const char *id)
{
    for (int i = 0; i < d->nvars; i++) if (!strcmp(d->ids[i], id)) return i;
    return -1;
}

static void vcd_parse(const char *text, vcd_dump *d)
{
    memset(d, 0, sizeof *d);
    d->ev = calloc(200000, sizeof *d->ev);
    for (const char *p = text; (p = strstr(p, "$var ")) && d->nvars < 64; p++) {
        char type[16], id[8], name[32];
        int w;
        if (sscanf(p, "$var %15s %d %7s %31s", type, &w, id, name) == 4) {
            snprintf(d->ids[d->nvars], 8, "%s", id);
            snprintf(d->names[d->nvars], 32, "%s", name);
            d->nvars++;
        }
    }
    unsigned long long t = 0;
    for (const char *l = strstr(text, "$enddefinitions"); l && *l; l = strchr(l, '\n'), l = l ? l + 1 : NULL) {
        char val[72], id[8];
        if (*l == '#') { t = strtoull(l + 1, NULL, 10); continue; }
        if ((*l == 'b' || *l == 'r') && sscanf(l, "%71s %7s", val, id) == 2) {
        } else if ((*l == '0' || *l == '1') && sscanf(l + 1, "%7s", id) == 1) {
            val[0] = *l; val[1] = 0;
        } else continue;
        int v = vcd_var(d, id);
        if (v >= 0 && d->nev < 200000) {
            d->ev[d->nev].t = t;
            d->ev[d->nev].var = v;
            snprintf(d->ev[d->nev].val, sizeof d->ev[0].val, "%s", val);
            d->nev++;
        }
    }
}

/* Every variable's value at the end of time step t (after its changes). */
static void vcd_state(const vcd_dump *d, unsigned long long t, char st[64][72])
{
    for (int i = 0; i < 64; i++) st[i][0] = 0;
    for (int e = 0; e < d->nev && d->ev[e].t <= t; e++) snprintf(st[d->ev[e].var], 72, "%s", d->ev[e].val);
}

static void t_window(void)
{
    /* Six pixels of one cubic, dumped whole and with --vcd-from 2
     * --vcd-to 3. The window starts at the edge where item 2 is offered:
     * in the whole dump, where the input t first takes item 2's value; it
     * ends at the edge that samples item 3's output, the cycle the monitor
     * recorded (rising edges at 5 + 10 c end cycle c); and at every time
     * it has, it shows the whole dump's state. */
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = 24;
    unit_fmts fm;
    char err[300];
    TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s", err);
    vec_set vs;
    vec_set_init(&vs);
    tb_expected_header(u, &cfg, &vs);
    double ts[6] = { 0.125, 0.25, 0.375, 0.5, 0.625, 0.75 };
    for (int k = 0; k < 6; k++) {
        double t = ts[k], row[6] = { 1.5, -2.25, 0.75, 0.5, t, ((1.5 * t - 2.25) * t + 0.75) * t + 0.5 };
        vec_set_push(&vs, row);
    }
    char full[128], win[128];
    snprintf(full, sizeof full, "%s/full.vcd", tmpdir);
    snprintf(win, sizeof win, "%s/win.vcd", tmpdir);
    tb_opts of = { .vcd_path = full }, ow = { .vcd_path = win, .vcd_window = 1, .vcd_from = 2, .vcd_to = 3 };
    tb_result rf, rw;
    TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, &of, &rf, err, sizeof err), TB_OK);
    TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, &ow, &rw, err, sizeof err), TB_OK);
    char *tf = slurp(full, NULL), *tw = slurp(win, NULL);
    TST_CHECK(tf && tw, "no dumps");
    if (tf && tw) {
        static vcd_dump df, dw;
        vcd_parse(tf, &df);
        vcd_parse(tw, &dw);
        TST_EQ_INT(dw.nvars, df.nvars);
        TST_CHECK(dw.nev > 0, "empty window");
        /* item 2's t as the hardware holds it, in VCD binary */
        sim_fmt f = fm.f[unit_sig_index(u, "t")];
        int64_t raw = (int64_t)ldexp(ts[2], f.fbits);
        char bits[72] = "b";
        int nb = 0;
        for (int b = 63; b >= 0; b--) if (nb || (raw >> b & 1) || b == 0) bits[1 + nb++] = (char)('0' + (raw >> b & 1));
        bits[1 + nb] = 0;
        int tvar = -1;
        for (int i = 0; i < df.nvars; i++) if (!strcmp(df.names[i], "t")) tvar = i;
        unsigned long long t_offer = 0;
        int found = 0;
        for (int e = 0; e < df.nev && !found; e++)
            if (df.ev[e].var == tvar && !strcmp(df.ev[e].val, bits)) { t_offer = df.ev[e].t; found = 1; }
        TST_CHECK(found, "item 2's t (%s) never appears in the whole dump", bits);
        if (dw.nev > 0) {
            TST_EQ_INT(dw.ev[0].t, t_offer);
            TST_EQ_INT(dw.ev[dw.nev - 1].t, 5 + 10 * rf.beat_cycle[3]);
            TST_CHECK(strstr(tw, "$dumpvars") != NULL, "the window starts without $dumpvars");
            /* the same state at every time the window has */
            static char sf[64][72], sw[64][72];
            int bad = 0;
            for (int e = 0; e < dw.nev && !bad; e++) {
                if (e + 1 < dw.nev && dw.ev[e + 1].t == dw.ev[e].t) continue;
                vcd_state(&df, dw.ev[e].t, sf);
                vcd_state(&dw, dw.ev[e].t, sw);
                for (int i = 0; i < df.nvars && !bad; i++)
                    if (strcmp(sf[i], sw[i])) {
                        bad = 1;
                        TST_CHECK(0, "at #%llu %s is %s in the window, %s in the whole dump", dw.ev[e].t, df.names[i], sw[i], sf[i]);
                    }
            }
        }
        /* a window to the last item ends where the whole dump ends */
        free(dw.ev);
        free(df.ev);
    }
    free(tf); free(tw);
    tb_result_free(&rf); tb_result_free(&rw);
    snprintf(win, sizeof win, "%s/win2.vcd", tmpdir);
    tb_opts o2 = { .vcd_path = win, .vcd_window = 1, .vcd_from = 0, .vcd_to = 5 };
    TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, &o2, &rw, err, sizeof err), TB_OK);
    size_t n1, n2;
    tf = slurp(full, &n1);
    tw = slurp(win, &n2);
    TST_CHECK(tf && tw && n1 == n2 && !memcmp(tf, tw, n1), "the window 0..5 differs from the whole dump");
    free(tf); free(tw);
    tb_result_free(&rw);
    if (have("vcd2fst")) vcd2fst_accepts(full);   /* real variables included */
    unlink(full); unlink(win);
    snprintf(win, sizeof win, "%s/win.vcd", tmpdir);
    unlink(win);
    vec_set_free(&vs);
}

static void t_horner3_readback(void)
{
    /* Three pixels of one cubic; the VCD must show RG taking B, At+B,
     * (At+B)t, (At+B)t+C, ((At+B)t+C)t, I for each pixel in turn. */
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = 24;
    unit_fmts fm;
    char err[300];
    TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s", err);
    vec_set vs;
    vec_set_init(&vs);
    tb_expected_header(u, &cfg, &vs);
    double A = 1.5, B = -2.25, C = 0.75, D = 0.5, ts[3] = { 0.25, 0.5, 0.75 };
    for (int k = 0; k < 3; k++) {
        double t = ts[k], row[6] = { A, B, C, D, t, ((A * t + B) * t + C) * t + D };
        vec_set_push(&vs, row);
    }
    char path[128];
    snprintf(path, sizeof path, "%s/h3.vcd", tmpdir);
    tb_opts o = { .vcd_path = path, .gtkw = 1 };
    tb_result r;
    TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, &o, &r, err, sizeof err), TB_OK);
    TST_EQ_INT(r.cycles_per_item, 6);
    char *text = slurp(path, NULL);
    TST_CHECK(text != NULL, "no VCD");
    int64_t got[64];
    int n = text ? rg_history(text, got, 64) : -1;
    /* The expected RG sequence, exact at 24 bits for these dyadic values;
     * a value equal to the previous one makes no change in a VCD. */
    double want[64];
    int m = 0;
    want[m++] = 0;   /* $dumpvars */
    for (int k = 0; k < 3; k++) {
        double t = ts[k], s1 = B, s2 = A * t + B, s3 = s2 * t, s4 = s3 + C, s5 = s4 * t, s6 = s5 + D;
        double seq[6] = { s1, s2, s3, s4, s5, s6 };
        for (int j = 0; j < 6; j++) if (want[m - 1] != seq[j]) want[m++] = seq[j];
    }
    /* After the last pixel the controller waits at step 0, where RG loads B
     * (the inputs are held), on the edge that delivers the last output. */
    want[m++] = B;
    TST_EQ_INT(n, m);
    sim_fmt f = fm.f[unit_sig_index(u, "rg")];
    for (int i = 0; i < n && i < m; i++) TST_NEAR(sim_fx_to_real(got[i], f), want[i], 0);
    if (have("vcd2fst")) vcd2fst_accepts(path);
    /* The save file names the unit's signals. */
    char g[160];
    snprintf(g, sizeof g, "%s.gtkw", path);
    char *gt = slurp(g, NULL);
    TST_CHECK(gt && strstr(gt, "top.horner3.rg["), "gtkw content");
    /* It names its dump and itself by their names alone, as they lie
     * side by side (GTKWave resolves the dump from the save file's folder;
     * no absolute path: the same bytes wherever the run was), and shows rg
     * in fixed point: GTKWave's fixed-point flag (bit 30) and rg's
     * fraction bits. */
    char *dir = realpath(tmpdir, NULL), want_line[400], fp[200];
    snprintf(want_line, sizeof want_line, "[dumpfile] \"h3.vcd\"\n[savefile] \"h3.vcd.gtkw\"\n");
    TST_CHECK(gt && strstr(gt, want_line), "no %s in the .gtkw", want_line);
    TST_CHECK(gt && dir && !strstr(gt, dir), "an absolute path in the .gtkw");
    snprintf(fp, sizeof fp, "@40000424\n[fpshift_count] %d\ntop.horner3.rg[%d:0]\n", f.fbits, f.width - 1);
    TST_CHECK(gt && strstr(gt, fp), "rg is not shown as fixed point with %d fraction bits", f.fbits);
    TST_CHECK(gt && strstr(gt, "top.tb.expected_y\n") && strstr(gt, "top.tb.err_y\n"), "no expected/error traces in the .gtkw");
    free(dir);
    /* The expected and error traces: expected_y takes each pixel's value
     * from the vectors (the cubic of t, computed here), err_y the
     * hardware's output minus it, at each output beat. */
    double ex[8], er[8], wex[8] = { 0 }, wer[8] = { 0 };   /* 0 at $dumpvars */
    int ne = real_history(text, "expected_y", ex, 8), nr = real_history(text, "err_y", er, 8), mx = 1, mr = 1;
    for (int k = 0; k < 3; k++) {
        /* a value equal to the previous one is no change */
        double t = ts[k], y = ((A * t + B) * t + C) * t + D, e = sim_fx_to_real(r.raw[k], r.out[0].fmt) - y;
        if (y != wex[mx - 1]) wex[mx++] = y;
        if (e != wer[mr - 1]) wer[mr++] = e;
    }
    TST_EQ_INT(ne, mx);
    TST_EQ_INT(nr, mr);
    for (int k = 0; k < ne && k < mx; k++) TST_NEAR(ex[k], wex[k], 0);
    for (int k = 0; k < nr && k < mr; k++) TST_NEAR(er[k], wer[k], 0);
    free(gt); free(text);
    unlink(g); unlink(path);
    tb_result_free(&r);
    vec_set_free(&vs);
}

static void t_vcd2fst(void)
{
    if (!have("vcd2fst")) TST_SKIP("vcd2fst not installed (Debian package gtkwave)");
    char path[128];
    snprintf(path, sizeof path, "%s/small2.vcd", tmpdir);
    small_design(path);
    vcd2fst_accepts(path);
    unlink(path);
}

int main(void)
{
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    TST_RUN(t_golden_small);
    TST_RUN(t_unwritable);
    TST_RUN(t_horner3_readback);
    TST_RUN(t_window);
    TST_RUN(t_vcd2fst);
    rmdir(tmpdir);
    TST_EXIT();
}
