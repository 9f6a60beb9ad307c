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

void sim_lut_fill(int64_t *tab, int bits, int n, sim_signal *const *in, const uint64_t *mask,
                  sim_lut_code code, sim_logic_fn fn, void *user, sim_fmt out)
{
    /* a field f decodes to (f ^ x) - s: for a signed input of w bits,
     * s = 2^(w-1) and, in the two's complement code, x = s too (f below
     * s is f, above it f - 2^w), in the offset code x = 0 (f + raw_min);
     * an unsigned input's field is its raw in either code */
    uint64_t x[8], s[8];
    for (int j = 0; j < n; j++) {
        s[j] = in[j]->fmt.is_signed ? (uint64_t)1 << (in[j]->fmt.width - 1) : 0;
        x[j] = code == SIM_LUT_TWOS ? s[j] : 0;
    }
    /* the fields count up as an odometer does (field 0 the lowest digit,
     * the fields side by side from bit 0: sh[j] is the widths below j),
     * so each index decodes only the fields that changed */
    uint64_t f[8];
    int64_t v[8];
    for (int j = 0; j < n; j++) { f[j] = 0; v[j] = (int64_t)(x[j] - s[j]); }
    for (uint64_t ix = 0; ix < ((uint64_t)1 << bits); ix++) {
        tab[ix] = sim__canon(fn(v, user), out);
        for (int j = 0; j < n; j++) {
            f[j] = (f[j] + 1) & mask[j];
            v[j] = (int64_t)((f[j] ^ x[j]) - s[j]);
            if (f[j]) break;
        }
    }
}
