/* test_elem.c - every element kind of sim_elem.h's list through every
 * engine. The list is walked, not copied: a kind added to it is tested
 * here at once, and fails until each engine implements it.
 *
 * For each kind, a small design with one element of that kind (its
 * "subject"; for a source kind, the input, clock or constant itself) runs
 * on the kernel, one context per lane, and in the batch mode, all lanes
 * at once, on random inputs for a few clock edges: every signal's value
 * in every lane equals the kernel's, and the subject's equals a formula
 * computed here from the inputs (formats chosen wide enough that every
 * result is exact). The toggle counts of both engines agree. The
 * interval evaluation of a point gives the kernel's value. The Verilog
 * export writes the design. The subject's area, delay and energy per
 * toggle are nonzero exactly where the list says the kind has them. */
#include "tests/tst.h"
#include "sim/sim_prim.h"
#include "sim/sim_batch.h"
#include "sim/sim_toggle.h"
#include "sim/sim_energy.h"
#include "sim/sim_ival.h"
#include "sim/sim_verilog.h"

/* the list's rows, as data */
typedef struct row {
    sim_kind    kind;
    const char *name;
    int         role;
    const char *energy;
    int         area, delay;
} row;
#define ROW(K, name, role, eval, vlog, energy, area, delay) { SIM_KIND_##K, name, role, #energy, area, delay },
static const row rows[] = { SIM_ELEM_LIST(ROW) };
#define NROWS ((int)(sizeof rows / sizeof rows[0]))

enum { LANES = 8, EDGES = 10, RST_RAW = 5, K_RAW = 37 };

/* One design: clk outside the unit's scope, inputs a, b (s4.4), sel
 * (u2.0), en and rs (u1.0) in it, and the subject y. */
typedef struct design {
    sim_ctx    *c;
    sim_scope  *sc;
    sim_signal *clk, *a, *b, *sel, *en, *rs, *y;
} design;

static sim_fmt fmt(int sgn, int ib, int fb)
{
    sim_fmt f = { .is_signed = (uint8_t)sgn, .ibits = (int8_t)ib, .fbits = (int8_t)fb, .width = (uint8_t)(ib + fb) };
    return f;
}

static int64_t logic_fn(const int64_t *in, void *user)
{
    (void)user;
    return in[0] * 3 ^ in[1];
}

static int64_t wide_fn(const int64_t *in, void *user)
{
    (void)user;
    return in[0] - 2 * in[1];
}

/* narrow: outputs of 2 integer and 2 fraction bits, half-up and
 * saturation (every quantization path; no formula then). */
/* a signed input's table: 8 bits, tabulated by both engines, each in
 * its own code (sim_lut.h); a function that tells a raw from the raw
 * 2^7 away (a wrong decode of the sign) in its low 6 bits */
static int64_t signed_fn(const int64_t *in, void *user)
{
    (void)user;
    return (in[0] >> 3) * 3 + 1;
}

/* signed_fn's value in s6.0 (low 6 bits, sign-extended), by hand:
 * floor(a / 8) without a shift */
static int64_t signed_ref(int64_t a)
{
    int64_t q = a >= 0 ? a / 8 : -((-a + 7) / 8);
    int64_t v = (q * 3 + 1) & 63;
    return v >= 32 ? v - 64 : v;
}

