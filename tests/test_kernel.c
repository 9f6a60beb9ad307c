/* test_kernel.c - kernel semantics: non-blocking register updates, delta
 * cycles, loop detection, clocks, and the datapath primitives' arithmetic
 * against independent double-precision computations. Every test runs on
 * the fast kernel, then again on its reference (sim_set_reference: no
 * fast path), which must meet the same hand-derived expectations; and
 * the two must agree on every counter of a design with every kind of
 * element (t_reference_counters). */
#include "tests/tst.h"
#include "sim/sim.h"
#include "sim/sim_prim.h"
#include "sim/sim_area.h"

/* 1 while the tests run on the kernel's reference. */
static int on_reference;

static sim_ctx *ctx_new(void)
{
    sim_ctx *c = sim_new();
    sim_set_reference(c, on_reference);
    return c;
}

static sim_fmt F(const char *s)
{
    sim_fmt f;
    char err[128];
    if (sim_fmt_parse(s, &f, err, sizeof err)) { printf("  bad test format %s\n", s); abort(); }
    return f;
}

/* Clock with period 10: rising edges at 5, 15, 25, ... */
static sim_signal *clock(sim_ctx *c)
{
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_clock(c, clk, 5, 5);
    return clk;
}

static void t_shift_register(void)
{
    /* in -> r0 -> r1 -> r2 -> r3: after k edges r_i holds in's value of
     * edge k-i, in either creation order of the registers. */
    for (int order = 0; order < 2; order++) {
        sim_ctx *c = ctx_new();
        sim_signal *clk = clock(c);
        sim_signal *in = sim_signal_new(c, NULL, "in", F("u8.0"), SIM_KIND_INPUT);
        sim_signal *r[4];
        for (int j = 0; j < 4; j++) {
            int i = order ? 3 - j : j;
            char n[8];
            snprintf(n, sizeof n, "r%d", i);
            r[i] = sim_reg(c, NULL, n, F("u8.0"), clk, NULL, NULL, NULL, 0);
        }
        for (int i = 0; i < 4; i++) sim_reg_connect(r[i], i ? r[i - 1] : in);
        int64_t hist[16] = { 0 };
        for (int k = 1; k <= 10; k++) {
            hist[k] = 10 + 7 * k;
            sim_force(in, hist[k]);
            TST_EQ_INT(sim_run(c, (sim_time)(10 * k - 5)), SIM_OK);   /* through edge k */
            for (int i = 0; i < 4; i++) TST_EQ_INT(r[i]->cur, k - i >= 1 ? hist[k - i] : 0);
        }
        TST_EQ_INT(sim_get_stats(c)->clocks, 10);
        sim_free(c);
    }
}

static void t_swap(void)
{
    /* a <= b; b <= a on one edge exchanges them, in either creation order. */
    for (int order = 0; order < 2; order++) {
        sim_ctx *c = ctx_new();
        sim_signal *clk = clock(c);
        sim_signal *a, *b;
        if (!order) {
            a = sim_reg(c, NULL, "a", F("s8.0"), clk, NULL, NULL, NULL, 3);
            b = sim_reg(c, NULL, "b", F("s8.0"), clk, NULL, NULL, NULL, -5);
        } else {
            b = sim_reg(c, NULL, "b", F("s8.0"), clk, NULL, NULL, NULL, -5);
            a = sim_reg(c, NULL, "a", F("s8.0"), clk, NULL, NULL, NULL, 3);
        }
        sim_reg_connect(a, b);
        sim_reg_connect(b, a);
        sim_run(c, 5);
        TST_EQ_INT(a->cur, -5);
        TST_EQ_INT(b->cur, 3);
        sim_run(c, 15);
        TST_EQ_INT(a->cur, 3);
        TST_EQ_INT(b->cur, -5);
        sim_free(c);
    }
}

static void t_enable_reset(void)
{
    sim_ctx *c = ctx_new();
    sim_signal *clk = clock(c);
    sim_signal *d = sim_signal_new(c, NULL, "d", F("u4.0"), SIM_KIND_INPUT);
    sim_signal *en = sim_bit_new(c, NULL, "en", SIM_KIND_INPUT);
    sim_signal *rst = sim_bit_new(c, NULL, "rst", SIM_KIND_INPUT);
    sim_signal *q = sim_reg(c, NULL, "q", F("u4.0"), clk, d, en, rst, 9);
    TST_EQ_INT(q->cur, 9);                 /* reset value from the start */
    sim_force(d, 5); sim_force(en, 0);
    sim_run(c, 5);
    TST_EQ_INT(q->cur, 9);                 /* disabled: holds */
    sim_force(en, 1);
    sim_run(c, 15);
    TST_EQ_INT(q->cur, 5);
    sim_force(rst, 1); sim_force(d, 2);
    sim_run(c, 25);
    TST_EQ_INT(q->cur, 9);                 /* synchronous reset wins */
    TST_CHECK(q->area_ge > 4 * SIM_GE_DFF, "enable mux and reset flop add area");
    sim_free(c);
}

