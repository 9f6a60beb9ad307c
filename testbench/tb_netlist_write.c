/* tb_netlist_write.c - a built unit as netlist text (tb_netlist.h,
 * docs/netlist.md): what the context holds after tb_build, one line a
 * signal, read from the element records (sim_prim_describe).
 *
 * What a record does not hold, the text says by checking itself: the
 * writer reads its own text back, builds it, and compares every signal's
 * area and delay arcs with the unit's. Where they differ the element was
 * adjusted after its constructor (a logic element's depth, a constant
 * multiplier built as a shift-and-add network), and the line says so;
 * what still differs after that is refused rather than written wrong.
 */
#include "testbench/tb_netlist.h"
#include "testbench/tb_netlist_int.h"
#include "testbench/tb_vexpr.h"
#include "sim/sim_prim.h"
#include "sim/sim_delay.h"
#include "base/base_out.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct wr {
    FILE *f;
    const sim_scope *sc;
    const sim_signal *clk;
    sim_round r;
    sim_ovf o;
    char *err;
    size_t errlen;
    const nl_dpw *dp;    /* the datapath form, or NULL */
    uint32_t at;         /* the signal being written */
} wr;

/* " KEY=PATH" for signal s (which must be below the unit's scope or be
 * its clock). */
static int put_ref(wr *w, const char *key, const sim_signal *s)
{
    char p[256];
    if (s == w->clk) snprintf(p, sizeof p, "%s", s->name);
    else if (sim_signal_path_below(s, w->sc, p, sizeof p) || !nl_name_ok(p)) {
        snprintf(w->err, w->errlen, "signal %s is outside the unit's scope or has a name the text cannot hold",
                 s->name);
        return -1;
    }
    if (key) fprintf(w->f, " %s=%s", key, p);
    else fputs(p, w->f);
    return 0;
}

/* A logic element's truth table over every raw of its inputs (in[0] the
 * most significant field, as the Verilog export tabulates it): hex
 * digits, (width + 3) / 4 an entry, the output's raw bits. */
static void put_table(wr *w, const sim_prim_info *e, int bits)
{
    int dig = (e->y->fmt.width + 3) / 4;
    uint64_t ymask = e->y->fmt.width >= 64 ? UINT64_MAX : (((uint64_t)1 << e->y->fmt.width) - 1);
    fputs(" table=", w->f);
    for (uint64_t k = 0; k < (uint64_t)1 << bits; k++) {
        int64_t v[8];
        int at = bits;
        for (int i = 0; i < e->n; i++) {
            sim_fmt fi = e->in[i]->fmt;
            at -= fi.width;
            v[i] = sim_fx_canon((int64_t)((k >> at) & (((uint64_t)1 << fi.width) - 1)), fi);
        }
        fprintf(w->f, "%0*llx", dig, (unsigned long long)((uint64_t)e->fn(v, e->user) & ymask));
    }
}

/* 1 if fn(user) gives what e's function gives on every input tried: each
 * input all zeros, all ones, and 4000 draws of every bit at random. */
static int same_fn(const sim_prim_info *e, sim_logic_fn fn, void *user)
{
    uint64_t r = 0x9e3779b97f4a7c15u;
    for (int k = 0; k < 4002; k++) {
        int64_t v[8];
        for (int i = 0; i < e->n; i++) {
            int w = e->in[i]->fmt.width;
            r ^= r << 13; r ^= r >> 7; r ^= r << 17;
            uint64_t bitsv = k == 0 ? 0 : k == 1 ? UINT64_MAX : r;
            v[i] = sim_fx_canon((int64_t)(bitsv & (w >= 64 ? UINT64_MAX : (((uint64_t)1 << w) - 1))), e->in[i]->fmt);
        }
        if (sim_fx_canon(e->fn(v, e->user), e->y->fmt) != sim_fx_canon(fn(v, user), e->y->fmt)) return 0;
    }
    return 1;
}

