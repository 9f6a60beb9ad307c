/* tb_ref_claims.h - each numerical claim of the papers next to what the double
 * references measure, as one table shared by `shadesim claims`, the report,
 * the docs and the tests.
 *
 * A row holds the claim as the paper states it (with where it is stated),
 * the paper's number, our number, and a verdict that is exactly one of
 *   "holds"                      the claim is true as stated,
 *   "holds only for <condition>" true under the condition named, false
 *                                outside it (the note says by how much),
 *   "does not hold"              false where the paper says it is true.
 * Where the paper's wording is qualitative ("high accuracy"), the note
 * states the criterion we apply. Percentages are in percent.
 */
#ifndef TB_REF_CLAIMS_H
#define TB_REF_CLAIMS_H
#include <stddef.h>

#define CLAIMS_MAX 64          /* enough rows for claims_compute + claims_speed */

#define CLAIM_HOLDS       "holds"
#define CLAIM_HOLDS_ONLY  "holds only for "      /* a prefix */
#define CLAIM_FAILS       "does not hold"

typedef struct claim_result {
    const char *id;            /* stable key, e.g. "d16_m0.2" */
    const char *source;        /* where: the paper (short name), section, eq./fig. */
    const char *claim;         /* text of the claim */
    double claimed;            /* the paper's number; NAN when it gives none */
    double measured;           /* ours, in the unit of `claimed`; always finite */
    char measured_text[160];   /* ours in words, with units and detail */
    const char *verdict;       /* see above */
    char note[256];            /* how it was measured, why it differs */
} claim_result;

/* Computes every deterministic claim (not the speed claims) in double
 * precision and writes the first `max` rows to out. Returns the number of
 * rows written. Takes about 0.1 s. */
size_t claims_compute(claim_result *out, size_t max);

/* 1 for "holds", 0 for "holds only for ...", -1 for "does not hold",
 * -2 for anything else. */
int claims_verdict_kind(const char *verdict);

/* ---- CPU speed claims (Nechyporuk & Romanyuk (2020) and Romanyuk et al. (SPIE): D16 4.34x faster than D, Ward
 * approximation more than 2x). Timing-dependent: for `make bench` only
 * (bench/bench_claims.c), never in `shadesim claims`'s verdicts, never
 * asserted in tests. ---- */

typedef enum claims_kernel {
    CLAIMS_CPU_D,        /* Beckmann D, float: expf and a division */
    CLAIMS_CPU_D16,      /* D16, float: clamp and 4 squarings */
    CLAIMS_CPU_WARD,     /* Ward specular term with expf */
    CLAIMS_CPU_WARD16,   /* the same with the 16th-power polynomial */
    CLAIMS_CPU_COUNT
} claims_kernel;

const char *claims_kernel_name(claims_kernel k);
/* Nanoseconds per evaluation of kernel k in float on this CPU: the best of
 * three runs of at least min_seconds each. Negative for a bad k. */
double claims_cpu_ns(claims_kernel k, double min_seconds);
/* The two speed claims as rows (timing with claims_cpu_ns); returns rows
 * written. Takes about 12 * min_seconds. */
size_t claims_speed(claim_result *out, size_t max, double min_seconds);

#endif
