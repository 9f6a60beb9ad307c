/* unit.c - the unit registry, parameters and format/bound helpers. */
#include "units/unit.h"
#include "units/unit_net.h"     /* the /3 network's paper defaults */
#include "base/base_num.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The registry: every unit, in the order `shadesim list` and docs/units.md
 * show them, one line each. A unit is its descriptor unit_NAME (its own
 * file, units/unit_*.c, which points at its float reference in vectors/)
 * and its line here: nothing else lists units (docs/adding-a-unit.md). */
#define UNIT_LIST(X) \
    X(horner3)      /* unit_horner.c: the Horner datapath, Fig. 9 */ \
    X(horner2) \
    X(div3)         /* unit_div3.c: the divide-by-3 network, Fig. 7 */ \
    X(coef3_n1)     /* unit_coef.c: the coefficient units, Fig. 8 */ \
    X(coef3_n2) \
    X(coef2) \
    X(interp3)      /* unit_interp.c: coefficients and Horner per interval */ \
    X(interp2) \
    X(powg)         /* unit_powg.c: the power engine */ \
    X(pow_n)        /* unit_pow_n.c */ \
    X(d_approx)     /* unit_dapprox.c */ \
    X(ward_approx) \
    X(div)          /* unit_div.c: the restoring divider */ \
    X(schlick)      /* unit_schlick.c */ \
    X(mschlick) \
    X(span1)        /* unit_span.c: span interpolation, any length */ \
    X(span2) \
    X(span3) \
    X(span23) \
    X(hf_lookup)    /* unit_hflookup.c: the factorized BRDF's lookups */ \
    X(sqrt)         /* unit_sqrt.c: the restoring square root */ \
    X(dot3)         /* unit_dot3.c: the dot product (unit_nrm.c) */ \
    X(norm3)        /* unit_norm3.c: N/|N| (unit_nrm.c) */ \
    X(shade)        /* unit_shade.c: one pixel of Blinn shading */ \
    X(shade_cook)   /* unit_shade_cook.c: one pixel of Cook-Torrance with D_g */

#define UNIT_DECLARE(name) extern const unit_desc unit_##name;
#define UNIT_ENTRY(name) &unit_##name,
UNIT_LIST(UNIT_DECLARE)
static const unit_desc *const registry[] = { UNIT_LIST(UNIT_ENTRY) };
#define NUNITS (sizeof registry / sizeof registry[0])

size_t unit_count(void) { return NUNITS; }

const unit_desc *unit_at(size_t i) { return i < NUNITS ? registry[i] : NULL; }

const unit_desc *unit_find(const char *name)
{
    for (size_t i = 0, n = unit_count(); i < n; i++)
        if (!strcmp(unit_at(i)->name, name)) return unit_at(i);
    return NULL;
}

/* Store v into parameter p's field (ints and enums: an int). */
static void param_put(const unit_param *p, unit_cfg *cfg, double v)
{
    char *base = (char *)cfg + p->offset;
    if (p->type == UNIT_P_REAL) *(double *)base = v;
    else *(int *)base = (int)v;
}

void unit_cfg_default(const unit_desc *u, unit_cfg *c)
{
    memset(c, 0, sizeof *c);
    c->width = 16;
    c->rnd = SIM_RND_TRUNC;
    c->ovf = SIM_OVF_WRAP;
    /* Fields that are not u's parameters: shared values its code may read */
    c->terms = DIV3_PAPER_TERMS;
    c->series = DIV3_PAPER;
    vec_params_default(&c->model);      /* L, g, n, m, alpha, nodes */
    /* u's parameters: its own defaults */
    for (int i = 0; u && i < u->nparams; i++) param_put(&u->params[i], c, u->params[i].def);
}

static int count_role(const unit_desc *u, unit_role r)
{
    int n = 0;
    for (int i = 0; i < u->nsigs; i++) n += u->sigs[i].role == r;
    return n;
}
int unit_n_in(const unit_desc *u) { return count_role(u, UNIT_SIG_IN); }
int unit_n_out(const unit_desc *u) { return count_role(u, UNIT_SIG_OUT); }

