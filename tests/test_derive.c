/* test_derive.c - derived ranges (sim_ival, tb_derive): an element's
 * interval against brute force over every operand raw, quantized by
 * sim_fx_requant; and, for several units, that the derived intervals
 * contain every value a run settles to on random and corner stimuli over
 * the declared ranges, and that formats with derived integer bits never
 * overflow there. */
#include "tests/tst.h"
#include "testbench/tb_derive.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* mul, add, sub and shift on small formats, every rounding mode: the
 * interval (before overflow handling) is exactly the hull of the element's
 * rounded values over every pair of raws in the operand intervals. */
static void ival_matches_brute_force(void)
{
    for (int rm = 0; rm < 3; rm++)
        for (int kind = 0; kind < 4; kind++) {
            sim_ctx *c = sim_new();
            sim_set_quant(c, (sim_round)rm, SIM_OVF_WRAP);
            sim_fmt fa, fb, fy;
            sim_fmt_make(1, 3, 3, &fa, NULL, 0);
            sim_fmt_make(0, 2, 4, &fb, NULL, 0);
            sim_fmt_make(1, 3, 2, &fy, NULL, 0);
            sim_signal *a = sim_signal_new(c, NULL, "a", fa, SIM_KIND_INPUT);
            sim_signal *b = sim_signal_new(c, NULL, "b", fb, SIM_KIND_INPUT);
            sim_signal *y = kind == 0 ? sim_mul(c, NULL, "y", fy, a, b) : kind == 1 ? sim_add(c, NULL, "y", fy, a, b)
                          : kind == 2 ? sim_sub(c, NULL, "y", fy, a, b) : sim_shift(c, NULL, "y", fy, a, -3);
            sim_ival v[8];
            int64_t alo = -23, ahi = 17, blo = 5, bhi = 41;
            v[a->index] = (sim_ival){ alo, ahi };
            v[b->index] = (sim_ival){ blo, bhi };
            sim_ival pre, post;
            TST_EQ_INT(sim_ival_eval(y, v, &pre, &post), 0);
            sim_wide lo = 0, hi = 0;
            int first = 1;
            for (int64_t x = alo; x <= ahi; x++)
                for (int64_t z = blo; z <= bhi; z++) {
                    sim_wide e;
                    int sf;
                    if (kind == 0) { e = (sim_wide)x * z; sf = 7; }
                    else if (kind == 1) { e = (sim_wide)x * 2 + z; sf = 4; }
                    else if (kind == 2) { e = (sim_wide)x * 2 - z; sf = 4; }
                    else { e = x; sf = 6; }
                    /* a wide format: rounding only, no overflow */
                    sim_fmt w;
                    sim_fmt_make(1, 40, 2, &w, NULL, 0);
                    sim_wide q = sim_fx_requant(e, sf, w, (sim_round)rm, SIM_OVF_WRAP, NULL);
                    if (first || q < lo) lo = q;
                    if (first || q > hi) hi = q;
                    first = 0;
                }
            TST_CHECK(pre.lo == lo && pre.hi == hi, "kind %d round %d: [%lld, %lld], brute force [%lld, %lld]", kind, rm,
                      (long long)pre.lo, (long long)pre.hi, (long long)lo, (long long)hi);
            sim_free(c);
        }
}

/* A block key guarded by a logic function of z, passing an element of z
 * (1 - z, z * w) or z one clock late (a register): for every interval of
 * z, the key's interval is exactly the hull of its values over every z
 * (and w) by sim_elem_eval, the one executable definition: narrowed to
 * the z where the guard passes when the passed value is computed from z
 * in the same delta, left whole through a register (whose z is another
 * clock's). The guard is not monotone (z % 5 != 0 and z < 20), so only
 * the ends of where it passes count. */
static int64_t guard_fn(const int64_t *in, void *u) { (void)u; return in[0] % 5 != 0 && in[0] < 20; }

static sim_wide elem_at(const sim_signal *y, const int64_t *in)
{
    sim_prim_info e;
    int64_t out = 0;
    int ovf;
    sim_prim_describe(y, &e);
    sim_elem_eval(&e, in, &out, &ovf);
    return out;
}

