/* test_span.c - the span units (span1, span2, span3, span23) and their
 * stream driver tb_span_run: intervals of every length, divisors that are
 * not powers of two, the adaptive degree's clocks, the error bound.
 *
 * References are computed here, independently of the units and of
 * vectors/: Lagrange interpolation and Vandermonde solves (tst_ref.h),
 * the /3 network's factor in closed form, intensity profiles given as
 * polynomials along the span, clock counts from the schedules' steps. */
#include "tests/tst.h"
#include "tests/tst_ref.h"
#include "testbench/tb.h"
#include "testbench/study/tb_span.h"
#include "sim/sim_area.h"
#include <stdint.h>
#include <unistd.h>

static const double T_N1[4] = { 0, 1, 0.5, 0.25 }, T_N2[4] = { 0, 1, 0.5, 0.75 }, T_Q[3] = { 0, 1, 0.5 },
                    T_LIN[2] = { 0, 1 };

/* A unit under test: name, node set (span3/span23), node count. */
typedef struct ut { const char *name; int n2; int nin; } ut;
static const ut UNITS[] = {
    { "span1", 0, 2 }, { "span2", 0, 3 }, { "span3", 0, 4 }, { "span3", 1, 4 }, { "span23", 0, 4 }, { "span23", 1, 4 },
};
#define NUNITS (sizeof UNITS / sizeof UNITS[0])
static const char *const SCHED[] = { "paper", "mac", "pipe" };

static uint64_t rng = 0x1234567;
static double urand(void)       /* an LCG, independent of vec_rng */
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng >> 11) * 0x1p-53;
}

/* The /3 network's factor in closed form: the paper series 1/2 - sum of
 * 2^-(2i+1), i = 1..n, is 1/3 + 4^-n / 6; the quarter series (1 - 4^-n)/3. */
static double factor(int terms, int quarter)
{
    double q = ldexp(1.0, -2 * terms);
    return quarter ? (1 - q) / 3 : 1.0 / 3 + q / 6;
}

/* Nodes of an item of unit t with degree deg. */
static const double *nodes_of(const ut *t, int deg, int *k)
{
    if (!strcmp(t->name, "span1")) { *k = 2; return T_LIN; }
    if (deg == 2 || !strcmp(t->name, "span2")) { *k = 3; return T_Q; }
    *k = 4;
    return t->n2 ? T_N2 : T_N1;
}

/* The ideal polynomial's coefficients (highest first) through nodes I with
 * the network's factor f in place of 1/3: the Vandermonde solve plus what
 * f - 1/3 adds where the cubic's formulas divide by 3 (docs/units.md). */
static void ideal_coef(const ut *t, int deg, const double *I, double f, double *c, int *k)
{
    const double *tn = nodes_of(t, deg, k);
    tst_vander(tn, I, *k, c);
    if (*k == 4) {
        double d = f - 1.0 / 3;
        if (!t->n2) { c[0] += 8 * d * (I[1] + 8 * I[3]); c[2] += d * (I[1] + 32 * I[3]); }
        else { c[0] -= 8 * d * (8 * I[3] + I[0]); c[2] -= d * (13 * I[0] + 32 * I[3]); }
    }
}
static double poly(const double *c, int k, double x)
{
    double s = 0;
    for (int i = 0; i < k; i++) s += c[i] * pow(x, k - 1 - i);
    return s;
}

/* Configuration and formats of unit t. */
static const unit_desc *setup(const ut *t, int sched, int width, int L, int terms, const char *const *ov, int nov,
                              unit_cfg *cfg, unit_fmts *f)
{
    const unit_desc *u = unit_find(t->name);
    char err[600];
    if (!u) { TST_CHECK(0, "no unit %s", t->name); return NULL; }
    unit_cfg_default(u, cfg);
    cfg->width = width;
    cfg->L = L;
    cfg->terms = terms;
    cfg->nodes = t->n2;
    cfg->schedule = unit_sched_find(u, SCHED[sched]);
    TST_CHECK(cfg->schedule == sched, "%s schedule %s", t->name, SCHED[sched]);
    if (tb_formats(u, cfg, ov, nov, f, err, sizeof err)) { TST_CHECK(0, "%s: %s", t->name, err); return NULL; }
    return u;
}

static int has_deg(const ut *t) { return !strcmp(t->name, "span23"); }

/* Held (quantized) value of a node as the testbench gives it. */
static double held(double x, const unit_desc *u, const unit_fmts *f, const unit_cfg *cfg, int i)
{
    char nm[4] = { 'i', (char)('1' + i), 0 };
    sim_fmt fi = f->f[unit_sig_index(u, nm)];
    return sim_fx_to_real(sim_fx_from_real(x, fi, cfg->rnd, cfg->ovf, NULL), fi);
}

/* ---- every length, every divisor, wide formats: the float interpolation -- */

