/* tb_datapath.c - a datapath file: the netlist text (docs/netlist.md) as a
 * unit of its own, with no built-in unit behind it (docs/datapaths.md).
 *
 * What a netlist takes from the unit it names, a datapath file says
 * itself: each element's format as a rule of the width W (s7.(W-7)), the
 * inputs' ranges, the control as a table of control words per clock of an
 * item in one or more schedules, and the ideal function as one expression
 * per output. From these the reader makes a unit_desc every verb runs as
 * it runs a built-in unit:
 *  - formats: each rule at the configuration's width (--width, sweeps);
 *  - the control: a step counter (the built-in Horner unit's: it waits at
 *    step 0 for in_valid and runs an item to its end), a decoder per
 *    control signal from the chosen schedule's rows, in_ready on the last
 *    step and out_valid a register of it; a pipeline (latency N) takes an
 *    item a clock, its valid bit through N registers; a file with neither
 *    is combinational (in_ready 1, out_valid = in_valid);
 *  - the float reference: the expressions in double, the golden vectors
 *    drawn uniformly from the inputs' ranges (draw=, else range=);
 *  - the ideal: the same expressions on the quantized inputs, exactly
 *    (sim_dy) where they have no division or square root;
 *  - the bound: the walk of unit_net.h over the elements, one clock at a
 *    time through the schedule, where the file has only the kinds it
 *    knows and every multiplexer and block key is driven by the control;
 *    otherwise none (the verdict then needs a target, which decides alone).
 * A file that names a built-in unit (ideal unit=NAME, as netlist --datapath
 * writes it) takes the unit's descriptor instead (its reference, vectors,
 * ideal, bound, parameters and schedules) with the file's build and
 * formats: its ports are the unit's, and an element named as one of the
 * unit's signals gives that signal its format. A file may also give its
 * own handshake (port in_valid/in_ready/out_valid lines) in place of
 * schedules: its control is then its own elements.
 * The descriptor's functions take no pointer to the file they came from,
 * so each live file has a slot with functions of its own (DP_SLOTS).
 */
#include "testbench/tb_netlist_int.h"
#include "testbench/tb_expr.h"
#include "units/unit_net.h"
#include "sim/sim_area.h"
#include "base/base_out.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BAD(...) nl_bad(x, x->line, __VA_ARGS__)
#define DP_DEFAULT_VECTORS 1000

static sim_fmt ufmt(int bits) { return unit_fmt(0, bits, 0); }

/* ------------------------------------------------------------ order and loops */

/* Depth-first over the operands: post-order is an order where every
 * operand comes first (the file's own order when it already is one); a
 * grey element met again closes a combinational loop. The recursion is
 * as deep as the longest chain, at most the UNIT_MAX_SIGS signals and the
 * control's elements (nl_dp_finish counts the signals first). */
typedef struct dp_topo { nl *x; unsigned char *col; int *ord, n, *stack, sp; } dp_topo;

static int edge_list(const nl_el *e, int *out)
{
    int n = 0;
    for (int k = 0; k < 5; k++) {
        if (e->op[k] < 0 || k == OP_CLK) continue;
        if (e->kind == SIM_KIND_REG && k == OP_A) continue;   /* a register breaks a loop */
        out[n++] = e->op[k];
    }
    for (int j = 0; j < e->n; j++) out[n++] = e->in[j];
    return n;
}

static int visit(dp_topo *t, int i)
{
    nl *x = t->x;
    if (t->col[i] == 2) return 0;
    if (t->col[i] == 1) {
        /* the stack holds the readers down to i: the data flows back up */
        char msg[300];
        snprintf(msg, sizeof msg, "%s", x->el[i].name);
        for (int k = t->sp - 1; k >= 0 && t->stack[k] != i; k--) {
            size_t m = strlen(msg);
            snprintf(msg + m, sizeof msg - m, " -> %s", x->el[t->stack[k]].name);
        }
        size_t m = strlen(msg);
        snprintf(msg + m, sizeof msg - m, " -> %s", x->el[i].name);
        return nl_bad(x, x->el[i].line, "a combinational loop: %s (a register must break it)", msg);
    }
    t->col[i] = 1;
    t->stack[t->sp++] = i;
    int ops[1040];
    int n = edge_list(&x->el[i], ops);
    for (int k = 0; k < n; k++) if (visit(t, ops[k])) return -1;
    t->sp--;
    t->col[i] = 2;
    t->ord[t->n++] = i;
    return 0;
}

