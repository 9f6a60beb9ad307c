/* vectors.c - vector-set helpers and the models' default parameters (the
 * models themselves: ref_*.c; each unit's descriptor points at its own). */
#include "vectors/vectors.h"
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

void vec_params_default(vec_params *p)
{
    p->L = 8; p->g = 16; p->n = 32; p->m = 0.2; p->alpha = 0.2; p->nodes = 0;
}

void vec_set_init(vec_set *s) { memset(s, 0, sizeof *s); }
void vec_set_free(vec_set *s) { free(s->data); vec_set_init(s); }

int vec_set_push(vec_set *s, const double *v)
{
    if (s->flush && s->n_rows >= s->flush_rows && s->flush(s, s->flush_arg)) return -1;
    if (s->n_rows == s->cap_rows) {
        size_t cap = s->cap_rows ? 2 * s->cap_rows : 256;
        size_t stride = (size_t)(s->n_in + s->n_out);
        double *d = realloc(s->data, cap * (stride ? stride : 1) * sizeof *d);
        if (!d) return -1;
        s->data = d; s->cap_rows = cap;
    }
    memcpy(vec_row(s, s->n_rows), v, (size_t)(s->n_in + s->n_out) * sizeof(double));
    s->n_rows++;
    return 0;
}

void vec_set_header(vec_set *s, const vec_model *m, const vec_params *p)
{
    snprintf(s->unit, sizeof s->unit, "%s", m->name);
    m->ports(p, &s->n_in, s->in_names, &s->n_out, s->out_names);
}

uint64_t vec_rng_next(vec_rng *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
double vec_rng_unit(vec_rng *r) { return (double)(vec_rng_next(r) >> 11) * 0x1p-53; }
double vec_rng_range(vec_rng *r, double lo, double hi) { return lo + (hi - lo) * vec_rng_unit(r); }
