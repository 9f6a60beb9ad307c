/* unit_nrm.h - the normalization datapath dot3, norm3 and shade share
 * (unit_nrm.c), written against the unet walk (unit_net.h) so that one
 * construction builds the hardware and bounds its error. Internal to
 * units/.
 *
 *   a.b        three products and two adders, exact: the products keep
 *              every bit (2F fraction bits for F-bit operands), so the sum
 *              is the dot product of the held vectors and its sign is
 *              exact (shade gates on it);
 *   1/|N|      root = sqrt(N.N) (unit_rec.c's square root, truncated),
 *              then rinv = 1/root (its reciprocal, truncated); their
 *              errors derived (docs/bounds.md, "norm3") and carried on
 *              by the walk into whatever multiplies by rinv.
 */
#ifndef UNIT_NRM_H
#define UNIT_NRM_H
#include "units/unit_net.h"
#include "units/unit_rec.h"

/* The domain of the normal's length as the hardware holds it, |N| in
 * [NRM_NMIN, NRM_NMAX] (the reference's generators keep inside it). */
#define NRM_NMIN 0.5
#define NRM_NMAX 1.0

/* Fraction bits of the dot products of vectors held as s2.(W-2): every
 * bit of the products (2W - 4) while a product fits 64 bits with room,
 * W <= 25; W + 21 above, still one more a width (and no longer exact). */
int nrm_prod_fbits(int W);

/* a.b into elements of signal sig's format: products "<pfx>_x", "_y",
 * "_z", partial sum "<pfx>_xy", the sum "<pfx>"; imag is the caller's
 * bound on |a.b| (Cauchy-Schwarz on its domain: the walk's product of
 * ranges is far looser). reg: the products registered ("<pfx>_x_r1"...)
 * before the adders, a pipeline stage between them. */
unet_val nrm_dot(unet *n, int sig, const char *pfx, const unet_val *a, const unet_val *b, double imag, int reg);

/* 1/sqrt(s) for s = N.N held exactly in signal sig_s's format (u1.2F):
 * root (signal sig_root, u1.F_r) and rinv (sig_rinv, u2.F_q).
 * pipe: both recurrences unrolled, *stages their pipeline registers.
 * Otherwise iterative: the root from the clock where first_root is 1,
 * stepping where root_run is 1 (its K clocks, so that its registers hold
 * the root after them), the reciprocal from the clock where first_rcp is
 * 1 (rec_steps of the root later), stepping where rcp_run is 1.
 * Bounding (no hardware), rinv's error derived for |N| >= NRM_NMIN.
 * 0, or -1 with a message (formats the recurrences cannot take). */
int nrm_rsqrt(unet *n, unet_val s, int sig_root, int sig_rinv, int pipe,
              sim_signal *first_root, sim_signal *root_run, sim_signal *first_rcp, sim_signal *rcp_run,
              unet_val *rinv, int *stages,
              char *err, size_t errlen);
/* 0 when the recurrences take the radicand format fs and the formats of
 * sig_root and sig_rinv, else -1 with the recurrence's message (the
 * check nrm_rsqrt makes first; a unit states it before anything that
 * depends on the recurrences' clocks). */
int nrm_check(const unet *n, sim_fmt fs, int sig_root, int sig_rinv, char *err, size_t errlen);
/* Clocks (stages) of the two recurrences for these formats. */
int nrm_steps(sim_fmt fs, sim_fmt froot, sim_fmt frinv, int *k_root, int *k_rcp);

/* v through k pipeline registers "<pfx>1".."<pfx>k" (building; the walk:
 * v unchanged, a register copies its value exactly). */
unet_val nrm_delay(unet *n, const char *pfx, unet_val v, int k);
/* The gate "a > 0" (b NULL) or "a > 0 && b > 0" on exact values: their
 * sign bits and an OR over their bits (element name). */
sim_signal *nrm_gate(sim_ctx *c, sim_scope *sc, const char *name, sim_signal *a, sim_signal *b);
/* "x >= 1" (element "clamp"): the output multiplexer's select of a sum
 * clamped at 1. */
sim_signal *nrm_ge_one(sim_ctx *c, sim_scope *sc, sim_signal *x);
#endif
