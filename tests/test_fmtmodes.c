/* test_fmtmodes.c - formats that carry their own rounding and overflow
 * modes ("s7.12:half-up:sat"): the text form, the quantization, the
 * primitives, a unit run with one or every signal given modes, the bound
 * that must not claim more than it derives, and the Verilog export.
 *
 * References are computed here with integer arithmetic written out by hand
 * (floor division, clamping, wrapping modulo 2^W), not with sim_fixed.c. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include "testbench/tb_verilog.h"
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

static sim_fmt F(const char *s)
{
    sim_fmt f;
    char err[160];
    if (sim_fmt_parse(s, &f, err, sizeof err)) { printf("  bad test format %s: %s\n", s, err); abort(); }
    return f;
}

/* ---- hand references ---- */

static int64_t floor_div(int64_t a, int k) { return a >= 0 ? a >> k : -((-a + ((int64_t)1 << k) - 1) >> k); }

/* raw with src fraction bits into a signed W-bit format with fb fraction
 * bits (fb <= src): rounding r, then overflow o. */
static int64_t hand_q(int64_t raw, int src, int W, int fb, int r, int o, int *ovf)
{
    int k = src - fb;
    int64_t q;
    if (k == 0) q = raw;
    else if (r == 0) q = floor_div(raw, k);                                   /* trunc */
    else if (r == 1) q = floor_div(raw + ((int64_t)1 << (k - 1)), k);         /* half-up */
    else {                                                                     /* even */
        int64_t fl = floor_div(raw, k), rem = raw - fl * ((int64_t)1 << k), half = (int64_t)1 << (k - 1);
        q = rem > half || (rem == half && (fl & 1)) ? fl + 1 : fl;
    }
    int64_t lo = -((int64_t)1 << (W - 1)), hi = ((int64_t)1 << (W - 1)) - 1;
    *ovf = q < lo || q > hi;
    if (!*ovf) return q;
    if (o == 1) return q < lo ? lo : hi;
    int64_t m = (int64_t)1 << W, w = ((q % m) + m) % m;                       /* wrap modulo 2^W */
    return w > hi ? w - m : w;
}

/* ---- the text form ---- */

