/* test_vec_num.c - vec_num_strtod equals strtod bit for bit (value and end
 * pointer) on a lean corpus (tests/tst_num.h: random doubles in %.17g and
 * other precisions, random digit strings, exact halfway cases and their
 * neighbours, exponents near the limits, subnormals, malformed input);
 * bench/bench_vec_num.c runs ten million. */
#include "tests/tst.h"
#include "vectors/vec_num.h"
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
    TST_CHECK(vec_num_strtod("9007199254740993", NULL) == 0x1p53, "2^53+1");
    /* 2^53 + 3: halfway between 2^53 + 2 and 2^53 + 4: even is + 4 */
    TST_CHECK(vec_num_strtod("9007199254740995", NULL) == 0x1p53 + 4, "2^53+3");
    /* 2^52 + 0.5: between 2^52 and 2^52 + 1, even is 2^52; + 1.5 -> + 2 */
    TST_CHECK(vec_num_strtod("4503599627370496.5", NULL) == 0x1p52, "2^52+1/2");
    TST_CHECK(vec_num_strtod("4503599627370497.5", NULL) == 0x1p52 + 2, "2^52+3/2");
    /* just above halfway rounds up */
    TST_CHECK(vec_num_strtod("4503599627370496.5000001", NULL) == 0x1p52 + 1, "above half");
    TST_CHECK(vec_num_strtod("-0", NULL) == 0 && signbit(vec_num_strtod("-0", NULL)), "-0");
    char *end;
    const char *s = "1.25e2 | 3";
    TST_CHECK(vec_num_strtod(s, &end) == 125.0 && end == s + 6, "end after the exponent");
    s = "7e";
    TST_CHECK(vec_num_strtod(s, &end) == 7.0 && end == s + 1, "'e' without digits is not read");
}

int main(void)
{
    TST_RUN(t_corpus);
    TST_RUN(t_halfway);
    TST_RUN(t_small_exponents);
    TST_EXIT();
}
