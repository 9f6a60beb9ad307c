/* unit_div.c - a sequential restoring divider, one quotient bit per clock,
 * and the div unit built on it (schlick and mschlick reuse the core,
 * unit_schlick.c).
 *
 * The classic A-Q structure: a remainder register R and a quotient shift
 * register Q. Every clock
 *
 *   R2    = 2 R + msb(Q)          wiring (a shift)
 *   TRIAL = R2 - D                subtractor
 *   qbit  = TRIAL >= 0            its sign bit
 *   R    <= qbit ? TRIAL : R2     restore mux
 *   Q    <= (Q << 1) | qbit       wiring
 *
 * In the first clock of an item R and Q come from the dividend instead
 * (muxes R_IN, Q_IN). With raws as integers, the unit divides the dividend
 * N' = n_raw 2^s, s = F_q + F_r - F_n, by d_raw aligned to R's LSB, so
 * after F clocks (F = the quotient register's value bits) Q holds
 * floor(n/d 2^F_q) exactly, i.e. the quotient truncated to q's format, and
 * R the remainder, (n - q d) 2^F_q in R's format. Low dividend bits that
 * enter Q first are what makes integer division work (formats u8.0: N' =
 * n, R starts at 0 and n's bits are shifted in).
 *
 * Any d > 0 works as long as the quotient fits, n/d < 2^I_q: the domain
 * [1/2, 1] of the div unit is only the golden vectors' choice. d = 0 sets
 * the dz flag; every trial then succeeds, so Q is all ones and R ends as
 * the dividend, the RISC-V convention. The divider always truncates,
 * whatever --round says: rounding would need a guard bit and a sticky
 * remainder test (docs/brdf.md).
 */
#include "units/unit.h"
#include "units/units_brdf.h"
#include "vectors/ref_brdf.h"
#include "sim/sim_area.h"
#include <math.h>
#include <stddef.h>
#include <string.h>

/* Quotient bits: the Q register's width without a sign bit. */
static int dv_steps(sim_fmt q) { return q.width - q.is_signed; }

/* ------------------------------------------------------------------ logic */

typedef struct dv_load { int s, qb; } dv_load;

/* N' = floor(num_raw 2^(s - shr)). Formats keep num_raw 2^s within 125
 * bits (checked at build), so this fits a __int128. */
static sim_wide dividend(const int64_t *in, const dv_load *l, int has_shr)
{
    int e = l->s - (has_shr ? (int)in[1] : 0);
    sim_wide v = in[0];
    if (e >= 0) return v * ((sim_wide)1 << e);
    if (e <= -126) return v < 0 ? -1 : 0;
    sim_wide d = (sim_wide)1 << -e, q = v / d;
    return q * d > v ? q - 1 : q;               /* floor, also for v < 0 */
}
static int64_t f_r_load(const int64_t *in, void *u)
{
    const dv_load *l = u;
    return (int64_t)(dividend(in, l, 0) >> l->qb);
}
static int64_t f_r_load_shr(const int64_t *in, void *u)
{
    const dv_load *l = u;
    return (int64_t)(dividend(in, l, 1) >> l->qb);
}
static int64_t f_q_load(const int64_t *in, void *u)
{
    const dv_load *l = u;
    return (int64_t)(dividend(in, l, 0) & (((sim_wide)1 << l->qb) - 1));
}
static int64_t f_q_load_shr(const int64_t *in, void *u)
{
    const dv_load *l = u;
    return (int64_t)(dividend(in, l, 1) & (((sim_wide)1 << l->qb) - 1));
}
static int64_t f_not(const int64_t *in, void *u) { (void)u; return !in[0]; }
/* R2 = 2 R + msb(Q) */
static int64_t f_r2(const int64_t *in, void *u)
{
    int qb = *(const int *)u;
    return (int64_t)((uint64_t)in[0] << 1) + ((in[1] >> (qb - 1)) & 1);
}
static int64_t f_qbit(const int64_t *in, void *u) { (void)u; return in[0] >= 0; }
static int64_t f_q_next(const int64_t *in, void *u)
{
    int qb = *(const int *)u;
    uint64_t mask = qb >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << qb) - 1;
    return (int64_t)((((uint64_t)in[0] << 1) | (uint64_t)in[1]) & mask);
}
static int64_t f_is_zero(const int64_t *in, void *u) { return in[0] == 0 ? *(const int64_t *)u : 0; }

