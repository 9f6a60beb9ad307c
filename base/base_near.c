/* base_near.c - the nearest name to a mistyped word (base_near.h). */
#include "base/base_near.h"
#include <ctype.h>
#include <string.h>

int base_near_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 40 || lb > 40) return 99;
    int row[41];
    for (size_t j = 0; j <= lb; j++) row[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int up = row[j];
            int sub = diag + (tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]));
            int best = up + 1 < row[j - 1] + 1 ? up + 1 : row[j - 1] + 1;
            row[j] = sub < best ? sub : best;
            diag = up;
        }
    }
    return row[lb];
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
