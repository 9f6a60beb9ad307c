/* vec_file.c - golden vector files (docs/cli.md): a strict reader and an atomic
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
#define _GNU_SOURCE     /* F_SETPIPE_SZ (Linux), where fcntl.h has it */
#include "vectors/vec_file.h"
#include "vectors/vec_gen.h"
#include "base/base_strtod.h"
#include "base/base_out.h"
#include "base/base_par.h"
#include "base/base_mem.h"
#include "base/base_pool.h"
#include "base/base_join.h"
#include <errno.h>
#include <fcntl.h>
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
    /* base_out: a temporary beside a regular file, renamed when complete
     * (a reader never sees half a file); devices and FIFOs written
     * through; "-" is stdout. */
    base_out *o = base_out_open(path, err, errlen);
    if (!o) return -1;
    (void)vec_file_print(base_out_file(o), s);  /* an error is kept in the stream */
    return base_out_close(o, err, errlen);
}

/* ---- reading ---------------------------------------------------------
 *
 * The file is read in large blocks (no per-character stdio call). One
 * pass over a line, eight bytes at a time, finds its end and any byte
 * that is not allowed; the line is cut out of the block in place and its
 * numbers parsed straight from it by base_strtod_padded (strtod's results,
 * faster; a token is only copied out for an error message). Once the
 * first row has been read, the rows of a large block are parsed by two
 * threads, each taking half of the block, joined in order. Every check,
 * its message and the line it names are those of a line-by-line,
 * character-by-character reading: the first problem in file order is the
 * one reported. */

typedef struct reader {
    const char *path;
    long line;              /* number of the line being parsed */
    char *err;
    size_t errlen;
    char why[512];          /* second thread: message without "PATH:LINE: " */
    int defer;              /* 1: fail() fills why only */
} reader;

