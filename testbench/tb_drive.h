/* tb_drive.h - the one valid/ready driver of every testbench, parameterized
 * by where its items come from (the source) and by the engine it drives
 * (the kernel's signals, or one lane of the batch).
 *
 * The protocol, the same in every engine: at each rising edge, the item
 * offered was accepted if in_valid and in_ready were both high before the
 * edge; then the next item is offered (its inputs and in_valid = 1), or
 * in_valid drops past the last. While the unit holds an item the inputs
 * and valid already hold what would be written again (nothing else drives
 * them), so those writes are skipped. The kernel runs the driver once at
 * initialization, before any edge: the first item is offered then.
 *
 * Sources:
 *  - TB_SRC_RAWS: inputs quantized beforehand, [item][input] (tb_run,
 *    tb_lanes);
 *  - TB_SRC_ROWS: a vector set's rows, quantized when offered with each
 *    input's conversion, overflows counted (tb_batch);
 *  - TB_SRC_RECS: an array of records (structs), each port reading a
 *    double or an int field of its own, quantized when offered (tb_span's
 *    intervals, both engines: node intensities, n, dv, deg);
 *  - TB_SRC_FN: a function giving item i's raws or NULL, which may read
 *    ahead or fail (tb_stream: rows read a block at a time).
 * An item is quantized once, when first offered: its overflows are
 * counted once.
 */
#ifndef TB_DRIVE_H
#define TB_DRIVE_H
#include "testbench/tb.h"
#include "vectors/vec_file.h"
#include <stdint.h>
#include <string.h>

typedef enum { TB_SRC_RAWS, TB_SRC_ROWS, TB_SRC_RECS, TB_SRC_FN } tb_src_kind;

typedef struct tb_drive tb_drive;
/* TB_SRC_FN: item i's n_in raws, or NULL (past the end; d->failed set on
 * an error, which stops the run). */
typedef const int64_t *(*tb_drive_fn)(tb_drive *d, size_t i);

struct tb_drive {
    /* the source */
    tb_src_kind kind;
    int         n_in;
    size_t      n_items;                 /* RAWS, ROWS, RECS: items [0, n_items) */
    const int64_t *raws;                 /* RAWS */
    const vec_set *rows;                 /* ROWS */
    const char *recs;                    /* RECS: record i at recs + i * stride */
    size_t      stride;
    tb_drive_fn fn;                      /* FN */
    void       *data;                    /* FN: the source's own state */
    /* the handshake */
    const unit_io *io;                   /* the kernel engine's ports */
    const sim_ctx *ctx;                  /* the kernel engine's context (the clock count) */
    size_t      next;                    /* the item offered, or to be */
    size_t      offered;                 /* the kernel engine: next at the last writes */
    uint64_t    first_accept;            /* the clock count at the first accept */
    uint64_t    in_ovf;                  /* ROWS, RECS: the quantization's overflows */
    int         started, failed;
    /* read at an offer only: last */
    int64_t     scratch[UNIT_MAX_IO];    /* the kernel engine: the item offered */
    size_t      off[UNIT_MAX_IO];        /* RECS: each port's field, its offset in the record */
    unsigned char is_int[UNIT_MAX_IO];   /* RECS: 1 an int field, 0 a double */
    sim_fx_conv conv[UNIT_MAX_IO];       /* ROWS, RECS: each port's quantization */
};

/* The sources (the engine's fields, io and ctx, are set by the caller). */
void tb_drive_raws(tb_drive *d, int n_in, const int64_t *raws, size_t n_items);
/* cv: each input port's conversion (copied) */
void tb_drive_rows(tb_drive *d, int n_in, const vec_set *rows, const sim_fx_conv *cv);
/* off, is_int, cv: each port's field (offsetof, and whether an int) and
 * conversion (copied) */
void tb_drive_recs(tb_drive *d, int n_in, const void *recs, size_t stride, size_t n_items, const size_t *off,
                   const unsigned char *is_int, const sim_fx_conv *cv);
void tb_drive_fn_source(tb_drive *d, int n_in, tb_drive_fn fn, void *data);

/* RAWS and FN: item i's raws where they are, NULL past the end. */
static inline const int64_t *tb_drive_raws_at(tb_drive *d, size_t i)
{
    if (d->kind == TB_SRC_RAWS) return i < d->n_items ? d->raws + i * (size_t)d->n_in : NULL;
    return d->fn(d, i);
}

/* Item i's inputs as the hardware takes them into dst[p][l], port by
 * port: 1, or 0 past the end (a batch lane's columns, or the kernel's
 * scratch; quantized straight into them, no copy between). */
static inline int tb_drive_put(tb_drive *d, size_t i, int64_t *const *dst, uint32_t l)
{
    const int n_in = d->n_in;
    if (d->kind == TB_SRC_ROWS) {
        if (i >= d->n_items) return 0;
        const double *row = vec_row(d->rows, i);
        /* the next row is read a few clocks from now: ask for it already
         * (a batch reads as many streams of items as it has lanes, more
         * than the CPU's own prefetcher follows; a GNU builtin, a hint) */
        if (i + 1 < d->n_items) {
            const double *nx = vec_row(d->rows, i + 1);
            __builtin_prefetch(nx);
            __builtin_prefetch(nx + n_in - 1);
        }
        uint64_t o = 0;
        for (int p = 0; p < n_in; p++) {
            int ov = 0;
            dst[p][l] = sim_fx_conv_real(&d->conv[p], row[p], &ov);
            o += (uint64_t)ov;
        }
        d->in_ovf += o;
        return 1;
    }
    if (d->kind == TB_SRC_RECS) {
        if (i >= d->n_items) return 0;
        const char *rec = d->recs + i * d->stride;
        if (i + 1 < d->n_items) {
            __builtin_prefetch(rec + d->stride);
            __builtin_prefetch(rec + 2 * d->stride - 1);
        }
        for (int p = 0; p < n_in; p++) {
            const char *at = rec + d->off[p];
            double v;
            if (d->is_int[p]) { int k; memcpy(&k, at, sizeof k); v = k; }
            else memcpy(&v, at, sizeof v);
            int ov = 0;
            dst[p][l] = sim_fx_conv_real(&d->conv[p], v, &ov);
            d->in_ovf += (uint64_t)ov;
        }
        return 1;
    }
    const int64_t *v = tb_drive_raws_at(d, i);
    if (!v) return 0;
    for (int p = 0; p < n_in; p++) dst[p][l] = v[p];
    return 1;
}

/* ---------------------------------------------------------- the kernel */

/* The driver process (p->data: a tb_drive with io and ctx set), sensitive
 * to the clock's rising edge. */
void tb_drive_proc(sim_proc *p);

/* ------------------------------------------------------- a batch lane */

/* The batch's arrays the lanes' drivers write (sim_batch_next). */
typedef struct tb_drive_lanes {
    int64_t *in[UNIT_MAX_IO], *valid;
} tb_drive_lanes;

/* Offer item d->next on lane l (valid low past the last): at
 * initialization, and after each accept. A value written stays from
 * edge to edge, as a signal keeps its value. */
static inline void tb_drive_lane_offer(tb_drive *d, const tb_drive_lanes *x, uint32_t l)
{
    x->valid[l] = tb_drive_put(d, d->next, x->in, l);
}

/* Lane l accepted the item offered (in_valid and in_ready high before
 * edge e): the next one. */
static inline void tb_drive_lane_accept(tb_drive *d, const tb_drive_lanes *x, uint32_t l, uint64_t e)
{
    if (d->next == 0) d->first_accept = e;
    d->next++;
    tb_drive_lane_offer(d, x, l);
}
#endif
