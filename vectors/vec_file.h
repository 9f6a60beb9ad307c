/* vec_file.h - golden vector files in the text format of docs/vectors.md:
 *
 *     # shadesim vectors 1
 *     # unit: horner3
 *     # inputs: a b c d t
 *     # outputs: y
 *     0.125 -0.5 0.25 0.75 0.5 | 0.765625
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

/* The same file a block at a time (a few MB of text), for readers whose
 * memory must not grow with the file: open, then vec_stream_next until it
 * returns 0 (end) or -1 (the message, "PATH:LINE: what" exactly as
 * vec_file_read gives it, in vec_stream_error). Each call replaces *rows'
 * rows with the next ones (at least one); *rows also carries the header
 * (unit, port names) once the first call has returned 1. open: NULL with
 * "PATH: cannot open: why" in err. */
typedef struct vec_stream vec_stream;
vec_stream *vec_stream_open(const char *path, const vec_set *expect, char *err, size_t errlen);
int         vec_stream_next(vec_stream *v, const vec_set **rows);
/* The next vec_stream_next gives the same rows again (a caller that
 * looked at the header and first rows hands the stream on untouched). */
void        vec_stream_unread(vec_stream *v);
const char *vec_stream_error(const vec_stream *v);
/* vec_stream_next's rows appended to *dst (its n_in and n_out the
 * stream's) instead: the block parsed straight into dst, not into the
 * stream's set and copied (rows held by vec_stream_unread, or generated,
 * are copied). 1, 0 at the end, -1 with the message; on -1 dst keeps the
 * rows it had. The rows vec_stream_next gave last stay as they are, so
 * that a caller can go on using them while it appends the next. */
int         vec_stream_append(vec_stream *v, vec_set *dst);
/* 1 when the file's end has been read: the rows vec_stream_next gave last
 * are the file's last (the next call returns 0). A generated stream
 * (vec_stream_gen) knows its end only once vec_stream_next returned 0. */
int         vec_stream_done(const vec_stream *v);
/* Parse a block on up to n threads (default: 2 where there are 2 cores). */
void        vec_stream_threads(vec_stream *v, int n);
/* ... on p's threads (base_pool.h), kept by the caller, instead of a
 * thread made for each block (NULL: that). */
struct base_pool;
void        vec_stream_pool(vec_stream *v, struct base_pool *p);
void        vec_stream_close(vec_stream *v);
/* The rows a reference model generates (m->gen(p, n, seed), the same rows
 * in the same order as into a vec_set), as a stream: generated on a
 * thread of their own a block at a time, memory a few blocks whatever n
 * is. NULL with the message when the model's ports are not expect's. */
vec_stream *vec_stream_gen(const vec_model *m, const vec_params *p, size_t n, uint64_t seed, const vec_set *expect,
                           char *err, size_t errlen);
#endif
