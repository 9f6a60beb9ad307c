/* test_toggle.c - switching activity: settled bit toggles per signal
 * (sim/sim_toggle.h), the batch mode's counts (sim/sim_batch.h), and the
 * testbench's (tb_ppa.toggles, per signal).
 *
 *  - hand-built designs with counts known by hand: a counter register
 *    (the bits its values flip, summed independently), and a subtractor
 *    that glitches within a time step and settles back (0 toggles);
 *  - a run's counts equal the bit changes in the VCD the same run dumps,
 *    read back here with a parser of our own (several units);
 *  - every unit the batch testbench runs: per lane, per signal, the
 *    batch's toggles and energy equal tb_run's for that lane alone; the
 *    span units' lanes (tb_span_run_lanes) equal tb_span_run's. */
#include "tests/tst.h"
#include "sim/sim_toggle.h"
#include "sim/sim_batch.h"
#include "sim/sim_prim.h"
#include "sim/sim_energy.h"
#include "testbench/tb.h"
#include "testbench/tb_batch.h"
#include "testbench/study/tb_span.h"
#include "testbench/study/tb_scene.h"
#include <unistd.h>

static int bits_of(uint64_t x)
{
    int n = 0;
    for (; x; x >>= 1) n += (int)(x & 1);
    return n;
}

/* q <= q + 1 in u4 (wrapping), N clocks: q's toggles are the bits that
 * differ between k - 1 and k (mod 16), k = 1..N; the adder's output n =
 * q + 1 flips the same bits one step ahead; the clock toggles twice a
 * period. The batch counts the same in each of 70 lanes (two words of
 * lanes: its general settle, not the one-word one). */
static void t_counter(void)
{
    enum { N = 37 };
    sim_fmt u4 = { .is_signed = 0, .ibits = 4, .fbits = 0, .width = 4 };
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_scope *sc = sim_scope_new(c, NULL, "cnt");
    sim_signal *one = sim_const_raw(c, sc, "one", u4, 1);
    sim_signal *q = sim_reg(c, sc, "q", u4, clk, NULL, NULL, NULL, 0);
    sim_signal *n = sim_add(c, sc, "n", u4, q, one);
    sim_reg_connect(q, n);
    sim_clock(c, clk, 5, 5);
    sim_toggle *t = sim_toggle_new(c);
    TST_CHECK(t != NULL, "out of memory");
    if (!t) { sim_free(c); return; }
    TST_EQ_INT(sim_run(c, 10 * N), SIM_OK);   /* rises at 5 .. 10N - 5, falls at 10 .. 10N */
    uint64_t want_q = 0, want_n = 0;
    for (int k = 1; k <= N; k++) {
        want_q += (uint64_t)bits_of((uint64_t)((k - 1) & 15) ^ (uint64_t)(k & 15));
        want_n += (uint64_t)bits_of((uint64_t)(k & 15) ^ (uint64_t)((k + 1) & 15));
    }
    TST_EQ_INT(sim_toggle_count(t, q), want_q);
    TST_EQ_INT(sim_toggle_count(t, n), want_n);
    TST_EQ_INT(sim_toggle_count(t, one), 0);
    TST_EQ_INT(sim_toggle_count(t, clk), 2 * N);
    TST_EQ_INT(sim_toggle_total(t), want_q + want_n);   /* the clock left out */
    sim_toggle_free(t);
    sim_free(c);

    /* the batch: a fresh design, never simulated by the kernel */
    c = sim_new();
    clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sc = sim_scope_new(c, NULL, "cnt");
    one = sim_const_raw(c, sc, "one", u4, 1);
    q = sim_reg(c, sc, "q", u4, clk, NULL, NULL, NULL, 0);
    n = sim_add(c, sc, "n", u4, q, one);
    sim_reg_connect(q, n);
    char err[200];
    sim_batch *b = sim_batch_new(c, clk, 70, err, sizeof err);
    TST_CHECK(b != NULL, "%s", err);
    if (b) {
        TST_CHECK(sim_batch_toggles(b, q) == NULL, "counting while off");
        TST_EQ_INT(sim_batch_toggles_on(b), 0);
        sim_batch_start(b);
        for (int k = 0; k < N; k++) sim_batch_cycle(b);
        for (uint32_t l = 0; l < 70; l++) {
            TST_EQ_INT(sim_batch_toggles(b, q)[l], want_q);
            TST_EQ_INT(sim_batch_toggles(b, n)[l], want_n);
            TST_EQ_INT(sim_batch_toggles(b, clk)[l], 0);
        }
        sim_batch_free(b);
    }
    sim_free(c);
}

