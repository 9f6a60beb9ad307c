/* test_reference.c - the reference kernel (sim_set_reference) is
 * independent of every fast path it checks: over every unit and schedule,
 * a run on it enters no fast path (sim_stats.fast_paths stays 0: every
 * primitive went through sim_elem_eval alone), the same run on the fast
 * kernel does enter them (so the count can fail), and the two agree on
 * every counter, every overflow and every output raw. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include <stdint.h>

static int run(const unit_desc *u, const unit_cfg *cfg, const vec_set *vs, int reference, tb_result *r)
{
    char err[600];
    unit_fmts fm;
    memset(r, 0, sizeof *r);
    if (tb_formats(u, cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return -1; }
    tb_opts o = { .reference = reference };
    int rc = tb_run(u, cfg, &fm, vs, &o, r, err, sizeof err);
    TST_CHECK(rc == TB_OK, "%s %s: %s", u->name, u->sched[cfg->schedule].name, err);
    return rc == TB_OK ? 0 : -1;
}

static void t_reference_enters_no_fast_path(void)
{
    int runs = 0;
    for (size_t i = 0; i < unit_count(); i++) {
        const unit_desc *u = unit_at(i);
        for (int s = 0; s < u->nsched; s++) {
            unit_cfg cfg;
            unit_cfg_default(u, &cfg);
            cfg.schedule = s;
            vec_set vs;
            char err[600];
            if (tb_make_vectors(u, &cfg, 12, 1, &vs, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); continue; }
            tb_result k, r;
            if (run(u, &cfg, &vs, 0, &k) == 0 && run(u, &cfg, &vs, 1, &r) == 0) {
                const char *n = u->name, *sn = u->sched[s].name;
                TST_CHECK(r.stats.fast_paths == 0, "%s %s: the reference entered %llu fast paths", n, sn,
                          (unsigned long long)r.stats.fast_paths);
                TST_CHECK(k.stats.fast_paths > 0, "%s %s: the fast kernel entered none", n, sn);
                TST_CHECK(k.stats.clocks == r.stats.clocks && k.stats.events == r.stats.events &&
                          k.stats.deltas == r.stats.deltas && k.stats.proc_runs == r.stats.proc_runs &&
                          k.stats.time_steps == r.stats.time_steps, "%s %s: counters differ", n, sn);
                TST_CHECK(k.overflows == r.overflows && k.ovf_discarded == r.ovf_discarded,
                          "%s %s: overflows %llu/%llu, reference %llu/%llu", n, sn,
                          (unsigned long long)k.overflows, (unsigned long long)k.ovf_discarded,
                          (unsigned long long)r.overflows, (unsigned long long)r.ovf_discarded);
                size_t nraw = k.vectors * (size_t)k.beats * (size_t)k.n_out;
                TST_CHECK(k.vectors == r.vectors && !memcmp(k.raw, r.raw, nraw * sizeof *k.raw),
                          "%s %s: outputs differ", n, sn);
                runs++;
            }
            tb_result_free(&k);
            tb_result_free(&r);
            vec_set_free(&vs);
        }
    }
    TST_CHECK(runs >= 10, "only %d unit schedules ran", runs);
}

int main(void)
{
    TST_RUN(t_reference_enters_no_fast_path);
    TST_EXIT();
}
