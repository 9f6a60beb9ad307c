/* base_strtod.c - decimal to double: an exact fast path, strtod for the rest.
 *
 * A decimal w * 10^q with w < 10^19 (19 significant digits at most) and
 * |q| <= 27 is w * 5^q * 2^q, and 5^|q| < 2^63 fits one word:
 *  - q >= 0: N = w * 5^q is an exact 128-bit integer;
 *  - q < 0:  N = floor(w * 2^s / 5^-q) with s chosen so that N has at
 *    least 64 significant bits, plus a sticky bit (remainder nonzero).
 * Rounding N (and the sticky bit) to 53 bits, to nearest with ties to
 * even, is then the correctly rounded double of the decimal, which is what
 * glibc's strtod gives; the binary exponent 2^q or 2^(q-s) is put in the
 * result's exponent field (the values reachable here, 10^-127 to 10^46,
 * are far from subnormals and infinity). For -108 <= q < -27 (vector
 * files hold many tiny values) 5^-q takes more than a word: N is the
 * same floor, w * 2^s held in a few words and divided by 5^27 and then
 * by the rest of 5^-q, one word at a time. Before that, Clinger's fast path:
 * w <= 2^53 and |q| <= 22 make w and 10^|q| exact doubles, so one IEEE
 * multiply or divide rounds correctly.
 *
 * Anything else -- more digits, larger exponents, hexadecimal, inf/nan,
 * leading blanks, a number followed by an unusual character -- goes to
 * strtod, so the value and the end pointer are always strtod's.
 */
#include "base/base_strtod.h"
#include <float.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const uint64_t pow5[28] = {
    1u, 5u, 25u, 125u, 625u, 3125u, 15625u, 78125u, 390625u, 1953125u, 9765625u, 48828125u,
    244140625u, 1220703125u, 6103515625u, 30517578125u, 152587890625u, 762939453125u,
    3814697265625u, 19073486328125u, 95367431640625u, 476837158203125u, 2384185791015625u,
    11920928955078125u, 59604644775390625u, 298023223876953125u, 1490116119384765625u,
    7450580596923828125u
};

static const double pow10d[23] = {
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22
};

__extension__ typedef unsigned __int128 u128;

/* Decimal exponents down to -BIG_Q take the exact path through a few
 * words (small_quotient); w 2^s then has at most 65 + 2.33 BIG_Q bits. */
#define BIG_Q 108
#define BIG_WORDS 7

static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* Significant bits of n > 0. */
static int bits128(u128 n)
{
    uint64_t hi = (uint64_t)(n >> 64);
    return hi ? 128 - __builtin_clzll(hi) : 64 - __builtin_clzll((uint64_t)n);
}

/* m * 2^e2, m in [2^52, 2^53), as a double; 0 when it would not be a
 * normal one (the caller then asks strtod). */
static int pack_double(uint64_t m, int e2, int neg, double *out)
{
    int be = e2 + 52 + 1023;
    if (be <= 0 || be >= 2047) return 0;
    uint64_t bits = ((uint64_t)neg << 63) | ((uint64_t)be << 52) | (m & ((UINT64_C(1) << 52) - 1));
    memcpy(out, &bits, sizeof *out);
    return 1;
}

/* n * 2^e2 (+ a fraction of 2^e2 below n's last bit when sticky), n > 0,
 * rounded to nearest even; 0 when the result would not be a normal double
 * (the caller then asks strtod). */
static int round_to_double(u128 n, int sticky, int e2, int neg, double *out)
{
    int b = bits128(n);
    uint64_t m;
    if (b <= 53) {
        m = (uint64_t)n << (53 - b);     /* exact (sticky is 0 here) */
        e2 -= 53 - b;
    } else {
        /* n with its top bit at bit 127: m is the top 53 bits, the 75
         * below are the dropped ones (b - 53 of n's, then zeros); half is
         * the first of them alone (0x400 in hi's low 11 bits, lo 0) */
        u128 t = n << (128 - b);
        uint64_t hi = (uint64_t)(t >> 64), lo = (uint64_t)t, rb = hi & 0x7ff;
        m = hi >> 11;
        if (rb > 0x400 || (rb == 0x400 && (lo || sticky || (m & 1)))) {
            m++;
            if (m >> 53) { m >>= 1; e2++; }
        }
        e2 += b - 53;
    }
    return pack_double(m, e2, neg, out);
}

