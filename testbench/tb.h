/* tb.h - per-unit testbenches: drive a unit with golden vectors, clock by
 * clock, and measure cycles, area and quantization error.
 *
 * The testbench engine's public header (testbench/): one unit, one run -
 * build it (tb_build), its formats (tb_formats), its vectors (vector files,
 * or tb_make_vectors from its float reference), run it (tb_run; streamed:
 * tb_stream.h; many lanes at once: tb_batch.h, tb_lanes.h; span units:
 * tb_span.h), the verdict, PPA and timing, ranges and derived formats
 * (tb_range.h, tb_derive.h), energy (tb_energy.h), waveforms (tb_wave.h),
 * the Verilog export and co-simulation (tb_verilog.h), the JSON and CSV
 * of a result. The studies (testbench/study/study.h) run it many times;
 * the command line (testbench/cli/cli.h) prints it. The engine includes
 * neither (tests/cli_layers.sh).
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

/* How an output's error against the ideal compares with its bound
 * (docs/bounds.md, "The verdict"). */
enum {
    TB_CHECK_OK = 0,        /* every value within the bound, decided exactly */
    TB_CHECK_EXCEEDED,      /* some value is over the bound, decided exactly */
    TB_CHECK_UNCHECKED,     /* the ideal is a double that cannot decide it */
    TB_CHECK_NO_BOUND       /* the unit derives no bound for these formats */
};
const char *tb_check_name(int check);      /* "ok" "exceeded" "unchecked" "no bound" */

typedef struct tb_metrics {
    char    name[16];
    sim_fmt fmt;
    /* Golden error: hardware against the vector file's expected outputs. */
    double  max_abs_err, mean_err, rms_err, nmse, max_err_lsb;
    double  bound;          /* allowed |hardware - ideal(quantized inputs)|; inf/NaN: none */
    double  max_err_ideal;  /* measured |hardware - ideal(quantized inputs)| */
    double  sum_e2, sum_ref2;
    size_t  n;
    int     check;          /* TB_CHECK_* of this output */
    /* The golden check: |hw - expected| <= allowed, with allowed = bound +
     * |ideal(rounded inputs) - ideal(inputs)| + |ideal(inputs) - ref(inputs)|
     * (docs/bounds.md). golden_ok 0: first row over it, its error and allowance. */
    int     golden_ok;
    size_t  golden_first;
    double  golden_err, golden_allowed;
    double  max_method_err; /* max |ideal(inputs) - ref(inputs)|: the method's own approximation */
    double  max_input_err;  /* max |ideal(rounded inputs) - ideal(inputs)|: rounding the inputs */
} tb_metrics;

/* Range logging of one signal of the unit: settled values sampled at every
 * rising clock edge, and the overflows counted on it. */
typedef struct tb_sig {
    char     name[48];      /* path below the unit's scope: "y", "div3_a.t1" */
    sim_fmt  fmt;
    int      kind;          /* sim_kind */
    uint64_t overflows;     /* inputs: quantization of the vectors; constants: at build;
                             * elements: of values used that clock (sim_prim.h) */
    uint64_t ovf_discarded; /* overflows on values no consumer took that clock */
    uint64_t toggles;       /* settled bit changes over the run (docs/timing.md) */
    int64_t  min, max;      /* observed raw values (valid if seen) */
    int      seen;
} tb_sig;

/* Speed and energy in hardware terms (docs/timing.md): the critical path
 * of the built design between registers (or ports), the clock it allows,
 * and the switching activity of the run. */
#define TB_PATH_MAX 64
typedef struct tb_ppa {
    int      levels;            /* gate levels on the critical path */
    double   crit_ps;           /* its delay: clock-to-q + logic + setup, ps */
    int      npath;             /* signals on it, from its start to its end */
    char     path[TB_PATH_MAX][48];
    double   fmax_mhz;          /* 1e6 / crit_ps */
    double   items_per_s;       /* fmax / cycles per item */
    uint64_t toggles;           /* settled bit changes of every unit signal */
    double   energy_pj_per_item;
} tb_ppa;

/* The critical path of a built design (c, the unit's scope sc: names are
 * relative to it), its f_max, and items_per_s = f_max / cycles_per_item
 * (not set when cycles_per_item <= 0); toggles and energy untouched.
 * 0, or -1 with a message (a combinational loop). tb_run and the
 * streamed run fill their result's ppa with it. */
int  tb_ppa_timing(const sim_ctx *c, const sim_scope *sc, double cycles_per_item, tb_ppa *p,
                   char *err, size_t errlen);
/* The same for a unit built with tb_build and freed (sweeps, scenes):
 * items_per_s is left 0, as the cycles per item need a run
 * (tb_ppa_rate sets it from them). 0, or -1 with a message. */
int  tb_unit_timing(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, tb_ppa *p,
                    char *err, size_t errlen);
/* Both model the netlist `synth --sta` makes with ABC's script as --abc
 * auto chooses it (tb_abc_auto on the unit's area): the default script's
 * ripple carries, the light script's prefix ones (sim_delay.h); with abc
 * (TB_ABC_FULL or TB_ABC_LIGHT, tb_synth.h) the one given. */
int  tb_unit_timing_abc(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, int abc, tb_ppa *p,
                        char *err, size_t errlen);
void tb_ppa_rate(tb_ppa *p, double cycles_per_item);

