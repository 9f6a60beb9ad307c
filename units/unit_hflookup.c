/* unit_hflookup.c - hf_lookup: the factorized BRDF lambda(d0) pi(h)
 * lambda(di) of the homomorphic factorization (Romanyuk, Vyatkin, Voitko,
 * Romanyuk 2020), evaluated as the paper's three texture lookups and two
 * multiplications, in fixed point, combinationally (one item a clock).
 *
 * Three lookup paths, one per direction (sub-scopes l0 for d0, li for di,
 * ph for h; their signals share formats by name). Each:
 *
 *   ZQ  = z's top A fraction bits    the reciprocal ROM's address (wiring)
 *   REC ~ 1 / (1 + z)                reciprocal ROM of 2^A + 1 entries and a
 *                                    linear interpolation between two of them
 *   U = x REC, V = y REC             multipliers: the parabolic map
 *   SU, SV = clamp(U R/2 + (R-1)/2, 0, R-1)   texel coordinates (shift,
 *                                    add of a constant, clamp)
 *   IX, AX / IY, AY                  integer and fraction of SU / SV (wiring;
 *                                    at the last texel IX = R-2, AX = 1)
 *   T00, T01, T10, T11               the map's ROM at (IX + a, IY + b)
 *   TOP = T00 + AX (T01 - T00), BOT = T10 + AX (T11 - T10)
 *   VAL = TOP + AY (BOT - TOP)       the bilinear filter: 3 multipliers
 *
 * then M1 = VAL_l0 * VAL_li and Y = M1 * VAL_ph. The ROMs hold a Ward
 * factorization (vectors/ref_factor.h, rf_ward_maps: roughness alpha,
 * R x R texels with R = the parameter L), each map scaled to largest
 * entry 1.
 *
 * Area: each of a lookup's four texel reads is its own table (the export
 * writes a case statement a read, and synthesis shares none of them: a
 * single-port ROM cannot serve four addresses, nor d0 and di, in one
 * clock) at HF_GE_TABLE_BIT gate equivalents a bit, as such a table maps;
 * the reciprocal ROMs at HF_GE_PER_ROM_BIT (a mask ROM estimate); the
 * arithmetic from the primitives.
 */
#include "units/unit.h"
#include "units/units_brdf.h"
#include "vectors/ref_factor.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define HF_GE_PER_ROM_BIT 0.25
/* One texel read of R x R words of W bits, a case statement over its
 * address, as Yosys and ABC map it to the NanGate45 cells: 0.296, 0.283
 * and 0.283 GE a bit at W = 8, 16, 24 (sh scripts/rom_area.sh L, ABC's
 * light script; its default one 0.262 at 8: docs/area.md, "Tables as
 * mapped"). Before, the model charged the four reads one table at 0.25
 * GE a bit, a quarter each: a quarter to a fifth of what they map to. */
#define HF_GE_TABLE_BIT 0.29

extern const unit_desc unit_hf_lookup;

#define HF_SIGS(X) \
    X(HF_X0,  "x0", IN, "d0 (view) x, local frame") \
    X(HF_Y0,  "y0", IN, "d0 y") \
    X(HF_Z0,  "z0", IN, "d0 z (along the normal), in [0, 1]") \
    X(HF_XI,  "xi", IN, "di (light) x") \
    X(HF_YI,  "yi", IN, "di y") \
    X(HF_ZI,  "zi", IN, "di z") \
    X(HF_XH,  "xh", IN, "h = norm(d0 + di) x") \
    X(HF_YH,  "yh", IN, "h y") \
    X(HF_ZH,  "zh", IN, "h z") \
    X(HF_Y,   "y", OUT, "lambda(d0) lambda(di) pi(h), maps scaled to largest entry 1") \
    X(HF_ZQ,  "zq", INTERNAL, "z's top bits: the reciprocal ROM's address (per lookup: l0, li, ph)") \
    X(HF_REC, "rec", INTERNAL, "1 / (1 + z): reciprocal ROM at zq and zq + 1 LSB, linear interpolation") \
    X(HF_U,   "u", INTERNAL, "multiplier u = x rec (parabolic map)") \
    X(HF_V,   "v", INTERNAL, "multiplier v = y rec") \
    X(HF_SU,  "su", INTERNAL, "texel coordinate clamp(u R/2 + (R-1)/2, 0, R-1)") \
    X(HF_SV,  "sv", INTERNAL, "texel coordinate from v") \
    X(HF_IX,  "ix", INTERNAL, "integer part of su (R-2 at the last texel)") \
    X(HF_AX,  "ax", INTERNAL, "fraction of su (1 at the last texel)") \
    X(HF_IY,  "iy", INTERNAL, "integer part of sv") \
    X(HF_AY,  "ay", INTERNAL, "fraction of sv") \
    X(HF_ROM, "rom", INTERNAL, "the map's ROM reads t00, t01, t10, t11 at (ix + a, iy + b): the entry format") \
    X(HF_DX0, "dx0", INTERNAL, "subtractor dx0 = t01 - t00") \
    X(HF_MX0, "mx0", INTERNAL, "multiplier mx0 = ax dx0") \
    X(HF_TOP, "top", INTERNAL, "adder top = t00 + mx0") \
    X(HF_DX1, "dx1", INTERNAL, "subtractor dx1 = t11 - t10") \
    X(HF_MX1, "mx1", INTERNAL, "multiplier mx1 = ax dx1") \
    X(HF_BOT, "bot", INTERNAL, "adder bot = t10 + mx1") \
    X(HF_DY,  "dy", INTERNAL, "subtractor dy = bot - top") \
    X(HF_MY,  "my", INTERNAL, "multiplier my = ay dy") \
    X(HF_VAL, "val", INTERNAL, "adder val = top + my: the bilinear lookup") \
    X(HF_M1,  "m1", INTERNAL, "multiplier m1 = val(l0) val(li)")
