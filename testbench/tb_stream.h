/* tb_stream.h - the testbench pieces that work one item at a time, shared
 * by tb_run (every item in memory) and tb_run_stream (a vector file read a
 * block at a time, memory independent of its length):
 *
 *  - tb_prep: quantize one row's inputs as the hardware holds them and
 *    compute what the unit should give (ideal, exact ideal, the golden
 *    check's figures);
 *  - tb_acc: the error metrics, accumulated item by item in item order
 *    (so the sums are added in the same order whichever way the items
 *    come: the reports are the same bytes).
 */
#ifndef TB_STREAM_H
#define TB_STREAM_H
#include "testbench/tb.h"
#include "vectors/vec_file.h"

/* What the double ideals of units without an exact one are taken to be
 * accurate to, relative to max(1, |ideal|): their float formulas have at
 * most a few dozen roundings of 2^-53 each (pow_n: 10 squarings). A
 * comparison closer than this to the bound is "unchecked"; the golden
 * check allows this much relative to its terms' size. */
#define TB_DOUBLE_IDEAL_REL 0x1p-40

/* What tb_prep needs of the unit, set once per run. */
typedef struct tb_prep_ctx {
    const unit_desc *u;
    const unit_cfg  *cfg;
    const unit_fmts *fmts;
    const vec_model *model;     /* NULL: the row's expected values stand in */
    vec_params vp;
    int n_in, nv;               /* inputs; output values per item (beats x outputs) */
    int in_idx[UNIT_MAX_IO];    /* signal index of input i */
    /* Input i's format and rounding, and 2^F and 2^-F of its F fraction
     * bits (0..64: normal doubles, so that a product by one is ldexp's
     * value, exactly and without the call). */
    sim_fmt   in_fmt[UNIT_MAX_IO];
    sim_round in_rnd[UNIT_MAX_IO];
    double    in_up[UNIT_MAX_IO], in_down[UNIT_MAX_IO];
    sim_fx_conv in_cv[UNIT_MAX_IO];   /* its quantization (sim_fx_from_real's) */
} tb_prep_ctx;

/* One item's figures, nv values each (beat-major) unless noted. */
typedef struct tb_item {
    int64_t *in_raw;            /* n_in quantized inputs */
    double  *ideal, *ideal_r, *ideal_u, *ref_u;
    sim_dy  *exact, *den, *hi;  /* NULL when the unit has no such ideal */
    unsigned char *exact_ok;    /* one: 0 none, 1 exact (or ratio), 2 interval */
    /* Where set (a unit with an exact ideal and neither ratio nor
     * interval), the exact ideal kept as its double only (sim_dy_to_double;
     * NaN when it did not fit), 8 bytes instead of a sim_dy: tb_prep
     * still works it out in exact (scratch) and fills this; tb_acc_item,
     * given exact NULL, decides from the double where that is exact
     * (tb_check_quick) and works the exact value out again from in_raw
     * where it is not (tb_acc's pc). The verdicts and figures are the
     * same. */
    double  *exact_d;
} tb_item;

void tb_prep_init(tb_prep_ctx *p, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts);
/* row: n_in inputs then nv expected values. in_ovf[i] counts input i's
 * quantization overflows. */
void tb_prep(const tb_prep_ctx *p, const double *row, const tb_item *it, uint64_t *in_ovf);
/* The exact ideal (nv values) of quantized inputs in_raw, as tb_prep
 * works it out: 0, or nonzero when it does not fit (u->ideal_exact). */
int  tb_prep_exact(const tb_prep_ctx *p, const int64_t *in_raw, sim_dy *exact);

/* Error metrics of a run, item by item. r->out[o].fmt, name and bound must
 * be set before tb_acc_begin. */
typedef struct tb_acc {
    double se[UNIT_MAX_IO], out_scale[UNIT_MAX_IO];
    double lsb[UNIT_MAX_IO], bd[UNIT_MAX_IO];   /* sim_fmt_lsb(fmt); b as a double */
    sim_dy b[UNIT_MAX_IO];
    int    has_bound[UNIT_MAX_IO];
    int    any_unchecked[UNIT_MAX_IO], any_exceeded[UNIT_MAX_IO];
    size_t first_unchecked[UNIT_MAX_IO], first_exceeded[UNIT_MAX_IO];
    /* For items with exact_d (tb_item): the unit, and room for nv
     * values, to work an exact ideal out again (set after tb_acc_begin). */
    const tb_prep_ctx *pc;
    sim_dy *exact_tmp;
} tb_acc;
void tb_acc_begin(tb_acc *a, tb_result *r);
/* Item number idx: its raws and expected values (nv each) and figures. */
void tb_acc_item(tb_acc *a, tb_result *r, size_t idx, const int64_t *raw, const double *expected,
                 const tb_item *it);