/* ------------------------------------------------------ the logic as RTL
 * For the Verilog export (sim_logic_verilog): the same functions as
 * statements, exact by construction; test_verilog co-simulates them. */

/* Bits [lo + w - 1 : lo] of floor(x * 2^d), x the input %K of width wx
 * (signed or not), shifted further right by input %1 when var_shr: into
 * %y, zero-extended from w to wy bits. */
static void vl_scaled(sim_signal *y, int wx, int sgn, int d, int var_shr, int w, int wy)
{
    char t[600], pad[40] = "";
    int dpos = d > 0 ? d : 0, dneg = d < 0 ? -d : 0, T = wx + dpos + dneg + w + 1;
    char sgnbit[32];
    snprintf(sgnbit, sizeof sgnbit, sgn ? "%%0[%d]" : "1'b0", wx - 1);
    if (wy > w) snprintf(pad, sizeof pad, "%d'b0, ", wy - w);
    char zeros[32] = "";
    if (dpos) snprintf(zeros, sizeof zeros, ", %d'b0", dpos);
    int n = snprintf(t, sizeof t, "wire [%d:0] %%t_e = {{%d{%s}}, %%0%s};\n", T - 1, T - wx - dpos, sgnbit, zeros);
    if (var_shr)
        n += snprintf(t + n, sizeof t - (size_t)n, "wire [%d:0] %%t_s = %s;\nassign %%y = {%s%%t_s[%d:%d]};\n", T - 1,
                      sgn ? "$signed(%t_e) >>> %1" : "%t_e >> %1", pad, dneg + w - 1, dneg);
    else
        n += snprintf(t + n, sizeof t - (size_t)n, "assign %%y = {%s%%t_e[%d:%d]};\n", pad, dneg + w - 1, dneg);
    sim_logic_verilog(y, t);
}

/* ------------------------------------------------------------------ build */

/* Builds the sequencer and the divider of num by den (num shifted right by
 * the raw value of shr first, when shr is given; shr_max its largest value,
 * for the barrel shifter's area). Formats of the unit's signals "q", "r"
 * and, if it has one, "dz". Returns Q, or NULL with a message. */
