/* test_batch.c - the batch mode (sim/sim_batch.h) against the event-driven
 * kernel, which is its reference: the same streams through both must give
 * the same bytes in every output, clock count and overflow count.
 *
 * The span units as the scene drives them (tb_span_run_lanes against
 * tb_span_run lane by lane), on random intervals, at configurations with
 * and without overflows (a lane with one must come from the kernel); every
 * registered unit through the generic batch testbench (tb_batch.h) against
 * tb_run; and the batch's own refusals. */
#include "tests/tst.h"
#include "sim/sim_batch.h"
#include "sim/sim_prim.h"
#include "testbench/tb.h"
#include "testbench/study/tb_span.h"
#include "testbench/tb_batch.h"

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t rnd(void)
{
    rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
    return rng;
}
static double unif(void) { return (double)(rnd() >> 11) * 0x1p-53; }

/* A random stream of intervals a scene could give: n <= L pixels with
 * n - 1 <= dv <= L, nodes in [0, hi]. */
static tb_span_item *random_items(size_t n, int L, double hi)
{
    tb_span_item *it = calloc(n ? n : 1, sizeof *it);
    for (size_t i = 0; i < n; i++) {
        it[i].n = 1 + (int)(rnd() % (uint64_t)L);
        int lo = it[i].n - 1 > 1 ? it[i].n - 1 : 1;
        it[i].dv = lo + (int)(rnd() % (uint64_t)(L - lo + 1));
        for (int k = 0; k < 4; k++) it[i].node[k] = hi * unif();
        it[i].deg = 2 + (int)(rnd() & 1);
    }
    return it;
}

/* Lanes of random streams through unit `name` with the given --fmt
 * overrides, batch against tb_span_run; counts lanes the batch gave and
 * lanes that overflowed. */
static void span_case_ovf(const char *name, int L, const char *sched, const char *fmt, double hi,
                          size_t *batched, size_t *fell_back, size_t *overflowed)
{
    const unit_desc *u = unit_find(name);
    TST_CHECK(u != NULL, "%s", name);
    if (!u) return;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.L = L;
    for (int s = 0; s < u->nsched; s++) if (!strcmp(u->sched[s].name, sched)) cfg.schedule = s;
    unit_fmts fm;
    char err[300];
    const char *ov[1] = { fmt };
    TST_CHECK(tb_formats(u, &cfg, ov, fmt ? 1 : 0, &fm, err, sizeof err) == 0, "%s", err);
    enum { N = 8 };   /* a multiple of 4: the vector loops apply when on */
    tb_span_lane lanes[N];
    tb_span_item *items[N];
    double *pix[N];
    memset(lanes, 0, sizeof lanes);
    for (int k = 0; k < N; k++) {
        size_t ni = k == 3 ? 0 : (size_t)(rnd() % 40) + 1;   /* lane 3: an empty stream */
        items[k] = random_items(ni, L, hi);
        pix[k] = calloc(ni * (size_t)L + 1, sizeof *pix[k]);
        lanes[k] = (tb_span_lane){ .items = items[k], .nitems = ni, .pix = pix[k] };
    }
    tb_span_run_lanes(u, &cfg, &fm, lanes, N, 1);
    for (int k = 0; k < N; k++) {
        size_t np = 0;
        for (size_t i = 0; i < lanes[k].nitems; i++) np += (size_t)items[k][i].n;
        double *ref = calloc(np + 1, sizeof *ref);
        tb_span_stats st;
        char e2[300] = "";
        int rc = tb_span_run(u, &cfg, &fm, items[k], lanes[k].nitems, ref, &st, NULL, e2, sizeof e2);
        TST_EQ_INT(lanes[k].rc, rc);
        TST_EQ_STR(lanes[k].err, rc == TB_OK ? lanes[k].err : e2);
        TST_CHECK(!memcmp(ref, pix[k], np * sizeof *ref), "%s %s lane %d: pixels differ", name, sched, k);
        TST_EQ_INT(lanes[k].st.clocks, st.clocks);
        TST_EQ_INT(lanes[k].st.pixels, st.pixels);
        TST_EQ_INT(lanes[k].st.items, st.items);
        TST_EQ_INT(lanes[k].st.items_deg2, st.items_deg2);
        TST_EQ_INT(lanes[k].st.overflows, st.overflows);
        TST_CHECK(lanes[k].st.area_ge == st.area_ge, "%s lane %d area", name, k);
        if (lanes[k].nitems) { *batched += (size_t)lanes[k].batched; *fell_back += (size_t)!lanes[k].batched; }
        if (lanes[k].batched && st.overflows) ++*overflowed;
        free(ref);
        free(items[k]);
        free(pix[k]);
    }
}

