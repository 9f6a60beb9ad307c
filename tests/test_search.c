/* test_search.c - the target search's held-out check and margin, and the
 * sweep's acceptance flags, through the engine (tb_sweep.h): each figure
 * recomputed here by running the same design on the same stimuli. */
#include "tests/tst.h"
#include "testbench/study/tb_sweep.h"
#include "testbench/tb.h"

static int sweep_h3(tb_sweep *s, vec_set *vs, int lo, int hi, const tb_accept *acc)
{
    tb_sweep_spec sp;
    char err[600];
    memset(&sp, 0, sizeof sp);
    sp.u = unit_find("horner3");
    unit_cfg_default(sp.u, &sp.base);
    sp.wlo = lo; sp.whi = hi;
    sp.nsched = sp.nrnd = sp.novf = 1;
    if (acc) sp.accept = *acc;
    if (tb_sweep_init(s, &sp, err, sizeof err)) { printf("  %s\n", err); return -1; }
    if (tb_make_vectors(sp.u, &sp.base, 0, 1, vs, err, sizeof err)) { printf("  %s\n", err); return -1; }
    s->vs[0] = vs;
    TST_CHECK(tb_sweep_fingerprint(s, err, sizeof err) == 0, "%s", err);
    return tb_sweep_run(s, 1, 0, 0, NULL, NULL) ? -1 : 0;
}

/* A margin of b bits divides a max-error target by 2^b, an NMSE target by 4^b. */
static void goal_is_target_less_margin(void)
{
    TST_NEAR(tb_target_goal(TB_TARGET_MAX_ABS_ERR, 1e-3, 0), 1e-3, 0);
    TST_NEAR(tb_target_goal(TB_TARGET_MAX_ABS_ERR, 1e-3, 1), 5e-4, 0);
    TST_NEAR(tb_target_goal(TB_TARGET_MAX_ABS_ERR, 1e-3, 3), 1.25e-4, 0);
    TST_NEAR(tb_target_goal(TB_TARGET_NMSE, 1e-4, 1), 2.5e-5, 0);
}

/* The held-out verdict is the chosen design's own run on the held-out
 * set against the target; the search result itself meets the goal. */
static void heldout_is_a_fresh_run(void)
{
    tb_sweep s;
    vec_set vs, ho;
    char err[600];
    vec_set_init(&vs);
    vec_set_init(&ho);
    if (sweep_h3(&s, &vs, 12, 22, NULL)) { TST_CHECK(0, "sweep failed"); return; }
    const unit_desc *u = s.spec.u;
    TST_EQ_INT(tb_make_vectors(u, &s.spec.base, vs.n_rows, 2, &ho, err, sizeof err), 0);
    for (int margin = 0; margin <= 1; margin++) {
        double target = 1e-2, goal = tb_target_goal(TB_TARGET_MAX_ABS_ERR, target, margin);
        tb_target_res t;
        TST_EQ_INT(tb_sweep_target(&s, 0, TB_TARGET_MAX_ABS_ERR, goal, 1, &t, err, sizeof err), 0);
        TST_CHECK(t.met && t.r.max_abs_err <= goal, "margin %d: %g > goal %g", margin, t.r.max_abs_err, goal);
        TST_EQ_INT(tb_sweep_target_heldout(&s, &ho, TB_TARGET_MAX_ABS_ERR, target, &t, err, sizeof err), 0);
        TST_EQ_INT(t.heldout, 1);
        tb_result r;
        TST_EQ_INT(tb_run(u, &s.cfg[t.uniform].cfg, &t.fmts, &ho, NULL, &r, err, sizeof err), TB_OK);
        TST_NEAR(t.heldout_r.max_abs_err, r.max_abs_err, 0);
        TST_EQ_INT(t.heldout_ok, r.max_abs_err <= target && r.within_bound);
        /* t in [0, 1) at every fraction bit: the chosen t cannot be the
         * pixel grid's three bits and meet 1e-2 on all of it. */
        TST_CHECK(t.fmts.f[unit_sig_index(u, "t")].fbits > 3, "t kept %d fraction bits", t.fmts.f[unit_sig_index(u, "t")].fbits);
        tb_result_free(&r);
    }
    vec_set_free(&ho);
    vec_set_free(&vs);
    tb_sweep_free(&s);
}

/* --max-error on a sweep: each row's meets_target is max |e| <= E. */
static void accept_marks_rows(void)
{
    tb_sweep s;
    vec_set vs;
    tb_accept acc;
    memset(&acc, 0, sizeof acc);
    acc.max_error = 0.05;
    vec_set_init(&vs);
    if (sweep_h3(&s, &vs, 8, 16, &acc)) { TST_CHECK(0, "sweep failed"); return; }
    int meets = 0, misses = 0;
    for (size_t i = 0; i < s.n; i++) {
        const tb_result *r = &s.row[i].r;
        TST_EQ_INT(r->target_set, 1);
        TST_EQ_INT(r->target_met, r->max_abs_err <= 0.05);
        meets += r->target_met;
        misses += !r->target_met;
    }
    TST_CHECK(meets > 0 && misses > 0, "%d meet, %d miss", meets, misses);
    vec_set_free(&vs);
    tb_sweep_free(&s);
}

int main(void)
{
    TST_RUN(goal_is_target_less_margin);
    TST_RUN(heldout_is_a_fresh_run);
    TST_RUN(accept_marks_rows);
    TST_EXIT();
}