static int dp_order(nl *x)
{
    dp_topo t = { x, nl_alloc(x, (size_t)x->nel + 1), nl_alloc(x, ((size_t)x->nel + 1) * sizeof(int)), 0,
                  nl_alloc(x, ((size_t)x->nel + 1) * sizeof(int)), 0 };
    for (int i = 0; i < x->nel; i++) if (visit(&t, i)) return -1;
    /* the file's order where it already is one (a wire may name a later
     * signal, as a built unit's do: the builder connects it after) */
    int in_order = 1;
    for (int i = 0; i < x->nel && in_order; i++) {
        const nl_el *e = &x->el[i];
        int ops[1040], n = e->kind == SIM_KIND_WIRE || e->kind == SIM_KIND_INPUT ? 0 : edge_list(e, ops);
        for (int k = 0; k < n; k++) in_order &= ops[k] < i;
    }
    if (in_order) return 0;
    int *where = nl_alloc(x, ((size_t)x->nel + 1) * sizeof(int));
    for (int i = 0; i < x->nel; i++) where[t.ord[i]] = i;
    nl_el *el = malloc(((size_t)x->nel + 1) * sizeof *el);
    if (!el) base_out_of_memory();
    for (int i = 0; i < x->nel; i++) {
        nl_el e = x->el[t.ord[i]];
        for (int k = 0; k < 5; k++) if (e.op[k] >= 0) e.op[k] = where[e.op[k]];
        for (int j = 0; j < e.n; j++) e.in[j] = where[e.in[j]];
        el[i] = e;
    }
    free(x->el);
    x->el = el;
    x->cap = x->nel + 1;
    for (int r = 0; r < 5; r++) for (int j = 0; j < x->nport[r]; j++) x->port[r][j] = where[x->port[r][j]];
    return 0;
}

/* A pipeline (latency N): every operand of an element has passed the same
 * number of registers since the inputs (a constant any number), and each
 * output N, so that an item's values meet in one clock and leave N clocks
 * after it entered. The elements are in operand order. */
static int dp_stages(nl *x)
{
    int *st = nl_alloc(x, ((size_t)x->nel + 1) * sizeof(int));
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        if (e->gen) { st[i] = -1; continue; }
        if (e->kind == SIM_KIND_INPUT && e->op[OP_A] < 0) { st[i] = 0; continue; }
        if (e->kind == SIM_KIND_CONST) { st[i] = -1; continue; }
        int ops[1040], n = 0, at = -1, from = -1;
        if (e->kind == SIM_KIND_REG) ops[n++] = e->op[OP_A];
        else n = edge_list(e, ops);
        for (int k = 0; k < n; k++) {
            int d = ops[k] >= 0 ? st[ops[k]] : -1;
            if (d < 0) continue;
            if (at >= 0 && d != at)
                return nl_bad(x, e->line, "%s %s: in a pipeline its operands %s and %s come %d and %d registers after the inputs",
                              sim_kind_name(e->kind), e->name, x->el[from].name, x->el[ops[k]].name, at, d);
            at = d;
            from = ops[k];
        }
        st[i] = at < 0 ? -1 : at + (e->kind == SIM_KIND_REG);
    }
    for (int j = 0; j < x->nport[P_OUT]; j++) {
        int d = st[x->port[P_OUT][j]];
        if (d != x->latency)
            return nl_bad(x, x->port_line[P_OUT][j], "port out %s: %d register%s after the inputs, where latency says %d",
                          x->el[x->port[P_OUT][j]].name, d, d == 1 ? "" : "s", x->latency);
    }
    return 0;
}

/* ------------------------------------------------------------ the slots */

#define DP_SLOTS 8
static nl *dp_slot[DP_SLOTS];

static int rule_fmt(const nl *x, const nl_el *e, int W, sim_fmt *f, char *err, size_t errlen)
{
    if (!e->rule) { *f = e->fmt; return 0; }
    char m[400];
    if (!nl_rule_at(e->rule, W, f, m, sizeof m)) return 0;
    snprintf(err, errlen, "%s:%d: %s %s: %s", x->path, e->line, sim_kind_name(e->kind), e->name, m);
    return -1;
}

