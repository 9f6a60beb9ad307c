/* tb_scene_keys.c - the colour keys of a render's maps as small SVG
 * images beside them (degree-key.svg, region-key.svg, err-key.svg): the
 * maps keep one pixel per pixel, and the key travels with them instead of
 * living only in scene.json and the docs. Drawn from the colour functions
 * that colour the maps (scn_label_rgb, scn_heat_rgb). */
#include "testbench/study/tb_scene.h"
#include "base/base_out.h"
#include <stdio.h>
#include <stdlib.h>

#define KEY_ROW 22              /* one swatch and its label a row */

static void head(FILE *f, int w, int rows, const char *title)
{
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
               "font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n"
               "<text x=\"8\" y=\"18\" font-weight=\"bold\">%s</text>\n", w, 28 + rows * KEY_ROW + 6, title);
}

static void swatch(FILE *f, int row, const uint8_t c[3], const char *label)
{
    int y = 28 + row * KEY_ROW;
    fprintf(f, "<rect x=\"8\" y=\"%d\" width=\"28\" height=\"16\" fill=\"#%02x%02x%02x\" stroke=\"#000000\" "
               "stroke-width=\"0.5\"/>\n<text x=\"44\" y=\"%d\">%s</text>\n", y, c[0], c[1], c[2], y + 13, label);
}

static int put(base_outset *set, const char *dir, const char *name, char *buf, size_t len, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    int rc = base_outset_write(set, path, buf, len, err, errlen);
    free(buf);
    return rc;
}

int tb_scene_write_keys(base_outset *set, const char *dir, const tb_scene_result *r, int K, char *err, size_t errlen)
{
    char *buf;
    size_t len;
    uint8_t c[3] = { 0, 0, 0 };
    char label[64];
    /* degree: the three, and the background */
    FILE *f = open_memstream(&buf, &len);
    if (!f) base_out_of_memory();
    head(f, 220, 4, "degree.png: degree");
    for (int g = 1; g <= 3; g++) {
        scn_label_rgb(g, c);
        snprintf(label, sizeof label, "%d (%s)", g, g == 1 ? "linear" : g == 2 ? "quadratic" : "cubic");
        swatch(f, g - 1, c, label);
    }
    c[0] = c[1] = c[2] = 0;
    swatch(f, 3, c, "not covered");
    fputs("</svg>\n", f);
    fclose(f);
    int rc = put(set, dir, "degree-key.svg", buf, len, err, errlen);
    /* region: each label present, and the background */
    int seen[256] = { 0 }, n = 0;
    size_t np = (size_t)r->w * r->h;
    for (size_t i = 0; i < np; i++)
        if (r->deg[i]) seen[r->region[i]] = 1;
    for (int k = 0; k < 256; k++) n += seen[k];
    if (!(f = open_memstream(&buf, &len))) base_out_of_memory();
    head(f, 220, n + 1, "region.png: mesh region");
    int row = 0;
    for (int k = 0; k < 256; k++) {
        if (!seen[k]) continue;
        scn_label_rgb(k, c);
        snprintf(label, sizeof label, "region %d", k);
        swatch(f, row++, c, label);
    }
    c[0] = c[1] = c[2] = 0;
    swatch(f, row, c, "not covered");
    fputs("</svg>\n", f);
    fclose(f);
    rc = rc ? rc : put(set, dir, "region-key.svg", buf, len, err, errlen);
    /* the heat map: its five stops at the render's scale K */
    if (!(f = open_memstream(&buf, &len))) base_out_of_memory();
    snprintf(label, sizeof label, "err-x%d.png: |hw - ref|", K);
    head(f, 240, 5, label);
    for (int k = 0; k <= 4; k++) {
        scn_heat_rgb(k / 4.0, c);
        snprintf(label, sizeof label, "%s%.6g", k == 4 ? "&gt;= " : "", k / 4.0 / K);
        swatch(f, k, c, label);
    }
    fputs("</svg>\n", f);
    fclose(f);
    rc = rc ? rc : put(set, dir, "err-key.svg", buf, len, err, errlen);
    return rc;
}
