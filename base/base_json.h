/* base_json.h - the two JSON values every JSON writer of shadesim needs:
 * numbers and strings. (The writers lay out their own objects: each
 * output's shape is its own business, these two rules are common.)
 */
#ifndef BASE_JSON_H
#define BASE_JSON_H
#include <stdio.h>

/* v with `digits` significant digits (printf %.*g), or null when v is
 * inf or NaN (JSON has neither). 17 digits read back as the same double;
 * an output that promises fewer says so and passes its own count. */
void base_json_num(FILE *f, double v, int digits);
/* s as a JSON string: in quotes, " and \ escaped by a backslash, other
 * bytes below 0x20 as \u00XX; every other byte as it is (UTF-8 passes
 * through). NULL is written as "". */
void base_json_str(FILE *f, const char *s);
#endif
