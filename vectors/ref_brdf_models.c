/* ref_brdf_models.c - reference models of the BRDF units (Nechyporuk & Romanyuk (2020) sec. III,
 * 001, 004): powg, d_approx, ward_approx, pow_n, div, schlick, mschlick.
 *
 * Expected outputs are the exact function each unit implements (e.g. D_g
 * with its base clamped at 0), not the physical model it approximates: a
 * testbench measures quantization error against these, while the
 * approximation error of each method is measured in testbench/study/tb_ref_claims.c.
 *
 * Generators: the first rows are fixed hard cases (endpoints, the clamp
 * point, ...), the rest are random draws from a stream seeded by (seed,
 * model name), so the rows for n are a prefix of the rows for any larger n.
 * For the cosine inputs half the draws are angles dense near the highlight
 * (within the "hot" angle where the function falls to ~2^-16 of its peak)
 * and half cover the whole [0, 90] deg with density falling towards the
 * tail, so the tail is sampled sparsely but is sampled.
 */
#include "vectors/vectors.h"
#include "vectors/ref_brdf.h"
#include <math.h>
#include <stdio.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define BRDF_DEFAULT_ROWS 256
#define BRDF_MAX_FIXED 8
/* Divider inputs keep d - n >= 2^-8 so that any input format with at least
 * 8 fraction bits still has n < d after rounding (else the quotient would
 * not be a fraction). */
#define DIV_GAP 0x1p-8

/* ---- ports ---- */

static void set_ports(const char *const *in, int ni, const char *const *out, int no,
                      int *n_in, char in_names[][16], int *n_out, char out_names[][16])
{
    *n_in = ni;
    *n_out = no;
    for (int i = 0; i < ni; i++) snprintf(in_names[i], 16, "%s", in[i]);
    for (int i = 0; i < no; i++) snprintf(out_names[i], 16, "%s", out[i]);
}

#define PORTS_FN(fn, INS, OUTS) \
    static void fn(const vec_params *p, int *n_in, char in[][16], int *n_out, char out[][16]) \
    { \
        static const char *const i_[] = INS, *const o_[] = OUTS; \
        (void)p; \
        set_ports(i_, (int)(sizeof i_ / sizeof i_[0]), o_, (int)(sizeof o_ / sizeof o_[0]), \
                  n_in, in, n_out, out); \
    }
#define LIST(...) { __VA_ARGS__ }
PORTS_FN(ports_x_y, LIST("x"), LIST("y"))
PORTS_FN(ports_c_d, LIST("c"), LIST("d"))
PORTS_FN(ports_c_e, LIST("c"), LIST("e"))
PORTS_FN(ports_c_f, LIST("c"), LIST("f"))
PORTS_FN(ports_nd_q, LIST("n", "d"), LIST("q"))

/* ---- eval ---- */

static void eval_powg(const vec_params *p, const double *in, double *out)
{ out[0] = ref_brdf_powg(in[0], p->g); }
static void eval_d_approx(const vec_params *p, const double *in, double *out)
{ out[0] = ref_brdf_dg_clamped(in[0], p->m, p->g); }
static void eval_ward_approx(const vec_params *p, const double *in, double *out)
{ out[0] = ref_brdf_ward_exp_approx_clamped(in[0], p->alpha); }
static void eval_pow_n(const vec_params *p, const double *in, double *out)
{ out[0] = pow(in[0], p->n); }
static void eval_div(const vec_params *p, const double *in, double *out)
{ (void)p; out[0] = in[0] / in[1]; }
static void eval_schlick(const vec_params *p, const double *in, double *out)
{ out[0] = ref_brdf_schlick(in[0], p->n); }
static void eval_mschlick(const vec_params *p, const double *in, double *out)
{ out[0] = ref_brdf_mschlick(in[0], p->n); }

/* ---- generation ---- */

typedef enum { DRAW_ANGLE, DRAW_X, DRAW_DIV } draw_kind;

/* What a model's generator needs: fixed first rows and a random sampler. */
typedef struct gen_plan {
    draw_kind kind;
    double hot;               /* DRAW_ANGLE: angle (rad); DRAW_X: x below 1 */
    size_t n_fixed;
    double fixed[BRDF_MAX_FIXED][2];
} gen_plan;

