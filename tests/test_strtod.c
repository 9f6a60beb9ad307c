/* test_strtod.c - base_strtod equals strtod bit for bit (value and end
 * pointer) on a lean corpus (tests/tst_num.h: random doubles in %.17g and
 * other precisions, random digit strings, exact halfway cases and their
 * neighbours, exponents near the limits, subnormals, malformed input);
 * every string also through the exact path alone (base_strtod_exact);
 * and the fast steps (base_strtod_fast: Clinger, Eisel-Lemire) on millions of
 * w 10^q against the exact path and strtod, counting how many they decide.
 * bench/bench_strtod.c runs ten million. */
#include "tests/tst.h"
#include "base/base_strtod.h"
#include "tests/tst_num.h"

#define CORPUS 200000

static void t_corpus(void)
{
    char buf[128], why[300];
    long bad = 0;
    for (uint64_t i = 0; i < CORPUS; i++) {
        tst_num_make(1, i, buf, sizeof buf);
        if (tst_num_check(buf, why, sizeof why)) {
            if (bad++ < 10) TST_CHECK(0, "%s", why);
        }
    }
    TST_EQ_INT(bad, 0);
}

/* Mantissas of 1 to 19 digits with decimal exponents from -112 to -24:
 * the range the parser divides exactly through a few words (between its
 * one-word quotient and strtod), and its edges. Digits from a fixed LCG. */
static void t_small_exponents(void)
{
    char buf[64], why[300];
    long bad = 0;
    uint64_t x = 0x2545f4914f6cdd1dull;
    for (int i = 0; i < 60000; i++) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        int nd = 1 + (int)((x >> 59) % 19), e = -112 + (int)((x >> 20) % 89);
        uint64_t y = x;
        char digits[24];
        for (int d = 0; d < nd; d++) {
            y = y * 6364136223846793005ull + 1442695040888963407ull;
            digits[d] = (char)('0' + (d == 0 ? 1 + (y >> 60) % 9 : (y >> 60) % 10));
        }
        digits[nd] = 0;
        snprintf(buf, sizeof buf, "%s%se%d", (x >> 7) & 1 ? "-" : "", digits, e);
        if (tst_num_check(buf, why, sizeof why) && bad++ < 10) TST_CHECK(0, "%s", why);
    }
    TST_EQ_INT(bad, 0);
}

/* Known roundings, from the definition: ties go to the even neighbour. */
static void t_halfway(void)
{
    /* 2^53 + 1 lies halfway between 2^53 and 2^53 + 2: even is 2^53 */
    TST_CHECK(base_strtod("9007199254740993", NULL) == 0x1p53, "2^53+1");
    /* 2^53 + 3: halfway between 2^53 + 2 and 2^53 + 4: even is + 4 */
    TST_CHECK(base_strtod("9007199254740995", NULL) == 0x1p53 + 4, "2^53+3");
    /* 2^52 + 0.5: between 2^52 and 2^52 + 1, even is 2^52; + 1.5 -> + 2 */
    TST_CHECK(base_strtod("4503599627370496.5", NULL) == 0x1p52, "2^52+1/2");
    TST_CHECK(base_strtod("4503599627370497.5", NULL) == 0x1p52 + 2, "2^52+3/2");
    /* just above halfway rounds up */
    TST_CHECK(base_strtod("4503599627370496.5000001", NULL) == 0x1p52 + 1, "above half");
    TST_CHECK(base_strtod("-0", NULL) == 0 && signbit(base_strtod("-0", NULL)), "-0");
    char *end;
    const char *s = "1.25e2 | 3";
    TST_CHECK(base_strtod(s, &end) == 125.0 && end == s + 6, "end after the exponent");
    s = "7e";
    TST_CHECK(base_strtod(s, &end) == 7.0 && end == s + 1, "'e' without digits is not read");
}

/* w 10^q as "[-]we<q>" through tst_num_check (fast = exact = strtod);
 * then base_strtod_fast on the same w, q: when it decides, the same bits.
 * Returns -1 on a mismatch, else whether the fast steps decided. */
static int fast_case(uint64_t w, long q, int neg, char *why, size_t len)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%s%llue%ld", neg ? "-" : "", (unsigned long long)w, q);
    if (tst_num_check(buf, why, len)) return -1;
    double f;
    if (!base_strtod_fast(w, q, neg, &f)) return 0;
    double b = strtod(buf, NULL);
    if (memcmp(&f, &b, sizeof f)) {
        snprintf(why, len, "'%s': fast step %a against strtod's %a", buf, f, b);
        return -1;
    }
    return 1;
}