/* A wide logic element as wiring (bits=): where its Verilog text is
 * "assign %y = EXPR;" with EXPR of nl_bits's form, and EXPR computes what
 * its function computes on every input tried (each input all zeros, all
 * ones, and 4000 draws of every bit at random): 1 and *b; else 0. */
static int wiring_of(const sim_prim_info *e, nl_bits *b)
{
    if (!e->verilog || e->n > 8) return 0;
    char t[600];
    size_t n = 0;
    for (const char *p = e->verilog; *p && n < sizeof t - 1; p++)
        if (*p != ' ' && *p != '\n') t[n++] = *p;
    t[n] = 0;
    if (strncmp(t, "assign%y=", 9) || n < 11 || t[n - 1] != ';') return 0;
    t[n - 1] = 0;
    int w[8];
    for (int i = 0; i < e->n; i++) w[i] = e->in[i]->fmt.width;
    if (nl_bits_parse(t + 9, e->n, w, b)) return 0;
    return same_fn(e, nl_bits_fn, b);
}

/* A wide logic element whose Verilog text tb_vexpr evaluates to what its
 * function gives on every input tried: 1 (fn=verilog). */
static int verilog_of(const sim_prim_info *e)
{
    if (!e->verilog || e->n > 8) return 0;
    int w[8];
    for (int i = 0; i < e->n; i++) w[i] = e->in[i]->fmt.width;
    char err[300];
    tb_vexpr *p = tb_vexpr_compile(e->verilog, e->n, w, e->y->fmt.width, err, sizeof err);
    int ok = p && same_fn(e, tb_vexpr_fn, p);
    tb_vexpr_free(p);
    return ok;
}

/* The element's modes when they are not what its format and the file's
 * defaults give. */
static void put_modes(wr *w, const sim_prim_info *e)
{
    sim_fmt f = e->y->fmt;
    if (e->r != sim_fmt_round(f, w->r)) fprintf(w->f, " round=%s", sim_round_name(e->r));
    if (e->o != sim_fmt_ovf(f, w->o)) fprintf(w->f, " overflow=%s", sim_ovf_name(e->o));
}