static void ival_guarded_key(void)
{
    for (int form = 0; form < 3; form++) {
        sim_ctx *c = sim_new();
        sim_fmt fz, fw, fy, u1;
        sim_fmt_make(0, 3, 2, &fz, NULL, 0);     /* z: u3.2, raws 0..31 */
        sim_fmt_make(1, 3, 1, &fw, NULL, 0);
        sim_fmt_make(1, 7, 2, &fy, NULL, 0);
        sim_fmt_make(0, 1, 0, &u1, NULL, 0);
        sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
        sim_signal *z = sim_signal_new(c, NULL, "z", fz, SIM_KIND_INPUT);
        sim_signal *w = sim_signal_new(c, NULL, "w", fw, SIM_KIND_INPUT);
        sim_signal *one = sim_const(c, NULL, "one", fy, 1.0);
        sim_signal *pass = sim_logic(c, NULL, "pass", u1, 1, &z, guard_fn, NULL, 1);
        sim_signal *x = form == 0 ? sim_sub(c, NULL, "x", fy, one, z) : form == 1 ? sim_mul(c, NULL, "x", fy, z, w)
                      : sim_reg(c, NULL, "x", fy, clk, z, NULL, NULL, 0);
        sim_signal *k = sim_bk(c, NULL, "k", fy, pass, x);
        sim_ival v[16], pre, post;
        memset(v, 0, sizeof v);
        v[one->index] = (sim_ival){ one->cur, one->cur };
        v[w->index] = (sim_ival){ -5, 3 };
        int bad = 0;
        for (int64_t lo = 0; lo < 32; lo++)
            for (int64_t hi = lo; hi < 32; hi++) {
                v[z->index] = (sim_ival){ lo, hi };
                if (form == 2) v[x->index] = (sim_ival){ lo, hi };    /* the register's own: z's */
                else sim_ival_eval(x, v, &v[x->index], &post);
                sim_ival_eval(pass, v, &v[pass->index], &post);
                sim_ival_eval(k, v, &pre, &post);
                /* brute force: z now (the guard's), z a clock before (the register's), w */
                sim_wide blo = 0, bhi = 0;
                int first = 1;
                for (int64_t zn = lo; zn <= hi; zn++)
                    for (int64_t zp = lo; zp <= (form == 2 ? hi : lo); zp++)
                        for (int64_t wv = v[w->index].lo; wv <= (form == 1 ? v[w->index].hi : v[w->index].lo); wv++) {
                            int64_t in[2] = { form == 0 ? one->cur : zn, form == 0 ? zn : wv };
                            int64_t xv = form == 2 ? zp : (int64_t)elem_at(x, in);
                            int64_t kin[2] = { guard_fn(&zn, NULL), xv };
                            sim_wide kv = elem_at(k, kin);
                            if (first || kv < blo) blo = kv;
                            if (first || kv > bhi) bhi = kv;
                            first = 0;
                        }
                if (pre.lo != blo || pre.hi != bhi) {
                    if (!bad++)
                        TST_CHECK(0, "form %d, z raws [%lld, %lld]: key [%lld, %lld], brute force [%lld, %lld]", form,
                                  (long long)lo, (long long)hi, (long long)pre.lo, (long long)pre.hi, (long long)blo,
                                  (long long)bhi);
                }
            }
        TST_EQ_INT(bad, 0);
        sim_free(c);
    }
}

/* The interpolation y = a + t (b - a) (sub, mul, add; the mul and the
 * add rounding to fewer bits), every rounding mode: for intervals of a,
 * b and t (t within [0, 1], and one past 1 where the rule must not
 * apply), every combination of raws through sim_elem_eval lies within
 * the derived interval; with t in [0, 1] that interval is within
 * hull(a, b) widened by the roundings (two LSBs of y), where the plain
 * intervals reach far past it. */