static void span_case(const char *name, int L, const char *sched, const char *fmt, double hi,
                      size_t *batched, size_t *fell_back)
{
    size_t ovf = 0;
    span_case_ovf(name, L, sched, fmt, hi, batched, fell_back, &ovf);
}

static void t_span_lanes_equal_kernel(void)
{
    static const char *const units[] = { "span1", "span2", "span3", "span23" };
    static const char *const scheds[] = { "paper", "mac", "pipe" };
    size_t batched = 0, fell = 0;
    for (int i = 0; i < 4; i++)
        for (int s = 0; s < 3; s++) {
            const unit_desc *u = unit_find(units[i]);
            int has = 0;
            for (int k = 0; u && k < u->nsched; k++) has |= !strcmp(u->sched[k].name, scheds[s]);
            if (!has) continue;
            /* the vector loops the CPU has, 8 and 4 lanes wide in turns,
             * and the scalar ones */
            sim_batch_vector((i + s) % 2 ? 4 : 8);
            span_case(units[i], 8, scheds[s], NULL, 1.0, &batched, &fell);
            sim_batch_vector(0);
            span_case(units[i], 5, scheds[s], NULL, 1.0, &batched, &fell);
            sim_batch_vector(8);
        }
    /* every default lane in [0, 1] is the batch's: no overflow there */
    TST_EQ_INT(fell, 0);
    TST_CHECK(batched > 50, "%zu lanes batched", batched);
}

static void t_span_overflow_on_lanes(void)
{
    /* A = 8 da in s3.13 (|A| < 4) overflows for steep intervals: those
     * lanes stay on the batch, with the kernel's counts (span_case holds
     * each lane's to tb_span_run's). */
    size_t batched = 0, fell = 0, ovf = 0;
    span_case_ovf("span3", 8, "paper", "a=s3.13", 1.0, &batched, &fell, &ovf);
    span_case_ovf("span23", 8, "mac", "a=s3.13", 1.0, &batched, &fell, &ovf);
    sim_batch_vector(0);   /* the scalar loops note their overflows too */
    span_case_ovf("span2", 8, "pipe", "a=s3.13", 1.0, &batched, &fell, &ovf);
    sim_batch_vector(8);
    TST_CHECK(ovf > 0, "no lane overflowed (%zu batched)", batched);
    TST_EQ_INT(fell, 0);
}

/* Every registered unit, its default configuration, random stimulus
 * (the float reference's vectors) split into lanes: the batch testbench
 * against tb_run on each lane's vectors alone. */
