/* tst_num.h - a corpus of decimal strings for comparing base_strtod with
 * strtod (tests/test_strtod.c: a lean corpus; bench/bench_strtod.c: ten
 * million). Deterministic: string i of a seed is always the same.
 *
 * Kinds, drawn in turn:
 *  - random doubles (random bits: every binade, subnormals included) in
 *    %.17g (what vector files hold) and %.Ng for N in 1..25 (long and
 *    short mantissas);
 *  - random decimal strings: 1..24 digits, a point anywhere, exponents
 *    mostly near 0, sometimes near the limits (+-300..+-345);
 *  - exact halfway cases between two doubles (c * 5^q * 2^t, c odd of
 *    54 bits written as w e q; and (2M+1) 5^k 2^j / 10^k with a point)
 *    and their neighbours one unit of the last digit away;
 *  - fixed oddities (tst_num_fixed): signs, lone points, "1e", hex,
 *    inf/nan, blanks, the extremes of the double range.
 */
#ifndef TST_NUM_H
#define TST_NUM_H
#include <stdint.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include "base/base_strtod.h"

static const char *const tst_num_fixed[] = {
    "0", "-0", "+0", "0.0", "-0.0", "00000", "0e999999", "-0e-999999", "1e", "1e+", "1e-", "1E5", "1e+5",
    ".5", "5.", ".", "-", "+", "", " 1", "\t2", "-.5e-3", "+.5E+3", "0x1p3", "0X10", "inf", "-Infinity",
    "nan", "NAN(123)", "1.5|2", "1,5", "1e400", "-1e400", "1e-400", "4.9e-324", "2.4703282292062327e-324",
    "2.4703282292062328e-324", "2.2250738585072014e-308", "2.2250738585072011e-308",
    "1.7976931348623157e308", "1.7976931348623158e308", "1.7976931348623159e308", "9007199254740993",
    "9007199254740992.5", "9007199254740993.0000000001", "4503599627370496.5", "4503599627370497.5",
    "123456789012345678901234567890", "0.000000000000000000000000000000000001", "1e-27", "1e27", "1e28",
    "1e-28", "9999999999999999999e27", "9999999999999999999e-27", "99999999999999999999",
    "10000000000000000000", "18446744073709551615", "18446744073709551616", "1.5 ", "1.5\t", "1.5\n",
    "1.5|", "1.5x", "1.5e3x", "1..5", "--1", "+-1", "1e0000000000000000000005", "1e-0000000000000000005",
    "0.1", "0.2", "0.3", "1e23", "8.98846567431158e307", "7.2057594037927933e16", "1e-22", "1e22",
    "12345678901234567e-27", "12345678901234567e27", "3.0517578125e-05", "0.000030517578125",
};
#define TST_NUM_NFIXED (sizeof tst_num_fixed / sizeof tst_num_fixed[0])