static void t_delta_chain(void)
{
    /* x -> +1 -> +1 -> ... (n adders): a change at x settles after exactly
     * n+1 delta cycles (one to update x, one per adder). */
    enum { N = 7 };
    sim_ctx *c = ctx_new();
    sim_signal *x = sim_signal_new(c, NULL, "x", F("s16.0"), SIM_KIND_INPUT);
    sim_signal *one = sim_const(c, NULL, "one", F("s16.0"), 1.0);
    sim_signal *y = x;
    for (int i = 0; i < N; i++) y = sim_add(c, NULL, "add", F("s16.0"), y, one);
    sim_run(c, 0);
    TST_EQ_INT(y->cur, N);
    uint64_t d0 = sim_get_stats(c)->deltas, e0 = sim_get_stats(c)->events;
    sim_force(x, 100);
    sim_run(c, 1);
    TST_EQ_INT(y->cur, 100 + N);
    TST_EQ_INT(sim_get_stats(c)->deltas - d0, N + 1);
    TST_EQ_INT(sim_get_stats(c)->events - e0, N + 1);
    /* Writing the same value again changes nothing and wakes nobody. */
    uint64_t r0 = sim_get_stats(c)->proc_runs;
    sim_force(x, 100);
    sim_run(c, 2);
    TST_EQ_INT(sim_get_stats(c)->proc_runs - r0, 0);
    sim_free(c);
}

static int64_t inv_fn(const int64_t *in, void *u) { (void)u; return !in[0]; }
static int64_t buf_fn(const int64_t *in, void *u) { (void)u; return in[0]; }

static void t_loop_detected(void)
{
    /* w -> inv -> y -> w oscillates: reported by name, not hung. */
    sim_ctx *c = ctx_new();
    sim_set_max_deltas(c, 50);
    sim_scope *u = sim_scope_new(c, NULL, "ring");
    sim_signal *w = sim_bit_new(c, u, "w", SIM_KIND_WIRE);
    sim_signal *y = sim_logic(c, u, "y", w->fmt, 1, &w, inv_fn, NULL, 1.0);
    sim_assign(c, w, y);
    TST_EQ_INT(sim_run(c, 100), SIM_ERR_LOOP);
    const char *e = sim_error(c);
    TST_CHECK(strstr(e, "combinational loop") != NULL, "%s", e);
    TST_CHECK(strstr(e, "top.ring.w") != NULL && strstr(e, "top.ring.y") != NULL, "%s", e);
    TST_CHECK(strchr(e, '\n') == NULL, "one line: %s", e);
    sim_free(c);

    /* A chain that settles is not a loop, even a long one. */
    c = ctx_new();
    sim_set_max_deltas(c, 50);
    sim_signal *x = sim_bit_new(c, NULL, "x", SIM_KIND_INPUT);
    sim_signal *z = x;
    for (int i = 0; i < 40; i++) z = sim_logic(c, NULL, "b", x->fmt, 1, &z, buf_fn, NULL, 1.0);
    sim_force(x, 1);
    TST_EQ_INT(sim_run(c, 10), SIM_OK);
    TST_EQ_INT(z->cur, 1);
    sim_free(c);
}

/* Independent reference for a quantized result: round a double the way the
 * format asks (the formats here are small enough that doubles are exact). */
static int ref_ovf;
static double ref_q(double v, sim_fmt f, int rnd, int sat)
{
    double s = ldexp(v, f.fbits), r;
    if (rnd == 0) r = floor(s);
    else if (rnd == 1) r = floor(s + 0.5);
    else { r = floor(s); double fr = s - r; if (fr > 0.5 || (fr == 0.5 && fmod(r, 2) != 0)) r += 1; }
    double lo = f.is_signed ? -ldexp(1, f.width - 1) : 0, hi = f.is_signed ? ldexp(1, f.width - 1) - 1 : ldexp(1, f.width) - 1;
    ref_ovf += r < lo || r > hi;
    if (sat) r = r < lo ? lo : r > hi ? hi : r;
    else { double m = ldexp(1, f.width); r = fmod(r - lo, m); if (r < 0) r += m; r += lo; }
    return ldexp(r, -f.fbits);
}

