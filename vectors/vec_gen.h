/* vec_gen.h - a reference model's generator as a stream of rows, a block
 * at a time (vec_stream_gen in vec_file.h is its public face): what
 * vec_file.c's stream calls. Not for other files. */
#ifndef VEC_GEN_H
#define VEC_GEN_H
#include "vectors/vectors.h"

typedef struct vec_gen vec_gen;
/* The generator m->gen(p, n, seed) started on its own thread, its rows
 * handed over in blocks; hdr: the model's header (copied). NULL when out
 * of memory or a thread cannot be made. */
vec_gen *vec_gen_open(const vec_model *m, const vec_params *p, size_t n, uint64_t seed, const vec_set *hdr);
/* The next block into *rows (its rows replaced; the set keeps its
 * header): 1, 0 at the end, -1 when the generator failed. */
int  vec_gen_next(vec_gen *g, vec_set *rows);
/* Stops the generator if it is still going, and frees it. */
void vec_gen_close(vec_gen *g);
#endif
