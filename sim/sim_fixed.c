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
 *  - A format's own modes are applied at the two public entries
 *    (sim_fx_requant, sim_fx_from_real), so quant() sees final modes.
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
    out->rnd = out->ovf = 0;
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

/* Text for a one-line message: at most max characters (then "..."),
 * control characters shown as '?' (a stray '\n' would split the line). */
static void shown_text(const char *s, size_t len, char *out, size_t max)
{
    size_t k = 0, i = 0;
    for (; i < len && s[i] && k < max; i++)
        out[k++] = ((unsigned char)s[i] < 0x20 || s[i] == 0x7f) ? '?' : s[i];
    if (i < len && s[i]) { out[k++] = '.'; out[k++] = '.'; out[k++] = '.'; }
    out[k] = 0;
}

static int round_find(const char *s, size_t n);
static int ovf_find(const char *s, size_t n);

/* The modes after a format's ":" (p at the first ':'); 0, or -1 with the
 * reason in why. */
static int parse_modes(const char *p, sim_fmt *f, char *why, size_t n)
{
    while (*p == ':') {
        const char *m = p + 1;
        size_t len = strcspn(m, ":");
        int r = round_find(m, len), o = ovf_find(m, len);
        char tok[28];
        shown_text(m, len, tok, 20);
        if (len == 0) {
            snprintf(why, n, "empty mode after ':' (rounding: trunc, half-up, even; overflow: wrap, sat)");
            return -1;
        }
        if (r < 0 && o < 0) {
            snprintf(why, n, "unknown mode '%s' (rounding: trunc, half-up, even; overflow: wrap, sat)", tok);
            return -1;
        }
        if ((r >= 0 && f->rnd) || (o >= 0 && f->ovf)) {
            snprintf(why, n, "%s mode given twice ('%s')", r >= 0 ? "rounding" : "overflow", tok);
            return -1;
        }
        if (r >= 0) f->rnd = (uint8_t)(1 + r);
        else f->ovf = (uint8_t)(1 + o);
        p = m + len;
    }
    return 0;
}

int sim_fmt_parse(const char *s, sim_fmt *out, char *err, size_t errlen)
{
    /* The offending text goes into a one-line message: cut it short and
     * hide control characters. */
    char shown[44];
    shown_text(s ? s : "", SIZE_MAX, shown, 40);

    int ibits = 0, fbits = 0;
    const char *p = s;
    char why[128];
    sim_fmt f;
    if (!s || (s[0] != 's' && s[0] != 'u') || !(p = parse_count(s + 1, &ibits))
        || *p != '.' || !(p = parse_count(p + 1, &fbits)) || (*p && *p != ':')) {
        snprintf(why, sizeof why, "expected sI.F or uI.F (e.g. s2.14 or s7.12:half-up:sat)");
    } else if (ibits >= 1000 || fbits >= 1000) {
        /* the count was cut at 1000: don't print it back as a width */
        snprintf(why, sizeof why, "%s bits out of range 0..64",
                 ibits >= 1000 ? "integer" : "fraction");
    } else if (fmt_check(s[0] == 's', ibits, fbits, why, sizeof why) == 0
               && sim_fmt_make(s[0] == 's', ibits, fbits, &f, NULL, 0) == 0
               && parse_modes(p, &f, why, sizeof why) == 0) {
        *out = f;
        return 0;
    }
    if (err && errlen)
        snprintf(err, errlen, "bad format '%s': %s", shown, why);
    return -1;
}