/* At s8.40 everywhere (the ROM u1.50, so that t = k * rcp keeps 40
 * bits) and 20 terms of /3, every pixel is the Lagrange interpolant of
 * the held nodes at k/dv to 1e-9, for intervals of every length 1..L with
 * dv = L and dv = n - 1. */
static void t_wide_every_length(void)
{
    static const int Ls[] = { 2, 3, 5, 8, 13, 32 };
    static const char *const ov[] = { "all=s8.40", "rcp=u1.50" };
    for (size_t ui = 0; ui < NUNITS; ui++)
        for (int s = 0; s < 3; s++)
            for (size_t li = 0; li < sizeof Ls / sizeof Ls[0]; li++) {
                const ut *t = &UNITS[ui];
                int L = Ls[li];
                unit_cfg cfg;
                unit_fmts f;
                const unit_desc *u = setup(t, s, 16, L, 20, ov, 2, &cfg, &f);
                if (!u) return;
                tb_span_item it[2 * 64 * 2];
                size_t ni = 0, npix = 0;
                for (int rep = 0; rep < 2; rep++)
                    for (int n = 1; n <= L; n++)
                        for (int d = 0; d < 2; d++) {
                            tb_span_item *m = &it[ni++];
                            memset(m, 0, sizeof *m);
                            m->n = n;
                            m->dv = d ? (n > 1 ? n - 1 : 1) : L;
                            m->deg = 2 + ((n + d + rep) & 1);
                            for (int k = 0; k < 4; k++) m->node[k] = floor(urand() * 65536) / 65536;
                            npix += (size_t)n;
                        }
                double pix[2 * 64 * 65];
                tb_span_stats st;
                char err[300];
                int rc = tb_span_run(u, &cfg, &f, it, ni, pix, &st, NULL, err, sizeof err);
                TST_CHECK(rc == TB_OK, "%s %s L=%d: %s", t->name, SCHED[s], L, err);
                if (rc != TB_OK) continue;
                TST_EQ_INT(st.pixels, npix);
                TST_EQ_INT(st.overflows, 0);
                double worst = 0;
                size_t p = 0;
                for (size_t i = 0; i < ni; i++) {
                    int k;
                    const double *tn = nodes_of(t, has_deg(t) ? it[i].deg : 3, &k);
                    for (int x = 0; x < it[i].n; x++, p++)
                        worst = fmax(worst, fabs(pix[p] - tst_lagrange(tn, it[i].node, k, (double)x / it[i].dv)));
                }
                TST_CHECK(worst <= 1e-9, "%s%s %s L=%d: max |y - Lagrange| = %g", t->name, t->n2 ? " n2" : "",
                          SCHED[s], L, worst);
            }
}

/* ---- profiles reproduced exactly ----------------------------------------- */

/* A span of `len` pixels cut as a scene cuts it (intervals of L, the last
 * with dv = n - 1), nodes from the profile I(x) = c . x^j along the span. */
static size_t cut_span(int len, int L, int deg, const double *tn, int k, const double *c, int nc,
                       tb_span_item *it)
{
    size_t ni = 0;
    for (int s = 0; s < len; s += L) {
        tb_span_item *m = &it[ni++];
        memset(m, 0, sizeof *m);
        m->n = len - s < L ? len - s : L;
        m->dv = s + L >= len ? (m->n > 1 ? m->n - 1 : 1) : L;
        m->deg = deg;
        for (int i = 0; i < k; i++) m->node[i] = poly(c, nc, s + m->dv * tn[i]);
    }
    return ni;
}

/* span2 reproduces a quadratic profile bit for bit when the nodes and t
 * are exact: a dyadic profile along spans cut as a scene cuts them, L = 8
 * and 16, the last intervals' divisors n - 1 = 4 and 8 powers of two, wide
 * formats. span3's /3 network (20 terms) is not exactly 1/3, so a cubic is
 * bit-exact where the network's inputs vanish: per interval p(t) = (t - 1)
 * (t - 1/4)(a t + b) for n1 (I(1) = I(1/4) = 0), t (t - 3/4)(a t + b) for
 * n2 (I(0) = I(3/4) = 0); and a cubic profile along whole spans is met to
 * the network's deviation (1e-10). */
