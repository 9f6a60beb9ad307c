/* test_out.c - base_out: output files replaced atomically, devices, FIFOs
 * and stdout written through, symlinks kept, errors reported, temporaries
 * removed on abort and on SIGINT/SIGTERM/SIGHUP.
 *
 * Everything happens in a scratch folder under /tmp; device nodes are the
 * system's /dev/null and /dev/full, only ever opened, and checked to still
 * be character devices afterwards. The process umask is set to 027 before
 * the first base_out call so that "respects the umask" is distinguishable
 * from a hard-coded 0644.
 */
#include "tst.h"
#include "base/base_out.h"
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define UMASK 027

static char dir[128];

static void path_in(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/%s", dir, name);
}

/* The whole file into buf (NUL-terminated); its length, or -1. */
static long slurp(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    size_t n = fread(buf, 1, cap - 1, f);
    fclose(f);
    buf[n] = 0;
    return (long)n;
}

static void put(const char *path, const char *text, mode_t mode)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, mode);
    if (fd < 0) return;
    if (write(fd, text, strlen(text)) < 0) { /* checked by the reader */ }
    fchmod(fd, mode);
    close(fd);
}

/* Entries of the scratch folder other than "." and ".." (temporaries are
 * hidden names, so count everything). */
static int entries(void)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    if (d) closedir(d);
    return n;
}

/* 1 if the folder holds a name containing ".tmp-". */
static int has_temp(void)
{
    DIR *d = opendir(dir);
    int found = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (strstr(e->d_name, ".tmp-")) found = 1;
    if (d) closedir(d);
    return found;
}

static void t_new_path(void)
{
    tst_rmtree(dir);
    char p[400], buf[256], err[300];
    path_in(p, sizeof p, "new.txt");
    const char *text = "one\ntwo\n";
    TST_EQ_INT(base_out_write_all(p, text, strlen(text), err, sizeof err), 0);
    TST_EQ_INT(slurp(p, buf, sizeof buf), (long)strlen(text));
    TST_EQ_STR(buf, text);
    struct stat st;
    TST_CHECK(stat(p, &st) == 0 && S_ISREG(st.st_mode), "a regular file");
    TST_EQ_INT(st.st_mode & 0777, 0666 & ~UMASK);
    TST_EQ_INT(entries(), 1);
}

static void t_replace_regular(void)
{
    tst_rmtree(dir);
    char p[400], buf[256], err[300];
    path_in(p, sizeof p, "r.csv");
    put(p, "old contents\n", 0600);
    base_out *o = base_out_open(p, err, sizeof err);
    TST_CHECK(o != NULL, "%s", err);
    if (!o) return;
    fputs("new", base_out_file(o));
    fflush(base_out_file(o));
    /* Until close, readers see the old file; the new one is a temporary. */
    TST_EQ_INT(slurp(p, buf, sizeof buf), 13);
    TST_EQ_STR(buf, "old contents\n");
    TST_CHECK(has_temp(), "a temporary beside the file while writing");
    TST_EQ_INT(base_out_close(o, err, sizeof err), 0);
    TST_EQ_INT(slurp(p, buf, sizeof buf), 3);
    TST_EQ_STR(buf, "new");
    struct stat st;
    TST_CHECK(stat(p, &st) == 0, "stat");
    TST_EQ_INT(st.st_mode & 0777, 0600);       /* the replaced file's mode kept */
    TST_EQ_INT(entries(), 1);

    /* Abort: the old file stays, nothing else. */
    o = base_out_open(p, err, sizeof err);
    TST_CHECK(o != NULL, "%s", err);
    if (!o) return;
    fputs("half", base_out_file(o));
    base_out_abort(o);
    TST_EQ_INT(slurp(p, buf, sizeof buf), 3);
    TST_EQ_STR(buf, "new");
    TST_EQ_INT(entries(), 1);
}

