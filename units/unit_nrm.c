/* unit_nrm.c - the normalization datapath of dot3, norm3 and shade
 * (unit_nrm.h). */
#include "units/unit_nrm.h"
#include "units/units_brdf.h"
#include <math.h>
#include "sim/sim_area.h"
#include <stdio.h>

int nrm_prod_fbits(int W)
{
    return 2 * (W - 2) < W + 21 ? 2 * (W - 2) : W + 21;
}

unet_val nrm_dot(unet *n, int sig, const char *pfx, const unet_val *a, const unet_val *b, double imag, int reg)
{
    char nm[48];
    unet_val p[3];
    for (int k = 0; k < 3; k++) {
        snprintf(nm, sizeof nm, "%s_%c", pfx, "xyz"[k]);
        p[k] = unet_mul(n, sig, nm, a[k], b[k]);
        snprintf(nm, sizeof nm, "%s_%c_r", pfx, "xyz"[k]);
        if (reg) p[k] = nrm_delay(n, nm, p[k], 1);
    }
    snprintf(nm, sizeof nm, "%s_xy", pfx);
    unet_val s = unet_add(n, sig, nm, p[0], p[1]);
    s = unet_add(n, sig, pfx, s, p[2]);
    s.imag = fmin(s.imag, imag);
    return s;
}

static void specs(sim_fmt fs, sim_fmt froot, sim_fmt frinv, rec_spec *sq, rec_spec *rc)
{
    *sq = (rec_spec){ REC_SQRT, fs.fbits, froot.fbits, 0 };
    *rc = (rec_spec){ REC_RECIP, froot.fbits, frinv.fbits, 0 };
}

int nrm_steps(sim_fmt fs, sim_fmt froot, sim_fmt frinv, int *k_root, int *k_rcp)
{
    rec_spec sq, rc;
    specs(fs, froot, frinv, &sq, &rc);
    *k_root = rec_steps(&sq);
    *k_rcp = rec_steps(&rc);
    return *k_root + *k_rcp;
}

int nrm_check(const unet *n, sim_fmt fs, int sig_root, int sig_rinv, char *err, size_t errlen)
{
    sim_fmt froot = n->fm.f[sig_root], frinv = n->fm.f[sig_rinv];
    char b1[SIM_FMT_STRLEN], b2[SIM_FMT_STRLEN], b3[SIM_FMT_STRLEN];
    rec_spec sq, rc;
    specs(fs, froot, frinv, &sq, &rc);
    if (fs.is_signed || fs.ibits > 1 || !brdf_holds(froot, 0, 1) || !brdf_holds(frinv, 0, 2)) {
        snprintf(err, errlen, "%s: the radicand %s must be unsigned below 2, root=%s hold [0, 1] and "
                 "rinv=%s hold [1, 2]", n->u->name, sim_fmt_str(fs, b1), sim_fmt_str(froot, b2), sim_fmt_str(frinv, b3));
        return -1;
    }
    return rec_check(&sq, err, errlen) || rec_check(&rc, err, errlen) ? -1 : 0;
}

