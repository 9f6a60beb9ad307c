/* sim_timing.c - arrival times over the element graph (a depth-first walk
 * from every signal back to where its paths start, each signal once), the
 * latest endpoint, and the path back to its start. */
#include "sim/sim_timing.h"
#include "sim/sim_delay.h"
#include "sim/sim_prim.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct walk {
    const sim_ctx *c;
    sim_delay *al, *am;   /* arrival of each signal's least and most significant bit (NONE: no path) */
    int32_t *pred;        /* the input its most significant bit came through, or -1 at a start */
    unsigned char *st;    /* 0 not seen, 1 on the walk's stack, 2 done */
    char    *err;
    size_t   errlen;
} walk;

/* Later arrival wins (by ps; at a tie, more levels); NONE loses. */
static int later(sim_delay a, sim_delay b) { return a.lv >= 0 && (b.lv < 0 || a.ps > b.ps || (a.ps == b.ps && a.lv > b.lv)); }

static int visit(walk *w, const sim_signal *s)
{
    uint32_t i = s->index;
    if (w->st[i] == 2) return 0;
    if (w->st[i] == 1) {
        char path[256];
        snprintf(w->err, w->errlen, "combinational loop through %s", sim_signal_path(s, path, sizeof path));
        return -1;
    }
    w->st[i] = 1;
    w->al[i] = w->am[i] = SIM_DELAY_NONE;
    w->pred[i] = -1;
    sim_prim_info in;
    const sim_delay zero = { 0, 0.0 };
    if (s->kind == SIM_KIND_CONST || s->kind == SIM_KIND_CLOCK) {
        /* no path starts at a tied value or at the clock (as data) */
    } else if (!s->driver || sim_prim_describe(s, &in)) {
        w->al[i] = w->am[i] = zero;     /* an input, or a process whose timing is its own */
    } else if (in.kind == SIM_KIND_REG) {
        w->al[i] = w->am[i] = sim_arcs_of(s).mm;   /* clock-to-q */
    } else {
        const sim_signal **r = malloc((size_t)(10 + (in.n > 0 ? in.n : 0)) * sizeof *r);
        if (!r) { snprintf(w->err, w->errlen, "out of memory"); return -1; }
        int nr = sim_prim_reads(&in, r);
        sim_arcs a = sim_arcs_of(s);
        for (int k = 0; k < nr; k++) {
            if (visit(w, r[k])) { free(r); return -1; }
            uint32_t j = r[k]->index;
            const sim_delay l[2] = { sim_delay_then(w->al[j], a.ll), sim_delay_then(w->am[j], a.ml) };
            const sim_delay m[2] = { sim_delay_then(w->al[j], a.lm), sim_delay_then(w->am[j], a.mm) };
            for (int e = 0; e < 2; e++) {
                if (later(l[e], w->al[i])) w->al[i] = l[e];
                if (later(m[e], w->am[i])) { w->am[i] = m[e]; w->pred[i] = (int32_t)j; }
            }
        }
        free(r);
    }
    w->st[i] = 2;
    return 0;
}

int sim_timing_analyze(const sim_ctx *c, sim_timing *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    uint32_t n = sim_signal_count(c);
    walk w = { c, malloc((n ? n : 1) * sizeof(sim_delay)), malloc((n ? n : 1) * sizeof(sim_delay)),
               malloc((n ? n : 1) * sizeof(int32_t)), calloc(n ? n : 1, 1), err, errlen };
    int32_t *chain = malloc((size_t)(n + 1) * sizeof *chain);
    int rc = -1;
    if (!w.al || !w.am || !w.pred || !w.st || !chain) { snprintf(err, errlen, "out of memory"); goto done; }
    for (uint32_t i = 0; i < n; i++)
        if (visit(&w, sim_signal_at(c, i))) goto done;
    /* Endpoints: every signal as it is (a port no register captures ends
     * there), and every register's sampled inputs plus what they need. */
    sim_delay best = SIM_DELAY_NONE;
    int32_t best_src = -1, best_reg = -1;
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = sim_signal_at(c, i);
        if (later(w.am[i], best)) { best = w.am[i]; best_src = (int32_t)i; best_reg = -1; }
        sim_prim_info in;
        if (s->kind != SIM_KIND_REG || !s->driver || sim_prim_describe(s, &in) || in.kind != SIM_KIND_REG) continue;
        const sim_signal *src[3] = { in.a, in.c, in.rst };
        const sim_delay need[3] = { sim_delay_reg_d(in.c != NULL), sim_delay_reg_en(), sim_delay_reg_rst() };
        for (int k = 0; k < 3; k++) {
            if (!src[k]) continue;
            sim_delay t = sim_delay_then(w.am[src[k]->index], need[k]);
            if (later(t, best)) { best = t; best_src = (int32_t)src[k]->index; best_reg = (int32_t)i; }
        }
    }
    if (best_src >= 0) {
        int m = 0;
        if (best_reg >= 0) chain[m++] = best_reg;
        for (int32_t j = best_src; j >= 0 && m <= (int)n; j = w.pred[j]) chain[m++] = j;
        out->levels = best.lv;
        out->ps = best.ps;
        out->fmax_mhz = best.ps > 0 ? 1e6 / best.ps : 0;
        out->nfull = m;
        /* start first; a path too long keeps its beginning and its end */
        int keep = m < SIM_TIMING_PATH_MAX ? m : SIM_TIMING_PATH_MAX;
        for (int k = 0; k < keep - 1; k++) out->path[k] = sim_signal_at(c, (uint32_t)chain[m - 1 - k]);
        if (keep > 0) out->path[keep - 1] = sim_signal_at(c, (uint32_t)chain[0]);
        out->npath = keep;
    }
    rc = 0;
done:
    free(w.al); free(w.am); free(w.pred); free(w.st); free(chain);
    return rc;
}
