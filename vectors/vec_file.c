/* vec_file.c - golden vector files (SPEC 4): a strict reader and an atomic
 * writer.
 *
 * The reader is meant to face hand-edited and truncated files: every
 * problem is one line "PATH:LINE: what is wrong", nothing is read into a
 * fixed buffer without a bound, and binary junk is recognised as such
 * instead of being reported as a strange number.
 *
 * vec_file_read treats s as output only: it is (re)initialized, so pass a
 * set that holds no rows (or free it first). On failure it is left empty.
 */
#include "vectors/vec_file.h"
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define VEC_LINE_MAX 65536      /* longest accepted line, bytes */
#define VEC_MAGIC "shadesim vectors 1"

static void msg(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || !errlen) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

/* ---- writing --------------------------------------------------------- */

static int print_names(FILE *f, const char *key, int n, const char names[][16])
{
    if (fprintf(f, "# %s:", key) < 0) return -1;
    for (int i = 0; i < n; i++)
        if (fprintf(f, " %s", names[i]) < 0) return -1;
    return fputc('\n', f) == EOF ? -1 : 0;
}

int vec_file_print(FILE *f, const vec_set *s)
{
    if (fprintf(f, "# " VEC_MAGIC "\n# unit: %s\n", s->unit) < 0) return -1;
    if (print_names(f, "inputs", s->n_in, s->in_names)) return -1;
    if (print_names(f, "outputs", s->n_out, s->out_names)) return -1;
    for (size_t r = 0; r < s->n_rows; r++) {
        const double *v = vec_row(s, r);
        for (int i = 0; i < s->n_in + s->n_out; i++) {
            const char *sep = i == 0 ? "" : i == s->n_in ? " | " : " ";
            if (fprintf(f, "%s%.17g", sep, v[i]) < 0) return -1;
        }
        if (fputc('\n', f) == EOF) return -1;
    }
    return ferror(f) ? -1 : 0;
}

/* What the reader would refuse, refused before anything is written. */
static int check_set(const vec_set *s, char *err, size_t errlen, const char *path)
{
    if (s->n_in < 1 || s->n_in > VEC_MAX_PORTS || s->n_out < 1 || s->n_out > VEC_MAX_PORTS) {
        msg(err, errlen, "%s: vector set has %d inputs and %d outputs (1..%d each)",
            path, s->n_in, s->n_out, VEC_MAX_PORTS);
        return -1;
    }
    if (!s->n_rows) {
        /* The reader refuses such a file; do not write one. */
        msg(err, errlen, "%s: no vector rows to write", path);
        return -1;
    }
    if (!s->unit[0]) {
        msg(err, errlen, "%s: vector set has no unit name", path);
        return -1;
    }
    for (size_t r = 0; r < s->n_rows; r++)
        for (int i = 0; i < s->n_in + s->n_out; i++)
            if (!isfinite(vec_row(s, r)[i])) {
                msg(err, errlen, "%s: row %zu has a non-finite value", path, r + 1);
                return -1;
            }
    return 0;
}

