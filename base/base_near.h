/* base_near.h - "did you mean": the nearest of a list of names to a word
 * a user mistyped, by edit distance (insertions, deletions,
 * substitutions and swaps of two neighbours, case ignored), close enough
 * to be a likely typo.
 */
#ifndef BASE_NEAR_H
#define BASE_NEAR_H
#include <stddef.h>

/* Edit distance of a and b (a swap of two neighbours one edit), case
 * ignored; 99 when either is longer than
 * 40 characters. */
int base_near_distance(const char *a, const char *b);
/* The name among names[0..n-1] (NULL entries skipped) nearest to word,
 * or NULL when none is close: at most 2 edits, or at most a third of the
 * word's length. The first of equally near names wins. */
const char *base_near(const char *word, const char *const *names, size_t n);
#endif
