/* ref_interp.c - exact float models of the units of Nechyporuk & Romanyuk (2020) and
 * their golden-vector generators.
 *
 * Expected outputs are the exact function of each unit (the exact cubic,
 * the exact coefficients, the exact x/3), never the true shading value: a
 * testbench then measures the unit's quantization error only. The shading
 * spans of ref_shading.c are only where realistic node intensities come
 * from.
 */
#include "vectors/ref_interp.h"
#include "vectors/ref_shading.h"
#include "vectors/vectors.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

const double ref_nodes_n1[4] = { 0, 1, 0.5, 0.25 };
const double ref_nodes_n2[4] = { 0, 1, 0.5, 0.75 };
const double ref_nodes_q[3] = { 0, 1, 0.5 };

/* ---- the plain reference functions ---------------------------------- */

void ref_coef3_n1(const double I[4], double abcd[4])
{
    double I1 = I[0], I2 = I[1], I3 = I[2], I4 = I[3];
    abcd[0] = 8 * (I2 + 8 * I4) / 3 - 8 * (I1 + 2 * I3);
    abcd[1] = 2 * (7 * I1 - I2 + 10 * I3 - 16 * I4);
    abcd[2] = (I2 + 32 * I4) / 3 - 7 * I1 - 4 * I3;
    abcd[3] = I1;
}

void ref_coef3_n2(const double I[4], double abcd[4])
{
    double I1 = I[0], I2 = I[1], I3 = I[2], I4 = I[3];
    abcd[0] = 8 * (I2 + 2 * I3) - 8 * (8 * I4 + I1) / 3;
    abcd[1] = 2 * (3 * I1 - 5 * I2 - 14 * I3 + 16 * I4);
    abcd[2] = 3 * (I2 + 4 * I3) - (13 * I1 + 32 * I4) / 3;
    abcd[3] = I1;
}

void ref_coef2(const double I[3], double abc[3])
{
    double I1 = I[0], I2 = I[1], I3 = I[2];
    abc[0] = 2 * I1 + 2 * I2 - 4 * I3;
    abc[1] = 4 * I3 - 3 * I1 - I2;
    abc[2] = I1;
}

double ref_horner3(double a, double b, double c, double d, double t)
{
    return ((a * t + b) * t + c) * t + d;
}

double ref_horner2(double a, double b, double c, double t)
{
    return (a * t + b) * t + c;
}

/* The interpolants are evaluated in Lagrange form, not as coefficients +
 * Horner: the coefficients reach +-34 for intensities in [0, 1], so the
 * Horner form loses ~34 ulp to cancellation, while here every node
 * difference and t = k/L is dyadic, the weights are exact but for one
 * rounding where a 3 divides, and at a node the weights are exactly 0 and
 * 1, so y equals the node intensity exactly. */
double ref_lagrange(const double *tn, const double *I, int k, double t)
{
    double y = 0;
    for (int i = 0; i < k; i++) {
        double num = 1, den = 1;
        for (int j = 0; j < k; j++) {
            if (j == i) continue;
            num *= t - tn[j];
            den *= tn[i] - tn[j];
        }
        y += num / den * I[i];
    }
    return y;
}

void ref_interp3(const double I[4], int L, double *y)
{
    for (int i = 0; i < L; i++) y[i] = ref_lagrange(ref_nodes_n1, I, 4, (double)i / L);
}

void ref_interp2(const double I[3], int L, double *y)
{
    for (int i = 0; i < L; i++) y[i] = ref_lagrange(ref_nodes_q, I, 3, (double)i / L);
}

double ref_div3_factor(int terms, int series)
{
    /* Past 600 terms every further power of two underflows to 0. */
    if (terms < 0) terms = 0;
    if (terms > 600) terms = 600;
    double f;
    if (series == REF_DIV3_PAPER) {
        f = 0.5;
        for (int i = 1; i <= terms; i++) f -= ldexp(1.0, -(2 * i + 1));
    } else if (series == REF_DIV3_QUARTER) {
        f = 0;
        for (int i = 1; i <= terms; i++) f += ldexp(1.0, -2 * i);
    } else {
        return NAN;
    }
    return f;
}

