/* tb_items_memo.h - tb_items_run's results kept for the same run asked
 * again (a sweep whose grid points share their nodes: the same normals
 * through the same shade unit). A run is the same when every byte of its
 * unit, configuration, formats, energy flag and items is: the simulation
 * is deterministic (tb_items.h: every figure the same for any number of
 * threads), so a kept result is the bytes a new run would give. A
 * configuration made differently (its padding) only misses, never hits
 * wrongly. Safe to share between threads: a thread asking for a run
 * another is making waits for its answer (a failed run is not kept). */
#ifndef TB_ITEMS_MEMO_H
#define TB_ITEMS_MEMO_H
#include "testbench/tb_items.h"

typedef struct tb_items_memo tb_items_memo;

tb_items_memo *tb_items_memo_new(void);
void           tb_items_memo_free(tb_items_memo *m);
/* Runs kept and runs answered from them. */
void           tb_items_memo_counts(const tb_items_memo *m, size_t *kept, size_t *hits);

/* tb_items_run, answered from m when it holds the same run (m NULL: no
 * memo); a successful run is kept. */
int tb_items_run_memo(tb_items_memo *m, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                      const double *in, size_t n, int jobs, int energy, double *out, tb_items_stats *st,
                      char *err, size_t errlen);
#endif