static void ival_interpolation(void)
{
    static const int64_t box[][6] = {     /* a lo, hi; b lo, hi; t lo, hi (t u1.3: 8 is 1) */
        { 0, 8, 0, 8, 0, 8 }, { -5, 3, 2, 7, 1, 6 }, { 4, 4, -8, -2, 0, 8 }, { -8, 7, -8, 7, 3, 3 }, { 0, 8, 0, 8, 0, 12 },
    };
    for (int rm = 0; rm < 3; rm++)
        for (size_t bx = 0; bx < sizeof box / sizeof box[0]; bx++) {
            sim_ctx *c = sim_new();
            sim_set_quant(c, (sim_round)rm, SIM_OVF_WRAP);
            sim_fmt fab, ft, fd, fm, fy;
            sim_fmt_make(1, 2, 3, &fab, NULL, 0);    /* a, b: s2.3 */
            sim_fmt_make(0, 1, 3, &ft, NULL, 0);     /* t: u1.3 */
            sim_fmt_make(1, 3, 3, &fd, NULL, 0);     /* b - a exact */
            sim_fmt_make(1, 4, 2, &fm, NULL, 0);     /* t (b - a) rounded */
            sim_fmt_make(1, 4, 2, &fy, NULL, 0);     /* y rounded */
            sim_signal *a = sim_signal_new(c, NULL, "a", fab, SIM_KIND_INPUT);
            sim_signal *b = sim_signal_new(c, NULL, "b", fab, SIM_KIND_INPUT);
            sim_signal *t = sim_signal_new(c, NULL, "t", ft, SIM_KIND_INPUT);
            sim_signal *d = sim_sub(c, NULL, "d", fd, b, a);
            sim_signal *m = bx & 1 ? sim_mul(c, NULL, "m", fm, d, t) : sim_mul(c, NULL, "m", fm, t, d);
            sim_signal *y = bx & 1 ? sim_add(c, NULL, "y", fy, m, a) : sim_add(c, NULL, "y", fy, a, m);
            sim_ival v[16], pre, post;
            memset(v, 0, sizeof v);
            v[a->index] = (sim_ival){ box[bx][0], box[bx][1] };
            v[b->index] = (sim_ival){ box[bx][2], box[bx][3] };
            v[t->index] = (sim_ival){ box[bx][4], box[bx][5] };
            sim_ival_eval(d, v, &v[d->index], &post);
            sim_ival_eval(m, v, &v[m->index], &post);
            TST_EQ_INT(sim_ival_eval(y, v, &pre, &post), 0);
            sim_wide lo = 0, hi = 0;
            int first = 1;
            for (int64_t x = box[bx][0]; x <= box[bx][1]; x++)
                for (int64_t z = box[bx][2]; z <= box[bx][3]; z++)
                    for (int64_t tt = box[bx][4]; tt <= box[bx][5]; tt++) {
                        int64_t in_d[2] = { z, x }, dv = (int64_t)elem_at(d, in_d);
                        int64_t in_m[2] = { bx & 1 ? dv : tt, bx & 1 ? tt : dv }, mv = (int64_t)elem_at(m, in_m);
                        int64_t in_y[2] = { bx & 1 ? mv : x, bx & 1 ? x : mv };
                        sim_wide yv = elem_at(y, in_y);
                        if (first || yv < lo) lo = yv;
                        if (first || yv > hi) hi = yv;
                        first = 0;
                    }
            TST_CHECK(pre.lo <= lo && pre.hi >= hi, "box %zu round %d: [%lld, %lld] misses brute force [%lld, %lld]", bx, rm,
                      (long long)pre.lo, (long long)pre.hi, (long long)lo, (long long)hi);
            /* hull(a, b) in y's raws (2 fraction bits: a raw / 2), two LSBs out */
            int64_t hlo = (box[bx][0] < box[bx][2] ? box[bx][0] : box[bx][2]), hhi = (box[bx][1] > box[bx][3] ? box[bx][1] : box[bx][3]);
            if (box[bx][5] <= 8)
                TST_CHECK(pre.lo >= (sim_wide)floor(hlo / 2.0) - 2 && pre.hi <= (sim_wide)ceil(hhi / 2.0) + 2,
                          "box %zu round %d: [%lld, %lld] not within hull [%lld, %lld] / 2 + 2 LSBs", bx, rm,
                          (long long)pre.lo, (long long)pre.hi, (long long)hlo, (long long)hhi);
            sim_free(c);
        }
}

/* A logic element of z and of zq = g(z) (a ROM's address beside the
 * value it comes from, as the reciprocal's): z's values alone are
 * enumerated, zq's computed from each, so the interval is exactly the
 * hull of f(z, g(z)) over z; z and zq taken as free would reach values
 * f never gives (here 8 + 7 = 15 where f(z, g(z)) is at most 8). */
static int64_t top_bits(const int64_t *in, void *u) { (void)u; return in[0] >> 3; }
static int64_t rest_plus(const int64_t *in, void *u) { (void)u; return (in[0] - (in[1] << 3)) + in[1]; }
static void ival_logic_dependent_input(void)
{
    sim_ctx *c = sim_new();
    sim_fmt fz, fq, fy;
    sim_fmt_make(0, 6, 0, &fz, NULL, 0);
    sim_fmt_make(0, 3, 0, &fq, NULL, 0);
    sim_fmt_make(0, 5, 0, &fy, NULL, 0);
    sim_signal *z = sim_signal_new(c, NULL, "z", fz, SIM_KIND_INPUT);
    sim_signal *zq = sim_logic(c, NULL, "zq", fq, 1, &z, top_bits, NULL, 0);
    sim_signal *ins[2] = { z, zq };
    sim_signal *y = sim_logic(c, NULL, "y", fy, 2, ins, rest_plus, NULL, 0);
    sim_ival v[8], pre, post;
    memset(v, 0, sizeof v);
    for (int64_t lo = 0; lo < 64; lo += 5)
        for (int64_t hi = lo; hi < 64; hi += 7) {
            v[z->index] = (sim_ival){ lo, hi };
            sim_ival_eval(zq, v, &v[zq->index], &post);
            sim_ival_eval(y, v, &pre, &post);
            sim_wide blo = 0, bhi = 0;
            for (int64_t x = lo; x <= hi; x++) {
                int64_t in[2] = { x, top_bits(&x, NULL) };
                sim_wide yv = elem_at(y, in);
                if (x == lo || yv < blo) blo = yv;
                if (x == lo || yv > bhi) bhi = yv;
            }
            TST_CHECK(pre.lo == blo && pre.hi == bhi, "z [%lld, %lld]: [%lld, %lld], brute force [%lld, %lld]", (long long)lo,
                      (long long)hi, (long long)pre.lo, (long long)pre.hi, (long long)blo, (long long)bhi);
        }
    sim_free(c);
}

