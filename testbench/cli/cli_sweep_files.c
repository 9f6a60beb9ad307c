/* cli_sweep_files.c - a sweep's output files as one set (cli_sweep.h). */
#include "testbench/cli/cli_sweep.h"
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

/* A sweep's files are written in full first, each to its own temporary
 * (base_out: removed if the process is interrupted), and only then moved
 * into DIR one after the other under a lock on DIR/.sweep.lock. So an
 * interrupted sweep changes nothing in DIR, and two sweeps into one folder
 * move their sets in turn: the folder ends up with the whole set of the
 * one that finished last (a file the other wrote and this one does not,
 * e.g. target.json, is removed under the same lock, if it is a regular
 * file). base_outset finishes every file (write errors of a device such
 * as a link to /dev/full included) before it moves any in. */
FILE *sweep_oset_open(oset *os, const char *name)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/%s", os->dir, name);
    if (!os->set && !(os->set = base_outset_new())) base_out_of_memory();
    FILE *f = base_outset_open(os->set, path, err, sizeof err);
    if (!f) { cli_usage_error("%s", err); return NULL; }
    os->n++;
    return f;
}

void sweep_oset_abort(oset *os)
{
    base_outset_abort(os->set);
    os->set = NULL;
    os->n = 0;
}

int sweep_oset_commit(oset *os, const char *const *gone, int ngone)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/.sweep.lock", os->dir);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) {
        sweep_oset_abort(os);
        return cli_usage_error("%s: cannot open: %s", path, strerror(errno));
    }
    struct flock lk;
    memset(&lk, 0, sizeof lk);
    lk.l_type = F_WRLCK;
    lk.l_whence = SEEK_SET;
    /* Where locks are not supported (ENOLCK) the set still moves in, only
     * without the guarantee against a concurrent sweep. */
    while (fcntl(fd, F_SETLKW, &lk) == -1 && errno == EINTR) {}
    int rc = 0;
    if (base_outset_commit(os->set, err, sizeof err)) rc = cli_usage_error("%s", err);
    os->set = NULL;
    os->n = 0;
    /* Files of an earlier sweep this one does not write: removed only
     * when they are regular files (a user's link or FIFO stays). */
    for (int k = 0; k < ngone && !rc; k++) {
        snprintf(path, sizeof path, "%s/%s", os->dir, gone[k]);
        base_out_remove_stale(path);
    }
    close(fd);                  /* releases the lock */
    return rc;
}