static void t_symlink(void)
{
    tst_rmtree(dir);
    char sub[400], tgt[400], lnk[400], dang[400], buf[256], err[300];
    path_in(sub, sizeof sub, "sub");
    mkdir(sub, 0777);
    path_in(tgt, sizeof tgt, "sub/target.csv");
    path_in(lnk, sizeof lnk, "link.csv");
    put(tgt, "target before\n", 0644);
    /* Relative link: resolved against the link's folder, not the cwd. */
    TST_CHECK(symlink("sub/target.csv", lnk) == 0, "symlink: %s", strerror(errno));
    TST_EQ_INT(base_out_write_all(lnk, "via link\n", 9, err, sizeof err), 0);
    struct stat st;
    TST_CHECK(lstat(lnk, &st) == 0 && S_ISLNK(st.st_mode), "the link is still a link");
    TST_EQ_INT(slurp(tgt, buf, sizeof buf), 9);
    TST_EQ_STR(buf, "via link\n");
    TST_CHECK(lstat(tgt, &st) == 0 && S_ISREG(st.st_mode), "the target a regular file");
    /* A dangling link: the file appears where the link points. */
    path_in(dang, sizeof dang, "dangling.csv");
    TST_CHECK(symlink("sub/later.csv", dang) == 0, "symlink");
    TST_EQ_INT(base_out_write_all(dang, "x", 1, err, sizeof err), 0);
    TST_CHECK(lstat(dang, &st) == 0 && S_ISLNK(st.st_mode), "the dangling link is still a link");
    path_in(tgt, sizeof tgt, "sub/later.csv");
    TST_EQ_INT(slurp(tgt, buf, sizeof buf), 1);
    /* A loop is an error, not a hang. */
    char a[400], b[400];
    path_in(a, sizeof a, "la");
    path_in(b, sizeof b, "lb");
    TST_CHECK(symlink("lb", a) == 0 && symlink("la", b) == 0, "symlinks");
    TST_EQ_INT(base_out_write_all(a, "x", 1, err, sizeof err), -1);
    TST_CHECK(strstr(err, "symbolic links") != NULL, "err = %s", err);
    TST_CHECK(!has_temp(), "no temporary left");
}

/* A character device is written through: after the write it must be the
 * same device node (root would otherwise have replaced /dev/null). */
static void t_devnull(void)
{
    struct stat before, after;
    if (stat("/dev/null", &before) || !S_ISCHR(before.st_mode)) TST_SKIP("/dev/null is not a character device here");
    char err[300];
    static char big[1 << 17];
    memset(big, 'v', sizeof big);
    TST_EQ_INT(base_out_write_all("/dev/null", big, sizeof big, err, sizeof err), 0);
    TST_CHECK(stat("/dev/null", &after) == 0 && S_ISCHR(after.st_mode), "still a character device");
    TST_EQ_INT(after.st_rdev, before.st_rdev);
    TST_EQ_INT(after.st_ino, before.st_ino);
}

/* /dev/full: every write fails with ENOSPC; close must say so. */
static void t_devfull(void)
{
    struct stat st;
    if (stat("/dev/full", &st) || !S_ISCHR(st.st_mode)) TST_SKIP("/dev/full not available");
    char err[300] = "";
    /* Small (stays in the buffer until close) and large (fails in fwrite). */
    TST_EQ_INT(base_out_write_all("/dev/full", "abc", 3, err, sizeof err), -1);
    TST_CHECK(strstr(err, strerror(ENOSPC)) != NULL, "err = %s", err);
    static char big[1 << 17];
    memset(big, 'f', sizeof big);
    err[0] = 0;
    TST_EQ_INT(base_out_write_all("/dev/full", big, sizeof big, err, sizeof err), -1);
    TST_CHECK(strstr(err, strerror(ENOSPC)) != NULL, "err = %s", err);
    TST_CHECK(stat("/dev/full", &st) == 0 && S_ISCHR(st.st_mode), "still a character device");
    /* Through a stream the caller writes with fprintf. */
    base_out *o = base_out_open("/dev/full", err, sizeof err);
    TST_CHECK(o != NULL, "%s", err);
    if (!o) return;
    for (int i = 0; i < 10000; i++) fprintf(base_out_file(o), "line %d\n", i);
    TST_EQ_INT(base_out_close(o, err, sizeof err), -1);
    TST_CHECK(strstr(err, strerror(ENOSPC)) != NULL, "err = %s", err);
}

