/* ref_span.c - float reference of the span units (span1, span2, span3,
 * span23): the polynomial through the nodes, with exact 1/3, at the pixels
 * t = k/dv of one interval.
 *
 * Ports: i1 i2 [i3 [i4]] n dv [deg] | y0 .. y{L-1}. A vector always has L
 * outputs (the generic testbench gives every item the same beats), so the
 * default vectors have n = L: full intervals (dv = L) and span-final ones
 * that happen to be L long (dv = L - 1, t reaching 1 at the last pixel),
 * alternately; span23's rows alternate degree 3 and 2 over those.
 * Intervals of other lengths go through tb_span_run (testbench/study/tb_span.h).
 *
 * The interpolant is evaluated in Lagrange form (as ref_interp.c does for
 * interp3/interp2): no coefficient formula and no Horner cancellation, and
 * exact at the nodes.
 */
#include "vectors/vectors.h"
#include "vectors/ref_interp.h"
#include "vectors/ref_shading.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

enum { SP_LIN, SP_QUAD, SP_CUBE, SP_ADAPT };

static const double nodes_lin[2] = { 0, 1 };

static int span_L(const vec_params *p)
{
    vec_params d;
    if (!p) { vec_params_default(&d); p = &d; }
    return p->L >= 2 && p->L <= 64 ? p->L : -1;
}
/* ports and eval cannot report errors: a bad L falls back to 8 there for
 * memory safety; gen refuses it. */
static int safe_L(const vec_params *p) { int L = span_L(p); return L > 0 ? L : 8; }
static int n2_of(const vec_params *p) { return p && p->nodes == 1; }

static int nin_of(int kind) { return kind == SP_LIN ? 2 : kind == SP_QUAD ? 3 : 4; }

static void ports(int kind, const vec_params *p, int *n_in, char in[][16], int *n_out, char out[][16])
{
    static const char *const names[] = { "i1", "i2", "i3", "i4" };
    int k = 0, L = safe_L(p);
    for (int i = 0; i < nin_of(kind); i++) snprintf(in[k++], 16, "%s", names[i]);
    snprintf(in[k++], 16, "n");
    snprintf(in[k++], 16, "dv");
    if (kind == SP_ADAPT) snprintf(in[k++], 16, "deg");
    *n_in = k;
    for (int i = 0; i < L && i < VEC_MAX_PORTS; i++) snprintf(out[i], 16, "y%d", i);
    *n_out = L < VEC_MAX_PORTS ? L : VEC_MAX_PORTS;
}

/* Node positions and count of the interpolant a row asks for. */
static const double *row_nodes(int kind, const vec_params *p, const double *in, int *k)
{
    if (kind == SP_LIN) { *k = 2; return nodes_lin; }
    if (kind == SP_QUAD || (kind == SP_ADAPT && floor(in[6]) == 2)) { *k = 3; return ref_nodes_q; }
    *k = 4;
    return n2_of(p) ? ref_nodes_n2 : ref_nodes_n1;
}

static void eval(int kind, const vec_params *p, const double *in, double *out)
{
    int L = safe_L(p), k, ni = nin_of(kind);
    const double *tn = row_nodes(kind, p, in, &k);
    double dv = floor(in[ni + 1]);
    for (int i = 0; i < L && i < VEC_MAX_PORTS; i++) out[i] = ref_lagrange(tn, in, k, dv > 0 ? i / dv : 0);
}

/* ---- gen ----------------------------------------------------------------- */

static uint64_t model_seed(const char *name, uint64_t seed)
{
    uint64_t h = 0xcbf29ce484222325ull;         /* FNV-1a */
    for (; *name; name++) h = (h ^ (unsigned char)*name) * 0x100000001b3ull;
    return seed ^ h;
}

/* Node intensities of row r at positions tn[0..k-1] of an interval:
 * every named span split into M = 4, 2, 8, 1 intervals, each interval in
 * turn; then every 0/1 pattern of the nodes (the coefficients' extremes);
 * then random spans, split into M in {1, 2, 4, 8, 16}, a random interval. */