static void t_profiles_exact(void)
{
    static const char *const ov[] = { "all=s8.40", "rcp=u1.50" };
    static const int Ls[] = { 8, 16 };
    for (int li = 0; li < 2; li++)
        for (int s = 0; s < 3; s++) {
            int L = Ls[li];
            /* span2: I(x) = 1/4 + x/64 - 3 x^2 / 4096 (dyadic), spans of 2L + 5 and 3L + 9 pixels */
            const ut *t2 = &UNITS[1];
            unit_cfg cfg;
            unit_fmts f;
            const unit_desc *u = setup(t2, s, 16, L, 20, ov, 2, &cfg, &f);
            if (!u) return;
            double cq[3] = { -3.0 / 4096, 1.0 / 64, 0.25 };
            tb_span_item it[32];
            size_t ni = cut_span(2 * L + 5, L, 2, T_Q, 3, cq, 3, it);
            ni += cut_span(3 * L + 9, L, 2, T_Q, 3, cq, 3, it + ni);
            double pix[512];
            tb_span_stats st;
            char err[300];
            if (tb_span_run(u, &cfg, &f, it, ni, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
            size_t p = 0;
            int bad = 0;
            for (int sp = 0; sp < 2; sp++) {
                int len = sp ? 3 * L + 9 : 2 * L + 5;
                for (int x = 0; x < len; x++, p++) bad += pix[p] != poly(cq, 3, x);
            }
            TST_CHECK(bad == 0, "span2 %s L=%d: %d pixels off the quadratic profile", SCHED[s], L, bad);

            for (int n2 = 0; n2 < 2; n2++) {
                const ut *t3 = &UNITS[2 + n2];
                u = setup(t3, s, 16, L, 20, ov, 2, &cfg, &f);
                if (!u) return;
                /* per interval: p(t) = (t - r1)(t - r2)(a t + b) with the /3 inputs' nodes as roots */
                double r1 = n2 ? 0 : 1, r2 = n2 ? 0.75 : 0.25;
                ni = 0;
                for (int q = 0; q < 8; q++) {
                    tb_span_item *m = &it[ni++];
                    memset(m, 0, sizeof *m);
                    m->n = q < 4 ? L : L / 2 + 1;
                    m->dv = q < 4 ? L : L / 2;
                    double a = (double)(q - 3) / 8, b = (double)(q + 1) / 16;
                    for (int i = 0; i < 4; i++) {
                        double x = (n2 ? T_N2 : T_N1)[i];
                        m->node[i] = (x - r1) * (x - r2) * (a * x + b);
                    }
                }
                if (tb_span_run(u, &cfg, &f, it, ni, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
                p = 0;
                bad = 0;
                for (size_t i = 0; i < ni; i++) {
                    double a = (double)((int)i - 3) / 8, b = (double)(i + 1) / 16;
                    for (int k = 0; k < it[i].n; k++, p++) {
                        double x = (double)k / it[i].dv;
                        bad += pix[p] != (x - r1) * (x - r2) * (a * x + b);
                    }
                }
                TST_CHECK(bad == 0, "span3 %s %s L=%d: %d pixels off the cubic", n2 ? "n2" : "n1", SCHED[s], L, bad);
                /* along spans: I(x) = 1/8 + x/32 + x^2/1024 - x^3/65536, to the network's deviation */
                double cc[4] = { -1.0 / 65536, 1.0 / 1024, 1.0 / 32, 0.125 };
                ni = cut_span(2 * L + 5, L, 3, n2 ? T_N2 : T_N1, 4, cc, 4, it);
                if (tb_span_run(u, &cfg, &f, it, ni, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
                double worst = 0;
                for (int x = 0; x < 2 * L + 5; x++) worst = fmax(worst, fabs(pix[x] - poly(cc, 4, x)));
                TST_CHECK(worst <= 1e-10, "span3 %s %s L=%d: cubic profile off by %g", n2 ? "n2" : "n1", SCHED[s], L, worst);
            }
        }
}

/* ---- t from the ROM -------------------------------------------------------- */

/* span1 with I1 = 0, I2 = 1 gives y = t. At the default t (u1.15) and ROM
 * (u1.15+G) for L = 13 and 64: t <= k/dv (the ROM rounds down), k/dv - t
 * below two LSBs of t, and t = k/dv exactly where dv is a power of two. */
static void t_rom_t(void)
{
    static const int Ls[] = { 13, 64 };
    static const char *const ov[] = { "a=s8.40", "ra=s8.40", "mul=s8.40", "sm=s8.40", "rg=s8.40", "y=s8.40" };
    for (int li = 0; li < 2; li++) {
        int L = Ls[li];
        unit_cfg cfg;
        unit_fmts f;
        const unit_desc *u = setup(&UNITS[0], 1, 16, L, 3, ov, 6, &cfg, &f);
        if (!u) return;
        TST_EQ_INT(f.f[unit_sig_index(u, "t")].fbits, 15);
        tb_span_item it[64];
        for (int dv = 1; dv <= L; dv++) {
            memset(&it[dv - 1], 0, sizeof it[0]);
            it[dv - 1].n = dv + 1 <= L ? dv + 1 : L;
            it[dv - 1].dv = dv;
            it[dv - 1].node[1] = 1;
        }
        double pix[64 * 65];
        tb_span_stats st;
        char err[300];
        if (tb_span_run(u, &cfg, &f, it, (size_t)L, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
        size_t p = 0;
        int above = 0, far = 0, inexact = 0;
        for (int dv = 1; dv <= L; dv++)
            for (int k = 0; k < it[dv - 1].n; k++, p++) {
                double x = (double)k / dv;
                above += pix[p] > x;
                far += x - pix[p] >= 2 * 0x1p-15;
                inexact += !(dv & (dv - 1)) && pix[p] != x;
            }
        TST_EQ_INT(above, 0);
        TST_EQ_INT(far, 0);
        TST_EQ_INT(inexact, 0);
    }
    /* The ROM area model by hand: words {1, 2, 3}, 2 bits: 2 address
     * inverters, 3 word lines of one AND2, one OR2 for each bit. */
    int64_t w[3] = { 1, 2, 3 };
    TST_NEAR(sim_area_rom(w, 3, 2), 2 * SIM_GE_INV + 3 * SIM_GE_AND2 + 2 * SIM_GE_OR2, 1e-12);
}

/* ---- clocks ----------------------------------------------------------------- */

/* Clocks per pixel of each unit, schedule and degree, from the schedules:
 * paper 2 deg, mac deg, pipe 1 (span1: its paper 2, mac and pipe 1); and
 * what follows the last pixel's last step: the output register (1), or
 * in the pipe the stages after the one it entered (deg, span1: 1). */
static int steps(const ut *t, int s, int deg)
{
    if (!strcmp(t->name, "span1")) return s == 0 ? 2 : 1;
    return s == 0 ? 2 * deg : s == 1 ? deg : 1;
}
static int tail(const ut *t, int s)
{
    if (s != 2 || !strcmp(t->name, "span1")) return 1;
    return !strcmp(t->name, "span2") ? 2 : 3;
}

/* Back-to-back streams of random intervals: clocks from the first accept
 * to the last pixel = sum of steps * n, plus the tail; span23 mixed:
 * degree-2 items take the quadratic's clocks (paper 4, mac 2 a pixel),
 * degree-3 the cubic's (6, 3); items_deg2 counted. */
static void t_clocks(void)
{
    for (size_t ui = 0; ui < NUNITS; ui++)
        for (int s = 0; s < 3; s++) {
            const ut *t = &UNITS[ui];
            unit_cfg cfg;
            unit_fmts f;
            const unit_desc *u = setup(t, s, 16, 12, 3, NULL, 0, &cfg, &f);
            if (!u) return;
            tb_span_item it[300];
            uint64_t want = 0, npix = 0, d2 = 0;
            for (int i = 0; i < 300; i++) {
                memset(&it[i], 0, sizeof it[i]);
                it[i].n = 1 + (int)(urand() * 12);
                it[i].dv = urand() < 0.5 ? 12 : (it[i].n > 1 ? it[i].n - 1 : 1);
                it[i].deg = urand() < 0.5 ? 2 : 3;
                for (int k = 0; k < 4; k++) it[i].node[k] = urand();
                int deg = has_deg(t) ? it[i].deg : !strcmp(t->name, "span2") ? 2 : 3;
                want += (uint64_t)(steps(t, s, deg) * it[i].n);
                npix += (uint64_t)it[i].n;
                d2 += has_deg(t) && it[i].deg == 2;
            }
            want += (uint64_t)tail(t, s);
            double pix[300 * 12];
            tb_span_stats st;
            char err[300];
            if (tb_span_run(u, &cfg, &f, it, 300, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
            TST_CHECK(st.clocks == want, "%s %s: %llu clocks, expected %llu", t->name, SCHED[s],
                      (unsigned long long)st.clocks, (unsigned long long)want);
            TST_EQ_INT(st.pixels, npix);
            TST_EQ_INT(st.items, 300);
            TST_EQ_INT(st.items_deg2, d2);
            TST_CHECK(st.area_ge > 1000, "%s area %g", t->name, st.area_ge);
        }
    /* span23 paper: all-quadratic items are 4 clocks a pixel, all-cubic 6 */
    for (int deg = 2; deg <= 3; deg++) {
        unit_cfg cfg;
        unit_fmts f;
        const unit_desc *u = setup(&UNITS[4], 0, 16, 8, 3, NULL, 0, &cfg, &f);
        if (!u) return;
        tb_span_item it[50];
        for (int i = 0; i < 50; i++) {
            memset(&it[i], 0, sizeof it[i]);
            it[i].n = it[i].dv = 8;
            it[i].deg = deg;
        }
        double pix[400];
        tb_span_stats st;
        char err[300];
        if (tb_span_run(u, &cfg, &f, it, 50, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
        TST_EQ_INT(st.clocks, (deg == 2 ? 4 : 6) * 400 + 1);
    }
}

/* ---- the bound ---------------------------------------------------------------- */

/* Narrow widths 8, 10, 12, truncation and rounding, random intervals of
 * random lengths and both divisors: every pixel within the unit's bound of
 * the ideal (the network's 1/3, the held nodes, t = k/dv exact), and the
 * worst pixel of each unit and width at least a fifth of the bound (over
 * the runs measured it is 0.3 to 0.9 of it). */
static void t_bound(void)
{
    static const int widths[] = { 8, 10, 12 };
    static const sim_round rnds[] = { SIM_RND_TRUNC, SIM_RND_HALF_UP };
    double min_ratio = 1;
    for (size_t ui = 0; ui < NUNITS; ui++)
        for (int wi = 0; wi < 3; wi++) {
            double worst_ratio = 0;
            for (int s = 0; s < 3; s++)
                for (int ri = 0; ri < 2; ri++) {
                    const ut *t = &UNITS[ui];
                    unit_cfg cfg;
                    unit_fmts f;
                    int L = (s == 1 && ri == 1) ? 13 : 8;
                    const unit_desc *u = setup(t, s, widths[wi], L, 3, NULL, 0, &cfg, &f);
                    if (!u) return;
                    cfg.rnd = rnds[ri];
                    double b;
                    u->bound(&cfg, &f, &b);
                    tb_span_item it[400];
                    for (int i = 0; i < 400; i++) {
                        memset(&it[i], 0, sizeof it[i]);
                        it[i].n = 1 + (int)(urand() * L);
                        it[i].dv = urand() < 0.5 ? L : (it[i].n > 1 ? it[i].n - 1 : 1);
                        it[i].deg = urand() < 0.5 ? 2 : 3;
                        /* intensities, and every tenth interval a 0/1 corner (extreme coefficients) */
                        for (int k = 0; k < 4; k++) it[i].node[k] = i % 10 ? urand() : (double)(urand() < 0.5);
                    }
                    double pix[400 * 13];
                    tb_span_stats st;
                    char err[300];
                    if (tb_span_run(u, &cfg, &f, it, 400, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
                    TST_EQ_INT(st.overflows, 0);
                    double fac = factor(cfg.terms, 0), worst = 0;
                    size_t p = 0;
                    for (int i = 0; i < 400; i++) {
                        double I[4], c[4];
                        for (int k = 0; k < 4; k++) I[k] = held(it[i].node[k], u, &f, &cfg, k < t->nin ? k : 0);
                        int k;
                        ideal_coef(t, has_deg(t) ? it[i].deg : 3, I, fac, c, &k);
                        for (int x = 0; x < it[i].n; x++, p++)
                            worst = fmax(worst, fabs(pix[p] - poly(c, k, (double)x / it[i].dv)));
                    }
                    TST_CHECK(worst <= b * (1 + 1e-12), "%s%s %s W=%d %s: |e| %g > bound %g", t->name, t->n2 ? " n2" : "",
                              SCHED[s], widths[wi], sim_round_name(cfg.rnd), worst, b);
                    worst_ratio = fmax(worst_ratio, worst / b);
                }
            TST_CHECK(worst_ratio >= 0.2, "%s W=%d: bound loose, worst |e| only %.3f of it", UNITS[ui].name,
                      widths[wi], worst_ratio);
            min_ratio = fmin(min_ratio, worst_ratio);
            if (getenv("TST_VERBOSE")) printf("  %s%s W=%d: worst |e| / bound = %.3f\n", UNITS[ui].name,
                                              UNITS[ui].n2 ? " n2" : "", widths[wi], worst_ratio);
        }
    if (getenv("TST_VERBOSE")) printf("  smallest worst/bound ratio over units and widths: %.3f\n", min_ratio);
}

/* The bound follows --fmt overrides, the /3 network's terms and series,
 * the rounding mode and L: t and the ROM without guard bits, a coarse
 * multiplier, adder or registers, narrow inputs, a wider everything;
 * random intervals, every unit and schedule, never above the bound. */
static void t_bound_overrides(void)
{
    static const char *const ovs[][3] = {
        { "t=u1.5", "rcp=u1.5", NULL }, { "t=u1.9", "rcp=u1.7", NULL }, { "rcp=u1.4", NULL, NULL },
        { "sm=s7.4", "rg=s7.6", NULL }, { "ra=s7.3", "rb=s7.5", "y=s7.3" }, { "all=s9.7", "t=u1.12", "rcp=u1.20" },
        { "i1=u1.6", "i2=u1.6", "t=u1.4" },
    };
    int runs = 0;
    for (size_t ui = 0; ui < NUNITS; ui++)
        for (int s = 0; s < 3; s++)
            for (size_t o = 0; o < sizeof ovs / sizeof ovs[0]; o++) {
                const ut *t = &UNITS[ui];
                int nov = 0;
                while (nov < 3 && ovs[o][nov]) nov++;
                /* the overrides of signals this schedule has (the pipe has no sm, rg) */
                const unit_desc *ud = unit_find(t->name);
                int have = 1;
                for (int k = 0; k < nov; k++) {
                    char nm[16];
                    snprintf(nm, sizeof nm, "%.*s", (int)strcspn(ovs[o][k], "="), ovs[o][k]);
                    int i = unit_sig_index(ud, nm);
                    have &= !strcmp(nm, "all") || (i >= 0 && unit_sig_used(ud, i, s));
                }
                if (!have) continue;
                unit_cfg cfg;
                unit_fmts f;
                int L = 2 + (int)(urand() * 40), terms = 1 + (int)(urand() * 5);
                const unit_desc *u = setup(t, s, 10, L, terms, ovs[o], nov, &cfg, &f);
                if (!u) return;
                cfg.series = urand() < 0.5;
                cfg.rnd = (sim_round)(int)(urand() * 3);
                double b;
                u->bound(&cfg, &f, &b);
                tb_span_item it[100];
                for (int i = 0; i < 100; i++) {
                    memset(&it[i], 0, sizeof it[i]);
                    it[i].n = 1 + (int)(urand() * L);
                    it[i].dv = urand() < 0.5 ? L : (it[i].n > 1 ? it[i].n - 1 : 1);
                    it[i].deg = urand() < 0.5 ? 2 : 3;
                    for (int k = 0; k < 4; k++) it[i].node[k] = i % 7 ? urand() : (double)(urand() < 0.5);
                }
                double pix[100 * 42];
                tb_span_stats st;
                char err[300];
                if (tb_span_run(u, &cfg, &f, it, 100, pix, &st, NULL, err, sizeof err) != TB_OK) { TST_CHECK(0, "%s", err); return; }
                double fac = factor(cfg.terms, cfg.series), worst = 0;
                size_t p = 0;
                for (int i = 0; i < 100; i++) {
                    double I[4], c[4];
                    for (int k = 0; k < 4; k++) I[k] = held(it[i].node[k], u, &f, &cfg, k < t->nin ? k : 0);
                    int k;
                    ideal_coef(t, has_deg(t) ? it[i].deg : 3, I, fac, c, &k);
                    for (int x = 0; x < it[i].n; x++, p++)
                        worst = fmax(worst, fabs(pix[p] - poly(c, k, (double)x / it[i].dv)));
                }
                TST_CHECK(worst <= b * (1 + 1e-12), "%s%s %s overrides %zu L=%d terms=%d %s: |e| %g > bound %g", t->name,
                          t->n2 ? " n2" : "", SCHED[s], o, L, cfg.terms, sim_round_name(cfg.rnd), worst, b);
                runs++;
            }
    TST_CHECK(runs >= 100, "%d runs", runs);
}

/* ---- the generic testbench ------------------------------------------------------ */

/* `run` through tb_run: the default vectors (n = L, dv = L and L - 1)
 * within bound at widths 12 and 16, L = 8 and 64 (64 outputs a vector). */
static void t_generic_run(void)
{
    static const int Ls[] = { 8, 64 };
    for (size_t ui = 0; ui < NUNITS; ui++)
        for (int li = 0; li < 2; li++)
            for (int w = 12; w <= 16; w += 4) {
                const ut *t = &UNITS[ui];
                unit_cfg cfg;
                unit_fmts f;
                const unit_desc *u = setup(t, 0, w, Ls[li], 3, NULL, 0, &cfg, &f);
                if (!u) return;
                vec_set vs;
                char err[600];
                if (tb_make_vectors(u, &cfg, Ls[li] == 64 ? 20 : 0, 1, &vs, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
                TST_EQ_INT(vs.n_out, Ls[li]);
                tb_result r;
                int rc = tb_run(u, &cfg, &f, &vs, NULL, &r, err, sizeof err);
                TST_CHECK(rc == TB_OK, "%s: %s", t->name, err);
                if (rc == TB_OK) {
                    TST_CHECK(r.within_bound, "%s L=%d W=%d: bound exceeded at item %zu", t->name, Ls[li], w, r.first_violation);
                    /* paper: span1 2, span2 4, span3 6 clocks a pixel; span23's vectors are half quadratic: 5 */
                    double cpb = !strcmp(t->name, "span1") ? 2 : !strcmp(t->name, "span2") ? 4 : has_deg(t) ? 5 : 6;
                    TST_NEAR(r.cycles_per_beat, cpb, 0.05);
                }
                /* the reference's rows are the Lagrange interpolant at k/dv */
                double worst = 0;
                for (size_t i = 0; i < vs.n_rows; i++) {
                    const double *v = vec_row(&vs, i);
                    int k, ni = t->nin;
                    const double *tn = nodes_of(t, has_deg(t) ? (int)v[ni + 2] : 3, &k);
                    TST_CHECK(v[ni] == Ls[li] && (v[ni + 1] == Ls[li] || v[ni + 1] == Ls[li] - 1), "row %zu n, dv", i);
                    for (int x = 0; x < Ls[li]; x++)
                        worst = fmax(worst, fabs(v[vs.n_in + x] - tst_lagrange(tn, v, k, x / v[ni + 1])));
                }
                TST_CHECK(worst < 1e-12, "%s reference vs Lagrange %g", t->name, worst);
                tb_result_free(&r);
                vec_set_free(&vs);
            }
}

/* ---- signals ---------------------------------------------------------------------- */

/* Every listed internal signal is built (in the unit, its coef, horner or
 * dp scope) exactly when the schedule has it and, for the cubic networks'
 * own elements, the node set has it. */
static void t_signals_built(void)
{
    for (size_t ui = 0; ui < NUNITS; ui++)
        for (int s = 0; s < 3; s++) {
            const ut *t = &UNITS[ui];
            unit_cfg cfg;
            unit_fmts f;
            const unit_desc *u = setup(t, s, 16, 8, 3, NULL, 0, &cfg, &f);
            if (!u) return;
            sim_ctx *c = sim_new();
            sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
            unit_io io;
            memset(&io, 0, sizeof io);
            char err[300];
            TST_CHECK(u->build(c, sim_scope_new(c, NULL, u->name), clk, &cfg, &f, &io, err, sizeof err) == 0, "%s", err);
            for (int i = 0; i < u->nsigs; i++) {
                if (u->sigs[i].role != UNIT_SIG_INTERNAL) continue;
                static const char *const where[] = { "", "coef.", "horner.", "dp." };
                int got = 0;
                for (int w = 0; w < 4; w++) {
                    char path[64];
                    snprintf(path, sizeof path, "%s.%s%s", u->name, where[w], u->sigs[i].name);
                    got |= sim_find(c, NULL, path) != NULL;
                }
                const char *what = u->sigs[i].what;
                int want = unit_sig_used(u, i, s) && !(t->n2 && !strncmp(what, "n1 only", 7))
                           && !(!t->n2 && !strncmp(what, "n2 only", 7));
                /* the /3 networks are scopes: their output y */
                if (!strncmp(u->sigs[i].name, "div3_", 5)) {
                    char path[64];
                    snprintf(path, sizeof path, "%s.coef.%s.y", u->name, u->sigs[i].name);
                    got = sim_find(c, NULL, path) != NULL;
                }
                TST_CHECK(want == got, "%s%s %s: %s %s", t->name, t->n2 ? " n2" : "", SCHED[s], u->sigs[i].name,
                          want ? "missing" : "built");
            }
            sim_free(c);
        }
}

/* ---- bad configurations ---------------------------------------------------------- */

static void t_rejected(void)
{
    unit_cfg cfg;
    unit_fmts f;
    char err[300];
    const unit_desc *u = setup(&UNITS[2], 0, 16, 8, 3, NULL, 0, &cfg, &f);
    if (!u) return;
    tb_span_item ok = { { 0.5, 0.5, 0.5, 0.5 }, 8, 8, 3 };
    double pix[64];
    tb_span_stats st;
    struct { tb_span_item it; const char *msg; } bad[] = {
        { { { 0, 0, 0, 0 }, 4, 9, 3 }, "dv = 9" },
        { { { 0, 0, 0, 0 }, 0, 8, 3 }, "n = 0" },
        { { { 0, 0, 0, 0 }, 9, 8, 3 }, "n = 9" },
        { { { 0, 0, 0, 0 }, 6, 3, 3 }, "past 1" },
        { { { 0, 0, 0, 0 }, 4, 0, 3 }, "dv = 0" },
        { { { NAN, 0, 0, 0 }, 4, 8, 3 }, "not finite" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        tb_span_item it[2] = { ok, bad[k].it };
        err[0] = 0;
        TST_CHECK(tb_span_run(u, &cfg, &f, it, 2, pix, &st, NULL, err, sizeof err) == TB_BADINPUT
                  && strstr(err, bad[k].msg) && strstr(err, "interval 1"), "%s: '%s'", bad[k].msg, err);
    }
    /* span23: a degree other than 2 or 3 */
    const unit_desc *u23 = setup(&UNITS[4], 0, 16, 8, 3, NULL, 0, &cfg, &f);
    tb_span_item d4 = ok;
    d4.deg = 4;
    TST_CHECK(tb_span_run(u23, &cfg, &f, &d4, 1, pix, &st, NULL, err, sizeof err) == TB_BADINPUT && strstr(err, "degree 4"),
              "deg 4: '%s'", err);
    /* L out of range: the parameter table, the builder and tb_span_run */
    TST_CHECK(unit_param_set(u, &cfg, "L", "65", err, sizeof err) < 0 && strstr(err, "65"), "L=65: '%s'", err);
    TST_CHECK(unit_param_set(u, &cfg, "L", "1", err, sizeof err) < 0, "L=1 accepted");
    TST_CHECK(unit_param_set(u, &cfg, "L", "13", err, sizeof err) == 0 && cfg.L == 13, "L=13: '%s'", err);
    TST_CHECK(unit_param_set(u, &cfg, "nodes", "n3", err, sizeof err) < 0 && strstr(err, "n1 n2"), "nodes=n3: '%s'", err);
    cfg.L = 65;
    TST_CHECK(tb_span_run(u, &cfg, &f, &ok, 1, pix, &st, NULL, err, sizeof err) == TB_BADINPUT && strstr(err, "L = 65"),
              "L=65 run: '%s'", err);
    sim_ctx *c = sim_new();
    unit_io io;
    memset(&io, 0, sizeof io);
    cfg.L = 1;
    TST_CHECK(u->build(c, sim_scope_new(c, NULL, "x"), sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK), &cfg, &f, &io, err,
                       sizeof err) < 0 && strstr(err, "L = 1"), "build L=1: '%s'", err);
    sim_free(c);
    /* a t format that cannot hold 1 */
    const char *ov = "t=u0.16";
    u = setup(&UNITS[2], 0, 16, 8, 3, &ov, 1, &cfg, &f);
    TST_CHECK(tb_span_run(u, &cfg, &f, &ok, 1, pix, &st, NULL, err, sizeof err) == TB_BADINPUT && strstr(err, "t format"),
              "t=u0.16: '%s'", err);
    /* n, dv formats that cannot hold L */
    static const char *const narrow[] = { "n=u3.0", "dv=s4.2" };
    for (int k = 0; k < 2; k++) {
        u = setup(&UNITS[2], 0, 16, 8, 3, &narrow[k], 1, &cfg, &f);
        TST_CHECK(tb_span_run(u, &cfg, &f, &ok, 1, pix, &st, NULL, err, sizeof err) == TB_BADINPUT
                  && strstr(err, "cannot hold 8"), "%s: '%s'", narrow[k], err);
    }
    /* not a span unit */
    unit_cfg hc;
    unit_cfg_default(unit_find("horner3"), &hc);
    unit_fmts hf;
    unit_find("horner3")->formats(&hc, &hf);
    TST_CHECK(tb_span_run(unit_find("horner3"), &hc, &hf, &ok, 1, pix, &st, NULL, err, sizeof err) == TB_BADINPUT
              && strstr(err, "not a span unit"), "horner3: '%s'", err);
}

/* ---- VCD ------------------------------------------------------------------------- */

static void t_vcd(void)
{
    char dir[] = "/tmp/tspanXXXXXX", path[64];
    if (!mkdtemp(dir)) TST_SKIP("mkdtemp failed");
    snprintf(path, sizeof path, "%s/s.vcd", dir);
    unit_cfg cfg;
    unit_fmts f;
    const unit_desc *u = setup(&UNITS[4], 1, 12, 5, 3, NULL, 0, &cfg, &f);
    if (!u) return;
    tb_span_item it[3] = { { { 0.1, 0.9, 0.5, 0.3 }, 5, 5, 3 }, { { 0.9, 0.2, 0.4, 0 }, 3, 2, 2 }, { { 0, 1, 1, 1 }, 1, 1, 3 } };
    double pix[9];
    tb_span_stats st;
    char err[300];
    TST_EQ_INT(tb_span_run(u, &cfg, &f, it, 3, pix, &st, path, err, sizeof err), TB_OK);
    FILE *fp = fopen(path, "r");
    TST_CHECK(fp != NULL, "no VCD");
    if (fp) {
        char line[512];
        int rcp = 0, t = 0;
        while (fgets(line, sizeof line, fp)) { rcp |= strstr(line, " rcp ") != NULL; t |= strstr(line, " t ") != NULL; }
        fclose(fp);
        TST_CHECK(rcp && t, "VCD lacks rcp or t");
    }
    TST_EQ_INT(st.pixels, 9);
    snprintf(path, sizeof path, "%s/no/such/s.vcd", dir);
    TST_EQ_INT(tb_span_run(u, &cfg, &f, it, 3, pix, &st, path, err, sizeof err), TB_BADINPUT);
    tst_rmtree(dir);
    rmdir(dir);
}

int main(void)
{
    TST_RUN(t_wide_every_length);
    TST_RUN(t_profiles_exact);
    TST_RUN(t_rom_t);
    TST_RUN(t_clocks);
    TST_RUN(t_bound);
    TST_RUN(t_bound_overrides);
    TST_RUN(t_generic_run);
    TST_RUN(t_signals_built);
    TST_RUN(t_rejected);
    TST_RUN(t_vcd);
    TST_EXIT();
}