static void t_fifo(void)
{
    tst_rmtree(dir);
    char p[400], err[300];
    path_in(p, sizeof p, "pipe");
    if (mkfifo(p, 0666)) TST_SKIP("mkfifo: %s", strerror(errno));
    /* The reader: a child that counts the bytes and checks each one. */
    size_t n = 200000;
    pid_t pid = fork();
    if (pid == 0) {
        FILE *f = fopen(p, "rb");
        if (!f) _exit(3);
        size_t got = 0, bad = 0;
        int c;
        while ((c = getc(f)) != EOF) { if (c != 'a' + (int)(got % 26)) bad++; got++; }
        fclose(f);
        _exit(got == n && !bad ? 0 : 1);
    }
    TST_CHECK(pid > 0, "fork");
    if (pid < 0) return;
    char *buf = malloc(n);
    for (size_t i = 0; i < n; i++) buf[i] = (char)('a' + i % 26);
    TST_EQ_INT(base_out_write_all(p, buf, n, err, sizeof err), 0);
    free(buf);
    int status = 0;
    waitpid(pid, &status, 0);
    TST_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the reader got every byte (status %d)", status);
    struct stat st;
    TST_CHECK(lstat(p, &st) == 0 && S_ISFIFO(st.st_mode), "still a FIFO");
    TST_EQ_INT(entries(), 1);
}

/* The rename fails (a folder took the name meanwhile): error, the
 * temporary removed, the folder untouched. */
static void t_rename_fails(void)
{
    tst_rmtree(dir);
    char p[400], err[300] = "";
    path_in(p, sizeof p, "late");
    base_out *o = base_out_open(p, err, sizeof err);
    TST_CHECK(o != NULL, "%s", err);
    if (!o) return;
    fputs("data", base_out_file(o));
    TST_CHECK(mkdir(p, 0777) == 0, "mkdir");
    TST_EQ_INT(base_out_close(o, err, sizeof err), -1);
    TST_CHECK(strstr(err, "rename") != NULL, "err = %s", err);
    struct stat st;
    TST_CHECK(stat(p, &st) == 0 && S_ISDIR(st.st_mode), "the folder is still there");
    TST_EQ_INT(entries(), 1);
}

/* A regular file that cannot grow (RLIMIT_FSIZE stands in for a full
 * disk): close fails with the cause, the old file is kept, no temporary
 * is left. In a child, so that the limit stays there. */
static void t_file_too_big(void)
{
    tst_rmtree(dir);
    char p[400];
    path_in(p, sizeof p, "limited.csv");
    put(p, "old\n", 0644);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = { 4096, 4096 };
        if (setrlimit(RLIMIT_FSIZE, &rl)) _exit(3);
        static char big[1 << 16];
        memset(big, 'b', sizeof big);
        char err[300] = "";
        if (base_out_write_all(p, big, sizeof big, err, sizeof err) != -1) _exit(4);
        if (!strstr(err, strerror(EFBIG))) _exit(5);
        _exit(0);
    }
    TST_CHECK(pid > 0, "fork");
    if (pid <= 0) return;
    int status = 0;
    waitpid(pid, &status, 0);
    TST_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "child status %d", WEXITSTATUS(status));
    char buf[64];
    TST_EQ_INT(slurp(p, buf, sizeof buf), 4);
    TST_EQ_STR(buf, "old\n");
    TST_EQ_INT(entries(), 1);
}

