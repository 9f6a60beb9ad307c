/* test_verilog.c - the Verilog export against shadesim, and shadesim
 * against RTL written by hand.
 *
 *  - t_horner3_handwritten: Icarus Verilog simulates
 *    tests/data/verilog/horner3_ref.v (RTL written from the paper, not
 *    from units/unit_horner.c nor by the exporter) on the float
 *    reference's vectors, and every output raw and its cycle must equal
 *    shadesim's, at three widths.
 *  - t_cosim_icarus: every unit and schedule the export covers, at two
 *    widths and two rounding/overflow mode pairs: the exported module in
 *    Icarus gives every output raw at the same cycle as shadesim; the
 *    units it refuses are exactly the known ones, with the reason.
 *  - t_cosim_verilator, t_lint, t_yosys: a subset in Verilator; every
 *    export with its testbench lint-clean under `verilator --lint-only
 *    -Wall --timing` (Verilator 5 needs --timing or --no-timing for any
 *    delay, the testbench's clock); every export read alone, parsed and
 *    coarse-synthesized by Yosys (a small one fully).
 *  - t_cosim_resets, t_reset_flops: the asynchronous reset and no reset
 *    (initial blocks) bit-exact too, on units with registers that reset to
 *    1 and registers with an enable; Yosys finds every one of horner3's 20
 *    register bits (3 step, 16 RG, 1 out_valid: counted by hand from the
 *    datapath) with the reset asked for.
 * The tool-driven tests run in the plain build only, and are skipped when
 * their tool is not installed.
 *
 * TST_VERILOG_FULL=1 (tests/cli_verilog_full.sh, in `make test-long`) runs
 * the whole matrix: every unit and schedule at 16 and 24 bits in Icarus,
 * every schedule linted and synthesized. make test runs one design a
 * unit and schedule in Icarus (the width and mode pair turning with the
 * schedule's place in the list, so that every pair is met), and lints and
 * synthesizes each unit's first schedule: the same checks, a third of
 * the tools' time. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include "testbench/tb_verilog.h"
#include "sim/sim_verilog.h"
#include <sys/stat.h>
#include <string.h>
#include <unistd.h>

#define NVEC 200

static char tmpdir[] = "/tmp/shadesim_verilog_XXXXXX";

static int have(const char *tool)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* The whole matrix (TST_VERILOG_FULL=1) or the suite's part of it. */
static int full_matrix(void)
{
    const char *e = getenv("TST_VERILOG_FULL");
    return e && !strcmp(e, "1");
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
    unit_cfg_default(u, &cfg);
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
    TST_CHECK(tb_make_vectors(u, &cfg, NVEC, 11, &vs, err, sizeof err) == 0, "%s", err);
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
             "iverilog -g2005 -P horner3_ref_tb.W=%d -P horner3_ref_tb.MAXN=%d -o %s "
             "tests/data/verilog/horner3_ref_tb.v tests/data/verilog/horner3_ref.v 2>&1 && "
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

static void t_horner3_handwritten(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("iverilog") || !have("vvp")) TST_SKIP("iverilog not installed");
    one_width(16);
    one_width(12);
    one_width(24);
}

/* One design: export into a fresh folder under tmpdir, cosim; returns the
 * folder's path (static buffer) or NULL. */
static const char *cosim_one(const unit_desc *u, int sched, int W, sim_round rnd, sim_ovf ovf, int sim, int n,
                             int *exact)
{
    static char dir[256];
    static int seq;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = W; cfg.schedule = sched; cfg.rnd = rnd; cfg.ovf = ovf;
    unit_fmts fm;
    char err[600], msg[1200];
    *exact = 0;
    TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s: %s", u->name, err);
    vec_set vs;
    if (tb_make_vectors(u, &cfg, (size_t)n, 3, &vs, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return NULL; }
    snprintf(dir, sizeof dir, "%s/d%d", tmpdir, seq++);
    mkdir(dir, 0777);
    int rc = tb_cosim(u, &cfg, &fm, &vs, sim, dir, msg, sizeof msg);
    vec_set_free(&vs);
    TST_CHECK(rc == TB_COSIM_EXACT, "%s %s W=%d %s/%s: %s", u->name, u->sched[sched].name, W,
              sim_round_name(rnd), sim_ovf_name(ovf), msg);
    *exact = rc == TB_COSIM_EXACT;
    return dir;
}

/* Lines of a file, and how many distinct ones. */
static void count_lines(const char *path, int *lines, int *distinct)
{
    char prev[512] = "", cur[512];
    *lines = *distinct = 0;
    FILE *f = fopen(path, "r");
    if (!f) return;
    while (fgets(cur, sizeof cur, f)) {
        ++*lines;
        /* the output raws after the cycle */
        const char *a = strchr(cur, ' '), *b = strchr(prev, ' ');
        if (!b || !a || strcmp(a, b)) ++*distinct;
        snprintf(prev, sizeof prev, "%s", cur);
    }
    fclose(f);
}

static void rm_rf(const char *dir)
{
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd)) { /* best effort */ }
}

