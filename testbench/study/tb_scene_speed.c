/* tb_scene_speed.c - a render's speed and energy in hardware terms, and
 * the bound the buildable part of a per-pixel reference puts on it
 * (tb_scene.h, tb_scene_speed). */
#include "testbench/study/tb_scene.h"
#include "testbench/study/tb_scene_pipes.h"
#include "base/base_json.h"
#include <math.h>
#include <string.h>

/* The div unit at `width` on 64 of its reference's vectors (seed 1): its
 * clocks per division, critical path, f_max and energy per division. */
static int divider(int width, double *clocks, tb_ppa *p, char *err, size_t errlen)
{
    const unit_desc *u = unit_find("div");
    if (!u || !u->ref) { snprintf(err, errlen, "no div unit to bound the reference with"); return -1; }
    unit_cfg cfg;
    unit_fmts f;
    unit_cfg_default(u, &cfg);
    cfg.width = width;
    if (tb_formats(u, &cfg, NULL, 0, &f, err, errlen)) return -1;
    vec_set vs;
    vec_set_init(&vs);
    vec_set_header(&vs, u->ref, &cfg.model);
    if (u->ref->gen(&cfg.model, 64, 1, &vs)) {
        vec_set_free(&vs);
        snprintf(err, errlen, "cannot generate vectors for div");
        return -1;
    }
    tb_result r;
    int rc = tb_run(u, &cfg, &f, &vs, NULL, &r, err, errlen);
    if (rc == TB_OK) {
        *clocks = r.cycles_per_item;
        *p = r.ppa;
    }
    tb_result_free(&r);
    vec_set_free(&vs);
    return rc == TB_OK ? 0 : -1;
}

int tb_scene_speed_of(tb_scene_result *r, int width, char *err, size_t errlen)
{
    tb_scene_speed *sp = &r->speed;
    memset(sp, 0, sizeof *sp);
    r->have_speed = 0;
    sp->energy_pj_per_pixel = sp->ref_energy_pj_per_pixel_min = NAN;
    if (tb_unit_timing(r->unit, &r->cfg, &r->fmts, &sp->hw, err, errlen)) return -1;
    tb_ppa_rate(&sp->hw, r->clocks_per_pixel);
    sp->pixels_per_s = r->clocks_per_pixel > 0 ? sp->hw.fmax_mhz * 1e6 / r->clocks_per_pixel : NAN;
    if (r->hwst.pixels && r->hwst.energy_pj > 0) sp->energy_pj_per_pixel = r->energy_pj_per_pixel;
    sp->ref_divs = r->ops_ref[SCN_OP_DIV];
    if (divider(width, &sp->div_clocks, &sp->div, err, errlen)) return -1;
    double divs_per_s = sp->div_clocks > 0 ? sp->div.fmax_mhz * 1e6 / sp->div_clocks : NAN;
    sp->ref_pixels_per_s_max = sp->ref_divs > 0 ? divs_per_s / sp->ref_divs : INFINITY;
    sp->ref_energy_pj_per_pixel_min = sp->div.energy_pj_per_item * sp->ref_divs;
    sp->node_divs = r->ops_hw[SCN_OP_DIV];
    sp->node_pixels_per_s_max = sp->node_divs > 0 ? divs_per_s / sp->node_divs : INFINITY;
    r->have_speed = 1;
    return 0;
}

void tb_scene_speed_print(FILE *f, const tb_scene_result *r)
{
    if (!r->have_speed) return;
    const tb_scene_speed *sp = &r->speed;
    char a[64], path[600];
    tb_ppa_path_text(&sp->hw, path, sizeof path);
    snprintf(a, sizeof a, "%.0f MHz", sp->hw.fmax_mhz);
    fprintf(f, "  %-22s %-14s critical path %d levels, %.0f ps (%s)\n", "f_max", a, sp->hw.levels,
            sp->hw.crit_ps, path);
    snprintf(a, sizeof a, "%.4g M", sp->pixels_per_s / 1e6);
    fprintf(f, "  %-22s %-14s at f_max, %.3f clocks per pixel\n", "pixels / s", a, r->clocks_per_pixel);
    if (isnan(sp->energy_pj_per_pixel)) snprintf(a, sizeof a, "-");
    else snprintf(a, sizeof a, "%.3g pJ", sp->energy_pj_per_pixel);
    fprintf(f, "  %-22s %-14s switching and clock of unit %s (not the node shading; docs/timing.md)\n",
            "energy / pixel", a, r->unit->name);
    /* the bounds where the shade unit does not measure the reference */
    if (r->pipes && r->pipes->ok) return;
    snprintf(a, sizeof a, "%.4g M", sp->ref_pixels_per_s_max / 1e6);
    fprintf(f, "  %-22s <= %-11s %.3g divide%s per pixel on unit div: %.0f clocks each at %.0f MHz, %.3g pJ\n",
            "ref. pixels / s", a, sp->ref_divs, sp->ref_divs == 1 ? "" : "s", sp->div_clocks, sp->div.fmax_mhz,
            sp->div.energy_pj_per_item);
    snprintf(a, sizeof a, "%.3g pJ", sp->ref_energy_pj_per_pixel_min);
    fprintf(f, "  %-22s >= %-11s (its square roots and powers would add to both; the shade unit does not take "
            "this lighting)\n", "ref. energy / pixel", a);
    /* The method's shaded nodes divide too: on the same divider they
     * bound its rate as the reference's divides bound the reference's. */
    snprintf(a, sizeof a, "%.4g M", sp->node_pixels_per_s_max / 1e6);
    fprintf(f, "  %-22s <= %-11s the method's node shading, %.3g divides per pixel on the same divider\n",
            "nodes pixels / s", a, sp->node_divs);
}

void tb_scene_speed_json(FILE *f, const tb_scene_result *r)
{
    if (!r->have_speed) return;
    const tb_scene_speed *sp = &r->speed;
    fputs(",\n  \"critical_path\": ", f);
    tb_ppa_json_path(f, &sp->hw);
    fputs(",\n  \"fmax_mhz\": ", f); base_json_num(f, sp->hw.fmax_mhz, 17);
    fputs(",\n  \"pixels_per_s\": ", f); base_json_num(f, sp->pixels_per_s, 17);
    fputs(",\n  \"energy_pj_per_pixel\": ", f); base_json_num(f, sp->energy_pj_per_pixel, 17);
    fputs(",\n  \"reference_bound\": {\"divides_per_pixel\": ", f); base_json_num(f, sp->ref_divs, 17);
    fputs(", \"div_clocks\": ", f); base_json_num(f, sp->div_clocks, 17);
    fputs(", \"div_fmax_mhz\": ", f); base_json_num(f, sp->div.fmax_mhz, 17);
    fputs(", \"div_energy_pj\": ", f); base_json_num(f, sp->div.energy_pj_per_item, 17);
    fputs(", \"pixels_per_s_max\": ", f); base_json_num(f, sp->ref_pixels_per_s_max, 17);
    fputs(", \"energy_pj_per_pixel_min\": ", f); base_json_num(f, sp->ref_energy_pj_per_pixel_min, 17);
    fputs("},\n  \"nodes_bound\": {\"divides_per_pixel\": ", f); base_json_num(f, sp->node_divs, 17);
    fputs(", \"pixels_per_s_max\": ", f); base_json_num(f, sp->node_pixels_per_s_max, 17);
    fputs("}", f);
}