int unit_sig_index(const unit_desc *u, const char *name)
{
    for (int i = 0; i < u->nsigs; i++)
        if (!strcmp(u->sigs[i].name, name)) return i;
    return -1;
}

int unit_sig_fmt_fixed(const unit_desc *u, int i)
{
    for (int k = 0; k < 4 && u->fmt_fixed[k]; k++)
        if (!strcmp(u->sigs[i].name, u->fmt_fixed[k])) return 1;
    return 0;
}

int unit_sig_used(const unit_desc *u, int i, int sched)
{
    unsigned m = u->sigs[i].scheds;
    return !m || (sched >= 0 && sched < 32 && (m >> sched & 1u));
}

int unit_sig_built(const unit_desc *u, int i, const unit_cfg *cfg)
{
    if (!unit_sig_used(u, i, cfg->schedule)) return 0;
    return !u->sig_used || u->sig_used(cfg, i);
}

int unit_sig_must(const unit_desc *u, const char *name)
{
    int i = unit_sig_index(u, name);
    if (i < 0) {
        fprintf(stderr, "shadesim: internal error: unit %s has no signal '%s'\n", u->name, name);
        abort();
    }
    return i;
}

int unit_sched_find(const unit_desc *u, const char *name)
{
    for (int i = 0; i < u->nsched; i++)
        if (!strcmp(u->sched[i].name, name)) return i;
    return -1;
}

/* Index of word `w` in a space-separated list, or -1. */
static int choice_index(const char *list, const char *w)
{
    size_t n = strlen(w);
    int i = 0;
    for (const char *p = list; *p; i++) {
        size_t k = strcspn(p, " ");
        if (k == n && !strncmp(p, w, n)) return i;
        p += k;
        while (*p == ' ') p++;
    }
    return -1;
}

int unit_param_set(const unit_desc *u, unit_cfg *cfg, const char *name,
                   const char *value, char *err, size_t errlen)
{
    const unit_param *p = NULL;
    for (int i = 0; i < u->nparams; i++)
        if (!strcmp(u->params[i].name, name)) p = &u->params[i];
    if (!p) {
        char list[256] = "";
        for (int i = 0; i < u->nparams; i++) {
            strncat(list, i ? ", " : "", sizeof list - strlen(list) - 1);
            strncat(list, u->params[i].name, sizeof list - strlen(list) - 1);
        }
        snprintf(err, errlen, "unit %s has no parameter '%s' (it has: %s)", u->name, name,
                 u->nparams ? list : "none");
        return -1;
    }
    char *base = (char *)cfg + p->offset;
    if (p->type == UNIT_P_ENUM) {
        int k = choice_index(p->choices, value);
        if (k < 0) { snprintf(err, errlen, "parameter %s: '%s' is not one of: %s", name, value, p->choices); return -1; }
        *(int *)base = k;
        return 0;
    }
    /* One syntax of numbers (base_num.h): a whole-number parameter takes
     * digits only ("1e1", "10.0" are refused); a '-' where the range
     * does not go below 0 is outside it, "-0" too. */
    int whole = p->type == UNIT_P_INT || p->type == UNIT_P_POW2;
    double v;
    if (whole) {
        long long w;
        if (base_num_whole(value, 1, &w)) {
            snprintf(err, errlen, "parameter %s: '%s' is not a whole number", name, value);
            return -1;
        }
        v = w < -(1LL << 53) ? -HUGE_VAL : w > (1LL << 53) ? HUGE_VAL : (double)w;
    } else if (base_num_real(value, 1, &v)) {
        snprintf(err, errlen, "parameter %s: '%s' is not a number", name, value);
        return -1;
    }
    if (*value == '-' && p->min >= 0) v = -HUGE_VAL;    /* "-0": outside, below */
    if (v < p->min || v > p->max) {
        snprintf(err, errlen, "parameter %s: %s is outside %g..%g", name, value, p->min, p->max);
        return -1;
    }
    if (p->type == UNIT_P_POW2 && ((long)v & ((long)v - 1))) {
        snprintf(err, errlen, "parameter %s: %s is not a power of two", name, value);
        return -1;
    }
    param_put(p, cfg, v);
    return 0;
}