static void t_text(void)
{
    static const char *const rn[] = { "", ":trunc", ":half-up", ":even" }, *on[] = { "", ":wrap", ":sat" };
    char s[64], back[SIM_FMT_STRLEN], err[200];
    for (int r = 0; r < 4; r++)
        for (int o = 0; o < 3; o++)
            for (int swap = 0; swap < 2; swap++) {
                snprintf(s, sizeof s, "s7.12%s%s", swap ? on[o] : rn[r], swap ? rn[r] : on[o]);
                sim_fmt f;
                TST_CHECK(sim_fmt_parse(s, &f, err, sizeof err) == 0, "%s: %s", s, err);
                TST_CHECK(f.is_signed == 1 && f.ibits == 7 && f.fbits == 12 && f.width == 19, "%s", s);
                TST_CHECK(f.rnd == r && f.ovf == o, "%s -> rnd %d ovf %d", s, f.rnd, f.ovf);
                char want[64];
                snprintf(want, sizeof want, "s7.12%s%s", rn[r], on[o]);   /* rounding first */
                TST_EQ_STR(sim_fmt_str(f, back), want);
                sim_fmt g;
                TST_CHECK(sim_fmt_parse(back, &g, err, sizeof err) == 0 && !memcmp(&f, &g, sizeof f), "%s round trip", s);
            }
    /* the widest text fits the buffer */
    sim_fmt f = F("u31.32:half-up:wrap");
    TST_EQ_STR(sim_fmt_str(f, back), "u31.32:half-up:wrap");
    /* a plain format prints as it always did, and sim_fmt_make gives no modes */
    TST_EQ_STR(sim_fmt_str(F("s2.14"), back), "s2.14");
    TST_EQ_INT(sim_fmt_make(1, 2, 14, &f, NULL, 0), 0);
    TST_CHECK(!sim_fmt_has_modes(f), "make gave modes");
    TST_EQ_INT(sim_fmt_round(f, SIM_RND_EVEN), SIM_RND_EVEN);
    TST_EQ_INT(sim_fmt_ovf(F("s2.14:sat"), SIM_OVF_WRAP), SIM_OVF_SAT);

    static const struct { const char *s, *why; } bad[] = {
        { "s7.12:foo", "unknown mode 'foo'" }, { "s7.12:sat:sat", "overflow mode given twice" },
        { "s7.12:", "empty mode" }, { "s7.12::sat", "empty mode" }, { "s7.12:sat:", "empty mode" },
        { "s7.12:trunc:even", "rounding mode given twice" }, { "s7.12:Sat", "unknown mode 'Sat'" },
        { "s7.12:half_up", "unknown mode" }, { "s7.12 :sat", "expected sI.F" }, { ":sat", "expected sI.F" },
        { "s70.1:sat", "width 71 > 64" }, { "s7.12:sat\n", "unknown mode 'sat?'" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        sim_fmt x = { 7, 7, 7, 7, 7, 7 };
        err[0] = 0;
        TST_EQ_INT(sim_fmt_parse(bad[k].s, &x, err, sizeof err), -1);
        TST_CHECK(x.width == 7 && x.rnd == 7, "'%s' wrote the output", bad[k].s);
        TST_CHECK(strstr(err, bad[k].why) && !strchr(err, '\n') && !strncmp(err, "bad format '", 12),
                  "'%s': message '%s' lacks '%s'", bad[k].s, err, bad[k].why);
    }
}

/* ---- quantization: the format's modes win over the caller's ---- */

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t rnd64(void) { rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17; return rng; }

static void t_requant(void)
{
    static const char *const rn[] = { "trunc", "half-up", "even" }, *on[] = { "wrap", "sat" };
    int n = 0, differ = 0;
    for (int r = 0; r < 3; r++)
        for (int o = 0; o < 2; o++) {
            char s[40];
            snprintf(s, sizeof s, "s3.8:%s:%s", rn[r], on[o]);
            sim_fmt own = F(s), plain = F("s3.8");
            for (int i = 0; i < 2000; i++) {
                int64_t raw = (int64_t)(rnd64() % (1u << 24)) - (1 << 23);   /* s12.12-ish, 12 fraction bits */
                int ov_h, ov;
                int64_t want = hand_q(raw, 12, 11, 8, r, o, &ov_h);
                /* the caller asks for the other modes: the format's win */
                int64_t got = sim_fx_requant(raw, 12, own, (sim_round)((r + 1) % 3), (sim_ovf)!o, &ov);
                TST_CHECK(got == want && ov == ov_h, "%s raw %lld: %lld, expected %lld", s, (long long)raw,
                          (long long)got, (long long)want);
                /* a plain format takes the caller's */
                TST_EQ_INT(sim_fx_requant(raw, 12, plain, (sim_round)r, (sim_ovf)o, NULL), want);
                /* and a real the same way: raw * 2^-12 is exact in a double */
                TST_EQ_INT(sim_fx_from_real(ldexp((double)raw, -12), own, SIM_RND_TRUNC, SIM_OVF_WRAP, NULL), want);
                differ += sim_fx_requant(raw, 12, plain, (sim_round)((r + 1) % 3), (sim_ovf)!o, NULL) != want;
                n++;
            }
        }
    TST_CHECK(differ > n / 4, "the caller's modes would give the same raws (%d of %d differ)", differ, n);
}

/* ---- primitives ---- */

static void t_primitives(void)
{
    /* Context trunc/wrap; one multiplier's format says half-up/sat, a
     * second one (plain) takes the context's; a register with its own
     * sat behind the plain one. */
    sim_ctx *c = sim_new();
    sim_set_quant(c, SIM_RND_TRUNC, SIM_OVF_WRAP);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_clock(c, clk, 5, 5);
    sim_signal *a = sim_signal_new(c, NULL, "a", F("s4.8"), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, NULL, "b", F("s4.8"), SIM_KIND_INPUT);
    sim_signal *m1 = sim_mul(c, NULL, "m1", F("s2.8:half-up:sat"), a, b);
    sim_signal *m2 = sim_mul(c, NULL, "m2", F("s2.8"), a, b);
    sim_signal *s1 = sim_add(c, NULL, "s1", F("s2.6:even"), a, b);
    sim_signal *r1 = sim_reg(c, NULL, "r1", F("s1.8:sat"), clk, m2, NULL, NULL, 0);
    sim_signal *k1 = sim_const(c, NULL, "k1", F("s2.2:half-up:sat"), 7.4);
    sim_signal *k2 = sim_const(c, NULL, "k2", F("s2.2"), 1.375);
    sim_prim_info in;
    TST_EQ_INT(sim_prim_describe(m1, &in), 0);
    TST_CHECK(in.r == SIM_RND_HALF_UP && in.o == SIM_OVF_SAT, "m1 described as %d/%d", in.r, in.o);
    TST_EQ_INT(sim_prim_describe(m2, &in), 0);
    TST_CHECK(in.r == SIM_RND_TRUNC && in.o == SIM_OVF_WRAP, "m2 described as %d/%d", in.r, in.o);
    TST_EQ_INT(sim_prim_describe(s1, &in), 0);
    TST_CHECK(in.r == SIM_RND_EVEN && in.o == SIM_OVF_WRAP, "s1 described as %d/%d", in.r, in.o);
    TST_EQ_INT(sim_prim_describe(r1, &in), 0);
    TST_CHECK(in.r == SIM_RND_TRUNC && in.o == SIM_OVF_SAT, "r1 described as %d/%d", in.r, in.o);
    /* constants: 7.4 saturates to 1.75 (raw 7); 1.375 truncates to 1.25 */
    TST_EQ_INT(k1->cur, 7);
    TST_EQ_INT(k2->cur, 5);
    int sat_seen = 0, wrap_seen = 0;
    sim_time T = 0;
    for (int i = 0; i < 300; i++) {
        int64_t av = (int64_t)(rnd64() % 4096) - 2048, bv = (int64_t)(rnd64() % 4096) - 2048;
        sim_force(a, av);
        sim_force(b, bv);
        T += 10;
        sim_run(c, T);   /* settles, then one rising edge: r1 takes m2's new value */
        int o1, o2, o3, o4;
        int64_t w1 = hand_q(av * bv, 16, 10, 8, 1, 1, &o1);
        int64_t w2 = hand_q(av * bv, 16, 10, 8, 0, 0, &o2);
        int64_t w3 = hand_q(av + bv, 8, 8, 6, 2, 0, &o3);
        int64_t w4 = hand_q(w2, 8, 9, 8, 0, 1, &o4);
        TST_CHECK(m1->cur == w1, "m1 %lld*%lld: %lld, expected %lld", (long long)av, (long long)bv, (long long)m1->cur, (long long)w1);
        TST_CHECK(m2->cur == w2, "m2 %lld*%lld: %lld, expected %lld", (long long)av, (long long)bv, (long long)m2->cur, (long long)w2);
        TST_CHECK(s1->cur == w3, "s1 %lld+%lld: %lld, expected %lld", (long long)av, (long long)bv, (long long)s1->cur, (long long)w3);
        TST_CHECK(r1->cur == w4, "r1 <= %lld: %lld, expected %lld", (long long)w2, (long long)r1->cur, (long long)w4);
        sat_seen += o1;
        wrap_seen += o2 && w1 != w2;
    }
    TST_CHECK(sat_seen > 50 && wrap_seen > 50, "too few overflows to tell sat from wrap (%d, %d)", sat_seen, wrap_seen);
    TST_CHECK(m1->overflows > 0 && m2->overflows > 0, "overflows not counted: %llu %llu",
              (unsigned long long)m1->overflows, (unsigned long long)m2->overflows);
    sim_free(c);
}

/* ---- a unit ---- */

static int run_unit(const char *name, const char *round, const char *const *ov, int nov, tb_result *r, char *err, size_t errlen)
{
    const unit_desc *u = unit_find(name);
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    if (round && sim_round_parse(round, &cfg.rnd)) abort();
    unit_fmts fm;
    memset(r, 0, sizeof *r);
    if (tb_formats(u, &cfg, ov, nov, &fm, err, errlen)) return -1;
    vec_set vs;
    if (tb_make_vectors(u, &cfg, 300, 7, &vs, err, errlen)) return -1;
    int rc = tb_run(u, &cfg, &fm, &vs, NULL, r, err, errlen);
    if (rc == TB_OK) tb_verdict(r, NULL);
    vec_set_free(&vs);
    return rc;
}

static int same_raws(const tb_result *x, const tb_result *y)
{
    size_t n = x->vectors * (size_t)x->beats * (size_t)x->n_out;
    return x->vectors == y->vectors && !memcmp(x->raw, y->raw, n * sizeof *x->raw);
}

/* Every signal of horner3 given :half-up under the global trunc builds the
 * design the global --round half-up builds: the same raws. The bound is
 * then not claimed (it assumes the global mode); every signal given the
 * global mode itself keeps it. */
static void t_unit_all_signals(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts def;
    char err[600];
    TST_EQ_INT(tb_formats(u, &cfg, NULL, 0, &def, err, sizeof err), 0);
    char ovb[UNIT_MAX_SIGS][48], ovt[UNIT_MAX_SIGS][48];
    const char *ov[UNIT_MAX_SIGS], *ot[UNIT_MAX_SIGS];
    int n = 0;
    for (int i = 0; i < u->nsigs; i++) {
        if (!unit_sig_built(u, i, &cfg)) continue;
        char fb[SIM_FMT_STRLEN];
        snprintf(ovb[n], sizeof ovb[n], "%s=%s:half-up", u->sigs[i].name, sim_fmt_str(def.f[i], fb));
        snprintf(ovt[n], sizeof ovt[n], "%s=%s:trunc", u->sigs[i].name, sim_fmt_str(def.f[i], fb));
        ov[n] = ovb[n]; ot[n] = ovt[n]; n++;
    }
    tb_result g, p, t, pt;
    TST_EQ_INT(run_unit("horner3", "half-up", NULL, 0, &g, err, sizeof err), TB_OK);
    TST_EQ_INT(run_unit("horner3", NULL, ov, n, &p, err, sizeof err), TB_OK);
    TST_EQ_INT(run_unit("horner3", NULL, NULL, 0, &t, err, sizeof err), TB_OK);
    TST_EQ_INT(run_unit("horner3", NULL, ot, n, &pt, err, sizeof err), TB_OK);
    TST_CHECK(same_raws(&g, &p), "per-signal half-up differs from the global --round half-up");
    TST_CHECK(!same_raws(&g, &t), "half-up and trunc give the same raws: the check above cannot fail");
    TST_CHECK(same_raws(&t, &pt), "per-signal trunc differs from the global trunc");
    TST_EQ_INT(g.bound_check, TB_CHECK_OK);
    TST_EQ_INT(p.bound_check, TB_CHECK_NO_BOUND);
    TST_CHECK(!p.ok && strstr(p.why, "NO BOUND"), "verdict '%s'", p.why);
    TST_EQ_INT(pt.bound_check, TB_CHECK_OK);
    TST_CHECK(pt.out[0].bound == t.out[0].bound, "bound %g, global %g", pt.out[0].bound, t.out[0].bound);
    tb_result_free(&g); tb_result_free(&p); tb_result_free(&t); tb_result_free(&pt);
}

/* horner3's paper schedule by hand in raws, A..D in s7.9 and t in u1.15
 * (truncated, as the testbench quantizes them): v = A; then for each of
 * B, C, D: v = sm(mul(v t) + coef), the product truncated from 24 to 9
 * fraction bits into mul's format (s2.9 here), the sum wrapped in s7.9.
 * mux, block key and register are copies in one format. */
static int64_t horner_hand(const double *row, int mul_sat)
{
    int64_t c[4], t = (int64_t)floor(ldexp(row[4], 15)), v;
    for (int i = 0; i < 4; i++) c[i] = (int64_t)floor(ldexp(row[i], 9));
    v = c[0];
    for (int i = 1; i < 4; i++) {
        int o;
        int64_t m = hand_q(v * t, 24, 11, 9, 0, mul_sat, &o);
        v = hand_q(m + c[i], 9, 16, 9, 0, 0, &o);
    }
    return v;
}

/* One signal saturates, the rest wrap: the outputs follow the hand model
 * with mul saturating, and the same design without the mode follows it
 * with mul wrapping; the overflows are mul's. */
static void t_unit_one_signal(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    char err[600];
    vec_set vs;
    TST_EQ_INT(tb_make_vectors(u, &cfg, 300, 7, &vs, err, sizeof err), 0);
    const char *ov_sat[] = { "mul=s2.9:sat" }, *ov_wrap[] = { "mul=s2.9" };
    tb_result s, w;
    TST_EQ_INT(run_unit("horner3", NULL, ov_sat, 1, &s, err, sizeof err), TB_OK);
    TST_EQ_INT(run_unit("horner3", NULL, ov_wrap, 1, &w, err, sizeof err), TB_OK);
    int differ = 0;
    for (size_t i = 0; i < vs.n_rows && i < s.vectors; i++) {
        int64_t hs = horner_hand(vec_row(&vs, i), 1), hw = horner_hand(vec_row(&vs, i), 0);
        TST_CHECK(s.raw[i] == hs, "vector %zu: mul sat gives %lld, expected %lld", i, (long long)s.raw[i], (long long)hs);
        TST_CHECK(w.raw[i] == hw, "vector %zu: mul wrap gives %lld, expected %lld", i, (long long)w.raw[i], (long long)hw);
        differ += hs != hw;
    }
    TST_CHECK(differ >= 5, "only %d vectors tell sat from wrap", differ);
    uint64_t mul_s = 0, mul_w = 0, other = 0;
    for (int k = 0; k < s.nsigs; k++) {
        if (!strcmp(s.sigs[k].name, "mul")) mul_s = s.sigs[k].overflows;
        else other += s.sigs[k].overflows;
        TST_CHECK(!strcmp(s.sigs[k].name, "mul") ? s.sigs[k].fmt.ovf == 2 : !sim_fmt_has_modes(s.sigs[k].fmt),
                  "signal %s has modes %d/%d", s.sigs[k].name, s.sigs[k].fmt.rnd, s.sigs[k].fmt.ovf);
    }
    for (int k = 0; k < w.nsigs; k++) if (!strcmp(w.sigs[k].name, "mul")) mul_w = w.sigs[k].overflows;
    /* (the counts differ: after a saturation the next products differ) */
    TST_CHECK(mul_s > 0 && mul_w > 0 && other == 0, "overflows: mul sat %llu, mul wrap %llu, others %llu",
              (unsigned long long)mul_s, (unsigned long long)mul_w, (unsigned long long)other);
    /* an overflow mode alone keeps the bound */
    TST_CHECK(s.bound_check != TB_CHECK_NO_BOUND, "sat alone lost the bound");
    tb_result_free(&s); tb_result_free(&w);
    vec_set_free(&vs);
}

/* Modes on a signal the unit computes with its own logic are refused,
 * naming the option; unknown texts name the option too. */
static void t_refused(void)
{
    const unit_desc *u = unit_find("hf_lookup");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts fm;
    char err[600];
    const char *o1[] = { "rec=u1.15:half-up" }, *o2[] = { "u=s2.14:half-up" }, *o3[] = { "mul=s7.12:foo" };
    TST_EQ_INT(tb_formats(u, &cfg, o1, 1, &fm, err, sizeof err), -1);
    TST_CHECK(strstr(err, "--fmt rec=u1.15:half-up") && strstr(err, "own logic"), "'%s'", err);
    TST_EQ_INT(tb_formats(u, &cfg, o2, 1, &fm, err, sizeof err), 0);      /* a multiplier: fine */
    TST_EQ_INT(tb_formats(unit_find("horner3"), &cfg, o3, 1, &fm, err, sizeof err), -1);
    TST_CHECK(strstr(err, "--fmt mul=s7.12:foo") && strstr(err, "unknown mode 'foo'") && !strchr(err, '\n'), "'%s'", err);
}

/* Units whose bound is the unet walk (div3, the coefficient units) follow
 * each signal's own rounding: div3's bound by hand, and random mixes of
 * modes within their bounds on every vector (tb_run's exact check). */
static void t_unet_bound(void)
{
    const unit_desc *u = unit_find("div3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts fm;
    char err[600];
    /* W = 16, terms 3: x s1.15, terms and sums s1.17. t1 = x/8, t2 = x/32,
     * t3 = x/128 drop 1, 3 and 5 bits; y drops 2 of s3's 17. Trunc loses
     * 2^-F - 2^-src, rounding 2^-(F+1); t2 rounds half-up. */
    const char *ov[] = { "t2=s1.17:half-up" };
    TST_EQ_INT(tb_formats(u, &cfg, ov, 1, &fm, err, sizeof err), 0);
    double b, want = (ldexp(1, -17) - ldexp(1, -18)) + ldexp(1, -18) + (ldexp(1, -17) - ldexp(1, -22))
                     + (ldexp(1, -15) - ldexp(1, -17));
    unit_bound(u, &cfg, &fm, &b);
    TST_NEAR(b, want, 1e-20);
    static const char *const rn[] = { "trunc", "half-up", "even" };
    static const char *const units[] = { "div3", "coef3_n1", "coef2" };
    int runs = 0;
    for (size_t k = 0; k < 3; k++)
        for (int rep = 0; rep < 4; rep++) {
            u = unit_find(units[k]);
            unit_cfg_default(u, &cfg);
            cfg.rnd = (sim_round)(rnd64() % 3);
            unit_fmts def;
            TST_EQ_INT(tb_formats(u, &cfg, NULL, 0, &def, err, sizeof err), 0);
            char buf[UNIT_MAX_SIGS][64];
            const char *o[UNIT_MAX_SIGS];
            int n = 0, other = 0;
            for (int i = 0; i < u->nsigs; i++) {
                if (!unit_sig_built(u, i, &cfg) || rnd64() % 2) continue;
                char fb[SIM_FMT_STRLEN];
                int r = (int)(rnd64() % 3);
                other |= r != (int)cfg.rnd;
                snprintf(buf[n], sizeof buf[n], "%s=%s:%s", u->sigs[i].name, sim_fmt_str(def.f[i], fb), rn[r]);
                o[n] = buf[n]; n++;
            }
            tb_result r;
            vec_set vs;
            TST_EQ_INT(tb_formats(u, &cfg, o, n, &fm, err, sizeof err), 0);
            TST_EQ_INT(tb_make_vectors(u, &cfg, 200, 100 + (uint64_t)rep, &vs, err, sizeof err), 0);
            TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, NULL, &r, err, sizeof err), TB_OK);
            tb_verdict(&r, NULL);
            TST_CHECK(r.bound_check == TB_CHECK_OK && r.overflows == r.in_overflows, "%s --round %s with %d own modes: %s",
                      units[k], rn[cfg.rnd], n, r.why);
            runs += other;
            tb_result_free(&r);
            vec_set_free(&vs);
        }
    TST_CHECK(runs >= 6, "only %d runs mixed modes", runs);
}

