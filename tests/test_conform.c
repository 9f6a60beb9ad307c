/* test_conform.c - every registered unit conforms to the unit contract.
 *
 * One test per unit of the registry (unit_count / unit_at), so that a new
 * unit is checked the moment its registry line exists, with nothing to add
 * here. For the unit at its default parameters and every schedule:
 *  - its descriptor is well formed: names unique, inputs then outputs then
 *    internals, counts within the limits, every required hook there, every
 *    parameter's default inside its own range and printed back as set;
 *  - its float reference (the oracle the descriptor points to) has the
 *    unit's ports, with beats expanded (y0..y{L-1}), and its default
 *    stimulus is the checked-in vector file's header;
 *  - it builds, and the signals its scope holds are exactly the listed
 *    (built) ones; the VCD of a run declares exactly those at the unit's
 *    top level, and GTKWave's vcd2fst accepts it (plain build only);
 *  - the head of its default vectors runs within the derived bound (the
 *    verdict ok: what makes `shadesim run` exit 0), every beat sampled;
 *  - --fmt rejects a name the unit does not have and the names of signals
 *    these parameters do not build.
 * tests/cli_conform.sh checks the same through the command line (exit
 * statuses, docs/units.md).
 */
#include "tests/tst.h"
#include "tests/tst_scope.h"
#include "testbench/tb.h"
#include "vectors/vec_file.h"
#include <unistd.h>

#define HEAD_ROWS 12    /* items of the default vectors each schedule runs */

static const unit_desc *cur;    /* the unit of the running test */

static int have(const char *tool)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* ------------------------------------------------------------ descriptor */

static void check_desc(const unit_desc *u)
{
    TST_CHECK(u->name && *u->name && strlen(u->name) < 16, "name");
    TST_CHECK(u->summary && *u->summary, "%s: summary", u->name);
    TST_CHECK(u->source && *u->source, "%s: source (the paper)", u->name);
    TST_CHECK(u->fmt_rule && *u->fmt_rule, "%s: fmt_rule", u->name);
    TST_CHECK(u->formats && u->beats && u->build && u->ideal && u->bound, "%s: a required hook is NULL", u->name);
    TST_CHECK(unit_find(u->name) == u, "%s: unit_find finds it (names unique)", u->name);
    TST_CHECK(u->nsigs >= 2 && u->nsigs <= UNIT_MAX_SIGS, "%s: nsigs %d", u->name, u->nsigs);
    TST_CHECK(u->nsched >= 1 && u->nsched <= UNIT_MAX_SCHED, "%s: nsched %d", u->name, u->nsched);
    TST_CHECK(u->nparams >= 0 && u->nparams <= UNIT_MAX_PARAMS, "%s: nparams %d", u->name, u->nparams);
    int nin = unit_n_in(u), nout = unit_n_out(u);
    TST_CHECK(nin >= 1 && nin <= UNIT_MAX_IO && nout >= 1 && nout <= UNIT_MAX_IO, "%s: %d in, %d out", u->name, nin, nout);
    /* Roles in order; every entry up to nsigs named, unique; none after. */
    for (int i = 0; i < u->nsigs; i++) {
        const unit_sig *s = &u->sigs[i];
        TST_CHECK(s->name && *s->name && s->what && *s->what, "%s: signal %d named and described", u->name, i);
        if (!s->name) continue;
        TST_CHECK(unit_sig_index(u, s->name) == i, "%s: signal '%s' declared twice", u->name, s->name);
        unit_role want = i < nin ? UNIT_SIG_IN : i < nin + nout ? UNIT_SIG_OUT : UNIT_SIG_INTERNAL;
        TST_CHECK(s->role == want, "%s: signal '%s' (%d) out of order: inputs, outputs, internals", u->name, s->name, i);
        TST_CHECK(s->role == UNIT_SIG_INTERNAL || !s->scheds, "%s: port '%s' must belong to every schedule", u->name, s->name);
        TST_CHECK(!s->scheds || s->scheds < (1u << u->nsched), "%s: '%s' names a schedule the unit lacks", u->name, s->name);
    }
    if (u->nsigs < UNIT_MAX_SIGS) TST_CHECK(!u->sigs[u->nsigs].name, "%s: a signal after nsigs", u->name);
    for (int k = 0; k < u->nsched; k++)
        TST_CHECK(u->sched[k].name && u->sched[k].what && unit_sched_find(u, u->sched[k].name) == k,
                  "%s: schedule %d", u->name, k);
    /* Each parameter's default lies in its range, and its printed form
     * sets it back (what `list` shows is what --param takes). */
    unit_cfg d;
    unit_cfg_default(u, &d);
    for (int p = 0; p < u->nparams; p++) {
        const unit_param *pp = &u->params[p];
        char val[64], err[256];
        unit_param_get(pp, &d, val, sizeof val);
        unit_cfg c2 = d;
        TST_CHECK(unit_param_set(u, &c2, pp->name, val, err, sizeof err) == 0, "%s: default %s=%s: %s", u->name, pp->name, val, err);
        TST_CHECK(!memcmp(&c2, &d, sizeof d), "%s: %s=%s does not set the default back", u->name, pp->name, val);
        TST_CHECK(pp->help && *pp->help, "%s: parameter %s has no help", u->name, pp->name);
    }
    int lim;
    int mw = unit_min_width(u, &d, &lim);
    TST_CHECK(mw >= 1 && mw <= d.width, "%s: smallest width %d above the default %d", u->name, mw, d.width);
}

