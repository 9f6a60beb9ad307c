/* tb_datapath_parse.c - the lines only a datapath file has
 * (docs/datapaths.md): formats as rules of the width, schedules and their
 * control rows, the ideal expressions' text, and at the end of the file
 * the control and handshake elements the reader makes from them
 * (tb_netlist_int.h; tb_datapath.c makes the unit). */
#include "testbench/tb_netlist_int.h"
#include "base/base_num.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BAD(...) nl_bad(x, x->line, __VA_ARGS__)

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

int nl_rule_at(const nl_rule *r, int W, sim_fmt *f, char *err, size_t errlen)
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

/* ideal unit=NAME: the built-in unit whose reference the file runs with;
 * the file's width and modes so far are kept, the rest is the unit's
 * default configuration (its parameters, its first schedule). */
static int ideal_unit(nl *x, const char *name)
{
    if (x->base) return BAD("ideal unit= given twice (first at line %d)", x->ref_line);
    if (x->nideal) return BAD("ideal unit=%s: the file gives ideal expressions (line %d): one or the other", name, x->ideal_line[0]);
    const unit_desc *u = unit_find(name);
    if (!u) return BAD("ideal unit=%s: no such built-in unit (shadesim list)", name);
    unit_cfg keep = x->cfg;
    unit_cfg_default(u, &x->cfg);
    x->cfg.width = keep.width;
    x->cfg.rnd = keep.rnd;
    x->cfg.ovf = keep.ovf;
    x->base = u;
    x->ref_line = x->line;
    return 0;
}

int nl_dp_line(nl *x, char **tok, int nt)
{
    const char *k = tok[0];
    if (!strcmp(k, "ctl")) return parse_ctl(x, tok, nt);
    close_ctl(x);
    if (!strcmp(k, "schedule") && nt == 2 && x->base) {
        /* the unit's schedule the file's own control is for */
        int s = unit_sched_find(x->base, tok[1]);
        if (s < 0) return BAD("schedule %s: unit %s has no such schedule", tok[1], x->base->name);
        if (x->ref_sched_line) return BAD("schedule %s: the unit's schedule named twice (first at line %d)", tok[1], x->ref_sched_line);
        x->cfg.schedule = s;
        x->ref_sched_line = x->line;
        return 0;
    }
    if (!strcmp(k, "schedule")) {
        if (x->hs_line) return BAD("schedule: the file gives its own handshake (port at line %d): one or the other", x->hs_line);
        if (x->latency_line) return BAD("schedule: the file is a pipeline (latency at line %d): one or the other", x->latency_line);
        return parse_schedule(x, tok, nt);
    }
    if (!strcmp(k, "latency")) {
        long long n;
        if (nt != 2 || base_num_whole(tok[1], 0, &n) || n < 1 || n > NL_MAX_CLOCKS)
            return BAD("latency: expected latency N, the clocks from an item in to its result out, 1..%d", NL_MAX_CLOCKS);
        if (x->latency_line) return BAD("latency given twice (first at line %d)", x->latency_line);
        if (x->hs_line) return BAD("latency: the file gives its own handshake (port at line %d): one or the other", x->hs_line);
        if (x->nsched) return BAD("latency: the file has schedules (line %d): one or the other", x->sched_line[0]);
        x->latency = (int)n;
        x->latency_line = x->line;
        return 0;
    }
    if (!strcmp(k, "ideal") && nt == 2 && !strncmp(tok[1], "unit=", 5)) return ideal_unit(x, tok[1] + 5);
    if (!strcmp(k, "ideal")) {
        if (x->base) return BAD("ideal: the file's ideal is unit %s's (line %d): no expressions beside it", x->base->name, x->ref_line);
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
    if (!strcmp(k, "port") && nt == 3 && strcmp(tok[1], "in") && strcmp(tok[1], "out")) {
        /* the handshake written out: the file's own control (a counter of
         * its own, a pipeline's valid registers) in place of schedules */
        if (x->nsched || x->latency_line)
            return BAD("port %s: the handshake is made from the file's %s (line %d): port in and port out only", tok[1],
                       x->nsched ? "schedules" : "latency", x->nsched ? x->sched_line[0] : x->latency_line);
        if (!x->hs_line) x->hs_line = x->line;
    }
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
    } else if (x->hs_line) {
        /* the file's own handshake: its port lines name its elements */
        static const char *const hs[3] = { "in_valid", "in_ready", "out_valid" };
        for (int r = P_IN_VALID; r <= P_OUT_VALID; r++)
            if (!x->nport[r])
                return nl_bad(x, x->hs_line, "the file gives its own handshake: it needs port in_valid, port in_ready "
                              "and port out_valid (no port %s)", hs[r - P_IN_VALID]);
        x->line = 0;
        return 0;
    } else {
        for (int i = 0; i < x->nel && !x->latency; i++)
            if (x->el[i].kind == SIM_KIND_REG)
                return nl_bad(x, x->el[i].line, "reg %s: a datapath without a schedule is combinational (add schedule "
                              "NAME clocks=N and its control rows, or latency N for a pipeline)", x->el[i].name);
        /* an item a clock; a pipeline's valid bit travels beside it */
        gen_el(x, SIM_KIND_INPUT, "in_valid", NL_GEN_VALID, 0);
        nl_el *r = gen_el(x, SIM_KIND_CONST, "in_ready", NL_GEN_LAST, 0);
        r->raw = 1;
        const char *prev = "in_valid";
        for (int k = 1; k <= x->latency; k++) {
            char nm[24];
            snprintf(nm, sizeof nm, k == x->latency ? "out_valid" : "valid%d", k);
            nl_el *v = gen_el(x, SIM_KIND_REG, nm, NL_GEN_OUTV, x->latency_line);
            v->ref[OP_A] = (char *)prev;
            v->ref[OP_CLK] = x->clk;
            prev = v->name;
        }
        if (!x->latency) {
            nl_el *ov = gen_el(x, SIM_KIND_WIRE, "out_valid", NL_GEN_OUTV, 0);
            ov->ref[OP_A] = "in_valid";
        }
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