static void t_primitives_arith(void)
{
    /* add, sub, mul, shift, mux, bk over a grid of operands in mixed
     * formats, every rounding and overflow mode, against ref_q. */
    const char *fa = "s3.5", *fb = "s2.7", *fy = "s3.4";
    for (int rnd = 0; rnd < 3; rnd++) for (int sat = 0; sat < 2; sat++) {
        sim_ctx *c = ctx_new();
        sim_set_quant(c, (sim_round)rnd, sat ? SIM_OVF_SAT : SIM_OVF_WRAP);
        sim_signal *a = sim_signal_new(c, NULL, "a", F(fa), SIM_KIND_INPUT);
        sim_signal *b = sim_signal_new(c, NULL, "b", F(fb), SIM_KIND_INPUT);
        sim_signal *sel = sim_bit_new(c, NULL, "sel", SIM_KIND_INPUT);
        sim_signal *ab[2] = { a, b };
        sim_signal *add = sim_add(c, NULL, "add", F(fy), a, b);
        sim_signal *sub = sim_sub(c, NULL, "sub", F(fy), a, b);
        sim_signal *mul = sim_mul(c, NULL, "mul", F(fy), a, b);
        sim_signal *shr = sim_shift(c, NULL, "shr", F(fy), a, -3);
        sim_signal *shl = sim_shift(c, NULL, "shl", F(fy), b, 2);
        sim_signal *mux = sim_mux(c, NULL, "mux", F(fy), sel, 2, ab);
        sim_signal *bk = sim_bk(c, NULL, "bk", F(fy), sel, b);
        sim_time t = 0;
        int n = 0, add_ovf = 0, mul_ovf = 0;
        for (int64_t ra = -128; ra < 128; ra += 7) for (int64_t rb = -256; rb < 256; rb += 13) {
            int s = (int)((ra + rb) & 1);
            sim_force(a, ra); sim_force(b, rb); sim_force(sel, s);
            sim_run(c, t++);
            double va = ldexp((double)ra, -5), vb = ldexp((double)rb, -7);
            sim_fmt Y = F(fy);
            ref_ovf = 0;
            TST_NEAR(sim_fx_to_real(add->cur, Y), ref_q(va + vb, Y, rnd, sat), 0);
            add_ovf += ref_ovf; ref_ovf = 0;
            TST_NEAR(sim_fx_to_real(sub->cur, Y), ref_q(va - vb, Y, rnd, sat), 0);
            ref_ovf = 0;
            TST_NEAR(sim_fx_to_real(mul->cur, Y), ref_q(va * vb, Y, rnd, sat), 0);
            mul_ovf += ref_ovf;
            TST_NEAR(sim_fx_to_real(shr->cur, Y), ref_q(va / 8, Y, rnd, sat), 0);
            TST_NEAR(sim_fx_to_real(shl->cur, Y), ref_q(vb * 4, Y, rnd, sat), 0);
            TST_NEAR(sim_fx_to_real(mux->cur, Y), ref_q(s ? vb : va, Y, rnd, sat), 0);
            TST_NEAR(sim_fx_to_real(bk->cur, Y), s ? ref_q(vb, Y, rnd, sat) : 0.0, 0);
            n++;
        }
        TST_CHECK(n > 500, "grid too small");
        /* s3.4 holds [-4, 4): sums up to 6 and products up to 8 overflow;
         * the counters agree with the reference's count. */
        TST_CHECK(add_ovf > 0 && mul_ovf > 0, "grid reaches overflow");
        TST_EQ_INT(add->overflows, add_ovf);
        TST_EQ_INT(mul->overflows, mul_ovf);
        sim_free(c);
    }
}

static void t_wide_mul(void)
{
    /* 32x32 and 63x63-bit products are exact before quantization. */
    sim_ctx *c = ctx_new();
    sim_signal *a = sim_signal_new(c, NULL, "a", F("s32.0"), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, NULL, "b", F("s32.0"), SIM_KIND_INPUT);
    sim_signal *p = sim_mul(c, NULL, "p", F("s64.0"), a, b);
    sim_signal *hi = sim_mul(c, NULL, "hi", F("s33.0"), a, b);   /* keeps the top bits only... */
    (void)hi;
    sim_force(a, -2147483647LL); sim_force(b, 2147483647LL);
    sim_run(c, 0);
    TST_EQ_INT(p->cur, -(2147483647LL * 2147483647LL));
    sim_free(c);

    c = ctx_new();
    a = sim_signal_new(c, NULL, "a", F("s1.63"), SIM_KIND_INPUT);
    b = sim_signal_new(c, NULL, "b", F("s1.63"), SIM_KIND_INPUT);
    p = sim_mul(c, NULL, "p", F("s2.62"), a, b);
    /* (1 - 2^-63)^2 = 1 - 2^-62 + 2^-126: truncated to 62 fraction bits
     * gives 1 - 2^-62 exactly (raw 2^62 - 1). */
    sim_force(a, INT64_MAX); sim_force(b, INT64_MAX);
    sim_run(c, 0);
    TST_EQ_INT(p->cur, (int64_t)((((uint64_t)1) << 62) - 1));
    sim_free(c);
}

