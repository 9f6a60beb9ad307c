/* tb_netlist_int.h - what the netlist writer and reader share (tb_netlist.h). */
#ifndef TB_NETLIST_INT_H
#define TB_NETLIST_INT_H
#include "testbench/tb_netlist.h"
#include <stdio.h>
#include <stdint.h>

/* What a line adds to its element's constructor (the writer's self-check
 * finds them): the depth of a logic element in AND2 levels
 * (sim_logic_depth), a constant multiplier as a shift-and-add network
 * (brdf_cmul). */
enum { NL_FIX_DEPTH = 1u, NL_FIX_CSD = 2u };

/* A character of a signal or scope name. */
static inline int nl_name_char(char ch)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
}
/* x in the fewest digits that read back as x (%.15g to %.17g). */
const char *nl_real_str(double x, char *buf, size_t len);
/* s as "..." with \\, \" and \n escaped. */
void nl_put_quoted(FILE *f, const char *s);
/* A logic element that is wiring (tb_netlist_bits.c): its output is the
 * concatenation, most significant first, of items: an input's bits
 * (%K, %K[B], %K[H:L]), inverted with a leading ~, or constant bits
 * (W'bBITS, W'hHEX); at most 64 bits in all, zero-extended or cut to the
 * output's width. */
#define NL_BITS_MAX 16
typedef struct nl_bits_item { int8_t in; uint8_t hi, lo, inv; uint64_t k; } nl_bits_item;   /* in -1: k */
typedef struct nl_bits { int n; nl_bits_item item[NL_BITS_MAX]; } nl_bits;
/* text ("{%0,2'b01}", no blanks) for inputs of widths in_width[0..nin-1]:
 * 0, or -1 when it is not of that form. */
int     nl_bits_parse(const char *text, int nin, const int *in_width, nl_bits *out);
int64_t nl_bits_fn(const int64_t *in, void *user);   /* a sim_logic_fn; user: the nl_bits */
void    nl_bits_put(FILE *f, const nl_bits *b);
/* tb_netlist_load on text in memory (len bytes), named path in messages. */
const unit_desc *nl_load_text(const char *text, size_t len, const char *path, unit_cfg *cfg, unit_fmts *fm,
                              char *err, size_t errlen);

/* What the datapath form of a built unit adds to its netlist text
 * (tb_netlist_dpw.c writes it with tb_netlist_write.c's lines): per
 * signal (creation order) its format as a rule of W ("": the format as
 * built) and whether the reader makes it from the schedule block, which
 * goes where signal `anchor` was (-1: no block, the handshake written
 * out as the unit's schedule `sched`). */
typedef struct nl_dpw {
    char (*rule)[48];
    unsigned char *skip;
    int anchor;
    const char *block;
} nl_dpw;
/* The text of built unit b (u with cfg and the --fmt overrides), checked
 * by building it back: a netlist (dp NULL) or a datapath file. *buf
 * malloc'd; 0, or -1 with err. */
int nl_write_text(const nl_dpw *dp, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                  const tb_built *b, char **buf, size_t *len, char *err, size_t errlen);
/* text built at width W (0: its own) is b, signal by signal: 0, or -1 with err. */
int nl_check_at(const char *text, size_t len, const tb_built *b, int W, char *err, size_t errlen);

/* ---- the reader's records (tb_netlist_parse.c reads the lines into them,
 * tb_netlist_read.c resolves the names and builds) ---- */
#define NL_NONE (-1)
#define NL_CLK  (-2)                     /* the clock, as an operand */
#define NL_ERR  (-3)                     /* a name that did not resolve (message given) */

typedef struct nl_el {
    int         line;
    sim_kind    kind;
    char       *name;       /* path below the unit's scope */
    const char *leaf;       /* its last part */
    int         scope;      /* index into nl.scopes, NL_NONE: the unit's */
    sim_fmt     fmt;
    int         r, o;       /* round=, overflow=: the mode, or NL_NONE */
    /* operands: names as read, then indices into nl.el (NL_CLK, NL_NONE) */
    char       *ref[5];
    int         op[5];      /* OP_A, OP_B, OP_C, OP_RST, OP_CLK */
    int         n;
    char      **in_ref;
    int        *in;
    long long   raw, rst_raw;
    unsigned long long ovf;
    int         shift;
    double      area;
    int         has_area, depth, csd, fn_unit, fn_verilog;
    char       *verilog;
    const char *table_hex;
    const char *bits_text;  /* bits=, parsed into bits */
    nl_bits    *bits;
    uint64_t   *table;
    sim_logic_fn fn;        /* fn=unit: the built-in unit's */
    void       *user;
    /* a datapath file's own (tb_datapath.c) */
    struct nl_rule *rule;   /* the format as a rule of the width (NULL: fmt as written) */
    double      range[2], draw[2], value;
    int         has_range, has_draw, has_value;
    char       *what;
    int         gen;        /* NL_GEN_*: made by the reader for the control */
    int         ctl;        /* NL_GEN_CTL: index into nl.ctl */
    int         sig;        /* index into the unit's signals, -1: none */
} nl_el;

/* The format of a datapath file's element as a rule of the width W:
 * sI.F with I = i0 + i1 W and F = f0 + f1 W, and the format's own modes. */
typedef struct nl_rule { int sg, i0, i1, f0, f1; char modes[24]; char text[48]; } nl_rule;
/* The control the reader makes from a datapath file's schedules: the step
 * counter, its next-state logic, a decoder per control signal, the last
 * step (in_ready) and the input and output handshake. */