/* ------------------------------------------------------------- reference */

static void join(char *dst, size_t len, char names[][16], int n)
{
    dst[0] = 0;
    for (int k = 0; k < n; k++) {
        if (k) strncat(dst, " ", len - strlen(dst) - 1);
        strncat(dst, names[k], len - strlen(dst) - 1);
    }
}

/* The oracle's ports are the unit's, and the default vector file is made
 * by that oracle for this unit. Returns the file's rows in *vs (0), or -1. */
static int check_reference(const unit_desc *u, const unit_cfg *cfg, vec_set *vs)
{
    const vec_model *m = u->ref;
    const vec_params *vp = &cfg->model;
    TST_CHECK(m != NULL, "%s: no float reference", u->name);
    if (!m) return -1;
    vec_set want, got;
    tb_expected_header(u, cfg, &want);
    vec_set_init(&got);
    vec_set_header(&got, m, vp);
    TST_EQ_STR(got.unit, u->name);
    char a[VEC_MAX_PORTS * 16], b[VEC_MAX_PORTS * 16];
    join(a, sizeof a, got.in_names, got.n_in);
    join(b, sizeof b, want.in_names, want.n_in);
    TST_CHECK(!strcmp(a, b), "%s: reference inputs '%s', unit inputs '%s'", u->name, a, b);
    join(a, sizeof a, got.out_names, got.n_out);
    join(b, sizeof b, want.out_names, want.n_out);
    TST_CHECK(!strcmp(a, b), "%s: reference outputs '%s', unit outputs '%s'", u->name, a, b);
    vec_set_free(&got);

    char path[256], err[512];
    snprintf(path, sizeof path, "vectors/%s.vec", u->name);
    vec_set_init(vs);
    if (vec_file_read(path, vs, &want, err, sizeof err)) {
        TST_CHECK(0, "%s: default stimulus: %s", u->name, err);
        return -1;
    }
    /* The file holds the oracle's default stimulus: its first rows are
     * what the reference generates (inputs and expected outputs). */
    vec_set gen;
    vec_set_init(&gen);
    vec_set_header(&gen, m, vp);
    TST_CHECK(m->gen(vp, 0, 1, &gen) == 0, "%s: gen", u->name);
    TST_EQ_INT(gen.n_rows, vs->n_rows);
    size_t stride = (size_t)(vs->n_in + vs->n_out);
    for (size_t r = 0; r < HEAD_ROWS && r < gen.n_rows && r < vs->n_rows; r++)
        for (size_t k = 0; k < stride; k++)
            TST_CHECK(vec_row(&gen, r)[k] == vec_row(vs, r)[k], "%s: row %zu value %zu: file %.17g, reference %.17g",
                      u->name, r, k, vec_row(vs, r)[k], vec_row(&gen, r)[k]);
    vec_set_free(&gen);
    if (vs->n_rows > HEAD_ROWS) vs->n_rows = HEAD_ROWS;
    return 0;
}

/* ------------------------------------------------------------- build, run */

