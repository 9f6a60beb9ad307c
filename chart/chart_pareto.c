/* chart_pareto.c - Pareto fronts over two and three costs (chart.h). */
#include "chart/chart.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct { double x, y; size_t i; } chart_pp;

static int chart_pp_cmp(const void *pa, const void *pb)
{
    const chart_pp *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);   /* qsort is not stable */
}

size_t chart_pareto(const double *x, const double *y, size_t n, unsigned char *on_front)
{
    if (!on_front || n == 0) return 0;
    memset(on_front, 0, n);
    if (!x || !y) return 0;

    size_t count = 0;
    chart_pp *p = n <= SIZE_MAX / sizeof *p ? malloc(n * sizeof *p) : NULL;
    if (!p) {
        /* No memory for the sort: the quadratic definition still works. */
        for (size_t i = 0; i < n; i++) {
            if (isnan(x[i]) || isnan(y[i])) continue;
            int dom = 0;
            for (size_t j = 0; j < n && !dom; j++)
                dom = x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i]);
            on_front[i] = !dom;
            count += !dom;
        }
        return count;
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (!isnan(x[i]) && !isnan(y[i])) { p[m].x = x[i]; p[m].y = y[i]; p[m].i = i; m++; }
    qsort(p, m, sizeof *p, chart_pp_cmp);

    /* Sweep by increasing x. A group of equal x is sorted by y, so only its
     * smallest y (and exact copies of it) can be on the front, and only if
     * it beats every point of strictly smaller x: equal y there would be
     * dominated by the smaller x. */
    double best = 0;
    int have_best = 0;
    for (size_t g = 0; g < m;) {
        size_t h = g;
        while (h < m && p[h].x == p[g].x) h++;
        double ymin = p[g].y;
        int front = !have_best || ymin < best;
        for (size_t k = g; k < h; k++) {
            unsigned char on = front && p[k].y == ymin;
            on_front[p[k].i] = on;
            count += on;
        }
        if (front) { best = ymin; have_best = 1; }
        g = h;
    }
    free(p);
    return count;
}

typedef struct { double v[3]; size_t i; } chart_p3;

static int chart_p3_cmp(const void *pa, const void *pb)
{
    const chart_p3 *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

/* b dominates a: no worse in every coordinate, better in one. */
static int chart_dom3(const double *b, const double *a)
{
    return b[0] <= a[0] && b[1] <= a[1] && b[2] <= a[2] && (b[0] < a[0] || b[1] < a[1] || b[2] < a[2]);
}

size_t chart_pareto3(const double *x, const double *y, const double *z, size_t n, unsigned char *on_front)
{
    if (!on_front || n == 0) return 0;
    memset(on_front, 0, n);
    if (!x || !y || !z) return 0;
    chart_p3 *p = n <= SIZE_MAX / sizeof *p ? malloc(n * sizeof *p) : NULL;
    size_t *front = n <= SIZE_MAX / sizeof *front ? malloc(n * sizeof *front) : NULL;
    size_t m = 0, nf = 0;
    if (!p || !front) {
        free(p);
        free(front);
        /* No memory for the sort: the quadratic definition. */
        for (size_t i = 0; i < n; i++) {
            double a[3] = { x[i], y[i], z[i] };
            if (isnan(a[0]) || isnan(a[1]) || isnan(a[2])) continue;
            int dom = 0;
            for (size_t j = 0; j < n && !dom; j++) {
                double b[3] = { x[j], y[j], z[j] };
                dom = chart_dom3(b, a);
            }
            on_front[i] = !dom;
            nf += !dom;
        }
        return nf;
    }
    for (size_t i = 0; i < n; i++)
        if (!isnan(x[i]) && !isnan(y[i]) && !isnan(z[i])) {
            p[m].v[0] = x[i]; p[m].v[1] = y[i]; p[m].v[2] = z[i]; p[m].i = i; m++;
        }
    qsort(p, m, sizeof *p, chart_p3_cmp);
    /* In lexicographic order a point's dominators all come before it, and
     * dominance is transitive, so some dominator is on the front: checking
     * against the front found so far is enough. */
    for (size_t k = 0; k < m; k++) {
        int dom = 0;
        for (size_t j = 0; j < nf && !dom; j++) dom = chart_dom3(p[front[j]].v, p[k].v);
        if (!dom) { front[nf++] = k; on_front[p[k].i] = 1; }
    }
    free(p);
    free(front);
    return nf;
}
