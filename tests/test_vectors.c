/* test_vectors.c - the float reference and golden vectors (vectors/):
 * coefficient formulas against a Vandermonde solve, the /3 network against
 * closed forms, interpolation against Lagrange, shading at hand-computed
 * points, every model's generator, and the vector file reader/writer
 * (round trips, every class of bad input, failed writes). The references
 * here are written independently of the code under test. */
#include "tests/tst.h"
#include "tests/tst_ref.h"
#include "vectors/vectors.h"
#include "vectors/vec_file.h"
#include "vectors/ref_interp.h"
#include "vectors/ref_shading.h"
#include "units/unit.h"
#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <sys/stat.h>
#include <unistd.h>

/* A unit's reference model (its descriptor points at it). */
static const vec_model *model_of(const char *name)
{
    const unit_desc *u = unit_find(name);
    return u ? u->ref : NULL;
}

/* ---- independent references ------------------------------------------ */



static const double T_N1[4] = { 0, 1, 0.5, 0.25 };
static const double T_N2[4] = { 0, 1, 0.5, 0.75 };
static const double T_Q[3] = { 0, 1, 0.5 };

static double poly(const double *c, int k, double t)   /* highest first */
{
    double s = 0;
    for (int i = 0; i < k; i++) s += c[i] * pow(t, k - 1 - i);
    return s;
}

static double urand(uint64_t *s)    /* independent of vec_rng: an LCG */
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

/* ---- coefficient formulas -------------------------------------------- */

typedef void (*coef_fn)(const double *I, double *c);

static void check_coef(coef_fn fn, const double *tn, int k, const char *what)
{
    double I[4], c[4], want[4];
    /* Monomials t^p: coefficient vector is the unit vector e_(k-1-p). */
    for (int p = 0; p < k; p++) {
        for (int i = 0; i < k; i++) I[i] = pow(tn[i], p);
        fn(I, c);
        tst_vander(tn, I, k, want);
        for (int j = 0; j < k; j++) {
            double e = j == k - 1 - p ? 1.0 : 0.0;
            TST_CHECK(fabs(c[j] - e) <= 1e-12, "%s t^%d coef %d = %.17g", what, p, j, c[j]);
            TST_CHECK(fabs(want[j] - e) <= 1e-12, "%s solver t^%d coef %d", what, p, j);
        }
    }
    /* Random polynomials and random node values. */
    uint64_t s = 12345;
    for (int r = 0; r < 200; r++) {
        double truth[4];
        for (int j = 0; j < k; j++) truth[j] = 20 * urand(&s) - 10;
        for (int i = 0; i < k; i++) I[i] = poly(truth, k, tn[i]);
        fn(I, c);
        for (int j = 0; j < k; j++)
            TST_CHECK(fabs(c[j] - truth[j]) <= 1e-12 * 64, "%s random poly coef %d: %.17g vs %.17g",
                      what, j, c[j], truth[j]);
        for (int i = 0; i < k; i++) I[i] = urand(&s);
        fn(I, c);
        tst_vander(tn, I, k, want);
        for (int j = 0; j < k; j++)
            TST_CHECK(fabs(c[j] - want[j]) <= 1e-12, "%s random nodes coef %d: %.17g vs %.17g",
                      what, j, c[j], want[j]);
    }
}

static void coef_n1(const double *I, double *c) { ref_coef3_n1(I, c); }
static void coef_n2(const double *I, double *c) { ref_coef3_n2(I, c); }
static void coef_q(const double *I, double *c) { ref_coef2(I, c); }

static void t_coef_formulas(void)
{
    check_coef(coef_n1, T_N1, 4, "N1");
    check_coef(coef_n2, T_N2, 4, "N2");
    check_coef(coef_q, T_Q, 3, "quadratic");
    for (int i = 0; i < 4; i++) {
        TST_CHECK(ref_nodes_n1[i] == T_N1[i], "ref_nodes_n1[%d]", i);
        TST_CHECK(ref_nodes_n2[i] == T_N2[i], "ref_nodes_n2[%d]", i);
    }
    for (int i = 0; i < 3; i++) TST_CHECK(ref_nodes_q[i] == T_Q[i], "ref_nodes_q[%d]", i);
    /* The coefficient extremes over nodes in [0, 1] (vertices of the cube):
     * N1 A in [-24, 24], B in [-34, 34]. */
    double I[4] = { 0, 1, 0, 1 }, c[4];
    ref_coef3_n1(I, c);
    TST_NEAR(c[0], 24, 1e-13);
    double J[4] = { 1, 0, 1, 0 };
    ref_coef3_n1(J, c);
    TST_NEAR(c[1], 34, 1e-13);
}

static void t_horner(void)
{
    uint64_t s = 99;
    for (int r = 0; r < 200; r++) {
        double a = urand(&s) * 4 - 2, b = urand(&s) * 4 - 2, c = urand(&s) * 4 - 2,
               d = urand(&s) * 4 - 2, t = urand(&s);
        TST_NEAR(ref_horner3(a, b, c, d, t), a * t * t * t + b * t * t + c * t + d, 1e-13);
        TST_NEAR(ref_horner2(a, b, c, t), a * t * t + b * t + c, 1e-13);
    }
    TST_CHECK(ref_horner3(0.125, -0.5, 0.25, 0.75, 0.5) == 0.765625, "hand value");
}

/* ---- divide by 3 ----------------------------------------------------- */