static void t_bad_paths(void)
{
    tst_rmtree(dir);
    char err[300] = "", p[400];
    TST_CHECK(base_out_open("", err, sizeof err) == NULL, "empty path refused");
    TST_CHECK(strstr(err, "empty") != NULL, "err = %s", err);
    TST_CHECK(base_out_open(dir, err, sizeof err) == NULL, "a folder refused");
    path_in(p, sizeof p, "no/such/folder/x.csv");
    TST_CHECK(base_out_open(p, err, sizeof err) == NULL, "missing folder refused");
    TST_CHECK(strstr(err, strerror(ENOENT)) != NULL, "err = %s", err);
    /* Raw bytes of a path are escaped in the message. */
    path_in(p, sizeof p, "no/\x01\xff/x");
    TST_CHECK(base_out_open(p, err, sizeof err) == NULL, "refused");
    TST_CHECK(strstr(err, "\\x01\\xff") != NULL && !strchr(err, '\x01'), "err = %s", err);
    /* A name near NAME_MAX: the temporary's name must still fit. */
    char name[256];
    memset(name, 'n', 250);
    name[250] = 0;
    path_in(p, sizeof p, name);
    TST_EQ_INT(base_out_write_all(p, "long", 4, err, sizeof err), 0);
    TST_EQ_INT(entries(), 1);
}

/* Standard output, in a child whose stdout is a file, then /dev/full. */
static void t_stdout(void)
{
    tst_rmtree(dir);
    char p[400];
    path_in(p, sizeof p, "stdout.txt");
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        int fd = open(p, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0 || dup2(fd, 1) < 0) _exit(3);
        char err[300];
        base_out *o = base_out_open("-", err, sizeof err);
        if (!o || base_out_file(o) != stdout) _exit(4);
        fputs("first ", base_out_file(o));
        if (base_out_close(o, err, sizeof err)) _exit(5);
        /* stdout is still open after close. */
        if (fputs("second\n", stdout) < 0 || base_out_stdout_check(err, sizeof err)) _exit(6);
        int full = open("/dev/full", O_WRONLY);
        if (full < 0) _exit(0);         /* the first half was checked */
        fflush(stdout);
        dup2(full, 1);
        printf("lost");
        if (base_out_stdout_check(err, sizeof err) != -1 || !strstr(err, strerror(ENOSPC))) _exit(7);
        o = base_out_open("-", err, sizeof err);
        if (!o) _exit(8);
        fputs("lost too", base_out_file(o));
        if (base_out_close(o, err, sizeof err) != -1) _exit(9);
        _exit(0);
    }
    TST_CHECK(pid > 0, "fork");
    if (pid <= 0) return;
    int status = 0;
    waitpid(pid, &status, 0);
    TST_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "child status %d", WEXITSTATUS(status));
    char buf[64];
    TST_EQ_INT(slurp(p, buf, sizeof buf), 13);
    TST_EQ_STR(buf, "first second\n");
}

/* A child opens a file, writes, confirms its temporary exists (through a
 * pipe), then dies by sig: nothing may be left in the folder. */
static void killed_child(int sig)
{
    tst_rmtree(dir);
    int fds[2];
    TST_CHECK(pipe(fds) == 0, "pipe");
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        base_out_install_signals();
        char p[400], err[300];
        path_in(p, sizeof p, "big.vcd");
        base_out *o = base_out_open(p, err, sizeof err);
        if (!o) _exit(3);
        for (int i = 0; i < 100000; i++) fprintf(base_out_file(o), "#%d\n", i);
        fflush(base_out_file(o));
        char seen = has_temp() ? '1' : '0';
        if (write(fds[1], &seen, 1) != 1) _exit(4);
        raise(sig);
        _exit(5);                       /* not reached: the signal kills */
    }
    TST_CHECK(pid > 0, "fork");
    if (pid <= 0) return;
    close(fds[1]);
    char seen = 0;
    TST_CHECK(read(fds[0], &seen, 1) == 1 && seen == '1', "the child had a temporary (%c)", seen);
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    TST_CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sig, "died by signal %d (status %#x)", sig, status);
    TST_EQ_INT(entries(), 0);
}

static void t_sigterm(void) { killed_child(SIGTERM); }
static void t_sigint(void)  { killed_child(SIGINT); }
static void t_sighup(void)  { killed_child(SIGHUP); }

