/* scene_span.c - spans of a surface buffer, attributes along them.
 *
 * A span is a maximal run of covered pixels of one row. It ends where the
 * next pixel is uncovered, has another region label, or lies across a
 * depth jump. Depth jump between horizontal neighbours a = x-1 and b = x,
 * with dd = depth[b] - depth[a] and the footprint f = foot0 + foot1 * z
 * (world size of one pixel at the nearer depth z, from the rasterizer):
 *
 *   |dd| > JUMP_K * f   (the surface would be steeper than JUMP_K : 1
 *                        against the image plane: 8 : 1, about 83 degrees)
 *   and no neighbouring difference supports it: neither the difference
 *   before (x-2 -> x-1) nor the one after (x -> x+1), where those pixels
 *   are covered (in any region), has the same sign and at least 1/JUMP_M
 *   of its size (JUMP_M = 3).
 *
 * The second condition keeps a smooth surface turning away from the
 * viewer (a sphere near its outline, where the depth steps grow
 * gradually) in one span, while the step from an occluding part to what
 * lies behind it (much larger than the steps on either side) breaks.
 * A gbuf with foot0 = foot1 = 0 (built by hand) has no depth breaks.
 *
 * scn_spans: *out is non-NULL on success, even with no spans; out of
 * memory returns 0 with *out NULL.
 */
#include "scene/scene.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define JUMP_K 8.0
#define JUMP_M 3.0

/* Pixels i and j (same row) can be in one span as far as coverage and
 * region go. */
static int joinable(const scn_gbuf *g, size_t i, size_t j)
{
    return g->tri[i] >= 0 && g->tri[j] >= 0 && g->region[i] == g->region[j];
}

/* Is there a depth jump between x-1 and x on row y? */
static int jump(const scn_gbuf *g, int y, int x)
{
    if (g->foot0 == 0 && g->foot1 == 0) return 0;
    size_t r = (size_t)y * g->w, a = r + x - 1, b = r + x;
    double za = g->depth[a], zb = g->depth[b];
    double dd = zb - za, z = za < zb ? za : zb;
    double f = g->foot0 + g->foot1 * z;
    if (!(fabs(dd) > JUMP_K * f)) return 0;
    if (!isfinite(dd)) return 1;
    if (x >= 2 && g->tri[a - 1] >= 0) {
        double dp = za - g->depth[a - 1];
        if (dp * dd > 0 && fabs(dp) * JUMP_M >= fabs(dd)) return 0;
    }
    if (x + 1 < g->w && g->tri[b + 1] >= 0) {
        double dn = g->depth[b + 1] - zb;
        if (dn * dd > 0 && fabs(dn) * JUMP_M >= fabs(dd)) return 0;
    }
    return 1;
}

size_t scn_spans(const scn_gbuf *g, scn_span **out)
{
    size_t n = 0, cap = 16;
    scn_span *s = malloc(cap * sizeof *s);   /* non-NULL even with no spans */
    *out = NULL;
    if (!s) return 0;
    for (int y = 0; y < g->h; y++) {
        size_t r = (size_t)y * g->w;
        int x = 0;
        while (x < g->w) {
            if (g->tri[r + x] < 0) { x++; continue; }
            int x0 = x++;
            while (x < g->w && joinable(g, r + x - 1, r + x) && !jump(g, y, x)) x++;
            if (n == cap) {
                size_t nc = 2 * cap;
                scn_span *ns = realloc(s, nc * sizeof *ns);
                if (!ns) { free(s); return 0; }
                s = ns;
                cap = nc;
            }
            s[n].y = y;
            s[n].x0 = x0;
            s[n].x1 = x;
            s[n].region = g->region[r + x0];
            n++;
        }
    }
    *out = s;
    return n;
}

void scn_span_at(const scn_gbuf *g, const scn_span *s, double x, double pos[3], double nrm[3])
{
    double lo = s->x0, hi = s->x1 - 1;
    if (!(x >= lo)) x = lo;                  /* NaN too */
    if (x > hi) x = hi;
    int i = (int)floor(x);
    double f = x - i;
    if (i >= s->x1 - 1) {                    /* the last pixel (or a 1-pixel span) */
        i = s->x1 - 1;
        f = 0;
    }
    size_t a = (size_t)s->y * g->w + i, b = f > 0 ? a + 1 : a;
    for (int e = 0; e < 3; e++) {
        pos[e] = (1 - f) * g->pos[a][e] + f * g->pos[b][e];
        nrm[e] = (1 - f) * g->nrm[a][e] + f * g->nrm[b][e];
    }
    double l = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (l > 1e-300 && isfinite(l)) {
        for (int e = 0; e < 3; e++) nrm[e] /= l;
        return;
    }
    /* Opposite normals cancelled (or a zero normal): the nearer pixel's,
     * else facing the viewer's side of the world, +z. */
    size_t c = f < 0.5 ? a : b;
    l = sqrt(g->nrm[c][0] * g->nrm[c][0] + g->nrm[c][1] * g->nrm[c][1] + g->nrm[c][2] * g->nrm[c][2]);
    if (l > 1e-300 && isfinite(l)) {
        for (int e = 0; e < 3; e++) nrm[e] = g->nrm[c][e] / l;
    } else {
        nrm[0] = nrm[1] = 0;
        nrm[2] = 1;
    }
}