static void t_units_lanes_equal_kernel(void)
{
    size_t tried = 0, refused = 0;
    uint64_t in_ovf = 0;
    /* 4 lanes (a multiple of 4: the vector loops apply), then 70 (a whole
     * 64-lane word and a part of one: the masks of several words) */
    enum { MAXL = 70 };
    for (size_t ui = 0; ui < 2 * unit_count(); ui++) {
        const unit_desc *u = unit_at(ui % unit_count());
        const int NL = ui < unit_count() ? 4 : MAXL;
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        unit_fmts fm;
        char err[600];
        if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); continue; }
        vec_set vs[MAXL];
        tb_batch_lane lanes[MAXL];
        memset(lanes, 0, sizeof lanes);
        int ok = 1;
        for (int k = 0; k < NL && ok; k++) {
            size_t n = 3 + (size_t)(k % 4) * 3;   /* lanes that end at different clocks */
            if (tb_make_vectors(u, &cfg, n, 11 + (uint64_t)k, &vs[k], err, sizeof err)) {
                TST_CHECK(0, "%s: %s", u->name, err);
                ok = 0;
                while (k--) vec_set_free(&vs[k]);
                break;
            }
            lanes[k].vs = &vs[k];
            /* lanes 1, 5, ...: an input far out of its format's range
             * (an input overflow, counted by the driver) */
            if (k % 4 == 1) vec_row(&vs[k], 1)[0] = 1e12;
        }
        if (!ok) continue;
        int rc = tb_batch_run(u, &cfg, &fm, lanes, NL, err, sizeof err);
        tried++;
        if (rc == TB_UNSUPPORTED) { refused++; TST_CHECK(err[0], "%s: refused without a reason", u->name); }
        else TST_EQ_INT(rc, TB_OK);
        for (int k = 0; k < NL; k++) {
            tb_result r;
            char e2[600];
            int rr = tb_run(u, &cfg, &fm, &vs[k], NULL, &r, e2, sizeof e2);
            TST_EQ_INT(rr, TB_OK);
            if (rc == TB_OK && rr == TB_OK) {
                size_t nv = vs[k].n_rows * (size_t)r.beats * (size_t)r.n_out;
                size_t nb = vs[k].n_rows * (size_t)r.beats;
                TST_CHECK(!memcmp(r.raw, lanes[k].raw, nv * sizeof *r.raw), "%s lane %d: outputs differ", u->name, k);
                TST_CHECK(!memcmp(r.beat_cycle, lanes[k].beat_cycle, nb * sizeof *r.beat_cycle),
                          "%s lane %d: beat cycles differ", u->name, k);
                TST_EQ_INT(lanes[k].clocks, r.stats.clocks);
                /* the unit's own overflows (tb_run adds the inputs') */
                TST_EQ_INT(lanes[k].overflows, r.overflows - r.in_overflows);
                TST_EQ_INT(lanes[k].in_overflows, r.in_overflows);
                in_ovf += lanes[k].in_overflows;
            }
            if (rr == TB_OK) tb_result_free(&r);
            free(lanes[k].raw);
            free(lanes[k].beat_cycle);
            vec_set_free(&vs[k]);
        }
    }
    TST_CHECK(tried == 2 * unit_count(), "%zu of %zu", tried, 2 * unit_count());
    /* the units built of primitives only: all but the BRDF table unit */
    TST_CHECK(refused <= 2, "%zu units refused", refused);
    TST_CHECK(in_ovf > 0, "no input overflowed");
}

static void t_refusals(void)
{
    char err[300];
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_fmt f = { .is_signed = 1, .ibits = 4, .fbits = 4, .width = 8 };
    sim_signal *x = sim_signal_new(c, NULL, "x", f, SIM_KIND_INPUT);
    sim_signal *w = sim_signal_new(c, NULL, "w", f, SIM_KIND_WIRE);
    sim_signal *y = sim_add(c, NULL, "y", f, x, w);
    sim_assign(c, w, y);   /* y = x + y: a loop */
    TST_CHECK(sim_batch_new(c, clk, 4, err, sizeof err) == NULL, "loop accepted");
    TST_CHECK(strstr(err, "loop") != NULL, "%s", err);
    sim_free(c);

    c = sim_new();
    clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    x = sim_signal_new(c, NULL, "x", f, SIM_KIND_INPUT);
    sim_reg(c, NULL, "r", f, clk, x, NULL, NULL, 0);
    sim_batch *b = sim_batch_new(c, clk, 0, err, sizeof err);
    TST_CHECK(b == NULL, "0 lanes accepted");
    b = sim_batch_new(c, clk, 2, err, sizeof err);
    TST_CHECK(b != NULL, "%s", err);
    if (b) {
        TST_EQ_INT(sim_batch_set(b, sim_find(c, NULL, "r"), 0, 1), -1);   /* a register is no input */
        TST_EQ_INT(sim_batch_set(b, x, 2, 1), -1);                       /* no lane 2 */
        sim_batch_free(b);
    }
    sim_signal *other = sim_bit_new(c, NULL, "clk2", SIM_KIND_CLOCK);
    sim_reg(c, NULL, "r2", f, other, x, NULL, NULL, 0);
    TST_CHECK(sim_batch_new(c, clk, 2, err, sizeof err) == NULL, "second clock accepted");
    sim_free(c);
}

/* A small design by hand: lanes that differ only in their inputs give the
 * values computed here from the formulas, edge by edge. y = r + 3x/4
 * (s4.4, wrap), r <= y each rising edge. */
