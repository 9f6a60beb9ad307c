/* test_items.c - a unit over a list of items on the batch's lanes
 * (testbench/tb_items.c) against the kernel's testbench (tb_run) on the
 * same items: every output, the steady-state clocks per item and the area
 * equal tb_run's; the figures are the same for any number of threads. A
 * memo of runs (tb_items_memo.c) answers the same run with tb_items_run's
 * bytes and runs anything else. */
#include "tests/tst.h"
#include "testbench/tb_items_memo.h"
#include "sim/sim_fixed.h"

/* n items of u's reference vectors (seed 3) through tb_items_run on
 * `jobs` threads and through tb_run. */
static void same_as_tb_run(const char *name, size_t n)
{
    const unit_desc *u = unit_find(name);
    TST_CHECK(u && u->ref, "no unit %s", name);
    if (!u || !u->ref) return;
    unit_cfg cfg;
    unit_fmts f;
    char err[600];
    unit_cfg_default(u, &cfg);
    TST_CHECK(!tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err), "%s", err);
    vec_set vs;
    vec_set_init(&vs);
    vec_set_header(&vs, u->ref, &cfg.model);
    TST_CHECK(!u->ref->gen(&cfg.model, n, 3, &vs), "vectors");
    int n_in = unit_n_in(u), n_out = unit_n_out(u);
    double *in = malloc(vs.n_rows * (size_t)n_in * sizeof *in), *o1 = malloc(vs.n_rows * sizeof *o1),
           *o2 = malloc(vs.n_rows * sizeof *o2);
    for (size_t i = 0; i < vs.n_rows; i++)
        for (int k = 0; k < n_in; k++) in[i * (size_t)n_in + k] = vec_row(&vs, i)[k];
    tb_items_stats s1, s2;
    TST_EQ_INT(tb_items_run(u, &cfg, &f, in, vs.n_rows, 1, 1, o1, &s1, err, sizeof err), TB_OK);
    TST_EQ_INT(tb_items_run(u, &cfg, &f, in, vs.n_rows, 2, 1, o2, &s2, err, sizeof err), TB_OK);
    tb_result r;
    TST_EQ_INT(tb_run(u, &cfg, &f, &vs, NULL, &r, err, sizeof err), TB_OK);
    size_t bad = 0;
    for (size_t i = 0; i < vs.n_rows; i++) {
        double want = sim_fx_to_real(r.raw[i * (size_t)r.beats * (size_t)n_out], r.out[0].fmt);
        bad += o1[i] != want || o2[i] != want;
    }
    TST_EQ_INT(bad, 0);
    TST_NEAR(s1.cycles_per_item, r.cycles_per_item, 0);
    TST_NEAR(s1.area_ge, r.area_ge, 1e-9);
    TST_CHECK(s1.lanes > 1 || vs.n_rows <= 256, "%s: %u lanes for %zu items", name, s1.lanes, vs.n_rows);
    /* the threads change nothing */
    TST_CHECK(s1.clocks == s2.clocks && s1.energy_pj == s2.energy_pj && s1.overflows == s2.overflows,
              "%s: -j 1 and -j 2 differ", name);
    TST_CHECK(s1.energy_pj > 0, "%s: no energy counted", name);
    tb_result_free(&r);
    vec_set_free(&vs);
    free(in);
    free(o1);
    free(o2);
}

static void div_items(void) { same_as_tb_run("div", 3000); }

/* More lanes than a group holds: the figures, energy too, the same for
 * one thread and three. */
