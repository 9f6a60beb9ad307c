/* fuzz_fmt.c - the format parser (sim_fmt_parse, "sI.F" / "uI.F" with
 * optional ":ROUND" / ":OVERFLOW" modes) on any text: a format it accepts
 * must print back as text it parses to the same format, modes included. */
#include "sim/sim_fixed.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char s[256], err[256], b[SIM_FMT_STRLEN];
    if (size >= sizeof s) size = sizeof s - 1;
    memcpy(s, data, size);
    s[size] = 0;
    sim_fmt f, g;
    if (sim_fmt_parse(s, &f, err, sizeof err)) return 0;
    if (sim_fmt_parse(sim_fmt_str(f, b), &g, err, sizeof err)) abort();
    if (f.is_signed != g.is_signed || f.ibits != g.ibits || f.fbits != g.fbits
        || f.rnd != g.rnd || f.ovf != g.ovf) abort();
    return 0;
}