static design build(sim_kind k, int narrow)
{
    design d;
    d.c = sim_new();
    if (narrow) sim_set_quant(d.c, SIM_RND_HALF_UP, SIM_OVF_SAT);
    sim_fmt n22 = fmt(1, 2, 2);
    d.sc = sim_scope_new(d.c, sim_root(d.c), "u");
    d.clk = sim_bit_new(d.c, NULL, "clk", SIM_KIND_CLOCK);
    sim_fmt s44 = fmt(1, 4, 4), u2 = fmt(0, 2, 0), u1 = fmt(0, 1, 0);
    d.a = sim_signal_new(d.c, d.sc, "a", s44, SIM_KIND_INPUT);
    d.b = sim_signal_new(d.c, d.sc, "b", s44, SIM_KIND_INPUT);
    d.sel = sim_signal_new(d.c, d.sc, "sel", u2, SIM_KIND_INPUT);
    d.en = sim_signal_new(d.c, d.sc, "en", u1, SIM_KIND_INPUT);
    d.rs = sim_signal_new(d.c, d.sc, "rs", u1, SIM_KIND_INPUT);
    d.y = NULL;
    sim_signal *k37 = NULL, *mi[3];
    switch (k) {
    case SIM_KIND_WIRE:
    case SIM_KIND_INPUT:   /* a declared signal a sim_assign drives */
        d.y = sim_signal_new(d.c, d.sc, "y", narrow ? n22 : s44, k);
        sim_assign(d.c, d.y, d.a);
        break;
    case SIM_KIND_CLOCK:   /* the clock itself; a register shows its edges */
        d.y = d.clk;
        sim_reg(d.c, d.sc, "q", s44, d.clk, d.a, NULL, NULL, 0);
        break;
    case SIM_KIND_CONST:
        d.y = sim_const_raw(d.c, d.sc, "y", s44, K_RAW);
        break;
    case SIM_KIND_REG:
        d.y = sim_reg(d.c, d.sc, "y", narrow ? n22 : s44, d.clk, d.a, d.en, d.rs, narrow ? 1 : RST_RAW);
        break;
    case SIM_KIND_MUX:
        k37 = sim_const_raw(d.c, d.sc, "k", s44, K_RAW);
        mi[0] = d.a; mi[1] = d.b; mi[2] = k37;
        d.y = sim_mux(d.c, d.sc, "y", narrow ? n22 : s44, d.sel, 3, mi);
        break;
    case SIM_KIND_BK:
        d.y = sim_bk(d.c, d.sc, "y", narrow ? n22 : s44, d.en, d.a);
        break;
    case SIM_KIND_ADD: d.y = sim_add(d.c, d.sc, "y", narrow ? n22 : fmt(1, 5, 4), d.a, d.b); break;
    case SIM_KIND_SUB: d.y = sim_sub(d.c, d.sc, "y", narrow ? n22 : fmt(1, 5, 4), d.a, d.b); break;
    case SIM_KIND_MUL: d.y = sim_mul(d.c, d.sc, "y", narrow ? n22 : fmt(1, 8, 8), d.a, d.b); break;
    case SIM_KIND_SHIFT: d.y = sim_shift(d.c, d.sc, "y", narrow ? n22 : fmt(1, 6, 4), d.a, narrow ? -3 : 2); break;
    case SIM_KIND_LOGIC: {
        sim_signal *li[2] = { d.sel, d.en }, *wi[2] = { d.a, d.b };
        d.y = sim_logic(d.c, d.sc, "y", fmt(0, 3, 0), 2, li, logic_fn, NULL, 4.0);
        /* 16 input bits: called, not tabulated, by both engines */
        sim_signal *w = sim_logic(d.c, d.sc, "w", fmt(1, 9, 0), 2, wi, wide_fn, NULL, 40.0);
        sim_logic_verilog(w, "assign %y = {%0[7], %0} - {%1, 1'b0};");
        sim_logic(d.c, d.sc, "z", fmt(1, 6, 0), 1, &d.a, signed_fn, NULL, 20.0);
        break;
    }
    default:
        break;
    }
    return d;
}

/* The inputs of lane l at step e (step 0: before the first edge). */
typedef struct ins { int64_t a, b, sel, en, rs; } ins;
static ins inputs(uint32_t l, int e)
{
    uint64_t x = 0x9e3779b97f4a7c15ull * (uint64_t)(l * 131 + (uint32_t)e * 7 + 1);
    x ^= x >> 29; x *= 0xbf58476d1ce4e5b9ull; x ^= x >> 32;
    ins v = { (int64_t)(x & 255) - 128, (int64_t)((x >> 8) & 255) - 128, (int64_t)((x >> 16) & 3),
              (int64_t)((x >> 18) & 1), (int64_t)(((x >> 19) & 7) == 0) };
    return v;
}

