/* base_out.h - output files, written so that a reader never sees half of
 * one and nothing that is not ours is replaced.
 *
 *  - a new path, or an existing regular file: written to a temporary file
 *    beside it and renamed over it when complete (atomic replace);
 *  - a symbolic link: written through, never replaced: the link is kept
 *    and so is the file it names (its inode), which gets the bytes once
 *    the output is complete (a link to a device or FIFO: written through
 *    as below, at once);
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
/* Make folder dir and its parents (mkdir -p; mode 0777 less the umask)
 * and check that a file can be created in it; the folders made while a
 * set is current are removed by its abort (when empty). 0, or -1 with "DIR: cannot
 * create folder P: why", "... is not a folder" or "cannot write in ...". */
int      base_out_mkdirs(const char *dir, char *err, size_t errlen);
/* Flush standard output and report a write error on it (EPIPE, ENOSPC):
 * 0, or -1 with a message. Every verb that prints results calls it last. */
int      base_out_stdout_check(char *err, size_t errlen);
/* A set of outputs that appear together: each opened as base_out_open
 * does, written, and at base_outset_commit finished (flushed, synced,
 * closed, write errors of written-through devices seen) before any of them
 * is moved in; a failure up to that point leaves every path of the set as
 * it was (a device or FIFO member has had its bytes, as always). The
 * commit and the abort free the set. base_outset_open's stream belongs to
 * the set (do not close it). */
typedef struct base_outset base_outset;
base_outset *base_outset_new(void);
/* NULL with a message (also for a NULL set: out of memory). */
FILE    *base_outset_open(base_outset *s, const char *path, char *err, size_t errlen);
/* buf as the whole of a member; 0, or -1 with a message. A write error
 * is reported by the commit. */
int      base_outset_write(base_outset *s, const char *path, const void *buf, size_t len, char *err, size_t errlen);
/* 0, or -1 with the first failure's message (nothing moved in then,
 * unless a rename failed after others had succeeded). */
int      base_outset_commit(base_outset *s, char *err, size_t errlen);
void     base_outset_abort(base_outset *s);
/* A set made current in this thread, for a verb whose files are written
 * by many functions: until its commit or abort, every output closed in
 * this thread (base_out_close, base_out_write_all, and the commit of a
 * set inside it) is finished and joins it instead of appearing. Sets
 * nest. NULL: out of memory. */
base_outset *base_outset_begin(void);
/* Where path's bytes are while it waits in a current set (its
 * temporary), else path: for a verb that reads back what it wrote. */
const char *base_out_pending(const char *path);
/* Remove a file an earlier run left (an optional output this run does not
 * write), only if it is a regular file: a link, FIFO or device of that
 * name is the user's and stays. 0 (also when absent), or -1. */
int      base_out_remove_stale(const char *path);
/* Remove registered temporaries on SIGINT, SIGTERM, SIGHUP, then die by
 * the same signal; catch SIGPIPE so that a closed pipe is the write error
 * EPIPE (reported, exit status 2). Called once by main. */
void     base_out_install_signals(void);

/* Out of memory: the one policy for every layer that can include base/
 * (sim/ stands alone and does the same in sim_kernel.c). One line
 * "shadesim: out of memory" on stderr, the registered temporaries of
 * unfinished outputs removed (as on a signal, so no output appears half
 * written), and exit status BASE_EXIT_OOM at once, without flushing
 * stdout's buffer: a result cut short is not printed as if it were whole.
 * docs/cli.md, "Exit status". */
#define BASE_EXIT_OOM 3
_Noreturn void base_out_of_memory(void);
#endif