static void t_accumulator_by_hand(void)
{
    char err[300];
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_fmt f = { .is_signed = 1, .ibits = 4, .fbits = 4, .width = 8 };
    sim_signal *x = sim_signal_new(c, NULL, "x", f, SIM_KIND_INPUT);
    sim_signal *k = sim_const(c, NULL, "k", f, 0.75);
    sim_signal *m = sim_mul(c, NULL, "m", f, x, k);
    sim_signal *r = sim_reg(c, NULL, "r", f, clk, NULL, NULL, NULL, 0);
    sim_signal *y = sim_add(c, NULL, "y", f, r, m);
    sim_reg_connect(r, y);
    sim_batch *b = sim_batch_new(c, clk, 3, err, sizeof err);
    TST_CHECK(b != NULL, "%s", err);
    if (!b) { sim_free(c); return; }
    int64_t xs[3] = { 16, -8, 5 };   /* 1.0, -0.5, 0.3125 */
    for (uint32_t l = 0; l < 3; l++) sim_batch_set(b, x, l, xs[l]);
    sim_batch_start(b);
    int64_t acc[3] = { 0, 0, 0 };
    int wrapped = 0;
    for (int e = 0; e < 12; e++) {
        for (uint32_t l = 0; l < 3; l++) {
            int64_t mm = (xs[l] * 12) >> 4;   /* 0.75 = 12/16, truncated */
            int64_t yy = acc[l] + mm;
            int64_t yw = (int64_t)(int8_t)(uint8_t)yy;   /* wrap to 8 bits */
            wrapped |= (l == 0 && yw != yy);
            TST_EQ_INT(sim_batch_val(b, y)[l], yw);
            acc[l] = yw;
        }
        sim_batch_cycle(b);
    }
    TST_CHECK(wrapped, "lane 0 never wrapped");
    TST_CHECK(sim_batch_overflowed(b, 0), "lane 0's wrap not flagged");
    TST_CHECK(!sim_batch_overflowed(b, 1) && !sim_batch_overflowed(b, 2), "lanes 1, 2 never overflow");
    sim_batch_free(b);
    sim_free(c);
}

/* A testbench that marks what it writes (sim_batch_mark): an input
 * written without a mark keeps its value over the edges until marked;
 * sim_batch_set needs no mark. */
static void t_marked_inputs(void)
{
    char err[300];
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_fmt f = { .is_signed = 1, .ibits = 8, .fbits = 0, .width = 8 };
    sim_signal *x = sim_signal_new(c, NULL, "x", f, SIM_KIND_INPUT);
    sim_signal *w = sim_signal_new(c, NULL, "w", f, SIM_KIND_INPUT);
    sim_signal *r = sim_reg(c, NULL, "r", f, clk, x, NULL, NULL, 0);
    sim_batch *b = sim_batch_new(c, clk, 2, err, sizeof err);
    TST_CHECK(b != NULL, "%s", err);
    if (!b) { sim_free(c); return; }
    int64_t *nx = sim_batch_next(b, x), *nw = sim_batch_next(b, w);
    nx[0] = 3; nx[1] = 4;
    sim_batch_start(b);                         /* the start takes every input */
    TST_EQ_INT(sim_batch_val(b, x)[1], 4);
    nx[1] = 7;
    sim_batch_mark(b, x);
    sim_batch_cycle(b);                         /* marked: taken, r sampled the 4 before it */
    TST_EQ_INT(sim_batch_val(b, x)[1], 7);
    TST_EQ_INT(sim_batch_val(b, r)[1], 4);
    TST_EQ_INT(sim_batch_changed(b, x)[0], 2);  /* lane 1 alone */
    nx[0] = 9;
    nw[1] = 5;
    sim_batch_mark(b, w);
    sim_batch_cycle(b);                         /* x unmarked: held */
    TST_EQ_INT(sim_batch_val(b, x)[0], 3);
    TST_EQ_INT(sim_batch_val(b, w)[1], 5);
    TST_EQ_INT(sim_batch_changed(b, x)[0], 0);
    sim_batch_cycle(b);
    TST_EQ_INT(sim_batch_val(b, x)[0], 3);
    sim_batch_set(b, x, 1, -2);                 /* a set is marked: both pending values go */
    sim_batch_cycle(b);
    TST_EQ_INT(sim_batch_val(b, x)[0], 9);
    TST_EQ_INT(sim_batch_val(b, x)[1], -2);
    TST_EQ_INT(sim_batch_changed(b, x)[0], 3);
    TST_EQ_INT(sim_batch_val(b, r)[0], 3);
    sim_batch_free(b);
    sim_free(c);
}