int vec_file_write(const char *path, const vec_set *s, char *err, size_t errlen)
{
    if (check_set(s, err, errlen, path)) return -1;
    if (!strcmp(path, "-")) {
        if (vec_file_print(stdout, s) || fflush(stdout)) {
            msg(err, errlen, "-: write error: %s", strerror(errno));
            return -1;
        }
        return 0;
    }
    /* Temporary next to the target so that rename() is atomic: a reader
     * never sees a half-written file under the final name. */
    size_t len = strlen(path);
    char *tmp = malloc(len + sizeof ".tmp-XXXXXX");
    if (!tmp) {
        msg(err, errlen, "%s: out of memory", path);
        return -1;
    }
    memcpy(tmp, path, len);
    memcpy(tmp + len, ".tmp-XXXXXX", sizeof ".tmp-XXXXXX");
    int fd = mkstemp(tmp);
    if (fd < 0) {
        msg(err, errlen, "%s: cannot create: %s", path, strerror(errno));
        free(tmp);
        return -1;
    }
    /* mkstemp makes the file 0600; a vector file is for sharing. Keep
     * the mode of a file being replaced, else rw-r--r--. (umask cannot be
     * read without changing it, which is not thread-safe.) */
    struct stat st;
    (void)fchmod(fd, stat(path, &st) == 0 ? (st.st_mode & 07777) : 0644);
    FILE *f = fdopen(fd, "w");
    if (!f) {
        msg(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        unlink(tmp);
        free(tmp);
        return -1;
    }
    errno = 0;
    int bad = vec_file_print(f, s);
    int e = errno;
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (bad) {
        msg(err, errlen, "%s: write error: %s", path, strerror(e ? e : EIO));
    } else if (rename(tmp, path) != 0) {
        bad = 1;
        msg(err, errlen, "%s: cannot rename into place: %s", path, strerror(errno));
    }
    if (bad) unlink(tmp);
    free(tmp);
    return bad ? -1 : 0;
}

/* ---- reading --------------------------------------------------------- */

typedef struct reader {
    FILE *f;
    const char *path;
    long line;              /* number of the line in buf */
    char *buf;              /* VEC_LINE_MAX + 1 bytes */
    char *err;
    size_t errlen;
} reader;

static int fail(reader *r, const char *fmt, ...)
{
    if (!r->err || !r->errlen) return -1;
    int n = snprintf(r->err, r->errlen, "%s:%ld: ", r->path, r->line);
    if (n >= 0 && (size_t)n < r->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(r->err + n, r->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* Next line into r->buf without its end (LF or CRLF). 1 for a line, 0 at
 * the end of the file, -1 on error (message set). */
static int next_line(reader *r)
{
    int c;
    size_t n = 0;
    c = getc_unlocked(r->f);
    if (c == EOF) {
        if (ferror(r->f)) {
            r->line++;
            return fail(r, "read error: %s", strerror(errno));
        }
        return 0;
    }
    r->line++;
    for (; c != EOF && c != '\n'; c = getc_unlocked(r->f)) {
        if (c == '\r') {            /* CRLF, or a CR at the very end */
            int d = getc_unlocked(r->f);
            if (d == '\n' || d == EOF) { c = d; break; }
            return fail(r, "binary data (carriage return inside a line)");
        }
        if (c == 0 || c == 0x7f || (c < 0x20 && c != '\t'))
            return fail(r, "binary data (byte 0x%02x)", c);
        if (n == VEC_LINE_MAX)
            return fail(r, "line longer than %d bytes", VEC_LINE_MAX);
        r->buf[n++] = (char)c;
    }
    if (c == EOF && ferror(r->f)) return fail(r, "read error: %s", strerror(errno));
    r->buf[n] = 0;
    return 1;
}

static int is_space(char c) { return c == ' ' || c == '\t'; }
static char *skip_space(char *p) { while (is_space(*p)) p++; return p; }

/* Cut the next whitespace-separated token out of *p (NUL-terminates it);
 * NULL when there is none. */
static char *token(char **p)
{
    char *s = skip_space(*p);
    if (!*s) { *p = s; return NULL; }
    char *e = s;
    while (*e && !is_space(*e)) e++;
    if (*e) *e++ = 0;
    *p = e;
    return s;
}

/* A token for a message: at most 20 characters, "..." when cut. */
static const char *shorten(const char *tok, char out[32])
{
    if (strlen(tok) <= 20) return tok;
    snprintf(out, 32, "%.20s...", tok);
    return out;
}

static int valid_name(const char *s)
{
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
              (*s >= '0' && *s <= '9') || *s == '_'))
            return 0;
    return 1;
}

/* "# inputs: a b c" -> names. */
static int parse_names(reader *r, char *p, const char *key, int *n, char names[][16])
{
    char *tok, cut[32];
    *n = 0;
    while ((tok = token(&p))) {
        if (*n == VEC_MAX_PORTS)
            return fail(r, "too many %s (more than %d)", key, VEC_MAX_PORTS);
        if (!valid_name(tok))
            return fail(r, "bad port name '%s' in %s (letters, digits, '_')", shorten(tok, cut), key);
        if (strlen(tok) > 15)
            return fail(r, "port name '%s' too long (max 15 characters)", shorten(tok, cut));
        for (int i = 0; i < *n; i++)
            if (!strcmp(names[i], tok)) return fail(r, "duplicate port name '%s' in %s", tok, key);
        memcpy(names[*n], tok, strlen(tok) + 1);
        (*n)++;
    }
    if (*n == 0) return fail(r, "no %s named", key);
    return 0;
}

/* "a b c" for a message. */
static void join_names(char *out, size_t outlen, int n, const char names[][16])
{
    size_t used = 0;
    out[0] = 0;
    for (int i = 0; i < n && used < outlen; i++) {
        int k = snprintf(out + used, outlen - used, "%s%s", i ? " " : "", names[i]);
        if (k < 0) break;
        used += (size_t)k;
    }
}

static int same_names(int n, const char a[][16], int m, const char b[][16])
{
    if (n != m) return 0;
    for (int i = 0; i < n; i++)
        if (strcmp(a[i], b[i])) return 0;
    return 1;
}

/* Header comment: "# unit: x", "# inputs: ...", "# outputs: ...". Other
 * comments are ignored. seen: bit 0 unit, 1 inputs, 2 outputs. */
static int parse_comment(reader *r, char *p, vec_set *s, const vec_set *expect,
                         unsigned *seen, int rows_started)
{
    static const char *const keys[] = { "unit:", "inputs:", "outputs:" };
    p = skip_space(p + 1);
    int k = -1;
    for (int i = 0; i < 3; i++)
        if (!strncmp(p, keys[i], strlen(keys[i]))) { k = i; p += strlen(keys[i]); break; }
    if (k < 0) return 0;
    const char *key = k == 0 ? "unit" : k == 1 ? "inputs" : "outputs";
    if (rows_started) return fail(r, "'# %s:' header after the first vector row", key);
    if (*seen & (1u << k)) return fail(r, "duplicate '# %s:' header", key);
    *seen |= 1u << k;
    char buf[512], cut[32];
    if (k == 0) {
        char *name = token(&p);
        if (!name) return fail(r, "empty unit name");
        if (token(&p)) return fail(r, "unit name must be one word");
        if (strlen(name) >= sizeof s->unit)
            return fail(r, "unit name '%s' too long (max %zu characters)",
                        shorten(name, cut), sizeof s->unit - 1);
        memcpy(s->unit, name, strlen(name) + 1);
        if (expect && expect->unit[0] && strcmp(expect->unit, s->unit))
            return fail(r, "file is for unit '%s', expected '%s'", s->unit, expect->unit);
        return 0;
    }
    int *n = k == 1 ? &s->n_in : &s->n_out;
    char (*names)[16] = k == 1 ? s->in_names : s->out_names;
    if (parse_names(r, p, key, n, names)) return -1;
    if (expect) {
        int en = k == 1 ? expect->n_in : expect->n_out;
        const char (*enames)[16] = k == 1 ? expect->in_names : expect->out_names;
        if (en > 0 && !same_names(*n, (const char (*)[16])names, en, enames)) {
            char want[VEC_MAX_PORTS * 16 + 1];
            join_names(buf, sizeof buf, *n, (const char (*)[16])names);
            join_names(want, sizeof want, en, enames);
            return fail(r, "%s are '%s', expected '%s'", key, buf, want);
        }
    }
    return 0;
}

/* One number; the whole token must be a finite real. */
static int parse_num(reader *r, const char *tok, double *out)
{
    char cut[32], *end;
    errno = 0;
    double v = strtod(tok, &end);
    if (end == tok || *end)
        return fail(r, "not a number: '%s'", shorten(tok, cut));
    if (isnan(v)) return fail(r, "NaN is not a valid value: '%s'", shorten(tok, cut));
    if (!isfinite(v)) return fail(r, "infinite value: '%s'", shorten(tok, cut));
    *out = v;
    return 0;
}

/* Numbers of one side of a row into v; found vs want counted in full. */
static int parse_side(reader *r, char *p, const char *side, int want, double *v)
{
    char *tok;
    int found = 0;
    while ((tok = token(&p))) {
        if (found < want && parse_num(r, tok, &v[found])) return -1;
        found++;
    }
    if (found != want)
        return fail(r, "found %d %s, expected %d", found, side, want);
    return 0;
}

static int parse_row(reader *r, char *p, vec_set *s, unsigned seen)
{
    static const char *const what[] = { "# unit:", "# inputs:", "# outputs:" };
    for (int k = 0; k < 3; k++)
        if (!(seen & (1u << k)))
            return fail(r, "missing '%s' header before the first vector row", what[k]);
    char *bar = strchr(p, '|');
    if (!bar) return fail(r, "missing '|' between inputs and outputs");
    if (strchr(bar + 1, '|')) return fail(r, "more than one '|'");
    *bar = 0;
    double v[2 * VEC_MAX_PORTS];
    if (parse_side(r, p, "inputs", s->n_in, v)) return -1;
    if (parse_side(r, bar + 1, "outputs", s->n_out, v + s->n_in)) return -1;
    if (vec_set_push(s, v)) return fail(r, "out of memory");
    return 0;
}

static int read_all(reader *r, vec_set *s, const vec_set *expect)
{
    int got, magic = 0, rows_started = 0;
    unsigned seen = 0;
    while ((got = next_line(r)) > 0) {
        char *p = skip_space(r->buf);
        if (!*p) continue;
        if (!magic) {
            /* The first non-blank line says what this file is. */
            char *q = p;
            char *t1 = *q == '#' ? (q++, token(&q)) : NULL;
            char *t2 = t1 ? token(&q) : NULL;
            char *t3 = t2 ? token(&q) : NULL;
            if (!t1 || strcmp(t1, "shadesim") || !t2 || strcmp(t2, "vectors") || !t3)
                return fail(r, "not a shadesim vector file (the first line must be '# " VEC_MAGIC "')");
            if (strcmp(t3, "1") || token(&q))
                return fail(r, "unsupported vector file version (expected '# " VEC_MAGIC "')");
            magic = 1;
            continue;
        }
        if (*p == '#') {
            if (parse_comment(r, p, s, expect, &seen, rows_started)) return -1;
            continue;
        }
        rows_started = 1;
        if (parse_row(r, p, s, seen)) return -1;
    }
    if (got < 0) return -1;
    if (r->line == 0) r->line = 1;
    if (!magic) return fail(r, "empty file (expected '# " VEC_MAGIC "')");
    if (!s->n_rows) return fail(r, "no vector rows");
    return 0;
}

int vec_file_read(const char *path, vec_set *s, const vec_set *expect,
                  char *err, size_t errlen)
{
    vec_set_init(s);
    int is_stdin = !strcmp(path, "-");
    reader r = { NULL, is_stdin ? "<stdin>" : path, 0, NULL, err, errlen };
    r.f = is_stdin ? stdin : fopen(path, "rb");
    if (!r.f) {
        msg(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    r.buf = malloc(VEC_LINE_MAX + 1);
    int rc = r.buf ? read_all(&r, s, expect) : (msg(err, errlen, "%s: out of memory", path), -1);
    free(r.buf);
    if (!is_stdin) fclose(r.f);
    if (rc) vec_set_free(s);
    return rc;
}