/* y = x - copy(x): when x changes, y first sees the new x and the old copy
 * (a glitch: y changes), then settles back to 0 in the same time step. */
static void t_glitch_counts_zero(void)
{
    sim_fmt s8 = { .is_signed = 1, .ibits = 8, .fbits = 0, .width = 8 };
    sim_ctx *c = sim_new();
    sim_scope *sc = sim_scope_new(c, NULL, "g");
    sim_signal *x = sim_signal_new(c, sc, "x", s8, SIM_KIND_INPUT);
    sim_signal *xc = sim_shift(c, sc, "xc", s8, x, 0);
    sim_signal *y = sim_sub(c, sc, "y", s8, x, xc);
    sim_toggle *t = sim_toggle_new(c);
    TST_CHECK(t != NULL, "out of memory");
    if (!t) { sim_free(c); return; }
    sim_run(c, 1);
    static const int64_t vals[] = { 3, -7, 100, 0, 1 };
    uint64_t want_x = 0;
    int64_t prev = 0;
    for (int i = 0; i < 5; i++) {
        sim_force(x, vals[i]);
        sim_run(c, (sim_time)(2 + i));
        want_x += (uint64_t)bits_of(((uint64_t)prev ^ (uint64_t)vals[i]) & 0xff);
        prev = vals[i];
    }
    TST_CHECK(y->changes > 0, "no glitch happened (y changed %llu times)", (unsigned long long)y->changes);
    TST_EQ_INT(y->cur, 0);
    TST_EQ_INT(sim_toggle_count(t, y), 0);
    TST_EQ_INT(sim_toggle_count(t, x), want_x);
    TST_EQ_INT(sim_toggle_count(t, xc), want_x);
    sim_toggle_free(t);
    sim_free(c);
}

/* ---- the VCD check ---- */

typedef struct vvar { char id[64], path[200]; int width; uint64_t last, toggles; } vvar;

/* Read a dump: every `$var`'s full path, then count, after the $dumpvars
 * section, the bits of each value that differ from the last. Returns the
 * number of variables, -1 on a parse error. */
static int vcd_count(const char *path, vvar *v, int cap)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[512], scope[16][64];
    int depth = 0, nv = 0, body = 0, indump = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        char a[64], b[64], cc[64], d[128];
        if (!body) {
            if (sscanf(line, "$scope module %63s", a) == 1 && depth < 16) { snprintf(scope[depth++], 64, "%s", a); continue; }
            if (!strncmp(line, "$upscope", 8)) { depth--; continue; }
            if (!strncmp(line, "$enddefinitions", 15)) { body = 1; continue; }
            int w;
            if (sscanf(line, "$var %63s %d %63s %127s", a, &w, cc, d) == 4 && !strcmp(a, "wire") && nv < cap) {
                vvar *x = &v[nv++];
                memset(x, 0, sizeof *x);
                snprintf(x->id, sizeof x->id, "%s", cc);
                x->width = w;
                size_t at = 0;
                for (int i = 0; i < depth; i++) at += (size_t)snprintf(x->path + at, sizeof x->path - at, "%s.", scope[i]);
                snprintf(x->path + at, sizeof x->path - at, "%s", d);
            }
            continue;
        }
        if (!strncmp(line, "$dumpvars", 9)) { indump = 1; continue; }
        if (!strncmp(line, "$end", 4)) { indump = 0; continue; }
        if (line[0] == '#' || line[0] == 'r' || !line[0]) continue;
        uint64_t val = 0;
        const char *id;
        if (line[0] == 'b') {
            if (sscanf(line + 1, "%63s %63s", a, b) != 2) { fclose(f); return -1; }
            for (const char *p = a; *p; p++) val = val << 1 | (uint64_t)(*p == '1');
            id = b;
        } else if (line[0] == '0' || line[0] == '1') {
            val = (uint64_t)(line[0] == '1');
            id = line + 1;
        } else { fclose(f); return -1; }
        int k = 0;
        while (k < nv && strcmp(v[k].id, id)) k++;
        if (k == nv) continue;   /* not a wire we declared */
        if (!indump) v[k].toggles += (uint64_t)bits_of(v[k].last ^ val);
        v[k].last = val;
    }
    fclose(f);
    return nv;
}

