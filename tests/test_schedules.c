/* test_schedules.c - the faster schedules of the Horner units and the
 * interpolators (docs/schedules.md): mac (a multiply-add a clock), pipe (a
 * pixel a clock) and, for interp3/interp2, fwd (forward differencing).
 *
 * Every check runs the real path (descriptor -> formats -> tb_run on the
 * units' default vectors from the reference) and compares the hardware with
 * the unit's ideal function of the inputs as the hardware holds them. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include "units/unit_horner.h"
#include <stdint.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *const UNITS[] = { "horner3", "horner2", "interp3", "interp2" };
#define NUNITS 4

static unit_cfg cfg_of(const unit_desc *u, const char *sched, int width, int L)
{
    unit_cfg c;
    unit_cfg_default(u, &c);
    c.width = width;
    c.L = L;
    c.schedule = unit_sched_find(u, sched);
    return c;
}

/* A run of unit u with cfg on its default vectors (generated for cfg's
 * parameters, seed 1), format overrides ov; per-beat |hw - ideal| in
 * err_beat[beat] (max over items) when given. The result is freed by the
 * caller; TB_OK or not. */
static int run(const unit_desc *u, const unit_cfg *cfg, const char *const *ov, int nov, tb_result *r,
               double *err_beat)
{
    char err[600];
    unit_fmts fm;
    memset(r, 0, sizeof *r);
    if (tb_formats(u, cfg, ov, nov, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return -1; }
    vec_set vs;
    if (tb_make_vectors(u, cfg, 0, 1, &vs, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return -1; }
    int rc = tb_run(u, cfg, &fm, &vs, NULL, r, err, sizeof err);
    TST_CHECK(rc == TB_OK, "%s %s W=%d: %s", u->name, u->sched[cfg->schedule].name, cfg->width, err);
    if (rc == TB_OK && err_beat) {
        int nb = r->beats, nin = r->n_in;
        int in_idx[UNIT_MAX_IO], k = 0;
        for (int i = 0; i < u->nsigs; i++) if (u->sigs[i].role == UNIT_SIG_IN) in_idx[k++] = i;
        for (int b = 0; b < nb; b++) err_beat[b] = 0;
        for (size_t it = 0; it < r->vectors; it++) {
            double q[UNIT_MAX_IO], id[64];
            for (int i = 0; i < nin; i++) {
                sim_fmt f = fm.f[in_idx[i]];
                q[i] = sim_fx_to_real(sim_fx_from_real(vec_row(&vs, it)[i], f, cfg->rnd, cfg->ovf, NULL), f);
            }
            u->ideal(cfg, q, id);
            for (int b = 0; b < nb; b++) {
                double hw = sim_fx_to_real(r->raw[it * (size_t)nb + (size_t)b], r->out[0].fmt);
                err_beat[b] = fmax(err_beat[b], fabs(hw - id[b]));
            }
        }
    }
    vec_set_free(&vs);
    return rc;
}

/* The per-beat bounds of a configuration (every beat the port's bound when
 * the unit has no bound_beats). */
static void beat_bounds(const unit_desc *u, const unit_cfg *cfg, const char *const *ov, int nov, double *b)
{
    unit_fmts fm;
    char err[600];
    tb_formats(u, cfg, ov, nov, &fm, err, sizeof err);
    if (u->bound_beats) { u->bound_beats(cfg, &fm, b); return; }
    double p[UNIT_MAX_IO];
    u->bound(cfg, &fm, p);
    for (int k = 0; k < u->beats(cfg); k++) b[k] = p[0];
}

/* ---- signals follow the schedule ------------------------------------------ */

/* Built elements: every internal signal that belongs to some schedules
 * only is built (as an element of the unit, its horner or its fwd scope)
 * exactly when the schedule has it. */
static void t_signals_follow_schedule(void)
{
    for (int k = 0; k < NUNITS; k++) {
        const unit_desc *u = unit_find(UNITS[k]);
        int interp = !strncmp(u->name, "interp", 6);
        TST_EQ_INT(u->nsched, interp ? 4 : 3);
        for (int s = 0; s < u->nsched; s++) {
            unit_cfg cfg = cfg_of(u, u->sched[s].name, 16, 8);
            unit_fmts fm;
            u->formats(&cfg, &fm);
            sim_ctx *c = sim_new();
            sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
            unit_io io;
            memset(&io, 0, sizeof io);
            char err[300];
            TST_CHECK(u->build(c, sim_scope_new(c, NULL, u->name), clk, &cfg, &fm, &io, err, sizeof err) == 0, "%s", err);
            int checked = 0;
            for (int i = 0; i < u->nsigs; i++) {
                if (!u->sigs[i].scheds || u->sigs[i].role != UNIT_SIG_INTERNAL) continue;
                /* an element of the unit, its horner scope or its fwd scope */
                static const char *const where[] = { "", "horner.", "fwd." };
                int want = unit_sig_built(u, i, &cfg), got = 0;
                for (int w = 0; w < 3; w++) {
                    char path[64];
                    snprintf(path, sizeof path, "%s.%s%s", u->name, where[w], u->sigs[i].name);
                    got |= sim_find(c, NULL, path) != NULL;
                }
                TST_CHECK(want == got, "%s %s: %s %s", u->name, u->sched[s].name, u->sigs[i].name, want ? "missing" : "built");
                checked++;
            }
            TST_CHECK(checked >= 6, "%s: %d masked signals", u->name, checked);
            sim_free(c);
        }
    }
}

/* ---- bounds and exactness ------------------------------------------------- */

/* Every schedule meets its bound at widths 12 and 20, per beat. */
static void t_within_bound(void)
{
    static const int widths[] = { 12, 20 };
    for (int k = 0; k < NUNITS; k++) {
        const unit_desc *u = unit_find(UNITS[k]);
        for (int s = 0; s < u->nsched; s++)
            for (int w = 0; w < 2; w++) {
                unit_cfg cfg = cfg_of(u, u->sched[s].name, widths[w], 8);
                tb_result r;
                double eb[64], bb[64];
                if (run(u, &cfg, NULL, 0, &r, eb) == TB_OK) {
                    TST_CHECK(r.within_bound, "%s %s W=%d: bound exceeded at item %zu", u->name, u->sched[s].name,
                              widths[w], r.first_violation);
                    beat_bounds(u, &cfg, NULL, 0, bb);
                    for (int b = 0; b < r.beats; b++)
                        TST_CHECK(eb[b] <= bb[b] + 1e-12, "%s %s W=%d beat %d: %g > %g", u->name, u->sched[s].name,
                                  widths[w], b, eb[b], bb[b]);
                }
                tb_result_free(&r);
            }
    }
}

/* With every signal s12.50 every schedule computes the exact polynomial to
 * 1e-9 (fwd's start values still drop bits below 2^-50: a few 1e-14). */
static void t_exact_when_wide(void)
{
    const char *ov[1] = { "all=s12.50" };
    for (int k = 0; k < NUNITS; k++) {
        const unit_desc *u = unit_find(UNITS[k]);
        for (int s = 0; s < u->nsched; s++) {
            unit_cfg cfg = cfg_of(u, u->sched[s].name, 16, 8);
            tb_result r;
            if (run(u, &cfg, ov, 1, &r, NULL) == TB_OK) {
                TST_CHECK(r.within_bound, "%s %s at s12.50", u->name, u->sched[s].name);
                TST_CHECK(r.out[0].max_err_ideal <= 1e-9, "%s %s: |hw - ideal| = %g at s12.50", u->name,
                          u->sched[s].name, r.out[0].max_err_ideal);
            }
            tb_result_free(&r);
        }
    }
}

/* The bound comes from the formats given: coarsen each internal signal of
 * each new schedule by 5 fraction bits; the unit still meets its (larger)
 * bound. */
static void t_bound_follows_overrides(void)
{
    for (int k = 0; k < NUNITS; k++) {
        const unit_desc *u = unit_find(UNITS[k]);
        for (int s = 1; s < u->nsched; s++) {
            unit_cfg cfg = cfg_of(u, u->sched[s].name, 20, 8);
            unit_fmts def;
            u->formats(&cfg, &def);
            double b0[UNIT_MAX_IO], b1[UNIT_MAX_IO];
            u->bound(&cfg, &def, b0);
            for (int i = 0; i < u->nsigs; i++) {
                if (u->sigs[i].role != UNIT_SIG_INTERNAL || !unit_sig_built(u, i, &cfg) || !strcmp(u->sigs[i].name, "t"))
                    continue;
                sim_fmt f = def.f[i];
                char ov[64], fs[SIM_FMT_STRLEN];
                snprintf(ov, sizeof ov, "%s=%s", u->sigs[i].name, sim_fmt_str(unit_fmt(f.is_signed, f.ibits, f.fbits - 5), fs));
                const char *ovs[1] = { ov };
                tb_result r;
                if (run(u, &cfg, ovs, 1, &r, NULL) == TB_OK)
                    TST_CHECK(r.within_bound, "%s %s --fmt %s: bound exceeded", u->name, u->sched[s].name, ov);
                tb_result_free(&r);
                unit_fmts fm;
                char err[600];
                tb_formats(u, &cfg, ovs, 1, &fm, err, sizeof err);
                u->bound(&cfg, &fm, b1);
                TST_CHECK(b1[0] >= b0[0], "%s %s --fmt %s: bound fell from %g to %g", u->name, u->sched[s].name, ov, b0[0], b1[0]);
            }
        }
    }
}

/* The pipe's copies of t narrower than t: the product's error then grows
 * with |x| (the bound scales t's error by the multiplicand's range).
 * Vectors with t of 15 fraction bits, not k/8. */
static void t_pipe_narrow_t_copies(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg = cfg_of(u, "pipe", 20, 8);
    vec_set vs;
    vec_set_init(&vs);
    tb_expected_header(u, &cfg, &vs);
    uint64_t x = 12345;
    for (int i = 0; i < 400; i++) {
        double row[6];
        for (int j = 0; j < 5; j++) {
            x = x * 6364136223846793005ull + 1442695040888963407ull;
            double r = (double)(x >> 11) / 9007199254740992.0;
            row[j] = j < 4 ? 30 * r - 15 : r;   /* |partial sums| < 60: no overflow */
        }
        row[5] = ((row[0] * row[4] + row[1]) * row[4] + row[2]) * row[4] + row[3];
        vec_set_push(&vs, row);
    }
    const char *ov[2] = { "t1=u1.4", "t2=u1.4" };
    unit_fmts fm;
    char err[600];
    tb_result r;
    TST_CHECK(tb_formats(u, &cfg, ov, 2, &fm, err, sizeof err) == 0, "%s", err);
    TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, NULL, &r, err, sizeof err), TB_OK);
    TST_CHECK(r.within_bound, "narrow t copies: %g > bound %g", r.out[0].max_err_ideal, r.out[0].bound);
    TST_CHECK(r.out[0].max_err_ideal > 0.5, "narrow t copies: error %g, expected a large one", r.out[0].max_err_ideal);
    tb_result_free(&r);
    vec_set_free(&vs);
}

