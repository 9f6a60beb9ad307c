/* base_out.c - output files (see base_out.h).
 *
 * Decisions beyond the header:
 *  - The temporary is ".NAME.tmp-XXXXXX" in the target's folder (hidden,
 *    and recognisably ours if a SIGKILL ever leaves one behind); rename()
 *    within one folder is atomic.
 *  - Mode: a replaced regular file keeps its permission bits; a new file
 *    gets 0666 & ~umask, as open(O_CREAT, 0666) would give. The umask can
 *    only be read by setting it, which is not thread-safe, so it is read
 *    once: in base_out_install_signals (main, before any thread) or, in
 *    programs that do not call it, at the first open.
 *  - Write-through targets (devices, FIFOs) are opened O_WRONLY without
 *    O_TRUNC: truncating a FIFO or a tty means nothing, and the node must
 *    stay what it is.
 *  - Symbolic links are followed one hop at a time (readlink), not with
 *    realpath, so a dangling link still names where the file will go.
 *  - The registry of temporaries is a fixed array that a signal handler
 *    may read at any moment: the path is copied in before the slot's flag
 *    is raised, and the flag is lowered before the slot is reused. The
 *    mutex only orders threads claiming slots; the handler never takes it.
 *    A path that does not fit (more slots busy than REG_N, or a path over
 *    REG_LEN) is still written, only not cleaned up on a signal.
 *  - Paths are escaped in messages (bytes outside printable ASCII as \xNN)
 *    so that a hostile name cannot put control characters on a terminal.
 */
#include "base/base_out.h"
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { OUT_TEMP, OUT_THROUGH, OUT_STDOUT };

struct base_out {
    FILE *f;
    int   kind;
    int   slot;       /* registry slot of tmp, or -1 */
    char *shown;      /* the path as given (messages) */
    char *target;     /* where the file goes (symlinks resolved) */
    char *tmp;        /* OUT_TEMP: the temporary */
    int   werr;       /* errno of a failed write seen by base_out_write_all */
};

/* ---- registry of temporaries ------------------------------------------ */

#define REG_N   128
#define REG_LEN 4096

static char reg_path[REG_N][REG_LEN];
static volatile sig_atomic_t reg_used[REG_N];
static pthread_mutex_t reg_mu = PTHREAD_MUTEX_INITIALIZER;

static int reg_add(const char *path)
{
    size_t n = strlen(path);
    if (n >= REG_LEN) return -1;
    int slot = -1;
    pthread_mutex_lock(&reg_mu);
    for (int i = 0; i < REG_N; i++)
        if (!reg_used[i]) {
            memcpy(reg_path[i], path, n + 1);
            atomic_thread_fence(memory_order_seq_cst);  /* path before flag */
            reg_used[i] = 1;
            slot = i;
            break;
        }
    pthread_mutex_unlock(&reg_mu);
    return slot;
}

static void reg_remove(int slot)
{
    if (slot < 0) return;
    pthread_mutex_lock(&reg_mu);
    reg_used[slot] = 0;
    atomic_thread_fence(memory_order_seq_cst);
    pthread_mutex_unlock(&reg_mu);
}

/* Only async-signal-safe calls: unlink, signal, raise. The signal is
 * blocked while its handler runs, so the raise is delivered on return,
 * now with the default action. */
static void on_signal(int sig)
{
    int saved = errno;
    for (int i = 0; i < REG_N; i++)
        if (reg_used[i]) unlink(reg_path[i]);
    signal(sig, SIG_DFL);
    raise(sig);
    errno = saved;
}

/* ---- umask ------------------------------------------------------------- */

static mode_t new_mode = 0644;
static pthread_once_t mode_once = PTHREAD_ONCE_INIT;

static void read_umask(void)
{
    mode_t m = umask(022);
    umask(m);
    new_mode = 0666 & ~m;
}

void base_out_install_signals(void)
{
    pthread_once(&mode_once, read_umask);
    static const int sigs[] = { SIGINT, SIGTERM, SIGHUP };
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction sa, old;
        /* A signal ignored by whoever started us (nohup) stays ignored. */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

/* ---- messages ---------------------------------------------------------- */

/* s with bytes outside printable ASCII as \xNN, cut to fit out. */
static void escape(const char *s, char *out, size_t n)
{
    static const char hex[] = "0123456789abcdef";
    size_t j = 0;
    for (; *s && j + 5 < n; s++) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20 && c < 0x7f && c != '\\') out[j++] = (char)c;
        else if (c == '\\') { out[j++] = '\\'; out[j++] = '\\'; }
        else { out[j++] = '\\'; out[j++] = 'x'; out[j++] = hex[c >> 4]; out[j++] = hex[c & 15]; }
    }
    if (*s && j + 3 < n) { out[j++] = '.'; out[j++] = '.'; out[j++] = '.'; }
    out[j] = 0;
}

static void msg(char *err, size_t errlen, const char *path, const char *fmt, ...)
{
    if (!err || !errlen) return;
    int saved = errno;          /* callers may report errno after us */
    char p[512], what[512];
    escape(path, p, sizeof p);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    snprintf(err, errlen, "%s: %s", p, what);
    errno = saved;
}