static int fail(reader *r, const char *fmt, ...)
{
    va_list ap;
    if (r->defer) {
        va_start(ap, fmt);
        vsnprintf(r->why, sizeof r->why, fmt, ap);
        va_end(ap);
        return -1;
    }
    if (!r->err || !r->errlen) return -1;
    int n = snprintf(r->err, r->errlen, "%s:%ld: ", r->path, r->line);
    if (n >= 0 && (size_t)n < r->errlen) {
        va_start(ap, fmt);
        vsnprintf(r->err + n, r->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* The bytes of one line (without its LF) as a line-by-line reader takes
 * them, character by character: a CR must end the line (CRLF, or CR at
 * the end of the file), no other control byte but tab, at most
 * VEC_LINE_MAX bytes. The first offence in the line is reported. On
 * success the line is NUL-terminated in place (over its CR or LF, or on
 * the byte after the data, which the buffer keeps free). The common clean
 * line never comes here (do_lines). */
static int check_line(reader *r, char *s, size_t n)
{
    size_t kept = 0;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == '\r') {
            if (i + 1 == n) break;     /* CRLF, or a CR at the very end */
            return fail(r, "binary data (carriage return inside a line)");
        }
        if (c == 0 || c == 0x7f || (c < 0x20 && c != '\t'))
            return fail(r, "binary data (byte 0x%02x)", c);
        if (kept == VEC_LINE_MAX)
            return fail(r, "line longer than %d bytes", VEC_LINE_MAX);
        kept++;
    }
    s[kept] = 0;
    return 0;
}

/* The first byte of [p, e) below 0x20 other than tab, or 0x7f (a line's
 * end or a bad byte); e if none. Eight bytes at a time: a byte b < 0x20
 * sets the top bit of (b - 0x20) & ~b, a byte 0x7f makes a zero of
 * b ^ 0x7f; a borrow can only mark bytes above a true one, so the lowest
 * mark is exact. */
static char *first_control(char *p, char *e)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    const uint64_t ones = 0x0101010101010101u, high = 0x8080808080808080u;
    while (e - p >= 8) {
        uint64_t x, y;
        memcpy(&x, p, 8);
        y = x ^ (0x7f * ones);
        uint64_t m = (((x - 0x20 * ones) & ~x) | ((y - ones) & ~y)) & high;
        if (!m) { p += 8; continue; }
        char *q = p + __builtin_ctzll(m) / 8;   /* little-endian: lowest address */
        if (*q != '\t') return q;
        p = q + 1;
    }
#endif
    for (; p < e; p++) {
        unsigned char c = (unsigned char)*p;
        if ((c < 0x20 && c != '\t') || c == 0x7f) return p;
    }
    return e;
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
    out[0] = 0;
    for (int i = 0; i < n; i++) base_join_add(out, outlen, " ", names[i]);
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

/* One number at *pp, a token ending at a space, a tab or the end: the
 * whole token must be a finite real. base_strtod_padded (strtod's result, bit
 * for bit) reads it in place; only a token it refuses is cut out, for the
 * message. */
static int parse_num(reader *r, char **pp, double *out)
{
    char cut[32], *tok = *pp, *end;
    errno = 0;
    double v = base_strtod_padded(tok, &end);     /* in the padded block */
    if (end == tok || (*end && !is_space(*end))) {
        char *e = tok;
        while (*e && !is_space(*e)) e++;
        *e = 0;
        return fail(r, "not a number: '%s'", shorten(tok, cut));
    }
    if (!isfinite(v)) {
        *end = 0;
        if (isnan(v)) return fail(r, "NaN is not a valid value: '%s'", shorten(tok, cut));
        return fail(r, "infinite value: '%s'", shorten(tok, cut));
    }
    *out = v;
    *pp = end;
    return 0;
}

/* Numbers of one side of a row into v; found vs want counted in full. */
static int parse_side(reader *r, char *p, const char *side, int want, double *v)
{
    int found = 0;
    for (p = skip_space(p); *p; p = skip_space(p)) {
        if (found < want) {
            if (parse_num(r, &p, &v[found])) return -1;
        } else {
            while (*p && !is_space(*p)) p++;
        }
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
    if (vec_set_push(s, v)) base_out_of_memory();
    return 0;
}

/* State of a file being read, line by line in file order. */
typedef struct rstate {
    int magic, rows_started;
    unsigned seen;
} rstate;

/* One line (already checked and NUL-terminated) of the file. */
static int do_line(reader *r, char *line, vec_set *s, const vec_set *expect, rstate *st)
{
    char *p = skip_space(line);
    if (!*p) return 0;
    if (!st->magic) {
        /* The first non-blank line says what this file is. */
        char *q = p;
        char *t1 = *q == '#' ? (q++, token(&q)) : NULL;
        char *t2 = t1 ? token(&q) : NULL;
        char *t3 = t2 ? token(&q) : NULL;
        if (!t1 || strcmp(t1, "shadesim") || !t2 || strcmp(t2, "vectors") || !t3)
            return fail(r, "not a shadesim vector file (the first line must be '# " VEC_MAGIC "')");
        if (strcmp(t3, "1") || token(&q))
            return fail(r, "unsupported vector file version (expected '# " VEC_MAGIC "')");
        st->magic = 1;
        return 0;
    }
    if (*p == '#') return parse_comment(r, p, s, expect, &st->seen, st->rows_started);
    st->rows_started = 1;
    return parse_row(r, p, s, st->seen);
}

/* Lines [b, e) of a block, each ending in LF (the last may end at e only
 * when it is the end of the file). r->line counts them. */
static int do_lines(reader *r, char *b, char *e, vec_set *s, const vec_set *expect, rstate *st)
{
    while (b < e) {
        /* One pass finds the line's end and its bad bytes: a clean line
         * ends at the first control byte, its LF (or the end of the data,
         * where the buffer has room for the NUL). */
        char *q = first_control(b, e);
        r->line++;
        if ((q == e || *q == '\n') && q - b <= VEC_LINE_MAX) {
            *q = 0;
            if (do_line(r, b, s, expect, st)) return -1;
            b = q + 1;
            continue;
        }
        /* CR, bad bytes or too long: the exact per-character rules. */
        char *nl = memchr(q, '\n', (size_t)(e - q));
        char *end = nl ? nl : e;
        if (check_line(r, b, (size_t)(end - b))) return -1;
        if (do_line(r, b, s, expect, st)) return -1;
        b = end + 1;
    }
    return 0;
}

/* ---- two threads for the rows of a large block ---- */

#define VEC_PAR_MIN (1u << 18)   /* bytes of rows worth a second thread */

typedef struct half {
    reader r;                   /* line counts from 0 at the half's start */
    char *b, *e;
    vec_set *rows;
    rstate st;
    int rc;
} half;

/* What the reading of one file shares between blocks. */
typedef struct par {
    int ncpu;
    base_pool *pool;            /* NULL: a thread made for each block */
    vec_set rows;               /* the second thread's rows of a block */
} par;

/* The two halves of a block as the items of a parallel-for: item 0 is
 * the first half, read into the block's own set; item 1 the second. */
typedef struct halves {
    reader *r;
    char *b, *mid;
    vec_set *s;
    const vec_set *expect;
    rstate *st;
    int rc;                     /* item 0's */
    half h;                     /* item 1 */
} halves;

static void half_item(void *arg, size_t i)
{
    halves *t = arg;
    if (i == 0) t->rc = do_lines(t->r, t->b, t->mid, t->s, t->expect, t->st);
    else t->h.rc = do_lines(&t->h.r, t->h.b, t->h.e, t->h.rows, NULL, &t->h.st);
}

/* Append t's rows to s, growing s as vec_set_push does (doubling). */
static int append_rows(vec_set *s, const vec_set *t)
{
    size_t need = s->n_rows + t->n_rows, stride = (size_t)(s->n_in + s->n_out);
    if (!t->n_rows) return 0;
    if (need > s->cap_rows) {
        size_t cap = s->cap_rows ? s->cap_rows : 256;
        while (cap < need) cap *= 2;
        double *d = realloc(s->data, cap * stride * sizeof *d);
        if (!d) return -1;
        s->data = d;
        s->cap_rows = cap;
    }
    memcpy(vec_row(s, s->n_rows), t->data, t->n_rows * stride * sizeof *t->data);
    s->n_rows = need;
    return 0;
}

/* Rows region [b, e): once the first row has been read, every later line
 * is a row, a blank or a comment, each understood on its own, so the
 * region splits at a line boundary into halves parsed at once. */
static int do_rows(reader *r, char *b, char *e, vec_set *s, const vec_set *expect, rstate *st,
                   par *pp)
{
    size_t n = (size_t)(e - b);
    char *mid = n >= VEC_PAR_MIN && pp->ncpu > 1 ? memchr(b + n / 2, '\n', (size_t)(e - (b + n / 2))) : NULL;
    if (!mid || mid + 1 >= e) return do_lines(r, b, e, s, expect, st);
    mid++;
    halves t;
    memset(&t, 0, sizeof t);
    half *h = &t.h;
    h->r.path = r->path;
    h->r.defer = 1;
    h->b = mid; h->e = e;
    pp->rows.n_in = s->n_in;
    pp->rows.n_out = s->n_out;
    pp->rows.n_rows = 0;
    h->rows = &pp->rows;
    h->st = *st;
    t.r = r; t.b = b; t.mid = mid; t.s = s; t.expect = expect; t.st = st;
    if (pp->pool) base_pool_for(pp->pool, 2, half_item, &t);
    else base_par_for(2, 2, half_item, &t);
    if (t.rc) return t.rc;
    /* The second half's lines follow the first's. (Out of memory while
     * appending is reported on the half's last line.) */
    r->line += h->r.line;
    if (h->rc) return fail(r, "%s", h->r.why);
    if (append_rows(s, &pp->rows)) base_out_of_memory();
    return 0;
}

/* Lines of a block: one by one until the first row, then as rows. */
static int do_block(reader *r, char *b, char *e, vec_set *s, const vec_set *expect, rstate *st,
                    par *pp)
{
    while (b < e && !st->rows_started) {
        char *nl = memchr(b, '\n', (size_t)(e - b));
        char *end = nl ? nl : e;
        if (do_lines(r, b, end == e ? e : end + 1, s, expect, st)) return -1;
        b = end == e ? e : end + 1;
    }
    return b < e ? do_rows(r, b, e, s, expect, st, pp) : 0;
}

#define VEC_BLOCK (1u << 20)     /* bytes read at a time */

/* A file being read: the state read_all kept in locals, so that the rows
 * can be taken a block at a time (vec_stream_next) as well as all at once
 * (vec_file_read); both run the same steps, so the checks, messages and
 * line numbers are the same. */
struct vec_stream {
    reader r;
    FILE *f;
    int is_stdin;
    /* buf holds the unfinished line carried over plus one block. A line
     * that needs more than VEC_LINE_MAX + 2 bytes (CR, LF) is too long,
     * or has bad bytes before that: check_line finds which. */
    char *buf;
    size_t cap, len;
    int eof, done, failed, held;
    rstate st;
    par pp;
    const vec_set *expect;
    vec_set hdr_expect;         /* the stream's copy of expect */
    vec_set rows;               /* header and the rows of the last block */
    size_t total;               /* rows read so far */
    char err[600];
    vec_gen *gen;               /* vec_stream_gen: the rows come from it, not from f */
};

/* One block: read, cut at its last LF, parse its lines into s. 0, or -1
 * with the message. Sets done at the end of the file (after the checks a
 * whole file gets). */
static int read_step(vec_stream *v, vec_set *s)
{
    reader *r = &v->r;
    char *buf = v->buf;
    size_t cap = v->cap, len = v->len;
    size_t before = s->n_rows;
    int rerr = 0;
    /* A block's bytes at most, not the room left: a pipe holds a block
     * (F_SETPIPE_SZ below), and asking for more than it holds waits on
     * the writer at every block. The room left (the carried line's) is
     * still taken when it is less. */
    size_t want = cap - len < VEC_BLOCK ? cap - len : VEC_BLOCK;
    size_t k = fread(buf + len, 1, want, v->f);
    len += k;
    if (k < want) {                /* short read: end of file or error */
        v->eof = 1;
        if (ferror(v->f)) rerr = errno ? errno : EIO;
    }
    char *cut = v->eof ? buf + len : NULL;
    if (!v->eof) {
        /* Up to the last LF of the block; the rest waits for more. */
        char *q = buf + len;
        while (q > buf && q[-1] != '\n') q--;
        cut = q;
        if (cut == buf) {
            /* No LF in a block's bytes or more: a line too long (or
             * bad bytes before its end). */
            r->line++;
            if (check_line(r, buf, len) == 0) fail(r, "line longer than %d bytes", VEC_LINE_MAX);
            return -1;
        }
    }
    if (rerr) {
        /* Complete lines first, as a line-by-line reader would meet
         * them; then the characters of the unfinished line; then the
         * error, on the line it hit. */
        char *q = buf + len;
        while (q > buf && q[-1] != '\n') q--;
        if (do_block(r, buf, q, s, v->expect, &v->st, &v->pp)) return -1;
        r->line++;
        if (q < buf + len && check_line(r, q, (size_t)(buf + len - q))) return -1;
        return fail(r, "read error: %s", strerror(rerr));
    }
    if (do_block(r, buf, cut, s, v->expect, &v->st, &v->pp)) return -1;
    v->total += s->n_rows - before;
    len = (size_t)(buf + len - cut);
    memmove(buf, cut, len);
    v->len = len;
    if (v->eof) {
        v->done = 1;
        if (r->line == 0) r->line = 1;
        if (!v->st.magic) return fail(r, "empty file (expected '# " VEC_MAGIC "')");
        if (!v->total) return fail(r, "no vector rows");
    }
    return 0;
}

vec_stream *vec_stream_open(const char *path, const vec_set *expect, char *err, size_t errlen)
{
    vec_stream *v = calloc(1, sizeof *v);
    if (!v) base_out_of_memory();
    v->is_stdin = !strcmp(path, "-");
    v->r.path = v->is_stdin ? "<stdin>" : path;
    v->r.err = v->err;
    v->r.errlen = sizeof v->err;
    v->cap = VEC_BLOCK + VEC_LINE_MAX + 8;
    /* zeroed, and BASE_STRTOD_PAD bytes longer: base_strtod_padded reads
     * digits eight bytes at a time, up to seven past a line's end */
    v->buf = calloc(v->cap + 1 + BASE_STRTOD_PAD, 1);
    if (!v->buf) base_out_of_memory();
    base_mem_populate(v->buf, v->cap + 1 + BASE_STRTOD_PAD);   /* the first block fills it */
    v->f = v->is_stdin ? stdin : fopen(path, "rb");
#ifdef F_SETPIPE_SZ
    /* A pipe of a block's size instead of 64 KiB: the writer runs a block
     * ahead and the reader wakes once a block, not sixteen times (a pipe
     * of 10^7 rows read on two threads spent a fifth of its time waiting
     * on it). Not a pipe, or not allowed: nothing changes. */
    if (v->is_stdin) (void)fcntl(fileno(stdin), F_SETPIPE_SZ, (int)VEC_BLOCK);
#endif
    if (!v->f) {
        msg(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        if (v->f && !v->is_stdin) fclose(v->f);
        free(v->buf);
        free(v);
        return NULL;
    }
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    v->pp.ncpu = ncpu > 1 ? 2 : 1;
    vec_set_init(&v->pp.rows);
    vec_set_init(&v->rows);
    if (expect) { v->hdr_expect = *expect; v->hdr_expect.data = NULL; v->hdr_expect.n_rows = v->hdr_expect.cap_rows = 0; v->expect = &v->hdr_expect; }
    errno = 0;
    return v;
}

/* A generated stream's next rows into `into` (which trades its buffer
 * with the generator's). */
static int gen_step(vec_stream *v, vec_set *into)
{
    int rc = vec_gen_next(v->gen, into);
    if (rc < 0) { v->failed = 1; msg(v->err, sizeof v->err, "%s: cannot generate vectors", v->rows.unit); }
    if (rc == 0) v->done = 1;   /* (a generator's end is known only here) */
    return rc;
}

int vec_stream_next(vec_stream *v, const vec_set **rows)
{
    *rows = &v->rows;
    if (v->held) { v->held = 0; return v->rows.n_rows ? 1 : 0; }
    v->rows.n_rows = 0;
    if (v->failed) return -1;
    if (v->gen) return gen_step(v, &v->rows);
    while (!v->done && !v->rows.n_rows)
        if (read_step(v, &v->rows)) { v->failed = 1; v->rows.n_rows = 0; return -1; }
    return v->rows.n_rows ? 1 : 0;
}

int vec_stream_append(vec_stream *v, vec_set *dst)
{
    size_t before = dst->n_rows;
    if (v->gen && !v->held && !v->failed) {
        /* through a scratch set, the stream's own left as it is */
        int rc = gen_step(v, &v->pp.rows);
        if (rc > 0 && append_rows(dst, &v->pp.rows)) base_out_of_memory();
        return rc;
    }
    if (v->held || v->failed) {
        const vec_set *rows;
        int rc = vec_stream_next(v, &rows);
        if (rc > 0 && append_rows(dst, rows)) base_out_of_memory();
        return rc;
    }
    v->rows.n_rows = 0;
    while (!v->done && dst->n_rows == before)
        if (read_step(v, dst)) { v->failed = 1; dst->n_rows = before; return -1; }
    return dst->n_rows > before;
}

void vec_stream_unread(vec_stream *v) { if (!v->failed) v->held = 1; }

const char *vec_stream_error(const vec_stream *v) { return v->err; }

int vec_stream_done(const vec_stream *v) { return v->done && !v->held; }

void vec_stream_threads(vec_stream *v, int n)
{
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    v->pp.ncpu = n > 1 && ncpu > 1 ? 2 : 1;
}

void vec_stream_pool(vec_stream *v, base_pool *p) { v->pp.pool = p; }

void vec_stream_close(vec_stream *v)
{
    if (!v) return;
    vec_gen_close(v->gen);
    if (!v->is_stdin && v->f) fclose(v->f);
    free(v->buf);
    vec_set_free(&v->pp.rows);
    vec_set_free(&v->rows);
    free(v);
}

vec_stream *vec_stream_gen(const vec_model *m, const vec_params *p, size_t n, uint64_t seed, const vec_set *expect,
                           char *err, size_t errlen)
{
    vec_stream *v = calloc(1, sizeof *v);
    if (!v) base_out_of_memory();
    vec_set_init(&v->pp.rows);
    vec_set_init(&v->rows);
    vec_set_header(&v->rows, m, p);
    if (expect && (strcmp(expect->unit, v->rows.unit) || expect->n_in != v->rows.n_in || expect->n_out != v->rows.n_out)) {
        msg(err, errlen, "%s's generator does not give %s's vectors", m->name, expect->unit);
        free(v);
        return NULL;
    }
    if (!(v->gen = vec_gen_open(m, p, n, seed, &v->rows))) base_out_of_memory();
    return v;
}

int vec_file_read(const char *path, vec_set *s, const vec_set *expect,
                  char *err, size_t errlen)
{
    vec_set_init(s);
    vec_stream *v = vec_stream_open(path, expect, err, errlen);
    if (!v) return -1;
    int rc = 0;
    while (!v->done)
        if (read_step(v, s)) { rc = -1; break; }
    if (rc) { msg(err, errlen, "%s", v->err); vec_set_free(s); }
    vec_stream_close(v);
    return rc;
}