sim_signal *dv_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                     const unit_fmts *f, unit_io *io, sim_signal *num, sim_signal *den,
                     sim_signal *shr, int shr_max, char *err, size_t errlen)
{
    int iq = unit_sig_index(u, "q"), ir = unit_sig_index(u, "r"), idz = unit_sig_index(u, "dz");
    char b1[SIM_FMT_STRLEN], b2[SIM_FMT_STRLEN];
    if (iq < 0 || ir < 0) { snprintf(err, errlen, "%s: internal: no q or r signal", u->name); return NULL; }
    sim_fmt fq = f->f[iq], fr = f->f[ir], fd = den->fmt, fn = num->fmt;
    int qb = dv_steps(fq);
    if (fr.fbits < fd.fbits || sim_fmt_real_max(fr) < sim_fmt_real_max(fd) || fr.width > 62) {
        snprintf(err, errlen, "%s: the remainder register r=%s cannot hold every value below the divisor "
                 "%s=%s (r needs at least its fraction bits and range, and at most 62 bits: set --fmt r=... too)",
                 u->name, sim_fmt_str(fr, b1), den->name, sim_fmt_str(fd, b2));
        return NULL;
    }
    dv_load *ld = sim_alloc(c, sizeof *ld);
    ld->qb = qb;
    ld->s = fq.fbits + fr.fbits - fn.fbits;
    if (qb < 1 || ld->s + fn.width > 125 || ld->s < -125) {
        snprintf(err, errlen, "%s: formats q=%s, r=%s and the dividend's %s are too far apart "
                 "for the divider", u->name, sim_fmt_str(fq, b1), sim_fmt_str(fr, b2), sim_fmt_str(fn, b1));
        return NULL;
    }
    if (idz >= 0 && !brdf_holds(f->f[idz], 0, 1)) {
        snprintf(err, errlen, "%s: the flag dz=%s must hold 1", u->name, sim_fmt_str(f->f[idz], b1));
        return NULL;
    }

    sim_signal *next, *first;
    brdf_seq(c, sc, clk, qb, io, &next, &first);
    (void)next;
    int *qbp = sim_alloc(c, sizeof *qbp);
    *qbp = qb;
    sim_fmt u1 = unit_fmt(0, 1, 0);
    sim_signal *ld_in[2] = { num, shr };
    int nld = shr ? 2 : 1;
    /* Loading is wiring, unless the dividend is shifted by a variable
     * amount: then a barrel shifter over the R-Q pair. */
    double shifter = shr ? brdf_bitlen((uint64_t)shr_max) * (fr.width + qb) * SIM_GE_MUX2 : 0.0;
    sim_signal *r_load = sim_logic(c, sc, "r_load", fr, nld, ld_in, shr ? f_r_load_shr : f_r_load, ld, shifter);
    vl_scaled(r_load, fn.width, fn.is_signed, ld->s - qb, shr != NULL, fr.width, fr.width);
    if (!shr) {
        /* For range analysis: R's load is n 2^(F_q - qb), floored to R's
         * LSB (exact when s >= qb), as long as R holds every value of it
         * (the function is monotone in n: its ends suffice). */
        int64_t ends[2] = { num->raw_min, num->raw_max }, v0 = f_r_load(&ends[0], ld), v1 = f_r_load(&ends[1], ld);
        if (v0 >= sim_fmt_raw_min(fr) && v1 <= sim_fmt_raw_max(fr)) {
            double lsb = ldexp(1, -fr.fbits), e = ld->s >= qb ? 0 : (1 - ldexp(1, ld->s - qb)) * lsb;
            sim_logic_linear(r_load, 0, ldexp(1, fq.fbits - qb), -e, 0);
        }
    }
    sim_logic_depth(r_load, shr ? brdf_bitlen((uint64_t)shr_max) : 0);   /* wiring, or the shifter's levels */
    char vt[200];

    sim_signal *r = sim_reg(c, sc, "r", fr, clk, NULL, NULL, NULL, 0);
    sim_signal *q = sim_reg(c, sc, "q", fq, clk, NULL, NULL, NULL, 0);
    sim_signal *r_in_src[2] = { r, r_load };
    sim_signal *r_in = sim_mux(c, sc, "r_in", fr, first, 2, r_in_src);
    sim_signal *q_in;
    if (shr || ld->s < qb) {
        /* Dividend bits below the quotient's LSB enter through Q. */
        sim_signal *q_load = sim_logic(c, sc, "q_load", fq, nld, ld_in, shr ? f_q_load_shr : f_q_load, ld, 0);
        vl_scaled(q_load, fn.width, fn.is_signed, ld->s, shr != NULL, qb < fq.width ? qb : fq.width, fq.width);
        sim_logic_depth(q_load, shr ? brdf_bitlen((uint64_t)shr_max) : 0);
        sim_signal *q_in_src[2] = { q, q_load };
        q_in = sim_mux(c, sc, "q_in", fq, first, 2, q_in_src);
    } else {
        /* They never do: Q starts at zero, an AND gate a bit. */
        sim_signal *busy = sim_logic(c, sc, "busy", u1, 1, &first, f_not, NULL, SIM_GE_INV);
        sim_logic_depth(busy, 1);
        q_in = sim_bk(c, sc, "q_in", fq, busy, q);
    }
    sim_signal *r2_in[2] = { r_in, q_in };
    sim_signal *r2 = sim_logic(c, sc, "r2", unit_fmt(fr.is_signed, fr.ibits + 1, fr.fbits), 2, r2_in, f_r2, qbp, 0);
    snprintf(vt, sizeof vt, "assign %%y = {%%0, %%1[%d]};", qb - 1);
    sim_logic_verilog(r2, vt);
    sim_logic_depth(r2, 0);       /* R shifted left, Q's top bit in: wiring */
    sim_logic_linear(r2, 0, 2, 0, ldexp(1, -fr.fbits));    /* 2 R + one LSB or none */
    sim_signal *trial = sim_sub(c, sc, "trial", unit_fmt(1, fr.ibits + 2, fr.fbits), r2, den);
    sim_signal *qbit = sim_logic(c, sc, "qbit", u1, 1, &trial, f_qbit, NULL, SIM_GE_INV);
    snprintf(vt, sizeof vt, "assign %%y = ~%%0[%d];", trial->fmt.width - 1);
    sim_logic_verilog(qbit, vt);
    /* the trial's sign inverted: mapped, no cell of its own (ABC takes
     * the polarity into the sign's last AOI/OAI cell and the restore
     * mux's select: OpenSTA's path through div at width 8 has no
     * inverter there), as a subtractor's inverter is none */
    sim_logic_depth(qbit, 0);
    sim_logic_monotone(qbit);     /* 0 below zero, 1 from there */
    /* The restore mux keeps TRIAL's format: its select arrives a delta
     * after its data, and a narrower output would count the transient
     * (unselected) values as overflows. R quantizes the settled value. */
    sim_signal *r_next_src[2] = { r2, trial };
    sim_reg_connect(r, sim_mux(c, sc, "r_next", trial->fmt, qbit, 2, r_next_src));
    sim_signal *q_next_in[2] = { q_in, qbit };
    sim_signal *q_next = sim_logic(c, sc, "q_next", fq, 2, q_next_in, f_q_next, qbp, 0);
    {
        int kb = qb < fq.width ? qb : fq.width;     /* the quotient bits kept */
        char pad[32] = "", low[40] = "";
        if (fq.width > kb) snprintf(pad, sizeof pad, "%d'b0, ", fq.width - kb);
        if (kb >= 2) snprintf(low, sizeof low, "%%0[%d:0], ", kb - 2);
        snprintf(vt, sizeof vt, "assign %%y = {%s%s%%1};", pad, low);
        sim_logic_verilog(q_next, vt);
        sim_logic_depth(q_next, 0);   /* Q shifted left, the new bit in: wiring */
    }
    sim_reg_connect(q, q_next);
    if (idz >= 0) {
        int64_t *one = sim_alloc(c, sizeof *one);
        *one = sim_fx_from_real(1.0, f->f[idz], SIM_RND_TRUNC, SIM_OVF_SAT, NULL);
        /* A NOR over d's bits, registered like Q and R: in the clock the
         * result is valid the source already offers the next item. */
        sim_signal *z = sim_logic(c, sc, "dz_next", f->f[idz], 1, &den, f_is_zero, one, fd.width * SIM_GE_NAND2);
        sim_fmt fz = f->f[idz];
        snprintf(vt, sizeof vt, "assign %%y = (%%0 == %d'b0) ? %d'h%llx : %d'b0;", fd.width, fz.width,
                 (unsigned long long)((uint64_t)*one & (fz.width >= 64 ? ~0ull : (1ull << fz.width) - 1)), fz.width);
        sim_logic_verilog(z, vt);
        sim_reg(c, sc, "dz", f->f[idz], clk, z, NULL, NULL, 0);
    }
    return q;
}