static void dp_formats(nl *x, const unit_cfg *cfg, unit_fmts *out)
{
    memset(out, 0, sizeof *out);
    if (x->base) x->base->formats(cfg, out);   /* the unit's signals the file does not make */
    char err[1400];
    for (int i = 0; i < x->nel; i++) {
        const nl_el *e = &x->el[i];
        sim_fmt f;
        if (e->sig >= 0) out->f[e->sig] = rule_fmt(x, e, cfg->width, &f, err, sizeof err) ? ufmt(1) : f;
    }
}

/* A file that names its unit: its schedule block for the unit's schedule
 * cfg chose (the file's one design, when it has no blocks), and a width
 * its elements follow. */
static int base_sched(const nl *x, const unit_cfg *cfg, int *sched, char *err, size_t errlen)
{
    const char *want = x->base->sched[cfg->schedule].name;
    if (x->nsched) {
        *sched = -1;
        for (int s = 0; s < x->nsched; s++) if (!strcmp(x->sched_name[s], want)) *sched = s;
        if (*sched < 0) {
            snprintf(err, errlen, "%s: schedule %s: the file has no rows for it (its first: %s, line %d)", x->path, want,
                     x->sched_name[0], x->sched_line[0]);
            return -1;
        }
    } else if (cfg->schedule != x->cfg.schedule) {
        snprintf(err, errlen, "%s: schedule %s: the file's control is that of unit %s's schedule %s", x->path, want,
                 x->base->name, x->base->sched[x->cfg.schedule].name);
        return -1;
    }
    if (cfg->width == x->cfg.width) return 0;
    int rules = 0;
    for (int i = 0; i < x->nel; i++) {
        rules |= x->el[i].rule != NULL;
        if (x->el[i].fn_unit) {
            snprintf(err, errlen, "%s:%d: logic %s: fn=unit is unit %s's function at the file's width %d, not %d", x->path,
                     x->el[i].line, x->el[i].name, x->base->name, x->cfg.width, cfg->width);
            return -1;
        }
    }
    if (!rules) {
        snprintf(err, errlen, "%s: its formats are written for width %d alone (no rule of W): not %d", x->path, x->cfg.width,
                 cfg->width);
        return -1;
    }
    return 0;
}

static int dp_build(nl *x, sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, const unit_fmts *f,
                    unit_io *io, char *err, size_t errlen)
{
    int sched = cfg->schedule;
    if (x->base && base_sched(x, cfg, &sched, err, errlen)) return -1;
    sim_fmt *fm = malloc(((size_t)x->nel + 1) * sizeof *fm);
    if (!fm) base_out_of_memory();
    int rc = 0;
    for (int i = 0; i < x->nel && !rc; i++) {
        const nl_el *e = &x->el[i];
        rc = rule_fmt(x, e, cfg->width, &fm[i], err, errlen);
        if (!rc && e->sig >= 0) fm[i] = f->f[e->sig];
    }
    for (int i = 0; i < x->nel && !rc; i++) {   /* a table is for its inputs' widths at the file's */
        const nl_el *e = &x->el[i];
        for (int j = 0; (e->table || e->fn_verilog) && !e->gen && j < e->n && !rc; j++)
            if (fm[e->in[j]].width != x->el[e->in[j]].fmt.width) {
                snprintf(err, errlen, "%s:%d: logic %s: its %s is for %s of %d bits; at width %d it has %d", x->path,
                         e->line, e->name, e->table ? "table" : "verilog text", x->el[e->in[j]].name, x->el[e->in[j]].fmt.width, cfg->width, fm[e->in[j]].width);
                rc = -1;
            }
    }
    if (!rc) rc = nl_build(x, fm, sched, c, sc, clk, io, err, errlen);
    free(fm);
    return rc;
}

static int dp_beats(const unit_cfg *cfg) { (void)cfg; return 1; }

static void dp_ideal(nl *x, const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    for (int o = 0; o < x->nport[P_OUT]; o++) out[o] = tb_expr_eval(x->ideal[o], in);
}

static int dp_ideal_exact(nl *x, const unit_cfg *cfg, const sim_dy *in, sim_dy *out)
{
    (void)cfg;
    for (int o = 0; o < x->nport[P_OUT]; o++) if (tb_expr_exact(x->ideal[o], in, &out[o])) return -1;
    return 0;
}