/* Mux with a data select, block key with a data pass, register with an
 * unknown enable: the hull of the outcomes; with known ones, exactly the
 * chosen one. */
static void ival_selects(void)
{
    sim_ctx *c = sim_new();
    sim_fmt f8, u2, u1;
    sim_fmt_make(1, 4, 4, &f8, NULL, 0);
    sim_fmt_make(0, 2, 0, &u2, NULL, 0);
    sim_fmt_make(0, 1, 0, &u1, NULL, 0);
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_signal *x = sim_signal_new(c, NULL, "x", f8, SIM_KIND_INPUT);
    sim_signal *z = sim_signal_new(c, NULL, "z", f8, SIM_KIND_INPUT);
    sim_signal *sel = sim_signal_new(c, NULL, "sel", u2, SIM_KIND_INPUT);
    sim_signal *en = sim_signal_new(c, NULL, "en", u1, SIM_KIND_INPUT);
    sim_signal *in[3] = { x, z, x };
    sim_signal *m = sim_mux(c, NULL, "m", f8, sel, 3, in);
    sim_signal *k = sim_bk(c, NULL, "k", f8, en, x);
    sim_signal *q = sim_reg(c, NULL, "q", f8, clk, z, en, NULL, 0);
    sim_ival v[16], pre, post;
    memset(v, 0, sizeof v);
    v[x->index] = (sim_ival){ 10, 20 };
    v[z->index] = (sim_ival){ -30, -25 };
    v[q->index] = (sim_ival){ 3, 3 };
    v[sel->index] = (sim_ival){ 1, 1 };
    sim_ival_eval(m, v, &pre, &post);
    TST_CHECK(pre.lo == -30 && pre.hi == -25, "mux sel 1: [%lld, %lld]", (long long)pre.lo, (long long)pre.hi);
    v[sel->index] = (sim_ival){ 1, 3 };     /* 3 is out of range: 0 */
    sim_ival_eval(m, v, &pre, &post);
    TST_CHECK(pre.lo == -30 && pre.hi == 20, "mux sel 1..3: [%lld, %lld]", (long long)pre.lo, (long long)pre.hi);
    v[en->index] = (sim_ival){ 0, 1 };
    sim_ival_eval(k, v, &pre, &post);
    TST_CHECK(pre.lo == 0 && pre.hi == 20, "bk: [%lld, %lld]", (long long)pre.lo, (long long)pre.hi);
    sim_ival_eval(q, v, &pre, &post);
    TST_CHECK(pre.lo == -30 && pre.hi == 3, "reg en 0..1: [%lld, %lld]", (long long)pre.lo, (long long)pre.hi);
    v[en->index] = (sim_ival){ 0, 0 };
    sim_ival_eval(q, v, &pre, &post);
    TST_CHECK(pre.lo == 3 && pre.hi == 3, "reg en 0: [%lld, %lld]", (long long)pre.lo, (long long)pre.hi);
    /* wrap of a set that straddles the top: the whole format; sat: clamped */
    sim_ival w = sim_ival_fit((sim_ival){ 120, 130 }, f8, SIM_OVF_WRAP);
    TST_CHECK(w.lo == -128 && w.hi == 127, "wrap: [%lld, %lld]", (long long)w.lo, (long long)w.hi);
    w = sim_ival_fit((sim_ival){ 130, 140 }, f8, SIM_OVF_WRAP);
    TST_CHECK(w.lo == -126 && w.hi == -116, "wrap within a period: [%lld, %lld]", (long long)w.lo, (long long)w.hi);
    w = sim_ival_fit((sim_ival){ 120, 130 }, f8, SIM_OVF_SAT);
    TST_CHECK(w.lo == 120 && w.hi == 127, "sat: [%lld, %lld]", (long long)w.lo, (long long)w.hi);
    TST_EQ_INT(sim_ival_ibits((sim_ival){ -129, 127 }, f8), 5);   /* s5.4 holds -256..255 */
    TST_EQ_INT(sim_ival_ibits((sim_ival){ -1, 3 }, u2), -1);
    sim_free(c);
}