static void t_div3_network(void)
{
    TST_CHECK(ref_div3_factor(3, REF_DIV3_PAPER) == 0.3359375, "paper factor %.17g",
              ref_div3_factor(3, REF_DIV3_PAPER));
    double rel = (ref_div3_factor(3, REF_DIV3_PAPER) - 1.0 / 3) / (1.0 / 3);
    TST_NEAR(rel, 0.0078125, 1e-15);
    TST_CHECK(ref_div3_factor(3, REF_DIV3_QUARTER) == 0.328125, "quarter factor");
    TST_CHECK(ref_div3_factor(0, REF_DIV3_PAPER) == 0.5, "paper, no terms");
    TST_CHECK(ref_div3_factor(0, REF_DIV3_QUARTER) == 0, "quarter, no terms");
    TST_CHECK(isnan(ref_div3_factor(3, 7)), "unknown series is NaN");
    /* Closed forms: paper 1/3 + 4^-t/6 (from above), quarter 1/3 - 4^-t/3
     * (from below); both converge, the error shrinking 4x per term. */
    double prev0 = 1, prev1 = 1;
    for (int t = 0; t <= 30; t++) {
        double f0 = ref_div3_factor(t, REF_DIV3_PAPER), f1 = ref_div3_factor(t, REF_DIV3_QUARTER);
        TST_NEAR(f0, 1.0 / 3 + pow(4, -t) / 6, 1e-16);
        TST_NEAR(f1, 1.0 / 3 - pow(4, -t) / 3, 1e-16);
        TST_CHECK(f0 >= 1.0 / 3 && f1 <= 1.0 / 3, "sides at %d", t);
        TST_CHECK(fabs(f0 - 1.0 / 3) <= prev0 && fabs(f1 - 1.0 / 3) <= prev1, "monotone at %d", t);
        prev0 = fabs(f0 - 1.0 / 3);
        prev1 = fabs(f1 - 1.0 / 3);
    }
    TST_CHECK(prev0 < 1e-16 && prev1 < 1e-16, "converged: %g %g", prev0, prev1);
    TST_CHECK(ref_div3_factor(1000000, REF_DIV3_PAPER) == ref_div3_factor(40, REF_DIV3_PAPER),
              "huge term count");
    TST_CHECK(ref_div3_factor(-5, REF_DIV3_PAPER) == 0.5, "negative terms");
    TST_CHECK(ref_div3_network(0.75, 3, REF_DIV3_PAPER) == 0.75 * 0.3359375, "network value");
    TST_CHECK(ref_div3_network(-1, 3, REF_DIV3_QUARTER) == -0.328125, "network negative");
}

/* ---- interpolation models -------------------------------------------- */

static void t_interp_lagrange(void)
{
    const vec_model *m3 = (&ref_model_interp3), *m2 = (&ref_model_interp2);
    TST_CHECK(m3 && m2, "models registered");
    if (!m3 || !m2) return;
    uint64_t s = 7;
    for (int L = 1; L <= 32; L *= 2) {
        vec_params p;
        vec_params_default(&p);
        p.L = L;
        int ni, no;
        char in[VEC_MAX_PORTS][16], out[VEC_MAX_PORTS][16];
        m3->ports(&p, &ni, in, &no, out);
        TST_EQ_INT(ni, 4);
        TST_EQ_INT(no, L);
        char want[16];
        snprintf(want, sizeof want, "y%d", L - 1);
        TST_EQ_STR(out[L - 1], want);
        m2->ports(&p, &ni, in, &no, out);
        TST_EQ_INT(ni, 3);
        TST_EQ_INT(no, L);
        for (int r = 0; r < 20; r++) {
            double I[4], y[32];
            for (int i = 0; i < 4; i++) I[i] = urand(&s);
            m3->eval(&p, I, y);
            for (int k = 0; k < L; k++)
                TST_NEAR(y[k], tst_lagrange(T_N1, I, 4, (double)k / L), 1e-12);
            /* At the nodes the interpolant is the node intensity, exactly:
             * no rounding residue such as -2e-16 for an intensity of 0. */
            if (L >= 4) TST_CHECK(y[0] == I[0] && y[L / 4] == I[3] && y[L / 2] == I[2],
                                  "cubic at nodes, L = %d", L);
            double c[4];
            ref_coef3_n1(I, c);
            for (int k = 0; k < L; k++)
                TST_NEAR(y[k], ref_horner3(c[0], c[1], c[2], c[3], (double)k / L), 1e-12);
            m2->eval(&p, I, y);
            for (int k = 0; k < L; k++)
                TST_NEAR(y[k], tst_lagrange(T_Q, I, 3, (double)k / L), 1e-12);
            if (L >= 2) TST_CHECK(y[0] == I[0] && y[L / 2] == I[2], "quadratic at nodes, L = %d", L);
        }
    }
    /* Invalid L: gen refuses it. */
    vec_params p;
    vec_params_default(&p);
    vec_set s3;
    int bad[] = { 0, 3, 64, -8 };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        p.L = bad[i];
        vec_set_init(&s3);
        TST_EQ_INT(m3->gen(&p, 0, 1, &s3), -1);
        vec_set_free(&s3);
        vec_set_init(&s3);
        TST_EQ_INT(m2->gen(&p, 0, 1, &s3), -1);
        vec_set_free(&s3);
    }
}

/* ---- every model ------------------------------------------------------ */

static int gen_default(const vec_model *m, uint64_t seed, size_t n, vec_set *s)
{
    vec_params p;
    vec_params_default(&p);
    vec_set_init(s);
    vec_set_header(s, m, &p);
    return m->gen(&p, n, seed, s);
}

static int rows_equal(const vec_set *a, const vec_set *b)
{
    if (a->n_rows != b->n_rows || a->n_in != b->n_in || a->n_out != b->n_out) return 0;
    for (size_t r = 0; r < a->n_rows; r++)
        if (memcmp(vec_row(a, r), vec_row(b, r), (size_t)(a->n_in + a->n_out) * sizeof(double)))
            return 0;
    return 1;
}