void tb_acc_end(tb_acc *a, tb_result *r);

/* The exact check of one value (tb_check.c): TB_CHECK_OK / EXCEEDED /
 * UNCHECKED, and |hw - ideal| in *err. */
int tb_check_value(int64_t raw, sim_fmt f, const sim_dy *exact, const sim_dy *den, const sim_dy *hi,
                   double ideal_d, const sim_dy *bound, double *err);
/* The same with what is fixed per output worked out once: lsb is
 * sim_fmt_lsb(f), bound_d sim_dy_to_double(bound). */
/* The verdict of tb_check_value_at from the exact ideal's double id_d
 * alone (sim_dy_to_double of it; NaN: it did not fit): TB_CHECK_OK or
 * TB_CHECK_EXCEEDED with *err when that is exact, -1 when only the exact
 * value can decide. */
int tb_check_quick(int64_t raw, sim_fmt f, double lsb, double id_d, double bound_d, double *err);
int tb_check_value_at(int64_t raw, sim_fmt f, double lsb, const sim_dy *exact, const sim_dy *den, const sim_dy *hi,
                      double ideal_d, const sim_dy *bound, double bound_d, double *err);

/* The --out CSV (tb_out.c): its header, and one item's row. */
void tb_csv_header(FILE *f, int n_out, const char names[][16]);
void tb_csv_row(FILE *f, const tb_result *r, size_t idx, uint64_t cycle, const int64_t *raw,
                const double *expected);

/* Called with each item once its last output beat is in: its index, the
 * cycle of its first beat, its raws and expected values (nv each). */
typedef void (*tb_row_fn)(void *data, const tb_result *r, size_t idx, uint64_t cycle,
                          const int64_t *raw, const double *expected);

/* tb_run on the rows of a stream (vec_file.h; opened with the unit's
 * expected header, tb_expected_header, so that its header is checked).
 * Nothing proportional to the number of rows is kept: res->raw and
 * res->beat_cycle are NULL, row (if not NULL) sees every item as it
 * completes. No VCD and no lanes: of o (NULL: none) only reference is
 * taken. A bad row in the file stops the run: TB_BADINPUT with the
 * reader's "PATH:LINE: what" in err. */
int tb_run_stream(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
                  vec_stream *vs, tb_row_fn row, void *row_data, const tb_opts *o, tb_result *res,
                  char *err, size_t errlen);
/* Each output's name, format and bound in r (before tb_acc_begin). */
void tb_stream_outputs(tb_result *r, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts);
/* The figures of a stream of n items whose first beat came at clock
 * first_cycle, the last item's first at last_item_cycle, the last beat at
 * last_cycle: latency, cycles, cycles per item and beat; area and the
 * critical path of the build (c, sc), its overflows and the inputs'
 * (in_ovf, per input). */
void tb_stream_figures(tb_result *r, size_t n, uint64_t first_cycle, uint64_t last_item_cycle, uint64_t last_cycle,
                       sim_ctx *c, const sim_scope *sc, const uint64_t *in_ovf);

/* tb_run_stream on the batch's lanes (tb_lanes.h), a wave of items at a
 * time on up to `threads` threads: the same report, to the byte, but for
 * the engine (res->lanes set; no events, delta cycles or process runs).
 * TB_OK, TB_BADINPUT (a bad row: err) or TB_STREAM_KERNEL: the lanes do
 * not give the kernel's results (res->engine_why says why); *rewound is
 * then 1 if vs is back at its first rows (hand it to tb_run_stream), 0 if
 * rows were taken (a file must be opened again; a pipe cannot). */
enum { TB_STREAM_KERNEL = 4 };
int tb_run_stream_lanes(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts, vec_stream *vs,
                        tb_row_fn row, void *row_data, int threads, tb_result *res, int *rewound,
                        char *err, size_t errlen);
#endif