/* n (len words, little-endian, the top one nonzero) /= d; the remainder. */
static uint64_t mw_div(uint64_t *n, int *len, uint64_t d)
{
    uint64_t r = 0;
    for (int i = *len - 1; i >= 0; i--) {
        /* (r 2^64 + n[i]) / d with r < d: the quotient fits a word */
        u128 c = ((u128)r << 64) | n[i];
        uint64_t q = (uint64_t)(c / d);
        r = (uint64_t)(c - (u128)q * d);
        n[i] = q;
    }
    while (*len > 1 && !n[*len - 1]) (*len)--;
    return r;
}

/* w 10^-k for 27 < k <= BIG_Q, as the k <= 27 case but with 5^k over
 * one word: N = floor(w 2^s / 5^k), dividing a few words by 5^27 and then
 * by the rest (floor(floor(a / b) / c) is floor(a / (b c)); the sticky bit
 * is any remainder), s chosen so that N lies in [2^63, 2^68). */
static __attribute__((noinline)) int small_quotient(uint64_t w, int k, int neg, double *out)
{
    uint64_t n[BIG_WORDS] = { 0 };
    int bw = 64 - __builtin_clzll(w);
    int b5 = k * 2322 / 1000 + 1;           /* bits of 5^k, give or take one */
    int s = 65 + b5 - bw;                   /* w 2^s has 65 + b5 bits */
    int ws = s / 64, bs = s % 64;
    n[ws] = w << bs;
    if (bs) n[ws + 1] = w >> (64 - bs);
    int len = ws + 2;
    while (len > 1 && !n[len - 1]) len--;
    int sticky = 0;
    for (int left = k; left > 0; ) {
        int j = left > 27 ? 27 : left;
        sticky |= mw_div(n, &len, pow5[j]) != 0;
        left -= j;
    }
    if (len > 2) return 0;
    u128 q = ((u128)n[1] << 64) | n[0];
    return round_to_double(q, sticky, -k - s, neg, out);
}

/* The Eisel-Lemire step for w 10^-k, 1 <= k <= LEM_Q (every exponent
 * of a nonzero double with at most 19 digits): recip[k] is
 * R = floor(2^E / 5^k) with R in [2^127, 2^128), computed once from exact
 * integers (the same division by 5^27-sized pieces as small_quotient).
 * With wn = w 2^sh normalized to [2^63, 2^64), T = wn 2^E / 5^k / 2^64 is
 * the decimal times a power of two (w 10^-k = T 2^(64 - E - sh - k)), and
 * X = floor(wn R / 2^64) satisfies X <= T < X + 2 (R is below 2^E / 5^k
 * by less than one, and the floor loses less than one more). X >= 2^126;
 * shifting X (and T) to a top bit at 127 at most doubles that margin to 4
 * in units of the 75 bits rounding drops. When every value in [X, X + 4)
 * of those bits lies on one side of half, rounding T is decided; else
 * (about 2^-72 of random input, and every exact tie) the exact path. */
#define LEM_Q 342
#define LEM_WORDS 16                        /* 2^(129 + 796) */
struct vec_recip { uint64_t hi, lo; int e; };
static struct vec_recip recip[LEM_Q + 1];
static pthread_once_t recip_once = PTHREAD_ONCE_INIT;
static atomic_int recip_ready;      /* set (release) once the table is made */