static void t_area_model(void)
{
    /* Element areas scale as the structures they model. */
    TST_NEAR(sim_area_add(16), 16 * SIM_GE_FA, 1e-9);
    TST_NEAR(sim_area_mul(8, 8) / sim_area_mul(4, 4), (64 * SIM_GE_AND2 + 56 * SIM_GE_FA) / (16 * SIM_GE_AND2 + 12 * SIM_GE_FA), 1e-9);
    TST_NEAR(sim_area_mux(10, 4), 30 * SIM_GE_MUX2, 1e-9);
    TST_NEAR(sim_area_reg(8, 1, 0), 8 * (SIM_GE_DFF + SIM_GE_MUX2), 1e-9);
    sim_ctx *c = ctx_new();
    sim_scope *u = sim_scope_new(c, NULL, "u");
    sim_signal *a = sim_signal_new(c, u, "a", F("s4.4"), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, u, "b", F("s4.4"), SIM_KIND_INPUT);
    sim_add(c, u, "s", F("s5.4"), a, b);
    sim_mul(c, u, "m", F("s8.8"), a, b);
    /* the array as ABC maps a signed x signed 8 x 8 product: 1.481 times
     * (docs/area.md, "Products as mapped": 568.0 GE over the array's 383.6) */
    const double ss8 = 1.481;
    /* the sum: a chain of 8 bits where both operands vary, as an 8-bit adder
     * maps (49.0 GE, scripts/add_area.sh), and a half adder for its carry
     * into the top bit; a and b each drive 10 pins a bit (the adder's 2,
     * the product's 8: 16.5 fF, 2.2 times an X1 cell's 7.5 fF), a BUF_X2
     * a bit (docs/area.md, "Buffer trees") */
    const double add9 = 49.0 + SIM_GE_HA, bufs = 16 * 1.33;   /* 1.064 um^2, to 2 places as the table */
    TST_NEAR(sim_scope_area(u), add9 + ss8 * sim_area_mul(8, 8) + bufs, 1e-3);
    TST_NEAR(sim_scope_area(sim_root(c)), sim_scope_area(u), 1e-9);
    /* a narrower product costs less: 4 fraction bits fewer, 4 sum XOR2 */
    sim_signal *m4 = sim_mul(c, u, "m4", F("s8.4"), a, b);
    TST_NEAR(m4->area_ge, ss8 * (sim_area_mul(8, 8) - 4 * SIM_GE_XOR2), 1e-9);
    /* a square (one operand twice) maps smaller: 399.0 GE over 383.6 */
    sim_signal *sq = sim_mul(c, u, "sq", F("s8.8"), a, a);
    TST_NEAR(sq->area_ge, 1.040 * sim_area_mul(8, 8), 1e-9);
    /* unsigned x unsigned at 12 bits: halfway between 8 (1.218) and 16 (1.245) */
    sim_signal *ua = sim_signal_new(c, u, "ua", F("u6.6"), SIM_KIND_INPUT);
    sim_signal *ub = sim_signal_new(c, u, "ub", F("u6.6"), SIM_KIND_INPUT);
    sim_signal *um = sim_mul(c, u, "um", F("u12.12"), ua, ub);
    TST_NEAR(um->area_ge, (1.218 + 1.245) / 2 * sim_area_mul(12, 12), 1e-9);
    sim_free(c);

    /* Rounding to nearest where bits are dropped costs an incrementer;
     * saturation where the result can exceed the output costs the clamp. */
    for (int rnd = 0; rnd < 2; rnd++) for (int sat = 0; sat < 2; sat++) {
        c = ctx_new();
        sim_set_quant(c, rnd ? SIM_RND_HALF_UP : SIM_RND_TRUNC, sat ? SIM_OVF_SAT : SIM_OVF_WRAP);
        a = sim_signal_new(c, NULL, "a", F("s4.4"), SIM_KIND_INPUT);
        b = sim_signal_new(c, NULL, "b", F("s4.4"), SIM_KIND_INPUT);
        sim_signal *m = sim_mul(c, NULL, "m", F("s5.3"), a, b);      /* drops 5 bits, 8 -> 5 integer bits */
        sim_signal *s2 = sim_add(c, NULL, "s", F("s5.4"), a, b);    /* exact: nothing to round or clamp */
        /* the array of the 16 product bits less the top 3 columns (13, 14, 15:
         * 2, 1 and 0 of its 64 partial products) and the sum XOR2 of each of
         * the 5 columns below the output, which still carry into it */
        double arr = 1.481 * (sim_area_mul(8, 8) * (64 - 3) / 64.0 - 5 * SIM_GE_XOR2);
        TST_NEAR(m->area_ge, arr + (rnd ? 8 * SIM_GE_HA : 0) + (sat ? 8 * SIM_GE_MUX2 + 3 * SIM_GE_XOR2 : 0), 1e-9);
        TST_NEAR(s2->area_ge, 49.0 + SIM_GE_HA, 1e-3);
        sim_free(c);
    }
}

/* Adders as mapped (scripts/add_area.sh's figures), the buffer trees of
 * heavy nets and the incrementers a multi-operand adder shares. */
static void t_area_adders_nets(void)
{
    /* an 8-bit chain maps to 49.0 GE (add) and 55.3 (sub); 12 bits: halfway
     * between 8 (6.125 a bit) and 16 (6.812) */
    TST_NEAR(sim_area_addsub(0, 8, 0, 0, 0), 49.0, 1e-3);
    TST_NEAR(sim_area_addsub(1, 8, 0, 0, 0), 55.336, 1e-3);
    TST_NEAR(sim_area_addsub(0, 12, 0, 0, 0), 12 * (6.125 + 6.812) / 2, 1e-9);
    /* 3 incrementer bits above, 4 negated below, the carry of 4 bits (8.7 GE) */
    TST_NEAR(sim_area_addsub(1, 8, 3, 4, 4), 55.336 + 7 * SIM_GE_HA + 8.668, 1e-3);
    /* buffer trees: the load in units of 7.5 fF (an X1 cell's at its
     * figures), a BUF_X2 (1.064 um^2) for every 3 units beyond the first */
    TST_NEAR(sim_area_buffers(0, 4), 0.0, 1e-12);                 /* 6.6 fF */
    TST_NEAR(sim_area_buffers(4, 0), 1.33, 1e-9);                  /* 7.68 fF */
    TST_NEAR(sim_area_buffers(0, 40), 3 * 1.33, 1e-9);              /* 66 fF: 8.8 units */

    sim_ctx *c = ctx_new();
    sim_scope *u = sim_scope_new(c, NULL, "u");
    sim_signal *a = sim_signal_new(c, u, "a", F("s4.4"), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, u, "b", F("s4.4"), SIM_KIND_INPUT);
    sim_signal *d = sim_signal_new(c, u, "d", F("s4.4"), SIM_KIND_INPUT);
    /* s1 = a - b: 8 chain bits, its carry into the top (s5.4) an incrementer
     * bit; s2 = s1 - d: 8 chain bits, 2 above (s6.4) */
    sim_signal *s1 = sim_sub(c, u, "s1", F("s5.4"), a, b);
    sim_signal *s2 = sim_sub(c, u, "s2", F("s6.4"), s1, d);
    TST_NEAR(s1->area_ge, 55.336 + SIM_GE_HA, 1e-3);
    TST_NEAR(s2->area_ge, 55.336 + 2 * SIM_GE_HA, 1e-3);
    /* s1's one reader is s2: one multi-operand adder, whose top bits s2's
     * incrementer makes; no net drives more than 7.5 fF (2 pins a bit) */
    TST_NEAR(sim_scope_area(u), 2 * 55.336 + 2 * SIM_GE_HA, 1e-3);
    /* a second reader: s1 is an adder of its own again */
    sim_signal *s3 = sim_add(c, u, "s3", F("s6.4"), s1, a);
    TST_NEAR(sim_scope_area(u), s1->area_ge + s2->area_ge + s3->area_ge, 1e-9);
    /* the minuend zero in the two low bits (a shifted up by 2: 2^-2 and
     * up): d's two bits there are negated (0 - d, an incrementer bit each),
     * the chain the 6 bits where both vary (2^-2 .. 2^3), 3 above (a4's
     * 2^4 and 2^5 and the carry into 2^6) */
    sim_signal *a4 = sim_shift(c, u, "a4", F("s6.4"), a, 2);
    sim_signal *n = sim_sub(c, u, "n", F("s7.4"), a4, d);
    TST_NEAR(n->area_ge, 6 * (5.750 + (6.917 - 5.750) / 2) + 2 * SIM_GE_HA + 3 * SIM_GE_HA, 1e-3);
    sim_free(c);
}

