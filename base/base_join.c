/* base_join.c - lists of names for messages (see base_join.h). */
#include "base/base_join.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* s onto buf at *k, cut to fit; -1 when cut. */
static int put(char *buf, size_t cap, size_t *k, const char *s)
{
    size_t n = strlen(s), room = cap - 1 - *k;
    int cut = n > room;
    if (cut) n = room;
    memcpy(buf + *k, s, n);
    *k += n;
    buf[*k] = 0;
    return cut ? -1 : 0;
}

int base_join_add(char *buf, size_t cap, const char *sep, const char *item)
{
    if (!cap) return -1;
    size_t k = strnlen(buf, cap - 1);
    int rc = 0;
    if (k && sep) rc = put(buf, cap, &k, sep);
    if (put(buf, cap, &k, item ? item : "")) rc = -1;
    return rc;
}

int base_join_addf(char *buf, size_t cap, const char *sep, const char *fmt, ...)
{
    char item[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(item, sizeof item, fmt, ap);
    va_end(ap);
    int rc = base_join_add(buf, cap, sep, n < 0 ? "" : item);
    return n < 0 || (size_t)n >= sizeof item ? -1 : rc;
}