double ref_div3_network(double x, int terms, int series)
{
    /* The factor is a short sum of powers of two, exact in a double for
     * up to 26 terms; one rounding in the product. */
    return x * ref_div3_factor(terms, series);
}

/* ---- parameters and ports ------------------------------------------- */

static vec_params params_or_default(const vec_params *p)
{
    vec_params d;
    if (p) return *p;
    vec_params_default(&d);
    return d;
}

/* L when it is a power of two in 1..32, else -1. */
static int valid_L(const vec_params *p)
{
    int L = params_or_default(p).L;
    if (L < 1 || L > 32 || (L & (L - 1))) return -1;
    return L;
}

/* ports and eval cannot report errors: an invalid L falls back to 8 there
 * for memory safety; gen refuses it, which is where a bad -p L=.. is seen. */
static int safe_L(const vec_params *p)
{
    int L = valid_L(p);
    return L > 0 ? L : 8;
}

static void set_names(int *n, char names[][16], const char *const *src)
{
    *n = 0;
    for (; src[*n]; (*n)++) snprintf(names[*n], 16, "%s", src[*n]);
}

static void set_ys(int *n, char names[][16], int L)
{
    for (int k = 0; k < L; k++) snprintf(names[k], 16, "y%d", k);
    *n = L;
}

static const char *const in_h3[] = { "a", "b", "c", "d", "t", NULL };
static const char *const in_h2[] = { "a", "b", "c", "t", NULL };
static const char *const in_x[] = { "x", NULL };
static const char *const out_y[] = { "y", NULL };
static const char *const in_i4[] = { "i1", "i2", "i3", "i4", NULL };
static const char *const in_i3[] = { "i1", "i2", "i3", NULL };
static const char *const out_abcd[] = { "a", "b", "c", "d", NULL };
static const char *const out_abc[] = { "a", "b", "c", NULL };

#define PORTS_FIXED(fn, IN, OUT) \
    static void fn(const vec_params *p, int *n_in, char in[][16], \
                   int *n_out, char out[][16]) \
    { (void)p; set_names(n_in, in, IN); set_names(n_out, out, OUT); }
PORTS_FIXED(ports_horner3, in_h3, out_y)
PORTS_FIXED(ports_horner2, in_h2, out_y)
PORTS_FIXED(ports_div3, in_x, out_y)
PORTS_FIXED(ports_coef3, in_i4, out_abcd)
PORTS_FIXED(ports_coef2, in_i3, out_abc)

static void ports_interp3(const vec_params *p, int *n_in, char in[][16],
                          int *n_out, char out[][16])
{
    set_names(n_in, in, in_i4);
    set_ys(n_out, out, safe_L(p));
}

static void ports_interp2(const vec_params *p, int *n_in, char in[][16],
                          int *n_out, char out[][16])
{
    set_names(n_in, in, in_i3);
    set_ys(n_out, out, safe_L(p));
}

/* ---- eval ------------------------------------------------------------ */

static void eval_horner3(const vec_params *p, const double *in, double *out)
{
    (void)p;
    out[0] = ref_horner3(in[0], in[1], in[2], in[3], in[4]);
}
static void eval_horner2(const vec_params *p, const double *in, double *out)
{
    (void)p;
    out[0] = ref_horner2(in[0], in[1], in[2], in[3]);
}
static void eval_div3(const vec_params *p, const double *in, double *out)
{
    (void)p;
    out[0] = in[0] / 3;
}
static void eval_coef3_n1(const vec_params *p, const double *in, double *out)
{
    (void)p;
    ref_coef3_n1(in, out);
}
static void eval_coef3_n2(const vec_params *p, const double *in, double *out)
{
    (void)p;
    ref_coef3_n2(in, out);
}
static void eval_coef2(const vec_params *p, const double *in, double *out)
{
    (void)p;
    ref_coef2(in, out);
}
static void eval_interp3(const vec_params *p, const double *in, double *out)
{
    int L = safe_L(p);
    if (!p->nodes) ref_interp3(in, L, out);
    else for (int i = 0; i < L; i++) out[i] = ref_lagrange(ref_nodes_n2, in, 4, (double)i / L);
}
static void eval_interp2(const vec_params *p, const double *in, double *out)
{
    ref_interp2(in, safe_L(p), out);
}

