/* test_cells.c - every element kind against its one definition,
 * sim_elem_eval (sim/sim_elem_eval.c), exhaustively for narrow formats, as
 * Yosys's test_cell checks every cell type's implementations against each
 * other.
 *
 * A cell is one kind with given operand formats: its inputs, and one
 * element of the kind for every output format and every rounding and
 * overflow mode (the output format's own modes), all in one design. Every
 * combination of input values, over the inputs' whole formats, is run
 *  - on the fast kernel and on the reference kernel (sim_set_reference),
 *    in step, one combination a time step: each output, and each overflow
 *    counted (every element is an output, so every overflow is used);
 *  - on the batch's lanes, one combination a lane, through its vector
 *    loops (where the CPU has them: AVX-512's and AVX2's both, on a CPU
 *    with the first) and through its scalar loops alone:
 *    each output and each lane's overflow flag;
 *  - through the intervals (sim_ival_eval): a point gives the value
 *    itself, and a box of inputs gives an interval holding the value at
 *    every point of the box (soundness),
 * and compared with sim_elem_eval of the element's record.
 *
 * Formats: widths 1 to 4 (TST_CELLS_FULL=1, tests/slow.list's
 * test_cells_full) or 1 to 2 for the operands and 1 to 3 for the outputs
 * (the quick table, `make test-quick`), signed and unsigned, every
 * fraction-bit count from 0 to the width (so the operands' binary points
 * are offset from each other and from the output's). Kinds: every kind of
 * sim_elem.h's list that a primitive computes.
 */
#include "tests/tst.h"
#include "sim/sim_prim.h"
#include "sim/sim_batch.h"
#include "sim/sim_ival.h"
#include "sim/sim_verilog.h"
#include <stdint.h>

#define MAXF   32          /* formats */
#define MAXIN  3           /* input signals of a cell */
#define MAXEL  (MAXF * 6 * 5)
#define MAXCMB 1024        /* input combinations (4 * 16 * 16) */
#define LANES  64

static sim_fmt in_f[MAXF], out_f[MAXF];
static int n_in_f, n_out_f;
static const int SHIFTS[] = { -2, -1, 0, 1, 2 };

static int list_fmts(sim_fmt *f, int wmax)
{
    int n = 0;
    for (int s = 0; s <= 1; s++)
        for (int w = 1; w <= wmax; w++)
            for (int fb = 0; fb <= w; fb++) {
                char err[100];
                if (sim_fmt_make(s, w - fb, fb, &f[n], err, sizeof err) == 0) n++;
            }
    return n;
}

static sim_fmt u_fmt(int w)
{
    sim_fmt f;
    char err[100];
    sim_fmt_make(0, w, 0, &f, err, sizeof err);
    return f;
}

static int64_t cell_logic(const int64_t *in, void *user)
{
    (void)user;
    return in[0] * 3 - (in[1] ^ 5);
}

static int is_binary(sim_kind k)
{
    return k == SIM_KIND_MUX || k == SIM_KIND_ADD || k == SIM_KIND_SUB || k == SIM_KIND_MUL || k == SIM_KIND_LOGIC;
}

/* "s1.1" or "s1.1, u2.0": the cell's operand formats, for messages. */
static const char *opnds(sim_kind k, sim_fmt fa, sim_fmt fb, char *buf)
{
    char x[SIM_FMT_STRLEN], z[SIM_FMT_STRLEN];
    sim_fmt_str(fa, x);
    if (!is_binary(k)) { strcpy(buf, x); return buf; }
    sprintf(buf, "%s, %s", x, sim_fmt_str(fb, z));
    return buf;
}

/* One cell in one context. */
typedef struct cell {
    sim_ctx    *c;
    sim_signal *clk, *in[MAXIN];
    int         nin;
    sim_signal *y[MAXEL];
    sim_prim_info e[MAXEL];   /* each element's record */
    int         ny;
} cell;

/* The cell of kind k on operand formats fa, fb: inputs (a select, pass,
 * enable or reset of u2.0 or u1.0 where the kind has one), then the
 * elements. */
