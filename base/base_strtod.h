/* base_strtod.h - decimal text to double, equal to strtod bit for bit, faster
 * for the numbers vector files hold.
 *
 * base_strtod(s, &end) gives exactly what strtod(s, &end) gives (value
 * and end pointer) in the "C" locale. The common case -- an optional sign,
 * at most 19 significant decimal digits, a decimal exponent q with
 * -342 <= q <= 27, followed by a space, tab, '|', newline or the end of
 * the string -- is converted by Clinger's fast path, or for negative q
 * an Eisel-Lemire product that proves its rounding (normal results);
 * else, for -108 <= q <= 27 (5^|q| in one word, or for q < -27 in a
 * few), exact integer arithmetic and one correctly rounded step; every
 * other input is handed to strtod itself.
 * tests/test_strtod.c and bench/bench_strtod.c compare the two.
 */
#ifndef BASE_STRTOD_H
#define BASE_STRTOD_H

#include <stdint.h>

double base_strtod(const char *s, char **end);

/* The same, reading digits eight at a time: for a string after whose
 * terminating NUL at least BASE_STRTOD_PAD more bytes may be read (a buffer
 * allocated that much longer; vectors/vec_file.c's). */
#define BASE_STRTOD_PAD 8
double base_strtod_padded(const char *s, char **end);

/* For tests: the same parse without the fast steps (every number in the
 * common case through the exact integer path), and the fast steps alone
 * on w 10^q: Clinger's (w <= 2^53, |q| <= 22) and for -342 <= q < 0 an
 * Eisel-Lemire product with a 128-bit 5^-q (normal results only); 1 and *out set when they
 * decide the correctly rounded double, 0 when the exact path must. */
double base_strtod_exact(const char *s, char **end);
int base_strtod_fast(uint64_t w, long q, int neg, double *out);
#endif