/* ---- opening ----------------------------------------------------------- */

/* Follow symbolic links from path. Returns the final name (malloc'd) and
 * sets *st / *exists; NULL with errno on failure. */
static char *resolve(const char *path, struct stat *st, int *exists)
{
    char *cur = strdup(path);
    if (!cur) return NULL;
    for (int hop = 0;; hop++) {
        if (lstat(cur, st) != 0) {
            if (errno == ENOENT) { *exists = 0; return cur; }
            free(cur);
            return NULL;
        }
        if (!S_ISLNK(st->st_mode)) { *exists = 1; return cur; }
        if (hop >= 40) { free(cur); errno = ELOOP; return NULL; }
        size_t cap = st->st_size > 0 ? (size_t)st->st_size + 1 : 256;
        char *lnk;
        ssize_t r;
        for (;;) {
            lnk = malloc(cap);
            if (!lnk) { free(cur); errno = ENOMEM; return NULL; }
            r = readlink(cur, lnk, cap);
            if (r < 0) { int e = errno; free(lnk); free(cur); errno = e; return NULL; }
            if ((size_t)r < cap) break;
            free(lnk);
            cap *= 2;
        }
        lnk[r] = 0;
        char *next;
        const char *slash = strrchr(cur, '/');
        if (lnk[0] == '/' || !slash) {
            next = lnk;
        } else {            /* relative: against the link's own folder */
            size_t d = (size_t)(slash - cur) + 1;
            next = malloc(d + (size_t)r + 1);
            if (!next) { free(lnk); free(cur); errno = ENOMEM; return NULL; }
            memcpy(next, cur, d);
            memcpy(next + d, lnk, (size_t)r + 1);
            free(lnk);
        }
        free(cur);
        cur = next;
    }
}

static void out_free(base_out *o)
{
    if (!o) return;
    int saved = errno;
    free(o->shown); free(o->target); free(o->tmp); free(o);
    errno = saved;
}

static int open_temp(base_out *o, const struct stat *st, int exists, char *err, size_t errlen)
{
    const char *t = o->target;
    size_t tl = strlen(t);
    if (tl && t[tl - 1] == '/') {
        errno = EISDIR;
        msg(err, errlen, o->shown, "names a folder, not a file");
        return -1;
    }
    const char *slash = strrchr(t, '/');
    size_t d = slash ? (size_t)(slash - t) + 1 : 0;
    size_t bl = tl - d;
    if (bl > 200) bl = 200;     /* ".NAME.tmp-XXXXXX" within NAME_MAX */
    o->tmp = malloc(d + 1 + bl + sizeof ".tmp-XXXXXX");
    if (!o->tmp) { msg(err, errlen, o->shown, "out of memory"); return -1; }
    memcpy(o->tmp, t, d);
    o->tmp[d] = '.';
    memcpy(o->tmp + d + 1, t + d, bl);
    memcpy(o->tmp + d + 1 + bl, ".tmp-XXXXXX", sizeof ".tmp-XXXXXX");

    /* Block the signals while the temporary exists but is not yet
     * registered, so that it cannot be left behind in between. */
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT); sigaddset(&block, SIGTERM); sigaddset(&block, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &block, &old);
    int fd = mkstemp(o->tmp);
    int e = errno;
    if (fd >= 0) o->slot = reg_add(o->tmp);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (fd < 0) {
        errno = e;
        msg(err, errlen, o->shown, "cannot create: %s", strerror(e));
        return -1;
    }
    (void)fchmod(fd, exists ? (st->st_mode & 07777) : new_mode);
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        e = errno;
        close(fd);
        unlink(o->tmp);
        reg_remove(o->slot);
        o->slot = -1;
        errno = e;
        msg(err, errlen, o->shown, "cannot write: %s", strerror(e));
        return -1;
    }
    o->kind = OUT_TEMP;
    return 0;
}

base_out *base_out_open(const char *path, char *err, size_t errlen)
{
    pthread_once(&mode_once, read_umask);
    if (!path || !*path) {
        if (err && errlen) snprintf(err, errlen, "empty output path");
        errno = ENOENT;
        return NULL;
    }
    base_out *o = calloc(1, sizeof *o);
    if (!o || !(o->shown = strdup(path))) {
        free(o);
        errno = ENOMEM;
        msg(err, errlen, path, "out of memory");
        return NULL;
    }
    o->slot = -1;
    if (!strcmp(path, "-")) {
        o->kind = OUT_STDOUT;
        o->f = stdout;
        return o;
    }
    struct stat st;
    int exists = 0;
    o->target = resolve(path, &st, &exists);
    if (!o->target) {
        msg(err, errlen, path, "cannot open: %s", strerror(errno));
        out_free(o);
        return NULL;
    }
    if (exists && S_ISDIR(st.st_mode)) {
        errno = EISDIR;
        msg(err, errlen, path, "is a folder");
        out_free(o);
        return NULL;
    }
    if (!exists || S_ISREG(st.st_mode)) {
        if (open_temp(o, &st, exists, err, errlen)) { out_free(o); return NULL; }
        return o;
    }
    /* Device, FIFO, socket: write through, never replace. */
    int fd = open(o->target, O_WRONLY | O_CLOEXEC);
    if (fd < 0) {
        msg(err, errlen, path, "cannot open: %s", strerror(errno));
        out_free(o);
        return NULL;
    }
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        int e = errno;
        msg(err, errlen, path, "cannot write: %s", strerror(e));
        close(fd);
        out_free(o);
        errno = e;
        return NULL;
    }
    o->kind = OUT_THROUGH;
    return o;
}