/* A signal from outside (kill with the child's pid) while it writes. */
static void t_kill_from_outside(void)
{
    tst_rmtree(dir);
    int fds[2];
    TST_CHECK(pipe(fds) == 0, "pipe");
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        base_out_install_signals();
        char p[400], err[300];
        path_in(p, sizeof p, "endless.csv");
        base_out *o = base_out_open(p, err, sizeof err);
        if (!o) _exit(3);
        if (write(fds[1], "g", 1) != 1) _exit(4);
        for (unsigned long i = 0;; i++) {
            fprintf(base_out_file(o), "%lu\n", i);
            if (i % 100000 == 0) { base_out_abort(o); if (!(o = base_out_open(p, err, sizeof err))) _exit(6); }
        }
    }
    TST_CHECK(pid > 0, "fork");
    if (pid <= 0) return;
    close(fds[1]);
    char go;
    TST_CHECK(read(fds[0], &go, 1) == 1, "child started");
    close(fds[0]);
    struct timespec ts = { 0, 50000000 };   /* let it write a while */
    nanosleep(&ts, NULL);
    kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    TST_CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM, "status %#x", status);
    TST_EQ_INT(entries(), 0);
}

/* Sweeps write from several threads at once. */
typedef struct { int k; int rc; } job;
static void *writer(void *arg)
{
    job *j = arg;
    char p[400], err[300], name[32], text[64];
    for (int r = 0; r < 50 && !j->rc; r++) {
        snprintf(name, sizeof name, "t%d.txt", j->k);
        path_in(p, sizeof p, name);
        snprintf(text, sizeof text, "thread %d round %d\n", j->k, r);
        j->rc = base_out_write_all(p, text, strlen(text), err, sizeof err);
    }
    return NULL;
}

static void t_threads(void)
{
    tst_rmtree(dir);
    enum { N = 8 };
    pthread_t th[N];
    job jobs[N];
    for (int k = 0; k < N; k++) { jobs[k] = (job){ k, 0 }; pthread_create(&th[k], NULL, writer, &jobs[k]); }
    for (int k = 0; k < N; k++) pthread_join(th[k], NULL);
    for (int k = 0; k < N; k++) {
        TST_EQ_INT(jobs[k].rc, 0);
        char p[400], name[32], buf[64], want[64];
        snprintf(name, sizeof name, "t%d.txt", k);
        path_in(p, sizeof p, name);
        snprintf(want, sizeof want, "thread %d round 49\n", k);
        slurp(p, buf, sizeof buf);
        TST_EQ_STR(buf, want);
    }
    TST_EQ_INT(entries(), N);
}

/* A set: nothing appears until every member is complete; a member that
 * fails (a link to /dev/full) leaves every path as it was; a set made
 * current gathers base_out_write_all and takes back the folders it made. */