static void t_find_and_paths(void)
{
    sim_ctx *c = ctx_new();
    sim_scope *u = sim_scope_new(c, NULL, "u");
    sim_scope *v = sim_scope_new(c, u, "v");
    sim_signal *s = sim_signal_new(c, v, "sig", F("u3.0"), SIM_KIND_WIRE);
    char buf[64];
    TST_EQ_STR(sim_signal_path(s, buf, sizeof buf), "top.u.v.sig");
    TST_CHECK(sim_find(c, NULL, "u.v.sig") == s, "find by path");
    TST_CHECK(sim_find(c, u, "v.sig") == s, "find relative");
    TST_CHECK(sim_find(c, NULL, "u.x.sig") == NULL, "missing scope");
    TST_CHECK(sim_find(c, NULL, "u.v.nope") == NULL, "missing signal");
    sim_free(c);
}

static void t_overflow_settled_only(void)
{
    /* y = 8x - x in s4.15 (range [-8, 8)). The shift's output reaches the
     * subtractor one delta after x does, so when x drops from 1.1 to 0.1
     * the subtractor briefly sees 8.8 - 0.1: a glitch, not an overflow of
     * the hardware, since 7 x 0.1 fits. Only x = 1.2 (7 x 1.2 = 8.4)
     * overflows for real, once for the one time step it is computed in. */
    sim_ctx *c = ctx_new();
    sim_signal *x = sim_signal_new(c, NULL, "x", F("u1.15"), SIM_KIND_INPUT);
    sim_signal *x8 = sim_shift(c, NULL, "x8", F("u4.15"), x, 3);
    sim_signal *y = sim_sub(c, NULL, "y", F("s4.15"), x8, x);
    sim_time t = 0;
    for (int k = 0; k < 10; k++) {
        sim_force(x, sim_fx_from_real(k & 1 ? 0.1 : 1.1, x->fmt, SIM_RND_TRUNC, SIM_OVF_WRAP, NULL));
        sim_run(c, t++);
    }
    TST_EQ_INT(y->overflows, 0);
    TST_NEAR(sim_fx_to_real(y->cur, y->fmt), 7 * sim_fx_to_real(x->cur, x->fmt), 1e-12);
    sim_force(x, sim_fx_from_real(1.2, x->fmt, SIM_RND_TRUNC, SIM_OVF_WRAP, NULL));
    sim_run(c, t++);
    sim_run(c, t++);   /* nothing changes: no new count */
    TST_EQ_INT(y->overflows, 1);
    sim_free(c);
}

static void t_overflow_glitch_same_raw(void)
{
    /* y = a + b in u3.0 (range 0..7, wrap), b = x one delta late. From
     * a = 0, b = 10 (y = 10 wraps to 2: a real overflow) a step sets a = 2
     * and x = 2: the adder first sees 2 + 10 = 12, which wraps to 4, then
     * 2 + 2 = 4, in range. The settled 4 equals the glitch's wrapped raw,
     * but the last evaluation did not overflow: no count. */
    sim_ctx *c = ctx_new();
    sim_signal *a = sim_signal_new(c, NULL, "a", F("u4.0"), SIM_KIND_INPUT);
    sim_signal *x = sim_signal_new(c, NULL, "x", F("u4.0"), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, NULL, "b", F("u4.0"), SIM_KIND_WIRE);
    sim_assign(c, b, x);
    sim_signal *y = sim_add(c, NULL, "y", F("u3.0"), a, b);
    sim_run(c, 0);
    sim_force(x, 10);
    sim_run(c, 1);
    TST_EQ_INT(y->cur, 10 - 8);
    TST_EQ_INT(y->overflows, 1);
    sim_force(a, 2);
    sim_force(x, 2);
    sim_run(c, 2);
    TST_EQ_INT(y->cur, 4);
    TST_EQ_INT(y->overflows, 1);
    sim_free(c);
}