static void t_interp_ports(void)
{
    static const struct { const char *name, *in, *out; } want[] = {
        { "horner3", "a b c d t", "y" },
        { "horner2", "a b c t", "y" },
        { "div3", "x", "y" },
        { "coef3_n1", "i1 i2 i3 i4", "a b c d" },
        { "coef3_n2", "i1 i2 i3 i4", "a b c d" },
        { "coef2", "i1 i2 i3", "a b c" },
        { "interp3", "i1 i2 i3 i4", "y0 y1 y2 y3 y4 y5 y6 y7" },
        { "interp2", "i1 i2 i3", "y0 y1 y2 y3 y4 y5 y6 y7" },
    };
    static const vec_model *const vec_models_interp[] = {
        &ref_model_horner3, &ref_model_horner2, &ref_model_div3, &ref_model_coef3_n1,
        &ref_model_coef3_n2, &ref_model_coef2, &ref_model_interp3, &ref_model_interp2, NULL };
    size_t n = 0;
    while (vec_models_interp[n]) n++;
    TST_EQ_INT(n, sizeof want / sizeof want[0]);
    for (size_t i = 0; i < n && i < sizeof want / sizeof want[0]; i++) {
        const vec_model *m = vec_models_interp[i];
        TST_EQ_STR(m->name, want[i].name);
        TST_CHECK(unit_find(want[i].name) && unit_find(want[i].name)->ref == m, "the unit %s points at it", want[i].name);
        vec_params p;
        vec_params_default(&p);
        vec_set s;
        vec_set_init(&s);
        vec_set_header(&s, m, &p);
        char got[VEC_MAX_PORTS * 16] = "";
        for (int k = 0; k < s.n_in; k++) { if (k) strcat(got, " "); strcat(got, s.in_names[k]); }
        TST_EQ_STR(got, want[i].in);
        got[0] = 0;
        for (int k = 0; k < s.n_out; k++) { if (k) strcat(got, " "); strcat(got, s.out_names[k]); }
        TST_EQ_STR(got, want[i].out);
        /* NULL params mean the defaults. */
        int ni, no;
        char in[VEC_MAX_PORTS][16], out[VEC_MAX_PORTS][16];
        m->ports(NULL, &ni, in, &no, out);
        TST_CHECK(ni == s.n_in && no == s.n_out, "%s ports(NULL)", m->name);
        /* gen gives an empty set the model's header, and refuses to append
         * to a set of another shape (2 in, 2 out: no unit of the interpolation paper). */
        vec_set g, w;
        vec_set_init(&g);
        TST_EQ_INT(m->gen(&p, 3, 1, &g), 0);
        TST_CHECK(!strcmp(g.unit, m->name) && g.n_in == s.n_in && g.n_out == s.n_out && g.n_rows == 3,
                  "%s gen into an empty set", m->name);
        vec_set_free(&g);
        vec_set_init(&w);
        w.n_in = 2; w.n_out = 2;
        TST_EQ_INT(m->gen(&p, 4, 1, &w), -1);
        vec_set_free(&w);
    }
}

/* Generic properties, for every registered model (other modules too). */
static void t_every_model(void)
{
    TST_CHECK(unit_count() >= 8, "count %zu", unit_count());
    for (size_t i = 0; i < unit_count(); i++) {
        const vec_model *m = unit_at(i)->ref;
        vec_params p;
        vec_params_default(&p);
        vec_set a, b, c, d;
        vec_set_init(&a);
        vec_set_header(&a, m, &p);
        TST_CHECK(a.n_in >= 1 && a.n_in <= VEC_MAX_PORTS && a.n_out >= 1 && a.n_out <= VEC_MAX_PORTS,
                  "%s port counts %d %d", m->name, a.n_in, a.n_out);
        for (int k = 0; k < a.n_in + a.n_out; k++) {
            const char *nk = k < a.n_in ? a.in_names[k] : a.out_names[k - a.n_in];
            TST_CHECK(nk[0] != 0, "%s port %d named", m->name, k);
        }
        vec_set_free(&a);
        TST_EQ_INT(gen_default(m, 1, 0, &a), 0);
        TST_EQ_INT(gen_default(m, 1, 0, &b), 0);
        TST_EQ_INT(gen_default(m, 2, 0, &c), 0);
        TST_EQ_INT(gen_default(m, 5, 10, &d), 0);
        TST_CHECK(a.n_rows >= 16 && a.n_rows <= 1000, "%s default rows %zu", m->name, a.n_rows);
        TST_EQ_INT(d.n_rows, 10);
        TST_CHECK(rows_equal(&a, &b), "%s: same seed, same rows", m->name);
        TST_CHECK(!rows_equal(&a, &c), "%s: another seed, other rows", m->name);
        double out[VEC_MAX_PORTS];
        int bad_eval = 0, bad_finite = 0;
        for (size_t r = 0; r < a.n_rows; r++) {
            const double *v = vec_row(&a, r);
            m->eval(&p, v, out);
            for (int k = 0; k < a.n_out; k++) bad_eval += out[k] != v[a.n_in + k];
            for (int k = 0; k < a.n_in + a.n_out; k++) bad_finite += !isfinite(v[k]);
        }
        TST_EQ_INT(bad_eval, 0);
        TST_EQ_INT(bad_finite, 0);
        vec_set_free(&a); vec_set_free(&b); vec_set_free(&c); vec_set_free(&d);
    }
}

/* Every model's rows streamed (vec_stream_gen: a generator on a thread,
 * blocks of 16384 rows) are its rows into a set, bit for bit, in order:
 * 17000 rows (two blocks, the last short) and one block exactly; a
 * stream closed after its first block stops its generator (no hang, no
 * leak under the sanitizers); the rows appended after the first block
 * leave the first block's as they are. */
static void t_gen_stream(void)
{
    static const size_t counts[] = { 17000, 16384, 7 };
    for (size_t i = 0; i < unit_count(); i++) {
        const vec_model *m = unit_at(i)->ref;
        vec_params p;
        vec_params_default(&p);
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
            size_t n = counts[c];
            vec_set a;
            vec_set_init(&a);
            vec_set_header(&a, m, &p);
            TST_EQ_INT(m->gen(&p, n, 3, &a), 0);
            char err[300];
            vec_stream *v = vec_stream_gen(m, &p, n, 3, &a, err, sizeof err);
            TST_CHECK(v != NULL, "%s: %s", m->name, err);
            if (!v) { vec_set_free(&a); continue; }
            size_t got = 0, blocks = 0, stride = (size_t)(a.n_in + a.n_out);
            int same = 1, rc;
            const vec_set *rows;
            while ((rc = vec_stream_next(v, &rows)) > 0) {
                blocks++;
                if (strcmp(rows->unit, a.unit) || rows->n_in != a.n_in || rows->n_out != a.n_out) same = 0;
                if (got + rows->n_rows > a.n_rows ||
                    memcmp(rows->data, vec_row(&a, got), rows->n_rows * stride * sizeof(double)))
                    same = 0;
                got += rows->n_rows;
            }
            TST_EQ_INT(rc, 0);
            TST_EQ_INT(got, a.n_rows);
            TST_EQ_INT(blocks, (n + 16383) / 16384);
            TST_CHECK(same, "%s: %zu rows streamed differ from the set's", m->name, n);
            vec_stream_close(v);
            /* left after the first block */
            v = vec_stream_gen(m, &p, n, 3, NULL, err, sizeof err);
            TST_EQ_INT(vec_stream_next(v, &rows), 1);
            vec_stream_close(v);
            /* the first block by vec_stream_next, the rest appended to a
             * set: the first block's rows stay as they were (the lanes
             * simulate them while the next are appended) */
            if (n > 16384) {
                v = vec_stream_gen(m, &p, n, 3, NULL, err, sizeof err);
                TST_EQ_INT(vec_stream_next(v, &rows), 1);
                size_t k = rows->n_rows;
                vec_set d;
                vec_set_init(&d);
                d.n_in = a.n_in; d.n_out = a.n_out;
                while ((rc = vec_stream_append(v, &d)) > 0) {}
                TST_EQ_INT(rc, 0);
                int kept = k + d.n_rows == a.n_rows && !memcmp(rows->data, a.data, k * stride * sizeof(double)) &&
                           !memcmp(d.data, vec_row(&a, k), d.n_rows * stride * sizeof(double));
                TST_CHECK(kept, "%s: the first block's rows or the appended ones differ from the set's", m->name);
                vec_stream_close(v);
                vec_set_free(&d);
            }
            vec_set_free(&a);
        }
    }
}