static void vcd_case(const char *unit, const char *sched)
{
    const unit_desc *u = unit_find(unit);
    TST_CHECK(u != NULL, "%s", unit);
    if (!u) return;
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    for (int s = 0; sched && s < u->nsched; s++) if (!strcmp(u->sched[s].name, sched)) cfg.schedule = s;
    unit_fmts fm;
    char err[600];
    if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    vec_set vs;
    if (tb_make_vectors(u, &cfg, 40, 5, &vs, err, sizeof err)) { TST_CHECK(0, "%s", err); return; }
    char path[] = "/tmp/shadesim_toggle_XXXXXX";
    int fd = mkstemp(path);
    TST_CHECK(fd >= 0, "mkstemp");
    if (fd < 0) { vec_set_free(&vs); return; }
    close(fd);
    tb_opts o;
    memset(&o, 0, sizeof o);
    o.vcd_path = path;
    tb_result r;
    TST_EQ_INT(tb_run(u, &cfg, &fm, &vs, &o, &r, err, sizeof err), TB_OK);
    enum { CAP = 2000 };
    vvar *v = calloc(CAP, sizeof *v);
    int nv = vcd_count(path, v, CAP);
    TST_CHECK(nv > 0, "%s: the dump did not parse", unit);
    char prefix[80];
    snprintf(prefix, sizeof prefix, "top.%s.", u->name);
    size_t pl = strlen(prefix);
    int matched = 0, in_unit = 0;
    uint64_t sum = 0;
    for (int k = 0; k < nv; k++) {
        if (strncmp(v[k].path, prefix, pl)) continue;
        in_unit++;
        for (int i = 0; i < r.nsigs; i++)
            if (!strcmp(r.sigs[i].name, v[k].path + pl)) {
                matched++;
                sum += v[k].toggles;
                TST_CHECK(r.sigs[i].toggles == v[k].toggles, "%s %s: %s toggles %llu, the VCD has %llu", unit,
                          sched ? sched : "", r.sigs[i].name, (unsigned long long)r.sigs[i].toggles,
                          (unsigned long long)v[k].toggles);
            }
    }
    TST_EQ_INT(in_unit, r.nsigs);
    TST_EQ_INT(matched, r.nsigs);
    TST_EQ_INT(r.ppa.toggles, sum);
    TST_CHECK(sum > 0, "%s: nothing toggled", unit);
    /* the clock: one toggle per edge in the dump, 2 per cycle */
    for (int k = 0; k < nv; k++)
        if (!strcmp(v[k].path, "top.clk")) TST_CHECK(v[k].toggles >= 2 * r.stats.clocks - 1, "clock toggles %llu",
                                                     (unsigned long long)v[k].toggles);
    free(v);
    unlink(path);
    char gtkw[64];
    snprintf(gtkw, sizeof gtkw, "%s.gtkw", path);
    unlink(gtkw);
    tb_result_free(&r);
    vec_set_free(&vs);
}

static void t_vcd_matches_toggles(void)
{
    vcd_case("horner3", "paper");
    vcd_case("horner3", "pipe");
    vcd_case("div3", NULL);
    vcd_case("span3", NULL);
}

/* ---- the batch against the kernel ---- */

/* nl lanes of unit u, lane k with 4 + 5 (k % 7) items (so that lanes end
 * at different clocks and a word of lanes is partly busy): each lane's
 * toggles and energy against tb_run's on its items alone. Lanes compared
 * that came from the batch, added to *compared. */
static void lanes_equal_kernel(const unit_desc *u, int nl, size_t *compared)
{
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts fm;
    char err[600];
    if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return; }
    vec_set *vs = calloc((size_t)nl, sizeof *vs);
    tb_batch_lane *lanes = calloc((size_t)nl, sizeof *lanes);
    if (!vs || !lanes) { TST_CHECK(0, "out of memory"); free(vs); free(lanes); return; }
    int made = 0;
    for (; made < nl; made++) {
        if (tb_make_vectors(u, &cfg, 4 + (size_t)(made % 7) * 5, 21 + (uint64_t)made, &vs[made], err, sizeof err)) {
            TST_CHECK(0, "%s: %s", u->name, err);
            break;
        }
        lanes[made].vs = &vs[made];
        lanes[made].energy = 1;
    }
    int rc = made == nl ? tb_batch_run(u, &cfg, &fm, lanes, (uint32_t)nl, err, sizeof err) : TB_FAIL;
    for (int k = 0; k < made; k++) {
        if (rc == TB_OK) {
            tb_result r;
            char e2[600];
            TST_EQ_INT(tb_run(u, &cfg, &fm, &vs[k], NULL, &r, e2, sizeof e2), TB_OK);
            TST_EQ_INT(lanes[k].nsig, r.nsigs);
            for (int i = 0; i < r.nsigs && i < lanes[k].nsig; i++)
                TST_CHECK(lanes[k].sig_toggles[i] == r.sigs[i].toggles, "%s lane %d %s: batch %llu, kernel %llu",
                          u->name, k, r.sigs[i].name, (unsigned long long)lanes[k].sig_toggles[i],
                          (unsigned long long)r.sigs[i].toggles);
            TST_EQ_INT(lanes[k].toggles, r.ppa.toggles);
            TST_CHECK(lanes[k].energy_pj_per_item == r.ppa.energy_pj_per_item, "%s lane %d: %.17g pJ, kernel %.17g",
                      u->name, k, lanes[k].energy_pj_per_item, r.ppa.energy_pj_per_item);
            *compared += (size_t)lanes[k].batched;
            tb_result_free(&r);
        }
        free(lanes[k].raw);
        free(lanes[k].beat_cycle);
        free(lanes[k].sig_toggles);
        vec_set_free(&vs[k]);
    }
    free(vs);
    free(lanes);
}