static void t_overflow_used_values(void)
{
    /* mul = 2x in s2.0 (range -2..1): x = 3 gives 6, an overflow. Its
     * readers: q <= (sel ? k : mul), q2 <= (pass ? mul : 0) and r <= mul
     * when en, all clocked. The value is used on a clock where one of them
     * takes it (sel 0, pass 1 or en 1), and discarded otherwise. Inputs
     * change between edges (times 10 i), the registers take them at 10 i
     * + 5. */
    sim_ctx *c = ctx_new();
    sim_signal *clk = clock(c);
    sim_signal *x = sim_signal_new(c, NULL, "x", F("s4.0"), SIM_KIND_INPUT);
    sim_signal *sel = sim_bit_new(c, NULL, "sel", SIM_KIND_INPUT);
    sim_signal *pass = sim_bit_new(c, NULL, "pass", SIM_KIND_INPUT);
    sim_signal *en = sim_bit_new(c, NULL, "en", SIM_KIND_INPUT);
    sim_signal *two = sim_const_raw(c, NULL, "two", F("u2.0"), 2);
    sim_signal *k = sim_const_raw(c, NULL, "k", F("s2.0"), 1);
    sim_signal *mul = sim_mul(c, NULL, "mul", F("s2.0"), x, two);
    sim_signal *in[2] = { mul, k };
    sim_signal *m = sim_mux(c, NULL, "m", F("s2.0"), sel, 2, in);
    sim_signal *q = sim_reg(c, NULL, "q", F("s2.0"), clk, m, NULL, NULL, 0);
    sim_signal *bk = sim_bk(c, NULL, "bk", F("s2.0"), pass, mul);
    sim_signal *q2 = sim_reg(c, NULL, "q2", F("s2.0"), clk, bk, NULL, NULL, 0);
    sim_signal *r = sim_reg(c, NULL, "r", F("s2.0"), clk, mul, en, NULL, 0);
    /* x, sel, pass, en; then the used and discarded counts after it */
    static const int steps[][6] = {
        { 3, 1, 0, 0, 0, 1 },   /* k selected, BK closed, r disabled: discarded */
        { 0, 1, 0, 0, 0, 1 },
        { 3, 0, 0, 0, 1, 1 },   /* the mux takes it */
        { 0, 1, 0, 0, 1, 1 },
        { 3, 1, 1, 0, 2, 1 },   /* the block key passes it */
        { 0, 1, 0, 0, 2, 1 },
        { 3, 1, 0, 1, 3, 1 },   /* r is enabled */
        { 0, 1, 0, 0, 3, 1 },
        { 3, 1, 0, 0, 3, 2 },   /* discarded again */
    };
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        sim_force(x, steps[i][0]);
        sim_force(sel, steps[i][1]);
        sim_force(pass, steps[i][2]);
        sim_force(en, steps[i][3]);
        sim_run(c, (sim_time)(10 * i));
        TST_CHECK(mul->overflows == (uint64_t)steps[i][4] && mul->ovf_discarded == (uint64_t)steps[i][5],
                  "step %zu: used %llu discarded %llu, expected %d %d", i, (unsigned long long)mul->overflows,
                  (unsigned long long)mul->ovf_discarded, steps[i][4], steps[i][5]);
        if (i == 2) {
            sim_run(c, (sim_time)(10 * i + 5));
            TST_EQ_INT(q->cur, 6 - 8);          /* the wrapped product reached q */
        }
    }
    TST_EQ_INT(q2->overflows + r->overflows + m->overflows + bk->overflows, 0);
    /* an output port's value leaves the design: used on any clock */
    sim_signal_output(mul);
    sim_force(x, 0);
    sim_run(c, 100);
    sim_force(x, 3);
    sim_run(c, 110);
    TST_CHECK(mul->overflows == 4 && mul->ovf_discarded == 2, "output: used %llu discarded %llu",
              (unsigned long long)mul->overflows, (unsigned long long)mul->ovf_discarded);
    sim_free(c);
}

/* A logic function with a result wider than the elements' outputs, that
 * counts its calls (user points at the counter). */
static int64_t lut_fn(const int64_t *in, void *u)
{
    ++*(int *)u;
    return in[0] * 37 - in[1] * 11 + (in[0] ^ in[1]) * 5;
}
static int64_t lut_fn1(const int64_t *in, void *u)
{
    int64_t two[2] = { in[0], 3 };
    return lut_fn(two, u);
}
/* The element's output: the low W bits, sign-extended or not (written out
 * here, not the kernel's). */
static int64_t low_bits(int64_t v, sim_fmt f)
{
    uint64_t m = f.width >= 64 ? UINT64_MAX : (((uint64_t)1 << f.width) - 1), b = (uint64_t)v & m;
    if (f.is_signed && (b >> (f.width - 1)) & 1) b |= ~m;
    return (int64_t)b;
}