enum { HF_SIGS(UNIT_SIG_ID) HF_NSIGS };

static int lg2(int R) { int k = 0; while ((1 << k) < R) k++; return k; }

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

/* Default formats for width W (docs/factorization.md, "the unit"). */
static void hf_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width, lr = lg2(cfg->L);
    int A = W / 2 > 12 ? 12 : W / 2;     /* reciprocal ROM: 2^A + 1 entries */
    for (int k = 0; k < 3; k++) {
        out->f[HF_X0 + 3 * k] = unit_fmt(1, 2, W - 2);     /* x, y in [-1, 1] */
        out->f[HF_Y0 + 3 * k] = unit_fmt(1, 2, W - 2);
        out->f[HF_Z0 + 3 * k] = unit_fmt(0, 1, W - 1);     /* z in [0, 1] */
    }
    out->f[HF_ZQ] = unit_fmt(0, 1, A);                     /* 2^A-entry reciprocal ROM */
    out->f[HF_REC] = unit_fmt(0, 1, W - 1);                /* 1/(1+z) in [1/2, 1] */
    out->f[HF_U] = unit_fmt(1, 2, W - 2);
    out->f[HF_V] = unit_fmt(1, 2, W - 2);
    out->f[HF_SU] = unit_fmt(0, lr, W - lr);               /* [0, R-1] */
    out->f[HF_SV] = unit_fmt(0, lr, W - lr);
    out->f[HF_IX] = unit_fmt(0, lr, 0);
    out->f[HF_IY] = unit_fmt(0, lr, 0);
    out->f[HF_AX] = unit_fmt(0, 1, W - lr);                /* [0, 1] */
    out->f[HF_AY] = unit_fmt(0, 1, W - lr);
    out->f[HF_ROM] = unit_fmt(0, 1, W - 1);                /* entries in (0, 1] */
    out->f[HF_DX0] = out->f[HF_DX1] = unit_fmt(1, 2, W - 1);
    out->f[HF_MX0] = out->f[HF_MX1] = unit_fmt(1, 2, W - 1);
    out->f[HF_TOP] = out->f[HF_BOT] = unit_fmt(1, 2, W - 1);
    out->f[HF_DY] = unit_fmt(1, 2, W - 1);
    out->f[HF_MY] = unit_fmt(1, 2, W - 1);
    out->f[HF_VAL] = unit_fmt(1, 2, W - 1);
    out->f[HF_M1] = unit_fmt(1, 2, W - 1);
    out->f[HF_Y] = unit_fmt(1, 2, W - 2);
}

/* ------------------------------------------------------------ elements */

/* Quantize v / 2^src into f with rounding r (the kernel's rules: trunc
 * toward minus infinity, round half up); saturates (these elements clamp
 * by construction, so a saturation never happens with the unit's ranges). */
static int64_t quant(__int128 v, int src, sim_fmt f, sim_round r)
{
    int sh = src - f.fbits;
    if (sh > 0) {
        if (r != SIM_RND_TRUNC) v += (__int128)1 << (sh - 1);
        v >>= sh;       /* arithmetic: floor */
    } else if (sh < 0) v *= (__int128)1 << -sh;
    __int128 lo = f.is_signed ? -((__int128)1 << (f.ibits + f.fbits - 1)) : 0;
    __int128 hi = f.is_signed ? ((__int128)1 << (f.ibits + f.fbits - 1)) - 1 : ((__int128)1 << (f.ibits + f.fbits)) - 1;
    if (v < lo) v = lo;
    if (v > hi) v = hi;
    return (int64_t)v;
}

typedef struct hf_rec { sim_fmt fz, fq, fr; sim_round r; } hf_rec;

/* The reciprocal ROM's entry i: 1/(1 + i 2^-A) in REC's fraction bits,
 * rounded by the unit's mode (truncated, or to nearest). */
static int64_t rec_entry(const hf_rec *p, int64_t i)
{
    int A = p->fq.fbits, Fr = p->fr.fbits;
    __int128 den = ((__int128)1 << A) + i;
    __int128 q = p->r == SIM_RND_TRUNC ? ((__int128)1 << (A + Fr)) / den
                                       : (((__int128)1 << (A + Fr + 1)) + den) / (2 * den);
    return (int64_t)q;
}

/* The reciprocal 1/(1 + z) from a ROM of 2^A + 1 entries and a linear
 * interpolation between two of them (the chord):
 *   k = ZQ 2^A (the address), t = (z - ZQ) 2^A in [0, 1),
 *   e_k = 1/(1 + k 2^-A) quantized to REC's format (the ROM),
 *   REC = e_k + t (e_(k+1) - e_k), exact, then quantized into REC.
 * One element: a 2^A-entry ROM with a second read port, a subtractor, a
 * (bits of t) x (bits of REC) multiplier and an adder. */