/* Does set s hold a row whose first k inputs are I (within 1e-15)? */
static int has_inputs(const vec_set *s, const double *I, int k)
{
    for (size_t r = 0; r < s->n_rows; r++) {
        int ok = 1;
        for (int i = 0; i < k && ok; i++) ok = fabs(vec_row(s, r)[i] - I[i]) <= 1e-15;
        if (ok) return 1;
    }
    return 0;
}

/* The default vectors of the node units hold every named span, split in 4,
 * every interval; node intensities stay in [0, 1]. */
static void t_gen_realistic(void)
{
    static const char *units[] = { "coef3_n1", "coef3_n2", "coef2", "interp3", "interp2" };
    for (size_t u = 0; u < sizeof units / sizeof units[0]; u++) {
        const vec_model *m = model_of(units[u]);
        TST_CHECK(m != NULL, "%s", units[u]);
        if (!m) continue;
        const double *tn = u == 1 ? T_N2 : (u == 2 || u == 4) ? T_Q : T_N1;
        int k = (u == 2 || u == 4) ? 3 : 4;
        vec_set s;
        TST_EQ_INT(gen_default(m, 3, 0, &s), 0);
        int missing = 0, out_of_range = 0;
        for (size_t i = 0; i < shade_span_count(); i++)
            for (int j = 0; j < 4; j++) {
                double I[4];
                for (int q = 0; q < k; q++) I[q] = shade_span_eval(shade_span_at(i), (j + tn[q]) / 4);
                if (!has_inputs(&s, I, k)) {
                    missing++;
                    printf("  %s: span %s interval %d missing\n", units[u], shade_span_at(i)->name, j);
                }
            }
        for (size_t r = 0; r < s.n_rows; r++)
            for (int q = 0; q < k; q++) out_of_range += !(vec_row(&s, r)[q] >= 0 && vec_row(&s, r)[q] <= 1);
        TST_EQ_INT(missing, 0);
        TST_EQ_INT(out_of_range, 0);
        vec_set_free(&s);
    }
    /* Horner: t covers all of [0, 1) -- the pixel grid k/8 on even rows,
     * off-grid values on odd rows, every sixteenth of [0, 1) hit, both
     * ends' neighbourhoods within 2^-15 -- and the coefficient extremes
     * (range edges) are in. */
    const char *hn[] = { "horner3", "horner2" };
    for (int h = 0; h < 2; h++) {
        const vec_model *m = model_of(hn[h]);
        vec_set s;
        TST_EQ_INT(gen_default(m, 3, 0, &s), 0);
        int tcol = h == 0 ? 4 : 3, bad_t = 0, grid = 0, off = 0, bins[16] = { 0 }, empty = 0;
        double amax = -1e9, amin = 1e9, tmax = 0, tmin = 1;
        for (size_t r = 0; r < s.n_rows; r++) {
            double t = vec_row(&s, r)[tcol];
            bad_t += !(t >= 0 && t < 1);
            if (t * 8 == floor(t * 8)) grid++;
            else off++;
            if (t >= 0 && t < 1) bins[(int)(t * 16)]++;
            if (t > 0) tmin = fmin(tmin, t);
            tmax = fmax(tmax, t);
            amax = fmax(amax, vec_row(&s, r)[0]);
            amin = fmin(amin, vec_row(&s, r)[0]);
        }
        for (int b = 0; b < 16; b++) empty += bins[b] == 0;
        TST_EQ_INT(bad_t, 0);
        TST_CHECK(grid >= (int)s.n_rows / 2 && off >= (int)s.n_rows / 3, "%s: %d on the grid, %d off", hn[h], grid, off);
        TST_EQ_INT(empty, 0);
        TST_CHECK(tmax >= 1 - 0x1p-15 && tmin <= 0x1p-15, "%s: t in [%g, %g]", hn[h], tmin, tmax);
        TST_NEAR(amax, h == 0 ? 24 : 4, 1e-12);     /* quadratic A = 2I1+2I2-4I3 */
        TST_NEAR(amin, h == 0 ? -24 : -4, 1e-12);
        vec_set_free(&s);
    }
    /* div3: x in [-1, 1), both ends' neighbourhood present. */
    vec_set s;
    TST_EQ_INT(gen_default((&ref_model_div3), 3, 0, &s), 0);
    double lo = 1, hi = -1;
    for (size_t r = 0; r < s.n_rows; r++) {
        lo = fmin(lo, vec_row(&s, r)[0]);
        hi = fmax(hi, vec_row(&s, r)[0]);
        TST_CHECK(vec_row(&s, r)[1] == vec_row(&s, r)[0] / 3, "exact x/3 row %zu", r);
    }
    TST_CHECK(lo == -1 && hi < 1 && hi > 0.99, "div3 range [%g, %g]", lo, hi);
    vec_set_free(&s);
}

/* ---- shading ---------------------------------------------------------- */

static shade_span base_span(shade_model model)
{
    shade_span s;
    memset(&s, 0, sizeof s);
    s.model = model;
    s.n0[2] = s.n1[2] = 1;
    s.p1[0] = 1;
    s.light_kind = s.view_kind = SHADE_DIRECTIONAL;
    s.view[2] = 1;
    s.kd = 1; s.ks = 1; s.n = 1;
    return s;
}