/* 1 if the unit_net.h walk knows every element: the kinds it bounds, each
 * multiplexer's select and block key's pass a control decoder (the walk
 * follows the schedule's rows), registers with an input and without
 * enable or reset. */
static int dp_walkable(const nl *x)
{
    for (int i = 0; i < x->nel; i++) {
        const nl_el *e = &x->el[i];
        if (e->gen) continue;
        if (e->kind == SIM_KIND_LOGIC) return 0;
        if ((e->kind == SIM_KIND_MUX || e->kind == SIM_KIND_BK) && x->el[e->op[OP_C]].gen != NL_GEN_CTL) return 0;
        if (e->kind == SIM_KIND_REG && (e->op[OP_A] < 0 || e->op[OP_C] >= 0 || e->op[OP_RST] >= 0 || e->rst_raw)) return 0;
        if (e->kind == SIM_KIND_INPUT && e->op[OP_A] < 0 && e->sig < 0) return 0;
    }
    return 1;
}

/* The walk: the combinational elements in order each clock, then every
 * register at once; the outputs read after the item's last clock. */
static void dp_bound(nl *x, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    int nout = x->nport[P_OUT];
    for (int o = 0; o < nout; o++) per_out[o] = INFINITY;
    if (!dp_walkable(x)) return;
    unit_fmts fm = *f;
    for (int i = 0; i < x->nel; i++) {     /* an element's own round= is its format's mode */
        const nl_el *e = &x->el[i];
        if (e->sig >= 0 && e->r >= 0 && !fm.f[e->sig].rnd) fm.f[e->sig].rnd = (uint8_t)(e->r + 1);
    }
    unet n;
    unet_init(&n, &x->desc, &fm, cfg->rnd);
    unet_val *v = calloc((size_t)x->nel + 1, sizeof *v), *nx = calloc((size_t)x->nel + 1, sizeof *v);
    if (!v || !nx) base_out_of_memory();
    int s = x->nsched ? cfg->schedule : 0, C = x->nsched ? x->sched_clocks[s] : x->latency;
    for (int i = 0; i < x->nel; i++)
        if (x->el[i].kind == SIM_KIND_REG && !x->el[i].gen) v[i] = unet_reg(&n, x->el[i].sig, NULL);
    for (int k = 0; k <= C; k++) {
        for (int i = 0; i < x->nel; i++) {
            const nl_el *e = &x->el[i];
            if (e->gen || e->kind == SIM_KIND_REG) continue;
            int sg = e->sig, a = e->op[OP_A], b = e->op[OP_B];
            sim_fmt ef = fm.f[sg];
            int on = e->op[OP_C] >= 0 && x->el[e->op[OP_C]].gen == NL_GEN_CTL ? x->ctl[x->el[e->op[OP_C]].ctl].val[s][C ? k % C : 0] : 0;
            /* a pipeline's multiplexer or block key is driven by data: the
             * walk does not reach here (dp_walkable) */
            switch (e->kind) {
            case SIM_KIND_INPUT: case SIM_KIND_WIRE:
                if (a >= 0) { v[i] = unet_shift(&n, sg, NULL, v[a], 0); break; }
                v[i] = unet_wrap(NULL, ef, -1);
                if (e->has_range) {
                    double m = fmax(fabs(e->range[0]), fabs(e->range[1]));
                    v[i].mag = fmin(v[i].mag, m);
                    v[i].imag = fmin(v[i].imag, m);
                }
                break;
            case SIM_KIND_CONST: {
                double ideal = e->has_value ? e->value : sim_fx_to_real(e->raw, ef);
                int ovf = 0;
                double hw = e->has_value ? sim_fx_to_real(sim_fx_from_real(ideal, ef, cfg->rnd, cfg->ovf, &ovf), ef) : ideal;
                v[i] = unet_wrap(NULL, ef, -1);
                v[i].err = v[i].q = fabs(hw - ideal);
                v[i].mag = fabs(hw);
                v[i].imag = fabs(ideal);
                break;
            }
            case SIM_KIND_SHIFT: v[i] = unet_shift(&n, sg, NULL, v[a], e->shift); break;
            case SIM_KIND_ADD: v[i] = unet_add(&n, sg, NULL, v[a], v[b]); break;
            case SIM_KIND_SUB: v[i] = unet_sub(&n, sg, NULL, v[a], v[b]); break;
            case SIM_KIND_MUL: v[i] = unet_mul(&n, sg, NULL, v[a], v[b]); break;
            case SIM_KIND_BK: v[i] = unet_bk(&n, sg, NULL, NULL, v[a], on); break;
            case SIM_KIND_MUX: {
                unet_val m[8];
                int nv = e->n < 8 ? e->n : 8;
                for (int j = 0; j < nv; j++) m[j] = v[e->in[j]];
                if (on >= e->n) { v[i] = unet_wrap(NULL, ef, -1); v[i].mag = v[i].imag = 0; break; }   /* 0 out of range */
                v[i] = unet_mux(&n, sg, NULL, NULL, nv, m, on);
                break;
            }
            default: break;
            }
        }
        if (k == C) break;
        for (int i = 0; i < x->nel; i++)
            if (x->el[i].kind == SIM_KIND_REG && !x->el[i].gen) { nx[i] = v[i]; unet_reg_set(&n, &nx[i], v[x->el[i].op[OP_A]]); }
        for (int i = 0; i < x->nel; i++) if (x->el[i].kind == SIM_KIND_REG && !x->el[i].gen) v[i] = nx[i];
    }
    for (int o = 0; o < nout; o++) per_out[o] = v[x->port[P_OUT][o]].err;
    free(v);
    free(nx);
}