/* Registers reading registers, lane by lane against the hand formula, in
 * two designs (a ring anywhere makes the batch update every register
 * through a copy, so each case has its own): a chain built first stage
 * first (q1 <= x, q2 <= q1, q3 <= q2), where an update in place in that
 * order would give q3 = x at once, and a ring (r1 <= r2, r2 <= r1, reset
 * to 5 and 9) whose values swap every edge, where an update in place in
 * any order would make them equal. */
enum { RR_LANES = 70 };   /* a whole 64-lane word and a part of one */
static void register_case(int ring)
{
    char err[300];
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_fmt f = { .is_signed = 1, .ibits = 8, .fbits = 0, .width = 8 };
    sim_fmt u1 = { .is_signed = 0, .ibits = 1, .fbits = 0, .width = 1 };
    sim_signal *x = sim_signal_new(c, NULL, "x", f, SIM_KIND_INPUT);
    sim_signal *rs = sim_signal_new(c, NULL, "rs", u1, SIM_KIND_INPUT);
    sim_signal *q[3] = { NULL, NULL, NULL }, *r1 = NULL, *r2 = NULL;
    if (!ring) {
        for (int i = 0; i < 3; i++) {
            char nm[4] = { 'q', (char)('1' + i), 0, 0 };
            q[i] = sim_reg(c, NULL, nm, f, clk, i ? q[i - 1] : x, NULL, NULL, 0);
        }
    } else {
        r1 = sim_reg(c, NULL, "r1", f, clk, NULL, NULL, rs, 5);
        r2 = sim_reg(c, NULL, "r2", f, clk, r1, NULL, rs, 9);
        sim_reg_connect(r1, r2);
    }
    sim_batch *b = sim_batch_new(c, clk, RR_LANES, err, sizeof err);
    TST_CHECK(b != NULL, "%s", err);
    if (!b) { sim_free(c); return; }
    int64_t *nx = sim_batch_next(b, x), *nrs = sim_batch_next(b, rs);
    for (uint32_t l = 0; l < RR_LANES; l++) { nx[l] = 0; nrs[l] = 1; }
    sim_batch_start(b);
    /* set at iteration e, taken at edge e: x = (7e + l) mod 100, and the
     * ring's reset high at e = 0 only (lane 3: up to e = 2) */
    int bad = 0;
    for (int e = 0; e < 12 && !bad; e++) {
        for (uint32_t l = 0; l < RR_LANES; l++) {
            nx[l] = (7 * e + (int64_t)l) % 100;
            nrs[l] = e < (l == 3 ? 3 : 1);
        }
        sim_batch_cycle(b);
        for (uint32_t l = 0; l < RR_LANES && !bad; l++) {
            if (!ring) {
                /* after edge e, q1 holds what x was before it: the value
                 * set at e - 1 (0 from the start); q2 and q3 the two before */
                for (int d = 0; d < 3 && !bad; d++) {
                    int64_t want = e - 1 - d >= 0 ? (7 * (e - 1 - d) + (int64_t)l) % 100 : 0;
                    bad = sim_batch_val(b, q[d])[l] != want;
                    TST_CHECK(!bad, "chain, edge %d lane %u: q%d = %lld, want %lld", e, l, d + 1,
                              (long long)sim_batch_val(b, q[d])[l], (long long)want);
                }
                continue;
            }
            /* rs before edge e is what was set at e - 1 (high from the
             * start before edge 0): the last reset edge is 1 (lane 3: 3),
             * and the ring swaps on every edge after it */
            int last_rst = l == 3 ? 3 : 1, since = e - last_rst;
            int64_t w1 = e <= last_rst ? 5 : (since % 2 ? 9 : 5);
            int64_t w2 = e <= last_rst ? 9 : (since % 2 ? 5 : 9);
            bad = sim_batch_val(b, r1)[l] != w1 || sim_batch_val(b, r2)[l] != w2;
            TST_CHECK(!bad, "ring, edge %d lane %u: %lld %lld, want %lld %lld", e, l,
                      (long long)sim_batch_val(b, r1)[l], (long long)sim_batch_val(b, r2)[l],
                      (long long)w1, (long long)w2);
        }
    }
    sim_batch_free(b);
    sim_free(c);
}