static void t_shading_points(void)
{
    const double c30 = sqrt(3) / 2;
    /* Lambert, light at 30 degrees, flat normal: kd cos 30. */
    shade_span s = base_span(SHADE_DIFFUSE);
    s.light[0] = 0.5; s.light[2] = c30; s.kd = 0.5;
    TST_NEAR(shade_span_eval(&s, 0.3), 0.5 * c30, 1e-15);
    /* Phong: R = (-0.5, 0, c30), R.V = c30, squared 0.75. */
    s.model = SHADE_PHONG; s.ks = 1; s.n = 2;
    TST_NEAR(shade_span_eval(&s, 0.7), 0.75, 1e-15);
    /* Blinn: H at 15 degrees, cos^4 15. */
    s.model = SHADE_BLINN; s.n = 4;
    TST_NEAR(shade_span_eval(&s, 0.1), pow(cos(acos(-1.0) / 12), 4), 1e-15);
    /* Diffuse + Phong = 0.5 c30 + 0.75 > 1: clamped. */
    s.model = SHADE_DIFFUSE_PHONG; s.n = 2;
    TST_CHECK(shade_span_eval(&s, 0.5) == 1, "clamped sum");
    s.ks = 0.25;
    TST_NEAR(shade_span_eval(&s, 0.5), 0.5 * c30 + 0.25 * 0.75, 1e-15);
    /* Interpolated, renormalized normal: ends at +-45 degrees, light on z:
     * at x = 1/4 the normal is (1, 0, 2)/sqrt 5, N.L = 2/sqrt 5. */
    s = base_span(SHADE_DIFFUSE);
    s.n0[0] = 1; s.n1[0] = -1;
    s.light[2] = 1;
    TST_NEAR(shade_span_eval(&s, 0.25), 2 / sqrt(5), 1e-15);
    TST_NEAR(shade_span_eval(&s, 0.5), 1, 1e-15);
    TST_NEAR(shade_span_eval(&s, 0), sqrt(0.5), 1e-15);
    TST_NEAR(shade_span_eval(&s, -3), sqrt(0.5), 1e-15);     /* clamped x */
    TST_NEAR(shade_span_eval(&s, NAN), sqrt(0.5), 1e-15);
    /* Point light at (0,0,1) over a span from (-1,0,0) to (1,0,0). */
    s = base_span(SHADE_DIFFUSE);
    s.p0[0] = -1;
    s.light_kind = SHADE_POINT; s.light[2] = 1;
    TST_NEAR(shade_span_eval(&s, 0), sqrt(0.5), 1e-15);
    TST_NEAR(shade_span_eval(&s, 0.5), 1, 1e-15);
    /* Degenerate: opposite end normals at x = 1/2, light on the surface. */
    s = base_span(SHADE_DIFFUSE);
    s.n1[2] = -1; s.light[2] = 1;
    TST_CHECK(shade_span_eval(&s, 0.5) == 0, "zero normal");
    s = base_span(SHADE_DIFFUSE);
    s.light_kind = SHADE_POINT;     /* at (0,0,0) = p(0) */
    TST_CHECK(shade_span_eval(&s, 0) == 0, "light on surface");
    /* Specular gated off when the light is behind the surface. */
    s = base_span(SHADE_PHONG);
    s.light[0] = 0.2; s.light[2] = -1;
    s.n = 1;
    TST_CHECK(shade_span_eval(&s, 0.5) == 0, "light behind");
    TST_EQ_STR(shade_model_name(SHADE_DIFFUSE_BLINN), "diffuse+blinn");
}

static void t_shading_named(void)
{
    const char *need[] = { "narrow_highlight", "highlight_at_edge", "flat", "dark",
                           "wide_diffuse", "terminator", "clamped_sum", "pinpoint" };
    for (size_t i = 0; i < sizeof need / sizeof need[0]; i++)
        TST_CHECK(shade_span_find(need[i]) != NULL, "span %s", need[i]);
    TST_CHECK(shade_span_find("nope") == NULL && shade_span_at(shade_span_count()) == NULL, "lookup");
    for (size_t i = 0; i < shade_span_count(); i++)
        for (size_t j = i + 1; j < shade_span_count(); j++)
            TST_CHECK(strcmp(shade_span_at(i)->name, shade_span_at(j)->name), "unique names");
    const shade_span *dark = shade_span_find("dark"), *flat = shade_span_find("flat");
    const shade_span *edge = shade_span_find("highlight_at_edge");
    const shade_span *narrow = shade_span_find("narrow_highlight");
    const shade_span *wide = shade_span_find("wide_diffuse");
    if (!dark || !flat || !edge || !narrow || !wide) return;
    double xmax = 0, vmax = -1;
    for (int k = 0; k <= 4000; k++) {
        double x = k / 4000.0;
        TST_CHECK(shade_span_eval(dark, x) == 0, "dark at %g", x);
        TST_NEAR(shade_span_eval(flat, x), 0.4, 1e-15);
        double v = shade_span_eval(narrow, x);
        if (v > vmax) { vmax = v; xmax = x; }
    }
    /* Narrow highlight: peak strictly inside the interval (1/4, 1/2), and
     * already below 1% of the peak at that interval's nodes. */
    TST_CHECK(xmax > 0.3 && xmax < 0.45, "narrow peak at %g", xmax);
    TST_CHECK(shade_span_eval(narrow, 0.25) < 0.01 * vmax && shade_span_eval(narrow, 0.5) < 0.01 * vmax,
              "narrow highlight between nodes");
    /* Highlight exactly at x = 1/2: N = H there, so I = ks. */
    TST_NEAR(shade_span_eval(edge, 0.5), edge->ks, 1e-15);
    TST_CHECK(shade_span_eval(edge, 0.499) < shade_span_eval(edge, 0.5) &&
              shade_span_eval(edge, 0.501) < shade_span_eval(edge, 0.5), "edge peak");
    /* Wide diffuse: cos of the normal's tilt at the ends, 1 in the middle. */
    TST_NEAR(shade_span_eval(wide, 0), 0.18 / sqrt(1 + 0.18 * 0.18), 1e-15);
    TST_NEAR(shade_span_eval(wide, 0.5), 1, 1e-15);
    /* Random spans and all named spans stay in [0, 1]. */
    vec_rng r = { 42 };
    int bad = 0;
    for (int i = 0; i < 2000; i++) {
        shade_span s;
        shade_span_random(&r, &s);
        for (int k = 0; k <= 8; k++) {
            double v = shade_span_eval(&s, k / 8.0);
            bad += !(v >= 0 && v <= 1);
        }
    }
    for (size_t i = 0; i < shade_span_count(); i++)
        for (int k = 0; k <= 64; k++) {
            double v = shade_span_eval(shade_span_at(i), k / 64.0);
            bad += !(v >= 0 && v <= 1);
        }
    TST_EQ_INT(bad, 0);
}

/* ---- vector files ---------------------------------------------------- */

static char tmpdir[64];

