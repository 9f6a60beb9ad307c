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
 *    step and out_valid a register of it; a file without a schedule is
 *    combinational (in_ready 1, out_valid = in_valid);
 *  - the float reference: the expressions in double, the golden vectors
 *    drawn uniformly from the inputs' ranges (draw=, else range=);
 *  - the ideal: the same expressions on the quantized inputs, exactly
 *    (sim_dy) where they have no division or square root;
 *  - the bound: the walk of unit_net.h over the elements, one clock at a
 *    time through the schedule, where the file has only the kinds it
 *    knows and every multiplexer and block key is driven by the control;
 *    otherwise none (the verdict then needs --target-error).
 * The descriptor's functions take no pointer to the file they came from,
 * so each live file has a slot with functions of its own (DP_SLOTS).
 */
#include "testbench/tb_netlist_int.h"
#include "testbench/tb_expr.h"
#include "units/unit_net.h"
#include "sim/sim_area.h"
#include "base/base_num.h"
#include "base/base_out.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BAD(...) nl_bad(x, x->line, __VA_ARGS__)
#define DP_DEFAULT_VECTORS 1000

/* ------------------------------------------------------------ format rules */

/* One side of a rule: a whole number, W, or a parenthesized sum of terms
 * K, W and K*W. */
static int rule_side(const char **pp, int *k0, int *k1)
{
    const char *p = *pp;
    *k0 = *k1 = 0;
    int paren = *p == '(';
    if (paren) p++;
    int sign = 1, first = 1;
    for (;;) {
        if (!first || paren) {
            if (*p == '+' || *p == '-') { sign = *p == '-' ? -1 : 1; p++; }
            else if (!first) break;
        }
        long k = 1;
        int num = *p >= '0' && *p <= '9';
        if (num) { k = strtol(p, (char **)&p, 10); if (k > 4096) return -1; }
        if (*p == '*' && num) p++;
        if (*p == 'W') { p++; *k1 += sign * (int)k; }
        else if (num) *k0 += sign * (int)k;
        else return -1;
        first = 0;
        sign = 1;
        if (!paren) break;
    }
    if (paren && *p++ != ')') return -1;
    *pp = p;
    return 0;
}

int nl_dp_format(nl *x, nl_el *e, const char *tok)
{
    if (!strchr(tok, 'W')) {
        char err[200];
        if (sim_fmt_parse(tok, &e->fmt, err, sizeof err)) return BAD("format %s: %s", tok, err);
        return 0;
    }
    nl_rule r;
    memset(&r, 0, sizeof r);
    const char *p = tok;
    if ((*p != 's' && *p != 'u') || strlen(tok) >= sizeof r.text) goto bad;
    r.sg = *p++ == 's';
    if (rule_side(&p, &r.i0, &r.i1) || *p++ != '.' || rule_side(&p, &r.f0, &r.f1)) goto bad;
    if (*p && *p != ':') goto bad;
    snprintf(r.modes, sizeof r.modes, "%s", p);
    snprintf(r.text, sizeof r.text, "%s", tok);
    e->rule = nl_alloc(x, sizeof *e->rule);
    *e->rule = r;
    return 0;
bad:
    return BAD("format %s: expected sI.F or uI.F, I and F each a whole number, W, or a sum like (W-7) or (2*W+1) "
               "(W: the width), then :MODES", tok);
}

