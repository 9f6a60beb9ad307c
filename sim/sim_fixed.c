/* sim_fixed.c - fixed-point formats and quantization (see sim_fixed.h).
 *
 * Decisions beyond the header:
 *  - Unsigned formats are limited to 63 bits: a raw is an int64_t, and the
 *    largest raw of a 64-bit unsigned format (2^64-1) would not fit.
 *    Signed formats go to 64 bits.
 *  - *ovf is always assigned (0 or 1) when non-NULL, never accumulated.
 *  - sim_fx_requant accepts any src_fbits, not only 0..128: a negative
 *    value scales up, which is what a constant left shift needs.
 *  - NaN and infinities quantize to 0 with *ovf = 1.
 *
 * Everything numeric funnels into quant(): an exact integer times 2^-sh,
 * rounded with integer operations only, so doubles and 128-bit sums share
 * one rounding path and cannot disagree.
 */
#include "sim/sim_fixed.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

typedef unsigned __int128 sim_uwide;

/* Reason text only; callers prefix what they were given. */
static int fmt_check(int is_signed, int ibits, int fbits, char *why, size_t n)
{
    long long w = (long long)ibits + fbits;   /* make() may get any ints */
    if (ibits < 0)
        snprintf(why, n, "integer bits %d out of range 0..64", ibits);
    else if (fbits < 0)
        snprintf(why, n, "fraction bits %d out of range 0..64", fbits);
    else if (w == 0)
        snprintf(why, n, "width 0: a format needs 1 to 64 bits");
    else if (w > SIM_FX_MAX_WIDTH)
        snprintf(why, n, "width %lld > 64: a format needs 1 to 64 bits", w);
    else if (!is_signed && w > 63)
        snprintf(why, n, "width %lld: unsigned formats are limited to 63 bits "
                 "(raws are int64); use a signed format", w);
    else
        return 0;
    return -1;
}

int sim_fmt_make(int is_signed, int ibits, int fbits, sim_fmt *out,
                 char *err, size_t errlen)
{
    char why[128];
    if (fmt_check(is_signed, ibits, fbits, why, sizeof why)) {
        if (err && errlen)
            snprintf(err, errlen, "bad format %c%d.%d: %s",
                     is_signed ? 's' : 'u', ibits, fbits, why);
        return -1;
    }
    out->is_signed = is_signed ? 1 : 0;
    out->ibits = (int8_t)ibits;
    out->fbits = (int8_t)fbits;
    out->width = (uint8_t)(ibits + fbits);
    return 0;
}

/* Digits to int, saturating at 1000 so that "s99999999999999999999.1" is
 * an out-of-range count rather than signed overflow. */
static const char *parse_count(const char *p, int *v)
{
    if (*p < '0' || *p > '9') return NULL;
    int n = 0;
    for (; *p >= '0' && *p <= '9'; p++)
        n = n >= 1000 ? 1000 : n * 10 + (*p - '0');
    *v = n;
    return p;
}

int sim_fmt_parse(const char *s, sim_fmt *out, char *err, size_t errlen)
{
    /* The offending text goes into a one-line message: cut it short and
     * hide control characters (a stray '\n' would split the line). */
    char shown[44];
    size_t k = 0;
    for (const char *p = s ? s : ""; *p && k < 40; p++)
        shown[k++] = ((unsigned char)*p < 0x20 || *p == 0x7f) ? '?' : *p;
    if (s && strlen(s) > 40) { shown[k++] = '.'; shown[k++] = '.'; shown[k++] = '.'; }
    shown[k] = 0;

    int ibits = 0, fbits = 0;
    const char *p = s;
    char why[128];
    if (!s || (s[0] != 's' && s[0] != 'u') || !(p = parse_count(s + 1, &ibits))
        || *p != '.' || !(p = parse_count(p + 1, &fbits)) || *p) {
        snprintf(why, sizeof why, "expected sI.F or uI.F (e.g. s2.14)");
    } else if (ibits >= 1000 || fbits >= 1000) {
        /* the count was cut at 1000: don't print it back as a width */
        snprintf(why, sizeof why, "%s bits out of range 0..64",
                 ibits >= 1000 ? "integer" : "fraction");
    } else if (fmt_check(s[0] == 's', ibits, fbits, why, sizeof why) == 0) {
        return sim_fmt_make(s[0] == 's', ibits, fbits, out, err, errlen);
    }
    if (err && errlen)
        snprintf(err, errlen, "bad format '%s': %s", shown, why);
    return -1;
}

char *sim_fmt_str(sim_fmt f, char *buf)
{
    snprintf(buf, SIM_FMT_STRLEN, "%c%d.%d", f.is_signed ? 's' : 'u',
             (int)f.ibits, (int)f.fbits);
    return buf;
}

static const char *const round_names[] = { "trunc", "half-up", "even" };
static const char *const ovf_names[] = { "wrap", "sat" };

const char *sim_round_name(sim_round r)
{
    return (unsigned)r < 3 ? round_names[r] : "?";
}

const char *sim_ovf_name(sim_ovf o)
{
    return (unsigned)o < 2 ? ovf_names[o] : "?";
}

