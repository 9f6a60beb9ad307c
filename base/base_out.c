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
 *  - A link to a regular file (or a dangling one) is written through, but
 *    only once the output is complete: the bytes go to a temporary beside
 *    the link, and are copied into the file the link names (opened
 *    through the link, O_TRUNC) at the close or the set's commit. So the
 *    file keeps its inode (its other links, owner, mode) and an output
 *    that fails before its end leaves it untouched; only a failure during
 *    the copy itself (ENOSPC) leaves it cut, as any write-through would.
 *  - A set (base_outset) finishes every member first - flush, fsync,
 *    close, write-through ones checked (ENOSPC of /dev/full) - and only
 *    when all are complete copies the links and renames the temporaries
 *    in, so a failure anywhere before that changes none of its paths.
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

enum { OUT_TEMP, OUT_THROUGH, OUT_STDOUT, OUT_LINK };

struct base_out {
    FILE *f;
    int   kind;
    int   slot;       /* registry slot of tmp, or -1 */
    char *shown;      /* the path as given (messages) */
    char *target;     /* where the file goes (symlinks resolved) */
    char *tmp;        /* OUT_TEMP, OUT_LINK: the temporary */
    int   werr;       /* errno of a failed write seen by base_out_write_all */
    int   finished;   /* out_finish done: f closed, the temporary complete */
};

/* ---- registry of temporaries ------------------------------------------ */

#define REG_N   128
#define REG_LEN 4096

static char reg_path[REG_N][REG_LEN];
static volatile sig_atomic_t reg_used[REG_N];
static volatile sig_atomic_t reg_dir[REG_N];    /* a folder a set made: rmdir'd (if empty), not unlinked */
static pthread_mutex_t reg_mu = PTHREAD_MUTEX_INITIALIZER;

static int reg_add_kind(const char *path, int dir);
static int reg_add(const char *path) { return reg_add_kind(path, 0); }