static void cell_build(cell *d, sim_kind k, sim_fmt fa, sim_fmt fb)
{
    memset(d, 0, sizeof *d);
    d->c = sim_new();
    sim_scope *sc = sim_scope_new(d->c, sim_root(d->c), "cell");
    d->clk = sim_bit_new(d->c, NULL, "clk", SIM_KIND_CLOCK);
    sim_signal *a = sim_signal_new(d->c, sc, "a", fa, SIM_KIND_INPUT), *b = NULL, *x = NULL, *z = NULL;
    switch (k) {
    case SIM_KIND_MUX: x = sim_signal_new(d->c, sc, "sel", u_fmt(2), SIM_KIND_INPUT); break;
    case SIM_KIND_BK:  x = sim_signal_new(d->c, sc, "pass", u_fmt(1), SIM_KIND_INPUT); break;
    case SIM_KIND_REG:
        x = sim_signal_new(d->c, sc, "en", u_fmt(1), SIM_KIND_INPUT);
        z = sim_signal_new(d->c, sc, "rst", u_fmt(1), SIM_KIND_INPUT);
        break;
    default: break;
    }
    int binary = is_binary(k);
    if (binary) b = sim_signal_new(d->c, sc, "b", fb, SIM_KIND_INPUT);
    sim_signal *all[] = { x, a, b, z };
    for (int i = 0; i < 4; i++) if (all[i]) d->in[d->nin++] = all[i];
    int nsh = k == SIM_KIND_SHIFT ? 5 : 1;
    for (int f = 0; f < n_out_f; f++)
        for (int m = 0; m < 6; m++)
            for (int s = 0; s < nsh; s++) {
                sim_fmt fy = out_f[f];
                fy.rnd = (uint8_t)(1 + m / 2);
                fy.ovf = (uint8_t)(1 + m % 2);
                char name[32];
                snprintf(name, sizeof name, "y%d", d->ny);
                sim_signal *y = NULL, *mi[2] = { a, b };
                switch (k) {
                case SIM_KIND_WIRE:
                    y = sim_signal_new(d->c, sc, name, fy, SIM_KIND_WIRE);
                    sim_assign(d->c, y, a);
                    break;
                case SIM_KIND_REG:   y = sim_reg(d->c, sc, name, fy, d->clk, a, x, z, 1); break;
                case SIM_KIND_MUX:   y = sim_mux(d->c, sc, name, fy, x, 2, mi); break;
                case SIM_KIND_BK:    y = sim_bk(d->c, sc, name, fy, x, a); break;
                case SIM_KIND_ADD:   y = sim_add(d->c, sc, name, fy, a, b); break;
                case SIM_KIND_SUB:   y = sim_sub(d->c, sc, name, fy, a, b); break;
                case SIM_KIND_MUL:   y = sim_mul(d->c, sc, name, fy, a, b); break;
                case SIM_KIND_SHIFT: y = sim_shift(d->c, sc, name, fy, a, SHIFTS[s]); break;
                case SIM_KIND_LOGIC: y = sim_logic(d->c, sc, name, fy, 2, mi, cell_logic, NULL, 1.0); break;
                default: break;
                }
                sim_signal_output(y);
                TST_EQ_INT(sim_prim_describe(y, &d->e[d->ny]), 0);
                d->y[d->ny++] = y;
            }
}

/* Combination i's input values into v. */
static int ncombos(const cell *d)
{
    int n = 1;
    for (int j = 0; j < d->nin; j++) n *= (int)(d->in[j]->raw_max - d->in[j]->raw_min + 1);
    return n;
}
static void combo(const cell *d, int i, int64_t *v)
{
    for (int j = d->nin - 1; j >= 0; j--) {
        int span = (int)(d->in[j]->raw_max - d->in[j]->raw_min + 1);
        v[j] = d->in[j]->raw_min + i % span;
        i /= span;
    }
}

/* Element e's input values (sim_elem_read's order) from the cell's input
 * values v, by signal. */
static void elem_inputs(const cell *d, const sim_prim_info *e, const int64_t *v, int64_t *ev)
{
    int n = sim_elem_nin(e);
    /* point the element's inputs at the cell's values: read them as the
     * kernel would, from a copy whose signals hold v */
    for (int j = 0; j < d->nin; j++) d->in[j]->cur = v[j];
    int64_t tmp[8];
    sim_elem_read(e, tmp);
    for (int j = 0; j < n; j++) ev[j] = tmp[j];
}

