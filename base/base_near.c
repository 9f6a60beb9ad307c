/* base_near.c - the nearest name to a mistyped word (base_near.h). */
#include "base/base_near.h"
#include <ctype.h>
#include <string.h>

static int same(char x, char y) { return tolower((unsigned char)x) == tolower((unsigned char)y); }

/* The optimal string alignment distance: Levenshtein's three edits plus
 * the swap of two neighbours as one (the commonest typo: "widht" is one
 * edit from "width", two from "light", so the nearer name wins instead of
 * the first of a tie). Three rows of the table: two back for the swap. */
int base_near_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 40 || lb > 40) return 99;
    int r0[41], r1[41], r2[41];
    int *pp = r0, *p = r1, *c = r2;
    for (size_t j = 0; j <= lb; j++) p[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        c[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int v = p[j - 1] + !same(a[i - 1], b[j - 1]);
            if (p[j] + 1 < v) v = p[j] + 1;
            if (c[j - 1] + 1 < v) v = c[j - 1] + 1;
            if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]) && pp[j - 2] + 1 < v)
                v = pp[j - 2] + 1;
            c[j] = v;
        }
        int *t = pp; pp = p; p = c; c = t;
    }
    return p[lb];
}

const char *base_near(const char *word, const char *const *names, size_t n)
{
    const char *best = NULL;
    int bd = 99;
    for (size_t k = 0; k < n; k++) {
        if (!names[k]) continue;
        int d = base_near_distance(word, names[k]);
        if (d < bd) { bd = d; best = names[k]; }
    }
    /* A near name, but not one that shares almost nothing with the word. */
    if (best && (bd <= 2 || (size_t)bd * 3 <= strlen(word))) return best;
    return NULL;
}
