/* sim_lut.c - the logic tabulator (sim_lut.h). */
#include "sim/sim_lut.h"
#include "sim/sim_quant.h"

int sim_lut_layout(int n, sim_signal *const *in, int max_bits, int *sh, uint64_t *mask)
{
    if (n < 0 || n > 8) return -1;
    if (max_bits > SIM_LUT_BITS) max_bits = SIM_LUT_BITS;
    int bits = 0;
    for (int j = 0; j < n; j++) {
        int w = in[j]->fmt.width;
        sh[j] = bits;
        mask[j] = UINT64_MAX >> (64 - w);
        bits += w;
    }
    return bits > max_bits ? -1 : bits;
}

void sim_lut_fill(int64_t *tab, int bits, int n, sim_signal *const *in, const int *sh,
                  const uint64_t *mask, sim_lut_code code, sim_logic_fn fn, void *user, sim_fmt out)
{
    for (uint64_t ix = 0; ix < ((uint64_t)1 << bits); ix++) {
        int64_t v[8];
        for (int j = 0; j < n; j++) {
            uint64_t f = (ix >> sh[j]) & mask[j];
            v[j] = code == SIM_LUT_OFFSET ? in[j]->raw_min + (int64_t)f : sim__canon((int64_t)f, in[j]->fmt);
        }
        tab[ix] = sim__canon(fn(v, user), out);
    }
}