static void dp_ports(nl *x, int *n_in, char in[][16], int *n_out, char out[][16])
{
    *n_in = x->nport[P_IN];
    *n_out = x->nport[P_OUT];
    for (int j = 0; j < *n_in; j++) snprintf(in[j], 16, "%s", x->el[x->port[P_IN][j]].name);
    for (int j = 0; j < *n_out; j++) snprintf(out[j], 16, "%s", x->el[x->port[P_OUT][j]].name);
}

/* The golden vectors: each input uniform in its draw= (else range=). */
static int dp_gen(nl *x, size_t n, uint64_t seed, vec_set *out)
{
    vec_rng r = { seed };
    int nin = x->nport[P_IN], nout = x->nport[P_OUT];
    double row[2 * UNIT_MAX_IO];
    if (!n) n = DP_DEFAULT_VECTORS;
    for (size_t k = 0; k < n; k++) {
        for (int j = 0; j < nin; j++) {
            const nl_el *e = &x->el[x->port[P_IN][j]];
            const double *d = e->has_draw ? e->draw : e->range;
            row[j] = vec_rng_range(&r, d[0], d[1]);
        }
        for (int o = 0; o < nout; o++) row[nin + o] = tb_expr_eval(x->ideal[o], row);
        if (vec_set_push(out, row)) return -1;
    }
    return 0;
}

/* Each slot's functions: the descriptor's, calling the above with the
 * slot's file. */
#define DP_SLOT_FNS(k) \
    static void f_fmts##k(const unit_cfg *c, unit_fmts *o) { dp_formats(dp_slot[k], c, o); } \
    static int f_build##k(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, const unit_fmts *f, \
                          unit_io *io, char *err, size_t errlen) { return dp_build(dp_slot[k], c, sc, clk, cfg, f, io, err, errlen); } \
    static void f_ideal##k(const unit_cfg *c, const double *in, double *out) { dp_ideal(dp_slot[k], c, in, out); } \
    static int f_exact##k(const unit_cfg *c, const sim_dy *in, sim_dy *out) { return dp_ideal_exact(dp_slot[k], c, in, out); } \
    static void f_bound##k(const unit_cfg *c, const unit_fmts *f, double *o) { dp_bound(dp_slot[k], c, f, o); } \
    static void f_ports##k(const vec_params *p, int *ni, char in[][16], int *no, char out[][16]) \
    { (void)p; dp_ports(dp_slot[k], ni, in, no, out); } \
    static void f_eval##k(const vec_params *p, const double *in, double *out) { dp_ideal(dp_slot[k], NULL, in, out); (void)p; } \
    static int f_gen##k(const vec_params *p, size_t n, uint64_t seed, vec_set *out) { (void)p; return dp_gen(dp_slot[k], n, seed, out); }
