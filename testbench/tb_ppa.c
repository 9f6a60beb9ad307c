/* tb_ppa.c - the speed and energy figures a result derives from its
 * critical path and switching activity (tb_ppa, docs/timing.md), and the
 * constraints a search or a run can put on them. A pixel is an output
 * beat: an interpolation unit's item is L pixels, any other unit's item
 * one result. */
#include "testbench/tb.h"
#include "base/base_json.h"
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

void tb_ppa_path_text(const tb_ppa *p, char *buf, size_t len)
{
    size_t k = 0;
    if (!len) return;
    buf[0] = 0;
    for (int i = 0; i < p->npath && k + 1 < len; i++) {
        int m;
        /* a long path: its first four and last four signals */
        if (p->npath > 10 && i == 4) {
            m = snprintf(buf + k, len - k, " -> ... (%d more)", p->npath - 8);
            i = p->npath - 5;
        } else m = snprintf(buf + k, len - k, "%s%s", i ? " -> " : "", p->path[i]);
        if (m < 0) break;
        k += (size_t)m;
    }
}

void tb_ppa_json_path(FILE *f, const tb_ppa *p)
{
    fprintf(f, "{\"levels\": %d, \"ps\": ", p->levels);
    base_json_num(f, p->crit_ps, 17);
    fputs(", \"signals\": [", f);
    for (int i = 0; i < p->npath; i++) {
        fputs(i ? ", " : "", f);
        base_json_str(f, p->path[i]);
    }
    fputs("]}", f);
}
