/* test_observe.c - what the kernel offers besides simulating: observers
 * called at the end of every time step with the signals that changed,
 * elaboration errors (two drivers on one wire, a logic element with too
 * many inputs) reported before anything runs, time steps counted once per
 * time, and iteration over processes. */
#include "tests/tst.h"
#include "sim/sim.h"
#include "sim/sim_prim.h"

static sim_fmt F(const char *s)
{
    sim_fmt f;
    char err[128];
    if (sim_fmt_parse(s, &f, err, sizeof err)) { printf("  bad test format %s\n", s); abort(); }
    return f;
}

/* What an observer saw: per call, the time and the changed signals. */
enum { MAXCALLS = 64, MAXCHG = 8 };
typedef struct seen {
    int        ncalls;
    sim_time   t[MAXCALLS];
    int        nchg[MAXCALLS];
    const sim_signal *chg[MAXCALLS][MAXCHG];
    int        tag;        /* for the order of two observers */
    int       *order, *norder;
} seen;

static void record(sim_ctx *c, sim_time now, void *data)
{
    seen *s = data;
    if (s->order) s->order[(*s->norder)++] = s->tag;
    if (s->ncalls == MAXCALLS) return;
    int k = s->ncalls++;
    s->t[k] = now;
    TST_EQ_INT(now, sim_now(c));
    uint32_t n;
    sim_signal *const *d = sim_changed(c, &n);
    s->nchg[k] = (int)n;
    for (uint32_t i = 0; i < n && i < MAXCHG; i++) s->chg[k][i] = d[i];
}

/* A 4-bit counter q <= q + 1 on a clock of period 10 (rising at 5, 15..). */
typedef struct counter { sim_ctx *c; sim_signal *clk, *one, *q, *n; } counter;

static counter counter_new(void)
{
    counter k;
    k.c = sim_new();
    k.clk = sim_bit_new(k.c, NULL, "clk", SIM_KIND_CLOCK);
    k.one = sim_const_raw(k.c, NULL, "one", F("u4.0"), 1);
    k.q = sim_reg(k.c, NULL, "q", F("u4.0"), k.clk, NULL, NULL, NULL, 0);
    k.n = sim_add(k.c, NULL, "n", F("u4.0"), k.q, k.one);
    sim_reg_connect(k.q, k.n);
    sim_clock(k.c, k.clk, 5, 5);
    return k;
}

static void t_observer_per_step(void)
{
    /* Expected, from the design: at time 0 the initialization computes
     * n = 0 + 1; at each rising edge (5, 15, ...) clk rises, q takes n,
     * n follows, in that order; at each falling edge only clk changes. */
    counter k = counter_new();
    static seen s;
    memset(&s, 0, sizeof s);
    TST_EQ_INT(sim_observe(k.c, record, &s, SIM_OBS_CHANGES), 0);
    TST_EQ_INT(sim_run(k.c, 42), SIM_OK);
    TST_EQ_INT(s.ncalls, 9);                 /* 0, 5, 10, ..., 40 */
    for (int i = 0; i < s.ncalls; i++) {
        sim_time t = (sim_time)(5 * i);
        TST_EQ_INT(s.t[i], t);
        if (t == 0) {
            TST_EQ_INT(s.nchg[i], 1);
            TST_CHECK(s.chg[i][0] == k.n, "time 0: n changed");
        } else if (t % 10 == 5) {
            TST_EQ_INT(s.nchg[i], 3);
            TST_CHECK(s.chg[i][0] == k.clk && s.chg[i][1] == k.q && s.chg[i][2] == k.n,
                      "time %llu: clk, q, n in the order they changed", (unsigned long long)t);
        } else {
            TST_EQ_INT(s.nchg[i], 1);
            TST_CHECK(s.chg[i][0] == k.clk, "time %llu: clk only", (unsigned long long)t);
        }
    }
    TST_EQ_INT(k.q->cur, 4);                 /* edges at 5, 15, 25, 35 */
    /* Removed: not called any more. */
    sim_unobserve(k.c, record, &s);
    sim_run(k.c, 62);
    TST_EQ_INT(s.ncalls, 9);
    uint32_t n = 99;
    TST_CHECK(sim_changed(k.c, &n) == NULL && n == 0, "no list kept without a watcher");
    sim_free(k.c);
}

/* Checks every step as it comes: what t_observer_per_step expects. */
typedef struct stepcheck { const counter *k; long steps, bad; } stepcheck;

static void check_step(sim_ctx *c, sim_time now, void *data)
{
    stepcheck *sc = data;
    const counter *k = sc->k;
    uint32_t n;
    sim_signal *const *d = sim_changed(c, &n);
    int ok;
    if (now == 0) ok = n == 1 && d[0] == k->n;
    else if (now % 10 == 5) ok = n == 3 && d[0] == k->clk && d[1] == k->q && d[2] == k->n;
    else ok = n == 1 && d[0] == k->clk;
    sc->steps++;
    sc->bad += !ok;
}