/* The declared range of each input: what the unit's default stimuli span. */
static void default_ranges(const unit_desc *u, const unit_cfg *cfg, tb_ranges *rg, vec_set *vs)
{
    memset(rg, 0, sizeof *rg);
    vec_set_init(vs);
    vec_set_header(vs, u->ref, &cfg->model);
    u->ref->gen(&cfg->model, 0, 1, vs);
    for (int i = 0, k = 0; i < u->nsigs; i++) {
        if (u->sigs[i].role != UNIT_SIG_IN) continue;
        rg->set[i] = 1;
        rg->lo[i] = rg->hi[i] = vec_row(vs, 0)[k];
        for (size_t r = 1; r < vs->n_rows; r++) {
            double x = vec_row(vs, r)[k];
            if (x < rg->lo[i]) rg->lo[i] = x;
            if (x > rg->hi[i]) rg->hi[i] = x;
        }
        k++;
    }
}

/* Stimuli over the box: every corner, then uniform draws; expected
 * outputs from the float reference. */
static void box_stimuli(const unit_desc *u, const unit_cfg *cfg, const tb_ranges *rg, size_t n, uint64_t seed, vec_set *vs)
{
    vec_set_init(vs);
    vec_set_header(vs, u->ref, &cfg->model);
    vec_rng rng = { seed };
    double v[2 * VEC_MAX_PORTS];
    int nin = vs->n_in, idx[VEC_MAX_PORTS];
    for (int i = 0, k = 0; i < u->nsigs; i++) if (u->sigs[i].role == UNIT_SIG_IN) idx[k++] = i;
    size_t corners = nin <= 8 ? (size_t)1 << nin : 0;
    int blo = -1, bhi = -1;         /* the unit's precondition lo < hi (div's n < d) */
    for (int j = 0; j < nin && u->below.lo; j++) {
        if (!strcmp(u->sigs[idx[j]].name, u->below.lo)) blo = j;
        if (!strcmp(u->sigs[idx[j]].name, u->below.hi)) bhi = j;
    }
    for (size_t r = 0; r < corners + n; r++) {
        for (int j = 0; j < nin; j++) {
            double lo = rg->lo[idx[j]], hi = rg->hi[idx[j]];
            v[j] = r < corners ? ((r >> j) & 1 ? hi : lo) : vec_rng_range(&rng, lo, hi);
        }
        /* outside the unit's domain: not a stimulus (two LSBs of room at
         * width 16, so that the quantized inputs keep it) */
        if (blo >= 0 && bhi >= 0 && !(v[blo] <= v[bhi] - 0x1p-14)) continue;
        u->ref->eval(&cfg->model, v, v + nin);
        vec_set_push(vs, v);
    }
}

/* One unit and schedule: formats with derived integer bits, a run on
 * stimuli over the ranges, every observed value within its derived
 * interval and no overflow. */
static void check_unit_keep(const char *name, int sched, int width, const char *keep_sig);
static void check_unit(const char *name, int sched, int width) { check_unit_keep(name, sched, width, NULL); }
/* keep_sig: a signal whose format stays (one a unit's build rule ties to
 * another's: div's r holds d's range) */