FILE *base_out_file(base_out *o)
{
    return o ? o->f : NULL;
}

/* ---- closing ----------------------------------------------------------- */

/* Flush f and return 0, or the errno of the failure. When the error flag
 * was set by an earlier write (glibc drops the buffer then, so the flush
 * succeeds), the cause is gone from the stream; the caller's errno on
 * entry is taken if it is one a write gives (a writer stops at its first
 * failed fprintf, so errno still holds ENOSPC), else EIO. */
static int flush_err(FILE *f, int entry_errno)
{
    errno = 0;
    if (fflush(f) != 0) return errno ? errno : EIO;
    if (!ferror(f)) return 0;
    switch (entry_errno) {
    case ENOSPC: case EDQUOT: case EFBIG: case EPIPE: case EIO: case ENXIO: case EROFS:
        return entry_errno;
    default:
        return EIO;
    }
}

int base_out_close(base_out *o, char *err, size_t errlen)
{
    if (!o) return 0;
    int e = flush_err(o->f, o->werr ? o->werr : errno);
    if (o->kind == OUT_STDOUT) {
        if (e) msg(err, errlen, "standard output", "write failed: %s", strerror(e));
        out_free(o);
        if (e) errno = e;
        return e ? -1 : 0;
    }
    const char *what = "write failed";
    if (!e && o->kind == OUT_TEMP && fsync(fileno(o->f)) != 0 &&
        errno != EINVAL && errno != EROFS && errno != ENOTSUP) {
        e = errno;
    }
    if (fclose(o->f) != 0 && !e) e = errno ? errno : EIO;
    o->f = NULL;
    if (o->kind == OUT_TEMP) {
        if (!e && rename(o->tmp, o->target) != 0) {
            e = errno;
            what = "cannot rename into place";
        }
        if (e) unlink(o->tmp);
        reg_remove(o->slot);
    }
    if (e) msg(err, errlen, o->shown, "%s: %s", what, strerror(e));
    out_free(o);
    if (e) errno = e;           /* for callers that only get -1 */
    return e ? -1 : 0;
}

void base_out_abort(base_out *o)
{
    if (!o) return;
    if (o->kind == OUT_STDOUT) {
        fflush(stdout);
    } else {
        if (o->f) fclose(o->f);
        if (o->kind == OUT_TEMP) {
            unlink(o->tmp);
            reg_remove(o->slot);
        }
    }
    out_free(o);
}

int base_out_write_all(const char *path, const void *buf, size_t len, char *err, size_t errlen)
{
    base_out *o = base_out_open(path, err, errlen);
    if (!o) return -1;
    errno = 0;
    if (len && fwrite(buf, 1, len, o->f) != len) o->werr = errno ? errno : EIO;
    return base_out_close(o, err, errlen);
}

int base_out_stdout_check(char *err, size_t errlen)
{
    int e = flush_err(stdout, errno);
    if (!e) return 0;
    if (err && errlen) snprintf(err, errlen, "standard output: write failed: %s", strerror(e));
    return -1;
}

int base_out_mkdirs(const char *dir, char *err, size_t errlen)
{
    char p[4096];
    if (!dir[0]) { snprintf(err, errlen, "empty folder name"); return -1; }
    if (snprintf(p, sizeof p, "%s", dir) >= (int)sizeof p) {
        snprintf(err, errlen, "%s: path too long", dir);
        return -1;
    }
    for (char *s = p + 1;; s++) {
        char ch = *s;
        if (ch == '/' || ch == 0) {
            *s = 0;
            struct stat st;
            if (mkdir(p, 0777) && errno != EEXIST) {
                snprintf(err, errlen, "%s: cannot create folder %s: %s", dir, p, strerror(errno));
                return -1;
            }
            if (stat(p, &st) || !S_ISDIR(st.st_mode)) {
                snprintf(err, errlen, "%s: %s is not a folder", dir, p);
                return -1;
            }
            *s = ch;
        }
        if (!ch) break;
    }
    /* A long run should not find out at its end that it cannot write. */
    char probe[4200];
    snprintf(probe, sizeof probe, "%s/.shadesim-probe-%ld", dir, (long)getpid());
    int fd = open(probe, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot write in the output folder: %s", dir, strerror(errno));
        return -1;
    }
    close(fd);
    unlink(probe);
    return 0;
}
