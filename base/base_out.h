/* base_out.h - output files, written so that a reader never sees half of
 * one and nothing that is not ours is replaced.
 *
 *  - a new path, or an existing regular file: written to a temporary file
 *    beside it and renamed over it when complete (atomic replace);
 *  - a symbolic link: followed; its target is treated as above (the
 *    target is replaced, the link is kept);
 *  - an existing path that is not a regular file (character device such
 *    as /dev/null or /dev/full, FIFO, socket): written through, in place;
 *  - "-": standard output.
 * Every write error (ENOSPC from /dev/full included) is reported at
 * base_out_close. Temporaries are registered so that SIGINT, SIGTERM and
 * SIGHUP remove them before the process dies (base_out_install_signals).
 */
#ifndef BASE_OUT_H
#define BASE_OUT_H
#include <stdio.h>
#include <stddef.h>

typedef struct base_out base_out;

/* Open path for writing (binary). NULL with a message on failure. */
base_out *base_out_open(const char *path, char *err, size_t errlen);
/* The stream to write to. */
FILE    *base_out_file(base_out *o);
/* Flush, check every error, and make the file appear (rename). 0, or -1
 * with a message (the temporary is removed, an existing file is kept).
 * Frees o either way. */
int      base_out_close(base_out *o, char *err, size_t errlen);
/* Give up: remove the temporary (if any) and free o. */
void     base_out_abort(base_out *o);
/* The whole of buf to path, as open + write + close. 0 or -1. */
int      base_out_write_all(const char *path, const void *buf, size_t len, char *err, size_t errlen);
/* Make folder dir and its parents (mkdir -p; mode 0777 less the umask).
 * and check that a file can be created in it. 0, or -1 with "DIR: cannot
 * create folder P: why", "... is not a folder" or "cannot write in ...". */
int      base_out_mkdirs(const char *dir, char *err, size_t errlen);
/* Flush standard output and report a write error on it (EPIPE, ENOSPC):
 * 0, or -1 with a message. Every verb that prints results calls it last. */
int      base_out_stdout_check(char *err, size_t errlen);
/* Remove registered temporaries on SIGINT, SIGTERM, SIGHUP, then die by
 * the same signal. Called once by main. */
void     base_out_install_signals(void);
#endif