static void row_intensities(size_t r, const double *tn, int k, vec_rng *rng, double *I)
{
    static const int splits[] = { 4, 2, 8, 1 };
    size_t nsp = shade_span_count();
    for (int m = 0; m < 4; m++) {
        size_t M = (size_t)splits[m];
        if (r < M * nsp) {
            const shade_span *s = shade_span_at(r / M);
            for (int i = 0; i < k; i++) I[i] = shade_span_eval(s, ((double)(r % M) + tn[i]) / (double)M);
            return;
        }
        r -= M * nsp;
    }
    if (r < ((size_t)1 << k)) {
        for (int b = 0; b < k; b++) I[b] = (double)((r >> b) & 1);
        return;
    }
    shade_span s;
    shade_span_random(rng, &s);
    int M = 1 << (vec_rng_next(rng) % 5);
    int j = (int)(vec_rng_next(rng) % (uint64_t)M);
    for (int i = 0; i < k; i++) I[i] = shade_span_eval(&s, (j + tn[i]) / M);
}

static int gen(int kind, const vec_model *m, const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    int L = span_L(p);
    if (L < 0 || (p && p->nodes != 0 && p->nodes != 1)) return -1;
    vec_set h;
    vec_set_init(&h);
    vec_set_header(&h, m, p);
    if (out->n_in == 0 && out->n_out == 0) vec_set_header(out, m, p);
    else if (h.n_in != out->n_in || h.n_out != out->n_out) return -1;
    if (n == 0) n = 256;
    int ni = nin_of(kind), k = ni;
    const double *tn = kind == SP_LIN ? nodes_lin : kind == SP_QUAD ? ref_nodes_q
                     : n2_of(p) ? ref_nodes_n2 : ref_nodes_n1;
    vec_rng rng = { model_seed(m->name, seed) };
    double v[2 * VEC_MAX_PORTS + 8];
    for (size_t r = 0; r < n; r++) {
        memset(v, 0, sizeof v);
        row_intensities(r, tn, k, &rng, v);
        v[ni] = L;
        v[ni + 1] = r & 1 ? L - 1 : L;
        if (kind == SP_ADAPT) v[ni + 2] = (r >> 1) & 1 ? 2 : 3;
        m->eval(p, v, v + out->n_in);
        if (vec_set_push(out, v)) return -1;
    }
    return 0;
}

#define SPAN_MODEL_FNS(sfx, KIND, M) \
    static void ports_##sfx(const vec_params *p, int *n_in, char in[][16], int *n_out, char out[][16]) \
    { ports(KIND, p, n_in, in, n_out, out); } \
    static void eval_##sfx(const vec_params *p, const double *in, double *out) { eval(KIND, p, in, out); } \
    static int gen_##sfx(const vec_params *p, size_t n, uint64_t seed, vec_set *out) \
    { return gen(KIND, &M, p, n, seed, out); }

SPAN_MODEL_FNS(1, SP_LIN, ref_model_span1)
SPAN_MODEL_FNS(2, SP_QUAD, ref_model_span2)
SPAN_MODEL_FNS(3, SP_CUBE, ref_model_span3)
SPAN_MODEL_FNS(23, SP_ADAPT, ref_model_span23)

/* linear I1 + (I2 - I1) t at the pixels t = k/dv of an interval (params L) */
const vec_model ref_model_span1 = {
    "span1",
    ports_1, eval_1, gen_1 };
/* quadratic through I(0), I(1), I(1/2) at t = k/dv (params L) */
const vec_model ref_model_span2 = {
    "span2",
    ports_2, eval_2, gen_2 };
/* cubic through node set N1 or N2 at t = k/dv (params L, nodes) */
const vec_model ref_model_span3 = {
    "span3",
    ports_3, eval_3, gen_3 };
/* quadratic (deg 2) or cubic (deg 3) through the nodes at t = k/dv (params L, nodes) */
const vec_model ref_model_span23 = {
    "span23",
    ports_23, eval_23, gen_23 };