static void recip_init(void)
{
    for (int k = 1; k <= LEM_Q; k++) {
        uint64_t n[LEM_WORDS] = { 0 };
        int b5 = k * 2322 / 1000 + 1;       /* bits of 5^k, or one more */
        int S = 129 + b5;                   /* 2^S / 5^k has 130 to 132 bits */
        n[S / 64] = UINT64_C(1) << (S % 64);
        int len = S / 64 + 1;
        for (int left = k; left > 0; ) {
            int j = left > 27 ? 27 : left;
            mw_div(n, &len, pow5[j]);
            left -= j;
        }
        /* floor(floor(x) / 2) = floor(x / 2): halve down to 128 bits */
        while (len > 2) {
            n[0] = (n[0] >> 1) | (n[1] << 63);
            n[1] = (n[1] >> 1) | (n[2] << 63);
            n[2] >>= 1;
            S--;
            if (!n[2]) len = 2;
        }
        recip[k].hi = n[1];
        recip[k].lo = n[0];
        recip[k].e = S;
    }
    atomic_store_explicit(&recip_ready, 1, memory_order_release);
}

static inline __attribute__((always_inline)) int lemire_neg(uint64_t w, int k, int neg, double *out)
{
    const struct vec_recip *t = &recip[k];
    int sh = __builtin_clzll(w);
    uint64_t wn = w << sh;
    u128 x = (u128)wn * t->hi + (((u128)wn * t->lo) >> 64);
    int l = !(x >> 127);
    x <<= l;
    uint64_t hi = (uint64_t)(x >> 64), lo = (uint64_t)x;
    uint64_t m = hi >> 11, rb = hi & 0x7ff;
    int e2 = 75 - l + 64 - t->e - sh - k;
    if (rb > 0x400 || (rb == 0x400 && lo)) {            /* all above half */
        m++;
        if (m >> 53) { m >>= 1; e2++; }
    } else if (!(rb < 0x3ff || (rb == 0x3ff && lo <= UINT64_MAX - 3))) {
        return 0;                                       /* near half: undecided */
    }
    return pack_double(m, e2, neg, out);
}

static inline __attribute__((always_inline)) int fast_steps(uint64_t w, long q, int neg, double *out)
{
#if FLT_EVAL_METHOD == 0
    if (w <= (UINT64_C(1) << 53) && q >= -22 && q <= 22) {
        double r = (double)w;
        r = q >= 0 ? r * pow10d[q] : r / pow10d[-q];
        *out = neg ? -r : r;
        return 1;
    }
#endif
    if (q < 0 && q >= -LEM_Q) {
        if (!atomic_load_explicit(&recip_ready, memory_order_acquire))
            pthread_once(&recip_once, recip_init);
        return lemire_neg(w, (int)-q, neg, out);
    }
    return 0;
}

int base_strtod_fast(uint64_t w, long q, int neg, double *out) { return fast_steps(w, q, neg, out); }

/* Eight digits at once (little-endian loads): whether the eight bytes at
 * p are all digits, and their value. The usual SWAR forms: a byte is a
 * digit when its high nibble is 3 and adding 6 keeps it so; the value by
 * pairs, quads, then the two halves. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define SWAR 1
static inline uint64_t load8(const char *p) { uint64_t v; memcpy(&v, p, 8); return v; }
static inline int all8_digits(uint64_t v)
{
    return ((v & UINT64_C(0xF0F0F0F0F0F0F0F0)) |
            (((v + UINT64_C(0x0606060606060606)) & UINT64_C(0xF0F0F0F0F0F0F0F0)) >> 4))
           == UINT64_C(0x3333333333333333);
}
static inline uint64_t value8(uint64_t v)
{
    const uint64_t mask = UINT64_C(0x000000FF000000FF);
    v -= UINT64_C(0x3030303030303030);
    v = v * 10 + (v >> 8);                          /* pairs */
    return ((v & mask) * (100 + (UINT64_C(1000000) << 32)) +
            ((v >> 16) & mask) * (1 + (UINT64_C(10000) << 32))) >> 32;
}
#else
#define SWAR 0
#endif