static int64_t f_rec(const int64_t *in, void *u)
{
    const hf_rec *p = u;
    int Fz = p->fz.fbits, A = p->fq.fbits, Fr = p->fr.fbits;
    int64_t k = in[1];                               /* ZQ's raw: z's top A fraction bits */
    int Ft = Fz > A ? Fz - A : 0;
    int64_t t = Fz > A ? in[0] - (k << (Fz - A)) : 0;   /* t 2^Ft */
    int64_t e[2] = { rec_entry(p, k), rec_entry(p, k + 1) };
    __int128 v = ((__int128)e[0] << Ft) + (__int128)t * (e[1] - e[0]);    /* at Fr + Ft bits */
    return quant(v, Fr + Ft, p->fr, p->r);
}

/* ZQ: z's top A fraction bits (wiring: a truncation whatever the mode). */
static int64_t f_zq(const int64_t *in, void *u)
{
    const hf_rec *p = u;
    int sh = p->fz.fbits - p->fq.fbits;
    return sh >= 0 ? in[0] >> sh : in[0] << -sh;
}

typedef struct hf_addr { sim_fmt fu, fs; int R; sim_round r; } hf_addr;

/* clamp(U R/2 + (R-1)/2, 0, R-1), exact at Fu + 1 fraction bits, then
 * quantized into SU's format. */
static int64_t f_addr(const int64_t *in, void *u)
{
    const hf_addr *p = u;
    int F = p->fu.fbits + 1;
    __int128 s = (__int128)in[0] * p->R + (__int128)(p->R - 1) * ((__int128)1 << p->fu.fbits);
    __int128 hi = (__int128)(p->R - 1) << F;
    if (s < 0) s = 0;
    if (s > hi) s = hi;
    return quant(s, F, p->fs, p->r);
}

typedef struct hf_split { int fs, fa, fi, R, frac; } hf_split;

/* The integer part (frac 0) or the fraction (frac 1) of S; at S >= R-1,
 * R-2 and 1 (the same bilinear value, and IX + 1 stays in the map). */
static int64_t f_split(const int64_t *in, void *u)
{
    const hf_split *p = u;
    int64_t i = in[0] >> p->fs;
    if (i >= p->R - 1) return p->frac ? (int64_t)1 << p->fa : (int64_t)(p->R - 2) << p->fi;
    if (!p->frac) return i << p->fi;
    int64_t f = in[0] & (((int64_t)1 << p->fs) - 1);
    return p->fa >= p->fs ? f << (p->fa - p->fs) : f >> (p->fs - p->fa);
}

typedef struct hf_rom { const int64_t *raw; int R, ox, oy, fx, fy; } hf_rom;

static int64_t f_rom(const int64_t *in, void *u)
{
    const hf_rom *p = u;
    int x = (int)(in[0] >> p->fx) + p->ox, y = (int)(in[1] >> p->fy) + p->oy;
    if (x < 0 || x >= p->R || y < 0 || y >= p->R) return 0;
    return p->raw[y * p->R + x];
}

/* A map quantized into the ROM's format (the kernel's rounding). */
static int64_t rom_raw(double x, sim_fmt f, sim_round r)
{
    double s = ldexp(x, f.fbits);
    double v = r == SIM_RND_TRUNC ? floor(s) : floor(s + 0.5);
    double hi = ldexp(1.0, f.ibits + f.fbits - f.is_signed) - 1;
    return (int64_t)(v > hi ? hi : v < 0 ? 0 : v);
}

/* ------------------------------------------------------ the logic as RTL
 * For the Verilog export (sim_logic_verilog): each element above as
 * statements, the same arithmetic on explicitly sized vectors, exact by
 * construction (test_verilog co-simulates them); the reciprocal ROM as a
 * function of its address, read at zq and zq + 1. An element whose
 * vectors would pass 64 bits (formats far from the defaults) gets no text,
 * and the export refuses it by name. */

typedef struct vt { char *p; size_t n, cap; int full; } vt;

