/* base_line.c - bounded line reading (see base_line.h).
 * getc_unlocked: a line reader owns its stream (no other thread reads
 * it), and the locked getc costs several times more per byte. */
#include "base/base_out.h"
#include "base/base_line.h"
#include <errno.h>
#include <stdlib.h>
#include <string.h>

long base_line_read(FILE *f, char *buf, size_t max)
{
    size_t n = 0;
    int c;
    errno = 0;
    while ((c = getc_unlocked(f)) != EOF) {
        if (c == '\n') { buf[n] = 0; return (long)n; }
        if (c == 0) return BASE_LINE_NUL;
        if (n == max) return BASE_LINE_LONG;
        buf[n++] = (char)c;
    }
    if (ferror(f)) { if (!errno) errno = EIO; return BASE_LINE_ERR; }
    if (!n) return BASE_LINE_EOF;
    buf[n] = 0;
    return (long)n;
}

char *base_text_read(const char *path, size_t max_line, size_t *len, char *err, size_t errlen)
{
    int is_stdin = !strcmp(path, "-");
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f) { snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno)); return NULL; }
    size_t cap = 1 << 16, n = 0, line_start = 0, lineno = 1;
    char *b = malloc(cap);
    char *ret = NULL;
    for (;;) {
        if (!b) base_out_of_memory();
        size_t k = fread(b + n, 1, cap - n - 1, f);
        /* Check what just arrived: NULs, and each line's length. */
        char *nul = memchr(b + n, 0, k);
        size_t upto = nul ? (size_t)(nul - b) : n + k;
        for (char *q = b + n; (q = memchr(q, '\n', (size_t)(b + upto - q))); q++) {
            line_start = (size_t)(q - b) + 1;
            lineno++;
        }
        if (nul) {
            snprintf(err, errlen, "%s:%zu: not a text file (NUL byte)", path, lineno);
            break;
        }
        n += k;
        if (n - line_start > max_line) {
            snprintf(err, errlen, "%s:%zu: line longer than %zu bytes", path, lineno, max_line);
            break;
        }
        if (k == 0 || n < cap - 1) {
            if (ferror(f)) {
                snprintf(err, errlen, "%s: read error: %s", path, strerror(errno ? errno : EIO));
                break;
            }
            if (feof(f)) { b[n] = 0; *len = n; ret = b; b = NULL; break; }
            continue;               /* a short read from a pipe or FIFO */
        }
        /* Room for what a line may still need, no more: memory follows
         * the file, not a runaway line. */
        char *nb = realloc(b, cap * 2);
        if (!nb) free(b);
        b = nb;
        cap *= 2;
    }
    free(b);
    if (!is_stdin) fclose(f);
    return ret;
}
