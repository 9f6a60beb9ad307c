/* tb_build.c - a unit in a context of its own (tb.h: tb_build), the first
 * step of every testbench, the batch mode's, the Verilog export's and the
 * format checks'. */
#include "testbench/tb.h"
#include "testbench/tb_netlist.h"
#include "base/base_out.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int tb_build(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, tb_built *b, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    b->c = sim_new();
    if (!b->c) base_out_of_memory();
    sim_set_quant(b->c, cfg->rnd, cfg->ovf);
    b->clk = sim_bit_new(b->c, NULL, "clk", SIM_KIND_CLOCK);
    b->sc = sim_scope_new(b->c, NULL, u->name);
    /* a unit read from a netlist file builds from its text (tb_netlist.h) */
    if (tb_netlist_is(u) ? tb_netlist_build(u, b->c, b->sc, b->clk, &b->io, err, errlen)
                         : u->build(b->c, b->sc, b->clk, cfg, f, &b->io, err, errlen))
        return -1;
    /* The ports' values leave the unit: an overflow on one is used even
     * on a clock the unit's own elements ignore it (sim_prim.h). */
    for (int i = 0; i < UNIT_MAX_IO; i++)
        if (b->io.out[i]) sim_signal_output(b->io.out[i]);
    return 0;
}