/* horner3, paper schedule, mul at s0.16 ([-0.5, 0.5)), t = 0.75, B = C = 0.
 * In step 0 of each pixel the multiplier computes RG t from the last
 * pixel's I while MX2 takes B: with D = 1.5 (A = 0) that product, 1.125,
 * overflows on every pixel after the first, and nothing takes it (every
 * other product is 0; y is exact). With A = 1.5 (D = 0) step 1's A t =
 * 1.125 overflows and MX2 takes it: used, and y is wrong. */
static void t_overflow_used_horner(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg = cfg_of(u, "paper", 16, 8);
    const char *ov[1] = { "mul=s0.16" };
    unit_fmts fm;
    char err[600];
    TST_CHECK(tb_formats(u, &cfg, ov, 1, &fm, err, sizeof err) == 0, "%s", err);
    for (int used = 0; used < 2; used++) {
        vec_set vs;
        vec_set_init(&vs);
        tb_expected_header(u, &cfg, &vs);
        const double a = used ? 1.5 : 0, d = used ? 0 : 1.5, t = 0.75;
        double row[6] = { a, 0, 0, d, t, a * t * t * t + d };
        const int n = 4;
        for (int i = 0; i < n; i++) vec_set_push(&vs, row);
        tb_result r;
        TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, NULL, &r, err, sizeof err), TB_OK);
        uint64_t sig_used = 0, sig_disc = 0;
        for (int i = 0; i < r.nsigs; i++)
            if (!strcmp(r.sigs[i].name, "mul")) { sig_used = r.sigs[i].overflows; sig_disc = r.sigs[i].ovf_discarded; }
            else TST_CHECK(r.sigs[i].overflows + r.sigs[i].ovf_discarded == 0, "%s overflowed", r.sigs[i].name);
        if (used) {
            TST_CHECK(r.overflows == (uint64_t)n && sig_used == (uint64_t)n && r.ovf_discarded == 0,
                      "A t: used %llu discarded %llu", (unsigned long long)r.overflows,
                      (unsigned long long)r.ovf_discarded);
            TST_CHECK(r.max_abs_err > 0.1, "a used overflow spoils y: error %g", r.max_abs_err);
        } else {
            TST_CHECK(r.overflows == 0 && sig_used == 0, "RG t in step 0: %llu counted as used",
                      (unsigned long long)r.overflows);
            TST_CHECK(sig_disc >= (uint64_t)n - 1 && sig_disc <= (uint64_t)n && r.ovf_discarded == sig_disc,
                      "discarded %llu (mul %llu), expected %d or %d", (unsigned long long)r.ovf_discarded,
                      (unsigned long long)sig_disc, n - 1, n);
            TST_CHECK(r.max_abs_err == 0, "y is exact: error %g", r.max_abs_err);
        }
        tb_result_free(&r);
        vec_set_free(&vs);
    }
}

