/* tb.h - per-unit testbenches: drive a unit with golden vectors, clock by
 * clock, and measure cycles, area and quantization error.
 *
 * tb_run composes the layers: it builds the unit (units/) into a fresh
 * simulation (sim/), quantizes the vectors' inputs (vectors/) to the unit's
 * input formats, offers one item at a time through the valid/ready
 * handshake, and samples each output beat at the rising edge that ends the
 * cycle it is valid in. A beat's cycle is the number of clock cycles from
 * the start (the first cycle is 0).
 */
#ifndef TB_H
#define TB_H
#include "units/unit.h"
#include "vectors/vectors.h"

typedef struct tb_metrics {
    char    name[16];
    sim_fmt fmt;
    double  max_abs_err, mean_err, rms_err, nmse, max_err_lsb;
    double  bound;          /* allowed |hardware - ideal(quantized inputs)| */
    double  max_err_ideal;  /* measured |hardware - ideal(quantized inputs)| */
    double  sum_e2, sum_ref2;
    size_t  n;
} tb_metrics;

typedef struct tb_result {
    const unit_desc *unit;
    unit_cfg   cfg;
    unit_fmts  fmts;
    size_t     vectors;          /* items driven */
    int        beats, n_in, n_out;
    uint64_t   cycles;           /* cycle of the last output beat + 1 */
    double     cycles_per_item;  /* steady state: (last - first) / (items - 1) */
    double     cycles_per_beat;
    uint64_t   latency;          /* cycles until the first beat is valid */
    double     max_abs_err, mean_err, rms_err, nmse, max_err_lsb;  /* over all outputs */
    uint64_t   overflows;        /* inputs' quantization + every unit signal */
    double     area_ge;
    int        within_bound;     /* 1 if every beat met its bound */
    size_t     first_violation;  /* item index, if !within_bound */
    tb_metrics out[UNIT_MAX_IO];
    sim_stats  stats;
    /* Per item and beat (item-major): the cycle it appeared, and raws per port. */
    uint64_t  *beat_cycle;
    int64_t   *raw;              /* [item][beat][port] */
} tb_result;

typedef struct tb_opts {
    const char *vcd_path;        /* NULL: no dump */
    int         gtkw;            /* also write VCD_PATH with .gtkw */
} tb_opts;

enum { TB_OK = 0, TB_FAIL = 1, TB_BADINPUT = 2 };

/* Run; returns TB_OK, TB_FAIL (the simulation failed: loop, no output in
 * time; message in err) or TB_BADINPUT (vectors do not fit the unit, VCD
 * path unwritable; message in err). A bound violation is TB_OK with
 * res->within_bound == 0. */
int  tb_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
            const vec_set *vs, const tb_opts *o, tb_result *res, char *err, size_t errlen);
void tb_result_free(tb_result *res);

/* The vector-set header a unit expects (unit name, inputs, outputs with
 * beats expanded: y0..y{L-1}), for checking files and making vectors. */
void tb_expected_header(const unit_desc *u, const unit_cfg *cfg, vec_set *hdr);
/* The reference model's parameters for a unit's configuration. */
void tb_vec_params(const unit_cfg *cfg, vec_params *p);

/* Formats from cfg->width, then overrides "NAME=sI.F" / "all=sI.F" applied
 * in order; 0, or -1 with a message. */
int  tb_formats(const unit_desc *u, const unit_cfg *cfg, const char *const *overrides,
                int n, unit_fmts *out, char *err, size_t errlen);

/* Output writers. Each writes atomically where it writes a file. */
int  tb_write_json(FILE *f, const tb_result *r);
int  tb_write_csv(const char *path, const tb_result *r, const vec_set *vs, char *err, size_t errlen);
void tb_print_table(FILE *f, const tb_result *r);
#endif