static void plan_fixed(gen_plan *pl, double a, double b)
{
    if (pl->n_fixed < BRDF_MAX_FIXED) {
        pl->fixed[pl->n_fixed][0] = a;
        pl->fixed[pl->n_fixed][1] = b;
        pl->n_fixed++;
    }
}

/* Add the cosine c as a fixed row when it lies in [0, 1]. */
static void plan_cos(gen_plan *pl, double c)
{
    if (c >= 0.0 && c <= 1.0) plan_fixed(pl, c, 0.0);
}

static void draw(vec_rng *r, size_t i, const gen_plan *pl, double *in)
{
    double u = vec_rng_unit(r);
    switch (pl->kind) {
    case DRAW_ANGLE:
        in[0] = cos((i & 1) ? (M_PI / 2) * u * u : pl->hot * pow(u, 1.5));
        if (in[0] < 0.0) in[0] = 0.0;       /* cos(pi/2) rounds to 6e-17 */
        break;
    case DRAW_X:
        in[0] = (i & 1) ? u : 1.0 - (1.0 - pl->hot) * u * u;
        break;
    case DRAW_DIV: {
        double d = 0.5 + 0.5 * u;
        in[0] = (d - DIV_GAP) * vec_rng_unit(r);
        in[1] = d;
        break;
    }
    }
}

/* FNV-1a of the model name, so models given the same seed get different
 * streams. */
static uint64_t name_hash(const char *s)
{
    uint64_t h = 0xcbf29ce484222325ull;
    while (*s) { h ^= (unsigned char)*s++; h *= 0x100000001b3ull; }
    return h;
}

static int gen_rows(const vec_model *self, const vec_params *p, size_t n, uint64_t seed,
                    vec_set *out, const gen_plan *pl)
{
    vec_set_header(out, self, p);
    if (n == 0) n = BRDF_DEFAULT_ROWS;
    vec_rng r = { seed ^ name_hash(self->name) };
    double v[4];
    for (size_t i = 0; i < n; i++) {
        if (i < pl->n_fixed) { v[0] = pl->fixed[i][0]; v[1] = pl->fixed[i][1]; }
        else draw(&r, i, pl, v);
        self->eval(p, v, v + out->n_in);
        if (vec_set_push(out, v) != 0) return -1;
    }
    return 0;
}

/* Angle where a clamped base A(c - 1) + 1, raised to g, falls to 2^-16. */
static double hot_angle_poly(double A, int g)
{
    if (!(A > 0.0)) return M_PI / 2;
    double c = 1.0 - (1.0 - exp2(-16.0 / g)) / A;
    return c > 0.0 ? acos(c) : M_PI / 2;
}


static int gen_powg(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (p->g < 1) return -1;
    gen_plan pl = { .kind = DRAW_X, .hot = exp2(-16.0 / p->g) };
    plan_fixed(&pl, 1.0, 0);
    plan_fixed(&pl, 0.0, 0);
    plan_fixed(&pl, 0.5, 0);
    plan_fixed(&pl, exp2(-1.0 / p->g), 0);          /* y = 1/2 */
    return gen_rows(&ref_model_powg, p, n, seed, out, &pl);
}

static int gen_d_approx(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (!(p->m > 0.0) || p->g < 1) return -1;
    double A = (2.0 / (p->m * p->m) - 4.0) / p->g;
    gen_plan pl = { .kind = DRAW_ANGLE, .hot = hot_angle_poly(A, p->g) };
    double c0 = ref_brdf_dg_base_zero_cos(p->m, p->g);
    plan_cos(&pl, 1.0);
    plan_cos(&pl, 0.0);
    plan_cos(&pl, c0);                  /* the clamp point: base = 0 */
    plan_cos(&pl, c0 + 0x1p-10);        /* just inside */
    plan_cos(&pl, c0 - 0x1p-10);        /* just clamped */
    return gen_rows(&ref_model_d_approx, p, n, seed, out, &pl);
}

static int gen_ward_approx(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (!(p->alpha > 0.0)) return -1;
    double A = 1.0 / (8.0 * p->alpha * p->alpha);
    gen_plan pl = { .kind = DRAW_ANGLE, .hot = hot_angle_poly(A, 16) };
    double c0 = 1.0 - 1.0 / A;
    plan_cos(&pl, 1.0);
    plan_cos(&pl, 0.0);
    plan_cos(&pl, c0);
    plan_cos(&pl, c0 + 0x1p-10);
    plan_cos(&pl, c0 - 0x1p-10);
    return gen_rows(&ref_model_ward_approx, p, n, seed, out, &pl);
}