static void t_cosim_icarus(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("iverilog") || !have("vvp")) TST_SKIP("iverilog not installed");
    static const struct { sim_round r; sim_ovf o; } modes[] = { { SIM_RND_TRUNC, SIM_OVF_WRAP }, { SIM_RND_EVEN, SIM_OVF_SAT },
                                                               { SIM_RND_HALF_UP, SIM_OVF_WRAP } };
    int designs = 0, full = full_matrix(), turn = 0;
    for (size_t k = 0; k < unit_count(); k++) {
        const unit_desc *u = unit_at(k);
        int span = !strncmp(u->name, "span", 4);
        for (int s = 0; s < u->nsched; s++, turn++)
            for (int wi = 0; wi < 2; wi++)
                for (int m = 0; m < 3; m++) {
                    /* trunc/wrap at 16 bits, even/sat at 24, half-up/wrap
                     * at 16 but not for the span units (interp's datapath
                     * with a span controller); outside the full matrix,
                     * the one pair of the three this schedule's turn picks */
                    if ((m == 0 && wi) || (m == 1 && !wi) || (m == 2 && (wi || span))) continue;
                    if (!full && m != turn % (span ? 2 : 3)) continue;
                    int W = wi ? 24 : 16, exact;
                    const char *dir = cosim_one(u, s, W, modes[m].r, modes[m].o, TB_SIM_ICARUS, 12, &exact);
                    if (!dir) continue;
                    designs++;
                    if (exact) {
                        /* the comparison is not vacuous: every beat is there,
                         * and the outputs vary */
                        char p[300];
                        int lines, distinct;
                        snprintf(p, sizeof p, "%s/icarus.out", dir);
                        count_lines(p, &lines, &distinct);
                        unit_cfg cfg;
                        unit_cfg_default(u, &cfg);
                        cfg.schedule = s;
                        TST_EQ_INT(lines, 12 * u->beats(&cfg));
                        TST_CHECK(distinct >= 2, "%s: only %d distinct outputs", u->name, distinct);
                    }
                    rm_rf(dir);
                }
    }
    TST_CHECK(designs >= (full ? 90 : 40), "only %d designs co-simulated", designs);
    printf("  %d designs bit-exact in Icarus\n", designs);
}

/* Verilator on horner3 with the asynchronous reset (the synchronous one:
 * tests/cli_rtl.sh, the hand-written design in Verilator). */
static void t_cosim_verilator(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("verilator")) TST_SKIP("verilator not installed");
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.rnd = SIM_RND_EVEN; cfg.ovf = SIM_OVF_SAT;
    unit_fmts fm;
    char err[600], msg[1200], dir[256];
    TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s", err);
    vec_set vs;
    if (tb_make_vectors(u, &cfg, 12, 3, &vs, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    snprintf(dir, sizeof dir, "%s/va", tmpdir);
    mkdir(dir, 0777);
    tb_cosim_opts co = { SIM_VRESET_ASYNC, NULL, 0, NULL, 0, 0 };
    int rc = tb_cosim_opt(u, &cfg, &fm, &vs, &co, TB_SIM_VERILATOR, dir, msg, sizeof msg);
    TST_CHECK(rc == TB_COSIM_EXACT && strstr(msg, "(verilator)"), "%s", msg);
    vec_set_free(&vs);
    rm_rf(dir);
}

/* Export (unit, schedule) at W into dir; 0 on success. */
static int export_one_reset(const unit_desc *u, int s, int W, sim_round r, sim_ovf o, sim_vreset reset, const char *dir)
{
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.width = W; cfg.schedule = s; cfg.rnd = r; cfg.ovf = o;
    unit_fmts fm;
    char err[600];
    if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) return -1;
    return tb_verilog_write(u, &cfg, &fm, reset, dir, NULL, err, sizeof err);
}

static int export_one(const unit_desc *u, int s, int W, sim_round r, sim_ovf o, const char *dir)
{
    return export_one_reset(u, s, W, r, o, SIM_VRESET_SYNC, dir);
}