static const char *tpath(const char *name)
{
    static char buf[4][400];        /* a few live at once */
    static int i;
    i = (i + 1) % 4;
    snprintf(buf[i], sizeof buf[i], "%s/%s", tmpdir, name);
    return buf[i];
}

static void put_file(const char *path, const char *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f) { printf("  cannot write %s\n", path); abort(); }
    fwrite(data, 1, len, f);
    fclose(f);
}

/* Files in tmpdir whose name contains sub. */
static int count_files(const char *sub)
{
    DIR *d = opendir(tmpdir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (strstr(e->d_name, sub)) n++;
    if (d) closedir(d);
    return n;
}

static void expect_header(vec_set *e, const char *unit)
{
    vec_params p;
    vec_params_default(&p);
    vec_set_init(e);
    vec_set_header(e, model_of(unit), &p);
}

static void t_file_roundtrip(void)
{
    for (size_t i = 0; i < unit_count(); i++) {
        const vec_model *m = unit_at(i)->ref;
        vec_set a, b;
        char err[512] = "";
        TST_EQ_INT(gen_default(m, 11, 0, &a), 0);
        const char *path = tpath("round.vec");
        int rc = vec_file_write(path, &a, err, sizeof err);
        TST_CHECK(rc == 0, "%s write: %s", m->name, err);
        rc = vec_file_read(path, &b, &a, err, sizeof err);
        TST_CHECK(rc == 0, "%s read: %s", m->name, err);
        TST_EQ_STR(b.unit, a.unit);
        TST_CHECK(b.n_in == a.n_in && b.n_out == a.n_out, "%s counts", m->name);
        for (int k = 0; k < a.n_in && k < b.n_in; k++) TST_EQ_STR(b.in_names[k], a.in_names[k]);
        for (int k = 0; k < a.n_out && k < b.n_out; k++) TST_EQ_STR(b.out_names[k], a.out_names[k]);
        TST_CHECK(rows_equal(&a, &b), "%s: bitwise round trip", m->name);
        vec_set_free(&a);
        vec_set_free(&b);
    }
    /* Awkward doubles: -0, subnormals, extremes, non-dyadic. */
    vec_set a, b;
    char err[512] = "";
    expect_header(&a, "horner3");
    double v[6] = { -0.0, 4.9406564584124654e-324, DBL_MAX, -DBL_MIN, 0.1, 1.0 / 3 };
    double w[6] = { 2.2250738585072009e-308, -DBL_MAX, 1e-300, -123456789.123456789, 0, 0 };
    vec_set_push(&a, v);
    vec_set_push(&a, w);
    TST_EQ_INT(vec_file_write(tpath("odd.vec"), &a, err, sizeof err), 0);
    TST_EQ_INT(vec_file_read(tpath("odd.vec"), &b, NULL, err, sizeof err), 0);
    TST_CHECK(rows_equal(&a, &b), "odd doubles round trip bitwise");
    TST_CHECK(b.n_rows == 2 && signbit(vec_row(&b, 0)[0]), "-0 kept");
    vec_set_free(&b);
    /* The writer's exact text. */
    vec_set_free(&a);
    expect_header(&a, "horner3");
    double x[6] = { 0.125, -0.5, 0.25, 0.75, 0.5, 0.765625 };
    vec_set_push(&a, x);
    TST_EQ_INT(vec_file_write(tpath("text.vec"), &a, err, sizeof err), 0);
    FILE *f = fopen(tpath("text.vec"), "rb");
    char text[512] = "";
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    text[n] = 0;
    if (f) fclose(f);
    TST_EQ_STR(text, "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d t\n"
                     "# outputs: y\n0.125 -0.5 0.25 0.75 0.5 | 0.765625\n");
    vec_set_free(&a);
    TST_EQ_INT(count_files(".tmp-"), 0);
}

/* A bad file: reading it fails, naming the file and the line, with the
 * word(s) given in the message. */
static void bad_case(const char *name, const char *data, size_t len, int line,
                     const char *word, const char *unit)
{
    const char *path = tpath(name);
    put_file(path, data, len);
    vec_set s, e;
    expect_header(&e, unit ? unit : "horner3");
    char err[512] = "", want[300];
    vec_set_init(&s);
    int rc = vec_file_read(path, &s, &e, err, sizeof err);
    snprintf(want, sizeof want, "%s:%d: ", path, line);
    TST_CHECK(rc == -1, "%s: accepted", name);
    TST_CHECK(strncmp(err, want, strlen(want)) == 0, "%s: message '%s', expected to start '%s'",
              name, err, want);
    TST_CHECK(strstr(err, word) != NULL, "%s: message '%s' lacks '%s'", name, err, word);
    TST_CHECK(!strchr(err, '\n'), "%s: message has a newline", name);
    TST_CHECK(s.n_rows == 0 && s.data == NULL, "%s: set not left empty", name);
    unlink(path);
}
#define BAD(name, text, line, word) bad_case(name, text, sizeof text - 1, line, word, NULL)

#define HDR "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d t\n# outputs: y\n"
#define ROW "1 2 3 4 0.5 | 5\n"

static void t_file_bad(void)
{
    BAD("empty.vec", "", 1, "empty file");
    BAD("blank.vec", "\n  \n\t\n", 3, "empty file");
    BAD("unknown.vec", "a,b,c\n1,2,3\n", 1, "not a shadesim vector file");
    BAD("comment_first.vec", "\n# generated\n# shadesim vectors 1\n", 2, "not a shadesim");
    BAD("version.vec", "# shadesim vectors 2\n" ROW, 1, "unsupported");
    BAD("no_unit.vec", "# shadesim vectors 1\n# inputs: a b c d t\n# outputs: y\n" ROW, 4,
        "missing '# unit:'");
    BAD("no_inputs.vec", "# shadesim vectors 1\n# unit: horner3\n# outputs: y\n\n" ROW, 5,
        "missing '# inputs:'");
    BAD("no_outputs.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d t\n" ROW, 4,
        "missing '# outputs:'");
    BAD("other_unit.vec", "# shadesim vectors 1\n# unit: div3\n# inputs: x\n# outputs: y\n1 | 2\n",
        2, "file is for unit 'div3', expected 'horner3'");
    BAD("in_names.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d x\n# outputs: y\n" ROW,
        3, "inputs are 'a b c d x', expected 'a b c d t'");
    BAD("out_names.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d t\n# outputs: z\n" ROW,
        4, "outputs are 'z', expected 'y'");
    BAD("few_in.vec", HDR ROW "1 2 3 4 | 5\n", 6, "found 4 inputs, expected 5");
    BAD("many_in.vec", HDR "1 2 3 4 5 6 | 5\n", 5, "found 6 inputs, expected 5");
    BAD("many_out.vec", HDR ROW ROW "# c\n1 2 3 4 5 | 5 6\n", 8, "found 2 outputs, expected 1");
    BAD("no_out.vec", HDR "1 2 3 4 5 |\n", 5, "found 0 outputs, expected 1");
    BAD("no_bar.vec", HDR "1 2 3 4 5 6\n", 5, "missing '|'");
    BAD("two_bars.vec", HDR "1 2 3 4 5 | 6 | 7\n", 5, "more than one '|'");
    BAD("word.vec", HDR "1 2 abc 4 5 | 6\n", 5, "not a number: 'abc'");
    BAD("suffix.vec", HDR "1 2 3 4 0.5x | 6\n", 5, "not a number: '0.5x'");
    BAD("comma.vec", HDR "1,5 2 3 4 5 | 6\n", 5, "not a number: '1,5'");
    BAD("long_tok.vec", HDR "1 2 3 4 5 | 0123456789abcdefghijKLMNOPQRSTUVWXYZ\n", 5,
        "'0123456789abcdefghij...'");
    BAD("nan.vec", HDR "1 2 3 4 5 | nan\n", 5, "NaN");
    BAD("nan2.vec", HDR "NAN(0x1) 2 3 4 5 | 1\n", 5, "NaN");
    BAD("inf.vec", HDR ROW "1 2 3 -inf 5 | 1\n", 6, "infinite");
    BAD("infinity.vec", HDR "1 2 3 4 5 | Infinity\n", 5, "infinite");
    BAD("huge.vec", HDR "1e999 2 3 4 5 | 1\n", 5, "infinite");
    BAD("no_rows.vec", HDR "# nothing here\n\n", 6, "no vector rows");
    BAD("no_rows2.vec", HDR, 4, "no vector rows");
    BAD("nul.vec", HDR "1 2 3\0 4 5 | 6\n", 5, "binary data");
    BAD("elf.vec", "\x7f" "ELF\x02\x01\x01\0\0\0", 1, "binary data");
    BAD("ctrl.vec", HDR ROW "\x1b[31m1 2 3 4 5 | 6\n", 6, "binary data");
    BAD("cr.vec", HDR "1 2 3\r4 5 | 6\n", 5, "binary data");
    BAD("dup_unit.vec", "# shadesim vectors 1\n# unit: horner3\n# unit: horner3\n", 3, "duplicate");
    BAD("late_hdr.vec", HDR ROW "# inputs: a b c d t\n", 6, "after the first vector row");
    BAD("bad_name.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs: a b- c d t\n", 3,
        "bad port name 'b-'");
    BAD("long_name.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d abcdefghijklmnop\n",
        3, "too long");
    BAD("long_unit.vec", "# shadesim vectors 1\n# unit: horner3_with_a_very_long_unit_name\n", 2,
        "too long");
    BAD("no_names.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs:\n", 3, "no inputs named");
    BAD("dup_name.vec", "# shadesim vectors 1\n# unit: horner3\n# inputs: a a c d t\n", 3, "duplicate");
    /* Too many ports: VEC_MAX_PORTS + 1 inputs. */
    char many[1024] = "# shadesim vectors 1\n# unit: horner3\n# inputs:";
    for (int i = 0; i < VEC_MAX_PORTS + 1; i++) snprintf(many + strlen(many), sizeof many - strlen(many), " p%d", i);
    strcat(many, "\n");
    bad_case("many_ports.vec", many, strlen(many), 3, "too many inputs", NULL);
    /* A line over 64 KiB. */
    size_t big = 70000;
    char *lng = malloc(sizeof HDR + big + 2);
    memcpy(lng, HDR, sizeof HDR - 1);
    memset(lng + sizeof HDR - 1, '1', big);
    lng[sizeof HDR - 1 + big] = '\n';
    bad_case("long_line.vec", lng, sizeof HDR + big, 5, "longer than", NULL);
    free(lng);

    /* Missing file, a directory. */
    vec_set s;
    char err[512] = "";
    TST_EQ_INT(vec_file_read(tpath("does_not_exist.vec"), &s, NULL, err, sizeof err), -1);
    TST_CHECK(strstr(err, "does_not_exist.vec") != NULL, "message: %s", err);
    err[0] = 0;
    TST_EQ_INT(vec_file_read(tmpdir, &s, NULL, err, sizeof err), -1);
    TST_CHECK(strstr(err, tmpdir) != NULL, "message: %s", err);
    /* A small error buffer truncates, never overflows. */
    char tiny[8];
    put_file(tpath("t.vec"), "junk\n", 5);
    TST_EQ_INT(vec_file_read(tpath("t.vec"), &s, NULL, tiny, sizeof tiny), -1);
    TST_CHECK(strlen(tiny) == 7, "truncated message");
    TST_EQ_INT(vec_file_read(tpath("t.vec"), &s, NULL, NULL, 0), -1);
}

static void t_file_good_variants(void)
{
    vec_set s, e;
    char err[512] = "";
    expect_header(&e, "horner3");
    const char *ok[] = {
        HDR ROW,                                                    /* plain */
        "\n\n# shadesim vectors 1\r\n# unit: horner3\r\n# inputs: a b c d t\r\n"
        "# outputs: y\r\n1 2 3 4 0.5 | 5\r\n",                     /* CRLF, leading blanks */
        HDR "# a comment\n\n  \t1\t2 3 4 0.5|5   \n# unit-less comment\n1 2 3 4 0.5 | 5",
        "#shadesim   vectors 1\n#unit:horner3\n#  inputs:a b c d t\n# outputs:  y\n"
        "0x1p-3 -5e-1 .25 +4 0.5 | 5\n",
        HDR "# \xc3\xa9t\xc3\xa9 (UTF-8 in a comment)\n" ROW,
    };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        put_file(tpath("ok.vec"), ok[i], strlen(ok[i]));
        int rc = vec_file_read(tpath("ok.vec"), &s, &e, err, sizeof err);
        TST_CHECK(rc == 0, "variant %zu: %s", i, err);
        TST_CHECK(s.n_rows >= 1 && vec_row(&s, 0)[4] == 0.5 && vec_row(&s, 0)[5] == 5, "variant %zu values", i);
        vec_set_free(&s);
    }
    /* Without expect any unit's file is fine. */
    const char *dv = "# shadesim vectors 1\n# unit: div3\n# inputs: x\n# outputs: y\n3 | 1\n";
    put_file(tpath("d.vec"), dv, strlen(dv));
    TST_EQ_INT(vec_file_read(tpath("d.vec"), &s, NULL, err, sizeof err), 0);
    TST_EQ_STR(s.unit, "div3");
    vec_set_free(&s);
}