static void check_unit_keep(const char *name, int sched, int width, const char *keep_sig)
{
    const unit_desc *u = unit_find(name);
    TST_CHECK(u != NULL, "no unit %s", name);
    if (!u) return;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    cfg.schedule = sched;
    cfg.width = width;
    tb_ranges rg;
    vec_set def, box;
    default_ranges(u, &cfg, &rg, &def);
    unit_fmts f0, f;
    char err[600];
    TST_CHECK(!tb_formats(u, &cfg, NULL, 0, &f0, err, sizeof err), "%s", err);
    unsigned char keep[UNIT_MAX_SIGS] = { 0 };
    if (keep_sig) keep[unit_sig_index(u, keep_sig)] = 1;
    int bad = tb_derive_fmts(u, &cfg, &f0, &rg, keep, &f, err, sizeof err);
    TST_CHECK(!bad, "%s: %s", name, err);
    box_stimuli(u, &cfg, &rg, 3000, 77, &box);
    tb_derived d;
    tb_result r;
    if (!bad && !tb_derive(u, &cfg, &f, &rg, &d, err, sizeof err)) {
        TST_EQ_INT(d.nfail, 0);
        /* the default stimuli, the box's, and runs of 1 and 2 items (a
         * pipeline drains differently with fewer items in flight) */
        vec_set few = box;
        for (int pass = 0; pass < 4; pass++) {
            few.n_rows = (size_t)pass - 1;
            int st = tb_run(u, &cfg, &f, pass == 0 ? &def : pass == 1 ? &box : &few, NULL, &r, err, sizeof err);
            TST_CHECK(st == TB_OK, "%s: %s", name, err);
            if (st != TB_OK) continue;
            TST_CHECK(r.overflows == 0, "%s %s: %llu overflows", name, u->sched[sched].name, (unsigned long long)r.overflows);
            TST_EQ_INT(r.nsigs, d.nsigs);
            for (int i = 0; i < r.nsigs && i < d.nsigs; i++) {
                const tb_sig *s = &r.sigs[i];
                TST_EQ_STR(s->name, d.sigs[i].name);
                if (!s->seen) continue;
                TST_CHECK(s->min >= d.sigs[i].pre.lo && s->max <= d.sigs[i].pre.hi,
                          "%s %s: %s observed [%lld, %lld] outside derived [%lld, %lld]", name, u->sched[sched].name,
                          s->name, (long long)s->min, (long long)s->max, (long long)d.sigs[i].pre.lo,
                          (long long)d.sigs[i].pre.hi);
            }
            tb_result_free(&r);
        }
        tb_derived_free(&d);
    } else if (!bad) {
        TST_CHECK(0, "%s: %s", name, err);
    }
    vec_set_free(&def);
    vec_set_free(&box);
}

static void horner3_every_schedule(void)
{
    const unit_desc *u = unit_find("horner3");
    for (int s = 0; s < u->nsched; s++) check_unit("horner3", s, 16);
}
static void horner2_contains(void) { check_unit("horner2", 0, 16); }
static void coef3_n1_contains(void) { check_unit("coef3_n1", 0, 16); }
static void div3_contains(void) { check_unit("div3", 0, 16); }
/* the clamp max(0, 1 - P): a guarded block key (ival_guarded_key) */
static void d_approx_contains(void) { check_unit("d_approx", 0, 16); check_unit("d_approx", 0, 10); }
static void ward_approx_contains(void) { check_unit("ward_approx", 0, 16); }
/* hf_lookup's bilinear lookups a + t (b - a), t in [0, 1]
 * (ival_interpolation), and its reciprocal, a logic element of z and of
 * z's top bits (ival_logic_dependent_input): on its stimuli's box and
 * on its formats' whole ranges (x, y in [-2, 2), z in [0, 2)) every
 * format holds its interval; before, 11 and 17 signals "could not". */
static void hf_lookup_contains(void)
{
    check_unit("hf_lookup", 0, 16);
    const unit_desc *u = unit_find("hf_lookup");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts f;
    char err[600] = "";
    tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err);
    tb_derived d;
    TST_CHECK(!tb_derive(u, &cfg, &f, NULL, &d, err, sizeof err), "%s", err);
    TST_EQ_INT(d.nfail, 0);
    tb_derived_free(&d);
}
/* div's remainder register under its divisor: with the precondition
 * n < d it declares, r is derived within [0, d) and every format holds
 * (before: r in [-1.99997, 3.99997], "cannot hold" in u1.15); runs on
 * stimuli with n < d stay within the derived intervals. Without the
 * precondition r is flagged again, and rightly: n = 1.5, d = 1 makes
 * 2 r - d = 2 on the first step, which u1.15 cannot hold, and a run with
 * it counts the overflow. */
static void div_contains(void)
{
    check_unit_keep("div", 0, 16, "r");
    const unit_desc *u = unit_find("div");
    unit_desc plain = *u;
    plain.below.lo = plain.below.hi = NULL;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts f;
    char err[600] = "";
    tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err);
    tb_derived d;
    for (int k = 0; k < 2; k++) {
        TST_CHECK(!tb_derive(k ? &plain : u, &cfg, &f, NULL, &d, err, sizeof err), "%s", err);
        TST_EQ_INT(d.nfail, k);
        int r = d.at[unit_sig_index(u, "r")];
        /* with n < d: r within [0, 2 - 2^-14] (d below 2, r below d, both on 2^-15) */
        if (!k) TST_CHECK(d.sigs[r].pre.lo == 0 && d.sigs[r].pre.hi == 65534, "r derived [%lld, %lld]",
                          (long long)d.sigs[r].pre.lo, (long long)d.sigs[r].pre.hi);
        tb_derived_free(&d);
    }
    vec_set vs;
    vec_set_init(&vs);
    vec_set_header(&vs, u->ref, &cfg.model);
    double row[3] = { 1.5, 1.0, 1.5 };
    vec_set_push(&vs, row);
    tb_result res;
    TST_EQ_INT(tb_run(u, &cfg, &f, &vs, NULL, &res, err, sizeof err), TB_OK);
    TST_CHECK(res.overflows > 0, "n = 1.5, d = 1: no overflow");
    tb_result_free(&res);
    vec_set_free(&vs);
}

