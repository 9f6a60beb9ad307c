/* tb_drive.c - the driver's sources and its kernel process (tb_drive.h). */
#include "testbench/tb_drive.h"
#include <stdint.h>
#include <string.h>

static void init(tb_drive *d, tb_src_kind kind, int n_in)
{
    memset(d, 0, sizeof *d);
    d->kind = kind;
    d->n_in = n_in;
    d->offered = SIZE_MAX;
}

void tb_drive_raws(tb_drive *d, int n_in, const int64_t *raws, size_t n_items)
{
    init(d, TB_SRC_RAWS, n_in);
    d->raws = raws;
    d->n_items = n_items;
}

void tb_drive_rows(tb_drive *d, int n_in, const vec_set *rows, const sim_fx_conv *cv)
{
    init(d, TB_SRC_ROWS, n_in);
    d->rows = rows;
    d->n_items = rows->n_rows;
    memcpy(d->conv, cv, (size_t)n_in * sizeof *cv);
}

void tb_drive_recs(tb_drive *d, int n_in, const void *recs, size_t stride, size_t n_items, const size_t *off,
                   const unsigned char *is_int, const sim_fx_conv *cv)
{
    init(d, TB_SRC_RECS, n_in);
    d->recs = recs;
    d->stride = stride;
    d->n_items = n_items;
    memcpy(d->off, off, (size_t)n_in * sizeof *off);
    memcpy(d->is_int, is_int, (size_t)n_in * sizeof *is_int);
    memcpy(d->conv, cv, (size_t)n_in * sizeof *cv);
}

void tb_drive_fn_source(tb_drive *d, int n_in, tb_drive_fn fn, void *data)
{
    init(d, TB_SRC_FN, n_in);
    d->fn = fn;
    d->data = data;
}

/* The next item's writes (kept out of tb_drive_proc, so that the clocks
 * at which the unit holds its item cost a call of a few compares and no
 * saving of the registers the sources use). */
static __attribute__((noinline)) void offer(tb_drive *d, sim_proc *p)
{
    const unit_io *io = d->io;
    d->started = 1;
    d->offered = d->next;
    const int64_t *v;
    if (d->kind == TB_SRC_RAWS || d->kind == TB_SRC_FN) {
        v = tb_drive_raws_at(d, d->next);     /* where they are: no copy */
    } else {
        int64_t *at[UNIT_MAX_IO];
        for (int i = 0; i < d->n_in; i++) at[i] = &d->scratch[i];
        v = tb_drive_put(d, d->next, at, 0) ? d->scratch : NULL;
    }
    if (v) {
        for (int i = 0; i < d->n_in; i++) sim_write(io->in[i], v[i]);
        sim_write(io->in_valid, 1);
    } else {
        sim_write(io->in_valid, 0);
    }
    if (d->failed) sim_stop(p->ctx);
}

/* At each rising edge: the accept (valid and ready before the edge), then
 * the next item's writes, skipped while the unit holds the item offered
 * (a source that failed stops the run at every edge). */
void tb_drive_proc(sim_proc *p)
{
    tb_drive *d = p->data;
    const unit_io *io = d->io;
    if (d->started && io->in_valid->cur && io->in_ready->cur) {
        if (d->next == 0) d->first_accept = sim_get_stats(d->ctx)->clocks;
        d->next++;
    }
    if (d->started && d->next == d->offered && !d->failed) return;
    offer(d, p);
}