/* The digits at p into w (which wraps past 19 digits: the caller counts
 * them and sends such numbers to strtod); the first non-digit. With pad,
 * eight bytes at a time while they are all digits (reading up to seven
 * bytes past the first non-digit, which the caller allows). */
static inline __attribute__((always_inline)) const char *digits(const char *p, uint64_t *w, int pad)
{
    uint64_t v = *w;
#if SWAR
    if (pad)
        for (uint64_t x; all8_digits(x = load8(p)); p += 8) v = v * 100000000u + value8(x);
#else
    (void)pad;
#endif
    for (; is_digit(*p); p++) v = v * 10 + (uint64_t)(*p - '0');
    *w = v;
    return p;
}

/* The parse, and with fast set the fast steps before the exact ones;
 * pad: the caller allows reads of BASE_STRTOD_PAD bytes past the string. */
static inline __attribute__((always_inline)) double parse(const char *s, char **end, int fast, int pad)

{
    const char *p = s;
    int neg = 0;
    if (*p == '-' || *p == '+') { neg = *p == '-'; p++; }
    uint64_t w = 0;
    long frac = 0;
    const char *d0 = p;
    while (*p == '0') p++;                          /* leading zeros are not significant */
    /* The digits are summed first and counted after: more than 19
     * (where w would wrap) go to strtod anyway. */
    const char *ds = p;
    p = digits(p, &w, pad);
    long nd = p - ds;
    if (nd > 19) goto slow;
    if (*p == '.') {
        const char *f0 = ++p;
        if (!nd) while (*p == '0') p++;
        const char *fs = p;
        p = digits(p, &w, pad);
        if (nd + (p - fs) > 19) goto slow;
        frac = p - f0;
        if (p - d0 == 1) goto slow;                 /* a lone point: no digit at all */
    } else if (p == d0) {
        goto slow;                                  /* no digit at all */
    }
    long e = 0;
    if (*p == 'e' || *p == 'E') {
        const char *q = p + 1;
        int eneg = 0;
        if (*q == '+' || *q == '-') { eneg = *q == '-'; q++; }
        if (is_digit(*q)) {
            for (; is_digit(*q); q++)
                if (e < 100000) e = e * 10 + (*q - '0');
            if (eneg) e = -e;
            p = q;
        }
        /* "1e" or "1e+": strtod stops before the 'e'; the check below
         * sends such a number to it. */
    }
    /* Only a number ending where vector files end one; anything else is
     * strtod's to judge. */
    if (*p && *p != ' ' && *p != '\t' && *p != '|' && *p != '\n') goto slow;
    long q10 = e - frac;
    if (!w) {
        if (end) *end = (char *)p;
        return neg ? -0.0 : 0.0;
    }
    double r;
    if (fast && fast_steps(w, q10, neg, &r)) {
        if (end) *end = (char *)p;
        return r;
    }
    if (q10 >= 0 && q10 <= 27) {
        if (!round_to_double((u128)w * pow5[q10], 0, (int)q10, neg, &r)) goto slow;
    } else if (q10 < 0 && q10 >= -27) {
        uint64_t d = pow5[-q10];
        int s = 127 - (64 - __builtin_clzll(w));   /* w 2^s just below 2^127 */
        u128 n0 = (u128)w << s, n = n0 / d;
        if (!round_to_double(n, n0 - n * d != 0, (int)q10 - s, neg, &r)) goto slow;
    } else if (q10 < -27 && q10 >= -BIG_Q) {
        if (!small_quotient(w, (int)-q10, neg, &r)) goto slow;
    } else {
        goto slow;
    }
    if (end) *end = (char *)p;
    return r;
slow:
    return strtod(s, end);
}

double base_strtod(const char *s, char **end) { return parse(s, end, 1, 0); }
double base_strtod_padded(const char *s, char **end) { return parse(s, end, 1, 1); }
double base_strtod_exact(const char *s, char **end) { return parse(s, end, 0, 0); }