static void vt_add(vt *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void vt_add(vt *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(b->p + b->n, b->cap - b->n, fmt, ap);
    va_end(ap);
    if (k < 0 || (size_t)k >= b->cap - b->n) { b->full = 1; return; }
    b->n += (size_t)k;
}

/* N-bit literal of raw (two's complement). */
static void vt_lit(vt *b, int N, int64_t raw)
{
    uint64_t m = N >= 64 ? UINT64_MAX : (((uint64_t)1 << N) - 1);
    vt_add(b, "%d'h%llx", N, (unsigned long long)((uint64_t)raw & m));
}

/* Input %arg (format f) as a signed value of N >= its width + !signed bits. */
static void vt_sx(vt *b, int arg, sim_fmt f, int N)
{
    int pad = N - f.width;
    if (pad <= 0) vt_add(b, "%%%d", arg);
    else if (f.is_signed) vt_add(b, "{{%d{%%%d[%d]}}, %%%d}", pad, arg, f.width - 1, arg);
    else vt_add(b, "{%d'b0, %%%d}", pad, arg);
}

static int sw(sim_fmt f) { return f.width + !f.is_signed; }

/* %y = quant(v, src, f, r) (the function above) of the N-bit signed wire
 * %t_v: the rounding increment, the shift, the clamp to f's range. */
static void vt_quant(vt *b, int N, int src, sim_fmt f, sim_round r)
{
    int sh = src - f.fbits, up = sh > 0 ? sh : 0, dn = sh < 0 ? -sh : 0;
    int M = (N > f.width + up ? N : f.width + up) + 1;        /* room for the increment, and f's range */
    vt_add(b, "wire [%d:0] %%t_a = {{%d{%%t_v[%d]}}, %%t_v}", M - 1, M - N, N - 1);
    if (up > 63) { b->full = 1; return; }   /* the increment would not fit the 64-bit literal */
    if (up && r != SIM_RND_TRUNC) { vt_add(b, " + "); vt_lit(b, M, (int64_t)1 << (up - 1)); }
    vt_add(b, ";\n");
    int S = M - up + dn;
    if (up) vt_add(b, "wire [%d:0] %%t_s = %%t_a[%d:%d];\n", S - 1, M - 1, up);
    else if (dn) vt_add(b, "wire [%d:0] %%t_s = {%%t_a, %d'b0};\n", S - 1, dn);
    else vt_add(b, "wire [%d:0] %%t_s = %%t_a;\n", S - 1);
    vt_add(b, "assign %%y = $signed(%%t_s) < $signed(");
    vt_lit(b, S, sim_fmt_raw_min(f));
    vt_add(b, ") ? ");
    vt_lit(b, f.width, sim_fmt_raw_min(f));
    vt_add(b, " : $signed(%%t_s) > $signed(");
    vt_lit(b, S, sim_fmt_raw_max(f));
    vt_add(b, ") ? ");
    vt_lit(b, f.width, sim_fmt_raw_max(f));
    vt_add(b, " : %%t_s[%d:0];\n", f.width - 1);
    if (S > 64) b->full = 1;
}

/* The text into y, unless it did not fit (then y has none). */
static void vt_set(sim_signal *y, vt *b)
{
    if (!b->full) sim_logic_verilog(y, b->p);
}

static vt vt_new(sim_ctx *c, size_t cap)
{
    vt b = { sim_alloc(c, cap), 0, cap, 0 };
    b.p[0] = 0;
    return b;
}

/* zq = z shifted right by Fz - A (f_zq), its low bits. */
static void vl_zq(sim_ctx *c, sim_signal *zq, const hf_rec *p)
{
    vt b = vt_new(c, 512);
    int sh = p->fz.fbits - p->fq.fbits, wq = zq->fmt.width;
    int K = sw(p->fz) > wq + sh ? sw(p->fz) : wq + sh;
    vt_add(&b, "wire [%d:0] %%t_z = ", K - 1 + (sh < 0 ? -sh : 0));
    if (sh < 0) vt_add(&b, "{");
    vt_sx(&b, 0, p->fz, K);
    if (sh < 0) vt_add(&b, ", %d'b0}", -sh);
    vt_add(&b, ";\nassign %%y = %%t_z[%d:%d];\n", (sh > 0 ? sh : 0) + wq - 1, sh > 0 ? sh : 0);
    vt_set(zq, &b);
}

/* rec (f_rec): t = z - zq 2^Ft, the entries at zq and zq + 1 from the
 * ROM function, e0 2^Ft + t (e1 - e0), quantized. */
static void vl_rec(sim_ctx *c, sim_signal *rec, const hf_rec *p)
{
    int wq = p->fq.width, A = p->fq.fbits, Fz = p->fz.fbits, Ft = Fz > A ? Fz - A : 0;
    if (wq > 14 || p->fq.is_signed) return;
    int64_t n = ((int64_t)1 << wq) + 1, emax = 0;
    for (int64_t i = 0; i < n; i++) if (rec_entry(p, i) > emax) emax = rec_entry(p, i);
    int EW = 1;
    while (EW < 62 && ((int64_t)1 << EW) <= emax) EW++;
    vt b = vt_new(c, (size_t)n * 64 + 4096);
    vt_add(&b, "function [%d:0] %%t_rom;\ninput [%d:0] i;\ncase (i)\n", EW - 1, wq);
    for (int64_t i = 0; i < n; i++) {
        vt_add(&b, "    ");
        vt_lit(&b, wq + 1, i);
        vt_add(&b, ": %%t_rom = ");
        vt_lit(&b, EW, rec_entry(p, i));
        vt_add(&b, ";\n");
    }
    vt_add(&b, "    default: %%t_rom = %d'b0;\nendcase\nendfunction\n", EW);
    vt_add(&b, "wire [%d:0] %%t_e0 = %%t_rom({1'b0, %%1});\n", EW - 1);
    vt_add(&b, "wire [%d:0] %%t_e1 = %%t_rom({1'b0, %%1} + ", EW - 1);
    vt_lit(&b, wq + 1, 1);
    vt_add(&b, ");\n");
    if (!Ft) {
        vt_add(&b, "wire [%d:0] %%t_v = {1'b0, %%t_e0};\n", EW);
        vt_quant(&b, EW + 1, p->fr.fbits, p->fr, p->r);
    } else {
        int NT = (sw(p->fz) > wq + 1 + Ft ? sw(p->fz) : wq + 1 + Ft) + 1;
        int NP = NT + EW + 1, NV = (NP > EW + 1 + Ft ? NP : EW + 1 + Ft) + 1;
        vt_add(&b, "wire [%d:0] %%t_t = ", NT - 1);
        vt_sx(&b, 0, p->fz, NT);
        vt_add(&b, " - {%d'b0, %%1, %d'b0};\n", NT - wq - Ft, Ft);
        vt_add(&b, "wire [%d:0] %%t_d = {1'b0, %%t_e1} - {1'b0, %%t_e0};\n", EW);
        vt_add(&b, "wire [%d:0] %%t_p = $signed(%%t_t) * $signed(%%t_d);\n", NP - 1);
        vt_add(&b, "wire [%d:0] %%t_v = {%d'b0, %%t_e0, %d'b0} + {{%d{%%t_p[%d]}}, %%t_p};\n",
               NV - 1, NV - EW - Ft, Ft, NV - NP, NP - 1);
        vt_quant(&b, NV, p->fr.fbits + Ft, p->fr, p->r);
    }
    vt_set(rec, &b);
}

/* su, sv (f_addr): clamp(U R + (R-1) 2^Fu, 0, (R-1) 2^(Fu+1)) at Fu + 1
 * fraction bits, quantized; R a power of two (the parameter's kind). */
static void vl_addr(sim_ctx *c, sim_signal *s, const hf_addr *p)
{
    int lr = lg2(p->R);
    if ((1 << lr) != p->R) return;
    int F = p->fu.fbits + 1, NS = sw(p->fu) + lr + 2;
    /* the literals below are NS-bit values held in 64 bits: no text past that */
    if (NS > 64) return;
    vt b = vt_new(c, 1024);
    vt_add(&b, "wire [%d:0] %%t_w = {", NS - 1);
    vt_sx(&b, 0, p->fu, NS - lr);
    vt_add(&b, lr ? ", %d'b0} + " : "} + ", lr);
    vt_lit(&b, NS, (int64_t)(p->R - 1) << p->fu.fbits);
    vt_add(&b, ";\nwire [%d:0] %%t_v = $signed(%%t_w) < $signed(%d'b0) ? %d'b0 : $signed(%%t_w) > $signed(", NS - 1, NS, NS);
    vt_lit(&b, NS, (int64_t)(p->R - 1) << F);
    vt_add(&b, ") ? ");
    vt_lit(&b, NS, (int64_t)(p->R - 1) << F);
    vt_add(&b, " : %%t_w;\n");
    vt_quant(&b, NS, F, s->fmt, p->r);
    vt_set(s, &b);
}

/* ix, iy, ax, ay (f_split): S's integer part or its fraction, R-2 and 1
 * at the last texel; into y's bits. */
static void vl_split(sim_ctx *c, sim_signal *y, sim_fmt fs, const hf_split *p)
{
    int wo = y->fmt.width, lr = lg2(p->R), NX = sw(fs) > p->fs + lr + 2 ? sw(fs) : p->fs + lr + 2;
    vt b = vt_new(c, 1024);
    vt_add(&b, "wire [%d:0] %%t_x = ", NX - 1);
    vt_sx(&b, 0, fs, NX);
    vt_add(&b, ";\nwire %%t_c = $signed(%%t_x[%d:%d]) >= $signed(", NX - 1, p->fs);
    vt_lit(&b, NX - p->fs, p->R - 1);
    vt_add(&b, ");\nwire [%d:0] %%t_r = ", wo - 1);
    if (p->frac) {
        int lsh = p->fa > p->fs ? p->fa - p->fs : 0, rsh = p->fs > p->fa ? p->fs - p->fa : 0;
        if (!p->fs) vt_add(&b, "%d'b0;\n", wo);
        else {
            vt_add(&b, "%%t_f[%d:%d];\nwire [%d:0] %%t_f = {%d'b0, %%t_x[%d:0]", rsh + wo - 1, rsh,
                   wo + p->fs + lsh - 1, wo, p->fs - 1);
            vt_add(&b, lsh ? ", %d'b0};\n" : "};\n", lsh);
        }
    } else {
        vt_add(&b, "%%t_i[%d:0];\nwire [%d:0] %%t_i = {{%d{%%t_x[%d]}}, %%t_x[%d:%d]", wo - 1,
               wo + NX - p->fs + p->fi - 1, wo, NX - 1, NX - 1, p->fs);
        vt_add(&b, p->fi ? ", %d'b0};\n" : "};\n", p->fi);
    }
    vt_add(&b, "assign %%y = %%t_c ? ");
    vt_lit(&b, wo, p->frac ? (int64_t)1 << p->fa : (int64_t)(p->R - 2) << p->fi);
    vt_add(&b, " : %%t_r;\n");
    vt_set(y, &b);
}

static sim_signal *lookup(sim_ctx *c, sim_scope *top, const char *scope, const unit_cfg *cfg,
                          const unit_fmts *f, sim_signal *x, sim_signal *y, sim_signal *z,
                          const double *map)
{
    sim_scope *sc = sim_scope_new(c, top, scope);
    int R = cfg->L;
    const sim_fmt *F = f->f;
    hf_rec *rp = sim_alloc(c, sizeof *rp);
    rp->fz = z->fmt; rp->fq = F[HF_ZQ]; rp->fr = F[HF_REC]; rp->r = cfg->rnd;
    sim_signal *zq = sim_logic(c, sc, "zq", F[HF_ZQ], 1, &z, f_zq, rp, 0);
    vl_zq(c, zq, rp);
    int A = F[HF_ZQ].fbits, wr = F[HF_REC].ibits + F[HF_REC].fbits;
    int wt = rp->fz.fbits > A ? rp->fz.fbits - A : 0;
    double rec_ge = HF_GE_PER_ROM_BIT * (ldexp(1.0, A) + 1) * wr * 2     /* two read ports */
                  + (double)wt * wr * SIM_GE_FA + 2.0 * wr * SIM_GE_FA;  /* multiplier, subtractor, adder */
    sim_signal *zin[2] = { z, zq };
    sim_signal *rec = sim_logic(c, sc, "rec", F[HF_REC], 2, zin, f_rec, rp, rec_ge);
    vl_rec(c, rec, rp);
    /* For range analysis, which cannot enumerate z past 2^16 values: the
     * reciprocal is within [0, 1] (every entry is, and so is a chord
     * between two of them, rounded onto the same grid), when REC holds 1 */
    if (brdf_holds(F[HF_REC], 0, 1)) sim_logic_linear(rec, 0, 0, 0, 1);
    sim_signal *u = sim_mul(c, sc, "u", F[HF_U], x, rec);
    sim_signal *v = sim_mul(c, sc, "v", F[HF_V], y, rec);
    sim_signal *ax = NULL, *ix = NULL, *ay = NULL, *iy = NULL;
    for (int k = 0; k < 2; k++) {
        hf_addr *ap = sim_alloc(c, sizeof *ap);
        ap->fu = F[k ? HF_V : HF_U]; ap->fs = F[k ? HF_SV : HF_SU]; ap->R = R; ap->r = cfg->rnd;
        int w = ap->fu.ibits + ap->fu.fbits + 2;
        sim_signal *s = sim_logic(c, sc, k ? "sv" : "su", ap->fs, 1, k ? &v : &u, f_addr, ap,
                                  w * (SIM_GE_FA + 2 * SIM_GE_MUX2));
        vl_addr(c, s, ap);
        hf_split *pi = sim_alloc(c, sizeof *pi), *pa = sim_alloc(c, sizeof *pa);
        pi->fs = pa->fs = ap->fs.fbits; pi->R = pa->R = R;
        pi->fa = 0; pi->frac = 0; pi->fi = F[k ? HF_IY : HF_IX].fbits;
        pa->fa = F[k ? HF_AY : HF_AX].fbits; pa->frac = 1;
        int lr = lg2(R);
        sim_signal *ii = sim_logic(c, sc, k ? "iy" : "ix", F[k ? HF_IY : HF_IX], 1, &s, f_split, pi, lr * SIM_GE_MUX2);
        sim_signal *aa = sim_logic(c, sc, k ? "ay" : "ax", F[k ? HF_AY : HF_AX], 1, &s, f_split, pa,
                                   (pa->fa + 1) * SIM_GE_AND2);
        vl_split(c, ii, ap->fs, pi);
        vl_split(c, aa, ap->fs, pa);
        if (brdf_holds(F[k ? HF_AY : HF_AX], 0, 1)) sim_logic_linear(aa, 0, 0, 0, 1);   /* a fraction, or 1 */
        if (k) { iy = ii; ay = aa; } else { ix = ii; ax = aa; }
    }
    int64_t *raw = sim_alloc(c, sizeof(int64_t) * (size_t)R * R);
    for (int j = 0; j < R * R; j++) raw[j] = rom_raw(map[j], F[HF_ROM], cfg->rnd);
    double rom_ge = HF_GE_TABLE_BIT * R * R * (F[HF_ROM].ibits + F[HF_ROM].fbits);
    sim_signal *t[4], *idx[2] = { ix, iy };
    static const char *const tn[4] = { "t00", "t01", "t10", "t11" };
    sim_scope *rs = sim_scope_new(c, sc, "rom");    /* the four reads share the entry format "rom" */
    for (int k = 0; k < 4; k++) {
        hf_rom *p = sim_alloc(c, sizeof *p);
        p->raw = raw; p->R = R; p->ox = k & 1; p->oy = k >> 1;
        p->fx = F[HF_IX].fbits; p->fy = F[HF_IY].fbits;
        t[k] = sim_logic(c, rs, tn[k], F[HF_ROM], 2, idx, f_rom, p, rom_ge);
    }
    sim_signal *dx0 = sim_sub(c, sc, "dx0", F[HF_DX0], t[1], t[0]);
    sim_signal *mx0 = sim_mul(c, sc, "mx0", F[HF_MX0], ax, dx0);
    sim_signal *tp = sim_add(c, sc, "top", F[HF_TOP], t[0], mx0);
    sim_signal *dx1 = sim_sub(c, sc, "dx1", F[HF_DX1], t[3], t[2]);
    sim_signal *mx1 = sim_mul(c, sc, "mx1", F[HF_MX1], ax, dx1);
    sim_signal *bt = sim_add(c, sc, "bot", F[HF_BOT], t[2], mx1);
    sim_signal *dy = sim_sub(c, sc, "dy", F[HF_DY], bt, tp);
    sim_signal *my = sim_mul(c, sc, "my", F[HF_MY], ay, dy);
    return sim_add(c, sc, "val", F[HF_VAL], tp, my);
}

static int hf_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                    const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    (void)clk;
    const rf_maps *m = rf_ward_maps(cfg->L, cfg->alpha);
    if (!m) { snprintf(err, errlen, "hf_lookup: the factorization of the maps failed"); return -1; }
    if (f->f[HF_ROM].is_signed || f->f[HF_ZQ].is_signed) {
        snprintf(err, errlen, "hf_lookup: rom and zq must be unsigned formats");
        return -1;
    }
    sim_fmt u1 = unit_fmt(0, 1, 0);
    for (int i = 0; i < 9; i++) io->in[i] = sim_signal_new(c, sc, unit_hf_lookup.sigs[i].name, f->f[i], SIM_KIND_INPUT);
    io->in_valid = sim_bit_new(c, sc, "in_valid", SIM_KIND_INPUT);
    io->in_ready = sim_const_raw(c, sc, "in_ready", u1, 1);
    io->out_valid = sim_signal_new(c, sc, "out_valid", u1, SIM_KIND_WIRE);
    sim_assign(c, io->out_valid, io->in_valid);
    sim_signal *l0 = lookup(c, sc, "l0", cfg, f, io->in[0], io->in[1], io->in[2], m->lam);
    sim_signal *li = lookup(c, sc, "li", cfg, f, io->in[3], io->in[4], io->in[5], m->lam);
    sim_signal *ph = lookup(c, sc, "ph", cfg, f, io->in[6], io->in[7], io->in[8], m->pi);
    sim_signal *m1 = sim_mul(c, sc, "m1", f->f[HF_M1], l0, li);
    io->out[0] = sim_mul(c, sc, "y", f->f[HF_Y], m1, ph);
    io->scope = sc;
    return 0;
}

