/* base_proc.c - an external program run to its end, a time limit or a
 * signal (base_proc.h). The parent polls: waitpid without blocking, the
 * signal flag and the clock, ten times a second; a signal handler only
 * sets the flag, so everything else happens outside it. */
#define _XOPEN_SOURCE 700          /* nftw */
#include "base/base_proc.h"
#include <ftw.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static volatile sig_atomic_t got_signal;
static int last_signal;         /* what stopped the last run (base_proc_signal) */
static int holding;             /* between base_proc_hold and base_proc_release */

static void on_signal(int sig) { if (!got_signal) got_signal = sig; }

static const int caught[] = { SIGINT, SIGTERM, SIGHUP };
#define NCAUGHT (sizeof caught / sizeof caught[0])
static struct sigaction held_old[NCAUGHT];      /* the handlers base_proc_release restores */

double base_proc_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void nap(long ms)
{
    struct timespec t = { ms / 1000, (ms % 1000) * 1000000L };
    nanosleep(&t, NULL);        /* a signal cuts it short: fine, we poll */
}

/* The group gone: SIGTERM, up to two seconds for it to end, then SIGKILL;
 * the child reaped. */
static void end_group(pid_t pid)
{
    kill(-pid, SIGTERM);
    for (int i = 0; i < 20; i++) {
        if (waitpid(pid, NULL, WNOHANG) == pid) { kill(-pid, SIGKILL); return; }
        nap(100);
    }
    kill(-pid, SIGKILL);
    while (waitpid(pid, NULL, 0) < 0 && errno == EINTR) { }
}

static void progress(const base_proc *p, double now, int *shown)
{
    char detail[120] = "";
    if (p->detail) p->detail(p->ctx, detail, sizeof detail);
    fprintf(stderr, "\r\033[K%s: %s%s%s%s, %.0f s", p->verb, p->step, detail[0] ? " (" : "", detail,
            detail[0] ? ")" : "", now - p->start);
    if (p->limit_s > 0) fprintf(stderr, " of at most %.0f", p->limit_s);
    fflush(stderr);
    *shown = 1;
}

int base_proc_run(const char *cmd, base_proc *p, char *err, size_t errlen)
{
    struct sigaction sa, old[NCAUGHT];
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (holding && got_signal) {        /* recorded while held: no tool starts */
        p->signal = last_signal = got_signal;
        return BASE_PROC_SIGNAL;
    }
    if (!holding) got_signal = 0;
    for (size_t i = 0; i < NCAUGHT; i++) {
        sigaction(caught[i], NULL, &old[i]);
        /* a signal ignored by whoever started us (nohup) stays ignored */
        if (old[i].sa_handler != SIG_IGN) sigaction(caught[i], &sa, NULL);
    }
    fflush(NULL);               /* nothing buffered written twice by the child */
    pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        for (size_t i = 0; i < NCAUGHT; i++) sigaction(caught[i], &old[i], NULL);
        int fd = open("/dev/null", O_RDONLY);
        if (fd >= 0) { dup2(fd, 0); close(fd); }
        if (p->dir && chdir(p->dir) != 0) _exit(127);
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    int rc = BASE_PROC_DONE, shown = 0;
    if (pid < 0) {
        snprintf(err, errlen, "%s: cannot start %s: %s", p->verb, p->step, strerror(errno));
        rc = BASE_PROC_ERROR;
    } else {
        setpgid(pid, pid);      /* also here: no window where the group is not yet its own */
        double last = 0;
        for (;;) {
            int st;
            pid_t w = waitpid(pid, &st, WNOHANG);
            if (w == pid) {
                p->status = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : 1;
                break;
            }
            if (w < 0 && errno != EINTR) { p->status = 1; break; }
            double now = base_proc_now();
            if (got_signal) { p->signal = last_signal = got_signal; end_group(pid); rc = BASE_PROC_SIGNAL; break; }
            if (p->limit_s > 0 && now - p->start >= p->limit_s) { end_group(pid); rc = BASE_PROC_TIMEOUT; break; }
            if (p->progress && now - last >= 1.0) { progress(p, now, &shown); last = now; }
            nap(100);
        }
    }
    if (shown) { fputs("\r\033[K", stderr); fflush(stderr); }
    for (size_t i = 0; i < NCAUGHT; i++) sigaction(caught[i], &old[i], NULL);
    return rc;
}

int base_proc_signal(void) { return last_signal ? last_signal : holding ? got_signal : 0; }

void base_proc_hold(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    got_signal = 0;
    last_signal = 0;
    for (size_t i = 0; i < NCAUGHT; i++) {
        sigaction(caught[i], NULL, &held_old[i]);
        if (held_old[i].sa_handler != SIG_IGN) sigaction(caught[i], &sa, NULL);
    }
    holding = 1;
}

void base_proc_release(void)
{
    if (!holding) return;
    for (size_t i = 0; i < NCAUGHT; i++) sigaction(caught[i], &held_old[i], NULL);
    holding = 0;
    if (got_signal && !last_signal) last_signal = got_signal;
}

_Noreturn void base_proc_reraise(int sig)
{
    raise(sig);                 /* base_out's handler: temporaries removed, death by sig */
    signal(sig, SIG_DFL);       /* a handler that returned: die all the same */
    raise(sig);
    _exit(128 + sig);
}

static int rm_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st; (void)ftw;
    return (flag == FTW_DP ? rmdir(path) : unlink(path)) != 0;
}

int base_proc_rmtree(const char *dir)
{
    return nftw(dir, rm_one, 16, FTW_DEPTH | FTW_PHYS) == 0 ? 0 : -1;
}
