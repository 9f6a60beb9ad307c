/* vectors.h - the double-precision float reference and golden vectors.
 *
 * Each hardware unit has a reference model here (ref_*.c), the oracle its
 * hardware is checked against: independent code, written from the
 * formulas, not from the hardware. A model knows its input and output
 * names, computes the exact outputs for given inputs (eval), and generates
 * a deterministic set of golden input vectors (gen) that exercise the
 * unit: real intensity profiles, hard cases, range edges.
 *
 * This layer knows nothing of the hardware and includes nothing of units/:
 * each unit's descriptor (units/unit.h, unit_desc.ref) points at its model,
 * so the include graph runs sim <- vectors <- units <- testbench with no
 * circle, and there is one registry (the units'), not two matched by name.
 * The model's parameters are the unit's (unit_cfg holds a vec_params).
 * Files (the format of docs/vectors.md) are read and written by vec_file.h.
 */
#ifndef VECTORS_H
#define VECTORS_H
#include <stdint.h>
#include <stddef.h>

#define VEC_MAX_PORTS 64    /* inputs or outputs of one vector (span units: L <= 64 pixels) */

/* Parameters a model may take, written once: vec_params is these fields,
 * and units/unit.h's unit_cfg holds the same fields as a vec_params
 * (cfg->model) and by name (cfg->L), so a unit's configuration is its
 * model's parameters without a copy. A model ignores those it does not use.
 *   L      pixels per interval (interp: a power of two; span: 2..64)
 *   g      power for powg/d_approx (a power of two)
 *   n      exponent for pow_n; refractive-like n for schlick
 *   m      Beckmann roughness for d_approx
 *   alpha  Ward roughness
 *   nodes  span3, span23, interp3: cubic node set, 0 = N1, 1 = N2 */
#define VEC_PARAMS_FIELDS int L; int g; int n; double m; double alpha; int nodes;
typedef struct vec_params { VEC_PARAMS_FIELDS } vec_params;
/* The reference's own defaults (L 8, g 16, n 32, m 0.2, alpha 0.2, nodes
 * N1), what a model takes when given no parameters. A unit's defaults are
 * its descriptor's (units/unit.h, unit_param.def), so far the same values;
 * the checked-in vector files are made with the unit's. */
void vec_params_default(vec_params *p);


typedef struct vec_set {
    char unit[32];
    int n_in, n_out;
    char in_names[VEC_MAX_PORTS][16];
    char out_names[VEC_MAX_PORTS][16];
    size_t n_rows, cap_rows;
    double *data;           /* rows of n_in + n_out values, packed */
    /* A set that hands its rows on (vec_gen.c: a generator streamed):
     * vec_set_push calls flush before adding a row to flush_rows rows;
     * flush takes them (n_rows back to 0), or returns -1 to stop. */
    int   (*flush)(struct vec_set *s, void *arg);
    void   *flush_arg;
    size_t  flush_rows;
} vec_set;

/* Row i: its n_in inputs, then its n_out expected outputs. */
static inline double *vec_row(const vec_set *s, size_t i)
{
    return s->data + i * (size_t)(s->n_in + s->n_out);
}

void vec_set_init(vec_set *s);
void vec_set_free(vec_set *s);
/* Append a row (copies n_in + n_out doubles); 0, or -1 when out of memory. */
int  vec_set_push(vec_set *s, const double *v);

/* A reference model. */
typedef struct vec_model {
    const char *name;                    /* its unit's name (the file header's "unit:") */
    /* Port names; for multi-output models these may depend on params (e.g.
     * y0..y{L-1}), so they come from a function. Returns counts. */
    void (*ports)(const vec_params *p, int *n_in, char in[][16],
                  int *n_out, char out[][16]);
    /* Exact outputs for inputs. */
    void (*eval)(const vec_params *p, const double *in, double *out);
    /* Append n golden input vectors (with expected outputs) from the seed;
     * n = 0 means the model's default count. Deterministic for (n, seed). */
    int  (*gen)(const vec_params *p, size_t n, uint64_t seed, vec_set *out);
} vec_model;

/* Fill a set's header (unit name, port names) for a model and params. */
void vec_set_header(vec_set *s, const vec_model *m, const vec_params *p);

/* A small deterministic PRNG (splitmix64) for generators. */
typedef struct vec_rng { uint64_t s; } vec_rng;
uint64_t vec_rng_next(vec_rng *r);
double   vec_rng_unit(vec_rng *r);            /* [0, 1) with 53 bits */
double   vec_rng_range(vec_rng *r, double lo, double hi);
#endif