/* ---- clocks ----------------------------------------------------------------- */

/* cycles per item and latency exactly, and every beat on its cycle: no
 * gaps between items. */
static void check_clocks(const char *unit, const char *sched, int L, int per_item, int latency)
{
    const unit_desc *u = unit_find(unit);
    unit_cfg cfg = cfg_of(u, sched, 16, L);
    tb_result r;
    if (run(u, &cfg, NULL, 0, &r, NULL) == TB_OK) {
        TST_NEAR(r.cycles_per_item, per_item, 0);
        TST_EQ_INT(r.latency, latency);
        int nb = r.beats, per_beat = per_item / nb, bad = 0;
        for (size_t i = 0; i < r.vectors * (size_t)nb; i++)
            bad += r.beat_cycle[i] != (uint64_t)latency + i * (uint64_t)per_beat;
        TST_CHECK(!bad, "%s %s L=%d: %d beats off their cycle", unit, sched, L, bad);
    }
    tb_result_free(&r);
}

static void t_clocks(void)
{
    /* horner: 6/3/1 and 4/2/1 clocks per pixel; latency = the clocks of
     * one pixel (paper, mac) or the stages (pipe) */
    check_clocks("horner3", "paper", 8, 6, 6);
    check_clocks("horner3", "mac", 8, 3, 3);
    check_clocks("horner3", "pipe", 8, 1, 3);
    check_clocks("horner2", "paper", 8, 4, 4);
    check_clocks("horner2", "mac", 8, 2, 2);
    check_clocks("horner2", "pipe", 8, 1, 2);
    TST_EQ_INT(horner_steps(3, HORNER_MAC), 3);
    TST_EQ_INT(horner_latency(3, HORNER_PIPE), 3);
    TST_EQ_INT(horner_steps(2, HORNER_PIPE), 1);
    /* interp: steps * L per item with no gap (the next item is accepted in
     * the last step of the last pixel); the first pixel 1 + latency of the
     * Horner after the start (1: the accept); fwd 1 */
    for (int L = 4; L <= 16; L *= 4) {
        check_clocks("interp3", "paper", L, 6 * L, 7);
        check_clocks("interp3", "mac", L, 3 * L, 4);
        check_clocks("interp3", "pipe", L, L, 4);
        check_clocks("interp3", "fwd", L, L, 1);
        check_clocks("interp2", "paper", L, 4 * L, 5);
        check_clocks("interp2", "mac", L, 2 * L, 3);
        check_clocks("interp2", "pipe", L, L, 3);
        check_clocks("interp2", "fwd", L, L, 1);
    }
}