typedef struct expect { int64_t out[MAXEL]; int wr[MAXEL], ovf[MAXEL]; } expect;

/* sim_elem_eval of every element for combination v (on a scratch cell
 * whose input signals are set to v). */
static void definition(const cell *d, const int64_t *v, expect *x)
{
    for (int k = 0; k < d->ny; k++) {
        int64_t ev[8];
        elem_inputs(d, &d->e[k], v, ev);
        x->wr[k] = sim_elem_eval(&d->e[k], ev, &x->out[k], &x->ovf[k]);
    }
}

static uint64_t ovf_of(const sim_signal *y) { return y->overflows + y->ovf_discarded; }

static int bad;   /* failures reported in the current kind (the log stays short) */

/* The fast kernel and the reference kernel, in step, against the
 * definition; a scratch cell (never run) evaluates the definition. */
static void kernels(sim_kind k, sim_fmt fa, sim_fmt fb)
{
    static cell d[3];
    for (int i = 0; i < 3; i++) cell_build(&d[i], k, fa, fb);
    sim_set_reference(d[1].c, 1);
    static expect x;
    int64_t q[2][MAXEL];
    for (int i = 0; i < 2; i++) {
        TST_EQ_INT(sim_run(d[i].c, 0), SIM_OK);
        for (int j = 0; j < d[i].ny; j++) q[i][j] = d[i].y[j]->cur;
    }
    int n = ncombos(&d[2]);
    int64_t prev[MAXIN] = { 0 };
    for (int ci = 0; ci < n; ci++) {
        int64_t v[MAXIN];
        combo(&d[2], ci, v);
        definition(&d[2], v, &x);
        for (int i = 0; i < 2; i++) {
            cell *c = &d[i];
            uint64_t o0[MAXEL];
            for (int j = 0; j < c->ny; j++) o0[j] = ovf_of(c->y[j]);
            for (int j = 0; j < c->nin; j++) sim_force(c->in[j], v[j]);
            sim_run(c->c, (sim_time)(2 * ci + 1));
            int reg = k == SIM_KIND_REG;
            if (reg) {   /* the edge: registers take the definition's value */
                sim_force(c->clk, 1);
                sim_run(c->c, (sim_time)(2 * ci + 2));
                sim_force(c->clk, 0);
            }
            for (int j = 0; j < c->ny; j++) {
                /* an element not woken (its own inputs unchanged) counts nothing */
                int woken = reg || ci == 0;
                for (int t = 0; t < c->nin && !woken; t++) woken = v[t] != prev[t];
                if (x.wr[j]) q[i][j] = x.out[j];
                uint64_t dov = ovf_of(c->y[j]) - o0[j];
                if ((c->y[j]->cur != q[i][j] || (woken && dov != (uint64_t)x.ovf[j]) || (!woken && dov)) &&
                    bad++ < 8) {
                    char fs[3][SIM_FMT_STRLEN], ops[2 * SIM_FMT_STRLEN + 2];
                    TST_CHECK(0, "%s %s -> %s (%s kernel), inputs %lld %lld %lld: %lld, overflows %llu; "
                              "the definition %lld, overflow %d", sim_kind_name(k), opnds(k, fa, fb, ops),
                              sim_fmt_str(c->y[j]->fmt, fs[2]), i ? "reference" : "fast",
                              (long long)v[0], (long long)(c->nin > 1 ? v[1] : 0), (long long)(c->nin > 2 ? v[2] : 0),
                              (long long)c->y[j]->cur, (unsigned long long)dov, (long long)q[i][j], x.ovf[j]);
                }
            }
        }
        memcpy(prev, v, sizeof prev);
    }
    TST_CHECK(d[1].c && sim_get_stats(d[1].c)->fast_paths == 0, "the reference took a fast path");
    for (int i = 0; i < 3; i++) sim_free(d[i].c);
}