int nrm_rsqrt(unet *n, unet_val s, int sig_root, int sig_rinv, int pipe,
              sim_signal *first_root, sim_signal *root_run, sim_signal *first_rcp, sim_signal *rcp_run,
              unet_val *rinv, int *stages,
              char *err, size_t errlen)
{
    sim_fmt fs = s.f;
    sim_fmt froot = n->fm.f[sig_root], frinv = n->fm.f[sig_rinv];
    char b1[SIM_FMT_STRLEN];
    rec_spec sq, rc;
    specs(fs, froot, frinv, &sq, &rc);
    if (nrm_check(n, fs, sig_root, sig_rinv, err, errlen)) return -1;
    int ks = rec_steps(&sq), kq = rec_steps(&rc);
    if (stages) *stages = pipe ? ks + kq : 0;
    unet_val root = s, q = s;
    root.f = froot;
    q.f = frinv;
    if (n->c) {
        sim_signal *qs, *qq;
        if (pipe) {
            qs = rec_pipe(n->c, n->sc, n->clk, "sq", &sq, s.s);
        } else {
            qs = rec_iter(n->c, n->sc, n->clk, "sq_", &sq, s.s, first_root, root_run);
        }
        root.s = sim_shift(n->c, n->sc, "root", froot, qs, -froot.fbits);
        if (pipe) {
            qq = rec_pipe(n->c, n->sc, n->clk, "rc", &rc, root.s);
        } else {
            /* the root's registers hold it while the reciprocal runs (the
             * root steps only where root_run is 1), and the reciprocal
             * steps only where rcp_run is 1: neither runs on a changing
             * operand */
            qq = rec_iter(n->c, n->sc, n->clk, "rc_", &rc, root.s, first_rcp, rcp_run);
        }
        q.s = sim_shift(n->c, n->sc, "rinv", frinv, qq, -frinv.fbits);
    }
    /* The root truncated: r - 2^-F_r < root <= r = sqrt(s), s exact. The
     * reciprocal of the truncated root, truncated: with rmin = NRM_NMIN,
     * 1/root - 1/r lies in [0, 2^-F_r / ((rmin - 2^-F_r) rmin)] and rinv
     * in (1/root - 2^-F_q, 1/root]: |rinv - 1/r| is below their sum (below
     * the larger when s is exact, as they then have opposite signs; the
     * sum keeps the bound from growing when rinv is widened, which moves
     * the truncation into the products that read it). */
    double er = sim_fmt_lsb(froot), rmin = NRM_NMIN;
    root.err = s.err / (sqrt(fmax(0.0, rmin * rmin - s.err)) + rmin) + er;
    root.q = er;
    root.eff = froot.fbits;
    root.imag = NRM_NMAX;
    root.mag = NRM_NMAX;
    double e_rcp = root.err / ((rmin - root.err) * rmin);
    q.err = e_rcp + sim_fmt_lsb(frinv);
    q.q = sim_fmt_lsb(frinv);
    q.eff = frinv.fbits;
    q.imag = 1 / rmin;
    /* |rinv| <= 1/|N| + its error: a bound that requantizing rinv (a
     * multiplexer's narrower input) moves exactly as it moves the error,
     * so that widening rinv never grows a product's bound */
    q.mag = q.imag + q.err;
    if (!(rmin - root.err > 0)) {
        snprintf(err, errlen, "%s: root=%s too coarse for |N| >= %g", n->u->name, sim_fmt_str(froot, b1), rmin);
        return -1;
    }
    *rinv = q;
    return 0;
}

unet_val nrm_delay(unet *n, const char *pfx, unet_val v, int k)
{
    if (n->c && v.s) v.s = rec_delay(n->c, n->sc, n->clk, pfx, v.s, k);
    return v;
}

/* ------------------------------------------------------------ gates */

/* DL > 0 (and DH > 0): the sign bits and an OR over the bits. */
static int64_t f_pos(const int64_t *in, void *u) { (void)u; return in[0] > 0; }
static int64_t f_pos2(const int64_t *in, void *u) { (void)u; return in[0] > 0 && in[1] > 0; }
/* SUM >= 1: its raw against 1's */
static int64_t f_ge1(const int64_t *in, void *u) { return in[0] >= *(const int64_t *)u; }

static const char *pos_vl(char *buf, size_t len, sim_fmt f, int k)
{
    if (f.is_signed) snprintf(buf, len, "(~%%%d[%d] & (|%%%d))", k, f.width - 1, k);
    else snprintf(buf, len, "(|%%%d)", k);
    return buf;
}

sim_signal *nrm_gate(sim_ctx *c, sim_scope *sc, const char *name, sim_signal *a, sim_signal *b)
{
    sim_signal *in[2] = { a, b };
    int two = b != NULL;
    double ge = (a->fmt.width + (two ? b->fmt.width : 0)) * SIM_GE_NAND2 / 2;
    sim_signal *g = sim_logic(c, sc, name, unit_fmt(0, 1, 0), two ? 2 : 1, in, two ? f_pos2 : f_pos, NULL, ge);
    char t[200], p0[60], p1[60];
    if (two) snprintf(t, sizeof t, "assign %%y = %s & %s;", pos_vl(p0, sizeof p0, a->fmt, 0), pos_vl(p1, sizeof p1, b->fmt, 1));
    else snprintf(t, sizeof t, "assign %%y = %s;", pos_vl(p0, sizeof p0, a->fmt, 0));
    sim_logic_verilog(g, t);
    return g;
}

sim_signal *nrm_ge_one(sim_ctx *c, sim_scope *sc, sim_signal *x)
{
    int64_t *one = sim_alloc(c, sizeof *one);
    sim_fmt f = x->fmt;
    *one = (int64_t)1 << f.fbits;
    sim_signal *g = sim_logic(c, sc, "clamp", unit_fmt(0, 1, 0), 1, &x, f_ge1, one, f.width * SIM_GE_NAND2 / 2);
    char t[160];
    if (f.is_signed) snprintf(t, sizeof t, "assign %%y = $signed(%%0) >= $signed(%d'h%llx);", f.width, (unsigned long long)*one);
    else snprintf(t, sizeof t, "assign %%y = %%0 >= %d'h%llx;", f.width, (unsigned long long)*one);
    sim_logic_verilog(g, t);
    return g;
}