/* What the user accepts (0 / negative: not set). */
typedef struct tb_accept {
    double max_error;       /* --max-error: max |hw - expected| */
    double max_nmse;        /* --max-nmse */
    double max_lsb;         /* --max-lsb: max |hw - expected| in output LSBs */
    int    allow_overflow;  /* --allow-overflow */
} tb_accept;

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
    uint64_t   overflows;        /* inputs' quantization + every unit signal (values used) */
    uint64_t   ovf_discarded;    /* more overflows, on values no consumer took that clock */
    double     area_ge;
    tb_ppa     ppa;
    int        within_bound;     /* 1 if every beat met its bound */
    size_t     first_violation;  /* item index, if !within_bound */
    tb_metrics out[UNIT_MAX_IO];
    sim_stats  stats;            /* the kernel's; only clocks when the batch ran */
    uint32_t   lanes;            /* the batch's lanes that simulated it (tb_lanes.h); 0: the kernel */
    int        reference;        /* the kernel ran as its reference (sim_set_reference) */
    char       engine_why[160];  /* lanes asked for but the kernel ran: why ("" otherwise) */
    /* The verdict (tb_verdict): */
    int        bound_check;      /* worst TB_CHECK_* over the outputs */
    int        golden_ok;        /* every output within its golden allowance */
    uint64_t   in_overflows;     /* of the inputs' quantization */
    int        target_set, target_met;   /* user acceptance (tb_accept) */
    int        ok;               /* the overall verdict */
    char       why[256];         /* one line: what failed, or what "ok" means */
    /* Range logging: every signal of the unit, in creation order. */
    tb_sig    *sigs;
    int        nsigs;
    /* Per item and beat (item-major): the cycle it appeared, and raws per port. */
    uint64_t  *beat_cycle;
    int64_t   *raw;              /* [item][beat][port] */
} tb_result;

/* Figures derived from tb_ppa (tb_ppa.c): output beats (pixels) per
 * second at f_max, and energy per beat; NaN where unknown. */
double tb_pixels_per_s(const tb_result *r);
double tb_energy_pj_per_pixel(const tb_result *r);
/* Limits on speed and energy (0: none): --min-throughput, --max-energy. */
typedef struct tb_ppa_limits {
    double min_items_per_s;
    double max_energy_pj;     /* per item */
} tb_ppa_limits;
/* 1 if r meets l (NULL: no limits); else 0 and why ("... items/s < ..."). */
int tb_ppa_meets(const tb_result *r, const tb_ppa_limits *l, char *why, size_t len);
/* The critical path's signals as "a -> b -> c" (a path of more than ten:
 * its first and last four around "... (N more)"), cut to fit buf; and as
 * the JSON object {"levels": L, "ps": P, "signals": [...]}. */
void tb_ppa_path_text(const tb_ppa *p, char *buf, size_t len);
void tb_ppa_json_path(FILE *f, const tb_ppa *p);

typedef struct tb_opts {
    const char *vcd_path;        /* NULL: no dump */
    int         gtkw;            /* also write VCD_PATH with .gtkw */
    int         vcd_window;      /* dump only items vcd_from..vcd_to (testbench/tb_wave.h) */
    size_t      vcd_from, vcd_to;
    int         fst;             /* VCD_PATH is an FST file, converted by vcd2fst */
    int         lanes;           /* simulate on the batch's lanes where they give the kernel's
                                  * results (tb_lanes.h; not with a dump), else the kernel */
    int         reference;       /* the kernel as its reference, without its fast paths
                                  * (sim_set_reference; implies the kernel, not lanes) */
    int         threads;         /* the lanes' threads (0: 2); any number gives the same results */
} tb_opts;

enum { TB_OK = 0, TB_FAIL = 1, TB_BADINPUT = 2 };

/* A unit built into a context of its own, as every testbench starts one:
 * the configuration's rounding and overflow as the context's defaults, a
 * 1-bit clock "clk", the unit's scope (named after it) and its ports. The
 * caller adds the clock's timing and its own processes, and frees b->c
 * with sim_free. Returns 0; or -1 with err when the unit refuses the
 * configuration (b->c is made all the same: free it). */
typedef struct tb_built {
    sim_ctx    *c;
    sim_signal *clk;
    sim_scope  *sc;
    unit_io     io;
} tb_built;
int tb_build(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, tb_built *b, char *err, size_t errlen);

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
/* A unit's golden vectors generated from its float reference model: n
 * items (0: the model's default count) from seed. 0, or -1 with a message
 * (no reference model, generation failed). (tb_vectors.c) */
int  tb_make_vectors(const unit_desc *u, const unit_cfg *cfg, size_t n, uint64_t seed,
                     vec_set *vs, char *err, size_t errlen);

/* Formats from cfg->width, then overrides "NAME=sI.F" / "all=sI.F" applied
 * in order; 0, or -1 with a message. */
int  tb_formats(const unit_desc *u, const unit_cfg *cfg, const char *const *overrides,
                int n, unit_fmts *out, char *err, size_t errlen);

/* Compute r->ok, r->target_* and r->why for acceptance a (NULL: none;
 * tb_run does this with none, callers with a user's targets call it again). The verdict is
 * ok when the bound check is ok, the golden check is ok, no signal
 * overflowed (unless allowed), and the user's targets, if any, are met. */
void tb_verdict(tb_result *r, const tb_accept *a);
/* Overflows as "NAME:COUNT NAME:COUNT" (signals with any), for a CSV
 * column or a message; "" if none. */
void tb_overflow_list(const tb_result *r, char *buf, size_t len);

/* snprintf into a fixed text field, cut to fit (claims and atlas rows). */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void tb_settext(char *dst, size_t size, const char *fmt, ...);

/* Output writers. Each writes atomically where it writes a file. */
int  tb_write_json(FILE *f, const tb_result *r);
int  tb_write_csv(const char *path, const tb_result *r, const vec_set *vs, char *err, size_t errlen);
void tb_print_table(FILE *f, const tb_result *r);
/* The per-signal range table; all: every signal, else only those that
 * overflowed. */
void tb_print_ranges(FILE *f, const tb_result *r, int all);
#endif
