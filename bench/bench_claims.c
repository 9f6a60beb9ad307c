/* bench_claims.c - The papers' CPU speed claims (D16 4.34x faster than D,
 * the Ward approximation more than 2x) timed on this machine in float
 * code. Machine-, compiler- and libm-dependent: that is why these figures
 * live here, in `make bench`, and not in `shadesim claims`, whose verdicts
 * use our hardware's clocks and are the same on every machine. */
#include "testbench/study/tb_ref_claims.h"
#include <stdio.h>

int main(void)
{
    claim_result rows[4];
    size_t n = claims_speed(rows, 4, 0.05);
    for (size_t i = 0; i < n; i++)
        printf("bench_claims %s: %s (paper %g): %s\n", rows[i].id, rows[i].measured_text, rows[i].claimed,
               rows[i].verdict);
    return 0;
}