/* One signal's line; fix: what the self-check found (NL_FIX_*). */
static int put_signal(wr *w, const sim_signal *s, unsigned fix)
{
    sim_prim_info e;
    char fs[SIM_FMT_STRLEN];
    int has = !sim_prim_describe(s, &e);
    if (s->kind == SIM_KIND_CLOCK || (!has && s->driver)) {
        snprintf(w->err, w->errlen, "signal %s: a %s the text cannot hold", s->name,
                 s->kind == SIM_KIND_CLOCK ? "second clock" : "process that is no element");
        return -1;
    }
    fprintf(w->f, "%s ", sim_kind_name((sim_kind)s->kind));
    if (put_ref(w, NULL, s)) return -1;
    const char *rule = w->dp && w->dp->rule[w->at][0] ? w->dp->rule[w->at] : NULL;
    fprintf(w->f, " %s", rule ? rule : sim_fmt_str(s->fmt, fs));
    int rc = 0;
    switch (s->kind) {
    case SIM_KIND_INPUT:
    case SIM_KIND_WIRE:
        if (has && e.a) { rc = put_ref(w, "from", e.a); put_modes(w, &e); }
        break;
    case SIM_KIND_CONST:
        if (rule) {   /* a value that each width quantizes */
            char num[40];
            fprintf(w->f, " value=%s", nl_real_str(sim_fx_to_real(s->cur, s->fmt), num, sizeof num));
            break;
        }
        fprintf(w->f, " raw=%lld", (long long)s->cur);
        if (s->overflows) fprintf(w->f, " overflows=%llu", (unsigned long long)s->overflows);
        break;
    case SIM_KIND_REG:
        if (e.a) rc |= put_ref(w, "d", e.a);
        if (e.c) rc |= put_ref(w, "en", e.c);
        if (e.rst) rc |= put_ref(w, "rst", e.rst);
        if (e.rst_raw) fprintf(w->f, " init=%lld", (long long)e.rst_raw);   /* at the start, and at a reset */
        rc |= put_ref(w, "clk", e.clk);
        put_modes(w, &e);
        break;
    case SIM_KIND_MUX:
        rc |= put_ref(w, "sel", e.c);
        fputs(" in=", w->f);
        for (int i = 0; i < e.n; i++) {
            if (i) fputc(',', w->f);
            rc |= put_ref(w, NULL, e.in[i]);
        }
        put_modes(w, &e);
        break;
    case SIM_KIND_BK:
        rc |= put_ref(w, "pass", e.c);
        rc |= put_ref(w, "x", e.a);
        put_modes(w, &e);
        break;
    case SIM_KIND_ADD: case SIM_KIND_SUB: case SIM_KIND_MUL:
        rc |= put_ref(w, "a", e.a);
        rc |= put_ref(w, "b", e.b);
        put_modes(w, &e);
        if (fix & NL_FIX_CSD) fputs(" net=csd", w->f);
        break;
    case SIM_KIND_SHIFT:
        rc |= put_ref(w, "x", e.a);
        fprintf(w->f, " by=%d", e.shift);
        put_modes(w, &e);
        break;
    case SIM_KIND_LOGIC: {
        int bits = 0;
        fputs(" in=", w->f);
        for (int i = 0; i < e.n; i++) {
            if (i) fputc(',', w->f);
            rc |= put_ref(w, NULL, e.in[i]);
            bits += e.in[i]->fmt.width;
        }
        char num[40];
        fprintf(w->f, " area=%s", nl_real_str(s->area_ge, num, sizeof num));
        if (fix & NL_FIX_DEPTH) fprintf(w->f, " depth=%d", s->dly_lv[3]);
        if (e.verilog) {
            fputs(" verilog=", w->f);
            nl_put_quoted(w->f, e.verilog);
        }
        nl_bits wiring;
        if (bits <= TB_NETLIST_TABLE_BITS) put_table(w, &e, bits);
        else if (wiring_of(&e, &wiring)) { fputs(" bits=", w->f); nl_bits_put(w->f, &wiring); }
        else if (verilog_of(&e)) fputs(" fn=verilog", w->f);
        else fputs(" fn=unit", w->f);
        break;
    }
    default:
        snprintf(w->err, w->errlen, "signal %s: kind %d the text cannot hold", s->name, s->kind);
        return -1;
    }
    fputc('\n', w->f);
    return rc;
}

/* The scopes below sc, parents first, siblings in the order made (the
 * order the waveforms list them). */
static int put_scopes(wr *w, const sim_scope *sc, const char *prefix)
{
    for (const sim_scope *k = sc->first_child; k; k = k->next_sibling) {
        char p[256];
        snprintf(p, sizeof p, "%s%s%s", prefix, *prefix ? "." : "", k->name);
        if (!nl_name_ok(p)) {
            snprintf(w->err, w->errlen, "scope %s: a name the text cannot hold", p);
            return -1;
        }
        fprintf(w->f, "scope %s\n", p);
        if (put_scopes(w, k, p)) return -1;
    }
    return 0;
}

static void put_head(wr *w, const unit_desc *u, const unit_cfg *cfg)
{
    FILE *f = w->f;
    if (!w->dp) {
        fprintf(f, "# the unit %s as built by shadesim (docs/netlist.md)\nnetlist 1\nunit %s\n", u->name, u->name);
        fprintf(f, "schedule %s\n", u->sched[cfg->schedule].name);
    } else {
        fprintf(f, "# the unit %s as a datapath file (docs/datapaths.md): shadesim netlist %s --datapath\n", u->name, u->name);
        fprintf(f, "netlist 1\ndatapath %s ", u->name);
        nl_put_quoted(f, u->summary);
        fprintf(f, "\nideal unit=%s\n", u->name);
        if (w->dp->anchor < 0) fprintf(f, "schedule %s\n", u->sched[cfg->schedule].name);
    }
    fprintf(f, "width %d\nround %s\noverflow %s\n", cfg->width, sim_round_name(cfg->rnd), sim_ovf_name(cfg->ovf));
}

