/* test_vcd.c - the VCD writer: a small design's dump equals a checked-in
 * file; a 3-pixel horner3 run read back shows RG's Horner sequence; every
 * dump is accepted by GTKWave's vcd2fst when it is installed. */
#include "tests/tst.h"
#include "sim/sim.h"
#include "sim/sim_prim.h"
#include "sim/sim_vcd.h"
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
    sim_fmt u3 = { 0, 3, 0, 3 }, s4 = { 1, 2, 2, 4 };
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
    sim_vcd *v = sim_vcd_open(c, path, "1ns", err, sizeof err);
    TST_CHECK(v != NULL, "%s", err);
    sim_run(c, 60);
    TST_EQ_INT(sim_vcd_close(v), 0);
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
    sim_ctx *c = sim_new();
    sim_bit_new(c, NULL, "x", SIM_KIND_WIRE);
    char err[200] = "";
    sim_vcd *v = sim_vcd_open(c, "/nonexistent/dir/x.vcd", "1ns", err, sizeof err);
    TST_CHECK(v == NULL, "opened an impossible path");
    TST_CHECK(strstr(err, "/nonexistent/dir/x.vcd") != NULL && !strchr(err, '\n'), "%s", err);
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

static void t_horner3_readback(void)
{
    /* Three pixels of one cubic; the VCD must show RG taking B, At+B,
     * (At+B)t, (At+B)t+C, ((At+B)t+C)t, I for each pixel in turn. */
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(&cfg);
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
    tb_opts o = { path, 1 };
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
    TST_CHECK(gt && strstr(gt, "top.horner3.rg[") && strstr(gt, "[dumpfile] \"h3.vcd\""), "gtkw content");
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
    TST_RUN(t_vcd2fst);
    rmdir(tmpdir);
    TST_EXIT();
}
