/* tb_range.c - range logging and the per-signal table of a run. */
#include "testbench/tb_range.h"
#include <stdlib.h>
#include <string.h>

/* 1 if s is in scope sc or below it. */
int tb_range_in_scope(const sim_signal *s, const sim_scope *sc)
{
    for (const sim_scope *p = s->scope; p; p = p->parent) if (p == sc) return 1;
    return 0;
}

/* s's dotted path below scope sc: "y", "div3_a.t1". */
void tb_range_name(const sim_signal *s, const sim_scope *sc, char *buf, size_t len)
{
    const sim_scope *chain[16];
    int n = 0;
    for (const sim_scope *p = s->scope; p && p != sc && n < 16; p = p->parent) chain[n++] = p;
    size_t at = 0;
    buf[0] = 0;
    while (n-- > 0 && at + 1 < len) {
        int w = snprintf(buf + at, len - at, "%s.", chain[n]->name);
        if (w < 0) break;
        at += (size_t)w < len - at ? (size_t)w : len - at - 1;
    }
    snprintf(buf + at, len - at, "%s", s->name);
}

int tb_range_init(tb_range *g, sim_ctx *c, const sim_scope *sc, const sim_signal *clk)
{
    memset(g, 0, sizeof *g);
    size_t n = sim_signal_count(c);
    if (!n) n = 1;
    g->smp = calloc(n, sizeof *g->smp);
    g->mn = calloc(n, sizeof *g->mn);
    g->mx = calloc(n, sizeof *g->mx);
    g->live = calloc(n, sizeof *g->live);
    g->lv = calloc(n, sizeof *g->lv);
    if (!g->smp || !g->mn || !g->mx || !g->live || !g->lv) return -1;
    for (uint32_t i = 0, ns = sim_signal_count(c); i < ns; i++) {
        sim_signal *sg = sim_signal_at(c, i);
        if (sg == clk || !tb_range_in_scope(sg, sc)) continue;
        /* a constant never changes: its range is its value, not sampled */
        int cst = sg->kind == SIM_KIND_CONST;
        g->mn[g->nsmp] = cst ? sg->cur : INT64_MAX;
        g->mx[g->nsmp] = cst ? sg->cur : INT64_MIN;
        if (!cst) {
            g->lv[g->nlive].sig = sg;           /* its range is set by the first sample */
            g->live[g->nlive++] = g->nsmp;
        }
        g->smp[g->nsmp++] = sg;
    }
    return 0;
}

void tb_range_widen(tb_range_live *l, uint64_t d, int first)
{
    int64_t v = (int64_t)((uint64_t)l->lo + d);
    if (first) { l->lo = v; l->span = 0; return; }
    int64_t lo = l->lo, hi = (int64_t)((uint64_t)lo + l->span);
    if (v < lo) lo = v;
    if (v > hi) hi = v;
    l->lo = lo;
    l->span = (uint64_t)hi - (uint64_t)lo;
}

void tb_range_finish(tb_range *g, const sim_scope *sc, const unit_io *io, const uint64_t *in_ovf,
                     tb_result *r)
{
    /* never sampled: min > max, "not seen", as for no value at all */
    for (int j = 0; j < g->nlive; j++) {
        g->mn[g->live[j]] = g->sampled ? g->lv[j].lo : INT64_MAX;
        g->mx[g->live[j]] = g->sampled ? (int64_t)((uint64_t)g->lv[j].lo + g->lv[j].span) : INT64_MIN;
    }
    r->sigs = calloc(g->nsmp ? (size_t)g->nsmp : 1, sizeof *r->sigs);
    if (!r->sigs) return;
    for (int i = 0; i < g->nsmp; i++) {
        const sim_signal *sg = g->smp[i];
        tb_sig *t = &r->sigs[i];
        tb_range_name(sg, sc, t->name, sizeof t->name);
        t->fmt = sg->fmt;
        t->kind = sg->kind;
        t->overflows = sg->overflows;
        t->ovf_discarded = sg->ovf_discarded;
        for (int j = 0; j < r->n_in; j++) if (io->in[j] == sg) t->overflows += in_ovf[j];
        t->seen = g->mn[i] <= g->mx[i];
        t->min = g->mn[i];
        t->max = g->mx[i];
    }
    r->nsigs = g->nsmp;
}

void tb_range_free(tb_range *g)
{
    free(g->smp);
    free(g->mn);
    free(g->mx);
    free(g->live);
    free(g->lv);
    memset(g, 0, sizeof *g);
}

uint64_t tb_scope_ovf_discarded(const sim_scope *sc)
{
    uint64_t n = 0;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) n += s->ovf_discarded;
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) n += tb_scope_ovf_discarded(ch);
    return n;
}

uint64_t tb_scope_overflows(const sim_scope *sc)
{
    uint64_t n = 0;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) n += s->overflows;
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) n += tb_scope_overflows(ch);
    return n;
}
