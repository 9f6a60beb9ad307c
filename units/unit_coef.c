/* unit_coef.c - the coefficient units of Nechyporuk & Romanyuk (2020) (Fig. 8): cubic
 * coefficients from node sets N1 and N2, quadratic from three nodes.
 *
 * Each unit is one network of unit_coef.h walked by one builder: the
 * networks differ only in their data. Combinational: one item per clock.
 */
#include "units/unit_coef.h"
#include "vectors/ref_interp.h"
#include <stddef.h>
#include <string.h>

/* ------------------------------------------------------------ networks */

#define COEF_NODE_X(name, op, a, b, k, what) { #name, COEF_##op, #a, #b, k, 0 },
#define COEF_NODE_O(name, op, a, b, k, what) { #name, COEF_##op, #a, #b, k, 1 },

static const coef_node n1_nodes[] = { COEF3_N1_NET(COEF_NODE_X, COEF_NODE_O) };
static const coef_node n2_nodes[] = { COEF3_N2_NET(COEF_NODE_X, COEF_NODE_O) };
static const coef_node q_nodes[] = { COEF2_NET(COEF_NODE_X, COEF_NODE_O) };

/* The coefficient formulas (docs/units.md), with `th` for 1/3. */
static void formula_n1(const double *I, double th, double *o)
{
    o[0] = 8 * (I[1] + 8 * I[3]) * th - 8 * (I[0] + 2 * I[2]);
    o[1] = 2 * (7 * I[0] - I[1] + 10 * I[2] - 16 * I[3]);
    o[2] = (I[1] + 32 * I[3]) * th - 7 * I[0] - 4 * I[2];
    o[3] = I[0];
}
static void formula_n2(const double *I, double th, double *o)
{
    o[0] = 8 * (I[1] + 2 * I[2]) - 8 * (8 * I[3] + I[0]) * th;
    o[1] = 2 * (3 * I[0] - 5 * I[1] - 14 * I[2] + 16 * I[3]);
    o[2] = 3 * (I[1] + 4 * I[2]) - (13 * I[0] + 32 * I[3]) * th;
    o[3] = I[0];
}
static void formula_q(const double *I, double th, double *o)
{
    (void)th;
    o[0] = 2 * I[0] + 2 * I[1] - 4 * I[2];
    o[1] = 4 * I[2] - 3 * I[0] - I[1];
    o[2] = I[0];
}

int coef_exact(const coef_net *net, double third, const sim_dy *in, sim_dy *out)
{
    double e[4] = { 0, 0, 0, 0 }, col[4][4];
    for (int j = 0; j < net->nin; j++) {
        e[j] = 1;
        net->formula(e, third, col[j]);
        e[j] = 0;
    }
    int bad = 0;
    for (int i = 0; i < net->nout; i++) {
        sim_dy acc, c, p;
        sim_dy_int(&acc, 0, 0);
        for (int j = 0; j < net->nin; j++) {
            sim_dy_double(&c, col[j][i]);
            sim_dy_mul(&p, &c, &in[j]);
            sim_dy_add(&acc, &acc, &p);
        }
        out[i] = acc;
        bad |= acc.ovf;
    }
    return bad ? -1 : 0;
}

const coef_net coef_net_n1 = { 4, 4, COEF3_N1_NODES, n1_nodes, formula_n1 };
const coef_net coef_net_n2 = { 4, 4, COEF3_N2_NODES, n2_nodes, formula_n2 };
const coef_net coef_net_q = { 3, 3, COEF2_NODES, q_nodes, formula_q };

sim_fmt coef_input_fmt(int width) { return unit_fmt(0, 1, width - 1); }

/* An operand: input i<k> or an earlier element. */
static int operand(unet *n, const coef_net *net, int upto, const char *name,
                   const unet_val *in, const unet_val *val, unet_val *v)
{
    if (name[0] == 'i' && name[1] >= '1' && name[1] < '1' + net->nin && !name[2]) {
        *v = in[name[1] - '1'];
        return 0;
    }
    for (int j = 0; j < upto; j++)
        if (!strcmp(net->node[j].name, name)) { *v = val[j]; return 0; }
    if (!n->why[0]) snprintf(n->why, sizeof n->why, "network of %s: no operand '%s'", n->u->name, name);
    return -1;
}