/* Mutated and random files: the reader answers 0 or -1 with a message
 * naming the file, and never crashes (run under ASan/UBSan). */
static void t_file_fuzz(void)
{
    vec_set a, s;
    char err[512];
    TST_EQ_INT(gen_default((&ref_model_coef3_n1), 1, 20, &a), 0);
    const char *src = tpath("fz_src.vec");
    TST_EQ_INT(vec_file_write(src, &a, err, sizeof err), 0);
    vec_set_free(&a);
    FILE *f = fopen(src, "rb");
    char good[8192];
    size_t glen = f ? fread(good, 1, sizeof good, f) : 0;
    if (f) fclose(f);
    TST_CHECK(glen > 100 && glen < sizeof good, "source file size %zu", glen);
    uint64_t rs = 5;
    char buf[8192];
    const char *path = tpath("fz.vec");
    int bad_msg = 0, accepted = 0;
    for (int it = 0; it < 400; it++) {
        size_t len = glen;
        memcpy(buf, good, glen);
        int kind = it % 4;
        if (kind == 0) len = (size_t)(urand(&rs) * glen);                 /* truncation */
        else if (kind == 1)                                                 /* byte flips */
            for (int k = 0; k < 3; k++) buf[(size_t)(urand(&rs) * glen)] = (char)(unsigned char)(urand(&rs) * 256);
        else if (kind == 2)                                                 /* random bytes */
            for (size_t k = 0; k < len; k++) buf[k] = (char)(unsigned char)(urand(&rs) * 256);
        else {                                                              /* printable junk */
            static const char cs[] = "0123456789.-+eE|# \nabcnaif";
            for (size_t k = 80; k < len; k++) buf[k] = cs[(size_t)(urand(&rs) * (sizeof cs - 1))];
        }
        put_file(path, buf, len);
        err[0] = 0;
        int rc = vec_file_read(path, &s, NULL, err, sizeof err);
        if (rc == 0) accepted++;
        else if (strncmp(err, path, strlen(path)) || err[strlen(path)] != ':') bad_msg++;
        vec_set_free(&s);
    }
    TST_EQ_INT(bad_msg, 0);
    TST_CHECK(accepted > 0 && accepted < 400, "accepted %d of 400", accepted);
}