/* 10^(d-1) <= w < 10^d drawn uniformly, 1 <= d <= 19 */
static uint64_t digits_w(uint64_t *x, int d)
{
    uint64_t lo = 1;
    for (int i = 1; i < d; i++) lo *= 10;
    uint64_t span = d == 19 ? UINT64_C(10000000000000000000) - lo : lo * 9;
    return lo + tst_num_rand(x) % span;
}

/* Whether w 10^-k (k >= 1, a normal double) lies exactly halfway
 * between two doubles: w = c 5^k and c's odd part has 54 bits. */
static int is_tie(uint64_t w, int k)
{
    for (int i = 0; i < k; i++) {
        if (w % 5) return 0;
        w /= 5;
    }
    w >>= __builtin_ctzll(w);
    return w >> 53 == 1;
}

/* Two million random decimals (a tenth in make test-quick and under the
 * sanitizers: tst_fewer): 1 to 19
 * significant digits, q from -345 to +22 (all the range the fast steps
 * take, beyond it, and Clinger's positive side), random signs. The
 * Eisel-Lemire step leaves only values within 2^-72 of a tie to the exact
 * path (one in about 10^21 of random input), the exact ties, and results
 * near or below the subnormals: here it must decide every other case. */
static void t_fast_random(void)
{
    uint64_t x = 27;
    long bad = 0, n = 0, fast = 0, neg_q = 0, neg_fast = 0, ties = 0, odd = 0, sub = 0;
    char why[300];
    const int draws = tst_fewer() ? 200000 : 2000000;
    for (int i = 0; i < draws; i++) {
        uint64_t r = tst_num_rand(&x);
        int d = 1 + (int)(r % 19);
        long q = -345 + (long)((r >> 8) % 368);
        uint64_t w = digits_w(&x, d);
        int k = fast_case(w, q, (int)(r >> 20) & 1, why, sizeof why);
        if (k < 0) { if (bad++ < 10) TST_CHECK(0, "%s", why); continue; }
        n++;
        fast += k;
        if (q < 0 && w > (UINT64_C(1) << 53)) {
            neg_q++;
            neg_fast += k;
            if (!k) {
                char b[64];
                snprintf(b, sizeof b, "%llue%ld", (unsigned long long)w, q);
                if (fabs(strtod(b, NULL)) < 0x1p-1021) sub++;   /* near subnormal: not its job */
                else if (is_tie(w, (int)-q)) ties++;
                else if (odd++ < 10) TST_CHECK(0, "%llue%ld not decided", (unsigned long long)w, q);
            }
        }
    }
    TST_EQ_INT(bad, 0);
    printf("  %ld decimals, %ld by the fast steps; %ld beyond Clinger with q < 0: %ld by Eisel-Lemire, "
           "%ld exact ties and %ld below 2^-1021 left to the exact path or strtod\n", n, fast, neg_q, neg_fast, ties, sub);
    TST_CHECK(neg_q > draws / 10, "%ld cases for Eisel-Lemire", neg_q);
    TST_EQ_INT(odd, 0);
}

/* What vector files hold: %.17g of a million random doubles (a tenth in
 * make test-quick and under the sanitizers) from 2^-1020
 * (8.9e-308, where q = -324) to 2^53, both signs, through the string
 * parse; the fast steps must decide every one. (Above 2^53, q >= 0 and
 * w > 2^53 take the exact path's one-word product w 5^q, a multiply.) */
