/* tb_items.c - a unit over a list of independent items on the batch's
 * lanes (tb_items.h). */
#include "testbench/tb_items.h"
#include "testbench/tb_batch.h"
#include "base/base_out.h"
#include "base/base_par.h"
#include "sim/sim_area.h"
#include <stdlib.h>
#include <string.h>

/* Items per lane: long enough that a lane's start (its latency) is a
 * small part of it, few enough lanes that the batch's vector loops fill. */
#define ITEMS_PER_LANE 256
#define ITEMS_MAX_LANES 1024
#define ITEMS_GROUP_LANES 128    /* lanes a group (each group builds the unit and runs on one thread) */
#define ITEMS_GROUPS (ITEMS_MAX_LANES / ITEMS_GROUP_LANES)

typedef struct items_job {
    const unit_desc *u;
    const unit_cfg *cfg;
    const unit_fmts *f;
    const double *in;
    size_t n;
    int n_in, n_out, energy;
    uint32_t nlanes, ngroups;
    vec_set *vs;
    tb_batch_lane *lanes;
    int rc[ITEMS_GROUPS];
    char err[ITEMS_GROUPS][300];
} items_job;

static size_t lane_first(const items_job *J, uint32_t k)
{
    return (size_t)((unsigned __int128)J->n * k / J->nlanes);
}

static void group_run(void *arg, size_t g)
{
    items_job *J = arg;
    uint32_t k0 = (uint32_t)((uint64_t)J->nlanes * g / J->ngroups);
    uint32_t k1 = (uint32_t)((uint64_t)J->nlanes * (g + 1) / J->ngroups);
    if (k1 <= k0) return;
    J->rc[g] = tb_batch_run(J->u, J->cfg, J->f, &J->lanes[k0], k1 - k0, J->err[g], sizeof J->err[g]);
}

/* The first output's format: the first signal of the descriptor whose
 * role is an output. */
static sim_fmt out_fmt(const unit_desc *u, const unit_fmts *f)
{
    for (int i = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_OUT) return f->f[i];
    return f->f[0];
}

int tb_items_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, const double *in, size_t n, int jobs,
                 int energy, double *out, tb_items_stats *st, char *err, size_t errlen)
{
    memset(st, 0, sizeof *st);
    st->items = n;
    tb_built b;
    if (tb_build(u, cfg, f, &b, err, errlen)) { sim_free(b.c); return TB_BADINPUT; }
    st->area_ge = sim_scope_area(b.sc);
    sim_free(b.c);
    if (!n) return TB_OK;
    items_job J = { .u = u, .cfg = cfg, .f = f, .in = in, .n = n, .n_in = unit_n_in(u), .n_out = unit_n_out(u),
                    .energy = energy };
    size_t nl = (n + ITEMS_PER_LANE - 1) / ITEMS_PER_LANE;
    J.nlanes = (uint32_t)(nl > ITEMS_MAX_LANES ? ITEMS_MAX_LANES : nl);
    /* groups of lanes fixed by the count alone, as the lanes are: a
     * lane's switching is counted until its group's last lane ends, so a
     * grouping by threads would change the energy with -j */
    J.ngroups = (J.nlanes + ITEMS_GROUP_LANES - 1) / ITEMS_GROUP_LANES;
    J.vs = calloc(J.nlanes, sizeof *J.vs);
    J.lanes = calloc(J.nlanes, sizeof *J.lanes);
    double *row = malloc((size_t)(J.n_in + J.n_out) * sizeof *row);
    if (!J.vs || !J.lanes || !row) base_out_of_memory();
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(u, cfg, &hdr);
    for (uint32_t k = 0; k < J.nlanes; k++) {
        vec_set *vs = &J.vs[k];
        *vs = hdr;                        /* the header: unit, ports; no rows */
        vs->data = NULL;
        vs->n_rows = vs->cap_rows = 0;
        memset(row, 0, (size_t)(J.n_in + J.n_out) * sizeof *row);   /* no expected outputs: not checked */
        for (size_t i = lane_first(&J, k); i < lane_first(&J, k + 1); i++) {
            memcpy(row, in + i * (size_t)J.n_in, (size_t)J.n_in * sizeof *row);
            if (vec_set_push(vs, row)) base_out_of_memory();
        }
        J.lanes[k].vs = vs;
        J.lanes[k].energy = energy;
    }
    vec_set_free(&hdr);
    free(row);
    base_par_for(J.ngroups, jobs < 1 ? 1 : jobs, group_run, &J);
    int rc = TB_OK;
    for (uint32_t g = 0; g < J.ngroups; g++)
        if (J.rc[g] != TB_OK && rc == TB_OK) { rc = J.rc[g]; snprintf(err, errlen, "%s", J.err[g]); }
    sim_fmt fo = out_fmt(u, f);
    size_t stride = (size_t)u->beats(cfg) * (size_t)J.n_out;
    for (uint32_t k = 0; k < J.nlanes; k++) {
        tb_batch_lane *L = &J.lanes[k];
        size_t i0 = lane_first(&J, k), m = J.vs[k].n_rows;
        if (rc == TB_OK) {
            for (size_t i = 0; i < m; i++) out[i0 + i] = sim_fx_to_real(L->raw[i * stride], fo);
            st->clocks += L->clocks;
            st->overflows += L->overflows;
            st->in_overflows += L->in_overflows;
            st->energy_pj += L->energy_pj_per_item * (double)m;
            if (m > 1) {
                double cpi = (double)(L->beat_cycle[(m - 1) * (size_t)u->beats(cfg)] - L->beat_cycle[0]) / (double)(m - 1);
                if (cpi > st->cycles_per_item) st->cycles_per_item = cpi;
            }
        }
        free(L->raw);
        free(L->beat_cycle);
        free(L->sig_toggles);
        vec_set_free(&J.vs[k]);
    }
    if (n == 1 && rc == TB_OK) st->cycles_per_item = (double)J.lanes[0].clocks;
    st->lanes = J.nlanes;
    free(J.vs);
    free(J.lanes);
    return rc;
}