/* The subject's value after step e's inputs settled, from the formulas;
 * prev: its value at step e - 1 (state). */
static int64_t expect(sim_kind k, ins v, ins before, int e, int64_t prev)
{
    switch (k) {
    case SIM_KIND_WIRE: case SIM_KIND_INPUT: return v.a;
    case SIM_KIND_CLOCK: return 0;   /* the batch holds no clock value; the kernel's is checked apart */
    case SIM_KIND_CONST: return K_RAW;
    case SIM_KIND_REG:
        if (!e) return RST_RAW;
        return before.rs ? RST_RAW : before.en ? before.a : prev;
    case SIM_KIND_MUX: return v.sel == 0 ? v.a : v.sel == 1 ? v.b : v.sel == 2 ? K_RAW : 0;
    case SIM_KIND_BK: return v.en ? v.a : 0;
    case SIM_KIND_ADD: return v.a + v.b;
    case SIM_KIND_SUB: return v.a - v.b;
    case SIM_KIND_MUL: return v.a * v.b;
    case SIM_KIND_SHIFT: return v.a * 4;
    case SIM_KIND_LOGIC: return (v.sel * 3 ^ v.en) & 7;
    default: return INT64_MIN;
    }
}

static void force(design *d, ins v)
{
    sim_force(d->a, v.a); sim_force(d->b, v.b); sim_force(d->sel, v.sel);
    sim_force(d->en, v.en); sim_force(d->rs, v.rs);
}

static void put(sim_batch *b, design *d, uint32_t l, ins v)
{
    sim_batch_set(b, d->a, l, v.a); sim_batch_set(b, d->b, l, v.b); sim_batch_set(b, d->sel, l, v.sel);
    sim_batch_set(b, d->en, l, v.en); sim_batch_set(b, d->rs, l, v.rs);
}