static void hf_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    const rf_maps *m = rf_ward_maps(cfg->L, cfg->alpha);
    out[0] = m ? rf_maps_lookup(m, in, in + 3, in + 6) : NAN;
}

/* ---------------------------------------------------------------- bound */

/* Largest difference of neighbouring texels along x (dir 0) or y (1):
 * the bilinear filter's slope per texel of address error. */
static double slope(const double *map, int R, int dir)
{
    double d = 0;
    for (int j = 0; j < R; j++)
        for (int i = 0; i + 1 < R; i++) {
            double a = dir ? map[i * R + j] : map[j * R + i], b = dir ? map[(i + 1) * R + j] : map[j * R + i + 1];
            if (fabs(a - b) > d) d = fabs(a - b);
        }
    return d;
}

static int imin(int a, int b) { return a < b ? a : b; }
static int imax(int a, int b) { return a > b ? a : b; }

/* |VAL - bilinear(map, exact address)| for one lookup (docs/factorization.md):
 * the address error through the map's slopes, the ROM's quantization, the
 * filter's arithmetic. Each value carries the fraction bits it really has
 * (eff: its format's, or fewer when its operands have fewer), so that
 * widening a signal never makes the bound grow. *eff_val: VAL's.
 * INFINITY when a format cannot hold its value. */
