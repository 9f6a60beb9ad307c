/* tb_sweep_rule.c - the target search's acceptance rules (tb_sweep.h),
 * on a run's result alone: a leaf, which the search (tb_sweep.c) and its
 * start under derived ranges (tb_sweep_ranges.c) both call. */
#include "testbench/study/tb_sweep.h"
#include <math.h>

int tb_target_holds(const tb_result *r, int status, tb_target_kind k, double target, uint64_t max_ovf)
{
    /* a design without a derived bound (a datapath file with logic of its
     * own) is held to the target alone, as run's verdict holds it */
    int bound_ok = r->within_bound || r->bound_check == TB_CHECK_NO_BOUND;
    if (status != TB_OK || !bound_ok || r->overflows > max_ovf) return 0;
    double v = k == TB_TARGET_NMSE ? r->nmse : r->max_abs_err;
    return v <= target;
}

double tb_derived_err(const tb_result *r)
{
    double w = 0;
    for (int o = 0; o < r->n_out; o++) {
        const tb_metrics *m = &r->out[o];
        if (!isfinite(m->bound) || m->bound < 0) return INFINITY;
        double e = m->bound + m->max_input_err + m->max_method_err;
        if (e > w) w = e;
    }
    return w;
}

int tb_target_holds_derived(const tb_result *r, int status, tb_target_kind k, double target)
{
    if (!tb_target_holds(r, status, k, target, 0)) return 0;
    return k != TB_TARGET_MAX_ABS_ERR || tb_derived_err(r) <= target;
}