DP_SLOT_FNS(0)
DP_SLOT_FNS(1)
DP_SLOT_FNS(2)
DP_SLOT_FNS(3)
DP_SLOT_FNS(4)
DP_SLOT_FNS(5)
DP_SLOT_FNS(6)
DP_SLOT_FNS(7)
#define DP_SLOT_ROW(k) { f_fmts##k, f_build##k, f_ideal##k, f_exact##k, f_bound##k, f_ports##k, f_eval##k, f_gen##k }
static const struct dp_fns {
    void (*formats)(const unit_cfg *, unit_fmts *);
    int (*build)(sim_ctx *, sim_scope *, sim_signal *, const unit_cfg *, const unit_fmts *, unit_io *, char *, size_t);
    void (*ideal)(const unit_cfg *, const double *, double *);
    int (*exact)(const unit_cfg *, const sim_dy *, sim_dy *);
    void (*bound)(const unit_cfg *, const unit_fmts *, double *);
    void (*ports)(const vec_params *, int *, char[][16], int *, char[][16]);
    void (*eval)(const vec_params *, const double *, double *);
    int (*gen)(const vec_params *, size_t, uint64_t, vec_set *);
} dp_fns[DP_SLOTS] = { DP_SLOT_ROW(0), DP_SLOT_ROW(1), DP_SLOT_ROW(2), DP_SLOT_ROW(3),
                       DP_SLOT_ROW(4), DP_SLOT_ROW(5), DP_SLOT_ROW(6), DP_SLOT_ROW(7) };

void nl_dp_release(const nl *x)
{
    for (int k = 0; k < DP_SLOTS; k++) if (dp_slot[k] == x) dp_slot[k] = NULL;
    for (int o = 0; o < UNIT_MAX_IO; o++) if (x->ideal[o]) tb_expr_free(x->ideal[o]);
}

/* ------------------------------------------------------------ the unit */

static int add_sig(nl *x, nl_el *e, unit_role role)
{
    unit_desc *d = &x->desc;
    if (d->nsigs == UNIT_MAX_SIGS) return nl_bad(x, e->line, "%s: more than %d signals in a datapath", e->name, UNIT_MAX_SIGS);
    e->sig = d->nsigs;
    d->sigs[d->nsigs].name = e->name;
    d->sigs[d->nsigs].role = role;
    static const char *const kind_what[SIM_KIND__COUNT] = {
        [SIM_KIND_INPUT] = "input", [SIM_KIND_WIRE] = "wire", [SIM_KIND_CONST] = "constant", [SIM_KIND_REG] = "register",
        [SIM_KIND_MUX] = "multiplexer", [SIM_KIND_BK] = "block key", [SIM_KIND_ADD] = "adder", [SIM_KIND_SUB] = "subtractor",
        [SIM_KIND_MUL] = "multiplier", [SIM_KIND_SHIFT] = "shift", [SIM_KIND_LOGIC] = "logic" };
    const char *kw = kind_what[e->kind];
    d->sigs[d->nsigs++].what = e->what ? e->what : kw ? kw : sim_kind_name(e->kind);
    return 0;
}

/* The ports of a file that names its unit (ideal unit=NAME): the unit's
 * inputs and outputs, by name and in its order; each element at the top
 * of the file's scope that has a signal's name of the unit gives that
 * signal its format. 0, or -1 after nl_bad. */
static int base_ports(nl *x)
{
    const unit_desc *b = x->base;
    for (int r = P_IN; r <= P_OUT; r++) {
        int j = 0;
        for (int i = 0; i < b->nsigs; i++) {
            if (b->sigs[i].role != (r == P_IN ? UNIT_SIG_IN : UNIT_SIG_OUT)) continue;
            if (j == x->nport[r])
                return nl_bad(x, x->ref_line, "unit %s has %s %s, which the file's port %s lines do not give", b->name,
                              r == P_IN ? "input" : "output", b->sigs[i].name, nl_port_names[r]);
            const nl_el *e = &x->el[x->port[r][j]];
            if (strcmp(e->name, b->sigs[i].name))
                return nl_bad(x, x->port_line[r][j], "port %s %s: unit %s's %s %d is %s", nl_port_names[r], e->name,
                              b->name, r == P_IN ? "input" : "output", j + 1, b->sigs[i].name);
            j++;
        }
        if (j < x->nport[r])
            return nl_bad(x, x->port_line[r][j], "port %s %s: unit %s has %d %s", nl_port_names[r],
                          x->el[x->port[r][j]].name, b->name, j, r == P_IN ? "inputs" : "outputs");
    }
    for (int i = 0; i < x->nel; i++)
        if (x->el[i].scope == NL_NONE && !x->el[i].gen) x->el[i].sig = unit_sig_index(b, x->el[i].name);
    return 0;
}

