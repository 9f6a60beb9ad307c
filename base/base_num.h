/* base_num.h - the one syntax of numbers the program reads, wherever it
 * reads them (options, unit parameters, scene files): decimal, the whole
 * text the number, no spaces, '+', hexadecimal, inf or nan.
 *   real:  [-]DIGITS[.DIGITS][(e|E)[+|-]DIGITS]   (".5" and "5." too)
 *   whole: [-]DIGITS
 * A '-' only where the caller allows negative values: "-0" is refused
 * where they are not (a value >= 0 is written without a sign).
 */
#ifndef BASE_NUM_H
#define BASE_NUM_H

/* Is s a real number in the syntax above (the sign allowed)? */
int base_num_is_real(const char *s);
/* s as a finite double: 0, or -1 (not the syntax, a '-' when neg_ok is
 * 0, or beyond the doubles: 1e999). An underflow (1e-999) is 0. */
int base_num_real(const char *s, int neg_ok, double *out);
/* s as a whole number: 0, or -1 (not [-]DIGITS, a '-' when neg_ok is 0,
 * or beyond long long). "1e1", "10.0" and "8e0" are not whole numbers. */
int base_num_whole(const char *s, int neg_ok, long long *out);
#endif