static void t_observer_many_steps(void)
{
    /* Over 140001 steps (more than twice 65536: the list's 16-bit
     * epochs wrap), every step lists exactly what changed in it. */
    counter k = counter_new();
    stepcheck sc = { &k, 0, 0 };
    sim_observe(k.c, check_step, &sc, SIM_OBS_CHANGES);
    sim_run(k.c, 700000);
    TST_EQ_INT(sc.steps, 140001);
    TST_EQ_INT(sc.bad, 0);
    TST_EQ_INT(k.q->cur, 70000 % 16);      /* 70000 rising edges, 4-bit wrap */
    sim_free(k.c);
}

static void t_two_observers_in_order(void)
{
    counter k = counter_new();
    static seen a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    int order[64], norder = 0;
    a.tag = 1; a.order = order; a.norder = &norder;
    b.tag = 2; b.order = order; b.norder = &norder;
    /* b reads sim_changed without asking for it: it sees the list only
     * because a asked. */
    sim_observe(k.c, record, &a, SIM_OBS_CHANGES);
    sim_observe(k.c, record, &b, 0);
    sim_run(k.c, 12);                         /* steps 0, 5, 10 */
    TST_EQ_INT(norder, 6);
    for (int i = 0; i < norder; i++) TST_EQ_INT(order[i], i % 2 ? 2 : 1);
    for (int i = 0; i < 3; i++) {
        TST_EQ_INT(b.t[i], a.t[i]);
        TST_EQ_INT(b.nchg[i], a.nchg[i]);
    }
    /* Without a watcher of changes, the list is empty for everyone. */
    sim_unobserve(k.c, record, &a);
    sim_run(k.c, 22);                         /* 12 (where the last run stopped), 15, 20 */
    TST_EQ_INT(b.ncalls, 6);
    for (int i = 3; i < 6; i++) TST_EQ_INT(b.nchg[i], 0);
    sim_free(k.c);
}

static void count_calls(sim_ctx *c, sim_time now, void *data) { (void)c; (void)now; (*(int *)data)++; }
static int64_t inv_fn(const int64_t *in, void *u) { (void)u; return !in[0]; }

static void t_observer_at_loop(void)
{
    /* The step a combinational loop is found in is observed too. */
    sim_ctx *c = sim_new();
    sim_set_max_deltas(c, 20);
    sim_signal *w = sim_bit_new(c, NULL, "w", SIM_KIND_WIRE);
    sim_signal *y = sim_logic(c, NULL, "y", w->fmt, 1, &w, inv_fn, NULL, 1.0);
    sim_assign(c, w, y);
    int calls = 0;
    sim_observe(c, count_calls, &calls, 0);
    TST_EQ_INT(sim_run(c, 10), SIM_ERR_LOOP);
    TST_EQ_INT(calls, 1);
    sim_free(c);
}

static void t_two_drivers(void)
{
    /* Every way of driving a wire twice is refused before the run, with
     * the wire named; nothing is evaluated. */
    for (int how = 0; how < 4; how++) {
        sim_ctx *c = sim_new();
        sim_scope *u = sim_scope_new(c, NULL, "u");
        sim_signal *a = sim_signal_new(c, u, "a", F("u4.0"), SIM_KIND_INPUT);
        sim_signal *b = sim_signal_new(c, u, "b", F("u4.0"), SIM_KIND_INPUT);
        sim_signal *w;
        const char *path;
        if (how == 0) {        /* two assignments */
            w = sim_signal_new(c, u, "w", F("u4.0"), SIM_KIND_WIRE);
            sim_assign(c, w, a);
            path = "top.u.w";
        } else if (how == 1 || how == 3) { /* an adder's output; as a clock */
            w = sim_add(c, u, "s", F("u5.0"), a, b);
            path = "top.u.s";
        } else {               /* a constant */
            w = sim_const_raw(c, u, "k", F("u4.0"), 3);
            path = "top.u.k";
        }
        if (how < 3) sim_assign(c, w, b);
        else sim_clock(c, w, 5, 5);
        TST_EQ_INT(sim_run(c, 10), SIM_ERR_ELAB);
        const char *e = sim_error(c);
        TST_CHECK(strstr(e, path) != NULL && strstr(e, "two drivers") != NULL, "%s", e);
        TST_CHECK(strchr(e, '\n') == NULL, "one line: %s", e);
        TST_EQ_INT(sim_get_stats(c)->proc_runs, 0);
        TST_EQ_INT(sim_get_stats(c)->deltas, 0);
        TST_EQ_INT(sim_run(c, 20), SIM_ERR_ELAB);   /* and stays refused */
        sim_free(c);
    }
    /* One driver each: fine. */
    sim_ctx *c = sim_new();
    sim_signal *a = sim_signal_new(c, NULL, "a", F("u4.0"), SIM_KIND_INPUT);
    sim_signal *w = sim_signal_new(c, NULL, "w", F("u4.0"), SIM_KIND_WIRE);
    sim_signal *v = sim_signal_new(c, NULL, "v", F("u4.0"), SIM_KIND_WIRE);
    sim_assign(c, w, a);
    sim_assign(c, v, a);
    sim_force(a, 9);
    TST_EQ_INT(sim_run(c, 0), SIM_OK);
    TST_EQ_INT(w->cur, 9);
    TST_EQ_INT(v->cur, 9);
    sim_free(c);
}