/* The batch: every combination a lane, LANES at a time, with vector loops
 * of at most vec lanes (0: the scalar loops alone). Returns the groups
 * its vector loops evaluated. */
static uint64_t batch(sim_kind k, sim_fmt fa, sim_fmt fb, uint32_t vec)
{
    static cell d, s;
    cell_build(&d, k, fa, fb);
    cell_build(&s, k, fa, fb);
    static expect x[LANES];
    sim_batch_vector(vec);
    int n = ncombos(&d);
    uint64_t groups = 0;
    for (int c0 = 0; c0 < n; c0 += LANES) {
        char err[300];
        sim_batch *b = sim_batch_new(d.c, d.clk, LANES, err, sizeof err);
        TST_CHECK(b != NULL, "%s: the batch refuses it: %s", sim_kind_name(k), err);
        if (!b) break;
        /* every input 0 at the start (no overflow there: 0 is in every
         * format), then the combinations at an edge, so that the loops
         * after an edge (the vector ones among them) evaluate them; a
         * second edge loads the registers */
        sim_batch_start(b);
        for (uint32_t l = 0; l < LANES; l++) {
            int64_t v[MAXIN];
            combo(&d, c0 + (int)l < n ? c0 + (int)l : c0, v);
            definition(&s, v, &x[l]);
            for (int j = 0; j < d.nin; j++) sim_batch_set(b, d.in[j], l, v[j]);
        }
        sim_batch_cycle(b);
        sim_batch_cycle(b);
        for (uint32_t l = 0; l < LANES; l++) {
            int any = 0;
            for (int j = 0; j < d.ny; j++) {
                int64_t want = x[l].wr[j] ? x[l].out[j] : d.y[j]->cur;   /* a held register: its reset value */
                any |= x[l].ovf[j];
                if (sim_batch_val(b, d.y[j])[l] != want && bad++ < 8) {
                    char fs[3][SIM_FMT_STRLEN], ops[2 * SIM_FMT_STRLEN + 2];
                    TST_CHECK(0, "%s %s -> %s (batch, vectors %u), lane %u: %lld, the definition %lld",
                              sim_kind_name(k), opnds(k, fa, fb, ops),
                              sim_fmt_str(d.y[j]->fmt, fs[2]), vec, l,
                              (long long)sim_batch_val(b, d.y[j])[l], (long long)want);
                }
            }
            if (sim_batch_overflowed(b, l) != any && bad++ < 8)
                TST_CHECK(0, "%s (batch, vectors %u), lane %u: overflow flag %d, the definition %d",
                          sim_kind_name(k), vec, l, sim_batch_overflowed(b, l), any);
        }
        uint64_t g, fell;
        sim_batch_vector_stats(b, &g, &fell);
        groups += g;
        sim_batch_free(b);
    }
    sim_batch_vector(8);
    sim_free(d.c);
    sim_free(s.c);
    return groups;
}