static void t_batch_lanes_equal_kernel(void)
{
    size_t compared = 0;
    /* the vector loops the CPU has, then the scalar ones */
    for (size_t step = 0; step < 2 * unit_count(); step++) {
        size_t ui = step % unit_count();
        if (ui == 0) sim_batch_vector(step ? 0 : 8);
        lanes_equal_kernel(unit_at(ui), 4, &compared);
    }
    sim_batch_vector(8);
    TST_CHECK(compared > 80, "only %zu lanes came from the batch", compared);
}

/* More than a word of lanes (a unit over a list of items runs 128 a
 * group, tb_items.c): the count over whole words of mostly busy lanes
 * and lane by lane where few are, the vector loops and the scalar ones. */
static void t_batch_many_lanes_equal_kernel(void)
{
    static const char *const names[] = { "shade", "div" };
    size_t compared = 0;
    for (int v = 0; v < 2; v++) {
        sim_batch_vector(v ? 0 : 8);
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
            if (unit_find(names[i])) lanes_equal_kernel(unit_find(names[i]), 130, &compared);
    }
    sim_batch_vector(8);
    TST_CHECK(compared > 400, "only %zu lanes came from the batch", compared);
}

/* The span units' lanes, as a scene runs them: each lane's toggles and
 * energy equal tb_span_run's for its stream alone. */
static void t_span_lanes_equal_kernel(void)
{
    static const char *const units[] = { "span1", "span2", "span3", "span23" };
    uint64_t rng = 0x2545f4914f6cdd1dull;
    size_t batched = 0;
    for (int ui = 0; ui < 4; ui++) {
        const unit_desc *u = unit_find(units[ui]);
        TST_CHECK(u != NULL, "%s", units[ui]);
        if (!u) continue;
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        unit_fmts fm;
        char err[300];
        if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s", err); continue; }
        enum { N = 4, NI = 25 };
        tb_span_item items[N][NI];
        double *pix[N];
        tb_span_lane lanes[N];
        memset(lanes, 0, sizeof lanes);
        for (int k = 0; k < N; k++) {
            for (int i = 0; i < NI; i++) {
                rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
                tb_span_item *it = &items[k][i];
                it->n = 1 + (int)(rng % (uint64_t)cfg.L);
                it->dv = it->n > 1 ? it->n - 1 + (int)((rng >> 8) % (uint64_t)(cfg.L - it->n + 2)) : 1;
                for (int j = 0; j < 4; j++) it->node[j] = (double)((rng >> (16 + 8 * j)) & 0xff) / 256.0;
                it->deg = 2 + (int)((rng >> 60) & 1);
            }
            pix[k] = calloc((size_t)NI * (size_t)cfg.L, sizeof *pix[k]);
            lanes[k] = (tb_span_lane){ .items = items[k], .nitems = NI, .pix = pix[k], .energy = 1 };
        }
        tb_span_run_lanes(u, &cfg, &fm, lanes, N, 1);
        for (int k = 0; k < N; k++) {
            double *ref = calloc((size_t)NI * (size_t)cfg.L, sizeof *ref);
            tb_span_stats st;
            TST_EQ_INT(tb_span_run_energy(u, &cfg, &fm, items[k], NI, ref, &st, NULL, err, sizeof err), TB_OK);
            TST_EQ_INT(lanes[k].rc, TB_OK);
            TST_EQ_INT(lanes[k].st.toggles, st.toggles);
            TST_CHECK(lanes[k].st.energy_pj == st.energy_pj, "%s lane %d: %.17g pJ, kernel %.17g", u->name, k,
                      lanes[k].st.energy_pj, st.energy_pj);
            TST_CHECK(st.toggles > 0 && st.energy_pj > 0, "%s: nothing counted", u->name);
            batched += (size_t)lanes[k].batched;
            free(ref);
            free(pix[k]);
        }
    }
    TST_CHECK(batched >= 12, "only %zu span lanes came from the batch", batched);
}

