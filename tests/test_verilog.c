/* test_verilog.c - an independent reference for the whole horner3 datapath:
 * Icarus Verilog simulates bench/verilog/horner3.v (RTL written from the
 * paper, not from units/unit_horner.c) on the float reference's vectors,
 * quantized exactly as the testbench quantizes them, and every output raw
 * and the cycle it appeared in must equal shadesim's, at two widths.
 * Skipped when iverilog is not installed. */
#include "tests/tst.h"
#include "testbench/cli.h"
#include <unistd.h>

#define NVEC 200

static char tmpdir[] = "/tmp/shadesim_verilog_XXXXXX";

static int have(const char *tool)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

static int is_fmt(sim_fmt f, int is_signed, int ibits, int fbits)
{
    return f.is_signed == is_signed && f.ibits == ibits && f.fbits == fbits;
}

static void one_width(int W)
{
    const unit_desc *u = unit_find("horner3");
    TST_CHECK(u != NULL, "no horner3 unit");
    if (!u) return;
    unit_cfg cfg;
    unit_cfg_default(&cfg);
    cfg.width = W;
    char err[600];
    unit_fmts fm;
    TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s", err);

    /* The RTL hard-wires shadesim's default rule and modes; say so if they
     * ever change, rather than compare two different designs. */
    static const char *const dp[] = { "a", "b", "c", "d", "y", "mx1", "mul", "mx2", "bk", "sm", "rg" };
    for (size_t i = 0; i < sizeof dp / sizeof dp[0]; i++) {
        int k = unit_sig_index(u, dp[i]);
        TST_CHECK(k >= 0 && is_fmt(fm.f[k], 1, 7, W - 7), "W=%d: %s is not s7.%d as horner3.v assumes", W, dp[i], W - 7);
    }
    int kt = unit_sig_index(u, "t");
    TST_CHECK(kt >= 0 && is_fmt(fm.f[kt], 0, 1, W - 1), "W=%d: t is not u1.%d as horner3.v assumes", W, W - 1);
    TST_CHECK(cfg.rnd == SIM_RND_TRUNC && cfg.ovf == SIM_OVF_WRAP, "default modes are not trunc/wrap");

    vec_set vs;
    TST_CHECK(cli_make_vectors(u, &cfg, NVEC, 11, &vs, err, sizeof err) == 0, "%s", err);
    TST_EQ_INT(vs.n_rows, NVEC);

    /* Inputs quantized as tb_run does, as hex raws of W bits. */
    char in_path[128], out_path[128], vvp[128], cmd[1024];
    snprintf(in_path, sizeof in_path, "%s/in%d.hex", tmpdir, W);
    snprintf(out_path, sizeof out_path, "%s/out%d.txt", tmpdir, W);
    snprintf(vvp, sizeof vvp, "%s/tb%d.vvp", tmpdir, W);
    FILE *f = fopen(in_path, "w");
    TST_CHECK(f != NULL, "cannot write %s", in_path);
    if (!f) { vec_set_free(&vs); return; }
    static const char *const in_names[] = { "a", "b", "c", "d", "t" };
    uint64_t mask = ((uint64_t)1 << W) - 1;
    for (size_t r = 0; r < vs.n_rows; r++)
        for (int i = 0; i < 5; i++) {
            sim_fmt qf = fm.f[unit_sig_index(u, in_names[i])];
            int64_t raw = sim_fx_from_real(vec_row(&vs, r)[i], qf, cfg.rnd, cfg.ovf, NULL);
            fprintf(f, "%llx%c", (unsigned long long)((uint64_t)raw & mask), i < 4 ? ' ' : '\n');
        }
    TST_CHECK(fclose(f) == 0, "write %s", in_path);

    snprintf(cmd, sizeof cmd,
             "iverilog -g2005 -P horner3_tb.W=%d -P horner3_tb.MAXN=%d -o %s "
             "bench/verilog/horner3_tb.v bench/verilog/horner3.v 2>&1 && "
             "vvp -n %s +in=%s +out=%s >/dev/null 2>&1",
             W, NVEC + 8, vvp, vvp, in_path, out_path);
    TST_CHECK(system(cmd) == 0, "W=%d: icarus failed: %s", W, cmd);

    /* Icarus: "CYCLE Y" per output. */
    int64_t iy[NVEC + 1];
    long long icyc[NVEC + 1];
    int n = 0;
    f = fopen(out_path, "r");
    TST_CHECK(f != NULL, "W=%d: no icarus output", W);
    if (f) {
        long long cy, yv;
        while (n <= NVEC && fscanf(f, "%lld %lld", &cy, &yv) == 2) { icyc[n] = cy; iy[n] = yv; n++; }
        fclose(f);
    }
    TST_EQ_INT(n, NVEC);

    /* shadesim on the same vectors. */
    tb_result r;
    int rc = tb_run(u, &cfg, &fm, &vs, NULL, &r, err, sizeof err);
    TST_CHECK(rc == TB_OK, "W=%d: %s", W, err);
    if (rc == TB_OK) {
        int bad = 0;
        for (int i = 0; i < n && i < (int)r.vectors; i++) {
            if (r.raw[i] != iy[i] || (long long)r.beat_cycle[i] != icyc[i]) {
                if (bad++ < 5)
                    TST_CHECK(0, "W=%d pixel %d: shadesim y raw %lld at cycle %llu, icarus %lld at cycle %lld",
                              W, i, (long long)r.raw[i], (unsigned long long)r.beat_cycle[i],
                              (long long)iy[i], icyc[i]);
            }
        }
        TST_EQ_INT(bad, 0);
        TST_NEAR(r.cycles_per_item, 6, 0);
        TST_EQ_INT(r.latency, 6);
        for (int i = 1; i < n; i++)
            if (icyc[i] - icyc[i - 1] != 6) { TST_CHECK(0, "W=%d: icarus pixel %d after %lld cycles", W, i, icyc[i] - icyc[i - 1]); break; }
        /* Not a trivial comparison: the outputs vary. */
        int distinct = 0;
        for (int i = 1; i < n; i++) distinct += iy[i] != iy[i - 1];
        TST_CHECK(distinct > NVEC / 4, "W=%d: only %d changes in %d outputs", W, distinct, n);
        tb_result_free(&r);
    }
    vec_set_free(&vs);
    unlink(in_path); unlink(out_path); unlink(vvp);
}

static void t_horner3_icarus(void)
{
    if (!have("iverilog") || !have("vvp")) TST_SKIP("iverilog not installed");
    one_width(16);
    one_width(12);
    one_width(24);
}

int main(void)
{
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    TST_RUN(t_horner3_icarus);
    rmdir(tmpdir);
    TST_EXIT();
}