/* ---- node-intensity source for the generators ------------------------- */

/* A deterministic stream of node sets (intensities at the node positions
 * tn[0..k-1] of one interval):
 *  1. every named span of ref_shading, split into M equal intervals for
 *     each M of splits[] in turn, every interval (hard cases included);
 *  2. the range edges: every 0/1 pattern of the k nodes (the coefficients
 *     are linear in the nodes, so these reach their extremes, e.g. A = +-24
 *     and B = +-34 for N1);
 *  3. then forever: a random span (shade_span_random), split into
 *     M in {1,2,4,8,16}, a random interval. */
typedef struct node_stream {
    const double *tn;
    int k;
    const int *splits;
    int n_splits;
    size_t idx;         /* position in parts 1 and 2 */
    vec_rng rng;
} node_stream;

static void node_stream_init(node_stream *ns, const double *tn, int k,
                             const int *splits, int n_splits, uint64_t seed)
{
    ns->tn = tn; ns->k = k; ns->splits = splits; ns->n_splits = n_splits;
    ns->idx = 0;
    ns->rng.s = seed;
}

static void span_nodes(const shade_span *s, int M, int j, const double *tn,
                       int k, double *I)
{
    for (int i = 0; i < k; i++) I[i] = shade_span_eval(s, (j + tn[i]) / M);
}

static void node_next(node_stream *ns, double *I)
{
    size_t i = ns->idx, nsp = shade_span_count();
    for (int m = 0; m < ns->n_splits; m++) {
        size_t M = (size_t)ns->splits[m];
        if (i < M * nsp) {
            ns->idx++;
            span_nodes(shade_span_at(i / M), (int)M, (int)(i % M), ns->tn, ns->k, I);
            return;
        }
        i -= M * nsp;
    }
    if (i < ((size_t)1 << ns->k)) {
        ns->idx++;
        for (int b = 0; b < ns->k; b++) I[b] = (double)((i >> b) & 1);
        return;
    }
    shade_span s;
    shade_span_random(&ns->rng, &s);
    int M = 1 << (vec_rng_next(&ns->rng) % 5);
    int j = (int)(vec_rng_next(&ns->rng) % (uint64_t)M);
    span_nodes(&s, M, j, ns->tn, ns->k, I);
}

/* ---- gen --------------------------------------------------------------- */

/* A per-model stream seed, so that two units given the same seed do not
 * see the same random sequence. */
static uint64_t model_seed(const char *name, uint64_t seed)
{
    uint64_t h = 0xcbf29ce484222325ull;         /* FNV-1a */
    for (; *name; name++) h = (h ^ (unsigned char)*name) * 0x100000001b3ull;
    return seed ^ h;
}

/* Give out the model's header when it has none; refuse a set that already
 * has another shape. */
static int gen_begin(const vec_model *m, const vec_params *p, vec_set *out)
{
    if (out->n_in == 0 && out->n_out == 0) {
        vec_set_header(out, m, p);
        return 0;
    }
    vec_set h;
    vec_set_init(&h);
    vec_set_header(&h, m, p);
    return h.n_in == out->n_in && h.n_out == out->n_out ? 0 : -1;
}

/* Evaluate the row's outputs from its inputs and append it. */
static int push_row(const vec_model *m, const vec_params *p, vec_set *out, double *v)
{
    m->eval(p, v, v + out->n_in);
    return vec_set_push(out, v);
}

static const int splits_all[] = { 4, 2, 8, 1 };
static const int splits_4[] = { 4 };