/* verilator --lint-only -Wall --timing on the module and its testbench:
 * no line at all. */
static int lint_clean(const unit_desc *u, const char *sched, const char *dir, const char *what)
{
    char cmd[800], log[300];
    snprintf(cmd, sizeof cmd, "cd %s && verilator --lint-only -Wall --timing %s.v %s_tb.v >lint.log 2>&1",
             dir, u->name, u->name);
    int rc = system(cmd);
    snprintf(log, sizeof log, "%s/lint.log", dir);
    int lines, distinct;
    count_lines(log, &lines, &distinct);
    TST_CHECK(rc == 0 && lines == 0, "%s %s %s: verilator -Wall gave %d lines (rc %d)", u->name, sched, what, lines, rc);
    return rc == 0 && lines == 0;
}

static void t_lint(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("verilator")) TST_SKIP("verilator not installed");
    int n = 0;
    for (size_t k = 0; k < unit_count(); k++) {
        const unit_desc *u = unit_at(k);
        for (int s = 0; s < u->nsched; s++) {
            /* even/sat: the most logic; the default synchronous reset, and
             * for the first schedule of each unit the other two */
            for (int rs = 0; rs < 3; rs++) {
                if (rs && s) continue;
                /* outside the full matrix: the first schedule, its reset
                 * style turning with the unit's place in the list */
                if (!full_matrix() && (s || rs != (int)(k % 3))) continue;
                char dir[200];
                snprintf(dir, sizeof dir, "%s/lint", tmpdir);
                if (export_one_reset(u, s, 16, SIM_RND_EVEN, SIM_OVF_SAT, (sim_vreset)rs, dir)) {
                    TST_CHECK(0, "%s: export failed", u->name);
                    continue;
                }
                static const char *const rn[] = { "sync", "async", "none" };
                n += lint_clean(u, u->sched[s].name, dir, rn[rs]);
                rm_rf(dir);
            }
        }
    }
    TST_CHECK(n >= (full_matrix() ? 50 : 20), "only %d exports linted clean", n);
}

static void t_yosys(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("yosys")) TST_SKIP("yosys not installed");
    int n = 0;
    for (size_t k = 0; k < unit_count(); k++) {
        const unit_desc *u = unit_at(k);
        /* shade_cook's coarse synthesis alone takes half a minute of CPU
         * at width 16 (some 300 stage registers of 30 bits): the full
         * matrix (make test-long) runs it */
        if (!full_matrix() && !strcmp(u->name, "shade_cook")) continue;
        for (int s = 0; s < (full_matrix() ? u->nsched : 1); s++) {
            char dir[200], cmd[1400];
            snprintf(dir, sizeof dir, "%s/ys", tmpdir);
            if (export_one(u, s, 16, SIM_RND_EVEN, SIM_OVF_SAT, dir)) { TST_CHECK(0, "%s: export failed", u->name); continue; }
            /* parse, elaborate and coarse synthesis (every export); the
             * whole flow down to gates for div3 */
            int full = !strcmp(u->name, "div3");
            snprintf(cmd, sizeof cmd, "yosys -q -p 'read_verilog %s/%s.v; synth -top %s%s; tee -o %s/stat.txt stat' >%s/ys.log 2>&1",
                     dir, u->name, u->name, full ? "; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX" : " -run begin:fine", dir, dir);
            TST_CHECK(system(cmd) == 0, "%s %s: yosys failed (%s/ys.log)", u->name, u->sched[s].name, dir);
            char st[300];
            snprintf(st, sizeof st, "%s/stat.txt", dir);
            FILE *f = fopen(st, "r");
            long cells = -1;
            char line[300];
            while (f && fgets(line, sizeof line, f)) if (strstr(line, "Number of cells:")) cells = atol(strchr(line, ':') + 1);
            if (f) fclose(f);
            TST_CHECK(cells > 0, "%s %s: yosys reports %ld cells", u->name, u->sched[s].name, cells);
            n++;
            rm_rf(dir);
        }
    }
    TST_CHECK(n >= 20, "only %d exports synthesized", n);
}

/* The asynchronous reset and no reset: bit-exact too, in Icarus
 * (t_cosim_verilator: the asynchronous one in Verilator), on horner3, a unit whose registers reset to 1 and to a
 * control word (pow_n: brdf_seq's "first" and decoders) and one whose
 * registers have enables (interp3 fwd). */