/* -------------------------------------------------------------- the unit */

#define DIV_SIGS(X) \
    X(DV_N,  "n", IN, "dividend, 0 <= n < d") \
    X(DV_D,  "d", IN, "divisor, in [1/2, 1] for the golden vectors (any d > 0 works)") \
    X(DV_Q,  "q", OUT, "quotient register Q: floor(n/d) in q's format after the last clock") \
    X(DV_R,  "r", INTERNAL, "remainder register R: (n - q d) 2^F_q at the end") \
    X(DV_DZ, "dz", INTERNAL, "divide-by-zero flag register, d == 0, valid with q")
enum { DIV_SIGS(UNIT_SIG_ID) DV_NSIGS };

static void div_formats(const unit_cfg *cfg, unit_fmts *out)
{
    int W = cfg->width;
    out->f[DV_N] = unit_fmt(0, 1, W - 1);
    out->f[DV_D] = unit_fmt(0, 1, W - 1);
    out->f[DV_Q] = unit_fmt(0, 0, W);           /* q < 1: W fraction bits, W clocks */
    out->f[DV_R] = out->f[DV_D];                /* the remainder is below d */
    out->f[DV_DZ] = unit_fmt(0, 1, 0);
}

static int beats1(const unit_cfg *cfg) { (void)cfg; return 1; }