/* ---- the same arithmetic gives the same bits ------------------------------ */

static int same_raw(const tb_result *a, const tb_result *b)
{
    size_t n = a->vectors * (size_t)a->beats * (size_t)a->n_out;
    return a->vectors == b->vectors && a->beats == b->beats && !memcmp(a->raw, b->raw, n * sizeof *a->raw);
}

/* paper, mac and pipe compute the same multiply-adds; paper only passes
 * the product through MX2, Sm, RG and BK once more. With the default rule
 * (one format for all) those transfers drop nothing, so the three agree
 * bit for bit at every width. */
static void t_same_bits_default(void)
{
    static const int widths[] = { 8, 12, 16, 24 };
    for (int k = 0; k < NUNITS; k++) {
        const unit_desc *u = unit_find(UNITS[k]);
        for (int w = 0; w < 4; w++) {
            tb_result r[3];
            for (int s = 0; s < 3; s++) {
                unit_cfg cfg = cfg_of(u, u->sched[s].name, widths[w], 8);
                run(u, &cfg, NULL, 0, &r[s], NULL);
            }
            TST_CHECK(r[0].raw && same_raw(&r[0], &r[1]), "%s W=%d: mac differs from paper", u->name, widths[w]);
            TST_CHECK(r[0].raw && same_raw(&r[0], &r[2]), "%s W=%d: pipe differs from paper", u->name, widths[w]);
            for (int s = 0; s < 3; s++) tb_result_free(&r[s]);
        }
    }
}

