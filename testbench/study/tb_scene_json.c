/* tb_scene_json.c - a render's outputs: scene.json (tb_scene_json, with
 * the key of the maps) and the folder of images (tb_scene_write). */
#include "testbench/study/tb_scene.h"
#include "testbench/study/tb_scene_pipes.h"
#include "base/base_json.h"
#include "base/base_out.h"
#include "units/unit_net.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

int tb_scene_err_scale(const tb_scene_result *r)
{
    int k = 4096;
    while (k > 1 && r->max_abs_err * k > 1) k /= 4;
    return k;
}

static void jops(FILE *f, const double *ops)
{
    fputc('{', f);
    for (int k = 0; k < SCN_OP__COUNT; k++) {
        fprintf(f, "%s\"%s\": ", k ? ", " : "", scn_op_name[k]);
        base_json_num(f, ops[k], 17);
    }
    fputc('}', f);
}

static void jrgb(FILE *f, const uint8_t c[3])
{
    fprintf(f, "\"#%02x%02x%02x\"", c[0], c[1], c[2]);
}

/* The key of the maps tb_scene_write draws, from the same colour functions:
 * the uncovered background, the colour of each degree (all three) and of
 * each region label present, and the heat map's five stops as errors
 * |hw - ref| at the render's scale K (full white: 1/K or more). */
static void legend_json(FILE *f, const tb_scene_result *r)
{
    uint8_t c[3] = { 0, 0, 0 };
    int K = tb_scene_err_scale(r);
    fputs(",\n  \"legend\": {\n    \"background\": ", f);
    jrgb(f, c);
    fputs(",\n    \"degree\": {", f);
    for (int g = 1; g <= 3; g++) {
        scn_label_rgb(g, c);
        fprintf(f, "%s\"%d\": ", g > 1 ? ", " : "", g);
        jrgb(f, c);
    }
    fputs("},\n    \"region\": {", f);
    int seen[256] = { 0 }, n = 0;
    size_t np = (size_t)r->w * r->h;
    for (size_t i = 0; i < np; i++)
        if (r->deg[i]) seen[r->region[i]] = 1;
    for (int k = 0; k < 256; k++) {
        if (!seen[k]) continue;
        scn_label_rgb(k, c);
        fprintf(f, "%s\"%d\": ", n++ ? ", " : "", k);
        jrgb(f, c);
    }
    fprintf(f, "},\n    \"error\": {\"file\": \"err-x%d.png\", \"white\": ", K);
    base_json_num(f, 1.0 / K, 17);
    fputs(", \"stops\": [", f);
    for (int k = 0; k <= 4; k++) {
        scn_heat_rgb(k / 4.0, c);
        fputs(k ? ", [" : "[", f);
        base_json_num(f, k / 4.0 / K, 17);
        fputs(", ", f);
        jrgb(f, c);
        fputc(']', f);
    }
    fputs("]}\n  }", f);
}

int tb_scene_json(FILE *f, const scn_desc *d, const tb_scene_result *r)
{
    const unit_desc *u = r->unit;
    char fb[SIM_FMT_STRLEN];
    fputs("{\n  \"mesh\": ", f);
    base_json_str(f, d->mesh);
    fprintf(f, ",\n  \"resolution\": \"%dx%d\",\n  \"view\": \"%s\",\n  \"policy\": \"%s\",\n", r->w, r->h,
            r->heldout ? "heldout" : "main", scn_policy_name(d->policy));
    fprintf(f, "  \"L\": %d,\n  \"terms\": %d,\n  \"series\": \"%s\",\n  \"width\": %d,\n", r->cfg.L, r->cfg.terms,
            r->cfg.series == DIV3_QUARTER ? "quarter" : "paper", r->cfg.width);
    fprintf(f, "  \"cubic_nodes\": \"%s\",\n  \"auto_threshold\": ", tb_scene_nodes_n2(d) ? "n2" : "n1");
    base_json_num(f, d->auto_threshold, 17);
    fprintf(f, ",\n  \"unit\": \"%s\",\n  \"schedule\": \"%s\",\n  \"formats\": {", u->name, u->sched[r->cfg.schedule].name);
    for (int i = 0, n = 0; i < u->nsigs; i++)
        if (unit_sig_built(u, i, &r->cfg))
            fprintf(f, "%s\"%s\": \"%s\"", n++ ? ", " : "", u->sigs[i].name, sim_fmt_str(r->fmts.f[i], fb));
    fprintf(f, "},\n  \"round\": \"%s\",\n  \"overflow\": \"%s\",\n", sim_round_name(r->cfg.rnd), sim_ovf_name(r->cfg.ovf));
    fprintf(f, "  \"covered\": %zu,\n  \"nmse\": ", r->covered); base_json_num(f, r->nmse, 17);
    fputs(",\n  \"nmse8\": ", f); base_json_num(f, r->nmse8, 17);
    fputs(",\n  \"psnr\": ", f); base_json_num(f, r->psnr, 17);
    fputs(",\n  \"max_abs_err\": ", f); base_json_num(f, r->max_abs_err, 17);
    fprintf(f, ",\n  \"max_err8\": %d,\n  \"diff8_share\": ", r->max_err8); base_json_num(f, r->diff8_share, 17);
    fprintf(f, ",\n  \"err_scale\": %d,\n", tb_scene_err_scale(r));
    fprintf(f, "  \"clocks\": %llu,\n  \"pixels\": %llu,\n  \"clocks_per_pixel\": ",
            (unsigned long long)r->hwst.clocks, (unsigned long long)r->hwst.pixels);
    base_json_num(f, r->clocks_per_pixel, 17);
    fputs(",\n  \"area_ge\": ", f); base_json_num(f, r->hwst.area_ge, 17);
    fprintf(f, ",\n  \"overflows\": %llu,\n  \"spans\": %zu,\n  \"intervals\": %zu,\n  \"intervals_deg2\": %zu,\n  \"deg2_share\": ",
            (unsigned long long)r->hwst.overflows, r->spans, r->intervals, r->intervals_deg2);
    base_json_num(f, r->deg2_share, 17);
    fprintf(f, ",\n  \"nodes_shaded\": %zu,\n  \"ops_ref\": ", r->nodes_shaded);
    jops(f, r->ops_ref);
    fputs(",\n  \"ops_hw\": ", f); jops(f, r->ops_hw);
    fputs(",\n  \"cost_weights\": ", f); jops(f, d->cost);
    fputs(",\n  \"cost_ref\": ", f); base_json_num(f, r->cost_ref, 17);
    fputs(",\n  \"cost_hw\": ", f); base_json_num(f, r->cost_hw, 17);
    fputs(",\n  \"speedup\": ", f); base_json_num(f, r->speedup, 17);
    fputs(",\n  \"long_ops_ref\": ", f); base_json_num(f, r->long_ref, 17);
    fputs(",\n  \"long_ops_hw\": ", f); base_json_num(f, r->long_hw, 17);
    fputs(",\n  \"speedup_long\": ", f); base_json_num(f, r->speedup_long, 17);
    tb_scene_speed_json(f, r);
    tb_scene_pipes_json(f, r->pipes);
    legend_json(f, r);
    fputs("\n}\n", f);
    return ferror(f) ? -1 : 0;
}

