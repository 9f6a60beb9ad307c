/* test_widths.c - no silent widening: a unit's minimum width, what
 * tb_formats does below it, and that a unit's own misspelt signal name is
 * an error rather than a default format. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

static int same(sim_fmt a, sim_fmt b) { return a.is_signed == b.is_signed && a.ibits == b.ibits && a.fbits == b.fbits; }

/* horner3/horner2 datapaths are s7.(W-7) (docs/units.md): 7 integer bits,
 * so W = 7 gives s7.0 as W = 6 does, and the first width with a format
 * of its own is 8. */
static void horner_minimum_is_8(void)
{
    const char *names[] = { "horner3", "horner2" };
    for (int k = 0; k < 2; k++) {
        const unit_desc *u = unit_find(names[k]);
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        int lim;
        TST_EQ_INT(unit_min_width(u, &cfg, &lim), 7 + 1);
        TST_CHECK(lim >= 0 && u->sigs[lim].name[0] != 't', "%s: limited by %s", names[k], lim >= 0 ? u->sigs[lim].name : "-");
    }
}

/* For every unit, at its minimum and above, every signal that follows the
 * width has a format of its own at each width (no clamp); one below, some
 * signal repeats its format; tb_formats refuses below and accepts at. */
static void every_unit_minimum_is_honest(void)
{
    for (size_t k = 0; k < unit_count(); k++) {
        const unit_desc *u = unit_at(k);
        for (int s = 0; s < u->nsched; s++) {
            unit_cfg cfg;
            unit_cfg_default(u, &cfg);
            cfg.schedule = s;
            int lim, wmin = unit_min_width(u, &cfg, &lim);
            unit_fmts a, b, f16, f17;
            cfg.width = 16; u->formats(&cfg, &f16);
            cfg.width = 17; u->formats(&cfg, &f17);
            for (int w = wmin; w < 40; w++) {
                cfg.width = w - 1; u->formats(&cfg, &a);
                cfg.width = w; u->formats(&cfg, &b);
                for (int i = 0; i < u->nsigs; i++)
                    if (unit_sig_built(u, i, &cfg) && !same(f16.f[i], f17.f[i]))
                        TST_CHECK(!same(a.f[i], b.f[i]), "%s W=%d: %s as at W-1", u->name, w, u->sigs[i].name);
            }
            char err[400];
            unit_fmts fm;
            cfg.width = wmin;
            TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) == 0, "%s W=%d: %s", u->name, wmin, err);
            if (wmin > 2) {
                cfg.width = wmin - 1;
                TST_CHECK(tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err) < 0 && strstr(err, "needs --width >="),
                          "%s W=%d accepted", u->name, wmin - 1);
                const char *all = "all=s8.8";
                TST_CHECK(tb_formats(u, &cfg, &all, 1, &fm, err, sizeof err) == 0, "%s all=: %s", u->name, err);
            }
        }
    }
}

/* d_approx's k = (2/m^2 - 4)/g needs more integer bits for a small m, so
 * the minimum width follows the parameter: m = 0.05, g = 2 gives k = 398,
 * 9 integer bits (2^8 <= 398 < 2^9), so its uI.(W-I) is clamped below
 * W = 10. */
static void minimum_follows_parameters(void)
{
    const unit_desc *u = unit_find("d_approx");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    char err[200];
    TST_EQ_INT(unit_param_set(u, &cfg, "m", "0.05", err, sizeof err), 0);
    TST_EQ_INT(unit_param_set(u, &cfg, "g", "2", err, sizeof err), 0);
    int lim, w = unit_min_width(u, &cfg, &lim);
    TST_CHECK(w >= 10, "d_approx m=0.05 g=2: minimum %d", w);
    TST_CHECK(lim >= 0, "no limiting signal");
}

/* A name a unit's own code uses that the unit does not have aborts with
 * the name (a child process, so the test goes on). */
static void unknown_own_signal_aborts(void)
{
    fflush(stdout);
    pid_t p = fork();
    if (p == 0) {
        FILE *null = freopen("/dev/null", "w", stderr);
        (void)null;
        unit_sig_must(unit_find("horner3"), "mull");
        _exit(0);
    }
    int st = 0;
    waitpid(p, &st, 0);
    TST_CHECK(WIFSIGNALED(st) && WTERMSIG(st) == SIGABRT, "status %d", st);
    TST_EQ_INT(unit_sig_must(unit_find("horner3"), "mul"), unit_sig_index(unit_find("horner3"), "mul"));
}

int main(void)
{
    TST_RUN(horner_minimum_is_8);
    TST_RUN(every_unit_minimum_is_honest);
    TST_RUN(minimum_follows_parameters);
    TST_RUN(unknown_own_signal_aborts);
    TST_EXIT();
}