/* Kernel (a context per lane) against the batch and the formulas. */
static void engines(const row *r, int narrow)
{
    char err[300];
    design bd = build(r->kind, narrow), kd[LANES];
    TST_CHECK(bd.y != NULL, "%s: no design", r->name);
    if (!bd.y) { sim_free(bd.c); return; }
    sim_batch *b = sim_batch_new(bd.c, bd.clk, LANES, err, sizeof err);
    TST_CHECK(b != NULL, "%s: the batch refuses it: %s", r->name, err);
    if (!b) { sim_free(bd.c); return; }
    TST_CHECK(sim_batch_toggles_on(b) == 0, "%s", r->name);
    sim_toggle *tg[LANES];
    for (uint32_t l = 0; l < LANES; l++) {
        kd[l] = build(r->kind, narrow);
        tg[l] = sim_toggle_new(kd[l].c);
        force(&kd[l], inputs(l, 0));
        TST_EQ_INT(sim_run(kd[l].c, 0), SIM_OK);
        put(b, &bd, l, inputs(l, 0));
    }
    sim_batch_start(b);
    int64_t prev[LANES] = { 0 };
    int bad = 0, clk_edges = 0;
    uint32_t ns = sim_signal_count(bd.c);
    for (int e = 0; e <= EDGES && bad < 5; e++) {
        if (e) {
            for (uint32_t l = 0; l < LANES; l++) {
                /* the edge: registers take the values before it, then
                 * the inputs of step e arrive (as sim_batch_cycle) */
                int before = (int)kd[l].clk->changes;
                sim_force(kd[l].clk, 1);
                sim_run(kd[l].c, (sim_time)(2 * e));
                clk_edges += (int)kd[l].clk->changes - before;
                sim_force(kd[l].clk, 0);
                force(&kd[l], inputs(l, e));
                sim_run(kd[l].c, (sim_time)(2 * e + 1));
                put(b, &bd, l, inputs(l, e));
            }
            sim_batch_cycle(b);
        }
        for (uint32_t l = 0; l < LANES; l++) {
            for (uint32_t i = 0; i < ns; i++) {
                const sim_signal *s = sim_signal_at(bd.c, i), *ks = sim_signal_at(kd[l].c, i);
                if (s == bd.clk) continue;
                if (sim_batch_val(b, s)[l] != ks->cur && bad++ < 5)
                    TST_CHECK(0, "%s: %s at step %d lane %u: batch %lld, kernel %lld", r->name, s->name, e, l,
                              (long long)sim_batch_val(b, s)[l], (long long)ks->cur);
            }
            const sim_signal *ky = r->kind == SIM_KIND_CLOCK ? NULL : sim_signal_at(kd[l].c, bd.y->index);
            int64_t want = expect(r->kind, inputs(l, e), inputs(l, e ? e - 1 : 0), e, prev[l]);
            if (ky && !narrow && ky->cur != want && bad++ < 5)
                TST_CHECK(0, "%s: y at step %d lane %u: %lld, by the formula %lld", r->name, e, l,
                          (long long)ky->cur, (long long)want);
            if (ky) prev[l] = ky->cur;
            const sim_signal *kz = sim_find(kd[l].c, kd[l].sc, "z");
            if (kz && kz->cur != signed_ref(inputs(l, e).a) && bad++ < 5)
                TST_CHECK(0, "%s: z at step %d lane %u: %lld, by the formula %lld", r->name, e, l,
                          (long long)kz->cur, (long long)signed_ref(inputs(l, e).a));
        }
    }
    if (r->kind == SIM_KIND_CLOCK)   /* the kernel saw every edge go up */
        TST_EQ_INT(clk_edges, LANES * EDGES);
    /* toggles: every signal but the clock (the batch does not model its wire) */
    for (uint32_t l = 0; l < LANES; l++) {
        for (uint32_t i = 0; i < ns; i++) {
            const sim_signal *s = sim_signal_at(bd.c, i);
            if (s == bd.clk) continue;
            uint64_t kt = sim_toggle_count(tg[l], sim_signal_at(kd[l].c, i)), bt = sim_batch_toggles(b, s)[l];
            if (kt != bt && bad++ < 5)
                TST_CHECK(0, "%s: %s's toggles in lane %u: batch %llu, kernel %llu", r->name, s->name, l,
                          (unsigned long long)bt, (unsigned long long)kt);
        }
        sim_toggle_free(tg[l]);
        sim_free(kd[l].c);
    }
    sim_batch_free(b);
    sim_free(bd.c);
}

/* Exact formats, then every quantization path; the batch with its
 * vector loops (where the CPU has them) and with its scalar loops alone. */
static void t_engines_every_kind(void)
{
    for (int v = 0; v < 2; v++) {
        sim_batch_vector(v ? 0 : 8);
        for (int narrow = 0; narrow < 2; narrow++)
            for (int i = 0; i < NROWS; i++) engines(&rows[i], narrow);
    }
    sim_batch_vector(8);
}

/* The list and the enum it makes agree: every kind one row, in order,
 * with a name; the lookups answer for each. */
static void t_list(void)
{
    TST_EQ_INT(NROWS, SIM_KIND__COUNT);
    for (int i = 0; i < NROWS; i++) {
        TST_EQ_INT(rows[i].kind, i);
        TST_EQ_STR(sim_kind_name(rows[i].kind), rows[i].name);
        TST_EQ_INT(sim_kind_role(rows[i].kind), rows[i].role);
        for (int j = 0; j < i; j++) TST_CHECK(strcmp(rows[i].name, rows[j].name), "%s twice", rows[i].name);
    }
    TST_CHECK(sim_kind_name(SIM_KIND__COUNT) == NULL, "a name past the list");
}