char *sim_fmt_str(sim_fmt f, char *buf)
{
    int n = snprintf(buf, SIM_FMT_STRLEN, "%c%d.%d", f.is_signed ? 's' : 'u',
                     (int)f.ibits, (int)f.fbits);
    if (n > 0 && n < SIM_FMT_STRLEN && f.rnd)
        n += snprintf(buf + n, SIM_FMT_STRLEN - (size_t)n, ":%s", sim_round_name(sim_fmt_round(f, SIM_RND_TRUNC)));
    if (n > 0 && n < SIM_FMT_STRLEN && f.ovf)
        snprintf(buf + n, SIM_FMT_STRLEN - (size_t)n, ":%s", sim_ovf_name(sim_fmt_ovf(f, SIM_OVF_WRAP)));
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

/* Index of the mode named by the n characters at s, or -1. */
static int name_find(const char *const *names, int count, const char *s, size_t n)
{
    for (int i = 0; s && i < count; i++)
        if (strlen(names[i]) == n && !strncmp(s, names[i], n)) return i;
    return -1;
}
static int round_find(const char *s, size_t n) { return name_find(round_names, 3, s, n); }
static int ovf_find(const char *s, size_t n) { return name_find(ovf_names, 2, s, n); }

int sim_round_parse(const char *s, sim_round *out)
{
    int i = s ? round_find(s, strlen(s)) : -1;
    if (i < 0) return -1;
    *out = (sim_round)i;
    return 0;
}

int sim_ovf_parse(const char *s, sim_ovf *out)
{
    int i = s ? ovf_find(s, strlen(s)) : -1;
    if (i < 0) return -1;
    *out = (sim_ovf)i;
    return 0;
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
    return quant(raw, src_fbits - f.fbits, f, sim_fmt_round(f, r), sim_fmt_ovf(f, o), ovf);
}

void sim_fx_conv_init(sim_fx_conv *cv, sim_fmt f, sim_round r, sim_ovf o)
{
    cv->f = f;
    cv->r = r;
    cv->o = o;
    r = sim_fmt_round(f, r);
    cv->scale = r != SIM_RND_EVEN && f.fbits <= 52 ? (double)((uint64_t)1 << f.fbits) : 0;
    cv->half_up = r == SIM_RND_HALF_UP;
    cv->lo = sim_fmt_raw_min(f);
    cv->hi = sim_fmt_raw_max(f);
}

int64_t sim_fx_from_real(double x, sim_fmt f, sim_round r, sim_ovf o, int *ovf)
{
    if (!isfinite(x)) {
        if (ovf) *ovf = 1;
        return 0;
    }
    /* The common case without frexp (sim__fx_fast): x 2^F is exact (a
     * power-of-two scaling, here never past 2^52 and never subnormal), so
     * is its floor below 2^52 (taken by truncation toward zero, then one
     * down if that was above), and so is floor(y) + 1/2; rounding half-up
     * adds one when y is at least that (compared, not subtracted: y -
     * floor(y) of a negative y can round). In range, that is the raw. */
    r = sim_fmt_round(f, r);   /* a format's own modes win over the caller's */
    o = sim_fmt_ovf(f, o);
    int64_t v;
    if (r != SIM_RND_EVEN && f.fbits <= 52
        && sim__fx_fast(x, (double)((uint64_t)1 << f.fbits), r == SIM_RND_HALF_UP,
                        sim_fmt_raw_min(f), sim_fmt_raw_max(f), &v)) {
        if (ovf) *ovf = 0;
        return v;
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

/* ---- exact dyadic numbers (sim_dy) ----
 * Sign and magnitude; after every operation the magnitude is made odd
 * (trailing zero bits moved into e), so that values stay as short as their
 * meaning and alignment shifts stay small. */

static int dy_zero(const sim_dy *a)
{
    for (int i = 0; i < SIM_DY_WORDS; i++) if (a->m[i]) return 0;
    return 1;
}

/* 1 if only the low word is in use (the fast paths' case). */
_Static_assert(SIM_DY_WORDS == 8, "dy_small names the words");
static inline int dy_small(const sim_dy *a)
{
    /* the seven words written out: gcc's loop took twice the instructions */
    const uint64_t *m = a->m;
    return ((m[1] | m[2]) | (m[3] | m[4]) | (m[5] | m[6]) | m[7]) == 0;
}

/* Set d to sign neg and magnitude v * 2^-e, normalized (v < 2^128). */
static void dy_set128(sim_dy *d, int neg, unsigned __int128 v, int e)
{
    memset(d, 0, sizeof *d);
    if (!v) return;
    int tz = (uint64_t)v ? __builtin_ctzll((uint64_t)v) : 64 + __builtin_ctzll((uint64_t)(v >> 64));
    v >>= tz;
    d->m[0] = (uint64_t)v;
    d->m[1] = (uint64_t)(v >> 64);
    d->e = e - tz;
    d->neg = neg;
}

static void dy_norm(sim_dy *d)
{
    if (d->ovf) return;
    if (dy_small(d)) {
        if (!d->m[0]) { d->neg = 0; d->e = 0; return; }
        int tz = __builtin_ctzll(d->m[0]);
        d->m[0] >>= tz;
        d->e -= tz;
        return;
    }
    if (dy_zero(d)) { d->neg = 0; d->e = 0; return; }
    int w = 0;
    while (!d->m[w]) w++;
    int tz = 64 * w + __builtin_ctzll(d->m[w]);
    int ws = tz / 64, bs = tz % 64;
    for (int i = 0; i < SIM_DY_WORDS; i++) {
        uint64_t lo = i + ws < SIM_DY_WORDS ? d->m[i + ws] : 0;
        uint64_t hi = i + ws + 1 < SIM_DY_WORDS ? d->m[i + ws + 1] : 0;
        d->m[i] = bs ? (lo >> bs) | (hi << (64 - bs)) : lo;
    }
    d->e -= tz;
}

/* m <<= k; 1 if bits were lost (the value does not fit). */
static int mag_shl(uint64_t *m, int k)
{
    if (k <= 0) return 0;
    if (k >= SIM_DY_BITS) return 1;     /* callers never shift a zero */
    int ws = k / 64, bs = k % 64;
    for (int i = SIM_DY_WORDS - ws; i < SIM_DY_WORDS; i++) if (m[i]) return 1;
    if (bs && (m[SIM_DY_WORDS - ws - 1] >> (64 - bs))) return 1;
    for (int i = SIM_DY_WORDS - 1; i >= 0; i--) {
        uint64_t lo = i - ws >= 0 ? m[i - ws] : 0;
        uint64_t lo2 = i - ws - 1 >= 0 ? m[i - ws - 1] : 0;
        m[i] = bs ? (lo << bs) | (lo2 >> (64 - bs)) : lo;
    }
    return 0;
}

static int mag_cmp(const uint64_t *a, const uint64_t *b)
{
    for (int i = SIM_DY_WORDS - 1; i >= 0; i--)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

void sim_dy_int(sim_dy *d, int64_t v, int e)
{
    memset(d, 0, sizeof *d);
    if (!v) return;                 /* zero: m, neg and e all 0, as dy_norm makes it */
    uint64_t m = v < 0 ? 0 - (uint64_t)v : (uint64_t)v;
    int tz = __builtin_ctzll(m);    /* dy_norm's odd magnitude, directly */
    d->m[0] = m >> tz;
    d->e = e - tz;
    d->neg = v < 0;
}

void sim_dy_raw(sim_dy *d, int64_t raw, sim_fmt f) { sim_dy_int(d, raw, f.fbits); }

void sim_dy_double(sim_dy *d, double x)
{
    if (!isfinite(x)) { memset(d, 0, sizeof *d); d->ovf = 1; return; }
    /* x = m 2^-e from its fields (sim_dy_int makes m odd, so the result is
     * the value's one form whichever m is given): a normal x is
     * (2^52 + frac) 2^(E-1075), a subnormal one frac 2^-1074. */
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int be = (int)(bits >> 52) & 0x7ff;
    int64_t m = (int64_t)(bits & ((UINT64_C(1) << 52) - 1));
    if (be) m |= INT64_C(1) << 52;
    sim_dy_int(d, bits >> 63 ? -m : m, be ? 1075 - be : 1074);
}

/* a and b brought to a common e (the larger); 0 if that does not fit. */
static int dy_align(const sim_dy *a, const sim_dy *b, sim_dy *x, sim_dy *y)
{
    *x = *a; *y = *b;
    if (dy_zero(x)) x->e = y->e;
    if (dy_zero(y)) y->e = x->e;
    if (x->e < y->e) { if (mag_shl(x->m, y->e - x->e)) return 0; x->e = y->e; }
    else if (y->e < x->e) { if (mag_shl(y->m, x->e - y->e)) return 0; y->e = x->e; }
    return 1;
}

static void dy_addsub_words(sim_dy *r, const sim_dy *a, const sim_dy *b, int negate);

/* r = a + (negate b ? -b : b) */
static inline void dy_addsub(sim_dy *r, const sim_dy *a, const sim_dy *b, int negate)
{
    /* Fast path: one word each, exponents within 62 of each other: the
     * aligned values and their sum fit a signed 128-bit integer. */
    if (!a->ovf && !b->ovf && dy_small(a) && dy_small(b)) {
        int e = a->e > b->e ? a->e : b->e, sa = e - a->e, sb = e - b->e;
        if (sa <= 62 && sb <= 62) {
            /* sign and magnitude: equal signs add, else the larger
             * magnitude keeps its sign (a zero result has none) */
            unsigned __int128 x = (unsigned __int128)a->m[0] << sa, y = (unsigned __int128)b->m[0] << sb;
            int na = a->neg, nb = b->neg ^ negate;
            if (na == nb) dy_set128(r, na, x + y, e);
            else if (x >= y) dy_set128(r, na, x - y, e);
            else dy_set128(r, nb, y - x, e);
            return;
        }
    }
    dy_addsub_words(r, a, b, negate);
}

/* dy_addsub's general case, out of line so that the fast path saves no
 * registers. */
static __attribute__((noinline)) void dy_addsub_words(sim_dy *r, const sim_dy *a, const sim_dy *b, int negate)
{
    sim_dy x, y;
    if (a->ovf || b->ovf || !dy_align(a, b, &x, &y)) { memset(r, 0, sizeof *r); r->ovf = 1; return; }
    int yneg = y.neg ^ (negate && !dy_zero(&y));
    sim_dy o;
    memset(&o, 0, sizeof o);
    o.e = x.e;
    if (x.neg == yneg) {
        unsigned __int128 c = 0;
        for (int i = 0; i < SIM_DY_WORDS; i++) {
            c += (unsigned __int128)x.m[i] + y.m[i];
            o.m[i] = (uint64_t)c;
            c >>= 64;
        }
        o.neg = x.neg;
        o.ovf = c != 0;
    } else {
        const sim_dy *big = &x, *small = &y;
        int bneg = x.neg;
        if (mag_cmp(x.m, y.m) < 0) { big = &y; small = &x; bneg = yneg; }
        uint64_t borrow = 0;
        for (int i = 0; i < SIM_DY_WORDS; i++) {
            uint64_t s = small->m[i] + borrow;
            uint64_t nb = (s < borrow) || (big->m[i] < s);
            o.m[i] = big->m[i] - s;
            borrow = nb;
        }
        o.neg = bneg;
    }
    dy_norm(&o);
    *r = o;
}

void sim_dy_add(sim_dy *r, const sim_dy *a, const sim_dy *b) { dy_addsub(r, a, b, 0); }
void sim_dy_sub(sim_dy *r, const sim_dy *a, const sim_dy *b) { dy_addsub(r, a, b, 1); }

static void dy_mul_words(sim_dy *r, const sim_dy *a, const sim_dy *b);

void sim_dy_mul(sim_dy *r, const sim_dy *a, const sim_dy *b)
{
    if (!a->ovf && !b->ovf && dy_small(a) && dy_small(b)) {   /* fast path: one word each */
        dy_set128(r, (a->neg ^ b->neg) && a->m[0] && b->m[0], (unsigned __int128)a->m[0] * b->m[0], a->e + b->e);
        return;
    }
    dy_mul_words(r, a, b);
}

/* sim_dy_mul's general case, out of line so that the fast path saves no
 * registers. */
static __attribute__((noinline)) void dy_mul_words(sim_dy *r, const sim_dy *a, const sim_dy *b)
{
    uint64_t p[2 * SIM_DY_WORDS];
    memset(p, 0, sizeof p);
    sim_dy o;
    memset(&o, 0, sizeof o);
    if (a->ovf || b->ovf) { o.ovf = 1; *r = o; return; }
    int nb = SIM_DY_WORDS;
    while (nb > 0 && !b->m[nb - 1]) nb--;     /* b's used words */
    for (int i = 0; i < SIM_DY_WORDS; i++) {
        if (!a->m[i]) continue;
        unsigned __int128 c = 0;
        for (int j = 0; j < nb; j++) {
            c += (unsigned __int128)a->m[i] * b->m[j] + p[i + j];
            p[i + j] = (uint64_t)c;
            c >>= 64;
        }
        p[i + nb] = (uint64_t)c;
    }
    for (int i = SIM_DY_WORDS; i < 2 * SIM_DY_WORDS; i++) if (p[i]) o.ovf = 1;
    memcpy(o.m, p, sizeof o.m);
    o.neg = a->neg ^ b->neg;
    o.e = a->e + b->e;
    dy_norm(&o);
    *r = o;
}

void sim_dy_abs(sim_dy *r, const sim_dy *a) { *r = *a; r->neg = 0; }

void sim_dy_cut(sim_dy *d, int e_max, int up)
{
    if (d->ovf || d->e <= e_max) return;
    int sh = d->e - e_max, lost = 0;
    if (sh >= SIM_DY_BITS) {
        lost = !dy_zero(d);
        memset(d->m, 0, sizeof d->m);
    } else {
        int ws = sh / 64, bs = sh % 64;
        for (int i = 0; i < ws; i++) lost |= d->m[i] != 0;
        if (bs) lost |= (d->m[ws] & ((1ULL << bs) - 1)) != 0;
        for (int i = 0; i < SIM_DY_WORDS; i++) {
            uint64_t lo = i + ws < SIM_DY_WORDS ? d->m[i + ws] : 0;
            uint64_t hi = i + ws + 1 < SIM_DY_WORDS ? d->m[i + ws + 1] : 0;
            d->m[i] = bs ? (lo >> bs) | (hi << (64 - bs)) : lo;
        }
    }
    d->e = e_max;
    if (up && lost) {           /* add one unit of the last kept place */
        int neg = d->neg;
        sim_dy one;
        sim_dy_int(&one, 1, e_max);
        d->neg = 0;
        sim_dy_add(d, d, &one);
        d->neg = neg && !dy_zero(d);
        return;
    }
    int neg = d->neg;
    dy_norm(d);
    d->neg = neg && !dy_zero(d);
}

int sim_dy_cmp(const sim_dy *a, const sim_dy *b)
{
    sim_dy d;
    sim_dy_sub(&d, a, b);
    if (d.ovf) {            /* cannot align: the exponents are far apart */
        double x = sim_dy_to_double(a), y = sim_dy_to_double(b);
        return x < y ? -1 : x > y;
    }
    if (dy_zero(&d)) return 0;
    return d.neg ? -1 : 1;
}

double sim_dy_to_double(const sim_dy *a)
{
    if (a->ovf) return NAN;
    /* The words from the top, v = v 2^64 + m[i]; leading zero words leave
     * v at +0 (0 2^64 + 0), so the sum starts at the first nonzero one. */
    int i = SIM_DY_WORDS - 1;
    while (i > 0 && !a->m[i]) i--;
    double v = (double)a->m[i];
    while (--i >= 0) v = v * 0x1p64 + (double)a->m[i];
    int k = -a->e;
    if (k >= -1022 && k <= 1023) {
        /* ldexp(v, k) as a product by 2^k, a normal double: exact, or
         * rounded once as ldexp rounds (overflow, subnormal results) */
        uint64_t bits = (uint64_t)(k + 1023) << 52;
        double p;
        memcpy(&p, &bits, sizeof p);
        v *= p;
    } else {
        v = ldexp(v, k);
    }
    return a->neg ? -v : v;
}