static int64_t sum_fn(const int64_t *in, void *u)
{
    int64_t s = 0;
    for (int i = 0; i < *(int *)u; i++) s += in[i] << i;
    return s;
}

static void t_logic_inputs(void)
{
    /* 8 inputs: every one reaches the function (bit i of the result is
     * input i); 9: an elaboration error naming the element. */
    for (int n = 8; n <= 9; n++) {
        sim_ctx *c = sim_new();
        sim_scope *u = sim_scope_new(c, NULL, "ctl");
        sim_signal *in[9];
        for (int i = 0; i < n; i++) {
            char name[16];
            snprintf(name, sizeof name, "i%d", i);
            in[i] = sim_bit_new(c, u, name, SIM_KIND_INPUT);
        }
        int nn = n;
        sim_signal *y = sim_logic(c, u, "dec", F("u9.0"), n, in, sum_fn, &nn, 1.0);
        TST_CHECK(y != NULL, "an output even on error");
        for (int i = 0; i < n; i++) sim_force(in[i], (0x15a >> i) & 1);
        sim_status st = sim_run(c, 0);
        if (n == 8) {
            TST_EQ_INT(st, SIM_OK);
            TST_EQ_INT(y->cur, 0x15a & 0xff);
        } else {
            TST_EQ_INT(st, SIM_ERR_ELAB);
            const char *e = sim_error(c);
            TST_CHECK(strstr(e, "top.ctl.dec") != NULL && strstr(e, "9 inputs") != NULL, "%s", e);
        }
        sim_free(c);
    }
}

static void t_time_steps(void)
{
    /* Steps at 0, 5, ..., 20: five distinct times. Running again to the
     * same time, after a force, evaluates (one more delta) but is the same
     * time step. */
    counter k = counter_new();
    sim_signal *x = sim_signal_new(k.c, NULL, "x", F("u4.0"), SIM_KIND_INPUT);
    sim_signal *y = sim_add(k.c, NULL, "y", F("u5.0"), x, k.one);
    int calls = 0;
    sim_observe(k.c, count_calls, &calls, 0);
    sim_run(k.c, 20);
    TST_EQ_INT(sim_get_stats(k.c)->time_steps, 5);
    uint64_t d0 = sim_get_stats(k.c)->deltas;
    sim_force(x, 6);
    sim_run(k.c, 20);
    TST_EQ_INT(y->cur, 7);
    TST_CHECK(sim_get_stats(k.c)->deltas > d0, "the force was evaluated");
    TST_EQ_INT(sim_get_stats(k.c)->time_steps, 5);
    TST_EQ_INT(calls, 6);                     /* observers see the resumed step */
    sim_run(k.c, 30);                         /* 25, 30 */
    TST_EQ_INT(sim_get_stats(k.c)->time_steps, 7);
    sim_free(k.c);
}

static void user_fn(sim_proc *p) { (void)p; }

static void t_proc_iteration(void)
{
    sim_ctx *c = sim_new();
    sim_scope *u = sim_scope_new(c, NULL, "u");
    sim_signal *a = sim_signal_new(c, u, "a", F("u4.0"), SIM_KIND_INPUT);
    sim_signal *s = sim_add(c, u, "s", F("u5.0"), a, a);
    int data;
    sim_proc *p = sim_proc_new(c, "tb.watch", user_fn, &data);
    sim_sensitive(p, a, SIM_EDGE_ANY);
    TST_EQ_INT(sim_proc_count(c), 2);
    TST_CHECK(sim_proc_at(c, 0) == s->driver, "the adder's process first");
    TST_CHECK(sim_proc_at(c, 1) == p, "then the user's");
    TST_CHECK(sim_proc_at(c, 2) == NULL, "past the end");
    TST_EQ_STR(sim_proc_name(p), "tb.watch");
    TST_EQ_STR(sim_proc_name(s->driver), "u.s");
    TST_CHECK(p->data == &data && p->ctx == c, "public fields");
    sim_run(c, 0);                            /* initialization: each once */
    sim_force(a, 3);
    sim_run(c, 1);                            /* a changes: each once more */
    TST_EQ_INT(sim_proc_runs(p), 2);
    TST_EQ_INT(sim_proc_runs(s->driver), 2);
    TST_EQ_INT(s->cur, 6);
    sim_free(c);
}

int main(void)
{
    TST_RUN(t_observer_per_step);
    TST_RUN(t_observer_many_steps);
    TST_RUN(t_two_observers_in_order);
    TST_RUN(t_observer_at_loop);
    TST_RUN(t_two_drivers);
    TST_RUN(t_logic_inputs);
    TST_RUN(t_time_steps);
    TST_RUN(t_proc_iteration);
    TST_EXIT();
}