int coef_walk(unet *n, const coef_net *net, const unet_val *in, int terms, int series,
              unet_val *out)
{
    unet_val val[COEF_MAX_NODES], a, b;
    int no = 0;
    for (int j = 0; j < net->nnodes && j < COEF_MAX_NODES; j++) {
        const coef_node *e = &net->node[j];
        int sig = unet_sig(n, e->name);
        if (sig < 0 || operand(n, net, j, e->a, in, val, &a)) return -1;
        if (e->op == COEF_ADD || e->op == COEF_SUB)
            if (operand(n, net, j, e->b, in, val, &b)) return -1;
        switch (e->op) {
        case COEF_SHL: val[j] = unet_shift(n, sig, e->name, a, e->k); break;
        case COEF_ADD: val[j] = unet_add(n, sig, e->name, a, b); break;
        case COEF_SUB: val[j] = unet_sub(n, sig, e->name, a, b); break;
        case COEF_DIV3: {
            sim_scope *up = n->sc;
            if (n->c) n->sc = sim_scope_new(n->c, up, e->name);
            val[j] = div3_walk(n, a, terms, series, sig);
            n->sc = up;
            break;
        }
        }
        if (e->is_out) out[no++] = val[j];
    }
    return n->why[0] ? -1 : 0;
}

/* ------------------------------------------------ the coefficient units */

static const char *const in_names[] = { "i1", "i2", "i3", "i4" };

/* Inputs then the network, walked by n (already set up to build, bound or
 * choose formats). */
static int walk_unit(unet *n, const coef_net *net, const unit_cfg *cfg, unet_val *in, unet_val *out)
{
    for (int i = 0; i < net->nin; i++) in[i] = unet_input(n, in_names[i], i);
    return coef_walk(n, net, in, cfg->terms, cfg->series, out);
}

/* The rule: inputs u1.(W-1) (intensities in [0, 1]); internals keep all
 * W-1 fraction bits through shifts and adds, with the integer bits their
 * exact range over [0, 1]^n needs (that is where 8x and 32x get their
 * guard bits: 8 I4 is u4.(W-4) exactly, I2 + 32 I4 u6.(W-1)); the /3
 * networks keep G more; the coefficients get W bits, sI.(W-I). */
static void coef_formats(const unit_desc *u, const coef_net *net, const unit_cfg *cfg, unit_fmts *out)
{
    static const double lo[UNET_MAXIN] = { 0, 0, 0, 0 }, hi[UNET_MAXIN] = { 1, 1, 1, 1 };
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, NULL, cfg->rnd);
    unet_rule(&n, cfg->width, lo, hi, net->nin);
    for (int i = 0; i < net->nin; i++) n.fm.f[unit_sig_must(u, in_names[i])] = coef_input_fmt(cfg->width);
    walk_unit(&n, net, cfg, in, o);
    *out = n.fm;
}

static int coef_build(const unit_desc *u, const coef_net *net, sim_ctx *c, sim_scope *sc,
                      const unit_cfg *cfg, const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    unet_hw(&n, c, sc);
    if (walk_unit(&n, net, cfg, in, o)) { snprintf(err, errlen, "%s", n.why); return -1; }
    for (int i = 0; i < net->nin; i++) io->in[i] = in[i].s;
    for (int i = 0; i < net->nout; i++) io->out[i] = o[i].s;
    /* Combinational: always ready, outputs valid with the inputs. */
    sim_fmt u1 = unit_fmt(0, 1, 0);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    io->in_ready = sim_const_raw(c, sc, "in_ready", u1, 1);
    io->out_valid = sim_signal_new(c, sc, "out_valid", u1, SIM_KIND_WIRE);
    sim_assign(c, io->out_valid, io->in_valid);
    io->scope = sc;
    return 0;
}

/* The walk's worst-case errors of the coefficients. */
static void coef_bound(const unit_desc *u, const coef_net *net, const unit_cfg *cfg,
                       const unit_fmts *f, double *per_out)
{
    unet n;
    unet_val in[UNET_MAXIN], o[UNET_MAXIN];
    unet_init(&n, u, f, cfg->rnd);
    walk_unit(&n, net, cfg, in, o);
    for (int i = 0; i < net->nout; i++) per_out[i] = o[i].err;
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* The four hooks of one unit, over its network. */
#define COEF_UNIT_FNS(sfx, UNIT, NET) \
    extern const unit_desc UNIT; \
    static void formats_##sfx(const unit_cfg *cfg, unit_fmts *out) { coef_formats(&UNIT, &NET, cfg, out); } \
    static int build_##sfx(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg, \
                           const unit_fmts *f, unit_io *io, char *err, size_t errlen) \
    { (void)clk; return coef_build(&UNIT, &NET, c, sc, cfg, f, io, err, errlen); } \
    static void ideal_##sfx(const unit_cfg *cfg, const double *in, double *out) \
    { NET.formula(in, ref_div3_factor(cfg->terms, cfg->series), out); } \
    static void bound_##sfx(const unit_cfg *cfg, const unit_fmts *f, double *o) { coef_bound(&UNIT, &NET, cfg, f, o); } \
    static int exact_##sfx(const unit_cfg *cfg, const sim_dy *in, sim_dy *out) \
    { return coef_exact(&NET, ref_div3_factor(cfg->terms, cfg->series), in, out); }