/* The intervals: points give the definition's value; boxes hold it. */
static void intervals(sim_kind k, sim_fmt fa, sim_fmt fb)
{
    static cell d;
    static expect all[MAXCMB];
    static int64_t cv[MAXCMB][MAXIN];
    cell_build(&d, k, fa, fb);
    int n = ncombos(&d);
    uint32_t ns = sim_signal_count(d.c);
    sim_ival *vals = calloc(ns, sizeof *vals);
    int64_t held[MAXEL];
    for (int j = 0; j < d.ny; j++) held[j] = d.y[j]->cur;   /* a register's value before the edge */
    for (int ci = 0; ci < n; ci++) {
        combo(&d, ci, cv[ci]);
        definition(&d, cv[ci], &all[ci]);
    }
    for (int j = 0; j < d.ny; j++) { d.y[j]->cur = held[j]; vals[d.y[j]->index].lo = vals[d.y[j]->index].hi = held[j]; }
    /* boxes: each input over its whole format, its lower or upper half,
     * or -1..1; a point is a box of one combination */
    int nbox = 1;
    for (int t = 0; t < d.nin; t++) nbox *= 4;
    for (int bi = -n; bi < nbox; bi++) {
        sim_ival box[MAXIN];
        for (int t = 0, r = bi; t < d.nin; t++, r /= 4) {
            int64_t lo = d.in[t]->raw_min, hi = d.in[t]->raw_max, mid = lo + (hi - lo) / 2;
            if (bi < 0) { box[t].lo = box[t].hi = cv[bi + n][t]; continue; }
            switch (r % 4) {
            case 0: box[t].lo = lo; box[t].hi = hi; break;
            case 1: box[t].lo = lo; box[t].hi = mid; break;
            case 2: box[t].lo = mid < hi ? mid + 1 : hi; box[t].hi = hi; break;
            default: box[t].lo = lo > -1 ? lo : -1; box[t].hi = hi < 1 ? hi : 1; break;
            }
            if (box[t].lo > box[t].hi) box[t].lo = box[t].hi;
        }
        for (int t = 0; t < d.nin; t++) vals[d.in[t]->index] = box[t];
        for (int j = 0; j < d.ny; j++) {
            sim_ival pre, post;
            if (sim_ival_eval(d.y[j], vals, &pre, &post)) { TST_CHECK(0, "%s: no interval", sim_kind_name(k)); return; }
            for (int ci = 0; ci < n; ci++) {
                int in_box = 1;
                for (int t = 0; t < d.nin; t++) in_box &= cv[ci][t] >= box[t].lo && cv[ci][t] <= box[t].hi;
                if (!in_box) continue;
                int64_t want = all[ci].wr[j] ? all[ci].out[j] : held[j];
                int fail = bi < 0 ? post.lo != want || post.hi != want : want < post.lo || want > post.hi;
                if (fail && bad++ < 8) {
                    char fs[3][SIM_FMT_STRLEN], ops[2 * SIM_FMT_STRLEN + 2];
                    TST_CHECK(0, "%s %s -> %s (intervals, %s), inputs %lld %lld %lld: [%lld, %lld], "
                              "the definition %lld", sim_kind_name(k), opnds(k, fa, fb, ops),
                              sim_fmt_str(d.y[j]->fmt, fs[2]), bi < 0 ? "a point" : "a box",
                              (long long)cv[ci][0], (long long)(d.nin > 1 ? cv[ci][1] : 0),
                              (long long)(d.nin > 2 ? cv[ci][2] : 0), (long long)post.lo, (long long)post.hi,
                              (long long)want);
                }
            }
        }
    }
    free(vals);
    sim_free(d.c);
}

static const sim_kind KINDS[] = { SIM_KIND_WIRE, SIM_KIND_REG, SIM_KIND_MUX, SIM_KIND_BK, SIM_KIND_ADD,
                                  SIM_KIND_SUB, SIM_KIND_MUL, SIM_KIND_SHIFT, SIM_KIND_LOGIC };
#define NKINDS ((int)(sizeof KINDS / sizeof KINDS[0]))

/* Every operand format pair of kind k (a second operand only where it
 * has one) through fn. */
static void each_cell(sim_kind k, void (*fn)(sim_kind, sim_fmt, sim_fmt))
{
    int binary = is_binary(k);
    for (int i = 0; i < n_in_f; i++)
        for (int j = 0; j < (binary ? n_in_f : 1); j++) fn(k, in_f[i], in_f[j]);
}

static void t_kernels(void)
{
    for (int i = 0; i < NKINDS; i++) { bad = 0; each_cell(KINDS[i], kernels); }
}

static uint64_t vec_groups, vec4_groups;
static uint32_t vec_width;
static void batch_vec(sim_kind k, sim_fmt fa, sim_fmt fb) { vec_groups += batch(k, fa, fb, 8); }
static void batch_vec4(sim_kind k, sim_fmt fa, sim_fmt fb) { vec4_groups += batch(k, fa, fb, 4); }
static void batch_scalar(sim_kind k, sim_fmt fa, sim_fmt fb) { TST_EQ_INT(batch(k, fa, fb, 0), 0); }