static void t_cosim_resets(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("iverilog") || !have("vvp")) TST_SKIP("iverilog not installed");
    static const char *const names[] = { "horner3", "pow_n", "interp3" };
    for (size_t i = 0; i < 3; i++)
        for (int rs = SIM_VRESET_ASYNC; rs <= SIM_VRESET_NONE; rs++) {
            const unit_desc *u = unit_find(names[i]);
            TST_CHECK(u != NULL, "no unit %s", names[i]);
            if (!u) continue;
            unit_cfg cfg;
            unit_cfg_default(u, &cfg);
            int s = 0;
            while (s < u->nsched && strcmp(u->sched[s].name, "fwd")) s++;
            cfg.schedule = s < u->nsched ? s : 0;
            unit_fmts fm;
            char err[600], msg[1200], dir[256];
            TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s", err);
            vec_set vs;
            if (tb_make_vectors(u, &cfg, 12, 9, &vs, err, sizeof err)) { TST_CHECK(0, "%s", err); continue; }
            snprintf(dir, sizeof dir, "%s/r%zu_%d", tmpdir, i, rs);
            mkdir(dir, 0777);
            tb_cosim_opts co = { (sim_vreset)rs, NULL, 0, NULL, 0, 0 };
            int rc = tb_cosim_opt(u, &cfg, &fm, &vs, &co, TB_SIM_ICARUS, dir, msg, sizeof msg);
            TST_CHECK(rc == TB_COSIM_EXACT, "%s reset %d: %s", names[i], rs, msg);
            vec_set_free(&vs);
            rm_rf(dir);
        }
}

/* Yosys on horner3 alone, each reset: its flip-flop cells by type. */
static void t_reset_flops(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("yosys")) TST_SKIP("yosys not installed");
    const unit_desc *u = unit_find("horner3");
    for (int rs = 0; rs < 3; rs++) {
        char dir[200], cmd[1400], st[300], line[300];
        snprintf(dir, sizeof dir, "%s/yr%d", tmpdir, rs);
        TST_CHECK(export_one_reset(u, 0, 16, SIM_RND_TRUNC, SIM_OVF_WRAP, (sim_vreset)rs, dir) == 0, "export");
        snprintf(cmd, sizeof cmd, "yosys -q -p 'read_verilog %s/horner3.v; synth -top horner3; tee -o %s/stat.txt stat' >%s/ys.log 2>&1",
                 dir, dir, dir);
        TST_CHECK(system(cmd) == 0, "reset %d: yosys failed (%s/ys.log)", rs, dir);
        snprintf(st, sizeof st, "%s/stat.txt", dir);
        FILE *f = fopen(st, "r");
        long sdff = 0, adff = 0, all = 0;
        while (f && fgets(line, sizeof line, f)) {
            char cell[100];
            long n;
            if (sscanf(line, " %99s %ld", cell, &n) != 2 || !strstr(cell, "DFF")) continue;
            all += n;
            if (!strncmp(cell, "$_SDFF", 6)) sdff += n;
            else if (strpbrk(strchr(cell + 2, '_'), "01")) adff += n;   /* $_DFF_PP0_: a reset value */
        }
        if (f) fclose(f);
        TST_EQ_INT(all, 20);
        if (rs == SIM_VRESET_SYNC) TST_EQ_INT(sdff, 20);
        if (rs == SIM_VRESET_ASYNC) TST_EQ_INT(adff, 20);
        if (rs == SIM_VRESET_NONE) TST_EQ_INT(adff, 0);
        rm_rf(dir);
    }
}

/* Parameters change the built design (div3's terms, interp's L, the
 * powers): a few of them, co-simulated. */
static void t_cosim_params(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("iverilog") || !have("vvp")) TST_SKIP("iverilog not installed");
    static const struct { const char *u, *p, *v; } P[] = {
        { "div3", "terms", "6" }, { "div3", "series", "quarter" }, { "interp3", "L", "4" },
        { "pow_n", "n", "7" }, { "mschlick", "n", "8" }, { "d_approx", "g", "8" } };
    for (size_t i = 0; i < sizeof P / sizeof P[0]; i++) {
        const unit_desc *u = unit_find(P[i].u);
        TST_CHECK(u != NULL, "no unit %s", P[i].u);
        if (!u) continue;
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        cfg.width = 20; cfg.rnd = SIM_RND_HALF_UP; cfg.ovf = SIM_OVF_SAT;
        char err[600], msg[1200], dir[256];
        TST_CHECK(unit_param_set(u, &cfg, P[i].p, P[i].v, err, sizeof err) == 0, "%s", err);
        unit_fmts fm;
        TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s", err);
        vec_set vs;
        if (tb_make_vectors(u, &cfg, 12, 5, &vs, err, sizeof err)) { TST_CHECK(0, "%s", err); continue; }
        snprintf(dir, sizeof dir, "%s/p%zu", tmpdir, i);
        mkdir(dir, 0777);
        int rc = tb_cosim(u, &cfg, &fm, &vs, TB_SIM_ICARUS, dir, msg, sizeof msg);
        TST_CHECK(rc == TB_COSIM_EXACT, "%s %s=%s: %s", P[i].u, P[i].p, P[i].v, msg);
        vec_set_free(&vs);
        rm_rf(dir);
    }
}

