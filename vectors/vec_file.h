/* vec_file.h - golden vector files in the SPEC's text format:
 *
 *     # shadesim vectors 1
 *     # unit: horner3
 *     # inputs: a b c d t
 *     # outputs: y
 *     0.125 -0.5 0.25 0.75 0.5 | 0.78125
 *
 * Numbers are written with %.17g so that they read back exactly.
 */
#ifndef VEC_FILE_H
#define VEC_FILE_H
#include <stdio.h>
#include "vectors/vectors.h"

/* Write s to path (atomically: temporary name, then rename). 0, or -1 with
 * a one-line message "PATH: what" in err. */
int vec_file_write(const char *path, const vec_set *s, char *err, size_t errlen);
/* Write s to an open stream (e.g. stdout). */
int vec_file_print(FILE *f, const vec_set *s);
/* Read path ("-" for stdin) into s. When expect is given, the file's unit,
 * inputs and outputs must match it. 0, or -1 with "PATH:LINE: what" in err
 * (wrong column count, non-numeric, NaN/inf, empty file, another unit's
 * file, binary junk, missing header). */
int vec_file_read(const char *path, vec_set *s, const vec_set *expect,
                  char *err, size_t errlen);
#endif