static int gen_pow_n(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (p->n < 1) return -1;
    gen_plan pl = { .kind = DRAW_ANGLE, .hot = acos(exp2(-16.0 / p->n)) };
    plan_cos(&pl, 1.0);
    plan_cos(&pl, 0.0);
    plan_cos(&pl, 0.5);
    plan_cos(&pl, exp2(-1.0 / p->n));               /* y = 1/2 */
    return gen_rows(&ref_model_pow_n, p, n, seed, out, &pl);
}

static int gen_div(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    gen_plan pl = { .kind = DRAW_DIV };
    plan_fixed(&pl, 0.0, 0.5);
    plan_fixed(&pl, 0.0, 1.0);
    plan_fixed(&pl, 0.25, 0.5);                     /* q = 1/2 exactly */
    plan_fixed(&pl, 0.375, 0.75);
    plan_fixed(&pl, 0.5 - DIV_GAP, 0.5);            /* largest q, smallest d */
    plan_fixed(&pl, 1.0 - DIV_GAP, 1.0);
    plan_fixed(&pl, 0.25, 0.75);                    /* q = 1/3: non-terminating */
    return gen_rows(&ref_model_div, p, n, seed, out, &pl);
}

static int gen_schlick_like(const vec_model *self, double hot, const vec_params *p,
                            size_t n, uint64_t seed, vec_set *out)
{
    if (p->n < 1) return -1;
    gen_plan pl = { .kind = DRAW_ANGLE, .hot = hot };
    plan_cos(&pl, 1.0);
    plan_cos(&pl, 0.0);
    plan_cos(&pl, pow(0.3, 1.0 / p->n));            /* Zavalniuk et al. (2022)'s epicenter */
    plan_cos(&pl, cos(hot));
    return gen_rows(self, p, n, seed, out, &pl);
}

/* The highlight of the Schlick forms: where they fall below 2^-8 (eqs. 10, 12). */
static int gen_schlick(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (p->n < 1) return -1;
    return gen_schlick_like(&ref_model_schlick, ref_brdf_cutoff_schlick(p->n, 8), p, n, seed, out);
}

static int gen_mschlick(const vec_params *p, size_t n, uint64_t seed, vec_set *out)
{
    if (p->n < 1) return -1;
    return gen_schlick_like(&ref_model_mschlick, ref_brdf_cutoff_mschlick(p->n, 8), p, n, seed, out);
}

/* ---- the models (ref_brdf.h; each unit's descriptor points at its own) ---- */

/* y = x^g, g = 4/8/16 by repeated squaring; x in [0,1] */
const vec_model ref_model_powg = {
    "powg",
    ports_x_y, eval_powg, gen_powg };
/* D_g = (1/(4m^2)) max(0, ((2/m^2-4)/g)(c-1)+1)^g; c = N.H; d up to 1/(4m^2) (6.25 at m=0.2) */
const vec_model ref_model_d_approx = {
    "d_approx",
    ports_c_d, eval_d_approx, gen_d_approx };
/* e = max(0, (c-1)/(8 alpha^2)+1)^16 ~ exp(-tan^2/alpha^2); c = N.H; e in [0,1] */
const vec_model ref_model_ward_approx = {
    "ward_approx",
    ports_c_e, eval_ward_approx, gen_ward_approx };
/* y = x^n (Blinn/Phong cos^n), n = 1..1024; x in [0,1] */
const vec_model ref_model_pow_n = {
    "pow_n",
    ports_x_y, eval_pow_n, gen_pow_n };
/* q = n/d, fraction quotient: d in [1/2,1], 0 <= n <= d - 2^-8, q in [0,1) */
const vec_model ref_model_div = {
    "div",
    ports_nd_q, eval_div, gen_div };
/* f = c/(n - n c + c) (Schlick; Zavalniuk et al. (2022), eq. 2); f in [0,1] */
const vec_model ref_model_schlick = {
    "schlick",
    ports_c_f, eval_schlick, gen_schlick };
/* f = 2c/(1.25 (n - n c + 1.25 c)^2) (Zavalniuk et al. (2022), eq. 5); f in [0,1.024] */
const vec_model ref_model_mschlick = {
    "mschlick",
    ports_c_f, eval_mschlick, gen_mschlick };