static void t_logic_table(void)
{
    /* Logic elements with 3 and 3 + 3 input bits are tables made when the
     * simulation starts: their functions are called once per input value
     * then, never while simulating, and give what a call gives; one with
     * 9 input bits is called at each evaluation. A raw forced outside its
     * input's format is outside the table: that evaluation calls. */
    sim_ctx *c = ctx_new();
    sim_signal *x = sim_signal_new(c, NULL, "x", F("u3.0"), SIM_KIND_INPUT);
    sim_signal *z = sim_signal_new(c, NULL, "z", F("s2.1"), SIM_KIND_INPUT);
    sim_signal *w = sim_signal_new(c, NULL, "w", F("u6.0"), SIM_KIND_INPUT);
    int n1 = 0, n2 = 0, nb = 0;
    sim_signal *xz[2] = { x, z }, *xw[2] = { x, w };
    sim_signal *y1 = sim_logic(c, NULL, "y1", F("s4.0"), 1, &x, lut_fn1, &n1, 1.0);
    sim_signal *y2 = sim_logic(c, NULL, "y2", F("u5.0"), 2, xz, lut_fn, &n2, 1.0);
    sim_signal *yb = sim_logic(c, NULL, "yb", F("s6.0"), 2, xw, lut_fn, &nb, 1.0);
    TST_EQ_INT(sim_run(c, 0), SIM_OK);
    /* the reference makes no table: one call per evaluation */
    int t1 = on_reference ? 1 : 8, t2 = on_reference ? 1 : 8 * 8;
    TST_EQ_INT(n1, t1);
    TST_EQ_INT(n2, t2);
    TST_EQ_INT(nb, 1);      /* its initialization run */
    sim_time t = 1;
    int bad = 0;
    for (int64_t xv = 0; xv <= 7; xv++)
        for (int64_t zv = -4; zv <= 3; zv++) {
            int64_t wv = (xv * 8 + zv + 4) * 3 % 64;
            sim_force(x, xv); sim_force(z, zv); sim_force(w, wv);
            sim_run(c, t++);
            int dummy = 0;
            int64_t e1 = low_bits(lut_fn1((int64_t[]){ xv }, &dummy), y1->fmt);
            int64_t e2 = low_bits(lut_fn((int64_t[]){ xv, zv }, &dummy), y2->fmt);
            int64_t eb = low_bits(lut_fn((int64_t[]){ xv, wv }, &dummy), yb->fmt);
            bad += y1->cur != e1 || y2->cur != e2 || yb->cur != eb;
        }
    TST_EQ_INT(bad, 0);
    if (on_reference) { t1 = (int)sim_proc_runs(y1->driver); t2 = (int)sim_proc_runs(y2->driver); }
    TST_EQ_INT(n1, t1);
    TST_EQ_INT(n2, t2);
    TST_EQ_INT(nb, (int)sim_proc_runs(yb->driver));
    TST_CHECK(nb > 60, "the untabulated element ran: %d", nb);
    /* x = 9 does not fit u3.0: y1 and y2 call their functions. */
    sim_force(x, 9); sim_force(z, -1);
    sim_run(c, t++);
    int dummy = 0;
    TST_EQ_INT(y1->cur, low_bits(lut_fn1((int64_t[]){ 9 }, &dummy), y1->fmt));
    TST_EQ_INT(y2->cur, low_bits(lut_fn((int64_t[]){ 9, -1 }, &dummy), y2->fmt));
    TST_EQ_INT(n1, t1 + 1);
    TST_EQ_INT(n2, t2 + 1);
    sim_free(c);
}

/* ---- the reference against the fast kernel, counter by counter ---- */

/* An observer's record of a run: a hash of every signal's value at the
 * end of every time step, the steps, and the changed lists' lengths. */
typedef struct obs_rec { uint64_t hash, steps, changed; } obs_rec;

static void obs_fn(sim_ctx *c, sim_time now, void *data)
{
    obs_rec *r = data;
    uint64_t h = r->hash ^ now;
    for (uint32_t i = 0; i < sim_signal_count(c); i++) h = (h ^ (uint64_t)sim_signal_at(c, i)->cur) * 0x100000001b3ull;
    uint32_t n;
    sim_changed(c, &n);
    r->hash = h;
    r->steps++;
    r->changed += n;
}

static int64_t mix_fn(const int64_t *in, void *u) { (void)u; return in[0] * 5 + in[1] * 3 + (in[0] & 2); }
static int64_t wide_fn(const int64_t *in, void *u) { (void)u; return in[0] ^ (int64_t)((uint64_t)in[1] << 2); }

/* A design with every kind of element the kernel evaluates itself (copy,
 * add, sub, mul, mux, block key, logic both ways and tabulated, their
 * overflows, the *_X forms) and some it does not (shift), two clocks (so
 * that some time steps are not one clock edge alone), inputs forced
 * between edges and a feedback register. Runs 60 time units. */