/* The rule at width W: 0, or -1 with why in err. */
static int rule_at(const nl_rule *r, int W, sim_fmt *f, char *err, size_t errlen)
{
    long I = r->i0 + (long)r->i1 * W, F = r->f0 + (long)r->f1 * W;
    char t[96], e[120];
    snprintf(t, sizeof t, "%c%ld.%ld%s", r->sg ? 's' : 'u', I, F, r->modes);
    if (I < 0 || F < 0 || I + F < 1) {
        snprintf(err, errlen, "format rule %s gives %s at width %d", r->text, I + F < 1 ? "no bits" : "a negative count of bits", W);
        return -1;
    }
    if (sim_fmt_parse(t, f, e, sizeof e)) {
        snprintf(err, errlen, "format rule %s gives %s at width %d (%s)", r->text, t, W, e);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ the lines */

static int bits_for(int v) { int b = 1; while (b < 62 && ((int64_t)1 << b) <= v) b++; return b; }

static sim_fmt ufmt(int bits) { return unit_fmt(0, bits, 0); }

static nl_el *gen_el(nl *x, sim_kind kind, const char *name, int gen, int line)
{
    nl_el *e = nl_el_new(x, kind, name, ufmt(1));
    e->gen = gen;
    e->line = line;
    return e;
}

/* The end of the first schedule's block: the last step, in_ready. */
static void close_ctl(nl *x)
{
    if (!x->ctl_open) return;
    x->ctl_open = 0;
    if (x->nsched == 1) {
        nl_el *e = gen_el(x, SIM_KIND_LOGIC, "in_ready", NL_GEN_LAST, x->sched_line[0]);
        e->n = 1;
        e->in_ref = nl_alloc(x, sizeof *e->in_ref);
        e->in_ref[0] = "step";
        e->has_area = 1;
    }
}

static int parse_schedule(nl *x, char **tok, int nt)
{
    if (nt < 3 || nt > 4 || strncmp(tok[2], "clocks=", 7))
        return BAD("schedule: expected schedule NAME clocks=N [\"what it does\"]");
    if (!nl_name_ok(tok[1]) || strchr(tok[1], '.')) return BAD("schedule %s: not a name", tok[1]);
    for (int s = 0; s < x->nsched; s++)
        if (!strcmp(x->sched_name[s], tok[1])) return BAD("schedule %s given twice (first at line %d)", tok[1], x->sched_line[s]);
    if (x->nsched == UNIT_MAX_SCHED) return BAD("more than %d schedules", UNIT_MAX_SCHED);
    long long n;
    if (base_num_whole(tok[2] + 7, 0, &n) || n < 2 || n > NL_MAX_CLOCKS)
        return BAD("%s: expected a whole number of clocks per item 2..%d", tok[2], NL_MAX_CLOCKS);
    if (!x->clk) return BAD("schedule before clock NAME (the step counter's clock)");
    close_ctl(x);
    int s = x->nsched++;
    x->sched_name[s] = nl_strdup(x, tok[1], strlen(tok[1]));
    x->sched_what[s] = nl_strdup(x, nt == 4 ? tok[3] : "", strlen(nt == 4 ? tok[3] : ""));
    x->sched_clocks[s] = (int)n;
    x->sched_line[s] = x->line;
    x->cur_sched = s;
    x->ctl_open = 1;
    if (s == 0) {       /* the counter, where the first schedule is */
        gen_el(x, SIM_KIND_INPUT, "in_valid", NL_GEN_VALID, x->line);
        nl_el *st = gen_el(x, SIM_KIND_REG, "step", NL_GEN_STEP, x->line);
        st->ref[OP_A] = "step_next";
        st->ref[OP_CLK] = x->clk;
        nl_el *nx = gen_el(x, SIM_KIND_LOGIC, "step_next", NL_GEN_NEXT, x->line);
        nx->n = 2;
        nx->in_ref = nl_alloc(x, 2 * sizeof *nx->in_ref);
        nx->in_ref[0] = "step";
        nx->in_ref[1] = "in_valid";
        nx->has_area = 1;
    }
    return 0;
}

static int parse_ctl(nl *x, char **tok, int nt)
{
    if (!x->ctl_open) return BAD("ctl: a control signal's row belongs right after its schedule NAME clocks=N line");
    int s = x->cur_sched, n = x->sched_clocks[s];
    if (nt < 2 || !nl_name_ok(tok[1]) || strchr(tok[1], '.')) return BAD("ctl: expected ctl NAME V0 V1 ... (one value a clock)");
    if (nt - 2 != n)
        return BAD("ctl %s: %d values; schedule %s has %d clocks per item", tok[1], nt - 2, x->sched_name[s], n);
    int k = -1;
    for (int i = 0; i < x->nctl; i++) if (!strcmp(x->ctl[i].name, tok[1])) k = i;
    if (k >= 0 && (x->ctl[k].have >> s & 1)) return BAD("ctl %s given twice in schedule %s", tok[1], x->sched_name[s]);
    if (k < 0) {
        if (s > 0) return BAD("ctl %s: not a control signal of schedule %s (every schedule drives the same ones)", tok[1], x->sched_name[0]);
        if (x->nctl == NL_MAX_CTL) return BAD("more than %d control signals", NL_MAX_CTL);
        k = x->nctl++;
        x->ctl[k].name = nl_strdup(x, tok[1], strlen(tok[1]));
        x->ctl[k].line = x->line;
        nl_el *e = gen_el(x, SIM_KIND_LOGIC, tok[1], NL_GEN_CTL, x->line);
        e->ctl = k;
        e->n = 1;
        e->in_ref = nl_alloc(x, sizeof *e->in_ref);
        e->in_ref[0] = "step";
        e->has_area = 1;
    }
    for (int c = 0; c < n; c++) {
        long long v;
        if (base_num_whole(tok[2 + c], 0, &v) || v > 255)
            return BAD("ctl %s: %s at clock %d: expected a whole number 0..255", tok[1], tok[2 + c], c);
        x->ctl[k].val[s][c] = (int)v;
    }
    x->ctl[k].have |= 1u << s;
    return 0;
}

int nl_dp_line(nl *x, char **tok, int nt)
{
    const char *k = tok[0];
    if (!strcmp(k, "ctl")) return parse_ctl(x, tok, nt);
    close_ctl(x);
    if (!strcmp(k, "schedule")) return parse_schedule(x, tok, nt);
    if (!strcmp(k, "ideal")) {
        if (nt < 3) return BAD("ideal: expected ideal OUTPUT EXPRESSION");
        if (x->nideal == UNIT_MAX_IO) return BAD("ideal: more than %d", UNIT_MAX_IO);
        size_t len = 0;
        for (int i = 2; i < nt; i++) len += strlen(tok[i]) + 1;
        char *t = nl_alloc(x, len + 1);
        for (int i = 2; i < nt; i++) { strcat(t, tok[i]); if (i + 1 < nt) strcat(t, " "); }
        x->ideal_out[x->nideal] = nl_strdup(x, tok[1], strlen(tok[1]));
        x->ideal_text[x->nideal] = t;
        x->ideal_line[x->nideal++] = x->line;
        return 0;
    }
    if (!strcmp(k, "port") && nt == 3 && strcmp(tok[1], "in") && strcmp(tok[1], "out"))
        return BAD("port %s: a datapath file's handshake is made from its schedules (port in and port out only)", tok[1]);
    return 1;
}

int nl_dp_close(nl *x)
{
    close_ctl(x);
    if (!x->clk) return nl_bad(x, 0, "no clock NAME line");
    int line = x->line;
    if (x->nsched) {
        int maxc = 0;
        for (int s = 0; s < x->nsched; s++) if (x->sched_clocks[s] > maxc) maxc = x->sched_clocks[s];
        x->step_bits = bits_for(maxc - 1);
        for (int k = 0; k < x->nctl; k++) {
            int vmax = 0;
            for (int s = 0; s < x->nsched; s++) {
                if (!(x->ctl[k].have >> s & 1))
                    return nl_bad(x, x->sched_line[s], "schedule %s: no row for ctl %s (every schedule drives the same "
                                  "control signals)", x->sched_name[s], x->ctl[k].name);
                for (int c = 0; c < x->sched_clocks[s]; c++) if (x->ctl[k].val[s][c] > vmax) vmax = x->ctl[k].val[s][c];
            }
            for (int i = 0; i < x->nel; i++) if (x->el[i].gen == NL_GEN_CTL && x->el[i].ctl == k) x->el[i].fmt = ufmt(bits_for(vmax));
        }
        for (int i = 0; i < x->nel; i++)
            if (x->el[i].gen == NL_GEN_STEP || x->el[i].gen == NL_GEN_NEXT) x->el[i].fmt = ufmt(x->step_bits);
        x->line = line + 1;
        nl_el *ov = gen_el(x, SIM_KIND_REG, "out_valid", NL_GEN_OUTV, 0);
        ov->ref[OP_A] = "in_ready";
        ov->ref[OP_CLK] = x->clk;
    } else {
        for (int i = 0; i < x->nel; i++)
            if (x->el[i].kind == SIM_KIND_REG)
                return nl_bad(x, x->el[i].line, "reg %s: a datapath without a schedule is combinational (add schedule "
                              "NAME clocks=N and its control rows)", x->el[i].name);
        gen_el(x, SIM_KIND_INPUT, "in_valid", NL_GEN_VALID, 0);
        nl_el *r = gen_el(x, SIM_KIND_CONST, "in_ready", NL_GEN_LAST, 0);
        r->raw = 1;
        nl_el *ov = gen_el(x, SIM_KIND_WIRE, "out_valid", NL_GEN_OUTV, 0);
        ov->ref[OP_A] = "in_valid";
    }
    static const char *const hs[3] = { "in_valid", "in_ready", "out_valid" };
    for (int r = P_IN_VALID; r <= P_OUT_VALID; r++) {
        x->port_ref[r] = nl_alloc(x, UNIT_MAX_IO * sizeof(char *));
        x->port_ref[r][0] = (char *)hs[r - P_IN_VALID];
        x->nport[r] = 1;
    }
    x->line = 0;
    return 0;
}

/* ------------------------------------------------------------ order and loops */

/* Depth-first over the operands: post-order is an order where every
 * operand comes first (the file's own order when it already is one); a
 * grey element met again closes a combinational loop. */
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

/* ------------------------------------------------------------ the slots */

#define DP_SLOTS 4
static nl *dp_slot[DP_SLOTS];

static int rule_fmt(const nl *x, const nl_el *e, int W, sim_fmt *f, char *err, size_t errlen)
{
    if (!e->rule) { *f = e->fmt; return 0; }
    char m[400];
    if (!rule_at(e->rule, W, f, m, sizeof m)) return 0;
    snprintf(err, errlen, "%s:%d: %s %s: %s", x->path, e->line, sim_kind_name(e->kind), e->name, m);
    return -1;
}

static void dp_formats(nl *x, const unit_cfg *cfg, unit_fmts *out)
{
    memset(out, 0, sizeof *out);
    char err[1400];
    for (int i = 0; i < x->nel; i++) {
        const nl_el *e = &x->el[i];
        sim_fmt f;
        if (e->sig >= 0) out->f[e->sig] = rule_fmt(x, e, cfg->width, &f, err, sizeof err) ? ufmt(1) : f;
    }
}

static int dp_build(nl *x, sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, const unit_fmts *f,
                    unit_io *io, char *err, size_t errlen)
{
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
        for (int j = 0; e->table && !e->gen && j < e->n && !rc; j++)
            if (fm[e->in[j]].width != x->el[e->in[j]].fmt.width) {
                snprintf(err, errlen, "%s:%d: logic %s: its table is for %s of %d bits; at width %d it has %d", x->path,
                         e->line, e->name, x->el[e->in[j]].name, x->el[e->in[j]].fmt.width, cfg->width, fm[e->in[j]].width);
                rc = -1;
            }
    }
    if (!rc) rc = nl_build(x, fm, cfg->schedule, c, sc, clk, io, err, errlen);
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
 * follows the schedule's rows), registers without enable or reset. */
static int dp_walkable(const nl *x)
{
    for (int i = 0; i < x->nel; i++) {
        const nl_el *e = &x->el[i];
        if (e->gen) continue;
        if (e->kind == SIM_KIND_LOGIC) return 0;
        if ((e->kind == SIM_KIND_MUX || e->kind == SIM_KIND_BK) && x->el[e->op[OP_C]].gen != NL_GEN_CTL) return 0;
        if (e->kind == SIM_KIND_REG && (e->op[OP_C] >= 0 || e->op[OP_RST] >= 0 || e->rst_raw)) return 0;
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
    int s = x->nsched ? cfg->schedule : 0, C = x->nsched ? x->sched_clocks[s] : 0;
    for (int i = 0; i < x->nel; i++)
        if (x->el[i].kind == SIM_KIND_REG && !x->el[i].gen) v[i] = unet_reg(&n, x->el[i].sig, NULL);
    for (int k = 0; k <= C; k++) {
        for (int i = 0; i < x->nel; i++) {
            const nl_el *e = &x->el[i];
            if (e->gen || e->kind == SIM_KIND_REG) continue;
            int sg = e->sig, a = e->op[OP_A], b = e->op[OP_B];
            sim_fmt ef = fm.f[sg];
            int on = e->op[OP_C] >= 0 && x->el[e->op[OP_C]].gen == NL_GEN_CTL ? x->ctl[x->el[e->op[OP_C]].ctl].val[s][C ? k % C : 0] : 0;
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
} dp_fns[DP_SLOTS] = { DP_SLOT_ROW(0), DP_SLOT_ROW(1), DP_SLOT_ROW(2), DP_SLOT_ROW(3) };

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
        if (!e->has_range && !e->has_draw) { nl_bad(x, e->line, "input %s: needs range=LO,HI (the values it takes)", e->name); return NULL; }
        if (add_sig(x, e, UNIT_SIG_IN)) return NULL;
    }
    for (int j = 0; j < nout; j++) {
        nl_el *e = &x->el[x->port[P_OUT][j]];
        if (e->sig >= 0 || e->gen) { nl_bad(x, x->port_line[P_OUT][j], "port out %s: an input or the handshake's", e->name); return NULL; }
        if (add_sig(x, e, UNIT_SIG_OUT)) return NULL;
    }
    for (int j = 0; j < nin + nout; j++)
        if (strlen(d->sigs[j].name) > 15) { nl_bad(x, 0, "port %s: a port's name has at most 15 characters", d->sigs[j].name); return NULL; }
    for (int i = 0; i < x->nel; i++) {
        nl_el *e = &x->el[i];
        if (e->kind == SIM_KIND_INPUT && !e->gen && e->sig < 0 && !e->ref[OP_A])
            { nl_bad(x, e->line, "input %s: not a port (port in %s), and no from=", e->name, e->name); return NULL; }
        if (!e->gen && e->sig < 0 && add_sig(x, e, UNIT_SIG_INTERNAL)) return NULL;
        char err[1400];
        if (e->rule && rule_fmt(x, e, x->cfg.width, &e->fmt, err, sizeof err)) { snprintf(x->err, x->errlen, "%s", err); return NULL; }
    }
    /* the signals are listed in the file's order, built in an order where
     * each operand comes first */
    if (dp_order(x)) return NULL;
    const char *names[UNIT_MAX_IO];
    for (int j = 0; j < nin; j++) names[j] = d->sigs[j].name;
    int exact = 1;
    for (int k = 0; k < x->nideal; k++) {
        int o = -1;
        for (int j = 0; j < nout; j++) if (!strcmp(x->ideal_out[k], d->sigs[nin + j].name)) o = j;
        if (o < 0) { nl_bad(x, x->ideal_line[k], "ideal %s: not an output (port out NAME)", x->ideal_out[k]); return NULL; }
        if (x->ideal[o]) { nl_bad(x, x->ideal_line[k], "ideal %s given twice", x->ideal_out[k]); return NULL; }
        char e[300];
        if (tb_expr_parse(x->ideal_text[k], nin, names, &x->ideal[o], e, sizeof e)) {
            nl_bad(x, x->ideal_line[k], "ideal %s: %s in '%s'", x->ideal_out[k], e, x->ideal_text[k]);
            return NULL;
        }
        exact &= tb_expr_is_exact(x->ideal[o]);
    }
    for (int j = 0; j < nout; j++)
        if (!x->ideal[j]) { nl_bad(x, 0, "output %s has no ideal line (ideal %s EXPRESSION)", d->sigs[nin + j].name, d->sigs[nin + j].name); return NULL; }
    d->name = x->dp_name;
    d->summary = x->dp_summary;
    d->source = x->path;
    d->nsched = x->nsched ? x->nsched : 1;
    for (int s = 0; s < x->nsched; s++) { d->sched[s].name = x->sched_name[s]; d->sched[s].what = x->sched_what[s]; }
    if (!x->nsched) { d->sched[0].name = "comb"; d->sched[0].what = "combinational: an item a clock"; }
    d->fmt_rule = "each element's format as the file gives it, a rule of the width W (docs/datapaths.md)";
    const struct dp_fns *fn = &dp_fns[slot];
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
    dp_slot[slot] = x;
    x->slot = slot;
    *cfg = x->cfg;
    dp_formats(x, cfg, fm);
    return d;
}

int tb_datapath_is(const unit_desc *u)
{
    for (int k = 0; k < DP_SLOTS; k++) if (dp_slot[k] && &dp_slot[k]->desc == u) return 1;
    return 0;
}
