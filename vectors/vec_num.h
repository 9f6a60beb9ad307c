/* vec_num.h - decimal text to double, equal to strtod bit for bit, faster
 * for the numbers vector files hold.
 *
 * vec_num_strtod(s, &end) gives exactly what strtod(s, &end) gives (value
 * and end pointer) in the "C" locale. The common case -- an optional sign,
 * at most 19 significant decimal digits, a decimal exponent q with
 * -108 <= q <= 27 (5^|q| in one word, or for q < -27 in a few),
 * followed by a space, tab, '|', newline or the end of the string -- is
 * converted with exact integer arithmetic and one correctly rounded step;
 * every other input is handed to strtod itself.
 * tests/test_vec_num.c and bench/bench_vec_num.c compare the two.
 */
#ifndef VEC_NUM_H
#define VEC_NUM_H

double vec_num_strtod(const char *s, char **end);
#endif