COEF_UNIT_FNS(n1, unit_coef3_n1, coef_net_n1)
COEF_UNIT_FNS(n2, unit_coef3_n2, coef_net_n2)
COEF_UNIT_FNS(q, unit_coef2, coef_net_q)

#define COEF_RULE "i* u1.(W-1) (intensities in [0, 1]); a b c d sI.(W-I) (d: uI) with I the fewest integer bits " \
    "holding the coefficient's exact range over [0, 1]^4 plus its error bound; every shift and adder keeps " \
    "all the fraction bits it produces (left shifts need fewer, so 8x, 32x are exact) with I from its range, " \
    "unsigned unless it is a difference or can be negative; each /3 network (one format for its terms, sums " \
    "and output) keeps G = ceil(log2(terms+1)) fraction bits more"
#define COMB_SCHED { { "comb", "combinational: one item per clock" } }

const unit_desc unit_coef3_n1 = {
    .name = "coef3_n1",
    .ref = &ref_model_coef3_n1,
    .summary = "cubic coefficients A B C D from I(0), I(1), I(1/2), I(1/4) by shifts, adders and two /3 networks (Fig. 8)",
    .source = "Nechyporuk & Romanyuk (2020), Fig. 8, nodes N1: I(0), I(1), I(1/2), I(1/4)",
    UNIT_SIGS(COEF_SIGS_I123, COEF_SIG_I4_N1,
              COEF3_N1_NET(COEF_SIG_SKIP, COEF_SIG_OUT)
              COEF3_N1_NET(COEF_SIG_INT, COEF_SIG_SKIP)),
    .nsched = 1, .sched = COMB_SCHED,
    .nparams = 2, .params = { DIV3_P_TERMS, DIV3_P_SERIES },
    .fmt_rule = COEF_RULE,
    .formats = formats_n1, .beats = beats1, .build = build_n1, .ideal = ideal_n1, .bound = bound_n1, .ideal_exact = exact_n1,
    .bound_own_modes = 1,   /* the unet walk's */
};

const unit_desc unit_coef3_n2 = {
    .name = "coef3_n2",
    .ref = &ref_model_coef3_n2,
    .summary = "cubic coefficients A B C D from I(0), I(1), I(1/2), I(3/4), same structure as coef3_n1",
    .source = "Nechyporuk & Romanyuk (2020), nodes N2: I(0), I(1), I(1/2), I(3/4)",
    UNIT_SIGS(COEF_SIGS_I123, COEF_SIG_I4_N2,
              COEF3_N2_NET(COEF_SIG_SKIP, COEF_SIG_OUT)
              COEF3_N2_NET(COEF_SIG_INT, COEF_SIG_SKIP)),
    .nsched = 1, .sched = COMB_SCHED,
    .nparams = 2, .params = { DIV3_P_TERMS, DIV3_P_SERIES },
    .fmt_rule = COEF_RULE,
    .formats = formats_n2, .beats = beats1, .build = build_n2, .ideal = ideal_n2, .bound = bound_n2, .ideal_exact = exact_n2,
    .bound_own_modes = 1,   /* the unet walk's */
};

const unit_desc unit_coef2 = {
    .name = "coef2",
    .ref = &ref_model_coef2,
    .summary = "quadratic coefficients A B C from I(0), I(1), I(1/2) by shifts and adders (no /3)",
    .source = "Nechyporuk & Romanyuk (2020), quadratic through I(0), I(1), I(1/2)",
    UNIT_SIGS(COEF_SIGS_I123,
              COEF2_NET(COEF_SIG_SKIP, COEF_SIG_OUT)
              COEF2_NET(COEF_SIG_INT, COEF_SIG_SKIP)),
    .nsched = 1, .sched = COMB_SCHED,
    .nparams = 0,
    .fmt_rule = "i* u1.(W-1) (intensities in [0, 1]); a b c sI.(W-I) (c: uI) with I the fewest integer bits "
                "holding the coefficient's exact range over [0, 1]^3 plus its error bound; every shift and adder "
                "keeps all the fraction bits it produces, with I from its range, unsigned unless it is a "
                "difference or can be negative",
    .formats = formats_q, .beats = beats1, .build = build_q, .ideal = ideal_q, .bound = bound_q, .ideal_exact = exact_q,
    .bound_own_modes = 1,   /* the unet walk's */
};