/* Where they differ, and why: a BK narrower than RG rounds RG's partial
 * sum once more in paper (mac has no BK); a RG narrower than the
 * multiplier rounds paper's product (A t + B) t, which mac never
 * registers. pipe equals mac whenever its stages have mac's formats. */
static void t_where_they_differ(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg p = cfg_of(u, "paper", 16, 8), m = cfg_of(u, "mac", 16, 8), q = cfg_of(u, "pipe", 16, 8);
    const char *bk[1] = { "bk=s7.4" }, *rg[2] = { "rg=s7.6", "sm=s7.6" };
    tb_result a, b;
    run(u, &p, bk, 1, &a, NULL);
    run(u, &m, NULL, 0, &b, NULL);
    TST_CHECK(a.raw && b.raw && !same_raw(&a, &b), "narrow BK: paper should differ from mac");
    TST_CHECK(a.within_bound && b.within_bound, "narrow BK: bounds");
    tb_result_free(&a);
    tb_result_free(&b);
    run(u, &p, rg, 2, &a, NULL);
    run(u, &m, rg, 2, &b, NULL);
    TST_CHECK(a.raw && b.raw && !same_raw(&a, &b), "narrow RG: paper should differ from mac");
    TST_CHECK(a.within_bound && b.within_bound, "narrow RG: bounds");
    tb_result_free(&a);
    tb_result_free(&b);
    /* narrower multipliers, the same in both: the same bits */
    const char *mm[1] = { "mul=s7.5" }, *mp[3] = { "mul1=s7.5", "mul2=s7.5", "mul3=s7.5" };
    run(u, &m, mm, 1, &a, NULL);
    run(u, &q, mp, 3, &b, NULL);
    TST_CHECK(a.raw && b.raw && same_raw(&a, &b), "narrow multipliers: pipe should equal mac");
    tb_result_free(&a);
    tb_result_free(&b);
    /* fwd is other arithmetic: it meets its own bound, not Horner's bits */
    const unit_desc *i3 = unit_find("interp3");
    unit_cfg h = cfg_of(i3, "paper", 16, 8), f = cfg_of(i3, "fwd", 16, 8);
    run(i3, &h, NULL, 0, &a, NULL);
    run(i3, &f, NULL, 0, &b, NULL);
    TST_CHECK(a.raw && b.raw && !same_raw(&a, &b), "fwd gave Horner's bits at W=16");
    tb_result_free(&a);
    tb_result_free(&b);
}