static void groups_any_jobs(void)
{
    const unit_desc *u = unit_find("div");
    unit_cfg cfg;
    unit_fmts f;
    char err[600];
    unit_cfg_default(u, &cfg);
    TST_CHECK(!tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err), "%s", err);
    size_t n = 40000;
    double *in = malloc(2 * n * sizeof *in), *o1 = malloc(n * sizeof *o1), *o3 = malloc(n * sizeof *o3);
    for (size_t i = 0; i < n; i++) {
        in[2 * i] = (double)(i % 97) / 200;          /* a < b: the quotient below 1 */
        in[2 * i + 1] = 0.5 + (double)(i % 89) / 200;
    }
    tb_items_stats s1, s3;
    TST_EQ_INT(tb_items_run(u, &cfg, &f, in, n, 1, 1, o1, &s1, err, sizeof err), TB_OK);
    TST_EQ_INT(tb_items_run(u, &cfg, &f, in, n, 3, 1, o3, &s3, err, sizeof err), TB_OK);
    TST_CHECK(s1.lanes > 128, "%u lanes: one group only", s1.lanes);
    TST_CHECK(!memcmp(o1, o3, n * sizeof *o1), "outputs differ");
    TST_CHECK(s1.clocks == s3.clocks && s1.energy_pj == s3.energy_pj && s1.cycles_per_item == s3.cycles_per_item,
              "-j 1 and -j 3: %g and %g pJ", s1.energy_pj, s3.energy_pj);
    free(in);
    free(o1);
    free(o3);
}
static void powg_items(void) { same_as_tb_run("powg", 700); }

/* One run of div through memo m, against tb_items_run without it: the
 * same outputs and figures, byte for byte. */
static void memo_run_same(tb_items_memo *m, int width, const double *in, size_t n)
{
    const unit_desc *u = unit_find("div");
    unit_cfg cfg;
    unit_fmts f;
    char err[600];
    unit_cfg_default(u, &cfg);
    cfg.width = width;
    TST_CHECK(!tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err), "%s", err);
    double *o1 = malloc(n * sizeof *o1), *o2 = malloc(n * sizeof *o2);
    tb_items_stats s1, s2;
    TST_EQ_INT(tb_items_run_memo(m, u, &cfg, &f, in, n, 2, 1, o1, &s1, err, sizeof err), TB_OK);
    TST_EQ_INT(tb_items_run(u, &cfg, &f, in, n, 1, 1, o2, &s2, err, sizeof err), TB_OK);
    TST_CHECK(!memcmp(o1, o2, n * sizeof *o1), "width %d: outputs differ from a run without the memo", width);
    TST_CHECK(s1.items == s2.items && s1.lanes == s2.lanes && s1.clocks == s2.clocks &&
              s1.cycles_per_item == s2.cycles_per_item && s1.overflows == s2.overflows &&
              s1.in_overflows == s2.in_overflows && s1.energy_pj == s2.energy_pj && s1.area_ge == s2.area_ge,
              "width %d: figures differ (%g and %g pJ)", width, s1.energy_pj, s2.energy_pj);
    free(o1);
    free(o2);
}

static void memo_same_bytes(void)
{
    size_t n = 3000, kept, hits;
    double *in = malloc(2 * n * sizeof *in);
    for (size_t i = 0; i < n; i++) {
        in[2 * i] = (double)(i % 97) / 200;
        in[2 * i + 1] = 0.5 + (double)(i % 89) / 200;
    }
    tb_items_memo *m = tb_items_memo_new();
    memo_run_same(m, 16, in, n);                /* run, kept */
    memo_run_same(m, 16, in, n);                /* answered */
    tb_items_memo_counts(m, &kept, &hits);
    TST_EQ_INT(kept, 1);
    TST_EQ_INT(hits, 1);
    memo_run_same(m, 12, in, n);                /* another configuration: run */
    in[2 * (n - 1)] = 0.125;                    /* one item changed: run */
    memo_run_same(m, 16, in, n);
    memo_run_same(m, 16, in, n - 1);            /* fewer items: run */
    tb_items_memo_counts(m, &kept, &hits);
    TST_EQ_INT(kept, 4);
    TST_EQ_INT(hits, 1);
    memo_run_same(m, 12, in, n);                /* the changed items at width 12: run */
    memo_run_same(m, 16, in, n - 1);            /* answered */
    tb_items_memo_counts(m, &kept, &hits);
    TST_EQ_INT(kept, 5);
    TST_EQ_INT(hits, 2);
    tb_items_memo_free(m);
    memo_run_same(NULL, 16, in, n);             /* no memo */
    free(in);
}

int main(void)
{
    TST_RUN(div_items);
    TST_RUN(powg_items);
    TST_RUN(groups_any_jobs);
    TST_RUN(memo_same_bytes);
    TST_EXIT();
}