extern const unit_desc unit_div;

static int div_build(sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                     const unit_fmts *f, unit_io *io, char *err, size_t errlen)
{
    (void)cfg;
    io->in[0] = sim_signal_new(c, sc, "n", f->f[DV_N], SIM_KIND_INPUT);
    io->in[1] = sim_signal_new(c, sc, "d", f->f[DV_D], SIM_KIND_INPUT);
    io->out[0] = dv_build(&unit_div, c, sc, clk, f, io, io->in[0], io->in[1], NULL, 0, err, errlen);
    io->scope = sc;
    return io->out[0] ? 0 : -1;
}

static void div_ideal(const unit_cfg *cfg, const double *in, double *out)
{
    (void)cfg;
    out[0] = in[0] / in[1];
}

/* n/d exactly (d > 0 in the unit's domain; d <= 0 is not a ratio the
 * check can use: -1). */
static int div_ratio(const unit_cfg *cfg, const sim_dy *in, sim_dy *num, sim_dy *den)
{
    (void)cfg;
    sim_dy z;
    sim_dy_int(&z, 0, 0);
    if (sim_dy_cmp(&in[1], &z) <= 0) return -1;
    *num = in[0];
    *den = in[1];
    return 0;
}

/* The golden vectors' domain (vectors/ref_brdf_models.c): d in [1/2, 1],
 * 0 <= n <= d - 2^-8, so that n < d still holds after the inputs are
 * quantized to at least 8 fraction bits. */
#define DV_GAP 0x1p-8

/* The quotient is n/d truncated to q's format: below one LSB of q, for
 * every quantized n, d with 0 <= n < d 2^I_q. Inputs from the domain above
 * stay there when their formats hold [0, 1] and quantizing cannot close
 * the gap; otherwise the bound is q's range (n/d < 2), and none at all
 * when the input formats cannot hold the domain. */
static void div_bound(const unit_cfg *cfg, const unit_fmts *f, double *per_out)
{
    sim_fmt fn = f->f[DV_N], fd = f->f[DV_D];
    double ln = sim_fmt_lsb(fn), ld = sim_fmt_lsb(fd);
    if (!brdf_holds(fn, 0, 1) || !brdf_holds(fd, 0.5, 1)) {
        per_out[0] = INFINITY;          /* inputs may wrap, d to 0: no bound */
        return;
    }
    int ok = sim_fmt_real_max(f->f[DV_Q]) >= 1 - sim_fmt_lsb(f->f[DV_Q]);
    if (cfg->rnd == SIM_RND_TRUNC) ok = ok && ld <= DV_GAP;            /* n_q <= n, d_q > d - ld */
    else ok = ok && (ln + ld) / 2 < DV_GAP;                          /* each moves half an LSB */
    per_out[0] = ok ? sim_fmt_lsb(f->f[DV_Q]) : brdf_range_bound(f->f[DV_Q], 2.0);
}

const unit_desc unit_div = {
    .name = "div",
    .ref = &ref_model_div,
    .summary = "q = n/d by a restoring divider, one quotient bit a clock (remainder r, flag dz)",
    .source = "Zavalniuk et al. (2022), the division of F_SH and F_MSH",
    UNIT_SIGS(DIV_SIGS(UNIT_SIG_ROW)),
    .nsched = 1,
    .sched = { { "restoring", "one quotient bit a clock: as many clocks as q has value bits" } },
    .nparams = 0,
    .fmt_rule = "n, d, r u1.(W-1); q u0.W (W clocks); dz u1.0",
    .formats = div_formats, .beats = beats1, .build = div_build, .ideal = div_ideal, .bound = div_bound, .ideal_ratio = div_ratio,
    .below = { "n", "d" },
    .fmt_fixed = { "q" },
};
