/* test_sigset.c - only built signals exist: for every unit, schedule and
 * a spread of parameter values, the signals unit_sig_built names are
 * exactly the unit's signals the build puts in its scope (what the VCD
 * dumps), and --fmt accepts exactly those. */
#include "tests/tst.h"
#include "tests/tst_scope.h"
#include "testbench/tb.h"

/* Under ASan (TST_BUILD ending in -asan) the per-signal --fmt check runs
 * for the default parameters only (it is the same code for every
 * configuration); the plain build checks every configuration. */
static int check_cfg(const unit_desc *u, const unit_cfg *cfg, int fmt_checks)
{
    unit_fmts fm;
    char err[800];
    if (tb_formats(u, cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return 1; }
    tb_built bu;
    int bad = 0;
    if (tb_build(u, cfg, &fm, &bu, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); bad = 1; }
    sim_ctx *c = bu.c;
    sim_scope *sc = bu.sc;
    for (int i = 0; !bad && i < u->nsigs; i++) {
        const char *nm = u->sigs[i].name;
        int built = unit_sig_built(u, i, cfg);
        if (built && !in_tree(sc, nm)) { TST_CHECK(0, "%s sched %d terms %d series %d: listed '%s' is not built", u->name, cfg->schedule, cfg->terms, cfg->series, nm); bad = 1; }
        if (!built && at_top(sc, nm)) { TST_CHECK(0, "%s sched %d terms %d series %d: '%s' is built but not listed", u->name, cfg->schedule, cfg->terms, cfg->series, nm); bad = 1; }
        if (!fmt_checks) continue;
        /* --fmt NAME=... is accepted exactly for the built signals. */
        char ov[64];
        const char *ovp = ov;
        snprintf(ov, sizeof ov, "%s=s4.8", nm);
        unit_fmts f2;
        int rc = tb_formats(u, cfg, &ovp, 1, &f2, err, sizeof err);
        if (built != (rc == 0)) { TST_CHECK(0, "%s: --fmt %s: rc %d, built %d (%s)", u->name, ov, rc, built, err); bad = 1; }
    }
    sim_free(c);
    return bad;
}

static void built_signals_are_listed_ones(void)
{
    for (size_t k = 0; k < unit_count(); k++) {
        const unit_desc *u = unit_at(k);
        for (int s = 0; s < u->nsched; s++)
            for (int v = 0; v < 3; v++) {
                unit_cfg cfg;
                unit_cfg_default(u, &cfg);
                cfg.schedule = s;
                /* defaults, then every parameter at its minimum, then at its maximum */
                for (int p = 0; v && p < u->nparams; p++) {
                    const unit_param *pp = &u->params[p];
                    char val[32], e[200];
                    double x = v == 1 ? pp->min : pp->max;
                    if (pp->type == UNIT_P_ENUM) snprintf(val, sizeof val, "%.*s", (int)strcspn(v == 1 ? pp->choices : strrchr(pp->choices, ' ') + 1, " "), v == 1 ? pp->choices : strrchr(pp->choices, ' ') + 1);
                    else if (pp->type == UNIT_P_REAL) snprintf(val, sizeof val, "%g", x);
                    else snprintf(val, sizeof val, "%d", (int)x);
                    if (unit_param_set(u, &cfg, pp->name, val, e, sizeof e)) { TST_CHECK(0, "%s", e); continue; }
                }
                if (check_cfg(u, &cfg, v == 0 || !tst_asan_build())) return;
            }
    }
}

/* div3 with 3 terms: t0..t3, s1..s3 (paper); quarter: t1..t3, s2..s3. */
static void div3_builds_its_terms_only(void)
{
    const unit_desc *u = unit_find("div3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.terms = 3;
    const char *paper[] = { "x", "y", "t0", "t1", "t2", "t3", "s1", "s2", "s3" };
    int n = 0;
    for (int i = 0; i < u->nsigs; i++) n += unit_sig_built(u, i, &cfg);
    TST_EQ_INT(n, 9);
    for (size_t k = 0; k < sizeof paper / sizeof paper[0]; k++)
        TST_CHECK(unit_sig_built(u, unit_sig_index(u, paper[k]), &cfg), "%s", paper[k]);
    cfg.series = 1;
    n = 0;
    for (int i = 0; i < u->nsigs; i++) n += unit_sig_built(u, i, &cfg);
    TST_EQ_INT(n, 7);
    TST_CHECK(!unit_sig_built(u, unit_sig_index(u, "t0"), &cfg), "quarter has no t0");
    TST_CHECK(!unit_sig_built(u, unit_sig_index(u, "s1"), &cfg), "quarter has no s1");
}

int main(void)
{
    TST_RUN(div3_builds_its_terms_only);
    TST_RUN(built_signals_are_listed_ones);
    TST_EXIT();
}