static int put_text(wr *w, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                    const tb_built *b, const unsigned *fix)
{
    FILE *f = w->f;
    put_head(w, u, cfg);
    for (int i = 0; i < u->nparams; i++) {
        char v[64];
        unit_param_get(&u->params[i], cfg, v, sizeof v);
        fprintf(f, "param %s %s\n", u->params[i].name, v);
    }
    for (int i = 0; i < nfmt; i++) fprintf(f, "fmt %s\n", fmt[i]);
    fprintf(f, "clock %s\n", b->clk->name);
    if (put_scopes(w, b->sc, "")) return -1;
    for (uint32_t i = 0, n = sim_signal_count(b->c); i < n; i++) {
        const sim_signal *s = sim_signal_at(b->c, i);
        if (s == b->clk) continue;
        if (w->dp && w->dp->anchor == (int)i) fputs(w->dp->block, f);
        if (w->dp && w->dp->skip[i]) continue;
        w->at = i;
        if (put_signal(w, s, fix ? fix[i] : 0)) return -1;
    }
    const unit_io *io = &b->io;
    int rc = 0;
    for (int k = 0; k < unit_n_in(u); k++) { fputs("port in ", f); rc |= put_ref(w, NULL, io->in[k]); fputc('\n', f); }
    for (int k = 0; k < unit_n_out(u); k++) { fputs("port out ", f); rc |= put_ref(w, NULL, io->out[k]); fputc('\n', f); }
    const sim_signal *hs[3] = { io->in_valid, io->in_ready, io->out_valid };
    static const char *const hn[3] = { "in_valid", "in_ready", "out_valid" };
    for (int k = 0; k < 3 && !(w->dp && w->dp->anchor >= 0); k++)
        if (hs[k]) { fprintf(f, "port %s ", hn[k]); rc |= put_ref(w, NULL, hs[k]); fputc('\n', f); }
    return rc;
}

static int arcs_equal(const sim_signal *a, const sim_signal *b)
{
    for (int k = 0; k < 4; k++)
        if (a->dly_ps[k] != b->dly_ps[k] || a->dly_lv[k] != b->dly_lv[k]) return 0;
    return 1;
}

/* What the text must add for signal s, built from it as t, to be the
 * unit's; or ~0u when nothing the text can say makes them equal. */
static unsigned fix_of(const sim_signal *s, const sim_signal *t)
{
    if (s->area_ge == t->area_ge && arcs_equal(s, t)) return 0;
    if (s->kind == SIM_KIND_LOGIC && s->area_ge == t->area_ge) {
        /* sim_logic_depth: every arc the same levels of AND2 */
        for (int k = 0; k < 4; k++)
            if (s->dly_lv[k] != s->dly_lv[3] || s->dly_ps[k] != s->dly_lv[3] * SIM_PS_AND2) return ~0u;
        return NL_FIX_DEPTH;
    }
    sim_prim_info e;
    if (s->kind == SIM_KIND_MUL && !sim_prim_describe(s, &e) && e.b->kind == SIM_KIND_CONST) return NL_FIX_CSD;
    return ~0u;
}

/* The text into a memory buffer (*buf, malloc'd). */
static int text_of(wr *w, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                   const tb_built *b, const unsigned *fix, char **buf, size_t *len)
{
    *buf = NULL;
    FILE *m = open_memstream(buf, len);
    if (!m) base_out_of_memory();
    FILE *keep = w->f;
    w->f = m;
    int rc = put_text(w, u, cfg, fmt, nfmt, b, fix);
    w->f = keep;
    if (fclose(m)) base_out_of_memory();
    if (rc) { free(*buf); *buf = NULL; }
    return rc;
}

/* Build text back (the reader's own path) and compare it with b signal by
 * signal: names, kinds, formats, values, area and arcs. Fills fix (when
 * not NULL) with what each signal's line must add; 0 when equal. */