enum { NL_GEN_NONE, NL_GEN_VALID, NL_GEN_STEP, NL_GEN_NEXT, NL_GEN_CTL, NL_GEN_LAST, NL_GEN_OUTV };
#define NL_MAX_CLOCKS 256   /* the step counter's 8 bits; a ctl row is one line (NL_MAX_TOK) */
typedef struct nl_ctl {
    char *name;
    int   line, el;
    int   val[UNIT_MAX_SCHED][NL_MAX_CLOCKS];
    unsigned have;          /* bit s: schedule s gave its row */
} nl_ctl;
#define NL_MAX_CTL 32
enum { OP_A, OP_B, OP_C, OP_RST, OP_CLK };

typedef struct nl {
    unit_desc   desc;       /* the unit it builds (first: the registry's key) */
    const unit_desc *base;  /* the built-in unit it names */
    unit_cfg    cfg;
    unit_fmts   fm;
    char      **fmt;        /* fmt lines */
    int         nfmt;
    char       *clk;
    char      **scopes;
    int        *scope_parent;
    int         nscope;
    nl_el      *el;
    int         nel, cap;
    char      **port_ref[5];   /* in, out, in_valid, in_ready, out_valid */
    int        *port[5];
    int         nport[5];
    int         port_line[5][UNIT_MAX_IO];
    tb_built    ref;        /* the built-in unit, built for fn=unit (ref.c NULL: not) */
    void      **mem;        /* every allocation, freed with it */
    struct tb_vexpr **vx;   /* fn=verilog's programs, freed with it */
    int         nvx;
    size_t      nmem, capmem;
    const char *path;
    int         version;    /* the netlist line seen */
    int         line;
    char       *err;
    size_t      errlen;
    /* a datapath file (datapath NAME): a unit of its own (tb_datapath.c) */
    int         dp, dp_line;
    char       *dp_name, *dp_summary;
    int         nsched, cur_sched, ctl_open, step_bits;
    int         latency, latency_line;   /* latency N: a pipeline (no schedule) */
    char        pipe_what[64];
    char       *sched_name[UNIT_MAX_SCHED], *sched_what[UNIT_MAX_SCHED];
    int         sched_clocks[UNIT_MAX_SCHED], sched_line[UNIT_MAX_SCHED];
    nl_ctl      ctl[NL_MAX_CTL];
    int         nctl;
    char       *ideal_out[UNIT_MAX_IO], *ideal_text[UNIT_MAX_IO];
    int         ideal_line[UNIT_MAX_IO], nideal;
    struct tb_expr *ideal[UNIT_MAX_IO];   /* by output port */
    int         slot;       /* its place among the live datapath units */
    /* ideal unit=NAME: the built-in unit (base) whose float reference,
     * vectors, ideal, bound, parameters and schedules the file runs with
     * (what netlist --datapath writes); schedule NAME names the one its
     * own control is for, when it has no schedule blocks */
    int         ref_line, ref_sched_line;
    int         hs_line;    /* the first port in_valid/in_ready/out_valid: the handshake is the file's */
    vec_model   model;
} nl;
enum { P_IN, P_OUT, P_IN_VALID, P_IN_READY, P_OUT_VALID };
extern const char *const nl_port_names[5];   /* the ROLEs of port lines */

/* Memory owned by x (zeroed), freed with it. */
void *nl_alloc(nl *x, size_t n);
char *nl_strdup(nl *x, const char *s, size_t n);
/* "PATH:LINE: message" (line 0: "PATH: message") into x's err; -1. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
int nl_bad(nl *x, int line, const char *fmt, ...);
/* 1 if s is a name or a path of names joined by single dots. */
int nl_name_ok(const char *s);
/* One line of the file into x: 0, or -1 after nl_bad. */
int nl_parse_line(nl *x, char *line);
/* A new element record at the end of x->el (zeroed but for its defaults). */
nl_el *nl_el_new(nl *x, sim_kind kind, const char *name, sim_fmt f);

/* ---- datapath files (tb_datapath.c) ---- */
/* The lines only a datapath file has (schedule, ctl, ideal) and its
 * element attributes: 0, 1 (not such a line), or -1. */
int nl_dp_line(nl *x, char **tok, int nt);
/* A format token of a datapath file: a rule of W or a plain format. */
int nl_dp_format(nl *x, nl_el *e, const char *tok);
/* A rule at width W: 0, or -1 with why in err. */
int nl_rule_at(const nl_rule *r, int W, sim_fmt *f, char *err, size_t errlen);
/* Every rule at the file's width, into its element's format (the
 * checks of tables and fn=unit read them): 0, or -1 after nl_bad. */
int nl_dp_rules(nl *x);
/* The end of the file: the handshake's elements and ports. */
int nl_dp_close(nl *x);
/* After the names are resolved: the elements in an order where each
 * operand comes first (a combinational loop is an error naming it), the
 * ideal expressions, the unit. NULL after nl_bad. */
const unit_desc *nl_dp_finish(nl *x, unit_cfg *cfg, unit_fmts *fm);
/* The shared builder (tb_netlist_read.c): the elements with formats
 * fmt[0..nel-1] (NULL: each element's own), logic tables for the control
 * from the datapath's schedule sched. */
int nl_build(nl *x, const sim_fmt *fmt, int sched, sim_ctx *c, sim_scope *sc, sim_signal *clk, unit_io *io,
             char *err, size_t errlen);
void nl_free(nl *x);
void nl_dp_release(const nl *x);   /* its slot and expressions */
/* Resolve every name (tb_netlist_read.c) */
int nl_resolve_all(nl *x);
#endif