/* Node-set units (coefficients, interpolation): one row per node set. */
static int gen_nodes(const vec_model *m, const double *tn, int k,
                     const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (gen_begin(m, p, out)) return -1;
    if (n == 0) n = 256;
    node_stream ns;
    node_stream_init(&ns, tn, k, splits_all, 4, model_seed(m->name, seed));
    double v[2 * VEC_MAX_PORTS];
    for (size_t r = 0; r < n; r++) {
        node_next(&ns, v);
        if (push_row(m, p, out, v)) return -1;
    }
    return 0;
}

static int gen_coef3_n1(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    return gen_nodes(&ref_model_coef3_n1, ref_nodes_n1, 4, p, n, seed, out);
}
static int gen_coef3_n2(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    return gen_nodes(&ref_model_coef3_n2, ref_nodes_n2, 4, p, n, seed, out);
}
static int gen_coef2(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    return gen_nodes(&ref_model_coef2, ref_nodes_q, 3, p, n, seed, out);
}
static int gen_interp3(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (valid_L(p) < 0) return -1;
    return gen_nodes(&ref_model_interp3, p->nodes ? ref_nodes_n2 : ref_nodes_n1, 4, p, n, seed, out);
}
static int gen_interp2(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (valid_L(p) < 0) return -1;
    return gen_nodes(&ref_model_interp2, ref_nodes_q, 3, p, n, seed, out);
}

/* t values at the range's edges that a pixel grid k/L never reaches: the
 * largest t below 1 at 8, 16, 24 and 53 fraction bits, the smallest above
 * 0, and one LSB either side of 1/2 (in a u1.F format they quantize to the
 * format's own extremes). */
static const double horner_t_edges[] = {
    0x1.fffep-1, 0x1p-16, 0x1.fep-1, 0x1.fffffep-1, 0x1.fffffffffffffp-1,
    0x1.fffcp-2, 0x1.0002p-1, 0x1p-8,
};

/* Horner units: the coefficients a coefficient unit would hand them (the
 * named spans split in 4, the 0/1 node patterns that give the coefficient
 * extremes, then random spans; N1 for the cubic), each at 8 positions t:
 * the pixels t = k/8 of an interval of L = 8 for even k, and for odd k a t
 * drawn uniformly from all of [0, 1) (the first rows: the edges above), so
 * that t's whole range is exercised and a search for t's format cannot
 * fit the pixel grid alone. */
static int gen_horner(const vec_model *m, int cubic, size_t n, uint64_t seed,
                      vec_set *out)
{
    if (gen_begin(m, NULL, out)) return -1;
    if (n == 0) n = cubic ? 640 : 512;
    const int L = 8;
    node_stream ns;
    node_stream_init(&ns, cubic ? ref_nodes_n1 : ref_nodes_q, cubic ? 4 : 3,
                     splits_4, 1, model_seed(m->name, seed));
    vec_rng rt = { model_seed(m->name, seed) ^ 0x9e3779b97f4a7c15ull };
    double I[4], v[2 * VEC_MAX_PORTS];
    int nc = cubic ? 4 : 3;
    size_t ne = sizeof horner_t_edges / sizeof horner_t_edges[0], odd = 0;
    for (size_t r = 0; r < n; r++) {
        if (r % L == 0) {
            node_next(&ns, I);
            if (cubic) ref_coef3_n1(I, v);
            else ref_coef2(I, v);
        }
        if (r % 2 == 0) v[nc] = (double)(r % L) / L;
        else {
            v[nc] = odd < ne ? horner_t_edges[odd] : vec_rng_unit(&rt);
            odd++;
        }
        if (push_row(m, NULL, out, v)) return -1;
    }
    return 0;
}

static int gen_horner3(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    (void)p;
    return gen_horner(&ref_model_horner3, 1, n, seed, out);
}
static int gen_horner2(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    (void)p;
    return gen_horner(&ref_model_horner2, 0, n, seed, out);
}