/* The vector loops against the scalar ones (tests above hold the scalar
 * ones to the kernel): a design with every element kind they cover, wide
 * formats (products up to 2^59, a 64-bit product's high halves in play),
 * fraction bits that differ between operands and outputs, half-up and
 * truncating rounding, wrapping and saturation, and values that overflow
 * now and then (those groups of four lanes take the scalar loop). Some
 * lanes hold their inputs for a few edges, so that the element masks are
 * partial, and on some edges most lanes do (the loops for a few lanes). Every signal in every lane at every edge, and the overflow
 * flags, must be the same. */
static int64_t lg3(const int64_t *in, void *u) { (void)u; return (in[0] * 3 + in[1] * 5 + in[2]) & 7; }
/* small tables (3 and 4 input bits: held in registers by the vector
 * loops), with negative entries, one wrapped into its output's width */
static int64_t lg_small(const int64_t *in, void *u) { (void)u; return in[0] * 5 - in[1] * 7 - 3; }
static int64_t lg_wide(const int64_t *in, void *u) { (void)u; return (in[0] - 4) * 100000 + in[1]; }
static int64_t lg_one(const int64_t *in, void *u) { (void)u; return in[0] * 3 - 11; }

static int vector_run(sim_round rm, sim_ovf om, uint32_t lanes, uint32_t vec, int64_t *trace, unsigned char *ovf,
                      int edges, uint32_t *nsig)
{
    char err[300];
    sim_batch_vector(vec);
    sim_ctx *c = sim_new();
    sim_set_quant(c, rm, om);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
#define F(sg, i, f) ((sim_fmt){ .is_signed = (sg), .ibits = (i), .fbits = (f), .width = (i) + (f) })
    sim_signal *x = sim_signal_new(c, NULL, "x", F(1, 30, 10), SIM_KIND_INPUT);
    sim_signal *w = sim_signal_new(c, NULL, "w", F(1, 12, 8), SIM_KIND_INPUT);
    sim_signal *sl = sim_signal_new(c, NULL, "s", F(0, 2, 0), SIM_KIND_INPUT);
    sim_signal *en = sim_signal_new(c, NULL, "e", F(0, 1, 0), SIM_KIND_INPUT);
    sim_signal *g = sim_signal_new(c, NULL, "g", F(0, 3, 0), SIM_KIND_INPUT);
    sim_signal *m = sim_mul(c, NULL, "m", F(1, 36, 6), x, w);         /* k = 12 */
    sim_signal *a = sim_add(c, NULL, "a", F(1, 20, 12), x, w);        /* wider fraction than both */
    sim_signal *d = sim_sub(c, NULL, "d", F(1, 24, 4), x, w);         /* k = 6 */
    sim_signal *sh = sim_shift(c, NULL, "sh", F(1, 10, 14), w, -3);
    sim_signal *mi[2] = { x, a };
    sim_signal *mx = sim_mux(c, NULL, "mx", F(1, 24, 9), sl, 2, mi); /* k = 1 and 3; s = 2, 3: 0 */
    sim_signal *mi3[3] = { x, a, w };
    sim_signal *mx3 = sim_mux(c, NULL, "mx3", F(1, 24, 8), sl, 3, mi3);   /* k = 2, 4, 0; s = 3: 0 */
    sim_signal *bk = sim_bk(c, NULL, "bk", F(1, 28, 6), en, x);
    sim_signal *li[3] = { sl, en, g };
    sim_signal *t = sim_logic(c, NULL, "t", F(0, 3, 0), 3, li, lg3, NULL, 1);
    sim_signal *li3[2] = { sl, en }, *li4[2] = { g, en };
    sim_signal *t3 = sim_logic(c, NULL, "t3", F(1, 4, 0), 2, li3, lg_small, NULL, 1);
    sim_signal *t4 = sim_logic(c, NULL, "t4", F(1, 21, 0), 2, li4, lg_wide, NULL, 1);
    sim_signal *t1 = sim_logic(c, NULL, "t1", F(1, 5, 0), 1, &g, lg_one, NULL, 1);
    sim_signal *cp = sim_signal_new(c, NULL, "cp", F(1, 36, 2), SIM_KIND_WIRE);
    sim_assign(c, cp, m);
    sim_signal *r1 = sim_reg(c, NULL, "r1", F(1, 30, 10), clk, x, en, NULL, 0);
    sim_signal *mj[2] = { x, r1 };
    sim_signal *mx2 = sim_mux(c, NULL, "mx2", F(1, 24, 10), sl, 2, mj);   /* no shifts; wide x overflows */
    sim_signal *r2 = sim_reg(c, NULL, "r2", F(1, 36, 4), clk, m, NULL, NULL, 0);
    sim_signal *r3 = sim_reg(c, NULL, "r3", F(1, 30, 9), clk, mx, NULL, en, 3);
    sim_signal *y = sim_add(c, NULL, "y", F(1, 40, 8), r2, r1);
    sim_signal *z = sim_mul(c, NULL, "z", F(1, 20, 4), r3, t);
#undef F
    (void)d; (void)sh; (void)bk; (void)cp; (void)y; (void)z; (void)t3; (void)t4; (void)t1; (void)mx2; (void)mx3;
    sim_batch *b = sim_batch_new(c, clk, lanes, err, sizeof err);
    TST_CHECK(b != NULL, "%s", err);
    if (!b) { sim_free(c); return -1; }
    *nsig = sim_signal_count(c);
    uint64_t st = 0x243f6a8885a308d3ull;   /* the same stimuli in both runs */
#define RND() (st ^= st << 13, st ^= st >> 7, st ^= st << 17, st)
    int64_t *in[5] = { sim_batch_next(b, x), sim_batch_next(b, w), sim_batch_next(b, sl), sim_batch_next(b, en),
                       sim_batch_next(b, g) };
    for (int e = 0; e <= edges; e++) {
        /* every fourth edge, few lanes change (one in sixteen): the
         * elements' masks are sparse (the loops for a few lanes) */
        int sparse = e % 4 == 2;
        for (uint32_t l = 0; l < lanes; l++) {
            if (e && (sparse ? RND() % 16 != 0 : (RND() % 3) == 0)) continue;   /* this lane holds its inputs */
            uint64_t r = RND();
            /* lanes 3, 7, ...: now and then an x whose product overflows
             * m (on the sparse edges more often) */
            in[0][l] = l % 4 == 3 && r % (sparse ? 4 : 17) == 0 ? (int64_t)(RND() >> 25) - ((int64_t)1 << 38)
                                                 : (int64_t)(r % 2000001) - 1000000;
            in[1][l] = (int64_t)(RND() % 1048575) - 524287;
            in[2][l] = (int64_t)(RND() % 4);
            in[3][l] = (int64_t)(RND() % 2);
            in[4][l] = (int64_t)(RND() % 8);
        }
        if (!e) sim_batch_start(b);
        else sim_batch_cycle(b);
        for (uint32_t i = 0; i < *nsig; i++) {
            const sim_signal *si = sim_signal_at(c, i);
            const int64_t *v = sim_batch_val(b, si);
            memcpy(trace + ((size_t)e * *nsig + i) * lanes, v, lanes * sizeof *trace);
            if (!e) continue;
            const int64_t *was = trace + ((size_t)(e - 1) * *nsig + i) * lanes;
            /* the lanes the edge changed s in, against the values before
             * and after it; a signal said uniform holds one value */
            uint64_t want = 0, got = sim_batch_changed(b, si)[0];
            int same = 1;
            for (uint32_t l = 0; l < lanes; l++) { want |= (uint64_t)(v[l] != was[l]) << l; same &= v[l] == v[0]; }
            TST_CHECK(got == want, "edge %d, %s: changed in lanes %llx, want %llx", e, si->name,
                      (unsigned long long)got, (unsigned long long)want);
            TST_CHECK(same || !sim_batch_uniform(b, si), "edge %d, %s: said uniform", e, si->name);
        }
    }
#undef RND
    for (uint32_t l = 0; l < lanes; l++) ovf[l] = (unsigned char)sim_batch_overflowed(b, l);
    uint64_t groups, fell;
    sim_batch_vector_stats(b, &groups, &fell);
    if (!vec) TST_CHECK(groups == 0 && fell == 0, "scalar run: %llu vector groups", (unsigned long long)groups);
    /* the vector loops did the work: some lanes' overflows send a few
     * groups to the scalar loop, the rest stay */
    else TST_CHECK(groups > 500 && fell > 0 && fell * 20 < groups, "%u lanes: %llu groups, %llu handed back", lanes,
                   (unsigned long long)groups, (unsigned long long)fell);
    sim_batch_free(b);
    sim_free(c);
    return 0;
}