static void t_set(void)
{
    tst_rmtree(dir);
    char a[400], b[400], full[400], sub[400], inner[400], buf[256], err[300];
    path_in(a, sizeof a, "a.csv");
    path_in(b, sizeof b, "b.csv");
    path_in(full, sizeof full, "full.csv");
    put(a, "old a\n", 0644);
    TST_CHECK(symlink("/dev/full", full) == 0, "symlink");
    base_outset *s = base_outset_new();
    FILE *f = base_outset_open(s, a, err, sizeof err);
    TST_CHECK(f != NULL, "%s", err);
    if (f) fputs("new a\n", f);
    TST_EQ_INT(base_outset_write(s, b, "new b\n", 6, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, full, "x", 1, err, sizeof err), 0);
    TST_EQ_INT(base_outset_commit(s, err, sizeof err), -1);
    TST_CHECK(strstr(err, "No space left") != NULL, "err = %s", err);
    TST_EQ_INT(slurp(a, buf, sizeof buf), 6);
    TST_EQ_STR(buf, "old a\n");
    TST_CHECK(access(b, F_OK) != 0, "b.csv did not appear");
    TST_CHECK(!has_temp(), "no temporary left");
    /* the same set without the failing member: both appear */
    s = base_outset_new();
    TST_EQ_INT(base_outset_write(s, a, "new a\n", 6, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, b, "new b\n", 6, err, sizeof err), 0);
    TST_CHECK(access(b, F_OK) != 0, "not before the commit");
    TST_EQ_INT(base_outset_commit(s, err, sizeof err), 0);
    TST_EQ_INT(slurp(a, buf, sizeof buf), 6);
    TST_EQ_STR(buf, "new a\n");
    TST_EQ_INT(slurp(b, buf, sizeof buf), 6);
    /* a current set: write_all joins it, its bytes readable where they
     * wait, the folder it made taken back by the abort */
    path_in(sub, sizeof sub, "made");
    path_in(inner, sizeof inner, "made/c.csv");
    s = base_outset_begin();
    TST_EQ_INT(base_out_mkdirs(sub, err, sizeof err), 0);
    TST_EQ_INT(base_out_write_all(inner, "c\n", 2, err, sizeof err), 0);
    TST_CHECK(access(inner, F_OK) != 0, "c.csv waits for the commit");
    TST_CHECK(strcmp(base_out_pending(inner), inner) != 0 && slurp(base_out_pending(inner), buf, sizeof buf) == 2,
              "pending bytes readable");
    base_outset_abort(s);
    TST_CHECK(access(sub, F_OK) != 0, "the folder made for the set is gone");
    TST_EQ_STR(base_out_pending(inner), inner);
    /* stale outputs: a regular file goes, a link or FIFO stays */
    char fifo[400], lnk[400];
    path_in(fifo, sizeof fifo, "fifo");
    path_in(lnk, sizeof lnk, "lnk");
    TST_CHECK(mkfifo(fifo, 0600) == 0 && symlink("a.csv", lnk) == 0, "fifo, link");
    TST_EQ_INT(base_out_remove_stale(fifo), 0);
    TST_EQ_INT(base_out_remove_stale(lnk), 0);
    TST_EQ_INT(base_out_remove_stale(b), 0);
    struct stat st;
    TST_CHECK(lstat(fifo, &st) == 0 && S_ISFIFO(st.st_mode), "FIFO kept");
    TST_CHECK(lstat(lnk, &st) == 0 && S_ISLNK(st.st_mode), "link kept");
    TST_CHECK(access(a, F_OK) == 0 && access(b, F_OK) != 0, "a kept, b removed");
}

/* A link to a regular file is written through: same inode, a hard link
 * sees the bytes, and nothing changes before the output is complete. */
static void t_symlink_through(void)
{
    tst_rmtree(dir);
    char tgt[400], hard[400], lnk[400], buf[256], err[300];
    path_in(tgt, sizeof tgt, "t.csv");
    path_in(hard, sizeof hard, "h.csv");
    path_in(lnk, sizeof lnk, "l.csv");
    put(tgt, "before\n", 0640);
    TST_CHECK(link(tgt, hard) == 0 && symlink("t.csv", lnk) == 0, "links");
    struct stat s0, s1;
    stat(tgt, &s0);
    base_out *o = base_out_open(lnk, err, sizeof err);
    TST_CHECK(o != NULL, "%s", err);
    if (!o) return;
    fputs("after\n", base_out_file(o));
    fflush(base_out_file(o));
    TST_EQ_INT(slurp(hard, buf, sizeof buf), 7);     /* untouched until the close */
    TST_EQ_INT(base_out_close(o, err, sizeof err), 0);
    stat(tgt, &s1);
    TST_CHECK(s0.st_ino == s1.st_ino, "same inode");
    TST_CHECK((s1.st_mode & 0777) == 0640, "mode kept: %o", (unsigned)(s1.st_mode & 0777));
    TST_EQ_INT(slurp(hard, buf, sizeof buf), 6);
    TST_EQ_STR(buf, "after\n");
    TST_CHECK(!has_temp(), "no temporary left");
}