/* The unit of a file that names its unit: the unit's descriptor with the
 * file's build and formats. */
static void base_desc(nl *x, const struct dp_fns *fn)
{
    unit_desc *d = &x->desc;
    *d = *x->base;
    d->name = x->dp_name;
    d->summary = x->dp_summary;
    d->source = x->path;
    d->formats = fn->formats;
    d->build = fn->build;
    if (!x->ref_sched_line && x->nsched) x->cfg.schedule = unit_sched_find(x->base, x->sched_name[0]);
}

/* The file's own ports: inputs with their ranges, outputs, then every
 * other element a signal of the unit in the file's order. */
static int own_sigs(nl *x)
{
    unit_desc *d = &x->desc;
    int nin = x->nport[P_IN], nout = x->nport[P_OUT];
    for (int j = 0; j < nin; j++) {
        nl_el *e = &x->el[x->port[P_IN][j]];
        if (e->sig >= 0) return nl_bad(x, x->port_line[P_IN][j], "port in %s given twice", e->name);
        if (!e->has_range && !e->has_draw) return nl_bad(x, e->line, "input %s: needs range=LO,HI (the values it takes)", e->name);
        if (add_sig(x, e, UNIT_SIG_IN)) return -1;
    }
    for (int j = 0; j < nout; j++) {
        nl_el *e = &x->el[x->port[P_OUT][j]];
        if (e->sig >= 0 || e->gen)
            return nl_bad(x, x->port_line[P_OUT][j], "port out %s: %s", e->name, e->gen ? "the handshake's own" : "given twice, or an input");
        if (add_sig(x, e, UNIT_SIG_OUT)) return -1;
    }
    for (int j = 0; j < nin + nout; j++)
        if (strlen(d->sigs[j].name) > 15) return nl_bad(x, 0, "port %s: a port's name has at most 15 characters", d->sigs[j].name);
    return 0;
}

/* The ideal expressions, by output port; *exact: all of them exact. */
static int own_ideal(nl *x, int *exact)
{
    unit_desc *d = &x->desc;
    int nin = x->nport[P_IN], nout = x->nport[P_OUT];
    const char *names[UNIT_MAX_IO];
    for (int j = 0; j < nin; j++) names[j] = d->sigs[j].name;
    *exact = 1;
    for (int k = 0; k < x->nideal; k++) {
        int o = -1;
        for (int j = 0; j < nout; j++) if (!strcmp(x->ideal_out[k], d->sigs[nin + j].name)) o = j;
        if (o < 0) return nl_bad(x, x->ideal_line[k], "ideal %s: not an output (port out NAME)", x->ideal_out[k]);
        if (x->ideal[o]) return nl_bad(x, x->ideal_line[k], "ideal %s given twice", x->ideal_out[k]);
        char e[300];
        if (tb_expr_parse(x->ideal_text[k], nin, names, &x->ideal[o], e, sizeof e))
            return nl_bad(x, x->ideal_line[k], "ideal %s: %s in '%s'", x->ideal_out[k], e, x->ideal_text[k]);
        *exact &= tb_expr_is_exact(x->ideal[o]);
    }
    for (int j = 0; j < nout; j++)
        if (!x->ideal[j])
            return nl_bad(x, 0, "output %s has no ideal line (ideal %s EXPRESSION, or ideal unit=NAME)", d->sigs[nin + j].name,
                          d->sigs[nin + j].name);
    return 0;
}

int nl_dp_rules(nl *x)
{
    char err[1400];
    for (int i = 0; i < x->nel; i++)
        if (x->el[i].rule && rule_fmt(x, &x->el[i], x->cfg.width, &x->el[i].fmt, err, sizeof err)) {
            snprintf(x->err, x->errlen, "%s", err);
            return -1;
        }
    return 0;
}