void unit_param_get(const unit_param *p, const unit_cfg *cfg, char *buf, size_t len)
{
    const char *base = (const char *)cfg + p->offset;
    if (p->type == UNIT_P_INT || p->type == UNIT_P_POW2) { snprintf(buf, len, "%d", *(const int *)base); return; }
    if (p->type == UNIT_P_REAL) { snprintf(buf, len, "%g", *(const double *)base); return; }
    int k = *(const int *)base;
    const char *s = p->choices;
    while (k-- > 0 && *s) { s += strcspn(s, " "); while (*s == ' ') s++; }
    snprintf(buf, len, "%.*s", (int)strcspn(s, " "), s);
}

static int fmt_eq(sim_fmt a, sim_fmt b)
{
    return a.is_signed == b.is_signed && a.ibits == b.ibits && a.fbits == b.fbits;
}

int unit_min_width(const unit_desc *u, const unit_cfg *cfg, int *limit_sig)
{
    unit_cfg c = *cfg;
    unit_fmts f16, f17, prev, cur;
    unsigned char dep[UNIT_MAX_SIGS];
    /* The signals that follow W: their formats differ between 16 and 17
     * (mid-range: no clamp at either end). */
    c.width = 16; u->formats(&c, &f16);
    c.width = 17; u->formats(&c, &f17);
    for (int i = 0; i < u->nsigs; i++) dep[i] = unit_sig_built(u, i, &c) && !fmt_eq(f16.f[i], f17.f[i]);
    int lim = -1;
    c.width = 1;
    u->formats(&c, &prev);
    for (int w = 2; w <= 64; w++, prev = cur) {
        c.width = w;
        u->formats(&c, &cur);
        int bad = -1;
        for (int i = 0; i < u->nsigs; i++)
            if (dep[i] && fmt_eq(cur.f[i], prev.f[i]) && (bad < 0 || cur.f[i].ibits > cur.f[bad].ibits)) bad = i;
        if (bad < 0) {
            if (limit_sig) *limit_sig = lim;
            return w;
        }
        lim = bad;
    }
    if (limit_sig) *limit_sig = lim;
    return 64;
}

sim_fmt unit_fmt(int is_signed, int ibits, int fbits)
{
    sim_fmt f = { 0 };      /* no modes of its own */
    if (fbits < 0) fbits = 0;
    int maxw = is_signed ? 64 : 63;
    if (ibits + fbits > maxw) fbits = maxw - ibits;
    if (ibits + fbits < 1) fbits = 1 - ibits;
    f.is_signed = (uint8_t)(is_signed != 0);
    f.ibits = (int8_t)ibits;
    f.fbits = (int8_t)fbits;
    f.width = (uint8_t)(ibits + fbits);
    return f;
}

double unit_qerr(sim_fmt f, int src_f, sim_round r)
{
    if (src_f <= f.fbits) return 0.0;
    r = sim_fmt_round(f, r);
    /* trunc drops at most all-ones below the kept LSB: 2^-F - 2^-src_f
     * (a double rounds it up, never down); not a whole LSB, so that a
     * signal made wider does not make its consumer's bound grow */
    if (r == SIM_RND_TRUNC) return ldexp(1.0, -f.fbits) - ldexp(1.0, -src_f);
    return ldexp(0.5, -f.fbits);
}

void unit_bound(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    u->bound(cfg, f, per_out);
    if (u->bound_own_modes) return;
    for (int i = 0; i < u->nsigs; i++)
        if (unit_sig_built(u, i, cfg) && sim_fmt_round(f->f[i], cfg->rnd) != cfg->rnd) {
            for (int o = 0, n = unit_n_out(u); o < n; o++) per_out[o] = INFINITY;
            return;
        }
}
