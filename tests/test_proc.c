/* test_proc.c - base_proc: a command's exit status and folder; the time
 * limit and a signal end the command's whole process group (a grandchild
 * `sleep` included, whose pid the command writes down); after a signal the
 * caller can die by it; base_proc_rmtree removes a tree without following
 * its links. Everything runs in a scratch folder under /tmp.
 */
#include "tst.h"
#include "base/base_proc.h"
#include <errno.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char dir[128];

static base_proc job(double limit)
{
    base_proc p = { "test", "sh", dir, NULL, NULL, base_proc_now(), limit, 0, 0, 0 };
    return p;
}

/* The pid the command wrote to dir/pid (0: none yet). */
static pid_t read_pid(void)
{
    char path[256];
    long v = 0;
    snprintf(path, sizeof path, "%s/pid", dir);
    FILE *f = fopen(path, "r");
    if (f && fscanf(f, "%ld", &v) != 1) v = 0;
    if (f) fclose(f);
    return (pid_t)v;
}

static void nap_ms(long ms)
{
    struct timespec t = { ms / 1000, (ms % 1000) * 1000000L };
    nanosleep(&t, NULL);
}

/* 1 if pid is gone within a second: no such process, or a zombie (dead,
 * waiting for whoever inherited it to reap it). */
static int gone(pid_t pid)
{
    for (int i = 0; i < 100; i++) {
        if (kill(pid, 0) != 0 && errno == ESRCH) return 1;
        char path[64], st[256] = "";
        snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
        FILE *f = fopen(path, "r");
        if (f && fgets(st, sizeof st, f)) {
            const char *rp = strrchr(st, ')');
            if (rp && rp[1] == ' ' && (rp[2] == 'Z' || rp[2] == 'X')) { fclose(f); return 1; }
        }
        if (f) fclose(f);
        nap_ms(10);
    }
    return 0;
}

static void t_status(void)
{
    char err[200];
    base_proc p = job(0);
    TST_EQ_INT(base_proc_run("exit 3", &p, err, sizeof err), BASE_PROC_DONE);
    TST_EQ_INT(p.status, 3);
    p = job(0);
    TST_EQ_INT(base_proc_run("kill -9 $$", &p, err, sizeof err), BASE_PROC_DONE);
    TST_EQ_INT(p.status, 128 + 9);
    /* it runs in dir, with stdin from /dev/null */
    p = job(0);
    TST_EQ_INT(base_proc_run("pwd >where; cat >in", &p, err, sizeof err), BASE_PROC_DONE);
    TST_EQ_INT(p.status, 0);
    char path[256], line[256] = "";
    snprintf(path, sizeof path, "%s/where", dir);
    FILE *f = fopen(path, "r");
    TST_CHECK(f && fgets(line, sizeof line, f), "no pwd output");
    if (f) fclose(f);
    line[strcspn(line, "\n")] = 0;
    TST_EQ_STR(line, dir);
    struct stat st;
    snprintf(path, sizeof path, "%s/in", dir);
    TST_CHECK(stat(path, &st) == 0 && st.st_size == 0, "stdin was not empty");
}

static void t_timeout(void)
{
    char err[200];
    unlink("pid");
    base_proc p = job(0.5);
    double t0 = base_proc_now();
    int rc = base_proc_run("sleep 30 & echo $! >pid; wait", &p, err, sizeof err);
    double took = base_proc_now() - t0;
    TST_EQ_INT(rc, BASE_PROC_TIMEOUT);
    TST_CHECK(took >= 0.5 && took < 3.5, "took %.2f s", took);
    pid_t g = read_pid();
    TST_CHECK(g > 0 && gone(g), "the grandchild sleep %ld is still there", (long)g);
    TST_EQ_INT(base_proc_signal(), 0);
}

/* A child process runs the command; the parent sends it SIGTERM once the
 * grandchild's pid is written: base_proc_run returns SIGNAL, the child
 * checks what it was told and dies by the signal (base_proc_reraise). */
static void t_signal(void)
{
    char path[256];
    snprintf(path, sizeof path, "%s/pid", dir);
    unlink(path);
    pid_t c = fork();
    if (c == 0) {
        char err[200];
        base_proc p = job(0);
        int rc = base_proc_run("sleep 30 & echo $! >pid; wait", &p, err, sizeof err);
        if (rc == BASE_PROC_SIGNAL && p.signal == SIGTERM && base_proc_signal() == SIGTERM) base_proc_reraise(SIGTERM);
        _exit(1);
    }
    TST_CHECK(c > 0, "fork failed");
    if (c <= 0) return;
    pid_t g = 0;
    for (int i = 0; i < 500 && !(g = read_pid()); i++) nap_ms(10);
    TST_CHECK(g > 0, "the command never started");
    kill(c, SIGTERM);
    int st = 0;
    while (waitpid(c, &st, 0) < 0 && errno == EINTR) { }
    TST_CHECK(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM, "the caller ended with status %#x, not by SIGTERM", st);
    TST_CHECK(g > 0 && gone(g), "the grandchild sleep %ld is still there", (long)g);
}

static void t_rmtree(void)
{
    char top[256], p[300];
    snprintf(top, sizeof top, "%s/tree", dir);
    mkdir(top, 0700);
    snprintf(p, sizeof p, "%s/a", top); mkdir(p, 0700);
    snprintf(p, sizeof p, "%s/a/b", top); mkdir(p, 0700);
    snprintf(p, sizeof p, "%s/a/b/f", top);
    FILE *f = fopen(p, "w");
    if (f) { fputs("x\n", f); fclose(f); }
    /* a link to a file outside, and one to a folder outside: not followed */
    char outf[256], outd[256];
    snprintf(outf, sizeof outf, "%s/keep", dir);
    snprintf(outd, sizeof outd, "%s/keepdir", dir);
    f = fopen(outf, "w");
    if (f) fclose(f);
    mkdir(outd, 0700);
    snprintf(p, sizeof p, "%s/a/lf", top);
    TST_CHECK(symlink(outf, p) == 0, "symlink");
    snprintf(p, sizeof p, "%s/ld", top);
    TST_CHECK(symlink(outd, p) == 0, "symlink");
    TST_EQ_INT(base_proc_rmtree(top), 0);
    struct stat st;
    TST_CHECK(lstat(top, &st) != 0, "the tree is still there");
    TST_CHECK(stat(outf, &st) == 0 && stat(outd, &st) == 0, "a link's target went too");
    TST_CHECK(base_proc_rmtree(top) != 0, "a missing folder is not an error?");
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/shadesim-test-proc-%ld", (long)getpid());
    mkdir(dir, 0700);
    if (chdir(dir) != 0) return 1;
    TST_RUN(t_status);
    TST_RUN(t_timeout);
    TST_RUN(t_signal);
    TST_RUN(t_rmtree);
    tst_rmtree(dir);
    rmdir(dir);
    TST_EXIT();
}
