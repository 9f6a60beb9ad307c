/* base_join.h - lists of names in a fixed buffer, for messages: "it has:
 * a, b, c", "it builds: x y t0". A list that does not fit is cut (the
 * message still goes out, a little shorter); it never overflows.
 */
#ifndef BASE_JOIN_H
#define BASE_JOIN_H
#include <stddef.h>

/* Append item to the list in buf (cap bytes, holding a string): sep first
 * unless buf is still empty. What does not fit is cut; buf stays a string
 * (cap 0: nothing is touched). 0, or -1 when something was cut. */
int base_join_add(char *buf, size_t cap, const char *sep, const char *item);
/* The same with the item made by printf(fmt, ...), e.g. "W=%d: %d". */
int base_join_addf(char *buf, size_t cap, const char *sep, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
#endif