static void t_fast_g17(void)
{
    uint64_t x = 17;
    long bad = 0, fast = 0, n = tst_fewer() ? 100000 : 1000000;
    char buf[64], why[300];
    for (long i = 0; i < n; i++) {
        uint64_t r = tst_num_rand(&x);
        double v = ldexp((double)((r >> 11) | (UINT64_C(1) << 52)), -52 - 1020 + (int)(r % 1073));
        if (r & 1024) v = -v;
        snprintf(buf, sizeof buf, "%.17g", v);
        if (tst_num_check(buf, why, sizeof why) && bad++ < 10) TST_CHECK(0, "%s", why);
        /* its w and q: the digits without point, the exponent less the
         * digits after the point */
        uint64_t w = 0;
        long q = 0, frac = -1;
        const char *p = buf + (buf[0] == '-');
        for (; *p && *p != 'e'; p++) {
            if (*p == '.') { frac = 0; continue; }
            w = w * 10 + (uint64_t)(*p - '0');
            if (frac >= 0) frac++;
        }
        if (*p == 'e') q = strtol(p + 1, NULL, 10);
        if (frac > 0) q -= frac;
        double f;
        if (base_strtod_fast(w, q, buf[0] == '-', &f)) {
            fast++;
            if (memcmp(&f, &v, sizeof f) && bad++ < 10) TST_CHECK(0, "'%s': fast step %a", buf, f);
        }
    }
    TST_EQ_INT(bad, 0);
    printf("  %ld %%.17g doubles, %ld by the fast steps\n", n, fast);
    TST_EQ_INT(fast, n);
}

/* Exact ties, which only the exact path may round: the midpoint between
 * adjacent doubles M 2^e and (M+1) 2^e, M in [2^52, 2^53), is
 * (2M+1) 2^(e-1); with 2^(e-1) = 10^-j 5^j, j = 1..3, it is
 * w = (2M+1) 5^j (under 10^19) times 10^-j; with 2^(e-1) = 2^i,
 * i = 0..9, the integer (2M+1) 2^i. The fast steps must leave every
 * tie to the exact path, and both neighbours w - 1 and w + 1 (one unit
 * of the last digit) round away from it correctly. */
static void t_fast_ties(void)
{
    uint64_t x = 99;
    long bad = 0, ties = 0, decided_ties = 0;
    char why[300];
    for (int i = 0; i < 100000; i++) {
        uint64_t M = (UINT64_C(1) << 52) | (tst_num_rand(&x) >> 12);
        uint64_t odd = 2 * M + 1, w;
        long q;
        int j = i % 13;
        if (j < 3) { w = odd * (j == 0 ? 5 : j == 1 ? 25 : 125); q = -(j + 1); }
        else { w = odd << (j - 3); q = 0; }
        int neg = (i >> 4) & 1;
        for (int dw = -1; dw <= 1; dw++) {
            int k = fast_case(w + (uint64_t)(long)dw, q, neg, why, sizeof why);
            if (k < 0) { if (bad++ < 10) TST_CHECK(0, "%s", why); continue; }
            if (!dw) { ties++; decided_ties += k; }
        }
    }
    TST_EQ_INT(bad, 0);
    TST_EQ_INT(decided_ties, 0);
    TST_CHECK(ties == 100000, "%ld ties", ties);
}

/* Edges: the smallest and largest exponents the fast step takes (q =
 * -108 with 1 and 19 digits), one beyond it, values near the bottom of
 * the normal range and past the top (strtod's subnormals and infinity),
 * and signs. tst_num_check compares all three readings. */
static void t_fast_edges(void)
{
    static const char *const s[] = {
        "1e-108", "-1e-108", "9999999999999999999e-108", "-9999999999999999999e-108", "1e-109",
        "9999999999999999999e-109", "1e-1", "-1e-1", "9999999999999999999e-1", "18446744073709551615e-5",
        "2.2250738585072014e-308", "-2.2250738585072014e-308", "2.2250738585072011e-308",
        "4.9406564584124654e-324", "-4.9406564584124654e-324", "2.4703282292062328e-324",
        "1.7976931348623157e308", "-1.7976931348623157e308", "1.7976931348623159e308", "-1.8e308",
        "9007199254740993e-22", "9007199254740993e-23", "9007199254740992e22", "-0e-50", "+5e-20",
        "1e-342", "9999999999999999999e-342", "1e-343", "2.2250738585072014e-308", "22250738585072014e-324",
        "-9999999999999999999e-327", "1e-307", "-2.9762636928672464e-148",
        "1.0000000000000002", "0.99999999999999989", "0.99999999999999994", "0.999999999999999944",
    };
    char why[300];
    for (size_t i = 0; i < sizeof s / sizeof s[0]; i++)
        if (tst_num_check(s[i], why, sizeof why)) TST_CHECK(0, "%s", why);
}

int main(void)
{
    TST_RUN(t_corpus);
    TST_RUN(t_halfway);
    TST_RUN(t_small_exponents);
    TST_RUN(t_fast_random);
    TST_RUN(t_fast_g17);
    TST_RUN(t_fast_ties);
    TST_RUN(t_fast_edges);
    TST_EXIT();
}
