/* sim_fixed.h - fixed-point formats and quantization.
 *
 * A format sI.F / uI.F is signed/unsigned with I integer bits (for signed,
 * including the sign bit) and F fraction bits: width W = I+F, 1..64, as
 * SystemC's sc_fixed<W,I> / sc_ufixed<W,I>. A value is held as its raw
 * two's-complement integer (sign-extended to 64 bits for signed formats,
 * zero-extended for unsigned); its real value is raw * 2^-F.
 * Unsigned formats are limited to 63 bits, so that every raw fits int64_t.
 *
 * Quantization takes an exact value (a double, or a wide raw integer with
 * its own fraction bits) to a format: first rounding (drop fraction bits),
 * then overflow handling (fit the integer range), as sc_fixed does.
 *
 * A format may carry its own rounding and overflow modes, as sc_fixed's
 * template arguments do ("s7.9:half-up:sat"): a value quantized into it
 * uses them whatever mode the caller passes, so one signal can round or
 * saturate differently from the rest of a design. A format without them
 * (the usual case, and what sim_fmt_make and zeroed memory give)
 * takes the caller's modes, which come from the simulation context
 * (sim_set_quant).
 */
#ifndef SIM_FIXED_H
#define SIM_FIXED_H
#include <stdint.h>
#include <stddef.h>

#define SIM_FX_MAX_WIDTH 64

typedef enum { SIM_RND_TRUNC, SIM_RND_HALF_UP, SIM_RND_EVEN } sim_round;
typedef enum { SIM_OVF_WRAP, SIM_OVF_SAT } sim_ovf;

typedef struct sim_fmt {
    uint8_t is_signed;   /* 1: sI.F, 0: uI.F */
    int8_t  ibits;       /* I, 0..64 */
    int8_t  fbits;       /* F, 0..64 */
    uint8_t width;       /* I+F, 1..64 */
    /* Own modes: 0 = none (use the caller's), else 1 + sim_round /
     * 1 + sim_ovf. Zero means none so that { 0 }, designated
     * initializers of the four fields above and sim_fmt_make all give
     * a plain format. */
    uint8_t rnd;
    uint8_t ovf;
} sim_fmt;

/* The modes a quantization into f uses: f's own, else the given default. */
static inline sim_round sim_fmt_round(sim_fmt f, sim_round dflt)
{
    return f.rnd ? (sim_round)(f.rnd - 1) : dflt;
}
static inline sim_ovf sim_fmt_ovf(sim_fmt f, sim_ovf dflt)
{
    return f.ovf ? (sim_ovf)(f.ovf - 1) : dflt;
}
/* 1 if f carries a rounding or an overflow mode of its own. */
static inline int sim_fmt_has_modes(sim_fmt f) { return f.rnd || f.ovf; }

/* Wide exact intermediate (sums and products before quantization). */
typedef __int128 sim_wide;

/* Build a format (without modes of its own); returns 0, or -1 (with a
 * message in err) when invalid. */
int sim_fmt_make(int is_signed, int ibits, int fbits, sim_fmt *out,
                 char *err, size_t errlen);
/* Parse "s2.14" / "u1.15", optionally followed by the format's own modes:
 * ":ROUND" and/or ":OVERFLOW" in either order, each at most once, with the
 * names below ("s7.12:half-up:sat", "u1.15:sat"). 0 on success, -1 with a
 * one-line message (nothing written to *out). */
int sim_fmt_parse(const char *s, sim_fmt *out, char *err, size_t errlen);
/* "s2.14", plus ":ROUND" then ":OVERFLOW" for the modes the format has
 * ("s7.12:half-up:sat"); what sim_fmt_parse reads back. buf of at least
 * SIM_FMT_STRLEN bytes. Returns buf. */
#define SIM_FMT_STRLEN 24
char *sim_fmt_str(sim_fmt f, char *buf);

/* Names of modes as on the command line: "trunc" "half-up" "even",
 * "wrap" "sat". Parse returns 0 or -1. */
const char *sim_round_name(sim_round r);
const char *sim_ovf_name(sim_ovf o);
int sim_round_parse(const char *s, sim_round *out);
int sim_ovf_parse(const char *s, sim_ovf *out);

/* Range of raw values and of reals. */
int64_t sim_fmt_raw_min(sim_fmt f);
int64_t sim_fmt_raw_max(sim_fmt f);
double  sim_fmt_lsb(sim_fmt f);                  /* 2^-F */
double  sim_fmt_real_min(sim_fmt f);
double  sim_fmt_real_max(sim_fmt f);

/* Quantize a finite real. *ovf (may be NULL) is set to 1 when the rounded
 * value was outside the format's range (then wrapped or saturated). Here
 * and in sim_fx_requant, f's own modes (if any) take the place of r / o. */