static uint64_t tst_num_rand(uint64_t *s)
{
    /* splitmix64 */
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static int tst_num_bits(uint64_t x) { return x ? 64 - __builtin_clzll(x) : 0; }

/* String number i of the corpus of a seed into buf (at least 96 bytes). */
static void tst_num_make(uint64_t seed, uint64_t i, char *buf, size_t len)
{
    uint64_t st = seed * 0x9e3779b97f4a7c15u + i;
    uint64_t r = tst_num_rand(&st);
    switch (i % 6) {
    case 0: case 1: {                         /* a random double */
        uint64_t b = tst_num_rand(&st);
        double x;
        memcpy(&x, &b, sizeof x);
        if (x != x || x - x != 0) x = (double)(int64_t)b * 0x1p-40;   /* not nan / inf */
        int prec = i % 6 == 0 ? 17 : 1 + (int)(r % 25);
        snprintf(buf, len, "%.*g", prec, x);
        break;
    }
    case 2: case 3: {                         /* random digits, point, exponent */
        char *p = buf;
        int nd = 1 + (int)(r % 24), pt = (int)((r >> 8) % (uint64_t)(nd + 2)) - 1;
        if ((r >> 16) & 1) *p++ = '-';
        for (int k = 0; k < nd; k++) {
            if (k == pt) *p++ = '.';
            int d = (int)(tst_num_rand(&st) % 10);
            if (k == 0 && (r >> 17) % 4) d = 1 + d % 9;
            *p++ = (char)('0' + d);
        }
        if (pt == nd) *p++ = '.';
        int ek = (int)((r >> 24) % 8);
        if (ek < 5) {
            int e = (int)((r >> 32) % 61) - 30;
            if (ek) p += snprintf(p, len - (size_t)(p - buf), "e%d", e);
        } else {
            int e = (int)((r >> 32) % 46) + 300;
            p += snprintf(p, len - (size_t)(p - buf), "e%s%d", ek == 5 ? "-" : "", e);
        }
        *p = 0;
        break;
    }
    case 4: {                                 /* halfway, q >= 0: c 5^q 2^t, c odd, c 5^q of 54 bits */
        int q = (int)(r % 24);                /* 5^24 has more than 54 bits */
        uint64_t p5 = 1;
        for (int k = 0; k < q; k++) p5 *= 5;
        int b5 = tst_num_bits(p5);
        int cb = 55 - b5;                     /* c of cb bits: c 5^q has 53 to 55 bits */
        uint64_t c = 1;
        for (int tries = 0; tries < 64; tries++) {
            c = cb > 1 ? (tst_num_rand(&st) >> (64 - cb)) | ((uint64_t)1 << (cb - 1)) : 1;
            c |= 1;
            unsigned __int128 n = (unsigned __int128)c * p5;
            int nb = (n >> 64) ? 64 + tst_num_bits((uint64_t)(n >> 64)) : tst_num_bits((uint64_t)n);
            if (nb == 54) break;
        }
        int t = (int)((r >> 8) % (uint64_t)(64 - tst_num_bits(c)));
        unsigned __int128 w = (unsigned __int128)c << t;
        while (w >= (unsigned __int128)10000000000000000000u) w >>= 1;
        uint64_t wv = (uint64_t)w;
        int nb = (int)((r >> 20) % 3);        /* exact, one below, one above */
        if (nb == 1 && wv > 1) wv--;
        if (nb == 2) wv++;
        snprintf(buf, len, "%s%llue%d", (r >> 30) & 1 ? "-" : "", (unsigned long long)wv, q);
        break;
    }
    default:
        if ((r >> 40) & 1) {                  /* within one unit of the 19th digit of a halfway case */
            uint64_t m = ((tst_num_rand(&st) >> 11) | ((uint64_t)1 << 53)) | 1;   /* odd, 54 bits */
            int e = (int)((r >> 4) % 100) - 90;   /* h = m 2^e: up to 10^-27 h in [10^18, 10^19) */
            snprintf(buf, len, "%llu", (unsigned long long)m);
            for (int k = 0; k < 40; k++) {
                /* h 10^k = m 5^k 2^(e+k) in [10^18, 10^19): its floor or ceiling */
                unsigned __int128 v = m;
                for (int z = 0; z < k; z++) v *= 5;
                int sh = e + k;
                if (sh > 0) { if (sh > 60 || (v >> (127 - sh))) break; v <<= sh; }
                unsigned __int128 fl = sh >= 0 ? v : v >> -sh;
                int inexact = sh < 0 && (v & (((unsigned __int128)1 << -sh) - 1));
                if (fl >= (unsigned __int128)10000000000000000000u) break;
                if (fl < (unsigned __int128)1000000000000000000u) continue;
                uint64_t w = (uint64_t)fl + (uint64_t)(inexact && ((r >> 41) & 1));
                snprintf(buf, len, "%llue-%d", (unsigned long long)w, k);
                break;
            }
            break;
        }
        {                                     /* halfway, q < 0: (2M+1) 5^k 2^j with k decimals */
            int k = 1 + (int)(r % 3), j = (int)((r >> 4) % 3);
            uint64_t m = ((tst_num_rand(&st) >> 11) | ((uint64_t)1 << 53)) | 1;   /* odd, 54 bits */
            unsigned __int128 w = m;
            for (int z = 0; z < k; z++) w *= 5;
            w <<= j;
            while (w >= (unsigned __int128)10000000000000000000u) w >>= 1;
            uint64_t wv = (uint64_t)w;
            int nb = (int)((r >> 20) % 3);
            if (nb == 1) wv--;
            if (nb == 2) wv++;
            char d[32];
            int n = snprintf(d, sizeof d, "%llu", (unsigned long long)wv);
            snprintf(buf, len, "%.*s.%s", n - k, d, d + n - k);
            break;
        }
    }
    if (i < TST_NUM_NFIXED) snprintf(buf, len, "%s", tst_num_fixed[i]);
}

/* Compare one string: 0 when base_strtod, its exact path alone
 * (base_strtod_exact), its padded reading (base_strtod_padded) and
 * strtod agree on the value's bits and the end
 * pointer, else a message in why. */
static int tst_num_check(const char *s, char *why, size_t len)
{
    char *e1, *e2, *e3;
    double a = base_strtod(s, &e1);
    double b = strtod(s, &e2);
    double c = base_strtod_exact(s, &e3);
    /* the padded reading on a copy in a buffer exactly BASE_STRTOD_PAD bytes
     * longer than the string (ASan sees a read past it) */
    size_t n = strlen(s) + 1;
    char *cp = malloc(n + BASE_STRTOD_PAD), *e4;
    if (!cp) { snprintf(why, len, "out of memory"); return -1; }
    memcpy(cp, s, n);
    memset(cp + n, '9', BASE_STRTOD_PAD);     /* digits: must not be read as such */
    double d = base_strtod_padded(cp, &e4);
    long o4 = e4 - cp;
    free(cp);
    uint64_t ba, bb, bc, bd;
    memcpy(&ba, &a, sizeof a);
    memcpy(&bb, &b, sizeof b);
    memcpy(&bc, &c, sizeof c);
    memcpy(&bd, &d, sizeof d);
    if (ba == bb && bc == bb && bd == bb && e1 == e2 && e3 == e2 && o4 == e2 - s) return 0;
    snprintf(why, len, "'%s': %a (end +%d), exact path %a (end +%d), padded %a (end +%ld), against strtod's %a (end +%d)",
             s, a, (int)(e1 - s), c, (int)(e3 - s), d, o4, b, (int)(e2 - s));
    return -1;
}
#endif