static int write_png(base_outset *set, const char *dir, const char *name, int w, int h, int ch, const uint8_t *pix,
                     char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    uint8_t *buf;
    size_t len;
    if (scn_png_encode(w, h, ch, pix, &buf, &len)) base_out_of_memory();    /* its one failure */
    int rc = base_outset_write(set, path, buf, len, err, errlen);
    free(buf);
    return rc;
}

/* The images and scene.json are one set (base_outset): all of them move
 * in together or, on a failure or an interruption, none. */
int tb_scene_write(const scn_desc *d, const tb_scene_result *r, const char *dir, char *err, size_t errlen)
{
    if (base_out_mkdirs(dir, err, errlen)) return -1;
    size_t np = (size_t)r->w * r->h;
    uint8_t *g8 = calloc(np ? np : 1, 1), *rgb = calloc(np ? np * 3 : 1, 1);
    base_outset *set = base_outset_new();
    if (!g8 || !rgb || !set) base_out_of_memory();
    int rc = 0;
    for (size_t i = 0; i < np; i++) g8[i] = r->deg[i] ? tb_scene_to8(r->ref[i]) : 0;
    rc = rc ? rc : write_png(set, dir, "ref.png", r->w, r->h, 1, g8, err, errlen);
    for (size_t i = 0; i < np; i++) g8[i] = r->deg[i] ? tb_scene_to8(r->hw[i]) : 0;
    rc = rc ? rc : write_png(set, dir, "hw.png", r->w, r->h, 1, g8, err, errlen);
    /* both pipelines in hardware: the reference through the shade unit,
     * and the method with its nodes from it */
    const tb_scene_pipes *pp = r->pipes && r->pipes->ok ? r->pipes : NULL;
    for (int k = 0; pp && k < 2; k++) {
        const double *img = k ? pp->hw_nodes : pp->ref_hw;
        for (size_t i = 0; i < np; i++) g8[i] = r->deg[i] ? tb_scene_to8(img[i]) : 0;
        rc = rc ? rc : write_png(set, dir, k ? "hw-nodes.png" : "ref-hw.png", r->w, r->h, 1, g8, err, errlen);
    }
    int K = tb_scene_err_scale(r);
    for (size_t i = 0; i < np; i++) {
        if (!r->deg[i]) { memset(rgb + 3 * i, 0, 3); continue; }
        double e = fabs(r->hw[i] - r->ref[i]) * K;
        scn_heat_rgb(e < 1 ? e : 1, rgb + 3 * i);
    }
    char name[64];
    snprintf(name, sizeof name, "err-x%d.png", K);
    rc = rc ? rc : write_png(set, dir, name, r->w, r->h, 3, rgb, err, errlen);
    for (size_t i = 0; i < np; i++) {
        if (r->deg[i]) scn_label_rgb(r->deg[i], rgb + 3 * i);
        else memset(rgb + 3 * i, 0, 3);
    }
    rc = rc ? rc : write_png(set, dir, "degree.png", r->w, r->h, 3, rgb, err, errlen);
    for (size_t i = 0; i < np; i++) {
        if (r->deg[i]) scn_label_rgb(r->region[i], rgb + 3 * i);
        else memset(rgb + 3 * i, 0, 3);
    }
    rc = rc ? rc : write_png(set, dir, "region.png", r->w, r->h, 3, rgb, err, errlen);
    rc = rc ? rc : tb_scene_write_keys(set, dir, r, K, err, errlen);
    free(g8);
    free(rgb);
    char path[4200];
    snprintf(path, sizeof path, "%s/scene.json", dir);
    FILE *jf = rc ? NULL : base_outset_open(set, path, err, errlen);
    if (!jf) { base_outset_abort(set); return -1; }
    tb_scene_json(jf, d, r);
    if (base_outset_commit(set, err, errlen)) return -1;
    /* the heat maps of earlier renders at other scales would mislead */
    for (int k = 1; k <= 4096; k *= 4) {
        if (k == K) continue;
        char old[4200];
        snprintf(old, sizeof old, "%s/err-x%d.png", dir, k);
        base_out_remove_stale(old);
    }
    return 0;
}