static void t_file_write_fail(void)
{
    vec_set a;
    char err[512] = "";
    TST_EQ_INT(gen_default((&ref_model_div3), 1, 5, &a), 0);
    /* Directory does not exist. */
    const char *p1 = tpath("no/such/dir/x.vec");
    TST_EQ_INT(vec_file_write(p1, &a, err, sizeof err), -1);
    TST_CHECK(strstr(err, p1) != NULL && !strchr(err, '\n'), "message: %s", err);
    /* Target is a directory: the temp file is written, the rename fails,
     * and the temp file must be gone. */
    const char *p2 = tpath("adir");
    TST_EQ_INT(mkdir(p2, 0755), 0);
    err[0] = 0;
    TST_EQ_INT(vec_file_write(p2, &a, err, sizeof err), -1);
    TST_CHECK(strstr(err, p2) != NULL, "message: %s", err);
    TST_EQ_INT(count_files(".tmp-"), 0);
    rmdir(p2);
    /* An empty set is refused (the reader would refuse the file). */
    vec_set empty;
    expect_header(&empty, "div3");
    err[0] = 0;
    TST_EQ_INT(vec_file_write(tpath("empty_out.vec"), &empty, err, sizeof err), -1);
    TST_CHECK(strstr(err, "no vector rows") != NULL, "message: %s", err);
    TST_EQ_INT(count_files("empty_out"), 0);
    /* A non-finite value is refused before anything is written. */
    vec_row(&a, 0)[1] = NAN;
    err[0] = 0;
    TST_EQ_INT(vec_file_write(tpath("nan_out.vec"), &a, err, sizeof err), -1);
    TST_CHECK(strstr(err, "non-finite") != NULL, "message: %s", err);
    TST_EQ_INT(count_files("nan_out"), 0);
    vec_set_free(&a);
    /* An existing file is replaced whole. */
    put_file(tpath("old.vec"), "old content\n", 12);
    chmod(tpath("old.vec"), 0640);
    TST_EQ_INT(gen_default((&ref_model_div3), 1, 5, &a), 0);
    TST_EQ_INT(vec_file_write(tpath("old.vec"), &a, err, sizeof err), 0);
    vec_set b;
    TST_EQ_INT(vec_file_read(tpath("old.vec"), &b, NULL, err, sizeof err), 0);
    TST_CHECK(rows_equal(&a, &b), "replaced file");
    struct stat st;
    TST_CHECK(stat(tpath("old.vec"), &st) == 0 && (st.st_mode & 0777) == 0640, "mode kept %o",
              (unsigned)(st.st_mode & 0777));
    TST_CHECK(stat(tpath("text.vec"), &st) == 0 && (st.st_mode & 0777) == 0644, "new file mode %o",
              (unsigned)(st.st_mode & 0777));
    vec_set_free(&a);
    vec_set_free(&b);
    TST_EQ_INT(count_files(".tmp-"), 0);
}

static void remove_tmpdir(void)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        unlink(tpath(e->d_name));
    }
    if (d) closedir(d);
    rmdir(tmpdir);
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/test_vectors-XXXXXX");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    TST_RUN(t_coef_formulas);
    TST_RUN(t_horner);
    TST_RUN(t_div3_network);
    TST_RUN(t_interp_lagrange);
    TST_RUN(t_interp_ports);
    TST_RUN(t_every_model);
    TST_RUN(t_gen_realistic);
    TST_RUN(t_shading_points);
    TST_RUN(t_shading_named);
    TST_RUN(t_file_roundtrip);
    TST_RUN(t_file_bad);
    TST_RUN(t_file_good_variants);
    TST_RUN(t_file_fuzz);
    TST_RUN(t_file_write_fail);
    TST_RUN(t_gen_stream);
    remove_tmpdir();
    TST_EXIT();
}