static void t_batch(void)
{
    vec_width = sim_batch_vector(8);
    for (int i = 0; i < NKINDS; i++) {
        bad = 0;
        each_cell(KINDS[i], batch_scalar);
        each_cell(KINDS[i], batch_vec);
        /* a CPU with AVX-512 runs the AVX2 loops too (their emulated
         * product and arithmetic shift are their own) */
        if (vec_width > 4) each_cell(KINDS[i], batch_vec4);
    }
    /* the vector loops ran, where this CPU has them */
    TST_CHECK(vec_width == 0 || vec_groups > 0, "vector width %u but no group evaluated", vec_width);
    TST_CHECK(vec_width <= 4 || vec4_groups > 0, "the AVX2 loops evaluated no group");
}

static void t_intervals(void)
{
    for (int i = 0; i < NKINDS; i++) { bad = 0; each_cell(KINDS[i], intervals); }
}

/* ---- Icarus: one generated table of cases against the Verilog export ----
 * Each kind's cell on two operand formats (signed and unsigned, their
 * binary points offset), every output format and mode of the quick table:
 * exported (sim_verilog_module), driven by a generated testbench over
 * every input combination, simulated by Icarus; each output's bits against
 * sim_elem_eval's. */

static int have(const char *tool)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* The testbench: inputs counted up through every bit pattern, then the
 * outputs shown (after the clock's edge, for registers) one line per
 * combination: the inputs' bits, then each output's. */
static void write_tb(FILE *f, const cell *d, int reg)
{
    fprintf(f, "`timescale 1ns/1ps\nmodule tb;\nreg clk = 0;\n");
    int bits = 0;
    for (int j = 0; j < d->nin; j++) {
        fprintf(f, "reg [%d:0] i%d = 0;\n", d->in[j]->fmt.width - 1, j);
        bits += d->in[j]->fmt.width;
    }
    for (int k = 0; k < d->ny; k++) fprintf(f, "wire [%d:0] y%d;\n", d->y[k]->fmt.width - 1, k);
    fprintf(f, "cells_dut u(.clk(clk)");
    for (int j = 0; j < d->nin; j++) fprintf(f, ", .%s(i%d)", d->in[j]->name, j);
    for (int k = 0; k < d->ny; k++) fprintf(f, ", .y%d(y%d)", k, k);
    fprintf(f, ");\ninteger n;\ninitial begin\n  for (n = 0; n < %d; n = n + 1) begin\n    {", 1 << bits);
    for (int j = 0; j < d->nin; j++) fprintf(f, "%si%d", j ? ", " : "", j);
    fprintf(f, "} = n;\n    #1;\n");
    if (reg) fprintf(f, "    clk = 1; #1; clk = 0; #1;\n");
    fprintf(f, "    $write(\"");
    for (int j = 0; j < d->nin; j++) fprintf(f, "%%0d ");
    fprintf(f, ":\"");
    for (int j = 0; j < d->nin; j++) fprintf(f, ", i%d", j);
    fprintf(f, ");\n");
    for (int k = 0; k < d->ny; k++) fprintf(f, "    $write(\" %%0d\", y%d);\n", k);
    fprintf(f, "    $write(\"\\n\");\n  end\n  $finish;\nend\nendmodule\n");
}

static uint64_t low_bits(int64_t v, int w) { return (uint64_t)v & (UINT64_MAX >> (64 - w)); }

/* Export d, simulate it, compare; the lines compared, or -1. */
static int icarus_cell(const char *dir, sim_kind k, sim_fmt fa, sim_fmt fb)
{
    static cell d, s;
    static expect x;
    cell_build(&d, k, fa, fb);
    cell_build(&s, k, fa, fb);
    char path[512], cmd[1400], err[300];
    sim_vport ports[MAXIN + MAXEL];
    int np = 0;
    for (int j = 0; j < d.nin; j++) ports[np++] = (sim_vport){ d.in[j]->name, d.in[j], 0 };
    for (int j = 0; j < d.ny; j++) ports[np++] = (sim_vport){ d.y[j]->name, d.y[j], 1 };
    snprintf(path, sizeof path, "%s/cell.v", dir);
    FILE *f = fopen(path, "w");
    int rc = f ? sim_verilog_module(f, d.c, sim_root(d.c)->first_child, "cells_dut", d.clk, SIM_VRESET_NONE, ports,
                                    np, err, sizeof err) : -1;
    if (f) fclose(f);
    TST_CHECK(rc == 0, "%s: export: %s", sim_kind_name(k), f ? err : "cannot write");
    snprintf(path, sizeof path, "%s/tb.v", dir);
    if (rc == 0 && (f = fopen(path, "w"))) { write_tb(f, &d, k == SIM_KIND_REG); fclose(f); }
    snprintf(cmd, sizeof cmd, "cd %s && iverilog -g2005 -o cell.vvp tb.v cell.v >log 2>&1 && vvp -n cell.vvp >out 2>>log",
             dir);
    if (rc || system(cmd) != 0) { TST_CHECK(0, "%s: Icarus failed (%s/log)", sim_kind_name(k), dir); rc = -1; }
    snprintf(path, sizeof path, "%s/out", dir);
    f = rc ? NULL : fopen(path, "r");
    int lines = 0;
    int64_t q[MAXEL];
    for (int j = 0; j < d.ny; j++) q[j] = d.y[j]->cur;
    char line[16384];
    while (f && fgets(line, sizeof line, f)) {
        char *p = line;
        int64_t v[MAXIN];
        for (int j = 0; j < d.nin; j++) v[j] = sim_fx_canon(strtoll(p, &p, 10), d.in[j]->fmt);
        p = strchr(p, ':');
        if (!p) break;
        p++;
        definition(&s, v, &x);
        for (int j = 0; j < d.ny; j++) {
            unsigned long long got = strtoull(p, &p, 10);
            if (x.wr[j]) q[j] = x.out[j];
            if (got != low_bits(q[j], d.y[j]->fmt.width) && bad++ < 8) {
                char fs[SIM_FMT_STRLEN], ops[2 * SIM_FMT_STRLEN + 2];
                TST_CHECK(0, "%s %s -> %s (Icarus), inputs %lld %lld %lld: bits %llu, the definition %lld",
                          sim_kind_name(k), opnds(k, fa, fb, ops), sim_fmt_str(d.y[j]->fmt, fs), (long long)v[0],
                          (long long)(d.nin > 1 ? v[1] : 0), (long long)(d.nin > 2 ? v[2] : 0), got, (long long)q[j]);
            }
        }
        lines++;
    }
    if (f) fclose(f);
    TST_CHECK(rc || lines == ncombos(&d), "%s: %d lines from Icarus, %d combinations", sim_kind_name(k), lines,
              ncombos(&d));
    sim_free(d.c);
    sim_free(s.c);
    return rc ? -1 : lines;
}

static void t_icarus(void)
{
    /* the export (sim_verilog.c) reads no portable flag, and Icarus's run
     * of its bytes is a tool's, not the sanitized program's */
    if (!tst_plain_build()) TST_SKIP("the Verilog export's bytes are no flavour's own: the plain build runs it");
    if (!have("iverilog") || !have("vvp")) TST_SKIP("iverilog not installed");
    char dir[] = "/tmp/test_cells.XXXXXX";
    if (!mkdtemp(dir)) { TST_CHECK(0, "no temporary folder"); return; }
    sim_fmt fa, fb;
    char err[100];
    sim_fmt_make(1, 1, 1, &fa, err, sizeof err);   /* s1.1 */
    sim_fmt_make(0, 0, 2, &fb, err, sizeof err);   /* u0.2 */
    int cases = 0;
    for (int i = 0; i < NKINDS; i++) {
        bad = 0;
        int n = icarus_cell(dir, KINDS[i], fa, fb);
        if (n > 0) cases += n;
    }
    printf("  %d input combinations, every output format and mode, bit-exact in Icarus\n", cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (!tst_failed_checks && system(cmd) != 0) TST_CHECK(0, "cannot remove %s", dir);
}

int main(void)
{
    const char *full = getenv("TST_CELLS_FULL");
    int wide = full && *full == '1';
    n_in_f = list_fmts(in_f, wide ? 4 : 2);
    n_out_f = list_fmts(out_f, wide ? 4 : 3);
    TST_RUN(t_kernels);
    TST_RUN(t_batch);
    TST_RUN(t_intervals);
    TST_RUN(t_icarus);
    TST_EXIT();
}