static double lookup_bound(const unit_cfg *cfg, const unit_fmts *fm, const double *map, int kx, int *eff_val)
{
    const sim_fmt *F = fm->f;
    sim_round r = cfg->rnd;
    int R = cfg->L;
    sim_fmt fx = F[kx], fy = F[kx + 1], fz = F[kx + 2];
    if (!brdf_holds(fx, -1, 1) || !brdf_holds(fy, -1, 1) || !brdf_holds(fz, 0, 1)) return INFINITY;
    if (!brdf_holds(F[HF_ZQ], 0, 1) || F[HF_ZQ].fbits > fz.fbits || F[HF_ZQ].fbits > 20
        || !brdf_holds(F[HF_REC], 0.5, 1)) return INFINITY;
    /* the chord of 1/(1+z) over a step h = 2^-A lies above it by at most
     * h^2 max|f''| / 8 = h^2 / 4; the ROM's entries and REC's
     * quantization add one quantization each */
    int A = F[HF_ZQ].fbits;
    double e_rec = ldexp(0.25, -2 * A) + 2 * unit_qerr(F[HF_REC], 200, r);
    int e_fr = F[HF_REC].fbits;
    double e_s[2];
    int eff_a[2];
    for (int k = 0; k < 2; k++) {
        sim_fmt fi = k ? fy : fx, fu = F[k ? HF_V : HF_U], fs = F[k ? HF_SV : HF_SU];
        double e_u = e_rec + unit_qerr(fu, fi.fbits + e_fr, r);       /* |x| <= 1 */
        int eff_u = imin(fu.fbits, fi.fbits + e_fr);
        if (!brdf_holds(fu, -1 - e_u, 1 + e_u)) return INFINITY;
        if (!brdf_holds(fs, 0, R - 1)) return INFINITY;
        e_s[k] = e_u * R / 2 + unit_qerr(fs, eff_u + 1, r);             /* the clamp is 1-Lipschitz */
        int eff_s = imin(fs.fbits, eff_u + 1);
        sim_fmt fa = F[k ? HF_AY : HF_AX], fi2 = F[k ? HF_IY : HF_IX];
        if (!brdf_holds(fa, 0, 1) || !brdf_holds(fi2, 0, R - 2)) return INFINITY;
        /* a weight with fewer fraction bits than the coordinate is its
         * truncation (wiring drops the low bits, whatever the mode) */
        e_s[k] += unit_qerr(fa, eff_s, SIM_RND_TRUNC);
        eff_a[k] = imin(fa.fbits, eff_s);
    }
    sim_fmt fr = F[HF_ROM];
    if (!brdf_holds(fr, 0, 1)) return INFINITY;
    double e_rom = unit_qerr(fr, 200, r);
    double sx = slope(map, R, 0) + 2 * e_rom, sy = slope(map, R, 1) + 2 * e_rom;
    /* the filter at the hardware's address, on the ROM's values: the x
     * lerps (top from dx0, mx0; bot from dx1, mx1), then the y lerp */
    double e_row[2];
    int eff_row[2];
    for (int k = 0; k < 2; k++) {
        sim_fmt fd = F[k ? HF_DX1 : HF_DX0], fm2 = F[k ? HF_MX1 : HF_MX0], ft = F[k ? HF_BOT : HF_TOP];
        if (!brdf_holds(fd, -1, 1) || !brdf_holds(fm2, -1, 1)) return INFINITY;
        double e_dx = unit_qerr(fd, fr.fbits, r);
        int eff_dx = imin(fd.fbits, fr.fbits);
        int fp = eff_a[0] + eff_dx;
        double e_mx = e_dx + unit_qerr(fm2, fp, r);                     /* |AX| <= 1 */
        int eff_mx = imin(fm2.fbits, fp);
        e_row[k] = e_mx + unit_qerr(ft, imax(fr.fbits, eff_mx), r);
        eff_row[k] = imin(ft.fbits, imax(fr.fbits, eff_mx));
        if (!brdf_holds(ft, -e_row[k], 1 + e_row[k])) return INFINITY;
    }
    double e_tb = e_row[0] > e_row[1] ? e_row[0] : e_row[1];
    int src_dy = imax(eff_row[0], eff_row[1]);
    double e_dy0 = unit_qerr(F[HF_DY], src_dy, r);
    int eff_dy = imin(F[HF_DY].fbits, src_dy);
    double m_dy = 1 + e_row[0] + e_row[1] + e_dy0;
    double e_my0 = unit_qerr(F[HF_MY], eff_a[1] + eff_dy, r);
    int eff_my = imin(F[HF_MY].fbits, eff_a[1] + eff_dy);
    if (!brdf_holds(F[HF_DY], -m_dy, m_dy) || !brdf_holds(F[HF_MY], -m_dy - e_my0, m_dy + e_my0)) return INFINITY;
    /* VAL - exact = (1 - AY)(TOP - top) + AY (BOT - bot) + AY e(DY) + e(MY) + e(VAL) */
    int src_val = imax(eff_row[0], eff_my);
    double e_val = e_tb + e_dy0 + e_my0 + unit_qerr(F[HF_VAL], src_val, r);
    *eff_val = imin(F[HF_VAL].fbits, src_val);
    double e = sx * e_s[0] + sy * e_s[1] + e_rom + e_val;
    if (!brdf_holds(F[HF_VAL], -e, 1 + e)) return INFINITY;
    return e;
}

