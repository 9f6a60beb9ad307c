/* unit_span.h - what the span units' files share (unit_span.c: networks,
 * formats, ideal and the descriptors; unit_span_hw.c: the hardware;
 * unit_span_bound.c: the error bound). Internal to units/: the units
 * themselves are reached through the registry (unit.h).
 */
#ifndef UNIT_SPAN_H
#define UNIT_SPAN_H
#include "units/unit_coef.h"
#include "units/unit_horner.h"

#define SPAN_LMAX 64

enum { K_LIN = 1, K_QUAD = 2, K_CUBE = 3, K_ADAPT = 23 };
enum { SP_PAPER = HORNER_PAPER, SP_MAC = HORNER_MAC, SP_PIPE = HORNER_PIPE };

typedef struct span_kind {
    const unit_desc *u;
    int kind;           /* K_LIN, K_QUAD, K_CUBE, K_ADAPT */
    int nin;            /* node inputs i1.. */
} span_kind;

extern const char *const span_in_names[4], *const span_coef_names[4], *const span_reg_names[4];
/* span23's quadratic network: coef2's with its elements named q_* */
extern const coef_net span_net_q2;

/* The network of the unit's (main) degree, and for span23 the quadratic. */
const coef_net *span_main_net(const span_kind *K, const unit_cfg *cfg);
static inline int span_main_deg(const span_kind *K) { return K->kind == K_ADAPT ? 3 : K->kind; }
/* Bits of k = 0..L, of n and dv: ceil(log2(L+1)). */
static inline int span_kbits(int L) { int b = 1; while ((1 << b) < L + 1) b++; return b; }
static inline int span_sig(const span_kind *K, const char *name) { return unit_sig_index(K->u, name); }
static inline int span_valid_L(int L) { return L >= 2 && L <= SPAN_LMAX; }

/* The reciprocal ROM: 1/dv rounded down to format f (its largest value at
 * most 1/dv), for dv = 1..L: rounding down keeps k * rcp <= k/dv. */
typedef struct span_rom {
    int L;
    int64_t raw[SPAN_LMAX + 1];     /* raw[dv], dv = 1..L; raw[0] = 0 (dv = 0: only t = 0 is asked) */
} span_rom;
void span_rom_fill(span_rom *r, int L, sim_fmt f);

/* The unit's hooks, for kind K (unit_span_hw.c, unit_span_bound.c). */
int  span_build(const span_kind *K, sim_ctx *c, sim_scope *sc, sim_signal *clk, const unit_cfg *cfg,
                const unit_fmts *f, unit_io *io, char *err, size_t errlen);
void span_bound(const span_kind *K, const unit_cfg *cfg, const unit_fmts *f, double *per_out);
#endif