/* div3: the range picked is x in [-1, 1), a plain s1.F input.
 *  - edges: -1, the largest value below 1 in 16 bits, +-1 LSB of 8 and 16
 *    bits, multiples of 3 times a power of two (exact quotients), 1/3, 2/3;
 *  - then alternately a uniform random x in [-1, 1) and one of the sums the
 *    coefficient units divide by 3 (N1: I2 + 8 I4 and I2 + 32 I4; N2:
 *    I1 + 8 I4 and 13 I1 + 32 I4; range [0, 45]) for realistic node sets,
 *    scaled by 2^-6 into [0, 0.703]. x/3 commutes with that binary-point
 *    shift, so these are the coefficient unit's operand bit patterns in a
 *    [-1, 1) format. */
static const double div3_edges[] = {
    0, -1, 0x1.fffep-1, -0x1.fffep-1, 0x1p-16, -0x1p-16, 0x1p-8, -0x1p-8,
    0x1.fep-1, -0x1.fep-1, 0.5, -0.5, 0.25, 0.75, -0.75, 0.375, 0x3p-10,
    -0x3p-12, 1.0 / 3, 2.0 / 3, -2.0 / 3, 45.0 / 64, 9.0 / 64,
};

static int gen_div3(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    (void)p;
    if (gen_begin(&ref_model_div3, NULL, out)) return -1;
    if (n == 0) n = 256;
    vec_rng r = { model_seed("div3", seed) };
    node_stream s1, s2;
    node_stream_init(&s1, ref_nodes_n1, 4, splits_all, 4, r.s + 1);
    node_stream_init(&s2, ref_nodes_n2, 4, splits_all, 4, r.s + 2);
    double v[2], sums[4];
    size_t ne = sizeof div3_edges / sizeof div3_edges[0];
    for (size_t i = 0; i < n; i++) {
        if (i < ne) {
            v[0] = div3_edges[i];
        } else if ((i - ne) % 2 == 0) {
            v[0] = vec_rng_range(&r, -1, 1);
        } else {
            size_t q = ((i - ne) / 2) % 4;
            if (q == 0) {
                double a[4], b[4];
                node_next(&s1, a);
                node_next(&s2, b);
                sums[0] = a[1] + 8 * a[3];
                sums[1] = a[1] + 32 * a[3];
                sums[2] = b[0] + 8 * b[3];
                sums[3] = 13 * b[0] + 32 * b[3];
            }
            v[0] = ldexp(sums[q], -6);
        }
        if (push_row(&ref_model_div3, NULL, out, v)) return -1;
    }
    return 0;
}

/* ---- the models (ref_interp.h; each unit's descriptor points at its own) ---- */

/* cubic Horner ((a t + b) t + c) t + d (Fig. 9) */
const vec_model ref_model_horner3 = {
    "horner3",
    ports_horner3, eval_horner3, gen_horner3 };
/* quadratic Horner (a t + b) t + c */
const vec_model ref_model_horner2 = {
    "horner2",
    ports_horner2, eval_horner2, gen_horner2 };
/* x/3 by the shift network (Fig. 7), exact x/3 expected */
const vec_model ref_model_div3 = {
    "div3",
    ports_div3, eval_div3, gen_div3 };
/* cubic coefficients from I(0), I(1), I(1/2), I(1/4) (Fig. 8) */
const vec_model ref_model_coef3_n1 = {
    "coef3_n1",
    ports_coef3, eval_coef3_n1, gen_coef3_n1 };
/* cubic coefficients from I(0), I(1), I(1/2), I(3/4) */
const vec_model ref_model_coef3_n2 = {
    "coef3_n2",
    ports_coef3, eval_coef3_n2, gen_coef3_n2 };
/* quadratic coefficients from I(0), I(1), I(1/2) */
const vec_model ref_model_coef2 = {
    "coef2",
    ports_coef2, eval_coef2, gen_coef2 };
/* cubic through N1 (or, param nodes, N2) nodes at the L pixels t = k/L (param L) */
const vec_model ref_model_interp3 = {
    "interp3",
    ports_interp3, eval_interp3, gen_interp3 };
/* quadratic through I(0), I(1), I(1/2) at t = k/L (param L) */
const vec_model ref_model_interp2 = {
    "interp2",
    ports_interp2, eval_interp2, gen_interp2 };