static void hf_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    const rf_maps *m = rf_ward_maps(cfg->L, cfg->alpha);
    per_out[0] = INFINITY;
    if (!m) return;
    int f0, fi, fp;
    double e0 = lookup_bound(cfg, f, m->lam, HF_X0, &f0), ei = lookup_bound(cfg, f, m->lam, HF_XI, &fi);
    double ep = lookup_bound(cfg, f, m->pi, HF_XH, &fp);
    if (!isfinite(e0) || !isfinite(ei) || !isfinite(ep)) return;
    sim_fmt f1 = f->f[HF_M1], fyo = f->f[HF_Y];
    /* values in [0, 1] exactly, within e of it in hardware */
    double e1 = e0 * (1 + ei) + ei + unit_qerr(f1, f0 + fi, cfg->rnd);
    int eff1 = imin(f1.fbits, f0 + fi);
    if (!brdf_holds(f1, -e1, 1 + e1)) return;
    double ey = e1 * (1 + ep) + ep + unit_qerr(fyo, eff1 + fp, cfg->rnd);
    if (!brdf_holds(fyo, -ey, 1 + ey)) return;
    per_out[0] = ey;
}

const unit_desc unit_hf_lookup = {
    .name = "hf_lookup",
    .ref = &ref_model_hf_lookup,
    .summary = "factorized BRDF lambda(d0) pi(h) lambda(di): parabolic addresses, 3 bilinear ROM lookups, 2 multipliers; one item a clock",
    .source = "Romanyuk et al. (2020), eqs. 6-7 (homomorphic factorization)",
    UNIT_SIGS(HF_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "comb", "three lookup paths and two multipliers, combinational: one item a clock" } },
    .nparams = 2,
    .params = {
        { "L", UNIT_P_POW2, offsetof(unit_cfg, L), 4, 32, 8, NULL, "map resolution R (R x R texels)" },
        { "alpha", UNIT_P_REAL, offsetof(unit_cfg, alpha), 0.1, 0.6, 0.2, NULL, "roughness of the Ward BRDF the maps factorize" } },
    .fmt_rule = "x, y s2.(W-2); z u1.(W-1); zq u1.min(W/2, 12); rec, rom u1.(W-1); u, v s2.(W-2); su, sv "
                "u(lgR).(W-lgR); filter s2.(W-1); y s2.(W-2)",
    .formats = hf_formats, .beats = beats1, .build = hf_build,
    .ideal = hf_ideal, .bound = hf_bound,
};

