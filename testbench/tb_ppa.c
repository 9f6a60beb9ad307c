/* tb_ppa.c - the speed and energy figures a result derives from its
 * critical path and switching activity (tb_ppa, docs/timing.md), and the
 * constraints a search or a run can put on them. A pixel is an output
 * beat: an interpolation unit's item is L pixels, any other unit's item
 * one result. */
#include "testbench/tb.h"
#include <math.h>

double tb_pixels_per_s(const tb_result *r)
{
    if (!(r->ppa.fmax_mhz > 0) || !(r->cycles_per_beat > 0)) return NAN;
    return r->ppa.fmax_mhz * 1e6 / r->cycles_per_beat;
}

double tb_energy_pj_per_pixel(const tb_result *r)
{
    return r->beats > 0 ? r->ppa.energy_pj_per_item / r->beats : NAN;
}

int tb_ppa_meets(const tb_result *r, const tb_ppa_limits *l, char *why, size_t len)
{
    if (why && len) why[0] = 0;
    if (!l) return 1;
    if (l->min_items_per_s > 0 && !(r->ppa.items_per_s >= l->min_items_per_s)) {
        if (why) snprintf(why, len, "%.4g items/s < %.4g", r->ppa.items_per_s, l->min_items_per_s);
        return 0;
    }
    if (l->max_energy_pj > 0 && !(r->ppa.energy_pj_per_item <= l->max_energy_pj)) {
        if (why) snprintf(why, len, "%.4g pJ/item > %.4g", r->ppa.energy_pj_per_item, l->max_energy_pj);
        return 0;
    }
    return 1;
}