int64_t sim_fx_from_real(double x, sim_fmt f, sim_round r, sim_ovf o, int *ovf);
/* The same conversion prepared once for a format and modes, for a
 * testbench that quantizes many inputs into one port: sim_fx_conv_real(cv,
 * x, ovf) is sim_fx_from_real(x, f, r, o, ovf), bit for bit, with the
 * common case (a value in range, rounded down or half up) inline. */
typedef struct sim_fx_conv {
    double   scale;        /* 2^F; 0 when the fast step does not apply */
    int64_t  lo, hi;       /* the raw range */
    int      half_up;
    sim_fmt  f;
    sim_round r;
    sim_ovf  o;
} sim_fx_conv;
void sim_fx_conv_init(sim_fx_conv *cv, sim_fmt f, sim_round r, sim_ovf o);

/* The fast step (sim_fixed.c says why it is exact): 1 with the raw in *v
 * when x 2^F, rounded down or half up, is an integer in [lo, hi] below
 * 2^52 in magnitude; 0 otherwise (NaN, infinities and the rest included:
 * the general path decides). */
static inline int sim__fx_fast(double x, double scale, int half_up, int64_t lo, int64_t hi, int64_t *v)
{
    double y = x * scale;
    if (!(y > -0x1p52 && y < 0x1p52 && (y == 0 || __builtin_fabs(x) >= 0x1p-960))) return 0;
    int64_t i = (int64_t)y;          /* toward zero, exact below 2^52 */
    double t = (double)i;
    if (t > y) { i--; t -= 1.0; }    /* floor */
    i += half_up && y >= t + 0.5;
    if (i < lo || i > hi) return 0;
    *v = i;
    return 1;
}

static inline int64_t sim_fx_conv_real(const sim_fx_conv *cv, double x, int *ovf)
{
    int64_t v;
    if (cv->scale != 0 && sim__fx_fast(x, cv->scale, cv->half_up, cv->lo, cv->hi, &v)) {
        if (ovf) *ovf = 0;
        return v;
    }
    return sim_fx_from_real(x, cv->f, cv->r, cv->o, ovf);
}

/* Quantize an exact wide raw value with src_fbits fraction bits. */
int64_t sim_fx_requant(sim_wide raw, int src_fbits, sim_fmt f,
                       sim_round r, sim_ovf o, int *ovf);
/* Real value of a raw (exact for widths <= 53; nearest double beyond). */
double  sim_fx_to_real(int64_t raw, sim_fmt f);
/* Bring a raw into canonical form for its format (sign-/zero-extend from W
 * bits); used when a raw arrives from outside (e.g. a VCD or a file). */
int64_t sim_fx_canon(int64_t raw, sim_fmt f);

/* ---- exact dyadic numbers, for checking results ----
 * A sim_dy is m * 2^-e exactly: a sign and a magnitude of up to
 * SIM_DY_BITS bits. Enough for the ideal of a cubic in 64-bit inputs
 * (4 * 64 bits plus carries); an operation whose result would not fit
 * sets ovf, and a result with ovf set is not a number (callers then say
 * they cannot check). Slow but exact: testbenches use it once per output. */
#define SIM_DY_WORDS 8
#define SIM_DY_BITS  (64 * SIM_DY_WORDS)
typedef struct sim_dy {
    uint64_t m[SIM_DY_WORDS];   /* magnitude, little-endian words */
    int      neg;               /* 1: negative (never for zero) */
    int      e;                 /* value = m * 2^-e */
    int      ovf;               /* did not fit: not a number */
} sim_dy;

void   sim_dy_int(sim_dy *d, int64_t v, int e);        /* v * 2^-e */
void   sim_dy_raw(sim_dy *d, int64_t raw, sim_fmt f);   /* a raw's exact value */
/* A finite double's exact value (0, ovf set, for NaN and infinities). */
void   sim_dy_double(sim_dy *d, double x);
void   sim_dy_add(sim_dy *r, const sim_dy *a, const sim_dy *b);
void   sim_dy_sub(sim_dy *r, const sim_dy *a, const sim_dy *b);
void   sim_dy_mul(sim_dy *r, const sim_dy *a, const sim_dy *b);
void   sim_dy_abs(sim_dy *r, const sim_dy *a);
/* Keep at most e_max fraction bits: the magnitude rounded down (toward
 * zero) or, with up, away from zero; for intervals that must contain a
 * value too long to hold. */
void   sim_dy_cut(sim_dy *d, int e_max, int up);
/* -1, 0, 1 as a < b, a == b, a > b (neither may have ovf set). */
int    sim_dy_cmp(const sim_dy *a, const sim_dy *b);
/* Nearest double or so (for printing: exact up to its last bit or two). */
double sim_dy_to_double(const sim_dy *a);

#endif