static int check_back(const char *text, size_t len, const tb_built *b, int W, unsigned *fix, char *err, size_t errlen)
{
    unit_cfg cfg;
    unit_fmts fm;
    const unit_desc *nu = nl_load_text(text, len, "(netlist text)", &cfg, &fm, err, errlen);
    if (!nu) return -1;
    tb_built t;
    int rc = 0;
    if (W && W != cfg.width) {
        cfg.width = W;
        rc = tb_formats(nu, &cfg, NULL, 0, &fm, err, errlen);
    }
    t.c = NULL;
    if (!rc) rc = tb_build(nu, &cfg, &fm, &t, err, errlen);
    uint32_t n = sim_signal_count(b->c);
    if (!rc && sim_signal_count(t.c) != n) {
        snprintf(err, errlen, "the text builds %u signals, the unit %u", sim_signal_count(t.c), n);
        rc = -1;
    }
    for (uint32_t i = 0; !rc && i < n; i++) {
        const sim_signal *s = sim_signal_at(b->c, i), *r = sim_signal_at(t.c, i);
        char p1[256], p2[256];
        sim_signal_path(s, p1, sizeof p1);
        sim_signal_path(r, p2, sizeof p2);
        if (strcmp(p1, p2) || s->kind != r->kind || memcmp(&s->fmt, &r->fmt, sizeof s->fmt) || s->cur != r->cur
            || s->overflows != r->overflows) {
            snprintf(err, errlen, "signal %s: the text builds it otherwise (%s, kind %d/%d, raw %lld/%lld)", p1, p2,
                     s->kind, r->kind, (long long)s->cur, (long long)r->cur);
            rc = -1;
            break;
        }
        unsigned x = fix_of(s, r);
        if (x == ~0u || (!fix && x)) {
            snprintf(err, errlen, "signal %s: its area or delay is not one the text can say", p1);
            rc = -1;
        } else if (fix) fix[i] = x;
    }
    if (t.c) sim_free(t.c);
    tb_netlist_free(nu);
    return rc;
}

int nl_check_at(const char *text, size_t len, const tb_built *b, int W, char *err, size_t errlen)
{
    return check_back(text, len, b, W, NULL, err, errlen);
}

int nl_write_text(const nl_dpw *dp, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                  const tb_built *b, char **buf, size_t *len, char *err, size_t errlen)
{
    wr w = { NULL, b->sc, b->clk, cfg->rnd, cfg->ovf, err, errlen, dp, 0 };
    uint32_t n = sim_signal_count(b->c);
    unsigned *fix = calloc(n ? n : 1, sizeof *fix);
    if (!fix) base_out_of_memory();
    char *t1 = NULL;
    size_t l1;
    *buf = NULL;
    int rc = text_of(&w, u, cfg, fmt, nfmt, b, NULL, &t1, &l1);
    if (!rc) rc = check_back(t1, l1, b, 0, fix, err, errlen);
    if (!rc) rc = text_of(&w, u, cfg, fmt, nfmt, b, fix, buf, len);
    if (!rc) rc = check_back(*buf, *len, b, 0, NULL, err, errlen);
    if (rc) { free(*buf); *buf = NULL; }
    free(t1);
    free(fix);
    return rc;
}

int tb_netlist_write(FILE *f, const unit_desc *u, const unit_cfg *cfg, const char *const *fmt, int nfmt,
                     char *err, size_t errlen)
{
    unit_fmts fm;
    if (tb_formats(u, cfg, fmt, nfmt, &fm, err, errlen)) return -1;
    tb_built b;
    if (tb_build(u, cfg, &fm, &b, err, errlen)) { sim_free(b.c); return -1; }
    char *t = NULL;
    size_t l;
    int rc = nl_write_text(NULL, u, cfg, fmt, nfmt, &b, &t, &l, err, errlen);
    if (!rc && fwrite(t, 1, l, f) != l) { snprintf(err, errlen, "write error"); rc = -1; }
    free(t);
    sim_free(b.c);
    return rc;
}
