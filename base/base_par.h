/* base_par.h - the parallel-for every multi-threaded loop of shadesim uses
 * (sweeps, format searches, scene bands, the halves of a vector file).
 *
 * Results stay deterministic because each item writes only its own slot
 * (fn(ctx, i) fills result i); which thread runs which item, and in what
 * order, is free. Sums over the items are made by the caller afterwards,
 * in item order.
 */
#ifndef BASE_PAR_H
#define BASE_PAR_H
#include <stddef.h>

/* Run fn(ctx, i) once for every i in [0, n) on up to `threads` threads
 * (the caller's thread among them; threads < 1 means 1); returns when all
 * are done. With one thread, or one item, the items run in order on the
 * caller's thread. If threads cannot be made, fewer do the work (down to
 * the caller's alone): a loop never fails for want of threads. */
void base_par_for(size_t n, int threads, void (*fn)(void *ctx, size_t i), void *ctx);
#endif