static void check_build(const unit_desc *u, const unit_cfg *cfg)
{
    unit_fmts fm;
    char err[800];
    if (tb_formats(u, cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return; }
    tb_built bu;
    int unbuilt = tb_build(u, cfg, &fm, &bu, err, sizeof err);
    sim_ctx *c = bu.c;
    sim_scope *sc = bu.sc;
    unit_io io = bu.io;
    if (unbuilt) {
        TST_CHECK(0, "%s schedule %s: build: %s", u->name, u->sched[cfg->schedule].name, err);
        sim_free(c);
        return;
    }
    TST_CHECK(io.in_valid && io.in_ready && io.out_valid && io.scope == sc, "%s: handshake signals", u->name);
    for (int i = 0; i < unit_n_in(u); i++) TST_CHECK(io.in[i] != NULL, "%s: input %d", u->name, i);
    for (int i = 0; i < unit_n_out(u); i++) TST_CHECK(io.out[i] != NULL, "%s: output %d", u->name, i);
    for (int i = 0; i < u->nsigs; i++) {
        const char *nm = u->sigs[i].name;
        int built = unit_sig_built(u, i, cfg);
        TST_CHECK(!built || in_tree(sc, nm), "%s %s: listed '%s' is not built", u->name, u->sched[cfg->schedule].name, nm);
        TST_CHECK(built || !at_top(sc, nm), "%s %s: '%s' is built but not listed", u->name, u->sched[cfg->schedule].name, nm);
    }
    sim_free(c);
}

/* The names of the variables the VCD declares directly in the unit's
 * scope (not in its sub-scopes), space separated with spaces around. */
static void vcd_top_vars(const char *path, const char *unit, char *out, size_t len)
{
    FILE *f = fopen(path, "r");
    out[0] = 0;
    if (!f) return;
    char line[512];
    int depth = 0, unit_depth = -1;
    strncat(out, " ", len - strlen(out) - 1);
    while (fgets(line, sizeof line, f) && !strstr(line, "$enddefinitions")) {
        char a[64], b[64], c[64], d[64], e[64];
        if (sscanf(line, " $scope %63s %63s", a, b) == 2) {
            depth++;
            if (unit_depth < 0 && !strcmp(b, unit)) unit_depth = depth;
        } else if (strstr(line, "$upscope")) {
            if (depth == unit_depth) unit_depth = -2;   /* left it: done */
            depth--;
        } else if (depth == unit_depth && sscanf(line, " $var %63s %63s %63s %63s %63s", a, b, c, d, e) == 5) {
            strncat(out, d, len - strlen(out) - 1);
            strncat(out, " ", len - strlen(out) - 1);
        }
    }
    fclose(f);
}

static int has_word(const char *list, const char *w)
{
    char k[80];
    snprintf(k, sizeof k, " %s ", w);
    return strstr(list, k) != NULL;
}

static void check_run(const unit_desc *u, const unit_cfg *cfg, const vec_set *vs, int vcd)
{
    unit_fmts fm;
    char err[800], path[128];
    if (tb_formats(u, cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", u->name, err); return; }
    tb_opts o;
    memset(&o, 0, sizeof o);
    snprintf(path, sizeof path, "/tmp/shadesim_conform_%ld_%s.vcd", (long)getpid(), u->name);
    if (vcd) o.vcd_path = path;
    tb_result r;
    const char *sn = u->sched[cfg->schedule].name;
    int rc = tb_run(u, cfg, &fm, vs, &o, &r, err, sizeof err);
    TST_CHECK(rc == TB_OK, "%s %s: tb_run %d: %s", u->name, sn, rc, err);
    if (rc != TB_OK) return;
    TST_EQ_INT(r.vectors, vs->n_rows);
    TST_CHECK(r.ok && r.within_bound && r.bound_check == TB_CHECK_OK && r.golden_ok,
              "%s %s: verdict not ok on its default vectors: %s", u->name, sn, r.why);
    size_t values = 0;
    for (int k = 0; k < r.n_out; k++) values += r.out[k].n;
    TST_CHECK(values == vs->n_rows * (size_t)r.beats * (size_t)unit_n_out(u), "%s %s: %zu output values sampled",
              u->name, sn, values);
    for (int k = 0; k < r.n_out; k++) {
        TST_CHECK(r.out[k].max_err_ideal <= r.out[k].bound, "%s %s: %s error %g over its bound %g",
                  u->name, sn, r.out[k].name, r.out[k].max_err_ideal, r.out[k].bound);
    }
    tb_result_free(&r);
    if (!vcd) return;
    static char vars[1 << 16];     /* shade_cook declares about 1400 */
    vcd_top_vars(path, u->name, vars, sizeof vars);
    TST_CHECK(strlen(vars) > 2, "%s: the VCD has no scope %s", u->name, u->name);
    for (int i = 0; i < u->nsigs; i++) {
        const char *nm = u->sigs[i].name;
        int built = unit_sig_built(u, i, cfg), inv = has_word(vars, nm);
        /* a built signal may live in a sub-scope (a sub-network named
         * after it); one that is not built must not be at the top */
        TST_CHECK(built || !inv, "%s %s: the VCD declares '%s', which is not built", u->name, sn, nm);
        if (u->sigs[i].role != UNIT_SIG_INTERNAL) TST_CHECK(inv, "%s %s: port '%s' missing from the VCD", u->name, sn, nm);
    }
    if (tst_asan_build()) {
        /* the external tool is slow under ASan: the plain build runs it */
    } else if (have("vcd2fst")) {
        char cmd[400], fst[140];
        snprintf(fst, sizeof fst, "%s.fst", path);
        snprintf(cmd, sizeof cmd, "vcd2fst %s %s >/dev/null 2>&1", path, fst);
        TST_CHECK(system(cmd) == 0 && access(fst, R_OK) == 0, "%s %s: vcd2fst rejects the VCD", u->name, sn);
        unlink(fst);
    }
    unlink(path);
    char gtkw[160];
    snprintf(gtkw, sizeof gtkw, "%s.gtkw", path);
    unlink(gtkw);
}

/* --fmt takes exactly the built signals' names (and all). */
static void check_fmt_names(const unit_desc *u, const unit_cfg *cfg)
{
    unit_fmts fm;
    char err[800];
    const char *bad = "no_such_signal=s4.8";
    TST_CHECK(tb_formats(u, cfg, &bad, 1, &fm, err, sizeof err) == -1 && strstr(err, "no_such_signal"),
              "%s: --fmt %s accepted (%s)", u->name, bad, err);
    for (int i = 0; i < u->nsigs; i++) {
        char ov[64];
        const char *ovp = ov;
        snprintf(ov, sizeof ov, "%s=s4.8", u->sigs[i].name);
        int rc = tb_formats(u, cfg, &ovp, 1, &fm, err, sizeof err);
        TST_CHECK((rc == 0) == unit_sig_built(u, i, cfg), "%s %s: --fmt %s gives %d", u->name,
                  u->sched[cfg->schedule].name, ov, rc);
    }
}

static void conform(void)
{
    const unit_desc *u = cur;
    check_desc(u);
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    vec_set vs;
    if (check_reference(u, &cfg, &vs)) return;
    for (int s = 0; s < u->nsched; s++) {
        cfg.schedule = s;
        check_build(u, &cfg);
        check_fmt_names(u, &cfg);
        check_run(u, &cfg, &vs, 1);
    }
    vec_set_free(&vs);
}

/* A unit's defaults are its own: a descriptor whose table gives another
 * default gets it, and no other unit does; a field a unit does not list
 * keeps the shared value (the reference's own default for the model's
 * fields), whatever the other units' tables say. */
static void defaults_per_unit(void)
{
    const unit_desc *sh = unit_find("schlick"), *pn = unit_find("pow_n"), *dv = unit_find("div");
    TST_CHECK(sh && pn && dv, "schlick, pow_n, div registered");
    if (!sh || !pn || !dv) return;
    int k = -1;
    for (int p = 0; p < sh->nparams; p++) if (!strcmp(sh->params[p].name, "n")) k = p;
    TST_CHECK(k >= 0, "schlick has a parameter n");
    if (k < 0) return;
    static unit_desc mine;          /* large: not on the stack */
    mine = *sh;
    int other = (int)sh->params[k].def == 7 ? 9 : 7;
    mine.params[k].def = other;
    unit_cfg a, b, c, none;
    unit_cfg_default(&mine, &a);
    unit_cfg_default(sh, &b);
    unit_cfg_default(pn, &c);
    unit_cfg_default(NULL, &none);
    TST_EQ_INT(a.n, other);
    TST_EQ_INT(b.n, (int)sh->params[k].def);
    TST_EQ_INT(c.n, (int)pn->params[0].def);
    a.n = b.n;
    TST_CHECK(!memcmp(&a, &b, sizeof a), "only n differs between the two schlick descriptors");
    /* div lists no parameter: every field is the shared value */
    unit_cfg d;
    unit_cfg_default(dv, &d);
    TST_CHECK(!memcmp(&d, &none, sizeof d), "div (no parameters) has the shared values");
    vec_params vp;
    memset(&vp, 0, sizeof vp);          /* its padding, as unit_cfg_default's memset leaves it: memcmp reads it */
    vec_params_default(&vp);
    TST_CHECK(!memcmp(&none.model, &vp, sizeof vp), "the model's fields are the reference's defaults");
    TST_EQ_INT(none.width, 16);
    TST_EQ_INT(none.terms, 3);          /* the paper's /3 network: x/2 - x/8 - x/32 - x/128 */
    TST_EQ_INT(none.series, 0);
}

/* The registry: at least the units the docs describe, each once. */
static void registry(void)
{
    size_t n = unit_count();
    TST_CHECK(n >= 20, "unit_count %zu", n);
    TST_CHECK(unit_at(n) == NULL, "unit_at past the end");
    for (size_t i = 0; i < n; i++) {
        TST_CHECK(unit_at(i) != NULL, "unit_at(%zu)", i);
        for (size_t j = 0; j < i; j++) TST_CHECK(unit_at(i) != unit_at(j), "%s registered twice", unit_at(i)->name);
    }
}

int main(void)
{
    /* The checked-in vectors are read relative to the source tree. */
    TST_RUN(registry);
    TST_RUN(defaults_per_unit);
    for (size_t i = 0; i < unit_count(); i++) {
        char name[64];
        cur = unit_at(i);
        snprintf(name, sizeof name, "conform_%s", cur->name);
        tst_run(name, conform);
    }
    TST_EXIT();
}
