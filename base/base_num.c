/* base_num.c - strict decimal numbers (see base_num.h). strtod and
 * strtoll do the conversion only after the syntax is checked here: alone
 * they take leading spaces, '+', hexadecimal ("0x0.8"), inf and nan. */
#include "base/base_num.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>

static const char *digits(const char *s) { while (*s >= '0' && *s <= '9') s++; return s; }

int base_num_is_real(const char *s)
{
    if (*s == '-') s++;
    const char *a = digits(s);
    int n = (int)(a - s);
    s = a;
    if (*s == '.') { a = digits(++s); n += (int)(a - s); s = a; }
    if (!n) return 0;
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '-' || *s == '+') s++;
        a = digits(s);
        if (a == s) return 0;
        s = a;
    }
    return !*s;
}

int base_num_real(const char *s, int neg_ok, double *out)
{
    if (!base_num_is_real(s) || (*s == '-' && !neg_ok)) return -1;
    errno = 0;
    double v = strtod(s, NULL);
    if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1)) return -1;
    *out = v;
    return 0;
}

int base_num_whole(const char *s, int neg_ok, long long *out)
{
    const char *d = s + (*s == '-' && neg_ok);
    const char *e = digits(d);
    if (e == d || *e) return -1;
    errno = 0;
    long long v = strtoll(s, NULL, 10);
    if (errno) return -1;
    *out = v;
    return 0;
}