/* A set whose commit fails part-way is all-or-nothing (issue: output
 * sets whole even when the last step fails):
 * (a) a link member whose copy fails (its target's folder is gone) stops
 *     the commit there: a later link's file keeps its bytes, and the
 *     renamed members are put back;
 * (b) a rename failing part-way (the target became a folder) puts back
 *     the members renamed before it, old bytes and all, and leaves a new
 *     member where there was none not there. */
static void t_set_whole(void)
{
    tst_rmtree(dir);
    char a[400], b[400], l1[400], l2[400], t2[400], buf[256], err[300];
    path_in(a, sizeof a, "a.csv");
    path_in(b, sizeof b, "b.csv");
    path_in(l1, sizeof l1, "l1.csv");
    path_in(l2, sizeof l2, "l2.csv");
    path_in(t2, sizeof t2, "t2.csv");
    put(a, "old a\n", 0644);
    put(t2, "old t2\n", 0644);
    TST_CHECK(symlink("/nonexistent-shadesim/dir/x.csv", l1) == 0 && symlink("t2.csv", l2) == 0, "links");
    base_outset *s = base_outset_new();
    TST_EQ_INT(base_outset_write(s, a, "new a\n", 6, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, b, "new b\n", 6, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, l1, "new l1\n", 7, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, l2, "new l2\n", 7, err, sizeof err), 0);
    TST_EQ_INT(base_outset_commit(s, err, sizeof err), -1);
    TST_CHECK(strstr(err, "l1.csv") != NULL, "err = %s", err);
    TST_EQ_INT(slurp(t2, buf, sizeof buf), 7);
    TST_EQ_STR(buf, "old t2\n");               /* (a): the link after the failure not written */
    TST_EQ_INT(slurp(a, buf, sizeof buf), 6);
    TST_EQ_STR(buf, "old a\n");                /* renamed, then put back */
    TST_CHECK(access(b, F_OK) != 0, "b.csv (new) taken back");
    TST_CHECK(!has_temp(), "no temporary left");
    TST_EQ_INT(entries(), 4);                   /* a, t2, l1, l2: no .old- link left */
    /* (b) */
    tst_rmtree(dir);
    char c[400], d[400], inside[400];
    path_in(c, sizeof c, "c.csv");
    path_in(d, sizeof d, "d.csv");
    path_in(inside, sizeof inside, "d.csv/keep");
    put(a, "old a\n", 0644);
    s = base_outset_new();
    TST_EQ_INT(base_outset_write(s, a, "new a\n", 6, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, c, "new c\n", 6, err, sizeof err), 0);
    TST_EQ_INT(base_outset_write(s, d, "new d\n", 6, err, sizeof err), 0);
    /* d.csv becomes a folder that is not empty before the commit */
    TST_CHECK(mkdir(d, 0755) == 0, "mkdir");
    put(inside, "x", 0644);
    TST_EQ_INT(base_outset_commit(s, err, sizeof err), -1);
    TST_CHECK(strstr(err, "d.csv") != NULL, "err = %s", err);
    TST_EQ_INT(slurp(a, buf, sizeof buf), 6);
    TST_EQ_STR(buf, "old a\n");
    TST_CHECK(access(c, F_OK) != 0, "c.csv (new) taken back");
    TST_CHECK(!has_temp(), "no temporary left");
    TST_EQ_INT(entries(), 2);                   /* a.csv, d.csv/ */
}

/* (c) A signal during the commit finds the set either not begun or whole:
 * a child commits 100 members over their old bytes, the parent sends
 * SIGINT at times spread over the commit; every member then has the same
 * bytes, old or new. (d) The folders a set made go with an interrupted
 * set (an interrupted report into a new folder left an empty scene/). */