const unit_desc *nl_dp_finish(nl *x, unit_cfg *cfg, unit_fmts *fm)
{
    int slot = -1;
    for (int k = 0; k < DP_SLOTS && slot < 0; k++) if (!dp_slot[k]) slot = k;
    if (slot < 0) { nl_bad(x, 0, "more than %d datapath files at once", DP_SLOTS); return NULL; }
    unit_desc *d = &x->desc;
    memset(d, 0, sizeof *d);
    int nin = x->nport[P_IN], nout = x->nport[P_OUT];
    if (!nin || !nout) { nl_bad(x, 0, "needs port in NAME and port out NAME lines (its inputs and outputs)"); return NULL; }
    for (int j = 0; j < nin; j++) {
        nl_el *e = &x->el[x->port[P_IN][j]];
        if (e->gen) { nl_bad(x, x->port_line[P_IN][j], "port in %s: the handshake's own", e->name); return NULL; }
    }
    if (x->base ? base_ports(x) : own_sigs(x)) return NULL;
    int in_valid = x->nport[P_IN_VALID] ? x->port[P_IN_VALID][0] : -1;
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        int port = i == in_valid;
        for (int j = 0; j < nin; j++) port |= x->port[P_IN][j] == i;
        if (e->kind == SIM_KIND_INPUT && !e->gen && !port && !e->ref[OP_A])
            { nl_bad(x, e->line, "input %s: not a port (port in %s), and no from=", e->name, e->name); return NULL; }
        if (!x->base && !e->gen && e->sig < 0 && add_sig(x, e, UNIT_SIG_INTERNAL)) return NULL;
    }
    /* the signals are listed in the file's order, built in an order where
     * each operand comes first */
    if (dp_order(x) || (x->latency && dp_stages(x))) return NULL;
    int exact = 0;
    if (!x->base && own_ideal(x, &exact)) return NULL;
    const struct dp_fns *fn = &dp_fns[slot];
    if (x->base) base_desc(x, fn);
    else {
        d->name = x->dp_name;
        d->summary = x->dp_summary;
        d->source = x->path;
        d->nsched = x->nsched ? x->nsched : 1;
        for (int s = 0; s < x->nsched; s++) { d->sched[s].name = x->sched_name[s]; d->sched[s].what = x->sched_what[s]; }
        if (!x->nsched && !x->latency) { d->sched[0].name = "comb"; d->sched[0].what = "combinational: an item a clock"; }
        if (x->latency) {
            snprintf(x->pipe_what, sizeof x->pipe_what, "a pipeline: an item a clock, its result %d clock%s later", x->latency,
                     x->latency > 1 ? "s" : "");
            d->sched[0].name = "pipe";
            d->sched[0].what = x->pipe_what;
        }
        d->fmt_rule = "each element's format as the file gives it, a rule of the width W (docs/datapaths.md)";
        x->model.name = x->dp_name;
        x->model.ports = fn->ports;
        x->model.eval = fn->eval;
        x->model.gen = fn->gen;
        d->ref = &x->model;
        d->formats = fn->formats;
        d->beats = dp_beats;
        d->build = fn->build;
        d->ideal = fn->ideal;
        d->bound = fn->bound;
        d->ideal_exact = exact ? fn->exact : NULL;
        d->bound_own_modes = 1;
    }
    if (x->base && x->nsched)
        for (int s = 0; s < x->nsched; s++)
            if (unit_sched_find(x->base, x->sched_name[s]) < 0) {
                nl_bad(x, x->sched_line[s], "schedule %s: unit %s has no such schedule (ideal unit=%s runs the unit's)",
                       x->sched_name[s], x->base->name, x->base->name);
                return NULL;
            }
    dp_slot[slot] = x;
    x->slot = slot;
    *cfg = x->cfg;
    dp_formats(x, cfg, fm);
    return d;
}

const unit_desc *tb_datapath_base(const unit_desc *u)
{
    for (int k = 0; k < DP_SLOTS; k++) if (dp_slot[k] && &dp_slot[k]->desc == u) return dp_slot[k]->base;
    return NULL;
}

int tb_datapath_is(const unit_desc *u)
{
    for (int k = 0; k < DP_SLOTS; k++) if (dp_slot[k] && &dp_slot[k]->desc == u) return 1;
    return 0;
}
