/* tb_netlist_dpw.c - a built-in unit as a datapath file (tb_netlist.h:
 * tb_netlist_write_dp, docs/datapaths.md): the netlist text of
 * tb_netlist_write.c with the two things a datapath file says in its own
 * words, each written only where the file it gives builds the unit back:
 *  - the formats as rules of the width W, fitted from the unit built at
 *    the file's width and two others, and kept only when the file built
 *    at those two is the unit built there, signal by signal;
 *  - the control as a schedule's rows where the unit's is the step
 *    counter the reader makes (the Horner units'); else the counter, its
 *    decoders and the handshake stay elements and ports of their own.
 * The file names the unit (ideal unit=NAME): it runs with the unit's
 * float reference, vectors, ideal function and bound.
 */
#include "testbench/tb_netlist_int.h"
#include "sim/sim_prim.h"
#include "base/base_out.h"
#include <stdlib.h>
#include <string.h>

/* One side of a rule, c0 + c1 W, as the reader reads it. */
static void side(char *buf, size_t len, int c0, int c1)
{
    if (!c1) { snprintf(buf, len, "%d", c0); return; }
    char w[16];
    if (c1 == 1) snprintf(w, sizeof w, "W");
    else if (c1 == -1) snprintf(w, sizeof w, "-W");
    else snprintf(w, sizeof w, "%d*W", c1);
    if (!c0 && c1 == 1) snprintf(buf, len, "W");
    else if (!c0) snprintf(buf, len, "(%s)", w);
    else snprintf(buf, len, "(%s%+d)", w, c0);
}

/* The slope of v over the widths W[0..2] when it is a whole number and
 * the same between each pair: 0 and *k, else -1. */
static int slope(const int *W, const int *v, int *k)
{
    int d = W[1] - W[0], e = W[2] - W[0];
    if ((v[1] - v[0]) % d || (v[2] - v[0]) % e || (v[1] - v[0]) / d != (v[2] - v[0]) / e) return -1;
    *k = (v[1] - v[0]) / d;
    return 0;
}

/* Rules for every signal of b[0] from b[0..2] built at W[0..2]: 0, or -1
 * when the builds differ in their signals or a format is no line of W. */
static int fit_rules(tb_built *b, const int *W, char (*rule)[48])
{
    uint32_t n = sim_signal_count(b[0].c);
    if (sim_signal_count(b[1].c) != n || sim_signal_count(b[2].c) != n) return -1;
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s[3];
        int I[3], F[3];
        char p[3][256];
        for (int k = 0; k < 3; k++) {
            s[k] = sim_signal_at(b[k].c, i);
            sim_signal_path(s[k], p[k], sizeof p[k]);
            I[k] = s[k]->fmt.ibits;
            F[k] = s[k]->fmt.fbits;
        }
        if (strcmp(p[0], p[1]) || strcmp(p[0], p[2]) || s[0]->kind != s[1]->kind || s[0]->kind != s[2]->kind) return -1;
        rule[i][0] = 0;
        int ki, kf;
        if (s[0]->kind == SIM_KIND_CLOCK || slope(W, I, &ki) || slope(W, F, &kf) || (!ki && !kf)) continue;
        char fs[SIM_FMT_STRLEN], a[20], c[20];
        const char *modes = strchr(sim_fmt_str(s[0]->fmt, fs), ':');
        side(a, sizeof a, I[0] - ki * W[0], ki);
        side(c, sizeof c, F[0] - kf * W[0], kf);
        snprintf(rule[i], 48, "%c%s.%s%s", s[0]->fmt.is_signed ? 's' : 'u', a, c, modes ? modes : "");
    }
    return 0;
}

/* A logic element's value on inputs v. */
static int64_t logic_at(const sim_signal *s, int64_t v0, int64_t v1)
{
    sim_prim_info e;
    if (sim_prim_describe(s, &e) || s->kind != SIM_KIND_LOGIC) return -1;
    int64_t v[2] = { v0, v1 };
    return e.fn(v, e.user);
}

static int bits_for(int v) { int b = 1; while (b < 62 && ((int64_t)1 << b) <= v) b++; return b; }

/* The unit's control as the reader's step counter (tb_datapath_parse.c):
 * step, step_next, a decoder per control signal (a logic element of step
 * alone), in_ready on the last step and out_valid its register, each
 * table what the reader tabulates from the rows. The block's text into
 * *block (malloc'd), the signals it makes marked in skip, and the anchor;
 * 0, or -1 when the control is another. */