/* ---- forward differencing accumulates --------------------------------------- */

/* At a narrow width the measured error per pixel k stays under the per-k
 * bound, the bound is a cubic (quadratic for interp2) in k with a positive
 * constant top difference, as derived, and the measured error itself grows:
 * the last pixels are off by more than the bound allows pixel 0. */
static void check_fwd_growth(const char *unit, int deg, int width, int L)
{
    const unit_desc *u = unit_find(unit);
    unit_cfg cfg = cfg_of(u, "fwd", width, L);
    tb_result r;
    double eb[64], bb[64];
    if (run(u, &cfg, NULL, 0, &r, eb) != TB_OK) { tb_result_free(&r); return; }
    beat_bounds(u, &cfg, NULL, 0, bb);
    for (int k = 0; k < L; k++) TST_CHECK(eb[k] <= bb[k] + 1e-12, "%s L=%d W=%d pixel %d: %g > bound %g", unit, L, width, k, eb[k], bb[k]);
    for (int k = 1; k < L; k++) TST_CHECK(bb[k] > bb[k - 1], "%s: bound does not grow at pixel %d", unit, k);
    /* the deg-th differences of the bound over k are one positive constant */
    double d[64];
    for (int k = 0; k < L; k++) d[k] = bb[k];
    for (int o = 0; o < deg; o++)
        for (int k = 0; k + o + 1 < L; k++) d[k] = d[k + 1] - d[k];
    for (int k = 0; k + deg < L; k++) TST_NEAR(d[k], d[0], 1e-9 * bb[L - 1]);
    TST_CHECK(d[0] > 0, "%s: top difference of the bound %g", unit, d[0]);
    double late = 0;
    for (int k = L / 2; k < L; k++) late = fmax(late, eb[k]);
    TST_CHECK(late > bb[0], "%s L=%d W=%d: no accumulation measured (late pixels %g, pixel-0 bound %g)", unit, L, width,
              late, bb[0]);
    TST_CHECK(r.within_bound, "%s fwd", unit);
    tb_result_free(&r);
}

static void t_fwd_accumulates(void)
{
    check_fwd_growth("interp3", 3, 12, 32);
    check_fwd_growth("interp3", 3, 12, 16);
    check_fwd_growth("interp2", 2, 12, 32);
}

/* Where fwd breaks: at W = 12 and L = 32 its error is many times the
 * Horner's (the start values' quantization grows with k^3), while at
 * W = 24 and L = 8 the two are within a factor 2. */
static void t_fwd_breaks_where_horner_holds(void)
{
    const unit_desc *u = unit_find("interp3");
    double e[2][2];
    static const int W[2] = { 12, 24 }, L[2] = { 32, 8 };
    for (int c = 0; c < 2; c++)
        for (int s = 0; s < 2; s++) {
            unit_cfg cfg = cfg_of(u, s ? "fwd" : "paper", W[c], L[c]);
            tb_result r;
            e[c][s] = run(u, &cfg, NULL, 0, &r, NULL) == TB_OK ? r.out[0].max_err_ideal : NAN;
            tb_result_free(&r);
        }
    TST_CHECK(e[0][1] > 5 * e[0][0], "W=12 L=32: fwd %g vs paper %g", e[0][1], e[0][0]);
    TST_CHECK(e[0][1] > 1.0, "W=12 L=32: fwd %g is not useless", e[0][1]);
    TST_CHECK(e[1][1] < 2 * e[1][0], "W=24 L=8: fwd %g vs paper %g", e[1][1], e[1][0]);
}

/* ---- the command line ----------------------------------------------------- */