static int reg_add_kind(const char *path, int dir)
{
    size_t n = strlen(path);
    if (n >= REG_LEN) return -1;
    int slot = -1;
    pthread_mutex_lock(&reg_mu);
    for (int i = 0; i < REG_N; i++)
        if (!reg_used[i]) {
            memcpy(reg_path[i], path, n + 1);
            reg_dir[i] = dir;
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

/* A folder a set made, registered while the set is open: a signal's
 * handler removes it if it is empty (a report into a new folder left an
 * empty scene/ when interrupted). Unregistered by path. */
static void reg_remove_dir(const char *path)
{
    pthread_mutex_lock(&reg_mu);
    for (int i = 0; i < REG_N; i++)
        if (reg_used[i] && reg_dir[i] && !strcmp(reg_path[i], path)) {
            reg_used[i] = 0;
            atomic_thread_fence(memory_order_seq_cst);
            break;
        }
    pthread_mutex_unlock(&reg_mu);
}

/* The registered temporaries unlinked, then the registered folders
 * removed where empty: a few passes, so that a folder goes after the ones
 * made inside it whatever their slots. Async-signal-safe calls only. */
static void reg_clean(void)
{
    for (int i = 0; i < REG_N; i++)
        if (reg_used[i] && !reg_dir[i]) unlink(reg_path[i]);
    for (int pass = 0; pass < 8; pass++)
        for (int i = REG_N - 1; i >= 0; i--)
            if (reg_used[i] && reg_dir[i]) rmdir(reg_path[i]);
}

/* A set's move in progress (base_outset_commit): a signal that reaches
 * another thread then waits for it, as the committing thread holds it. */
static volatile sig_atomic_t moving, moved_sig;

/* Only async-signal-safe calls: unlink, rmdir, signal, raise. The signal
 * is blocked while its handler runs, so the raise is delivered on return,
 * now with the default action. */
static void on_signal(int sig)
{
    int saved = errno;
    if (moving) { moved_sig = sig; errno = saved; return; }
    reg_clean();
    signal(sig, SIG_DFL);
    raise(sig);
    errno = saved;
}

_Noreturn void base_out_of_memory(void)
{
    static const char msg[] = "shadesim: out of memory\n";
    /* write(2), not stdio: stdio may need the memory there is none of */
    if (write(STDERR_FILENO, msg, sizeof msg - 1) < 0) { /* nothing left to report it on */ }
    reg_clean();
    _exit(BASE_EXIT_OOM);
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

/* SIGPIPE is caught, not ignored: a write to a closed pipe then fails
 * with EPIPE, reported like any write error (exit status 2, not death by
 * the signal), and the programs shadesim starts (rsvg-convert, iverilog)
 * get the default action back at their exec, as an ignored signal would
 * not. */
static void on_pipe(int sig) { (void)sig; }

void base_out_install_signals(void)
{
    pthread_once(&mode_once, read_umask);
    struct sigaction pa, pold;
    if (sigaction(SIGPIPE, NULL, &pold) == 0 && pold.sa_handler != SIG_IGN) {
        memset(&pa, 0, sizeof pa);
        pa.sa_handler = on_pipe;
        sigemptyset(&pa.sa_mask);
        sigaction(SIGPIPE, &pa, NULL);
    }
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

static int open_temp(base_out *o, const char *t, const struct stat *st, int exists, char *err, size_t errlen)
{
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
    if (!o->tmp) base_out_of_memory();
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
    (void)fchmod(fd, exists ? (st->st_mode & 07777) : st ? new_mode : 0600);
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
    struct stat lst;
    int is_link = lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode);
    if (is_link && (!exists || S_ISREG(st.st_mode))) {
        /* written through at the close, from a temporary beside the link */
        if (open_temp(o, path, NULL, 0, err, errlen)) { out_free(o); return NULL; }
        o->kind = OUT_LINK;
        return o;
    }
    if (!exists || S_ISREG(st.st_mode)) {
        if (open_temp(o, o->target, &st, exists, err, errlen)) { out_free(o); return NULL; }
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

/* The file complete and closed, every error seen; nothing moved yet.
 * 0, or -1 with the message (the temporary removed). */
static int out_finish(base_out *o, char *err, size_t errlen)
{
    if (o->finished) return 0;
    o->finished = 1;
    int e = flush_err(o->f, o->werr ? o->werr : errno);
    if (o->kind == OUT_STDOUT) {
        if (e) { msg(err, errlen, "standard output", "write failed: %s", strerror(e)); errno = e; }
        return e ? -1 : 0;
    }
    if (!e && o->kind == OUT_TEMP && fsync(fileno(o->f)) != 0 &&
        errno != EINVAL && errno != EROFS && errno != ENOTSUP) {
        e = errno;
    }
    if (fclose(o->f) != 0 && !e) e = errno ? errno : EIO;
    o->f = NULL;
    if (e) {
        if (o->tmp) { unlink(o->tmp); reg_remove(o->slot); o->slot = -1; free(o->tmp); o->tmp = NULL; }
        msg(err, errlen, o->shown, "write failed: %s", strerror(e));
        errno = e;
        return -1;
    }
    return 0;
}

/* OUT_LINK: the temporary's bytes into the file the link names. */
static int copy_through(base_out *o, char *err, size_t errlen)
{
    int in = open(o->tmp, O_RDONLY | O_CLOEXEC), e = 0;
    int out = in < 0 ? -1 : open(o->shown, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, (mode_t)new_mode);
    const char *what = "cannot open";
    if (in < 0 || out < 0) e = errno;
    char buf[1 << 16];
    for (ssize_t k; !e && (k = read(in, buf, sizeof buf)) != 0;) {
        if (k < 0) { if (errno == EINTR) continue; e = errno; what = "read back failed"; break; }
        for (ssize_t w = 0; w < k;) {
            ssize_t r = write(out, buf + w, (size_t)(k - w));
            if (r < 0) { if (errno == EINTR) continue; e = errno; what = "write failed"; break; }
            w += r;
        }
    }
    if (out >= 0 && close(out) != 0 && !e) { e = errno; what = "write failed"; }
    if (in >= 0) close(in);
    if (e) { msg(err, errlen, o->shown, "%s: %s", what, strerror(e)); errno = e; }
    return e ? -1 : 0;
}

/* After out_finish: make the file appear (rename, or the link's copy),
 * and free o. 0, or -1 with the message. */
static int out_publish(base_out *o, char *err, size_t errlen)
{
    int rc = 0;
    if (o->kind == OUT_TEMP && rename(o->tmp, o->target) != 0) {
        int e = errno;
        msg(err, errlen, o->shown, "cannot rename into place: %s", strerror(e));
        errno = e;
        rc = -1;
    }
    if (o->kind == OUT_LINK) rc = copy_through(o, err, errlen);
    if (o->tmp && (rc || o->kind == OUT_LINK)) unlink(o->tmp);
    if (o->tmp) reg_remove(o->slot);
    int saved = errno;
    out_free(o);
    errno = saved;
    return rc;
}

struct base_outset {
    int n, cap;
    base_out **o;
    base_outset *parent;        /* the set current before base_outset_begin */
    char **made;                /* folders base_out_mkdirs made for it, in order */
    int nmade;
};

/* The set base_outset_begin made current in this thread: outputs closed
 * meanwhile join it instead of appearing. */
static _Thread_local base_outset *cur_set;

static int set_add(base_outset *s, base_out *o)
{
    if (s->n == s->cap) {
        int nc = s->cap ? 2 * s->cap : 8;
        base_out **no = realloc(s->o, (size_t)nc * sizeof *no);
        if (!no) return -1;
        s->o = no;
        s->cap = nc;
    }
    s->o[s->n++] = o;
    return 0;
}

base_outset *base_outset_begin(void)
{
    base_outset *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->parent = cur_set;
    cur_set = s;
    return s;
}

const char *base_out_pending(const char *path)
{
    for (base_outset *s = cur_set; s; s = s->parent)
        for (int i = s->n - 1; i >= 0; i--)
            if (s->o[i]->kind == OUT_TEMP && s->o[i]->tmp && !strcmp(s->o[i]->shown, path)) return s->o[i]->tmp;
    return path;
}

int base_out_close(base_out *o, char *err, size_t errlen)
{
    if (!o) return 0;
    if (out_finish(o, err, errlen)) { int e = errno; out_free(o); errno = e; return -1; }
    if (cur_set && o->kind != OUT_STDOUT) {
        if (set_add(cur_set, o)) { msg(err, errlen, o->shown, "out of memory"); base_out_abort(o); return -1; }
        return 0;
    }
    return out_publish(o, err, errlen);
}

void base_out_abort(base_out *o)
{
    if (!o) return;
    if (o->kind == OUT_STDOUT) {
        fflush(stdout);
    } else {
        if (o->f) fclose(o->f);
        if (o->tmp) {
            unlink(o->tmp);
            reg_remove(o->slot);
        }
    }
    out_free(o);
}

/* ---- sets --------------------------------------------------------------- */

base_outset *base_outset_new(void)
{
    base_outset *s = calloc(1, sizeof *s);
    return s;
}

/* s out of the current chain if it is there (its own begin). */
static void set_pop(base_outset *s)
{
    if (cur_set == s) cur_set = s->parent;
}

FILE *base_outset_open(base_outset *s, const char *path, char *err, size_t errlen)
{
    if (!s) { if (err && errlen) snprintf(err, errlen, "%s: out of memory", path); return NULL; }
    base_out *o = base_out_open(path, err, errlen);
    if (!o) return NULL;
    if (set_add(s, o)) { base_out_abort(o); msg(err, errlen, path, "out of memory"); return NULL; }
    return o->f;
}

int base_outset_write(base_outset *s, const char *path, const void *buf, size_t len, char *err, size_t errlen)
{
    FILE *f = base_outset_open(s, path, err, errlen);
    if (!f) return -1;
    errno = 0;
    if (len && fwrite(buf, 1, len, f) != len) s->o[s->n - 1]->werr = errno ? errno : EIO;
    return 0;
}

void base_outset_abort(base_outset *s)
{
    if (!s) return;
    set_pop(s);
    for (int i = 0; i < s->n; i++) base_out_abort(s->o[i]);
    /* the folders made for it go too, the last made first, if empty */
    for (int i = s->nmade - 1; i >= 0; i--) { rmdir(s->made[i]); reg_remove_dir(s->made[i]); free(s->made[i]); }
    free(s->made);
    free(s->o);
    free(s);
}

static void set_forget_made(base_outset *s)
{
    for (int i = 0; i < s->nmade; i++) { reg_remove_dir(s->made[i]); free(s->made[i]); }
    free(s->made);
    s->made = NULL;
    s->nmade = 0;
}

/* A hard link ".NAME.old-PID-K" to target beside it, for putting the old
 * file back: its path (malloc'd), or NULL when there is no old file or
 * no link can be made (then the member is published without a way back). */
static char *keep_old(const char *target)
{
    struct stat st;
    if (lstat(target, &st) || !S_ISREG(st.st_mode)) return NULL;
    const char *slash = strrchr(target, '/');
    size_t dl = slash ? (size_t)(slash - target + 1) : 0, n = strlen(target) + 64;
    char *p = malloc(n);
    if (!p) base_out_of_memory();
    static atomic_uint seq;
    for (int tries = 0; tries < 8; tries++) {
        snprintf(p, n, "%.*s.%s.old-%ld-%u", (int)dl, target, target + dl, (long)getpid(), atomic_fetch_add(&seq, 1));
        if (link(target, p) == 0) return p;
        if (errno != EEXIST) break;
    }
    free(p);
    return NULL;
}

int base_outset_commit(base_outset *s, char *err, size_t errlen)
{
    if (!s) return 0;
    set_pop(s);
    int rc = 0;
    for (int i = 0; i < s->n && !rc; i++)
        if (out_finish(s->o[i], err, errlen)) rc = -1;
    if (rc) { base_outset_abort(s); return -1; }
    /* Within a set still current (a verb's, around this one): the members
     * join it and appear with it. */
    if (cur_set) {
        for (int i = 0; i < s->n; i++) {
            if (!rc && set_add(cur_set, s->o[i]) == 0) continue;
            if (!rc) msg(err, errlen, s->o[i]->shown, "out of memory");
            rc = -1;
            base_out_abort(s->o[i]);
        }
        for (int i = 0; i < s->nmade; i++) {     /* the folders, to the outer set */
            char **nm = realloc(cur_set->made, (size_t)(cur_set->nmade + 1) * sizeof *nm);
            if (!nm) { free(s->made[i]); continue; }
            cur_set->made = nm;
            nm[cur_set->nmade++] = s->made[i];
        }
        free(s->made);
        free(s->o);
        free(s);
        return rc;
    }
    /* Every member complete. Publishing is as near all-or-nothing as POSIX
     * allows:
     *  - SIGINT, SIGTERM and SIGHUP are held until it ends (one arriving
     *    mid-way left a new sweep.csv beside the old summary), so a signal
     *    finds the set either not begun or whole;
     *  - the renames come first, each existing target kept as a hard link
     *    ".NAME.old-PID-K" beside it, so that one failing part-way (an
     *    immutable or foreign-owned member) puts back those before it;
     *  - the links' copies (which can fail: ENOSPC) last, stopping at the
     *    first failure, which also puts the renamed members back. A link
     *    copied before the failing one keeps its new bytes: a file written
     *    through in place cannot be taken back (docs/cli.md).
     * A SIGKILL mid-way can leave a ".NAME.old-..." behind. */
    sigset_t hold, was;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT);
    sigaddset(&hold, SIGTERM);
    sigaddset(&hold, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &hold, &was);
    moving = 1;
    char **tgt = calloc((size_t)s->n + 1, sizeof *tgt), **old = calloc((size_t)s->n + 1, sizeof *old);
    char *pub = calloc((size_t)s->n + 1, 1);     /* renamed in */
    if (!tgt || !old || !pub) base_out_of_memory();
    for (int i = 0; i < s->n && !rc; i++) {
        if (s->o[i]->kind != OUT_TEMP) continue;
        if (!(tgt[i] = strdup(s->o[i]->target))) base_out_of_memory();
        old[i] = keep_old(tgt[i]);
        if (out_publish(s->o[i], err, errlen)) rc = -1;
        else pub[i] = 1;
        s->o[i] = NULL;
    }
    for (int i = 0; i < s->n && !rc; i++)          /* links; write-through ones are done */
        if (s->o[i]) {
            if (out_publish(s->o[i], err, errlen)) rc = -1;
            s->o[i] = NULL;
        }
    for (int i = 0; i < s->n; i++) {
        if (rc && pub[i]) {
            /* put back: the old file (its link kept if that fails), or none */
            if (!old[i]) unlink(tgt[i]);
            else if (rename(old[i], tgt[i]) != 0) { free(old[i]); old[i] = NULL; }
        } else if (old[i]) unlink(old[i]);      /* the old file's extra name */
        free(tgt[i]);
        free(old[i]);
    }
    free(pub);
    for (int i = 0; i < s->n; i++) if (s->o[i]) base_out_abort(s->o[i]);
    free(tgt);
    free(old);
    moving = 0;
    pthread_sigmask(SIG_SETMASK, &was, NULL);
    if (!rc) set_forget_made(s);
    else for (int i = s->nmade - 1; i >= 0; i--) { rmdir(s->made[i]); reg_remove_dir(s->made[i]); free(s->made[i]); }
    if (rc) { free(s->made); s->made = NULL; s->nmade = 0; }
    free(s->o);
    free(s);
    if (moved_sig) raise(moved_sig);            /* one another thread took during the move */
    return rc;
}

int base_out_remove_stale(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0) return errno == ENOENT ? 0 : -1;
    if (!S_ISREG(st.st_mode)) return 0;         /* a link, FIFO, device: not ours */
    return unlink(path);
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
            if (mkdir(p, 0777) == 0) {
                /* a folder a current set's abort should take back */
                if (cur_set) {
                    char **nm = realloc(cur_set->made, (size_t)(cur_set->nmade + 1) * sizeof *nm);
                    if (nm) {
                        cur_set->made = nm;
                        if ((nm[cur_set->nmade] = strdup(p))) {
                            reg_add_kind(p, 1);
                            cur_set->nmade++;
                        }
                    }
                }
            } else if (errno != EEXIST) {
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