/* Every statement a unit makes about a logic element (sim_logic_linear:
 * y = k x + e with e in [lo, hi]; sim_logic_monotone: y does not
 * decrease) against the function over every raw of its inputs, at small
 * widths where that is at most 2^20 combinations: for every unit that
 * makes one (div, and schlick and mschlick through the same divider). */
static void logic_statements_hold(void)
{
    int checked = 0;
    for (int w = 6; w <= 8; w += 2)
        for (size_t ui = 0; ui < unit_count(); ui++) {
            const unit_desc *u = unit_at(ui);
            unit_cfg cfg;
            unit_cfg_default(u, &cfg);
            cfg.width = w;
            unit_fmts f;
            char err[600];
            tb_built b;
            if (tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err) || tb_build(u, &cfg, &f, &b, err, sizeof err)) continue;
            for (uint32_t i = 0; i < sim_signal_count(b.c); i++) {
                const sim_signal *y = sim_signal_at(b.c, i);
                sim_prim_info pi;
                if (sim_prim_describe(y, &pi) || pi.kind != SIM_KIND_LOGIC || (!pi.lin && !pi.monotone)) continue;
                double combos = 1;
                for (int k = 0; k < pi.n; k++) combos *= (double)(pi.in[k]->raw_max - pi.in[k]->raw_min + 1);
                if (combos > 0x1p20) continue;
                int64_t v[8], prev = 0;
                for (int k = 0; k < pi.n; k++) v[k] = pi.in[k]->raw_min;
                int bad = 0;
                for (int first = 1;; first = 0) {
                    int64_t out = elem_at(y, v);
                    if (pi.lin) {
                        double x = sim_fx_to_real(v[pi.lin->i], pi.in[pi.lin->i]->fmt), yr = sim_fx_to_real(out, y->fmt);
                        double e = yr - pi.lin->k * x;
                        if (!(e >= pi.lin->lo && e <= pi.lin->hi) && !bad++)
                            TST_CHECK(0, "%s w%d %s: at x = %g, y = %g: e = %g outside [%g, %g]", u->name, w, y->name, x, yr,
                                      e, pi.lin->lo, pi.lin->hi);
                    }
                    if (pi.monotone && !first && out < prev && !bad++)
                        TST_CHECK(0, "%s w%d %s: decreases at raw %lld", u->name, w, y->name, (long long)v[0]);
                    prev = out;
                    int k = 0;
                    for (; k < pi.n; k++) {
                        if (v[k] < pi.in[k]->raw_max) { v[k]++; break; }
                        v[k] = pi.in[k]->raw_min;
                    }
                    if (k == pi.n) break;
                }
                checked++;
            }
            sim_free(b.c);
        }
    TST_CHECK(checked >= 6, "only %d statements checked", checked);
}

/* A multiplexer selected by a monotone test of z = p - q (the restoring
 * step: z >= 0 ? z : p): for intervals of p and q, every value through
 * sim_elem_eval lies in the derived interval, which is exactly the hull
 * of those values (each input only where the test selects it), where the
 * plain hull of both inputs is wider. */