int sim_round_parse(const char *s, sim_round *out)
{
    for (int i = 0; s && i < 3; i++)
        if (!strcmp(s, round_names[i])) { *out = (sim_round)i; return 0; }
    return -1;
}

int sim_ovf_parse(const char *s, sim_ovf *out)
{
    for (int i = 0; s && i < 2; i++)
        if (!strcmp(s, ovf_names[i])) { *out = (sim_ovf)i; return 0; }
    return -1;
}

int64_t sim_fmt_raw_min(sim_fmt f)
{
    return f.is_signed ? -(INT64_MAX >> (64 - f.width)) - 1 : 0;
}

int64_t sim_fmt_raw_max(sim_fmt f)
{
    return INT64_MAX >> (64 - f.width - !f.is_signed);
}

double sim_fmt_lsb(sim_fmt f) { return ldexp(1.0, -f.fbits); }
double sim_fmt_real_min(sim_fmt f) { return ldexp((double)sim_fmt_raw_min(f), -f.fbits); }
double sim_fmt_real_max(sim_fmt f) { return ldexp((double)sim_fmt_raw_max(f), -f.fbits); }

/* Low W bits of v, sign-/zero-extended. Negative results are built by
 * negation so that no out-of-range unsigned->signed conversion is needed. */
static int64_t extend(uint64_t v, sim_fmt f)
{
    uint64_t mask = UINT64_MAX >> (64 - f.width);
    v &= mask;
    if (f.is_signed && (v >> (f.width - 1)))
        return -(int64_t)(mask - v) - 1;
    return (int64_t)v;
}

/* Quantize raw * 2^-sh (sh = source fraction bits minus target's).
 * beyond: the exact value did not fit 128 bits; q then holds its low 128
 * bits (all wrap needs) and neg its sign (all sat needs). */
static int64_t quant(sim_wide raw, int sh, sim_fmt f, sim_round r, sim_ovf o,
                     int *ovf)
{
    sim_wide q = raw;
    int beyond = 0;
    if (sh >= 128) {
        /* |raw * 2^-sh| <= 1/2 and equals 1/2 only for raw = -2^127, a tie
         * that both rounding modes send up: so only trunc of a negative
         * value is nonzero. */
        q = (r == SIM_RND_TRUNC && raw < 0) ? -1 : 0;
    } else if (sh > 0) {
        q = raw >> sh;   /* arithmetic on gcc/clang: floor */
        if (r != SIM_RND_TRUNC) {
            sim_uwide rem = (sim_uwide)raw & (((sim_uwide)1 << sh) - 1);
            sim_uwide half = (sim_uwide)1 << (sh - 1);
            /* q + 1 cannot overflow: |q| <= 2^126 here */
            if (rem > half || (rem == half && (r == SIM_RND_HALF_UP || (q & 1))))
                q++;
        }
    } else if (sh < 0 && raw != 0) {
        if (sh <= -128) {
            q = 0;
            beyond = 1;
        } else {
            /* Fits iff the top 1-sh bits are copies of the sign. */
            sim_wide top = raw >> (127 + sh);
            beyond = top != 0 && top != -1;
            q = (sim_wide)((sim_uwide)raw << -sh);
        }
    }

    sim_wide lo = f.is_signed ? -((sim_wide)1 << (f.width - 1)) : 0;
    sim_wide hi = f.is_signed ? ((sim_wide)1 << (f.width - 1)) - 1
                              : ((sim_wide)1 << f.width) - 1;
    if (!beyond && q >= lo && q <= hi) {
        if (ovf) *ovf = 0;
        return (int64_t)q;
    }
    if (ovf) *ovf = 1;
    if (o == SIM_OVF_SAT)
        return (int64_t)((beyond ? raw < 0 : q < lo) ? lo : hi);
    return extend((uint64_t)q, f);
}

int64_t sim_fx_requant(sim_wide raw, int src_fbits, sim_fmt f,
                       sim_round r, sim_ovf o, int *ovf)
{
    /* Beyond +-128 every shift behaves alike; clamping keeps the
     * subtraction below from overflowing an int. */
    if (src_fbits > 256) src_fbits = 256;
    if (src_fbits < -256) src_fbits = -256;
    return quant(raw, src_fbits - f.fbits, f, r, o, ovf);
}

int64_t sim_fx_from_real(double x, sim_fmt f, sim_round r, sim_ovf o, int *ovf)
{
    if (!isfinite(x)) {
        if (ovf) *ovf = 1;
        return 0;
    }
    /* x = m * 2^(e-53) exactly, m an integer of at most 53 bits: the
     * double becomes an exact wide raw, with no rounding in floating point
     * and no out-of-range conversion however large x is. */
    int e;
    double m = ldexp(frexp(x, &e), 53);
    return quant((sim_wide)(int64_t)m, 53 - e - f.fbits, f, r, o, ovf);
}

double sim_fx_to_real(int64_t raw, sim_fmt f)
{
    return ldexp((double)raw, -f.fbits);
}

int64_t sim_fx_canon(int64_t raw, sim_fmt f)
{
    return extend((uint64_t)raw, f);
}