/* The energy model's figures from its constants, worked by hand. */
static void t_energy_model(void)
{
    sim_fmt f8 = { .is_signed = 1, .ibits = 4, .fbits = 4, .width = 8 };
    sim_ctx *c = sim_new();
    sim_signal *clk = sim_bit_new(c, NULL, "clk", SIM_KIND_CLOCK);
    sim_signal *a = sim_signal_new(c, NULL, "a", f8, SIM_KIND_INPUT);
    sim_signal *b = sim_signal_new(c, NULL, "b", f8, SIM_KIND_INPUT);
    sim_signal *m = sim_mul(c, NULL, "m", f8, a, b);
    sim_signal *q = sim_reg(c, NULL, "q", f8, clk, m, NULL, NULL, 0);
    sim_signal *s = sim_add(c, NULL, "s", f8, a, b);
    double load = 0.5 * 1.89 * 1.1 * 1.1;   /* 1/2 C V^2, fJ */
    TST_NEAR(sim_energy_toggle_fj(q), 4.171 + load, 1e-12);
    TST_NEAR(sim_energy_toggle_fj(a), load, 1e-12);
    double add = 3.440 + load + 0.5 * (3.618 + load);
    TST_NEAR(sim_energy_toggle_fj(s), add, 1e-12);
    TST_NEAR(sim_energy_toggle_fj(m), (64 * (2.469 + load) + 56 * add) / 8, 1e-9);
    TST_EQ_INT(sim_energy_flops(c), 8);
    TST_NEAR(sim_energy_clock_fj(c), 8 * 8.019, 1e-12);
    sim_free(c);
}

/* A scene render: energy counted on the batch lanes equals the kernel's
 * band by band (no_batch), and asking for it changes no image or figure. */
static void t_scene_energy(void)
{
    scn_mesh face;
    char err[600];
    if (scn_mesh_builtin("face", 1, &face, err, sizeof err)) { TST_CHECK(0, "face: %s", err); return; }
    scn_desc d;
    scn_desc_default(&d);
    d.width = d.height = 64;
    tb_scene_result r[3];
    for (int k = 0; k < 3; k++) {
        /* 0: plain; 1: energy on the batch; 2: energy on the kernel alone */
        tb_scene_opts o = { 2, 0, NULL, NULL, k == 2, k > 0, NULL, NULL };
        TST_EQ_INT(tb_scene_render(&d, &face, &o, &r[k], err, sizeof err), TB_OK);
    }
    size_t n = (size_t)r[0].w * (size_t)r[0].h;
    for (int k = 1; k < 3; k++) {
        TST_CHECK(!memcmp(r[0].hw, r[k].hw, n * sizeof *r[0].hw), "render %d: the image changed", k);
        TST_EQ_INT(r[k].hwst.clocks, r[0].hwst.clocks);
        TST_EQ_INT(r[k].hwst.pixels, r[0].hwst.pixels);
    }
    TST_EQ_INT(r[0].hwst.toggles, 0);
    TST_CHECK(r[0].hwst.energy_pj == 0 && r[0].energy_pj_per_pixel == 0, "energy counted while not asked for");
    TST_CHECK(r[1].hwst.toggles > 0, "no toggles");
    TST_EQ_INT(r[1].hwst.toggles, r[2].hwst.toggles);
    TST_CHECK(r[1].hwst.energy_pj == r[2].hwst.energy_pj, "batch %.17g pJ, kernel %.17g", r[1].hwst.energy_pj,
              r[2].hwst.energy_pj);
    TST_NEAR(r[1].energy_pj_per_pixel, r[1].hwst.energy_pj / (double)r[1].hwst.pixels, 1e-12);
    for (int k = 0; k < 3; k++) tb_scene_free(&r[k]);
    scn_mesh_free(&face);
}

int main(void)
{
    TST_RUN(t_counter);
    TST_RUN(t_glitch_counts_zero);
    TST_RUN(t_energy_model);
    TST_RUN(t_vcd_matches_toggles);
    TST_RUN(t_batch_lanes_equal_kernel);
    TST_RUN(t_batch_many_lanes_equal_kernel);
    TST_RUN(t_span_lanes_equal_kernel);
    TST_RUN(t_scene_energy);
    TST_EXIT();
}