static void t_vector_loops_equal_scalar(void)
{
    uint32_t widest = sim_batch_vector(8);
    if (!widest) TST_SKIP("no vector loops here (a CPU without AVX2, or a build without them): the scalar loops only");
    enum { EDGES = 60, MAXL = 64, MAXSIG = 32 };
    static const uint32_t lanes_of[] = { 4, 8, 24, 64 };
    int64_t *tr[2];
    tr[0] = malloc((size_t)(EDGES + 1) * MAXSIG * MAXL * sizeof *tr[0]);
    tr[1] = malloc((size_t)(EDGES + 1) * MAXSIG * MAXL * sizeof *tr[1]);
    int any_ovf = 0, any_clean = 0;
    /* each width the CPU has: AVX2 (4), AVX-512 (8; a batch of 4 lanes
     * takes AVX2) */
    for (uint32_t vw = 4; vw <= widest; vw *= 2)
        for (int mode = 0; mode < 2; mode++)
            for (int li = 0; li < 4; li++) {
                uint32_t L = lanes_of[li], ns[2] = { 0, 0 };
                unsigned char of[2][MAXL];
                sim_round rm = mode ? SIM_RND_HALF_UP : SIM_RND_TRUNC;
                sim_ovf om = mode ? SIM_OVF_SAT : SIM_OVF_WRAP;
                if (vector_run(rm, om, L, 0, tr[0], of[0], EDGES, &ns[0])
                    || vector_run(rm, om, L, vw, tr[1], of[1], EDGES, &ns[1]))
                    break;
                TST_EQ_INT(ns[0], ns[1]);
                TST_CHECK(ns[0] <= MAXSIG, "%u signals", ns[0]);
                size_t n = (size_t)(EDGES + 1) * ns[0] * L, k = 0;
                while (k < n && tr[0][k] == tr[1][k]) k++;
                TST_CHECK(k == n, "width %u, mode %d, %u lanes: edge %zu, signal %zu, lane %zu: scalar %lld, vector %lld",
                          vw, mode, L, k / L / ns[0], k / L % ns[0], k % L, (long long)(k < n ? tr[0][k] : 0),
                          (long long)(k < n ? tr[1][k] : 0));
                TST_CHECK(!memcmp(of[0], of[1], L), "width %u, mode %d, %u lanes: overflow flags differ", vw, mode, L);
                for (uint32_t l = 0; l < L; l++) { any_ovf |= of[0][l]; any_clean |= !of[0][l]; }
            }
    sim_batch_vector(8);
    /* both kinds of lane were there: ones with an overflow (the scalar
     * fallback ran) and ones without */
    TST_CHECK(any_ovf && any_clean, "overflowed lanes %d, clean lanes %d", any_ovf, any_clean);
    free(tr[0]);
    free(tr[1]);
}

static void t_register_chain(void) { register_case(0); }
static void t_register_ring(void) { register_case(1); }

int main(void)
{
    TST_RUN(t_accumulator_by_hand);
    TST_RUN(t_register_chain);
    TST_RUN(t_register_ring);
    TST_RUN(t_refusals);
    TST_RUN(t_marked_inputs);
    TST_RUN(t_vector_loops_equal_scalar);
    TST_RUN(t_span_lanes_equal_kernel);
    TST_RUN(t_span_overflow_on_lanes);
    TST_RUN(t_units_lanes_equal_kernel);
    TST_EXIT();
}