static void t_set_signal(void)
{
    enum { N = 100, RUNS = 16 };     /* N within the registry's 128 slots */
    int mixed = 0, runs = 0, made_left = 0;
    /* on tmpfs, where fsync costs nothing, the commit's time is its
     * renames, and the signals land among them */
    char saved[sizeof dir];
    memcpy(saved, dir, sizeof dir);
    struct stat shm;
    if (stat("/dev/shm", &shm) == 0 && S_ISDIR(shm.st_mode)) {
        snprintf(dir, sizeof dir, "/dev/shm/shadesim-test-out-%ld", (long)getpid());
        mkdir(dir, 0700);
    }
    for (int run = 0; run < RUNS; run++) {
        tst_rmtree(dir);
        char p[400], err[300], name[32];
        for (int k = 0; k < N; k++) {
            snprintf(name, sizeof name, "m%03d.csv", k);
            path_in(p, sizeof p, name);
            put(p, "old\n", 0644);
        }
        int fds[2];
        TST_CHECK(pipe(fds) == 0, "pipe");
        fflush(stdout);
        pid_t pid = fork();
        if (pid == 0) {
            close(fds[0]);
            base_out_install_signals();
            char sub[400];
            path_in(sub, sizeof sub, "new/scene");
            base_outset *s = base_outset_begin();
            if (base_out_mkdirs(sub, err, sizeof err)) _exit(3);
            for (int k = 0; k < N; k++) {
                snprintf(name, sizeof name, "m%03d.csv", k);
                path_in(p, sizeof p, name);
                if (base_out_write_all(p, "new\n", 4, err, sizeof err)) _exit(4);
            }
            if (write(fds[1], "g", 1) != 1) _exit(5);
            if (run % 4 == 3) for (;;) pause();   /* (d): killed before its commit */
            base_outset_commit(s, err, sizeof err);
            for (;;) pause();
        }
        TST_CHECK(pid > 0, "fork");
        if (pid <= 0) return;
        close(fds[1]);
        char go;
        int started = read(fds[0], &go, 1) == 1;
        close(fds[0]);
        struct timespec ts = { 0, 25000L * run };    /* 0 to 0.4 ms into the commit */
        nanosleep(&ts, NULL);
        kill(pid, SIGINT);
        int status = 0;
        waitpid(pid, &status, 0);
        if (!started) continue;
        runs++;
        int nnew = 0;
        for (int k = 0; k < N; k++) {
            char buf[16];
            snprintf(name, sizeof name, "m%03d.csv", k);
            path_in(p, sizeof p, name);
            if (slurp(p, buf, sizeof buf) == 4 && !strcmp(buf, "new\n")) nnew++;
        }
        if (nnew && nnew != N) mixed++;
        char sub[400];
        path_in(sub, sizeof sub, "new");
        if (run % 4 == 3 && access(sub, F_OK) == 0) made_left++;
        if (has_temp()) made_left += 100;
    }
    if (strcmp(dir, saved)) { tst_rmtree(dir); rmdir(dir); }
    memcpy(dir, saved, sizeof dir);
    TST_EQ_INT(runs, RUNS);
    TST_EQ_INT(mixed, 0);
    TST_EQ_INT(made_left, 0);
}

int main(void)
{
    umask(UMASK);
    snprintf(dir, sizeof dir, "/tmp/shadesim-test-out-%ld", (long)getpid());
    mkdir(dir, 0700);
    TST_RUN(t_new_path);
    TST_RUN(t_replace_regular);
    TST_RUN(t_symlink);
    TST_RUN(t_symlink_through);
    TST_RUN(t_set_whole);
    TST_RUN(t_set_signal);
    TST_RUN(t_set);
    TST_RUN(t_devnull);
    TST_RUN(t_devfull);
    TST_RUN(t_fifo);
    TST_RUN(t_rename_fails);
    TST_RUN(t_file_too_big);
    TST_RUN(t_bad_paths);
    TST_RUN(t_stdout);
    TST_RUN(t_sigterm);
    TST_RUN(t_sigint);
    TST_RUN(t_sighup);
    TST_RUN(t_kill_from_outside);
    TST_RUN(t_threads);
    tst_rmtree(dir);
    rmdir(dir);
    TST_EXIT();
}