static int find_block(const tb_built *b, const char *sched, unsigned char *skip, int *anchor, char **block)
{
    const sim_signal *iv = sim_find(b->c, b->sc, "in_valid"), *st = sim_find(b->c, b->sc, "step"),
                     *nx = sim_find(b->c, b->sc, "step_next"), *rdy = sim_find(b->c, b->sc, "in_ready"),
                     *ov = sim_find(b->c, b->sc, "out_valid");
    sim_prim_info e;
    if (!iv || !st || !nx || !rdy || !ov || iv != b->io.in_valid || rdy != b->io.in_ready || ov != b->io.out_valid
        || st->kind != SIM_KIND_REG || sim_prim_describe(st, &e) || e.a != nx || ov->kind != SIM_KIND_REG
        || sim_prim_describe(ov, &e) || e.a != rdy || st->fmt.fbits || st->fmt.is_signed)
        return -1;
    int sb = st->fmt.width, C = 0;
    if (sb > 8) return -1;
    for (int k = 1; k < 1 << sb && !C; k++) if (logic_at(nx, k, 1) == 0) C = k + 1;
    if (C < 2 || C > NL_MAX_CLOCKS || bits_for(C - 1) != sb) return -1;
    for (int k = 0; k < 1 << sb; k++)
        for (int v = 0; v < 2; v++)
            if (logic_at(nx, k, v) != ((k == 0 && !v) || k >= C - 1 ? 0 : k + 1)) return -1;
    for (int k = 0; k < 1 << sb; k++) if (logic_at(rdy, k, 0) != (k == C - 1)) return -1;
    size_t len;
    FILE *m = open_memstream(block, &len);
    if (!m) base_out_of_memory();
    fprintf(m, "schedule %s clocks=%d\n", sched, C);
    int nctl = 0;
    uint32_t n = sim_signal_count(b->c);
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = sim_signal_at(b->c, i);
        skip[i] = s == iv || s == st || s == nx || s == rdy || s == ov;
        if (s == iv) *anchor = (int)i;
        if (s == rdy || s->kind != SIM_KIND_LOGIC || sim_prim_describe(s, &e) || e.n != 1 || e.in[0] != st) continue;
        int ok = s->scope == b->sc && s->fmt.width <= 8 && !s->fmt.is_signed && !s->fmt.fbits, vmax = 0;
        for (int k = 0; k < 1 << sb && ok; k++) {
            int64_t v = logic_at(s, k, 0);
            ok = k >= C || (v >= 0 && v <= 255);   /* past the last step: never reached */
            if (k < C && v > vmax) vmax = (int)v;
        }
        if (!ok || bits_for(vmax) != s->fmt.width || ++nctl > NL_MAX_CTL) { fclose(m); free(*block); *block = NULL; return -1; }
        skip[i] = 1;
        fprintf(m, "ctl %s", s->name);
        for (int k = 0; k < C; k++) fprintf(m, " %lld", (long long)logic_at(s, k, 0));
        fputc('\n', m);
    }
    if (fclose(m)) base_out_of_memory();
    return 0;
}

/* The unit built at width W (with the --fmt overrides): 0, or -1. */
static int build_at(const unit_desc *u, const unit_cfg *cfg, int W, const char *const *fmt, int nfmt, tb_built *b)
{
    unit_cfg c = *cfg;
    c.width = W;
    unit_fmts fm;
    char err[600];
    b->c = NULL;
    if (W < 1 || W > 64 || tb_formats(u, &c, fmt, nfmt, &fm, err, sizeof err)) return -1;
    if (tb_build(u, &c, &fm, b, err, sizeof err)) { sim_free(b->c); b->c = NULL; return -1; }
    return 0;
}

int tb_netlist_write_dp(FILE *f, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                        char *err, size_t errlen)
{
    tb_built b[3];
    int W[3] = { cfg->width, 0, 0 };
    unit_fmts fm;
    if (tb_formats(u, cfg, fmt, nfmt, &fm, err, errlen)) return -1;
    if (tb_build(u, cfg, &fm, &b[0], err, errlen)) { sim_free(b[0].c); return -1; }
    /* two other widths the unit builds at, nearest first */
    static const int near[] = { 1, -1, 2, -2, 3, -3 };
    int nb = 1;
    for (size_t k = 0; k < sizeof near / sizeof near[0] && nb < 3; k++)
        if (!build_at(u, cfg, cfg->width + near[k], fmt, nfmt, &b[nb])) W[nb++] = cfg->width + near[k];
    uint32_t n = sim_signal_count(b[0].c);
    nl_dpw dp = { calloc(n + 1, 48), calloc(n + 1, 1), -1, NULL };
    unsigned char *no_skip = calloc(n + 1, 1);
    char (*no_rule)[48] = calloc(n + 1, 48);
    if (!dp.rule || !dp.skip || !no_skip || !no_rule) base_out_of_memory();
    int rules = nb == 3 && !fit_rules(b, W, dp.rule);
    char *block = NULL;
    int has_block = !find_block(&b[0], u->sched[cfg->schedule].name, dp.skip, &dp.anchor, &block);
    /* the forms from the most the file says in its own words to the least */
    char *t = NULL;
    size_t l = 0;
    int rc = -1;
    for (int form = 0; form < 4 && rc; form++) {
        int with_block = !(form & 2), with_rules = !(form & 1);
        if ((with_block && !has_block) || (with_rules && !rules)) continue;
        nl_dpw d = { with_rules ? dp.rule : no_rule, with_block ? dp.skip : no_skip, with_block ? dp.anchor : -1,
                     with_block ? block : NULL };
        free(t);
        rc = nl_write_text(&d, u, cfg, fmt, nfmt, &b[0], &t, &l, err, errlen);
        for (int k = 1; k < 3 && !rc && with_rules; k++) rc = nl_check_at(t, l, &b[k], W[k], err, errlen);
    }
    if (!rc && fwrite(t, 1, l, f) != l) { snprintf(err, errlen, "write error"); rc = -1; }
    free(t);
    free(block);
    free(dp.rule);
    free(dp.skip);
    free(no_skip);
    free(no_rule);
    for (int k = 0; k < nb; k++) sim_free(b[k].c);
    return rc;
}