static int64_t sign_test(const int64_t *in, void *u) { (void)u; return in[0] >= 0; }
static void ival_guarded_mux(void)
{
    sim_ctx *c = sim_new();
    sim_fmt fp, fz, u1;
    sim_fmt_make(0, 3, 2, &fp, NULL, 0);        /* p, q: u3.2, raws 0..31 */
    sim_fmt_make(1, 4, 2, &fz, NULL, 0);
    sim_fmt_make(0, 1, 0, &u1, NULL, 0);
    sim_signal *p = sim_signal_new(c, NULL, "p", fp, SIM_KIND_INPUT);
    sim_signal *q = sim_signal_new(c, NULL, "q", fp, SIM_KIND_INPUT);
    sim_signal *z = sim_sub(c, NULL, "z", fz, p, q);
    sim_signal *g = sim_logic(c, NULL, "g", u1, 1, &z, sign_test, NULL, 1);
    sim_logic_monotone(g);
    sim_signal *in[2] = { p, z };
    sim_signal *m = sim_mux(c, NULL, "m", fz, g, 2, in);
    sim_ival v[8], pre, post;
    memset(v, 0, sizeof v);
    int bad = 0, tighter = 0;
    for (int64_t plo = 0; plo < 32; plo += 3)
        for (int64_t phi = plo; phi < 32; phi += 4)
            for (int64_t qlo = 0; qlo < 32; qlo += 5)
                for (int64_t qhi = qlo; qhi < 32; qhi += 6) {
                    v[p->index] = (sim_ival){ plo, phi };
                    v[q->index] = (sim_ival){ qlo, qhi };
                    sim_ival_eval(z, v, &v[z->index], &post);
                    sim_ival_eval(g, v, &v[g->index], &post);
                    sim_ival_eval(m, v, &pre, &post);
                    sim_wide blo = 0, bhi = 0;
                    for (int64_t a = plo; a <= phi; a++)
                        for (int64_t b = qlo; b <= qhi; b++) {
                            int64_t zin[2] = { a, b }, zv = (int64_t)elem_at(z, zin), gv = (int64_t)elem_at(g, &zv);
                            int64_t min[3] = { gv, a, zv };
                            sim_wide mv = elem_at(m, min);
                            if ((a == plo && b == qlo) || mv < blo) blo = mv;
                            if ((a == plo && b == qlo) || mv > bhi) bhi = mv;
                        }
                    if ((pre.lo != blo || pre.hi != bhi) && !bad++)
                        TST_CHECK(0, "p [%lld, %lld] q [%lld, %lld]: [%lld, %lld], brute force [%lld, %lld]", (long long)plo,
                                  (long long)phi, (long long)qlo, (long long)qhi, (long long)pre.lo, (long long)pre.hi,
                                  (long long)blo, (long long)bhi);
                    sim_ival zv = v[z->index];
                    tighter += pre.hi < (phi > zv.hi ? phi : zv.hi) || pre.lo > (zv.lo < plo ? zv.lo : plo);
                }
    TST_EQ_INT(bad, 0);
    TST_CHECK(tighter > 0, "never tighter than the plain hull");
    sim_free(c);
}

/* A span unit's handshake depends on its data (the span's pixel count):
 * not derived, refused with a message rather than a wrong interval. */
static void span3_refused(void)
{
    const unit_desc *u = unit_find("span3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts f;
    char err[600] = "";
    tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err);
    tb_derived d;
    TST_CHECK(tb_derive(u, &cfg, &f, NULL, &d, err, sizeof err) == -1, "span3 derived");
    TST_CHECK(strstr(err, "depends on the data") != NULL, "message: %s", err);
}

/* The default horner3 at width 16 with a..d over [-64, 64) (their formats)
 * and t over [0, 2): the multiplier's interval is known by hand,
 * |mx1 * t| <= 64 * 2 = 128 (corner products), so s7.9 cannot hold it. */
static void horner3_format_ranges_by_hand(void)
{
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts f;
    char err[600];
    tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err);
    tb_derived d;
    TST_CHECK(!tb_derive(u, &cfg, &f, NULL, &d, err, sizeof err), "%s", err);
    int mul = d.at[7];
    TST_EQ_STR(u->sigs[7].name, "mul");
    /* mx1 in [-64, 64 - 2^-9], t in [0, 2 - 2^-15]: (-64)(2 - 2^-15) truncated to 9 fraction bits */
    TST_NEAR(d.sigs[mul].lo, floor(-64 * (2 - ldexp(1, -15)) * 512) / 512, 0);
    TST_NEAR(d.sigs[mul].hi, floor((64 - ldexp(1, -9)) * (2 - ldexp(1, -15)) * 512) / 512, 0);
    TST_CHECK(!d.sigs[mul].fits, "mul s7.9 holds [%g, %g]?", d.sigs[mul].lo, d.sigs[mul].hi);
    tb_derived_free(&d);
}

int main(void)
{
    TST_RUN(ival_matches_brute_force);
    TST_RUN(ival_selects);
    TST_RUN(ival_guarded_key);
    TST_RUN(ival_interpolation);
    TST_RUN(ival_logic_dependent_input);
    TST_RUN(horner3_format_ranges_by_hand);
    TST_RUN(horner3_every_schedule);
    TST_RUN(horner2_contains);
    TST_RUN(coef3_n1_contains);
    TST_RUN(div3_contains);
    TST_RUN(d_approx_contains);
    TST_RUN(ward_approx_contains);
    TST_RUN(hf_lookup_contains);
    TST_RUN(ival_guarded_mux);
    TST_RUN(logic_statements_hold);
    TST_RUN(div_contains);
    TST_RUN(span3_refused);
    TST_EXIT();
}