static int sh(const char *cmd)
{
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void t_fmt_of_other_schedule(void)
{
    /* the library */
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg = cfg_of(u, "paper", 16, 8);
    unit_fmts fm;
    char err[600] = "";
    const char *ov[1] = { "mul1=s4.12" };
    TST_CHECK(tb_formats(u, &cfg, ov, 1, &fm, err, sizeof err) < 0 && strstr(err, "mul1") && strstr(err, "pipe")
              && !strchr(err, '\n'), "paper --fmt mul1: '%s'", err);
    cfg.schedule = unit_sched_find(u, "pipe");
    TST_CHECK(tb_formats(u, &cfg, ov, 1, &fm, err, sizeof err) == 0, "pipe --fmt mul1: %s", err);
    /* the command line: exit 2, one line naming the signal */
    const char *S = tst_shadesim();
    if (access(S, X_OK)) TST_SKIP("%s not built", S);
    char dir[] = "/tmp/tschedXXXXXX", cmd[1200];
    if (!mkdtemp(dir)) TST_SKIP("mkdtemp failed");
    static const char *const bad[] = { "horner3 --fmt mul1=s4.12", "horner3 --schedule mac --fmt bk=s7.9",
                                       "horner2 --schedule pipe --fmt rg=s7.9", "interp3 --schedule fwd --fmt rg=s7.9",
                                       "interp2 --schedule mac --fmt fy=s4.12" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(cmd, sizeof cmd, "%s run %s > %s/out 2> %s/err", S, bad[i], dir, dir);
        TST_EQ_INT(sh(cmd), 2);
        snprintf(cmd, sizeof cmd, "test $(wc -l < %s/err) -eq 1 && grep -q 'has no signal' %s/err && test ! -s %s/out", dir, dir, dir);
        TST_CHECK(sh(cmd) == 0, "run %s: not one line on stderr", bad[i]);
    }
    /* JSON formats and list show the schedule's signals only */
    snprintf(cmd, sizeof cmd, "%s run horner3 --schedule pipe --fmt mul1=s7.12 --json > %s/p.json", S, dir);
    TST_EQ_INT(sh(cmd), 0);
    snprintf(cmd, sizeof cmd, "grep -q '\"mul1\": \"s7.12\"' %s/p.json && ! grep -q '\"bk\"' %s/p.json", dir, dir);
    TST_CHECK(sh(cmd) == 0, "pipe JSON formats");
    snprintf(cmd, sizeof cmd, "%s run interp3 --json > %s/q.json && ! grep -q '\"fd1\"' %s/q.json && grep -q '\"bk\"' %s/q.json",
             S, dir, dir, dir);
    TST_CHECK(sh(cmd) == 0, "paper JSON formats");
    snprintf(cmd, sizeof cmd, "%s list interp3 --schedule fwd > %s/l && grep -q ' fd3 ' %s/l && ! grep -q ' mx1 ' %s/l",
             S, dir, dir, dir);
    TST_CHECK(sh(cmd) == 0, "list --schedule fwd");
    snprintf(cmd, sizeof cmd, "%s list horner3 > %s/l && grep -q ' bk ' %s/l && ! grep -q ' mul1 ' %s/l", S, dir, dir, dir);
    TST_CHECK(sh(cmd) == 0, "list (paper)");
    snprintf(cmd, sizeof cmd, "%s list horner3 --schedule nosuch 2> /dev/null", S);
    TST_EQ_INT(sh(cmd), 2);
    /* the VCD holds the schedule's elements */
    snprintf(cmd, sizeof cmd, "%s run horner3 --schedule pipe --vcd %s/p.vcd > /dev/null && grep -q ' rg3 ' %s/p.vcd"
             " && ! grep -q ' bk ' %s/p.vcd", S, dir, dir, dir);
    TST_CHECK(sh(cmd) == 0, "pipe VCD");
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    sh(cmd);
}

int main(void)
{
    TST_RUN(t_signals_follow_schedule);
    TST_RUN(t_within_bound);
    TST_RUN(t_exact_when_wide);
    TST_RUN(t_bound_follows_overrides);
    TST_RUN(t_pipe_narrow_t_copies);
    TST_RUN(t_clocks);
    TST_RUN(t_same_bits_default);
    TST_RUN(t_where_they_differ);
    TST_RUN(t_fwd_accumulates);
    TST_RUN(t_fwd_breaks_where_horner_holds);
    TST_RUN(t_fmt_of_other_schedule);
    TST_RUN(t_overflow_used_horner);
    TST_EXIT();
}