/* ---- the Verilog export follows each element's own modes ---- */

static void t_cosim(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (system("command -v iverilog >/dev/null 2>&1 && command -v vvp >/dev/null 2>&1")) TST_SKIP("iverilog not installed");
    static const struct { const char *u; const char *ov[3]; } D[] = {
        { "horner3", { "mul=s3.12:half-up:sat", "sm=s7.12:even", "t=u1.15:half-up" } },
        { "div3", { "s2=s1.16:half-up", "t3=s1.16:even:sat", "y=s1.12:half-up:sat" } },
    };
    char dir[] = "/tmp/shadesim_fmtmodes_XXXXXX";
    if (!mkdtemp(dir)) { TST_CHECK(0, "mkdtemp"); return; }
    for (size_t k = 0; k < sizeof D / sizeof D[0]; k++) {
        const unit_desc *u = unit_find(D[k].u);
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        cfg.width = 16;
        unit_fmts fm;
        char err[600], msg[1200];
        TST_CHECK(tb_formats(u, &cfg, D[k].ov, 3, &fm, err, sizeof err) == 0, "%s: %s", D[k].u, err);
        vec_set vs;
        if (tb_make_vectors(u, &cfg, 40, 11, &vs, err, sizeof err)) { TST_CHECK(0, "%s", err); continue; }
        char sub[300];
        snprintf(sub, sizeof sub, "%s/%s", dir, D[k].u);
        mkdir(sub, 0777);
        int rc = tb_cosim(u, &cfg, &fm, &vs, TB_SIM_ICARUS, sub, msg, sizeof msg);
        TST_CHECK(rc == TB_COSIM_EXACT, "%s: %s", D[k].u, msg);
        printf("  %s: %s\n", D[k].u, msg);
        vec_set_free(&vs);
    }
    char cmd[200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd)) { /* best effort */ }
}

int main(void)
{
    TST_RUN(t_text);
    TST_RUN(t_requant);
    TST_RUN(t_primitives);
    TST_RUN(t_unit_all_signals);
    TST_RUN(t_unit_one_signal);
    TST_RUN(t_refused);
    TST_RUN(t_unet_bound);
    TST_RUN(t_cosim);
    TST_EXIT();
}