/* A logic element too wide to tabulate and without RTL text is refused,
 * naming it; a narrow one is tabulated exactly (checked against the C
 * function for every input). */
static int64_t f_parity_plus(const int64_t *in, void *u) { (void)u; return __builtin_popcountll((uint64_t)in[0]) + in[1]; }
static void t_logic_table(void)
{
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *sc = sim_scope_new(c, NULL, "u");
    sim_signal *a = sim_signal_new(c, sc, "a", unit_fmt(0, 9, 0), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, sc, "b", unit_fmt(1, 9, 0), SIM_KIND_INPUT);
    sim_signal *in[2] = { a, b };
    sim_signal *y = sim_logic(c, sc, "y", unit_fmt(1, 5, 0), 2, in, f_parity_plus, NULL, 1.0);
    sim_vport ports[3] = { { "a", a, 0 }, { "b", b, 0 }, { "y", y, 1 } };
    char err[300] = "";
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    int rc = sim_verilog_module(f, c, sc, "u", clk, SIM_VRESET_SYNC, ports, 3, err, sizeof err);
    fclose(f);
    TST_CHECK(rc == -1 && strstr(err, "logic element y has 18 input bits"), "rc %d, err '%s'", rc, err);
    free(buf);
    sim_free(c);

    /* 4 + 3 bits: the table, entry by entry */
    c = sim_new();
    clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sc = sim_scope_new(c, NULL, "u");
    a = sim_signal_new(c, sc, "a", unit_fmt(0, 4, 0), SIM_KIND_INPUT);
    b = sim_signal_new(c, sc, "b", unit_fmt(1, 3, 0), SIM_KIND_INPUT);
    in[0] = a; in[1] = b;
    y = sim_logic(c, sc, "y", unit_fmt(1, 4, 0), 2, in, f_parity_plus, NULL, 1.0);
    ports[0].sig = a; ports[1].sig = b; ports[2].sig = y;
    buf = NULL;
    f = open_memstream(&buf, &len);
    rc = sim_verilog_module(f, c, sc, "u", clk, SIM_VRESET_SYNC, ports, 3, err, sizeof err);
    fclose(f);
    TST_EQ_INT(rc, 0);
    int checked = 0;
    for (int av = 0; av < 16 && buf; av++)
        for (int bv = -4; bv < 4; bv++) {
            /* the expected value, computed here: popcount(a) + b, in s4.0 */
            int v = __builtin_popcount((unsigned)av) + bv;
            unsigned key = ((unsigned)av << 3) | ((unsigned)bv & 7);
            char want[64];
            snprintf(want, sizeof want, "7'h%x: y__t = 4'h%x;", key, (unsigned)v & 15);
            /* the default value is not listed: find the line or the default */
            if (strstr(buf, want)) { checked++; continue; }
            char keyl[32];
            snprintf(keyl, sizeof keyl, "7'h%x:", key);
            TST_CHECK(!strstr(buf, keyl), "a=%d b=%d: wrong entry", av, bv);
            char dflt[64];
            snprintf(dflt, sizeof dflt, "default: y__t = 4'h%x;", (unsigned)v & 15);
            TST_CHECK(strstr(buf, dflt) != NULL, "a=%d b=%d: not the default either", av, bv);
            checked++;
        }
    TST_EQ_INT(checked, 128);
    free(buf);
    sim_free(c);
}

int main(void)
{
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    TST_RUN(t_horner3_handwritten);
    TST_RUN(t_logic_table);
    TST_RUN(t_cosim_icarus);
    TST_RUN(t_cosim_params);
    TST_RUN(t_cosim_resets);
    TST_RUN(t_reset_flops);
    TST_RUN(t_cosim_verilator);
    TST_RUN(t_lint);
    TST_RUN(t_yosys);
    rm_rf(tmpdir);
    TST_EXIT();
}