static void mixed_run(int reference, sim_stats *st, obs_rec *rec, uint64_t *sigs, uint64_t *runs, uint32_t *nsig,
                      uint32_t *nproc)
{
    sim_ctx *c = sim_new();
    sim_set_reference(c, reference);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_signal *clk2 = sim_bit_new(c, NULL, "clk2", SIM_KIND_CLOCK);
    sim_clock(c, clk, 2, 2);
    sim_clock(c, clk2, 3, 3);
    sim_signal *a = sim_signal_new(c, NULL, "a", F("s4.2"), SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, NULL, "b", F("s3.3"), SIM_KIND_INPUT);
    sim_signal *s = sim_bit_new(c, NULL, "s", SIM_KIND_INPUT);
    sim_signal *k = sim_signal_new(c, NULL, "k", F("u2.0"), SIM_KIND_INPUT);
    sim_signal *add = sim_add(c, NULL, "add", F("s4.2"), a, b);            /* rounds b: QUANT; overflows */
    sim_signal *addx = sim_add(c, NULL, "addx", F("s6.3"), a, b);          /* exact: the _X form */
    sim_signal *sub = sim_sub(c, NULL, "sub", F("s3.1"), a, b);
    sim_signal *mul = sim_mul(c, NULL, "mul", F("s4.2"), a, b);
    sim_signal *sh = sim_shift(c, NULL, "sh", F("s6.2"), a, 1);
    sim_signal *in3[3] = { add, sub, mul };
    sim_signal *mx = sim_mux(c, NULL, "mx", F("s4.2"), k, 3, in3);         /* k = 3: no input */
    sim_signal *bk = sim_bk(c, NULL, "bk", F("s3.1"), s, mul);
    sim_signal *ab[2] = { k, s };
    sim_signal *lut = sim_logic(c, NULL, "lut", F("s4.0"), 2, ab, mix_fn, NULL, 1.0);
    sim_signal *aw[2] = { a, b };
    sim_signal *lw = sim_logic(c, NULL, "lw", F("u5.0"), 2, aw, wide_fn, NULL, 1.0);
    sim_signal *inv = sim_logic(c, NULL, "inv", s->fmt, 1, &s, inv_fn, NULL, 1.0);
    sim_signal *r = sim_reg(c, NULL, "r", F("s4.2"), clk, mx, s, NULL, 0);
    sim_signal *r2 = sim_reg(c, NULL, "r2", F("s3.1"), clk2, bk, inv, NULL, 0);
    sim_signal *acc = sim_reg(c, NULL, "acc", F("s5.2"), clk, NULL, NULL, NULL, 0);
    sim_signal *sum = sim_add(c, NULL, "sum", F("s5.2"), acc, r);
    sim_reg_connect(acc, sum);
    sim_signal *cp = sim_reg(c, NULL, "cp", F("s6.2"), clk2, sh, NULL, NULL, 0);
    (void)addx; (void)lut; (void)lw; (void)r2; (void)cp;
    obs_rec rr = { 0, 0, 0 };
    TST_EQ_INT(sim_observe(c, obs_fn, &rr, SIM_OBS_CHANGES), 0);
    for (int t = 0; t < 60; t++) {
        sim_force(a, (t * 7) % 64 - 32);
        if (t % 3 == 0) sim_force(b, (t * 5) % 64 - 32);
        sim_force(s, t % 5 < 2);
        if (t % 4 == 1) sim_force(k, (t / 4) % 4);
        TST_EQ_INT(sim_run(c, (sim_time)t), SIM_OK);
    }
    *st = *sim_get_stats(c);
    *rec = rr;
    *nsig = sim_signal_count(c);
    *nproc = sim_proc_count(c);
    for (uint32_t i = 0; i < *nsig; i++) {
        const sim_signal *x = sim_signal_at(c, i);
        sigs[3 * i] = x->changes; sigs[3 * i + 1] = x->overflows; sigs[3 * i + 2] = x->ovf_discarded;
    }
    for (uint32_t i = 0; i < *nproc; i++) runs[i] = sim_proc_runs(sim_proc_at(c, i));
    sim_free(c);
}

static void t_reference_counters(void)
{
    sim_stats s[2];
    obs_rec o[2];
    uint64_t sig[2][3 * 64], runs[2][64];
    uint32_t ns[2], np[2];
    for (int m = 0; m < 2; m++) mixed_run(m, &s[m], &o[m], sig[m], runs[m], &ns[m], &np[m]);
    TST_EQ_INT(s[1].clocks, s[0].clocks);
    TST_EQ_INT(s[1].events, s[0].events);
    TST_EQ_INT(s[1].deltas, s[0].deltas);
    TST_EQ_INT(s[1].proc_runs, s[0].proc_runs);
    TST_EQ_INT(s[1].time_steps, s[0].time_steps);
    TST_CHECK(o[1].hash == o[0].hash, "values at the ends of time steps differ");
    TST_EQ_INT(o[1].steps, o[0].steps);
    TST_EQ_INT(o[1].changed, o[0].changed);
    TST_EQ_INT(ns[1], ns[0]);
    TST_EQ_INT(np[1], np[0]);
    TST_CHECK(!memcmp(sig[0], sig[1], 3 * ns[0] * sizeof **sig), "a signal's changes or overflows differ");
    TST_CHECK(!memcmp(runs[0], runs[1], np[0] * sizeof **runs), "a process's runs differ");
    /* the run did what it is meant to: both clocks, overflows, used and discarded */
    TST_EQ_INT(s[0].clocks, 15 + 10);
    uint64_t ovf = 0, disc = 0;
    for (uint32_t i = 0; i < ns[0]; i++) { ovf += sig[0][3 * i + 1]; disc += sig[0][3 * i + 2]; }
    TST_CHECK(ovf > 0 && disc > 0, "overflows used %llu, discarded %llu", (unsigned long long)ovf,
              (unsigned long long)disc);
}

/* Every test on the fast kernel, then on its reference. */
#define RUN(fn) tst_run(on_reference ? #fn "/reference" : #fn, fn)
static void all(void)
{
    RUN(t_shift_register);
    RUN(t_swap);
    RUN(t_enable_reset);
    RUN(t_delta_chain);
    RUN(t_loop_detected);
    RUN(t_primitives_arith);
    RUN(t_wide_mul);
    RUN(t_area_model);
    RUN(t_area_adders_nets);
    RUN(t_find_and_paths);
    RUN(t_overflow_settled_only);
    RUN(t_overflow_glitch_same_raw);
    RUN(t_overflow_used_values);
    RUN(t_logic_table);
}

int main(void)
{
    all();
    on_reference = 1;
    all();
    TST_RUN(t_reference_counters);
    TST_EXIT();
}