/* Area, delay and energy per toggle: nonzero where the list says so; an
 * interval of points gives the kernel's value; the Verilog export writes
 * each design. */
static void t_models_every_kind(void)
{
    for (int i = 0; i < NROWS; i++) {
        const row *r = &rows[i];
        design d = build(r->kind, 0);
        if (!d.y) { TST_CHECK(0, "%s: no design", r->name); sim_free(d.c); continue; }
        ins v = inputs(3, 0);
        force(&d, v);
        TST_EQ_INT(sim_run(d.c, 0), SIM_OK);
        const sim_signal *y = d.y;
        TST_CHECK((y->area_ge > 0) == r->area, "%s: area %g", r->name, y->area_ge);
        double ps = 0;
        for (int j = 0; j < 4; j++) if (y->dly_ps[j] > ps) ps = y->dly_ps[j];
        TST_CHECK((ps > 0) == r->delay, "%s: delay %g ps", r->name, ps);
        double fj = sim_energy_toggle_fj(y);
        TST_CHECK((fj > 0) == (strcmp(r->energy, "none") != 0), "%s: %g fJ a toggle (model %s)", r->name, fj, r->energy);
        /* intervals: a driven subject's from points is its value */
        if (r->role != SIM_ELEM_SEQ && (y->driver || r->kind == SIM_KIND_CONST)) {
            uint32_t ns = sim_signal_count(d.c);
            sim_ival *vals = calloc(ns, sizeof *vals), pre, post;
            for (uint32_t j = 0; j < ns; j++) vals[j].lo = vals[j].hi = sim_signal_at(d.c, j)->cur;
            TST_EQ_INT(sim_ival_eval(y, vals, &pre, &post), 0);
            TST_CHECK(post.lo == y->cur && post.hi == y->cur, "%s: interval [%lld, %lld], value %lld", r->name,
                      (long long)post.lo, (long long)post.hi, (long long)y->cur);
            free(vals);
        } else if (r->role == SIM_ELEM_SEQ) {
            sim_ival vals[16] = { { 0, 0 } }, pre, post;
            TST_CHECK(sim_signal_count(d.c) <= 16, "%s", r->name);
            TST_EQ_INT(sim_ival_eval(y, vals, &pre, &post), 0);
        }
        /* Verilog: the inputs as ports, the subject (or, for the clock,
         * the register it clocks) an output */
        sim_signal *out = r->kind == SIM_KIND_CLOCK ? sim_find(d.c, d.sc, "q") : d.y;
        sim_vport ports[6] = { { "a", d.a, 0 }, { "b", d.b, 0 }, { "sel", d.sel, 0 }, { "en", d.en, 0 },
                               { "rs", d.rs, 0 }, { out->name, out, 1 } };
        char err[300] = "", *text = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&text, &len);
        int rc = sim_verilog_module(f, d.c, d.sc, "elem", d.clk, SIM_VRESET_SYNC, ports, 6, err, sizeof err);
        fclose(f);
        TST_CHECK(rc == 0, "%s: the export refuses it: %s", r->name, err);
        TST_CHECK(text && strstr(text, "module elem") && strstr(text, "endmodule"), "%s: no module", r->name);
        /* every driven signal of the unit has its line ("// NAME: FORMAT") */
        for (uint32_t j = 0; text && j < sim_signal_count(d.c); j++) {
            const sim_signal *s = sim_signal_at(d.c, j);
            if (s->scope != d.sc || (!s->driver && s->kind != SIM_KIND_CONST)) continue;
            char want[64];
            snprintf(want, sizeof want, "// %s: ", s->name);
            TST_CHECK(strstr(text, want) != NULL, "%s: %s not written", r->name, s->name);
        }
        free(text);
        sim_free(d.c);
    }
}

int main(void)
{
    TST_RUN(t_list);
    TST_RUN(t_engines_every_kind);
    TST_RUN(t_models_every_kind);
    TST_EXIT();
}
